//! Which of a run's peaks and first yield lie at a singular point of the
//! mesh ([`crate::model::singular`]), and the share of the error estimate
//! in the elements at that point.
//!
//! **Rule.** A place in body b is at a singular point p when p belongs to b
//! and their distance is at most one local element size: the larger of
//! p's size (the largest diameter of the elements at p) and the diameter of
//! the element holding the place. A Gauss point of an element touching p
//! is always within it. Of several such points the nearest is taken.
//!
//! **Share.** Σ η_e² over the elements at p divided by η² = Σ η_e² over the
//! mesh ([`crate::measure::estimate`]): how much of the estimated error
//! (squared energy norm, the interface's jump term included) sits at the
//! corner. None without an estimate.

use crate::measure::estimate::Estimate;
use crate::model::singular::{diameter, SingularPoint};
use crate::model::Model;

/// A place the run reports: what (`first_yield`, `max_von_mises`,
/// `max_peeq`), in which body, where, and the element holding it.
#[derive(Clone, Debug, PartialEq)]
pub struct Place {
    pub what: &'static str,
    pub body: usize,
    pub x: [f64; 3],
    pub element: Option<usize>,
}

/// A place found at a singular point.
#[derive(Clone, Debug, PartialEq)]
pub struct Flag {
    pub place: Place,
    /// The point's index in [`Model::singular`].
    pub point: usize,
    /// Its share of the error estimate (module text).
    pub share: Option<f64>,
}

impl Flag {
    /// The singular point.
    pub fn at<'a>(&self, model: &'a Model) -> &'a SingularPoint {
        &model.singular[self.point]
    }
}

/// The singular point of `model` nearest to `place` within one local
/// element size of it (module text), if any.
pub fn point_at(model: &Model, place: &Place) -> Option<usize> {
    if place.x.iter().take(2).any(|v| !v.is_finite()) {
        return None;
    }
    let own = place
        .element
        .filter(|&e| e < model.mesh.elements.len() && model.mesh.dim() == 2)
        .map_or(0.0, |e| diameter(&model.mesh, e));
    model
        .singular
        .iter()
        .enumerate()
        .filter(|(_, p)| p.bodies.contains(&place.body))
        .map(|(k, p)| (k, (p.x[0] - place.x[0]).hypot(p.x[1] - place.x[1]), p.size))
        .filter(|&(_, d, size)| d <= size.max(own))
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        .map(|(k, _, _)| k)
}

/// The share of η² in the elements at `p` (none without an estimate, or
/// with η = 0).
pub fn share(p: &SingularPoint, estimate: Option<&Estimate>) -> Option<f64> {
    let est = estimate?;
    let total: f64 = est.element.iter().sum();
    if total <= 0.0 || !total.is_finite() {
        return None;
    }
    let at: f64 = p.elements.iter().filter_map(|&e| est.element.get(e)).sum();
    Some(at / total)
}

/// The places found at a singular point, in the order given.
pub fn flag(model: &Model, places: &[Place], estimate: Option<&Estimate>) -> Vec<Flag> {
    places
        .iter()
        .filter_map(|place| {
            let point = point_at(model, place)?;
            Some(Flag {
                place: place.clone(),
                point,
                share: share(&model.singular[point], estimate),
            })
        })
        .collect()
}
