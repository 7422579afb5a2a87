//! Hertz's sphere in 3D (issue 47): a layout reaching the axis revolved
//! with O-grid cores, the ball's cap and the flat's top meshed apart and
//! joined by node-to-surface springs. cases/hertz-sphere-3d (a quarter,
//! pressed by a platen) against Hertz and against the axisymmetric model of
//! the same layout; tests/data/hertz-sphere-3d-slide (a half through 180°,
//! symmetric about the plane z = 0 that holds the tangential load, with
//! friction) against Cattaneo-Mindlin.
//!
//! Hertz, two spheres of equal elastic constants (here R against a flat;
//! Johnson, *Contact Mechanics*, 1985, eq. 4.22-4.23): 1/E* = 2(1 − ν²)/E,
//! a = (3PR/(4E*))^(1/3), p₀ = 3P/(2πa²), p(r) = p₀ √(1 − r²/a²).
//! Cattaneo-Mindlin for the same contact under a tangential force Q < μP,
//! P held (Johnson, section 7.2, eq. 7.38-7.39): the stick zone is the disk
//! r < c with c/a = (1 − Q/(μP))^(1/3); in the annulus c < r < a the shear
//! is μp.

use crate::common;
use asperity::model::Model;
use asperity::physics::contact::Status;
use asperity::solve::{Increment, Observer, State};
use std::f64::consts::PI;

const E: f64 = 206_000.0;
const NU: f64 = 0.3;
const R: f64 = 50.0;

fn e_star() -> f64 {
    E / (2.0 * (1.0 - NU * NU))
}

/// Hertz's contact radius and peak pressure under the load P (N).
fn hertz(p: f64) -> (f64, f64) {
    let a = (3.0 * p * R / (4.0 * e_star())).cbrt();
    (a, 3.0 * p / (2.0 * PI * a * a))
}

/// Keeps the state of every increment.
struct Keep(Vec<State>);

impl Observer for Keep {
    fn increment(&mut self, _: &Model, state: &State, _: &Increment) -> asperity::Result<()> {
        self.0.push(state.clone());
        Ok(())
    }
}

fn run(text: &str) -> (Model, Vec<State>) {
    let model = common::model(text);
    let mut keep = Keep(Vec::new());
    asperity::app::driver::solve(&model, &mut keep).unwrap_or_else(|e| panic!("{e}"));
    (model, keep.0)
}

/// A spring point at a state: its radius about the y axis, its area, its
/// pressure, status and shear (along t₁ = +x on the flat, and t₂).
struct Spring {
    r: f64,
    area: f64,
    p_n: f64,
    status: Status,
    shear: [f64; 2],
}

fn springs(model: &Model, state: &State) -> Vec<Spring> {
    let im = &model.interfaces[0];
    let gap = model.gap_at(0, state.time);
    im.points
        .iter()
        .enumerate()
        .map(|(k, pt)| {
            let (u_n, _) = im.point_kinematics_at(pt, &state.u, gap);
            let (pair, _) = pt.coupling.pairs().next().unwrap();
            let x = im.pairs[pair].x;
            let c = &state.contact[k];
            Spring {
                r: x[0].hypot(x[2]),
                area: pt.area,
                p_n: im.law.pressure(u_n).0,
                status: state.status[k],
                shear: [c.p_t, c.second_shear()],
            }
        })
        .collect()
}

/// The contact's edge: the largest radius of a pressed point and the
/// smallest of an open one (the pressed points make a disk where the
/// second is the larger).
fn contact_edge(s: &[Spring]) -> (f64, f64) {
    let closed = s
        .iter()
        .filter(|q| q.p_n > 0.0)
        .fold(0.0f64, |m, q| m.max(q.r));
    let open = s
        .iter()
        .filter(|q| q.p_n <= 0.0)
        .fold(f64::INFINITY, |m, q| m.min(q.r));
    (closed, open)
}

/// The quarter's results: P (the whole sphere's), the contact edge, the
/// peak pressure, and the pressure's worst deviation from Hertz's profile
/// over r < 0.9a (a fraction of p₀).
struct Pressed {
    load: f64,
    edge: (f64, f64),
    peak: f64,
    worst: f64,
}

