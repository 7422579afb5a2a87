//! The step problem: the paper's residual, tangent, convergence rules and
//! status check for one load step (eq. 4.1-4.8), as the [`Problem`] that the
//! built-in Newton loop ([`Engine::step`]) or PETSc's SNES drives.

use super::Engine;
use crate::input::case::{Acceleration, Method};
use crate::linalg::failure::StepFailure;
use crate::linalg::nonlinear::{Problem, Verdict};
use crate::physics::contact::Status;
use crate::physics::element::solid::{Response, Tangent};
use crate::solve::accelerate::Anderson;
use crate::solve::State;

/// A residual this many times the reference, after the first iterations, is
/// divergence: the step is abandoned without waiting for the iteration limit.
const DIVERGENCE: f64 = 1e10;
/// Iterations before the divergence test applies.
const DIVERGENCE_AFTER: usize = 2;
/// Contraction factor under which the displacement test uses the
/// contraction's error bound ([`StepProblem::error_estimate`]).
const FAST_CONTRACTION: f64 = 0.5;
/// Sufficient decrease of the residual norm in the line search.
const ARMIJO: f64 = 1e-4;
/// Step cuts of the line search before it takes its best step.
const BACKTRACKS: usize = 4;
/// The first correction of a step (from the predictor or the committed
/// state, where Gauss points pass from elastic to plastic) is taken whole:
/// the line search applies from this correction on (0-based).
const SEARCH_FROM: usize = 1;

/// One load step as a [`Problem`]: the paper's residual, tangent, convergence
/// rules and status check, driven by the built-in loop or by SNES.
pub struct StepProblem<'a, 'm> {
    pub(super) engine: &'a mut Engine<'m>,
    committed: &'a State,
    trial: State,
    lambda: f64,
    response: Response,
    /// The step starts from the committed state and moves prescribed
    /// dofs: its first evaluation is elastic ([`StepProblem::new`]).
    lift: bool,
    method: Method,
    free: Vec<usize>,
    evaluations: usize,
    /// The interface loop fell back in this step: not tried again in it
    /// (its condensed problem is singular or far from converging here, and
    /// what it then returns hangs on round-off).
    loop_failed: bool,
    evaluate_seconds: f64,
    status: Vec<Status>,
    last_status: Option<Vec<Status>>,
    /// The statuses of this step's earlier iterates (before `last_status`),
    /// while a line search may ask for them.
    visited: Vec<Vec<Status>>,
    du_inf: f64,
    /// ‖Δu‖∞ of the correction before the last (∞ before the second).
    du_prev_inf: f64,
    r_norm: f64,
    /// ‖R‖ at the iterate the last correction started from (NaN before it).
    r_prev: f64,
    /// Whether the last correction was taken whole (no line-search cut).
    whole: bool,
    reference: f64,
    anderson: Option<Anderson>,
    /// The iterate of the last evaluation made by the line search and its
    /// residual (free equations): the solver's next evaluation there reuses it.
    searched: Option<(Vec<f64>, Vec<f64>)>,
    /// Corrections made in this step.
    corrections: usize,
    /// Set when the problem stops: the iteration count, or why it failed.
    outcome: Option<Result<usize, StepFailure>>,
}

