//! The contact stabilization's springs (the mechanism of [`super::stabilize`],
//! which decides when they act): the rigid-body bookkeeping of each body, the
//! spring stiffness and start guess an engine holds while a stabilized solve
//! runs, and the spring's contribution at one interface point, which the
//! Newton assembly adds. This layer knows nothing of the engine.

use super::State;
use crate::case::Stabilization;
use crate::interface::{InterfaceModel, Point};
use crate::model::Model;

/// An approach above this counts as contact able to carry load (mm): the
/// first iteration of a step gives such pairs the secant start stiffness.
const TOUCH: f64 = -1e-12;

/// A closed pair supports a body when its pressure is at least this fraction
/// of the step's reference pressure: a pair left touching at a pressure of
/// 10⁻¹⁷ MPa after unloading to zero has a tangent (2p/u for m = 1/2) too
/// small to carry the next load step.
const SUPPORT: f64 = 1e-8;

/// A failed step whose torque on a body held about the axis only by
/// friction is at least this fraction of what that friction held at the last
/// converged pressures is explained by it: the pressures of the step's end
/// are unknown (a clamp unloaded under a held torque lowers them: the step
/// that crosses the slip torque starts below it), and close to the slip
/// torque the sticking core that is left carries the whole torque, whose
/// last steps Newton may not reach (a shrink fit failed at 98.9 % of it).
const NEAR_SLIP: f64 = 0.98;

/// Rigid-body constraint data of one body: centroid, size and the Gram matrix
/// of the rows its boundary conditions impose on (t_x, t_y, θ·L); with twist
/// also the rotation about the axis, u_θ = ω r, whose rows (r/L) ω are
/// gathered in the scalar `turn`.
#[derive(Clone, Debug)]
struct Body {
    centre: [f64; 2],
    size: f64,
    bc: [f64; 6],
    /// Σ (r/L)² over the prescribed u_θ at r > 0 (1 without twist: nothing
    /// to hold).
    turn: f64,
    /// Force of each load pattern at factor 1 (N, Σ |f| over the body's nodes).
    load: Vec<f64>,
    /// Torque of each load pattern about the axis at factor 1 (N·mm, Σ r f_θ
    /// over the body's nodes; zero without twist).
    torque: Vec<f64>,
    /// The histories of the non-zero prescribed displacements acting on it.
    driven: Vec<Option<usize>>,
}

/// What the run reports about stabilization (summary.json "stabilization").
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Steps that started stabilized and were released (exact answer).
    pub released: usize,
    /// Steps accepted with the springs still acting (no release possible).
    pub stabilized: usize,
    /// Energy dissipated by the springs in accepted steps, N·mm.
    pub dissipated: f64,
    /// Largest internal energy seen (strain + plastic work + interface), N·mm.
    pub internal: f64,
    /// The limit on dissipated / internal.
    pub limit: f64,
}

/// The stabilization of one engine.
#[derive(Clone, Debug)]
pub struct Stabilizer {
    bodies: Vec<Body>,
    /// Bodies with an interface whose boundary conditions leave a rigid motion free.
    loose: Vec<bool>,
    /// Per interface, whether each pair can carry force
    /// ([`InterfaceModel::carrying_pairs`]), fixed with the model.
    carrying: Vec<Vec<bool>>,
    pub(super) enabled: bool,
    /// Spring stiffness per interface (MPa/mm) while a stabilized solve runs.
    pub(super) springs: Option<Vec<f64>>,
    /// Start of the next solve (all dofs) instead of the committed state.
    pub(super) guess: Option<Vec<f64>>,
    /// Filled by the last step, moved into the report when it is committed.
    pub(super) pending: Option<(bool, f64)>,
    pub report: Report,
    /// Steps that used the stabilization at all (committed or not).
    pub used: usize,
}

fn det3(g: &[f64; 6]) -> f64 {
    // packed symmetric [g00, g01, g02, g11, g12, g22]
    let [a, b, c, d, e, f] = *g;
    a * (d * f - e * e) - b * (b * f - e * c) + c * (b * e - d * c)
}

/// Whether the rows gathered in a Gram matrix fix all three rigid motions.
fn fixes_all(g: &[f64; 6]) -> bool {
    let tr = g[0] + g[3] + g[5];
    tr > 0.0 && det3(g) > 1e-9 * (tr / 3.0).powi(3)
}

