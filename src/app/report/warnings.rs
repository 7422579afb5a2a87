//! Section 6: everything summary.json says that qualifies the results: its
//! `warnings` (tables used far beyond their last row, cycles of too few
//! increments, …), a run stopped early, tables extrapolated, singular
//! corners, the stabilization acting, interface loops and event searches
//! that did not converge.

use super::format::figure;
use super::html::Page;
use super::{num, text};
use serde_json::Value;

/// The warnings, each a sentence.
pub(super) fn collect(s: &Value) -> Vec<String> {
    let mut out: Vec<String> = list(s, "warnings")
        .iter()
        .filter_map(|w| w.as_str().map(str::to_string))
        .collect();
    if s.get("complete").and_then(Value::as_bool) == Some(false) {
        let by = text(s, "stopped_by").unwrap_or_else(|| "an unrecorded reason".into());
        out.push(if by == "torque_limit" {
            "the run ended at its torque limit (event torque_limit): a body held about the axis by friction alone could not hold the torque on it beyond, so the results end at the last state that held, not at the end of the load history".to_string()
        } else {
            format!("the run was stopped early by {by}: the results end at its last converged increment, not at the end of the load history")
        });
    }
    for t in list(s, "tables")
        .iter()
        .filter(|t| t.get("beyond_limit").and_then(Value::as_bool) == Some(true))
    {
        out.push(format!(
            "interface {}: its {} was extrapolated to {} times its last row ({} = {} {})",
            text(t, "interface").unwrap_or_default(),
            text(t, "key").unwrap_or_default(),
            num(t, "ratio").map_or("—".into(), figure),
            text(t, "argument").unwrap_or_default(),
            num(t, "largest").map_or("—".into(), figure),
            text(t, "unit").unwrap_or_default()
        ));
    }
    for p in list(s, "singular") {
        out.push(format!(
            "{} in body {} at a singular point, {} {}: {}",
            text(p, "what").unwrap_or_default().replace('_', " "),
            text(p, "body").unwrap_or_default(),
            text(p, "corner").unwrap_or_default(),
            super::results::place(p),
            text(p, "note").unwrap_or_else(|| "its value grows with refinement".into())
        ));
    }
    out.extend(solver_notes(s));
    out
}

/// The array `key` of `s` (empty where absent).
fn list<'a>(s: &'a Value, key: &str) -> &'a [Value] {
    s.get(key)
        .and_then(Value::as_array)
        .map_or(&[], Vec::as_slice)
}

/// The stabilization acting, interface loops that fell back, event
/// searches that stopped short.
fn solver_notes(s: &Value) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(st) = s.get("stabilization").filter(|v| v.is_object()) {
        if num(st, "steps_stabilized").is_some_and(|n| n > 0.0) {
            out.push(format!(
                "{} steps were accepted with the contact stabilization acting (dissipated energy {} of the internal energy)",
                num(st, "steps_stabilized").map_or("—".into(), figure),
                num(st, "energy_ratio").map_or("—".into(), figure)
            ));
        }
    }
    if let Some(n) = num(s, "interface_fallbacks").filter(|&n| n > 0.0) {
        out.push(format!("{} interface loops did not converge in their iterations (their best iterate was taken)", figure(n)));
    }
    for e in list(s, "events") {
        let failed = e.get("solve_failed").and_then(Value::as_bool) == Some(true);
        let loose = e.get("converged").and_then(Value::as_bool) == Some(false);
        if failed || loose {
            out.push(format!(
                "the event {} was not located to its tolerance{}: its bracket is [{}]",
                text(e, "event").unwrap_or_default(),
                if failed {
                    " (a step of its search did not converge)"
                } else {
                    ""
                },
                e.get("bracket")
                    .and_then(Value::as_array)
                    .map(|b| b
                        .iter()
                        .map(|v| v.as_f64().map_or("—".into(), figure))
                        .collect::<Vec<_>>()
                        .join(", "))
                    .unwrap_or_default()
            ));
        }
    }
    out
}

/// The section: each warning, or a line saying there is none.
pub(super) fn section(page: &mut Page, warnings: &[String]) {
    page.section("warnings", "Warnings");
    if warnings.is_empty() {
        page.text("summary.json records no warning for this run.");
    }
    for w in warnings {
        page.warning(w);
    }
}
