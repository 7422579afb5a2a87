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

/// A model with twist stopped half-way resumes from its restart file (six
/// stress components per Gauss point) and ends as the uninterrupted run,
/// byte for byte; its VTU files carry u_θ as the displacement's third
/// component and σ_rθ, σ_zθ as `twist_shear`.
#[test]
fn a_twisting_run_resumes_and_writes_its_fields() {
    let dir = common::scratch("twist-restart");
    let case = common::root().join("tests/data/axisymmetric-punch-twist");
    let out = |n: &str| dir.join(n);
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
            .arg("run")
            .arg(&case)
            .arg("--quiet")
            .args(args)
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let (stopped, resumed, full) = (out("stopped"), out("resumed"), out("full"));
    let s = stopped.to_str().unwrap();
    let (code, err) = run(&["--out", s, "--stop-after", "4"]);
    assert_eq!(code, Some(3), "{err}");
    let (code, err) = run(&["--out", resumed.to_str().unwrap(), "--restart", s]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = run(&["--out", full.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{err}");
    for f in [
        "curve.csv",
        "reactions.csv",
        "peaks.csv",
        "restart.bin",
        "vtu/0008.vtu",
    ] {
        assert!(
            std::fs::read(resumed.join(f)).unwrap() == std::fs::read(full.join(f)).unwrap(),
            "{f} of the resumed run differs"
        );
    }
    let vtu = full.join("vtu/0008.vtu");
    let u = common::vtu_array(&vtu, "displacement");
    let shear = common::vtu_array(&vtu, "twist_shear");
    assert!(u.chunks_exact(3).any(|c| c[2] != 0.0), "no u_θ");
    assert_eq!(shear.len(), 2 * u.len() / 3);
    assert!(shear.iter().any(|&v| v.abs() > 1.0), "no σ_zθ");
    // the torque the hoop shear puts on the foundation's side comes back at
    // its bottom: T = τ 2π R² h
    let csv = std::fs::read_to_string(full.join("reactions.csv")).unwrap();
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let k = head
        .iter()
        .position(|h| *h == "foundation.bottom:torque_nmm")
        .unwrap();
    let t = 30.0 * std::f64::consts::TAU * 30.0 * 30.0 * 30.0;
    assert!(common::rel(-last[k], t) < 1e-8, "torque {} vs {t}", last[k]);
}
