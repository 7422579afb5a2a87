//! Von Mises plasticity with linear isotropic hardening on all six stress
//! components of an axisymmetric body with twist (x = r, y = z and the
//! circumferential displacement u_θ): the radial return (Simo & Hughes 1998,
//! box 3.2; paper eqs 3.8-3.11) in full 3D, and its consistent tangent
//! (Simo & Taylor 1985; Simo & Hughes eq. 3.3.20).
//!
//! The strain is [ε_rr, ε_zz, γ_rz, ε_θθ, γ_rθ, γ_zθ] (engineering shear),
//! every component given by the element: no component is condensed, so the
//! 3D return applies unchanged, and with γ_rθ = γ_zθ = 0 it is the
//! four-component return of `radial` (a unit test checks it to round-off).
//!
//! ```text
//!   εᵉ = ε − εᵖₙ,   sᵗʳ = 2G dev εᵉ,   p = K tr εᵉ,   qᵗʳ = √(3/2 sᵗʳ:sᵗʳ)
//!   f = qᵗʳ − σ_y(ε̄ᵖₙ) ≤ 0: elastic, σ = sᵗʳ + p 1
//!   Δγ = f / (3G + H),  s = (1 − 3GΔγ/qᵗʳ) sᵗʳ,  εᵖ += Δγ (3/2) sᵗʳ/qᵗʳ,  ε̄ᵖ += Δγ
//!   C_alg = K 1⊗1 + 2G(1 − 3GΔγ/qᵗʳ) I_dev + 6G²(Δγ/qᵗʳ − 1/(3G + H)) N̂⊗N̂,  N̂ = sᵗʳ/‖sᵗʳ‖
//!   C_ep  = K 1⊗1 + 2G I_dev − 6G²/(3G + H) N̂⊗N̂   (the continuum tangent, eq. 3.13)
//! ```
//! s:s counts each shear component twice (s_rz² + s_zr², ...). Inside this
//! file the 3D Voigt order is (rr, zz, θθ, rz, rθ, zθ), normals first, shear
//! as tensor components; the matrices are returned in the external order.

use super::{PointState, VonMises};
use nalgebra::Matrix6;

/// Position of each external component (rr, zz, rz, θθ, rθ, zθ) in the Voigt
/// order (rr, zz, θθ, rz, rθ, zθ).
const VOIGT: [usize; 6] = [0, 1, 3, 2, 4, 5];

/// A Voigt-ordered matrix in the external order.
fn external(d: &Matrix6<f64>) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| d[(VOIGT[i], VOIGT[j])])
}

/// K 1⊗1 + 2G b I_dev + a N̂⊗N̂ in Voigt order, engineering shear strain
/// (a shear column of I_dev is ½: dε_ij/dγ_ij); `n` the unit deviatoric
/// direction, shear as tensor components.
fn voigt_tangent(g: f64, k: f64, b: f64, a: f64, n: &[f64; 6]) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| {
        let normal = i < 3 && j < 3;
        let identity = match (i == j, i < 3) {
            (true, true) => 1.0,
            (true, false) => 0.5,
            _ => 0.0,
        };
        let idev = identity - if normal { 1.0 / 3.0 } else { 0.0 };
        let vol = if normal { k } else { 0.0 };
        vol + 2.0 * g * b * idev + a * n[i] * n[j]
    })
}

/// The 6×6 isotropic elastic matrix in the external order.
pub(super) fn elastic_matrix(g: f64, k: f64) -> Matrix6<f64> {
    external(&voigt_tangent(g, k, 1.0, 0.0, &[0.0; 6]))
}

/// The elastic strain in Voigt order (tensor shear) from the total strain
/// (external order, engineering shear) and the committed plastic strain
/// ([`PointState::plastic_strain`]: rr, zz, rz, θθ, rθ, zθ, tensor shear).
fn elastic_strain(strain: &[f64; 6], ep: &[f64; 6]) -> [f64; 6] {
    [
        strain[0] - ep[0],
        strain[1] - ep[1],
        strain[3] - ep[3],
        0.5 * strain[2] - ep[2],
        0.5 * strain[4] - ep[4],
        0.5 * strain[5] - ep[5],
    ]
}

/// The stress in the external order from a Voigt deviator and the pressure.
fn external_stress(s: &[f64; 6], p: f64) -> [f64; 6] {
    [s[0] + p, s[1] + p, s[3], s[2] + p, s[4], s[5]]
}

/// ‖s‖ of a Voigt deviator (each shear counted twice).
fn norm(s: &[f64; 6]) -> f64 {
    (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]))
        .sqrt()
}

