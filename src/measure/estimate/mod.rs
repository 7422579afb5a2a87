//! A posteriori error estimate: the Zienkiewicz–Zhu estimator with
//! superconvergent patch recovery (Zienkiewicz & Zhu 1992, IJNME 33,
//! part 1: the recovery; part 2: the estimate and its effectivity), plus
//! the interface's traction jump, and Dörfler's bulk marking.
//!
//! ```text
//!   η_e² = ∫_e (σ* − σ_h)ᵀ C⁻¹ (σ* − σ_h) dΩ  (+ η²_I,e, [`jump`])     (part 2)
//!   ‖u_h‖²_E = ∫_Ω σ_hᵀ C⁻¹ σ_h dΩ,     η² = Σ_e η_e²,   relative η / ‖u_h‖_E
//!   effectivity θ = η / ‖u − u_h‖_E   (→ 1 on smooth problems, part 2)
//! ```
//! σ* is the stress recovered by SPR ([`recovery`]) and interpolated with
//! the Q8 shape functions, σ_h the element's own (`sample`); both are
//! integrated by 3×3 Gauss with the model's volume element (thickness, or
//! 2π r in axisymmetry). C⁻¹ is the isotropic 3D compliance on all six
//! components (xx, yy, xy, zz or θθ, rθ, zθ),
//! ```text
//!   sᵀC⁻¹s = [s_xx² + s_yy² + s_zz² − 2ν (s_xx s_yy + s_yy s_zz + s_zz s_xx)] / E
//!            + (s_xy² + s_rθ² + s_zθ²) / G
//! ```
//! which is the plane-strain energy with σ_zz = ν(σ_xx + σ_yy) (ε_zz = 0
//! adds nothing), the plane-stress one with σ_zz = 0, the axisymmetric one
//! with the hoop stress, and the twist one with both shears. Plastic
//! elements use the elastic compliance too (as usual for ZZ applied to
//! plasticity, a known limitation: there it measures the stress jumps, not
//! the error in the plastic energy).

mod jump;
pub mod recovery;
mod sample;

use crate::model::state::State;
use crate::model::Model;
use crate::physics::element::family::{Family, GaussRule};
use crate::physics::element::family3::MAX_NODES3;
use crate::physics::element::solid::ElementGeometry;
use crate::physics::element::solid3::ElementGeometry3;
use crate::physics::material::VonMises;
use serde_json::json;

/// The estimate of one state.
#[derive(Clone, Debug, Default)]
pub struct Estimate {
    /// η_e² per element (N·mm): the recovery part plus the interface part.
    pub element: Vec<f64>,
    /// The interface's part of η_e² per element (N·mm; 0 off interfaces).
    pub interface: Vec<f64>,
    /// η = √Σ η_e² (√(N·mm)).
    pub total: f64,
    /// ‖u_h‖_E = √∫ σ_hᵀ C⁻¹ σ_h dΩ (√(N·mm)).
    pub norm: f64,
}

impl Estimate {
    /// η / ‖u_h‖_E (0 for an unstressed body).
    pub fn relative(&self) -> f64 {
        if self.norm > 0.0 {
            self.total / self.norm
        } else {
            0.0
        }
    }

    /// Each element's share of η², η_e² / η² (0 everywhere when η = 0).
    pub(crate) fn shares(&self) -> Vec<f64> {
        let t2 = self.total * self.total;
        self.element
            .iter()
            .map(|&e| if t2 > 0.0 { e / t2 } else { 0.0 })
            .collect()
    }

