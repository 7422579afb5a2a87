//! Tests of the block generator: counts, grading, interfaces, curved sides.

use super::shape::Chamfer;
use super::*;

pub(super) fn punch() -> (Vec<BlockSpec>, Vec<InterfaceSpec>) {
    let b = |body: &str, x: Vec<f64>, nx, rx, y: Vec<f64>, ny, ry| BlockSpec {
        body: body.into(),
        name: None,
        x,
        nx,
        rx,
        y,
        ny,
        ry,
        bottom: None,
        top: None,
        left: None,
        right: None,
    };
    (
        vec![
            b(
                "punch",
                vec![0., 20.],
                vec![4],
                vec![0.25],
                vec![0., 20.],
                vec![4],
                vec![4.0],
            ),
            b(
                "foundation",
                vec![0., 20., 60.],
                vec![4, 5],
                vec![0.25, 8.0],
                vec![-60., 0.],
                vec![6],
                vec![0.1],
            ),
        ],
        vec![InterfaceSpec {
            name: "contact".into(),
            upper: Some("punch".into()),
            lower: Some("foundation".into()),
            upper_curve: None,
            lower_curve: None,
            upper_surface: None,
            lower_surface: None,
            left: None,
            right: None,
            matching: None,
        }],
    )
}

#[test]
fn punch_mesh_counts_grading_and_interface() {
    let (bl, ifs) = punch();
    let m = generate(&bl, &ifs, 1).unwrap();
    m.validate().unwrap();
    // Q8 nodes per block: (2nx+1)(2ny+1) − nx·ny
    assert_eq!(m.nodes.len(), (9 * 9 - 16) + (19 * 13 - 54));
    assert_eq!(m.elements.len(), 16 + 54);
    let xs = graded_axis("f", "x", &[0., 20., 60.], &[4, 5], &[0.25, 8.0], 1).unwrap();
    let h: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
    assert!((h[3] / h[0] - 0.25).abs() < 1e-12 && (h[8] / h[4] - 8.0).abs() < 1e-12);
    let iface = &m.interfaces[0];
    assert_eq!(iface.edges.len(), 4);
    for e in &iface.edges {
        for i in 0..3 {
            assert_eq!(m.nodes[e.a[i]], m.nodes[e.b[i]]);
            assert_ne!(e.a[i], e.b[i]);
        }
        assert!(m.nodes[e.a[0]][0] < m.nodes[e.a[2]][0]);
    }
    // top edge walked with the body on the left: outward normal (dy, −dx) points up
    let top = &m.edge_sets["punch.top"][0];
    let (x0, x2) = (m.nodes[top[0]], m.nodes[top[2]]);
    assert!(-(x2[0] - x0[0]) > 0.0);
    let r2 = generate(&bl, &ifs, 2).unwrap();
    assert_eq!(r2.elements.len(), 4 * m.elements.len());
}

#[test]
fn mismatched_interface_and_bad_specs_are_named() {
    let (mut bl, ifs) = punch();
    bl[0].nx = vec![3];
    let e = generate(&bl, &ifs, 1).unwrap_err();
    assert!(
        e.0.contains("interface \"contact\"") && e.0.contains("partner"),
        "{e}"
    );
    let (mut bl, ifs) = punch();
    bl[1].rx = vec![1.0];
    assert!(generate(&bl, &ifs, 1)
        .unwrap_err()
        .0
        .contains("rx has 1 entries"));
    let (mut bl, ifs) = punch();
    bl[1].x = vec![0.0, 30.0, 20.0];
    assert!(generate(&bl, &ifs, 1)
        .unwrap_err()
        .0
        .contains("strictly increasing"));
}

pub(super) fn block(
    body: &str,
    x: Vec<f64>,
    nx: Vec<usize>,
    y: Vec<f64>,
    ny: Vec<usize>,
) -> BlockSpec {
    BlockSpec {
        body: body.into(),
        name: None,
        x,
        nx,
        rx: Vec::new(),
        y,
        ny,
        ry: Vec::new(),
        bottom: None,
        top: None,
        left: None,
        right: None,
    }
}

