//! The tangential law in two directions (issue 26): slip and shear are
//! vectors of the tangent plane, u_T = (u₁, u₂), p_T = (p₁, p₂) (at an
//! interface of a twisting axisymmetric model: along the meridian and
//! around the axis, r Δφ).
//!
//! **Isotropic memory.** The law of [`super`] (eqs 2.6, 2.16, 2.18, 2.21,
//! 2.22) with |p_T| in place of the signed shear: the elastic range is a
//! disc, the slip flows along p_T (associated in the tangent plane, the
//! isotropic Coulomb law with a regularized stick of Wriggers 2006,
//! Computational Contact Mechanics, 2nd ed., ch. 5), κ = ∫|du_T^p| is the
//! slip length:
//!
//! ```text
//!   p_T = k_T^e (u_T − u_T^p),   |p_T| ≤ Y(κ) = min(p_T^Y + H κ, μ_F(κ) p_N)
//!   du_T^p = dκ n,   n = p_T / |p_T|
//! ```
//!
//! Backward Euler is the radial return (Simo & Hughes 1998, Computational
//! Inelasticity, ch. 3, the return of J2 flow with isotropic hardening,
//! whose deviatoric disc this is in two dimensions): the trial shear
//! p^tr = k_T^e (u_T − u_T,n^p) keeps its direction n, its magnitude a = |p^tr|
//! solves the scalar equation a − k_T^e Δκ = Y(κ_n + Δκ) of [`super`], and
//! p_T = Y(κ) n, u_T^p = u_T,n^p + Δκ n. Its consistent tangent, with
//! Y_κ = ∂Y/∂κ, Y_p = ∂Y/∂p_N, k' = dk_T^e/dp_N, |u_e| = a / k_T^e:
//!
//! ```text
//!   ∂p_T/∂u_T = k Y_κ/(k + Y_κ) n nᵀ + k Y/a (I − n nᵀ)
//!   ∂p_T/∂u_N = k_N n [Y_κ (k' |u_e| − k' Δκ − Y_p)/(k + Y_κ) + Y_p]
//! ```
//!
//! ∂p_T/∂u_T is symmetric (the flow is normal to the disc): along n the
//! scalar law's elastic-plastic modulus, across n the secant k Y/a =
//! k (1 − k Δκ/a) by which the return shortens p^tr (in a Coulomb slide,
//! μ p_N/|u_e|: the traction turns with the slip). The law's tangent is
//! unsymmetric only through ∂p_T/∂u_N (the cap μ_F p_N, p_T^Y and k_T^e
//! depend on p_N, p_N not on u_T). Along one axis this is the scalar law
//! term by term (the same return, n = ±1, I − n nᵀ zero along it).
//!
//! **Kinematic memory.** A finite set of Jenkins elements with vector
//! stretches ([`super::jenkins`]): exact for the bilinear backbone, a
//! discretization of the Iwan density.
//!
//! An open point (p_N ≤ 0) carries no shear and slides freely.

use super::jenkins::{across, Stretch2, JENKINS};
use super::{Memory, Slip, TangentialLaw};

/// History of one point of the vector law: plastic slip u_T^p (mm, the slip
/// p_T / k_T^e does not explain), slip length κ (mm), and under the
/// kinematic memory the stretches of its Jenkins elements.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SlipState2 {
    pub u_p: [f64; 2],
    pub kappa: f64,
    pub mem: Stretch2,
}

/// Result of one evaluation of the vector law.
#[derive(Clone, Copy, Debug)]
pub(crate) struct VectorEval {
    pub p_t: [f64; 2],
    /// ∂p_T/∂u_T: `d_ut[i][j]` = ∂p_i/∂u_j.
    pub(crate) d_ut: [[f64; 2]; 2],
    /// ∂p_T/∂u_N.
    pub(crate) d_un: [f64; 2],
    pub state: SlipState2,
    pub slip: Slip,
    pub(crate) mu_f: f64,
}

impl SlipState2 {
    /// Doubles per state in [`SlipState2::pack`].
    pub const PACKED: usize = 3 + 2 * JENKINS;

    /// u_T^p (2), κ, then e₁ … e_J as (x, y) pairs: a layout for restart
    /// files and the MPI exchange.
    pub fn pack(&self) -> [f64; Self::PACKED] {
        let mut v = [0.0; Self::PACKED];
        v[..3].copy_from_slice(&[self.u_p[0], self.u_p[1], self.kappa]);
        for (slot, e) in v[3..].chunks_exact_mut(2).zip(&self.mem.e) {
            slot.copy_from_slice(e);
        }
        v
    }

    /// The inverse of [`SlipState2::pack`] (`v` holds at least `PACKED` values).
    pub(crate) fn unpack(v: &[f64]) -> Self {
        let mut s = SlipState2 {
            u_p: [v[0], v[1]],
            kappa: v[2],
            ..Default::default()
        };
        for (e, slot) in s.mem.e.iter_mut().zip(v[3..Self::PACKED].chunks_exact(2)) {
            *e = [slot[0], slot[1]];
        }
        s
    }

    /// Whether a law can continue from this state (one read from an
    /// untrusted restart file): every value finite, κ ≥ 0, stretches only
    /// in the law's Jenkins elements (none under the isotropic memory or
    /// without a law), each within `bound` mm. The message names the value.
    pub fn check(&self, law: Option<&TangentialLaw>, bound: f64) -> Result<(), String> {
        if let Some(k) = self.pack().iter().position(|x| !x.is_finite()) {
            return Err(format!("value {} of the slip state is not finite", k + 1));
        }
        if self.kappa < 0.0 {
            return Err(format!("slip length κ = {} (≥ 0 expected)", self.kappa));
        }
        let used = law.map_or(0, |l| l.elements().len);
        if let Some(i) = (used..JENKINS).find(|&i| self.mem.e[i] != [0.0; 2]) {
            return Err(format!(
                "a stretch in Jenkins element {} but the law has {used} (0 expected beyond)",
                i + 1
            ));
        }
        if let Some(i) = (0..used).find(|&i| self.mem.e[i][0].hypot(self.mem.e[i][1]) > bound) {
            return Err(format!(
                "the stretch of Jenkins element {} is longer than {bound} mm",
                i + 1
            ));
        }
        Ok(())
    }
}

