//! The joint outputs as a user meets them (docs/output.md): `joints.csv`,
//! `cycles.csv`, the `joints` entry of `summary.json` and the hysteresis
//! figure; restarts carry the joint energies (and files of earlier builds
//! without them still resume).

use crate::common;
use asperity::interface::joint::{self, JointMeasures};
use asperity::model::Model;
use asperity::output::joints as out;
use asperity::solve::{Increment, Observer, State};
use serde_json::Value;
use std::path::Path;

fn asperity(args: &[&str]) -> (i32, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

fn run(case: &Path, dir: &Path, extra: &[&str]) {
    let (c, d) = (case.display().to_string(), dir.display().to_string());
    let mut args = vec!["run", &c, "--out", &d, "--quiet"];
    args.extend_from_slice(extra);
    let (code, err) = asperity(&args);
    assert_eq!(code, 0, "{err}");
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn summary(dir: &Path) -> Value {
    serde_json::from_str(&read(&dir.join("summary.json"))).unwrap()
}

/// joints.csv rows: (increment, interface, the 11 values).
fn joint_rows(dir: &Path) -> Vec<(usize, String, Vec<f64>)> {
    let text = read(&dir.join("joints.csv"));
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap().to_string() + "\n", out::JOINTS_HEADER);
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 3 + JointMeasures::PACKED, "{l}");
            (
                f[0].parse().unwrap(),
                f[2].to_string(),
                f[3..].iter().map(|v| v.parse().unwrap()).collect(),
            )
        })
        .collect()
}

#[test]
fn a_run_writes_joint_rows_matching_its_summary_and_no_figure_without_a_cycle() {
    let dir = common::scratch("joints-friction");
    let case = common::root().join("cases/punch-friction-b");
    run(&case, &dir, &["--increments", "4"]);
    let rows = joint_rows(&dir);
    assert_eq!(rows.len(), 4, "4 increments × 1 interface");
    assert_eq!(rows.iter().map(|r| r.0).collect::<Vec<_>>(), [1, 2, 3, 4]);
    let s = summary(&dir);
    let j = &s["joints"][0];
    assert_eq!(j["interface"], "contact");
    assert_eq!(
        (j["body_a"].as_str(), j["body_b"].as_str()),
        (Some("punch"), Some("foundation"))
    );
    assert_eq!(j["direction"], serde_json::json!([1.0, 0.0]));
    assert_eq!(j["measure_unit"], "mm");
    let fin = &j["final"];
    let last = &rows[3].2;
    for (k, key) in [
        "normal_force_n",
        "tangential_force_n",
        "mean_approach_mm",
        "mean_slip_mm",
        "open_measure",
        "closed_measure",
        "stick_measure",
        "micro_slip_measure",
        "macro_slip_measure",
        "dissipation_nmm",
        "work_nmm",
    ]
    .iter()
    .enumerate()
    {
        let v = fin[key].as_f64().unwrap();
        assert!(
            common::rel(v, last[k]) < 1e-9 || v == last[k],
            "{key}: {v} vs {}",
            last[k]
        );
    }
    // the punch (A) spreads outwards over the foundation: +x, a positive drag;
    // its 20 mm of interface all closed; friction dissipates
    assert!(last[1] > 0.0 && last[3] > 0.0, "{last:?}");
    // (the summary's full-precision values: the CSV has ten digits)
    let measure: f64 = [
        "open_measure",
        "closed_measure",
        "stick_measure",
        "micro_slip_measure",
        "macro_slip_measure",
    ]
    .iter()
    .map(|k| fin[k].as_f64().unwrap())
    .sum();
    assert!(common::rel(measure, 20.0) < 1e-12, "{measure}");
    assert!(last[9] > 0.0 && last[10] >= last[9], "{last:?}");
    // the whole-model load: F_N = mean pressure × 20 mm × 1 mm
    let p = s["final"]["mean_pressure_mpa"].as_f64().unwrap();
    assert!(common::rel(last[0], 20.0 * p) < 1e-9, "{} vs {p}", last[0]);
    // no histories: no cycle, no figure
    assert_eq!(read(&dir.join("cycles.csv")), out::CYCLES_HEADER);
    assert_eq!(j["cycles"], serde_json::json!([]));
    for f in ["hysteresis.svg", "hysteresis.png", "hysteresis.csv"] {
        assert!(!dir.join(f).exists(), "{f} written without a cycle");
    }
}

struct Quiet;
impl Observer for Quiet {
    fn increment(&mut self, _: &Model, _: &State, _: &Increment) -> asperity::Result<()> {
        Ok(())
    }
}

