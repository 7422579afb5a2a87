//! The load-increment loop (paper section 4): scheduled load factors, Newton
//! steps with the status check, automatic cutback of a failed step with the
//! committed state restored, and the location of first yield.

mod accelerate;
pub mod newton;
pub mod stepping;
mod yield_point;

pub use newton::{Engine, Stats};
pub use yield_point::{max_yield_ratio, FirstYield};

use crate::error::{Error, Result};
use crate::fem::solid::Response;
use crate::interface::Status;
use crate::material::{PointState, VonMises};
use crate::model::Model;

/// Evolving state: displacements, Gauss point states and interface statuses.
#[derive(Clone, Debug)]
pub struct State {
    pub u: Vec<f64>,
    pub gauss: Vec<PointState>,
    pub status: Vec<Status>,
    /// Tangential state of every interface point (all interfaces, in order).
    pub contact: Vec<crate::interface::PointState>,
    /// Sum of the reactions at the dofs with a non-zero prescribed displacement
    /// (the force needed to impose it), N.
    pub prescribed_reaction: f64,
}

impl State {
    pub fn initial(model: &Model) -> State {
        let n_points: usize = model.interfaces.iter().map(|i| i.points.len()).sum();
        State {
            u: vec![0.0; model.mesh.num_dofs()],
            gauss: vec![PointState::default(); model.mesh.elements.len() * model.n_gauss()],
            status: vec![Status::Closed; n_points],
            contact: vec![crate::interface::PointState::default(); n_points],
            prescribed_reaction: 0.0,
        }
    }
}

/// What is recorded for each converged increment.
#[derive(Clone, Debug)]
pub struct Increment {
    pub increment: usize,
    pub load_factor: f64,
    pub iterations: usize,
    /// Failed attempts (cutbacks) before this increment converged.
    pub cutbacks: usize,
    pub measures: Measures,
}

/// Scalar measures of a state.
#[derive(Clone, Copy, Debug, Default)]
pub struct Measures {
    /// Normal force carried by the (first) interface, N, model as meshed.
    pub normal_force: f64,
    /// Mean contact pressure: normal force / nominal interface area, MPa.
    pub mean_pressure: f64,
    /// Whole-body load per mm of thickness, kN.
    pub total_load_kn: f64,
    /// Vertical displacement of the probe node, mm (negative = down).
    pub center_displacement: f64,
    pub max_peeq: f64,
    /// See [`State::prescribed_reaction`].
    pub prescribed_reaction: f64,
}

impl Measures {
    pub fn of(model: &Model, state: &State) -> Measures {
        let mut m = Measures {
            center_displacement: state.u[2 * model.probe_node + 1],
            max_peeq: state.gauss.iter().fold(0.0f64, |a, g| a.max(g.peeq)),
            prescribed_reaction: state.prescribed_reaction,
            ..Measures::default()
        };
        if let Some(im) = model.interfaces.first() {
            let force: f64 = im
                .points
                .iter()
                .map(|pt| pt.area * im.law.pressure(im.point_kinematics(pt, &state.u).0).0)
                .sum();
            m.normal_force = force;
            m.mean_pressure = force / im.area();
            m.total_load_kn = force * model.load_scale_kn();
        }
        m
    }
}

/// Callbacks of a run (progress, output).
pub trait Observer {
    fn increment(&mut self, model: &Model, state: &State, inc: &Increment) -> Result<()>;
    fn cutback(&mut self, _from: f64, _to: f64, _reason: &str) {}
}

/// The outcome of a run.
#[derive(Clone, Debug)]
pub struct RunResult {
    pub backend: String,
    pub ranks: usize,
    /// Peak resident memory summed over ranks (VmHWM), MB; 0 where unknown.
    pub peak_memory_mb: f64,
    pub backend_stats: Vec<(String, f64)>,
    pub increments: Vec<Increment>,
    pub first_yield: Option<FirstYield>,
    pub stats: Stats,
    pub cutbacks: usize,
    pub final_state: State,
}

