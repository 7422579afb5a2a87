//! The three-dimensional solid element, small strain, elastic-plastic: the
//! 20-node serendipity hexahedron ([`super::h20`]) or the 10-node tetrahedron
//! ([`super::t10`]), three displacements per node.
//!
//! # Voigt order
//!
//! Strain, stress and plastic strain keep the order of the plane and
//! axisymmetric code, the three out-of-plane shears last:
//! ```text
//!   ε = [ε_xx, ε_yy, γ_xy, ε_zz, γ_xz, γ_yz]     (engineering shear, γ = 2 ε_ij)
//!   σ = [σ_xx, σ_yy, σ_xy, σ_zz, σ_xz, σ_yz]     (PointState::stress)
//!   εᵖ = [εᵖ_xx, εᵖ_yy, εᵖ_xy, εᵖ_zz, εᵖ_xz, εᵖ_yz] (PointState::plastic_strain, tensor shear)
//! ```
//! This is, slot for slot, the order (rr, zz, rz, θθ, rθ, zθ) of the
//! six-component return mapping of the axisymmetric model with twist
//! ([`VonMises::update_twist`](crate::physics::material::VonMises::update_twist)) under the relabelling x → r, y → z, z → θ,
//! so that return is called unchanged, with no permutation. It is a general
//! 3D J2 return: it takes the six strains (engineering shear) and returns
//! the six stresses and tensor plastic strains, works on the strain tensor
//! only (isotropic elasticity, von Mises surface, radial return) and uses no
//! coordinate, radius or `mat.plane` (which is not consulted). An isotropic
//! law is invariant under every orthogonal change of axes, reflections
//! included, so the relabelling (a left-handed (r, z, θ) for a right-handed
//! (x, y, z)) changes nothing; the tests check that a rotated strain gives
//! the rotated stress, plastic strain and tangent, and that the elastic law
//! is σ = λ tr ε 1 + 2G ε with γ = 2ε_ij. The same order makes a 3D state
//! the twist model's [`PointState`] (packing, [`VonMises::equivalent_stress`](crate::physics::material::VonMises::equivalent_stress)).
//!
//! # Element
//!
//! Per node a, with (N_x, N_y, N_z) = ∂N_a/∂(x, y, z) and the nodal dofs
//! interleaved (u_x, u_y, u_z), the 6 × 3 block of B (Zienkiewicz, Taylor &
//! Zhu, *The Finite Element Method: Its Basis and Fundamentals*, 7th ed.,
//! ch. 6, the three-dimensional strain-displacement matrix, rows reordered
//! to the Voigt order above):
//! ```text
//!   ⎡N_x  0    0  ⎤   ε_xx
//!   ⎢0    N_y  0  ⎥   ε_yy
//!   ⎢N_y  N_x  0  ⎥   γ_xy
//!   ⎢0    0    N_z⎥   ε_zz
//!   ⎢N_z  0    N_x⎥   γ_xz
//!   ⎣0    N_z  N_y⎦   γ_yz
//! ```
//! and (ZTZ 7th ed., ch. 2 and 6, the element integrals, by Gauss
//! quadrature):
//! ```text
//!   fᵉ = Σ_p Bᵀ σ dv_p        Kᵉ = Σ_p Bᵀ C B dv_p        dv_p = det J · w_p
//!   ∂N/∂x = Σ_k ∂N/∂ξ_k g^k,  g^k = (g_{k+1} × g_{k+2}) / det J,  g_k = ∂x/∂ξ_k
//! ```
//! (the dual basis g^k are the rows of J⁻¹, det J = g_0 · (g_1 × g_2)). C is
//! the algorithmic tangent of the radial return (Simo & Hughes 1998, box
//! 3.2, and its consistent tangent, eq. 3.3.20; Simo & Taylor 1985), the
//! continuum C_ep at the committed state or the elastic D, as
//! [`Tangent`] chooses.
//!
//! Geometry is recomputed per call (as [`super::solid`] does) and lives on
//! the stack; the element arrays are the caller's slices, `ke` row-major
//! (3·nodes)², at most 60 × 60. No heap allocation per element call.
#![allow(dead_code)] // wired by the 3D model (issue 44)

use super::gauss3::GaussRule3;
use super::solid::{Response, Tangent};
use crate::physics::material::{PointMaterials, PointState};
use nalgebra::Matrix6;

pub(crate) use super::family3::{Family3, MAX_NODES3, MAX_POINTS3};
#[cfg(test)]
use super::{family3::MAX_DOFS3, h20, t10};

/// Per-element Gauss point geometry of a 3D element, on the stack (about
/// 20 KB).
#[derive(Clone, Debug)]
pub(crate) struct ElementGeometry3 {
    /// Number of Gauss points.
    pub n: usize,
    /// Number of nodes (the family's: 20 or 10).
    pub nodes: usize,
    /// ∂N_a/∂(x, y, z) at each Gauss point.
    pub dndx: [[[f64; 3]; MAX_NODES3]; MAX_POINTS3],
    /// det J · weight at each Gauss point.
    pub dv: [f64; MAX_POINTS3],
    /// Physical coordinates of each Gauss point.
    pub x: [[f64; 3]; MAX_POINTS3],
    /// N_a at each Gauss point.
    pub shape: [[f64; MAX_NODES3]; MAX_POINTS3],
}

