//! Tests of bodies of several blocks: the merge against one block, an
//! L-shaped bolt's sets, interfaces on such a body, and the refusals.

use super::super::tests::{block, iface, punch};
use super::super::*;

/// A block of body `body` named `name`.
fn part(
    body: &str,
    name: &str,
    x: Vec<f64>,
    nx: Vec<usize>,
    y: Vec<f64>,
    ny: Vec<usize>,
) -> BlockSpec {
    BlockSpec {
        name: Some(name.into()),
        ..block(body, x, nx, y, ny)
    }
}

/// An L-shaped bolt: a head 0 ≤ x ≤ 20, 40 ≤ y ≤ 50 on a shank 0 ≤ x ≤ 8.
fn bolt() -> Vec<BlockSpec> {
    vec![
        part(
            "bolt",
            "head",
            vec![0., 8., 20.],
            vec![4, 4],
            vec![40., 50.],
            vec![3],
        ),
        part(
            "bolt",
            "shank",
            vec![0., 8.],
            vec![4],
            vec![0., 40.],
            vec![8],
        ),
    ]
}

/// The node ids of a set whose coordinates satisfy `f`, sorted.
fn nodes_where(m: &Mesh, f: impl Fn([f64; 2]) -> bool) -> Vec<usize> {
    (0..m.nodes.len()).filter(|&n| f(m.xy(n))).collect()
}

#[test]
fn a_rectangle_of_two_blocks_is_the_rectangle_of_one() {
    let whole = block(
        "plate",
        vec![0., 10., 30.],
        vec![3, 4],
        vec![0., 5., 20.],
        vec![2, 3],
    );
    let one = generate(std::slice::from_ref(&whole), &[], 1).unwrap();
    let split_x = vec![
        part(
            "plate",
            "a",
            vec![0., 10.],
            vec![3],
            whole.y.clone(),
            vec![2, 3],
        ),
        part(
            "plate",
            "b",
            vec![10., 30.],
            vec![4],
            whole.y.clone(),
            vec![2, 3],
        ),
    ];
    let split_y = vec![
        part(
            "plate",
            "lo",
            whole.x.clone(),
            vec![3, 4],
            vec![0., 5.],
            vec![2],
        ),
        part(
            "plate",
            "hi",
            whole.x.clone(),
            vec![3, 4],
            vec![5., 20.],
            vec![3],
        ),
    ];
    for (blocks, shared) in [(split_x, 2 * 5 + 1), (split_y, 2 * 7 + 1)] {
        let m = generate(&blocks, &[], 1).unwrap();
        m.validate().unwrap();
        assert_eq!(m.bodies, ["plate"]);
        assert_eq!(m.elements.len(), one.elements.len());
        // each block's nodes, less the shared side's once
        let own = |b: &BlockSpec| {
            let (nx, ny) = (b.nx.iter().sum::<usize>(), b.ny.iter().sum::<usize>());
            (2 * nx + 1) * (2 * ny + 1) - nx * ny
        };
        assert_eq!(own(&blocks[0]) + own(&blocks[1]) - shared, m.nodes.len());
        assert_eq!(m.nodes.len(), one.nodes.len());
        // the same points, and the same elements by their points
        let key = |x: [f64; 3]| (x[0].to_bits(), x[1].to_bits());
        let mut a: Vec<_> = m.nodes.iter().map(|&x| key(x)).collect();
        let mut b: Vec<_> = one.nodes.iter().map(|&x| key(x)).collect();
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b);
        let els = |m: &Mesh| {
            let mut v: Vec<_> = (0..m.elements.len())
                .map(|e| m.element_coords(e).map(|[x, y]| key([x, y, 0.0])))
                .collect();
            v.sort_unstable();
            v
        };
        assert_eq!(els(&m), els(&one));
        assert_eq!(
            m.node_sets["plate.all"],
            (0..m.nodes.len()).collect::<Vec<_>>()
        );
        // the outer sides of both blocks make the rectangle's boundary; the
        // shared side is in no set
        let boundary: usize = m.edge_sets.values().map(|e| e.len()).sum();
        assert_eq!(boundary, 2 * (7 + 5));
    }
}

