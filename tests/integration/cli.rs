//! The command line on good and bad input: one clear error line, exit code 2,
//! no panic and no output folder left behind. The bad case files themselves are
//! the corpus under tests/bad_inputs/ (tests/integration/bad_inputs.rs).

use crate::common;
use std::process::Command;

fn asperity(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

// Bad case files (unknown keys, wrong types, impossible values, broken meshes,
// unsupported bodies, a load that cannot converge …) live in the corpus
// tests/bad_inputs/, run by tests/integration/bad_inputs.rs.

#[test]
fn a_case_that_is_not_there_is_an_error() {
    let (code, _, err) = asperity(&["run", "no/such/case.toml", "--quiet"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error: no/such/case.toml"), "{err}");
}

#[test]
fn check_describes_the_case_without_solving() {
    let (code, out, err) = asperity(&[
        "check",
        common::root()
            .join("cases/punch-plane-stress")
            .to_str()
            .unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("valid") && out.contains("dofs") && out.contains("increments"),
        "{out}"
    );
}

/// The binary with extra environment variables (used by the serial-build test below).
#[cfg(not(feature = "parallel"))]
fn asperity_env(args: &[&str], env: &[(&str, &str)]) -> (i32, String, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_asperity"));
    cmd.args(args);
    for v in [
        "OMPI_COMM_WORLD_SIZE",
        "OMPI_COMM_WORLD_RANK",
        "PMI_SIZE",
        "PMI_RANK",
        "PMIX_RANK",
    ] {
        cmd.env_remove(v);
    }
    cmd.envs(env.iter().copied());
    let out = cmd.output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// A build without the `parallel` feature started by `mpirun -n 4` would run
/// four serial solves into one output folder: every process exits with 2, rank
/// 0 says why (once) and names the feature; nothing is written. One process
/// (size 1) runs as usual.
#[cfg(not(feature = "parallel"))]
#[test]
fn a_serial_build_under_mpirun_refuses() {
    let case = common::root().join("cases/punch-plane-stress");
    let case = case.to_str().unwrap();
    let out = common::scratch("serial-under-mpirun").join("out");
    let args = ["run", case, "--quiet", "--out", out.to_str().unwrap()];
    for env in [
        &[("OMPI_COMM_WORLD_SIZE", "4"), ("OMPI_COMM_WORLD_RANK", "0")][..],
        &[("PMI_SIZE", "4"), ("PMI_RANK", "0")],
    ] {
        let (code, stdout, err) = asperity_env(&args, env);
        assert_eq!(code, 2, "{env:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with("error: started by an MPI launcher as 4 processes")
                && err.contains("cargo build --release --features parallel"),
            "{err}"
        );
        assert!(stdout.is_empty() && !out.exists(), "{stdout}");
    }
    // the other ranks exit 2 without a word (one message, not four)
    for env in [
        &[("OMPI_COMM_WORLD_SIZE", "4"), ("OMPI_COMM_WORLD_RANK", "3")][..],
        &[("PMIX_RANK", "2")],
    ] {
        let (code, _, err) = asperity_env(&args, env);
        assert_eq!((code, err.as_str()), (2, ""), "{env:?}");
    }
    assert!(!out.exists());
    // with --log-format json: one JSON error event
    let mut json_args = args.to_vec();
    json_args.extend(["--log-format", "json"]);
    let (code, _, err) = asperity_env(&json_args, &[("OMPI_COMM_WORLD_SIZE", "4")]);
    assert_eq!(code, 2, "{err}");
    let v: serde_json::Value = serde_json::from_str(err.trim()).expect(&err);
    assert_eq!(v["event"], "error", "{err}");
    assert!(
        v["message"]
            .as_str()
            .unwrap()
            .contains("--features parallel"),
        "{err}"
    );
    // `check` too; a world of one process is a plain serial run
    let (code, _, err) = asperity_env(&["check", case], &[("OMPI_COMM_WORLD_SIZE", "4")]);
    assert_eq!(code, 2, "{err}");
    let (code, out, err) = asperity_env(
        &["check", case],
        &[("OMPI_COMM_WORLD_SIZE", "1"), ("OMPI_COMM_WORLD_RANK", "0")],
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("valid"), "{out}");
}

/// Input files are read with a bound: a case file over 16 MiB and a mesh file
/// over 256 MiB are refused from their size (sparse files here: nothing is
/// read), naming the file and the limit.
#[test]
fn oversized_case_and_mesh_files_are_refused_before_reading() {
    let dir = common::scratch("oversized-inputs");
    let case = dir.join("big-case.toml");
    let f = std::fs::File::create(&case).unwrap();
    f.set_len((16 << 20) + 1).unwrap();
    let (code, _, err) = asperity(&["check", case.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("big-case.toml: the case file has 16777217 bytes or more, more than the limit of 16777216 bytes (16 MiB)"),
        "{err}"
    );
    let mesh_case = dir.join("mesh-case");
    std::fs::create_dir_all(&mesh_case).unwrap();
    let text = std::fs::read_to_string(common::root().join("cases/punch-gmsh/case.toml")).unwrap();
    std::fs::write(mesh_case.join("case.toml"), text).unwrap();
    let f = std::fs::File::create(mesh_case.join("mesh.msh")).unwrap();
    f.set_len((256 << 20) + 1).unwrap();
    let started = std::time::Instant::now();
    let (code, _, err) = asperity(&["run", mesh_case.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("mesh.msh: the mesh file has 268435457 bytes or more, more than the limit of 268435456 bytes (256 MiB)"),
        "{err}"
    );
    assert!(started.elapsed().as_secs_f64() < 5.0);
}

/// One prescribed value per node and direction: the same value from two
/// entries is allowed (a corner in two fixed sets), two values are refused
/// (tests/bad_inputs/110-boundary-two-values).
#[test]
fn the_same_prescribed_value_twice_is_allowed() {
    let dir = common::scratch("same-value-twice");
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let extra = "\n[[boundary]]\nset = \"foundation.all\"\nuy = 0.0\ny_range = [-60.0, -60.0]\n";
    let text = text.replacen("\n[[load]]", &format!("{extra}\n[[load]]"), 1);
    assert!(text.contains("foundation.all"));
    std::fs::write(dir.join("case.toml"), text).unwrap();
    let (code, out, err) = asperity(&["check", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("valid"), "{out}");
}

/// Two punches side by side on one foundation, one interface matching and
/// one not: the non-matching interface's master side (the foundation's whole
/// top) reaches under the other punch, but only its edges facing the slave
/// side are in contact, so the two interfaces share no edge and the case runs
/// (issue 30: the check of interfaces over the same sides).
#[test]
fn a_matching_and_a_non_matching_interface_side_by_side_run() {
    let case = common::root().join("tests/data/side-by-side-mixed");
    let out = common::scratch("side-by-side-mixed").join("out");
    let (code, _, err) = asperity(&[
        "run",
        case.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.join("summary.json").is_file());
}

/// The thread count: `--threads`, else `ASPERITY_THREADS`, else every core;
/// summary.json and the start event report the count used (bad counts: the
/// corpus, tests/bad_inputs/370-378).
#[test]
fn the_thread_count_is_chosen_and_reported() {
    let case = common::root().join("cases/punch-plane-stress");
    let out = common::scratch("thread-count").join("out");
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    for (args, env, expected) in [
        (&[][..], None, cores),
        (&[][..], Some("3"), 3),
        (&["--threads", "1"][..], None, 1),
        (&["--threads", "2"][..], Some("3"), 2),
    ] {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_asperity"));
        cmd.args([
            "run",
            case.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .args(["--increments", "2", "--log-format", "json"])
        .args(args)
        .env_remove("ASPERITY_THREADS");
        if let Some(v) = env {
            cmd.env("ASPERITY_THREADS", v);
        }
        let run = cmd.output().unwrap();
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(run.status.success(), "{args:?} {env:?}: {err}");
        let start: serde_json::Value = serde_json::from_str(err.lines().next().unwrap()).unwrap();
        assert_eq!(start["event"], "start", "{err}");
        assert_eq!(start["threads"], expected, "{args:?} {env:?}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["threads"], expected, "{args:?} {env:?}");
    }
}

/// `--out` replaces the folder it names as a whole: a folder that holds the
/// case (the case's own, or one above it) and an existing file are refused
/// before anything is written, and so is a stop before the first increment
/// (nothing to resume). The case and the file are left as they were.
#[test]
fn the_output_folder_never_replaces_input() {
    let dir = common::scratch("out-replaces-input");
    let case = dir.join("sandbox").join("case");
    std::fs::create_dir_all(&case).unwrap();
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-friction-b/case.toml")).unwrap();
    std::fs::write(case.join("case.toml"), &text).unwrap();
    let keep = dir.join("sandbox").join("keep.txt");
    std::fs::write(&keep, "keep").unwrap();
    let file = dir.join("afile");
    std::fs::write(&file, "a file").unwrap();
    let c = case.to_str().unwrap();
    let toml = case.join("case.toml");
    for (out, expect) in [
        (c.to_string(), "--out: "),
        (
            dir.join("sandbox").to_str().unwrap().to_string(),
            "an input of this run",
        ),
        (format!("{c}/../../sandbox"), "an input of this run"),
        (file.to_str().unwrap().to_string(), "is a file"),
    ] {
        for case_arg in [c, toml.to_str().unwrap()] {
            let (code, stdout, stderr) = asperity(&["run", case_arg, "--quiet", "--out", &out]);
            assert_eq!(code, 2, "{out}: {stdout} {stderr}");
            assert_eq!(stderr.lines().count(), 1, "{stderr}");
            assert!(
                stderr.contains(expect) && stderr.contains("--out"),
                "{out}: {stderr}"
            );
        }
    }
    // a Gmsh mesh outside the case's folder, in the folder named by --out
    let (g, m) = (dir.join("gmsh-case"), dir.join("meshes"));
    std::fs::create_dir_all(&g).unwrap();
    std::fs::create_dir_all(&m).unwrap();
    let gtext = std::fs::read_to_string(common::root().join("cases/punch-gmsh/case.toml"))
        .unwrap()
        .replace("file = \"mesh.msh\"", "file = \"../meshes/mesh.msh\"");
    std::fs::write(g.join("case.toml"), &gtext).unwrap();
    std::fs::copy(
        common::root().join("cases/punch-gmsh/mesh.msh"),
        m.join("mesh.msh"),
    )
    .unwrap();
    let (code, _, stderr) = asperity(&[
        "run",
        g.to_str().unwrap(),
        "--quiet",
        "--out",
        m.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("mesh.msh, an input of this run"),
        "{stderr}"
    );
    assert!(m.join("mesh.msh").is_file());
    std::fs::remove_dir_all(&g).unwrap();
    std::fs::remove_dir_all(&m).unwrap();
    let out = dir.join("out");
    let (code, _, stderr) = asperity(&[
        "run",
        c,
        "--quiet",
        "--stop-after",
        "0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("--stop-after"), "{stderr}");
    assert!(!out.exists());
    // nothing was touched or left behind
    assert_eq!(
        std::fs::read_to_string(case.join("case.toml")).unwrap(),
        text
    );
    assert_eq!(std::fs::read_to_string(&keep).unwrap(), "keep");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "a file");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["afile", "sandbox"]);
    assert_eq!(std::fs::read_dir(dir.join("sandbox")).unwrap().count(), 2);
}

/// `check` names the first step the run takes (issue 42): under automatic
/// steps the case's first increment within `max_increment` and up to the
/// first history breakpoint. It printed the case's `first_increment`
/// whatever the run then took (0.5 against 0.25, 0.05 against 0.01 or a
/// breakpoint at 0.02).
#[test]
fn check_names_the_first_step_the_run_takes() {
    let text =
        std::fs::read_to_string(common::root().join("cases/shrink-fit-torque/case.toml")).unwrap();
    let early = text.replacen(
        "press = [[0.0, 0.0], [1.0, 1.0]]",
        "press = [[0.0, 0.0], [0.02, 0.1], [1.0, 1.0]]",
        1,
    );
    for (k, (text, solver)) in [
        (&text, "step_control = \"auto\"\nfirst_increment = 0.5"),
        (&text, "step_control = \"auto\"\nmax_increment = 0.01"),
        (&early, "step_control = \"auto\"\nfirst_increment = 0.5"),
        (&text, "increments = 3"),
    ]
    .into_iter()
    .enumerate()
    {
        let case = common::case_dir(
            &format!("check-first-step-{k}"),
            &common::with_solver_table(text, solver),
        );
        let case = case.to_str().unwrap();
        let (code, out, err) = asperity(&["check", case]);
        assert_eq!(code, 0, "{err}");
        let said: f64 = out
            .split("(first to λ = ")
            .nth(1)
            .and_then(|r| r.split([',', ')']).next())
            .unwrap_or_else(|| panic!("{out}"))
            .parse()
            .unwrap();
        let dir = std::path::Path::new(case).parent().unwrap().join("out");
        let (code, _, err) = asperity(&[
            "run",
            case,
            "--out",
            dir.to_str().unwrap(),
            "--quiet",
            "--stop-after",
            "1",
        ]);
        assert_eq!(code, 3, "{err}");
        let taken = common::csv_column(&dir.join("curve.csv"), "load_factor")[0];
        assert!(
            (said - taken).abs() < 5e-5,
            "{solver}: check says the first step is {said}, the run takes {taken}"
        );
    }
}
