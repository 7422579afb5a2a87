use super::*;

/// A slider on a base through a rough joint with friction, preloaded and
/// then dragged back and forth once (`plane`: "strain" or "axisymmetric",
/// `model`: more `[model]` keys, `rating`: the rating's keys).
fn model(plane: &str, model: &str, rating: &str) -> Result<Model> {
    let text = format!(
        r#"
[model]
plane = "{plane}"
{model}
[[mesh.block]]
body = "slider"
x = [10.0, 30.0]
nx = [4]
y = [0.0, 5.0]
ny = [1]
[[mesh.block]]
body = "base"
x = [10.0, 30.0]
nx = [4]
y = [-5.0, 0.0]
ny = [1]
[[mesh.interface]]
name = "way"
upper = "slider"
lower = "base"
[materials.slider]
young = 200000.0
poisson = 0.3
[materials.base]
young = 200000.0
poisson = 0.3
[history]
preload = [[0.0, 0.0], [1.0, 1.0]]
drive = [[1.0, 0.0], [2.0, 0.5], [3.0, -0.5], [4.0, 0.0]]
[interface.way]
law = "power"
c_n = 0.002
m = 0.5
[interface.way.tangential]
r = 0.9
s = 0.5
mu = 0.15
kp_ratio = 0.3
[[boundary]]
set = "base.bottom"
ux = 0.0
uy = 0.0
[[load]]
edges = "slider.top"
pressure = 20.0
history = "preload"
[[load]]
edges = "slider.top"
shear = 3.0
history = "drive"
[[rating]]
standard = "joint cycles"
interface = "way"
{rating}
"#
    );
    Model::parse(&text, "case.toml")
}

fn posed(m: &Model) -> Result<Posed> {
    let RatingSpec::Cycles(spec) = &m.ratings[0] else {
        panic!("not a cycles rating")
    };
    pose(m, spec, "rating[0]")
}

use crate::input::case::rating::RatingSpec;

/// A plane model's forces are for its thickness t: the part of width b is
/// b/t of it, times the joints it holds; an axisymmetric model is the whole
/// ring already: only the count scales it.
#[test]
fn the_part_is_the_model_scaled_by_width_over_thickness_or_the_ring_by_count() {
    let plane = model("strain", "thickness = 2.0", "width = 80.0\ncount = 3").unwrap();
    assert_eq!(posed(&plane).unwrap().scale, 80.0 / 2.0 * 3.0);
    let default = model("strain", "thickness = 2.0", "").unwrap();
    assert_eq!(posed(&default).unwrap().scale, 1.0);
    let ring = model("axisymmetric", "", "count = 12").unwrap();
    assert_eq!(posed(&ring).unwrap().scale, 12.0);
    let e = posed(&model("axisymmetric", "", "width = 80.0").unwrap())
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("width") && e.contains("whole ring"), "{e}");
}

/// The checks of a cycle: forces, stiffness and dissipation times the
/// scale, the slip in µm and the loss factor as the model's.
#[test]
fn a_cycle_s_checks_are_the_model_s_numbers_for_the_part() {
    let c = Cycle {
        start_increment: 11,
        end_increment: 41,
        start_time: 1.0,
        end_time: 4.0,
        dissipation: 0.0122,
        work: 0.0122,
        secant_stiffness: Some(2.78e5),
        force_range: [-54.0, 54.0],
        slip_range: [-2e-4, 2e-4],
        tip_slip: [-1.9e-4, 1.95e-4],
        force_scale: 1200.0,
        floor: 0.0,
        torque_range: [0.0; 2],
        twist_range: [0.0; 2],
        torsional_stiffness: None,
        tip_twist: [0.0; 2],
    };
    let spec: CyclesSpec =
        toml::from_str("interface = \"way\"\nmin_loss_factor = 0.2\nmax_stiffness = 1e4").unwrap();
    let checks = cycle_checks(&spec, 80.0, 1, &c, None);
    let by = |s: &str| checks.iter().find(|k| k.symbol == s).unwrap();
    assert_eq!(by("F_a").fe, Some(80.0 * 54.0));
    assert_eq!(by("u_a").fe, Some(1e3 * c.slip_amplitude()));
    assert_eq!(by("k_s").fe, Some(1e-3 * 80.0 * 2.78e5));
    assert_eq!(by("D").fe, Some(80.0 * 0.0122));
    assert_eq!(by("η").fe, c.loss_factor());
    assert!(checks
        .iter()
        .all(|k| k.cycle == Some(1) && k.handbook.is_none()));
    // η = 0.0122 / (π · 54 · 1.925e-4) = 0.374 ≥ 0.2; k_s = 22 240 N/µm > 10⁴
    assert_eq!(by("η").pass, Some(true));
    let upper: Vec<&Check> = checks.iter().filter(|k| k.symbol == "k_s").collect();
    assert_eq!(upper.len(), 2);
    assert_eq!(upper[1].pass, Some(false));
    assert!(upper[1].quantity.ends_with("at most"));
}
