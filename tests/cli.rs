//! The command line on good and bad input: one clear error line, exit code 2,
//! no panic and no output folder left behind. The bad case files themselves are
//! the corpus under tests/bad_inputs/ (tests/bad_inputs.rs).

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

// Bad case files (unknown keys, wrong types, impossible values, broken meshes,
// unsupported bodies, a load that cannot converge …) live in the corpus
// tests/bad_inputs/, run by tests/bad_inputs.rs.

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
