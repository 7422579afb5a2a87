//! Non-matching interfaces of file meshes: the slave curve chained, both
//! sides oriented from their quadrangles, and the refusals.

use super::*;
use crate::input::mesh::gmsh::parse_msh;

const LINE: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/nonmatching-line.msh"
));
const ARC: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/nonmatching-arc.msh"
));

fn spec(upper: &str, lower: &str) -> InterfaceSpec {
    InterfaceSpec {
        name: "contact".into(),
        upper: None,
        lower: None,
        upper_curve: Some(upper.into()),
        lower_curve: Some(lower.into()),
        upper_surface: None,
        lower_surface: None,
        left: None,
        right: None,
        matching: Some(false),
    }
}

fn build(text: &str, spec: InterfaceSpec) -> Result<Mesh> {
    let msh = parse_msh(text.as_bytes(), "t.msh")?;
    build_mesh(&msh, &[spec], "case.toml")
}

fn err(text: &str, spec: InterfaceSpec) -> String {
    let e = build(text, spec).expect_err("must be refused").to_string();
    assert!(!e.contains('\n'), "{e}");
    e
}

/// Which side of the walk p → q the point c is on: > 0 left, < 0 right.
fn side(p: [f64; 2], q: [f64; 2], c: [f64; 2]) -> f64 {
    (q[0] - p[0]) * (c[1] - p[1]) - (q[1] - p[1]) * (c[0] - p[0])
}

/// The centroid of the quadrangle that has the edge's two ends as corners.
fn owner_centroid(m: &Mesh, e: &[usize; 3]) -> [f64; 2] {
    let el = m
        .elements
        .iter()
        .find(|el| el.nodes()[..4].contains(&e[0]) && el.nodes()[..4].contains(&e[2]))
        .expect("an element has the edge");
    let c = el.nodes()[..4].iter().fold([0.0, 0.0], |s, &n| {
        [s[0] + m.nodes[n][0] / 4.0, s[1] + m.nodes[n][1] / 4.0]
    });
    c
}

#[test]
fn file_sides_are_oriented_by_their_quadrangles_and_the_slave_side_is_chained() {
    for (what, text, top) in [("line", LINE, 0.0), ("arc", ARC, 0.5)] {
        let m = build(text, spec("upper.bottom", "lower.top")).unwrap();
        m.validate().unwrap();
        let iface = &m.interfaces[0];
        assert_eq!(m.bodies[iface.body_a], "upper");
        assert_eq!(m.bodies[iface.body_b], "lower");
        assert!(iface.edges.is_empty());
        let nm = iface.nonmatching.as_ref().unwrap();
        assert_eq!((nm.slave.len(), nm.master.len()), (8, 4), "{what}");
        // the file lists the upper bottom's pieces out of order and in alternating
        // directions: its edge set is not one chain, the slave side is
        let raw = &m.edge_sets["upper.bottom"];
        assert!(raw.windows(2).any(|w| w[0][2] != w[1][0]), "{what}");
        for w in nm.slave.windows(2) {
            assert_eq!(w[0][2], w[1][0], "{what}: slave edges chained");
        }
        let x = |n: usize| m.xy(n);
        assert_eq!(
            x(nm.slave[0][0]),
            [0.0, 0.0],
            "{what}: starts at the left end"
        );
        assert_eq!(x(nm.slave[7][2]), [10.0, 0.0], "{what}");
        for e in &nm.slave {
            // body A (upper) on the left of every slave edge
            assert!(
                side(x(e[0]), x(e[2]), owner_centroid(&m, e)) > 0.0,
                "{what}"
            );
            assert!(x(e[2])[0] > x(e[0])[0], "{what}: walked in +x");
        }
        let mut mid_y = f64::NEG_INFINITY;
        for e in &nm.master {
            // body B (lower) on the right of every master edge: its left normal
            // points from B into A
            assert!(
                side(x(e[0]), x(e[2]), owner_centroid(&m, e)) < 0.0,
                "{what}"
            );
            assert!(x(e[2])[0] > x(e[0])[0], "{what}: walked in +x");
            mid_y = mid_y.max(x(e[1])[1]);
        }
        // the sides share no node and are not merged
        let a: HashSet<usize> = nm.slave.iter().flatten().copied().collect();
        assert!(nm.master.iter().flatten().all(|n| !a.contains(n)));
        assert!(
            (mid_y - top).abs() < 0.05,
            "{what}: master midsides up to y = {mid_y}"
        );
    }
}

