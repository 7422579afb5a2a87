//! Studies and pictures: the paper's figures regenerated from our runs.

pub mod figures;
pub mod refine;
pub mod runner;
pub mod stability;
