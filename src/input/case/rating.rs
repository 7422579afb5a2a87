//! The keys of `[[rating]]` (docs/case-schema.md, "Ratings"): a joint rated
//! to a design standard, with the inputs the FE cannot know (safety factors,
//! thread, friction in the thread, tightening scatter, material limits). What
//! they name on the model (interfaces, sections, loads) is checked when the
//! model is built ([`crate::verdict`]); here, what the case alone decides.

use crate::error::{clip, Error, Result};
use serde::{Deserialize, Serialize};

/// One `[[rating]]`: the standard is its `standard` key.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(tag = "standard")]
pub enum RatingSpec {
    /// DIN 7190-1:2017, a cylindrical interference fit.
    #[serde(rename = "DIN 7190-1:2017", alias = "DIN 7190")]
    Fit(FitSpec),
    /// VDI 2230-1:2015, a concentric through-bolted joint.
    #[serde(rename = "VDI 2230-1:2015", alias = "VDI 2230")]
    Bolt(BoltSpec),
    /// A joint under load cycles: the steady cycles of one interface for the
    /// part a designer names (no standard: the closed form of a uniform
    /// Masing joint beside the run).
    #[serde(rename = "joint cycles")]
    Cycles(CyclesSpec),
}

/// DIN 7190-1:2017: the fit along `interface` (an axisymmetric model: the
/// inner body is the shaft, the outer the hub; their radii and the joint's
/// length are read from the mesh, the interference from the interface's
/// `gap`).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FitSpec {
    /// The rating's name in the outputs; default: the interface's.
    pub name: Option<String>,
    pub interface: String,
    /// The torque the fit must transmit, N·m (before the application factor).
    pub torque: Option<f64>,
    /// The axial force it must transmit, N.
    pub axial_force: Option<f64>,
    /// K_A; default 1.
    pub application_factor: Option<f64>,
    /// S_r required against slip; default 1.5.
    pub slip_safety: Option<f64>,
    /// S_F required against yield; default 1.1.
    pub yield_safety: Option<f64>,
    /// ν_r, the adhesion coefficient; default the interface's `mu`.
    pub adhesion: Option<f64>,
    /// Rz of the hub's bore and of the shaft, µm; default 0.
    pub rz_hub: Option<f64>,
    pub rz_shaft: Option<f64>,
    /// The smoothing ΔU = k (Rz_hub + Rz_shaft); default 0.4 (2017; 0.8 in 2001).
    pub smoothing: Option<f64>,
}

/// VDI 2230-1:2015: the through-bolted joint whose bolt is the pretension
/// section `pretension`, clamping plates that meet at `joint`, the head and
/// nut bearing on the interfaces `head` and `nut` (an axisymmetric model
/// about the bolt's axis).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BoltSpec {
    /// The rating's name in the outputs; default: the section's.
    pub name: Option<String>,
    pub pretension: String,
    /// The interface between the clamped plates.
    pub joint: String,
    /// The interfaces under the head and under the nut.
    pub head: String,
    pub nut: String,
    /// ISO metric thread: "M12" (coarse) or "M12x1.5".
    pub thread: String,
    /// ISO 898-1 property class ("8.8", "10.9", …); default: the bolt
    /// body's `yield_stress` as R_p0.2.
    pub property_class: Option<String>,
    /// μ_G, friction in the thread (for F_M,zul and the tightening torque).
    pub thread_friction: f64,
    /// μ_K, friction under the head; default μ_G.
    pub head_friction: Option<f64>,
    /// α_A, the tightening factor (F_M,max / F_M,min).
    pub tightening_factor: f64,
    /// "rolled" (before heat treatment, the default) or
    /// "rolled_after_heat_treatment".
    pub threads: Option<String>,
    /// The `[[load]]` and `[[force]]` entries that are the service load
    /// F_A (`load[0]`, `force[1]`); default every one of them.
    pub service_load: Option<Vec<String>>,
    /// F_K,erf, the clamp load the joint needs, N; default 0.
    pub clamp_load: Option<f64>,
    /// f_Z, the embedding (settling), µm; default the standard's guide
    /// value for Rz < 10 µm.
    pub embedding: Option<f64>,
    /// p_G, the limiting surface pressure of the clamped parts, MPa.
    pub surface_pressure_limit: Option<f64>,
    /// n, the load introduction factor of the handbook's side; default the
    /// FE's, back-calculated.
    pub load_introduction: Option<f64>,
    /// Free loaded thread length inside the clamp, mm; default 0.
    pub free_thread_length: Option<f64>,
}

/// A joint under load cycles: the last (steady) cycle of each amplitude
/// block of `interface`, for the part the model stands for: a plane model's
/// `width` (its results are for the model's thickness), an axisymmetric
/// model's whole ring, times `count` repeated joints.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CyclesSpec {
    /// The rating's name in the outputs; default: the interface's.
    pub name: Option<String>,
    pub interface: String,
    /// The part's width across the plane, mm (plane models only); default
    /// the model's thickness.
    pub width: Option<f64>,
    /// How many such joints the part holds (the ways of a slide, the bolts
    /// of a flange); default 1.
    pub count: Option<u32>,
    /// The least loss factor η each steady cycle must reach.
    pub min_loss_factor: Option<f64>,
    /// The least and the largest secant stiffness of the part, N/µm.
    pub min_stiffness: Option<f64>,
    pub max_stiffness: Option<f64>,
    /// The largest slip amplitude, µm.
    pub max_slip: Option<f64>,
}