#[test]
fn an_l_shaped_bolt_is_one_body_and_its_sets_are_its_outline() {
    let m = generate(&bolt(), &[], 1).unwrap();
    m.validate().unwrap();
    assert_eq!(m.bodies, ["bolt"]);
    // head 8 × 3, shank 4 × 8 elements; the shank's top (9 nodes) is merged
    assert_eq!(m.elements.len(), 24 + 32);
    assert_eq!(m.nodes.len(), (17 * 7 - 24) + (9 * 17 - 32) - 9);
    assert!(m.elements.iter().all(|e| e.body == 0));
    // the shank's top is inside the body: no edge, no node
    assert!(m.edge_sets["shank.top"].is_empty() && m.node_sets["shank.top"].is_empty());
    // the head's bottom is what is left of it, 8 ≤ x ≤ 20, nodes included
    assert_eq!(m.edge_sets["head.bottom"].len(), 4);
    assert_eq!(
        m.node_sets["head.bottom"],
        nodes_where(&m, |x| x[1] == 40. && x[0] >= 8.)
    );
    // the corner node (8, 40) is one node, on the head's bottom and the
    // shank's right side
    let corner = nodes_where(&m, |x| x == [8., 40.]);
    assert_eq!(corner.len(), 1);
    assert!(m.node_sets["shank.right"].contains(&corner[0]));
    assert_eq!(
        m.node_sets["shank.right"],
        nodes_where(&m, |x| x[0] == 8. && x[1] <= 40.)
    );
    // the left side of the bolt is two sets, joined at one node (0, 40)
    let left = nodes_where(&m, |x| x[0] == 0.);
    let mut both: Vec<usize> = m.node_sets["head.left"].clone();
    both.extend(&m.node_sets["shank.left"]);
    both.sort_unstable();
    both.dedup();
    assert_eq!(both, left);
    // .all: the body's is every node, a block's its own
    assert_eq!(
        m.node_sets["bolt.all"],
        (0..m.nodes.len()).collect::<Vec<_>>()
    );
    assert_eq!(m.node_sets["head.all"], nodes_where(&m, |x| x[1] >= 40.));
    assert_eq!(
        m.node_sets["shank.all"],
        nodes_where(&m, |x| x[1] <= 40. && x[0] <= 8.)
    );
    assert!(!m.node_sets.contains_key("bolt.bottom"));
    // every edge of the outline once, walked with the body on the left
    let mut outline: Vec<[usize; 3]> = m.edge_sets.values().flatten().copied().collect();
    assert_eq!(outline.len(), 4 + 3 + 8 + 3 + 8 + 4 + 8);
    outline.sort_unstable();
    outline.dedup();
    assert_eq!(outline.len(), 38);
    let area: f64 = outline
        .iter()
        .map(|e| {
            let (a, b) = (m.nodes[e[0]], m.nodes[e[2]]);
            0.5 * (a[0] * b[1] - b[0] * a[1])
        })
        .sum();
    assert!((area - (20. * 10. + 8. * 40.)).abs() < 1e-9, "{area}");
}

#[test]
fn four_blocks_round_a_point_merge_it_into_one_node() {
    let q = |name: &str, x: Vec<f64>, y: Vec<f64>| part("plate", name, x, vec![2], y, vec![3]);
    let blocks = vec![
        q("sw", vec![0., 1.], vec![0., 1.]),
        q("se", vec![1., 2.], vec![0., 1.]),
        q("ne", vec![1., 2.], vec![1., 2.]),
        q("nw", vec![0., 1.], vec![1., 2.]),
    ];
    let m = generate(&blocks, &[], 1).unwrap();
    m.validate().unwrap();
    // 4 × 2 by 2 × 3 elements: (9 × 13 − 24) nodes
    assert_eq!(m.nodes.len(), 9 * 13 - 24);
    assert_eq!(nodes_where(&m, |x| x == [1., 1.]).len(), 1);
    // the node numbering is compact and every node in use
    let mut used = vec![false; m.nodes.len()];
    m.elements
        .iter()
        .flat_map(|e| e.nodes())
        .for_each(|&n| used[n] = true);
    assert!(used.iter().all(|&u| u));
}

