//! Two bodies of a 3D mesh in one place: refused as the plane check refuses
//! two bodies sharing area ([`crate::model::consistency`]).
//!
//! Each element's corners span straight tetrahedra (the tetrahedron itself,
//! or a hexahedron cut into six by its diagonal 0–6); the centre and the
//! midside nodes of an element of one body must not lie strictly inside
//! (beyond 1e-6 of the element's size) a tetrahedron of an element of
//! another body. Elements are binned by their bounding boxes on a grid of
//! about one element per cell. It finds any overlap deeper than about half
//! an element; curved sides are taken by their chords. Between two bodies
//! joined by a non-matching interface (their surfaces are two meshes of one
//! surface: a midside node on a curved side lies beyond the other side's
//! chords) the depth allowed is [`crate::model::interface::OVERLAP_LIMIT`]
//! of the element's size, as in the plane check; the springs check the
//! overlap at each of their points.

use crate::error::{clip, Error, Result};
use crate::input::mesh::{Family, Mesh};
use crate::numbers::vec3::{cross, dot, sub};
use std::collections::BTreeMap;

/// The hexahedron's six tetrahedra about its diagonal 0–6 (corners in VTK
/// order), each positively oriented for a right-handed element.
const HEX_TETS: [[usize; 4]; 6] = [
    [0, 1, 2, 6],
    [0, 2, 3, 6],
    [0, 3, 7, 6],
    [0, 7, 4, 6],
    [0, 4, 5, 6],
    [0, 5, 1, 6],
];

/// Is `p` inside the tetrahedron `t` by more than `tol` (a length) from
/// every face?
fn strictly_inside(p: [f64; 3], t: [[f64; 3]; 4], tol: f64) -> bool {
    let faces = [[1, 2, 3, 0], [0, 3, 2, 1], [0, 1, 3, 2], [0, 2, 1, 3]];
    faces.iter().all(|&[a, b, c, opposite]| {
        let n = cross(sub(t[b], t[a]), sub(t[c], t[a]));
        let len = dot(n, n).sqrt();
        if len == 0.0 {
            return false;
        }
        // the distance of p from the face's plane, on the side of the
        // opposite corner
        let side = dot(n, sub(t[opposite], t[a])).signum();
        side * dot(n, sub(p, t[a])) / len > tol
    })
}

/// The straight tetrahedra of element e's corners.
fn tets(mesh: &Mesh, e: usize) -> Vec<[[f64; 3]; 4]> {
    let el = &mesh.elements[e];
    let x = |a: usize| mesh.nodes[el.nodes()[a]];
    match el.family {
        Family::T10 => vec![[x(0), x(1), x(2), x(3)]],
        _ => HEX_TETS.iter().map(|t| t.map(x)).collect(),
    }
}

/// Refuses two bodies of a 3D mesh that fill one place (see the module text).
pub(crate) fn check(mesh: &Mesh, place: &str) -> Result<()> {
    let n = mesh.elements.len();
    if mesh.bodies.len() < 2 || n == 0 {
        return Ok(());
    }
    let boxes: Vec<([f64; 3], [f64; 3])> = (0..n)
        .map(|e| {
            mesh.elements[e].nodes().iter().fold(
                ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                |(l, h), &k| {
                    let x = mesh.nodes[k];
                    (
                        std::array::from_fn(|c| l[c].min(x[c])),
                        std::array::from_fn(|c| h[c].max(x[c])),
                    )
                },
            )
        })
        .collect();
    let (lo, hi) = boxes
        .iter()
        .fold(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]), |(l, h), b| {
            (
                std::array::from_fn(|c| l[c].min(b.0[c])),
                std::array::from_fn(|c| h[c].max(b.1[c])),
            )
        });
    let side = ((n as f64).cbrt().ceil() as usize).clamp(1, 256);
    let cell = |x: f64, c: usize| {
        (((x - lo[c]) / (hi[c] - lo[c]).max(1e-300) * side as f64) as usize).min(side - 1)
    };
    let mut grid: BTreeMap<[usize; 3], Vec<usize>> = BTreeMap::new();
    for (e, (l, h)) in boxes.iter().enumerate() {
        for i in cell(l[0], 0)..=cell(h[0], 0) {
            for j in cell(l[1], 1)..=cell(h[1], 1) {
                for k in cell(l[2], 2)..=cell(h[2], 2) {
                    grid.entry([i, j, k]).or_default().push(e);
                }
            }
        }
    }
    let apart: std::collections::HashSet<(usize, usize)> = mesh
        .interfaces
        .iter()
        .filter(|i| i.nonmatching_faces.is_some())
        .map(|i| (i.body_a.min(i.body_b), i.body_a.max(i.body_b)))
        .collect();
    for (b, el) in mesh.elements.iter().enumerate() {
        let corners = el.family.corners();
        let centre = mesh.corner_mean(b);
        let points =
            std::iter::once(centre).chain(el.nodes()[corners..].iter().map(|&k| mesh.nodes[k]));
        for p in points {
            let key = [cell(p[0], 0), cell(p[1], 1), cell(p[2], 2)];
            for &a in grid.get(&key).into_iter().flatten() {
                let other = &mesh.elements[a];
                if other.body == el.body {
                    continue;
                }
                let (l, h) = boxes[a];
                let size = (0..3).map(|c| (h[c] - l[c]).powi(2)).sum::<f64>().sqrt();
                let pair = (el.body.min(other.body), el.body.max(other.body));
                let depth = if apart.contains(&pair) {
                    crate::model::interface::OVERLAP_LIMIT
                } else {
                    1e-6
                };
                if tets(mesh, a)
                    .into_iter()
                    .any(|t| strictly_inside(p, t, depth * size))
                {
                    return Err(Error::Mesh {
                        place: place.to_string(),
                        message: format!(
                            "bodies \"{}\" and \"{}\" overlap: {} of \"{}\" near ({:.4}, {:.4}, {:.4}) lies inside {} of \"{}\" (two bodies cannot fill the same volume)",
                            clip(&mesh.bodies[el.body]),
                            clip(&mesh.bodies[other.body]),
                            mesh.element_label(b),
                            clip(&mesh.bodies[el.body]),
                            p[0],
                            p[1],
                            p[2],
                            mesh.element_label(a),
                            clip(&mesh.bodies[other.body]),
                        ),
                    });
                }
            }
        }
    }
    Ok(())
}
