//! Solver settings chosen in a case's `[solver]` table: the iteration method,
//! its acceleration, the step control and the contact stabilization. The case
//! file spells them in kebab-case (`method = "modified-newton"`); `case`
//! defines them and `solve` re-exports them.

use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Consistent tangent at every iteration.
    #[default]
    FullNewton,
    /// Solid tangent from the start of the increment, contact matrix updated each iteration.
    ModifiedNewton,
    /// Elastic K₀ plus the current contact matrix (eq. 4.8).
    InitialStiffness,
}

impl Method {
    pub fn name(self) -> &'static str {
        match self {
            Method::FullNewton => "full-newton",
            Method::ModifiedNewton => "modified-newton",
            Method::InitialStiffness => "initial-stiffness",
        }
    }
}

#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Acceleration {
    /// The plain method: u ← u + Δu.
    None,
    /// Anderson mixing of the last corrections (see `solve::accelerate`).
    #[default]
    Anderson,
}

/// Contact stabilization of floating bodies (`solve::stabilize`).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Stabilization {
    /// Used only in the steps that need it: a body held only through open
    /// interface pairs, or carrying no load.
    #[default]
    Auto,
    /// Never: such steps fail, with the floating body named.
    Off,
}

/// How the load-factor steps are chosen.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum StepControl {
    /// The schedule as given (`increments`, `first_increment`, `load_factors`),
    /// halved on failure.
    #[default]
    Fixed,
    /// Steps adapted to the iteration count and the plastic strain increment
    /// between the waypoints (`load_factors`, else 1); see `solve::stepping`.
    Auto,
}

/// Quadrature of the interface energy along a contact edge (the case's
/// `weights`): the nodes themselves or 4-point Gauss (see the module comment).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Weights {
    /// Row-sum weights 1/6, 2/3, 1/6 (eq. 3.30-3.31): one spring per pair.
    #[default]
    Lumped,
    /// Gauss integration along the edge (eq. 3.29).
    Consistent,
    /// Non-matching interfaces only: one spring per slave node whose approach
    /// and slip are the slave side's gap and slip averaged over the node's
    /// shape function N_i, g̃_i = ∫ N_i g ds / ∫ N_i ds (a mortar projection,
    /// segment-to-segment; see [`crate::model::interface::Mortar`]).
    Mortar,
}

/// How the tangential stiffness enters the matrix.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FrictionScheme {
    /// Consistent tangent of the return mapping (unsymmetric ∂p_T/∂u_N included).
    #[default]
    ReturnMapping,
    /// The paper's stiffness modification (2.25-2.26): the secant k_T* = Δp_T/Δu_T
    /// of the increment for slipping springs, k_T^e for sticking ones, no coupling.
    StiffnessModification,
}
