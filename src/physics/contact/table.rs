//! Monotone interpolation of measured tables: the `law = "table"` normal law
//! (approach u_N → pressure p_N) and the tangential `k_table` (pressure p_N →
//! elastic shear stiffness k_T^e).
//!
//! Between the measured points x₁ < … < x_n the curve is a piecewise-cubic
//! Hermite interpolant with the knot derivatives of Fritsch & Butland
//! ("A method for constructing local monotone piecewise cubic interpolants",
//! SIAM J. Sci. Stat. Comput. 5 (1984) 300-304), which lie in the monotonicity
//! region of Fritsch & Carlson ("Monotone piecewise cubic interpolation",
//! SIAM J. Numer. Anal. 17 (1980) 238-246):
//!
//! ```text
//!   δ_k = (y_{k+1} − y_k) / h_k,  h_k = x_{k+1} − x_k
//!   d_k = (w₁ + w₂) / (w₁/δ_{k−1} + w₂/δ_k),  w₁ = 2h_k + h_{k−1}, w₂ = h_k + 2h_{k−1}
//!         (d_k = 0 when δ_{k−1} δ_k = 0)                               interior knots
//!   y(x) = y_k + d_k s + c₂ s² + c₃ s³,  s = x − x_k,
//!   c₂ = (3δ_k − 2d_k − d_{k+1}) / h_k,  c₃ = (d_k + d_{k+1} − 2δ_k) / h_k²
//! ```
//!
//! Below the first point the curve is the power law through the origin and the
//! first point, y = y₁ (x/x₁)^q, with q the local log-log exponent of the first
//! two points, ln(y₂/y₁)/ln(x₂/x₁), clamped to the caller's interval; its slope
//! q y₁/x₁ is the Hermite derivative at x₁ (the stiffness is continuous there).
//! Above the last point the curve continues linearly with the slope d_n at x_n:
//! the one-sided three-point derivative of the last two segments (exact for a
//! quadratic), kept within [½ δ_{n−1}, 2 δ_{n−1}] so the last segment stays
//! monotone; δ_{n−1} itself when there is one segment only.
//!
//! A first segment whose forced derivative q y₁/x₁ leaves the Fritsch-Carlson
//! region (a table that softens by more than about 3× right after its first
//! point) is refused by [`Monotone::new`]: no monotone cubic with a continuous
//! slope joins it.

/// Smallest step between consecutive rows of a column, relative to the
/// larger value: rows closer than this are refused (a column that may stay
/// level, k_T, may also repeat a value exactly). Each value is the decimal
/// of the case file rounded to a double (relative error ε/2, ε = 2.2e-16),
/// so the difference of two values a relative step δ apart is known to
/// about ε/δ, and so is the slope between the rows, the stiffness the solver
/// works with: at δ = 1e-9 to 2.2e-7, six significant digits; one ulp apart
/// it is round-off alone. No measurement resolves 9 significant digits, and
/// 1e-9 is the model's geometric tolerance too.
pub(crate) const MIN_RELATIVE_STEP: f64 = 1e-9;

/// How far beyond its data a table may be evaluated before the run and
/// `asperity check` warn: the law's argument (u_N for `table`, p_N for
/// `k_table`) above this multiple of the last row's, i.e. the linear tail
/// carrying over as far again as the whole measured range.
pub(crate) const EXTRAPOLATION_LIMIT: f64 = 2.0;

/// A monotone (non-decreasing, or strictly increasing) interpolant of
/// measured points with a continuous first derivative.
#[derive(Clone, Debug, PartialEq)]
pub struct Monotone {
    x: Vec<f64>,
    y: Vec<f64>,
    /// Knot derivatives dy/dx.
    d: Vec<f64>,
    /// Exponent q of the power law below the first point.
    q: f64,
    /// ∫₀^{x_k} y dx at each knot.
    area: Vec<f64>,
}

impl Monotone {
    /// Interpolant through `points` (x, y): x > 0 strictly increasing, y > 0
    /// non-decreasing (strictly increasing when `strict`), at least 2 points,
    /// all finite. `q_range` clamps the exponent of the power law below the
    /// first point. Errors name the row (1-based) and the problem; `names` are
    /// the two columns' symbols for the messages.
    pub fn new(
        points: &[(f64, f64)],
        strict: bool,
        q_range: (f64, f64),
        names: (&str, &str),
    ) -> Result<Self, String> {
        Monotone::numbered(points, strict, q_range, names, 1)
    }