#[test]
fn a_body_of_one_block_keeps_its_sets() {
    let (bl, ifs) = punch();
    let m = generate(&bl, &ifs, 1).unwrap();
    let names: Vec<&str> = m.node_sets.keys().map(|k| k.as_str()).collect();
    assert_eq!(
        names,
        [
            "foundation.all",
            "foundation.bottom",
            "foundation.left",
            "foundation.right",
            "foundation.top",
            "punch.all",
            "punch.bottom",
            "punch.left",
            "punch.right",
            "punch.top"
        ]
    );
    let named = BlockSpec {
        name: Some("p".into()),
        ..bl[0].clone()
    };
    // a single block named apart from its body: the body's set is its nodes
    let m = generate(&[named.clone(), bl[1].clone()], &[], 1).unwrap();
    assert_eq!(m.node_sets["punch.all"], m.node_sets["p.all"]);
    assert!(m.edge_sets.contains_key("p.top") && !m.edge_sets.contains_key("punch.top"));
}

#[test]
fn an_interface_on_a_body_of_blocks_is_remapped_and_one_within_a_body_refused() {
    // the bolt's head on a plate around the shank (a clearance hole)
    let mut blocks = bolt();
    blocks.push(block(
        "plate",
        vec![10., 30.],
        vec![4],
        vec![30., 40.],
        vec![2],
    ));
    blocks[0].x = vec![0., 8., 10., 20., 30.];
    blocks[0].nx = vec![4, 1, 2, 2];
    let seat = iface("seat", [Some("head"), Some("plate"), None, None]);
    let m = generate(&blocks, std::slice::from_ref(&seat), 1).unwrap();
    m.validate().unwrap();
    assert_eq!(m.bodies, ["bolt", "plate"]);
    let i = &m.interfaces[0];
    assert_eq!((i.body_a, i.body_b), (0, 1));
    assert_eq!(i.edges.len(), 4);
    for e in &i.edges {
        for k in 0..3 {
            assert_eq!(m.nodes[e.a[k]], m.nodes[e.b[k]]);
            assert!(m.node_sets["head.bottom"].contains(&e.a[k]));
        }
    }
    // non-matching: the master side is the plate's top, the slave side the
    // head's bottom over the plate
    let loose = InterfaceSpec {
        matching: Some(false),
        ..seat.clone()
    };
    let m = generate(&blocks, &[loose], 1).unwrap();
    m.validate().unwrap();
    let nm = m.interfaces[0].nonmatching.as_ref().unwrap();
    assert_eq!((nm.slave.len(), nm.master.len()), (4, 4));
    // an interface between the head and the shank: one body
    let inner = iface("neck", [Some("head"), Some("shank"), None, None]);
    let e = generate(&bolt(), &[inner], 1).unwrap_err().0;
    assert!(
        e.contains("interface \"neck\": blocks \"head\" and \"shank\" are both of body \"bolt\""),
        "{e}"
    );
}

#[test]
fn the_master_side_loses_the_edges_its_body_shares() {
    // a foundation of two blocks, a base and a pedestal on its left part;
    // a punch on the rest of the base's top, meshed apart
    let blocks = vec![
        part(
            "found",
            "base",
            vec![0., 10., 20.],
            vec![2, 2],
            vec![-10., 0.],
            vec![2],
        ),
        part(
            "found",
            "pedestal",
            vec![0., 10.],
            vec![2],
            vec![0., 5.],
            vec![1],
        ),
        block("punch", vec![10., 20.], vec![3], vec![0., 5.], vec![1]),
    ];
    let mut contact = iface("contact", [Some("punch"), Some("base"), None, None]);
    contact.matching = Some(false);
    let m = generate(&blocks, &[contact], 1).unwrap();
    m.validate().unwrap();
    let nm = m.interfaces[0].nonmatching.as_ref().unwrap();
    assert_eq!((nm.slave.len(), nm.master.len()), (3, 2));
    assert!(nm.master.iter().flatten().all(|&n| m.nodes[n][0] >= 10.));
    // the same edges as the base's top set, which walks the other way
    let mut top: Vec<[usize; 3]> = m.edge_sets["base.top"]
        .iter()
        .map(|e| [e[2], e[1], e[0]])
        .collect();
    top.reverse();
    assert_eq!(top, nm.master);
}

