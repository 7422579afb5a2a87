//! Vertical interfaces between blocks and the joint outputs against closed
//! forms and equilibrium (src/input/mesh/blocks.rs, src/measure/joint.rs):
//! blocks pressed together sideways carry p_N = q at every point; the joint
//! convention (A dragged in +t relative to B gives F_T, ū_T > 0) on a
//! horizontal and a vertical interface, with F_T the force that drags A;
//! several interfaces in one model, each in equilibrium.

use crate::common::{self, CaseText};
use asperity::measure::joint::JointMeasures;
use asperity::model::Model;
use asperity::solve::RunResult;

use crate::common::Quiet;

fn solve(model: &Model) -> RunResult {
    asperity::app::driver::solve(model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"))
}

fn last_joints(r: &RunResult) -> &[JointMeasures] {
    &r.increments.last().unwrap().joints
}

const SOLVER: &str = "increments = 4\nresidual_tolerance = 1e-12\ndisplacement_tolerance = 1e-12";

/// A shaft (left, x ≤ 10) and a hub (right), both 0 ≤ y ≤ 15, plane stress,
/// 2 mm thick; the shaft's left side held in x, both bottoms in y (the
/// shaft's moved up by `lift`).
fn side_by_side(weights: &str, lift: f64) -> CaseText {
    common::case()
        .plane("stress")
        .thickness(2.0)
        .block("shaft", [0.0, 10.0], [3], [0.0, 15.0], [3])
        .rx([0.5])
        .ry([2.0])
        .block("hub", [10.0, 25.0], [4], [0.0, 15.0], [3])
        .ry([2.0])
        .vertical_interface("fit", "shaft", "hub")
        .material("shaft", 70000.0, 0.33)
        .material("hub", 200000.0, 0.3)
        .law("fit", "power", 0.002, 0.5)
        .weights(weights)
        .ux("shaft.left", 0.0)
        .uy("shaft.bottom", lift)
        .uy("hub.bottom", 0.0)
        .solver(SOLVER)
}

#[test]
fn blocks_pressed_together_sideways_carry_the_applied_pressure_everywhere() {
    // uniform σ_xx = −q in both blocks (σ_yy = 0: free tops), exact for Q8;
    // the joint carries p_N = q, u_N = c q^m
    let (q, c, m, t, h) = (120.0f64, 0.002f64, 0.5f64, 2.0, 15.0);
    for w in ["lumped", "consistent"] {
        let model = common::model(&side_by_side(w, 0.0).pressure("hub.right", q).build());
        let r = solve(&model);
        let st = &r.final_state;
        let im = &model.interfaces[0];
        assert_eq!(model.mesh.bodies[im.body_a], "shaft");
        for pr in &im.pairs {
            assert!(
                (pr.normal[0] + 1.0).abs() < 1e-15 && pr.normal[1].abs() < 1e-15,
                "{w}: the normal from B (hub) into A (shaft) is −x: {:?}",
                pr.normal
            );
            let p = im.law.pressure(im.pair_approach(pr, &st.u)).0;
            assert!(
                common::rel(p, q) < 1e-9,
                "{w}: p_N = {p} at y = {}",
                pr.x[1]
            );
        }
        for pt in &im.points {
            let p = im.law.pressure(im.point_kinematics(pt, &st.u).0).0;
            assert!(common::rel(p, q) < 1e-9, "{w}: point p_N = {p}");
        }
        assert_eq!(asperity::model::interface::arcs::direction(im), [0.0, 1.0]);
        let j = last_joints(&r)[0];
        assert!(common::rel(j.normal_force, q * h * t) < 1e-9, "{w}: {j:?}");
        assert!(
            common::rel(j.mean_approach, c * q.powf(m)) < 1e-9,
            "{w}: {j:?}"
        );
        assert!(common::rel(j.closed, h) < 1e-12, "{w}: {j:?}");
        assert_eq!([j.open, j.stick, j.micro_slip, j.macro_slip], [0.0; 4]);
        // Poisson: u_y = ν q y / E in each block, no shear across the joint;
        // the softer shaft (A) rises relative to the hub: ū_T > 0 along +y
        let slip = q * 7.5 * (0.33 / 70000.0 - 0.3 / 200000.0);
        assert!(slip > 0.0);
        assert!(
            common::rel(j.mean_slip, slip) < 1e-9,
            "{w}: {} vs {slip}",
            j.mean_slip
        );
        assert_eq!((j.tangential_force, j.dissipation, j.work), (0.0, 0.0, 0.0));
    }
}

/// Checks the joint convention on a run where A is dragged in +t by the
/// only non-zero prescribed displacement: F_T is the force that drags it.
fn check_drag(what: &str, model: &Model, r: &RunResult) {
    let mut last = JointMeasures::default();
    for inc in &r.increments {
        let j = inc.joints[0];
        assert!(
            j.tangential_force > 0.0 && j.mean_slip > 0.0,
            "{what}: {j:?}"
        );
        let drag = inc.measures.prescribed_reaction;
        assert!(
            common::rel(j.tangential_force, drag) < 1e-8,
            "{what}: F_T {} vs the reaction dragging A {drag}",
            j.tangential_force
        );
        assert!(
            j.dissipation >= last.dissipation && j.work >= j.dissipation,
            "{what}: {j:?}"
        );
        let total = j.open + j.closed + j.stick + j.micro_slip + j.macro_slip;
        let length = model.interfaces[0].area() / 2.0;
        assert!(
            common::rel(total, length) < 1e-12,
            "{what}: {total} vs {length}"
        );
        last = j;
    }
    assert!(
        last.macro_slip > 0.0 && last.dissipation > 0.0,
        "{what}: {last:?}"
    );
}

#[test]
fn dragging_body_a_along_the_joint_gives_positive_force_and_slip() {
    // vertical: the shaft pressed by the hub (pressure on the hub's right
    // side) and pushed up by its bottom: A moves in +y = t
    let text = side_by_side("lumped", 0.05)
        .tangential("fit", 0.9, 0.5, 0.05, 0.2)
        .with("n", 275.0)
        .pressure("hub.right", 100.0)
        .build();
    let model = common::model(&text);
    check_drag("vertical", &model, &solve(&model));

    // horizontal: a block pressed on a base and its top pulled in +x = t
    let text = common::case()
        .plane("stress")
        .thickness(2.0)
        .block("block", [0.0, 10.0], [4], [0.0, 5.0], [2])
        .block("base", [0.0, 10.0], [4], [-5.0, 0.0], [2])
        .interface("fit", "block", "base")
        .material("block", 70000.0, 0.33)
        .material("base", 200000.0, 0.3)
        .law("fit", "power", 0.002, 0.5)
        .tangential("fit", 0.9, 0.5, 0.05, 0.2)
        .with("n", 275.0)
        .ux("block.top", 0.05)
        .fixed("base.bottom")
        .pressure("block.top", 100.0)
        .solver(SOLVER)
        .build();
    let model = common::model(&text);
    assert_eq!(
        asperity::model::interface::arcs::direction(&model.interfaces[0]),
        [1.0, 0.0]
    );
    check_drag("horizontal", &model, &solve(&model));
}

#[test]
fn a_shaft_in_a_hub_on_a_base_balances_both_interfaces() {
    // the hub pressed against the shaft (q₁ on its right side) and onto the
    // base (q₂ on its top); without friction each interface carries exactly
    // the hub's load across it
    let (q1, q2, t) = (80.0, 50.0, 2.0);
    let text = common::case()
        .plane("strain")
        .thickness(t)
        .block(
            "shaft",
            [0.0, 10.0],
            [2],
            [0.0, 10.0, 30.0, 40.0],
            [2, 4, 1],
        )
        .block("hub", [10.0, 30.0], [4], [10.0, 30.0], [4])
        .block("base", [10.0, 20.0, 30.0], [2, 2], [-10.0, 10.0], [2])
        .vertical_interface("fit", "shaft", "hub")
        .interface("seat", "hub", "base")
        .material("shaft", 200000.0, 0.3)
        .material("hub", 110000.0, 0.34)
        .material("base", 70000.0, 0.33)
        .law("fit", "power", 0.002, 0.5)
        .law("seat", "linear", 0.001, 0.5)
        .with("slope", 1e-5)
        .with("p_c", 5.0)
        .ux("shaft.left", 0.0)
        .uy("shaft.bottom", 0.0)
        .fixed("base.bottom")
        .pressure("hub.right", q1)
        .pressure("hub.top", q2)
        .solver(SOLVER)
        .build();
    let model = common::model(&text);
    let r = solve(&model);
    let j = last_joints(&r);
    assert_eq!(j.len(), 2);
    assert!(
        common::rel(j[0].normal_force, q1 * 20.0 * t) < 1e-9,
        "{:?}",
        j[0]
    );
    assert!(
        common::rel(j[1].normal_force, q2 * 20.0 * t) < 1e-9,
        "{:?}",
        j[1]
    );
    assert!(common::rel(j[0].closed, 20.0) < 1e-12 && common::rel(j[1].closed, 20.0) < 1e-12);
    // the arc length runs from each interface's first pair along its walk
    for (k, (origin, axis)) in [(10.0, 1), (10.0, 0)].into_iter().enumerate() {
        let (im, iface) = (&model.interfaces[k], &model.mesh.interfaces[k]);
        let s = asperity::model::interface::arcs::arc_lengths(&model.mesh, iface, im);
        for (pr, s) in im.pairs.iter().zip(&s) {
            assert!(
                (s - (pr.x[axis] - origin)).abs() < 1e-12,
                "{}: {s} at {:?}",
                im.name,
                pr.x
            );
        }
        // the same with the edges listed backwards (a mesh file's order)
        let mut back = iface.clone();
        back.edges.reverse();
        assert_eq!(
            asperity::model::interface::arcs::arc_lengths(&model.mesh, &back, im),
            s
        );
    }
    // the interface CSV: both interfaces, named, each in order of s
    let csv = asperity::files::output::interface_csv(&model, &r.final_state);
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(&head[9..], ["y_mm", "s_mm", "interface"]);
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(
        rows.len(),
        model.interfaces[0].pairs.len() + model.interfaces[1].pairs.len()
    );
    for name in ["fit", "seat"] {
        let s: Vec<f64> = rows
            .iter()
            .filter(|r| r[11] == name)
            .map(|r| r[10].parse().unwrap())
            .collect();
        assert!(
            s.len() == 9 && s[0] == 0.0 && s.windows(2).all(|w| w[1] > w[0]),
            "{name}: {s:?}"
        );
        assert!((s[8] - 20.0).abs() < 1e-9, "{name}: {s:?}");
    }
    // fit rows: x = 10, y = 10 + s
    for r in rows.iter().filter(|r| r[11] == "fit") {
        let (x, y, s): (f64, f64, f64) = (
            r[0].parse().unwrap(),
            r[9].parse().unwrap(),
            r[10].parse().unwrap(),
        );
        assert!(x == 10.0 && (y - 10.0 - s).abs() < 1e-9, "{r:?}");
    }
}