    /// [`Monotone::new`] with the rows numbered from `first` in the messages
    /// (2 when the table's written first row, the origin, was dropped).
    pub(crate) fn numbered(
        points: &[(f64, f64)],
        strict: bool,
        q_range: (f64, f64),
        names: (&str, &str),
        first: usize,
    ) -> Result<Self, String> {
        check_rows(points, strict, names, first)?;
        let knots = Knots::new(points, q_range);
        knots.check_monotone(strict, names, first)?;
        let Knots { x, y, h, d, q, .. } = knots;
        let n = x.len();
        let mut area = vec![y[0] * x[0] / (q + 1.0); n];
        for k in 0..n - 1 {
            area[k + 1] = area[k] + segment_area(&y, &d, k, h[k]);
        }
        Ok(Monotone { x, y, d, q, area })
    }

    /// The interpolated (y, dy/dx) at x; (0, 0) at x ≤ 0 unless the law below
    /// the first point is constant (q = 0): then (y₁, 0).
    pub(crate) fn eval(&self, x: f64) -> (f64, f64) {
        let (x1, y1) = (self.x[0], self.y[0]);
        if x <= x1 {
            if x <= 0.0 {
                return (if self.q == 0.0 { y1 } else { 0.0 }, 0.0);
            }
            let y = y1 * (x / x1).powf(self.q);
            return (y, self.q * y / x);
        }
        let n = self.x.len();
        if x >= self.x[n - 1] {
            let s = x - self.x[n - 1];
            return (self.y[n - 1] + self.d[n - 1] * s, self.d[n - 1]);
        }
        let k = self.segment(&self.x, x);
        let (c2, c3) = self.coefficients(k);
        let s = x - self.x[k];
        (
            self.y[k] + s * (self.d[k] + s * (c2 + s * c3)),
            self.d[k] + s * (2.0 * c2 + 3.0 * s * c3),
        )
    }

    /// ∫₀ˣ y dx (0 for x ≤ 0).
    pub fn integral(&self, x: f64) -> f64 {
        let (x1, y1) = (self.x[0], self.y[0]);
        if x <= 0.0 {
            return 0.0;
        }
        if x <= x1 {
            return y1 * x1 / (self.q + 1.0) * (x / x1).powf(self.q + 1.0);
        }
        let n = self.x.len();
        if x >= self.x[n - 1] {
            let s = x - self.x[n - 1];
            return self.area[n - 1] + self.y[n - 1] * s + 0.5 * self.d[n - 1] * s * s;
        }
        let k = self.segment(&self.x, x);
        let (c2, c3) = self.coefficients(k);
        let s = x - self.x[k];
        self.area[k] + s * (self.y[k] + s * (self.d[k] / 2.0 + s * (c2 / 3.0 + s * c3 / 4.0)))
    }

    /// The x with y(x) = v (strictly increasing curves; v > 0): the power law
    /// inverted below the first point, the tail inverted above the last,
    /// safeguarded Newton on a cubic segment between.
    pub fn inverse(&self, v: f64) -> f64 {
        if v <= 0.0 {
            return 0.0;
        }
        let n = self.x.len();
        if v <= self.y[0] {
            return self.x[0] * (v / self.y[0]).powf(1.0 / self.q);
        }
        if v >= self.y[n - 1] {
            return self.x[n - 1] + (v - self.y[n - 1]) / self.d[n - 1];
        }
        let k = self.segment(&self.y, v);
        let (mut lo, mut hi) = (self.x[k], self.x[k + 1]);
        let mut x = lo + (v - self.y[k]) / (self.y[k + 1] - self.y[k]) * (hi - lo);
        for _ in 0..200 {
            let (y, dy) = self.eval(x);
            let r = y - v;
            if r == 0.0 {
                break;
            }
            if r < 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            let next = x - r / dy;
            x = if dy > 0.0 && next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
            if hi - lo <= 4.0 * f64::EPSILON * hi || (r.abs() <= 1e-15 * v) {
                break;
            }
        }
        x
    }

