//! VDI 2230-1:2015, systematic calculation of highly stressed bolted joints: the handbook's side
//! of a concentric single-bolt joint, through-bolted with a nut (DSV) or screwed into a tapped
//! part (ESV), loaded by a concentric axial working load.
//!
//! Units: N, mm, MPa; torques in N·mm; resiliences δ in mm/N; embedding in µm where the
//! guideline gives it in µm. The requirement numbers R3 to R13 are those of the guideline's
//! calculation steps. Eccentric clamping and loading (Φ*_en, the bending terms) are not covered.

use super::thread::{circle, Thread};
use super::{non_negative, positive, safety};
use std::f64::consts::PI;

/// Utilization ν of the minimum yield strength by the equivalent stress at assembly that
/// VDI 2230-1:2015 R7 uses for its tables (0.9).
pub const UTILIZATION: f64 = 0.9;

/// The kind of joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Joint {
    /// Through-bolted joint with a nut (DSV): the cone opens from both bearing faces, w = 1.
    Through,
    /// Tapped thread joint (ESV), the bolt screwed into the last part: one cone, w = 2.
    Tapped,
}

impl Joint {
    /// The joint coefficient w of the deformation cone: 1 for DSV, 2 for ESV.
    pub fn w(self) -> f64 {
        match self {
            Joint::Through => 1.0,
            Joint::Tapped => 2.0,
        }
    }
}

/// The bolt head, for the substitute length of its resilience.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Head {
    /// Hexagon head: l_SK = 0.5 d.
    Hexagon,
    /// Hexagon socket (cap screw) head: l_SK = 0.4 d.
    Socket,
}

/// A cylindrical section of the bolt's shank inside the clamp (or between head and clamp).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShankSection {
    /// Length l_i (mm).
    pub length: f64,
    /// Diameter d_i (mm).
    pub diameter: f64,
}

/// The bolt, for its resilience δ_S.
#[derive(Clone, Debug, PartialEq)]
pub struct Bolt {
    /// The thread (nominal d, pitch).
    pub thread: Thread,
    /// The head type.
    pub head: Head,
    /// The unthreaded shank sections, head to thread (none for a fully threaded bolt).
    pub shank: Vec<ShankSection>,
    /// Length l_Gew of the free loaded thread between the shank and the engaged thread (mm).
    pub free_thread: f64,
    /// Young's modulus of the bolt E_S (MPa).
    pub e_bolt: f64,
    /// Young's modulus of the nut (DSV) E_M or of the tapped part (ESV) E_BI (MPa).
    pub e_nut: f64,
}

/// The bolt's resilience and its parts (mm/N), δ = l/(E A), VDI 2230-1:2015 R3.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoltResilience {
    /// Head δ_SK = l_SK/(E_S A_N), l_SK = 0.5 d (hexagon) or 0.4 d (socket).
    pub head: f64,
    /// Shank sections Σ l_i/(E_S A_i), A_i = π d_i²/4.
    pub shank: f64,
    /// Free loaded thread δ_Gew = l_Gew/(E_S A_d3).
    pub free_thread: f64,
    /// Engaged thread δ_G = 0.5 d/(E_S A_d3).
    pub engaged_thread: f64,
    /// Nut or tapped part δ_M = l_M/(E_M A_N), l_M = 0.4 d (DSV, nut), 0.33 d (ESV).
    pub nut: f64,
    /// δ_S, the sum.
    pub total: f64,
}

/// Resilience of the bolt δ_S = δ_SK + Σ δ_i + δ_Gew + δ_G + δ_M (mm/N), the parts as in
/// [`BoltResilience`] (VDI 2230-1:2015 R3, resilience of the bolt). `None` unless d3 > 0, the
/// moduli and the shank diameters are positive and the lengths are not negative.
pub fn bolt_resilience(bolt: &Bolt, joint: Joint) -> Option<BoltResilience> {
    let d = bolt.thread.d;
    let (a_n, a_d3) = (bolt.thread.nominal_area(), bolt.thread.core_area());
    let shank_ok = bolt
        .shank
        .iter()
        .all(|s| non_negative(s.length) && positive(s.diameter));
    let ok = positive(d) && bolt.thread.d3() > 0.0 && positive(bolt.e_bolt) && positive(bolt.e_nut);
    if !ok || !shank_ok || !non_negative(bolt.free_thread) {
        return None;
    }
    let e = bolt.e_bolt;
    let l_sk = match bolt.head {
        Head::Hexagon => 0.5 * d,
        Head::Socket => 0.4 * d,
    };
    let l_m = match joint {
        Joint::Through => 0.4 * d,
        Joint::Tapped => 0.33 * d,
    };
    let head = l_sk / (e * a_n);
    let shank = bolt
        .shank
        .iter()
        .map(|s| s.length / (e * circle(s.diameter)))
        .sum();
    let free_thread = bolt.free_thread / (e * a_d3);
    let engaged_thread = 0.5 * d / (e * a_d3);
    let nut = l_m / (bolt.e_nut * a_n);
    Some(BoltResilience {
        head,
        shank,
        free_thread,
        engaged_thread,
        nut,
        total: head + shank + free_thread + engaged_thread + nut,
    })
}

