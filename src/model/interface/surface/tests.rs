use super::closest::{project, shape_second};
use super::*;
use crate::input::case::settings::FrictionScheme;
use crate::input::mesh::NodeDofs;
use crate::model::interface::InterfaceModel;
use crate::numbers::fd;
use crate::numbers::vec3::cross;
use crate::physics::contact::{PointState, TangentialLaw};

#[test]
fn the_second_shape_derivatives_are_those_of_the_first() {
    for family in [Family::Q8, Family::T6] {
        for xi in [[0.3, -0.6], [0.1, 0.2], [-0.9, 0.45]] {
            let dd = shape_second(family, xi);
            let h = 1e-4;
            let at = |d: [f64; 2]| family.shape_derivs([xi[0] + d[0], xi[1] + d[1]]);
            let (px, mx, py, my) = (at([h, 0.0]), at([-h, 0.0]), at([0.0, h]), at([0.0, -h]));
            for a in 0..family.nodes() {
                // the first derivatives are quadratic: central differences exact to round-off
                let want = [
                    (px[a][0] - mx[a][0]) / (2.0 * h),
                    (py[a][0] - my[a][0]) / (2.0 * h),
                    (py[a][1] - my[a][1]) / (2.0 * h),
                ];
                let also = (px[a][1] - mx[a][1]) / (2.0 * h);
                for k in 0..3 {
                    assert!((dd[a][k] - want[k]).abs() < 1e-9, "{family:?} {a} {k}");
                }
                assert!((dd[a][1] - also).abs() < 1e-9);
            }
        }
    }
}

/// The 8 nodes of a quadrilateral face x(ξ, η) = map(ξ, η) (the face's
/// own shape then interpolates `map` at its nodes).
fn q8_face(map: impl Fn(f64, f64) -> [f64; 3]) -> Vec<[f64; 3]> {
    crate::physics::element::q8::NODE_XI
        .iter()
        .map(|&[s, t]| map(s, t))
        .collect()
}

/// A face patch of the sphere of radius 50 about (0, −50, 0) near its top
/// (0, 0, 0): the nodes on the sphere above the square (u, v) ∈ [0.2, 1.4] ×
/// [−0.5, 0.7] of the plane y = 0; ∂x/∂ξ × ∂x/∂η points out of the sphere.
fn sphere_q8() -> Vec<[f64; 3]> {
    q8_face(|s, t| {
        let (u, v) = (0.8 + 0.6 * s, 0.1 - 0.6 * t);
        let r = 50.0;
        [u, (r * r - u * u - v * v).sqrt() - r, v]
    })
}

/// The point at distance `d` along the face's normal from its point at ξ.
fn above(family: Family, x: &[[f64; 3]], xi: [f64; 2], d: f64) -> [f64; 3] {
    let p = closest::point_at(family, x, xi);
    let n = geometry(family, x, xi).1;
    std::array::from_fn(|c| p[c] + d * n[c])
}

#[test]
fn a_point_above_a_face_projects_onto_its_foot_flat_and_curved() {
    // a flat tilted quadrilateral: the foot, the normal and the distance exact
    let flat = q8_face(|s, t| [1.0 + 2.0 * s + 0.3 * t, 0.5 * s - t, 0.2 * s + 0.4 * t]);
    let tri = [
        [0.0, 0.0, 0.0],
        [3.0, 0.5, 0.0],
        [0.5, 2.5, 1.0],
        [1.5, 0.25, 0.0],
        [1.75, 1.5, 0.5],
        [0.25, 1.25, 0.5],
    ];
    // a 6-node triangle on the sphere: its corners and midsides on it
    let on_sphere = |u: f64, v: f64| [u, (2500.0 - u * u - v * v).sqrt() - 50.0, v];
    let curved_tri: Vec<[f64; 3]> = [
        [0.2, -0.3],
        [1.4, 0.1],
        [0.5, 0.9],
        [0.8, -0.1],
        [0.95, 0.5],
        [0.35, 0.3],
    ]
    .iter()
    .map(|&[u, v]| on_sphere(u, -v))
    .collect();
    let cases: [(Family, Vec<[f64; 3]>, [f64; 2]); 4] = [
        (Family::Q8, flat, [0.3, -0.7]),
        (Family::Q8, sphere_q8(), [-0.45, 0.6]),
        (Family::T6, tri.to_vec(), [0.2, 0.5]),
        (Family::T6, curved_tri, [0.6, 0.15]),
    ];
    for (family, x, xi0) in cases {
        for d in [0.37, -0.02, 0.0] {
            let p = above(family, &x, xi0, d);
            let c = closest(family, &x, p);
            assert_eq!(c.on, On::Inside, "{family:?} {d}");
            assert!(
                (c.xi[0] - xi0[0]).abs() < 1e-12 && (c.xi[1] - xi0[1]).abs() < 1e-12,
                "{family:?} d = {d}: ξ {:?} vs {xi0:?}",
                c.xi
            );
            assert!((c.d2.sqrt() - d.abs()).abs() < 1e-12, "{family:?} {}", c.d2);
            // the spring of the point: its normal and geometric gap
            let n = geometry(family, &x, c.xi).1;
            let gap = dot(sub(p, c.at), n);
            assert!((gap - d).abs() < 1e-12, "{family:?}: gap {gap} vs {d}");
        }
        // the foot is the face's closest point: no sampled point is closer
        let p = above(family, &x, xi0, 0.37);
        let c = closest(family, &x, p);
        for i in 0..=40 {
            for j in 0..=40 {
                let (u, v) = (i as f64 / 40.0, j as f64 / 40.0);
                let xi = match family {
                    Family::Q8 => [2.0 * u - 1.0, 2.0 * v - 1.0],
                    _ if u + v <= 1.0 => [u, v],
                    _ => continue,
                };
                let q = sub(closest::point_at(family, &x, xi), p);
                assert!(dot(q, q) >= c.d2 - 1e-12);
            }
        }
    }
}

