//! Pretension sections (`[[pretension]]`), after Abaqus's *PRE-TENSION
//! SECTION and CalculiX's pre-tension section: a bolt is tightened by cutting
//! its shank and pulling the two sides of the cut together.
//!
//! The cut follows element edges in a plane or axisymmetric model (the line
//! y = h, or x = c in plane models) and element faces in a 3D one (the plane
//! x = c, y = h or z = c: its normal along an axis, a bolt along that axis):
//! every node of the body on the cut that elements on both sides share is
//! doubled (in 3D the corners and midsides of the faces in the plane), the
//! elements beyond the cut (on the side the normal n = +x, +y or +z points
//! to) take the copy ([`cut`]). One more unknown, the shortening s, lives on
//! a reference node of its own after the mesh's N nodes (section k's first
//! dof, K (N + k) with K dofs per node; its other dofs always 0), and the
//! copies follow the originals through the model's linear constraints
//! ([`crate::model::constraint`]):
//!
//! ```text
//!   u_n(copy) = u_n(node) − s,   u_t(copy) = u_t(node),   u_θ(copy) = u_θ(node) (twist)
//!   3D: u_n(copy) = u_n(node) − s,   the two in-plane components equal
//! ```
//!
//! so s > 0 shortens the body across the cut, rigidly over the whole cut.
//! With twist (an axisymmetric model with u_θ, [`crate::input::case::twist`])
//! the circumferential displacement is continuous across the cut: the cut is
//! a device of the model in a shank that is whole, and carries its torque
//! (the friction torque under a bolt's head goes down the shank to its
//! thread) as the uncut shank would; no section's normal is θ, so no
//! shortening enters u_θ.
//! The virtual work of the cut is N δs with N the force the body transmits
//! across the cut (tension positive): the force on s's equation is the
//! section force, and it is what is reported (`crate::solve::State::section_force`).
//! Three ways to load it, each over a history:
//! * `force = F`: a force F h(t) on s's equation, then, by default
//!   (`lock = true`), **locked** after the history's last time: s keeps the
//!   value it had there (its equation is held, [`crate::model::constraint`]) and
//!   the section force follows the service loads — the bolt's share of them,
//!   VDI 2230's load factor Φ;
//! * `lock = false`: the force is kept (a bolt force no real bolt keeps);
//! * `shortening = s₀`: s = s₀ h(t) prescribed (the nut turned by a known
//!   amount), held by its history.

use crate::error::{Error, Result};
use crate::input::case::{Case, PretensionSpec};
use crate::input::mesh::{Mesh, NodeDofs};
use crate::model::constraint::Constraint;
use std::collections::{BTreeMap, HashMap};

mod cut;
#[cfg(test)]
mod tests;

/// The most sections a case may have.
pub(crate) const MAX_SECTIONS: usize = 64;

/// A section of the model.
#[derive(Clone, Debug)]
pub struct Section {
    pub name: String,
    pub body: usize,
    /// The normal's component: 0 (x = c), 1 (y = h) or 2 (z = c, 3D).
    pub axis: usize,
    /// The cut's coordinate (mm).
    pub at: f64,
    /// (node, its copy beyond the cut) of every cut node.
    pub pairs: Vec<(usize, usize)>,
    /// The shortening's dof (its reference node's first dof).
    pub dof: usize,
    /// Locked (held) at pseudo-times after this one (∞: never).
    pub lock_after: f64,
    /// "force", "shortening" (what controls it).
    pub control: &'static str,
}

/// The first dof of section k's reference node, numbered as a node after
/// the mesh's nodes.
pub fn dof(nd: NodeDofs, mesh_nodes: usize, k: usize) -> usize {
    nd.dof(mesh_nodes + k, 0)
}

/// Every dof of a model with these sections: the mesh's and a node's per
/// section.
pub(crate) fn total_dofs(case: &Case, mesh: &Mesh) -> usize {
    total_dofs_of(mesh, case.pretension.len())
}

/// Every dof of a mesh with `sections` pretension sections.
pub(crate) fn total_dofs_of(mesh: &Mesh, sections: usize) -> usize {
    mesh.node_dofs.count(mesh.nodes.len() + sections)
}

fn at(place: &str, k: usize, spec: &PretensionSpec) -> String {
    format!(
        "{place}: pretension[{k}] (\"{}\")",
        crate::error::clip(&spec.name)
    )
}

