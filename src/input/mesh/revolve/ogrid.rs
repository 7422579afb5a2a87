//! The O-grid core of a revolved layout on the axis ([`super`]): for each
//! layout element on the axis, whose axis side lies on x = 0 and whose
//! outer side on x = r₁, the disk sector r ≤ r₁ of a quarter (q = 1,
//! through 90°) or a half (q = 2, through 180°) is meshed as a rectangle
//! of 2m × m quadrangles (m × m for a quarter) of side s = 0.55 r₁ and a
//! ring of 2mq quadrangles from the rectangle's boundary to the arc r = r₁,
//! one element thick, whose arc nodes are the revolution's own at r₁
//! (n = 2mq layers: the ring's arc corners are the layer planes):
//! ```text
//!   rectangle (a, b):  G(2a, 2b), G(2a+2, 2b), G(2a+2, 2b+2), G(2a, 2b+2) + midsides,
//!                      G(i, j) = (s i/2m, s j/2m),   a from 0 (quarter) or −m (half) to m − 1
//!   ring j:            B₂ⱼ, A₂ⱼ, A₂ⱼ₊₂, B₂ⱼ₊₂ + midsides (radial ones straight,
//!                      A₂ⱼ₊₁ on the arc, B₂ⱼ₊₁ on the rectangle's side)
//!   B_i = G(2m, i) (i ≤ 2m), G(4m − i, 2m) (2m ≤ i ≤ 2m + 2mq), G(−2m, 8m − i) (half, i ≥ 6m)
//!   A_i = r₁ (cos θᵢ, sin θᵢ),   θᵢ = i (π/2)/(4m)
//! ```
//! and swept along y into 20-node hexahedra between the element's bottom
//! and top: a node at radius r of the cross-section sits at the height of
//! the layout's bottom (top) side there, y_b(r) = Σ N_k(s) y_k with
//! x(s) = Σ N_k(s) x_k = r on that quadratic side (its y where the side is
//! flat), the corners' vertical midsides at ½(y_b(r) + y_t(r)) (at r₁ and
//! on the axis the layout's own midside nodes). A flat bottom and top give
//! the cylinder [0, r₁] × [y₀, y₁] of a straight rectangle; an arc gives a
//! sphere's cap. The core's nodes join the revolved part's by their place
//! within one body.
//!
//! Sets: a layout edge set on the element's bottom or top side gains the
//! core's faces there and its node set their nodes, a set holding the whole
//! element (`.all`) every core node, the axis side's set the nodes on the
//! axis, and `<name>.theta0` / `.theta1` the core's faces in the planes of
//! θ = 0 (z = 0) and θ = 90° (x = 0) or 180° (z = 0, x < 0). Interfaces: a
//! non-matching interface on the bottom or top side gains the core's faces
//! there as slave faces (body A's, walked into A) or master faces (body
//! B's, walked out of B), a matching one contact faces of its two sides'
//! cores, which are meshed alike (the same r₁, the same quadrangles in the
//! same order) and pair face for face, node for node.

use super::super::{ContactFace, Element, Face, Family, Mesh, MeshError, NonMatchingFaces};
use std::collections::{BTreeMap, HashMap};

/// The side of the core's square as a fraction of r₁ (module text).
const CORE_SQUARE: f64 = 0.55;

/// A layout element on the axis: its sides' nodes and their coordinates,
/// the bottom and the top walked from the axis out.
pub(super) struct AxisElement {
    element: usize,
    r1: f64,
    /// The side at the lower y, at the higher y, on the axis and at r₁,
    /// each [end, mid, end]; the bottom and the top from the axis out.
    bottom: [usize; 3],
    top: [usize; 3],
    on_axis: [usize; 3],
    outer: [usize; 3],
    /// (x, y) of the bottom's and the top's nodes.
    sides: [[[f64; 2]; 3]; 2],
    /// y of the axis side's and the outer side's midside nodes.
    mid_y: [f64; 2],
}