/// Return mapping from the committed state `c` for the total strain
/// [ε_rr, ε_zz, γ_rz, ε_θθ, γ_rθ, γ_zθ]: the new state and the algorithmic
/// tangent dσ/dε, 6×6 in that order.
pub(super) fn update(
    m: &VonMises,
    c: &PointState,
    strain: &[f64; 6],
) -> (PointState, Matrix6<f64>) {
    let (g, k, h) = (m.shear_modulus(), m.bulk_modulus(), m.hardening);
    let ep = c.plastic_strain;
    // trial state
    let ee = elastic_strain(strain, &ep);
    let vol = ee[0] + ee[1] + ee[2];
    let st: [f64; 6] =
        std::array::from_fn(|i| 2.0 * g * if i < 3 { ee[i] - vol / 3.0 } else { ee[i] });
    let nrm = norm(&st);
    let q = 1.5f64.sqrt() * nrm;
    let sy = m.current_yield(c);
    let f = q - sy;
    let pressure = k * vol;
    // elastic update
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // !(x > tol) is meant to be true for NaN
    if !(f > 1e-12 * sy) {
        let state = PointState {
            stress: external_stress(&st, pressure),
            plastic_strain: ep,
            peeq: c.peeq,
            yielding: false,
        };
        return (state, elastic_matrix(g, k));
    }
    // plastic correction, closed form for linear hardening
    let dgamma = f / (3.0 * g + h);
    let beta = 1.0 - 3.0 * g * dgamma / q;
    let s: [f64; 6] = std::array::from_fn(|i| beta * st[i]);
    let flow: [f64; 6] = std::array::from_fn(|i| dgamma * 1.5 * st[i] / q);
    let state = PointState {
        stress: external_stress(&s, pressure),
        plastic_strain: [
            ep[0] + flow[0],
            ep[1] + flow[1],
            ep[2] + flow[3],
            ep[3] + flow[2],
            ep[4] + flow[4],
            ep[5] + flow[5],
        ],
        peeq: c.peeq + dgamma,
        yielding: true,
    };
    // consistent tangent
    let n: [f64; 6] = std::array::from_fn(|i| st[i] / nrm);
    let a = 6.0 * g * g * (dgamma / q - 1.0 / (3.0 * g + h));
    (state, external(&voigt_tangent(g, k, beta, a, &n)))
}

/// Stress from the elastic law alone, keeping the committed plastic strain:
/// σ = D (ε − εᵖ).
pub(super) fn elastic(m: &VonMises, c: &PointState, strain: &[f64; 6]) -> PointState {
    let (g, k) = (m.shear_modulus(), m.bulk_modulus());
    let ee = elastic_strain(strain, &c.plastic_strain);
    let vol = ee[0] + ee[1] + ee[2];
    let s: [f64; 6] =
        std::array::from_fn(|i| 2.0 * g * if i < 3 { ee[i] - vol / 3.0 } else { ee[i] });
    PointState {
        stress: external_stress(&s, k * vol),
        plastic_strain: c.plastic_strain,
        peeq: c.peeq,
        yielding: false,
    }
}

/// The continuum tangent C_ep (eq. 3.13) at the stress σ (external order).
pub(super) fn continuum(m: &VonMises, stress: &[f64; 6]) -> Matrix6<f64> {
    let (g, k, h) = (m.shear_modulus(), m.bulk_modulus(), m.hardening);
    let p = (stress[0] + stress[1] + stress[3]) / 3.0;
    let s = [
        stress[0] - p,
        stress[1] - p,
        stress[3] - p,
        stress[2],
        stress[4],
        stress[5],
    ];
    let nrm = norm(&s);
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // a NaN stress gives D too
    if !(nrm > 0.0) {
        return elastic_matrix(g, k);
    }
    let n: [f64; 6] = std::array::from_fn(|i| s[i] / nrm);
    external(&voigt_tangent(g, k, 1.0, -6.0 * g * g / (3.0 * g + h), &n))
}

#[cfg(test)]
mod tests {
    use super::super::Plane;
    use super::*;
    use crate::numbers::fd;

    fn mat(h: f64) -> VonMises {
        VonMises::new(200000.0, 0.3, 250.0, h, Plane::Axisymmetric).unwrap()
    }

    /// Worst difference between the 6×6 algorithmic tangent and central
    /// differences of the stress, relative to the tangent's largest entry.
    fn fd_error(m: &VonMises, committed: &PointState, eps: [f64; 6]) -> fd::Mismatch {
        let (_, c) = update(m, committed, &eps);
        let scale = eps.iter().fold(1e-6f64, |a, v| a.max(v.abs()));
        let h = 1e-7 * scale;
        let jac = fd::central_jacobian(
            |e| {
                update(m, committed, e.try_into().unwrap())
                    .0
                    .stress
                    .to_vec()
            },
            &eps,
            h,
        );
        fd::worst(&jac, |i, j| c[(i, j)], fd::Scale::Of(c.amax()))
    }

