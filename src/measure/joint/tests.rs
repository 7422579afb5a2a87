use super::*;
use crate::physics::contact::tangential::SlipState;
use crate::physics::contact::TangentialLaw;

/// A spring's states along a path of u_T at constant p_N, from the real
/// tangential law (committed state carried from step to step).
fn walk(law: &TangentialLaw, p_n: f64, path: &[f64]) -> Vec<PointState> {
    let mut states = vec![PointState::default()];
    for &u_t in path {
        let prev = *states.last().unwrap();
        let ev = law.eval(p_n, 0.0, u_t, &prev.slip);
        states.push(PointState {
            slip: ev.state,
            p_t: ev.p_t,
            u_t,
            mu_f: ev.mu_f,
            ..Default::default()
        });
    }
    states
}

/// D and W of a point at constant pressure `p_n` along its states.
fn energies(law: &TangentialLaw, p_n: f64, area: f64, states: &[PointState]) -> (f64, f64) {
    states.windows(2).fold((0.0, 0.0), |(d, w), s| {
        let (dd, dw) = point_energy(Some(law), area, (p_n, &s[0]), (p_n, &s[1]));
        (d + dd, w + dw)
    })
}

#[test]
fn work_minus_dissipation_is_the_stored_elastic_energy_on_any_path() {
    // slip hardening, micro-slip and the friction cap all visited
    let law = TangentialLaw::new(0.9, 0.5, 0.05, 0.2, 0.6, 275.0, 0.625).unwrap();
    let p_n = 150.0;
    let k = law.elastic_stiffness(p_n).0;
    let area = 2.5;
    let mut path = Vec::new();
    for (a, n) in [
        (0.0, 0usize),
        (0.03, 17),
        (-0.02, 23),
        (0.045, 31),
        (0.001, 9),
    ] {
        let from = path.last().copied().unwrap_or(0.0);
        path.extend((1..=n).map(|i| from + (a - from) * i as f64 / n as f64));
    }
    let states = walk(&law, p_n, &path);
    let (d, w) = energies(&law, p_n, area, &states);
    let last = states.last().unwrap();
    let stored = area * last.p_t * last.p_t / (2.0 * k);
    assert!(d > 0.0, "the path slips: D = {d}");
    assert!(
        (w - d - stored).abs() <= 1e-12 * w.abs().max(d),
        "W {w} − D {d} = {} vs stored {stored}",
        w - d
    );
}

#[test]
fn an_elastic_perfectly_plastic_loop_dissipates_the_limit_times_the_slip() {
    // p_T = k (u_T − u_p) with |p_T| ≤ Y: a loop through the kinks that
    // returns the spring to its start (u_T = u_p = p_T = 0)
    let (k, y, area): (f64, f64, f64) = (40.0, 2.0, 1.5);
    let mut states = vec![PointState::default()];
    let mut up: f64 = 0.0;
    let mut slip: f64 = 0.0;
    for u_t in [0.05, 0.1, 0.0, -0.1, 0.0, 0.05, 0.0] {
        let trial = k * (u_t - up);
        if trial.abs() > y {
            let new = u_t - y * trial.signum() / k;
            slip += (new - up).abs();
            up = new;
        }
        states.push(PointState {
            slip: SlipState {
                u_p: up,
                kappa: slip,
                ..Default::default()
            },
            p_t: k * (u_t - up),
            u_t,
            mu_f: 0.0,
            ..Default::default()
        });
    }
    let end = states.last().unwrap();
    assert!(end.u_t == 0.0 && end.slip.u_p.abs() < 1e-15 && end.p_t.abs() < 1e-12);
    // the isotropic law's slider: its work depends on the states only
    let law = TangentialLaw::new(0.9, 0.5, 1.0, 0.2, 1.0, 0.0, 0.625).unwrap();
    let (d, w) = energies(&law, 1.0, area, &states);
    let expected = area * y * slip;
    assert!(slip > 0.1, "{slip}");
    assert!(
        (d - expected).abs() <= 1e-12 * expected,
        "{d} vs {expected}"
    );
    assert!((w - d).abs() <= 1e-12 * d, "W {w} vs D {d}");
}

