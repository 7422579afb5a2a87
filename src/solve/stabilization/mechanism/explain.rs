//! The physical reason a step may have no solution, for the failure's
//! message ([`Stabilizer::explain`]): a torque past what friction holds, a
//! body held by nothing (or by one side of a free pretension section's cut
//! only), a body whose position nothing fixes at zero load, or a free
//! section's force pulled past.

use super::*;
use crate::model::pretension::{free_at, Section};

/// λ as short as it is exact to six places: "0", "0.5", "0.000195".
fn short(lambda: f64) -> String {
    format!("{lambda:.6}")
        .trim_end_matches('0')
        .trim_end_matches('.')
        .to_string()
}

/// How a free section is controlled at `lambda`, for a message.
fn control(s: &Section) -> String {
    if s.lock_after.is_finite() {
        format!("force-controlled until its lock at t = {}", s.lock_after)
    } else {
        "force-controlled and never locked (lock = false)".to_string()
    }
}

/// A body held about the axis only by friction, under a torque near or past
/// what that friction holds ([`Stabilizer::friction_limit`]).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FrictionLimit {
    pub body: usize,
    /// The interfaces with a tangential law that hold it, in model order.
    pub interfaces: Vec<usize>,
    /// |T| applied at the load factor asked (N·mm).
    pub applied: f64,
    /// Σ μ p_N r dA at the pressures of the displacements given (N·mm).
    pub hold: f64,
}

impl Stabilizer {
    /// The torque applied to body `b` about the axis at `lambda` (N·mm,
    /// signed as its load).
    pub(crate) fn applied_torque(&self, model: &Model, b: usize, lambda: f64) -> f64 {
        (self.bodies[b].torque.iter().zip(model.patterns()))
            .map(|(&t, (s, _))| t * model.scale(s, lambda))
            .sum()
    }

    /// A body held about the axis only by friction (twist: no prescribed
    /// rotation of its own) whose applied torque at `lambda` is at least
    /// [`NEAR_SLIP`] of the most its interfaces' friction can hold at the
    /// pressures of `u`, Σ μ_m p_N r A (μ_m the friction cap, eq. 2.21): a
    /// torque-controlled twist at or past the slip torque, which has no
    /// equilibrium past it.
    pub(crate) fn friction_limit(
        &self,
        model: &Model,
        u: &[f64],
        lambda: f64,
    ) -> Option<FrictionLimit> {
        if !model.node_dofs().twist() {
            return None;
        }
        (0..self.bodies.len()).find_map(|b| {
            if self.bodies[b].turn > 0.0 {
                return None;
            }
            let applied = self.applied_torque(model, b, lambda);
            let mut interfaces = Vec::new();
            let mut hold = 0.0;
            for (i, im) in model.interfaces.iter().enumerate() {
                let Some(law) = im.tangential.as_ref() else {
                    continue;
                };
                if im.body_a != b && im.body_b != b {
                    continue;
                }
                interfaces.push(i);
                let gap = im.gap_at(lambda);
                for (pt, r) in im.points.iter().zip(im.point_radii()) {
                    let un = im.point_kinematics_at(pt, u, gap).0;
                    hold += pt.area * law.mu * im.law.pressure(un).0 * r;
                }
            }
            let near = applied != 0.0 && applied.abs() >= NEAR_SLIP * hold;
            (near && !interfaces.is_empty()).then(|| FrictionLimit {
                body: b,
                interfaces,
                applied: applied.abs(),
                hold,
            })
        })
    }

