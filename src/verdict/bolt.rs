//! VDI 2230-1:2015 for a concentric through-bolted joint of an axisymmetric
//! model: the guideline's side from [`handbook::vdi2230`](crate::verdict::handbook::vdi2230) with the geometry
//! read off the mesh, beside what the run measured.
//!
//! How the run's resiliences are split: at the lock the section carries
//! the preload F_V and has shortened by s = (δ_S + δ_P) F_V. The plates'
//! compression is the approach of the bolt's two bearing surfaces (the area
//! mean axial displacement of the bolt's side of the head's and of the nut's
//! bearing interfaces, the probes of [`crate::model::outputs::bearings`]), so
//! δ_P = (approach) / F_V includes the rough layers under head and nut and
//! between the plates, which the guideline's cone leaves out, and
//! δ_S = s / F_V − δ_P the bolt with its head and nut. Φ_n is the bolt's
//! force increase over the service load at the first service increment
//! (before the joint opens), n = Φ_n / Φ_K back-calculated.

use super::handbook::thread::{PropertyClass, Thread};
use super::handbook::vdi2230::{self as vdi, Bolt, Clamp, Head, Joint, ShankSection};
use super::rating::{max_pressure, radii, Check, Input, Rating};
use super::Run;
use crate::error::{clip, Error, Result};
use crate::input::case::rating::BoltSpec;
use crate::model::Model;
use crate::solve::events::Kind;

/// The joint as the mesh and the case give it.
pub struct Posed {
    section: usize,
    joint: usize,
    head: usize,
    /// The two bearing probes' indices in the plan.
    probes: [usize; 2],
    /// +1 when the head bears above the nut (larger y).
    orientation: f64,
    thread: Thread,
    r_p02: f64,
    clamp: Clamp,
    bolt: Bolt,
    service: Vec<usize>,
    pub inputs: Vec<Input>,
}

/// Reads the joint off the model; refuses what VDI 2230 cannot rate.
pub fn pose(model: &Model, spec: &BoltSpec, at: &str) -> Result<Posed> {
    if !model.section.axisymmetric || model.mesh.dim() != 2 {
        return Err(Error::input(at, "VDI 2230 rates a concentric bolt: give it an axisymmetric model about the bolt's axis (plane = \"axisymmetric\")"));
    }
    if model.node_dofs().twist() {
        // not built: the guideline's torque terms (the clamp load a torque
        // M_Y needs against slip, F_KQerf = M_Y / (q_M r_a μ_T,min), R2/R10)
        // and the bolt's torsion in service are not in the rating
        return Err(Error::input(at, "VDI 2230 is rated on the axial joint: in a model with twist ([model] twist = true) its torque terms (the clamp load against slip under a torque M_Y, the bolt's torsion in service) are not rated yet; rate the bolt on the model without twist, and read the joint's torque in joints.csv"));
    }
    let section = model
        .sections
        .iter()
        .position(|s| s.name == spec.pretension)
        .unwrap_or(usize::MAX);
    let sec = model.sections.get(section).ok_or_else(|| {
        Error::input(
            format!("{at} pretension"),
            format!("names no section \"{}\"", clip(&spec.pretension)),
        )
    })?;
    if !sec.lock_after.is_finite() {
        return Err(Error::input(format!("{at} pretension"), "is not a locked force-controlled section (a `shortening`, or `lock = false`): VDI 2230 rates a bolt tightened to a preload F_V and then locked; give the section a `force` with a history"));
    }
    let find = |key: &str, name: &str| {
        model
            .interfaces
            .iter()
            .position(|m| m.name == name)
            .ok_or_else(|| {
                Error::input(
                    format!("{at} {key}"),
                    format!("names no interface \"{}\"", clip(name)),
                )
            })
    };
    let (joint, head, nut) = (
        find("joint", &spec.joint)?,
        find("head", &spec.head)?,
        find("nut", &spec.nut)?,
    );
    distinct(model, spec, sec.body, [joint, head, nut], at)?;
    let thread = thread(&spec.thread).ok_or_else(|| {
        Error::input(
            format!("{at} thread"),
            format!(
                "\"{}\" is no ISO metric thread: \"M12\" (coarse, M3 to M64) or \"M12x1.5\"",
                clip(&spec.thread)
            ),
        )
    })?;
    let r_p02 = yield_strength(model, spec, &thread, sec.body, at)?;
    fits_the_shank(model, sec, &thread, at)?;
    let service = service_loads(model, spec, at)?;
    service_after_lock(model, &service, sec.lock_after, at)?;
    let names =
        crate::model::outputs::bearings::names(spec.name.as_deref().unwrap_or(&spec.pretension));
    let probe = |n: &String| {
        model
            .plan
            .probes
            .iter()
            .position(|p| &p.name == n)
            .unwrap_or(0)
    };
    let (clamp, bolt, orientation) = geometry(model, spec, thread, sec.body, [head, nut]);
    if spec.free_thread_length.unwrap_or(0.0) >= clamp.l_k {
        return Err(Error::input(
            format!("{at} free_thread_length"),
            format!(
                "is not shorter than the clamp length l_K = {} mm",
                crate::numbers::num(clamp.l_k)
            ),
        ));
    }
    let inputs = inputs(spec, &thread, r_p02, &clamp);
    Ok(Posed {
        section,
        joint,
        head,
        probes: [probe(&names[0]), probe(&names[1])],
        orientation,
        thread,
        r_p02,
        clamp,
        bolt,
        service,
        inputs,
    })
}

