//! Section 5, second part: the run's own results beside the ratings: the
//! final state and first yield, the reactions, the bodies' peaks, the
//! pretension sections and the events located (with their meaning).

use super::format::{component, figure, kn, with_unit};
use super::html::{Cell, Page};
use super::{num, text};
use serde_json::Value;

/// `(x, y)` or `(x, y, z)` of an entry's `x_mm`, `y_mm`, `z_mm`.
pub(super) fn place(v: &Value) -> String {
    let coords: Vec<String> = ["x_mm", "y_mm", "z_mm"]
        .iter()
        .filter_map(|k| num(v, k))
        .map(figure)
        .collect();
    if coords.is_empty() {
        "—".into()
    } else {
        format!("({})", coords.join(", "))
    }
}

/// A number of `v` with its unit, `—` where absent or null.
fn value(v: &Value, key: &str, unit: &str) -> Cell {
    Cell::n(num(v, key).map_or("—".into(), |x| with_unit(x, unit)))
}

/// The last increment and the first yield, side by side.
pub(super) fn state(page: &mut Page, s: &Value) {
    page.heading("Final state and first yield");
    let end = s.get("final").filter(|v| v.is_object());
    let fy = s.get("first_yield").filter(|v| v.is_object());
    let row = |label: &str, key: &str, unit: &str| {
        let at = |v: Option<&Value>| v.map_or(Cell::n("—".into()), |v| value(v, key, unit));
        vec![Cell::from(label), at(end), at(fy)]
    };
    let mut rows = vec![
        row("load factor (pseudo-time)", "load_factor", ""),
        row(
            "total load (first interface's normal force)",
            "total_load_kn",
            "kN",
        ),
        row("mean contact pressure", "mean_pressure_mpa", "MPa"),
        row("probe displacement u_y", "center_displacement_mm", "mm"),
        row("largest PEEQ", "max_peeq", ""),
    ];
    if let Some(f) = fy {
        rows.push(vec![
            Cell::from("first yield: body, element"),
            Cell::n("".into()),
            Cell::from(format!(
                "{}, element {}",
                text(f, "body").unwrap_or_default(),
                num(f, "element").map_or("—".into(), figure)
            )),
        ]);
        let at = match num(f, "y_mm") {
            Some(_) => place(f),
            None => format!(
                "x = {}, {} below the probe node",
                num(f, "x_mm").map_or("—".into(), figure),
                num(f, "depth_mm").map_or("—".into(), figure)
            ),
        };
        rows.push(vec![
            Cell::from("first yield: Gauss point (mm)"),
            Cell::n("".into()),
            Cell::n(at),
        ]);
    }
    page.table(
        "The last increment and the first yield (summary.json final, first_yield)",
        &["", "final", "first yield"],
        rows,
    );
    if fy.is_none() {
        page.text("No Gauss point yields in this run (first_yield is null or absent).");
    }
}

/// Each reaction group's components: final, largest, smallest.
pub(super) fn reactions(page: &mut Page, s: &Value) {
    page.heading("Reactions");
    let Some(list) = s
        .get("reactions")
        .and_then(Value::as_array)
        .filter(|l| !l.is_empty())
    else {
        page.absent("summary.json lists no reactions.");
        return;
    };
    let mut rows = Vec::new();
    for g in list {
        let comps = g
            .get("components")
            .and_then(Value::as_array)
            .cloned()
            .unwrap_or_default();
        let at = |key: &str, k: usize| {
            g.get(key)
                .and_then(|a| a.get(k))
                .and_then(Value::as_f64)
                .unwrap_or(f64::NAN)
        };
        for (k, c) in comps.iter().enumerate() {
            let c = c.as_str().unwrap_or("");
            let (symbol, last) = component(c, at("final", k));
            rows.push(vec![
                Cell::from(text(g, "name").unwrap_or_default()),
                Cell::from(text(g, "source").unwrap_or_default()),
                Cell::from(symbol),
                Cell::n(last),
                Cell::n(component(c, at("max", k)).1),
                Cell::n(component(c, at("min", k)).1),
            ]);
        }
    }
    let head = [
        "support",
        "entry",
        "component",
        "final",
        "largest",
        "smallest",
    ];
    page.table(
        "Reactions: the force each support exerts on the body (summary.json reactions)",
        &head,
        rows,
    );
}

