//! Checks of the handbook formulas: worked examples to the digits they were printed with, and,
//! because those numbers were themselves computed from the same formulas, independent checks —
//! the limits the formulas must reach, a direct solve of the two-cylinder compatibility, the
//! continuity of the cone cases, and values of ISO 724 and of the VDI tables typed here.

use super::din7190::*;
use super::masing::UniformJoint;
use super::thread::{PropertyClass, Thread};
use super::vdi2230::*;
use super::*;
use nalgebra::{Matrix5, Vector5};
use std::f64::consts::PI;

/// `value` rounds to `printed` at the step it was printed with (0.01 for "15.11").
fn assert_printed(value: f64, printed: f64, step: f64) {
    assert!(
        (value - printed).abs() <= 0.5 * step * (1.0 + 1e-9),
        "{value} does not print as {printed} (step {step})"
    );
}

fn assert_rel(a: f64, b: f64, tol: f64) {
    assert!(
        (a - b).abs() <= tol * b.abs(),
        "{a} vs {b} (relative {tol})"
    );
}

// ---------------------------------------------------------------------------------------------
// DIN 7190-1

/// The worked example: eAssistant's geometry (D_F 50, l_F 20, D_aA 95, D_iI 30), steel on
/// steel, H7/s6 (U = 18…59 µm), Rz 6 + 4 µm, R_eL 430 (hub) and 590 (shaft), ν = 0.15.
fn example_fit() -> Fit {
    Fit {
        d_f: 50.0,
        l_f: 20.0,
        d_aa: 95.0,
        d_ii: 30.0,
        e_hub: 210_000.0,
        poisson_hub: 0.3,
        e_shaft: 210_000.0,
        poisson_shaft: 0.3,
        interference: 0.018,
        rz_hub: 6.0,
        rz_shaft: 4.0,
        smoothing: SMOOTHING_2017,
        yield_hub: 430.0,
        yield_shaft: 590.0,
        adhesion_torque: 0.15,
        adhesion_axial: 0.15,
    }
}

const STEEL_DENSITY: f64 = 7.85e-9;

/// Contact pressure from a direct solve of the two cylinders' compatibility: plane-stress Lamé
/// fields u = A r + B/r (+ C r³ with C = −(1 − ν²) ρ ω²/(8E) when rotating), unknowns
/// [A_hub, B_hub, A_shaft, B_shaft, p]; free outer hub face, σ_r = −p on both sides of the
/// joint, free bore (or B = 0 for a solid shaft), u_hub − u_shaft = U_w/2 at the joint.
fn compatibility_pressure(fit: &Fit, omega: f64, rho_hub: f64, rho_shaft: f64) -> f64 {
    compatibility_pressure_hot(fit, omega, (rho_hub, rho_shaft), (0.0, 0.0))
}

/// [`compatibility_pressure`] with each part at a uniform free thermal strain ε = α ΔT (hub,
/// shaft), taken off the strains in Hooke's law: σ_r = c ((1 + ν) A − (1 − ν) B/r² − (1 + ν) ε)
/// − (3 + ν) ρ ω² r²/8, c = E/(1 − ν²); the parts stay joined at the same U_w (the drawn
/// interference), so the thermal strains enter through the stresses alone, not through a
/// shortened interference.
fn compatibility_pressure_hot(
    fit: &Fit,
    omega: f64,
    (rho_hub, rho_shaft): (f64, f64),
    (eps_hub, eps_shaft): (f64, f64),
) -> f64 {
    let (r_i, r_f, r_o) = (fit.d_ii / 2.0, fit.d_f / 2.0, fit.d_aa / 2.0);
    let w2 = omega * omega;
    // σ_r = c (1 + ν) A − c (1 − ν) B/r² − c (1 + ν) ε − (3 + ν) ρ ω² r²/8, c = E/(1 − ν²)
    let radial = |e: f64, nu: f64, rho: f64, eps: f64, r: f64| {
        let c = e / (1.0 - nu * nu);
        (
            c * (1.0 + nu),
            -c * (1.0 - nu) / (r * r),
            (3.0 + nu) * rho * w2 * r * r / 8.0 + c * (1.0 + nu) * eps,
        )
    };
    let cubic = |e: f64, nu: f64, rho: f64| -(1.0 - nu * nu) * rho * w2 / (8.0 * e);
    let (eh, nh, es, ns) = (fit.e_hub, fit.poisson_hub, fit.e_shaft, fit.poisson_shaft);
    let mut m = Matrix5::zeros();
    let mut b = Vector5::zeros();
    let (a, bb, body) = radial(eh, nh, rho_hub, eps_hub, r_o);
    (m[(0, 0)], m[(0, 1)], b[0]) = (a, bb, body);
    let (a, bb, body) = radial(eh, nh, rho_hub, eps_hub, r_f);
    (m[(1, 0)], m[(1, 1)], m[(1, 4)], b[1]) = (a, bb, 1.0, body);
    let (a, bb, body) = radial(es, ns, rho_shaft, eps_shaft, r_f);
    (m[(2, 2)], m[(2, 3)], m[(2, 4)], b[2]) = (a, bb, 1.0, body);
    if r_i > 0.0 {
        let (a, bb, body) = radial(es, ns, rho_shaft, eps_shaft, r_i);
        (m[(3, 2)], m[(3, 3)], b[3]) = (a, bb, body);
    } else {
        m[(3, 3)] = 1.0;
    }
    (m[(4, 0)], m[(4, 1)], m[(4, 2)], m[(4, 3)]) = (r_f, 1.0 / r_f, -r_f, -1.0 / r_f);
    let cubic_gap = (cubic(eh, nh, rho_hub) - cubic(es, ns, rho_shaft)) * r_f.powi(3);
    b[4] = fit.effective_interference() / 2.0 - cubic_gap;
    m.lu()
        .solve(&b)
        .expect("the compatibility system is regular")[4]
}

/// A spread of fits: the example, a solid aluminium shaft in a steel hub, a thin-walled hollow
/// steel shaft in a grey-iron hub, a bronze hub on a thick hollow steel shaft.
fn varied_fits() -> Vec<Fit> {
    let ex = example_fit();
    vec![
        ex,
        Fit {
            d_ii: 0.0,
            e_shaft: 70_000.0,
            poisson_shaft: 0.33,
            interference: 0.045,
            ..ex
        },
        Fit {
            d_f: 80.0,
            d_aa: 200.0,
            d_ii: 64.0,
            e_hub: 110_000.0,
            poisson_hub: 0.25,
            interference: 0.09,
            ..ex
        },
        Fit {
            d_f: 40.0,
            d_aa: 52.0,
            d_ii: 12.0,
            e_hub: 115_000.0,
            poisson_hub: 0.34,
            interference: 0.03,
            rz_hub: 2.5,
            rz_shaft: 1.6,
            smoothing: SMOOTHING_2001,
            ..ex
        },
    ]
}