fn pressed(s: &[Spring], share: f64) -> Pressed {
    let load = s.iter().map(|q| q.area * q.p_n).sum::<f64>() / share;
    let (a, p0) = hertz(load);
    let worst = s
        .iter()
        .filter(|q| q.r < 0.9 * a)
        .map(|q| (q.p_n - p0 * (1.0 - (q.r / a).powi(2)).sqrt()).abs() / p0)
        .fold(0.0, f64::max);
    Pressed {
        load,
        edge: contact_edge(s),
        peak: s.iter().map(|q| q.p_n).fold(0.0, f64::max),
        worst,
    }
}

/// The case's text as the axisymmetric model of its layout: no sweep, no
/// symmetry planes (the axis holds itself).
fn axisymmetric(text: &str) -> String {
    let mut out = String::new();
    for block in text.split("\n\n") {
        if block.contains(".theta") {
            continue;
        }
        let block = block.replace("plane = \"3d\"", "plane = \"axisymmetric\"");
        let lines: Vec<&str> = block
            .lines()
            .filter(|l| !l.starts_with("revolve") && *l != "[mesh]")
            .collect();
        out += &lines.join("\n");
        out += "\n\n";
    }
    out
}

/// The quarter sphere of cases/hertz-sphere-3d: Hertz's contact radius
/// (midway between the last pressed and the first open spring, the pressed
/// ones a disk) and peak pressure within 2 % at the load P the springs carry
/// (measured −0.67 % and −0.38 %); then the axisymmetric model of the same
/// layout, whose load (within 1e-3), contact edge and peak (within 1 %) the
/// 3D run gives (measured 1e-5, 0, 0.08 %; printed with `--nocapture`).
#[test]
fn a_quarter_sphere_in_3d_reproduces_hertz_and_its_axisymmetric_model() {
    let text =
        std::fs::read_to_string(common::root().join("cases/hertz-sphere-3d/case.toml")).unwrap();
    let started = std::time::Instant::now();
    let (model, states) = run(&text);
    let seconds = started.elapsed().as_secs_f64();
    let s = springs(&model, states.last().unwrap());
    let q = pressed(&s, 0.25);
    let (a, p0) = hertz(q.load);
    let a_fe = 0.5 * (q.edge.0 + q.edge.1);
    println!(
        "hertz-sphere-3d ({} dofs, {} springs, {seconds:.1} s): P = {:.1} N; a FE {a_fe:.4} (last pressed {:.4}, first open {:.4}) vs Hertz {a:.4} mm ({:+.2} %); peak {:.1} vs p0 {p0:.1} MPa ({:+.2} %); profile worst {:.2} % of p0",
        model.num_dofs(),
        s.len(),
        q.load,
        q.edge.0,
        q.edge.1,
        100.0 * (a_fe / a - 1.0),
        q.peak,
        100.0 * (q.peak / p0 - 1.0),
        100.0 * q.worst
    );
    assert!(
        q.edge.1 > q.edge.0,
        "an open spring inside the contact: {:?}",
        q.edge
    );
    assert!(common::rel(a_fe, a) < 0.02, "a: FE {a_fe} vs Hertz {a}");
    assert!(
        common::rel(q.peak, p0) < 0.02,
        "p0: FE {} vs Hertz {p0}",
        q.peak
    );

    // the axisymmetric model of the same layout
    let (m2, st2) = run(&axisymmetric(&text));
    let s2 = springs(&m2, st2.last().unwrap());
    let q2 = pressed(&s2, 1.0);
    let a2 = 0.5 * (q2.edge.0 + q2.edge.1);
    println!(
        "axisymmetric model of the layout: P = {:.1} N ({:+.2} % from 3D), a {a2:.4} mm ({:+.2} %), peak {:.1} MPa ({:+.2} %), profile worst {:.2} % of p0",
        q2.load,
        100.0 * (q.load / q2.load - 1.0),
        100.0 * (a_fe / a2 - 1.0),
        q2.peak,
        100.0 * (q.peak / q2.peak - 1.0),
        100.0 * q2.worst
    );
    // measured: the load to 1e-5, the edge on the same rings, the peak 0.08 %
    assert!(
        common::rel(q.load, q2.load) < 1e-3,
        "P: 3D {} vs axisymmetric {}",
        q.load,
        q2.load
    );
    assert!(common::rel(q.peak, q2.peak) < 0.01);
    assert!(common::rel(a_fe, a2) < 0.01);
}

