//! Reliability: interrupts (real SIGINT/SIGTERM and the `--stop-after` hook),
//! restart from `restart.bin` giving the uninterrupted run's files bit for bit,
//! corrupted restart files refused, JSON log lines, and run-to-run determinism.

use crate::common;
use serde_json::Value;
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_asperity"))
}

fn asperity(args: &[&str]) -> (i32, String, String) {
    let out = bin().args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn case() -> String {
    common::root()
        .join("cases/punch-plane-stress")
        .display()
        .to_string()
}

/// `run CASE --increments 10 --out OUT --quiet` plus `extra`.
fn run(out: &Path, extra: &[&str]) -> (i32, String, String) {
    let c = case();
    let o = out.display().to_string();
    let mut args = vec!["run", &c, "--increments", "10", "--out", &o, "--quiet"];
    args.extend_from_slice(extra);
    asperity(&args)
}

/// Fields of summary.json that measure this machine, not the solution.
const MEASURED: [&str; 5] = [
    "wall_seconds",
    "memory_stages_mb",
    "assembly_seconds",
    "solve_seconds",
    "peak_memory_mb",
];

fn summary(dir: &Path) -> Value {
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Every file under `dir`, by relative path.
fn files(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, d: &Path, m: &mut BTreeMap<PathBuf, Vec<u8>>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, m);
            } else {
                m.insert(
                    p.strip_prefix(root).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap(),
                );
            }
        }
    }
    let mut m = BTreeMap::new();
    walk(dir, dir, &mut m);
    m
}

/// The two folders hold the same files, byte for byte, except the measured
/// fields of summary.json.
fn assert_same_output(a: &Path, b: &Path) {
    let (fa, fb) = (files(a), files(b));
    assert_eq!(
        fa.keys().collect::<Vec<_>>(),
        fb.keys().collect::<Vec<_>>(),
        "different file sets in {} and {}",
        a.display(),
        b.display()
    );
    for (k, va) in &fa {
        if k == Path::new("summary.json") {
            let (mut sa, mut sb) = (summary(a), summary(b));
            for f in MEASURED {
                assert!(sa.get(f).is_some(), "summary.json lacks {f}");
                sa.as_object_mut().unwrap().remove(f);
                sb.as_object_mut().unwrap().remove(f);
            }
            assert_eq!(sa, sb, "summary.json differs beyond the measured fields");
        } else {
            assert!(va == &fb[k], "{} differs", k.display());
        }
    }
}

fn no_partial_left(parent: &Path) {
    let left: Vec<String> = std::fs::read_dir(parent)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("partial") || n.contains(".old-"))
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

#[test]
fn two_runs_give_byte_identical_output() {
    let dir = common::scratch("robust-determinism");
    let (a, b) = (dir.join("a"), dir.join("b"));
    for o in [&a, &b] {
        let (code, _, err) = run(o, &[]);
        assert_eq!(code, 0, "{err}");
    }
    assert_eq!(summary(&a)["complete"], Value::Bool(true));
    assert_eq!(summary(&a)["stopped_by"], Value::Null);
    assert_same_output(&a, &b);
    no_partial_left(&dir);
}