#[test]
fn beyond_its_edge_a_point_finds_the_edge_or_the_corner() {
    let x = q8_face(|s, t| [s, 0.0, -t]);
    // beyond the edge ξ = 1 (the side x = 1), above the plane
    let c = closest(Family::Q8, &x, [1.5, 0.2, 0.3]);
    assert_eq!(c.on, On::Edge(1));
    assert!((c.xi[0] - 1.0).abs() < 1e-15 && (c.xi[1] + 0.3).abs() < 1e-12);
    assert!((c.d2 - 0.25 - 0.04).abs() < 1e-12);
    // beyond the corner (1, 0, −1): the node itself (ξ = η = 1)
    let c = closest(Family::Q8, &x, [1.5, 0.2, -1.5]);
    assert_eq!(c.on, On::Corner(2));
    assert_eq!(c.xi, [1.0, 1.0]);
    // a newton root within 1e-9 of the edge is inside
    let c = closest(Family::Q8, &x, [1.0 + 1e-12, 0.2, 0.3]);
    assert_eq!(c.on, On::Inside);
    assert_eq!(c.xi[0], 1.0);
    assert!(project(Family::Q8, &x, [1.0, 0.2, 0.3]).is_some());
}

/// A mesh of 2 × 2 master faces (body B) on [0, 2]² of the plane y = 0 and,
/// at height `h`, one slave face (body A) on [x0, x0 + 1] × [z0, z0 + 1]
/// bowed by `bow` (y = h − bow (u² + w²) about its centre): nodes 0..n of B's
/// grid, then A's 8.
fn two_sides(h: f64, x0: f64, z0: f64, bow: f64) -> (Mesh, NonMatchingFaces) {
    let mut mesh = Mesh::default();
    // the 5 × 5 node grid without the faces' centres
    let mut id = [[usize::MAX; 5]; 5];
    for (i, row) in id.iter_mut().enumerate() {
        for (j, slot) in row.iter_mut().enumerate() {
            if i % 2 == 1 && j % 2 == 1 {
                continue;
            }
            *slot = mesh.nodes.len();
            mesh.nodes.push([0.5 * i as f64, 0.0, 0.5 * j as f64]);
        }
    }
    // walked so that ∂x/∂ξ × ∂x/∂η = +y: ξ along x, η along −z
    let mut master = Vec::new();
    for a in 0..2 {
        for b in 0..2 {
            let (i, j) = (2 * a, 2 * b + 2);
            let n = |di: usize, dj: usize| id[i + di][j - dj];
            let nodes = [
                n(0, 0),
                n(2, 0),
                n(2, 2),
                n(0, 2),
                n(1, 0),
                n(2, 1),
                n(1, 2),
                n(0, 1),
            ];
            master.push(Face::new(Family::Q8, &nodes));
        }
    }
    let first = mesh.nodes.len();
    for p in q8_face(|s, t| {
        let (u, w) = (0.5 * s, -0.5 * t);
        [x0 + 0.5 + u, h - bow * (u * u + w * w), z0 + 0.5 + w]
    }) {
        mesh.nodes.push(p);
    }
    let slave = vec![Face::new(
        Family::Q8,
        &(first..first + 8).collect::<Vec<_>>(),
    )];
    (mesh, NonMatchingFaces { slave, master })
}

