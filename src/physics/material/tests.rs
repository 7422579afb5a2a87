//! Material-point checks: finite differences of the tangents, closed-form stress
//! paths, yield consistency, parameter validation.

use super::*;
use crate::numbers::fd;

fn mat(plane: Plane, h: f64) -> VonMises {
    VonMises::new(200000.0, 0.3, 250.0, h, plane).unwrap()
}

fn fd_check(m: &VonMises, committed: &PointState, eps: [f64; 3]) -> fd::Mismatch {
    let (_, c) = m.update(committed, &eps).unwrap();
    let scale = eps.iter().fold(1e-6f64, |a, v| a.max(v.abs()));
    let h = 1e-7 * scale;
    let cmax = c.amax();
    let jac = fd::central_jacobian(
        |e| m.update(committed, e.try_into().unwrap()).unwrap().0.stress[..3].to_vec(),
        &eps,
        h,
    );
    fd::worst(&jac, |i, j| c[(i, j)], fd::Scale::Of(cmax))
}

#[test]
fn consistent_tangent_matches_finite_differences() {
    let paths = [
        [1e-4, -2e-5, 3e-5],       // elastic
        [1.6e-3, -0.3e-3, 0.2e-3], // just past yield
        [8e-3, -1e-3, 6e-3],       // deep plastic, shear
        [-5e-3, 4e-3, -2e-3],      // mixed signs
        [3e-3, 3e-3, 0.0],         // equibiaxial
    ];
    for plane in [Plane::Stress, Plane::Strain] {
        for h in [0.0, 2000.0, 50000.0] {
            let m = mat(plane, h);
            // from a virgin state and from a committed plastic state
            let pre = m
                .update(&PointState::default(), &[2e-3, 0.0, 1e-3])
                .unwrap()
                .0;
            for c in [PointState::default(), pre] {
                for eps in paths {
                    let e = fd_check(&m, &c, eps);
                    assert!(e.ratio < 1e-6, "{plane:?} H={h} eps={eps:?}: FD error {e}");
                }
            }
        }
    }
}

#[test]
fn yield_consistency_and_plane_stress_sigma_zz() {
    for plane in [Plane::Stress, Plane::Strain] {
        let m = mat(plane, 3000.0);
        for eps in [[5e-3, -1e-3, 2e-3], [-4e-3, -4e-3, 1e-2], [1e-2, 2e-3, 0.0]] {
            let (s, _) = m.update(&PointState::default(), &eps).unwrap();
            assert!(s.yielding);
            let q = VonMises::equivalent_stress(&s.stress);
            assert!(
                (q - m.current_yield(&s)).abs() < 1e-10 * q,
                "{plane:?}: {q} vs {}",
                m.current_yield(&s)
            );
            if plane == Plane::Stress {
                assert_eq!(s.stress[3], 0.0);
            }
            let ep = s.plastic_strain;
            assert!(
                (ep[0] + ep[1] + ep[3]).abs() < 1e-15,
                "plastic flow is isochoric"
            );
        }
    }
}

#[test]
fn continuum_tangent_is_the_limit_of_the_consistent_one() {
    for plane in [Plane::Stress, Plane::Strain] {
        let m = mat(plane, 2000.0);
        let eps = [3e-3, -1e-3, 1e-3];
        let (c, _) = m.update(&PointState::default(), &eps).unwrap();
        let cont = m.continuum_tangent(&c);
        // a tiny further strain along the same direction: Δγ → 0
        let e2 = [
            eps[0] * (1.0 + 1e-9),
            eps[1] * (1.0 + 1e-9),
            eps[2] * (1.0 + 1e-9),
        ];
        let (_, alg) = m.update(&c, &e2).unwrap();
        assert!(
            (cont - alg).amax() < 1e-5 * cont.amax(),
            "{plane:?}:\n{cont}\n{alg}"
        );
    }
}

/// Drives σyy = σxy = 0 with εxx prescribed (plane stress uniaxial tension).
fn uniaxial_plane_stress(m: &VonMises, exx: f64) -> PointState {
    let mut eps = [exx, -m.poisson * exx, 0.0];
    for _ in 0..50 {
        let (s, c) = m.update(&PointState::default(), &eps).unwrap();
        if s.stress[1].abs() < 1e-10 * m.yield_stress {
            return s;
        }
        eps[1] -= s.stress[1] / c[(1, 1)];
    }
    panic!("uniaxial iteration did not converge");
}

#[test]
fn plane_stress_uniaxial_tension_follows_the_bilinear_curve() {
    let (e, h, sy) = (200000.0, 2000.0, 250.0);
    let m = mat(Plane::Stress, h);
    for exx in [0.5 * sy / e, 3e-3, 1e-2] {
        let s = uniaxial_plane_stress(&m, exx);
        let ey = sy / e;
        let exact = if exx <= ey {
            e * exx
        } else {
            sy + e * h / (e + h) * (exx - ey)
        };
        assert!(
            (s.stress[0] - exact).abs() < 1e-8 * exact,
            "εxx = {exx}: {} vs {exact}",
            s.stress[0]
        );
        if exx > ey {
            assert!((s.stress[0] - (sy + h * s.peeq)).abs() < 1e-8 * sy);
        }
    }
}

