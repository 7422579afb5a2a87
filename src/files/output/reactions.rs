//! The reaction groups' files: `reactions.csv` and summary.json's
//! `reactions` ([`crate::model::outputs::reactions`] defines the groups).

use super::joints_csv::csv_field;
use crate::model::outputs::reactions::Group;
use crate::solve::RunResult;
use serde_json::{json, Value};
use std::fmt::Write as _;

/// `reactions.csv`: `increment, time`, then one column per group and
/// component, headed `<group>:<component>`.
pub fn csv(groups: &[Group], r: &RunResult, at: impl Fn(&[f64]) -> &[f64]) -> String {
    let mut s = String::from("increment,time");
    for g in groups {
        for c in &g.components {
            s.push(',');
            s += &csv_field(&format!("{}:{}", g.name, c.label));
        }
    }
    s.push('\n');
    for inc in &r.increments {
        let v = at(&inc.record);
        let _ = write!(s, "{},{:.9}", inc.increment, inc.load_factor);
        for x in v {
            let _ = write!(s, ",{x:.9e}");
        }
        s.push('\n');
    }
    s
}

/// The groups' values as a summary array: `[{name, values}]`.
pub(crate) fn named_values(groups: &[Group], v: &[f64]) -> Value {
    let mut k = 0;
    groups
        .iter()
        .map(|g| {
            let n = g.components.len();
            let vals = &v[k.min(v.len())..(k + n).min(v.len())];
            k += n;
            json!({"name": g.name, "values": vals})
        })
        .collect()
}

/// The summary's `reactions`: per group its source, set, component labels
/// and the last increment's, the smallest and the largest values.
pub fn summary(groups: &[Group], rows: &[&[f64]]) -> Value {
    let mut k = 0;
    groups
        .iter()
        .map(|g| {
            let n = g.components.len();
            let col = |j: usize| rows.iter().map(move |r| r[k + j]);
            let last: Vec<f64> = (0..n)
                .map(|j| rows.last().map_or(f64::NAN, |r| r[k + j]))
                .collect();
            let min: Vec<f64> = (0..n).map(|j| col(j).fold(f64::NAN, f64::min)).collect();
            let max: Vec<f64> = (0..n).map(|j| col(j).fold(f64::NAN, f64::max)).collect();
            k += n;
            json!({
                "name": g.name,
                "source": g.source,
                "set": g.set,
                "components": g.components.iter().map(|c| c.label).collect::<Vec<_>>(),
                "final": super::json::numbers(&last),
                "min": super::json::numbers(&min),
                "max": super::json::numbers(&max),
            })
        })
        .collect()
}
