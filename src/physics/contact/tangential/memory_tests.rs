//! The kinematic memory and the Iwan backbone (issue 28): tangents against
//! finite differences, loop areas against their closed forms, Masing's rules.

use super::*;
use crate::numbers::fd;

const P: f64 = 150.0;

fn bilinear(kp: f64) -> TangentialLaw {
    TangentialLaw::new(0.9, 0.5, kp, 0.2, 1.0, 0.0, 0.625).unwrap()
}

fn iwan(memory: Memory, chi: f64, spike: f64) -> TangentialLaw {
    bilinear(1.0)
        .with_memory(memory, Backbone::Iwan { chi, spike })
        .unwrap()
}

fn kinematic(kp: f64) -> TangentialLaw {
    bilinear(kp)
        .with_memory(Memory::Kinematic, Backbone::Bilinear)
        .unwrap()
}

/// Every law of this file.
fn laws() -> Vec<TangentialLaw> {
    vec![
        kinematic(0.05),
        kinematic(0.3),
        kinematic(1.0),
        kinematic(0.0),
        iwan(Memory::Kinematic, 0.0, 0.0),
        iwan(Memory::Kinematic, -0.5, 0.0),
        iwan(Memory::Kinematic, 0.3, 0.25),
        iwan(Memory::Isotropic, 0.0, 0.0),
        iwan(Memory::Isotropic, -0.5, 0.2),
    ]
}

/// p(u_N) = (u/c)², as in the tests of the paper's law.
fn pressure(un: f64) -> (f64, f64) {
    let c = 0.001;
    ((un / c).powi(2), 2.0 * un / (c * c))
}

/// u_N of pressure p.
fn approach(p: f64) -> f64 {
    0.001 * p.sqrt()
}

/// Drives one point through a path of u_T at constant p_N: (u_T, p_T) per step.
fn drive(law: &TangentialLaw, p: f64, path: &[f64], st: &mut SlipState) -> Vec<(f64, f64)> {
    path.iter()
        .map(|&u| {
            let ev = law.eval(p, 0.0, u, st);
            *st = ev.state;
            (u, ev.p_t)
        })
        .collect()
}

