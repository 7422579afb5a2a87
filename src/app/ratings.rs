//! The ratings in the words a designer reads: `check`'s line per
//! `[[rating]]` (the standard, what it rates, the inputs read off the mesh)
//! and the run's verdict per check (FE beside handbook, safety, pass).

use crate::model::Model;
use crate::solve::RunResult;
use crate::verdict::rating::{Check, Rating};

/// The run's last lines: each rating and its checks.
pub fn end_text(model: &Model, r: &RunResult) -> String {
    let ratings = match crate::verdict::rate(model, r) {
        Ok(v) => v,
        Err(e) => return format!("ratings: {e}\n"),
    };
    ratings.iter().map(rating_text).collect()
}

fn rating_text(rating: &Rating) -> String {
    let verdict = match (rating.passes(), &rating.incomplete) {
        (_, Some(why)) => format!("NOT RATED: {why}"),
        (Some(true), None) => "PASS".into(),
        (Some(false), None) => "FAIL".into(),
        (None, None) => "no verdict (no demand given)".into(),
    };
    let mut s = format!(
        "{} {} ({}): {verdict}\n",
        rating.standard, rating.name, rating.subject
    );
    for c in &rating.checks {
        s += &format!("  {}\n", check_text(c));
    }
    s
}

/// "transmissible torque M_t: FE 565 N·m, handbook 540.2 N·m (+4.6 %); demand 96 N·m, safety 5.89 ≥ 1.5: pass".
pub fn check_text(c: &Check) -> String {
    let n = number;
    let unit = if c.unit.is_empty() {
        String::new()
    } else {
        format!(" {}", c.unit)
    };
    let mut parts = Vec::new();
    if let Some(v) = c.fe {
        parts.push(format!("FE {}{unit}", n(v)));
    }
    if let Some(v) = c.handbook {
        let diff = c
            .difference
            .map_or(String::new(), |d| format!(" ({:+.1} %)", 100.0 * d));
        parts.push(format!("handbook {}{unit}{diff}", n(v)));
    }
    if parts.is_empty() {
        return format!("{} {}: not rated ({})", c.quantity, c.symbol, c.note);
    }
    let mut s = format!("{} {}: {}", c.quantity, c.symbol, parts.join(", "));
    if let (Some(req), Some(safety), Some(want)) = (c.required, c.safety, c.required_safety) {
        let verdict = if c.pass == Some(true) { "pass" } else { "FAIL" };
        s += &format!(
            "; against {}{unit}, safety {} (≥ {}): {verdict}",
            n(req),
            n(safety),
            n(want)
        );
    } else if let (Some(safety), Some(want)) = (c.safety, c.required_safety) {
        let verdict = if c.pass == Some(true) { "pass" } else { "FAIL" };
        s += &format!("; safety {} (≥ {}): {verdict}", n(safety), n(want));
    }
    s
}

/// Four significant digits, plain between 0.001 and 10⁶ (30000 N, not 3e4).
fn number(v: f64) -> String {
    let v = v + 0.0;
    let a = v.abs();
    if a == 0.0 || !(1e-3..1e6).contains(&a) {
        return crate::numbers::sig(v, 4);
    }
    let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
    format!("{v:.decimals$}")
}
