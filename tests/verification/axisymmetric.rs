//! Axisymmetric bodies (x = r, y = z) against closed forms: the patch test on a
//! distorted mesh (also touching the axis), the thick cylinder under internal
//! pressure (Lamé), and a solid cylinder (elements on the axis) in uniaxial
//! compression, elastic and elastic-plastic with linear hardening.

use crate::common::{self, CaseText};
use asperity::model::Model;
use asperity::physics::element::element_forces;
use asperity::physics::element::family::GaussRule;
use asperity::physics::element::q8::{gauss_2x2, gauss_3x3};
use asperity::physics::element::solid::{ElementGeometry, Response, Tangent};
use asperity::physics::element::Section;
use asperity::physics::material::{Plane, PointState, VonMises};
use asperity::solve::State;
use nalgebra::{DMatrix, DVector, Vector4};

use crate::common::Quiet;

const REVOLUTION: Section = Section {
    axisymmetric: true,
    thickness: 1.0,
};

/// Element-by-element forces of the patch at displacement `u` (dense K, the
/// Gauss states).
fn assemble(
    nodes: &[[f64; 2]],
    els: &[[usize; 8]],
    rule: &GaussRule,
    mat: &VonMises,
    u: &DVector<f64>,
) -> (DMatrix<f64>, Vec<PointState>) {
    let n = nodes.len();
    let ng = rule.points.len();
    let mut k = DMatrix::<f64>::zeros(2 * n, 2 * n);
    let (mut fe, mut ke) = ([0.0; 16], [0.0; 256]);
    let zero = vec![PointState::default(); ng];
    let mut states = Vec::new();
    for el in els {
        let c: [[f64; 2]; 8] = std::array::from_fn(|a| nodes[el[a]]);
        let geom = ElementGeometry::with_section(
            asperity::physics::element::family::Family::Q8,
            &c,
            rule,
            &REVOLUTION,
        )
        .unwrap();
        let ue: [f64; 16] = std::array::from_fn(|a| u[2 * el[a / 2] + a % 2]);
        let mut st = zero.clone();
        element_forces(
            &geom,
            mat,
            &[0.0; 9],
            &ue,
            &zero,
            &mut st,
            Response::Plastic,
            Some(Tangent::Consistent),
            &mut fe,
            &mut ke,
        )
        .unwrap();
        for a in 0..16 {
            for b in 0..16 {
                k[(2 * el[a / 2] + a % 2, 2 * el[b / 2] + b % 2)] += ke[a * 16 + b];
            }
        }
        states.extend(st);
    }
    (k, states)
}

/// The patch of `patch.rs` moved to r ≥ r0, straight-sided (midside nodes at
/// the middle of their edges) or with curved edges as built there.
fn axisymmetric_patch(r0: f64, straight: bool) -> (Vec<[f64; 2]>, Vec<[usize; 8]>) {
    let (mut nodes, els) = crate::patch::patch();
    if straight {
        for el in &els {
            for k in 0..4 {
                let (a, b) = (el[k], el[(k + 1) % 4]);
                nodes[el[4 + k]] = [0, 1].map(|c| 0.5 * (nodes[a][c] + nodes[b][c]));
            }
        }
    }
    for x in &mut nodes {
        x[0] += r0;
    }
    (nodes, els)
}