#[test]
fn restart_continues_to_the_uninterrupted_result() {
    let dir = common::scratch("robust-restart");
    let full = dir.join("full");
    let (code, _, err) = run(&full, &[]);
    assert_eq!(code, 0, "{err}");
    // stop after 3, resume and stop again after 7, resume to the end
    let part = dir.join("part");
    let p = part.display().to_string();
    let (code, _, err) = run(&part, &["--stop-after", "3"]);
    assert_eq!(code, 3, "{err}");
    assert!(
        err.contains("stopped by stop-after after increment 3/10"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "one line with --quiet: {err}");
    let s = summary(&part);
    assert_eq!(s["complete"], Value::Bool(false));
    assert_eq!(s["stopped_by"], Value::String("stop-after".into()));
    assert_eq!(s["increments"], Value::from(3));
    let curve = std::fs::read_to_string(part.join("curve.csv")).unwrap();
    assert_eq!(curve.lines().count(), 1 + 3);
    assert!(part.join("restart.bin").is_file());
    let (code, _, err) = run(&part, &["--restart", &p, "--stop-after", "7"]);
    assert_eq!(code, 3, "{err}");
    assert_eq!(summary(&part)["increments"], Value::from(7));
    let (code, _, err) = run(&part, &["--restart", &p]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(summary(&part)["complete"], Value::Bool(true));
    assert_same_output(&full, &part);
    // restarting a complete run changes nothing
    let again = dir.join("again");
    let (code, _, err) = run(&again, &["--restart", &p]);
    assert_eq!(code, 0, "{err}");
    assert_same_output(&full, &again);
    no_partial_left(&dir);
}

/// Automatic step control keeps its state (step size, waypoints, failures) in
/// restart.bin: a stopped and resumed run takes the same steps.
#[test]
fn restart_under_automatic_steps_takes_the_same_steps() {
    let dir = common::scratch("robust-restart-auto");
    let c = case();
    let go = |out: &Path, extra: &[&str]| {
        let o = out.display().to_string();
        let mut args = vec!["run", &c, "--step-control", "auto", "--out", &o, "--quiet"];
        args.extend_from_slice(extra);
        asperity(&args)
    };
    let full = dir.join("full");
    let (code, _, err) = go(&full, &[]);
    assert_eq!(code, 0, "{err}");
    let n = summary(&full)["increments"].as_u64().unwrap();
    assert!(n > 8, "{n} increments");
    let part = dir.join("part");
    let p = part.display().to_string();
    // stop inside the plastic range, where the steps are being adapted
    let (code, _, err) = go(&part, &["--stop-after", "7"]);
    assert_eq!(code, 3, "{err}");
    assert!(err.contains("after increment 7/auto"), "{err}");
    let (code, _, err) = go(&part, &["--restart", &p]);
    assert_eq!(code, 0, "{err}");
    assert_same_output(&full, &part);
    no_partial_left(&dir);
}

#[test]
fn a_corrupted_truncated_or_foreign_restart_file_is_refused() {
    let dir = common::scratch("robust-corrupt");
    let good = dir.join("good");
    let (code, _, err) = run(&good, &["--stop-after", "2"]);
    assert_eq!(code, 3, "{err}");
    let bytes = std::fs::read(good.join("restart.bin")).unwrap();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "flipped",
            {
                let mut b = bytes.clone();
                let i = b.len() / 2;
                b[i] ^= 0x10;
                b
            },
            "checksum",
        ),
        ("truncated", bytes[..bytes.len() - 100].to_vec(), "restart"),
        ("empty", Vec::new(), "bad magic"),
        (
            "magic",
            {
                let mut b = bytes.clone();
                b[0] = b'X';
                b
            },
            "bad magic",
        ),
    ];
    for (name, data, needle) in cases {
        let d = dir.join(name);
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("restart.bin"), &data).unwrap();
        let before = files(&d);
        let ds = d.display().to_string();
        let (code, _, err) = run(&d, &["--restart", &ds]);
        assert_eq!(code, 2, "{name}: {err}");
        assert!(
            err.starts_with("error: ") && err.lines().count() == 1,
            "{name}: {err}"
        );
        assert!(
            err.contains("restart.bin") && err.contains(needle),
            "{name}: {err}"
        );
        assert!(files(&d) == before, "{name}: the folder was changed");
    }
    // a restart.bin that is not a regular file: a link (here to a device
    // that never ends) or a FIFO (whose reader would wait for a writer)
    #[cfg(unix)]
    {
        let d = dir.join("device");
        std::fs::create_dir_all(&d).unwrap();
        std::os::unix::fs::symlink("/dev/zero", d.join("restart.bin")).unwrap();
        let ds = d.display().to_string();
        let (code, _, err) = run(&d, &["--restart", &ds]);
        assert_eq!(code, 2, "{err}");
        assert!(
            err.contains("restart.bin: the restart file is a symbolic link"),
            "{err}"
        );
        let d = dir.join("fifo");
        std::fs::create_dir_all(&d).unwrap();
        let fifo = std::ffi::CString::new(d.join("restart.bin").display().to_string()).unwrap();
        // SAFETY: a valid NUL-terminated path
        assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o600) }, 0);
        let ds = d.display().to_string();
        let (code, _, err) = run(&d, &["--restart", &ds]);
        assert_eq!(code, 2, "{err}");
        assert!(
            err.contains(
                "restart.bin: the restart file is a device, FIFO or socket, not a regular file"
            ),
            "{err}"
        );
    }
    // another case (here: another load schedule) or a missing file
    let g = good.display().to_string();
    let c = case();
    let o = dir.join("other").display().to_string();
    let (code, _, err) = asperity(&[
        "run",
        &c,
        "--increments",
        "12",
        "--out",
        &o,
        "--quiet",
        "--restart",
        &g,
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("different case or mesh"), "{err}");
    let (code, _, err) = asperity(&[
        "run",
        &c,
        "--refine",
        "2",
        "--increments",
        "10",
        "--out",
        &o,
        "--quiet",
        "--restart",
        &g,
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("different case or mesh"), "{err}");
    let missing = dir.join("missing").display().to_string();
    let (code, _, err) = run(&dir.join("x"), &["--restart", &missing]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("restart.bin"), "{err}");
    assert!(!dir.join("other").exists() && !dir.join("x").exists());
    no_partial_left(&dir);
}

#[test]
fn an_existing_folder_is_replaced_only_by_a_finished_run() {
    let dir = common::scratch("robust-atomic");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("marker"), "old").unwrap();
    // fails in the middle of the run (every assembly from the 12th on)
    let (code, _, err) = run(&out, &["--inject-fault", "0:12"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("fault injected"), "{err}");
    assert_eq!(std::fs::read_to_string(out.join("marker")).unwrap(), "old");
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 1);
    no_partial_left(&dir);
    // a stopped run is a finished one: it replaces the folder
    let (code, _, err) = run(&out, &["--stop-after", "1"]);
    assert_eq!(code, 3, "{err}");
    assert!(!out.join("marker").exists() && out.join("summary.json").is_file());
    no_partial_left(&dir);
}

