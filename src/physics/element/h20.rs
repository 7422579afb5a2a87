//! The 20-node serendipity hexahedron (H20) on [−1, 1]³: shape functions,
//! Gauss rules, edges, faces and the node order of Gmsh's 20-node hexahedron
//! (Zienkiewicz, Taylor & Zhu, *The Finite Element Method: Its Basis and
//! Fundamentals*, 7th ed., ch. 6, the three-dimensional serendipity "brick":
//! the quadratic member of the family whose face is the 8-node quad of
//! [`super::q8`]).
//!
//! ```text
//!          ζ
//!          7 ──── 14 ───── 6        corners 0..3 on ζ = −1 and 4..7 on
//!         ╱│              ╱│        ζ = +1, each counter-clockwise seen
//!       15 │            13 │        from +ζ; midsides 8..11 on the bottom
//!       ╱  19           ╱  18       edges 0–1, 1–2, 2–3, 3–0, 12..15 on the
//!      4 ──── 12 ───── 5   │        top edges 4–5, 5–6, 6–7, 7–4, 16..19 on
//!      │   │           │   │  η     the vertical edges 0–4, 1–5, 2–6, 3–7
//!      │   3 ──── 10 ──│── 2        (VTK_QUADRATIC_HEXAHEDRON, cell type 25)
//!     16  ╱           17  ╱
//!      │ 11            │ 9          N_corner = ⅛(1+ξξᵢ)(1+ηηᵢ)(1+ζζᵢ)(ξξᵢ+ηηᵢ+ζζᵢ−2)
//!      │╱              │╱           N_mid(ξᵢ=0) = ¼(1−ξ²)(1+ηηᵢ)(1+ζζᵢ)
//!      0 ───── 8 ───── 1  ξ         and likewise for ηᵢ = 0, ζᵢ = 0
//! ```
//!
//! The shape functions span the complete quadratic polynomials in (ξ, η, ζ)
//! plus ξηζ and the cubics ξ²η, ξ²ζ, … that are linear in two of the
//! coordinates (the 20-dimensional serendipity space).

use super::edge::gauss_1d;
use super::gauss3::GaussRule3;

/// Natural coordinates (ξ, η, ζ) of the nodes.
pub(crate) const NODE_XI: [[f64; 3]; 20] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, -1.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [-1.0, 0.0, 1.0],
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

/// The 12 edges, each [end, mid, end] in local node numbers: the bottom
/// edges, the top edges, then the vertical ones.
pub(crate) const EDGES: [[usize; 3]; 12] = [
    [0, 8, 1],
    [1, 9, 2],
    [2, 10, 3],
    [3, 11, 0],
    [4, 12, 5],
    [5, 13, 6],
    [6, 14, 7],
    [7, 15, 4],
    [0, 16, 4],
    [1, 17, 5],
    [2, 18, 6],
    [3, 19, 7],
];

/// The 6 faces, each numbered as an 8-node quad ([`super::q8`]): corners
/// counter-clockwise seen from outside the element (the right-hand rule on
/// them gives the outward normal), then the midsides of the face's corner
/// pairs 0–1, 1–2, 2–3, 3–0. In order: ζ = −1, ζ = +1, η = −1, ξ = +1,
/// η = +1, ξ = −1.
pub(crate) const FACES: [[usize; 8]; 6] = [
    [0, 3, 2, 1, 11, 10, 9, 8],
    [4, 5, 6, 7, 12, 13, 14, 15],
    [0, 1, 5, 4, 8, 17, 12, 16],
    [1, 2, 6, 5, 9, 18, 13, 17],
    [2, 3, 7, 6, 10, 19, 14, 18],
    [3, 0, 4, 7, 11, 16, 15, 19],
];

