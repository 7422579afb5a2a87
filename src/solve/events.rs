//! Events of a run, each located inside the increment where it happens:
//! first yield (the root of the yield ratio, `super::yield_point`), and per
//! interface its first opening, its first full slip and its full
//! separation.
//!
//! An interface event is the sign change of a monitored scalar between the
//! committed state (load factor λₙ) and the accepted step (λₙ₊₁):
//!
//! - **first opening** of an interface that was closed (every pair in
//!   contact, u_N > 0 so p > 0, at λₙ): the smallest approach u_N over its
//!   pairs; it happens when one of them opens (u_N ≤ 0);
//! - **full slip**: the number of closed points of an interface with a
//!   tangential law that are not in macro-slip; it happens when every
//!   closed point is in macro-slip (the holding force: F_T is then μ F_N
//!   at most);
//! - **full separation**: the largest approach over the pairs; it happens
//!   when no pair is in contact any more;
//! - **first contact** of an interface open from the start (every pair
//!   with a gap, u_N < 0, and no force carried at any increment): the
//!   largest approach; it happens when one pair closes (u_N > 0).
//!
//! Only the pairs that can carry force count (`InterfaceModel::carrying_pairs`:
//! not the pair on the axis of an axisymmetric model, whose area is 0).
//!
//! Each is bracketed by bisection on the load factor: a step from the
//! committed state to the midpoint (the step the increment itself took,
//! shortened), the half in which the scalar changes sign kept, until the
//! bracket is at most `[output] event_tolerance` wide (at most
//! `MAX_HALVINGS` halvings). The steps of the search are not committed:
//! the run goes on from the accepted step as before, and the contact
//! stabilization's account is left as the step left it. A step of the search
//! that does not converge is tried once more a little off the midpoint
//! (at 0.45 of the bracket: the event itself may be a state no step reaches,
//! a stack unloaded to exactly zero); if that fails too, the search ends
//! with the bracket reached (reported as not converged). Every decision is taken on values every MPI rank holds
//! whole (displacements, statuses) and every solve is collective, so all
//! ranks search alike.

use super::{Checkpoint, Engine, State, StepFailure};
use crate::error::Result;
pub use crate::measure::gross_slip::Motion;
use crate::measure::joint::JointMeasures;
use crate::model::interface::InterfaceModel;
use crate::model::Model;
use crate::physics::contact::Status;
use crate::physics::element::solid::Response;

/// Most halvings of one search (2⁻⁵⁰ of the step: round-off).
pub(crate) const MAX_HALVINGS: usize = 50;
/// Where a halving splits its bracket: the midpoint, and, when the step
/// there does not converge, once more a little off it.
const SPLITS: [f64; 2] = [0.5, 0.45];
/// Most solves of one search.
pub(crate) const MAX_SOLVES: usize = MAX_HALVINGS * SPLITS.len();
/// Leading values of an event's row in a restart file ([`Event::pack`]);
/// the plan's record follows.
pub(crate) const FIXED: usize = 17;

/// What happened.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    FirstYield,
    FirstOpening,
    FullSlip,
    FullSeparation,
    /// An interface open from the start (every pair with a gap, none ever
    /// in contact) first closes: a gap closed, a hub heated for assembly
    /// gripping its shaft as it cools.
    FirstContact,
    /// The load a joint in full slip holds as it slides on, in the way it
    /// moved ([`plateaus`]): read off the increments at the run's end,
    /// never searched nor stored in a restart file.
    HoldingPlateau(Motion),
    /// Where a body held about the axis only by friction can no longer hold
    /// the torque on it (src/solve/limit.rs): the run ends there; never
    /// stored in a restart file (a resumed run finds it again).
    TorqueLimit,
}

