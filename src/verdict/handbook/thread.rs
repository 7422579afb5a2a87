//! ISO metric threads (ISO 261 sizes, ISO 262 selected pitches, ISO 724 basic dimensions) and
//! the strength of bolt property classes (ISO 898-1).
//!
//! Lengths in mm, areas in mm², strengths in MPa. The diameters follow from d and the pitch P by
//! the basic profile (ISO 68-1, fundamental triangle height H = (√3/2) P):
//!
//! ```text
//!   d2 = d − 0.64952 P          (pitch diameter, ISO 724)
//!   d3 = d − 1.22687 P          (minor diameter of the bolt, with the root radius H/6)
//!   A_S  = π/4 ((d2 + d3)/2)²   (stress area, ISO 898-1)
//!   A_d3 = π/4 d3²,   A_N = π/4 d²
//! ```

use std::f64::consts::PI;

/// ISO 261 coarse series, first and second choice, M3 to M64: (d, P) in mm.
const COARSE: [(f64, f64); 26] = [
    (3.0, 0.5),
    (3.5, 0.6),
    (4.0, 0.7),
    (5.0, 0.8),
    (6.0, 1.0),
    (8.0, 1.25),
    (10.0, 1.5),
    (12.0, 1.75),
    (14.0, 2.0),
    (16.0, 2.0),
    (18.0, 2.5),
    (20.0, 2.5),
    (22.0, 2.5),
    (24.0, 3.0),
    (27.0, 3.0),
    (30.0, 3.5),
    (33.0, 3.5),
    (36.0, 4.0),
    (39.0, 4.0),
    (42.0, 4.5),
    (45.0, 4.5),
    (48.0, 5.0),
    (52.0, 5.0),
    (56.0, 5.5),
    (60.0, 5.5),
    (64.0, 6.0),
];

/// The pitches of ISO 261 (coarse and fine), mm.
pub const PITCHES: [f64; 24] = [
    0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.6, 0.7, 0.75, 0.8, 1.0, 1.25, 1.5, 1.75, 2.0, 2.5, 3.0,
    3.5, 4.0, 4.5, 5.0, 5.5, 6.0,
];

/// A metric ISO thread: nominal diameter and pitch. Build it with [`Thread::coarse`],
/// [`Thread::coarse_of`] or [`Thread::fine`], which check the numbers; a thread written field by
/// field is taken as given (the rating functions still refuse a non-positive d3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thread {
    /// Nominal (major) diameter d (mm).
    pub d: f64,
    /// Pitch P (mm).
    pub pitch: f64,
}

impl Thread {
    /// The coarse thread of ISO 261 named like "M12" or "M3.5" (case and surrounding blanks
    /// ignored), M3 to M64, first and second choice; `None` for any other name (fine threads
    /// such as "M12x1.5" included: use [`Thread::fine`]).
    pub fn coarse(name: &str) -> Option<Thread> {
        let name = name.trim();
        let digits = name.strip_prefix('M').or_else(|| name.strip_prefix('m'))?;
        let d: f64 = digits.parse().ok()?;
        Thread::coarse_of(d)
    }

    /// The coarse thread of ISO 261 of nominal diameter d (mm), M3 to M64 (first and second
    /// choice); `None` for a diameter not in the series.
    pub fn coarse_of(d: f64) -> Option<Thread> {
        COARSE
            .iter()
            .find(|&&(dn, _)| (dn - d).abs() < 1e-9)
            .map(|&(d, pitch)| Thread { d, pitch })
    }

    /// Whether the pitch is one of ISO 261's series ([`PITCHES`]) and at most
    /// the coarse pitch of its size (a fine thread is finer than the coarse
    /// one; a size outside the coarse table: at most d/4).
    pub fn iso_pitch(&self) -> bool {
        let coarsest = Thread::coarse_of(self.d).map_or(self.d / 4.0, |c| c.pitch);
        PITCHES.iter().any(|&p| (p - self.pitch).abs() < 1e-9) && self.pitch <= coarsest + 1e-9
    }

