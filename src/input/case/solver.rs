//! The `[solver]` table of a case: the iteration method and its limits, the
//! step control and its schedule, tolerances, acceleration, the line search and
//! the interface loop, the contact stabilization (its enums in `settings`).

use super::{Acceleration, Method, Stabilization, StepControl};
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    #[serde(default)]
    pub method: Method,
    /// "fixed" or "auto"; default: auto when the case gives no schedule
    /// (`increments`, `first_increment`, `load_factors`), else fixed. See
    /// [`SolverSpec::step_mode`].
    pub step_control: Option<StepControl>,
    /// Auto: the largest load-factor step (default 0.25).
    pub max_increment: Option<f64>,
    /// Auto: the target of the largest equivalent plastic strain increment of a step.
    #[serde(default = "default_plastic_strain_step")]
    pub(crate) plastic_strain_step: f64,
    /// Number of equal load steps from 0 to 1 (after the first one); default 20.
    /// Read it with `SolverSpec::n_increments`.
    pub increments: Option<usize>,
    /// Size of the first load step (the paper uses about 5%); default 1/increments.
    pub first_increment: Option<f64>,
    /// Explicit load factors instead of increments; may decrease (unloading).
    pub load_factors: Option<Vec<f64>>,
    /// Iteration limit per attempt; default 30 (full Newton) or 400 (others).
    pub(crate) max_iterations: Option<usize>,
    /// ‖R‖ ≤ tol · ‖F_ref‖.
    #[serde(default = "default_residual_tol")]
    pub residual_tolerance: f64,
    /// ‖Δu‖∞ ≤ tol · ‖u‖∞.
    #[serde(default = "default_displacement_tol")]
    pub displacement_tolerance: f64,
    /// Halvings allowed for one scheduled increment.
    #[serde(default = "default_cutbacks")]
    pub max_cutbacks: usize,
    /// "none" or "anderson": acceleration of the fixed-matrix methods (modified
    /// Newton, initial stiffness); full Newton is never accelerated.
    #[serde(default)]
    pub acceleration: Acceleration,
    /// History depth of Anderson acceleration.
    #[serde(default = "default_anderson_depth")]
    pub(crate) anderson_depth: usize,
    /// Locate the load of first yield by root finding inside the increment where it occurs.
    #[serde(default = "super::yes")]
    pub(crate) locate_first_yield: bool,
    /// Full Newton: a backtracking line search on the residual norm
    /// (`solve::newton::StepProblem`); on by default (issue 29,
    /// docs/performance.md "Contact status convergence").
    #[serde(default = "super::yes")]
    pub line_search: bool,
    /// Full Newton, serial: within each Newton iteration, the interface law
    /// solved exactly on the tangent condensed on the interface equations
    /// (`solve::newton::interface_loop`; docs/performance.md, "Contact
    /// status convergence"). Read it with [`SolverSpec::interface_loop`].
    pub interface_loop: Option<bool>,
    /// "auto" or "off": contact stabilization of bodies held only through open
    /// interface pairs, or at zero load (see `solve::stabilize`).
    #[serde(default)]
    pub stabilization: Stabilization,
    /// Largest allowed ratio of the energy dissipated by the stabilization to
    /// the largest internal energy of the run; default 1e-3.
    #[serde(default = "default_stabilization_energy")]
    pub stabilization_energy: f64,
}

/// `[solver] interface_loop` where the case does not say
/// (docs/performance.md, "The interface loop (2026-11-27)").
pub(crate) const INTERFACE_LOOP_DEFAULT: bool = true;

impl SolverSpec {
    /// Whether the interface loop is asked for (the case's key, else
    /// `INTERFACE_LOOP_DEFAULT`).
    pub fn interface_loop(&self) -> bool {
        self.interface_loop.unwrap_or(INTERFACE_LOOP_DEFAULT)
    }

    /// The scheduled load factors: explicit list, or a first step then equal steps to 1.
    pub fn schedule(&self) -> Vec<f64> {
        if let Some(l) = &self.load_factors {
            return l.clone();
        }
        let n = self.n_increments();
        match self.first_increment {
            Some(f) if f < 1.0 && n > 1 => {
                let mut v = vec![f];
                let rest = n - 1;
                v.extend((1..=rest).map(|i| f + (1.0 - f) * i as f64 / rest as f64));
                v
            }
            _ => (1..=n).map(|i| i as f64 / n as f64).collect(),
        }
    }

    /// Equal load steps of the fixed schedule (default 20).
    pub(crate) fn n_increments(&self) -> usize {
        self.increments.unwrap_or(20)
    }

    /// The step control in force: as given, else automatic when the case gives
    /// no schedule of its own.
    pub fn step_mode(&self) -> StepControl {
        self.step_control.unwrap_or(
            if self.increments.is_none()
                && self.first_increment.is_none()
                && self.load_factors.is_none()
            {
                StepControl::Auto
            } else {
                StepControl::Fixed
            },
        )
    }

    pub(crate) fn iteration_limit(&self) -> usize {
        self.max_iterations.unwrap_or(match self.method {
            Method::FullNewton => 30,
            _ => 400,
        })
    }
}

impl Default for SolverSpec {
    fn default() -> Self {
        toml::from_str("").expect("the empty solver table has only defaults")
    }
}

pub(crate) fn default_plastic_strain_step() -> f64 {
    2e-3
}
fn default_residual_tol() -> f64 {
    1e-8
}
fn default_displacement_tol() -> f64 {
    1e-8
}
fn default_stabilization_energy() -> f64 {
    1e-3
}
fn default_anderson_depth() -> usize {
    5
}
fn default_cutbacks() -> usize {
    8
}
