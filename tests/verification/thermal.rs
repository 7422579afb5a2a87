//! Uniform body temperatures (`[[temperature]]`, docs/theory.md "Thermal
//! strain") against closed forms.
//!
//! * A body free to expand (plane stress, axisymmetric with and without
//!   twist): a uniform ΔT strains it by α ΔT in every direction with no
//!   stress; u = α ΔT x, exactly for any mesh (a linear field).
//! * The note's item 4a (issue 46), a plane-strain block free in its plane
//!   and held along z by ε_zz = 0 (the out-of-plane direction is the
//!   restrained one: held in x in its plane instead, the stress would be
//!   biaxial, −E α ΔT/(1 − ν) in x and z, and yield at (1 − ν) ΔT_y):
//!   σ_zz = −E α ΔT, first yield at ΔT_y = σ_Y/(E α) = 103.52 K, at 200 K
//!   −σ_Y perfectly plastic (ε^p_zz = −(α ΔT − σ_Y/E)) and −252.33 MPa with
//!   linear hardening (E_t = 2100 MPa, H = E E_t/(E − E_t)); cooled back, the
//!   residual stress E α ΔT − |σ| = +233.00 and +230.67 MPa (elastic
//!   unloading, 200 K < 2 ΔT_y). Uniform, so exact to the solver's
//!   tolerance.

use crate::common;
use asperity::model::Model;
use asperity::physics::material::PointState;
use asperity::solve::{Increment, Observer, RunResult, State};

const E: f64 = 210_000.0;
const NU: f64 = 0.3;
const ALPHA: f64 = 11.5e-6;
const SY: f64 = 250.0;

/// Every converged increment's pseudo-time, displacements and Gauss states.
#[derive(Default)]
struct Capture(Vec<(f64, Vec<f64>, Vec<PointState>)>);
impl Observer for Capture {
    fn increment(&mut self, _: &Model, s: &State, inc: &Increment) -> asperity::error::Result<()> {
        self.0
            .push((inc.load_factor, s.u.clone(), s.gauss.iter().collect()));
        Ok(())
    }
}

fn solve(text: &str) -> (Model, RunResult, Capture) {
    let model = common::model(text);
    let mut c = Capture::default();
    let r = asperity::app::driver::solve(&model, &mut c).unwrap_or_else(|e| panic!("{e}"));
    (model, r, c)
}

/// Largest |u − α ΔT x| over every node and in-plane component, and the
/// largest |σ| of every Gauss point.
fn free_error(model: &Model, u: &[f64], gauss: &[PointState], strain: f64) -> (f64, f64) {
    let k = model.node_dofs().per_node();
    let mut du = 0.0f64;
    for (n, x) in model.mesh.nodes.iter().enumerate() {
        for c in 0..2 {
            du = du.max((u[k * n + c] - strain * x[c]).abs());
        }
        if k == 3 {
            du = du.max(u[k * n + 2].abs());
        }
    }
    let ds = gauss
        .iter()
        .flat_map(|g| g.stress)
        .fold(0.0f64, |a, s| a.max(s.abs()));
    (du, ds)
}

fn free_case(plane: &str, twist: bool) -> String {
    let mut c = common::case().plane(plane);
    if twist {
        c = c.with("twist", true);
    }
    c = c
        .block("bar", [0.0, 10.0, 30.0], [2, 3], [0.0, 4.0, 8.0], [1, 2])
        .rx([1.0, 1.5])
        .material("bar", E, NU)
        .plastic(SY, 0.0)
        .with("expansion", ALPHA)
        .ux("bar.left", 0.0)
        .uy("bar.bottom", 0.0);
    if twist {
        c = c.with("rotation", 0.0);
    }
    c.raw("[[temperature]]")
        .with("body", "bar")
        .with("change", 80.0)
        .with("reference", 20.0)
        .solver("")
        .tolerances(1e-12, 1e-12)
        .no_vtu()
        .build()
}

