//! The singular points of a plane mesh: where the linear-elastic stress is
//! unbounded in theory, so that a peak or a first yield found there grows
//! (or falls, a load) without limit as the mesh is refined
//! (docs/joints.md, "Singular corners"). Three kinds, all at nodes of a
//! body's outline:
//!
//! - a **re-entrant corner**: the outline's interior angle exceeds
//!   180° + [`TURN_DEGREES`] (a head on a shank, a shoulder without fillet);
//! - the **end of a contact interface's side** where that side's body has a
//!   corner (its outline turns there by more than [`TURN_DEGREES`] either
//!   way): a punch's edge, a bolt head's rim, a hub's bore edge. The point
//!   belongs to both bodies of the interface (the face opposite the edge is
//!   as singular as the edge). Not where the side ends on a mirror (the
//!   outline's other edge there a roller or symmetry line, the corner at
//!   most 90° + [`TURN_DEGREES`]): the middle of a symmetric half punch;
//! - the **end of a support** (`[[boundary]]`): a node where the held
//!   components change along the outline (a fixed edge ending on a free
//!   one), or a node held alone (a point support). Not at a convex corner
//!   of at most 90° + [`TURN_DEGREES`] where one of the two edges is a
//!   mirror (one in-plane component held: a roller, a symmetry line): the
//!   mirror doubles the corner, and a wedge of twice a right angle is a
//!   straight edge, where the field is smooth. A clamped edge (both
//!   components held) meeting a free one is singular at a right angle.
//!
//! The angle at a node is the one between the tangents of its two outline
//! edges at that node: each quadratic edge's own tangent (its midside node
//! bends it), not its chord. A fillet or a curved block, whose edges meet
//! tangentially, has no corner however coarse its elements; a polygon's
//! vertex turns by its angle. The threshold of 30° leaves a circle drawn by
//! straight edges of 12 or more a segment, or a gentle kink, unflagged.
//!
//! The axis of an axisymmetric model is no corner: nodes on it are never
//! singular points. A pretension section's cut is no outline (its copies of
//! nodes are read as the nodes they were copied from). Edges of a locally
//! refined mesh that a hanging node splits are inside, not outline.
//!
//! 3D meshes (edges, dihedral angles) are not searched: a 3D model has no
//! singular points.

use crate::input::case::Case;
use crate::input::mesh::Mesh;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::f64::consts::PI;

#[cfg(test)]
mod tests;

/// How far an outline must turn at a node to make a corner, degrees.
pub const TURN_DEGREES: f64 = 30.0;

/// One singular point of the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct SingularPoint {
    /// The node (of the mesh before any pretension cut).
    pub node: usize,
    /// Its place, mm (z = 0).
    pub x: [f64; 3],
    /// The bodies whose peaks it may hold (its own; both of an interface).
    pub bodies: Vec<usize>,
    /// What it is, in words: `re-entrant corner (270°)`, `end of contact
    /// interface under_head`, `edge of support boundary[0]`, `point support
    /// boundary[0]`.
    pub corner: String,
    /// The local element size: the largest diameter of the elements at it.
    pub size: f64,
    /// Every element with a node at the point (any body), in mesh order.
    pub elements: Vec<usize>,
}

/// A support as the finder reads it: its name, its nodes and which
/// components it holds (x, y, and the third: twist's rotation).
pub struct Support {
    pub name: String,
    pub nodes: Vec<usize>,
    pub held: [bool; 3],
}

/// The singular points of the model built from `case` on `mesh` (cut by
/// the pretension sections whose node copies `origin` maps back; none in
/// 3D).
pub(crate) fn of_case(case: &Case, mesh: &Mesh, origin: &[usize]) -> Vec<SingularPoint> {
    if mesh.dim() == 3 {
        return Vec::new();
    }
    let in_range = crate::model::loads::in_range;
    let supports: Vec<Support> = case
        .boundary
        .iter()
        .enumerate()
        .map(|(i, bc)| Support {
            name: format!("boundary[{i}]"),
            nodes: mesh.node_sets.get(&bc.set).map_or(Vec::new(), |set| {
                set.iter()
                    .copied()
                    .filter(|&n| {
                        let x = mesh.nodes[n];
                        in_range(x[0], &bc.x_range) && in_range(x[1], &bc.y_range)
                    })
                    .collect()
            }),
            held: [bc.ux.is_some(), bc.uy.is_some(), bc.rotation.is_some()],
        })
        .collect();
    let axisymmetric = case.model.plane == crate::physics::material::Plane::Axisymmetric;
    find(mesh, origin, axisymmetric, &supports)
}

