//! DIN 7190-1:2017 for an interference fit of an axisymmetric model: the
//! standard's side from [`handbook::din7190`](crate::verdict::handbook::din7190) with the geometry read off the
//! mesh, beside what the run measured on the fit's interface.
//!
//! The FE's numbers: the fit pressure as the interface's normal force over
//! π D_F l_F (mean) and its largest pair pressure (peak, at the joint's
//! edges); the torque and axial force the fit held as the largest the
//! interface carried while it slid as a whole, turned or pushed by the
//! direction it moved (its holding plateau, when the run turns or pushes
//! the fit to gross slip), else the friction capacity p π D_F l_F ν of
//! the FE's mean pressure; each part's largest von Mises stress against its
//! yield stress.
//!
//! In service (a run with temperatures or a speed) the handbook's pressure,
//! torque, axial force and slip safety are the fit's at the run's end, as
//! the FE's are (`fit/service.rs`); its yield checks rate the larger of its
//! pressures at assembly and at the run's end.

use super::handbook::din7190::{Fit, SMOOTHING_2017};
use super::rating::{joint_series, max_pressure, max_von_mises, radii, Check, Input, Rating};
use super::Run;
use crate::error::{clip, Error, Result};
use crate::input::case::rating::FitSpec;
use crate::measure::gross_slip::Motion;
use crate::model::interface::InterfaceModel;
use crate::model::Model;
use std::f64::consts::PI;

mod service;

/// The fit as the mesh and the case give it: which interface, which body
/// is the hub, and the standard's inputs.
pub struct Posed {
    pub interface: usize,
    pub hub: usize,
    pub shaft: usize,
    pub fit: Fit,
    pub inputs: Vec<Input>,
}

/// Reads the fit off the model; refuses what DIN 7190 cannot rate.
pub fn pose(model: &Model, spec: &FitSpec, at: &str) -> Result<Posed> {
    let fail = |m: String| Error::input(format!("{at} interface"), m);
    if !model.section.axisymmetric || model.mesh.dim() != 2 {
        return Err(Error::input(at, "DIN 7190 rates a cylindrical fit: give it an axisymmetric model (plane = \"axisymmetric\")"));
    }
    let i = model
        .interfaces
        .iter()
        .position(|m| m.name == spec.interface)
        .ok_or_else(|| fail(format!("names no interface \"{}\"", clip(&spec.interface))))?;
    let im = &model.interfaces[i];
    if im.gap >= 0.0 {
        return Err(fail(format!(
            "\"{}\" has no interference (gap = {} mm): DIN 7190 rates a fit whose gap is negative",
            clip(&spec.interface),
            crate::numbers::num(im.gap)
        )));
    }
    let (r_f, l_f) = joint_extent(im);
    let (hub, shaft) = hub_and_shaft(model, im, r_f);
    let (lo, hi) = radii(model, hub);
    let (bore, _) = radii(model, shaft);
    if (hi - r_f).abs() < 1e-9 * r_f || (lo - r_f).abs() > 1e-6 * r_f.max(1.0) || l_f <= 0.0 {
        return Err(fail(format!(
            "\"{}\" is not a cylinder between a shaft and a hub round it (radius {} mm, length {} mm)",
            clip(&spec.interface),
            crate::numbers::num(r_f),
            crate::numbers::num(l_f)
        )));
    }
    let adhesion = match (spec.adhesion, &im.tangential) {
        (Some(v), _) => (v, "case"),
        (None, Some(t)) => (t.mu, "interface"),
        (None, None) => return Err(Error::input(format!("{at} adhesion"), "is needed: the interface has no friction (`[interface.NAME.tangential] mu`) to take it from")),
    };
    let (mh, ms) = (&model.materials[hub], &model.materials[shaft]);
    let d_ii = if bore < 1e-6 * r_f { 0.0 } else { 2.0 * bore };
    let fit = Fit {
        d_f: 2.0 * r_f,
        l_f,
        d_aa: 2.0 * hi,
        d_ii,
        e_hub: mh.young,
        poisson_hub: mh.poisson,
        e_shaft: ms.young,
        poisson_shaft: ms.poisson,
        interference: -2.0 * im.gap,
        rz_hub: spec.rz_hub.unwrap_or(0.0),
        rz_shaft: spec.rz_shaft.unwrap_or(0.0),
        smoothing: spec.smoothing.unwrap_or(SMOOTHING_2017),
        yield_hub: mh.yield_stress,
        yield_shaft: ms.yield_stress,
        adhesion_torque: adhesion.0,
        adhesion_axial: adhesion.0,
    };
    let mut inputs = inputs(&fit, spec, adhesion.1);
    inputs.extend(service::posed_inputs(model, &fit, (hub, shaft)));
    Ok(Posed {
        interface: i,
        hub,
        shaft,
        fit,
        inputs,
    })
}

