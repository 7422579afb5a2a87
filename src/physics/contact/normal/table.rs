//! `law = "table"`: measured points (u_N, p) interpolated monotonically (see
//! [`crate::physics::contact::table`]: a power law through the origin below
//! the first point, Fritsch-Butland monotone cubic Hermite between points,
//! linear beyond the last).

use super::law::{Given, Holds, Kind, Law, NormalLaw, Param};
use crate::physics::contact::table::{rows_of_two, Monotone};
use crate::physics::range::{DISPLACEMENT, PRESSURE};
use std::sync::Arc;

pub(crate) const KIND: Kind = Kind {
    name: "table",
    params: &[Param {
        key: "table",
        holds: Holds::Rows([("u_N", &DISPLACEMENT), ("p", &PRESSURE)]),
    }],
    build: |g: &Given| {
        let rows = rows_of_two(g.rows("table"), "u_N", "p").map_err(|m| format!("table: {m}"))?;
        new(&rows).map_err(|m| format!("table: {m}"))
    },
};

/// The interpolated points.
#[derive(Debug)]
pub struct Table(pub Arc<Monotone>);

/// Measured points (u_N mm, p MPa), the origin implied: at least 2, both
/// columns positive and strictly increasing, finite. A first row (0, 0) is
/// the origin itself and is dropped. Below the first point p = p₁ (u/u₁)^{1/m₁},
/// m₁ = ln(u₂/u₁)/ln(p₂/p₁) clamped to (0, 1] (the paper's power law 2.1 near
/// u = 0); above the last point linear with the end stiffness.
pub fn new(rows: &[(f64, f64)]) -> Result<NormalLaw, String> {
    // the messages number the rows as written, the origin included
    let (rows, first) = match rows.first() {
        Some(&(u, p)) if u == 0.0 && p == 0.0 => (&rows[1..], 2),
        _ => (rows, 1),
    };
    // q = 1/m ≥ 1: m in (0, 1]
    let t = Monotone::numbered(rows, true, (1.0, f64::INFINITY), ("u_N", "p"), first)?;
    Ok(NormalLaw::new(Table(Arc::new(t))))
}

impl Law for Table {
    fn pressure(&self, u: f64) -> (f64, f64) {
        self.0.eval(u)
    }

    fn approach(&self, p: f64) -> f64 {
        self.0.inverse(p)
    }

    fn energy(&self, u: f64) -> f64 {
        self.0.integral(u)
    }

    fn describe(&self) -> String {
        format!(
            "table of {} rows up to u_N = {} mm",
            self.0.points().count(),
            self.0.last().0
        )
    }

    fn table(&self) -> Option<&Monotone> {
        Some(&self.0)
    }
}
