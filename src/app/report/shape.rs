//! The types of the summary.json members the report reads (docs/output.md
//! gives them): a member of another type is refused, naming it, before
//! anything is drawn, so a forged or damaged summary cannot turn into a page
//! of blanks that reads like a run with nothing to report. A member that is
//! absent is allowed (an older run lacks the newer ones), and null where the
//! writer writes null.

use crate::error::{Error, Result};
use serde_json::Value;

/// What a member must be.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Type {
    /// A number, or null.
    Number,
    /// A string, or null.
    Text,
    /// true, false, or null.
    Flag,
    /// An array (of the members listed under `path[]`).
    List,
    /// An object, or null.
    Object,
    /// An array of numbers (null entries allowed: a value not finite).
    Numbers,
    /// An array of strings.
    Texts,
}

impl Type {
    fn admits(self, v: &Value) -> bool {
        match (self, v) {
            (Type::List | Type::Numbers | Type::Texts, Value::Array(a)) => match self {
                Type::Numbers => a.iter().all(|x| x.is_number() || x.is_null()),
                Type::Texts => a.iter().all(Value::is_string),
                _ => true,
            },
            (Type::List | Type::Numbers | Type::Texts, _) => false,
            (_, Value::Null) => true,
            (Type::Number, Value::Number(_)) => true,
            (Type::Text, Value::String(_)) => true,
            (Type::Flag, Value::Bool(_)) => true,
            (Type::Object, Value::Object(_)) => true,
            _ => false,
        }
    }

    fn words(self) -> &'static str {
        match self {
            Type::Number => "a number (or null)",
            Type::Text => "a string (or null)",
            Type::Flag => "true or false (or null)",
            Type::List => "an array",
            Type::Object => "an object (or null)",
            Type::Numbers => "an array of numbers",
            Type::Texts => "an array of strings",
        }
    }
}

use Type::*;

/// Every member the report reads, by its path (`[]`: each entry of an array).
const MEMBERS: &[(&str, Type)] = &[
    ("description", Text),
    ("plane", Text),
    ("complete", Flag),
    ("stopped_by", Text),
    ("increments", Number),
    ("wall_seconds", Number),
    ("interface_fallbacks", Number),
    ("estimate", Object),
    ("estimate.relative", Number),
    ("stabilization", Object),
    ("stabilization.steps_stabilized", Number),
    ("stabilization.energy_ratio", Number),
    ("warnings", Texts),
    ("final", Object),
    ("first_yield", Object),
    ("first_yield.body", Text),
    ("first_yield.element", Number),
    ("first_yield.x_mm", Number),
    ("first_yield.y_mm", Number),
    ("first_yield.depth_mm", Number),
    ("reactions", List),
    ("reactions[].name", Text),
    ("reactions[].source", Text),
    ("reactions[].components", Texts),
    ("reactions[].final", Numbers),
    ("reactions[].max", Numbers),
    ("reactions[].min", Numbers),
    ("peaks", List),
    ("peaks[].body", Text),
    ("peaks[].max_von_mises", Object),
    ("peaks[].max_peeq", Object),
    ("pretension", List),
    ("pretension[].name", Text),
    ("pretension[].body", Text),
    ("pretension[].cut", Text),
    ("pretension[].control", Text),
    ("pretension[].force_at_lock_n", Number),
    ("pretension[].force_n", Number),
    ("pretension[].force_min_n", Number),
    ("pretension[].force_max_n", Number),
    ("joints", List),
    ("joints[].interface", Text),
    ("contact", List),
    ("contact[].interface", Text),
    ("contact[].max_pressure", Object),
    ("contact[].max_pressure.value_mpa", Number),
    ("contact[].max_pressure.s_mm", Number),
    ("contact[].max_pressure.increment", Number),
    ("contact[].final_extent", Object),
    ("contact[].final_extent.from_s_mm", Number),
    ("contact[].final_extent.to_s_mm", Number),
    ("events", List),
    ("events[].event", Text),
    ("events[].interface", Text),
    ("events[].body", Text),
    ("events[].phase", Text),
    ("events[].quantity", Text),
    ("events[].meaning", Text),
    ("events[].load_factor", Number),
    ("events[].bracket", Numbers),
    ("events[].converged", Flag),
    ("events[].solve_failed", Flag),
    ("events[].total_load_kn", Number),
    ("events[].normal_force_n", Number),
    ("events[].tangential_force_n", Number),
    ("events[].torque_nm", Number),
    ("events[].speed_rpm", Number),
    ("events[].x_mm", Number),
    ("events[].y_mm", Number),
    ("events[].z_mm", Number),
    ("tables", List),
    ("tables[].interface", Text),
    ("tables[].key", Text),
    ("tables[].argument", Text),
    ("tables[].unit", Text),
    ("tables[].ratio", Number),
    ("tables[].largest", Number),
    ("tables[].beyond_limit", Flag),
    ("applied_loads", List),
    ("applied_loads[].name", Text),
    ("applied_loads[].kind", Text),
    ("applied_loads[].selection", Text),
    ("applied_loads[].components", Texts),
    ("applied_loads[].final", Numbers),
    ("applied_loads[].max", Numbers),
    ("applied_loads[].min", Numbers),
    ("ratings", List),
    ("ratings[].name", Text),
    ("ratings[].standard", Text),
    ("ratings[].subject", Text),
    ("ratings[].incomplete", Text),
    ("ratings[].inputs", List),
    ("ratings[].inputs[].name", Text),
    ("ratings[].inputs[].symbol", Text),
    ("ratings[].inputs[].unit", Text),
    ("ratings[].inputs[].from", Text),
    ("ratings[].checks", List),
    ("ratings[].checks[].quantity", Text),
    ("ratings[].checks[].symbol", Text),
    ("ratings[].checks[].unit", Text),
    ("ratings[].checks[].note", Text),
    ("ratings[].checks[].fe", Number),
    ("ratings[].checks[].handbook", Number),
    ("ratings[].checks[].difference", Number),
    ("ratings[].checks[].required", Number),
    ("ratings[].checks[].safety", Number),
    ("ratings[].checks[].required_safety", Number),
    ("ratings[].checks[].pass", Flag),
    ("singular", List),
    ("singular[].what", Text),
    ("singular[].body", Text),
    ("singular[].corner", Text),
    ("singular[].note", Text),
    ("singular[].estimate_share", Number),
    ("singular[].x_mm", Number),
    ("singular[].y_mm", Number),
    ("singular[].z_mm", Number),
];