fn springs(h: f64, x0: f64, z0: f64, bow: f64, w: Weights) -> Result<Vec<Point>, String> {
    let (mesh, nm) = two_sides(h, x0, z0, bow);
    node_to_surface(&mesh, "c", &nm, w).map(|(_, p)| p)
}

fn segment_of(p: &Point) -> Segment {
    match &p.coupling {
        Coupling::NodeToSegment { segment, .. } => *segment,
        c => panic!("not a node-to-surface point: {c:?}"),
    }
}

#[test]
fn springs_over_a_flat_master_side_have_the_geometric_gap_and_its_normal() {
    for (w, count) in [(Weights::Consistent, 16), (Weights::Lumped, 8)] {
        let points = springs(0.3, 0.3, 0.6, 0.0, w).unwrap();
        assert_eq!(points.len(), count);
        let area: f64 = points.iter().map(|p| p.area).sum();
        assert!((area - 1.0).abs() < 1e-13, "{area}");
        for p in &points {
            let g = segment_of(p);
            assert!((g.gap - 0.3).abs() < 1e-14, "{}", g.gap);
            assert_eq!(g.s, 0.0);
            assert_eq!(g.len_b, 8);
            assert!((p.normal[1] - 1.0).abs() < 1e-15, "{:?}", p.normal);
            // the foot's shape values interpolate the point's x and z
            let (mesh, nm) = two_sides(0.3, 0.3, 0.6, 0.0);
            let xb: [f64; 3] = std::array::from_fn(|c| {
                (0..g.len_b).map(|j| g.nb[j] * mesh.nodes[g.b[j]][c]).sum()
            });
            let xa: [f64; 3] = std::array::from_fn(|c| {
                (0..g.len_a).map(|i| g.na[i] * mesh.nodes[g.a[i]][c]).sum()
            });
            assert!((xa[0] - xb[0]).abs() < 1e-14 && (xa[2] - xb[2]).abs() < 1e-14);
            assert!(nm.master.iter().any(|f| f.nodes() == &g.b[..8]));
        }
    }
}

#[test]
fn points_off_the_master_side_facing_away_or_overlapping_are_refused() {
    // the slave face reaches to x = 2.3, beyond the master side's x = 2
    let e = springs(0.1, 1.3, 0.5, 0.0, Weights::Consistent).unwrap_err();
    assert!(
        e.contains("interface \"c\"")
            && e.contains("projects outside every face of the master side (body B)")
            && e.contains("x ∈ [0, 2], y ∈ [0, 0], z ∈ [0, 2]"),
        "{e}"
    );
    // flush with the master side's end: inside
    assert!(springs(0.1, 1.0, 1.0, 0.0, Weights::Lumped).is_ok());
    // an overlap up to 1 % of the slave face (√2 mm) is round-off
    assert!(springs(-0.014, 0.5, 0.5, 0.0, Weights::Consistent).is_ok());
    let e = springs(-0.05, 0.5, 0.5, 0.0, Weights::Consistent).unwrap_err();
    assert!(
        e.contains("overlaps body B by 5.0000e-2 mm") && e.contains("negative `gap`"),
        "{e}"
    );
    // the slave face walked the other way round: its normal points out of
    // A, so A lies below it and faces away from B's top
    let (mesh, mut nm) = two_sides(0.2, 0.5, 0.5, 0.0);
    let turned: Vec<usize> = Family::Q8
        .reversed()
        .iter()
        .map(|&k| nm.slave[0].nodes()[k])
        .collect();
    nm.slave[0] = Face::new(Family::Q8, &turned);
    let e = node_to_surface(&mesh, "c", &nm, Weights::Lumped).unwrap_err();
    assert!(
        e.contains("do not face each other") && e.contains("makes 0.0°"),
        "{e}"
    );
}

