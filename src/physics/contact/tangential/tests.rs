use super::*;
use crate::numbers::fd;

fn laws() -> Vec<TangentialLaw> {
    vec![
        TangentialLaw::new(0.9, 0.5, 1.0, 0.2, 1.0, 275.0, 0.625).unwrap(), // Fig. 7a
        TangentialLaw::new(0.9, 0.5, 0.05, 0.2, 1.0, 275.0, 0.625).unwrap(), // Fig. 7b
        TangentialLaw::new(0.9, 0.5, 0.05, 0.2, 0.2, 275.0, 0.625).unwrap(), // Fig. 7c
        TangentialLaw::new(0.9, 0.0, 0.0, 0.3, 0.5, 100.0, 0.5).unwrap(),
    ]
}

/// k_table sampled from p^0.5 / 0.9 MPa/µm at 20 ... 150 MPa: with the FD
/// check's u_N ≈ 0.014 mm (196 MPa) the stiffness is extrapolated; other
/// pressures below use the power law below the first point and the cubic.
fn table_laws() -> Vec<TangentialLaw> {
    let rows: Vec<(f64, f64)> = [20.0, 35.0, 60.0, 100.0, 150.0]
        .iter()
        .map(|&p: &f64| (p, p.sqrt() / 0.9))
        .collect();
    [(1.0, 1.0), (0.05, 1.0), (0.05, 0.2)]
        .iter()
        .map(|&(kp, beta)| TangentialLaw::with_k_table(&rows, kp, 0.2, beta, 275.0, 0.625).unwrap())
        .collect()
}

#[test]
fn k_table_stiffness_is_continuous_with_its_derivative() {
    let law = &table_laws()[0];
    for &p in &[5.0, 20.0, 27.0, 60.0, 80.0, 150.0, 300.0] {
        let (k, dk) = law.elastic_stiffness(p);
        assert!(k > 0.0 && dk > 0.0, "p = {p}");
        let h = 1e-6 * p;
        let fd = fd::central_derivative(|p| law.elastic_stiffness(p).0, p, h);
        assert!(
            (fd - dk).abs() <= 1e-6 * dk,
            "p = {p}: dk/dp {dk} vs FD {fd}"
        );
    }
    // the rows in MPa/µm are k in MPa/mm / 1000; below row 1: k ∝ p^0.5 (s₁ exact here)
    let k20 = law.elastic_stiffness(20.0).0;
    assert!((k20 - 1000.0 * 20f64.sqrt() / 0.9).abs() < 1e-9 * k20);
    let k5 = law.elastic_stiffness(5.0).0;
    assert!((k5 - 1000.0 * 5f64.sqrt() / 0.9).abs() < 1e-9 * k5);
    // beyond the last row: linear
    let (a, da) = law.elastic_stiffness(200.0);
    let (b, db) = law.elastic_stiffness(300.0);
    assert_eq!(da, db);
    assert!((b - a - 100.0 * da).abs() < 1e-9 * b);
}

#[test]
fn k_table_consistent_tangent_matches_finite_differences_in_every_regime() {
    // normal approaches giving p below row 1 (9 MPa), between rows (49, 121 MPa)
    // and beyond the last (196 MPa)
    for law in table_laws() {
        let mut seen = Vec::new();
        for un in [0.003, 0.007, 0.011, 0.014] {
            for committed in [
                SlipState::default(),
                SlipState {
                    u_p: 1.5e-4,
                    kappa: 4e-4,
                    ..Default::default()
                },
            ] {
                for ut in [2e-5, -7e-5, 2e-4, 6e-4, -9e-4, 3e-3, -8e-3] {
                    let (p, kn) = pressure(un);
                    let ev = law.eval(p, kn, ut, &committed);
                    seen.push(ev.slip);
                    let f = |un: f64, ut: f64| {
                        let (p, kn) = pressure(un);
                        law.eval(p, kn, ut, &committed).p_t
                    };
                    let h = 1e-10;
                    // columns ∂/∂u_N, ∂/∂u_T
                    let jac = fd::central_jacobian(|x| vec![f(x[0], x[1])], &[un, ut], h);
                    let scale = law.elastic_stiffness(p).0;
                    let t = fd::Mismatch::of(0, 1, ev.d_ut, jac[(0, 1)], fd::Scale::Absolute);
                    assert!(
                        t.diff < 1e-5 * scale,
                        "un={un} ut={ut} {:?}: d_ut {t}",
                        ev.slip,
                    );
                    let n = fd::Mismatch::of(
                        0,
                        0,
                        ev.d_un,
                        jac[(0, 0)],
                        fd::Scale::Relative(scale * 1e-3),
                    );
                    assert!(
                        n.diff < 1e-5 * n.scale,
                        "un={un} ut={ut} {:?}: d_un {n}",
                        ev.slip,
                    );
                }
            }
        }
        assert!(seen.contains(&Slip::Stick), "{seen:?}");
        assert!(seen.contains(&Slip::MacroSlip), "{seen:?}");
        if law.kp_ratio < 1.0 {
            assert!(seen.contains(&Slip::MicroSlip), "{seen:?}");
        }
    }
}

