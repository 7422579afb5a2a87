//! One study point: `asperity run` in a subprocess (serial, or PETSc under
//! `mpirun -n k`), read back from its summary.json and last interface file.

use std::path::Path;
use std::process::Command;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Which {
    Serial,
    Petsc(usize),
}

impl Which {
    pub fn label(self) -> String {
        match self {
            Which::Serial => "serial faer".into(),
            Which::Petsc(n) => format!("PETSc {n} rank{}", if n > 1 { "s" } else { "" }),
        }
    }

    /// PETSc runs need the `parallel` build and mpirun.
    pub fn available(self) -> bool {
        match self {
            Which::Serial => true,
            Which::Petsc(_) => {
                cfg!(feature = "parallel")
                    && Command::new("mpirun")
                        .arg("--version")
                        .output()
                        .is_ok_and(|o| o.status.success())
            }
        }
    }
}

/// What a study needs of one run.
#[derive(Clone, Debug, Default)]
pub struct Point {
    pub dofs: f64,
    pub wall: f64,
    pub iterations: f64,
    pub increments: f64,
    pub cutbacks: f64,
    pub(crate) first_yield_kn: f64,
    pub center: f64,
    pub(crate) edge_pressure: f64,
}

/// Runs `case` with extra `run` arguments; Err carries the run's error line.
pub fn run(case: &Path, args: &[String], which: Which, dir: &Path) -> Result<Point, String> {
    run_limited(case, args, which, dir, None)
}

/// As [`run`], killing the run after `limit` (Err "stopped after N s").
pub(crate) fn run_limited(
    case: &Path,
    args: &[String],
    which: Which,
    dir: &Path,
    limit: Option<std::time::Duration>,
) -> Result<Point, String> {
    // the running asperity, or (from a test harness) the one ASPERITY_EXE names
    let exe = match std::env::var_os("ASPERITY_EXE") {
        Some(p) => std::path::PathBuf::from(p),
        None => std::env::current_exe().map_err(|e| e.to_string())?,
    };
    let mut cmd = command(&exe, which);
    cmd.arg(case)
        .args(args)
        .arg("--quiet")
        .arg("--out")
        .arg(dir);
    // --quiet: stderr carries at most the error line, so a pipe cannot fill up
    cmd.stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped());
    let child = cmd
        .spawn()
        .map_err(|e| format!("cannot start {}: {e}", exe.display()))?;
    wait(child, limit)?;
    read_point(dir)
}

/// An adaptive run (`args` hold `--adapt`): one point per cycle from its
/// adapt.csv, the wall time summed over the cycles so far (what the run
/// paid to reach that mesh), no edge pressure (only the last cycle's
/// interface files are kept).
pub(crate) fn run_adaptive(
    case: &Path,
    args: &[String],
    which: Which,
    dir: &Path,
) -> Result<Vec<Point>, String> {
    run(case, args, which, dir)?;
    let text = std::fs::read_to_string(dir.join("adapt.csv")).map_err(|e| e.to_string())?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .ok_or(format!("adapt.csv has no column {name}"))
    };
    let (dofs, wall, its, incs, settle, fy) = (
        col("dofs")?,
        col("wall_s")?,
        col("newton_iterations")?,
        col("increments")?,
        col("settlement_mm")?,
        col("first_yield_kn")?,
    );
    let mut points = Vec::new();
    let mut spent = 0.0;
    for line in lines {
        let v: Vec<&str> = line.split(',').collect();
        let f = |k: usize| {
            v.get(k)
                .and_then(|x| x.parse::<f64>().ok())
                .unwrap_or(f64::NAN)
        };
        spent += f(wall);
        points.push(Point {
            dofs: f(dofs),
            wall: spent,
            iterations: f(its),
            increments: f(incs),
            cutbacks: 0.0,
            first_yield_kn: f(fy),
            center: f(settle),
            edge_pressure: f64::NAN,
        });
    }
    Ok(points)
}

/// `asperity run` on the serial backend, or under `mpirun -n N` on PETSc.
fn command(exe: &Path, which: Which) -> Command {
    match which {
        Which::Serial => {
            let mut c = Command::new(exe);
            c.args(["run", "--backend", "serial"]);
            c
        }
        Which::Petsc(n) => {
            let mut c = Command::new("mpirun");
            c.args(["-n", &n.to_string()])
                .arg(exe)
                .args(["run", "--backend", "petsc"]);
            for (k, v) in [
                ("OMPI_ALLOW_RUN_AS_ROOT", "1"),
                ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"),
                ("OMPI_MCA_rmaps_base_oversubscribe", "1"),
            ] {
                c.env(k, v);
            }
            c
        }
    }
}

/// Waits for a run, killing it after `limit`; Err is its error line.
fn wait(mut child: std::process::Child, limit: Option<std::time::Duration>) -> Result<(), String> {
    let start = std::time::Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(_)) => break,
            Ok(None) => {}
            Err(e) => return Err(e.to_string()),
        }
        if limit.is_some_and(|l| start.elapsed() > l) {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!(
                "stopped after {:.0} s",
                limit.unwrap_or_default().as_secs_f64()
            ));
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = child.wait_with_output().map_err(|e| e.to_string())?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        return Err(err
            .lines()
            .find(|l| l.starts_with("error:"))
            .unwrap_or("failed")
            .to_string());
    }
    Ok(())
}

/// The measures of a finished run from its output folder: summary.json and
/// the last interface file (the pressure at the pair of largest x: the
/// punch edge).
fn read_point(dir: &Path) -> Result<Point, String> {
    let text = std::fs::read_to_string(dir.join("summary.json")).map_err(|e| e.to_string())?;
    let s: serde_json::Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let f = |v: &serde_json::Value| v.as_f64().unwrap_or(f64::NAN);
    let mut files: Vec<_> = std::fs::read_dir(dir.join("interface"))
        .map_err(|e| e.to_string())?
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .collect();
    files.sort();
    let last = files
        .last()
        .map(std::fs::read_to_string)
        .transpose()
        .map_err(|e| e.to_string())?
        .unwrap_or_default();
    let edge = last
        .lines()
        .skip(1)
        .filter_map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            Some((
                v.first()?.parse::<f64>().ok()?,
                v.get(1)?.parse::<f64>().ok()?,
            ))
        })
        .fold((f64::MIN, f64::NAN), |a, b| if b.0 > a.0 { b } else { a })
        .1;
    Ok(Point {
        dofs: f(&s["dofs"]),
        wall: f(&s["wall_seconds"]),
        iterations: f(&s["newton_iterations"]),
        increments: f(&s["increments"]),
        cutbacks: f(&s["cutbacks"]),
        first_yield_kn: f(&s["first_yield"]["total_load_kn"]),
        center: f(&s["final"]["center_displacement_mm"]),
        edge_pressure: edge,
    })
}
