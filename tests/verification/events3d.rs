//! The interface events in 3D, on a block pressed onto a base through a
//! Winkler interface (the power law with m = 1, u_N = c_N p: a rigid block
//! on it has a linear pressure): its first opening under a growing
//! eccentric load against the kern of the rectangle (e = L / 6), its full
//! separation when pulled off, and its full slip when pushed sideways
//! against μ F_N.

use crate::common;
use asperity::solve::events::{Event, Kind};
use asperity::solve::RunResult;
use common::Quiet;

/// The block (20 × 10 mm in x, z; 10 mm high; stiff against its
/// interface) on its base, with `tail` appended (its histories and loads,
/// the supports of the block, a tangential law).
fn block(tail: &str) -> String {
    format!(
        r#"
[model]
plane = "3d"
[mesh]
extrude = {{ z = [0.0, 10.0], nz = [2] }}
[[mesh.block]]
body = "top"
x = [0.0, 20.0]
nx = [8]
y = [0.0, 10.0]
ny = [2]
[[mesh.block]]
body = "base"
x = [0.0, 20.0]
nx = [8]
y = [-10.0, 0.0]
ny = [2]
[[mesh.interface]]
name = "joint"
upper = "top"
lower = "base"
[materials.top]
young = 2000000.0
poisson = 0.3
yield_stress = 10000.0
hardening = 20000.0
[materials.base]
young = 2000000.0
poisson = 0.3
yield_stress = 10000.0
hardening = 20000.0
[interface.joint]
law = "power"
c_n = 0.01
m = 1.0
weights = "consistent"
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
{tail}
[solver]
increments = 10
residual_tolerance = 1e-10
[output]
event_tolerance = 1e-5
"#
    )
}

fn run(text: &str) -> RunResult {
    let model = common::model(text);
    asperity::app::driver::solve(&model, &mut Quiet).unwrap()
}

fn event(r: &RunResult, kind: Kind) -> &Event {
    r.events
        .iter()
        .find(|e| e.kind == kind)
        .unwrap_or_else(|| panic!("no {} among {:?}", kind.name(), r.events))
}

/// Pressed by 10 MPa, then by up to 60 MPa more on the half x < 10: the
/// resultant's eccentricity e = 5 F₂ / (F₁ + F₂) about the centre reaches
/// the kern L / 6 = 10/3 mm at F₂ = 2 F₁, q₂ = 40 MPa, t = 1 + 40/60; the
/// pressure there is zero at x = 20, the far edge, where the face opens.
#[test]
fn a_block_opens_at_the_kern_of_its_face() {
    let r = run(&block(
        r#"[history]
press = [[0.0, 0.0], [1.0, 1.0], [2.0, 1.0]]
second = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]
[[load]]
faces = "top.top"
pressure = 10.0
history = "press"
[[load]]
faces = "top.top"
pressure = 60.0
x_range = [0.0, 10.0]
history = "second"
[[boundary]]          # one line of the end held along x: the block tilts freely
set = "top.left"
ux = 0.0
y_range = [0.0, 0.0]"#,
    ));
    let e = event(&r, Kind::FirstOpening);
    let expected = 1.0 + 40.0 / 60.0;
    println!(
        "first opening at t = {} (kern: {expected}), at x = {}, y = {}, z = {}; F_N {} N",
        e.load_factor, e.place[0], e.place[1], e.place[2], e.values[2]
    );
    assert!(e.converged);
    assert!(
        (e.load_factor - expected).abs() < 0.01 * (expected - 1.0),
        "{e:?}"
    );
    assert!((e.place[0] - 20.0).abs() < 1e-9, "{e:?}");
    // in 3D the place's third value is the pair's z (on the face's far edge)
    assert!((0.0..=10.0).contains(&e.place[2]), "{e:?}");
    // F_N at the event: the two loads, 10 · 200 + q₂ · 100 N
    let f_n = 2000.0 + 60.0 * (e.load_factor - 1.0) * 100.0;
    assert!((e.values[2] - f_n).abs() < 1e-6 * f_n, "{e:?}");
}

/// Its top pressed down 0.1 mm (p = 0.1 / c_N = 10 MPa), then lifted to
/// 0.1 mm above where it started: the face lets go everywhere at once when
/// the top is back where it started, t = 1.5 (first opening and full
/// separation at the same load).
#[test]
fn a_block_lifted_off_separates_where_it_started() {
    let r = run(&block(
        r#"[history]
lift = [[0.0, 0.0], [1.0, 1.0], [2.0, -1.0]]
[[boundary]]
set = "top.top"
uy = -0.1
history = "lift"
[[boundary]]
set = "top.left"
ux = 0.0
y_range = [0.0, 0.0]"#,
    ));
    let s = event(&r, Kind::FullSeparation);
    let o = event(&r, Kind::FirstOpening);
    println!(
        "full separation at t = {}, first opening at t = {}",
        s.load_factor, o.load_factor
    );
    for e in [s, o] {
        assert!(e.converged);
        assert!((e.load_factor - 1.5).abs() <= 2e-5, "{e:?}");
    }
}

/// Pressed by 10 MPa (F_N = 2000 N), then its left end pushed 0.1 mm
/// along x, held by friction alone (μ = 0.3, β = 1): it slips as a whole
/// with F_T = μ F_N = 600 N.
#[test]
fn a_block_pushed_sideways_slips_at_mu_times_its_clamp_force() {
    let r = run(&block(
        r#"[history]
press = [[0.0, 0.0], [1.0, 1.0], [2.0, 1.0]]
second = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]
[[load]]
faces = "top.top"
pressure = 10.0
history = "press"
[[boundary]]
set = "top.left"
ux = 0.1
history = "second"
[interface.joint.tangential]
r = 0.9
s = 0.5
kp_ratio = 1.0
mu = 0.3
beta = 1.0
n = 275.0
yield_ratio = 0.625"#,
    ));
    let e = event(&r, Kind::FullSlip);
    println!(
        "full slip at t = {}, F_N {} N, F_T {} N (μ F_N = {} N), at x = {}",
        e.load_factor,
        e.values[2],
        e.values[3],
        0.3 * e.values[2],
        e.place[0]
    );
    assert!(e.converged);
    assert!((e.values[2] - 2000.0).abs() < 1e-6 * 2000.0, "{e:?}");
    assert!(
        (e.values[3].abs() - 0.3 * e.values[2]).abs() < 0.01 * 600.0,
        "{e:?}"
    );
}
