//! 3D interfaces over the same faces: the faces' counterpart of the plane
//! check of shared sides ([`super::shared_sides`]).

use super::mesh_err;
use crate::error::{clip, Result};
use crate::input::mesh::{Face, Interface, Mesh};
use std::collections::HashMap;

/// No face on a side of two 3D interfaces, whatever their coupling: two
/// interfaces over the same faces (the same surfaces named twice, or one
/// matching and one non-matching) would spring the same contact twice and
/// each report half its load. A face is known by its sorted corners. A
/// non-matching interface's master side may reach beyond its slave side (a
/// plate's whole face under a washer): only its faces whose centre lies
/// within half the shortest slave face of the slave side's box count, as in
/// the plane check.
pub(super) fn shared_faces(mesh: &Mesh, place: &str) -> Result<()> {
    let mut owner: HashMap<Vec<usize>, usize> = HashMap::new();
    for (k, iface) in mesh.interfaces.iter().enumerate() {
        for face in facing(mesh, iface) {
            let corners = &face.nodes()[..face.family.corners()];
            let mut key = corners.to_vec();
            key.sort_unstable();
            match owner.insert(key, k) {
                Some(j) if j != k => {
                    let x = centre(mesh, face);
                    return Err(mesh_err(
                        place,
                        format!(
                            "interfaces \"{}\" and \"{}\" both use the face centred at ({:.6}, {:.6}, {:.6}) of body \"{}\": the same contact would get its springs twice and each would report half the load; pose one interface per pair of surfaces",
                            clip(&mesh.interfaces[j].name),
                            clip(&iface.name),
                            x[0],
                            x[1],
                            x[2],
                            clip(&mesh.bodies[mesh.node_bodies()[corners[0]]]),
                        ),
                    ));
                }
                _ => {}
            }
        }
    }
    Ok(())
}

/// The faces of an interface that take part in its contact (module text).
fn facing<'a>(mesh: &Mesh, iface: &'a Interface) -> Vec<&'a Face> {
    let Some(nm) = &iface.nonmatching_faces else {
        return iface.faces.iter().flat_map(|f| [&f.a, &f.b]).collect();
    };
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let mut shortest = f64::INFINITY;
    for f in &nm.slave {
        let c = &f.nodes()[..f.family.corners()];
        for (i, &n) in c.iter().enumerate() {
            let (x, y) = (mesh.nodes[n], mesh.nodes[c[(i + 1) % c.len()]]);
            for k in 0..3 {
                lo[k] = lo[k].min(x[k]);
                hi[k] = hi[k].max(x[k]);
            }
            shortest = shortest.min((0..3).map(|k| (x[k] - y[k]).powi(2)).sum::<f64>().sqrt());
        }
    }
    let pad = 0.5 * shortest;
    let near = |f: &&Face| {
        let x = centre(mesh, f);
        (0..3).all(|k| x[k] > lo[k] - pad && x[k] < hi[k] + pad)
    };
    nm.slave
        .iter()
        .chain(nm.master.iter().filter(near))
        .collect()
}

/// The mean of a face's corners.
fn centre(mesh: &Mesh, f: &Face) -> [f64; 3] {
    let c = &f.nodes()[..f.family.corners()];
    let mut x = [0.0; 3];
    for &n in c {
        for (k, v) in x.iter_mut().enumerate() {
            *v += mesh.nodes[n][k] / c.len() as f64;
        }
    }
    x
}