#[test]
fn aggregation_reports_the_joint_convention_and_the_measures() {
    let s = |area, p_n, u_n, u_t, p_t, status| PointSample {
        hoop: None,
        space: None,
        area,
        p_n,
        u_n,
        u_t,
        p_t,
        status,
    };
    // thickness 2: measures are areas / 2
    let samples = [
        s(2.0, 100.0, 0.01, -0.002, -15.0, Status::Stick),
        s(4.0, 50.0, 0.005, -0.004, -10.0, Status::MicroSlip),
        s(1.0, 0.0, -0.001, -0.006, 0.0, Status::Open),
        s(3.0, 20.0, 0.002, -0.001, -4.0, Status::MacroSlip),
        s(6.0, 30.0, 0.003, 0.0, 0.0, Status::Closed),
    ];
    let totals = JointTotals {
        dissipation: 3.5,
        work: 4.0,
    };
    let m = aggregate(samples.iter().copied(), 0.5, totals);
    let area: f64 = samples.iter().map(|p| p.area).sum();
    let sum = |f: &dyn Fn(&PointSample) -> f64| samples.iter().map(|p| p.area * f(p)).sum::<f64>();
    assert_eq!(m.normal_force, sum(&|p| p.p_n));
    // A moved in +t relative to B: internal u_T, p_T < 0, joint values > 0
    assert!(m.tangential_force > 0.0 && m.mean_slip > 0.0);
    assert_eq!(m.tangential_force, -sum(&|p| p.p_t));
    assert!((m.mean_slip + sum(&|p| p.u_t) / area).abs() < 1e-18);
    assert!((m.mean_approach - sum(&|p| p.u_n) / area).abs() < 1e-18);
    assert_eq!(
        [m.open, m.closed, m.stick, m.micro_slip, m.macro_slip],
        [0.5, 3.0, 1.0, 2.0, 1.5]
    );
    assert_eq!((m.dissipation, m.work), (3.5, 4.0));
    assert_eq!(JointMeasures::unpack(&m.pack()), m);
}

fn marks(v: &[Option<f64>]) -> Vec<Option<Vec<f64>>> {
    // two histories: a constant preload and the given tangential factor
    v.iter().map(|x| x.map(|x| vec![1.0, x])).collect()
}

#[test]
fn cycles_close_where_the_history_values_return() {
    let (a, b, c) = (Some(0.0), Some(1.0), Some(-1.0));
    // out and back: one cycle
    assert_eq!(cycle_windows(&marks(&[a, None, b, None, a])), vec![(0, 4)]);
    // a hold is no cycle
    assert!(cycle_windows(&marks(&[a, None, a, a])).is_empty());
    // the latest equal breakpoint decides: a hold at B, then back to A
    assert_eq!(cycle_windows(&marks(&[a, b, b, a])), vec![(0, 3)]);
    assert_eq!(
        cycle_windows(&marks(&[a, b, a, b, a])),
        vec![(0, 2), (2, 4)]
    );
    // a full swing 0 → +1 → −1 → 0, twice
    assert_eq!(
        cycle_windows(&marks(&[a, b, c, a, b, c, a])),
        vec![(0, 3), (3, 6)]
    );
    // a cycle never reaches back before the end of the previous one
    assert_eq!(cycle_windows(&marks(&[b, a, b, c, a])), vec![(0, 2)]);
    // within 1e-12 of the history's magnitude: equal; beyond: not
    let near = |e: f64| {
        vec![
            Some(vec![2.0, 0.0]),
            Some(vec![2.0, 3.0]),
            Some(vec![2.0, e]),
        ]
    };
    assert_eq!(cycle_windows(&near(1e-12)), vec![(0, 2)]);
    assert!(cycle_windows(&near(1e-9)).is_empty());
    // no histories: every value list empty, never a cycle
    assert!(cycle_windows(&[Some(vec![]), Some(vec![]), None, Some(vec![])]).is_empty());
    assert!(cycle_windows(&[]).is_empty());
}

