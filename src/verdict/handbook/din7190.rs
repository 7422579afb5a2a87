//! DIN 7190-1:2017, cylindrical interference fits: the handbook's side of a shrink or press fit
//! between a hub (outer part, index A) and a solid or hollow shaft (inner part, index I).
//!
//! Both parts are thick cylinders in plane stress of the same length (the Lamé solution,
//! Timoshenko & Goodier, *Theory of Elasticity*, thick-walled cylinder), with different moduli
//! allowed. The hub may be partly plastic (the shaft stays elastic). Units: N, mm, MPa; torques in
//! N·mm; roughness in µm; temperatures in °C; densities in t/mm³ (steel 7.85e-9), so that
//! ρ ω² r is in N/mm³ with ω in rad/s.
//!
//! Notation of DIN 7190: Q_A = D_F/D_aA, Q_I = D_iI/D_F, ξ_w = U_w/D_F.
//!
//! The yield criterion of the standard is its simplified form of the distortion-energy
//! hypothesis, σ_v = (√3/2)(σ_max − σ_min) over the principal stresses with σ_z = 0 (it neglects
//! the axial stress in the von Mises expression). The stress results give it beside the exact
//! plane-stress von Mises value, which is what a finite-element run reports.

use super::{non_negative, positive, safety};
use std::f64::consts::PI;

/// Smoothing factor k of DIN 7190-1:2017: ΔU = 0.4 (Rz_A,i + Rz_I,a).
pub const SMOOTHING_2017: f64 = 0.4;

/// Smoothing factor k of the withdrawn DIN 7190:2001: ΔU = 0.8 (Rz_A,i + Rz_I,a).
pub const SMOOTHING_2001: f64 = 0.8;

/// √3.
const SQRT3: f64 = 1.732_050_807_568_877_2;

/// A cylindrical interference fit: geometry, materials, interference and roughness.
///
/// The pressure follows from the one `interference`; for the band of a fit build the two
/// fits with [`Fit::with_interference`] (U_min gives p_min, which rates slipping and opening;
/// U_max gives p_max, which rates yielding and joining).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// Joint (nominal fit) diameter D_F (mm).
    pub d_f: f64,
    /// Joint length l_F (mm).
    pub l_f: f64,
    /// Hub outer diameter D_aA (mm), greater than D_F.
    pub d_aa: f64,
    /// Shaft bore D_iI (mm): 0 for a solid shaft, otherwise less than D_F.
    pub d_ii: f64,
    /// Young's modulus of the hub E_A (MPa).
    pub e_hub: f64,
    /// Poisson's ratio of the hub ν_A (-).
    pub poisson_hub: f64,
    /// Young's modulus of the shaft E_I (MPa).
    pub e_shaft: f64,
    /// Poisson's ratio of the shaft ν_I (-).
    pub poisson_shaft: f64,
    /// Geometric diametral interference U (mm): shaft diameter minus hub bore, before smoothing.
    pub interference: f64,
    /// Roughness Rz of the hub bore, Rz_A,i (µm).
    pub rz_hub: f64,
    /// Roughness Rz of the shaft surface, Rz_I,a (µm).
    pub rz_shaft: f64,
    /// Smoothing factor k (-) in ΔU = k (Rz_A,i + Rz_I,a): [`SMOOTHING_2017`] = 0.4 by
    /// DIN 7190-1:2017 (the default to use), [`SMOOTHING_2001`] = 0.8 by DIN 7190:2001.
    pub smoothing: f64,
    /// Yield strength of the hub R_eL,A (MPa); R_p0.2 where there is no marked yield point.
    pub yield_hub: f64,
    /// Yield strength of the shaft R_eL,I (MPa); R_p0.2 where there is no marked yield point.
    pub yield_shaft: f64,
    /// Adhesion (static friction) coefficient for slipping in the circumferential direction,
    /// ν_ru (-): DIN's "Haftbeiwert", not a Poisson's ratio.
    pub adhesion_torque: f64,
    /// Adhesion coefficient for slipping in the axial direction, ν_rl (-).
    pub adhesion_axial: f64,
}