    /// summary.json's `estimate`: η and η/‖u_h‖_E, the interface's part, how
    /// many elements hold half of η² ([`doerfler_mark`] at θ = 0.5) and the
    /// five largest η_e² with their body and centroid.
    pub fn summary(&self, model: &Model) -> serde_json::Value {
        let mut order: Vec<usize> = (0..self.element.len()).collect();
        order.sort_by(|&a, &b| self.element[b].total_cmp(&self.element[a]).then(a.cmp(&b)));
        let t2 = self.total * self.total;
        let top: Vec<serde_json::Value> = order
            .iter()
            .take(5)
            .map(|&e| {
                let el = &model.mesh.elements[e];
                let c = centroid(model, e);
                let mut v = json!({
                    "element": e,
                    "body": model.mesh.bodies.get(el.body).cloned().unwrap_or_default(),
                    "x_mm": c[0],
                    "y_mm": c[1],
                    "eta_sq_nmm": self.element[e],
                    "share": if t2 > 0.0 { self.element[e] / t2 } else { 0.0 },
                });
                if model.mesh.dim() == 3 {
                    v["z_mm"] = json!(c[2]);
                }
                v
            })
            .collect();
        json!({
            "method": "zienkiewicz-zhu-spr",
            "eta": self.total,
            "energy_norm": self.norm,
            "relative": self.relative(),
            "interface_share": if t2 > 0.0 { self.interface.iter().sum::<f64>() / t2 } else { 0.0 },
            "elements_holding_half": doerfler_mark(&self.element, 0.5).len(),
            "top": top,
        })
    }
}

/// The estimate of a state whose Gauss states are every element's (the
/// whole state: serial, or what rank 0's writer sees under MPI).
pub fn estimate(model: &Model, state: &State) -> Estimate {
    let mesh = &model.mesh;
    let ne = mesh.elements.len();
    let own = own_weights(model);
    let of = |e: usize, full: bool| Points::of(model, state, e, full, &own);
    // σ_h at the sampling points of every element: what is recovered
    let mut samples = vec![recovery::Samples::default(); ne];
    for (e, s) in samples.iter_mut().enumerate() {
        let p = of(e, false);
        s.n = p.dv.len();
        s.points[..s.n].copy_from_slice(&p.x);
        s.values[..s.n].copy_from_slice(&p.stress);
    }
    let recovered = recovery::recover(mesh, &samples);
    let mut element = vec![0.0; ne];
    let mut norm2 = 0.0;
    for (e, el) in mesh.elements.iter().enumerate() {
        let p = of(e, true);
        let mats = model.point_materials(el.body, state.time, &p.x);
        let star = recovered.element(e);
        for (ip, sh) in p.stress.iter().enumerate() {
            let d: [f64; 6] = std::array::from_fn(|c| {
                let at: f64 = star.iter().zip(&p.shape[ip]).map(|(s, n)| n * s[c]).sum();
                at - sh[c]
            });
            element[e] += p.dv[ip] * compliance(mats.at(ip), &d);
            norm2 += p.dv[ip] * compliance(mats.at(ip), sh);
        }
    }
    let mut interface = vec![0.0; ne];
    jump::add(model, state, &recovered, &mut interface);
    for (e, i) in element.iter_mut().zip(&interface) {
        *e += i;
    }
    let total = element.iter().sum::<f64>().sqrt();
    Estimate {
        element,
        interface,
        total,
        norm: norm2.sqrt(),
    }
}

/// Each solid family's extrapolation of the model's rule ([`Family::SOLID`]
/// order), made once per estimate.
fn own_weights(model: &Model) -> [Vec<[f64; MAX_NODES3]>; 2] {
    Family::SOLID.map(|f| {
        let solid = f.solid().expect("a solid family");
        solid.extrapolation(model.rule3(solid))
    })
}

/// What the estimate asks of an element at the points of one of its rules,
/// plane or solid: their places (z = 0 in a plane model), volumes, shape
/// functions and σ_h ([`sample`]).
struct Points {
    x: Vec<[f64; 3]>,
    dv: Vec<f64>,
    shape: Vec<Vec<f64>>,
    stress: Vec<[f64; 6]>,
}