/// R_p0.2 of the bolt: its property class's, else its material's yield stress.
/// How far the bolt material's yield stress may lie from its property
/// class's R_p0.2 (a measured yield stress above the class's minimum, a
/// class's two diameter ranges).
const CLASS_SLACK: f64 = 0.1;

fn yield_strength(
    model: &Model,
    spec: &BoltSpec,
    thread: &Thread,
    body: usize,
    at: &str,
) -> Result<f64> {
    let r_p02 = match &spec.property_class {
        Some(c) => PropertyClass::of(c, thread.d)
            .ok_or_else(|| Error::input(format!("{at} property_class"), format!("\"{}\" is no ISO 898-1 class for d = {} mm (4.6, 5.6, 8.8, 9.8 up to M16, 10.9, 12.9)", clip(c), thread.d)))?
            .r_p02,
        None => model.materials[body].yield_stress,
    };
    if !r_p02.is_finite() {
        return Err(Error::input(
            format!("{at} property_class"),
            "is needed: the bolt's material has no yield stress to take R_p0.2 from",
        ));
    }
    let fe = model.materials[body].yield_stress;
    if fe.is_finite() && (fe - r_p02).abs() > CLASS_SLACK * r_p02 {
        return Err(Error::input(
            format!("{at} property_class"),
            format!(
                "\"{}\" has R_p0.2 = {} MPa, but the bolt's material \"{}\" yields at {} MPa: the run and the rating would yield the bolt at different stresses; give the material the class's yield stress (within 10 %) or leave property_class out",
                clip(spec.property_class.as_deref().unwrap_or("")),
                crate::numbers::num(r_p02),
                clip(&model.mesh.bodies[body]),
                crate::numbers::num(fe)
            ),
        ));
    }
    Ok(r_p02)
}

/// The clamp and the bolt as VDI 2230 models them, from the mesh: l_K
/// between the bearing interfaces, d_W the head interface's outer diameter,
/// d_h and D_A the plate's smallest and largest; a shank of the nominal
/// diameter over l_K less the free thread. And +1 when the head bears above
/// the nut.
fn geometry(
    model: &Model,
    spec: &BoltSpec,
    thread: Thread,
    body: usize,
    [head, nut]: [usize; 2],
) -> (Clamp, Bolt, f64) {
    let (yh, xh) = bearing(model, head);
    let (yn, _) = bearing(model, nut);
    let other = |i: usize| {
        let im = &model.interfaces[i];
        if im.body_a == body {
            im.body_b
        } else {
            im.body_a
        }
    };
    let plate = other(head);
    let (hole, outer) = radii(model, plate);
    let l_k = (yh - yn).abs();
    let clamp = Clamp {
        l_k,
        d_w: 2.0 * xh,
        d_h: 2.0 * hole,
        d_a: 2.0 * outer,
        e_plate: model.materials[plate].young,
    };
    let free = spec.free_thread_length.unwrap_or(0.0);
    let e_bolt = model.materials[body].young;
    let bolt = Bolt {
        thread,
        head: Head::Hexagon,
        shank: vec![ShankSection {
            length: (l_k - free).max(0.0),
            diameter: thread.d,
        }],
        free_thread: free,
        e_bolt,
        e_nut: e_bolt,
    };
    (clamp, bolt, if yh > yn { 1.0 } else { -1.0 })
}

