//! A disk held about the axis only by friction (issue 26: the contact
//! stabilization's rotation mode), `cases/face-coupling-torque`: a solid
//! disk 0 ≤ r ≤ R, 0 ≤ z ≤ h clamped by a pressure P onto a base
//! −h ≤ z ≤ 0 of the same radius and material through a rough face, then
//! twisted by a torque T on its top face (τ_θ = T r / J); the base is held at
//! its bottom, the disk by nothing but the face. Before the clamp closes the
//! face nothing holds the disk about the axis: its first step is solved with
//! the stabilization's springs (in the meridian plane and around the axis),
//! then again without them.
//!
//! Closed form while the whole face sticks. Both bodies are in uniaxial
//! compression σ_zz = −P (same E and ν: the same radial expansion ν P r/E,
//! no meridian slip), so p_N = P everywhere and the face's shear stiffness
//! k_T^e = 1000 P^S/R (eq. 2.6, MPa/mm) is uniform. Torsion with τ_zθ = T r/J
//! in each body (Timoshenko & Goodier §104) and p_Tθ = k_T^e r Δφ on the face
//! (J = π R⁴/2, ∫ r p_Tθ dA = T) give
//!
//! ```text
//!   u_θ = r T (z + h)/(G J)                       in the base
//!   u_θ = r [T (z + h)/(G J) + T/(k_T^e J)]       in the disk
//! ```
//!
//! linear in r and z, in the Q8 space; the face's 4-point Gauss rule
//! integrates its springs exactly, so every node holds it to round-off, as
//! long as p_Tθ(R) = T R/J stays below the micro-slip onset p_T^Y = 0.625 μ P
//! (eq. 2.18), T ≤ 0.625 μ P J/R = 0.469 of the slip torque (2/3) μ F R.

use crate::common;
use asperity::model::Model;
use asperity::solve::{Increment, Observer, State};

const R: f64 = 10.0;
const H: f64 = 10.0;
const P: f64 = 50.0;
const T: f64 = 12000.0;
const MU: f64 = 0.15;
const E: f64 = 206_000.0;
const NU: f64 = 0.3;

#[derive(Default)]
struct All(Vec<State>);
impl Observer for All {
    fn increment(&mut self, _: &Model, s: &State, _: &Increment) -> asperity::error::Result<()> {
        self.0.push(s.clone());
        Ok(())
    }
}

/// The joint measures of every interface in a converged state.
fn joints(model: &Model, s: &State) -> Vec<asperity::measure::joint::JointMeasures> {
    asperity::measure::joint::measures(
        &model.interfaces,
        model.section,
        s.time,
        &s.u,
        &s.status,
        &s.contact,
        &[],
    )
}

fn case_text() -> String {
    std::fs::read_to_string(common::root().join("cases/face-coupling-torque/case.toml")).unwrap()
}

/// Runs a case text and checks every increment: the base's reaction torque
/// and the face's torque against the applied torque `torque(t)`, and while
/// p_Tθ(R) is below the micro-slip onset at the clamp pressure `clamp(t)`
/// every u_θ against the closed form (module documentation), with a jump
/// T/(k_T^e J) per face below a body's nodes (`faces`: body name and the
/// faces between it and the base; every interface carries the torque).
/// Returns the numbers of sticking and of slipping increments.
fn check(
    text: &str,
    torque: impl Fn(f64) -> f64,
    clamp: impl Fn(f64) -> f64,
    faces: &[(&str, f64)],
) -> (usize, usize) {
    let model = common::model(text);
    let mut all = All::default();
    let result = asperity::app::driver::solve(&model, &mut all).unwrap_or_else(|e| panic!("{e}"));
    let report = (result.stabilization.as_ref()).expect("the first step is stabilized");
    assert!(report.released >= 1 && report.stabilized == 0, "{report:?}");
    let g = E / (2.0 * (1.0 + NU));
    let j = std::f64::consts::PI * R.powi(4) / 2.0;
    let nd = model.node_dofs();
    let mut below = vec![0.0; model.mesh.nodes.len()];
    for &(name, k) in faces {
        let b = model.mesh.bodies.iter().position(|b| b == name).unwrap();
        for el in model.mesh.elements.iter().filter(|e| e.body == b) {
            for &n in el.nodes() {
                below[n] = k;
            }
        }
    }
    let (mut stick_steps, mut slip_steps) = (0, 0);
    for s in &all.0 {
        let (t, p) = (torque(s.time), clamp(s.time));
        // equilibrium through the face: the base's supports take the torque
        let reaction: f64 = (model.prescribed.iter().zip(&s.reactions))
            .filter_map(|(&(d, _), &r)| {
                let (n, c) = nd.node_of(d);
                (c == 2).then_some(model.mesh.nodes[n][0] * r)
            })
            .sum();
        assert!(
            (reaction + t).abs() <= 1e-8 * T,
            "t = {}: reaction torque {reaction} vs applied {t}",
            s.time
        );
        let m = joints(&model, s);
        for face in &m {
            assert!(
                (face.torque - t).abs() <= 1e-8 * T,
                "t = {}: face torque {} vs applied {t}",
                s.time,
                face.torque
            );
        }
        if t > 0.625 * MU * p * j / R {
            slip_steps += 1;
            assert!(
                m.iter().all(|f| f.macro_slip == 0.0 && f.micro_slip > 0.0),
                "t = {}: {m:?}",
                s.time
            );
            continue;
        }
        stick_steps += 1;
        // k_T^e = p_N^S / R in MPa/µm (eq. 2.6), S = 0.5, R = 0.9
        let kt = 1000.0 * p.sqrt() / 0.9;
        let scale = (t / (g * j) * 2.0 * H + t / (kt * j)) * R;
        let mut worst = 0.0f64;
        for (n, x) in model.mesh.nodes.iter().enumerate() {
            let (r, z) = (x[0], x[1]);
            let jump = below[n] * t / (kt * j);
            let want = r * (t * (z + H) / (g * j) + jump);
            worst = worst.max((s.u[nd.dof(n, 2)] - want).abs() / scale.max(1e-300));
        }
        assert!(
            worst < 1e-8,
            "t = {}: u_θ off the closed form by {worst:.2e}",
            s.time
        );
        if t > 0.0 {
            eprintln!(
                "t = {:.4}, T = {t:.1} N·mm, p = {p:.3} MPa: every u_θ on the closed form within {worst:.1e} of the largest",
                s.time
            );
        }
    }
    (stick_steps, slip_steps)
}