#[test]
fn plane_strain_pure_shear_yields_at_k_and_stays_there_when_perfectly_plastic() {
    let m = mat(Plane::Strain, 0.0);
    let g = m.shear_modulus();
    let k = 250.0 / 3f64.sqrt();
    let gamma_y = k / g;
    let (s, _) = m
        .update(&PointState::default(), &[0.0, 0.0, 0.9 * gamma_y])
        .unwrap();
    assert!((s.stress[2] - 0.9 * k).abs() < 1e-9 * k && !s.yielding);
    let (s, _) = m
        .update(&PointState::default(), &[0.0, 0.0, 5.0 * gamma_y])
        .unwrap();
    assert!((s.stress[2] - k).abs() < 1e-9 * k && s.yielding);
    assert!(s.stress[0].abs() < 1e-9 && s.stress[3].abs() < 1e-9);
}

#[test]
fn plane_strain_uniaxial_strain_onset_of_yield() {
    // εxx only: σyy = σzz = ν/(1−ν) σxx, yield when σxx − σyy = σ_Y
    let m = mat(Plane::Strain, 0.0);
    let (e, nu) = (m.young, m.poisson);
    let c11 = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let onset = 250.0 / (c11 * (1.0 - nu / (1.0 - nu)));
    let (s, _) = m
        .update(&PointState::default(), &[0.999 * onset, 0.0, 0.0])
        .unwrap();
    assert!(!s.yielding);
    let (s, _) = m
        .update(&PointState::default(), &[1.001 * onset, 0.0, 0.0])
        .unwrap();
    assert!(s.yielding);
    // beyond yield, perfectly plastic: σxx − σyy stays σ_Y, mean stress grows with K
    let (s, _) = m
        .update(&PointState::default(), &[5.0 * onset, 0.0, 0.0])
        .unwrap();
    assert!((s.stress[0] - s.stress[1] - 250.0).abs() < 1e-9 * 250.0);
    let mean = (s.stress[0] + s.stress[1] + s.stress[3]) / 3.0;
    assert!((mean - m.bulk_modulus() * 5.0 * onset).abs() < 1e-9 * mean);
}

#[test]
fn one_radial_step_equals_many_small_ones_in_plane_strain() {
    let m = mat(Plane::Strain, 5000.0);
    let dir = [2e-3, -1.5e-3, 1e-3];
    let (big, _) = m.update(&PointState::default(), &dir).unwrap();
    // proportional path from the yield point: deviatoric direction stays fixed
    let mut st = PointState::default();
    for k in 1..=40 {
        let f = k as f64 / 40.0;
        st = m
            .update(&st, &[dir[0] * f, dir[1] * f, dir[2] * f])
            .unwrap()
            .0;
    }
    for i in 0..4 {
        assert!(
            (big.stress[i] - st.stress[i]).abs() < 1e-8 * 250.0,
            "{:?} vs {:?}",
            big.stress,
            st.stress
        );
    }
}

#[test]
fn bad_parameters_are_named_and_infinite_yield_is_elastic() {
    let ps = Plane::Stress;
    assert!(VonMises::new(-1.0, 0.3, 1.0, 0.0, ps)
        .unwrap_err()
        .contains("young"));
    assert!(VonMises::new(1.0, 0.5, 1.0, 0.0, ps)
        .unwrap_err()
        .contains("poisson"));
    assert!(VonMises::new(1.0, -1.0, 1.0, 0.0, ps)
        .unwrap_err()
        .contains("poisson"));
    assert!(VonMises::new(f64::NAN, 0.3, 1.0, 0.0, ps).is_err());
    assert!(VonMises::new(1.0, 0.3, 0.0, 0.0, ps)
        .unwrap_err()
        .contains("yield_stress"));
    assert!(VonMises::new(1.0, 0.3, 1.0, -1.0, ps)
        .unwrap_err()
        .contains("hardening"));
    for plane in [Plane::Stress, Plane::Strain] {
        let m = VonMises::new(1000.0, 0.3, f64::INFINITY, 0.0, plane).unwrap();
        let (s, c) = m
            .update(&PointState::default(), &[10.0, -3.0, 4.0])
            .unwrap();
        assert!(!s.yielding && s.stress.iter().all(|v| v.is_finite()));
        assert!((c - m.elastic_matrix()).amax() < 1e-12 * c.amax());
    }
}

