//! The load-increment loop (paper section 4): scheduled load factors, Newton
//! steps with the status check, automatic cutback of a failed step with the
//! committed state restored, and the location of first yield.

mod accelerate;
mod checkpoint;
pub mod events;
mod limit;
pub mod newton;
pub mod stabilization;
pub mod stepping;
pub(crate) mod yield_point;

pub use crate::input::case::settings::{Method, StepControl};
pub(crate) use crate::linalg::failure::StepFailure;
pub(crate) use crate::measure::joint_measures;
pub use crate::measure::Measures;
pub use crate::model::state::State;
pub use checkpoint::Checkpoint;
use checkpoint::{write_increment, write_last_state, written_everywhere};
pub use newton::Engine;
pub(crate) use newton::Stats;
pub use yield_point::FirstYield;

use crate::error::{Error, Result};
use crate::interrupt::Stop;
use crate::measure::joint::{self, JointMeasures};
use crate::model::Model;

use crate::physics::element::solid::Response;
use crate::physics::material::{PointState, VonMises};

/// What is recorded for each converged increment.
#[derive(Clone, Debug)]
pub struct Increment {
    pub increment: usize,
    pub load_factor: f64,
    pub iterations: usize,
    /// Failed attempts (cutbacks) before this increment converged.
    pub cutbacks: usize,
    pub measures: Measures,
    /// Joint quantities of every interface, in order
    /// ([`crate::measure::joint`]).
    pub joints: Vec<JointMeasures>,
    /// Every pretension section's [force (N), shortening (mm)], in order.
    pub sections: Vec<[f64; 2]>,
    /// The designer's outputs of the state ([`crate::model::outputs`]), the
    /// model's record width.
    pub record: Vec<f64>,
    /// The largest von Mises stress away from the start mesh's singular
    /// points (MPa, [`crate::model::excluded`]), where the model measures it
    /// (`[adapt] quantity = "max_von_mises"`); NaN otherwise, and in the
    /// increments a restart file gives back (an adaptive run is never
    /// resumed).
    pub von_mises_away: f64,
}

/// Callbacks of a run (progress, output).
pub trait Observer {
    fn increment(&mut self, model: &Model, state: &State, inc: &Increment) -> Result<()>;
    /// A step from `from` to `to` failed or was rejected; `next` is the
    /// target tried next (the midpoint under fixed steps, the automatic
    /// control's choice otherwise).
    fn cutback(&mut self, _from: f64, _to: f64, _next: f64, _reason: &str) {}
    /// Called after every converged increment with everything needed to resume
    /// the run from it (the writer stores it as `restart.bin`).
    fn checkpoint(&mut self, _model: &Model, _ck: &Checkpoint) -> Result<()> {
        Ok(())
    }
    /// Called once when a run stops early (signal, `--stop-after`) after at
    /// least one increment: the last converged state, which the output
    /// always shows (the writer adds its VTU file if `vtu_every` skipped it);
    /// [`Observer::checkpoint`] follows. Also called, without a checkpoint,
    /// when a resumed run has no increment left to solve (the writer then
    /// estimates its error, [`crate::measure::estimate`]).
    fn last_state(&mut self, _model: &Model, _state: &State, _inc: &Increment) -> Result<()> {
        Ok(())
    }
    /// Called once at the end of a run that did not fail: every increment's
    /// output is complete when it returns (the writer's thread drained), or
    /// the first write that failed.
    fn flush(&mut self) -> Result<()> {
        Ok(())
    }
}

/// How a run may stop early.
#[derive(Clone, Copy, Debug, Default)]
pub struct Control {
    /// Stop (like SIGINT) once this many increments have converged.
    pub stop_after: Option<usize>,
}

