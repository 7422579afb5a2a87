//! The joint in service: a speed's body force and a fit's temperatures
//! against the closed forms of spinning and heated disks (docs/theory.md,
//! "Body force of a speed"; Timoshenko & Goodier, Theory of Elasticity,
//! §§ 32, 150: the rotating disk and the thermal stresses of a disk).
//!
//! Every body here is a disk or a ring b ≤ r ≤ c, axisymmetric, uniform in z,
//! at a uniform temperature change ΔT and spinning at ω. Its radial
//! displacement solves D (u'' + u'/r − u/r²) = −ρ ω² r:
//!
//! ```text
//!   u   = C₁ r + C₂ / r − K r³ / 8,                    K = ρ ω² / D
//!   σ_r = D [(1 + ν*) C₁ − (1 − ν*) C₂ / r² − (3 + ν*) K r² / 8 − θ]
//!   σ_θ = D [(1 + ν*) C₁ + (1 − ν*) C₂ / r² − (1 + 3ν*) K r² / 8 − θ]
//! ```
//!
//! plane stress (free faces): D = E / (1 − ν²), ν* = ν, θ = (1 + ν) α ΔT;
//! plane strain (ε_z = 0, both faces held axially): D = E (1 − ν) / ((1 +
//! ν)(1 − 2ν)), ν* = ν / (1 − ν), θ = (1 + ν*)(1 + ν) α ΔT, σ_z = ν (σ_r +
//! σ_θ) − E α ΔT. Plane strain is the exact state of a slice held between
//! two frictionless planes whatever ω; plane stress is exact for a heated
//! disk loaded by a pressure (σ_r + σ_θ uniform, ε_z uniform) but not for a
//! spinning one (ε_z then varies with r), so the spinning cases are plane
//! strain and the heated fit plane stress.
//!
//! A fit (shaft 0 ≤ r ≤ b in a hub b ≤ r ≤ c, radial interference δ,
//! frictionless interface of the linear law u_N = c_N p, the power law with
//! m = 1) is four linear equations in C₁ of the shaft, C₁ and C₂ of the hub
//! and p: σ_r,hub(c) = 0, σ_r,hub(b) = σ_r,shaft(b) = −p,
//! u_hub(b) − u_shaft(b) + c_N p = δ. p is linear in ω² and in ΔT: the fit
//! opens where it reaches 0.

use crate::common;
use asperity::model::Model;
use asperity::physics::material::PointState;
use asperity::solve::events::{Event, Kind};
use asperity::solve::{Increment, Observer, RunResult, State};

const B: f64 = 20.0;
const C: f64 = 50.0;
const DELTA: f64 = 0.02;
const C_N: f64 = 2e-5;
const STEEL: Solid = Solid {
    e: 210_000.0,
    nu: 0.3,
    alpha: 11.5e-6,
    rho: 7850.0,
};
const ALUMINIUM: Solid = Solid {
    e: 70_000.0,
    nu: 0.33,
    alpha: 23.5e-6,
    rho: 2700.0,
};

#[derive(Clone, Copy)]
struct Solid {
    e: f64,
    nu: f64,
    alpha: f64,
    /// kg/m³
    rho: f64,
}

/// One body of the closed form at ω (rad/s) and ΔT (K).
struct Disk {
    d: f64,
    nus: f64,
    theta: f64,
    k: f64,
    m: Solid,
    dt: f64,
    strain: bool,
}

impl Disk {
    fn new(m: Solid, omega: f64, dt: f64, strain: bool) -> Disk {
        let (d, nus, a) = if strain {
            let d = m.e * (1.0 - m.nu) / ((1.0 + m.nu) * (1.0 - 2.0 * m.nu));
            (d, m.nu / (1.0 - m.nu), (1.0 + m.nu) * m.alpha)
        } else {
            (m.e / (1.0 - m.nu * m.nu), m.nu, m.alpha)
        };
        let k = m.rho * 1e-12 * omega * omega / d;
        Disk {
            d,
            nus,
            theta: (1.0 + nus) * a * dt,
            k,
            m,
            dt,
            strain,
        }
    }

    /// σ_r's coefficients of C₁ and C₂ at r, and its constant part.
    fn sr(&self, r: f64) -> ([f64; 2], f64) {
        let d = self.d;
        (
            [d * (1.0 + self.nus), -d * (1.0 - self.nus) / (r * r)],
            -d * ((3.0 + self.nus) * self.k * r * r / 8.0 + self.theta),
        )
    }

