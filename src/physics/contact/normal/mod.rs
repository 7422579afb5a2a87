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
//! Each law is one file of this folder: its parameters (keys, engineering
//! ranges), how it is built from them and checked, how `asperity check`
//! describes it, and its evaluation (`Law`); `KINDS` lists them. The
//! case's checks, the documentation's table of ranges and `check` go through
//! `KINDS` and `Law`, never through a list of their own.
//!
//! For u_N ≤ 0 the pair is open: p = 0, k = 0 (loss of contact, section 2.3).
//! The power law has k = 0 at u = 0 when m < 1, so the first iteration of a
//! load step uses the secant stiffness k = p_ref / u(p_ref) (eq. 2.8-2.9).

pub mod exponential;
mod law;
pub mod linear;
pub mod power;
pub mod table;

pub(crate) use law::{Given, Holds, NormalLaw, Param};
pub use law::{Kind, Value};

/// Every normal law, in the order the case's refusals list them
/// (`law = "…" is not a known law (power, exponential, linear, table)`).
pub(crate) const KINDS: &[&Kind] = &[
    &power::KIND,
    &exponential::KIND,
    &linear::KIND,
    &table::KIND,
];

/// Every parameter of every law once, the tables first, then the numbers in
/// the order of [`KINDS`]: the order in which a case's law keys are checked
/// (and the first refusal named).
pub(crate) fn all_params() -> Vec<&'static Param> {
    let mut out: Vec<&'static Param> = Vec::new();
    let rows = |p: &&Param| matches!(p.holds, Holds::Rows(_));
    for tables in [true, false] {
        for p in KINDS.iter().flat_map(|k| k.params) {
            if rows(&p) == tables && !out.iter().any(|q| q.key == p.key) {
                out.push(p);
            }
        }
    }
    out
}

/// The law named `name` (the case's `law`).
pub fn kind(name: &str) -> Result<&'static Kind, String> {
    KINDS
        .iter()
        .copied()
        .find(|k| k.name == name)
        .ok_or_else(|| {
            let names: Vec<&str> = KINDS.iter().map(|k| k.name).collect();
            format!("law = \"{name}\" is not a known law ({})", names.join(", "))
        })
}

impl Kind {
    /// The law from the parameters a case gives: each of its own needed,
    /// every other law's refused (in the order of [`all_params`]), then
    /// built and checked.
    pub(crate) fn law_from(&self, given: &Given) -> Result<NormalLaw, String> {
        let law = self.name;
        for p in all_params() {
            let own = self.params.iter().any(|q| q.key == p.key);
            match (own, given.has(p.key)) {
                (true, false) => return Err(format!("the {law} law needs `{}`", p.key)),
                (false, true) => {
                    return Err(format!("`{}` is not a parameter of the {law} law", p.key))
                }
                _ => {}
            }
        }
        (self.build)(given)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numbers::fd;

    fn laws() -> Vec<NormalLaw> {
        vec![
            power::new(0.001, 0.5).unwrap(),
            power::new(0.002, 1.0).unwrap(),
            power::new(0.003, 0.3).unwrap(),
            exponential::new(0.8, 150.0).unwrap(),
            linear::new(0.001, 0.5, 1e-5, 10.0).unwrap(),
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
        table::new(&rows).unwrap()
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
        let e = |rows: &[(f64, f64)]| table::new(rows).unwrap_err();
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

    /// The order in which a case's law keys are checked, and so which of
    /// two faults is named: the table first, then the numbers by law.
    #[test]
    fn the_keys_of_every_law_once_in_the_order_they_are_checked() {
        let keys: Vec<&str> = all_params().iter().map(|p| p.key).collect();
        assert_eq!(keys, ["table", "c_n", "m", "a", "b", "slope", "p_c"]);
        let names: Vec<&str> = KINDS.iter().map(|k| k.name).collect();
        assert_eq!(names, ["power", "exponential", "linear", "table"]);
        let e = kind("hertz").err().unwrap();
        assert_eq!(
            e,
            "law = \"hertz\" is not a known law (power, exponential, linear, table)"
        );
    }

    #[test]
    fn paper_values_and_open_pairs() {
        // c_N = 0.001, m = 0.5: 200 MPa needs √200 · 1 µm ≈ 14.1 µm of approach.
        let law = power::new(0.001, 0.5).unwrap();
        assert!((law.approach(200.0) - 0.001 * 200f64.sqrt()).abs() < 1e-15);
        assert_eq!(law.pressure(-1e-3), (0.0, 0.0));
        assert_eq!(law.pressure(0.0), (0.0, 0.0));
        // secant (2.9): k = p^{1-m} / c_N
        let k = law.secant_stiffness(100.0);
        assert!((k - 100f64.powf(0.5) / 0.001).abs() < 1e-9 * k);
    }

    #[test]
    fn bad_parameters_are_named() {
        assert!(power::new(-1.0, 0.5).unwrap_err().contains("c_n"));
        assert!(power::new(0.001, 1.5).unwrap_err().contains("m = 1.5"));
        assert!(power::new(0.001, 0.0).unwrap_err().contains("(0, 1]"));
        assert!(power::new(f64::NAN, 0.5).is_err());
        assert!(exponential::new(1.0, -2.0).unwrap_err().contains("b ="));
        assert!(linear::new(0.001, 0.5, 1.0, 10.0)
            .unwrap_err()
            .contains("softer"));
    }
}
