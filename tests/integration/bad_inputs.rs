//! The bad-input corpus: every folder `tests/bad_inputs/NN-name/` holds a case
//! (`case.toml`, perhaps with other files beside it) that `asperity` must reject,
//! and `expect.txt`, a piece of text the error message must contain.
//!
//! For each folder, in order, `asperity run <folder> --out <scratch>/out --quiet`
//! must exit with code 2, print exactly one line on stderr, starting `error: `
//! and containing the expected text, never mention a panic, and leave neither the
//! output folder nor a `.partial` folder behind. `asperity check <folder>` must
//! then either accept the case (the failure is one of solving, not of the input)
//! or fail with the very same line. Failures are collected and reported together.
//! A folder whose bad input is a run option rather than the case holds a valid
//! case and `args.txt` (more `run` arguments, one a line) and/or `env.txt`
//! (`NAME=value` lines for the run's environment); `check` must accept its case,
//! and, when the arguments are all overrides of the case (which `check` takes
//! too, [`RUN_ONLY`] none of them), refuse it with them with the run's very line.
//! See docs/reliability.md.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A run longer than this is a failure (the corpus must fail fast).
const TIME_LIMIT: Duration = Duration::from_secs(60);

struct Outcome {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    seconds: f64,
}

/// Environment variables a folder's `env.txt` may set: removed from every run,
/// so that the corpus does not depend on the caller's environment.
const OPTION_VARS: [&str; 1] = ["ASPERITY_THREADS"];

/// The options of `run` that `check` does not take (the others override the
/// case, and `check` takes them as `run` does).
const RUN_ONLY: [&str; 10] = [
    "--out",
    "--quiet",
    "--log-format",
    "--restart",
    "--stop-after",
    "--threads",
    "--backend",
    "--inject-fault",
    "--nonlinear",
    "--memory",
];

/// Runs the binary with a time limit and extra environment variables; a
/// process that overruns is killed.
fn asperity(args: &[&std::ffi::OsStr], env: &[(String, String)]) -> Outcome {
    let started = Instant::now();
    let dir = std::env::temp_dir();
    let tag = format!(
        "asperity-bad-inputs-{}-{}",
        std::process::id(),
        started.elapsed().as_nanos()
    );
    // stdout and stderr go to files: no pipe can fill up while we poll
    let (out_path, err_path) = (
        dir.join(format!("{tag}.out")),
        dir.join(format!("{tag}.err")),
    );
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_asperity"));
    for v in OPTION_VARS {
        cmd.env_remove(v);
    }
    let mut child = cmd
        .args(args)
        .envs(env.iter().map(|(k, v)| (k, v)))
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap())
        .spawn()
        .expect("cannot start asperity");
    let code = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status.code();
        }
        if started.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let read = |p: &Path| {
        let s = String::from_utf8_lossy(&std::fs::read(p).unwrap_or_default()).into_owned();
        let _ = std::fs::remove_file(p);
        s
    };
    Outcome {
        code,
        stdout: read(&out_path),
        stderr: read(&err_path),
        seconds: started.elapsed().as_secs_f64(),
    }
}

/// Problems with one outcome: exit code, the single error line, panics.
fn judge(what: &str, o: &Outcome, expect: &str, problems: &mut Vec<String>) {
    if o.code.is_none() {
        problems.push(format!(
            "{what}: killed after {:.0} s (or ended by a signal)",
            o.seconds
        ));
    } else if o.code != Some(2) {
        problems.push(format!("{what}: exit code {:?}, expected 2", o.code));
    }
    for (stream, text) in [("stdout", &o.stdout), ("stderr", &o.stderr)] {
        if text.contains("panicked") || text.contains("RUST_BACKTRACE") {
            problems.push(format!("{what}: panic on {stream}: {text:?}"));
        }
    }
    let lines: Vec<&str> = o.stderr.lines().collect();
    if lines.len() != 1 {
        problems.push(format!(
            "{what}: {} lines on stderr, expected exactly one: {:?}",
            lines.len(),
            o.stderr
        ));
    }
    let first = lines.first().copied().unwrap_or("");
    if !first.starts_with("error: ") {
        problems.push(format!(
            "{what}: stderr does not start with `error: `: {first:?}"
        ));
    }
    if !first.contains(expect) {
        problems.push(format!("{what}: expected text {expect:?} not in {first:?}"));
    }
}

/// The corpus folders, sorted by name.
fn folders() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_inputs");
    let mut v: Vec<PathBuf> = std::fs::read_dir(&root)
        .unwrap_or_else(|e| panic!("{}: {e}", root.display()))
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    v.sort();
    v
}