/// The outcome of a run.
#[derive(Clone, Debug)]
pub struct RunResult {
    pub backend: String,
    /// "builtin" or "snes".
    pub nonlinear_solver: String,
    /// e.g. "faer sparse LU", "preonly + lu (mumps)", "cg + gamg".
    pub linear_solver: String,
    pub ranks: usize,
    /// Threads of each process's element loop.
    pub threads: usize,
    /// Peak resident memory summed over ranks (VmHWM), MB; 0 where unknown.
    pub peak_memory_mb: f64,
    pub backend_stats: Vec<(String, f64)>,
    pub increments: Vec<Increment>,
    pub first_yield: Option<FirstYield>,
    pub stats: Stats,
    pub cutbacks: usize,
    /// The last committed state (under MPI: with this rank's Gauss states).
    pub final_state: State,
    /// Why the run stopped before the end of its schedule (None: complete).
    pub stopped: Option<Stop>,
    /// Increments taken over from a restart file (0: a fresh run).
    pub resumed_from: usize,
    /// The contact stabilization's account, when any step used it.
    pub stabilization: Option<stabilization::Report>,
    /// The largest approach and pressure of every interface over the run
    /// ([`Checkpoint::table_reach`]).
    pub table_reach: Vec<crate::model::interface::extrapolation::Reach>,
    /// The events located ([`events`]), in the order found.
    pub events: Vec<events::Event>,
    /// The error estimate of the last increment, where the run's writer made
    /// one (the process that writes the output; [`crate::measure::estimate`]).
    pub estimate: Option<crate::measure::estimate::Estimate>,
}

impl RunResult {
    /// The closed load cycles of every interface ([`joint::cycles`]: one
    /// list per interface, empty without histories that return).
    pub fn cycles(&self, model: &Model) -> Vec<Vec<joint::Cycle>> {
        cycles(model, &self.increments)
    }
}

/// The closed load cycles of every interface over `increments`, in order
/// ([`joint::cycles`]).
pub fn cycles(model: &Model, increments: &[Increment]) -> Vec<Vec<joint::Cycle>> {
    let times: Vec<f64> = increments.iter().map(|i| i.load_factor).collect();
    let joints: Vec<&[JointMeasures]> = increments.iter().map(|i| i.joints.as_slice()).collect();
    joint::cycles(
        &times,
        &joints,
        &model.breakpoints(),
        |t| model.history_values(t),
        model.interfaces.len(),
    )
}

/// Runs the whole load history with a given engine (any backend). Under MPI
/// every rank calls this; only rank 0's observer writes, and its outcome is
/// shared so that a failed write stops every rank.
pub fn run_with(engine: Engine, observer: &mut dyn Observer) -> Result<RunResult> {
    let start = Checkpoint::initial(engine.model);
    run_from(engine, observer, start, Control::default())
}

