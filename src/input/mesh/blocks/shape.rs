//! Curved bottom and top sides of a generated block (issue 19): an arc, or
//! quarter-circle roundings and straight chamfers at the ends (convex: the
//! block's own corner cut away). The concave fillets a bottom or top may
//! also name (`fillet_left`, `fillet_right`) are made in [`super::fillet`].

use serde::{Deserialize, Deserializer, Serialize};

/// The shape of a block's bottom or top side (issue 19: curved contact).
/// The side bulges out of the block's rectangle no further than its straight
/// line: a curved bottom rises from y₀, a curved top falls from y₁, so the
/// block stays inside its rectangle. Interior nodes are placed on the
/// straight line between the (curved) bottom and top point of their column,
/// at the graded height fraction: x(ξ, η) = (1 − η̂) B(ξ) + η̂ T(ξ), the
/// transfinite (Coons) map of a block whose left and right sides are straight.
/// Every node of a curved side, midside nodes included, lies on the curve.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
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
    /// A straight cut of the side's left corner (a convex chamfer): the side
    /// is straight up to x₀ + a and then runs straight to the left side,
    /// which it meets b above (bottom) or below (top) the corner. x₀ + a
    /// must be a breakpoint of `x`; the nodes on the cut are evenly spaced
    /// along it when its x segment is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chamfer_left: Option<Chamfer>,
    /// The same cut at the side's right end (x₁ − a a breakpoint).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chamfer_right: Option<Chamfer>,
    /// A concave fillet of this radius (mm) at the side's left end, between
    /// this side and the block's left side produced beyond the corner (the
    /// side of the block that continues there): [`super::fillet`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fillet_left: Option<f64>,
    /// The same concave fillet at the side's right end.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fillet_right: Option<f64>,
}

/// The two legs of a chamfer (mm): `along` the side it cuts (x) and
/// `across` it (y, along the block's left or right side). A case gives one
/// length (a 45° chamfer, both legs equal) or two, `[along, across]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chamfer {
    pub along: f64,
    pub across: f64,
}

/// As `[along, across]`, which reads back as the same chamfer (the case's
/// key, [`crate::input::case::Case::key`], is read back in tests).
impl Serialize for Chamfer {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        [self.along, self.across].serialize(s)
    }
}

