//! The applied loads in the words a designer reads: `check`'s line per
//! `[[load]]` and `[[force]]` (what, where, its resultant at its largest)
//! and the run's last line of them (kN, N·m).

use crate::model::loads::resultant::Components;
use crate::model::Model;

/// "F_y = 45.00 kN, T = 565.0 N·m": the components that are not zero next
/// to the largest force or moment (a straight edge's round-off is none).
pub fn words(comp: Components, v: &[f64]) -> String {
    let names: &[&str] = match comp {
        Components::Plane => &["F_x", "F_y", "M_z"],
        Components::Axisymmetric => &["F_r", "F_z"],
        Components::Twist => &["F_r", "F_z", "T"],
        Components::Solid => &["F_x", "F_y", "F_z", "M_x", "M_y", "M_z"],
    };
    let big = |moment: bool| {
        (0..v.len())
            .filter(|&c| comp.is_moment(c) == moment)
            .fold(0.0f64, |a, c| a.max(v[c].abs()))
    };
    let (force_max, moment_max) = (big(false), big(true));
    let mut parts = Vec::new();
    for (c, &x) in v.iter().enumerate() {
        let moment = comp.is_moment(c);
        let scale = if moment { moment_max } else { force_max };
        if x.abs() <= 1e-9 * scale || x == 0.0 {
            continue;
        }
        parts.push(match moment {
            true => format!("{} = {} N·m", names[c], crate::numbers::sig(x * 1e-3, 4)),
            false if x.abs() >= 1e3 => {
                format!("{} = {} kN", names[c], crate::numbers::sig(x * 1e-3, 4))
            }
            false => format!("{} = {} N", names[c], crate::numbers::sig(x, 4)),
        });
    }
    if parts.is_empty() {
        "no resultant (every component 0)".into()
    } else {
        parts.join(", ")
    }
}

/// `check`'s lines: each load, where it acts, and its resultant at the
/// largest value its history reaches.
pub fn check_text(model: &Model) -> String {
    let mut s = String::new();
    let half = half(model);
    for a in &model.applied {
        let (peak, when) = match a.history {
            Some(h) => (
                model.histories[h].peak(),
                "at its history's peak".to_string(),
            ),
            None if model.histories.is_empty() => (1.0, "at load factor 1".into()),
            None => (1.0, "at the end of the default ramp".into()),
        };
        let v: Vec<f64> = a.resultant.iter().map(|r| r * peak).collect();
        s += &format!(
            "  {}: {} on {}: {}{half} {when}\n",
            a.name,
            a.kind,
            a.selection,
            words(model.applied_components, &v)
        );
    }
    s
}

/// The run's last word on the loads: each one's resultant at the end.
pub fn end_text(model: &Model, t: f64) -> String {
    let mut s = String::new();
    let half = half(model);
    for (k, a) in model.applied.iter().enumerate() {
        let v = model.applied_at(k, t);
        s += &format!(
            "applied by {} ({}): {}{half}\n",
            a.name,
            a.selection,
            words(model.applied_components, &v)
        );
    }
    s
}

/// A symmetric half's loads are those of the half modelled (the curve's
/// total load is the whole punch's).
fn half(model: &Model) -> &'static str {
    if model.symmetric_half {
        " (on the modelled half)"
    } else {
        ""
    }
}
