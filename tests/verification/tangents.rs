//! Finite-difference checks of every analytic tangent: the solid element in both
//! plane states (elastic and plastic Gauss points), the interface points (lumped
//! and consistent, every normal law) and the assembled residual of a punch model.

use crate::common;
use asperity::input::case::Method;
use asperity::numbers::fd;
use asperity::physics::element::element_forces;
use asperity::physics::element::q8;
use asperity::physics::element::solid::{ElementGeometry, Response, Tangent};
use asperity::physics::material::{Plane, PointMaterials, PointState, VonMises};
use asperity::solve::State;

fn distorted() -> [[f64; 2]; 8] {
    let c = [[0.0, 0.0], [2.0, 0.2], [2.3, 1.9], [-0.2, 1.6]];
    let mut x = [[0.0; 2]; 8];
    x[..4].copy_from_slice(&c);
    for (k, (a, b)) in [(0, 1), (1, 2), (2, 3), (3, 0)].iter().enumerate() {
        x[4 + k] = [
            (c[*a][0] + c[*b][0]) / 2.0 + 0.05,
            (c[*a][1] + c[*b][1]) / 2.0 - 0.03,
        ];
    }
    x
}

/// The distorted element moved to x ≥ `r0` (its left corner at x = r0): an
/// axisymmetric element (r0 = 0: touching the axis with one corner).
fn distorted_at(r0: f64) -> [[f64; 2]; 8] {
    let mut x = distorted();
    for p in &mut x {
        p[0] += r0 + 0.2;
    }
    x
}

fn check_element(plane: Plane, scale: f64, hardening: f64) {
    let geom = ElementGeometry::new(
        asperity::physics::element::family::Family::Q8,
        &distorted(),
        &q8::gauss_3x3(),
        1.5,
    )
    .unwrap();
    check_element_geometry(plane, &geom, scale, hardening);
}

/// With no thermal strain and with one of the strains' size (a heated body:
/// the eigenstrain moves the return's point, not the tangent's form), with
/// one material for the element and with one per Gauss point (a body whose
/// E and σ_Y follow a temperature field: each point's tangent is its own
/// material's, ΔT prescribed adds no term).
fn check_element_geometry(plane: Plane, geom: &ElementGeometry, scale: f64, hardening: f64) {
    for thermal in [0.0, 0.4 * scale] {
        for per_point in [false, true] {
            check_element_thermal(plane, geom, (scale, hardening), thermal, per_point);
        }
    }
}

fn check_element_thermal(
    plane: Plane,
    geom: &ElementGeometry,
    (scale, hardening): (f64, f64),
    thermal: f64,
    per_point: bool,
) {
    let geom = geom.clone();
    let one = VonMises::new(200000.0, 0.3, 250.0, hardening, plane).unwrap();
    // per point: E and σ_Y falling from point to point (a hotter point is
    // softer and yields sooner), so some points yield and others do not
    let each: Vec<VonMises> = (0..9)
        .map(|ip| {
            let k = 1.0 - 0.06 * ip as f64;
            VonMises::new(200000.0 * k, 0.3, 250.0 * k * k, hardening, plane).unwrap()
        })
        .collect();
    let mat = if per_point {
        PointMaterials::PerPoint(&each)
    } else {
        PointMaterials::Uniform(&one)
    };
    // a thermal strain that varies from point to point (a temperature field)
    let thermal: [f64; 9] = std::array::from_fn(|ip| thermal * (1.0 + 0.1 * ip as f64));
    let thermal = &thermal;
    let mut ue = [0.0; 16];
    for (i, u) in ue.iter_mut().enumerate() {
        *u = scale * ((i as f64 * 0.77).sin() + 0.3 * (i as f64 * 1.3).cos());
    }
    // a committed plastic state: load once, then evaluate around a further strain
    let committed0 = vec![PointState::default(); 9];
    let mut committed = vec![PointState::default(); 9];
    let (mut fe, mut ke) = ([0.0; 16], [0.0; 256]);
    let half: [f64; 16] = std::array::from_fn(|i| 0.6 * ue[i]);
    element_forces(
        &geom,
        mat,
        thermal,
        &half,
        &committed0,
        &mut committed,
        Response::Plastic,
        None,
        &mut fe,
        &mut ke,
    )
    .unwrap();
    let mut trial = committed.clone();
    element_forces(
        &geom,
        mat,
        thermal,
        &ue,
        &committed,
        &mut trial,
        Response::Plastic,
        Some(Tangent::Consistent),
        &mut fe,
        &mut ke,
    )
    .unwrap();
    let plastic = trial.iter().filter(|g| g.yielding).count();
    if per_point {
        eprintln!("{plane:?} scale {scale} H {hardening}: {plastic} of 9 points plastic, materials per point");
    }
    let h = 1e-7 * scale;
    let kmax = ke.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let jac = fd::central_jacobian(
        |u| {
            let mut f = [0.0; 16];
            element_forces(
                &geom,
                mat,
                thermal,
                u,
                &committed,
                &mut trial.clone(),
                Response::Plastic,
                None,
                &mut f,
                &mut ke.clone(),
            )
            .unwrap();
            f.to_vec()
        },
        &ue,
        h,
    );
    let worst = fd::worst(&jac, |i, j| ke[i * 16 + j], fd::Scale::Of(kmax));
    assert!(
        worst.ratio < 1e-6,
        "{plane:?} scale {scale} H {hardening} α ΔT {:?} per point {per_point}: {plastic} plastic points, FD error {worst}",
        thermal[0]
    );
}