/// Stresses in the hub at its bore (r = D_F/2) and its outer surface (MPa, tension positive).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HubStresses {
    /// Hoop stress at the bore σ_t,Ai = p (1 + Q_A²)/(1 − Q_A²).
    pub tangential: f64,
    /// Radial stress at the bore σ_r,Ai = −p.
    pub radial: f64,
    /// Exact plane-stress von Mises stress at the bore, p √(3 + Q_A⁴)/(1 − Q_A²).
    pub von_mises: f64,
    /// DIN's simplified equivalent stress at the bore, (√3/2)|σ_t − σ_r| = √3 p/(1 − Q_A²).
    pub din_equivalent: f64,
    /// Hoop stress at the outer surface σ_t,Aa = 2 p Q_A²/(1 − Q_A²).
    pub outer_tangential: f64,
}

/// Stresses in the shaft (MPa, tension positive): at its most stressed inner point (the bore of
/// a hollow shaft; any point of a solid one, whose state is uniform) and at the joint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShaftStresses {
    /// Hoop stress at the inner point: −2p/(1 − Q_I²) at the bore, −p in a solid shaft.
    pub inner_tangential: f64,
    /// Radial stress at the inner point: 0 at the bore, −p in a solid shaft.
    pub inner_radial: f64,
    /// Exact plane-stress von Mises stress at the inner point: 2p/(1 − Q_I²), or p (solid).
    pub von_mises: f64,
    /// DIN's simplified equivalent stress at the inner point, (√3/2)(σ_max − σ_min) with
    /// σ_z = 0: √3 p/(1 − Q_I²), or (√3/2) p for a solid shaft.
    pub din_equivalent: f64,
    /// Hoop stress at the joint σ_t,Ia = −p (1 + Q_I²)/(1 − Q_I²) (−p for a solid shaft); the
    /// radial stress there is −p.
    pub joint_tangential: f64,
}

/// Yield safeties S_F = p_F/p of both parts (-).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct YieldSafety {
    /// S_F,A = p_FA/p.
    pub hub: f64,
    /// S_F,I = p_FI/p.
    pub shaft: f64,
}

impl Fit {
    /// The same fit with another geometric interference U (mm), for p_min and p_max.
    pub fn with_interference(self, interference: f64) -> Fit {
        Fit {
            interference,
            ..self
        }
    }

    /// Diameter ratios (Q_A, Q_I) = (D_F/D_aA, D_iI/D_F), or `None` unless
    /// 0 < D_F < D_aA, 0 ≤ D_iI < D_F, l_F > 0, E > 0 and −1 < ν < 0.5 for both parts, k ≥ 0 and
    /// Rz ≥ 0.
    pub fn ratios(&self) -> Option<(f64, f64)> {
        let poisson = |nu: f64| nu > -1.0 && nu < 0.5;
        let ok = positive(self.d_f)
            && positive(self.l_f)
            && positive(self.d_aa)
            && self.d_aa > self.d_f
            && self.d_ii >= 0.0
            && self.d_ii < self.d_f
            && positive(self.e_hub)
            && positive(self.e_shaft)
            && poisson(self.poisson_hub)
            && poisson(self.poisson_shaft)
            && self.interference.is_finite()
            && self.smoothing >= 0.0
            && self.rz_hub >= 0.0
            && self.rz_shaft >= 0.0;
        ok.then(|| (self.d_f / self.d_aa, self.d_ii / self.d_f))
    }

    /// Effective interference U_w = U − k (Rz_A,i + Rz_I,a)/1000 (mm; Rz in µm): the geometric
    /// interference less the smoothing of the roughness peaks on joining (DIN 7190-1:2017,
    /// effective interference). Negative when the fit is loose.
    pub fn effective_interference(&self) -> f64 {
        self.interference - self.smoothing * (self.rz_hub + self.rz_shaft) * 1e-3
    }

