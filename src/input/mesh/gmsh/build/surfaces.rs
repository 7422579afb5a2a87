//! The interfaces of a mesh of volumes: each `[[mesh.interface]]` between
//! the physical surfaces `upper_surface` (body A) and `lower_surface`
//! (body B), two face sets on two bodies.
//!
//! ```text
//!   matching (default):  every node of A's surface has a partner on B's, a
//!                        distinct node within tol = 1e-9 × the shortest face
//!                        side of the two surfaces; the partners of an A
//!                        face's nodes are the nodes of one face of B
//!                        (corners and midsides), each B face paired once
//!   ContactFace { a, b }: b = B's face walked outward from B (its normal
//!                        ∂x/∂ξ × ∂x/∂η from B into A), a[i] = the A node
//!                        paired with b[i]; A's own outward walk must be a's
//!                        reversed (the faces face each other)
//!   matching = false:    slave = A's faces turned round (normal from B
//!                        into A), master = B's faces as walked outward
//! ```
//!
//! B's surface may reach beyond A's: only the faces of B that partner a face
//! of A are in contact. Because every A face must find a whole B face (not
//! only nodes), a B surface meshed finer or coarser than A's over the
//! common part is refused as well: a node of B inside A's extent without a
//! partner would leave a B face unpaired next to a paired one.

use super::super::parse::MshFile;
use crate::error::{Error, Result};
use crate::input::mesh::blocks::InterfaceSpec;
use crate::input::mesh::{ContactFace, Face, Interface, Mesh, NonMatchingFaces};
use std::collections::{BTreeMap, HashMap};

/// The interface `spec` of a mesh of volumes (module text); `surface_bodies`
/// lists the bodies each physical surface lies on.
pub(super) fn pair_surfaces(
    msh: &MshFile,
    mesh: &Mesh,
    surface_bodies: &BTreeMap<String, Vec<usize>>,
    tag_of: &[u64],
    spec: &InterfaceSpec,
    place: &str,
) -> Result<Interface> {
    let at = format!("{place}: [[mesh.interface]] \"{}\"", spec.name);
    let bad = |m: String| Error::input(&at, m);
    if spec.left.is_some() || spec.right.is_some() {
        return Err(bad(
            "left / right name blocks of a generated mesh ([[mesh.block]]); a mesh read from a file pairs upper_surface (body A) with lower_surface (body B)"
                .into(),
        ));
    }
    if spec.upper_curve.is_some() || spec.lower_curve.is_some() {
        return Err(bad(format!(
            "upper_curve / lower_curve name physical curves of a plane mesh; {} is a mesh of volumes: give upper_surface and lower_surface (physical surfaces)",
            msh.name
        )));
    }
    let (Some(upper), Some(lower)) = (&spec.upper_surface, &spec.lower_surface) else {
        return Err(bad(
            "a mesh of volumes read from a file needs upper_surface and lower_surface (physical surface names)"
                .into(),
        ));
    };
    let ua = surface_on_body(msh, mesh, surface_bodies, upper, "upper_surface", &at)?;
    let lb = surface_on_body(msh, mesh, surface_bodies, lower, "lower_surface", &at)?;
    check_named_bodies(mesh, spec, [ua, lb], [upper, lower]).map_err(bad)?;
    if ua == lb {
        return Err(bad(format!(
            "upper_surface \"{upper}\" and lower_surface \"{lower}\" are on the same body \"{}\": an interface joins two bodies",
            mesh.bodies[ua]
        )));
    }
    let mut iface = Interface {
        name: spec.name.clone(),
        body_a: ua,
        body_b: lb,
        ..Default::default()
    };
    let (a_faces, b_faces) = (&mesh.face_sets[upper], &mesh.face_sets[lower]);
    if spec.matching == Some(false) {
        let turned = |f: &Face| {
            let nodes: Vec<usize> = f.family.reversed().iter().map(|&k| f.nodes()[k]).collect();
            Face::new(f.family, &nodes)
        };
        iface.nonmatching_faces = Some(NonMatchingFaces {
            slave: a_faces.iter().map(turned).collect(),
            master: b_faces.clone(),
        });
        return Ok(iface);
    }
    let sides = Sides {
        mesh,
        tag_of,
        file: &msh.name,
        upper,
        lower,
    };
    iface.faces = sides.coincident_faces(a_faces, b_faces).map_err(bad)?;
    Ok(iface)
}

