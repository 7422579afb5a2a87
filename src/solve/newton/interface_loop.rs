//! The interface loop: within one Newton iteration, the interface law solved
//! exactly on the tangent condensed on the interface equations (issue 29,
//! docs/performance.md "Contact status convergence", docs/theory.md "The
//! interface loop").
//!
//! The bodies' linearization at x_k is held fixed and only the springs'
//! law is nonlinear. With K = K_b + K_s (K_s: the interface points' blocks
//! as assembled, on the interface equations I only) the correction Δ solves
//!
//! ```text
//!   R(x_k) + K_b Δ + r_s(x_k + Δ) − r_s(x_k) = 0.
//! ```
//!
//! Eliminating the bulk equations B (`Δ_B = −K_BB⁻¹ (R_B + K_BI Δ_I)`) leaves
//! m equations in d = Δ_I. The plain Newton correction Δ⁰ = −K⁻¹ R has
//! Δ⁰_I = −(A + K_s0)⁻¹ g with g the condensed residual and A = S − K_s0 the
//! Schur complement of K_b on I (S = L_II L_IIᵀ, of the factored matrix, with
//! the interface ordered last: [`crate::linalg::backend::Condensed`]), so
//!
//! ```text
//!   F(d) = A (d − Δ⁰_I) + r_s(x_k + d) − r_s(x_k) − K_s0 Δ⁰_I = 0,
//!   J(d) = A + K_s(x_k + d)                     (dense m × m)
//! ```
//!
//! F(Δ⁰_I) is the springs' linearization error: where it is below a tenth of
//! the residual tolerance the plain correction stands, untouched (bit for
//! bit). Otherwise semismooth Newton on F from d = Δ⁰_I, each iteration a
//! dense LU of J, until ‖F‖ is below that; then the bulk follows by one
//! solve with the whole factor, `Δ = Δ⁰ + M⁻¹ [0; S (d − Δ⁰_I)]` (the bulk
//! rows of M and K are the same, and `(M⁻¹ [0; e])_I = S⁻¹ e`). The global
//! iteration then checks the true residual as before: the loop changes the
//! path to a step's solution, never its convergence test. Where it does not
//! converge within `MAX_INNER` iterations, or its matrix turns singular (a
//! body held only by points the loop opened), the iterate of the smallest
//! ‖F‖ is taken if that is below ‖F(Δ⁰_I)‖, else the plain correction stands:
//! any correction is a valid start for the next global iteration, which
//! alone decides convergence.
//!
//! For elastic bodies (R_b linear) one global correction then solves the
//! whole contact problem of the step; for plastic ones the outer loop still
//! handles the plasticity.

use super::Engine;
use crate::linalg::dense::dense_solve;
use crate::model::interface::{InterfaceModel, Point, PointEval};
use crate::model::Model;
use crate::physics::contact::PointState;
use crate::solve::State;

/// Most iterations of the interface loop in one Newton iteration.
pub(crate) const MAX_INNER: usize = 20;
/// Most evaluations of F in the line search of the loop's start
/// ([`Condensed::start`]).
const START_EVALUATIONS: usize = 40;
/// The loop stops when ‖F‖ ≤ this fraction of the Newton residual tolerance
/// (times the step's reference force).
pub(crate) const INNER_TOLERANCE: f64 = 0.1;
/// Approach (mm) above which a pair counts as "at zero approach or beyond" for
/// the secant start of eq. 2.8-2.9 in the first iteration of a step.
pub(super) const ZERO_APPROACH: f64 = 1e-12;

/// Counters of the interface loop over a run (summary.json).
#[derive(Clone, Debug, Default)]
pub struct LoopStats {
    /// Newton iterations in which the loop ran (the springs' linearization
    /// error above its tolerance).
    pub loops: usize,
    /// Its iterations (dense LU solves), in all.
    pub iterations: usize,
    /// Loops that did not converge (their iterate of the smallest ‖F‖
    /// taken, or the plain correction where none was below its ‖F‖).
    pub fallbacks: usize,
}

