//! Local refinement of a mesh of 8-node quads and 6-node triangles with
//! hanging nodes.
//!
//! A marked quad is split into four Q8 children at ξ = 0 and η = 0 of
//! its own natural coordinates; the 13 new nodes are placed by the parent's
//! isoparametric map x(ξ, η) = Σ Nₐ(ξ, η) xₐ ([`crate::physics::element::q8::shape`]), so a
//! curved edge stays on the parent's quadratic geometry:
//!
//! ```text
//!   3 ─ q ─ 6 ─ q ─ 2        ξ, η ∈ {−1, −½, 0, ½, 1}: the parent's corners
//!   │ c3    │    c2 │        and midsides stay; new are the 8 edge quarter
//!   q   i   c   i   q        points q (shared with the neighbour across the
//!   │       │       │        edge, made once per edge), the centre c and the
//!   7 ─ i ─ c ─ i ─ 5        4 interior midsides i; children c0..c3
//!   │ c0    │    c1 │        counter-clockwise from corner 0, each with its
//!   q   i   c   i   q        corners counter-clockwise from the parent's
//!   │       │       │        corner it holds.
//!   0 ─ q ─ 4 ─ q ─ 1
//! ```
//!
//! A marked triangle is split into four T6 children by its midsides (the
//! three corner triangles and the inverted centre one); its 9 new nodes (the
//! 6 edge quarter points and 3 interior midsides) are placed by its own map
//! (`split_t6`). Both families split each edge at its midside, so a quad
//! and a triangle side by side refine alike.
//!
//! Where a refined element meets an unrefined one, the coarse edge [a, m, b]
//! faces two fine edges [a, q₁, m] and [m, q₂, b]: q₁ and q₂ are **hanging
//! nodes**, tied to the coarse edge's quadratic shape (s = ∓½ on the edge),
//!
//! ```text
//!   u_q = N_a(s) u_a + N_m(s) u_m + N_b(s) u_b,
//!   N_a = s(s−1)/2, N_m = 1−s², N_b = s(s+1)/2:  (3/8, 3/4, −1/8) at s = −½
//! ```
//!
//! per dof component (`HangingNode::constraints`, the model's linear
//! constraints [`crate::model::constraint`]). The mesh stays **1-irregular**: at
//! most one level of difference across an edge ([`closure`] refines the
//! coarser neighbour of a marked element's half edge), so a hanging node's
//! masters are never hanging themselves.
//!
//! Hanging nodes are recognised from the topology alone ([`hanging_nodes`]:
//! an element edge whose two halves are edges of other elements), so a mesh
//! refined before, or read with hanging nodes, refines again the same way;
//! [`RefineState`] only carries each element's level and origin along.

mod sets;
#[cfg(test)]
mod tests;

use super::{Element, Family, Mesh, MeshError};
use crate::physics::element::family::MAX_NODES;
use std::collections::{BTreeSet, HashMap};

/// The deepest level an element may reach (4⁸ children of one element).
pub(crate) const MAX_LEVEL: u8 = 8;

/// The quadratic edge shape functions at s ∈ [−1, 1] along [a, m, b].
pub fn edge_shape(s: f64) -> [f64; 3] {
    [0.5 * s * (s - 1.0), 1.0 - s * s, 0.5 * s * (s + 1.0)]
}

/// A hanging node: `node` at s = ∓½ on the coarse edge `edge` [a, m, b]
/// (walked counter-clockwise around `element`, the coarse element).
#[derive(Clone, Debug, PartialEq)]
pub struct HangingNode {
    pub node: usize,
    pub edge: [usize; 3],
    pub s: f64,
    pub element: usize,
}

/// Each element's refinement level (0: an element of the start mesh) and
/// the start-mesh element it came from: what travels with a refined mesh
/// into its next refinement (an adaptive loop).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RefineState {
    pub level: Vec<u8>,
    pub origin: Vec<usize>,
}

impl RefineState {
    /// The start: every element at level 0, its own origin.
    pub fn new(mesh: &Mesh) -> RefineState {
        RefineState {
            level: vec![0; mesh.elements.len()],
            origin: (0..mesh.elements.len()).collect(),
        }
    }
}