/// Checks every `[[pretension]]` by itself and cuts the mesh along each:
/// the sections with their node pairs (dofs and lock times come from
/// [`finish`]). The mesh gains the copies; the elements beyond each cut, and
/// their edges in edge sets and interfaces (faces in face sets), take them.
pub fn cut(case: &Case, mesh: &mut Mesh, place: &str) -> Result<Vec<Section>> {
    let mut out: Vec<Section> = Vec::new();
    if case.pretension.len() > MAX_SECTIONS {
        return Err(Error::input(
            format!("{place}: [[pretension]]"),
            format!(
                "{} sections, more than {MAX_SECTIONS} (the limit: a joint has a few bolts)",
                case.pretension.len()
            ),
        ));
    }
    let tol = crate::model::consistency::tolerance(mesh);
    for (k, spec) in case.pretension.iter().enumerate() {
        let at = at(place, k, spec);
        let err = |m: String| Err(Error::input(&at, m));
        let blame = |m: String| Error::input(&at, m);
        check_name(spec, &out).map_err(blame)?;
        let Some(body) = mesh.bodies.iter().position(|b| *b == spec.body) else {
            return err(format!(
                "body \"{}\" does not exist (bodies: {})",
                crate::error::clip(&spec.body),
                mesh.bodies.join(", ")
            ));
        };
        let dim = mesh.dim();
        let (axis, value) = plane_of(case, spec, dim).map_err(blame)?;
        check_control(spec).map_err(blame)?;
        if let Some(other) = out
            .iter()
            .find(|s| s.body == body && s.axis == axis && (s.at - value).abs() <= tol)
        {
            return err(format!(
                "cuts body \"{}\" {} as pretension \"{}\"",
                spec.body,
                if dim == 3 {
                    "in the same plane"
                } else {
                    "along the same line"
                },
                other.name
            ));
        }
        let pairs = cut::split(
            mesh,
            &cut::Cut {
                body,
                axis,
                at: value,
                dim,
                name: &spec.body,
                place: &at,
            },
        )?;
        out.push(Section {
            name: spec.name.clone(),
            body,
            axis,
            at: value,
            pairs,
            dof: 0,
            lock_after: f64::INFINITY,
            control: if spec.force.is_some() {
                "force"
            } else {
                "shortening"
            },
        });
    }
    Ok(out)
}

/// A section's name: not empty, plain (it heads pretension.csv's
/// columns), not taken by an earlier section of `out`.
fn check_name(spec: &PretensionSpec, out: &[Section]) -> std::result::Result<(), String> {
    if spec.name.trim().is_empty() {
        return Err("name is empty".into());
    }
    let plain = spec.name.trim() == spec.name
        && spec.name.len() <= crate::input::case::MAX_NAME_BYTES
        && !spec
            .name
            .chars()
            .any(|c| c.is_control() || c == ',' || c == '"');
    if !plain {
        return Err(format!(
            "name {:?} is not a usable section name (no blanks around it, at most {} bytes, no comma, quote or control character): it heads pretension.csv's columns",
            crate::error::clip(&spec.name),
            crate::input::case::MAX_NAME_BYTES
        ));
    }
    if out.iter().any(|s| s.name == spec.name) {
        return Err("two [[pretension]] sections have this name".into());
    }
    Ok(())
}

/// The line (plane in 3D) of a section's cut in a mesh of dimension
/// `dim`: (axis, value) of x_axis = value.
fn plane_of(
    case: &Case,
    spec: &PretensionSpec,
    dim: usize,
) -> std::result::Result<(usize, f64), String> {
    let given: Vec<(usize, f64)> = [spec.x, spec.y, spec.z]
        .into_iter()
        .enumerate()
        .filter_map(|(k, v)| Some((k, v?)))
        .collect();
    let (axis, value) = match given[..] {
        [(2, _)] if dim != 3 => {
            return Err("z = c is the cut of a 3D model (plane = \"3d\"); a plane or axisymmetric model is cut along y = h or x = c".into());
        }
        [(0, _)] if case.model.plane == crate::physics::material::Plane::Axisymmetric => {
            return Err("x = c cuts a body of revolution along a cylinder: in an axisymmetric model a section is a cut y = h across the axis (a bolt along y)".into());
        }
        [one] => one,
        [] if dim == 3 => return Err(
            "give the plane of the cut: x = c, y = h or z = c (normal +x, +y or +z: a bolt along that axis)"
                .into(),
        ),
        [] => return Err(
            "give the line of the cut: y = h (normal +y) or, in plane models, x = c (normal +x)"
                .into(),
        ),
        _ if dim == 3 => {
            return Err("give one of x, y and z (the plane of the cut, its normal along that axis), not two".into())
        }
        _ => return Err("give x or y (the line of the cut), not both".into()),
    };
    if !crate::input::case::ranges::COORDINATE.admits(value) {
        return Err(format!(
            "{} = {}: {}",
            ["x", "y", "z"][axis],
            crate::numbers::exact(value),
            crate::input::case::ranges::COORDINATE.refusal(value)
        ));
    }
    Ok((axis, value))
}

