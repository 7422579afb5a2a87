//! A pretension section through a stop and a restart (issue 27): a run
//! stopped in its preload, resumed with `--restart`, writes the same
//! pretension.csv as the run that was not stopped, the locked phase included
//! (the section's rows and its shortening travel in restart.bin).

use crate::common;
use std::process::Command;

fn asperity(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The bar of tests/common (held at both ends, cut at x = 30), preloaded by
/// 1 kN over t ∈ [0, 1], locked, then pulled at x = 60 over t ∈ [1, 2].
fn bar() -> String {
    common::pretension_bar(
        "force = 1000.0\nhistory = \"preload\"",
        r#"
[history]
preload = [[0, 0], [1, 1]]
service = [[1, 0], [2, 1]]
[[force]]
nodes = "bar.all"
fx = 100.0
x_range = [60.0, 60.0]
history = "service""#,
    )
}

#[test]
fn a_stopped_pretension_run_resumes_to_the_same_section_forces() {
    let case = common::case_dir("pretension-restart-case", &bar());
    let root = common::scratch("pretension-restart");
    let (c, o) = (case.display().to_string(), |n: &str| {
        root.join(n).display().to_string()
    });
    let (full, stopped, resumed) = (o("full"), o("stopped"), o("resumed"));
    let (code, e) = asperity(&["run", &c, "--out", &full, "--quiet"]);
    assert_eq!(code, 0, "{e}");
    // a stopped run exits with 3 (docs/running.md)
    let (code, e) = asperity(&["run", &c, "--out", &stopped, "--quiet", "--stop-after", "3"]);
    assert_eq!(code, 3, "{e}");
    let (code, e) = asperity(&[
        "run",
        &c,
        "--out",
        &resumed,
        "--quiet",
        "--restart",
        &stopped,
    ]);
    assert_eq!(code, 0, "{e}");
    let read =
        |d: &str| std::fs::read_to_string(std::path::Path::new(d).join("pretension.csv")).unwrap();
    let (a, b) = (read(&full), read(&resumed));
    assert!(a.lines().count() > 4, "{a}");
    assert_eq!(a, b, "pretension.csv differs after a restart");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("full/summary.json")).unwrap())
            .unwrap();
    let p = &s["pretension"][0];
    assert_eq!(p["name"], "bolt");
    assert_eq!(p["control"], "force");
    assert_eq!(p["locked_after"], 1.0);
    assert!((p["force_at_lock_n"].as_f64().unwrap() - 1000.0).abs() < 1e-7);
}
