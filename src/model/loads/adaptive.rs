//! What an adaptive run ([`crate::app::adapt`]) needs of the loads and supports
//! read on its start mesh: that every refined mesh selects the same part of
//! the body. A refinement splits edges and elements and adds their new nodes
//! to the sets that held the whole edge or element ([`crate::input::mesh::refine`]);
//! an `x_range` / `y_range` then selects among them. Where a range's end lies
//! inside an edge or element of the set, the part it selects moves with the
//! mesh (a `[[load]]` takes the edges whose midpoint is in range: a longer or
//! shorter strip on every cycle; a `[[boundary]]` holds the new nodes on one
//! side of the end and not the other), and each cycle would solve another
//! problem. Such a range is refused in an adaptive run: it must end on
//! element edges (a block breakpoint there).
//!
//! A piece (an edge curve, or an element's area) is selected the same on
//! every mesh when it lies wholly inside the ranges or wholly outside them,
//! or meets them only along its own boundary (a range ending on the piece's
//! end, or a point range on its side). Its extent — the bounding box of the
//! quadratic edge curves, exact — decides that, axis by axis.

use crate::error::{Error, Result};
use crate::input::mesh::Mesh;
use std::collections::HashSet;

/// The tolerance of [`super::in_range`] (mm).
const TOL: f64 = 1e-9;

/// How a piece's extent [e₀, e₁] along one axis lies against a range.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Along {
    /// Within the range (or no range on this axis).
    Inside,
    /// Beyond it: no point of the piece is selected.
    Apart,
    /// Meeting it at the piece's own extreme only.
    Touching,
    /// The range's end lies inside the piece.
    Cut,
}

fn along([e0, e1]: [f64; 2], range: &Option<[f64; 2]>) -> Along {
    let Some([lo, hi]) = *range else {
        return Along::Inside;
    };
    if e0 >= lo - TOL && e1 <= hi + TOL {
        Along::Inside
    } else if e1 < lo - TOL || e0 > hi + TOL {
        Along::Apart
    } else if e1 <= lo + TOL || e0 >= hi - TOL {
        Along::Touching
    } else {
        Along::Cut
    }
}

/// The axis (0: x, 1: y) whose range cuts a piece of this extent, when the
/// piece has points both selected and not beyond its own boundary.
fn cutting(extent: [[f64; 2]; 2], ranges: [&Option<[f64; 2]>; 2]) -> Option<usize> {
    let rel = [along(extent[0], ranges[0]), along(extent[1], ranges[1])];
    if rel
        .iter()
        .any(|r| matches!(r, Along::Apart | Along::Touching))
    {
        return None;
    }
    rel.iter().position(|&r| r == Along::Cut)
}

