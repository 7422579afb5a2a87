use super::super::{side, FrictionScheme, PointEval};
use super::*;
use crate::input::mesh::NodeDofs;
use crate::numbers::fd;
use crate::physics::contact::{PointState, TangentialLaw};

/// A flat 8-node face, a × b, tilted in space: the rows of `q8::NODE_XI`
/// mapped by origin + ξ a/2 u + η b/2 v.
fn tilted_face(a: f64, b: f64) -> (Vec<[f64; 3]>, [f64; 3]) {
    let s = 0.6f64;
    let (u, v) = (
        [s.cos(), s.sin(), 0.0],
        [-s.sin() * 0.8, s.cos() * 0.8, 0.6],
    );
    let origin = [1.0, -2.0, 0.5];
    let x = (0..8)
        .map(|k| {
            let [xi, eta] = crate::physics::element::q8::NODE_XI[k];
            std::array::from_fn(|c| origin[c] + 0.5 * a * xi * u[c] + 0.5 * b * eta * v[c])
        })
        .collect();
    (x, cross(u, v))
}

#[test]
fn lumped_areas_are_positive_and_sum_to_the_face() {
    let (a, b) = (3.0, 2.0);
    let (x, n) = tilted_face(a, b);
    let w = lumped(Family::Q8, &x);
    let total: f64 = w.iter().map(|p| p.0).sum();
    assert!((total - a * b).abs() < 1e-12 * a * b, "{total}");
    // the scaled diagonal of a flat serendipity face (on [−1, 1]²,
    // ∫N_c² = 2/15 and ∫N_m² = 32/45): corners 3/76, midsides 4/19 of the area
    for (k, (wk, nk)) in w.iter().enumerate() {
        let share = if k < 4 { 3.0 / 76.0 } else { 4.0 / 19.0 };
        assert!((wk - share * a * b).abs() < 1e-12, "node {k}: {wk}");
        assert!((0..3).all(|c| (nk[c] - n[c]).abs() < 1e-12), "{nk:?} {n:?}");
    }
    // a flat 6-node triangle: corners 1/19, midsides 16/57 of its area
    let t = [
        [0.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [0.0, 3.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.5, 0.0],
        [0.0, 1.5, 0.0],
    ];
    let w = lumped(Family::T6, &t);
    for (k, (wk, nk)) in w.iter().enumerate() {
        let share = if k < 3 { 1.0 / 19.0 } else { 16.0 / 57.0 };
        assert!((wk - share * 6.0).abs() < 1e-12, "node {k}: {wk}");
        assert!((nk[2] - 1.0).abs() < 1e-12);
    }
}

#[test]
fn the_consistent_rule_integrates_the_face() {
    let (x, n) = tilted_face(3.0, 2.0);
    let (mut area, mut moment) = (0.0, [0.0; 3]);
    for (xi, w) in face_rule(Family::Q8) {
        let (shape, nk, da) = geometry(Family::Q8, &x, xi);
        area += w * da;
        assert!((0..3).all(|c| (nk[c] - n[c]).abs() < 1e-12));
        let p: [f64; 3] = std::array::from_fn(|c| (0..8).map(|a| shape[a] * x[a][c]).sum());
        for c in 0..3 {
            moment[c] += w * da * p[c];
        }
    }
    assert!((area - 6.0).abs() < 1e-12);
    // the centroid is the origin
    let centroid = moment.map(|m| m / area);
    for (c, want) in [1.0, -2.0, 0.5].iter().enumerate() {
        assert!((centroid[c] - want).abs() < 1e-12, "{centroid:?}");
    }
}

#[test]
fn the_slip_frame_is_orthonormal_and_the_plane_tangent_on_a_swept_face() {
    for n in [
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.6, 0.0, 0.8],
        [0.0, 0.0, -1.0],
        [0.1, 0.2, 0.97467943],
    ] {
        let n = unit(n);
        let t = frame(n);
        assert!(dot(t, n).abs() < 1e-15 && (dot(t, t) - 1.0).abs() < 1e-15);
        if n[2] == 0.0 {
            // the plane interface's (n_y, −n_x)
            assert_eq!(t, [n[1], -n[0], 0.0]);
        }
    }
}

/// Two coincident 8-node faces on the plane y = 0 (A above): nodes A 0..8,
/// B 8..16; one consistent point of the face at ξ.
fn model(xi: [f64; 2]) -> InterfaceModel {
    let x: Vec<[f64; 3]> = (0..8)
        .map(|k| {
            let [s, t] = crate::physics::element::q8::NODE_XI[k];
            [2.0 + 1.5 * s, 0.0, -1.0 - 1.0 * t + 0.1 * s * t]
        })
        .collect();
    // walked so that ∂x/∂ξ × ∂x/∂η is +y: x along ξ, −z along η
    let (shape, n, da) = geometry(Family::Q8, &x, xi);
    assert!((n[1] - 1.0).abs() < 1e-12, "{n:?}");
    let pairs = (0..8)
        .map(|i| Pair {
            a: i,
            b: 8 + i,
            x: x[i],
            normal: n,
            area: 0.5,
            spring: None,
        })
        .collect();
    let ids: Vec<usize> = (0..8).collect();
    let point = Point {
        area: 0.7 * da,
        normal: n,
        tangent: frame(n),
        coupling: Coupling::Coincident {
            pairs: side(&ids),
            shape,
            len: 8,
        },
    };
    InterfaceModel {
        name: "face".into(),
        body_a: 0,
        body_b: 1,
        law: crate::physics::contact::normal::power::new(0.001, 0.5).unwrap(),
        gap: -0.004,
        gap_history: None,
        pairs,
        points: vec![point],
        start_pressure: None,
        tangential: Some(TangentialLaw::new(0.9, 0.5, 0.5, 0.15, 1.0, 0.0, 0.625).unwrap()),
        scheme: FrictionScheme::ReturnMapping,
        node_dofs: NodeDofs::SOLID,
        moment_point: [0.0; 3],
    }
}

