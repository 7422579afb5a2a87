//! The quadratic edge [end, mid, end] every element family shares (the
//! sides of the 8-node quad and of the 6-node triangle): its shape functions
//! and the Gauss–Legendre rules that integrate along it.

/// Gauss–Legendre points and weights on [−1, 1] (n = 1..=4).
pub fn gauss_1d(n: usize) -> Vec<(f64, f64)> {
    match n {
        1 => vec![(0.0, 2.0)],
        2 => {
            let a = 1.0 / 3f64.sqrt();
            vec![(-a, 1.0), (a, 1.0)]
        }
        3 => {
            let a = 0.6f64.sqrt();
            vec![(-a, 5.0 / 9.0), (0.0, 8.0 / 9.0), (a, 5.0 / 9.0)]
        }
        _ => {
            let r = (6.0f64 / 5.0).sqrt();
            let (a, b) = (
                (3.0 / 7.0 - 2.0 / 7.0 * r).sqrt(),
                (3.0 / 7.0 + 2.0 / 7.0 * r).sqrt(),
            );
            let (wa, wb) = ((18.0 + 30f64.sqrt()) / 36.0, (18.0 - 30f64.sqrt()) / 36.0);
            vec![(-b, wb), (-a, wa), (a, wa), (b, wb)]
        }
    }
}

/// Shape functions of a quadratic edge [end, mid, end] at s ∈ [−1, 1].
pub fn shape(s: f64) -> [f64; 3] {
    [0.5 * s * (s - 1.0), 1.0 - s * s, 0.5 * s * (s + 1.0)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_rules_integrate_polynomials_exactly() {
        for (n, deg) in [(2usize, 3i32), (3, 5), (4, 7)] {
            let s: f64 = gauss_1d(n)
                .iter()
                .map(|&(x, w)| w * x.powi(deg - 1) * (x + 1.0))
                .sum();
            // ∫ x^{d−1}(x+1) over [−1,1]
            let exact = |p: i32| {
                if p % 2 == 0 {
                    2.0 / (p as f64 + 1.0)
                } else {
                    0.0
                }
            };
            assert!((s - exact(deg) - exact(deg - 1)).abs() < 1e-14, "n = {n}");
        }
    }

    #[test]
    fn edge_shape_is_a_partition_of_unity_and_interpolates() {
        for (i, s) in [-1.0, 0.0, 1.0].into_iter().enumerate() {
            for (k, v) in shape(s).into_iter().enumerate() {
                assert_eq!(v, f64::from(u8::from(i == k)));
            }
        }
        assert!((shape(0.37).iter().sum::<f64>() - 1.0).abs() < 1e-15);
    }
}
