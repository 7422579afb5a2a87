//! Location of first yield inside the increment where plastic flow first appears.
//!
//! Below first yield the response is elastic (with the nonlinear interface), so
//! g(λ) = max over Gauss points of σ_eq/σ_Y − 1, computed from elastic solves
//! from the last elastic state, is a smooth function whose root is the first-
//! yield load. It is found by the Illinois variant of regula falsi to 1e-9 in g.

use super::{yield_ratio, Engine, State, StepFailure};

use crate::model::Model;
use crate::physics::element::solid::Response;

/// Regula-falsi steps of the search after its first solve: at most
/// `1 + SEARCH_STEPS` elastic solves locate first yield (a restart file's
/// counters are bounded by it, [`crate::files::restart`]).
pub(crate) const SEARCH_STEPS: usize = 60;

/// Where and at what load the first Gauss point reaches the yield stress.
#[derive(Clone, Debug)]
pub struct FirstYield {
    pub load_factor: f64,
    pub mean_pressure: f64,
    pub total_load_kn: f64,
    pub x: f64,
    /// Depth below the probe node (the foundation surface), mm.
    pub depth: f64,
    /// z of the point, mm (0 in a plane model).
    pub z: f64,
    pub body: String,
    pub element: usize,
}

/// What the search found besides [`FirstYield`]: the last load factors
/// evaluated below and at or above yield (the bracket), whether the root
/// was found to 1e-9 in g, and the solution at the load factor reported.
pub(super) struct Located {
    pub first_yield: FirstYield,
    pub bracket: [f64; 2],
    pub root: bool,
    pub state: State,
}

/// Relative width of a tie in the yield ratio: the Gauss points whose ratio
/// is within it of the largest are tied, and the lowest (element, point)
/// among them is the one named. Mirror-image points of a symmetric model
/// (the bolted joint's bolt) reach the same ratio up to round-off, which
/// would otherwise pick either one from run to run as the iterates change
/// in their last digits.
pub const RATIO_TIE: f64 = 1e-12;

/// Max yield ratio over the Gauss points of the `held` elements (whose points
/// `state.gauss` holds, in this order) and the (element, point) where it
/// occurs, the lowest within [`RATIO_TIE`] of it; [`Engine::max_yield_ratio`]
/// takes it over every rank.
pub fn max_yield_ratio(model: &Model, state: &State, held: &[u32]) -> (f64, usize, usize) {
    let best = ratios(model, state, held).fold(0.0, |a: f64, (r, _, _)| a.max(r));
    let (e, ip) = lowest_tied(model, state, held, best).unwrap_or((0, 0));
    (best, e, ip)
}

/// The lowest (element, point) of the `held` elements whose yield ratio is
/// within [`RATIO_TIE`] of `best` (none where `best` is not positive or no
/// point reaches it).
pub(crate) fn lowest_tied(
    model: &Model,
    state: &State,
    held: &[u32],
    best: f64,
) -> Option<(usize, usize)> {
    let floor = best * (1.0 - RATIO_TIE);
    (best > 0.0)
        .then(|| ratios(model, state, held).find(|&(r, _, _)| r >= floor))
        .flatten()
        .map(|(_, e, ip)| (e, ip))
}

/// The yield ratio of every held Gauss point with its (element, point), in
/// element order.
fn ratios<'a>(
    model: &'a Model,
    state: &'a State,
    held: &'a [u32],
) -> impl Iterator<Item = (f64, usize, usize)> + 'a {
    model.held_points(held).flat_map(move |(e, local)| {
        let mats = model.element_materials(e, state.time);
        let states = state.gauss.range(local);
        (0..states.len()).map(move |ip| (yield_ratio(mats.at(ip), &states.get(ip)), e, ip))
    })
}

/// First yield between the last elastic state `last_elastic` (at `lambda0`,
/// its yield ratio `ratio0`) and `lambda1`, where the step's solution has
/// yielded. `before`: the elastic solution (load factor, displacements)
/// before `last_elastic`, when the run has one; with it the first solve, at
/// `lambda1`, starts from the two's linear extrapolation (the step's own
/// predictor, [`super::predict`]) instead of from `last_elastic`.
pub(super) fn locate(
    engine: &mut Engine,
    last_elastic: &State,
    (lambda0, ratio0): (f64, f64),
    lambda1: f64,
    before: Option<(f64, Vec<f64>)>,
) -> std::result::Result<Located, (f64, StepFailure)> {
    let model = engine.model;
    // the two latest solutions (load factor, displacements): each solve
    // starts from their linear inter- or extrapolation to its load factor
    let mut known: Vec<(f64, Vec<f64>)> = before.into_iter().collect();
    known.push((lambda0, last_elastic.u.clone()));
    let mut eval = |l: f64| -> std::result::Result<(f64, State), (f64, StepFailure)> {
        let start = match known.as_slice() {
            [.., (l0, u0), (l1, u1)] if (l1 - l0).abs() > 0.0 => {
                let t = (l - l1) / (l1 - l0);
                Some(
                    u1.iter()
                        .zip(u0)
                        .map(|(b, a)| b + t * (b - a))
                        .collect::<Vec<f64>>(),
                )
            }
            _ => None,
        };
        let (s, _) = engine
            .step_from(last_elastic, l, Response::ElasticOnly, start.as_deref())
            .map_err(|f| (l, f))?;
        if known.len() == 2 {
            known.remove(0);
        }
        known.push((l, s.u.clone()));
        Ok((engine.max_yield_ratio(&s).0 - 1.0, s))
    };
    let (mut a, mut ga) = (lambda0, ratio0 - 1.0);
    let (mut b, (mut gb, mut sb)) = (lambda1, eval(lambda1)?);
    // the tightest bracket seen: below yield (g < 0), at or above it
    let mut bracket = [lambda0, lambda1];
    let mut root = false;
    for _ in 0..SEARCH_STEPS {
        if gb.abs() < 1e-9 || (b - a).abs() < 1e-12 {
            root = true;
            break;
        }
        let c = b - gb * (b - a) / (gb - ga);
        let (gc, sc) = eval(c)?;
        bracket[usize::from(gc >= 0.0)] = c;
        if gc * gb < 0.0 {
            (a, ga) = (b, gb);
        } else {
            ga *= 0.5; // Illinois: keep the retained end from stalling
        }
        (b, gb, sb) = (c, gc, sc);
    }
    let (_, e, ip) = engine.max_yield_ratio(&sb);
    let m = engine.measures(&sb);
    let x = model.point_x(e, ip);
    let first_yield = FirstYield {
        load_factor: b,
        mean_pressure: m.mean_pressure,
        total_load_kn: m.total_load_kn,
        x: x[0],
        depth: model.surface_y - x[1],
        z: x[2],
        body: model.mesh.bodies[model.mesh.elements[e].body].clone(),
        element: e,
    };
    Ok(Located {
        first_yield,
        bracket,
        root: root || gb.abs() < 1e-9,
        state: sb,
    })
}
