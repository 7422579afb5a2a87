//! The axis of an axisymmetric model: nodes at r = 0 cannot move radially.
//!
//! A node on the axis x = r = 0 belongs to every meridian plane at once, so its
//! radial displacement must be zero (otherwise the body would tear open along
//! the axis). `hold_axis` prescribes u_r = 0 there after the case's own
//! `[[boundary]]` entries are known; a case may give ux = 0 on the axis itself,
//! but not another value. With twist the circumferential u_θ is held there
//! too (a prescribed rotation gives φ · 0 = 0 on the axis anyway).

use super::Case;
use crate::error::{clip, Error, Result};
use crate::input::mesh::Mesh;
use crate::physics::material::Plane;

/// Adds ux = 0 at every node with |r| ≤ 1e-9 × the model's size to the
/// prescribed dofs (sorted by dof, as given) of an axisymmetric case; other
/// cases are returned unchanged. A non-zero prescribed ux on the axis is an
/// error naming the `[[boundary]]` entry.
pub(crate) fn hold_axis(
    case: &Case,
    mesh: &Mesh,
    mut prescribed: Vec<(usize, f64)>,
    place: &str,
) -> Result<Vec<(usize, f64)>> {
    if case.model.plane != Plane::Axisymmetric {
        return Ok(prescribed);
    }
    let tol = super::whole::tolerance(mesh);
    let given: std::collections::HashMap<usize, f64> = prescribed.iter().copied().collect();
    for (n, x) in mesh.nodes.iter().enumerate() {
        if x[0].abs() > tol {
            continue;
        }
        let d = mesh.node_dofs.dof(n, 0);
        match given.get(&d) {
            None => prescribed.push((d, 0.0)),
            Some(&v) if v != 0.0 => return Err(nonzero_on_axis(case, mesh, n, v, place)),
            Some(_) => {}
        }
        // with twist, u_θ = 0 on the axis too (a prescribed rotation gives
        // φ·0 = 0 there)
        if mesh.node_dofs.twist() {
            let d = mesh.node_dofs.dof(n, 2);
            if !given.contains_key(&d) {
                prescribed.push((d, 0.0));
            }
        }
    }
    prescribed.sort_by_key(|&(d, _)| d);
    Ok(prescribed)
}

/// The error for node n on the axis given ux = v ≠ 0, naming the first
/// `[[boundary]]` entry that gives it.
fn nonzero_on_axis(case: &Case, mesh: &Mesh, n: usize, v: f64, place: &str) -> Error {
    let x = mesh.nodes[n];
    let within =
        |c: f64, r: &Option<[f64; 2]>| r.is_none_or(|[lo, hi]| c >= lo - 1e-9 && c <= hi + 1e-9);
    let entry = case.boundary.iter().enumerate().find(|(_, bc)| {
        bc.ux == Some(v)
            && within(x[0], &bc.x_range)
            && within(x[1], &bc.y_range)
            && mesh.node_sets.get(&bc.set).is_some_and(|s| s.contains(&n))
    });
    let at = match entry {
        Some((i, bc)) => format!("{place}: boundary[{i}] (set \"{}\") ux", clip(&bc.set)),
        None => format!("{place}: [[boundary]] ux"),
    };
    Error::input(
        at,
        format!(
            "gives ux = {v} to node {n} at ({}, {}) on the axis r = 0: with plane = \"axisymmetric\" a node on the axis cannot move radially (u_r = 0 is prescribed there automatically; give ux = 0 or nothing)",
            x[0], x[1]
        ),
    )
}
