//! Normal interface laws per unit area (paper section 2.1, 2.3).
//!
//! The approach u_N (mm, > 0 when the asperities are compressed) gives the
//! contact pressure p_N (MPa, ≥ 0) and the stiffness k_N = dp_N/du_N (MPa/mm):
//!
//! ```text
//!   power        u_N = c_N p^m                 p = (u/c_N)^{1/m}         (2.1)
//!   exponential  p = a (e^{b u} − 1)           (2.2, shifted: p(0) = 0)
//!   linear       u = c_N p^m      for p < p_c                           (2.3)
//!                u = A p + B      for p ≥ p_c, B = c_N p_c^m − A p_c (continuity)
//! ```
//!
//! For u_N ≤ 0 the pair is open: p = 0, k = 0 (loss of contact, section 2.3).
//! The power law has k = 0 at u = 0 when m < 1, so the first iteration of a
//! load step uses the secant stiffness k = p_ref / u(p_ref) (eq. 2.8-2.9).

/// A normal compliance law. Parameters are validated by [`NormalLaw::new_power`] & co.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NormalLaw {
    Power {
        c: f64,
        m: f64,
    },
    Exponential {
        a: f64,
        b: f64,
    },
    Linear {
        c: f64,
        m: f64,
        slope: f64,
        p_c: f64,
    },
}

impl NormalLaw {
    /// Power law u = c p^m; c > 0, m ∈ (0, 1].
    pub fn new_power(c: f64, m: f64) -> Result<Self, String> {
        check_c_m(c, m)?;
        Ok(NormalLaw::Power { c, m })
    }

    /// Exponential law p = a (e^{b u} − 1); a > 0, b > 0.
    pub fn new_exponential(a: f64, b: f64) -> Result<Self, String> {
        if !(a.is_finite() && a > 0.0) {
            return Err(format!("a = {a} must be a positive number (MPa)"));
        }
        if !(b.is_finite() && b > 0.0) {
            return Err(format!("b = {b} must be a positive number (1/mm)"));
        }
        Ok(NormalLaw::Exponential { a, b })
    }

    /// Power law below p_c, linear u = A p + B above; A > 0, p_c > 0, and the
    /// linear branch must be at least as stiff as the power law at p_c
    /// (A ≤ du/dp there) so the law stays convex-monotone.
    pub fn new_linear(c: f64, m: f64, slope: f64, p_c: f64) -> Result<Self, String> {
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
                "slope A = {slope} mm/MPa is softer than the power law at p_c (du/dp = {dudp:.4e}); \
                 the linear branch must be stiffer"
            ));
        }
        Ok(NormalLaw::Linear { c, m, slope, p_c })
    }

    /// Pressure and stiffness (p, dp/du) at approach u. Open (u ≤ 0): (0, 0).
    pub fn pressure(&self, u: f64) -> (f64, f64) {
        if u <= 0.0 {
            return (0.0, 0.0);
        }
        match *self {
            NormalLaw::Power { c, m } => power(c, m, u),
            NormalLaw::Exponential { a, b } => {
                let e = (b * u).exp();
                (a * (e - 1.0), a * b * e)
            }
            NormalLaw::Linear { c, m, slope, p_c } => {
                let u_c = c * p_c.powf(m);
                if u < u_c {
                    power(c, m, u)
                } else {
                    (p_c + (u - u_c) / slope, 1.0 / slope)
                }
            }
        }
    }

    /// Approach u at pressure p ≥ 0 (the law's inverse).
    pub fn approach(&self, p: f64) -> f64 {
        if p <= 0.0 {
            return 0.0;
        }
        match *self {
            NormalLaw::Power { c, m } => c * p.powf(m),
            NormalLaw::Exponential { a, b } => (p / a).ln_1p() / b,
            NormalLaw::Linear { c, m, slope, p_c } => {
                if p < p_c {
                    c * p.powf(m)
                } else {
                    c * p_c.powf(m) + slope * (p - p_c)
                }
            }
        }
    }

    /// Secant stiffness p / u(p) from the origin to pressure p (eq. 2.9).
    pub fn secant_stiffness(&self, p: f64) -> f64 {
        let p = p.max(f64::MIN_POSITIVE.sqrt());
        p / self.approach(p)
    }

    /// Stored energy per unit area ∫₀ᵘ p(s) ds (for checks of the residual as a gradient).
    pub fn energy(&self, u: f64) -> f64 {
        if u <= 0.0 {
            return 0.0;
        }
        match *self {
            NormalLaw::Power { c, m } => {
                let q = 1.0 / m;
                c * (u / c).powf(q + 1.0) / (q + 1.0)
            }
            NormalLaw::Exponential { a, b } => a * (((b * u).exp() - 1.0) / b - u),
            NormalLaw::Linear { c, m, slope, p_c } => {
                let u_c = c * p_c.powf(m);
                let power_part = NormalLaw::Power { c, m }.energy(u.min(u_c));
                if u <= u_c {
                    power_part
                } else {
                    let d = u - u_c;
                    power_part + p_c * d + 0.5 * d * d / slope
                }
            }
        }
    }
}

