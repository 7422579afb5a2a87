//! The rough interface between body A (upper, "punch", or left) and body B
//! (lower, "foundation", or right): spring pairs, their quadrature along the contact edges, and the
//! per-point residual and tangent (paper sections 2.1, 2.3 and 3.29-3.31).
//!
//! ```text
//!        A:  a0 ──── a1 ──── a2        one contact edge = three node pairs
//!            ┆        ┆        ┆       (a_i, b_i) at the same position;
//!        B:  b0 ──── b1 ──── b2        springs act along the normal n (B → A)
//! ```
//!
//! The interface energy is Π = t ∫ φ(u_N(s)) ds with φ' = p_N. Two quadratures of
//! that integral give the paper's two contact matrices:
//! * lumped: the nodes themselves, weights L/6, 2L/3, L/6 (row sums of eq. 3.29,
//!   the matrix (A/30) diag(5, 20, 5) of eq. 3.31): one independent spring per pair;
//! * consistent: 4-point Gauss along the edge with u_N interpolated quadratically;
//!   for a linear law this is exactly (k A/30)[4 2 −1; 2 16 2; −1 2 4] (eq. 3.29).
//!
//! A non-matching interface (`matching = false`, issue 19) has the same
//! quadrature points on the slave side (body A), each projected once onto
//! the closest quadratic edge of the master side (body B) and coupled to
//! its three nodes through the edge's shape functions N(ξ) (node-to-segment,
//! small sliding: docs/theory.md, "Non-matching interfaces"); see [`Segment`].
//! In a 3D model the same springs stand on faces: each slave point projected
//! once onto the closest 8-node quadrilateral or 6-node triangle of the
//! master side (node-to-surface, `surface.rs`).

pub mod arcs;
mod circumferential;
pub mod extrapolation;
mod faces;
mod segment;
mod surface;

use crate::input::case::settings::{FrictionScheme, Weights};
use crate::input::mesh::{Interface, Mesh};
use crate::numbers::vec3::cross;
use crate::physics::contact::{NormalLaw, PointState, Slip, Status, TangentialLaw};
pub(crate) use circumferential::Gradients;
pub(crate) use faces::tangents;
pub use segment::{project, OVERLAP_LIMIT};

/// The most nodes of one side of an interface element: a quadratic edge's
/// three, a 6-node triangle's or an 8-node quadrilateral's face.
pub const MAX_SIDE: usize = 8;

/// A node pair across the interface.
#[derive(Clone, Debug)]
pub struct Pair {
    pub a: usize,
    pub b: usize,
    /// Position (z = 0 in a plane or axisymmetric model), mm.
    pub x: [f64; 3],
    /// Unit normal from B into A (z component 0 in 2D).
    pub normal: [f64; 3],
    /// Tributary (lumped) area, mm².
    pub area: f64,
    /// On a non-matching interface: the spring point this row stands for
    /// (one pair per point, `a` the nearest slave node, `b` the nearest
    /// master node, `x` the slave point); `None` for a coincident pair.
    pub spring: Option<usize>,
}

/// Node-to-segment coupling of a spring point of a non-matching interface
/// (see the module comment): the slave point x_A = Σ N_i^A x_{a_i} on body
/// A's side and its closest point x_B(ξ) = Σ N_j(ξ) x_{b_j} on a quadratic
/// edge of body B, ξ fixed at the start (small sliding).
#[derive(Clone, Copy, Debug)]
pub struct Segment {
    /// Slave nodes and their shape values (first `len_a` used).
    pub a: [usize; MAX_SIDE],
    pub na: [f64; MAX_SIDE],
    pub(crate) len_a: usize,
    /// The master side's nodes (an edge's three, a face's six or eight) and
    /// its shape functions N(ξ) at the projection (first `len_b` used).
    pub b: [usize; MAX_SIDE],
    pub nb: [f64; MAX_SIDE],
    pub(crate) len_b: usize,
    /// Geometric initial gap (x_A − x_B(ξ))·n, mm (0 on a straight common
    /// line); the interface's `gap` adds to it.
    pub gap: f64,
    /// Arc length of the slave point along the slave side, mm.
    pub s: f64,
}