    /// σ_r, σ_θ, σ_z at r for the constants c.
    fn stress(&self, c: [f64; 2], r: f64) -> [f64; 3] {
        let (d, n) = (self.d, self.nus);
        let sr = d
            * ((1.0 + n) * c[0]
                - (1.0 - n) * c[1] / (r * r)
                - (3.0 + n) * self.k * r * r / 8.0
                - self.theta);
        let st = d
            * ((1.0 + n) * c[0] + (1.0 - n) * c[1] / (r * r)
                - (1.0 + 3.0 * n) * self.k * r * r / 8.0
                - self.theta);
        let sz = if self.strain {
            self.m.nu * (sr + st) - self.m.e * self.m.alpha * self.dt
        } else {
            0.0
        };
        [sr, st, sz]
    }
}

/// Solves the 4×4 system a x = y by Gaussian elimination with pivoting.
fn solve4(mut a: [[f64; 4]; 4], mut y: [f64; 4]) -> [f64; 4] {
    for i in 0..4 {
        let p = (i..4)
            .max_by(|&j, &k| a[j][i].abs().total_cmp(&a[k][i].abs()))
            .unwrap();
        a.swap(i, p);
        y.swap(i, p);
        for j in i + 1..4 {
            let f = a[j][i] / a[i][i];
            let pivot_row = a[i];
            for (ajk, aik) in a[j][i..].iter_mut().zip(&pivot_row[i..]) {
                *ajk -= f * aik;
            }
            y[j] -= f * y[i];
        }
    }
    let mut x = [0.0; 4];
    for i in (0..4).rev() {
        let s: f64 = (i + 1..4).map(|k| a[i][k] * x[k]).sum();
        x[i] = (y[i] - s) / a[i][i];
    }
    x
}

/// The fit's closed form: the shaft's and the hub's constants and p
/// (negative: the fit would need a tension to stay closed, it is open).
fn fit(shaft: &Disk, hub: &Disk) -> ([f64; 2], [f64; 2], f64) {
    fit_with(shaft, hub, DELTA)
}

/// [`fit`] with the radial interference `delta`.
fn fit_with(shaft: &Disk, hub: &Disk, delta: f64) -> ([f64; 2], [f64; 2], f64) {
    let (hc, hc0) = hub.sr(C);
    let (hb, hb0) = hub.sr(B);
    let (sb, sb0) = shaft.sr(B);
    // unknowns: C₁ shaft, C₁ hub, C₂ hub, p
    let a = [
        [0.0, hc[0], hc[1], 0.0],
        [0.0, hb[0], hb[1], 1.0],
        [sb[0], 0.0, 0.0, 1.0],
        [-B, B, 1.0 / B, C_N],
    ];
    let y = [
        -hc0,
        -hb0,
        -sb0,
        delta + (hub.k - shaft.k) * B.powi(3) / 8.0,
    ];
    let x = solve4(a, y);
    ([x[0], 0.0], [x[1], x[2]], x[3])
}

/// Every converged increment's pseudo-time and Gauss states.
#[derive(Default)]
struct Capture(Vec<(f64, Vec<PointState>)>);
impl Observer for Capture {
    fn increment(&mut self, _: &Model, s: &State, inc: &Increment) -> asperity::error::Result<()> {
        self.0.push((inc.load_factor, s.gauss.iter().collect()));
        Ok(())
    }
}

fn solve(text: &str) -> (Model, RunResult, Capture) {
    let model = common::model(text);
    let mut c = Capture::default();
    let r = asperity::app::driver::solve(&model, &mut c).unwrap_or_else(|e| panic!("{e}"));
    (model, r, c)
}

/// The largest difference of the Gauss points' σ_r, σ_z, σ_θ of `body`
/// from the closed form's, and the largest closed-form stress for scale.
fn stress_error(
    model: &Model,
    gauss: &[PointState],
    body: usize,
    disk: &Disk,
    c: [f64; 2],
) -> (f64, f64) {
    let (mut err, mut scale) = (0.0f64, 0.0f64);
    for (e, el) in model.mesh.elements.iter().enumerate() {
        if el.body != body {
            continue;
        }
        for (ip, g) in model.points(e).enumerate() {
            let r = model.point_x(e, ip)[0];
            let [sr, st, sz] = disk.stress(c, r);
            let s = gauss[g].stress;
            for (fe, cf) in [(s[0], sr), (s[3], st), (s[1], sz)] {
                err = err.max((fe - cf).abs());
                scale = scale.max(cf.abs());
            }
            err = err.max(s[2].abs());
        }
    }
    (err, scale)
}