/// `n` steps from `a` to `b`, `b` included.
fn ramp(a: f64, b: f64, n: usize) -> Vec<f64> {
    (1..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

/// ∮ p du of a closed path by the trapezoid rule.
fn area(points: &[(f64, f64)]) -> f64 {
    points
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum()
}

/// φ, the displacement at which every element slips, at pressure p.
fn phi(law: &TangentialLaw, p: f64) -> f64 {
    law.mu * p * law.density().big_c / law.elastic_stiffness(p).0
}

#[test]
fn tangents_match_finite_differences_after_irregular_histories() {
    let un = approach(P);
    for law in laws() {
        let f = phi(&law, P);
        // committed states: virgin, after loading, after a reversal, after a nested loop
        let mut states = vec![SlipState::default()];
        for path in [
            vec![0.6 * f],
            vec![0.8 * f, -0.3 * f],
            vec![0.9 * f, -0.7 * f, 0.2 * f, -0.1 * f],
        ] {
            let mut st = SlipState::default();
            // one step to each turning point: the law is rate independent
            drive(&law, P, &path, &mut st);
            states.push(st);
        }
        let (mut checked, mut seen) = (0, Vec::new());
        for committed in &states {
            for s in [-1.3, -0.75, -0.4, -0.05, 0.07, 0.35, 0.55, 0.95, 1.6] {
                let ut = s * f;
                let (p, kn) = pressure(un);
                let ev = law.eval(p, kn, ut, committed);
                seen.push(ev.slip);
                let g = |un: f64, ut: f64| {
                    let (p, kn) = pressure(un);
                    law.eval(p, kn, ut, committed).p_t
                };
                let scale = law.elastic_stiffness(p).0;
                // one-sided differences that disagree: a kink (an element
                // starting or ending to slip) at this point; not checked
                let (h, hn) = (1e-7 * f, 1e-9);
                // columns ∂/∂u_N (step hn), ∂/∂u_T (step h)
                let d = fd::sided_columns(&[hn, h], |j, step| {
                    vec![if j == 0 {
                        g(un + step, ut)
                    } else {
                        g(un, ut + step)
                    }]
                });
                let smooth_t = d.kink(0, 1) < 1e-4 * scale;
                let smooth_n = d.kink(0, 0) < 1e-4 * (ev.d_un.abs().max(scale * 1e-2));
                if smooth_t && smooth_n {
                    checked += 1;
                    let t = fd::Mismatch::of(0, 1, ev.d_ut, d.central[(0, 1)], fd::Scale::Absolute);
                    assert!(
                        t.diff < 1e-5 * scale,
                        "{law:?} ut = {s} φ {:?}: d_ut {t}",
                        ev.slip,
                    );
                    let n = fd::Mismatch::of(
                        0,
                        0,
                        ev.d_un,
                        d.central[(0, 0)],
                        fd::Scale::Relative(scale * 1e-3),
                    );
                    assert!(
                        n.diff < 1e-5 * n.scale,
                        "{law:?} ut = {s} φ {:?}: d_un {n}",
                        ev.slip,
                    );
                }
            }
        }
        assert!(checked >= 28, "{law:?}: only {checked} of 36 points smooth");
        if law.kp_ratio > 0.0 {
            assert!(seen.contains(&Slip::MacroSlip), "{law:?}: {seen:?}");
        }
        if law.kp_ratio < 1.0 || matches!(law.backbone, Backbone::Iwan { .. }) {
            assert!(seen.contains(&Slip::MicroSlip), "{law:?}: {seen:?}");
        }
    }
}

/// Loop areas of cycles u_T = ±a at constant p_N, cycle by cycle (the first
/// starts from the virgin state at 0 and loads to +a first).
fn loops(law: &TangentialLaw, a: f64, cycles: usize) -> Vec<f64> {
    let n = 4000;
    let mut st = SlipState::default();
    drive(law, P, &ramp(0.0, a, n), &mut st);
    let start = law.eval(P, 0.0, a, &st).p_t;
    (0..cycles)
        .map(|_| {
            let mut path = ramp(a, -a, 2 * n);
            path.extend(ramp(-a, a, 2 * n));
            let mut pts = vec![(a, start)];
            pts.extend(drive(law, P, &path, &mut st));
            area(&pts)
        })
        .collect()
}

#[test]
fn loop_areas_match_their_closed_forms() {
    // Iwan: D = 4 k φ² c (1+χ) x^{χ+3} / ((χ+2)(χ+3)) + 4 s k φ (a − φ)₊, x = min(a/φ, 1)
    for (chi, spike) in [(0.0, 0.0), (-0.5, 0.0), (0.3, 0.25)] {
        let law = iwan(Memory::Kinematic, chi, spike);
        let (k, f) = (law.elastic_stiffness(P).0, phi(&law, P));
        let c = 1.0 - spike;
        for s in [0.05, 0.3, 0.8, 1.5] {
            let a = s * f;
            let x: f64 = s.min(1.0);
            let d = 4.0 * k * f * f * c * (1.0 + chi) * x.powf(chi + 3.0)
                / ((chi + 2.0) * (chi + 3.0))
                + 4.0 * spike * k * f * (a - f).max(0.0)
                // beyond φ the continuous part slips at its full limit too
                + if s > 1.0 { 4.0 * c * k * f * (1.0 + chi) / (chi + 2.0) * (a - f) } else { 0.0 };
            for (i, got) in loops(&law, a, 3).into_iter().enumerate() {
                assert!(
                    (got - d).abs() < 1e-5 * d,
                    "χ = {chi}, spike {spike}, a = {s} φ, cycle {}: {got} vs {d}",
                    i + 1
                );
            }
        }
    }
    // the paper's two lines as two Jenkins elements: Σ 4 k mⱼ ηⱼ φ (a − ηⱼ φ)₊
    for kp in [0.05, 0.3, 1.0] {
        let law = kinematic(kp);
        let (k, f) = (law.elastic_stiffness(P).0, phi(&law, P));
        for s in [0.2, 0.6, 1.4] {
            let a = s * f;
            let d: f64 = law
                .density()
                .masses
                .iter()
                .map(|&(eta, m)| 4.0 * k * m * eta * f * (a - eta * f).max(0.0))
                .sum();
            for got in loops(&law, a, 2) {
                assert!(
                    (got - d).abs() < 1e-5 * d.max(1e-3 * k * f * f),
                    "k_p/k = {kp}, a = {s} φ: {got} vs {d}"
                );
            }
        }
    }
}

/// Under force cycles the isotropic memory slips in the first only (its
/// limit is the largest |p_T| reached); under these displacement cycles
/// every reversal slips a little less (the limit grows with κ): the loops
/// shrink toward none (shakedown) while the kinematic memory's stay. (At
/// larger amplitudes κ may reach the friction cap first: Coulomb loops.)
#[test]
fn the_isotropic_memory_shakes_down_under_constant_amplitude() {
    for law in [bilinear(0.3), iwan(Memory::Isotropic, 0.0, 0.0)] {
        let f = phi(
            &law.clone()
                .with_memory(Memory::Kinematic, law.backbone)
                .unwrap(),
            P,
        );
        let d = loops(&law, 0.5 * f, 8);
        assert!(d[0] > 0.0, "{law:?}: {d:?}");
        for w in d.windows(2) {
            assert!(w[1] < w[0], "{law:?}: {d:?}");
        }
        assert!(d[7] < 0.05 * d[0], "{law:?}: {d:?}");
    }
}

/// f(u): the first-loading curve of a law from the virgin state.
fn backbone(law: &TangentialLaw, u: f64) -> f64 {
    law.eval(P, 0.0, u, &SlipState::default()).p_t
}

#[test]
fn masing_branches_are_the_backbone_scaled_by_two_and_nested_loops_close() {
    for law in [
        iwan(Memory::Kinematic, 0.0, 0.0),
        iwan(Memory::Kinematic, -0.4, 0.1),
        kinematic(0.2),
    ] {
        let f = phi(&law, P);
        let scale = law.mu * P;
        // rule 1: after a reversal at (u_r, p_r), p = p_r − 2 f((u_r − u)/2)
        let ur = 0.7 * f;
        let mut st = SlipState::default();
        drive(&law, P, &ramp(0.0, ur, 50), &mut st);
        let pr = backbone(&law, ur);
        let down = drive(&law, P, &ramp(ur, -0.9 * f, 80), &mut st.clone());
        for &(u, p) in &down {
            let expect = if u >= -ur {
                pr - 2.0 * backbone(&law, 0.5 * (ur - u))
            } else {
                // past −u_r the branch has met the mirrored first loading
                -backbone(&law, -u)
            };
            assert!(
                (p - expect).abs() < 1e-9 * scale,
                "{law:?} at u = {u}: {p} vs {expect}"
            );
        }
        // rules 2-3: an inner loop B → C → B leaves the outer branch unchanged
        let mut outer = st;
        let mut inner = st;
        drive(&law, P, &ramp(ur, -0.6 * f, 40), &mut outer);
        drive(&law, P, &ramp(ur, -0.6 * f, 40), &mut inner);
        drive(&law, P, &ramp(-0.6 * f, 0.1 * f, 30), &mut inner);
        drive(&law, P, &ramp(0.1 * f, -0.3 * f, 30), &mut inner);
        drive(&law, P, &ramp(-0.3 * f, 0.1 * f, 30), &mut inner);
        let a = drive(&law, P, &ramp(0.1 * f, 0.6 * f, 20), &mut inner);
        drive(&law, P, &ramp(-0.6 * f, 0.1 * f, 30), &mut outer);
        let b = drive(&law, P, &ramp(0.1 * f, 0.6 * f, 20), &mut outer);
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (x.1 - y.1).abs() < 1e-9 * scale,
                "{law:?} at u = {}: {} after the inner loop, {} without",
                x.0,
                x.1,
                y.1
            );
        }
    }
}

