//! Adaptive runs on a largest value (issue 46): `[adapt] over = "history"`
//! reads the named quantity as its largest over every converged increment,
//! from the run's own records (the value equals the largest of the run's
//! outputs on the last mesh), and `quantity = "max_von_mises"` leaves out
//! the Gauss points within one element size of a singular point of the
//! start mesh, so the run converges on a stress that has a limit instead of
//! chasing the corner. Print the cycles with
//! `cargo test --release --test verification adapt_over:: -- --nocapture`.

use crate::common;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// A case written into a scratch folder `tag`/case and run: its output
/// folder and summary.json.
fn run(tag: &str, text: &str) -> (PathBuf, Value) {
    let dir = common::scratch(tag);
    let case = dir.join("case");
    std::fs::create_dir_all(&case).unwrap();
    std::fs::write(case.join("case.toml"), text).unwrap();
    let out = dir.join("out");
    let (code, err) = common::run_case(&case, &out, &[]);
    assert_eq!(code, 0, "{tag}: {err}");
    let s = serde_json::from_str(&common::read_out(&out, "summary.json")).unwrap();
    (out, s)
}

/// `text` with `old` (which it holds) replaced by `new`.
fn edit(text: &str, old: &str, new: &str) -> String {
    assert!(text.contains(old), "{old:?}");
    text.replace(old, new)
}

/// The punch of cases/punch-adaptive, coarser, pressed to 250 MPa at t = 1
/// and unloaded to 40 % of it at t = 2 (the foundation yields, so the
/// unloading is not the loading backwards), adapted three cycles on
/// `quantity` over the history.
fn pressed_and_unloaded(quantity: &str) -> String {
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-adaptive/case.toml")).unwrap();
    let text = edit(&text, "nx = [8]\n", "nx = [4]\n");
    let text = edit(&text, "ny = [6]\n", "ny = [3]\n");
    let text = edit(&text, "nx = [8, 8]", "nx = [4, 6]");
    let text = edit(&text, "ny = [12]", "ny = [6]");
    let text = edit(
        &text,
        "pressure = 250.0 ",
        "history = \"press\"\npressure = 250.0 ",
    );
    let text = edit(
        &text,
        "[solver]\nmethod = \"full-newton\"\nincrements = 20\nfirst_increment = 0.05",
        "[history]\npress = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.4]]\n\n[solver]\nmethod = \"full-newton\"\nincrements = 4",
    );
    let text = edit(&text, "tolerance = 0.01 ", "tolerance = 1e-6 ");
    edit(
        &text,
        "quantity = \"energy\"",
        &format!("quantity = \"{quantity}\"\nover = \"history\"\nmax_cycles = 3"),
    ) + "\n[output]\nvtu = false\n"
}

/// The values of column `name` of a CSV file (every cell a number).
fn column(out: &Path, file: &str, name: &str) -> Vec<f64> {
    common::csv_column(&out.join(file), name)
}