/// Each body's largest von Mises stress and PEEQ, where and when.
pub(super) fn peaks(page: &mut Page, s: &Value) {
    page.heading("Peaks per body");
    let Some(list) = s
        .get("peaks")
        .and_then(Value::as_array)
        .filter(|l| !l.is_empty())
    else {
        page.absent("summary.json lists no peaks.");
        return;
    };
    let mut rows = Vec::new();
    for b in list {
        let body = text(b, "body").unwrap_or_default();
        for (key, label, field, unit) in [
            (
                "max_von_mises",
                "largest von Mises stress",
                "value_mpa",
                "MPa",
            ),
            ("max_peeq", "largest PEEQ", "value", ""),
        ] {
            let Some(p) = b.get(key).filter(|v| v.is_object()) else {
                rows.push(vec![
                    Cell::from(body.clone()),
                    Cell::from(label),
                    Cell::n("none".into()),
                    Cell::n("—".into()),
                    Cell::n("—".into()),
                ]);
                continue;
            };
            rows.push(vec![
                Cell::from(body.clone()),
                Cell::from(label),
                value(p, field, unit),
                Cell::n(place(p)),
                Cell::n(format!(
                    "{} (t = {})",
                    num(p, "increment").map_or("—".into(), figure),
                    num(p, "time").map_or("—".into(), figure)
                )),
            ]);
        }
    }
    let head = [
        "body",
        "quantity",
        "value",
        "Gauss point (mm)",
        "increment (time)",
    ];
    page.table(
        "Peaks over the run at the Gauss points (summary.json peaks)",
        &head,
        rows,
    );
}

/// Each pretension section: control, force at the lock, at the end, range.
pub(super) fn pretension(page: &mut Page, s: &Value) {
    let Some(list) = s
        .get("pretension")
        .and_then(Value::as_array)
        .filter(|l| !l.is_empty())
    else {
        return;
    };
    page.heading("Pretension sections");
    let force = |p: &Value, k: &str| Cell::n(num(p, k).map_or("—".into(), kn));
    let rows = list
        .iter()
        .map(|p| {
            vec![
                Cell::from(text(p, "name").unwrap_or_default()),
                Cell::from(format!(
                    "{}, {}",
                    text(p, "body").unwrap_or_default(),
                    text(p, "cut").unwrap_or_default()
                )),
                Cell::from(text(p, "control").unwrap_or_default()),
                force(p, "force_at_lock_n"),
                force(p, "force_n"),
                force(p, "force_min_n"),
                force(p, "force_max_n"),
            ]
        })
        .collect();
    let head = [
        "section",
        "body, cut",
        "control",
        "force at the lock",
        "final force",
        "smallest",
        "largest",
    ];
    page.table(
        "Pretension sections (summary.json pretension; tension positive)",
        &head,
        rows,
    );
}

/// The events located, in order, with what each means.
pub(super) fn events(page: &mut Page, s: &Value) {
    page.heading("Events");
    let Some(list) = s
        .get("events")
        .and_then(Value::as_array)
        .filter(|l| !l.is_empty())
    else {
        page.absent("No event was located (summary.json events is empty or absent).");
        return;
    };
    // a model with twist reports each interface event's torque
    let twist = list.iter().any(|e| num(e, "torque_nm").is_some());
    // a spinning model reports each event's speed
    let spinning = list.iter().any(|e| num(e, "speed_rpm").is_some());
    let rows = list
        .iter()
        .map(|e| {
            let at = text(e, "interface")
                .or_else(|| text(e, "body"))
                .unwrap_or_default();
            let phase = text(e, "phase")
                .map(|p| format!(" ({p})"))
                .unwrap_or_default();
            let quantity = text(e, "quantity")
                .map(|q| format!(" of {q}"))
                .unwrap_or_default();
            let mut row = vec![
                Cell::from(format!(
                    "{}{quantity}{phase}",
                    text(e, "event").unwrap_or_default()
                )),
                Cell::from(at),
                value(e, "load_factor", ""),
                value(e, "total_load_kn", "kN"),
                Cell::n(num(e, "normal_force_n").map_or("—".into(), kn)),
                Cell::n(num(e, "tangential_force_n").map_or("—".into(), kn)),
            ];
            if twist {
                row.push(value(e, "torque_nm", "N·m"));
            }
            if spinning {
                row.push(value(e, "speed_rpm", "rpm"));
            }
            row.push(Cell::n(place(e)));
            row.push(Cell::from(text(e, "meaning").unwrap_or_else(|| "—".into())));
            row
        })
        .collect();
    let mut head = vec![
        "event",
        "interface or body",
        "load factor",
        "total load",
        "F_N",
        "F_T",
    ];
    if twist {
        head.push("T");
    }
    if spinning {
        head.push("n");
    }
    head.extend(["where (mm)", "meaning"]);
    page.table("Events located (summary.json events)", &head, rows);
}