/// The clamped parts, for their resilience δ_P (one material).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clamp {
    /// Clamp length l_K (mm).
    pub l_k: f64,
    /// Outer diameter of the bearing face of head or nut, d_W (mm).
    pub d_w: f64,
    /// Diameter of the clearance hole d_h (mm).
    pub d_h: f64,
    /// Outer diameter of the clamped parts (mm): the substitute diameter D'_A of the basic
    /// solid in y = D'_A/d_W and the diameter D_A that selects the case. They are the same for a
    /// cylindrical clamp; for other shapes the guideline's D'_A is the caller's choice.
    pub d_a: f64,
    /// Young's modulus of the clamped parts E_P (MPa).
    pub e_plate: f64,
}

/// Which body of revolution carries the clamp load (VDI 2230-1:2015 R3, resilience of the
/// clamped parts).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlateCase {
    /// D_A ≥ D_A,Gr: full deformation cone(s).
    Cone,
    /// d_W < D_A < D_A,Gr: cones cut by the outer diameter, a sleeve between them.
    ConeAndSleeve,
    /// D_A ≤ d_W: a sleeve of outer diameter D_A.
    Sleeve,
}

/// The clamped parts' resilience and the cone it came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlateResilience {
    /// δ_P (mm/N).
    pub delta_p: f64,
    /// tan φ of the deformation cone (-).
    pub tan_phi: f64,
    /// Limit diameter D_A,Gr = d_W + w l_K tan φ (mm).
    pub limit_diameter: f64,
    /// The case that applies.
    pub case: PlateCase,
}

/// Tangent of the cone angle (VDI 2230-1:2015 R3, deformation cone), with β_L = l_K/d_W and
/// y = D'_A/d_W:
///
/// ```text
///   DSV: tan φ_D = 0.362 + 0.032 ln(β_L/2) + 0.153 ln y
///   ESV: tan φ_E = 0.348 + 0.013 ln β_L + 0.193 ln y
/// ```
///
/// `None` unless β_L > 0, y > 0 and the result is positive.
pub fn cone_tangent(joint: Joint, beta_l: f64, y: f64) -> Option<f64> {
    if !positive(beta_l) || !positive(y) {
        return None;
    }
    let t = match joint {
        Joint::Through => 0.362 + 0.032 * (beta_l / 2.0).ln() + 0.153 * y.ln(),
        Joint::Tapped => 0.348 + 0.013 * beta_l.ln() + 0.193 * y.ln(),
    };
    positive(t).then_some(t)
}

/// Resilience of the clamped parts δ_P (mm/N) by the deformation cone (VDI 2230-1:2015 R3):
/// tan φ from [`cone_tangent`], D_A,Gr = d_W + w l_K tan φ, then [`plate_resilience_cone`] for
/// D_A ≥ D_A,Gr, [`plate_resilience_cone_sleeve`] for d_W < D_A < D_A,Gr and
/// [`plate_resilience_sleeve`] for D_A ≤ d_W. `None` for an invalid clamp (see those).
pub fn plate_resilience(clamp: &Clamp, joint: Joint) -> Option<PlateResilience> {
    check_clamp(clamp)?;
    let tan_phi = cone_tangent(joint, clamp.l_k / clamp.d_w, clamp.d_a / clamp.d_w)?;
    let limit_diameter = clamp.d_w + joint.w() * clamp.l_k * tan_phi;
    let (case, delta_p) = if clamp.d_a >= limit_diameter {
        (
            PlateCase::Cone,
            plate_resilience_cone(clamp, joint, tan_phi)?,
        )
    } else if clamp.d_a > clamp.d_w {
        let d = plate_resilience_cone_sleeve(clamp, joint, tan_phi)?;
        (PlateCase::ConeAndSleeve, d)
    } else {
        (PlateCase::Sleeve, plate_resilience_sleeve(clamp)?)
    };
    Some(PlateResilience {
        delta_p,
        tan_phi,
        limit_diameter,
        case,
    })
}