pub(super) fn iface(name: &str, sides: [Option<&str>; 4]) -> InterfaceSpec {
    let s = |i: usize| sides[i].map(String::from);
    InterfaceSpec {
        name: name.into(),
        upper: s(0),
        lower: s(1),
        upper_curve: None,
        lower_curve: None,
        upper_surface: None,
        lower_surface: None,
        left: s(2),
        right: s(3),
        matching: None,
    }
}

/// A shaft (x ≤ 10) in a hub (x ≥ 10, 10 ≤ y ≤ 30) that sits on a base
/// (y ≤ 10): one vertical and one horizontal interface.
fn shaft_hub_base() -> (Vec<BlockSpec>, Vec<InterfaceSpec>) {
    (
        vec![
            block(
                "shaft",
                vec![0., 10.],
                vec![2],
                vec![0., 10., 30., 40.],
                vec![2, 4, 1],
            ),
            block("hub", vec![10., 30.], vec![4], vec![10., 30.], vec![4]),
            block(
                "base",
                vec![10., 20., 30.],
                vec![2, 2],
                vec![-10., 10.],
                vec![2],
            ),
        ],
        vec![
            iface("fit", [None, None, Some("shaft"), Some("hub")]),
            iface("seat", [Some("hub"), Some("base"), None, None]),
        ],
    )
}

#[test]
fn a_vertical_interface_pairs_the_right_side_of_left_with_the_left_side_of_right() {
    let (bl, ifs) = shaft_hub_base();
    let m = generate(&bl, &ifs, 1).unwrap();
    m.validate().unwrap();
    assert_eq!(m.interfaces.len(), 2);
    let fit = &m.interfaces[0];
    assert_eq!((fit.body_a, fit.body_b), (0, 1));
    // four hub elements along 10 ≤ y ≤ 30, walked upwards (B on the right)
    assert_eq!(fit.edges.len(), 4);
    let mut last_y = 10.0;
    for e in &fit.edges {
        let y = e.a.map(|n| m.nodes[n][1]);
        assert!(
            y[0] == last_y && y[0] < y[1] && y[1] < y[2],
            "{y:?} after {last_y}"
        );
        last_y = y[2];
        for i in 0..3 {
            let (xa, xb) = (m.nodes[e.a[i]], m.nodes[e.b[i]]);
            assert_eq!(xa, xb);
            assert_ne!(e.a[i], e.b[i]);
            assert_eq!(xa[0], 10.0);
            assert!(m.node_sets["shaft.right"].binary_search(&e.a[i]).is_ok());
            assert!(m.node_sets["hub.left"].binary_search(&e.b[i]).is_ok());
        }
    }
    assert_eq!(last_y, 30.0);
    assert_eq!(m.nodes[fit.edges[0].a[0]][1], 10.0);
    assert_eq!(m.nodes[fit.edges[3].a[2]][1], 30.0);
    // the horizontal one as before: hub bottom on base top, increasing x
    let seat = &m.interfaces[1];
    assert_eq!((seat.body_a, seat.body_b), (1, 2));
    assert_eq!(seat.edges.len(), 4);
    for w in seat.edges.windows(2) {
        assert!(m.nodes[w[0].a[2]][0] <= m.nodes[w[1].a[0]][0]);
    }
    assert!(seat
        .edges
        .iter()
        .all(|e| e.a.iter().all(|&n| m.nodes[n][1] == 10.0)));
}