    /// The compliance K (1/MPa) in ξ_w = K p, from the plane-stress Lamé solution of the two
    /// cylinders:
    ///
    /// ```text
    ///   K = (1/E_A) [(1 + Q_A²)/(1 − Q_A²) + ν_A] + (1/E_I) [(1 + Q_I²)/(1 − Q_I²) − ν_I]
    /// ```
    ///
    /// DIN 7190-1:2017, elastic joint pressure for different materials (derived from the
    /// thick-walled cylinder, Timoshenko & Goodier). `None` for an invalid fit ([`Fit::ratios`]).
    pub fn compliance(&self) -> Option<f64> {
        let (q_a, q_i) = self.ratios()?;
        let hub = ((1.0 + q_a * q_a) / (1.0 - q_a * q_a) + self.poisson_hub) / self.e_hub;
        let shaft = ((1.0 + q_i * q_i) / (1.0 - q_i * q_i) - self.poisson_shaft) / self.e_shaft;
        Some(hub + shaft)
    }

    /// Elastic joint pressure p = ξ_w/K (MPa), ξ_w = U_w/D_F (DIN 7190-1:2017, elastic
    /// interference fit). Zero when U_w ≤ 0 (the fit is loose; [`Fit::effective_interference`]
    /// tells by how much). With the same E for both parts it reduces to
    /// p = ξ_w E (1 − Q_A²)(1 − Q_I²)/(2 (1 − Q_A² Q_I²)).
    pub fn pressure(&self) -> Option<f64> {
        self.pressure_in_service(0.0, 0.0)
    }

    /// Diametral interference lost to the operating temperatures, ΔU_ϑ (mm):
    ///
    /// ```text
    ///   ΔU_ϑ = D_F (α_A ΔT_A − α_I ΔT_I)
    /// ```
    ///
    /// with ΔT_A, ΔT_I the uniform temperature changes of hub and shaft from the assembly
    /// state and α_A, α_I (1/K) their expansion coefficients: the interference lost (gained
    /// when negative) by their different thermal expansions, DIN 7190-1:2017's change of the
    /// interference at operating temperature. Derivation (the standard's equation was not at
    /// hand to cite by number): a free disk or ring at a uniform ΔT grows without stress,
    /// u = α ΔT r (plane stress, and exactly in three dimensions); the fit is elastic and
    /// linear, so this free growth superposes on the joined state, the hub's bore and the
    /// shaft's surface at r = D_F/2 moving apart by (α_A ΔT_A − α_I ΔT_I) D_F/2, while the
    /// compliance K of the pressure is unchanged (a uniform ΔT sets no stress in a free
    /// part). Same material, warmed alike: 0. `None` for an invalid fit or a non-finite
    /// input.
    pub fn thermal_loss(
        &self,
        (alpha_hub, dt_hub): (f64, f64),
        (alpha_shaft, dt_shaft): (f64, f64),
    ) -> Option<f64> {
        self.ratios()?;
        let loss = self.d_f * (alpha_hub * dt_hub - alpha_shaft * dt_shaft);
        loss.is_finite().then_some(loss)
    }

    /// Joint pressure in service (MPa): the interference less the smoothing and the losses of
    /// the operating temperatures and of the speed,
    ///
    /// ```text
    ///   p = (U_w − ΔU_ϑ − ΔU_ω)/(D_F K)
    /// ```
    ///
    /// with ΔU_ϑ from [`Fit::thermal_loss`] (`thermal`, mm) and ΔU_ω from
    /// [`Fit::centrifugal_loss`] (`centrifugal`, mm): the elastic pressure of the fit
    /// (DIN 7190-1:2017, elastic joint pressure, [`Fit::compliance`]) with the interference the
    /// service leaves, the losses superposed on the joined state (each derived in its
    /// function). Zero once the fit has opened (U_w ≤ ΔU_ϑ + ΔU_ω). With both losses 0 it is
    /// [`Fit::pressure`], bit for bit. `None` for an invalid fit or a non-finite loss.
    pub fn pressure_in_service(&self, thermal: f64, centrifugal: f64) -> Option<f64> {
        let k = self.compliance()?;
        if !thermal.is_finite() || !centrifugal.is_finite() {
            return None;
        }
        let left = self.effective_interference() - thermal - centrifugal;
        Some((left / self.d_f / k).max(0.0))
    }

