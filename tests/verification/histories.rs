//! Load histories, tangential tractions, concentrated forces and the
//! interference as a load (issue 18, docs/case-schema.md "Load histories"):
//! a linear case reaches the same state in one step or through history
//! segments; unloading from a plastic state leaves a settlement and an
//! elastic one does not; a shear traction and a concentrated force against
//! their resultants and the simple-shear closed form; an interference
//! pressed in by its history ends where the interference imposed at once
//! does; the stepper stops at every breakpoint and never crosses one.

use crate::common::{self, CaseText};
use asperity::input::case::SolverSpec;
use asperity::model::Model;
use asperity::solve::stepping::{segment_steps, Retry, Stepper, Why};
use asperity::solve::{Increment, Observer, RunResult, State};

/// Every converged increment's pseudo-time and displacements.
#[derive(Default)]
struct Capture(Vec<(f64, Vec<f64>)>);
impl Observer for Capture {
    fn increment(&mut self, _: &Model, s: &State, inc: &Increment) -> asperity::error::Result<()> {
        self.0.push((inc.load_factor, s.u.clone()));
        Ok(())
    }
}

fn solve(model: &Model) -> (RunResult, Vec<(f64, Vec<f64>)>) {
    let mut c = Capture::default();
    let r = asperity::app::driver::solve(model, &mut c).unwrap_or_else(|e| panic!("{e}"));
    (r, c.0)
}

const E: f64 = 200_000.0;
const NU: f64 = 0.3;

/// One elastic plane-strain block [0, w] × [0, h] ("block"), fixed at its
/// bottom; loads, histories and the solver are added to it.
fn block(w: f64, h: f64, nx: usize, ny: usize) -> CaseText {
    common::case()
        .plane("strain")
        .block("block", [0.0, w], [nx], [0.0, h], [ny])
        .material("block", E, NU)
        .fixed("block.bottom")
        .no_vtu()
}

/// Largest |a − b| over the largest |a|.
fn field_difference(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// The support reactions (residual at the prescribed dofs) of a converged
/// state, summed in x and in y.
fn reactions(model: &Model, r: &RunResult) -> [f64; 2] {
    let mut engine = asperity::app::driver::serial_engine(
        model,
        model.solver.method,
        asperity::threads::available(),
    )
    .unwrap();
    let t = r.increments.last().unwrap().load_factor;
    let res = engine
        .linearize(&r.final_state, &r.final_state.u, t)
        .unwrap();
    let mut sum = [0.0; 2];
    for &(d, _) in &model.prescribed {
        sum[d % 2] += res[d];
    }
    sum
}

/// A linear case: a block 10 × 4, a pressure and a shear on its top, a
/// prescribed displacement of its right side, all following `history` (a
/// name and its points) if given.
fn linear(history: Option<(&str, &str)>, solver: &str) -> String {
    let mut case = block(10.0, 4.0, 5, 2);
    if let Some(h) = history {
        case = case.histories(&[h]);
    }
    case = case.ux("block.right", -0.002).y_range(0.5, 4.0);
    if let Some((name, _)) = history {
        case = case.history(name);
    }
    case = case.pressure("block.top", 40.0).with("shear", 15.0);
    if let Some((name, _)) = history {
        case = case.history(name);
    }
    case.solver(solver).build()
}

#[test]
fn one_step_and_two_history_segments_reach_the_same_state() {
    let one = linear(None, "increments = 1");
    let two = linear(
        Some(("two", "[[0, 0], [1, 0.5], [2, 1]]")),
        "increments = 1",
    );
    let (m1, m2) = (common::model(&one), common::model(&two));
    assert!(m1.breakpoints().is_empty() && m1.history_values(0.5).is_empty());
    assert_eq!(m2.breakpoints(), vec![0.0, 1.0, 2.0]);
    assert_eq!(m2.history_values(1.5), vec![0.75]);
    let (r1, s1) = solve(&m1);
    let (r2, s2) = solve(&m2);
    let t1: Vec<f64> = s1.iter().map(|s| s.0).collect();
    let t2: Vec<f64> = s2.iter().map(|s| s.0).collect();
    assert_eq!(t1, vec![1.0]);
    assert_eq!(t2, vec![1.0, 2.0]);
    let d = field_difference(&r1.final_state.u, &r2.final_state.u);
    eprintln!("one step vs two segments: {d:.2e}");
    assert!(d < 1e-12, "final fields differ by {d:e}");
    // halfway along the history the linear response is half of it
    let half: Vec<f64> = s1[0].1.iter().map(|v| 0.5 * v).collect();
    let d = field_difference(&half, &s2[0].1);
    assert!(d < 1e-12, "the state at t = 1 differs from half by {d:e}");
}

#[test]
fn elastic_loading_and_unloading_returns_to_zero() {
    let model = common::model(&linear(
        Some(("up_down", "[[0, 0], [1, 1], [2, 0]]")),
        "increments = 2",
    ));
    let (r, states) = solve(&model);
    let peak = states
        .iter()
        .find(|s| s.0 == 1.0)
        .expect("a step ends at the breakpoint t = 1");
    let scale = peak.1.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 1e-4, "peak displacement {scale}");
    let left = r.final_state.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    eprintln!("elastic load-unload: peak {scale:.3e} mm, left {left:.2e} mm");
    assert!(left <= 1e-12 * scale, "{left:e} left of {scale:e}");
    assert_eq!(r.increments.last().unwrap().load_factor, 2.0);
}