#[test]
fn vertical_interface_errors_are_named() {
    let check = |bl: &[BlockSpec], ifs: &[InterfaceSpec], want: &[&str]| {
        let e = generate(bl, ifs, 1).unwrap_err().0;
        for w in want {
            assert!(e.contains(w), "{e:?} lacks {w:?}");
        }
    };
    // the hub moved away from the shaft: the sides do not face each other
    let (mut bl, ifs) = shaft_hub_base();
    bl[1].x = vec![11., 30.];
    check(
        &bl,
        &ifs[..1],
        &[
            "interface \"fit\"",
            "the right side of \"shaft\" is at x = 10",
            "the left side of \"hub\" is at x = 11",
        ],
    );
    // the hub above the shaft: no overlap in y
    let (mut bl, ifs) = shaft_hub_base();
    bl[1].y = vec![40., 60.];
    check(&bl, &ifs[..1], &["do not overlap in y"]);
    // a coarser hub: unmatched nodes
    let (mut bl, ifs) = shaft_hub_base();
    bl[1].ny = vec![3];
    check(&bl, &ifs[..1], &["node at y = ", "no partner"]);
    // the shaft's element edge crosses the hub's end
    let (mut bl, ifs) = shaft_hub_base();
    bl[0].ny = vec![1, 4, 1];
    bl[1].y = vec![5., 15., 30.];
    bl[1].ny = vec![1, 3];
    check(
        &bl,
        &ifs[..1],
        &["straddles the end of the overlap at y = "],
    );
    // mixed and incomplete specifications
    let (bl, _) = shaft_hub_base();
    let mixed = iface("fit", [Some("shaft"), None, None, Some("hub")]);
    check(&bl, &[mixed], &["interface \"fit\"", "not both"]);
    let half = iface("fit", [None, None, Some("shaft"), None]);
    check(&bl, &[half], &["give left and right"]);
    let none = iface("fit", [None, None, None, None]);
    check(&bl, &[none], &["give upper and lower", "or left and right"]);
    let same = iface("fit", [None, None, Some("hub"), Some("hub")]);
    check(&bl, &[same], &["left and right are the same block"]);
    let unknown = iface("fit", [None, None, Some("shaft"), Some("sleeve")]);
    check(&bl, &[unknown], &["no block named \"sleeve\""]);
}

#[test]
fn curved_sides_put_every_side_node_on_the_curve() {
    // a cylinder segment: bottom arc of radius 50 with its apex at x = 0
    let mut cyl = block(
        "cyl",
        vec![-10., -2., 2., 10.],
        vec![3, 4, 3],
        vec![0., 20.],
        vec![4],
    );
    cyl.bottom = Some(SideShape {
        radius: Some(50.0),
        center: Some(0.0),
        round_left: None,
        round_right: None,
        ..Default::default()
    });
    // a punch with a 1 mm rounding at its right end, and a crowned top
    let mut punch = block(
        "punch",
        vec![0., 19., 20.],
        vec![4, 3],
        vec![30., 50.],
        vec![4],
    );
    punch.bottom = Some(SideShape {
        radius: None,
        center: None,
        round_left: None,
        round_right: Some(1.0),
        ..Default::default()
    });
    punch.top = Some(SideShape {
        radius: Some(100.0),
        center: None,
        round_left: None,
        round_right: None,
        ..Default::default()
    });
    let m = generate(&[cyl, punch], &[], 1).unwrap();
    m.validate().unwrap();
    for &n in &m.node_sets["cyl.bottom"] {
        let [x, y, _] = m.nodes[n];
        assert!(
            (x * x + (y - 50.0).powi(2) - 2500.0).abs() < 1e-9,
            "{x} {y}"
        );
    }
    let bottom = &m.node_sets["punch.bottom"];
    let mut on_round = 0;
    for &n in bottom {
        let [x, y, _] = m.nodes[n];
        if x > 19.0 + 1e-12 {
            on_round += 1;
            assert!(((x - 19.0).powi(2) + (y - 31.0).powi(2) - 1.0).abs() < 1e-12);
        } else {
            assert_eq!(y, 30.0);
        }
    }
    assert_eq!(on_round, 6); // 3 elements: 2 corners, 3 midsides, the end
                             // the rounding's nodes are evenly spaced in angle, the last at 90°
    let end = m.node_sets["punch.right"]
        .iter()
        .map(|&n| m.nodes[n])
        .min_by(|a, b| a[1].total_cmp(&b[1]))
        .unwrap();
    assert!((end[0] - 20.0).abs() < 1e-12 && (end[1] - 31.0).abs() < 1e-12);
    // the crowned top: highest at the middle (x = 10), 100 mm radius
    for &n in &m.node_sets["punch.top"] {
        let [x, y, _] = m.nodes[n];
        assert!(((x - 10.0).powi(2) + (y - (50.0 - 100.0)).powi(2) - 1e4).abs() < 1e-8);
    }
}

