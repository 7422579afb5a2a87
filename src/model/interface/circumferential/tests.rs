use super::super::{side, Coupling, FrictionScheme, Pair, Point, Segment, TangentialLaw};
use super::*;
use crate::input::mesh::NodeDofs;
use crate::numbers::fd;

/// A vertical interface at r = 20 (A left, B right: n = −x, t = +y) of three
/// coincident pairs, nodes A 0..3, B 3..6; one consistent point on it and
/// one node-to-segment point of the same nodes.
fn model(node_dofs: NodeDofs) -> InterfaceModel {
    let pairs = (0..3)
        .map(|i| Pair {
            a: i,
            b: 3 + i,
            x: [20.0, i as f64, 0.0],
            normal: [-1.0, 0.0, 0.0],
            area: 40.0,
            spring: None,
        })
        .collect();
    let shape = crate::physics::element::edge::shape(0.3);
    let coincident = Point {
        area: 55.0,
        normal: [-1.0, 0.1f64.sin(), 0.0],
        tangent: [0.1f64.sin(), 1.0, 0.0],
        coupling: Coupling::Coincident {
            pairs: side(&[0, 1, 2]),
            shape: side(&shape),
            len: 3,
        },
    };
    let segment = Point {
        coupling: Coupling::NodeToSegment {
            pair: 0,
            segment: Segment {
                a: side(&[0, 1, 2]),
                na: side(&shape),
                len_a: 3,
                b: side(&[3, 4, 5]),
                nb: side(&crate::physics::element::edge::shape(0.25)),
                len_b: 3,
                gap: 0.0,
                s: 0.6,
            },
        },
        ..coincident.clone()
    };
    InterfaceModel {
        name: "fit".into(),
        body_a: 0,
        body_b: 1,
        law: crate::physics::contact::normal::power::new(0.001, 0.5).unwrap(),
        gap: -0.004,
        gap_history: None,
        pairs,
        points: vec![coincident, segment],
        start_pressure: None,
        tangential: Some(TangentialLaw::new(0.9, 0.5, 0.5, 0.15, 1.0, 0.0, 0.625).unwrap()),
        scheme: FrictionScheme::ReturnMapping,
        node_dofs,
        moment_point: [0.0; 3],
    }
}

/// Displacements of the six nodes (3 dofs each): a closing approach, slip
/// along t scaled by `s1` and around the axis by `s2`.
fn displacements(s1: f64, s2: f64) -> Vec<f64> {
    let mut u = vec![0.0; 18];
    for i in 0..3 {
        let w = 1.0 + 0.2 * i as f64;
        u[3 * i] = 1e-3 * w; // A moves out (toward B): approach
        u[3 * i + 1] = -s1 * w;
        u[3 * i + 2] = -s2 * (1.0 - 0.1 * i as f64);
        u[9 + 3 * i] = -2e-4;
        u[9 + 3 * i + 1] = 0.3 * s1;
        u[9 + 3 * i + 2] = 0.5 * s2;
    }
    u
}

