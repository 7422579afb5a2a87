//! Tabulated laws used far beyond their data (issue 30; docs/case-schema.md,
//! "Tabulated laws"): `asperity check` warns where the applied load alone
//! takes a table past 2 × its last row, a run warns after it where it did,
//! and a restart keeps what the increments before it reached.

use crate::common;
use serde_json::Value;
use std::path::{Path, PathBuf};

const PUNCH: &str = include_str!("../../cases/punch-plane-stress/case.toml");
const POWER: &str =
    "law = \"power\"\nc_n = 0.001          # mm/MPa^m: 14 µm of approach at 200 MPa\nm = 0.5";

/// punch-plane-stress with its power law u_N = 0.001 p^0.5 sampled at the
/// given pressures as a `law = "table"`.
fn punch_with_table(name: &str, pressures: &[f64], solver: &str) -> PathBuf {
    let rows: Vec<String> = pressures
        .iter()
        .map(|&p| format!("[{:e}, {p:e}]", 0.001 * p.sqrt()))
        .collect();
    let table = format!("law = \"table\"\ntable = [{}]", rows.join(", "));
    // the whole [solver] schedule replaced (a first_increment beside
    // load_factors would be refused)
    let text = PUNCH.replace(POWER, &table).replace(
        "increments = 20\nfirst_increment = 0.05   # the paper's small first step (section 2.3)",
        solver,
    );
    assert!(text.contains(&table) && text.contains(solver), "{name}");
    common::case_dir(name, &text)
}

/// Exit code, stdout and stderr of the program.
fn asperity(args: &[&str]) -> (i32, String, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into(),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

fn run(case: &Path, out: &Path, extra: &[&str]) -> (i32, String) {
    let (c, d) = (case.display().to_string(), out.display().to_string());
    let mut args = vec!["run", &c, "--out", &d, "--quiet"];
    args.extend_from_slice(extra);
    let (code, _, err) = asperity(&args);
    (code, err)
}

fn summary(out: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn check_and_run_warn_when_a_table_is_used_far_beyond_its_data() {
    // rows up to 20 MPa under a 250 MPa punch: the mean pressure alone needs
    // the approach of about 250 MPa on the linear tail, far past 2 × u_N(20)
    let far = punch_with_table("tables-far", &[5.0, 10.0, 20.0], "increments = 4");
    let (code, out, err) = asperity(&["check", far.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("valid"), "{out}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].starts_with("warning: ")
            && lines[0].contains(
                "[interface.contact] table: the applied load's mean pressure alone needs u_N = "
            )
            && lines[0].contains("its last row's u_N = 4.4721e-3 mm"),
        "{err}"
    );
    let dir = far.parent().unwrap().join("out");
    let (code, err) = run(&far, &dir, &[]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].starts_with("warning: ")
            && lines[0].contains("[interface.contact] table: the run evaluated it up to u_N = "),
        "{err}"
    );
    let s = summary(&dir);
    let t = &s["tables"][0];
    assert_eq!(t["key"], "table");
    assert_eq!(t["beyond_limit"], true);
    let ratio = t["ratio"].as_f64().unwrap();
    assert!(ratio > 2.0, "{t}");
    assert_eq!(
        s["warnings"][0].as_str().unwrap(),
        &lines[0]["warning: ".len()..]
    );

    // the same law sampled up to 1000 MPa covers the run: no warning anywhere
    let covered = punch_with_table(
        "tables-covered",
        &[2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0],
        "increments = 4",
    );
    let (code, _, err) = asperity(&["check", covered.to_str().unwrap()]);
    assert!(code == 0 && err.is_empty(), "{err}");
    let dir = covered.parent().unwrap().join("out");
    let (code, err) = run(&covered, &dir, &[]);
    assert!(code == 0 && err.is_empty(), "{err}");
    let s = summary(&dir);
    let t = &s["tables"][0];
    assert_eq!(t["beyond_limit"], false, "{t}");
    assert!(t["largest"].as_f64().unwrap() > 0.0, "{t}");
    assert!(s.get("warnings").is_none(), "{s}");
}

/// The reach is the largest over the whole run: loaded to λ = 1, unloaded
/// to 0.25, stopped after λ = 0.5 and restarted, the run reports the peak
/// of λ = 1 (from the restart file's `table_reach`), as the uninterrupted
/// run does; a file without that section (as the builds before it wrote
/// it) is refused naming it, and its folder stays as it was.
#[test]
fn a_restart_keeps_how_far_the_tables_were_used() {
    let case = punch_with_table(
        "tables-restart",
        &[5.0, 10.0, 20.0],
        "load_factors = [0.5, 1.0, 0.5, 0.25]",
    );
    let root = case.parent().unwrap();
    let (full, part, old) = (root.join("full"), root.join("part"), root.join("old"));
    let (code, err) = run(&case, &full, &[]);
    assert_eq!(code, 0, "{err}");
    for o in [&part, &old] {
        let (code, err) = run(&case, o, &["--stop-after", "3"]);
        assert_eq!(code, 3, "{err}");
    }
    let rs = old.join("restart.bin");
    let stripped = common::strip_restart_sections(&std::fs::read(&rs).unwrap(), &["table_reach"]);
    std::fs::write(&rs, &stripped).unwrap();
    let (code, err) = run(&case, &part, &["--restart", part.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let summary_before = std::fs::read(old.join("summary.json")).unwrap();
    let (code, err) = run(&case, &old, &["--restart", old.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    // (after the case's warning of its table, when the run gives it first)
    assert_eq!(
        err.lines().last().unwrap_or(""),
        format!(
            "error: {}: section table_reach missing: every restart file of format 5 holds it",
            rs.display()
        )
    );
    assert_eq!(std::fs::read(&rs).unwrap(), stripped);
    assert_eq!(
        std::fs::read(old.join("summary.json")).unwrap(),
        summary_before
    );
    let (a, b) = (summary(&full), summary(&part));
    assert_eq!(a["tables"], b["tables"]);
    assert_eq!(a["warnings"].as_array().map(|w| w.len()), Some(1), "{a}");
}
