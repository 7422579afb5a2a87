//! The ranges of every number of a calibration input (issue 30).
//!
//! Each quantity has two ranges. Outside the *accepted* range the value is not
//! a surface or a material anyone means (a subnormal σ, a modulus of 1e300 MPa,
//! summits closer than atoms) and is refused with the key's name: it would
//! otherwise turn into a meaningless curve or an error blamed on another key.
//! Outside the *usual* range (the engineering range of the quantity) the value
//! is legal but suspicious, typically a slip of unit prefix (σ in µm written as
//! mm, a density per m² written per mm²): the calibration is made and a
//! warning names the key. docs/calibration.md ("Ranges") has the table, checked
//! by a test below.

use crate::error::{Error, Result};
pub use crate::numbers::{exact, num, sig};
use std::fmt;

/// The ranges of one quantity: refused outside `accepted`, warned outside
/// `usual` (both inclusive).
#[derive(Clone, Copy, Debug)]
pub struct Limit {
    /// What it is, as in a sentence: "σ_s, the standard deviation of summit heights".
    pub quantity: &'static str,
    pub unit: &'static str,
    pub accepted: [f64; 2],
    pub usual: [f64; 2],
    /// What the usual range spans, for the messages and the docs.
    pub(crate) usual_is: &'static str,
    /// The likely slip when a value is above / below the usual range.
    pub above: &'static str,
    pub below: &'static str,
}

/// Young's modulus: accepted as by the case file (src/input/case/ranges.rs MODULUS).
pub(crate) const YOUNG: Limit = Limit {
    quantity: "Young's modulus",
    unit: "MPa",
    accepted: [
        crate::input::case::ranges::MODULUS.lo,
        crate::input::case::ranges::MODULUS.hi,
    ],
    usual: [1.0, 1.2e6],
    usual_is: "1 MPa for soft elastomers to 1.2e6 MPa for diamond",
    above: "a value in kPa or Pa written as MPa?",
    below: "a value in GPa written as MPa?",
};
/// Hardness of the softer body (CEB summits).
pub(crate) const HARDNESS: Limit = Limit {
    quantity: "the hardness",
    unit: "MPa",
    accepted: [
        crate::input::case::ranges::YIELD_STRESS.lo,
        crate::input::case::ranges::YIELD_STRESS.hi,
    ],
    usual: [10.0, 1.0e5],
    usual_is: "10 MPa for indium or lead to 1e5 MPa for diamond",
    above: "a value in kPa written as MPa?",
    below: "a value in GPa written as MPa?",
};
/// η, summits per mm².
pub(crate) const DENSITY: Limit = Limit {
    quantity: "η, the summit density",
    unit: "/mm²",
    // one summit per m² to summits 0.1 nm apart (an atomic distance)
    accepted: [1e-6, 1e14],
    usual: [1.0, 1.0e6],
    usual_is: "1 to 1e6 per mm², summits 1 mm to 1 µm apart",
    above: "a density per m² written as per mm² (1 /mm² = 1e6 /m²)?",
    below: "a density per µm² written as per mm² (1 /µm² = 1e6 /mm²)?",
};
/// β, mm.
pub(crate) const RADIUS: Limit = Limit {
    quantity: "β, the summit radius",
    unit: "mm",
    accepted: [1e-7, 1e4],
    usual: [1e-4, 10.0],
    usual_is: "0.1 µm to 10 mm",
    above: "a value in µm written as mm?",
    below: "a value in m written as mm?",
};
/// σ_s, mm.
pub(crate) const SIGMA: Limit = Limit {
    quantity: "σ_s, the standard deviation of summit heights",
    unit: "mm",
    // 0.1 nm (atomic) to 100 mm
    accepted: [1e-7, 100.0],
    usual: [1e-5, 0.1],
    usual_is: "0.01 µm for lapped or polished to 100 µm for sand-cast or rough-turned faces",
    above: "a value in µm written as mm?",
    below: "a value in m written as mm?",
};
/// Δ, mm.
pub(crate) const SAMPLING: Limit = Limit {
    quantity: "Δ, the sampling interval",
    unit: "mm",
    accepted: [1e-9, 100.0],
    usual: [1e-6, 0.1],
    usual_is: "1 nm for an atomic force microscope to 100 µm for a coarse profilometer",
    above: "a value in µm written as mm?",
    below: "a value in m written as mm?",
};
/// The fit range: accepted as the case file's pressures (src/input/case/ranges.rs PRESSURE).
pub(crate) const PRESSURE: Limit = Limit {
    quantity: "a fit pressure",
    unit: "MPa",
    accepted: [
        crate::input::case::ranges::PRESSURE.lo,
        crate::input::case::ranges::PRESSURE.hi,
    ],
    usual: [1e-3, 1e4],
    usual_is: "1 kPa to 10 GPa, the hardness of the hardest steels",
    above: "a value in kPa or Pa written as MPa?",
    below: "a value in GPa written as MPa?",
};
/// The reference pressure (u_N = 0): small by design, so no usual range.
pub(crate) const REFERENCE: Limit = Limit {
    quantity: "the reference pressure",
    unit: "MPa",
    accepted: [1e-12, crate::input::case::ranges::PRESSURE.hi],
    usual: [1e-12, crate::input::case::ranges::PRESSURE.hi],
    usual_is: "",
    above: "",
    below: "",
};

