//! Sane magnitudes per physical quantity (mm, N, MPa).
//!
//! Each range is generous: several orders of magnitude beyond any engineering
//! use on either side. A value outside it is not a model anyone means (a
//! thickness of 1e-310 mm, a modulus of 1e300 MPa) and would either make every
//! result zero (denormal numbers: every increment "converges" in 0 iterations)
//! or overflow later; it is refused up front with the key's name. The table is
//! repeated in `docs/case-schema.md` ("Ranges"), checked by a test below.

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

/// Every node coordinate, block breakpoint, probe coordinate (1 km).
pub const COORDINATE: Range = Range {
    quantity: "a coordinate",
    unit: "mm",
    lo: 0.0,
    hi: 1e6,
};
/// The size of an element (the diagonal of its corners' bounding box).
pub const ELEMENT_SIZE: Range = Range {
    quantity: "an element size",
    unit: "mm",
    lo: 1e-6,
    hi: 1e6,
};
pub const THICKNESS: Range = Range {
    quantity: "the thickness",
    unit: "mm",
    lo: 1e-6,
    hi: 1e6,
};
/// Young's modulus: 100 Pa (a soft gel is ~1 kPa) to 10⁸ MPa (diamond ~1.2·10⁶).
pub const MODULUS: Range = Range {
    quantity: "Young's modulus",
    unit: "MPa",
    lo: 1e-4,
    hi: 1e8,
};
pub const YIELD_STRESS: Range = Range {
    quantity: "a yield stress",
    unit: "MPa",
    lo: 1e-4,
    hi: 1e6,
};
/// Plastic modulus H (0 allowed: perfectly plastic).
pub const HARDENING: Range = Range {
    quantity: "a hardening modulus",
    unit: "MPa",
    lo: 1e-4,
    hi: 1e9,
};
/// Applied pressures, start pressures, critical pressures, exponential `a`.
pub const PRESSURE: Range = Range {
    quantity: "a pressure",
    unit: "MPa",
    lo: 1e-6,
    hi: 1e6,
};
/// Concentrated forces (`[[force]] fx`, `fy`): 1 µN to 1 TN.
pub const FORCE: Range = Range {
    quantity: "a force",
    unit: "N",
    lo: 1e-6,
    hi: 1e12,
};
/// Non-zero prescribed displacements and gaps.
pub const DISPLACEMENT: Range = Range {
    quantity: "a displacement or gap",
    unit: "mm",
    lo: 1e-9,
    hi: 1e4,
};
/// c_N of the power and linear laws (mm/MPa^m): 0.001 in the paper.
pub const COMPLIANCE: Range = Range {
    quantity: "an interface compliance c_N",
    unit: "mm/MPa^m",
    lo: 1e-12,
    hi: 1e3,
};
/// Slope A of the linear law's upper branch.
pub const SLOPE: Range = Range {
    quantity: "a compliance slope A",
    unit: "mm/MPa",
    lo: 1e-15,
    hi: 1e3,
};
/// b of the exponential law: 150 /mm in the docs.
pub const EXP_RATE: Range = Range {
    quantity: "an exponential rate b",
    unit: "1/mm",
    lo: 1e-3,
    hi: 1e9,
};
/// R of the tangential law (k_T^e = p_N^S / R, MPa/µm).
pub const SHEAR_R: Range = Range {
    quantity: "the shear compliance R",
    unit: "µm·MPa^(S-1)",
    lo: 1e-6,
    hi: 1e6,
};
/// The elastic shear stiffness k_T^e (MPa/µm) of a `k_table`: the values
/// p^S/R takes over the ranges of a pressure and of R with S in [0, 1].
pub const SHEAR_STIFFNESS: Range = Range {
    quantity: "a shear stiffness k_T^e",
    unit: "MPa/µm",
    lo: 1e-12,
    hi: 1e12,
};
pub const FRICTION: Range = Range {
    quantity: "a friction coefficient",
    unit: "",
    lo: 1e-4,
    hi: 100.0,
};
/// Slip-hardening rate n (0 allowed).
pub const SLIP_RATE: Range = Range {
    quantity: "a slip-hardening rate",
    unit: "1/mm",
    lo: 1e-6,
    hi: 1e9,
};

/// Every range, in the order of the documentation's table.
pub const ALL: [&Range; 16] = [
    &COORDINATE,
    &ELEMENT_SIZE,
    &THICKNESS,
    &MODULUS,
    &YIELD_STRESS,
    &HARDENING,
    &PRESSURE,
    &FORCE,
    &DISPLACEMENT,
    &COMPLIANCE,
    &SLOPE,
    &EXP_RATE,
    &SHEAR_R,
    &SHEAR_STIFFNESS,
    &FRICTION,
    &SLIP_RATE,
];

impl Range {
    /// Is `v` (finite) within the range? Zero passes: the per-key checks decide
    /// whether a key may be 0.
    pub fn admits(&self, v: f64) -> bool {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn denormal_and_huge_values_are_refused_zero_is_left_to_the_key() {
        assert!(!THICKNESS.admits(1e-310));
        assert!(!MODULUS.admits(1e300));
        assert!(MODULUS.admits(206000.0));
        assert!(THICKNESS.admits(0.0));
        let e = THICKNESS.check("case.toml: [model] thickness", 1e-310);
        let e = e.unwrap_err().to_string();
        assert!(
            e.contains("[model] thickness") && e.contains("1e-310") && e.contains("1e-6"),
            "{e}"
        );
        assert!(MODULUS.check("x", f64::NAN).is_ok());
    }

    /// The k_table stiffness range is what p^S/R spans over the ranges of
    /// p and R, S in [0, 1]: the extremes at S = 1.
    #[test]
    fn the_shear_stiffness_range_is_that_of_the_scalar_law() {
        let k = |p: f64, s: f64, r: f64| p.powf(s) / r;
        let corners = [PRESSURE.lo, PRESSURE.hi]
            .iter()
            .flat_map(|&p| [0.0, 1.0].map(|s| [SHEAR_R.lo, SHEAR_R.hi].map(|r| k(p, s, r))))
            .flatten()
            .collect::<Vec<f64>>();
        let lo = corners.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = corners.iter().copied().fold(0.0, f64::max);
        assert!((lo / SHEAR_STIFFNESS.lo - 1.0).abs() < 1e-12, "{lo}");
        assert!((hi / SHEAR_STIFFNESS.hi - 1.0).abs() < 1e-12, "{hi}");
    }

    /// docs/case-schema.md lists every range with these bounds.
    #[test]
    fn the_documented_table_matches() {
        let doc = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/case-schema.md"));
        for r in ALL {
            let row = doc
                .lines()
                .find(|l| l.starts_with(&format!("| {} |", r.quantity)))
                .unwrap_or_else(|| panic!("no row for {} in docs/case-schema.md", r.quantity));
            let bounds = if r.lo == 0.0 {
                format!("| ≤ {:e} |", r.hi)
            } else {
                format!("| {:e} … {:e} |", r.lo, r.hi)
            };
            assert!(row.contains(&bounds), "{row:?} should contain {bounds:?}");
        }
    }
}