impl Kind {
    /// The kinds searched during the run (and stored in restart files).
    pub(crate) const ALL: [Kind; 5] = [
        Kind::FirstYield,
        Kind::FirstOpening,
        Kind::FullSlip,
        Kind::FullSeparation,
        Kind::FirstContact,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Kind::FirstYield => "first_yield",
            Kind::FirstOpening => "first_opening",
            Kind::FullSlip => "full_slip",
            Kind::FullSeparation => "full_separation",
            Kind::FirstContact => "first_contact",
            Kind::HoldingPlateau(_) => "holding_plateau",
            Kind::TorqueLimit => "torque_limit",
        }
    }
}

/// How the event's load factor was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Regula falsi on elastic solves to |g| < 1e-9 (first yield).
    RootFinding,
    /// Bisection to the tolerance.
    Bisection,
    /// Not searched: the increment is the bracket (`locate_first_yield = false`).
    Increment,
}

impl Method {
    const ALL: [Method; 3] = [Method::RootFinding, Method::Bisection, Method::Increment];

    pub fn name(self) -> &'static str {
        match self {
            Method::RootFinding => "root-finding",
            Method::Bisection => "bisection",
            Method::Increment => "increment",
        }
    }
}

/// One located event.
#[derive(Clone, Debug, PartialEq)]
pub struct Event {
    pub kind: Kind,
    /// Its interface (none for first yield).
    pub interface: Option<usize>,
    /// The load factor (pseudo-time) reported: the end of the bracket where
    /// it has happened (first yield: the root found).
    pub load_factor: f64,
    /// The last load factor of the search where it had not happened, and
    /// the first where it had.
    pub before: f64,
    pub after: f64,
    /// The increment inside which it happened.
    pub increment: usize,
    pub method: Method,
    /// The bracket is within the tolerance (or the root was found).
    pub converged: bool,
    /// A step of the search did not converge: the bracket reached.
    pub solve_failed: bool,
    /// Where: x, y (mm), the arc length s of the pair (interface events;
    /// z in 3D, and of a first yield in 3D) and the element (first yield) or the body
    /// (torque limit); NaN where it does not apply.
    pub place: [f64; 4],
    /// total_load_kn, mean_pressure_mpa ([`super::Measures`]), and the
    /// interface's F_N, F_T and torque T (N, N, N·mm; joint convention; T
    /// is 0 without twist; NaN for first yield).
    pub values: [f64; 5],
    /// The plan's record of the state at `load_factor`.
    pub record: Vec<f64>,
}

impl Event {
    /// The body that lets go at a torque limit (its place's fourth value).
    pub fn body(&self) -> Option<usize> {
        let b = self.place[3];
        (self.kind == Kind::TorqueLimit && b >= 0.0).then_some(b as usize)
    }

    /// Its row in a restart file: `FIXED` values, then the record.
    pub fn pack(&self) -> Vec<f64> {
        let mut v = vec![
            Kind::ALL.iter().position(|&k| k == self.kind).unwrap_or(0) as f64,
            self.interface.map_or(-1.0, |i| i as f64),
            self.load_factor,
            self.before,
            self.after,
            self.increment as f64,
            Method::ALL
                .iter()
                .position(|&m| m == self.method)
                .unwrap_or(0) as f64,
            f64::from(u8::from(self.converged) + 2 * u8::from(self.solve_failed)),
        ];
        v.extend(self.place);
        v.extend(self.values);
        v.extend(&self.record);
        v
    }