/// Every limit, in the order of the documentation's table.
#[cfg(test)]
pub(crate) const ALL: [(&str, &Limit); 13] = [
    ("young", &YOUNG),
    ("hardness", &HARDNESS),
    ("density", &DENSITY),
    ("radius", &RADIUS),
    ("sigma", &SIGMA),
    ("sampling", &SAMPLING),
    ("ra", &RA),
    ("rz", &RZ),
    ("hurst", &HURST_LIMIT),
    ("cutoff", &CUTOFF),
    ("short_cutoff", &SHORT_CUTOFF),
    ("pressure", &PRESSURE),
    ("reference_pressure", &REFERENCE),
];

/// A legal but suspicious value: `place: key: message`, printed as
/// `warning: …` and kept in fit.json and interface.toml.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    pub place: String,
    pub key: String,
    pub message: String,
}

impl fmt::Display for Warning {
    /// One line, escaped like an error.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let line = format!("{}: {}: {}", self.place, self.key, self.message);
        f.write_str(&crate::error::bounded(&crate::error::escape_controls(
            &line,
        )))
    }
}

impl Limit {
    fn with_unit(&self, v: f64) -> String {
        if self.unit.is_empty() {
            num(v)
        } else {
            format!("{} {}", num(v), self.unit)
        }
    }

    /// Refuses `v` outside the accepted range (and non-finite, non-positive or
    /// subnormal) with `place: key`; outside the usual range, a warning is
    /// pushed to `warnings`.
    pub fn check(&self, place: &str, key: &str, v: f64, warnings: &mut Vec<Warning>) -> Result<()> {
        self.check_hinted(place, key, v, warnings, None)
    }

    /// [`Limit::check`] with the warning's guess at the slip given (a value
    /// derived from a profile has other likely causes than its key's unit).
    pub(crate) fn check_hinted(
        &self,
        place: &str,
        key: &str,
        v: f64,
        warnings: &mut Vec<Warning>,
        hint: Option<&str>,
    ) -> Result<()> {
        self.judge(place, key, None, v, warnings, hint)
    }

    /// A value no key gives, derived from the input keys `inputs` (σ_s, η
    /// and β from a profile's heights or from Ra / Rz): refused or warned as
    /// [`Limit::check_hinted`], at those keys (`place: inputs`, never a name
    /// of the derived quantity), the message naming the quantity and `how`
    /// the keys made it ("derived from them, H = 0.8 assumed").
    pub(crate) fn check_derived(
        &self,
        place: &str,
        inputs: &str,
        how: &str,
        v: f64,
        warnings: &mut Vec<Warning>,
        hint: Option<&str>,
    ) -> Result<()> {
        self.judge(place, inputs, Some(how), v, warnings, hint)
    }

