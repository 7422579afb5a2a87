//! Uniform body temperatures (`[[temperature]]`, docs/case-schema.md
//! "Temperatures"): each body's change ΔT from the stress-free state with its
//! history, read with the material's expansion coefficient α into the free
//! thermal strain α ΔT h(t) that its elements subtract from their normal
//! strains (docs/theory.md, "Thermal strain").

use super::field::interpolate;
pub use super::field::{Coordinate, Field, Formula, Profile};
use super::{clip, Resolver, Scaled};
use crate::error::{Error, Result};
use crate::input::case::ranges;
use crate::input::case::Case;
use crate::input::mesh::Mesh;
use crate::model::history::History;
use crate::physics::element::Section;
use crate::physics::material::VonMises;

pub(crate) use crate::input::case::ranges::ABSOLUTE_ZERO;

/// One body's uniform temperature change.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyTemperature {
    /// The body, by index in the mesh's bodies.
    pub body: usize,
    /// ΔT at factor 1, K.
    pub change: f64,
    /// α ΔT at factor 1: the free thermal strain.
    pub strain: f64,
    /// α, the material's expansion coefficient, 1/K.
    pub alpha: f64,
    /// The temperature of the stress-free state, °C, when given.
    pub reference: Option<f64>,
    /// Its history (`None`: the load factor, or the default ramp).
    pub history: Option<usize>,
    /// Young's modulus and the initial yield stress against the body's
    /// temperature (rows [T °C, value], T rising), when its material has them.
    pub young: Option<Vec<[f64; 2]>>,
    pub yield_stress: Option<Vec<[f64; 2]>>,
    /// A temperature field: ΔT(x) = change × its factor at x.
    pub field: Option<Field>,
}

impl BodyTemperature {
    /// The body's material at the load factor `factor` of its history: E and
    /// σ_Y read off their tables at the temperature reference + ΔT · factor
    /// (linear between rows); `base` as it is without tables.
    /// (Where the body has a field, `factor` is its history's factor times
    /// the field's at the point: [`BodyTemperature::field_factor`].)
    pub fn material(&self, base: &VonMises, factor: f64) -> VonMises {
        let mut m = base.clone();
        if let Some(reference) = self.reference {
            let t = reference + self.change * factor;
            if let Some(rows) = &self.young {
                m.young = interpolate(rows, t);
            }
            if let Some(rows) = &self.yield_stress {
                m.yield_stress = interpolate(rows, t);
            }
        }
        m
    }

    /// Whether its material varies from point to point: a temperature field
    /// with a table of E or σ_Y (each Gauss point's material is then read
    /// at its own temperature).
    pub fn varies(&self) -> bool {
        self.field.is_some() && (self.young.is_some() || self.yield_stress.is_some())
    }

    /// Its field's factor at x (1 without a field).
    pub fn field_factor(&self, x: [f64; 3]) -> f64 {
        self.field.as_ref().map_or(1.0, |f| f.factor(x))
    }
}

/// A table's rows (two numbers each: checked with the case) as pairs.
fn pairs(rows: &[Vec<f64>]) -> Vec<[f64; 2]> {
    rows.iter().map(|r| [r[0], r[1]]).collect()
}

/// Every `[[temperature]]`: its body known, named once, its material with an
/// `expansion`, its reference a temperature; ΔT joins `scaled` (its range
/// times its history's peak is checked with the loads').
pub(super) fn read(
    case: &Case,
    (mesh, section): (&Mesh, &Section),
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
        let m = &case.materials[&t.body];
        let field = super::field::read(t, mesh, (body, section), &at)?;
        let peak = field.as_ref().map_or(1.0, |f| f.largest());
        if peak == 0.0 {
            return Err(Error::input(
                format!("{at} field"),
                "it is 0 over the whole body, so ΔT is 0 everywhere: give a field that is not zero somewhere, or leave the [[temperature]] out",
            ));
        }
        let label = match &field {
            Some(Field::Profile(_)) => {
                format!("{at} change (× its profile's largest factor, {peak})")
            }
            Some(Field::Formula(_)) => {
                format!("{at} change (× its field's largest |value| over the body, {peak})")
            }
            None => format!("{at} change"),
        };
        scaled.push((label, t.change * peak, &ranges::TEMPERATURE_CHANGE, history));
        out.push(BodyTemperature {
            body,
            change: t.change,
            strain: alpha * t.change,
            alpha,
            reference: t.reference,
            history,
            young: m.young_table.as_deref().map(pairs),
            yield_stress: m.yield_table.as_deref().map(pairs),
            field,
        });
    }
    tables_need_a_temperature(case, mesh, &out, place)?;
    Ok(out)
}