    /// Any thread of the ISO profile, for fine pitches (ISO 262) or sizes outside the table:
    /// `None` unless d > 0, P > 0 and the minor diameter d3 = d − 1.22687 P is positive.
    pub fn fine(d: f64, pitch: f64) -> Option<Thread> {
        let t = Thread { d, pitch };
        (d.is_finite() && pitch.is_finite() && pitch > 0.0 && t.d3() > 0.0).then_some(t)
    }

    /// Pitch diameter d2 = d − 0.64952 P (mm), ISO 724.
    pub fn d2(&self) -> f64 {
        self.d - 0.64952 * self.pitch
    }

    /// Minor diameter of the bolt thread d3 = d − 1.22687 P (mm), ISO 724 / ISO 898-1.
    pub fn d3(&self) -> f64 {
        self.d - 1.22687 * self.pitch
    }

    /// Diameter of the stress area d_S = (d2 + d3)/2 (mm), so that A_S = π d_S²/4.
    pub fn stress_diameter(&self) -> f64 {
        0.5 * (self.d2() + self.d3())
    }

    /// Stress area A_S = π/4 ((d2 + d3)/2)² (mm²), ISO 898-1.
    pub fn stress_area(&self) -> f64 {
        circle(self.stress_diameter())
    }

    /// Core area A_d3 = π d3²/4 (mm²).
    pub fn core_area(&self) -> f64 {
        circle(self.d3())
    }

    /// Nominal area A_N = π d²/4 (mm²).
    pub fn nominal_area(&self) -> f64 {
        circle(self.d)
    }
}

/// Area of a circle of diameter `d`, π d²/4.
pub(crate) fn circle(d: f64) -> f64 {
    0.25 * PI * d * d
}

/// Minimum strengths of a bolt property class, ISO 898-1 (MPa).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PropertyClass {
    /// The class as written, "8.8".
    pub name: &'static str,
    /// Minimum tensile strength R_m,min (MPa).
    pub r_m: f64,
    /// Minimum yield strength (MPa): the lower yield strength R_eL for 4.6 and 5.6, the 0.2 %
    /// proof strength R_p0.2 for 8.8 to 12.9 (VDI 2230-1 calls either R_p0.2min).
    pub r_p02: f64,
}

impl PropertyClass {
    /// The minimum strengths of class `name` ("4.6", "5.6", "8.8", "9.8", "10.9", "12.9") for a
    /// bolt of nominal diameter d (mm), ISO 898-1:
    ///
    /// ```text
    ///   4.6: R_m 400, R_eL 240          8.8, d ≤ 16: R_m 800, R_p0.2 640
    ///   5.6: R_m 500, R_eL 300          8.8, d > 16: R_m 830, R_p0.2 660
    ///   9.8 (d ≤ 16 only): 900, 720     10.9: 1040, 940      12.9: 1220, 1100
    /// ```
    ///
    /// `None` for an unknown class, for 9.8 above d = 16, and for d outside the standard's range
    /// 1.6 ≤ d ≤ 39 mm.
    pub fn of(name: &str, d: f64) -> Option<PropertyClass> {
        if !(1.6..=39.0).contains(&d) {
            return None;
        }
        let small = d <= 16.0;
        let (name, r_m, r_p02) = match name.trim() {
            "4.6" => ("4.6", 400.0, 240.0),
            "5.6" => ("5.6", 500.0, 300.0),
            "8.8" if small => ("8.8", 800.0, 640.0),
            "8.8" => ("8.8", 830.0, 660.0),
            "9.8" if small => ("9.8", 900.0, 720.0),
            "10.9" => ("10.9", 1040.0, 940.0),
            "12.9" => ("12.9", 1220.0, 1100.0),
            _ => return None,
        };
        Some(PropertyClass { name, r_m, r_p02 })
    }
}
