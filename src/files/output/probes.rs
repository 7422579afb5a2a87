//! The probes' files: `probes.csv` and summary.json's `probes`
//! ([`crate::model::outputs::probes`] defines the probes).

use super::joints_csv::csv_field;
use crate::input::mesh::Mesh;
use crate::model::outputs::probes::{Probe, Target};
use crate::solve::RunResult;
use serde_json::{json, Value};
use std::fmt::Write as _;

pub(crate) const HEADER: &str = "increment,time,probe,ux_mm,uy_mm\n";

/// The header of a model with twist: u_θ as a third column.
pub(crate) const HEADER_TWIST: &str = "increment,time,probe,ux_mm,uy_mm,utheta_mm\n";

/// `probes.csv`: one row per increment and probe (the header alone without
/// probes), `per` values each (`components`).
pub fn csv(probes: &[Probe], per: usize, r: &RunResult, at: impl Fn(&[f64]) -> &[f64]) -> String {
    let mut s = String::from(if per == 3 { HEADER_TWIST } else { HEADER });
    for inc in &r.increments {
        let v = at(&inc.record);
        for (p, u) in probes.iter().zip(v.chunks_exact(per)) {
            let _ = write!(
                s,
                "{},{:.9},{}",
                inc.increment,
                inc.load_factor,
                csv_field(&p.name)
            );
            for x in u {
                let _ = write!(s, ",{x:.9e}");
            }
            s.push('\n');
        }
    }
    s
}

/// The summary's `probes`: what each reads (the snapped node and its
/// coordinates, or the set and statistic) and its last, smallest and
/// largest values.
pub fn summary(probes: &[Probe], mesh: &Mesh, rows: &[&[f64]]) -> Value {
    let per = crate::model::outputs::probes::components(mesh.node_dofs);
    probes
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let col = |c: usize| rows.iter().map(move |r| r[per * k + c]);
            let pick = |f: fn(f64, f64) -> f64| {
                let v: Vec<f64> = (0..per).map(|c| col(c).fold(f64::NAN, f)).collect();
                super::json::numbers(&v)
            };
            let last: Vec<f64> = (0..per)
                .map(|c| rows.last().map_or(f64::NAN, |r| r[per * k + c]))
                .collect();
            let mut fin = json!({"ux_mm": super::json::number(last[0]), "uy_mm": super::json::number(last[1])});
            if per == 3 {
                fin["utheta_mm"] = super::json::number(last[2]);
            }
            let mut o = json!({
                "name": p.name,
                "final": fin,
                "min_mm": pick(f64::min),
                "max_mm": pick(f64::max),
            });
            match &p.target {
                Target::Point { at, body, node } => {
                    o["kind"] = json!("point");
                    o["at"] = json!(at);
                    o["body"] = json!(body);
                    o["node"] = json!(node);
                    o["x_mm"] = json!(mesh.nodes[*node][0]);
                    o["y_mm"] = json!(mesh.nodes[*node][1]);
                }
                Target::Nodes {
                    set,
                    nodes,
                    statistic,
                } => {
                    o["kind"] = json!("nodes");
                    o["set"] = json!(set);
                    o["statistic"] = json!(statistic.name());
                    o["node_count"] = json!(nodes.len());
                }
            }
            o
        })
        .collect()
}
