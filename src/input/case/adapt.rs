//! The `[adapt]` table (docs/case-schema.md, "Adaptive runs"): solve, estimate
//! the error, refine where it is, and solve again from the start of the load
//! history until the estimate is below a tolerance ([`crate::app::adapt`]). What
//! the case alone decides is checked here; the dof cap against the start mesh
//! when the model is built.

use super::Case;
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The largest number of adaptive cycles (solves) a case may ask for.
pub(crate) const MAX_CYCLES: usize = 20;
/// The default number of cycles.
pub(crate) const DEFAULT_CYCLES: usize = 8;
/// The default share of the squared estimate the marked elements hold
/// (Dörfler's bulk criterion, θ).
pub(crate) const DEFAULT_FRACTION: f64 = 0.5;
/// The default cap on the dofs of an adapted mesh.
pub(crate) const DEFAULT_MAX_DOFS: usize = 400_000;
/// The largest cap a case may give: about the dofs of a plane mesh of
/// [`super::MAX_ELEMENTS`] Q8 elements (some 3 nodes an element, 2 dofs a
/// node), the limit of every mesh, which each adapted mesh is held to as
/// well ([`crate::app::adapt`]).
pub(crate) const MAX_DOFS: usize = 6 * super::MAX_ELEMENTS;

/// `[adapt]`: an adaptive run.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct AdaptSpec {
    /// The estimate to reach, relative: of the energy norm, or of the named
    /// quantity; in (0, 1).
    pub tolerance: f64,
    /// What the tolerance applies to (default `energy`).
    #[serde(default)]
    pub quantity: Quantity,
    /// When the named quantity is read: at the end of the history (default)
    /// or its largest over every converged increment.
    #[serde(default)]
    pub over: Over,
    /// The most solves (the start mesh's included), 1..=`MAX_CYCLES`.
    #[serde(default = "default_cycles")]
    pub max_cycles: usize,
    /// No mesh with more dofs is solved: the run ends on the last mesh below.
    #[serde(default = "default_max_dofs")]
    pub max_dofs: usize,
    /// Dörfler's θ: the marked elements hold this share of Σ η_e², in (0, 1].
    #[serde(default = "default_fraction")]
    pub fraction: f64,
}

fn default_cycles() -> usize {
    DEFAULT_CYCLES
}
fn default_max_dofs() -> usize {
    DEFAULT_MAX_DOFS
}
fn default_fraction() -> f64 {
    DEFAULT_FRACTION
}

impl AdaptSpec {
    /// `--adapt TOL` without an `[adapt]` table: the energy norm, defaults.
    pub(crate) fn with_tolerance(tolerance: f64) -> AdaptSpec {
        AdaptSpec {
            tolerance,
            quantity: Quantity::Energy,
            over: Over::End,
            max_cycles: DEFAULT_CYCLES,
            max_dofs: DEFAULT_MAX_DOFS,
            fraction: DEFAULT_FRACTION,
        }
    }
}

/// The answer an adaptive run drives to its tolerance.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Quantity {
    /// The recovery estimate relative to the energy norm of the solution.
    #[default]
    Energy,
    /// The probe node's vertical displacement at the end of the history.
    Settlement,
    /// The whole-body load at the end of the history.
    TotalLoad,
    /// The first interface's mean contact pressure at the end.
    MeanPressure,
    /// The largest contact pressure at the end, over every interface.
    PeakPressure,
    /// The load (whole-body, kN) at which the first Gauss point yields.
    FirstYield,
    /// The torque the first interface transmits at the end (N·mm; twist).
    Torque,
    /// The largest von Mises stress over every body's Gauss points but
    /// those within one element size of a singular point of the start mesh
    /// ([`crate::model::excluded`]), MPa.
    MaxVonMises,
}

impl Quantity {
    pub(crate) const ALL: [(&'static str, Quantity); 8] = [
        ("energy", Quantity::Energy),
        ("settlement", Quantity::Settlement),
        ("total_load", Quantity::TotalLoad),
        ("mean_pressure", Quantity::MeanPressure),
        ("peak_pressure", Quantity::PeakPressure),
        ("first_yield", Quantity::FirstYield),
        ("torque", Quantity::Torque),
        ("max_von_mises", Quantity::MaxVonMises),
    ];

    pub fn name(self) -> &'static str {
        Quantity::ALL
            .iter()
            .find(|(_, q)| *q == self)
            .map(|(n, _)| *n)
            .expect("every quantity is named")
    }
}

/// When an adaptive run reads its named quantity (`[adapt] over`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Over {
    /// At the last converged increment, the end of the history.
    #[default]
    End,
    /// The value farthest from 0 over every converged increment (the rows
    /// of curve.csv), its sign kept ([`crate::app::adapt::farthest_from_zero`]).
    History,
}

impl Over {
    pub fn name(self) -> &'static str {
        match self {
            Over::End => "end",
            Over::History => "history",
        }
    }
}

/// The name [`Over::name`] gives, as the case spells it.
impl Serialize for Over {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Over {
    /// A string, `end` or `history`; anything else (another string, a
    /// number) is refused naming both.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Choice;
        impl serde::de::Visitor<'_> for Choice {
            type Value = Over;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("over \"end\" or \"history\"")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<Over, E> {
                match v {
                    "end" => Ok(Over::End),
                    "history" => Ok(Over::History),
                    _ => Err(E::invalid_value(serde::de::Unexpected::Str(v), &self)),
                }
            }
        }
        d.deserialize_any(Choice)
    }
}

