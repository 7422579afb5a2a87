//! The 6-node quadratic triangle (T6): shape functions in area coordinates
//! and its Gauss rules.
//!
//! ```text
//!   η
//!   2              corners 0, 1, 2 counter-clockwise, midsides 3 (0–1),
//!   │ ╲            4 (1–2), 5 (2–0), as Gmsh's 6-node triangle (type 9)
//!   5   4          L₁ = 1 − ξ − η,  L₂ = ξ,  L₃ = η
//!   │     ╲        N_corner i = Lᵢ (2Lᵢ − 1)
//!   0 ── 3 ── 1 ξ  N_mid(i, j) = 4 Lᵢ Lⱼ
//! ```
//! (Zienkiewicz, Taylor & Zhu, *The Finite Element Method: Its Basis and
//! Fundamentals*, 7th ed., sec. 6.3, eq. 6.27 for the quadratic triangle.)
//!
//! Gauss rules on the reference triangle (area ½), symmetric in the area
//! coordinates (ZTZ table 6.3; Strang & Fix / Dunavant): 3 points exact for
//! degree 2, 6 points exact for degree 4.

use super::gauss::GaussRule;

/// Natural coordinates (ξ, η) of the nodes.
pub(crate) const NODE_XI: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
];

/// Shape function values at (ξ, η) (eq. 6.27).
pub fn shape(xi: f64, eta: f64) -> [f64; 6] {
    let l = [1.0 - xi - eta, xi, eta];
    [
        l[0] * (2.0 * l[0] - 1.0),
        l[1] * (2.0 * l[1] - 1.0),
        l[2] * (2.0 * l[2] - 1.0),
        4.0 * l[0] * l[1],
        4.0 * l[1] * l[2],
        4.0 * l[2] * l[0],
    ]
}

/// Derivatives (∂N/∂ξ, ∂N/∂η) at (ξ, η), with ∂L₁ = (−1, −1), ∂L₂ = (1, 0),
/// ∂L₃ = (0, 1).
pub(crate) fn shape_derivs(xi: f64, eta: f64) -> [[f64; 2]; 6] {
    let l1 = 1.0 - xi - eta;
    [
        [1.0 - 4.0 * l1, 1.0 - 4.0 * l1],
        [4.0 * xi - 1.0, 0.0],
        [0.0, 4.0 * eta - 1.0],
        [4.0 * (l1 - xi), -4.0 * xi],
        [4.0 * eta, 4.0 * xi],
        [-4.0 * eta, 4.0 * (l1 - eta)],
    ]
}

/// The 3-point rule, exact for polynomials of degree 2: the points at area
/// coordinates (⅔, ⅙, ⅙) and permutations, weight ⅙ each.
pub(crate) fn gauss_3() -> GaussRule {
    let (a, b) = (1.0 / 6.0, 2.0 / 3.0);
    GaussRule {
        points: vec![
            ([a, a], 1.0 / 6.0),
            ([b, a], 1.0 / 6.0),
            ([a, b], 1.0 / 6.0),
        ],
    }
}

/// The 6-point rule, exact for polynomials of degree 4 (Dunavant's degree-4
/// rule): two orbits (a, a, 1 − 2a) with weights (on area ½) w/2.
pub(crate) fn gauss_6() -> GaussRule {
    let orbits = [
        (0.445_948_490_915_965, 0.223_381_589_678_011),
        (0.091_576_213_509_771, 0.109_951_743_655_322),
    ];
    let mut points = Vec::with_capacity(6);
    for (a, w) in orbits {
        let c = 1.0 - 2.0 * a;
        for p in [[a, a], [c, a], [a, c]] {
            points.push((p, 0.5 * w));
        }
    }
    GaussRule { points }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_of_unity_kronecker_and_derivatives() {
        for (a, &[x, y]) in NODE_XI.iter().enumerate() {
            for (b, v) in shape(x, y).iter().enumerate() {
                assert!((v - f64::from(u8::from(a == b))).abs() < 1e-14);
            }
        }
        let (x, y, h) = (0.27, 0.31, 1e-6);
        assert!((shape(x, y).iter().sum::<f64>() - 1.0).abs() < 1e-14);
        let d = shape_derivs(x, y);
        let (px, mx) = (shape(x + h, y), shape(x - h, y));
        let (py, my) = (shape(x, y + h), shape(x, y - h));
        for a in 0..6 {
            assert!((d[a][0] - (px[a] - mx[a]) / (2.0 * h)).abs() < 1e-9, "{a}");
            assert!((d[a][1] - (py[a] - my[a]) / (2.0 * h)).abs() < 1e-9, "{a}");
        }
    }

    /// ∫ ξ^p η^q over the reference triangle = p! q! / (p + q + 2)!.
    #[test]
    fn rules_integrate_their_degree_exactly() {
        let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
        for (rule, degree) in [(gauss_3(), 2), (gauss_6(), 4)] {
            for p in 0..=degree {
                for q in 0..=degree - p {
                    let s: f64 = rule
                        .points
                        .iter()
                        .map(|&([x, y], w)| w * x.powi(p as i32) * y.powi(q as i32))
                        .sum();
                    let exact = fact(p) * fact(q) / fact(p + q + 2);
                    assert!((s - exact).abs() < 1e-12, "degree {degree}: ξ^{p} η^{q}");
                }
            }
        }
        // and not one degree more
        let s: f64 = gauss_3()
            .points
            .iter()
            .map(|&([x, _], w)| w * x.powi(3))
            .sum();
        assert!((s - fact(3) / fact(5)).abs() > 1e-4);
    }
}
