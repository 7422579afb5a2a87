//! The state of an interface point: its status (open, closed, sticking,
//! slipping) and its tangential history, committed per increment, with the
//! layouts of restart files and of the MPI exchange.
//!
//! Without twist a point carries the scalar law's [`SlipState`] and its last
//! p_T, u_T, μ_F. In a model with twist ([`crate::input::mesh::NodeDofs::twist`])
//! the slip and shear are 2-vectors (along the meridian t and around the
//! axis θ) and the point carries the vector law's `SlipState2` instead;
//! the scalar `slip` then stays at its default.
//!
//! ```text
//!   without twist (PACKED = 25):  u_p  κ  p_T  u_T  μ_F  η₁…η_M  e₁…e_M
//!   with twist (PACKED_TWIST = 56): p_T  u_T  μ_F  p_Tθ  u_Tθ  SlipState2 (51)
//! ```

use super::tangential::{SlipState, SlipState2, Stretch, MEMORY_POINTS};

/// Status of an interface point, decided from its approach and shear.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[repr(u8)]
pub enum Status {
    #[default]
    Open = 0,
    /// Closed, no tangential law.
    Closed,
    Stick,
    MicroSlip,
    MacroSlip,
}

impl Status {
    /// Inverse of `status as u8`, for codes this process made (the sums of
    /// the reductions over ranks): any other code is taken as open. Codes
    /// read from a file go through [`Status::checked`].
    pub(crate) fn from_code(c: u8) -> Status {
        Status::checked(c).unwrap_or_default()
    }

    /// Inverse of `status as u8`; `None` for a code that is no status.
    pub fn checked(c: u8) -> Option<Status> {
        Some(match c {
            0 => Status::Open,
            1 => Status::Closed,
            2 => Status::Stick,
            3 => Status::MicroSlip,
            4 => Status::MacroSlip,
            _ => return None,
        })
    }

    /// Normal status: "open" or "closed".
    pub fn name(self) -> &'static str {
        match self {
            Status::Open => "open",
            _ => "closed",
        }
    }

    /// Tangential status: "none", "stick", "micro-slip", "macro-slip" ("free" when open).
    pub(crate) fn tangential_name(self) -> &'static str {
        match self {
            Status::Open => "free",
            Status::Closed => "none",
            Status::Stick => "stick",
            Status::MicroSlip => "micro-slip",
            Status::MacroSlip => "macro-slip",
        }
    }
}

/// Tangential history and last values of one point (committed per increment).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointState {
    pub slip: SlipState,
    /// Shear traction and tangential displacement (for the secant scheme and output).
    pub p_t: f64,
    pub u_t: f64,
    pub(crate) mu_f: f64,
    /// With twist: the circumferential shear p_Tθ (MPa) and slip
    /// u_Tθ = u_θB − u_θA (mm, r Δφ) in the internal convention, and the
    /// vector law's history (0 and default without twist).
    pub(crate) p_h: f64,
    pub u_h: f64,
    pub(crate) slip2: SlipState2,
}

impl PointState {
    /// The second component of the shear, MPa: with twist the
    /// circumferential p_Tθ, in a 3D model the shear along the slip frame's
    /// t₂ (0 in a plane model).
    pub fn second_shear(&self) -> f64 {
        self.p_h
    }

    /// Doubles per state in [`PointState::pack_twist`] (a model with twist).
    pub(crate) const PACKED_TWIST: usize = 5 + SlipState2::PACKED;

    /// Doubles per state in the model's layout: [`PointState::PACKED`]
    /// without twist, [`PointState::PACKED_TWIST`] with it.
    pub(crate) fn packed_len(twist: bool) -> usize {
        if twist {
            Self::PACKED_TWIST
        } else {
            Self::PACKED
        }
    }

    /// The state in the model's layout ([`PointState::pack`] or
    /// [`PointState::pack_twist`]), `packed_len(twist)` values.
    pub(crate) fn pack_as(&self, twist: bool) -> Vec<f64> {
        if twist {
            self.pack_twist().to_vec()
        } else {
            self.pack().to_vec()
        }
    }

    /// The inverse of [`PointState::pack_as`] (`v` holds at least
    /// `packed_len(twist)` values).
    pub(crate) fn unpack_as(v: &[f64], twist: bool) -> Self {
        if twist {
            Self::unpack_twist(v)
        } else {
            Self::unpack(v)
        }
    }

    /// A point of a model with twist: p_T, u_T, μ_F, p_Tθ, u_Tθ, then the
    /// vector law's state ([`SlipState2::pack`]).
    pub(crate) fn pack_twist(&self) -> [f64; Self::PACKED_TWIST] {
        let mut v = [0.0; Self::PACKED_TWIST];
        v[..5].copy_from_slice(&[self.p_t, self.u_t, self.mu_f, self.p_h, self.u_h]);
        v[5..].copy_from_slice(&self.slip2.pack());
        v
    }