    #[test]
    fn consistent_tangent_matches_finite_differences() {
        let paths = [
            [1e-4, -2e-5, 3e-5, 4e-5, 2e-5, -1e-5],         // elastic
            [0.0, 0.0, 0.0, 0.0, 3e-3, 0.0],                // torsion alone
            [1.0e-3, -0.3e-3, 0.2e-3, -0.4e-3, 1e-3, 5e-4], // just past yield
            [8e-3, -1e-3, 6e-3, 2e-3, -4e-3, 3e-3],         // deep plastic
            [-5e-3, 4e-3, -2e-3, 3e-3, 0.0, -6e-3],         // mixed signs
        ];
        let mut plastic = 0;
        for h in [0.0, 2000.0, 50000.0] {
            let m = mat(h);
            let pre = update(
                &m,
                &PointState::default(),
                &[2e-3, 0.0, 1e-3, -1e-3, 2e-3, 1e-3],
            )
            .0;
            assert!(pre.yielding);
            for c in [PointState::default(), pre] {
                for eps in paths {
                    plastic += usize::from(update(&m, &c, &eps).0.yielding);
                    let e = fd_error(&m, &c, eps);
                    assert!(e.ratio < 1e-6, "H={h} eps={eps:?}: FD error {e}");
                }
            }
        }
        assert!(
            plastic >= 18,
            "only {plastic} of the checked updates were plastic"
        );
    }

    #[test]
    fn without_twist_shear_it_is_the_four_component_return() {
        let m = mat(3000.0);
        let pre = m
            .update_axisymmetric(&PointState::default(), &[3e-3, -1e-3, 2e-3, 1e-3])
            .0;
        for c in [PointState::default(), pre] {
            for e in [
                [5e-3, -1e-3, 2e-3, 1e-3],
                [-4e-3, -4e-3, 1e-2, 0.0],
                [1e-4, 0.0, 0.0, 0.0],
            ] {
                let (a, ca) = m.update_axisymmetric(&c, &e);
                let (b, cb) = update(&m, &c, &[e[0], e[1], e[2], e[3], 0.0, 0.0]);
                assert_eq!(a.yielding, b.yielding);
                for i in 0..4 {
                    assert!(
                        (a.stress[i] - b.stress[i]).abs() < 1e-12 * 250.0,
                        "{a:?} {b:?}"
                    );
                    assert!((a.plastic_strain[i] - b.plastic_strain[i]).abs() < 1e-15);
                    for j in 0..4 {
                        assert!((ca[(i, j)] - cb[(i, j)]).abs() < 1e-9 * ca.amax());
                    }
                }
                assert_eq!(b.stress[4..], [0.0, 0.0]);
                assert!((a.peeq - b.peeq).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn pure_torsion_yields_at_tau_y_over_root_three_and_stays_on_the_surface() {
        // σ_rθ = G γ_rθ while elastic; von Mises yields at τ = σ_Y/√3, and
        // beyond it the stress stays on the surface q = σ_Y + H ε̄ᵖ
        let m = mat(10000.0);
        let g = m.shear_modulus();
        let gy = 250.0 / 3f64.sqrt() / g;
        let (s, _) = update(
            &m,
            &PointState::default(),
            &[0.0, 0.0, 0.0, 0.0, 0.9 * gy, 0.0],
        );
        assert!(!s.yielding && (s.stress[4] - 0.9 * gy * g).abs() < 1e-9 * 250.0);
        let (s, _) = update(
            &m,
            &PointState::default(),
            &[0.0, 0.0, 0.0, 0.0, 3.0 * gy, 0.0],
        );
        let q = VonMises::equivalent_stress(&s.stress);
        assert!(s.yielding && (q - (250.0 + 10000.0 * s.peeq)).abs() < 1e-9 * 250.0);
        assert!(s.stress[..4]
            .iter()
            .chain(&s.stress[5..])
            .all(|v| v.abs() < 1e-9));
        // the plastic shear strain accounts for the rest: γ = τ/G + 2 εᵖ_rθ
        assert!((3.0 * gy - s.stress[4] / g - 2.0 * s.plastic_strain[4]).abs() < 1e-12);
    }

    #[test]
    fn continuum_tangent_is_elastic_minus_the_normal_projection() {
        let m = mat(2000.0);
        let (s, _) = update(
            &m,
            &PointState::default(),
            &[4e-3, -1e-3, 2e-3, 1e-3, 3e-3, -2e-3],
        );
        let cep = m.continuum_tangent_6(&s);
        // along the flow direction (a deviatoric strain ∝ the stress
        // deviator) C_ep = D − 6G²/(3G+H) N̂⊗N̂ scales the elastic response
        // by 1 − 3G/(3G+H) = H/(3G+H)
        let p = (s.stress[0] + s.stress[1] + s.stress[3]) / 3.0;
        let dev = [
            s.stress[0] - p,
            s.stress[1] - p,
            s.stress[2],
            s.stress[3] - p,
            s.stress[4],
            s.stress[5],
        ];
        // engineering strain along the deviator: shear entries doubled
        let de = nalgebra::Vector6::from_fn(|i, _| {
            if [2, 4, 5].contains(&i) {
                2.0 * dev[i]
            } else {
                dev[i]
            }
        });
        let ds = cep * de;
        let dse = m.elastic_matrix_6() * de;
        let (g, h) = (m.shear_modulus(), 2000.0);
        let ratio = h / (3.0 * g + h);
        for i in 0..6 {
            assert!(
                (ds[i] - ratio * dse[i]).abs() < 1e-9 * dse.amax(),
                "{i}: {ds} vs {dse}"
            );
        }
    }
}
