//! The finite-element stress σ_h of an element at the points of either of
//! its family's Gauss rules: what the solver stored at the model's own
//! points, and at the points of the other rule the elastic law applied to the
//! strain of u_h with the plastic strain interpolated from the stored points,
//! ```text
//!   σ_h(ξ) = D (ε(u_h)(ξ) − εᵖ(ξ)),   εᵖ(ξ) = Σ_k w_k(ξ) εᵖ_k
//! ```
//! (w_k the weights of the polynomial through the stored points,
//! [`crate::physics::element::family::Family::interpolation_weights`]:
//! bilinear from 2×2, biquadratic from 3×3, linear from the triangle's 3
//! points, quadratic from its 6; in a solid εᵖ is read at the nodes from
//! the stored points, [`crate::physics::element::family3::Family3::extrapolation`],
//! and interpolated with the shape functions). In an element that never yielded εᵖ = 0
//! and σ_h is exact at any point; the stored stress of a converged state is
//! D (ε − εᵖ) as well, so both rules see one field.
//!
//! The recovery samples σ_h at the reduced rule's points (the
//! superconvergent points: 2×2 of the 8-node quadrilateral, Zienkiewicz &
//! Zhu 1992 part 1; the 3 midpoints-of-medians points of the 6-node
//! triangle; the 2×2×2 points of the 20-node hexahedron and the 4-point
//! rule's of the 10-node tetrahedron) and the error integrals use the full
//! rule's points, where σ_h
//! is not superconvergent (an integral at the sampling points would hide the
//! error it measures).

use crate::model::Model;
use crate::physics::element::family::GaussRule;
use crate::physics::element::gauss3::GaussRule3;
use crate::physics::element::solid::{
    elastic_state_thermal, less_thermal, ElementGeometry, MAX_POINTS,
};
use crate::physics::element::solid3::ElementGeometry3;
use crate::physics::material::{GaussStates, Plane, PointState};

/// σ_h ([`PointState::stress`] order: xx, yy, xy, zz or θθ, rθ, zθ) of
/// element `e` at the points of `rule`, whose geometry is `geom`; `gauss`
/// holds every element's states at the model's rule; `time` the state's
/// pseudo-time, at which the body's free thermal strain α ΔT is taken off
/// the normal strains and its material read ([`Model::material_point`]).
pub fn stresses(
    model: &Model,
    gauss: &GaussStates,
    u: &[f64],
    e: usize,
    rule: &GaussRule,
    geom: &ElementGeometry,
    time: f64,
) -> [[f64; 6]; MAX_POINTS] {
    let stored = gauss.range(model.points(e));
    let own = model.rule(e);
    let mut out = [[0.0; 6]; MAX_POINTS];
    if rule == own {
        for (o, g) in out.iter_mut().zip(stored) {
            *o = g.stress;
        }
        return out;
    }
    let el = &model.mesh.elements[e];
    let xs: Vec<[f64; 3]> = (0..geom.n)
        .map(|ip| [geom.x[ip][0], geom.x[ip][1], 0.0])
        .collect();
    let mats = model.point_materials(el.body, time, &xs);
    let ue = model.element_u(e, u);
    let twist = model.node_dofs().twist();
    for (ip, &(xi, _)) in rule.points.iter().enumerate() {
        let w = el.family.interpolation_weights(own, xi);
        let mut committed = PointState::default();
        for (k, g) in stored.iter().enumerate() {
            for (c, v) in committed.plastic_strain.iter_mut().enumerate() {
                *v += w[k] * g.plastic_strain[c];
            }
        }
        let thermal = model.thermal_at(el.body, time, xs[ip]);
        let mat = mats.at(ip);
        let s = if twist {
            let eps = crate::physics::element::axisymmetric_twist::strain(geom, ip, &ue);
            mat.elastic_state_twist(&committed, &less_thermal(eps, thermal))
        } else if model.plane == Plane::Axisymmetric {
            let eps = less_thermal(geom.strain_axisymmetric(ip, &ue), thermal);
            mat.elastic_state_axisymmetric(&committed, &eps)
        } else {
            elastic_state_thermal(mat, &committed, &geom.strain(ip, &ue), thermal)
        };
        out[ip] = s.stress;
    }
    out
}

/// σ_h of solid element `e` at the points of `rule` (the module text),
/// whose geometry is `geom`: the stored stress at the model's own rule, else
/// the elastic law from the strain of u_h and the plastic strain read at the
/// nodes from the stored points (by `w`, the element family's
/// [`crate::physics::element::family3::Family3::extrapolation`] of the
/// model's rule, made once per family by the caller) and interpolated.
#[allow(clippy::too_many_arguments)]
pub(crate) fn stresses3(
    model: &Model,
    gauss: &GaussStates,
    u: &[f64],
    e: usize,
    rule: &GaussRule3,
    geom: &ElementGeometry3,
    w: &[[f64; crate::physics::element::family3::MAX_NODES3]],
    time: f64,
) -> Vec<[f64; 6]> {
    let stored = gauss.range(model.points(e));
    let el = &model.mesh.elements[e];
    let solid = el.family.solid().expect("a solid element");
    let own = model.rule3(solid);
    if rule == own {
        return stored.iter().map(|g| g.stress).collect();
    }
    let mats = model.point_materials(el.body, time, &geom.x[..geom.n]);
    let ue = model.element_u(e, u);
    // εᵖ at the nodes: Σ_k W_ka εᵖ_k
    let mut nodal = vec![[0.0; 6]; geom.nodes];
    for (k, g) in stored.iter().enumerate() {
        for (a, n) in nodal.iter_mut().enumerate() {
            for (c, v) in n.iter_mut().enumerate() {
                *v += w[k][a] * g.plastic_strain[c];
            }
        }
    }
    (0..geom.n)
        .map(|ip| {
            let mut committed = PointState::default();
            for (a, n) in nodal.iter().enumerate() {
                for (c, v) in committed.plastic_strain.iter_mut().enumerate() {
                    *v += geom.shape[ip][a] * n[c];
                }
            }
            let thermal = model.thermal_at(el.body, time, geom.x[ip]);
            let eps = less_thermal(geom.strain(ip, &ue), thermal);
            mats.at(ip).elastic_state_twist(&committed, &eps).stress
        })
        .collect()
}