#[test]
fn din_example_pressures() {
    let fit = example_fit();
    let (q_a, q_i) = fit.ratios().unwrap();
    assert_printed(q_a, 0.5263, 1e-4);
    assert_printed(q_i, 0.6, 1e-4);
    assert_printed(fit.compliance().unwrap(), 1.8530e-5, 1e-9);
    assert_printed(fit.effective_interference(), 0.014, 1e-6);
    let max = fit.with_interference(0.059);
    assert_printed(fit.pressure().unwrap(), 15.11, 0.01);
    assert_printed(max.pressure().unwrap(), 59.36, 0.01);
    // the 2001 smoothing
    let old = |f: Fit| {
        Fit {
            smoothing: SMOOTHING_2001,
            ..f
        }
        .pressure()
        .unwrap()
    };
    assert_printed(old(fit), 10.79, 0.01);
    assert_printed(old(max), 55.05, 0.01);
}

#[test]
fn din_example_loads() {
    let fit = example_fit();
    let p_min = fit.pressure().unwrap();
    assert_printed(
        fit.transmissible_torque(p_min).unwrap() / 1000.0,
        178.0,
        0.1,
    );
    assert_printed(fit.transmissible_axial_force(p_min).unwrap(), 7121.0, 1.0);
    assert_printed(
        fit.slip_safety(p_min, 80_000.0, 125.0, 1.2).unwrap(),
        1.85,
        0.01,
    );
    // press-in force at p_max with ν_e 0.08 and 0.15: 14.9 and 28.0 kN
    let max = fit.with_interference(0.059);
    let p_max = max.pressure().unwrap();
    for (nu_e, kn) in [(0.08, 14.9), (0.15, 28.0)] {
        let press = Fit {
            adhesion_axial: nu_e,
            ..max
        };
        assert_printed(
            press.transmissible_axial_force(p_max).unwrap() / 1e3,
            kn,
            0.1,
        );
    }
}

#[test]
fn din_example_stresses_and_limits() {
    let max = example_fit().with_interference(0.059);
    let p_max = max.pressure().unwrap();
    let hub = max.hub_stresses(p_max).unwrap();
    assert_printed(hub.tangential, 104.9, 0.1);
    assert_printed(hub.radial, -59.4, 0.1);
    assert_printed(hub.von_mises, 144.0, 0.1);
    assert_printed(hub.din_equivalent, 142.2, 0.1);
    assert_printed(hub.tangential - hub.radial, 164.2, 0.1); // Tresca
    assert_printed(
        max.shaft_stresses(p_max).unwrap().inner_tangential,
        -185.5,
        0.1,
    );
    assert_printed(max.yield_pressure_hub().unwrap(), 179.5, 0.1);
    assert_printed(max.yield_pressure_shaft().unwrap(), 218.0, 0.1);
    assert_printed(max.plastic_limit_hub().unwrap(), 318.7, 0.1);
    let s = max.yield_safety(p_max).unwrap();
    assert_printed(s.hub, 3.02, 0.01);
    assert_printed(s.shaft, 3.67, 0.01);
    for (p_a, p) in [(0.6, 223.9), (0.7, 268.2), (0.8, 297.3)] {
        assert_printed(max.pressure_partly_plastic_hub(p_a).unwrap(), p, 0.1);
    }
}

#[test]
fn din_example_joining_and_speed() {
    let fit = example_fit();
    let max = fit.with_interference(0.059);
    assert_printed(
        max.joining_temperature(20.0, 0.05, 11e-6).unwrap(),
        218.0,
        1.0,
    );
    let omega = 2000.0 * 2.0 * PI / 60.0;
    let loss = fit
        .centrifugal_loss(omega, STEEL_DENSITY, STEEL_DENSITY)
        .unwrap();
    assert_printed(loss * 1e3, 0.137, 0.001);
    let drop = fit.pressure().unwrap()
        - fit
            .pressure_at_speed(omega, STEEL_DENSITY, STEEL_DENSITY)
            .unwrap();
    assert_printed(drop, 0.15, 0.01);
    let n_ab = fit.opening_speed(STEEL_DENSITY, STEEL_DENSITY).unwrap() * 60.0 / (2.0 * PI);
    assert_printed(n_ab, 20_190.0, 10.0);
}

#[test]
fn din_pressure_matches_a_direct_compatibility_solve() {
    for fit in varied_fits() {
        let direct = compatibility_pressure(&fit, 0.0, STEEL_DENSITY, STEEL_DENSITY);
        assert_rel(fit.pressure().unwrap(), direct, 1e-12);
    }
}

#[test]
fn din_same_material_reduces_to_the_closed_form() {
    for fit in varied_fits() {
        let same = Fit {
            e_shaft: fit.e_hub,
            poisson_shaft: fit.poisson_hub,
            ..fit
        };
        let (qa2, qi2) = (
            (same.d_f / same.d_aa).powi(2),
            (same.d_ii / same.d_f).powi(2),
        );
        let xi = same.effective_interference() / same.d_f;
        let closed = xi * same.e_hub * (1.0 - qa2) * (1.0 - qi2) / (2.0 * (1.0 - qa2 * qi2));
        assert_rel(same.pressure().unwrap(), closed, 1e-12);
        // centrifugal: ΔU_ω = ρ ω² D_F (3 + ν)(D_aA² − D_iI²)/(16 E) and its opening speed
        let (rho, nu, e) = (STEEL_DENSITY, same.poisson_hub, same.e_hub);
        let span = same.d_aa.powi(2) - same.d_ii.powi(2);
        let omega = 700.0;
        let loss = rho * omega * omega * same.d_f * (3.0 + nu) * span / (16.0 * e);
        assert_rel(same.centrifugal_loss(omega, rho, rho).unwrap(), loss, 1e-12);
        let u_w = same.effective_interference();
        let opening = (16.0 * e * u_w / (rho * same.d_f * (3.0 + nu) * span)).sqrt();
        assert_rel(same.opening_speed(rho, rho).unwrap(), opening, 1e-12);
    }
}