    /// [`Stabilizer::friction_limit`] as a failure's reason.
    fn beyond_friction(&self, model: &Model, u: &[f64], lambda: f64) -> Option<String> {
        let limit = self.friction_limit(model, u, lambda)?;
        // spinning, the speed takes pressure off a fit: this is the speed
        // at which it can no longer hold its torque
        let speed = (model.rpm(lambda)).map_or(String::new(), |n| format!(" ({n:.6e} rpm)"));
        let how = if limit.applied > limit.hold {
            "more than".to_string()
        } else {
            format!("{:.2} % of what", 100.0 * limit.applied / limit.hold)
        };
        let names: Vec<&str> = (limit.interfaces.iter())
            .map(|&i| model.interfaces[i].name.as_str())
            .collect();
        Some(format!(
            "the torque on body \"{}\" at λ = {}{speed}, {:.6e} N·mm, is {how} the friction of interface \"{}\" can hold about the axis at the present contact pressures, Σ μ p_N r dA = {:.6e} N·mm, and nothing else holds the body about the axis: past the slip torque there is no equilibrium, and within 2 % of it the last sticking points may not converge (prescribe a [[boundary]] rotation instead to turn the joint past slip)",
            model.mesh.bodies[limit.body],
            short(lambda),
            limit.applied,
            names.join("\", \""),
            limit.hold,
        ))
    }

    /// The physical reason a step from `committed` to `lambda` may have no
    /// solution, if there is one: a body held by nothing (a side of a free
    /// section's cut among them), held about the axis by friction only and
    /// loaded by a torque beyond it, a body whose position nothing fixes at
    /// zero load, or a free section whose force is all that holds the sides
    /// of its cut together while other loads act.
    pub(crate) fn explain(&self, model: &Model, committed: &State, lambda: f64) -> Option<String> {
        if let Some(why) = self.beyond_friction(model, &committed.u, lambda) {
            return Some(why);
        }
        let unloaded = self.unloaded(model, lambda);
        let floating = self.floating(model, &committed.u, lambda);
        // held if its free sections were held: a side of a cut floats, which
        // the section's force drives (whatever else carries no load)
        let cuts_held = self.floating_as(model, &committed.u, lambda, |_| false);
        if let Some(&b) = floating.iter().find(|b| !cuts_held.contains(b)) {
            return Some(self.loose_side(model, &committed.u, lambda, b));
        }
        let Some(b) = unloaded.or(floating.first().copied()) else {
            return self.free_section(model, lambda);
        };
        let lambda = short(lambda);
        let name = &model.mesh.bodies[b];
        let via: Vec<&str> = model
            .interfaces
            .iter()
            .filter(|im| im.body_a == b || im.body_b == b)
            .map(|im| im.name.as_str())
            .collect();
        let via = if via.is_empty() {
            "no interface".to_string()
        } else {
            format!("interface \"{}\"", via.join("\", \""))
        };
        Some(if floating.contains(&b) {
            format!(
                "body \"{name}\" is not in contact at the start of the step to λ = {lambda} \
                 (every pair of {via} is open, or closed without pressure) and nothing else \
                 holds it: its boundary conditions leave a rigid-body motion free"
            )
        } else {
            format!(
                "body \"{name}\" carries no load at λ = {lambda} and is held only through \
                 {via}: at zero contact force nothing fixes its position"
            )
        })
    }