    /// The events of a restart file's section (rows of [`FIXED`] + `width`
    /// values), checked against the model and the restored increments:
    /// known kinds and methods, an interface of the model for the interface
    /// events and none for first yield, each event once, an increment of
    /// the curve, finite load factors, and no infinite value.
    pub(crate) fn unpack(
        v: &[f64],
        width: usize,
        model: &Model,
        load_factors: &[f64],
    ) -> std::result::Result<Vec<Event>, String> {
        let increments = load_factors.len();
        let row = FIXED + width;
        if v.len() % row != 0 {
            return Err(format!(
                "section events has {} values, not a whole number of rows of {row}",
                v.len()
            ));
        }
        let code = |x: f64, n: usize| -> Option<usize> {
            (x >= 0.0 && x < n as f64 && x.fract() == 0.0).then_some(x as usize)
        };
        let mut out: Vec<Event> = Vec::new();
        for (k, r) in v.chunks_exact(row).enumerate() {
            let bad = |what: &str| format!("section events: event {}: {what}", k + 1);
            if let Some(x) = r.iter().find(|x| x.is_infinite()) {
                return Err(bad(&format!("a value {x}")));
            }
            let kind = code(r[0], Kind::ALL.len())
                .map(|c| Kind::ALL[c])
                .ok_or_else(|| bad("no such kind"))?;
            let interface = match (kind, r[1]) {
                (Kind::FirstYield, -1.0) => None,
                (Kind::FirstYield, _) => return Err(bad("first yield names an interface")),
                (_, x) => {
                    Some(code(x, model.interfaces.len()).ok_or_else(|| bad("no such interface"))?)
                }
            };
            if r[2..5].iter().any(|x| !x.is_finite()) {
                return Err(bad("a load factor is not finite"));
            }
            let increment = code(r[5], increments + 1)
                .filter(|&i| i >= 1)
                .ok_or_else(|| bad("not an increment of the curve"))?;
            let method = code(r[6], Method::ALL.len())
                .map(|c| Method::ALL[c])
                .ok_or_else(|| bad("no such method"))?;
            let flags = code(r[7], 4).ok_or_else(|| bad("no such flags"))?;
            if out
                .iter()
                .any(|e| e.kind == kind && e.interface == interface)
            {
                return Err(bad("appears twice"));
            }
            // the bracket is ascending, holds the event, and lies within
            // the run's pseudo-times; the place is a place of the model
            // (within its increment: from the load factor before it to its own)
            let (lf, lo, hi) = (r[2], r[3], r[4]);
            let top = load_factors[increment - 1];
            let bottom = if increment > 1 {
                load_factors[increment - 2]
            } else {
                0.0
            };
            let slack = 1e-12 * top.abs().max(1.0);
            if !(lo <= lf && lf <= hi && lo >= bottom - slack && hi <= top + slack) {
                return Err(bad(&format!(
                    "load factor {lf} outside its bracket [{lo}, {hi}] or its increment {increment} ({bottom} … {top})"
                )));
            }
            let coordinate = crate::input::case::ranges::COORDINATE;
            if r[8..11]
                .iter()
                .any(|&x| !(x.is_nan() || coordinate.admits(x) || x == 0.0))
            {
                return Err(bad("a place outside any model"));
            }
            if kind == Kind::FirstYield
                && !(r[11].is_nan() || code(r[11], model.mesh.elements.len()).is_some())
            {
                return Err(bad("no such element"));
            }
            out.push(Event {
                kind,
                interface,
                load_factor: r[2],
                before: r[3],
                after: r[4],
                increment,
                method,
                converged: flags & 1 == 1,
                solve_failed: flags & 2 == 2,
                place: [r[8], r[9], r[10], r[11]],
                values: [r[12], r[13], r[14], r[15], r[16]],
                record: r[FIXED..].to_vec(),
            });
        }
        Ok(out)
    }
}

/// Whether an event of this kind (and interface) was found already.
fn found(events: &[Event], kind: Kind, interface: Option<usize>) -> bool {
    events
        .iter()
        .any(|e| e.kind == kind && e.interface == interface)
}