#[test]
fn a_point_in_the_wedge_of_a_kink_takes_the_shared_edge() {
    // two master faces meeting at x = 1 at a convex kink: the plane y = 0
    // for x < 1, falling at 30° beyond
    let (c30, s30) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let mut mesh = Mesh::default();
    let left = q8_face(|s, t| [0.5 + 0.5 * s, 0.0, -t]);
    let right = q8_face(|s, t| {
        let u = 0.5 + 0.5 * s;
        [1.0 + c30 * u, -s30 * u, -t]
    });
    let mut faces = Vec::new();
    let mut index: HashMap<[u64; 3], usize> = HashMap::new();
    for x in [left, right] {
        let ids: Vec<usize> = x
            .iter()
            .map(|p| {
                *index
                    .entry(p.map(|v| (v + 0.0).to_bits()))
                    .or_insert_with(|| {
                        mesh.nodes.push(*p);
                        mesh.nodes.len() - 1
                    })
            })
            .collect();
        faces.push(Face::new(Family::Q8, &ids));
    }
    let master = Master::new(&mesh, &faces);
    assert_eq!(master.free_edges.len(), 6);
    // across the wedge: the foot on the shared edge, the normal along the ray
    for deg in [1.0, 10.0, 20.0, 29.0] {
        let a = f64::to_radians(deg);
        let d = 0.4;
        let sp = SlavePoint {
            a: [0; MAX_SIDE],
            na: [0.0; MAX_SIDE],
            len_a: 1,
            x: [1.0 + d * a.sin(), d * a.cos(), 0.25],
            area: 1.0,
            out: [0.0, -1.0, 0.0],
            h: 1.0,
        };
        let f = master.foot("c", &sp).unwrap();
        assert!((f.gap - d).abs() < 1e-12, "{deg}: gap {}", f.gap);
        assert!(
            (f.n[0] - a.sin()).abs() < 1e-12 && (f.n[1] - a.cos()).abs() < 1e-12,
            "{deg}: n {:?}",
            f.n
        );
        let on = closest::point_at(Family::Q8, &master.coords[f.k], f.xi);
        assert!((on[0] - 1.0).abs() < 1e-12 && on[1].abs() < 1e-12 && (on[2] - 0.25).abs() < 1e-12);
    }
    // beyond the free edge x = 0: refused
    let sp = SlavePoint {
        a: [0; MAX_SIDE],
        na: [0.0; MAX_SIDE],
        len_a: 1,
        x: [-0.2, 0.3, 0.5],
        area: 1.0,
        out: [0.0, -1.0, 0.0],
        h: 1.0,
    };
    let e = master.foot("c", &sp).unwrap_err();
    assert!(e.contains("projects outside every face"), "{e}");
}

#[test]
fn the_tree_finds_the_nearest_face_as_a_scan_of_all_does() {
    // a bumpy master side of 12 × 12 faces, points scattered above it
    let n = 12;
    let mut mesh = Mesh::default();
    let mut faces = Vec::new();
    let bump = |x: f64, z: f64| 0.3 * (0.7 * x).sin() * (0.5 * z).cos();
    for a in 0..n {
        for b in 0..n {
            let first = mesh.nodes.len();
            for p in q8_face(|s, t| {
                let (x, z) = (a as f64 + 0.5 + 0.5 * s, b as f64 + 0.5 - 0.5 * t);
                [x, bump(x, z), z]
            }) {
                mesh.nodes.push(p);
            }
            faces.push(Face::new(
                Family::Q8,
                &(first..first + 8).collect::<Vec<_>>(),
            ));
        }
    }
    let master = Master::new(&mesh, &faces);
    let mut tested = 0usize;
    for k in 0..200 {
        let t = k as f64;
        let p = [
            (t * 0.618_034).fract() * n as f64,
            0.5 + 2.0 * (t * 0.414_213).fract(),
            (t * 0.732_050).fract() * n as f64,
        ];
        let (f, c) = master.nearest(p).unwrap();
        let scan = (0..faces.len())
            .map(|g| closest(Family::Q8, &master.coords[g], p).d2)
            .fold(f64::INFINITY, f64::min);
        assert!(
            (c.d2 - scan).abs() <= 1e-12 * scan.max(1.0),
            "{p:?}: face {f}"
        );
        master.tree.nearest(p, |g| {
            tested += 1;
            closest(Family::Q8, &master.coords[g], p).d2
        });
    }
    // far fewer face tests than the scan's 144 a point
    println!("tree: {:.1} faces tested a point", tested as f64 / 200.0);
    assert!(tested < 200 * 40, "{tested}");
}

/// An interface model of one consistent spring of [`two_sides`] (the
/// slave face bowed, so the point's gap and normal are its own), with
/// friction.
fn model(gap: f64) -> (InterfaceModel, usize) {
    let (mesh, nm) = two_sides(0.01, 0.35, 0.45, 0.02);
    let (pairs, points) = node_to_surface(&mesh, "c", &nm, Weights::Consistent).unwrap();
    let im = InterfaceModel {
        name: "c".into(),
        body_a: 0,
        body_b: 1,
        law: crate::physics::contact::normal::power::new(0.001, 0.5).unwrap(),
        gap,
        gap_history: None,
        pairs,
        points,
        start_pressure: None,
        tangential: Some(TangentialLaw::new(0.9, 0.5, 0.5, 0.15, 1.0, 0.0, 0.625).unwrap()),
        scheme: FrictionScheme::ReturnMapping,
        node_dofs: NodeDofs::SOLID,
        moment_point: [0.0; 3],
    };
    (im, mesh.nodes.len())
}

