//! Finite elements: the 8-node serendipity quad and the solid element.

pub mod axisymmetric_twist;
pub mod dofs;
pub mod q8;
pub mod solid;

/// What turns an integral over the mesh plane into one over the body: the
/// thickness t of a plane model, or 2π r (the full revolution) of an
/// axisymmetric one, where x = r. Forces, areas and volumes of a plane model
/// are for its thickness, those of an axisymmetric model for the whole
/// revolution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Section {
    /// x is the radius r and the model is a body of revolution about x = 0.
    pub axisymmetric: bool,
    /// Thickness, mm (plane models; 1 in axisymmetry).
    pub thickness: f64,
}

impl Section {
    /// The out-of-plane measure at point x: t, or 2π r.
    pub fn measure(&self, x: [f64; 2]) -> f64 {
        if self.axisymmetric {
            std::f64::consts::TAU * x[0]
        } else {
            self.thickness
        }
    }
}
