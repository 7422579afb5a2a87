//! The finite-element stress σ_h of an element at the points of any 2×2 or
//! 3×3 Gauss rule: what the solver stored at the model's own points, and at
//! the points of the other rule the elastic law applied to the strain of
//! u_h with the plastic strain interpolated from the stored points,
//! ```text
//!   σ_h(ξ) = D (ε(u_h)(ξ) − εᵖ(ξ)),   εᵖ(ξ) = Σ_ij L_i(ξ) L_j(η) εᵖ_ij
//! ```
//! (L_i the Lagrange polynomials through the stored rule's 1D points:
//! bilinear from 2×2, biquadratic from 3×3). In an element that never
//! yielded εᵖ = 0 and σ_h is exact at any point; the stored stress of a
//! converged state is D (ε − εᵖ) as well, so both rules see one field.
//!
//! The recovery samples σ_h at the 2×2 points (the superconvergent points
//! of the 8-node quadrilateral, Zienkiewicz & Zhu 1992 part 1) and the
//! error integrals use the 3×3 points, where σ_h is not superconvergent
//! (an integral at the 2×2 points would hide the error it measures).

use crate::model::Model;
use crate::physics::element::q8::{gauss_1d, GaussRule};
use crate::physics::element::solid::{elastic_state, ElementGeometry, MAX_POINTS};
use crate::physics::material::{Plane, PointState};

/// σ_h ([`PointState::stress`] order: xx, yy, xy, zz or θθ, rθ, zθ) of
/// element `e` at the points of `rule`, whose geometry is `geom`; `gauss`
/// holds every element's states at the model's rule.
pub fn stresses(
    model: &Model,
    gauss: &[PointState],
    u: &[f64],
    e: usize,
    rule: &GaussRule,
    geom: &ElementGeometry,
) -> [[f64; 6]; MAX_POINTS] {
    let ng = model.n_gauss();
    let stored = &gauss[e * ng..(e + 1) * ng];
    let mut out = [[0.0; 6]; MAX_POINTS];
    if rule.points.len() == ng {
        // the model's own rule (2×2 and 3×3 differ in their point count)
        for (o, g) in out.iter_mut().zip(stored) {
            *o = g.stress;
        }
        return out;
    }
    let mat = &model.materials[model.mesh.elements[e].body];
    let ue = model.element_u(e, u);
    let twist = model.node_dofs().twist();
    let n = (ng as f64).sqrt().round() as usize;
    let g: Vec<f64> = gauss_1d(n).iter().map(|p| p.0).collect();
    for (ip, &([xi, eta], _)) in rule.points.iter().enumerate() {
        let lx = lagrange(&g, xi);
        let ly = lagrange(&g, eta);
        let mut committed = PointState::default();
        for j in 0..n {
            for i in 0..n {
                let w = lx[i] * ly[j];
                for (c, v) in committed.plastic_strain.iter_mut().enumerate() {
                    *v += w * stored[j * n + i].plastic_strain[c];
                }
            }
        }
        let s = if twist {
            let eps = crate::physics::element::axisymmetric_twist::strain(geom, ip, &ue);
            mat.elastic_state_twist(&committed, &eps)
        } else if model.plane == Plane::Axisymmetric {
            mat.elastic_state_axisymmetric(&committed, &geom.strain_axisymmetric(ip, &ue))
        } else {
            elastic_state(mat, &committed, &geom.strain(ip, &ue))
        };
        out[ip] = s.stress;
    }
    out
}

/// The Lagrange polynomials through the points `g` at x (at most 3 points).
fn lagrange(g: &[f64], x: f64) -> [f64; 3] {
    let mut l = [0.0; 3];
    for (i, li) in l.iter_mut().enumerate().take(g.len()) {
        *li = (0..g.len())
            .filter(|&k| k != i)
            .map(|k| (x - g[k]) / (g[i] - g[k]))
            .product();
    }
    l
}

#[cfg(test)]
mod tests {
    use super::lagrange;

    #[test]
    fn lagrange_polynomials_interpolate_a_quadratic_exactly() {
        let g = [-0.6f64.sqrt(), 0.0, 0.6f64.sqrt()];
        let f = |x: f64| 2.0 - 3.0 * x + 0.5 * x * x;
        for x in [-1.0, -0.3, 0.57735, 1.0] {
            let l = lagrange(&g, x);
            let v: f64 = (0..3).map(|i| l[i] * f(g[i])).sum();
            assert!((v - f(x)).abs() < 1e-14, "{v} vs {}", f(x));
        }
    }
}