const RPM: f64 = 12_000.0;

fn omega(rpm: f64) -> f64 {
    rpm * std::f64::consts::PI / 30.0
}

/// A solid steel disk of radius C spinning at 12 000 rpm, a slice held
/// between two frictionless planes (plane strain): every Gauss point's
/// stresses within 1e-4 of the largest, the radial displacement of the rim
/// within 1e-6 of the closed form's, in two increments (ω ∝ t, the force
/// ∝ t²: the half-speed state carries a quarter of the stress).
#[test]
fn a_spinning_disk_matches_the_closed_form() {
    let text = common::case()
        .plane("axisymmetric")
        .block("disk", [0.0, C], [48], [0.0, 4.0], [1])
        .material("disk", STEEL.e, STEEL.nu)
        .with("density", STEEL.rho)
        .uy("disk.bottom", 0.0)
        .uy("disk.top", 0.0)
        .raw("[speed]")
        .with("rpm", RPM)
        .solver("increments = 2\nstep_control = \"fixed\"")
        .tolerances(1e-12, 1e-12)
        .no_vtu()
        .build();
    let (model, _, cap) = solve(&text);
    assert_eq!(model.rpm(0.5), Some(RPM / 2.0));
    for (t, gauss) in &cap.0 {
        let disk = Disk::new(STEEL, omega(RPM * t), 0.0, true);
        // the rim is free: σ_r(C) = 0
        let c1 = (3.0 + disk.nus) * disk.k * C * C / 8.0 / (1.0 + disk.nus);
        let (err, scale) = stress_error(&model, gauss, 0, &disk, [c1, 0.0]);
        eprintln!(
            "t = {t}: stress error {:.2e} of {scale:.3} MPa (σ_r(0) = {:.4} MPa)",
            err / scale,
            disk.stress([c1, 0.0], 1e-9)[0]
        );
        assert!(err < 1e-4 * scale, "t = {t}: {err} of {scale}");
    }
}

/// [`stress_error`] of the shaft (body 0) and the hub (body 1) together:
/// the largest difference and the largest closed-form stress of the pair.
fn pair_error(model: &Model, gauss: &[PointState], bodies: [(&Disk, [f64; 2]); 2]) -> (f64, f64) {
    let [a, b] = [0, 1].map(|k| stress_error(model, gauss, k, bodies[k].0, bodies[k].1));
    (a.0.max(b.0), a.1.max(b.1))
}

/// Every increment of a fit's run against the closed form of `pair(x)` at
/// x = `top` · t (a speed, rpm, or a ΔT, K): the mean pressure within 1e-4
/// of p₀, 0 where the closed form is open, and both bodies' stresses within
/// 1e-4 of the pair's largest. Returns the load factor of the fit's first
/// opening.
fn follows_the_closed_form(
    (model, r, cap): (&Model, &RunResult, &Capture),
    top: f64,
    p0: f64,
    pair: impl Fn(f64) -> (Disk, Disk),
    unit: &str,
) -> f64 {
    for (t, p) in mean_pressures(model, r) {
        let x = top * t;
        let (s, h) = pair(x);
        let (cs, ch, pc) = fit(&s, &h);
        if pc <= 0.0 {
            assert!(p.abs() < 1e-9 * p0, "open at {x} {unit}: p = {p}");
            continue;
        }
        eprintln!(
            "{x:9.3} {unit}: FE {p:.6} MPa, closed form {pc:.6} ({:.1e})",
            (p - pc) / p0
        );
        assert!((p - pc).abs() < 1e-4 * p0, "{x} {unit}: FE {p} vs {pc}");
        let gauss = &cap.0.iter().find(|c| c.0 == t).unwrap().1;
        let (err, scale) = pair_error(model, gauss, [(&s, cs), (&h, ch)]);
        assert!(err < 1e-4 * scale, "{x} {unit}: {err} of {scale}");
    }
    (r.events.iter())
        .find(|e| e.kind == Kind::FirstOpening)
        .expect("the fit opens")
        .load_factor
}

/// The fit's mean pressure (the joint's F_N over its area) at each
/// increment.
fn mean_pressures(model: &Model, r: &RunResult) -> Vec<(f64, f64)> {
    let area = model.interfaces[0].area();
    (r.increments.iter())
        .map(|i| (i.load_factor, i.joints[0].normal_force / area))
        .collect()
}

