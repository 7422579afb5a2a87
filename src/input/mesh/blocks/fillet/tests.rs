//! The concave fillet: its map (positive Jacobian, the identity beyond r),
//! the bolt's fillet on the mesh (every arc node on the circle, evenly
//! spaced in angle, positive Jacobians, the area and the volume of
//! revolution converging to the exact ones at order 4), all eight corners a
//! fillet may be named at, and the refusals.

use super::*;
use crate::input::mesh::blocks::tests::block;
use crate::input::mesh::blocks::{generate, SideShape};
use crate::physics::element::family::Family;
use std::f64::consts::{FRAC_PI_2, PI};

/// The eight (a, b) pairs of axis-aligned unit legs, at C = (0, 0).
fn all_orientations(r: f64) -> Vec<Fillet> {
    let units = [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]];
    let mut out = Vec::new();
    for a in units {
        for b in units {
            if a[0] * b[0] + a[1] * b[1] == 0.0 {
                out.push(Fillet {
                    block: 0,
                    side: "right",
                    key: "fillet_top",
                    r,
                    c: [0.0, 0.0],
                    a,
                    b,
                });
            }
        }
    }
    out
}

/// The map as a function of the whole plane (the identity where it leaves a
/// point).
fn map(f: &Fillet, p: [f64; 2]) -> [f64; 2] {
    f.place(p).unwrap_or(p)
}

#[test]
fn the_map_has_a_positive_jacobian_and_is_the_identity_beyond_r() {
    let r = 1.5;
    let h = 1e-6;
    let mut least = f64::INFINITY;
    for f in all_orientations(r) {
        let n = 120;
        for i in 0..=n {
            for j in 0..=n {
                let p = [
                    -2.0 * r + 4.0 * r * i as f64 / n as f64,
                    -2.0 * r + 4.0 * r * j as f64 / n as f64,
                ];
                let (s, t) = f.local(p);
                // the stencil within the body (off the empty quadrant)
                if s > -2.0 * h && t > -2.0 * h {
                    continue;
                }
                let d = |e: [f64; 2]| {
                    let (q, m) = (
                        map(&f, [p[0] + h * e[0], p[1] + h * e[1]]),
                        map(&f, [p[0] - h * e[0], p[1] - h * e[1]]),
                    );
                    [(q[0] - m[0]) / (2.0 * h), (q[1] - m[1]) / (2.0 * h)]
                };
                let (dx, dy) = (d([1.0, 0.0]), d([0.0, 1.0]));
                let det = dx[0] * dy[1] - dx[1] * dy[0];
                least = least.min(det);
                if s.abs() >= r || t.abs() >= r {
                    assert_eq!(f.place(p), None, "{p:?}");
                }
            }
        }
        // the corner goes to the arc's middle, the legs' ends stay
        let m = map(&f, f.c);
        let o = f.center();
        assert!(((m[0] - o[0]).hypot(m[1] - o[1]) - r).abs() < 1e-14);
        for end in [f.at(r, 0.0), f.at(0.0, r)] {
            let q = map(&f, end);
            assert!((q[0] - end[0]).abs() < 1e-15 && (q[1] - end[1]).abs() < 1e-15);
        }
    }
    println!("fillet map: least det J {least:.4}");
    assert!(least > 0.5, "{least}");
}

/// The bolt of docs/case-schema.md ("Bodies of several blocks") with a
/// fillet of radius r under its head: n elements on each half of the arc.
fn bolt(r: f64, n: usize) -> Vec<BlockSpec> {
    let mut head = block(
        "bolt",
        vec![0., 8., 8. + r, 20.],
        vec![4, n, 4],
        vec![40., 50.],
        vec![3],
    );
    head.name = Some("head".into());
    let mut shank = block(
        "bolt",
        vec![0., 8.],
        vec![4],
        vec![0., 40. - r, 40.],
        vec![6, n],
    );
    shank.name = Some("shank".into());
    shank.right = Some(SideFillets {
        fillet_top: Some(r),
        ..Default::default()
    });
    vec![head, shank]
}

