//! Named displacement probes (`[[probe]]`): a point snapped to the nearest
//! node (of one body, if `body` says so), or a node set reduced by a
//! statistic (mean, min or max of each component). `[output] probe`, the
//! settlement probe of `curve.csv`, is separate and unchanged.

use crate::error::{clip, Error, Result};
use crate::input::case::outputs::{ProbeSpec, Statistic};
use crate::input::case::Case;
use crate::input::mesh::{Mesh, NodeDofs};
use crate::model::interface::InterfaceModel;

/// A point within this fraction of an element's size of the element's
/// outline (its 8 nodes joined by straight lines) counts as inside it: a
/// point on a curved edge lies a little outside the straight lines.
const OUTLINE_TOLERANCE: f64 = 0.02;

/// What a probe reads.
#[derive(Clone, Debug)]
pub enum Target {
    /// The node nearest to the point asked for.
    Point {
        /// [x, y] or, in a 3D model, [x, y, z].
        at: Vec<f64>,
        body: Option<String>,
        node: usize,
    },
    /// Every node of a set, reduced by a statistic.
    Nodes {
        set: String,
        nodes: Vec<usize>,
        statistic: Statistic,
    },
    /// One side of an interface, its nodes' displacements averaged with the
    /// area each stands for (a rating's bearing surface, [`surface`]).
    Surface {
        interface: String,
        /// The body whose side it is.
        body: String,
        nodes: Vec<usize>,
        /// The area each node stands for, mm² (Σ = the side's area).
        weights: Vec<f64>,
    },
}

#[derive(Clone, Debug)]
pub struct Probe {
    pub name: String,
    pub target: Target,
}

/// Values a probe reads per increment: u_x and u_y, and u_θ with twist.
pub fn components(nd: NodeDofs) -> usize {
    nd.per_node()
}

impl Probe {
    /// (u_x, u_y), with twist (u_x, u_y, u_θ), in a state's displacements
    /// (all dofs, numbered by `nd`).
    pub fn value(&self, nd: NodeDofs, u: &[f64]) -> Vec<f64> {
        let of = |c: usize| -> f64 {
            match &self.target {
                Target::Point { node, .. } => u[nd.dof(*node, c)],
                Target::Nodes {
                    nodes, statistic, ..
                } => {
                    let vals = nodes.iter().map(|&n| u[nd.dof(n, c)]);
                    match statistic {
                        Statistic::Mean => vals.sum::<f64>() / nodes.len().max(1) as f64,
                        Statistic::Min => vals.fold(f64::INFINITY, f64::min),
                        Statistic::Max => vals.fold(f64::NEG_INFINITY, f64::max),
                    }
                }
                Target::Surface { nodes, weights, .. } => {
                    let sum = nodes.iter().zip(weights).map(|(&n, w)| w * u[nd.dof(n, c)]);
                    sum.sum::<f64>() / weights.iter().sum::<f64>()
                }
            }
        };
        // + 0.0: no negative zero (a fixed dof scaled by a negative history)
        (0..components(nd)).map(|c| of(c) + 0.0).collect()
    }
}

