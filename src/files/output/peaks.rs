//! Peaks of a converged state: per body the largest von Mises stress and
//! the largest equivalent plastic strain over its Gauss points, with the
//! point's coordinates and element; per interface the largest contact
//! pressure over its pairs with the pair's place, and the contact extent
//! (the stretch of the interface, by arc length s, from the first to the
//! last pair with p > 0).
//!
//! The Gauss states of an MPI run are spread over the ranks: the body peaks
//! are reduced over every rank (the largest value, then the lowest
//! (element, point) index holding it, as one process finds it), so every
//! rank gets the same record. The interface values come from the
//! displacements, which every rank holds whole.

use super::joints_csv::csv_field;
use crate::model::Model;
use crate::physics::material::VonMises;
use crate::solve::{Engine, RunResult, State};
use serde_json::{json, Value};
use std::fmt::Write as _;

/// Values per body in a record: von Mises (MPa, x, y, element), then
/// PEEQ (value, x, y, element).
pub const PER_BODY: usize = 8;
/// Values per interface in a record: the largest pressure (MPa, x, y, s),
/// then the extent (from s, to s, from x, from y, to x, to y).
pub const PER_INTERFACE: usize = 10;

/// The body peaks of a state (collective under MPI): [`PER_BODY`] values
/// per body. A body without plastic strain has PEEQ 0 and no place (NaN).
pub fn bodies(engine: &Engine, state: &State) -> Vec<f64> {
    body_peaks(engine.model, engine.held_elements(), &state.gauss, |v| {
        engine.backend.max(v)
    })
}

/// [`bodies`] of a whole state in one process (every element's Gauss
/// states, as a restart file holds them): what a run's record holds,
/// whatever its ranks.
pub fn bodies_whole(model: &Model, gauss: &[crate::physics::material::PointState]) -> Vec<f64> {
    let all: Vec<u32> = (0..model.mesh.elements.len() as u32).collect();
    body_peaks(model, &all, gauss, |_| {})
}

/// The body peaks over the elements `held` (their Gauss states `gauss`, in
/// that order), `max` the reduction over the ranks.
fn body_peaks(
    model: &Model,
    held: &[u32],
    gauss: &[crate::physics::material::PointState],
    max: impl Fn(&mut [f64]),
) -> Vec<f64> {
    let nb = model.mesh.bodies.len();
    let ng = model.n_gauss();
    // this rank's largest von Mises and PEEQ per body, and their point index
    let mut best = vec![(f64::NEG_INFINITY, usize::MAX); 2 * nb];
    for (k, &e) in held.iter().enumerate() {
        let e = e as usize;
        let b = model.mesh.elements[e].body;
        for ip in 0..ng {
            let g = &gauss[k * ng + ip];
            let i = e * ng + ip;
            for (slot, v) in [
                (b, VonMises::equivalent_stress(&g.stress)),
                (nb + b, g.peeq),
            ] {
                if v > best[slot].0 {
                    best[slot] = (v, i);
                }
            }
        }
    }
    let mut top: Vec<f64> = best.iter().map(|b| b.0).collect();
    max(&mut top);
    // the lowest index holding the largest value (negated: a max reduction)
    let mut key: Vec<f64> = best
        .iter()
        .zip(&top)
        .map(|(&(v, i), &t)| {
            if v == t && i != usize::MAX {
                -(i as f64)
            } else {
                f64::NEG_INFINITY
            }
        })
        .collect();
    max(&mut key);
    let place = |slot: usize| -> [f64; 3] {
        if key[slot] == f64::NEG_INFINITY {
            return [f64::NAN; 3];
        }
        let i = (-key[slot]) as usize;
        let (e, ip) = (i / ng, i % ng);
        let x = model.geometry(e).x[ip];
        [x[0], x[1], e as f64]
    };
    let mut out = Vec::with_capacity(PER_BODY * nb);
    for b in 0..nb {
        let vm = top[b].max(0.0);
        let pe = top[nb + b].max(0.0);
        out.push(vm);
        out.extend(place(b));
        out.push(pe);
        // no plastic strain: no place
        out.extend(if pe > 0.0 {
            place(nb + b)
        } else {
            [f64::NAN; 3]
        });
    }
    out
}

