//! Curved bottom and top sides of a generated block (issue 19): an arc, or
//! quarter-circle roundings at the ends.

use super::MeshError;
use serde::Deserialize;

/// The shape of a block's bottom or top side (issue 19: curved contact).
/// The side bulges out of the block's rectangle no further than its straight
/// line: a curved bottom rises from y₀, a curved top falls from y₁, so the
/// block stays inside its rectangle. Interior nodes are placed on the
/// straight line between the (curved) bottom and top point of their column,
/// at the graded height fraction: x(ξ, η) = (1 − η̂) B(ξ) + η̂ T(ξ), the
/// transfinite (Coons) map of a block whose left and right sides are straight.
/// Every node of a curved side, midside nodes included, lies on the curve.
#[derive(Clone, Debug, Deserialize, PartialEq)]
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
    pub round_left: Option<f64>,
    /// The same rounding at the side's right end (x₁ − r a breakpoint).
    #[serde(default)]
    pub round_right: Option<f64>,
}

impl SideShape {
    /// Checks the shape against its block; `side` is "bottom" or "top".
    pub(super) fn check(
        &self,
        body: &str,
        side: &str,
        xs: &[f64],
        height: f64,
    ) -> Result<(), MeshError> {
        let err = |m: String| Err(MeshError(format!("block \"{body}\" {side}: {m}")));
        let (x0, x1) = (xs[0], xs[xs.len() - 1]);
        let positive = |name: &str, v: f64| -> Result<(), MeshError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                err(format!("{name} = {v} must be a positive length in mm"))
            }
        };
        let rounded = self.round_left.is_some() || self.round_right.is_some();
        match self.radius {
            Some(r) => {
                if rounded {
                    return err("give either radius (an arc) or round_left / round_right (rounded ends), not both".into());
                }
                positive("radius", r)?;
                let c = self.center.unwrap_or(0.5 * (x0 + x1));
                if !c.is_finite() {
                    return err(format!("center = {c} must be finite"));
                }
                let reach = (x0 - c).abs().max((x1 - c).abs());
                if reach >= 0.9 * r {
                    return err(format!(
                        "the block reaches {reach} mm from the arc's apex at x = {c}; with radius = {r} it must stay within 0.9 R (the arc would turn steeper than 64° from the side)"
                    ));
                }
                let rise = r - (r * r - reach * reach).sqrt();
                if rise >= 0.5 * height {
                    return err(format!(
                        "the arc rises {rise} mm over the block, which is {height} mm high: make the block at least twice as high as the rise"
                    ));
                }
            }
            None => {
                if self.center.is_some() {
                    return err("center belongs to radius (an arc)".into());
                }
                if !rounded {
                    return err(
                        "give radius (an arc) or round_left / round_right (rounded ends)".into(),
                    );
                }
                let l = self.round_left.unwrap_or(0.0);
                let r = self.round_right.unwrap_or(0.0);
                for (name, v) in [
                    ("round_left", self.round_left),
                    ("round_right", self.round_right),
                ] {
                    if let Some(v) = v {
                        positive(name, v)?;
                        if v >= 0.5 * height {
                            return err(format!(
                                "{name} = {v} mm must be less than half the block's height ({height} mm)"
                            ));
                        }
                    }
                }
                if x0 + l > x1 - r + 1e-12 * (x1 - x0) {
                    return err(format!(
                        "the roundings ({l} + {r} mm) are wider than the block ({} mm)",
                        x1 - x0
                    ));
                }
                let near = |v: f64| xs.iter().any(|&b| (b - v).abs() <= 1e-9 * (x1 - x0));
                if self.round_left.is_some() && !near(x0 + l) {
                    return err(format!(
                        "x must have a breakpoint where the left rounding ends, x = {}",
                        x0 + l
                    ));
                }
                if self.round_right.is_some() && !near(x1 - r) {
                    return err(format!(
                        "x must have a breakpoint where the right rounding starts, x = {}",
                        x1 - r
                    ));
                }
            }
        }
        Ok(())
    }

    /// The point of the side for the straight side's abscissa x: (x, drop)
    /// becomes (x', depth), where depth ≥ 0 is how far the curve lies inside
    /// the block from the straight side.
    pub(super) fn point(&self, x: f64, x0: f64, x1: f64) -> (f64, f64) {
        if let Some(r) = self.radius {
            let c = self.center.unwrap_or(0.5 * (x0 + x1));
            let d = x - c;
            return (x, r - (r * r - d * d).sqrt());
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