impl AxisElement {
    /// Element e of the layout, which has two corners on the axis: refused
    /// unless it is an 8-node quadrilateral with its axis side on x = 0 and
    /// its outer side on x = r₁, its bottom and top running from one to the
    /// other with x increasing (their midside nodes within the middle half).
    pub(super) fn of(plane: &Mesh, e: usize, size: f64) -> Result<AxisElement, MeshError> {
        let el = &plane.elements[e];
        let x = |n: usize| plane.nodes[n];
        let tol = 1e-9 * size;
        let edges: Vec<[usize; 3]> = el.edges().collect();
        let on = |n: usize| x(n)[0].abs() <= tol;
        let k = edges.iter().position(|s| s.iter().all(|&n| on(n)));
        let (Some(k), 4) = (k, edges.len()) else {
            return Err(not_a_rectangle(plane, e));
        };
        let outer = edges[(k + 2) % 4];
        let r1 = x(outer[0])[0];
        if r1 <= tol || outer.iter().any(|&n| (x(n)[0] - r1).abs() > tol) {
            return Err(not_a_rectangle(plane, e));
        }
        let from_axis = |s: [usize; 3]| if on(s[0]) { s } else { [s[2], s[1], s[0]] };
        let (s1, s3) = (from_axis(edges[(k + 1) % 4]), from_axis(edges[(k + 3) % 4]));
        let graph = |s: &[usize; 3]| {
            let xm = x(s[1])[0];
            on(s[0]) && (x(s[2])[0] - r1).abs() <= tol && xm > 0.25 * r1 && xm < 0.75 * r1
        };
        if !graph(&s1) || !graph(&s3) {
            return Err(not_a_rectangle(plane, e));
        }
        let mean_y = |s: &[usize; 3]| x(s[0])[1] + x(s[2])[1];
        let (bottom, top) = if mean_y(&s1) < mean_y(&s3) {
            (s1, s3)
        } else {
            (s3, s1)
        };
        let xy = |s: [usize; 3]| s.map(|n| [x(n)[0], x(n)[1]]);
        Ok(AxisElement {
            element: e,
            r1,
            bottom,
            top,
            on_axis: edges[k],
            outer,
            sides: [xy(bottom), xy(top)],
            mid_y: [x(edges[k][1])[1], x(outer[1])[1]],
        })
    }

    /// y of the bottom (`side` 0) or the top (1) at radius r (module text).
    fn y(&self, side: usize, r: f64) -> f64 {
        let e = &self.sides[side];
        if r <= 1e-12 * self.r1 {
            return e[0][1];
        }
        if r >= (1.0 - 1e-12) * self.r1 {
            return e[2][1];
        }
        if e[0][1] == e[1][1] && e[1][1] == e[2][1] {
            return e[0][1];
        }
        // x(s) = r on the side, x increasing along it
        let mut s = (2.0 * r / self.r1 - 1.0).clamp(-1.0, 1.0);
        for _ in 0..50 {
            let n = crate::physics::element::edge::shape(s);
            let dn = [s - 0.5, -2.0 * s, s + 0.5];
            let f = n[0] * e[0][0] + n[1] * e[1][0] + n[2] * e[2][0] - r;
            let df = dn[0] * e[0][0] + dn[1] * e[1][0] + dn[2] * e[2][0];
            let step = f / df;
            s = (s - step).clamp(-1.0, 1.0);
            if step.abs() < 1e-15 {
                break;
            }
        }
        let n = crate::physics::element::edge::shape(s);
        n[0] * e[0][1] + n[1] * e[1][1] + n[2] * e[2][1]
    }

    /// y of the corners' vertical midsides at radius r (module text).
    fn y_mid(&self, r: f64) -> f64 {
        if r <= 1e-12 * self.r1 {
            self.mid_y[0]
        } else if r >= (1.0 - 1e-12) * self.r1 {
            self.mid_y[1]
        } else {
            0.5 * (self.y(0, r) + self.y(1, r))
        }
    }

    /// An interface on the element's outer side (a block one element wide
    /// on the axis, its side on an interface) is refused: the core's ring
    /// there is not made into contact faces.
    pub(super) fn refuse_outer_interface(&self, plane: &Mesh) -> Result<(), MeshError> {
        let side = self.outer;
        let same = |e: &[usize; 3]| *e == side || [e[2], e[1], e[0]] == side;
        for iface in &plane.interfaces {
            let on_nonmatching = iface
                .nonmatching
                .as_ref()
                .is_some_and(|nm| nm.slave.iter().chain(&nm.master).any(same));
            if on_nonmatching || iface.edges.iter().any(|e| same(&e.a) || same(&e.b)) {
                let x = plane.nodes[side[0]];
                return Err(MeshError(format!(
                    "revolve: the interface \"{}\" runs along the outer side (r = {}) of the element on the axis at y = {}, which becomes the O-grid core: give the block on the axis more than one element across (nx), so that the interface lies beyond the core",
                    iface.name, x[0], x[1]
                )));
            }
        }
        Ok(())
    }
}