/// The mesh's area and its volume of revolution about x = 0 (3×3 Gauss,
/// exact for the Q8's polynomial det J and x det J), and the area inside
/// its outline (∮ x dy over the quadratic edges no two elements share).
fn measures(mesh: &Mesh) -> (f64, f64, f64) {
    let rule = Family::Q8.rule(true);
    let (mut area, mut volume) = (0.0, 0.0);
    let mut count = std::collections::HashMap::new();
    for (e, el) in mesh.elements.iter().enumerate() {
        let c = mesh.element_coords(e);
        for &(xi, w) in &rule.points {
            let (det, _) = el.family.physical_derivs(&c, xi).unwrap();
            let n = el.family.shape(xi);
            let x: f64 = (0..8).map(|a| n[a] * c[a][0]).sum();
            area += w * det;
            volume += 2.0 * PI * x * w * det;
        }
        for ed in el.edges() {
            *count
                .entry((ed[0].min(ed[2]), ed[0].max(ed[2])))
                .or_insert(0) += 1;
        }
    }
    let g = [-(0.6f64.sqrt()), 0.0, 0.6f64.sqrt()];
    let wg = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let mut outline = 0.0;
    for el in &mesh.elements {
        for ed in el.edges() {
            if count[&(ed[0].min(ed[2]), ed[0].max(ed[2]))] != 1 {
                continue;
            }
            let p = ed.map(|k| mesh.xy(k));
            for (xi, w) in g.iter().zip(wg) {
                let n = [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)];
                let dn = [xi - 0.5, -2.0 * xi, xi + 0.5];
                let x: f64 = (0..3).map(|a| n[a] * p[a][0]).sum();
                let dy: f64 = (0..3).map(|a| dn[a] * p[a][1]).sum();
                outline += w * x * dy;
            }
        }
    }
    (area, volume, outline)
}

#[test]
fn the_bolts_fillet_lies_on_its_circle_and_its_area_converges() {
    let r = 0.6;
    let (cx, cy) = (8.0 + r, 40.0 - r);
    let exact_area = 8.0 * 40.0 + 20.0 * 10.0 + r * r * (1.0 - PI / 4.0);
    // the fillet's ring: the square [8, 8 + r] × [40 − r, 40] less the
    // quarter disc about (8 + r, 40 − r) whose centroid is 4r/3π inside it
    let ring =
        2.0 * PI * (r * r * (8.0 + r / 2.0) - PI * r * r / 4.0 * (cx - 4.0 * r / (3.0 * PI)));
    let exact_volume = PI * 64.0 * 40.0 + PI * 400.0 * 10.0 + ring;
    let mut errors = Vec::new();
    for refine in [1, 2, 4] {
        let n = 2;
        let m = generate(&bolt(r, n), &[], refine).unwrap();
        m.validate().unwrap();
        // the arc's nodes: n·refine elements on each half, 2 + 2 sides' nodes
        let on: Vec<f64> = m
            .nodes
            .iter()
            .filter(|x| (x[0] - cx).hypot(x[1] - cy) < r + 1e-9 && x[0] <= cx && x[1] >= cy)
            .map(|x| {
                let d = (x[0] - cx).hypot(x[1] - cy);
                assert!((d - r).abs() < 1e-12, "{x:?} at {d}");
                (x[1] - cy).atan2(cx - x[0])
            })
            .collect();
        let k = n * refine;
        assert_eq!(on.len(), 4 * k + 1, "refine {refine}");
        let mut angles = on.clone();
        angles.sort_by(f64::total_cmp);
        for w in angles.windows(2) {
            let step = FRAC_PI_2 / (4 * k) as f64;
            assert!((w[1] - w[0] - step).abs() < 1e-12, "{angles:?}");
        }
        // the arc is the outline: its nodes are in the side sets
        let sides: Vec<usize> = ["shank.right", "head.bottom"]
            .iter()
            .flat_map(|s| m.node_sets[*s].clone())
            .collect();
        let arc_nodes = (0..m.nodes.len())
            .filter(|&n| {
                let x = m.nodes[n];
                ((x[0] - cx).hypot(x[1] - cy) - r).abs() < 1e-12 && x[0] <= cx && x[1] >= cy
            })
            .count();
        assert_eq!(arc_nodes, 4 * k + 1);
        assert!(sides.len() >= arc_nodes);
        let (area, volume, outline) = measures(&m);
        // the elements tile the outline's inside: no gap, no overlap
        assert!((area - outline).abs() < 1e-12 * area, "{area} vs {outline}");
        errors.push((
            (area - exact_area).abs() / exact_area,
            (volume - exact_volume).abs() / exact_volume,
        ));
    }
    // quadratic edges on a circle: the area between them falls as Δψ⁴
    let order =
        |i: usize, pick: fn(&(f64, f64)) -> f64| (pick(&errors[i]) / pick(&errors[i + 1])).log2();
    println!("bolt fillet: relative errors of area and volume {errors:?}");
    for pick in [|e: &(f64, f64)| e.0, |e: &(f64, f64)| e.1] {
        let (o1, o2) = (order(0, pick), order(1, pick));
        println!("orders {o1:.2} {o2:.2}");
        assert!(
            (3.5..4.6).contains(&o1) && (3.5..4.6).contains(&o2),
            "{errors:?}"
        );
        assert!(pick(&errors[2]) < 1e-9, "{errors:?}");
    }
}