#[test]
fn bad_k_tables_are_named() {
    let e = |rows: &[(f64, f64)]| {
        TangentialLaw::with_k_table(rows, 0.05, 0.2, 1.0, 275.0, 0.625).unwrap_err()
    };
    assert!(e(&[(10.0, 3.0)]).contains("at least 2"));
    assert!(e(&[(10.0, 3.0), (20.0, 2.0)]).contains("not monotone"));
    assert!(e(&[(10.0, 3.0), (5.0, 4.0)]).contains("row 2: p_N = 5"));
    assert!(e(&[(10.0, 0.0), (20.0, 4.0)]).contains("row 1"));
    // a constant stiffness (S = 0) is a valid table
    let law =
        TangentialLaw::with_k_table(&[(10.0, 3.0), (20.0, 3.0)], 0.05, 0.2, 1.0, 275.0, 0.625)
            .unwrap();
    assert_eq!(law.elastic_stiffness(15.0), (3000.0, 0.0));
}

/// p(u_N) = (u/c)² (power law m = 1/2) so ∂p_T/∂u_N can be checked too.
fn pressure(un: f64) -> (f64, f64) {
    let c = 0.001;
    ((un / c).powi(2), 2.0 * un / (c * c))
}

#[test]
fn consistent_tangent_matches_finite_differences_in_every_regime() {
    let un = 0.014; // ≈ 196 MPa
    for law in laws() {
        let mut seen = Vec::new();
        for committed in [
            SlipState::default(),
            SlipState {
                u_p: 1.5e-3,
                kappa: 4e-3,
                ..Default::default()
            },
        ] {
            for ut in [2e-4, -7e-4, 1.2e-3, 2.5e-3, 6e-3, -9e-3, 3e-2, -0.08] {
                let (p, kn) = pressure(un);
                let ev = law.eval(p, kn, ut, &committed);
                seen.push(ev.slip);
                let h = 1e-9;
                let f = |un: f64, ut: f64| {
                    let (p, kn) = pressure(un);
                    law.eval(p, kn, ut, &committed).p_t
                };
                // columns ∂/∂u_N, ∂/∂u_T
                let jac = fd::central_jacobian(|x| vec![f(x[0], x[1])], &[un, ut], h);
                let scale = law.elastic_stiffness(p).0;
                let t = fd::Mismatch::of(0, 1, ev.d_ut, jac[(0, 1)], fd::Scale::Absolute);
                assert!(
                    t.diff < 1e-5 * scale,
                    "{law:?} {committed:?} ut={ut} {:?}: d_ut {t}",
                    ev.slip,
                );
                let n = fd::Mismatch::of(
                    0,
                    0,
                    ev.d_un,
                    jac[(0, 0)],
                    fd::Scale::Relative(scale * 1e-3),
                );
                assert!(
                    n.diff < 1e-5 * n.scale,
                    "{law:?} ut={ut} {:?}: d_un {n}",
                    ev.slip,
                );
            }
        }
        // every regime the law has was exercised
        // (with k_T^p = 0 the limit stays at ρ μ p_N: micro-slip only, no cap)
        assert!(seen.contains(&Slip::Stick), "{law:?}: {seen:?}");
        if law.kp_ratio > 0.0 {
            assert!(seen.contains(&Slip::MacroSlip), "{law:?}: {seen:?}");
        }
        if law.kp_ratio < 1.0 {
            assert!(seen.contains(&Slip::MicroSlip), "{law:?}: {seen:?}");
        }
    }
}

/// Drives one spring through a displacement history at fixed pressure p.
fn drive(law: &TangentialLaw, p: f64, path: &[f64]) -> Vec<(f64, TangentialEval)> {
    let mut st = SlipState::default();
    let mut out = Vec::new();
    for &ut in path {
        let ev = law.eval(p, 0.0, ut, &st);
        st = ev.state;
        out.push((ut, ev));
    }
    out
}

