//! The increments a case plans, from its `[solver]` table and the
//! breakpoints of its load histories: the waypoints no step crosses and the
//! fixed schedule through them (docs/case-schema.md, "Load histories").
//! Pure functions of the input, below the model and the solver: the loads
//! use them to bound a case's length, the stepper to march.

use crate::input::case::{SolverSpec, StepControl};

/// The pseudo-times a run with histories must stop at, ascending: the
/// breakpoints after 0 (the model's [`crate::model::Model::breakpoints`]),
/// ending at the last one or at 1, whichever is later. Empty without
/// histories.
pub fn waypoints(breakpoints: &[f64]) -> Vec<f64> {
    if breakpoints.is_empty() {
        return Vec::new();
    }
    let mut w: Vec<f64> = breakpoints.iter().copied().filter(|&t| t > 0.0).collect();
    w.push(1.0);
    w.sort_by(f64::total_cmp);
    w.dedup();
    w
}

/// The number of equal steps of a segment of length `len` at `per_unit`
/// steps per unit of pseudo-time: ceil(len · per_unit), at least 1, where a
/// product within round-off of an integer counts as that integer (no sliver
/// step from 0.3 · 10 = 3.0000000000000004).
pub fn segment_steps(len: f64, per_unit: usize) -> usize {
    let x = len * per_unit as f64;
    let r = x.round();
    let k = if (x - r).abs() <= 1e-9 * r.max(1.0) {
        r
    } else {
        x.ceil()
    };
    (k as usize).max(1)
}

/// The fixed schedule of a run with histories: from t = 0 through every
/// waypoint (ascending, see [`waypoints`]), each segment in
/// [`segment_steps`] equal steps; `first` (when shorter than the first
/// segment) is the first step, the rest of that segment split alike.
pub(crate) fn segment_schedule(waypoints: &[f64], per_unit: usize, first: Option<f64>) -> Vec<f64> {
    let mut out = Vec::new();
    let mut a = 0.0;
    for (i, &b) in waypoints.iter().enumerate() {
        let mut start = a;
        if let Some(f) = first.filter(|&f| i == 0 && f < b - a) {
            start = a + f;
            out.push(start);
        }
        let k = segment_steps(b - start, per_unit);
        out.extend((1..k).map(|j| start + (b - start) * j as f64 / k as f64));
        out.push(b);
        a = b;
    }
    out
}

/// The fixed schedule: the case's own without histories, else
/// `segment_schedule` through the breakpoints.
pub fn schedule(spec: &SolverSpec, breakpoints: &[f64]) -> Vec<f64> {
    let ways = waypoints(breakpoints);
    if ways.is_empty() {
        spec.schedule()
    } else {
        segment_schedule(&ways, spec.n_increments(), spec.first_increment)
    }
}

/// Increments planned: the schedule's length (counted, not built), or
/// None for automatic control.
pub fn planned(spec: &SolverSpec, breakpoints: &[f64]) -> Option<usize> {
    if spec.step_mode() != StepControl::Fixed {
        return None;
    }
    let ways = waypoints(breakpoints);
    if ways.is_empty() {
        return Some(spec.schedule().len());
    }
    let first = spec.first_increment.filter(|&f| f < ways[0]);
    let mut a = first.unwrap_or(0.0);
    let mut n = usize::from(first.is_some());
    for &b in &ways {
        n = n.saturating_add(segment_steps(b - a, spec.n_increments()));
        a = b;
    }
    Some(n)
}
