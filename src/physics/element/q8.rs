//! The 8-node serendipity quadrilateral: shape functions, Gauss rules,
//! Jacobian, and extrapolation of Gauss point values to the nodes
//! (Zienkiewicz, Taylor & Zhu, 7th ed., sec. 6.2, the serendipity quadrilateral).
//!
//! ```text
//!   η
//!   3 ── 6 ── 2      corners 0..3 counter-clockwise, midsides 4..7
//!   │         │      N_corner = ¼(1+ξξᵢ)(1+ηηᵢ)(ξξᵢ+ηηᵢ−1)
//!   7         5  ξ   N_mid(ξᵢ=0) = ½(1−ξ²)(1+ηηᵢ)
//!   │         │      N_mid(ηᵢ=0) = ½(1+ξξᵢ)(1−η²)
//!   0 ── 4 ── 1
//! ```

use super::edge::gauss_1d;
use super::gauss::GaussRule;

/// Natural coordinates of the nodes.
pub(crate) const NODE_XI: [[f64; 2]; 8] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
];

/// Shape function values at (ξ, η).
pub fn shape(xi: f64, eta: f64) -> [f64; 8] {
    let mut n = [0.0; 8];
    for (a, &[xa, ya]) in NODE_XI.iter().enumerate() {
        n[a] = if a < 4 {
            0.25 * (1.0 + xi * xa) * (1.0 + eta * ya) * (xi * xa + eta * ya - 1.0)
        } else if xa == 0.0 {
            0.5 * (1.0 - xi * xi) * (1.0 + eta * ya)
        } else {
            0.5 * (1.0 + xi * xa) * (1.0 - eta * eta)
        };
    }
    n
}

/// Derivatives (∂N/∂ξ, ∂N/∂η) at (ξ, η).
pub(crate) fn shape_derivs(xi: f64, eta: f64) -> [[f64; 2]; 8] {
    let mut d = [[0.0; 2]; 8];
    for (a, &[xa, ya]) in NODE_XI.iter().enumerate() {
        d[a] = if a < 4 {
            [
                0.25 * xa * (1.0 + eta * ya) * (2.0 * xi * xa + eta * ya),
                0.25 * ya * (1.0 + xi * xa) * (xi * xa + 2.0 * eta * ya),
            ]
        } else if xa == 0.0 {
            [-xi * (1.0 + eta * ya), 0.5 * (1.0 - xi * xi) * ya]
        } else {
            [0.5 * xa * (1.0 - eta * eta), -eta * (1.0 + xi * xa)]
        };
    }
    d
}

fn tensor(n: usize) -> GaussRule {
    let g = gauss_1d(n);
    let mut points = Vec::with_capacity(n * n);
    for &(eta, we) in &g {
        for &(xi, wx) in &g {
            points.push(([xi, eta], wx * we));
        }
    }
    GaussRule { points }
}

/// 2×2 rule (reduced integration).
pub fn gauss_2x2() -> GaussRule {
    tensor(2)
}

/// 3×3 rule (full integration).
pub fn gauss_3x3() -> GaussRule {
    tensor(3)
}

/// Values at the 8 nodes from values at the Gauss points of a 2×2 or 3×3 rule:
/// the bilinear (2×2) or biquadratic-Lagrange (3×3) interpolant through the Gauss
/// points, evaluated at the nodes.
pub(crate) fn extrapolate_to_nodes(rule: &GaussRule, values: &[f64]) -> [f64; 8] {
    let mut out = [0.0; 8];
    for (a, &x) in NODE_XI.iter().enumerate() {
        out[a] = interpolate(rule, values, x);
    }
    out
}

/// The value at (ξ, η) of the tensor Lagrange interpolant through the points
/// of a 2×2 or 3×3 rule (bilinear or biquadratic).
pub(crate) fn interpolate(rule: &GaussRule, values: &[f64], [xa, ya]: [f64; 2]) -> f64 {
    let n = (rule.points.len() as f64).sqrt().round() as usize;
    let g: Vec<f64> = gauss_1d(n).iter().map(|p| p.0).collect();
    let lagrange = |x: f64, i: usize| -> f64 {
        (0..n)
            .filter(|&k| k != i)
            .map(|k| (x - g[k]) / (g[i] - g[k]))
            .product()
    };
    let mut v = 0.0;
    for j in 0..n {
        for i in 0..n {
            v += lagrange(xa, i) * lagrange(ya, j) * values[j * n + i];
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numbers::fd;

    #[test]
    fn partition_of_unity_and_kronecker() {
        for &(x, y) in &[(0.3, -0.7), (-0.9, 0.1), (0.0, 0.0)] {
            let s: f64 = shape(x, y).iter().sum();
            assert!((s - 1.0).abs() < 1e-14);
            let d = shape_derivs(x, y);
            assert!(d.iter().map(|v| v[0]).sum::<f64>().abs() < 1e-14);
        }
        for (a, &[x, y]) in NODE_XI.iter().enumerate() {
            let n = shape(x, y);
            for (b, v) in n.iter().enumerate() {
                assert!((v - f64::from(u8::from(a == b))).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let (x, y, h) = (0.31, -0.47, 1e-6);
        let d = shape_derivs(x, y);
        let jac = fd::central_jacobian(|p| shape(p[0], p[1]).to_vec(), &[x, y], h);
        let worst = fd::worst(&jac, |a, k| d[a][k], fd::Scale::Absolute);
        assert!(worst.diff < 1e-9, "∂N_a/∂ξ_k, {worst}");
    }

    #[test]
    fn area_of_a_straight_sided_element_and_inversion() {
        let c = [[0.0, 0.0], [3.0, 0.5], [2.5, 2.0], [0.2, 1.5]];
        let mut x = [[0.0; 2]; 8];
        x[..4].copy_from_slice(&c);
        for (k, (a, b)) in [(0, 1), (1, 2), (2, 3), (3, 0)].iter().enumerate() {
            x[4 + k] = [(c[*a][0] + c[*b][0]) / 2.0, (c[*a][1] + c[*b][1]) / 2.0];
        }
        let area: f64 = gauss_3x3()
            .points
            .iter()
            .map(|&([s, t], w)| {
                w * crate::physics::element::family::Family::Q8
                    .physical_derivs(&x, [s, t])
                    .unwrap()
                    .0
            })
            .sum();
        let shoelace = 0.5
            * (0..4)
                .map(|i| c[i][0] * c[(i + 1) % 4][1] - c[(i + 1) % 4][0] * c[i][1])
                .sum::<f64>();
        assert!((area - shoelace).abs() < 1e-12);
        // clockwise numbering: the same element inverted
        x.swap(1, 3);
        x.swap(4, 7);
        x.swap(5, 6);
        assert!(crate::physics::element::family::Family::Q8
            .physical_derivs(&x, [0.0, 0.0])
            .is_err());
    }

    #[test]
    fn extrapolation_reproduces_polynomials() {
        for (rule, f) in [
            (
                gauss_2x2(),
                (|x: f64, y: f64| 1.0 + 2.0 * x - y + 0.5 * x * y) as fn(f64, f64) -> f64,
            ),
            (gauss_3x3(), |x: f64, y: f64| {
                1.0 + x * x - 2.0 * y * y + x * y * y
            }),
        ] {
            let vals: Vec<f64> = rule.points.iter().map(|&([x, y], _)| f(x, y)).collect();
            let nodes = extrapolate_to_nodes(&rule, &vals);
            for (a, &[x, y]) in NODE_XI.iter().enumerate() {
                assert!((nodes[a] - f(x, y)).abs() < 1e-12);
            }
        }
    }
}