/// The coarse punch of the bad-input corpus (its base case `punch.toml`: plane
/// stress, half model), its pressure following `history`.
fn punch(pressure: f64, yield_stress: &str, history: &str) -> String {
    let base = std::fs::read_to_string(common::corpus::base_dir().join("punch.toml"))
        .unwrap()
        .replace("yield_stress = 196.0\n", yield_stress)
        .replace(
            "increments = 4\nfirst_increment = 0.05\n",
            "increments = 8\n",
        )
        .replace(
            "pressure = 250.0\n",
            &format!("pressure = {pressure}\nhistory = {history}\n"),
        );
    assert!(base.contains(history) && !base.contains("gap ="));
    base
}

#[test]
fn unloading_from_a_plastic_state_leaves_a_residual_settlement() {
    let model = common::model(&punch(
        250.0,
        "yield_stress = 196.0\n",
        "[[0, 0], [1, 1], [2, 0]]",
    ));
    let (r, states) = solve(&model);
    let probe = 2 * model.probe_node + 1;
    let peak = states.iter().find(|s| s.0 == 1.0).expect("a step at t = 1");
    let at_peak = peak.1[probe];
    let last = r.increments.last().unwrap();
    assert_eq!(last.load_factor, 2.0);
    let residual = r.final_state.u[probe];
    let peeq = last.measures.max_peeq;
    eprintln!(
        "punch 250 MPa: settlement {at_peak:.4e} mm at the peak, {residual:.4e} mm after unloading, peeq {peeq:.3e}"
    );
    assert!(peeq > 1e-4, "no plastic strain: {peeq}");
    // the plastic part stays: a settlement of the same sign, a good part
    // of the peak's, with no pressure left on the punch
    assert!(
        residual < 0.0 && residual.abs() > 0.05 * at_peak.abs(),
        "{residual} after {at_peak}"
    );
    assert!(residual.abs() < at_peak.abs(), "{residual} after {at_peak}");
    assert!(
        last.measures.mean_pressure.abs() < 1e-6 * 250.0,
        "contact pressure {} left",
        last.measures.mean_pressure
    );
}

#[test]
fn a_shear_traction_has_its_resultant_and_the_simple_shear_displacement() {
    // a wide thin layer: away from its ends the state is simple shear,
    // u_x = τ y / G, u_y = 0 (the traction-free top carries no normal stress)
    let (w, h, tau) = (100.0, 1.0, 30.0);
    let model = common::model(
        &block(w, h, 100, 2)
            .shear("block.top", tau)
            .solver("increments = 1")
            .build(),
    );
    let mut f = vec![0.0; model.mesh.num_dofs()];
    model.external_force(1.0, &mut f);
    let fx: f64 = f.iter().step_by(2).sum();
    let fy: f64 = f.iter().skip(1).step_by(2).sum();
    assert!(common::rel(fx, tau * w) < 1e-13, "Σ f_x = {fx}");
    assert!(fy.abs() < 1e-13 * tau * w, "Σ f_y = {fy}");
    let (r, _) = solve(&model);
    let react = reactions(&model, &r);
    eprintln!("shear layer: Σ f_x {fx}, reactions {react:?}");
    assert!(common::rel(-react[0], tau * w) < 1e-9, "{react:?}");
    assert!(react[1].abs() < 1e-9 * tau * w, "{react:?}");
    let g = E / (2.0 * (1.0 + NU));
    let mid = (0..model.mesh.nodes.len())
        .find(|&n| model.mesh.xy(n) == [w / 2.0, h])
        .expect("a node at the middle of the top");
    let (ux, uy) = (r.final_state.u[2 * mid], r.final_state.u[2 * mid + 1]);
    let exact = tau * h / g;
    eprintln!("simple shear: u_x {ux:.9e} mm, τh/G {exact:.9e} mm, u_y {uy:.2e}");
    assert!(common::rel(ux, exact) < 1e-9, "{ux} vs {exact}");
    assert!(uy.abs() < 1e-9 * exact, "u_y {uy}");
}