/// The interface's radius (area mean of its pairs' x) and its axial length.
fn joint_extent(im: &InterfaceModel) -> (f64, f64) {
    let area: f64 = im.pairs.iter().map(|p| p.area).sum();
    let r = im.pairs.iter().map(|p| p.area * p.x[0]).sum::<f64>() / area.max(f64::MIN_POSITIVE);
    let (lo, hi) = im
        .pairs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.x[1]), b.max(p.x[1]))
        });
    (r, hi - lo)
}

/// (hub, shaft): the body of the two that reaches beyond the interface.
fn hub_and_shaft(model: &Model, im: &InterfaceModel, r_f: f64) -> (usize, usize) {
    let (_, hi_a) = radii(model, im.body_a);
    if hi_a > r_f * (1.0 + 1e-9) {
        (im.body_a, im.body_b)
    } else {
        (im.body_b, im.body_a)
    }
}

fn inputs(fit: &Fit, spec: &FitSpec, adhesion_from: &'static str) -> Vec<Input> {
    let from = |given: bool| if given { "case" } else { "default" };
    let mut list = vec![
        Input::new("joint diameter", "D_F", fit.d_f, "mm", "mesh"),
        Input::new("joint length", "l_F", fit.l_f, "mm", "mesh"),
        Input::new("hub outer diameter", "D_aA", fit.d_aa, "mm", "mesh"),
        Input::new("shaft bore", "D_iI", fit.d_ii, "mm", "mesh"),
        Input::new(
            "interference (diametral)",
            "U",
            fit.interference * 1e3,
            "µm",
            "interface",
        ),
        Input::new(
            "hub bore roughness",
            "Rz_A",
            fit.rz_hub,
            "µm",
            from(spec.rz_hub.is_some()),
        ),
        Input::new(
            "shaft roughness",
            "Rz_I",
            fit.rz_shaft,
            "µm",
            from(spec.rz_shaft.is_some()),
        ),
        Input::new(
            "smoothing factor",
            "k",
            fit.smoothing,
            "",
            from(spec.smoothing.is_some()),
        ),
        Input::new(
            "adhesion coefficient",
            "ν_r",
            fit.adhesion_torque,
            "",
            adhesion_from,
        ),
        Input::new(
            "hub yield stress",
            "R_eL,A",
            fit.yield_hub,
            "MPa",
            "material",
        ),
        Input::new(
            "shaft yield stress",
            "R_eL,I",
            fit.yield_shaft,
            "MPa",
            "material",
        ),
        Input::new(
            "application factor",
            "K_A",
            spec.application_factor.unwrap_or(1.0),
            "",
            from(spec.application_factor.is_some()),
        ),
        Input::new(
            "slip safety required",
            "S_r",
            spec.slip_safety.unwrap_or(1.5),
            "",
            from(spec.slip_safety.is_some()),
        ),
        Input::new(
            "yield safety required",
            "S_F",
            spec.yield_safety.unwrap_or(1.1),
            "",
            from(spec.yield_safety.is_some()),
        ),
    ];
    // the demands the case gives (N·m and N, before K_A)
    for (name, symbol, v, unit) in [
        ("torque to transmit", "M_t,erf", spec.torque, "N·m"),
        ("axial force to transmit", "F_ax,erf", spec.axial_force, "N"),
    ] {
        if let Some(value) = v {
            list.push(Input {
                name,
                symbol,
                value,
                unit,
                from: "case",
            });
        }
    }
    list
}