/// A spring of a mortar (segment-to-segment) non-matching interface
/// (`weights = "mortar"`): at slave node i, with A_i = ∫ N_i dA over the
/// slave edges around it,
/// u_N = (1/A_i) ∫ N_i [(u_B(ξ(s)) − u_A(s))·n(s) − g₀(s)] dA − gap and
/// u_T = (1/A_i) ∫ N_i (u_B(ξ(s)) − u_A(s))·t(s) dA, integrated by 4-point
/// Gauss on each piece of a slave edge between the projections of the
/// master side's corner nodes (so the integrand is smooth on each piece);
/// ξ(s) is the closest point of the master side, fixed at the start (small
/// sliding). Both are linear in the displacements: u_N = Σ_j dn_j·u_j − g₀
/// − gap over the nodes the integral touches. Energy Π = Σ_i A_i φ(u_N,i),
/// so the tangent stays symmetric without friction. A uniform pressure
/// crosses exactly whatever the two sides' divisions (the master's nodal
/// forces p ∫ N_k^B dA are integrated exactly on each piece).
#[derive(Clone, Debug)]
pub struct Mortar {
    /// Nodes whose displacements enter u_N and u_T (slave, then master).
    pub nodes: Vec<usize>,
    /// ∂u_N/∂u_node and ∂u_T/∂u_node, (x, y) per node.
    pub(crate) dn: Vec<[f64; 2]>,
    pub dt: Vec<[f64; 2]>,
    /// ∂u_Tθ/∂u_θ,node (a model with twist): (1/A_i) ∫ N_i (±N_node) dA,
    /// − on the slave side, + on the master side.
    pub dh: Vec<f64>,
    /// Weighted geometric initial gap, mm; the interface's `gap` adds to it.
    pub gap: f64,
    /// Arc length of the slave node along the slave side, mm.
    pub s: f64,
    /// (1/A_i) ∫ N_i x dA, mm: the slave side's x (r in axisymmetry)
    /// averaged with the node's weight function, the arm about the axis of
    /// the spring's force on the slave nodes (Σ_j x_j ∂u_Tθ/∂u_θj over them,
    /// with the sign reversed), which is not the node's own x.
    pub radius: f64,
}

/// An integration point of the interface energy.
#[derive(Clone, Debug)]
pub struct Point {
    /// Integration weight: area represented, mm².
    pub area: f64,
    /// Unit normal from B into A (z component 0 in 2D).
    pub normal: [f64; 3],
    /// The first unit tangent t₁ of the slip: in 2D (n_y, −n_x, 0); in 3D a
    /// direction of the face's tangent plane, the second t₂ = n × t₁
    /// ([`Point::binormal`]).
    pub tangent: [f64; 3],
    /// How the point couples the two sides' nodes.
    pub coupling: Coupling,
}

/// How a point couples the two sides: coincident pairs of a matching
/// interface, or a spring of a non-matching one (node-to-segment or mortar),
/// each with what it needs and nothing else.
#[derive(Clone, Debug)]
pub enum Coupling {
    /// A matching interface: the point interpolates its pairs (the first
    /// `len` of `pairs`, indices into [`InterfaceModel::pairs`]) by the
    /// edge's shape values.
    Coincident {
        pairs: [usize; MAX_SIDE],
        shape: [f64; MAX_SIDE],
        len: usize,
    },
    /// A non-matching interface's node-to-segment spring; `pair` is its row
    /// in [`InterfaceModel::pairs`] (whose `spring` names this point).
    NodeToSegment { pair: usize, segment: Segment },
    /// A mortar spring (`weights = "mortar"`); `pair` as for node-to-segment.
    Mortar {
        pair: usize,
        mortar: std::sync::Arc<Mortar>,
    },
}

impl Coupling {
    /// The pairs the point stands on, with their weights: a coincident
    /// point's pairs and shape values, a spring's own row with weight 1.
    pub fn pairs(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        let (pairs, shape): (&[usize], &[f64]) = match self {
            Coupling::Coincident { pairs, shape, len } => (&pairs[..*len], &shape[..*len]),
            Coupling::NodeToSegment { pair, .. } | Coupling::Mortar { pair, .. } => {
                (std::slice::from_ref(pair), &[1.0])
            }
        };
        pairs.iter().copied().zip(shape.iter().copied())
    }