/// δ_P of the full cone(s), D_A ≥ D_A,Gr (mm/N), VDI 2230-1:2015 R3:
///
/// ```text
///   δ_P = 2 ln[(d_W + d_h)(d_W + w l_K tan φ − d_h) / ((d_W − d_h)(d_W + w l_K tan φ + d_h))]
///         / (w E_P π d_h tan φ)
/// ```
///
/// (D_A is not used.) `None` unless l_K > 0, d_W > d_h > 0, E_P > 0, tan φ > 0.
pub fn plate_resilience_cone(clamp: &Clamp, joint: Joint, tan_phi: f64) -> Option<f64> {
    let Clamp { l_k, d_w, d_h, .. } = *clamp;
    if !(positive(l_k) && positive(d_h) && d_w > d_h && positive(clamp.e_plate)) {
        return None;
    }
    if !positive(tan_phi) {
        return None;
    }
    let w = joint.w();
    let spread = d_w + w * l_k * tan_phi;
    let log = ((d_w + d_h) * (spread - d_h) / ((d_w - d_h) * (spread + d_h))).ln();
    Some(2.0 * log / (w * clamp.e_plate * PI * d_h * tan_phi))
}

/// δ_P of the cones cut by the outer diameter with a sleeve between them,
/// d_W ≤ D_A ≤ D_A,Gr (mm/N), VDI 2230-1:2015 R3:
///
/// ```text
///   δ_P = { 2/(w d_h tan φ) ln[(d_W + d_h)(D_A − d_h) / ((d_W − d_h)(D_A + d_h))]
///         + 4/(D_A² − d_h²) [l_K − (D_A − d_W)/(w tan φ)] } / (E_P π)
/// ```
///
/// Equal to the full cone at D_A = D_A,Gr and to the sleeve at D_A = d_W. `None` for an invalid
/// clamp ([`plate_resilience`]) or D_A outside [d_W, D_A,Gr].
pub fn plate_resilience_cone_sleeve(clamp: &Clamp, joint: Joint, tan_phi: f64) -> Option<f64> {
    check_clamp(clamp)?;
    let Clamp {
        l_k, d_w, d_h, d_a, ..
    } = *clamp;
    let w = joint.w();
    // cone length left for the sleeve; a rounding's worth beyond D_A,Gr counts as zero
    let sleeve = l_k - (d_a - d_w) / (w * tan_phi);
    if !positive(tan_phi) || d_a < d_w || sleeve < -1e-12 * l_k {
        return None;
    }
    let log = ((d_w + d_h) * (d_a - d_h) / ((d_w - d_h) * (d_a + d_h))).ln();
    let cones = 2.0 / (w * d_h * tan_phi) * log;
    let sleeve = 4.0 / (d_a * d_a - d_h * d_h) * sleeve.max(0.0);
    Some((cones + sleeve) / (clamp.e_plate * PI))
}

/// δ_P of a sleeve, D_A ≤ d_W: δ_P = l_K/(E_P π/4 (D_A² − d_h²)) (mm/N), VDI 2230-1:2015 R3.
/// `None` for an invalid clamp ([`plate_resilience`]).
pub fn plate_resilience_sleeve(clamp: &Clamp) -> Option<f64> {
    check_clamp(clamp)?;
    let area = circle(clamp.d_a) - circle(clamp.d_h);
    Some(clamp.l_k / (clamp.e_plate * area))
}

/// l_K > 0, d_W > d_h > 0, D_A > d_h, E_P > 0.
fn check_clamp(c: &Clamp) -> Option<()> {
    let ok = positive(c.l_k)
        && positive(c.d_h)
        && positive(c.d_w)
        && c.d_w > c.d_h
        && positive(c.d_a)
        && c.d_a > c.d_h
        && positive(c.e_plate);
    ok.then_some(())
}

/// Load factor Φ_K = δ_P/(δ_S + δ_P) (-), concentric clamping with the load introduced under
/// the head and nut (VDI 2230-1:2015 R3). `None` unless both resiliences are positive.
pub fn load_factor(delta_s: f64, delta_p: f64) -> Option<f64> {
    (positive(delta_s) && positive(delta_p)).then(|| delta_p / (delta_s + delta_p))
}

