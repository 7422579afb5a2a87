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

use crate::linalg::backend::Comm;
use crate::model::state::State;
use crate::model::Model;
use crate::physics::material::{GaussStates, VonMises};

use crate::model::outputs::{PER_BODY, PER_INTERFACE};

/// The body peaks of a state (collective under MPI): `PER_BODY` values
/// per body. A body without plastic strain has PEEQ 0 and no place (NaN).
pub fn bodies(model: &Model, comm: &dyn Comm, held: &[u32], state: &State) -> Vec<f64> {
    body_peaks(model, held, &state.gauss, |v| comm.max(v))
}

/// [`bodies`] of a whole state in one process (every element's Gauss
/// states, as a restart file holds them): what a run's record holds,
/// whatever its ranks.
pub(crate) fn bodies_whole(model: &Model, gauss: &GaussStates) -> Vec<f64> {
    let all: Vec<u32> = (0..model.mesh.elements.len() as u32).collect();
    body_peaks(model, &all, gauss, |_| {})
}

/// The body peaks over the elements `held` (their Gauss states `gauss`, in
/// that order), `max` the reduction over the ranks.
fn body_peaks(
    model: &Model,
    held: &[u32],
    gauss: &GaussStates,
    max: impl Fn(&mut [f64]),
) -> Vec<f64> {
    let nb = model.mesh.bodies.len();
    // this rank's largest von Mises and PEEQ per body, and their point index
    let mut best = vec![(f64::NEG_INFINITY, usize::MAX); 2 * nb];
    for (e, local) in model.held_points(held) {
        let b = model.mesh.elements[e].body;
        for (ip, g) in gauss.range(local).iter().enumerate() {
            let i = model.points(e).start + ip;
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
    let place = |slot: usize| -> [f64; 4] {
        if key[slot] == f64::NEG_INFINITY {
            return [f64::NAN; 4];
        }
        let i = (-key[slot]) as usize;
        let e = model.element_of_point(i);
        let x = model.point_x(e, i - model.points(e).start);
        [x[0], x[1], x[2], e as f64]
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
            [f64::NAN; 4]
        });
    }
    out
}

/// The interface peaks of displacements `u` at pseudo-time `time`:
/// `PER_INTERFACE` values per interface (`arcs`: each pair's arc length,
/// [`crate::model::interface::arcs::arc_lengths`]). An interface without
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