/// The rating of a finished run.
pub fn rate(model: &Model, r: &Run, spec: &FitSpec, posed: Posed) -> Rating {
    let Posed {
        interface: i,
        hub,
        shaft,
        fit,
        inputs,
    } = posed;
    let t = r.increments.last().map_or(0.0, |inc| inc.load_factor);
    let end = service::end(model, t, &fit, (hub, shaft));
    let service = end.service();
    let p_assembly = fit.pressure();
    // the handbook's pressure at the run's end, and the largest it knows
    let (p_hb, p_top) = match service {
        Some(s) => {
            let p = s.pressure();
            (p, p_assembly.zip(p).map(|(a, b)| a.max(b)))
        }
        None => (p_assembly, p_assembly),
    };
    let suffix = match service {
        Some(_) => " (the handbook's pressure at the run's end)",
        None => "",
    };
    let mut checks = slip_checks(model, r, spec, (i, &fit), (p_hb, p_top), suffix);
    if let Some(s) = service {
        checks.insert(0, left_in_service(s));
    }
    if fit.effective_interference() <= 0.0 {
        let mut c = Check::both(
            "effective interference",
            "U_w",
            "µm",
            None,
            Some(fit.effective_interference() * 1e3),
        );
        c.pass = Some(false);
        checks.insert(0, c.note("U − k (Rz_A + Rz_I): by the standard's smoothing the fit is loose and holds nothing"));
    }
    let state = match service {
        None => "",
        Some(_) if p_top == p_assembly => "; handbook at assembly (room temperature, standing still), where its pressure is the larger",
        Some(_) => "; handbook at the run's end, where the service raises its pressure above the assembly's (the spinning parts' own stresses left out)",
    };
    let yield_s = spec.yield_safety.unwrap_or(1.1);
    checks.extend(yield_checks(
        model,
        r,
        &fit,
        (hub, shaft),
        p_top,
        yield_s,
        state,
    ));
    let names = &model.mesh.bodies;
    let mut inputs = inputs;
    inputs.extend(joining(model, &fit, hub));
    inputs.extend(service.map(|s| s.inputs()).unwrap_or_default());
    Rating {
        standard: "DIN 7190-1:2017",
        name: spec.name.clone().unwrap_or_else(|| spec.interface.clone()),
        subject: format!(
            "interference fit \"{}\": the shaft is body \"{}\", the hub body \"{}\"{}",
            spec.interface,
            names[shaft],
            names[hub],
            in_service(&end)
        ),
        inputs,
        checks,
        incomplete: None,
    }
}