/// Load factor with the load introduction factor n, Φ_n = n Φ_K (-), concentric case
/// (VDI 2230-1:2015 R3; n from the guideline's table of joint types). `None` unless
/// 0 ≤ n ≤ 1 and 0 ≤ Φ_K ≤ 1.
pub fn load_factor_introduced(phi_k: f64, n: f64) -> Option<f64> {
    ((0.0..=1.0).contains(&n) && (0.0..=1.0).contains(&phi_k)).then_some(n * phi_k)
}

/// Additional bolt load F_SA = Φ_n F_A (N), VDI 2230-1:2015 R3.
pub fn additional_bolt_load(phi_n: f64, f_a: f64) -> f64 {
    phi_n * f_a
}

/// Load relieving the clamped parts F_PA = (1 − Φ_n) F_A (N), VDI 2230-1:2015 R3.
pub fn plate_relief(phi_n: f64, f_a: f64) -> f64 {
    (1.0 - phi_n) * f_a
}

/// Guide value of the embedding f_Z (µm) of solid steel parts under an axial load, from the
/// mean roughness depth Rz (µm) and the number of interfaces: one thread, `bearing_faces` head
/// or nut bearing faces (2 for DSV, 1 for ESV) and `inner_interfaces` interfaces between the
/// clamped parts (VDI 2230-1:2015 R4, guide values for embedding):
///
/// ```text
///   Rz < 10:       3 + 2.5 per bearing face + 1.5 per inner interface
///   10 ≤ Rz < 40:  3 + 3   per bearing face + 2   per inner interface
///   40 ≤ Rz < 160: 3 + 4   per bearing face + 3   per inner interface
/// ```
///
/// These guide values are recalled, not read from the guideline; they need checking against its
/// table (which also has values for a transverse load, not given here). `None` for Rz < 0 or
/// Rz ≥ 160.
pub fn embedding_guide(rz: f64, bearing_faces: u32, inner_interfaces: u32) -> Option<f64> {
    let (thread, bearing, inner) = if !non_negative(rz) {
        return None;
    } else if rz < 10.0 {
        (3.0, 2.5, 1.5)
    } else if rz < 40.0 {
        (3.0, 3.0, 2.0)
    } else if rz < 160.0 {
        (3.0, 4.0, 3.0)
    } else {
        return None;
    };
    Some(thread + bearing * f64::from(bearing_faces) + inner * f64::from(inner_interfaces))
}

/// Loss of preload by embedding F_Z = f_Z/(δ_S + δ_P) (N), f_Z in µm (divided by 1000 here),
/// VDI 2230-1:2015 R4. `None` for f_Z < 0 or non-positive resiliences.
pub fn embedding_loss(f_z: f64, delta_s: f64, delta_p: f64) -> Option<f64> {
    let ok = non_negative(f_z) && positive(delta_s) && positive(delta_p);
    ok.then(|| f_z * 1e-3 / (delta_s + delta_p))
}

/// Minimum assembly preload F_M,min = F_K,erf + (1 − Φ_n) F_A,max + F_Z + ΔF'_Vth (N),
/// VDI 2230-1:2015 R5: required clamp load, relief by the working load, embedding and the
/// thermal change of preload (0 at room temperature).
pub fn min_assembly_preload(f_k_erf: f64, phi_n: f64, f_a_max: f64, f_z: f64, dfv_th: f64) -> f64 {
    f_k_erf + plate_relief(phi_n, f_a_max) + f_z + dfv_th
}

/// Maximum assembly preload F_M,max = α_A F_M,min (N), α_A the tightening factor (-),
/// VDI 2230-1:2015 R6. `None` for α_A < 1. The joint passes R6/R7 when F_M,max ≤ F_M,zul.
pub fn max_assembly_preload(alpha_a: f64, f_m_min: f64) -> Option<f64> {
    (alpha_a.is_finite() && alpha_a >= 1.0).then_some(alpha_a * f_m_min)
}

/// Residual clamp load F_KR = F_M,min − F_PA − F_Z − ΔF'_Vth (N), which must be at least
/// F_K,erf (VDI 2230-1:2015 R5 rearranged).
pub fn residual_clamp_load(f_m_min: f64, f_pa: f64, f_z: f64, dfv_th: f64) -> f64 {
    f_m_min - f_pa - f_z - dfv_th
}

