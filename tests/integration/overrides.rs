//! Command-line overrides of the load steps and what a run says about its
//! steps: `--increments` and `--step-control` against the case's schedule,
//! the `cutback` events' next target, the suggested restart command.

use crate::common;
use serde_json::Value;

/// A `cutback` event names the target actually tried next: the midpoint
/// under fixed steps, the automatic control's resized step when it rejects
/// a step for its plastic strain (the line said "halving it" for both until
/// 2026-11-27). The attempt after every cutback (a converged increment or
/// another cutback) starts at `from` and goes to `next_to`.
#[test]
fn a_cutback_event_names_the_step_tried_next() {
    let dir = common::scratch("robust-cutback-next");
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let i = text.find("\n[solver]\n").unwrap();
    for (name, solver, redone) in [
        // a step far above the plastic strain target: redone smaller
        (
            "auto",
            "step_control = \"auto\"\nmax_increment = 0.5\nplastic_strain_step = 2e-4\n",
            "plastic strain increment",
        ),
        // two iterations cannot converge the contact's first step: halved
        (
            "fixed",
            "increments = 2\nmax_iterations = 3\nmax_cutbacks = 3\n",
            "",
        ),
    ] {
        let case = common::case_dir(
            &format!("robust-cutback-{name}"),
            &format!("{}\n[solver]\n{solver}", &text[..i]),
        );
        let out = dir.join(name).display().to_string();
        let (_, err, _) = common::run_asperity_out(&[
            "run",
            case.to_str().unwrap(),
            "--out",
            &out,
            "--log-format",
            "json",
        ]);
        let ev: Vec<Value> = err
            .lines()
            .filter_map(|l| serde_json::from_str::<Value>(l).ok())
            .collect();
        let cuts: Vec<usize> = (0..ev.len())
            .filter(|&k| ev[k]["event"] == "cutback")
            .collect();
        assert!(!cuts.is_empty(), "{name}: no cutback\n{err}");
        let mut seen_redo = false;
        for &k in &cuts {
            let c = &ev[k];
            let (from, to, next) = (
                c["from"].as_f64().unwrap(),
                c["to"].as_f64().unwrap(),
                c["next_to"].as_f64().unwrap(),
            );
            assert!(next > from && next < to, "{name}: {c}");
            let reason = c["reason"].as_str().unwrap();
            if name == "fixed" {
                assert!((next - 0.5 * (from + to)).abs() < 1e-12, "{c}");
            } else if reason.contains(redone) {
                seen_redo = true;
            }
            // what came next tried `next`
            let after = ev[k + 1..]
                .iter()
                .find(|e| e["event"] == "increment" || e["event"] == "cutback");
            if let Some(a) = after {
                let tried = if a["event"] == "increment" {
                    a["load_factor"].as_f64().unwrap()
                } else {
                    assert_eq!(a["from"].as_f64(), Some(from), "{name}: {a}");
                    a["to"].as_f64().unwrap()
                };
                assert!((tried - next).abs() <= 1e-12, "{name}: {c} then {a}");
            }
        }
        assert!(
            name == "fixed" || seen_redo,
            "{name}: no plastic redo\n{err}"
        );
    }
}