#[test]
fn swapped_curves_are_refused_when_the_bodies_are_named_and_consistent_otherwise() {
    let mut s = spec("lower.top", "upper.bottom");
    s.upper = Some("upper".into());
    s.lower = Some("lower".into());
    let e = err(LINE, s);
    assert!(
        e.contains("upper = \"upper\" but upper_curve \"lower.top\" lies on body \"lower\"")
            && e.contains("swapped"),
        "{e}"
    );
    // without body names, "upper" is whatever upper_curve lies on: body A is the
    // lower body, walked with A on the left (−x); the master normals point into it
    let m = build(LINE, spec("lower.top", "upper.bottom")).unwrap();
    let iface = &m.interfaces[0];
    assert_eq!(m.bodies[iface.body_a], "lower");
    let nm = iface.nonmatching.as_ref().unwrap();
    assert_eq!((nm.slave.len(), nm.master.len()), (4, 8));
    assert_eq!(m.xy(nm.slave[0][0]), [10.0, 0.0]);
    for e in &nm.master {
        assert!(m.nodes[e[2]][0] < m.nodes[e[0]][0]);
    }
}

#[test]
fn a_slave_curve_in_two_pieces_and_an_empty_curve_are_refused() {
    // curve entity 3 (x from 5 to 7.5) taken out of "upper.bottom"
    let gap = LINE.replace(
        "\n3 5 0 0 7.5 0 0 1 3 2 3 -4 \n",
        "\n3 5 0 0 7.5 0 0 0 2 3 -4 \n",
    );
    assert_ne!(gap, LINE);
    let e = err(&gap, spec("upper.bottom", "lower.top"));
    assert!(
        e.contains(
            "upper_curve \"upper.bottom\" in t.msh (the slave side) is not one connected chain"
        ) && e.contains("breaks off at node ")
            && e.contains(" at (5, 0) and goes on at node ")
            && e.contains(" at (7.5, 0)")
            && e.contains("[[mesh.interface]] \"contact\""),
        "{e}"
    );
    // a master side in pieces is fine (each point finds its closest edge)
    let gap = LINE.replace(
        "\n14 5 0 0 7.5 0 0 1 9 2 14 -15 \n",
        "\n14 5 0 0 7.5 0 0 0 2 14 -15 \n",
    );
    assert_ne!(gap, LINE);
    let m = build(&gap, spec("upper.bottom", "lower.top")).unwrap();
    assert_eq!(
        m.interfaces[0].nonmatching.as_ref().unwrap().master.len(),
        3
    );
    // a physical curve without line elements
    let empty = LINE.replace(
        "$PhysicalNames\n10\n",
        "$PhysicalNames\n11\n1 11 \"upper.nothing\"\n",
    );
    let e = err(&empty, spec("upper.nothing", "lower.top"));
    assert!(
        e.contains("physical curve \"upper.nothing\" in t.msh is empty"),
        "{e}"
    );
    // a curve on the wrong body: both on the upper one
    let e = err(LINE, spec("upper.bottom", "upper.top"));
    assert!(e.contains("are on the same body \"upper\""), "{e}");
}

/// Nodes 0..n on the x axis, edges [2k, 2k+1, 2k+2]: a straight chain.
fn polyline(n_edges: usize) -> (Mesh, Vec<u64>, Vec<[usize; 3]>) {
    let mesh = Mesh {
        nodes: (0..=2 * n_edges)
            .map(|i| [i as f64 * 0.5, 0.0, 0.0])
            .collect(),
        ..Mesh::default()
    };
    let tags = (0..=2 * n_edges as u64).map(|i| 100 + i).collect();
    let edges = (0..n_edges)
        .map(|k| [2 * k, 2 * k + 1, 2 * k + 2])
        .collect();
    (mesh, tags, edges)
}

#[test]
fn the_chain_follows_the_edges_whatever_their_order() {
    let (m, tags, edges) = polyline(5);
    let shuffled = [edges[3], edges[0], edges[4], edges[2], edges[1]];
    assert_eq!(chain(&m, &tags, "c", "t.msh", &shuffled).unwrap(), edges);
    // a closed loop is one chain too, from the first edge given
    let mut m = m;
    m.nodes.push([1.0, 1.0, 0.0]);
    let back = [10, 11, 0];
    let loop_edges = [edges[2], back, edges[0], edges[4], edges[1], edges[3]];
    let c = chain(&m, &tags, "c", "t.msh", &loop_edges).unwrap();
    assert_eq!(c.len(), 6);
    assert_eq!(c[0], edges[2]);
    assert_eq!(c.last().unwrap()[2], edges[2][0]);
    for w in c.windows(2) {
        assert_eq!(w[0][2], w[1][0]);
    }
}

