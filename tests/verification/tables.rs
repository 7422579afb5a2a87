//! Tabulated interface laws (issue 20): a `law = "table"` sampled from the
//! paper's power law u_N = c_N p^m (c_N = 0.001, m = 0.5) and a `k_table`
//! sampled from k_T^e = p^S/R (R = 0.9, S = 0.5) reproduce the punch cases of
//! the closed-form laws to within their interpolation error, and a table with
//! twice the segments comes closer.

use crate::common;
use asperity::app::driver::{self, RunOptions};
use asperity::physics::contact::TangentialLaw;
use asperity::solve::RunResult;

const C_N: f64 = 0.001;
const M: f64 = 0.5;
const R: f64 = 0.9;
const S: f64 = 0.5;
/// The FE quantities may differ from the closed-form law's by at most this
/// multiple of the table's largest relative interpolation error.
const MULTIPLE: f64 = 1.0;

/// `n` pressures from 2 to 1000 MPa, evenly in log p (the punch cases reach
/// about 940 MPa at the punch edge); `n = 2 k − 1` holds the points of `k`.
fn pressures(n: usize) -> Vec<f64> {
    let (lo, hi) = (2.0f64, 1000.0f64);
    (0..n)
        .map(|i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
        .collect()
}

fn toml_rows(rows: &[(f64, f64)]) -> String {
    let r: Vec<String> = rows
        .iter()
        .map(|(a, b)| format!("[{a:e}, {b:e}]"))
        .collect();
    format!("[{}]", r.join(", "))
}

/// The case text with the lines `law = "power"`, `c_n`, `m` of
/// `[interface.contact]` (and, for `k_table`, `r`, `s` of its tangential
/// table) replaced.
fn with_lines(case: &str, replace: &[(&str, &str)]) -> String {
    let text =
        std::fs::read_to_string(common::root().join("cases").join(case).join("case.toml")).unwrap();
    let mut out = Vec::new();
    let mut hits = 0;
    for line in text.lines() {
        match replace.iter().find(|(start, _)| line.starts_with(start)) {
            Some((_, new)) => {
                hits += 1;
                if !new.is_empty() {
                    out.push(new.to_string());
                }
            }
            None => out.push(line.to_string()),
        }
    }
    assert_eq!(
        hits,
        replace.len(),
        "{case}: every replaced line found once"
    );
    out.join("\n")
}

fn run(tag: &str, text: &str) -> (std::path::PathBuf, RunResult) {
    let path = common::case_dir(&format!("tables-{tag}"), text);
    let dir = path.parent().unwrap().to_path_buf();
    let out = dir.join("out");
    let opts = RunOptions {
        out: Some(out.clone()),
        quiet: true,
        ..RunOptions::default()
    };
    let (_, _, r) = driver::run(&dir, &opts).unwrap_or_else(|e| panic!("{tag}: {e}"));
    assert!(r.stopped.is_none(), "{tag}: the run is complete");
    (out, r)
}

/// Column `col` of the last increment's interface CSV, with x.
fn last_interface(out: &std::path::Path, col: &str) -> Vec<(f64, f64)> {
    let dir = out.join("interface");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let text = std::fs::read_to_string(files.last().unwrap()).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let j = head.iter().position(|h| *h == col).unwrap();
    lines
        .map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            (v[0].parse().unwrap(), v[j].parse().unwrap())
        })
        .collect()
}

/// Largest |a − b| over the profile, relative to the largest |b|.
fn profile_difference(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    assert_eq!(a.len(), b.len());
    let peak = b.iter().map(|v| v.1.abs()).fold(0.0, f64::max);
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            assert_eq!(x.0, y.0);
            (x.1 - y.1).abs()
        })
        .fold(0.0, f64::max)
        / peak
}

/// Largest relative difference of `f` and `exact` on 20 000 points of [lo, hi]
/// (evenly in log x).
fn max_rel_error(lo: f64, hi: f64, f: impl Fn(f64) -> f64, exact: impl Fn(f64) -> f64) -> f64 {
    (0..=20_000)
        .map(|i| {
            let x = lo * (hi / lo).powf(i as f64 / 20_000.0);
            common::rel(f(x), exact(x))
        })
        .fold(0.0, f64::max)
}

struct Compared {
    interpolation: f64,
    first_yield: f64,
    settlement: f64,
    profile: f64,
}