impl<'a, 'm> StepProblem<'a, 'm> {
    /// The step from `committed` to `lambda`, its iteration started at
    /// `start` (all dofs), else at the committed displacements.
    ///
    /// **The first evaluation lifts the prescribed increments elastically**
    /// where the step starts from the committed state (no predictor: the
    /// first step, a history breakpoint, a predictor restart) and a
    /// prescribed dof moves. Its start then carries the whole increment
    /// of every prescribed dof in the element layer next to it (the
    /// neighbours still at their committed values): a strain that layer
    /// never sees, which the return mapping yields wherever the step is not
    /// small (a shaft's end turned by 0.25 mrad: 300 MPa of shear over one
    /// 1 mm element). The consistent tangent of that spuriously plastic
    /// layer hardly transmits the prescribed motion, so the first
    /// correction swings the bodies and their interface far from the
    /// solution (a pressed fit turned in one step of 0.1 failed with
    /// "contact status still changing" while 0.05 converged). The first
    /// evaluation therefore takes the elastic response from the committed
    /// plastic strain ([`Response::ElasticOnly`], exact where nothing
    /// yields), so the first correction spreads the prescribed increment as
    /// the linear tangent predictor does; every later evaluation is the
    /// step's own response and the convergence test is unchanged. Under
    /// modified Newton the solid matrix is formed again at the second
    /// evaluation (the tangent at the lifted start, not the elastic one).
    pub fn new(
        engine: &'a mut Engine<'m>,
        committed: &'a State,
        lambda: f64,
        response: Response,
        start: Option<&[f64]>,
    ) -> Self {
        let m = engine.model;
        let spec = &m.solver;
        let mut trial = committed.clone();
        if let Some(start) = start {
            trial.u.copy_from_slice(start);
        }
        trial.time = lambda;
        let mut moved = false;
        for (d, v) in m.prescribed_at(lambda) {
            moved |= v != committed.u[d];
            trial.u[d] = v;
        }
        let lift = start.is_none() && moved && response == Response::Plastic;
        engine.hold_for(lambda);
        m.fill_slaves(&mut trial.u, lambda);
        let method = if response == Response::ElasticOnly {
            Method::FullNewton
        } else {
            engine.method
        };
        let anderson = (method != Method::FullNewton
            && spec.acceleration == Acceleration::Anderson)
            .then(|| Anderson::new(spec.anderson_depth));
        let free: Vec<usize> = (0..trial.u.len())
            .filter(|&d| m.dofs.equation(d).is_some())
            .collect();
        StepProblem {
            engine,
            committed,
            trial,
            lambda,
            response,
            lift,
            method,
            free,
            evaluations: 0,
            loop_failed: false,
            evaluate_seconds: 0.0,
            status: Vec::new(),
            last_status: None,
            visited: Vec::new(),
            du_inf: f64::INFINITY,
            du_prev_inf: f64::INFINITY,
            r_norm: f64::NAN,
            r_prev: f64::NAN,
            whole: true,
            reference: 1.0,
            anderson,
            searched: None,
            corrections: 0,
            outcome: None,
        }
    }

    /// The error of the current iterate x_k that the displacement test
    /// bounds: the last correction ‖Δu_{k−1}‖∞, or the a-posteriori bound of
    /// a contraction, θ/(1−θ) ‖Δu_{k−1}‖∞ (the distance from x_k to the
    /// fixed point; Banach), where the iteration contracts fast (θ < 1/2),
    /// whichever of two measures of θ is smaller:
    /// - the ratio of the last two corrections, ‖Δu_{k−1}‖∞ / ‖Δu_{k−2}‖∞;
    /// - the ratio of the residuals at x_k and x_{k−1}, ‖R_k‖ / ‖R_{k−1}‖,
    ///   which estimates the next correction from the residual at x_k, the
    ///   rate-of-convergence estimate of the next correction that commercial
    ///   codes use (‖Δu_k‖ ≈ ‖R_k‖/‖R_{k−1}‖ ‖Δu_{k−1}‖ where the tangent
    ///   changes little). Used only where the last correction was taken
    ///   whole; the verdict asks in any case that no status changed between
    ///   x_{k−1} and x_k, so the two residuals are of the same smooth piece of
    ///   the contact law. After an active-set step (the correction ratio says
    ///   nothing there: the two corrections are of different pieces) this is
    ///   what ends the step when the new set is the right one, where the
    ///   residual falls to round-off.
    ///
    /// The last correction alone measures the error of the iterate before
    /// it, so a quadratically converging Newton iteration would take one
    /// more solve than the tolerance asks for; where θ ≥ 1/2 the last
    /// correction is the smaller bound and stays the test.
    fn error_estimate(&self) -> f64 {
        let bound = |theta: f64| {
            if theta < FAST_CONTRACTION {
                theta / (1.0 - theta) * self.du_inf
            } else {
                self.du_inf
            }
        };
        let by_corrections = bound(self.du_inf / self.du_prev_inf);
        let rho = self.r_norm / self.r_prev;
        if self.whole && rho.is_finite() {
            by_corrections.min(bound(rho))
        } else {
            by_corrections
        }
    }