/// A section's control: a force or a shortening, one of them, in range
/// and not zero; `lock` with a force only.
fn check_control(spec: &PretensionSpec) -> std::result::Result<(), String> {
    match (spec.force, spec.shortening) {
        (Some(_), Some(_)) => return Err("give force or shortening, not both".into()),
        (None, None) => return Err("give force (N, tension positive) or shortening (mm)".into()),
        (None, Some(_)) if spec.lock.is_some() => {
            return Err("lock is given with shortening: a prescribed shortening is held by its history (lock applies to a force-controlled section)".into());
        }
        _ => {}
    }
    if let Some(f) = spec.force {
        if f == 0.0 || !crate::input::case::ranges::FORCE.admits(f) {
            return Err(format!(
                "force = {f}: {}",
                if f == 0.0 {
                    "a section without force (give the bolt force, N)".to_string()
                } else {
                    crate::input::case::ranges::FORCE.refusal(f)
                }
            ));
        }
    }
    if let Some(s) = spec.shortening {
        if s == 0.0 || !crate::input::case::ranges::DISPLACEMENT.admits(s) {
            return Err(format!(
                "shortening = {s}: {}",
                if s == 0.0 {
                    "a section without shortening (give the shortening, mm)".to_string()
                } else {
                    crate::input::case::ranges::DISPLACEMENT.refusal(s)
                }
            ));
        }
    }
    Ok(())
}

/// The node each node of a cut mesh (`nodes` of them) was before the cuts:
/// itself, or for a copy the node it copies (through every section, in
/// order: a copy of a copy is its first original).
pub(crate) fn origins(sections: &[Section], nodes: usize) -> Vec<usize> {
    let mut origin: Vec<usize> = (0..nodes).collect();
    for s in sections {
        for &(n, c) in &s.pairs {
            origin[c] = origin[n];
        }
    }
    origin
}

/// The pairs of elements that face each other across a section's cut in
/// the uncut `mesh` (an element edge, or face in 3D, of the body on the
/// cut, one element on each side): an adaptive run splits both together
/// (`crate::input::mesh::refine::Refined::refine_tied`), so that no hanging node
/// lies on a cut, where it would hang across the cut from the nodes of the
/// other side. A section the cut would refuse (an unknown body, no line)
/// gives none.
pub fn facing(case: &Case, mesh: &Mesh) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for spec in &case.pretension {
        let Some(body) = mesh.bodies.iter().position(|b| *b == spec.body) else {
            continue;
        };
        let (axis, value) = match (spec.x, spec.y, spec.z) {
            (Some(x), None, None) => (0, x),
            (None, Some(y), None) => (1, y),
            (None, None, Some(z)) => (2, z),
            _ => continue,
        };
        out.extend(cut::facing(mesh, body, axis, value));
    }
    out.sort_unstable();
    out
}

/// Completes the sections once the loads are known: each one's dof after
/// the `nodes` mesh nodes and its lock time (the end of its force history:
/// `end_of(history)`; never with `lock = false`, a shortening, or no
/// history in a case without histories).
pub fn finish(
    case: &Case,
    sections: &mut [Section],
    nd: NodeDofs,
    nodes: usize,
    lock_end: &[Option<f64>],
) {
    for (k, (s, spec)) in sections.iter_mut().zip(&case.pretension).enumerate() {
        s.dof = dof(nd, nodes, k);
        s.lock_after = match (spec.force, spec.lock.unwrap_or(true)) {
            (Some(_), true) => lock_end[k].unwrap_or(f64::INFINITY),
            _ => f64::INFINITY,
        };
    }
}

