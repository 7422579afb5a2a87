//! The keys of the designer's outputs (docs/case-schema.md, "Probes and
//! events"): `[[probe]]` entries and `[output] event_tolerance`. What they
//! name on the mesh (sets, bodies, points inside the model) is checked when
//! the model is built ([`crate::model::outputs`]); here, what the case alone
//! decides: names, coordinates, the tolerance.

use super::Case;
use crate::error::{clip, Error, Result};
use serde::{Deserialize, Serialize};

/// The default width of an event's bracket in load factor (pseudo-time).
pub(crate) const DEFAULT_EVENT_TOLERANCE: f64 = 1e-3;
/// The smallest width an event's bracket may be asked for: below it the
/// bisection would split load factors at round-off.
pub(crate) const MIN_EVENT_TOLERANCE: f64 = 1e-12;
/// Most `[[probe]]` entries of a case.
pub(crate) const MAX_PROBES: usize = 1000;

/// A named displacement history: a point (snapped to the nearest node) or a
/// node set reduced by a statistic.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeSpec {
    /// Unique among the probes; a column of `probes.csv`.
    pub name: String,
    /// A point [x, y] (mm; [x, y, z] in a 3D model) inside the model: the
    /// nearest node is taken.
    #[serde(default, deserialize_with = "super::point_opt")]
    pub at: Option<Vec<f64>>,
    /// With `at`: only this body's nodes are candidates (at an interface two
    /// coincident nodes belong to two bodies).
    pub body: Option<String>,
    /// A node set instead of a point.
    pub nodes: Option<String>,
    /// With `nodes`: "mean" (default), "min" or "max" of each component.
    pub(crate) statistic: Option<Statistic>,
}

/// How a node set's displacements are reduced to one value per component.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Statistic {
    Mean,
    Min,
    Max,
}

impl Statistic {
    pub fn name(self) -> &'static str {
        match self {
            Statistic::Mean => "mean",
            Statistic::Min => "min",
            Statistic::Max => "max",
        }
    }
}

/// The name [`Statistic::name`] gives, as the case spells it.
impl Serialize for Statistic {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Statistic {
    /// A string, `mean`, `min` or `max`; anything else is refused naming
    /// the choices.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Choice;
        impl serde::de::Visitor<'_> for Choice {
            type Value = Statistic;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("statistic \"mean\", \"min\" or \"max\"")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<Statistic, E> {
                match v {
                    "mean" => Ok(Statistic::Mean),
                    "min" => Ok(Statistic::Min),
                    "max" => Ok(Statistic::Max),
                    _ => Err(E::invalid_value(serde::de::Unexpected::Str(v), &self)),
                }
            }
        }
        d.deserialize_any(Choice)
    }
}

/// The case's event tolerance: as given, else `DEFAULT_EVENT_TOLERANCE`.
pub fn event_tolerance(case: &Case) -> f64 {
    case.output
        .event_tolerance
        .unwrap_or(DEFAULT_EVENT_TOLERANCE)
}