#[test]
fn a_drop_of_pressure_clips_the_stretches_and_an_open_point_forgets() {
    let law = iwan(Memory::Kinematic, 0.0, 0.0);
    let f = phi(&law, P);
    let mut st = SlipState::default();
    drive(&law, P, &[0.5 * f], &mut st);
    // at a quarter of the pressure every element's range is a quarter
    let ev = law.eval(P / 4.0, 0.0, 0.5 * f, &st);
    assert!(ev.state.mem.largest_ratio() <= phi(&law, P / 4.0) * (1.0 + 1e-12));
    assert!(ev.p_t.abs() <= law.mu * P / 4.0 * (1.0 + 1e-12));
    // open: no shear, no stretch, u_p follows u_T
    let open = law.eval(0.0, 0.0, 0.3 * f, &st);
    assert_eq!(open.p_t, 0.0);
    assert_eq!(open.state.mem, Stretch::default());
    assert_eq!(open.state.u_p, 0.3 * f);
}

#[test]
fn bad_memory_combinations_are_named() {
    let iw = |chi, spike| Backbone::Iwan { chi, spike };
    let e = |law: TangentialLaw, m, b| law.with_memory(m, b).unwrap_err();
    assert!(e(bilinear(0.3), Memory::Kinematic, iw(-1.0, 0.0)).contains("chi = -1"));
    assert!(e(bilinear(0.3), Memory::Isotropic, iw(0.0, 1.0)).contains("spike = 1"));
    assert!(e(bilinear(0.3), Memory::Isotropic, iw(f64::NAN, 0.0)).contains("chi"));
    let hardening = TangentialLaw::new(0.9, 0.5, 0.3, 0.2, 0.5, 100.0, 0.625).unwrap();
    assert!(e(hardening.clone(), Memory::Kinematic, Backbone::Bilinear).contains("beta = 0.5"));
    assert!(e(hardening, Memory::Isotropic, iw(0.0, 0.0)).contains("beta"));
}