impl ElementGeometry3 {
    /// Precomputes the geometry of an element of `family` with nodes at
    /// `coords` (the family's count) for `rule`; an Err names the Gauss
    /// point with det J ≤ 0 (or too small to trust).
    pub(crate) fn new(
        family: Family3,
        coords: &[[f64; 3]],
        rule: &GaussRule3,
    ) -> Result<Self, String> {
        let nn = family.nodes();
        if coords.len() != nn {
            return Err(format!(
                "a {} needs {nn} node coordinates, got {}",
                family.name(),
                coords.len()
            ));
        }
        if rule.points.len() > MAX_POINTS3 {
            return Err(format!(
                "{} Gauss points (at most {MAX_POINTS3})",
                rule.points.len()
            ));
        }
        let mut g = ElementGeometry3 {
            n: rule.points.len(),
            nodes: nn,
            dndx: [[[0.0; 3]; MAX_NODES3]; MAX_POINTS3],
            dv: [0.0; MAX_POINTS3],
            x: [[0.0; 3]; MAX_POINTS3],
            shape: [[0.0; MAX_NODES3]; MAX_POINTS3],
        };
        for (ip, &(xi, w)) in rule.points.iter().enumerate() {
            let (det, d) = family
                .physical_derivs(coords, xi)
                .map_err(|e| format!("Gauss point {ip}: {e}"))?;
            let n = family.shape(xi);
            let mut x = [0.0; 3];
            for a in 0..nn {
                for (i, xi) in x.iter_mut().enumerate() {
                    *xi += n[a] * coords[a][i];
                }
            }
            g.dndx[ip] = d;
            g.dv[ip] = det * w;
            g.x[ip] = x;
            g.shape[ip] = n;
        }
        Ok(g)
    }

    /// Element dofs: 3 per node.
    pub(crate) fn dofs(&self) -> usize {
        3 * self.nodes
    }

    /// The element's volume Σ dv.
    pub(crate) fn volume(&self) -> f64 {
        self.dv[..self.n].iter().sum()
    }

    /// Strain B u = [ε_xx, ε_yy, γ_xy, ε_zz, γ_xz, γ_yz] at Gauss point `ip`
    /// from the element displacements (node-major, u_x, u_y, u_z per node).
    pub(crate) fn strain(&self, ip: usize, ue: &[f64]) -> [f64; 6] {
        let d = &self.dndx[ip];
        let mut e = [0.0; 6];
        for a in 0..self.nodes {
            let [nx, ny, nz] = d[a];
            let (ux, uy, uz) = (ue[3 * a], ue[3 * a + 1], ue[3 * a + 2]);
            e[0] += nx * ux;
            e[1] += ny * uy;
            e[2] += ny * ux + nx * uy;
            e[3] += nz * uz;
            e[4] += nz * ux + nx * uz;
            e[5] += nz * uy + ny * uz;
        }
        e
    }
}

/// Internal force fᵉ = Σ Bᵀ σ dv and (optionally) tangent Kᵉ = Σ Bᵀ C B dv
/// of one 3D element (module text), mirroring [`super::solid::forces`]:
/// `ue`, `fe` hold 3 · nodes dofs (node-major, u_x, u_y, u_z), `ke` is
/// row-major (3 · nodes)² (only that prefix of each slice is used), and
/// `trial` receives the updated Gauss point states. [`Response::Plastic`]
/// is the radial return ([`VonMises::update_twist`](crate::physics::material::VonMises::update_twist), Simo & Hughes box
/// 3.2), [`Response::ElasticOnly`] the elastic law from the committed
/// plastic strain; C is the algorithmic tangent of that update
/// ([`Tangent::Consistent`]), the continuum C_ep at the committed state
/// ([`Tangent::Continuum`], eq. 3.13) or D ([`Tangent::Elastic`]). Errors
/// name a wrong slice length.
#[allow(clippy::too_many_arguments)]
pub(crate) fn forces3<'m>(
    geom: &ElementGeometry3,
    mats: impl Into<PointMaterials<'m>>,
    thermal: &[f64],
    ue: &[f64],
    committed: &[PointState],
    trial: &mut [PointState],
    response: Response,
    tangent: Option<Tangent>,
    fe: &mut [f64],
    ke: &mut [f64],
) -> Result<(), String> {
    let ne = geom.dofs();
    if ue.len() < ne || fe.len() < ne {
        return Err(format!(
            "{ne} element dofs, but {} displacements and {} forces",
            ue.len(),
            fe.len()
        ));
    }
    if tangent.is_some() && ke.len() < ne * ne {
        return Err(format!("a {ne} × {ne} tangent in {} entries", ke.len()));
    }
    if committed.len() < geom.n || trial.len() < geom.n {
        return Err(format!(
            "{} Gauss points, but {} committed and {} trial states",
            geom.n,
            committed.len(),
            trial.len()
        ));
    }
    let mats = mats.into();
    fe[..ne].fill(0.0);
    if tangent.is_some() {
        ke[..ne * ne].fill(0.0);
    }
    for ip in 0..geom.n {
        let mat = mats.at(ip);
        let eps = super::solid::less_thermal(geom.strain(ip, ue), thermal[ip]);
        let (state, c_alg) = match response {
            Response::Plastic => mat.update_twist(&committed[ip], &eps),
            Response::ElasticOnly => (
                mat.elastic_state_twist(&committed[ip], &eps),
                mat.elastic_matrix_6(),
            ),
        };
        trial[ip] = state;
        let (dv, d, s) = (geom.dv[ip], &geom.dndx[ip], &state.stress);
        for a in 0..geom.nodes {
            let [nx, ny, nz] = d[a];
            fe[3 * a] += dv * (nx * s[0] + ny * s[2] + nz * s[4]);
            fe[3 * a + 1] += dv * (ny * s[1] + nx * s[2] + nz * s[5]);
            fe[3 * a + 2] += dv * (nz * s[3] + nx * s[4] + ny * s[5]);
        }
        if let Some(t) = tangent {
            let c = match t {
                Tangent::Consistent => c_alg,
                Tangent::Continuum => mat.continuum_tangent_6(&committed[ip]),
                Tangent::Elastic => mat.elastic_matrix_6(),
            };
            add_btcb3(d, geom.nodes, &c, dv, &mut ke[..ne * ne]);
        }
    }
    Ok(())
}