/// A refined mesh, its levels and its hanging nodes.
#[derive(Clone, Debug)]
pub struct Refined {
    pub mesh: Mesh,
    pub state: RefineState,
    pub hanging: Vec<HangingNode>,
}

impl Refined {
    /// The unrefined mesh as the start of a sequence of refinements.
    pub fn start(mesh: &Mesh) -> Refined {
        Refined {
            mesh: mesh.clone(),
            state: RefineState::new(mesh),
            hanging: hanging_nodes(mesh),
        }
    }

    /// Refines this mesh again: `marked` are element ids of `self.mesh`.
    pub fn refine(&self, marked: &[usize]) -> Result<Refined, MeshError> {
        refine_with(&self.mesh, &self.state, marked, &[])
    }

    /// [`Refined::refine`] with pairs of elements that are split together
    /// (each pair's two elements face each other across an edge the
    /// refinement must keep matched, e.g. a pretension cut:
    /// [`crate::model::pretension::facing`]).
    pub(crate) fn refine_tied(
        &self,
        marked: &[usize],
        tied: &[(usize, usize)],
    ) -> Result<Refined, MeshError> {
        refine_with(&self.mesh, &self.state, marked, tied)
    }
}

/// Refines the marked elements of `mesh` (each split into four, plus the
/// closure: [`closure`]); the mesh may hold hanging nodes already.
pub fn refine(mesh: &Mesh, marked: &[usize]) -> Result<Refined, MeshError> {
    refine_with(mesh, &RefineState::new(mesh), marked, &[])
}

/// Every element split into four (no hanging node is made).
pub fn uniform(mesh: &Mesh) -> Result<Refined, MeshError> {
    let all: Vec<usize> = (0..mesh.elements.len()).collect();
    refine(mesh, &all)
}

/// Refines `levels` times the elements whose centroid (the map of ξ = η = 0)
/// lies in the box x ∈ [x₀, x₁], y ∈ [y₀, y₁] (`[mesh] refine_region`),
/// with their closure; refused: a box that holds no centroid, a mesh that
/// would grow beyond `max_elements`.
pub fn in_box(
    mesh: &Mesh,
    x: [f64; 2],
    y: [f64; 2],
    levels: usize,
    max_elements: usize,
) -> Result<Refined, MeshError> {
    let mut r = Refined::start(mesh);
    for level in 1..=levels {
        let marked: Vec<usize> = (0..r.mesh.elements.len())
            .filter(|&e| {
                let el = &r.mesh.elements[e];
                let c = map_point(el.family, &r.mesh.element_coords(e), el.family.centre_xi());
                (x[0]..=x[1]).contains(&c[0]) && (y[0]..=y[1]).contains(&c[1])
            })
            .collect();
        if marked.is_empty() {
            return Err(MeshError(format!(
                "the box x = {x:?}, y = {y:?} holds no element's centroid{}",
                if level == 1 {
                    ""
                } else {
                    " after the first level"
                }
            )));
        }
        if r.mesh.elements.len() + 3 * marked.len() > max_elements {
            return Err(MeshError(format!(
                "refine_region level {level} would make more than {max_elements} elements (the limit)"
            )));
        }
        r = r.refine(&marked)?;
    }
    Ok(r)
}

/// A corner pair as an edge key.
fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// Every element edge by its corner pair: the elements that hold it, and
/// its midside node.
struct EdgeMap {
    owner: HashMap<(usize, usize), Vec<usize>>,
    mid: HashMap<(usize, usize), usize>,
}

impl EdgeMap {
    fn new(mesh: &Mesh) -> EdgeMap {
        let mut owner: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        let mut mid = HashMap::new();
        for (e, el) in mesh.elements.iter().enumerate() {
            for [a, m, b] in el.edges() {
                let k = key(a, b);
                owner.entry(k).or_default().push(e);
                mid.insert(k, m);
            }
        }
        EdgeMap { owner, mid }
    }

    /// The two halves' midsides of [a, m, b] when both halves are edges of
    /// other elements (the edge is a hanging coarse edge).
    fn halves(&self, [a, m, b]: [usize; 3]) -> Option<[usize; 2]> {
        Some([*self.mid.get(&key(a, m))?, *self.mid.get(&key(m, b))?])
    }
}