    /// Full Newton with `[solver] line_search = true`: backtracking on the
    /// residual norm (issue 29, docs/performance.md
    /// "Contact status convergence"): the full correction is kept when it
    /// lowers ‖R‖ (Armijo, [`ARMIJO`]) or changes a contact status to a set
    /// no iterate of this step had (an active-set step of the nonsmooth
    /// residual, whose norm is no guide); a status change back to a set an
    /// earlier iterate had is a cycle of the active set, which taken whole
    /// repeats itself (friction near the stick-slip transition: two sets
    /// that each linearize into the other, a pressed fit's first turn
    /// swinging between them for 30 iterations), so it is searched like any
    /// other correction. Else the step is cut (the minimum of a quadratic model of ½‖R‖²,
    /// kept within [0.1, 0.5] of the last step) at most [`BACKTRACKS`]
    /// times, and the step of the smallest residual is taken. Not searched:
    /// the first correction of a step ([`SEARCH_FROM`]) and a correction
    /// from an iterate whose residual already passes the residual test.
    /// Only the path to the solution changes, not the convergence test:
    /// the displacement test still bounds the error by the whole correction.
    /// The residual is replicated on every rank, so the decisions are the
    /// same everywhere (and agreed). The evaluation at the step taken is
    /// kept for the solver's next one, which is there bit for bit (`x + du`,
    /// as both the built-in loop and SNES's post-check add it): a correction
    /// whose full step is taken costs no extra assembly.
    fn line_search(&mut self, x: &[f64], du: &mut [f64]) {
        let r0 = self.r_norm;
        let tol = self.engine.model.solver.residual_tolerance * self.reference;
        let wanted = self.method == Method::FullNewton && self.engine.model.solver.line_search;
        self.whole = true;
        if !(wanted && r0.is_finite() && r0 > tol) || self.corrections < SEARCH_FROM {
            return;
        }
        let n = x.len();
        let full = du.to_vec();
        let (mut xt, mut rt) = (vec![0.0; n], vec![0.0; n]);
        let mut alpha = 1.0;
        let mut best = (f64::INFINITY, 1.0);
        for cut in 0..=BACKTRACKS {
            for k in 0..n {
                du[k] = if alpha == 1.0 {
                    full[k]
                } else {
                    alpha * full[k]
                };
                xt[k] = x[k] + du[k];
            }
            let ok = self.evaluate(&xt, &mut rt);
            let merit = if ok { self.r_norm } else { f64::INFINITY };
            if !ok {
                self.outcome = None;
            }
            if merit < best.0 {
                best = (merit, alpha);
            }
            // a step that changes contact statuses is an active-set step of
            // a nonsmooth residual, whose norm says little: taken whole,
            // unless it returns to the set of an earlier iterate (a cycle)
            let flips = ok
                && alpha == 1.0
                && self.last_status.as_ref() != Some(&self.status)
                && !self.visited.contains(&self.status);
            let accept = self
                .engine
                .backend
                .agree(ok && (flips || merit <= (1.0 - ARMIJO * alpha) * r0));
            if accept {
                self.whole = alpha == 1.0;
                self.searched = Some((xt, rt));
                return;
            }
            if cut == BACKTRACKS {
                break;
            }
            // φ(α) = ½‖R(x + α du)‖², φ'(0) = −‖R(x)‖² for a Newton correction
            let (p0, pa) = (0.5 * r0 * r0, 0.5 * merit * merit);
            let q = if merit.is_finite() {
                r0 * r0 * alpha * alpha / (2.0 * (pa - p0 + r0 * r0 * alpha))
            } else {
                0.1 * alpha
            };
            alpha = q.clamp(0.1 * alpha, 0.5 * alpha);
        }
        // no step met the condition: the smallest residual seen
        let a = best.1;
        self.whole = a == 1.0;
        for k in 0..n {
            du[k] = if a == 1.0 { full[k] } else { a * full[k] };
        }
    }

