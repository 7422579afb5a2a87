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

use crate::linalg::backend::Comm;
use crate::measure::estimate::Estimate;
use crate::model::excluded::Excluded;
use crate::model::singular::{diameter, SingularPoint};
use crate::model::Model;
use crate::physics::material::{GaussStates, VonMises};

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

/// The largest von Mises stress over the Gauss points of the elements
/// `held` (their states `gauss`, in that order) that `excluded` leaves in,
/// over every rank (collective under MPI: one max reduction); NaN when it
/// leaves none in. `[adapt] quantity = "max_von_mises"` at one increment.
pub fn von_mises_away(
    model: &Model,
    comm: &dyn Comm,
    held: &[u32],
    gauss: &GaussStates,
    excluded: &Excluded,
) -> f64 {
    let mut top = [f64::NEG_INFINITY];
    for (e, local) in model.held_points(held) {
        let first = model.points(e).start;
        for (ip, g) in gauss.range(local).iter().enumerate() {
            if !excluded.points[first + ip] {
                top[0] = top[0].max(VonMises::equivalent_stress(&g.stress));
            }
        }
    }
    comm.max(&mut top);
    if top[0] == f64::NEG_INFINITY {
        f64::NAN
    } else {
        top[0]
    }
}

#[cfg(test)]
mod tests {
    use super::{flag, point_at, share, von_mises_away, Place};
    use crate::measure::estimate::Estimate;
    use crate::model::Model;

    /// An L of three unit squares (body "l", plane strain) on rollers along
    /// its whole bottom and left side, and
    /// a square beside it (body "block"), apart.
    fn l_model() -> Model {
        l_model_with("")
    }

