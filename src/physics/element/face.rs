//! The 8-node quadrilateral face of a 20-node hexahedron (or the 6-node
//! triangle of a tetrahedron) in space: the consistent nodal forces of a
//! pressure and of a traction vector on it.
//!
//! ```text
//!   fₐ = ∫ Nₐ (t − p n) dA = Σ_g Nₐ(ξ_g) (t |g_ξ × g_η| − p g_ξ × g_η)(ξ_g) w_g
//! ```
//! (g_ξ = ∂x/∂ξ, g_η = ∂x/∂η, so g_ξ × g_η = n dA / dξ dη)
//! with the face's serendipity shape functions ([`super::q8`], ZTZ 7th ed.
//! sec. 6.2) and its nodes numbered as [`super::h20::FACES`]: corners
//! counter-clockwise seen from outside, so ∂x/∂ξ × ∂x/∂η is the outward
//! normal times the area element and a positive p pushes into the body
//! (Zienkiewicz, Taylor & Zhu, 7th ed., sec. 6.5 on boundary loads:
//! the surface integral of Nᵀ t).

use super::family::{Family, MAX_NODES};

/// Nodal forces (N) of a uniform pressure `p` (MPa) on a face of the plane
/// `family` (the 8-node quadrilateral of a hexahedron, the 6-node triangle
/// of a tetrahedron) with node coordinates `x` (mm), by the family's full
/// Gauss rule (exact for a flat face with straight sides, and to the rule's
/// order on a curved one). The first `family.nodes()` entries are used.
#[cfg(test)]
pub(crate) fn pressure_forces(family: Family, x: &[[f64; 3]], p: f64) -> [[f64; 3]; MAX_NODES] {
    face_forces(family, x, p, [0.0; 3])
}

/// Nodal forces (N) of a uniform pressure `p` (MPa, pushing in) and a
/// uniform traction vector `t` (MPa, a force per area of the face in
/// global axes) on a face, as [`pressure_forces`].
pub(crate) fn face_forces(
    family: Family,
    x: &[[f64; 3]],
    p: f64,
    t: [f64; 3],
) -> [[f64; 3]; MAX_NODES] {
    let nn = family.nodes();
    let mut f = [[0.0; 3]; MAX_NODES];
    for &(xi, w) in &family.rule(true).points {
        let (n, d) = (family.shape(xi), family.shape_derivs(xi));
        let mut g = [[0.0; 3]; 2];
        for a in 0..nn {
            for (k, tk) in g.iter_mut().enumerate() {
                for c in 0..3 {
                    tk[c] += d[a][k] * x[a][c];
                }
            }
        }
        let normal = crate::numbers::vec3::cross(g[0], g[1]);
        let da = crate::numbers::vec3::dot(normal, normal).sqrt();
        for a in 0..nn {
            for c in 0..3 {
                f[a][c] += n[a] * (t[c] * da - p * normal[c]) * w;
            }
        }
    }
    f
}

/// The nodal forces (N) of the hoop traction of a unit torque density on a
/// face, t(x) = ŷ × x = (z, 0, −x) (MPa per N·mm/mm⁴: τ_θ = r along the
/// right-handed hoop direction about the y axis), and the face's polar
/// moment ∫ r² dA (r² = x² + z², mm⁴), by the family's full Gauss rule as
/// [`face_forces`]. A torque T on faces of polar moment J = Σ ∫ r² dA is
/// T / J times these forces: τ_θ = T r / J, the end-face shear of an
/// elastic shaft (Timoshenko & Goodier, *Theory of Elasticity*, § 104: the
/// circular shaft, τ = G θ r, T = G θ J), whose moment about the
/// axis is ∫ r τ_θ dA = T.
pub(crate) fn torque_forces(family: Family, x: &[[f64; 3]]) -> ([[f64; 3]; MAX_NODES], f64) {
    let nn = family.nodes();
    let mut f = [[0.0; 3]; MAX_NODES];
    let mut polar = 0.0;
    for &(xi, w) in &family.rule(true).points {
        let (n, d) = (family.shape(xi), family.shape_derivs(xi));
        let mut g = [[0.0; 3]; 2];
        let mut p = [0.0; 3];
        for a in 0..nn {
            for (k, tk) in g.iter_mut().enumerate() {
                for c in 0..3 {
                    tk[c] += d[a][k] * x[a][c];
                }
            }
            for c in 0..3 {
                p[c] += n[a] * x[a][c];
            }
        }
        let normal = crate::numbers::vec3::cross(g[0], g[1]);
        let da = crate::numbers::vec3::dot(normal, normal).sqrt() * w;
        let t = [p[2], 0.0, -p[0]];
        for a in 0..nn {
            for c in 0..3 {
                f[a][c] += n[a] * t[c] * da;
            }
        }
        polar += (p[0] * p[0] + p[2] * p[2]) * da;
    }
    (f, polar)
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
        // a traction vector takes the same shares of t a b, whatever its
        // direction against the face
        let t = [2.0, -1.0, 0.5];
        let f = face_forces(Family::Q8, &x, 0.0, t);
        for (k, fk) in f.iter().enumerate().take(8) {
            let share = if k < 4 { -1.0 / 12.0 } else { 1.0 / 3.0 };
            for c in 0..3 {
                let want = share * a * b * t[c];
                assert!((fk[c] - want).abs() < 1e-12 * total, "node {k}: {fk:?}");
            }
        }
    }

    /// An annular sector a ≤ r ≤ b, 0 ≤ θ ≤ β in the plane y = 0 (one
    /// 8-node face, its nodes on the arcs): the forces' moment about the y
    /// axis is their ∫ r² dA, which is (b⁴ − a⁴) β / 4 but for the quadratic
    /// arcs, and their resultant is the hoop traction's,
    /// ∫ (z, 0, −x) dA = ((b³ − a³)/3) (1 − cos β, 0, −sin β).
    #[test]
    fn a_unit_torque_density_on_an_annular_face_has_its_polar_moment() {
        let (a, b, beta): (f64, f64, f64) = (10.0, 25.0, 0.3);
        // (the face's orientation does not enter a traction)
        let at = |r: f64, th: f64| [r * th.cos(), 0.0, r * th.sin()];
        let x = [
            at(a, 0.0),
            at(b, 0.0),
            at(b, beta),
            at(a, beta),
            at(0.5 * (a + b), 0.0),
            at(b, 0.5 * beta),
            at(0.5 * (a + b), beta),
            at(a, 0.5 * beta),
        ];
        let (f, polar) = torque_forces(Family::Q8, &x);
        let exact = (b.powi(4) - a.powi(4)) * beta / 4.0;
        assert!((polar / exact - 1.0).abs() < 1e-4, "{polar} vs {exact}");
        let mut my = 0.0;
        let mut total = [0.0; 3];
        for k in 0..8 {
            my += x[k][2] * f[k][0] - x[k][0] * f[k][2];
            for c in 0..3 {
                total[c] += f[k][c];
            }
        }
        // Σ x_a × f_a = ∫ x × t dA on the isoparametric face: r² exactly
        assert!((my / polar - 1.0).abs() < 1e-12, "{my} vs {polar}");
        let cube = (b.powi(3) - a.powi(3)) / 3.0;
        let want = [cube * (1.0 - beta.cos()), 0.0, -cube * beta.sin()];
        for c in 0..3 {
            assert!(
                (total[c] - want[c]).abs() < 1e-4 * cube,
                "{total:?} vs {want:?}"
            );
        }
    }
}
