//! A Gauss rule in three dimensions: the points and weights the solid
//! element families integrate with ([`super::h20`] on [−1, 1]³,
//! [`super::t10`] on the reference tetrahedron of volume ⅙).

/// Natural coordinates (ξ, η, ζ) and weights (on [−1, 1]³ for the hexahedron,
/// on the reference tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) of volume ⅙
/// for the tetrahedron: the weights sum to the reference volume).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct GaussRule3 {
    pub(crate) points: Vec<([f64; 3], f64)>,
}