fn thread(name: &str) -> Option<Thread> {
    if let Some(t) = Thread::coarse(name) {
        return Some(t);
    }
    let rest = name.trim().strip_prefix(['M', 'm'])?;
    let (d, p) = rest.split_once(['x', 'X', '×'])?;
    Thread::fine(d.trim().parse().ok()?, p.trim().parse().ok()?)
}

/// The joint between the plates, the head's and the nut's bearing: three
/// interfaces, the first not on the bolt.
fn distinct(
    model: &Model,
    spec: &BoltSpec,
    bolt: usize,
    [joint, head, nut]: [usize; 3],
    at: &str,
) -> Result<()> {
    if joint == head || joint == nut || head == nut {
        return Err(Error::input(format!("{at} joint"), "joint, head and nut name one interface twice: the plates' joint, the head's bearing and the nut's are three"));
    }
    let j = &model.interfaces[joint];
    if j.body_a == bolt || j.body_b == bolt {
        return Err(Error::input(
            format!("{at} joint"),
            format!(
                "\"{}\" is on the bolt's body: name the interface between the clamped plates",
                clip(&spec.joint)
            ),
        ));
    }
    Ok(())
}

/// The thread must be the shank's the section cuts (its diameter within a
/// quarter), its pitch one a thread of that size can have.
fn fits_the_shank(
    model: &Model,
    sec: &crate::model::pretension::Section,
    t: &Thread,
    at: &str,
) -> Result<()> {
    let r = sec
        .pairs
        .iter()
        .map(|&(n, _)| model.mesh.nodes[n][0].abs())
        .fold(0.0f64, f64::max);
    if (t.d - 2.0 * r).abs() > 0.25 * t.d {
        return Err(Error::input(format!("{at} thread"), format!("M{} does not fit the shank the section cuts ({} mm across): give the bolt's thread", t.d, crate::numbers::num(2.0 * r))));
    }
    if !t.iso_pitch() {
        let coarsest = Thread::coarse_of(t.d).map_or(t.d / 4.0, |c| c.pitch);
        return Err(Error::input(
            format!("{at} thread"),
            format!(
                "pitch {} mm is no pitch of an M{} thread (ISO 261: one of its series 0.2, 0.25, … 6 mm, at most the coarse pitch {} mm)",
                crate::numbers::num(t.pitch),
                t.d,
                crate::numbers::num(coarsest)
            ),
        ));
    }
    Ok(())
}

/// Every service load acts only after the lock: the preload is the
/// section's alone.
fn service_after_lock(model: &Model, service: &[usize], lock: f64, at: &str) -> Result<()> {
    for &k in service {
        let a = &model.applied[k];
        if model.factor(a.history, lock) != 0.0 {
            return Err(Error::input(format!("{at} service_load"), format!("{} acts before the section is locked (t = {}): give it a history that starts at the lock", a.name, crate::numbers::num(lock))));
        }
    }
    if service
        .iter()
        .all(|&k| model.applied[k].resultant[1] == 0.0)
    {
        return Err(Error::input(
            format!("{at} service_load"),
            "has no force along the bolt's axis: F_A is the axial service load",
        ));
    }
    Ok(())
}