impl RatingSpec {
    /// Its name in the outputs.
    pub fn name(&self) -> &str {
        match self {
            RatingSpec::Fit(f) => f.name.as_deref().unwrap_or(&f.interface),
            RatingSpec::Bolt(b) => b.name.as_deref().unwrap_or(&b.pretension),
            RatingSpec::Cycles(c) => c.name.as_deref().unwrap_or(&c.interface),
        }
    }

    /// The standard as printed.
    pub fn standard(&self) -> &'static str {
        match self {
            RatingSpec::Fit(_) => "DIN 7190-1:2017",
            RatingSpec::Bolt(_) => "VDI 2230-1:2015",
            RatingSpec::Cycles(_) => "joint cycles",
        }
    }
}

/// Each number of a rating against its range (a factor of safety below 1,
/// a friction coefficient of 3, a negative roughness), and unique names.
pub(crate) fn check(ratings: &[RatingSpec], place: &dyn Fn(&str) -> String) -> Result<()> {
    let mut names = std::collections::BTreeSet::new();
    for (i, r) in ratings.iter().enumerate() {
        let at = place(&format!("rating[{i}] ({})", r.standard()));
        let n = r.name();
        let bad = n.is_empty()
            || n.trim() != n
            || n.chars().any(|c| c == ',' || c == '"' || c.is_control());
        if bad {
            return Err(Error::input(
                format!("{at} name"),
                format!("\"{}\" cannot name a rating: it heads probes' rows and report lines, so no blanks around it, no comma, quote or control character, not empty", clip(n)),
            ));
        }
        if !names.insert(r.name().to_string()) {
            return Err(Error::input(
                at,
                format!(
                    "is named \"{}\" like an earlier rating: give each a `name` of its own",
                    clip(r.name())
                ),
            ));
        }
        for (key, v, lo, hi) in numbers(r) {
            if let Some(v) = v {
                if !(v.is_finite() && v >= lo && v <= hi) {
                    return Err(Error::input(
                        format!("{at} {key}"),
                        format!(
                            "= {} is outside [{lo}, {hi}], the range any design of this kind uses",
                            crate::numbers::num(v)
                        ),
                    ));
                }
            }
        }
        if let RatingSpec::Cycles(c) = r {
            if let (Some(lo), Some(hi)) = (c.min_stiffness, c.max_stiffness) {
                if lo > hi {
                    return Err(Error::input(
                        format!("{at} min_stiffness"),
                        format!(
                            "= {} N/µm is above max_stiffness = {} N/µm: no stiffness meets both",
                            crate::numbers::num(lo),
                            crate::numbers::num(hi)
                        ),
                    ));
                }
            }
        }
        if let RatingSpec::Bolt(b) = r {
            if let Some(t) = &b.threads {
                if t != "rolled" && t != "rolled_after_heat_treatment" {
                    return Err(Error::input(
                        format!("{at} threads"),
                        format!("= \"{}\" is not a kind of thread: \"rolled\" (before heat treatment) or \"rolled_after_heat_treatment\"", clip(t)),
                    ));
                }
            }
        }
    }
    Ok(())
}

type Ranged = (&'static str, Option<f64>, f64, f64);

/// Every number of a rating with its engineering range.
fn numbers(r: &RatingSpec) -> Vec<Ranged> {
    match r {
        RatingSpec::Fit(f) => vec![
            ("torque", f.torque, 0.0, 1e7),
            ("axial_force", f.axial_force, 0.0, 1e8),
            ("application_factor", f.application_factor, 1.0, 5.0),
            ("slip_safety", f.slip_safety, 1.0, 10.0),
            ("yield_safety", f.yield_safety, 1.0, 10.0),
            ("adhesion", f.adhesion, 0.01, 0.6),
            ("rz_hub", f.rz_hub, 0.0, 200.0),
            ("rz_shaft", f.rz_shaft, 0.0, 200.0),
            ("smoothing", f.smoothing, 0.0, 1.0),
        ],
        RatingSpec::Bolt(b) => vec![
            ("thread_friction", Some(b.thread_friction), 0.02, 0.6),
            ("head_friction", b.head_friction, 0.02, 0.6),
            ("tightening_factor", Some(b.tightening_factor), 1.0, 5.0),
            ("clamp_load", b.clamp_load, 0.0, 1e8),
            ("embedding", b.embedding, 0.0, 200.0),
            (
                "surface_pressure_limit",
                b.surface_pressure_limit,
                10.0,
                5000.0,
            ),
            ("load_introduction", b.load_introduction, 0.0, 1.0),
            ("free_thread_length", b.free_thread_length, 0.0, 1e4),
        ],
        RatingSpec::Cycles(c) => vec![
            ("width", c.width, 1e-3, 1e5),
            ("count", c.count.map(f64::from), 1.0, 1e4),
            ("min_loss_factor", c.min_loss_factor, 1e-6, 1.5),
            ("min_stiffness", c.min_stiffness, 1e-6, 1e9),
            ("max_stiffness", c.max_stiffness, 1e-6, 1e9),
            ("max_slip", c.max_slip, 1e-6, 1e4),
        ],
    }
}
