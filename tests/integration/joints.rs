//! The joint outputs as a user meets them (docs/output.md): `joints.csv`,
//! `cycles.csv`, the `joints` entry of `summary.json` and the hysteresis
//! figure; restarts carry the joint energies (and files of earlier builds
//! without them still resume).

use crate::common;
use asperity::files::output::joints_csv as out;
use asperity::measure::joint::{self, JointMeasures};
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
    assert_eq!(
        read(&dir.join("damping.csv")),
        asperity::files::output::damping::DAMPING_HEADER
    );
    assert!(s["damping"][0]["exponent"].is_null(), "{s}");
    for f in [
        "hysteresis.svg",
        "hysteresis.png",
        "hysteresis.csv",
        "damping.svg",
        "damping.png",
    ] {
        assert!(!dir.join(f).exists(), "{f} written without a cycle");
    }
    // the backbone: the rows up to the first drop of |F_T| (the punch's
    // drag falls once it yields), the last row where it does not drop
    let f: Vec<f64> = rows.iter().map(|r| r.2[1].abs()).collect();
    let end = (0..3).find(|&k| f[k + 1] < f[k]).unwrap_or(3);
    let backbone = read(&dir.join("backbone.csv"));
    assert_eq!(backbone.lines().count(), 1 + end + 1, "{backbone}");
    for (b, r) in backbone.lines().skip(1).zip(&rows) {
        assert!(b.starts_with(&format!("contact,{},", r.0)), "{b}");
    }
}

use crate::common::Quiet;