    /// The point's first pair (a spring's own row): where a partition places it.
    #[cfg(feature = "parallel")]
    pub(crate) fn first_pair(&self) -> usize {
        match self {
            Coupling::Coincident { pairs, .. } => pairs[0],
            Coupling::NodeToSegment { pair, .. } | Coupling::Mortar { pair, .. } => *pair,
        }
    }

    /// Is the point a spring of a mortar interface?
    pub fn is_mortar(&self) -> bool {
        matches!(self, Coupling::Mortar { .. })
    }
}

impl Point {
    /// On a non-matching interface: the geometric initial gap of the spring
    /// (node-to-segment or mortar), mm; `None` on coincident pairs.
    pub fn geometric_gap(&self) -> Option<f64> {
        match &self.coupling {
            Coupling::Coincident { .. } => None,
            Coupling::NodeToSegment { segment, .. } => Some(segment.gap),
            Coupling::Mortar { mortar, .. } => Some(mortar.gap),
        }
    }

    /// On a non-matching interface: the spring's arc length along the slave
    /// side, mm; `None` on coincident pairs.
    pub(crate) fn slave_arc(&self) -> Option<f64> {
        match &self.coupling {
            Coupling::Coincident { .. } => None,
            Coupling::NodeToSegment { segment, .. } => Some(segment.s),
            Coupling::Mortar { mortar, .. } => Some(mortar.s),
        }
    }

    /// Number of nodes the point couples: 2·len for coincident pairs (A's,
    /// then B's), the slave and master nodes of a node-to-segment (or
    /// node-to-surface) spring, the nodes of a mortar spring.
    pub fn node_count(&self) -> usize {
        match &self.coupling {
            Coupling::Coincident { len, .. } => 2 * len,
            Coupling::NodeToSegment { segment: g, .. } => g.len_a + g.len_b,
            Coupling::Mortar { mortar: m, .. } => m.nodes.len(),
        }
    }

    /// Number of in-plane local dofs, two per node
    /// ([`Point::node_count`]); `InterfaceModel::point_ndofs` counts every
    /// dof of the nodes.
    pub fn ndofs(&self) -> usize {
        2 * self.node_count()
    }

    /// The second unit tangent of a 3D point, t₂ = n × t₁.
    pub fn binormal(&self) -> [f64; 3] {
        cross(self.normal, self.tangent)
    }

    /// The derivatives of the relative approach u_N and slip u_T (eq. 3.29-3.31:
    /// B's minus A's displacement, interpolated by the edge's shape
    /// functions, along the normal and the tangent t = (n_y, −n_x)) with
    /// respect to the point's local dofs (A pairs (x, y), then B pairs); the
    /// first 4·len entries of each are used.
    pub(crate) fn gradients(&self) -> (Vec<f64>, Vec<f64>) {
        let t = self.tangent;
        let zeros = || (vec![0.0f64; self.ndofs()], vec![0.0f64; self.ndofs()]);
        match &self.coupling {
            Coupling::Mortar { mortar: m, .. } => {
                let flat = |d: &[[f64; 2]]| d.iter().flat_map(|v| *v).collect::<Vec<f64>>();
                (flat(&m.dn), flat(&m.dt))
            }
            Coupling::NodeToSegment { segment: g, .. } => {
                let (mut gn, mut gt) = zeros();
                let m = g.len_a;
                for c in 0..2 {
                    for i in 0..m {
                        gn[2 * i + c] = -g.na[i] * self.normal[c];
                        gt[2 * i + c] = -g.na[i] * t[c];
                    }
                    for j in 0..g.len_b {
                        gn[2 * m + 2 * j + c] = g.nb[j] * self.normal[c];
                        gt[2 * m + 2 * j + c] = g.nb[j] * t[c];
                    }
                }
                (gn, gt)
            }
            Coupling::Coincident { shape, len, .. } => {
                let (mut gn, mut gt) = zeros();
                let n = *len;
                for (i, &s) in shape.iter().enumerate().take(n) {
                    for c in 0..2 {
                        gn[2 * i + c] = -s * self.normal[c];
                        gn[2 * n + 2 * i + c] = s * self.normal[c];
                        gt[2 * i + c] = -s * t[c];
                        gt[2 * n + 2 * i + c] = s * t[c];
                    }
                }
                (gn, gt)
            }
        }
    }
}