/// `--increments N` is N equal steps, as its help says, also on a case
/// whose `[solver]` asks for automatic steps (it took N only as the size of
/// the automatic control's first step until 2026-11-27); with
/// `--step-control auto` beside it, that is what it does.
#[test]
fn increments_on_the_command_line_are_equal_steps_in_an_automatic_case() {
    let case = common::root().join("cases/punch-rounded-stress");
    let text = std::fs::read_to_string(case.join("case.toml")).unwrap();
    assert!(text.contains("step_control = \"auto\""));
    let dir = common::scratch("robust-increments-auto");
    for (name, extra, mode, lambdas) in [
        ("fixed", vec![], "fixed", [0.25, 0.5]),
        // the first step 1/4, capped by the case's max_increment (0.05)
        ("auto", vec!["--step-control", "auto"], "auto", [0.05, 0.1]),
    ] {
        let out = dir.join(name);
        let mut args = vec!["--increments", "4", "--stop-after", "2"];
        args.extend(extra);
        let (code, err) = common::run_case(&case, &out, &args);
        assert_eq!(code, 3, "{name}: {err}");
        let s: Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(s["step_control"], mode, "{name}");
        let got: Vec<f64> = common::csv_column(&out.join("curve.csv"), "load_factor");
        assert_eq!(got.len(), 2, "{name}: {got:?}");
        for (g, w) in got.iter().zip(lambdas) {
            assert!(
                (g - w).abs() < 1e-12,
                "{name}: load factors {got:?}, expected {lambdas:?}"
            );
        }
    }
    // automatic steps keep a case's load_factors as waypoints (the unloading
    // to 0.2 here); fixed steps would replace them, which is refused
    // (tests/bad_inputs/550)
    let case = common::corpus::bad_input("550-increments-flag-beside-load-factors");
    let out = dir.join("waypoints");
    let (code, err) = common::run_case(
        &case,
        &out,
        &[
            "--increments",
            "8",
            "--step-control",
            "auto",
            "--stop-after",
            "5",
        ],
    );
    assert_eq!(code, 3, "{err}");
    let got: Vec<f64> = common::csv_column(&out.join("curve.csv"), "load_factor");
    let want = [0.125, 0.3, 0.6, 0.35, 0.2];
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() < 1e-9,
            "load factors {got:?}, expected {want:?}"
        );
    }
}

/// The command a stopped run suggests for continuing repeats the run's
/// overrides and its output folder (a restart must be given the same
/// overrides; the suggestion without them was refused as a fingerprint
/// mismatch), and it runs to the end.
#[test]
fn the_suggested_restart_command_repeats_the_overrides_and_runs() {
    let dir = common::scratch("overrides-resume");
    let out = dir.join("out");
    let case = common::root().join("cases/punch-plane-stress");
    let (code, err) = common::run_case(
        &case,
        &out,
        &[
            "--refine",
            "2",
            "--increments",
            "6",
            "--step-control",
            "auto",
            "--stop-after",
            "2",
        ],
    );
    assert_eq!(code, 3, "{err}");
    let line = err.lines().find(|l| l.contains("continue with")).unwrap();
    let command = line.split('`').nth(1).unwrap();
    let args: Vec<&str> = command.split_whitespace().collect();
    assert_eq!(args[..2], ["asperity", "run"], "{command}");
    for want in [
        "--refine 2",
        "--increments 6",
        "--step-control auto",
        "--restart",
    ] {
        assert!(command.contains(want), "{command}");
    }
    let (code, err, _) = common::run_asperity_out(&args[1..]);
    assert_eq!(code, 0, "{command}: {err}");
    let s: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["complete"], true);
    assert_eq!(s["final"]["load_factor"], 1.0);
}

