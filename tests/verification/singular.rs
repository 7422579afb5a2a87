//! Singular points (summary.json `singular`, docs/joints.md "Singular
//! corners"): the shipped cases with a sharp corner flag the peak and the
//! first yield there, the filleted shaft does not flag its fillet's peak,
//! and what a flag claims, that the value grows (a first-yield load falls)
//! as the mesh is refined, holds on two refinements of two cases.

use crate::common;
use serde_json::Value;

/// Runs `case` (with `extra` arguments) and returns its summary.json and stderr.
fn run(case: &str, tag: &str, extra: &[&str]) -> (Value, String) {
    let out = common::scratch(&format!("singular-{tag}"));
    let _ = std::fs::remove_dir_all(&out);
    let (code, err) = common::run_case(&common::root().join("cases").join(case), &out, extra);
    assert_eq!(code, 0, "{case}: {err}");
    let s: Value = serde_json::from_str(&common::read_out(&out, "summary.json")).unwrap();
    let _ = std::fs::remove_dir_all(&out);
    (s, err)
}

/// The flagged entry `what` of `body`.
fn flagged<'a>(s: &'a Value, what: &str, body: &str) -> Option<&'a Value> {
    s["singular"]
        .as_array()
        .expect("summary.json singular")
        .iter()
        .find(|p| p["what"] == what && p["body"] == body)
}

/// The largest `key` (`max_von_mises` or `max_peeq`) of `body`: its value.
fn peak(s: &Value, body: &str, key: &str) -> f64 {
    let p = s["peaks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["body"] == body)
        .unwrap();
    let v = &p[key];
    v["value_mpa"].as_f64().or(v["value"].as_f64()).unwrap()
}

#[test]
fn sharp_corners_are_flagged_and_the_fillet_is_not() {
    // the bolt's head on its shank: a 270° corner at (6, 12)
    let (s, err) = run("bolted-joint", "bolt", &[]);
    for what in ["first_yield", "max_von_mises"] {
        let p = flagged(&s, what, "bolt").unwrap_or_else(|| panic!("{what}: {}", s["singular"]));
        assert_eq!(p["corner"], "re-entrant corner (270°)", "{p}");
        assert_eq!(
            (p["corner_x_mm"].as_f64(), p["corner_y_mm"].as_f64()),
            (Some(6.0), Some(12.0))
        );
        // its place is the one summary.json reports for it
        let fy = &s["first_yield"];
        if what == "first_yield" {
            assert_eq!(p["x_mm"].as_f64(), fy["x_mm"].as_f64());
        }
        let share = p["estimate_share"].as_f64().unwrap();
        assert!(share > 0.05 && share < 1.0, "{share}");
        assert!(p["note"].as_str().unwrap().contains("fillet the corner"));
    }
    let event = s["events"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["event"] == "first_yield")
        .unwrap();
    assert!(
        event["meaning"]
            .as_str()
            .unwrap()
            .contains("at a singular point of the mesh, re-entrant corner (270°)"),
        "{}",
        event["meaning"]
    );
    // the plates' peaks sit at the bore's edge under the head and the nut
    let plate = flagged(&s, "max_von_mises", "top_plate").unwrap();
    assert_eq!(plate["corner"], "end of contact interface under_head");
    // one line per entry, before the run's end block, no warning (a run
    // without --quiet; with it, none)
    assert!(!err.contains("singular:"), "{err}");
    let out = common::scratch("singular-bolt-lines");
    let case = common::root().join("cases/bolted-joint");
    let (code, err, _) = common::run_asperity_out(&[
        "run",
        &case.display().to_string(),
        "--out",
        &out.display().to_string(),
    ]);
    assert_eq!(code, 0, "{err}");
    let end = err.find("\nfirst yield:").expect("the end block");
    assert!(err.rfind("singular:").is_some_and(|k| k < end), "{err}");
    let lines = err
        .lines()
        .filter(|l| l.starts_with("singular:") && l.contains("lies at a singular point"));
    assert!(!err.contains("warning:"), "{err}");
    assert_eq!(
        lines.count(),
        s["singular"].as_array().unwrap().len(),
        "{err}"
    );

    // the punch's edge on the foundation: the foundation's first yield
    let (s, _) = run("punch-plane-strain", "punch", &[]);
    let p = flagged(&s, "first_yield", "foundation").unwrap_or_else(|| panic!("{}", s["singular"]));
    assert_eq!(p["corner"], "end of contact interface contact");
    assert_eq!(
        (p["corner_x_mm"].as_f64(), p["corner_y_mm"].as_f64()),
        (Some(20.0), Some(0.0))
    );

    // the shaft's 1 mm shoulder fillet holds its peak (K_t), and no corner
    let (s, err) = run("shaft-fillet", "fillet", &[]);
    assert!(peak(&s, "shaft", "max_von_mises") > 150.0);
    assert_eq!(s["singular"], serde_json::json!([]), "{}", s["singular"]);
    assert!(!err.contains("singular point"), "{err}");
}

#[test]
fn a_flagged_peak_grows_with_refinement() {
    // the bolt's corner: its first yield comes earlier (from the service
    // load at refine 1 into the preload at refine 2) and its PEEQ grows
    let (a, _) = run("bolted-joint", "bolt-1", &["--refine", "1"]);
    let (b, _) = run("bolted-joint", "bolt-2", &["--refine", "2"]);
    for s in [&a, &b] {
        assert!(
            flagged(s, "first_yield", "bolt").is_some(),
            "{}",
            s["singular"]
        );
        assert!(
            flagged(s, "max_peeq", "bolt").is_some(),
            "{}",
            s["singular"]
        );
    }
    let load = |s: &Value| s["first_yield"]["load_factor"].as_f64().unwrap();
    assert!(load(&b) < 0.8 * load(&a), "{} → {}", load(&a), load(&b));
    let peeq = |s: &Value| peak(s, "bolt", "max_peeq");
    assert!(peeq(&b) > 2.0 * peeq(&a), "{} → {}", peeq(&a), peeq(&b));
    // the punch's edge: the foundation's first-yield load falls, its
    // largest von Mises stress grows
    let (a, _) = run("punch-plane-strain", "punch-1", &["--refine", "1"]);
    let (b, _) = run("punch-plane-strain", "punch-2", &["--refine", "2"]);
    for s in [&a, &b] {
        assert!(
            flagged(s, "first_yield", "foundation").is_some(),
            "{}",
            s["singular"]
        );
        assert!(
            flagged(s, "max_von_mises", "foundation").is_some(),
            "{}",
            s["singular"]
        );
    }
    let load = |s: &Value| s["first_yield"]["total_load_kn"].as_f64().unwrap();
    assert!(load(&b) < 0.97 * load(&a), "{} → {}", load(&a), load(&b));
    let vm = |s: &Value| peak(s, "foundation", "max_von_mises");
    assert!(vm(&b) > 1.1 * vm(&a), "{} → {}", vm(&a), vm(&b));
}
