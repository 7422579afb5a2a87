//! Section 5, first part: the ratings (summary.json `ratings`: each
//! standard's check beside the FE's number, PASS or FAIL in words and
//! colour, and the inputs it used), the loads applied (`applied_loads`) and
//! the points flagged as singular (`singular`).

use super::format::{component, figure, percent, with_unit};
use super::html::{Cell, Page};
use super::{num, text};
use serde_json::Value;

/// The ratings, one table of checks and one of inputs each.
pub(super) fn ratings(page: &mut Page, s: &Value) {
    page.heading("Ratings");
    let Some(list) = s.get("ratings").and_then(Value::as_array) else {
        page.absent("summary.json has no ratings: the case rates nothing against a standard (or the run predates them).");
        return;
    };
    if list.is_empty() {
        page.absent("The case has no rating.");
    }
    for r in list {
        let name = text(r, "name").unwrap_or_else(|| "unnamed".into());
        let standard = text(r, "standard").unwrap_or_else(|| "standard not recorded".into());
        let subject = text(r, "subject")
            .map(|t| format!(": {t}"))
            .unwrap_or_default();
        page.text(&format!("Rating {name} after {standard}{subject}."));
        if let Some(why) = text(r, "incomplete") {
            page.text(&format!("NOT RATED: {why}."));
        }
        let checks = r
            .get("checks")
            .and_then(Value::as_array)
            .map(Vec::as_slice)
            .unwrap_or(&[]);
        let rows = checks.iter().map(check_row).collect();
        let head = [
            "quantity",
            "symbol",
            "FE",
            "handbook",
            "difference",
            "required",
            "safety",
            "result",
            "note",
        ];
        page.table(&format!("Rating {name}: checks ({standard})"), &head, rows);
        inputs(page, r, &name);
    }
}

/// One check: its values with its unit, its safety against the required
/// one, and PASS / FAIL / not rated.
fn check_row(c: &Value) -> Vec<Cell> {
    let unit = text(c, "unit").unwrap_or_default();
    let value = |key: &str| Cell::n(num(c, key).map_or("—".into(), |v| with_unit(v, &unit)));
    let safety = match (num(c, "safety"), num(c, "required_safety")) {
        (Some(s), Some(r)) => format!("{} (required ≥ {})", figure(s), figure(r)),
        (Some(s), None) => figure(s),
        (None, _) => "—".into(),
    };
    let result = match c.get("pass").and_then(Value::as_bool) {
        Some(true) => Cell {
            text: "PASS".into(),
            class: "pass",
        },
        Some(false) => Cell {
            text: "FAIL".into(),
            class: "fail",
        },
        None => Cell::from("not rated"),
    };
    vec![
        Cell::from(text(c, "quantity").unwrap_or_default()),
        Cell::from(text(c, "symbol").unwrap_or_default()),
        value("fe"),
        value("handbook"),
        Cell::n(num(c, "difference").map_or("—".into(), percent)),
        value("required"),
        Cell::n(safety),
        result,
        Cell::from(text(c, "note").unwrap_or_default()),
    ]
}

/// The inputs of a rating: name, symbol, value with unit, where it came from.
fn inputs(page: &mut Page, r: &Value, name: &str) {
    let Some(list) = r
        .get("inputs")
        .and_then(Value::as_array)
        .filter(|l| !l.is_empty())
    else {
        page.absent(&format!("Rating {name} lists no inputs."));
        return;
    };
    let rows = list
        .iter()
        .map(|i| {
            let unit = text(i, "unit").unwrap_or_default();
            let value = match i.get("value") {
                Some(Value::Number(_)) => with_unit(num(i, "value").unwrap_or(f64::NAN), &unit),
                Some(Value::String(t)) => format!("{t} {unit}").trim().to_string(),
                _ => "—".into(),
            };
            vec![
                Cell::from(text(i, "name").unwrap_or_default()),
                Cell::from(text(i, "symbol").unwrap_or_default()),
                Cell::n(value),
                Cell::from(text(i, "from").unwrap_or_default()),
            ]
        })
        .collect();
    page.table(
        &format!("Rating {name}: inputs"),
        &["input", "symbol", "value", "from"],
        rows,
    );
}

/// The applied loads: one row per load and component, final, largest and
/// smallest over the run (forces in kN, moments in N·m).
pub(super) fn applied_loads(page: &mut Page, s: &Value) {
    page.heading("Applied loads");
    let Some(list) = s.get("applied_loads").and_then(Value::as_array) else {
        page.absent("summary.json has no applied_loads (the run predates them).");
        return;
    };
    let mut rows = Vec::new();
    for l in list {
        let comps: Vec<String> = l
            .get("components")
            .and_then(Value::as_array)
            .map(|a| {
                a.iter()
                    .filter_map(|c| c.as_str().map(str::to_string))
                    .collect()
            })
            .unwrap_or_default();
        let at = |key: &str, k: usize| {
            l.get(key)
                .and_then(|a| a.get(k))
                .and_then(Value::as_f64)
                .unwrap_or(f64::NAN)
        };
        for (k, c) in comps.iter().enumerate() {
            let (symbol, last) = component(c, at("final", k));
            rows.push(vec![
                Cell::from(text(l, "name").unwrap_or_default()),
                Cell::from(text(l, "kind").unwrap_or_default()),
                Cell::from(text(l, "selection").unwrap_or_default()),
                Cell::from(symbol),
                Cell::n(last),
                Cell::n(component(c, at("max", k)).1),
                Cell::n(component(c, at("min", k)).1),
            ]);
        }
    }
    let head = [
        "load",
        "kind",
        "where",
        "component",
        "final",
        "largest",
        "smallest",
    ];
    page.table("Applied loads (summary.json applied_loads)", &head, rows);
}

/// The points flagged as singular (a peak or first yield at a corner).
pub(super) fn singular(page: &mut Page, s: &Value) {
    page.heading("Singular points");
    let Some(list) = s.get("singular").and_then(Value::as_array) else {
        page.absent("summary.json has no singular list: a 3D run, whose corners are not searched, or one that predates it.");
        return;
    };
    if list.is_empty() {
        page.text("No peak and no first yield lies at a singular corner.");
        return;
    }
    let rows = list
        .iter()
        .map(|p| {
            vec![
                Cell::from(text(p, "what").unwrap_or_default()),
                Cell::from(text(p, "body").unwrap_or_default()),
                Cell::n(super::results::place(p)),
                Cell::from(text(p, "corner").unwrap_or_default()),
                Cell::n(
                    num(p, "estimate_share")
                        .map_or("—".into(), |v| format!("{} %", figure(100.0 * v))),
                ),
                Cell::from(text(p, "note").unwrap_or_default()),
            ]
        })
        .collect();
    let head = [
        "what",
        "body",
        "where (mm)",
        "corner",
        "share of the error estimate",
        "note",
    ];
    page.table(
        "Points at singular corners (summary.json singular)",
        &head,
        rows,
    );
}