fn power(c: f64, m: f64, u: f64) -> (f64, f64) {
    let q = 1.0 / m;
    let r = u / c;
    let p = r.powf(q);
    (p, q * p / u)
}

fn check_c_m(c: f64, m: f64) -> Result<(), String> {
    if !(c.is_finite() && c > 0.0) {
        return Err(format!("c_n = {c} must be a positive number (mm/MPa^m)"));
    }
    if !(m.is_finite() && m > 0.0 && m <= 1.0) {
        return Err(format!("m = {m} must be in (0, 1]"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn laws() -> Vec<NormalLaw> {
        vec![
            NormalLaw::new_power(0.001, 0.5).unwrap(),
            NormalLaw::new_power(0.002, 1.0).unwrap(),
            NormalLaw::new_power(0.003, 0.3).unwrap(),
            NormalLaw::new_exponential(0.8, 150.0).unwrap(),
            NormalLaw::new_linear(0.001, 0.5, 1e-5, 10.0).unwrap(),
        ]
    }

    #[test]
    fn stiffness_is_the_derivative_of_pressure() {
        for law in laws() {
            for &u in &[1e-4, 2e-3, 3.1e-3, 0.01, 0.02] {
                let h = 1e-7 * u;
                let fd = (law.pressure(u + h).0 - law.pressure(u - h).0) / (2.0 * h);
                let k = law.pressure(u).1;
                assert!(
                    (fd - k).abs() <= 1e-6 * k.abs().max(1e-9),
                    "{law:?} u={u}: {fd} vs {k}"
                );
            }
        }
    }

    #[test]
    fn pressure_is_the_derivative_of_energy_and_inverse_of_approach() {
        for law in laws() {
            for &p in &[0.5, 5.0, 12.0, 50.0, 200.0] {
                let u = law.approach(p);
                assert!((law.pressure(u).0 - p).abs() <= 1e-9 * p, "{law:?} p={p}");
                let h = 1e-6 * u;
                let fd = (law.energy(u + h) - law.energy(u - h)) / (2.0 * h);
                assert!(
                    (fd - p).abs() <= 1e-6 * p,
                    "{law:?} energy derivative {fd} vs {p}"
                );
            }
        }
    }

    #[test]
    fn paper_values_and_open_pairs() {
        // c_N = 0.001, m = 0.5: 200 MPa needs √200 · 1 µm ≈ 14.1 µm of approach.
        let law = NormalLaw::new_power(0.001, 0.5).unwrap();
        assert!((law.approach(200.0) - 0.001 * 200f64.sqrt()).abs() < 1e-15);
        assert_eq!(law.pressure(-1e-3), (0.0, 0.0));
        assert_eq!(law.pressure(0.0), (0.0, 0.0));
        // secant (2.9): k = p^{1-m} / c_N
        let k = law.secant_stiffness(100.0);
        assert!((k - 100f64.powf(0.5) / 0.001).abs() < 1e-9 * k);
    }

    #[test]
    fn bad_parameters_are_named() {
        assert!(NormalLaw::new_power(-1.0, 0.5).unwrap_err().contains("c_n"));
        assert!(NormalLaw::new_power(0.001, 1.5)
            .unwrap_err()
            .contains("m = 1.5"));
        assert!(NormalLaw::new_power(0.001, 0.0)
            .unwrap_err()
            .contains("(0, 1]"));
        assert!(NormalLaw::new_power(f64::NAN, 0.5).is_err());
        assert!(NormalLaw::new_exponential(1.0, -2.0)
            .unwrap_err()
            .contains("b ="));
        assert!(NormalLaw::new_linear(0.001, 0.5, 1.0, 10.0)
            .unwrap_err()
            .contains("softer"));
    }
}
