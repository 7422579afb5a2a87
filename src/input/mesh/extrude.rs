//! A 3D mesh from a plane one: every 8-node quad of the block layout swept
//! along z through graded layers into 20-node hexahedra
//! ([`crate::physics::element::h20`]), the layout's sets carried along.
//!
//! ```text
//!   levels k = 0, 1, …, 2·layers: z of the layer planes (even k) and of
//!   their midplanes (odd k); a plane node n is copied to every even level,
//!   a corner node also to the odd ones (the vertical edges' midsides)
//!
//!   quad [c0 c1 c2 c3 m0 m1 m2 m3] in layer j (levels 2j, 2j+1, 2j+2):
//!   hexahedron [c@2j, c@2j+2, m@2j, m@2j+2, c@2j+1]   (VTK order)
//! ```
//! A quad counter-clockwise in (x, y) swept towards +z is a right-handed
//! hexahedron (det J > 0). Sets: a node set of the layout becomes the nodes
//! of every copy of its nodes (the side `punch.left` becomes the face
//! x = x₀ through the whole depth); an edge set becomes the face set of its
//! edges swept through every layer, each face an 8-node quad walked
//! counter-clockwise seen from outside (the edge walked with the body on its
//! left, then up: (b − a) × e_z points out); and every set `<name>.all`
//! (a block or a body) gives `<name>.zmin` and `<name>.zmax`, the nodes and
//! faces of its elements on the first and the last level.
//!
//! A revolution about the y axis is the same sweep with z read as the angle
//! ([`super::revolve`]).

use super::{ContactFace, Element, Face, Family, Interface, Mesh, MeshError, NonMatchingFaces};
use std::collections::BTreeMap;

/// The layout `plane` swept through the z levels `zs` (the layer planes,
/// strictly increasing, at least two).
pub(crate) fn extrude(plane: &Mesh, zs: &[f64]) -> Result<Mesh, MeshError> {
    sweep(plane, zs, ["zmin", "zmax"])
}

/// The sweep of both: `plane` through the levels `zs`, the ends' sets named
/// `<name>.<ends[0]>` and `<name>.<ends[1]>`.
pub(super) fn sweep(plane: &Mesh, zs: &[f64], ends: [&str; 2]) -> Result<Mesh, MeshError> {
    if let Some(el) = plane.elements.iter().find(|el| el.family != Family::Q8) {
        return Err(MeshError(format!(
            "a sweep (extrude, revolve) takes 8-node quads; the layout has a {}",
            el.family.name()
        )));
    }
    let layers = zs.len() - 1;
    let levels: Vec<f64> = (0..=2 * layers)
        .map(|k| match k % 2 {
            0 => zs[k / 2],
            _ => 0.5 * (zs[k / 2] + zs[k / 2 + 1]),
        })
        .collect();
    let mut corner = vec![false; plane.nodes.len()];
    for el in &plane.elements {
        for &c in el.corners() {
            corner[c] = true;
        }
    }
    // copy[n][k]: node n's copy on level k (usize::MAX: none)
    let mut copy = vec![vec![usize::MAX; levels.len()]; plane.nodes.len()];
    let mut mesh = Mesh {
        bodies: plane.bodies.clone(),
        node_dofs: plane.node_dofs,
        ..Mesh::default()
    };
    for (k, &z) in levels.iter().enumerate() {
        for (n, c) in copy.iter_mut().enumerate() {
            if k % 2 == 0 || corner[n] {
                c[k] = mesh.nodes.len();
                let [x, y, _] = plane.nodes[n];
                mesh.nodes.push([x, y, z]);
            }
        }
    }
    for j in 0..layers {
        let (b, m, t) = (2 * j, 2 * j + 1, 2 * j + 2);
        for el in &plane.elements {
            let q = el.nodes();
            let at = |a: usize, k: usize| copy[q[a]][k];
            let mut h = [0; 20];
            for a in 0..4 {
                h[a] = at(a, b);
                h[4 + a] = at(a, t);
                h[8 + a] = at(4 + a, b);
                h[12 + a] = at(4 + a, t);
                h[16 + a] = at(a, m);
            }
            mesh.elements.push(Element::new(Family::H20, &h, el.body));
        }
    }
    for (name, set) in &plane.node_sets {
        let mut nodes: Vec<usize> = set
            .iter()
            .flat_map(|&n| copy[n].iter().copied().filter(|&c| c != usize::MAX))
            .collect();
        nodes.sort_unstable();
        mesh.node_sets.insert(name.clone(), nodes);
    }
    for (name, edges) in &plane.edge_sets {
        let faces = edges
            .iter()
            .flat_map(|edge| (0..layers).map(|j| swept_face(&copy, edge, j)))
            .collect();
        mesh.face_sets.insert(name.clone(), faces);
    }
    mesh.interfaces = plane
        .interfaces
        .iter()
        .map(|i| swept_interface(&copy, layers, i))
        .collect();
    add_end_sets(plane, &copy, ends, &mut mesh);
    Ok(mesh)
}

