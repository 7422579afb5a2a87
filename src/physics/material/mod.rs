//! Von Mises (Huber-Mises) plasticity with linear isotropic hardening
//! (paper eqs 3.8-3.14), plane strain, plane stress and axisymmetry, small strain.
//!
//! ```text
//!   f = √(3 J₂) − σ_y(ε̄ᵖ),   σ_y = σ_Y + H ε̄ᵖ,   εᵖ̇ = γ̇ ∂f/∂σ   (3.8, 3.11)
//!   C_ep = C − (C:n ⊗ n:C) / (h + n:C:n),   n = √(3/2) s/σ_y        (3.13, 3.14)
//! ```
//! `hardening` is the plastic modulus H (slope of σ_y against ε̄ᵖ). With the unit
//! normal n of (3.14), n:C:n = 2G and the paper's h in (3.13) is h = 2H/3; the
//! uniaxial tangent modulus is E H/(E + H).
//!
//! * Plane strain (ε_zz = 0) and axisymmetry (x = r, y = z): one radial return
//!   (Simo & Hughes, eqs 3.8-3.11) in the 4 components (xx, yy, zz, xy), closed
//!   form for linear hardening, with its algorithmic tangent (module `radial`).
//!   The out-of-plane strain is given: 0 in plane strain, the hoop strain
//!   ε_θθ = u_r/r in axisymmetry (`VonMises::update_axisymmetric`, 4×4 tangents).
//! * Plane stress (σ_zz = 0): the projected return of Simo & Taylor in the
//!   plane-stress subspace, a scalar Newton iteration for Δγ, and its consistent
//!   tangent; not a 3D return with σ_zz forced afterwards.
//!
//! Strains are total ([εxx, εyy, γxy], engineering shear); the update starts from
//! the committed plastic strain, so it is path-independent within a load step.

mod plane_stress;
mod radial;
mod six_components;
mod storage;

#[cfg(test)]
mod tests;

use nalgebra::{Matrix3, Matrix4, Matrix6};
use std::fmt;

pub(crate) use storage::{GaussMut, GaussRef, GaussStates};

/// The idealization of the model (the case's `[model] plane`: "stress",
/// "strain", "axisymmetric" or "3d").
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Plane {
    /// σ_zz = 0 (thin bodies; the thickness scales the forces).
    Stress,
    /// ε_zz = 0 (long bodies; solved per unit thickness unless one is given).
    Strain,
    /// A body of revolution about x = 0 (x = r, y = z), loaded symmetrically:
    /// the fourth strain and stress component is the hoop one (θθ), and every
    /// integral is over the full revolution.
    Axisymmetric,
    /// Three-dimensional solids: six strain and stress components, the
    /// general return (`VonMises::update_twist`, which consults no plane).
    #[serde(rename = "3d")]
    Solid,
}

/// State at one Gauss point, committed at the end of a converged increment
/// (stored in a `GaussStates`, which keeps the twist components only in a
/// model with twist).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointState {
    /// σxx, σyy, σxy, σzz (σzz = 0 in plane stress; the hoop stress σ_θθ in
    /// axisymmetry, where x = r and y = z), then σ_rθ, σ_zθ: the shear
    /// stresses of twist (0 without it).
    pub stress: [f64; 6],
    /// εᵖxx, εᵖyy, εᵖxy (tensor component), εᵖzz, then εᵖ_rθ, εᵖ_zθ (tensor
    /// components; 0 without twist).
    pub(crate) plastic_strain: [f64; 6],
    /// Accumulated equivalent plastic strain ε̄ᵖ.
    pub peeq: f64,
    /// The update that produced this state was plastic (Δγ > 0).
    pub yielding: bool,
}

impl PointState {
    /// Doubles per state in [`PointState::pack`] without twist.
    pub const PACKED: usize = 10;
    /// Doubles per state with twist: the shear stresses and plastic strains
    /// of u_θ follow.
    pub(crate) const PACKED_TWIST: usize = 14;

    /// Doubles per state in a model with (or without) twist.
    pub(crate) fn packed_len(twist: bool) -> usize {
        if twist {
            Self::PACKED_TWIST
        } else {
            Self::PACKED
        }
    }