/// One interface of the model, ready to evaluate.
#[derive(Clone, Debug)]
pub struct InterfaceModel {
    pub name: String,
    pub body_a: usize,
    pub body_b: usize,
    pub law: NormalLaw,
    /// Initial gap g₀, mm (positive = open): the gap at every pseudo-time
    /// without a gap history ([`InterfaceModel::gap_at`]).
    pub gap: f64,
    /// The gap at pseudo-time t is g₀ · h(t) (set by the model after `new`).
    pub gap_history: Option<crate::model::history::History>,
    pub pairs: Vec<Pair>,
    pub points: Vec<Point>,
    /// Secant-start reference pressure (MPa) if given in the case.
    pub(crate) start_pressure: Option<f64>,
    pub tangential: Option<TangentialLaw>,
    pub scheme: FrictionScheme,
    /// The mesh's dofs per node: a point's local dofs are the in-plane
    /// (x, y) ones of its nodes, at these global dofs.
    pub node_dofs: crate::input::mesh::NodeDofs,
    /// In 3D: the point the joint's moment is taken about
    /// (`[interface.<name>] moment_point`, by default the interface's
    /// centroid, set by [`InterfaceModel::new`]); the origin in 2D.
    pub moment_point: [f64; 3],
}

/// Result of evaluating one point.
pub struct PointEval {
    pub u_n: f64,
    pub p_n: f64,
    pub status: Status,
    /// Trial tangential state.
    pub state: PointState,
    /// Area times ∂p_T/∂u_N: the coefficient of the point's unsymmetric
    /// tangent term `coupling · g_T g_Nᵀ` (0 without it; see
    /// `InterfaceModel::eval_point_parts`). With twist the coefficient of
    /// g_T1 in the vector form `(coupling g_T1 + coupling_hoop g_θ) g_Nᵀ`.
    pub coupling: f64,
    /// With twist: area times ∂p_Tθ/∂u_N, the coefficient of g_θ in the
    /// point's unsymmetric term (0 without twist).
    pub(crate) coupling_hoop: f64,
}

impl InterfaceModel {
    /// Builds pairs and points from a mesh interface. Each quadrature point's
    /// area is its weight along the edge times `section.measure(x)`: the
    /// thickness, or 2π r of the full revolution in axisymmetry (r at the node
    /// for lumped weights, at the Gauss point for consistent ones).
    #[allow(clippy::too_many_arguments)] // the case's interface settings, each used once here
    pub fn new(
        mesh: &Mesh,
        iface: &Interface,
        law: NormalLaw,
        gap: f64,
        weights: Weights,
        section: crate::physics::element::Section,
        start_pressure: Option<f64>,
        tangential: Option<(TangentialLaw, FrictionScheme)>,
    ) -> Result<Self, String> {
        let (pairs, points) = match &iface.nonmatching {
            _ if iface.on_faces() => on_faces(mesh, iface, weights)?,
            None if weights == Weights::Mortar => {
                return Err(format!(
                    "interface \"{}\": weights = \"mortar\" couples two sides meshed apart; it needs matching = false",
                    iface.name
                ))
            }
            None => Self::coincident(mesh, iface, weights, section),
            Some(nm) if weights == Weights::Mortar => {
                segment::mortar(mesh, &iface.name, nm, section)?
            }
            Some(nm) => segment::node_to_segment(mesh, &iface.name, nm, weights, section)?,
        };
        let mut im = InterfaceModel {
            name: iface.name.clone(),
            body_a: iface.body_a,
            body_b: iface.body_b,
            law,
            gap,
            gap_history: None,
            pairs,
            points,
            start_pressure,
            scheme: tangential.as_ref().map(|t| t.1).unwrap_or_default(),
            tangential: tangential.map(|t| t.0),
            node_dofs: mesh.node_dofs,
            moment_point: [0.0; 3],
        };
        if im.node_dofs.solid() {
            im.moment_point = im.centroid();
        }
        Ok(im)
    }