#[test]
fn din_rotating_pressure_matches_the_direct_solve_and_vanishes_at_the_opening_speed() {
    // the shafts of different density (aluminium, bronze) take the different-material path
    let densities = [
        (7.85e-9, 7.85e-9),
        (7.85e-9, 2.7e-9),
        (7.2e-9, 7.85e-9),
        (8.8e-9, 7.85e-9),
    ];
    for (fit, (rho_a, rho_i)) in varied_fits().into_iter().zip(densities) {
        let omega_ab = fit.opening_speed(rho_a, rho_i).unwrap();
        assert!(omega_ab.is_finite() && omega_ab > 0.0);
        let omega = 0.5 * omega_ab;
        let direct = compatibility_pressure(&fit, omega, rho_a, rho_i);
        assert_rel(
            fit.pressure_at_speed(omega, rho_a, rho_i).unwrap(),
            direct,
            1e-10,
        );
        assert_rel(direct, 0.75 * fit.pressure().unwrap(), 1e-10); // p falls with ω²
        let at_opening = compatibility_pressure(&fit, omega_ab, rho_a, rho_i);
        assert!(
            at_opening.abs() < 1e-9 * fit.pressure().unwrap(),
            "{at_opening}"
        );
        assert_eq!(
            fit.pressure_at_speed(1.1 * omega_ab, rho_a, rho_i),
            Some(0.0)
        );
    }
    // a hub that grows no more than its (heavier) shaft never opens
    let heavy_shaft = Fit {
        d_aa: 52.0,
        d_ii: 0.0,
        ..example_fit()
    };
    assert_eq!(heavy_shaft.opening_speed(1e-9, 20e-9), Some(f64::INFINITY));
}

/// The parts' expansion coefficients (1/K) for [`varied_fits`]: steel in steel, an aluminium
/// shaft in steel, steel in grey iron, steel in bronze.
const ALPHAS: [(f64, f64); 4] = [
    (11.5e-6, 11.5e-6),
    (11.5e-6, 23.5e-6),
    (10.0e-6, 11.5e-6),
    (18.0e-6, 11.5e-6),
];

#[test]
fn din_same_expansion_warmed_alike_keeps_its_pressure() {
    for fit in varied_fits() {
        // free growth alike: no interference lost, whatever the moduli
        for dt in [-40.0, 60.0, 150.0] {
            let loss = fit.thermal_loss((11.5e-6, dt), (11.5e-6, dt)).unwrap();
            assert_eq!(loss, 0.0);
            let eps = 11.5e-6 * dt;
            let direct = compatibility_pressure_hot(&fit, 0.0, (1e-9, 1e-9), (eps, eps));
            assert_rel(direct, fit.pressure().unwrap(), 1e-10);
        }
        // both losses 0: the pressure at assembly, bit for bit
        assert_eq!(fit.pressure_in_service(0.0, 0.0), fit.pressure());
    }
}

#[test]
fn din_pressure_in_service_matches_the_direct_solve_hot_and_spinning() {
    let densities = [
        (7.85e-9, 7.85e-9),
        (7.85e-9, 2.7e-9),
        (7.2e-9, 7.85e-9),
        (8.8e-9, 7.85e-9),
    ];
    for ((fit, (rho_a, rho_i)), (a_a, a_i)) in varied_fits().into_iter().zip(densities).zip(ALPHAS)
    {
        for (dt_a, dt_i, omega) in [(30.0, 10.0, 0.0), (50.0, 50.0, 400.0), (-20.0, 40.0, 900.0)] {
            let thermal = fit.thermal_loss((a_a, dt_a), (a_i, dt_i)).unwrap();
            assert_rel(thermal, fit.d_f * (a_a * dt_a - a_i * dt_i), 1e-14);
            let spin = fit.centrifugal_loss(omega, rho_a, rho_i).unwrap();
            let direct =
                compatibility_pressure_hot(&fit, omega, (rho_a, rho_i), (a_a * dt_a, a_i * dt_i));
            let p = fit.pressure_in_service(thermal, spin).unwrap();
            if direct > 0.0 {
                assert_rel(p, direct, 1e-10);
            } else {
                assert_eq!(p, 0.0, "open: the direct solve needs a tension {direct}");
            }
        }
    }
}

#[test]
fn din_opening_temperature_is_where_the_direct_solve_reaches_zero() {
    for (fit, (a_a, a_i)) in varied_fits().into_iter().zip(ALPHAS) {
        let p0 = fit.pressure().unwrap();
        let rho = (1e-9, 1e-9);
        for (a_hub, a_shaft) in [(a_a, a_i), (a_a, 0.0), (0.0, a_i)] {
            let Some(dt) = fit.opening_temperature_change(a_hub, a_shaft) else {
                assert_eq!(a_hub, a_shaft, "only equal coefficients never open");
                continue;
            };
            assert_rel(
                dt,
                fit.effective_interference() / (fit.d_f * (a_hub - a_shaft)),
                1e-14,
            );
            let at = |x: f64| compatibility_pressure_hot(&fit, 0.0, rho, (a_hub * x, a_shaft * x));
            assert!(at(dt).abs() < 1e-9 * p0, "{}", at(dt));
            // linear in ΔT: half-way, half the pressure
            assert_rel(at(0.5 * dt), 0.5 * p0, 1e-10);
            let thermal = fit.thermal_loss((a_hub, 1.01 * dt), (a_shaft, 1.01 * dt));
            assert_eq!(fit.pressure_in_service(thermal.unwrap(), 0.0), Some(0.0));
        }
    }
    // the shaft expanding more opens the fit on cooling
    let al_shaft = varied_fits()[1];
    assert!(
        al_shaft
            .opening_temperature_change(11.5e-6, 23.5e-6)
            .unwrap()
            < 0.0
    );
    assert_eq!(al_shaft.opening_temperature_change(11.5e-6, 11.5e-6), None);
}

#[test]
fn din_pressure_in_service_is_quadratic_in_the_speed_to_its_opening() {
    for (fit, (a_a, a_i)) in varied_fits().into_iter().zip(ALPHAS) {
        let (rho_a, rho_i) = (7.85e-9, 2.7e-9);
        let thermal = fit.thermal_loss((a_a, 20.0), (a_i, 15.0)).unwrap();
        let omega_ab = fit.opening_speed_in_service(thermal, rho_a, rho_i).unwrap();
        assert!(omega_ab.is_finite() && omega_ab > 0.0, "{omega_ab}");
        let p = |w: f64| {
            let spin = fit.centrifugal_loss(w, rho_a, rho_i).unwrap();
            fit.pressure_in_service(thermal, spin).unwrap()
        };
        // p(ω) = p(0) (1 − (ω/ω_ab)²)
        for x in [0.25, 0.5, 0.9] {
            assert_rel(p(x * omega_ab), p(0.0) * (1.0 - x * x), 1e-10);
        }
        let eps = (a_a * 20.0, a_i * 15.0);
        let at_opening = compatibility_pressure_hot(&fit, omega_ab, (rho_a, rho_i), eps);
        assert!(at_opening.abs() < 1e-9 * p(0.0), "{at_opening}");
        assert_eq!(p(1.1 * omega_ab), 0.0);
        // without the temperatures, the opening speed at rest
        assert_eq!(
            fit.opening_speed_in_service(0.0, rho_a, rho_i),
            fit.opening_speed(rho_a, rho_i)
        );
        // the temperatures alone open it: no speed left
        let hot = fit.effective_interference() * 1.01;
        assert_eq!(fit.opening_speed_in_service(hot, rho_a, rho_i), Some(0.0));
    }
    let ex = example_fit();
    assert_eq!(ex.thermal_loss((f64::NAN, 1.0), (1e-5, 1.0)), None);
    assert_eq!(ex.pressure_in_service(f64::INFINITY, 0.0), None);
    assert_eq!(
        ex.opening_speed_in_service(f64::NAN, 7.85e-9, 7.85e-9),
        None
    );
}