/// The singular points of a plane mesh (module text): `origin` maps every
/// node to the one it was copied from (itself when not a copy).
pub fn find(
    mesh: &Mesh,
    origin: &[usize],
    axisymmetric: bool,
    supports: &[Support],
) -> Vec<SingularPoint> {
    let outline = Outline::of(mesh, origin);
    let held = Held::of(supports, origin);
    let tol = 1e-9 * extent(mesh).max(1e-300);
    let on_axis = |n: usize| axisymmetric && mesh.nodes[n][0].abs() <= tol;
    let turn = TURN_DEGREES.to_radians();
    // (node, bodies, what) in the order found: corners, contact ends, supports
    let mut found: Vec<(usize, Vec<usize>, String)> = Vec::new();
    for &(b, n) in outline.from.keys() {
        let Some(a) = outline.angle(mesh, b, n) else {
            continue;
        };
        if a > PI + turn && !on_axis(n) {
            found.push((
                n,
                vec![b],
                format!("re-entrant corner ({:.0}°)", a.to_degrees()),
            ));
        }
    }
    for im in &mesh.interfaces {
        let sides: [Vec<[usize; 3]>; 2] = match &im.nonmatching {
            Some(nm) => [nm.slave.clone(), nm.master.clone()],
            None => [
                im.edges.iter().map(|e| e.a).collect(),
                im.edges.iter().map(|e| e.b).collect(),
            ],
        };
        for (side, body) in sides.iter().zip([im.body_a, im.body_b]) {
            for n in chain_ends(side, origin) {
                let Some(a) = outline.angle(mesh, body, n) else {
                    continue;
                };
                if (a - PI).abs() > turn
                    && !on_axis(n)
                    && !mirrored_end(&outline, &held, body, n, a)
                {
                    let what = format!("end of contact interface {}", im.name);
                    found.push((n, vec![im.body_a, im.body_b], what));
                }
            }
        }
    }
    found.extend(support_ends(mesh, &outline, &held, &on_axis));
    gather(mesh, found, tol)
}

/// Whether a contact side ending at node `n` of body `b` (interior angle
/// `a`) ends on a mirror: the outline's other edge there is a roller or
/// symmetry line and the corner at most 90° + [`TURN_DEGREES`] (the
/// middle of a symmetric punch, not its edge).
fn mirrored_end(outline: &Outline, held: &Held, b: usize, n: usize, a: f64) -> bool {
    outline.walk(b, n).is_some_and(|(into, from)| {
        let (h_in, h_out) = (held.edge(&into), held.edge(&from));
        (mirror(h_in) || mirror(h_out)) && a <= PI / 2.0 + TURN_DEGREES.to_radians()
    })
}

/// The largest extent of the mesh's bounding box, mm.
fn extent(mesh: &Mesh) -> f64 {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for x in &mesh.nodes {
        for c in 0..2 {
            lo[c] = lo[c].min(x[c]);
            hi[c] = hi[c].max(x[c]);
        }
    }
    (hi[0] - lo[0]).max(hi[1] - lo[1])
}

/// The nodes that end a chain of edges (the ends of one edge only).
fn chain_ends(edges: &[[usize; 3]], origin: &[usize]) -> Vec<usize> {
    let mut count: BTreeMap<usize, u32> = BTreeMap::new();
    for e in edges {
        *count.entry(origin[e[0]]).or_default() += 1;
        *count.entry(origin[e[2]]).or_default() += 1;
    }
    count
        .into_iter()
        .filter(|&(_, c)| c == 1)
        .map(|(n, _)| n)
        .collect()
}

