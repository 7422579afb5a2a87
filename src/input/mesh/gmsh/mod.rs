//! Meshes read from Gmsh `.msh` files, format version 4.1, ASCII or binary.
//!
//! Physical surfaces become bodies (named by their physical names), physical
//! curves become node sets and edge sets of the same name (a mesh of volumes:
//! physical volumes are the bodies and physical surfaces face sets,
//! `build/solid.rs`), and each
//! `[[mesh.interface]]` pairs the nodes of an upper body's curve with the
//! coincident nodes of a lower body's curve (or, with `matching = false`,
//! takes the two curves as the slave and master sides of node-to-segment
//! springs). Bodies must be meshed with 8-node quads (element type 16) and
//! curves with 3-node lines (type 8): in Gmsh, `Mesh.ElementOrder = 2;
//! Mesh.SecondOrderIncomplete = 1;` and recombined surfaces. See
//! `docs/gmsh.md`.
//!
//! The reader never panics: every count is checked against the bytes left in
//! the file before anything is allocated, arithmetic is checked, and every
//! error is one line naming the file and the line (ASCII) or byte offset
//! (binary data) where the problem is.
//!
//! `parse` reads the file into a `MshFile` (sections, counts, binary or
//! ASCII numbers); `build` turns that into the solver's [`Mesh`] (bodies,
//! node and edge sets, paired interface curves).

mod build;
mod parse;

pub use build::build_mesh;
pub use parse::parse_msh;

use super::Mesh;
use crate::error::Result;
use crate::input::mesh::blocks::InterfaceSpec;
use std::path::Path;