/// Whether the in-plane Gram matrix `g` and the rotation's `turn` fix every
/// rigid motion of a body.
fn fixes(g: &[f64; 6], turn: f64) -> bool {
    fixes_all(g) && turn > 0.0
}

fn add_row(g: &mut [f64; 6], r: [f64; 3]) {
    g[0] += r[0] * r[0];
    g[1] += r[0] * r[1];
    g[2] += r[0] * r[2];
    g[3] += r[1] * r[1];
    g[4] += r[1] * r[2];
    g[5] += r[2] * r[2];
}

impl Body {
    /// The constraint row of a displacement along unit vector `e` at `x`.
    fn row(&self, x: [f64; 2], e: [f64; 2]) -> [f64; 3] {
        let (rx, ry) = (
            (x[0] - self.centre[0]) / self.size,
            (x[1] - self.centre[1]) / self.size,
        );
        [e[0], e[1], e[1] * rx - e[0] * ry]
    }

    /// The row (r/L) of a u_θ at `x` on the rotation about the axis; zero
    /// on the axis, where u_θ = ω r vanishes.
    fn turn_row(&self, x: [f64; 2]) -> f64 {
        let r = x[0].abs() / self.size;
        if r > 1e-9 {
            r * r
        } else {
            0.0
        }
    }
}

impl Stabilizer {
    pub fn new(model: &Model) -> Stabilizer {
        let mesh = &model.mesh;
        let nb = mesh.bodies.len();
        let body_of = mesh.node_bodies();
        let mut lo = vec![[f64::INFINITY; 2]; nb];
        let mut hi = vec![[f64::NEG_INFINITY; 2]; nb];
        for (n, x) in mesh.nodes.iter().enumerate() {
            if let Some(b) = body_of.get(n).copied().filter(|&b| b < nb) {
                for c in 0..2 {
                    lo[b][c] = lo[b][c].min(x[c]);
                    hi[b][c] = hi[b][c].max(x[c]);
                }
            }
        }
        let twist = model.node_dofs().twist();
        let mut bodies: Vec<Body> = (0..nb)
            .map(|b| Body {
                centre: [0.5 * (lo[b][0] + hi[b][0]), 0.5 * (lo[b][1] + hi[b][1])],
                size: (hi[b][0] - lo[b][0])
                    .max(hi[b][1] - lo[b][1])
                    .max(f64::MIN_POSITIVE),
                bc: [0.0; 6],
                turn: if twist { 0.0 } else { 1.0 },
                load: vec![0.0; model.patterns().count()],
                torque: vec![0.0; model.patterns().count()],
                driven: Vec::new(),
            })
            .collect();
        if model.section.axisymmetric {
            // a body of revolution has one rigid motion, along the axis: a
            // radial translation strains it around the hoop, and it cannot
            // rotate in the meridian plane
            for b in &mut bodies {
                add_row(&mut b.bc, [1.0, 0.0, 0.0]);
                add_row(&mut b.bc, [0.0, 0.0, 1.0]);
            }
        }
        for (&(d, v), &h) in model.prescribed.iter().zip(&model.prescribed_history) {
            // u_θ (twist) holds the rotation about the axis, the in-plane
            // dofs the motions in the meridian plane
            let (n, c) = model.node_dofs().node_of(d);
            let Some(b) = body_of.get(n).copied().filter(|&b| b < nb) else {
                continue;
            };
            match c {
                0 | 1 => {
                    let e = if c == 0 { [1.0, 0.0] } else { [0.0, 1.0] };
                    let r = bodies[b].row(mesh.nodes[n], e);
                    add_row(&mut bodies[b].bc, r);
                }
                _ => bodies[b].turn += bodies[b].turn_row(mesh.nodes[n]),
            }
            if v != 0.0 && !bodies[b].driven.contains(&h) {
                bodies[b].driven.push(h);
            }
        }
        for (p, (_, f)) in model.patterns().enumerate() {
            for (n, &b) in body_of.iter().enumerate() {
                if b < nb {
                    let v = &f[model.node_dofs().of(n)];
                    bodies[b].load[p] +=
                        v.iter().skip(2).fold(v[0].hypot(v[1]), |a, x| a.hypot(*x));
                    if twist {
                        bodies[b].torque[p] += mesh.nodes[n][0] * v[2];
                    }
                }
            }
        }
        // a body without an interface and without enough supports is a
        // mechanism no interface spring can hold (and mostly refused up front)
        let loose = (0..nb)
            .map(|b| {
                !fixes(&bodies[b].bc, bodies[b].turn)
                    && model
                        .interfaces
                        .iter()
                        .any(|im| im.body_a == b || im.body_b == b)
            })
            .collect();
        Stabilizer {
            bodies,
            loose,
            carrying: model
                .interfaces
                .iter()
                .map(InterfaceModel::carrying_pairs)
                .collect(),
            enabled: model.solver.stabilization == Stabilization::Auto,
            springs: None,
            guess: None,
            pending: None,
            report: Report {
                limit: model.solver.stabilization_energy,
                ..Report::default()
            },
            used: 0,
        }
    }

