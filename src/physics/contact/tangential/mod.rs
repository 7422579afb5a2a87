//! Tangential interface law (paper sections 2.2, 2.4-2.6, Fig. 1), per unit area.
//!
//! ```text
//!   k_T^e = p_N^S / R                      elastic shear stiffness (2.6), MPa/µm
//!   p_T^Y = ρ μ_m p_N                       initial yield, ρ = 0.625 (2.18; 2.5 says ½)
//!   H = k_T^e k_T^p / (k_T^e − k_T^p)      hardening modulus (2.16)
//!   μ_F(κ) = μ_m [1 − (1 − β) e^{−n κ}]    slip-hardening friction (2.21)
//!   |p_T| ≤ Y(κ) = min(p_T^Y + H κ, μ_F(κ) p_N)      micro-slip, then macro-slip (2.22)
//! ```
//! p_T = k_T^e (u_T − u_T^p); κ = ∫|du_T^p| is the accumulated plastic slip. The yield
//! limit grows with κ only, so after unloading and reversal the response stays
//! elastic until |p_T| exceeds the highest value reached before (the memory of
//! section 2.2). A backward-Euler return mapping solves
//! `|p_T^tr| − k_T^e Δκ = Y(κ_n + Δκ)` and its consistent tangent gives
//! ∂p_T/∂u_T and the unsymmetric coupling ∂p_T/∂u_N (p_T^Y, H, k_T^e depend on p_N).
//!
//! Units: with p in MPa, R is such that p_N^S / R is in MPa/µm (the paper's R = 0.9,
//! S = 0.5 give 15.7 MPa/µm at 200 MPa); internally k_T^e = 1000 p_N^S / R MPa/mm.
//!
//! In place of R and S a measured table of k_T^e (MPa/µm) against p_N (MPa) may
//! be given ([`TangentialLaw::with_k_table`]): interpolated monotonically in p
//! (Fritsch-Butland cubic Hermite, [`super::table`]) so that k_T^e and dk_T^e/dp_N
//! are continuous for the coupling ∂p_T/∂u_N; below the first point
//! k ∝ p^{s₁} through it (s₁ = ln(k₂/k₁)/ln(p₂/p₁) clamped to [0, 1], the form of 2.6);
//! above the last point linear with the end slope.

use super::table::Monotone;
use std::sync::Arc;

mod jenkins;
mod kinematic;
pub(crate) mod params;
mod vector;
mod work;
pub use jenkins::Elements;
pub(crate) use kinematic::{Density, Stretch, MEMORY_POINTS};
pub(crate) use vector::SlipState2;
pub(crate) use work::{Side, Side2};

/// How the law remembers its slip history.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Memory {
    /// Section 2.2: the yield limit grows with the accumulated slip κ, so
    /// after a reversal nothing slips until |p_T| passes its earlier
    /// maximum (slip hardening, isotropic in p_T).
    #[default]
    Isotropic,
    /// Masing: the elastic range moves with the load, a reversal starts the
    /// first-loading curve scaled by two, nested loops close
    /// (`kinematic`).
    Kinematic,
}

/// The smallest Iwan exponent χ: at −0.99 the slip range φ is already 100
/// times the elastic slip μ p_N / k_T^e.
pub(crate) const CHI_MIN: f64 = -0.99;

/// The first-loading curve p_T(u_T) at constant p_N.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Backbone {
    /// The paper's two straight lines (Fig. 1): k_T^e to p_T^Y, k_T^p to μ p_N.
    #[default]
    Bilinear,
    /// An Iwan density of slip thresholds (Segalman 2005): (1 − spike) (1 + χ) η^χ
    /// on η ∈ [0, 1] plus a point mass `spike` at η = 1. The stiffness falls
    /// from k_T^e at once, the dissipation per cycle grows as the slip
    /// amplitude to the power 3 + χ from zero on (`kinematic`; against the
    /// force amplitude faster, docs/theory.md).
    Iwan { chi: f64, spike: f64 },
}