#[test]
fn a_closed_cycle_gets_its_row_and_the_hysteresis_figure() {
    let text = read(&common::root().join("cases/punch-friction-b/case.toml"))
        .replace("increments = 20", "increments = 2");
    let model = common::model(&text);
    let mut r = asperity::driver::solve(&model, &mut Quiet).unwrap();
    // a synthetic load history over the two real increments and five more:
    // the tangential factor 0 → 1 → −1 → 0 at t = 1 … 4 (breakpoints), the
    // joint a parallelogram loop
    let (k, f, d) = (2.0e4, 30.0, 0.01);
    let loop_pts = [
        (0.0, 0.0),
        (f / k, f),
        (d, f),
        (d - 2.0 * f / k, -f),
        (-d, -f),
        (-d + 2.0 * f / k, f),
        (0.0, f),
    ];
    let proto = r.increments[0].clone();
    r.increments = loop_pts
        .iter()
        .enumerate()
        .map(|(i, &(u, force))| {
            let mut inc = proto.clone();
            inc.increment = i + 1;
            inc.load_factor = 1.0 + 0.5 * i as f64;
            inc.joints = vec![JointMeasures {
                tangential_force: force,
                mean_slip: u,
                dissipation: 0.1 * i as f64,
                ..JointMeasures::default()
            }];
            inc
        })
        .collect();
    let times: Vec<f64> = r.increments.iter().map(|i| i.load_factor).collect();
    let joints: Vec<&[JointMeasures]> = r.increments.iter().map(|i| i.joints.as_slice()).collect();
    let values = |t: f64| vec![1.0, [0.0, 1.0, -1.0, 0.0][(t - 1.0).round() as usize]];
    let cycles = joint::cycles(&times, &joints, &[1.0, 2.0, 3.0, 4.0], values, 1);
    assert_eq!(cycles[0].len(), 1, "{cycles:?}");
    let c = &cycles[0][0];
    assert_eq!((c.start_increment, c.end_increment), (1, 7));
    assert!(common::rel(c.dissipation, 0.6) < 1e-12);
    assert!(
        common::rel(c.secant_stiffness.unwrap(), f / d) < 1e-12,
        "{c:?}"
    );
    let csv = out::cycles_csv(&model, &cycles);
    assert_eq!(csv.lines().count(), 2, "{csv}");
    assert!(csv
        .lines()
        .nth(1)
        .unwrap()
        .starts_with("contact,1,1,7,1.000000000,4.000000000,"));
    let dir = common::scratch("joints-hysteresis");
    let files = out::hysteresis(&model, &r, &cycles, &dir).unwrap();
    let points = read(&dir.join("hysteresis.csv"));
    // the origin, then one point per increment
    assert_eq!(points.lines().count(), 1 + 1 + loop_pts.len(), "{points}");
    if asperity::study::plot::load_font() {
        for f in ["hysteresis.svg", "hysteresis.png"] {
            assert!(files.contains(&dir.join(f)), "{f} not reported: {files:?}");
            let len = std::fs::metadata(dir.join(f)).unwrap().len();
            assert!(len > 1000, "{f}: {len} bytes");
        }
        assert!(read(&dir.join("hysteresis.svg")).contains("<svg"));
    }
    // no cycle: nothing drawn
    let none = common::scratch("joints-no-hysteresis");
    let empty = vec![Vec::new()];
    assert!(out::hysteresis(&model, &r, &empty, &none)
        .unwrap()
        .is_empty());
    assert_eq!(std::fs::read_dir(&none).unwrap().count(), 0);
}

#[test]
fn a_restart_carries_the_joint_energies_and_an_older_file_still_resumes() {
    let dir = common::scratch("joints-restart");
    let case = common::root().join("cases/punch-friction-b");
    let (full, part, old) = (dir.join("full"), dir.join("part"), dir.join("old"));
    run(&case, &full, &["--increments", "6"]);
    for o in [&part, &old] {
        let (c, d) = (case.display().to_string(), o.display().to_string());
        let (code, err) = asperity(&[
            "run",
            &c,
            "--increments",
            "6",
            "--out",
            &d,
            "--quiet",
            "--stop-after",
            "3",
        ]);
        assert_eq!(code, 3, "{err}");
    }
    run(
        &case,
        &part,
        &[
            "--increments",
            "6",
            "--restart",
            &part.display().to_string(),
        ],
    );
    assert_eq!(
        read(&full.join("joints.csv")),
        read(&part.join("joints.csv"))
    );
    assert_eq!(summary(&full)["joints"], summary(&part)["joints"]);
    // the same from a file of an earlier build: the earlier increments have
    // no joint rows and the energies start again from zero
    let rs = old.join("restart.bin");
    let stripped =
        common::strip_restart_sections(&std::fs::read(&rs).unwrap(), &["joints", "joint_totals"]);
    std::fs::write(&rs, stripped).unwrap();
    run(
        &case,
        &old,
        &["--increments", "6", "--restart", &old.display().to_string()],
    );
    let (a, b) = (joint_rows(&full), joint_rows(&old));
    assert_eq!(b.iter().map(|r| r.0).collect::<Vec<_>>(), [4, 5, 6]);
    for (x, y) in a[3..].iter().zip(&b) {
        assert_eq!(
            x.2[..9],
            y.2[..9],
            "increment {}: the state is the same",
            x.0
        );
        assert!(
            y.2[9] < x.2[9] && y.2[9] > 0.0,
            "D {} vs {}",
            y.2[9],
            x.2[9]
        );
    }
    let d_then = a[2].2[9];
    assert!(
        common::rel(a[5].2[9] - d_then, b[2].2[9]) < 1e-9,
        "D after the restart"
    );
}