/// The shipped case: clamped over t ∈ [0, 1], then twisted to 0.76 of the
/// slip torque: the face sticks up to T = 0.469 of it, then micro-slips
/// from its rim in, and never macro-slips.
#[test]
fn a_disk_held_about_the_axis_only_by_friction_twists_as_the_closed_form_while_it_sticks() {
    let torque = |t: f64| T * (t - 1.0).clamp(0.0, 1.0);
    let clamp = |t: f64| P * t.clamp(0.0, 1.0);
    let (stick, slip) = check(&case_text(), torque, clamp, &[("disk", 1.0)]);
    assert!(
        stick > 20 && slip > 5,
        "{stick} sticking and {slip} slipping increments"
    );
}

/// Clamped and twisted at once across an initial gap of 2 µm: nothing but
/// the stabilization's springs holds the disk about the axis until the face
/// closes, while the torque already acts (without the springs around the
/// axis that step has no solution). T = 3000 N·mm stays below the onset at
/// every load factor (T and P grow together), so the face sticks throughout.
#[test]
fn a_disk_twisted_before_its_face_closes_is_held_by_the_stabilization_then_released() {
    let text = case_text()
        .replace(
            "weights = \"consistent\"",
            "weights = \"consistent\"\ngap = 0.002",
        )
        .replace(
            "torque = 12000.0\nhistory = \"turn\"",
            "torque = 3000.0\nhistory = \"clamp\"",
        )
        .replace("turn  = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]", "");
    assert!(text.contains("gap = 0.002") && !text.contains("\"turn\""));
    let torque = |t: f64| 3000.0 * t.clamp(0.0, 1.0);
    let clamp = |t: f64| P * t.clamp(0.0, 1.0);
    let (stick, slip) = check(&text, torque, clamp, &[("disk", 1.0)]);
    assert!(
        stick > 20 && slip == 0,
        "{stick} sticking and {slip} slipping increments"
    );
}

/// The shipped case with its face matching (the disk's and the base's nodes
/// coincide) and consistent weights (issue 46: a tangential law on a
/// matching interface with consistent weights, 4 Gauss points per edge, each
/// with its own slip history): the same closed form while the face sticks
/// (the 4-point rule integrates r p_Tθ dA, of degree 4 in r, exactly), then
/// micro-slip from the rim.
#[test]
fn a_matching_face_with_consistent_weights_twists_as_the_closed_form_while_it_sticks() {
    let text = case_text().replace(
        "matching = false      # spring points at 4 Gauss points per edge: each with its own slip\n",
        "",
    );
    assert!(!text.contains("matching") && text.contains("weights = \"consistent\""));
    let torque = |t: f64| T * (t - 1.0).clamp(0.0, 1.0);
    let clamp = |t: f64| P * t.clamp(0.0, 1.0);
    let (stick, slip) = check(&text, torque, clamp, &[("disk", 1.0)]);
    assert!(
        stick > 20 && slip > 5,
        "{stick} sticking and {slip} slipping increments"
    );
}

