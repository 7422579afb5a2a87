//! The `[[load]]` of a 3D model: a uniform pressure and traction vector on a
//! face set, integrated consistently on each face
//! ([`crate::physics::element::face::face_forces`]), and a torque T about
//! the y axis, the hoop traction τ_θ = T r / J over the selected faces, J =
//! ∫ r² dA ([`crate::physics::element::face::torque_forces`]).

use crate::error::{Error, Result};
use crate::input::case::LoadSpec;
use crate::input::mesh::Mesh;
use crate::physics::element::face::{face_forces, torque_forces};

/// The (dof, force) terms at factor 1 of `ld` on its face set (those faces
/// whose centre passes the x, y and z ranges).
pub(super) fn face_traction(ld: &LoadSpec, mesh: &Mesh, at: &str) -> Result<Vec<(usize, f64)>> {
    let name = ld.faces.as_deref().unwrap_or_default();
    let faces = mesh.face_sets.get(name).ok_or_else(|| {
        Error::input(
            at,
            format!(
                "no face set \"{}\" (sets: {})",
                super::clip(name),
                super::names(mesh.face_sets.keys())
            ),
        )
    })?;
    let t = match ld.traction.as_deref() {
        Some(&[x, y, z]) => [x, y, z],
        _ => [0.0; 3],
    };
    let nd = mesh.node_dofs;
    let mut terms = Vec::new();
    // a torque's forces per unit T / J, and J = Σ ∫ r² dA
    let (mut twist, mut polar) = (Vec::new(), 0.0);
    for face in faces {
        let nodes = face.nodes();
        let x: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.nodes[n]).collect();
        let k = nodes.len() as f64;
        let centre: [f64; 3] = std::array::from_fn(|c| x.iter().map(|p| p[c]).sum::<f64>() / k);
        let ranges = [&ld.x_range, &ld.y_range, &ld.z_range];
        if !(0..3).all(|c| super::in_range(centre[c], ranges[c])) {
            continue;
        }
        let f = face_forces(face.family, &x, ld.pressure, t);
        for (a, &n) in nodes.iter().enumerate() {
            terms.extend((0..3).map(|c| (nd.dof(n, c), f[a][c])));
        }
        if ld.torque.is_some() {
            let (f, j) = torque_forces(face.family, &x);
            polar += j;
            for (a, &n) in nodes.iter().enumerate() {
                twist.extend((0..3).map(|c| (nd.dof(n, c), f[a][c])));
            }
        }
    }
    if terms.is_empty() {
        return Err(Error::input(
            at,
            super::selects_none("face", faces.is_empty(), true),
        ));
    }
    if let Some(torque) = ld.torque {
        // J > 0 on any face of positive area (r = 0 only along the axis)
        if !(polar.is_finite() && polar > 0.0) {
            return Err(Error::input(
                format!("{at} torque"),
                "acts on faces without a polar moment ∫ r² dA about the y axis",
            ));
        }
        terms.extend(twist.into_iter().map(|(d, v)| (d, v * torque / polar)));
    }
    Ok(terms)
}