#[test]
fn din_partly_plastic_hub_reaches_its_limits() {
    for fit in varied_fits() {
        let (q_a, _) = fit.ratios().unwrap();
        let at_q = fit.pressure_partly_plastic_hub(q_a).unwrap();
        assert_rel(at_q, fit.yield_pressure_hub().unwrap(), 1e-12);
        let at_one = fit.pressure_partly_plastic_hub(1.0).unwrap();
        assert_rel(at_one, fit.plastic_limit_hub().unwrap(), 1e-12);
        // typed: −(2/√3) R_eL ln Q_A
        assert_rel(at_one, -2.0 / 3f64.sqrt() * fit.yield_hub * q_a.ln(), 1e-12);
        // the pressure grows with the plastic zone
        let mid = fit.pressure_partly_plastic_hub(0.5 * (q_a + 1.0)).unwrap();
        assert!(at_q < mid && mid < at_one);
        assert_eq!(fit.pressure_partly_plastic_hub(0.99 * q_a), None);
        assert_eq!(fit.pressure_partly_plastic_hub(1.01), None);
    }
}

#[test]
fn din_equivalent_stress_reaches_the_yield_strength_at_the_limit_pressures() {
    let solid = Fit {
        d_ii: 0.0,
        ..example_fit()
    };
    for fit in varied_fits().into_iter().chain([solid]) {
        let p_fa = fit.yield_pressure_hub().unwrap();
        let hub = fit.hub_stresses(p_fa).unwrap();
        assert_rel(hub.din_equivalent, fit.yield_hub, 1e-12);
        let p_fi = fit.yield_pressure_shaft().unwrap();
        let shaft = fit.shaft_stresses(p_fi).unwrap();
        assert_rel(shaft.din_equivalent, fit.yield_shaft, 1e-12);
        // the exact plane-stress von Mises stress from the components
        let vm = |t: f64, r: f64| (t * t + r * r - t * r).sqrt();
        assert_rel(hub.von_mises, vm(hub.tangential, hub.radial), 1e-12);
        assert_rel(
            shaft.von_mises,
            vm(shaft.inner_tangential, shaft.inner_radial),
            1e-12,
        );
        // hub: the exact value exceeds DIN's simplified one (σ_z neglected only by DIN)
        assert!(hub.von_mises >= hub.din_equivalent);
    }
    // the solid shaft's uniform state: exact von Mises p, DIN (√3/2) p; p_FI = 2 R_eL/√3
    let shaft = solid.shaft_stresses(100.0).unwrap();
    assert_eq!(
        (shaft.inner_tangential, shaft.inner_radial),
        (-100.0, -100.0)
    );
    assert_rel(shaft.von_mises, 100.0, 1e-12);
    assert_rel(
        solid.yield_pressure_shaft().unwrap(),
        2.0 * 590.0 / 3f64.sqrt(),
        1e-12,
    );
}

#[test]
fn din_hub_stresses_balance_the_lame_field() {
    // σ_t + σ_r is constant through a Lamé cylinder: bore and outer surface agree
    let fit = example_fit();
    let hub = fit.hub_stresses(50.0).unwrap();
    assert_rel(hub.tangential + hub.radial, hub.outer_tangential, 1e-12);
    let shaft = fit.shaft_stresses(50.0).unwrap();
    assert_rel(shaft.inner_tangential, shaft.joint_tangential - 50.0, 1e-12);
}

#[test]
fn din_slip_safety_reduces_to_the_single_loads() {
    let fit = Fit {
        adhesion_axial: 0.1,
        ..example_fit()
    };
    let p = 30.0;
    let torque_only = fit.slip_safety(p, 100_000.0, 0.0, 1.3).unwrap();
    let m_t = fit.transmissible_torque(p).unwrap();
    assert_rel(torque_only, m_t / (1.3 * 100_000.0), 1e-12);
    let axial_only = fit.slip_safety(p, 0.0, 5000.0, 1.3).unwrap();
    let f_ax = fit.transmissible_axial_force(p).unwrap();
    assert_rel(axial_only, f_ax / (1.3 * 5000.0), 1e-12);
    // combined loads rate lower than either alone
    let both = fit.slip_safety(p, 100_000.0, 5000.0, 1.3).unwrap();
    assert!(both < torque_only.min(axial_only));
    assert_eq!(fit.slip_safety(p, 0.0, 0.0, 1.0), Some(f64::INFINITY));
    assert_eq!(fit.slip_safety(p, 1.0, 0.0, 0.0), None);
}

#[test]
fn din_refuses_invalid_fits() {
    let ex = example_fit();
    let bad = [
        Fit { d_aa: 50.0, ..ex },
        Fit { d_ii: 50.0, ..ex },
        Fit { d_ii: -1.0, ..ex },
        Fit { d_f: 0.0, ..ex },
        Fit { l_f: -20.0, ..ex },
        Fit { e_hub: 0.0, ..ex },
        Fit {
            poisson_shaft: 0.5,
            ..ex
        },
        Fit {
            interference: f64::NAN,
            ..ex
        },
        Fit {
            smoothing: -0.4,
            ..ex
        },
    ];
    for fit in bad {
        assert_eq!(fit.ratios(), None, "{fit:?}");
        assert_eq!(fit.pressure(), None);
        assert_eq!(fit.yield_pressure_hub(), None);
        assert_eq!(fit.transmissible_torque(10.0), None);
        assert_eq!(fit.opening_speed(STEEL_DENSITY, STEEL_DENSITY), None);
    }
    assert_eq!(ex.hub_stresses(-1.0), None);
    assert_eq!(ex.transmissible_torque(f64::NAN), None);
    assert_eq!(
        Fit {
            yield_hub: 0.0,
            ..ex
        }
        .yield_pressure_hub(),
        None
    );
    assert_eq!(ex.joining_temperature(20.0, 0.05, 0.0), None);
    assert_eq!(ex.centrifugal_loss(100.0, 0.0, STEEL_DENSITY), None);
    // a loose fit carries nothing and is open at rest
    let loose = ex.with_interference(0.003);
    assert!(loose.effective_interference() < 0.0);
    assert_eq!(loose.pressure(), Some(0.0));
    assert_eq!(loose.opening_speed(STEEL_DENSITY, STEEL_DENSITY), Some(0.0));
}