/// Free expansion: no stress, u = α ΔT x (to 1e-10 of α ΔT L), in every
/// plane setting that leaves a body free (plane strain holds ε_zz: item 4a).
#[test]
fn a_body_free_to_expand_is_unstressed() {
    for (plane, twist) in [
        ("stress", false),
        ("axisymmetric", false),
        ("axisymmetric", true),
    ] {
        let (model, r, _) = solve(&free_case(plane, twist));
        let g: Vec<PointState> = r.final_state.gauss.iter().collect();
        let strain = ALPHA * 80.0;
        let (du, ds) = free_error(&model, &r.final_state.u, &g, strain);
        assert!(
            du < 1e-10 * strain * 30.0,
            "{plane} twist {twist}: |u − α ΔT x| = {du:e}"
        );
        // stress against E α ΔT (193 MPa)
        assert!(
            ds < 1e-8 * E * strain,
            "{plane} twist {twist}: |σ| = {ds:e}"
        );
        assert!(r.first_yield.is_none());
    }
}

/// Item 4a: the plane-strain block heated by 200 K and cooled back.
fn held_block(hardening: f64) -> (Model, RunResult, Capture) {
    let text = common::case()
        .plane("strain")
        .block("bar", [0.0, 20.0], [2], [0.0, 6.0], [1])
        .material("bar", E, NU)
        .plastic(SY, hardening)
        .with("expansion", ALPHA)
        .ux("bar.left", 0.0)
        .uy("bar.bottom", 0.0)
        .raw("[[temperature]]")
        .with("body", "bar")
        .with("change", 200.0)
        .with("history", [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])
        .solver("")
        .tolerances(1e-12, 1e-12)
        .no_vtu()
        .build();
    solve(&text)
}

/// The state of every Gauss point at pseudo-time t (one of the increments).
fn at(c: &Capture, t: f64) -> &[PointState] {
    &c.0.iter()
        .find(|s| s.0 == t)
        .unwrap_or_else(|| panic!("no increment at t = {t}"))
        .2
}

/// Every Gauss point's component i within rel of `want`.
fn all_near(g: &[PointState], i: usize, want: f64, rel: f64, what: &str) {
    for (k, p) in g.iter().enumerate() {
        let s = p.stress[i];
        assert!(
            (s - want).abs() <= rel * want.abs(),
            "{what}: point {k} σ[{i}] = {s}, closed form {want}"
        );
        for j in [0, 1, 2] {
            assert!(
                p.stress[j].abs() < 1e-8 * SY,
                "{what}: σ[{j}] = {}",
                p.stress[j]
            );
        }
    }
}

#[test]
fn held_block_yields_at_the_closed_form_and_keeps_its_residual_stress() {
    let dty = SY / (E * ALPHA);
    assert!((dty - 103.52).abs() < 0.005);
    let dt = 200.0;
    for (hardening, hot, cold) in [
        (0.0, -250.0, 233.00),
        (E * 2100.0 / (E - 2100.0), -252.33, 230.67),
    ] {
        let (_, r, c) = held_block(hardening);
        let fy = r.first_yield.as_ref().expect("the block yields");
        let dt_y = fy.load_factor * dt;
        assert!(
            (dt_y - dty).abs() < 1e-6 * dty,
            "H {hardening}: first yield at ΔT = {dt_y} K, closed form {dty}"
        );
        // the closed forms exactly (the note's numbers are rounded to 0.01)
        let top = (E * hardening * ALPHA * dt + E * SY) / (E + hardening);
        assert!((top + hot).abs() < 0.005, "{top} vs {hot}");
        let res = E * ALPHA * dt - top;
        assert!((res - cold).abs() < 0.005, "{res} vs {cold}");
        all_near(at(&c, 1.0), 3, -top, 1e-6, "heated");
        all_near(at(&c, 2.0), 3, res, 1e-6, "cooled back");
        // plastic strain: ε^p_zz = −(α ΔT − |σ|/E), the in-plane ones half of it
        let ep = -(ALPHA * dt - top / E);
        for p in at(&c, 2.0) {
            // εᵖ_zz in the packed layout (restart files' order)
            let pzz = p.pack()[7];
            assert!(
                (pzz - ep).abs() < 1e-6 * ep.abs(),
                "ε^p_zz = {pzz}, closed form {ep}"
            );
        }
    }
}