/// Evaluates a point from `committed` at `u` (gap of the model): residual
/// and tangent, the coupling kept in it or not.
fn eval(
    im: &InterfaceModel,
    pt: &Point,
    u: &[f64],
    committed: &PointState,
    with_coupling: bool,
) -> (Vec<f64>, Vec<f64>, PointEval) {
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

/// The committed state after a slip of (s1, s2) from rest.
fn after(im: &InterfaceModel, pt: &Point, s1: f64, s2: f64) -> PointState {
    eval(im, pt, &displacements(s1, s2), &PointState::default(), true)
        .2
        .state
}

#[test]
fn the_twisting_point_tangent_is_the_derivative_of_its_residual() {
    let im = model(NodeDofs::TWIST);
    for pt in &im.points {
        let dofs = im.point_dofs(pt);
        assert_eq!(dofs.len(), im.point_ndofs(pt));
        // stick, micro-slip and macro-slip, in both directions at once, from
        // rest and from a committed slip along another direction
        for (s1, s2, from) in [
            (1e-5, 2e-5, None),
            (2e-4, 1e-4, None),
            (3e-3, -4e-3, None),
            (3e-3, 2e-3, Some((-2e-3, 1e-3))),
        ] {
            let committed = from.map_or(PointState::default(), |(a, b)| after(&im, pt, a, b));
            let u = displacements(s1, s2);
            let (r, k, ev) = eval(&im, pt, &u, &committed, true);
            assert!(ev.p_n > 0.0);
            let nd = dofs.len();
            let scale = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let h = 1e-9;
            let jac = fd::central_columns(&vec![h; nd], |j, s| {
                let mut up = u.clone();
                up[dofs[j]] += s;
                eval(&im, pt, &up, &committed, true).0
            });
            let worst = fd::worst(&jac, |i, j| k[i * nd + j], fd::Scale::Absolute);
            assert!(
                worst.diff < 1e-5 * scale,
                "slip ({s1}, {s2}) from {from:?}: tangent off by {worst} of {scale:e} ({:?})",
                ev.status
            );
            // the residual is a (p_N g_N + p_T1 g_T1 + p_Tθ g_θ): the hoop
            // force on B's θ dofs sums to a p_Tθ
            let g = im.point_gradients(pt);
            let on_b: f64 = (0..nd).filter(|&i| g.h[i] > 0.0).map(|i| r[i]).sum();
            let wb: f64 = g.h.iter().filter(|&&w| w > 0.0).sum();
            assert!((on_b - pt.area * ev.state.p_h * wb).abs() <= 1e-12 * on_b.abs().max(1.0));
        }
    }
}

#[test]
fn the_split_tangent_plus_its_vector_coupling_is_the_whole() {
    let im = model(NodeDofs::TWIST);
    for pt in &im.points {
        let u = displacements(3e-3, -4e-3);
        let (_, whole, ev) = eval(&im, pt, &u, &PointState::default(), true);
        let (_, part, _) = eval(&im, pt, &u, &PointState::default(), false);
        assert!(ev.coupling != 0.0 && ev.coupling_hoop != 0.0);
        let g = im.point_gradients(pt);
        let nd = g.n.len();
        for i in 0..nd {
            let ui = ev.coupling * g.t[i] + ev.coupling_hoop * g.h[i];
            for j in 0..nd {
                let sum = part[i * nd + j] + ui * g.n[j];
                assert!((sum - whole[i * nd + j]).abs() <= 1e-9 * whole[i * nd + j].abs().max(1.0));
            }
        }
        // the split part is symmetric
        for i in 0..nd {
            for j in 0..i {
                let (a, b) = (part[i * nd + j], part[j * nd + i]);
                assert!((a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0));
            }
        }
    }
}

#[test]
fn without_hoop_slip_the_twisting_point_is_the_plane_point() {
    let (tw, plane) = (model(NodeDofs::TWIST), model(NodeDofs::PLANE));
    for (pt, pp) in tw.points.iter().zip(&plane.points) {
        let mut st_t = PointState::default();
        let mut st_p = PointState::default();
        for s1 in [1e-5, 2e-4, 3e-3, -1e-3, 4e-3] {
            let u3 = displacements(s1, 0.0);
            let u2: Vec<f64> = u3.chunks_exact(3).flat_map(|c| [c[0], c[1]]).collect();
            let (r3, k3, e3) = eval(&tw, pt, &u3, &st_t, true);
            let (r2, k2, e2) = eval(&plane, pp, &u2, &st_p, true);
            let (n3, n2) = (r3.len(), r2.len());
            assert_eq!(n3 / 3, n2 / 2);
            for a in 0..n2 {
                let ia = a / 2 * 3 + a % 2;
                assert_eq!(r3[ia], r2[a], "residual entry {a} at slip {s1}");
                for b in 0..n2 {
                    let ib = b / 2 * 3 + b % 2;
                    assert_eq!(k3[ia * n3 + ib], k2[a * n2 + b], "tangent ({a}, {b})");
                }
            }
            assert_eq!(e3.status, e2.status);
            assert_eq!(e3.coupling, e2.coupling);
            assert_eq!(e3.coupling_hoop, 0.0);
            assert_eq!((e3.state.p_t, e3.state.mu_f), (e2.state.p_t, e2.state.mu_f));
            assert_eq!(e3.state.slip2.u_p[0], e2.state.slip.u_p);
            assert_eq!(e3.state.slip2.kappa, e2.state.slip.kappa);
            (st_t, st_p) = (e3.state, e2.state);
        }
    }
}

#[test]
fn the_hoop_slip_is_b_minus_a_around_the_axis() {
    let im = model(NodeDofs::TWIST);
    let mut u = vec![0.0; 18];
    // B's nodes turned by 1e-3 mm, A's by −2e-3 mm: u_Tθ = 3e-3 everywhere
    for i in 0..3 {
        u[3 * i + 2] = -2e-3;
        u[9 + 3 * i + 2] = 1e-3;
    }
    for pt in &im.points {
        assert!((im.point_second_slip(pt, &u) - 3e-3).abs() < 1e-15);
    }
    assert_eq!(
        model(NodeDofs::PLANE).point_second_slip(&im.points[0], &u[..12]),
        0.0
    );
}
