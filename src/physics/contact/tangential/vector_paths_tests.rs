//! The vector law on 2-D paths with closed forms (issue 26): the tractrix
//! of a Coulomb slide turned by 90°, the steady slide around a circle, a
//! straight path at an angle as the scalar law along it, Coulomb as one
//! Jenkins element; the Iwan density's discretization against the loop
//! areas of the exact 1-D law.

use super::jenkins::{Stretch2, IWAN_LOWEST, JENKINS};
use super::vector_tests::{all_laws, approach, drive2, paths, pressure, reach, Lcg};
use super::*;

const P: f64 = 150.0;

/// The paper's law with k_T^p = k_T^e and β = 1: Coulomb's law with an
/// elastic stick, |p_T| ≤ μ p_N.
fn coulomb() -> TangentialLaw {
    TangentialLaw::new(0.9, 0.5, 1.0, 0.2, 1.0, 0.0, 0.625).unwrap()
}

/// The Coulomb law preloaded to sliding along +x, then moved along +y by
/// 1.5 r in `n` steps (r = μ p_N / k_T^e): p_T and κ at the end.
fn turned_slide(n: usize) -> ([f64; 2], f64) {
    let law = coulomb();
    let r = law.mu * P / law.elastic_stiffness(P).0;
    let mut st = law
        .eval_vector(P, 0.0, [2.0 * r, 0.0], &SlipState2::default())
        .state;
    let mut p_t = [0.0; 2];
    for i in 1..=n {
        let ev = law.eval_vector(P, 0.0, [2.0 * r, 1.5 * r * i as f64 / n as f64], &st);
        assert_eq!(ev.slip, Slip::MacroSlip);
        st = ev.state;
        p_t = ev.p_t;
    }
    (p_t, st.kappa)
}

/// A slide turned by 90°: the elastic slip u_e = p_T/k stays on the circle
/// of radius r and turns toward the path as a tractrix. With θ the angle
/// between p_T and the path, dθ/ds = −sin θ / r:
///
/// ```text
///   tan(θ/2) = tan(θ₀/2) e^{−s/r},   θ₀ = π/2;   dκ = cos θ ds,  κ = κ₀ + r ln cosh(s/r)
/// ```
///
/// The radial return is its backward-Euler approximation: first order in
/// the step, so the error halves with the step and Richardson's
/// extrapolation 2 v(2n) − v(n) is second order.
#[test]
fn a_slide_turned_by_90_degrees_follows_the_tractrix_to_first_order() {
    let law = coulomb();
    let cap = law.mu * P;
    let r = cap / law.elastic_stiffness(P).0;
    let s = 1.5 * r;
    let theta = 2.0 * (-s / r).exp().atan();
    let exact = [cap * theta.sin(), cap * theta.cos()];
    let kappa = r + r * (s / r).cosh().ln();
    let err = |p: [f64; 2]| (p[0] - exact[0]).hypot(p[1] - exact[1]) / cap;
    let runs: Vec<_> = [100, 200, 400].iter().map(|&n| turned_slide(n)).collect();
    for w in runs.windows(2) {
        let (e1, e2) = (err(w[0].0), err(w[1].0));
        assert!(
            (1.9..2.1).contains(&(e1 / e2)),
            "p_T errors {e1:e}, {e2:e}: not first order"
        );
        let (k1, k2) = ((w[0].1 - kappa).abs(), (w[1].1 - kappa).abs());
        assert!((1.9..2.1).contains(&(k1 / k2)), "κ errors {k1:e}, {k2:e}");
        let rich = [2.0 * w[1].0[0] - w[0].0[0], 2.0 * w[1].0[1] - w[0].0[1]];
        assert!(
            err(rich) < 0.02 * e2,
            "extrapolated {:e} vs {e2:e}",
            err(rich)
        );
    }
    // n = 400: 0.07 % of μ p_N
    assert!(err(runs[2].0) < 1e-3, "{:e}", err(runs[2].0));
}

/// Slid around a circle of radius R = 4 r (3 turns, `n` steps a turn):
/// p_T and κ of the last turn.
fn circle_slide(n: usize) -> ([f64; 2], f64) {
    let law = coulomb();
    let r = law.mu * P / law.elastic_stiffness(P).0;
    let big_r = 4.0 * r;
    let mut st = law
        .eval_vector(P, 0.0, [big_r, 0.0], &SlipState2::default())
        .state;
    let (mut p_t, mut k2) = ([0.0; 2], 0.0);
    for i in 1..=3 * n {
        let t = std::f64::consts::TAU * i as f64 / n as f64;
        let ev = law.eval_vector(P, 0.0, [big_r * t.cos(), big_r * t.sin()], &st);
        assert!((ev.p_t[0].hypot(ev.p_t[1]) - law.mu * P).abs() < 1e-13 * law.mu * P);
        st = ev.state;
        p_t = ev.p_t;
        if i == 2 * n {
            k2 = st.kappa;
        }
    }
    (p_t, st.kappa - k2)
}