    /// The temperature change ΔT (K) of hub and shaft heated alike, standing still, at which
    /// the fit opens: ΔU_ϑ = U_w with ΔT_A = ΔT_I = ΔT ([`Fit::thermal_loss`]),
    ///
    /// ```text
    ///   ΔT_ab = U_w / (D_F (α_A − α_I))
    /// ```
    ///
    /// Pass `alpha_shaft` = 0 for the hub heated alone (the shaft at its assembly temperature)
    /// and `alpha_hub` = 0 for the shaft alone. Negative where the fit opens on cooling (the
    /// shaft expands more); 0 when U_w ≤ 0 (loose at rest). `None` for an invalid fit, a
    /// non-finite α, or α_A = α_I (the fit keeps its interference at every temperature).
    pub fn opening_temperature_change(&self, alpha_hub: f64, alpha_shaft: f64) -> Option<f64> {
        self.ratios()?;
        let differ = alpha_hub - alpha_shaft;
        if !differ.is_finite() || differ == 0.0 {
            return None;
        }
        let u_w = self.effective_interference();
        Some(if u_w <= 0.0 {
            0.0
        } else {
            u_w / (self.d_f * differ)
        })
    }

    /// Stresses in the hub at the pressure `p` (MPa), see [`HubStresses`] (plane-stress Lamé,
    /// DIN 7190-1:2017 stresses of the outer part). `None` for an invalid fit or p < 0.
    pub fn hub_stresses(&self, p: f64) -> Option<HubStresses> {
        let (q_a, _) = self.ratios()?;
        if !non_negative(p) {
            return None;
        }
        let s = 1.0 - q_a * q_a;
        let tangential = p * (1.0 + q_a * q_a) / s;
        Some(HubStresses {
            tangential,
            radial: -p,
            von_mises: p * (3.0 + q_a.powi(4)).sqrt() / s,
            din_equivalent: din_equivalent(tangential, -p),
            outer_tangential: 2.0 * p * q_a * q_a / s,
        })
    }

    /// Stresses in the shaft at the pressure `p` (MPa), see [`ShaftStresses`] (plane-stress
    /// Lamé, DIN 7190-1:2017 stresses of the inner part). `None` for an invalid fit or p < 0.
    pub fn shaft_stresses(&self, p: f64) -> Option<ShaftStresses> {
        let (_, q_i) = self.ratios()?;
        if !non_negative(p) {
            return None;
        }
        let s = 1.0 - q_i * q_i;
        let (t, r) = if q_i > 0.0 {
            (-2.0 * p / s, 0.0)
        } else {
            (-p, -p)
        };
        Some(ShaftStresses {
            inner_tangential: t,
            inner_radial: r,
            von_mises: (t * t + r * r - t * r).sqrt(),
            din_equivalent: din_equivalent(t, r),
            joint_tangential: -p * (1.0 + q_i * q_i) / s,
        })
    }

    /// Pressure at which the hub bore starts to yield, p_FA = (1 − Q_A²) R_eL,A/√3 (MPa):
    /// DIN's simplified equivalent stress √3 p/(1 − Q_A²) set equal to R_eL,A (DIN 7190-1:2017,
    /// limit of the elastic outer part). `None` for an invalid fit or R_eL,A ≤ 0.
    pub fn yield_pressure_hub(&self) -> Option<f64> {
        let (q_a, _) = self.ratios()?;
        positive(self.yield_hub).then(|| (1.0 - q_a * q_a) * self.yield_hub / SQRT3)
    }

