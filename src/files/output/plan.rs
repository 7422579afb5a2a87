//! What the designer's outputs measure in every converged state, fixed when
//! the model is built: the reaction groups ([`reactions`]), the probes
//! ([`probes`]), the interfaces' arc lengths (for the contact extent,
//! [`peaks`]), the event tolerance and the named histories.
//!
//! Each converged increment gets one flat record of numbers
//! ([`crate::solve::Increment::record`]), laid out by [`Layout`]: the
//! reactions (per group and component), the probes (u_x, u_y each), the
//! body peaks ([`peaks::PER_BODY`] each) and the interface peaks
//! ([`peaks::PER_INTERFACE`] each). The record is computed on every rank
//! (its reductions are collective), kept in the checkpoint and the restart
//! file, and written out at the end of the run (`reactions.csv`,
//! `probes.csv`, `peaks.csv`, `contact.csv`, summary.json).

use super::{peaks, probes, reactions};
use crate::error::Result;
use crate::input::case::Case;
use crate::input::mesh::Mesh;
use crate::model::interface::InterfaceModel;
use crate::solve::{Engine, State};
use std::ops::Range;

/// The designer's outputs of a model.
#[derive(Clone, Debug, Default)]
pub struct Plan {
    pub reactions: Vec<reactions::Group>,
    pub probes: Vec<probes::Probe>,
    /// Each interface's pairs' arc lengths s.
    pub arcs: Vec<Vec<f64>>,
    /// Width of an event's bracket in load factor (pseudo-time).
    pub event_tolerance: f64,
    /// The names of the case's named histories (the first histories of the
    /// model, in name order).
    pub history_names: Vec<String>,
    pub layout: Layout,
}

/// Where each part of a record lies.
#[derive(Clone, Debug, Default)]
pub struct Layout {
    pub reactions: Range<usize>,
    pub probes: Range<usize>,
    pub bodies: Range<usize>,
    pub interfaces: Range<usize>,
}

impl Layout {
    pub fn width(&self) -> usize {
        self.interfaces.end
    }
}

impl Plan {
    /// The plan of a case on its mesh, its interfaces and prescribed dofs
    /// built; refuses a probe the mesh does not hold (a set, a body, a point
    /// outside the model).
    pub fn build(
        case: &Case,
        mesh: &Mesh,
        interfaces: &[InterfaceModel],
        prescribed: &[(usize, f64)],
        place: &str,
    ) -> Result<Plan> {
        let reactions = reactions::groups(case, mesh, prescribed);
        let probes = probes::build(case, mesh, place)?;
        let arcs = interfaces
            .iter()
            .zip(&mesh.interfaces)
            .map(|(im, iface)| crate::model::interface::joint::arc_lengths(mesh, iface, im))
            .collect();
        let r = reactions::width(&reactions);
        let p = r + probes::components(mesh.node_dofs) * probes.len();
        let b = p + peaks::PER_BODY * mesh.bodies.len();
        let i = b + peaks::PER_INTERFACE * interfaces.len();
        Ok(Plan {
            reactions,
            probes,
            arcs,
            event_tolerance: crate::input::case::outputs::event_tolerance(case),
            history_names: case.history.keys().cloned().collect(),
            layout: Layout {
                reactions: 0..r,
                probes: r..p,
                bodies: p..b,
                interfaces: b..i,
            },
        })
    }

    /// Values per record.
    pub fn width(&self) -> usize {
        self.layout.width()
    }

    /// The record of a converged state (collective under MPI: every rank
    /// calls it with its own Gauss states and gets the same record).
    pub fn record(&self, engine: &Engine, state: &State) -> Vec<f64> {
        let model = engine.model;
        let mut v = Vec::with_capacity(self.width());
        v.extend(reactions::values(&self.reactions, &state.reactions));
        v.extend(probes::values(&self.probes, model.node_dofs(), &state.u));
        v.extend(peaks::bodies(engine, state));
        v.extend(peaks::interfaces(model, &self.arcs, &state.u, state.time));
        debug_assert_eq!(v.len(), self.width());
        v
    }

    /// The part of a converged state's record from the probes on (the
    /// probes, the body peaks and the interface peaks: what its displacements
    /// and Gauss states fix), computed in one process from the whole state,
    /// as a restart file holds it; the reactions before them come from the
    /// residual, which the state does not keep.
    pub fn state_part(&self, model: &crate::model::Model, state: &State) -> Vec<f64> {
        let mut v = Vec::with_capacity(self.width() - self.layout.probes.start);
        v.extend(probes::values(&self.probes, model.node_dofs(), &state.u));
        v.extend(peaks::bodies_whole(model, &state.gauss));
        v.extend(peaks::interfaces(model, &self.arcs, &state.u, state.time));
        v
    }

    /// Restores a restart file's designer sections into a checkpoint whose
    /// curve is restored: `records`, each increment's record (this plan's
    /// width per increment: finite or NaN, no infinity; a row all NaN is an
    /// increment without one, restored from a file of an earlier build), and
    /// `events` ([`crate::solve::events::Event::unpack`]). A section that is
    /// absent or empty restores nothing. The error is a message for the
    /// restart file's line.
    pub fn restore(
        &self,
        ck: &mut crate::solve::Checkpoint,
        records: Option<&[f64]>,
        events: Option<&[f64]>,
        model: &crate::model::Model,
    ) -> std::result::Result<(), String> {
        let w = self.width();
        if let Some(v) = records.filter(|v| !v.is_empty()) {
            if v.len() != w * ck.increments.len() {
                return Err(format!(
                    "section records has {} values, the model needs {}",
                    v.len(),
                    w * ck.increments.len()
                ));
            }
            if let Some(i) = v.iter().position(|x| x.is_infinite()) {
                return Err(format!(
                    "section records: value {} is infinite ({})",
                    i + 1,
                    v[i]
                ));
            }
            for (inc, row) in ck.increments.iter_mut().zip(v.chunks_exact(w.max(1))) {
                if !row.iter().all(|x| x.is_nan()) {
                    inc.record = row.to_vec();
                }
            }
        }
        if let Some(v) = events {
            let load_factors: Vec<f64> = ck.increments.iter().map(|i| i.load_factor).collect();
            ck.events = crate::solve::events::Event::unpack(v, w, model, &load_factors)?;
        }
        Ok(())
    }

    /// The part of a record given by `range`, or `None` for a record of
    /// another width (an increment restored from an older restart file).
    pub fn part<'a>(&self, record: &'a [f64], range: &Range<usize>) -> Option<&'a [f64]> {
        (record.len() == self.width()).then(|| &record[range.clone()])
    }
}