/// The held block of [`held_block`] with a Young's modulus and a yield stress
/// that fall with temperature (`young_table`, `yield_table`: E(T) = E (1 −
/// 5e-4 (T − 20)), σ_Y(T) = σ_Y (1 − 1e-3 (T − 20)), linear between rows at
/// 0 and 300 °C), heated from 20 °C by 160 K and cooled back. Uniaxial along
/// z, σ_zz = E(T) (−α ΔT − εᵖ_zz) (the total form: the stress of a held
/// body falls with its modulus), so
/// - first yield where E(T) α ΔT = σ_Y(T): the smaller root of
///   −E α a ΔT² + (E α + σ_Y b) ΔT − σ_Y = 0 (a = 5e-4, b = 1e-3), 98.18 K;
/// - hot (perfectly plastic), σ_zz = −σ_Y(180 °C) = −210 MPa, εᵖ_zz = −(α ΔT −
///   σ_Y(T)/E(T));
/// - cooled back elastically, the residual E (α ΔT − σ_Y(T)/E(T)) = 158.14 MPa.
#[test]
fn held_block_with_temperature_dependent_modulus_and_yield_stress() {
    let (a, b) = (5e-4, 1e-3);
    let e_at = |t: f64| E * (1.0 - a * (t - 20.0));
    let s_at = |t: f64| SY * (1.0 - b * (t - 20.0));
    let dt = 160.0;
    let text = common::case()
        .plane("strain")
        .block("bar", [0.0, 20.0], [2], [0.0, 6.0], [1])
        .material("bar", E, NU)
        .plastic(SY, 0.0)
        .with("expansion", ALPHA)
        .with("young_table", [[0.0, e_at(0.0)], [300.0, e_at(300.0)]])
        .with("yield_table", [[0.0, s_at(0.0)], [300.0, s_at(300.0)]])
        .ux("bar.left", 0.0)
        .uy("bar.bottom", 0.0)
        .raw("[[temperature]]")
        .with("body", "bar")
        .with("change", dt)
        .with("reference", 20.0)
        .with("history", [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])
        .solver("")
        .tolerances(1e-12, 1e-12)
        .no_vtu()
        .build();
    let (model, r, c) = solve(&text);
    // the material at 180 °C
    let hot = model.material_at(0, 1.0);
    assert!((hot.young - e_at(180.0)).abs() < 1e-9 * E);
    assert!((hot.yield_stress - s_at(180.0)).abs() < 1e-12 * SY);
    let ea = E * ALPHA;
    let q = ea + SY * b;
    let dty = (q - (q * q - 4.0 * ea * a * SY).sqrt()) / (2.0 * ea * a);
    let fy = r.first_yield.as_ref().expect("the block yields");
    eprintln!(
        "first yield at ΔT = {:.6} K, closed form {dty:.6} K",
        fy.load_factor * dt
    );
    assert!((fy.load_factor * dt - dty).abs() < 1e-6 * dty);
    let top = s_at(20.0 + dt);
    all_near(at(&c, 1.0), 3, -top, 1e-6, "heated");
    let ep = -(ALPHA * dt - top / e_at(20.0 + dt));
    let res = -E * ep;
    eprintln!("hot {:.4} MPa, residual {res:.4} MPa", -top);
    all_near(at(&c, 2.0), 3, res, 1e-6, "cooled back");
    // on the way down: elastic, σ_zz = E(T) (−α ΔT − εᵖ_zz)
    for (t, _, g) in &c.0 {
        if *t > 1.0 && *t < 2.0 {
            let d = dt * (2.0 - t);
            let want = e_at(20.0 + d) * (-ALPHA * d - ep);
            all_near(g, 3, want, 1e-6, "cooling");
        }
    }
}