    /// Pressure at which the shaft starts to yield, p_FI (MPa), DIN 7190-1:2017, limit of the
    /// elastic inner part:
    ///
    /// * hollow shaft: p_FI = (1 − Q_I²) R_eL,I/√3 (yield at the bore);
    /// * solid shaft: p_FI = 2 R_eL,I/√3.
    ///
    /// The solid-shaft form is DIN's simplified criterion (√3/2)(σ_max − σ_min) applied to the
    /// uniform state σ_t = σ_r = −p, σ_z = 0, which gives (√3/2) p = R_eL,I. It is the form
    /// consistent with the hub's and the hollow shaft's limits and with
    /// [`ShaftStresses::din_equivalent`]; the solid-shaft text of the standard was not
    /// available to confirm it. The exact plane-stress von Mises stress of that state is p, so
    /// the exact limit p = R_eL,I is lower by the factor √3/2 ≈ 0.87: compare
    /// [`ShaftStresses::von_mises`] with R_eL,I for the stricter check. (The hollow-shaft form
    /// does not tend to the solid one as Q_I → 0: a small bore doubles the hoop stress.)
    /// `None` for an invalid fit or R_eL,I ≤ 0.
    pub fn yield_pressure_shaft(&self) -> Option<f64> {
        let (_, q_i) = self.ratios()?;
        if !positive(self.yield_shaft) {
            return None;
        }
        Some(if q_i > 0.0 {
            (1.0 - q_i * q_i) * self.yield_shaft / SQRT3
        } else {
            2.0 * self.yield_shaft / SQRT3
        })
    }

    /// Joint pressure of a partly plastic hub (elastic shaft) whose plastic zone reaches the
    /// diameter D_plA = P_A D_aA, Q_A ≤ P_A ≤ 1 (MPa):
    ///
    /// ```text
    ///   p = (R_eL,A/√3) (1 − P_A² + 2 ln(P_A/Q_A))
    /// ```
    ///
    /// DIN 7190-1:2017, elastic-plastic outer part; derived from the thick tube with the yield
    /// condition σ_t − σ_r = 2 R_eL/√3 in the plastic ring (Hill, *The Mathematical Theory of
    /// Plasticity*, expansion of a thick tube). P_A = Q_A gives p_FA, P_A = 1 the fully plastic
    /// limit [`Fit::plastic_limit_hub`]. `None` for an invalid fit, R_eL,A ≤ 0 or P_A outside
    /// [Q_A, 1].
    pub fn pressure_partly_plastic_hub(&self, p_a: f64) -> Option<f64> {
        let (q_a, _) = self.ratios()?;
        if !positive(self.yield_hub) || !(q_a..=1.0).contains(&p_a) {
            return None;
        }
        Some(self.yield_hub / SQRT3 * (1.0 - p_a * p_a + 2.0 * (p_a / q_a).ln()))
    }

    /// Largest pressure a hub can carry, fully plastic (P_A = 1):
    /// p_A,max = −(2/√3) R_eL,A ln Q_A (MPa), DIN 7190-1:2017, fully plastic outer part. `None`
    /// for an invalid fit or R_eL,A ≤ 0.
    pub fn plastic_limit_hub(&self) -> Option<f64> {
        let (q_a, _) = self.ratios()?;
        positive(self.yield_hub).then(|| -2.0 / SQRT3 * self.yield_hub * q_a.ln())
    }

    /// Yield safeties S_F,A = p_FA/p and S_F,I = p_FI/p at the pressure `p` (MPa; rate with
    /// p_max), DIN 7190-1:2017. `None` for an invalid fit or yield strength, or p < 0.
    pub fn yield_safety(&self, p: f64) -> Option<YieldSafety> {
        Some(YieldSafety {
            hub: safety(self.yield_pressure_hub()?, p)?,
            shaft: safety(self.yield_pressure_shaft()?, p)?,
        })
    }

    /// Transmissible torque M_t = p π D_F² l_F ν_ru/2 (N·mm) at the pressure `p` (MPa; rate with
    /// p_min), DIN 7190-1:2017, transmissible torque. `None` for an invalid fit, ν_ru ≤ 0 or
    /// p < 0.
    pub fn transmissible_torque(&self, p: f64) -> Option<f64> {
        Some(self.friction_capacity(p, self.adhesion_torque)? * self.d_f / 2.0)
    }