fn fit_case(plane_strain: bool, twist: bool) -> common::CaseText {
    let mut c = common::case().plane("axisymmetric");
    if twist {
        c = c.with("twist", true);
    }
    c = c
        .block("shaft", [0.0, B], [24], [0.0, 4.0], [1])
        .block("hub", [B, C], [56], [0.0, 4.0], [1])
        .rx([6.0])
        .vertical_interface("fit", "shaft", "hub")
        .material("shaft", STEEL.e, STEEL.nu)
        .with("density", STEEL.rho)
        .with("expansion", STEEL.alpha)
        .material("hub", ALUMINIUM.e, ALUMINIUM.nu)
        .with("density", ALUMINIUM.rho)
        .with("expansion", ALUMINIUM.alpha)
        .law("fit", "power", C_N, 1.0)
        .gap(-DELTA)
        .uy("shaft.bottom", 0.0)
        .uy("hub.bottom", 0.0);
    if plane_strain {
        c = c.uy("shaft.top", 0.0).uy("hub.top", 0.0);
    }
    c
}

/// An aluminium hub on a steel shaft spun up to 1.3 times the speed at
/// which it opens (plane strain):
/// the pressure at each increment within 1e-4 of the closed form's, and
/// the fit's first opening (an event) at the closed form's speed within
/// 1e-4 (the hub, lighter but softer and larger, grows away from the
/// shaft).
#[test]
fn a_spinning_fit_loses_its_pressure_and_opens_at_the_closed_form_speed() {
    let w = |rpm: f64| {
        let s = Disk::new(STEEL, omega(rpm), 0.0, true);
        let h = Disk::new(ALUMINIUM, omega(rpm), 0.0, true);
        fit(&s, &h)
    };
    // p = p₀ − k ω²: the speed where it reaches 0
    let (p0, p1) = (w(0.0).2, w(1000.0).2);
    let open_rpm = 1000.0 * (p0 / (p0 - p1)).sqrt();
    let top = 1.3 * open_rpm;
    eprintln!("closed form: p(0) = {p0:.5} MPa, opens at {open_rpm:.3} rpm");
    let text = fit_case(true, false)
        .raw("[speed]")
        .with("rpm", top)
        .solver("increments = 10\nstep_control = \"fixed\"")
        .tolerances(1e-12, 1e-12)
        .raw("[output]")
        .with("event_tolerance", 1e-7)
        .with("vtu", false)
        .build();
    let (model, r, cap) = solve(&text);
    let pair = |rpm: f64| {
        let w = omega(rpm);
        (
            Disk::new(STEEL, w, 0.0, true),
            Disk::new(ALUMINIUM, w, 0.0, true),
        )
    };
    let open = follows_the_closed_form((&model, &r, &cap), top, p0, pair, "rpm");
    let at = model.rpm(open).unwrap();
    eprintln!(
        "first opening at {at:.3} rpm ({:.1e})",
        common::rel(at, open_rpm)
    );
    assert!(common::rel(at, open_rpm) < 1e-4, "{at} vs {open_rpm}");
}

/// The same pair heated as a whole (both bodies ΔT, plane stress: free
/// faces): the aluminium hub expands more than the steel shaft and the fit
/// loses its pressure, to 0 at the closed form's temperature; the pressure
/// at each increment within 1e-4, the opening within 1e-4.
#[test]
fn a_heated_aluminium_hub_on_a_steel_shaft_opens_at_the_closed_form_temperature() {
    let w = |dt: f64| {
        let s = Disk::new(STEEL, 0.0, dt, false);
        let h = Disk::new(ALUMINIUM, 0.0, dt, false);
        fit(&s, &h)
    };
    let (p0, p1) = (w(0.0).2, w(1.0).2);
    let open_dt = p0 / (p0 - p1);
    let top = 1.3 * open_dt;
    eprintln!("closed form: p(20 °C) = {p0:.5} MPa, opens at ΔT = {open_dt:.4} K");
    let mut c = fit_case(false, false);
    for body in ["shaft", "hub"] {
        c = c
            .raw("[[temperature]]")
            .with("body", body)
            .with("change", top)
            .with("reference", 20.0);
    }
    let text = c
        .solver("increments = 10\nstep_control = \"fixed\"")
        .tolerances(1e-10, 1e-10)
        .raw("[output]")
        .with("event_tolerance", 1e-7)
        .with("vtu", false)
        .build();
    let (model, r, cap) = solve(&text);
    let pair = |dt: f64| {
        (
            Disk::new(STEEL, 0.0, dt, false),
            Disk::new(ALUMINIUM, 0.0, dt, false),
        )
    };
    let open = follows_the_closed_form((&model, &r, &cap), top, p0, pair, "K");
    let at = top * open;
    eprintln!(
        "first opening at ΔT = {at:.4} K ({:.1e})",
        common::rel(at, open_dt)
    );
    assert!(common::rel(at, open_dt) < 1e-4, "{at} vs {open_dt}");
}

