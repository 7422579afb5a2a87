//! Energy per cycle of a Hertzian line contact (issue 28): two equal
//! cylinders pressed together under a held normal load P, then sheared
//! 0 → +Q* → −Q* → +Q* → −Q* → +Q* at each of several amplitudes, in the
//! Coulomb limit (elastic stick, then |p_T| = μ p_N). The steady cycle's
//! dissipation against Mindlin-Deresiewicz for the line contact
//! (docs/theory.md, "Energy per cycle of a Hertzian line contact"):
//!
//! D(Q*) = (μP)²/(πE*) · [2(1 − y²) + 4y ln y],  y = 1 − Q*/(μP),
//!
//! 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂; D ≈ 2Q*³/(3πE*μP) at small amplitude.
//!
//! The two cylinders are mirror images of each other (R = 50 mm each, the
//! upper one's bottom and the lower one's top): pressing then moves both
//! surfaces alike and leaves no shear in the stick zone, as between two
//! half-planes of equal constants (a cylinder on a flat block leaves some,
//! cases/cattaneo-mindlin/README.md). D depends on P, μ and E* only.

use crate::common;

const E: f64 = 206_000.0;
const NU: f64 = 0.3;
const MU: f64 = 0.3;
/// Half-width of each body (mm), its height, the half-width of the band
/// about the contact beyond which the columns coarsen quickly.
const L: f64 = 15.0;
const H: f64 = 20.0;
const BAND: f64 = 1.3;
/// The band's columns (per side, from the middle out): 14 over |x| < 0.85
/// coarsening toward the middle (0.12 → 0.024 mm), 15 uniform ones of 0.01 mm
/// over 0.85 ≤ |x| ≤ 1.0 about the contact's edges (a ≈ 0.95 mm: the slip
/// zones c ≤ |x| ≤ a are 0.05 mm wide at Q*/μP = 0.1, 0.10 mm at 0.2), 10
/// growing from 0.014 to 0.055 mm out to |x| = 1.3; 12 more out to L
/// (0.25 → 3 mm). 12 rows, 0.015 mm at the contact, graded 600:1 in depth
/// (at 150:1, 0.049 mm, D at 0.1 came out 2 % higher: the first row was as
/// thick as the slip zone).
const EDGE: [f64; 2] = [0.85, 1.0];
/// The platen's approach: P ≈ 3.2 kN/mm, a ≈ 0.95 mm.
const APPROACH: f64 = 0.07;
/// Shear traction on the upper body's top (30 mm wide) per unit of the
/// `shear` history: 30 τ ≈ μP, so the history's values are about Q*/(μP).
const TAU: f64 = 32.63;
/// Increments per unit of pseudo-time (per half-cycle).
const INCREMENTS: usize = 8;
/// R of k_T^e = p^S / R (S = 0): 2e4 MPa/µm.
const R_T: f64 = 5.0e-5;

/// E* of two equal bodies, plane strain: 1/E* = 2(1 − ν²)/E.
fn e_star() -> f64 {
    E / (2.0 * (1.0 - NU * NU))
}

/// Mindlin-Deresiewicz for the line contact: the Masing loop's area.
fn mindlin(q: f64, p: f64) -> f64 {
    let y = 1.0 - q / (MU * p);
    (MU * p).powi(2) / (std::f64::consts::PI * e_star()) * (2.0 * (1.0 - y * y) + 4.0 * y * y.ln())
}

