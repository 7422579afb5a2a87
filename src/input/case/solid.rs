//! A 3D model (`[model] plane = "3d"`): its keys checked one by one and
//! together, before the mesh exists.
//!
//! Keys: `[mesh] extrude` (the block layout swept along z,
//! `input::mesh::extrude`), `[[load]] faces` with `pressure`,
//! `traction = [t_x, t_y, t_z]` and `torque` (about the y axis), `uz` of `[[boundary]]`, `fz` of
//! `[[force]]`, `z_range` of all three, and `z` of `[[pretension]]`. A 3D key in a plane model, a
//! plane-only key in a 3D one, and every feature not yet built in 3D
//! (twist, a half model, local and adaptive refinement, a rounded or
//! chamfered block side) are
//! refused here, each naming its key. A pretension section's plane is
//! checked with the mesh ([`crate::model::pretension`]). Whether a
//! Gmsh file holds volumes is checked when it is read
//! ([`crate::model::Model::build`]).

use crate::error::{clip, Error, Result};
use crate::input::case::{ranges, Case};
use crate::physics::material::Plane;

/// The case's 3D keys, whichever the model's dimension.
pub fn check_case(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    if case.model.plane == Plane::Solid {
        check_solid(case, at)
    } else {
        refuse_solid_keys(case, at)
    }
}

/// A plane model with a key only a 3D model has.
fn refuse_solid_keys(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let need = |key: String| {
        Err(Error::input(
            key,
            "is a key of a 3D model (plane = \"3d\"); a plane or axisymmetric model has no z",
        ))
    };
    if case.mesh.extrude.is_some() {
        return need(at("[mesh] extrude"));
    }
    if case.mesh.revolve.is_some() {
        return need(at("[mesh] revolve"));
    }
    if let Some(name) = case
        .interface
        .iter()
        .find(|i| i.1.moment_point.is_some())
        .map(|i| i.0)
    {
        return need(at(&format!("[interface.{}] moment_point", clip(name))));
    }
    for (i, bc) in case.boundary.iter().enumerate() {
        for (k, given) in [("uz", bc.uz.is_some()), ("z_range", bc.z_range.is_some())] {
            if given {
                return need(at(&format!("boundary[{i}] {k}")));
            }
        }
    }
    for (i, ld) in case.load.iter().enumerate() {
        for (k, given) in [
            ("faces", ld.faces.is_some()),
            ("traction", ld.traction.is_some()),
            ("z_range", ld.z_range.is_some()),
        ] {
            if given {
                return need(at(&format!("load[{i}] {k}")));
            }
        }
        if ld.edges.is_empty() {
            return Err(Error::input(
                at(&format!("load[{i}] edges")),
                "is missing: name the edge set the traction acts on",
            ));
        }
    }
    for (i, f) in case.force.iter().enumerate() {
        for (k, given) in [("fz", f.fz != 0.0), ("z_range", f.z_range.is_some())] {
            if given {
                return need(at(&format!("force[{i}] {k}")));
            }
        }
    }
    if let Some(k) = case.pretension.iter().position(|p| p.z.is_some()) {
        return Err(Error::input(
            at(&format!("pretension[{k}] z")),
            "is the cut of a 3D model (plane = \"3d\"), the plane z = c; a plane or axisymmetric model is cut along y = h (or x = c in plane models)",
        ));
    }
    Ok(())
}

/// A 3D model: its mesh given as a sweep (or a file), its loads on faces,
/// and nothing that is plane only or not yet built in 3D.
fn check_solid(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let not_yet = |key: String, what: &str| {
        Err(Error::input(
            key,
            format!("{what} is not yet available in a 3D model (plane = \"3d\"); remove it"),
        ))
    };
    let m = &case.model;
    if let Some(t) = m.thickness.0 {
        return Err(Error::input(
            at("[model] thickness"),
            format!(
                "thickness = {t} in a 3D model: the mesh has its own depth (z); remove the key"
            ),
        ));
    }
    if m.symmetric_half {
        return Err(Error::input(
            at("[model] symmetric_half"),
            "is true in a 3D model: model the part and its symmetry planes with [[boundary]] (u normal to the plane = 0); remove the key",
        ));
    }
    if m.twist {
        return not_yet(at("[model] twist"), "twist");
    }
    check_mesh_source(case, at)?;
    if case.mesh.refine_region.is_some() {
        return not_yet(at("[mesh] refine_region"), "local refinement");
    }
    if case.adapt.is_some() {
        return not_yet(at("[adapt]"), "an adaptive run");
    }
    for (i, b) in case.mesh.block.iter().enumerate() {
        // a rounding or a chamfer (an arc is swept as the layout's nodes
        // are, a cylinder along z or a sphere's cap about the axis, and so
        // is a concave fillet: it moves them before the sweep)
        let cuts = |s: &Option<crate::input::mesh::blocks::SideShape>| {
            s.as_ref().is_some_and(|s| s.cuts() && s.radius.is_none())
        };
        for (k, given) in [("bottom", cuts(&b.bottom)), ("top", cuts(&b.top))] {
            if given {
                let key = at(&format!("[[mesh.block]] \"{}\" {k}", clip(b.name())));
                return not_yet(key, &format!("a curved side (block {i})"));
            }
        }
    }
    if let Some(r) = &case.mesh.revolve {
        check_revolve(r, case.mesh.refine, &at)?;
    }
    if let Some(e) = &case.mesh.extrude {
        crate::input::mesh::blocks::graded_axis(
            "extrude",
            "z",
            &e.z,
            &e.nz,
            &e.rz,
            case.mesh.refine,
        )
        .map_err(|m| Error::input(at("[mesh] extrude"), m.0))?;
        for &z in &e.z {
            ranges::COORDINATE.check(at("[mesh] extrude z"), z)?;
        }
    }
    for (name, spec) in &case.interface {
        if let Some(p) = &spec.moment_point {
            let key = at(&format!("[interface.{}] moment_point", clip(name)));
            if p.len() != 3 {
                return Err(Error::input(
                    key,
                    format!(
                        "expected exactly 3 numbers [x, y, z] (mm), found {}",
                        p.len()
                    ),
                ));
            }
            for &v in p {
                if !v.is_finite() {
                    return Err(Error::input(
                        key,
                        format!("{v} is not a number of mm: give a point [x, y, z]"),
                    ));
                }
                ranges::COORDINATE.check(key.clone(), v)?;
            }
        }
    }
    check_solid_loads(case, at)
}

