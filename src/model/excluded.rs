//! The Gauss points an adaptive run on the bodies' stress leaves out
//! (`[adapt] quantity = "max_von_mises"`, docs/case-schema.md "Adaptive
//! runs"): those within one element size of a singular point of the start
//! mesh ([`crate::model::singular`]), where the linear-elastic stress is
//! unbounded and its largest value grows with every refinement instead of
//! converging.
//!
//! **Rule.** Each singular point p of the case's own mesh (the first
//! adaptive cycle's) makes a disc: its centre p, its radius p's local
//! element size there (the largest diameter of the elements at p, the size
//! [`crate::measure::singular`] flags a peak within), its bodies p's. A
//! Gauss point of body b is excluded when it lies in a disc of b: its
//! distance to the centre at most the radius (every Gauss point of an
//! element at p is). The discs are kept for the whole run: every refined
//! mesh leaves out the same region, so the quantity is the largest stress
//! of one fixed part of the bodies, which converges as the mesh is refined
//! (a disc shrinking with the local size would follow the singularity in:
//! σ ~ r^(λ−1), the largest value outside r = h growing as h^(λ−1), by a
//! factor 2^(1−λ) per halving: 1.37 at a right-angled re-entrant corner,
//! λ = 0.544, Williams 1952).
//!
//! 3D models have no singular points (and no adaptive runs): nothing would
//! be excluded.

use crate::model::singular::SingularPoint;
use crate::model::Model;

/// A disc about a singular point of the start mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Disc {
    /// Its centre, mm (z = 0).
    pub x: [f64; 3],
    /// Its radius: the point's local element size on the start mesh, mm.
    pub radius: f64,
    /// The bodies it holds points of (the singular point's).
    pub bodies: Vec<usize>,
    /// What the point is, in words ([`SingularPoint::corner`]).
    pub corner: String,
}

impl Disc {
    /// The disc of a singular point (module text).
    pub fn about(p: &SingularPoint) -> Disc {
        Disc {
            x: p.x,
            radius: p.size,
            bodies: p.bodies.clone(),
            corner: p.corner.clone(),
        }
    }

    /// Whether a place `x` of body `body` lies in the disc.
    pub fn holds(&self, body: usize, x: [f64; 3]) -> bool {
        self.bodies.contains(&body) && (x[0] - self.x[0]).hypot(x[1] - self.x[1]) <= self.radius
    }
}

/// The discs of a model and the Gauss points they hold.
#[derive(Clone, Debug, PartialEq)]
pub struct Excluded {
    pub discs: Vec<Disc>,
    /// Per Gauss point, in [`Model::points`] order: whether a disc holds it.
    pub points: Vec<bool>,
}

impl Excluded {
    /// The Gauss points of `model` that `discs` hold (one pass over the
    /// elements when the model is built).
    pub fn on(model: &Model, discs: Vec<Disc>) -> Excluded {
        let mut points = vec![false; model.n_points()];
        if !discs.is_empty() {
            for e in 0..model.mesh.elements.len() {
                let body = model.mesh.elements[e].body;
                let geometry = model.element_geometry(e);
                for (ip, i) in model.points(e).enumerate() {
                    let x = geometry.x(ip);
                    points[i] = discs.iter().any(|d| d.holds(body, x));
                }
            }
        }
        Excluded { discs, points }
    }

    /// How many Gauss points are left out.
    pub fn count(&self) -> usize {
        self.points.iter().filter(|&&p| p).count()
    }
}
