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
    let case = common::root().join("tests/bad_inputs/550-increments-flag-beside-load-factors");
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