/// The first-yield event: from the root-finding search (`bracket`: the last
/// load factors below and above it, `state`: the solution at the root) or,
/// without the search, the increment (`state`: the accepted step).
pub(super) fn first_yield(
    engine: &Engine,
    fy: Option<&super::FirstYield>,
    bracket: [f64; 2],
    root: bool,
    state: &State,
    increment: usize,
) -> Event {
    let model = engine.model;
    let m = engine.measures(state);
    let (method, load_factor, place) = match fy {
        Some(fy) => (
            Method::RootFinding,
            fy.load_factor,
            [
                fy.x,
                model.surface_y - fy.depth,
                if model.mesh.dim() == 3 {
                    fy.z
                } else {
                    f64::NAN
                },
                fy.element as f64,
            ],
        ),
        None => {
            let (_, e, ip) = engine.max_yield_ratio(state);
            let x = model.point_x(e, ip);
            (
                Method::Increment,
                bracket[1],
                [
                    x[0],
                    x[1],
                    if model.mesh.dim() == 3 {
                        x[2]
                    } else {
                        f64::NAN
                    },
                    e as f64,
                ],
            )
        }
    };
    Event {
        kind: Kind::FirstYield,
        interface: None,
        load_factor,
        before: bracket[0],
        after: bracket[1],
        increment,
        method,
        converged: root || (bracket[1] - bracket[0]).abs() <= model.plan.event_tolerance,
        solve_failed: false,
        place,
        values: [
            m.total_load_kn,
            m.mean_pressure,
            f64::NAN,
            f64::NAN,
            f64::NAN,
        ],
        record: engine.record(state),
    }
}

/// The approach of every pair of an interface in a state (NaN for a pair
/// that carries nothing).
fn approaches(im: &InterfaceModel, carrying: &[bool], state: &State) -> Vec<f64> {
    let gap = im.gap_at(state.time);
    im.pairs
        .iter()
        .zip(carrying)
        .map(|(p, &c)| {
            if c {
                im.pair_approach_at(p, &state.u, gap)
            } else {
                f64::NAN
            }
        })
        .collect()
}

/// The monitor of one interface event, armed at the committed state.
struct Monitor {
    kind: Kind,
    interface: usize,
    /// The pairs that can carry force.
    carrying: Vec<bool>,
    /// The interface's first point in the states' point arrays.
    base: usize,
}

impl Monitor {
    /// The monitor of `kind` on interface `i`, if it can happen from the
    /// committed state (something in contact to open or separate, a
    /// tangential law not yet fully slipping, every pair open with a gap on
    /// an interface that never carried a force, `touched` false).
    fn armed(
        model: &Model,
        (kind, i, base): (Kind, usize, usize),
        committed: &State,
        touched: bool,
    ) -> Option<Self> {
        let im = &model.interfaces[i];
        let carrying = im.carrying_pairs();
        let a = approaches(im, &carrying, committed);
        let closed = a.iter().filter(|&&x| x > 0.0).count();
        let carried = carrying.iter().filter(|&&c| c).count();
        let m = Monitor {
            kind,
            interface: i,
            carrying,
            base,
        };
        let ready = match kind {
            Kind::FirstOpening => closed > 0 && closed == carried,
            Kind::FullSeparation => closed > 0,
            Kind::FirstContact => {
                !touched && carried > 0 && a.iter().all(|&x| x.is_nan() || x < 0.0)
            }
            Kind::FullSlip => im.tangential.is_some() && !m.happened(model, committed),
            Kind::FirstYield | Kind::HoldingPlateau(_) | Kind::TorqueLimit => false,
        };
        ready.then_some(m)
    }

    /// The scalar's sign: has the event happened in `state`?
    fn happened(&self, model: &Model, state: &State) -> bool {
        let im = &model.interfaces[self.interface];
        match self.kind {
            Kind::FirstOpening => approaches(im, &self.carrying, state)
                .iter()
                .any(|&a| a <= 0.0),
            Kind::FullSeparation => !approaches(im, &self.carrying, state)
                .iter()
                .any(|&a| a > 0.0),
            Kind::FirstContact => approaches(im, &self.carrying, state)
                .iter()
                .any(|&a| a > 0.0),
            Kind::FullSlip => {
                let st = &state.status[self.base..self.base + im.points.len()];
                let closed = st.iter().filter(|&&s| s != Status::Open).count();
                closed > 0
                    && st
                        .iter()
                        .all(|&s| s == Status::Open || s == Status::MacroSlip)
            }
            Kind::FirstYield | Kind::HoldingPlateau(_) | Kind::TorqueLimit => false,
        }
    }