#[test]
fn curved_side_errors_are_named() {
    let shape = |radius, round_right| SideShape {
        radius,
        center: None,
        round_left: None,
        round_right,
        ..Default::default()
    };
    let check = |b: BlockSpec, ifs: &[InterfaceSpec], want: &str| {
        let e = generate(&[b], ifs, 1).unwrap_err().0;
        assert!(e.contains(want), "{e:?} lacks {want:?}");
    };
    let base = || block("p", vec![0., 19., 20.], vec![2, 1], vec![0., 10.], vec![2]);
    let mut b = base();
    b.bottom = Some(shape(Some(5.0), None));
    check(b, &[], "bottom.radius: 5 mm is too small");
    let mut b = base();
    b.bottom = Some(shape(Some(50.0), Some(1.0)));
    check(b, &[], "not both");
    let mut b = base();
    b.bottom = Some(shape(None, Some(2.0)));
    check(b, &[], "breakpoint where the right rounding starts, x = 18");
    let mut b = base();
    b.bottom = Some(shape(None, Some(-1.0)));
    check(b, &[], "bottom.round_right: -1 must be a positive length");
    let mut b = base();
    b.top = Some(shape(None, None));
    check(b, &[], "block \"p\" top.radius: missing: give radius");
    // a curved side on a matching interface
    let mut up = block("up", vec![0., 20.], vec![2], vec![0., 10.], vec![2]);
    up.bottom = Some(shape(Some(100.0), None));
    let low = block("low", vec![0., 20.], vec![2], vec![-10., 0.], vec![2]);
    let e = generate(
        &[up, low],
        &[iface("c", [Some("up"), Some("low"), None, None])],
        1,
    )
    .unwrap_err()
    .0;
    assert!(
        e.contains("the bottom of block \"up\" is curved") && e.contains("matching = false"),
        "{e}"
    );
}

#[test]
fn inverted_element_is_detected() {
    let (bl, ifs) = punch();
    let mut m = generate(&bl, &ifs, 1).unwrap();
    m.elements[3].nodes_mut().swap(1, 3);
    let e = m.validate().unwrap_err();
    assert!(e.0.contains("element 3") && e.0.contains("inverted"), "{e}");
}

