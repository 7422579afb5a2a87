//! The load stepping of a restart file, replayed from the case's own
//! stepper and checked against what it leaves.

use super::*;

/// The load stepping, checked against the case: the curve's increments are
/// replayed from the case's own stepper ([`Stepper::replay`]), and the
/// stored load factor, last step, pending schedule (fixed) or waypoints
/// (automatic) must be what that leaves, so a resumed run always continues
/// to the end of the case's load history. The automatic step size must lie
/// between the case's smallest and largest step; there are no failures or
/// cutbacks pending after a converged increment, and the total of cutbacks
/// is the curve's.
pub(in crate::files::restart) fn restore_stepper(
    ck: &mut Checkpoint,
    s: &Sections,
    model: &Model,
) -> Decoded<()> {
    let incs = &ck.increments;
    let path: Vec<(f64, usize)> = incs.iter().map(|i| (i.load_factor, i.cutbacks)).collect();
    let mut expect = Stepper::for_model(model);
    let initial = expect.clone();
    expect
        .replay(&path)
        .map_err(|m| format!("section curve: {m}"))?;
    let n = incs.len();
    let at = |k: usize| if k == 0 { 0.0 } else { incs[k - 1].load_factor };
    let (end, last) = (at(n), if n == 0 { 0.0 } else { at(n) - at(n - 1) });
    let total: u64 = incs.iter().map(|i| i.cutbacks as u64).sum();
    restore_position(ck, s, n, end, last)?;
    restore_schedule(ck, s, expect, &initial, n)?;
    restore_counters(ck, s, model, n, total)
}

/// Where the curve ends: the load factor `end` of increment `n`, the last
/// step `last` of the curve, and the predictor's direction (a value per
/// dof, or none).
fn restore_position(
    ck: &mut Checkpoint,
    s: &Sections,
    n: usize,
    end: f64,
    last: f64,
) -> Decoded<()> {
    let nu = ck.committed.u.len();
    ck.lambda = s.finite("load_factor", Some(1))?[0];
    if ck.lambda.to_bits() != end.to_bits() {
        return Err(format!(
            "section load_factor: load factor {}, but increment {n} ended at {}",
            num(ck.lambda),
            num(end)
        ));
    }
    ck.last_step = s.finite("last_step", Some(1))?[0];
    if ck.last_step.to_bits() != last.to_bits() {
        return Err(format!(
            "section last_step: {}, but the curve's last step is {}",
            num(ck.last_step),
            num(last)
        ));
    }
    // the predictor's direction: a value per dof, or none (the next
    // increment then starts from the committed state)
    let v = s.f("last_du", None)?;
    if !v.is_empty() && v.len() != nu {
        return Err(format!(
            "section last_du has {} values, the model needs {nu} (or none)",
            v.len()
        ));
    }
    all_finite("last_du", v)?;
    all_within(
        "last_du",
        v,
        MAX_DISPLACEMENT,
        "mm",
        "the displacement range of a case",
    )?;
    ck.last_du = v.clone();
    Ok(())
}

/// The pending schedule (fixed steps) or the waypoints ahead (automatic
/// steps) and the step size: what the case's stepper `expect`, replayed
/// over the curve's `n` increments from `initial`, leaves.
fn restore_schedule(
    ck: &mut Checkpoint,
    s: &Sections,
    expect: Stepper,
    initial: &Stepper,
    n: usize,
) -> Decoded<()> {
    let pl = s.f("pending_load_factor", None)?;
    let pd = s.u("pending_depth", None)?;
    if pl.len() != pd.len() {
        return Err("pending schedule: lengths differ".into());
    }
    let pending: Vec<(f64, usize)> = pl.iter().zip(pd).map(|(&l, &d)| (l, d as usize)).collect();
    let waypoints = s.f("auto_waypoints", None)?;
    let auto = expect.mode() == crate::input::case::StepControl::Auto;
    // the mode not in force never changes its part of the stepper
    // a run stopped exactly at a waypoint may hold it or not yet: compare
    // the waypoints ahead of the load factor
    let (waypoints, ahead) = if auto {
        let mut w = waypoints.clone();
        crate::solve::stepping::drop_reached(&mut w, ck.lambda);
        (w, expect.waypoints_ahead(ck.lambda))
    } else {
        (waypoints.clone(), initial.waypoints.clone())
    };
    let (want_pending, want_waypoints) = if auto {
        (&initial.pending, &ahead)
    } else {
        (&expect.pending, &ahead)
    };
    if !same_schedule(&pending, want_pending) {
        return Err(format!(
            "the pending schedule (section pending_load_factor) is not what the case's schedule leaves after increment {n}: {} found, {} expected",
            describe(pending.iter().map(|p| p.0)),
            describe(want_pending.iter().map(|p| p.0))
        ));
    }
    if !same_values(&waypoints, want_waypoints) {
        return Err(format!(
            "the waypoints (section auto_waypoints) are not the case's load history after increment {n}: {} found, {} expected",
            describe(waypoints.iter().copied()),
            describe(want_waypoints.iter().copied())
        ));
    }
    ck.stepper = expect;
    let step = s.f("auto_step", Some(1))?[0];
    let (lo, hi) = ck.stepper.step_bounds();
    let fits = if auto {
        step.is_finite() && step >= lo * 0.999_999 && step <= hi
    } else {
        step.to_bits() == initial.step.to_bits()
    };
    if !fits {
        return Err(if auto {
            format!(
                "section auto_step: step {}, outside the case's steps [{}, {}]",
                num(step),
                num(lo),
                num(hi)
            )
        } else {
            format!(
                "section auto_step: {}, but fixed steps leave it at {}",
                num(step),
                num(initial.step)
            )
        });
    }
    ck.stepper.step = step;
    Ok(())
}