fn normal_table(n: usize, reference: &(std::path::PathBuf, RunResult)) -> Compared {
    let rows: Vec<(f64, f64)> = pressures(n).iter().map(|&p| (C_N * p.powf(M), p)).collect();
    let law = asperity::physics::contact::normal::table::new(&rows).unwrap();
    // p(u) against the power law over the table (below the first point the
    // table's power law is the paper's, exactly: checked too)
    let (u_lo, u_hi) = (rows[0].0 * 1e-2, rows[n - 1].0);
    let interpolation = max_rel_error(
        u_lo,
        u_hi,
        |u| law.pressure(u).0,
        |u| (u / C_N).powf(1.0 / M),
    );
    let text = with_lines(
        "punch-plane-stress",
        &[
            (
                "law = \"power\"",
                &format!("law = \"table\"\ntable = {}", toml_rows(&rows)),
            ),
            ("c_n = ", ""),
            ("m = ", ""),
        ],
    );
    let (out, r) = run(&format!("normal-{n}"), &text);
    let (ref_out, reference) = reference;
    let fy = r.first_yield.as_ref().unwrap().total_load_kn;
    let fy0 = reference.first_yield.as_ref().unwrap().total_load_kn;
    let last = |r: &RunResult| r.increments.last().unwrap().measures.center_displacement;
    Compared {
        interpolation,
        first_yield: common::rel(fy, fy0),
        settlement: common::rel(last(&r), last(reference)),
        profile: profile_difference(
            &last_interface(&out, "p_n_mpa"),
            &last_interface(ref_out, "p_n_mpa"),
        ),
    }
}

fn report(what: &str, n: usize, c: &Compared) {
    eprintln!(
        "{what}, {n} points: interpolation error {:.3e}; first-yield load {:.3e}, settlement {:.3e}, final profile {:.3e} (relative differences)",
        c.interpolation, c.first_yield, c.settlement, c.profile
    );
}

fn within(what: &str, c: &Compared) {
    assert!(
        c.interpolation > 0.0,
        "{what}: the table is not the law itself"
    );
    for (q, d) in [
        ("first-yield load", c.first_yield),
        ("settlement", c.settlement),
        ("pressure/shear profile", c.profile),
    ] {
        assert!(
            d <= MULTIPLE * c.interpolation,
            "{what}: {q} differs by {d:.3e}, more than {MULTIPLE} × the interpolation error {:.3e}",
            c.interpolation
        );
    }
}

#[test]
fn a_table_sampled_from_the_power_law_reproduces_the_punch_to_its_interpolation_error() {
    let reference = run(
        "power",
        &std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml"))
            .unwrap(),
    );
    let coarse = normal_table(10, &reference);
    report("normal table", 10, &coarse);
    within("10 points", &coarse);
    let fine = normal_table(19, &reference);
    report("normal table", 19, &fine);
    within("19 points", &fine);
    // twice the segments: the law and the FE results come closer
    assert!(fine.interpolation < coarse.interpolation);
    assert!(fine.settlement < coarse.settlement);
    assert!(fine.first_yield < coarse.first_yield);
    assert!(fine.profile < coarse.profile);
}

fn k_table(n: usize, reference: &(std::path::PathBuf, RunResult)) -> Compared {
    // rows in MPa/µm, as the case file gives them
    let rows: Vec<(f64, f64)> = pressures(n).iter().map(|&p| (p, p.powf(S) / R)).collect();
    let law = TangentialLaw::with_k_table(&rows, 1.0, 0.2, 1.0, 275.0, 0.625).unwrap();
    let exact = TangentialLaw::new(R, S, 1.0, 0.2, 1.0, 275.0, 0.625).unwrap();
    let interpolation = max_rel_error(
        rows[0].0 * 1e-2,
        rows[n - 1].0,
        |p| law.elastic_stiffness(p).0,
        |p| exact.elastic_stiffness(p).0,
    );
    let text = with_lines(
        "punch-friction-a",
        &[
            ("r = 0.9", &format!("k_table = {}", toml_rows(&rows))),
            ("s = 0.5", ""),
        ],
    );
    let (out, r) = run(&format!("tangential-{n}"), &text);
    let (ref_out, reference) = reference;
    let fy = r.first_yield.as_ref().unwrap().total_load_kn;
    let fy0 = reference.first_yield.as_ref().unwrap().total_load_kn;
    let last = |r: &RunResult| r.increments.last().unwrap().measures.center_displacement;
    Compared {
        interpolation,
        first_yield: common::rel(fy, fy0),
        settlement: common::rel(last(&r), last(reference)),
        profile: profile_difference(
            &last_interface(&out, "p_t_mpa"),
            &last_interface(ref_out, "p_t_mpa"),
        ),
    }
}

#[test]
fn a_k_table_sampled_from_p_s_over_r_reproduces_punch_friction_a() {
    let reference = run(
        "friction-a",
        &std::fs::read_to_string(common::root().join("cases/punch-friction-a/case.toml")).unwrap(),
    );
    let coarse = k_table(10, &reference);
    report("k_table", 10, &coarse);
    within("k_table 10 points", &coarse);
    let fine = k_table(19, &reference);
    report("k_table", 19, &fine);
    within("k_table 19 points", &fine);
    assert!(fine.interpolation < coarse.interpolation);
    assert!(fine.profile < coarse.profile);
}