/// Runs the load history from a checkpoint (the initial one or one read from
/// `restart.bin`). Stops early, with `stopped` set, at an increment boundary
/// after a SIGINT/SIGTERM (any rank) or `control.stop_after` increments; a
/// second signal abandons the increment in progress.
///
/// Each pass of the loop: the collective stop decision, one attempt at the
/// next load factor (`attempt`), then either its acceptance (`accept`:
/// first yield, commit, output) or a cutback (`cut_back`). The stepper is
/// only changed once the step's fate is known, so an interrupted step leaves
/// it (and the checkpoint) as it was.
pub fn run_from(
    mut engine: Engine,
    observer: &mut dyn Observer,
    start: Checkpoint,
    control: Control,
) -> Result<RunResult> {
    let resumed_from = start.increments.len();
    let mut ck = start;
    engine.localize(&mut ck.committed);
    engine.stats.iterations = ck.iterations;
    engine.stats.factorizations = ck.factorizations;
    engine.stats.event_iterations = ck.event_iterations;
    engine.stats.interface = ck.interface.clone();
    let mut stopped = None;
    let mut limit_event = None;
    while let Some(target) = ck.stepper.next(ck.lambda) {
        if ck.increments.len() >= crate::input::case::MAX_INCREMENTS {
            // the automatic step control kept its steps tiny: a bound on
            // the run's length (identical on every rank)
            return Err(Error::Convergence {
                increment: ck.increments.len() + 1,
                load_factor: target,
                message: format!(
                    "{} increments converged without reaching the end of the load history (the limit): the steps stayed tiny; raise [solver] max_increment or refine less",
                    ck.increments.len()
                ),
            });
        }
        if let Some(stop) = stop_at_boundary(&engine, &ck, control) {
            stopped = Some(stop);
            break;
        }
        let why = match attempt(&mut engine, &ck, target)? {
            Ok((trial, iterations)) => {
                match accept(&mut engine, observer, &mut ck, trial, target, iterations)? {
                    Accepted::Yes => {
                        if ck.increments.len() == resumed_from + 1 {
                            engine
                                .stats
                                .memory_mb
                                .push(("first_increment", peak_memory_mb()));
                        }
                        continue;
                    }
                    Accepted::Interrupted(signal) => {
                        stopped = Some(Stop::Signal(signal));
                        break;
                    }
                    Accepted::No(why) => why,
                }
            }
            Err(StepFailure::Interrupted { signal, .. }) => {
                stopped = Some(Stop::Signal(signal));
                break;
            }
            Err(failure) => (stepping::Why::Failed, failure.to_string()),
        };
        if let Err(e) = cut_back(&mut ck, observer, target, why) {
            // steps that fail however short: at a torque limit the run ends
            // (none before the first increment: there is nothing to write)
            let located = if ck.increments.is_empty() {
                None
            } else {
                limit::locate(&mut engine, &ck, target)?
            };
            match located {
                Some(limit::Limited::At(event)) => {
                    limit_event = Some(event);
                    stopped = Some(Stop::TorqueLimit);
                }
                Some(limit::Limited::Interrupted(signal)) => stopped = Some(Stop::Signal(signal)),
                None => return Err(e),
            }
            break;
        }
    }
    if stopped.is_some() && ck.increments.len() > resumed_from {
        write_last_state(&engine, observer, &mut ck)?;
    } else if resumed_from > 0 && ck.increments.len() == resumed_from {
        // a resumed run that solved nothing more: the writer still sees its
        // last state (the error estimate of summary.json), and writes no
        // file it already has
        let model = engine.model;
        written_everywhere(&engine, &mut ck, |ck| match ck.increments.last() {
            Some(inc) => observer.last_state(model, &ck.committed, inc),
            None => Ok(()),
        })?;
    }
    // the writer's thread done: every file complete, or the run's error on
    // every rank
    let flushed = observer.flush();
    if !engine.backend.agree(flushed.is_ok()) {
        return Err(flushed
            .err()
            .unwrap_or_else(|| Error::Output("writing the output failed on rank 0".into())));
    }
    Ok(finish(engine, ck, (stopped, limit_event), resumed_from))
}

/// The stop decision at an increment boundary, collective: `--stop-after`
/// reached, or a stop signal on any rank.
fn stop_at_boundary(engine: &Engine, ck: &Checkpoint, control: Control) -> Option<Stop> {
    if let Some(n) = control.stop_after {
        if ck.increments.len() >= n {
            return Some(Stop::StopAfter(n));
        }
    }
    let mut flag = [
        crate::interrupt::requested() as f64,
        f64::from(crate::interrupt::first_signal()),
    ];
    engine.backend.max(&mut flag);
    (flag[0] >= 1.0).then(|| Stop::Signal(flag[1] as i32))
}

/// One step to `target` from the committed state: from the predictor's start,
/// and again from the committed state when that fails (before any cutback).
/// The outer error is a failure no cutback can cure (memory).
fn attempt(
    engine: &mut Engine,
    ck: &Checkpoint,
    target: f64,
) -> Result<std::result::Result<(State, usize), StepFailure>> {
    // at a history breakpoint the load path may turn: the last increment
    // says nothing about the next one
    let turning = engine.model.breakpoints().contains(&ck.lambda);
    let start = if turning {
        None
    } else {
        predict(&ck.committed, &ck.last_du, ck.last_step, target - ck.lambda)
    };
    let mut outcome = engine.step_from(&ck.committed, target, Response::Plastic, start.as_deref());
    if start.is_some()
        && outcome
            .as_ref()
            .is_err_and(|f| f.signal().is_none() && !f.is_fatal())
    {
        // the extrapolated start led astray (a status change the last
        // increment did not foresee): the same step from the committed
        // state, as without a predictor, before any cutback
        engine.stats.predictor_restarts += 1;
        outcome = engine.step(&ck.committed, target, Response::Plastic);
    }
    match outcome {
        // no smaller step needs less memory: the run ends here
        Err(f) if f.is_fatal() => Err(f.into_error()),
        outcome => Ok(outcome),
    }
}

