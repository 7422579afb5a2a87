//! The designer's outputs (docs/output.md): reactions per boundary set that
//! balance the applied loads, probes, peaks with their place, the contact
//! extent, and that all of it survives a restart.

use crate::common;
use asperity::app::driver::{run, RunOptions};
use asperity::model::Model;
use asperity::solve::RunResult;
use std::path::{Path, PathBuf};

fn run_text(tag: &str, text: &str, extra: RunOptions) -> (PathBuf, Model, RunResult) {
    let path = common::case_dir(tag, text);
    let opts = RunOptions {
        out: Some(Path::new(env!("CARGO_TARGET_TMPDIR")).join(tag).join("out")),
        quiet: true,
        ..extra
    };
    run(&path, &opts).unwrap_or_else(|e| panic!("{tag}: {e}"))
}

fn data(case: &str) -> String {
    std::fs::read_to_string(
        common::root()
            .join("tests/data")
            .join(case)
            .join("case.toml"),
    )
    .unwrap()
}

/// Per increment: the sums of the reactions and of the applied forces, per
/// component, and the largest magnitude among them (the scale).
fn balance(model: &Model, r: &RunResult) -> Vec<([f64; 2], [f64; 2], f64)> {
    let plan = &model.plan;
    r.increments
        .iter()
        .map(|inc| {
            let v = &inc.record[plan.layout.reactions.clone()];
            let mut sum = [0.0; 2];
            let mut scale = 0.0f64;
            let mut k = 0;
            for g in &plan.reactions {
                for c in &g.components {
                    let axis = usize::from(c.label == "fy_n");
                    sum[axis] += v[k];
                    scale = scale.max(v[k].abs());
                    k += 1;
                }
            }
            let mut f = vec![0.0; model.mesh.num_dofs()];
            model.external_force(inc.load_factor, &mut f);
            let applied = [
                f.iter().step_by(2).sum::<f64>(),
                f.iter().skip(1).step_by(2).sum::<f64>(),
            ];
            let scale = scale.max(applied[0].abs()).max(applied[1].abs());
            (sum, applied, scale)
        })
        .collect()
}

/// A body loaded by a pressure, a concentrated force and a shear drag,
/// held by supports (the block pushed across a rough interface, with a
/// downward force on its side): in every increment the reactions sum to
/// minus the applied forces, per component, to 1e-9 of the largest force.
/// Axisymmetric, the axial component the same (the radial one is balanced
/// by the hoop stresses).
#[test]
fn reactions_sum_to_the_applied_loads() {
    let text = data("block-slip").replace(
        "[solver]\n",
        "[[force]]\nnodes = \"upper.right\"\nfy = -4.0\nhistory = \"press\"\n\n[solver]\nresidual_tolerance = 1e-13\n",
    );
    assert!(text.contains("[[force]]"));
    let (_, model, r) = run_text("designer-balance", &text, RunOptions::default());
    let names: Vec<&str> = model
        .plan
        .reactions
        .iter()
        .map(|g| g.name.as_str())
        .collect();
    assert_eq!(names, ["upper.top", "lower.bottom"]);
    let b = balance(&model, &r);
    assert_eq!(b.len(), 8);
    for (k, (sum, applied, scale)) in b.iter().enumerate() {
        for c in 0..2 {
            assert!(
                (sum[c] + applied[c]).abs() <= 1e-9 * scale,
                "increment {}: component {c}: reactions {} against applied {}",
                k + 1,
                sum[c],
                applied[c]
            );
        }
        // the pressure (200 N) and the force (4 N per node) act down
        assert!(applied[1] < -200.0 * (k + 1).min(4) as f64 / 4.0);
    }
    // axisymmetric: the axial balance
    let text =
        std::fs::read_to_string(common::root().join("tests/data/axisymmetric-punch/case.toml"))
            .unwrap();
    let text = text.replacen("[solver]\n", "[solver]\nresidual_tolerance = 1e-13\n", 1);
    assert!(text.contains("residual_tolerance = 1e-13"));
    let (_, model, r) = run_text("designer-balance-axi", &text, RunOptions::default());
    assert!(model.plan.reactions.iter().any(|g| g.name == "axis"));
    for (k, (sum, applied, scale)) in balance(&model, &r).iter().enumerate() {
        assert!(
            (sum[1] + applied[1]).abs() <= 1e-9 * scale,
            "axisymmetric increment {}: {} against {}",
            k + 1,
            sum[1],
            applied[1]
        );
    }
}