/// The name [`Quantity::name`] gives, as the case spells it.
impl Serialize for Quantity {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Quantity {
    /// One of the names of `Quantity::ALL`; anything else is refused with
    /// every choice.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Choice;
        impl serde::de::Visitor<'_> for Choice {
            type Value = Quantity;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                let names: Vec<String> = Quantity::ALL
                    .iter()
                    .map(|(n, _)| format!("\"{n}\""))
                    .collect();
                write!(f, "quantity {}", names.join(", "))
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<Quantity, E> {
                Quantity::ALL
                    .iter()
                    .find(|(n, _)| *n == v)
                    .map(|(_, q)| *q)
                    .ok_or_else(|| E::invalid_value(serde::de::Unexpected::Str(v), &self))
            }
        }
        d.deserialize_str(Choice)
    }
}

/// The checks of `[adapt]` that need no mesh.
pub fn check(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let Some(a) = &case.adapt else { return Ok(()) };
    let exact = crate::numbers::exact;
    if !(a.tolerance.is_finite() && a.tolerance > 0.0 && a.tolerance < 1.0) {
        return Err(Error::input(
            at("[adapt] tolerance"),
            format!(
                "{} must be in (0, 1): the estimate to reach, relative to the quantity",
                exact(a.tolerance)
            ),
        ));
    }
    if a.tolerance < 1e-6 {
        return Err(Error::input(
            at("[adapt] tolerance"),
            format!(
                "{} is below 1e-6: no mesh this program can hold reaches it",
                exact(a.tolerance)
            ),
        ));
    }
    if !(1..=MAX_CYCLES).contains(&a.max_cycles) {
        return Err(Error::input(
            at("[adapt] max_cycles"),
            format!(
                "{} must be in 1..={MAX_CYCLES}: the solves, the start mesh's included",
                a.max_cycles
            ),
        ));
    }
    if a.max_dofs > MAX_DOFS {
        return Err(Error::input(
            at("[adapt] max_dofs"),
            format!(
                "{} is above {MAX_DOFS}, about the dofs of a mesh of {} elements (the limit of every mesh, adapted or not); a serial run takes some 3 kB of memory a dof (0.7 GB at 210 000 dofs): give at most {MAX_DOFS}",
                a.max_dofs,
                super::MAX_ELEMENTS
            ),
        ));
    }
    if !(a.fraction.is_finite() && a.fraction > 0.0 && a.fraction <= 1.0) {
        return Err(Error::input(
            at("[adapt] fraction"),
            format!(
                "{} must be in (0, 1]: the share of the squared estimate the refined elements hold",
                exact(a.fraction)
            ),
        ));
    }
    if a.quantity == Quantity::FirstYield
        && case.materials.values().all(|m| m.yield_stress.is_none())
    {
        return Err(Error::input(
            at("[adapt] quantity"),
            "\"first_yield\" in a case whose materials never yield (no yield_stress)",
        ));
    }
    if a.over == Over::History {
        check_history(a.quantity, at)?;
    }
    if a.quantity == Quantity::Torque && !case.model.twist {
        return Err(Error::input(
            at("[adapt] quantity"),
            "\"torque\" needs a twisting model ([model] twist = true): without twist no interface carries a torque",
        ));
    }
    // a torque-driven model: the torque through the interface is the applied
    // torque by equilibrium, the same on every mesh, so the run would stop
    // after two cycles, "reached", whatever the mesh
    if a.quantity == Quantity::Torque
        && !case
            .boundary
            .iter()
            .any(|b| b.rotation.is_some_and(|r| r != 0.0))
    {
        return Err(Error::input(
            at("[adapt] quantity"),
            "\"torque\" in a model driven by a torque (no [[boundary]] rotation other than 0): the interface transmits the applied torque by equilibrium on every mesh, so it measures no error; adapt on \"energy\", or prescribe the rotation",
        ));
    }
    // every named answer but the bodies' stress is read at the interfaces
    // (curve.csv's first interface, the probe node of body B): without one
    // it is 0 on every mesh, and the run would stop at once, "reached"
    if !matches!(a.quantity, Quantity::Energy | Quantity::MaxVonMises)
        && case.mesh.interface.is_empty()
        && case.interface.is_empty()
    {
        return Err(Error::input(
            at("[adapt] quantity"),
            format!(
                "\"{}\" in a case without an interface: it is measured at the interface (curve.csv), 0 on every mesh here; adapt on \"energy\" or \"max_von_mises\"",
                a.quantity.name()
            ),
        ));
    }
    Ok(())
}

/// `over = "history"` for a quantity that has no largest over the history:
/// the energy estimate (made of the last state alone) and the first-yield
/// load (one moment of the history, not a value at every increment).
fn check_history(q: Quantity, at: &dyn Fn(&str) -> String) -> Result<()> {
    let why = match q {
        Quantity::Energy => "the energy estimate η/‖u_h‖_E is made of the last state alone, not at every increment; name a quantity (\"peak_pressure\", \"max_von_mises\", ...) to adapt on its largest over the history, or leave `over` out",
        Quantity::FirstYield => "the first-yield load is one moment of the history (the load at which the first Gauss point yields), not a value at every increment: it has no largest over the history; leave `over` out, or adapt on \"max_von_mises\" over the history",
        _ => return Ok(()),
    };
    Err(Error::input(
        at("[adapt] over"),
        format!("\"history\" with quantity \"{}\": {why}", q.name()),
    ))
}