    /// The pairs and points of a matching interface (coincident node pairs).
    fn coincident(
        mesh: &Mesh,
        iface: &Interface,
        weights: Weights,
        section: crate::physics::element::Section,
    ) -> (Vec<Pair>, Vec<Point>) {
        let mut pairs: Vec<Pair> = Vec::new();
        let mut index = std::collections::HashMap::new();
        let mut edge_pairs = Vec::with_capacity(iface.edges.len());
        for edge in &iface.edges {
            let mut ids = [0usize; MAX_SIDE];
            for (i, id) in ids.iter_mut().take(3).enumerate() {
                let key = (edge.a[i], edge.b[i]);
                *id = *index.entry(key).or_insert_with(|| {
                    pairs.push(Pair {
                        a: edge.a[i],
                        b: edge.b[i],
                        x: mesh.nodes[edge.b[i]],
                        normal: [0.0; 3],
                        area: 0.0,
                        spring: None,
                    });
                    pairs.len() - 1
                });
            }
            edge_pairs.push(ids);
        }
        let mut points = Vec::new();
        for (edge, ids) in iface.edges.iter().zip(&edge_pairs) {
            let xb = [mesh.xy(edge.b[0]), mesh.xy(edge.b[1]), mesh.xy(edge.b[2])];
            // lumped weights and averaged nodal normals
            for (i, &s) in [-1.0, 0.0, 1.0].iter().enumerate() {
                let (n, ds) = edge_normal(&xb, s);
                let w = [1.0 / 3.0, 4.0 / 3.0, 1.0 / 3.0][i] * ds * section.measure(xb[i]);
                // the normal is averaged along the edge alone (2π r is 0 on the axis)
                let wn = if section.axisymmetric {
                    [1.0 / 3.0, 4.0 / 3.0, 1.0 / 3.0][i] * ds
                } else {
                    w
                };
                let pr = &mut pairs[ids[i]];
                pr.area += w;
                pr.normal[0] += wn * n[0];
                pr.normal[1] += wn * n[1];
            }
            if weights == Weights::Consistent {
                for (s, wg) in gauss4() {
                    let (n, ds) = edge_normal(&xb, s);
                    let shape = crate::physics::element::edge::shape(s);
                    let x = [0, 1].map(|c| (0..3).map(|k| shape[k] * xb[k][c]).sum::<f64>());
                    points.push(Point {
                        area: wg * ds * section.measure(x),
                        normal: [n[0], n[1], 0.0],
                        tangent: [n[1], -n[0], 0.0],
                        coupling: Coupling::Coincident {
                            pairs: *ids,
                            shape: side(&shape),
                            len: 3,
                        },
                    });
                }
            }
        }
        for p in &mut pairs {
            let l = p.normal[0].hypot(p.normal[1]);
            p.normal = [p.normal[0] / l, p.normal[1] / l, 0.0];
        }
        if weights == Weights::Lumped {
            points = lumped_points(&pairs, |n| [n[1], -n[0], 0.0]);
        }
        (pairs, points)
    }

    /// Whether each pair can carry force: some integration point of positive
    /// area couples it with a non-zero weight. A pair whose every point has
    /// no area (the pair on the axis of an axisymmetric model under lumped
    /// weights, where the measure 2π r is 0) transmits nothing, whatever its
    /// approach; the contact stabilization does not count it as support.
    pub(crate) fn carrying_pairs(&self) -> Vec<bool> {
        let mut carries = vec![false; self.pairs.len()];
        for pt in self.points.iter().filter(|pt| pt.area > 0.0) {
            for (pair, w) in pt.coupling.pairs() {
                if w != 0.0 {
                    carries[pair] = true;
                }
            }
        }
        carries
    }

    /// Total nominal area of the interface, mm².
    pub fn area(&self) -> f64 {
        self.pairs.iter().map(|p| p.area).sum()
    }

    /// The gap at pseudo-time t, mm: g₀, or g₀ · h(t) with a gap history.
    pub fn gap_at(&self, t: f64) -> f64 {
        match &self.gap_history {
            None => self.gap,
            Some(h) => self.gap * h.value(t),
        }
    }

