//! A 3D mesh from a plane layout revolved about the y axis: the sweep of
//! [`super::extrude`] with z read as the angle θ, each node then placed at
//! ```text
//!   (x, y, θ) ↦ (x cos θ, y, x sin θ)      det ∂(x', y', z')/∂(x, y, θ) = x
//! ```
//! so a layout with x > 0 keeps every element right-handed and every face
//! set outward; the midside nodes of the circumferential edges sit on their
//! arcs (at the mid angle), the element edges in the layout's plane stay as
//! they were. Its end sets are `<name>.theta0` (the plane z = 0) and
//! `<name>.theta1` (θ = the angle).
//!
//! A layout that reaches the axis (a bolt, a solid shaft) cannot be swept
//! there: its elements on the axis would collapse into a line. Through 90°
//! they are replaced by an O-grid core: for each layout element
//! [0, r₁] × [y₀, y₁] on the axis, the quarter disk r ≤ r₁ of the plane
//! y = const is meshed as a square [0, s]² of m × m quadrangles (s = 0.55 r₁)
//! and a ring of 2m quadrangles from the square's boundary to the arc r = r₁,
//! one element thick, whose arc nodes are the revolution's own at r₁
//! (n = 2m layers: the ring's arc corners are the layer planes), and swept
//! along y through y₀, the midplane and y₁ into 20-node hexahedra:
//! ```text
//!   square (a, b):  G(2a, 2b), G(2a+2, 2b), G(2a+2, 2b+2), G(2a, 2b+2) + midsides,
//!                   G(i, j) = (s i/2m, s j/2m)
//!   ring j:         B₂ⱼ, A₂ⱼ, A₂ⱼ₊₂, B₂ⱼ₊₂ + midsides (radial ones straight,
//!                   A₂ⱼ₊₁ on the arc, B₂ⱼ₊₁ on the square's side)
//!   B_i = G(2m, i) (i ≤ 2m), G(4m − i, 2m) (i ≥ 2m);   A_i = r₁ (cos θᵢ, sin θᵢ),
//!   θᵢ = i (π/2)/(4m)
//! ```
//! The core's nodes join the revolved part's by their place. Sets: a layout
//! edge set on the element's bottom or top side gains the core's faces there
//! and its node set their nodes, a set holding the whole element (`.all`)
//! every core node, the axis side's set the nodes on the axis, and
//! `<name>.theta0` / `.theta1` the core's faces in the planes z = 0 and
//! x = 0.

use super::extrude::sweep;
use super::{Element, Face, Family, Mesh, MeshError};
use std::collections::HashMap;

/// The side of the core's square as a fraction of r₁ (module text).
const CORE_SQUARE: f64 = 0.55;