/// One interface point's local residual `rl` and tangent `kl` at `u` (all
/// dofs), as the Newton assembly adds them: the interface law
/// ([`InterfaceModel::eval_point_parts`], its unsymmetric coupling part in
/// `kl` when `with_coupling`), the secant floor `kf` where the point is at
/// zero approach or beyond, and the stabilization spring of stiffness
/// `spring` ([`crate::solve::stabilization::mechanism::add_point`]).
#[allow(clippy::too_many_arguments)] // the point, two states and its options
pub(super) fn point_parts(
    im: &InterfaceModel,
    pt: &Point,
    u: &[f64],
    gap: f64,
    committed_u: &[f64],
    committed: &PointState,
    kf: Option<f64>,
    spring: Option<f64>,
    rl: &mut [f64],
    kl: &mut [f64],
    with_coupling: bool,
) -> PointEval {
    let un = im.point_kinematics_at(pt, u, gap).0;
    let kfloor = kf.filter(|_| un > -ZERO_APPROACH);
    let ev = im.eval_point_parts(pt, u, gap, committed, kfloor, rl, Some(kl), with_coupling);
    if let Some(ks) = spring {
        crate::solve::stabilization::mechanism::add_point(im, pt, ks, committed_u, u, rl, kl);
    }
    ev
}

/// The interface points on the interface equations: per point, the
/// position among them of each local dof (`u32::MAX`: prescribed).
struct Points<'a> {
    model: &'a Model,
    /// The stabilization's spring stiffness per interface, while it acts.
    springs: Option<&'a [f64]>,
    committed: &'a State,
    lambda: f64,
    /// Flat over the points, in point order; `start[q]..start[q + 1]`.
    at: Vec<u32>,
    start: Vec<usize>,
    m: usize,
}

impl<'a> Points<'a> {
    fn new(
        model: &'a Model,
        springs: Option<&'a [f64]>,
        committed: &'a State,
        lambda: f64,
        eqs: &[usize],
    ) -> Self {
        let mut pos = vec![u32::MAX; model.dofs.n_eq];
        for (k, &e) in eqs.iter().enumerate() {
            pos[e] = k as u32;
        }
        let (mut at, mut start) = (Vec::new(), vec![0]);
        for im in &model.interfaces {
            for pt in &im.points {
                for d in im.point_dofs(pt) {
                    at.push(model.dofs.equation(d).map_or(u32::MAX, |e| pos[e]));
                }
                start.push(at.len());
            }
        }
        Points {
            model,
            springs,
            committed,
            lambda,
            at,
            start,
            m: eqs.len(),
        }
    }

    /// Σ of the points' residuals at `u` into `r` (m) and, with `k`, their
    /// tangents added into the dense column-major `k` (m × m) with `sign`.
    /// `floor`: the secant start of the step's first evaluation.
    fn eval(
        &self,
        u: &[f64],
        floor: Option<&[f64]>,
        with_coupling: bool,
        r: &mut [f64],
        mut k: Option<(&mut [f64], f64)>,
    ) {
        let (model, springs) = (self.model, self.springs);
        r.fill(0.0);
        let m = self.m;
        let (mut rl, mut kl) = (Vec::new(), Vec::new());
        let mut q = 0;
        for (i, im) in model.interfaces.iter().enumerate() {
            let gap = im.gap_at(self.lambda);
            for pt in &im.points {
                let nd = im.point_ndofs(pt);
                rl.resize(nd, 0.0);
                kl.resize(nd * nd, 0.0);
                point_parts(
                    im,
                    pt,
                    u,
                    gap,
                    &self.committed.u,
                    &self.committed.contact[q],
                    floor.map(|f| f[i]),
                    springs.map(|s| s[i]),
                    &mut rl,
                    &mut kl,
                    with_coupling,
                );
                let at = &self.at[self.start[q]..self.start[q + 1]];
                for (a, &p) in at.iter().enumerate() {
                    if p == u32::MAX {
                        continue;
                    }
                    r[p as usize] += rl[a];
                    if let Some((k, sign)) = k.as_mut() {
                        for (b, &pb) in at.iter().enumerate() {
                            if pb != u32::MAX {
                                k[pb as usize * m + p as usize] += *sign * kl[a * nd + b];
                            }
                        }
                    }
                }
                q += 1;
            }
        }
    }
}

