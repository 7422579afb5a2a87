//! Uniform body temperatures (`[[temperature]]`, docs/case-schema.md
//! "Temperatures"): each body's change ΔT from the stress-free state with its
//! history, read with the material's expansion coefficient α into the free
//! thermal strain α ΔT h(t) that its elements subtract from their normal
//! strains (docs/theory.md, "Thermal strain").

use super::{clip, Resolver, Scaled};
use crate::error::{Error, Result};
use crate::input::case::ranges;
use crate::input::case::Case;
use crate::input::mesh::Mesh;
use crate::model::history::History;

/// Absolute zero, °C.
pub(crate) const ABSOLUTE_ZERO: f64 = -273.15;

/// One body's uniform temperature change.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyTemperature {
    /// The body, by index in the mesh's bodies.
    pub body: usize,
    /// ΔT at factor 1, K.
    pub change: f64,
    /// α ΔT at factor 1: the free thermal strain.
    pub strain: f64,
    /// The temperature of the stress-free state, °C, when given.
    pub reference: Option<f64>,
    /// Its history (`None`: the load factor, or the default ramp).
    pub history: Option<usize>,
}

/// Every `[[temperature]]`: its body known, named once, its material with an
/// `expansion`, its reference a temperature; ΔT joins `scaled` (its range
/// times its history's peak is checked with the loads').
pub(super) fn read(
    case: &Case,
    mesh: &Mesh,
    place: &str,
    res: &mut Resolver<'_>,
    scaled: &mut Vec<Scaled>,
) -> Result<Vec<BodyTemperature>> {
    let mut out: Vec<BodyTemperature> = Vec::new();
    for (i, t) in case.temperature.iter().enumerate() {
        let at = format!("{place}: temperature[{i}] (body \"{}\")", clip(&t.body));
        let Some(body) = mesh.bodies.iter().position(|b| *b == t.body) else {
            return Err(Error::input(
                at,
                format!(
                    "no body named \"{}\" (bodies: {})",
                    clip(&t.body),
                    mesh.bodies.join(", ")
                ),
            ));
        };
        if let Some(k) = out.iter().position(|o| o.body == body) {
            return Err(Error::input(
                at,
                format!("the body already has a temperature (temperature[{k}]): give each body one [[temperature]]"),
            ));
        }
        let alpha = case.materials.get(&t.body).and_then(|m| m.expansion);
        let Some(alpha) = alpha else {
            return Err(Error::input(
                at,
                format!(
                    "[materials.{}] has no expansion: give the body's thermal expansion coefficient (1/K) to heat or cool it",
                    clip(&t.body)
                ),
            ));
        };
        if !t.change.is_finite() {
            return Err(Error::input(
                format!("{at} change"),
                format!("{} is not a finite number (K)", t.change),
            ));
        }
        if let Some(r) = t.reference {
            if !(r.is_finite() && (ABSOLUTE_ZERO..=1e4).contains(&r)) {
                return Err(Error::input(
                    format!("{at} reference"),
                    format!("{r} °C is no temperature of a solid: give one in [{ABSOLUTE_ZERO}, 1e4] °C"),
                ));
            }
        }
        let history = res.resolve(t.history.as_ref(), &format!("{at} history"))?;
        scaled.push((
            format!("{at} change"),
            t.change,
            &ranges::TEMPERATURE_CHANGE,
            history,
        ));
        out.push(BodyTemperature {
            body,
            change: t.change,
            strain: alpha * t.change,
            reference: t.reference,
            history,
        });
    }
    Ok(out)
}

/// With a reference given, the body's lowest temperature over the run
/// (ΔT times the lowest and the highest factor of its history, or of the
/// load factor from 0 to `largest`) must not fall below absolute zero.
pub(super) fn check_absolute(
    temperatures: &[BodyTemperature],
    histories: &[History],
    largest: f64,
    place: &str,
    bodies: &[String],
) -> Result<()> {
    for (i, t) in temperatures.iter().enumerate() {
        let Some(reference) = t.reference else {
            continue;
        };
        let (lo, hi) = match t.history {
            Some(h) => histories[h].extremes(),
            None if histories.is_empty() => (0.0, largest),
            None => (0.0, 1.0),
        };
        let lowest = reference + (t.change * lo).min(t.change * hi);
        if lowest < ABSOLUTE_ZERO {
            return Err(Error::input(
                format!(
                    "{place}: temperature[{i}] (body \"{}\") change",
                    clip(&bodies[t.body])
                ),
                format!(
                    "takes the body to {lowest} °C from its reference {reference} °C: below absolute zero ({ABSOLUTE_ZERO} °C)"
                ),
            ));
        }
    }
    Ok(())
}