    /// The measured points (without the origin).
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.x.iter().copied().zip(self.y.iter().copied())
    }

    /// The last measured point (x_n, y_n): beyond it the curve is extrapolated.
    pub fn last(&self) -> (f64, f64) {
        let n = self.x.len();
        (self.x[n - 1], self.y[n - 1])
    }

    /// Exponent q of the power law below the first point.
    #[cfg(test)]
    pub(crate) fn exponent_below(&self) -> f64 {
        self.q
    }

    /// The segment k with xs[k] ≤ v < xs[k+1] (xs[0] < v < xs[n−1]).
    fn segment(&self, xs: &[f64], v: f64) -> usize {
        let k = xs.partition_point(|&a| a <= v);
        k.saturating_sub(1).min(xs.len() - 2)
    }

    fn coefficients(&self, k: usize) -> (f64, f64) {
        let h = self.x[k + 1] - self.x[k];
        let delta = (self.y[k + 1] - self.y[k]) / h;
        coefficients(self.d[k], self.d[k + 1], delta, h)
    }
}

/// Checks the rows of a table (numbered from `first` in the messages):
/// finite, positive, increasing (`strict`: both columns) and rows not closer
/// than [`MIN_RELATIVE_STEP`].
fn check_rows(
    points: &[(f64, f64)],
    strict: bool,
    names: (&str, &str),
    first: usize,
) -> Result<(), String> {
    let (xn, yn) = names;
    if points.len() < 2 {
        return Err(format!(
            "has {} point{} besides the origin; a table needs at least 2",
            points.len(),
            if points.len() == 1 { "" } else { "s" }
        ));
    }
    for (i, &(x, y)) in points.iter().enumerate() {
        let row = i + first;
        if !x.is_finite() || !y.is_finite() {
            return Err(format!(
                "row {row}: [{x}, {y}] is not a pair of finite numbers"
            ));
        }
        if x <= 0.0 {
            return Err(format!(
                "row {row}: {xn} = {x} must be positive (only a first row [0, 0] may stand for the origin)"
            ));
        }
        if y <= 0.0 {
            return Err(format!(
                "row {row}: {yn} = {y} must be positive (negative or zero)"
            ));
        }
        if i > 0 {
            let (x0, y0) = points[i - 1];
            if x <= x0 {
                return Err(format!(
                    "row {row}: {xn} = {x} does not increase on row {} ({xn} = {x0}); the table is not monotone",
                    row - 1
                ));
            }
            if strict && y <= y0 {
                return Err(format!(
                    "row {row}: {yn} = {y} does not increase on row {} ({yn} = {y0}); the table is not monotone",
                    row - 1
                ));
            }
            if y < y0 {
                return Err(format!(
                    "row {row}: {yn} = {y} falls below row {}'s {yn} = {y0}; the table is not monotone",
                    row - 1
                ));
            }
            for (name, a, b) in [(xn, x0, x), (yn, y0, y)] {
                if b != a && b - a < MIN_RELATIVE_STEP * b {
                    return Err(format!(
                        "row {row}: {name} = {b} is within {:.1e} (relative) of row {}'s {name} = {a}: the slope between the rows would be round-off, not a measurement (rows must differ by at least {MIN_RELATIVE_STEP:e} of their value{}); drop one of them",
                        (b - a) / b,
                        row - 1,
                        if name == yn && !strict { ", or repeat it exactly for a level stretch" } else { "" }
                    ));
                }
            }
        }
    }
    Ok(())
}

/// The knots of the interpolant: the points, the segments' widths h_k and
/// slopes δ_k, the knot derivatives d_k (Fritsch & Butland inside, the
/// power law's slope at the first, the clamped three-point one at the last)
/// and the exponent q below the first point.
struct Knots {
    x: Vec<f64>,
    y: Vec<f64>,
    h: Vec<f64>,
    delta: Vec<f64>,
    d: Vec<f64>,
    q: f64,
}

impl Knots {
    /// The knots of checked rows ([`check_rows`]); `q_range` clamps q.
    fn new(points: &[(f64, f64)], q_range: (f64, f64)) -> Knots {
        let n = points.len();
        let x: Vec<f64> = points.iter().map(|p| p.0).collect();
        let y: Vec<f64> = points.iter().map(|p| p.1).collect();
        let h: Vec<f64> = (0..n - 1).map(|k| x[k + 1] - x[k]).collect();
        let delta: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
        let q = ((y[1] / y[0]).ln() / (x[1] / x[0]).ln()).clamp(q_range.0, q_range.1);
        let mut d = vec![0.0; n];
        d[0] = q * y[0] / x[0];
        for k in 1..n - 1 {
            let (a, b) = (delta[k - 1], delta[k]);
            if a > 0.0 && b > 0.0 {
                let w1 = 2.0 * h[k] + h[k - 1];
                let w2 = h[k] + 2.0 * h[k - 1];
                d[k] = (w1 + w2) / (w1 / a + w2 / b);
            }
        }
        let last = delta[n - 2];
        d[n - 1] = if n == 2 {
            last
        } else {
            let (h1, h0) = (h[n - 2], h[n - 3]);
            let three = ((2.0 * h1 + h0) * last - h1 * delta[n - 3]) / (h1 + h0);
            three.clamp(0.5 * last, 2.0 * last)
        };
        Knots {
            x,
            y,
            h,
            delta,
            d,
            q,
        }
    }