/// `upper = "..."` and `lower = "..."`, when given, against the bodies the
/// surfaces lie on (`bodies` = [A, B]); a hint when they are swapped.
fn check_named_bodies(
    mesh: &Mesh,
    spec: &InterfaceSpec,
    bodies: [usize; 2],
    surfaces: [&str; 2],
) -> std::result::Result<(), String> {
    let name = |b: usize| mesh.bodies[b].as_str();
    let swapped = spec.upper.as_deref() == Some(name(bodies[1]))
        && spec.lower.as_deref() == Some(name(bodies[0]));
    let given = [(&spec.upper, "upper"), (&spec.lower, "lower")];
    for (k, (given, side)) in given.into_iter().enumerate() {
        let Some(g) = given else { continue };
        if g != name(bodies[k]) {
            let hint = if swapped {
                format!(": upper_surface and lower_surface are swapped (upper_surface must lie on body A, \"{}\", the slave side with matching = false)", name(bodies[1]))
            } else {
                String::new()
            };
            return Err(format!(
                "{side} = \"{g}\" but {side}_surface \"{}\" lies on body \"{}\"{hint}",
                surfaces[k],
                name(bodies[k])
            ));
        }
    }
    Ok(())
}

/// The one body the physical surface `name` lies on; an error naming what
/// `name` is instead (empty, on two bodies, another dimension, unknown).
fn surface_on_body(
    msh: &MshFile,
    mesh: &Mesh,
    surface_bodies: &BTreeMap<String, Vec<usize>>,
    name: &str,
    key: &str,
    at: &str,
) -> Result<usize> {
    let refuse = |m: String| Err(Error::input(at, m));
    let file = &msh.name;
    match surface_bodies.get(name).map(Vec::as_slice) {
        Some([b]) => return Ok(*b),
        Some(more) => {
            let names: Vec<String> = more
                .iter()
                .map(|&b| format!("\"{}\"", mesh.bodies[b]))
                .collect();
            return refuse(format!(
                "{key} \"{name}\" in {file} lies on the bodies {}: an interface surface must lie on one body (split it into one physical surface per body)",
                names.join(" and ")
            ));
        }
        None => {}
    }
    if let Some((&(d, _), _)) = msh.physical_names.iter().find(|(_, n)| *n == name) {
        if d == 2 {
            return refuse(format!(
                "{key} \"{name}\" in {file} is empty: it holds no faces of volume elements (8-node quadrangles or 6-node triangles; is its surface meshed?)"
            ));
        }
        let what = [
            "a physical point",
            "a physical curve",
            "a physical surface",
            "a physical volume (a body)",
        ][d.clamp(0, 3) as usize];
        return refuse(format!(
            "{key} \"{name}\" is {what} (dimension {d}) in {file}, not a physical surface of 8-node quadrangles or 6-node triangles"
        ));
    }
    let known: Vec<&str> = surface_bodies.keys().map(String::as_str).collect();
    refuse(format!(
        "{key}: physical surface \"{name}\" not found in {file} (physical surfaces: {})",
        known.join(", ")
    ))
}

/// The two surfaces of a matching interface, for pairing and messages.
struct Sides<'a> {
    mesh: &'a Mesh,
    tag_of: &'a [u64],
    file: &'a str,
    upper: &'a str,
    lower: &'a str,
}

