//! The jobs behind the command line: `run` and `check` ([`driver`]),
//! adaptive runs ([`adapt`]), studies ([`study`]), `calibrate`
//! ([`calibrate`]), the calculation report of a finished output folder
//! ([`report`]) and the MPI entry (`parallel`).

pub mod adapt;
pub mod applied;
pub mod calibrate;
pub mod driver;
pub mod options;
#[cfg(feature = "parallel")]
pub mod parallel;
pub mod ratings;
pub mod report;
pub mod study;
