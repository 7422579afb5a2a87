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
use std::path::Path;
use std::process::Command;

const E: f64 = 206_000.0;
const NU: f64 = 0.3;
const MU: f64 = 0.3;
/// Half-width of each body (mm), its height, the half-width of the
/// uniformly meshed band about the contact.
const L: f64 = 15.0;
const H: f64 = 20.0;
const BAND: f64 = 1.3;
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
    let (nmid, nout, ny) = (64usize, 14usize, 12usize);
    common::case()
        .plane("strain")
        .block(
            "upper",
            [-L, -BAND, BAND, L],
            [nout, nmid, nout],
            [0.0, H],
            [ny],
        )
        .rx([1.0 / 12.0, 1.0, 12.0])
        .ry([150.0])
        .raw("bottom = { radius = 50.0, center = 0.0 }")
        .block(
            "lower",
            [-L, -BAND, BAND, L],
            [nout, nmid, nout],
            [-H, 0.0],
            [ny],
        )
        .rx([1.0 / 12.0, 1.0, 12.0])
        .ry([1.0 / 150.0])
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

/// Column `name` of a CSV file as numbers.
fn column(path: &Path, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let k = head
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no column {name} in {head:?}"));
    lines
        .map(|l| l.split(',').nth(k).unwrap().parse().unwrap())
        .collect()
}

#[test]
fn a_line_contact_dissipates_per_cycle_what_mindlin_and_deresiewicz_say() {
    // Q*/(μP) about 0.2, 0.4, 0.8 (the history's values), two cycles each
    let amps = [0.2, 0.4, 0.8];
    let text = case(&amps, INCREMENTS, R_T);
    let path = common::case_dir("damping-line", &text);
    let dir = path.parent().unwrap();
    let out = dir.join("out");
    let start = std::time::Instant::now();
    let run = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .arg("run")
        .arg(dir)
        .arg("--out")
        .arg(&out)
        .arg("--quiet")
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    eprintln!("damping-line: run {:.1} s", start.elapsed().as_secs_f64());

    // the normal load, held by the platen while the shear cycles
    let times = column(&out.join("joints.csv"), "time");
    let normal = column(&out.join("joints.csv"), "normal_force_n");
    let p = *normal.last().unwrap();
    for (t, n) in times.iter().zip(&normal).filter(|(t, _)| **t >= 1.0) {
        assert!(common::rel(*n, p) < 1e-4, "t = {t}: P {n} vs {p}");
    }
    let cycles = out.join("cycles.csv");
    let d = column(&cycles, "dissipation_nmm");
    let (f_lo, f_hi) = (
        column(&cycles, "force_min_n"),
        column(&cycles, "force_max_n"),
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
    // the log-log slope between the two smallest amplitudes, against the
    // formula's between the same two (3 only in the limit Q* → 0)
    let slope = |a: (f64, f64), b: (f64, f64)| (b.1 / a.1).ln() / (b.0 / a.0).ln();
    let fe = slope((rows[0].0, rows[0].1), (rows[1].0, rows[1].1));
    let th = slope((rows[0].0, rows[0].2), (rows[1].0, rows[1].2));
    eprintln!("damping-line: log-log slope FE {fe:.3}, Mindlin-Deresiewicz {th:.3}");
    assert!((fe - th).abs() < 0.15, "slope {fe} vs {th}");
}