/// The service loads' indices in [`Model::applied`].
fn service_loads(model: &Model, spec: &BoltSpec, at: &str) -> Result<Vec<usize>> {
    let Some(names) = &spec.service_load else {
        return Ok((0..model.applied.len()).collect());
    };
    if names.is_empty() {
        return Err(Error::input(
            format!("{at} service_load"),
            "is empty: name the loads that are F_A, or leave the key out (every load)",
        ));
    }
    if let Some(d) = names
        .iter()
        .enumerate()
        .find(|(i, n)| names[..*i].contains(n))
    {
        return Err(Error::input(
            format!("{at} service_load"),
            format!("names {} twice", clip(d.1)),
        ));
    }
    names
        .iter()
        .map(|n| {
            model
                .applied
                .iter()
                .position(|a| &a.name == n)
                .ok_or_else(|| {
                    let known: Vec<&str> = model.applied.iter().map(|a| a.name.as_str()).collect();
                    Error::input(
                        format!("{at} service_load"),
                        format!(
                            "names no load \"{}\" (loads: {})",
                            clip(n),
                            if known.is_empty() {
                                "none".into()
                            } else {
                                known.join(", ")
                            }
                        ),
                    )
                })
        })
        .collect()
}

/// An interface's plane (y) and its outer radius.
fn bearing(model: &Model, i: usize) -> (f64, f64) {
    let pairs = &model.interfaces[i].pairs;
    let y = pairs.iter().map(|p| p.x[1]).sum::<f64>() / pairs.len().max(1) as f64;
    let x = pairs.iter().fold(0.0f64, |a, p| a.max(p.x[0]));
    (y, x)
}

fn inputs(spec: &BoltSpec, t: &Thread, r_p02: f64, c: &Clamp) -> Vec<Input> {
    let from = |given: bool| if given { "case" } else { "default" };
    let class = if spec.property_class.is_some() {
        "case"
    } else {
        "material"
    };
    let mut list = vec![
        Input::new("thread diameter", "d", t.d, "mm", "case"),
        Input::new("pitch", "P", t.pitch, "mm", "case"),
        Input::new("stress area", "A_S", t.stress_area(), "mm²", "case"),
        Input::new("yield strength of the bolt", "R_p0.2", r_p02, "MPa", class),
        Input::new("clamp length", "l_K", c.l_k, "mm", "mesh"),
        Input::new("bearing diameter", "d_W", c.d_w, "mm", "mesh"),
        Input::new("hole diameter", "d_h", c.d_h, "mm", "mesh"),
        Input::new("outer diameter of the plates", "D_A", c.d_a, "mm", "mesh"),
        Input::new(
            "friction in the thread",
            "μ_G",
            spec.thread_friction,
            "",
            "case",
        ),
        Input::new(
            "friction under the head",
            "μ_K",
            spec.head_friction.unwrap_or(spec.thread_friction),
            "",
            from(spec.head_friction.is_some()),
        ),
        Input::new(
            "tightening factor",
            "α_A",
            spec.tightening_factor,
            "",
            "case",
        ),
        Input::new(
            "clamp load required",
            "F_K,erf",
            spec.clamp_load.unwrap_or(0.0),
            "N",
            from(spec.clamp_load.is_some()),
        ),
    ];
    // the embedding and the limits where the case or the standard gives them
    let guide = spec.embedding.or_else(|| vdi::embedding_guide(5.0, 2, 1));
    let more = [
        ("embedding", "f_Z", guide, "µm", spec.embedding.is_some()),
        (
            "limiting surface pressure",
            "p_G",
            spec.surface_pressure_limit,
            "MPa",
            true,
        ),
        (
            "load introduction factor",
            "n",
            spec.load_introduction,
            "",
            true,
        ),
        (
            "free loaded thread",
            "l_Gew",
            spec.free_thread_length,
            "mm",
            true,
        ),
    ];
    list.extend(
        more.into_iter()
            .filter_map(|(name, symbol, v, unit, given)| {
                v.map(|value| Input {
                    name,
                    symbol,
                    value,
                    unit,
                    from: from(given),
                })
            }),
    );
    list
}

/// The service load F_A at pseudo-time t: the axial resultant of the
/// service loads; a self-equilibrated pair (one on each plate) is one F_A.
fn service_load(model: &Model, service: &[usize], t: f64) -> f64 {
    let f: Vec<f64> = service.iter().map(|&k| model.applied_at(k, t)[1]).collect();
    let sum: f64 = f.iter().sum();
    let magnitude: f64 = f.iter().map(|v| v.abs()).sum();
    if sum.abs() <= 1e-6 * magnitude {
        0.5 * magnitude
    } else {
        sum.abs()
    }
}