/// The components held at each node by the supports, and the first
/// support holding it.
struct Held<'a> {
    supports: &'a [Support],
    at: HashMap<usize, ([bool; 3], usize)>,
}

impl<'a> Held<'a> {
    fn of(supports: &'a [Support], origin: &[usize]) -> Held<'a> {
        let mut at: HashMap<usize, ([bool; 3], usize)> = HashMap::new();
        for (k, s) in supports.iter().enumerate() {
            for &n in &s.nodes {
                let h = at.entry(origin[n]).or_insert(([false; 3], k));
                for c in 0..3 {
                    h.0[c] |= s.held[c];
                }
            }
        }
        Held { supports, at }
    }

    fn node(&self, n: usize) -> [bool; 3] {
        self.at.get(&n).map_or([false; 3], |h| h.0)
    }

    /// The components held along an outline edge: by all three of its nodes.
    fn edge(&self, e: &[usize; 3]) -> [bool; 3] {
        let (a, m, b) = (self.node(e[0]), self.node(e[1]), self.node(e[2]));
        [0, 1, 2].map(|c| a[c] && m[c] && b[c])
    }
}

/// Whether an edge holding `h` is a mirror of the corner: one in-plane
/// component held (a roller, a symmetry line).
fn mirror(h: [bool; 3]) -> bool {
    h[0] != h[1]
}

/// Whether a change from `h_in` to `h_out` at a convex corner of interior
/// angle `a` leaves the field smooth: a mirror edge (or only the third
/// component changing) at a corner of at most 90° + [`TURN_DEGREES`]. A
/// mirror doubles the corner; a wedge of twice a right angle is a straight
/// edge.
fn smooth_change(h_in: [bool; 3], h_out: [bool; 3], a: f64) -> bool {
    let inplane_free = |h: [bool; 3]| !h[0] && !h[1];
    let mirrored = mirror(h_in) || mirror(h_out) || (inplane_free(h_in) && inplane_free(h_out));
    mirrored && a <= PI / 2.0 + TURN_DEGREES.to_radians()
}

/// The ends of every support (module text): the components held along the
/// outline change at the node (unless [`smooth_change`]), or the node is
/// held while neither edge is (a point support).
fn support_ends(
    mesh: &Mesh,
    outline: &Outline,
    held: &Held,
    on_axis: &dyn Fn(usize) -> bool,
) -> Vec<(usize, Vec<usize>, String)> {
    let mut out = Vec::new();
    for &(b, n) in outline.from.keys() {
        let Some(&(_, k)) = held.at.get(&n) else {
            continue;
        };
        let (Some((into, from)), Some(a)) = (outline.walk(b, n), outline.angle(mesh, b, n)) else {
            continue;
        };
        let (h_in, h_out) = (held.edge(&into), held.edge(&from));
        let point = h_in == [false; 3] && h_out == [false; 3];
        if on_axis(n) || (!point && (h_in == h_out || smooth_change(h_in, h_out, a))) {
            continue;
        }
        let kind = if point {
            "point support"
        } else {
            "edge of support"
        };
        out.push((n, vec![b], format!("{kind} {}", held.supports[k].name)));
    }
    out
}

/// The points found, one per place (a later find at an earlier one's place
/// adds its bodies), with their size and elements.
fn gather(mesh: &Mesh, found: Vec<(usize, Vec<usize>, String)>, tol: f64) -> Vec<SingularPoint> {
    let mut out: Vec<SingularPoint> = Vec::new();
    for (n, bodies, corner) in found {
        let x = mesh.nodes[n];
        let near = |y: [f64; 3]| (x[0] - y[0]).hypot(x[1] - y[1]) <= tol;
        if let Some(p) = out.iter_mut().find(|p| near(p.x)) {
            for b in bodies {
                if !p.bodies.contains(&b) {
                    p.bodies.push(b);
                }
            }
            continue;
        }
        let elements: Vec<usize> = (0..mesh.elements.len())
            .filter(|&e| {
                mesh.elements[e]
                    .nodes()
                    .iter()
                    .any(|&m| near(mesh.nodes[m]))
            })
            .collect();
        let size = elements
            .iter()
            .map(|&e| diameter(mesh, e))
            .fold(0.0, f64::max);
        out.push(SingularPoint {
            node: n,
            x,
            bodies,
            corner,
            size,
            elements,
        });
    }
    out
}

/// A plane element's diameter (its longer diagonal, a triangle's longest
/// side), mm.
pub fn diameter(mesh: &Mesh, e: usize) -> f64 {
    mesh.elements[e].family.diameter(&mesh.element_coords(e))
}

/// The outline of every body: the element edges no other element of the
/// body shares (nodes through `origin`), each walked with its body on the
/// left, and at each node the edges that start there.
struct Outline {
    /// (body, [end, mid, end]) of every outline edge.
    edges: Vec<(usize, [usize; 3])>,
    /// (body, node) → the outline edges starting at the node.
    from: BTreeMap<(usize, usize), Vec<usize>>,
    /// (body, node) → the outline edges ending at the node.
    into: HashMap<(usize, usize), Vec<usize>>,
}

impl Outline {
    fn of(mesh: &Mesh, origin: &[usize]) -> Outline {
        let key = |b: usize, p: usize, q: usize| (b, p.min(q), p.max(q));
        let mut count: HashMap<(usize, usize, usize), u32> = HashMap::new();
        let mut all = Vec::new();
        for el in &mesh.elements {
            for e in el.edges() {
                let e = e.map(|n| origin[n]);
                *count.entry(key(el.body, e[0], e[2])).or_default() += 1;
                all.push((el.body, e));
            }
        }
        let single = |b: usize, p: usize, q: usize| count.get(&key(b, p, q)) == Some(&1);
        // a coarse edge that a hanging node splits, and its two halves: inside
        let mut split: HashSet<(usize, usize, usize)> = HashSet::new();
        for &(b, [p, m, q]) in &all {
            if single(b, p, q) && single(b, p, m) && single(b, m, q) {
                split.extend([key(b, p, q), key(b, p, m), key(b, m, q)]);
            }
        }
        let edges: Vec<(usize, [usize; 3])> = all
            .into_iter()
            .filter(|&(b, e)| single(b, e[0], e[2]) && !split.contains(&key(b, e[0], e[2])))
            .collect();
        let mut from: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
        let mut into: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        for (i, &(b, e)) in edges.iter().enumerate() {
            from.entry((b, e[0])).or_default().push(i);
            into.entry((b, e[2])).or_default().push(i);
        }
        Outline { edges, from, into }
    }

