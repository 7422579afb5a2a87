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
    let lattice = Lattice::new(axes);
    let n = lattice.cells;
    // no face or body centres: at most one odd index
    let (nodes, id) = lattice.points(|p| p.iter().map(|i| i % 2).sum::<usize>() < 2);
    let index = |i: usize, j: usize, k: usize| lattice.index([i, j, k]);
    let mut elements = Vec::with_capacity(n[0] * n[1] * n[2]);
    let mut faces = empty_faces(name);
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

/// The (2n+1) points per axis of a graded box: its corners at even indices,
/// the midpoints between them at odd ones.
struct Lattice<'a> {
    axes: [&'a [f64]; 3],
    /// Cells per axis.
    cells: [usize; 3],
    /// Points per axis, 2 cells + 1.
    dims: [usize; 3],
}

impl<'a> Lattice<'a> {
    fn new(axes: [&'a [f64]; 3]) -> Self {
        let cells = axes.map(|a| a.len() - 1);
        Lattice {
            axes,
            cells,
            dims: cells.map(|k| 2 * k + 1),
        }
    }

    fn index(&self, [i, j, k]: [usize; 3]) -> usize {
        (k * self.dims[1] + j) * self.dims[0] + i
    }

    fn coordinate(&self, axis: usize, i: usize) -> f64 {
        let a = self.axes[axis];
        if i % 2 == 0 {
            a[i / 2]
        } else {
            0.5 * (a[i / 2] + a[i / 2 + 1])
        }
    }

    /// The points that `keep`, in index order, and each lattice index's
    /// node (usize::MAX where not kept).
    fn points(&self, keep: impl Fn([usize; 3]) -> bool) -> (Vec<[f64; 3]>, Vec<usize>) {
        let mut id = vec![usize::MAX; self.dims.iter().product()];
        let mut nodes = Vec::new();
        for k in 0..self.dims[2] {
            for j in 0..self.dims[1] {
                for i in 0..self.dims[0] {
                    if keep([i, j, k]) {
                        id[self.index([i, j, k])] = nodes.len();
                        nodes.push([
                            self.coordinate(0, i),
                            self.coordinate(1, j),
                            self.coordinate(2, k),
                        ]);
                    }
                }
            }
        }
        (nodes, id)
    }
}

/// The six face sets of a box, empty.
fn empty_faces<F>(name: &str) -> BTreeMap<String, Vec<F>> {
    FACE_NAMES
        .iter()
        .map(|f| (format!("{name}.{f}"), Vec::new()))
        .collect()
}

/// A sector of a thick-walled cylinder about the z axis: the box on the
/// axes [r, θ (degrees), z] mapped to x = r cos θ, y = r sin θ, so that the
/// midside nodes of the circumferential edges lie on their arcs. The map
/// keeps the orientation (its Jacobian is r > 0): faces stay outward. Its
/// face sets are `<name>.rmin` (the bore), `.rmax`, `.tmin` (θ at its
/// start), `.tmax`, `.zmin`, `.zmax`.
pub(crate) fn sector_mesh(name: &str, axes: [&[f64]; 3]) -> BoxMesh {
    let m = box_mesh(name, axes);
    BoxMesh {
        nodes: to_sector(m.nodes),
        elements: m.elements,
        faces: sector_faces(name, m.faces),
    }
}

/// [`sector_mesh`] in 10-node tetrahedra ([`tet_box_mesh`]).
pub(crate) fn tet_sector_mesh(name: &str, axes: [&[f64]; 3]) -> TetMesh {
    let m = tet_box_mesh(name, axes);
    TetMesh {
        nodes: to_sector(m.nodes),
        elements: m.elements,
        faces: sector_faces(name, m.faces),
    }
}

/// Points (r, θ in degrees, z) to (x, y, z).
fn to_sector(mut nodes: Vec<[f64; 3]>) -> Vec<[f64; 3]> {
    for x in &mut nodes {
        let (r, t) = (x[0], x[1].to_radians());
        *x = [r * t.cos(), r * t.sin(), x[2]];
    }
    nodes
}

/// A box's face sets under the names of a sector's.
fn sector_faces<F>(name: &str, mut faces: BTreeMap<String, Vec<F>>) -> BTreeMap<String, Vec<F>> {
    FACE_NAMES
        .iter()
        .zip(SECTOR_FACE_NAMES)
        .map(|(f, s)| {
            let list = faces.remove(&format!("{name}.{f}")).unwrap_or_default();
            (format!("{name}.{s}"), list)
        })
        .collect()
}

/// A box of 10-node tetrahedra: each cell of the graded box split into six
/// along its diagonal from its lowest to its highest corner (Kuhn's
/// subdivision: the face diagonals of neighbouring cells agree, so the mesh
/// is conforming), each tetrahedron's corners ordered for a positive volume
/// and its midside nodes at the midpoints of its edges (points of the full
/// lattice: cell edges, face centres, cell centres). Faces as [`box_mesh`]'s,
/// 6-node triangles numbered as [`crate::physics::element::t10::FACES`].
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct TetMesh {
    pub(crate) nodes: Vec<[f64; 3]>,
    pub(crate) elements: Vec<[usize; 10]>,
    pub(crate) faces: BTreeMap<String, Vec<[usize; 6]>>,
}

/// The tetrahedral box on the corner coordinates `axes` ([`box_mesh`]).
pub(crate) fn tet_box_mesh(name: &str, axes: [&[f64]; 3]) -> TetMesh {
    use crate::physics::element::t10;
    let lattice = Lattice::new(axes);
    let n = lattice.cells;
    // every lattice point is a node: its index is its number
    let (nodes, _) = lattice.points(|_| true);
    let index = |p: [usize; 3]| lattice.index(p);
    const PATHS: [[usize; 3]; 6] = [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [0, 2, 1],
        [2, 1, 0],
        [1, 0, 2],
    ];
    let mut elements = Vec::with_capacity(6 * n[0] * n[1] * n[2]);
    let mut faces = empty_faces(name);
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                for (q, path) in PATHS.iter().enumerate() {
                    // lattice corners: the lowest, then one axis at a time
                    let mut c = [[2 * i, 2 * j, 2 * k]; 4];
                    for s in 0..3 {
                        c[s + 1] = c[s];
                        c[s + 1][path[s]] += 2;
                    }
                    if q >= 3 {
                        // an odd permutation: its volume is negative until turned
                        c.swap(1, 2);
                    }
                    let el: [usize; 10] = std::array::from_fn(|a| {
                        let (u, v) = match a {
                            0..=3 => (a, a),
                            _ => T10_EDGE_ENDS[a - 4],
                        };
                        index(std::array::from_fn(|d| (c[u][d] + c[v][d]) / 2))
                    });
                    for face in t10::FACES {
                        let side = (0..3).find_map(|d| {
                            let vals = [0, 1, 2].map(|s| c[face[s]][d]);
                            let same = vals.iter().all(|&v| v == vals[0]);
                            match (same, vals[0]) {
                                (true, 0) => Some([5, 2, 0][d]),
                                (true, v) if v == 2 * n[d] => Some([3, 4, 1][d]),
                                _ => None,
                            }
                        });
                        if let Some(s) = side {
                            let key = format!("{name}.{}", FACE_NAMES[s]);
                            faces.get_mut(&key).unwrap().push(face.map(|a| el[a]));
                        }
                    }
                    elements.push(el);
                }
            }
        }
    }
    TetMesh {
        nodes,
        elements,
        faces,
    }
}