/// What the run measured of the joint.
struct Measured {
    /// Preload at the lock F_V (N) and the resiliences δ_S, δ_P (mm/N).
    preload: f64,
    delta_s: f64,
    delta_p: f64,
    /// Φ_n at the first service increment, the largest F_A, the bolt's force
    /// there and its smallest in service, the joint's clamp force there.
    phi_n: Option<f64>,
    f_a_max: f64,
    bolt_max: f64,
    bolt_min: f64,
    clamp_at_max: f64,
    /// F_A at the joint's full separation in service.
    separation: Option<f64>,
    /// The largest normal force under the head (N).
    head_force: f64,
}

fn measure(model: &Model, r: &Run, p: &Posed) -> Option<Measured> {
    let sec = &model.sections[p.section];
    let lock = r
        .increments
        .iter()
        .rposition(|i| i.load_factor <= sec.lock_after * (1.0 + 1e-12))?;
    let at_lock = &r.increments[lock];
    let [preload, shortening] = *at_lock.sections.get(p.section)?;
    let plan = &model.plan;
    let nc = crate::model::outputs::probes::components(model.mesh.node_dofs);
    let u = |inc: &crate::solve::Increment, k: usize| {
        plan.part(&inc.record, &plan.layout.probes)
            .get(k * nc + 1)
            .copied()
    };
    let approach = p.orientation * (u(at_lock, p.probes[1])? - u(at_lock, p.probes[0])?);
    let delta_p = approach / preload;
    let delta_s = shortening / preload - delta_p;
    let service: Vec<&crate::solve::Increment> = r.increments[lock + 1..].iter().collect();
    let f_a = |inc: &crate::solve::Increment| service_load(model, &p.service, inc.load_factor);
    let force =
        |inc: &crate::solve::Increment| inc.sections.get(p.section).map_or(f64::NAN, |v| v[0]);
    let first = service.iter().find(|i| f_a(i) > 0.0);
    let phi_n = first.map(|i| (force(i) - preload) / f_a(i));
    let top = service
        .iter()
        .copied()
        .max_by(|a, b| f_a(a).total_cmp(&f_a(b)));
    let separation = r
        .events
        .iter()
        .find(|e| {
            e.kind == Kind::FullSeparation
                && e.interface == Some(p.joint)
                && e.load_factor > sec.lock_after
        })
        .map(|e| service_load(model, &p.service, e.load_factor));
    let head_force = r
        .increments
        .iter()
        .filter_map(|i| i.joints.get(p.head))
        .map(|j| j.normal_force)
        .fold(0.0, f64::max);
    Some(Measured {
        preload,
        delta_s,
        delta_p,
        phi_n,
        f_a_max: top.map_or(0.0, f_a),
        bolt_max: top.map_or(preload, force),
        bolt_min: service.iter().map(|i| force(i)).fold(preload, f64::min),
        clamp_at_max: top
            .and_then(|i| i.joints.get(p.joint))
            .map_or(f64::NAN, |j| j.normal_force),
        separation,
        head_force,
    })
}

/// The rating of a finished run.
pub fn rate(model: &Model, r: &Run, spec: &BoltSpec, p: Posed) -> Rating {
    let name = spec.name.clone().unwrap_or_else(|| spec.pretension.clone());
    let subject = format!(
        "bolted joint \"{}\": {} M{}×{} clamping {} mm at \"{}\"",
        name, spec.pretension, p.thread.d, p.thread.pitch, p.clamp.l_k, spec.joint
    );
    let mut rating = Rating {
        standard: "VDI 2230-1:2015",
        name,
        subject,
        inputs: p.inputs.clone(),
        checks: Vec::new(),
        incomplete: None,
    };
    let Some(m) = measure(model, r, &p) else {
        rating.incomplete =
            Some("the run ended before the section was locked: nothing to rate".into());
        return rating;
    };
    rating.checks = checks(model, r, spec, &p, &m);
    rating.incomplete = match m.phi_n {
        _ if m.f_a_max <= 0.0 => Some("no service load acted after the lock: nothing to rate".into()),
        Some(f) if f > 0.0 || spec.load_introduction.is_some() => None,
        f => Some(format!(
            "the bolt's force did not rise with the service load (Φ_n = {}): the joint is not loaded in tension as VDI 2230 rates it; give load_introduction for the handbook's side",
            f.map_or("-".into(), |v| crate::numbers::sig(v, 4))
        )),
    };
    rating
}