/// The counters: no failure or cutback pending after a converged increment,
/// the curve's `total` of cutbacks, Newton iterations, factorizations and
/// the interface loop's counts within what a run of `n` increments can
/// count, and the elastic ratio of the last step.
fn restore_counters(
    ck: &mut Checkpoint,
    s: &Sections,
    model: &Model,
    n: usize,
    total: u64,
) -> Decoded<()> {
    let failures = s.u("auto_failures", Some(1))?[0];
    let cb = s.u("cutbacks", Some(2))?;
    if failures != 0 || cb[1] != 0 || cb[0] != total {
        return Err(format!(
            "sections auto_failures/cutbacks: {failures} failures and {} cutbacks pending, {} cutbacks in all, where a converged increment leaves none pending and the curve counts {total}",
            cb[1], cb[0]
        ));
    }
    ck.stepper.failures = 0;
    (ck.cutbacks_total, ck.cutbacks_here) = (total as usize, 0);
    let ct = s.u("counters", Some(2))?;
    // the event searches' share of the Newton iterations; the bound is on
    // the run's own
    let ev = s.u("event_counters", Some(1))?[0];
    if ev > ct[0] {
        return Err(format!(
            "section event_counters: {ev} Newton iterations of event searches, more than the {} of the whole run",
            ct[0]
        ));
    }
    let most = most_iterations(model, n as u64, total);
    for (v, what) in [(ct[0] - ev, "Newton iterations"), (ct[1], "factorizations")] {
        if u128::from(v) > most {
            return Err(format!(
                "section counters: {v} {what}, more than a run of this case can count after {n} increments and {total} cutbacks ({most}: per step attempt a predicted and a plain solve, each with {} stabilization levels, and a first-yield search, at the iteration limit {}, × {COUNTER_MARGIN})",
                stabilize::LEVELS,
                model.solver.iteration_limit()
            ));
        }
    }
    (ck.iterations, ck.factorizations) = (ct[0] as usize, ct[1] as usize);
    ck.event_iterations = ev as usize;
    // the interface loop runs at most once per Newton iteration, at most
    // MAX_INNER iterations each, and falls back at most once per run of it
    let lc = s.u("interface_counters", Some(3))?;
    let inner = crate::solve::newton::interface_loop::MAX_INNER as u64;
    if lc[0] > ct[0] || lc[2] > lc[0] || lc[1] > lc[0].saturating_mul(inner) {
        return Err(format!(
            "section interface_counters: {} loops, {} iterations and {} fallbacks, where a run of {} Newton iterations has at most one loop per iteration, {inner} iterations per loop and one fallback per loop",
            lc[0], lc[1], lc[2], ct[0]
        ));
    }
    ck.interface = crate::solve::newton::interface_loop::LoopStats {
        loops: lc[0] as usize,
        iterations: lc[1] as usize,
        fallbacks: lc[2] as usize,
    };
    ck.elastic_ratio_prev = s.finite("elastic_ratio_prev", Some(1))?[0];
    if ck.elastic_ratio_prev < 0.0 {
        return Err(format!(
            "section elastic_ratio_prev: {} is negative",
            num(ck.elastic_ratio_prev)
        ));
    }
    Ok(())
}

pub(in crate::files::restart) fn same_values(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

pub(in crate::files::restart) fn same_schedule(a: &[(f64, usize)], b: &[(f64, usize)]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| x.0.to_bits() == y.0.to_bits() && x.1 == y.1)
}

/// "N targets, last L" of a list stored last first.
pub(in crate::files::restart) fn describe(v: impl Iterator<Item = f64>) -> String {
    let v: Vec<f64> = v.collect();
    match v.first() {
        Some(&l) => format!("{} targets to λ = {}", v.len(), num(l)),
        None => "none".into(),
    }
}
