//! Load histories: piecewise-linear tables from pseudo-time t to a factor
//! (docs/case-schema.md, "Load histories").
//!
//! The march variable of a run is the pseudo-time t. A case without any
//! history scales every load, prescribed displacement and nothing else by t
//! itself (t is then the load factor, as it always was). A case with at least
//! one history scales each load by its own history, and those without one by
//! the default ramp [[0, 0], [1, 1]], held at 1 afterwards.

/// The latest pseudo-time a history may name: a run beyond it would take
/// more steps than any case needs.
pub(crate) const MAX_TIME: f64 = 1.0e4;
/// Most points of one history.
pub(crate) const MAX_POINTS: usize = 10_000;
/// Most distinct times of all histories of a case together: each is an
/// increment of the run (a thousand load cycles of four points each take
/// 4 000).
pub(crate) const MAX_BREAKPOINTS: usize = 20_000;
/// The largest magnitude of a history's value (a factor on the loads).
pub(crate) const MAX_VALUE: f64 = 1.0e6;

/// A piecewise-linear table t → factor, held at its first value before the
/// first time and at its last value after the last time (as Abaqus
/// amplitudes).
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// (time, value), times strictly increasing, the first ≥ 0, at least two.
    points: Vec<(f64, f64)>,
}

impl History {
    /// The default ramp of a load without a history in a case with histories.
    pub fn ramp() -> History {
        History {
            points: vec![(0.0, 0.0), (1.0, 1.0)],
        }
    }

    /// A history from its table as written in the case (`[[t, v], ...]`):
    /// the reason when it is not one (for the caller to place).
    pub fn new(table: &[Vec<f64>]) -> Result<History, String> {
        if table.len() < 2 {
            return Err(format!(
                "has {} point(s): a history needs at least two [time, value] points",
                table.len()
            ));
        }
        if table.len() > MAX_POINTS {
            return Err(format!(
                "has {} points, more than {MAX_POINTS}",
                table.len()
            ));
        }
        let mut points = Vec::with_capacity(table.len());
        for (i, p) in table.iter().enumerate() {
            let &[t, v] = p.as_slice() else {
                return Err(format!(
                    "point {i} has {} numbers: each point is [time, value]",
                    p.len()
                ));
            };
            if !(t.is_finite() && v.is_finite()) {
                return Err(format!("point {i} [{t}, {v}] is not two finite numbers"));
            }
            if v.abs() > MAX_VALUE {
                return Err(format!(
                    "point {i}: value {v:e} is far outside any engineering use (a factor: at most {MAX_VALUE:e} in magnitude)"
                ));
            }
            if !(0.0..=MAX_TIME).contains(&t) {
                return Err(format!(
                    "point {i}: time {t} must be in [0, {MAX_TIME}] (pseudo-time starts at 0)"
                ));
            }
            if let Some(&(t0, _)) = points.last() {
                if t <= t0 {
                    return Err(format!(
                        "point {i}: time {t} does not increase (the point before is at {t0}); times must be strictly increasing"
                    ));
                }
            }
            points.push((t, v));
        }
        if points.iter().all(|p| p.1 == 0.0) {
            return Err(
                "is zero at every point: whatever it scales never acts; give it non-zero values or remove it".into(),
            );
        }
        Ok(History { points })
    }

    /// The largest magnitude of its values: with linear segments held at
    /// the ends, the largest |value| over all pseudo-time.
    pub fn peak(&self) -> f64 {
        self.points.iter().fold(0.0, |a, p| a.max(p.1.abs()))
    }

    /// The lowest and the highest value: with linear segments held at the
    /// ends, the extremes over all pseudo-time.
    pub fn extremes(&self) -> (f64, f64) {
        self.points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.1), hi.max(p.1))
            })
    }

    /// The factor at pseudo-time t: linear between the points, held outside.
    pub fn value(&self, t: f64) -> f64 {
        let p = &self.points;
        let (first, last) = (p[0], p[p.len() - 1]);
        if t <= first.0 {
            return first.1;
        }
        if t >= last.0 {
            return last.1;
        }
        // the segment [p[k−1], p[k]] holding t (p[k].0 > t ≥ p[k−1].0)
        let k = p.partition_point(|q| q.0 <= t);
        let ((t0, v0), (t1, v1)) = (p[k - 1], p[k]);
        if t == t0 {
            return v0;
        }
        v0 + (v1 - v0) * ((t - t0) / (t1 - t0))
    }

    /// The times of the points, ascending.
    pub fn times(&self) -> impl Iterator<Item = f64> + '_ {
        self.points.iter().map(|p| p.0)
    }

    /// The last point's time: from there on the value is held.
    pub fn end(&self) -> f64 {
        self.points[self.points.len() - 1].0
    }
}

/// Every point's time of these histories, ascending and without repeats,
/// with 0 and 1 (the default ramp's points); empty without histories.
pub fn breakpoints(histories: &[History]) -> Vec<f64> {
    if histories.is_empty() {
        return Vec::new();
    }
    let mut t: Vec<f64> = [0.0, 1.0]
        .into_iter()
        .chain(histories.iter().flat_map(|h| h.times()))
        .collect();
    t.sort_by(f64::total_cmp);
    t.dedup();
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn h(v: &[[f64; 2]]) -> Result<History, String> {
        History::new(&v.iter().map(|p| p.to_vec()).collect::<Vec<_>>())
    }

    #[test]
    fn values_are_linear_between_points_and_held_outside() {
        let s = h(&[[1.0, 0.0], [2.0, 1.0], [3.0, -1.0], [4.0, 0.0]]).unwrap();
        assert_eq!(s.value(0.0), 0.0);
        assert_eq!(s.value(0.5), 0.0);
        assert_eq!(s.value(1.5), 0.5);
        assert_eq!(s.value(2.0), 1.0);
        assert_eq!(s.value(2.25), 0.5);
        assert_eq!(s.value(3.0), -1.0);
        assert_eq!(s.value(3.5), -0.5);
        assert_eq!(s.value(9.0), 0.0);
        assert_eq!(s.end(), 4.0);
        let r = History::ramp();
        assert_eq!(r.value(0.3), 0.3);
        assert_eq!(r.value(7.0), 1.0);
    }

    #[test]
    fn bad_tables_are_refused() {
        assert!(h(&[]).unwrap_err().contains("at least two"));
        assert!(h(&[[0.0, 1.0]]).unwrap_err().contains("at least two"));
        assert!(h(&[[0.0, 0.0], [1.0, 1.0], [1.0, 2.0]])
            .unwrap_err()
            .contains("strictly increasing"));
        assert!(h(&[[-1.0, 0.0], [1.0, 1.0]])
            .unwrap_err()
            .contains("starts at 0"));
        assert!(h(&[[0.0, f64::NAN], [1.0, 1.0]])
            .unwrap_err()
            .contains("finite"));
        assert!(History::new(&[vec![0.0, 0.0], vec![1.0, 1.0, 2.0]])
            .unwrap_err()
            .contains("[time, value]"));
    }
}