#[test]
fn a_cycle_reports_its_dissipation_stiffness_and_ranges() {
    // a parallelogram loop: stick with stiffness k up to ±f, slip at ±f
    let (k, f, d) = (5000.0, 40.0, 0.02);
    let pts = [
        (0.0, 0.0),
        (f / k, f),
        (d, f),
        (d - 2.0 * f / k, -f),
        (-d, -f),
        (-d + 2.0 * f / k, f),
        (0.0, f),
    ];
    // energies: any increasing synthetic totals
    let rows: Vec<(f64, JointMeasures)> = pts
        .iter()
        .enumerate()
        .map(|(i, &(u, force))| {
            let jm = JointMeasures {
                tangential_force: force,
                mean_slip: u,
                dissipation: 7.0 + (i * i) as f64,
                work: 8.0 + (i * i * i) as f64,
                ..JointMeasures::default()
            };
            (i as f64 * 0.5, jm)
        })
        .collect();
    let c = cycle_of(&rows, (1, 5));
    assert_eq!((c.start_increment, c.end_increment), (2, 6));
    assert_eq!((c.start_time, c.end_time), (0.5, 2.5));
    assert_eq!(c.dissipation, rows[5].1.dissipation - rows[1].1.dissipation);
    assert_eq!(c.work, rows[5].1.work - rows[1].1.work);
    assert_eq!(c.force_range, [-f, f]);
    assert_eq!(c.slip_range, [-d, d]);
    // tip to tip: the largest force at the largest slip, the smallest at the smallest
    let secant = 2.0 * f / (2.0 * d);
    assert!((c.secant_stiffness.unwrap() - secant).abs() <= 1e-12 * secant.abs());
    // a span where the force never changes slip: no stiffness
    let flat = cycle_of(&rows[..2], (0, 0));
    assert_eq!(flat.secant_stiffness, None);
}

/// Two increments at the same prescribed extreme force, held by
/// equilibrium only to the Newton tolerance, are one tip: the one of the
/// larger slip at the top (the smaller at the bottom), whichever force
/// round-off made larger.
#[test]
fn forces_equal_to_round_off_are_one_tip_of_the_loop() {
    let (f, k) = (72.0, 2.0e5);
    let row = |force: f64, u: f64| {
        (
            0.0,
            JointMeasures {
                tangential_force: force,
                mean_slip: u,
                ..JointMeasures::default()
            },
        )
    };
    for (eps_a, eps_b) in [(0.0, -2.7e-6), (-2.7e-6, 0.0)] {
        // tip to tip: the window starts and ends at +f, the end slid further
        let rows = [
            row(f + eps_a, 3.50e-4),
            row(0.0, 0.0),
            row(-f, -3.30e-4),
            row(0.0, -1.0e-5),
            row(f + eps_b, 3.39e-4),
        ];
        let c = cycle_of(&rows, (0, 4));
        assert_eq!(c.tip_slip, [-3.30e-4, 3.50e-4], "{eps_a} {eps_b}");
        let secant = (rows[0].1.tangential_force + f) / (3.50e-4 + 3.30e-4);
        assert!((c.secant_stiffness.unwrap() - secant).abs() < 1e-9 * k);
    }
    // a force short of the extreme by more than the tie is not a tip
    let rows = [row(f - 1e-3, 5.0e-4), row(-f, -3.30e-4), row(f, 3.39e-4)];
    assert_eq!(cycle_of(&rows, (0, 2)).tip_slip, [-3.30e-4, 3.39e-4]);
}