#[test]
fn blocks_of_one_body_that_do_not_fit_together_are_refused_by_name() {
    let refused = |blocks: &[BlockSpec], want: &[&str]| {
        let e = generate(blocks, &[], 1).unwrap_err().0;
        for w in want {
            assert!(e.contains(w), "{e:?} lacks {w:?}");
        }
    };
    // names: twice the same, the body's in a body of two, another body's
    let mut b = bolt();
    b[1].name = Some("head".into());
    refused(&b, &["two blocks are named \"head\"", "each need a `name`"]);
    let mut b = bolt();
    b[1].name = None;
    refused(
        &b,
        &["body \"bolt\" has 2 blocks", "named \"bolt\" like the body"],
    );
    let mut b = bolt();
    b.push(block(
        "shank",
        vec![30., 40.],
        vec![1],
        vec![0., 1.],
        vec![1],
    ));
    b[1].name = Some("shank".into());
    refused(&b, &["two blocks are named \"shank\""]);
    let mut b = bolt();
    b.push(part(
        "nut",
        "n",
        vec![30., 40.],
        vec![1],
        vec![0., 1.],
        vec![1],
    ));
    b[1].name = Some("nut".into());
    refused(
        &b,
        &[
            "block \"nut\" of body \"bolt\" has the name of body \"nut\"",
            "nut.all",
        ],
    );
    // area in common
    let mut b = bolt();
    b[1].y = vec![0., 45.];
    refused(
        &b,
        &["blocks \"head\" and \"shank\" of body \"bolt\" overlap in x = 0 … 8, y = 40 … 45"],
    );
    // apart, or touching at a corner only
    let mut b = bolt();
    b[1].y = vec![0., 39.];
    refused(
        &b,
        &["block \"shank\" of body \"bolt\" shares no side with block \"head\""],
    );
    let mut b = bolt();
    b[1].x = vec![20., 28.];
    refused(&b, &["block \"shank\"", "shares no side"]);
    // a third block joined to nothing
    let mut b = bolt();
    b.push(part(
        "bolt",
        "tip",
        vec![0., 8.],
        vec![1],
        vec![-5., -1.],
        vec![1],
    ));
    refused(&b, &["block \"tip\" of body \"bolt\" shares no side"]);
    // nodes that do not match
    let mut b = bolt();
    b[1].nx = vec![3];
    refused(
        &b,
        &[
            "blocks \"shank\" and \"head\" of body \"bolt\" share the side y = 40 (x = 0 … 8)",
            "the node of \"shank\" at (1.3333333333333333, 40) has no node of \"head\" there",
        ],
    );
    let mut b = bolt();
    b[1].rx = vec![2.0];
    refused(&b, &["has no node of"]);
    // an edge of the head across the shank's end
    let mut b = bolt();
    b[0].x = vec![0., 7., 8.5, 20.];
    b[0].nx = vec![4, 1, 2];
    b[1].x = vec![0., 7., 8.];
    b[1].nx = vec![4, 1];
    refused(
        &b,
        &["an element edge of \"head\" straddles the end of the shared side at x = "],
    );
    // a curved side shared
    let mut b = bolt();
    b[0].bottom = Some(SideShape {
        radius: Some(100.),
        center: Some(0.),
        round_left: None,
        round_right: None,
        ..Default::default()
    });
    refused(
        &b,
        &["the bottom of \"head\" is curved: a curved side cannot be shared"],
    );
}
