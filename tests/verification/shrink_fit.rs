//! A long shrink fit against the closed form (issue 18 part 6): a solid
//! shaft 0 ≤ r ≤ b in a hub b ≤ r ≤ c, axisymmetric, both bodies held
//! axially (u_z = 0) on their top and bottom so that plane-strain Lamé
//! applies, pressed together by an interference δ (`gap = −δ`) across a
//! frictionless rough interface (vertical interface, left = shaft, right =
//! hub). The fit pressure p solves
//!
//! ```text
//!   δ = u_hub(p) + u_shaft(p) + c_N p^m
//!   u_hub(p)   = (1+ν)/E · [(1−2ν) A b + B/b],  A = p b²/(c²−b²), B = p b² c²/(c²−b²)
//!   u_shaft(p) = p b (1+ν)(1−2ν)/E           (solid shaft, external pressure, plane strain)
//! ```
//!
//! solved here by bisection; the finite-element pressure is compared with it
//! for a nearly rigid interface and two roughness levels, pressed in by a
//! `gap_history` and imposed at once.

use crate::common;
use asperity::model::Model;
use asperity::solve::RunResult;

use crate::common::Quiet;

const B: f64 = 20.0;
const C: f64 = 40.0;
const DELTA: f64 = 0.02;
const E: f64 = 206_000.0;
const NU: f64 = 0.3;
const M: f64 = 0.5;

/// Radial growth of the hub's bore under internal pressure p (plane strain).
fn u_hub(p: f64) -> f64 {
    let a = p * B * B / (C * C - B * B);
    let bb = p * B * B * C * C / (C * C - B * B);
    (1.0 + NU) / E * ((1.0 - 2.0 * NU) * a * B + bb / B)
}

/// Radial shrinkage of the solid shaft under external pressure p (plane strain).
fn u_shaft(p: f64) -> f64 {
    p * B * (1.0 + NU) * (1.0 - 2.0 * NU) / E
}

