//! The tangential law's parameters as a case gives them
//! (`[interface.<name>.tangential]`): their engineering ranges, and the law
//! as `asperity check` describes it. The checks of the case
//! (`input::case::validate::tangential`) and `asperity calibrate` take the
//! ranges from here.

use super::{Backbone, Memory, TangentialLaw};
use crate::physics::range::{Range, PRESSURE};

/// R of the tangential law (k_T^e = p_N^S / R, MPa/µm).
pub(crate) const SHEAR_R: Range = Range {
    quantity: "the shear compliance R",
    unit: "µm·MPa^(S-1)",
    lo: 1e-6,
    hi: 1e6,
};
/// The elastic shear stiffness k_T^e (MPa/µm) of a `k_table`: the values
/// p^S/R takes over the ranges of a pressure and of R with S in [0, 1].
pub(crate) const SHEAR_STIFFNESS: Range = Range {
    quantity: "a shear stiffness k_T^e",
    unit: "MPa/µm",
    lo: 1e-12,
    hi: 1e12,
};
pub const FRICTION: Range = Range {
    quantity: "a friction coefficient",
    unit: "",
    lo: 1e-4,
    hi: 100.0,
};
/// Slip-hardening rate n (0 allowed).
pub(crate) const SLIP_RATE: Range = Range {
    quantity: "a slip-hardening rate",
    unit: "1/mm",
    lo: 1e-6,
    hi: 1e9,
};

/// The numbers whose magnitude is checked against a range, by key, in the
/// order they are checked (after the law is built).
pub(crate) const NUMBERS: [(&str, &Range); 3] =
    [("r", &SHEAR_R), ("mu", &FRICTION), ("n", &SLIP_RATE)];

/// The columns of a `k_table` row, each within its range (checked before the
/// table is interpolated).
pub(crate) const K_TABLE_COLUMNS: [(&str, &Range); 2] =
    [("p_N", &PRESSURE), ("k_T", &SHEAR_STIFFNESS)];

/// Every range the tangential law's keys take (the documentation's table).
pub(crate) const RANGES: [&Range; 4] = [&SHEAR_R, &SHEAR_STIFFNESS, &FRICTION, &SLIP_RATE];

impl TangentialLaw {
    /// The law as `asperity check` prints it: μ, stiffness, backbone, memory
    /// (the scheme, a solver setting, follows).
    pub(crate) fn describe(&self) -> String {
        let stiffness = match &self.k_table {
            Some(t) => format!("k_T^e from a k_table of {} rows", t.points().count()),
            None => format!("k_T^e = p^S/R (R = {}, S = {})", self.r, self.s),
        };
        let backbone = match self.backbone {
            Backbone::Bilinear => format!(
                "bilinear backbone (k_T^p/k_T^e = {}, yield ratio {}, beta = {}, n = {} 1/mm)",
                self.kp_ratio, self.yield_ratio, self.beta, self.n
            ),
            Backbone::Iwan { chi, spike } => {
                format!("Iwan backbone (chi = {chi}, spike = {spike})")
            }
        };
        let memory = match self.memory {
            Memory::Isotropic => "isotropic memory (section 2.2)",
            Memory::Kinematic => "kinematic memory (Masing)",
        };
        format!("mu = {}, {stiffness}, {backbone}, {memory}", self.mu)
    }
}
