//! A rating as the outputs hold it: the standard's inputs, then each check
//! with the FE's number beside the handbook's, the demand, the safety and
//! the verdict (summary.json's `ratings`, docs/output.md).

use super::Run;
use crate::model::Model;
use serde::Serialize;
use std::borrow::Cow;

/// One input of a rating and where its value came from.
#[derive(Clone, Debug, Serialize)]
pub struct Input {
    pub name: &'static str,
    pub symbol: &'static str,
    pub value: f64,
    pub unit: &'static str,
    /// "case" (the rating's key), "mesh", "material", "interface", "default".
    pub from: &'static str,
}

impl Input {
    pub fn new(
        name: &'static str,
        symbol: &'static str,
        value: f64,
        unit: &'static str,
        from: &'static str,
    ) -> Input {
        Input {
            name,
            symbol,
            value,
            unit,
            from,
        }
    }
}

/// One check: the FE's number, the handbook's, and against what.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Check {
    pub quantity: Cow<'static, str>,
    pub symbol: &'static str,
    pub unit: &'static str,
    pub fe: Option<f64>,
    pub handbook: Option<f64>,
    /// fe / handbook − 1.
    pub difference: Option<f64>,
    /// The demand or the limit the value is held against.
    pub required: Option<f64>,
    /// The safety against `required` (the FE's where it has one).
    pub safety: Option<f64>,
    pub required_safety: Option<f64>,
    pub pass: Option<bool>,
    pub note: String,
    /// A joint-cycles rating's: the cycle it reads (summary.json
    /// `joints[].cycles[].cycle`); absent from the outputs elsewhere.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cycle: Option<usize>,
}

impl Check {
    /// A quantity the FE and the handbook both give.
    pub fn both(
        q: impl Into<Cow<'static, str>>,
        symbol: &'static str,
        unit: &'static str,
        fe: Option<f64>,
        hb: Option<f64>,
    ) -> Check {
        let fe = fe.filter(|v| v.is_finite());
        let handbook = hb.filter(|v| v.is_finite());
        let difference = match (fe, handbook) {
            (Some(a), Some(b)) if b != 0.0 => Some(a / b - 1.0),
            _ => None,
        };
        Check {
            quantity: q.into(),
            symbol,
            unit,
            fe,
            handbook,
            difference,
            ..Check::default()
        }
    }

    /// Held against a demand: safety = capacity / demand, which must reach
    /// `required_safety` (the FE's capacity, else the handbook's).
    pub fn against(mut self, demand: Option<f64>, required_safety: f64) -> Check {
        self.required = demand;
        self.required_safety = Some(required_safety);
        let capacity = self.fe.or(self.handbook);
        if let (Some(c), Some(d)) = (capacity, demand) {
            if d > 0.0 {
                // a capacity below zero (a clamp load lost) is no safety at all
                let s = (c / d).max(0.0);
                self.safety = Some(s);
                self.pass = Some(s >= required_safety);
            }
        }
        self
    }

    /// Held below a limit: safety = limit / value, which must reach
    /// `required_safety`.
    pub fn below(mut self, limit: Option<f64>, required_safety: f64) -> Check {
        self.required = limit;
        self.required_safety = Some(required_safety);
        let value = self.fe.or(self.handbook);
        if let (Some(v), Some(l)) = (value, limit) {
            if v > 0.0 {
                let s = l / v;
                self.safety = Some(s);
                self.pass = Some(s >= required_safety);
            }
        }
        self
    }

    pub fn note(mut self, note: impl Into<String>) -> Check {
        self.note = note.into();
        self
    }
}

/// One `[[rating]]`'s result.
#[derive(Clone, Debug, Serialize)]
pub struct Rating {
    pub standard: &'static str,
    pub name: String,
    /// What is rated, in words.
    pub subject: String,
    pub inputs: Vec<Input>,
    pub checks: Vec<Check>,
    /// Why the rating gives no verdict (a run stopped early, a joint the
    /// standard does not rate as posed); null when it does.
    pub incomplete: Option<String>,
}

impl Rating {
    /// Whether every check with a verdict passes (None: no check has one,
    /// or the rating is incomplete).
    pub fn passes(&self) -> Option<bool> {
        if self.incomplete.is_some() {
            return None;
        }
        let verdicts: Vec<bool> = self.checks.iter().filter_map(|c| c.pass).collect();
        (!verdicts.is_empty()).then(|| verdicts.iter().all(|&p| p))
    }
}

/// The increments' values of interface `i`'s joint measures.
pub(crate) fn joint_series<'a>(
    r: &Run<'a>,
    i: usize,
) -> impl Iterator<Item = (f64, &'a crate::measure::joint::JointMeasures)> + 'a {
    r.increments
        .iter()
        .filter_map(move |inc| inc.joints.get(i).map(|j| (inc.load_factor, j)))
}

/// The largest von Mises stress (MPa) of body `b` at any increment.
pub(crate) fn max_von_mises(model: &Model, r: &Run, b: usize) -> Option<f64> {
    let plan = &model.plan;
    let k = crate::model::outputs::PER_BODY * b;
    r.increments
        .iter()
        .map(|inc| {
            plan.part(&inc.record, &plan.layout.bodies)
                .get(k)
                .copied()
                .unwrap_or(f64::NAN)
        })
        .filter(|v| v.is_finite())
        .reduce(f64::max)
}

/// The largest contact pressure (MPa) of interface `i` at any increment.
pub(crate) fn max_pressure(model: &Model, r: &Run, i: usize) -> Option<f64> {
    let plan = &model.plan;
    let k = crate::model::outputs::PER_INTERFACE * i;
    r.increments
        .iter()
        .map(|inc| {
            plan.part(&inc.record, &plan.layout.interfaces)
                .get(k)
                .copied()
                .unwrap_or(f64::NAN)
        })
        .filter(|v| v.is_finite())
        .reduce(f64::max)
}

/// The smallest and largest radius (x) of body b's nodes.
pub(crate) fn radii(model: &Model, b: usize) -> (f64, f64) {
    let mesh = &model.mesh;
    mesh.elements
        .iter()
        .filter(|e| e.body == b)
        .flat_map(|e| e.nodes().iter())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &n| {
            let x = mesh.nodes[n][0];
            (lo.min(x), hi.max(x))
        })
}
