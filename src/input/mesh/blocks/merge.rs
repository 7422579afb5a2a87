//! Bodies of several blocks (issue 27): blocks that name the same body and
//! share a side are one body, their coincident nodes merged.
//!
//! Two blocks of one body share a side where the right side of one and the
//! left side of the other (or the top of one and the bottom of the other)
//! lie on one line and overlap along it with positive length (more than the
//! tolerance, 1e-9 of the longer side, as for interfaces). Over the overlap
//! every node of either side must coincide with a node of the other (within
//! that tolerance), and no element edge may straddle an end of the overlap:
//! the shared edges are then the same quadratic curves on both sides, and
//! merging their nodes changes no geometry. A curved bottom or top is never
//! shared (its nodes lie off the line). The blocks of a body must not share
//! area, and must form one piece through shared sides; the names of blocks
//! and bodies must leave every set name one set ([`check_names`]).
//!
//! The merge keeps the lowest-numbered node of each coincident group, with
//! its coordinates, numbers the kept nodes in their order and remaps the
//! elements, the sets and the interfaces. The shared edges leave the
//! blocks' side edge sets (they are inside the body), a side's node set
//! becomes the nodes of its remaining edges (a support on it holds no
//! interior node), and a non-matching interface's sides lose them too. A
//! mesh without a body of several blocks is left as it was, node for node.

use super::{BlockSpec, Grid};
use crate::error::clip;
use crate::input::mesh::{Mesh, MeshError};
use std::collections::HashSet;

/// What [`apply`] merges, found by [`plan`] on the blocks' own node ids.
#[derive(Default)]
pub(super) struct Plan {
    /// Coincident nodes of two shared sides.
    pairs: Vec<(usize, usize)>,
    /// The mid nodes of the shared edges (a mid node is on one edge).
    inner: HashSet<usize>,
}

/// Block names: every block's its own; a block named like a body only when
/// it is that body's only block (its `<name>.all` is then the body's).
/// Otherwise `<name>.all` would be two sets, and interfaces could not tell
/// the blocks apart.
pub(super) fn check_names(blocks: &[BlockSpec]) -> Result<(), MeshError> {
    for (k, b) in blocks.iter().enumerate() {
        let name = b.name();
        if let Some(a) = blocks[..k].iter().find(|a| a.name() == name) {
            let hint = if a.body == b.body {
                "the blocks of a body of several blocks each need a `name` of their own"
            } else {
                "give one of them a `name` (it names the block's sets and interfaces)"
            };
            return Err(MeshError(format!(
                "two blocks are named \"{}\": {hint}",
                clip(name)
            )));
        }
    }
    for b in blocks {
        let name = b.name();
        if name != b.body && blocks.iter().any(|a| a.body == name) {
            return Err(MeshError(format!(
                "block \"{}\" of body \"{}\" has the name of body \"{}\": the set {}.all would be both the block's nodes and that body's; give the block another name",
                clip(name),
                clip(&b.body),
                clip(name),
                clip(name)
            )));
        }
        let count = blocks.iter().filter(|a| a.body == b.body).count();
        if name == b.body && count > 1 {
            return Err(MeshError(format!(
                "body \"{}\" has {count} blocks and one of them is named \"{}\" like the body (no `name`, or the body's): {}.all is the whole body; give every block of a body of several blocks a `name` other than the body's",
                clip(name),
                clip(name),
                clip(name)
            )));
        }
    }
    Ok(())
}

/// The shared sides of every body of several blocks (see the module text),
/// or the refusal that names the blocks.
pub(super) fn plan(mesh: &Mesh, grids: &[Grid]) -> Result<Plan, MeshError> {
    let mut plan = Plan::default();
    for body in 0..mesh.bodies.len() {
        let members: Vec<usize> = (0..grids.len())
            .filter(|&k| grids[k].body == body)
            .collect();
        if members.len() < 2 {
            continue;
        }
        for (n, &i) in members.iter().enumerate() {
            for &j in &members[..n] {
                no_common_area(mesh, &grids[j], &grids[i])?;
            }
        }
        let mut links = Vec::new();
        for (n, &i) in members.iter().enumerate() {
            for &j in &members[n + 1..] {
                for (p, q) in [(i, j), (j, i)] {
                    for vertical in [true, false] {
                        if share(mesh, &grids[p], &grids[q], vertical, &mut plan)? {
                            links.push((i, j));
                        }
                    }
                }
            }
        }
        one_piece(mesh, grids, &members, &links)?;
    }
    Ok(plan)
}