/// The hanging nodes of a mesh, recognised from its topology: an element
/// edge [a, m, b] whose halves [a, ·, m] and [m, ·, b] are edges of other
/// elements (its midside m a corner of theirs). A 3D mesh has none (it is
/// never refined locally).
pub fn hanging_nodes(mesh: &Mesh) -> Vec<HangingNode> {
    if mesh.dim() == 3 {
        return Vec::new();
    }
    let map = EdgeMap::new(mesh);
    let mut out = Vec::new();
    for (e, el) in mesh.elements.iter().enumerate() {
        for edge in el.edges() {
            if let Some([q1, q2]) = map.halves(edge) {
                out.push(HangingNode {
                    node: q1,
                    edge,
                    s: -0.5,
                    element: e,
                });
                out.push(HangingNode {
                    node: q2,
                    edge,
                    s: 0.5,
                    element: e,
                });
            }
        }
    }
    out
}

/// The marked elements and those the closure adds, to a fixed point: the
/// coarser neighbour across a marked element's half edge (its refinement
/// would otherwise hang a second level on that edge), the facing element
/// across a matching interface edge (the coincident pairs stay pairs), and
/// the other element of a `tied` pair. Refused: an element id out of range.
pub fn closure(
    mesh: &Mesh,
    marked: &[usize],
    tied: &[(usize, usize)],
) -> Result<Vec<bool>, MeshError> {
    let n = mesh.elements.len();
    if let Some(&e) = marked
        .iter()
        .chain(tied.iter().flat_map(|(a, b)| [a, b]))
        .find(|&&e| e >= n)
    {
        return Err(MeshError(format!(
            "refinement: element {e} is marked or tied but the mesh has {n} elements"
        )));
    }
    let map = EdgeMap::new(mesh);
    // the coarse element of each half edge
    let mut coarser: HashMap<(usize, usize), usize> = HashMap::new();
    for h in hanging_nodes(mesh) {
        let [a, m, b] = h.edge;
        coarser.insert(key(a, m), h.element);
        coarser.insert(key(m, b), h.element);
    }
    let mut facing: HashMap<usize, Vec<usize>> = HashMap::new();
    let one = |edge: &[usize; 3]| {
        map.owner
            .get(&key(edge[0], edge[2]))
            .and_then(|o| o.first().copied())
    };
    for iface in &mesh.interfaces {
        for ce in &iface.edges {
            if let (Some(ea), Some(eb)) = (one(&ce.a), one(&ce.b)) {
                facing.entry(ea).or_default().push(eb);
                facing.entry(eb).or_default().push(ea);
            }
        }
    }
    for &(a, b) in tied {
        facing.entry(a).or_default().push(b);
        facing.entry(b).or_default().push(a);
    }
    let mut on = vec![false; n];
    let mut work: Vec<usize> = marked.to_vec();
    while let Some(e) = work.pop() {
        if std::mem::replace(&mut on[e], true) {
            continue;
        }
        let el = &mesh.elements[e];
        for [a, _, b] in el.edges() {
            if let Some(&c) = coarser.get(&key(a, b)) {
                work.push(c);
            }
        }
        work.extend(facing.get(&e).into_iter().flatten().copied());
    }
    Ok(on)
}

/// The point at natural ξ of an element of `family` with nodes at `c`.
fn map_point(family: Family, c: &[[f64; 2]; MAX_NODES], xi: [f64; 2]) -> [f64; 2] {
    let n = family.shape(xi);
    (0..family.nodes()).fold([0.0, 0.0], |p, a| {
        [p[0] + n[a] * c[a][0], p[1] + n[a] * c[a][1]]
    })
}

/// The new nodes of a refinement: the quarter points of every split edge
/// (by corner pair: [near the smaller id, near the larger]).
pub(crate) struct Quarters {
    pub(crate) of: HashMap<(usize, usize), [usize; 2]>,
    /// The corner pairs of the edges of refined elements.
    pub(crate) split: BTreeSet<(usize, usize)>,
}

