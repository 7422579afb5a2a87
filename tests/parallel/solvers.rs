//! Linear solvers: the size-following default, options from the command line,
//! `--memory lean`, and the near-null space handed to GAMG.

use crate::common;
use crate::support::*;

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
    // summary.json names the solver that ran: MUMPS's Cholesky for the
    // symmetric tangent of a case without a tangential law
    assert_eq!(a["linear_solver"], "preonly + cholesky (mumps)");
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

/// `--memory lean` with GAMG applies its settings (seen in PETSc's own
/// views) beside asperity's smoothers under GMRES, names itself in summary.json, and changes the answer only within
/// the solver tolerance; it is refused with the built-in Newton loop and on
/// the serial backend.
#[test]
fn memory_lean_applies_its_gamg_settings_and_gives_the_same_answer() {
    let root = common::scratch("parallel-lean");
    let case = common::root().join("cases/punch-plane-stress");
    punch_on_two_ranks(&root.join("lu"), &[]);
    let lean = root.join("lean");
    #[rustfmt::skip]
    let out = run_on(2, &case, &lean, &[
        "--memory", "lean", "--",
        "-ksp_type", "gmres", "-pc_type", "gamg", "-ksp_rtol", "1e-10", "-ksp_max_it", "2000",
        "-snes_view",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    for setting in [
        // lean's lag and product (its widened Chebyshev interval is seen
        // below, where Chebyshev is chosen: asperity's smoothers are
        // Gauss-Seidel's)
        "rebuilt every 1000 new Jacobians",
        "using allatonce MatPtAP() implementation",
        "type: sor",
        "restart=150",
        // GAMG's own smoothed aggregation and V-cycle, as without lean
        "Number smoothing steps 1",
        "cycles=v",
    ] {
        assert!(text.contains(setting), "no '{setting}' in:\n{text}");
    }
    // asperity's GAMG default threshold, lean or not, on every level
    let thresholds: Vec<f64> = text
        .lines()
        .find_map(|l| l.split_once("Threshold for dropping small values in graph on each level ="))
        .map(|(_, v)| v.split_whitespace().map(|t| t.parse().unwrap()).collect())
        .unwrap_or_default();
    assert!(!thresholds.is_empty(), "no thresholds in:\n{text}");
    assert!(thresholds.iter().all(|&t| t == 0.01), "{thresholds:?}");
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

/// The near-null space handed to GAMG: the three rigid-body modes of the
/// assembly, orthonormal over every dof in PETSc order; each vector is one
/// rigid motion of the whole mesh (a translation plus a multiple of (−y, x),
/// the same on both bodies), and together they span all three.
#[test]
fn the_rigid_body_modes_are_orthonormal_rigid_motions_of_the_assembly() {
    use asperity::linalg::backend::petsc::solver::Partition;
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let model = common::model(&text);
    assert_eq!(model.mesh.bodies.len(), 2);
    let part = Partition::new(&model, 1).unwrap();
    let modes = part.rigid_body_modes(&model, 0);
    assert_eq!(modes.len(), 3);
    for (i, a) in modes.iter().enumerate() {
        assert_eq!(a.len(), model.mesh.num_dofs());
        for (j, b) in modes.iter().enumerate() {
            let d: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((d - want).abs() < 1e-12, "mode {i}·mode {j} = {d}");
        }
    }
    // fit mode = a·[comp==0] + b·[comp==1] + c·r over every dof, per mode
    let nodes = &model.mesh.nodes;
    let mut coefficients = nalgebra::Matrix3::<f64>::zeros();
    for (k, mode) in modes.iter().enumerate() {
        let mut rows = Vec::new();
        for (i, p) in nodes.iter().enumerate() {
            for comp in 0..2 {
                let r = if comp == 0 { -p[1] } else { p[0] };
                rows.push((comp, r, mode[part.dof_index[2 * i + comp] as usize]));
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
            "mode {k} is not a rigid motion: {resid}"
        );
        coefficients.set_column(k, &c.normalize());
    }
    // x, y translation and rotation all present: independent coefficients
    let det = coefficients.determinant();
    assert!(
        det.abs() > 1e-3,
        "the modes do not span the rigid motions: {det}"
    );
}

/// The PETSc default linear solver follows the size: MUMPS below
/// `LinearDefault::MULTIGRID_FROM` dofs, GAMG above it, Cholesky and CG for the
/// symmetric tangent of a case without a tangential law, LU and GMRES for the
/// return-mapping friction scheme's unsymmetric one.
#[test]
fn the_default_linear_solver_follows_the_size_of_the_model() {
    use asperity::linalg::backend::petsc::LinearDefault;
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress-fine/case.toml"))
            .unwrap();
    let at = |refine: usize| {
        let model = common::model(&text.replace("refine = 8", &format!("refine = {refine}")));
        (model.mesh.num_dofs(), LinearDefault::for_model(&model))
    };
    let (small, d) = at(12);
    assert!(small < LinearDefault::MULTIGRID_FROM);
    assert_eq!(d, LinearDefault::Direct { symmetric: true });
    let friction =
        std::fs::read_to_string(common::root().join("cases/punch-friction-b/case.toml")).unwrap();
    assert_eq!(
        LinearDefault::for_model(&common::model(&friction)),
        LinearDefault::Direct { symmetric: false }
    );
    let (big, d) = at(18);
    assert!(big >= LinearDefault::MULTIGRID_FROM);
    assert_eq!(d, LinearDefault::Multigrid { symmetric: true });
}

/// CG + GAMG, asperity's multigrid default, through the plastic steps of the
/// fine punch (refine 4: 23,716 dofs, the whole load, heavy yielding under the
/// punch edge) takes the same path as MUMPS LU: the same increments, cutbacks
/// and Newton iterations, and the same answer to 1e-6, with asperity's
/// Gauss-Seidel smoothers (one symmetric sweep, seen in `-snes_view`) and with
/// PETSc's Chebyshev smoothers chosen on the command line. Both GAMG modes: with
/// PETSc's default eigenvalue bounds for the Chebyshev smoothers (reused from
/// the prolongator smoothing; 1.1 times the estimate under the lagged
/// preconditioner of `--memory lean`) CG met an indefinite preconditioner here
/// and cut back where LU did not (116 iterations, 3 cutbacks, 7 increments
/// against 134, 2, 6), and at refine 8 gave up at 99% of the load. With CG
/// outside, the smoothers' eigenvalue estimates are made by CG as well (seen
/// in `-snes_view`; under an outer GMRES the smoothers are Gauss-Seidel's,
/// the test below).
/// Plain Newton on all three (`interface_loop = false`): the interface loop
/// needs a factor, which GAMG has not, so with it on the LU run would take
/// the loop's path (33 Newton iterations against 39).
#[test]
fn cg_with_gamg_follows_lu_through_the_plastic_steps() {
    let root = common::scratch("parallel-gamg-plastic");
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress-fine/case.toml"))
            .unwrap();
    // the four steps the case shipped with until 2026-11-27 (0.3, 0.6, 0.8, 1):
    // the long plastic steps where CG met an indefinite preconditioner
    let text = common::with_solver_table(
        &text,
        "method = \"full-newton\"\nload_factors = [0.3, 0.6, 0.8, 1.0]",
    );
    assert!(text.contains("[output]") && !text.contains("\nincrements"));
    let case = common::case_dir(
        "parallel-gamg-plastic-case",
        &common::with_interface_loop(&text, false),
    );
    let case = case.parent().unwrap().to_path_buf();
    let run = |name: &str, extra: &[&str]| {
        let mut args = vec!["--refine", "4"];
        args.extend_from_slice(extra);
        let out = run_on(2, &case, &root.join(name), &args);
        (
            json(&root.join(name)),
            String::from_utf8_lossy(&out.stdout).into_owned(),
        )
    };
    let (lu, _) = run("lu", &[]);
    assert_eq!(lu["linear_solver"], "preonly + cholesky (mumps)");
    assert!(lu["final"]["max_peeq"].as_f64().unwrap() > 0.05, "{lu}");
    let gamg = [
        "--",
        "-ksp_type",
        "cg",
        "-pc_type",
        "gamg",
        "-ksp_rtol",
        "1e-10",
        "-ksp_max_it",
        "2000",
        "-snes_view",
    ];
    let lean: Vec<&str> = ["--memory", "lean"].iter().chain(&gamg).copied().collect();
    let chebyshev = [
        "-mg_levels_ksp_type",
        "chebyshev",
        "-mg_levels_pc_type",
        "jacobi",
    ];
    let with_chebyshev =
        |v: &[&'static str]| -> Vec<&'static str> { v.iter().chain(&chebyshev).copied().collect() };
    for (name, extra, transform) in [
        ("fast", gamg.to_vec(), None),
        ("lean", lean.clone(), None),
        (
            "fast-chebyshev",
            with_chebyshev(&gamg),
            Some("[0. 0.1; 0. 1.1]"),
        ),
        (
            "lean-chebyshev",
            with_chebyshev(&lean),
            Some("[0. 0.1; 0. 1.5]"),
        ),
    ] {
        let (b, view) = run(name, &extra);
        if let Some(transform) = transform {
            // the smoothers' eigenvalue estimates are made by CG, as the outer solve
            let cg = format!("eigenvalues estimated using cg with transform: {transform}");
            assert!(
                view.contains(&cg),
                "{name}: no '{cg}' in the -snes_view output"
            );
            assert!(!view.contains("estimated using gmres"), "{name}");
        } else {
            // asperity's default: one symmetric Gauss-Seidel sweep on every level
            // (the coarse solve's "maximum iterations=1" is not a smoother's)
            assert!(view.contains("type: sor"), "{name}: no SOR in:\n{view}");
            let lines: Vec<&str> = view.lines().collect();
            let smoothers: Vec<usize> = (0..lines.len())
                .filter(|&i| lines[i].contains("type: richardson"))
                .collect();
            assert!(!smoothers.is_empty(), "{name}: no Richardson in:\n{view}");
            for i in smoothers {
                let sweeps = lines[i..(i + 4).min(lines.len())]
                    .iter()
                    .any(|l| l.contains("maximum iterations=1,"));
                assert!(sweeps, "{name}: a smoother not of one sweep:\n{view}");
            }
            assert!(!view.contains("chebyshev"), "{name}: {view}");
        }
        for key in ["increments", "cutbacks", "newton_iterations"] {
            assert_eq!(lu[key], b[key], "{name}: {key}");
        }
        for key in ["center_displacement_mm", "max_peeq"] {
            let (x, y) = (
                lu["final"][key].as_f64().unwrap(),
                b["final"][key].as_f64().unwrap(),
            );
            assert!(close(x, y, x.abs()), "{name}: {key}: {x} vs {y}");
        }
    }
}

/// GMRES + GAMG (an unsymmetric tangent: friction) smooths by Gauss-Seidel
/// (Richardson + SOR) with GMRES restarting after 150 iterations, asperity's
/// defaults under GMRES (seen in `-ksp_view`), and follows MUMPS LU: the same
/// Newton iterations and answer (1e-6) at a Krylov tolerance of 1e-12. The punch with friction at refine 4
/// on two ranks has GAMG coarse operators with zero rows (aggregates of fewer
/// dofs than rigid modes): without the smoothers' diagonal shift every solve
/// failed there (`DIVERGED_PC_FAILED`, a zero pivot in SOR).
#[test]
fn gmres_with_gamg_smooths_by_gauss_seidel_and_follows_lu_with_friction() {
    let root = common::scratch("parallel-gamg-friction");
    let case = common::root().join("cases/punch-friction-a");
    let run = |name: &str, petsc: &[&str]| {
        let dir = root.join(name);
        let mut extra = vec!["--refine", "4", "--stop-after", "2", "--"];
        extra.extend_from_slice(petsc);
        // exit code 3: stopped by --stop-after, with its results
        let out = run_on_ending(2, &case, &dir, &extra, 3);
        (
            json(&dir),
            String::from_utf8_lossy(&out.stdout).into_owned(),
        )
    };
    let (lu, _) = run("lu", &[]);
    assert_eq!(lu["linear_solver"], "preonly + lu (mumps)");
    // -ksp_rtol 1e-12: at the default 1e-10 this run took one Newton
    // iteration more than LU's (9 against 8, the same answer to 1e-14): an
    // iterate 1e-10 away crossed the convergence test's line one step later
    #[rustfmt::skip]
    let (mg, view) = run("gamg", &[
        "-ksp_type", "gmres", "-pc_type", "gamg", "-ksp_rtol", "1e-12", "-ksp_view",
        "-ksp_converged_reason",
    ]);
    assert_eq!(mg["linear_solver"], "gmres + gamg");
    for setting in ["type: richardson", "type: sor", "restart=150"] {
        assert!(view.contains(setting), "no '{setting}' in:\n{view}");
    }
    assert!(!view.contains("chebyshev"), "{view}");
    assert!(!view.contains("DIVERGED"), "{view}");
    assert_eq!(lu["newton_iterations"], mg["newton_iterations"]);
    assert_eq!(mg["cutbacks"], 0);
    for key in ["center_displacement_mm", "total_load_kn"] {
        let (x, y) = (
            lu["final"][key].as_f64().unwrap(),
            mg["final"][key].as_f64().unwrap(),
        );
        assert!(close(x, y, x.abs()), "{key}: {x} vs {y}");
    }
}
