//! The standards' own formulas: pure functions of the designer's inputs, in N, mm and MPa
//! (torques in N·mm, roughness in µm where the standard gives it in µm; each field names its
//! unit).
//!
//! * [`din7190`]: DIN 7190-1:2017, cylindrical interference fits (elastic, with the partly and
//!   the fully plastic hub): pressure, stresses, limit pressures, transmissible loads, slip and
//!   yield safeties, joining temperature, the interference lost in service (operating
//!   temperatures, speed) and the pressure, opening speed and opening temperature there.
//! * [`vdi2230`]: VDI 2230-1:2015, concentric single-bolt joints (through-bolted and tapped):
//!   resiliences, load factor, embedding, preloads, tightening torque, working stress, fatigue,
//!   surface pressure (requirements R3 to R10 and R13).
//! * [`masing`]: a uniform joint of Jenkins elements under Masing's rules (Iwan 1966, Segalman
//!   2005): the force amplitude, dissipation and loss factor of a cycle at a slip amplitude.
//! * [`thread`]: ISO metric threads (ISO 261/262/724) and bolt property classes (ISO 898-1).
//!
//! Every function states its formula and where it comes from. Invalid inputs (non-positive
//! diameters, ratios at or beyond 1, ...) give `None` rather than a number, so that the caller can
//! report them.

pub mod din7190;
pub mod masing;
pub mod thread;
pub mod vdi2230;

#[cfg(test)]
mod tests;

/// A safety factor S = capacity/demand: S_F = p_F/p, S_D = σ_AS/σ_a, S_P = p_G/p and the like.
/// Infinite for a zero demand with a positive capacity; `None` for a negative or non-finite
/// input, or for both zero.
pub fn safety(capacity: f64, demand: f64) -> Option<f64> {
    let valid = capacity.is_finite() && demand.is_finite() && capacity >= 0.0 && demand >= 0.0;
    if !valid || (capacity == 0.0 && demand == 0.0) {
        return None;
    }
    Some(if demand == 0.0 {
        f64::INFINITY
    } else {
        capacity / demand
    })
}

/// `x` is a finite number greater than zero.
fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

/// `x` is a finite number not below zero.
fn non_negative(x: f64) -> bool {
    x.is_finite() && x >= 0.0
}