/// The constraints of the sections: the copies follow their nodes (or,
/// where only a copy is held, the node follows its copy); a tie whose two
/// dofs are both prescribed to the same value and that no section's
/// shortening enters (a cut node on the axis, held u_r = 0 on both sides)
/// is left out; a node held on both sides of a cut otherwise is refused.
///
/// The copies of one mesh node form a group: one copy per section through
/// it, and where two sections cross, copies of copies (the quadrant beyond
/// both cuts holds the node moved by both shortenings). In each component
/// every member is u(root) − Σ s_k over the sections k between it and the
/// group's mesh node whose normal is that component; the group's master is
/// its first held member (else the mesh node itself), and every other
/// member follows the master directly, so a hold anywhere in the group is
/// one master, never a dof tied twice.
pub fn constraints(
    nd: NodeDofs,
    nodes: &[[f64; 3]],
    sections: &[Section],
    prescribed: &[(usize, f64)],
    prescribed_history: &[Option<usize>],
    place: &str,
) -> Result<Vec<Constraint>> {
    let given: HashMap<usize, (f64, Option<usize>)> = prescribed
        .iter()
        .zip(prescribed_history)
        .map(|(&(d, v), &h)| (d, (v, h)))
        .collect();
    let mut groups = groups_by_root(sections);
    let names = |ks: &[usize]| -> String {
        ks.iter()
            .map(|&k| format!("\"{}\"", sections[k].name))
            .collect::<Vec<_>>()
            .join(" and ")
    };
    // slave dof → its constraint
    let mut made: HashMap<usize, Constraint> = HashMap::new();
    for (&r, members) in &mut groups {
        members.sort_unstable_by_key(|m| m.0);
        // u_θ too with twist: no section's normal is θ, so the copy turns
        // with its node and the cut carries the torque
        for comp in 0..nd.per_node() {
            // the sections whose shortening enters this component of member m
            let enter = |path: &[usize]| -> Vec<usize> {
                path.iter()
                    .copied()
                    .filter(|&k| sections[k].axis == comp)
                    .collect()
            };
            let held = |m: usize| given.get(&nd.dof(m, comp));
            let (master, master_path) = members
                .iter()
                .find(|m| held(m.0).is_some())
                .unwrap_or(&members[0]);
            let from = enter(master_path);
            for (m, path) in members.iter() {
                if m == master {
                    continue;
                }
                let to = enter(path);
                // u(m) = u(master) + Σ_{from∖to} s − Σ_{to∖from} s
                let mut terms = vec![(nd.dof(*master, comp), 1.0)];
                let mut through: Vec<usize> = Vec::new();
                for (k, section) in sections.iter().enumerate() {
                    match (from.contains(&k), to.contains(&k)) {
                        (true, false) => terms.push((section.dof, 1.0)),
                        (false, true) => terms.push((section.dof, -1.0)),
                        _ => continue,
                    }
                    through.push(k);
                }
                let mut path_all: Vec<usize> = path.iter().chain(master_path).copied().collect();
                path_all.sort_unstable();
                path_all.dedup();
                if let Some(v) = held(*m) {
                    if through.is_empty() && Some(v) == held(*master) {
                        continue;
                    }
                    let node = node_words(nd, nodes, r);
                    let what = component(nd, comp);
                    return Err(held_twice(&node, what, &path_all, &through, place, &names));
                }
                made.insert(
                    nd.dof(*m, comp),
                    Constraint {
                        slave: nd.dof(*m, comp),
                        terms,
                        offset: 0.0,
                        history: None,
                        origin: format!("pretension {}", names(&path_all)),
                    },
                );
            }
        }
    }
    // in the order of the sections' pairs (the copy's tie, then the node's)
    let mut out = Vec::with_capacity(made.len());
    for s in sections {
        for &(n, c) in &s.pairs {
            for comp in 0..nd.per_node() {
                for m in [c, n] {
                    if let Some(k) = made.remove(&nd.dof(m, comp)) {
                        out.push(k);
                    }
                }
            }
        }
    }
    Ok(out)
}

