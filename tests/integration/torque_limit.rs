//! A run that ends at its torque limit (docs/output.md "Events",
//! docs/running.md "Exit codes"): cases/fit-speed-limit, a hub held about
//! the axis by the friction of its fit alone, spun up under a torque until
//! it lets go. Exit code 4, one stop line, the output up to the last state
//! that held with the event in summary.json, the report's warning; resumed
//! from its folder it ends at the same event again; an adaptive run ends
//! its adaptation there.

use crate::common;
use serde_json::Value;

fn case() -> std::path::PathBuf {
    common::root().join("cases/fit-speed-limit")
}

fn summary(dir: &std::path::Path) -> Value {
    serde_json::from_str(&common::read_out(dir, "summary.json")).unwrap()
}

/// The one torque_limit event of a summary, and its load factor.
fn limit(s: &Value) -> (Value, f64) {
    let events: Vec<&Value> = (s["events"].as_array().unwrap().iter())
        .filter(|e| e["event"] == "torque_limit")
        .collect();
    assert_eq!(events.len(), 1, "{}", s["events"]);
    let e = events[0].clone();
    let t = e["load_factor"].as_f64().unwrap();
    (e, t)
}

#[test]
fn a_fit_that_lets_go_of_its_torque_ends_with_exit_4_and_its_event() {
    let dir = common::scratch("torque-limit");
    let out = dir.join("out");
    let (code, err) = common::run_case(&case(), &out, &[]);
    assert_eq!(code, 4, "{err}");
    let stops: Vec<&str> = err
        .lines()
        .filter(|l| l.starts_with("ended at the torque limit"))
        .collect();
    assert_eq!(stops.len(), 1, "{err}");
    assert!(
        stops[0].contains("body \"hub\"") && stops[0].contains("rpm"),
        "{err}"
    );
    let s = summary(&out);
    assert_eq!(s["complete"], false);
    assert_eq!(s["stopped_by"], "torque_limit");
    let (e, t) = limit(&s);
    assert_eq!(e["body"], "hub");
    assert_eq!(e["interface"], "fit");
    assert_eq!(e["converged"], true);
    // after the last increment written, which held the torque
    let last = s["final"]["load_factor"].as_f64().unwrap();
    let bracket: Vec<f64> = (e["bracket"].as_array().unwrap().iter())
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(
        last <= bracket[0] && bracket[1] == t,
        "{last} {bracket:?} {t}"
    );
    assert_eq!(
        e["increment"].as_u64().unwrap(),
        s["increments"].as_u64().unwrap() + 1
    );
    // the case spins 0 → 25 000 rpm over t in [1, 2], holding the torque
    let rpm = e["speed_rpm"].as_f64().unwrap();
    assert!(t > 1.0 && t < 2.0, "{t}");
    assert!(
        (rpm - 25_000.0 * (t - 1.0)).abs() < 1e-9 * rpm,
        "{rpm} at {t}"
    );
    assert!(
        (e["torque_nm"].as_f64().unwrap().abs() - 350.0).abs() < 1e-6,
        "{e}"
    );
    let rows = common::read_out(&out, "curve.csv").lines().count() - 1;
    assert_eq!(rows as u64, s["increments"].as_u64().unwrap());
    // the report says why the results end early
    let (code, err) = common::run_asperity(&["report", &out.display().to_string()]);
    assert_eq!(code, 0, "{err}");
    let html = common::read_out(&out, "report.html");
    assert!(
        html.contains("ended at its torque limit"),
        "no warning in the report"
    );

    // resumed from its folder: the same limit, found again, once
    let again = dir.join("again");
    let (code, err) = common::run_case(&case(), &again, &["--restart", &out.display().to_string()]);
    assert_eq!(code, 4, "{err}");
    let r = summary(&again);
    assert_eq!(r["increments"], s["increments"]);
    assert_eq!(limit(&r).1, t);
}

#[test]
fn an_adaptive_run_ends_its_adaptation_at_the_torque_limit() {
    let dir = common::scratch("torque-limit-adapt");
    let out = dir.join("out");
    let (code, err) = common::run_case(&case(), &out, &["--adapt", "0.05"]);
    assert_eq!(code, 4, "{err}");
    assert!(err.contains("[adapt] ends with cycle 1"), "{err}");
    let s = summary(&out);
    assert_eq!(s["stopped_by"], "torque_limit");
    limit(&s);
}

/// A torque past what friction holds, in the four ways the program met it
/// before it located the limit (then each a run error naming the torque
/// and the friction's hold; tests/data/torque-limits, patches of the bad
/// inputs' bases): each now ends at the `torque_limit` event of the body
/// held only by friction, exit code 4, the failing steps' cutback lines
/// naming the torque and what the friction holds, and the torque held at
/// the last state that held within 1 % of the hand value its patch names
/// (the face coupling's (2/3) μ F R = 15.7 N·m for a uniform pressure; the
/// shrink fit's μ N R = 566 N·m at the pressures reached; the bolted hub's
/// two faces, 457 N·m) or, the clamp unloaded under 12 N·m, where the slip
/// torque falls to it, at 76 % of the clamp (t = 2.24).
#[test]
fn every_torque_past_what_friction_holds_ends_at_its_limit() {
    let data = common::root().join("tests/data/torque-limits");
    let base = common::root().join("tests/bad_inputs/base");
    // (patch, body, the torque held at the limit (N·m) or the load factor)
    let cases: [(&str, &str, Option<f64>, Option<f64>); 4] = [
        (
            "twist-torque-past-the-slip-torque",
            "disk",
            Some(15.7),
            None,
        ),
        (
            "twist-clamp-unloaded-under-a-held-torque",
            "disk",
            Some(12.0),
            Some(2.24),
        ),
        (
            "twist-shrink-fit-torque-at-the-slip-torque",
            "shaft",
            Some(566.0),
            None,
        ),
        (
            "twist-pretension-torque-past-the-faces",
            "hub",
            Some(457.0),
            None,
        ),
    ];
    for (name, body, torque, at) in cases {
        let patch = std::fs::read_to_string(data.join(format!("{name}.patch"))).unwrap();
        let (_, text) = common::corpus::apply_patch(&patch, &base).unwrap();
        let dir = common::scratch(&format!("torque-limit-{name}"));
        std::fs::write(dir.join("case.toml"), &text).unwrap();
        let out = dir.join("out");
        let (code, err) = common::run_asperity(&[
            "run",
            &dir.display().to_string(),
            "--out",
            &out.display().to_string(),
        ]);
        assert_eq!(code, 4, "{name}: {err}");
        assert!(
            err.contains("the friction of interface") && err.contains("can hold about the axis"),
            "{name}: no cutback names the friction's hold: {err}"
        );
        let s = summary(&out);
        let (e, t) = limit(&s);
        let held = e["torque_nm"].as_f64().unwrap().abs();
        println!(
            "{name}: body {} lets go at λ = {t:.6}, holding {held:.4} N·m",
            e["body"]
        );
        assert_eq!(e["body"], body, "{name}");
        if let Some(hand) = torque {
            assert!(
                (held - hand).abs() < 0.01 * hand,
                "{name}: {held} vs {hand}"
            );
        }
        if let Some(hand) = at {
            assert!((t - hand).abs() < 0.01, "{name}: λ = {t} vs {hand}");
        }
    }
}