/// A temperature field: a solid cylinder 0 ≤ r ≤ b held between two
/// frictionless planes (ε_z = 0) with ΔT(r) = T₀ + T₁ r/b, T₀ = 100 K, T₁ =
/// −80 K, given three ways: the table along x (r in axisymmetry) [[0, 1], [b,
/// 0.2]] times 100 K, the same table along r, and the expression
/// `field = "1 - 0.8*r/30"`. Timoshenko & Goodier § 151 (plane strain, ε_z = 0): with
/// k = α E/(1 − ν), σ_r = k T₁ (1 − r/b)/3, σ_θ = k T₁ (1/3 − 2r/(3b)),
/// σ_z = k (ν (T₀ + 2T₁/3) − T₀ − T₁ r/b). u(r) is quadratic in r, which the
/// element holds: every Gauss point to 1e-9 of the largest stress, each way.
#[test]
fn a_cylinder_with_a_radial_temperature_field_matches_the_closed_form() {
    let b = 30.0;
    let (t0, t1) = (100.0, -80.0);
    let ways: [(&str, &[(&str, &str)]); 3] = [
        (
            "table along x",
            &[("along", "\"x\""), ("profile", "[[0.0, 1.0], [30.0, 0.2]]")],
        ),
        (
            "table along r",
            &[("along", "\"r\""), ("profile", "[[0.0, 1.0], [30.0, 0.2]]")],
        ),
        ("expression", &[("field", "\"1 - 0.8*r/30\"")]),
    ];
    for (way, keys) in ways {
        let mut c = common::case()
            .plane("axisymmetric")
            .block("bar", [0.0, b], [6], [0.0, 5.0], [1])
            .material("bar", E, NU)
            .with("expansion", ALPHA)
            .uy("bar.bottom", 0.0)
            .uy("bar.top", 0.0)
            .raw("[[temperature]]")
            .with("body", "bar")
            .with("change", t0);
        for (k, v) in keys {
            c = c.raw(&format!("{k} = {v}"));
        }
        let text = c
            .solver("increments = 1\nstep_control = \"fixed\"")
            .tolerances(1e-12, 1e-12)
            .no_vtu()
            .build();
        let (model, r, _) = solve(&text);
        let k = ALPHA * E / (1.0 - NU);
        let (mut err, mut scale) = (0.0f64, 0.0f64);
        for e in 0..model.mesh.elements.len() {
            for (ip, g) in model.points(e).enumerate() {
                let r_ip = model.point_x(e, ip)[0];
                let s = r.final_state.gauss.get(g).stress;
                let want = [
                    k * t1 * (1.0 - r_ip / b) / 3.0,
                    k * (NU * (t0 + 2.0 * t1 / 3.0) - t0 - t1 * r_ip / b),
                    0.0,
                    k * t1 * (1.0 / 3.0 - 2.0 * r_ip / (3.0 * b)),
                ];
                for c in 0..4 {
                    err = err.max((s[c] - want[c]).abs());
                    scale = scale.max(want[c].abs());
                }
            }
        }
        eprintln!(
            "radial field ({way}): error {:.2e} of {scale:.3} MPa",
            err / scale
        );
        assert!(err < 1e-9 * scale, "{way}: {err} of {scale}");
    }
}

/// A free 3D block (held against rigid motion only) heated by 60 K times
/// the field `keys` give: its displacements and the largest |σ|.
fn free_solid(keys: &[(&str, &str)]) -> (Vec<f64>, f64) {
    let mut c = common::case()
        .plane("3d")
        .raw("[mesh]\nextrude = { z = [0.0, 6.0], nz = [2] }")
        .block("bar", [0.0, 20.0], [3], [0.0, 8.0], [2])
        .material("bar", E, NU)
        .with("expansion", ALPHA)
        // six constraints, the rigid motions: a corner held, the far corner
        // along x held in y and z, the corner along y in z
        .raw("[[boundary]]\nset = \"bar.left\"\nux = 0.0\ny_range = [0.0, 0.0]\nz_range = [0.0, 0.0]\nuy = 0.0\nuz = 0.0")
        .raw("[[boundary]]\nset = \"bar.right\"\ny_range = [0.0, 0.0]\nz_range = [0.0, 0.0]\nuy = 0.0\nuz = 0.0")
        .raw("[[boundary]]\nset = \"bar.left\"\ny_range = [8.0, 8.0]\nz_range = [0.0, 0.0]\nuz = 0.0")
        .raw("[[temperature]]")
        .with("body", "bar")
        .with("change", 60.0);
    for (k, v) in keys {
        c = c.raw(&format!("{k} = {v}"));
    }
    let text = c
        .solver("increments = 1\nstep_control = \"fixed\"")
        .tolerances(1e-10, 1e-10)
        .no_vtu()
        .build();
    let (_, r, _) = solve(&text);
    let worst = (r.final_state.gauss.iter())
        .flat_map(|g| g.stress)
        .fold(0.0f64, |a, s| a.max(s.abs()));
    (r.final_state.u.clone(), worst)
}