/// A material with a property table needs its body's `[[temperature]]`
/// with a `reference` (the table is in °C), and its plain value (`young`,
/// `yield_stress`) must be the table's at that reference.
fn tables_need_a_temperature(
    case: &Case,
    mesh: &Mesh,
    temperatures: &[BodyTemperature],
    place: &str,
) -> Result<()> {
    for (b, name) in mesh.bodies.iter().enumerate() {
        let Some(m) = case.materials.get(name) else {
            continue;
        };
        let plain = [
            ("young_table", &m.young_table, "young", m.young),
            (
                "yield_table",
                &m.yield_table,
                "yield_stress",
                m.yield_stress.unwrap_or(f64::NAN),
            ),
        ];
        for (key, table, plain_key, value) in plain {
            let Some(rows) = table.as_deref().map(pairs) else {
                continue;
            };
            let at = format!("{place}: [materials.{}] {key}", clip(name));
            let reference = temperatures
                .iter()
                .find(|t| t.body == b)
                .and_then(|t| t.reference);
            let Some(reference) = reference else {
                return Err(Error::input(
                    at,
                    format!("is read at the body's temperature: give \"{}\" a [[temperature]] with a `reference` (°C)", clip(name)),
                ));
            };
            let (lo, hi) = (rows[0][0], rows[rows.len() - 1][0]);
            if !(lo..=hi).contains(&reference) {
                return Err(Error::input(
                    at,
                    format!(
                        "spans {lo} … {hi} °C, not the body's reference temperature {reference} °C"
                    ),
                ));
            }
            let v = interpolate(&rows, reference);
            if (v - value).abs() > 1e-9 * v.abs() {
                return Err(Error::input(
                    at,
                    format!("gives {v} at the reference temperature {reference} °C, but {plain_key} = {value}: {plain_key} is the value at the reference; make the two agree"),
                ));
            }
        }
    }
    Ok(())
}

/// Every body temperature along the history (reference + ΔT × the lowest
/// and the highest factor, with a field times its lowest and highest
/// factor: [`span`]) within its material's tables: a table is not
/// extrapolated.
pub(super) fn check_tables(
    temperatures: &[BodyTemperature],
    histories: &[History],
    largest: f64,
    place: &str,
    bodies: &[String],
) -> Result<()> {
    for t in temperatures {
        let Some(reference) = t.reference else {
            continue;
        };
        let (a, b) = span(t, histories, largest);
        let (cold, hot) = (reference + a, reference + b);
        for (key, rows) in [("young_table", &t.young), ("yield_table", &t.yield_stress)] {
            let Some(rows) = rows else {
                continue;
            };
            let (t0, t1) = (rows[0][0], rows[rows.len() - 1][0]);
            if cold < t0 - 1e-9 || hot > t1 + 1e-9 {
                let over = if t.field.is_some() {
                    "over the history and its field"
                } else {
                    "over the history"
                };
                return Err(Error::input(
                    format!("{place}: [materials.{}] {key}", clip(&bodies[t.body])),
                    format!("spans {t0} … {t1} °C, but the body's temperature runs {cold} … {hot} °C {over}: give rows that cover it (a table is not extrapolated)"),
                ));
            }
        }
    }
    Ok(())
}

/// The lowest and the highest factor of a temperature's history (or of the
/// load factor from 0 to `largest`).
fn factor_range(t: &BodyTemperature, histories: &[History], largest: f64) -> (f64, f64) {
    match t.history {
        Some(h) => histories[h].extremes(),
        None if histories.is_empty() => (0.0, largest),
        None => (0.0, 1.0),
    }
}

/// The lowest and the highest ΔT of a body over the run: ΔT times its
/// history's lowest and highest factor, and with a field times the field's
/// lowest and highest factor too.
fn span(t: &BodyTemperature, histories: &[History], largest: f64) -> (f64, f64) {
    let (lo, hi) = factor_range(t, histories, largest);
    let (flo, fhi) = t.field.as_ref().map_or((1.0, 1.0), |f| f.extremes());
    let products = [lo * flo, lo * fhi, hi * flo, hi * fhi].map(|f| t.change * f);
    let low = products.iter().copied().fold(f64::INFINITY, f64::min);
    let high = products.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (low, high)
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
        let lowest = reference + span(t, histories, largest).0;
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
