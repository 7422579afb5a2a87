//! Interfaces of a mesh of volumes: the stacked boxes of
//! tests/data/stacked-h20.msh (hexahedra) and a box of tetrahedra beside its
//! mirror image (6-node triangles), paired face for face or as the two
//! sides of node-to-surface springs, each face numbered so that its normal
//! points from B into A.

use super::super::super::parse::{ElementBlock, MshFile};
use super::super::super::parse_msh;
use super::super::build_mesh;
use crate::input::mesh::blocks::InterfaceSpec;
use crate::input::mesh::{Face, Family, Mesh};
use crate::numbers::vec3::{cross, dot, sub};

const STACKED: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/stacked-h20.msh"
));
const BOX_T10: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/box-t10.msh"
));

fn spec(upper: &str, lower: &str, matching: Option<bool>) -> InterfaceSpec {
    InterfaceSpec {
        name: "joint".into(),
        upper: None,
        lower: None,
        upper_curve: None,
        lower_curve: None,
        upper_surface: Some(upper.into()),
        lower_surface: Some(lower.into()),
        left: None,
        right: None,
        matching,
    }
}

/// The unit normal ∂x/∂ξ × ∂x/∂η of a flat face, from its first three
/// corners (counter-clockwise seen from where it points).
fn normal(mesh: &Mesh, f: &Face) -> [f64; 3] {
    let x = |k: usize| mesh.nodes[f.nodes()[k]];
    let n = cross(sub(x(1), x(0)), sub(x(2), x(0)));
    let len = dot(n, n).sqrt();
    n.map(|v| v / len)
}

fn stacked(spec: InterfaceSpec) -> crate::error::Result<Mesh> {
    let msh = parse_msh(STACKED.as_bytes(), "s.msh").unwrap();
    build_mesh(&msh, &[spec], "case.toml")
}

/// Matching: the top's two bottom faces on two of the base's three top
/// faces, node i on node i at the same place, the normal +y (from the base,
/// B, into the top, A); A's nodes on the top, B's on the base.
#[test]
fn stacked_boxes_pair_face_for_face() {
    let mesh = stacked(spec("top.bottom", "base.top", None)).unwrap();
    mesh.validate().unwrap();
    let iface = &mesh.interfaces[0];
    assert_eq!((iface.body_a, iface.body_b), (0, 1));
    assert_eq!(mesh.bodies, ["top", "base"]);
    assert_eq!(iface.faces.len(), 2);
    assert_eq!(mesh.face_sets["base.top"].len(), 3);
    let bodies = mesh.node_bodies();
    for f in &iface.faces {
        assert_eq!((f.a.family, f.b.family), (Family::Q8, Family::Q8));
        for (&a, &b) in f.a.nodes().iter().zip(f.b.nodes()) {
            assert_ne!(a, b);
            assert_eq!(mesh.nodes[a], mesh.nodes[b]);
            assert_eq!((bodies[a], bodies[b]), (0, 1));
        }
        for n in [normal(&mesh, &f.a), normal(&mesh, &f.b)] {
            assert!((n[1] - 1.0).abs() < 1e-14, "{n:?}");
        }
    }
}

/// `matching = false`: the slave side the top's faces, the master side all
/// of the base's top, every face turned so that its normal is +y.
#[test]
fn stacked_boxes_apart_give_slave_and_master_faces_from_b_into_a() {
    let mesh = stacked(spec("top.bottom", "base.top", Some(false))).unwrap();
    let iface = &mesh.interfaces[0];
    assert!(iface.faces.is_empty());
    let nm = iface.nonmatching_faces.as_ref().unwrap();
    assert_eq!((nm.slave.len(), nm.master.len()), (2, 3));
    let bodies = mesh.node_bodies();
    for (faces, body) in [(&nm.slave, 0), (&nm.master, 1)] {
        for f in faces {
            assert!(f.nodes().iter().all(|&n| bodies[n] == body));
            assert!((normal(&mesh, f)[1] - 1.0).abs() < 1e-14);
        }
    }
}

/// The box of tetrahedra (3 × 2 × 1, Gmsh) and its mirror image in the
/// plane x = 3 as a second body "mirror" with its own nodes: their faces on
/// x = 3 are one triangulation, so box.xmax (A) pairs with mirror.face (B)
/// triangle for triangle, the normal −x (from the mirror into the box).
#[test]
fn tetrahedra_pair_triangle_for_triangle() {
    let mut msh = parse_msh(BOX_T10.as_bytes(), "t.msh").unwrap();
    mirror(&mut msh);
    let mesh = build_mesh(&msh, &[spec("box.xmax", "mirror.face", None)], "case.toml").unwrap();
    mesh.validate().unwrap();
    let iface = &mesh.interfaces[0];
    assert_eq!(iface.faces.len(), mesh.face_sets["box.xmax"].len());
    assert_eq!(iface.faces.len(), 50);
    let mut area = 0.0;
    for f in &iface.faces {
        assert_eq!(f.b.family, Family::T6);
        for (&a, &b) in f.a.nodes().iter().zip(f.b.nodes()) {
            assert_ne!(a, b);
            assert_eq!(mesh.nodes[a], mesh.nodes[b]);
        }
        let n = normal(&mesh, &f.b);
        assert!((n[0] + 1.0).abs() < 1e-12, "{n:?}");
        let x = |k: usize| mesh.nodes[f.b.nodes()[k]];
        let c = cross(sub(x(1), x(0)), sub(x(2), x(0)));
        area += 0.5 * dot(c, c).sqrt();
    }
    assert!((area - 2.0).abs() < 1e-12, "{area}");
}