/// The 16 nodes' displacements: A pressed down (−y) into B, slid along x
/// by `s1` and along z by `s2`, each node a little differently.
fn displacements(s1: f64, s2: f64) -> Vec<f64> {
    let mut u = vec![0.0; 48];
    for i in 0..8 {
        let w = 1.0 + 0.1 * i as f64;
        u[3 * i] = s1 * w;
        u[3 * i + 1] = -1e-3 * w;
        u[3 * i + 2] = s2 * (1.0 - 0.05 * i as f64);
        u[24 + 3 * i + 1] = 2e-4;
        u[24 + 3 * i] = -0.3 * s1;
    }
    u
}

fn eval(
    im: &InterfaceModel,
    u: &[f64],
    committed: &PointState,
    with_coupling: bool,
) -> (Vec<f64>, Vec<f64>, PointEval) {
    let pt = &im.points[0];
    let nd = im.point_ndofs(pt);
    let (mut r, mut k) = (vec![0.0; nd], vec![0.0; nd * nd]);
    let ev = im.eval_point_parts(
        pt,
        u,
        im.gap,
        committed,
        None,
        &mut r,
        Some(&mut k),
        with_coupling,
    );
    (r, k, ev)
}

#[test]
fn a_rigid_motion_of_both_faces_neither_closes_nor_slips() {
    let im = model([0.3, -0.6]);
    let pt = &im.points[0];
    let mut u = vec![0.0; 48];
    for i in 0..16 {
        // a translation and a small rotation about the z axis through (2, 0, −1)
        let x = im.pairs[i % 8].x;
        let w = 1e-4;
        u[3 * i] = 0.01 - w * x[1];
        u[3 * i + 1] = -0.02 + w * (x[0] - 2.0);
        u[3 * i + 2] = 0.005;
    }
    let [un, t1, t2] = im.point_kinematics_3d(pt, &u, 0.0);
    assert!(un.abs() < 1e-17 && t1.abs() < 1e-17 && t2.abs() < 1e-17);
    // A moved down by d: an approach d, whatever it slides
    for i in 0..8 {
        u[3 * i + 1] -= 1e-3;
        u[3 * i] += 2e-3;
        u[3 * i + 2] -= 5e-4;
    }
    let [un, t1, t2] = im.point_kinematics_3d(pt, &u, 0.0);
    assert!((un - 1e-3).abs() < 1e-15, "{un}");
    // B − A along t₁ = (n_y, −n_x, 0) = +x and t₂ = n × t₁ = −z
    assert!(
        (t1 + 2e-3).abs() < 1e-15 && (t2 + 5e-4).abs() < 1e-15,
        "{t1} {t2}"
    );
}

#[test]
fn the_face_point_tangent_is_the_derivative_of_its_residual() {
    let im = model([0.3, -0.6]);
    let pt = &im.points[0];
    let dofs = im.point_dofs(pt);
    assert_eq!(dofs.len(), 48);
    for (s1, s2, from) in [
        (1e-5, 2e-5, None),
        (2e-4, 1e-4, None),
        (3e-3, -4e-3, None),
        (3e-3, 2e-3, Some((-2e-3, 1e-3))),
    ] {
        let committed = from.map_or(PointState::default(), |(a, b)| {
            eval(&im, &displacements(a, b), &PointState::default(), true)
                .2
                .state
        });
        let u = displacements(s1, s2);
        let (r, k, ev) = eval(&im, &u, &committed, true);
        assert!(ev.p_n > 0.0);
        let scale = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let jac = fd::central_columns(&[1e-9; 48], |j, s| {
            let mut up = u.clone();
            up[dofs[j]] += s;
            eval(&im, &up, &committed, true).0
        });
        let worst = fd::worst(&jac, |i, j| k[i * 48 + j], fd::Scale::Absolute);
        assert!(
            worst.diff < 1e-5 * scale,
            "slip ({s1}, {s2}) from {from:?}: off by {worst} of {scale:e} ({:?})",
            ev.status
        );
        // the residual is the point's force: p_N n a on B, −… on A, in
        // balance, and along n its size is a p_N
        let force_b: [f64; 3] = std::array::from_fn(|c| (8..16).map(|i| r[3 * i + c]).sum());
        let force_a: [f64; 3] = std::array::from_fn(|c| (0..8).map(|i| r[3 * i + c]).sum());
        for c in 0..3 {
            assert!((force_a[c] + force_b[c]).abs() < 1e-12 * scale);
        }
        assert!((dot(force_b, pt.normal) - pt.area * ev.p_n).abs() < 1e-12 * pt.area * ev.p_n);
    }
}