/// The layout `plane` (x the radius, y the axis) revolved about the y axis
/// from θ = 0 (the plane z = 0) through `angle` radians in `n` equal
/// layers (module text); elements on the axis become an O-grid core when
/// the angle is 90° and n even, and are refused otherwise.
pub(crate) fn revolve(plane: &Mesh, angle: f64, n: usize) -> Result<Mesh, MeshError> {
    let size = plane
        .nodes
        .iter()
        .fold(0.0f64, |m, x| m.max(x[0].abs()).max(x[1].abs()));
    let on_axis = |n: usize| plane.nodes[n][0] <= 1e-9 * size;
    let axis: Vec<usize> = (0..plane.elements.len())
        .filter(|&e| {
            plane.elements[e]
                .corners()
                .iter()
                .filter(|&&c| on_axis(c))
                .count()
                == 2
        })
        .collect();
    let touching = plane
        .elements
        .iter()
        .enumerate()
        .find(|(e, el)| !axis.contains(e) && el.nodes().iter().any(|&n| on_axis(n)));
    if let Some((_, el)) = touching {
        let n0 = el
            .nodes()
            .iter()
            .copied()
            .find(|&n| on_axis(n))
            .unwrap_or(0);
        return Err(MeshError(format!(
            "revolve: the layout touches the axis at (x, y) = ({}, {}) with a single node of an element",
            plane.nodes[n0][0], plane.nodes[n0][1]
        )));
    }
    if axis.is_empty() {
        return revolved(plane, angle, n);
    }
    let first = &plane.nodes[plane.elements[axis[0]].corners()[0]];
    if let Some(i) = plane.interfaces.first() {
        return Err(MeshError(format!(
            "revolve: the layout reaches the axis at (x, y) = (0, {}) and has the interface \"{}\": \
             an interface in a revolved part with a core on the axis is not available yet; revolve \
             a layout with x > 0 (a hollow part), or extrude",
            first[1], i.name
        )));
    }
    if (angle - std::f64::consts::FRAC_PI_2).abs() > 1e-12 || n % 2 != 0 {
        return Err(MeshError(format!(
            "revolve: the layout reaches the axis at (x, y) = (0, {}): its elements there become \
             a core meshed as an O-grid, made for a quarter only, through 90° in an even number of \
             layers (angle = {}°, n = {n}); revolve a quarter, or a layout with x > 0 (a hollow part)",
            first[1],
            angle.to_degrees()
        )));
    }
    let shapes = axis
        .iter()
        .map(|&e| AxisElement::of(plane, e, size))
        .collect::<Result<Vec<_>, _>>()?;
    let outer = without(plane, &axis);
    let mut mesh = revolved(&outer, angle, n)?;
    let mut core = Core::new(&mesh, size, n / 2);
    for shape in &shapes {
        core.add(plane, shape, &mut mesh);
    }
    Ok(mesh)
}

/// The sweep through θ and the map to space (module text).
fn revolved(plane: &Mesh, angle: f64, n: usize) -> Result<Mesh, MeshError> {
    let thetas: Vec<f64> = (0..=n).map(|k| angle * k as f64 / n as f64).collect();
    let mut mesh = sweep(plane, &thetas, ["theta0", "theta1"])?;
    for x in &mut mesh.nodes {
        let [r, y, theta] = *x;
        *x = [r * theta.cos(), y, r * theta.sin()];
    }
    Ok(mesh)
}

/// A layout element on the axis: [0, r₁] × [y₀, y₁], its sides' nodes.
struct AxisElement {
    element: usize,
    r1: f64,
    y: [f64; 3],
    /// The side at y₀, at y₁ and on the axis, each [end, mid, end].
    bottom: [usize; 3],
    top: [usize; 3],
    on_axis: [usize; 3],
}

impl AxisElement {
    /// Element e of the layout, which has two corners on the axis: refused
    /// unless it is a rectangle with its sides along x and y.
    fn of(plane: &Mesh, e: usize, size: f64) -> Result<AxisElement, MeshError> {
        let el = &plane.elements[e];
        let x = |n: usize| plane.nodes[n];
        let tol = 1e-9 * size;
        let edges: Vec<[usize; 3]> = el.edges().collect();
        let find = |pred: &dyn Fn([f64; 3], [f64; 3]) -> bool| {
            edges.iter().copied().find(|&[a, _, b]| pred(x(a), x(b)))
        };
        let axis = find(&|a, b| a[0].abs() <= tol && b[0].abs() <= tol);
        let horizontal: Vec<[usize; 3]> = edges
            .iter()
            .copied()
            .filter(|&[a, _, b]| (x(a)[1] - x(b)[1]).abs() <= tol)
            .collect();
        let (Some(on_axis), [h0, h1]) = (axis, horizontal.as_slice()) else {
            return Err(not_a_rectangle(plane, e));
        };
        let (bottom, top) = if x(h0[0])[1] < x(h1[0])[1] {
            (*h0, *h1)
        } else {
            (*h1, *h0)
        };
        let r1 = x(bottom[0])[0].max(x(bottom[2])[0]);
        let r1_top = x(top[0])[0].max(x(top[2])[0]);
        if (r1 - r1_top).abs() > tol || r1 <= tol {
            return Err(not_a_rectangle(plane, e));
        }
        let (y0, y1) = (x(bottom[0])[1], x(top[0])[1]);
        Ok(AxisElement {
            element: e,
            r1,
            y: [y0, 0.5 * (y0 + y1), y1],
            bottom,
            top,
            on_axis,
        })
    }
}

