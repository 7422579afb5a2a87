//! The mesh of a model: made from the case (blocks or a Gmsh file, with
//! `refine_region`) or handed in (an adaptive run's), and checked.

use crate::error::{Error, Result};
use crate::input::case::Case;
use crate::input::mesh::{blocks, gmsh, Mesh};
use crate::model::consistency as whole;

/// The mesh of a case (a Gmsh file beside the case, or its blocks), checked
/// as a mesh and as a whole ([`whole::check_mesh`]).
pub(super) fn make_mesh(case: &Case, place: &str) -> Result<Mesh> {
    let mesh = match &case.mesh.file {
        Some(file) => {
            let dir = case.source.parent().unwrap_or(std::path::Path::new(""));
            let mesh = gmsh::read(&dir.join(file), &case.mesh.interface, place)?;
            let solid = case.model.plane == crate::physics::material::Plane::Solid;
            if solid != (mesh.dim() == 3) {
                return Err(Error::input(
                    case.at("[mesh] file"),
                    if solid {
                        format!("{} holds no volume elements (20-node hexahedra, 10-node tetrahedra), but plane = \"3d\": mesh the volumes, or pose a plane model", file.display())
                    } else {
                        format!(
                            "{} holds volume elements: a 3D mesh needs plane = \"3d\"",
                            file.display()
                        )
                    },
                ));
            }
            mesh
        }
        None => {
            let layout = blocks::generate(&case.mesh.block, &case.mesh.interface, case.mesh.refine);
            let sweep = crate::input::mesh::extrude::extrude;
            let mesh = match (&case.mesh.extrude, &case.mesh.revolve) {
                (Some(e), _) => layout.and_then(|plane| {
                    let zs =
                        blocks::graded_axis("extrude", "z", &e.z, &e.nz, &e.rz, case.mesh.refine)?;
                    sweep(&plane, &zs)
                }),
                (None, Some(r)) => layout.and_then(|plane| {
                    let n = r.n * case.mesh.refine;
                    crate::input::mesh::revolve::revolve(&plane, r.angle.to_radians(), n)
                }),
                (None, None) => layout,
            };
            mesh.map_err(|e| Error::Mesh {
                place: format!("{place} [mesh]"),
                message: e.to_string(),
            })?
        }
    };
    // a region refines a valid mesh; the refined one is checked below
    let Some(r) = &case.mesh.refine_region else {
        return check_mesh(case, mesh, place);
    };
    let mesh = check_mesh_only(mesh, place)?;
    // on the mesh `--refine` may have made finer
    let at = match case.option("[mesh] refine") {
        Some(o) => format!("{place}: [mesh] refine_region, on the mesh of {o}"),
        None => format!("{place}: [mesh] refine_region"),
    };
    let refined = crate::input::mesh::refine::in_box(
        &mesh,
        r.x,
        r.y,
        r.levels,
        crate::input::case::MAX_ELEMENTS,
    )
    .map_err(|e| Error::Mesh {
        place: at.clone(),
        message: e.to_string(),
    })?;
    let mesh = check_mesh_only(refined.mesh, &at)?;
    whole::check_mesh(case, &mesh, place)?;
    Ok(mesh)
}

/// A refusal of a case that `--uniform` ungraded (`case.overrides`): when
/// the case graded as its file says passes `again` (the same checks), the
/// option made it, and is named; else it is the case's own, as it was.
pub(super) fn blame_uniform(
    case: &Case,
    e: Error,
    again: impl FnOnce(Case) -> Result<()>,
) -> Error {
    let Some(graded) = case.overrides.graded_blocks.clone() else {
        return e;
    };
    if !matches!(e, Error::Input { .. } | Error::Mesh { .. }) {
        return e;
    }
    let mut case = case.clone();
    case.mesh.block = graded;
    case.overrides.graded_blocks = None;
    if again(case).is_err() {
        return e;
    }
    Error::input(
        "--uniform",
        format!("the mesh with every block ungraded is refused, graded as the case file says it is not: {e}"),
    )
}

/// A mesh checked as a mesh ([`Mesh::validate`]) and as a whole
/// ([`whole::check_mesh`]): the case's own, or one handed to
/// [`super::Model::build_on`] (an adaptive run's refined mesh).
pub(super) fn check_mesh(case: &Case, mesh: Mesh, place: &str) -> Result<Mesh> {
    let mesh = check_mesh_only(mesh, place)?;
    whole::check_mesh(case, &mesh, place)?;
    Ok(mesh)
}

/// [`Mesh::validate`] with the place of the case.
fn check_mesh_only(mesh: Mesh, place: &str) -> Result<Mesh> {
    mesh.validate().map_err(|e| Error::Mesh {
        place: place.to_string(),
        message: e.to_string(),
    })?;
    Ok(mesh)
}