/// `check` prints the load factor the run's first increment goes to, as
/// the run takes it (one function: the case's initial stepper asked from
/// λ = 0): under automatic steps capped by `max_increment`, onto a waypoint
/// of `load_factors` or a history breakpoint within reach, and with the
/// command line's overrides, which `check` takes as `run` does. It printed
/// `first_increment` (or 1/increments) whatever the run took, and took no
/// overrides, until issue 42.
#[test]
fn check_prints_the_first_step_the_run_takes() {
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let ramp = text.replace(
        "pressure = 250.0 ",
        "history = [[0.0, 0.0], [0.03, 0.03], [1.0, 1.0]]\npressure = 250.0 ",
    );
    let auto = "method = \"full-newton\"\nstep_control = \"auto\"\n";
    let variants: [(&str, String, &[&str], f64); 7] = [
        // the first step capped by max_increment (check said 0.5)
        (
            "capped",
            common::with_solver_table(
                &text,
                &format!("{auto}first_increment = 0.5\nmax_increment = 0.1"),
            ),
            &[],
            0.1,
        ),
        // a waypoint within 1.2 steps is taken (check said 0.05)
        (
            "waypoint",
            common::with_solver_table(
                &text,
                &format!("{auto}first_increment = 0.05\nload_factors = [0.06, 1.0]"),
            ),
            &[],
            0.06,
        ),
        // a waypoint nearer than the first step (check said 0.05)
        (
            "breakpoint",
            common::with_solver_table(&ramp, &format!("{auto}first_increment = 0.05")),
            &[],
            0.03,
        ),
        // fixed steps with a first increment
        (
            "fixed-first",
            common::with_solver_table(&text, "increments = 10\nfirst_increment = 0.02"),
            &[],
            0.02,
        ),
        // the overrides: 1/4 capped by the case's max_increment
        (
            "overrides-auto",
            common::with_solver_table(&text, &format!("{auto}max_increment = 0.04")),
            &["--increments", "4", "--step-control", "auto"],
            0.04,
        ),
        // --step-control fixed drops max_increment; the case's first_increment stays
        (
            "overrides-fixed",
            common::with_solver_table(
                &text,
                &format!("{auto}first_increment = 0.03\nmax_increment = 0.02"),
            ),
            &["--step-control", "fixed"],
            0.03,
        ),
        // --increments replaces the case's first_increment
        (
            "overrides-increments",
            common::with_solver_table(&text, "increments = 20\nfirst_increment = 0.01"),
            &["--increments", "25"],
            0.04,
        ),
    ];
    let dir = common::scratch("overrides-first-step");
    for (name, case_text, overrides, want) in variants {
        let case = common::case_dir(&format!("overrides-first-step-{name}"), &case_text);
        let c = case.to_str().unwrap();
        let mut args = vec!["check", c];
        args.extend_from_slice(overrides);
        let (code, err, out) = common::run_asperity_out(&args);
        assert_eq!(code, 0, "{name}: {err}");
        let line = out.lines().find(|l| l.contains("solver:")).unwrap();
        let printed: f64 = line
            .split("first to λ = ")
            .nth(1)
            .and_then(|r| r.split([',', ')']).next())
            .unwrap_or_else(|| panic!("{name}: no first step in {line:?}"))
            .parse()
            .unwrap();
        let out_dir = dir.join(name);
        let mut run = vec!["--stop-after", "1"];
        run.extend_from_slice(overrides);
        let (code, err) = common::run_case(&case, &out_dir, &run);
        assert_eq!(code, 3, "{name}: {err}");
        let taken = common::csv_column(&out_dir.join("curve.csv"), "load_factor")[0];
        assert!(
            (printed - taken).abs() < 1e-9 && (taken - want).abs() < 1e-9,
            "{name}: check printed {printed}, the run took {taken}, expected {want}"
        );
    }
}

/// Every override of the case (each option `check` takes, as `run` does)
/// has a bad input in tests/bad_inputs whose refusal arises from the
/// setting it made and names it first (`--increments 60000: …`; the corpus
/// runner checks `run` and `check` with the option give that very line),
/// so that a new override gets one too. Until issue 42 an `--increments`
/// too large through histories, a `--friction-scheme` that twist refuses
/// and a `--uniform` that unmatched a body's blocks were blamed on keys of
/// the case file, which did not hold them. `--plain` (no Anderson
/// acceleration) makes no setting any check refuses.
#[test]
fn every_override_has_a_refusal_that_names_it() {
    let (code, _, help) = common::run_asperity_out(&["check", "--help"]);
    assert_eq!(code, 0);
    let options: Vec<&str> = help
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("--"))
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    assert!(options.len() >= 9, "{options:?}");
    let refuses_nothing = ["plain"];
    let corpus = common::corpus::folders();
    let mut missing = Vec::new();
    for option in options {
        let flag = format!("--{option}");
        let named = corpus.iter().any(|dir| {
            let args = std::fs::read_to_string(dir.join("args.txt")).unwrap_or_default();
            let expect = std::fs::read_to_string(dir.join("expect.txt")).unwrap_or_default();
            args.lines().next() == Some(flag.as_str()) && expect.starts_with(&flag)
        });
        if named == refuses_nothing.contains(&option) {
            missing.push(flag);
        }
    }
    assert!(
        missing.is_empty(),
        "overrides without a bad input that names them (or with one, though listed as refusing nothing): {missing:?}"
    );
}