/// Working load at which the concentric joint opens, F_A,ab = F_V/(1 − Φ_n) (N), with the
/// preload F_V = F_M − F_Z: the load that relieves the clamped parts by all of F_V
/// (VDI 2230-1:2015, opening limit for concentric loading). `None` for Φ_n outside [0, 1).
pub fn separation_load(f_v: f64, phi_n: f64) -> Option<f64> {
    (0.0..1.0).contains(&phi_n).then(|| f_v / (1.0 - phi_n))
}

/// Permissible assembly preload (N), VDI 2230-1:2015 R7:
///
/// ```text
///   F_M,zul = ν R_p0.2min A_0 / √(1 + 3 [(3/2)(d2/d_0)(P/(π d2) + 1.155 µ_G,min)]²)
/// ```
///
/// The equivalent stress at assembly reaches ν R_p0.2min (ν = [`UTILIZATION`]) with the thread
/// torque [`thread_torque`] on the fully plastic torsional modulus π d_0³/12 (hence the 3/2).
/// A_0 = π d_0²/4 is the smallest section; d_0 = d_S ([`Thread::stress_diameter`]) for a
/// normal shank bolt, the waist diameter of a necked-down one. `None` unless d_0, d2 and
/// R_p0.2 are positive, µ_G ≥ 0 and 0 < ν ≤ 1.
pub fn permissible_assembly_preload(
    thread: &Thread,
    d_0: f64,
    r_p02: f64,
    mu_g: f64,
    utilization: f64,
) -> Option<f64> {
    let d2 = thread.d2();
    let ok = positive(d_0) && positive(d2) && positive(thread.pitch) && positive(r_p02);
    if !(ok && non_negative(mu_g) && positive(utilization) && utilization <= 1.0) {
        return None;
    }
    let k = 1.5 * d2 / d_0 * (thread.pitch / (PI * d2) + 1.155 * mu_g);
    Some(utilization * r_p02 * circle(d_0) / (1.0 + 3.0 * k * k).sqrt())
}

/// Thread torque M_G = F_M (d2/2)(P/(π d2) + 1.155 µ_G) (N·mm) at the preload F_M (N),
/// VDI 2230-1:2015 R7/R8 (1.155 = 1/cos 30°, the flank angle of the metric thread).
pub fn thread_torque(thread: &Thread, f_m: f64, mu_g: f64) -> f64 {
    let d2 = thread.d2();
    f_m * d2 / 2.0 * (thread.pitch / (PI * d2) + 1.155 * mu_g)
}

/// Friction diameter of the bearing face D_Km = (d_W + d_h)/2 (mm), VDI 2230-1:2015 R13.
pub fn friction_diameter(d_w: f64, d_h: f64) -> f64 {
    0.5 * (d_w + d_h)
}

/// Tightening torque M_A = F_M (0.16 P + 0.58 d2 µ_G + µ_K D_Km/2) (N·mm) for the preload F_M
/// (N; F_M,zul for the tables), VDI 2230-1:2015 R13.
pub fn tightening_torque(thread: &Thread, f_m: f64, mu_g: f64, mu_k: f64, d_km: f64) -> f64 {
    f_m * (0.16 * thread.pitch + 0.58 * thread.d2() * mu_g + mu_k * d_km / 2.0)
}

/// Largest bolt force in service F_S,max = F_M,zul + Φ_n F_A,max − ΔF_Vth (N),
/// VDI 2230-1:2015 R8 (ΔF_Vth: the thermal loss of preload, 0 at room temperature).
pub fn max_bolt_force(f_m_zul: f64, phi_n: f64, f_a_max: f64, dfv_th: f64) -> f64 {
    f_m_zul + additional_bolt_load(phi_n, f_a_max) - dfv_th
}

/// The working stress of the bolt, VDI 2230-1:2015 R8.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkingStress {
    /// Tensile stress σ_z,max = F_S,max/A_0 (MPa).
    pub tension: f64,
    /// Torsional stress τ_max = M_G/W_p, W_p = π d_0³/16 (MPa).
    pub torsion: f64,
    /// Equivalent stress σ_red,B = √(σ_z,max² + 3 (k_τ τ_max)²) (MPa).
    pub equivalent: f64,
    /// Safety against yield S_F = R_p0.2min/σ_red,B (-), required ≥ 1.0.
    pub safety: f64,
}