/// The peak pressure over the history of the pressed and partly unloaded
/// punch: every cycle's value is that of its run, and on the last mesh it
/// is the largest of contact.csv's `max_pressure_mpa` over the increments
/// (summary.json's `contact[].max_pressure`, full precision: to 1e-12),
/// reached at the end of the pressing (t = 1), well above the end's.
#[test]
fn the_peak_pressure_over_the_history_is_the_largest_of_the_runs_increments() {
    let (out, s) = run("adapt-over-peak", &pressed_and_unloaded("peak_pressure"));
    let a = &s["adapt"];
    assert_eq!(
        (a["quantity"].as_str(), a["over"].as_str()),
        (Some("peak_pressure"), Some("history"))
    );
    let cycles = a["cycles"].as_array().unwrap();
    assert_eq!(cycles.len(), 3, "{a}");
    let value = cycles[2]["value"].as_f64().unwrap();
    let peak = s["contact"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["max_pressure"]["value_mpa"].as_f64().unwrap())
        .fold(f64::NAN, f64::max);
    assert!(common::rel(value, peak) <= 1e-12, "{value} vs {peak}");
    assert_eq!(s["contact"][0]["max_pressure"]["time"].as_f64(), Some(1.0));
    // contact.csv (nine digits): its largest row, and its last row far below
    let p = column(&out, "contact.csv", "max_pressure_mpa");
    let t = column(&out, "contact.csv", "time");
    assert_eq!(*t.last().unwrap(), 2.0);
    let largest = p.iter().copied().fold(f64::NAN, f64::max);
    assert!(common::rel(value, largest) <= 1e-9, "{value} vs {p:?}");
    let end = *p.last().unwrap();
    assert!(
        end < 0.6 * value,
        "the end's {end} vs the history's {value}"
    );
    // the estimate is the change of these values between meshes
    for w in cycles.windows(2) {
        let (q0, q1) = (
            w[0]["value"].as_f64().unwrap(),
            w[1]["value"].as_f64().unwrap(),
        );
        let e = w[1]["estimate"].as_f64().unwrap();
        assert!(
            common::rel(e, ((q1 - q0) / q1).abs()) <= 1e-12,
            "{e} {q0} {q1}"
        );
    }
    eprintln!(
        "punch pressed to t = 1 and unloaded to 40 %: peak pressure over the history {value:.3} MPa, at the end {end:.3} MPa; per cycle {:?}",
        cycles.iter().map(|c| c["value"].as_f64().unwrap()).collect::<Vec<_>>()
    );
}

/// The settlement over the history: the probe node's displacement
/// farthest from 0 (the deepest, at t = 1), its sign kept: the smallest of
/// curve.csv's `center_displacement_mm`, not its last row.
#[test]
fn the_settlement_over_the_history_is_the_deepest_of_the_curve() {
    let (out, s) = run("adapt-over-settlement", &pressed_and_unloaded("settlement"));
    let cycles = s["adapt"]["cycles"].as_array().unwrap();
    let value = cycles.last().unwrap()["value"].as_f64().unwrap();
    let w = column(&out, "curve.csv", "center_displacement_mm");
    let deepest = w.iter().copied().fold(f64::NAN, f64::min);
    assert!(
        value < 0.0 && common::rel(value, deepest) <= 1e-9,
        "{value} vs {w:?}"
    );
    // every cycle's settlement_mm column stays the end's
    let end = cycles.last().unwrap()["settlement_mm"].as_f64().unwrap();
    assert!(
        common::rel(end, *w.last().unwrap()) <= 1e-9,
        "{end} vs {w:?}"
    );
    assert!(end.abs() < 0.9 * value.abs(), "{end} vs {value}");
}

/// A stepped plate (plane strain, elastic) pulled along its axis by a
/// prescribed displacement: the step makes a re-entrant corner at (3, 4),
/// the mesh's only singular point (the rollers meet the free edges at
/// right angles: mirrors).
const STEPPED: &str = r#"
description = "a stepped plate pulled: re-entrant corner at (3, 4)"
[model]
plane = "strain"
[[mesh.block]]
body = "plate"
name = "wide"
x = [0.0, 3.0, 6.0]
nx = [3, 3]
y = [0.0, 4.0]
ny = [4]
[[mesh.block]]
body = "plate"
name = "narrow"
x = [0.0, 3.0]
nx = [3]
y = [4.0, 8.0]
ny = [4]
[materials.plate]
young = 200000.0
poisson = 0.3
[[boundary]]
set = "wide.bottom"
uy = 0.0
[[boundary]]
set = "wide.left"
ux = 0.0
[[boundary]]
set = "narrow.left"
ux = 0.0
[[boundary]]
set = "narrow.top"
uy = 0.01
[solver]
increments = 2
[output]
vtu = false
[adapt]
tolerance = 1e-6
quantity = "max_von_mises"
over = "history"
max_cycles = 7
"#;