    /// Transmissible axial force F_ax = p π D_F l_F ν_rl (N) at the pressure `p` (MPa),
    /// DIN 7190-1:2017, transmissible axial force. `None` for an invalid fit, ν_rl ≤ 0 or p < 0.
    pub fn transmissible_axial_force(&self, p: f64) -> Option<f64> {
        self.friction_capacity(p, self.adhesion_axial)
    }

    /// Slip safety under a torque `torque` (N·mm) and an axial force `axial` (N) together,
    /// both multiplied by the application factor K_A, at the pressure `p` (MPa; rate with
    /// p_min). DIN 7190-1:2017 combines them to the resultant friction force,
    /// S_r = p π D_F l_F ν / (K_A √(F_ax² + F_t²)) with F_t = 2 M_t/D_F. With different
    /// coefficients for the two directions this uses the elliptic generalisation
    ///
    /// ```text
    ///   S_r = p π D_F l_F / (K_A √((F_t/ν_ru)² + (F_ax/ν_rl)²))
    /// ```
    ///
    /// which is the resultant form when ν_ru = ν_rl and M_t,transmissible/(K_A M_t) when
    /// F_ax = 0. Infinite without load; `None` for an invalid fit, coefficients ≤ 0, p < 0 or
    /// K_A ≤ 0.
    pub fn slip_safety(&self, p: f64, torque: f64, axial: f64, k_a: f64) -> Option<f64> {
        self.ratios()?;
        let ok = positive(self.adhesion_torque) && positive(self.adhesion_axial) && positive(k_a);
        if !ok || !torque.is_finite() || !axial.is_finite() {
            return None;
        }
        let f_t = 2.0 * torque / self.d_f / self.adhesion_torque;
        let f_ax = axial / self.adhesion_axial;
        let capacity = p * PI * self.d_f * self.l_f;
        safety(capacity, k_a * f_t.hypot(f_ax))
    }

    /// Joining temperature of the heated hub with the shaft at room temperature (°C):
    ///
    /// ```text
    ///   ϑ_A = ϑ_room + (U + ΔS_ü)/(α_A D_F)
    /// ```
    ///
    /// U is this fit's geometric interference (mm, use U_max, not smoothed), `clearance` the
    /// joining clearance ΔS_ü (mm, customarily about 0.001 D_F), `alpha_hub` the hub's thermal
    /// expansion coefficient α_A (1/K), `room` ϑ_room (°C). DIN 7190-1:2017, shrink fit joining
    /// temperature. `None` for an invalid fit, α_A ≤ 0 or a negative clearance.
    pub fn joining_temperature(&self, room: f64, clearance: f64, alpha_hub: f64) -> Option<f64> {
        self.ratios()?;
        let ok = room.is_finite() && clearance >= 0.0 && positive(alpha_hub);
        ok.then(|| room + (self.interference + clearance) / (alpha_hub * self.d_f))
    }

    /// Diametral interference lost to rotation at ω (rad/s), ΔU_ω = 2 (u_A − u_I) (mm), with
    /// the radial growth at r = D_F/2 of the free rotating hub and shaft (plane stress,
    /// densities ρ in t/mm³):
    ///
    /// ```text
    ///   u_A = ρ_A ω² D_F/(32 E_A) ((3 + ν_A) D_aA² + (1 − ν_A) D_F²)
    ///   u_I = ρ_I ω² D_F/(32 E_I) ((3 + ν_I) D_iI² + (1 − ν_I) D_F²)
    /// ```
    ///
    /// The rotating disk of uniform thickness (Timoshenko & Goodier), superposed on the fit;
    /// DIN 7190-1:2017 counts this loss of interference for rotating fits. Same material:
    /// ΔU_ω = ρ ω² D_F (3 + ν)(D_aA² − D_iI²)/(16 E). Negative when the shaft grows more.
    /// `None` for an invalid fit or densities ≤ 0.
    pub fn centrifugal_loss(
        &self,
        omega: f64,
        density_hub: f64,
        density_shaft: f64,
    ) -> Option<f64> {
        Some(omega * omega * self.centrifugal_coefficient(density_hub, density_shaft)?)
    }

