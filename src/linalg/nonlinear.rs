//! The seam between one load step's nonlinear problem and the solver that
//! iterates on it.
//!
//! A load step (paper eq. 4.1-4.8) is a [`Problem`]: it evaluates the residual
//! over the free equations at an iterate (and, in the same pass, assembles the
//! tangent of the step's method into the backend), judges convergence with the
//! paper's rules (residual, correction, unchanged contact statuses), and may
//! modify a Newton correction (Anderson mixing of the fixed-matrix methods).
//!
//! Two solvers drive it: the built-in loop in `super::newton` (serial faer and
//! PETSc), and PETSc's SNES (`--nonlinear snes`, the default on the PETSc
//! backend), whose callbacks call the same three methods. Both therefore take the
//! same iterates, statuses and decisions.

/// What a problem says after an evaluation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Not converged yet: solve for a correction and go on.
    Continue,
    /// Converged or failed; the problem holds which (and why).
    Stop,
}

pub trait Problem {
    /// The starting iterate (free equations, the model's equation order).
    fn initial(&self) -> Vec<f64>;
    /// Residual at `x` into `r` (both replicated, equation order); assembles the
    /// step's tangent at `x` into the backend. `false` when the evaluation
    /// failed (e.g. a return mapping); the problem keeps the message.
    fn evaluate(&mut self, x: &[f64], r: &mut [f64]) -> bool;
    /// Judges the last evaluation; `it` counts the corrections made so far.
    fn verdict(&mut self, it: usize) -> Verdict;
    /// The correction `du` about to be added to `x` (may be changed in place, as
    /// Anderson mixing and the interface loop do); counts the iteration.
    /// `whole`: `du` is the whole Newton correction −K⁻¹R (not a line
    /// search's fraction of it), which the interface loop needs.
    fn correct(&mut self, x: &[f64], du: &mut [f64], whole: bool);
    /// The problem has stopped (converged or failed).
    fn stopped(&self) -> bool;
    /// The problem has stopped converged.
    fn converged(&self) -> bool;
    /// Time spent inside `evaluate`, seconds (for the solve-time split).
    fn evaluate_seconds(&self) -> f64;
}

/// A nonlinear solver other than the built-in loop (PETSc SNES).
pub trait NonlinearSolver {
    /// "snes".
    fn name(&self) -> &'static str;
    /// Iterates from `problem.initial()` until the problem says stop. An `Err`
    /// is a failure of the solver itself (linear solve, line search).
    fn solve(&mut self, problem: &mut dyn Problem) -> Result<(), super::failure::StepFailure>;
    /// The linear solver inside, when it is not the backend's.
    fn linear_solver(&self) -> Option<String> {
        None
    }
    /// Counters reported in summary.json under "backend_stats" (added to the
    /// backend's counters of the same name).
    fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        Vec::new()
    }
}