fn checks(model: &Model, r: &Run, spec: &BoltSpec, p: &Posed, m: &Measured) -> Vec<Check> {
    let delta_s_hb = vdi::bolt_resilience(&p.bolt, Joint::Through).map(|b| b.total);
    let delta_p_hb = vdi::plate_resilience(&p.clamp, Joint::Through).map(|c| c.delta_p);
    let phi_k_fe = vdi::load_factor(m.delta_s, m.delta_p);
    let phi_k_hb = delta_s_hb
        .zip(delta_p_hb)
        .and_then(|(s, q)| vdi::load_factor(s, q));
    let n_fe = m.phi_n.zip(phi_k_fe).map(|(a, b)| a / b);
    let n = spec.load_introduction.or(n_fe);
    let phi_n_hb = phi_k_hb
        .zip(n)
        .and_then(|(k, n)| vdi::load_factor_introduced(k, n));
    let f_a = m.f_a_max;
    let a_s = p.thread.stress_area();
    let mut c = vec![
        Check::both("bolt resilience", "δ_S", "mm/N", Some(m.delta_s), delta_s_hb).note("FE: the section's shortening at the lock / F_V − δ_P; handbook: head 0.5d, shank over l_K, engaged thread 0.5d and nut 0.4d"),
        Check::both("plate resilience", "δ_P", "mm/N", Some(m.delta_p), delta_p_hb).note("FE: the approach of the head's and the nut's bearing surfaces / F_V, with the rough layers; handbook: the deformation cone (cone and sleeve), no layers"),
        Check::both("load factor (load under the head)", "Φ_K", "", phi_k_fe, phi_k_hb).note("δ_P / (δ_S + δ_P)"),
        Check::both("load factor", "Φ_n", "", m.phi_n, phi_n_hb).note(format!("FE: the bolt's force increase over F_A in the first service increment; handbook: n Φ_K with n = {}", n.map_or("-".into(), |v| crate::numbers::sig(v, 3)))),
        Check::both("load introduction factor", "n", "", n_fe, spec.load_introduction).note("FE: Φ_n / Φ_K back-calculated; handbook: the case's load_introduction, where given"),
        Check::both("preload at the lock", "F_V", "N", Some(m.preload), None),
        Check::both("service load, largest", "F_A", "N", Some(f_a), None).note("the axial resultant of the service loads (a pair on the two plates counted once)"),
        Check::both("additional bolt load", "F_SA", "N", Some(m.bolt_max - m.preload), phi_n_hb.map(|f| vdi::additional_bolt_load(f, f_a))),
        Check::both("residual clamp load", "F_KR", "N", Some(m.clamp_at_max), phi_n_hb.map(|f| m.preload - vdi::plate_relief(f, f_a)))
            .against(spec.clamp_load, 1.0)
            .note("at the largest F_A; FE: the normal force across the joint; handbook: F_V − (1 − Φ_n) F_A"),
        Check::both("separation load", "F_A,ab", "N", m.separation, phi_n_hb.and_then(|f| vdi::separation_load(m.preload, f)))
            .against(Some(f_a), 1.0)
            .note("FE: F_A at the joint's full separation; handbook: F_V / (1 − Φ_n); held against the largest F_A"),
    ];
    c.extend(strength(
        model,
        r,
        spec,
        p,
        m,
        phi_n_hb,
        a_s,
        (delta_s_hb, delta_p_hb),
    ));
    c
}