#[test]
fn a_parallelogram_loop_has_the_closed_form_stored_energy_and_loss_factor() {
    // from the tip (d, f) around the loop and back; stick slope k, slip at ±f
    let (k, f, d) = (5000.0, 40.0, 0.02);
    let pts = [
        (d, f),
        (d - f / k, 0.0),
        (d - 2.0 * f / k, -f),
        (0.0, -f),
        (-d, -f),
        (-d + 2.0 * f / k, f),
        (0.0, f),
        (d, f),
    ];
    // D accumulated as the trapezoid of F dū (a spring's loop: D = W)
    let mut diss = 0.0;
    let rows: Vec<(f64, JointMeasures)> = pts
        .iter()
        .enumerate()
        .map(|(i, &(u, force))| {
            if i > 0 {
                let (u0, f0) = pts[i - 1];
                diss += 0.5 * (f0 + force) * (u - u0);
            }
            let jm = JointMeasures {
                tangential_force: force,
                mean_slip: u,
                dissipation: diss,
                work: diss,
                ..JointMeasures::default()
            };
            (i as f64, jm)
        })
        .collect();
    let c = cycle_of(&rows, (0, pts.len() - 1));
    // the parallelogram's area 4 f (d − f/k) = 4 · 40 · 0.012 = 1.92 N·mm
    assert!((c.dissipation - 1.92).abs() < 1e-12, "{c:?}");
    // tips (−d, −f) and (d, f): F_a = f, u_a = d, U = ½ f d = 0.4 N·mm
    assert_eq!(c.tip_slip, [-d, d]);
    assert_eq!((c.force_amplitude(), c.slip_amplitude()), (f, d));
    assert!((c.stored_energy() - 0.4).abs() < 1e-15, "{c:?}");
    // η = D / (2π U) = 4 (d − f/k) / (π d) = 2.4 / π
    let eta = c.loss_factor().unwrap();
    assert!((eta - 2.4 / std::f64::consts::PI).abs() < 1e-12, "{eta}");
    // no slip between the tips: no stored energy, no loss factor
    let mut rigid = rows.clone();
    for r in &mut rigid {
        r.1.mean_slip = 0.0;
    }
    let c = cycle_of(&rigid, (0, pts.len() - 1));
    assert_eq!((c.stored_energy(), c.loss_factor()), (0.0, None));
}

#[test]
fn cycles_of_a_run_use_only_breakpoint_increments() {
    let times = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0];
    let rows: Vec<Vec<JointMeasures>> = (0..times.len())
        .map(|i| {
            let v = JointMeasures {
                tangential_force: (i as f64 * 1.3).sin(),
                mean_slip: (i as f64 * 0.7).cos(),
                dissipation: i as f64,
                ..JointMeasures::default()
            };
            vec![v, v]
        })
        .collect();
    let refs: Vec<&[JointMeasures]> = rows.iter().map(Vec::as_slice).collect();
    // a tangential history 0 at t = 1, 1 at t = 2, 0 at t = 3 (t = 1.5, 2.5 between)
    let values = |t: f64| vec![1.0 - (t - 2.0).abs()];
    let cycles = cycles(&times, &refs, &[1.0, 2.0, 3.0], values, 2);
    assert_eq!(cycles.len(), 2);
    assert_eq!(cycles[0].len(), 1);
    let c = &cycles[0][0];
    assert_eq!((c.start_increment, c.end_increment), (2, 6));
    assert_eq!(c.dissipation, 4.0);
    // without histories: none
    let none = super::cycles(&times, &refs, &[], |_| Vec::new(), 2);
    assert!(none.iter().all(Vec::is_empty));
    assert!(at_breakpoint(2.0, &[1.0, 2.0, 3.0]) && !at_breakpoint(2.5, &[1.0, 2.0, 3.0]));
    assert!(at_breakpoint(2.0 + 1e-14, &[1.0, 2.0, 3.0]));
}

/// The torque-twist loop of a cycle (a twisting model): its tips and the
/// torsional secant stiffness between them, ties broken by the twist.
#[test]
fn a_cycle_reads_its_torque_twist_loop() {
    // a bilinear torque-twist loop: elastic 1e9 N·mm/rad up to ±5e5 N·mm
    let pts = [
        (0.0, 0.0),
        (4e-4, 4e5),
        (5e-4, 5e5),
        (9e-4, 5e5),
        (0.0, -4e5),
        (-5e-4, -5e5),
        (-9e-4, -5e5),
        (0.0, 4e5),
    ];
    let rows: Vec<(f64, JointMeasures)> = pts
        .iter()
        .enumerate()
        .map(|(k, &(phi, t))| {
            let m = JointMeasures {
                torque: t,
                twist: phi,
                ..JointMeasures::default()
            };
            (k as f64, m)
        })
        .collect();
    let c = cycle_of(&rows, (0, pts.len() - 1));
    assert_eq!(c.torque_range, [-5e5, 5e5]);
    assert_eq!(c.twist_range, [-9e-4, 9e-4]);
    // the tips at the plateaus' far ends: (−9e-4, −5e5) and (9e-4, 5e5)
    let k = c.torsional_stiffness.unwrap();
    assert!((k - 1e6 / 1.8e-3).abs() < 1e-6 * k, "{k}");
    // without twist: no torque, no stiffness
    let flat: Vec<(f64, JointMeasures)> = (0..3)
        .map(|k| (k as f64, JointMeasures::default()))
        .collect();
    assert_eq!(cycle_of(&flat, (0, 2)).torsional_stiffness, None);
}