/// The pressure, the transmissible torque and axial force, and the slip
/// safety: the FE's at the run's end (or its holding plateau) beside the
/// handbook's at `p_hb`; the peak beside the handbook's largest, `p_top`.
/// `suffix` ends the notes of a run in service.
fn slip_checks(
    model: &Model,
    r: &Run,
    spec: &FitSpec,
    (i, fit): (usize, &Fit),
    (p_hb, p_top): (Option<f64>, Option<f64>),
    suffix: &str,
) -> Vec<Check> {
    let area = PI * fit.d_f * fit.l_f;
    let last = r.increments.last().and_then(|inc| inc.joints.get(i));
    let p_fe = last.map(|j| j.normal_force / area);
    let k_a = spec.application_factor.unwrap_or(1.0);
    let slip = spec.slip_safety.unwrap_or(1.5);
    let torque_demand = spec.torque.map(|t| k_a * t);
    let axial_demand = spec.axial_force.map(|f| k_a * f);
    let held_torque = held(model, r, i, Motion::Turning);
    let held_axial = held(model, r, i, Motion::Pushing);
    let (turned, pushed) = (held_torque.is_some(), held_axial.is_some());
    let fe_torque = held_torque.or_else(|| p_fe.and_then(|p| fit.transmissible_torque(p)));
    let fe_axial = held_axial.or_else(|| p_fe.and_then(|p| fit.transmissible_axial_force(p)));
    let in_service = !suffix.is_empty();
    let mut checks = vec![
        Check::both("fit pressure, mean", "p", "MPa", p_fe, p_hb)
            .note(if in_service { "FE: the interface's normal force / (π D_F l_F) at the run's end; handbook: plane-stress Lamé at the run's end, (U_w − ΔU_ϑ − ΔU_ω)/(D_F K), U_w with the smoothing k (Rz_A + Rz_I)" } else { "FE: the interface's normal force / (π D_F l_F) at the end; handbook: plane-stress Lamé with the smoothing k (Rz_A + Rz_I)" }),
        Check::both("fit pressure, peak", "p_max", "MPa", max_pressure(model, r, i), p_top)
            .note(if in_service { "FE: the largest pair pressure over the run, at the joint's edges where the hub ends; the handbook's is uniform, the larger of its pressures at assembly and at the run's end" } else { "FE: the largest pair pressure over the run, at the joint's edges where the hub ends; the handbook's is uniform" }),
        Check::both("transmissible torque", "M_t", "N·m", fe_torque.map(|t| t * 1e-3), p_hb.and_then(|p| fit.transmissible_torque(p)).map(|t| t * 1e-3))
            .against(torque_demand, slip)
            .note(format!("{}{suffix}", if turned { "FE: the largest torque the fit held (its plateau as it slips); handbook: p π D_F² l_F ν/2" } else { "FE: p π D_F² l_F ν/2 with the FE's mean pressure (the run does not turn the fit); handbook: with Lamé's" })),
        Check::both("transmissible axial force", "F_ax", "N", fe_axial, p_hb.and_then(|p| fit.transmissible_axial_force(p)))
            .against(axial_demand, slip)
            .note(format!("{}{suffix}", if pushed { "FE: the largest axial force the fit held as it slipped; handbook: p π D_F l_F ν" } else { "FE: p π D_F l_F ν with the FE's mean pressure; handbook: with Lamé's" })),
    ];
    if torque_demand.is_some() || axial_demand.is_some() {
        let (t, f) = (
            spec.torque.unwrap_or(0.0) * 1e3,
            spec.axial_force.unwrap_or(0.0),
        );
        let mut c = Check::both(
            "combined slip safety",
            "S_r",
            "",
            p_fe.and_then(|p| fit.slip_safety(p, t, f, k_a)),
            p_hb.and_then(|p| fit.slip_safety(p, t, f, k_a)),
        );
        c.required_safety = Some(slip);
        c.safety = c.fe.or(c.handbook);
        c.pass = c.safety.map(|s| s >= slip);
        checks.push(c.note(format!(
            "torque and axial force together: S_r = p π D_F l_F ν / (K_A √(F_ax² + (2 M_t/D_F)²)){suffix}"
        )));
    }
    checks
}

/// The interference the service leaves, U_w − ΔU_ϑ − ΔU_ω (handbook only):
/// failed where the service opens a fit that holds at rest.
fn left_in_service(s: &service::Service) -> Check {
    let left = s.left();
    let mut c = Check::both(
        "interference left in service",
        "U_w,s",
        "µm",
        None,
        Some(left * 1e3),
    );
    if left <= 0.0 && s.fit.effective_interference() > 0.0 {
        c.pass = Some(false);
    }
    c.note("U_w − ΔU_ϑ − ΔU_ω at the run's end: the effective interference less what the temperatures and the speed take off; at 0 or below the fit is open and holds nothing")
}

/// What a run in service adds to the rating's subject: what each side is.
/// In service both sides are the run's end (its temperatures and speed):
/// the FE's as measured, the handbook's with the interference the service
/// leaves. A part at a temperature field there has no uniform ΔT for the
/// standard, so the handbook side stays the fit at assembly (room
/// temperature, standing still), and a difference between the sides is
/// then the service's, not the method's. Empty for a run with neither.
fn in_service(end: &service::End) -> String {
    let state = end.words.join(", ");
    match end.side {
        service::Side::Assembly => String::new(),
        service::Side::Service(_) => format!(
            "; in service, both sides are the run's end ({state}): the FE side as the run measured it, the handbook side DIN 7190's fit with the interference less what the temperatures and the speed take off, p = (U_w − ΔU_ϑ − ΔU_ω)/(D_F K); its yield checks at the larger of its pressures at assembly and at the run's end"
        ),
        service::Side::Field(what) => format!(
            "; in service: the FE side is the run's end ({state}), the handbook side the fit at assembly (room temperature, standing still): the {what} has a temperature field there, no uniform ΔT for DIN 7190's ΔU_ϑ, so their difference is the service's, not the method's"
        ),
    }
}