    /// Where, in the states on either side of the bracket: the first pair
    /// to open (the smallest approach after), the last in contact (the
    /// largest approach before), none for full slip; the lowest pair on a tie.
    /// Its x, y and arc length s, or in 3D (where a face has no arc length)
    /// its x, y and z.
    fn place(&self, model: &Model, before: &State, after: &State) -> [f64; 4] {
        let im = &model.interfaces[self.interface];
        let arc = &model.plan.arcs[self.interface];
        let space = model.mesh.dim() == 3;
        let pick = |k: Option<usize>| {
            k.map_or([f64::NAN; 4], |k| {
                let x = im.pairs[k].x;
                let third = if space {
                    x[2]
                } else {
                    arc.get(k).copied().unwrap_or(f64::NAN)
                };
                [x[0], x[1], third, f64::NAN]
            })
        };
        match self.kind {
            Kind::FirstOpening => {
                let a = approaches(im, &self.carrying, after);
                pick(
                    (0..a.len())
                        .filter(|&k| !a[k].is_nan())
                        .min_by(|&x, &y| a[x].total_cmp(&a[y])),
                )
            }
            // the pair first in contact: the largest approach after
            Kind::FirstContact => {
                let a = approaches(im, &self.carrying, after);
                pick(
                    (0..a.len())
                        .filter(|&k| !a[k].is_nan())
                        .max_by(|&x, &y| a[x].total_cmp(&a[y]).then(y.cmp(&x))),
                )
            }
            Kind::FullSeparation => {
                let a = approaches(im, &self.carrying, before);
                pick(
                    (0..a.len())
                        .filter(|&k| !a[k].is_nan())
                        .max_by(|&x, &y| a[x].total_cmp(&a[y]).then(y.cmp(&x))),
                )
            }
            _ => [f64::NAN; 4],
        }
    }
}

/// Whether nothing loads the model at pseudo-time t: no load pattern, no
/// prescribed displacement, no temperature and no interference acts there,
/// so the unloaded mesh is the equilibrium at t.
fn at_rest(model: &Model, t: f64) -> bool {
    let loads =
        (model.patterns()).any(|(s, f)| model.scale(s, t) != 0.0 && f.iter().any(|&v| v != 0.0));
    let moved = (model.prescribed.iter().zip(&model.prescribed_history))
        .any(|(&(_, v), &h)| v != 0.0 && model.factor(h, t) != 0.0);
    let heated = model.thermal_strains(t).iter().any(|&e| e != 0.0);
    let pressed = model.interfaces.iter().any(|im| im.gap_at(t) < 0.0);
    !(loads || moved || heated || pressed)
}

/// What an accepted step's search found.
pub(super) enum Found {
    Events(Vec<Event>),
    /// A second stop signal abandoned the search.
    Interrupted(i32),
}