#[test]
fn axisymmetric_element_tangent_matches_finite_differences() {
    let section = asperity::physics::element::Section {
        axisymmetric: true,
        thickness: 1.0,
    };
    for r0 in [0.0, 0.5, 40.0] {
        let x = distorted_at(r0);
        for rule in [q8::gauss_3x3(), q8::gauss_2x2()] {
            let geom = ElementGeometry::with_section(
                asperity::physics::element::family::Family::Q8,
                &x,
                &rule,
                &section,
            )
            .unwrap();
            check_element_geometry(Plane::Axisymmetric, &geom, 1e-5 * (1.0 + r0), 2000.0);
            check_element_geometry(Plane::Axisymmetric, &geom, 2e-3 * (1.0 + r0), 2000.0);
            check_element_geometry(Plane::Axisymmetric, &geom, 2e-3 * (1.0 + r0), 0.0);
        }
    }
}

#[test]
fn solid_element_tangent_matches_finite_differences() {
    for plane in [Plane::Stress, Plane::Strain] {
        check_element(plane, 1e-5, 2000.0); // elastic
        check_element(plane, 2e-3, 2000.0); // plastic, hardening
        check_element(plane, 2e-3, 0.0); // plastic, perfectly plastic
    }
}

const PUNCH: &str = include_str!("../../cases/punch-plane-stress/case.toml");
/// Normal law plus the Fig. 7c tangential law (unsymmetric point tangent).
const FRICTION: &str = "law = \"power\"\nc_n = 0.001\nm = 0.5\n[interface.contact.tangential]\nr = 0.9\ns = 0.5\nkp_ratio = 0.05\nmu = 0.2\nbeta = 0.2\nn = 275.0";

