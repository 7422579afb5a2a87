//! The torque limit: where a body held about the axis only by friction can
//! no longer hold the torque on it.
//!
//! A torque-controlled twist has an equilibrium only while the torque T(λ)
//! stays within what the interfaces' friction holds, Σ μ p_N r dA (μ the
//! friction cap of eq. 2.21): the torque raised past it, or the pressure
//! taken off under it (a hub spun up, or warmed, under its torque), leaves
//! no state to converge to, and the run's steps fail however short. When the
//! step control gives up on such a step (the stabilization names the body:
//! its torque at least 98 % of what friction held at the committed
//! pressures), the limit is located by
//! bisection on the load factor between the committed state, which held,
//! and the step that failed: a step from the committed state to the
//! midpoint that converges held, one that does not did not, until the
//! bracket is at most `[output] event_tolerance` wide. The run ends there
//! with the event `torque_limit`: its load factor the first where nothing
//! held, its values those of the last state that held: the torque on the
//! body (what its interfaces' friction held between them), the sum of
//! their normal forces, the pressures; its interface the first of them. The event is where
//! the steps stop converging: close to the limit the sticking core left
//! carries the whole torque, and Newton could stop short of it (the search
//! starts only when the torque is within 2 % of the friction's hold); a
//! fit turned by a torque ramp ends within 3e-8 of its slip torque
//! (tests/verification/service.rs).
//!
//! The steps of the search are not committed (the run's last increment is
//! the last it committed) and the stabilization's account is left as the
//! run left it. Every decision is taken on values every MPI rank holds
//! whole, and every solve is collective.

use super::events::{Event, Kind, Method, MAX_HALVINGS};
use super::{Checkpoint, Engine, StepFailure};
use crate::error::Result;
use crate::physics::element::solid::Response;

/// What the search ended with.
pub(super) enum Limited {
    /// The limit, located.
    At(Event),
    /// A second stop signal abandoned the search.
    Interrupted(i32),
}

/// The torque limit crossed by the failed step from the committed state to
/// `target`, located, when the step failed because a body held only by
/// friction cannot hold its torque there; `None` for any other failure.
pub(super) fn locate(engine: &mut Engine, ck: &Checkpoint, target: f64) -> Result<Option<Limited>> {
    let model = engine.model;
    let Some(st) = engine.stabilizer.as_ref() else {
        return Ok(None);
    };
    let Some(limit) = st.friction_limit(model, &ck.committed.u, target) else {
        return Ok(None);
    };
    let saved = engine.stabilizer.clone();
    let before = engine.stats.iterations;
    let tol = model.plan.event_tolerance;
    let (mut a, mut b) = (ck.lambda, target);
    let mut held = ck.committed.clone();
    for _ in 0..MAX_HALVINGS {
        let c = 0.5 * (a + b);
        if (b - a).abs() <= tol || c == a || c == b {
            break;
        }
        match engine.step(&ck.committed, c, Response::Plastic) {
            Ok((s, _)) => (a, held) = (c, s),
            Err(StepFailure::Interrupted { signal, .. }) => {
                engine.stabilizer = saved;
                return Ok(Some(Limited::Interrupted(signal)));
            }
            Err(f) if f.is_fatal() => return Err(f.into_error()),
            Err(_) => b = c,
        }
    }
    engine.stabilizer = saved;
    engine.stats.event_iterations += engine.stats.iterations - before;
    // the body's clamp: the normal forces of all its interfaces with
    // friction; the torque on it, which they hold between them
    let normal: f64 = (limit.interfaces.iter())
        .map(|&i| super::events::joint_in(model, &held, i).normal_force)
        .sum();
    let st = engine.stabilizer.as_ref().expect("it named the limit");
    let torque = st.applied_torque(model, limit.body, a);
    let meas = engine.measures(&held);
    Ok(Some(Limited::At(Event {
        kind: Kind::TorqueLimit,
        interface: Some(limit.interfaces[0]),
        load_factor: b,
        before: a,
        after: b,
        // the increment the run could not take
        increment: ck.increments.len() + 1,
        method: Method::Bisection,
        converged: (b - a).abs() <= tol,
        solve_failed: false,
        // the body that lets go, where a first yield has its element
        place: [f64::NAN, f64::NAN, f64::NAN, limit.body as f64],
        values: [
            meas.total_load_kn,
            meas.mean_pressure,
            normal,
            f64::NAN,
            torque,
        ],
        record: engine.record(&held),
    })))
}
