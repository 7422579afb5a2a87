//! Curved bottom and top sides of a generated block (issue 19): an arc, or
//! quarter-circle roundings at the ends.

use serde::{Deserialize, Serialize};

/// The shape of a block's bottom or top side (issue 19: curved contact).
/// The side bulges out of the block's rectangle no further than its straight
/// line: a curved bottom rises from y₀, a curved top falls from y₁, so the
/// block stays inside its rectangle. Interior nodes are placed on the
/// straight line between the (curved) bottom and top point of their column,
/// at the graded height fraction: x(ξ, η) = (1 − η̂) B(ξ) + η̂ T(ξ), the
/// transfinite (Coons) map of a block whose left and right sides are straight.
/// Every node of a curved side, midside nodes included, lies on the curve.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SideShape {
    /// A circular arc of this radius (mm) whose apex is the straight side's
    /// point at x = `center`: a cylinder or a crown,
    /// y = y₀ + R − √(R² − (x − c)²) on a bottom side (mirrored on a top).
    #[serde(default)]
    pub radius: Option<f64>,
    /// x of the arc's apex (mm); default the middle of the block.
    #[serde(default)]
    pub center: Option<f64>,
    /// A quarter-circle rounding of this radius (mm) at the side's left end:
    /// the side is straight up to x₀ + r and turns through 90° to meet the
    /// left side r above (bottom) or below (top) the corner. x₀ + r must be a
    /// breakpoint of `x`; nodes on the rounding are spaced evenly in angle.
    #[serde(default)]
    pub(crate) round_left: Option<f64>,
    /// The same rounding at the side's right end (x₁ − r a breakpoint).
    #[serde(default)]
    pub round_right: Option<f64>,
}

/// The smallest rise of an arc and the smallest rounding, as a fraction of
/// the block's size (the diagonal of its rectangle): the model's geometric
/// tolerance ([`crate::model::consistency`], 1e-9 of its size), below which two
/// points count as one and a side cannot be told from straight. A radius
/// above the bound is a flat side to round-off (R = 1e300 made every
/// coordinate NaN), a rounding below it a sharp corner.
pub(crate) const MIN_RELATIVE_CURVE: f64 = 1e-9;

/// A broken rule of a curved side: the key it concerns (`radius`, `center`,
/// `round_left`, `round_right`) and the reason, without the place.
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeError {
    pub key: &'static str,
    pub message: String,
}

/// v with about 5 significant digits, in plain notation where that is short.
fn short(v: f64) -> String {
    if (1e-3..1e6).contains(&v.abs()) {
        let decimals = (4 - v.abs().log10().floor() as i32).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.4e}")
    }
}

/// The rise of an arc of radius r at the distance d from its apex (|d| < r),
/// r − √(r² − d²), computed without cancellation or overflow.
fn rise(r: f64, d: f64) -> f64 {
    let q = d / r;
    r * q * q / (1.0 + ((1.0 - q) * (1.0 + q)).sqrt())
}

