//! `law = "power"`: u_N = c_N p^m (paper eq. 2.1), p = (u/c_N)^{1/m}.

use super::law::{Given, Holds, Kind, Law, NormalLaw, Param};
use crate::physics::range::Range;

/// c_N of the power and linear laws (mm/MPa^m): 0.001 in the paper.
pub(crate) const COMPLIANCE: Range = Range {
    quantity: "an interface compliance c_N",
    unit: "mm/MPa^m",
    lo: 1e-12,
    hi: 1e3,
};

/// `c_n`, also the linear law's.
pub const C_N: Param = Param {
    key: "c_n",
    holds: Holds::Number(Some(&COMPLIANCE)),
};
/// `m` in (0, 1] (its own check), also the linear law's.
pub const M: Param = Param {
    key: "m",
    holds: Holds::Number(None),
};

pub(crate) const KIND: Kind = Kind {
    name: "power",
    params: &[C_N, M],
    build: |g: &Given| new(g.number("c_n"), g.number("m")),
};

/// u = c p^m.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Power {
    pub c: f64,
    pub m: f64,
}

/// Power law u = c p^m; c > 0, m ∈ (0, 1].
pub fn new(c: f64, m: f64) -> Result<NormalLaw, String> {
    check_c_m(c, m)?;
    Ok(NormalLaw::new(Power { c, m }))
}

/// c_N > 0 and m ∈ (0, 1] (the power and linear laws).
pub(crate) fn check_c_m(c: f64, m: f64) -> Result<(), String> {
    if !(c.is_finite() && c > 0.0) {
        return Err(format!("c_n = {c} must be a positive number (mm/MPa^m)"));
    }
    if !(m.is_finite() && m > 0.0 && m <= 1.0) {
        return Err(format!("m = {m} must be in (0, 1]"));
    }
    Ok(())
}

impl Law for Power {
    fn pressure(&self, u: f64) -> (f64, f64) {
        let q = 1.0 / self.m;
        let r = u / self.c;
        let p = r.powf(q);
        (p, q * p / u)
    }

    fn approach(&self, p: f64) -> f64 {
        self.c * p.powf(self.m)
    }

    fn energy(&self, u: f64) -> f64 {
        let (c, q) = (self.c, 1.0 / self.m);
        c * (u / c).powf(q + 1.0) / (q + 1.0)
    }

    fn describe(&self) -> String {
        let Power { c, m } = self;
        format!("power u_N = c_N p^m (c_N = {c}, m = {m})")
    }
}