/// Steady sliding around a circle of radius R: u_T^p runs on the circle of
/// radius √(R² − r²), u_e = u_T − u_T^p is tangent to it, so |p_T| = μ p_N
/// with the outward component μ p_N r/R and the component along the path
/// μ p_N √(1 − r²/R²) (p_T tangent to the path only as r/R → 0), and κ
/// grows by 2π √(R² − r²) a turn. First order in the step again.
#[test]
fn steady_sliding_around_a_circle_matches_its_closed_form() {
    let law = coulomb();
    let cap = law.mu * P;
    let r = cap / law.elastic_stiffness(P).0;
    let big_r = 4.0 * r;
    // at the end of a turn u_T = (R, 0): outward is x, along the path y
    let exact = [cap * r / big_r, cap * (1.0 - (r / big_r).powi(2)).sqrt()];
    let turn = std::f64::consts::TAU * (big_r * big_r - r * r).sqrt();
    let runs: Vec<_> = [360, 720, 1440].iter().map(|&n| circle_slide(n)).collect();
    let errs: Vec<[f64; 3]> = runs
        .iter()
        .map(|(p, k)| {
            [
                (p[0] - exact[0]) / exact[0],
                (p[1] - exact[1]) / exact[1],
                (k - turn) / turn,
            ]
        })
        .collect();
    for w in errs.windows(2) {
        for (a, b) in w[0].iter().zip(&w[1]) {
            assert!((1.9..2.1).contains(&(a / b)), "{errs:?}: not first order");
        }
    }
    // 1440 steps a turn: the outward component within 1 %, the rest 0.1 %
    let last = errs[2];
    assert!(
        last[0].abs() < 1e-2 && last[1].abs() < 1e-3 && last[2].abs() < 1e-3,
        "{last:?}"
    );
}

/// An irregular history of s with reversals and pressure changes.
fn walk(f: f64, seed: u64) -> Vec<(f64, f64, f64)> {
    let mut rng = Lcg(seed);
    let (mut s, mut un) = (0.0, approach(P));
    (0..400)
        .map(|i| {
            let dir = if (i / 40) % 2 == 0 { 1.0 } else { -1.0 };
            s += f * (0.12 * dir + 0.3 * (rng.next() - 0.5));
            un = (un + 0.0015 * (rng.next() - 0.5)).clamp(0.005, 0.016);
            let (p, kn) = pressure(un);
            (p, kn, s)
        })
        .collect()
}

/// A straight path at an angle is the scalar law along it: p_T = p n,
/// n·(∂p_T/∂u_T) n = ∂p/∂s, ∂p_T/∂u_N = n ∂p/∂u_N (the Iwan density's
/// discretization excepted).
#[test]
fn a_straight_path_at_an_angle_is_the_scalar_law_along_it() {
    for law in all_laws() {
        if law.memory == Memory::Kinematic && matches!(law.backbone, Backbone::Iwan { .. }) {
            continue;
        }
        let f = reach(&law, P);
        for angle in [0.4f64, 2.2, -1.3] {
            let n = [angle.cos(), angle.sin()];
            let (mut s1, mut s2) = (SlipState::default(), SlipState2::default());
            for (step, &(p, kn, s)) in walk(f, 17).iter().enumerate() {
                let a = law.eval(p, kn, s, &s1);
                let b = law.eval_vector(p, kn, [s * n[0], s * n[1]], &s2);
                let (k, cap) = (law.elastic_stiffness(p).0, law.mu * p);
                let dn: f64 = (0..2)
                    .map(|i| (0..2).map(|j| n[i] * b.d_ut[i][j] * n[j]).sum::<f64>())
                    .sum();
                let rel = [
                    (b.p_t[0] - a.p_t * n[0]).hypot(b.p_t[1] - a.p_t * n[1]) / cap,
                    (dn - a.d_ut).abs() / k,
                    (b.d_un[0] - a.d_un * n[0]).hypot(b.d_un[1] - a.d_un * n[1]) / (kn * law.mu),
                    (b.state.kappa - a.state.kappa).abs() / a.state.kappa.max(f),
                    (b.state.u_p[0] - a.state.u_p * n[0])
                        .hypot(b.state.u_p[1] - a.state.u_p * n[1])
                        / a.state.u_p.abs().max(f),
                ];
                assert!(
                    rel.iter().all(|&x| x < 1e-12),
                    "{law:?} angle {angle} step {step}: {rel:?}"
                );
                assert_eq!(a.slip, b.slip);
                s1 = a.state;
                s2 = b.state;
            }
        }
    }
}