/// `y = A x` (A dense column-major m × m).
fn mat_vec(a: &[f64], x: &[f64], y: &mut [f64]) {
    let m = x.len();
    y.fill(0.0);
    for (j, &xj) in x.iter().enumerate() {
        if xj != 0.0 {
            for (yi, aij) in y.iter_mut().zip(&a[j * m..(j + 1) * m]) {
                *yi += aij * xj;
            }
        }
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The condensed problem of one Newton iteration (module comment):
/// F(d) = A (d − Δ⁰_I) + r_s(x_k + d) − c0 on the interface equations.
struct Condensed<'a> {
    pts: &'a Points<'a>,
    /// The iterate x_k (all dofs) and the dof of each interface equation.
    u: &'a [f64],
    dof_of: &'a [usize],
    a: Vec<f64>,
    d0: Vec<f64>,
    c0: Vec<f64>,
}

impl Condensed<'_> {
    /// F(d) into `f`, with `ud` (all dofs) set to x_k + d and `diff` to
    /// d − Δ⁰_I (`work`: m scratch values).
    fn residual(
        &self,
        d: &[f64],
        ud: &mut [f64],
        diff: &mut [f64],
        f: &mut [f64],
        work: &mut [f64],
    ) {
        for (k, &dof) in self.dof_of.iter().enumerate() {
            ud[dof] = self.u[dof] + d[k];
        }
        for ((x, di), d0i) in diff.iter_mut().zip(d).zip(&self.d0) {
            *x = di - d0i;
        }
        mat_vec(&self.a, diff, f);
        self.pts.eval(ud, None, true, work, None);
        for ((fi, ri), ci) in f.iter_mut().zip(work.iter()).zip(&self.c0) {
            *fi += ri - ci;
        }
    }

    /// The loop's start on the line of the plain correction, d = s Δ⁰_I,
    /// s ∈ (0, 1]: a Galerkin line search (Matthies & Strang 1979; Crisfield,
    /// Non-linear Finite Element Analysis of Solids and Structures, vol. 1,
    /// §9.3), a root of G(s) = Δ⁰_Iᵀ F(s Δ⁰_I), the minimum along the line of
    /// the energy whose gradient F is where the law is elastic (normal
    /// springs; friction at fixed p_N). Searched only where the whole
    /// correction overshoots it, G(1) > ½ |G(0)|, G(0) < 0, to
    /// |G(s)| ≤ ½ |G(0)| by the Illinois method on [0, 1], at most
    /// [`START_EVALUATIONS`] evaluations of F (the points and one m × m
    /// product each, no factorization). Why: where the correction starts
    /// from an open interface it is carried by springs much softer than the
    /// contact law (the secant floor, the stabilization), and taken whole it
    /// closes far more than the step closes (a sphere pressed by a force in
    /// its first step: 176 of 192 points against 31, a contact radius 20
    /// times too large), from where semismooth Newton opens the zone by
    /// about a tenth of its radius per iteration; the search starts where
    /// the contact builds up along the correction instead. Also where it
    /// swings a friction interface between two slip states. `f` holds F(Δ⁰_I)
    /// on entry and F(d) on return; `d` the start.
    fn start(
        &self,
        d: &mut [f64],
        ud: &mut [f64],
        diff: &mut [f64],
        f: &mut [f64],
        work: &mut [f64],
    ) {
        let dot = |f: &[f64]| -> f64 { self.d0.iter().zip(f).map(|(a, b)| a * b).sum() };
        let g1 = dot(f);
        let mut f0 = vec![0.0; f.len()];
        let zero = vec![0.0; f.len()];
        self.residual(&zero, ud, diff, &mut f0, work);
        let g0 = dot(&f0);
        d.copy_from_slice(&self.d0);
        if !(g0 < 0.0 && g1 > 0.5 * g0.abs()) {
            self.residual(d, ud, diff, f, work);
            return;
        }
        // Illinois: regula falsi whose retained end's value is halved when
        // the same end is kept twice
        let (mut lo, mut g_lo, mut hi, mut g_hi) = (0.0, g0, 1.0, g1);
        let mut kept = 0i8;
        for _ in 0..START_EVALUATIONS {
            let mut s = hi - g_hi * (hi - lo) / (g_hi - g_lo);
            if !(s > lo && s < hi) {
                s = 0.5 * (lo + hi);
            }
            for (di, d0i) in d.iter_mut().zip(&self.d0) {
                *di = s * d0i;
            }
            self.residual(d, ud, diff, f, work);
            let g = dot(f);
            if g.abs() <= 0.5 * g0.abs() {
                return;
            }
            if g < 0.0 {
                (lo, g_lo) = (s, g);
                if kept == -1 {
                    g_hi *= 0.5;
                }
                kept = -1;
            } else {
                (hi, g_hi) = (s, g);
                if kept == 1 {
                    g_lo *= 0.5;
                }
                kept = 1;
            }
        }
    }
}