/// The free 3D block of [`free_solid`] with a temperature that rises
/// linearly along x, given as an expression (`field = "0.5 + x/20"`) and as
/// the table along x [[0, 0.5], [20, 1.5]] (times 60 K): the two are one
/// field, so one solution to round-off (1e-12 of the largest displacement),
/// and unstressed ([`a_free_solid_with_a_linear_temperature_field_is_unstressed`]).
#[test]
fn a_field_given_as_an_expression_equals_the_same_field_as_a_table() {
    let (table, _) = free_solid(&[("along", "\"x\""), ("profile", "[[0.0, 0.5], [20.0, 1.5]]")]);
    let (expr, worst) = free_solid(&[("field", "\"0.5 + x/20\"")]);
    let scale = table.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let diff = (table.iter().zip(&expr)).fold(0.0f64, |a, (p, q)| a.max((p - q).abs()));
    eprintln!("expression vs table: |Δu| {diff:.2e} of {scale:.3e} mm, |σ| {worst:.2e} MPa");
    assert!(scale > 1e-3, "{scale}");
    assert!(diff < 1e-12 * scale, "{diff} of {scale}");
    assert!(worst < 1e-8 * E * ALPHA * 90.0, "{worst}");
}

/// A free 3D block (held against rigid motion only) with a temperature that
/// rises linearly along x (profile [[0, 0.5], [20, 1.5]] times 60 K): a
/// linear field's thermal strain is compatible, so the body bends and
/// stretches unstressed, for any mesh.
#[test]
fn a_free_solid_with_a_linear_temperature_field_is_unstressed() {
    let (_, worst) = free_solid(&[("along", "\"x\""), ("profile", "[[0.0, 0.5], [20.0, 1.5]]")]);
    eprintln!(
        "3D linear field: largest |σ| {worst:.3e} MPa (E α ΔT = {:.1} MPa)",
        E * ALPHA * 90.0
    );
    assert!(worst < 1e-8 * E * ALPHA * 90.0, "{worst}");
}

/// r in `field` (and in `along = "r"`) is the distance from the model's
/// axis, as a speed's: |x| in axisymmetry, √(x² + y²) in a plane model (about
/// z), √(x² + z²) in 3D (about y). The free thermal strain at a point is α ΔT
/// times the field's value there, the expression's and the table's alike.
#[test]
fn r_is_the_distance_from_the_model_axis() {
    let field = |keys: &[(&str, &str)], plane: &str| {
        let mut c = common::case().plane(plane);
        if plane == "3d" {
            c = c
                .raw("[mesh]\nextrude = { z = [0.0, 10.0], nz = [1] }")
                .raw("[[boundary]]\nset = \"bar.left\"\nuz = 0.0");
        }
        c = c
            .block("bar", [0.0, 10.0], [1], [0.0, 10.0], [1])
            .material("bar", E, NU)
            .with("expansion", ALPHA)
            .ux("bar.left", 0.0)
            .uy("bar.bottom", 0.0)
            .raw("[[temperature]]")
            .with("body", "bar")
            .with("change", 50.0);
        for (k, v) in keys {
            c = c.raw(&format!("{k} = {v}"));
        }
        common::model(&c.solver("").build())
    };
    let x = [3.0, 4.0, 5.0];
    for (plane, r) in [
        ("axisymmetric", 3.0),
        ("stress", 5.0),
        ("3d", 34.0f64.sqrt()),
    ] {
        let want = ALPHA * 50.0 * (1.0 - 0.02 * r);
        for keys in [
            &[("field", "\"1 - 0.02*r\"")][..],
            &[("along", "\"r\""), ("profile", "[[0.0, 1.0], [20.0, 0.6]]")][..],
        ] {
            let m = field(keys, plane);
            let got = m.thermal_at(0, 1.0, x);
            assert!(
                (got - want).abs() < 1e-14 * want,
                "{plane} {keys:?}: α ΔT {got}, want {want} (r = {r})"
            );
        }
    }
}