/// The case: each amplitude of `amps` (in units of TAU × width) reached
/// from the previous one over 0.25 of pseudo-time, then cycled twice, one
/// unit of pseudo-time per half-cycle; `inc` increments per unit.
fn case(amps: &[f64], inc: usize, r: f64) -> String {
    let mut shear = vec![(1.0, 0.0)];
    let mut t = 1.0;
    for &a in amps {
        t += 0.25;
        shear.push((t, a));
        for v in [-a, a, -a, a] {
            t += 1.0;
            shear.push((t, v));
        }
    }
    let shear: Vec<String> = shear.iter().map(|(t, v)| format!("[{t}, {v}]")).collect();
    let [e0, e1] = EDGE;
    let x = [-L, -BAND, -e1, -e0, 0.0, e0, e1, BAND, L];
    let nx = [12, 10, 15, 14, 14, 15, 10, 12];
    let rx = [1.0 / 12.0, 0.25, 1.0, 5.0, 0.2, 1.0, 4.0, 12.0];
    let ny = 12;
    common::case()
        .plane("strain")
        .block("upper", x, nx, [0.0, H], [ny])
        .rx(rx)
        .ry([600.0])
        .raw("bottom = { radius = 50.0, center = 0.0 }")
        .block("lower", x, nx, [-H, 0.0], [ny])
        .rx(rx)
        .ry([1.0 / 600.0])
        .raw("top = { radius = 50.0, center = 0.0 }")
        .interface("contact", "upper", "lower")
        .with("matching", false)
        .material("upper", E, NU)
        .material("lower", E, NU)
        .histories(&[
            ("press", "[[0.0, 0.0], [1.0, 1.0]]"),
            ("shear", &format!("[{}]", shear.join(", "))),
        ])
        .law("contact", "power", 5.0e-8, 1.0)
        .weights("consistent")
        .tangential("contact", r, 0.0, 1.0, MU)
        .with("beta", 1.0)
        .with("n", 0.0)
        .fixed("lower.bottom")
        .uy("upper.top", -APPROACH)
        .history("press")
        .shear("upper.top", TAU)
        .history("shear")
        .solver(&format!("increments = {inc}"))
        .no_vtu()
        .build()
}

#[test]
fn a_line_contact_dissipates_per_cycle_what_mindlin_and_deresiewicz_say() {
    // Q*/(μP) about 0.1, 0.2, 0.4, 0.8 (the history's values), two cycles each
    let amps = [0.1, 0.2, 0.4, 0.8];
    let text = case(&amps, INCREMENTS, R_T);
    let path = common::case_dir("damping-line", &text);
    let dir = path.parent().unwrap();
    let out = dir.join("out");
    let start = std::time::Instant::now();
    common::run_ok(dir, &out);
    eprintln!("damping-line: run {:.1} s", start.elapsed().as_secs_f64());

    // the normal load, held by the platen while the shear cycles
    let times = common::csv_column(&out.join("joints.csv"), "time");
    let normal = common::csv_column(&out.join("joints.csv"), "normal_force_n");
    let p = *normal.last().unwrap();
    for (t, n) in times.iter().zip(&normal).filter(|(t, _)| **t >= 1.0) {
        assert!(common::rel(*n, p) < 1e-4, "t = {t}: P {n} vs {p}");
    }
    let cycles = out.join("cycles.csv");
    let d = common::csv_column(&cycles, "dissipation_nmm");
    let (f_lo, f_hi) = (
        common::csv_column(&cycles, "force_min_n"),
        common::csv_column(&cycles, "force_max_n"),
    );
    assert_eq!(d.len(), 2 * amps.len(), "two closed cycles per amplitude");
    let mut rows = Vec::new();
    for k in 0..amps.len() {
        let c = 2 * k + 1; // the second (steady) cycle
        let q = 0.5 * (f_hi[c] - f_lo[c]);
        let want = mindlin(q, p);
        eprintln!(
            "damping-line: P = {p:.1} N/mm, Q*/μP = {:.4}: D cycle 1 {:.5e}, cycle 2 {:.5e} N·mm/mm, \
             Mindlin-Deresiewicz {want:.5e} ({:+.2} %), small-amplitude 2Q*³/(3πE*μP) {:.5e}",
            q / (MU * p),
            d[c - 1],
            d[c],
            100.0 * (d[c] / want - 1.0),
            2.0 * q.powi(3) / (3.0 * std::f64::consts::PI * e_star() * MU * p)
        );
        rows.push((q, d[c], want));
    }
    for &(q, d, want) in &rows {
        assert!(
            common::rel(d, want) < 0.05,
            "Q*/μP = {}: D {d} vs {want}",
            q / (MU * p)
        );
    }
    // the log-log slope between neighbouring amplitudes against the
    // formula's between the same two (3.08, 3.19, 3.57: 3 only as Q* → 0),
    // and between the two smallest (0.1 and 0.2) against 3 itself (issue 28)
    let slope = |a: (f64, f64), b: (f64, f64)| (b.1 / a.1).ln() / (b.0 / a.0).ln();
    let mut fe = Vec::new();
    for w in rows.windows(2) {
        let f = slope((w[0].0, w[0].1), (w[1].0, w[1].1));
        let th = slope((w[0].0, w[0].2), (w[1].0, w[1].2));
        eprintln!(
            "damping-line: log-log slope between Q*/μP = {:.3} and {:.3}: FE {f:.3}, \
             Mindlin-Deresiewicz {th:.3}",
            w[0].0 / (MU * p),
            w[1].0 / (MU * p)
        );
        assert!((f - th).abs() < 0.15, "slope {f} vs {th}");
        fe.push(f);
    }
    assert!(
        (fe[0] - 3.0).abs() < 0.15,
        "slope at small amplitude {} vs 3",
        fe[0]
    );
}

