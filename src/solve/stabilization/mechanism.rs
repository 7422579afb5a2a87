//! The contact stabilization's springs (the mechanism of [`super`],
//! which decides when they act): the rigid-body bookkeeping of each body, the
//! spring stiffness and start guess an engine holds while a stabilized solve
//! runs, and the spring's contribution at one interface point, which the
//! Newton assembly adds. This layer knows nothing of the engine.

use crate::input::case::Stabilization;
use crate::model::interface::{InterfaceModel, Point};
use crate::model::Model;
use crate::solve::State;
use gram::Gram;

mod explain;
mod gram;

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
/// of the rows its boundary conditions impose on its rigid motions (t_x,
/// t_y, θ·L in a plane; t_x, t_y, t_z, θ_x·L, θ_y·L, θ_z·L in 3D), then the
/// motion of each pretension section that cuts it in two, [`Cut`]; with
/// twist also the rotation about the axis, u_θ = ω r, whose rows (r/L) ω are
/// gathered in the scalar `turn`.
#[derive(Clone, Debug)]
struct Body {
    centre: [f64; 3],
    size: f64,
    /// The rigid motions: 3 in a plane, 6 in 3D.
    motions: usize,
    /// The body's cuts (indices into [`Stabilizer::cuts`]), in the order of
    /// their motions after the first three.
    cuts: Vec<usize>,
    bc: Gram,
    /// Σ (r/L)² over the prescribed u_θ at r > 0 (1 without twist: nothing
    /// to hold).
    turn: f64,
    /// Force of each load pattern at factor 1 (N, Σ |f| over the body's nodes).
    load: Vec<f64>,
    /// Torque of each load pattern about the axis at factor 1 (N·mm, Σ r f_θ
    /// over the body's nodes; zero without twist).
    torque: Vec<f64>,
    /// The histories of the non-zero prescribed displacements acting on it
    /// (a prescribed shortening of a section through it among them).
    driven: Vec<Option<usize>>,
}

/// A pretension section that cuts its body in two
/// ([`crate::model::pretension::sides`]): while it is free (force control before
/// its lock) its shortening moves the side beyond the cut rigidly along the
/// cut's normal, one rigid motion more of the body, which only a support or
/// a supporting pair on that side (along the normal) holds; locked or
/// prescribed, the shortening holds it.
#[derive(Clone, Debug)]
struct Cut {
    section: usize,
    /// Each node's side: beyond the cut.
    beyond: Vec<bool>,
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
pub(crate) struct Stabilizer {
    bodies: Vec<Body>,
    /// The force-controlled pretension sections that cut their bodies in two.
    cuts: Vec<Cut>,
    /// Bodies with an interface.
    linked: Vec<bool>,
    /// Per interface, whether each pair can carry force
    /// ([`InterfaceModel::carrying_pairs`]), fixed with the model.
    carrying: Vec<Vec<bool>>,
    pub(in crate::solve) enabled: bool,
    /// Spring stiffness per interface (MPa/mm) while a stabilized solve runs.
    pub(in crate::solve) springs: Option<Vec<f64>>,
    /// Start of the next solve (all dofs) instead of the committed state.
    pub(in crate::solve) guess: Option<Vec<f64>>,
    /// Filled by the last step, moved into the report when it is committed.
    pub(in crate::solve) pending: Option<(bool, f64)>,
    pub report: Report,
    /// Steps that used the stabilization at all (committed or not).
    pub used: usize,
}

/// Whether the Gram matrix `g` and the rotation's `turn` fix every rigid
/// motion of a body.
fn fixes(g: &Gram, turn: f64) -> bool {
    g.fixes_all() && turn > 0.0
}

impl Body {
    /// The constraint row of a displacement along unit vector `e` at node
    /// `node`, at `x`: on the rigid motions, then on each cut's (the
    /// component along the cut's normal on the side beyond it).
    fn row(&self, cuts: &[Cut], model: &Model, node: usize, x: [f64; 3], e: [f64; 3]) -> Vec<f64> {
        let mut r = self.rigid_row(x, e);
        r.extend(self.cuts.iter().map(|&c| {
            let cut = &cuts[c];
            match cut.beyond.get(node) {
                Some(true) => e[model.sections[cut.section].axis],
                _ => 0.0,
            }
        }));
        r
    }