/// The interface events that happen between the committed state and the
/// accepted step `trial` at `target`, each located by bisection.
pub(super) fn search(
    engine: &mut Engine,
    ck: &Checkpoint,
    trial: &State,
    target: f64,
    increment: usize,
) -> Result<Found> {
    let model = engine.model;
    let mut monitors = Vec::new();
    let mut base = 0;
    // an event starts from a converged state: the run's first step starts
    // from the unloaded mesh, which is one only where nothing loads it at
    // λ = 0 (a hub hot at the start of a heat assembly is not yet
    // expanded there, its drawn interference no contact)
    if ck.increments.is_empty() && !at_rest(model, ck.lambda) {
        return Ok(Found::Events(Vec::new()));
    }
    for (i, im) in model.interfaces.iter().enumerate() {
        // an interface that carried a force at some increment has been in
        // contact: its closing again is no first contact
        // (once its first contact is found it has, and the increments need
        // not be read again)
        let touched = found(&ck.events, Kind::FirstContact, Some(i))
            || (ck.increments.iter())
                .any(|inc| inc.joints.get(i).is_some_and(|j| j.normal_force != 0.0));
        for kind in [
            Kind::FirstContact,
            Kind::FirstOpening,
            Kind::FullSlip,
            Kind::FullSeparation,
        ] {
            if found(&ck.events, kind, Some(i)) {
                continue;
            }
            if let Some(m) = Monitor::armed(model, (kind, i, base), &ck.committed, touched) {
                if m.happened(model, trial) {
                    monitors.push(m);
                }
            }
        }
        base += im.points.len();
    }
    if monitors.is_empty() {
        return Ok(Found::Events(Vec::new()));
    }
    // the search's steps leave the stabilization as the accepted step left it
    let saved = engine.stabilizer.clone();
    // and count apart from the run's own iterations
    let before = engine.stats.iterations;
    let mut out = Vec::new();
    let mut result = Ok(());
    for m in &monitors {
        match bisect(engine, ck, trial, target, increment, m) {
            Ok(Ok(e)) => out.push(e),
            Ok(Err(signal)) => {
                result = Err(signal);
                break;
            }
            Err(e) => {
                engine.stabilizer = saved;
                engine.stats.event_iterations += engine.stats.iterations - before;
                return Err(e);
            }
        }
    }
    engine.stabilizer = saved;
    engine.stats.event_iterations += engine.stats.iterations - before;
    Ok(match result {
        Ok(()) => Found::Events(out),
        Err(signal) => Found::Interrupted(signal),
    })
}

/// Brackets one event between the committed state and `trial`.
fn bisect(
    engine: &mut Engine,
    ck: &Checkpoint,
    trial: &State,
    target: f64,
    increment: usize,
    m: &Monitor,
) -> Result<std::result::Result<Event, i32>> {
    let model = engine.model;
    let tol = model.plan.event_tolerance;
    let (lambda0, committed) = (ck.lambda, &ck.committed);
    let (mut a, mut b) = (lambda0, target);
    let (mut sa, mut sb) = (committed.clone(), trial.clone());
    let mut failed = false;
    'halving: for _ in 0..MAX_HALVINGS {
        if (b - a).abs() <= tol {
            break;
        }
        // the midpoint, or off it when its step does not converge (the
        // event itself may be a state the step cannot reach: a stack
        // unloaded to exactly zero)
        for split in SPLITS {
            let c = a + split * (b - a);
            if c == a || c == b {
                break 'halving;
            }
            // from the straight line between the two ends of the step
            let w = (c - lambda0) / (target - lambda0);
            let start: Vec<f64> = committed
                .u
                .iter()
                .zip(&trial.u)
                .map(|(u0, u1)| u0 + w * (u1 - u0))
                .collect();
            match engine.step_from(committed, c, Response::Plastic, Some(&start)) {
                Ok((s, _)) => {
                    if m.happened(model, &s) {
                        (b, sb) = (c, s);
                    } else {
                        (a, sa) = (c, s);
                    }
                    continue 'halving;
                }
                Err(StepFailure::Interrupted { signal, .. }) => return Ok(Err(signal)),
                Err(f) if f.is_fatal() => return Err(f.into_error()),
                Err(_) => {}
            }
        }
        failed = true;
        break;
    }
    let i = m.interface;
    let meas = engine.measures(&sb);
    let j = joint_in(model, &sb, i);
    Ok(Ok(Event {
        kind: m.kind,
        interface: Some(i),
        load_factor: b,
        before: a,
        after: b,
        increment,
        method: Method::Bisection,
        converged: (b - a).abs() <= tol,
        solve_failed: failed,
        place: m.place(model, &sa, &sb),
        values: [
            meas.total_load_kn,
            meas.mean_pressure,
            j.normal_force,
            j.tangential_force,
            j.torque,
        ],
        record: engine.record(&sb),
    }))
}

