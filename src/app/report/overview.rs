//! Section 1: what was computed: the case in words, the model and the run,
//! the program's version and the case's fingerprint.

use super::format::{figure, with_unit};
use super::html::{esc, Cell, Page};
use super::{num, text};
use serde_json::Value;

/// The page's title: the case's name.
pub(super) fn title(s: &Value) -> String {
    format!(
        "Calculation report: {}",
        text(s, "case").unwrap_or_default()
    )
}

/// The lines under the title: the case in words, and how many warnings
/// section 6 holds.
pub(super) fn lead(s: &Value, warnings: usize) -> String {
    let words = text(s, "description").unwrap_or_else(|| text(s, "case").unwrap_or_default());
    let mut out = format!("<p><strong>{}</strong></p>", esc(&words));
    if warnings > 0 {
        out += &format!(
            "<p class=\"warn\">{warnings} warning{} qualify these results: see <a href=\"#warnings\">Warnings</a>.</p>",
            if warnings == 1 { "" } else { "s" }
        );
    }
    out
}

/// The section: a table of the model and the run.
pub(super) fn section(page: &mut Page, s: &Value) {
    page.section("run", "The model and the run");
    let said = |key: &str| text(s, key).unwrap_or_else(|| "not recorded".into());
    let int = |key: &str| num(s, key).map_or("not recorded".to_string(), figure_int);
    let estimate = s.get("estimate").and_then(|e| num(e, "relative"));
    let rows: Vec<(&str, String)> = vec![
        ("case", text(s, "case").unwrap_or_default()),
        ("model", plane(s)),
        ("elements", int("elements")),
        ("degrees of freedom", int("dofs")),
        ("interface node pairs", int("interface_pairs")),
        ("method", said("method")),
        ("backend", said("backend")),
        ("ranks", int("ranks")),
        ("increments", int("increments")),
        ("cutbacks", int("cutbacks")),
        (
            "wall time",
            num(s, "wall_seconds").map_or("not recorded".into(), |t| with_unit(t, "s")),
        ),
        ("run", state(s)),
        (
            "estimated error (energy norm, relative)",
            estimate.map_or("not recorded".into(), |r| {
                format!("{} %", figure(100.0 * r))
            }),
        ),
        ("program version", said("asperity_version")),
        ("case fingerprint", said("case_fingerprint")),
    ];
    let rows = rows
        .into_iter()
        .map(|(k, v)| vec![Cell::from(k), Cell::from(v)])
        .collect();
    page.table(
        "The model and the run (summary.json)",
        &["item", "value"],
        rows,
    );
}

/// The model in words: plane stress, plane strain, axisymmetric or 3D.
fn plane(s: &Value) -> String {
    match text(s, "plane").as_deref() {
        Some("stress") => "plane stress".to_string(),
        Some("strain") => "plane strain".to_string(),
        Some("axisymmetric") => {
            "axisymmetric (x = r, y = z; forces of the full revolution)".to_string()
        }
        Some("3d") => "3D".to_string(),
        Some(other) => other.to_string(),
        None => "not recorded".to_string(),
    }
}

/// Complete, or stopped early and by what.
fn state(s: &Value) -> String {
    match (
        s.get("complete").and_then(Value::as_bool),
        text(s, "stopped_by"),
    ) {
        (Some(false), by) => format!(
            "stopped early ({})",
            by.unwrap_or_else(|| "reason not recorded".into())
        ),
        (Some(true), _) => "complete".to_string(),
        (None, _) => "not recorded".to_string(),
    }
}

/// A count as a whole number.
fn figure_int(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{v:.0}")
    } else {
        figure(v)
    }
}
