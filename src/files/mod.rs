//! Files a run writes and reads back: the output folder ([`output`]), the
//! restart file ([`restart`]), the charts ([`plot`]) and the rules for
//! reading a folder not written by this run (`inside`).

pub(crate) mod inside;
pub mod output;
pub mod plot;
pub mod restart;