    /// Joint pressure at the speed ω (rad/s), p(ω) = (U_w − ΔU_ω)/(D_F K) (MPa), zero once the
    /// fit has opened. `None` as for [`Fit::centrifugal_loss`].
    pub fn pressure_at_speed(
        &self,
        omega: f64,
        density_hub: f64,
        density_shaft: f64,
    ) -> Option<f64> {
        let loss = self.centrifugal_loss(omega, density_hub, density_shaft)?;
        self.pressure_in_service(0.0, loss)
    }

    /// Angular speed at which the fit opens (rad/s), where ΔU_ω = U_w:
    /// ω_ab = √(U_w / c) with ΔU_ω = c ω² ([`Fit::centrifugal_loss`]); rate with U_w,min. Same
    /// material: ω_ab = √(16 E U_w/(ρ D_F (3 + ν)(D_aA² − D_iI²))). The speed in 1/min is
    /// n_ab = 60 ω_ab/(2π). Zero when U_w ≤ 0; infinite when the hub grows no more than the
    /// shaft (c ≤ 0). `None` as for [`Fit::centrifugal_loss`].
    pub fn opening_speed(&self, density_hub: f64, density_shaft: f64) -> Option<f64> {
        self.opening_speed_in_service(0.0, density_hub, density_shaft)
    }

    /// Angular speed at which the fit opens at its operating temperatures (rad/s), where
    /// ΔU_ω = U_w − ΔU_ϑ: ω_ab = √((U_w − ΔU_ϑ)/c), `thermal` = ΔU_ϑ (mm) from
    /// [`Fit::thermal_loss`], c as in [`Fit::opening_speed`] (which this is for ΔU_ϑ = 0); the
    /// speed at which [`Fit::pressure_in_service`] reaches 0. Zero when the temperatures alone
    /// open the fit (U_w ≤ ΔU_ϑ); infinite when the hub grows no more than the shaft. `None` as
    /// for [`Fit::centrifugal_loss`], or for a non-finite `thermal`.
    pub fn opening_speed_in_service(
        &self,
        thermal: f64,
        density_hub: f64,
        density_shaft: f64,
    ) -> Option<f64> {
        let c = self.centrifugal_coefficient(density_hub, density_shaft)?;
        if !thermal.is_finite() {
            return None;
        }
        let u_w = self.effective_interference() - thermal;
        Some(if u_w <= 0.0 {
            0.0
        } else if c <= 0.0 {
            f64::INFINITY
        } else {
            (u_w / c).sqrt()
        })
    }

    /// The friction force p π D_F l_F ν (N), or `None` for an invalid fit, ν ≤ 0 or p < 0.
    fn friction_capacity(&self, p: f64, adhesion: f64) -> Option<f64> {
        self.ratios()?;
        (positive(adhesion) && non_negative(p)).then_some(p * PI * self.d_f * self.l_f * adhesion)
    }

    /// c in ΔU_ω = c ω² (mm s²): 2 (u_A − u_I)/ω².
    fn centrifugal_coefficient(&self, density_hub: f64, density_shaft: f64) -> Option<f64> {
        self.ratios()?;
        if !positive(density_hub) || !positive(density_shaft) {
            return None;
        }
        let growth = |rho: f64, e: f64, nu: f64, d: f64| {
            rho * self.d_f / (32.0 * e) * ((3.0 + nu) * d * d + (1.0 - nu) * self.d_f * self.d_f)
        };
        let hub = growth(density_hub, self.e_hub, self.poisson_hub, self.d_aa);
        let shaft = growth(density_shaft, self.e_shaft, self.poisson_shaft, self.d_ii);
        Some(2.0 * (hub - shaft))
    }
}

/// DIN's simplified equivalent stress (√3/2)(σ_max − σ_min) over the in-plane stresses `t`, `r`
/// and σ_z = 0.
fn din_equivalent(t: f64, r: f64) -> f64 {
    let max = t.max(r).max(0.0);
    let min = t.min(r).min(0.0);
    0.5 * SQRT3 * (max - min)
}
