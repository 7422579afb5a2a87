//! Radial return of von Mises plasticity with linear isotropic hardening (paper
//! eqs 3.8-3.11; Simo & Hughes 1998, box 3.2) in the four non-zero components of
//! a plane or axisymmetric strain, and its consistent (algorithmic) tangent. One
//! function for plane strain and axisymmetry; plane stress has its own return
//! (`plane_stress`).
//!
//! The strain is [ε_xx, ε_yy, γ_xy, ε_zz] (engineering shear) with the
//! out-of-plane ε_zz given: 0 in plane strain, the hoop strain ε_θθ = u_r / r in
//! axisymmetry (x = r, y = z). With it given, the 3D return applies unchanged.
//!
//! Closed form for linear hardening:
//! ```text
//!   εᵉ = ε − εᵖₙ,   sᵗʳ = 2G dev εᵉ,   p = K tr εᵉ,   qᵗʳ = √(3/2 sᵗʳ:sᵗʳ)
//!   f = qᵗʳ − σ_y(ε̄ᵖₙ) ≤ 0: elastic, σ = sᵗʳ + p 1
//!   Δγ = f / (3G + H),  s = (1 − 3GΔγ/qᵗʳ) sᵗʳ,  εᵖ += Δγ (3/2) sᵗʳ/qᵗʳ,  ε̄ᵖ += Δγ
//!   C_alg = K 1⊗1 + 2G(1 − 3GΔγ/qᵗʳ) I_dev + 6G²(Δγ/qᵗʳ − 1/(3G + H)) N̂⊗N̂,  N̂ = sᵗʳ/‖sᵗʳ‖
//! ```
//! The continuum tangent C_ep (eq. 3.13) is `VonMises::continuum_tangent_4`.
//!
//! Component order of the strain, the stress ([`PointState::stress`]) and the
//! returned 4×4 tangents: xx, yy, xy, zz (rr, zz, rz, θθ in axisymmetry). Inside
//! this file the 3D Voigt order is xx, yy, zz, xy (as `elastic_3d` and
//! `continuum_3d`).

use super::{elastic_3d, PointState, VonMises};
use nalgebra::Matrix4;

/// Position of each external component (xx, yy, xy, zz) in the Voigt order
/// (xx, yy, zz, xy) of the 3D matrices.
pub(super) const VOIGT: [usize; 4] = [0, 1, 3, 2];

/// A 3D Voigt (xx, yy, zz, xy) matrix in the external order (xx, yy, xy, zz).
pub(super) fn external(d: &Matrix4<f64>) -> Matrix4<f64> {
    Matrix4::from_fn(|i, j| d[(VOIGT[i], VOIGT[j])])
}

/// Return mapping from the committed state `c` for the total strain
/// [ε_xx, ε_yy, γ_xy, ε_zz] (ε_zz = 0 in plane strain, ε_θθ in axisymmetry);
/// the new state and the algorithmic tangent dσ/dε, 4×4 in that order.
pub(super) fn update(
    m: &VonMises,
    c: &PointState,
    strain: &[f64; 4],
) -> (PointState, Matrix4<f64>) {
    let (g, k, h) = (m.shear_modulus(), m.bulk_modulus(), m.hardening);
    // committed plastic strain: xx, yy, xy (tensor), zz
    let ep = c.plastic_strain;
    // elastic strain, Voigt xx, yy, zz, xy (tensor shear)
    let ee = [
        strain[0] - ep[0],
        strain[1] - ep[1],
        strain[3] - ep[3],
        0.5 * strain[2] - ep[2],
    ];
    let vol = ee[0] + ee[1] + ee[2];
    let st: [f64; 4] =
        std::array::from_fn(|i| 2.0 * g * if i < 3 { ee[i] - vol / 3.0 } else { ee[i] });
    let norm = (st[0] * st[0] + st[1] * st[1] + st[2] * st[2] + 2.0 * st[3] * st[3]).sqrt();
    let q = 1.5f64.sqrt() * norm;
    let sy = m.current_yield(c);
    let f = q - sy;
    let pressure = k * vol;
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // !(x > tol) is meant to be true for NaN
    if !(f > 1e-12 * sy) {
        let state = PointState {
            stress: [
                st[0] + pressure,
                st[1] + pressure,
                st[3],
                st[2] + pressure,
                0.0,
                0.0,
            ],
            plastic_strain: ep,
            peeq: c.peeq,
            yielding: false,
        };
        return (state, external(&elastic_3d(g, k)));
    }
    let dgamma = f / (3.0 * g + h);
    let beta = 1.0 - 3.0 * g * dgamma / q;
    let s: [f64; 4] = std::array::from_fn(|i| beta * st[i]);
    let flow: [f64; 4] = std::array::from_fn(|i| dgamma * 1.5 * st[i] / q);
    let state = PointState {
        stress: [
            s[0] + pressure,
            s[1] + pressure,
            s[3],
            s[2] + pressure,
            0.0,
            0.0,
        ],
        plastic_strain: [
            ep[0] + flow[0],
            ep[1] + flow[1],
            ep[2] + flow[3],
            ep[3] + flow[2],
            ep[4],
            ep[5],
        ],
        peeq: c.peeq + dgamma,
        yielding: true,
    };
    let n: [f64; 4] = std::array::from_fn(|i| st[i] / norm);
    (state, external(&algorithmic(g, k, h, beta, dgamma / q, &n)))
}

/// C_alg in Voigt (xx, yy, zz, xy), engineering shear strain; `dg_q` = Δγ/qᵗʳ,
/// `n` the unit deviatoric trial direction (shear as tensor component).
fn algorithmic(g: f64, k: f64, h: f64, beta: f64, dg_q: f64, n: &[f64; 4]) -> Matrix4<f64> {
    let a = 6.0 * g * g * (dg_q - 1.0 / (3.0 * g + h));
    Matrix4::from_fn(|i, j| {
        let normal = i < 3 && j < 3;
        let identity = match (i == j, i < 3) {
            (true, true) => 1.0,
            (true, false) => 0.5,
            _ => 0.0,
        };
        let idev = identity - if normal { 1.0 / 3.0 } else { 0.0 };
        let vol = if normal { k } else { 0.0 };
        vol + 2.0 * g * beta * idev + a * n[i] * n[j]
    })
}

/// Stress from the elastic law alone for the total strain [ε_xx, ε_yy, γ_xy,
/// ε_zz], keeping the committed plastic strain: σ = D (ε − εᵖ).
pub(super) fn elastic(m: &VonMises, c: &PointState, strain: &[f64; 4]) -> PointState {
    let ep = &c.plastic_strain;
    let ee = nalgebra::Vector4::new(
        strain[0] - ep[0],
        strain[1] - ep[1],
        strain[2] - 2.0 * ep[2],
        strain[3] - ep[3],
    );
    let s = m.elastic_matrix_4() * ee;
    PointState {
        stress: [s[0], s[1], s[2], s[3], 0.0, 0.0],
        plastic_strain: *ep,
        peeq: c.peeq,
        yielding: false,
    }
}