fn not_a_rectangle(plane: &Mesh, e: usize) -> MeshError {
    let c = plane.nodes[plane.elements[e].corners()[0]];
    MeshError(format!(
        "revolve: the element on the axis at (x, y) = ({}, {}) is not a rectangle [0, r] × [y₀, y₁] \
         (its bottom and top may be curved): the core of a revolved layout is made from 8-node \
         quadrilaterals with their axis side on x = 0 and their outer side at one radius r",
        c[0], c[1]
    ))
}

/// One quadrangle of a core's cross-section: its 8 points in (x, z), and
/// its sides in the end planes θ = 0 and θ = the angle, if any, as [end,
/// mid, end] local points.
type CoreQuad = ([[f64; 2]; 8], Option<[usize; 3]>, Option<[usize; 3]>);

/// The cores' builder: the nodes of the mesh by body and place (the
/// revolved part's and the cores' own), m and the quarters q, and the
/// contact faces of matching interfaces waiting for their other side.
pub(super) struct Core {
    m: usize,
    quarters: usize,
    quantum: f64,
    by_place: HashMap<(usize, [i64; 3]), usize>,
    /// By (interface, contact edge): A's core faces and B's.
    contact: BTreeMap<(usize, usize), [Vec<Face>; 2]>,
}

impl Core {
    pub(super) fn new(mesh: &Mesh, size: f64, m: usize, quarters: usize) -> Core {
        let quantum = 1e-9 * size;
        let mut core = Core {
            m,
            quarters,
            quantum,
            by_place: HashMap::new(),
            contact: BTreeMap::new(),
        };
        let bodies = mesh.node_bodies();
        for (n, &x) in mesh.nodes.iter().enumerate() {
            core.by_place.insert((bodies[n], core.key(x)), n);
        }
        core
    }

    fn key(&self, x: [f64; 3]) -> [i64; 3] {
        x.map(|v| (v / self.quantum).round() as i64)
    }

    /// The node of `body` at `x`: the mesh's there, or a new one.
    fn node(&mut self, mesh: &mut Mesh, body: usize, x: [f64; 3]) -> usize {
        let key = (body, self.key(x));
        *self.by_place.entry(key).or_insert_with(|| {
            mesh.nodes.push(x);
            mesh.nodes.len() - 1
        })
    }

