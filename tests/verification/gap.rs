//! Force control across a gap and bodies held only through the interface
//! (src/solve/stabilization/mod.rs): the stabilized answer once contact is established
//! equals the displacement-controlled one and the gap-free one; the
//! stabilization's dissipated energy stays within its stated fraction; a run
//! that cannot be solved names the floating body.

use crate::common;
use asperity::model::Model;
use asperity::solve::{Increment, Observer, RunResult, State};

struct Quiet;
impl Observer for Quiet {
    fn increment(&mut self, _: &Model, _: &State, _: &Increment) -> asperity::error::Result<()> {
        Ok(())
    }
}

fn gap_case() -> String {
    std::fs::read_to_string(common::root().join("cases/punch-gap/case.toml")).unwrap()
}

fn solve(model: &Model) -> RunResult {
    asperity::app::driver::solve(model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"))
}

/// Largest difference of two displacement fields over the largest displacement.
fn field_difference(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

#[test]
fn force_control_across_a_gap_equals_displacement_control_at_the_same_contact_force() {
    // elastic range (first yield is at 155 MPa): the end state does not depend on the path
    let text = gap_case().replace("pressure = 250.0", "pressure = 100.0");
    assert!(text.contains("pressure = 100.0") && text.contains("gap = 0.01"));
    let text = text.replace("increments = 20", "increments = 4");
    let force = common::model(&text);
    let rf = solve(&force);
    let st = rf
        .stabilization
        .as_ref()
        .expect("the gap needs the stabilization");
    assert!(st.released >= 1 && st.stabilized == 0, "{st:?}");
    assert_eq!(st.dissipated, 0.0);
    let uf = &rf.final_state.u;
    let ff = rf.increments.last().unwrap().measures.normal_force;
    // 100 MPa on the 20 mm half punch, 1 mm thick
    assert!(common::rel(ff, 2000.0) < 1e-7, "contact force {ff}");

    // the same model with the punch top driven to the force-controlled
    // displacements instead of loaded: the punch is held by its boundary
    // conditions, no stabilization is involved
    let (head, tail) = text.split_once("[[load]]").unwrap();
    let tail = tail.split_once("[solver]").unwrap().1;
    let text_d = format!("{head}[[boundary]]\nset = \"punch.top\"\nuy = -1.0\n\n[solver]{tail}");
    let mut disp = common::model(&text_d);
    let mut driven = 0;
    for (d, v) in disp.prescribed.iter_mut() {
        if *v == -1.0 {
            *v = uf[*d];
            driven += 1;
        }
    }
    assert!(driven > 5, "{driven} top dofs");
    let rd = solve(&disp);
    assert!(rd.stabilization.is_none());
    let ud = &rd.final_state.u;
    let fd = rd.increments.last().unwrap().measures.normal_force;
    let du = field_difference(uf, ud);
    eprintln!(
        "contact force: force control {ff:.12e} N, displacement control {fd:.12e} N; \
         displacement fields differ by {du:.3e} of the largest"
    );
    assert!(common::rel(ff, fd) < 1e-6, "{ff} vs {fd}");
    assert!(du < 1e-6, "displacement fields differ by {du:.3e}");
    // the reaction of the driven top is the applied load
    assert!(common::rel(-rd.final_state.prescribed_reaction, 2000.0) < 1e-6);
}

#[test]
fn a_uniform_gap_only_shifts_the_punch() {
    // the shipped case against punch-plane-stress (no gap): same loads, same
    // foundation, the punch lower by the gap
    let gap = solve(&common::model(&gap_case()));
    let flush_text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let flush = solve(&common::model(&flush_text));
    assert_eq!(gap.increments.len(), flush.increments.len());
    for (a, b) in gap.increments.iter().zip(&flush.increments) {
        assert_eq!(a.load_factor, b.load_factor);
        let (ma, mb) = (a.measures, b.measures);
        assert!(common::rel(ma.normal_force, mb.normal_force) < 1e-7);
        assert!(
            common::rel(ma.center_displacement, mb.center_displacement) < 1e-6,
            "increment {}: {} vs {}",
            a.increment,
            ma.center_displacement,
            mb.center_displacement
        );
    }
    let (fa, fb) = (gap.first_yield.unwrap(), flush.first_yield.unwrap());
    assert!(common::rel(fa.load_factor, fb.load_factor) < 1e-6);
    let m = common::model(&gap_case());
    let punch = m.mesh.bodies.iter().position(|b| b == "punch").unwrap();
    let (ug, uf) = (&gap.final_state.u, &flush.final_state.u);
    let mut worst: f64 = 0.0;
    for el in m.mesh.elements.iter().filter(|e| e.body == punch) {
        for &n in el.nodes() {
            worst = worst
                .max((ug[2 * n] - uf[2 * n]).abs())
                .max((ug[2 * n + 1] - (uf[2 * n + 1] - 0.01)).abs());
        }
    }
    eprintln!("punch: gap run − (flush run − 0.01 mm) up to {worst:.3e} mm");
    assert!(worst < 1e-8, "{worst}");
    let st = gap.stabilization.unwrap();
    assert_eq!(
        (st.released, st.stabilized),
        (1, 0),
        "only the first step floats"
    );

    // automatic steps: the step control sees the released solve's iterations,
    // so it takes the same steps as without the gap
    let auto = |t: &str| {
        let t = t
            .replace("increments = 20\n", "")
            .replace("first_increment = 0.05", "");
        solve(&common::model(&t))
    };
    let (ga, fa) = (auto(&gap_case()), auto(&flush_text));
    assert_eq!(ga.increments.len(), fa.increments.len());
    for (a, b) in ga.increments.iter().zip(&fa.increments) {
        // steps chosen from plastic strain increments equal to round-off
        assert!(common::rel(a.load_factor, b.load_factor) < 1e-12);
        assert!(
            common::rel(
                a.measures.center_displacement,
                b.measures.center_displacement
            ) < 1e-6
        );
    }
}

/// punch-plane-stress with an elastic foundation, loaded, unloaded to zero and
/// loaded again; plain Newton (`interface_loop = false`). The tests below
/// hold the zero-load state and the reloaded forces to 1e-9, below the
/// Newton tolerance, which the interface loop's path to the same
/// equilibrium honours (6e-7 N left at zero load); and without the
/// stabilization the loop converges the step to zero load, to the punch
/// touching the foundation at zero pressure: an equilibrium, one of many
/// (any lift-off is one too), which plain Newton refuses to pick.
fn unloading_case() -> String {
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let text = text
        .replace("yield_stress = 196.0\n", "")
        .replace(
            "increments = 20\n",
            "load_factors = [0.5, 1.0, 0.5, 0.0, 0.5, 1.0]\n",
        )
        .replace("first_increment = 0.05", "");
    assert!(text.contains("load_factors") && !text.contains("196.0"));
    common::with_interface_loop(&text, false)
}

#[test]
fn unloading_to_zero_is_held_by_the_stabilization_within_its_energy_limit() {
    let r = solve(&common::model(&unloading_case()));
    assert_eq!(r.increments.len(), 6);
    let zero = &r.increments[3];
    assert_eq!(zero.load_factor, 0.0);
    let st = r.stabilization.as_ref().expect("stabilized");
    eprintln!("{st:?}");
    assert_eq!(st.stabilized, 1, "{st:?}");
    assert!(st.dissipated > 0.0 && st.internal > 0.0);
    assert!(st.dissipated <= st.limit * st.internal, "{st:?}");
    // what is left in the interface at zero load is the springs' holding force: tiny
    let peak = r.increments[1].measures;
    assert!(zero.measures.normal_force.abs() < 1e-6 * peak.normal_force);
    // elastic: the punch comes back to where it started, but for the springs'
    // offset (µm-scale here, against a 53 µm settlement under load)
    let settle = zero.measures.center_displacement.abs();
    eprintln!(
        "at zero load: contact force {:.3e} N, settlement {settle:.3e} mm (under load {:.3e} mm)",
        zero.measures.normal_force, peak.center_displacement
    );
    assert!(settle < 1e-3 * peak.center_displacement.abs());
    // reloaded from the stabilized state, the answers are the first loading's
    // (elastic: no path dependence), whatever the stabilization left behind
    for (again, first) in [(4, 0), (5, 1)] {
        let (a, b) = (r.increments[again].measures, r.increments[first].measures);
        eprintln!(
            "λ = {}: settlement {:.12e} vs {:.12e} mm",
            r.increments[again].load_factor, a.center_displacement, b.center_displacement
        );
        assert!(common::rel(a.center_displacement, b.center_displacement) < 1e-7);
        assert!(common::rel(a.normal_force, b.normal_force) < 1e-9);
    }

    // with a limit it cannot meet, the step fails and says why
    let strict = unloading_case().replace(
        "[solver]\n",
        "[solver]\nstabilization_energy = 1e-15\nmax_cutbacks = 1\n",
    );
    let e = asperity::app::driver::solve(&common::model(&strict), &mut Quiet)
        .expect_err("cannot meet the limit")
        .to_string();
    eprintln!("{e}");
    assert!(e.contains("body \"punch\" carries no load"), "{e}");
    assert!(
        e.contains("stabilization_energy = 0.000000000000001"),
        "{e}"
    );
}

#[test]
fn without_stabilization_the_failure_names_the_floating_body() {
    let text = gap_case().replace(
        "[solver]\n",
        "[solver]\nstabilization = \"off\"\nmax_cutbacks = 1\n",
    );
    let e = asperity::app::driver::solve(&common::model(&text), &mut Quiet)
        .expect_err("a floating punch cannot be solved without stabilization")
        .to_string();
    eprintln!("{e}");
    assert!(
        e.contains("body \"punch\" is not in contact")
            && e.contains("nothing else holds it")
            && e.contains("interface \"contact\""),
        "{e}"
    );
    let text = unloading_case().replace(
        "[solver]\n",
        "[solver]\nstabilization = \"off\"\nmax_cutbacks = 1\n",
    );
    let e = asperity::app::driver::solve(&common::model(&text), &mut Quiet)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("body \"punch\" carries no load at λ = 0"), "{e}");
}

#[test]
fn reloading_after_unloading_a_plastic_foundation_to_zero() {
    // the plain step to λ = 0 converges, leaving pairs touching at ~1e-17 MPa;
    // the reloading step from there diverged before the stabilization (its
    // tangent is 2p/u of that pressure) and is now stabilized and released
    let text = std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml"))
        .unwrap()
        .replace(
            "increments = 20\n",
            "load_factors = [0.2, 0.4, 0.6, 0.8, 1.0, 0.5, 0.0, 0.5, 1.0]\n",
        )
        .replace("first_increment = 0.05", "");
    // plain Newton: the zero-load force below is held to 1e-9 N
    // (`unloading_case`)
    let text = common::with_interface_loop(&text, false);
    let r = solve(&common::model(&text));
    assert_eq!(r.increments.len(), 9);
    let st = r.stabilization.as_ref().expect("the reload needs it");
    assert_eq!((st.released, st.stabilized), (1, 0), "{st:?}");
    let (zero, again, before) = (&r.increments[6], &r.increments[7], &r.increments[5]);
    assert_eq!(zero.load_factor, 0.0);
    assert!(zero.measures.normal_force.abs() < 1e-9);
    // back at λ = 0.5 close to the unloading branch's state (reverse
    // plasticity at unloading is the only difference)
    assert!(
        common::rel(
            again.measures.center_displacement,
            before.measures.center_displacement
        ) < 1e-5
    );
}