/// How stiff the stick must be: the same contact with k_T^e from 2e4 MPa/µm
/// (the test above) down to 20 MPa/µm, as the ratio k_T^e a / E* of the
/// springs' stiffness to the half-plane's over the contact (a the Hertz
/// half-width): the second cycle's D against Mindlin-Deresiewicz at
/// Q*/μP ≈ 0.1, 0.2, 0.4. The Coulomb limit is the stiff end; a soft stick
/// layer takes part of the tangential compliance from the bodies and
/// changes the slip zones. About 5 minutes: run with
/// `cargo test --release --test verification -- --ignored --nocapture damping_line`
/// (docs/theory.md "Energy per cycle of a Hertzian line contact" has the table).
#[test]
#[ignore]
fn the_error_against_mindlin_deresiewicz_falls_with_the_stick_stiffness() {
    let amps = [0.1, 0.2, 0.4];
    let mut worst = Vec::new();
    for r in [5.0e-3, 1.5e-3, 5.0e-4, 1.5e-4, 5.0e-5] {
        let path = common::case_dir(&format!("damping-line-r{r}"), &case(&amps, INCREMENTS, r));
        let dir = path.parent().unwrap();
        let out = dir.join("out");
        common::run_ok(dir, &out);
        let p = *common::csv_column(&out.join("joints.csv"), "normal_force_n")
            .last()
            .unwrap();
        let cycles = out.join("cycles.csv");
        let d = common::csv_column(&cycles, "dissipation_nmm");
        let (lo, hi) = (
            common::csv_column(&cycles, "force_min_n"),
            common::csv_column(&cycles, "force_max_n"),
        );
        // a from Hertz for two cylinders of R = 50 mm: a² = 4 P R* / (π E*)
        let a = (4.0 * p * 25.0 / (std::f64::consts::PI * e_star())).sqrt();
        let k = 1000.0 / r; // MPa/mm, S = 0
        let errors: Vec<f64> = (0..amps.len())
            .map(|i| {
                let c = 2 * i + 1;
                let q = 0.5 * (hi[c] - lo[c]);
                d[c] / mindlin(q, p) - 1.0
            })
            .collect();
        eprintln!(
            "stick stiffness k_T^e = {:.0} MPa/µm, k_T^e a / E* = {:.3}: D vs Mindlin-Deresiewicz {}",
            k / 1000.0,
            k * a / e_star(),
            errors
                .iter()
                .map(|e| format!("{:+.2} %", 100.0 * e))
                .collect::<Vec<_>>()
                .join(", ")
        );
        worst.push(errors.iter().fold(0.0f64, |m, e| m.max(e.abs())));
    }
    // the error falls as the stick stiffens (measured 64.5, 48.0, 26.2,
    // 9.0, 2.1 %), within the test's 5 % at the stiffest
    assert!(worst.windows(2).all(|w| w[0] > w[1]), "{worst:?}");
    assert!(worst[4] < 0.05, "{worst:?}");
}
