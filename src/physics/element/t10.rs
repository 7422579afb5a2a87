//! The 10-node quadratic tetrahedron (T10): shape functions in volume
//! coordinates, Gauss rules, edges, faces and the node order of Gmsh's
//! 10-node tetrahedron (Zienkiewicz, Taylor & Zhu, *The Finite Element
//! Method: Its Basis and Fundamentals*, 7th ed., ch. 6, the tetrahedral
//! family in volume coordinates: the quadratic member, whose face is the
//! 6-node triangle of [`super::t6`]).
//!
//! ```text
//!          ζ
//!          3                corners 0 (0,0,0), 1 (1,0,0), 2 (0,1,0),
//!         ╱│╲               3 (0,0,1); midsides 4 (0–1), 5 (1–2),
//!        ╱ │  ╲             6 (2–0), 7 (0–3), 8 (1–3), 9 (2–3)
//!       7  9   8            (VTK_QUADRATIC_TETRA, cell type 24)
//!      ╱   │     ╲
//!     ╱    2 ─ ─ ─╲─ η      L₁ = 1 − ξ − η − ζ, L₂ = ξ, L₃ = η, L₄ = ζ
//!    ╱   ╱6    5   ╲        N_corner i = Lᵢ (2Lᵢ − 1)
//!   0 ─────── 4 ──── 1  ξ   N_mid(i, j) = 4 Lᵢ Lⱼ
//! ```
//!
//! The shape functions span exactly the complete quadratics in (ξ, η, ζ).
//!
//! Rules on the reference tetrahedron (volume ⅙, the weights sum to ⅙), all
//! with positive weights: [`gauss_4`] (degree 2) and [`gauss_14`] (degree 5).
//! The model's `integration = "full"` (the default) takes [`gauss_14`],
//! `"reduced"` [`gauss_4`]: for a straight-sided T10 the Jacobian is
//! constant and Bᵀ D B is of degree 2, so 4 points integrate it exactly; a
//! curved (isoparametric) T10 makes the integrand rational, and [`gauss_14`]
//! is the better choice there. The 5-point degree-3 rule is not
//! offered: its centre weight is negative.

use super::gauss3::GaussRule3;

/// Natural coordinates (ξ, η, ζ) of the nodes.
pub(crate) const NODE_XI: [[f64; 3]; 10] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.5, 0.0, 0.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.0],
    [0.0, 0.0, 0.5],
    [0.5, 0.0, 0.5],
    [0.0, 0.5, 0.5],
];

/// The corner pair of each midside node 4..9.
const MIDS: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];

/// The 6 edges, each [end, mid, end] in local node numbers.
pub(crate) const EDGES: [[usize; 3]; 6] = [
    [0, 4, 1],
    [1, 5, 2],
    [2, 6, 0],
    [0, 7, 3],
    [1, 8, 3],
    [2, 9, 3],
];

/// The 4 faces, each numbered as a 6-node triangle ([`super::t6`]): corners
/// counter-clockwise seen from outside the element (the right-hand rule on
/// them gives the outward normal), then the midsides of the face's corner
/// pairs 0–1, 1–2, 2–0. Face i is the one opposite corner i.
pub(crate) const FACES: [[usize; 6]; 4] = [
    [1, 2, 3, 5, 9, 8],
    [0, 3, 2, 7, 9, 6],
    [0, 1, 3, 4, 8, 7],
    [0, 2, 1, 6, 5, 4],
];

/// Gmsh's 10-node tetrahedron (element type 11) to this numbering:
/// `GMSH_TO_LOCAL[g]` is the local node that Gmsh's node g is, so an element
/// read from a .msh file has `local[GMSH_TO_LOCAL[g]] = gmsh[g]` (a swap, so
/// the same array also maps back).
///
/// Gmsh numbers nodes 0..7 as VTK does, but its node 8 is on edge 2–3 and
/// its node 9 on edge 1–3: VTK's 8 and 9 swapped. Established with Gmsh
/// 4.15.2 (Python module): `gmsh.model.mesh.getElementProperties(11)` gives
/// the reference coordinates 8: (0, ½, ½), 9: (½, 0, ½); and a single
/// tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) meshed with a large mesh
/// size, `setOrder(2)`, written as .msh 4.1, gave one type-11 element whose
/// node coordinates (in the test below) put node 8 at the midpoint of
/// corners 2 and 3, node 9 at that of 1 and 3, with a positive volume.
pub(crate) const GMSH_TO_LOCAL: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

