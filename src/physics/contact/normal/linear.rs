//! `law = "linear"` (paper eq. 2.3): the power law u = c_N p^m below the
//! critical pressure p_c, u = A p + B above, B = c_N p_c^m − A p_c (continuity).

use super::law::{Given, Holds, Kind, Law, NormalLaw, Param};
use super::power::{check_c_m, Power, C_N, M};
use crate::physics::range::{Range, PRESSURE};

/// Slope A of the linear law's upper branch.
pub(crate) const SLOPE: Range = Range {
    quantity: "a compliance slope A",
    unit: "mm/MPa",
    lo: 1e-15,
    hi: 1e3,
};

pub(crate) const KIND: Kind = Kind {
    name: "linear",
    params: &[
        C_N,
        M,
        Param {
            key: "slope",
            holds: Holds::Number(Some(&SLOPE)),
        },
        Param {
            key: "p_c",
            holds: Holds::Number(Some(&PRESSURE)),
        },
    ],
    build: |g: &Given| {
        new(
            g.number("c_n"),
            g.number("m"),
            g.number("slope"),
            g.number("p_c"),
        )
    },
};

/// u = c p^m below p_c, linear with slope A above.
#[derive(Clone, Copy, Debug)]
pub struct Linear {
    pub c: f64,
    pub m: f64,
    pub slope: f64,
    pub p_c: f64,
}

/// Power law below p_c, linear u = A p + B above; A > 0, p_c > 0, and the
/// linear branch must be at least as stiff as the power law at p_c
/// (A ≤ du/dp there) so the law stays convex-monotone.
pub fn new(c: f64, m: f64, slope: f64, p_c: f64) -> Result<NormalLaw, String> {
    check_c_m(c, m)?;
    if !(slope.is_finite() && slope > 0.0) {
        return Err(format!(
            "slope A = {slope} must be a positive number (mm/MPa)"
        ));
    }
    if !(p_c.is_finite() && p_c > 0.0) {
        return Err(format!("p_c = {p_c} must be a positive number (MPa)"));
    }
    let dudp = c * m * p_c.powf(m - 1.0);
    if slope > dudp * (1.0 + 1e-12) {
        return Err(format!(
            "slope A = {slope} mm/MPa is softer than the power law at p_c (its du/dp there, \
             c_n m p_c^(m-1) = {c} · {m} · {p_c}^({m} - 1), is {dudp:.4e} mm/MPa); \
             the linear branch must be stiffer"
        ));
    }
    Ok(NormalLaw::new(Linear { c, m, slope, p_c }))
}

impl Linear {
    fn power(&self) -> Power {
        Power {
            c: self.c,
            m: self.m,
        }
    }
}

impl Law for Linear {
    fn pressure(&self, u: f64) -> (f64, f64) {
        let Linear { c, m, slope, p_c } = *self;
        let u_c = c * p_c.powf(m);
        if u < u_c {
            self.power().pressure(u)
        } else {
            (p_c + (u - u_c) / slope, 1.0 / slope)
        }
    }

    fn approach(&self, p: f64) -> f64 {
        let Linear { c, m, slope, p_c } = *self;
        if p < p_c {
            c * p.powf(m)
        } else {
            c * p_c.powf(m) + slope * (p - p_c)
        }
    }

    fn energy(&self, u: f64) -> f64 {
        let Linear { c, m, slope, p_c } = *self;
        let u_c = c * p_c.powf(m);
        // the power law's energy up to u_c (the wrapper's open check: u_c > 0)
        let v = u.min(u_c);
        let power_part = if v <= 0.0 {
            0.0
        } else {
            self.power().energy(v)
        };
        if u <= u_c {
            power_part
        } else {
            let d = u - u_c;
            power_part + p_c * d + 0.5 * d * d / slope
        }
    }

    fn describe(&self) -> String {
        let Linear { c, m, slope, p_c } = self;
        format!("power-linear (c_N = {c}, m = {m}, slope = {slope} MPa/mm beyond p_c = {p_c} MPa)")
    }
}