/// Refines the plain Newton correction `du` (free equations) at the
/// iterate `u` (all dofs) by the interface loop, where the backend offers
/// the condensation of its factor. `first`: the step's first evaluation
/// (its tangent holds the secant floor); `tol`: the loop's tolerance on
/// ‖F‖. Returns whether `du` changed.
pub(super) fn refine(
    engine: &mut Engine,
    committed: &State,
    u: &[f64],
    lambda: f64,
    first: bool,
    tol: f64,
    du: &mut [f64],
) -> bool {
    let Some(eqs) = engine.backend.condensed().map(|c| c.equations().to_vec()) else {
        return false;
    };
    let split = engine.backend.splits_coupling();
    let floor = first.then(|| engine.start_stiffness(lambda));
    let model = engine.model;
    let springs = engine
        .stabilizer
        .as_ref()
        .and_then(|s| s.springs.as_deref());
    let dof_of = equation_dofs(model, &eqs);
    let pts = Points::new(model, springs, committed, lambda, &eqs);
    let d0: Vec<f64> = eqs.iter().map(|&e| du[e]).collect();
    let Linearized {
        mut r0,
        k0,
        c0,
        mut ud,
        mut f,
    } = linearize(&pts, u, floor.as_deref(), &d0, &dof_of);
    // every decision below is rank 0's (the data are replicated and equal
    // on every rank; the backend's operations after it are collective)
    if engine.backend.agree(norm(&f) <= tol) {
        return false;
    }
    // A = S − K_s0 (the part of K_s0 the factored matrix holds: without the
    // coupling terms where the backend keeps them apart)
    let s = engine.backend.condensed().and_then(|c| c.schur());
    if !engine.backend.agree(s.is_some()) {
        return false;
    }
    let Some(s) = s else {
        return false;
    };
    let mut a = s.clone();
    if split {
        pts.eval(u, floor.as_deref(), false, &mut r0, Some((&mut a, -1.0)));
    } else {
        for (ai, ki) in a.iter_mut().zip(&k0) {
            *ai -= ki;
        }
    }
    drop(k0);
    let problem = Condensed {
        pts: &pts,
        u,
        dof_of: &dof_of,
        a,
        d0,
        c0,
    };
    let Inner {
        converged,
        best,
        mut diff,
        stats: st,
    } = problem.iterate(&mut ud, &mut f, tol);
    let converged = engine.backend.agree(converged);
    let has_best = engine.backend.agree(best.is_some());
    let total = &mut engine.stats.interface;
    total.loops += st.loops;
    total.iterations += st.iterations;
    if !converged {
        // the smallest ‖F‖ seen, where it is below the plain correction's
        total.fallbacks += 1;
        if !has_best {
            return false;
        }
        if let Some(b) = best {
            diff = b;
        }
    }
    // Δ = Δ⁰ + M⁻¹ [0; S (d − Δ⁰_I)]
    let mut e = vec![0.0; eqs.len()];
    mat_vec(&s, &diff, &mut e);
    engine.backend.condensed().is_some_and(|c| c.lift(&e, du))
}

/// The dof of each interface equation `eqs`.
fn equation_dofs(model: &Model, eqs: &[usize]) -> Vec<usize> {
    let mut dof_of = vec![0usize; eqs.len()];
    let mut pos = vec![u32::MAX; model.dofs.n_eq];
    for (k, &e) in eqs.iter().enumerate() {
        pos[e] = k as u32;
    }
    for d in 0..model.dofs.eq.len() {
        if let Some(e) = model.dofs.equation(d).filter(|&e| pos[e] != u32::MAX) {
            dof_of[pos[e] as usize] = d;
        }
    }
    dof_of
}

/// The springs linearized at the iterate x_k, as [`linearize`] returns them.
struct Linearized {
    /// r_s(x_k) and the points' whole tangent K_s0 (the coupling terms in).
    r0: Vec<f64>,
    k0: Vec<f64>,
    /// c0 = r_s(x_k) + K_s0 Δ⁰_I.
    c0: Vec<f64>,
    /// x_k + Δ⁰ (all dofs) and F(Δ⁰_I) = r_s(x_k + Δ⁰) − c0.
    ud: Vec<f64>,
    f: Vec<f64>,
}

