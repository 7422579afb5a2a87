//! Which load factor to try next: the fixed schedule of the case, or automatic
//! step control between waypoints.
//!
//! Automatic control (`step_control = "auto"`) adapts the load-factor step to
//! two measures of the step just taken:
//! - how hard it was to solve: the Newton iteration count against a target
//!   (at most the target: may double; up to twice the target: keep; more:
//!   halve — full Newton only, as the fixed-matrix methods' rate near a limit
//!   load does not improve with smaller steps);
//! - how much it changed the path-dependent solution: the largest increment of
//!   equivalent plastic strain at any Gauss point against `plastic_strain_step`.
//!   Elastic steps are path-independent and may be large; plastic steps are not.
//!   A step whose plastic increment exceeds three times the target is redone at
//!   the size that would have met it (a cutback that costs accuracy nothing).
//!
//! A failed step is halved, as in the fixed schedule, with the committed state
//! restored; `max_cutbacks` bounds consecutive halvings.
//!
//! With load histories the march variable is the pseudo-time t and every
//! history breakpoint is a waypoint that no step crosses, in both modes: the
//! fixed schedule splits each segment between consecutive breakpoints into
//! ceil(length × `increments`) equal steps (`segment_schedule`); automatic
//! control takes each breakpoint as a waypoint. Without histories the
//! schedule is the case's own, as it always was.

use crate::input::case::{SolverSpec, StepControl};
pub use crate::model::schedule::{segment_steps, waypoints};

/// Relative tolerance under which two load factors are the same waypoint.
const SAME: f64 = 1e-12;
/// Largest automatic step (load factor) unless `max_increment` says otherwise.
const MAX_STEP: f64 = 0.25;
/// Full Newton's iteration target: at most this many, the step may double; up
/// to twice as many, it is kept; more, it is halved.
const NEWTON_TARGET_ITERATIONS: f64 = 6.0;
/// The fixed-matrix methods' target: this fraction of the iteration limit,
/// but at least [`MIN_FIXED_TARGET`].
const FIXED_TARGET_FRACTION: f64 = 1.0 / 8.0;
const MIN_FIXED_TARGET: f64 = 4.0;
/// A step whose largest plastic strain increment exceeds this many times
/// `plastic_strain_step` is redone.
const TOO_PLASTIC: f64 = 3.0;
/// The bounds of the plastic-strain factor of the next step.
const PLASTIC_FACTOR: (f64, f64) = (0.25, 2.0);
/// The step grows at most by this factor.
const GROWTH: f64 = 2.0;
/// The waypoint is taken when it is at most this many steps away (no sliver
/// of a step before it).
const WAYPOINT_REACH: f64 = 1.2;

/// The plan of load factors of a run.
#[derive(Clone, Debug)]
pub struct Stepper {
    pub(crate) mode: StepControl,
    /// Fixed mode: remaining targets, last first, with their cut depth.
    pub(crate) pending: Vec<(f64, usize)>,
    /// Auto mode: remaining waypoints, last first.
    pub(crate) waypoints: Vec<f64>,
    /// Auto mode: current step size (absolute load-factor change).
    pub(crate) step: f64,
    max_step: f64,
    min_step: f64,
    target_iterations: f64,
    /// Full Newton: the iteration count measures the step's nonlinearity.
    newton: bool,
    plastic_step: f64,
    /// Consecutive failures of the current step.
    pub(crate) failures: usize,
    max_cutbacks: usize,
}

/// Why a step is redone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Why {
    /// It did not converge (or failed otherwise).
    Failed,
    /// It converged with this largest plastic strain increment, too large.
    TooPlastic(f64),
}

/// What the stepper says after a failed or rejected step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Retry {
    /// Try this load factor next.
    At(f64),
    /// Too many cutbacks: give up.
    GiveUp,
}

impl Stepper {
    /// The stepper of a case without histories.
    pub fn new(spec: &SolverSpec) -> Stepper {
        Stepper::with_breakpoints(spec, &[])
    }

    /// The stepper of a model: its breakpoints are waypoints.
    pub fn for_model(model: &crate::model::Model) -> Stepper {
        Stepper::with_breakpoints(&model.solver, &model.breakpoints())
    }