/// The corners joined by each midside node of the T10 (nodes 4 to 9).
const T10_EDGE_ENDS: [(usize, usize); 6] = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::mesh::blocks::graded_axis;
    use crate::physics::element::face;
    use crate::physics::element::family::Family;
    use crate::physics::element::solid::{Response, Tangent};
    use crate::physics::element::solid3::{forces3, ElementGeometry3, Family3};
    use crate::physics::material::{Plane, PointState, VonMises};
    use nalgebra::{DMatrix, DVector};

    fn axes() -> [Vec<f64>; 3] {
        [
            graded_axis("b", "x", &[0.0, 2.0, 5.0], &[2, 1], &[0.5, 1.0], 1).unwrap(),
            graded_axis("b", "y", &[0.0, 3.0], &[2], &[3.0], 1).unwrap(),
            graded_axis("b", "z", &[-1.0, 1.0], &[3], &[1.0], 1).unwrap(),
        ]
    }

    fn graded() -> BoxMesh {
        let [x, y, z] = axes();
        box_mesh("b", [&x, &y, &z])
    }

    fn graded_tets() -> TetMesh {
        let [x, y, z] = axes();
        tet_box_mesh("b", [&x, &y, &z])
    }

    /// A mesh as the tests below use it: its family, nodes and elements.
    struct Solid {
        family: Family3,
        nodes: Vec<[f64; 3]>,
        elements: Vec<Vec<usize>>,
    }

    impl From<BoxMesh> for Solid {
        fn from(m: BoxMesh) -> Self {
            let elements = m.elements.iter().map(|e| e.to_vec()).collect();
            Solid {
                family: Family3::H20,
                nodes: m.nodes,
                elements,
            }
        }
    }

    impl From<TetMesh> for Solid {
        fn from(m: TetMesh) -> Self {
            let elements = m.elements.iter().map(|e| e.to_vec()).collect();
            Solid {
                family: Family3::T10,
                nodes: m.nodes,
                elements,
            }
        }
    }

    impl Solid {
        fn geometry(&self, el: &[usize], full: bool) -> ElementGeometry3 {
            let c: Vec<[f64; 3]> = el.iter().map(|&a| self.nodes[a]).collect();
            ElementGeometry3::new(self.family, &c, &self.family.rule(full)).unwrap()
        }

        /// The elastic stiffness, dense.
        fn stiffness(&self, mat: &VonMises, full: bool) -> DMatrix<f64> {
            let nd = 3 * self.nodes.len();
            let mut k = DMatrix::<f64>::zeros(nd, nd);
            for el in &self.elements {
                let g = self.geometry(el, full);
                let ne = g.dofs();
                let committed = vec![PointState::default(); g.n];
                let mut trial = committed.clone();
                let (mut fe, mut ke) = (vec![0.0; ne], vec![0.0; ne * ne]);
                let ue = vec![0.0; ne];
                forces3(
                    &g,
                    mat,
                    &[0.0; crate::physics::element::family3::MAX_POINTS3],
                    &ue,
                    &committed,
                    &mut trial,
                    Response::Plastic,
                    Some(Tangent::Elastic),
                    &mut fe,
                    &mut ke,
                )
                .unwrap();
                for a in 0..ne {
                    for b in 0..ne {
                        k[(3 * el[a / 3] + a % 3, 3 * el[b / 3] + b % 3)] += ke[a * ne + b];
                    }
                }
            }
            k
        }
    }

    /// u with u = `given` where `fixed`, K_ff u_f = f_f − K_fp u_p elsewhere.
    fn solve(k: &DMatrix<f64>, f: &[f64], fixed: &[bool], given: &[f64]) -> Vec<f64> {
        let nd = f.len();
        let free: Vec<usize> = (0..nd).filter(|&d| !fixed[d]).collect();
        assert!(!free.is_empty());
        let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
        let rhs = DVector::from_fn(free.len(), |i, _| {
            f[free[i]]
                - (0..nd)
                    .filter(|&d| fixed[d])
                    .map(|d| k[(free[i], d)] * given[d])
                    .sum::<f64>()
        });
        let uf = kff
            .cholesky()
            .expect("supported: K_ff positive definite")
            .solve(&rhs);
        let mut u: Vec<f64> = given.to_vec();
        for (i, &d) in free.iter().enumerate() {
            u[d] = uf[i];
        }
        u
    }

    fn elastic() -> VonMises {
        VonMises::new(210_000.0, 0.3, f64::INFINITY, 0.0, Plane::Strain).unwrap()
    }

    fn counts_volume_and_jacobians(m: &Solid, elements: usize, nodes: usize) {
        assert_eq!(m.elements.len(), elements);
        assert_eq!(m.nodes.len(), nodes);
        let mut volume = 0.0;
        let mut used = vec![false; m.nodes.len()];
        for el in &m.elements {
            let g = m.geometry(el, true);
            assert!(g.dv[..g.n].iter().all(|&v| v > 0.0));
            volume += g.volume();
            for (a, &n) in el.iter().enumerate() {
                assert!(!el[..a].contains(&n));
                used[n] = true;
            }
        }
        assert!((volume - 5.0 * 3.0 * 2.0).abs() < 1e-12, "{volume}");
        assert!(used.iter().all(|&u| u), "a node of no element");
    }

    #[test]
    fn counts_volume_and_every_jacobian_of_a_graded_box() {
        let (nx, ny, nz) = (3, 2, 3);
        // hexahedra: corners, then midsides on the edges along x, y and z
        let corners = (nx + 1) * (ny + 1) * (nz + 1);
        let mids = nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
        counts_volume_and_jacobians(&graded().into(), nx * ny * nz, corners + mids);
        // tetrahedra: the whole lattice
        let lattice = (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1);
        counts_volume_and_jacobians(&graded_tets().into(), 6 * nx * ny * nz, lattice);
    }

    /// Each face set of both boxes lies on its side, faces outward, and
    /// covers the side's area.
    #[test]
    fn each_face_set_lies_on_its_side_and_faces_outward() {
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
        let hexes = graded();
        let tets = graded_tets();
        for (f, &(axis, value, sign)) in sides.iter().enumerate() {
            let key = format!("b.{}", FACE_NAMES[f]);
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let expected = (hi[u] - lo[u]) * (hi[v] - lo[v]);
            // a face by its corners: a rectangle (4) or a triangle (3)
            let corners: Vec<Vec<[f64; 3]>> = hexes.faces[&key]
                .iter()
                .map(|q| q[..4].iter().map(|&n| hexes.nodes[n]).collect())
                .chain(
                    tets.faces[&key]
                        .iter()
                        .map(|t| t[..3].iter().map(|&n| tets.nodes[n]).collect()),
                )
                .collect();
            let (mut hex_area, mut tet_area) = (0.0, 0.0);
            for (q, c) in corners.iter().enumerate() {
                assert!(c.iter().all(|x| x[axis] == value), "{key}");
                let normal = cross(sub(c[1], c[0]), sub(c[2], c[1]));
                assert!(normal[axis] * sign > 0.0, "{key}: a face points inward");
                let twice = normal[axis].abs();
                if q < hexes.faces[&key].len() {
                    hex_area += twice;
                } else {
                    tet_area += 0.5 * twice;
                }
            }
            assert!((hex_area - expected).abs() < 1e-12, "{key}: {hex_area}");
            assert!((tet_area - expected).abs() < 1e-12, "{key}: {tet_area}");
            // the midside nodes of each face lie on the side too
            assert!(hexes.faces[&key]
                .iter()
                .flatten()
                .all(|&n| hexes.nodes[n][axis] == value));
            assert!(tets.faces[&key]
                .iter()
                .flatten()
                .all(|&n| tets.nodes[n][axis] == value));
        }
    }

    use crate::numbers::vec3::{cross, sub};

    fn on_boundary(x: [f64; 3]) -> bool {
        x[0] == 0.0 || x[0] == 5.0 || x[1] == 0.0 || x[1] == 3.0 || x[2] == -1.0 || x[2] == 1.0
    }

    /// The mesh with its interior nodes moved off the lattice (by at most
    /// 0.12 mm: the elements stay valid, their edges curve).
    fn distorted(mut m: Solid) -> Solid {
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
    fn patch_error(m: &Solid, full: bool) -> f64 {
        let field = |x: [f64; 3]| {
            [
                1e-3 * x[0] + 2e-4 * x[1] - 3e-4 * x[2] + 0.01,
                -5e-4 * x[0] + 7e-4 * x[1] + 1e-4 * x[2] - 0.02,
                3e-4 * x[0] - 2e-4 * x[1] + 9e-4 * x[2] + 0.005,
            ]
        };
        let k = m.stiffness(&elastic(), full);
        // the box's own boundary (its nodes were not moved)
        let fixed: Vec<bool> = m.nodes.iter().flat_map(|&x| [on_boundary(x); 3]).collect();
        let given: Vec<f64> = m.nodes.iter().flat_map(|&x| field(x)).collect();
        let u = solve(&k, &vec![0.0; given.len()], &fixed, &given);
        u.iter()
            .zip(&given)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    }

    /// The patch test for both families: the full rule (27 points, 14 for
    /// the tetrahedron) passes on curved elements, the reduced one (8, 4) on
    /// straight-sided ones only: on a curved element it does not integrate
    /// the divergence theorem exactly and misses the linear field (by
    /// 2.5e-6 mm of a field of 0.016 mm for the hexahedra here, interior
    /// nodes moved by up to 0.12 mm in elements of 0.5-2 mm), which the
    /// full rule does not.
    #[test]
    fn an_assembled_box_passes_the_patch_test() {
        for (name, straight) in [
            ("H20", Solid::from(graded())),
            ("T10", Solid::from(graded_tets())),
        ] {
            let curved = distorted(Solid {
                family: straight.family,
                nodes: straight.nodes.clone(),
                elements: straight.elements.clone(),
            });
            let full = patch_error(&curved, true);
            assert!(full < 1e-12, "{name} full rule, curved: {full:e} mm");
            let reduced = patch_error(&straight, false);
            assert!(
                reduced < 1e-12,
                "{name} reduced rule, straight: {reduced:e} mm"
            );
            let miss = patch_error(&curved, false);
            println!("{name} patch errors, mm: full curved {full:e}, reduced straight {reduced:e}, reduced curved {miss:e}");
            assert!(
                miss > 1e-9 && miss < 1e-4,
                "{name} reduced rule, curved: {miss:e} mm"
            );
        }
    }

    /// Lamé's thick-walled cylinder in plane strain as a quarter of a 3D
    /// sector (symmetry planes θ = 0, 90°, z held on both faces), bore
    /// pressure on the curved face, in hexahedra (the default rule, 27
    /// points): the radial displacement at every node against
    /// u_r = (1+ν)/E · p a²/(b²−a²) · ((1−2ν) r + b²/r), converging as the
    /// mesh is halved. The largest nodal error of the hexahedra falls at
    /// order 3.3, 3.7 (9.2e-3, 9.5e-4, 7.3e-5 of u_r(a)); that of the
    /// tetrahedra of Kuhn's subdivision at 1.9, 2.5, then 2.2 one level
    /// finer (2.9e-2, 7.6e-3, 1.3e-3, 2.9e-4): quadratic, without the
    /// nodal superconvergence of the tensor-product hexahedron.
    #[test]
    fn a_quarter_cylinder_in_3d_matches_lame() {
        let (a, b, p, e, nu) = (10.0, 20.0, 100.0, 210_000.0, 0.3);
        let exact = |r: f64| {
            (1.0 + nu) / e * p * a * a / (b * b - a * a) * ((1.0 - 2.0 * nu) * r + b * b / r)
        };
        for family in [Family3::H20, Family3::T10] {
            let mut errors = Vec::new();
            for (nr, nt) in [(1, 2), (2, 4), (4, 8)] {
                let r = graded_axis("c", "r", &[a, b], &[nr], &[], 1).unwrap();
                let t = graded_axis("c", "t", &[0.0, 90.0], &[nt], &[], 1).unwrap();
                let axes = [&r[..], &t[..], &[0.0, 2.0][..]];
                // the mesh, and each face set as lists of nodes, whichever family
                let lists = |m: &BTreeMap<String, Vec<Vec<usize>>>| m.clone();
                let (solid, faces, face_family) = match family {
                    Family3::H20 => {
                        let m = sector_mesh("c", axes);
                        let f = m
                            .faces
                            .iter()
                            .map(|(k, v)| (k.clone(), v.iter().map(|q| q.to_vec()).collect()))
                            .collect();
                        (Solid::from(m), lists(&f), Family::Q8)
                    }
                    Family3::T10 => {
                        let m = tet_sector_mesh("c", axes);
                        let f = m
                            .faces
                            .iter()
                            .map(|(k, v)| (k.clone(), v.iter().map(|q| q.to_vec()).collect()))
                            .collect();
                        (Solid::from(m), lists(&f), Family::T6)
                    }
                };
                let k = solid.stiffness(&elastic(), true);
                let nd = 3 * solid.nodes.len();
                let mut f = vec![0.0; nd];
                for face in &faces["c.rmin"] {
                    let x: Vec<[f64; 3]> = face.iter().map(|&n| solid.nodes[n]).collect();
                    let forces = face::pressure_forces(face_family, &x, p);
                    for (q, fq) in forces.iter().enumerate().take(face.len()) {
                        for c in 0..3 {
                            f[3 * face[q] + c] += fq[c];
                        }
                    }
                }
                // supports: uy on θ = 0, ux on θ = 90°, uz on both z faces
                let mut fixed = vec![false; nd];
                for (set, c) in [("c.tmin", 1), ("c.tmax", 0), ("c.zmin", 2), ("c.zmax", 2)] {
                    for &n in faces[set].iter().flatten() {
                        fixed[3 * n + c] = true;
                    }
                }
                let u = solve(&k, &f, &fixed, &vec![0.0; nd]);
                let mut worst = 0.0f64;
                for (n, x) in solid.nodes.iter().enumerate() {
                    let r = x[0].hypot(x[1]);
                    let ur = (u[3 * n] * x[0] + u[3 * n + 1] * x[1]) / r;
                    let ut = (-u[3 * n] * x[1] + u[3 * n + 1] * x[0]) / r;
                    worst = worst.max((ur - exact(r)).abs()).max(ut.abs());
                }
                errors.push(worst / exact(a));
            }
            println!("Lamé in 3D, {family:?}, largest nodal error / u_r(a): {errors:?}");
            let (least_order, finest) = match family {
                Family3::H20 => (2.5, 1e-4),
                Family3::T10 => (1.8, 2e-3),
            };
            for w in errors.windows(2) {
                let order = (w[0] / w[1]).log2();
                assert!(
                    order > least_order,
                    "{family:?}: order {order} from {errors:?}"
                );
            }
            assert!(errors[2] < finest, "{family:?}: {errors:?}");
        }
    }
}