/// A bar 0 ≤ x ≤ L held at both ends (u_x = 0 there; u_y = 0 everywhere, so
/// ε_yy = 0 and the state is one-dimensional), heated by ΔT(x) = ΔT₀ x/L
/// (`field = "x/100"`, ΔT₀ = 100 K) from 20 °C, with a modulus that falls
/// with temperature (`young_table`: E(T) = E (1 − 0.003 (T − 20)), so
/// E(x) = E (1 − k x), k = 0.3/L). Each Gauss point reads its own E. Plane
/// stress with ε_yy = 0: σ_xx = E(x)/(1 − ν²) (ε_xx − (1 + ν) α ΔT(x));
/// equilibrium makes σ_xx = σ₀ uniform, and the held ends ∫ ε_xx dx = 0:
///
/// σ₀ = −α ∫ ΔT dx / ((1 − ν) ∫ dx/E(x)) = −α ΔT₀ L/2 · k E / ((1 − ν)(−ln(1 − kL)))
///
/// (−145.09 MPa; with E uniform it would be −E α ΔT₀/(2(1 − ν)) = −172.5).
/// u_x is not a polynomial, so the elements approach it: every Gauss point
/// within 1e-4 of σ₀ on 20 elements, and the error falls with the mesh.
#[test]
fn a_bar_held_at_its_ends_with_a_modulus_falling_along_its_field_matches_equilibrium() {
    let l = 100.0;
    let (dt0, k) = (100.0, 0.3 / l);
    let e_at = |t: f64| E * (1.0 - 0.003 * (t - 20.0));
    let sigma0 = -ALPHA * dt0 * l / 2.0 * k * E / ((1.0 - NU) * (-(1.0 - k * l).ln()));
    eprintln!("held bar: closed form σ₀ = {sigma0:.4} MPa");
    let mut errors = Vec::new();
    for n in [5, 20] {
        let text = common::case()
            .plane("stress")
            .block("bar", [0.0, l], [n], [0.0, 5.0], [1])
            .material("bar", E, NU)
            .with("expansion", ALPHA)
            .with("young_table", [[20.0, E], [120.0, e_at(120.0)]])
            .ux("bar.left", 0.0)
            .ux("bar.right", 0.0)
            .uy("bar.all", 0.0)
            .raw("[[temperature]]")
            .with("body", "bar")
            .with("change", dt0)
            .with("reference", 20.0)
            .raw("field = \"x/100\"")
            .solver("increments = 1\nstep_control = \"fixed\"")
            .tolerances(1e-12, 1e-12)
            .no_vtu()
            .build();
        let (model, r, _) = solve(&text);
        // the material at a point: E at its own temperature
        let mid = model.material_point(0, 1.0, [50.0, 2.0, 0.0]);
        assert!((mid.young - e_at(70.0)).abs() < 1e-9 * E, "{}", mid.young);
        let err = (0..model.mesh.elements.len())
            .flat_map(|e| model.points(e))
            .map(|g| (r.final_state.gauss.get(g).stress[0] - sigma0).abs())
            .fold(0.0f64, f64::max);
        eprintln!(
            "held bar, {n} elements: largest |σ_xx − σ₀| / |σ₀| = {:.2e}",
            err / sigma0.abs()
        );
        errors.push(err / sigma0.abs());
    }
    assert!(errors[1] < 1e-4, "{errors:?}");
    assert!(errors[1] < errors[0] / 4.0, "{errors:?}");
}

