//! Sane magnitudes per physical quantity (mm, N, MPa): [`Range`] (see
//! [`crate::physics::range`] for why each is refused up front).
//!
//! The ranges of the interface laws' parameters are declared with their law
//! (`physics/contact/normal/<law>.rs`, `physics/contact/tangential/params.rs`)
//! and re-exported here; the case's other quantities are here. [`all`] lists
//! them all, in the order of the table in `docs/case-schema.md` ("Ranges"),
//! checked by a test below.

pub use crate::physics::contact::tangential::params::FRICTION;
pub(crate) use crate::physics::contact::tangential::params::SHEAR_STIFFNESS;
pub(crate) use crate::physics::range::{Range, DISPLACEMENT, PRESSURE};

/// Every node coordinate, block breakpoint, probe coordinate (1 km).
pub(crate) const COORDINATE: Range = Range {
    quantity: "a coordinate",
    unit: "mm",
    lo: 0.0,
    hi: 1e6,
};
/// The size of an element (the diagonal of its corners' bounding box).
pub(crate) const ELEMENT_SIZE: Range = Range {
    quantity: "an element size",
    unit: "mm",
    lo: 1e-6,
    hi: 1e6,
};
pub(crate) const THICKNESS: Range = Range {
    quantity: "the thickness",
    unit: "mm",
    lo: 1e-6,
    hi: 1e6,
};
/// Young's modulus: 100 Pa (a soft gel is ~1 kPa) to 10⁸ MPa (diamond ~1.2·10⁶).
pub(crate) const MODULUS: Range = Range {
    quantity: "Young's modulus",
    unit: "MPa",
    lo: 1e-4,
    hi: 1e8,
};
pub(crate) const YIELD_STRESS: Range = Range {
    quantity: "a yield stress",
    unit: "MPa",
    lo: 1e-4,
    hi: 1e6,
};
/// Plastic modulus H (0 allowed: perfectly plastic).
pub(crate) const HARDENING: Range = Range {
    quantity: "a hardening modulus",
    unit: "MPa",
    lo: 1e-4,
    hi: 1e9,
};
/// Thermal expansion coefficients α (`[materials.<body>] expansion`; 0
/// allowed: a body that does not expand). Metals 1e-5 … 3e-5, plastics up
/// to 2e-4, Invar 1e-6.
pub(crate) const EXPANSION: Range = Range {
    quantity: "a thermal expansion coefficient",
    unit: "1/K",
    lo: 1e-9,
    hi: 1e-3,
};
/// A body's temperature change ΔT (`[[temperature]] change` times the
/// largest value of its history).
pub(crate) const TEMPERATURE_CHANGE: Range = Range {
    quantity: "a temperature change",
    unit: "K",
    lo: 1e-6,
    hi: 1e3,
};
/// Absolute zero, °C: no temperature of a body below it.
pub(crate) const ABSOLUTE_ZERO: f64 = -273.15;
/// Densities ρ (`[materials.<body>] density`): 10 kg/m³ (a rigid foam is
/// 30) to 30 000 kg/m³ (osmium 22 590).
pub(crate) const DENSITY: Range = Range {
    quantity: "a density",
    unit: "kg/m³",
    lo: 10.0,
    hi: 3e4,
};
/// A rotational speed (`[speed] rpm` times the largest value of its
/// history): up to 10⁶ rpm (an ultracentrifuge's rotor runs at 1.5·10⁵).
pub(crate) const SPEED: Range = Range {
    quantity: "a rotational speed",
    unit: "rpm",
    lo: 1e-3,
    hi: 1e6,
};
/// Concentrated forces (`[[force]] fx`, `fy`): 1 µN to 1 TN.
pub(crate) const FORCE: Range = Range {
    quantity: "a force",
    unit: "N",
    lo: 1e-6,
    hi: 1e12,
};

/// Every range: the case's quantities, then the normal laws' (in the order
/// of `crate::physics::contact::normal::KINDS`, each quantity once), then
/// the tangential law's. A new law's ranges join by its parameters.
pub fn all() -> Vec<&'static Range> {
    let mut out: Vec<&'static Range> = vec![
        &COORDINATE,
        &ELEMENT_SIZE,
        &THICKNESS,
        &MODULUS,
        &YIELD_STRESS,
        &HARDENING,
        &EXPANSION,
        &TEMPERATURE_CHANGE,
        &DENSITY,
        &SPEED,
        &PRESSURE,
        &FORCE,
        &DISPLACEMENT,
    ];
    use crate::physics::contact::normal::{all_params, Holds};
    for p in all_params() {
        let ranges: Vec<&'static Range> = match p.holds {
            Holds::Number(r) => r.into_iter().collect(),
            Holds::Rows(columns) => columns.iter().map(|c| c.1).collect(),
        };
        for r in ranges {
            if !out.iter().any(|q| q.quantity == r.quantity) {
                out.push(r);
            }
        }
    }
    out.extend(crate::physics::contact::tangential::params::RANGES);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::contact::tangential::params::SHEAR_R;

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
        for r in all() {
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

    /// Every normal law's name and keys are in docs/case-schema.md: the name
    /// on the `law = ` line, each key in the `[interface]` example, and each
    /// ranged key (or table column) in the row of its range.
    #[test]
    fn every_normal_law_and_its_keys_are_documented() {
        use crate::physics::contact::normal::{all_params, Holds, KINDS};
        let doc = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/case-schema.md"));
        let law_line = doc.lines().find(|l| l.starts_with("law = \"")).unwrap();
        for k in KINDS {
            assert!(
                law_line.contains(&format!("\"{}\"", k.name)),
                "{law_line:?}: {}",
                k.name
            );
        }
        let row = |quantity: &str| {
            doc.lines()
                .find(|l| l.starts_with(&format!("| {quantity} |")))
                .unwrap_or_else(|| panic!("no row for {quantity}"))
        };
        for p in all_params() {
            let example = |l: &str| {
                l.trim_start_matches("# ")
                    .starts_with(&format!("{} ", p.key))
            };
            assert!(
                doc.lines().any(example),
                "`{}` is not in the example",
                p.key
            );
            match p.holds {
                Holds::Number(Some(r)) => {
                    let r = row(r.quantity);
                    assert!(r.contains(&format!("`{}`", p.key)), "{r:?}: `{}`", p.key);
                }
                Holds::Number(None) => {}
                Holds::Rows(columns) => {
                    for (column, r) in columns {
                        let r = row(r.quantity);
                        let named = format!("`{}` {column}", p.key);
                        assert!(r.contains(&named), "{r:?}: {named}");
                    }
                }
            }
        }
    }
}