/// Volume coordinates (L₁, L₂, L₃, L₄) at ξ.
fn volume_coords([x, y, z]: [f64; 3]) -> [f64; 4] {
    [1.0 - x - y - z, x, y, z]
}

/// ∂Lᵢ/∂(ξ, η, ζ).
const DL: [[f64; 3]; 4] = [
    [-1.0, -1.0, -1.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];

/// Shape function values at ξ = (ξ, η, ζ).
pub(crate) fn shape(xi: [f64; 3]) -> [f64; 10] {
    let l = volume_coords(xi);
    let mut n = [0.0; 10];
    for i in 0..4 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
    }
    for (m, [i, j]) in MIDS.into_iter().enumerate() {
        n[4 + m] = 4.0 * l[i] * l[j];
    }
    n
}

/// Derivatives (∂N/∂ξ, ∂N/∂η, ∂N/∂ζ) at ξ: (4Lᵢ − 1) ∇Lᵢ at a corner,
/// 4 (Lᵢ ∇Lⱼ + Lⱼ ∇Lᵢ) at a midside.
pub(crate) fn shape_derivs(xi: [f64; 3]) -> [[f64; 3]; 10] {
    let l = volume_coords(xi);
    let mut d = [[0.0; 3]; 10];
    for i in 0..4 {
        d[i] = DL[i].map(|g| (4.0 * l[i] - 1.0) * g);
    }
    for (m, [i, j]) in MIDS.into_iter().enumerate() {
        d[4 + m] = std::array::from_fn(|k| 4.0 * (l[i] * DL[j][k] + l[j] * DL[i][k]));
    }
    d
}

/// The points of a symmetric orbit: (a, a, a, 1 − 3a) and its 4 permutations
/// of the volume coordinates, or (b, b, ½ − b, ½ − b) and its 6, as (ξ, η, ζ)
/// = (L₂, L₃, L₄).
fn orbit(l: [f64; 4], w: f64, points: &mut Vec<([f64; 3], f64)>) {
    let mut seen: Vec<[u64; 4]> = Vec::new();
    for p in [
        [0, 1, 2, 3],
        [1, 0, 2, 3],
        [2, 1, 0, 3],
        [3, 1, 2, 0],
        [0, 2, 1, 3],
        [0, 3, 2, 1],
        [0, 1, 3, 2],
        [2, 3, 0, 1],
        [1, 2, 0, 3],
        [1, 3, 2, 0],
        [3, 2, 1, 0],
        [2, 0, 3, 1],
    ] {
        let q = p.map(|i| l[i]);
        let key = q.map(f64::to_bits);
        if !seen.contains(&key) {
            seen.push(key);
            points.push(([q[1], q[2], q[3]], w));
        }
    }
}

/// The 4-point rule, exact for degree 2: volume coordinates (b, a, a, a) and
/// permutations with a = (5 − √5)/20, b = 1 − 3a = (5 + 3√5)/20, weight
/// 1/24 each (ZTZ 7th ed., ch. 6, the table of tetrahedron rules).
pub(crate) fn gauss_4() -> GaussRule3 {
    let a = (5.0 - 5f64.sqrt()) / 20.0;
    let mut points = Vec::with_capacity(4);
    orbit([1.0 - 3.0 * a, a, a, a], 1.0 / 24.0, &mut points);
    GaussRule3 { points }
}