/// The rectangle of a block: [x₀, x₁, y₀, y₁].
fn rect(g: &Grid) -> [f64; 4] {
    [g.xs[0], g.xs[g.xs.len() - 1], g.ys[0], g.ys[g.ys.len() - 1]]
}

/// Two blocks of one body may touch, not share area (within 1e-9 of the
/// larger block's size, as between bodies: [`crate::model::consistency`]).
fn no_common_area(mesh: &Mesh, a: &Grid, b: &Grid) -> Result<(), MeshError> {
    if let Some([x0, x1, y0, y1]) = crate::input::mesh::blocks::common_area(rect(a), rect(b)) {
        return Err(MeshError(format!(
            "blocks \"{}\" and \"{}\" of body \"{}\" overlap in x = {x0} … {x1}, y = {y0} … {y1}: the blocks of one body may share sides, not area",
            clip(&a.name),
            clip(&b.name),
            clip(&mesh.bodies[a.body])
        )));
    }
    Ok(())
}

/// Do the right side (`vertical`) or the top of block `p` and the left side
/// or the bottom of block `q` share a side? If they do, their node pairs and
/// shared edges go into `plan`; if they lie on one line and overlap but do
/// not match node for node, or one is curved, the refusal names both.
fn share(
    mesh: &Mesh,
    p: &Grid,
    q: &Grid,
    vertical: bool,
    plan: &mut Plan,
) -> Result<bool, MeshError> {
    // both lines in increasing coordinate along the side
    let (k, lp, lq, ap, aq) = if vertical {
        let il = p.ids[0].len() - 1;
        (
            1,
            p.ids.iter().map(|row| row[il]).collect::<Vec<_>>(),
            q.ids.iter().map(|row| row[0]).collect::<Vec<_>>(),
            p.xs[p.xs.len() - 1],
            q.xs[0],
        )
    } else {
        (
            0,
            p.ids[p.ids.len() - 1].clone(),
            q.ids[0].clone(),
            p.ys[p.ys.len() - 1],
            q.ys[0],
        )
    };
    let (along, across) = (["x", "y"][k], ["x", "y"][1 - k]);
    let at = |n: usize| mesh.nodes[n][k];
    let range = |l: &[usize]| [at(l[0]), at(l[l.len() - 1])];
    let (rp, rq) = (range(&lp), range(&lq));
    let tol = 1e-9 * (rp[1] - rp[0]).max(rq[1] - rq[0]);
    let (lo, hi) = (rp[0].max(rq[0]), rp[1].min(rq[1]));
    if (ap - aq).abs() > tol || hi - lo <= tol {
        return Ok(false);
    }
    let body = clip(&mesh.bodies[p.body]);
    let (np, nq) = (clip(&p.name), clip(&q.name));
    let shared = format!(
        "blocks \"{np}\" and \"{nq}\" of body \"{body}\" share the side {across} = {ap} ({along} = {lo} … {hi})"
    );
    if !vertical && (p.curved[1] || q.curved[0]) {
        let (block, side) = if p.curved[1] {
            (&np, "top")
        } else {
            (&nq, "bottom")
        };
        return Err(MeshError(format!(
            "{shared}, but the {side} of \"{block}\" is curved: a curved side cannot be shared (its nodes lie off the line); make the blocks two bodies with an interface, or the side straight"
        )));
    }
    let inside = |v: f64| v >= lo - tol && v <= hi + tol;
    let lines = [(&lp, &lq, &np, &nq), (&lq, &lp, &nq, &np)];
    for (line, _, name, _) in lines {
        for w in line.windows(3).step_by(2) {
            if !(inside(at(w[0])) && inside(at(w[2]))) {
                if inside(at(w[1])) {
                    return Err(MeshError(format!(
                        "{shared}, but an element edge of \"{name}\" straddles the end of the shared side at {along} = {}: the blocks of one body must match node for node along a shared side",
                        at(w[1])
                    )));
                }
                continue;
            }
            plan.inner.insert(w[1]);
        }
    }
    for (line, other, name, other_name) in lines {
        for &n in line.iter().filter(|&&n| inside(at(n))) {
            let (x, v) = (mesh.nodes[n], at(n));
            // the lines run in increasing coordinate: binary search
            let first = other.partition_point(|&m| at(m) < v - tol);
            let close = |m: &usize| {
                let y = mesh.nodes[*m];
                (x[0] - y[0]).hypot(x[1] - y[1]) <= tol
            };
            let Some(m) = other.get(first).copied().filter(close) else {
                return Err(MeshError(format!(
                    "{shared}, but the node of \"{name}\" at ({}, {}) has no node of \"{other_name}\" there: the blocks of one body must match node for node along a shared side (the same breakpoints, element counts and grading)",
                    x[0], x[1]
                )));
            };
            plan.pairs.push((n, m));
        }
    }
    Ok(true)
}

