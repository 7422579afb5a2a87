//! A 3D mesh from a plane layout revolved about the y axis: the sweep of
//! [`super::extrude`] with z read as the angle θ, each node then placed at
//! ```text
//!   (x, y, θ) ↦ (x cos θ, y, x sin θ)      det ∂(x', y', z')/∂(x, y, θ) = x
//! ```
//! so a layout with x > 0 keeps every element right-handed and every face
//! set outward; the midside nodes of the circumferential edges sit on their
//! arcs (at the mid angle), the element edges in the layout's plane stay as
//! they were. Its end sets are `<name>.theta0` (the plane z = 0) and
//! `<name>.theta1` (θ = the angle) of every block and body, and `theta0`,
//! `theta1` of the whole mesh (every body's end at once: the two faces of a
//! cyclic sector of several bodies).
//!
//! A layout that reaches the axis (a bolt, a solid shaft, a sphere) cannot
//! be swept there: its elements on the axis would collapse into a line.
//! Through 90° or 180° they are replaced by an O-grid core ([`ogrid`]): for
//! each layout element on the axis, from the axis to r₁, the disk sector
//! r ≤ r₁ is meshed as a square (a rectangle for a half) and a ring out to
//! the arc r = r₁ whose nodes are the revolution's own there, swept along y
//! between the element's bottom and top (each a surface of revolution: a
//! sphere's cap where the layout's side is an arc).
//!
//! Interfaces go along: the revolved part's contact edges become contact
//! faces ([`super::extrude`]), and those on the bottom or top side of an
//! element on the axis the core's faces there: a non-matching interface's
//! slave or master faces, or a matching one's contact faces, the two sides'
//! cores meshed alike face for face. The core's nodes join the revolved
//! part's by their place within one body: the two sides of an interface
//! that meet on the axis (a sphere's apex on a flat) stay two nodes.

use super::extrude::sweep;
use super::{ContactEdge, Element, Interface, Mesh, MeshError, NonMatching};
use ogrid::{AxisElement, Core};

mod ogrid;

/// The layout `plane` (x the radius, y the axis) revolved about the y axis
/// from θ = 0 (the plane z = 0) through `angle` radians in `n` equal
/// layers (module text); elements on the axis become an O-grid core when
/// the angle is 90° and n even, or 180° and n a multiple of 4, and are
/// refused otherwise.
pub(crate) fn revolve(plane: &Mesh, angle: f64, n: usize) -> Result<Mesh, MeshError> {
    let mut mesh = revolve_bodies(plane, angle, n)?;
    add_mesh_ends(&mut mesh);
    Ok(mesh)
}

/// The ends of the whole mesh, `theta0` and `theta1`: the union of every
/// body's `<body>.theta0` / `.theta1` (nodes and faces; bodies share no
/// node, so neither a node nor a face comes twice), unless the layout named
/// a set so already.
fn add_mesh_ends(mesh: &mut Mesh) {
    for end in ["theta0", "theta1"] {
        if mesh.node_sets.contains_key(end) {
            continue;
        }
        let names: Vec<String> = mesh.bodies.iter().map(|b| format!("{b}.{end}")).collect();
        let mut nodes: Vec<usize> = (names.iter())
            .filter_map(|k| mesh.node_sets.get(k))
            .flatten()
            .copied()
            .collect();
        if nodes.is_empty() {
            continue;
        }
        nodes.sort_unstable();
        let faces: Vec<super::Face> = (names.iter())
            .filter_map(|k| mesh.face_sets.get(k))
            .flatten()
            .cloned()
            .collect();
        mesh.node_sets.insert(end.to_string(), nodes);
        mesh.face_sets.entry(end.to_string()).or_insert(faces);
    }
}

/// [`revolve`] but for the mesh-wide end sets.
fn revolve_bodies(plane: &Mesh, angle: f64, n: usize) -> Result<Mesh, MeshError> {
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
    let right = |deg: f64| (angle - deg.to_radians()).abs() <= 1e-12;
    let quarters = match n {
        _ if right(90.0) && n % 2 == 0 => 1,
        _ if right(180.0) && n % 4 == 0 => 2,
        _ => {
            return Err(MeshError(format!(
                "revolve: the layout reaches the axis at (x, y) = (0, {}): its elements there become \
                 a core meshed as an O-grid, made for a quarter through 90° in an even number of \
                 layers or a half through 180° in a multiple of 4 (angle = {}°, n = {n}); revolve a \
                 quarter or a half, or a layout with x > 0 (a hollow part)",
                first[1],
                // the case's degrees, not their round trip through radians
                (angle.to_degrees() * 1e9).round() / 1e9
            )));
        }
    };
    let shapes = axis
        .iter()
        .map(|&e| AxisElement::of(plane, e, size))
        .collect::<Result<Vec<_>, _>>()?;
    for shape in &shapes {
        shape.refuse_outer_interface(plane)?;
    }
    let outer = without(plane, &axis);
    let mut mesh = revolved(&outer, angle, n)?;
    let mut core = Core::new(&mesh, size, n / (2 * quarters), quarters);
    for shape in &shapes {
        core.add(plane, shape, &mut mesh);
    }
    core.pair_contact_faces(&mut mesh);
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

/// The layout without the elements `drop`, its nodes renumbered, its sets
/// and interfaces keeping what is left (an edge only with all three nodes).
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
    let keep = |e: &[usize; 3]| -> Option<[usize; 3]> {
        let e = e.map(|n| new[n]);
        e.iter().all(|&n| n != usize::MAX).then_some(e)
    };
    let interfaces = plane
        .interfaces
        .iter()
        .map(|i| Interface {
            name: i.name.clone(),
            body_a: i.body_a,
            body_b: i.body_b,
            edges: i
                .edges
                .iter()
                .filter_map(|e| {
                    Some(ContactEdge {
                        a: keep(&e.a)?,
                        b: keep(&e.b)?,
                    })
                })
                .collect(),
            nonmatching: i.nonmatching.as_ref().map(|nm| NonMatching {
                slave: nm.slave.iter().filter_map(keep).collect(),
                master: nm.master.iter().filter_map(keep).collect(),
            }),
            ..Default::default()
        })
        .collect();
    Mesh {
        nodes,
        elements,
        bodies: plane.bodies.clone(),
        node_sets,
        edge_sets,
        interfaces,
        node_dofs: plane.node_dofs,
        ..Mesh::default()
    }
}

#[cfg(test)]
mod tests;
