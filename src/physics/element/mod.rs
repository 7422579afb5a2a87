//! Finite elements: the element families (the 8-node serendipity quad and
//! the 6-node triangle, [`family::Family`]) and the solid element built on
//! them.

pub(crate) mod axisymmetric_twist;
pub mod dofs;
pub mod edge;
pub(crate) mod face;
pub mod family;
pub(crate) mod family3;
pub mod gauss;
pub(crate) mod gauss3;
pub(crate) mod h20;
pub mod q8;
#[cfg(test)]
mod shape_checks;
pub mod solid;
pub(crate) mod solid3;
pub(crate) mod t10;
pub mod t6;

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

/// Internal force and (optionally) tangent of one element. `trial` receives the
/// updated Gauss point states. `thermal` is the free thermal strain α ΔT of
/// the element's body, subtracted from the normal strains before the
/// material's update (0: none). Errors name the Gauss point.
///
/// The element's dofs are `ue.len()` (= `fe.len()`, `ke.len()` = its square):
/// two per node (`NodeDofs::PLANE`: 16 for the quad, 12 for the triangle),
/// or three in an axisymmetric model with twist (`NodeDofs::TWIST`,
/// `crate::physics::element::axisymmetric_twist`).
#[allow(clippy::too_many_arguments)]
pub fn element_forces<'m>(
    geom: &solid::ElementGeometry,
    mat: impl Into<crate::physics::material::PointMaterials<'m>>,
    thermal: &[f64],
    ue: &[f64],
    committed: &[crate::physics::material::PointState],
    trial: &mut [crate::physics::material::PointState],
    response: solid::Response,
    tangent: Option<solid::Tangent>,
    fe: &mut [f64],
    ke: &mut [f64],
) -> Result<(), String> {
    let mat = mat.into();
    if ue.len() == dofs::NodeDofs::TWIST.per_node() * geom.nodes {
        if mat.plane() != crate::physics::material::Plane::Axisymmetric {
            return Err("three dofs per node need an axisymmetric model (twist)".into());
        }
        return axisymmetric_twist::forces(
            geom, mat, thermal, ue, committed, trial, response, tangent, fe, ke,
        );
    }
    solid::forces(
        geom, mat, thermal, ue, committed, trial, response, tangent, fe, ke,
    )
}

/// The Gauss point geometry of one element, plane or solid: what the
/// element loop and the measures ask of an element whatever its dimension.
/// Built on the stack and used once per element (a boxed solid variant
/// would allocate per element in the assembly).
#[allow(clippy::large_enum_variant)]
pub(crate) enum Geometry {
    Plane(solid::ElementGeometry),
    Solid(solid3::ElementGeometry3),
}

impl Geometry {
    /// Where Gauss point `ip` is, in space (z = 0 for a plane element).
    pub(crate) fn x(&self, ip: usize) -> [f64; 3] {
        match self {
            Geometry::Plane(g) => [g.x[ip][0], g.x[ip][1], 0.0],
            Geometry::Solid(g) => g.x[ip],
        }
    }

    /// The volume each Gauss point stands for, mm³ (a plane element's with
    /// its out-of-plane measure).
    pub(crate) fn dv(&self) -> &[f64] {
        match self {
            Geometry::Plane(g) => &g.dv[..g.n],
            Geometry::Solid(g) => &g.dv[..g.n],
        }
    }

    /// Internal force and (optionally) tangent of the element, `thermal` the
    /// free thermal strain α ΔT of its body ([`element_forces`] for a plane one, [`solid3::forces3`] for a solid).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn forces(
        &self,
        mat: crate::physics::material::PointMaterials<'_>,
        thermal: &[f64],
        ue: &[f64],
        committed: &[crate::physics::material::PointState],
        trial: &mut [crate::physics::material::PointState],
        response: solid::Response,
        tangent: Option<solid::Tangent>,
        fe: &mut [f64],
        ke: &mut [f64],
    ) -> Result<(), String> {
        match self {
            Geometry::Plane(g) => element_forces(
                g, mat, thermal, ue, committed, trial, response, tangent, fe, ke,
            ),
            Geometry::Solid(g) => solid3::forces3(
                g, mat, thermal, ue, committed, trial, response, tangent, fe, ke,
            ),
        }
    }
}
