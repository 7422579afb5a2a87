//! `asperity figures` produces well-formed data (the pictures' pixels are not
//! checked), Fig. 8 shows the paper's trend: the foundation settles less as
//! the hardening modulus grows, and the combined shrink fit's torque-twist
//! loop is drawn.

use crate::common;
use asperity::app::study::figures::figures;

fn rows(path: &std::path::Path) -> Vec<(String, f64, f64)> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .filter(|l| !l.starts_with("\"reference"))
        .map(|l| {
            let (name, rest) = l.rsplit_once("\",").unwrap();
            let (x, y) = rest.split_once(',').unwrap();
            (
                name.trim_start_matches('"').to_string(),
                x.parse().unwrap(),
                y.parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn figures_write_well_formed_data_and_fig_8_hardens() {
    let out = common::scratch("figures");
    let files = figures(&common::root().join("cases"), &out).unwrap_or_else(|e| panic!("{e}"));
    for stem in [
        "fig5-load-displacement",
        "fig6a-contact-pressure",
        "fig6b-contact-pressure",
        "fig7a-shear-traction",
        "fig7b-shear-traction",
        "fig7c-shear-traction",
        "fig8-deflection-hardening",
    ] {
        let csv = out.join(format!("{stem}.csv"));
        assert!(files.contains(&csv), "{stem}.csv not reported");
        let r = rows(&csv);
        assert!(r.len() >= 20, "{stem}: {} rows", r.len());
        assert!(
            r.iter().all(|(_, x, y)| x.is_finite() && y.is_finite()),
            "{stem}: non-finite value"
        );
        let series: std::collections::BTreeSet<&str> = r.iter().map(|r| r.0.as_str()).collect();
        assert!(series.len() >= 2, "{stem}: {series:?}");
    }
    // Fig. 8: settlement under the punch centre falls as h grows (E/100 → E/10)
    let r = rows(&out.join("fig8-deflection-hardening.csv"));
    let centre = |h: &str| r.iter().find(|(s, x, _)| s == h && *x == 0.0).unwrap().2;
    let seq: Vec<f64> = ["h = E/100", "h = E/50", "h = E/20", "h = E/10"]
        .iter()
        .map(|h| centre(h))
        .collect();
    assert!(
        seq.windows(2).all(|w| w[1] > w[0]),
        "settlements {seq:?} (negative = down)"
    );
    // the combined shrink fit's torque-twist loop (docs/joints.md): one
    // interface, from the origin through three cycles turned ±0.3 mrad at
    // the drive, its torque tips opposite and within 1 % of each other
    let csv = out.join("torque-twist-loop.csv");
    assert!(files.contains(&csv), "torque-twist-loop.csv not reported");
    let r = rows(&csv);
    assert!(r.len() > 100, "{} rows", r.len());
    assert!(r
        .iter()
        .all(|(s, x, y)| s.starts_with("fit (3 closed cycles") && x.is_finite() && y.is_finite()));
    assert_eq!((r[0].1, r[0].2), (0.0, 0.0));
    let (lo, hi) = r
        .iter()
        .fold((0.0f64, 0.0f64), |(a, b), p| (a.min(p.2), b.max(p.2)));
    assert!(
        lo < 0.0 && (hi + lo).abs() < 0.01 * hi,
        "torque tips {lo}, {hi} kN·mm"
    );
}