impl Sides<'_> {
    /// "node 12 at (2.5, 0, 1)": a node by its tag in the file and its place.
    fn node(&self, n: usize) -> String {
        let x = self.mesh.nodes[n];
        format!("node {} at ({}, {}, {})", self.tag_of[n], x[0], x[1], x[2])
    }

    /// "the face of \"a.bottom\" with corners at nodes 1, 2, 5, 4 (centre …)".
    fn face(&self, surface: &str, f: &Face) -> String {
        let corners = &f.nodes()[..f.family.corners()];
        let tags: Vec<String> = corners
            .iter()
            .map(|&n| self.tag_of[n].to_string())
            .collect();
        let mut c = [0.0; 3];
        for &n in corners {
            for (k, v) in c.iter_mut().enumerate() {
                *v += self.mesh.nodes[n][k] / corners.len() as f64;
            }
        }
        format!(
            "the face of \"{surface}\" with corners at nodes {} (centre ({:.6}, {:.6}, {:.6}))",
            tags.join(", "),
            c[0],
            c[1],
            c[2]
        )
    }

    /// The contact faces (module text): each face of A with the face of B
    /// its nodes' partners make.
    fn coincident_faces(
        &self,
        a_faces: &[Face],
        b_faces: &[Face],
    ) -> std::result::Result<Vec<ContactFace>, String> {
        let mesh = self.mesh;
        let tol = 1e-9 * shortest_side(mesh, a_faces.iter().chain(b_faces));
        let partners = Partners::new(mesh, b_faces, tol);
        let mut b_of: HashMap<Vec<usize>, usize> = HashMap::with_capacity(b_faces.len());
        for (k, f) in b_faces.iter().enumerate() {
            b_of.insert(corner_key(f.nodes(), f.family.corners()), k);
        }
        let mut used = vec![false; b_faces.len()];
        let mut faces = Vec::with_capacity(a_faces.len());
        for fa in a_faces {
            let mut p = Vec::with_capacity(fa.nodes().len());
            for &n in fa.nodes() {
                let Some(m) = partners.of(mesh.nodes[n]) else {
                    return Err(format!(
                        "{} of surface \"{}\" in {} has no partner on surface \"{}\" within {tol:.1e} mm (the two sides must have coincident nodes; an interference is the law's negative `gap`, not an overlap in the mesh, and sides meshed apart take `matching = false`)",
                        self.node(n), self.upper, self.file, self.lower
                    ));
                };
                p.push(m);
            }
            let corners = fa.family.corners();
            let whole = b_of
                .get(&corner_key(&p, corners))
                .filter(|&&k| b_faces[k].family == fa.family)
                .filter(|&&k| b_faces[k].nodes().iter().all(|m| p.contains(m)));
            let Some(&k) = whole else {
                return Err(format!(
                    "{}: its nodes' partners on \"{}\" are not the nodes of one face of it (the two surfaces must be meshed alike, face for face, over their common part; sides meshed apart take `matching = false`)",
                    self.face(self.upper, fa), self.lower
                ));
            };
            if std::mem::replace(&mut used[k], true) {
                return Err(format!(
                    "{} pairs with a face of \"{}\" that another face of \"{}\" pairs with already (a face given twice?)",
                    self.face(self.upper, fa), self.lower, self.upper
                ));
            }
            let fb = &b_faces[k];
            // a[j]: the A node whose partner is fb's node j
            let a: Vec<usize> = fb
                .nodes()
                .iter()
                .map(|m| fa.nodes()[p.iter().position(|q| q == m).unwrap_or(0)])
                .collect();
            if same_turn(&fa.nodes()[..corners], &a[..corners]) {
                return Err(format!(
                    "{} and its partner on \"{}\" do not face each other: both are walked the same way seen from outside their bodies, so bodies \"{}\" and \"{}\" lie on the same side of it (an interface is between two bodies on either side of the surface)",
                    self.face(self.upper, fa),
                    self.lower,
                    mesh.bodies[mesh.node_bodies()[fa.nodes()[0]]],
                    mesh.bodies[mesh.node_bodies()[fb.nodes()[0]]]
                ));
            }
            faces.push(ContactFace {
                a: Face::new(fb.family, &a),
                b: fb.clone(),
            });
        }
        Ok(faces)
    }
}

/// The sorted first `corners` nodes of `nodes`: a face's key.
fn corner_key(nodes: &[usize], corners: usize) -> Vec<usize> {
    let mut key = nodes[..corners].to_vec();
    key.sort_unstable();
    key
}

/// Whether the cycles of corners `x` and `y` (the same nodes) run the same
/// way round: `y` is a rotation of `x`, not of `x` reversed.
fn same_turn(x: &[usize], y: &[usize]) -> bool {
    let n = x.len();
    let Some(k) = x.iter().position(|&v| v == y[0]) else {
        return false;
    };
    n > 2 && x[(k + 1) % n] == y[1]
}

/// The shortest side (corner to corner) of the faces.
fn shortest_side<'a>(mesh: &Mesh, faces: impl Iterator<Item = &'a Face>) -> f64 {
    let mut h = f64::INFINITY;
    for f in faces {
        let c = &f.nodes()[..f.family.corners()];
        for (i, &p) in c.iter().enumerate() {
            let (x, y) = (mesh.nodes[p], mesh.nodes[c[(i + 1) % c.len()]]);
            let d = (0..3).map(|k| (x[k] - y[k]).powi(2)).sum::<f64>().sqrt();
            h = h.min(d);
        }
    }
    h
}

/// The nodes of B's faces sorted by x, to find the one within `tol` of a
/// point (the nearest, if several).
struct Partners<'a> {
    mesh: &'a Mesh,
    by_x: Vec<usize>,
    tol: f64,
}

impl<'a> Partners<'a> {
    fn new(mesh: &'a Mesh, faces: &[Face], tol: f64) -> Partners<'a> {
        let mut by_x: Vec<usize> = faces
            .iter()
            .flat_map(|f| f.nodes().iter().copied())
            .collect();
        by_x.sort_unstable();
        by_x.dedup();
        by_x.sort_by(|&p, &q| mesh.nodes[p][0].total_cmp(&mesh.nodes[q][0]));
        Partners { mesh, by_x, tol }
    }

    fn of(&self, x: [f64; 3]) -> Option<usize> {
        let nodes = &self.mesh.nodes;
        let from = self
            .by_x
            .partition_point(|&m| nodes[m][0] < x[0] - self.tol);
        self.by_x[from..]
            .iter()
            .take_while(|&&m| nodes[m][0] <= x[0] + self.tol)
            .map(|&m| {
                let d = (0..3)
                    .map(|k| (nodes[m][k] - x[k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                (d, m)
            })
            .filter(|&(d, _)| d <= self.tol)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, m)| m)
    }
}

#[cfg(test)]
mod tests;