/// The fit of [`fit_case`] (plane strain, twisting) with friction
/// μ = 0.15, its hub turned by a torque load `t` on its rim (the history
/// `torque` among `histories`), the shaft held about the axis at its foot,
/// and spun at `rpm` (the history `spin`) if given, run until it lets go:
/// the model, the run and its `torque_limit` event (event tolerance 1e-7).
fn torque_limit_run(t: f64, histories: &str, rpm: Option<f64>) -> (Model, RunResult, Event) {
    let mut c = fit_case(true, true)
        .tangential("fit", 0.9, 0.5, 0.05, 0.15)
        .raw(&format!("[history]\n{histories}"))
        .raw("[[boundary]]\nset = \"shaft.bottom\"\nrotation = 0.0")
        .raw("[[load]]\nedges = \"hub.right\"")
        .with("torque", t)
        .history("torque");
    if let Some(n) = rpm {
        c = c.raw("[speed]").with("rpm", n).history("spin");
    }
    let text = c
        .solver("increments = 20\nstep_control = \"fixed\"")
        .raw("[output]")
        .with("event_tolerance", 1e-7)
        .with("vtu", false)
        .build();
    let model = common::model(&text);
    let r = asperity::app::driver::solve(&model, &mut common::Quiet)
        .unwrap_or_else(|e| panic!("the run ends at its torque limit, not in an error: {e}"));
    assert_eq!(r.stopped, Some(asperity::interrupt::Stop::TorqueLimit));
    let e = (r.events.iter())
        .find(|e| e.kind == Kind::TorqueLimit)
        .cloned()
        .expect("a torque_limit event");
    (model, r, e)
}

/// The fit of [`a_spinning_fit_loses_its_pressure_and_opens_at_the_closed_form_speed`]
/// with friction (μ = 0.15), twisting: a torque T on the hub, then the speed
/// raised under it. The hub is held about the axis by friction alone, so at
/// the speed where μ p(ω) 2π b² L falls to T it can no longer hold its
/// torque: the run ends there with the event `torque_limit`, located to
/// 1e-7 of the pseudo-time, within 1e-5 of the closed form's speed (p
/// linear in ω², as above).
#[test]
fn a_spinning_fit_under_a_torque_lets_go_at_the_closed_form_speed() {
    const MU: f64 = 0.15;
    const T: f64 = 3.0e4;
    const L: f64 = 4.0;
    let w = |rpm: f64| {
        let s = Disk::new(STEEL, omega(rpm), 0.0, true);
        let h = Disk::new(ALUMINIUM, omega(rpm), 0.0, true);
        fit(&s, &h).2
    };
    let (p0, p1) = (w(0.0), w(1000.0));
    let hold = T / (MU * 2.0 * std::f64::consts::PI * B * B * L);
    let slip_rpm = 1000.0 * ((p0 - hold) / (p0 - p1)).sqrt();
    let top = 1.3 * slip_rpm;
    eprintln!("closed form: p = {hold:.5} MPa holds T at {slip_rpm:.3} rpm");
    let (model, r, e) = torque_limit_run(
        T,
        "torque = [[0, 0], [1, 1], [2, 1]]\nspin = [[0, 0], [1, 0], [2, 1]]",
        Some(top),
    );
    let at = model.rpm(e.load_factor).expect("a speed");
    let last = model.rpm(e.before).expect("a speed");
    eprintln!(
        "lets go at {at:.3} rpm ({:.1e}), held at {last:.3} rpm, bracket {:.1e}",
        common::rel(at, slip_rpm),
        e.after - e.before
    );
    assert!(e.converged && e.after - e.before <= 1e-7, "{e:?}");
    assert!(common::rel(at, slip_rpm) < 1e-5, "{at} vs {slip_rpm}");
    // the last state that held carries the torque, its last increment
    // before the event
    assert!(common::rel(e.values[4].abs(), T) < 1e-6, "{:?}", e.values);
    let end = r.increments.last().unwrap().load_factor;
    assert!(end <= e.before && e.increment == r.increments.len() + 1);
}

