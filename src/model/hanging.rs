//! The hanging nodes of a locally refined mesh as linear constraints of the
//! model ([`crate::mesh::refine`], [`crate::constraint`]).

use crate::constraint::Constraint;
use crate::error::{Error, Result};
use crate::mesh::refine::HangingNode;
use crate::mesh::Mesh;
use crate::pretension::Section;
use std::collections::HashSet;

/// The constraints u_q = Σ N_i(s) u_i of every hanging node (found on the
/// mesh before any pretension cut), every dof component of the node.
///
/// Refused: a hanging node held by a support, and a hanging node (or a node
/// of its coarse edge) on a pretension section's cut. Neither happens on a
/// mesh refined from the case's own boundary: a hanging node lies inside
/// the body, on the edge between a coarse element and two finer ones, while
/// supports act on boundary edges (edge sets walk the boundary), and a node
/// set gains a refinement's new node only where it held the whole split edge.
/// A node set drawn through the inside (a Gmsh physical line) can still hold
/// one; a slave dof cannot also take a prescribed value (it has no equation),
/// so the case is refused rather than one of the two silently dropped. A cut
/// duplicates the nodes on its line for the elements beyond it, which would
/// tie a hanging node to nodes of the other side; refining both sides of the
/// cut alike keeps hanging nodes off it.
pub(super) fn constraints(
    mesh: &Mesh,
    hanging: &[HangingNode],
    prescribed: &[(usize, f64)],
    sections: &[Section],
    place: &str,
) -> Result<Vec<Constraint>> {
    let held: HashSet<usize> = prescribed.iter().map(|p| p.0).collect();
    let cut: HashSet<usize> = sections
        .iter()
        .flat_map(|s| s.pairs.iter().flat_map(|&(n, c)| [n, c]))
        .collect();
    let nd = mesh.node_dofs;
    let at = |n: usize| mesh.nodes[n];
    let mut out = Vec::new();
    for h in hanging {
        if nd.of(h.node).any(|d| held.contains(&d)) {
            return Err(Error::input(
                format!("{place}: [mesh]"),
                format!(
                    "hanging node {} at {:?} (on the edge of element {} refined on one side only) is held by a support: a node tied to its edge cannot take a prescribed value too; refine both sides of the supported line alike",
                    h.node,
                    at(h.node),
                    h.element
                ),
            ));
        }
        if let Some(&n) = std::iter::once(&h.node)
            .chain(&h.edge)
            .find(|n| cut.contains(n))
        {
            return Err(Error::input(
                format!("{place}: [[pretension]]"),
                format!(
                    "the cut passes through node {n} at {:?} of the hanging node {} (an edge refined on one side only): refine both sides of the cut alike",
                    at(n),
                    h.node
                ),
            ));
        }
        out.extend(h.constraints(nd));
    }
    Ok(out)
}
