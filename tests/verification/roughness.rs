//! cases/shrink-fit-roughness: a shrink fit whose interface law comes from the
//! surfaces' roughness (`asperity calibrate` on the shipped profile), against
//! the closed form of a long fit with a compliant interface, against the DIN
//! 7190 rule for the interference lost to smoothing, and against the rigid
//! interface.
//!
//! Closed form (plane strain, both ends held): the fit pressure p solves
//! δ = u_hub(p) + u_shaft(p) + c_N p^m with u_hub = (1+ν)/E [(1−2ν) A b + B/b],
//! A = p b²/(c²−b²), B = p b² c²/(c²−b²) (Lamé, internal pressure on the hub)
//! and u_shaft = p b (1+ν)(1−2ν)/E (solid shaft under external pressure).
//! DIN 7190 smoothing rule: the interference is reduced by 0.8 (Rz_shaft +
//! Rz_hub) on the diameter, 0.4 (Rz_shaft + Rz_hub) on the radius, and the
//! interface is rigid. It is applied here with the plane-strain Lamé above,
//! the state of this model (both ends held); DIN 7190 itself uses
//! plane-stress Lamé (free ends), which for equal materials gives (1−ν²)
//! times the pressure: 61.34 instead of 67.40 MPa here (docs/joints.md).

use crate::common;
use serde_json::Value;
use std::process::Command;

const B: f64 = 20.0;
const C: f64 = 40.0;
const E: f64 = 206_000.0;
const NU: f64 = 0.3;
const DELTA: f64 = 0.02;
/// Rz of the shaft and of the bore the profile was made with (make_profile.py), mm.
const RZ: [f64; 2] = [4.0e-3, 6.3e-3];

/// Radial approach of hub and shaft under fit pressure p (elastic, plane strain).
fn bodies(p: f64) -> f64 {
    let (a, b) = (
        p * B * B / (C * C - B * B),
        p * B * B * C * C / (C * C - B * B),
    );
    let hub = (1.0 + NU) / E * ((1.0 - 2.0 * NU) * a * B + b / B);
    let shaft = p * B * (1.0 + NU) * (1.0 - 2.0 * NU) / E;
    hub + shaft
}

/// The fit pressure for interference `delta` and interface law u = c p^m.
fn fit_pressure(delta: f64, c: f64, m: f64) -> f64 {
    let f = |p: f64| bodies(p) + c * p.powf(m) - delta;
    let (mut lo, mut hi) = (0.0, 1.0);
    while f(hi) < 0.0 {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

fn run(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn the_calibrated_shrink_fit_matches_its_closed_form_and_the_din_rule() {
    let case = common::root().join("cases/shrink-fit-roughness");
    let dir = common::scratch("shrink-fit-roughness");
    // the law in case.toml is what calibrate makes of the shipped profile
    let cal = dir.join("surface");
    run(&[
        "calibrate",
        case.join("surface.toml").to_str().unwrap(),
        "--out",
        cal.to_str().unwrap(),
    ]);
    let fit: Value =
        serde_json::from_str(&std::fs::read_to_string(cal.join("fit.json")).unwrap()).unwrap();
    let (c_fit, m_fit) = (fit["c_n"].as_f64().unwrap(), fit["m"].as_f64().unwrap());
    let text = std::fs::read_to_string(case.join("case.toml")).unwrap();
    let toml: toml::Value = toml::from_str(&text).unwrap();
    let law = &toml["interface"]["fit"];
    let (c, m) = (law["c_n"].as_float().unwrap(), law["m"].as_float().unwrap());
    // pasted with 7 significant digits
    assert!(
        common::rel(c, c_fit) < 5e-7,
        "c_N {c} vs calibrated {c_fit}"
    );
    assert!(common::rel(m, m_fit) < 5e-6, "m {m} vs calibrated {m_fit}");
    // the FE fit pressure against the closed form with that law
    let out = dir.join("run");
    run(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let s: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let f_n = s["joints"][0]["final"]["normal_force_n"].as_f64().unwrap();
    let p_fe = f_n / (std::f64::consts::TAU * B * 30.0);
    let p_cal = fit_pressure(DELTA, c, m);
    assert!(
        common::rel(p_fe, p_cal) < 5e-3,
        "FE {p_fe} MPa vs closed form {p_cal} MPa"
    );
    // DIN 7190's smoothing rule: the rigid fit with the interference reduced
    // by 0.4 ΣRz, with plane-strain Lamé (not DIN 7190's plane-stress Lamé)
    let p_din = fit_pressure(DELTA - 0.4 * (RZ[0] + RZ[1]), 0.0, 1.0);
    let p_rigid = fit_pressure(DELTA, 0.0, 1.0);
    // the roughness costs about what the rule of thumb says (within 10 %),
    // and far more than nothing
    assert!(
        common::rel(p_fe, p_din) < 0.10,
        "calibrated {p_fe} vs DIN {p_din}"
    );
    assert!(
        p_fe < 0.85 * p_rigid,
        "calibrated {p_fe} vs rigid {p_rigid}"
    );
    // the other snippet: the GW curve itself as a table law in place of the
    // power law; the two differ by the fit's error (fit.json), and so do the
    // fit pressures (δ's share in the approach is about a quarter: a bound)
    let snippet = std::fs::read_to_string(cal.join("interface.toml")).unwrap();
    let start = snippet.find("law = \"table\"").unwrap();
    let end = start + snippet[start..].find("\n]").unwrap() + 2;
    // case.toml's `law`, `c_n` and `m` lines, replaced by the table
    let from = text.find("law = \"power\"").unwrap();
    let m_line = from + text[from..].find("\nm = ").unwrap() + 1;
    let to = m_line + text[m_line..].find('\n').unwrap();
    let tabled = format!("{}{}{}", &text[..from], &snippet[start..end], &text[to..]);
    let path = common::case_dir("shrink-fit-roughness-table", &tabled);
    let out_t = dir.join("run-table");
    run(&[
        "run",
        path.to_str().unwrap(),
        "--out",
        out_t.to_str().unwrap(),
        "--quiet",
    ]);
    let t: Value =
        serde_json::from_str(&std::fs::read_to_string(out_t.join("summary.json")).unwrap())
            .unwrap();
    let p_table = t["joints"][0]["final"]["normal_force_n"].as_f64().unwrap()
        / (std::f64::consts::TAU * B * 30.0);
    let fit_error = fit["max_relative_error_approach"].as_f64().unwrap();
    assert!(
        common::rel(p_table, p_fe) < fit_error,
        "table law {p_table} vs power law {p_fe} MPa (fit error {fit_error})"
    );
    eprintln!("fit pressure: calibrated {p_fe:.2} (closed form {p_cal:.2}; table law {p_table:.2}), DIN 7190 {p_din:.2}, rigid {p_rigid:.2} MPa");
}
