//! The evolving state of a model: displacements, Gauss point states, the
//! interface points' statuses and tangential states, the reactions.

use super::Model;
use crate::physics::contact::Status;
use crate::physics::material::GaussStates;

/// Evolving state: displacements, Gauss point states and interface statuses.
#[derive(Clone, Debug)]
pub struct State {
    pub u: Vec<f64>,
    /// Gauss point states, element by element: of every element in a whole
    /// state (one process, restart files, what the writer sees), of the
    /// elements a rank owns inside an MPI run (`Engine::localize`). The
    /// twist components are stored only in a model with twist.
    pub gauss: GaussStates,
    pub status: Vec<Status>,
    /// Tangential state of every interface point (all interfaces, in order).
    pub contact: Vec<crate::physics::contact::PointState>,
    /// Sum of the reactions at the dofs with a non-zero prescribed displacement
    /// (the force needed to impose it), N.
    pub prescribed_reaction: f64,
    /// The force across each pretension section (N, tension positive): the
    /// condensed internal force on its shortening's equation, set when a
    /// step converges (empty before; not kept in restart files, whose
    /// increments carry it).
    pub(crate) section_force: Vec<f64>,
    /// The residual at every prescribed dof (in the order of
    /// [`Model::prescribed`]): the reactions of a converged state, N (empty
    /// before the first step and in a state restored from a restart file).
    pub reactions: Vec<f64>,
    /// The pseudo-time of the state (the load factor without histories):
    /// where its loads, prescribed values and gaps are taken.
    pub time: f64,
}

impl State {
    pub fn initial(model: &Model) -> State {
        let n_points: usize = model.interfaces.iter().map(|i| i.points.len()).sum();
        State {
            u: vec![0.0; model.num_dofs()],
            gauss: GaussStates::new(model.n_points(), model.node_dofs().six_components()),
            status: vec![Status::Closed; n_points],
            contact: vec![crate::physics::contact::PointState::default(); n_points],
            prescribed_reaction: 0.0,
            section_force: Vec::new(),
            reactions: Vec::new(),
            time: 0.0,
        }
    }
}