/// Gmsh's 20-node hexahedron (element type 17) to this numbering:
/// `GMSH_TO_LOCAL[g]` is the local node that Gmsh's node g is, so an element
/// read from a .msh file has `local[GMSH_TO_LOCAL[g]] = gmsh[g]`.
///
/// Gmsh numbers the corners as VTK does but the midsides by edge in another
/// order: 8 (0–1), 9 (0–3), 10 (0–4), 11 (1–2), 12 (1–5), 13 (2–3),
/// 14 (2–6), 15 (3–7), 16 (4–5), 17 (4–7), 18 (5–6), 19 (6–7). Established
/// with Gmsh 4.15.2 (Python module): `gmsh.model.mesh.getElementProperties(17)`
/// gives the reference node coordinates on [−1, 1]³ (8: (0,−1,−1),
/// 9: (−1,0,−1), 10: (−1,−1,0), 11: (1,0,−1), 12: (1,−1,0), 13: (0,1,−1),
/// 14: (1,1,0), 15: (−1,1,0), 16: (0,−1,1), 17: (−1,0,1), 18: (1,0,1),
/// 19: (0,1,1)); and a unit cube meshed as one transfinite recombined
/// hexahedron, `setOrder(2)` with `Mesh.SecondOrderIncomplete = 1`, written
/// as .msh 4.1, gave a type-17 element whose node coordinates (in the test
/// below) have every Gmsh midside at the midpoint of the corners listed
/// here, and a positive Jacobian.
pub(crate) const GMSH_TO_LOCAL: [usize; 20] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 16, 9, 17, 10, 18, 19, 12, 15, 13, 14,
];

/// Shape function values at ξ = (ξ, η, ζ).
pub(crate) fn shape(xi: [f64; 3]) -> [f64; 20] {
    let mut n = [0.0; 20];
    for (a, xa) in NODE_XI.iter().enumerate() {
        // fₖ = 1 + ξₖ ξₖᵃ
        let f = [
            1.0 + xi[0] * xa[0],
            1.0 + xi[1] * xa[1],
            1.0 + xi[2] * xa[2],
        ];
        n[a] = match xa.iter().position(|&c| c == 0.0) {
            None => 0.125 * f[0] * f[1] * f[2] * (f[0] + f[1] + f[2] - 5.0),
            Some(m) => {
                let (j, k) = ((m + 1) % 3, (m + 2) % 3);
                0.25 * (1.0 - xi[m] * xi[m]) * f[j] * f[k]
            }
        };
    }
    n
}

/// Derivatives (∂N/∂ξ, ∂N/∂η, ∂N/∂ζ) at ξ = (ξ, η, ζ).
///
/// With fₖ = 1 + ξₖ ξₖᵃ and s = Σ ξₖ ξₖᵃ − 2, a corner's ∂N/∂ξₖ =
/// ⅛ ξₖᵃ fⱼ fₗ (s + fₖ); a midside's with ξₘᵃ = 0 is ∂N/∂ξₘ = −½ ξₘ fⱼ fₗ and
/// ∂N/∂ξⱼ = ¼ (1 − ξₘ²) ξⱼᵃ fₗ (j, l the other two).
pub(crate) fn shape_derivs(xi: [f64; 3]) -> [[f64; 3]; 20] {
    let mut d = [[0.0; 3]; 20];
    for (a, xa) in NODE_XI.iter().enumerate() {
        let f = [
            1.0 + xi[0] * xa[0],
            1.0 + xi[1] * xa[1],
            1.0 + xi[2] * xa[2],
        ];
        match xa.iter().position(|&c| c == 0.0) {
            None => {
                let s = f[0] + f[1] + f[2] - 5.0;
                for k in 0..3 {
                    let (j, l) = ((k + 1) % 3, (k + 2) % 3);
                    d[a][k] = 0.125 * xa[k] * f[j] * f[l] * (s + f[k]);
                }
            }
            Some(m) => {
                let (j, l) = ((m + 1) % 3, (m + 2) % 3);
                let bubble = 1.0 - xi[m] * xi[m];
                d[a][m] = -0.5 * xi[m] * f[j] * f[l];
                d[a][j] = 0.25 * bubble * xa[j] * f[l];
                d[a][l] = 0.25 * bubble * xa[l] * f[j];
            }
        }
    }
    d
}

/// The n×n×n tensor Gauss–Legendre rule, ξ fastest.
fn tensor(n: usize) -> GaussRule3 {
    let g = gauss_1d(n);
    let mut points = Vec::with_capacity(n * n * n);
    for &(zeta, wz) in &g {
        for &(eta, we) in &g {
            for &(xi, wx) in &g {
                points.push(([xi, eta, zeta], wx * we * wz));
            }
        }
    }
    GaussRule3 { points }
}

/// 3×3×3 rule (full integration): exact for ξᵃηᵇζᶜ with a, b, c ≤ 5.
pub(crate) fn gauss_27() -> GaussRule3 {
    tensor(3)
}

