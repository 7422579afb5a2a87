//! Our VTU output read by a real reader: runs cases/punch-plane-stress and hands
//! its output folder to ci/check_vtu.py, which reads every file of results.pvd
//! with Python's meshio and checks cells, arrays and finiteness. Here its report
//! is compared with our own summary.json, curve.csv and interface CSV.
//! Skips (with a message) only when python3 or meshio is missing; ci/python-deps
//! installs meshio.

use crate::common;
use std::process::Command;

fn meshio_available() -> bool {
    Command::new("python3")
        .args(["-c", "import meshio, numpy"])
        .output()
        .is_ok_and(|o| o.status.success())
}

fn number(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

#[test]
fn meshio_reads_our_vtu_series() {
    if !meshio_available() {
        // ci/test installs meshio and sets this: there the check must run
        assert!(
            std::env::var_os("ASPERITY_REQUIRE_MESHIO").is_none(),
            "ASPERITY_REQUIRE_MESHIO is set but python3 with meshio is not available"
        );
        println!("SKIPPED: python3 with meshio is not available (run ci/python-deps)");
        eprintln!("vtu_reader: SKIPPED: python3 with meshio is not available (run ci/python-deps)");
        return;
    }
    let root = common::root();
    let out = common::scratch("vtu-reader").join("punch");
    let run = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(["run", "--quiet", "--out"])
        .arg(&out)
        .arg(root.join("cases/punch-plane-stress"))
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let check = Command::new("python3")
        .arg(root.join("ci/check_vtu.py"))
        .arg(&out)
        .args(["0.0", "0.0"])
        .output()
        .unwrap();
    assert!(
        check.status.success(),
        "ci/check_vtu.py failed: {}{}",
        String::from_utf8_lossy(&check.stdout),
        String::from_utf8_lossy(&check.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&check.stdout).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    println!("meshio report: {report}");

    // sizes: every node and element of the model, one quad8 (VTK 23) block
    let dofs = summary["dofs"].as_u64().unwrap();
    assert_eq!(report["points"].as_u64().unwrap() * 2, dofs);
    assert_eq!(report["cells"], summary["elements"]);
    assert_eq!(report["cell_type"], "quad8");
    assert_eq!(report["vtk_types"], serde_json::json!([23]));
    // one file per increment (vtu_every = 1), load factors as time steps
    let curve = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let rows: Vec<Vec<f64>> = curve
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|v| v.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    assert_eq!(report["files"].as_u64().unwrap() as usize, rows.len());
    let times: Vec<f64> = report["timesteps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .collect();
    for (t, row) in times.iter().zip(&rows) {
        assert!(
            common::rel(*t, row[1]) < 1e-9,
            "time step {t} vs λ {}",
            row[1]
        );
    }
    for name in [
        "displacement",
        "stress",
        "von_mises",
        "peeq",
        "contact_pressure",
        "contact_closed",
    ] {
        assert!(
            report["point_arrays"]
                .as_array()
                .unwrap()
                .contains(&name.into()),
            "point array {name} missing: {report}"
        );
    }
    // the centre displacement seen by meshio is ours (summary and curve)
    let uy = number(&report, "probe_uy");
    let centre = number(&summary["final"], "center_displacement_mm");
    assert!(
        common::rel(uy, centre) < 1e-12,
        "meshio {uy} vs summary {centre}"
    );
    assert!(common::rel(uy, rows.last().unwrap()[5]) < 1e-8);
    assert_eq!(report["probe_point"], serde_json::json!([0.0, 0.0]));
    assert!(uy < 0.0, "the punch pushes the foundation down: {uy}");
    // the peak contact pressure is the interface CSV's, plasticity is there
    let last = format!("interface/{:04}.csv", rows.len());
    let csv = std::fs::read_to_string(out.join(last)).unwrap();
    let p_max = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse::<f64>().unwrap())
        .fold(0.0f64, f64::max);
    assert!(common::rel(number(&report, "max_contact_pressure"), p_max) < 1e-8);
    let peeq = number(&summary["final"], "max_peeq");
    assert!(peeq > 0.0 && common::rel(number(&report, "max_cell_peeq"), peeq) < 1e-9);
    assert!(number(&report, "max_von_mises") > 0.0);
    assert!(report["closed_points"].as_u64().unwrap() > 0);
}