#[test]
fn axisymmetric_patch_test_reproduces_u_r_ar_u_z_bz() {
    let (a, b) = (1.3e-3, -0.8e-3);
    let mat = VonMises::new(100000.0, 0.25, f64::INFINITY, 0.0, Plane::Axisymmetric).unwrap();
    let sig = mat.elastic_matrix_4() * Vector4::new(a, b, 0.0, a);
    // full integration on curved edges; 2×2 is exact on straight-sided elements
    for (rule, straight) in [
        (gauss_3x3(), false),
        (gauss_3x3(), true),
        (gauss_2x2(), true),
    ] {
        for r0 in [0.0, 2.5] {
            let (nodes, els) = axisymmetric_patch(r0, straight);
            let n = nodes.len();
            let (lo, hi) = (r0, r0 + 4.0);
            let boundary: Vec<bool> = nodes
                .iter()
                .map(|x| x[0] == lo || x[0] == hi || x[1] == 0.0 || x[1] == 4.0)
                .collect();
            let exact = |x: [f64; 2]| [a * x[0], b * x[1]];
            let (k, _) = assemble(&nodes, &els, &rule, &mat, &DVector::zeros(2 * n));
            let mut u = DVector::<f64>::zeros(2 * n);
            for i in (0..n).filter(|&i| boundary[i]) {
                let v = exact(nodes[i]);
                (u[2 * i], u[2 * i + 1]) = (v[0], v[1]);
            }
            let free: Vec<usize> = (0..2 * n).filter(|&d| !boundary[d / 2]).collect();
            let kff = DMatrix::from_fn(free.len(), free.len(), |r, c| k[(free[r], free[c])]);
            let rhs = DVector::from_fn(free.len(), |r, _| {
                -(0..2 * n)
                    .filter(|&d| boundary[d / 2])
                    .map(|d| k[(free[r], d)] * u[d])
                    .sum::<f64>()
            });
            let sol = kff.lu().solve(&rhs).unwrap();
            for (r, &d) in free.iter().enumerate() {
                u[d] = sol[r];
            }
            let what = format!(
                "{} points, straight {straight}, r0 = {r0}",
                rule.points.len()
            );
            for (i, x) in nodes.iter().enumerate() {
                let v = exact(*x);
                let err = (u[2 * i] - v[0]).abs().max((u[2 * i + 1] - v[1]).abs());
                assert!(
                    err < 1e-10 * a.abs() * 4.0,
                    "{what}: node {i} error {err:e}"
                );
            }
            // constant strain, hoop strain u_r/r = a included, and stress D ε
            let (_, states) = assemble(&nodes, &els, &rule, &mat, &u);
            for g in &states {
                for c in 0..4 {
                    let err = (g.stress[c] - sig[c]).abs();
                    assert!(
                        err < 1e-10 * sig.amax(),
                        "{what}: {:?} vs {sig:?}",
                        g.stress
                    );
                }
            }
        }
    }
}

/// Solves a case given as text; the model and its final state.
fn solve(text: &str) -> (Model, State) {
    let model = common::model(text);
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap();
    (model, r.final_state)
}

/// A thick tube a ≤ r ≤ b, its ends held axially (plane strain in z).
fn tube(a: f64, b: f64, p: f64, nx: usize, integration: &str) -> String {
    common::case()
        .plane("axisymmetric")
        .integration(integration)
        .block("tube", [a, b], [nx], [0.0, 1.0], [1])
        .rx([2.0])
        .material("tube", 210000.0, 0.3)
        .uy("tube.bottom", 0.0)
        .uy("tube.top", 0.0)
        .pressure("tube.left", p)
        .solver("increments = 1")
        .tolerances(1e-10, 1e-12)
        .no_vtu()
        .build()
}

