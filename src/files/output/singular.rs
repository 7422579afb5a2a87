//! summary.json's `singular` and the lines the run prints of it before its end: the peaks
//! (per body, the largest von Mises stress and PEEQ over the run, as
//! summary.json's `peaks` places them) and the first yield that lie at a
//! singular point of the mesh ([`crate::measure::singular`] decides,
//! [`crate::model::singular`] finds the points).

use super::json::number;
use crate::measure::singular::{flag, point_at, Flag, Place};
use crate::model::Model;
use crate::solve::events::{Event, Kind};
use crate::solve::RunResult;
use serde_json::{json, Value};

/// The place of a first-yield event (its Gauss point, its element's body).
pub fn first_yield_place(model: &Model, e: &Event) -> Option<Place> {
    if e.kind != Kind::FirstYield {
        return None;
    }
    let el = e.place[3];
    let element = (el.is_finite() && el >= 0.0 && (el as usize) < model.mesh.elements.len())
        .then_some(el as usize)?;
    Some(Place {
        what: "first_yield",
        body: model.mesh.elements[element].body,
        x: [e.place[0], e.place[1], e.place[2]],
        element: Some(element),
    })
}

/// The singular point a first-yield event lies at, if any.
pub fn first_yield_point<'a>(
    model: &'a Model,
    e: &Event,
) -> Option<&'a crate::model::singular::SingularPoint> {
    let place = first_yield_place(model, e)?;
    point_at(model, &place).map(|k| &model.singular[k])
}

/// The places the run reports: its first yield, then per body its largest
/// von Mises stress and PEEQ over the run (summary.json's `peaks`).
fn places(model: &Model, r: &RunResult, peaks: &Value) -> Vec<Place> {
    let mut out: Vec<Place> = r
        .events
        .iter()
        .filter_map(|e| first_yield_place(model, e))
        .take(1)
        .collect();
    for (b, p) in peaks
        .as_array()
        .map_or(&[][..], Vec::as_slice)
        .iter()
        .enumerate()
    {
        for what in ["max_von_mises", "max_peeq"] {
            let v = &p[what];
            let (Some(x), Some(y)) = (v["x_mm"].as_f64(), v["y_mm"].as_f64()) else {
                continue;
            };
            out.push(Place {
                what,
                body: b,
                x: [x, y, v["z_mm"].as_f64().unwrap_or(0.0)],
                element: v["element"].as_u64().map(|e| e as usize),
            });
        }
    }
    out
}

/// The run's places at singular points, with their share of the error
/// estimate (`peaks`: summary.json's `peaks`).
pub fn flags(model: &Model, r: &RunResult, peaks: &Value) -> Vec<Flag> {
    flag(model, &places(model, r, peaks), r.estimate.as_ref())
}

/// [`flags`] with the peaks computed from the run's records.
pub fn run_flags(model: &Model, r: &RunResult) -> Vec<Flag> {
    let plan = &model.plan;
    let rows: Vec<(usize, &[f64])> = r
        .increments
        .iter()
        .enumerate()
        .map(|(k, i)| (k, i.record.as_slice()))
        .collect();
    let (peaks, _) = super::peaks::summary(
        model,
        r,
        &rows,
        plan.layout.bodies.start,
        plan.layout.interfaces.start,
    );
    flags(model, r, &peaks)
}

/// What to do about a place at this point, after what it does under
/// refinement.
fn note(model: &Model, f: &Flag) -> String {
    let grows = if f.place.what == "first_yield" {
        "its load falls with refinement"
    } else {
        "grows with refinement"
    };
    let corner = &f.at(model).corner;
    let fix = if corner.starts_with("re-entrant") {
        "read a nominal stress or fillet the corner"
    } else if corner.starts_with("end of contact") {
        "read a nominal stress or round the edge"
    } else {
        "read the stress a distance away from the support's end"
    };
    format!("{grows}: {fix}")
}

/// summary.json's `singular`: one object per flagged place; absent (None)
/// in a 3D model, whose corners are not searched.
pub fn summary(model: &Model, flags: &[Flag]) -> Option<Value> {
    if model.mesh.dim() == 3 {
        return None;
    }
    Some(
        flags
            .iter()
            .map(|f| {
                let p = &f.place;
                json!({
                    "what": p.what,
                    "body": model.mesh.bodies[p.body],
                    "x_mm": number(p.x[0]),
                    "y_mm": number(p.x[1]),
                    "corner": f.at(model).corner,
                    "corner_x_mm": f.at(model).x[0],
                    "corner_y_mm": f.at(model).x[1],
                    "estimate_share": f.share.map_or(Value::Null, number),
                    "note": note(model, f),
                })
            })
            .collect(),
    )
}

/// What a place is, in words.
fn words(what: &str) -> &str {
    match what {
        "first_yield" => "first yield",
        "max_von_mises" => "largest von Mises stress",
        "max_peeq" => "largest PEEQ",
        other => other,
    }
}

/// One line per flagged place (without `singular: `).
pub fn lines(model: &Model, flags: &[Flag]) -> Vec<String> {
    let source = model.source.display();
    flags
        .iter()
        .map(|f| {
            let p = &f.place;
            let share = f.share.map_or(String::new(), |s| {
                format!(" ({:.1} % of the error estimate in the elements there)", 100.0 * s)
            });
            format!(
                "{source}: {} in body {:?} at ({:.4}, {:.4}) mm lies at a singular point, {} at ({:.4}, {:.4}){share}: {} (docs/joints.md, \"Singular corners\")",
                words(p.what),
                model.mesh.bodies[p.body],
                p.x[0],
                p.x[1],
                f.at(model).corner,
                f.at(model).x[0],
                f.at(model).x[1],
                note(model, f)
            )
        })
        .collect()
}
