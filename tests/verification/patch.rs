//! Patch tests: a mesh of distorted 8-node elements reproduces any linear
//! displacement field exactly (constant strain and stress), both plane states,
//! full and reduced integration.

use asperity::physics::element::element_forces;
use asperity::physics::element::family::Family;
use asperity::physics::element::solid::{ElementGeometry, Response, Tangent};
use asperity::physics::material::{Plane, PointState, VonMises};
use nalgebra::{DMatrix, DVector};

/// 2×2 elements on [0,4]² with the centre node and midsides moved off-grid.
pub(crate) fn patch() -> (Vec<[f64; 2]>, Vec<[usize; 8]>) {
    // 5×5 grid of candidate points (corners and midsides), centres unused
    let mut nodes = Vec::new();
    let mut id = [[usize::MAX; 5]; 5];
    for (j, row) in id.iter_mut().enumerate() {
        for (i, slot) in row.iter_mut().enumerate() {
            if i % 2 == 1 && j % 2 == 1 {
                continue;
            }
            let (mut x, mut y) = (i as f64, j as f64);
            if (1..4).contains(&i) && (1..4).contains(&j) {
                x += 0.23 * ((i * 3 + j) as f64).sin();
                y += 0.19 * ((i + 5 * j) as f64).cos();
            }
            *slot = nodes.len();
            nodes.push([x, y]);
        }
    }
    let mut els = Vec::new();
    for ej in 0..2 {
        for ei in 0..2 {
            let (i, j) = (2 * ei, 2 * ej);
            els.push([
                id[j][i],
                id[j][i + 2],
                id[j + 2][i + 2],
                id[j + 2][i],
                id[j][i + 1],
                id[j + 1][i + 2],
                id[j + 2][i + 1],
                id[j + 1][i],
            ]);
        }
    }
    (nodes, els)
}

#[test]
fn linear_fields_are_reproduced_to_round_off() {
    let (nodes, els) = patch();
    let els: Vec<Mixed> = els.iter().map(|e| (Family::Q8, e.to_vec())).collect();
    check_patch(&nodes, &els, 1e-9);
}

/// An element of a mixed mesh: its family and its nodes.
type Mixed = (Family, Vec<usize>);

/// The 5×5 grid on [0, 4]² with every interior point moved off-grid (the
/// same moves as [`patch`]), meshed as two 6-node triangles in the lower
/// left and upper right squares (split along opposite diagonals) and 8-node
/// quads in the other two: a mixed mesh whose triangles and quads share
/// straight but distorted sides. Only the points some element uses are
/// nodes.
fn mixed_patch() -> (Vec<[f64; 2]>, Vec<Mixed>) {
    let point = |i: usize, j: usize| {
        let (mut x, mut y) = (i as f64, j as f64);
        if (1..4).contains(&i) && (1..4).contains(&j) {
            x += 0.23 * ((i * 3 + j) as f64).sin();
            y += 0.19 * ((i + 5 * j) as f64).cos();
        }
        [x, y]
    };
    let g = |i: usize, j: usize| (i, j);
    // each element: its family and its nodes as grid points (i, j)
    type Cell = (Family, Vec<(usize, usize)>);
    let mut cells: Vec<Cell> = vec![
        (
            Family::T6,
            vec![g(0, 0), g(2, 0), g(2, 2), g(1, 0), g(2, 1), g(1, 1)],
        ),
        (
            Family::T6,
            vec![g(0, 0), g(2, 2), g(0, 2), g(1, 1), g(1, 2), g(0, 1)],
        ),
        (
            Family::T6,
            vec![g(2, 2), g(4, 2), g(2, 4), g(3, 2), g(3, 3), g(2, 3)],
        ),
        (
            Family::T6,
            vec![g(4, 2), g(4, 4), g(2, 4), g(4, 3), g(3, 4), g(3, 3)],
        ),
    ];
    for (i, j) in [(2, 0), (0, 2)] {
        let q = vec![
            g(i, j),
            g(i + 2, j),
            g(i + 2, j + 2),
            g(i, j + 2),
            g(i + 1, j),
            g(i + 2, j + 1),
            g(i + 1, j + 2),
            g(i, j + 1),
        ];
        cells.push((Family::Q8, q));
    }
    let mut id = std::collections::BTreeMap::new();
    let mut nodes = Vec::new();
    let els = cells
        .into_iter()
        .map(|(f, pts)| {
            let ns = pts
                .into_iter()
                .map(|(i, j)| {
                    *id.entry((i, j)).or_insert_with(|| {
                        nodes.push(point(i, j));
                        nodes.len() - 1
                    })
                })
                .collect();
            (f, ns)
        })
        .collect();
    (nodes, els)
}