#[test]
fn shear_turns_with_the_edge() {
    // +x on a top edge, −y on a right edge, +y on a left edge (and −x on a
    // bottom edge; the bottom is held here, where a load never acts)
    let text = block(6.0, 4.0, 3, 2)
        .shear("block.right", 2.0)
        .shear("block.left", 3.0)
        .shear("block.top", 5.0)
        .build();
    let model = common::model(&text);
    // Σ f_y over the nodes of a side x = const
    let side_fy = |x: f64| -> f64 {
        (0..model.mesh.nodes.len())
            .filter(|&n| model.mesh.nodes[n][0] == x)
            .map(|n| model.f_ext[2 * n + 1])
            .sum()
    };
    // right side: −2 · 4; left side: +3 · 4 (the top's shear is along x)
    assert!(common::rel(side_fy(6.0), -2.0 * 4.0) < 1e-13);
    assert!(common::rel(side_fy(0.0), 3.0 * 4.0) < 1e-13);
    // top y = 4: Σ f_x = +5 · 6
    let fx: f64 = model.f_ext.iter().step_by(2).sum();
    assert!(common::rel(fx, 5.0 * 6.0) < 1e-13, "{fx}");
    let fy: f64 = model.f_ext.iter().skip(1).step_by(2).sum();
    assert!(common::rel(fy, (3.0 - 2.0) * 4.0) < 1e-13, "{fy}");
}

#[test]
fn a_concentrated_force_is_carried_by_the_supports() {
    let (fx, fy) = (120.0, -250.0);
    let text = block(10.0, 4.0, 5, 2)
        .raw(&format!(
            "[[force]]\nnodes = \"block.top\"\nx_range = [4.9, 5.1]\nfx = {fx}\nfy = {fy}\n\
             [[force]]\nnodes = \"block.top\"\nfy = -10.0\nhistory = [[0, 0], [1, 2]]"
        ))
        .solver("increments = 2")
        .build();
    let model = common::model(&text);
    let top = model.mesh.node_sets["block.top"].len();
    let (r, _) = solve(&model);
    let react = reactions(&model, &r);
    // the second force at every top node, its history at 2 at t = 1
    let total = [fx, fy - 2.0 * 10.0 * top as f64];
    eprintln!("concentrated forces {total:?}, reactions {react:?}");
    for c in 0..2 {
        assert!(
            common::rel(-react[c], total[c]) < 1e-9,
            "{c}: {react:?} vs {total:?}"
        );
    }
}

/// Two stacked blocks pressed apart by an interference of 2 µm across a
/// frictionless rough interface, both held at their far ends; the
/// interference imposed at once or pressed in by its `gap_history`.
fn fit(pressed_in: bool) -> String {
    let mut case = common::case()
        .plane("strain")
        .block("upper", [0.0, 10.0], [5], [0.0, 4.0], [2])
        .block("lower", [0.0, 10.0], [5], [-6.0, 0.0], [3])
        .interface("joint", "upper", "lower")
        .material("upper", E, NU)
        .material("lower", E, NU)
        .law("joint", "power", 0.001, 0.5)
        .gap(-0.002);
    if pressed_in {
        case = case.raw("gap_history = [[0, 0], [1, 1]]");
    }
    case.fixed("lower.bottom")
        .fixed("upper.top")
        .solver("increments = 4")
        .no_vtu()
        .build()
}

#[test]
fn an_interference_alone_loads_the_model_at_once_or_through_its_history() {
    let at_once = common::model(&fit(false));
    let ramped = common::model(&fit(true));
    assert_eq!(ramped.gap_at(0, 0.25), -0.0005);
    assert_eq!(at_once.gap_at(0, 0.25), -0.002);
    let (ra, _) = solve(&at_once);
    let (rr, states) = solve(&ramped);
    // the pressure grows with the interference
    let p: Vec<f64> = rr
        .increments
        .iter()
        .map(|i| i.measures.mean_pressure)
        .collect();
    assert!(p.windows(2).all(|w| w[1] > w[0]), "{p:?}");
    assert_eq!(states.len(), 4);
    let (pa, pr) = (
        ra.increments.last().unwrap().measures.mean_pressure,
        *p.last().unwrap(),
    );
    // elastic bodies and a frictionless interface: the end does not depend on the path
    eprintln!("interference 2 µm: {pa} MPa at once, {pr} MPa pressed in");
    assert!(pa > 0.5, "{pa}");
    assert!(common::rel(pa, pr) < 1e-6, "{pa} vs {pr}");
    assert!(field_difference(&ra.final_state.u, &rr.final_state.u) < 1e-6);
}