#[test]
fn load_unload_reverse_reload_follows_fig_1() {
    let law = laws()[1].clone(); // k_T^p = 0.05 k_T^e, β = 1
    let p = 200.0;
    let (ke, _) = law.elastic_stiffness(p);
    let ky = law.yield_ratio * law.mu * p; // 25 MPa
    let u_y = ky / ke;
    let kp = law.kp_ratio * ke;
    let cap = law.mu * p; // 40 MPa
    let u_cap = u_y + (cap - ky) / kp;
    // load in small steps to 2 u_cap, unload to 0 shear, reverse, reload
    let mut path: Vec<f64> = (1..=200).map(|i| 2.0 * u_cap * i as f64 / 200.0).collect();
    let top = path[path.len() - 1];
    path.extend((1..=200).map(|i| top - 2.5 * u_cap * i as f64 / 200.0));
    let res = drive(&law, p, &path);
    for (ut, ev) in &res[..200] {
        let expect = if *ut <= u_y {
            ke * ut
        } else if *ut <= u_cap {
            ky + kp * (ut - u_y)
        } else {
            cap
        };
        assert!(
            (ev.p_t - expect).abs() < 1e-9 * cap,
            "loading at u = {ut}: {} vs {expect}",
            ev.p_t
        );
    }
    // unloading and reversal: elastic with slope k_T^e until the shear reaches −(highest earlier) = −cap
    let (u_top, ev_top) = res[199];
    for (ut, ev) in &res[200..] {
        let elastic = ev_top.p_t + ke * (ut - u_top);
        if elastic >= -cap {
            assert!(
                (ev.p_t - elastic).abs() < 1e-9 * cap,
                "unloading at u = {ut}"
            );
            assert_eq!(
                ev.state.kappa, ev_top.state.kappa,
                "no new plastic slip on reversal below the earlier maximum"
            );
        } else {
            assert!(
                (ev.p_t + cap).abs() < 1e-9 * cap,
                "reversed macro-slip at −μ p_N"
            );
        }
    }
}

#[test]
fn slip_hardening_follows_eq_2_21() {
    let law = laws()[2].clone(); // β = 0.2: starts slipping at 0.2 μ p_N
    let p = 150.0;
    let path: Vec<f64> = (1..=400).map(|i| 0.05 * i as f64 / 400.0).collect();
    for (_, ev) in drive(&law, p, &path) {
        if ev.slip == Slip::MacroSlip {
            let mu_f = law.mu * (1.0 - (1.0 - law.beta) * (-law.n * ev.state.kappa).exp());
            assert!(
                (ev.p_t - mu_f * p).abs() < 1e-9 * p,
                "p_T = μ_F p_N on macro-slip"
            );
            assert!((ev.mu_f - mu_f).abs() < 1e-15);
        }
    }
    let last = drive(&law, p, &path).pop().unwrap().1;
    assert!(
        (last.p_t - law.mu * p).abs() < 1e-3 * law.mu * p,
        "saturates at μ_m p_N: {}",
        last.p_t
    );
}

#[test]
fn bad_parameters_are_named() {
    assert!(TangentialLaw::new(0.0, 0.5, 0.05, 0.2, 1.0, 275.0, 0.625)
        .unwrap_err()
        .contains("r ="));
    assert!(TangentialLaw::new(0.9, 0.5, 1.5, 0.2, 1.0, 275.0, 0.625)
        .unwrap_err()
        .contains("kp_ratio"));
    assert!(TangentialLaw::new(0.9, 0.5, 0.05, 0.2, 0.0, 275.0, 0.625)
        .unwrap_err()
        .contains("beta"));
    assert!(TangentialLaw::new(0.9, 0.5, 0.05, -0.2, 1.0, 275.0, 0.625)
        .unwrap_err()
        .contains("mu"));
}

/// A force cycled back to its earlier peak reaches the limit Y(κ) within
/// round-off: no slip there (stick and slip alternated between Newton
/// iterations and the step failed before, issue 28).
#[test]
fn the_earlier_peak_reached_again_within_round_off_sticks() {
    let law = laws()[1].clone();
    let p = 200.0;
    let (k, _) = law.elastic_stiffness(p);
    let mut st = SlipState::default();
    // into micro-slip, then back to zero shear
    let top = 4.0 * law.yield_ratio * law.mu * p / k;
    let peak = law.eval(p, 0.0, top, &st);
    assert_eq!(peak.slip, Slip::MicroSlip);
    st = peak.state;
    // the peak's u_T again, one ulp-scale step beyond
    for ut in [top, top * (1.0 + 1e-15)] {
        let ev = law.eval(p, 0.0, ut, &st);
        assert_eq!(ev.slip, Slip::Stick, "u_T = {ut}");
        assert_eq!(ev.d_ut, k);
        assert_eq!(ev.state, st);
    }
    // clearly beyond: slips
    assert_eq!(law.eval(p, 0.0, top * 1.001, &st).slip, Slip::MicroSlip);
}