/// The torque-twist loop's stored energy and torsional loss factor against
/// the closed form of a Jenkins element (a torsional spring k_θ in series with
/// a slider at ±T_s) turned between ±φ_a: a parallelogram of area
/// D = 4 T_s (φ_a − T_s / k_θ), U_θ = ½ T_s φ_a, so
/// η_θ = D / (2π U_θ) = 4 (1 − T_s / (k_θ φ_a)) / π.
#[test]
fn a_jenkins_torque_twist_loop_has_the_closed_form_torsional_loss_factor() {
    // stick slope k, slides at ±t_s, turned between ±phi_a (phi_a > t_s / k)
    let (k, t_s, phi_a) = (2.0e9, 3.0e5, 4.0e-4);
    let pts = [
        (phi_a, t_s),
        (phi_a - t_s / k, 0.0),
        (phi_a - 2.0 * t_s / k, -t_s),
        (-phi_a, -t_s),
        (-phi_a + t_s / k, 0.0),
        (-phi_a + 2.0 * t_s / k, t_s),
        (phi_a, t_s),
    ];
    // D accumulated as the trapezoid of T dφ̄ (a closed loop: D = W)
    let mut diss = 0.0;
    let rows: Vec<(f64, JointMeasures)> = pts
        .iter()
        .enumerate()
        .map(|(i, &(phi, t))| {
            if i > 0 {
                let (p0, t0) = pts[i - 1];
                diss += 0.5 * (t0 + t) * (phi - p0);
            }
            let jm = JointMeasures {
                torque: t,
                twist: phi,
                dissipation: diss,
                work: diss,
                ..JointMeasures::default()
            };
            (i as f64, jm)
        })
        .collect();
    let mut c = cycle_of(&rows, (0, pts.len() - 1));
    // the parallelogram: height 2 t_s, width 2 (φ_a − t_s/k) along the slides
    let area = 4.0 * t_s * (phi_a - t_s / k);
    assert!((c.dissipation - area).abs() < 1e-12 * area, "{c:?}");
    assert_eq!(c.tip_twist, [-phi_a, phi_a]);
    assert_eq!((c.torque_amplitude(), c.twist_amplitude()), (t_s, phi_a));
    let u = 0.5 * t_s * phi_a;
    assert!((c.torsional_stored_energy() - u).abs() < 1e-12 * u, "{c:?}");
    // η_θ = 4 (φ_a − T_s/k) / (π φ_a): 1 − T_s/(k φ_a) = 0.625 of 4/π
    let eta = c.torsional_loss_factor().unwrap();
    let want = 4.0 * (1.0 - t_s / (k * phi_a)) / std::f64::consts::PI;
    assert!((eta - want).abs() < 1e-12 * want, "{eta} against {want}");
    // no force-slip loop in it: the force-slip loss factor stays empty
    assert_eq!((c.stored_energy(), c.loss_factor()), (0.0, None));
    // an elastic loop (D at round-off) has no torsional loss factor
    c.dissipation = 0.0;
    c.floor = 1e-12 * t_s * 2.0 * phi_a;
    assert_eq!(c.torsional_loss_factor(), None);
    // a model without twist: no torque-twist loop, no torsional loss factor
    let flat: Vec<(f64, JointMeasures)> = (0..3)
        .map(|k| (k as f64, JointMeasures::default()))
        .collect();
    let c = cycle_of(&flat, (0, 2));
    assert_eq!(
        (c.torsional_stored_energy(), c.torsional_loss_factor()),
        (0.0, None)
    );
}