/// The face edge [a, mid, e] of the layout sweeps through layer j: an
/// 8-node quad walked counter-clockwise seen from the edge's right (the
/// edge walked, then up: (e − a) × e_z, the outward normal of a body on
/// the edge's left).
fn swept_face(copy: &[Vec<usize>], &[a, mid, e]: &[usize; 3], j: usize) -> Face {
    let (b, m, t) = (2 * j, 2 * j + 1, 2 * j + 2);
    let nodes = [
        copy[a][b],
        copy[e][b],
        copy[e][t],
        copy[a][t],
        copy[mid][b],
        copy[e][m],
        copy[mid][t],
        copy[a][m],
    ];
    Face::new(Family::Q8, &nodes)
}

/// The edge swept through layer j as a face of an interface: walked the
/// other way round, so that ∂x/∂ξ × ∂x/∂η points to the edge's left (a
/// contact edge has A on its left: the normal from B into A).
fn interface_face(copy: &[Vec<usize>], edge: &[usize; 3], j: usize) -> Face {
    let face = swept_face(copy, edge, j);
    let nodes: Vec<usize> = Family::Q8
        .reversed()
        .iter()
        .map(|&k| face.nodes()[k])
        .collect();
    Face::new(Family::Q8, &nodes)
}

/// A layout interface swept through every layer: its contact edges into
/// contact faces (node i of A's face paired with node i of B's), a
/// non-matching one's slave and master edges into slave and master faces.
fn swept_interface(copy: &[Vec<usize>], layers: usize, plane: &Interface) -> Interface {
    let sweep = |edges: &[[usize; 3]]| -> Vec<Face> {
        edges
            .iter()
            .flat_map(|e| (0..layers).map(move |j| interface_face(copy, e, j)))
            .collect()
    };
    let faces = plane
        .edges
        .iter()
        .flat_map(|e| {
            (0..layers).map(move |j| ContactFace {
                a: interface_face(copy, &e.a, j),
                b: interface_face(copy, &e.b, j),
            })
        })
        .collect();
    Interface {
        name: plane.name.clone(),
        body_a: plane.body_a,
        body_b: plane.body_b,
        faces,
        nonmatching_faces: plane.nonmatching.as_ref().map(|nm| NonMatchingFaces {
            slave: sweep(&nm.slave),
            master: sweep(&nm.master),
        }),
        ..Default::default()
    }
}

/// `<name>.<ends[0]>` and `<name>.<ends[1]>` (`zmin`, `zmax` of a sweep
/// along z) of every set `<name>.all` of the layout: its elements' ends on
/// the first and the last level (an element of the layout belongs to
/// `<name>` when all its nodes are in the set: a block's neighbour shares at
/// most one side with it).
fn add_end_sets(plane: &Mesh, copy: &[Vec<usize>], ends: [&str; 2], mesh: &mut Mesh) {
    let last = copy.first().map_or(0, |c| c.len() - 1);
    let mut sets = BTreeMap::new();
    for (name, all) in &plane.node_sets {
        let Some(base) = name.strip_suffix(".all") else {
            continue;
        };
        let inside = |n: &usize| all.binary_search(n).is_ok();
        let elements: Vec<&Element> = plane
            .elements
            .iter()
            .filter(|el| el.nodes().iter().all(inside))
            .collect();
        for (end, k, turn) in [(ends[0], 0, true), (ends[1], last, false)] {
            let faces: Vec<Face> = elements
                .iter()
                .map(|el| {
                    let q = el.nodes();
                    // seen from outside: the top as the quad is, the bottom
                    // walked the other way round
                    let order: Vec<usize> = if turn {
                        Family::Q8.reversed().iter().map(|&a| q[a]).collect()
                    } else {
                        q.to_vec()
                    };
                    let nodes: Vec<usize> = order.iter().map(|&n| copy[n][k]).collect();
                    Face::new(Family::Q8, &nodes)
                })
                .collect();
            let mut nodes: Vec<usize> = faces.iter().flat_map(|f| f.nodes().to_vec()).collect();
            nodes.sort_unstable();
            nodes.dedup();
            sets.insert(format!("{base}.{end}"), (nodes, faces));
        }
    }
    for (name, (nodes, faces)) in sets {
        mesh.node_sets.entry(name.clone()).or_insert(nodes);
        mesh.face_sets.entry(name).or_insert(faces);
    }
}

#[cfg(test)]
pub(super) mod tests;