/// Interface `i`'s joint measures (forces, torque, status shares) in a
/// state.
pub(super) fn joint_in(model: &Model, state: &State, i: usize) -> JointMeasures {
    let base: usize = model.interfaces[..i].iter().map(|im| im.points.len()).sum();
    let points = base..base + model.interfaces[i].points.len();
    let joint = crate::measure::joint::measures(
        &model.interfaces[i..=i],
        model.section,
        state.time,
        &state.u,
        &state.status[points.clone()],
        &state.contact[points],
        &[],
    );
    joint.first().copied().unwrap_or_default()
}

/// Within this share of its largest value a joint's held load is on its
/// plateau: the Newton tolerance leaves a sliding joint's force steady to
/// about 1e-8 of the loads, a plateau of a rate-independent law is flat to
/// that; 1e-3 also takes in a plateau that still creeps as a pressure
/// settles (a pressed fit's edges).
pub const PLATEAU: f64 = 1e-3;

/// The holding plateaus of a finished run's interfaces: for each way a
/// joint moved while it slipped as a whole ([`crate::measure::gross_slip`]:
/// turned, or pushed along its tangent), the largest load it held in that
/// motion (|T| turning, |F_T| pushed), located at the first such increment
/// within [`PLATEAU`] of it, when a later increment of the same motion is
/// within it too: the joint held that load as it slid on. A joint that
/// first slips as a whole and then takes more (the axial friction a
/// pressing locked in sliding out under the torque) reaches its plateau
/// after its full slip; a load still rising at its last slipping increment
/// is no plateau and gives none. Located to the increment (method
/// `increment`: its bracket is the increment); read at the run's end from
/// the increments, so a resumed run finds them alike.
pub fn plateaus(model: &Model, increments: &[super::Increment]) -> Vec<Event> {
    let mut out = Vec::new();
    for (i, im) in model.interfaces.iter().enumerate() {
        if im.tangential.is_none() {
            continue;
        }
        let series: Vec<_> = increments
            .iter()
            .filter_map(|inc| inc.joints.get(i))
            .collect();
        for motion in [Motion::Turning, Motion::Pushing] {
            if !crate::measure::gross_slip::imposed(model, i, motion) {
                continue;
            }
            let held = crate::measure::gross_slip::held(&series, motion);
            let top = held.iter().map(|h| h.1).fold(0.0, f64::max);
            let on: Vec<usize> = held
                .iter()
                .filter(|h| top > 0.0 && h.1 >= (1.0 - PLATEAU) * top)
                .map(|h| h.0)
                .collect();
            if on.len() < 2 {
                continue;
            }
            out.push(plateau(i, motion, on[0], increments));
        }
    }
    out
}

/// The plateau event of interface `i` at increment `k` (0-based).
fn plateau(i: usize, motion: Motion, k: usize, increments: &[super::Increment]) -> Event {
    let inc = &increments[k];
    let j = &inc.joints[i];
    let before = if k == 0 {
        0.0
    } else {
        increments[k - 1].load_factor
    };
    Event {
        kind: Kind::HoldingPlateau(motion),
        interface: Some(i),
        load_factor: inc.load_factor,
        before,
        after: inc.load_factor,
        increment: inc.increment,
        method: Method::Increment,
        converged: true,
        solve_failed: false,
        place: [f64::NAN; 4],
        values: [
            inc.measures.total_load_kn,
            inc.measures.mean_pressure,
            j.normal_force,
            j.tangential_force,
            j.torque,
        ],
        record: inc.record.clone(),
    }
}