/// The converged state before the committed one, (load factor,
/// displacements) = (λ_n − Δλ_prev, u_n − Δu_prev), where the predictor
/// would extrapolate from it ([`predict`]: not at a history breakpoint, nor
/// after a step the stabilization held, nor before the second increment).
/// Before first yield it is an elastic solution, the one before the
/// committed state: the first-yield search starts its first elastic solve
/// from the two ([`yield_point::locate`]).
fn elastic_before(model: &Model, ck: &Checkpoint) -> Option<(f64, Vec<f64>)> {
    let usable = ck.last_step > 0.0
        && ck.last_du.len() == ck.committed.u.len()
        && !model.breakpoints().contains(&ck.lambda);
    usable.then(|| {
        let u = ck.committed.u.iter().zip(&ck.last_du);
        (ck.lambda - ck.last_step, u.map(|(u, d)| u - d).collect())
    })
}

/// What became of a converged step.
enum Accepted {
    /// Committed and written.
    Yes,
    /// Redone smaller, for this reason.
    No((stepping::Why, String)),
    /// A second stop signal abandoned the first-yield search.
    Interrupted(i32),
}

/// A converged step to `target`: rejected when its plastic strain increment
/// is too large for the automatic control, else first yield located inside it
/// (if it is there), the state committed, the increment recorded and written.
fn accept(
    engine: &mut Engine,
    observer: &mut dyn Observer,
    ck: &mut Checkpoint,
    trial: State,
    target: f64,
    iterations: usize,
) -> Result<Accepted> {
    // each rank holds its elements' Gauss states: maxima over all ranks
    let dpeeq = engine.max_over_points(
        trial
            .gauss
            .iter()
            .zip(&ck.committed.gauss)
            .map(|(t, c)| t.peeq - c.peeq),
    );
    if ck.stepper.too_plastic(ck.lambda, target, dpeeq) {
        let reason =
            format!("largest plastic strain increment {dpeeq:.2e} above 3 × plastic_strain_step");
        return Ok(Accepted::No((stepping::Why::TooPlastic(dpeeq), reason)));
    }
    let increment = ck.increments.len() + 1;
    let (found, located) = match step_events(engine, ck, &trial, target, increment)? {
        StepEvents::Found(found, located) => (found, located),
        StepEvents::Interrupted(signal) => return Ok(Accepted::Interrupted(signal)),
    };
    ck.events.extend(found);
    if located.is_some() {
        ck.first_yield = located;
    }
    let step = Step {
        target,
        iterations,
        dpeeq,
    };
    commit(engine, ck, trial, step);
    let inc = increment_row(engine, ck, iterations);
    ck.cutbacks_here = 0;
    ck.iterations = engine.stats.iterations;
    ck.factorizations = engine.stats.factorizations;
    ck.event_iterations = engine.stats.event_iterations;
    ck.interface = engine.stats.interface.clone();
    write_increment(engine, observer, ck, inc)?;
    Ok(Accepted::Yes)
}

/// An accepted step's events, in the order of their load factors along the
/// step: first yield (located by root finding when the case asks for it)
/// and the interface events ([`events::search`]), with the first yield to
/// keep once the whole step is accepted.
fn step_events(
    engine: &mut Engine,
    ck: &mut Checkpoint,
    trial: &State,
    target: f64,
    increment: usize,
) -> Result<StepEvents> {
    let model = engine.model;
    let yielded_now = ck.first_yield.is_none()
        && engine.max_over_points(trial.gauss.iter().map(|g| g.peeq)) > 0.0;
    let mut found = Vec::new();
    // kept once the whole step is accepted (the event search may still be
    // interrupted: the checkpoint then stays the committed one)
    let mut located = None;
    if yielded_now && model.solver.locate_first_yield {
        match yield_point::locate(
            engine,
            &ck.committed,
            (ck.lambda, ck.elastic_ratio_prev),
            target,
            elastic_before(model, ck),
        ) {
            Ok(at) => {
                found.push(events::first_yield(
                    engine,
                    Some(&at.first_yield),
                    at.bracket,
                    at.root,
                    &at.state,
                    increment,
                ));
                located = Some(at.first_yield);
            }
            Err((_, StepFailure::Interrupted { signal, .. })) => {
                return Ok(StepEvents::Interrupted(signal))
            }
            Err((load_factor, f)) => {
                return Err(Error::Convergence {
                    increment: 0,
                    load_factor,
                    message: format!("elastic solve while locating first yield: {f}"),
                })
            }
        }
    } else if ck.first_yield.is_none() {
        if yielded_now && !ck.events.iter().any(|e| e.kind == events::Kind::FirstYield) {
            // not searched (locate_first_yield = false): the increment
            found.push(events::first_yield(
                engine,
                None,
                [ck.lambda, target],
                false,
                trial,
                increment,
            ));
        }
        ck.elastic_ratio_prev = engine.max_yield_ratio(trial).0;
    }
    match events::search(engine, ck, trial, target, increment)? {
        events::Found::Events(e) => found.extend(e),
        events::Found::Interrupted(signal) => return Ok(StepEvents::Interrupted(signal)),
    }
    // in the order of their load factors along the step
    found.sort_by(|a, b| {
        ((a.load_factor - ck.lambda).abs()).total_cmp(&(b.load_factor - ck.lambda).abs())
    });
    Ok(StepEvents::Found(found, located))
}

