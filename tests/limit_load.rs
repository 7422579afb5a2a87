//! Flat punch limit loads on a large, fine, perfectly plastic foundation.
//!
//! A rigid, smooth punch of half-width a is pressed into the foundation by a
//! prescribed settlement of the surface nodes under it (u_x free). The mean
//! pressure under the punch tends to the collapse pressure:
//! * plane strain, Prandtl: p = (2 + π) σ_Y/√3 = 582 MPa for σ_Y = 196 MPa;
//! * plane stress: p = 2 σ_Y/√3 = 226 MPa (the value quoted from Kachanov by
//!   Lee & Kwak and by the paper).
//! Plane strain uses 2×2 integration: full 3×3 integration locks under the
//! nearly incompressible plastic flow and overestimates the limit.

mod common;
use asperity::model::Model;
use asperity::solve::{self, Increment, Observer, State};

struct Quiet;
impl Observer for Quiet {
    fn increment(&mut self, _: &Model, _: &State, _: &Increment) -> asperity::Result<()> {
        Ok(())
    }
}

fn limit_pressure(plane: &str, integration: &str, settlement: f64) -> f64 {
    let a = 5.0;
    let text = format!(
        r#"
[model]
plane = "{plane}"
integration = "{integration}"
[[mesh.block]]
body = "foundation"
x = [0.0, 5.0, 50.0]
nx = [10, 14]
rx = [0.3, 12.0]
y = [-50.0, 0.0]
ny = [18]
ry = [0.08]
[materials.foundation]
young = 206000.0
poisson = 0.3
yield_stress = 196.0
hardening = 0.0
[[boundary]]
set = "foundation.left"
ux = 0.0
[[boundary]]
set = "foundation.bottom"
uy = 0.0
[[boundary]]
set = "foundation.right"
ux = 0.0
[[boundary]]
set = "foundation.top"
x_range = [0.0, {a}]
uy = {settlement}
[solver]
increments = 30
first_increment = 0.02
"#
    );
    let model = common::model(&text);
    let r = solve::run(&model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"));
    let last = r.increments.last().unwrap();
    assert!(last.load_factor == 1.0);
    // reaction on the punch: sum of the residual at the prescribed settlement dofs
    last.measures.prescribed_reaction.abs() / (a * model.thickness)
}

#[test]
fn plane_strain_prandtl_limit() {
    let k = 196.0 / 3f64.sqrt();
    let p = limit_pressure("strain", "reduced", -0.25);
    let prandtl = (2.0 + std::f64::consts::PI) * k;
    eprintln!("plane strain limit: {p:.1} MPa, Prandtl {prandtl:.1} MPa");
    assert!(
        (p - prandtl).abs() < 0.05 * prandtl,
        "p = {p}, Prandtl = {prandtl}"
    );
}

#[test]
fn plane_stress_limit() {
    let p = limit_pressure("stress", "full", -0.25);
    let limit = 2.0 * 196.0 / 3f64.sqrt();
    eprintln!("plane stress limit: {p:.1} MPa, 2σ_Y/√3 = {limit:.1} MPa");
    assert!((p - limit).abs() < 0.05 * limit, "p = {p}, limit = {limit}");
}