    /// The interface loop on the plain Newton correction `du` from `x`
    /// ([`super::interface_loop`]; full Newton with `[solver] interface_loop`,
    /// where the backend offers the condensation of its factor).
    pub(super) fn interface_loop(&mut self, x: &[f64], du: &mut [f64]) {
        if self.method != Method::FullNewton
            || !self.engine.model.solver.interface_loop()
            || self.loop_failed
        {
            return;
        }
        let mut u = self.trial.u.clone();
        for (k, &d) in self.free.iter().enumerate() {
            u[d] = x[k];
        }
        let spec = &self.engine.model.solver;
        let tol = super::interface_loop::INNER_TOLERANCE * spec.residual_tolerance * self.reference;
        // the tangent holds the secant floor after the step's first evaluation only
        let first = self.evaluations == 1;
        let fallbacks = self.engine.stats.interface.fallbacks;
        super::interface_loop::refine(self.engine, self.committed, &u, self.lambda, first, tol, du);
        // the fallback is decided on rank 0's data (`agree`): the same on every rank
        self.loop_failed = self.engine.stats.interface.fallbacks > fallbacks;
    }

    /// The converged state, or why the step failed (`solved`: the solver's own
    /// failure, if any).
    pub(super) fn finish(
        self,
        solved: Result<(), StepFailure>,
    ) -> Result<(State, usize), StepFailure> {
        match self.outcome {
            Some(Ok(it)) => Ok((self.trial, it)),
            Some(Err(failure)) => Err(failure),
            None => Err(solved.err().unwrap_or_else(|| {
                StepFailure::Solver("the nonlinear solver stopped without a verdict".into())
            })),
        }
    }
}

impl Problem for StepProblem<'_, '_> {
    fn initial(&self) -> Vec<f64> {
        self.free.iter().map(|&d| self.trial.u[d]).collect()
    }

    fn evaluate(&mut self, x: &[f64], r: &mut [f64]) -> bool {
        if let Some((at, res)) = self.searched.take() {
            if at.len() == x.len() && at.iter().zip(x).all(|(a, b)| a.to_bits() == b.to_bits()) {
                r.copy_from_slice(&res);
                return true;
            }
        }
        let t0 = std::time::Instant::now();
        for (k, &d) in self.free.iter().enumerate() {
            self.trial.u[d] = x[k];
        }
        let e = &mut *self.engine;
        if !e.model.constraints.is_empty() || !e.model.sections.is_empty() {
            // a held dof keeps its committed value, the slaves follow
            for s in &e.model.sections {
                if e.is_held(s.dof) {
                    self.trial.u[s.dof] = self.committed.u[s.dof];
                }
            }
            e.model.fill_slaves(&mut self.trial.u, self.lambda);
        }
        let solid_tangent = match self.method {
            Method::FullNewton => Some(Tangent::Consistent),
            Method::ModifiedNewton if !e.solid_valid => Some(Tangent::Continuum),
            Method::InitialStiffness if !e.solid_valid => Some(Tangent::Elastic),
            _ => None,
        };
        let floor = (self.evaluations == 0).then(|| e.start_stiffness(self.lambda));
        let lifting = self.lift && self.evaluations == 0;
        let response = if lifting {
            Response::ElasticOnly
        } else {
            self.response
        };
        self.evaluations += 1;
        let assembled = e.assemble(
            self.committed,
            &mut self.trial,
            self.lambda,
            response,
            solid_tangent,
            floor,
        );
        if lifting && self.method == Method::ModifiedNewton {
            // its matrix is the tangent at the step's (lifted) start
            e.solid_valid = false;
        }
        let dt = t0.elapsed().as_secs_f64();
        e.stats.assembly_seconds += dt;
        self.evaluate_seconds += dt;
        match assembled {
            Ok(status) => self.status = status,
            Err(msg) => {
                self.outcome = Some(Err(msg));
                return false;
            }
        }
        // norms over free dofs; reactions over prescribed dofs
        let m = e.model;
        e.load_at(self.lambda);
        let (mut r2, mut f2, mut react2) = (0.0, 0.0, 0.0);
        for (d, (&r, &f)) in e.r.iter().zip(&e.load).enumerate() {
            if m.dofs.equation(d).is_some() && !e.is_held(d) {
                r2 += r * r;
                f2 += f.powi(2);
            } else {
                react2 += r * r;
            }
        }
        self.reference = f2.sqrt().max(react2.sqrt()).max(m.force_floor());
        self.r_norm = r2.sqrt();
        for (k, &d) in self.free.iter().enumerate() {
            // a held equation is an identity row: no residual, no correction
            r[k] = if e.is_held(d) { 0.0 } else { e.r[d] };
        }
        true
    }