fn spec(text: &str) -> SolverSpec {
    toml::from_str(text).unwrap()
}

/// Drives a stepper as the run does, every step converging in `its`
/// iterations with no plastic strain, except those longer than `fail_above`.
fn drive(s: &mut Stepper, its: usize, fail_above: f64) -> Vec<f64> {
    let (mut t, mut path) = (0.0, vec![]);
    let mut target = s.next(t);
    while let Some(to) = target {
        if (to - t).abs() > fail_above {
            match s.retry(t, to, Why::Failed) {
                Retry::At(x) => target = Some(x),
                Retry::GiveUp => panic!("gave up at {t}"),
            }
            continue;
        }
        s.accepted(t, to, its, 0.0);
        t = to;
        path.push(t);
        target = s.next(t);
        assert!(path.len() < 100_000);
    }
    path
}

/// Every breakpoint is a step's end and no step crosses one.
fn stops_at_every_breakpoint(path: &[f64], breakpoints: &[f64]) {
    for &b in breakpoints.iter().filter(|&&b| b > 0.0) {
        assert!(path.contains(&b), "{b} missing from {path:?}");
    }
    let mut t0: f64 = 0.0;
    for &t1 in path {
        assert!(
            !breakpoints
                .iter()
                .any(|&b| b > t0.min(t1) && b < t0.max(t1)),
            "the step {t0} → {t1} crosses a breakpoint"
        );
        t0 = t1;
    }
}

#[test]
fn fixed_steps_split_each_segment_and_stop_at_every_breakpoint() {
    let bps = [0.0, 0.3, 1.0, 2.5, 3.0];
    let mut s = Stepper::with_breakpoints(&spec("increments = 10"), &bps);
    let path = drive(&mut s, 3, f64::INFINITY);
    stops_at_every_breakpoint(&path, &bps);
    // ceil(len · 10) equal steps per segment: 3 + 7 + 15 + 5
    assert_eq!(path.len(), 3 + 7 + 15 + 5, "{path:?}");
    assert_eq!(
        Stepper::planned(&spec("increments = 10"), &bps),
        Some(path.len())
    );
    for (a, b, n) in [(0.0, 0.3, 3), (0.3, 1.0, 7), (1.0, 2.5, 15), (2.5, 3.0, 5)] {
        let inside: Vec<f64> = path.iter().copied().filter(|&t| t > a && t <= b).collect();
        assert_eq!(inside.len(), n, "segment {a} → {b}: {inside:?}");
        let steps: Vec<f64> = std::iter::once(a)
            .chain(inside.iter().copied())
            .collect::<Vec<_>>()
            .windows(2)
            .map(|w| w[1] - w[0])
            .collect();
        let h = (b - a) / n as f64;
        assert!(steps.iter().all(|d| (d - h).abs() < 1e-12), "{steps:?}");
    }
    // a first increment, then the rest of the first segment in equal steps
    let mut s = Stepper::with_breakpoints(&spec("increments = 10\nfirst_increment = 0.05"), &bps);
    let path = drive(&mut s, 3, f64::INFINITY);
    assert_eq!(path[0], 0.05);
    assert_eq!(path.len(), 1 + 3 + 7 + 15 + 5, "{path:?}");
    stops_at_every_breakpoint(&path, &bps);
    // cut back steps stay inside their segment
    let mut s = Stepper::with_breakpoints(&spec("increments = 2"), &bps);
    let path = drive(&mut s, 3, 0.2);
    stops_at_every_breakpoint(&path, &bps);
    assert_eq!(*path.last().unwrap(), 3.0);
    // round-off does not add a sliver step: 0.3 · 10 is 3 steps, not 4
    assert_eq!(segment_steps(0.3, 10), 3);
    assert_eq!(segment_steps(0.7, 10), 7);
    assert_eq!(segment_steps(0.31, 10), 4);
    assert_eq!(segment_steps(1e-9, 10), 1);
}