    /// The inverse of [`PointState::pack_twist`] (`v` holds at least
    /// `PACKED_TWIST` values).
    pub(crate) fn unpack_twist(v: &[f64]) -> Self {
        PointState {
            slip: SlipState::default(),
            p_t: v[0],
            u_t: v[1],
            mu_f: v[2],
            p_h: v[3],
            u_h: v[4],
            slip2: SlipState2::unpack(&v[5..Self::PACKED_TWIST]),
        }
    }

    /// Doubles per state in [`PointState::pack`].
    pub const PACKED: usize = 5 + 2 * MEMORY_POINTS;

    /// Plastic slip u_p, slip memory κ, p_T, u_T, μ_F, then the kinematic
    /// memory's breakpoints η₁ … η_M and e₁ … e_M (zero under the
    /// isotropic memory): the layout of restart files and of the MPI
    /// exchange of interface states.
    pub fn pack(&self) -> [f64; Self::PACKED] {
        let mut v = [0.0; Self::PACKED];
        v[..5].copy_from_slice(&[
            self.slip.u_p,
            self.slip.kappa,
            self.p_t,
            self.u_t,
            self.mu_f,
        ]);
        v[5..5 + MEMORY_POINTS].copy_from_slice(&self.slip.mem.eta);
        v[5 + MEMORY_POINTS..].copy_from_slice(&self.slip.mem.e);
        v
    }

    /// The inverse of [`PointState::pack`] (`v` holds at least `PACKED` values).
    pub(crate) fn unpack(v: &[f64]) -> Self {
        let mut mem = Stretch::default();
        mem.eta.copy_from_slice(&v[5..5 + MEMORY_POINTS]);
        mem.e
            .copy_from_slice(&v[5 + MEMORY_POINTS..5 + 2 * MEMORY_POINTS]);
        PointState {
            slip: SlipState {
                u_p: v[0],
                kappa: v[1],
                mem,
            },
            p_t: v[2],
            u_t: v[3],
            mu_f: v[4],
            ..Default::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_twisting_point_packs_its_vector_state() {
        let mut slip2 = SlipState2 {
            u_p: [1e-3, -2e-3],
            kappa: 5e-3,
            ..Default::default()
        };
        slip2.mem.e[3] = [2e-4, -1e-4];
        let s = PointState {
            p_t: -3.5,
            u_t: 1e-4,
            mu_f: 0.25,
            p_h: 7.5,
            u_h: -2e-4,
            slip2,
            ..Default::default()
        };
        let v = s.pack_twist();
        assert_eq!(v.len(), 56);
        assert_eq!(v[..8], [-3.5, 1e-4, 0.25, 7.5, -2e-4, 1e-3, -2e-3, 5e-3]);
        assert_eq!(v[5 + 3 + 6..5 + 3 + 8], [2e-4, -1e-4]);
        assert_eq!(PointState::unpack_twist(&v), s);
        assert_eq!(PointState::unpack_as(&s.pack_as(true), true), s);
        assert_eq!(PointState::packed_len(true), PointState::PACKED_TWIST);
        assert_eq!(PointState::packed_len(false), PointState::PACKED);
    }

    #[test]
    fn point_state_pack_round_trips_in_the_restart_order() {
        let mut mem = Stretch::default();
        mem.eta[..2].copy_from_slice(&[0.25, 1.0]);
        mem.e[..2].copy_from_slice(&[-2e-4, 3e-4]);
        let s = PointState {
            slip: SlipState {
                u_p: -1.5e-3,
                kappa: 4e-3,
                mem,
            },
            p_t: -12.25,
            u_t: 7.0e-4,
            mu_f: 0.3,
            ..Default::default()
        };
        let v = s.pack();
        assert_eq!(v.len(), PointState::PACKED);
        assert_eq!(v[..5], [-1.5e-3, 4e-3, -12.25, 7.0e-4, 0.3]);
        assert_eq!(v[5..7], [0.25, 1.0]);
        assert_eq!(v[5 + MEMORY_POINTS..7 + MEMORY_POINTS], [-2e-4, 3e-4]);
        assert_eq!(PointState::unpack(&v), s);
        // one state in a longer buffer (a chunk of a packed array)
        let mut buf = [9.0; 3 * PointState::PACKED];
        buf[PointState::PACKED..2 * PointState::PACKED].copy_from_slice(&v);
        assert_eq!(PointState::unpack(&buf[PointState::PACKED..]), s);
        assert_eq!(
            PointState::unpack(&PointState::default().pack()),
            PointState::default()
        );
    }
}
