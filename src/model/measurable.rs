//! Whether an adaptive run's named answer (`[adapt] quantity`,
//! [`crate::app::adapt`]) can measure the mesh at all. Its estimate is the
//! answer's change between two meshes; an answer that equilibrium or a
//! support fixes is the same on every mesh, to round-off, and the run would
//! stop at once, "reached", whatever the mesh. Refused here, on the built
//! model (the checks that need no mesh are in [`crate::input::case::adapt::check`]):
//!
//! - `settlement` read at a node whose vertical displacement is prescribed;
//! - `total_load` and `mean_pressure` (the first interface's normal force)
//!   where one of the interface's two bodies is held along the interface's
//!   normal by that interface alone (no prescribed displacement of the body
//!   with a component along the normal, no other interface on it): the
//!   interface then carries the load applied to that body, on every mesh.
//!   Only a straight interface (one normal) has a resultant equilibrium
//!   fixes, and in axisymmetry only a face across the axis (a radial ring
//!   force is no resultant: the hoop stress balances it);
//! - `torque` through a first interface without a tangential law (it
//!   carries none), or where one of its bodies is held about the axis by
//!   that interface alone (it carries the torque applied to that body);
//! - `max_von_mises` where the discs about the start mesh's singular
//!   points ([`crate::model::excluded`]) hold every Gauss point: nothing is
//!   left to measure, on this mesh or any refined one.

use crate::error::{Error, Result};
use crate::input::case::adapt::{AdaptSpec, Quantity};
use crate::model::interface::InterfaceModel;
use std::collections::HashSet;

/// The refusals of the module text for the model `m`.
pub(super) fn check(m: &super::Model, spec: &AdaptSpec, place: &str) -> Result<()> {
    let at = format!("{place}: [adapt] quantity");
    let name = spec.quantity.name();
    let held: HashSet<usize> = m.prescribed.iter().map(|p| p.0).collect();
    let nd = m.mesh.node_dofs;
    match spec.quantity {
        Quantity::Settlement if held.contains(&nd.dof(m.probe_node, 1)) => {
            let x = m.mesh.nodes[m.probe_node];
            Err(Error::input(
                at,
                format!(
                    "\"settlement\" is read at node {} at ({}, {}) (the interface node of the lower body nearest to [output] probe), whose uy a [[boundary]] prescribes: it is the same on every mesh and measures no error; adapt on \"energy\", or move the probe to a node that is free to settle",
                    m.probe_node, x[0], x[1]
                ),
            ))
        }
        Quantity::TotalLoad | Quantity::MeanPressure => {
            let Some(im) = m.interfaces.first() else {
                return Ok(());
            };
            let Some(n) = straight_normal(im, m.section.axisymmetric) else {
                return Ok(());
            };
            let along: Vec<usize> = (0..2).filter(|&c| n[c].abs() > 1e-9).collect();
            match free_body(m, im, &along, &held) {
                Some(b) => Err(Error::input(
                    at,
                    format!(
                        "\"{name}\" (the normal force of interface \"{}\") is fixed by equilibrium: body \"{}\" is held along the interface's normal by that interface alone (no [[boundary]] along it, no other interface), so the interface carries the load applied to the body on every mesh, to round-off, and measures no error; adapt on \"energy\", \"settlement\" or \"peak_pressure\", or drive the body by a prescribed displacement",
                        im.name, m.mesh.bodies[b]
                    ),
                )),
                None => Ok(()),
            }
        }
        Quantity::Torque => {
            let Some(im) = m.interfaces.first() else {
                return Ok(());
            };
            if im.tangential.is_none() {
                return Err(Error::input(
                    at,
                    format!(
                        "\"torque\" through interface \"{}\", which has no tangential law ([interface.{}.tangential]): it carries no torque, 0 on every mesh; adapt on \"energy\", or give the interface its tangential law",
                        im.name, im.name
                    ),
                ));
            }
            match free_body(m, im, &[2], &held) {
                Some(b) => Err(Error::input(
                    at,
                    format!(
                        "\"torque\" through interface \"{}\" is fixed by equilibrium: body \"{}\" is held about the axis by that interface alone (no [[boundary]] rotation on it, no other interface), so the interface carries the torque applied to the body on every mesh and measures no error; adapt on \"energy\", or prescribe the rotation of that body",
                        im.name, m.mesh.bodies[b]
                    ),
                )),
                None => Ok(()),
            }
        }
        Quantity::MaxVonMises => match &m.excluded {
            Some(x) if x.count() == x.points.len() => Err(Error::input(
                at,
                format!(
                    "\"max_von_mises\" leaves out the Gauss points within one element size of the mesh's singular points ({}), and these hold every Gauss point of the start mesh: nothing is left to measure on any refined mesh; make the case's mesh finer about them ([mesh] refine, more block divisions), or adapt on \"energy\"",
                    x.discs
                        .iter()
                        .map(|d| format!("{} at ({}, {})", d.corner, d.x[0], d.x[1]))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )),
            _ => Ok(()),
        },
        _ => Ok(()),
    }
}

/// The interface's one normal, when every point has it (a straight
/// interface); in axisymmetry only a face across the axis (normal ±y).
fn straight_normal(im: &InterfaceModel, axisymmetric: bool) -> Option<[f64; 2]> {
    let n = im.points.first()?.normal;
    let same = |p: &crate::model::interface::Point| {
        (p.normal[0] - n[0]).abs() <= 1e-9 && (p.normal[1] - n[1]).abs() <= 1e-9
    };
    if !im.points.iter().all(same) || (axisymmetric && n[0].abs() > 1e-9) {
        return None;
    }
    Some([n[0], n[1]])
}

/// A body of interface `im` that nothing but `im` holds in the dof
/// components `along`: no prescribed dof of its nodes in them (but the
/// axis's own, in axisymmetry), and no other interface on the body.
fn free_body(
    m: &super::Model,
    im: &InterfaceModel,
    along: &[usize],
    held: &HashSet<usize>,
) -> Option<usize> {
    let nd = m.mesh.node_dofs;
    let body_of = m.mesh.node_bodies();
    let tol = crate::model::consistency::tolerance(&m.mesh);
    // the axis's own u_r = u_θ = 0 holds no force: no area, no lever arm
    let axis = |node: usize, c: usize| {
        m.section.axisymmetric && c != 1 && m.mesh.nodes[node][0].abs() <= tol
    };
    let mut supported = vec![false; m.mesh.bodies.len()];
    for &d in held {
        let (node, c) = nd.node_of(d);
        if node >= m.mesh.nodes.len() || axis(node, c) {
            continue;
        }
        if let Some(&b) = body_of.get(node).filter(|&&b| b != usize::MAX) {
            supported[b] |= along.contains(&c);
        }
    }
    for other in m.interfaces.iter().skip(1) {
        supported[other.body_a] = true;
        supported[other.body_b] = true;
    }
    [im.body_a, im.body_b].into_iter().find(|&b| !supported[b])
}
