//! What a designer concludes from a run: the ratings of the standards a joint is designed to
//! (DIN 7190-1:2017 for interference fits, VDI 2230-1:2015 for bolted joints), the handbook's side
//! computed from the standard's own formulas ([`handbook`]) and set beside the numbers the run
//! measured.

pub mod handbook;