/// DIN 7190's joining temperature of the hub heated for assembly (clearance
/// 0.001 D_F, the room at the hub's reference temperature), when the hub has
/// a temperature (its α from α ΔT / ΔT) with a reference.
fn joining(model: &Model, fit: &Fit, hub: usize) -> Option<Input> {
    let bt = model.temperatures.iter().find(|bt| bt.body == hub)?;
    let room = bt.reference?;
    let t = fit.joining_temperature(room, 1e-3 * fit.d_f, bt.alpha)?;
    Some(Input::new(
        "joining temperature of the hub (clearance 0.001 D_F)",
        "ϑ_A",
        t,
        "°C",
        "material",
    ))
}

/// The largest load the fit held while it slid as a whole in `motion`
/// (|T| turned, N·mm; |F_T| pushed, N), by the direction each increment
/// moved ([`crate::measure::gross_slip`]): its holding plateau when the run
/// reaches one; none when it never slid so, or slid without that motion
/// imposed ([`crate::measure::gross_slip::imposed`]: a torque load, a
/// thermal contraction: what it held then is no capacity).
fn held(model: &Model, r: &Run, i: usize, motion: Motion) -> Option<f64> {
    if !crate::measure::gross_slip::imposed(model, i, motion) {
        return None;
    }
    let series: Vec<_> = joint_series(r, i).map(|(_, j)| j).collect();
    crate::measure::gross_slip::held(&series, motion)
        .into_iter()
        .map(|(_, h)| h)
        .reduce(f64::max)
}

/// Hub and shaft against yield: the FE's largest von Mises stress and the
/// handbook's at the bore, each against R_eL; and the standard's pressure
/// limits (elastic p_F, the hub's fully plastic limit) against the pressure.
/// `state` ends each note in service: which state the handbook rates.
fn yield_checks(
    model: &Model,
    r: &Run,
    fit: &Fit,
    (hub, shaft): (usize, usize),
    p: Option<f64>,
    s_f: f64,
    state: &str,
) -> Vec<Check> {
    let hub_hb = p.and_then(|p| fit.hub_stresses(p)).map(|s| s.von_mises);
    let shaft_hb = p.and_then(|p| fit.shaft_stresses(p)).map(|s| s.von_mises);
    vec![
        Check::both("hub von Mises stress", "σ_v,A", "MPa", max_von_mises(model, r, hub), hub_hb)
            .below(Some(fit.yield_hub), s_f)
            .note(format!("FE: the hub's largest von Mises stress over the run (edge peaks included); handbook: plane-stress Lamé at the bore{state}")),
        Check::both("shaft von Mises stress", "σ_v,I", "MPa", max_von_mises(model, r, shaft), shaft_hb)
            .below(Some(fit.yield_shaft), s_f)
            .note(format!("FE: the shaft's largest von Mises stress over the run; handbook: plane-stress Lamé at its bore (solid: uniform){state}")),
        Check::both("hub elastic limit pressure", "p_FA", "MPa", None, fit.yield_pressure_hub())
            .against(p, s_f)
            .note(format!("the pressure at which the hub's bore starts to yield, (1 − Q_A²) R_eL,A/√3, against the Lamé pressure{state}")),
        Check::both("hub fully plastic limit pressure", "p_A,max", "MPa", None, fit.plastic_limit_hub())
            .against(p, 1.0)
            .note(format!("the pressure a fully plastic hub holds, −(2/√3) R_eL,A ln Q_A: the absolute limit{state}")),
    ]
}