    /// The checks of [`Limit::check_hinted`] and [`Limit::check_derived`]
    /// (`derived`: how `key`, the inputs, made `v`).
    fn judge(
        &self,
        place: &str,
        key: &str,
        derived: Option<&str>,
        v: f64,
        warnings: &mut Vec<Warning>,
        hint: Option<&str>,
    ) -> Result<()> {
        let refuse = |message: String| Err(Error::input(format!("{place}: {key}"), message));
        // what the messages call the value, and the quantity after "as"
        // and "of": a key's value is the quantity, a derived one is named
        let (value, as_q, of_q) = match derived {
            None => (
                self.with_unit(v),
                format!(" as {}", self.quantity),
                format!("the usual range of {}", self.quantity),
            ),
            Some(how) => (
                format!("{} for {}, {how},", self.with_unit(v), self.quantity),
                String::new(),
                "its usual range".to_string(),
            ),
        };
        if !v.is_finite() || v <= 0.0 {
            return refuse(match derived {
                None if !v.is_finite() => format!("must be a finite number, got {v}"),
                None => format!("must be a positive finite number, got {}", num(v)),
                Some(how) => format!(
                    "{} for {}, {how}, is not a positive finite number",
                    num(v),
                    self.quantity
                ),
            });
        }
        let [lo, hi] = self.accepted;
        if v < f64::MIN_POSITIVE {
            let not = match derived {
                None => format!(", not {}", self.quantity),
                Some(_) => String::new(),
            };
            let value = match derived {
                None => num(v),
                Some(how) => format!("{} for {}, {how},", num(v), self.quantity),
            };
            return refuse(format!(
                "{value} is a subnormal number (below 2.2e-308){not}: accepted {} to {}",
                self.with_unit(lo),
                self.with_unit(hi)
            ));
        }
        if v < lo || v > hi {
            let usual = if self.usual_is.is_empty() {
                String::new()
            } else {
                format!("; usual {}", self.usual_is)
            };
            return refuse(format!(
                "{value} is far outside any use{as_q}: accepted {} to {}{usual}",
                self.with_unit(lo),
                self.with_unit(hi),
            ));
        }
        let [ulo, uhi] = self.usual;
        if v < ulo || v > uhi {
            let (side, hint) = if v > uhi {
                ("above", hint.unwrap_or(self.above))
            } else {
                ("below", hint.unwrap_or(self.below))
            };
            warnings.push(Warning {
                place: place.to_string(),
                key: key.to_string(),
                message: format!("{value} is {side} {of_q}, {}: {hint}", self.usual_is),
            });
        }
        Ok(())
    }
}

/// ν: accepted in (−1, 0.5) (zero included, subnormals not), usual [0, 0.5).
pub(crate) fn check_poisson(
    place: &str,
    key: &str,
    v: f64,
    warnings: &mut Vec<Warning>,
) -> Result<()> {
    let refuse = |message: String| Err(Error::input(format!("{place}: {key}"), message));
    if !(v > -1.0 && v < 0.5) {
        return refuse(format!("must be in (−1, 0.5), got {}", num(v)));
    }
    if v != 0.0 && v.abs() < f64::MIN_POSITIVE {
        return refuse(format!(
            "{} is a subnormal number (below 2.2e-308), not a Poisson ratio",
            num(v)
        ));
    }
    if v < 0.0 {
        warnings.push(Warning {
            place: place.to_string(),
            key: key.to_string(),
            message: format!(
                "{} is negative: only auxetic foams and lattices have ν < 0 (metals 0.25-0.35, polymers 0.35-0.5); a minus sign too many?",
                num(v)
            ),
        });
    }
    Ok(())
}

