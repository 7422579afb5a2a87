//! Interfaces on a Gmsh mesh of volumes (`upper_surface` /
//! `lower_surface`): two boxes of 20-node hexahedra stacked along y, written
//! as MSH 4.1 text (tests/common/msh.rs).
//!
//! * Matching: the same two blocks swept from the layout (`extrude`) and
//!   read from the file give the same displacements, contact pressures and
//!   joint forces, moment and dissipation to round-off, with friction and
//!   an eccentric load, with consistent and with lumped weights.
//! * `matching = false` (node-to-surface springs) on meshes that do not
//!   coincide: a block pressed uniformly, free to spread, is in uniaxial
//!   stress σ_y = −p; its springs carry p, their approach is the power
//!   law's u_N = c_N p^m (paper eq. 2.1), and the top moves
//!   down by 2 h p / E + u_N. Exact where each slave face lies on one master
//!   face (its 4 × 4 Gauss points then integrate the master's shape
//!   functions exactly); on meshes that cut across each other the joint
//!   still carries p A (equilibrium).

use crate::common;
use crate::common::msh::{boxes_msh, cells, Box3};
use asperity::model::Model;
use asperity::solve::RunResult;
use common::Quiet;
use std::collections::HashMap;

/// The case `text` (its mesh `msh`, if any, written beside it as mesh.msh)
/// built and run.
fn run(name: &str, text: &str, msh: Option<&str>) -> (Model, RunResult) {
    let path = common::case_dir(name, text);
    if let Some(m) = msh {
        std::fs::write(path.with_file_name("mesh.msh"), m).unwrap();
    }
    let case = asperity::input::case::Case::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let model = Model::build(case).unwrap_or_else(|e| panic!("{e}"));
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap();
    (model, r)
}

/// Materials, law, supports and the eccentric load of the two blocks "top"
/// (on y = 0) and "base" (below), after the mesh and its interface.
fn physics(weights: &str) -> String {
    format!(
        r#"
[materials.top]
young = 200000.0
poisson = 0.3
yield_stress = 1000.0
hardening = 2000.0
[materials.base]
young = 200000.0
poisson = 0.3
yield_stress = 1000.0
hardening = 2000.0
[interface.joint]
law = "power"
c_n = 0.001
m = 0.5
weights = "{weights}"
[interface.joint.tangential]
r = 0.9
s = 0.5
kp_ratio = 1.0
mu = 0.3
beta = 1.0
n = 275.0
yield_ratio = 0.625
[[boundary]]
set = "base.bottom"
uy = 0.0
[[boundary]]
set = "base.left"
ux = 0.0
[[boundary]]
set = "base.zmin"
uz = 0.0
[[boundary]]
set = "top.zmin"
uz = 0.0
[[load]]
faces = "top.top"
pressure = 100.0
x_range = [0.0, 10.0]
[[load]]
faces = "top.right"
traction = [0.0, 0.0, 5.0]
[solver]
increments = 2
residual_tolerance = 1e-10
"#
    )
}

/// The swept layout: top [0, 20] × [0, 10], base [0, 30] × [−10, 0] (wider
/// than the top), both through z ∈ [0, 10].
fn layout(weights: &str) -> String {
    r#"[model]
plane = "3d"
[mesh]
extrude = { z = [0.0, 10.0], nz = [2] }
[[mesh.block]]
body = "top"
x = [0.0, 20.0]
nx = [4]
y = [0.0, 10.0]
ny = [2]
[[mesh.block]]
body = "base"
x = [0.0, 30.0]
nx = [6]
y = [-10.0, 0.0]
ny = [2]
[[mesh.interface]]
name = "joint"
upper = "top"
lower = "base"
"#
    .to_string()
        + &physics(weights)
}

/// The same model read from a Gmsh file.
fn from_file(weights: &str, matching: bool) -> String {
    let more = if matching { "" } else { "matching = false\n" };
    format!(
        "[model]\nplane = \"3d\"\n[mesh]\nfile = \"mesh.msh\"\n[[mesh.interface]]\nname = \"joint\"\nupper_surface = \"top.bottom\"\nlower_surface = \"base.top\"\n{more}{}",
        physics(weights)
    )
}

/// The layout's two blocks as boxes of a Gmsh file, `top` with `n` cells
/// along x and z (the layout's 4 and 2 when they match).
fn stacked(n: [usize; 2]) -> String {
    boxes_msh(&[
        Box3 {
            name: "top",
            axes: [
                cells(0.0, 20.0, n[0]),
                cells(0.0, 10.0, 2),
                cells(0.0, 10.0, n[1]),
            ],
        },
        Box3 {
            name: "base",
            axes: [
                cells(0.0, 30.0, 6),
                cells(-10.0, 0.0, 2),
                cells(0.0, 10.0, 2),
            ],
        },
    ])
}

/// A place as a key (to 1e-9 mm) with its body.
fn key(x: &[f64; 3], body: usize) -> ([i64; 3], usize) {
    (x.map(|v| (v * 1e9).round() as i64), body)
}