/// ke += Bᵀ C B dv, with the three nonzeros of each column of the nodal B
/// blocks (module text): CB per node first (6 × 3), then Bᵀ (CB).
fn add_btcb3(d: &[[f64; 3]; MAX_NODES3], nn: usize, c: &Matrix6<f64>, dv: f64, ke: &mut [f64]) {
    let ne = 3 * nn;
    // cb[b][r][j] = (C B)_{r, 3b + j}
    let mut cb = [[[0.0f64; 3]; 6]; MAX_NODES3];
    for b in 0..nn {
        let [bx, by, bz] = d[b];
        for (r, row) in cb[b].iter_mut().enumerate() {
            row[0] = c[(r, 0)] * bx + c[(r, 2)] * by + c[(r, 4)] * bz;
            row[1] = c[(r, 1)] * by + c[(r, 2)] * bx + c[(r, 5)] * bz;
            row[2] = c[(r, 3)] * bz + c[(r, 4)] * bx + c[(r, 5)] * by;
        }
    }
    for a in 0..nn {
        let [ax, ay, az] = d[a];
        for (b, m) in cb.iter().enumerate().take(nn) {
            for j in 0..3 {
                // rows of Bᵀ for node a: u_x [ax, 0, ay, 0, az, 0],
                // u_y [0, ay, ax, 0, 0, az], u_z [0, 0, 0, az, ax, ay]
                let kx = ax * m[0][j] + ay * m[2][j] + az * m[4][j];
                let ky = ay * m[1][j] + ax * m[2][j] + az * m[5][j];
                let kz = az * m[3][j] + ax * m[4][j] + ay * m[5][j];
                ke[(3 * a) * ne + 3 * b + j] += dv * kx;
                ke[(3 * a + 1) * ne + 3 * b + j] += dv * ky;
                ke[(3 * a + 2) * ne + 3 * b + j] += dv * kz;
            }
        }
    }
}

#[cfg(test)]
mod extrapolation_tests {
    use super::*;

