//! Serial faer against PETSc on 1 and on 2 MPI ranks, on a refined case with
//! plasticity and contact opening (`cases/strip-lift-off`, refine 3) and on the
//! friction punch: same increments, same contact statuses, same first-yield
//! increment, displacements and interface pressures equal to 1e-6 relative
//! (the direct solvers agree to round-off; 1e-6 leaves room for Newton stopping
//! one iteration apart). Also: no mallocs during PETSc assembly, and an error on
//! one rank ends every rank with one message and exit code 2.
#![cfg(feature = "parallel")]

mod common;
use std::path::{Path, PathBuf};
use std::process::Command;

/// `mpirun -n N asperity ARGS`, as root and oversubscribed where needed.
fn mpirun_output(n: usize, args: &[&str]) -> std::process::Output {
    Command::new("mpirun")
        .args(["-n", &n.to_string()])
        .arg(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_rmaps_base_oversubscribe", "1")
        .env("OMPI_MCA_mpi_yield_when_idle", "1")
        .env("OMPI_MCA_hwloc_base_binding_policy", "none")
        .output()
        .expect("mpirun is on PATH (apt-get install openmpi-bin)")
}

/// Exit code and stderr of `mpirun -n N asperity ARGS`.
fn mpirun(n: usize, args: &[&str]) -> (i32, String) {
    let out = mpirun_output(n, args);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn serial(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn json(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// (x, p_n, u_n, status) rows of every interface file.
fn interfaces(dir: &Path) -> Vec<Vec<(f64, f64, f64, String)>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir.join("interface"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| {
            std::fs::read_to_string(f)
                .unwrap()
                .lines()
                .skip(1)
                .map(|l| {
                    let v: Vec<&str> = l.split(',').collect();
                    (
                        v[0].parse().unwrap(),
                        v[1].parse().unwrap(),
                        v[2].parse().unwrap(),
                        format!("{}/{}", v[3], v[8]),
                    )
                })
                .collect()
        })
        .collect()
}

/// A named DataArray of the last .vtu file of a run, as numbers.
fn last_vtu_array(dir: &Path, name: &str) -> Vec<f64> {
    let mut files: Vec<_> = std::fs::read_dir(dir.join("vtu"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "vtu"))
        .collect();
    files.sort();
    let text = std::fs::read_to_string(files.last().expect("a .vtu file")).unwrap();
    let start = text
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("no {name} array"));
    let body = &text[start..];
    let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
    body.split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-6 * scale
}

fn compare(case: &str, refine: &str) {
    let root = common::scratch(&format!("parallel-{case}"));
    let case = common::root().join("cases").join(case);
    let case = case.to_str().unwrap();
    let out = |n: &str| root.join(n);
    let (c, e) = serial(&[
        "run",
        case,
        "--refine",
        refine,
        "--quiet",
        "--backend",
        "serial",
        "--out",
        out("serial").to_str().unwrap(),
    ]);
    assert_eq!(c, 0, "{e}");
    let (c, e) = mpirun(
        1,
        &[
            "run",
            case,
            "--refine",
            refine,
            "--quiet",
            "--out",
            out("petsc1").to_str().unwrap(),
        ],
    );
    assert_eq!(c, 0, "{e}");
    let (c, e) = mpirun(
        2,
        &[
            "run",
            case,
            "--refine",
            refine,
            "--quiet",
            "--out",
            out("petsc2").to_str().unwrap(),
        ],
    );
    assert_eq!(c, 0, "{e}");
    let s = json(&out("serial"));
    let s_if = interfaces(&out("serial"));
    let u_scale = s["final"]["center_displacement_mm"].as_f64().unwrap().abs();
    for run in ["petsc1", "petsc2"] {
        let p = json(&out(run));
        assert_eq!(p["backend"], "petsc");
        assert_eq!(
            p["ranks"].as_u64().unwrap(),
            if run == "petsc1" { 1 } else { 2 }
        );
        assert_eq!(
            p["backend_stats"]["assembly_mallocs"].as_f64().unwrap(),
            0.0,
            "{run}: mallocs during assembly"
        );
        assert_eq!(p["increments"], s["increments"], "{run}: increments");
        let (fs, fp) = (&s["first_yield"], &p["first_yield"]);
        assert!(
            close(
                fs["total_load_kn"].as_f64().unwrap(),
                fp["total_load_kn"].as_f64().unwrap(),
                1.0
            ),
            "{run}: first yield"
        );
        assert_eq!(fs["element"], fp["element"], "{run}: first-yield element");
        let (us, up) = (
            s["final"]["center_displacement_mm"].as_f64().unwrap(),
            p["final"]["center_displacement_mm"].as_f64().unwrap(),
        );
        assert!(
            close(us, up, u_scale),
            "{run}: center displacement {us} vs {up}"
        );
        // fields from the Gauss states, which each rank holds only for its
        // own elements and rank 0 gathers to write
        for field in ["peeq", "von_mises", "stress"] {
            let (a, b) = (
                last_vtu_array(&out("serial"), field),
                last_vtu_array(&out(run), field),
            );
            assert_eq!(a.len(), b.len(), "{run}: {field} length");
            let scale = a.iter().fold(1e-30f64, |m, v| m.max(v.abs()));
            for (i, (x, y)) in a.iter().zip(&b).enumerate() {
                assert!(close(*x, *y, scale), "{run}: {field}[{i}] {x} vs {y}");
            }
        }
        let (ps, pp) = (
            s["final"]["max_peeq"].as_f64().unwrap(),
            p["final"]["max_peeq"].as_f64().unwrap(),
        );
        assert_eq!(
            ps > 0.0,
            !s["first_yield"].is_null(),
            "yielded iff first yield"
        );
        assert!(close(ps, pp, ps.max(1e-30)), "{run}: max peeq {ps} vs {pp}");
        let p_if = interfaces(&out(run));
        assert_eq!(p_if.len(), s_if.len());
        for (inc, (a, b)) in s_if.iter().zip(&p_if).enumerate() {
            let p_scale = a.iter().fold(1e-30f64, |m, r| m.max(r.1.abs()));
            let u_scale = a.iter().fold(1e-30f64, |m, r| m.max(r.2.abs()));
            for (ra, rb) in a.iter().zip(b) {
                assert_eq!(
                    ra.3,
                    rb.3,
                    "{run}: status at x = {} in increment {}",
                    ra.0,
                    inc + 1
                );
                assert!(
                    close(ra.1, rb.1, p_scale),
                    "{run}: p_n at x = {} in increment {}: {} vs {}",
                    ra.0,
                    inc + 1,
                    ra.1,
                    rb.1
                );
                assert!(
                    close(ra.2, rb.2, u_scale),
                    "{run}: u_n at x = {} in increment {}",
                    ra.0,
                    inc + 1
                );
            }
        }
    }
}

#[test]
fn serial_petsc1_and_petsc2_agree_on_a_refined_case_with_plasticity_and_lift_off() {
    compare("strip-lift-off", "3");
}

#[test]
fn serial_petsc1_and_petsc2_agree_with_friction() {
    compare("punch-friction-b", "1");
}

/// Runs `case` on 2 ranks into `root/out` (plus `extra` options), expecting
/// failure: exit code 2, exactly one `error:` line, and neither an output
/// folder nor a partial one left behind. Returns stderr.
fn fails_cleanly_on_two_ranks(root: &Path, case: &Path, extra: &[&str]) -> String {
    let out = root.join("out");
    let mut args = vec![
        "run",
        case.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let (code, err) = mpirun(2, &args);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.matches("error:").count(), 1, "{err}");
    assert!(!out.exists(), "output left behind");
    let partial = std::fs::read_dir(root)
        .unwrap()
        .filter_map(|e| e.ok())
        .any(|e| e.file_name().to_string_lossy().contains("partial"));
    assert!(!partial, "partial output left behind");
    err
}

#[test]
fn a_bad_case_ends_every_rank_with_one_message() {
    let text = include_str!("../cases/punch-plane-stress/case.toml").replace("m = 0.5", "m = 1.5");
    let case = common::case_dir("parallel-bad", &text);
    let (code, err) = mpirun(2, &["run", case.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.matches("error:").count(), 1, "{err}");
    assert!(err.contains("m = 1.5 must be in (0, 1]"), "{err}");
}

#[test]
fn a_fault_on_rank_1_ends_every_rank_with_its_message_and_no_output() {
    let root = common::scratch("parallel-fault");
    let case = common::root().join("cases/punch-plane-stress");
    let t = std::time::Instant::now();
    let err = fails_cleanly_on_two_ranks(&root, &case, &["--inject-fault", "1:30"]);
    assert!(err.contains("rank 1: fault injected on rank 1"), "{err}");
    assert!(t.elapsed().as_secs() < 30, "took {:?}", t.elapsed());
}

/// punch-plane-stress on 2 ranks into `dir`, with PETSc options; panics on failure.
fn punch_on_two_ranks(dir: &Path, petsc: &[&str]) -> std::process::Output {
    let case = common::root().join("cases/punch-plane-stress");
    let mut args = vec![
        "run",
        case.to_str().unwrap(),
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
        "--",
    ];
    args.extend_from_slice(petsc);
    let out = mpirun_output(2, &args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

#[test]
fn krylov_solvers_from_the_options_database_give_the_same_answer() {
    let root = common::scratch("parallel-ksp");
    punch_on_two_ranks(&root.join("lu"), &[]);
    #[rustfmt::skip]
    punch_on_two_ranks(&root.join("gmres"), &[
        "-ksp_type", "gmres", "-pc_type", "bjacobi", "-ksp_rtol", "1e-12", "-ksp_max_it", "5000",
    ]);
    // algebraic multigrid with the rigid-body near-null space
    #[rustfmt::skip]
    punch_on_two_ranks(&root.join("gamg"), &[
        "-ksp_type", "gmres", "-pc_type", "gamg", "-ksp_rtol", "1e-10", "-ksp_max_it", "2000",
    ]);
    let a = json(&root.join("lu"));
    let ua = a["final"]["center_displacement_mm"].as_f64().unwrap();
    // summary.json names the solver that ran
    assert_eq!(a["linear_solver"], "preonly + lu (mumps)");
    assert_eq!(
        json(&root.join("gmres"))["linear_solver"],
        "gmres + bjacobi"
    );
    assert_eq!(json(&root.join("gamg"))["linear_solver"], "gmres + gamg");
    for run in ["gmres", "gamg"] {
        let b = json(&root.join(run));
        let ub = b["final"]["center_displacement_mm"].as_f64().unwrap();
        assert!(close(ua, ub, ua.abs()), "{run}: {ua} vs {ub}");
        assert!(
            b["backend_stats"]["ksp_iterations"].as_f64().unwrap()
                > a["backend_stats"]["ksp_iterations"].as_f64().unwrap()
        );
    }
}

/// `--memory lean` with GAMG applies its four settings (seen in PETSc's own
/// views), names itself in summary.json, and changes the answer only within
/// the solver tolerance; it is refused with the built-in Newton loop and on
/// the serial backend.
#[test]
fn memory_lean_applies_its_gamg_settings_and_gives_the_same_answer() {
    let root = common::scratch("parallel-lean");
    let case = common::root().join("cases/punch-plane-stress");
    punch_on_two_ranks(&root.join("lu"), &[]);
    let lean = root.join("lean");
    #[rustfmt::skip]
    let out = mpirun_output(2, &[
        "run", case.to_str().unwrap(), "--quiet", "--out", lean.to_str().unwrap(),
        "--memory", "lean", "--",
        "-ksp_type", "gmres", "-pc_type", "gamg", "-ksp_rtol", "1e-10", "-ksp_max_it", "2000",
        "-snes_view",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for setting in [
        "rebuilt every 1000 new Jacobians",
        "Number smoothing steps 0",
        "cycles=w",
        "using allatonce MatPtAP() implementation",
    ] {
        assert!(text.contains(setting), "no '{setting}' in:\n{text}");
    }
    let (a, b) = (json(&root.join("lu")), json(&lean));
    assert_eq!(b["linear_solver"], "gmres + gamg (memory lean)");
    assert_eq!(a["increments"], b["increments"]);
    for key in ["center_displacement_mm", "max_peeq"] {
        let (x, y) = (
            a["final"][key].as_f64().unwrap(),
            b["final"][key].as_f64().unwrap(),
        );
        assert!(close(x, y, x.abs()), "{key}: {x} vs {y}");
    }
    std::fs::create_dir_all(root.join("builtin")).unwrap();
    let err = fails_cleanly_on_two_ranks(
        &root.join("builtin"),
        &case,
        &["--memory", "lean", "--nonlinear", "builtin"],
    );
    assert!(err.contains("--memory lean needs the SNES"), "{err}");
    let (code, err) = serial(&[
        "run",
        case.to_str().unwrap(),
        "--backend",
        "serial",
        "--memory",
        "lean",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--memory lean applies to the PETSc backend"),
        "{err}"
    );
}

/// `--stop-after` under `mpirun -n 2` stops every rank at the same increment
/// (collective decision), writes a partial folder, and `--restart` continues it
/// to the uninterrupted run's result (to round-off: the Krylov history is not
/// part of the restart state).
#[test]
fn a_stopped_two_rank_run_resumes_to_the_uninterrupted_result() {
    fn args(v: &[String]) -> Vec<&str> {
        v.iter().map(String::as_str).collect()
    }
    let root = common::scratch("parallel-restart");
    let case = common::root().join("cases/punch-plane-stress");
    let c = case.to_str().unwrap();
    let full = root.join("full");
    let part = root.join("part");
    let (f, p) = (full.to_str().unwrap(), part.to_str().unwrap());
    let base = [
        "run",
        c,
        "--increments",
        "10",
        "--quiet",
        "--backend",
        "petsc",
    ];
    let with = |extra: &[&str]| -> Vec<String> {
        base.iter().chain(extra).map(|s| s.to_string()).collect()
    };
    let a = with(&["--out", f]);
    let (code, err) = mpirun(2, &args(&a));
    assert_eq!(code, 0, "{err}");
    let a = with(&["--out", p, "--stop-after", "4"]);
    let (code, err) = mpirun(2, &args(&a));
    assert_ne!(code, 0, "{err}");
    assert_eq!(err.matches("stopped by stop-after").count(), 1, "{err}");
    let s = json(&part);
    assert_eq!(s["complete"], false);
    assert_eq!(s["increments"], 4);
    assert_eq!(s["ranks"], 2);
    let a = with(&["--out", p, "--restart", p]);
    let (code, err) = mpirun(2, &args(&a));
    assert_eq!(code, 0, "{err}");
    let (sf, sp) = (json(&full), json(&part));
    assert_eq!(sp["complete"], true);
    assert_eq!(sf["increments"], sp["increments"]);
    assert_eq!(sf["newton_iterations"], sp["newton_iterations"]);
    for k in [
        "total_load_kn",
        "center_displacement_mm",
        "max_peeq",
        "mean_pressure_mpa",
    ] {
        let (x, y) = (
            sf["final"][k].as_f64().unwrap(),
            sp["final"][k].as_f64().unwrap(),
        );
        assert!(close(x, y, x.abs().max(1e-9)), "{k}: {x} vs {y}");
    }
    let (a, b) = (interfaces(&full), interfaces(&part));
    assert_eq!(a.len(), b.len());
    for (ra, rb) in a.iter().zip(&b) {
        for (x, y) in ra.iter().zip(rb) {
            assert!(close(x.1, y.1, 250.0) && x.3 == y.3, "{x:?} vs {y:?}");
        }
    }
}

/// Determinism under MPI: two 2-rank runs of the same case write the same
/// curve, interface and VTU files, byte for byte (summary.json differs in its
/// timing and memory fields only). With a deterministic linear solver (PETSc's
/// LU on the gathered matrix): MUMPS on 2 ranks adds contributions in message
/// arrival order and varies at round-off when the machine is loaded.
#[test]
fn two_runs_on_two_ranks_give_identical_files() {
    let root = common::scratch("parallel-determinism");
    let case = common::root().join("cases/punch-friction-b");
    let dirs = [root.join("a"), root.join("b")];
    for d in &dirs {
        let (code, err) = mpirun(
            2,
            &[
                "run",
                case.to_str().unwrap(),
                "--quiet",
                "--backend",
                "petsc",
                "--out",
                d.to_str().unwrap(),
                "--",
                "-pc_type",
                "redundant",
                "-redundant_pc_type",
                "lu",
            ],
        );
        assert_eq!(code, 0, "{err}");
    }
    let mut files = vec![PathBuf::from("curve.csv")];
    for sub in ["interface", "vtu"] {
        let mut names: Vec<PathBuf> = std::fs::read_dir(dirs[0].join(sub))
            .unwrap()
            .map(|e| PathBuf::from(sub).join(e.unwrap().file_name()))
            .collect();
        names.sort();
        files.extend(names);
    }
    assert!(files.len() > 20, "{files:?}");
    for f in &files {
        let (a, b) = (
            std::fs::read(dirs[0].join(f)).unwrap(),
            std::fs::read(dirs[1].join(f)).unwrap(),
        );
        assert!(
            a == b,
            "{} differs between two identical 2-rank runs",
            f.display()
        );
    }
    let (sa, sb) = (json(&dirs[0]), json(&dirs[1]));
    for k in [
        "increments",
        "newton_iterations",
        "cutbacks",
        "first_yield",
        "final",
    ] {
        assert_eq!(sa[k], sb[k], "summary.json {k}");
    }
}

/// Every file a run writes except `summary.json` (which holds wall times).
fn result_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.file_name().unwrap() != "summary.json" {
                let name = p.strip_prefix(dir).unwrap().to_string_lossy().into_owned();
                out.push((name, std::fs::read(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// SNES (the default) and our own Newton loop take the same iterates: with
/// full steps (`-snes_linesearch_type basic`) and the paper's convergence test
/// and Anderson correction installed as SNES callbacks, the two write
/// byte-identical files on 2 ranks for all three methods (initial stiffness
/// and modified Newton exercise the post-check that applies the Anderson
/// correction). The summary names the nonlinear solver. Both solve K y = r and
/// step by −y (MUMPS's distributed solve is not exactly odd in its right-hand
/// side). The linear solver here is PETSc's LU on the gathered matrix
/// (`-pc_type redundant`), which is deterministic; MUMPS on 2 ranks sums
/// contributions in message-arrival order, so under load two runs, either
/// path, differ at round-off (see the README on determinism).
#[test]
fn snes_and_the_builtin_loop_take_the_same_iterates_for_all_three_methods() {
    let root = common::scratch("parallel-snes");
    let case = common::root().join("cases/punch-plane-stress");
    let case = case.to_str().unwrap();
    for method in ["full-newton", "modified-newton", "initial-stiffness"] {
        let mut dirs = Vec::new();
        for nl in ["snes", "builtin"] {
            let dir = root.join(format!("{method}-{nl}"));
            let (c, e) = mpirun(
                2,
                &[
                    "run",
                    case,
                    "--quiet",
                    "--method",
                    method,
                    "--nonlinear",
                    nl,
                    "--out",
                    dir.to_str().unwrap(),
                    "--",
                    "-pc_type",
                    "redundant",
                    "-redundant_pc_type",
                    "lu",
                ],
            );
            assert_eq!(c, 0, "{method} {nl}: {e}");
            assert_eq!(json(&dir)["nonlinear_solver"], nl);
            dirs.push(dir);
        }
        let (a, b) = (result_files(&dirs[0]), result_files(&dirs[1]));
        assert!(a.len() > 10, "{method}: too few files");
        assert_eq!(a.len(), b.len(), "{method}: file lists differ");
        for ((na, da), (nb, db)) in a.iter().zip(&b) {
            assert_eq!(na, nb);
            assert!(da == db, "{method}: {na} differs between SNES and builtin");
        }
        let (sa, sb) = (json(&dirs[0]), json(&dirs[1]));
        assert_eq!(sa["newton_iterations"], sb["newton_iterations"], "{method}");
        assert!(sa["backend_stats"]["snes_iterations"].as_f64().unwrap() > 0.0);
    }
}

/// SNES options from the command line reach the solver: `-snes_monitor`
/// prints once per iteration from rank 0 only, and a backtracking line search
/// with an iterative KSP still converges to the same answer (1e-6).
#[test]
fn snes_options_from_the_command_line_apply() {
    let root = common::scratch("parallel-snes-options");
    punch_on_two_ranks(&root.join("a"), &[]);
    #[rustfmt::skip]
    let out = punch_on_two_ranks(&root.join("b"), &[
        "-snes_monitor", "-snes_linesearch_type", "bt", "-ksp_type", "gmres",
        "-pc_type", "bjacobi", "-ksp_rtol", "1e-12", "-ksp_max_it", "5000",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let (a, b) = (json(&root.join("a")), json(&root.join("b")));
    // One monitor line per SNES iteration plus one per solve (iteration 0),
    // printed by rank 0 only: twice as many would mean both ranks print.
    let lines: Vec<&str> = stdout
        .lines()
        .filter(|l| l.contains("SNES Function norm"))
        .collect();
    let solves = lines
        .iter()
        .filter(|l| l.trim_start().starts_with("0 SNES Function norm"))
        .count();
    let its = b["backend_stats"]["snes_iterations"].as_f64().unwrap() as usize;
    assert!(solves >= a["increments"].as_u64().unwrap() as usize);
    assert_eq!(
        lines.len(),
        solves + its,
        "monitor lines vs SNES iterations"
    );
    let (ua, ub) = (
        a["final"]["center_displacement_mm"].as_f64().unwrap(),
        b["final"]["center_displacement_mm"].as_f64().unwrap(),
    );
    assert!(close(ua, ub, ua.abs()), "{ua} vs {ub}");
}

/// A load that cannot converge, solved by SNES on 2 ranks: exit code 2, one
/// message, no output folder.
#[test]
fn a_load_snes_cannot_converge_ends_every_rank_cleanly() {
    let root = common::scratch("parallel-snes-fail");
    let case = common::root().join("tests/bad_inputs/85-cannot-converge");
    let err = fails_cleanly_on_two_ranks(&root, &case, &[]);
    assert!(err.contains("did not converge"), "{err}");
}

/// The near-null space handed to GAMG: three rigid-body modes per body
/// (the interface springs let each body move almost rigidly against the
/// other), orthonormal over every dof in PETSc order; restricted to one body,
/// each vector is a rigid motion of it: a translation plus a multiple of (−y, x).
#[test]
fn the_rigid_body_modes_are_orthonormal_rigid_motions_of_each_body() {
    use asperity::backend::petsc::solver::Partition;
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let model = common::model(&text);
    let part = Partition::new(&model, 1).unwrap();
    let modes = part.rigid_body_modes(&model, 0);
    assert_eq!(model.mesh.bodies.len(), 2);
    assert_eq!(modes.len(), 6);
    for (i, a) in modes.iter().enumerate() {
        assert_eq!(a.len(), model.mesh.num_dofs());
        for (j, b) in modes.iter().enumerate() {
            let d: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((d - want).abs() < 1e-12, "mode {i}·mode {j} = {d}");
        }
    }
    let mut body_of = vec![0; model.mesh.nodes.len()];
    for el in &model.mesh.elements {
        for &n in &el.nodes {
            body_of[n] = el.body;
        }
    }
    let nodes = &model.mesh.nodes;
    let mut rotation_seen = [false; 2];
    for (k, mode) in modes.iter().enumerate() {
        for body in 0..2 {
            // fit mode = a·[comp==0] + b·[comp==1] + c·r over this body's dofs
            let mut rows = Vec::new();
            for (i, p) in nodes.iter().enumerate() {
                if body_of[i] != body {
                    continue;
                }
                for comp in 0..2 {
                    let r = if comp == 0 { -p[1] } else { p[0] };
                    let y = mode[part.dof_index[2 * i + comp] as usize];
                    rows.push((comp, r, y));
                }
            }
            let mut m = nalgebra::Matrix3::<f64>::zeros();
            let mut v = nalgebra::Vector3::<f64>::zeros();
            for &(comp, r, y) in &rows {
                let f = nalgebra::Vector3::new(
                    if comp == 0 { 1.0 } else { 0.0 },
                    if comp == 1 { 1.0 } else { 0.0 },
                    r,
                );
                m += f * f.transpose();
                v += f * y;
            }
            let c = m.lu().solve(&v).unwrap();
            let resid: f64 = rows
                .iter()
                .map(|&(comp, r, y)| {
                    let fit = if comp == 0 { c[0] } else { c[1] } + c[2] * r;
                    (fit - y).powi(2)
                })
                .sum();
            assert!(
                resid.sqrt() < 1e-12,
                "mode {k} is not rigid on body {body}: {resid}"
            );
            rotation_seen[body] |= c[2].abs() > 1e-6;
        }
    }
    assert_eq!(rotation_seen, [true, true], "each body has a rotation mode");
}

/// The PETSc default linear solver follows the size: MUMPS LU below
/// `LinearDefault::MULTIGRID_FROM` dofs, GAMG above it, inside CG for the
/// symmetric tangent of a case without a tangential law.
#[test]
fn the_default_linear_solver_follows_the_size_of_the_model() {
    use asperity::backend::petsc::LinearDefault;
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress-fine/case.toml"))
            .unwrap();
    let at = |refine: usize| {
        let model = common::model(&text.replace("refine = 8", &format!("refine = {refine}")));
        (model.mesh.num_dofs(), LinearDefault::for_model(&model))
    };
    let (small, d) = at(12);
    assert!(small < LinearDefault::MULTIGRID_FROM);
    assert_eq!(d, LinearDefault::DirectLu);
    let (big, d) = at(18);
    assert!(big >= LinearDefault::MULTIGRID_FROM);
    assert_eq!(d, LinearDefault::Multigrid { symmetric: true });
}