impl Probe {
    /// What it reads, for `asperity check`: the snapped node and its
    /// coordinates, or the set and its statistic.
    pub(crate) fn describe(&self, mesh: &Mesh) -> String {
        match &self.target {
            Target::Point { at, body, node } => {
                let x = &mesh.nodes[*node][..at.len()];
                let list = |v: &[f64]| {
                    v.iter()
                        .map(|c| c.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                format!(
                    "node {node} at ({}), the nearest{} to ({})",
                    list(x),
                    body.as_ref()
                        .map_or(String::new(), |b| format!(" of body \"{b}\"")),
                    list(at)
                )
            }
            Target::Nodes {
                set,
                nodes,
                statistic,
            } => format!(
                "{} of the {} nodes of set \"{set}\" (each component)",
                statistic.name(),
                nodes.len()
            ),
            Target::Surface {
                interface,
                body,
                nodes,
                ..
            } => format!(
                "area mean over {body}'s side of interface \"{interface}\" ({} nodes)",
                nodes.len()
            ),
        }
    }
}

/// The probe of body `body`'s side of interface `iface` (the area mean of
/// its nodes' displacements, each node weighted by the tributary areas of
/// the interface's pairs it holds), named `name`.
pub fn surface(name: String, iface: &InterfaceModel, body: usize, mesh: &Mesh) -> Probe {
    let mut weight: std::collections::BTreeMap<usize, f64> = Default::default();
    for p in &iface.pairs {
        let node = if iface.body_a == body { p.a } else { p.b };
        *weight.entry(node).or_insert(0.0) += p.area;
    }
    Probe {
        name,
        target: Target::Surface {
            interface: iface.name.clone(),
            body: mesh.bodies[body].clone(),
            nodes: weight.keys().copied().collect(),
            weights: weight.values().copied().collect(),
        },
    }
}

/// The probes of a case on its mesh: each point inside the model (of its
/// body), each set and body named by the mesh; the refusal names the key.
pub fn build(case: &Case, mesh: &Mesh, place: &str) -> Result<Vec<Probe>> {
    case.probe
        .iter()
        .enumerate()
        .map(|(i, p)| probe(i, p, mesh, place))
        .collect()
}

fn probe(i: usize, p: &ProbeSpec, mesh: &Mesh, place: &str) -> Result<Probe> {
    let key = |k: &str| format!("{place}: probe[{i}] {k}");
    let target = match (&p.at, &p.nodes) {
        (Some(at), _) => {
            let body = match &p.body {
                Some(b) => Some(mesh.bodies.iter().position(|n| n == b).ok_or_else(|| {
                    Error::input(
                        key("body"),
                        format!(
                            "no body named \"{}\" (bodies: {})",
                            clip(b),
                            crate::model::loads::names(mesh.bodies.iter())
                        ),
                    )
                })?),
                None => None,
            };
            // the case checks gave the model's count of coordinates
            let x = [at[0], at[1], at.get(2).copied().unwrap_or(0.0)];
            let held = match mesh.dim() {
                3 => inside_solid(mesh, x, body),
                _ => inside(mesh, [x[0], x[1]], body),
            };
            if !held {
                let within = match &p.body {
                    Some(b) => format!("body \"{}\"", clip(b)),
                    None => "the model".to_string(),
                };
                let point: Vec<String> = at.iter().map(|v| v.to_string()).collect();
                return Err(Error::input(
                    key("at"),
                    format!(
                        "the point ({}) is outside {within}: no element holds it (a probe reads the node nearest to a point inside the mesh)",
                        point.join(", ")
                    ),
                ));
            }
            Target::Point {
                at: at.clone(),
                body: p.body.clone(),
                node: nearest(mesh, x, body),
            }
        }
        (None, Some(set)) => {
            let nodes = mesh.node_sets.get(set).ok_or_else(|| {
                Error::input(
                    key("nodes"),
                    format!(
                        "no node set \"{}\" (sets: {})",
                        clip(set),
                        crate::model::loads::names(mesh.node_sets.keys())
                    ),
                )
            })?;
            if nodes.is_empty() {
                return Err(Error::input(
                    key("nodes"),
                    format!(
                        "the set \"{}\" is empty (a side its body shares with another of its blocks): a probe needs nodes",
                        clip(set)
                    ),
                ));
            }
            Target::Nodes {
                set: set.clone(),
                nodes: nodes.clone(),
                statistic: p.statistic.unwrap_or(Statistic::Mean),
            }
        }
        // refused by crate::input::case::outputs::check
        (None, None) => unreachable!("a probe without at or nodes was refused"),
    };
    Ok(Probe {
        name: p.name.clone(),
        target,
    })
}

/// Is `p` inside (or on) some element of the mesh (of body `body`)?
fn inside(mesh: &Mesh, p: [f64; 2], body: Option<usize>) -> bool {
    (0..mesh.elements.len())
        .filter(|&e| body.is_none_or(|b| mesh.elements[e].body == b))
        .any(|e| {
            let outline = mesh.outline(e);
            let (lo, hi) = outline.iter().fold(
                ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
                |(lo, hi), x| {
                    (
                        [lo[0].min(x[0]), lo[1].min(x[1])],
                        [hi[0].max(x[0]), hi[1].max(x[1])],
                    )
                },
            );
            let tol = OUTLINE_TOLERANCE * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
            if p[0] < lo[0] - tol || p[0] > hi[0] + tol || p[1] < lo[1] - tol || p[1] > hi[1] + tol
            {
                return false;
            }
            in_polygon(p, &outline) || near_outline(p, &outline, tol)
        })
}

/// Even-odd rule: a horizontal ray from `p` crosses the outline an odd
/// number of times.
fn in_polygon(p: [f64; 2], poly: &[[f64; 2]]) -> bool {
    let mut odd = false;
    for (k, &a) in poly.iter().enumerate() {
        let b = poly[(k + 1) % poly.len()];
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if x > p[0] {
                odd = !odd;
            }
        }
    }
    odd
}

/// Is `p` within `tol` of a side of the outline?
fn near_outline(p: [f64; 2], poly: &[[f64; 2]], tol: f64) -> bool {
    poly.iter().enumerate().any(|(k, &a)| {
        let b = poly[(k + 1) % poly.len()];
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let s = if len2 > 0.0 {
            (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p[0] - a[0] - s * d[0]).hypot(p[1] - a[1] - s * d[1]) <= tol
    })
}

/// Is `p` inside (or on) some solid element of the mesh (of body `body`)?
/// Its natural coordinates in an element whose box holds it lie in the
/// reference element within [`OUTLINE_TOLERANCE`].
fn inside_solid(mesh: &Mesh, p: [f64; 3], body: Option<usize>) -> bool {
    (0..mesh.elements.len())
        .filter(|&e| body.is_none_or(|b| mesh.elements[e].body == b))
        .any(|e| {
            let el = &mesh.elements[e];
            let Some(solid) = el.family.solid() else {
                return false;
            };
            let coords: Vec<[f64; 3]> = el.nodes().iter().map(|&n| mesh.nodes[n]).collect();
            let tol = OUTLINE_TOLERANCE * solid.diameter(&coords);
            let boxed = (0..3).all(|i| {
                let (lo, hi) = coords
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                        (lo.min(c[i]), hi.max(c[i]))
                    });
                p[i] >= lo - tol && p[i] <= hi + tol
            });
            boxed
                && solid
                    .natural_coords(&coords, p)
                    .is_some_and(|xi| solid.contains(xi, OUTLINE_TOLERANCE))
        })
}

/// The node nearest to `p` (of body `body`; z = 0 in a plane model); the
/// lowest number on a tie.
fn nearest(mesh: &Mesh, p: [f64; 3], body: Option<usize>) -> usize {
    let mut of_body = vec![body.is_none(); mesh.nodes.len()];
    if let Some(b) = body {
        for el in mesh.elements.iter().filter(|el| el.body == b) {
            for &n in el.nodes() {
                of_body[n] = true;
            }
        }
    }
    let dist = |n: usize| {
        let x = mesh.nodes[n];
        (x[0] - p[0]).hypot(x[1] - p[1]).hypot(x[2] - p[2])
    };
    (0..mesh.nodes.len())
        .filter(|&n| of_body[n])
        .min_by(|&a, &b| dist(a).total_cmp(&dist(b)))
        .unwrap_or(0)
}

/// Values of every probe, [`components`] each, in order.
pub fn values(probes: &[Probe], nd: NodeDofs, u: &[f64]) -> Vec<f64> {
    probes.iter().flat_map(|p| p.value(nd, u)).collect()
}
