//! The damping outputs of the uniform elastic-perfectly-plastic loop of
//! `the_loop_area_of_identical_springs_is_the_reported_dissipation`: its
//! stored energy and loss factor against the closed form, damping.csv against
//! cycles.csv, backbone.csv against joints.csv.

use super::{column, csv};
use crate::common;
use serde_json::Value;

/// The elastic-perfectly-plastic loop of identical springs: slip force f_s,
/// amplitude a, elastic slip u_s, the step's bound on the dissipation.
pub(super) struct Epp {
    pub f_s: f64,
    pub a: f64,
    pub u_s: f64,
    pub bound: f64,
}

/// Tips (±a, ±f_s): F_a = f_s, u_a = a, U = ½ f_s a; D = 4 f_s (a − u_s)
/// (less at most the step's bound), so η = D / (2π U) = 4 (a − u_s) / (π a).
pub(super) fn loss_factor_of_the_epp_loop(out: &std::path::Path, e: &Epp, summary: &Value) {
    let (ch, cr) = csv(&out.join("cycles.csv"));
    let col = |name: &str| column(&ch, &cr, name);
    let (d, f_a, u_a, u, eta) = (
        col("dissipation_nmm"),
        col("force_amplitude_n"),
        col("slip_amplitude_mm"),
        col("stored_energy_nmm"),
        col("loss_factor"),
    );
    let closed = 4.0 * (e.a - e.u_s) / (std::f64::consts::PI * e.a);
    let eta_bound = e.bound / (std::f64::consts::PI * e.f_s * e.a);
    for c in 0..cr.len() {
        eprintln!(
            "cycle {}: F_a {:.6} N, u_a {:.6e} mm, U {:.6e} N·mm, η {:.6} (closed form {closed:.6}, \
             step bound {eta_bound:.1e})",
            c + 1,
            f_a[c],
            u_a[c],
            u[c],
            eta[c]
        );
        assert!(
            common::rel(f_a[c], e.f_s) < 1e-8,
            "F_a {} vs f_s {}",
            f_a[c],
            e.f_s
        );
        assert!(
            common::rel(u_a[c], e.a) < 1e-9,
            "u_a {} vs a {}",
            u_a[c],
            e.a
        );
        assert!(common::rel(u[c], 0.5 * e.f_s * e.a) < 1e-8, "U {}", u[c]);
        // the definition on the reported numbers (ten digits each)
        let def = d[c] / (2.0 * std::f64::consts::PI * u[c]);
        assert!(
            common::rel(eta[c], def) < 1e-8,
            "η {} vs D/(2πU) {def}",
            eta[c]
        );
        assert!(
            closed - eta[c] >= -1e-7 * closed && closed - eta[c] <= eta_bound + 1e-7 * closed,
            "cycle {c}: η {} vs the closed form {closed} (bound {eta_bound})",
            eta[c]
        );
        let s = &summary["joints"][0]["cycles"][c];
        for (key, v) in [
            ("force_amplitude_n", f_a[c]),
            ("slip_amplitude_mm", u_a[c]),
            ("stored_energy_nmm", u[c]),
            ("loss_factor", eta[c]),
        ] {
            assert!(
                common::rel(s[key].as_f64().unwrap(), v) < 1e-9,
                "{key}: {s}"
            );
        }
    }
}

/// damping.csv holds the numbers of cycles.csv (the same text), two cycles of
/// one amplitude are one block (the first carries the first loading, the
/// second is the steady value), and one amplitude gives no fit.
pub(super) fn damping_csv_is_cycles_csv_in_blocks(out: &std::path::Path, summary: &Value) {
    let (ch, cr) = csv(&out.join("cycles.csv"));
    let (dh, dr) = csv(&out.join("damping.csv"));
    assert_eq!(dr.len(), cr.len());
    let field = |h: &[String], r: &[String], name: &str| {
        r[h.iter().position(|x| x == name).unwrap()].clone()
    };
    for (c, d) in cr.iter().zip(&dr) {
        for name in [
            "interface",
            "cycle",
            "start_time",
            "end_time",
            "force_amplitude_n",
            "slip_amplitude_mm",
            "dissipation_nmm",
            "stored_energy_nmm",
            "loss_factor",
        ] {
            assert_eq!(field(&ch, c, name), field(&dh, d, name), "{name}");
        }
    }
    let flags: Vec<[String; 4]> = dr
        .iter()
        .map(|r| ["block", "first_in_block", "last_in_block", "in_fit"].map(|n| field(&dh, r, n)))
        .collect();
    assert_eq!(
        flags,
        [
            ["1", "true", "false", "false"],
            ["1", "false", "true", "false"]
        ]
        .map(|r| r.map(String::from))
    );
    let fit = &summary["damping"][0];
    assert_eq!(fit["interface"], "joint");
    assert_eq!(
        (fit["cycles"].as_u64(), fit["blocks"].as_u64()),
        (Some(2), Some(1))
    );
    assert_eq!(fit["cycles_used"], 0);
    assert!(
        fit["exponent"].is_null() && fit["coefficient"].is_null() && fit["r_squared"].is_null()
    );
}

/// backbone.csv: the rows of joints.csv (the same text) from the first
/// increment to the first reversal of F_T, at pseudo-time `tip`.
pub(super) fn backbone_is_the_first_loading(out: &std::path::Path, tip: f64) {
    let (jh, jr) = csv(&out.join("joints.csv"));
    let (bh, br) = csv(&out.join("backbone.csv"));
    let names = [
        "increment",
        "time",
        "tangential_force_n",
        "mean_slip_mm",
        "normal_force_n",
    ];
    let pick = |h: &[String], r: &[String]| {
        names.map(|n| r[h.iter().position(|x| x == n).unwrap()].clone())
    };
    assert!(!br.is_empty());
    for (k, b) in br.iter().enumerate() {
        assert_eq!(pick(&bh, b), pick(&jh, &jr[k]), "backbone row {k}");
    }
    let times = column(&bh, &br, "time");
    assert_eq!(
        *times.last().unwrap(),
        tip,
        "the backbone ends at the first tip"
    );
    let f = column(&jh, &jr, "tangential_force_n");
    let n = br.len();
    assert!(
        f[n].abs() < f[n - 1].abs(),
        "|F_T| drops after the backbone"
    );
    assert!(
        f[..n]
            .windows(2)
            .all(|w| w[1].abs() >= w[0].abs() * (1.0 - 1e-9)),
        "|F_T| never drops on the backbone"
    );
}
