//! `law = "exponential"`: p = a (e^{b u} − 1) (paper eq. 2.2, shifted so p(0) = 0).

use super::law::{Given, Holds, Kind, Law, NormalLaw, Param};
use crate::physics::range::{Range, PRESSURE};

/// b of the exponential law: 150 /mm in the docs.
pub(crate) const EXP_RATE: Range = Range {
    quantity: "an exponential rate b",
    unit: "1/mm",
    lo: 1e-3,
    hi: 1e9,
};

pub(crate) const KIND: Kind = Kind {
    name: "exponential",
    params: &[
        Param {
            key: "a",
            holds: Holds::Number(Some(&PRESSURE)),
        },
        Param {
            key: "b",
            holds: Holds::Number(Some(&EXP_RATE)),
        },
    ],
    build: |g: &Given| new(g.number("a"), g.number("b")),
};

/// p = a (e^{b u} − 1).
#[derive(Clone, Copy, Debug)]
pub struct Exponential {
    pub a: f64,
    pub b: f64,
}

/// Exponential law p = a (e^{b u} − 1); a > 0, b > 0.
pub fn new(a: f64, b: f64) -> Result<NormalLaw, String> {
    if !(a.is_finite() && a > 0.0) {
        return Err(format!("a = {a} must be a positive number (MPa)"));
    }
    if !(b.is_finite() && b > 0.0) {
        return Err(format!("b = {b} must be a positive number (1/mm)"));
    }
    Ok(NormalLaw::new(Exponential { a, b }))
}

impl Law for Exponential {
    fn pressure(&self, u: f64) -> (f64, f64) {
        let Exponential { a, b } = *self;
        let e = (b * u).exp();
        (a * (e - 1.0), a * b * e)
    }

    fn approach(&self, p: f64) -> f64 {
        (p / self.a).ln_1p() / self.b
    }

    fn energy(&self, u: f64) -> f64 {
        let Exponential { a, b } = *self;
        a * (((b * u).exp() - 1.0) / b - u)
    }

    fn describe(&self) -> String {
        let Exponential { a, b } = self;
        format!("exponential p = a (e^(b u_N) - 1) (a = {a} MPa, b = {b} 1/mm)")
    }
}