/// The bolt turned and mirrored into each of the eight places a fillet may
/// be named: `sx`, `sy` mirror x and y, `swap` exchanges them first.
fn turned(r: f64, sx: f64, sy: f64, swap: bool) -> (Vec<BlockSpec>, [f64; 2]) {
    let mut out = Vec::new();
    for mut b in bolt(r, 2) {
        let fillet = b.right.take().and_then(|s| s.fillet_top);
        if swap {
            std::mem::swap(&mut b.x, &mut b.y);
            std::mem::swap(&mut b.nx, &mut b.ny);
        }
        let flip = |v: &mut Vec<f64>, n: &mut Vec<usize>, s: f64| {
            if s < 0.0 {
                *v = v.iter().rev().map(|x| -x).collect();
                n.reverse();
            }
        };
        flip(&mut b.x, &mut b.nx, sx);
        flip(&mut b.y, &mut b.ny, sy);
        if let Some(r) = fillet {
            // the shank's right side's top end, moved alike
            let (side, end) = match (swap, sx < 0.0, sy < 0.0) {
                (false, false, false) => ("right", "top"),
                (false, true, false) => ("left", "top"),
                (false, false, true) => ("right", "bottom"),
                (false, true, true) => ("left", "bottom"),
                (true, false, false) => ("top", "right"),
                (true, true, false) => ("top", "left"),
                (true, false, true) => ("bottom", "right"),
                (true, true, true) => ("bottom", "left"),
            };
            let fl = SideFillets {
                fillet_bottom: (end == "bottom").then_some(r),
                fillet_top: (end == "top").then_some(r),
            };
            let sh = SideShape {
                fillet_left: (end == "left").then_some(r),
                fillet_right: (end == "right").then_some(r),
                ..Default::default()
            };
            match side {
                "left" => b.left = Some(fl),
                "right" => b.right = Some(fl),
                "bottom" => b.bottom = Some(sh),
                _ => b.top = Some(sh),
            }
        }
        out.push(b);
    }
    let (cx, cy) = if swap {
        (40.0 - r, 8.0 + r)
    } else {
        (8.0 + r, 40.0 - r)
    };
    (out, [sx * cx, sy * cy])
}

#[test]
fn a_fillet_may_be_named_at_each_of_the_eight_corner_ends() {
    let r = 0.8;
    let exact = 8.0 * 40.0 + 20.0 * 10.0 + r * r * (1.0 - PI / 4.0);
    let mut areas = Vec::new();
    for swap in [false, true] {
        for sx in [1.0, -1.0] {
            for sy in [1.0, -1.0] {
                let (blocks, o) = turned(r, sx, sy, swap);
                let m = generate(&blocks, &[], 1).unwrap();
                m.validate().unwrap();
                let on = m
                    .nodes
                    .iter()
                    .filter(|x| ((x[0] - o[0]).hypot(x[1] - o[1]) - r).abs() < 1e-12)
                    .count();
                assert_eq!(on, 9, "swap {swap} sx {sx} sy {sy}");
                areas.push(measures(&m).0);
            }
        }
    }
    for a in &areas {
        assert!((a - areas[0]).abs() < 1e-12 * exact, "{areas:?}");
        assert!((a - exact).abs() < 1e-6 * exact, "{a} vs {exact}");
    }
}

/// `check` refuses `blocks` with a message that contains `want`.
fn refused(blocks: &[BlockSpec], axis: Option<&str>, want: &str) {
    let e = check(blocks, axis).expect_err(want);
    let text = format!("block {} {}.{}: {}", e.block, e.side, e.key, e.message);
    assert!(text.contains(want), "{text:?} lacks {want:?}");
}

/// Each rule of the module text, refused naming the block, side and key:
/// the radius, the axis, the blocks around the corner.
#[test]
fn broken_fillets_are_refused_by_name() {
    assert!(check(&bolt(0.6, 2), Some("the axis r = 0")).is_ok());
    for r in [0.0, -0.5, f64::NAN, f64::INFINITY] {
        let mut b = bolt(0.6, 2);
        b[1].right.as_mut().unwrap().fillet_top = Some(r);
        refused(&b, None, "block 1 right.fillet_top");
        refused(&b, None, "must be a positive length");
    }
    // larger than the head is thick (10 mm), the shank wide (8 mm)
    let b = bolt(10.5, 2);
    refused(&b, None, "larger than the blocks around its corner");
    // across the axis: the shank's radius 8 is below r
    let mut b = bolt(8.5, 2);
    b[0].y[1] = 60.0;
    refused(&b, Some("the axis r = 0"), "reaches across the axis r = 0");
    // on the axis: the shank's left side at r = 0
    let mut b = bolt(0.6, 2);
    b[1].right = None;
    b[1].left = Some(SideFillets {
        fillet_top: Some(0.6),
        ..Default::default()
    });
    refused(&b, Some("the axis r = 0"), "lies on the axis r = 0");
    // where no block meets: the shank alone
    let b = vec![bolt(0.6, 2).remove(1)];
    refused(
        &b,
        None,
        "no other block of body \"bolt\" meets the corner (8, 40)",
    );
    // the fillet's end no breakpoint of the head's bottom (nor the shank's side)
    let mut b = bolt(0.6, 2);
    b[0].x = vec![0., 8., 9., 20.];
    refused(&b, None, "x = 8.6 on the bottom of block \"head\"");
    let mut b = bolt(0.6, 2);
    b[1].y = vec![0., 39., 40.];
    refused(&b, None, "y = 39.4 on the right side of block \"shank\"");
}