impl Points {
    /// Element e's points of its full rule (`full`) or its sampling rule:
    /// 2×2 of the 8-node quadrilateral, the 6-node triangle's 3 points, 2×2×2
    /// of the 20-node hexahedron, the 10-node tetrahedron's 4 points.
    /// `own`: each solid family's extrapolation of the model's rule
    /// ([`Family::SOLID`] order).
    fn of(
        model: &Model,
        state: &State,
        e: usize,
        full: bool,
        own: &[Vec<[f64; MAX_NODES3]>],
    ) -> Points {
        let family = model.mesh.elements[e].family;
        let (gauss, u) = (&state.gauss, &state.u[..]);
        if let Some(solid) = family.solid() {
            let rule = solid.rule(full);
            let coords = model.mesh.element_coords3(e);
            let g = ElementGeometry3::new(solid, &coords[..family.nodes()], &rule)
                .expect("element geometry was checked when the model was built");
            return Points {
                x: g.x[..g.n].to_vec(),
                dv: g.dv[..g.n].to_vec(),
                shape: (0..g.n).map(|ip| g.shape[ip][..g.nodes].to_vec()).collect(),
                stress: {
                    let k = Family::SOLID.iter().position(|&f| f == family).unwrap_or(0);
                    sample::stresses3(model, gauss, u, e, &rule, &g, &own[k], state.time)
                },
            };
        }
        let rule = if full {
            family.rule(true)
        } else {
            family.sampling_rule()
        };
        let g = geometry(model, e, &rule);
        let s = sample::stresses(model, gauss, u, e, &rule, &g, state.time);
        Points {
            x: (0..g.n).map(|ip| [g.x[ip][0], g.x[ip][1], 0.0]).collect(),
            dv: g.dv[..g.n].to_vec(),
            shape: (0..g.n).map(|ip| g.shape[ip][..g.nodes].to_vec()).collect(),
            stress: s[..g.n].to_vec(),
        }
    }
}

/// sᵀ C⁻¹ s with the isotropic 3D compliance (module text), MPa.
pub fn compliance(mat: &VonMises, s: &[f64; 6]) -> f64 {
    let (e, nu, g) = (mat.young, mat.poisson, mat.shear_modulus());
    (s[0] * s[0] + s[1] * s[1] + s[3] * s[3] - 2.0 * nu * (s[0] * s[1] + s[1] * s[3] + s[3] * s[0]))
        / e
        + (s[2] * s[2] + s[4] * s[4] + s[5] * s[5]) / g
}

/// Dörfler's bulk marking (Dörfler 1996, "A convergent adaptive algorithm
/// for Poisson's equation", SIAM J. Numer. Anal. 33, 1106–1124; θ the bulk
/// fraction): the smallest set M of elements with
/// Σ_{e∈M} η_e² ≥ θ Σ_e η_e², taken largest first (ties by index); sorted
/// by index. θ ≤ 0 or a zero estimate marks nothing; θ ≥ 1 marks every
/// element with η_e² > 0.
pub fn doerfler_mark(eta_sq: &[f64], theta: f64) -> Vec<usize> {
    let total: f64 = eta_sq.iter().sum();
    if theta <= 0.0 || total <= 0.0 {
        return Vec::new();
    }
    let mut order: Vec<usize> = (0..eta_sq.len()).filter(|&e| eta_sq[e] > 0.0).collect();
    order.sort_by(|&a, &b| eta_sq[b].total_cmp(&eta_sq[a]).then(a.cmp(&b)));
    let goal = theta.min(1.0) * total;
    let mut held = 0.0;
    let mut marked = Vec::new();
    for e in order {
        if held >= goal {
            break;
        }
        held += eta_sq[e];
        marked.push(e);
    }
    marked.sort_unstable();
    marked
}

/// The geometry of element e at `rule` (checked valid when the model was built).
fn geometry(model: &Model, e: usize, rule: &GaussRule) -> ElementGeometry {
    let family = model.mesh.elements[e].family;
    let coords = model.mesh.element_coords(e);
    ElementGeometry::with_section(family, &coords, rule, &model.section)
        .expect("element geometry was checked when the model was built")
}

/// The mean of an element's node coordinates (mm; z = 0 in a plane model).
fn centroid(model: &Model, e: usize) -> [f64; 3] {
    let nodes = model.mesh.elements[e].nodes();
    let k = nodes.len() as f64;
    let mut c = [0.0; 3];
    for &n in nodes {
        for (ci, x) in c.iter_mut().zip(model.mesh.nodes[n]) {
            *ci += x / k;
        }
    }
    c
}

#[cfg(test)]
mod tests;