/// The interface peaks of displacements `u` at pseudo-time `time`:
/// [`PER_INTERFACE`] values per interface (`arcs`: each pair's arc length,
/// [`crate::model::interface::joint::arc_lengths`]). An interface without
/// contact has pressure 0 and no place or extent (NaN).
pub fn interfaces(model: &Model, arcs: &[Vec<f64>], u: &[f64], time: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(PER_INTERFACE * model.interfaces.len());
    for (im, arc) in model.interfaces.iter().zip(arcs) {
        let gap = im.gap_at(time);
        let mut peak: Option<(f64, usize)> = None;
        let mut from: Option<usize> = None;
        let mut to: Option<usize> = None;
        for (i, pr) in im.pairs.iter().enumerate() {
            let p = im.law.pressure(im.pair_approach_at(pr, u, gap)).0;
            if p <= 0.0 {
                continue;
            }
            if peak.is_none_or(|(q, _)| p > q) {
                peak = Some((p, i));
            }
            let s = arc.get(i).copied().unwrap_or(f64::NAN);
            if from.is_none_or(|j| s < arc[j]) {
                from = Some(i);
            }
            if to.is_none_or(|j| s > arc[j]) {
                to = Some(i);
            }
        }
        let at = |i: Option<usize>| -> [f64; 3] {
            i.map_or([f64::NAN; 3], |i| {
                let x = im.pairs[i].x;
                [x[0], x[1], arc.get(i).copied().unwrap_or(f64::NAN)]
            })
        };
        out.push(peak.map_or(0.0, |p| p.0));
        out.extend(at(peak.map(|p| p.1)));
        let (f, t) = (at(from), at(to));
        out.extend([f[2], t[2], f[0], f[1], t[0], t[1]]);
    }
    out
}

pub const BODIES_HEADER: &str = "increment,time,body,von_mises_mpa,von_mises_x_mm,von_mises_y_mm,von_mises_element,peeq,peeq_x_mm,peeq_y_mm,peeq_element\n";

/// `peaks.csv`: one row per increment and body (an empty place where there
/// is none).
pub fn bodies_csv(model: &Model, r: &RunResult, at: impl Fn(&[f64]) -> Option<&[f64]>) -> String {
    let mut s = String::from(BODIES_HEADER);
    for inc in &r.increments {
        let Some(v) = at(&inc.record) else { continue };
        for (name, b) in model.mesh.bodies.iter().zip(v.chunks_exact(PER_BODY)) {
            let _ = writeln!(
                s,
                "{},{:.9},{},{},{},{},{},{},{},{},{}",
                inc.increment,
                inc.load_factor,
                csv_field(name),
                real(b[0]),
                real(b[1]),
                real(b[2]),
                whole(b[3]),
                real(b[4]),
                real(b[5]),
                real(b[6]),
                whole(b[7])
            );
        }
    }
    s
}

pub const CONTACT_HEADER: &str = "increment,time,interface,max_pressure_mpa,max_pressure_x_mm,max_pressure_y_mm,max_pressure_s_mm,contact_from_s_mm,contact_to_s_mm,contact_from_x_mm,contact_from_y_mm,contact_to_x_mm,contact_to_y_mm\n";

/// `contact.csv`: one row per increment and interface.
pub fn contact_csv(model: &Model, r: &RunResult, at: impl Fn(&[f64]) -> Option<&[f64]>) -> String {
    let mut s = String::from(CONTACT_HEADER);
    for inc in &r.increments {
        let Some(v) = at(&inc.record) else { continue };
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

/// One peak over the run: value, place and when, or null.
fn peak(r: &RunResult, rows: &[(usize, &[f64])], at: usize, unit: &str, body: bool) -> Value {
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
    if body {
        o["element"] = json!(v[at + 3] as i64);
    } else {
        o["s_mm"] = json!(v[at + 3]);
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
    let bodies = model
        .mesh
        .bodies
        .iter()
        .enumerate()
        .map(|(b, name)| {
            let o = body_at + PER_BODY * b;
            json!({
                "body": name,
                "max_von_mises": peak(r, rows, o, "value_mpa", true),
                "max_peeq": peak(r, rows, o + 4, "value", true),
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
                "max_pressure": peak(r, rows, o, "value_mpa", false),
                "final_extent": extent,
            })
        })
        .collect();
    (bodies, contact)
}
