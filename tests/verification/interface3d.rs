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
