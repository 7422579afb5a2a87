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
//!
//! `law = "table"` interpolates measured points (u_N, p) monotonically (see
//! [`super::table`]: a power law through the origin below the first point,
//! Fritsch-Butland monotone cubic Hermite between points, linear beyond the last).
//!
//! For u_N ≤ 0 the pair is open: p = 0, k = 0 (loss of contact, section 2.3).
//! The power law has k = 0 at u = 0 when m < 1, so the first iteration of a
//! load step uses the secant stiffness k = p_ref / u(p_ref) (eq. 2.8-2.9).

use super::table::Monotone;
use std::sync::Arc;

/// A normal compliance law. Parameters are validated by [`NormalLaw::new_power`] & co.
/// `Clone` (not `Copy`): a table holds its points (shared, behind an `Arc`).
#[derive(Clone, Debug, PartialEq)]
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
    /// Measured (u_N, p) points, interpolated monotonically.
    Table(Arc<Monotone>),
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
                "slope A = {slope} mm/MPa is softer than the power law at p_c (its du/dp there, \
                 c_n m p_c^(m-1) = {c} · {m} · {p_c}^({m} - 1), is {dudp:.4e} mm/MPa); \
                 the linear branch must be stiffer"
            ));
        }
        Ok(NormalLaw::Linear { c, m, slope, p_c })
    }

    /// Measured points (u_N mm, p MPa), the origin implied: at least 2, both
    /// columns positive and strictly increasing, finite. A first row (0, 0) is
    /// the origin itself and is dropped. Below the first point p = p₁ (u/u₁)^{1/m₁},
    /// m₁ = ln(u₂/u₁)/ln(p₂/p₁) clamped to (0, 1] (the paper's power law 2.1 near
    /// u = 0); above the last point linear with the end stiffness.
    pub fn new_table(rows: &[(f64, f64)]) -> Result<Self, String> {
        // the messages number the rows as written, the origin included
        let (rows, first) = match rows.first() {
            Some(&(u, p)) if u == 0.0 && p == 0.0 => (&rows[1..], 2),
            _ => (rows, 1),
        };
        // q = 1/m ≥ 1: m in (0, 1]
        let t = Monotone::numbered(rows, true, (1.0, f64::INFINITY), ("u_N", "p"), first)?;
        Ok(NormalLaw::Table(Arc::new(t)))
    }

    /// Pressure and stiffness (p, dp/du) at approach u. Open (u ≤ 0): (0, 0).
    pub fn pressure(&self, u: f64) -> (f64, f64) {
        if u <= 0.0 {
            return (0.0, 0.0);
        }
        match *self {
            NormalLaw::Table(ref t) => t.eval(u),
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
            NormalLaw::Table(ref t) => t.inverse(p),
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
            NormalLaw::Table(ref t) => t.integral(u),
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
    use crate::numbers::fd;

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
                let fd = fd::central_derivative(|u| law.pressure(u).0, u, h);
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
                let fd = fd::central_derivative(|u| law.energy(u), u, h);
                assert!(
                    (fd - p).abs() <= 1e-6 * p,
                    "{law:?} energy derivative {fd} vs {p}"
                );
            }
        }
    }

    /// A table sampled from u = 0.001 p^0.5 at 2 ... 14 µm (4 ... 196 MPa), unevenly.
    fn table() -> NormalLaw {
        let rows: Vec<(f64, f64)> = [0.0, 2e-3, 3e-3, 5e-3, 6e-3, 9e-3, 1.4e-2]
            .iter()
            .map(|&u| (u, (u / 0.001f64).powi(2)))
            .collect();
        NormalLaw::new_table(&rows).unwrap()
    }

    #[test]
    fn table_law_tangent_energy_and_inverse_in_every_regime() {
        let law = table();
        // below the first point (power law through the origin), on a knot,
        // between points, beyond the last (linear)
        for &u in &[
            3e-4, 1.5e-3, 2e-3, 2.6e-3, 4.4e-3, 6e-3, 1.1e-2, 1.4e-2, 2.5e-2,
        ] {
            let (p, k) = law.pressure(u);
            assert!(p > 0.0 && k > 0.0, "u = {u}: p {p}, k {k}");
            let h = 1e-7 * u;
            let fd = fd::central_derivative(|u| law.pressure(u).0, u, h);
            assert!((fd - k).abs() <= 1e-6 * k, "u = {u}: dp/du {k} vs FD {fd}");
            let fe = fd::central_derivative(|u| law.energy(u), u, h);
            assert!((fe - p).abs() <= 1e-6 * p, "u = {u}: dφ/du {fe} vs p {p}");
            assert!((law.approach(p) - u).abs() <= 1e-12 * u, "u = {u}: inverse");
            let sec = law.secant_stiffness(p);
            assert!((sec - p / u).abs() <= 1e-9 * sec, "u = {u}: secant (2.9)");
        }
        // open
        assert_eq!(law.pressure(-1e-3), (0.0, 0.0));
        assert_eq!(law.pressure(0.0), (0.0, 0.0));
        assert_eq!(law.energy(-1e-3), 0.0);
        // the measured points themselves, and the paper's exponent below the first
        for &u in &[2e-3, 5e-3, 1.4e-2] {
            let exact = (u / 0.001f64).powi(2);
            assert!((law.pressure(u).0 - exact).abs() <= 1e-12 * exact);
        }
        let u = 1e-3;
        assert!(
            (law.pressure(u).0 - 1.0).abs() < 1e-12,
            "p = (u/c)² below row 1"
        );
        // beyond the last point: linear with the end stiffness
        let (p1, k1) = law.pressure(0.02);
        let (p2, k2) = law.pressure(0.03);
        assert_eq!(k1, k2);
        assert!((p2 - p1 - k1 * 0.01).abs() <= 1e-12 * p2);
    }

    #[test]
    fn table_law_is_monotone_with_a_continuous_stiffness() {
        let law = table();
        let mut p_prev = 0.0;
        for i in 1..=4000 {
            let u = 2e-2 * i as f64 / 4000.0;
            let (p, k) = law.pressure(u);
            assert!(p > p_prev && k > 0.0, "u = {u}");
            p_prev = p;
        }
        // no jump of the stiffness at the measured points (the first one joins
        // the power law below, the last one the linear tail)
        for &u in &[2e-3, 3e-3, 5e-3, 6e-3, 9e-3, 1.4e-2] {
            let e = 1e-10 * u;
            let (l, r) = (law.pressure(u - e).1, law.pressure(u + e).1);
            assert!((l - r).abs() <= 1e-6 * l, "u = {u}: k {l} | {r}");
        }
    }

    #[test]
    fn bad_tables_are_named() {
        let e = |rows: &[(f64, f64)]| NormalLaw::new_table(rows).unwrap_err();
        assert!(e(&[(0.0, 0.0), (1e-3, 1.0)]).contains("1 point"));
        assert!(e(&[(1e-3, 1.0), (2e-3, 0.5)]).contains("not monotone"));
        assert!(e(&[(1e-3, -1.0), (2e-3, 4.0)]).contains("row 1: p = -1"));
        assert!(e(&[(1e-3, 1.0), (2e-3, f64::NAN)]).contains("row 2"));
        // only the origin itself may have u = 0
        assert!(e(&[(0.0, 1.0), (2e-3, 4.0), (3e-3, 9.0)]).contains("row 1: u_N = 0"));
        // rows counted as written: with the origin written first, the bad
        // row is the fourth, not the third of the rows after it
        let m = e(&[(0.0, 0.0), (2e-3, 4.0), (5e-3, 25.0), (8e-3, 20.0)]);
        assert!(m.contains("row 4: p = 20") && m.contains("row 3"), "{m}");
        let m = e(&[(0.0, 0.0), (1.0, 10.0), (2.0, 10.5), (3.0, 11.0)]);
        assert!(
            m.contains("rows 2-3: the table softens too fast after row 2"),
            "{m}"
        );
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