/// What [`step_events`] found.
enum StepEvents {
    /// The events, and the first yield located (kept once the step is accepted).
    Found(Vec<events::Event>, Option<FirstYield>),
    /// A second stop signal abandoned a search.
    Interrupted(i32),
}

/// A converged step's numbers as [`commit`] takes them.
#[derive(Clone, Copy)]
struct Step {
    target: f64,
    iterations: usize,
    /// The largest plastic strain increment of the step.
    dpeeq: f64,
}

/// Commits `trial` as the converged state at `step.target`: the stepper
/// told, the step's displacement kept for the predictor, the joints'
/// totals accumulated and the tables' reach widened.
fn commit(engine: &mut Engine, ck: &mut Checkpoint, trial: State, step: Step) {
    let model = engine.model;
    let Step {
        target,
        iterations,
        dpeeq,
    } = step;
    ck.stepper.accepted(ck.lambda, target, iterations, dpeeq);
    ck.last_du.clear();
    ck.last_du
        .extend(trial.u.iter().zip(&ck.committed.u).map(|(a, b)| a - b));
    // every rank holds every point's tangential state (share_state) and
    // every dof: the same totals everywhere
    joint::accumulate(
        &model.interfaces,
        joint::Snapshot::of(&ck.committed.u, ck.committed.time, &ck.committed.contact),
        joint::Snapshot::of(&trial.u, trial.time, &trial.contact),
        &mut ck.joint_totals,
    );
    ck.committed = trial;
    for (r, im) in ck.table_reach.iter_mut().zip(&model.interfaces) {
        *r = r.max(crate::model::interface::extrapolation::Reach::of(
            im,
            &ck.committed.u,
            ck.committed.time,
        ));
    }
    if !engine.committed() {
        // a stabilized or released step closed a gap by a rigid motion: the
        // next step starts from the committed state, not an extrapolation
        ck.last_du.clear();
    }
    ck.last_step = target - ck.lambda;
    ck.lambda = target;
}

/// The increment's row of the run: its measures, the joints', the
/// pretension sections' and the record of the committed state.
fn increment_row(engine: &Engine, ck: &Checkpoint, iterations: usize) -> Increment {
    let model = engine.model;
    Increment {
        increment: ck.increments.len() + 1,
        load_factor: ck.lambda,
        iterations,
        cutbacks: ck.cutbacks_here,
        measures: engine.measures(&ck.committed),
        joints: joint_measures(model, &ck.committed, &ck.joint_totals),
        sections: (0..model.sections.len())
            .map(|k| {
                let c = &ck.committed;
                let across = c.section_force.get(k).copied().unwrap_or(f64::NAN);
                model.section_row(k, across, &c.u, c.time)
            })
            .collect(),
        record: engine.record(&ck.committed),
        von_mises_away: engine.von_mises_away(&ck.committed),
    }
}

/// A failed or rejected step: the stepper's next try, or the end of the run
/// when the cutbacks are used up.
fn cut_back(
    ck: &mut Checkpoint,
    observer: &mut dyn Observer,
    target: f64,
    (why, reason): (stepping::Why, String),
) -> Result<()> {
    match ck.stepper.retry(ck.lambda, target, why) {
        stepping::Retry::GiveUp => Err(Error::Convergence {
            increment: ck.increments.len() + 1,
            load_factor: target,
            message: format!(
                "{reason}; gave up after {} cutbacks",
                ck.stepper.max_cutbacks()
            ),
        }),
        stepping::Retry::At(next) => {
            observer.cutback(ck.lambda, target, next, &reason);
            ck.cutbacks_total += 1;
            ck.cutbacks_here += 1;
            Ok(())
        }
    }
}