#[test]
fn a_broken_or_branching_chain_is_refused_with_the_node() {
    let (mut m, tags, edges) = polyline(5);
    // two pieces
    let e = chain(
        &m,
        &tags,
        "c",
        "t.msh",
        &[edges[4], edges[0], edges[1], edges[3]],
    )
    .unwrap_err();
    assert!(
        e.contains("breaks off at node 104 at (2, 0) and goes on at node 106 at (3, 0)")
            && e.contains("(2 of its 4 edges are in other pieces"),
        "{e}"
    );
    // an open chain and a closed loop
    m.nodes.push([9.0, 9.0, 0.0]);
    let e = chain(
        &m,
        &tags,
        "c",
        "t.msh",
        &[edges[0], edges[3], [8, 11, 6], edges[1]],
    )
    .unwrap_err();
    assert!(
        e.contains("breaks off at node 104 at (2, 0) and goes on at node 106 at (3, 0)"),
        "{e}"
    );
    // two edges from one node, two edges into one node
    let e = chain(&m, &tags, "c", "t.msh", &[edges[0], edges[1], [2, 11, 6]]).unwrap_err();
    assert!(
        e.contains("branches at node 102 at (1, 0): two of its edges start there"),
        "{e}"
    );
    let e = chain(&m, &tags, "c", "t.msh", &[edges[0], edges[1], [6, 11, 4]]).unwrap_err();
    assert!(e.contains("two of its edges end there"), "{e}");
}

#[test]
fn a_curve_between_two_quadrangles_of_its_body_is_refused() {
    // two unit squares side by side; the edge x = 1 is shared
    let nodes = vec![
        [0.0, 0.0],
        [1.0, 0.0],
        [2.0, 0.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [0.0, 1.0],
        [0.5, 0.0],
        [1.0, 0.5],
        [0.5, 1.0],
        [0.0, 0.5],
        [1.5, 0.0],
        [2.0, 0.5],
        [1.5, 1.0],
    ];
    let m = Mesh {
        nodes: nodes.iter().map(|&[x, y]| [x, y, 0.0]).collect(),
        elements: vec![
            Element::q8([0, 1, 4, 5, 6, 7, 8, 9], 0),
            Element::q8([1, 2, 3, 4, 10, 11, 12, 7], 0),
        ],
        bodies: vec!["b".into()],
        ..Mesh::default()
    };
    m.validate().unwrap();
    let tags: Vec<u64> = (1..=13).collect();
    let inner = inner_edges(&m);
    assert_eq!(inner.len(), 1);
    on_boundary(
        &m,
        &tags,
        &inner,
        "b.bottom",
        "t.msh",
        &[[0, 6, 1], [1, 10, 2]],
    )
    .unwrap();
    let e = on_boundary(&m, &tags, &inner, "b.middle", "t.msh", &[[1, 7, 4]]).unwrap_err();
    assert!(
        e.contains("curve \"b.middle\" in t.msh runs inside its body")
            && e.contains("from node 2 at (1, 0) to node 5 at (1, 1)"),
        "{e}"
    );
}

/// The punch meshed by Gmsh in 6-node triangles (type 9).
const TRIANGLES: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/tiny-t6.msh"
));

/// A triangle given clockwise (corners 0, 2, 1 and its midsides to match)
/// is read as the same counter-clockwise element.
#[test]
fn a_clockwise_triangle_is_turned_counter_clockwise() {
    let read = |text: &str| {
        let msh = parse_msh(text.as_bytes(), "t.msh").unwrap();
        build_mesh(&msh, &[], "case.toml").unwrap()
    };
    let mesh = read(TRIANGLES);
    assert!(mesh.elements.iter().all(|el| el.family == Family::T6));
    mesh.validate().unwrap();
    // element 13: corners 1 2 28, midsides 11 29 30 → 1 28 2, 30 29 11
    let turned = TRIANGLES.replacen("\n13 1 2 28 11 29 30 \n", "\n13 1 28 2 30 29 11 \n", 1);
    assert_ne!(turned, TRIANGLES);
    let again = read(&turned);
    again.validate().unwrap();
    assert_eq!(again.elements, mesh.elements);
}
