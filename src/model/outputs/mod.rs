//! What the designer's outputs measure in every converged state, fixed when
//! the model is built: the reaction groups ([`reactions`]), the probes
//! ([`probes`]), the interfaces' arc lengths (for the contact extent,
//! [`crate::measure::peaks`]), the event tolerance and the named histories.
//!
//! Each converged increment gets one flat record of numbers
//! ([`crate::solve::Increment::record`]), laid out by [`Layout`]: the
//! reactions (per group and component), the probes (u_x, u_y each), the
//! body peaks (`PER_BODY` each) and the interface peaks
//! (`PER_INTERFACE` each). The record is computed on every rank
//! (its reductions are collective), kept in the checkpoint and the restart
//! file, and written out at the end of the run (`reactions.csv`,
//! `probes.csv`, `peaks.csv`, `contact.csv`, summary.json).

pub mod bearings;
pub mod probes;
pub mod reactions;
use crate::error::Result;
use crate::input::case::Case;
use crate::input::mesh::Mesh;
use crate::model::interface::InterfaceModel;
use std::ops::Range;

/// Values per body in a record: von Mises (MPa, x, y, z, element), then
/// PEEQ (value, x, y, z, element); z = 0 in a plane model.
pub(crate) const PER_BODY: usize = 10;
/// Values per interface in a record: the largest pressure (MPa, x, y, s),
/// then the extent (from s, to s, from x, from y, to x, to y).
pub(crate) const PER_INTERFACE: usize = 10;

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
    pub(crate) history_names: Vec<String>,
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
        let mut probes = probes::build(case, mesh, place)?;
        probes.extend(bearings::build(case, mesh, interfaces, place)?);
        let arcs = interfaces
            .iter()
            .zip(&mesh.interfaces)
            .map(|(im, iface)| crate::model::interface::arcs::arc_lengths(mesh, iface, im))
            .collect();
        let r = reactions::width(&reactions);
        let p = r + probes::components(mesh.node_dofs) * probes.len();
        let b = p + PER_BODY * mesh.bodies.len();
        let i = b + PER_INTERFACE * interfaces.len();
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

    /// The part of a record (of this plan's [`Plan::width`]) given by `range`.
    pub fn part<'a>(&self, record: &'a [f64], range: &Range<usize>) -> &'a [f64] {
        &record[range.clone()]
    }
}
