//! The interface points' contact states of a restart file: the layout of
//! this build (25 values a point) or of the builds before the kinematic
//! memory (5), each state one its law can continue from and the one its
//! law gives at the committed displacements.

use super::*;
use crate::interface::{InterfaceModel, PointState as ContactState, Stretch, MEMORY_POINTS};

/// Section `contact` into `contact` (one state per interface point, in
/// order), every state checked ([`check_contact_point`],
/// [`check_contact_against_u`]).
pub(super) fn restore(
    s: &Sections,
    model: &Model,
    u: &[f64],
    lambda: f64,
    contact: &mut [ContactState],
) -> Decoded<()> {
    let np = contact.len();
    let laws = model
        .interfaces
        .iter()
        .flat_map(|im| im.points.iter().map(move |_| im));
    // 5 values per point before the kinematic memory existed (issue 28):
    // such a file resumes with every memory empty, as its laws keep none
    let width = match s.0.get("contact") {
        Some(Data::F64(v)) if np > 0 && v.len() == OLD_CONTACT * np => OLD_CONTACT,
        _ => ContactState::PACKED,
    };
    let mut full = [0.0; ContactState::PACKED];
    for (i, ((p, v), im)) in contact
        .iter_mut()
        .zip(s.finite("contact", Some(width * np))?.chunks_exact(width))
        .zip(laws)
        .enumerate()
    {
        full[..width].copy_from_slice(v);
        *p = ContactState::unpack(&full);
        check_contact_point(im, i, p)?;
    }
    check_contact_against_u(model, u, lambda, contact)
}

/// The contact states against the committed displacements: each point's
/// u_T as the displacements give it, and its shear p_T as its law gives it
/// from its slip memory there (a converged state evaluated again: the same
/// numbers, up to the solver's last correction). A forged shear or slip
/// would otherwise enter the energies of every later increment.
fn check_contact_against_u(
    model: &Model,
    u: &[f64],
    lambda: f64,
    contact: &[ContactState],
) -> Decoded<()> {
    let u_max = u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut q = 0;
    for im in &model.interfaces {
        let gap = im.gap_at(lambda);
        for pt in &im.points {
            let st = &contact[q];
            q += 1;
            let at = || format!("section contact: interface point {q} ({})", im.name);
            let (u_n, u_t) = im.point_kinematics_at(pt, u, gap);
            if (st.u_t - u_t).abs() > 1e-6 * u_max + 1e-12 {
                return Err(format!(
                    "{}: u_T = {} mm, but the displacements (section u) give {} mm",
                    at(),
                    num(st.u_t),
                    num(u_t)
                ));
            }
            let (p_n, k_n) = im.law.pressure(u_n);
            let (p_t, bound) = match &im.tangential {
                Some(law) => (law.eval(p_n, k_n, u_t, &st.slip).p_t, law.mu * p_n.max(0.0)),
                None => (0.0, 0.0),
            };
            if (st.p_t - p_t).abs() > 1e-3 * (p_t.abs() + bound) + 1e-9 {
                return Err(format!(
                    "{}: shear p_T = {} MPa, but its law gives {} MPa from its slip memory at the displacements of section u",
                    at(),
                    num(st.p_t),
                    num(p_t)
                ));
            }
        }
    }
    Ok(())
}

/// Values per interface point in the `contact` section of earlier builds.
const OLD_CONTACT: usize = 5;

/// A contact state a law can continue from: κ ≥ 0, and the kinematic
/// memory's stretch function as it stores one (η rising to 1), its
/// stretches within the slip range of any pressure a case allows; all
/// zero under the isotropic memory or without a tangential law.
fn check_contact_point(im: &InterfaceModel, i: usize, p: &ContactState) -> Decoded<()> {
    let at = || format!("section contact: interface point {} ({})", i + 1, im.name);
    if p.slip.kappa < 0.0 {
        return Err(format!(
            "{}: slip memory κ = {} (≥ 0 expected)",
            at(),
            num(p.slip.kappa)
        ));
    }
    let mem = &p.slip.mem;
    let kinematic = im
        .tangential
        .as_ref()
        .is_some_and(|t| t.memory == crate::interface::Memory::Kinematic);
    if !kinematic && *mem != Stretch::default() {
        return Err(format!(
            "{}: a kinematic slip memory in an interface without one (all {} memory values 0 expected)",
            at(),
            2 * MEMORY_POINTS
        ));
    }
    if !mem.is_valid() || mem.largest_ratio() > MAX_DISPLACEMENT {
        return Err(format!(
            "{}: the kinematic slip memory is no stretch function (breakpoints η rising in (0, 1] to 1, zeros after, stretches within ±{} mm)",
            at(),
            num(MAX_DISPLACEMENT)
        ));
    }
    Ok(())
}
