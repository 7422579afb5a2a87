//! A joint slipping as a whole: whether every point it closes is in
//! macro-slip at an increment, and which way it moved there (turned about
//! the axis, or pushed along its tangent), from the increment's change of
//! the joint's mean slips. The holding plateaus
//! ([`crate::solve::events::plateaus`]) and the fit's rating
//! ([`crate::verdict::fit`]) read a joint's slip by the direction it moved,
//! not by which of its friction forces is the larger: a fit pressed and
//! then turned still carries the axial friction the pressing locked in when
//! it first slips as a whole under the torque.

use super::joint::JointMeasures;
use crate::model::Model;

/// The share of a joint's touching measure in macro-slip from which it
/// slips as a whole (the rest is round-off of the status boundary).
pub const WHOLE: f64 = 0.999;

/// How a joint in full slip moved over an increment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// About the axis: the circumferential slip ū_θ changed the more.
    Turning,
    /// Along the interface's tangent: the slip ū_T changed the more.
    Pushing,
}

impl Motion {
    /// The quantity that holds the joint in this motion, in words.
    pub fn quantity(self) -> &'static str {
        match self {
            Motion::Turning => "torque",
            Motion::Pushing => "tangential force",
        }
    }

    /// That quantity's magnitude in a joint's measures: |T| (N·mm) or |F_T| (N).
    pub fn held(self, j: &JointMeasures) -> f64 {
        match self {
            Motion::Turning => j.torque.abs(),
            Motion::Pushing => j.tangential_force.abs(),
        }
    }
}

/// Whether what interface `i` holds as it slides in `motion` is its
/// capacity: the motion was imposed, some prescribed rotation about the
/// axis (turning) or translation (pushing) of the model not zero, and,
/// turning, no torque load acts on either of its bodies. A joint turned by
/// a torque load holds that load as it creeps (its plateau would be the
/// load, not what it can hold: the run ends at its `torque_limit`); one
/// that slides with nothing imposing the motion (the hub of a heat
/// assembly contracting along the shaft as it cools) holds the friction of
/// that moment, not a capacity in service.
pub fn imposed(model: &Model, i: usize, motion: Motion) -> bool {
    let dofs = model.node_dofs();
    let twist = |dof: usize| dofs.twist() && dofs.node_of(dof).1 == 2;
    let moved = (model.prescribed.iter())
        .any(|&(d, v)| v != 0.0 && twist(d) == (motion == Motion::Turning));
    if !moved {
        return false;
    }
    if motion == Motion::Pushing {
        return true;
    }
    let im = &model.interfaces[i];
    let body_of = model.mesh.node_bodies();
    let torqued = |b: usize| {
        model.patterns().any(|(_, f)| {
            (body_of.iter().enumerate()).any(|(n, &nb)| nb == b && f[dofs.dof(n, 2)] != 0.0)
        })
    };
    !torqued(im.body_a) && !torqued(im.body_b)
}

/// Whether every point of the joint in contact is in macro-slip (to
/// [`WHOLE`] of their measure), and some is.
pub fn whole(j: &JointMeasures) -> bool {
    let touching = j.closed + j.stick + j.micro_slip + j.macro_slip;
    j.macro_slip > 0.0 && j.macro_slip >= WHOLE * touching
}

/// Each increment of a joint's series at which it slips as a whole, with
/// the way it moved from the increment before (the unloaded start before
/// the first): turning when |Δū_θ| > |Δū_T|, pushing otherwise; an
/// increment over which neither mean slip changed is left out (the joint
/// did not move: no motion to name).
pub fn motions(series: &[&JointMeasures]) -> Vec<(usize, Motion)> {
    let rest = JointMeasures::default();
    let mut out = Vec::new();
    for (k, j) in series.iter().enumerate() {
        if !whole(j) {
            continue;
        }
        let before = if k == 0 { &rest } else { series[k - 1] };
        let along = (j.mean_slip - before.mean_slip).abs();
        let about = (j.hoop_slip - before.hoop_slip).abs();
        if along == 0.0 && about == 0.0 {
            continue;
        }
        let m = if about > along {
            Motion::Turning
        } else {
            Motion::Pushing
        };
        out.push((k, m));
    }
    out
}

/// The load the joint held (|T| or |F_T|, [`Motion::held`]) at each
/// increment of `series` at which it slid as a whole in `motion`.
pub fn held(series: &[&JointMeasures], motion: Motion) -> Vec<(usize, f64)> {
    motions(series)
        .into_iter()
        .filter(|&(_, m)| m == motion)
        .map(|(k, m)| (k, m.held(series[k])))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(slip: f64, hoop: f64, macro_slip: f64, stick: f64) -> JointMeasures {
        JointMeasures {
            mean_slip: slip,
            hoop_slip: hoop,
            macro_slip,
            stick,
            tangential_force: 10.0 * slip,
            torque: 100.0 * hoop,
            ..Default::default()
        }
    }

    #[test]
    fn a_fit_pressed_then_turned_moves_first_along_then_about_the_axis() {
        // pressed (slip grows, all in macro-slip), held, then turned with
        // the axial slip locked in: each increment named by its motion
        let s = [
            state(0.01, 0.0, 1.0, 0.0),
            state(0.02, 0.0, 1.0, 0.0),
            state(0.02, 0.0, 0.5, 0.5), // sticking again: not whole
            state(0.02, 0.001, 1.0, 0.0),
            state(0.0201, 0.003, 1.0, 0.0),
            state(0.0201, 0.003, 1.0, 0.0), // did not move
        ];
        let refs: Vec<&JointMeasures> = s.iter().collect();
        let m = motions(&refs);
        assert_eq!(
            m,
            vec![
                (0, Motion::Pushing),
                (1, Motion::Pushing),
                (3, Motion::Turning),
                (4, Motion::Turning)
            ]
        );
        assert_eq!(Motion::Turning.held(&s[4]), 0.3);
        assert_eq!(Motion::Pushing.held(&s[4]), 0.201);
    }

    #[test]
    fn whole_slip_needs_every_touching_point() {
        assert!(whole(&state(0.0, 0.0, 0.9995, 0.0005)));
        assert!(!whole(&state(0.0, 0.0, 0.99, 0.01)));
        assert!(!whole(&state(0.0, 0.0, 0.0, 0.0)));
    }
}