    /// Approach at a pair (nodal value): u_N = (u_B − u_A)·n − g₀, with the
    /// initial gap g₀ ([`InterfaceModel::pair_approach_at`] takes the gap at t).
    pub fn pair_approach(&self, pair: &Pair, u: &[f64]) -> f64 {
        self.pair_approach_at(pair, u, self.gap)
    }

    /// Approach at a pair across the given gap: u_N = (u_B − u_A)·n − gap.
    /// On a non-matching interface, the approach of the pair's spring point.
    pub fn pair_approach_at(&self, pair: &Pair, u: &[f64], gap: f64) -> f64 {
        if let Some(j) = pair.spring {
            return self.point_kinematics_at(&self.points[j], u, gap).0;
        }
        let (n, nd) = (pair.normal, self.node_dofs);
        let du = |c: usize| u[nd.dof(pair.b, c)] - u[nd.dof(pair.a, c)];
        (0..self.dim()).map(|c| du(c) * n[c]).sum::<f64>() - gap
    }

    /// Normal approach and tangential displacement at a point, interpolated from
    /// its pairs; t = (n_y, −n_x); across the initial gap g₀.
    pub fn point_kinematics(&self, pt: &Point, u: &[f64]) -> (f64, f64) {
        self.point_kinematics_at(pt, u, self.gap)
    }

    /// [`InterfaceModel::point_kinematics`] across the given gap.
    /// On a non-matching interface u_N = (u_B(ξ) − u_A)·n − g₀(point) − gap
    /// and u_T = (u_B(ξ) − u_A)·t, u_B(ξ) = Σ N_j(ξ) u_{b_j} on the master
    /// edge and u_A = Σ N_i^A u_{a_i} at the slave point.
    pub fn point_kinematics_at(&self, pt: &Point, u: &[f64], gap: f64) -> (f64, f64) {
        if self.node_dofs.solid() {
            let [u_n, u_t, _] = self.point_kinematics_3d(pt, u, gap);
            return (u_n, u_t);
        }
        let nd = self.node_dofs;
        let (n, t) = (pt.normal, pt.tangent);
        match &pt.coupling {
            Coupling::Mortar { mortar: m, .. } => {
                let (mut un, mut ut) = (-m.gap - gap, 0.0);
                for (j, &node) in m.nodes.iter().enumerate() {
                    let u_j = [u[nd.dof(node, 0)], u[nd.dof(node, 1)]];
                    un += m.dn[j][0] * u_j[0] + m.dn[j][1] * u_j[1];
                    ut += m.dt[j][0] * u_j[0] + m.dt[j][1] * u_j[1];
                }
                (un, ut)
            }
            Coupling::NodeToSegment { segment: g, .. } => {
                let mut du = [0.0f64; 2];
                for c in 0..2 {
                    for j in 0..g.len_b {
                        du[c] += g.nb[j] * u[nd.dof(g.b[j], c)];
                    }
                    for i in 0..g.len_a {
                        du[c] -= g.na[i] * u[nd.dof(g.a[i], c)];
                    }
                }
                let un = du[0] * n[0] + du[1] * n[1] - g.gap - gap;
                (un, du[0] * t[0] + du[1] * t[1])
            }
            Coupling::Coincident { pairs, shape, len } => {
                let (mut un, mut ut) = (-gap, 0.0);
                for i in 0..*len {
                    let pr = &self.pairs[pairs[i]];
                    let du = [
                        u[nd.dof(pr.b, 0)] - u[nd.dof(pr.a, 0)],
                        u[nd.dof(pr.b, 1)] - u[nd.dof(pr.a, 1)],
                    ];
                    un += shape[i] * (du[0] * n[0] + du[1] * n[1]);
                    ut += shape[i] * (du[0] * t[0] + du[1] * t[1]);
                }
                (un, ut)
            }
        }
    }

    /// The dofs of a point in local order: A pairs (x, y) then B pairs (x, y);
    /// on a non-matching interface the slave nodes, then the master edge's
    /// (`InterfaceModel::point_nodes`). With twist each node's (r, z, θ).
    pub fn point_dofs(&self, pt: &Point) -> Vec<usize> {
        let nd = self.node_dofs;
        let nodes = self.point_nodes(pt);
        nodes.into_iter().flat_map(|n| nd.of(n)).collect()
    }

