//! What a run measures in a converged state, computed once, here, for every
//! increment and every event: the scalar measures of the curve
//! ([`Measures`]), the joints' measures ([`joint`]), the designer's record
//! ([`record`]: reactions, probes, peaks laid out by the model's
//! [`crate::model::outputs::Plan`]) and the error estimate ([`estimate`]).
//!
//! Under MPI every rank calls these with its own Gauss states and gets the
//! same numbers: the reductions go through a small communication interface
//! ([`Comm`]: sum, max, agree, rank), never through the solver.

pub mod estimate;
pub mod gross_slip;
pub mod joint;
pub mod peaks;
pub mod singular;
pub mod sweep;

use crate::linalg::backend::Comm;
use crate::model::state::State;
use crate::model::Model;

/// The designer's record of a converged state (collective under MPI: every
/// rank calls it with the Gauss states of the elements it holds, `held`,
/// and gets the same record).
pub fn record(model: &Model, comm: &dyn Comm, held: &[u32], state: &State) -> Vec<f64> {
    let plan = &model.plan;
    let mut v = Vec::with_capacity(plan.width());
    v.extend(crate::model::outputs::reactions::values(
        &plan.reactions,
        &state.reactions,
    ));
    v.extend(crate::model::outputs::probes::values(
        &plan.probes,
        model.node_dofs(),
        &state.u,
    ));
    v.extend(peaks::bodies(model, comm, held, state));
    v.extend(peaks::interfaces(model, &plan.arcs, &state.u, state.time));
    debug_assert_eq!(v.len(), plan.width());
    v
}

/// The part of a converged state's record from the probes on (the probes,
/// the body peaks and the interface peaks: what its displacements and Gauss
/// states fix), computed in one process from the whole state, as a restart
/// file holds it; the reactions before them come from the residual, which
/// the state does not keep.
pub(crate) fn state_part(model: &Model, state: &State) -> Vec<f64> {
    let plan = &model.plan;
    let mut v = Vec::with_capacity(plan.width() - plan.layout.probes.start);
    v.extend(crate::model::outputs::probes::values(
        &plan.probes,
        model.node_dofs(),
        &state.u,
    ));
    v.extend(peaks::bodies_whole(model, &state.gauss));
    v.extend(peaks::interfaces(model, &plan.arcs, &state.u, state.time));
    v
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
            center_displacement: state.u[model.node_dofs().dof(model.probe_node, 1)],
            max_peeq: state.gauss.iter().fold(0.0f64, |a, g| a.max(g.peeq)),
            prescribed_reaction: state.prescribed_reaction,
            ..Measures::default()
        };
        if let Some(im) = model.interfaces.first() {
            let gap = im.gap_at(state.time);
            let force: f64 = im
                .points
                .iter()
                .map(|pt| {
                    pt.area
                        * im.law
                            .pressure(im.point_kinematics_at(pt, &state.u, gap).0)
                            .0
                })
                .sum();
            m.normal_force = force;
            m.mean_pressure = force / im.area();
            m.total_load_kn = force * model.load_scale_kn();
        }
        m
    }
}

/// The joint measures of every interface in a committed state, with the
/// energies so far `totals`: an increment's `joints` (a restart file's last
/// row is compared with them, [`crate::files::restart`]).
pub(crate) fn joint_measures(
    model: &Model,
    state: &State,
    totals: &[joint::JointTotals],
) -> Vec<joint::JointMeasures> {
    joint::measures(
        &model.interfaces,
        model.section,
        state.time,
        &state.u,
        &state.status,
        &state.contact,
        totals,
    )
}