#[test]
fn thick_cylinder_under_internal_pressure_matches_lame() {
    let (a, b, p, e, nu): (f64, f64, f64, f64, f64) = (10.0, 25.0, 150.0, 210000.0, 0.3);
    let (model, st) = solve(&tube(a, b, p, 80, "reduced"));
    let big_a = p * a * a / (b * b - a * a);
    let big_b = p * a * a * b * b / (b * b - a * a);
    let u_r = |r: f64| (1.0 + nu) / e * ((1.0 - 2.0 * nu) * big_a * r + big_b / r);
    let hoop = |r: f64| big_a + big_b / (r * r);
    let radial = |r: f64| big_a - big_b / (r * r);
    // radial displacement at every node on the inner and outer radius
    for (n, x) in model.mesh.nodes.iter().enumerate() {
        if x[0] == a || x[0] == b {
            let err = common::rel(st.u[2 * n], u_r(x[0]));
            assert!(
                err < 1e-6,
                "u_r at r = {}: {} vs {} ({err:e})",
                x[0],
                st.u[2 * n],
                u_r(x[0])
            );
            assert!(st.u[2 * n + 1].abs() < 1e-12 * u_r(a), "u_z at node {n}");
        }
    }
    // hoop, radial and axial stress at every Gauss point (2×2: the
    // superconvergent points of the quadratic element), at its radius
    let ng = model.rule(0).points.len();
    let (mut r_min, mut r_max) = (f64::MAX, 0.0f64);
    for e in 0..model.mesh.elements.len() {
        let g = model.geometry(e);
        for ip in 0..ng {
            let r = g.x[ip][0];
            (r_min, r_max) = (r_min.min(r), r_max.max(r));
            let s = st.gauss.get(e * ng + ip).stress;
            let err = common::rel(s[3], hoop(r));
            assert!(
                err < 1e-6,
                "σ_θθ at r = {r}: {} vs {} ({err:e})",
                s[3],
                hoop(r)
            );
            assert!(
                (s[0] - radial(r)).abs() < 1e-6 * p,
                "σ_rr at r = {r}: {} vs {}",
                s[0],
                radial(r)
            );
            // plane strain in z: σ_zz = ν (σ_rr + σ_θθ) = 2ν A
            assert!(
                (s[1] - 2.0 * nu * big_a).abs() < 1e-6 * p,
                "σ_zz at r = {r}: {}",
                s[1]
            );
        }
    }
    // the points nearest the inner and outer radius were among them
    assert!(r_min < a + 0.01 * (b - a) && r_max > b - 0.05 * (b - a));
}

/// A solid cylinder 0 ≤ r ≤ radius, 0 ≤ z ≤ length, on a frictionless base
/// (uz = 0 at z = 0; u_r = 0 on the axis is automatic); its top face is
/// loaded by what is added to it (a [[load]] or a [[boundary]] entry).
fn cylinder(radius: f64, length: f64, yield_stress: f64, hardening: f64) -> CaseText {
    common::case()
        .plane("axisymmetric")
        .block("rod", [0.0, radius], [4], [0.0, length], [5])
        .rx([0.5])
        .ry([1.5])
        .material("rod", 200000.0, 0.3)
        .plastic(yield_stress, hardening)
        .uy("rod.bottom", 0.0)
        .solver("increments = 5")
        .tolerances(1e-12, 1e-12)
        .no_vtu()
}

#[test]
fn solid_cylinder_under_axial_load_is_uniaxial_on_the_axis_too() {
    let (radius, length, p, e, nu): (f64, f64, f64, f64, f64) = (5.0, 12.0, 80.0, 200000.0, 0.3);
    let (model, st) = solve(
        &cylinder(radius, length, 1e6, 0.0)
            .pressure("rod.top", p)
            .build(),
    );
    // the load is the full revolution's: F = p π R²
    let fz: f64 = (0..model.mesh.nodes.len())
        .map(|n| model.f_ext[2 * n + 1])
        .sum();
    let force = p * std::f64::consts::PI * radius * radius;
    assert!(common::rel(-fz, force) < 1e-12, "F = {fz} vs {force}");
    // σ_zz = −F/(π R²) everywhere, the other components zero
    for g in &st.gauss {
        let s = g.stress;
        assert!(
            common::rel(s[1], -force / (std::f64::consts::PI * radius * radius)) < 1e-10,
            "{s:?}"
        );
        for c in [0, 2, 3] {
            assert!(s[c].abs() < 1e-10 * p, "{s:?}");
        }
    }
    // u_z = ε_zz z, u_r = −ν ε_zz r (u_r = 0 on the axis)
    let ezz = -p / e;
    let mut on_axis = 0;
    for (n, x) in model.mesh.nodes.iter().enumerate() {
        let (ur, uz) = (st.u[2 * n], st.u[2 * n + 1]);
        assert!(
            (ur + nu * ezz * x[0]).abs() < 1e-10 * nu * p / e * radius,
            "u_r at {x:?}: {ur}"
        );
        assert!(
            (uz - ezz * x[1]).abs() < 1e-10 * p / e * length,
            "u_z at {x:?}: {uz}"
        );
        if x[0] == 0.0 {
            on_axis += 1;
            assert_eq!(ur, 0.0, "node {n} on the axis");
        }
    }
    assert_eq!(on_axis, 11, "nodes on the axis");
}

