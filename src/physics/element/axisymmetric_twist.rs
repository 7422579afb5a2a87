//! The 8-node axisymmetric element with twist: three displacements per node,
//! u_r, u_z and the circumferential u_θ, all independent of θ (a body of
//! revolution loaded by axisymmetric forces and a torque about its axis, as
//! Abaqus' CGAX elements; Zienkiewicz & Taylor, *The Finite Element Method*,
//! vol. 1, the axisymmetric solid under torsion).
//!
//! With ∂/∂θ = 0 the small strains of (u_r, u_z, u_θ) in cylindrical
//! coordinates are (engineering shear):
//! ```text
//!   ε_rr = ∂u_r/∂r    ε_zz = ∂u_z/∂z    γ_rz = ∂u_r/∂z + ∂u_z/∂r    ε_θθ = u_r/r
//!   γ_rθ = ∂u_θ/∂r − u_θ/r              γ_zθ = ∂u_θ/∂z
//! ```
//! so per node (columns u_r, u_z, u_θ) the 6 × 3 block of B is
//! ```text
//!   ⎡∂N/∂r  0      0          ⎤   ε_rr
//!   ⎢0      ∂N/∂z  0          ⎥   ε_zz
//!   ⎢∂N/∂z  ∂N/∂r  0          ⎥   γ_rz
//!   ⎢N/r    0      0          ⎥   ε_θθ
//!   ⎢0      0      ∂N/∂r − N/r⎥   γ_rθ
//!   ⎣0      0      ∂N/∂z      ⎦   γ_zθ
//! ```
//! and fᵉ = Σ Bᵀ σ dv, Kᵉ = Σ Bᵀ C B dv with dv = det J · w · 2π r and C the
//! 6 × 6 algorithmic tangent of the six-component radial return
//! ([`VonMises::update_twist`](crate::physics::material::VonMises::update_twist)). A rigid rotation about the axis, u_θ = ω r,
//! strains nothing (γ_rθ = ω − ω = 0). The first four rows are those of the
//! axisymmetric element without twist ([`crate::physics::element::solid`]).

use crate::physics::element::solid::{ElementGeometry, Response, Tangent};
use crate::physics::material::{PointMaterials, PointState};
use nalgebra::Matrix6;

/// Most element dofs with twist (8 nodes × 3); an element uses 3 ×
/// [`ElementGeometry::nodes`] of them.
const NE: usize = 24;

/// The strain [ε_rr, ε_zz, γ_rz, ε_θθ, γ_rθ, γ_zθ] at Gauss point `ip` from the
/// element displacements (node-major, u_r, u_z, u_θ per node).
pub fn strain(geom: &ElementGeometry, ip: usize, ue: &[f64]) -> [f64; 6] {
    let b = b_matrix(geom, ip);
    std::array::from_fn(|i| (0..3 * geom.nodes).map(|j| b[i][j] * ue[j]).sum())
}

/// The 6 × 24 B at Gauss point `ip` (module text).
fn b_matrix(geom: &ElementGeometry, ip: usize) -> [[f64; NE]; 6] {
    let (d, n, r) = (&geom.dndx[ip], &geom.shape[ip], geom.x[ip][0]);
    let mut b = [[0.0; NE]; 6];
    for a in 0..geom.nodes {
        let (ur, uz, ut) = (3 * a, 3 * a + 1, 3 * a + 2);
        b[0][ur] = d[a][0];
        b[1][uz] = d[a][1];
        b[2][ur] = d[a][1];
        b[2][uz] = d[a][0];
        b[3][ur] = n[a] / r;
        b[4][ut] = d[a][0] - n[a] / r;
        b[5][ut] = d[a][1];
    }
    b
}