    /// The stepper of a case whose histories have these breakpoints (empty:
    /// no histories, the case's own schedule).
    pub fn with_breakpoints(spec: &SolverSpec, breakpoints: &[f64]) -> Stepper {
        let ways = waypoints(breakpoints);
        let schedule = Stepper::schedule(spec, breakpoints);
        let waypoints: Vec<f64> = match &spec.load_factors {
            _ if !ways.is_empty() => ways.iter().rev().copied().collect(),
            Some(l) => l.iter().rev().copied().collect(),
            None => vec![1.0],
        };
        let first = spec
            .first_increment
            .unwrap_or(1.0 / spec.n_increments().max(1) as f64);
        let max_step = spec.max_increment.unwrap_or(MAX_STEP);
        Stepper {
            mode: spec.step_mode(),
            pending: schedule.into_iter().rev().map(|l| (l, 0)).collect(),
            waypoints,
            step: first.min(max_step),
            max_step,
            min_step: first.min(max_step) * 0.5f64.powi(spec.max_cutbacks as i32),
            target_iterations: match spec.method {
                crate::input::case::Method::FullNewton => NEWTON_TARGET_ITERATIONS,
                _ => (spec.iteration_limit() as f64 * FIXED_TARGET_FRACTION).max(MIN_FIXED_TARGET),
            },
            newton: spec.method == crate::input::case::Method::FullNewton,
            plastic_step: spec.plastic_strain_step,
            failures: 0,
            max_cutbacks: spec.max_cutbacks,
        }
    }

    /// Halvings allowed for one step before the run gives up.
    pub fn max_cutbacks(&self) -> usize {
        self.max_cutbacks
    }

    /// The load factor the history ends at.
    pub fn final_target(&self, lambda: f64) -> f64 {
        match self.mode {
            StepControl::Fixed => self.pending.first().map_or(lambda, |p| p.0),
            StepControl::Auto => self.waypoints.first().copied().unwrap_or(lambda),
        }
    }

    /// The fixed schedule ([`crate::model::schedule::schedule`]).
    pub fn schedule(spec: &SolverSpec, breakpoints: &[f64]) -> Vec<f64> {
        crate::model::schedule::schedule(spec, breakpoints)
    }

    /// Increments planned ([`crate::model::schedule::planned`]).
    pub fn planned(spec: &SolverSpec, breakpoints: &[f64]) -> Option<usize> {
        crate::model::schedule::planned(spec, breakpoints)
    }

    /// Where the first increment of a run from the start goes (`None`: a
    /// history with nothing to do): what [`Stepper::next`] of this, the
    /// case's initial stepper, gives at λ = 0, as the run asks it
    /// ([`crate::solve::run_from`]). `asperity check` prints it.
    pub(crate) fn first_target(&self) -> Option<f64> {
        self.clone().next(0.0)
    }

    /// The mode in force.
    pub fn mode(&self) -> StepControl {
        self.mode
    }

    /// Automatic control: the smallest and the largest step size.
    pub(crate) fn step_bounds(&self) -> (f64, f64) {
        (self.min_step, self.max_step)
    }

    /// The most increments a run from this (initial) stepper can converge:
    /// fixed, every scheduled step halved into at most 2^`max_cutbacks`
    /// pieces; automatic, the path through the waypoints in steps of at
    /// least half the smallest step, plus one step onto each waypoint.
    /// Saturates at `usize::MAX`.
    pub(crate) fn most_increments(&self) -> usize {
        match self.mode {
            StepControl::Fixed => {
                let pieces = 1usize
                    .checked_shl(self.max_cutbacks as u32)
                    .unwrap_or(usize::MAX);
                self.pending.len().saturating_mul(pieces)
            }
            StepControl::Auto => {
                let mut at = 0.0;
                let mut length = 0.0;
                for &w in self.waypoints.iter().rev() {
                    length += (w - at).abs();
                    at = w;
                }
                let steps = (length / (0.5 * self.min_step)).ceil();
                if steps.is_finite() && steps < 1e18 {
                    (steps as usize).saturating_add(self.waypoints.len() + 1)
                } else {
                    usize::MAX
                }
            }
        }
    }

