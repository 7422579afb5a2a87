//! The records every increment adds beside the state: the joints' rows
//! (`joints`, `joints_twist`), the pretension sections' rows (`pretension`)
//! and the designer's records (`records`: probes and peaks). A record is
//! output, but a forged one would be written out as the run's answer (a
//! torque or probe spike, a locked bolt that moved, a pre-lock force other
//! than the case's) and the last one is where a resumed run's event search
//! starts. So each is, where the case fixes it, recomputed from the case; the
//! last increment's, beside the restored state, recomputed from that state
//! and compared (it is a function of it: the file's must be the same number);
//! and every other value checked against what the case and its laws allow.

use super::*;
use crate::model::pretension::free_at;

/// The joint measures of every increment: the totals finite, a row per
/// interface and increment (`joints`, and with twist `joints_twist`; empty
/// without), every value finite, every row within what the interface can
/// carry ([`check_joint_row`]), and the last one the restored state's own
/// ([`crate::solve::joint_measures`]).
pub(super) fn restore_joints(ck: &mut Checkpoint, s: &Sections, model: &Model) -> Decoded<()> {
    let interfaces = model.interfaces.len();
    let v = s.finite("joint_totals", Some(2 * interfaces))?;
    ck.joint_totals = v
        .chunks_exact(2)
        .map(|t| JointTotals {
            dissipation: t[0],
            work: t[1],
        })
        .collect();
    let n = ck.increments.len();
    let w = JointMeasures::PACKED * interfaces;
    let v = s.finite("joints", Some(w * n))?;
    for (inc, row) in ck.increments.iter_mut().zip(v.chunks_exact(w.max(1))) {
        inc.joints = row
            .chunks_exact(JointMeasures::PACKED)
            .map(JointMeasures::unpack)
            .collect();
    }
    // twist: torque, circumferential slip and twist of every row
    let twist = if model.node_dofs().twist() { n } else { 0 };
    let w = JointMeasures::PACKED_TWIST * interfaces;
    let v = s.finite("joints_twist", Some(w * twist))?;
    for (inc, row) in ck.increments.iter_mut().zip(v.chunks_exact(w.max(1))) {
        for (m, t) in inc
            .joints
            .iter_mut()
            .zip(row.chunks_exact(JointMeasures::PACKED_TWIST))
        {
            (m.torque, m.hoop_slip, m.twist) = (t[0], t[1], t[2]);
        }
    }
    // 3D: F_T2, ū_T2, the force and the moment on A of every row
    let space = if model.node_dofs().solid() { n } else { 0 };
    let w = JointMeasures::PACKED_SPACE * interfaces;
    let v = s.finite("joints_space", Some(w * space))?;
    for (inc, row) in ck.increments.iter_mut().zip(v.chunks_exact(w.max(1))) {
        for (m, t) in inc
            .joints
            .iter_mut()
            .zip(row.chunks_exact(JointMeasures::PACKED_SPACE))
        {
            m.unpack_space(t);
        }
    }
    for inc in &ck.increments {
        for (im, m) in model.interfaces.iter().zip(&inc.joints) {
            check_joint_row(model, im, m).map_err(|e| {
                format!(
                    "section joints{}: increment {}: interface {:?}: {e}",
                    match e.split(' ').next() {
                        Some("torque") => "_twist",
                        _ if e.contains("along t2") || e.contains(" on A ") => "_space",
                        _ => "",
                    },
                    inc.increment,
                    im.name
                )
            })?;
        }
    }
    // the last row is the restored state's (with the file's totals)
    if let Some(last) = ck.increments.last() {
        let own = crate::solve::joint_measures(model, &ck.committed, &ck.joint_totals);
        for ((im, got), want) in model.interfaces.iter().zip(&last.joints).zip(&own) {
            let (g, w) = (joint_values(got), joint_values(want));
            if let Some(k) = (0..g.len()).find(|&k| g[k].to_bits() != w[k].to_bits()) {
                return Err(format!(
                    "section {}: increment {} (the last): interface {:?}: {} = {}, but the restored state (sections u, status, contact, joint_totals) gives {}",
                    match k {
                        _ if k >= JointMeasures::PACKED + JointMeasures::PACKED_TWIST => "joints_space",
                        _ if k >= JointMeasures::PACKED => "joints_twist",
                        _ => "joints",
                    },
                    last.increment,
                    im.name,
                    JOINT_NAMES[k],
                    num(g[k]),
                    num(w[k])
                ));
            }
        }
    }
    Ok(())
}