#[test]
fn a_closed_cycle_gets_its_row_and_the_hysteresis_figure() {
    let text = read(&common::root().join("cases/punch-friction-b/case.toml"))
        .replace("increments = 20", "increments = 2");
    let model = common::model(&text);
    let mut r = asperity::app::driver::solve(&model, &mut Quiet).unwrap();
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
    if asperity::files::plot::load_font() {
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

/// A stopped and resumed run writes the uninterrupted run's joints.csv and
/// summary; a restart file without the joint sections (as the builds before
/// them wrote it) is refused naming the first one missing, and the folder
/// it is in stays as it was.
#[test]
fn a_restart_carries_the_joint_energies_and_a_file_without_them_is_refused() {
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
    let rs = old.join("restart.bin");
    let stripped =
        common::strip_restart_sections(&std::fs::read(&rs).unwrap(), &["joints", "joint_totals"]);
    std::fs::write(&rs, &stripped).unwrap();
    let joints = read(&old.join("joints.csv"));
    let (c, d) = (case.display().to_string(), old.display().to_string());
    let (code, err) = asperity(&[
        "run",
        &c,
        "--increments",
        "6",
        "--out",
        &d,
        "--quiet",
        "--restart",
        &d,
    ]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(
        err.trim_end(),
        format!(
            "error: {}: section joint_totals missing: every restart file of format 5 holds it",
            rs.display()
        )
    );
    assert_eq!(std::fs::read(&rs).unwrap(), stripped);
    assert_eq!(read(&old.join("joints.csv")), joints);
}

/// A CSV file's header and rows.
fn table(p: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = read(p);
    let mut lines = text.lines();
    let head = lines.next().unwrap().split(',').map(String::from).collect();
    (
        head,
        lines
            .map(|l| l.split(',').map(String::from).collect())
            .collect(),
    )
}

/// Column `name` as numbers (an empty field as NaN).
fn numbers(t: &(Vec<String>, Vec<Vec<String>>), name: &str) -> Vec<f64> {
    let k =
        t.0.iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("{name}"));
    t.1.iter()
        .map(|r| r[k].parse().unwrap_or(f64::NAN))
        .collect()
}

/// The damping.csv flags `name` (`true` / `false`) and the sweep's rows.
fn flags(d: &(Vec<String>, Vec<Vec<String>>), name: &str) -> Vec<bool> {
    let k = d.0.iter().position(|h| h == name).unwrap();
    d.1.iter().map(|r| r[k].parse().unwrap()).collect()
}

#[test]
fn the_slideway_sweep_fits_its_three_rising_amplitudes() {
    // cases/slideway-cycles: one cycle 0 → +a → −a → 0 at each of a = 0.3,
    // 0.6, 0.95 of μ p (shear traction 3 MPa on 60 mm): three blocks of one
    let dir = common::scratch("joints-sweep-slideway");
    run(&common::root().join("cases/slideway-cycles"), &dir, &[]);
    let d = table(&dir.join("damping.csv"));
    assert_eq!(
        d.0.join(",") + "\n",
        asperity::files::output::damping::DAMPING_HEADER
    );
    assert_eq!(numbers(&d, "block"), [1.0, 2.0, 3.0]);
    for name in ["first_in_block", "last_in_block", "in_fit"] {
        assert_eq!(flags(&d, name), [true; 3], "{name}");
    }
    // equilibrium under force control: F_a = a · 3 MPa · 60 mm
    let f_a = numbers(&d, "force_amplitude_n");
    for (f, want) in f_a.iter().zip([54.0, 108.0, 171.0]) {
        assert!(common::rel(*f, want) < 1e-6, "F_a {f} vs {want}");
    }
    let (diss, u, eta) = (
        numbers(&d, "dissipation_nmm"),
        numbers(&d, "stored_energy_nmm"),
        numbers(&d, "loss_factor"),
    );
    for k in 0..3 {
        let def = diss[k] / (2.0 * std::f64::consts::PI * u[k]);
        assert!(common::rel(eta[k], def) < 1e-8, "η {} vs {def}", eta[k]);
    }
    // the fit: least squares of ln D on ln F_a over the three cycles
    let pts: Vec<(f64, f64)> = (0..3).map(|k| (f_a[k].ln(), diss[k].ln())).collect();
    let xm = pts.iter().map(|p| p.0).sum::<f64>() / 3.0;
    let ym = pts.iter().map(|p| p.1).sum::<f64>() / 3.0;
    let q = pts.iter().map(|p| (p.0 - xm) * (p.1 - ym)).sum::<f64>()
        / pts.iter().map(|p| (p.0 - xm).powi(2)).sum::<f64>();
    let ln_c = ym - q * xm;
    let r2 = 1.0
        - pts
            .iter()
            .map(|p| (p.1 - ln_c - q * p.0).powi(2))
            .sum::<f64>()
            / pts.iter().map(|p| (p.1 - ym).powi(2)).sum::<f64>();
    let fit = &summary(&dir)["damping"][0];
    eprintln!(
        "slideway sweep: F_a {f_a:?} N, D {diss:?} N·mm, η {eta:?}; q = {q:.4}, \
         C = {:.4e}, R² = {r2:.6}",
        ln_c.exp()
    );
    assert_eq!(fit["interface"], "way");
    assert_eq!(
        (fit["cycles"].as_u64(), fit["blocks"].as_u64()),
        (Some(3), Some(3))
    );
    assert_eq!(fit["cycles_used"], 3);
    assert!(
        (fit["exponent"].as_f64().unwrap() - q).abs() < 1e-7,
        "{fit}"
    );
    assert!(common::rel(fit["coefficient"].as_f64().unwrap(), ln_c.exp()) < 1e-6);
    assert!(
        (fit["r_squared"].as_f64().unwrap() - r2).abs() < 1e-7,
        "{fit}"
    );
    // the micro-slip zones grow with the force: D grows faster than F_a
    assert!(q > 1.0, "q = {q}");
    // the backbone: joints.csv's rows up to the first tip (t = 2, F_T = 54 N)
    let b = table(&dir.join("backbone.csv"));
    let bt = numbers(&b, "time");
    assert_eq!(*bt.last().unwrap(), 2.0);
    let j = table(&dir.join("joints.csv"));
    let before = numbers(&j, "time").iter().filter(|&&t| t <= 2.0).count();
    assert_eq!(bt.len(), before);
    assert!(common::rel(*numbers(&b, "tangential_force_n").last().unwrap(), 54.0) < 1e-6);
    if asperity::files::plot::load_font() {
        assert!(read(&dir.join("damping.svg")).contains("<svg"));
        assert!(std::fs::metadata(dir.join("damping.png")).unwrap().len() > 1000);
    }
}

#[test]
fn repeated_cycles_below_the_cap_shake_down_and_stay_out_of_the_fit() {
    // the slideway driven in blocks of two cycles at a = 0.3, 0.6, 0.9 of μ p
    let text = read(&common::root().join("cases/slideway-cycles/case.toml"));
    let (from, to) = (
        text.find("drive = [").unwrap(),
        text.find("[interface.way]").unwrap(),
    );
    let mut drive = String::from("drive = [[1.0, 0.0]");
    let mut t = 1.0;
    for a in [0.3, 0.3, 0.6, 0.6, 0.9, 0.9] {
        for v in [a, -a, 0.0] {
            t += 1.0;
            drive += &format!(", [{t:.1}, {v}]");
        }
    }
    let text = format!(
        "{}{drive}]\n\n{}[output]\nvtu = false\n",
        &text[..from],
        &text[to..]
    );
    let case = common::case_dir("joints-sweep-blocks", &text);
    let dir = case.parent().unwrap().join("out");
    run(case.parent().unwrap(), &dir, &[]);
    let d = table(&dir.join("damping.csv"));
    assert_eq!(numbers(&d, "block"), [1.0, 1.0, 2.0, 2.0, 3.0, 3.0]);
    let alt = [true, false, true, false, true, false];
    assert_eq!(flags(&d, "first_in_block"), alt);
    assert_eq!(flags(&d, "last_in_block"), alt.map(|b| !b));
    let diss = numbers(&d, "dissipation_nmm");
    eprintln!("blocks of two: D {diss:?} N·mm");
    // the memory of section 2.2: below the cap the repeat is elastic (D at
    // round-off, < 1e-6 of the largest); at 0.9 μ p the ends slide (macro-
    // slip is not hardened) and the repeat still dissipates, less than the first
    let top = diss.iter().cloned().fold(0.0, f64::max);
    assert!(diss[1] < 1e-6 * top && diss[3] < 1e-6 * top, "{diss:?}");
    assert!(diss[5] > 1e-6 * top && diss[5] < diss[4], "{diss:?}");
    // the steady values: one amplitude dissipates, no fit
    assert_eq!(flags(&d, "in_fit"), [false; 6]);
    let fit = &summary(&dir)["damping"][0];
    assert_eq!(
        (fit["cycles"].as_u64(), fit["blocks"].as_u64()),
        (Some(6), Some(3))
    );
    assert_eq!(fit["cycles_used"], 0);
    assert!(
        fit["exponent"].is_null() && fit["r_squared"].is_null(),
        "{fit}"
    );
}
