//! A box of 20-node hexahedra: the 3D block, graded along each axis as the
//! 2D blocks are ([`super::blocks::graded_axis`]), with its six faces as
//! named face sets.
//!
//! The nodes are those of a (2nx+1)(2ny+1)(2nz+1) lattice on the graded
//! corner coordinates, each midside node halfway between its corners, less
//! the face and body centres a serendipity element does not have (lattice
//! points with two or three odd indices). Element nodes are numbered as
//! [`crate::physics::element::h20`] (VTK's quadratic hexahedron); each face
//! of the box is the list of its elements' faces, numbered as
//! [`crate::physics::element::h20::FACES`] (outward normal by the right-hand
//! rule).
//!
//! Not yet reached from a case: the 3D model (issue 44) will make these its
//! `[[mesh.block]]` with a z axis.

#![allow(dead_code)] // reached by the 3D model, not yet wired

use crate::physics::element::h20;
use std::collections::BTreeMap;

/// The faces of a box, in the order of [`h20::FACES`]: ζ = −1, ζ = +1,
/// η = −1, ξ = +1, η = +1, ξ = −1 of every element on that side.
pub(crate) const FACE_NAMES: [&str; 6] = ["zmin", "zmax", "ymin", "xmax", "ymax", "xmin"];

/// A box of 20-node hexahedra.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct BoxMesh {
    pub(crate) nodes: Vec<[f64; 3]>,
    pub(crate) elements: Vec<[usize; 20]>,
    /// `<name>.xmin` … `<name>.zmax`: each face's 8-node quadrilaterals,
    /// corners counter-clockwise seen from outside.
    pub(crate) faces: BTreeMap<String, Vec<[usize; 8]>>,
}

/// The box with corner coordinates `axes` = [x, y, z] (each strictly
/// increasing, at least two: the element boundaries along that axis, as
/// [`super::blocks::graded_axis`] gives them), its face sets named
/// `<name>.<face>`.
pub(crate) fn box_mesh(name: &str, axes: [&[f64]; 3]) -> BoxMesh {
    let n = axes.map(|a| a.len() - 1);
    let dims = n.map(|k| 2 * k + 1);
    // lattice coordinate along one axis: corners at even, midsides at odd indices
    let at = |axis: usize, i: usize| {
        let a = axes[axis];
        if i % 2 == 0 {
            a[i / 2]
        } else {
            0.5 * (a[i / 2] + a[i / 2 + 1])
        }
    };
    let mut id = vec![usize::MAX; dims[0] * dims[1] * dims[2]];
    let index = |i: usize, j: usize, k: usize| (k * dims[1] + j) * dims[0] + i;
    let mut nodes = Vec::new();
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                if (i % 2) + (j % 2) + (k % 2) >= 2 {
                    continue;
                }
                id[index(i, j, k)] = nodes.len();
                nodes.push([at(0, i), at(1, j), at(2, k)]);
            }
        }
    }
    let mut elements = Vec::with_capacity(n[0] * n[1] * n[2]);
    let mut faces: BTreeMap<String, Vec<[usize; 8]>> = FACE_NAMES
        .iter()
        .map(|f| (format!("{name}.{f}"), Vec::new()))
        .collect();
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let el: [usize; 20] = std::array::from_fn(|a| {
                    // natural coordinate −1, 0, 1 → lattice offset 0, 1, 2
                    let [x, y, z] = h20::NODE_XI[a].map(|v| (v + 1.0) as usize);
                    id[index(2 * i + x, 2 * j + y, 2 * k + z)]
                });
                let on_side = [
                    k == 0,
                    k + 1 == n[2],
                    j == 0,
                    i + 1 == n[0],
                    j + 1 == n[1],
                    i == 0,
                ];
                for (f, &side) in on_side.iter().enumerate() {
                    if side {
                        let face = h20::FACES[f].map(|a| el[a]);
                        faces
                            .get_mut(&format!("{name}.{}", FACE_NAMES[f]))
                            .unwrap()
                            .push(face);
                    }
                }
                elements.push(el);
            }
        }
    }
    BoxMesh {
        nodes,
        elements,
        faces,
    }
}

/// The faces of a sector, in the order of [`FACE_NAMES`] (x → r, y → θ).
pub(crate) const SECTOR_FACE_NAMES: [&str; 6] = ["zmin", "zmax", "tmin", "rmax", "tmax", "rmin"];

