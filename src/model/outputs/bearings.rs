//! The probes a VDI 2230 rating adds ([`crate::input::case::rating`]): the
//! area mean displacement of the bolt's side of the head's and the nut's
//! bearing interfaces, whose difference is the clamped plates' compression
//! (with the rough layers between them), so that the run's own resiliences
//! δ_P and δ_S can be split at the lock ([`crate::verdict`]).

use super::probes::{surface, Probe};
use crate::error::{clip, Error, Result};
use crate::input::case::rating::RatingSpec;
use crate::input::case::Case;
use crate::input::mesh::Mesh;
use crate::model::interface::InterfaceModel;

/// The probe names of rating `name`: head bearing, nut bearing.
pub fn names(name: &str) -> [String; 2] {
    [
        format!("{name}: head bearing"),
        format!("{name}: nut bearing"),
    ]
}

/// Two probes per bolt rating; refuses a section or an interface the case
/// does not have, and a bearing interface the bolt's body is not on.
pub fn build(
    case: &Case,
    mesh: &Mesh,
    interfaces: &[InterfaceModel],
    place: &str,
) -> Result<Vec<Probe>> {
    let mut out = Vec::new();
    for (i, r) in case.rating.iter().enumerate() {
        let RatingSpec::Bolt(b) = r else { continue };
        let at = |key: &str| format!("{place}: rating[{i}] (VDI 2230-1:2015) {key}");
        let section = case
            .pretension
            .iter()
            .find(|p| p.name == b.pretension)
            .ok_or_else(|| {
                let known: Vec<&str> = case.pretension.iter().map(|p| p.name.as_str()).collect();
                Error::input(
                    at("pretension"),
                    format!(
                        "names no [[pretension]] section \"{}\" (sections: {})",
                        clip(&b.pretension),
                        list(&known)
                    ),
                )
            })?;
        let body = mesh
            .bodies
            .iter()
            .position(|x| *x == section.body)
            .unwrap_or(usize::MAX);
        for (key, iface, probe) in [("head", &b.head, 0), ("nut", &b.nut, 1)] {
            let im = find(interfaces, iface).ok_or_else(|| {
                let known: Vec<&str> = interfaces.iter().map(|m| m.name.as_str()).collect();
                Error::input(
                    at(key),
                    format!(
                        "names no interface \"{}\" (interfaces: {})",
                        clip(iface),
                        list(&known)
                    ),
                )
            })?;
            if im.body_a != body && im.body_b != body {
                return Err(Error::input(
                    at(key),
                    format!(
                        "interface \"{}\" is between {} and {}, not on the bolt's body \"{}\": name the interface the {key} bears on",
                        clip(iface),
                        mesh.bodies[im.body_a],
                        mesh.bodies[im.body_b],
                        clip(&section.body)
                    ),
                ));
            }
            let name = names(r.name())[probe].clone();
            if case.probe.iter().any(|p| p.name == name) {
                return Err(Error::input(
                    at(key),
                    format!(
                        "adds the probe \"{}\", a name a [[probe]] has: rename that probe",
                        clip(&name)
                    ),
                ));
            }
            out.push(surface(name, im, body, mesh));
        }
    }
    Ok(out)
}

fn find<'a>(interfaces: &'a [InterfaceModel], name: &str) -> Option<&'a InterfaceModel> {
    interfaces.iter().find(|m| m.name == name)
}

fn list(names: &[&str]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}