/// How many of the 3×3 Gauss points of the start mesh (unit squares, 24 in
/// the wide block, 12 in the narrow one) lie within √2 of the corner
/// (3, 4): counted here from the rule's geometry alone.
fn gauss_points_within_the_corners_disc() -> usize {
    let g = [0.5 - 0.5 * 0.6f64.sqrt(), 0.5, 0.5 + 0.5 * 0.6f64.sqrt()];
    let squares: Vec<(usize, usize)> = (0..6)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .chain((0..3).flat_map(|i| (4..8).map(move |j| (i, j))))
        .collect();
    let mut n = 0;
    for (i, j) in squares {
        for a in g {
            for b in g {
                let (x, y) = (i as f64 + a, j as f64 + b);
                if (x - 3.0).hypot(y - 4.0) <= 2f64.sqrt() {
                    n += 1;
                }
            }
        }
    }
    n
}

/// `max_von_mises` at a re-entrant corner: the disc left out is the
/// corner's, of radius √2 (the diagonal of the start mesh's elements at
/// it), holding on the start mesh exactly the Gauss points within it; the
/// stress away from the corner converges (its change between meshes falls
/// by more than an order of magnitude) while the largest stress anywhere,
/// at the corner, grows by more than a tenth on every mesh (σ ~ r^(λ−1),
/// λ = 0.544), the singularity the exclusion keeps out of the answer.
#[test]
fn the_stress_away_from_a_re_entrant_corner_converges_where_the_raw_peak_does_not() {
    let (out, s) = run("adapt-max-von-mises", STEPPED);
    let a = &s["adapt"];
    let discs = a["excluded"].as_array().unwrap();
    assert_eq!(discs.len(), 1, "{a}");
    let d = &discs[0];
    assert_eq!(d["corner"], "re-entrant corner (270°)");
    assert_eq!(
        (d["x_mm"].as_f64(), d["y_mm"].as_f64()),
        (Some(3.0), Some(4.0))
    );
    assert!(
        common::rel(d["radius_mm"].as_f64().unwrap(), 2f64.sqrt()) < 1e-12,
        "{d}"
    );
    assert_eq!(d["bodies"], serde_json::json!(["plate"]));
    let cycles = a["cycles"].as_array().unwrap();
    assert_eq!(cycles.len(), 7, "{a}");
    let num = |c: &Value, k: &str| c[k].as_f64().unwrap();
    assert_eq!(
        cycles[0]["excluded_points"].as_u64(),
        Some(gauss_points_within_the_corners_disc() as u64)
    );
    for w in cycles.windows(2) {
        // the same disc holds more points of each finer mesh
        assert!(w[1]["excluded_points"].as_u64() > w[0]["excluded_points"].as_u64());
        // the raw peak grows by more than a tenth every cycle
        let (r0, r1) = (
            num(&w[0], "max_von_mises_all_mpa"),
            num(&w[1], "max_von_mises_all_mpa"),
        );
        assert!((r1 - r0) / r1 > 0.1, "{r0} then {r1}");
    }
    for c in cycles {
        assert!(num(c, "value") < num(c, "max_von_mises_all_mpa"), "{c}");
    }
    let e2 = num(&cycles[1], "estimate");
    let last = num(cycles.last().unwrap(), "estimate");
    assert!(last < e2 / 10.0 && last < 1e-3, "{e2} then {last}");
    // the raw peak over the history is summary.json's, and it sits in the disc
    let peak = &s["peaks"][0]["max_von_mises"];
    let raw = num(cycles.last().unwrap(), "max_von_mises_all_mpa");
    assert!(
        common::rel(raw, num(peak, "value_mpa")) <= 1e-12,
        "{raw} vs {peak}"
    );
    let r = (num(peak, "x_mm") - 3.0).hypot(num(peak, "y_mm") - 4.0);
    assert!(r <= 2f64.sqrt(), "{peak}");
    // adapt.csv holds the same columns
    let csv = column(&out, "adapt.csv", "excluded_points");
    assert_eq!(csv.len(), 7);
    eprintln!(
        "stepped plate: away from the corner {:?} MPa (estimates {:?}); anywhere {:?} MPa",
        cycles.iter().map(|c| num(c, "value")).collect::<Vec<_>>(),
        cycles
            .iter()
            .map(|c| c["estimate"].as_f64())
            .collect::<Vec<_>>(),
        cycles
            .iter()
            .map(|c| num(c, "max_von_mises_all_mpa"))
            .collect::<Vec<_>>()
    );
}
