//! Post-processing of converged states: the a posteriori error estimate
//! ([`estimate`]).

pub mod estimate;