/// Internal force and (optionally) tangent of one element with twist (24
/// dofs; `ke` row-major 24 × 24): the module's fᵉ and Kᵉ with the
/// algorithmic tangent, the continuum C_ep at the committed state
/// ([`VonMises::continuum_tangent_6`](crate::physics::material::VonMises::continuum_tangent_6)) or the elastic D. Errors name the
/// Gauss point.
#[allow(clippy::too_many_arguments)]
pub fn forces(
    geom: &ElementGeometry,
    mats: PointMaterials<'_>,
    thermal: &[f64],
    ue: &[f64],
    committed: &[PointState],
    trial: &mut [PointState],
    response: Response,
    tangent: Option<Tangent>,
    fe: &mut [f64],
    ke: &mut [f64],
) -> Result<(), String> {
    let ne = 3 * geom.nodes;
    fe.fill(0.0);
    if tangent.is_some() {
        ke.fill(0.0);
    }
    for ip in 0..geom.n {
        let r = geom.x[ip][0];
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN is refused too
        if !(r > 0.0) {
            return Err(format!(
                "Gauss point {ip} at r = {r}: an axisymmetric element must lie at r ≥ 0"
            ));
        }
        let mat = mats.at(ip);
        let b = b_matrix(geom, ip);
        let eps: [f64; 6] = std::array::from_fn(|i| (0..ne).map(|j| b[i][j] * ue[j]).sum());
        let eps = super::solid::less_thermal(eps, thermal[ip]);
        let (state, c_alg) = match response {
            Response::Plastic => mat.update_twist(&committed[ip], &eps),
            Response::ElasticOnly => (
                mat.elastic_state_twist(&committed[ip], &eps),
                mat.elastic_matrix_6(),
            ),
        };
        trial[ip] = state;
        let (dv, s) = (geom.dv[ip], &state.stress);
        for (j, f) in fe.iter_mut().enumerate().take(ne) {
            *f += dv * (0..6).map(|i| b[i][j] * s[i]).sum::<f64>();
        }
        if let Some(t) = tangent {
            let c = match t {
                Tangent::Consistent => c_alg,
                Tangent::Continuum => mat.continuum_tangent_6(&committed[ip]),
                Tangent::Elastic => mat.elastic_matrix_6(),
            };
            add_btcb(&b, ne, &c, dv, ke);
        }
    }
    Ok(())
}