#[test]
fn interface_point_tangents_match_finite_differences() {
    for (law, weights) in [
        ("law = \"power\"\nc_n = 0.001\nm = 0.5", "lumped"),
        ("law = \"power\"\nc_n = 0.001\nm = 0.5", "consistent"),
        ("law = \"power\"\nc_n = 0.002\nm = 0.3", "consistent"),
        ("law = \"exponential\"\na = 0.8\nb = 150.0", "lumped"),
        (
            "law = \"linear\"\nc_n = 0.001\nm = 0.5\nslope = 1e-5\np_c = 10.0",
            "consistent",
        ),
        (FRICTION, "lumped"),
    ] {
        let text = PUNCH.replace("law = \"power\"\nc_n = 0.001          # mm/MPa^m: 14 µm of approach at 200 MPa\nm = 0.5", &format!("weights = \"{weights}\"\n{law}"));
        assert!(text.contains(weights), "case text substitution failed");
        let model = common::model(&text);
        let im = &model.interfaces[0];
        let mut u = vec![0.0; model.mesh.num_dofs()];
        for (i, v) in u.iter_mut().enumerate() {
            *v = 0.004 * ((i as f64 * 0.37).sin() + 0.8);
        }
        // push the punch down so most points are closed, some open
        for pr in &im.pairs {
            u[2 * pr.a + 1] -= 0.01 * (1.0 + (pr.x[0] * 0.7).sin());
        }
        for pt in &im.points {
            let nd = pt.ndofs();
            let dofs = im.point_dofs(pt);
            let (mut r, mut k) = (vec![0.0; nd], vec![0.0; nd * nd]);
            let ev = im.eval_point(pt, &u, &Default::default(), None, &mut r, Some(&mut k));
            if ev.u_n.abs() < 1e-6 {
                continue; // kink of the linear law at zero approach
            }
            let kmax = k.iter().fold(1e-30f64, |a, v| a.max(v.abs()));
            let h = 1e-9;
            // a repeated dof (lumped points list each pair once) appears once here
            let jac = fd::central_columns(&vec![h; dofs.len()], |j, s| {
                let mut up = u.clone();
                up[dofs[j]] += s;
                let mut rp = vec![0.0; nd];
                im.eval_point(pt, &up, &Default::default(), None, &mut rp, None);
                rp
            });
            let worst = fd::worst(&jac, |i, j| k[i * nd + j], fd::Scale::Of(kmax));
            assert!(
                worst.ratio < 1e-5,
                "{law} {weights}: point u_n={} {worst}",
                ev.u_n,
            );
        }
    }
}

#[test]
fn assembled_tangent_matches_finite_differences_of_the_residual() {
    let friction = include_str!("../../cases/punch-friction-b/case.toml");
    for (plane, base) in [("stress", PUNCH), ("strain", PUNCH), ("stress", friction)] {
        let text = base.replace("plane = \"stress\"", &format!("plane = \"{plane}\""));
        let model = common::model(&text);
        let mut engine = asperity::app::driver::serial_engine(
            &model,
            Method::FullNewton,
            asperity::threads::available(),
        )
        .unwrap();
        let committed = State::initial(&model);
        // a converged plastic state to linearize around: solve to a high load
        let (state, _) = engine.step(&committed, 1.0, Response::Plastic).unwrap();
        assert!(
            state.gauss.iter().any(|g| g.yielding),
            "{plane}: no plastic point to test"
        );
        let mut u = state.u.clone();
        for (i, v) in u.iter_mut().enumerate() {
            *v *= 1.0 + 1e-3 * (i as f64).sin();
        }
        engine.linearize(&committed, &u, 1.0).unwrap();
        let vals = engine.backend.matrix_values().unwrap().to_vec();
        let pattern = &model.pattern();
        let kmax = vals.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        // check a spread of columns, including dofs at the interface
        let free: Vec<usize> = (0..u.len())
            .filter(|&d| model.dofs.equation(d).is_some())
            .collect();
        let picks: Vec<usize> = (0..free.len())
            .step_by(free.len() / 23 + 1)
            .chain(
                model.interfaces[0]
                    .pairs
                    .iter()
                    .flat_map(|p| [2 * p.a + 1, 2 * p.b + 1])
                    .filter_map(|d| model.dofs.equation(d))
                    .take(6),
            )
            .collect();
        let h = 1e-8 * u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        // rows: the free dofs; columns: the picked ones
        let jac = fd::central_columns(&vec![h; picks.len()], |j, s| {
            let mut up = u.clone();
            up[free[picks[j]]] += s;
            let r = engine.linearize(&committed, &up, 1.0).unwrap();
            free.iter().map(|&d| r[d]).collect()
        });
        let cols: Vec<Vec<f64>> = picks
            .iter()
            .map(|&c| {
                let mut col = vec![0.0; free.len()];
                for k in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
                    col[pattern.row_idx[k] as usize] = vals[k];
                }
                col
            })
            .collect();
        let worst = fd::worst(&jac, |row, j| cols[j][row], fd::Scale::Of(kmax));
        assert!(
            worst.ratio < 1e-6,
            "{plane}: K[{}, {}] (free equations), {worst}",
            worst.row,
            picks[worst.col]
        );
    }
}

