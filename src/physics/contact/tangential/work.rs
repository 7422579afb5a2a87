//! The energy a point dissipates in one step: the work of its friction
//! forces on their own slips.
//!
//! A point of the law is a set of sliders: under the isotropic memory one
//! (force p_T, slip u_T^p), under the kinematic memory its Jenkins elements
//! (element i: force k_T^e mᵢ eᵢ, slip sᵢ = eᵢ,n + Δu_T − eᵢ,n+1, what the
//! return mapping clipped from its stretch; for the Iwan density a
//! continuum over η, integrated exactly). Per slider and step
//!
//! ```text
//!   ΔD = max(0, ½ (f_n + f_n+1)·s)          f: the slider's force, s: its slip
//! ```
//!
//! summed over the sliders (per unit area, MPa·mm).
//!
//! **Why the trapezoid.** The tangential work W = Σ ½ (p_T,n + p_T,n+1)·Δu_T
//! is a trapezoid sum; with the same rule per slider and k_T^e constant,
//! W = D + ΔU in every step, U = Σ ½ k_T^e mᵢ |eᵢ|² the energy the elements
//! store (isotropic: ½ |p_T|² / k_T^e): over a cycle that returns every slider
//! to its start D = W, the trapezoid area of the loop. Backward Euler
//! (f_n+1·s) would count the slip of a step where sliding starts at the
//! limit it reached (exact for that step) and break this identity by the
//! corners of the loop the trapezoid cuts.
//!
//! **Why never negative.** A slider's end force lies on its limit L_n+1 and
//! points along its slip; its start force is within its start limit L_n:
//! ½ (f_n·n + L_n+1) |s| ≥ ½ (L_n+1 − L_n) |s|, non-negative unless the
//! limit fell in the step (p_N dropped) while the slider reversed through
//! its whole range. Its slip then happened at the end limit after an elastic
//! reversal, and the trapezoid's negative value is an artefact of the rule:
//! it counts as zero.
//!
//! **What it replaces.** Until issue 42 the point's total shear was taken
//! on u_T^p = u_T − p_T/k_T^e: ½ (p_T,n + p_T,n+1)·Δu_T^p. That is the
//! slider's work only for the isotropic law. Under the kinematic memory
//! it is W minus the change of ½ k_T^e |Σ mᵢ eᵢ|² (one spring carrying the
//! whole shear), not of the elements' own Σ ½ k_T^e mᵢ |eᵢ|²: after a
//! reversal the elements pull against each other, the second falls less
//! than the first and the running D fell with it (the shipped
//! slideway-damping in 130 of its 291 increments). Over a closed cycle at
//! constant pressure both are W.
//!
//! An open point (p_N ≤ 0) releases its shear: its slip follows u_T and its
//! sliders dissipate the trapezoid of their last force on that slip.

use super::{Memory, SlipState, SlipState2, TangentialLaw};

/// One end of a step of a scalar point: the normal pressure p_N (MPa), u_T
/// (mm), p_T (MPa) and the law's history there.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Side<'a> {
    pub p_n: f64,
    pub u_t: f64,
    pub p_t: f64,
    pub slip: &'a SlipState,
}

/// One end of a step of a point of the vector law: p_N (MPa), u_T (mm) and
/// p_T (MPa) as vectors, the history there.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Side2<'a> {
    pub p_n: f64,
    pub u_t: [f64; 2],
    pub p_t: [f64; 2],
    pub slip: &'a SlipState2,
}

impl TangentialLaw {
    /// k_T^e at p_N, 0 where the point is open.
    fn stiffness_at(&self, p: f64) -> f64 {
        if p > 0.0 {
            self.elastic_stiffness(p).0
        } else {
            0.0
        }
    }

    /// The energy dissipated per unit area from `before` to `after`, the
    /// committed and the new state of one step (see the module comment),
    /// MPa·mm = N·mm/mm²; never negative.
    pub(crate) fn slip_work(&self, before: &Side, after: &Side) -> f64 {
        if self.memory == Memory::Isotropic {
            let slip = after.slip.u_p - before.slip.u_p;
            return (0.5 * (before.p_t + after.p_t) * slip).max(0.0);
        }
        let d = self.density();
        let (from, to) = (&before.slip.mem, &after.slip.mem);
        // the shift the return mapping applied (u_T^p + ∫ w e = u_T)
        let du = after.u_t - (before.slip.u_p + d.integral(from));
        let (k0, k1) = (self.stiffness_at(before.p_n), self.stiffness_at(after.p_n));
        d.slip_work(from, k0, du, to, k1)
    }

    /// [`TangentialLaw::slip_work`] of the vector law (dot products of
    /// force and slip).
    pub(crate) fn slip_work2(&self, before: &Side2, after: &Side2) -> f64 {
        if self.memory == Memory::Isotropic {
            let (a, b) = (before.slip.u_p, after.slip.u_p);
            let w = (0..2)
                .map(|i| 0.5 * (before.p_t[i] + after.p_t[i]) * (b[i] - a[i]))
                .sum::<f64>();
            return w.max(0.0);
        }
        let el = self.elements();
        let (from, to) = (&before.slip.mem, &after.slip.mem);
        let s0 = el.sum(from);
        let du = [
            after.u_t[0] - (before.slip.u_p[0] + s0[0]),
            after.u_t[1] - (before.slip.u_p[1] + s0[1]),
        ];
        let (k0, k1) = (self.stiffness_at(before.p_n), self.stiffness_at(after.p_n));
        el.slip_work(from, k0, du, to, k1)
    }
}
