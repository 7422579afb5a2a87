//! The interface points' contact states of a restart file: 25 values a
//! point (56 with twist, the vector law's), each state one its law can
//! continue from and the one its law gives at the committed displacements.

use super::*;
use crate::model::interface::InterfaceModel;
use crate::physics::contact::{PointState as ContactState, Stretch, MEMORY_POINTS};

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
    // twist and 3D: the vector law's layout
    let twist = model.node_dofs().vector_slip();
    let width = ContactState::packed_len(twist);
    for (i, ((p, v), im)) in contact
        .iter_mut()
        .zip(s.finite("contact", Some(width * np))?.chunks_exact(width))
        .zip(laws)
        .enumerate()
    {
        *p = ContactState::unpack_as(v, twist);
        if twist {
            check_vector_point(im, i, p)?;
        } else {
            check_contact_point(im, i, p)?;
        }
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
            if im.node_dofs.vector_slip() {
                check_vector_against_u(im, pt, u, gap, u_max, st)
                    .map_err(|m| format!("{}: {m}", at()))?;
                continue;
            }
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
        .is_some_and(|t| t.memory == crate::physics::contact::Memory::Kinematic);
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

/// A twisting model's contact state ([`ContactState::pack_twist`]): the
/// vector law's state one the law can continue from
/// ([`crate::physics::contact::tangential::SlipState2::check`]), p_Tθ and u_Tθ
/// finite (the section is), nothing of the scalar state.
fn check_vector_point(im: &InterfaceModel, i: usize, p: &ContactState) -> Decoded<()> {
    let at = || format!("section contact: interface point {} ({})", i + 1, im.name);
    p.slip2
        .check(im.tangential.as_ref(), MAX_DISPLACEMENT)
        .map_err(|m| format!("{}: {m}", at()))
}

/// A twisting model's state against the committed displacements: u_T and
/// u_Tθ as they give them, p_T and p_Tθ as the vector law gives them there.
fn check_vector_against_u(
    im: &InterfaceModel,
    pt: &crate::model::interface::Point,
    u: &[f64],
    gap: f64,
    u_max: f64,
    st: &ContactState,
) -> std::result::Result<(), String> {
    let (u_n, u_t) = im.point_kinematics_at(pt, u, gap);
    let u_h = im.point_second_slip(pt, u);
    for (name, got, want) in [("u_T", st.u_t, u_t), ("u_Tθ", st.u_h, u_h)] {
        if (got - want).abs() > 1e-6 * u_max + 1e-12 {
            return Err(format!(
                "{name} = {} mm, but the displacements (section u) give {} mm",
                num(got),
                num(want)
            ));
        }
    }
    let (p_n, k_n) = im.law.pressure(u_n);
    let (p, bound) = match &im.tangential {
        Some(law) => (
            law.eval_vector(p_n, k_n, [u_t, u_h], &st.slip2).p_t,
            law.mu * p_n.max(0.0),
        ),
        None => ([0.0; 2], 0.0),
    };
    for (name, got, want) in [("p_T", st.p_t, p[0]), ("p_Tθ", st.p_h, p[1])] {
        if (got - want).abs() > 1e-3 * (want.abs() + bound) + 1e-9 {
            return Err(format!(
                "shear {name} = {} MPa, but its law gives {} MPa from its slip memory at the displacements of section u",
                num(got),
                num(want)
            ));
        }
    }
    Ok(())
}