fn json_lines(stderr: &str) -> Vec<Value> {
    stderr
        .lines()
        .map(|l| serde_json::from_str::<Value>(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect()
}

#[test]
fn json_log_lines_parse_and_carry_their_fields() {
    let dir = common::scratch("robust-json");
    let out = dir.join("out");
    let (c, o) = (case(), out.display().to_string());
    let (code, _, err) = asperity(&[
        "run",
        &c,
        "--increments",
        "5",
        "--out",
        &o,
        "--log-format",
        "json",
    ]);
    assert_eq!(code, 0, "{err}");
    let ev = json_lines(&err);
    let names: Vec<&str> = ev.iter().map(|e| e["event"].as_str().unwrap()).collect();
    assert_eq!(names.first(), Some(&"start"));
    assert_eq!(names.last(), Some(&"finish"));
    let incs: Vec<&Value> = ev.iter().filter(|e| e["event"] == "increment").collect();
    assert_eq!(incs.len(), 5);
    for e in &ev {
        assert!(e["time_s"].is_number(), "{e}");
    }
    for f in [
        "case",
        "dofs",
        "method",
        "backend",
        "ranks",
        "planned",
        "resumed_from",
        "output",
    ] {
        assert!(!ev[0][f].is_null(), "start lacks {f}: {}", ev[0]);
    }
    for (k, e) in incs.iter().enumerate() {
        assert_eq!(e["increment"], Value::from(k + 1));
        assert_eq!(e["planned"], Value::from(5));
        for f in [
            "load_factor",
            "total_load_kn",
            "mean_pressure_mpa",
            "elapsed_s",
            "max_peeq",
        ] {
            assert!(e[f].is_number(), "increment lacks {f}: {e}");
        }
        assert!(e["iterations"].is_u64() && e["cutbacks"].is_u64(), "{e}");
        assert!(e["eta_s"].is_number(), "{e}");
    }
    assert_eq!(incs[4]["eta_s"].as_f64(), Some(0.0));
    let fin = ev.last().unwrap();
    for f in [
        "output",
        "increments",
        "newton_iterations",
        "total_load_kn",
        "wall_seconds",
    ] {
        assert!(!fin[f].is_null(), "finish lacks {f}: {fin}");
    }
    // quiet: only the stop event; an error is a JSON event too
    let (code, _, err) = asperity(&[
        "run",
        &c,
        "--increments",
        "5",
        "--out",
        &o,
        "--log-format",
        "json",
        "--quiet",
        "--stop-after",
        "2",
    ]);
    assert_eq!(code, 3, "{err}");
    let ev = json_lines(&err);
    assert_eq!(ev.len(), 1, "{err}");
    assert_eq!(ev[0]["event"], "stop");
    assert_eq!(ev[0]["stopped_by"], "stop-after");
    assert_eq!(ev[0]["increments"], Value::from(2));
    assert_eq!(ev[0]["exit_code"], Value::from(3));
    let (code, _, err) = asperity(&["run", "no/such/case", "--log-format", "json", "--quiet"]);
    assert_eq!(code, 2);
    let ev = json_lines(&err);
    assert_eq!(ev.len(), 1, "{err}");
    assert_eq!(ev[0]["event"], "error");
    assert!(ev[0]["message"].as_str().unwrap().contains("no/such/case"));
}

/// Refinement of the interrupted runs (refine 5, 36,708 dofs): increments of
/// a few tenths of a second, long beside the 20 ms between two signals.
const SLOW_REFINE: &str = "5";

/// Starts a slow run (refine [`SLOW_REFINE`], 40 increments) with JSON
/// progress, waits for `after` increment events and then `fraction` of the
/// last increment's duration (to land inside the next increment, whatever the
/// solver's speed; `after` ≥ 2 when `fraction` > 0), sends `signals` 20 ms
/// apart and returns the exit code, the output folder and the seconds from the
/// first signal to the exit.
fn interrupted_run(
    tag: &str,
    signals: &[i32],
    after: usize,
    fraction: f64,
) -> (i32, PathBuf, f64, String) {
    assert!(fraction == 0.0 || after >= 2);
    let dir = common::scratch(tag);
    let out = dir.join("out");
    let mut child = bin()
        .args([
            "run",
            &case(),
            "--refine",
            SLOW_REFINE,
            "--increments",
            "40",
            "--out",
            out.to_str().unwrap(),
            "--log-format",
            "json",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let mut seen = 0;
    let mut log = String::new();
    let mut at = Vec::new();
    for line in lines.by_ref() {
        let line = line.unwrap();
        log += &line;
        log.push('\n');
        if line.contains("\"event\":\"increment\"") {
            seen += 1;
            at.push(Instant::now());
            if seen == after {
                break;
            }
        }
    }
    assert_eq!(seen, after, "the run ended early: {log}");
    if fraction > 0.0 {
        let last = at[after - 1] - at[after - 2];
        std::thread::sleep(last.mul_f64(fraction));
    }
    let t = Instant::now();
    for (k, &s) in signals.iter().enumerate() {
        if k > 0 {
            std::thread::sleep(Duration::from_millis(20));
        }
        // SAFETY: plain kill(2) on our own child.
        assert_eq!(unsafe { libc::kill(child.id() as i32, s) }, 0);
    }
    for line in lines {
        log += &line.unwrap();
        log.push('\n');
    }
    let status = child.wait().unwrap();
    let secs = t.elapsed().as_secs_f64();
    no_partial_left(&dir);
    (status.code().unwrap_or(-1), out, secs, log)
}

fn check_partial(out: &Path, signal: &str, log: &str) -> usize {
    let s = summary(out);
    assert_eq!(s["complete"], Value::Bool(false), "{s}");
    assert_eq!(s["stopped_by"], Value::String(signal.into()), "{s}");
    let n = s["increments"].as_u64().unwrap() as usize;
    assert!((1..40).contains(&n), "{n} increments");
    let curve = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    assert_eq!(curve.lines().count(), n + 1);
    let interface = std::fs::read_dir(out.join("interface")).unwrap().count();
    assert_eq!(interface, n);
    assert!(out.join("restart.bin").is_file() && out.join("results.pvd").is_file());
    let ev = json_lines(log);
    let stop: Vec<&Value> = ev.iter().filter(|e| e["event"] == "stop").collect();
    assert_eq!(stop.len(), 1, "{log}");
    assert_eq!(stop[0]["stopped_by"], signal);
    assert_eq!(stop[0]["increments"], Value::from(n));
    assert!(!ev.iter().any(|e| e["event"] == "finish"));
    n
}

#[test]
fn sigint_stops_at_the_next_increment_and_writes_the_converged_part() {
    let (code, out, secs, log) = interrupted_run("robust-sigint", &[libc::SIGINT], 2, 0.3);
    assert_eq!(code, 130, "{log}");
    let n = check_partial(&out, "SIGINT", &log);
    eprintln!("SIGINT: stopped after {n} increments, {secs:.3} s after the signal");
    // the signal came early in increment 3: that increment is finished
    assert_eq!(n, 3);
    // and the partial run resumes
    let o = out.display().to_string();
    let (code, _, err) = asperity(&[
        "run",
        &case(),
        "--refine",
        SLOW_REFINE,
        "--increments",
        "40",
        "--out",
        &o,
        "--quiet",
        "--restart",
        &o,
        "--stop-after",
        &(n + 1).to_string(),
    ]);
    assert_eq!(code, 3, "{err}");
    assert_eq!(summary(&out)["increments"], Value::from(n + 1));
}

#[test]
fn sigterm_exits_143_and_a_second_signal_abandons_the_increment() {
    let (code, out, secs, log) = interrupted_run("robust-sigterm", &[libc::SIGTERM], 1, 0.0);
    assert_eq!(code, 143, "{log}");
    check_partial(&out, "SIGTERM", &log);
    eprintln!("SIGTERM: {secs:.3} s after the signal");
    let (code, out, secs, log) =
        interrupted_run("robust-sigint-twice", &[libc::SIGINT, libc::SIGINT], 2, 0.3);
    assert_eq!(code, 130, "{log}");
    let n = check_partial(&out, "SIGINT", &log);
    eprintln!("SIGINT twice: stopped after {n} increments, {secs:.3} s after the first signal");
    // the second signal abandoned increment 3
    assert_eq!(n, 2);
}

/// Size and cost of restart.bin at refine 3 (13,468 dofs), for the docs:
/// `cargo test --release --test integration -- --ignored --nocapture restart_file_cost`.
#[test]
#[ignore]
fn restart_file_cost() {
    let text = include_str!("../../cases/punch-plane-stress/case.toml")
        .replace("refine = 1", "refine = 3");
    let model = common::model(&text);
    let mut ck = asperity::solve::Checkpoint::initial(&model);
    for (i, v) in ck.committed.u.iter_mut().enumerate() {
        *v = (i as f64).sin();
    }
    let dir = common::scratch("robust-cost");
    let n = 20;
    let t = Instant::now();
    for _ in 0..n {
        let bytes = asperity::files::restart::encode(&model, &ck, &[]);
        std::fs::write(dir.join("restart.bin.tmp"), &bytes).unwrap();
        std::fs::rename(dir.join("restart.bin.tmp"), dir.join("restart.bin")).unwrap();
    }
    let per = t.elapsed().as_secs_f64() / n as f64;
    let t = Instant::now();
    for _ in 0..n {
        std::hint::black_box(asperity::files::restart::encode(&model, &ck, &[]));
    }
    let enc = t.elapsed().as_secs_f64() / n as f64;
    let t = Instant::now();
    for _ in 0..n {
        std::hint::black_box(asperity::files::restart::fingerprint(&model));
    }
    let fp = t.elapsed().as_secs_f64() / n as f64;
    let big = vec![7u8; size_hint(&model)];
    let t = Instant::now();
    for _ in 0..n {
        std::hint::black_box(asperity::files::restart::fnv1a(std::hint::black_box(&big)));
    }
    let sum = t.elapsed().as_secs_f64() / n as f64;
    eprintln!(
        "encode {:.1} ms (fingerprint {:.1} ms, checksum {:.1} ms)",
        enc * 1e3,
        fp * 1e3,
        sum * 1e3
    );
    let size = std::fs::metadata(dir.join("restart.bin")).unwrap().len();
    let t = Instant::now();
    let (back, _) = asperity::files::restart::read(&dir, &model).unwrap();
    let read = t.elapsed().as_secs_f64();
    assert_eq!(back.committed.u, ck.committed.u);
    eprintln!(
        "{} dofs: restart.bin {:.2} MB, encode+write {:.1} ms, read+check {:.1} ms",
        model.mesh.num_dofs(),
        size as f64 / 1e6,
        per * 1e3,
        read * 1e3
    );
}

fn size_hint(model: &asperity::model::Model) -> usize {
    8 * (model.mesh.num_dofs() + 10 * model.mesh.elements.len() * model.rule(0).points.len())
}
