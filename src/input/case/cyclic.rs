//! Cyclic symmetry (`[model] cyclic = { sectors = N, faces = [A, B] }`): a
//! 3D model that is one sector of a part made of N equal sectors about the
//! model's axis (the y axis, the axis `[mesh] revolve` sweeps about), its
//! two cut faces tied by rotational periodicity ([`crate::model::cyclic`]).
//!
//! The key sits in `[model]` beside `symmetric_half`: like it, it says what
//! part the mesh is of, and so which outputs are scaled to the whole part;
//! the ties themselves follow from the mesh and the faces. Checked here,
//! before the mesh exists: a 3D model only, 2 ≤ N ≤ [`MAX_SECTORS`], two
//! face names, not the same. Everything that needs the mesh (the faces'
//! nodes, their partners, the sector's angle, the supports on the faces) is
//! checked when the model is built.

use crate::error::{clip, Error, Result};
use crate::input::case::Case;
use crate::physics::material::Plane;
use serde::{Deserialize, Serialize};

/// The fewest sectors: a half (N = 2, 180°).
pub const MIN_SECTORS: usize = 2;
/// The most sectors: 360 (1° each), beyond any bolt circle or blade count a
/// designer models one sector of.
pub const MAX_SECTORS: usize = 360;

/// `[model] cyclic`: the mesh is one of `sectors` equal sectors about the y
/// axis; every node of `faces[1]` is a node of `faces[0]` rotated by the
/// sector's angle 360°/N about it.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CyclicSpec {
    /// N, the part's number of sectors (the sector's angle is 360°/N).
    pub sectors: usize,
    /// The two cut faces (node sets): the first, and the second, its image
    /// rotated by 360°/N about the y axis.
    pub faces: Vec<String>,
}

/// The `[model] cyclic` key alone: a 3D model, N in range, two distinct
/// face names.
pub fn check_case(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let Some(c) = &case.model.cyclic else {
        return Ok(());
    };
    if case.model.plane != Plane::Solid {
        return Err(Error::input(
            at("[model] cyclic"),
            "needs plane = \"3d\": a cyclic sector is a 3D sector of a part about its y axis; a plane model has no sector to tie, and an axisymmetric one is the whole revolution already",
        ));
    }
    if !(MIN_SECTORS..=MAX_SECTORS).contains(&c.sectors) {
        return Err(Error::input(
            at("[model] cyclic sectors"),
            format!(
                "{} must be a whole number of sectors from {MIN_SECTORS} (a half, 180°) to {MAX_SECTORS} (1° each)",
                c.sectors
            ),
        ));
    }
    let [a, b] = c.faces.as_slice() else {
        return Err(Error::input(
            at("[model] cyclic faces"),
            format!(
                "expected exactly 2 node sets [first, second] (the cut faces; the second is the first rotated by 360°/N), found {}",
                c.faces.len()
            ),
        ));
    };
    if a == b {
        return Err(Error::input(
            at("[model] cyclic faces"),
            format!(
                "names \"{}\" twice: the two cut faces of the sector are two node sets (e.g. \"part.theta0\" and \"part.theta1\" of a revolved layout)",
                clip(a)
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/case-schema.md states the range of `sectors` as the code holds it.
    #[test]
    fn the_documented_range_of_sectors_is_the_codes() {
        let doc = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/case-schema.md"));
        for text in [
            format!("from **{MIN_SECTORS} to {MAX_SECTORS}**"),
            format!("outside {MIN_SECTORS} … {MAX_SECTORS};"),
        ] {
            assert!(doc.contains(&text), "docs/case-schema.md: {text}");
        }
    }
}