impl Quarters {
    /// The two quarter points of [a, m, b] in walk order (near a, near b),
    /// when the edge was split.
    pub(crate) fn along(&self, [a, _, b]: [usize; 3]) -> Option<[usize; 2]> {
        let k = key(a, b);
        if !self.split.contains(&k) {
            return None;
        }
        let q = self.of.get(&k)?;
        Some(if a < b { *q } else { [q[1], q[0]] })
    }
}

/// [`refine`] of a mesh whose elements carry `state` (levels, origins);
/// the two elements of a `tied` pair are split together ([`closure`]).
pub(crate) fn refine_with(
    mesh: &Mesh,
    state: &RefineState,
    marked: &[usize],
    tied: &[(usize, usize)],
) -> Result<Refined, MeshError> {
    let n = mesh.elements.len();
    if state.level.len() != n || state.origin.len() != n {
        return Err(MeshError(format!(
            "refinement: the state has {} levels for {n} elements (a state of another mesh)",
            state.level.len()
        )));
    }
    if let Some(el) = mesh.elements.iter().find(|el| el.family.dim() == 3) {
        return Err(MeshError(format!(
            "local refinement of a 3D mesh ({}) is not available: refine it uniformly (--refine)",
            el.family.name()
        )));
    }
    let on = closure(mesh, marked, tied)?;
    if let Some(e) = (0..n).find(|&e| on[e] && state.level[e] >= MAX_LEVEL) {
        return Err(MeshError(format!(
            "refinement: element {e} is at level {MAX_LEVEL}, the deepest"
        )));
    }
    let mut out = mesh.clone();
    out.elements.clear();
    out.source = None;
    let mut next = RefineState::default();
    // the existing hanging nodes are the quarter points of their coarse edge
    let mut quarters = Quarters {
        of: HashMap::new(),
        split: BTreeSet::new(),
    };
    for h in hanging_nodes(mesh) {
        let [a, _, b] = h.edge;
        let near_a = h.s < 0.0;
        let q = quarters.of.entry(key(a, b)).or_insert([usize::MAX; 2]);
        q[usize::from(near_a != (a < b))] = h.node;
    }
    let mut interior: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (e, el) in mesh.elements.iter().enumerate() {
        if !on[e] {
            out.elements.push(el.clone());
            next.level.push(state.level[e]);
            next.origin.push(state.origin[e]);
            continue;
        }
        let c = mesh.element_coords(e);
        let (children, inner) = match el.family {
            Family::Q8 => split(&mut out, &mut quarters, el, &c),
            Family::T6 => split_t6(&mut out, &mut quarters, el, &c),
            Family::H20 | Family::T10 => unreachable!("refused above"),
        };
        interior[e] = inner;
        for c in children {
            out.elements.push(c);
            next.level.push(state.level[e] + 1);
            next.origin.push(state.origin[e]);
        }
    }
    sets::carry(mesh, &mut out, &quarters, &on, &interior)?;
    let hanging = hanging_nodes(&out);
    Ok(Refined {
        mesh: out,
        state: next,
        hanging,
    })
}

