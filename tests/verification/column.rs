//! Elastic column across a compliant interface against its closed form.
//!
//! Two stacked blocks of width w (plane stress, free right side, symmetry on the
//! left), uniform pressure q on top, bottom held in y. The stress is uniform
//! (σ_yy = −q), so the FE solution is exact and the top settles by
//! u = q (h₁ + h₂)/E + c_N q^m (the interface approach of eq. 2.1).

use crate::common::{self, CaseText};
use asperity::model::Model;
use asperity::solve::{Increment, Observer, State};

use crate::common::Quiet;

/// The two blocks, their joint (with an initial gap if given) and supports;
/// the load and the solver are added to it.
fn column(plane: &str, m: f64, weights: &str, gap: Option<f64>) -> CaseText {
    let mut case = common::case()
        .plane(plane)
        .thickness(2.0)
        .block("top", [0.0, 10.0], [3], [0.0, 15.0], [3])
        .rx([0.5])
        .block("bottom", [0.0, 10.0], [3], [-25.0, 0.0], [4])
        .rx([0.5])
        .ry([0.3])
        .interface("joint", "top", "bottom")
        .material("top", 70000.0, 0.33)
        .material("bottom", 70000.0, 0.33)
        .law("joint", "power", 0.002, m)
        .weights(weights);
    if let Some(g) = gap {
        case = case.gap(g);
    }
    case.ux("top.left", 0.0)
        .ux("bottom.left", 0.0)
        .uy("bottom.bottom", 0.0)
}

/// The column under the pressure 120 MPa on its top, in 4 steps.
fn pressed(column: CaseText) -> String {
    column
        .pressure("top.top", 120.0)
        .solver("increments = 4")
        .tolerances(1e-12, 1e-12)
        .build()
}

fn settle(text: &str) -> (f64, f64, Model, State) {
    let model = common::model(text);
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap();
    let st = r.final_state;
    // top-left corner node: maximum y, x = 0
    let top = (0..model.mesh.nodes.len())
        .filter(|&n| model.mesh.nodes[n][0] == 0.0)
        .max_by(|&a, &b| model.mesh.nodes[a][1].total_cmp(&model.mesh.nodes[b][1]))
        .unwrap();
    let u = -st.u[2 * top + 1];
    let p = r.increments.last().unwrap().measures.mean_pressure;
    (u, p, model, st)
}

#[test]
fn plane_stress_column_matches_closed_form_for_m_half_and_one() {
    let (q, e, h, c): (f64, f64, f64, f64) = (120.0, 70000.0, 40.0, 0.002);
    for m in [0.5, 1.0] {
        for w in ["lumped", "consistent"] {
            let (u, p, model, st) = settle(&pressed(column("stress", m, w, None)));
            let exact = q * h / e + c * q.powf(m);
            assert!(
                common::rel(u, exact) < 1e-9,
                "m={m} {w}: u={u} exact={exact}"
            );
            assert!(common::rel(p, q) < 1e-9, "mean pressure {p} vs {q}");
            // every pair carries the same approach c q^m
            let im = &model.interfaces[0];
            for pr in &im.pairs {
                let un = im.pair_approach(pr, &st.u);
                assert!(
                    common::rel(un, c * q.powf(m)) < 1e-9,
                    "pair at x={}: {un}",
                    pr.x[0]
                );
            }
        }
    }
}

#[test]
fn plane_strain_column_matches_closed_form() {
    // plane strain with free sides: ε_yy = −q (1 − ν²)/E
    let (q, e, nu, h, c, m): (f64, f64, f64, f64, f64, f64) =
        (120.0, 70000.0, 0.33, 40.0, 0.002, 0.5);
    let (u, _, _, _) = settle(&pressed(column("strain", m, "lumped", None)));
    let exact = q * h * (1.0 - nu * nu) / e + c * q.powf(m);
    assert!(common::rel(u, exact) < 1e-9, "u={u} exact={exact}");
}

#[test]
fn initial_gap_adds_to_the_settlement_under_displacement_free_load() {
    // A closed joint with a prescribed start pressure works with a negative gap
    // (interference): the approach is c q^m and the settlement drops by the interference.
    let (q, e, h, c, m, g): (f64, f64, f64, f64, f64, f64) =
        (120.0, 70000.0, 40.0, 0.002, 0.5, -0.01);
    let (u, _, _, _) = settle(&pressed(column("stress", m, "lumped", Some(g))));
    let exact = q * h / e + c * q.powf(m) + g;
    assert!(common::rel(u, exact) < 1e-9, "u={u} exact={exact}");
}

/// Records every converged increment.
struct Record(Vec<(f64, f64, Vec<asperity::physics::contact::Status>)>);
impl Observer for Record {
    fn increment(&mut self, _: &Model, s: &State, inc: &Increment) -> asperity::Result<()> {
        self.0.push((
            inc.load_factor,
            inc.measures.mean_pressure,
            s.status.clone(),
        ));
        Ok(())
    }
}

#[test]
fn loss_of_contact_and_recontact_follow_the_closed_form() {
    // top pushed down by δ = 0.05 λ mm across an initial gap g₀ = 0.01 mm, then
    // lifted (the joint opens again) and pushed back down (re-contact)
    let (e, h, c, m, g0): (f64, f64, f64, f64, f64) = (70000.0, 40.0, 0.002, 0.5, 0.01);
    let text = column("stress", m, "lumped", Some(g0))
        .uy("top.top", -0.05)
        .solver("load_factors = [0.1, 0.3, 0.6, 1.0, 0.5, 0.15, 0.6]")
        .tolerances(1e-12, 1e-12)
        .build();
    let model = common::model(&text);
    let mut rec = Record(Vec::new());
    asperity::app::driver::solve(&model, &mut rec).unwrap();
    assert_eq!(rec.0.len(), 7);
    for (lambda, p, status) in &rec.0 {
        let delta = 0.05 * lambda;
        // closed form: δ − g₀ = q h/E + c q^m when δ > g₀, else q = 0
        let q = if delta <= g0 {
            0.0
        } else {
            let mut q: f64 = 10.0;
            for _ in 0..100 {
                let f = q * h / e + c * q.powf(m) - (delta - g0);
                let df = h / e + c * m * q.powf(m - 1.0);
                q -= f / df;
            }
            q
        };
        let closed = status
            .iter()
            .all(|s| *s == asperity::physics::contact::Status::Closed);
        let open = status
            .iter()
            .all(|s| *s == asperity::physics::contact::Status::Open);
        if q == 0.0 {
            assert!(
                open && *p == 0.0,
                "λ = {lambda}: expected an open joint, p = {p}"
            );
        } else {
            assert!(closed, "λ = {lambda}: expected a closed joint");
            assert!(
                common::rel(*p, q) < 1e-8,
                "λ = {lambda}: p = {p}, closed form {q}"
            );
        }
    }
}
