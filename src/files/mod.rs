//! Files a run writes and reads back: the output folder ([`output`]), the
//! restart file ([`restart`]) and the charts ([`plot`]).

pub mod output;
pub mod plot;
pub mod restart;
