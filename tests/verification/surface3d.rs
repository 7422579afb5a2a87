//! Node-to-surface springs (issue 47) on meshes that match: a 3D
//! interface declared `matching = false` whose two sides happen to be meshed
//! alike projects every slave point onto its partner's place on the
//! coincident master face (the same ξ, normal and area, a zero geometric
//! gap), so it must give the matching run's answers to round-off. On
//! cases/punch-slab-3d (swept along z, plastic, friction) and on a punch
//! revolved into O-grid cores on the axis, where it also checks that the
//! matching interface's core faces pair node for node.

use crate::common;
use asperity::model::Model;
use asperity::solve::RunResult;
use common::Quiet;

fn run(text: &str) -> (Model, RunResult) {
    let model = common::model(text);
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"));
    (model, r)
}

/// The case text with its interface declared meshed apart.
fn apart(text: &str) -> String {
    let out = text.replacen(
        "lower = \"foundation\"\n",
        "lower = \"foundation\"\nmatching = false\n",
        1,
    );
    assert_ne!(out, text);
    out
}

/// Runs the text as it is and declared non-matching; the largest
/// difference of the displacements (relative to the largest) and of the
/// joint's normal and tangential forces and dissipation, printed under
/// `name`.
fn compare(name: &str, text: &str) -> [f64; 4] {
    let (m1, r1) = run(text);
    let (m2, r2) = run(&apart(text));
    assert!(m1.interfaces[0]
        .points
        .iter()
        .all(|p| p.geometric_gap().is_none()));
    assert!(m2.interfaces[0]
        .points
        .iter()
        .all(|p| p.geometric_gap().is_some()));
    assert_eq!(m1.num_dofs(), m2.num_dofs());
    let (u1, u2) = (&r1.final_state.u, &r2.final_state.u);
    let scale = u1.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let du = u1
        .iter()
        .zip(u2)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale;
    let (j1, j2) = (
        r1.increments.last().unwrap().joints[0],
        r2.increments.last().unwrap().joints[0],
    );
    let rel = |a: f64, b: f64| (a - b).abs() / a.abs().max(b.abs()).max(1e-300);
    let out = [
        du,
        rel(j1.normal_force, j2.normal_force),
        rel(j1.tangential_force, j2.tangential_force),
        rel(j1.dissipation, j2.dissipation),
    ];
    println!(
        "{name}: matching = false vs matching: u {:.1e} of {scale:.3e} mm, F_N {:.1e} ({:.6e} N), F_T {:.1e}, D {:.1e}; {} and {} springs",
        out[0],
        out[1],
        j1.normal_force,
        out[2],
        out[3],
        m1.interfaces[0].points.len(),
        m2.interfaces[0].points.len()
    );
    out
}

/// cases/punch-slab-3d, consistent and lumped weights.
#[test]
fn a_slab_declared_meshed_apart_is_the_matching_slab() {
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-slab-3d/case.toml")).unwrap();
    for weights in ["consistent", "lumped"] {
        let text = text.replace(
            "weights = \"consistent\"",
            &format!("weights = \"{weights}\""),
        );
        let d = compare(&format!("punch-slab-3d, {weights}"), &text);
        assert!(d[0] < 1e-8, "{d:?}");
        assert!(d[1] < 1e-8 && d[2] < 1e-8 && d[3] < 1e-8, "{d:?}");
    }
}

/// A punch on a foundation, both reaching the axis, revolved through 90°
/// (a quarter with its symmetry planes): the matching interface through the
/// cores and the same declared meshed apart agree to round-off; the
/// interface carries the punch's load (on its top as meshed: the quarter
/// disk of quadratic arcs), and the top's settlement on the axis is the
/// axisymmetric model's within 1e-3 (measured 1.1e-5).
#[test]
fn a_punch_revolved_into_cores_is_the_same_matching_or_declared_apart() {
    let text = "\
[model]
plane = \"3d\"

[mesh]
revolve = { angle = 90.0, n = 4 }

[[mesh.block]]
body = \"punch\"
x = [0.0, 10.0]
nx = [4]
y = [0.0, 5.0]
ny = [2]

[[mesh.block]]
body = \"foundation\"
x = [0.0, 10.0, 20.0]
nx = [4, 2]
y = [-10.0, 0.0]
ny = [3]

[[mesh.interface]]
name = \"contact\"
upper = \"punch\"
lower = \"foundation\"

[materials.punch]
young = 206000.0
poisson = 0.3

[materials.foundation]
young = 206000.0
poisson = 0.3

[interface.contact]
law = \"power\"
c_n = 0.001
m = 0.5
weights = \"consistent\"

[interface.contact.tangential]
r = 0.9
s = 0.5
kp_ratio = 1.0
mu = 0.2
beta = 1.0
n = 275.0

[[boundary]]
set = \"punch.theta0\"
uz = 0.0

[[boundary]]
set = \"foundation.theta0\"
uz = 0.0

[[boundary]]
set = \"punch.theta1\"
ux = 0.0

[[boundary]]
set = \"foundation.theta1\"
ux = 0.0

[[boundary]]
set = \"foundation.bottom\"
uy = 0.0

[[load]]
faces = \"punch.top\"
pressure = 100.0

[solver]
increments = 2
";
    let d = compare("revolved punch", text);
    assert!(d[0] < 1e-8 && d[1] < 1e-8, "{d:?}");
    // the interface carries the quarter's load: 100 MPa on the top, a
    // quarter disk bounded by four quadratic arcs of 22.5° through r = 10
    // (each a triangle ½ r² sin φ and a parabolic segment ⅔ c h, c = 2r
    // sin(φ/2), h = r (1 − cos(φ/2)))
    let (m, r) = run(text);
    let phi = std::f64::consts::PI / 8.0;
    let arc = 0.5 * 100.0 * phi.sin()
        + 2.0 / 3.0 * (20.0 * (phi / 2.0).sin()) * 10.0 * (1.0 - (phi / 2.0).cos());
    let load = 100.0 * 4.0 * arc;
    let f = r.increments.last().unwrap().joints[0].normal_force;
    assert!(common::rel(f, load) < 1e-8, "{f} vs {load}");
    // the core's contact faces pair coincident nodes
    let iface = &m.mesh.interfaces[0];
    assert!(iface.nonmatching_faces.is_none() && !iface.faces.is_empty());
    // the axisymmetric model of the layout: the punch's mean settlement
    let axi: String = text
        .split("\n\n")
        .filter(|b| !b.contains(".theta"))
        .map(|b| {
            b.replace("plane = \"3d\"", "plane = \"axisymmetric\"")
                .replace("faces = \"punch.top\"", "edges = \"punch.top\"")
                .lines()
                .filter(|l| !l.starts_with("revolve") && *l != "[mesh]")
                .collect::<Vec<_>>()
                .join("\n")
        })
        .collect::<Vec<_>>()
        .join("\n\n");
    let (m2, r2) = run(&axi);
    let f2 = r2.increments.last().unwrap().joints[0].normal_force;
    assert!(
        common::rel(f2, 10_000.0 * std::f64::consts::PI) < 1e-8,
        "{f2}"
    );
    // the settlement of the punch's top on the axis
    let on_axis = |m: &Model| {
        let punch = m.mesh.bodies.iter().position(|b| b == "punch").unwrap();
        let bodies = m.mesh.node_bodies();
        (0..m.mesh.nodes.len())
            .find(|&n| bodies[n] == punch && m.mesh.nodes[n] == [0.0, 5.0, 0.0])
            .unwrap()
    };
    let s3 = r.final_state.u[3 * on_axis(&m) + 1];
    let s2 = r2.final_state.u[2 * on_axis(&m2) + 1];
    println!(
        "revolved punch: the top's settlement on the axis {s3:.6e} mm, axisymmetric {s2:.6e} mm"
    );
    assert!(common::rel(s3, s2) < 1e-3, "{s3} vs {s2}");
}