/// Loaded by a prescribed displacement alone (the stack pressed and pulled
/// apart): the two supports' reactions balance each other; the probes read
/// the prescribed displacement (a point snapped to the top corner, the mean
/// of the top), two coincident interface nodes told apart by `body`; and
/// the probes change nothing else (curve.csv and the reactions are those of
/// the case without them).
#[test]
fn prescribed_displacement_reactions_balance_and_probes_read_the_nodes() {
    let text = data("stack-separation");
    let (dir, model, r) = run_text("designer-stack", &text, RunOptions::default());
    let b = balance(&model, &r);
    let largest = b.iter().fold(0.0f64, |m, x| m.max(x.2));
    assert!(largest > 10.0, "{largest}");
    for (k, (sum, applied, _)) in b.iter().enumerate() {
        assert_eq!(applied, &[0.0, 0.0]);
        for s in sum {
            assert!(s.abs() <= 1e-9 * largest, "increment {}: {sum:?}", k + 1);
        }
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let probes = summary["probes"].as_array().unwrap();
    let named = |n: &str| probes.iter().find(|p| p["name"] == n).unwrap();
    assert_eq!(named("corner")["x_mm"], 10.0);
    assert_eq!(named("corner")["y_mm"], 5.0);
    assert_eq!(named("top")["node_count"], 9);
    let (a, b) = (named("edge upper"), named("edge lower"));
    assert_ne!(a["node"], b["node"]);
    assert_eq!((&a["x_mm"], &a["y_mm"]), (&b["x_mm"], &b["y_mm"]));
    let travel = |t: f64| if t <= 1.0 { -t } else { -1.0 + 2.2 * (t - 1.0) };
    let plan = &model.plan;
    for inc in &r.increments {
        let v = &inc.record[plan.layout.probes.clone()];
        let uy = 0.002 * travel(inc.load_factor);
        // corner, then top (mean): the prescribed value
        assert!((v[1] - uy).abs() < 1e-15, "{}: {}", inc.increment, v[1]);
        assert!((v[7] - uy).abs() < 1e-15, "{}: {}", inc.increment, v[7]);
        if inc.load_factor > 1.5 {
            // separated: the upper block moves rigidly, the lower one rests
            assert!((v[3] - uy).abs() < 1e-12 && v[5].abs() < 1e-12, "{v:?}");
        }
    }
    let csv = std::fs::read_to_string(dir.join("probes.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 5 * r.increments.len());
    assert!(csv.contains(",edge upper,"), "{csv}");
    // without the probes: the same curve and reactions
    let cut = text.find("\n[[probe]]").unwrap();
    let (bare, _, _) = run_text("designer-stack-bare", &text[..cut], RunOptions::default());
    for f in ["curve.csv", "reactions.csv", "peaks.csv", "contact.csv"] {
        assert_eq!(
            std::fs::read(dir.join(f)).unwrap(),
            std::fs::read(bare.join(f)).unwrap(),
            "{f}"
        );
    }
    assert_eq!(
        std::fs::read_to_string(bare.join("probes.csv")).unwrap(),
        "increment,time,probe,ux_mm,uy_mm\n"
    );
}

/// The paper's punch: the largest PEEQ over the bodies and the run is the
/// curve's last `max_peeq`, found at a Gauss point of the foundation; the
/// contact extent ends at the last pair with p > 0 of the last
/// interface/NNNN.csv, and the largest pressure is that file's.
#[test]
fn peaks_and_contact_extent_match_the_other_outputs() {
    let case = common::root().join("cases/punch-plane-stress");
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("designer-punch");
    let opts = RunOptions {
        out: Some(out.clone()),
        quiet: true,
        increments: Some(5),
        ..Default::default()
    };
    let (dir, _, r) = run(&case, &opts).unwrap();
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let peeq = s["final"]["max_peeq"].as_f64().unwrap();
    let peaks = s["peaks"].as_array().unwrap();
    let foundation = peaks.iter().find(|p| p["body"] == "foundation").unwrap();
    assert_eq!(foundation["max_peeq"]["value"].as_f64().unwrap(), peeq);
    assert_eq!(foundation["max_peeq"]["increment"], 5);
    let punch = peaks.iter().find(|p| p["body"] == "punch").unwrap();
    assert!(punch["max_peeq"].is_null(), "{punch}");
    assert!(punch["max_von_mises"]["value_mpa"].as_f64().unwrap() > 0.0);
    // the foundation's peak von Mises is at least its yield stress once it yields
    let vm = foundation["max_von_mises"]["value_mpa"].as_f64().unwrap();
    assert!(vm >= 196.0, "{vm}");
    let rows = std::fs::read_to_string(dir.join("peaks.csv")).unwrap();
    assert_eq!(rows.lines().count(), 1 + 2 * r.increments.len());
    // the last interface file: s and p of every pair
    let last = std::fs::read_to_string(dir.join("interface/0005.csv")).unwrap();
    let pairs: Vec<(f64, f64)> = last
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            (v[10].parse().unwrap(), v[1].parse().unwrap())
        })
        .collect();
    let to = pairs
        .iter()
        .filter(|p| p.1 > 0.0)
        .fold(f64::NEG_INFINITY, |m, p| m.max(p.0));
    let top = pairs.iter().fold(0.0f64, |m, p| m.max(p.1));
    let c = &s["contact"][0];
    let extent = &c["final_extent"];
    assert!(
        common::rel(extent["to_s_mm"].as_f64().unwrap(), to) < 1e-9,
        "{extent}"
    );
    assert_eq!(extent["from_s_mm"], 0.0);
    let p = c["max_pressure"]["value_mpa"].as_f64().unwrap();
    assert!(p >= top * (1.0 - 1e-9), "{p} vs {top}");
}

/// A run stopped after its full-slip event (shrink-fit: the push-out at
/// t ≈ 1.47, increment 30) and resumed writes the files of the
/// uninterrupted run, and the same events; so does one stopped before it.
#[test]
fn a_resumed_run_keeps_its_records_and_events() {
    let case = common::root().join("cases/shrink-fit");
    let root = common::scratch("designer-restart");
    let opts = |out: &Path| RunOptions {
        out: Some(out.to_path_buf()),
        quiet: true,
        ..Default::default()
    };
    let full = root.join("full");
    run(&case, &opts(&full)).unwrap();
    let summary = |d: &Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(d.join("summary.json")).unwrap()).unwrap()
    };
    let events = summary(&full)["events"].clone();
    assert_eq!(events[0]["event"], "full_slip", "{events}");
    for stop in [20, 31] {
        let part = root.join(format!("stopped-{stop}"));
        let (_, _, r) = run(
            &case,
            &RunOptions {
                hooks: asperity::app::options::Hooks {
                    stop_after: Some(stop),
                    ..Default::default()
                },
                ..opts(&part)
            },
        )
        .unwrap();
        assert!(r.stopped.is_some());
        // the searched events (a holding plateau is read off the increments
        // a partial run has, and the resumed run's own are compared below)
        let searched = summary(&part)["events"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|e| e["event"] != "holding_plateau")
            .count();
        assert_eq!(searched, usize::from(stop > 30));
        let resumed = root.join(format!("resumed-{stop}"));
        run(
            &case,
            &RunOptions {
                restart: Some(part.clone()),
                ..opts(&resumed)
            },
        )
        .unwrap();
        for f in [
            "reactions.csv",
            "probes.csv",
            "peaks.csv",
            "contact.csv",
            "curve.csv",
        ] {
            assert!(
                std::fs::read(resumed.join(f)).unwrap() == std::fs::read(full.join(f)).unwrap(),
                "stopped at {stop}: {f} differs"
            );
        }
        assert_eq!(summary(&resumed)["events"], events, "stopped at {stop}");
    }
}

