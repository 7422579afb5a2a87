//! Running asperity under mpirun and reading what it wrote.

use crate::common;
use std::path::{Path, PathBuf};
use std::process::Command;

/// `mpirun -n N asperity ARGS`, as root and oversubscribed where needed.
pub fn mpirun_output(n: usize, args: &[&str]) -> std::process::Output {
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
pub fn mpirun(n: usize, args: &[&str]) -> (i32, String) {
    let out = mpirun_output(n, args);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

pub fn serial(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

pub fn json(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// (x, p_n, u_n, status) rows of every interface file.
pub fn interfaces(dir: &Path) -> Vec<Vec<(f64, f64, f64, String)>> {
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
pub fn last_vtu_array(dir: &Path, name: &str) -> Vec<f64> {
    let mut files: Vec<_> = std::fs::read_dir(dir.join("vtu"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "vtu"))
        .collect();
    files.sort();
    crate::common::vtu_array(files.last().expect("a .vtu file"), name)
}

pub fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-6 * scale
}

/// Runs `case` on 2 ranks into `root/out` (plus `extra` options), expecting
/// failure: exit code 2, exactly one `error:` line, and neither an output
/// folder nor a partial one left behind. Returns stderr.
pub fn fails_cleanly_on_two_ranks(root: &Path, case: &Path, extra: &[&str]) -> String {
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

/// `asperity run CASE --quiet --out DIR EXTRA…` on `n` ranks; panics with
/// stderr if it fails.
pub fn run_on(n: usize, case: &Path, dir: &Path, extra: &[&str]) -> std::process::Output {
    run_on_ending(n, case, dir, extra, 0)
}

/// [`run_on`] ending with exit code `code` (3: stopped by `--stop-after`,
/// with its results); panics with stderr otherwise.
pub fn run_on_ending(
    n: usize,
    case: &Path,
    dir: &Path,
    extra: &[&str],
    code: i32,
) -> std::process::Output {
    let mut args = vec![
        "run",
        case.to_str().unwrap(),
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let out = mpirun_output(n, &args);
    assert_eq!(
        out.status.code(),
        Some(code),
        "{} on {n} rank(s): {}",
        case.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// `case` on the serial backend into `dir`, with `extra` arguments; panics
/// on failure.
pub fn run_serial(case: &Path, dir: &Path, extra: &[&str]) {
    let mut args = vec![
        "run",
        case.to_str().unwrap(),
        "--quiet",
        "--backend",
        "serial",
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let (c, e) = serial(&args);
    assert_eq!(c, 0, "{} on the serial backend: {e}", case.display());
}

/// punch-plane-stress on 2 ranks into `dir`, with PETSc options; panics on failure.
pub fn punch_on_two_ranks(dir: &Path, petsc: &[&str]) -> std::process::Output {
    let case = common::root().join("cases/punch-plane-stress");
    let mut extra = vec!["--"];
    extra.extend_from_slice(petsc);
    run_on(2, &case, dir, &extra)
}

/// Every file a run writes except `summary.json` (which holds wall times).
pub fn result_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
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