    /// Checks that each segment's slope stays ≥ 0 (> 0 when `strict`)
    /// between its knots; the rows are numbered from `first`.
    fn check_monotone(
        &self,
        strict: bool,
        names: (&str, &str),
        first: usize,
    ) -> Result<(), String> {
        let (xn, yn) = names;
        let (h, delta, d, q) = (&self.h, &self.delta, &self.d, self.q);
        let n = self.x.len();
        // each segment's slope stays ≥ 0 (> 0 when strict) between its knots
        for k in 0..n - 1 {
            let (c2, c3) = coefficients(d[k], d[k + 1], delta[k], h[k]);
            // slope d_k + 2c₂ s + 3c₃ s² on [0, h]: its minimum
            let mut lo = d[k].min(d[k + 1]);
            if c3 != 0.0 {
                let s = -c2 / (3.0 * c3);
                if s > 0.0 && s < h[k] {
                    lo = lo.min(d[k] + 2.0 * c2 * s + 3.0 * c3 * s * s);
                }
            }
            let bad = if strict {
                lo.is_nan() || lo <= 0.0
            } else {
                lo < -1e-12 * delta[k].max(d[k]).max(d[k + 1])
            };
            if bad {
                return Err(if k == 0 {
                    format!(
                        "rows {first}-{}: the table softens too fast after row {first} for a monotone interpolation with a continuous slope (the power law below row {first}, exponent {q:.3}, reaches row {first} with d{yn}/d{xn} = {:.4e}, more than 3 times the slope {:.4e} to row {}); add points or check the units",
                        first + 1, d[0], delta[0], first + 1
                    )
                } else {
                    format!(
                        "rows {}-{}: no monotone interpolation with a continuous slope; add points or check the units",
                        k + first,
                        k + first + 1
                    )
                });
            }
        }
        Ok(())
    }
}

/// c₂, c₃ of the Hermite cubic y_k + d_k s + c₂ s² + c₃ s³ on a segment of length h.
fn coefficients(d0: f64, d1: f64, delta: f64, h: f64) -> (f64, f64) {
    (
        (3.0 * delta - 2.0 * d0 - d1) / h,
        (d0 + d1 - 2.0 * delta) / (h * h),
    )
}

/// ∫ of the cubic over a whole segment: h (y_k + y_{k+1})/2 + h² (d_k − d_{k+1})/12.
fn segment_area(y: &[f64], d: &[f64], k: usize, h: f64) -> f64 {
    h * 0.5 * (y[k] + y[k + 1]) + h * h * (d[k] - d[k + 1]) / 12.0
}

/// Most rows of a `table` or `k_table` (a bound on what a case file can make the model hold).
pub(crate) const MAX_TABLE_ROWS: usize = 10_000;

