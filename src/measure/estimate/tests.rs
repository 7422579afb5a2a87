use super::{compliance, doerfler_mark};
use crate::physics::material::VonMises;

/// The smallest set holding θ of Σ η² (brute force over all subsets).
fn smallest_bulk(eta: &[f64], theta: f64) -> usize {
    let total: f64 = eta.iter().sum();
    (0u32..1 << eta.len())
        .filter(|m| {
            let held: f64 = (0..eta.len())
                .filter(|i| m & (1 << i) != 0)
                .map(|i| eta[i])
                .sum();
            held >= theta * total
        })
        .map(|m| m.count_ones() as usize)
        .min()
        .unwrap()
}

#[test]
fn doerfler_marks_the_smallest_set_holding_theta_of_the_estimate() {
    let eta = [0.3, 4.0, 0.05, 2.5, 1.0, 0.0, 2.5, 0.7, 0.01, 3.2];
    let total: f64 = eta.iter().sum();
    for theta in [0.1, 0.3, 0.5, 0.6, 0.8, 0.95, 1.0] {
        let m = doerfler_mark(&eta, theta);
        let held: f64 = m.iter().map(|&e| eta[e]).sum();
        assert!(
            held >= theta * total,
            "θ = {theta}: {held} < {}",
            theta * total
        );
        assert_eq!(m.len(), smallest_bulk(&eta, theta), "θ = {theta}: {m:?}");
        // sorted, unique, and every unmarked element is no larger than the smallest marked one
        assert!(m.windows(2).all(|w| w[0] < w[1]));
        let least = m.iter().map(|&e| eta[e]).fold(f64::MAX, f64::min);
        assert!((0..eta.len())
            .filter(|e| !m.contains(e))
            .all(|e| eta[e] <= least));
    }
    // θ = 1 marks every element with a non-zero estimate, not the zero one
    assert_eq!(doerfler_mark(&eta, 1.0).len(), 9);
    assert!(doerfler_mark(&eta, 0.0).is_empty());
    assert!(doerfler_mark(&[0.0; 4], 0.5).is_empty());
    assert!(doerfler_mark(&[], 0.5).is_empty());
    // equal values: ties go by index
    assert_eq!(doerfler_mark(&[1.0; 4], 0.5), vec![0, 1]);
}

#[test]
fn compliance_is_the_energy_of_the_elastic_strain() {
    use crate::physics::material::Plane;
    let (e, nu) = (200000.0, 0.3);
    let mat = VonMises::new(e, nu, 1e9, 0.0, Plane::Strain).unwrap();
    let g = e / (2.0 * (1.0 + nu));
    // a general 3D stress: σᵀ C⁻¹ σ = σ : ε with ε = C⁻¹ σ (engineering shear)
    let s = [120.0, -40.0, 35.0, 15.0, -22.0, 8.0];
    let eps = [
        (s[0] - nu * (s[1] + s[3])) / e,
        (s[1] - nu * (s[0] + s[3])) / e,
        s[2] / g,
        (s[3] - nu * (s[0] + s[1])) / e,
        s[4] / g,
        s[5] / g,
    ];
    let w: f64 = (0..6).map(|c| s[c] * eps[c]).sum();
    assert!((compliance(&mat, &s) - w).abs() < 1e-14 * w.abs());
}