/// Checks every member of `summary` the report reads; `place` names the file.
pub(super) fn check(summary: &Value, place: &str) -> Result<()> {
    for &(path, ty) in MEMBERS {
        for (at, v) in members(summary, path) {
            if !ty.admits(v) {
                return Err(Error::input(
                    place,
                    format!(
                        "{at} is {}, where the report reads {}: not the summary this program writes",
                        what(v),
                        ty.words()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The values at `path` in `v`, each with its concrete path
/// (`events[2].load_factor`); an absent member, or an entry of a list that
/// is no array, gives none (the list itself is checked on its own).
fn members<'a>(v: &'a Value, path: &str) -> Vec<(String, &'a Value)> {
    let mut found = vec![(String::new(), v)];
    for part in path.split('.') {
        let (key, each) = match part.strip_suffix("[]") {
            Some(k) => (k, true),
            None => (part, false),
        };
        let mut next = Vec::new();
        for (at, x) in found {
            let Some(y) = x.get(key) else { continue };
            let at = if at.is_empty() {
                key.to_string()
            } else {
                format!("{at}.{key}")
            };
            if each {
                if let Some(a) = y.as_array() {
                    next.extend(a.iter().enumerate().map(|(k, e)| (format!("{at}[{k}]"), e)));
                }
            } else {
                next.push((at, y));
            }
        }
        found = next;
    }
    found
}

/// A JSON value's kind, in words.
fn what(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn a_member_of_the_wrong_type_is_named_with_its_path() {
        let good = json!({"case": "c", "events": [{"event": "full_slip", "load_factor": 1.5, "bracket": [1.0, 1.5]}]});
        assert!(check(&good, "s.json").is_ok());
        let bad = json!({"case": "c", "events": [{"event": "full_slip"}, {"load_factor": "1.5"}]});
        let e = check(&bad, "s.json").unwrap_err().to_string();
        assert!(
            e.contains(
                "events[1].load_factor is a string, where the report reads a number (or null)"
            ),
            "{e}"
        );
        let bad = json!({"case": "c", "ratings": [{"checks": [{"pass": "yes"}]}]});
        let e = check(&bad, "s.json").unwrap_err().to_string();
        assert!(e.contains("ratings[0].checks[0].pass is a string"), "{e}");
        let bad = json!({"case": "c", "events": {"event": "x"}});
        let e = check(&bad, "s.json").unwrap_err().to_string();
        assert!(
            e.contains("events is an object, where the report reads an array"),
            "{e}"
        );
        let bad = json!({"case": "c", "applied_loads": [{"final": [1.0, "2"]}]});
        assert!(check(&bad, "s.json").is_err());
        // absent members and nulls where the writer writes null are allowed
        let old = json!({"case": "c", "first_yield": null, "events": [{"torque_nm": null}]});
        assert!(check(&old, "s.json").is_ok());
    }
}