fn compare(weights: &str) {
    let (m1, r1) = run(&format!("gmsh3d-layout-{weights}"), &layout(weights), None);
    let msh = stacked([4, 2]);
    let (m2, r2) = run(
        &format!("gmsh3d-file-{weights}"),
        &from_file(weights, true),
        Some(&msh),
    );
    let (u1, u2) = (&r1.final_state.u, &r2.final_state.u);
    assert_eq!(m1.mesh.nodes.len(), m2.mesh.nodes.len());
    let (b1, b2) = (m1.mesh.node_bodies(), m2.mesh.node_bodies());
    let at: HashMap<([i64; 3], usize), usize> = m1
        .mesh
        .nodes
        .iter()
        .enumerate()
        .map(|(n, x)| (key(x, b1[n]), n))
        .collect();
    let scale = u1.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut worst: f64 = 0.0;
    for (n, x) in m2.mesh.nodes.iter().enumerate() {
        let k = at[&key(x, b2[n])];
        for c in 0..3 {
            worst = worst.max((u2[3 * n + c] - u1[3 * k + c]).abs());
        }
    }
    let (i1, i2) = (&m1.interfaces[0], &m2.interfaces[0]);
    assert_eq!(i1.pairs.len(), i2.pairs.len());
    assert_eq!(i1.points.len(), i2.points.len());
    let pair1: HashMap<([i64; 3], usize), usize> = i1
        .pairs
        .iter()
        .enumerate()
        .map(|(k, p)| (key(&p.x, 0), k))
        .collect();
    let mut p_max: f64 = 0.0;
    let mut worst_p: f64 = 0.0;
    for p in &i2.pairs {
        let q = &i1.pairs[pair1[&key(&p.x, 0)]];
        let p2 = i2.law.pressure(i2.pair_approach(p, u2)).0;
        let p1 = i1.law.pressure(i1.pair_approach(q, u1)).0;
        assert!((p.area - q.area).abs() < 1e-12 * q.area);
        p_max = p_max.max(p1);
        worst_p = worst_p.max((p2 - p1).abs());
    }
    let (j1, j2) = (
        r1.increments.last().unwrap().joints[0],
        r2.increments.last().unwrap().joints[0],
    );
    println!(
        "{weights}: layout vs file: u {worst:.3e} of {scale:.3e} mm, p {worst_p:.3e} of {p_max:.3e} MPa; \
         F_N {:.12e} / {:.12e} N, F_T {:.12e} / {:.12e} N, F {:?} / {:?}, M {:?} / {:?}, D {:.12e} / {:.12e} N·mm",
        j1.normal_force, j2.normal_force, j1.tangential_force, j2.tangential_force,
        j1.force, j2.force, j1.moment, j2.moment, j1.dissipation, j2.dissipation
    );
    assert!(worst < 1e-9 * scale, "{worst:e} of {scale:e}");
    assert!(worst_p < 1e-9 * p_max, "{worst_p:e} of {p_max:e}");
    let f = 100.0 * 10.0 * 10.0;
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * f;
    assert!(near(j1.normal_force, j2.normal_force));
    assert!(near(j1.tangential_force, j2.tangential_force));
    assert!(near(j1.tangential_force_2, j2.tangential_force_2));
    for c in 0..3 {
        assert!(
            near(j1.force[c], j2.force[c]),
            "{:?} {:?}",
            j1.force,
            j2.force
        );
        assert!(
            (j1.moment[c] - j2.moment[c]).abs() <= 1e-9 * f * 10.0,
            "{:?} {:?}",
            j1.moment,
            j2.moment
        );
    }
    // the pressure's resultant is carried through, and friction works
    assert!((j2.force[1] - f).abs() < 1e-8 * f, "{:?}", j2.force);
    assert!(j2.dissipation > 0.0 && j2.tangential_force_2.abs() > 1.0);
    assert!((j1.dissipation - j2.dissipation).abs() <= 1e-9 * j1.dissipation);
}

#[test]
fn a_file_interface_is_the_swept_one_consistent() {
    compare("consistent");
}

#[test]
fn a_file_interface_is_the_swept_one_lumped() {
    compare("lumped");
}