/// The springs' residual and tangent at the iterate `u` and the loop's
/// residual F at the plain correction `d0` (the interface equations' part).
fn linearize(
    pts: &Points,
    u: &[f64],
    floor: Option<&[f64]>,
    d0: &[f64],
    dof_of: &[usize],
) -> Linearized {
    let m = d0.len();
    // r_s(x_k) and the points' whole tangent K_s0 (the coupling terms in)
    let (mut r0, mut k0) = (vec![0.0; m], vec![0.0; m * m]);
    pts.eval(u, floor, true, &mut r0, Some((&mut k0, 1.0)));
    // c0 = r_s(x_k) + K_s0 Δ⁰_I, and F(Δ⁰_I) = r_s(x_k + Δ⁰) − c0
    let mut c0 = vec![0.0; m];
    mat_vec(&k0, d0, &mut c0);
    for (ci, ri) in c0.iter_mut().zip(&r0) {
        *ci += ri;
    }
    let mut ud = u.to_vec();
    for (k, &dof) in dof_of.iter().enumerate() {
        ud[dof] = u[dof] + d0[k];
    }
    let mut f = vec![0.0; m];
    pts.eval(&ud, None, true, &mut f, None);
    for (fi, ci) in f.iter_mut().zip(&c0) {
        *fi -= ci;
    }
    Linearized { r0, k0, c0, ud, f }
}

/// The end of the loop's Newton iterations ([`Condensed::iterate`]).
struct Inner {
    /// ‖F‖ ≤ tol on this rank.
    converged: bool,
    /// d − Δ⁰_I of the smallest ‖F‖ seen below the plain correction's.
    best: Option<Vec<f64>>,
    /// d − Δ⁰_I of the last iterate.
    diff: Vec<f64>,
    stats: LoopStats,
}

impl Condensed<'_> {
    /// Newton's iterations on F(d) = 0 from the start [`Condensed::start`]
    /// finds, at most [`MAX_INNER`], from `ud` (x_k + Δ⁰) and `f` (F(Δ⁰_I)).
    fn iterate(&self, ud: &mut [f64], f: &mut [f64], tol: f64) -> Inner {
        let (pts, m) = (self.pts, self.d0.len());
        let mut st = LoopStats {
            loops: 1,
            ..LoopStats::default()
        };
        let (mut j, mut rs, mut step, mut diff) =
            (vec![0.0; m * m], vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        // the iterate of the smallest ‖F‖ so far (Δ⁰_I to begin with)
        let mut best = (norm(f), None::<Vec<f64>>);
        let mut d = vec![0.0; m];
        self.start(&mut d, ud, &mut diff, f, &mut rs);
        let mut f_norm = norm(f);
        let mut converged = f_norm <= tol;
        if f_norm < best.0 {
            best = (f_norm, Some(diff.clone()));
        }
        while !converged && st.iterations < MAX_INNER {
            // J = A + K_s(x_k + d); J δ = −F
            j.copy_from_slice(&self.a);
            pts.eval(ud, None, true, &mut rs, Some((&mut j, 1.0)));
            step.iter_mut().zip(f.iter()).for_each(|(s, fi)| *s = -fi);
            st.iterations += 1;
            if !dense_solve(&mut j, &mut step, 1) {
                break;
            }
            for (di, si) in d.iter_mut().zip(&step) {
                *di += si;
            }
            self.residual(&d, ud, &mut diff, f, &mut rs);
            f_norm = norm(f);
            if !f_norm.is_finite() {
                break;
            }
            converged = f_norm <= tol;
            if f_norm < best.0 {
                best = (f_norm, Some(diff.clone()));
            }
        }
        Inner {
            converged,
            best: best.1,
            diff,
            stats: st,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_dense_solve_solves_and_refuses_a_singular_matrix() {
        let m = 6;
        // unsymmetric, needs pivoting (zero first diagonal)
        let a: Vec<f64> = (0..m * m)
            .map(|k| {
                let (i, j) = (k % m, k / m);
                if i == j && i == 0 {
                    0.0
                } else {
                    1.0 / (1.0 + i as f64 + 2.0 * j as f64) + f64::from(u8::from(i == j))
                }
            })
            .collect();
        let x: Vec<f64> = (0..m).map(|i| (i as f64).sin() + 0.5).collect();
        let mut b = vec![0.0; m];
        mat_vec(&a, &x, &mut b);
        let mut j = a.clone();
        assert!(dense_solve(&mut j, &mut b, 1));
        for (p, q) in b.iter().zip(&x) {
            assert!((p - q).abs() < 1e-13, "{b:?} vs {x:?}");
        }
        let mut singular = vec![1.0; m * m];
        assert!(!dense_solve(&mut singular, &mut vec![1.0; m], 1));
    }
}