    /// Follows the converged increments of a run from its start (`path`: the
    /// load factor of each and the cutbacks taken before it, in order) as
    /// this stepper, the case's initial one, would have taken them. Fixed:
    /// the schedule is replayed exactly (each cutback halves the step as
    /// [`Stepper::retry`] does; each increment must land on the target that
    /// gives, bit for bit), and `pending` ends as the run left it. Automatic:
    /// every waypoint passed is dropped as [`Stepper::next`] drops it, and
    /// each step must go towards the next waypoint, not past it, and not
    /// farther than the largest step allows. `Err` names the first increment
    /// that does not fit.
    pub(crate) fn replay(&mut self, path: &[(f64, usize)]) -> Result<(), String> {
        let mut lambda = 0.0;
        for (i, &(to, cutbacks)) in path.iter().enumerate() {
            let k = i + 1;
            // the values come from a file: quoted short (a forged 1e300 as
            // `1e300`, not 301 digits)
            let num = crate::numbers::exact;
            let Some(mut target) = self.next(lambda) else {
                return Err(format!(
                    "increment {k} (load factor {}) comes after the end of the case's load history",
                    num(to)
                ));
            };
            match self.mode {
                StepControl::Fixed => {
                    // a retry never gives up without leaving `target` (the
                    // depth bounds the loop by max_cutbacks)
                    for _ in 0..cutbacks {
                        match self.retry(lambda, target, Why::Failed) {
                            Retry::At(t) => target = t,
                            Retry::GiveUp => {
                                return Err(format!(
                                    "increment {k}: {cutbacks} cutbacks, more than the case allows ({})",
                                    self.max_cutbacks
                                ))
                            }
                        }
                    }
                    if to.to_bits() != target.to_bits() {
                        return Err(format!(
                            "increment {k}: load factor {}, where the case's schedule (with {cutbacks} cutbacks) gives {}",
                            num(to),
                            num(target)
                        ));
                    }
                }
                StepControl::Auto => {
                    let w = *self.waypoints.last().expect("next gave a target");
                    let (d, room) = (to - lambda, w - lambda);
                    let slack = 4.0 * f64::EPSILON * lambda.abs().max(w.abs()).max(1.0);
                    let cap = if to == w {
                        WAYPOINT_REACH * self.max_step
                    } else {
                        self.max_step
                    };
                    let toward = d == 0.0 || d.signum() == room.signum();
                    if !(toward && d.abs() <= room.abs() && d.abs() <= cap * (1.0 + 1e-9) + slack) {
                        return Err(format!(
                            "increment {k}: a step from {} to {}, where automatic control steps towards {} by at most {}",
                            num(lambda),
                            num(to),
                            num(w),
                            num(cap)
                        ));
                    }
                }
            }
            self.accepted(lambda, to, 0, 0.0);
            lambda = to;
        }
        Ok(())
    }

    /// Auto mode: the waypoints still ahead of `lambda` (those reached are
    /// dropped when the next step is chosen, so a stepper stopped exactly at
    /// a waypoint may or may not hold it yet).
    pub(crate) fn waypoints_ahead(&self, lambda: f64) -> Vec<f64> {
        let mut w = self.waypoints.clone();
        drop_reached(&mut w, lambda);
        w
    }

    /// The next load factor to try from `lambda`, or `None` when the history is done.
    pub fn next(&mut self, lambda: f64) -> Option<f64> {
        match self.mode {
            StepControl::Fixed => self.pending.last().map(|p| p.0),
            StepControl::Auto => {
                drop_reached(&mut self.waypoints, lambda);
                let w = *self.waypoints.last()?;
                let dir = (w - lambda).signum();
                let remaining = (w - lambda).abs();
                // take the waypoint when the step would leave less than a fifth of a step
                if remaining <= WAYPOINT_REACH * self.step {
                    Some(w)
                } else {
                    Some(lambda + dir * self.step)
                }
            }
        }
    }

    /// Must a converged step to `target` be redone smaller because its largest
    /// plastic strain increment `dpeeq` is too large for an accurate path?
    /// (Automatic control only; then call [`Stepper::retry`] with
    /// [`Why::TooPlastic`].)
    pub(crate) fn too_plastic(&self, lambda: f64, target: f64, dpeeq: f64) -> bool {
        self.mode == StepControl::Auto
            && dpeeq > TOO_PLASTIC * self.plastic_step
            && (target - lambda).abs() > self.min_step * 1.000001
    }