    /// [`l_model`] with `mesh` (keys of `[mesh]`) before its blocks.
    fn l_model_with(mesh: &str) -> Model {
        let text = format!(
            r#"
[model]
plane = "strain"

[mesh]
{mesh}

[[mesh.block]]
name = "foot"
body = "l"
x = [0.0, 1.0, 2.0]
nx = [1, 1]
y = [0.0, 1.0]
ny = [1]

[[mesh.block]]
name = "arm"
body = "l"
x = [0.0, 1.0]
nx = [1]
y = [1.0, 2.0]
ny = [1]

[[mesh.block]]
body = "block"
x = [5.0, 6.0]
nx = [1]
y = [0.0, 1.0]
ny = [1]

[materials.l]
young = 206000.0
poisson = 0.3

[materials.block]
young = 206000.0
poisson = 0.3

[[boundary]]
set = "foot.bottom"
uy = 0.0

[[boundary]]
set = "foot.left"
ux = 0.0

[[boundary]]
set = "arm.left"
ux = 0.0

[[boundary]]
set = "block.bottom"
uy = 0.0

[[boundary]]
set = "block.left"
ux = 0.0

[[load]]
edges = "arm.top"
pressure = 10.0

[[load]]
edges = "block.top"
pressure = 10.0
"#
        );
        Model::parse(&text, "l.toml").unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn a_place_is_flagged_within_one_element_of_its_bodys_corner() {
        let model = l_model();
        assert_eq!(model.singular.len(), 1, "{:?}", model.singular);
        let corner = &model.singular[0];
        assert_eq!(corner.x, [1.0, 1.0, 0.0]);
        let l = model.mesh.bodies.iter().position(|b| b == "l").unwrap();
        let block = 1 - l;
        let place = |body, x: f64, y: f64, element| Place {
            what: "max_von_mises",
            body,
            x: [x, y, 0.0],
            element,
        };
        // a Gauss point of an element at the corner
        assert_eq!(point_at(&model, &place(l, 1.11, 1.11, Some(0))), Some(0));
        // one diagonal (√2) away: still within; beyond it: not
        assert_eq!(point_at(&model, &place(l, 1.0, 2.4, None)), Some(0));
        assert_eq!(point_at(&model, &place(l, 1.0, 2.5, None)), None);
        // the same place in another body: not its corner
        assert_eq!(point_at(&model, &place(block, 1.11, 1.11, None)), None);
    }

    #[test]
    fn the_share_is_the_corners_elements_part_of_the_estimate() {
        let model = l_model();
        let corner = &model.singular[0];
        // the three squares of the L touch the corner, the block does not
        assert_eq!(corner.elements.len(), 3);
        let n = model.mesh.elements.len();
        let mut element = vec![0.0; n];
        for (e, v) in element.iter_mut().enumerate() {
            *v = (e + 1) as f64;
        }
        let total: f64 = element.iter().sum();
        let at: f64 = corner.elements.iter().map(|&e| element[e]).sum();
        let est = Estimate {
            element,
            interface: vec![0.0; n],
            total: total.sqrt(),
            norm: 1.0,
        };
        let s = share(corner, Some(&est)).unwrap();
        assert!((s - at / total).abs() < 1e-15, "{s}");
        assert!(s < 1.0);
        assert_eq!(share(corner, None), None);
        let l = model.mesh.bodies.iter().position(|b| b == "l").unwrap();
        let p = Place {
            what: "first_yield",
            body: l,
            x: corner.x,
            element: None,
        };
        let flags = flag(&model, std::slice::from_ref(&p), Some(&est));
        assert_eq!(flags.len(), 1);
        assert_eq!((flags[0].point, flags[0].share), (0, Some(s)));
        assert_eq!(flags[0].place, p);
    }

    /// One process: every reduction is the identity.
    struct One;
    impl crate::linalg::backend::Comm for One {}

    /// The L with its unit squares split in four (elements of 0.5 mm): the
    /// re-entrant corner's disc (radius the diagonal of an element at it,
    /// √0.5) holds the Gauss points of the L within it, those of the four
    /// elements at the corner and some of their neighbours', exactly the
    /// points [`point_at`] flags at the corner (on a uniform mesh the
    /// element's own diameter is the corner's size), and none of the block.
    #[test]
    fn the_excluded_points_are_those_flagged_at_the_corner() {
        use crate::model::excluded::{Disc, Excluded};
        let model = l_model_with("refine = 2");
        assert_eq!(model.singular.len(), 1, "{:?}", model.singular);
        let corner = &model.singular[0];
        assert!(
            (corner.size - 0.5f64.hypot(0.5)).abs() < 1e-12,
            "{}",
            corner.size
        );
        let x = Excluded::on(&model, vec![Disc::about(corner)]);
        assert_eq!(x.points.len(), model.n_points());
        let l = model.mesh.bodies.iter().position(|b| b == "l").unwrap();
        let (mut at_corner, mut beyond) = (0, 0);
        for e in 0..model.mesh.elements.len() {
            let body = model.mesh.elements[e].body;
            for (ip, i) in model.points(e).enumerate() {
                let place = Place {
                    what: "max_von_mises",
                    body,
                    x: model.point_x(e, ip),
                    element: Some(e),
                };
                assert_eq!(
                    x.points[i],
                    point_at(&model, &place) == Some(0),
                    "{place:?}"
                );
                if corner.elements.contains(&e) {
                    // every Gauss point of an element at the corner
                    assert!(x.points[i], "{place:?}");
                    at_corner += 1;
                } else if x.points[i] {
                    assert_eq!(body, l);
                    beyond += 1;
                }
            }
        }
        assert_eq!(corner.elements.len(), 3);
        assert_eq!(x.count(), at_corner + beyond);
        // the disc reaches past the corner's elements into their neighbours
        assert!(beyond > 0 && at_corner > 0, "{at_corner} {beyond}");
    }

    /// The largest von Mises stress left in: each Gauss point given its own
    /// uniaxial stress (point i: i + 1 MPa), the largest of the points the
    /// discs leave in; the same from two halves of the elements (two ranks'
    /// shares); NaN when everything is left out; every point without discs.
    #[test]
    fn the_stress_away_is_the_largest_of_the_points_left_in() {
        use crate::model::excluded::{Disc, Excluded};
        use crate::physics::material::{GaussStates, PointState, VonMises};
        let model = l_model_with("refine = 2");
        let n = model.n_points();
        let mut gauss = GaussStates::new(n, false);
        for i in 0..n {
            let mut s = PointState::default();
            s.stress[1] = (i + 1) as f64;
            gauss.set(i, &s);
        }
        let all: Vec<u32> = (0..model.mesh.elements.len() as u32).collect();
        let x = Excluded::on(&model, vec![Disc::about(&model.singular[0])]);
        let vm = |i: usize| VonMises::equivalent_stress(&gauss.get(i).stress);
        assert!((vm(n - 1) - n as f64).abs() < 1e-12 * n as f64);
        let want = (0..n)
            .filter(|&i| !x.points[i])
            .map(vm)
            .fold(f64::NAN, f64::max);
        assert!(x.count() > 0 && want.is_finite());
        assert_eq!(von_mises_away(&model, &One, &all, &gauss, &x), want);
        // two ranks: each its elements' states, the larger of the two
        let (a, b) = all.split_at(all.len() / 2);
        let part = |held: &[u32]| {
            let mut g = GaussStates::new(0, false);
            for &e in held {
                for i in model.points(e as usize) {
                    g.push(&gauss.get(i));
                }
            }
            von_mises_away(&model, &One, held, &g, &x)
        };
        assert_eq!(part(a).max(part(b)), want);
        let none = Excluded::on(&model, Vec::new());
        assert_eq!(none.count(), 0);
        assert_eq!(von_mises_away(&model, &One, &all, &gauss, &none), vm(n - 1));
        let every = Excluded {
            discs: Vec::new(),
            points: vec![true; n],
        };
        assert!(von_mises_away(&model, &One, &all, &gauss, &every).is_nan());
    }
}
