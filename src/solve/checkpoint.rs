//! The committed state of the increment loop (what `restart.bin` holds) and
//! its writing: every committed increment, and the last state of a stopped
//! run, handed to the observer with the checkpoint, collectively.

use super::{events, newton, stepping, Engine, FirstYield, Increment, Observer, State};
use crate::error::{Error, Result};
use crate::measure::joint::JointTotals;
use crate::model::Model;

/// The committed state of the increment loop: enough to continue a run exactly
/// as if it had not been interrupted.
#[derive(Clone, Debug)]
pub struct Checkpoint {
    pub committed: State,
    /// Load factor of the committed state.
    pub lambda: f64,
    /// Size of the last converged step (load factor), 0 before the first.
    pub(crate) last_step: f64,
    /// Displacement change of the last converged increment (all dofs; empty
    /// before the first): the predictor's direction ([`predict`](super::predict)).
    pub last_du: Vec<f64>,
    /// The load steps still to take (fixed schedule or automatic control).
    pub stepper: stepping::Stepper,
    /// Converged increments so far (the rows of curve.csv).
    pub increments: Vec<Increment>,
    pub first_yield: Option<FirstYield>,
    /// Max yield ratio of the last elastic increment (for locating first yield).
    pub elastic_ratio_prev: f64,
    pub(crate) cutbacks_total: usize,
    /// Cutbacks since the last converged increment.
    pub(crate) cutbacks_here: usize,
    /// Newton iterations and factorizations so far (the event searches'
    /// included), and the event searches' iterations.
    pub iterations: usize,
    pub factorizations: usize,
    pub event_iterations: usize,
    /// The interface loop's counters so far (`newton::interface_loop`).
    pub interface: newton::interface_loop::LoopStats,
    /// Frictional dissipation and tangential work of every interface so far.
    pub joint_totals: Vec<JointTotals>,
    /// The largest approach and pressure of every interface over the
    /// converged states so far (how far its tables were used).
    pub table_reach: Vec<crate::model::interface::extrapolation::Reach>,
    /// The events located so far ([`events`]).
    pub events: Vec<events::Event>,
    /// The model has twist: its joints' records carry a torque and a twist
    /// (restart section `joints_twist`; the Gauss states' width is their
    /// own, `GaussStates::twist`).
    pub twist: bool,
    /// The interface points carry the vector law's state (twist, 3D):
    /// their restart layout, `ContactState::packed_len`.
    pub vector_slip: bool,
    /// The values of one designer's record (the model's
    /// [`Plan::width`](crate::model::outputs::Plan::width)): the layout of
    /// every increment's and event's record.
    pub(crate) record_width: usize,
}

impl Checkpoint {
    /// The start of a run: nothing converged, the whole schedule pending.
    pub fn initial(model: &Model) -> Checkpoint {
        Checkpoint {
            committed: State::initial(model),
            lambda: 0.0,
            last_step: 0.0,
            last_du: Vec::new(),
            stepper: stepping::Stepper::for_model(model),
            increments: Vec::new(),
            first_yield: None,
            elastic_ratio_prev: 0.0,
            cutbacks_total: 0,
            cutbacks_here: 0,
            iterations: 0,
            factorizations: 0,
            event_iterations: 0,
            interface: Default::default(),
            joint_totals: vec![JointTotals::default(); model.interfaces.len()],
            table_reach: vec![Default::default(); model.interfaces.len()],
            events: Vec::new(),
            twist: model.node_dofs().twist(),
            vector_slip: model.node_dofs().vector_slip(),
            record_width: model.plan.width(),
        }
    }
}

/// Records a committed increment and hands it to the observer (rank 0
/// writes), with the checkpoint; a failed write on rank 0 ends every rank.
pub(super) fn write_increment(
    engine: &Engine,
    observer: &mut dyn Observer,
    ck: &mut Checkpoint,
    inc: Increment,
) -> Result<()> {
    let model = engine.model;
    written_everywhere(engine, ck, |ck| {
        let written = observer.increment(model, &ck.committed, &inc);
        ck.increments.push(inc);
        written.and_then(|()| observer.checkpoint(model, ck))
    })
}

/// The last converged state of a stopped run, handed to the observer again
/// ([`Observer::last_state`]) with the checkpoint; collective like
/// [`write_increment`].
pub(super) fn write_last_state(
    engine: &Engine,
    observer: &mut dyn Observer,
    ck: &mut Checkpoint,
) -> Result<()> {
    let model = engine.model;
    written_everywhere(engine, ck, |ck| {
        let written = match ck.increments.last() {
            Some(inc) => observer.last_state(model, &ck.committed, inc),
            None => Ok(()),
        };
        written.and_then(|()| observer.checkpoint(model, ck))
    })
}

/// Runs a write with every element's Gauss states in the checkpoint (the
/// writer, rank 0, sees them all while it writes) and shares its outcome:
/// a failed write on rank 0 ends every rank.
pub(super) fn written_everywhere(
    engine: &Engine,
    ck: &mut Checkpoint,
    write: impl FnOnce(&mut Checkpoint) -> Result<()>,
) -> Result<()> {
    let local = engine
        .gather_gauss(&ck.committed)
        .map(|full| std::mem::replace(&mut ck.committed.gauss, full));
    let written = write(ck);
    if let Some(local) = local {
        ck.committed.gauss = local;
    }
    if !engine.backend.agree(written.is_ok()) {
        return Err(written
            .err()
            .unwrap_or_else(|| Error::Output("writing the output failed on rank 0".into())));
    }
    Ok(())
}