#[test]
fn a_rigid_motion_of_both_sides_neither_closes_nor_slips() {
    let (im, nodes) = model(0.0);
    let rigid = |a: [f64; 3], w: [f64; 3]| -> Vec<f64> {
        let (mesh, _) = two_sides(0.01, 0.35, 0.45, 0.02);
        (0..nodes)
            .flat_map(|n| {
                let r = cross(w, mesh.nodes[n]);
                [a[0] + r[0], a[1] + r[1], a[2] + r[2]]
            })
            .collect()
    };
    for pt in &im.points {
        let g0 = segment_of(pt).gap;
        // a translation: nothing
        let [un, t1, t2] = im.point_kinematics_3d(pt, &rigid([0.01, -0.02, 0.005], [0.0; 3]), 0.0);
        assert!((un + g0).abs() < 1e-16 && t1.abs() < 1e-16 && t2.abs() < 1e-16);
        // a small rotation: u_B − u_A = ω × (x_B − x_A) = −g₀ ω × n, no
        // approach, a slip of g₀ ω × n (0 where the sides touch)
        let w = [1e-3, -2e-3, 1.5e-3];
        let [un, t1, t2] = im.point_kinematics_3d(pt, &rigid([0.0; 3], w), 0.0);
        let s = cross(w, pt.normal).map(|v| -g0 * v);
        assert!((un + g0).abs() < 1e-15, "{un} {g0}");
        assert!((t1 - dot(s, pt.tangent)).abs() < 1e-16);
        assert!((t2 - dot(s, pt.binormal())).abs() < 1e-16);
    }
}

#[test]
fn the_surface_point_tangent_is_the_derivative_of_its_residual() {
    let (im, nodes) = model(-0.012);
    let pt = &im.points[5];
    let dofs = im.point_dofs(pt);
    let nd = dofs.len();
    assert_eq!(nd, 3 * 16);
    // A pressed down into B and slid along x and z, each node differently
    let displacements = |s1: f64, s2: f64| -> Vec<f64> {
        let mut u = vec![0.0; 3 * nodes];
        for n in 0..nodes {
            let w = 1.0 + 0.01 * n as f64;
            if n >= nodes - 8 {
                u[3 * n] = s1 * w;
                u[3 * n + 1] = -1e-3 * w;
                u[3 * n + 2] = s2 * (1.0 - 0.03 * (n + 8 - nodes) as f64);
            } else {
                u[3 * n] = -0.3 * s1 * w;
                u[3 * n + 1] = 2e-4 * w;
            }
        }
        u
    };
    let eval = |u: &[f64], committed: &PointState| {
        let (mut r, mut k) = (vec![0.0; nd], vec![0.0; nd * nd]);
        let ev = im.eval_point_parts(pt, u, im.gap, committed, None, &mut r, Some(&mut k), true);
        (r, k, ev)
    };
    for (s1, s2, from) in [
        (1e-5, 2e-5, None),
        (2e-4, 1e-4, None),
        (3e-3, -4e-3, None),
        (3e-3, 2e-3, Some((-2e-3, 1e-3))),
    ] {
        let committed = from.map_or(PointState::default(), |(a, b)| {
            eval(&displacements(a, b), &PointState::default()).2.state
        });
        let u = displacements(s1, s2);
        let (r, k, ev) = eval(&u, &committed);
        assert!(ev.p_n > 0.0, "{}", ev.u_n);
        let scale = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let jac = fd::central_columns(&vec![1e-9; nd], |j, s| {
            let mut up = u.clone();
            up[dofs[j]] += s;
            eval(&up, &committed).0
        });
        let worst = fd::worst(&jac, |i, j| k[i * nd + j], fd::Scale::Absolute);
        assert!(
            worst.diff < 1e-5 * scale,
            "slip ({s1}, {s2}) from {from:?}: off by {worst} of {scale:e} ({:?})",
            ev.status
        );
        // the point's force on B balances the one on A, p_N a along n
        let force = |nodes: std::ops::Range<usize>| -> [f64; 3] {
            std::array::from_fn(|c| nodes.clone().map(|i| r[3 * i + c]).sum())
        };
        let (fa, fb) = (force(0..8), force(8..16));
        for c in 0..3 {
            assert!((fa[c] + fb[c]).abs() < 1e-12 * scale);
        }
        assert!((dot(fb, pt.normal) - pt.area * ev.p_n).abs() < 1e-12 * pt.area * ev.p_n);
    }
}
