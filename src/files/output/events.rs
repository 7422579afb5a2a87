//! The summary's `events` ([`crate::solve::events`]) and the designer's
//! summary entries built from the increments' records: `reactions`,
//! `probes`, `peaks`, `contact`.

pub use super::json::{number, numbers};
use super::{peaks, probes, reactions};
use crate::model::Model;
use crate::solve::events::{Event, Kind};
use crate::solve::RunResult;
use serde_json::{json, Value};

/// One event as the summary states it: what, where, when (the load factor
/// and its bracket), and the loads there: the applied forces' resultant,
/// the named histories' values, the measures of curve.csv, the
/// interface's forces and every reaction group.
pub(crate) fn event_json(model: &Model, e: &Event) -> Value {
    let plan = &model.plan;
    let t = e.load_factor;
    let mut f = vec![0.0; model.mesh.num_dofs()];
    model.external_force(t, &mut f);
    let k = model.node_dofs().per_node();
    // F_x, F_y (and F_z in 3D)
    let applied: Vec<f64> = (0..model.mesh.dim())
        .map(|c| f.iter().skip(c).step_by(k).sum::<f64>())
        .collect();
    let values = model.history_values(t);
    let histories: Vec<Value> = plan
        .history_names
        .iter()
        .zip(&values)
        .map(|(n, v)| json!({"name": n, "value": v}))
        .collect();
    let reactions = reactions::named_values(
        &plan.reactions,
        plan.part(&e.record, &plan.layout.reactions),
    );
    let (lo, hi) = (e.before.min(e.after), e.before.max(e.after));
    // the interface's force and pressure: none without an interface
    let contact = |v: f64| {
        if model.interfaces.is_empty() {
            Value::Null
        } else {
            number(v)
        }
    };
    let mut o = json!({
        "event": e.kind.name(),
        "interface": e.interface.map(|i| model.interfaces[i].name.clone()),
        "load_factor": t,
        "bracket": [lo, hi],
        "width": hi - lo,
        "tolerance": plan.event_tolerance,
        "method": e.method.name(),
        "converged": e.converged,
        "solve_failed": e.solve_failed,
        "increment": e.increment,
        "x_mm": number(e.place[0]),
        "y_mm": number(e.place[1]),
        "s_mm": number(e.place[2]),
        "total_load_kn": contact(e.values[0]),
        "mean_pressure_mpa": contact(e.values[1]),
        "normal_force_n": number(e.values[2]),
        "tangential_force_n": number(e.values[3]),
        "torque_nm": torque(model, e).map_or(Value::Null, number),
        "quantity": match e.kind {
            Kind::HoldingPlateau(m) => json!(m.quantity()),
            _ => Value::Null,
        },
        "applied_force_n": numbers(&applied),
        "speed_rpm": model.rpm(t).map_or(Value::Null, number),
        "histories": histories,
        "reactions": reactions,
        "phase": phase(model, t),
        "meaning": meaning(model, e),
    });
    // in 3D the third place is z: a first yield has no arc length, nor
    // has a pair of an interface on faces
    if model.mesh.dim() == 3 {
        o["z_mm"] = number(e.place[2]);
        o["s_mm"] = Value::Null;
    }
    if e.kind == Kind::FirstYield {
        let el = e.place[3];
        o["element"] = if el.is_finite() {
            json!(el as usize)
        } else {
            Value::Null
        };
        o["body"] = if el.is_finite() && (el as usize) < model.mesh.elements.len() {
            json!(model.mesh.bodies[model.mesh.elements[el as usize].body])
        } else {
            Value::Null
        };
    } else {
        o["element"] = Value::Null;
        // the body that can no longer hold its torque
        o["body"] = (e.body())
            .and_then(|b| model.mesh.bodies.get(b))
            .map_or(Value::Null, |b| json!(b));
    }
    o
}

/// The interface's torque at the event, N·m: an interface event of a model
/// with twist.
fn torque(model: &Model, e: &Event) -> Option<f64> {
    (e.interface.is_some() && model.node_dofs().twist()).then(|| e.values[4] * 1e-3)
}

/// `preload` while a pretension section is still being tightened (before
/// its lock), `service` after every lock; null without sections.
fn phase(model: &Model, t: f64) -> Value {
    let locks = model
        .sections
        .iter()
        .map(|s| s.lock_after)
        .filter(|l| l.is_finite());
    match locks.fold(None, |a: Option<f64>, l| Some(a.map_or(l, |a| a.max(l)))) {
        Some(last) if t <= last => json!("preload"),
        Some(_) => json!("service"),
        None => Value::Null,
    }
}