    /// The sector's quadrangles in (x, z) (module text), each 8 points
    /// (corners counter-clockwise in (x, z), then midsides), with their
    /// sides on the planes θ = 0 and θ = the angle as [end, mid, end] local
    /// point numbers.
    fn quads(&self, r1: f64) -> Vec<CoreQuad> {
        let (m, q) = (self.m as i64, self.quarters as i64);
        let s = CORE_SQUARE * r1;
        let g = |i: i64, j: i64| [s * i as f64 / (2 * m) as f64, s * j as f64 / (2 * m) as f64];
        let mut out = Vec::new();
        for b in 0..m {
            for a in if q == 1 { 0 } else { -m }..m {
                let (i, j) = (2 * a, 2 * b);
                let pts = [
                    g(i, j),
                    g(i + 2, j),
                    g(i + 2, j + 2),
                    g(i, j + 2),
                    g(i + 1, j),
                    g(i + 2, j + 1),
                    g(i + 1, j + 2),
                    g(i, j + 1),
                ];
                // the bottom side (0, 4, 1) on z = 0: θ = 0 for x ≥ 0, θ =
                // 180° for x < 0 (a half); the left (3, 7, 0) on x = 0 the
                // end θ = 90° of a quarter
                let bottom = (b == 0).then_some([0, 4, 1]);
                let (start, end) = match (q, a) {
                    (1, _) => (bottom, (a == 0).then_some([3, 7, 0])),
                    (_, a) if a >= 0 => (bottom, None),
                    _ => (None, bottom),
                };
                out.push((pts, start, end));
            }
        }
        let boundary = |i: i64| {
            if i <= 2 * m {
                g(2 * m, i)
            } else if i <= 2 * m + 2 * m * q {
                g(4 * m - i, 2 * m)
            } else {
                g(-2 * m, 8 * m - i)
            }
        };
        let arc = |i: i64| {
            let t = std::f64::consts::FRAC_PI_2 * i as f64 / (4 * m) as f64;
            [r1 * t.cos(), r1 * t.sin()]
        };
        let mid = |p: [f64; 2], q: [f64; 2]| [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
        for j in 0..2 * m * q {
            let (i0, i1) = (2 * j, 2 * j + 2);
            let pts = [
                boundary(i0),
                arc(i0),
                arc(i1),
                boundary(i1),
                mid(boundary(i0), arc(i0)),
                arc(i0 + 1),
                mid(boundary(i1), arc(i1)),
                boundary(i0 + 1),
            ];
            // the first ring element's side (0, 4, 1) on θ = 0, the last's
            // (2, 6, 3) on θ = the angle
            out.push((
                pts,
                (j == 0).then_some([0, 4, 1]),
                (j == 2 * m * q - 1).then_some([2, 6, 3]),
            ));
        }
        out
    }

    /// The core of one axis element, with its sets and interfaces (module
    /// text).
    pub(super) fn add(&mut self, plane: &Mesh, shape: &AxisElement, mesh: &mut Mesh) {
        let body = plane.elements[shape.element].body;
        let rev = Family::Q8.reversed();
        let mut bottom_faces = Vec::new();
        let mut top_faces = Vec::new();
        let mut ends: [Vec<Face>; 2] = [Vec::new(), Vec::new()];
        let mut all = Vec::new();
        let mut axis_nodes = Vec::new();
        // outward at θ = 0 (the plane z = 0) and at the other end
        let outward = [
            [0.0, 0.0, -1.0],
            if self.quarters == 1 {
                [-1.0, 0.0, 0.0]
            } else {
                [0.0, 0.0, -1.0]
            },
        ];
        for (q, start, end) in self.quads(shape.r1) {
            let radius = |p: [f64; 2]| p[0].hypot(p[1]);
            let mut level = |side: usize, mesh: &mut Mesh| -> Vec<usize> {
                q.iter()
                    .map(|&p| self.node(mesh, body, [p[0], shape.y(side, radius(p)), p[1]]))
                    .collect()
            };
            let (b, t) = (level(0, mesh), level(1, mesh));
            let mid: Vec<usize> = q[..4]
                .iter()
                .map(|&p| self.node(mesh, body, [p[0], shape.y_mid(radius(p)), p[1]]))
                .collect();
            // counter-clockwise in (x, z) faces −y: the hexahedron walks the quad reversed
            let r = |v: &[usize], a: usize| v[rev[a]];
            let mut h = [0; 20];
            for a in 0..4 {
                h[a] = r(&b, a);
                h[4 + a] = r(&t, a);
                h[8 + a] = r(&b, 4 + a);
                h[12 + a] = r(&t, 4 + a);
                h[16 + a] = mid[rev[a]];
            }
            mesh.elements.push(Element::new(Family::H20, &h, body));
            bottom_faces.push(oriented(mesh, &b, [0.0, -1.0, 0.0]));
            top_faces.push(oriented(mesh, &t, [0.0, 1.0, 0.0]));
            for (k, side) in [start, end].into_iter().enumerate() {
                if let Some([p, m, e]) = side {
                    // the side swept up: an 8-node quad, then turned outward
                    let nodes = [b[p], b[e], t[e], t[p], b[m], mid[e], t[m], mid[p]];
                    ends[k].push(oriented(mesh, &nodes, outward[k]));
                }
            }
            all.extend(b.iter().chain(&t).chain(&mid).copied());
            axis_nodes.extend([b[0], t[0], mid[0]].into_iter().filter(|&n| {
                let x = mesh.nodes[n];
                x[0] == 0.0 && x[2] == 0.0
            }));
        }
        add_sets(
            plane,
            shape,
            mesh,
            [&bottom_faces, &top_faces],
            &ends,
            &all,
            &axis_nodes,
        );
        self.carry_interfaces(plane, shape, mesh, [&bottom_faces, &top_faces]);
    }

    /// The core's faces on the bottom and top (walked outward) onto the
    /// interfaces that name those sides (module text).
    fn carry_interfaces(
        &mut self,
        plane: &Mesh,
        shape: &AxisElement,
        mesh: &mut Mesh,
        faces: [&[Face]; 2],
    ) {
        let turned = |f: &Face| {
            let nodes: Vec<usize> = Family::Q8
                .reversed()
                .iter()
                .map(|&k| f.nodes()[k])
                .collect();
            Face::new(Family::Q8, &nodes)
        };
        for (side, fs) in [shape.bottom, shape.top].iter().zip(faces) {
            let same = |e: &[usize; 3]| e == side || [e[2], e[1], e[0]] == *side;
            for (i, iface) in plane.interfaces.iter().enumerate() {
                if let Some(nm) = &iface.nonmatching {
                    let to = mesh.interfaces[i].nonmatching_faces.get_or_insert_with(|| {
                        NonMatchingFaces {
                            slave: Vec::new(),
                            master: Vec::new(),
                        }
                    });
                    if nm.slave.iter().any(same) {
                        to.slave.extend(fs.iter().map(turned));
                    }
                    if nm.master.iter().any(same) {
                        to.master.extend(fs.iter().cloned());
                    }
                }
                for (k, e) in iface.edges.iter().enumerate() {
                    if same(&e.a) {
                        self.contact.entry((i, k)).or_default()[0] =
                            fs.iter().map(turned).collect();
                    }
                    if same(&e.b) {
                        self.contact.entry((i, k)).or_default()[1] = fs.to_vec();
                    }
                }
            }
        }
    }

    /// The contact faces of the matching interfaces through the cores: A's
    /// core faces paired with B's, in the order both were made.
    pub(super) fn pair_contact_faces(self, mesh: &mut Mesh) {
        for ((i, _), [a, b]) in self.contact {
            debug_assert_eq!(a.len(), b.len());
            let faces = a.into_iter().zip(b).map(|(a, b)| ContactFace { a, b });
            mesh.interfaces[i].faces.extend(faces);
        }
    }
}

/// The sets of one core (module text): `faces` on the bottom and the top,
/// `ends` in the planes θ = 0 and θ = the angle, every node of the core and
/// those on the axis.
fn add_sets(
    plane: &Mesh,
    shape: &AxisElement,
    mesh: &mut Mesh,
    faces: [&Vec<Face>; 2],
    ends: &[Vec<Face>; 2],
    all: &[usize],
    axis_nodes: &[usize],
) {
    let has =
        |set: &Vec<usize>, side: &[usize; 3]| side.iter().all(|n| set.binary_search(n).is_ok());
    let sides = [(&shape.bottom, faces[0]), (&shape.top, faces[1])];
    let el_nodes = plane.elements[shape.element].nodes();
    for (name, set) in &plane.node_sets {
        let mut add: Vec<usize> = Vec::new();
        if el_nodes.iter().all(|n| set.binary_search(n).is_ok()) {
            add.extend(all);
            if let Some(base) = name.strip_suffix(".all") {
                for (end, faces) in ["theta0", "theta1"].iter().zip(ends) {
                    let key = format!("{base}.{end}");
                    mesh.face_sets
                        .entry(key.clone())
                        .or_default()
                        .extend(faces.iter().cloned());
                    let ns = mesh.node_sets.entry(key).or_default();
                    ns.extend(faces.iter().flat_map(|f| f.nodes().to_vec()));
                }
            }
        } else {
            for (side, faces) in sides {
                if has(set, side) {
                    add.extend(faces.iter().flat_map(|f| f.nodes().to_vec()));
                }
            }
            if has(set, &shape.on_axis) {
                add.extend(axis_nodes);
            }
        }
        if !add.is_empty() {
            mesh.node_sets.entry(name.clone()).or_default().extend(add);
        }
    }
    for (name, edges) in &plane.edge_sets {
        for (side, faces) in sides {
            let same = |e: &[usize; 3]| e == side || [e[2], e[1], e[0]] == *side;
            if edges.iter().any(same) {
                mesh.face_sets
                    .entry(name.clone())
                    .or_default()
                    .extend(faces.iter().cloned());
            }
        }
    }
    for set in mesh.node_sets.values_mut() {
        set.sort_unstable();
        set.dedup();
    }
}

/// The 8-node quad `nodes` (corners, then midsides) as a face walked
/// counter-clockwise seen from the side `out` points to.
fn oriented(mesh: &Mesh, nodes: &[usize], out: [f64; 3]) -> Face {
    let x = |a: usize| mesh.nodes[nodes[a]];
    let (p, q, r) = (x(0), x(1), x(3));
    let u = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
    let v = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
    let n = crate::numbers::vec3::cross(u, v);
    if crate::numbers::vec3::dot(n, out) >= 0.0 {
        Face::new(Family::Q8, nodes)
    } else {
        let turned: Vec<usize> = Family::Q8.reversed().iter().map(|&a| nodes[a]).collect();
        Face::new(Family::Q8, &turned)
    }
}