/// Runs the whole load history of the model on the serial backend.
pub fn run(model: &Model, observer: &mut dyn Observer) -> Result<RunResult> {
    run_with(Engine::new(model, model.case.solver.method)?, observer)
}

/// Runs the whole load history with a given engine (any backend). Under MPI
/// every rank calls this; only rank 0's observer writes, and its outcome is
/// shared so that a failed write stops every rank.
pub fn run_with(mut engine: Engine, observer: &mut dyn Observer) -> Result<RunResult> {
    let model = engine.model;
    let spec = &model.case.solver;
    let mut committed = State::initial(model);
    let mut lambda = 0.0;
    let mut stepper = stepping::Stepper::new(spec);
    let mut increments = Vec::new();
    let mut first_yield = None;
    let mut cutbacks_total = 0;
    let mut cutbacks_here = 0;
    let mut elastic_ratio_prev = 0.0;
    let mut next = stepper.next(lambda);
    while let Some(target) = next {
        let failure = match engine.step(&committed, target, Response::Plastic) {
            Ok((trial, iterations)) => {
                let dpeeq = trial
                    .gauss
                    .iter()
                    .zip(&committed.gauss)
                    .fold(0.0f64, |a, (t, c)| a.max(t.peeq - c.peeq));
                if stepper.accept(lambda, target, iterations, dpeeq) {
                    let yielded_now =
                        first_yield.is_none() && trial.gauss.iter().any(|g| g.peeq > 0.0);
                    if yielded_now && spec.locate_first_yield {
                        first_yield = Some(yield_point::locate(
                            &mut engine,
                            &committed,
                            (lambda, elastic_ratio_prev),
                            target,
                        )?);
                    } else if first_yield.is_none() {
                        elastic_ratio_prev = max_yield_ratio(model, &trial).0;
                    }
                    committed = trial;
                    engine.committed();
                    lambda = target;
                    let inc = Increment {
                        increment: increments.len() + 1,
                        load_factor: lambda,
                        iterations,
                        cutbacks: cutbacks_here,
                        measures: Measures::of(model, &committed),
                    };
                    cutbacks_here = 0;
                    let written = observer.increment(model, &committed, &inc);
                    if !engine.backend.agree(written.is_ok()) {
                        return Err(written.err().unwrap_or_else(|| {
                            Error::Solver("writing the output failed on rank 0".into())
                        }));
                    }
                    increments.push(inc);
                    next = stepper.next(lambda);
                    continue;
                }
                // converged, but the plastic strain changed too much for an accurate path
                None
            }
            Err(reason) => Some(reason),
        };
        let retry = stepper.retry(lambda, target, failure.is_none());
        let reason = failure.unwrap_or_else(|| "plastic strain increment too large".into());
        match retry {
            stepping::Retry::GiveUp => {
                return Err(Error::Convergence {
                    increment: increments.len() + 1,
                    load_factor: target,
                    message: format!("{reason}; gave up after {} cutbacks", spec.max_cutbacks),
                });
            }
            stepping::Retry::At(t) => {
                observer.cutback(lambda, target, &reason);
                cutbacks_total += 1;
                cutbacks_here += 1;
                next = Some(t);
            }
        }
    }
    let mut memory = [peak_memory_mb()];
    engine.backend.sum(&mut memory);
    Ok(RunResult {
        peak_memory_mb: memory[0],
        backend: engine.backend.name().to_string(),
        ranks: engine.backend.ranks(),
        backend_stats: engine
            .backend
            .diagnostics()
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect(),
        increments,
        first_yield,
        stats: engine.stats.clone(),
        cutbacks: cutbacks_total,
        final_state: committed,
    })
}

/// The yield ratio σ_eq / σ_y of a Gauss point state for a material.
pub fn yield_ratio(mat: &VonMises, g: &PointState) -> f64 {
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
