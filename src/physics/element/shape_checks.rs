//! Checks every 3D family's shape functions must pass (tests only): the
//! partition of unity, the Kronecker property at the nodes, derivatives
//! summing to zero and matching central differences.

use crate::numbers::fd;

/// N sums to 1 and ∂N/∂ξ_k to 0 at `points`; N_b(ξ_a) = δ_ab at the nodes.
pub(super) fn partition_and_kronecker<const N: usize>(
    points: &[[f64; 3]],
    node_xi: &[[f64; 3]; N],
    shape: fn([f64; 3]) -> [f64; N],
    derivs: fn([f64; 3]) -> [[f64; 3]; N],
) {
    for &p in points {
        assert!((shape(p).iter().sum::<f64>() - 1.0).abs() < 1e-14, "{p:?}");
        let d = derivs(p);
        for k in 0..3 {
            let s: f64 = d.iter().map(|v| v[k]).sum();
            assert!(s.abs() < 1e-14, "Σ ∂N/∂ξ_{k} = {s} at {p:?}");
        }
    }
    for (a, &x) in node_xi.iter().enumerate() {
        for (b, v) in shape(x).iter().enumerate() {
            assert!(
                (v - f64::from(u8::from(a == b))).abs() < 1e-14,
                "N_{b} at node {a}"
            );
        }
    }
}

/// ∂N_a/∂ξ_k against central differences (h = 1e-5) to 1e-8 at `points`.
pub(super) fn derivatives_by_differences<const N: usize>(
    points: &[[f64; 3]],
    shape: fn([f64; 3]) -> [f64; N],
    derivs: fn([f64; 3]) -> [[f64; 3]; N],
) {
    for &p in points {
        let d = derivs(p);
        let jac = fd::central_jacobian(|x| shape([x[0], x[1], x[2]]).to_vec(), &p, 1e-5);
        let worst = fd::worst(&jac, |a, k| d[a][k], fd::Scale::Absolute);
        assert!(worst.diff < 1e-8, "∂N_a/∂ξ_k at {p:?}, {worst}");
    }
}
