//! Finite elements: the 8-node serendipity quad and the solid element.

pub mod q8;
pub mod solid;
