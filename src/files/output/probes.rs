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

/// The header of a 3D model: u_z as a third column.
pub(crate) const HEADER_SOLID: &str = "increment,time,probe,ux_mm,uy_mm,uz_mm\n";

/// The name of a probe's third component: twist's u_θ or a 3D model's u_z.
fn third(mesh: &Mesh) -> &'static str {
    if mesh.node_dofs.twist() {
        "utheta_mm"
    } else {
        "uz_mm"
    }
}

/// `probes.csv`: one row per increment and probe (the header alone without
/// probes), the mesh's components each.
pub fn csv(probes: &[Probe], mesh: &Mesh, r: &RunResult, at: impl Fn(&[f64]) -> &[f64]) -> String {
    let per = crate::model::outputs::probes::components(mesh.node_dofs);
    let header = match (per, third(mesh)) {
        (2, _) => HEADER,
        (_, "utheta_mm") => HEADER_TWIST,
        _ => HEADER_SOLID,
    };
    let mut s = String::from(header);
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
                fin[third(mesh)] = super::json::number(last[2]);
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
                    if mesh.dim() == 3 {
                        o["z_mm"] = json!(mesh.nodes[*node][2]);
                    }
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
                Target::Surface {
                    interface,
                    body,
                    nodes,
                    ..
                } => {
                    o["kind"] = json!("surface");
                    o["set"] = json!(format!("{interface} ({body}'s side)"));
                    o["statistic"] = json!("area mean");
                    o["node_count"] = json!(nodes.len());
                }
            }
            o
        })
        .collect()
}