/// A sector of a thick-walled cylinder about the z axis: the box on the
/// axes [r, θ (degrees), z] mapped to x = r cos θ, y = r sin θ, so that the
/// midside nodes of the circumferential edges lie on their arcs. The map
/// keeps the orientation (its Jacobian is r > 0): faces stay outward. Its
/// face sets are `<name>.rmin` (the bore), `.rmax`, `.tmin` (θ at its
/// start), `.tmax`, `.zmin`, `.zmax`.
pub(crate) fn sector_mesh(name: &str, axes: [&[f64]; 3]) -> BoxMesh {
    let mut m = box_mesh(name, axes);
    for x in &mut m.nodes {
        let (r, t) = (x[0], x[1].to_radians());
        *x = [r * t.cos(), r * t.sin(), x[2]];
    }
    m.faces = FACE_NAMES
        .iter()
        .zip(SECTOR_FACE_NAMES)
        .map(|(f, s)| {
            let faces = m.faces.remove(&format!("{name}.{f}")).unwrap_or_default();
            (format!("{name}.{s}"), faces)
        })
        .collect();
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::mesh::blocks::graded_axis;
    use crate::physics::element::solid::{Response, Tangent};
    use crate::physics::element::solid3::{forces3, ElementGeometry3, Family3};
    use crate::physics::material::{Plane, PointState, VonMises};
    use nalgebra::{DMatrix, DVector};

    fn graded() -> BoxMesh {
        let x = graded_axis("b", "x", &[0.0, 2.0, 5.0], &[2, 1], &[0.5, 1.0], 1).unwrap();
        let y = graded_axis("b", "y", &[0.0, 3.0], &[2], &[3.0], 1).unwrap();
        let z = graded_axis("b", "z", &[-1.0, 1.0], &[3], &[1.0], 1).unwrap();
        box_mesh("b", [&x, &y, &z])
    }

    #[test]
    fn counts_volume_and_every_jacobian_of_a_graded_box() {
        let m = graded();
        let (nx, ny, nz) = (3, 2, 3);
        assert_eq!(m.elements.len(), nx * ny * nz);
        // corners, then midsides on the edges along x, y and z
        let corners = (nx + 1) * (ny + 1) * (nz + 1);
        let mids = nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
        assert_eq!(m.nodes.len(), corners + mids);
        let rule = Family3::H20.rule(true);
        let mut volume = 0.0;
        for el in &m.elements {
            let c: Vec<[f64; 3]> = el.iter().map(|&a| m.nodes[a]).collect();
            let g = ElementGeometry3::new(Family3::H20, &c, &rule).unwrap();
            assert!(g.dv[..g.n].iter().all(|&v| v > 0.0));
            volume += g.volume();
        }
        assert!((volume - 5.0 * 3.0 * 2.0).abs() < 1e-12, "{volume}");
        // every node belongs to an element, none twice in one
        let mut used = vec![false; m.nodes.len()];
        for el in &m.elements {
            for (a, &n) in el.iter().enumerate() {
                assert!(!el[..a].contains(&n));
                used[n] = true;
            }
        }
        assert!(used.iter().all(|&u| u));
    }

    #[test]
    fn each_face_set_lies_on_its_side_and_faces_outward() {
        let m = graded();
        let (lo, hi) = ([0.0, 0.0, -1.0], [5.0, 3.0, 1.0]);
        // (axis, value, outward sign) per face, in FACE_NAMES order
        let sides = [
            (2, lo[2], -1.0),
            (2, hi[2], 1.0),
            (1, lo[1], -1.0),
            (0, hi[0], 1.0),
            (1, hi[1], 1.0),
            (0, lo[0], -1.0),
        ];
        let mut area = 0.0;
        for (f, &(axis, value, sign)) in sides.iter().enumerate() {
            let faces = &m.faces[&format!("b.{}", FACE_NAMES[f])];
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let expected = (hi[u] - lo[u]) * (hi[v] - lo[v]);
            let mut side_area = 0.0;
            for face in faces {
                assert!(
                    face.iter().all(|&n| m.nodes[n][axis] == value),
                    "{}",
                    FACE_NAMES[f]
                );
                let p = [0, 1, 2].map(|a| m.nodes[face[a]]);
                let (d1, d2) = (sub(p[1], p[0]), sub(p[2], p[1]));
                let normal = cross(d1, d2);
                assert!(
                    normal[axis] * sign > 0.0,
                    "face {} points inward",
                    FACE_NAMES[f]
                );
                // straight-sided rectangles: the corners' quadrilateral area
                side_area += (d1[0].powi(2) + d1[1].powi(2) + d1[2].powi(2)).sqrt()
                    * (d2[0].powi(2) + d2[1].powi(2) + d2[2].powi(2)).sqrt();
            }
            assert!(
                (side_area - expected).abs() < 1e-12,
                "{}: {side_area}",
                FACE_NAMES[f]
            );
            area += side_area;
        }
        assert!((area - 2.0 * (15.0 + 10.0 + 6.0)).abs() < 1e-12);
    }

    fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    fn on_boundary(x: [f64; 3]) -> bool {
        x[0] == 0.0 || x[0] == 5.0 || x[1] == 0.0 || x[1] == 3.0 || x[2] == -1.0 || x[2] == 1.0
    }

    /// The graded box with its interior nodes moved off the lattice (by at
    /// most 0.12 mm: the elements stay valid, their edges curve).
    fn distorted() -> BoxMesh {
        let mut m = graded();
        for (n, x) in m.nodes.iter_mut().enumerate() {
            if !on_boundary(*x) {
                let s = (n as f64 * 0.7).sin();
                x[0] += 0.12 * s;
                x[1] -= 0.08 * s;
                x[2] += 0.05 * (n as f64 * 1.3).cos();
            }
        }
        m
    }

    /// The patch test in 3D, assembled: a linear displacement field given on
    /// the boundary of the box: the largest error at an interior node, mm.
    fn patch_error(m: &BoxMesh, full: bool) -> f64 {
        let field = |x: [f64; 3]| {
            [
                1e-3 * x[0] + 2e-4 * x[1] - 3e-4 * x[2] + 0.01,
                -5e-4 * x[0] + 7e-4 * x[1] + 1e-4 * x[2] - 0.02,
                3e-4 * x[0] - 2e-4 * x[1] + 9e-4 * x[2] + 0.005,
            ]
        };
        let mat = VonMises::new(210_000.0, 0.3, f64::INFINITY, 0.0, Plane::Strain).unwrap();
        {
            let rule = Family3::H20.rule(full);
            let nd = 3 * m.nodes.len();
            let mut k = DMatrix::<f64>::zeros(nd, nd);
            for el in &m.elements {
                let c: Vec<[f64; 3]> = el.iter().map(|&a| m.nodes[a]).collect();
                let g = ElementGeometry3::new(Family3::H20, &c, &rule).unwrap();
                let committed = vec![PointState::default(); g.n];
                let mut trial = committed.clone();
                let (mut fe, mut ke) = (vec![0.0; 60], vec![0.0; 3600]);
                forces3(
                    &g,
                    &mat,
                    &[0.0; 60],
                    &committed,
                    &mut trial,
                    Response::Plastic,
                    Some(Tangent::Elastic),
                    &mut fe,
                    &mut ke,
                )
                .unwrap();
                for a in 0..60 {
                    for b in 0..60 {
                        k[(3 * el[a / 3] + a % 3, 3 * el[b / 3] + b % 3)] += ke[a * 60 + b];
                    }
                }
            }
            // K_ff u_f = −K_fp u_p
            let fixed: Vec<bool> = m.nodes.iter().flat_map(|&x| [on_boundary(x); 3]).collect();
            let free: Vec<usize> = (0..nd).filter(|&d| !fixed[d]).collect();
            let given: Vec<f64> = m.nodes.iter().flat_map(|&x| field(x)).collect();
            let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
            let rhs = DVector::from_fn(free.len(), |i, _| {
                -(0..nd)
                    .filter(|&d| fixed[d])
                    .map(|d| k[(free[i], d)] * given[d])
                    .sum::<f64>()
            });
            let u = kff.cholesky().expect("K_ff positive definite").solve(&rhs);
            assert!(!free.is_empty());
            free.iter()
                .zip(u.iter())
                .map(|(&d, v)| (v - given[d]).abs())
                .fold(0.0, f64::max)
        }
    }

    /// Full integration passes the patch test on curved (distorted) H20 and
    /// reduced integration on straight-sided parallelepipeds; reduced
    /// integration of a curved H20 does not integrate the divergence theorem
    /// exactly and misses the linear field (by 2.5e-6 mm of a field of
    /// 0.016 mm here, interior nodes moved by up to 0.12 mm in elements of
    /// 0.5-2 mm), which the full rule does not.
    #[test]
    fn an_assembled_box_passes_the_patch_test() {
        let full = patch_error(&distorted(), true);
        assert!(full < 1e-12, "full rule, distorted: {full:e} mm");
        let reduced = patch_error(&graded(), false);
        assert!(reduced < 1e-12, "reduced rule, graded: {reduced:e} mm");
        let curved = patch_error(&distorted(), false);
        println!("patch errors, mm: full distorted {full:e}, reduced graded {reduced:e}, reduced distorted {curved:e}");
        assert!(
            curved > 1e-9 && curved < 1e-4,
            "reduced rule, distorted: {curved:e} mm"
        );
    }

    /// Lamé's thick-walled cylinder in plane strain as a quarter of a 3D
    /// sector (symmetry planes θ = 0, 90°, z held on both faces), bore
    /// pressure on the curved face: the radial displacement at every node
    /// against u_r = (1+ν)/E · p a²/(b²−a²) · ((1−2ν) r + b²/r), converging
    /// as the mesh is halved.
    #[test]
    fn a_quarter_cylinder_in_3d_matches_lame() {
        let (a, b, p, e, nu) = (10.0, 20.0, 100.0, 210_000.0, 0.3);
        let exact = |r: f64| {
            (1.0 + nu) / e * p * a * a / (b * b - a * a) * ((1.0 - 2.0 * nu) * r + b * b / r)
        };
        let mat = VonMises::new(e, nu, f64::INFINITY, 0.0, Plane::Strain).unwrap();
        let mut errors = Vec::new();
        for (nr, nt) in [(1, 2), (2, 4), (4, 8)] {
            let r = graded_axis("c", "r", &[a, b], &[nr], &[], 1).unwrap();
            let t = graded_axis("c", "t", &[0.0, 90.0], &[nt], &[], 1).unwrap();
            let m = sector_mesh("c", [&r, &t, &[0.0, 2.0]]);
            let nd = 3 * m.nodes.len();
            let mut k = DMatrix::<f64>::zeros(nd, nd);
            let rule = Family3::H20.rule(true);
            for el in &m.elements {
                let c: Vec<[f64; 3]> = el.iter().map(|&n| m.nodes[n]).collect();
                let g = ElementGeometry3::new(Family3::H20, &c, &rule).unwrap();
                let committed = vec![PointState::default(); g.n];
                let mut trial = committed.clone();
                let (mut fe, mut ke) = (vec![0.0; 60], vec![0.0; 3600]);
                forces3(
                    &g,
                    &mat,
                    &[0.0; 60],
                    &committed,
                    &mut trial,
                    Response::Plastic,
                    Some(Tangent::Elastic),
                    &mut fe,
                    &mut ke,
                )
                .unwrap();
                for i in 0..60 {
                    for j in 0..60 {
                        k[(3 * el[i / 3] + i % 3, 3 * el[j / 3] + j % 3)] += ke[i * 60 + j];
                    }
                }
            }
            let mut f = DVector::<f64>::zeros(nd);
            for face in &m.faces["c.rmin"] {
                let x = face.map(|n| m.nodes[n]);
                for (q, fq) in crate::physics::element::face::pressure_forces(&x, p)
                    .iter()
                    .enumerate()
                {
                    for c in 0..3 {
                        f[3 * face[q] + c] += fq[c];
                    }
                }
            }
            // supports: uy on θ = 0, ux on θ = 90°, uz on both z faces
            let mut fixed = vec![false; nd];
            for (set, c) in [("c.tmin", 1), ("c.tmax", 0), ("c.zmin", 2), ("c.zmax", 2)] {
                for face in &m.faces[set] {
                    for &n in face {
                        fixed[3 * n + c] = true;
                    }
                }
            }
            let free: Vec<usize> = (0..nd).filter(|&d| !fixed[d]).collect();
            let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
            let ff = DVector::from_fn(free.len(), |i, _| f[free[i]]);
            let uf = kff
                .cholesky()
                .expect("supported: K_ff positive definite")
                .solve(&ff);
            let mut u = vec![0.0; nd];
            for (i, &d) in free.iter().enumerate() {
                u[d] = uf[i];
            }
            let mut worst = 0.0f64;
            for (n, x) in m.nodes.iter().enumerate() {
                let r = x[0].hypot(x[1]);
                let ur = (u[3 * n] * x[0] + u[3 * n + 1] * x[1]) / r;
                let ut = (-u[3 * n] * x[1] + u[3 * n + 1] * x[0]) / r;
                worst = worst.max((ur - exact(r)).abs()).max(ut.abs());
            }
            errors.push(worst / exact(a));
        }
        println!("Lamé in 3D, largest nodal error / u_r(a): {errors:?}");
        for w in errors.windows(2) {
            let order = (w[0] / w[1]).log2();
            assert!(order > 2.5, "order {order} from {errors:?}");
        }
        assert!(errors[2] < 1e-4, "{errors:?}");
    }
}