/// The shipped bolted joint's service load F_A is two pressures of
/// −170.52 MPa on the annuli r ∈ [8.5, 12.5] of the outer plate faces
/// (π (12.5² − 8.5²) = 263.89 mm²): each load's own resultant is
/// ±p A h(t) = ±45.0 kN at the end in `loads.csv` and in summary.json's
/// `applied_loads` (N), although the two sum to zero; the pretension
/// section's force is there too, equal to pretension.csv's.
#[test]
fn each_applied_load_reports_its_own_resultant() {
    let text =
        std::fs::read_to_string(common::root().join("cases/bolted-joint/case.toml")).unwrap();
    let (dir, model, r) = run_text("applied-bolt", &text, RunOptions::default());
    let area = std::f64::consts::PI * (12.5f64.powi(2) - 8.5f64.powi(2));
    let csv = std::fs::read_to_string(dir.join("loads.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "increment",
            "time",
            "load[0]:fx_n",
            "load[0]:fy_n",
            "load[1]:fx_n",
            "load[1]:fy_n"
        ]
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), r.increments.len());
    for row in &rows {
        let t = row[1];
        let service = (t - 1.0).clamp(0.0, 1.0);
        let want = 170.52 * area * service;
        assert!(
            (row[3] - want).abs() <= 1e-9 * 45e3,
            "t = {t}: {} against {want}",
            row[3]
        );
        assert!(
            (row[5] + want).abs() <= 1e-9 * 45e3,
            "t = {t}: {} against {}",
            row[5],
            -want
        );
        assert!(
            row[2].abs() <= 1e-9 * 45e3 && row[4].abs() <= 1e-9 * 45e3,
            "{row:?}"
        );
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let applied = summary["applied_loads"].as_array().unwrap();
    assert_eq!(
        applied.len(),
        3,
        "two loads and the pretension section: {applied:?}"
    );
    let last = rows.last().unwrap();
    // the CSV keeps ten significant digits
    let near = |a: &serde_json::Value, b: f64| (a.as_f64().unwrap() - b).abs() <= 1e-9 * b.abs();
    assert!(near(&applied[0]["final"][1], last[3]), "{applied:?}");
    assert!(near(&applied[1]["min"][1], last[5]), "{applied:?}");
    assert_eq!(
        applied[0]["selection"],
        "edges top_plate.top, x in [8.5, 12.5]"
    );
    let bolt = r.increments.last().unwrap().sections[0][0];
    assert_eq!(applied[2]["final"][0].as_f64().unwrap(), bolt);
    assert_eq!(applied[2]["name"], "pretension bolt");
    assert_eq!(model.applied.len(), 2);
}