    /// Whether this interface's spring tangents are symmetric: without a
    /// tangential law, or under the stiffness-modification scheme, whose
    /// tangent has no ∂p_T/∂u_N term (see [`InterfaceModel::eval_point`]).
    pub fn symmetric_tangent(&self) -> bool {
        self.tangential.is_none() || self.scheme == FrictionScheme::StiffnessModification
    }

    /// Evaluates a point from its committed state: local residual `r` (len 4·len)
    /// and, if given, the local tangent `k` (row-major (4·len)²). `k_floor`
    /// replaces the normal stiffness of a point at or below zero approach (the
    /// secant start of eq. 2.8-2.9). Across the initial gap g₀; the solver
    /// calls `InterfaceModel::eval_point_at` with the gap at its pseudo-time.
    pub fn eval_point(
        &self,
        pt: &Point,
        u: &[f64],
        committed: &PointState,
        k_floor: Option<f64>,
        r: &mut [f64],
        k: Option<&mut [f64]>,
    ) -> PointEval {
        self.eval_point_at(pt, u, self.gap, committed, k_floor, r, k)
    }

    /// [`InterfaceModel::eval_point`] across the given gap.
    #[allow(clippy::too_many_arguments)] // eval_point's arguments and the gap
    pub(crate) fn eval_point_at(
        &self,
        pt: &Point,
        u: &[f64],
        gap: f64,
        committed: &PointState,
        k_floor: Option<f64>,
        r: &mut [f64],
        k: Option<&mut [f64]>,
    ) -> PointEval {
        self.eval_point_parts(pt, u, gap, committed, k_floor, r, k, true)
    }

    /// [`InterfaceModel::eval_point_at`], with or without the unsymmetric
    /// part of the tangent in `k`. Without it (`with_coupling` false), `k`
    /// receives only the symmetric part `a (k_N g_N g_Nᵀ + ∂p_T/∂u_T g_T g_Tᵀ)`,
    /// and the rest `a ∂p_T/∂u_N g_T g_Nᵀ` (the return mapping's dependence of
    /// the slip limit μ p_N on the approach, eq. 2.18-2.21) is returned as its
    /// coefficient [`PointEval::coupling`], a rank-one term the serial solver
    /// keeps out of its Cholesky factor ([`crate::linalg::backend::serial`]).
    #[allow(clippy::too_many_arguments)] // eval_point_at's arguments and the split
    pub(crate) fn eval_point_parts(
        &self,
        pt: &Point,
        u: &[f64],
        gap: f64,
        committed: &PointState,
        k_floor: Option<f64>,
        r: &mut [f64],
        k: Option<&mut [f64]>,
        with_coupling: bool,
    ) -> PointEval {
        if self.node_dofs.vector_slip() {
            return self.eval_point_vector(pt, u, gap, committed, k_floor, r, k, with_coupling);
        }
        let (u_n, u_t) = self.point_kinematics_at(pt, u, gap);
        let (p_n, k_law) = self.law.pressure(u_n);
        let k_n = match k_floor {
            Some(kf) if u_n <= 0.0 => kf,
            _ => k_law,
        };
        // gn, gt: derivatives of u_N and u_T with respect to the local dofs
        let (gn, gt) = pt.gradients();
        let mut status = if u_n > 0.0 {
            Status::Closed
        } else {
            Status::Open
        };
        let (mut p_t, mut d_ut, mut d_un) = (0.0, 0.0, 0.0);
        let mut state = PointState { u_t, ..*committed };
        if let Some(law) = &self.tangential {
            let ev = law.eval(p_n, k_law, u_t, &committed.slip);
            (p_t, d_ut, d_un) = (ev.p_t, ev.d_ut, ev.d_un);
            state = PointState {
                slip: ev.state,
                p_t,
                u_t,
                mu_f: ev.mu_f,
                ..Default::default()
            };
            if u_n > 0.0 {
                status = match ev.slip {
                    Slip::Stick => Status::Stick,
                    Slip::MicroSlip => Status::MicroSlip,
                    Slip::MacroSlip => Status::MacroSlip,
                };
            }
            if self.scheme == FrictionScheme::StiffnessModification && status != Status::Stick {
                // secant of the increment (2.25), bounded by the elastic stiffness
                let du = u_t - committed.u_t;
                let ke = if p_n > 0.0 {
                    law.elastic_stiffness(p_n).0
                } else {
                    0.0
                };
                d_ut = if du.abs() > 1e-14 {
                    ((p_t - committed.p_t) / du).clamp(0.0, ke)
                } else {
                    d_ut
                };
                d_un = 0.0;
            } else if self.scheme == FrictionScheme::StiffnessModification {
                d_un = 0.0;
            }
        }
        let nd = pt.ndofs();
        for i in 0..nd {
            r[i] = pt.area * (p_n * gn[i] + p_t * gt[i]);
        }
        if let Some(k) = k {
            let a = pt.area;
            let d_kept = if with_coupling { d_un } else { 0.0 };
            for i in 0..nd {
                for j in 0..nd {
                    k[i * nd + j] =
                        a * (k_n * gn[i] * gn[j] + gt[i] * (d_ut * gt[j] + d_kept * gn[j]));
                }
            }
        }
        PointEval {
            u_n,
            p_n,
            status,
            state,
            coupling: pt.area * d_un,
            coupling_hoop: 0.0,
        }
    }
}

