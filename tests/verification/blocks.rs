//! Bodies of several blocks (issue 27, src/input/mesh/blocks/merge.rs): a body
//! split into blocks is the body meshed as one block, to round-off: the same
//! displacements at the same points and the same plastic strains, elastic
//! and elastic-plastic, split in x and in y, also under a face that spans
//! both blocks with an interface each; an L-shaped bolt (a head on a
//! shank, one body) pulled through a plate carries its load across the
//! seat, and its sets are its outline.

use crate::common::{self, CaseText};
use asperity::model::Model;
use asperity::solve::RunResult;
use std::collections::HashMap;

use crate::common::Quiet;

fn solve(model: &Model) -> RunResult {
    asperity::app::driver::solve(model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"))
}

const SOLVER: &str = "method = \"full-newton\"\nincrements = 4\nresidual_tolerance = 1e-12\ndisplacement_tolerance = 1e-12";

/// How the foundation is meshed.
#[derive(Clone, Copy, Debug)]
enum Split {
    /// One block with breakpoints at x = 10 and y = −5.
    None,
    /// Two blocks side by side, x ≤ 10 ("near") and x ≥ 10 ("far").
    X,
    /// Two blocks one on the other, y ≤ −5 ("deep") and y ≥ −5 ("skin").
    Y,
}

/// A punch 0 ≤ x ≤ 10, 0 ≤ y ≤ 8 pressed on a graded foundation
/// 0 ≤ x ≤ 30, −20 ≤ y ≤ 0 (the half model, plane strain) through a
/// rough interface; the foundation (body "found") meshed as `split` says,
/// with the same breakpoints, counts and grading whichever way.
fn punch_on(split: Split, plastic: bool) -> String {
    let (x, nx, rx) = ([0.0, 10.0, 30.0], [3usize, 4], [0.5, 2.0]);
    let (y, ny, ry) = ([-20.0, -5.0, 0.0], [3usize, 2], [0.5, 0.7]);
    let c = common::case()
        .plane("strain")
        .raw("symmetric_half = true")
        .block("punch", [0.0, 10.0], [3], [0.0, 8.0], [2])
        .rx([0.5]);
    let part = |c: CaseText,
                name: &str,
                x: &[f64],
                nx: &[usize],
                rx: &[f64],
                y: &[f64],
                ny: &[usize],
                ry: &[f64]| {
        c.block("found", x, nx, y, ny)
            .with("name", name)
            .rx(rx)
            .ry(ry)
    };
    // (the block under the punch, the sets of the bottom and of the plane x = 0)
    let (c, under, bottom, plane): (CaseText, &str, &[&str], &[&str]) = match split {
        Split::None => (
            c.block("found", x, nx, y, ny).rx(rx).ry(ry),
            "found",
            &["found.bottom"],
            &["found.left"],
        ),
        Split::X => {
            let c = part(c, "near", &x[..2], &nx[..1], &rx[..1], &y, &ny, &ry);
            let c = part(c, "far", &x[1..], &nx[1..], &rx[1..], &y, &ny, &ry);
            (c, "near", &["near.bottom", "far.bottom"], &["near.left"])
        }
        Split::Y => {
            let c = part(c, "skin", &x, &nx, &rx, &y[1..], &ny[1..], &ry[1..]);
            let c = part(c, "deep", &x, &nx, &rx, &y[..2], &ny[..1], &ry[..1]);
            (c, "skin", &["deep.bottom"], &["deep.left", "skin.left"])
        }
    };
    let mut c = c
        .interface("contact", "punch", under)
        .material("punch", 206000.0, 0.3)
        .material("found", 70000.0, 0.33);
    if plastic {
        c = c.plastic(150.0, 700.0);
    }
    c = c.law("contact", "power", 0.002, 0.5).ux("punch.left", 0.0);
    for s in plane {
        c = c.ux(s, 0.0);
    }
    for s in bottom {
        c = c.uy(s, 0.0);
    }
    c.pressure("punch.top", 220.0)
        .solver(SOLVER)
        .no_vtu()
        .build()
}

/// Every node's displacement by its body and its coordinates (exact: the
/// blocks put their nodes where the single block does, bit for bit).
fn by_point(model: &Model, u: &[f64]) -> HashMap<(usize, u64, u64), [f64; 2]> {
    let mesh = &model.mesh;
    let mut out = HashMap::new();
    for el in &mesh.elements {
        for &n in el.nodes() {
            let x = mesh.nodes[n];
            let key = (el.body, x[0].to_bits(), x[1].to_bits());
            out.insert(key, [u[2 * n], u[2 * n + 1]]);
        }
    }
    out
}

/// The largest equivalent plastic strain of each element, by the element's
/// corner coordinates.
fn peeq_by_element(model: &Model, r: &RunResult) -> HashMap<Vec<u64>, f64> {
    let ng = model.rule(0).points.len();
    (0..model.mesh.elements.len())
        .map(|e| {
            let key = model.mesh.element_coords(e)[..4]
                .iter()
                .flat_map(|x| [x[0].to_bits(), x[1].to_bits()])
                .collect();
            let states = r.final_state.gauss.range(e * ng..(e + 1) * ng);
            (key, states.iter().fold(0.0f64, |m, s| m.max(s.peeq)))
        })
        .collect()
}

#[test]
fn a_body_split_into_blocks_solves_as_the_body_of_one_block() {
    for plastic in [false, true] {
        let one = common::model(&punch_on(Split::None, plastic));
        let r1 = solve(&one);
        let u1 = by_point(&one, &r1.final_state.u);
        let scale = u1
            .values()
            .fold(0.0f64, |m, u| m.max(u[0].abs()).max(u[1].abs()));
        let p1 = peeq_by_element(&one, &r1);
        let most = p1.values().fold(0.0f64, |m, &p| m.max(p));
        assert_eq!(most > 1e-4, plastic, "the plastic case yields: {most}");
        for split in [Split::X, Split::Y] {
            let m = common::model(&punch_on(split, plastic));
            assert_eq!(m.mesh.nodes.len(), one.mesh.nodes.len(), "{split:?}");
            assert_eq!(m.mesh.bodies, one.mesh.bodies);
            let r = solve(&m);
            let u = by_point(&m, &r.final_state.u);
            assert_eq!(u.len(), u1.len());
            let worst = u1
                .iter()
                .map(|(k, a)| {
                    let b = u[k];
                    (a[0] - b[0]).abs().max((a[1] - b[1]).abs())
                })
                .fold(0.0f64, f64::max);
            assert!(
                worst <= 1e-12 * scale,
                "{split:?}, plastic {plastic}: |Δu| = {worst:e} of {scale:e}"
            );
            let p = peeq_by_element(&m, &r);
            for (k, a) in &p1 {
                assert!(
                    (a - p[k]).abs() <= 1e-12 * most.max(1e-300),
                    "{split:?}: peeq {a} against {}",
                    p[k]
                );
            }
            let (f1, f) = (
                r1.increments.last().unwrap().joints[0].normal_force,
                r.increments.last().unwrap().joints[0].normal_force,
            );
            assert!(
                common::rel(f, f1) < 1e-12,
                "{split:?}: F_N {f} against {f1}"
            );
        }
    }
}

/// A punch 0 ≤ x ≤ 20 on a foundation 0 ≤ x ≤ 30 (plane strain, the half
/// model), plastic; the foundation one block with a breakpoint at x = 10
/// under one interface, or two blocks meeting at x = 10 under the punch,
/// each with its own interface ("near", "far"; the two share the node pair
/// at x = 10).
fn wide_punch_on(split: bool) -> String {
    let c = common::case()
        .plane("strain")
        .raw("symmetric_half = true")
        .block("punch", [0.0, 20.0], [4], [0.0, 8.0], [2]);
    let c = if split {
        c.block("found", [0.0, 10.0], [2], [-20.0, 0.0], [4])
            .with("name", "near")
            .ry([0.5])
            .block("found", [10.0, 30.0], [4], [-20.0, 0.0], [4])
            .with("name", "far")
            .ry([0.5])
            .interface("near", "punch", "near")
            .interface("far", "punch", "far")
            .law("near", "power", 0.002, 0.5)
            .law("far", "power", 0.002, 0.5)
            .ux("near.left", 0.0)
            .uy("near.bottom", 0.0)
            .uy("far.bottom", 0.0)
    } else {
        c.block("found", [0.0, 10.0, 30.0], [2, 4], [-20.0, 0.0], [4])
            .ry([0.5])
            .interface("contact", "punch", "found")
            .law("contact", "power", 0.002, 0.5)
            .ux("found.left", 0.0)
            .uy("found.bottom", 0.0)
    };
    c.material("punch", 206000.0, 0.3)
        .material("found", 70000.0, 0.33)
        .plastic(150.0, 700.0)
        .ux("punch.left", 0.0)
        .pressure("punch.top", 220.0)
        .solver(SOLVER)
        .no_vtu()
        .build()
}

#[test]
fn a_face_over_two_blocks_of_one_body_with_an_interface_each_is_one_interface() {
    let one = common::model(&wide_punch_on(false));
    let two = common::model(&wide_punch_on(true));
    assert_eq!(two.interfaces.len(), 2);
    let (r1, r2) = (solve(&one), solve(&two));
    let (u1, u2) = (
        by_point(&one, &r1.final_state.u),
        by_point(&two, &r2.final_state.u),
    );
    let scale = u1
        .values()
        .fold(0.0f64, |m, u| m.max(u[0].abs()).max(u[1].abs()));
    let worst = u1
        .iter()
        .map(|(k, a)| (a[0] - u2[k][0]).abs().max((a[1] - u2[k][1]).abs()))
        .fold(0.0f64, f64::max);
    assert!(worst <= 1e-12 * scale, "|Δu| = {worst:e} of {scale:e}");
    let j2 = &r2.increments.last().unwrap().joints;
    let f1 = r1.increments.last().unwrap().joints[0].normal_force;
    assert!(j2[0].normal_force > 0.0 && j2[1].normal_force > 0.0);
    let f2 = j2[0].normal_force + j2[1].normal_force;
    assert!(common::rel(f2, f1) < 1e-12, "F_N {f2} against {f1}");
    assert!(common::rel(f1, 220.0 * 20.0) < 1e-9, "F_N {f1}");
}

/// An axisymmetric bolt of one body, a head 0 ≤ r ≤ 20, 40 ≤ z ≤ 50 on a
/// shank 0 ≤ r ≤ 8, seated on a plate 10 ≤ r ≤ 30, 30 ≤ z ≤ 40 (a
/// clearance hole) and pulled down at the shank's end by `pull` MPa.
fn bolt(pull: f64, extra: &str) -> String {
    common::case()
        .plane("axisymmetric")
        .block("bolt", [0.0, 8.0, 10.0, 20.0], [4, 1, 4], [40.0, 50.0], [3])
        .with("name", "head")
        .block("bolt", [0.0, 8.0], [4], [0.0, 40.0], [8])
        .with("name", "shank")
        .ry([0.5])
        .block("plate", [10.0, 20.0, 30.0], [4, 3], [30.0, 40.0], [3])
        .interface("seat", "head", "plate")
        .material("bolt", 206000.0, 0.3)
        .material("plate", 70000.0, 0.33)
        .law("seat", "power", 0.002, 0.5)
        .uy("plate.bottom", 0.0)
        .pressure("shank.bottom", -pull)
        .raw(extra)
        .solver(SOLVER)
        .no_vtu()
        .build()
}

#[test]
fn an_l_shaped_bolt_of_two_blocks_carries_its_pull_across_the_seat() {
    let pull = 50.0;
    let model = common::model(&bolt(pull, ""));
    let mesh = &model.mesh;
    assert_eq!(mesh.bodies, ["bolt", "plate"]);
    // head 9 × 3 and shank 4 × 8 elements less the shank's top, merged;
    // the plate 7 × 3
    let q8 = |nx: usize, ny: usize| (2 * nx + 1) * (2 * ny + 1) - nx * ny;
    assert_eq!(mesh.nodes.len(), q8(9, 3) + q8(4, 8) - 9 + q8(7, 3));
    // the sets are the outline: the head's bottom from the shank outwards,
    // nothing of the shank's top
    let head_bottom = &mesh.node_sets["head.bottom"];
    assert!(head_bottom
        .iter()
        .all(|&n| mesh.nodes[n][1] == 40.0 && mesh.nodes[n][0] >= 8.0));
    assert_eq!(head_bottom.len(), 2 * 5 + 1);
    assert!(mesh.node_sets["shank.top"].is_empty());
    let all = &mesh.node_sets["bolt.all"];
    let (head, shank) = (&mesh.node_sets["head.all"], &mesh.node_sets["shank.all"]);
    assert_eq!(all.len(), head.len() + shank.len() - 9);
    // the seat carries the pull (π r² p over the full revolution)
    let r = solve(&model);
    let f_n = r.increments.last().unwrap().joints[0].normal_force;
    let load = std::f64::consts::PI * 8.0 * 8.0 * pull;
    assert!(
        common::rel(f_n, load) < 1e-9,
        "F_N = {f_n}, pulled by {load}"
    );
    // a support on the shank's top is a support on nothing
    let inside = bolt(pull, "[[boundary]]\nset = \"shank.top\"\nux = 0.0");
    let case = asperity::input::case::Case::parse(&inside, "test.toml").unwrap();
    let e = Model::build(case).err().expect("refused").to_string();
    assert!(e.contains("the set is empty"), "{e}");
}
