//! Twist: an axisymmetric model whose nodes carry the circumferential
//! displacement u_θ as a third dof (`[model] twist = true`), loaded by torques
//! and prescribed rotations about its axis (docs/case-schema.md, "Twist").
//!
//! The element is `crate::physics::element::axisymmetric_twist`, the material the six-component
//! return of `crate::physics::material::VonMises::update_twist`; the dofs per node
//! are the mesh's [`crate::input::mesh::NodeDofs`], so everything else (assembly,
//! backends, restart, output) is the model with two dofs per node. This
//! module holds the case's twist keys' checks (key by key, before the mesh
//! exists), the prescribed rotation u_θ = φ r, and the torque's traction.
//!
//! Keys: `[model] twist`, `[[boundary]] rotation` (φ, rad: u_θ = φ r on the
//! selected nodes), `[[load]] hoop_shear` (τ_θ, MPa) and `[[load]] torque`
//! (T, N·mm about +z: a traction τ_θ = T r / ∫ r² dA over the selected
//! edges, dA = 2π r ds, so that ∫ r τ_θ dA = T; proportional to r as the
//! shear on an elastic shaft's end face, uniform on a cylindrical face).

use crate::error::{clip, Error, Result};
use crate::input::case::{ranges, Case};
use crate::physics::material::Plane;

/// The largest prescribed rotation, rad: a small-strain model's twist (u_θ
/// = φ r) beyond it is no small displacement.
pub(crate) const MAX_ROTATION: f64 = 0.5;

/// A prescribed rotation about the axis times the largest factor it is
/// scaled by (rad).
pub(crate) const ROTATION: ranges::Range = ranges::Range {
    quantity: "a rotation about the axis",
    unit: "rad",
    lo: 1e-12,
    hi: MAX_ROTATION,
};

/// A torque about the axis, N·mm (a force times a coordinate).
pub(crate) const TORQUE: ranges::Range = ranges::Range {
    quantity: "a torque",
    unit: "N·mm",
    lo: 1e-6,
    hi: 1e18,
};

/// The case's twist keys one by one, and together: twist only in an
/// axisymmetric model, its loads and supports only with twist, no torque and
/// prescribed rotation on one set, and no stiffness modification (a secant
/// of a scalar slip) in a twisting model. A pretension section goes with
/// twist: its cut carries u_θ ([`crate::model::pretension`]).
pub fn check_case(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let twist = case.model.twist;
    if twist && case.model.plane != Plane::Axisymmetric {
        return Err(Error::input(
            at("[model] twist"),
            "twist = true needs plane = \"axisymmetric\": the twist u_θ is the circumferential displacement of a body of revolution",
        ));
    }
    let need = |key: String| {
        Err(Error::input(
            key,
            "needs [model] twist = true (and plane = \"axisymmetric\"): only a model with twist has the circumferential displacement u_θ",
        ))
    };
    for (i, bc) in case.boundary.iter().enumerate() {
        let Some(phi) = bc.rotation else { continue };
        let key = at(&format!(
            "boundary[{i}] (set \"{}\") rotation",
            clip(&bc.set)
        ));
        if !twist {
            return need(key);
        }
        if !(phi.is_finite() && phi.abs() <= MAX_ROTATION) {
            return Err(Error::input(
                key,
                format!("{phi} must be a finite angle of at most {MAX_ROTATION} rad in magnitude (a small rotation about the axis, u_θ = φ r)"),
            ));
        }
    }
    // a 3D model's torque on faces is checked with its loads
    // (`crate::input::case::solid`)
    let edges = case.model.plane != Plane::Solid;
    for (i, ld) in case.load.iter().enumerate().filter(|_| edges) {
        let key = |k: &str| at(&format!("load[{i}] (edges \"{}\") {k}", clip(&ld.edges)));
        for (k, v) in [("hoop_shear", ld.hoop_shear), ("torque", ld.torque)] {
            let Some(v) = v else { continue };
            if !twist {
                return need(key(k));
            }
            if !v.is_finite() || v == 0.0 {
                return Err(Error::input(
                    key(k),
                    format!("{v} must be a finite, non-zero number"),
                ));
            }
        }
        if ld.hoop_shear.is_some() && ld.torque.is_some() {
            return Err(Error::input(
                key("torque"),
                "is given with hoop_shear: both load the edges around the axis; give the torque (N·mm) or the traction τ_θ (MPa), not both",
            ));
        }
        ranges::PRESSURE.check(key("hoop_shear"), ld.hoop_shear.unwrap_or(0.0))?;
        TORQUE.check(key("torque"), ld.torque.unwrap_or(0.0))?;
        if ld.hoop_shear.is_some() || ld.torque.is_some() {
            if let Some((j, _)) = case
                .boundary
                .iter()
                .enumerate()
                .find(|(_, b)| b.rotation.is_some() && b.set == ld.edges)
            {
                return Err(Error::input(
                    key(if ld.torque.is_some() { "torque" } else { "hoop_shear" }),
                    format!("twists the set \"{}\" whose rotation boundary[{j}] prescribes: a prescribed rotation takes the torque into its reaction, and the load never acts; give one or the other", clip(&ld.edges)),
                ));
            }
        }
    }
    if !twist {
        return Ok(());
    }
    for (name, spec) in &case.interface {
        let scheme = spec.tangential.as_ref().map(|t| t.scheme);
        if scheme == Some(crate::input::case::settings::FrictionScheme::StiffnessModification) {
            let why = "its secant Δp_T/Δu_T is one of a scalar slip, and the slip of a twisting interface is a 2-vector (along the meridian and around the axis)";
            let key = format!("[interface.{name}.tangential] scheme");
            return Err(match case.option(&key) {
                Some(o) => Error::input(
                    o,
                    format!("a model with twist ([model] twist = true in {}) takes no stiffness modification: {why}; use --friction-scheme return-mapping, or none (the case's scheme)", case.source.display()),
                ),
                None => Error::input(
                    at(&format!("[interface.{}.tangential] scheme", clip(name))),
                    format!("\"stiffness-modification\" in a model with twist: {why}; use scheme = \"return-mapping\" (the default)"),
                ),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    /// docs/case-schema.md lists twist's ranges with these bounds (as
    /// `ranges::all()`'s, [`crate::input::case::ranges`]).
    #[test]
    fn the_documented_ranges_match() {
        let doc = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/case-schema.md"));
        for r in [super::ROTATION, super::TORQUE] {
            let row = doc
                .lines()
                .find(|l| l.starts_with(&format!("| {} |", r.quantity)))
                .unwrap_or_else(|| panic!("no row for {} in docs/case-schema.md", r.quantity));
            let bounds = format!("| {:e} … {:e} |", r.lo, r.hi);
            assert!(row.contains(&bounds), "{row:?} should contain {bounds:?}");
        }
    }
}