    /// The step to `target` converged in `iterations` with the largest plastic
    /// strain increment `dpeeq`, and is kept.
    pub fn accepted(&mut self, lambda: f64, target: f64, iterations: usize, dpeeq: f64) {
        match self.mode {
            StepControl::Fixed => {
                self.pending.pop();
            }
            StepControl::Auto => {
                let taken = (target - lambda).abs();
                let p = self.plastic_step;
                let its = iterations as f64;
                let by_iterations: f64 = if its <= self.target_iterations {
                    GROWTH
                } else if its <= 2.0 * self.target_iterations || !self.newton {
                    // the fixed-matrix methods' rate near a limit load does not
                    // improve with smaller steps: only a failure shrinks theirs
                    1.0
                } else {
                    0.5
                };
                let by_plasticity = if dpeeq > 0.0 {
                    (p / dpeeq).clamp(PLASTIC_FACTOR.0, PLASTIC_FACTOR.1)
                } else {
                    GROWTH
                };
                // grow from the step taken (a waypoint may have shortened it)
                let base = taken.max(self.step.min(taken * GROWTH));
                self.step =
                    (base * by_iterations.min(by_plasticity)).clamp(self.min_step, self.max_step);
                self.failures = 0;
            }
        }
    }

    /// The step to `target` from `lambda` failed (or was rejected): where to
    /// go next. Giving up leaves the stepper as it was (a run that ends
    /// there at its torque limit writes it to restart.bin).
    pub fn retry(&mut self, lambda: f64, target: f64, why: Why) -> Retry {
        match self.mode {
            StepControl::Fixed => {
                let (t, depth) = self.pending.last().copied().unwrap_or((target, 0));
                if depth >= self.max_cutbacks {
                    return Retry::GiveUp;
                }
                self.pending.pop();
                let mid = 0.5 * (lambda + t);
                self.pending.push((t, depth + 1));
                self.pending.push((mid, depth + 1));
                Retry::At(mid)
            }
            StepControl::Auto => {
                match why {
                    Why::TooPlastic(dpeeq) => {
                        let taken = (target - lambda).abs();
                        self.step = (taken * self.plastic_step / dpeeq).max(self.min_step);
                    }
                    Why::Failed => {
                        let step = 0.5 * (target - lambda).abs();
                        if self.failures >= self.max_cutbacks || step < self.min_step * 0.999999 {
                            return Retry::GiveUp;
                        }
                        self.failures += 1;
                        self.step = step;
                    }
                }
                match self.next(lambda) {
                    Some(t) => Retry::At(t),
                    None => Retry::GiveUp,
                }
            }
        }
    }
}

