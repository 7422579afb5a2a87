//! Plane-strain radial return (ε_zz = 0), closed form for linear hardening.
//!
//! ```text
//!   sᵗʳ = 2G dev(ε − εᵖₙ),  qᵗʳ = √(3/2 sᵗʳ:sᵗʳ),  f = qᵗʳ − σ_y(ε̄ᵖₙ)
//!   Δγ = f / (3G + H),  s = (1 − 3GΔγ/qᵗʳ) sᵗʳ,  εᵖ += Δγ (3/2) sᵗʳ/qᵗʳ
//!   C = K 1⊗1 + 2G(1 − 3GΔγ/qᵗʳ) I_dev + 6G²(Δγ/qᵗʳ − 1/(3G + H)) N̂⊗N̂
//! ```

use super::{elastic_3d, PointState, VonMises};
use nalgebra::Matrix3;

/// Voigt order inside this file: xx, yy, zz, xy (tensor xy for strains).
pub(super) fn update(
    m: &VonMises,
    c: &PointState,
    strain: &[f64; 3],
) -> (PointState, Matrix3<f64>) {
    let (g, k, h) = (m.shear_modulus(), m.bulk_modulus(), m.hardening);
    let ep = c.plastic_strain; // xx yy xy zz
    let ee = [
        strain[0] - ep[0],
        strain[1] - ep[1],
        -ep[3],
        0.5 * strain[2] - ep[2],
    ];
    let vol = ee[0] + ee[1] + ee[2];
    let dev = [
        ee[0] - vol / 3.0,
        ee[1] - vol / 3.0,
        ee[2] - vol / 3.0,
        ee[3],
    ];
    let st: [f64; 4] = std::array::from_fn(|i| 2.0 * g * dev[i]);
    let norm = (st[0] * st[0] + st[1] * st[1] + st[2] * st[2] + 2.0 * st[3] * st[3]).sqrt();
    let q = (1.5f64).sqrt() * norm;
    let sy = m.current_yield(c);
    let f = q - sy;
    let pressure = k * vol;
    let idx = [0usize, 1, 3];
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // !(x > tol) is meant to be true for NaN
    if !(f > 1e-12 * sy) {
        let s = [st[0] + pressure, st[1] + pressure, st[3], st[2] + pressure];
        let d = elastic_3d(g, k);
        let state = PointState {
            stress: s,
            plastic_strain: ep,
            peeq: c.peeq,
            yielding: false,
        };
        return (state, Matrix3::from_fn(|i, j| d[(idx[i], idx[j])]));
    }
    let dgamma = f / (3.0 * g + h);
    let beta = 1.0 - 3.0 * g * dgamma / q;
    let n: [f64; 4] = std::array::from_fn(|i| st[i] / norm);
    let s: [f64; 4] = std::array::from_fn(|i| beta * st[i]);
    let flow: [f64; 4] = std::array::from_fn(|i| dgamma * 1.5 * st[i] / q);
    let state = PointState {
        stress: [s[0] + pressure, s[1] + pressure, s[3], s[2] + pressure],
        plastic_strain: [
            ep[0] + flow[0],
            ep[1] + flow[1],
            ep[2] + flow[3],
            ep[3] + flow[2],
        ],
        peeq: c.peeq + dgamma,
        yielding: true,
    };
    // algorithmic tangent in Voigt (xx, yy, zz, xy), engineering shear strain
    let mut d = nalgebra::Matrix4::zeros();
    let a = 6.0 * g * g * (dgamma / q - 1.0 / (3.0 * g + h));
    for i in 0..4 {
        for j in 0..4 {
            let idev = if i == j {
                if i < 3 {
                    1.0
                } else {
                    0.5
                }
            } else {
                0.0
            } - if i < 3 && j < 3 { 1.0 / 3.0 } else { 0.0 };
            let vol = if i < 3 && j < 3 { k } else { 0.0 };
            d[(i, j)] = vol + 2.0 * g * beta * idev + a * n[i] * n[j];
        }
    }
    (state, Matrix3::from_fn(|i, j| d[(idx[i], idx[j])]))
}