/// The rules of docs/case-schema.md ("Curved block sides") at their edges,
/// through [`SideShape::check`] (the key named, the reason given).
#[test]
fn curved_side_rules_hold_at_their_limits() {
    let xs = [0.0, 2.0, 15.0];
    let ys = [0.0, 20.0];
    let arc = |radius: f64, center: Option<f64>| SideShape {
        radius: Some(radius),
        center,
        round_left: None,
        round_right: None,
        ..Default::default()
    };
    let key = |s: &SideShape, on_axis| s.check(&xs, ys, on_axis).map_err(|e| (e.key, e.message));
    // the apex on the side, its ends included; off it refused, on either side
    assert!(key(&arc(50.0, Some(0.0)), None).is_ok());
    assert!(key(&arc(50.0, Some(15.0)), None).is_ok());
    for c in [-5.0, -1e-6, 15.001] {
        let e = key(&arc(50.0, Some(c)), Some("the axis r = 0")).unwrap_err();
        assert_eq!(e.0, "center", "{e:?}");
        assert!(e.1.contains("lies off the side"), "{e:?}");
    }
    // the smallest radius: max(reach / 0.9, (reach² + h²/4) / h) = 16.667 here
    let e = key(&arc(16.6, Some(0.0)), None).unwrap_err();
    assert!(
        e.0 == "radius" && e.1.contains("admits 16.667 < radius"),
        "{e:?}"
    );
    assert!(key(&arc(16.7, Some(0.0)), None).is_ok());
    // a low block: the rise (sagitta) binds, (225 + 1)/2 = 113 mm
    let low = |r: f64| arc(r, Some(0.0)).check(&xs, [0.0, 2.0], None);
    assert!(low(112.9).unwrap_err().message.contains("rises"));
    assert!(low(113.1).is_ok());
    // the largest: a rise of 1e-9 of the block's size (25 mm), R ≈ 15²/(2 · 2.5e-8)
    assert!(key(&arc(4.4e9, Some(0.0)), None).is_ok());
    for r in [4.6e9, 1e20, 1e300, f64::MAX] {
        let e = key(&arc(r, Some(0.0)), None).unwrap_err();
        assert!(
            e.0 == "radius" && e.1.contains("flat side to round-off"),
            "{e:?}"
        );
    }
    let e = key(&arc(f64::INFINITY, None), None).unwrap_err();
    assert!(e.1.contains("positive length"), "{e:?}");
    // roundings: below 1e-9 of the block a sharp corner; on the axis or a
    // symmetry plane a cusp (a block away from it may round its left end)
    let round = |l: Option<f64>, r: Option<f64>| SideShape {
        radius: None,
        center: None,
        round_left: l,
        round_right: r,
        ..Default::default()
    };
    let xr = [0.0, 1e-9, 2.0, 15.0];
    let e = round(Some(1e-9), None).check(&xr, ys, None).unwrap_err();
    assert!(
        e.key == "round_left" && e.message.contains("sharp corner"),
        "{e:?}"
    );
    let e = round(Some(2.0), None)
        .check(&xs, ys, Some("the axis r = 0"))
        .unwrap_err();
    assert!(e.key == "round_left" && e.message.contains("cusp"), "{e:?}");
    assert!(round(Some(2.0), None).check(&xs, ys, None).is_ok());
    assert!(round(None, Some(1.0))
        .check(&[0.0, 14.0, 15.0], ys, Some("the axis r = 0"))
        .is_ok());
}

/// The arc's depth r − √(r² − d²) is computed without cancellation: nodes
/// of a large radius lie on their circle to round-off of the depth, where
/// the textbook formula loses every digit.
#[test]
fn a_large_radius_keeps_its_depth() {
    let s = SideShape {
        radius: Some(1e9),
        center: Some(0.0),
        round_left: None,
        round_right: None,
        ..Default::default()
    };
    let (_, depth) = s.point(10.0, 0.0, 10.0);
    let exact = 100.0 / (2e9) * (1.0 + 100.0 / (4e18));
    assert!((depth - exact).abs() <= 1e-15 * exact, "{depth} vs {exact}");
    let naive = 1e9 - (1e18f64 - 100.0).sqrt();
    assert!((naive - exact).abs() > 1e-3 * exact, "{naive}");
}