/// Worst relative difference between the axisymmetric algorithmic tangent
/// (4×4, rr zz rz θθ) and central differences of the stress.
fn fd_check_axisymmetric(m: &VonMises, committed: &PointState, eps: [f64; 4]) -> fd::Mismatch {
    let (_, c) = m.update_axisymmetric(committed, &eps);
    let scale = eps.iter().fold(1e-6f64, |a, v| a.max(v.abs()));
    let h = 1e-7 * scale;
    let cmax = c.amax();
    let jac = fd::central_jacobian(
        |e| {
            m.update_axisymmetric(committed, e.try_into().unwrap())
                .0
                .stress[..4]
                .to_vec()
        },
        &eps,
        h,
    );
    fd::worst(&jac, |i, j| c[(i, j)], fd::Scale::Of(cmax))
}

#[test]
fn axisymmetric_consistent_tangent_matches_finite_differences() {
    let paths = [
        [1e-4, -2e-5, 3e-5, 4e-5],          // elastic
        [1.6e-3, -0.3e-3, 0.2e-3, -0.4e-3], // just past yield
        [8e-3, -1e-3, 6e-3, 2e-3],          // deep plastic, shear
        [-5e-3, 4e-3, -2e-3, 3e-3],         // mixed signs
        [0.0, 0.0, 0.0, 6e-3],              // hoop strain alone
    ];
    let mut plastic = 0;
    for h in [0.0, 2000.0, 50000.0] {
        let m = mat(Plane::Axisymmetric, h);
        let pre = m
            .update_axisymmetric(&PointState::default(), &[2e-3, 0.0, 1e-3, -1e-3])
            .0;
        for c in [PointState::default(), pre] {
            for eps in paths {
                plastic += usize::from(m.update_axisymmetric(&c, &eps).0.yielding);
                let e = fd_check_axisymmetric(&m, &c, eps);
                assert!(e.ratio < 1e-6, "H={h} eps={eps:?}: FD error {e}");
            }
        }
    }
    assert!(
        plastic >= 18,
        "only {plastic} of the checked updates were plastic"
    );
}

#[test]
fn axisymmetric_return_with_zero_hoop_strain_is_plane_strain() {
    let (ps, ax) = (mat(Plane::Strain, 3000.0), mat(Plane::Axisymmetric, 3000.0));
    for eps in [[5e-3, -1e-3, 2e-3], [-4e-3, -4e-3, 1e-2], [1e-4, 0.0, 0.0]] {
        let (a, ca) = ps.update(&PointState::default(), &eps).unwrap();
        let (b, cb) =
            ax.update_axisymmetric(&PointState::default(), &[eps[0], eps[1], eps[2], 0.0]);
        for i in 0..4 {
            assert!(
                (a.stress[i] - b.stress[i]).abs() < 1e-12 * 250.0,
                "{a:?} {b:?}"
            );
            assert!((a.plastic_strain[i] - b.plastic_strain[i]).abs() < 1e-15);
        }
        assert_eq!(a.yielding, b.yielding);
        for i in 0..3 {
            for j in 0..3 {
                assert!((ca[(i, j)] - cb[(i, j)]).abs() < 1e-10 * ca.amax());
            }
        }
    }
}

#[test]
fn axisymmetric_yield_consistency_elastic_state_and_continuum_limit() {
    let m = mat(Plane::Axisymmetric, 3000.0);
    let eps = [3e-3, -1e-3, 1e-3, 2e-3];
    let (s, _) = m.update_axisymmetric(&PointState::default(), &eps);
    assert!(s.yielding);
    let q = VonMises::equivalent_stress(&s.stress);
    assert!((q - m.current_yield(&s)).abs() < 1e-10 * q);
    let ep = s.plastic_strain;
    assert!(
        (ep[0] + ep[1] + ep[3]).abs() < 1e-15,
        "plastic flow is isochoric"
    );
    // the elastic law from the returned plastic strain gives the returned stress
    let e = m.elastic_state_axisymmetric(&s, &eps);
    for i in 0..4 {
        assert!((e.stress[i] - s.stress[i]).abs() < 1e-9 * 250.0);
    }
    // C_ep (3.13) is the limit of the algorithmic tangent as Δγ → 0
    let cont = m.continuum_tangent_4(&s);
    let e2 = eps.map(|v| v * (1.0 + 1e-9));
    let (_, alg) = m.update_axisymmetric(&s, &e2);
    assert!((cont - alg).amax() < 1e-5 * cont.amax(), "\n{cont}\n{alg}");
    // elastic 4×4 D: Hooke's law in 3D
    let d = m.elastic_matrix_4();
    let (e_, nu) = (m.young, m.poisson);
    let c11 = e_ * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let c12 = e_ * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    for (i, j, v) in [
        (0, 0, c11),
        (3, 3, c11),
        (0, 3, c12),
        (1, 3, c12),
        (2, 2, m.shear_modulus()),
        (2, 3, 0.0),
    ] {
        assert!(
            (d[(i, j)] - v).abs() < 1e-10 * c11,
            "D[{i},{j}] = {} vs {v}",
            d[(i, j)]
        );
    }
}
