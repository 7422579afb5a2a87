//! An adaptive run (`[adapt]`) stopped or resumed: docs/running.md, "Adaptive
//! runs" — an interrupt in a later cycle leaves the previous cycle's complete
//! folder, one in the first cycle leaves none, and `--restart` is refused
//! whether `[adapt]` comes from the case or from `--adapt`.

use crate::common;
use serde_json::Value;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};

fn case() -> String {
    common::root()
        .join("cases/punch-adaptive")
        .display()
        .to_string()
}

use crate::common::{run_asperity as asperity, run_asperity_out as asperity_out};

fn hidden_left(parent: &Path) -> Vec<String> {
    std::fs::read_dir(parent)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect()
}

#[test]
fn sigint_in_a_later_cycle_leaves_the_previous_cycles_complete_folder() {
    let dir = common::scratch("adapt-sigint");
    let out = dir.join("out");
    let mut child = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(["run", &case(), "--out"])
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // the signal goes out once cycle 1 is written: it lands in cycle 2
    let mut err = BufReader::new(child.stderr.take().unwrap());
    let mut log = String::new();
    let mut line = String::new();
    while err.read_line(&mut line).unwrap() > 0 {
        log += &line;
        if line.starts_with("adapt: cycle 1") {
            // SAFETY: plain kill(2) on our own child.
            assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGINT) }, 0);
        }
        line.clear();
    }
    let code = child.wait().unwrap().code();
    assert_eq!(code, Some(130), "{log}");
    assert!(
        log.contains("stopped by SIGINT in adaptive cycle 2")
            && log.contains("holds cycle 1's complete run"),
        "{log}"
    );
    let s: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["complete"], true, "the folder is cycle 1's whole run");
    assert_eq!(s["adapt"]["cycles"].as_array().unwrap().len(), 1);
    assert_eq!(s["adapt"]["cycles"][0]["elements"], 240);
    let csv = std::fs::read_to_string(out.join("adapt.csv")).unwrap();
    assert_eq!(csv.lines().count(), 2, "{csv}");
    assert!(hidden_left(&dir).is_empty(), "{:?}", hidden_left(&dir));
}

#[test]
fn a_stop_in_the_first_cycle_writes_nothing() {
    let dir = common::scratch("adapt-stop-first");
    let out = dir.join("out");
    let o = out.display().to_string();
    let (code, err, stdout) = asperity_out(&["run", &case(), "--out", &o, "--stop-after", "3"]);
    assert_eq!(code, 3, "{err}");
    assert_eq!(stdout, "", "no folder to name on stdout");
    assert!(
        err.contains("stopped by stop-after in adaptive cycle 1 after increment 3")
            && err.contains("no output was written"),
        "{err}"
    );
    assert!(!out.exists(), "a partial first cycle was written");
    assert!(hidden_left(&dir).is_empty(), "{:?}", hidden_left(&dir));
}

#[test]
fn restart_is_refused_for_an_adaptive_case_table() {
    let dir = common::scratch("adapt-restart");
    let from = dir.join("from");
    // a complete folder of the case (with restart.bin) to restart from
    let plain = dir.join("plain");
    std::fs::create_dir_all(&plain).unwrap();
    let text = std::fs::read_to_string(Path::new(&case()).join("case.toml")).unwrap();
    let cut = text.find("[adapt]").unwrap();
    std::fs::write(plain.join("case.toml"), &text[..cut]).unwrap();
    let f = from.display().to_string();
    let (code, err) = asperity(&[
        "run",
        &plain.display().to_string(),
        "--out",
        &f,
        "--quiet",
        "--stop-after",
        "2",
    ]);
    assert_eq!(code, 3, "{err}");
    let o = dir.join("out").display().to_string();
    let (code, err) = asperity(&["run", &case(), "--out", &o, "--restart", &f]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.starts_with("error: ")
            && err.contains("[adapt]")
            && err.contains("cannot resume (--restart)")
            && err.lines().count() == 1,
        "{err}"
    );
    assert!(!dir.join("out").exists());
}