/// A chamfer (convex, a straight cut of the corner): the nodes of the cut
/// on its line, evenly spaced along it, the right side starting `across`
/// above the corner; 45° from one number; its rules named by key.
#[test]
fn a_chamfer_cuts_the_corner_straight() {
    let mut p = block("p", vec![0., 18., 20.], vec![4, 4], vec![0., 10.], vec![2]);
    p.bottom = Some(SideShape {
        chamfer_right: Some(Chamfer {
            along: 2.0,
            across: 1.0,
        }),
        ..Default::default()
    });
    let m = generate(&[p.clone()], &[], 1).unwrap();
    m.validate().unwrap();
    let mut cut: Vec<[f64; 3]> = m.node_sets["p.bottom"]
        .iter()
        .map(|&n| m.nodes[n])
        .filter(|x| x[0] >= 18.0)
        .collect();
    cut.sort_by(|a, b| a[0].total_cmp(&b[0]));
    assert_eq!(cut.len(), 9);
    for (k, x) in cut.iter().enumerate() {
        // (18, 0) to (20, 1) in 8 equal steps
        let u = k as f64 / 8.0;
        assert!(
            (x[0] - 18.0 - 2.0 * u).abs() < 1e-12 && (x[1] - u).abs() < 1e-12,
            "{x:?}"
        );
    }
    let low = m.node_sets["p.right"]
        .iter()
        .map(|&n| m.nodes[n][1])
        .fold(f64::INFINITY, f64::min);
    assert_eq!(low, 1.0);
    // one number is a 45° chamfer, from a case file
    let s: SideShape = toml::from_str("chamfer_left = 1.5").unwrap();
    assert_eq!(
        s.chamfer_left,
        Some(Chamfer {
            along: 1.5,
            across: 1.5
        })
    );
    let s: SideShape = toml::from_str("chamfer_left = [2, 0.5]").unwrap();
    assert_eq!(
        s.chamfer_left,
        Some(Chamfer {
            along: 2.0,
            across: 0.5
        })
    );
    for bad in [
        "chamfer_left = [1.0]",
        "chamfer_left = [1.0, 2.0, 3.0]",
        "chamfer_left = \"a\"",
    ] {
        let e = toml::from_str::<SideShape>(bad).unwrap_err().to_string();
        assert!(e.contains("a leg length in mm"), "{bad}: {e}");
    }
}

/// A chamfer's rules, each named by its key: one shape per end, the leg
/// across less than half the block's height, a breakpoint where it starts,
/// positive legs, none on the axis, the shaped ends no wider than the block.
#[test]
fn a_chamfer_outside_its_rules_is_refused_by_key() {
    let xs = [0.0, 2.0, 18.0, 20.0];
    let c = |along, across| Some(Chamfer { along, across });
    let rule = |s: SideShape, on_axis: Option<&str>| {
        let e = s.check(&xs, [0.0, 10.0], on_axis).unwrap_err();
        format!("{}: {}", e.key, e.message)
    };
    let both = SideShape {
        round_right: Some(2.0),
        chamfer_right: c(2.0, 2.0),
        ..Default::default()
    };
    assert!(rule(both, None)
        .contains("chamfer_right: round_right and chamfer_right both shape the right end"));
    let both = SideShape {
        chamfer_left: c(2.0, 2.0),
        fillet_left: Some(1.0),
        ..Default::default()
    };
    assert!(rule(both, None).contains("fillet_left: chamfer_left and fillet_left both"));
    let deep = SideShape {
        chamfer_right: c(2.0, 5.0),
        ..Default::default()
    };
    assert!(rule(deep, None)
        .contains("chamfer_right: the leg across the side, 5 mm, must be less than half"));
    let off = SideShape {
        chamfer_right: c(3.0, 1.0),
        ..Default::default()
    };
    assert!(rule(off, None).contains("breakpoint where the right chamfer starts, x = 17"));
    let nan = SideShape {
        chamfer_left: c(2.0, f64::NAN),
        ..Default::default()
    };
    assert!(
        rule(nan, None).contains("chamfer_left: NaN (across the side) must be a positive length")
    );
    let axis = SideShape {
        chamfer_left: c(2.0, 1.0),
        ..Default::default()
    };
    assert!(rule(axis.clone(), Some("the axis r = 0"))
        .contains("chamfer_left: the block's left side lies on the axis r = 0"));
    assert!(axis.check(&xs, [0.0, 10.0], None).is_ok());
    let wide = SideShape {
        chamfer_left: c(2.0, 1.0),
        chamfer_right: c(18.5, 1.0),
        ..Default::default()
    };
    assert!(rule(wide, None).contains("wider than the block"));
}