/// The blocks of a body form one piece through shared sides; the first
/// block not joined to the body's first block is named.
fn one_piece(
    mesh: &Mesh,
    grids: &[Grid],
    members: &[usize],
    links: &[(usize, usize)],
) -> Result<(), MeshError> {
    let mut reached = vec![members[0]];
    loop {
        let before = reached.len();
        for &(i, j) in links {
            match (reached.contains(&i), reached.contains(&j)) {
                (true, false) => reached.push(j),
                (false, true) => reached.push(i),
                _ => {}
            }
        }
        if reached.len() == before {
            break;
        }
    }
    match members.iter().find(|k| !reached.contains(k)) {
        None => Ok(()),
        Some(&k) => Err(MeshError(format!(
            "block \"{}\" of body \"{}\" shares no side with block \"{}\" nor with the blocks joined to it: the blocks of one body must form one piece through shared sides (a side of one on a side of another, on one line, overlapping with positive length; a corner is not enough); give it a body of its own, or move it",
            clip(&grids[k].name),
            clip(&mesh.bodies[grids[k].body]),
            clip(&grids[members[0]].name)
        ))),
    }
}

/// Merges the nodes of the plan (see the module text) and gives every body
/// its set `<body>.all` (a body of one block named like it has it already).
pub(super) fn apply(mesh: &mut Mesh, plan: &Plan) {
    if !plan.pairs.is_empty() {
        merge(mesh, plan);
    }
    for (b, body) in mesh.bodies.iter().enumerate() {
        let key = format!("{body}.all");
        if mesh.node_sets.contains_key(&key) {
            continue;
        }
        let mut set: Vec<usize> = mesh
            .elements
            .iter()
            .filter(|el| el.body == b)
            .flat_map(|el| el.nodes().iter().copied())
            .collect();
        set.sort_unstable();
        set.dedup();
        mesh.node_sets.insert(key, set);
    }
}

/// The root of a node's group: its lowest-numbered node.
fn root(up: &mut [usize], mut n: usize) -> usize {
    while up[n] != n {
        up[n] = up[up[n]];
        n = up[n];
    }
    n
}

fn merge(mesh: &mut Mesh, plan: &Plan) {
    let count = mesh.nodes.len();
    let mut up: Vec<usize> = (0..count).collect();
    for &(a, b) in &plan.pairs {
        let (ra, rb) = (root(&mut up, a), root(&mut up, b));
        up[ra.max(rb)] = ra.min(rb);
    }
    let mut new = vec![usize::MAX; count];
    let mut nodes = Vec::with_capacity(count);
    for n in 0..count {
        let r = root(&mut up, n);
        if r == n {
            new[n] = nodes.len();
            nodes.push(mesh.nodes[n]);
        } else {
            // r < n: numbered already
            new[n] = new[r];
        }
    }
    mesh.nodes = nodes;
    let map3 = |e: &[usize; 3]| e.map(|n| new[n]);
    let outer = |e: &&[usize; 3]| !plan.inner.contains(&e[1]);
    for el in &mut mesh.elements {
        for n in el.nodes_mut() {
            *n = new[*n];
        }
    }
    for edges in mesh.edge_sets.values_mut() {
        *edges = edges.iter().filter(outer).map(map3).collect();
    }
    for (name, set) in mesh.node_sets.iter_mut() {
        *set = match mesh.edge_sets.get(name) {
            // a side: the nodes of its remaining edges
            Some(edges) => edges.iter().flatten().copied().collect(),
            None => set.iter().map(|&n| new[n]).collect(),
        };
        set.sort_unstable();
        set.dedup();
    }
    for iface in &mut mesh.interfaces {
        for e in &mut iface.edges {
            e.a = map3(&e.a);
            e.b = map3(&e.b);
        }
        if let Some(nm) = &mut iface.nonmatching {
            nm.slave = nm.slave.iter().filter(outer).map(map3).collect();
            nm.master = nm.master.iter().filter(outer).map(map3).collect();
        }
    }
}

#[cfg(test)]
mod tests;