/// A stack: a second disk (`top`, 10 ≤ z ≤ 20) on the disk, through a second
/// rough face of the same law; neither disk has a boundary condition, the
/// top one is held about the axis by friction to a disk that is itself held
/// only by friction. Clamped and twisted at once (T = 3000 N·mm with the
/// clamp, sticking throughout). The middle disk carries no load of its own:
/// its first step was accepted stabilized, unreleased (the springs took
/// 1e-6 of the clamp), as if its position were indeterminate; it is pressed
/// into place by the top disk and is released like the others. Closed form:
/// one jump T/(k_T^e J) per face below a node.
#[test]
fn a_stack_held_about_the_axis_through_two_friction_faces_is_released_on_the_closed_form() {
    let text = case_text()
        .replace(
            "[[mesh.interface]]",
            "[[mesh.block]]\nbody = \"top\"\nx = [0.0, 10.0]\nnx = [8]\nrx = [0.5]\ny = [10.0, 20.0]\nny = [3]\n\n[[mesh.interface]]\nname = \"face2\"\nupper = \"top\"\nlower = \"disk\"\nmatching = false\n\n[[mesh.interface]]",
        )
        .replace(
            "[materials.base]",
            "[materials.top]\nyoung = 206000.0\npoisson = 0.3\n\n[materials.base]",
        )
        .replace(
            "[[boundary]]",
            "[interface.face2]\nlaw = \"power\"\nc_n = 0.001\nm = 0.5\nweights = \"consistent\"\n\n[interface.face2.tangential]\nr = 0.9\ns = 0.5\nkp_ratio = 0.5\nmu = 0.15\nbeta = 1.0\n\n[[boundary]]",
        )
        .replace("edges = \"disk.top\"", "edges = \"top.top\"")
        .replace(
            "torque = 12000.0\nhistory = \"turn\"",
            "torque = 3000.0\nhistory = \"clamp\"",
        )
        .replace("turn  = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]", "")
        .replace("at = [10.0, 10.0]", "at = [10.0, 20.0]");
    assert!(text.contains("face2") && !text.contains("\"turn\""));
    let torque = |t: f64| 3000.0 * t.clamp(0.0, 1.0);
    let clamp = |t: f64| P * t.clamp(0.0, 1.0);
    let (stick, slip) = check(&text, torque, clamp, &[("disk", 1.0), ("top", 2.0)]);
    assert!(
        stick > 20 && slip == 0,
        "{stick} sticking and {slip} slipping increments"
    );
}

/// The shipped case with mortar coupling (`weights = "mortar"`): one spring
/// per slave node, its slip the slave side's averaged with the node's shape
/// function N_i. The face's torque Σ A r p_Tθ equals the applied torque (and
/// the base's support torque) only with r the arm of the spring's force,
/// (1/A_i) ∫ N_i r dA; with the node's own radius it was off by 1.1e-5 of
/// T (1.1e-4 with 5 disk edges on 8 of the base), and the mean twist with it.
/// While the face sticks the mean twist approaches Δφ = T/(k_T^e J) of the
/// closed form (a rigid jump gives u_Tθ/r = Δφ at every spring with that
/// arm; the nodal average of a traction linear in r is not exact): within
/// 5e-4 on equal meshes (observed 2.6e-4; 1.4e-3 with the node's radius).
#[test]
fn a_mortar_face_carries_the_applied_torque_with_its_springs_arms() {
    for (disk_edges, tol) in [("nx = [8]", 5e-4), ("nx = [5]", f64::INFINITY)] {
        let text = case_text()
            .replace("weights = \"consistent\"", "weights = \"mortar\"")
            .replacen("nx = [8]", disk_edges, 1);
        assert!(text.contains("\"mortar\"") && text.contains(disk_edges));
        let model = common::model(&text);
        let mut all = All::default();
        asperity::app::driver::solve(&model, &mut all).unwrap_or_else(|e| panic!("{e}"));
        let j = std::f64::consts::PI * R.powi(4) / 2.0;
        let mut twisted = 0;
        for s in &all.0 {
            let t = T * (s.time - 1.0).clamp(0.0, 1.0);
            let m = joints(&model, s);
            assert!(
                (m[0].torque - t).abs() <= 1e-8 * T,
                "{disk_edges}, t = {}: face torque {} vs applied {t}",
                s.time,
                m[0].torque
            );
            if t > 0.0 && t <= 0.625 * MU * P * j / R {
                let kt = 1000.0 * P.sqrt() / 0.9;
                let want = t / (kt * j);
                assert!(
                    (m[0].twist - want).abs() <= tol * want,
                    "{disk_edges}, t = {}: mean twist {} vs {want}",
                    s.time,
                    m[0].twist
                );
                twisted += 1;
            }
        }
        assert!(twisted > 10, "{twisted} sticking increments");
    }
}