/// Working stress and yield safety in service (VDI 2230-1:2015 R8) from the largest bolt force
/// F_S,max (N, [`max_bolt_force`]), the thread torque left from tightening M_G (N·mm,
/// [`thread_torque`] at F_M,zul), the smallest section's diameter d_0 (mm), the reduction of
/// the torsion k_τ (-, 0.5 recommended) and R_p0.2min (MPa); formulas in [`WorkingStress`].
/// `None` unless d_0 and R_p0.2 are positive, F_S,max and M_G finite and 0 ≤ k_τ ≤ 1.
pub fn working_stress(
    f_s_max: f64,
    m_g: f64,
    d_0: f64,
    k_tau: f64,
    r_p02: f64,
) -> Option<WorkingStress> {
    let ok = positive(d_0) && positive(r_p02) && f_s_max.is_finite() && m_g.is_finite();
    if !ok || !(0.0..=1.0).contains(&k_tau) {
        return None;
    }
    let tension = f_s_max / circle(d_0);
    let torsion = m_g / (PI * d_0.powi(3) / 16.0);
    let equivalent = tension.hypot(3f64.sqrt() * k_tau * torsion);
    Some(WorkingStress {
        tension,
        torsion,
        equivalent,
        safety: safety(r_p02, equivalent)?,
    })
}

/// Stress amplitude σ_a = (F_SAo − F_SAu)/(2 A_S) (MPa) from the upper and lower additional
/// bolt loads (N) and the stress area A_S (mm²; A_0 for a necked-down bolt),
/// VDI 2230-1:2015 R9. `None` for A_S ≤ 0.
pub fn stress_amplitude(f_sa_upper: f64, f_sa_lower: f64, a_s: f64) -> Option<f64> {
    positive(a_s).then(|| (f_sa_upper - f_sa_lower).abs() / (2.0 * a_s))
}

/// Endurance limit (amplitude) of a bolt rolled before heat treatment (SV),
/// σ_ASV = 0.85 (150/d + 45) (MPa, d in mm), VDI 2230-1:2015 R9. `None` for d ≤ 0.
pub fn endurance_rolled_before(d: f64) -> Option<f64> {
    positive(d).then(|| 0.85 * (150.0 / d + 45.0))
}

/// Endurance limit of a bolt rolled after heat treatment (SG),
/// σ_ASG = (2 − F_Sm/F_0.2min) σ_ASV (MPa), with the mean bolt force F_Sm (N) and
/// F_0.2min = R_p0.2min A_0 (N), VDI 2230-1:2015 R9. The guideline gives it for
/// 0.3 < F_Sm/F_0.2min < 1 (range recalled, to verify); `None` for a ratio outside (0, 1) or
/// d ≤ 0.
pub fn endurance_rolled_after(d: f64, f_sm: f64, f_02min: f64) -> Option<f64> {
    let ratio = f_sm / f_02min;
    let ok = positive(f_02min) && ratio > 0.0 && ratio < 1.0;
    if !ok {
        return None;
    }
    Some((2.0 - ratio) * endurance_rolled_before(d)?)
}

/// Fatigue safety S_D = σ_AS/σ_a (-), required ≥ 1.2, VDI 2230-1:2015 R9 (see
/// [`super::safety`]).
pub fn fatigue_safety(sigma_as: f64, sigma_a: f64) -> Option<f64> {
    safety(sigma_as, sigma_a)
}

/// Smallest bearing area under the head or nut A_p,min = π/4 (d_W² − d_h²) (mm²),
/// VDI 2230-1:2015 R10. `None` unless d_W > d_h ≥ 0.
pub fn bearing_area(d_w: f64, d_h: f64) -> Option<f64> {
    (non_negative(d_h) && d_w.is_finite() && d_w > d_h).then(|| circle(d_w) - circle(d_h))
}

/// Surface pressure p = F/A_p,min (MPa): with F = F_M,zul at assembly (p_M,max), with
/// F = F_V,max + F_SA,max − ΔF_Vth in service (p_B,max), VDI 2230-1:2015 R10. `None` for
/// A_p ≤ 0 or F < 0.
pub fn surface_pressure(force: f64, a_p: f64) -> Option<f64> {
    (positive(a_p) && non_negative(force)).then(|| force / a_p)
}

/// Safety against the limiting surface pressure S_P = p_G/p (-), required ≥ 1.0,
/// VDI 2230-1:2015 R10 (see [`super::safety`]).
pub fn surface_pressure_safety(p_g: f64, p: f64) -> Option<f64> {
    safety(p_g, p)
}