/// A prescribed motion reports the force its support applies: the twisted
/// shrink fit's drive turns the shaft's end, and its torque (N·m) in
/// `applied_loads` is the reaction group's `torque_nmm` / 1000.
#[test]
fn a_prescribed_motion_reports_its_support_force() {
    let text =
        std::fs::read_to_string(common::root().join("cases/shrink-fit-torque/case.toml")).unwrap();
    let text = text.replace("max_increment = 0.05", "max_increment = 0.25");
    let (dir, _model, _r) = run_text("applied-motion", &text, RunOptions::default());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let applied = summary["applied_loads"].as_array().unwrap();
    let drive = applied
        .iter()
        .find(|a| a["source"] == "boundary[1]")
        .expect("the drive");
    assert_eq!(
        drive["components"],
        serde_json::json!(["fy_n", "torque_nm"])
    );
    let group = summary["reactions"]
        .as_array()
        .unwrap()
        .iter()
        .find(|g| g["source"] == "boundary[1]")
        .unwrap();
    let torque_nmm = group["final"][1].as_f64().unwrap();
    assert!(
        torque_nmm.abs() > 1e5,
        "the fit holds a torque: {torque_nmm}"
    );
    assert_eq!(drive["final"][1].as_f64().unwrap(), torque_nmm * 1e-3);
    // the support that holds the hub still moves nothing: not an applied load
    assert!(
        applied.iter().all(|a| a["source"] != "boundary[0]"),
        "{applied:?}"
    );
}