/// The names of [`joint_values`], for messages.
const JOINT_NAMES: [&str;
    JointMeasures::PACKED + JointMeasures::PACKED_TWIST + JointMeasures::PACKED_SPACE] = [
    "normal force",
    "tangential force",
    "mean approach",
    "mean slip",
    "open measure",
    "closed measure",
    "stick measure",
    "micro-slip measure",
    "macro-slip measure",
    "dissipation",
    "work",
    "torque",
    "circumferential slip",
    "twist",
    "tangential force along t2",
    "mean slip along t2",
    "force on A along x",
    "force on A along y",
    "force on A along z",
    "moment on A about x",
    "moment on A about y",
    "moment on A about z",
];

/// A row's values, the twist ones last.
fn joint_values(m: &JointMeasures) -> Vec<f64> {
    m.pack()
        .into_iter()
        .chain(m.pack_twist())
        .chain(m.pack_space())
        .collect()
}

/// One interface's joint measures of an increment against what it can
/// carry: a normal force Σ A p_N ≥ 0, at most the pressure range over its
/// area; status measures ≥ 0 that add up to its measure; a tangential force
/// and (twist) a torque within what friction holds at that normal force,
/// |F_T| ≤ μ F_N and |T| ≤ μ r_max F_N (|p_T| ≤ μ_F p_N ≤ μ p_N at every
/// point: the return mapping's cap, eq. 2.21-2.22; zero without a
/// tangential law); approaches and slips within the displacement range.
/// In 3D also F_T2 within μ F_N, the force on A within (1 + μ) F_N (its
/// normal and shear parts at every point) and its moment within
/// (1 + μ) F_N r_max (r_max the points' largest distance from the moment
/// point). Round-off is allowed ([`REACH_REL`] of the bound, [`REACH_ABS`]).
fn check_joint_row(
    model: &Model,
    im: &crate::model::interface::InterfaceModel,
    m: &JointMeasures,
) -> std::result::Result<(), String> {
    let area: f64 = im.points.iter().map(|p| p.area).sum();
    let per_measure = if model.section.axisymmetric {
        1.0
    } else {
        1.0 / model.section.thickness
    };
    let slack = |bound: f64| REACH_REL * bound.abs() + REACH_ABS;
    let most = MAX_PRESSURE * area;
    if !(m.normal_force >= 0.0 && m.normal_force <= most) {
        return Err(format!(
            "normal force {} N, outside [0, {}] N (compressive, at most the pressure range over its area)",
            num(m.normal_force),
            num(most)
        ));
    }
    let statuses = [m.open, m.closed, m.stick, m.micro_slip, m.macro_slip];
    let whole = area * per_measure;
    let sum: f64 = statuses.iter().sum();
    if statuses.iter().any(|&x| x < 0.0) || (sum - whole).abs() > slack(whole) {
        return Err(format!(
            "status measures {} (open, closed, stick, micro-slip, macro-slip), not ≥ 0 adding up to the interface's {}",
            statuses.map(num).join(", "),
            num(whole)
        ));
    }
    let mu = im.tangential.as_ref().map_or(0.0, |law| law.mu);
    let hold = mu * m.normal_force;
    if m.tangential_force.abs() > hold + slack(hold) {
        return Err(format!(
            "tangential force {} N, beyond what friction holds at its normal force, μ F_N = {} N",
            num(m.tangential_force),
            num(hold)
        ));
    }
    if im.twist() {
        let r_max = im.point_radii().iter().fold(0.0f64, |a, r| a.max(r.abs()));
        let turn = hold * r_max;
        if m.torque.abs() > turn + slack(turn) {
            return Err(format!(
                "torque {} N·mm, beyond what friction holds at its normal force, μ F_N r_max = {} N·mm",
                num(m.torque),
                num(turn)
            ));
        }
    }
    if im.node_dofs.solid() {
        check_space_row(im, m, hold, &slack)?;
    }
    for (name, v) in [
        ("mean approach", m.mean_approach),
        ("mean slip", m.mean_slip),
        ("circumferential slip", m.hoop_slip),
        ("mean slip along t2", m.mean_slip_2),
    ] {
        if v.abs() > MAX_DISPLACEMENT {
            return Err(format!(
                "{name} {} mm, beyond the ±{} mm of the displacement range",
                num(v),
                num(MAX_DISPLACEMENT)
            ));
        }
    }
    Ok(())
}

