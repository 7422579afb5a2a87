//! Automatic step control on the punch: more accurate than the fixed schedule
//! at a similar cost with every method, and `study stability` producing
//! well-formed data on a small grid.
//!
//! (Full and modified Newton do not take the same automatic path: the step
//! grows with the iteration count, which differs between the methods, so
//! their answers agree to the path accuracy the control is set to, not to
//! the Newton tolerance; both are held to that accuracy.)

use crate::common;
use asperity::app::driver::{self, RunOptions};
use asperity::input::case::{Method, StepControl};
use asperity::solve::RunResult;

fn run(tag: &str, opts: RunOptions) -> RunResult {
    let out = common::scratch(&format!("stepping-{tag}")).join("out");
    let opts = RunOptions {
        out: Some(out),
        quiet: true,
        ..opts
    };
    let case = common::root().join("cases/punch-plane-stress");
    driver::run(&case, &opts)
        .unwrap_or_else(|e| panic!("{tag}: {e}"))
        .2
}

fn settlement(r: &RunResult) -> f64 {
    r.increments.last().unwrap().measures.center_displacement
}

#[test]
fn automatic_steps_beat_the_fixed_schedule_in_accuracy_per_iteration() {
    let reference = run(
        "ref",
        RunOptions {
            increments: Some(160),
            ..RunOptions::default()
        },
    );
    let fixed = run("fixed", RunOptions::default());
    let auto = run(
        "auto",
        RunOptions {
            step_control: Some(StepControl::Auto),
            ..RunOptions::default()
        },
    );
    let r = settlement(&reference);
    let (ef, ea) = (
        ((settlement(&fixed) - r) / r).abs(),
        ((settlement(&auto) - r) / r).abs(),
    );
    let (nf, na) = (fixed.stats.iterations, auto.stats.iterations);
    eprintln!(
        "settlement error: fixed 20 steps {ef:.2e} ({nf} it), auto {ea:.2e} ({na} it, {} steps)",
        auto.increments.len()
    );
    assert!(ea < ef / 5.0, "auto {ea} vs fixed {ef}");
    // modified Newton's automatic path is as accurate
    let modified = run(
        "auto-modified",
        RunOptions {
            method: Some(Method::ModifiedNewton),
            step_control: Some(StepControl::Auto),
            ..RunOptions::default()
        },
    );
    let em = ((settlement(&modified) - r) / r).abs();
    eprintln!("modified Newton, auto: settlement error {em:.2e}");
    assert!(em < ef / 5.0, "auto (modified Newton) {em} vs fixed {ef}");
    assert!(na < 2 * nf, "auto needs {na} iterations against {nf}");
    // first yield is located by root finding, independent of the steps
    let (fa, ff) = (
        auto.first_yield.unwrap().total_load_kn,
        fixed.first_yield.unwrap().total_load_kn,
    );
    assert!((fa - ff).abs() < 1e-6 * ff, "{fa} vs {ff}");
    // the run ends on the full load
    assert_eq!(auto.increments.last().unwrap().load_factor, 1.0);
}

#[test]
fn a_case_without_a_schedule_gets_automatic_steps() {
    let dir = common::scratch("stepping-noschedule");
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let stripped: String = text
        .lines()
        .filter(|l| !l.starts_with("increments") && !l.starts_with("first_increment"))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(dir.join("case.toml"), stripped).unwrap();
    let case = asperity::input::case::Case::load(&dir.join("case.toml")).unwrap();
    assert_eq!(case.solver.step_mode(), StepControl::Auto);
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    std::fs::write(dir.join("case.toml"), text).unwrap();
    let case = asperity::input::case::Case::load(&dir.join("case.toml")).unwrap();
    assert_eq!(case.solver.step_mode(), StepControl::Fixed);
}