    /// Body `b`, held were its free sections held, is not: the side of a
    /// free section's cut that nothing holds along the cut's normal (its
    /// supports along it and its supporting pairs at `u`), named with the
    /// section and the interfaces on that side.
    fn loose_side(&self, model: &Model, u: &[f64], lambda: f64, b: usize) -> String {
        let body = &self.bodies[b];
        let p_min: Vec<f64> = (0..model.interfaces.len())
            .map(|i| SUPPORT * model.reference_pressure(i, lambda))
            .collect();
        let name = &model.mesh.bodies[b];
        let free = body
            .cuts
            .iter()
            .map(|&c| &self.cuts[c])
            .filter(|c| free_at(&model.sections[c.section], lambda));
        let body_of = model.mesh.node_bodies();
        let mut first = None;
        for cut in free {
            let s = &model.sections[cut.section];
            // per side (before, beyond): held along the normal, the
            // interfaces with a pair there
            let mut held = [false; 2];
            let mut via: [Vec<&str>; 2] = [Vec::new(), Vec::new()];
            for &(d, _) in &model.prescribed {
                let (n, c) = model.node_dofs().node_of(d);
                if c == s.axis && body_of.get(n) == Some(&b) {
                    held[usize::from(cut.beyond[n])] = true;
                }
            }
            for (i, im) in model.interfaces.iter().enumerate() {
                if im.body_a != b && im.body_b != b {
                    continue;
                }
                let gap = im.gap_at(lambda);
                for (pr, &carries) in im.pairs.iter().zip(&self.carrying[i]) {
                    let node = if im.body_a == b { pr.a } else { pr.b };
                    let side = usize::from(cut.beyond.get(node).copied().unwrap_or(false));
                    if !via[side].contains(&im.name.as_str()) {
                        via[side].push(im.name.as_str());
                    }
                    let un = im.pair_approach_at(pr, u, gap);
                    let supports = if un > 0.0 {
                        im.law.pressure(un).0 >= p_min[i]
                    } else {
                        un > TOUCH
                    };
                    if carries && supports && pr.normal[s.axis] != 0.0 {
                        held[side] = true;
                    }
                }
            }
            let Some(side) = held.iter().position(|h| !h) else {
                first.get_or_insert(s);
                continue;
            };
            let line = ["x", "y", "z"][s.axis];
            let via = match via[side].as_slice() {
                [] => "it has no interface".to_string(),
                v => format!(
                    "every pair of interface \"{}\" on it is open, or closed without pressure",
                    v.join("\", \"")
                ),
            };
            return format!(
                "the side {line} {} {} of body \"{name}\" at the cut of pretension \"{}\" is \
                 held by nothing at the start of the step to λ = {} ({via}): the section is {}, \
                 so its force moves that side freely",
                if side == 1 { ">" } else { "<" },
                s.at,
                s.name,
                short(lambda),
                control(s)
            );
        }
        let s = first.expect("a body held only once its free sections are held has one");
        format!(
            "the two sides of body \"{name}\" at the cut of pretension \"{}\" are not both held at \
             the start of the step to λ = {}: the section is {}, so its force moves them freely \
             against each other",
            s.name,
            short(lambda),
            control(s)
        )
    }

    /// A free section whose force acts at `lambda` together with another
    /// load: its force is all that holds the two sides of its cut together,
    /// and a load that pulls them apart harder has no equilibrium.
    fn free_section(&self, model: &Model, lambda: f64) -> Option<String> {
        let on = |h: Option<usize>| model.factor(h, lambda) != 0.0;
        let section_dofs: Vec<usize> = model.sections.iter().map(|s| s.dof).collect();
        let others = model.patterns().any(|(s, f)| {
            model.scale(s, lambda) != 0.0
                && f.iter()
                    .enumerate()
                    .any(|(d, &v)| v != 0.0 && !section_dofs.contains(&d))
        }) || (model.prescribed.iter().zip(&model.prescribed_history))
            .any(|(&(d, v), &h)| v != 0.0 && on(h) && d < model.mesh.num_dofs());
        if !others {
            return None;
        }
        model.sections.iter().find_map(|s| {
            let force: f64 = model
                .patterns()
                .map(|(sc, f)| f[s.dof] * model.scale(sc, lambda))
                .sum();
            (free_at(s, lambda) && force != 0.0).then(|| {
                format!(
                    "pretension \"{}\" is {} at λ = {}: its force, {force:.6e} N, is all that \
                     holds the two sides of its cut together while other loads act, and a load \
                     that pulls them apart harder has no equilibrium (the joint opens and the \
                     section lengthens without end){}",
                    s.name,
                    control(s),
                    short(lambda),
                    if s.lock_after.is_finite() {
                        ""
                    } else {
                        "; lock the section (lock = true, the default) for it to take its share of the load"
                    }
                )
            })
        })
    }
}