    /// The bodies not held at displacement `u` in a step to `lambda`: neither
    /// by their boundary conditions nor through supporting pairs with a held
    /// body (approach in (−1e-12, 0] mm, where the secant start applies, or
    /// closed with a pressure of at least [`SUPPORT`] × the step's reference
    /// pressure); ascending. Only pairs that can carry force support
    /// ([`InterfaceModel::carrying_pairs`]): a pair without area, such as the
    /// apex of a sphere on the axis under lumped weights, touches at zero
    /// approach but holds nothing.
    pub fn floating(&self, model: &Model, u: &[f64], lambda: f64) -> Vec<usize> {
        let mut held: Vec<bool> = self.loose.iter().map(|l| !l).collect();
        if held.iter().all(|&h| h) {
            return Vec::new();
        }
        let p_min: Vec<f64> = (0..model.interfaces.len())
            .map(|i| SUPPORT * model.reference_pressure(i, lambda))
            .collect();
        loop {
            let mut changed = false;
            for b in 0..self.bodies.len() {
                if held[b] {
                    continue;
                }
                let body = &self.bodies[b];
                let mut g = body.bc;
                let mut turn = body.turn;
                for (i, im) in model.interfaces.iter().enumerate() {
                    let other = if im.body_a == b {
                        im.body_b
                    } else if im.body_b == b {
                        im.body_a
                    } else {
                        continue;
                    };
                    if !held[other] {
                        continue;
                    }
                    let gap = im.gap_at(lambda);
                    for (pr, _) in im.pairs.iter().zip(&self.carrying[i]).filter(|(_, &c)| c) {
                        let un = im.pair_approach_at(pr, u, gap);
                        let supports = if un > 0.0 {
                            im.law.pressure(un).0 >= p_min[i]
                        } else {
                            un > TOUCH
                        };
                        if supports {
                            add_row(&mut g, body.row(pr.x, pr.normal));
                            if im.tangential.is_some() && un > 0.0 {
                                add_row(&mut g, body.row(pr.x, [pr.normal[1], -pr.normal[0]]));
                                // friction around the axis as well (twist)
                                turn += body.turn_row(pr.x);
                            }
                        }
                    }
                }
                if fixes(&g, turn) {
                    held[b] = true;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        (0..held.len()).filter(|&b| !held[b]).collect()
    }

    /// Whether a body held only through interfaces carries no load at
    /// pseudo-time `lambda`: every load pattern and prescribed displacement
    /// acting on it at factor 0 there (all of them at λ = 0 without
    /// histories), and no interference on its interfaces.
    pub(super) fn unloaded(&self, model: &Model, lambda: f64) -> Option<usize> {
        (0..self.bodies.len()).find(|&b| self.loose[b] && !self.carries_load(model, b, lambda))
    }

    /// Whether some body held only through interfaces carries a load at
    /// `lambda`: then a body of [`Stabilizer::unloaded`] may still be pressed
    /// into place by it (the middle disk of a stack loaded on its top), and a
    /// stabilized step is released when it can be.
    pub(super) fn any_loaded(&self, model: &Model, lambda: f64) -> bool {
        (0..self.bodies.len()).any(|b| self.loose[b] && self.carries_load(model, b, lambda))
    }

    /// Whether body `b` carries a load at `lambda`: a load pattern or a
    /// prescribed displacement acting on it at a non-zero factor, or an
    /// interference on one of its interfaces.
    fn carries_load(&self, model: &Model, b: usize, lambda: f64) -> bool {
        let body = &self.bodies[b];
        let on = |h: Option<usize>| model.factor(h, lambda) != 0.0;
        (body.load.iter().zip(model.patterns())).any(|(&l, (h, _))| l != 0.0 && on(h))
            || body.driven.iter().any(|&h| on(h))
            || (model.interfaces.iter())
                .any(|im| (im.body_a == b || im.body_b == b) && im.gap_at(lambda) < 0.0)
    }

    /// A body held about the axis only by friction (twist: no prescribed
    /// rotation of its own) whose applied torque at `lambda` exceeds the most
    /// its interfaces' friction can hold at the pressures of `u`,
    /// Σ μ_m p_N r A (μ_m the friction cap, eq. 2.21): a torque-controlled
    /// twist past the slip torque, which has no equilibrium.
    fn beyond_friction(&self, model: &Model, u: &[f64], lambda: f64) -> Option<String> {
        if !model.node_dofs().twist() {
            return None;
        }
        (0..self.bodies.len()).find_map(|b| {
            let body = &self.bodies[b];
            if body.turn > 0.0 {
                return None;
            }
            let applied: f64 = (body.torque.iter().zip(model.patterns()))
                .map(|(&t, (h, _))| t * model.factor(h, lambda))
                .sum();
            let mut names = Vec::new();
            let mut hold = 0.0;
            for im in &model.interfaces {
                let Some(law) = im.tangential.as_ref() else {
                    continue;
                };
                if im.body_a != b && im.body_b != b {
                    continue;
                }
                names.push(im.name.as_str());
                let gap = im.gap_at(lambda);
                for (pt, r) in im.points.iter().zip(im.point_radii()) {
                    let un = im.point_kinematics_at(pt, u, gap).0;
                    hold += pt.area * law.mu * im.law.pressure(un).0 * r;
                }
            }
            (applied != 0.0 && applied.abs() >= NEAR_SLIP * hold && !names.is_empty()).then(|| {
                let lambda = format!("{lambda:.6}")
                    .trim_end_matches('0')
                    .trim_end_matches('.')
                    .to_string();
                let how = if applied.abs() > hold {
                    "more than".to_string()
                } else {
                    format!("{:.2} % of what", 100.0 * applied.abs() / hold)
                };
                format!(
                    "the torque on body \"{}\" at λ = {lambda}, {:.6e} N·mm, is {how} the friction of interface \"{}\" can hold about the axis at the present contact pressures, Σ μ p_N r dA = {hold:.6e} N·mm, and nothing else holds the body about the axis: a torque at or past the slip torque has no equilibrium (prescribe a [[boundary]] rotation instead to turn the joint past slip)",
                    model.mesh.bodies[b],
                    applied.abs(),
                    names.join("\", \"")
                )
            })
        })
    }

    /// The physical reason a step from `committed` to `lambda` may have no
    /// solution, if there is one: a body held by nothing, or held about the
    /// axis by friction only and loaded by a torque beyond it.
    pub fn explain(&self, model: &Model, committed: &State, lambda: f64) -> Option<String> {
        if let Some(why) = self.beyond_friction(model, &committed.u, lambda) {
            return Some(why);
        }
        let unloaded = self.unloaded(model, lambda);
        let floating = self.floating(model, &committed.u, lambda);
        let b = unloaded.or(floating.first().copied())?;
        // λ as short as it is exact to six places: "0", "0.5", "0.000195"
        let lambda = format!("{lambda:.6}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string();
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

    /// Called when the engine's last step is committed; whether that step
    /// was a plain one (neither stabilized nor released).
    pub(super) fn commit(&mut self) -> bool {
        let Some((stabilized, w)) = self.pending.take() else {
            return true;
        };
        if stabilized {
            self.report.stabilized += 1;
            self.report.dissipated += w;
        } else {
            self.report.released += 1;
        }
        false
    }
}

/// Adds the stabilization spring of one interface point to its local residual
/// `r` and matrix `k` (the layout of [`InterfaceModel::eval_point`]): stiffness
/// `ks` per area on the change of the relative displacement since `committed`.
/// Abaqus-style contact stabilization (see the module documentation).
pub fn add_point(
    im: &InterfaceModel,
    pt: &Point,
    ks: f64,
    committed: &[f64],
    u: &[f64],
    r: &mut [f64],
    k: &mut [f64],
) {
    let [dn, dt, dh] = increment(im, pt, committed, u);
    let g = im.point_gradients(pt);
    let (gn, gt) = (g.n, g.t);
    let nd = im.point_ndofs(pt);
    let a = pt.area * ks;
    for i in 0..nd {
        r[i] += a * (dn * gn[i] + dt * gt[i]);
        for j in 0..nd {
            k[i * nd + j] += a * (gn[i] * gn[j] + gt[i] * gt[j]);
        }
    }
    // with twist, around the axis as well: u_Tθ's spring holds a body that
    // only friction would hold about the axis once in contact
    let gh = g.h;
    if !gh.is_empty() {
        for i in 0..nd {
            r[i] += a * dh * gh[i];
            for j in 0..nd {
                k[i * nd + j] += a * gh[i] * gh[j];
            }
        }
    }
}

/// Change of the normal, tangential and (twist) circumferential relative
/// displacement at a point; the last is 0 without twist.
pub(super) fn increment(im: &InterfaceModel, pt: &Point, committed: &[f64], u: &[f64]) -> [f64; 3] {
    let (n1, t1) = im.point_kinematics(pt, u);
    let (n0, t0) = im.point_kinematics(pt, committed);
    let dh = im.point_hoop_slip(pt, u) - im.point_hoop_slip(pt, committed);
    [n1 - n0, t1 - t0, dh]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> Body {
        Body {
            centre: [10.0, 10.0],
            size: 20.0,
            bc: [0.0; 6],
            turn: 0.0,
            load: Vec::new(),
            torque: Vec::new(),
            driven: Vec::new(),
        }
    }

    #[test]
    fn the_rotation_about_the_axis_is_held_by_rows_off_the_axis_only() {
        let b = body();
        let mut g = [0.0; 6];
        add_row(&mut g, [1.0, 0.0, 0.0]);
        add_row(&mut g, [0.0, 0.0, 1.0]);
        add_row(&mut g, b.row([3.0, 0.0], [0.0, 1.0]));
        assert!(fixes_all(&g));
        // in-plane held, but nothing about the axis (twist)
        assert!(!fixes(&g, b.turn));
        // a u_θ on the axis holds nothing (u_θ = ω r vanishes there)
        assert_eq!(b.turn_row([0.0, 5.0]), 0.0);
        assert!(!fixes(&g, b.turn + b.turn_row([0.0, 5.0])));
        // one off the axis holds it: (r/L)² = (5/20)²
        assert_eq!(b.turn_row([5.0, 5.0]), 0.0625);
        assert!(fixes(&g, b.turn + b.turn_row([5.0, 5.0])));
    }

    #[test]
    fn rows_fix_the_rigid_motions_they_should() {
        let b = body();
        // u_x = 0 along the left edge: x translation and rotation, not y
        let mut g = [0.0; 6];
        for y in [0.0, 5.0, 10.0, 20.0] {
            add_row(&mut g, b.row([0.0, y], [1.0, 0.0]));
        }
        assert!(!fixes_all(&g));
        // one vertical support more fixes all three
        let mut h = g;
        add_row(&mut h, b.row([3.0, 0.0], [0.0, 1.0]));
        assert!(fixes_all(&h));
        // normal springs along a horizontal interface: y and rotation, with
        // the left edge's x: all three
        let mut s = g;
        for x in [0.0, 10.0, 20.0] {
            add_row(&mut s, b.row([x, 0.0], [0.0, 1.0]));
        }
        assert!(fixes_all(&s));
        // vertical springs at one point only leave the rotation free without x
        let mut one = [0.0; 6];
        add_row(&mut one, b.row([5.0, 0.0], [0.0, 1.0]));
        add_row(&mut one, b.row([5.0, 0.0], [0.0, 1.0]));
        assert!(!fixes_all(&one));
        assert!(!fixes_all(&[0.0; 6]));
    }
}