/// With k_T^p = k_T^e and β = 1 the isotropic law is one Jenkins element
/// of radius μ p_N / k_T^e: the bilinear kinematic law with k_T^p = k_T^e.
/// On every 2-D path, pressure drops included, the two agree to round-off.
#[test]
fn coulomb_is_one_jenkins_element_in_the_plane() {
    let iso = coulomb();
    let kin = iso
        .clone()
        .with_memory(Memory::Kinematic, Backbone::Bilinear)
        .unwrap();
    assert_eq!(kin.elements().len, 1);
    let f = reach(&iso, P);
    for (name, path) in paths(f) {
        let (mut a, mut b) = (SlipState2::default(), SlipState2::default());
        for (step, &(p, u)) in path.iter().enumerate() {
            let kn = pressure(approach(p)).1;
            let x = iso.eval_vector(p, kn, u, &a);
            let y = kin.eval_vector(p, kn, u, &b);
            let (k, cap) = (iso.elastic_stiffness(p).0, iso.mu * p);
            let mut rel = vec![
                (x.p_t[0] - y.p_t[0]).hypot(x.p_t[1] - y.p_t[1]) / cap,
                (x.state.kappa - y.state.kappa).abs() / f,
            ];
            for i in 0..2 {
                rel.push((x.d_un[i] - y.d_un[i]).abs() / (kn * iso.mu));
                for j in 0..2 {
                    rel.push((x.d_ut[i][j] - y.d_ut[i][j]).abs() / k);
                }
            }
            assert!(
                rel.iter().all(|&v| v < 1e-12),
                "{name} step {step}: {rel:?}"
            );
            assert_eq!(x.slip, y.slip, "{name} step {step}");
            a = x.state;
            b = y.state;
        }
    }
}

#[test]
fn an_open_point_carries_nothing_and_forgets() {
    for law in all_laws() {
        let f = reach(&law, P);
        let mut st = SlipState2::default();
        drive2(&law, &paths(f)[0].1, &mut st);
        let ev = law.eval_vector(0.0, 0.0, [0.3 * f, -0.2 * f], &st);
        assert_eq!(ev.p_t, [0.0; 2]);
        assert_eq!(ev.d_ut, [[0.0; 2]; 2]);
        assert_eq!(ev.d_un, [0.0; 2]);
        assert_eq!(ev.state.u_p, [0.3 * f, -0.2 * f]);
        assert_eq!(ev.state.kappa, st.kappa);
        assert_eq!(ev.state.mem, Stretch2::default());
        // closed again: it sticks where it opened
        let back = law.eval_vector(P, 0.0, [0.3 * f, -0.2 * f], &ev.state);
        assert_eq!(back.p_t, [0.0; 2]);
    }
}

/// The loop area of the Iwan density at amplitude a = x φ, over k φ²
/// (the closed form of `memory_tests`).
fn density_loop(chi: f64, spike: f64, x: f64) -> f64 {
    let c = 1.0 - spike;
    let xx = x.min(1.0);
    4.0 * (c * (1.0 + chi) * xx.powf(chi + 3.0) / ((chi + 2.0) * (chi + 3.0))
        + (spike + c * (1.0 + chi) / (chi + 2.0)) * (x - 1.0).max(0.0))
}

/// The loop area of a set of Jenkins elements, over k φ²: Σ 4 mᵢ ηᵢ (x − ηᵢ)₊.
fn discrete_loop(el: &Elements, x: f64) -> f64 {
    (0..el.len)
        .map(|i| 4.0 * el.mass[i] * el.eta[i] * (x - el.eta[i]).max(0.0))
        .sum()
}

/// The discretization's loop-area error bound at amplitude x φ, as
/// measured over χ ∈ [−0.9, 1] by the next test.
fn loop_bound(x: f64) -> f64 {
    if x >= 1.0 {
        0.011
    } else if x >= 10.0 * IWAN_LOWEST {
        0.054
    } else {
        assert!(x >= 3.0 * IWAN_LOWEST, "no bound below 3 λ φ");
        0.091
    }
}

fn iwan_kinematic(chi: f64, spike: f64) -> TangentialLaw {
    coulomb()
        .with_memory(Memory::Kinematic, Backbone::Iwan { chi, spike })
        .unwrap()
}

