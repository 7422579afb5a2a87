//! The options of `asperity run` (the command line's, or a study's).

use crate::input::case::Method;
use crate::progress::LogFormat;
use std::path::PathBuf;

/// Options of `asperity run`.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    pub out: Option<PathBuf>,
    pub quiet: bool,
    pub method: Option<Method>,
    pub refine: Option<usize>,
    /// Override: equal load steps (drops the case's first_increment / load_factors).
    pub increments: Option<usize>,
    pub max_cutbacks: Option<usize>,
    /// Override: ungraded mesh (every size ratio 1) with the same element counts.
    pub uniform: bool,
    /// Override: plain fixed-matrix iterations (no Anderson acceleration).
    pub plain: bool,
    /// Override: fixed or automatic load steps.
    pub step_control: Option<crate::input::case::StepControl>,
    /// Override: `[solver] interface_loop` (`--interface-loop on|off`).
    pub interface_loop: Option<bool>,
    /// Override: friction scheme of every tangential law.
    pub friction_scheme: Option<crate::input::case::settings::FrictionScheme>,
    /// Continue from the `restart.bin` in this output folder.
    pub restart: Option<PathBuf>,
    /// Progress line format.
    pub log_format: LogFormat,
    /// PETSc backend only: drive the steps with SNES (default) or the built-in loop.
    pub snes: bool,
    /// PETSc backend only: the memory-lean GAMG settings (`--memory lean`).
    pub lean_memory: bool,
    /// Threads of this process (`--threads`, `ASPERITY_THREADS`; see
    /// [`crate::threads`]); `None`: every core on one process, one per rank
    /// under MPI.
    pub threads: Option<usize>,
    /// `--adapt TOL`: an adaptive run to this relative estimate (the case's
    /// `[adapt]` table with its tolerance replaced, else the energy norm).
    pub adapt: Option<f64>,
    /// What tests and benchmarks ask of a run (not options of a user).
    #[doc(hidden)]
    pub hooks: Hooks,
}

/// Test and benchmark hooks of a run: failures injected, early stops,
/// another factorization. Hidden from the public options; the command
/// line's `--inject-fault` and `--stop-after` set them.
#[derive(Clone, Debug, Default)]
pub struct Hooks {
    /// Make the element loop fail on (rank, assembly number).
    pub fault: Option<(usize, usize)>,
    /// Stop (like SIGINT, but exit 3) after this many increments.
    pub stop_after: Option<usize>,
    /// Serial backend only (benchmarks): this factorization instead of the
    /// one the model's tangent calls for.
    pub factorization: Option<crate::linalg::backend::serial::Factorization>,
}