    fn verdict(&mut self, it: usize) -> Verdict {
        let error = self.error_estimate();
        let e = &mut *self.engine;
        let m = e.model;
        let spec = &m.solver;
        let limit = spec.iteration_limit();
        // a second stop request abandons the step (collectively)
        let mut flag = [
            crate::interrupt::requested() as f64,
            f64::from(crate::interrupt::first_signal()),
        ];
        e.backend.max(&mut flag);
        if flag[0] >= 2.0 {
            self.outcome = Some(Err(StepFailure::Interrupted {
                iteration: it,
                signal: flag[1] as i32,
            }));
            return Verdict::Stop;
        }
        let (r_norm, reference) = (self.r_norm, self.reference);
        if !e.backend.agree(r_norm.is_finite()) {
            self.outcome = Some(Err(StepFailure::NotFinite { iteration: it }));
            return Verdict::Stop;
        }
        let u_inf = self
            .trial
            .u
            .iter()
            .fold(0.0f64, |a, v| a.max(v.abs()))
            .max(1e-30);
        let same_status = self.last_status.as_ref() == Some(&self.status);
        let small_r = r_norm <= spec.residual_tolerance * reference;
        let small_du = it > 0 && error <= spec.displacement_tolerance * u_inf;
        let done = small_r && (small_du || (it == 0 && r_norm == 0.0)) && (same_status || it == 0);
        if e.backend.agree(done) {
            self.trial.status = std::mem::take(&mut self.status);
            self.trial.prescribed_reaction = m
                .prescribed
                .iter()
                .filter(|(_, v)| *v != 0.0)
                .map(|&(d, _)| e.r[d])
                .sum();
            // the force across each pretension section: the condensed
            // internal force on its shortening, r + f_ext (r is the
            // reaction of a held or prescribed one)
            self.trial.section_force = m
                .sections
                .iter()
                .map(|s| e.r[s.dof] + e.load[s.dof])
                .collect();
            self.trial.reactions.clear();
            self.trial
                .reactions
                .extend(m.prescribed.iter().map(|&(d, _)| e.r[d]));
            e.share_state(&mut self.trial);
            self.outcome = Some(Ok(it));
            return Verdict::Stop;
        }
        if it >= limit {
            self.outcome = Some(Err(StepFailure::NoConvergence {
                limit,
                residual: r_norm / reference,
                correction: self.du_inf / u_inf,
                status_changing: !same_status,
            }));
            return Verdict::Stop;
        }
        if e.backend
            .agree(r_norm > DIVERGENCE * reference && it > DIVERGENCE_AFTER)
        {
            self.outcome = Some(Err(StepFailure::Diverged {
                iteration: it,
                residual: r_norm / reference,
            }));
            return Verdict::Stop;
        }
        let wanted = self.method == Method::FullNewton && m.solver.line_search;
        if let Some(last) = self.last_status.take().filter(|_| wanted) {
            if !self.visited.contains(&last) {
                self.visited.push(last);
            }
        }
        self.last_status = Some(std::mem::take(&mut self.status));
        self.r_prev = r_norm;
        Verdict::Continue
    }

    fn correct(&mut self, x: &[f64], du: &mut [f64], whole: bool) {
        self.engine.stats.factorizations += 1;
        // both paths (the built-in loop and SNES's post-check) hand the
        // plain correction here: the interface loop refines it on either
        if whole {
            self.interface_loop(x, du);
        }
        if let Some(acc) = self.anderson.as_mut() {
            let mixed = acc.step(x, du);
            du.copy_from_slice(&mixed);
        }
        // the displacement test bounds the error by the whole correction,
        // not by the part of it a line search takes
        self.du_prev_inf = self.du_inf;
        self.du_inf = du.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        self.line_search(x, du);
        self.corrections += 1;
        self.engine.stats.iterations += 1;
    }

    fn stopped(&self) -> bool {
        self.outcome.is_some()
    }

    fn converged(&self) -> bool {
        matches!(self.outcome, Some(Ok(_)))
    }

    fn evaluate_seconds(&self) -> f64 {
        self.evaluate_seconds
    }
}