impl TangentialLaw {
    /// The law in two directions from `committed` at pressure p (stiffness
    /// k_n = dp/du_N) and total tangential displacement u_t (see the module
    /// comment). With u_t along one axis it is [`TangentialLaw::eval`].
    pub(crate) fn eval_vector(
        &self,
        p: f64,
        k_n: f64,
        u_t: [f64; 2],
        committed: &SlipState2,
    ) -> VectorEval {
        if p <= 0.0 {
            return VectorEval {
                p_t: [0.0; 2],
                d_ut: [[0.0; 2]; 2],
                d_un: [0.0; 2],
                state: SlipState2 {
                    u_p: u_t,
                    kappa: committed.kappa,
                    mem: Stretch2::default(),
                },
                slip: Slip::MacroSlip,
                mu_f: self.friction(committed.kappa).0,
            };
        }
        if self.memory == Memory::Kinematic {
            return self.eval_kinematic2(p, k_n, u_t, committed);
        }
        let (k, dk) = self.elastic_stiffness(p);
        // trial
        let ue = [u_t[0] - committed.u_p[0], u_t[1] - committed.u_p[1]];
        let p_tr = [k * ue[0], k * ue[1]];
        let a = p_tr[0].hypot(p_tr[1]);
        let Some(r) = self.radial_return(a, committed.kappa, p, k, dk) else {
            // elastic
            return VectorEval {
                p_t: p_tr,
                d_ut: [[k, 0.0], [0.0, k]],
                d_un: [dk * k_n * ue[0], dk * k_n * ue[1]],
                state: *committed,
                slip: Slip::Stick,
                mu_f: self.friction(committed.kappa).0,
            };
        };
        // radial return: the direction of the trial, the magnitude Y(κ)
        let n = [p_tr[0] / a, p_tr[1] / a];
        let along = r.yk * k / (k + r.yk);
        let secant = k * (r.y / a);
        let t = across(n);
        let mut d_ut = [[0.0; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                d_ut[i][j] = along * n[i] * n[j] + secant * t[i][j];
            }
        }
        let ue_len = ue[0].hypot(ue[1]);
        let s = r.yk * (dk * ue_len - r.dkappa * dk - r.yp) / (k + r.yk) + r.yp;
        VectorEval {
            p_t: [n[0] * r.y, n[1] * r.y],
            d_ut,
            d_un: [k_n * n[0] * s, k_n * n[1] * s],
            state: SlipState2 {
                u_p: [
                    committed.u_p[0] + n[0] * r.dkappa,
                    committed.u_p[1] + n[1] * r.dkappa,
                ],
                kappa: r.kappa,
                mem: Stretch2::default(),
            },
            slip: if r.macro_slip {
                Slip::MacroSlip
            } else {
                Slip::MicroSlip
            },
            mu_f: self.friction(r.kappa).0,
        }
    }

    /// The kinematic memory in two directions ([`super::jenkins`]):
    /// p_T = k Σ mᵢ eᵢ, ∂p_T/∂u_T = k Σ mᵢ ∂eᵢ/∂u_T and ∂p_T/∂u_N =
    /// k_N [k' Σ mᵢ eᵢ + k φ' Σ_sliding mᵢ ηᵢ nᵢ], φ'/φ = 1/p_N − k'/k.
    fn eval_kinematic2(
        &self,
        p: f64,
        k_n: f64,
        u_t: [f64; 2],
        committed: &SlipState2,
    ) -> VectorEval {
        let (k, dk) = self.elastic_stiffness(p);
        let el = self.elements();
        let phi = self.mu * p * el.big_c / k;
        let s0 = el.sum(&committed.mem);
        let du = [
            u_t[0] - (committed.u_p[0] + s0[0]),
            u_t[1] - (committed.u_p[1] + s0[1]),
        ];
        let up = el.update(&committed.mem, du, phi);
        let u_p = [u_t[0] - up.sum[0], u_t[1] - up.sum[1]];
        let shear = k * up.sum[0].hypot(up.sum[1]);
        // macro-slip: every element slides and the shear is at μ p_N
        let slip = if !up.slips {
            Slip::Stick
        } else if up.sticking <= 1e-12 && shear >= self.mu * p * (1.0 - 1e-9) {
            Slip::MacroSlip
        } else {
            Slip::MicroSlip
        };
        let dphi = phi * (1.0 / p - dk / k);
        let dp = |i: usize| k_n * (dk * up.sum[i] + k * dphi * up.slipping_moment[i]);
        let dk_ut = |i: usize, j: usize| k * up.d_sum[i][j];
        VectorEval {
            p_t: [k * up.sum[0], k * up.sum[1]],
            d_ut: [[dk_ut(0, 0), dk_ut(0, 1)], [dk_ut(1, 0), dk_ut(1, 1)]],
            d_un: [dp(0), dp(1)],
            state: SlipState2 {
                u_p,
                kappa: committed.kappa
                    + (u_p[0] - committed.u_p[0]).hypot(u_p[1] - committed.u_p[1]),
                mem: up.stretch,
            },
            slip,
            mu_f: self.mu,
        }
    }
}