/// A half sphere pressed by a platen (P held), then pulled along x; at each
/// pulling increment the load ratio Q/μP, the stick zone's radius c and
/// the contact's a as the radii of the half disks of the sticking and the
/// pressed springs' areas (c = √(2 A_stick/π)), and the band of radii where
/// sticking and slipping springs mix. Every slipping spring carries μ p.
struct Slide {
    time: f64,
    load: f64,
    ratio: f64,
    c: f64,
    a: f64,
    /// The contact's edge (the last pressed spring's radius, the first open one's).
    edge: (f64, f64),
    band: (f64, f64),
}

fn slide(text: &str, mu: f64) -> (Vec<Slide>, usize, f64) {
    let started = std::time::Instant::now();
    let (model, states) = run(text);
    let seconds = started.elapsed().as_secs_f64();
    let mut out = Vec::new();
    for state in states.iter().filter(|s| s.time > 1.0) {
        let s = springs(&model, state);
        let load = 2.0 * s.iter().map(|q| q.area * q.p_n).sum::<f64>();
        let q_x = 2.0 * s.iter().map(|q| q.area * q.shear[0]).sum::<f64>();
        let slipping = |q: &Spring| matches!(q.status, Status::MacroSlip | Status::MicroSlip);
        for q in s.iter().filter(|q| slipping(q)) {
            let shear = q.shear[0].hypot(q.shear[1]);
            assert!(
                (shear - mu * q.p_n).abs() <= 1e-8 * mu * q.p_n,
                "|p_T| {shear} vs μp"
            );
        }
        let area = |f: &dyn Fn(&Spring) -> bool| -> f64 {
            s.iter().filter(|q| f(q)).map(|q| q.area).sum()
        };
        let disk = |a: f64| (2.0 * a / PI).sqrt();
        let first_slip = s
            .iter()
            .filter(|q| slipping(q))
            .fold(f64::INFINITY, |m, q| m.min(q.r));
        let last_stick = s
            .iter()
            .filter(|q| q.status == Status::Stick)
            .fold(0.0f64, |m, q| m.max(q.r));
        out.push(Slide {
            time: state.time,
            load,
            ratio: q_x.abs() / (mu * load),
            c: disk(area(&|q| q.status == Status::Stick)),
            a: disk(area(&|q| q.p_n > 0.0)),
            edge: contact_edge(&s),
            band: (first_slip, last_stick),
        });
    }
    (out, model.num_dofs(), seconds)
}

