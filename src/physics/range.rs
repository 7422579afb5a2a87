//! The engineering range of a quantity: the magnitudes a case may give it
//! (mm, N, MPa). The ranges of the quantities the contact laws take are
//! declared here and beside each law's parameters
//! ([`crate::physics::contact::normal::Kind`]); the case's other quantities,
//! and the table of them all, are in `input::case::ranges`.
//!
//! Each range is generous: several orders of magnitude beyond any engineering
//! use on either side. A value outside it is not a model anyone means (a
//! thickness of 1e-310 mm, a modulus of 1e300 MPa) and would either make every
//! result zero (denormal numbers: every increment "converges" in 0 iterations)
//! or overflow later; it is refused up front with the key's name.

use crate::error::{Error, Result};

/// The accepted magnitudes of one quantity: `lo ≤ |v| ≤ hi` (zero and the sign
/// are the caller's business: the existing per-key checks say which sign a key
/// takes and whether 0 is allowed).
#[derive(Clone, Copy, Debug)]
pub struct Range {
    pub quantity: &'static str,
    pub unit: &'static str,
    pub lo: f64,
    pub hi: f64,
}

/// Applied pressures, start pressures, critical pressures, exponential `a`.
pub(crate) const PRESSURE: Range = Range {
    quantity: "a pressure",
    unit: "MPa",
    lo: 1e-6,
    hi: 1e6,
};
/// Non-zero prescribed displacements and gaps.
pub(crate) const DISPLACEMENT: Range = Range {
    quantity: "a displacement or gap",
    unit: "mm",
    lo: 1e-9,
    hi: 1e4,
};

impl Range {
    /// Is `v` (finite) within the range? Zero passes: the per-key checks decide
    /// whether a key may be 0.
    pub(crate) fn admits(&self, v: f64) -> bool {
        v == 0.0 || (v.abs() >= self.lo && v.abs() <= self.hi)
    }

    /// `Ok` when `v` is zero, not finite (left to the per-key checks) or in the
    /// range; otherwise an input error at `place` naming the range.
    pub fn check(&self, place: impl Into<String>, v: f64) -> Result<()> {
        if !v.is_finite() || self.admits(v) {
            return Ok(());
        }
        Err(Error::input(place, self.refusal(v)))
    }

    /// "1e-310 is far outside any engineering use (the thickness: 1e-6 … 1e6 mm in magnitude)".
    pub fn refusal(&self, v: f64) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        let within = if self.lo == 0.0 {
            format!("at most {:e}{unit}", self.hi)
        } else {
            format!("{:e} … {:e}{unit}", self.lo, self.hi)
        };
        format!(
            "{v:e} is far outside any engineering use ({}: {within} in magnitude)",
            self.quantity
        )
    }
}
