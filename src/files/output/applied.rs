//! What the run applied: `loads.csv` (every `[[load]]` and `[[force]]`'s
//! resultant per increment, N and N·mm) and summary.json's `applied_loads`
//! (those, each pretension section's force and each prescribed motion's
//! force, in the units a designer reads: N and N·m).

use super::joints_csv::csv_field;
use crate::model::outputs::reactions::Group;
use crate::model::Model;
use crate::solve::RunResult;
use serde_json::{json, Value};
use std::fmt::Write as _;

/// `loads.csv`: `increment, time`, then one column per load and component,
/// headed `<load>:<component>` (`load[0]:fy_n`, `load[1]:torque_nmm`).
pub fn csv(model: &Model, r: &RunResult) -> String {
    let labels = model.applied_components.labels();
    let mut s = String::from("increment,time");
    for a in &model.applied {
        for c in labels {
            s.push(',');
            s += &csv_field(&format!("{}:{c}", a.name));
        }
    }
    s.push('\n');
    for inc in &r.increments {
        let _ = write!(s, "{},{:.9}", inc.increment, inc.load_factor);
        for k in 0..model.applied.len() {
            for x in model.applied_at(k, inc.load_factor) {
                let _ = write!(s, ",{x:.9e}");
            }
        }
        s.push('\n');
    }
    s
}

/// One entry of `applied_loads`: its words, then the last, smallest and
/// largest value of each component over the increments.
struct Entry<'a> {
    name: String,
    source: String,
    kind: String,
    selection: String,
    components: Vec<&'a str>,
    rows: Vec<Vec<f64>>,
}

impl Entry<'_> {
    fn json(&self) -> Value {
        let n = self.components.len();
        let col = |j: usize| self.rows.iter().map(move |r| r[j]);
        let last: Vec<f64> = (0..n)
            .map(|j| self.rows.last().map_or(f64::NAN, |r| r[j]))
            .collect();
        let min: Vec<f64> = (0..n).map(|j| col(j).fold(f64::NAN, f64::min)).collect();
        let max: Vec<f64> = (0..n).map(|j| col(j).fold(f64::NAN, f64::max)).collect();
        json!({
            "name": self.name,
            "source": self.source,
            "kind": self.kind,
            "selection": self.selection,
            "components": self.components,
            "final": super::json::numbers(&last),
            "min": super::json::numbers(&min),
            "max": super::json::numbers(&max),
        })
    }
}

/// summary.json's `applied_loads`: every `[[load]]` and `[[force]]`, every
/// pretension section and every boundary that prescribes a motion, with
/// forces in N and moments in N·m.
pub fn summary(model: &Model, r: &RunResult, reactions: impl Fn(&[f64]) -> Vec<f64>) -> Value {
    let comp = model.applied_components;
    // moments in N·m: the label's `_nmm` becomes `_nm`, the value / 1000
    let designer: Vec<&str> = comp.labels().iter().map(|l| designer_label(l)).collect();
    let scale: Vec<f64> = (0..designer.len())
        .map(|c| if comp.is_moment(c) { 1e-3 } else { 1.0 })
        .collect();
    let mut out: Vec<Value> = Vec::new();
    for (k, a) in model.applied.iter().enumerate() {
        let rows = r
            .increments
            .iter()
            .map(|i| {
                let v = model.applied_at(k, i.load_factor);
                v.iter().zip(&scale).map(|(x, s)| x * s).collect()
            })
            .collect();
        let e = Entry {
            name: a.name.clone(),
            source: a.name.clone(),
            kind: a.kind.clone(),
            selection: a.selection.clone(),
            components: designer.clone(),
            rows,
        };
        out.push(e.json());
    }
    out.extend(sections(model, r).iter().map(Entry::json));
    out.extend(motions(model, r, reactions).iter().map(Entry::json));
    Value::Array(out)
}

fn moment_label(l: &str) -> &'static str {
    match l {
        "mx_nmm" => "mx_nm",
        "my_nmm" => "my_nm",
        "mz_nmm" => "mz_nm",
        "my_part_nmm" => "my_part_nm",
        _ => "torque_nm",
    }
}

/// Each pretension section's force (N, tension positive).
fn sections<'a>(model: &Model, r: &RunResult) -> Vec<Entry<'a>> {
    let axes = ["x", "y", "z"];
    model
        .sections
        .iter()
        .enumerate()
        .map(|(k, s)| Entry {
            name: format!("pretension {}", s.name),
            source: format!("pretension[{k}]"),
            kind: format!("pretension ({})", s.control),
            selection: format!(
                "cut {} = {} through {}",
                axes[s.axis],
                crate::numbers::num(s.at),
                model.mesh.bodies[s.body]
            ),
            components: vec!["force_n"],
            rows: r
                .increments
                .iter()
                .map(|i| vec![i.sections.get(k).map_or(f64::NAN, |v| v[0])])
                .collect(),
        })
        .collect()
}

/// Each `[[boundary]]` that prescribes a non-zero motion: the force its
/// support applies to the bodies (its reaction group's values).
fn motions<'a>(
    model: &'a Model,
    r: &RunResult,
    reactions: impl Fn(&[f64]) -> Vec<f64>,
) -> Vec<Entry<'a>> {
    let groups = &model.plan.reactions;
    let mut offset = 0;
    let mut out = Vec::new();
    for g in groups {
        let n = g.components.len();
        if moves(model, g) {
            let m = moment_scale(g);
            out.push(Entry {
                name: g.name.clone(),
                source: g.source.clone(),
                kind: "prescribed motion (the support's force on the bodies)".into(),
                selection: format!("nodes {}", g.set.as_deref().unwrap_or("on the axis")),
                components: g
                    .components
                    .iter()
                    .map(|c| designer_label(c.label))
                    .collect(),
                rows: r
                    .increments
                    .iter()
                    .map(|i| {
                        let v = reactions(&i.record);
                        (0..n)
                            .map(|j| v.get(offset + j).copied().unwrap_or(f64::NAN) * m[j])
                            .collect()
                    })
                    .collect(),
            });
        }
        offset += n;
    }
    out
}

/// Whether group `g` prescribes a displacement other than zero somewhere.
fn moves(model: &Model, g: &Group) -> bool {
    g.components
        .iter()
        .flat_map(|c| &c.terms)
        .any(|&k| model.prescribed.get(k).is_some_and(|p| p.1 != 0.0))
}

fn moment_scale(g: &Group) -> Vec<f64> {
    g.components
        .iter()
        .map(|c| if c.label.ends_with("_nmm") { 1e-3 } else { 1.0 })
        .collect()
}

fn designer_label(l: &'static str) -> &'static str {
    match l.strip_suffix("_nmm") {
        Some(_) => moment_label(l),
        None => l,
    }
}