/// Drops the waypoints (last first) that `lambda` has reached.
pub(crate) fn drop_reached(waypoints: &mut Vec<f64>, lambda: f64) {
    while let Some(&w) = waypoints.last() {
        if (w - lambda).abs() <= SAME * w.abs().max(1.0) {
            waypoints.pop();
        } else {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(extra: &str) -> SolverSpec {
        toml::from_str(extra).unwrap()
    }

    /// Drives a stepper with a synthetic solver: `its(λ0, λ1)` iterations,
    /// `dp(λ0, λ1)` plastic increment, failure when `its` exceeds 30.
    fn drive(
        s: &mut Stepper,
        its: impl Fn(f64, f64) -> usize,
        dp: impl Fn(f64, f64) -> f64,
    ) -> Result<Vec<f64>, f64> {
        let mut lambda = 0.0;
        let mut path = vec![];
        let mut target = match s.next(lambda) {
            Some(t) => t,
            None => return Ok(path),
        };
        for _ in 0..10_000 {
            let n = its(lambda, target);
            let ok = n <= 30;
            let retry = if ok {
                let d = dp(lambda, target);
                if !s.too_plastic(lambda, target, d) {
                    s.accepted(lambda, target, n, d);
                    lambda = target;
                    path.push(lambda);
                    match s.next(lambda) {
                        Some(t) => {
                            target = t;
                            continue;
                        }
                        None => return Ok(path),
                    }
                }
                s.retry(lambda, target, Why::TooPlastic(d))
            } else {
                s.retry(lambda, target, Why::Failed)
            };
            match retry {
                Retry::At(t) => target = t,
                Retry::GiveUp => return Err(lambda),
            }
        }
        panic!("no end");
    }

    /// [`drive`] that records each increment with its cutbacks and the
    /// stepper after it (as a checkpoint holds it).
    fn drive_recorded(
        s: &mut Stepper,
        its: impl Fn(f64, f64) -> usize,
        dp: impl Fn(f64, f64) -> f64,
    ) -> Vec<((f64, usize), Stepper)> {
        let mut lambda = 0.0;
        let mut out = vec![];
        let mut cutbacks = 0;
        let Some(mut target) = s.next(lambda) else {
            return out;
        };
        for _ in 0..10_000 {
            let n = its(lambda, target);
            let d = dp(lambda, target);
            let retry = if n > 30 {
                s.retry(lambda, target, Why::Failed)
            } else if s.too_plastic(lambda, target, d) {
                s.retry(lambda, target, Why::TooPlastic(d))
            } else {
                s.accepted(lambda, target, n, d);
                lambda = target;
                out.push(((lambda, cutbacks), s.clone()));
                cutbacks = 0;
                match s.next(lambda) {
                    Some(t) => {
                        target = t;
                        continue;
                    }
                    None => return out,
                }
            };
            match retry {
                Retry::At(t) => {
                    cutbacks += 1;
                    target = t
                }
                Retry::GiveUp => panic!("gave up at {lambda}"),
            }
        }
        panic!("no end");
    }

    /// Replaying any prefix of a run's increments from the case's stepper
    /// leaves the pending schedule (fixed) or the waypoints (automatic) the
    /// run had after it, bit for bit: with cutbacks, unloading and
    /// histories; a changed load factor or cutback count does not replay.
    #[test]
    fn a_replay_of_the_increments_gives_the_stepper_the_run_had() {
        // fails above 0.6 unless shorter than 0.04, plastic above 0.5
        let its = |a: f64, b: f64| {
            if a.max(b) > 0.6 && (b - a).abs() > 0.04 {
                99
            } else {
                3
            }
        };
        let dp = |a: f64, b: f64| 0.1 * (b.max(0.5) - a.max(0.5)).abs();
        let specs = [
            "increments = 4",
            "increments = 5\nfirst_increment = 0.05",
            "load_factors = [0.5, 1.0, 0.3, 0.8]",
            "step_control = \"auto\"\nfirst_increment = 0.05\nplastic_strain_step = 0.002",
            "step_control = \"auto\"\nload_factors = [1.0, 0.2]\nfirst_increment = 0.1",
        ];
        for text in specs {
            for breakpoints in [&[][..], &[0.5, 1.5, 2.0][..]] {
                let sp = spec(text);
                let fresh = || Stepper::with_breakpoints(&sp, breakpoints);
                let run = drive_recorded(&mut fresh(), its, dp);
                assert!(run.iter().any(|r| r.0 .1 > 0), "{text}: no cutback");
                let path: Vec<(f64, usize)> = run.iter().map(|r| r.0).collect();
                assert!(run.len() <= fresh().most_increments(), "{text}");
                for k in 0..=run.len() {
                    let mut s = fresh();
                    s.replay(&path[..k])
                        .unwrap_or_else(|e| panic!("{text}: {e}"));
                    let want = if k == 0 {
                        fresh()
                    } else {
                        run[k - 1].1.clone()
                    };
                    let bits = |v: &[(f64, usize)]| {
                        v.iter().map(|p| (p.0.to_bits(), p.1)).collect::<Vec<_>>()
                    };
                    assert_eq!(bits(&s.pending), bits(&want.pending), "{text}, {k}");
                    assert_eq!(s.waypoints, want.waypoints, "{text}, {k}");
                }
                if sp.step_mode() == StepControl::Fixed {
                    let mut moved = path.clone();
                    moved[1].1 += 1;
                    assert!(fresh().replay(&moved).is_err(), "{text}");
                }
                let mut moved = path.clone();
                moved[2].0 = 1e3;
                assert!(fresh().replay(&moved).is_err(), "{text}");
            }
        }
    }

    #[test]
    fn fixed_mode_is_the_schedule_and_halves_on_failure() {
        let mut s = Stepper::new(&spec("increments = 4"));
        let path = drive(&mut s, |_, _| 3, |_, _| 0.0).unwrap();
        assert_eq!(path, vec![0.25, 0.5, 0.75, 1.0]);
        // a step failing above 0.6 unless shorter than 0.1
        let mut s = Stepper::new(&spec("increments = 4"));
        let path = drive(
            &mut s,
            |a, b| if b > 0.6 && b - a > 0.1 { 99 } else { 3 },
            |_, _| 0.0,
        )
        .unwrap();
        assert_eq!(
            path,
            vec![0.25, 0.5, 0.5625, 0.625, 0.6875, 0.75, 0.8125, 0.875, 0.9375, 1.0]
        );
    }

    #[test]
    fn auto_grows_in_easy_elastic_steps_and_ends_on_the_waypoint() {
        let mut s = Stepper::new(&spec(
            "step_control = \"auto\"\nfirst_increment = 0.01\nmax_increment = 0.3",
        ));
        let path = drive(&mut s, |_, _| 2, |_, _| 0.0).unwrap();
        assert_eq!(*path.last().unwrap(), 1.0);
        // 0.01, 0.03, 0.07, 0.15, then steps capped at 0.3
        assert!(path.len() <= 8, "{path:?}");
        for w in path.windows(2) {
            assert!(w[1] - w[0] <= 0.3 * 1.2 + 1e-12, "{path:?}");
        }
    }

    #[test]
    fn auto_limits_the_plastic_strain_increment() {
        // plastic strain rate 0.1 per unit load factor above 0.5
        let dp = |a: f64, b: f64| 0.1 * ((b.max(0.5) - a.max(0.5)).max(0.0));
        let mut s = Stepper::new(&spec(
            "step_control = \"auto\"\nfirst_increment = 0.1\nplastic_strain_step = 0.001",
        ));
        let path = drive(&mut s, |_, _| 4, dp).unwrap();
        let mut prev = 0.0;
        let mut worst: f64 = 0.0;
        for &l in &path {
            worst = worst.max(dp(prev, l));
            prev = l;
        }
        // every accepted step within 3x the target, most near it
        assert!(worst <= 0.003 + 1e-12, "worst {worst} in {path:?}");
        let plastic_steps = path.iter().filter(|&&l| l > 0.5).count();
        assert!(
            (40..=80).contains(&plastic_steps),
            "{plastic_steps} in {path:?}"
        );
    }

    #[test]
    fn auto_halves_failures_and_gives_up_at_the_floor() {
        let mut s = Stepper::new(&spec(
            "step_control = \"auto\"\nfirst_increment = 0.5\nmax_cutbacks = 3",
        ));
        // converges only for steps ≤ 0.1
        let path = drive(&mut s, |a, b| if b - a > 0.1 { 99 } else { 4 }, |_, _| 0.0).unwrap();
        assert_eq!(*path.last().unwrap(), 1.0);
        let mut s = Stepper::new(&spec(
            "step_control = \"auto\"\nfirst_increment = 0.5\nmax_cutbacks = 3",
        ));
        // never converges: 0.5, 0.25, 0.125, 0.0625, give up
        assert_eq!(drive(&mut s, |_, _| 99, |_, _| 0.0), Err(0.0));
    }

    #[test]
    fn auto_follows_unloading_waypoints() {
        let mut s = Stepper::new(&spec(
            "step_control = \"auto\"\nload_factors = [1.0, 0.2]\nfirst_increment = 0.1",
        ));
        let path = drive(&mut s, |_, _| 3, |_, _| 0.0).unwrap();
        assert!(path.contains(&1.0), "{path:?}");
        assert_eq!(*path.last().unwrap(), 0.2);
        let i = path.iter().position(|&l| l == 1.0).unwrap();
        assert!(path[i + 1..].windows(2).all(|w| w[1] < w[0]), "{path:?}");
    }
}