/// The 14-point rule, exact for degree 5, all weights positive (the
/// symmetric rule with two 4-point orbits (a, a, a, 1 − 3a) and one 6-point
/// orbit (b, b, ½ − b, ½ − b), as tabulated by Walkington, "Quadrature on
/// simplices of arbitrary dimension", 2000, and by Keast, CMAME 55, 1986).
/// The values here were re-solved from the six moment equations of the
/// invariant polynomials of degree ≤ 5 to 40 digits (mpmath) and rounded to
/// the nearest double; the exactness test checks every monomial.
pub(crate) fn gauss_14() -> GaussRule3 {
    let mut points = Vec::with_capacity(14);
    for (a, w) in [
        (0.092_735_250_310_891_22, 0.012_248_840_519_393_659),
        (0.310_885_919_263_300_6, 0.018_781_320_953_002_643),
    ] {
        orbit([1.0 - 3.0 * a, a, a, a], w, &mut points);
    }
    let b = 0.454_496_295_874_350_36;
    orbit(
        [b, b, 0.5 - b, 0.5 - b],
        0.007_091_003_462_846_911,
        &mut points,
    );
    GaussRule3 { points }
}

#[cfg(test)]
mod tests {
    use super::*;

    const POINTS: [[f64; 3]; 4] = [
        [0.21, 0.17, 0.33],
        [0.05, 0.8, 0.1],
        [0.25, 0.25, 0.25],
        [0.0, 0.4, 0.0],
    ];

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

    #[test]
    fn interpolation_reproduces_the_complete_quadratic() {
        let u = |[x, y, z]: [f64; 3]| {
            1.5 - 2.0 * x + 0.5 * y + 3.0 * z + x * x - 0.7 * y * y + 1.3 * z * z + 0.4 * x * y
                - 1.1 * y * z
                + 0.9 * z * x
        };
        let nodal = NODE_XI.map(u);
        for &p in &POINTS {
            let v: f64 = shape(p).iter().zip(&nodal).map(|(n, u)| n * u).sum();
            assert!((v - u(p)).abs() < 1e-13, "{p:?}: {v} vs {}", u(p));
        }
        // and no cubic
        let u3 = |[x, y, z]: [f64; 3]| x * y * z;
        let nodal = NODE_XI.map(u3);
        let p = POINTS[2];
        let v: f64 = shape(p).iter().zip(&nodal).map(|(n, u)| n * u).sum();
        assert!((v - u3(p)).abs() > 1e-3);
    }

    /// ∫ L₁ᵃ L₂ᵇ L₃ᶜ L₄ᵈ dV = a! b! c! d! 3! / (a + b + c + d + 3)! × V, with
    /// V = ⅙ (the standard volume-coordinate integral, ZTZ 7th ed., ch. 6).
    #[test]
    fn rules_integrate_their_degree_exactly() {
        let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
        let exact = |e: [u32; 4]| {
            e.iter().map(|&k| fact(k)).product::<f64>() * 6.0
                / fact(e.iter().sum::<u32>() + 3)
                / 6.0
        };
        let quad = |rule: &GaussRule3, e: [u32; 4]| -> f64 {
            rule.points
                .iter()
                .map(|&(x, w)| {
                    let l = volume_coords(x);
                    w * (0..4).map(|k| l[k].powi(e[k] as i32)).product::<f64>()
                })
                .sum()
        };
        for (rule, n, degree) in [(gauss_4(), 4, 2), (gauss_14(), 14, 5)] {
            assert_eq!(rule.points.len(), n);
            assert!(rule.points.iter().all(|p| p.1 > 0.0));
            for &(x, _) in &rule.points {
                assert!(volume_coords(x).iter().all(|&l| l > 0.0), "{x:?} outside");
            }
            let mut checked = 0;
            for a in 0..=degree {
                for b in 0..=degree - a {
                    for c in 0..=degree - a - b {
                        for d in 0..=degree - a - b - c {
                            let e = [a, b, c, d];
                            let s = quad(&rule, e);
                            assert!((s - exact(e)).abs() < 1e-14, "degree {degree}: L^{e:?}");
                            checked += 1;
                        }
                    }
                }
            }
            assert!(checked > 10);
            // and not one degree more
            let e = [0, degree + 1, 0, 0];
            assert!(
                (quad(&rule, e) - exact(e)).abs() > 1e-6,
                "degree {degree} + 1"
            );
        }
    }

