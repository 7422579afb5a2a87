//! Joint loops against the energies the program reports (issue 18 part 6,
//! src/measure/joint.rs, docs/output.md "Joints: sign conventions"):
//!
//! * every spring alike (all nodes of both bodies prescribed): the loop area
//!   of F_T against ū_T in joints.csv, by the trapezoid rule, equals each
//!   closed cycle's dissipation in cycles.csv and summary.json to 1e-6, and
//!   the elastic-perfectly-plastic loop's closed form within the bound of
//!   the step size; the cycle's secant stiffness is the tip-to-tip slope;
//!   its stored energy ½ F_s a and loss factor 4 (a − u_s) / (π a) of the
//!   closed form; damping.csv has cycles.csv's numbers; backbone.csv is
//!   joints.csv up to the first tip;
//! * section 2.2's memory: unloading and reloading below the earlier maximum
//!   adds no slip and no dissipation, the reload is elastic (slope k_T^e ×
//!   area), and a reload beyond the earlier maximum slips again exactly there;
//! * an elastic slider dragged back and forth by a shear traction: the joint
//!   force equals the applied shear at every increment, two cycles are found,
//!   their energies are the per-spring trapezoid sums, and the second cycle
//!   dissipates no more than the first.

use crate::common;

mod damping;
use asperity::measure::joint::{self, JointMeasures};
use asperity::model::Model;
use asperity::solve::{Increment, Observer, RunResult, State};
use serde_json::Value;
use std::process::Command;

const C_N: f64 = 0.001;
const M: f64 = 0.5;
const R: f64 = 0.9;
const S: f64 = 0.5;
const MU: f64 = 0.2;
/// The initial-yield ratio ρ = p_T^Y / (μ p_N) (the schema's default).
const RHO: f64 = 0.625;
/// Interface length (plane strain, thickness 1: also the area, mm²).
const L: f64 = 10.0;

/// k_T^e = 1000 p_N^S / R, MPa/mm.
fn k_t(p: f64) -> f64 {
    1000.0 * p.powf(S) / R
}

/// A block on a base, 10 mm wide, plane strain; every node of the block
/// prescribed (uy = −d on the preload ramp, ux = a on the `drag` history),
/// every node of the base fixed: every spring of the joint sees the same
/// approach d and the same slip, so all are alike.
fn uniform(kp_ratio: f64, d: f64, a: f64, drag: &str, increments: usize) -> String {
    common::case()
        .plane("strain")
        .block("block", [0.0, L], [4], [0.0, 2.0], [1])
        .block("base", [0.0, L], [4], [-2.0, 0.0], [1])
        .interface("joint", "block", "base")
        .material("block", 210000.0, 0.3)
        .material("base", 210000.0, 0.3)
        .law("joint", "power", C_N, M)
        .weights("lumped")
        .tangential("joint", R, S, kp_ratio, MU)
        .with("beta", 1.0)
        .with("n", 0.0)
        .histories(&[("preload", "[[0, 0], [1, 1]]"), ("drag", drag)])
        .fixed("base.all")
        .uy("block.all", -d)
        .history("preload")
        .ux("block.all", a)
        .history("drag")
        .solver(&format!("increments = {increments}"))
        .no_vtu()
        .build()
}

/// A CSV file as a header and rows of fields.
fn csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let mut lines = text.lines();
    let head = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (head, rows)
}

/// Column `name` of `rows` as numbers.
fn column(head: &[String], rows: &[Vec<String>], name: &str) -> Vec<f64> {
    let k = head
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {head:?}"));
    rows.iter()
        .map(|r| {
            if r[k].is_empty() {
                f64::NAN
            } else {
                r[k].parse().unwrap()
            }
        })
        .collect()
}

/// Trapezoid rule of ∫ F dū over the sequence (the loop area when it closes).
fn trapezoid(f: &[f64], u: &[f64]) -> f64 {
    (1..f.len())
        .map(|k| 0.5 * (f[k - 1] + f[k]) * (u[k] - u[k - 1]))
        .sum()
}