/// A force held constant (an axial preload under a cycled torque) varies
/// over a cycle by the solver's round-off only: no amplitude, no secant
/// stiffness, no stored energy and no loss factor, where the raw
/// differences would give a stiffness of 1e-4 N/mm. A range just above
/// [`TIP_TIE`] is a loop again; the same for the torque.
#[test]
fn a_force_held_to_round_off_has_no_amplitude_and_no_secant_stiffness() {
    let row = |f: f64, s: f64, t: f64, phi: f64| {
        let jm = JointMeasures {
            tangential_force: f,
            mean_slip: s,
            torque: t,
            twist: phi,
            dissipation: 80.0 * s.abs(),
            ..JointMeasures::default()
        };
        (0.0, jm)
    };
    let f = -1e4;
    let held_rows = vec![
        row(f, -4.0e-4, 0.0, 0.0),
        row(f + 1.8e-8, -4.8e-4, 4e5, 7e-5),
        row(f - 1.6e-8, -4.4e-4, -4e5, -7e-5),
        row(f, -4.0e-4, 0.0, 0.0),
    ];
    let c = cycle_of(&held_rows, (0, 3));
    // the tips within the tie are chosen by slip: their raw difference is
    // round-off of either sign
    assert!(held(c.force_range, c.force_scale) && c.force_range[1] != c.force_range[0]);
    assert_eq!(c.force_amplitude(), 0.0);
    assert_eq!(c.secant_stiffness, None);
    assert_eq!((c.stored_energy(), c.loss_factor()), (0.0, None));
    // the torque is cycled: its loop is measured
    assert_eq!(c.torque_amplitude(), 4e5);
    assert!((c.torsional_stiffness.unwrap() - 8e5 / 14e-5).abs() < 1e-3);
    // 2 × 10⁻⁶ of the force: a loop
    let mut small = held_rows.clone();
    small[1].1.tangential_force = f + 0.02;
    let c = cycle_of(&small, (0, 3));
    assert!(!held(c.force_range, c.force_scale));
    assert!((c.force_amplitude() - 0.5 * (0.02 + 1.6e-8)).abs() < 1e-12);
    assert!(c.secant_stiffness.is_some());
    // the same for a torque held to round-off
    let mut torque_held = held_rows;
    for (k, r) in torque_held.iter_mut().enumerate() {
        r.1.torque = 5e5 + if k == 1 { 1e-7 } else { 0.0 };
    }
    let c = cycle_of(&torque_held, (0, 3));
    assert_eq!(c.torque_amplitude(), 0.0);
    assert_eq!(c.torsional_stiffness, None);
    assert_eq!(c.torsional_loss_factor(), None);
}

/// A shear held at zero while the normal force cycles: F_T and its range
/// are both noise (1e-13 N), so the range is round-off against F_N, not
/// against itself. No amplitude, no secant stiffness, no negative stored
/// energy or slip amplitude from tips that noise picked.
#[test]
fn a_shear_held_at_zero_under_a_cycled_normal_force_has_no_loop() {
    let row = |f_t: f64, f_n: f64, s: f64| {
        let jm = JointMeasures {
            tangential_force: f_t,
            normal_force: f_n,
            mean_slip: s,
            ..JointMeasures::default()
        };
        (0.0, jm)
    };
    let rows = vec![
        row(2e-13, 100.0, 1e-11),
        row(-5.9e-13, 60.0, 4e-11),
        row(5.8e-13, 100.0, -3e-11),
        row(-1e-13, 60.0, 2e-11),
        row(2e-13, 100.0, 1e-11),
    ];
    let c = cycle_of(&rows, (0, 4));
    assert_eq!(c.force_scale, 100.0);
    assert!(held(c.force_range, c.force_scale));
    assert_eq!(c.force_amplitude(), 0.0);
    assert_eq!(c.secant_stiffness, None);
    assert_eq!((c.stored_energy(), c.loss_factor()), (0.0, None));
    // every increment is one tip: the smallest and the largest slip
    assert_eq!(c.tip_slip, [-3e-11, 4e-11]);
    assert!(c.slip_amplitude() > 0.0);
    // without F_N the noise would be a loop of its own
    assert!(!held([-5.9e-13, 5.8e-13], 0.0));
}
