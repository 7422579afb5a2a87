//! Why a load step failed: one type instead of a message plus flags on the
//! engine, so that the increment loop decides by matching (cut back, stop at
//! a signal, end the run) and the message is written in one place.

use crate::error::Error;
use std::fmt;

/// A failed load step. Every rank holds the same value (each variant is
/// decided collectively or carries a message shared from the lowest rank).
#[derive(Debug)]
pub enum StepFailure {
    /// An element could not be evaluated (its return mapping failed, or a
    /// fault was injected by `--inject-fault`): the message of the lowest rank
    /// that has one, naming the element and its body.
    Element(String),
    /// The residual is not finite.
    NotFinite { iteration: usize },
    /// The iteration limit was reached.
    NoConvergence {
        limit: usize,
        /// ‖R‖ / ‖F_ref‖ and the displacement test's error over ‖u‖∞.
        residual: f64,
        correction: f64,
        /// An interface pair changed status in the last iteration.
        status_changing: bool,
    },
    /// The residual grew beyond any use.
    Diverged { iteration: usize, residual: f64 },
    /// The linear solve failed (a singular tangent, a non-finite matrix, memory).
    Linear(Error),
    /// A second stop request (SIGINT/SIGTERM on any rank) abandoned the step.
    Interrupted { iteration: usize, signal: i32 },
    /// The nonlinear solver (PETSc SNES) stopped on its own, with its reason.
    Solver(String),
    /// A body held only through the interface could not be held (the contact
    /// stabilization, `super::stabilize`): the cause in physical terms.
    Unheld(String),
}

impl StepFailure {
    /// The signal that abandoned the step, if one did.
    pub fn signal(&self) -> Option<i32> {
        match self {
            StepFailure::Interrupted { signal, .. } => Some(*signal),
            _ => None,
        }
    }

    /// A failure that a smaller step cannot cure: the run ends with it.
    pub(crate) fn is_fatal(&self) -> bool {
        matches!(self, StepFailure::Linear(Error::Memory(_)))
    }

    /// The error that ends a run on a fatal failure.
    pub(crate) fn into_error(self) -> Error {
        match self {
            StepFailure::Linear(e) => e,
            other => Error::Solver(other.to_string()),
        }
    }
}

impl fmt::Display for StepFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StepFailure::Element(m) | StepFailure::Solver(m) | StepFailure::Unheld(m) => {
                f.write_str(m)
            }
            StepFailure::NotFinite { iteration } => {
                write!(f, "residual is not finite at iteration {iteration}")
            }
            StepFailure::NoConvergence {
                limit,
                residual,
                correction,
                status_changing,
            } => write!(
                f,
                "no convergence in {limit} iterations (|R|/|F| = {residual:.3e}, |du|/|u| = {correction:.3e}{})",
                if *status_changing {
                    ", contact status still changing"
                } else {
                    ""
                }
            ),
            StepFailure::Diverged {
                iteration,
                residual,
            } => write!(
                f,
                "diverged at iteration {iteration} (|R|/|F| = {residual:.3e})"
            ),
            StepFailure::Linear(e) => write!(f, "{e}"),
            StepFailure::Interrupted { iteration, .. } => {
                write!(f, "interrupted at iteration {iteration}")
            }
        }
    }
}