#[allow(clippy::too_many_arguments)]
fn strength(
    model: &Model,
    r: &Run,
    spec: &BoltSpec,
    p: &Posed,
    m: &Measured,
    phi_n: Option<f64>,
    a_s: f64,
    (ds, dp): (Option<f64>, Option<f64>),
) -> Vec<Check> {
    let t = &p.thread;
    let f_m_zul = vdi::permissible_assembly_preload(
        t,
        t.stress_diameter(),
        p.r_p02,
        spec.thread_friction,
        vdi::UTILIZATION,
    );
    let f_z = spec
        .embedding
        .or_else(|| vdi::embedding_guide(5.0, 2, 1))
        .and_then(|fz| vdi::embedding_loss(fz, ds?, dp?));
    let f_m_min = m.preload / spec.tightening_factor;
    let relief = phi_n.map(|f| vdi::plate_relief(f, m.f_a_max));
    let f_kr_min = relief
        .zip(f_z)
        .map(|(rel, z)| vdi::residual_clamp_load(f_m_min, rel, z, 0.0));
    let sigma_as = match spec.threads.as_deref() {
        Some("rolled_after_heat_treatment") => vdi::endurance_rolled_after(
            t.d,
            m.preload + 0.5 * (m.bolt_max - m.preload),
            p.r_p02 * a_s,
        ),
        _ => vdi::endurance_rolled_before(t.d),
    };
    let sigma_a_fe = vdi::stress_amplitude(m.bolt_max, m.bolt_min, a_s);
    let sigma_a_hb = phi_n
        .and_then(|f| vdi::stress_amplitude(vdi::additional_bolt_load(f, m.f_a_max), 0.0, a_s));
    let a_p = vdi::bearing_area(p.clamp.d_w, p.clamp.d_h);
    let p_fe = a_p.and_then(|a| vdi::surface_pressure(m.head_force, a));
    let p_hb = a_p.zip(phi_n).and_then(|(a, f)| {
        vdi::surface_pressure(m.preload + vdi::additional_bolt_load(f, m.f_a_max), a)
    });
    let mu_k = spec.head_friction.unwrap_or(spec.thread_friction);
    let d_km = vdi::friction_diameter(p.clamp.d_w, p.clamp.d_h);
    vec![
        Check::both("assembly preload", "F_M", "N", Some(m.preload), None)
            .below(f_m_zul, 1.0)
            .note("the run's preload held against F_M,zul = 0.9 R_p0.2 A_0 / √(1 + 3 (3/2 d_2/d_0 (P/(π d_2) + 1.155 μ_G))²)"),
        Check::both("residual clamp load, smallest", "F_KR,min", "N", None, f_kr_min)
            .against(spec.clamp_load, 1.0)
            .note("handbook: F_V/α_A − F_Z − (1 − Φ_n) F_A, the tightening scatter and the embedding loss taken off the run's preload"),
        Check::both("separation load at the smallest preload", "F_A,ab,min", "N", None, phi_n.zip(f_z).and_then(|(f, z)| vdi::separation_load(f_m_min - z, f)))
            .against(Some(m.f_a_max), 1.0)
            .note("handbook: (F_V/α_A − F_Z) / (1 − Φ_n): the joint tightened to the low end of the scatter and settled; held against the largest F_A"),
        Check::both("surface pressure at the permissible preload", "p_M,max", "MPa", None, a_p.zip(f_m_zul).and_then(|(a, f)| vdi::surface_pressure(f, a)))
            .below(spec.surface_pressure_limit, 1.0)
            .note("handbook: F_M,zul / A_p, the assembly state of a bolt tightened to its limit"),
        Check::both("stress amplitude", "σ_a", "MPa", sigma_a_fe, sigma_a_hb)
            .below(sigma_as, 1.2)
            .note("FE: (largest − smallest bolt force in service) / (2 A_S); handbook: Φ_n F_A / (2 A_S); against the endurance σ_ASV (σ_ASG rolled after heat treatment), S_D ≥ 1.2"),
        Check::both("surface pressure under the head", "p", "MPa", p_fe, p_hb)
            .below(spec.surface_pressure_limit, 1.0)
            .note(format!("the force under the head / A_p = π/4 (d_W² − d_h²); the largest pair pressure there {} MPa", max_pressure(model, r, p.head).map_or("-".into(), |v| crate::numbers::sig(v, 4)))),
        Check::both("tightening torque", "M_A", "N·m", None, Some(vdi::tightening_torque(t, m.preload, spec.thread_friction, mu_k, d_km) * 1e-3))
            .note("the torque that brings the run's preload in: F_M (0.16 P + 0.58 d_2 μ_G + μ_K D_Km/2)"),
    ]
}