/// Steps a shipped case to `last` in load steps of `step` (each from the
/// linear extrapolation of the two latest solutions, as a run starts them);
/// the last two converged states.
fn states_near_the_limit_load(
    engine: &mut asperity::solve::Engine,
    model: &asperity::model::Model,
    step: f64,
    last: f64,
) -> (State, State) {
    let (mut before, mut now) = (State::initial(model), State::initial(model));
    let mut lambda = 0.0;
    while lambda < last - 1e-12 {
        let du: Vec<f64> = now.u.iter().zip(&before.u).map(|(a, b)| a - b).collect();
        let start = (lambda > 0.0)
            .then(|| asperity::solve::predict(&now, &du, step, step))
            .flatten();
        lambda += step;
        let (next, _) = engine
            .step_from(&now, lambda, Response::Plastic, start.as_deref())
            .unwrap_or_else(|e| panic!("λ = {lambda}: {e}"));
        engine.committed();
        before = std::mem::replace(&mut now, next);
    }
    (before, now)
}

/// The assembled tangent is the derivative of the assembled residual at the
/// states where the rounded punches' Newton increments are long (issue 29,
/// docs/performance.md "Plastic Newton near the limit load"): most of the
/// foundation plastic, plane stress (projected return) and plane strain
/// (radial return), a non-matching interface. Directional derivatives
/// (K v against central differences of R along v) with v on the nodes of the
/// elements that hold a yielding Gauss point, so that their tangents are what
/// K v measures.
#[test]
fn assembled_tangent_is_the_derivative_of_the_residual_near_the_limit_load() {
    for case in ["punch-rounded-stress", "punch-rounded-strain"] {
        let path = common::root().join("cases").join(case).join("case.toml");
        let model = common::model(&std::fs::read_to_string(path).unwrap());
        let mut engine =
            asperity::app::driver::serial_engine(&model, Method::FullNewton, 1).unwrap();
        let (before, now) = states_near_the_limit_load(&mut engine, &model, 0.1, 0.8);
        let ng = model.rule(0).points.len();
        let plastic: Vec<usize> = (0..model.mesh.elements.len())
            .filter(|&e| {
                now.gauss
                    .range(e * ng..(e + 1) * ng)
                    .iter()
                    .any(|g| g.yielding)
            })
            .collect();
        assert!(
            plastic.len() > 50,
            "{case}: {} plastic elements",
            plastic.len()
        );
        let mut on = vec![false; now.u.len()];
        for &e in &plastic {
            for &n in model.mesh.elements[e].nodes() {
                on[2 * n] = true;
                on[2 * n + 1] = true;
            }
        }
        let free: Vec<usize> = (0..now.u.len())
            .filter(|&d| model.dofs.equation(d).is_some())
            .collect();
        let pattern = model.pattern();
        let u_max = now.u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        // at the converged state and off it
        for wobble in [0.0, 1e-3] {
            let u: Vec<f64> = (0..now.u.len())
                .map(|i| now.u[i] * (1.0 + wobble * (i as f64).sin()))
                .collect();
            engine.linearize(&before, &u, 0.8).unwrap();
            let k = engine.backend.matrix_values().unwrap().to_vec();
            for seed in 0..2 {
                let v: Vec<f64> = free
                    .iter()
                    .enumerate()
                    .map(|(c, &d)| {
                        let s = ((c * 7 + seed * 13) as f64 * 0.731).sin();
                        if on[d] {
                            s
                        } else {
                            0.0
                        }
                    })
                    .collect();
                let mut kv = vec![0.0; free.len()];
                for (c, &vc) in v.iter().enumerate() {
                    for at in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
                        kv[pattern.row_idx[at] as usize] += k[at] * vc;
                    }
                }
                let h = 1e-8 * u_max;
                // one column: the derivative along v
                let jac = fd::central_columns(&[h], |_, s| {
                    let mut up = u.clone();
                    for (c, &d) in free.iter().enumerate() {
                        up[d] += s * v[c];
                    }
                    let r = engine.linearize(&before, &up, 0.8).unwrap();
                    free.iter().map(|&d| r[d]).collect()
                });
                let (mut err, mut norm) = (0.0, 0.0);
                for (row, kv) in kv.iter().enumerate() {
                    err += (jac[(row, 0)] - kv).powi(2);
                    norm += kv.powi(2);
                }
                let rel = (err / norm).sqrt();
                assert!(
                    rel < 1e-6,
                    "{case} (wobble {wobble}, direction {seed}): |FD − K v| / |K v| = {rel:e}"
                );
            }
        }
    }
}