/// The rows of a two-column table as pairs; the message names the row (1-based).
pub(crate) fn rows_of_two(rows: &[Vec<f64>], a: &str, b: &str) -> Result<Vec<(f64, f64)>, String> {
    if rows.len() > MAX_TABLE_ROWS {
        return Err(format!(
            "{} rows, more than {MAX_TABLE_ROWS} (the limit)",
            rows.len()
        ));
    }
    rows.iter()
        .enumerate()
        .map(|(i, r)| match r.as_slice() {
            &[x, y] => Ok((x, y)),
            _ => Err(format!(
                "row {}: {} numbers, expected 2 ([{a}, {b}])",
                i + 1,
                r.len()
            )),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numbers::fd;

    fn sample(f: impl Fn(f64) -> f64, xs: &[f64]) -> Vec<(f64, f64)> {
        xs.iter().map(|&x| (x, f(x))).collect()
    }

    #[test]
    fn passes_through_its_points_with_a_continuous_positive_slope() {
        let pts = sample(
            |x| (x / 0.001).powi(2) + 3.0 * x,
            &[1e-3, 2e-3, 4e-3, 5e-3, 9e-3],
        );
        let t = Monotone::new(&pts, true, (1.0, f64::INFINITY), ("u", "p")).unwrap();
        for &(x, y) in &pts {
            assert!((t.eval(x).0 - y).abs() <= 1e-12 * y, "{x}");
            // slope continuous across the knot (and the first point's power law, the tail)
            let e = 1e-9 * x;
            let (l, r) = (t.eval(x - e).1, t.eval(x + e).1);
            assert!((l - r).abs() <= 1e-5 * l, "slope jump at {x}: {l} vs {r}");
        }
        let mut prev = 0.0;
        for i in 1..2000 {
            let x = 1.2e-2 * i as f64 / 2000.0;
            let (y, dy) = t.eval(x);
            assert!(y > prev && dy > 0.0, "x = {x}: y {y} dy {dy}");
            prev = y;
        }
    }

    #[test]
    fn integral_and_inverse_agree_with_eval() {
        let pts = sample(|x| x.powf(1.7), &[0.5, 1.0, 1.5, 3.0, 3.2, 6.0]);
        let t = Monotone::new(&pts, true, (1.0, f64::INFINITY), ("u", "p")).unwrap();
        for &x in &[0.1, 0.5, 0.7, 1.2, 3.1, 4.0, 6.0, 9.0] {
            let h = 1e-6 * x;
            let fd = fd::central_derivative(|x| t.integral(x), x, h);
            assert!((fd - t.eval(x).0).abs() <= 1e-7 * fd, "x = {x}");
            let y = t.eval(x).0;
            assert!((t.inverse(y) - x).abs() <= 1e-12 * x, "x = {x}");
        }
        // the integral over the first piece is the power law's
        let q = t.exponent_below();
        assert!((t.integral(0.5) - 0.5 * 0.5f64.powf(1.7) / (q + 1.0)).abs() < 1e-15);
    }

    #[test]
    fn bad_tables_name_the_row() {
        let r =
            |pts: &[(f64, f64)]| Monotone::new(pts, true, (1.0, 1e9), ("u_N", "p")).unwrap_err();
        assert!(r(&[(1.0, 2.0)]).contains("at least 2"));
        assert!(r(&[(1.0, 2.0), (0.5, 3.0)]).contains("row 2: u_N = 0.5 does not increase"));
        assert!(r(&[(1.0, 2.0), (2.0, 1.5)]).contains("row 2: p = 1.5 does not increase"));
        assert!(r(&[(1.0, 2.0), (2.0, 2.0)]).contains("not monotone"));
        assert!(r(&[(1.0, -2.0), (2.0, 3.0)]).contains("row 1: p = -2 must be positive"));
        assert!(r(&[(1.0, 2.0), (f64::NAN, 3.0)]).contains("row 2"));
        // softening by far more than 3× after the first point
        assert!(r(&[(1.0, 10.0), (2.0, 10.5), (3.0, 11.0)]).contains("softens too fast"));
        // rows closer than 1e-9 (relative) in either column: round-off slopes
        let ulp = 0.005f64.next_up();
        let e = r(&[(0.002, 4.0), (0.005, 25.0), (ulp, 30.0)]);
        assert!(
            e.contains("row 3: u_N = ") && e.contains("round-off"),
            "{e}"
        );
        let e = r(&[(1.0, 2.0), (2.0, 3.0), (3.0, 3.0 * (1.0 + 5e-10))]);
        assert!(e.contains("row 3: p = ") && e.contains("round-off"), "{e}");
        assert!(Monotone::new(
            &[(1.0, 2.0), (2.0, 3.0), (2.0 + 4e-9, 3.0 * (1.0 + 2e-9))],
            true,
            (1.0, 1e9),
            ("u_N", "p")
        )
        .is_ok());
        let level = |k3: f64| {
            Monotone::new(
                &[(1.0, 2.0), (2.0, 3.0), (3.0, k3)],
                false,
                (0.0, 1.0),
                ("p", "k"),
            )
        };
        assert!(level(3.0).is_ok());
        assert!(level(3.0f64.next_up())
            .unwrap_err()
            .contains("repeat it exactly"));
        // non-strict: a flat stretch is allowed
        let t = Monotone::new(
            &[(1.0, 2.0), (2.0, 2.0), (3.0, 4.0)],
            false,
            (0.0, 1.0),
            ("p", "k"),
        )
        .unwrap();
        assert_eq!(t.eval(1.5), (2.0, 0.0));
    }
}