    /// The row of a displacement along `e` at `x` on the rigid motions
    /// u = a + ω × (x − x̄): u·e = a·e + ω·((x − x̄) × e), with ω scaled by
    /// the size L; in a plane the in-plane three (the z of the cross
    /// product).
    fn rigid_row(&self, x: [f64; 3], e: [f64; 3]) -> Vec<f64> {
        let (rx, ry) = (
            (x[0] - self.centre[0]) / self.size,
            (x[1] - self.centre[1]) / self.size,
        );
        if self.motions == 3 {
            return vec![e[0], e[1], e[1] * rx - e[0] * ry];
        }
        let r = [rx, ry, (x[2] - self.centre[2]) / self.size];
        let w = crate::numbers::vec3::cross(r, e);
        vec![e[0], e[1], e[2], w[0], w[1], w[2]]
    }

    /// The row holding the motion of the body's `k`-th cut (its section's
    /// shortening locked or prescribed).
    fn cut_row(&self, k: usize) -> Vec<f64> {
        let mut r = vec![0.0; self.motions + self.cuts.len()];
        r[self.motions + k] = 1.0;
        r
    }

    /// The row (r/L) of a u_θ at `x` on the rotation about the axis; zero
    /// on the axis, where u_θ = ω r vanishes.
    fn turn_row(&self, x: [f64; 3]) -> f64 {
        let r = x[0].abs() / self.size;
        if r > 1e-9 {
            r * r
        } else {
            0.0
        }
    }
}

/// Each body's box (its centre and size scale the rows of its rigid
/// motions), the force-controlled cuts it holds and, on a body of
/// revolution, the motions its symmetry holds; no support or load yet.
fn rigid_bodies(model: &Model, body_of: &[usize], cuts: &[Cut]) -> Vec<Body> {
    let mesh = &model.mesh;
    let nb = mesh.bodies.len();
    let twist = model.node_dofs().twist();
    let dim = mesh.dim();
    let motions = if dim == 3 { 6 } else { 3 };
    let mut lo = vec![[0.0f64; 3]; nb];
    let mut hi = vec![[0.0f64; 3]; nb];
    for b in 0..nb {
        for c in 0..dim {
            (lo[b][c], hi[b][c]) = (f64::INFINITY, f64::NEG_INFINITY);
        }
    }
    for (n, x) in mesh.nodes.iter().enumerate() {
        if let Some(b) = body_of.get(n).copied().filter(|&b| b < nb) {
            for c in 0..dim {
                lo[b][c] = lo[b][c].min(x[c]);
                hi[b][c] = hi[b][c].max(x[c]);
            }
        }
    }
    let mut bodies: Vec<Body> = (0..nb)
        .map(|b| {
            let cuts: Vec<usize> = (0..cuts.len())
                .filter(|&c| model.sections[cuts[c].section].body == b)
                .collect();
            Body {
                centre: std::array::from_fn(|c| 0.5 * (lo[b][c] + hi[b][c])),
                size: (0..3)
                    .map(|c| hi[b][c] - lo[b][c])
                    .fold(f64::MIN_POSITIVE, f64::max),
                motions,
                bc: Gram::new(motions + cuts.len()),
                cuts,
                turn: if twist { 0.0 } else { 1.0 },
                load: vec![0.0; model.patterns().count()],
                torque: vec![0.0; model.patterns().count()],
                driven: Vec::new(),
            }
        })
        .collect();
    if model.section.axisymmetric {
        // a body of revolution has one rigid motion, along the axis: a
        // radial translation strains it around the hoop, and it cannot
        // rotate in the meridian plane
        for b in &mut bodies {
            let n = b.motions + b.cuts.len();
            let unit = |i: usize| {
                (0..n)
                    .map(|j| f64::from(u8::from(i == j)))
                    .collect::<Vec<_>>()
            };
            b.bc.add(&unit(0));
            b.bc.add(&unit(2));
        }
    }
    bodies
}

/// Adds each prescribed dof to the rows of the motions its body's supports
/// hold (or, u_θ, to the rotation about the axis), and the load histories
/// that drive a body.
fn hold_by_supports(model: &Model, body_of: &[usize], cuts: &[Cut], bodies: &mut [Body]) {
    let mesh = &model.mesh;
    let nb = mesh.bodies.len();
    for (&(d, v), &h) in model.prescribed.iter().zip(&model.prescribed_history) {
        // u_θ (twist) holds the rotation about the axis, the in-plane
        // dofs the motions in the meridian plane; a section's reference
        // node (after the mesh's) belongs to the body it cuts
        let (n, c) = model.node_dofs().node_of(d);
        let b = match body_of.get(n) {
            Some(&b) if b < nb => b,
            Some(_) => continue,
            None => match model.sections.get(n - mesh.nodes.len()) {
                Some(s) if c == 0 => s.body,
                _ => continue,
            },
        };
        match c {
            _ if n >= mesh.nodes.len() => {}
            _ if c < mesh.dim() => {
                let mut e = [0.0; 3];
                e[c] = 1.0;
                let r = bodies[b].row(cuts, model, n, mesh.nodes[n], e);
                bodies[b].bc.add(&r);
            }
            _ => bodies[b].turn += bodies[b].turn_row(mesh.nodes[n]),
        }
        if v != 0.0 && !bodies[b].driven.contains(&h) {
            bodies[b].driven.push(h);
        }
    }
}

/// Adds the rows of a cyclic sector's ties ([`crate::model::cyclic`]): a
/// pair (m, s) of one body holds the rigid motions u = a + ω × (x − x̄)
/// to u(x_s) = R u(x_m), three rows eᵢ·u(x_s) − (Rᵀeᵢ)·u(x_m) (docs/theory.md,
/// "Cyclic symmetry"). A body tied across its cut faces is so held against
/// every motion but the translation along the axis and the rotation about
/// it, as the model's rigid-body check counts them.
fn hold_by_ties(model: &Model, body_of: &[usize], cuts: &[Cut], bodies: &mut [Body]) {
    let Some(cyclic) = model.cyclic.as_ref() else {
        return;
    };
    let rot = crate::model::cyclic::rotation(cyclic.angle);
    let nodes = &model.mesh.nodes;
    for &(m, s) in &cyclic.pairs {
        let b = body_of[s];
        if b >= bodies.len() || body_of[m] != b {
            continue;
        }
        for i in 0..3 {
            let mut e = [0.0; 3];
            e[i] = 1.0;
            let back = [rot[i][0], rot[i][1], rot[i][2]];
            let at_s = bodies[b].row(cuts, model, s, nodes[s], e);
            let at_m = bodies[b].row(cuts, model, m, nodes[m], back);
            let r: Vec<f64> = at_s.iter().zip(&at_m).map(|(p, q)| p - q).collect();
            bodies[b].bc.add(&r);
        }
    }
}

/// Adds the size of each load pattern's forces on a body (and, with twist,
/// their torque about the axis): the scale of the forces that move it.
fn add_loads(model: &Model, body_of: &[usize], bodies: &mut [Body]) {
    let mesh = &model.mesh;
    let nb = mesh.bodies.len();
    let twist = model.node_dofs().twist();
    for (p, (_, f)) in model.patterns().enumerate() {
        for (n, &b) in body_of.iter().enumerate() {
            if b < nb {
                let v = &f[model.node_dofs().of(n)];
                bodies[b].load[p] += v.iter().skip(2).fold(v[0].hypot(v[1]), |a, x| a.hypot(*x));
                if twist {
                    bodies[b].torque[p] += mesh.nodes[n][0] * v[2];
                }
            }
        }
        // a section's force loads the body it cuts
        for s in &model.sections {
            bodies[s.body].load[p] += f[s.dof].abs();
        }
    }
}

impl Stabilizer {
    /// The stabilizer of a model: its bodies' rigid motions, what holds and
    /// what loads each, the force-controlled cuts and the interfaces' carrying
    /// pairs.
    pub fn new(model: &Model) -> Stabilizer {
        let mesh = &model.mesh;
        let nb = mesh.bodies.len();
        let body_of = mesh.node_bodies();
        // a prescribed shortening holds its cut: only a force-controlled
        // section adds a motion (held again once it is locked)
        let cuts: Vec<Cut> = (model.sections.iter().enumerate())
            .filter(|(_, s)| s.control == "force")
            .filter_map(|(k, s)| {
                crate::model::pretension::sides(mesh, s).map(|beyond| Cut { section: k, beyond })
            })
            .collect();
        let mut bodies = rigid_bodies(model, &body_of, &cuts);
        hold_by_supports(model, &body_of, &cuts, &mut bodies);
        hold_by_ties(model, &body_of, &cuts, &mut bodies);
        add_loads(model, &body_of, &mut bodies);
        // a body without an interface and without enough supports is a
        // mechanism no interface spring can hold (and mostly refused up front)
        let linked = (0..nb)
            .map(|b| (model.interfaces.iter()).any(|im| im.body_a == b || im.body_b == b))
            .collect();
        Stabilizer {
            bodies,
            cuts,
            linked,
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
        self.floating_as(model, u, lambda, |s| {
            crate::model::pretension::free_at(s, lambda)
        })
    }

    /// [`Stabilizer::floating`] with the sections `free` says are free
    /// (the others hold their cuts).
    fn floating_as(
        &self,
        model: &Model,
        u: &[f64],
        lambda: f64,
        free: impl Fn(&crate::model::pretension::Section) -> bool,
    ) -> Vec<usize> {
        let mut held: Vec<bool> = (0..self.bodies.len())
            .map(|b| !self.loose_as(model, b, &free))
            .collect();
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
                let mut g = self.own(model, b, &free);
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
                            let node = if im.body_a == b { pr.a } else { pr.b };
                            let row = |e| body.row(&self.cuts, model, node, pr.x, e);
                            g.add(&row(pr.normal));
                            if im.tangential.is_some() && un > 0.0 {
                                for t in tangents(pr.normal, model.mesh.dim()) {
                                    g.add(&row(t));
                                }
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

    /// The rows body `b`'s own supports impose, and its cuts whose sections
    /// `free` does not free (locked, [`crate::model::pretension::free_at`]).
    fn own(
        &self,
        model: &Model,
        b: usize,
        free: &impl Fn(&crate::model::pretension::Section) -> bool,
    ) -> Gram {
        let body = &self.bodies[b];
        let mut g = body.bc.clone();
        for (k, &c) in body.cuts.iter().enumerate() {
            if !free(&model.sections[self.cuts[c].section]) {
                g.add(&body.cut_row(k));
            }
        }
        g
    }

    /// Whether body `b` has an interface and its own supports leave a rigid
    /// motion free (its cuts' sections free as `free` says).
    fn loose_as(
        &self,
        model: &Model,
        b: usize,
        free: &impl Fn(&crate::model::pretension::Section) -> bool,
    ) -> bool {
        self.linked[b] && !fixes(&self.own(model, b, free), self.bodies[b].turn)
    }

    /// [`Stabilizer::loose_as`] in a step to `lambda`.
    fn loose(&self, model: &Model, b: usize, lambda: f64) -> bool {
        self.loose_as(model, b, &|s| crate::model::pretension::free_at(s, lambda))
    }

    /// Whether a body held only through interfaces carries no load at
    /// pseudo-time `lambda`: every load pattern and prescribed displacement
    /// acting on it at factor 0 there (all of them at λ = 0 without
    /// histories), and no interference on its interfaces.
    pub(in crate::solve) fn unloaded(&self, model: &Model, lambda: f64) -> Option<usize> {
        (0..self.bodies.len())
            .find(|&b| self.loose(model, b, lambda) && !self.carries_load(model, b, lambda))
    }

    /// Whether some body held only through interfaces carries a load at
    /// `lambda`: then a body of [`Stabilizer::unloaded`] may still be pressed
    /// into place by it (the middle disk of a stack loaded on its top), and a
    /// stabilized step is released when it can be.
    pub(in crate::solve) fn any_loaded(&self, model: &Model, lambda: f64) -> bool {
        (0..self.bodies.len())
            .any(|b| self.loose(model, b, lambda) && self.carries_load(model, b, lambda))
    }

    /// Whether body `b` carries a load at `lambda`: a load pattern or a
    /// prescribed displacement acting on it at a non-zero factor, or an
    /// interference on one of its interfaces.
    fn carries_load(&self, model: &Model, b: usize, lambda: f64) -> bool {
        let body = &self.bodies[b];
        let on = |h: Option<usize>| model.factor(h, lambda) != 0.0;
        (body.load.iter().zip(model.patterns()))
            .any(|(&l, (s, _))| l != 0.0 && model.scale(s, lambda) != 0.0)
            || body.driven.iter().any(|&h| on(h))
            || (model.interfaces.iter())
                .any(|im| (im.body_a == b || im.body_b == b) && im.gap_at(lambda) < 0.0)
    }

    /// Called when the engine's last step is committed; whether that step
    /// was a plain one (neither stabilized nor released).
    pub(in crate::solve) fn commit(&mut self) -> bool {
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

/// The unit tangents of the plane normal to `n`: (n_y, −n_x) in a plane,
/// t₁ and t₂ = n × t₁ of the slip frame in 3D.
fn tangents(n: [f64; 3], dim: usize) -> Vec<[f64; 3]> {
    if dim == 2 {
        return vec![[n[1], -n[0], 0.0]];
    }
    crate::model::interface::tangents(n).to_vec()
}

/// Adds the stabilization spring of one interface point to its local residual
/// `r` and matrix `k` (the layout of [`InterfaceModel::eval_point`]): stiffness
/// `ks` per area on the change of the relative displacement since `committed`.
/// Abaqus-style contact stabilization (see the module documentation).
pub(crate) fn add_point(
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
pub(in crate::solve) fn increment(
    im: &InterfaceModel,
    pt: &Point,
    committed: &[f64],
    u: &[f64],
) -> [f64; 3] {
    let (n1, t1) = im.point_kinematics(pt, u);
    let (n0, t0) = im.point_kinematics(pt, committed);
    let dh = im.point_second_slip(pt, u) - im.point_second_slip(pt, committed);
    [n1 - n0, t1 - t0, dh]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> Body {
        Body {
            centre: [10.0, 10.0, 0.0],
            size: 20.0,
            motions: 3,
            cuts: Vec::new(),
            bc: Gram::new(3),
            turn: 0.0,
            load: Vec::new(),
            torque: Vec::new(),
            driven: Vec::new(),
        }
    }

    #[test]
    fn the_rotation_about_the_axis_is_held_by_rows_off_the_axis_only() {
        let b = body();
        let mut g = Gram::new(3);
        g.add(&[1.0, 0.0, 0.0]);
        g.add(&[0.0, 0.0, 1.0]);
        g.add(&b.rigid_row([3.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        assert!(g.fixes_all());
        // in-plane held, but nothing about the axis (twist)
        assert!(!fixes(&g, b.turn));
        // a u_θ on the axis holds nothing (u_θ = ω r vanishes there)
        assert_eq!(b.turn_row([0.0, 5.0, 0.0]), 0.0);
        assert!(!fixes(&g, b.turn + b.turn_row([0.0, 5.0, 0.0])));
        // one off the axis holds it: (r/L)² = (5/20)²
        assert_eq!(b.turn_row([5.0, 5.0, 0.0]), 0.0625);
        assert!(fixes(&g, b.turn + b.turn_row([5.0, 5.0, 0.0])));
    }

    #[test]
    fn rows_fix_the_rigid_motions_they_should() {
        let b = body();
        // u_x = 0 along the left edge: x translation and rotation, not y
        let mut g = Gram::new(3);
        for y in [0.0, 5.0, 10.0, 20.0] {
            g.add(&b.rigid_row([0.0, y, 0.0], [1.0, 0.0, 0.0]));
        }
        assert!(!g.fixes_all());
        // one vertical support more fixes all three
        let mut h = g.clone();
        h.add(&b.rigid_row([3.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        assert!(h.fixes_all());
        // normal springs along a horizontal interface: y and rotation, with
        // the left edge's x: all three
        let mut s = g.clone();
        for x in [0.0, 10.0, 20.0] {
            s.add(&b.rigid_row([x, 0.0, 0.0], [0.0, 1.0, 0.0]));
        }
        assert!(s.fixes_all());
        // vertical springs at one point only leave the rotation free without x
        let mut one = Gram::new(3);
        one.add(&b.rigid_row([5.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        one.add(&b.rigid_row([5.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        assert!(!one.fixes_all());
        assert!(!Gram::new(3).fixes_all());
    }
}
