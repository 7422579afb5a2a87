//! Rough interfaces on the faces of 3D solids: the shipped slab
//! (cases/punch-slab-3d, the paper's punch swept along z and held in z)
//! against the plane-strain model of the same layout, with and without
//! friction.

use crate::common;
use asperity::model::Model;
use asperity::solve::RunResult;
use common::Quiet;
use std::collections::HashMap;

fn run(text: &str) -> (Model, RunResult) {
    let model = common::model(text);
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap();
    (model, r)
}

/// The slab case's text, without its tangential law if `friction` is false.
fn slab(friction: bool) -> String {
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-slab-3d/case.toml")).unwrap();
    if friction {
        return text;
    }
    let start = text.find("[interface.contact.tangential]").unwrap();
    let end = start + text[start..].find("\n\n").unwrap();
    format!("{}{}", &text[..start], &text[end + 2..])
}

/// The same layout as a plane-strain model 10 mm thick: no sweep, no z
/// supports, the load on the edge set.
fn plane(text: &str) -> String {
    let mut out = String::new();
    for block in text.split("\n\n") {
        if block.contains("uz = 0.0") {
            continue;
        }
        let block = block
            .replace("plane = \"3d\"", "plane = \"strain\"\nthickness = 10.0")
            .replace("faces = \"punch.top\"", "edges = \"punch.top\"");
        let lines: Vec<&str> = block
            .lines()
            .filter(|l| !l.starts_with("extrude"))
            .collect();
        out += &lines.join("\n");
        out += "\n\n";
    }
    out
}

/// The 3D run and the plane run agree: every node's (u_x, u_y) at every
/// level z, every pair's contact pressure, the joint's forces and energies.
fn compare(friction: bool) {
    let text = slab(friction);
    let (m3, r3) = run(&text);
    let (m2, r2) = run(&plane(&text));
    let (s3, s2) = (&r3.final_state, &r2.final_state);
    let key = |x: &[f64; 3]| [x[0].to_bits(), x[1].to_bits()];
    // a node by its place and body (the interface's two sides share places)
    let (b2, b3) = (m2.mesh.node_bodies(), m3.mesh.node_bodies());
    let at: HashMap<([u64; 2], usize), usize> = m2
        .mesh
        .nodes
        .iter()
        .enumerate()
        .map(|(n, x)| ((key(x), b2[n]), n))
        .collect();
    let scale = s2.u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut worst: f64 = 0.0;
    for (n, x) in m3.mesh.nodes.iter().enumerate() {
        let k = at[&(key(x), b3[n])];
        for c in 0..2 {
            worst = worst.max((s3.u[3 * n + c] - s2.u[2 * k + c]).abs());
        }
    }
    // the interface's pairs: each 3D pair at (x, 0, z) against the plane
    // pair at (x, 0)
    let (i3, i2) = (&m3.interfaces[0], &m2.interfaces[0]);
    let pair2: HashMap<[u64; 2], usize> = i2
        .pairs
        .iter()
        .enumerate()
        .map(|(k, p)| (key(&p.x), k))
        .collect();
    let p_max = i2
        .pairs
        .iter()
        .map(|p| i2.law.pressure(i2.pair_approach(p, &s2.u)).0)
        .fold(0.0, f64::max);
    let mut worst_p: f64 = 0.0;
    for p in &i3.pairs {
        let q = &i2.pairs[pair2[&key(&p.x)]];
        let p3 = i3.law.pressure(i3.pair_approach(p, &s3.u)).0;
        let p2 = i2.law.pressure(i2.pair_approach(q, &s2.u)).0;
        worst_p = worst_p.max((p3 - p2).abs());
    }
    let (j3, j2) = (
        r3.increments.last().unwrap().joints[0],
        r2.increments.last().unwrap().joints[0],
    );
    println!(
        "slab (friction {friction}) vs plane strain: u {worst:.3e} of {scale:.3e} mm, p {worst_p:.3e} of {p_max:.3e} MPa; F_N {:.10e} / {:.10e} N, F_T {:.10e} / {:.10e} N, D {:.10e} / {:.10e} N·mm",
        j3.normal_force, j2.normal_force, j3.tangential_force, j2.tangential_force, j3.dissipation, j2.dissipation
    );
    // both faces' pairs, and the corners' on the midplane
    assert_eq!(
        i3.pairs.len(),
        2 * i2.pairs.len() + i2.pairs.len().div_ceil(2)
    );
    assert!(worst < 1e-8 * scale, "{worst:e} of {scale:e}");
    assert!(worst_p < 1e-8 * p_max, "{worst_p:e} of {p_max:e}");
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-8 * a.abs().max(b.abs());
    assert!(near(j3.normal_force, j2.normal_force));
    assert!(
        (j3.normal_force - 80e3).abs() < 1e-6 * 80e3,
        "{}",
        j3.normal_force
    );
    if friction {
        assert!(j2.tangential_force.abs() > 1e-3 * j2.normal_force);
        assert!(j2.dissipation > 0.0 && j2.macro_slip > 0.0);
        assert!(near(j3.tangential_force, j2.tangential_force));
        assert!(near(j3.dissipation, j2.dissipation));
        // the slip areas: the plane run's lengths times the depth
        assert!(near(j3.macro_slip, 10.0 * j2.macro_slip));
        assert!(near(j3.stick, 10.0 * j2.stick));
    }
}

