//! A 3D `.msh` (20-node hexahedra, type 17, and 10-node tetrahedra, type
//! 11) to the solver's [`Mesh`]: physical volumes → bodies, physical
//! surfaces (8-node quadrangles, 6-node triangles) → face sets walked
//! outward and node sets of the same name, physical curves and points →
//! node sets; each `[[mesh.interface]]` between two physical surfaces
//! ([`super::surfaces`]).

use super::super::parse::{ElementBlock, MshFile};
use super::mesh_err;
use crate::error::Result;
use crate::input::mesh::blocks::InterfaceSpec;
use crate::input::mesh::{Element, Face, Family, Mesh};
use std::collections::{BTreeMap, HashMap};

/// Builds a 3D mesh: the file holds volume elements.
pub(super) fn build_solid_mesh(
    msh: &MshFile,
    interfaces: &[InterfaceSpec],
    place: &str,
) -> Result<Mesh> {
    let file = msh.name.as_str();
    let (mut mesh, new_id, tag_of) = super::bodies(msh, 3)?;
    let surface_bodies = add_boundary_sets(msh, &new_id, &mut mesh, file)?;
    for spec in interfaces {
        let iface =
            super::surfaces::pair_surfaces(msh, &mesh, &surface_bodies, &tag_of, spec, place)?;
        mesh.interfaces.push(iface);
    }
    Ok(mesh)
}

/// The elements of one block of a body, in this code's node order.
pub(super) fn add_elements_of(b: &ElementBlock, body: usize, new_id: &[usize], mesh: &mut Mesh) {
    let family = if b.etype == 17 {
        Family::H20
    } else {
        Family::T10
    };
    let solid = family.solid().expect("a volume block's family");
    let order = solid.gmsh_to_local();
    for conn in b.conn.chunks_exact(family.nodes()) {
        let mut n = [0; 20];
        for (g, &c) in conn.iter().enumerate() {
            n[order[g]] = new_id[c];
        }
        mesh.elements
            .push(Element::new(family, &n[..family.nodes()], body));
    }
}

/// Physical surfaces → face sets (each face as the element it bounds walks
/// it: outward) and node sets; physical curves and points → node sets.
/// Returns the bodies each physical surface lies on (sorted; a surface
/// without elements is not listed).
fn add_boundary_sets(
    msh: &MshFile,
    new_id: &[usize],
    mesh: &mut Mesh,
    file: &str,
) -> Result<BTreeMap<String, Vec<usize>>> {
    // every element face by its sorted corners: the face as the element
    // walks it, how many elements hold it, and the body of the (first) one
    let mut faces: HashMap<Vec<usize>, (Face, usize, usize)> = HashMap::new();
    for el in &mesh.elements {
        let solid = el.family.solid().expect("a mesh of volumes");
        for local in solid.faces() {
            let nodes: Vec<usize> = local.iter().map(|&a| el.nodes()[a]).collect();
            let family = if nodes.len() == 8 {
                Family::Q8
            } else {
                Family::T6
            };
            let mut key = nodes[..family.corners()].to_vec();
            key.sort_unstable();
            faces
                .entry(key)
                .or_insert((Face::new(family, &nodes), 0, el.body))
                .1 += 1;
        }
    }
    let mut surface_bodies: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for b in msh.blocks.iter().filter(|b| b.dim < 3) {
        let Some(phys) = msh.entities.get(&(b.dim, b.entity)) else {
            return mesh_err(
                &b.at,
                format!(
                    "entity {} of dimension {} is not listed in $Entities",
                    b.entity, b.dim
                ),
            );
        };
        let per = b.conn.len() / b.tags.len().max(1);
        for t in phys {
            let Some(name) = msh.physical_names.get(&(b.dim, *t)) else {
                return mesh_err(file, format!("physical group {t} of dimension {} has no name in $PhysicalNames (sets are named by their physical names)", b.dim));
            };
            if mesh
                .bodies
                .iter()
                .any(|body| format!("{body}.all") == *name)
            {
                return mesh_err(
                    file,
                    format!("physical group \"{name}\" has the name of a body's own node set"),
                );
            }
            let mut nodes: Vec<usize> = Vec::with_capacity(b.conn.len());
            for (k, conn) in b.conn.chunks_exact(per.max(1)).enumerate() {
                let ids: Vec<usize> = conn.iter().map(|&c| new_id[c]).collect();
                if ids.contains(&usize::MAX) {
                    return mesh_err(&b.at, format!("element {} of physical group \"{name}\" has a node on no volume element (is its volume in a physical volume?)", b.tags[k]));
                }
                nodes.extend(&ids);
                if b.dim != 2 {
                    continue;
                }
                let corners = if per == 8 { 4 } else { 3 };
                let mut key = ids[..corners].to_vec();
                key.sort_unstable();
                match faces.get(&key) {
                    Some((face, 1, body)) => {
                        mesh.face_sets.entry(name.clone()).or_default().push(face.clone());
                        let on = surface_bodies.entry(name.clone()).or_default();
                        if let Err(at) = on.binary_search(body) {
                            on.insert(at, *body);
                        }
                    }
                    Some(_) => return mesh_err(&b.at, format!("face {} of physical surface \"{name}\" lies between two elements: a face set is on a body's boundary", b.tags[k])),
                    None => return mesh_err(&b.at, format!("element {} of physical surface \"{name}\" is no face of a volume element", b.tags[k])),
                }
            }
            let set = mesh.node_sets.entry(name.clone()).or_default();
            set.extend(nodes);
            set.sort_unstable();
            set.dedup();
        }
    }
    Ok(surface_bodies)
}