/// ke += Bᵀ C B dv for the 6-row B.
fn add_btcb(b: &[[f64; NE]; 6], ne: usize, c: &Matrix6<f64>, dv: f64, ke: &mut [f64]) {
    let mut cb = [[0.0f64; NE]; 6];
    for (i, row) in cb.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate().take(ne) {
            *v = (0..6).map(|k| c[(i, k)] * b[k][j]).sum();
        }
    }
    for p in 0..ne {
        for q in 0..ne {
            ke[p * ne + q] += dv * (0..6).map(|i| b[i][p] * cb[i][q]).sum::<f64>();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numbers::fd;
    use crate::physics::element::family::Family;
    use crate::physics::element::q8;
    use crate::physics::element::Section;
    use crate::physics::material::Plane;
    use crate::physics::material::VonMises;

    /// A distorted element away from the axis, curved edges included: its
    /// node coordinates and geometry.
    fn element() -> ([[f64; 2]; 8], ElementGeometry) {
        let mut x = [[0.0; 2]; 8];
        for (a, xi) in q8::NODE_XI.iter().enumerate() {
            x[a] = [
                6.0 + 2.0 * xi[0] + 0.3 * xi[1] + 0.1 * xi[0] * xi[1],
                1.0 + 1.5 * xi[1] - 0.2 * xi[0] + 0.15 * xi[0] * xi[0],
            ];
        }
        let section = Section {
            axisymmetric: true,
            thickness: 1.0,
        };
        let g = ElementGeometry::with_section(Family::Q8, &x, &q8::gauss_3x3(), &section).unwrap();
        (x, g)
    }

    fn geometry() -> ElementGeometry {
        element().1
    }

    fn eval(
        geom: &ElementGeometry,
        m: &VonMises,
        ue: &[f64; NE],
        committed: &[PointState],
        tangent: Option<Tangent>,
    ) -> ([f64; NE], Vec<f64>, Vec<PointState>) {
        let (mut fe, mut ke) = ([0.0; NE], vec![0.0; NE * NE]);
        let mut trial = committed.to_vec();
        forces(
            geom,
            m.into(),
            &[0.0; 9],
            ue,
            committed,
            &mut trial,
            Response::Plastic,
            tangent,
            &mut fe,
            &mut ke,
        )
        .unwrap();
        (fe, ke, trial)
    }

    #[test]
    fn stiffness_is_the_derivative_of_the_internal_force() {
        let geom = geometry();
        for h in [0.0, 5000.0] {
            let m = VonMises::new(200000.0, 0.3, 250.0, h, Plane::Axisymmetric).unwrap();
            let ue: [f64; NE] = std::array::from_fn(|i| {
                4e-3 * ((i as f64 * 0.77).sin() + 0.3 * (i as f64 * 1.3).cos())
            });
            // a committed plastic state, then a further strain
            let half: [f64; NE] = std::array::from_fn(|i| 0.6 * ue[i]);
            let committed = eval(&geom, &m, &half, &[PointState::default(); 9], None).2;
            let (_, ke, trial) = eval(&geom, &m, &ue, &committed, Some(Tangent::Consistent));
            let plastic = trial.iter().filter(|g| g.yielding).count();
            assert!(plastic >= 5, "H = {h}: only {plastic} plastic Gauss points");
            let kmax = ke.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let d = 1e-9;
            let jac = fd::central_jacobian(
                |u| {
                    eval(&geom, &m, u.try_into().unwrap(), &committed, None)
                        .0
                        .to_vec()
                },
                &ue,
                d,
            );
            let worst = fd::worst(&jac, |i, j| ke[i * NE + j], fd::Scale::Of(kmax));
            assert!(
                worst.ratio < 1e-6,
                "H = {h}: tangent against finite differences {worst}"
            );
            // the consistent tangent is symmetric (associated flow)
            for i in 0..NE {
                for j in 0..i {
                    assert!((ke[i * NE + j] - ke[j * NE + i]).abs() <= 1e-9 * kmax);
                }
            }
        }
    }

    #[test]
    fn rigid_motions_strain_nothing_and_the_plane_part_is_the_axisymmetric_element() {
        let m = VonMises::new(200000.0, 0.3, 250.0, 0.0, Plane::Axisymmetric).unwrap();
        let (x, geom) = element();
        // rotation about the axis u_θ = ω r and translation along it u_z = c:
        // u_θ = Σ N_a ω r_a = ω r exactly (isoparametric), so γ_rθ = ω − ω = 0
        let mut ue = [0.0; NE];
        for a in 0..8 {
            ue[3 * a + 1] = 0.25;
            ue[3 * a + 2] = 1e-2 * x[a][0];
        }
        for ip in 0..geom.n {
            let e = strain(&geom, ip, &ue);
            assert!(e.iter().all(|e| e.abs() < 1e-15), "{e:?}");
        }
        // the 16-dof element's stiffness is the u_r, u_z block of this one
        // (elastic: twist and in-plane strains decouple)
        let ue = [0.0; NE];
        let (_, ke, _) = eval(
            &geom,
            &m,
            &ue,
            &[PointState::default(); 9],
            Some(Tangent::Elastic),
        );
        let (mut fe2, mut ke2) = ([0.0; 16], [0.0; 256]);
        let mut trial = vec![PointState::default(); 9];
        crate::physics::element::solid::axisymmetric_forces(
            &geom,
            (&m).into(),
            &[0.0; 9],
            &[0.0; 16],
            &[PointState::default(); 9],
            &mut trial,
            Response::Plastic,
            Some(Tangent::Elastic),
            &mut fe2,
            &mut ke2,
        )
        .unwrap();
        let kmax = ke2.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for a in 0..8 {
            for b in 0..8 {
                for (ci, cj) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                    let k3 = ke[(3 * a + ci) * NE + 3 * b + cj];
                    let k2 = ke2[(2 * a + ci) * 16 + 2 * b + cj];
                    assert!((k3 - k2).abs() <= 1e-12 * kmax);
                }
                for c in 0..2 {
                    assert_eq!(ke[(3 * a + 2) * NE + 3 * b + c], 0.0);
                    assert_eq!(ke[(3 * a + c) * NE + 3 * b + 2], 0.0);
                }
            }
        }
    }
}