/// Parameters of the tangential law. `Clone` (not `Copy`): a k_table holds its points.
#[derive(Clone, Debug, PartialEq)]
pub struct TangentialLaw {
    /// R of 2.6 (NaN when `k_table` is given).
    pub r: f64,
    /// S of 2.6 (NaN when `k_table` is given).
    pub s: f64,
    /// k_T^e(p_N) in MPa/µm from a measured table, in place of p^S/R.
    pub k_table: Option<Arc<Monotone>>,
    /// k_T^p / k_T^e in [0, 1]; 1 = no micro-slip branch.
    pub kp_ratio: f64,
    pub mu: f64,
    pub beta: f64,
    /// Slip-hardening rate n, 1/mm.
    pub n: f64,
    /// ρ = p_T^Y / (μ_m p_N).
    pub(crate) yield_ratio: f64,
    pub memory: Memory,
    pub backbone: Backbone,
}

/// History of one spring: signed plastic slip and accumulated |slip|, mm;
/// under the kinematic memory the stretches of its Jenkins elements (all
/// zero under the isotropic one) and u_p = u_T − ∫ w e dη, the slip that
/// p_T / k_T^e does not explain.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SlipState {
    pub u_p: f64,
    pub kappa: f64,
    pub mem: Stretch,
}

/// Regime of a closed spring.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slip {
    Stick,
    MicroSlip,
    MacroSlip,
}

/// Result of one evaluation.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TangentialEval {
    pub p_t: f64,
    /// ∂p_T/∂u_T
    pub(crate) d_ut: f64,
    /// ∂p_T/∂u_N
    pub(crate) d_un: f64,
    pub state: SlipState,
    pub slip: Slip,
    pub(crate) mu_f: f64,
}

/// A return mapping that slipped: Δκ, κ = κ_n + Δκ, the limit Y(κ) with
/// ∂Y/∂κ and ∂Y/∂p_N, and whether the friction cap is the active branch.
#[derive(Clone, Copy, Debug)]
pub(super) struct Return {
    pub(crate) dkappa: f64,
    pub kappa: f64,
    pub y: f64,
    pub(crate) yk: f64,
    pub(crate) yp: f64,
    pub macro_slip: bool,
}