#[test]
fn the_loop_area_of_identical_springs_is_the_reported_dissipation() {
    let (d, a, increments) = (0.01f64, 0.01f64, 40usize);
    let p_n = (d / C_N).powf(1.0 / M); // 100 MPa
    let k = k_t(p_n);
    let f_s = MU * p_n * L; // the slip force of the joint, N
    let u_s = MU * p_n / k; // elastic slip at the cap, mm
    assert!(2.0 * u_s < 2.0 * a, "the loop must slip");
    let text = uniform(
        1.0,
        d,
        a,
        "[[1, 0], [2, 1], [3, -1], [4, 1], [5, -1], [6, 1]]",
        increments,
    );
    let case = common::case_dir("cycles-uniform", &text);
    let out = case.parent().unwrap().join("out");
    let run = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .arg("run")
        .arg(case.parent().unwrap())
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

    let (jh, jr) = csv(&out.join("joints.csv"));
    let inc = column(&jh, &jr, "increment");
    let force = column(&jh, &jr, "tangential_force_n");
    let slip = column(&jh, &jr, "mean_slip_mm");
    let normal = column(&jh, &jr, "normal_force_n");
    let diss = column(&jh, &jr, "dissipation_nmm");
    let work = column(&jh, &jr, "work_nmm");
    let times = column(&jh, &jr, "time");
    assert_eq!(*times.last().unwrap(), 6.0);
    assert!(common::rel(*normal.last().unwrap(), p_n * L) < 1e-9);
    let (ch, cr) = csv(&out.join("cycles.csv"));
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let sc = summary["joints"][0]["cycles"].as_array().unwrap();
    assert_eq!(cr.len(), 2, "two closed cycles: {cr:?}");
    assert_eq!(sc.len(), 2);
    let col = |name: &str| column(&ch, &cr, name);
    let (start, end) = (col("start_increment"), col("end_increment"));
    let (c_d, c_w, c_k) = (
        col("dissipation_nmm"),
        col("work_nmm"),
        col("secant_stiffness_n_per_mm"),
    );
    let (fmin, fmax, smin, smax) = (
        col("force_min_n"),
        col("force_max_n"),
        col("slip_min_mm"),
        col("slip_max_mm"),
    );
    assert_eq!(
        (col("start_time"), col("end_time")),
        (vec![2.0, 4.0], vec![4.0, 6.0])
    );
    // the step's slip: 2a per unit of pseudo-time, `increments` steps
    let du = 2.0 * a / increments as f64;
    // the trapezoid cuts the two corners where slip starts after each
    // reversal (the tips are breakpoints, on rows): at most ½ h · θ(1−θ) k A h
    // ≤ k A h² / 8 each
    let bound = k * L * du * du / 4.0;
    let closed = 4.0 * f_s * (a - u_s);
    for c in 0..2 {
        let rows: Vec<usize> = (0..inc.len())
            .filter(|&r| inc[r] >= start[c] && inc[r] <= end[c])
            .collect();
        assert_eq!(rows.len(), 2 * increments + 1, "cycle {c}");
        let f: Vec<f64> = rows.iter().map(|&r| force[r]).collect();
        let u: Vec<f64> = rows.iter().map(|&r| slip[r]).collect();
        let loop_area = trapezoid(&f, &u);
        let (r0, r1) = (rows[0], *rows.last().unwrap());
        eprintln!(
            "cycle {}: loop {loop_area:.9} N·mm, D {:.9}, W {:.9}, closed form {closed:.9} \
             (rel {:.2e}, step bound {:.2e})",
            c + 1,
            c_d[c],
            c_w[c],
            common::rel(loop_area, c_d[c]),
            bound / closed
        );
        // the identity: every spring back at its start state, W = D = loop
        assert!(
            common::rel(loop_area, c_d[c]) < 1e-6,
            "cycle {c}: loop {loop_area} vs D {}",
            c_d[c]
        );
        assert!(common::rel(c_w[c], c_d[c]) < 1e-6, "cycle {c}: W vs D");
        assert!(common::rel(diss[r1] - diss[r0], c_d[c]) < 1e-8);
        assert!(common::rel(work[r1] - work[r0], c_w[c]) < 1e-8);
        let s = &sc[c];
        assert!(common::rel(s["dissipation_nmm"].as_f64().unwrap(), c_d[c]) < 1e-9);
        assert!(common::rel(s["work_nmm"].as_f64().unwrap(), c_w[c]) < 1e-9);
        assert_eq!(s["start_increment"].as_f64().unwrap(), start[c]);
        assert_eq!(s["end_increment"].as_f64().unwrap(), end[c]);
        // the EPP parallelogram, within the corners the steps cut
        assert!(
            closed - c_d[c] >= -1e-9 * closed && closed - c_d[c] <= bound + 1e-9 * closed,
            "cycle {c}: D {} vs closed form {closed} (bound {bound})",
            c_d[c]
        );
        // ranges and the tip-to-tip secant from the rows
        let (f_lo, f_hi) = f
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), &v| (l.min(v), h.max(v)));
        let (u_lo, u_hi) = u
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), &v| (l.min(v), h.max(v)));
        assert_eq!(
            [fmin[c], fmax[c], smin[c], smax[c]],
            [f_lo, f_hi, u_lo, u_hi]
        );
        let secant = (f_hi - f_lo) / (u_hi - u_lo);
        assert!(common::rel(c_k[c], secant) < 1e-8, "{} vs {secant}", c_k[c]);
        assert!(common::rel(secant, f_s / a) < 1e-8, "{secant} vs F_s/a");
        assert!(common::rel(s["secant_stiffness_n_per_mm"].as_f64().unwrap(), secant) < 1e-8);
    }
    let epp = damping::Epp { f_s, a, u_s, bound };
    damping::loss_factor_of_the_epp_loop(&out, &epp, &summary);
    damping::damping_csv_is_cycles_csv_in_blocks(&out, &summary);
    damping::backbone_is_the_first_loading(&out, 2.0);
}