/// The extent of the quadratic edge [a, m, b] per axis: x(s) = x_m +
/// s (x_b − x_a)/2 + s² ((x_a + x_b)/2 − x_m) over s ∈ [−1, 1].
fn edge_extent(mesh: &Mesh, [a, m, b]: [usize; 3]) -> [[f64; 2]; 2] {
    let (xa, xm, xb) = (mesh.nodes[a], mesh.nodes[m], mesh.nodes[b]);
    std::array::from_fn(|k| {
        let lin = 0.5 * (xb[k] - xa[k]);
        let quad = 0.5 * (xa[k] + xb[k]) - xm[k];
        let mut lo = xa[k].min(xb[k]);
        let mut hi = xa[k].max(xb[k]);
        if quad != 0.0 {
            let s = -lin / (2.0 * quad);
            if s > -1.0 && s < 1.0 {
                let v = xm[k] + s * lin + s * s * quad;
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        [lo, hi]
    })
}

fn union(a: [[f64; 2]; 2], b: [[f64; 2]; 2]) -> [[f64; 2]; 2] {
    std::array::from_fn(|k| [a[k][0].min(b[k][0]), a[k][1].max(b[k][1])])
}

/// The key of the range that cuts, and its words.
fn key(axis: usize, ranges: [&Option<[f64; 2]>; 2]) -> (String, String) {
    let name = ["x_range", "y_range"][axis];
    let [lo, hi] = ranges[axis].expect("a cutting axis has a range");
    (name.to_string(), format!("{name} = [{lo}, {hi}]"))
}

fn edge_words(mesh: &Mesh, e: [usize; 3]) -> String {
    let (a, b) = (mesh.nodes[e[0]], mesh.nodes[e[2]]);
    format!("the edge from ({}, {}) to ({}, {})", a[0], a[1], b[0], b[1])
}

/// A `[[load]]`'s ranges against its edge set: refused where a range ends
/// inside an edge (`at` names the load).
pub(super) fn check_edges(
    mesh: &Mesh,
    edges: &[[usize; 3]],
    ranges: [&Option<[f64; 2]>; 2],
    at: &str,
) -> Result<()> {
    if ranges.iter().all(|r| r.is_none()) {
        return Ok(());
    }
    for &e in edges {
        if let Some(axis) = cutting(edge_extent(mesh, e), ranges) {
            let (name, range) = key(axis, ranges);
            return Err(Error::input(
                format!("{at} {name}"),
                format!(
                    "{range} ends inside {} of the set: an adaptive run ([adapt]) splits that edge and would load another part of it on every mesh (a range takes the edges whose midpoint it holds), so each cycle would solve another problem; end the range on an element edge (a block breakpoint there) or widen it to the edge's ends",
                    edge_words(mesh, e)
                ),
            ));
        }
    }
    Ok(())
}

/// A `[[boundary]]`'s ranges against its node set: refused where a range
/// ends inside an edge or an element whose nodes the set holds (those a
/// refinement adds nodes to).
pub(super) fn check_nodes(
    mesh: &Mesh,
    nodes: &[usize],
    ranges: [&Option<[f64; 2]>; 2],
    at: &str,
) -> Result<()> {
    if ranges.iter().all(|r| r.is_none()) {
        return Ok(());
    }
    let held: HashSet<usize> = nodes.iter().copied().collect();
    for (i, el) in mesh.elements.iter().enumerate() {
        let mut area: Option<[[f64; 2]; 2]> = None;
        for e in el.edges() {
            let ext = edge_extent(mesh, e);
            area = Some(area.map_or(ext, |a| union(a, ext)));
            if !e.iter().all(|n| held.contains(n)) {
                continue;
            }
            if let Some(axis) = cutting(ext, ranges) {
                let (name, range) = key(axis, ranges);
                return Err(Error::input(
                    format!("{at} {name}"),
                    format!(
                        "{range} ends inside {} of the set: an adaptive run ([adapt]) splits that edge and would hold the new nodes on one side of the range's end and not the other, another support on every mesh; end the range on an element edge (a block breakpoint there) or widen it to the edge's ends",
                        edge_words(mesh, e)
                    ),
                ));
            }
        }
        let whole = el.nodes().iter().all(|n| held.contains(n));
        if let Some(axis) = area.filter(|_| whole).and_then(|a| cutting(a, ranges)) {
            let (name, range) = key(axis, ranges);
            let c = mesh.node_mean(i);
            return Err(Error::input(
                format!("{at} {name}"),
                format!(
                    "{range} ends inside element {i} near ({:.4}, {:.4}), all of whose nodes the set holds: an adaptive run ([adapt]) splits it and would hold the new nodes on one side of the range's end and not the other, another support on every mesh; end the range on an element edge (a block breakpoint there)",
                    c[0], c[1]
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_range_ending_inside_a_piece_cuts_it_and_one_ending_on_it_does_not() {
        let r = Some([2.0, 4.0]);
        let none = None;
        // inside, beyond, touching at an end, cut at either end, spanning
        assert_eq!(cutting([[2.0, 4.0], [0.0, 1.0]], [&r, &none]), None);
        assert_eq!(cutting([[4.0, 5.0], [0.0, 1.0]], [&r, &none]), None);
        assert_eq!(cutting([[0.0, 2.0], [0.0, 1.0]], [&r, &none]), None);
        assert_eq!(cutting([[5.0, 6.0], [0.0, 1.0]], [&r, &none]), None);
        assert_eq!(cutting([[1.0, 3.0], [0.0, 1.0]], [&r, &none]), Some(0));
        assert_eq!(cutting([[3.0, 5.0], [0.0, 1.0]], [&r, &none]), Some(0));
        assert_eq!(cutting([[1.0, 5.0], [0.0, 1.0]], [&r, &none]), Some(0));
        // a point range: on a side of the piece, or through it
        let p = Some([3.0, 3.0]);
        assert_eq!(cutting([[3.0, 3.0], [0.0, 1.0]], [&p, &none]), None);
        assert_eq!(cutting([[1.0, 3.0], [0.0, 1.0]], [&p, &none]), None);
        assert_eq!(cutting([[1.0, 5.0], [0.0, 1.0]], [&p, &none]), Some(0));
        // a y range the piece is beyond: nothing of it is selected
        let y = Some([5.0, 6.0]);
        assert_eq!(cutting([[1.0, 5.0], [0.0, 1.0]], [&r, &y]), None);
    }
}