/// The same fit standing still under a torque raised to 1.3 times its slip
/// torque μ p 2π b² L (p uniform: plane strain, no speed): the run ends
/// at the event `torque_limit`, whose last state that held carries the
/// slip torque within 1e-6 (printed: 3e-8 with the event tolerance 1e-7).
#[test]
fn a_torque_past_what_friction_holds_ends_the_run_at_the_slip_torque() {
    const MU: f64 = 0.15;
    const L: f64 = 4.0;
    let p = fit(
        &Disk::new(STEEL, 0.0, 0.0, true),
        &Disk::new(ALUMINIUM, 0.0, 0.0, true),
    )
    .2;
    let slip = MU * p * 2.0 * std::f64::consts::PI * B * B * L;
    let (_, _, e) = torque_limit_run(slip, "torque = [[0, 0], [1, 0], [2, 1.3]]", None);
    let held = e.values[4].abs();
    eprintln!(
        "slip torque {slip:.6e} N·mm (p = {p:.6} MPa); held {held:.6e} ({:+.2e}) at λ = {:.7}, none past {:.7}",
        held / slip - 1.0,
        e.before,
        e.after
    );
    assert!(
        held <= slip * (1.0 + 1e-9) && held > (1.0 - 1e-6) * slip,
        "{held} vs {slip}"
    );
    // the torque then is the history's: T(λ) = slip (λ − 1) 1.3
    assert!(common::rel(held, slip * 1.3 * (e.before - 1.0)) < 1e-9);
}

/// The fit assembled by heating the hub (shrink fit proper): the hub, ΔT =
/// 150 K hotter at the start, has a clearance δ_c = α_hub ΔT b − δ; as it
/// cools (ΔT(t) = 150 (1 − t)) the bore closes on the shaft where its free
/// growth equals the interference, ΔT = δ / ((1 + ν) α_hub b) (plane strain:
/// held along z, the bore grows by (1 + ν) α ΔT b), and the fit ends at
/// the pressure of the closed form (and of the same fit pressed in, to
/// round-off: elastic, frictionless). No increment before the closing
/// carries a force, every one after it does; the event `first_contact` is
/// there (1e-6 of the pseudo-time), none at the start (the drawn
/// interference is no contact of a hub not yet expanded), and heated again
/// the fit opens where it gripped.
#[test]
fn a_hub_heated_for_assembly_grips_as_it_cools_to_the_closed_form_pressure() {
    const HOT: f64 = 150.0;
    let close_dt = DELTA / ((1.0 + ALUMINIUM.nu) * ALUMINIUM.alpha * B);
    let t_close = 1.0 - close_dt / HOT;
    let p = fit(
        &Disk::new(STEEL, 0.0, 0.0, true),
        &Disk::new(ALUMINIUM, 0.0, 0.0, true),
    )
    .2;
    eprintln!("closes at ΔT = {close_dt:.4} K (t = {t_close:.4}), ends at p = {p:.6} MPa");
    let text = fit_case(true, false)
        .raw("[history]\ncool = [[0, 1], [1, 0], [2, 1]]")
        .raw("[[temperature]]\nbody = \"hub\"")
        .with("change", HOT)
        .with("reference", 20.0)
        .history("cool")
        .solver("increments = 20\nstep_control = \"fixed\"")
        .tolerances(1e-12, 1e-12)
        .raw("[output]")
        .with("event_tolerance", 1e-7)
        .with("vtu", false)
        .build();
    let (model, r, _) = solve(&text);
    let pressures = mean_pressures(&model, &r);
    for &(t, pm) in pressures.iter().filter(|x| x.0 <= 1.0) {
        if t < t_close - 1e-12 {
            assert_eq!(pm, 0.0, "t = {t}: the hub is still clear of the shaft");
        } else {
            assert!(pm > 0.0, "t = {t}: the hub grips");
        }
    }
    let end = pressures.iter().find(|x| x.0 == 1.0).unwrap().1;
    eprintln!("FE at 20 °C: {end:.6} MPa ({:.1e})", common::rel(end, p));
    assert!(common::rel(end, p) < 1e-4, "{end} vs {p}");
    // the run starts from a hub not yet expanded: no event at λ ≈ 0; heated
    // again (t > 1), the fit opens where it gripped (elastic, frictionless)
    located(&r, Kind::FirstOpening, 1.0 + close_dt / HOT, "opens again");
    // it grips as it cools: its first contact where the bore's free growth
    // is the interference, the only event before t = 1
    located(&r, Kind::FirstContact, t_close, "grips");
    assert!(
        (r.events.iter()).all(|e| e.load_factor > 1.0 || e.kind == Kind::FirstContact),
        "{:?}",
        r.events
    );
}