/// The patch test on a mixed mesh of distorted 6-node triangles and 8-node
/// quads, both rules of each, both plane states: any linear displacement
/// field is reproduced at every node to 1e-14 and the stress at every Gauss
/// point is D ε to 1e-10 (Zienkiewicz, Taylor & Zhu, 7th ed., sec. 9.3, the
/// patch test as the test of consistency and stability).
#[test]
fn linear_fields_are_reproduced_on_a_mixed_mesh_of_triangles_and_quads() {
    let (nodes, els) = mixed_patch();
    check_patch(&nodes, &els, 1e-10);
}

/// The patch test on the elements `els` of the [0, 4]² square with nodes
/// `nodes`: the boundary prescribed to a linear field, the interior solved,
/// both rules, both plane states; every node to 1e-14, the stress at every
/// Gauss point D ε to `stress_tol` of its largest component.
fn check_patch(nodes: &[[f64; 2]], els: &[Mixed], stress_tol: f64) {
    let n = nodes.len();
    let exact = |x: [f64; 2]| {
        [
            1e-3 * (2.0 * x[0] - 0.7 * x[1]) + 0.01,
            1e-3 * (0.4 * x[0] + 1.1 * x[1]) - 0.02,
        ]
    };
    let boundary: Vec<bool> = nodes
        .iter()
        .map(|x| x[0] == 0.0 || x[0] == 4.0 || x[1] == 0.0 || x[1] == 4.0)
        .collect();
    for plane in [Plane::Stress, Plane::Strain] {
        for full in [true, false] {
            let mat = VonMises::new(100000.0, 0.25, f64::INFINITY, 0.0, plane).unwrap();
            let geoms: Vec<_> = els
                .iter()
                .map(|(f, e)| {
                    let c: Vec<[f64; 2]> = e.iter().map(|&a| nodes[a]).collect();
                    ElementGeometry::new(*f, &c, &f.rule(full), 1.0).unwrap()
                })
                .collect();
            let forces = |e: usize, ue: &[f64], ke: Option<&mut Vec<f64>>| {
                let ne = ue.len();
                let zero = vec![PointState::default(); geoms[e].n];
                let mut st = zero.clone();
                let (mut fe, mut scratch) = (vec![0.0; ne], vec![0.0; ne * ne]);
                let tangent = ke.is_some().then_some(Tangent::Consistent);
                let k = ke.unwrap_or(&mut scratch);
                element_forces(
                    &geoms[e],
                    &mat,
                    &[0.0; 9],
                    ue,
                    &zero,
                    &mut st,
                    Response::Plastic,
                    tangent,
                    &mut fe,
                    k,
                )
                .unwrap();
                st
            };
            let mut k = DMatrix::<f64>::zeros(2 * n, 2 * n);
            for (e, (_, el)) in els.iter().enumerate() {
                let ne = 2 * el.len();
                let mut ke = vec![0.0; ne * ne];
                forces(e, &vec![0.0; ne], Some(&mut ke));
                for a in 0..ne {
                    for b in 0..ne {
                        k[(2 * el[a / 2] + a % 2, 2 * el[b / 2] + b % 2)] += ke[a * ne + b];
                    }
                }
            }
            let mut u = DVector::<f64>::zeros(2 * n);
            for i in (0..n).filter(|&i| boundary[i]) {
                let v = exact(nodes[i]);
                (u[2 * i], u[2 * i + 1]) = (v[0], v[1]);
            }
            let free: Vec<usize> = (0..2 * n).filter(|&d| !boundary[d / 2]).collect();
            let kff = DMatrix::from_fn(free.len(), free.len(), |r, c| k[(free[r], free[c])]);
            let rhs = DVector::from_fn(free.len(), |r, _| {
                -(0..2 * n)
                    .filter(|&d| boundary[d / 2])
                    .map(|d| k[(free[r], d)] * u[d])
                    .sum::<f64>()
            });
            let sol = kff
                .lu()
                .solve(&rhs)
                .expect("the patch's stiffness is regular");
            for (r, &d) in free.iter().enumerate() {
                u[d] = sol[r];
            }
            for i in 0..n {
                let v = exact(nodes[i]);
                assert!(
                    (u[2 * i] - v[0]).abs() < 1e-14 && (u[2 * i + 1] - v[1]).abs() < 1e-14,
                    "{plane:?} full = {full}: node {i} at {:?}: {:?} vs {v:?}",
                    nodes[i],
                    [u[2 * i], u[2 * i + 1]]
                );
            }
            let eps = nalgebra::Vector3::new(2e-3, 1.1e-3, -0.7e-3 + 0.4e-3);
            let sig = mat.elastic_matrix() * eps;
            for (e, (f, el)) in els.iter().enumerate() {
                let ue: Vec<f64> = (0..2 * el.len())
                    .map(|a| u[2 * el[a / 2] + a % 2])
                    .collect();
                for (ip, g) in forces(e, &ue, None).iter().enumerate() {
                    for c in 0..3 {
                        assert!(
                            (g.stress[c] - sig[c]).abs() < stress_tol * sig.amax(),
                            "{plane:?} full = {full}: {f:?} element {e} point {ip}: {:?} vs {sig:?}",
                            g.stress
                        );
                    }
                }
            }
        }
    }
}