impl SideShape {
    /// Checks the shape against its block: `xs` its x breakpoints (finite,
    /// strictly increasing), `ys` the lower and upper y of its rectangle.
    /// `on_axis` names what the block's left side lies on when that is the
    /// axis of an axisymmetric model or the symmetry plane of a half model
    /// (a rounding there is a cusp). `ShapeError::key` is the offending key.
    pub fn check(&self, xs: &[f64], ys: [f64; 2], on_axis: Option<&str>) -> Result<(), ShapeError> {
        let (x0, x1) = (xs[0], xs[xs.len() - 1]);
        let (width, height) = (x1 - x0, ys[1] - ys[0]);
        let size = width.hypot(height);
        let least = MIN_RELATIVE_CURVE * size;
        let err = |key: &'static str, message: String| Err(ShapeError { key, message });
        let positive = |key: &'static str, v: f64| -> Result<(), ShapeError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                err(key, format!("{v} must be a positive length in mm"))
            }
        };
        let rounded = self.round_left.is_some() || self.round_right.is_some();
        let Some(r) = self.radius else {
            if self.center.is_some() {
                return err(
                    "center",
                    "belongs to radius (an arc); rounded ends take none".into(),
                );
            }
            if !rounded {
                return err(
                    "radius",
                    "missing: give radius (an arc) or round_left / round_right (rounded ends)"
                        .into(),
                );
            }
            return self.check_roundings(xs, height, least, on_axis);
        };
        if rounded {
            let key = if self.round_left.is_some() {
                "round_left"
            } else {
                "round_right"
            };
            return err(
                key,
                "give either radius (an arc) or round_left / round_right (rounded ends), not both"
                    .into(),
            );
        }
        positive("radius", r)?;
        let c = self.center.unwrap_or(0.5 * (x0 + x1));
        if !c.is_finite() {
            return err("center", format!("{c} must be a finite x (mm)"));
        }
        let slack = 1e-9 * width;
        if c < x0 - slack || c > x1 + slack {
            let start = match on_axis {
                Some(on) => format!("{x0} ({on})"),
                None => format!("{x0}"),
            };
            return err(
                "center",
                format!(
                    "x = {c} lies off the side, which runs from x = {start} to {x1}: the arc's apex is the side's point at x = center; put center within the block"
                ),
            );
        }
        let reach = (x0 - c).abs().max((x1 - c).abs());
        // the radii this block admits: the side within 0.9 R of the apex and
        // the rise under half the height (below), a rise of at least
        // `least` (above, about reach²/2·least)
        let r_min = (reach / 0.9).max((reach * reach + 0.25 * height * height) / height);
        let r_max = reach * reach / (2.0 * least);
        let admits = format!(
            "this block (reaching {reach} mm from the apex at x = {c}, {height} mm high) admits {} < radius < about {} mm",
            short(r_min),
            short(r_max)
        );
        if reach >= 0.9 * r {
            return err(
                "radius",
                format!(
                    "{r} mm is too small: the side reaches {reach} mm from the apex, beyond 0.9 R (the arc would turn steeper than 64° from the side); {admits}"
                ),
            );
        }
        let depth = rise(r, reach);
        if depth >= 0.5 * height {
            return err(
                "radius",
                format!(
                    "{r} mm is too small: the arc rises {} mm over the block, at least half its height ({height} mm); {admits}",
                    short(depth)
                ),
            );
        }
        if depth < least {
            return err(
                "radius",
                format!(
                    "{r:e} mm is a flat side to round-off: the arc rises {depth:e} mm over the block, less than {MIN_RELATIVE_CURVE:e} of its size ({size} mm), below which the model cannot tell it from straight; leave radius out for a flat side, or {admits}"
                ),
            );
        }
        Ok(())
    }

    /// The rules of rounded ends (no `radius`).
    fn check_roundings(
        &self,
        xs: &[f64],
        height: f64,
        least: f64,
        on_axis: Option<&str>,
    ) -> Result<(), ShapeError> {
        let (x0, x1) = (xs[0], xs[xs.len() - 1]);
        let err = |key: &'static str, message: String| Err(ShapeError { key, message });
        for (key, v) in [
            ("round_left", self.round_left),
            ("round_right", self.round_right),
        ] {
            let Some(v) = v else { continue };
            if !(v.is_finite() && v > 0.0) {
                return err(key, format!("{v} must be a positive length in mm"));
            }
            if v >= 0.5 * height {
                return err(
                    key,
                    format!("{v} mm must be less than half the block's height ({height} mm)"),
                );
            }
            if v < least {
                return err(
                    key,
                    format!(
                        "{v:e} mm is a sharp corner to round-off: less than {MIN_RELATIVE_CURVE:e} of the block's size, below which the model cannot tell it from a corner; leave it out"
                    ),
                );
            }
        }
        if let (Some(_), Some(on)) = (self.round_left, on_axis) {
            return err(
                "round_left",
                format!(
                    "the block's left side lies on {on}: there is no corner to round, and a rounding meeting it vertically is a cusp of the whole body; leave round_left out (a round end there is an arc: radius with center = {x0})"
                ),
            );
        }
        let l = self.round_left.unwrap_or(0.0);
        let r = self.round_right.unwrap_or(0.0);
        if x0 + l > x1 - r + 1e-12 * (x1 - x0) {
            let key = if self.round_right.is_some() {
                "round_right"
            } else {
                "round_left"
            };
            return err(
                key,
                format!(
                    "the roundings ({l} + {r} mm) are wider than the block ({} mm)",
                    x1 - x0
                ),
            );
        }
        // a breakpoint where the rounding meets the straight part, other
        // than the rounded end itself (a rounding below the tolerance of
        // `near` would otherwise find its own corner)
        let near = |v: f64, skip: usize| {
            xs.iter()
                .enumerate()
                .any(|(i, &b)| i != skip && (b - v).abs() <= 1e-9 * (x1 - x0))
        };
        if self.round_left.is_some() && !near(x0 + l, 0) {
            return err(
                "round_left",
                format!(
                    "x must have a breakpoint where the left rounding ends, x = {}",
                    x0 + l
                ),
            );
        }
        if self.round_right.is_some() && !near(x1 - r, xs.len() - 1) {
            return err(
                "round_right",
                format!(
                    "x must have a breakpoint where the right rounding starts, x = {}",
                    x1 - r
                ),
            );
        }
        Ok(())
    }

    /// The point of the side for the straight side's abscissa x: (x, drop)
    /// becomes (x', depth), where depth ≥ 0 is how far the curve lies inside
    /// the block from the straight side.
    pub(super) fn point(&self, x: f64, x0: f64, x1: f64) -> (f64, f64) {
        if let Some(r) = self.radius {
            let c = self.center.unwrap_or(0.5 * (x0 + x1));
            return (x, rise(r, x - c));
        }
        let quarter = |r: f64, u: f64| {
            // u ∈ [0, 1] along the rounding from its tangent point to the end
            let th = u.clamp(0.0, 1.0) * std::f64::consts::FRAC_PI_2;
            (r * th.sin(), r * (1.0 - th.cos()))
        };
        if let Some(r) = self.round_right {
            if x > x1 - r {
                let (dx, depth) = quarter(r, (x - (x1 - r)) / r);
                return (x1 - r + dx, depth);
            }
        }
        if let Some(r) = self.round_left {
            if x < x0 + r {
                let (dx, depth) = quarter(r, (x0 + r - x) / r);
                return (x0 + r - dx, depth);
            }
        }
        (x, 0.0)
    }
}