/// 2×2×2 rule (reduced integration): exact for ξᵃηᵇζᶜ with a, b, c ≤ 3.
/// Its 8 points × 6 strains give a stiffness of rank at most 48 < 60 − 6,
/// so an isolated H20 integrated with it has at least 6 zero-energy modes
/// besides the rigid ones.
pub(crate) fn gauss_8() -> GaussRule3 {
    tensor(2)
}

#[cfg(test)]
mod tests {
    use super::*;

    const POINTS: [[f64; 3]; 4] = [
        [0.31, -0.47, 0.13],
        [-0.9, 0.1, 0.77],
        [0.0, 0.0, 0.0],
        [1.0, -0.25, -1.0],
    ];

    /// The unit cube [0, 1]³ as an H20: node a at (NODE_XI[a] + 1) / 2.
    fn unit_cube() -> [[f64; 3]; 20] {
        NODE_XI.map(|x| x.map(|c| 0.5 * (c + 1.0)))
    }

    use crate::numbers::vec3::{cross, dot, sub};
    use crate::physics::element::shape_checks;

    #[test]
    fn partition_of_unity_kronecker_and_derivatives_sum_to_zero() {
        shape_checks::partition_and_kronecker(&POINTS, &NODE_XI, shape, shape_derivs);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        shape_checks::derivatives_by_differences(&POINTS, shape, shape_derivs);
    }

    /// u = any quadratic in (ξ, η, ζ), plus ξηζ and ξ²η, is reproduced by
    /// interpolating its nodal values.
    #[test]
    fn interpolation_reproduces_the_complete_quadratic() {
        let u = |[x, y, z]: [f64; 3]| {
            1.5 - 2.0 * x + 0.5 * y + 3.0 * z + x * x - 0.7 * y * y + 1.3 * z * z + 0.4 * x * y
                - 1.1 * y * z
                + 0.9 * z * x
                + 0.6 * x * y * z
                - 0.8 * x * x * y
        };
        let nodal = NODE_XI.map(u);
        for &p in &POINTS {
            let v: f64 = shape(p).iter().zip(&nodal).map(|(n, u)| n * u).sum();
            assert!((v - u(p)).abs() < 1e-13, "{p:?}: {v} vs {}", u(p));
        }
        // not complete to degree 3: ξ²η² is not in the space
        let u4 = |[x, y, _]: [f64; 3]| x * x * y * y;
        let nodal = NODE_XI.map(u4);
        let p = POINTS[0];
        let v: f64 = shape(p).iter().zip(&nodal).map(|(n, u)| n * u).sum();
        assert!((v - u4(p)).abs() > 1e-3);
    }

    /// ∫ ξᵃ ηᵇ ζᶜ over [−1, 1]³ = Π 2/(e + 1) for even exponents e, 0 if
    /// any is odd.
    #[test]
    fn rules_integrate_their_degree_exactly() {
        let exact1 = |e: u32| {
            if e % 2 == 0 {
                2.0 / f64::from(e + 1)
            } else {
                0.0
            }
        };
        let quad = |rule: &GaussRule3, e: [u32; 3]| -> f64 {
            rule.points
                .iter()
                .map(|&(x, w)| w * (0..3).map(|k| x[k].powi(e[k] as i32)).product::<f64>())
                .sum()
        };
        for (rule, degree) in [(gauss_8(), 3), (gauss_27(), 5)] {
            assert_eq!(rule.points.len(), (degree as usize + 1).pow(3) / 8);
            for a in 0..=degree {
                for b in 0..=degree {
                    for c in 0..=degree {
                        let s = quad(&rule, [a, b, c]);
                        let exact = exact1(a) * exact1(b) * exact1(c);
                        assert!(
                            (s - exact).abs() < 1e-13,
                            "degree {degree}: ξ^{a} η^{b} ζ^{c}"
                        );
                    }
                }
            }
            // and not one degree more per direction
            let e = degree + 1;
            assert!((quad(&rule, [e, 0, 0]) - exact1(e) * 4.0).abs() > 1e-3);
        }
    }