fn not_a_rectangle(plane: &Mesh, e: usize) -> MeshError {
    let c = plane.nodes[plane.elements[e].corners()[0]];
    MeshError(format!(
        "revolve: the element on the axis at (x, y) = ({}, {}) is not a rectangle [0, r] × [y₀, y₁]: \
         the core of a revolved layout is made from such elements",
        c[0], c[1]
    ))
}

/// The layout without the elements `drop`, its nodes renumbered, its sets
/// keeping what is left (an edge only with all three nodes).
fn without(plane: &Mesh, drop: &[usize]) -> Mesh {
    let kept: Vec<&Element> = (0..plane.elements.len())
        .filter(|e| !drop.contains(e))
        .map(|e| &plane.elements[e])
        .collect();
    let mut new = vec![usize::MAX; plane.nodes.len()];
    let mut nodes = Vec::new();
    for el in &kept {
        for &n in el.nodes() {
            if new[n] == usize::MAX {
                new[n] = nodes.len();
                nodes.push(plane.nodes[n]);
            }
        }
    }
    let elements = kept
        .iter()
        .map(|el| {
            let ns: Vec<usize> = el.nodes().iter().map(|&n| new[n]).collect();
            Element::new(el.family, &ns, el.body)
        })
        .collect();
    let node_sets = plane
        .node_sets
        .iter()
        .map(|(k, v)| {
            let mut s: Vec<usize> = v
                .iter()
                .map(|&n| new[n])
                .filter(|&n| n != usize::MAX)
                .collect();
            s.sort_unstable();
            (k.clone(), s)
        })
        .collect();
    let edge_sets = plane
        .edge_sets
        .iter()
        .map(|(k, v)| {
            let edges = v
                .iter()
                .map(|e| e.map(|n| new[n]))
                .filter(|e| e.iter().all(|&n| n != usize::MAX))
                .collect();
            (k.clone(), edges)
        })
        .collect();
    Mesh {
        nodes,
        elements,
        bodies: plane.bodies.clone(),
        node_sets,
        edge_sets,
        node_dofs: plane.node_dofs,
        ..Mesh::default()
    }
}

/// One quadrangle of a core's cross-section: its 8 points in (x, z), and
/// its sides on z = 0 and on x = 0, if any, as [end, mid, end] local points.
type CoreQuad = ([[f64; 2]; 8], Option<[usize; 3]>, Option<[usize; 3]>);

/// The cores' builder: the nodes of the mesh by place (the revolved part's
/// and the cores' own), and m.
struct Core {
    m: usize,
    quantum: f64,
    by_place: HashMap<[i64; 3], usize>,
}

impl Core {
    fn new(mesh: &Mesh, size: f64, m: usize) -> Core {
        let quantum = 1e-9 * size;
        let mut core = Core {
            m,
            quantum,
            by_place: HashMap::new(),
        };
        for (n, &x) in mesh.nodes.iter().enumerate() {
            core.by_place.insert(core.key(x), n);
        }
        core
    }

    fn key(&self, x: [f64; 3]) -> [i64; 3] {
        x.map(|v| (v / self.quantum).round() as i64)
    }

    /// The node at `x`: the mesh's there, or a new one.
    fn node(&mut self, mesh: &mut Mesh, x: [f64; 3]) -> usize {
        let key = self.key(x);
        *self.by_place.entry(key).or_insert_with(|| {
            mesh.nodes.push(x);
            mesh.nodes.len() - 1
        })
    }

