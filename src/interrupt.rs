//! SIGINT / SIGTERM handling for `asperity run`.
//!
//! The handler only counts signals and remembers the first one (atomics, which
//! are async-signal-safe); the solver polls them:
//! * 1st signal: the run stops at the next increment boundary and writes every
//!   converged increment ([`requested`] ≥ 1, checked by the increment loop);
//! * 2nd signal: the increment in progress is abandoned at its next Newton
//!   iteration ([`requested`] ≥ 2, checked inside the Newton loop) and the
//!   converged part is still written;
//! * 3rd signal: the process exits at once with 128 + signal (the output folder
//!   is left untouched; the hidden `.NAME.partial-PID` folder may remain).
//!
//! Under MPI every rank polls through `crate::linalg::backend::Backend::max`, so a
//! signal seen by any rank stops all of them at the same point.

use std::sync::atomic::{AtomicI32, AtomicUsize, Ordering};
use std::sync::Once;

static COUNT: AtomicUsize = AtomicUsize::new(0);
static FIRST: AtomicI32 = AtomicI32::new(0);
static INSTALL: Once = Once::new();

pub const SIGINT: i32 = signal_hook::consts::SIGINT;
pub const SIGTERM: i32 = signal_hook::consts::SIGTERM;

fn on_signal(sig: i32) {
    let _ = FIRST.compare_exchange(0, sig, Ordering::SeqCst, Ordering::SeqCst);
    if COUNT.fetch_add(1, Ordering::SeqCst) >= 2 {
        // third signal: the user insists
        signal_hook::low_level::exit(128 + sig);
    }
}

/// Installs the SIGINT and SIGTERM handlers (once per process).
#[allow(unsafe_code)] // signal_hook's registration, see the SAFETY note
pub fn install() -> std::io::Result<()> {
    let mut result = Ok(());
    INSTALL.call_once(|| {
        for sig in [SIGINT, SIGTERM] {
            // SAFETY: the handler only touches atomics and, on the third signal,
            // calls `_exit` through signal_hook::low_level::exit; all of these are
            // async-signal-safe.
            if let Err(e) = unsafe { signal_hook::low_level::register(sig, move || on_signal(sig)) }
            {
                result = Err(e);
            }
        }
    });
    result
}

/// How many stop requests were received (0: none) in this process.
pub fn requested() -> usize {
    COUNT.load(Ordering::SeqCst)
}

/// The first signal received (0: none).
pub(crate) fn first_signal() -> i32 {
    FIRST.load(Ordering::SeqCst)
}

/// Why a run stopped before its last increment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// A signal (SIGINT, SIGTERM).
    Signal(i32),
    /// The hidden `--stop-after N` test option.
    StopAfter(usize),
    /// A body held about the axis only by friction could no longer hold
    /// the torque on it (the `torque_limit` event): the load history has no
    /// equilibrium past it, so a resumed run would stop there again.
    TorqueLimit,
}

impl Stop {
    /// "SIGINT", "SIGTERM", "stop-after" or "torque_limit".
    pub fn name(self) -> String {
        match self {
            Stop::Signal(SIGINT) => "SIGINT".into(),
            Stop::Signal(SIGTERM) => "SIGTERM".into(),
            Stop::Signal(s) => format!("signal {s}"),
            Stop::StopAfter(_) => "stop-after".into(),
            Stop::TorqueLimit => "torque_limit".into(),
        }
    }

    /// Exit status of the process: 128 + signal, 3 for `--stop-after`, 4
    /// at a torque limit.
    pub fn exit_code(self) -> u8 {
        match self {
            Stop::Signal(s) => (128 + s).clamp(0, 255) as u8,
            Stop::StopAfter(_) => 3,
            Stop::TorqueLimit => 4,
        }
    }

    /// Whether the run may be resumed past where it stopped: not past a
    /// physical end of its load history.
    pub fn resumable(self) -> bool {
        self != Stop::TorqueLimit
    }
}