    /// σ (4), εᵖ (4), ε̄ᵖ, yielding as 0/1, then σ_rθ, σ_zθ, εᵖ_rθ, εᵖ_zθ:
    /// the layout of restart files and of the MPI gather of Gauss states. A
    /// model without twist uses the first [`PointState::PACKED`] values (the
    /// layout from before twist), one with twist all of them.
    pub fn pack(&self) -> [f64; Self::PACKED_TWIST] {
        let mut v = [0.0; Self::PACKED_TWIST];
        v[..4].copy_from_slice(&self.stress[..4]);
        v[4..8].copy_from_slice(&self.plastic_strain[..4]);
        v[8] = self.peeq;
        v[9] = f64::from(u8::from(self.yielding));
        v[10..12].copy_from_slice(&self.stress[4..]);
        v[12..14].copy_from_slice(&self.plastic_strain[4..]);
        v
    }

    /// The inverse of [`PointState::pack`] for `width` values
    /// ([`PointState::packed_len`]; `v` holds at least that many).
    pub(crate) fn unpack(v: &[f64], width: usize) -> Self {
        let (t, p) = if width >= Self::PACKED_TWIST {
            ([v[10], v[11]], [v[12], v[13]])
        } else {
            ([0.0; 2], [0.0; 2])
        };
        PointState {
            stress: [v[0], v[1], v[2], v[3], t[0], t[1]],
            plastic_strain: [v[4], v[5], v[6], v[7], p[0], p[1]],
            peeq: v[8],
            yielding: v[9] > 0.5,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct VonMises {
    pub young: f64,
    pub poisson: f64,
    pub yield_stress: f64,
    pub hardening: f64,
    pub plane: Plane,
}

/// The material of each Gauss point of an element: one for all of them (a
/// body at one temperature, or without tables of its properties), or one
/// per point (a body whose E or σ_Y follow a temperature field:
/// docs/theory.md, "Thermal strain"). A per-point slice holds a material
/// for every point of the element.
#[derive(Clone, Copy, Debug)]
pub enum PointMaterials<'a> {
    Uniform(&'a VonMises),
    PerPoint(&'a [VonMises]),
}

impl<'a> PointMaterials<'a> {
    /// Gauss point `ip`'s material.
    pub fn at(self, ip: usize) -> &'a VonMises {
        match self {
            PointMaterials::Uniform(m) => m,
            PointMaterials::PerPoint(m) => &m[ip],
        }
    }

    /// The plane setting, one for every point.
    pub fn plane(self) -> Plane {
        self.at(0).plane
    }
}

impl<'a> From<&'a VonMises> for PointMaterials<'a> {
    fn from(m: &'a VonMises) -> Self {
        PointMaterials::Uniform(m)
    }
}

/// A return mapping that failed to converge.
#[derive(Clone, Debug, PartialEq)]
pub struct ReturnMapError {
    pub iterations: usize,
    pub residual: f64,
    pub reason: String,
}

impl fmt::Display for ReturnMapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "return mapping failed after {} iterations (|φ| = {:.3e}): {}",
            self.iterations, self.residual, self.reason
        )
    }
}

impl std::error::Error for ReturnMapError {}