/// What the case alone says about its probes and its event tolerance: the
/// tolerance in [1e-12, 1); each probe named (not blank, unique, at most
/// `crate::input::case::MAX_NAME_BYTES` bytes), a point or a node set (not both),
/// `body` only with a point, `statistic` only with a set, the point's
/// coordinates finite and within the coordinate range.
pub fn check(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    if let Some(t) = case.output.event_tolerance {
        if !(t.is_finite() && (MIN_EVENT_TOLERANCE..1.0).contains(&t)) {
            return Err(Error::input(
                at("[output] event_tolerance"),
                format!(
                    "{} must be in [{MIN_EVENT_TOLERANCE:e}, 1): the width of an event's bracket in load factor (pseudo-time)",
                    crate::numbers::exact(t)
                ),
            ));
        }
    }
    if case.probe.len() > MAX_PROBES {
        return Err(Error::input(
            at("[[probe]]"),
            format!("{} probes, more than {MAX_PROBES}", case.probe.len()),
        ));
    }
    let mut seen = std::collections::BTreeSet::new();
    for (i, p) in case.probe.iter().enumerate() {
        let key = |k: &str| at(&format!("probe[{i}] {k}"));
        if p.name.trim().is_empty() || p.name.trim() != p.name {
            return Err(Error::input(
                key("name"),
                format!(
                    "\"{}\" is not a usable probe name (empty, blank, or with blanks around it): it heads the probe's columns",
                    clip(&p.name)
                ),
            ));
        }
        if p.name.len() > super::MAX_NAME_BYTES {
            return Err(Error::input(
                key("name"),
                format!(
                    "has {} bytes, more than {}",
                    p.name.len(),
                    super::MAX_NAME_BYTES
                ),
            ));
        }
        if !seen.insert(p.name.as_str()) {
            return Err(Error::input(
                key("name"),
                format!(
                    "two [[probe]] entries are named \"{}\": each probe needs its own name",
                    clip(&p.name)
                ),
            ));
        }
        match (&p.at, &p.nodes) {
            (Some(_), Some(_)) => {
                return Err(Error::input(
                    key("at"),
                    "give either at = [x, y] (a point) or nodes = \"<set>\" (a node set), not both",
                ))
            }
            (None, None) => {
                return Err(Error::input(
                    at(&format!("probe[{i}] (\"{}\")", clip(&p.name))),
                    "give at = [x, y] (a point, snapped to the nearest node) or nodes = \"<set>\" (a node set)",
                ))
            }
            (Some(x), None) => {
                if p.statistic.is_some() {
                    return Err(Error::input(
                        key("statistic"),
                        "applies to a node set (nodes = \"<set>\"); a point probe is one node",
                    ));
                }
                check_point(case, x, &|| key("at"))?;
            }
            (None, Some(_)) => {
                if p.body.is_some() {
                    return Err(Error::input(
                        key("body"),
                        "applies to a point probe (at = [x, y]); a node set names its nodes",
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A probe's point: the model's count of coordinates ([x, y], or [x, y, z]
/// in 3D), each finite and within the coordinate range.
fn check_point(case: &Case, x: &[f64], key: &dyn Fn() -> String) -> Result<()> {
    let dim = if case.model.plane == crate::physics::material::Plane::Solid {
        3
    } else {
        2
    };
    if x.len() != dim {
        return Err(Error::input(
            key(),
            match dim {
                3 => format!("{x:?} is a point in the plane; a 3D model's point has three coordinates, at = [x, y, z]"),
                _ => format!("{x:?} has three coordinates; a plane or axisymmetric model's point is at = [x, y]"),
            },
        ));
    }
    for v in x {
        if !v.is_finite() {
            return Err(Error::input(
                key(),
                format!("{x:?} must be finite numbers (mm)"),
            ));
        }
        super::ranges::COORDINATE.check(key(), *v)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::Case;

    const CASE: &str = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/cases/punch-plane-stress/case.toml"
    ));

    /// `[[probe]]` and `event_tolerance` are part of the case's key (and so
    /// of the restart fingerprint): a case that gives them has another key.
    #[test]
    fn the_designers_keys_are_part_of_the_case_key() {
        let plain = Case::parse(CASE, "case.toml").unwrap().key();
        assert!(plain.contains("\"event_tolerance\":null"), "{plain}");
        assert!(plain.contains("\"probe\":[]"), "{plain}");
        let text = format!("{CASE}\n[[probe]]\nname = \"p\"\nat = [1.0, 1.0]\n")
            .replace("[solver]", "[output]\nevent_tolerance = 1e-4\n\n[solver]");
        let given = Case::parse(&text, "case.toml").unwrap().key();
        assert!(given.contains("\"event_tolerance\":0.0001"), "{given}");
        assert!(given.contains("\"probe\":[{\"at\":[1.0,1.0]"), "{given}");
        assert_ne!(given, plain);
    }
}
