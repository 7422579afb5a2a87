//! Numbers in summary.json: null where not finite.

use serde_json::{json, Value};

/// A JSON number, null when not finite (no such value).
pub fn number(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// JSON numbers, null where not finite.
pub fn numbers(v: &[f64]) -> Value {
    v.iter().map(|&x| number(x)).collect()
}