impl TangentialLaw {
    /// Checks every parameter; the message names the bad one.
    pub fn new(
        r: f64,
        s: f64,
        kp_ratio: f64,
        mu: f64,
        beta: f64,
        n: f64,
        yield_ratio: f64,
    ) -> Result<Self, String> {
        let pos = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!("{name} = {v} must be a positive number"))
            }
        };
        pos("r", r)?;
        pos("mu", mu)?;
        if !(s.is_finite() && (0.0..=1.0).contains(&s)) {
            return Err(format!("s = {s} must be in [0, 1]"));
        }
        if !(kp_ratio.is_finite() && (0.0..=1.0).contains(&kp_ratio)) {
            return Err(format!("kp_ratio = {kp_ratio} must be in [0, 1]"));
        }
        if !(beta.is_finite() && beta > 0.0 && beta <= 1.0) {
            return Err(format!("beta = {beta} must be in (0, 1]"));
        }
        if !(n.is_finite() && n >= 0.0) {
            return Err(format!("n = {n} must be a non-negative number (1/mm)"));
        }
        if !(yield_ratio.is_finite() && yield_ratio > 0.0 && yield_ratio <= 1.0) {
            return Err(format!("yield_ratio = {yield_ratio} must be in (0, 1]"));
        }
        Ok(TangentialLaw {
            r,
            s,
            k_table: None,
            kp_ratio,
            mu,
            beta,
            n,
            yield_ratio,
            memory: Memory::Isotropic,
            backbone: Backbone::Bilinear,
        })
    }

    /// The law with another memory and backbone. The Iwan backbone's χ in
    /// [−0.99, 1] and spike in [0, 1); slip-hardening friction (β < 1) only
    /// with the isotropic memory and the bilinear backbone, the case it
    /// was measured for (eq. 2.21).
    pub(crate) fn with_memory(
        mut self,
        memory: Memory,
        backbone: Backbone,
    ) -> Result<Self, String> {
        if let Backbone::Iwan { chi, spike } = backbone {
            // χ → −1 puts every threshold at zero: F(1) = (1+χ)/(2+χ) → 0 and
            // the slip range φ = μ p_N / (k F(1)) grows without bound
            if !(chi.is_finite() && (CHI_MIN..=1.0).contains(&chi)) {
                return Err(format!(
                    "chi = {chi} must be in [{CHI_MIN}, 1] (towards -1 every slip threshold goes to zero and the slip range φ = μ p_N / (k_T^e F(1)) without bound)"
                ));
            }
            if !(spike.is_finite() && (0.0..1.0).contains(&spike)) {
                return Err(format!("spike = {spike} must be in [0, 1)"));
            }
        }
        let plain = memory == Memory::Isotropic && backbone == Backbone::Bilinear;
        if self.beta != 1.0 && !plain {
            return Err(format!(
                "beta = {} (slip-hardening friction, eq. 2.21) is only for memory = \"isotropic\" with backbone = \"bilinear\": give beta = 1",
                self.beta
            ));
        }
        self.memory = memory;
        self.backbone = backbone;
        Ok(self)
    }

    /// The density of slip thresholds the kinematic memory uses.
    pub fn density(&self) -> Density {
        match self.backbone {
            Backbone::Iwan { chi, spike } => {
                let c = 1.0 - spike;
                Density {
                    c,
                    chi,
                    masses: [(1.0, spike), (1.0, 0.0)],
                    big_c: 1.0 / (1.0 - c / (chi + 2.0)),
                }
            }
            Backbone::Bilinear => {
                let (rho, kp) = (self.yield_ratio, self.kp_ratio);
                if kp == 0.0 {
                    // one element: elastic to ρ μ p_N, then slipping there
                    return Density {
                        c: 0.0,
                        chi: 0.0,
                        masses: [(1.0, 1.0), (1.0, 0.0)],
                        big_c: rho,
                    };
                }
                let big_c = rho + (1.0 - rho) / kp;
                Density {
                    c: 0.0,
                    chi: 0.0,
                    masses: [(rho / big_c, 1.0 - kp), (1.0, kp)],
                    big_c,
                }
            }
        }
    }

    /// The law with k_T^e from measured rows (p_N MPa, k_T^e MPa/µm) in place of
    /// p^S/R: at least 2 rows, pressures positive and strictly increasing,
    /// stiffnesses positive and non-decreasing, all finite. R and S become NaN.
    #[allow(clippy::too_many_arguments)] // the same parameters as `new`
    pub fn with_k_table(
        rows: &[(f64, f64)],
        kp_ratio: f64,
        mu: f64,
        beta: f64,
        n: f64,
        yield_ratio: f64,
    ) -> Result<Self, String> {
        let mut law = TangentialLaw::new(1.0, 0.0, kp_ratio, mu, beta, n, yield_ratio)?;
        // kept in MPa/µm (the messages quote the rows as given); ×1000 on evaluation
        let t = Monotone::new(rows, false, (0.0, 1.0), ("p_N", "k_T"))?;
        law.r = f64::NAN;
        law.s = f64::NAN;
        law.k_table = Some(Arc::new(t));
        Ok(law)
    }

    /// k_T^e and dk_T^e/dp_N at normal pressure p > 0, MPa/mm.
    pub fn elastic_stiffness(&self, p: f64) -> (f64, f64) {
        if let Some(t) = &self.k_table {
            let (k, dk) = t.eval(p);
            return (1000.0 * k, 1000.0 * dk);
        }
        let k = 1000.0 * p.powf(self.s) / self.r;
        (k, if self.s == 0.0 { 0.0 } else { self.s * k / p })
    }

    /// μ_F(κ) and dμ_F/dκ (2.21).
    pub fn friction(&self, kappa: f64) -> (f64, f64) {
        let e = (-self.n * kappa).exp();
        (
            self.mu * (1.0 - (1.0 - self.beta) * e),
            self.mu * (1.0 - self.beta) * self.n * e,
        )
    }

    /// Yield limit Y(κ) at pressure p, with ∂Y/∂κ, ∂Y/∂p and whether the
    /// friction cap (macro-slip) is the active branch.
    fn limit(&self, kappa: f64, p: f64, k: f64, dk: f64) -> (f64, f64, f64, bool) {
        if let Backbone::Iwan { chi, spike } = self.backbone {
            return self.iwan_limit(chi, spike, kappa, p, k, dk);
        }
        let (mu_f, dmu) = self.friction(kappa);
        let cap = (mu_f * p, dmu * p, mu_f);
        if self.kp_ratio >= 1.0 {
            return (cap.0, cap.1, cap.2, true);
        }
        let q = self.kp_ratio / (1.0 - self.kp_ratio);
        let (h, dh) = (k * q, dk * q);
        let y1 = self.yield_ratio * self.mu * p + h * kappa;
        if y1 < cap.0 {
            (y1, h, self.yield_ratio * self.mu + dh * kappa, false)
        } else {
            (cap.0, cap.1, cap.2, true)
        }
    }

    /// The Iwan backbone as an isotropic yield limit. First loading follows
    /// p_T = k φ F(x), x = u_T/φ ≤ 1, F(x) = c (x − x^{χ+2}/(χ+2)) + (1 − c) x
    /// (the density's integral, [`kinematic`]), whose plastic slip
    /// u_T − p_T/k = c φ x^{χ+2}/(χ+2) is κ; so
    ///
    /// ```text
    ///   Y(κ) = k φ x − k κ,   x = ((χ+2) κ / (c φ))^{1/(χ+2)},   κ < c φ/(χ+2)
    ///   Y(κ) = μ p_N beyond,  k φ = μ p_N / F(1),  F(1) = 1 − c/(χ+2)
    /// ```
    ///
    /// with ∂Y/∂κ = k (1/(c x^{χ+1}) − 1) and ∂Y/∂p_N through k φ ∝ p_N and
    /// φ'/φ = 1/p_N − k'/k.
    fn iwan_limit(
        &self,
        chi: f64,
        spike: f64,
        kappa: f64,
        p: f64,
        k: f64,
        dk: f64,
    ) -> (f64, f64, f64, bool) {
        let c = 1.0 - spike;
        let q = chi + 2.0;
        let f1 = 1.0 - c / q;
        let kphi = self.mu * p / f1;
        let phi = kphi / k;
        if kappa >= c * phi / q {
            return (self.mu * p, 0.0, self.mu, true);
        }
        if kappa <= 0.0 {
            // an infinite hardening slope, finite for the arithmetic
            return (0.0, 1e30 * k, 0.0, false);
        }
        let x = (q * kappa / (c * phi)).powf(1.0 / q);
        let y = kphi * x - k * kappa;
        let yk = k * (1.0 / (c * x.powf(chi + 1.0)) - 1.0);
        let yp = self.mu / f1 * x - kphi * x / q * (1.0 / p - dk / k) - dk * kappa;
        (y, yk, yp, false)
    }

    /// The kinematic memory's update ([`kinematic`]): the stretches shifted
    /// by the change of u_T since `committed` and clipped to |e| ≤ η φ,
    /// φ = μ p_N C / k_T^e; p_T = k_T^e ∫ w e dη with ∂p_T/∂u_T = k_T^e ×
    /// (weight that sticks) and ∂p_T/∂p_N = k' ∫ w e dη + k φ' ∫_slipping w
    /// sign(e) η dη.
    fn eval_kinematic(&self, p: f64, k_n: f64, u_t: f64, committed: &SlipState) -> TangentialEval {
        let (k, dk) = self.elastic_stiffness(p);
        let dens = self.density();
        let phi = self.mu * p * dens.big_c / k;
        let before = committed.u_p + dens.integral(&committed.mem);
        let up = dens.update(&committed.mem, u_t - before, phi);
        let u_p = u_t - up.integral;
        // macro-slip: every element slides and the shear is at μ p_N (the
        // one element of k_T^p = 0 slides at ρ μ p_N: micro-slip, as in 2.22)
        let slip = if !up.slips {
            Slip::Stick
        } else if up.sticking <= 1e-12 && (k * up.integral).abs() >= self.mu * p * (1.0 - 1e-9) {
            Slip::MacroSlip
        } else {
            Slip::MicroSlip
        };
        let dphi = phi * (1.0 / p - dk / k);
        TangentialEval {
            p_t: k * up.integral,
            d_ut: k * up.sticking,
            d_un: k_n * (dk * up.integral + k * dphi * up.slipping_moment),
            state: SlipState {
                u_p,
                kappa: committed.kappa + (u_p - committed.u_p).abs(),
                mem: up.stretch,
            },
            slip,
            mu_f: self.mu,
        }
    }

    /// The backward-Euler return of a trial shear of magnitude `a` from κ_n
    /// at pressure p (k = k_T^e, dk = dk_T^e/dp_N), shared by the scalar and
    /// the vector law: `None` when |p_T^tr| ≤ Y(κ_n) (stick), else the root
    /// Δκ of `a − k Δκ = Y(κ_n + Δκ)` and the limit there.
    pub(super) fn radial_return(
        &self,
        a: f64,
        kappa_n: f64,
        p: f64,
        k: f64,
        dk: f64,
    ) -> Option<Return> {
        let (y0, ..) = self.limit(kappa_n, p, k, dk);
        // a force cycled back to its earlier peak meets the limit within
        // round-off: that is no slip (else stick and slip alternate there)
        if a <= y0 * (1.0 + 1e-12) {
            return None;
        }
        // g(Δκ) = a − k Δκ − Y(κ_n + Δκ) is decreasing: g(0) > 0 > g(a/k)
        let g = |dkap: f64| {
            let (y, yk, ..) = self.limit(kappa_n + dkap, p, k, dk);
            (a - k * dkap - y, -k - yk)
        };
        let (mut lo, mut hi) = (0.0, a / k);
        let mut x = 0.0;
        for _ in 0..100 {
            let (gv, gd) = g(x);
            if gv.abs() <= 1e-14 * a {
                break;
            }
            if gv > 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            let next = x - gv / gd;
            x = if next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
            if hi - lo <= 1e-16 * (a / k) {
                break;
            }
        }
        let kappa = kappa_n + x;
        let (y, yk, yp, macro_slip) = self.limit(kappa, p, k, dk);
        Some(Return {
            dkappa: x,
            kappa,
            y,
            yk,
            yp,
            macro_slip,
        })
    }

    /// Return mapping from `committed` at pressure p (stiffness k_n = dp/du_N) and
    /// total tangential displacement u_t. An open spring (p ≤ 0) carries no shear
    /// and slides freely: its plastic slip follows u_t.
    pub(crate) fn eval(&self, p: f64, k_n: f64, u_t: f64, committed: &SlipState) -> TangentialEval {
        if p <= 0.0 {
            return TangentialEval {
                p_t: 0.0,
                d_ut: 0.0,
                d_un: 0.0,
                state: SlipState {
                    u_p: u_t,
                    kappa: committed.kappa,
                    mem: Stretch::default(),
                },
                slip: Slip::MacroSlip,
                mu_f: self.friction(committed.kappa).0,
            };
        }
        if self.memory == Memory::Kinematic {
            return self.eval_kinematic(p, k_n, u_t, committed);
        }
        let (k, dk) = self.elastic_stiffness(p);
        let ue = u_t - committed.u_p;
        let p_tr = k * ue;
        let Some(r) = self.radial_return(p_tr.abs(), committed.kappa, p, k, dk) else {
            return TangentialEval {
                p_t: p_tr,
                d_ut: k,
                d_un: dk * k_n * ue,
                state: *committed,
                slip: Slip::Stick,
                mu_f: self.friction(committed.kappa).0,
            };
        };
        let Return {
            dkappa: x,
            kappa,
            y,
            yk,
            yp,
            macro_slip,
        } = r;
        let sgn = p_tr.signum();
        let d_ut = yk * k / (k + yk);
        let d_un = k_n * sgn * (yk * (sgn * dk * ue - x * dk - yp) / (k + yk) + yp);
        TangentialEval {
            p_t: sgn * y,
            d_ut,
            d_un,
            state: SlipState {
                u_p: committed.u_p + sgn * x,
                kappa,
                mem: Stretch::default(),
            },
            slip: if macro_slip {
                Slip::MacroSlip
            } else {
                Slip::MicroSlip
            },
            mu_f: self.friction(kappa).0,
        }
    }
}

#[cfg(test)]
mod memory_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod vector_paths_tests;
#[cfg(test)]
mod vector_tests;
#[cfg(test)]
mod work_tests;