/// The discrete set keeps the density's mass and first moment (initial
/// stiffness, friction limit); its loops and first loading differ from the
/// density's by the bounds of `loop_bound` (largest at χ = −0.9 near 3 λ φ,
/// at χ = 1 above 10 λ φ) and 1.3 % on the first loading above 3 λ φ.
#[test]
fn the_iwan_discretization_error_is_bounded_over_amplitudes() {
    for chi in [-0.9, -0.5, 0.0, 0.3, 0.5, 1.0] {
        for spike in [0.0, 0.25] {
            let law = iwan_kinematic(chi, spike);
            let el = law.elements();
            assert_eq!(el.len, JENKINS - usize::from(spike == 0.0));
            let mass: f64 = el.mass[..el.len].iter().sum();
            let moment: f64 = (0..el.len).map(|i| el.mass[i] * el.eta[i]).sum();
            assert!((mass - 1.0).abs() < 1e-14 && (moment * el.big_c - 1.0).abs() < 1e-14);
            let c = 1.0 - spike;
            let (mut worst, mut worst_f) = (0.0f64, 0.0f64);
            for i in 0..=3000 {
                let x = 3.0 * IWAN_LOWEST * (100.0f64).powf(i as f64 / 3000.0);
                let e = (discrete_loop(&el, x) / density_loop(chi, spike, x) - 1.0).abs();
                assert!(
                    e <= loop_bound(x),
                    "χ = {chi}, spike {spike}, a = {x} φ: loop area off by {e}"
                );
                worst = worst.max(e);
                if x <= 1.0 {
                    let f_d: f64 = (0..el.len).map(|j| el.mass[j] * x.min(el.eta[j])).sum();
                    let f_c = c * (x - x.powf(chi + 2.0) / (chi + 2.0)) + spike * x;
                    worst_f = worst_f.max((f_d / f_c - 1.0).abs());
                }
            }
            assert!(
                worst_f < 0.013,
                "χ = {chi}, spike {spike}: first loading off by {worst_f}"
            );
            eprintln!(
                "χ = {chi}, spike {spike}: loop areas within {worst:.2e}, first loading {worst_f:.2e}"
            );
        }
    }
}

/// Cycles u_T = ±a along a line at 40° from the virgin state: ∮ p_T·du per cycle.
fn loops_at_an_angle(law: &TangentialLaw, a: f64, cycles: usize) -> Vec<f64> {
    let n = [0.7f64.cos(), 0.7f64.sin()];
    let steps = 4000;
    let mut st = SlipState2::default();
    let at = |s: f64| [s * n[0], s * n[1]];
    let mut last = (0.0, 0.0);
    for i in 1..=steps {
        let s = a * i as f64 / steps as f64;
        let ev = law.eval_vector(P, 0.0, at(s), &st);
        st = ev.state;
        last = (s, ev.p_t[0] * n[0] + ev.p_t[1] * n[1]);
    }
    (0..cycles)
        .map(|_| {
            let mut area = 0.0;
            for i in 1..=4 * steps {
                let t = i as f64 / steps as f64;
                let s = if t <= 2.0 {
                    a * (1.0 - t)
                } else {
                    a * (t - 3.0)
                };
                let ev = law.eval_vector(P, 0.0, at(s), &st);
                st = ev.state;
                let p = ev.p_t[0] * n[0] + ev.p_t[1] * n[1];
                area += 0.5 * (p + last.1) * (s - last.0);
                last = (s, p);
            }
            area
        })
        .collect()
}

/// The vector law's Iwan loops: those of its Jenkins elements (to the
/// trapezoid rule's 1e-5), and the density's within the measured bound.
#[test]
fn iwan_loops_match_the_elements_exactly_and_the_density_within_the_bound() {
    for (chi, spike) in [(0.0, 0.0), (-0.5, 0.0), (0.3, 0.25)] {
        let law = iwan_kinematic(chi, spike);
        let (k, phi) = (law.elastic_stiffness(P).0, reach(&law, P));
        let el = law.elements();
        for x in [0.05, 0.3, 0.8, 1.5] {
            let (d_el, d_dens) = (
                k * phi * phi * discrete_loop(&el, x),
                k * phi * phi * density_loop(chi, spike, x),
            );
            for (i, d) in loops_at_an_angle(&law, x * phi, 2).into_iter().enumerate() {
                assert!(
                    (d - d_el).abs() < 1e-5 * d_el,
                    "χ = {chi}, spike {spike}, a = {x} φ, cycle {}: {d} vs the elements' {d_el}",
                    i + 1
                );
                assert!(
                    (d - d_dens).abs() <= loop_bound(x) * d_dens,
                    "χ = {chi}, spike {spike}, a = {x} φ: {d} vs the density's {d_dens}"
                );
            }
        }
    }
}