/// tests/data/hertz-sphere-3d-slide (ν = 0, where Mindlin's shear parallel
/// to Q is exact): at each pulling increment P stays put, the contact's
/// edge (midway between the last pressed and the first open spring) is
/// Hertz's a within 3 % (measured −2.5 %: the half is coarser around the
/// axis than the quarter), the stick zone is a disk (the
/// sticking and the slipping springs mix only within 5 % of a about its
/// edge) whose radius is Cattaneo-Mindlin's c = a (1 − Q/μP)^(1/3) within 3 %
/// (c/a as the ratio of the two disks' radii).
#[test]
fn the_stick_zone_of_a_sphere_shrinks_as_cattaneo_and_mindlin_say() {
    let text =
        std::fs::read_to_string(common::root().join("tests/data/hertz-sphere-3d-slide/case.toml"))
            .unwrap();
    assert!(text.contains("poisson = 0.0"));
    let e_star = E / 2.0;
    let (rows, dofs, seconds) = slide(&text, 0.3);
    println!("hertz-sphere-3d-slide (ν = 0): {dofs} dofs, {seconds:.1} s");
    assert_eq!(rows.len(), 2);
    let p_held = rows[0].load;
    for w in &rows {
        let a = (3.0 * w.load * R / (4.0 * e_star)).cbrt();
        let a_fe = 0.5 * (w.edge.0 + w.edge.1);
        let want = (1.0 - w.ratio).cbrt();
        println!(
            "t = {:.2}: P = {:.1} N, Q/μP = {:.3}: c/a FE {:.4} vs {want:.4} ({:+.2} %); contact edge {a_fe:.4} vs Hertz {a:.4} mm ({:+.2} %); stick and slip mix over r = {:.4} … {:.4} mm",
            w.time,
            w.load,
            w.ratio,
            w.c / w.a,
            100.0 * (w.c / w.a / want - 1.0),
            100.0 * (a_fe / a - 1.0),
            w.band.0.min(w.band.1),
            w.band.1.max(w.band.0),
        );
        assert!(
            common::rel(w.load, p_held) < 1e-3,
            "P {} vs {p_held}",
            w.load
        );
        // the coarser half has its edge within 3 % of Hertz's a (the
        // quarter of cases/hertz-sphere-3d within 2 %), pressed and open
        // springs mixing over two rings there
        assert!(common::rel(a_fe, a) < 0.03, "a {a_fe} vs {a}");
        assert!(
            w.edge.0 - w.edge.1 < 0.02 * a,
            "pressed and open mix over {:?}",
            w.edge
        );
        assert!(w.ratio > 0.2 && w.ratio < 0.9, "{}", w.ratio);
        assert!(
            common::rel(w.c / w.a, want) < 0.03,
            "c/a {} vs {want}",
            w.c / w.a
        );
        assert!(
            w.band.0 > w.c - 0.05 * a && w.band.1 < w.c + 0.05 * a,
            "stick and slip mix over {:?} about c = {}",
            w.band,
            w.c
        );
    }
}

/// The same half with ν = 0.3 and a finer mesh (slave elements of
/// 0.067 mm, 12 layers): Mindlin's shear parallel to Q is no longer exact
/// (the slip turns a little across Q, a shear along z of about a tenth of
/// Q's), and the stick zone comes out smaller than (1 − Q/μP)^(1/3) a
/// (measured −4.0 % at Q/μP = 0.34, −4.2 % at 0.63; 41,265 dofs, 150 s).
/// Printed, asserted only below Mindlin's: `cargo test --release --test
/// verification hertz3d -- --ignored --nocapture`.
#[test]
#[ignore]
fn the_stick_zone_with_poissons_ratio_0_3_finer() {
    let text =
        std::fs::read_to_string(common::root().join("tests/data/hertz-sphere-3d-slide/case.toml"))
            .unwrap()
            .replace("poisson = 0.0", "poisson = 0.3")
            .replace(
                "revolve = { angle = 180.0, n = 8 }",
                "revolve = { angle = 180.0, n = 12 }",
            )
            .replace(
                "x = [0.0, 1.6, 15.0]\nnx = [16, 3]",
                "x = [0.0, 1.6, 15.0]\nnx = [24, 3]",
            )
            .replace(
                "x = [0.0, 0.1, 2.5, 30.0]",
                "x = [0.0, 0.0666666666666667, 2.4666666666666667, 30.0]",
            );
    assert!(text.contains("n = 12") && text.contains("nx = [24, 3]") && text.contains("0.0666"));
    let (rows, dofs, seconds) = slide(&text, 0.3);
    println!("hertz-sphere-3d-slide with ν = 0.3, finer: {dofs} dofs, {seconds:.1} s");
    for w in &rows {
        let want = (1.0 - w.ratio).cbrt();
        println!(
            "t = {:.2}: P = {:.1} N, Q/μP = {:.3}: c/a FE {:.4} vs Mindlin {want:.4} ({:+.2} %)",
            w.time,
            w.load,
            w.ratio,
            w.c / w.a,
            100.0 * (w.c / w.a / want - 1.0)
        );
        assert!(w.c / w.a < want);
    }
}