#[test]
fn solid_cylinder_compressed_beyond_yield_follows_the_bilinear_curve() {
    let (radius, length, e, nu, sy, h): (f64, f64, f64, f64, f64, f64) =
        (5.0, 12.0, 200000.0, 0.3, 250.0, 2000.0);
    // 4 times the yield strain, shortening by a prescribed top displacement
    let eps = -4.0 * sy / e;
    let (model, st) = solve(
        &cylinder(radius, length, sy, h)
            .uy("rod.top", eps * length)
            .build(),
    );
    // σ = σ_Y + E H/(E + H) (ε − σ_Y/E) in compression
    let sigma = -(sy + e * h / (e + h) * (-eps - sy / e));
    let plastic_zz = eps - sigma / e;
    for g in &st.gauss {
        let s = g.stress;
        assert!(g.yielding, "every point yields");
        assert!(common::rel(s[1], sigma) < 1e-8, "σ_zz {} vs {sigma}", s[1]);
        for c in [0, 2, 3] {
            assert!(s[c].abs() < 1e-8 * sy, "{s:?}");
        }
        assert!(
            common::rel(g.peeq, -plastic_zz) < 1e-8,
            "ε̄ᵖ {} vs {}",
            g.peeq,
            -plastic_zz
        );
    }
    // lateral strain: elastic −ν σ/E plus isochoric plastic −½ εᵖ_zz
    let e_rr = -nu * sigma / e - 0.5 * plastic_zz;
    for (n, x) in model.mesh.nodes.iter().enumerate() {
        assert!(
            (st.u[2 * n] - e_rr * x[0]).abs() < 1e-8 * e_rr.abs() * radius,
            "u_r at {x:?}: {} vs {}",
            st.u[2 * n],
            e_rr * x[0]
        );
    }
}

/// Two stacked solid cylinders (radius R) pressed together by q on the top face
/// across a compliant interface: the springs are weighted by 2π r, so the
/// interface area is π R², the mean pressure q, every pair's approach c_N q^m
/// (eq. 2.1) and the reported load the full revolution's q π R².
#[test]
fn stacked_cylinders_weight_the_interface_by_the_full_revolution() {
    let (radius, q, c, m): (f64, f64, f64, f64) = (8.0, 120.0, 0.002, 0.5);
    for weights in ["lumped", "consistent"] {
        let text = common::case()
            .plane("axisymmetric")
            .block("top", [0.0, radius], [3], [0.0, 15.0], [3])
            .rx([0.5])
            .block("bottom", [0.0, radius], [3], [-25.0, 0.0], [4])
            .rx([0.5])
            .ry([0.3])
            .interface("joint", "top", "bottom")
            .material("top", 70000.0, 0.33)
            .material("bottom", 70000.0, 0.33)
            .law("joint", "power", c, m)
            .weights(weights)
            .uy("bottom.bottom", 0.0)
            .pressure("top.top", q)
            .solver("increments = 4")
            .tolerances(1e-12, 1e-12)
            .build();
        let model = common::model(&text);
        let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap();
        let im = &model.interfaces[0];
        let area = std::f64::consts::PI * radius * radius;
        assert!(
            common::rel(im.area(), area) < 1e-12,
            "{weights}: area {} vs {area}",
            im.area()
        );
        let last = r.increments.last().unwrap().measures;
        assert!(
            common::rel(last.mean_pressure, q) < 1e-9,
            "{weights}: p {}",
            last.mean_pressure
        );
        let kn = q * area / 1000.0;
        assert!(
            common::rel(last.total_load_kn, kn) < 1e-9,
            "{weights}: {} kN vs {kn}",
            last.total_load_kn
        );
        for pr in &im.pairs {
            let un = im.pair_approach(pr, &r.final_state.u);
            assert!(
                common::rel(un, c * q.powf(m)) < 1e-9,
                "{weights}: pair at r = {}: {un}",
                pr.x[0]
            );
        }
    }
}