impl<'de> Deserialize<'de> for Chamfer {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Chamfer, D::Error> {
        struct Legs;
        const WANT: &str = "a leg length in mm (a 45° chamfer) or two, [along the side, across it]";
        impl<'de> serde::de::Visitor<'de> for Legs {
            type Value = Chamfer;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(WANT)
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Chamfer, E> {
                Ok(Chamfer {
                    along: v,
                    across: v,
                })
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Chamfer, E> {
                self.visit_f64(v as f64)
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Chamfer, E> {
                self.visit_f64(v as f64)
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Chamfer, A::Error> {
                use serde::de::Error;
                let along: f64 = seq.next_element()?.ok_or_else(|| A::Error::custom(WANT))?;
                let across: f64 = seq.next_element()?.ok_or_else(|| A::Error::custom(WANT))?;
                if seq.next_element::<f64>()?.is_some() {
                    return Err(A::Error::custom(format!("{WANT}, not three")));
                }
                Ok(Chamfer { along, across })
            }
        }
        d.deserialize_any(Legs)
    }
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

/// A rounding's radius or a chamfer's leg (`what` says which leg): a
/// positive finite length of at least `least` (below it a sharp corner).
fn check_leg(key: &'static str, what: &str, v: f64, least: f64) -> Result<(), ShapeError> {
    if !(v.is_finite() && v > 0.0) {
        return Err(ShapeError {
            key,
            message: format!("{v}{what} must be a positive length in mm"),
        });
    }
    if v < least {
        return Err(ShapeError {
            key,
            message: format!(
                "{v:e} mm{what} is a sharp corner to round-off: less than {MIN_RELATIVE_CURVE:e} of the block's size, below which the model cannot tell it from a corner; leave it out"
            ),
        });
    }
    Ok(())
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
        let Some(r) = self.radius else {
            if self.center.is_some() {
                return err(
                    "center",
                    "belongs to radius (an arc); shaped ends take none".into(),
                );
            }
            if self.end_keys().next().is_none() {
                return err(
                    "radius",
                    "missing: give radius (an arc), or shape an end: round_left / round_right (rounded), chamfer_left / chamfer_right (cut), fillet_left / fillet_right (a concave fillet)"
                        .into(),
                );
            }
            return self.check_ends(xs, height, least, on_axis);
        };
        if let Some(key) = self.end_keys().next() {
            return err(
                key,
                "give either radius (an arc) or shaped ends (round_*, chamfer_*, fillet_*), not both"
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

    /// The end keys given, in the order of the docs.
    fn end_keys(&self) -> impl Iterator<Item = &'static str> + '_ {
        [
            ("round_left", self.round_left.is_some()),
            ("round_right", self.round_right.is_some()),
            ("chamfer_left", self.chamfer_left.is_some()),
            ("chamfer_right", self.chamfer_right.is_some()),
            ("fillet_left", self.fillet_left.is_some()),
            ("fillet_right", self.fillet_right.is_some()),
        ]
        .into_iter()
        .filter(|k| k.1)
        .map(|k| k.0)
    }

    /// Whether the side leaves its straight line: an arc, a rounding or a
    /// chamfer (a fillet alone leaves the block's own nodes where they are
    /// and is made on the body, [`super::fillet`]).
    pub fn cuts(&self) -> bool {
        self.radius.is_some()
            || self.round_left.is_some()
            || self.round_right.is_some()
            || self.chamfer_left.is_some()
            || self.chamfer_right.is_some()
    }

    /// The rules of shaped ends (no `radius`): one shape per end, each
    /// rounding or chamfer fitting the block and starting at a breakpoint.
    /// The fillets' own rules need the other blocks ([`super::fillet`]).
    fn check_ends(
        &self,
        xs: &[f64],
        height: f64,
        least: f64,
        on_axis: Option<&str>,
    ) -> Result<(), ShapeError> {
        self.one_shape_per_end()?;
        self.check_legs(height, least)?;
        let err = |key: &'static str, message: String| Err(ShapeError { key, message });
        let (x0, x1) = (xs[0], xs[xs.len() - 1]);
        if let (Some(on), Some(key)) = (on_axis, self.left_cut_key()) {
            return err(
                key,
                format!(
                    "the block's left side lies on {on}: there is no corner to round or cut, and a rounding or chamfer meeting it is a cusp or a cone's tip of the whole body; leave {key} out (a round end there is an arc: radius with center = {x0})"
                ),
            );
        }
        let l = self.cut(true);
        let r = self.cut(false);
        if x0 + l > x1 - r + 1e-12 * (x1 - x0) {
            let key = self
                .right_cut_key()
                .or(self.left_cut_key())
                .unwrap_or("round_left");
            return err(
                key,
                format!(
                    "the shaped ends ({l} + {r} mm) are wider than the block ({} mm)",
                    x1 - x0
                ),
            );
        }
        self.check_breakpoints(xs)
    }

    /// At most one of `round_*`, `chamfer_*` and `fillet_*` at each end.
    fn one_shape_per_end(&self) -> Result<(), ShapeError> {
        let ends = [
            (
                "left",
                [
                    ("round_left", self.round_left.is_some()),
                    ("chamfer_left", self.chamfer_left.is_some()),
                    ("fillet_left", self.fillet_left.is_some()),
                ],
            ),
            (
                "right",
                [
                    ("round_right", self.round_right.is_some()),
                    ("chamfer_right", self.chamfer_right.is_some()),
                    ("fillet_right", self.fillet_right.is_some()),
                ],
            ),
        ];
        for (end, keys) in ends {
            let given: Vec<&'static str> = keys.iter().filter(|k| k.1).map(|k| k.0).collect();
            if let [first, second, ..] = given[..] {
                return Err(ShapeError {
                    key: second,
                    message: format!(
                        "{first} and {second} both shape the {end} end of the side; give one"
                    ),
                });
            }
        }
        Ok(())
    }

    /// Each rounding's radius and chamfer's legs: positive lengths, not a
    /// sharp corner to round-off, and across the side less than half the
    /// block's height (a bottom's and a top's shapes of one end keep apart).
    fn check_legs(&self, height: f64, least: f64) -> Result<(), ShapeError> {
        let half = |key: &'static str, what: &str, v: f64| {
            if v >= 0.5 * height {
                let v = if what.is_empty() {
                    format!("{v} mm")
                } else {
                    format!("{what}, {v} mm,")
                };
                return Err(ShapeError {
                    key,
                    message: format!("{v} must be less than half the block's height ({height} mm)"),
                });
            }
            Ok(())
        };
        for (key, v) in [
            ("round_left", self.round_left),
            ("round_right", self.round_right),
        ] {
            let Some(v) = v else { continue };
            check_leg(key, "", v, least)?;
            half(key, "", v)?;
        }
        for (key, c) in [
            ("chamfer_left", self.chamfer_left),
            ("chamfer_right", self.chamfer_right),
        ] {
            let Some(c) = c else { continue };
            check_leg(key, " (along the side)", c.along, least)?;
            check_leg(key, " (across the side)", c.across, least)?;
            half(key, "the leg across the side", c.across)?;
        }
        Ok(())
    }

    /// A breakpoint of `x` where each rounding or chamfer meets the
    /// straight part, other than the shaped end itself (a length below the
    /// tolerance of `near` would otherwise find its own corner).
    fn check_breakpoints(&self, xs: &[f64]) -> Result<(), ShapeError> {
        let (x0, x1) = (xs[0], xs[xs.len() - 1]);
        let near = |v: f64, skip: usize| {
            xs.iter()
                .enumerate()
                .any(|(i, &b)| i != skip && (b - v).abs() <= 1e-9 * (x1 - x0))
        };
        for (left, key, at, skip) in [
            (true, self.left_cut_key(), x0 + self.cut(true), 0),
            (
                false,
                self.right_cut_key(),
                x1 - self.cut(false),
                xs.len() - 1,
            ),
        ] {
            let Some(key) = key else { continue };
            if !near(at, skip) {
                let what = if key.starts_with("round") {
                    "rounding"
                } else {
                    "chamfer"
                };
                let (end, how) = if left {
                    ("left", "ends")
                } else {
                    ("right", "starts")
                };
                return Err(ShapeError {
                    key,
                    message: format!(
                        "x must have a breakpoint where the {end} {what} {how}, x = {at}"
                    ),
                });
            }
        }
        Ok(())
    }

    /// How far along the side its left (or right) end is cut: a rounding's
    /// radius or a chamfer's leg along the side, 0 for a sharp or filleted
    /// end.
    fn cut(&self, left: bool) -> f64 {
        let (round, chamfer) = if left {
            (self.round_left, self.chamfer_left)
        } else {
            (self.round_right, self.chamfer_right)
        };
        round.or(chamfer.map(|c| c.along)).unwrap_or(0.0)
    }

    fn left_cut_key(&self) -> Option<&'static str> {
        match (self.round_left, self.chamfer_left) {
            (Some(_), _) => Some("round_left"),
            (None, Some(_)) => Some("chamfer_left"),
            _ => None,
        }
    }

    fn right_cut_key(&self) -> Option<&'static str> {
        match (self.round_right, self.chamfer_right) {
            (Some(_), _) => Some("round_right"),
            (None, Some(_)) => Some("chamfer_right"),
            _ => None,
        }
    }

    /// The part of the block's rectangle a shaped side changes, [x₀, x₁, y₀,
    /// y₁] (`ys` the rectangle's y range, `bottom` which side this is): the
    /// arc's whole side up to its rise, or the corner box of each rounding
    /// or chamfer. A fillet must keep off them ([`super::fillet`]).
    pub(crate) fn cut_boxes(&self, xs: &[f64], ys: [f64; 2], bottom: bool) -> Vec<[f64; 4]> {
        let (x0, x1) = (xs[0], xs[xs.len() - 1]);
        let band = |depth: f64| {
            if bottom {
                [ys[0], ys[0] + depth]
            } else {
                [ys[1] - depth, ys[1]]
            }
        };
        if let Some(r) = self.radius {
            let c = self.center.unwrap_or(0.5 * (x0 + x1));
            let reach = (x0 - c).abs().max((x1 - c).abs()).min(r);
            let [lo, hi] = band(rise(r, reach));
            return vec![[x0, x1, lo, hi]];
        }
        let mut out = Vec::new();
        let depth = |round: Option<f64>, chamfer: Option<Chamfer>| {
            round.or(chamfer.map(|c| c.across)).unwrap_or(0.0)
        };
        let l = self.cut(true);
        if l > 0.0 {
            let [lo, hi] = band(depth(self.round_left, self.chamfer_left));
            out.push([x0, x0 + l, lo, hi]);
        }
        let r = self.cut(false);
        if r > 0.0 {
            let [lo, hi] = band(depth(self.round_right, self.chamfer_right));
            out.push([x1 - r, x1, lo, hi]);
        }
        out
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
        if let Some(c) = self.chamfer_right {
            if x > x1 - c.along {
                return (x, c.across * (x - (x1 - c.along)) / c.along);
            }
        }
        if let Some(c) = self.chamfer_left {
            if x < x0 + c.along {
                return (x, c.across * (x0 + c.along - x) / c.along);
            }
        }
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
