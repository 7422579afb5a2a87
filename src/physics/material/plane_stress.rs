//! Plane-stress projected return mapping (Simo & Taylor 1986), σ_zz = 0 exactly.
//!
//! In the plane-stress subspace σ = [σxx, σyy, σxy]:
//! ```text
//!   φ = ½ σᵀPσ − ⅓ σ_y²,  P = ⅓[2 −1 0; −1 2 0; 0 0 6],  εᵖ̇ = γ̇ P σ
//!   σ(Δγ) = Ξ(Δγ) (ε − εᵖₙ),  Ξ = [C⁻¹ + Δγ P]⁻¹
//!   f̄²(Δγ) = σᵀPσ = (σ₁₁+σ₂₂)²/6 / (1 + EΔγ/(3(1−ν)))²
//!             + (½(σ₁₁−σ₂₂)² + 2σ₁₂²)ᵗʳ / (1 + 2GΔγ)²
//!   ε̄ᵖ = ε̄ᵖₙ + Δγ √(2/3 f̄²),  solve ½ f̄² − ⅓ σ_y(ε̄ᵖ)² = 0 for Δγ.
//!   C_alg = Ξ − (ΞPσ)(ΞPσ)ᵀ / (σᵀPΞPσ + b/θ),
//!   b = ⅔ σ_y H √(⅔ f̄²),  θ = 1 − (4/9) σ_y H Δγ / √(⅔ f̄²)
//! ```

use super::{PointState, ReturnMapError, VonMises};
use nalgebra::{Matrix3, Vector3};

fn p_matrix() -> Matrix3<f64> {
    Matrix3::new(2.0, -1.0, 0.0, -1.0, 2.0, 0.0, 0.0, 0.0, 6.0) / 3.0
}

/// ½ f̄²(Δγ) − ⅓ σ_y² and its derivative.
struct Consistency {
    a1: f64, // (σxx+σyy)²/6 at trial
    a2: f64, // ½(σxx−σyy)² + 2σxy² at trial
    c1: f64, // E/(3(1−ν))
    c2: f64, // 2G
    sy0: f64,
    h: f64,
    peeq: f64,
}

impl Consistency {
    fn fbar2(&self, dg: f64) -> (f64, f64) {
        let (d1, d2) = (1.0 + self.c1 * dg, 1.0 + self.c2 * dg);
        let f2 = self.a1 / (d1 * d1) + self.a2 / (d2 * d2);
        let df2 = -2.0 * self.a1 * self.c1 / d1.powi(3) - 2.0 * self.a2 * self.c2 / d2.powi(3);
        (f2, df2)
    }

    fn phi(&self, dg: f64) -> (f64, f64) {
        let (f2, df2) = self.fbar2(dg);
        let s = (2.0 / 3.0 * f2).sqrt();
        let ds = if s > 0.0 { df2 / (3.0 * s) } else { 0.0 };
        let sy = self.sy0 + self.h * (self.peeq + dg * s);
        let dsy = self.h * (s + dg * ds);
        (0.5 * f2 - sy * sy / 3.0, 0.5 * df2 - 2.0 / 3.0 * sy * dsy)
    }
}

pub(super) fn update(
    m: &VonMises,
    c: &PointState,
    strain: &[f64; 3],
) -> Result<(PointState, Matrix3<f64>), ReturnMapError> {
    let (e, nu, g, h) = (m.young, m.poisson, m.shear_modulus(), m.hardening);
    let ep = c.plastic_strain;
    let ee = Vector3::new(
        strain[0] - ep[0],
        strain[1] - ep[1],
        strain[2] - 2.0 * ep[2],
    );
    let d = m.elastic_matrix();
    let st = d * ee;
    let p = p_matrix();
    let sy_n = m.current_yield(c);
    let f_trial = 0.5 * st.dot(&(p * st)) - sy_n * sy_n / 3.0;
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // !(x > tol) is meant to be true for NaN
    if !(f_trial > 1e-12 * sy_n * sy_n) {
        let state = PointState {
            stress: [st[0], st[1], st[2], 0.0, 0.0, 0.0],
            plastic_strain: ep,
            peeq: c.peeq,
            yielding: false,
        };
        return Ok((state, d));
    }
    let phi = Consistency {
        a1: (st[0] + st[1]).powi(2) / 6.0,
        a2: 0.5 * (st[0] - st[1]).powi(2) + 2.0 * st[2] * st[2],
        c1: e / (3.0 * (1.0 - nu)),
        c2: 2.0 * g,
        sy0: m.yield_stress,
        h,
        peeq: c.peeq,
    };
    let dg = solve_dgamma(&phi, sy_n)?;
    // stress, plastic strain, tangent
    let cinv = d.try_inverse().unwrap_or_else(Matrix3::zeros);
    let xi = (cinv + dg * p)
        .try_inverse()
        .ok_or_else(|| ReturnMapError {
            iterations: 0,
            residual: f64::NAN,
            reason: "singular modulus Ξ".into(),
        })?;
    let s = xi * ee;
    let (f2, _) = phi.fbar2(dg);
    let sq = (2.0 / 3.0 * f2).sqrt();
    let peeq = c.peeq + dg * sq;
    let sy = m.yield_stress + h * peeq;
    let dep = dg * (p * s); // engineering shear in the third entry
    let n = xi * (p * s);
    let b = 2.0 / 3.0 * sy * h * sq;
    let theta = 1.0 - 4.0 / 9.0 * sy * h * dg / sq;
    let denom = (p * s).dot(&n) + b / theta;
    let c_alg = xi - n * n.transpose() / denom;
    let pe = [ep[0] + dep[0], ep[1] + dep[1], ep[2] + 0.5 * dep[2], 0.0];
    let state = PointState {
        stress: [s[0], s[1], s[2], 0.0, 0.0, 0.0],
        plastic_strain: [pe[0], pe[1], pe[2], -(pe[0] + pe[1]), 0.0, 0.0],
        peeq,
        yielding: true,
    };
    Ok((state, c_alg))
}

/// Safeguarded Newton for φ(Δγ) = 0 on [0, ∞): φ(0) > 0 and φ decreases.
fn solve_dgamma(phi: &Consistency, sy_n: f64) -> Result<f64, ReturnMapError> {
    let scale = sy_n * sy_n;
    let (mut lo, mut hi) = (0.0, f64::INFINITY);
    let mut dg = 0.0;
    let mut r = phi.phi(dg);
    for it in 0..60 {
        if r.0.abs() <= 1e-13 * scale {
            return Ok(dg);
        }
        if r.0 > 0.0 {
            lo = dg;
        } else {
            hi = dg;
        }
        let mut next = if r.1 < 0.0 { dg - r.0 / r.1 } else { f64::NAN };
        if !(next > lo && next < hi) {
            next = if hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                2.0 * lo.max(1e-12)
            };
        }
        dg = next;
        r = phi.phi(dg);
        if !r.0.is_finite() {
            return Err(ReturnMapError {
                iterations: it + 1,
                residual: r.0,
                reason: "non-finite consistency residual".into(),
            });
        }
    }
    Err(ReturnMapError {
        iterations: 60,
        residual: r.0 / scale,
        reason: "plane-stress consistency equation for Δγ did not converge".into(),
    })
}