// ---------------------------------------------------------------------------------------------
// VDI 2230-1

/// The worked example: ISO 4014 M12×55 8.8 (shank 25 mm, 5 mm free thread) with an ISO 4032
/// nut through two steel plates, l_K 30, d_W 16.63, d_h 13.5, D_A 26.
fn example_bolt() -> Bolt {
    Bolt {
        thread: Thread::coarse("M12").unwrap(),
        head: Head::Hexagon,
        shank: vec![ShankSection {
            length: 25.0,
            diameter: 12.0,
        }],
        free_thread: 5.0,
        e_bolt: 205_000.0,
        e_nut: 205_000.0,
    }
}

fn example_clamp() -> Clamp {
    Clamp {
        l_k: 30.0,
        d_w: 16.63,
        d_h: 13.5,
        d_a: 26.0,
        e_plate: 205_000.0,
    }
}

#[test]
fn vdi_example_resiliences() {
    let s = bolt_resilience(&example_bolt(), Joint::Through).unwrap();
    assert_printed(s.head, 2.588e-7, 1e-10);
    assert_printed(s.shank, 1.0783e-6, 1e-10);
    assert_printed(s.free_thread, 3.199e-7, 1e-10);
    assert_printed(s.engaged_thread, 3.839e-7, 1e-10);
    assert_printed(s.nut, 2.070e-7, 1e-10);
    assert_printed(s.total, 2.2478e-6, 1e-10);
    let c = example_clamp();
    let p = plate_resilience(&c, Joint::Through).unwrap();
    assert_printed(p.tan_phi, 0.4271, 1e-4);
    assert_printed(p.limit_diameter, 29.44, 0.01);
    assert_eq!(p.case, PlateCase::ConeAndSleeve);
    assert_printed(p.delta_p, 7.014e-7, 1e-10);
    let cone = plate_resilience_cone(&c, Joint::Through, p.tan_phi).unwrap();
    assert_printed(cone, 6.860e-7, 1e-10);
    let phi_k = load_factor(s.total, p.delta_p).unwrap();
    assert_printed(phi_k, 0.2378, 1e-4);
    assert_printed(load_factor_introduced(phi_k, 0.5).unwrap(), 0.1189, 1e-4);
}

#[test]
fn vdi_example_forces_and_strength() {
    let bolt = example_bolt();
    let (d_s, d_p) = (2.2478e-6, 7.014e-7);
    let phi_n = load_factor(d_s, d_p).unwrap() * 0.5;
    let (f_a, r_p02) = (10_000.0, 640.0);
    assert_printed(additional_bolt_load(phi_n, f_a), 1189.0, 1.0);
    let f_pa = plate_relief(phi_n, f_a);
    assert_printed(f_pa, 8811.0, 1.0);
    let f_z_um = embedding_guide(6.3, 2, 1).unwrap();
    assert_printed(f_z_um, 9.5, 0.1);
    let f_z = embedding_loss(f_z_um, d_s, d_p).unwrap();
    assert_printed(f_z, 3221.0, 1.0);
    let f_m_min = min_assembly_preload(2000.0, phi_n, f_a, f_z, 0.0);
    assert_printed(f_m_min, 14_032.0, 1.0);
    assert_printed(max_assembly_preload(1.6, f_m_min).unwrap(), 22_451.0, 1.0);
    let t = &bolt.thread;
    let f_m_zul = permissible_assembly_preload(t, t.stress_diameter(), r_p02, 0.12, UTILIZATION);
    let f_m_zul = f_m_zul.unwrap();
    assert_printed(f_m_zul, 43_110.0, 10.0);
    let d_km = friction_diameter(16.63, 13.5);
    assert_printed(d_km, 15.065, 0.001);
    assert_printed(
        tightening_torque(t, f_m_zul, 0.12, 0.12, d_km) / 1e3,
        83.6,
        0.1,
    );
    // tightened to F_M,zul with α_A = 1.6
    let floor = f_m_zul / 1.6;
    // the note subtracted its rounded values (26 944 − 8811 − 3221); the unrounded chain gives
    // 14 911.4
    assert_eq!(residual_clamp_load(26_944.0, 8811.0, 3221.0, 0.0), 14_912.0);
    assert_printed(residual_clamp_load(floor, f_pa, f_z, 0.0), 14_911.0, 1.0);
    assert_printed(
        separation_load(floor - f_z, phi_n).unwrap() / 1e3,
        26.9,
        0.1,
    );
    assert_printed(
        separation_load(f_m_min - f_z, phi_n).unwrap() / 1e3,
        12.27,
        0.01,
    );
    // R8
    let f_s_max = max_bolt_force(f_m_zul, phi_n, f_a, 0.0);
    assert_printed(f_s_max, 44_299.0, 1.0);
    let m_g = thread_torque(t, f_m_zul, 0.12);
    let w = working_stress(f_s_max, m_g, t.stress_diameter(), 0.5, r_p02).unwrap();
    assert_printed(w.tension, 525.7, 0.1);
    assert_printed(w.torsion, 203.8, 0.1);
    assert_printed(w.equivalent, 554.5, 0.1);
    assert_printed(w.safety, 1.15, 0.01);
    // R9
    let sigma_a = stress_amplitude(additional_bolt_load(phi_n, f_a), 0.0, t.stress_area());
    let sigma_a = sigma_a.unwrap();
    assert_printed(sigma_a, 7.06, 0.01);
    let asv = endurance_rolled_before(12.0).unwrap();
    assert_printed(asv, 48.9, 0.1);
    assert_printed(fatigue_safety(asv, sigma_a).unwrap(), 6.9, 0.1);
    let f_sm = f_m_zul + additional_bolt_load(phi_n, f_a) / 2.0;
    let f_02 = r_p02 * t.stress_area();
    assert_printed(f_sm, 43_704.0, 1.0);
    assert_printed(f_02, 53_931.0, 1.0);
    let asg = endurance_rolled_after(12.0, f_sm, f_02).unwrap();
    assert_printed(asg, 58.1, 0.1);
    assert_printed(fatigue_safety(asg, sigma_a).unwrap(), 8.2, 0.1);
    // R10
    let a_p = bearing_area(16.63, 13.5).unwrap();
    assert_printed(a_p, 74.07, 0.01);
    assert_printed(surface_pressure(f_m_zul, a_p).unwrap(), 582.0, 1.0);
    let service = f_m_zul - f_z + additional_bolt_load(phi_n, f_a);
    assert_printed(surface_pressure(service, a_p).unwrap(), 555.0, 1.0);
    assert!(surface_pressure_safety(480.0, 582.0).unwrap() < 1.0);
}

