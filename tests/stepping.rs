//! Automatic step control on the punch: more accurate than the fixed schedule
//! at a similar cost, the same path for every method, and `study stability`
//! producing well-formed data on a small grid.

mod common;
use asperity::case::{Method, StepControl};
use asperity::driver::{self, RunOptions};
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
fn automatic_steps_take_the_same_path_with_every_method() {
    let results: Vec<RunResult> = [Method::FullNewton, Method::ModifiedNewton]
        .into_iter()
        .map(|m| {
            run(
                &format!("auto-{m:?}"),
                RunOptions {
                    method: Some(m),
                    step_control: Some(StepControl::Auto),
                    ..RunOptions::default()
                },
            )
        })
        .collect();
    let (a, b) = (settlement(&results[0]), settlement(&results[1]));
    assert!((a - b).abs() < 1e-6 * a.abs(), "{a} vs {b}");
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
    let case = asperity::case::Case::load(&dir.join("case.toml")).unwrap();
    assert_eq!(case.solver.step_mode(), StepControl::Auto);
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    std::fs::write(dir.join("case.toml"), text).unwrap();
    let case = asperity::case::Case::load(&dir.join("case.toml")).unwrap();
    assert_eq!(case.solver.step_mode(), StepControl::Fixed);
}

#[test]
fn the_stability_study_writes_a_well_formed_map() {
    let out = common::scratch("stepping-study");
    std::env::set_var("ASPERITY_EXE", env!("CARGO_BIN_EXE_asperity"));
    let (files, outcomes, best) = asperity::study::stability::stability(
        &common::root().join("cases/punch-plane-stress"),
        &[2, 10],
        &[Method::FullNewton],
        &[],
        &out,
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
