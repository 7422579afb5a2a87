//! The peaks' files: `peaks.csv`, `contact.csv` and summary.json's
//! `peaks` ([`crate::measure::peaks`] computes them).

use super::joints_csv::csv_field;
use crate::model::outputs::{PER_BODY, PER_INTERFACE};
use crate::model::Model;
use crate::solve::RunResult;
use serde_json::{json, Value};
use std::fmt::Write as _;

pub(crate) const BODIES_HEADER: &str = "increment,time,body,von_mises_mpa,von_mises_x_mm,von_mises_y_mm,von_mises_element,peeq,peeq_x_mm,peeq_y_mm,peeq_element\n";

/// The header of a 3D model: z beside x and y.
pub(crate) const BODIES_HEADER_SOLID: &str = "increment,time,body,von_mises_mpa,von_mises_x_mm,von_mises_y_mm,von_mises_z_mm,von_mises_element,peeq,peeq_x_mm,peeq_y_mm,peeq_z_mm,peeq_element\n";

/// `peaks.csv`: one row per increment and body (an empty place where there
/// is none).
pub(crate) fn bodies_csv(model: &Model, r: &RunResult, at: impl Fn(&[f64]) -> &[f64]) -> String {
    let solid = model.mesh.dim() == 3;
    let mut s = String::from(if solid {
        BODIES_HEADER_SOLID
    } else {
        BODIES_HEADER
    });
    for inc in &r.increments {
        let v = at(&inc.record);
        for (name, b) in model.mesh.bodies.iter().zip(v.chunks_exact(PER_BODY)) {
            let _ = write!(
                s,
                "{},{:.9},{}",
                inc.increment,
                inc.load_factor,
                csv_field(name)
            );
            // value, x, y, (z,) element: twice
            for half in b.chunks_exact(PER_BODY / 2) {
                let _ = write!(s, ",{},{},{}", real(half[0]), real(half[1]), real(half[2]));
                if solid {
                    let _ = write!(s, ",{}", real(half[3]));
                }
                let _ = write!(s, ",{}", whole(half[4]));
            }
            s.push('\n');
        }
    }
    s
}

pub(crate) const CONTACT_HEADER: &str = "increment,time,interface,max_pressure_mpa,max_pressure_x_mm,max_pressure_y_mm,max_pressure_s_mm,contact_from_s_mm,contact_to_s_mm,contact_from_x_mm,contact_from_y_mm,contact_to_x_mm,contact_to_y_mm\n";

/// `contact.csv`: one row per increment and interface.
pub(crate) fn contact_csv(model: &Model, r: &RunResult, at: impl Fn(&[f64]) -> &[f64]) -> String {
    let mut s = String::from(CONTACT_HEADER);
    for inc in &r.increments {
        let v = at(&inc.record);
        for (im, c) in model.interfaces.iter().zip(v.chunks_exact(PER_INTERFACE)) {
            let _ = write!(
                s,
                "{},{:.9},{}",
                inc.increment,
                inc.load_factor,
                csv_field(&im.name)
            );
            for x in c {
                let _ = write!(s, ",{}", real(*x));
            }
            s.push('\n');
        }
    }
    s
}

/// A CSV number: `{:.9e}`, empty for NaN (no such value).
fn real(x: f64) -> String {
    if x.is_nan() {
        String::new()
    } else {
        format!("{x:.9e}")
    }
}

fn whole(x: f64) -> String {
    if x.is_nan() {
        String::new()
    } else {
        format!("{}", x as i64)
    }
}

/// The largest of column `col` over the rows with its row index (NaN
/// values skipped; the first row on a tie).
fn argmax(rows: &[&[f64]], col: usize) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (k, r) in rows.iter().enumerate() {
        if r[col].is_nan() {
            continue;
        }
        if best.is_none_or(|b| r[col] > rows[b][col]) {
            best = Some(k);
        }
    }
    best
}

/// One peak over the run: value, place and when, or null. `body`: a body's
/// peak (value, x, y, z, element; `Some(true)` in a 3D model, which names
/// z), else an interface's (value, x, y, s).
fn peak(
    r: &RunResult,
    rows: &[(usize, &[f64])],
    at: usize,
    unit: &str,
    body: Option<bool>,
) -> Value {
    let only: Vec<&[f64]> = rows.iter().map(|x| x.1).collect();
    let Some(k) = argmax(&only, at) else {
        return Value::Null;
    };
    let v = only[k];
    if v[at + 1].is_nan() {
        // a value without a place: nothing reached (no plastic strain, no contact)
        return Value::Null;
    }
    let inc = &r.increments[rows[k].0];
    let mut o = json!({
        unit: v[at],
        "x_mm": v[at + 1],
        "y_mm": v[at + 2],
        "increment": inc.increment,
        "time": inc.load_factor,
    });
    match body {
        Some(solid) => {
            if solid {
                o["z_mm"] = json!(v[at + 3]);
            }
            o["element"] = json!(v[at + 4] as i64);
        }
        None => o["s_mm"] = json!(v[at + 3]),
    }
    o
}

/// The summary's `peaks` (per body) and `contact` (per interface): the
/// largest values over the run's increments with their place and
/// increment, and the last increment's contact extent.
pub fn summary(
    model: &Model,
    r: &RunResult,
    rows: &[(usize, &[f64])],
    body_at: usize,
    iface_at: usize,
) -> (Value, Value) {
    let solid = model.mesh.dim() == 3;
    let bodies = model
        .mesh
        .bodies
        .iter()
        .enumerate()
        .map(|(b, name)| {
            let o = body_at + PER_BODY * b;
            json!({
                "body": name,
                "max_von_mises": peak(r, rows, o, "value_mpa", Some(solid)),
                "max_peeq": peak(r, rows, o + PER_BODY / 2, "value", Some(solid)),
            })
        })
        .collect();
    let contact = model
        .interfaces
        .iter()
        .enumerate()
        .map(|(i, im)| {
            let o = iface_at + PER_INTERFACE * i;
            let extent = rows.last().and_then(|(_, v)| {
                let e = &v[o + 4..o + 10];
                (!e[0].is_nan()).then(|| {
                    json!({
                        "from_s_mm": e[0],
                        "to_s_mm": e[1],
                        "from_x_mm": e[2],
                        "from_y_mm": e[3],
                        "to_x_mm": e[4],
                        "to_y_mm": e[5],
                    })
                })
            });
            json!({
                "interface": im.name,
                "max_pressure": peak(r, rows, o, "value_mpa", None),
                "final_extent": extent,
            })
        })
        .collect();
    (bodies, contact)
}