/// F_M,zul and M_A of a coarse 8.8 bolt at µ_G = µ_K = 0.12 computed here from the R7/R13
/// formulas with d2, d3 typed from ISO 724 (not from the thread table).
fn hand_table(p: f64, d2: f64, d3: f64, d_w: f64, d_h: f64) -> (f64, f64) {
    let d0 = (d2 + d3) / 2.0;
    let a0 = PI / 4.0 * d0 * d0;
    let torsion = 1.5 * d2 / d0 * (p / (PI * d2) + 1.155 * 0.12);
    let f = 0.9 * 640.0 * a0 / (1.0 + 3.0 * torsion * torsion).sqrt();
    let m = f * (0.16 * p + 0.58 * d2 * 0.12 + 0.12 * (d_w + d_h) / 4.0);
    (f, m)
}

#[test]
fn vdi_table_a1_values_for_m10_and_m12() {
    let r_p02 = PropertyClass::of("8.8", 12.0).unwrap().r_p02;
    // (name, P, d2, d3 from ISO 724; d_W of ISO 4014 grade A, d_h medium of ISO 273)
    for (name, p, d2, d3, d_w, d_h) in [
        ("M10", 1.5, 9.026, 8.160, 14.63, 11.0),
        ("M12", 1.75, 10.863, 9.853, 16.63, 13.5),
    ] {
        let t = Thread::coarse(name).unwrap();
        let f = permissible_assembly_preload(&t, t.stress_diameter(), r_p02, 0.12, 0.9).unwrap();
        let m = tightening_torque(&t, f, 0.12, 0.12, friction_diameter(d_w, d_h));
        let (f_hand, m_hand) = hand_table(p, d2, d3, d_w, d_h);
        assert_rel(f, f_hand, 2e-4);
        assert_rel(m, m_hand, 2e-4);
    }
    // and the numbers worked out by hand, the M12 ones as VDI 2230-1 Table A1 prints them
    let m10 = Thread::coarse("M10").unwrap();
    let f10 = permissible_assembly_preload(&m10, m10.stress_diameter(), r_p02, 0.12, 0.9);
    assert_printed(f10.unwrap() / 1e3, 29.6, 0.1);
    let m_a10 = tightening_torque(
        &m10,
        f10.unwrap(),
        0.12,
        0.12,
        friction_diameter(14.63, 11.0),
    );
    assert_printed(m_a10 / 1e3, 48.5, 0.1);
    let m12 = Thread::coarse("M12").unwrap();
    let f12 = permissible_assembly_preload(&m12, m12.stress_diameter(), r_p02, 0.12, 0.9);
    let m_a12 = tightening_torque(
        &m12,
        f12.unwrap(),
        0.12,
        0.12,
        friction_diameter(16.63, 13.5),
    );
    assert_rel(f12.unwrap(), 43_000.0, 0.01);
    assert_rel(m_a12, 84_000.0, 0.01);
}

#[test]
fn vdi_permissible_preload_is_the_plastic_torsion_von_mises_limit() {
    // at F_M,zul: √(σ² + 3τ²) = ν R_p0.2 with τ = M_G/(π d_0³/12), whatever the thread
    for (t, mu) in [
        (Thread::coarse("M8").unwrap(), 0.08),
        (Thread::coarse("M24").unwrap(), 0.14),
        (Thread::fine(16.0, 1.5).unwrap(), 0.2),
    ] {
        let d0 = 0.9 * t.stress_diameter(); // a necked-down bolt
        let f = permissible_assembly_preload(&t, d0, 940.0, mu, 0.9).unwrap();
        let d2 = t.d - 0.64952 * t.pitch;
        let m_g = f * d2 / 2.0 * (t.pitch / (PI * d2) + 1.155 * mu);
        let sigma = f / (PI * d0 * d0 / 4.0);
        let tau = m_g / (PI * d0.powi(3) / 12.0);
        assert_rel((sigma * sigma + 3.0 * tau * tau).sqrt(), 0.9 * 940.0, 1e-12);
    }
    let t = Thread::coarse("M12").unwrap();
    assert_eq!(
        permissible_assembly_preload(&t, 10.0, 640.0, 0.12, 1.2),
        None
    );
    assert_eq!(
        permissible_assembly_preload(&t, 0.0, 640.0, 0.12, 0.9),
        None
    );
    assert_eq!(
        permissible_assembly_preload(&t, 10.0, 640.0, -0.1, 0.9),
        None
    );
}

#[test]
fn vdi_plate_resilience_is_continuous_across_the_cases() {
    for joint in [Joint::Through, Joint::Tapped] {
        let c = example_clamp();
        let tan_phi = 0.45;
        let limit = c.d_w + joint.w() * c.l_k * tan_phi;
        let at_limit = Clamp { d_a: limit, ..c };
        let cone = plate_resilience_cone(&at_limit, joint, tan_phi).unwrap();
        let joined = plate_resilience_cone_sleeve(&at_limit, joint, tan_phi).unwrap();
        assert_rel(joined, cone, 1e-12);
        let at_dw = Clamp { d_a: c.d_w, ..c };
        let sleeve = plate_resilience_sleeve(&at_dw).unwrap();
        let joined = plate_resilience_cone_sleeve(&at_dw, joint, tan_phi).unwrap();
        assert_rel(joined, sleeve, 1e-12);
        // typed sleeve: l_K/(E π/4 (d_W² − d_h²))
        let typed = c.l_k / (c.e_plate * PI / 4.0 * (c.d_w * c.d_w - c.d_h * c.d_h));
        assert_rel(sleeve, typed, 1e-12);
        // a sleeve stiffens as it widens toward the cone
        let wider = plate_resilience_cone_sleeve(&Clamp { d_a: 22.0, ..c }, joint, tan_phi);
        assert!(cone < wider.unwrap() && wider.unwrap() < sleeve);
        assert_eq!(
            plate_resilience_cone_sleeve(
                &Clamp {
                    d_a: 1.1 * limit,
                    ..c
                },
                joint,
                tan_phi
            ),
            None
        );
    }
}