    /// The one outline edge of body `b` ending at node `n` and the one
    /// starting there (none where the node is on no outline, or where the
    /// body touches itself at the node).
    fn walk(&self, b: usize, n: usize) -> Option<([usize; 3], [usize; 3])> {
        match (
            self.into.get(&(b, n)).map(Vec::as_slice),
            self.from.get(&(b, n)).map(Vec::as_slice),
        ) {
            (Some([i]), Some([j])) => Some((self.edges[*i].1, self.edges[*j].1)),
            _ => None,
        }
    }

    /// The interior angle of body `b`'s outline at node `n`, radians in
    /// (0, 2π): π minus the turn from the incoming edge's tangent to the
    /// outgoing one's (body on the left: a left turn is convex). None where
    /// the node is not on one simple stretch of the outline.
    fn angle(&self, mesh: &Mesh, b: usize, n: usize) -> Option<f64> {
        let (into, out) = self.walk(b, n)?;
        let p = |k: usize| mesh.xy(k);
        // dx/dξ of the quadratic edge at its end (ξ = 1) and at its start (ξ = −1)
        let (a, m, e) = (p(into[0]), p(into[1]), p(into[2]));
        let t_in = [0, 1].map(|c| 0.5 * a[c] - 2.0 * m[c] + 1.5 * e[c]);
        let (s, m, e) = (p(out[0]), p(out[1]), p(out[2]));
        let t_out = [0, 1].map(|c| -1.5 * s[c] + 2.0 * m[c] - 0.5 * e[c]);
        let cross = t_in[0] * t_out[1] - t_in[1] * t_out[0];
        let dot = t_in[0] * t_out[0] + t_in[1] * t_out[1];
        Some(PI - cross.atan2(dot))
    }
}