impl VonMises {
    /// Checks E > 0, −1 < ν < 0.5, σ_Y > 0 (may be +∞: elastic), H ≥ 0.
    pub fn new(
        young: f64,
        poisson: f64,
        yield_stress: f64,
        hardening: f64,
        plane: Plane,
    ) -> Result<Self, String> {
        if !(young.is_finite() && young > 0.0) {
            return Err(format!("young = {young} must be a positive number (MPa)"));
        }
        if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
            return Err(format!("poisson = {poisson} must be in (-1, 0.5)"));
        }
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN must be rejected too
        if !(yield_stress > 0.0) {
            return Err(format!(
                "yield_stress = {yield_stress} must be a positive number (MPa)"
            ));
        }
        if !(hardening.is_finite() && hardening >= 0.0) {
            return Err(format!(
                "hardening = {hardening} must be a non-negative number (MPa)"
            ));
        }
        Ok(VonMises {
            young,
            poisson,
            yield_stress,
            hardening,
            plane,
        })
    }

    pub(crate) fn shear_modulus(&self) -> f64 {
        self.young / (2.0 * (1.0 + self.poisson))
    }

    pub(crate) fn bulk_modulus(&self) -> f64 {
        self.young / (3.0 * (1.0 - 2.0 * self.poisson))
    }

    /// In-plane elastic matrix D: [σxx σyy σxy] = D [εxx εyy γxy] (in
    /// axisymmetry: at zero hoop strain, the plane-strain matrix).
    pub fn elastic_matrix(&self) -> Matrix3<f64> {
        let (e, nu) = (self.young, self.poisson);
        match self.plane {
            Plane::Stress => {
                let c = e / (1.0 - nu * nu);
                Matrix3::new(
                    c,
                    c * nu,
                    0.0,
                    c * nu,
                    c,
                    0.0,
                    0.0,
                    0.0,
                    c * (1.0 - nu) / 2.0,
                )
            }
            Plane::Strain | Plane::Axisymmetric | Plane::Solid => {
                let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                Matrix3::new(
                    c * (1.0 - nu),
                    c * nu,
                    0.0,
                    c * nu,
                    c * (1.0 - nu),
                    0.0,
                    0.0,
                    0.0,
                    c * (1.0 - 2.0 * nu) / 2.0,
                )
            }
        }
    }

    /// σ_Y + H ε̄ᵖ.
    pub(crate) fn current_yield(&self, state: &PointState) -> f64 {
        self.yield_stress + self.hardening * state.peeq
    }

    /// √(3 J₂) of [σxx, σyy, σxy, σzz, σ_rθ, σ_zθ] (the last two 0 without
    /// twist, which leaves the value unchanged to the bit).
    pub(crate) fn equivalent_stress(s: &[f64; 6]) -> f64 {
        let (xx, yy, xy, zz) = (s[0], s[1], s[2], s[3]);
        let twist = 3.0 * (s[4] * s[4] + s[5] * s[5]);
        (0.5 * ((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2)) + 3.0 * xy * xy + twist)
            .sqrt()
    }

    /// Return mapping from `committed` for the total strain; returns the new state
    /// and the algorithmic tangent dσ/dε (in-plane, engineering shear).
    pub fn update(
        &self,
        committed: &PointState,
        strain: &[f64; 3],
    ) -> Result<(PointState, Matrix3<f64>), ReturnMapError> {
        self.update_thermal(committed, strain, 0.0)
    }

    /// [`VonMises::update`] with the free thermal strain `thermal` = α ΔT
    /// (an eigenstrain on every normal component, docs/theory.md "Thermal
    /// strain"): the return sees the mechanical strain ε − α ΔT. In plane
    /// stress the in-plane normals lose α ΔT and the thickness is free; in
    /// plane strain the total ε_zz is 0, so its mechanical part is −α ΔT.
    /// The tangent is that of the mechanical strain (α ΔT is prescribed).
    pub fn update_thermal(
        &self,
        committed: &PointState,
        strain: &[f64; 3],
        thermal: f64,
    ) -> Result<(PointState, Matrix3<f64>), ReturnMapError> {
        let e = [strain[0] - thermal, strain[1] - thermal, strain[2]];
        match self.plane {
            Plane::Stress => plane_stress::update(self, committed, &e),
            // ε_zz = 0 total (in axisymmetry: the in-plane strains with zero hoop strain)
            Plane::Strain | Plane::Axisymmetric | Plane::Solid => {
                let e4 = [e[0], e[1], e[2], 0.0 - thermal];
                let (state, c) = radial::update(self, committed, &e4);
                Ok((state, c.fixed_view::<3, 3>(0, 0).into_owned()))
            }
        }
    }

    /// Axisymmetric return mapping (radial return, eqs 3.8-3.11; Simo & Hughes
    /// box 3.2; the same function as plane strain's, module `radial`) from
    /// `committed` for the total strain [ε_rr, ε_zz, γ_rz, ε_θθ]: the new state
    /// (stress [σ_rr, σ_zz, σ_rz, σ_θθ]) and the algorithmic tangent dσ/dε, 4×4
    /// in that order. Used by every plane setting alike (the hoop strain is
    /// given, whatever `plane` says); the axisymmetric element's.
    pub(crate) fn update_axisymmetric(
        &self,
        committed: &PointState,
        strain: &[f64; 4],
    ) -> (PointState, Matrix4<f64>) {
        radial::update(self, committed, strain)
    }

    /// The 3D isotropic elastic matrix in the order (rr, zz, rz, θθ), engineering
    /// shear: [σ_rr σ_zz σ_rz σ_θθ] = D [ε_rr ε_zz γ_rz ε_θθ] (eq. 3.9's C).
    pub fn elastic_matrix_4(&self) -> Matrix4<f64> {
        radial::external(&elastic_3d(self.shear_modulus(), self.bulk_modulus()))
    }

    /// Stress from the elastic law alone, keeping the committed plastic strain,
    /// for the axisymmetric strain [ε_rr, ε_zz, γ_rz, ε_θθ] (no return mapping:
    /// first-yield location).
    pub(crate) fn elastic_state_axisymmetric(
        &self,
        committed: &PointState,
        strain: &[f64; 4],
    ) -> PointState {
        radial::elastic(self, committed, strain)
    }

    /// The return mapping of an axisymmetric point with twist ([`twist`]:
    /// the same radial return on all six components) from `committed` for
    /// the total strain [ε_rr, ε_zz, γ_rz, ε_θθ, γ_rθ, γ_zθ]: the new state and
    /// the algorithmic tangent dσ/dε, 6×6 in that order.
    pub(crate) fn update_twist(
        &self,
        committed: &PointState,
        strain: &[f64; 6],
    ) -> (PointState, Matrix6<f64>) {
        six_components::update(self, committed, strain)
    }

    /// The 3D isotropic elastic matrix in the order (rr, zz, rz, θθ, rθ, zθ),
    /// engineering shear.
    pub(crate) fn elastic_matrix_6(&self) -> Matrix6<f64> {
        six_components::elastic_matrix(self.shear_modulus(), self.bulk_modulus())
    }

    /// Stress from the elastic law alone for the strain with twist, keeping
    /// the committed plastic strain (first-yield location).
    pub(crate) fn elastic_state_twist(
        &self,
        committed: &PointState,
        strain: &[f64; 6],
    ) -> PointState {
        six_components::elastic(self, committed, strain)
    }

    /// Continuum tangent C_ep (3.13) at a committed state with twist, 6×6
    /// in the order (rr, zz, rz, θθ, rθ, zθ): C_ep if the state was
    /// yielding, else D.
    pub(crate) fn continuum_tangent_6(&self, state: &PointState) -> Matrix6<f64> {
        if !state.yielding {
            return self.elastic_matrix_6();
        }
        six_components::continuum(self, &state.stress)
    }

    /// Continuum tangent C_ep (3.13) at a committed state, 4×4 in the order
    /// (rr, zz, rz, θθ): C_ep if the state was yielding, else D.
    pub(crate) fn continuum_tangent_4(&self, state: &PointState) -> Matrix4<f64> {
        if !state.yielding {
            return self.elastic_matrix_4();
        }
        radial::external(&self.continuum_3d(&state.stress))
    }

    /// Continuum tangent at a committed state: C_ep (3.13) if the state was
    /// yielding, else D. In plane stress, the 3D C_ep condensed to σzz = 0.
    pub(crate) fn continuum_tangent(&self, state: &PointState) -> Matrix3<f64> {
        if !state.yielding {
            return self.elastic_matrix();
        }
        let c = self.continuum_3d(&state.stress);
        // Voigt order of c: xx, yy, zz, xy
        let idx = [0usize, 1, 3];
        match self.plane {
            Plane::Strain | Plane::Axisymmetric | Plane::Solid => {
                Matrix3::from_fn(|i, j| c[(idx[i], idx[j])])
            }
            Plane::Stress => {
                let czz = c[(2, 2)];
                Matrix3::from_fn(|i, j| c[(idx[i], idx[j])] - c[(idx[i], 2)] * c[(2, idx[j])] / czz)
            }
        }
    }

    /// 3D continuum C_ep in Voigt (xx, yy, zz, xy) with engineering shear strain:
    /// K 1⊗1 + 2G I_dev − 6G²/(3G + H) N̂⊗N̂, N̂ = s/‖s‖.
    fn continuum_3d(&self, stress: &[f64; 6]) -> Matrix4<f64> {
        let (g, k, h) = (self.shear_modulus(), self.bulk_modulus(), self.hardening);
        let s3 = [stress[0], stress[1], stress[3], stress[2]]; // xx yy zz xy
        let p = (s3[0] + s3[1] + s3[2]) / 3.0;
        let s = [s3[0] - p, s3[1] - p, s3[2] - p, s3[3]];
        let norm = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * s[3] * s[3]).sqrt();
        let mut c = elastic_3d(g, k);
        if norm > 0.0 {
            let a = 6.0 * g * g / (3.0 * g + h);
            for i in 0..4 {
                for j in 0..4 {
                    c[(i, j)] -= a * s[i] * s[j] / (norm * norm);
                }
            }
        }
        c
    }
}

/// 3D isotropic elasticity in Voigt (xx, yy, zz, xy), engineering shear strain.
pub(crate) fn elastic_3d(g: f64, k: f64) -> Matrix4<f64> {
    let mut c = Matrix4::zeros();
    for i in 0..3 {
        for j in 0..3 {
            c[(i, j)] = k - 2.0 * g / 3.0 + if i == j { 2.0 * g } else { 0.0 };
        }
    }
    c[(3, 3)] = g;
    c
}