    /// Each rule's extrapolation reproduces, at the nodes, the polynomials
    /// its fit spans: exactly where they are those of the element's shape.
    #[test]
    fn extrapolation_reproduces_the_fitted_polynomials() {
        let linear = |[x, y, z]: [f64; 3]| 1.0 + 2.0 * x - 0.5 * y + 0.25 * z;
        let quadratic =
            |p: [f64; 3]| linear(p) + p[0] * p[0] - 3.0 * p[1] * p[2] + 0.7 * p[2] * p[2];
        for (family, full, f) in [
            (Family3::H20, false, &linear as &dyn Fn([f64; 3]) -> f64),
            (Family3::H20, true, &quadratic),
            (Family3::T10, false, &linear),
            (Family3::T10, true, &quadratic),
        ] {
            let rule = family.rule(full);
            let w = family.extrapolation(&rule);
            for (a, &x) in family.node_xi().iter().enumerate() {
                let at: f64 = (0..rule.points.len())
                    .map(|k| w[k][a] * f(rule.points[k].0))
                    .sum();
                assert!(
                    (at - f(x)).abs() < 1e-11,
                    "{family:?} {full} node {a}: {at} vs {}",
                    f(x)
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numbers::fd;
    use crate::physics::material::Plane;
    use crate::physics::material::VonMises;
    use nalgebra::{DMatrix, DVector, Matrix3, SymmetricEigen, Vector6};

    const E: f64 = 200000.0;
    const NU: f64 = 0.3;
    const SY: f64 = 250.0;

    /// The material; `plane` is not consulted by the 3D element (Strain here,
    /// Axisymmetric in the twist model: the same return).
    fn mat(sy: f64, h: f64) -> VonMises {
        VonMises::new(E, NU, sy, h, Plane::Strain).unwrap()
    }

    /// A deterministic wiggle in [−1, 1].
    fn wig(i: usize) -> f64 {
        ((i as f64 + 1.0) * 2.399_963).sin()
    }

    /// A distorted H20: a curved map of [−1, 1]³ (curved edges and faces),
    /// then every node (corners and midsides) moved by up to 0.04 off it,
    /// so the midsides are not at their edges' midpoints.
    fn hex() -> Vec<[f64; 3]> {
        crate::physics::element::h20::NODE_XI
            .iter()
            .enumerate()
            .map(|(a, &[x, e, z])| {
                let base = [
                    2.0 + 1.0 * x + 0.15 * x * e + 0.1 * z * z,
                    1.0 + 0.8 * e + 0.12 * x * z - 0.1 * x * x,
                    0.5 + 1.2 * z + 0.1 * x * e + 0.08 * e * e,
                ];
                std::array::from_fn(|i| base[i] + 0.04 * wig(3 * a + i))
            })
            .collect()
    }

    /// A distorted T10: a general tetrahedron, every midside moved by up to
    /// 0.04 off its edge's midpoint (curved edges).
    fn tet() -> Vec<[f64; 3]> {
        let corners = [
            [0.0, 0.0, 0.0],
            [1.2, 0.1, -0.1],
            [0.2, 1.0, 0.15],
            [0.1, 0.25, 1.1],
        ];
        let mids = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
        let mut c = corners.to_vec();
        for (m, [i, j]) in mids.into_iter().enumerate() {
            c.push(std::array::from_fn(|k| {
                0.5 * (corners[i][k] + corners[j][k]) + 0.04 * wig(3 * m + k + 7)
            }));
        }
        c
    }

    /// The unit cube [0, 1]³ as an H20.
    fn cube() -> Vec<[f64; 3]> {
        crate::physics::element::h20::NODE_XI
            .iter()
            .map(|x| x.map(|c| 0.5 * (c + 1.0)))
            .collect()
    }

    /// (family, coordinates, full rule?) of every case the tests loop over.
    fn cases() -> Vec<(Family3, Vec<[f64; 3]>, bool)> {
        vec![
            (Family3::H20, hex(), true),
            (Family3::H20, hex(), false),
            (Family3::T10, tet(), true),
            (Family3::T10, tet(), false),
        ]
    }

    fn geometry(f: Family3, c: &[[f64; 3]], full: bool) -> ElementGeometry3 {
        ElementGeometry3::new(f, c, &f.rule(full)).unwrap()
    }

    /// fᵉ, Kᵉ (row-major) and the trial states.
    fn eval(
        g: &ElementGeometry3,
        m: &VonMises,
        ue: &[f64],
        committed: &[PointState],
        response: Response,
        tangent: Option<Tangent>,
    ) -> (Vec<f64>, Vec<f64>, Vec<PointState>) {
        let ne = g.dofs();
        let (mut fe, mut ke) = ([0.0; MAX_DOFS3], [0.0; MAX_DOFS3 * MAX_DOFS3]);
        let mut trial = vec![PointState::default(); g.n];
        forces3(
            g,
            m,
            &[0.0; MAX_POINTS3],
            ue,
            committed,
            &mut trial,
            response,
            tangent,
            &mut fe,
            &mut ke,
        )
        .unwrap();
        (fe[..ne].to_vec(), ke[..ne * ne].to_vec(), trial)
    }

    fn virgin(g: &ElementGeometry3) -> Vec<PointState> {
        vec![PointState::default(); g.n]
    }

    /// u = u0 + G x at the nodes.
    fn linear_field(c: &[[f64; 3]], u0: [f64; 3], gr: [[f64; 3]; 3]) -> Vec<f64> {
        c.iter()
            .flat_map(|x| (0..3).map(move |i| u0[i] + (0..3).map(|j| gr[i][j] * x[j]).sum::<f64>()))
            .collect()
    }

    /// The Voigt strain of the displacement gradient G (engineering shear).
    fn voigt_strain(gr: [[f64; 3]; 3]) -> [f64; 6] {
        [
            gr[0][0],
            gr[1][1],
            gr[0][1] + gr[1][0],
            gr[2][2],
            gr[0][2] + gr[2][0],
            gr[1][2] + gr[2][1],
        ]
    }

    /// A symmetric tensor from Voigt stress-like components (tensor shear).
    fn tensor(s: &[f64; 6]) -> Matrix3<f64> {
        Matrix3::new(s[0], s[2], s[4], s[2], s[1], s[5], s[4], s[5], s[3])
    }

    /// Voigt engineering strain of a symmetric tensor.
    fn strain_voigt(e: &Matrix3<f64>) -> [f64; 6] {
        [
            e[(0, 0)],
            e[(1, 1)],
            2.0 * e[(0, 1)],
            e[(2, 2)],
            2.0 * e[(0, 2)],
            2.0 * e[(1, 2)],
        ]
    }

    /// Voigt tensor components (stress, plastic strain) of a symmetric tensor.
    fn stress_voigt(s: &Matrix3<f64>) -> [f64; 6] {
        [
            s[(0, 0)],
            s[(1, 1)],
            s[(0, 1)],
            s[(2, 2)],
            s[(0, 2)],
            s[(1, 2)],
        ]
    }

    fn amax(v: &[f64]) -> f64 {
        v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
    }

    const GRAD: [[f64; 3]; 3] = [[1.0, 0.3, -0.4], [0.2, -0.6, 0.5], [-0.7, 0.1, 0.8]];

    // (1) the six-component return is a general 3D J2 return in this order

    #[test]
    fn the_six_component_return_is_isotropic_and_takes_engineering_shear() {
        let m = mat(SY, 3000.0);
        let (g, k) = (m.shear_modulus(), m.bulk_modulus());
        let lambda = k - 2.0 * g / 3.0;
        // elastic: σ = λ tr ε 1 + 2G ε with γ = 2 ε_ij
        let eps = Matrix3::new(3.0, 1.0, -2.0, 1.0, -1.0, 0.5, -2.0, 0.5, 2.0) * 1e-5;
        let (s, _) = m.update_twist(&PointState::default(), &strain_voigt(&eps));
        assert!(!s.yielding);
        let hooke = Matrix3::identity() * (lambda * eps.trace()) + eps * (2.0 * g);
        assert!((tensor(&s.stress) - hooke).amax() < 1e-12 * hooke.amax());
        // a rotation, and a rotation with a reflection (the relabelling
        // x, y, z → r, z, θ is one): rotated strains (and committed state)
        // give the rotated stress, plastic strain and tangent
        let axis = nalgebra::Vector3::new(1.0, 2.0, -0.5).normalize();
        let r = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_unchecked(axis), 0.7)
            .into_inner();
        let flip = Matrix3::from_diagonal(&nalgebra::Vector3::new(1.0, 1.0, -1.0));
        let e1 = Matrix3::new(2.0, 1.5, -1.0, 1.5, -1.0, 2.5, -1.0, 2.5, 0.5) * 1e-3;
        let e2 = Matrix3::new(4.0, 1.0, -3.0, 1.0, -2.0, 3.5, -3.0, 3.5, 1.0) * 1e-3;
        let de = Matrix3::new(1.0, -0.5, 0.3, -0.5, 0.2, 0.7, 0.3, 0.7, -0.9) * 1e-6;
        for q in [r, r * flip] {
            let rot = |t: &Matrix3<f64>| q * t * q.transpose();
            let c = m.update_twist(&PointState::default(), &strain_voigt(&e1)).0;
            assert!(c.yielding);
            let cq = PointState {
                stress: stress_voigt(&rot(&tensor(&c.stress))),
                plastic_strain: stress_voigt(&rot(&tensor(&c.plastic_strain))),
                ..c
            };
            let (a, ca) = m.update_twist(&c, &strain_voigt(&e2));
            let (b, cb) = m.update_twist(&cq, &strain_voigt(&rot(&e2)));
            assert!(a.yielding && b.yielding);
            let sa = rot(&tensor(&a.stress));
            assert!(
                (sa - tensor(&b.stress)).amax() < 1e-12 * sa.amax(),
                "{a:?} {b:?}"
            );
            let pa = rot(&tensor(&a.plastic_strain));
            assert!((pa - tensor(&b.plastic_strain)).amax() < 1e-12 * pa.amax());
            assert!((a.peeq - b.peeq).abs() < 1e-15);
            let ds_a = ca * Vector6::from(strain_voigt(&de));
            let ds_b = cb * Vector6::from(strain_voigt(&rot(&de)));
            let da = rot(&tensor(&ds_a.into()));
            assert!((da - tensor(&ds_b.into())).amax() < 1e-10 * da.amax());
        }
    }

    // (a) patch test

    #[test]
    fn a_linear_field_gives_the_exact_uniform_strain_and_consistent_nodal_forces() {
        let m = mat(f64::INFINITY, 0.0);
        let d = m.elastic_matrix_6();
        let exact = voigt_strain(GRAD);
        let sigma: [f64; 6] = (d * Vector6::from(exact)).into();
        for (f, c, full) in cases() {
            let g = geometry(f, &c, full);
            let ue = linear_field(&c, [0.3, -0.2, 0.7], GRAD);
            let mut worst = 0.0f64;
            for ip in 0..g.n {
                let e = g.strain(ip, &ue);
                for i in 0..6 {
                    worst = worst.max((e[i] - exact[i]).abs());
                }
            }
            assert!(worst < 1e-12, "{f:?} full {full}: strain off by {worst:e}");
            let (fe, ke, trial) = eval(
                &g,
                &m,
                &ue,
                &virgin(&g),
                Response::Plastic,
                Some(Tangent::Consistent),
            );
            for s in &trial {
                for i in 0..6 {
                    assert!((s.stress[i] - sigma[i]).abs() < 1e-9 * amax(&sigma));
                }
            }
            let fmax = amax(&fe);
            let ne = g.dofs();
            // equilibrium: Σ_a f_a = 0
            for i in 0..3 {
                let s: f64 = (0..g.nodes).map(|a| fe[3 * a + i]).sum();
                assert!(s.abs() < 1e-10 * fmax, "{f:?}: Σ f_{i} = {s:e} of {fmax:e}");
            }
            // the nodal forces of a uniform σ: Σ_a x_a ⊗ f_a = σ V (since
            // Σ_a x_a ∇N_a = 1 at every point)
            let v = g.volume();
            let st = tensor(&sigma);
            for i in 0..3 {
                for j in 0..3 {
                    let mom: f64 = (0..g.nodes).map(|a| fe[3 * a + i] * c[a][j]).sum();
                    assert!(
                        (mom - st[(i, j)] * v).abs() < 1e-10 * st.amax() * v,
                        "{f:?}: moment {i}{j} {mom} vs {}",
                        st[(i, j)] * v
                    );
                }
            }
            // fᵉ = Kᵉ uᵉ (linear elastic)
            let mut off = 0.0f64;
            for p in 0..ne {
                let ku: f64 = (0..ne).map(|q| ke[p * ne + q] * ue[q]).sum();
                off = off.max((ku - fe[p]).abs());
            }
            assert!(
                off < 1e-10 * fmax,
                "{f:?}: |Kᵉuᵉ − fᵉ| = {off:e} of {fmax:e}"
            );
            eprintln!(
                "patch {f:?} {} points: strain error {worst:.1e}, |Ku − f|/|f| {:.1e}",
                g.n,
                off / fmax
            );
        }
    }

    // (b) rigid-body modes

    /// The six rigid modes at the nodes: translations, then rotations ω × x.
    fn rigid_modes(c: &[[f64; 3]]) -> Vec<Vec<f64>> {
        let mut modes = Vec::new();
        for i in 0..3 {
            let mut t = [0.0; 3];
            t[i] = 1.0;
            modes.push(linear_field(c, t, [[0.0; 3]; 3]));
        }
        for k in 0..3 {
            // u = e_k × x: the skew gradient W with W x = e_k × x
            let mut w = [[0.0; 3]; 3];
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            w[j][i] = 1.0;
            w[i][j] = -1.0;
            modes.push(linear_field(c, [0.0; 3], w));
        }
        modes
    }

    #[test]
    fn rigid_body_modes_give_no_force() {
        let m = mat(SY, 1000.0);
        for (f, c, full) in cases() {
            let g = geometry(f, &c, full);
            let ne = g.dofs();
            // the force a unit strain would give: E · (volume)^(2/3)
            let scale = E * g.volume().powf(2.0 / 3.0);
            for (r, mode) in rigid_modes(&c).iter().enumerate() {
                let u: Vec<f64> = mode.iter().map(|v| 1e-2 * v).collect();
                let (fe, ke, trial) = eval(
                    &g,
                    &m,
                    &u,
                    &virgin(&g),
                    Response::Plastic,
                    Some(Tangent::Consistent),
                );
                assert!(trial.iter().all(|s| !s.yielding));
                assert!(amax(&fe) < 1e-14 * scale, "{f:?} mode {r}: {:e}", amax(&fe));
                let kmax = amax(&ke);
                for p in 0..ne {
                    let ku: f64 = (0..ne).map(|q| ke[p * ne + q] * mode[q]).sum();
                    assert!(
                        ku.abs() < 1e-11 * kmax * amax(mode),
                        "{f:?} mode {r}: K r = {ku:e}"
                    );
                }
            }
        }
    }

    // (c) symmetry and the zero eigenvalues

    /// The eigenvalues of Kᵉ with |λ| < 1e-9 λ_max, and (largest such,
    /// smallest other) / λ_max.
    fn zero_eigenvalues(ke: &[f64], ne: usize) -> (usize, f64, f64) {
        let k = DMatrix::from_row_slice(ne, ne, ke);
        let eig = SymmetricEigen::new(k).eigenvalues;
        let lmax = eig.amax();
        let zero = eig.iter().filter(|l| l.abs() < 1e-9 * lmax).count();
        let big = eig
            .iter()
            .filter(|l| l.abs() < 1e-9 * lmax)
            .fold(0.0f64, |a, l| a.max(l.abs()));
        let small = eig
            .iter()
            .filter(|l| l.abs() >= 1e-9 * lmax)
            .fold(f64::INFINITY, |a, l| a.min(l.abs()));
        (zero, big / lmax, small / lmax)
    }

    #[test]
    fn stiffness_is_symmetric_with_six_rigid_zero_modes_unless_under_integrated() {
        let m = mat(SY, 0.0);
        let mut all = cases();
        all.push((Family3::H20, cube(), true));
        all.push((Family3::H20, cube(), false));
        for (f, c, full) in all {
            let g = geometry(f, &c, full);
            let ne = g.dofs();
            let ue = vec![0.0; ne];
            let (_, ke, _) = eval(
                &g,
                &m,
                &ue,
                &virgin(&g),
                Response::Plastic,
                Some(Tangent::Elastic),
            );
            let kmax = amax(&ke);
            for p in 0..ne {
                for q in 0..p {
                    assert!((ke[p * ne + q] - ke[q * ne + p]).abs() <= 1e-13 * kmax);
                }
            }
            let (zero, big, small) = zero_eigenvalues(&ke, ne);
            eprintln!(
                "{f:?} {} points ({} nodes at {:.2},...): {zero} zero eigenvalues \
                 (largest {big:.1e} λmax, next {small:.1e} λmax)",
                g.n, g.nodes, c[0][0]
            );
            let expected = match (f, g.n) {
                (Family3::H20, 8) => 12, // 6 rigid + 6 spurious: rank 8 × 6 = 48
                _ => 6,
            };
            assert_eq!(zero, expected, "{f:?} with {} points", g.n);
            assert!(small > 1e-6, "{f:?}: no clear gap ({big:e} / {small:e})");
        }
    }

    // (d) the consistent tangent against finite differences

    /// A displacement well past yield: a linear field of strain ~4e-3 plus a
    /// quadratic wiggle.
    fn plastic_field(c: &[[f64; 3]]) -> Vec<f64> {
        let gr = GRAD.map(|r| r.map(|v| 4e-3 * v));
        let mut u = linear_field(c, [0.01, -0.02, 0.005], gr);
        for (i, v) in u.iter_mut().enumerate() {
            *v += 4e-4 * wig(i + 11);
        }
        u
    }

    #[test]
    fn consistent_tangent_matches_finite_differences_in_the_plastic_regime() {
        let m = mat(SY, 5000.0);
        for (f, c, full) in cases() {
            let g = geometry(f, &c, full);
            let ne = g.dofs();
            let ue = plastic_field(&c);
            let half: Vec<f64> = ue.iter().map(|v| 0.6 * v).collect();
            let committed = eval(&g, &m, &half, &virgin(&g), Response::Plastic, None).2;
            assert!(
                committed.iter().all(|s| s.yielding),
                "{f:?}: committed not plastic"
            );
            let (_, ke, trial) = eval(
                &g,
                &m,
                &ue,
                &committed,
                Response::Plastic,
                Some(Tangent::Consistent),
            );
            assert!(trial.iter().all(|s| s.yielding), "{f:?}: trial not plastic");
            let kmax = amax(&ke);
            let jac = fd::central_jacobian(
                |u| eval(&g, &m, u, &committed, Response::Plastic, None).0,
                &ue,
                1e-8,
            );
            let w = fd::worst(&jac, |i, j| ke[i * ne + j], fd::Scale::Of(kmax));
            eprintln!("FD {f:?} {} points: {w}", g.n);
            assert!(w.ratio < 1e-6, "{f:?} {} points: {w}", g.n);
            // associated flow: the consistent tangent is symmetric
            for p in 0..ne {
                for q in 0..p {
                    assert!((ke[p * ne + q] - ke[q * ne + p]).abs() <= 1e-12 * kmax);
                }
            }
            // and it differs from the elastic one (the check means something)
            let ke_el = eval(
                &g,
                &m,
                &ue,
                &committed,
                Response::Plastic,
                Some(Tangent::Elastic),
            )
            .1;
            let diff = ke
                .iter()
                .zip(&ke_el)
                .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
            assert!(
                diff > 0.05 * kmax,
                "{f:?}: plastic tangent {diff:e} off elastic"
            );
        }
    }

    #[test]
    fn elastic_and_continuum_tangents() {
        let m = mat(SY, 5000.0);
        let (f, c) = (Family3::H20, hex());
        let g = geometry(f, &c, true);
        let ne = g.dofs();
        let ue = plastic_field(&c);
        let committed = eval(&g, &m, &ue, &virgin(&g), Response::Plastic, None).2;
        // elastic-only response from a plastic state: linear, its Jacobian D
        let (_, ke_el, trial) = eval(
            &g,
            &m,
            &ue,
            &committed,
            Response::ElasticOnly,
            Some(Tangent::Consistent),
        );
        assert!(trial.iter().all(|s| !s.yielding));
        let kmax = amax(&ke_el);
        let jac = fd::central_jacobian(
            |u| eval(&g, &m, u, &committed, Response::ElasticOnly, None).0,
            &ue,
            1e-6,
        );
        let w = fd::worst(&jac, |i, j| ke_el[i * ne + j], fd::Scale::Of(kmax));
        assert!(w.ratio < 1e-8, "elastic only: {w}");
        let ke_d = eval(
            &g,
            &m,
            &ue,
            &committed,
            Response::Plastic,
            Some(Tangent::Elastic),
        )
        .1;
        assert!(ke_d
            .iter()
            .zip(&ke_el)
            .all(|(a, b)| (a - b).abs() <= 1e-12 * kmax));
        // a further plastic step of vanishing size: the consistent tangent
        // tends to the continuum C_ep at the committed state
        let u2: Vec<f64> = ue.iter().map(|v| v * (1.0 + 1e-7)).collect();
        let (_, ke_alg, t2) = eval(
            &g,
            &m,
            &u2,
            &committed,
            Response::Plastic,
            Some(Tangent::Consistent),
        );
        assert!(t2.iter().all(|s| s.yielding));
        let ke_cep = eval(
            &g,
            &m,
            &u2,
            &committed,
            Response::Plastic,
            Some(Tangent::Continuum),
        )
        .1;
        let diff = ke_alg
            .iter()
            .zip(&ke_cep)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        assert!(
            diff < 1e-5 * kmax,
            "continuum vs consistent {diff:e} of {kmax:e}"
        );
        let gap = ke_cep
            .iter()
            .zip(&ke_d)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        assert!(gap > 0.05 * kmax, "continuum is not elastic: {gap:e}");
        // from a virgin (elastic) committed state the continuum tangent is D
        let ke_c0 = eval(
            &g,
            &m,
            &ue,
            &virgin(&g),
            Response::Plastic,
            Some(Tangent::Continuum),
        )
        .1;
        assert!(ke_c0
            .iter()
            .zip(&ke_d)
            .all(|(a, b)| (a - b).abs() <= 1e-12 * kmax));
    }

    // (e) uniaxial stress through yield

    #[test]
    fn uniaxial_stress_through_yield_follows_the_closed_form() {
        let h = 10000.0;
        let m = mat(SY, h);
        let et = E * h / (E + h);
        let c = cube();
        let g = geometry(Family3::H20, &c, true);
        let ne = g.dofs();
        // symmetry planes x = 0, y = 0, z = 0; u_x = e on x = 1
        let mut fixed = vec![false; ne];
        let mut pulled = vec![false; ne];
        for (a, x) in c.iter().enumerate() {
            for i in 0..3 {
                fixed[3 * a + i] = x[i] == 0.0;
            }
            pulled[3 * a] = x[0] == 1.0;
        }
        let free: Vec<usize> = (0..ne).filter(|&p| !fixed[p] && !pulled[p]).collect();
        let mut u = vec![0.0; ne];
        let mut committed = virgin(&g);
        let mut crossed = false;
        for e in [0.5e-3, 1.2e-3, 2e-3, 4e-3, 1e-2, 2e-2] {
            for p in 0..ne {
                if pulled[p] {
                    u[p] = e;
                }
            }
            let mut its = 0;
            let mut history = Vec::new();
            let trial = loop {
                let (fe, ke, trial) = eval(
                    &g,
                    &m,
                    &u,
                    &committed,
                    Response::Plastic,
                    Some(Tangent::Consistent),
                );
                let r = DVector::from_iterator(free.len(), free.iter().map(|&p| fe[p]));
                history.push(r.amax());
                if r.amax() < 1e-12 * SY {
                    break trial;
                }
                its += 1;
                assert!(its <= 8, "e = {e}: no convergence, |r| = {:e}", r.amax());
                let k = DMatrix::from_fn(free.len(), free.len(), |i, j| ke[free[i] * ne + free[j]]);
                let du = k.lu().solve(&(-r)).unwrap();
                for (i, &p) in free.iter().enumerate() {
                    u[p] += du[i];
                }
            };
            committed = trial;
            // quadratic convergence near the solution (the consistent
            // tangent): ρ_{k+1} ≤ 100 ρ_k², ρ = |r| / |r_0|, above round-off
            let rho: Vec<f64> = history.iter().map(|r| r / history[0]).collect();
            for k in 0..rho.len() - 1 {
                if rho[k] < 1e-2 && rho[k + 1] > 1e-13 {
                    assert!(
                        rho[k + 1] <= 100.0 * rho[k] * rho[k],
                        "e = {e}: |r| {history:?}"
                    );
                }
            }
            let sigma = if E * e <= SY {
                E * e
            } else {
                SY + et * (e - SY / E)
            };
            let peeq = (sigma - SY).max(0.0) / h;
            for s in &committed {
                assert!(
                    (s.stress[0] - sigma).abs() < 1e-9 * sigma,
                    "e = {e}: σ_xx {} vs {sigma}",
                    s.stress[0]
                );
                assert!(
                    s.stress[1..].iter().all(|v| v.abs() < 1e-9 * sigma),
                    "{s:?}"
                );
                assert!(
                    (s.peeq - peeq).abs() < 1e-12,
                    "e = {e}: ε̄ᵖ {} vs {peeq}",
                    s.peeq
                );
                assert_eq!(s.yielding, E * e > SY);
                if s.yielding {
                    assert!((s.stress[0] - (SY + h * s.peeq)).abs() < 1e-9 * sigma);
                }
            }
            crossed |= committed[0].yielding;
            eprintln!(
                "uniaxial e = {e}: σ = {:.6} (closed form {sigma:.6}), ε̄ᵖ = {:.3e}, {its} Newton iterations, |r| {:?}",
                committed[0].stress[0],
                committed[0].peeq,
                history.iter().map(|r| format!("{r:.1e}")).collect::<Vec<_>>()
            );
        }
        assert!(crossed);
    }

    // (f) the element calls the twist model's material with the same components

    #[test]
    fn the_element_state_is_the_twist_material_call_on_the_voigt_strain() {
        let m = mat(SY, 2000.0);
        let gr = GRAD.map(|r| r.map(|v| 3e-3 * v));
        let exact = voigt_strain(gr);
        for (f, c, full) in cases() {
            let g = geometry(f, &c, full);
            let ue = linear_field(&c, [0.0; 3], gr);
            let half: Vec<f64> = ue.iter().map(|v| 0.5 * v).collect();
            let committed = eval(&g, &m, &half, &virgin(&g), Response::Plastic, None).2;
            let trial = eval(&g, &m, &ue, &committed, Response::Plastic, None).2;
            for ip in 0..g.n {
                let (want, _) = m.update_twist(&committed[ip], &exact);
                let (s, w) = (&trial[ip], &want);
                assert!(s.yielding && w.yielding);
                for i in 0..6 {
                    assert!((s.stress[i] - w.stress[i]).abs() < 1e-9 * SY, "{s:?} {w:?}");
                    assert!((s.plastic_strain[i] - w.plastic_strain[i]).abs() < 1e-12);
                }
                assert!((s.peeq - w.peeq).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn an_inverted_element_names_the_gauss_point() {
        let mut c = cube();
        // a top corner pushed through the bottom face
        c[6][2] = -0.8;
        let e = ElementGeometry3::new(Family3::H20, &c, &h20::gauss_27()).unwrap_err();
        assert!(
            e.starts_with("Gauss point ") && e.contains("Jacobian determinant"),
            "{e}"
        );
        // mirrored: det J < 0 everywhere
        let c: Vec<[f64; 3]> = cube().iter().map(|&[x, y, z]| [x, y, 1.0 - z]).collect();
        let e = ElementGeometry3::new(Family3::H20, &c, &h20::gauss_8()).unwrap_err();
        assert!(
            e.starts_with("Gauss point 0: Jacobian determinant -"),
            "{e}"
        );
        let t: Vec<[f64; 3]> = tet().iter().map(|&[x, y, z]| [x, y, -z]).collect();
        let e = ElementGeometry3::new(Family3::T10, &t, &t10::gauss_4()).unwrap_err();
        assert!(e.starts_with("Gauss point 0:"), "{e}");
        assert!(ElementGeometry3::new(Family3::T10, &t[..9], &t10::gauss_4()).is_err());
    }

    /// The inverse map of a curved, distorted element: every ξ mapped to x
    /// comes back from x to 1e-10, inside the reference element; a point
    /// pushed beyond a face comes back outside it.
    #[test]
    fn natural_coordinates_invert_the_map_of_a_distorted_element() {
        let inside = [
            [0.3, -0.6, 0.9],
            [-0.95, 0.1, -0.2],
            [0.0, 0.0, 0.0],
            [1.0, 1.0, -1.0],
        ];
        let inside_tet = [
            [0.1, 0.2, 0.3],
            [0.7, 0.1, 0.1],
            [0.25, 0.25, 0.25],
            [0.0, 0.0, 1.0],
        ];
        for (f, c, pts) in [
            (Family3::H20, hex(), inside),
            (Family3::T10, tet(), inside_tet),
        ] {
            let map = |xi: [f64; 3]| -> [f64; 3] {
                let n = f.shape(xi);
                std::array::from_fn(|i| (0..f.nodes()).map(|a| n[a] * c[a][i]).sum())
            };
            for xi in pts {
                let back = f.natural_coords(&c, map(xi)).unwrap();
                for k in 0..3 {
                    assert!((back[k] - xi[k]).abs() < 1e-10, "{f:?} {xi:?} → {back:?}");
                }
                assert!(f.contains(back, 1e-9), "{f:?} {xi:?}");
            }
            // beyond the face ξ = 1 (hexahedron) or ξ + η + ζ = 1 (tetrahedron)
            let out = match f {
                Family3::H20 => [1.15, 0.2, 0.1],
                Family3::T10 => [0.5, 0.4, 0.25],
            };
            let back = f.natural_coords(&c, map(out)).unwrap();
            assert!(!f.contains(back, 0.02), "{f:?} {back:?}");
        }
    }
}