/// What the event says about the joint or the part, in a sentence.
pub(crate) fn meaning(model: &Model, e: &Event) -> String {
    let preload = phase(model, e.load_factor) == json!("preload");
    let mut m = match e.kind {
        Kind::FirstYield => match super::singular::first_yield_point(model, e) {
            Some(p) => format!("the first Gauss point reached the yield stress at a singular point of the mesh, {} (summary.json singular): the elastic stress there is unbounded and this load falls as the mesh is refined; read a nominal stress there, or round the corner", p.corner),
            None => "the first Gauss point reached the yield stress; at a sharp corner or a contact's edge the stress is singular and this load falls as the mesh is refined: read a nominal stress there, or round the corner".to_string(),
        },
        Kind::FirstOpening if preload => "part of the interface opened while the preload was brought in (the clamped parts dish under the bolt): a state of assembly, not a failure of the joint".into(),
        Kind::FirstOpening => "part of the interface first opened: its contact is no longer whole, though it still clamps".into(),
        Kind::FullSlip if preload => "the whole interface slid while the preload was brought in (a head's or a nut's bearing face slides radially as the bolt stretches and the clamped parts compress and dish under it: a shear self-equilibrated about the bolt, F_T near zero): a state of assembly, not a loss of the joint's grip, which a service load's slip rates".into(),
        Kind::FullSlip => "the whole interface first in macro-slip: its first gross slip, not the load it holds; where friction was locked in by an earlier step (a fit pressed, then turned) the joint takes more after it, up to its holding plateau".into(),
        Kind::HoldingPlateau(m) => format!("the {} the joint holds as it slides on as a whole (its plateau, within 0.1 %): its capacity in this motion, a rating's transmissible {}", m.quantity(), if m == crate::solve::events::Motion::Turning { "torque" } else { "force" }),
        Kind::FullSeparation => "the interface carries no normal force any more: the joint has separated".into(),
        Kind::FirstContact if model.temperatures.is_empty() => "the interface, open from the start, first came into contact: its gap closed".into(),
        Kind::FirstContact => "the interface, open from the start, first came into contact: its gap closed (a hub heated for assembly grips its shaft here as it cools: the temperatures at this pseudo-time are its gripping temperatures)".into(),
        Kind::TorqueLimit => "the torque on the body reached what the friction of its interfaces holds about the axis, Σ μ p r dA, and nothing else holds it: past this load the fit slips through and a prescribed torque has no equilibrium, so the run ends here; the forces are those of the last state that held, the load factor the first where none did".into(),
    };
    if !e.converged {
        m += "; the search did not narrow the bracket to the tolerance: the event lies within the bracket, no closer";
    }
    m
}

/// An interface event as one line of the run's end: what, where and when.
pub fn line(model: &Model, e: &Event) -> String {
    let (lo, hi) = (e.before.min(e.after), e.before.max(e.after));
    let iface = e.interface.map_or(String::new(), |i| {
        format!(" of {}", model.interfaces[i].name)
    });
    let during = if phase(model, e.load_factor) == json!("preload") {
        " during the preload"
    } else {
        ""
    };
    let what = match e.kind {
        Kind::HoldingPlateau(m) => format!("holding plateau ({})", m.quantity()),
        k => k.name().replace('_', " "),
    };
    let torque = torque(model, e).map_or(String::new(), |t| format!(", T {t:.4e} N·m"));
    let speed = (model.rpm(e.load_factor)).map_or(String::new(), |n| format!(" at {n:.6e} rpm"));
    if e.kind == Kind::TorqueLimit {
        let body = (e.body())
            .and_then(|b| model.mesh.bodies.get(b))
            .map_or("", String::as_str);
        return format!(
            "torque limit of body {body} (held by {}): λ = {:.6}{speed} (bracket {:.6} … {:.6}{}); at the last state that held: ΣF_N {:.4e} N{torque}",
            iface.trim_start_matches(" of "),
            e.load_factor,
            lo,
            hi,
            if e.converged { "" } else { ", not converged" },
            e.values[2]
        );
    }
    format!(
        "{what}{iface}{during}: λ = {:.6}{speed} (bracket {:.6} … {:.6}{}), F_N {:.4e} N, F_T {:.4e} N{torque}",
        e.load_factor,
        lo,
        hi,
        if e.converged { "" } else { ", not converged" },
        e.values[2],
        e.values[3]
    )
}

/// The designer's summary entries: `reactions`, `probes`, `peaks`,
/// `contact`, `events` (from every increment's record).
pub fn summary(model: &Model, r: &RunResult, s: &mut Value) {
    let plan = &model.plan;
    let rows: Vec<(usize, &[f64])> = r
        .increments
        .iter()
        .enumerate()
        .map(|(k, i)| (k, i.record.as_slice()))
        .collect();
    let part = |range: &std::ops::Range<usize>| -> Vec<&[f64]> {
        rows.iter().map(|(_, v)| &v[range.clone()]).collect()
    };
    s["reactions"] = reactions::summary(&plan.reactions, &part(&plan.layout.reactions));
    s["probes"] = probes::summary(&plan.probes, &model.mesh, &part(&plan.layout.probes));
    let (bodies, contact) = peaks::summary(
        model,
        r,
        &rows,
        plan.layout.bodies.start,
        plan.layout.interfaces.start,
    );
    s["peaks"] = bodies;
    s["contact"] = contact;
    s["events"] = r.events.iter().map(|e| event_json(model, e)).collect();
}