/// Adds to the box of tetrahedra its mirror image x → 6 − x: new nodes,
/// the tetrahedra with two corners swapped (a positive volume), physical
/// volume "mirror" and the image of box.xmax as physical surface
/// "mirror.face".
fn mirror(msh: &mut MshFile) {
    let n0 = msh.nodes.len();
    let top = msh.node_tags.iter().copied().max().unwrap();
    for i in 0..n0 {
        let x = msh.nodes[i];
        msh.nodes.push([6.0 - x[0], x[1], x[2]]);
        msh.node_tags.push(top + 1 + i as u64);
    }
    let mut next = msh.blocks.iter().flat_map(|b| b.tags.iter()).max().unwrap() + 1;
    let mut blocks = Vec::new();
    for b in &msh.blocks {
        let (order, entity): (&[usize], i32) = match (b.dim, b.etype) {
            (3, 11) => (&[0, 2, 1, 3, 6, 5, 4, 7, 9, 8], 100),
            (2, _) if msh.entities[&(2, b.entity)] == [3] => (&[0, 1, 2, 3, 4, 5], 100),
            _ => continue,
        };
        let per = order.len();
        let conn = b
            .conn
            .chunks_exact(per)
            .flat_map(|c| order.iter().map(move |&k| n0 + c[k]))
            .collect();
        let tags = (0..b.tags.len() as u64).map(|k| next + k).collect();
        next += b.tags.len() as u64;
        blocks.push(ElementBlock {
            dim: b.dim,
            entity,
            etype: b.etype,
            at: b.at.clone(),
            tags,
            conn,
        });
    }
    msh.blocks.extend(blocks);
    msh.entities.insert((3, 100), vec![100]);
    msh.entities.insert((2, 100), vec![101]);
    msh.physical_names.insert((3, 100), "mirror".into());
    msh.physical_names.insert((2, 101), "mirror.face".into());
}

/// What a case may get wrong, each refused naming the interface.
#[test]
fn refusals_name_the_interface_and_the_surface() {
    let err = |s: InterfaceSpec| stacked(s).unwrap_err().to_string();
    let at = "case.toml: [[mesh.interface]] \"joint\": ";
    let e = err(spec("top.bottom", "top.top", None));
    assert!(
        e.starts_with(at) && e.contains("are on the same body \"top\""),
        "{e}"
    );
    let e = err(spec("top", "base.top", None));
    assert!(
        e.contains("upper_surface \"top\" is a physical volume (a body) (dimension 3) in s.msh"),
        "{e}"
    );
    let e = err(spec("top.botom", "base.top", None));
    assert!(
        e.contains("physical surface \"top.botom\" not found in s.msh (physical surfaces: base.bottom, base.left"),
        "{e}"
    );
    let mut s = spec("top.bottom", "base.top", None);
    s.upper_curve = Some("top.bottom".into());
    assert!(err(s).contains("upper_curve / lower_curve name physical curves of a plane mesh"));
    let mut s = spec("top.bottom", "base.top", None);
    s.upper_surface = None;
    assert!(err(s).contains("needs upper_surface and lower_surface"));
    let mut s = spec("top.bottom", "base.top", None);
    s.upper = Some("base".into());
    let e = err(s);
    assert!(
        e.contains("upper = \"base\" but upper_surface \"top.bottom\" lies on body \"top\"")
            && !e.contains("swapped"),
        "{e}"
    );
    // the same faces named twice: the base's top paired with the top's bottom
    // given as two entities of one physical surface
    let text = STACKED.replace(
        "4 -1000 -1000 -1000 1000 1000 1000 1 4 0",
        "4 -1000 -1000 -1000 1000 1000 1000 1 3 0",
    );
    let text = text.replacen(
        "2 4 16 2\n7 9 28 30 11 17 29 18 10\n",
        "2 4 16 2\n7 1 3 22 20 2 15 21 14\n",
        1,
    );
    assert_ne!(text, STACKED);
    let msh = parse_msh(text.as_bytes(), "s.msh").unwrap();
    let e = build_mesh(&msh, &[spec("top.bottom", "base.top", None)], "case.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("that another face of \"top.bottom\" pairs with already"),
        "{e}"
    );
}
