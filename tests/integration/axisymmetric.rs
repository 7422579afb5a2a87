//! Axisymmetric outputs: `asperity check` and summary.json state that forces
//! are for the full revolution, and every VTU file carries the hoop stress
//! (the fourth stress component) as its own array.

use crate::common;
use std::process::Command;

/// A solid shaft squeezed radially.
fn shaft() -> String {
    common::case()
        .with("description", "a solid shaft squeezed radially")
        .plane("axisymmetric")
        .block("shaft", [0.0, 10.0], [3], [0.0, 20.0], [3])
        .material("shaft", 206000.0, 0.3)
        .uy("shaft.bottom", 0.0)
        .pressure("shaft.right", 100.0)
        .solver("increments = 2")
        .build()
}

fn asperity(args: &[&std::ffi::OsStr]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn axisymmetric_outputs_state_the_revolution_and_carry_the_hoop_stress() {
    let case = common::case_dir("axisymmetric-outputs", &shaft());
    let check = asperity(&["check".as_ref(), case.as_os_str()]);
    assert!(check.contains("full revolution"), "{check}");
    let out = case.parent().unwrap().join("out");
    asperity(&[
        "run".as_ref(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
        case.as_os_str(),
    ]);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["plane"], "axisymmetric");
    assert!(summary["forces"]
        .as_str()
        .unwrap()
        .contains("full revolution"));
    let vtu = out.join("vtu/0002.vtu");
    let (stress, hoop) = (
        common::vtu_array(&vtu, "stress"),
        common::vtu_array(&vtu, "hoop_stress"),
    );
    assert_eq!(hoop.len() * 4, stress.len());
    for (n, h) in hoop.iter().enumerate() {
        assert_eq!(*h, stress[4 * n + 3], "node {n}");
    }
    // a solid shaft under external pressure p, ends free: σ_rr = σ_θθ = −p, σ_zz = 0
    for h in &hoop {
        assert!((h + 100.0).abs() < 1e-6 * 100.0, "hoop stress {h}");
    }
}