#[test]
fn automatic_steps_stop_at_every_breakpoint() {
    let bps = [0.0, 0.3, 1.0, 1.05, 2.5, 4.0];
    let mut s = Stepper::with_breakpoints(
        &spec("step_control = \"auto\"\nfirst_increment = 0.01\nmax_increment = 0.5"),
        &bps,
    );
    let path = drive(&mut s, 2, f64::INFINITY);
    stops_at_every_breakpoint(&path, &bps);
    assert_eq!(*path.last().unwrap(), 4.0);
    assert!(path.windows(2).all(|w| w[1] > w[0]), "{path:?}");
    // failures above 0.1 are halved and the steps still stop at every breakpoint
    let mut s = Stepper::with_breakpoints(
        &spec("step_control = \"auto\"\nfirst_increment = 0.5\nmax_increment = 0.5"),
        &bps,
    );
    let path = drive(&mut s, 2, 0.1);
    stops_at_every_breakpoint(&path, &bps);
    // a history ending before 1 runs to 1 (the default ramp's end)
    let mut s = Stepper::with_breakpoints(&spec("step_control = \"auto\""), &[0.0, 0.5]);
    assert_eq!(s.final_target(0.0), 1.0);
    let path = drive(&mut s, 2, f64::INFINITY);
    stops_at_every_breakpoint(&path, &[0.5, 1.0]);
    assert_eq!(*path.last().unwrap(), 1.0);
}

#[test]
fn a_run_with_histories_steps_on_every_breakpoint_in_both_modes() {
    for solver in ["increments = 4", "step_control = \"auto\""] {
        let text = block(10.0, 4.0, 5, 2)
            .histories(&[("ramp", "[[0, 0], [0.4, 1], [1.7, -0.5], [2.2, 0]]")])
            .pressure("block.top", 30.0)
            .history("ramp")
            .shear("block.top", 5.0)
            .solver(solver)
            .build();
        let model = common::model(&text);
        let bps = model.breakpoints();
        assert_eq!(bps, vec![0.0, 0.4, 1.0, 1.7, 2.2]);
        let (r, _) = solve(&model);
        let path: Vec<f64> = r.increments.iter().map(|i| i.load_factor).collect();
        stops_at_every_breakpoint(&path, &bps);
        assert_eq!(*path.last().unwrap(), 2.2, "{solver}: {path:?}");
    }
}

/// A slider pressed on a base and sheared back and forth over a rough,
/// frictional joint: preload, then a tangential cycle into slip.
fn slideway(solver: &str) -> String {
    common::case()
        .plane("strain")
        .block("slider", [0.0, 10.0], [6], [0.0, 4.0], [2])
        .block("base", [0.0, 10.0], [6], [-6.0, 0.0], [3])
        .interface("joint", "slider", "base")
        .material("slider", 210000.0, 0.3)
        .material("base", 210000.0, 0.3)
        .law("joint", "power", 0.001, 0.5)
        .tangential("joint", 0.9, 0.5, 0.05, 0.2)
        .histories(&[("shear", "[[1, 0], [2, 1], [3, -1], [4, 0]]")])
        .fixed("base.bottom")
        .pressure("slider.top", 50.0)
        .shear("slider.top", 9.0)
        .history("shear")
        .solver(solver)
        .no_vtu()
        .build()
}

#[test]
fn a_run_with_histories_stopped_and_restarted_takes_the_same_steps() {
    use asperity::app::driver::{self, RunOptions};
    for (tag, solver) in [
        ("fixed", "increments = 4"),
        ("auto", "step_control = \"auto\"\nmax_increment = 0.25"),
    ] {
        let case = common::case_dir(&format!("histories-restart-{tag}"), &slideway(solver));
        let dir = case.parent().unwrap().to_path_buf();
        let go = |out: &str, restart: bool, stop_after: Option<usize>| {
            let out = dir.join(out);
            let opts = RunOptions {
                out: Some(out.clone()),
                quiet: true,
                restart: restart.then(|| out.clone()),
                hooks: asperity::app::options::Hooks {
                    stop_after,
                    ..Default::default()
                },
                ..RunOptions::default()
            };
            driver::run(&case, &opts).unwrap_or_else(|e| panic!("{tag}: {e}"));
            std::fs::read_to_string(out.join("curve.csv")).unwrap()
        };
        let full = go("full", false, None);
        // stopped inside the shear cycle, after the reversal at t = 2
        let part = go("part", false, Some(9));
        assert_eq!(part.lines().count(), 1 + 9, "{tag}");
        let resumed = go("part", true, None);
        assert_eq!(full, resumed, "{tag}");
        let times: Vec<f64> = full
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
            .collect();
        stops_at_every_breakpoint(&times, &[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(*times.last().unwrap(), 4.0, "{tag}: {times:?}");
    }
}