use crate::common::Quiet;

fn solve(model: &Model) -> RunResult {
    asperity::app::driver::solve(model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn reversal_below_the_earlier_maximum_adds_no_slip() {
    // micro-slip: Y(κ) = ρ μ p_N + H κ, H = k k_p/(k − k_p); the first
    // excursion to a = 2 u_y (u_y = ρ μ p_N / k) stays below the cap
    let (kp_ratio, d, increments) = (0.3f64, 0.01f64, 20usize);
    let p_n = (d / C_N).powf(1.0 / M);
    let k = k_t(p_n);
    let h = k * kp_ratio / (1.0 - kp_ratio);
    let y0 = RHO * MU * p_n;
    let u_y = y0 / k;
    let a = 2.0 * u_y;
    let kappa = (k * a - y0) / (k + h); // slip at the first peak
    assert!(y0 + h * kappa < MU * p_n, "the first peak is in micro-slip");
    assert!(k * kappa < y0 + h * kappa, "unloading to 0 stays elastic");
    let model = common::model(&uniform(
        kp_ratio,
        d,
        a,
        "[[1, 0], [2, 1], [3, 0], [4, 0.8], [5, 0], [6, 1.2]]",
        increments,
    ));
    let r = solve(&model);
    let rows: Vec<(f64, JointMeasures)> = r
        .increments
        .iter()
        .map(|i| (i.load_factor, i.joints[0]))
        .collect();
    let at = |t: f64| {
        rows.iter()
            .find(|r| (r.0 - t).abs() < 1e-12)
            .unwrap_or_else(|| panic!("no increment at t = {t}"))
            .1
    };
    let peak = at(2.0);
    assert!(
        common::rel(peak.micro_slip, L) < 1e-12 && peak.macro_slip == 0.0,
        "{peak:?}"
    );
    // the first peak's dissipation: Y₀ κ + ½ H κ² per unit area, less at most
    // the yield increment's trapezoid error ½ k Δu² (Δu = a / increments)
    let exact = L * (y0 * kappa + 0.5 * h * kappa * kappa);
    let du = a / increments as f64;
    eprintln!(
        "first peak: D {:.6e} N·mm, closed form {exact:.6e} (rel {:.1e})",
        peak.dissipation,
        common::rel(peak.dissipation, exact)
    );
    assert!(
        (peak.dissipation - exact).abs() <= 0.5 * k * du * du * L + 1e-9 * exact,
        "D at the first peak {} vs {exact}",
        peak.dissipation
    );
    assert!(common::rel(peak.tangential_force, (y0 + h * kappa) * L) < 1e-9);
    // unloading, reloading to 0.8 a and unloading again: no new slip
    let reload_start = at(3.0);
    let k_joint = k * L;
    for (t, j) in rows.iter().filter(|r| r.0 > 2.0 && r.0 <= 5.0 + 1e-12) {
        assert!(
            common::rel(j.dissipation, peak.dissipation) < 1e-12,
            "t = {t}: D {} vs {} at the peak",
            j.dissipation,
            peak.dissipation
        );
        assert_eq!((j.micro_slip, j.macro_slip), (0.0, 0.0), "t = {t}: {j:?}");
        assert!(common::rel(j.stick, L) < 1e-12, "t = {t}: {j:?}");
        if *t > 3.0 && *t <= 4.0 + 1e-12 {
            // the reload is linear with the elastic slope
            let secant = (j.tangential_force - reload_start.tangential_force)
                / (j.mean_slip - reload_start.mean_slip);
            assert!(
                common::rel(secant, k_joint) < 1e-9,
                "t = {t}: reload slope {secant} vs k_T A = {k_joint}"
            );
        }
    }
    assert!(at(4.0).tangential_force < peak.tangential_force);
    // the reload beyond the earlier maximum: elastic up to ū = a (t = 5 + 1/1.2),
    // slipping again beyond
    let t_a = 5.0 + 1.0 / 1.2;
    for (t, j) in rows.iter().filter(|r| r.0 > 5.0) {
        if *t <= t_a - 1e-9 {
            assert!(
                common::rel(j.dissipation, peak.dissipation) < 1e-12 && j.micro_slip == 0.0,
                "t = {t}: {j:?}"
            );
        } else if *t > t_a + 1e-9 {
            assert!(
                j.dissipation > peak.dissipation * (1.0 + 1e-6) && j.micro_slip > 0.0,
                "t = {t}: {j:?}"
            );
        }
    }
    let end = rows.last().unwrap().1;
    eprintln!(
        "beyond the earlier maximum: D {:.6e} → {:.6e} N·mm",
        peak.dissipation, end.dissipation
    );
    // the closed form again: the spring hardens from κ to κ' at 1.2 a
    let kappa2 = (k * 1.2 * a - y0) / (k + h);
    let exact2 = L * (y0 * kappa2 + 0.5 * h * kappa2 * kappa2);
    assert!(
        (end.dissipation - exact2).abs() <= k * du * du * L + 1e-9 * exact2,
        "D at 1.2 a {} vs {exact2}",
        end.dissipation
    );
}

/// Every converged increment's pseudo-time and tangential point states.
#[derive(Default)]
struct Capture(Vec<(f64, Vec<asperity::physics::contact::PointState>)>);
impl Observer for Capture {
    fn increment(&mut self, _: &Model, s: &State, inc: &Increment) -> asperity::Result<()> {
        self.0.push((inc.load_factor, s.contact.clone()));
        Ok(())
    }
}

#[test]
fn a_slider_dragged_back_and_forth_balances_the_shear_and_shakes_down() {
    let (q, tau) = (50.0f64, 6.0f64);
    assert!(tau < MU * q, "below the friction limit");
    let text = common::case()
        .plane("strain")
        .block("slider", [0.0, L], [8], [0.0, 4.0], [2])
        .block("base", [0.0, L], [8], [-6.0, 0.0], [3])
        .interface("joint", "slider", "base")
        .material("slider", 210000.0, 0.3)
        .material("base", 210000.0, 0.3)
        .law("joint", "power", C_N, M)
        .weights("lumped")
        .tangential("joint", R, S, 0.05, MU)
        .histories(&[
            ("preload", "[[0, 0], [1, 1]]"),
            (
                "shear",
                "[[1, 0], [2, 1], [3, -1], [4, 0], [5, 1], [6, -1], [7, 0]]",
            ),
        ])
        .fixed("base.bottom")
        .pressure("slider.top", q)
        .history("preload")
        .shear("slider.top", tau)
        .history("shear")
        .solver("increments = 8")
        .tolerances(1e-12, 1e-12)
        .no_vtu()
        .build();
    let model = common::model(&text);
    let mut cap = Capture::default();
    let r = asperity::app::driver::solve(&model, &mut cap).unwrap_or_else(|e| panic!("{e}"));
    let times: Vec<f64> = r.increments.iter().map(|i| i.load_factor).collect();
    let joints: Vec<JointMeasures> = r.increments.iter().map(|i| i.joints[0]).collect();
    assert_eq!(*times.last().unwrap(), 7.0);

    // (a) the slider's equilibrium: F_T = the applied shear's resultant
    let shear = |t: f64| model.history_values(t)[1];
    assert_eq!(shear(2.0), 1.0);
    for (t, j) in times.iter().zip(&joints) {
        let applied = tau * shear(*t) * L;
        assert!(
            (j.tangential_force - applied).abs() < 1e-8 * tau * L,
            "t = {t}: F_T {} vs the applied shear {applied}",
            j.tangential_force
        );
        assert!(common::rel(j.normal_force, q * L * (t.min(1.0))) < 1e-8);
    }
    // the joint is not uniform: the slip spreads from the ends
    let peak = joints[times.iter().position(|&t| t == 2.0).unwrap()];
    assert!(peak.micro_slip > 0.0 && peak.stick > 0.0, "{peak:?}");

    // (b) two cycles, each with the energies of the per-spring trapezoid sums
    let refs: Vec<&[JointMeasures]> = r.increments.iter().map(|i| &i.joints[..]).collect();
    let cycles = joint::cycles(
        &times,
        &refs,
        &model.breakpoints(),
        |t| model.history_values(t),
        1,
    );
    let cycles = &cycles[0];
    assert_eq!(cycles.len(), 2, "{cycles:?}");
    assert_eq!(
        cycles
            .iter()
            .map(|c| (c.start_time, c.end_time))
            .collect::<Vec<_>>(),
        vec![(1.0, 4.0), (4.0, 7.0)]
    );
    let im = &model.interfaces[0];
    let states = &cap.0;
    assert_eq!(states.len(), times.len());
    for (n, c) in cycles.iter().enumerate() {
        let (i, j) = (c.start_increment - 1, c.end_increment - 1);
        // per spring: D = Σ A ½(p_T,n + p_T,n+1) Δu_p, W = Σ A ½(p_T,n + p_T,n+1) Δu_T
        let (mut d, mut w, mut nonuniform) = (0.0, 0.0, 0.0);
        for k in i..j {
            let (s0, s1) = (&states[k].1, &states[k + 1].1);
            let mean = |s: &[asperity::physics::contact::PointState]| {
                im.points
                    .iter()
                    .zip(s)
                    .map(|(pt, st)| pt.area * st.u_t)
                    .sum::<f64>()
                    / im.area()
            };
            let (m0, m1) = (mean(s0), mean(s1));
            for (pt, (a, b)) in im.points.iter().zip(s0.iter().zip(s1)) {
                let p = 0.5 * (a.p_t + b.p_t);
                d += pt.area * p * (b.slip.u_p - a.slip.u_p);
                w += pt.area * p * (b.u_t - a.u_t);
                // the work on the slip's departure from its mean
                nonuniform += pt.area * p * ((b.u_t - m1) - (a.u_t - m0));
            }
        }
        let f: Vec<f64> = joints[i..=j].iter().map(|m| m.tangential_force).collect();
        let u: Vec<f64> = joints[i..=j].iter().map(|m| m.mean_slip).collect();
        let loop_area = trapezoid(&f, &u);
        eprintln!(
            "cycle {}: D {:.6e}, W {:.6e} N·mm, loop {loop_area:.6e} ({:+.2}% of D), \
             work on the non-uniform slip {nonuniform:.3e}",
            n + 1,
            c.dissipation,
            c.work,
            100.0 * (loop_area - c.dissipation) / c.dissipation
        );
        assert!(c.dissipation > 0.0, "cycle {n}: {c:?}");
        assert!(
            common::rel(c.dissipation, d) < 1e-9,
            "cycle {n}: D {} vs the springs' {d}",
            c.dissipation
        );
        assert!(
            common::rel(c.work, w) < 1e-9,
            "cycle {n}: W {} vs the springs' {w}",
            c.work
        );
        // the joint's loop is the springs' work on the mean slip: W = loop +
        // the work on the departure from it (exact: F_T, ū_T are the sums)
        assert!(
            (loop_area + nonuniform - c.work).abs() < 1e-9 * c.work.abs().max(c.dissipation),
            "cycle {n}: loop {loop_area} + {nonuniform} vs W {}",
            c.work
        );
        // the joint loop is only an estimate of D here: it misses the work
        // on the non-uniform slip and W − D, the change of the shear energy
        // the springs store (their k_T^e follows p_N, which the shear's
        // moment changes); measured 2% and 10% below D. A sanity bound:
        assert!(
            loop_area > 0.0 && common::rel(loop_area, c.dissipation) < 0.2,
            "cycle {n}: loop {loop_area} vs D {}",
            c.dissipation
        );
    }
    // (c) shakedown of the micro-slip memory
    assert!(
        cycles[1].dissipation <= cycles[0].dissipation * (1.0 + 1e-9),
        "{cycles:?}"
    );
}