    #[test]
    fn edge_mid_nodes_are_at_the_midpoints() {
        let mut seen = [0; 10];
        for [a, m, b] in EDGES {
            let mid: [f64; 3] = std::array::from_fn(|k| 0.5 * (NODE_XI[a][k] + NODE_XI[b][k]));
            assert_eq!(NODE_XI[m], mid, "edge {a}-{m}-{b}");
            seen[m] += 1;
            seen[a] += 1;
            seen[b] += 1;
        }
        assert_eq!(seen, [3, 3, 3, 3, 1, 1, 1, 1, 1, 1]);
        for (m, [i, j]) in MIDS.into_iter().enumerate() {
            assert_eq!(EDGES[m], [i, 4 + m, j]);
        }
    }

    #[test]
    fn faces_are_numbered_outward_and_lie_in_their_planes() {
        let x = NODE_XI;
        let centre = [0.25; 3];
        let mut on_face = [0; 10];
        for (f, face) in FACES.into_iter().enumerate() {
            assert!(!face.contains(&f), "face {f} holds its opposite corner");
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
            // midsides 3..5 between corners 0–1, 1–2, 2–0
            for k in 0..3 {
                let (a, b) = (c[k], c[(k + 1) % 3]);
                for j in 0..3 {
                    assert_eq!(c[3 + k][j], 0.5 * (a[j] + b[j]), "face {face:?} mid {k}");
                }
            }
        }
        // every corner on 3 faces, every midside on 2
        assert_eq!(on_face, [3, 3, 3, 3, 2, 2, 2, 2, 2, 2]);
    }

    /// Gmsh's type-11 element of the single tetrahedron (see
    /// [`GMSH_TO_LOCAL`]): node coordinates in Gmsh's order, as Gmsh 4.15.2
    /// wrote them, and Gmsh's reference coordinates from
    /// `getElementProperties(11)`.
    #[test]
    fn gmsh_permutation_maps_each_node_to_the_same_point() {
        let gmsh_xyz: [[f64; 3]; 10] = [
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.5, 0.0],
            [0.0, 0.5, 0.5],
            [0.0, 0.0, 0.5],
            [0.5, 0.0, 0.0],
            [0.5, 0.0, 0.5],
            [0.5, 0.5, 0.0],
        ];
        let gmsh_ref: [[f64; 3]; 10] = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.0, 0.5, 0.0],
            [0.0, 0.0, 0.5],
            [0.0, 0.5, 0.5],
            [0.5, 0.0, 0.5],
        ];
        let mut sorted = GMSH_TO_LOCAL;
        sorted.sort_unstable();
        assert_eq!(sorted, std::array::from_fn(|i| i), "not a permutation");
        for g in 0..10 {
            assert_eq!(NODE_XI[GMSH_TO_LOCAL[g]], gmsh_ref[g], "Gmsh node {g}");
        }
        // the mesh element, renumbered: every node where the linear map of its
        // corners puts NODE_XI, and a positive volume
        let mut x = [[0.0; 3]; 10];
        for g in 0..10 {
            x[GMSH_TO_LOCAL[g]] = gmsh_xyz[g];
        }
        for (a, &xa) in NODE_XI.iter().enumerate() {
            let l = volume_coords(xa);
            let p: [f64; 3] = std::array::from_fn(|k| (0..4).map(|c| l[c] * x[c][k]).sum());
            assert_eq!(p, x[a], "local node {a}");
        }
        let (e1, e2, e3) = (sub(x[1], x[0]), sub(x[2], x[0]), sub(x[3], x[0]));
        assert!(dot(e1, cross(e2, e3)) > 0.0);
    }
}