/// Outward normal of body B (pointing into A) and ds/dξ at parameter s of a
/// quadratic contact edge walked with B on its right (A on its left).
fn edge_normal(x: &[[f64; 2]; 3], s: f64) -> ([f64; 2], f64) {
    let dn = [s - 0.5, -2.0 * s, s + 0.5];
    let mut t = [0.0; 2];
    for i in 0..3 {
        t[0] += dn[i] * x[i][0];
        t[1] += dn[i] * x[i][1];
    }
    let l = t[0].hypot(t[1]);
    // Contact edges are walked with B on the right: along B's top in increasing
    // x (horizontal interface, A above: n = +y) or along B's left side in
    // increasing y (vertical interface, A to the left: n = −x). The normal
    // into A, on the left of the walk direction t, is (−t_y, t_x); the
    // internal tangent (n_y, −n_x) is then t itself.
    ([-t[1] / l, t[0] / l], l)
}

/// The points of lumped weights: one per pair, at the pair, with its
/// area and normal; `tangent` gives t₁ from the normal.
fn lumped_points(pairs: &[Pair], tangent: impl Fn([f64; 3]) -> [f64; 3]) -> Vec<Point> {
    pairs
        .iter()
        .enumerate()
        .map(|(i, p)| Point {
            area: p.area,
            normal: p.normal,
            tangent: tangent(p.normal),
            coupling: Coupling::Coincident {
                pairs: [i; MAX_SIDE],
                shape: side(&[1.0]),
                len: 1,
            },
        })
        .collect()
}

/// A side's values in a [`MAX_SIDE`] array, zeros after them.
pub(crate) fn side<T: Copy + Default>(values: &[T]) -> [T; MAX_SIDE] {
    let mut out = [T::default(); MAX_SIDE];
    out[..values.len()].copy_from_slice(values);
    out
}

fn gauss4() -> [(f64, f64); 4] {
    let a = (3.0 / 7.0 - 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
    let b = (3.0 / 7.0 + 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
    let wa = (18.0 + 30f64.sqrt()) / 36.0;
    let wb = (18.0 - 30f64.sqrt()) / 36.0;
    [(-b, wb), (-a, wa), (a, wa), (b, wb)]
}

/// The pairs and points of a 3D interface: coincident faces; a
/// non-matching one's node-to-surface springs.
fn on_faces(
    mesh: &Mesh,
    iface: &Interface,
    weights: Weights,
) -> Result<(Vec<Pair>, Vec<Point>), String> {
    if weights == Weights::Mortar {
        return Err(format!(
            "interface \"{}\": weights = \"mortar\" is not available on the faces of a 3D model \
             (a segment-to-segment integral on faces needs the two sides' faces clipped against \
             each other); give weights = \"consistent\" or \"lumped\"",
            iface.name
        ));
    }
    if let Some(nm) = &iface.nonmatching_faces {
        return surface::node_to_surface(mesh, &iface.name, nm, weights);
    }
    Ok(InterfaceModel::coincident_faces(mesh, iface, weights))
}
