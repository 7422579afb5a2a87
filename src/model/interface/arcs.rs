//! Where along an interface its pairs lie: the interface's mean direction
//! and each pair's arc length s (the contact extent is read along s).

use super::InterfaceModel;
use crate::input::mesh::{Interface, Mesh};

/// The joint direction t of an interface: the internal tangent (n_y, −n_x)
/// at its first pair (+x on a horizontal interface, +y on a vertical one).
pub fn direction(im: &InterfaceModel) -> [f64; 2] {
    im.pairs
        .first()
        // + 0.0: no negative zero
        .map_or([1.0, 0.0], |p| [p.normal[1] + 0.0, -p.normal[0] + 0.0])
}

/// Length of the piece ξ ∈ [from, to] of a quadratic edge (3-point Gauss).
pub(crate) fn piece_length(x: &[[f64; 2]; 3], from: f64, to: f64) -> f64 {
    let (mid, half) = (0.5 * (from + to), 0.5 * (to - from));
    crate::physics::element::edge::gauss_1d(3)
        .iter()
        .map(|&(g, w)| {
            let s = mid + half * g;
            let dn = [s - 0.5, -2.0 * s, s + 0.5];
            let t = (0..3).fold([0.0, 0.0], |t, i| {
                [t[0] + dn[i] * x[i][0], t[1] + dn[i] * x[i][1]]
            });
            w * half * t[0].hypot(t[1])
        })
        .sum()
}

/// The arc length s of every pair of an interface (index as `im.pairs`),
/// mm, from its first pair along the walk direction (B on the right). The
/// edges are chained end to start; pieces that do not join (an interface
/// interrupted, or edges listed out of order in a mesh file) follow one
/// another by the position of their start along the interface's mean
/// direction, s continuing across a break by the straight distance.
///
/// On a non-matching interface (one pair per spring point) s is the slave
/// point's arc length along the slave side, from its first edge.
pub fn arc_lengths(mesh: &Mesh, iface: &Interface, im: &InterfaceModel) -> Vec<f64> {
    if iface.nonmatching.is_some() {
        return im
            .points
            .iter()
            .map(|p| p.slave_arc().unwrap_or(f64::NAN))
            .collect();
    }
    use std::collections::HashMap;
    let index: HashMap<(usize, usize), usize> = im
        .pairs
        .iter()
        .enumerate()
        .map(|(i, p)| ((p.a, p.b), i))
        .collect();
    let pair =
        |e: &crate::input::mesh::ContactEdge, i: usize| index.get(&(e.a[i], e.b[i])).copied();
    // edge by its start pair; a chain starts where no edge ends
    let mut by_start: HashMap<usize, usize> = HashMap::new();
    let mut ends = std::collections::HashSet::new();
    let mut dir = [0.0; 2];
    for (k, e) in iface.edges.iter().enumerate() {
        if let (Some(s), Some(t)) = (pair(e, 0), pair(e, 2)) {
            by_start.entry(s).or_insert(k);
            ends.insert(t);
        }
        let (p, q) = (mesh.nodes[e.b[0]], mesh.nodes[e.b[2]]);
        dir = [dir[0] + q[0] - p[0], dir[1] + q[1] - p[1]];
    }
    let along = |n: usize| mesh.nodes[n][0] * dir[0] + mesh.nodes[n][1] * dir[1];
    let mut starts: Vec<usize> = iface
        .edges
        .iter()
        .enumerate()
        .filter(|(_, e)| pair(e, 0).is_some_and(|s| !ends.contains(&s)))
        .map(|(k, _)| k)
        .collect();
    starts.sort_by(|&a, &b| along(iface.edges[a].b[0]).total_cmp(&along(iface.edges[b].b[0])));
    let mut s = vec![f64::NAN; im.pairs.len()];
    let mut done = vec![false; iface.edges.len()];
    let mut at = 0.0;
    let mut last: Option<[f64; 2]> = None;
    // the chains from their starts, then any closed loop left over
    let order: Vec<usize> = starts.into_iter().chain(0..iface.edges.len()).collect();
    for first in order {
        let mut k = first;
        while !done[k] {
            done[k] = true;
            let e = &iface.edges[k];
            let x: [[f64; 2]; 3] = std::array::from_fn(|i| mesh.xy(e.b[i]));
            if let Some(p) = last {
                at += (x[0][0] - p[0]).hypot(x[0][1] - p[1]);
            }
            let ids: [Option<usize>; 3] = std::array::from_fn(|i| pair(e, i));
            let marks = [
                at,
                at + piece_length(&x, -1.0, 0.0),
                at + piece_length(&x, -1.0, 1.0),
            ];
            for (id, mark) in ids.iter().zip(marks) {
                if let Some(&id) = id.as_ref() {
                    if s[id].is_nan() {
                        s[id] = mark;
                    }
                }
            }
            at = marks[2];
            last = Some(x[2]);
            match ids[2].and_then(|t| by_start.get(&t)) {
                Some(&next) => k = next,
                None => break,
            }
        }
    }
    // every pair lies on an edge; 0 only for a pair no edge names
    s.iter()
        .map(|v| if v.is_nan() { 0.0 } else { *v })
        .collect()
}