/// The outcome of a run from the engine's counters and the last checkpoint;
/// memory summed over the ranks (collective).
fn finish(
    mut engine: Engine,
    ck: Checkpoint,
    (stopped, limit): (Option<Stop>, Option<events::Event>),
    resumed_from: usize,
) -> RunResult {
    let stabilization = stabilization::final_report(&engine, &ck.committed);
    // the peak and every stage, summed over ranks (every rank passed the same stages)
    let mut memory: Vec<f64> = std::iter::once(peak_memory_mb())
        .chain(engine.stats.memory_mb.iter().map(|s| s.1))
        .collect();
    engine.backend.sum(&mut memory);
    for (s, m) in engine.stats.memory_mb.iter_mut().zip(&memory[1..]) {
        s.1 = *m;
    }
    RunResult {
        peak_memory_mb: memory[0],
        backend: engine.backend.name().to_string(),
        ranks: engine.backend.ranks(),
        threads: engine.threads(),
        linear_solver: engine
            .nonlinear
            .as_ref()
            .and_then(|s| s.linear_solver())
            .unwrap_or_else(|| engine.backend.linear_solver()),
        nonlinear_solver: engine
            .nonlinear
            .as_ref()
            .map_or("builtin", |s| s.name())
            .to_string(),
        backend_stats: backend_stats(&engine),
        events: {
            let mut events = ck.events;
            events.extend(events::plateaus(engine.model, &ck.increments));
            events.extend(limit);
            events
        },
        increments: ck.increments,
        first_yield: ck.first_yield,
        stats: engine.stats.clone(),
        cutbacks: ck.cutbacks_total,
        final_state: ck.committed,
        stopped,
        resumed_from,
        stabilization,
        table_reach: ck.table_reach,
        estimate: None,
    }
}

/// The backend's and the nonlinear solver's counters; counters of the same
/// name (ksp_iterations) add up.
fn backend_stats(engine: &Engine) -> Vec<(String, f64)> {
    let mut stats: Vec<(String, f64)> = Vec::new();
    let nonlinear = engine
        .nonlinear
        .as_ref()
        .map(|s| s.diagnostics())
        .unwrap_or_default();
    for (k, v) in engine.backend.diagnostics().into_iter().chain(nonlinear) {
        match stats.iter_mut().find(|(n, _)| n == k) {
            Some((_, total)) => *total += v,
            None => stats.push((k.to_string(), v)),
        }
    }
    stats
}

/// The predictor of an increment: the committed displacements plus the last
/// converged increment's change scaled to this step,
/// `u₀ = u_n + (Δλ / Δλ_prev) (u_n − u_{n−1})` (linear extrapolation along the
/// load path). Newton then starts within O(Δλ²) of the solution instead of
/// O(Δλ) and saves about one iteration per increment. `None` before the first
/// increment. The secant start of eq. 2.8-2.9 still applies to every pair the
/// prediction leaves at zero approach (the first evaluation's stiffness
/// floor, [`newton`]); the converged state does not depend on the start
/// beyond the Newton tolerance.
pub fn predict(committed: &State, last_du: &[f64], last_step: f64, step: f64) -> Option<Vec<f64>> {
    if last_du.len() != committed.u.len() || last_step <= 0.0 || step <= 0.0 {
        return None;
    }
    let scale = step / last_step;
    Some(
        committed
            .u
            .iter()
            .zip(last_du)
            .map(|(u, d)| u + scale * d)
            .collect(),
    )
}

/// The yield ratio σ_eq / σ_y of a Gauss point state for a material.
pub(crate) fn yield_ratio(mat: &VonMises, g: &PointState) -> f64 {
    let y = mat.current_yield(g);
    if y.is_finite() {
        VonMises::equivalent_stress(&g.stress) / y
    } else {
        0.0
    }
}

/// Peak resident set size of this process in MB (Linux /proc), 0 elsewhere.
pub fn peak_memory_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1024.0)
}