#[test]
fn the_stability_study_writes_a_well_formed_map() {
    let out = common::scratch("stepping-study");
    std::env::set_var("ASPERITY_EXE", env!("CARGO_BIN_EXE_asperity"));
    let (files, outcomes, best) = asperity::app::study::stability::stability(
        &common::root().join("cases/punch-plane-stress"),
        &[2, 10],
        &[Method::FullNewton],
        &[],
        &out,
        Some(std::time::Duration::from_secs(300)),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(files.contains(&out.join("stability-map.csv")));
    // two fixed columns and the automatic one, for one method
    assert_eq!(outcomes.len(), 3);
    assert!(
        outcomes.iter().all(|o| o.plain.is_ok()),
        "full Newton failed"
    );
    let csv = std::fs::read_to_string(out.join("stability-map.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 3, "{csv}");
    for r in &rows {
        assert!(r.starts_with("\"full-newton\","), "{r}");
        assert!(r.contains(",true,"), "{r}");
        assert!(r.contains("error "), "{r}");
    }
    // errors fall with smaller steps: 2 steps worse than 10
    let err = |r: &str| -> f64 {
        let t = r.split("error ").nth(1).unwrap();
        t.trim_end_matches("%\"").parse().unwrap()
    };
    assert!(err(rows[0]) > err(rows[1]), "{csv}");
    assert!(!best.is_empty());
}

/// Richardson extrapolation on a quantity whose order is known: the final
/// settlement of the plane-strain punch against the load step. The return
/// mapping is backward Euler, first order in the step, so the observed order
/// must be near 1. (The mesh order is not a fair check here: the punch edge is
/// a singular point and docs/verification.md ("Accuracy against mesh and time") discusses the order observed under refinement.)
#[test]
fn richardson_order_of_the_load_step_error_is_near_one() {
    let case = common::root().join("cases/punch-plane-strain");
    let q: Vec<f64> = [20usize, 40, 80]
        .iter()
        .map(|&n| {
            let opts = RunOptions {
                out: Some(common::scratch(&format!("stepping-order-{n}")).join("out")),
                quiet: true,
                increments: Some(n),
                ..RunOptions::default()
            };
            let r = driver::run(&case, &opts)
                .unwrap_or_else(|e| panic!("{e}"))
                .2;
            settlement(&r)
        })
        .collect();
    let (limit, order) = asperity::app::study::refine::richardson(
        [1.0 / 20.0, 1.0 / 40.0, 1.0 / 80.0],
        [q[0], q[1], q[2]],
    )
    .expect("a monotone sequence");
    eprintln!("settlements {q:?}: order {order:.3}, limit {limit:.6} mm");
    assert!((0.85..=1.15).contains(&order), "observed order {order}");
    // the limit lies beyond the finest value, on the side the sequence moves to
    assert!((limit - q[2]) * (q[2] - q[1]) > 0.0);
}

/// `study refine` on three small levels, graded and uniform, and an adaptive
/// run: a data row per run (per cycle), finite errors, error falling with
/// refinement on the graded mesh and over the adaptive cycles.
#[test]
fn the_refine_study_writes_well_formed_data() {
    use asperity::app::study::refine::{refine, Config};
    use asperity::app::study::runner::Which;
    std::env::set_var("ASPERITY_EXE", env!("CARGO_BIN_EXE_asperity"));
    let out = common::scratch("stepping-refine");
    let configs = [(false, false), (true, false), (false, true)].map(|(uniform, adapt)| Config {
        method: Method::FullNewton,
        levels: None,
        which: Which::Serial,
        uniform,
        adapt,
    });
    let (files, summary) = refine(
        &common::root().join("cases/punch-plane-stress"),
        &[1, 2, 3],
        &configs,
        &out,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(summary.contains("first-yield load"), "{summary}");
    let data = out.join("refine-data.csv");
    assert!(files.contains(&data));
    let csv = std::fs::read_to_string(&data).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').collect())
        .collect();
    // 3 graded, 3 uniform, then one row per adaptive cycle (8 at most)
    assert!((6 + 2..=6 + 8).contains(&rows.len()), "{csv}");
    // columns from the end: err_edge, err_center, err_first_yield, ...
    for (k, r) in rows.iter().enumerate() {
        for (j, v) in r[..3].iter().enumerate() {
            let e: f64 = v.parse().unwrap();
            // the adaptive rows have no edge pressure (one interface file kept)
            if k >= 6 && j == 0 {
                assert!(e.is_nan(), "{csv}");
                continue;
            }
            assert!(e.is_finite() && e >= 0.0, "{csv}");
        }
    }
    // the adaptive cycles: dofs and the summed wall time grow; the last
    // cycle's first-yield error is below the start mesh's (level 1)
    // (from the end: 7 wall_seconds, 8 dofs; the label holds commas)
    for w in rows[6..].windows(2) {
        let (d0, d1): (f64, f64) = (w[0][8].parse().unwrap(), w[1][8].parse().unwrap());
        let (t0, t1): (f64, f64) = (w[0][7].parse().unwrap(), w[1][7].parse().unwrap());
        assert!(d1 > d0 && t1 > t0, "{csv}");
    }
    let fy = |r: &Vec<&str>| -> f64 { r[2].parse().unwrap() };
    assert!(fy(rows.last().unwrap()) < fy(&rows[0]), "{csv}");
    // graded rows come first: the first-yield error falls level by level
    let e: Vec<f64> = rows[..3].iter().map(|r| r[2].parse().unwrap()).collect();
    assert!(e[0] > e[1] && e[1] > e[2], "{e:?}");
    for stem in ["refine-first_yield-dofs", "refine-center-time"] {
        assert!(
            files.contains(&out.join(format!("{stem}.csv")))
                || files.iter().any(|f| f.to_string_lossy().contains(stem)),
            "{stem} missing: {files:?}"
        );
    }
}
