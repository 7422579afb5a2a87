//! Patch tests: a mesh of distorted 8-node elements reproduces any linear
//! displacement field exactly (constant strain and stress), both plane states,
//! full and reduced integration.

use asperity::physics::element::element_forces;
use asperity::physics::element::q8::{gauss_2x2, gauss_3x3};
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
        for rule in [gauss_3x3(), gauss_2x2()] {
            let mat = VonMises::new(100000.0, 0.25, f64::INFINITY, 0.0, plane).unwrap();
            let ng = rule.points.len();
            let geoms: Vec<_> = els
                .iter()
                .map(|e| {
                    let c: [[f64; 2]; 8] = std::array::from_fn(|a| nodes[e[a]]);
                    ElementGeometry::new(
                        asperity::physics::element::family::Family::Q8,
                        &c,
                        &rule,
                        1.0,
                    )
                    .unwrap()
                })
                .collect();
            // assemble the dense stiffness, prescribe the boundary, solve the interior
            let mut k = DMatrix::<f64>::zeros(2 * n, 2 * n);
            let (mut fe, mut ke) = ([0.0; 16], [0.0; 256]);
            let zero = vec![PointState::default(); ng];
            let mut tr = zero.clone();
            for (e, el) in els.iter().enumerate() {
                element_forces(
                    &geoms[e],
                    &mat,
                    &[0.0; 16],
                    &zero,
                    &mut tr,
                    Response::Plastic,
                    Some(Tangent::Consistent),
                    &mut fe,
                    &mut ke,
                )
                .unwrap();
                for a in 0..16 {
                    for b in 0..16 {
                        k[(2 * el[a / 2] + a % 2, 2 * el[b / 2] + b % 2)] += ke[a * 16 + b];
                    }
                }
            }
            let mut u = DVector::<f64>::zeros(2 * n);
            for i in 0..n {
                if boundary[i] {
                    let v = exact(nodes[i]);
                    u[2 * i] = v[0];
                    u[2 * i + 1] = v[1];
                }
            }
            let free: Vec<usize> = (0..2 * n).filter(|&d| !boundary[d / 2]).collect();
            let kff = DMatrix::from_fn(free.len(), free.len(), |r, c| k[(free[r], free[c])]);
            let rhs = DVector::from_fn(free.len(), |r, _| {
                -(0..2 * n)
                    .filter(|&d| boundary[d / 2])
                    .map(|d| k[(free[r], d)] * u[d])
                    .sum::<f64>()
            });
            let sol = kff.lu().solve(&rhs).unwrap();
            for (r, &d) in free.iter().enumerate() {
                u[d] = sol[r];
            }
            for i in 0..n {
                let v = exact(nodes[i]);
                assert!(
                    (u[2 * i] - v[0]).abs() < 1e-14 && (u[2 * i + 1] - v[1]).abs() < 1e-14,
                    "{plane:?} node {i}"
                );
            }
            // constant stress at every Gauss point equals D ε
            let eps = nalgebra::Vector3::new(2e-3, 1.1e-3, -0.7e-3 + 0.4e-3);
            let sig = mat.elastic_matrix() * eps;
            for (e, el) in els.iter().enumerate() {
                let ue: [f64; 16] = std::array::from_fn(|a| u[2 * el[a / 2] + a % 2]);
                let mut st = zero.clone();
                element_forces(
                    &geoms[e],
                    &mat,
                    &ue,
                    &zero,
                    &mut st,
                    Response::Plastic,
                    None,
                    &mut fe,
                    &mut ke,
                )
                .unwrap();
                for g in &st {
                    for c in 0..3 {
                        assert!(
                            (g.stress[c] - sig[c]).abs() < 1e-9 * sig.amax(),
                            "{plane:?} element {e}: {:?} vs {sig:?}",
                            g.stress
                        );
                    }
                }
            }
        }
    }
}