/// A block held everywhere (u = 0: ε = 0 at every point, so each Gauss point
/// is its own closed form) heated by ΔT(x) = ΔT₀ x/20 (`field`, ΔT₀ =
/// 120 K) from 20 °C and cooled back, its E and σ_Y falling with temperature
/// as in [`held_block_with_temperature_dependent_modulus_and_yield_stress`],
/// perfectly plastic, plane stress. The mechanical strain −α ΔT(x) h(t) is
/// equibiaxial, so is the stress: σ_xx = σ_yy = s,
/// - heating: s = −min(E(T) α ΔT/(1 − ν), σ_Y(T)), T = 20 + ΔT₀ h f(x) (a
///   point yields where E(T) α ΔT/(1 − ν) reaches σ_Y(T), the return taking
///   σ_Y at the point's current temperature), with εᵖ = −α ΔT + σ_Y(T)(1 −
///   ν)/E(T) in xx and yy at the peak;
/// - cooling back (elastic): s = E(T)/(1 − ν) (−α ΔT − εᵖ).
///
/// Points near x = 0 stay elastic, the hot end yields: every Gauss point at
/// every increment to 1e-9 of σ_Y.
#[test]
fn a_held_block_yields_point_by_point_at_the_temperature_of_its_field() {
    let (a, b) = (5e-4, 1e-3);
    let e_at = |t: f64| E * (1.0 - a * (t - 20.0));
    let s_at = |t: f64| SY * (1.0 - b * (t - 20.0));
    let dt0 = 120.0;
    let text = common::case()
        .plane("stress")
        .block("bar", [0.0, 20.0], [4], [0.0, 6.0], [1])
        .material("bar", E, NU)
        .plastic(SY, 0.0)
        .with("expansion", ALPHA)
        .with("young_table", [[0.0, e_at(0.0)], [300.0, e_at(300.0)]])
        .with("yield_table", [[0.0, s_at(0.0)], [300.0, s_at(300.0)]])
        .ux("bar.all", 0.0)
        .uy("bar.all", 0.0)
        .raw("[[temperature]]")
        .with("body", "bar")
        .with("change", dt0)
        .with("reference", 20.0)
        .with("history", [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])
        .raw("field = \"x/20\"")
        .solver("")
        .tolerances(1e-12, 1e-12)
        .no_vtu()
        .build();
    let (model, _, c) = solve(&text);
    let elastic = |t: f64, dt: f64| e_at(t) * ALPHA * dt / (1.0 - NU);
    let (mut yielded, mut worst) = (0, 0.0f64);
    for (t, _, g) in &c.0 {
        let h = if *t <= 1.0 { *t } else { 2.0 - t };
        for e in 0..model.mesh.elements.len() {
            for (ip, k) in model.points(e).enumerate() {
                let f = model.point_x(e, ip)[0] / 20.0;
                let (dt, dt_peak) = (dt0 * h * f, dt0 * f);
                let want = if *t <= 1.0 {
                    -elastic(20.0 + dt, dt).min(s_at(20.0 + dt))
                } else {
                    let tp = 20.0 + dt_peak;
                    let ep = if elastic(tp, dt_peak) > s_at(tp) {
                        -ALPHA * dt_peak + s_at(tp) * (1.0 - NU) / e_at(tp)
                    } else {
                        0.0
                    };
                    e_at(20.0 + dt) / (1.0 - NU) * (-ALPHA * dt - ep)
                };
                let s = g[k].stress;
                worst = worst.max((s[0] - want).abs()).max((s[1] - want).abs());
                if *t == 1.0 && g[k].yielding {
                    yielded += 1;
                }
            }
        }
    }
    let n = model.mesh.elements.len() * model.points(0).len();
    eprintln!(
        "held block, field and tables: {yielded} of {n} points yielded at the peak, largest error {worst:.2e} MPa"
    );
    assert!(yielded > 0 && yielded < n, "{yielded} of {n}");
    assert!(worst < 1e-9 * SY, "{worst}");
}