    /// The quarter disk's quadrangles in (x, z), each 8 points (corners
    /// counter-clockwise in (x, z), then midsides), and which of them have a
    /// side on z = 0 (the plane θ = 0) and on x = 0 (θ = 90°): those sides
    /// as [end, mid, end] local point numbers.
    fn quads(&self, r1: f64) -> Vec<CoreQuad> {
        let m = self.m;
        let s = CORE_SQUARE * r1;
        let g = |i: usize, j: usize| [s * i as f64 / (2 * m) as f64, s * j as f64 / (2 * m) as f64];
        let mut out = Vec::new();
        for b in 0..m {
            for a in 0..m {
                let (i, j) = (2 * a, 2 * b);
                let q = [
                    g(i, j),
                    g(i + 2, j),
                    g(i + 2, j + 2),
                    g(i, j + 2),
                    g(i + 1, j),
                    g(i + 2, j + 1),
                    g(i + 1, j + 2),
                    g(i, j + 1),
                ];
                // the bottom side (0, 4, 1) on z = 0, the left (3, 7, 0) on x = 0
                out.push((
                    q,
                    (b == 0).then_some([0, 4, 1]),
                    (a == 0).then_some([3, 7, 0]),
                ));
            }
        }
        let boundary = |i: usize| {
            if i <= 2 * m {
                g(2 * m, i)
            } else {
                g(4 * m - i, 2 * m)
            }
        };
        let arc = |i: usize| {
            let t = std::f64::consts::FRAC_PI_2 * i as f64 / (4 * m) as f64;
            [r1 * t.cos(), r1 * t.sin()]
        };
        let mid = |p: [f64; 2], q: [f64; 2]| [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
        for j in 0..2 * m {
            let (i0, i1) = (2 * j, 2 * j + 2);
            let q = [
                boundary(i0),
                arc(i0),
                arc(i1),
                boundary(i1),
                mid(boundary(i0), arc(i0)),
                arc(i0 + 1),
                mid(boundary(i1), arc(i1)),
                boundary(i0 + 1),
            ];
            // the first ring element's side (0, 4, 1) on z = 0, the last's (2, 6, 3) on x = 0
            out.push((
                q,
                (j == 0).then_some([0, 4, 1]),
                (j == 2 * m - 1).then_some([2, 6, 3]),
            ));
        }
        out
    }

    /// The core of one axis element, with its sets (module text).
    fn add(&mut self, plane: &Mesh, shape: &AxisElement, mesh: &mut Mesh) {
        let body = plane.elements[shape.element].body;
        let [y0, ym, y1] = shape.y;
        let rev = Family::Q8.reversed();
        let mut bottom_faces = Vec::new();
        let mut top_faces = Vec::new();
        let mut ends: [Vec<Face>; 2] = [Vec::new(), Vec::new()];
        let mut all = Vec::new();
        let mut axis_nodes = Vec::new();
        for (q, on_z0, on_x0) in self.quads(shape.r1) {
            let at = |p: [f64; 2], y: f64| [p[0], y, p[1]];
            let mut level = |y: f64, mesh: &mut Mesh| -> Vec<usize> {
                q.iter().map(|&p| self.node(mesh, at(p, y))).collect()
            };
            let (b, t) = (level(y0, mesh), level(y1, mesh));
            let mid: Vec<usize> = q[..4].iter().map(|&p| self.node(mesh, at(p, ym))).collect();
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
            let outward = [[0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]];
            for (k, side) in [on_z0, on_x0].into_iter().enumerate() {
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
        let has =
            |set: &Vec<usize>, side: &[usize; 3]| side.iter().all(|n| set.binary_search(n).is_ok());
        let el_nodes = plane.elements[shape.element].nodes();
        for (name, set) in &plane.node_sets {
            let mut add: Vec<usize> = Vec::new();
            if el_nodes.iter().all(|n| set.binary_search(n).is_ok()) {
                add.extend(&all);
                if let Some(base) = name.strip_suffix(".all") {
                    for (end, faces) in ["theta0", "theta1"].iter().zip(&ends) {
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
                for (side, faces) in [(&shape.bottom, &bottom_faces), (&shape.top, &top_faces)] {
                    if has(set, side) {
                        add.extend(faces.iter().flat_map(|f| f.nodes().to_vec()));
                    }
                }
                if has(set, &shape.on_axis) {
                    add.extend(&axis_nodes);
                }
            }
            if !add.is_empty() {
                mesh.node_sets.entry(name.clone()).or_default().extend(add);
            }
        }
        for (name, edges) in &plane.edge_sets {
            for (side, faces) in [(&shape.bottom, &bottom_faces), (&shape.top, &top_faces)] {
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

#[cfg(test)]
mod tests;