/// The fit pressure: the root of δ − u_hub − u_shaft − c_N p^m (decreasing in p).
pub(crate) fn fit_pressure(c_n: f64) -> f64 {
    let f = |p: f64| DELTA - u_hub(p) - u_shaft(p) - c_n * p.powf(M);
    let (mut lo, mut hi) = (0.0, 1.0);
    while f(hi) > 0.0 {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The fit, the interference pressed in by a `gap_history` or imposed at
/// once; the shaft held axially at both ends or, given a friction
/// coefficient, pushed out (`history` "push") across a frictional interface.
/// The hub's ends are held axially.
fn case(c_n: f64, pressed_in: bool, push_out: Option<f64>) -> String {
    let mut case = common::case()
        .plane("axisymmetric")
        .block("shaft", [0.0, B], [8], [0.0, 10.0], [3])
        .block("hub", [B, C], [12], [0.0, 10.0], [3])
        .rx([2.0])
        .vertical_interface("fit", "shaft", "hub")
        .material("shaft", E, NU)
        .material("hub", E, NU)
        .law("fit", "power", c_n, M)
        .gap(-DELTA);
    if pressed_in {
        case = case.raw("gap_history = [[0, 0], [1, 1]]");
    }
    case = match push_out {
        None => case.uy("shaft.bottom", 0.0).uy("shaft.top", 0.0),
        Some(mu) => case
            .tangential("fit", 0.9, 0.5, 0.05, mu)
            .histories(&[("push", "[[1, 0], [2, 1]]")])
            .uy("shaft.all", 0.05)
            .history("push"),
    };
    case.uy("hub.bottom", 0.0)
        .uy("hub.top", 0.0)
        .solver("increments = 4")
        .tolerances(1e-12, 1e-12)
        .no_vtu()
        .build()
}

/// The mean interface pressure (joint F_N over the interface area) and
/// every pair's pressure at the end of the run.
fn pressures(model: &Model, r: &RunResult) -> (f64, Vec<f64>) {
    let im = &model.interfaces[0];
    let last = r.increments.last().unwrap();
    let mean = last.joints[0].normal_force / im.area();
    let gap = im.gap_at(last.load_factor);
    let pairs = im
        .pairs
        .iter()
        .map(|pr| {
            im.law
                .pressure(im.pair_approach_at(pr, &r.final_state.u, gap))
                .0
        })
        .collect();
    (mean, pairs)
}

#[test]
fn long_shrink_fit_matches_the_lame_closed_form_with_the_rough_interface() {
    let rigid = fit_pressure(1e-6);
    // the closed form without the interface, for scale: δ / (u_hub + u_shaft per MPa)
    let stiff = DELTA / (u_hub(1.0) + u_shaft(1.0));
    eprintln!("fit pressure without asperities {stiff:.4} MPa");
    let mut fe_rigid = 0.0;
    for c_n in [1e-6, 1e-4, 1e-3] {
        let p = fit_pressure(c_n);
        let model = common::model(&case(c_n, true, None));
        let area = 2.0 * std::f64::consts::PI * B * 10.0;
        assert!(common::rel(model.interfaces[0].area(), area) < 1e-12);
        let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"));
        let (mean, pairs) = pressures(&model, &r);
        let err = common::rel(mean, p);
        let (lo, hi) = pairs
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
        eprintln!(
            "c_N = {c_n:e}: closed form {p:.4} MPa, FE {mean:.4} MPa ({:+.2e}), pairs spread {:.1e}",
            (mean - p) / p,
            (hi - lo) / lo
        );
        assert!(err < 5e-3, "c_N = {c_n}: FE {mean} vs closed form {p}");
        // uniform along z: every pair within 0.5% of every other
        assert!(
            (hi - lo) / lo < 5e-3,
            "c_N = {c_n}: pair pressures {lo} … {hi}"
        );
        // the last step ends at the full interference
        assert_eq!(r.increments.last().unwrap().load_factor, 1.0);
        // on the way the joint outputs take the gap at the increment's
        // pseudo-time: F_N = the interface's mean pressure × its area, and
        // the interference pressed in raises it step by step
        let mut last = 0.0;
        for inc in &r.increments {
            let j = inc.joints[0];
            assert!(
                common::rel(j.normal_force, inc.measures.mean_pressure * area) < 1e-9,
                "c_N = {c_n}, t = {}: F_N {} vs p̄ A = {}",
                inc.load_factor,
                j.normal_force,
                inc.measures.mean_pressure * area
            );
            assert!(j.normal_force > last, "t = {}: {j:?}", inc.load_factor);
            last = j.normal_force;
        }
        if c_n == 1e-6 {
            fe_rigid = mean;
        } else {
            // the roughness lowers the fit pressure by the predicted amount
            let (drop, predicted) = (fe_rigid - mean, rigid - p);
            eprintln!(
                "  drop {drop:.4} MPa, predicted {predicted:.4} MPa ({:.1e})",
                common::rel(drop, predicted)
            );
            assert!(predicted > 0.0 && drop > 0.0);
            assert!(
                (drop - predicted).abs() < 5e-3 * predicted.max(0.05 * p),
                "c_N = {c_n}: drop {drop} vs {predicted}"
            );
        }

        // the interference imposed at once ends at the same pressure
        let at_once = common::model(&case(c_n, false, None));
        let ra =
            asperity::app::driver::solve(&at_once, &mut Quiet).unwrap_or_else(|e| panic!("{e}"));
        let (mean_once, _) = pressures(&at_once, &ra);
        eprintln!(
            "  at once: {mean_once:.6} MPa ({:.1e})",
            common::rel(mean_once, mean)
        );
        assert!(
            common::rel(mean_once, mean) < 1e-8,
            "c_N = {c_n}: at once {mean_once} vs pressed in {mean}"
        );
    }
}

/// The fit pushed out: after the interference is pressed in (t ≤ 1), every
/// node of the shaft is moved axially (t = 1 … 2) while the hub's ends stay
/// held. The shaft's rigid axial motion keeps its plane-strain state, so
/// the fit pressure stays the closed form's; once the whole interface
/// slides (β = 1, no slip hardening) the holding force is μ p 2π b L
/// (exactly μ F_N at every increment in macro-slip), and each step
/// dissipates F_T times its slip.
#[test]
fn the_pushed_out_shaft_is_held_by_mu_times_the_fit_pressure() {
    let (c_n, mu) = (1e-4, 0.15);
    let text = case(c_n, true, Some(mu));
    let model = common::model(&text);
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"));
    let area = 2.0 * std::f64::consts::PI * B * 10.0;
    let p = fit_pressure(c_n);
    let rows: Vec<_> = r
        .increments
        .iter()
        .map(|i| (i.load_factor, i.joints[0]))
        .collect();
    assert_eq!(rows.last().unwrap().0, 2.0);
    let mut sliding = 0;
    for w in rows.windows(2) {
        let ((_, a), (t, b)) = (w[0], w[1]);
        if t <= 1.0 {
            assert!(
                b.tangential_force.abs() < 1e-9 * b.normal_force,
                "t = {t}: {b:?}"
            );
            continue;
        }
        // the shaft moves up (+y = t): A dragged in +t
        assert!(
            b.tangential_force > 0.0 && b.mean_slip > 0.0,
            "t = {t}: {b:?}"
        );
        assert!(
            common::rel(b.normal_force / area, p) < 5e-3,
            "t = {t}: fit pressure {} vs {p}",
            b.normal_force / area
        );
        if common::rel(b.macro_slip, area) < 1e-12 && common::rel(a.macro_slip, area) < 1e-12 {
            sliding += 1;
            assert!(
                common::rel(b.tangential_force, mu * b.normal_force) < 1e-9,
                "t = {t}: F_T {} vs μ F_N {}",
                b.tangential_force,
                mu * b.normal_force
            );
            let d = b.dissipation - a.dissipation;
            let expect =
                0.5 * (a.tangential_force + b.tangential_force) * (b.mean_slip - a.mean_slip);
            assert!(common::rel(d, expect) < 1e-9, "t = {t}: ΔD {d} vs {expect}");
        }
    }
    let end = rows.last().unwrap().1;
    eprintln!(
        "push-out: F_T {:.2} N, μ p 2π b L = {:.2} N ({:+.1e}), sliding over {sliding} steps",
        end.tangential_force,
        mu * p * area,
        (end.tangential_force - mu * p * area) / (mu * p * area)
    );
    assert!(sliding >= 3, "{rows:?}");
    assert!(common::rel(end.tangential_force, mu * p * area) < 5e-3);
}