/// The event `kind` of a run at the pseudo-time `want` (1e-6), printed.
fn located(r: &RunResult, kind: Kind, want: f64, what: &str) {
    let e = (r.events.iter())
        .find(|e| e.kind == kind)
        .unwrap_or_else(|| panic!("no {} event: {:?}", kind.name(), r.events));
    eprintln!("{what} at t = {:.7} (closed form {want:.7})", e.load_factor);
    assert!(
        (e.load_factor - want).abs() < 1e-6,
        "{what}: {} vs {want}",
        e.load_factor
    );
}

/// The shipped case `cases/hub-in-service` against its README's hand check
/// (the closed form above with the case's numbers: δ = 0.03 mm, a 7075
/// hub): no force while the hot hub is clear of the shaft (ΔT_hub above
/// δ/((1 + ν) α b) = 47.99 K, t < 0.680), its first contact there, then the pressure at 20 °C
/// (t = 1), at 80 °C (t = 2) and at 80 °C and 6000 rpm (t = 3), and the
/// torque the fit holds as it slides there (its holding plateau) against
/// μ p 2π b² L, each within 1e-4.
#[test]
fn the_shipped_hub_in_service_follows_its_hand_check() {
    const DELTA_CASE: f64 = 0.03;
    const L: f64 = 20.0;
    const MU: f64 = 0.15;
    let al = Solid {
        e: 71_000.0,
        rho: 2810.0,
        ..ALUMINIUM
    };
    let p = |dt: f64, rpm: f64| {
        let s = Disk::new(STEEL, omega(rpm), dt, true);
        let h = Disk::new(al, omega(rpm), dt, true);
        fit_with(&s, &h, DELTA_CASE).2
    };
    let path = common::root().join("cases/hub-in-service/case.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let (model, r, _) = solve(&text);
    let pressures = mean_pressures(&model, &r);
    let t_close = 1.0 - DELTA_CASE / ((1.0 + al.nu) * al.alpha * B) / 150.0;
    for &(t, pm) in &pressures {
        if t < t_close - 1e-9 {
            assert_eq!(pm, 0.0, "t = {t}: the hub is still clear");
        }
    }
    // the event says where it grips (event_tolerance 1e-6)
    located(&r, Kind::FirstContact, t_close, "grips");
    for (t, dt, rpm) in [(1.0, 0.0, 0.0), (2.0, 60.0, 0.0), (3.0, 60.0, 6000.0)] {
        let fe = pressures.iter().find(|x| x.0 == t).unwrap().1;
        let hand = p(dt, rpm);
        eprintln!(
            "t = {t}: FE {fe:.4} MPa, hand {hand:.4} MPa ({:.1e})",
            common::rel(fe, hand)
        );
        assert!(common::rel(fe, hand) < 1e-4, "t = {t}: {fe} vs {hand}");
    }
    let plateau = (r.events.iter())
        .find(|e| matches!(e.kind, Kind::HoldingPlateau(_)))
        .expect("the fit slides at speed");
    let held = plateau.values[4].abs() * 1e-3;
    let hand = MU * p(60.0, 6000.0) * 2.0 * std::f64::consts::PI * B * B * L * 1e-3;
    eprintln!("holds {held:.3} N·m at 6000 rpm, hand {hand:.3} N·m");
    assert_eq!(model.rpm(plateau.load_factor), Some(6000.0));
    assert!(common::rel(held, hand) < 1e-4, "{held} vs {hand}");
}

/// The shipped case `cases/fit-speed-limit` against its README's hand
/// check: the pressed fit of hub-in-service (δ = 0.03 mm, a 7075 hub) at
/// 20 °C under 350 N·m, spun up: the run ends at the event `torque_limit`
/// where μ p(ω) 2π b² L falls to the torque, p(ω) = p₀ − k ω² the closed
/// form's, within 1e-4 (the mesh of the case: 8 + 12 elements across);
/// the last state that held carries the torque.
#[test]
fn the_shipped_fit_speed_limit_lets_go_at_its_hand_check() {
    const DELTA_CASE: f64 = 0.03;
    const L: f64 = 20.0;
    const MU: f64 = 0.15;
    const T: f64 = 350.0e3;
    let al = Solid {
        e: 71_000.0,
        rho: 2810.0,
        ..ALUMINIUM
    };
    let p = |rpm: f64| {
        let s = Disk::new(STEEL, omega(rpm), 0.0, true);
        let h = Disk::new(al, omega(rpm), 0.0, true);
        fit_with(&s, &h, DELTA_CASE).2
    };
    let (p0, p1) = (p(0.0), p(1000.0));
    let hold = T / (MU * 2.0 * std::f64::consts::PI * B * B * L);
    let hand = 1000.0 * ((p0 - hold) / (p0 - p1)).sqrt();
    let path = common::root().join("cases/fit-speed-limit/case.toml");
    let (model, r, _) = solve(&std::fs::read_to_string(&path).unwrap());
    assert_eq!(r.stopped, Some(asperity::interrupt::Stop::TorqueLimit));
    let e = (r.events.iter())
        .find(|e| e.kind == Kind::TorqueLimit)
        .expect("the fit lets go");
    let at = model.rpm(e.load_factor).unwrap();
    eprintln!(
        "p₀ = {p0:.4} MPa, holds 350 N·m down to p = {hold:.4} MPa: hand {hand:.1} rpm, program {at:.1} rpm ({:.1e})",
        common::rel(at, hand)
    );
    assert!(common::rel(at, hand) < 1e-4, "{at} vs {hand}");
    assert!(common::rel(e.values[4].abs(), T) < 1e-9, "{:?}", e.values);
}

/// The speed's nodal forces sum to the body force's resultant, exactly
/// (Σ_a N_a = 1), in each kind of model: a plane block 10 ≤ x ≤ 30,
/// 0 ≤ y ≤ 5, 2 mm thick, spinning about z (Σ f = ρ ω² t (h (b² − a²)/2,
/// (b − a) h²/2)); a ring of the same section about the axis (Σ f_r =
/// ρ ω² 2π h (b³ − a³)/3, per the whole revolution); the block extruded
/// 0 ≤ z ≤ 4 and spinning about y (Σ f = ρ ω² (h L (b² − a²)/2, 0,
/// (b − a) h L²/2)).
#[test]
fn the_centrifugal_forces_sum_to_the_body_force_resultant_in_every_model() {
    let (a, b, h, t, l) = (10.0, 30.0, 5.0, 2.0, 4.0);
    let w2 = STEEL.rho * 1e-12 * omega(RPM).powi(2);
    let sums = |text: String| {
        let model = common::model(&text);
        let mut f = vec![0.0; model.mesh.num_dofs()];
        model.external_force(1.0, &mut f);
        let k = model.node_dofs().per_node();
        (0..model.mesh.dim())
            .map(|c| f.iter().skip(c).step_by(k).sum::<f64>())
            .collect::<Vec<f64>>()
    };
    let spin = |c: common::CaseText, dim3: bool| {
        let c = c
            .material("block", STEEL.e, STEEL.nu)
            .with("density", STEEL.rho)
            .fixed("block.left");
        let c = if dim3 { c.with("uz", 0.0) } else { c };
        c.raw("[speed]").with("rpm", RPM).no_vtu().build()
    };
    let plane = sums(spin(
        common::case()
            .plane("stress")
            .thickness(t)
            .block("block", [a, b], [5], [0.0, h], [2]),
        false,
    ));
    let want = [
        w2 * t * h * (b * b - a * a) / 2.0,
        w2 * t * (b - a) * h * h / 2.0,
    ];
    for c in 0..2 {
        assert!(
            common::rel(plane[c], want[c]) < 1e-12,
            "plane {c}: {} vs {}",
            plane[c],
            want[c]
        );
    }
    let ring = sums(spin(
        common::case()
            .plane("axisymmetric")
            .block("block", [a, b], [5], [0.0, h], [2]),
        false,
    ));
    let want = w2 * 2.0 * std::f64::consts::PI * h * (b.powi(3) - a.powi(3)) / 3.0;
    assert!(
        common::rel(ring[0], want) < 1e-12,
        "ring: {} vs {want}",
        ring[0]
    );
    assert_eq!(ring[1], 0.0);
    let solid = sums(spin(
        common::case()
            .plane("3d")
            .raw("[mesh]\nextrude = { z = [0.0, 4.0], nz = [2] }")
            .block("block", [a, b], [5], [0.0, h], [2]),
        true,
    ));
    let want = [
        w2 * h * l * (b * b - a * a) / 2.0,
        0.0,
        w2 * (b - a) * h * l * l / 2.0,
    ];
    eprintln!("plane {plane:?}, ring {ring:?}, 3D {solid:?}");
    for c in [0, 2] {
        assert!(
            common::rel(solid[c], want[c]) < 1e-12,
            "3D {c}: {} vs {}",
            solid[c],
            want[c]
        );
    }
    assert_eq!(solid[1], 0.0);
}