/// Loads of a 3D model: on faces, pressure, traction and a torque about the
/// y axis ([`crate::model::loads`]) only.
fn check_solid_loads(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    for (i, ld) in case.load.iter().enumerate() {
        let key = |k: &str| at(&format!("load[{i}] {k}"));
        if !ld.edges.is_empty() {
            return Err(Error::input(
                key("edges"),
                "a 3D model loads faces: name the face set with faces = \"...\"",
            ));
        }
        if ld.faces.is_none() {
            return Err(Error::input(
                key("faces"),
                "is missing: name the face set the traction acts on",
            ));
        }
        for (k, given) in [
            ("shear", ld.shear != 0.0),
            ("hoop_shear", ld.hoop_shear.is_some()),
        ] {
            if given {
                return Err(Error::input(
                    key(k),
                    "is a plane model's key; in 3D give the traction vector, traction = [t_x, t_y, t_z] (MPa), or a torque about the y axis, torque = T (N·mm)",
                ));
            }
        }
        if let Some(t) = ld.torque {
            if !t.is_finite() || t == 0.0 {
                return Err(Error::input(
                    key("torque"),
                    format!("{t} must be a finite, non-zero number (N·mm)"),
                ));
            }
            crate::input::case::twist::TORQUE.check(key("torque"), t)?;
        }
        if let Some(t) = &ld.traction {
            if t.len() != 3 {
                return Err(Error::input(
                    key("traction"),
                    format!(
                        "expected exactly 3 numbers [t_x, t_y, t_z] (MPa), found {}",
                        t.len()
                    ),
                ));
            }
            for &v in t {
                ranges::PRESSURE.check(key("traction"), v)?;
            }
        }
        let traction = ld
            .traction
            .as_ref()
            .is_some_and(|t| t.iter().any(|&v| v != 0.0));
        if ld.pressure == 0.0 && !traction && ld.torque.is_none() {
            return Err(Error::input(
                key("pressure"),
                "and traction are both 0 or absent, and no torque: the load does nothing",
            ));
        }
    }
    for (i, bc) in case.boundary.iter().enumerate() {
        ranges::DISPLACEMENT.check(at(&format!("boundary[{i}] uz")), bc.uz.unwrap_or(0.0))?;
    }
    for (i, f) in case.force.iter().enumerate() {
        ranges::FORCE.check(at(&format!("force[{i}] fz")), f.fz)?;
    }
    Ok(())
}

/// `[mesh] revolve`: an angle of a sector, 0 < angle < 360 degrees (a whole
/// ring would need its seam joined: not built), and at least one layer.
fn check_revolve(
    r: &crate::input::case::Revolve,
    refine: usize,
    at: &dyn Fn(&str) -> String,
) -> Result<()> {
    if !(r.angle > 0.0 && r.angle < 360.0) {
        return Err(Error::input(
            at("[mesh] revolve angle"),
            format!(
                "{} must lie between 0 and 360 degrees (a sector; a whole ring is not yet built: model a half or a quarter with symmetry planes)",
                r.angle
            ),
        ));
    }
    if r.n == 0 {
        return Err(Error::input(
            at("[mesh] revolve n"),
            "must be at least 1 (the element layers around the axis)",
        ));
    }
    if r.n.checked_mul(refine).is_none_or(|n| n > 100_000) {
        return Err(Error::input(
            at("[mesh] revolve n"),
            format!(
                "{} layers (× refine {refine}) is more than 100,000 around the axis",
                r.n
            ),
        ));
    }
    Ok(())
}

/// A 3D model's mesh is made one way: a Gmsh file, a sweep along z or a
/// revolution.
fn check_mesh_source(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let given: Vec<&str> = [
        ("file", case.mesh.file.is_some()),
        ("extrude", case.mesh.extrude.is_some()),
        ("revolve", case.mesh.revolve.is_some()),
    ]
    .into_iter()
    .filter_map(|(k, g)| g.then_some(k))
    .collect();
    match given[..] {
        [] => {
            Err(Error::input(
                at("[mesh]"),
                "a 3D model needs its mesh in space: sweep the blocks along z with extrude = { z = [...], nz = [...] }, revolve them about the y axis with revolve = { angle = ..., n = ... }, or read a Gmsh mesh of volumes (file = \"...\")",
            ))
        }
        [_] => Ok(()),
        [a, b, ..] => {
            Err(Error::input(
                at(&format!("[mesh] {b}")),
                format!("is given with {a}, and each makes the 3D mesh alone: give one of file, extrude and revolve"),
            ))
        }
    }
}
