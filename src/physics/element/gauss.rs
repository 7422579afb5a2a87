//! A Gauss rule: the points and weights every element family integrates
//! with ([`super::q8`], [`super::t6`]; chosen per family by
//! [`super::family::Family::rule`]).

/// Natural coordinates and weights (on [−1, 1]² for the quad, on the
/// reference triangle of area ½ for the triangle).
#[derive(Clone, Debug, PartialEq)]
pub struct GaussRule {
    pub points: Vec<([f64; 2], f64)>,
}
