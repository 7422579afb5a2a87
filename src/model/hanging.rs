//! The hanging nodes of a locally refined mesh as linear constraints of the
//! model ([`crate::input::mesh::refine`], [`crate::model::constraint`]).

use crate::error::{Error, Result};
use crate::input::mesh::refine::edge_shape;
use crate::input::mesh::refine::HangingNode;
use crate::input::mesh::{Mesh, NodeDofs};
use crate::model::constraint::Constraint;
use crate::model::pretension::Section;
use std::collections::{HashMap, HashSet};

/// The constraints u_q = Σ N_i(s) u_i of every hanging node (found on the
/// mesh before any pretension cut), every dof component of the node.
///
/// A cut duplicates the nodes on its line for the elements beyond it, so
/// the masters are taken from the coarse element as it is after the cuts:
/// a coarse edge that ends on a cut (a hanging node beside the cut, on the
/// same side as its coarse element) follows that side's copy, which follows
/// the other side through the section's own constraint (the chain is
/// substituted, [`crate::model::constraint::Constraints::new`]).
///
/// A hanging node that a support holds keeps the support's value where
/// the support holds its edge alike (the same history, and the value the
/// edge's shape gives it: a body held as a whole, whose inside an adaptive
/// run refines); the tie is then left out for that dof.
///
/// Refused: a hanging node held by a support that does not hold its edge
/// alike (a node set drawn through the inside, such as a Gmsh physical
/// line, refined on one side only: a slave dof cannot also take another
/// value, so the case is refused rather than one of the two silently
/// dropped), and a hanging node on a cut whose coarse element lies on the
/// other side of it (`[mesh] refine_region` on one side of a cut: the node
/// would hang from the other side's nodes). An adaptive run splits the two
/// sides of a cut together ([`crate::model::pretension::facing`]).
pub(super) fn constraints(
    mesh: &Mesh,
    hanging: &[HangingNode],
    prescribed: &[(usize, f64)],
    prescribed_history: &[Option<usize>],
    sections: &[Section],
    place: &str,
) -> Result<Vec<Constraint>> {
    let given: HashMap<usize, (f64, Option<usize>)> = prescribed
        .iter()
        .zip(prescribed_history)
        .map(|(&(d, v), &h)| (d, (v, h)))
        .collect();
    // every node's node before the cuts (a copy's original)
    let origin = crate::model::pretension::origins(sections, mesh.nodes.len());
    let of_q: HashSet<usize> = hanging.iter().map(|h| h.node).collect();
    let mut holder: HashMap<usize, usize> = HashMap::new();
    for (e, el) in mesh.elements.iter().enumerate() {
        for &n in el.nodes().iter().filter(|n| of_q.contains(n)) {
            holder.entry(n).or_insert(e);
        }
    }
    let nd = mesh.node_dofs;
    let at = |n: usize| mesh.xy(n);
    let mut out = Vec::new();
    for h in hanging {
        // the coarse edge as its element holds it after the cuts
        let coarse = mesh.elements[h.element].nodes();
        let edge = h.edge.map(|n| {
            coarse
                .iter()
                .copied()
                .find(|&c| origin[c] == n)
                .unwrap_or(n)
        });
        let fine = holder.get(&h.node).map(|&e| mesh.elements[e].nodes());
        if fine.is_some_and(|f| !f.contains(&edge[1])) {
            let name = sections
                .iter()
                .find(|s| s.pairs.iter().any(|&(n, _)| origin[n] == h.edge[1]))
                .map_or(String::new(), |s| s.name.clone());
            return Err(Error::input(
                format!("{place}: [[pretension]] \"{}\"", crate::error::clip(&name)),
                format!(
                    "the cut passes along the edge of element {} at {:?} that is refined on the other side only (hanging node {}): the node would hang from the nodes across the cut; refine both sides of the cut alike (the refine_region box on both sides of the line)",
                    h.element,
                    at(h.edge[1]),
                    h.node
                ),
            ));
        }
        let h = HangingNode { edge, ..h.clone() };
        for c in node_constraints(&h, nd) {
            if !given.contains_key(&c.slave) {
                out.push(c);
            } else if !agrees(&c, &given) {
                return Err(Error::input(
                    format!("{place}: [mesh]"),
                    format!(
                        "hanging node {} at {:?} (on the edge of element {} refined on one side only) is held by a support that does not hold its edge alike: a node tied to its edge cannot take another value too; refine both sides of the supported line alike",
                        h.node,
                        at(h.node),
                        h.element
                    ),
                ));
            }
            // else the support gives the node the value its edge gives it
            // (a body held as a whole): the tie is the support's, left out
        }
    }
    Ok(out)
}

/// Whether the supports give a hanging node's dof the value its edge
/// does: every master held, on the slave's history, and Σ c v_m = v_s.
fn agrees(c: &Constraint, given: &HashMap<usize, (f64, Option<usize>)>) -> bool {
    let (v, h) = given[&c.slave];
    let mut sum = 0.0;
    let mut scale = v.abs();
    for &(d, w) in &c.terms {
        match given.get(&d) {
            Some(&(vm, hm)) if hm == h => {
                sum += w * vm;
                scale = scale.max(vm.abs());
            }
            _ => return false,
        }
    }
    (sum - v).abs() <= 1e-12 * scale
}

/// u_q = Σ N_i(s) u_i for every dof component of the hanging node `h`.
fn node_constraints(h: &HangingNode, nd: NodeDofs) -> Vec<Constraint> {
    let w = edge_shape(h.s);
    (0..nd.per_node())
        .map(|c| Constraint {
            slave: nd.dof(h.node, c),
            terms: (0..3).map(|i| (nd.dof(h.edge[i], c), w[i])).collect(),
            offset: 0.0,
            history: None,
            origin: format!(
                "hanging node {} on the edge of element {}",
                h.node, h.element
            ),
        })
        .collect()
}
