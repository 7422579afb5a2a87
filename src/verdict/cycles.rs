//! A joint under load cycles (`standard = "joint cycles"`): the steady
//! cycles of one interface, for the part a designer names. The run's cycles
//! ([`crate::measure::joint::Cycle`]) are those of the model as meshed (a
//! plane model's thickness, an axisymmetric model's whole ring); the rating
//! scales them to the part: forces, stiffness and dissipation by
//! s = (`width` / thickness) × `count` in a plane model, by `count` in an
//! axisymmetric or 3D one; slip and the loss factor are the same for any
//! part. Each amplitude block of the sweep ([`crate::measure::sweep`])
//! gives its last cycle, its steady value: force amplitude, slip amplitude,
//! secant stiffness, dissipation and loss factor, each beside a uniform
//! Masing joint at the run's slip amplitude
//! ([`handbook::masing`](crate::verdict::handbook::masing)) where the
//! interface keeps a kinematic memory.

use super::handbook::masing::UniformJoint;
use super::rating::{Check, Input, Rating};
use super::Run;
use crate::error::{clip, Error, Result};
use crate::input::case::rating::CyclesSpec;
use crate::measure::joint::{cycle_windows, Cycle};
use crate::model::Model;
use crate::physics::contact::tangential::Memory;

/// The rating as the model poses it: which interface and the factor from
/// the model's forces to the part's.
pub struct Posed {
    pub interface: usize,
    pub scale: f64,
    pub inputs: Vec<Input>,
}

/// Reads the joint off the model; refuses what cannot be rated.
pub fn pose(model: &Model, spec: &CyclesSpec, at: &str) -> Result<Posed> {
    let fail = |key: &str, m: String| Error::input(format!("{at} {key}"), m);
    let i = model
        .interfaces
        .iter()
        .position(|m| m.name == spec.interface)
        .ok_or_else(|| {
            fail(
                "interface",
                format!("names no interface \"{}\"", clip(&spec.interface)),
            )
        })?;
    if model.interfaces[i].tangential.is_none() {
        return Err(fail("interface", format!("\"{}\" has no friction (`[interface.{}.tangential]`): a joint without a tangential law carries no load cycle", clip(&spec.interface), clip(&spec.interface))));
    }
    let plane = !model.section.axisymmetric && model.mesh.dim() == 2;
    if spec.width.is_some() && !plane {
        let what = if model.section.axisymmetric {
            "an axisymmetric model is the whole ring"
        } else {
            "a 3D model is the part as meshed"
        };
        return Err(fail(
            "width",
            format!("is for a plane model (its results are per thickness): {what}; for repeated joints give `count`"),
        ));
    }
    if model.symmetric_half {
        return Err(Error::input(at, "rates the joint as meshed, and with `symmetric_half` the mesh is half of it: whether the other half's joint mirrors this one's loop is not the rating's to guess; mesh the whole joint"));
    }
    if !closes_a_cycle(model) {
        return Err(Error::input(at, "has no load cycle to rate: no breakpoint of the histories returns every history to its values at an earlier one (docs/joints.md, \"Reading a joint\")"));
    }
    let count = f64::from(spec.count.unwrap_or(1));
    let (width, scale) = if plane {
        let w = spec.width.unwrap_or(model.thickness);
        (Some(w), w / model.thickness * count)
    } else {
        (None, count)
    };
    let inputs = inputs(model, spec, width, count);
    Ok(Posed {
        interface: i,
        scale,
        inputs,
    })
}

/// Whether the histories, walked over their breakpoints, close a cycle
/// (the run marks its increments at the breakpoints the same way).
fn closes_a_cycle(model: &Model) -> bool {
    let marks: Vec<Option<Vec<f64>>> = model
        .breakpoints()
        .iter()
        .map(|&t| Some(model.history_values(t)))
        .collect();
    !cycle_windows(&marks).is_empty()
}

fn inputs(model: &Model, spec: &CyclesSpec, width: Option<f64>, count: f64) -> Vec<Input> {
    let mut v = Vec::new();
    if let Some(w) = width {
        v.push(Input::new(
            "model thickness",
            "t",
            model.thickness,
            "mm",
            "mesh",
        ));
        v.push(Input::new(
            "width of the part",
            "b",
            w,
            "mm",
            if spec.width.is_some() {
                "case"
            } else {
                "default"
            },
        ));
    }
    v.push(Input::new(
        "joints in the part",
        "n",
        count,
        "",
        if spec.count.is_some() {
            "case"
        } else {
            "default"
        },
    ));
    v
}

/// The rating of a finished run.
pub fn rate(model: &Model, r: &Run, spec: &CyclesSpec, posed: Posed) -> Rating {
    let Posed {
        interface: i,
        scale,
        inputs,
    } = posed;
    let cycles = crate::solve::cycles(model, r.increments).swap_remove(i);
    let sweep = crate::measure::sweep::sweep(&cycles);
    let steady: Vec<(usize, &Cycle)> = cycles
        .iter()
        .enumerate()
        .zip(&sweep.rows)
        .filter(|(_, row)| row.last_in_block)
        .map(|(c, _)| c)
        .filter(|(_, c)| c.stored_energy() > c.floor)
        .collect();
    let mut checks = Vec::new();
    for &(k, c) in &steady {
        let uniform = uniform_joint(model, r, i, c);
        checks.extend(cycle_checks(spec, scale, k + 1, c, uniform.as_ref()));
    }
    let incomplete = steady.is_empty().then(|| {
        if cycles.is_empty() {
            "the run closed no load cycle".to_string()
        } else {
            format!(
                "none of the run's {} closed cycles has a force-slip loop (the tangential force held, or no slip)",
                cycles.len()
            )
        }
    });
    let im = &model.interfaces[i];
    let names = &model.mesh.bodies;
    Rating {
        standard: "joint cycles",
        name: spec.name.clone().unwrap_or_else(|| spec.interface.clone()),
        subject: format!(
            "joint \"{}\" between {} and {} under load cycles, the steady cycle of each amplitude, {}",
            im.name,
            names[im.body_a],
            names[im.body_b],
            part_words(model, spec)
        ),
        inputs,
        checks,
        incomplete,
    }
}