/// The uniformly pressed block of the module text on the file mesh whose
/// top has `n` cells along x and z.
fn pressed(n: [usize; 2], weights: &str) -> (Model, RunResult) {
    let text = format!(
        r#"[model]
plane = "3d"
[mesh]
file = "mesh.msh"
[[mesh.interface]]
name = "joint"
upper_surface = "top.bottom"
lower_surface = "base.top"
matching = false
[materials.top]
young = 200000.0
poisson = 0.3
[materials.base]
young = 200000.0
poisson = 0.3
[interface.joint]
law = "power"
c_n = 0.001
m = 0.5
weights = "{weights}"
[[boundary]]
set = "base.bottom"
uy = 0.0
[[boundary]]
set = "base.left"
ux = 0.0
[[boundary]]
set = "top.left"
ux = 0.0
[[boundary]]
set = "base.zmin"
uz = 0.0
[[boundary]]
set = "top.zmin"
uz = 0.0
[[load]]
faces = "top.top"
pressure = 100.0
[solver]
increments = 1
residual_tolerance = 1e-11
"#
    );
    let msh = boxes_msh(&[
        Box3 {
            name: "top",
            axes: [
                cells(0.0, 20.0, n[0]),
                cells(0.0, 10.0, 2),
                cells(0.0, 10.0, n[1]),
            ],
        },
        Box3 {
            name: "base",
            axes: [
                cells(0.0, 20.0, 4),
                cells(-10.0, 0.0, 2),
                cells(0.0, 10.0, 2),
            ],
        },
    ]);
    run(
        &format!("gmsh3d-pressed-{}x{}-{weights}", n[0], n[1]),
        &text,
        Some(&msh),
    )
}

#[test]
fn a_block_pressed_on_a_surface_meshed_apart_is_the_closed_form() {
    let (p, e, h, c_n, m) = (100.0, 200000.0, 10.0, 0.001, 0.5);
    let u_n = c_n * f64::powf(p, m);
    // each top face within one base face: exact
    let (model, r) = pressed([8, 4], "consistent");
    let iface = &model.interfaces[0];
    let u = &r.final_state.u;
    assert_eq!(iface.points.len(), 8 * 4 * 16);
    let mut worst_p: f64 = 0.0;
    let mut worst_u: f64 = 0.0;
    for pt in &iface.points {
        let a = iface.point_kinematics(pt, u).0;
        worst_u = worst_u.max((a - u_n).abs());
        worst_p = worst_p.max((iface.law.pressure(a).0 - p).abs());
    }
    let top = &model.mesh.node_sets["top.top"];
    let want = -(2.0 * h * p / e + u_n);
    let worst_top = top
        .iter()
        .map(|&k| (u[3 * k + 1] - want).abs())
        .fold(0.0, f64::max);
    let j = r.increments.last().unwrap().joints[0];
    println!(
        "pressed block, nested faces: p {worst_p:.3e} MPa off {p}, u_N {worst_u:.3e} mm off {u_n}, top u_y {worst_top:.3e} mm off {want}, F_N {:.12e} N",
        j.normal_force
    );
    assert!(worst_p < 1e-9 * p, "{worst_p:e}");
    assert!(worst_u < 1e-9 * u_n, "{worst_u:e}");
    assert!(worst_top < 1e-9 * want.abs(), "{worst_top:e}");
    assert!((j.normal_force - p * 200.0).abs() < 1e-9 * p * 200.0);
    assert!((j.mean_approach - u_n).abs() < 1e-9 * u_n);
    // top faces across the base's: equilibrium, and close to the closed form
    for weights in ["consistent", "lumped"] {
        let (model, r) = pressed([3, 3], weights);
        let iface = &model.interfaces[0];
        let j = r.increments.last().unwrap().joints[0];
        let spread = iface
            .points
            .iter()
            .map(|pt| {
                (iface
                    .law
                    .pressure(iface.point_kinematics(pt, &r.final_state.u).0)
                    .0
                    - p)
                    .abs()
            })
            .fold(0.0, f64::max);
        println!(
            "pressed block, 3 x 3 on 4 x 2 ({weights}): F_N {:.12e} N (p A = {}), ū_N {:.6e} mm (u_N {u_n}), largest |p − {p}| {spread:.3e} MPa",
            j.normal_force,
            p * 200.0,
            j.mean_approach
        );
        assert!((j.normal_force - p * 200.0).abs() < 1e-8 * p * 200.0);
    }
}

/// The mesh of tests/data/stacked-h20.msh (and of the bad-input corpus's
/// base of the same name) is the helper's: two boxes 20 × 10 × 10 (top,
/// 2 × 1 × 1 cells) on 30 × 10 × 10 (base, 3 × 1 × 1), their interface
/// surfaces top.bottom and base.top; `ASPERITY_BLESS=1` writes both.
#[test]
fn the_stacked_boxes_file_is_the_helpers() {
    let want = boxes_msh(&[
        Box3 {
            name: "top",
            axes: [cells(0.0, 20.0, 2), vec![0.0, 10.0], vec![0.0, 10.0]],
        },
        Box3 {
            name: "base",
            axes: [cells(0.0, 30.0, 3), vec![-10.0, 0.0], vec![0.0, 10.0]],
        },
    ]);
    for path in [
        "tests/data/stacked-h20.msh",
        "tests/bad_inputs/base/stacked-h20.msh",
    ] {
        let path = common::root().join(path);
        if std::env::var_os("ASPERITY_BLESS").is_some() {
            std::fs::write(&path, &want).unwrap();
        }
        let got = std::fs::read_to_string(&path).unwrap();
        assert!(
            got == want,
            "{} is not the helper's output (ASPERITY_BLESS=1 writes it)",
            path.display()
        );
    }
}