/// Reads a `.msh` file and builds the mesh: bodies from physical surfaces,
/// node and edge sets from physical curves, and the interfaces.
/// `place` names the case (for errors about its keys).
pub fn read(path: &Path, interfaces: &[InterfaceSpec], place: &str) -> Result<Mesh> {
    let bytes =
        crate::input::case::read_input(path, crate::input::case::MAX_MESH_BYTES, "mesh file")?;
    let msh = parse_msh(&bytes, &path.display().to_string())?;
    build_mesh(&msh, interfaces, place)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TINY: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/tiny.msh"));
    const TINY_BIN: &[u8] = include_bytes!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/tiny-bin.msh"
    ));

    fn contact() -> InterfaceSpec {
        InterfaceSpec {
            name: "contact".into(),
            upper: None,
            lower: None,
            upper_curve: Some("punch.bottom".into()),
            lower_curve: Some("foundation.top".into()),
            upper_surface: None,
            lower_surface: None,
            left: None,
            right: None,
            matching: None,
        }
    }

    fn build(text: &str) -> Result<Mesh> {
        let msh = parse_msh(text.as_bytes(), "t.msh")?;
        build_mesh(&msh, &[contact()], "case.toml")
    }

    /// The error text of a file that must be rejected; checks it is one line.
    fn err(bytes: &[u8]) -> String {
        let r = parse_msh(bytes, "t.msh").and_then(|m| build_mesh(&m, &[contact()], "case.toml"));
        let e = r.expect_err("must be rejected").to_string();
        assert!(!e.contains('\n'), "{e}");
        e
    }

    #[test]
    fn tiny_mesh_ascii_and_binary() {
        let a = parse_msh(TINY.as_bytes(), "tiny.msh").unwrap();
        let b = parse_msh(TINY_BIN, "tiny-bin.msh").unwrap();
        assert!(!a.binary && b.binary);
        assert_eq!(a.nodes.len(), 21);
        assert_eq!(a.node_tags, b.node_tags);
        assert_eq!(a.physical_names, b.physical_names);
        assert_eq!(a.entities, b.entities);
        assert_eq!(a.physical_names[&(2, 1)], "punch");
        let m = build(TINY).unwrap();
        m.validate().unwrap();
        assert_eq!(m.bodies, ["punch", "foundation"]);
        assert_eq!(m.elements.len(), 3);
        assert_eq!(m.nodes.len(), 21);
        assert_eq!(m.node_sets["punch.bottom"].len(), 3);
        assert_eq!(m.node_sets["foundation.top"].len(), 5);
        assert_eq!(m.node_sets["punch.all"].len(), 8);
        let iface = &m.interfaces[0];
        assert_eq!((iface.body_a, iface.body_b, iface.edges.len()), (0, 1, 1));
        let e = &iface.edges[0];
        for i in 0..3 {
            assert_ne!(e.a[i], e.b[i]);
            assert_eq!(m.nodes[e.a[i]], m.nodes[e.b[i]]);
        }
        // along +x: the lower body on the right of the walk
        assert!(m.nodes[e.a[0]][0] < m.nodes[e.a[2]][0]);
        // the top edge of the punch walked with the punch on its left: −x
        let top = m.edge_sets["punch.top"][0];
        assert!(m.nodes[top[0]][0] > m.nodes[top[2]][0]);
        // loads on the foundation's two top curves: one edge set of two edges
        assert_eq!(m.edge_sets["foundation.top"].len(), 2);
    }

    #[test]
    fn clockwise_quads_are_turned_counter_clockwise() {
        let ccw = build(TINY).unwrap();
        let text = TINY.replace("11 1 2 3 4 11 12 13 14 ", "11 1 4 3 2 14 13 12 11 ");
        assert_ne!(text, TINY);
        let turned = build(&text).unwrap();
        turned.validate().unwrap();
        assert_eq!(turned.elements[0].nodes(), ccw.elements[0].nodes());
    }

    #[test]
    fn unknown_sections_are_skipped() {
        let text = TINY.replace(
            "$Entities",
            "$Comments\nanything $Nodes 1 2 3\n$EndComments\n$Entities",
        );
        build(&text).unwrap();
    }

    #[test]
    fn header_errors() {
        assert!(err(b"").contains("empty file"));
        let e = err(TINY.replace("4.1 0 8", "2.2 0 8").as_bytes());
        assert!(
            e.starts_with("mesh t.msh:2: MSH format version 2.2 is not supported"),
            "{e}"
        );
        assert!(err(TINY.replace("4.1 0 8", "4.1 0 4").as_bytes()).contains("data size 4"));
        assert!(err(b"hello").contains("must start with $MeshFormat"));
        let e = err(TINY.replace("PhysicalNames", "PhysicalNamez").as_bytes());
        assert!(e.contains("t.msh: missing section $PhysicalNames"), "{e}");
        let mut big = TINY_BIN.to_vec();
        let at = big.windows(8).position(|w| w == b"4.1 1 8\n").unwrap() + 8;
        big[at..at + 4].copy_from_slice(&1i32.to_be_bytes());
        let e = err(&big);
        assert!(
            e.contains("big-endian") && e.contains(&format!("(byte {at})")),
            "{e}"
        );
    }

    #[test]
    fn truncation_anywhere_is_an_error_not_a_panic() {
        for cut in 0..TINY.len() {
            let r = parse_msh(&TINY.as_bytes()[..cut], "t.msh");
            if let Err(e) = r {
                assert!(!e.to_string().contains('\n'));
            } else {
                // only a cut in the trailing whitespace may pass
                assert!(TINY[cut..].trim().is_empty(), "cut at {cut} passed");
            }
        }
        for cut in 0..TINY_BIN.len() {
            if let Ok(m) = parse_msh(&TINY_BIN[..cut], "t.msh") {
                assert_eq!(m.nodes.len(), 21, "cut at {cut} passed");
            }
        }
        let e = err(&TINY_BIN[..TINY_BIN.len() / 2]);
        assert!(e.contains("(byte ") && e.contains("truncated file"), "{e}");
    }

    #[test]
    fn node_errors() {
        let e = err(TINY.replace("\n20 20 0\n", "\n20 20 0.5\n").as_bytes());
        let line = TINY[..TINY.find("\n20 20 0\n").unwrap() + 1]
            .lines()
            .count()
            + 1;
        assert!(
            e.contains("node 3 has z = 0.5") && e.contains(&format!("t.msh:{line}:")),
            "{e}"
        );
        let e = err(TINY.replace("\n20 20 0\n", "\nnan 20 0\n").as_bytes());
        assert!(
            e.contains("node 3: coordinate x is NaN, not a finite number"),
            "{e}"
        );
        let e = err(TINY.replace("\n20 20 0\n", "\n20 inf 0\n").as_bytes());
        assert!(e.contains("coordinate y is inf"), "{e}");
        let e = err(TINY.replace("24 21 1 21", "24 22 1 22").as_bytes());
        assert!(
            e.contains("bad counts: $Nodes announces 22 nodes but its blocks hold 21"),
            "{e}"
        );
        let e = err(TINY
            .replace("24 21 1 21", "24 99999999999999 1 21")
            .as_bytes());
        assert!(
            e.contains("bad count: the number of nodes = 99999999999999"),
            "{e}"
        );
        let e = err(TINY.replace("0 2 0 1\n2\n", "0 2 0 1\n1\n").as_bytes());
        assert!(e.contains("node tag 1 appears twice"), "{e}");
        let e = err(TINY
            .replace("11 1 2 3 4 11 12 13 14 ", "11 1 2 3 4 11 12 13 99 ")
            .as_bytes());
        assert!(
            e.contains("element 11 refers to unknown node tag 99"),
            "{e}"
        );
        let e = err(TINY
            .replace("garbage", "")
            .replace("0 1 0 1\n1\n0 0 0", "0 1 0 1\n1\n0 zero 0")
            .as_bytes());
        assert!(
            e.contains("expected a node coordinate (a number), found \"zero\""),
            "{e}"
        );
    }

    #[test]
    fn element_and_physical_errors() {
        let e = err(TINY.replace("\n2 1 16 1\n", "\n2 1 10 1\n").as_bytes());
        assert!(
            e.contains("element type 10 (9-node quadrangle) not supported"),
            "{e}"
        );
        let line = TINY[..TINY.find("\n2 1 16 1\n").unwrap() + 1]
            .lines()
            .count()
            + 1;
        assert!(e.contains(&format!("t.msh:{line}:")), "{e}");
        let e = err(TINY.replace("\n2 1 16 1\n", "\n2 1 3 1\n").as_bytes());
        assert!(
            e.contains("element type 3 (4-node quadrangle)") && e.contains("ElementOrder"),
            "{e}"
        );
        let e = err(TINY.replace("\n2 1 16 1\n", "\n1 1 16 1\n").as_bytes());
        assert!(
            e.contains("in an entity of dimension 1 (expected 2)"),
            "{e}"
        );
        let e = err(TINY
            .replace("2 1 \"punch\"", "2 1 \"punch.top\"")
            .as_bytes());
        assert!(e.contains("\"punch.top\" is used twice"), "{e}");
        let e = err(TINY.replace("13 13 1 13", "13 14 1 14").as_bytes());
        assert!(e.contains("bad counts: $Elements announces 14"), "{e}");
        // a surface in no physical group
        let text = TINY.replace(
            "1 0 0 0 20 20 0 1 1 4 1 2 -3 -4",
            "1 0 0 0 20 20 0 0 4 1 2 -3 -4",
        );
        assert!(err(text.as_bytes())
            .contains("surface entity 1 has elements but is in no physical surface"));
        // the case names a group the file does not have, or one of the wrong dimension
        let msh = parse_msh(TINY.as_bytes(), "t.msh").unwrap();
        let mut spec = contact();
        spec.upper_curve = Some("punch.base".into());
        let e = build_mesh(&msh, &[spec], "case.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("physical curve \"punch.base\" not found in t.msh"),
            "{e}"
        );
        let mut spec = contact();
        spec.lower_curve = Some("foundation".into());
        let e = build_mesh(&msh, &[spec], "case.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("\"foundation\" is a physical surface (dimension 2)"),
            "{e}"
        );
        let mut spec = contact();
        spec.upper = Some("foundation".into());
        let e = build_mesh(&msh, &[spec], "case.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(
                "upper = \"foundation\" but upper_curve \"punch.bottom\" lies on body \"punch\""
            ),
            "{e}"
        );
    }

    #[test]
    fn bodies_sharing_nodes_are_rejected() {
        // the foundation's first element takes the punch's corner node 1 instead of its own 10
        let text = TINY.replace("12 5 6 9 10 15 21 18 20 ", "12 5 6 9 1 15 21 18 20 ");
        let e = err(text.as_bytes());
        assert!(
            e.contains("node 1 at (0, 0) belongs to both bodies \"punch\" and \"foundation\""),
            "{e}"
        );
    }

    #[test]
    fn unpaired_interface_node_names_tag_and_coordinates() {
        // move the punch's bottom midside node (tag 11) off its partner (tag 18)
        let text = TINY.replacen("11\n9.9999999999716 0 0", "11\n9.5 0 0", 1);
        let e = err(text.as_bytes());
        assert!(
            e.contains("node 11 at (9.5, 0) of curve \"punch.bottom\"") && e.contains("no partner"),
            "{e}"
        );
    }
}