#[cfg(test)]
mod tests {
    use super::super::super::parse_msh;
    use super::*;
    use crate::physics::element::face::face_forces;
    use crate::physics::element::solid3::ElementGeometry3;

    fn read(name: &str) -> Mesh {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(name);
        let bytes = std::fs::read(&path).unwrap();
        let msh = parse_msh(&bytes, name).unwrap();
        super::super::build_mesh(&msh, &[], "case.toml").unwrap()
    }

    /// The 3 × 2 × 1 box of 20-node hexahedra and of 10-node tetrahedra
    /// (Gmsh 4.15): valid elements of the box's volume, and each physical
    /// surface a face set walked outward (a unit pressure on it sums to
    /// −n × its area) whose node set lies on its plane.
    #[test]
    fn a_box_of_volumes_reads_with_outward_face_sets() {
        for (name, family) in [("box-h20.msh", Family::H20), ("box-t10.msh", Family::T10)] {
            let mesh = read(name);
            mesh.validate().unwrap();
            assert_eq!(mesh.dim(), 3);
            assert!(mesh.elements.iter().all(|el| el.family == family), "{name}");
            let solid = family.solid().unwrap();
            let rule = solid.rule(true);
            let volume: f64 = (0..mesh.elements.len())
                .map(|e| {
                    let c = mesh.element_coords3(e);
                    ElementGeometry3::new(solid, &c[..family.nodes()], &rule)
                        .unwrap()
                        .volume()
                })
                .sum();
            assert!((volume - 6.0).abs() < 1e-12, "{name}: {volume}");
            let size = [3.0, 2.0, 1.0];
            for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
                for (end, sign) in [("min", -1.0), ("max", 1.0)] {
                    let set = format!("box.{axis}{end}");
                    let mut total = [0.0; 3];
                    for face in &mesh.face_sets[&set] {
                        let x: Vec<[f64; 3]> =
                            face.nodes().iter().map(|&n| mesh.nodes[n]).collect();
                        let f = face_forces(face.family, &x, 1.0, [0.0; 3]);
                        for fa in f.iter().take(face.nodes().len()) {
                            for c in 0..3 {
                                total[c] += fa[c];
                            }
                        }
                    }
                    let area = size[(k + 1) % 3] * size[(k + 2) % 3];
                    for c in 0..3 {
                        let want = if c == k { -sign * area } else { 0.0 };
                        assert!((total[c] - want).abs() < 1e-12, "{name} {set}: {total:?}");
                    }
                    let plane = if sign < 0.0 { 0.0 } else { size[k] };
                    let nodes = &mesh.node_sets[&set];
                    assert!(nodes
                        .iter()
                        .all(|&n| (mesh.nodes[n][k] - plane).abs() < 1e-12));
                }
            }
        }
    }

    /// A plane mesh keeps refusing a node off z = 0, naming its line.
    #[test]
    fn a_plane_mesh_off_its_plane_is_refused() {
        let text = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/box-h20.msh"),
        )
        .unwrap();
        // the box without its volume elements: surfaces in space
        let msh = parse_msh(text.as_bytes(), "b.msh").unwrap();
        let mut plane = msh.clone();
        plane.blocks.retain(|b| b.dim < 3);
        let e = super::super::build_mesh(&plane, &[], "case.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("a plane mesh (no volume elements) must lie in the plane z = 0"),
            "{e}"
        );
        assert!(e.contains("b.msh:"), "{e}");
    }
}