/// The 3D measures of a joint row (see [`check_joint_row`]); `hold` is
/// μ F_N.
fn check_space_row(
    im: &crate::model::interface::InterfaceModel,
    m: &JointMeasures,
    hold: f64,
    slack: &dyn Fn(f64) -> f64,
) -> std::result::Result<(), String> {
    let norm = |v: [f64; 3]| crate::numbers::vec3::dot(v, v).sqrt();
    if m.tangential_force_2.abs() > hold + slack(hold) {
        return Err(format!(
            "tangential force along t2 {} N, beyond what friction holds at its normal force, μ F_N = {} N",
            num(m.tangential_force_2),
            num(hold)
        ));
    }
    let most = m.normal_force.max(0.0) + hold;
    if norm(m.force) > most + slack(most) {
        return Err(format!(
            "force on A of size {} N, beyond F_N + μ F_N = {} N",
            num(norm(m.force)),
            num(most)
        ));
    }
    let r_max = im.points.iter().fold(0.0f64, |a, pt| {
        let d = crate::numbers::vec3::sub(im.point_position(pt), im.moment_point);
        a.max(norm(d))
    });
    let turn = most * r_max;
    if norm(m.moment) > turn + slack(turn) {
        return Err(format!(
            "moment on A of size {} N·mm, beyond (F_N + μ F_N) r_max = {} N·mm",
            num(norm(m.moment)),
            num(turn)
        ));
    }
    Ok(())
}

/// Every increment's pretension section forces and shortenings (section
/// `pretension`, 2 numbers per section and increment, finite; empty in a
/// model without sections). What the
/// case fixes is the case's ([`Model::section_row`]): a free section's force
/// (force control before its lock) is recomputed as F h(t), a prescribed
/// shortening as its value at t, whatever the file holds; a locked section's
/// shortening is the one at its lock in every later row and in the state
/// (Newton holds it: a row or state that moved it is refused); the last
/// row's shortening is the state's; the other values (a locked or prescribed
/// section's force, a free one's shortening) within the force and
/// displacement ranges.
pub(super) fn restore_sections(ck: &mut Checkpoint, s: &Sections, model: &Model) -> Decoded<()> {
    let w = 2 * model.sections.len();
    let v = s.finite("pretension", Some(w * ck.increments.len()))?;
    for (inc, row) in ck.increments.iter_mut().zip(v.chunks_exact(w.max(1))) {
        for p in row.chunks_exact(2) {
            let (force, shortening) = (p[0], p[1]);
            if !(crate::input::case::ranges::FORCE.admits(force) || force == 0.0)
                || shortening.abs() > MAX_DISPLACEMENT
            {
                return Err(format!(
                    "section pretension: increment {}: a force {} or shortening {} outside any engineering use",
                    inc.increment,
                    num(force),
                    num(shortening)
                ));
            }
        }
        inc.sections = row.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
    }
    for (k, sec) in model.sections.iter().enumerate() {
        // the shortening held from the lock on: the last one before it
        // (0 without an increment before it)
        let mut locked_at = 0.0;
        for inc in &mut ck.increments {
            let t = inc.load_factor;
            let [force, shortening] = &mut inc.sections[k];
            if free_at(sec, t) {
                *force = model.section_load(k, t);
                locked_at = *shortening;
            } else if sec.control == "force" && shortening.to_bits() != f64::to_bits(locked_at) {
                return Err(format!(
                    "section pretension: increment {}: the shortening of pretension \"{}\" is {} mm, but it is locked from t = {} on at {} mm",
                    inc.increment,
                    sec.name,
                    num(*shortening),
                    num(sec.lock_after),
                    num(locked_at)
                ));
            }
            if sec.control == "shortening" {
                let prescribed = model
                    .prescribed_at(t)
                    .find(|&(d, _)| d == sec.dof)
                    .map_or(*shortening, |p| p.1);
                *shortening = prescribed;
            }
        }
    }
    // the committed shortening is the last increment's (a locked one never
    // moves, so a file whose state disagrees with its own record is forged)
    if let Some(last) = ck.increments.last() {
        for (k, sec) in model.sections.iter().enumerate() {
            let (u, rec) = (ck.committed.u[sec.dof], last.sections[k][1]);
            if u.to_bits() != rec.to_bits() {
                return Err(format!(
                    "section u: the shortening of pretension \"{}\" is {} but the last increment records {}",
                    sec.name,
                    num(u),
                    num(rec)
                ));
            }
        }
    }
    Ok(())
}

