//! What a refinement carries over besides the elements: node sets, edge
//! sets and interfaces.

use super::Quarters;
use crate::input::mesh::{ContactEdge, Mesh, MeshError};
use std::collections::HashSet;

/// [a, m, b] as its two halves [a, q₁, m], [m, q₂, b] when it was split.
fn halves(q: &Quarters, e: [usize; 3]) -> Option<[[usize; 3]; 2]> {
    let [q1, q2] = q.along(e)?;
    Some([[e[0], q1, e[1]], [e[1], q2, e[2]]])
}

/// Every edge of a list split where its element was refined, in walk order.
fn split_all(q: &Quarters, edges: &[[usize; 3]]) -> Vec<[usize; 3]> {
    edges
        .iter()
        .flat_map(|&e| match halves(q, e) {
            Some(h) => h.to_vec(),
            None => vec![e],
        })
        .collect()
}

/// Carries `mesh`'s sets and interfaces to `out` (its elements refined
/// where `on`; `interior` the new inside nodes of each refined element):
/// - an edge set's or a non-matching interface side's split edge becomes
///   its two halves in walk order;
/// - a node set gains the quarter points of a split edge whose three nodes
///   it holds, and the inside nodes of a refined element whose eight nodes
///   it holds (a set over a region);
/// - a matching interface edge becomes two, both sides split together (the
///   closure refined the facing elements); one side split alone is refused.
pub(crate) fn carry(
    mesh: &Mesh,
    out: &mut Mesh,
    q: &Quarters,
    on: &[bool],
    interior: &[Vec<usize>],
) -> Result<(), MeshError> {
    for edges in out.edge_sets.values_mut() {
        *edges = split_all(q, edges);
    }
    for set in out.node_sets.values_mut() {
        let held: HashSet<usize> = set.iter().copied().collect();
        for (e, el) in mesh.elements.iter().enumerate().filter(|(e, _)| on[*e]) {
            for edge in el.edges() {
                if edge.iter().all(|n| held.contains(n)) {
                    set.extend(q.along(edge).into_iter().flatten());
                }
            }
            if el.nodes().iter().all(|n| held.contains(n)) {
                set.extend(&interior[e]);
            }
        }
        set.sort_unstable();
        set.dedup();
    }
    for iface in out.interfaces.iter_mut() {
        let mut edges = Vec::with_capacity(iface.edges.len());
        for ce in &iface.edges {
            match (halves(q, ce.a), halves(q, ce.b)) {
                (None, None) => edges.push(ce.clone()),
                (Some(a), Some(b)) => {
                    edges.push(ContactEdge { a: a[0], b: b[0] });
                    edges.push(ContactEdge { a: a[1], b: b[1] });
                }
                _ => {
                    return Err(MeshError(format!(
                        "refinement: interface \"{}\" edge {:?} / {:?} was split on one side only",
                        iface.name, ce.a, ce.b
                    )))
                }
            }
        }
        iface.edges = edges;
        if let Some(nm) = iface.nonmatching.as_mut() {
            nm.slave = split_all(q, &nm.slave);
            nm.master = split_all(q, &nm.master);
        }
    }
    Ok(())
}