/// The rules of the module text that concern other blocks than the
/// corner's: a block in the empty quadrant, shaped sides and other fillets
/// within r, an empty side table.
#[test]
fn fillets_among_other_blocks_are_refused_by_name() {
    // a block in the empty quadrant: the body's own, or another body's
    let mut b = bolt(0.6, 2);
    b.push(block(
        "plate",
        vec![8., 20.],
        vec![2],
        vec![30., 40.],
        vec![2],
    ));
    refused(&b, None, "would overlap block \"plate\" of body \"plate\"");
    // a shaped side within r: the head split at the shank's radius, its
    // outer block's bottom rounded at the corner (a rounding far off is fine)
    let outer = |bottom: Option<SideShape>| {
        let mut b = bolt(0.6, 2);
        b[0].x = vec![0., 8.];
        b[0].nx = vec![4];
        let mut o = block(
            "bolt",
            vec![8., 8.3, 8.6, 20.],
            vec![1, 1, 4],
            vec![40., 50.],
            vec![3],
        );
        o.name = Some("outer".into());
        o.bottom = bottom;
        o.top = Some(SideShape {
            round_right: Some(1.0),
            ..Default::default()
        });
        o.x = vec![8., 8.3, 8.6, 19., 20.];
        o.nx = vec![1, 1, 4, 1];
        b.push(o);
        b
    };
    assert!(check(&outer(None), None).is_ok());
    let round = SideShape {
        round_left: Some(0.3),
        ..Default::default()
    };
    refused(
        &outer(Some(round)),
        None,
        "the bottom of block \"outer\" is curved, rounded or cut",
    );
    // two fillets that reach into each other: a short shank between a head
    // and a foot, filleted at both ends of its right side
    let mut b = bolt(0.6, 2);
    b[0].y = vec![1., 11.];
    b[1].y = vec![0., 0.4, 0.6, 1.];
    b[1].ny = vec![1, 1, 1];
    b[1].right.as_mut().unwrap().fillet_bottom = Some(0.6);
    let mut foot = block(
        "bolt",
        vec![0., 8., 8.6, 12.],
        vec![4, 2, 2],
        vec![-5., 0.],
        vec![2],
    );
    foot.name = Some("foot".into());
    b.push(foot);
    refused(&b, None, "reach into each other");
    // an empty side table
    let mut b = bolt(0.6, 2);
    b[1].right = Some(SideFillets::default());
    refused(&b, None, "right.fillet_top: missing");
}

/// A fillet is made in the layout, so a sweep takes it as it takes any
/// node: the bolt revolved through 90° (its shank on the axis: the O-grid
/// core) is a valid mesh whose volume is a quarter of the filleted bolt's
/// volume of revolution, to the sweep's and the arcs' chord error.
#[test]
fn a_revolved_filleted_bolt_has_the_volume_of_revolution() {
    use crate::physics::element::solid3::{ElementGeometry3, Family3};
    let r = 0.6;
    let plane = generate(&bolt(r, 2), &[], 2).unwrap();
    let (_, volume2d, _) = measures(&plane);
    let rule = Family3::H20.rule(true);
    let mut errors = Vec::new();
    for n in [12, 24] {
        let mesh = crate::input::mesh::revolve::revolve(&plane, FRAC_PI_2, n).unwrap();
        mesh.validate().unwrap();
        let v: f64 = (0..mesh.elements.len())
            .map(|e| {
                let c = mesh.element_coords3(e);
                ElementGeometry3::new(Family3::H20, &c[..20], &rule)
                    .unwrap()
                    .volume()
            })
            .sum();
        errors.push((4.0 * v - volume2d).abs() / volume2d);
    }
    println!("revolved filleted bolt: relative volume errors {errors:?} (12, 24 layers)");
    assert!(
        errors[1] < 1e-6 && errors[1] < errors[0] / 8.0,
        "{errors:?}"
    );
}