/// The designer's records against the state and the case: every probe
/// value within the displacement range (a probe is a displacement), and the
/// last increment's record from its probes on (probes, body and interface
/// peaks: [`crate::model::outputs::Plan::state_part`]) the restored state's,
/// NaN where the state gives NaN (no place). The reactions before them come
/// from the residual, which the state does not keep: range-free.
pub(super) fn check_records(ck: &Checkpoint, model: &Model) -> Decoded<()> {
    let plan = &model.plan;
    let probes = plan.layout.probes.clone();
    for inc in &ck.increments {
        let v = plan.part(&inc.record, &probes);
        if let Some(i) = v
            .iter()
            .position(|x| x.is_nan() || x.abs() > MAX_DISPLACEMENT)
        {
            return Err(format!(
                "section records: increment {}: probe value {} is {} mm, a displacement beyond the ±{} mm of a case",
                inc.increment,
                i + 1,
                num(v[i]),
                num(MAX_DISPLACEMENT)
            ));
        }
    }
    let Some(last) = ck.increments.last() else {
        return Ok(());
    };
    let own = crate::measure::state_part(model, &ck.committed);
    let got = &last.record[probes.start..];
    if let Some(k) = (0..own.len()).find(|&k| !same(got[k], own[k])) {
        let at = probes.start + k;
        let what = if plan.layout.probes.contains(&at) {
            "a probe"
        } else if plan.layout.bodies.contains(&at) {
            "a body peak"
        } else {
            "an interface peak"
        };
        return Err(format!(
            "section records: increment {} (the last): value {} ({what}) is {}, but the restored state (sections u, gauss) gives {}",
            last.increment,
            at + 1,
            num(got[k]),
            num(own[k])
        ));
    }
    Ok(())
}

/// Two values of a record alike: the same number, or both NaN.
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// The curve's rows against the case and the last one against the
/// restored state. Every row: the first interface's normal force within
/// [0, the pressure range × its area], its mean pressure and load that force
/// over the area and in kN (as every run computes them: exactly), none of
/// the three without an interface; the probe node's displacement within the
/// displacement range; the largest PEEQ within [0, [`MAX_PEEQ`]]. The last
/// row: its measures (those and the prescribed reaction) the state's own
/// ([`Measures::of`]).
pub(super) fn check_curve(ck: &Checkpoint, model: &Model) -> Decoded<()> {
    for inc in &ck.increments {
        let m = &inc.measures;
        let (area, scale) = match model.interfaces.first() {
            Some(im) => (im.area(), model.load_scale_kn()),
            None => (0.0, 0.0),
        };
        let bad = |what: String| Err(format!("section curve: row {}: {what}", inc.increment));
        let most = MAX_PRESSURE * area;
        if !(m.normal_force >= 0.0 && m.normal_force <= most) {
            return bad(format!(
                "normal force {} N, outside [0, {}] N (compressive, at most the pressure range over the interface)",
                num(m.normal_force),
                num(most)
            ));
        }
        let (mean, load) = match model.interfaces.first() {
            Some(_) => (m.normal_force / area, m.normal_force * scale),
            None => (0.0, 0.0),
        };
        if !same(m.mean_pressure, mean) || !same(m.total_load_kn, load) {
            return bad(format!(
                "mean pressure {} MPa and load {} kN, but its normal force {} N gives {} MPa and {} kN",
                num(m.mean_pressure),
                num(m.total_load_kn),
                num(m.normal_force),
                num(mean),
                num(load)
            ));
        }
        if m.center_displacement.abs() > MAX_DISPLACEMENT || !(0.0..=MAX_PEEQ).contains(&m.max_peeq)
        {
            return bad(format!(
                "centre displacement {} mm or largest PEEQ {} beyond the ranges of a state (±{} mm, [0, {}])",
                num(m.center_displacement),
                num(m.max_peeq),
                num(MAX_DISPLACEMENT),
                num(MAX_PEEQ)
            ));
        }
    }
    let Some(last) = ck.increments.last() else {
        return Ok(());
    };
    let own = Measures::of(model, &ck.committed);
    let m = &last.measures;
    let pairs = [
        ("normal force", m.normal_force, own.normal_force),
        ("mean pressure", m.mean_pressure, own.mean_pressure),
        ("load", m.total_load_kn, own.total_load_kn),
        (
            "centre displacement",
            m.center_displacement,
            own.center_displacement,
        ),
        ("largest PEEQ", m.max_peeq, own.max_peeq),
        (
            "prescribed reaction",
            m.prescribed_reaction,
            own.prescribed_reaction,
        ),
    ];
    if let Some((name, got, want)) = pairs.into_iter().find(|p| !same(p.1, p.2)) {
        return Err(format!(
            "section curve: row {} (the last): {name} {}, but the restored state (sections u, gauss, prescribed_reaction) gives {}",
            last.increment,
            num(got),
            num(want)
        ));
    }
    Ok(())
}
