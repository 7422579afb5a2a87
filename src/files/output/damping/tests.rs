use super::*;

#[test]
fn the_backbone_ends_at_the_first_drop_of_the_force_magnitude() {
    // a preload without drag, a rise, a plateau (macro-slip), the reversal
    assert_eq!(
        backbone_end(&[0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 2.0, -3.0]),
        6
    );
    // a drop within 1e-6 of the largest |F| (10) is not a reversal
    assert_eq!(backbone_end(&[0.0, 5.0, 10.0, 10.0 - 5e-6, 10.0, 8.0]), 4);
    assert_eq!(backbone_end(&[0.0, 5.0, 10.0, 10.0 - 2e-5, 10.0, 8.0]), 2);
    // a drag in −t: the magnitude counts
    assert_eq!(backbone_end(&[-1.0, -2.0, -3.0, -2.0]), 2);
    // never reversed: every row; no rows: 0
    assert_eq!(backbone_end(&[0.0, 1.0, 2.0]), 2);
    assert_eq!(backbone_end(&[]), 0);
}