    #[test]
    fn edge_mid_nodes_are_at_the_midpoints() {
        let x = unit_cube();
        let mut seen = [0; 20];
        for [a, m, b] in EDGES {
            let mid: [f64; 3] = std::array::from_fn(|k| 0.5 * (x[a][k] + x[b][k]));
            assert_eq!(x[m], mid, "edge {a}-{m}-{b}");
            // the ends differ in one coordinate only
            assert_eq!((0..3).filter(|&k| x[a][k] != x[b][k]).count(), 1);
            seen[m] += 1;
        }
        assert_eq!(seen[8..], [1; 12]);
    }

    #[test]
    fn faces_are_numbered_outward_and_lie_in_their_planes() {
        let x = unit_cube();
        let centre = [0.5; 3];
        let mut on_face = [0; 20];
        for face in FACES {
            let c = face.map(|a| x[a]);
            let n = cross(sub(c[1], c[0]), sub(c[2], c[0]));
            assert!(
                dot(n, sub(c[0], centre)) > 0.0,
                "face {face:?} points inward"
            );
            for (i, &p) in c.iter().enumerate() {
                assert!(dot(n, sub(p, c[0])).abs() < 1e-14, "face {face:?} node {i}");
                on_face[face[i]] += 1;
            }
            // midsides 4..7 between corners 0–1, 1–2, 2–3, 3–0
            for k in 0..4 {
                let (a, b) = (c[k], c[(k + 1) % 4]);
                for j in 0..3 {
                    assert_eq!(c[4 + k][j], 0.5 * (a[j] + b[j]), "face {face:?} mid {k}");
                }
            }
        }
        // every corner on 3 faces, every midside on 2
        assert_eq!(on_face[..8], [3; 8]);
        assert_eq!(on_face[8..], [2; 12]);
    }

    /// Gmsh's type-17 element of a unit cube (see [`GMSH_TO_LOCAL`]): node
    /// coordinates in Gmsh's order, as Gmsh 4.15.2 wrote them, and Gmsh's
    /// reference coordinates from `getElementProperties(17)`.
    #[test]
    fn gmsh_permutation_maps_each_node_to_the_same_point() {
        let gmsh_xyz: [[f64; 3]; 20] = [
            [0.0, 1.0, 1.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 0.5, 1.0],
            [0.0, 1.0, 0.5],
            [0.5, 1.0, 1.0],
            [0.0, 0.0, 0.5],
            [0.5, 0.0, 1.0],
            [0.0, 0.5, 0.0],
            [0.5, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [1.0, 0.5, 1.0],
            [1.0, 1.0, 0.5],
            [1.0, 0.0, 0.5],
            [1.0, 0.5, 0.0],
        ];
        let gmsh_ref: [[f64; 3]; 20] = [
            [-1.0, -1.0, -1.0],
            [1.0, -1.0, -1.0],
            [1.0, 1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
            [0.0, -1.0, -1.0],
            [-1.0, 0.0, -1.0],
            [-1.0, -1.0, 0.0],
            [1.0, 0.0, -1.0],
            [1.0, -1.0, 0.0],
            [0.0, 1.0, -1.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [0.0, -1.0, 1.0],
            [-1.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
        ];
        let mut sorted = GMSH_TO_LOCAL;
        sorted.sort_unstable();
        assert_eq!(sorted, std::array::from_fn(|i| i), "not a permutation");
        for g in 0..20 {
            assert_eq!(NODE_XI[GMSH_TO_LOCAL[g]], gmsh_ref[g], "Gmsh node {g}");
        }
        // the mesh element, renumbered: every node where the trilinear map of
        // its corners puts NODE_XI, and a positive Jacobian
        let mut x = [[0.0; 3]; 20];
        for g in 0..20 {
            x[GMSH_TO_LOCAL[g]] = gmsh_xyz[g];
        }
        for (a, xa) in NODE_XI.iter().enumerate() {
            let mut p = [0.0; 3];
            for (c, xc) in NODE_XI[..8].iter().enumerate() {
                let n = (0..3).map(|k| 0.5 * (1.0 + xa[k] * xc[k])).product::<f64>();
                for k in 0..3 {
                    p[k] += n * x[c][k];
                }
            }
            assert_eq!(p, x[a], "local node {a}");
        }
        let d = shape_derivs([0.1, -0.2, 0.3]);
        let mut j = [[0.0; 3]; 3];
        for a in 0..20 {
            for r in 0..3 {
                for c in 0..3 {
                    j[r][c] += x[a][r] * d[a][c];
                }
            }
        }
        assert!(dot(j[0], cross(j[1], j[2])) > 0.0);
    }
}