/// Splits one element of `out` (its coordinates `c`) into four children;
/// also the new nodes inside it (centre, interior midsides).
fn split(
    out: &mut Mesh,
    quarters: &mut Quarters,
    el: &Element,
    c: &[[f64; 2]; MAX_NODES],
) -> ([Element; 4], Vec<usize>) {
    // the 5 × 5 grid of natural points ξ = i/2 − 1, η = j/2 − 1
    let mut grid = [[usize::MAX; 5]; 5];
    for (loc, &(i, j)) in [
        (0, 0),
        (4, 0),
        (4, 4),
        (0, 4),
        (2, 0),
        (4, 2),
        (2, 4),
        (0, 2),
    ]
    .iter()
    .enumerate()
    {
        grid[i][j] = el.nodes()[loc];
    }
    let point =
        |i: usize, j: usize| map_point(Family::Q8, c, [i as f64 / 2.0 - 1.0, j as f64 / 2.0 - 1.0]);
    let add = |out: &mut Mesh, [x, y]: [f64; 2]| {
        out.nodes.push([x, y, 0.0]);
        out.nodes.len() - 1
    };
    // the edge quarter points, [near the edge's start, near its end]
    let edge_points: [[(usize, usize); 2]; 4] = [
        [(1, 0), (3, 0)],
        [(4, 1), (4, 3)],
        [(3, 4), (1, 4)],
        [(0, 3), (0, 1)],
    ];
    for (k, [na, _, nb]) in el.edges().enumerate() {
        let kk = key(na, nb);
        quarters.split.insert(kk);
        let [pa, pb] = edge_points[k];
        let q = quarters.of.entry(kk).or_insert([usize::MAX; 2]);
        // [near the smaller id, near the larger]
        let slots = if na < nb { [pa, pb] } else { [pb, pa] };
        for (s, (i, j)) in slots.into_iter().enumerate() {
            if q[s] == usize::MAX {
                q[s] = add(out, point(i, j));
            }
            grid[i][j] = q[s];
        }
    }
    let mut inner = Vec::new();
    for (i, j) in [(2, 2), (2, 1), (3, 2), (2, 3), (1, 2)] {
        grid[i][j] = add(out, point(i, j));
        inner.push(grid[i][j]);
    }
    let child = |i0: usize, j0: usize| {
        let g = |di: usize, dj: usize| grid[i0 + di][j0 + dj];
        let nodes = [
            g(0, 0),
            g(2, 0),
            g(2, 2),
            g(0, 2),
            g(1, 0),
            g(2, 1),
            g(1, 2),
            g(0, 1),
        ];
        Element::q8(nodes, el.body)
    };
    ([child(0, 0), child(2, 0), child(2, 2), child(0, 2)], inner)
}

/// Splits one triangle of `out` (its coordinates `c`) into four T6
/// children (module text); also its 3 new interior nodes. The children, in
/// natural coordinates of the parent:
/// ```text
///   2                 c0 = (0, 3, 5), c1 = (3, 1, 4), c2 = (5, 4, 2),
///   │ ╲               c3 = (4, 5, 3) the centre; each child's midsides
///   5 ─ 4             are quarter points of the parent's edges or the
///   │ ╲ │ ╲           midpoints of the inner triangle's sides
///   0 ─ 3 ─ 1         (¼, ¼), (½, ¼), (¼, ½)
/// ```
fn split_t6(
    out: &mut Mesh,
    quarters: &mut Quarters,
    el: &Element,
    c: &[[f64; 2]; MAX_NODES],
) -> ([Element; 4], Vec<usize>) {
    let point = |xi: [f64; 2]| map_point(Family::T6, c, xi);
    let add = |out: &mut Mesh, [x, y]: [f64; 2]| {
        out.nodes.push([x, y, 0.0]);
        out.nodes.len() - 1
    };
    // each edge's quarter points in walk order (near its start, near its end)
    let along: [[[f64; 2]; 2]; 3] = [
        [[0.25, 0.0], [0.75, 0.0]],
        [[0.75, 0.25], [0.25, 0.75]],
        [[0.0, 0.75], [0.0, 0.25]],
    ];
    let mut q = [[usize::MAX; 2]; 3];
    for (k, [na, _, nb]) in el.edges().enumerate() {
        let kk = key(na, nb);
        quarters.split.insert(kk);
        let slot = quarters.of.entry(kk).or_insert([usize::MAX; 2]);
        // slot 0 is near the smaller id
        let walk = if na < nb { [0, 1] } else { [1, 0] };
        for (s, w) in walk.into_iter().enumerate() {
            if slot[s] == usize::MAX {
                slot[s] = add(out, point(along[k][w]));
            }
            q[k][w] = slot[s];
        }
    }
    let inner: Vec<usize> = [[0.25, 0.25], [0.5, 0.25], [0.25, 0.5]]
        .into_iter()
        .map(|xi| add(out, point(xi)))
        .collect();
    let [i35, i34, i45] = [inner[0], inner[1], inner[2]];
    let n = el.nodes();
    let children = [
        [n[0], n[3], n[5], q[0][0], i35, q[2][1]],
        [n[3], n[1], n[4], q[0][1], q[1][0], i34],
        [n[5], n[4], n[2], i45, q[1][1], q[2][0]],
        [n[4], n[5], n[3], i45, i35, i34],
    ]
    .map(|nodes| Element::t6(nodes, el.body));
    (children, inner)
}