#[test]
fn vdi_plate_case_follows_the_outer_diameter() {
    let c = example_clamp();
    let wide = plate_resilience(&Clamp { d_a: 60.0, ..c }, Joint::Through).unwrap();
    assert_eq!(wide.case, PlateCase::Cone);
    let narrow = plate_resilience(&Clamp { d_a: 15.0, ..c }, Joint::Through).unwrap();
    assert_eq!(narrow.case, PlateCase::Sleeve);
    let typed = 30.0 / (205_000.0 * PI / 4.0 * (15.0 * 15.0 - 13.5 * 13.5));
    assert_rel(narrow.delta_p, typed, 1e-12);
    // the cone angles, typed: DSV 0.362 + 0.032 ln(β_L/2) + 0.153 ln y, ESV with w = 2
    let (beta, y): (f64, f64) = (30.0 / 16.63, 60.0 / 16.63);
    let dsv = 0.362 + 0.032 * (beta / 2.0).ln() + 0.153 * y.ln();
    assert_rel(wide.tan_phi, dsv, 1e-12);
    let tapped = plate_resilience(&Clamp { d_a: 60.0, ..c }, Joint::Tapped).unwrap();
    assert_rel(
        tapped.tan_phi,
        0.348 + 0.013 * beta.ln() + 0.193 * y.ln(),
        1e-12,
    );
    assert_rel(
        tapped.limit_diameter,
        16.63 + 2.0 * 30.0 * tapped.tan_phi,
        1e-12,
    );
    assert_eq!(
        plate_resilience(&Clamp { d_h: 17.0, ..c }, Joint::Through),
        None
    );
    assert_eq!(
        plate_resilience(&Clamp { d_a: 13.0, ..c }, Joint::Through),
        None
    );
    assert_eq!(
        plate_resilience(&Clamp { l_k: 0.0, ..c }, Joint::Through),
        None
    );
}

#[test]
fn vdi_bolt_resilience_parts() {
    let bolt = example_bolt();
    let through = bolt_resilience(&bolt, Joint::Through).unwrap();
    let tapped = bolt_resilience(&bolt, Joint::Tapped).unwrap();
    // only the nut/tapped term differs: 0.4 d against 0.33 d over E A_N
    let a_n = PI / 4.0 * 144.0;
    assert_rel(through.nut, 0.4 * 12.0 / (205_000.0 * a_n), 1e-12);
    assert_rel(tapped.nut, 0.33 * 12.0 / (205_000.0 * a_n), 1e-12);
    assert_rel(
        through.total - tapped.total,
        0.07 * 12.0 / (205_000.0 * a_n),
        1e-9,
    );
    let socket = bolt_resilience(
        &Bolt {
            head: Head::Socket,
            ..bolt.clone()
        },
        Joint::Through,
    );
    assert_rel(socket.unwrap().head, 0.4 * 12.0 / (205_000.0 * a_n), 1e-12);
    // two shank sections in series: a 10 mm waist of 15 mm
    let waisted = Bolt {
        shank: vec![
            ShankSection {
                length: 10.0,
                diameter: 12.0,
            },
            ShankSection {
                length: 15.0,
                diameter: 9.0,
            },
        ],
        ..bolt.clone()
    };
    let shank = bolt_resilience(&waisted, Joint::Through).unwrap().shank;
    let typed = 10.0 / (205_000.0 * a_n) + 15.0 / (205_000.0 * PI / 4.0 * 81.0);
    assert_rel(shank, typed, 1e-12);
    let bad = Bolt {
        shank: vec![ShankSection {
            length: 5.0,
            diameter: 0.0,
        }],
        ..bolt.clone()
    };
    assert_eq!(bolt_resilience(&bad, Joint::Through), None);
    assert_eq!(
        bolt_resilience(&Bolt { e_nut: 0.0, ..bolt }, Joint::Through),
        None
    );
}

#[test]
fn vdi_load_factor_embedding_and_opening() {
    assert_eq!(load_factor(1e-6, 1e-6), Some(0.5));
    assert_eq!(load_factor(0.0, 1e-6), None);
    assert_eq!(load_factor_introduced(0.3, 1.2), None);
    // F_SA + F_PA = F_A
    let phi_n = 0.17;
    assert_rel(
        additional_bolt_load(phi_n, 7000.0) + plate_relief(phi_n, 7000.0),
        7000.0,
        1e-15,
    );
    // at the opening load the plates are relieved by all of the preload
    let f_v = 20_000.0;
    let opening = separation_load(f_v, phi_n).unwrap();
    assert_rel(plate_relief(phi_n, opening), f_v, 1e-12);
    assert_eq!(separation_load(f_v, 1.0), None);
    // F_KR at F_M,min is the required clamp load
    let f_m_min = min_assembly_preload(3000.0, phi_n, 7000.0, 1500.0, 200.0);
    let f_kr = residual_clamp_load(f_m_min, plate_relief(phi_n, 7000.0), 1500.0, 200.0);
    assert_rel(f_kr, 3000.0, 1e-12);
    assert_eq!(max_assembly_preload(0.9, f_m_min), None);
    // f_Z guide: the three roughness classes
    assert_eq!(embedding_guide(5.0, 1, 0), Some(5.5));
    assert_eq!(embedding_guide(10.0, 2, 1), Some(11.0));
    assert_eq!(embedding_guide(100.0, 2, 2), Some(17.0));
    assert_eq!(embedding_guide(160.0, 2, 1), None);
    assert_eq!(embedding_guide(-1.0, 2, 1), None);
    assert_rel(
        embedding_loss(10.0, 2e-6, 3e-6).unwrap(),
        0.01 / 5e-6,
        1e-12,
    );
}

#[test]
fn vdi_fatigue_and_pressure_limits() {
    // SG tends to SV as the mean load reaches the proof load; rolling after hardening helps
    let asv = endurance_rolled_before(16.0).unwrap();
    assert_rel(asv, 0.85 * (150.0 / 16.0 + 45.0), 1e-12);
    assert_rel(
        endurance_rolled_after(16.0, 0.999_999, 1.0).unwrap(),
        asv,
        1e-5,
    );
    assert!(endurance_rolled_after(16.0, 0.5, 1.0).unwrap() > asv);
    assert_eq!(endurance_rolled_after(16.0, 1.0, 1.0), None);
    assert_eq!(endurance_rolled_before(0.0), None);
    assert_eq!(stress_amplitude(3000.0, 1000.0, 100.0), Some(10.0));
    assert_eq!(bearing_area(10.0, 11.0), None);
    assert_rel(bearing_area(2.0, 0.0).unwrap(), PI, 1e-15);
    assert_eq!(surface_pressure(100.0, 0.0), None);
    assert!(working_stress(1e4, 1e4, 10.0, 1.5, 640.0).is_none());
}

#[test]
fn safety_factors() {
    assert_eq!(safety(3.0, 2.0), Some(1.5));
    assert_eq!(safety(3.0, 0.0), Some(f64::INFINITY));
    assert_eq!(safety(0.0, 0.0), None);
    assert_eq!(safety(-1.0, 2.0), None);
    assert_eq!(safety(1.0, f64::NAN), None);
}

// ---------------------------------------------------------------------------------------------
// Threads and property classes