/// The nodes of the cuts grouped by the mesh node they copy (their root),
/// each with the sections between it and its root (ascending): a node and
/// its copies across every cut it lies on.
fn groups_by_root(sections: &[Section]) -> BTreeMap<usize, Vec<(usize, Vec<usize>)>> {
    // each copy's node and section, then each cut node's sections back to
    // its mesh node (ascending)
    let parent: HashMap<usize, (usize, usize)> = sections
        .iter()
        .enumerate()
        .flat_map(|(k, s)| s.pairs.iter().map(move |&(n, c)| (c, (n, k))))
        .collect();
    let root = |mut c: usize| -> (usize, Vec<usize>) {
        let mut path = Vec::new();
        while let Some(&(n, k)) = parent.get(&c) {
            path.push(k);
            c = n;
        }
        path.sort_unstable();
        (c, path)
    };
    let mut groups: BTreeMap<usize, Vec<(usize, Vec<usize>)>> = BTreeMap::new();
    for s in sections {
        for &(n, c) in &s.pairs {
            for m in [n, c] {
                let (r, path) = root(m);
                let g = groups.entry(r).or_default();
                if !g.iter().any(|x| x.0 == m) {
                    g.push((m, path));
                }
            }
        }
    }
    groups
}

/// Node `node` in a message: at (x, y), or (x, y, z) in a 3D model.
fn node_words(nd: NodeDofs, nodes: &[[f64; 3]], node: usize) -> String {
    let [x, y, z] = nodes[node];
    if nd.per_node() == 3 && !nd.twist() {
        format!("node {node} at ({x}, {y}, {z})")
    } else {
        format!("node {node} at ({x}, {y})")
    }
}

/// Component `comp` in a message.
fn component(nd: NodeDofs, comp: usize) -> &'static str {
    match comp {
        2 if nd.twist() => "u_θ (a rotation about the axis)",
        _ => ["ux", "uy", "uz"][comp],
    }
}

/// The refusal of a cut node (`at`, named by [`node_words`]) held in `x`
/// on both sides of a cut: `through`, the sections whose shortening the
/// two holds would fix (none: held with two values where no section
/// enters), `sections_at` all sections through it.
fn held_twice(
    at: &str,
    x: &str,
    sections_at: &[usize],
    through: &[usize],
    place: &str,
    names: &dyn Fn(&[usize]) -> String,
) -> Error {
    let where_ = if sections_at.len() > 1 {
        format!(
            "{at}, where the cuts of pretension {} meet,",
            names(sections_at)
        )
    } else {
        format!("{at} on the cut")
    };
    let what = if through.is_empty() {
        format!("{where_} is held in {x} with different values on the two sides of a cut, which its ties keep together")
    } else {
        format!(
            "{where_} is held in {x} on both sides of the cut of pretension {}: the section{} could not shorten (move the cut away from the supports)",
            names(through),
            if through.len() > 1 { "s" } else { "" }
        )
    };
    Error::input(format!("{place}: pretension {}", names(sections_at)), what)
}

/// The two sides of a section's cut when the cut divides its body in two
/// (the nodes of the elements beyond the cut and those of the elements
/// before it share none): each node's side, `true` beyond (the side the
/// normal points to; nodes of other bodies `false`). `None` when the body
/// stays in one piece around the cut's end (a cut part way across): then
/// the shortening strains the body, it moves no part of it rigidly.
pub fn sides(mesh: &Mesh, section: &Section) -> Option<Vec<bool>> {
    let mut side = vec![[false; 2]; mesh.nodes.len()];
    for el in mesh.elements.iter().filter(|el| el.body == section.body) {
        // every element lies on one side of its body's cuts
        // ([`cut`]): its centre tells which
        let corners = el.corners();
        let centre = corners
            .iter()
            .map(|&n| mesh.nodes[n][section.axis])
            .sum::<f64>()
            / corners.len() as f64;
        let beyond = usize::from(centre > section.at);
        for &n in el.nodes() {
            side[n][beyond] = true;
        }
    }
    (!side.iter().any(|s| s[0] && s[1])).then(|| side.iter().map(|s| s[1]).collect())
}

/// Whether section `s` is free at pseudo-time t (a step to t): controlled
/// by its force and not locked yet, so its sides move apart or together
/// with nothing but that force between them.
pub(crate) fn free_at(s: &Section, t: f64) -> bool {
    s.control == "force" && t <= s.lock_after
}