#[test]
fn every_bad_input_is_rejected_with_one_clear_line() {
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad_inputs");
    let _ = std::fs::remove_dir_all(&scratch);
    let mut failures: Vec<String> = Vec::new();
    let mut checked_only = 0;
    let all = folders();
    assert!(all.len() >= 60, "only {} corpus folders", all.len());
    for folder in &all {
        let name = folder.file_name().unwrap().to_string_lossy().into_owned();
        let mut problems = Vec::new();
        let expect = match std::fs::read_to_string(folder.join("expect.txt")) {
            Ok(s) if !s.trim().is_empty() => s.trim_end_matches(['\n', '\r']).to_string(),
            _ => {
                failures.push(format!("{name}: no expect.txt (or it is empty)"));
                continue;
            }
        };
        // a scratch folder of its own: `out` must not exist afterwards, nor any
        // `.out.partial-*` beside it
        let parent = scratch.join(&name);
        std::fs::create_dir_all(&parent).unwrap();
        let out = parent.join("out");
        let lines = |file: &str| -> Vec<String> {
            std::fs::read_to_string(folder.join(file))
                .map(|s| s.lines().map(str::to_string).collect())
                .unwrap_or_default()
        };
        let extra = lines("args.txt");
        let mut env = Vec::new();
        for line in lines("env.txt") {
            match line.split_once('=') {
                Some((k, v)) if OPTION_VARS.contains(&k) => env.push((k.into(), v.into())),
                _ => failures.push(format!(
                    "{name}: env.txt: {line:?} is not NAME=value of {OPTION_VARS:?}"
                )),
            }
        }
        let options = !extra.is_empty() || !env.is_empty();
        let mut args: Vec<&std::ffi::OsStr> = vec![
            "run".as_ref(),
            folder.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
            "--quiet".as_ref(),
        ];
        args.extend(extra.iter().map(std::ffi::OsStr::new));
        let run = asperity(&args, &env);
        judge("run", &run, &expect, &mut problems);
        if out.exists() {
            problems.push(format!("run: output folder {} left behind", out.display()));
        }
        let leftovers: Vec<String> = std::fs::read_dir(&parent)
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains("partial"))
            .collect();
        if !leftovers.is_empty() {
            problems.push(format!("run: partial output left: {leftovers:?}"));
        }
        // `check` validates without solving: it fails with the same line, or it
        // accepts a case whose trouble only shows when solving
        let check = asperity(&["check".as_ref(), folder.as_os_str()], &[]);
        let overrides_only = options
            && env.is_empty()
            && !extra
                .iter()
                .any(|a| RUN_ONLY.iter().any(|o| a.split('=').next() == Some(*o)));
        if overrides_only {
            // `check` with the same overrides: the run's very line
            let mut args: Vec<&std::ffi::OsStr> = vec!["check".as_ref(), folder.as_os_str()];
            args.extend(extra.iter().map(std::ffi::OsStr::new));
            let with = asperity(&args, &[]);
            judge("check with the overrides", &with, &expect, &mut problems);
            if with.stderr != run.stderr {
                problems.push(format!(
                    "check with the overrides and run disagree: {:?} vs {:?}",
                    with.stderr, run.stderr
                ));
            }
        }
        match check.code {
            // the case is valid: the run's options are what is wrong
            _ if options => {
                checked_only += 1;
                if check.code != Some(0) {
                    problems.push(format!(
                        "check rejected the case of a folder whose run options are the bad input: {:?}",
                        check.stderr
                    ));
                }
            }
            Some(0) => {
                checked_only += 1;
                let solving = ["did not converge", "linear solver"];
                if !solving.iter().any(|s| run.stderr.contains(s)) {
                    problems.push(format!(
                        "check accepted the case but run failed with an input error: {:?}",
                        run.stderr
                    ));
                }
            }
            _ => {
                judge("check", &check, &expect, &mut problems);
                if check.stderr != run.stderr {
                    problems.push(format!(
                        "check and run disagree: {:?} vs {:?}",
                        check.stderr, run.stderr
                    ));
                }
            }
        }
        println!(
            "{name}: {:.2} s  {}",
            run.seconds,
            run.stderr.lines().next().unwrap_or("")
        );
        failures.extend(problems.into_iter().map(|p| format!("{name}: {p}")));
    }
    println!(
        "{} cases, {} rejected by `check` too, {} only when solving",
        all.len(),
        all.len() - checked_only,
        checked_only
    );
    assert!(
        failures.is_empty(),
        "{} problem(s) in the bad-input corpus:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