#[test]
fn thread_dimensions_match_iso_724() {
    // (name, P, d2, d3, A_S) typed from ISO 724 and ISO 898-1
    let table = [
        ("M3", 0.5, 2.675, 2.387, 5.03),
        ("M8", 1.25, 7.188, 6.466, 36.6),
        ("M10", 1.5, 9.026, 8.160, 58.0),
        ("M12", 1.75, 10.863, 9.853, 84.3),
        ("M16", 2.0, 14.701, 13.546, 157.0),
        ("M20", 2.5, 18.376, 16.933, 245.0),
        ("M24", 3.0, 22.051, 20.319, 353.0),
        ("M36", 4.0, 33.402, 31.093, 817.0),
        ("M64", 6.0, 60.103, 56.639, 2676.0),
    ];
    for (name, p, d2, d3, a_s) in table {
        let t = Thread::coarse(name).unwrap();
        assert_eq!(t.pitch, p, "{name}");
        assert_printed(t.d2(), d2, 0.001);
        assert_printed(t.d3(), d3, 0.001);
        let digits = if a_s < 10.0 {
            0.01
        } else if a_s < 100.0 {
            0.1
        } else {
            1.0
        };
        assert_printed(t.stress_area(), a_s, digits);
        assert_eq!(Thread::coarse_of(t.d), Some(t));
    }
    let m12 = Thread::coarse("M12").unwrap();
    assert_rel(m12.core_area(), PI / 4.0 * 9.853f64.powi(2), 1e-4);
    assert_rel(m12.nominal_area(), 113.097, 1e-5);
    // fine threads of ISO 724
    for (d, p, a_s) in [(10.0, 1.25, 61.2), (12.0, 1.5, 88.1), (16.0, 1.5, 167.0)] {
        let digits = if a_s < 100.0 { 0.1 } else { 1.0 };
        assert_printed(Thread::fine(d, p).unwrap().stress_area(), a_s, digits);
    }
}

#[test]
fn thread_lookup_refuses_unknown_names() {
    assert_eq!(Thread::coarse(" m3.5 "), Thread::coarse_of(3.5));
    assert_eq!(Thread::coarse("M3.5").unwrap().pitch, 0.6);
    for name in ["M13", "M12x1.5", "12", "M", "", "X12", "M-12"] {
        assert_eq!(Thread::coarse(name), None, "{name}");
    }
    assert_eq!(Thread::coarse_of(2.5), None);
    assert_eq!(Thread::fine(12.0, 0.0), None);
    assert_eq!(Thread::fine(1.0, 1.0), None); // d3 < 0
    assert_eq!(Thread::fine(f64::NAN, 1.0), None);
}

#[test]
fn property_classes_of_iso_898_1() {
    let at = |name: &str, d: f64| PropertyClass::of(name, d).map(|c| (c.r_m, c.r_p02));
    assert_eq!(at("4.6", 12.0), Some((400.0, 240.0)));
    assert_eq!(at("5.6", 12.0), Some((500.0, 300.0)));
    assert_eq!(at("8.8", 16.0), Some((800.0, 640.0)));
    assert_eq!(at("8.8", 20.0), Some((830.0, 660.0)));
    assert_eq!(at("9.8", 10.0), Some((900.0, 720.0)));
    assert_eq!(at("9.8", 20.0), None);
    assert_eq!(at("10.9", 24.0), Some((1040.0, 940.0)));
    assert_eq!(at("12.9", 8.0), Some((1220.0, 1100.0)));
    assert_eq!(PropertyClass::of("12.9", 8.0).unwrap().name, "12.9");
    for name in ["7.7", "8,8", "", "88"] {
        assert_eq!(at(name, 12.0), None, "{name}");
    }
    assert_eq!(at("8.8", 48.0), None);
}

/// ISO 261's pitches: the series, at most the coarse pitch of the size.
#[test]
fn a_thread_pitch_is_one_of_iso_261s_and_at_most_the_coarse_one() {
    for (d, p, ok) in [
        (12.0, 1.75, true),
        (12.0, 1.5, true),
        (12.0, 1.25, true),
        (12.0, 1.37, false), // not in the series
        (12.0, 2.0, false),  // coarser than M12's 1.75
        (16.0, 1.5, true),
        (64.0, 6.0, true),
        (11.0, 1.0, true), // a size outside the coarse table: at most d/4
        (11.0, 3.0, false),
    ] {
        let t = Thread::fine(d, p).unwrap();
        assert_eq!(t.iso_pitch(), ok, "M{d}x{p}");
    }
}

/// One Jenkins element (no density, the whole mass at η = 1): the
/// elastic-perfectly-plastic loop, F_a = A k min(a, φ) and
/// D = 4 A k φ (a − φ)₊ (the parallelogram of yield force kφ A).
#[test]
fn a_single_jenkins_element_gives_the_elastic_plastic_parallelogram() {
    let j = UniformJoint {
        stiffness: 5000.0,
        slip_range: 2e-3,
        c: 0.0,
        chi: 0.0,
        masses: vec![(1.0, 1.0)],
        area: 60.0,
    };
    let f_y = 60.0 * 5000.0 * 2e-3;
    assert_rel(j.force_amplitude(1e-3).unwrap(), f_y / 2.0, 1e-14);
    assert_eq!(j.dissipation(1e-3), Some(0.0));
    assert_rel(j.force_amplitude(5e-3).unwrap(), f_y, 1e-14);
    assert_rel(j.dissipation(5e-3).unwrap(), 4.0 * f_y * 3e-3, 1e-14);
    assert_rel(j.secant_stiffness(5e-3).unwrap(), f_y / 5e-3, 1e-14);
    assert_rel(
        j.loss_factor(5e-3).unwrap(),
        4.0 * f_y * 3e-3 / (PI * f_y * 5e-3),
        1e-14,
    );
    assert_eq!(j.force_amplitude(0.0), None);
    assert_eq!(j.force_amplitude(-1e-3), None);
}

/// Masing's rule: a loop from −a to a of a backbone f has the area
/// D = 4 (2 ∫₀ᵃ f du − a f(a)); the Iwan density with a spike, below and
/// beyond the slip range, against that integral by Simpson's rule.
#[test]
fn the_iwan_loop_is_masing_s_rule_on_its_backbone() {
    for chi in [-0.5, 0.0, 0.7] {
        let j = UniformJoint {
            stiffness: 4969.0,
            slip_range: 1.8e-3,
            c: 0.8,
            chi,
            masses: vec![(1.0, 0.2), (1.0, 0.0)],
            area: 60.0,
        };
        for x in [0.05, 0.4, 1.0, 2.5] {
            let a = x * j.slip_range;
            let n = 20000;
            let h = a / n as f64;
            let f = |u: f64| {
                if u == 0.0 {
                    0.0
                } else {
                    j.force_amplitude(u).unwrap()
                }
            };
            let simpson: f64 = (0..=n)
                .map(|k| {
                    let w = if k == 0 || k == n {
                        1.0
                    } else if k % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    w * f(k as f64 * h)
                })
                .sum::<f64>()
                * h
                / 3.0;
            let masing = 4.0 * (2.0 * simpson - a * f(a));
            assert_rel(j.dissipation(a).unwrap(), masing, 1e-7);
        }
    }
}