/// "for 80 mm of width" / "for the whole ring" (× n joints).
fn part_words(model: &Model, spec: &CyclesSpec) -> String {
    let whole = if model.section.axisymmetric {
        "for the whole ring".to_string()
    } else if model.mesh.dim() == 2 {
        format!(
            "for {} mm of width",
            crate::numbers::sig(spec.width.unwrap_or(model.thickness), 6)
        )
    } else {
        "for the part as meshed".to_string()
    };
    match spec.count {
        Some(n) if n > 1 => format!("{whole}, times {n} joints"),
        _ => whole,
    }
}

/// The five checks of one steady cycle (number `n`, from 1) for the part
/// (`scale` times the model's forces), the uniform joint's beside them.
fn cycle_checks(
    spec: &CyclesSpec,
    scale: f64,
    n: usize,
    c: &Cycle,
    uniform: Option<&UniformJoint>,
) -> Vec<Check> {
    let u_a = c.slip_amplitude();
    let hb = |f: &dyn Fn(&UniformJoint) -> Option<f64>| uniform.and_then(f);
    let at = format!("cycle {n} (t {}–{})", num(c.start_time), num(c.end_time));
    let from = if uniform.is_some() {
        "; handbook: a uniform Masing joint at the FE's mean pressure and slip amplitude"
    } else {
        "; handbook: none (the closed form is of a kinematic memory; this interface shakes down)"
    };
    let label = |q: &str| format!("{at}, {q}");
    let mut v = vec![
        Check::both(
            label("force amplitude"),
            "F_a",
            "N",
            Some(scale * c.force_amplitude()),
            hb(&|j| j.force_amplitude(u_a)).map(|f| scale * f),
        )
        .note(format!(
            "FE: (F_T,max − F_T,min)/2 of the cycle, for the part{from}"
        )),
        Check::both(label("slip amplitude"), "u_a", "µm", Some(1e3 * u_a), None)
            .below(spec.max_slip, 1.0)
            .note("FE: (ū_T,hi − ū_T,lo)/2 at the loop's tips; the handbook's is the FE's"),
        Check::both(
            label("secant stiffness"),
            "k_s",
            "N/µm",
            c.secant_stiffness.map(|k| 1e-3 * scale * k),
            hb(&|j| j.secant_stiffness(u_a)).map(|k| 1e-3 * scale * k),
        )
        .against(spec.min_stiffness, 1.0)
        .note(format!(
            "FE: ΔF_T/Δū_T between the loop's tips, for the part{from}"
        )),
        Check::both(
            label("dissipation per cycle"),
            "D",
            "N·mm",
            Some(scale * c.dissipation),
            hb(&|j| j.dissipation(u_a)).map(|d| scale * d),
        )
        .note(format!(
            "FE: the frictional work of the cycle, for the part{from}"
        )),
        Check::both(
            label("loss factor"),
            "η",
            "",
            c.loss_factor(),
            hb(&|j| j.loss_factor(u_a)),
        )
        .against(spec.min_loss_factor, 1.0)
        .note(format!(
            "D / (2π U), U = ½ F_a u_a: the same for any part{from}"
        )),
    ];
    if let Some(hi) = spec.max_stiffness {
        let k = v[2].clone();
        v.insert(
            3,
            Check {
                quantity: label("secant stiffness, at most").into(),
                ..k
            }
            .below(Some(hi), 1.0),
        );
    }
    for check in &mut v {
        check.cycle = Some(n);
    }
    v
}

/// The uniform Masing joint of interface `i` over cycle `c`: its whole area
/// at the mean pressure F_N / A at the cycle's end; None without a
/// kinematic memory (the isotropic one shakes down: no steady loop).
fn uniform_joint(model: &Model, r: &Run, i: usize, c: &Cycle) -> Option<UniformJoint> {
    let im = &model.interfaces[i];
    let law = im.tangential.as_ref()?;
    if law.memory != Memory::Kinematic {
        return None;
    }
    let area: f64 = im.points.iter().map(|p| p.area).sum();
    let end = r.increments.get(c.end_increment.checked_sub(1)?)?;
    let p = end.joints.get(i)?.normal_force / area;
    if !(p.is_finite() && p > 0.0) {
        return None;
    }
    let k = law.elastic_stiffness(p).0;
    let d = law.density();
    Some(UniformJoint {
        stiffness: k,
        slip_range: law.mu * p * d.big_c / k,
        c: d.c,
        chi: d.chi,
        masses: d.masses.to_vec(),
        area,
    })
}

fn num(v: f64) -> String {
    crate::numbers::sig(v, 6)
}

#[cfg(test)]
mod tests;
