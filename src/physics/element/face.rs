//! The 8-node quadrilateral face of a 20-node hexahedron in space: the
//! consistent nodal forces of a pressure on it.
//!
//! ```text
//!   fₐ = −∫ p Nₐ n dA = −Σ_g p Nₐ(ξ_g) (∂x/∂ξ × ∂x/∂η)(ξ_g) w_g
//! ```
//! with the face's serendipity shape functions ([`super::q8`], ZTZ 7th ed.
//! sec. 6.2) and its nodes numbered as [`super::h20::FACES`]: corners
//! counter-clockwise seen from outside, so ∂x/∂ξ × ∂x/∂η is the outward
//! normal times the area element and a positive p pushes into the body
//! (Zienkiewicz, Taylor & Zhu, 7th ed., sec. 6.5 on boundary loads:
//! the surface integral of Nᵀ t).

#![allow(dead_code)] // reached by the 3D model's loads (issue 44), not yet wired

use super::family::{Family, MAX_NODES};

/// Nodal forces (N) of a uniform pressure `p` (MPa) on a face of the plane
/// `family` (the 8-node quadrilateral of a hexahedron, the 6-node triangle
/// of a tetrahedron) with node coordinates `x` (mm), by the family's full
/// Gauss rule (exact for a flat face with straight sides, and to the rule's
/// order on a curved one). The first `family.nodes()` entries are used.
pub(crate) fn pressure_forces(family: Family, x: &[[f64; 3]], p: f64) -> [[f64; 3]; MAX_NODES] {
    let nn = family.nodes();
    let mut f = [[0.0; 3]; MAX_NODES];
    for &(xi, w) in &family.rule(true).points {
        let (n, d) = (family.shape(xi), family.shape_derivs(xi));
        let mut t = [[0.0; 3]; 2];
        for a in 0..nn {
            for (k, tk) in t.iter_mut().enumerate() {
                for c in 0..3 {
                    tk[c] += d[a][k] * x[a][c];
                }
            }
        }
        let normal = crate::numbers::vec3::cross(t[0], t[1]);
        for a in 0..nn {
            for c in 0..3 {
                f[a][c] -= p * n[a] * normal[c] * w;
            }
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat rectangle a × b tilted in space: the forces sum to −p a b n,
    /// the corners take −1/12 and the midsides 1/3 of it (the serendipity
    /// face's consistent load), and their moment about the centre is zero.
    #[test]
    fn a_flat_face_takes_the_serendipity_shares_of_its_load() {
        let (a, b, p) = (3.0, 2.0, 5.0);
        // the face's own axes: u along ξ, v along η, n = u × v
        let s = 0.6f64;
        let (u, v) = (
            [s.cos(), s.sin(), 0.0],
            [-s.sin() * 0.8, s.cos() * 0.8, 0.6],
        );
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let origin = [1.0, -2.0, 0.5];
        let x: [[f64; 3]; 8] = std::array::from_fn(|k| {
            let [xi, eta] = crate::physics::element::q8::NODE_XI[k];
            std::array::from_fn(|c| origin[c] + 0.5 * a * xi * u[c] + 0.5 * b * eta * v[c])
        });
        let f = pressure_forces(Family::Q8, &x, p);
        let total = p * a * b;
        for (k, fk) in f.iter().enumerate().take(8) {
            let share = if k < 4 { -1.0 / 12.0 } else { 1.0 / 3.0 };
            for c in 0..3 {
                let want = -share * total * n[c];
                assert!((fk[c] - want).abs() < 1e-12 * total, "node {k}: {fk:?}");
            }
        }
        let mut moment = [0.0; 3];
        for k in 0..8 {
            let r: [f64; 3] = std::array::from_fn(|c| x[k][c] - origin[c]);
            let fk = f[k];
            moment[0] += r[1] * fk[2] - r[2] * fk[1];
            moment[1] += r[2] * fk[0] - r[0] * fk[2];
            moment[2] += r[0] * fk[1] - r[1] * fk[0];
        }
        assert!(moment.iter().all(|m| m.abs() < 1e-12 * total), "{moment:?}");
    }
}