/// The ranges of the roughness parameters of `[surface] model = "roughness"`
/// ([`super::roughness`]).
/// Ra, mm: ISO 4288 tabulates 0.006 to 80 µm.
pub(crate) const RA: Limit = Limit {
    quantity: "Ra, the arithmetic mean height",
    unit: "mm",
    accepted: [1e-7, 1.0],
    usual: [6e-6, 0.08],
    usual_is: "0.006 µm to 80 µm, the span of ISO 4288 Table 1",
    above: "a value in µm written as mm (Ra 0.8 µm is ra = 0.8e-3)?",
    below: "a value in m written as mm?",
};
/// Rz, mm: ISO 4288 tabulates 0.025 to 200 µm.
pub const RZ: Limit = Limit {
    quantity: "Rz, the mean peak-to-valley height",
    unit: "mm",
    accepted: [1e-7, 5.0],
    usual: [2.5e-5, 0.2],
    usual_is: "0.025 µm to 200 µm, the span of ISO 4288 Table 2",
    above: "a value in µm written as mm (Rz 6.3 µm is rz = 6.3e-3)?",
    below: "a value in m written as mm?",
};
/// H, the Hurst exponent of the assumed spectrum.
pub(crate) const HURST_LIMIT: Limit = Limit {
    quantity: "H, the Hurst exponent",
    unit: "",
    accepted: [0.1, 1.0],
    usual: [0.5, 1.0],
    usual_is: "0.5 to 1 for machined and blasted surfaces (Persson et al. 2005)",
    above: "",
    below: "a spectrum this rich in short waves is rare for machined faces",
};
/// λc, mm.
pub(crate) const CUTOFF: Limit = Limit {
    quantity: "λc, the cutoff wavelength",
    unit: "mm",
    accepted: [1e-3, 100.0],
    usual: [0.08, 8.0],
    usual_is: "0.08 to 8 mm, the cutoffs of ISO 4288",
    above: "a value in µm written as mm?",
    below: "a value in m written as mm?",
};
/// λs, mm.
pub(crate) const SHORT_CUTOFF: Limit = Limit {
    quantity: "λs, the short-wavelength cutoff",
    unit: "mm",
    accepted: [1e-6, 10.0],
    usual: [2.5e-4, 0.025],
    usual_is: "0.25 to 25 µm (ISO 3274 gives 2.5, 8 and 25 µm)",
    above: "a value in µm written as mm?",
    below: "a value in m written as mm?",
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subnormal_huge_and_negative_values_are_refused_naming_the_key() {
        let mut w = Vec::new();
        for (v, says) in [
            (1e-310, "subnormal"),
            (1e300, "far outside"),
            (f64::INFINITY, "finite"),
            (f64::NAN, "finite"),
            (0.0, "positive"),
            (-1e-3, "positive"),
        ] {
            let e = SIGMA
                .check("s.toml", "surface.sigma", v, &mut w)
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with("s.toml: surface.sigma: ") && e.contains(says),
                "{v}: {e}"
            );
        }
        assert!(w.is_empty());
    }

    #[test]
    fn a_unit_slip_warns_and_passes() {
        let mut w = Vec::new();
        SIGMA.check("s.toml", "surface.sigma", 1.0, &mut w).unwrap();
        DENSITY
            .check("s.toml", "surface.density", 1e12, &mut w)
            .unwrap();
        SIGMA
            .check("s.toml", "surface.sigma", 1e-3, &mut w)
            .unwrap();
        assert_eq!(w.len(), 2, "{w:?}");
        let s = w[0].to_string();
        assert!(
            s.starts_with("s.toml: surface.sigma: 1 mm is above the usual range")
                && s.contains("µm written as mm"),
            "{s}"
        );
        assert!(
            w[1].to_string().contains("per m² written as per mm²"),
            "{}",
            w[1]
        );
        check_poisson("s.toml", "materials.a.poisson", -0.2, &mut w).unwrap();
        assert_eq!(w.len(), 3);
        assert!(check_poisson("s.toml", "materials.a.poisson", 5e-324, &mut w).is_err());
        assert!(check_poisson("s.toml", "materials.a.poisson", 0.0, &mut w).is_ok());
    }

    #[test]
    fn usual_ranges_lie_inside_the_accepted_ones() {
        for (key, l) in ALL {
            assert!(
                l.accepted[0] >= f64::MIN_POSITIVE
                    && l.accepted[0] <= l.usual[0]
                    && l.usual[0] < l.usual[1]
                    && l.usual[1] <= l.accepted[1],
                "{key}"
            );
        }
    }

    /// docs/calibration.md lists every range with these bounds.
    #[test]
    fn the_docs_table_matches() {
        let doc = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/calibration.md"),
        )
        .unwrap();
        for (key, l) in ALL {
            let row = format!(
                "| `{key}` | {} | {} – {} | {} – {} |",
                l.unit,
                num(l.usual[0]),
                num(l.usual[1]),
                num(l.accepted[0]),
                num(l.accepted[1])
            );
            let row = if key == "reference_pressure" {
                format!(
                    "| `{key}` | {} | – | {} – {} |",
                    l.unit,
                    num(l.accepted[0]),
                    num(l.accepted[1])
                )
            } else {
                row
            };
            assert!(
                doc.contains(&row),
                "docs/calibration.md lacks the row {row}"
            );
        }
    }
}