/// A shaft in a hub meshed apart along its bore (4 and 3 elements up the
/// fit), revolved through 90° (the shaft's axis column an O-grid core): the
/// node-to-surface springs on the cylinder r = 10 carry what the
/// axisymmetric model of the layout's node-to-segment springs carry, the
/// normal force and the mean approach within 1e-4 (measured 1.2e-5 and
/// 3.3e-6).
#[test]
fn a_shaft_in_a_hub_meshed_apart_revolved_is_its_axisymmetric_model() {
    let text = "\
[model]
plane = \"3d\"

[mesh]
revolve = { angle = 90.0, n = 6 }

[[mesh.block]]
body = \"shaft\"
x = [0.0, 10.0]
nx = [3]
y = [0.0, 20.0]
ny = [4]

[[mesh.block]]
body = \"hub\"
x = [10.0, 25.0]
nx = [3]
y = [0.0, 20.0]
ny = [3]

[[mesh.interface]]
name = \"fit\"
left = \"shaft\"
right = \"hub\"
matching = false

[materials.shaft]
young = 200000.0
poisson = 0.3

[materials.hub]
young = 200000.0
poisson = 0.3

[interface.fit]
law = \"power\"
c_n = 0.002
m = 0.5
weights = \"consistent\"

[[boundary]]
set = \"shaft.theta0\"
uz = 0.0

[[boundary]]
set = \"hub.theta0\"
uz = 0.0

[[boundary]]
set = \"shaft.theta1\"
ux = 0.0

[[boundary]]
set = \"hub.theta1\"
ux = 0.0

[[boundary]]
set = \"shaft.bottom\"
uy = 0.0

[[boundary]]
set = \"hub.bottom\"
uy = 0.0

[[load]]
faces = \"hub.right\"
pressure = 100.0

[solver]
increments = 2
";
    let axi: String = text
        .split("\n\n")
        .filter(|b| !b.contains(".theta"))
        .map(|b| {
            b.replace("plane = \"3d\"", "plane = \"axisymmetric\"")
                .replace("faces = \"hub.right\"", "edges = \"hub.right\"")
                .lines()
                .filter(|l| !l.starts_with("revolve") && *l != "[mesh]")
                .collect::<Vec<_>>()
                .join("\n")
        })
        .collect::<Vec<_>>()
        .join("\n\n");
    let (m3, r3) = run(text);
    let (m2, r2) = run(&axi);
    assert!(m3.interfaces[0]
        .points
        .iter()
        .all(|p| p.geometric_gap().is_some()));
    assert!(m2.interfaces[0]
        .points
        .iter()
        .all(|p| p.geometric_gap().is_some()));
    let (j3, j2) = (
        r3.increments.last().unwrap().joints[0],
        r2.increments.last().unwrap().joints[0],
    );
    let (f, a) = (
        common::rel(4.0 * j3.normal_force, j2.normal_force),
        common::rel(j3.mean_approach, j2.mean_approach),
    );
    println!(
        "revolved fit meshed apart: F_N {:.6e} N (× 4) vs axisymmetric {:.6e} N ({f:.1e}), mean approach {:.6e} vs {:.6e} mm ({a:.1e})",
        4.0 * j3.normal_force,
        j2.normal_force,
        j3.mean_approach,
        j2.mean_approach
    );
    assert!(j2.normal_force > 1e4);
    assert!(f < 1e-4 && a < 1e-4, "{f} {a}");
}