#[test]
fn the_slab_without_friction_is_the_plane_strain_run() {
    compare(false);
}

#[test]
fn the_slab_with_friction_is_the_plane_strain_run() {
    compare(true);
}

/// A block pressed on half of its top onto another, held in x only by the
/// interface's friction: the interface's force on A balances the load,
/// F = (0, p A_load, 0), and its moment about the z axis through the
/// centroid balances the load's, −F × (x_load − x_centroid); the supports
/// in z on A's end add forces along z only, no moment about z.
#[test]
fn the_force_and_moment_on_a_balance_an_eccentric_load() {
    let text = r#"
[model]
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
x = [0.0, 20.0]
nx = [4]
y = [-10.0, 0.0]
ny = [2]
[[mesh.interface]]
name = "joint"
upper = "top"
lower = "base"
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
weights = "consistent"
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
[solver]
increments = 2
residual_tolerance = 1e-10
"#;
    let (m, r) = run(text);
    let j = r.increments.last().unwrap().joints[0];
    let f = 100.0 * 10.0 * 10.0;
    let c = m.interfaces[0].moment_point;
    println!(
        "eccentric block: force on A {:?} N, moment {:?} N·mm about {c:?}; F = {f} N, F e = {} N·mm",
        j.force,
        j.moment,
        f * 5.0
    );
    assert!((c[0] - 10.0).abs() < 1e-12 && c[1].abs() < 1e-12 && (c[2] - 5.0).abs() < 1e-12);
    assert!((j.force[1] - f).abs() < 1e-8 * f, "{:?}", j.force);
    assert!(j.force[0].abs() < 1e-8 * f, "{:?}", j.force);
    assert!((j.normal_force - f).abs() < 1e-8 * f);
    // the load's moment about z through the centroid is F · 5 mm
    assert!(
        (j.moment[2] + 5.0 * f).abs() < 1e-8 * 5.0 * f,
        "{:?}",
        j.moment
    );
    contact_map_of_the_eccentric_block(&m, &r, j.normal_force);
}

/// The eccentric block's contact map: drawn on (x, z), its cells tile the
/// 20 × 10 mm face, Σ p A over its points is the joint's normal force, the
/// loaded half presses harder than the other, and a cell shows the point
/// nearest its centre (each of the 16 Gauss points of a face is some
/// cell's own).
fn contact_map_of_the_eccentric_block(m: &Model, r: &RunResult, normal_force: f64) {
    use asperity::files::output::contact_map::contact_maps;
    let maps = contact_maps(m, &r.final_state);
    assert_eq!(maps.len(), 1);
    let map = &maps[0];
    assert_eq!(map.labels, ("x (mm)".to_string(), "z (mm)".to_string()));
    let shoelace = |c: &[[f64; 2]]| {
        let n = c.len();
        (0..n)
            .map(|i| c[i][0] * c[(i + 1) % n][1] - c[(i + 1) % n][0] * c[i][1])
            .sum::<f64>()
            .abs()
            / 2.0
    };
    let tiled: f64 = map.cells.iter().map(|c| shoelace(&c.corners)).sum();
    assert!((tiled - 200.0).abs() < 1e-10, "{tiled}");
    let force: f64 = map.points.iter().map(|p| p.p_n * p.area).sum();
    assert!(
        (force - normal_force).abs() < 1e-10 * normal_force,
        "{force} {normal_force}"
    );
    let mean = |left: bool| {
        let sel: Vec<_> = map
            .points
            .iter()
            .filter(|p| (p.x[0] < 10.0) == left)
            .collect();
        sel.iter().map(|p| p.p_n * p.area).sum::<f64>() / sel.iter().map(|p| p.area).sum::<f64>()
    };
    println!(
        "contact map: Σ p A = {force} N, mean p under the load {} MPa, beyond {} MPa",
        mean(true),
        mean(false)
    );
    assert!(mean(true) > 1.5 * mean(false));
    let mut shown = vec![false; map.points.len()];
    for c in &map.cells {
        shown[c.point] = true;
    }
    assert!(shown.iter().all(|&s| s), "a Gauss point no cell shows");
    assert_eq!(map.cells.len(), map.points.len());
}
