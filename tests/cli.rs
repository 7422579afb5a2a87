//! The command line on good and bad input: one clear error line, exit code 2,
//! no panic and no output folder left behind.

mod common;
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

const PUNCH: &str = include_str!("../cases/punch-plane-stress/case.toml");

/// Runs a broken variant of the punch case; expects exit 2, a single `error:`
/// line containing `needle`, and no output folder.
fn rejects(name: &str, text: &str, needle: &str) {
    let case = common::case_dir(&format!("bad-{name}"), text);
    let out = case.parent().unwrap().join("out");
    let (code, _, err) = asperity(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 2, "{name}: exit code {code}, stderr: {err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{name}: expected one line, got: {err}");
    assert!(lines[0].starts_with("error: "), "{name}: {err}");
    assert!(err.contains(needle), "{name}: '{needle}' not in: {err}");
    assert!(!err.contains("panicked"), "{name}: {err}");
    assert!(!out.exists(), "{name}: output folder left behind");
    let leftovers: Vec<_> = std::fs::read_dir(case.parent().unwrap())
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("partial"))
        .collect();
    assert!(
        leftovers.is_empty(),
        "{name}: partial output left: {leftovers:?}"
    );
}

#[test]
fn bad_inputs_give_one_clear_error_and_exit_2() {
    rejects(
        "unknown-key",
        &PUNCH.replace("[model]\n", "[model]\ncolour = \"red\"\n"),
        "unknown field `colour`",
    );
    rejects(
        "negative-modulus",
        &PUNCH.replacen("young = 206000.0", "young = -206000.0", 1),
        "materials.punch",
    );
    rejects(
        "m-too-large",
        &PUNCH.replace("m = 0.5", "m = 1.5"),
        "m = 1.5 must be in (0, 1]",
    );
    rejects("m-zero", &PUNCH.replace("m = 0.5", "m = 0.0"), "(0, 1]");
    rejects(
        "c-negative",
        &PUNCH.replace("c_n = 0.001", "c_n = -0.001"),
        "c_n",
    );
    rejects(
        "wrong-type",
        &PUNCH.replace("thickness = 1.0", "thickness = \"thick\""),
        "invalid type",
    );
    rejects(
        "missing-boundary",
        &PUNCH.replace("[[boundary]]\nset = \"foundation.bottom\"\nuy = 0.0\n", ""),
        "held by nothing in y",
    );
    rejects(
        "unknown-set",
        &PUNCH.replace("set = \"foundation.bottom\"", "set = \"foundation.botom\""),
        "foundation.botom",
    );
    rejects(
        "mismatched-interface",
        &PUNCH.replacen("nx = [8]", "nx = [7]", 1),
        "interface",
    );
    rejects(
        "no-law-parameter",
        &PUNCH.replace("m = 0.5\n", ""),
        "needs `m`",
    );
    rejects(
        "foreign-law-parameter",
        &PUNCH.replace("m = 0.5\n", "m = 0.5\nb = 3.0\n"),
        "`b` is not a parameter",
    );
    rejects(
        "zero-thickness",
        &PUNCH.replace("thickness = 1.0", "thickness = 0.0"),
        "thickness",
    );
    rejects(
        "nan-yield",
        &PUNCH.replace("yield_stress = 196.0", "yield_stress = nan"),
        "yield_stress",
    );
    let friction = include_str!("../cases/punch-friction-b/case.toml");
    rejects(
        "kp-ratio",
        &friction.replace("kp_ratio = 0.05", "kp_ratio = 1.5"),
        "kp_ratio = 1.5 must be in [0, 1]",
    );
    rejects(
        "friction-consistent",
        &friction.replace("m = 0.5\n", "m = 0.5\nweights = \"consistent\"\n"),
        "needs weights = \"lumped\"",
    );
    rejects(
        "friction-scheme",
        &friction.replace("scheme = \"return-mapping\"", "scheme = \"magic\""),
        "unknown variant `magic`",
    );
    // a load far beyond the collapse load of a perfectly plastic foundation
    let collapse = PUNCH
        .replace("hardening = 2060.0   # h = E/100", "hardening = 0.0")
        .replace("pressure = 250.0", "pressure = 900.0")
        .replace(
            "first_increment = 0.05",
            "first_increment = 0.05\nmax_cutbacks = 3\nmax_iterations = 15",
        );
    rejects("cannot-converge", &collapse, "did not converge");
}

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
