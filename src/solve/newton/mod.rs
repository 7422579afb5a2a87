//! One load step: the Newton iteration with the contact status check (paper
//! section 4, eq. 4.1-4.8), for the three methods.
//!
//! ```text
//!   R(u) = f_int(u) + f_c(u; g(t)) − f(t)      (4.1; f(t) = λ f_ext without histories)
//!   K Δu = −R,  u ← u + Δu                        (4.4, 4.7)
//!   K = K_AB^{E-P}(u) + K_c(u)        full Newton (4.6)
//!     = K_AB^{ep}(start of step) + K_c(u)  modified Newton
//!     = K_AB^{E} + K_c(u)              initial stiffness (4.8)
//! ```
//! The contact matrix is rebuilt every iteration in all three methods, as the
//! paper does. A step converges when the residual and the displacement correction
//! are small and no interface point changed status in the last iteration.

mod elements;
pub mod interface_loop;
mod step;
pub use step::StepProblem;

use super::stabilization::mechanism::Stabilizer;
use super::State;
use crate::input::case::Method;
use crate::linalg::backend::Backend;
use crate::linalg::failure::StepFailure;
use crate::linalg::nonlinear::{NonlinearSolver, Problem, Verdict};
use crate::model::Model;
use crate::physics::contact::Status;
use crate::physics::element::solid::{Response, Tangent};
use crate::physics::material::{GaussStates, PointState};

/// Points per reduction in `Engine::share_state` and `Engine::gather_gauss`.
const SHARE_CHUNK: usize = 8192;

/// Counters over a whole run.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    /// Newton corrections of every solve, the event searches' included.
    pub iterations: usize,
    /// The event searches' share of `iterations` ([`crate::solve::events`]):
    /// reported apart, so that the run's count is its own path's.
    pub event_iterations: usize,
    pub factorizations: usize,
    /// Steps whose predicted start failed and that were solved again from
    /// the committed state (see [`super::predict`]).
    pub(crate) predictor_restarts: usize,
    pub assembly_seconds: f64,
    pub solve_seconds: f64,
    /// The interface loop's counters ([`interface_loop`]).
    pub interface: interface_loop::LoopStats,
    /// Peak memory of this process when each stage was reached, MB: "model",
    /// "setup" (backend and solver objects), "first_assembly",
    /// "first_increment" (solved and written); summed over ranks in the result.
    pub(crate) memory_mb: Vec<(&'static str, f64)>,
}

pub struct Engine<'m> {
    /// A solver that replaces the built-in iteration loop (PETSc SNES); dropped
    /// before the backend whose matrix it holds.
    pub nonlinear: Option<Box<dyn NonlinearSolver + 'm>>,
    pub model: &'m Model,
    pub method: Method,
    pub backend: Box<dyn Backend + 'm>,
    /// The cached solid matrix belongs to this committed state (modified Newton)
    /// or to the whole run (initial stiffness).
    solid_valid: bool,
    r: Vec<f64>,
    /// The external force at pseudo-time `load_time` (all dofs).
    load: Vec<f64>,
    load_time: f64,
    pub stats: Stats,
    /// Test hook: (rank, assembly number) at which the element loop fails.
    pub fault: Option<(usize, usize)>,
    assemblies: usize,
    /// The elements whose Gauss states this process holds, ascending: all of
    /// them on one process, the owned ones under MPI. A state's `gauss` holds
    /// these elements' points in this order ([`Engine::localize`]).
    held_elements: Vec<u32>,
    /// Where held element k's Gauss states start in this process's state
    /// vector (and, last, their count; [`Model::held_points`]).
    held_offsets: Vec<usize>,
    /// Contact stabilization of floating bodies ([`super::stabilize`]).
    pub(crate) stabilizer: Option<Stabilizer>,
    /// Threads of the element loop ([`Engine::set_threads`]).
    threads: usize,
    /// One batch's element forces and tangents ([`ELEMENT_BATCH`](elements::ELEMENT_BATCH)), element
    /// after element, ne and ne² numbers each (ne = the model's
    /// [`NodeDofs::element`](crate::input::mesh::NodeDofs::element): a model without twist holds no room for it).
    fe_batch: Vec<f64>,
    ke_batch: Vec<f64>,
    /// The dofs held in the current step ([`Model::held_dofs`]); a cached
    /// solid matrix is of one set of them.
    held: Vec<usize>,
}

impl Stats {
    /// The Newton iterations of the run's own steps: every solve of its
    /// increments (failed attempts, the first-yield search and the contact
    /// stabilization's solves included), not the event searches'.
    pub fn run_iterations(&self) -> usize {
        self.iterations - self.event_iterations
    }
}

impl<'m> Engine<'m> {
    /// An engine on a backend (the caller's factory: [`crate::app::driver::serial_engine`]
    /// for the serial one, `parallel::run` for PETSc).
    pub fn with_backend(
        model: &'m Model,
        method: Method,
        mut backend: Box<dyn Backend + 'm>,
    ) -> Self {
        backend.reuse_solid(method != Method::FullNewton);
        let held_elements: Vec<u32> = (0..model.mesh.elements.len())
            .filter(|&e| backend.owns_element(e))
            .map(|e| e as u32)
            .collect();
        let held_offsets = std::iter::once(0)
            .chain(model.held_points(&held_elements).map(|(_, r)| r.end))
            .collect();
        Engine {
            nonlinear: None,
            model,
            method,
            backend,
            solid_valid: false,
            r: vec![0.0; model.num_dofs()],
            load: vec![0.0; model.num_dofs()],
            load_time: f64::NAN,
            stats: Stats::default(),
            fault: None,
            assemblies: 0,
            held_elements,
            held_offsets,
            stabilizer: Some(Stabilizer::new(model)),
            threads: 1,
            fe_batch: Vec::new(),
            ke_batch: Vec::new(),
            held: Vec::new(),
        }
    }

    /// Runs the element loop on `threads` threads (at least 1; 1 when
    /// made). The result does not depend on it: see [`Engine::assemble_solids`].
    pub(crate) fn set_threads(&mut self, threads: usize) {
        self.threads = threads.max(1);
    }

    /// Threads of the element loop.
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// The elements whose Gauss states this process holds, ascending.
    /// The designer's record of a converged state
    /// ([`crate::measure::record`]; collective under MPI).
    pub fn record(&self, state: &State) -> Vec<f64> {
        crate::measure::record(self.model, &*self.backend, &self.held_elements, state)
    }

    /// The largest von Mises stress of a converged state away from the
    /// model's excluded points ([`crate::measure::singular::von_mises_away`];
    /// collective under MPI where the model measures it, NaN elsewhere).
    pub fn von_mises_away(&self, state: &State) -> f64 {
        self.model.excluded.as_ref().map_or(f64::NAN, |x| {
            crate::measure::singular::von_mises_away(
                self.model,
                &*self.backend,
                &self.held_elements,
                &state.gauss,
                x,
            )
        })
    }

    pub(crate) fn held_elements(&self) -> &[u32] {
        &self.held_elements
    }

    /// Whether this process holds every element's Gauss states.
    fn holds_all(&self) -> bool {
        self.held_elements.len() == self.model.mesh.elements.len()
    }

    /// Drops from a whole state (every element's Gauss points, as built by
    /// [`State::initial`] or read from a restart file) the Gauss states of
    /// the elements this process does not hold; unchanged on one process.
    pub(crate) fn localize(&self, state: &mut State) {
        let m = self.model;
        if self.holds_all() || state.gauss.len() != m.n_points() {
            return;
        }
        let mut local = GaussStates::with_capacity(0, state.gauss.twist());
        for &e in &self.held_elements {
            local.extend_from(state.gauss.range(m.points(e as usize)));
        }
        state.gauss = local;
    }

    /// Every element's Gauss states, in element order, on rank 0 (collective;
    /// `None` on the other ranks and on one process, which holds them all
    /// already). Gathered in chunks, so the only transient beyond the result
    /// is one chunk.
    pub(crate) fn gather_gauss(&self, state: &State) -> Option<GaussStates> {
        // decided on the rank count, the same everywhere (a rank may hold
        // every element while another holds none)
        if self.backend.ranks() == 1 {
            return None;
        }
        let m = self.model;
        let ne = m.mesh.elements.len();
        let root = self.backend.rank() == 0;
        let twist = m.node_dofs().six_components();
        let mut full = GaussStates::with_capacity(if root { m.n_points() } else { 0 }, twist);
        let w = PointState::packed_len(twist);
        let per = (SHARE_CHUNK / crate::physics::element::family::MAX_POINTS).max(1);
        let mut g = Vec::new();
        let mut held = m.held_points(&self.held_elements).peekable();
        let mut e0 = 0;
        while e0 < ne {
            let e1 = (e0 + per).min(ne);
            let p0 = m.points(e0).start;
            g.clear();
            g.resize((m.points(e1 - 1).end - p0) * w, 0.0);
            while let Some((e, local)) = held.next_if(|(e, _)| *e < e1) {
                let at = (m.points(e).start - p0) * w;
                for (ip, s) in state.gauss.range(local).iter().enumerate() {
                    g[at + ip * w..][..w].copy_from_slice(&s.pack()[..w]);
                }
            }
            self.backend.sum(&mut g);
            if root {
                for v in g.chunks_exact(w) {
                    full.push(&PointState::unpack(v, w));
                }
            }
            e0 = e1;
        }
        root.then_some(full)
    }

    /// Max yield ratio over every Gauss point of the model (all ranks) and the
    /// (element, point) where it occurs: the lowest such index among the
    /// points tied with it (`super::yield_point::RATIO_TIE`), as one
    /// process finds it.
    pub fn max_yield_ratio(&self, state: &State) -> (f64, usize, usize) {
        use super::yield_point::{lowest_tied, max_yield_ratio};
        let local = max_yield_ratio(self.model, state, &self.held_elements);
        if self.backend.ranks() == 1 {
            return local;
        }
        let m = self.model;
        let mut best = [local.0];
        self.backend.max(&mut best);
        let tied = lowest_tied(self.model, state, &self.held_elements, best[0]);
        let mut key = [match tied {
            Some((e, ip)) => -((m.points(e).start + ip) as f64),
            None => f64::NEG_INFINITY,
        }];
        self.backend.max(&mut key);
        if key[0] == f64::NEG_INFINITY {
            return (best[0], 0, 0);
        }
        let i = (-key[0]) as usize;
        let e = m.element_of_point(i);
        (best[0], e, i - m.points(e).start)
    }

    /// Largest of `values` (one per held Gauss point) over every rank, 0 when
    /// none is positive.
    pub(crate) fn max_over_points(&self, values: impl Iterator<Item = f64>) -> f64 {
        let mut m = [values.fold(0.0f64, f64::max)];
        self.backend.max(&mut m);
        m[0]
    }

    /// The external force at pseudo-time t (all dofs), computed once per t.
    pub(crate) fn load_at(&mut self, t: f64) -> &[f64] {
        if self.load_time.to_bits() != t.to_bits() {
            self.model.external_force(t, &mut self.load);
            self.load_time = t;
        }
        &self.load
    }

    /// `Measures::of` with the largest plastic strain taken over all ranks.
    pub fn measures(&self, state: &State) -> super::Measures {
        let mut m = super::Measures::of(self.model, state);
        m.max_peeq = self.max_over_points(state.gauss.iter().map(|g| g.peeq));
        m
    }

    /// The dofs held in a step to pseudo-time t ([`Model::held_dofs`]); a
    /// change (a section locked) makes a cached solid matrix stale.
    pub(crate) fn hold_for(&mut self, t: f64) {
        let held = self.model.held_dofs(t);
        if held != self.held {
            self.held = held;
            self.solid_valid = false;
        }
    }

    /// Whether dof d is held in the current step.
    pub(crate) fn is_held(&self, d: usize) -> bool {
        self.held.contains(&d)
    }

    /// Called when a new state is committed: the modified-Newton matrix is stale.
    /// Returns whether the step was a plain one: a step that the contact
    /// stabilization held or released moved a body rigidly (a gap closing),
    /// which the next step's predictor must not extrapolate.
    pub fn committed(&mut self) -> bool {
        if self.method == Method::ModifiedNewton {
            self.solid_valid = false;
        }
        self.stabilizer.as_mut().is_none_or(|st| st.commit())
    }

    /// The step without the stabilization's choice (it may still hold springs
    /// or a start guess set by [`super::stabilize`], which overrides `start`).
    pub(super) fn plain_step(
        &mut self,
        committed: &State,
        lambda: f64,
        response: Response,
        start: Option<&[f64]>,
    ) -> Result<(State, usize), StepFailure> {
        let guess = self.stabilizer.as_mut().and_then(|s| s.guess.take());
        let start = guess.as_deref().or(start);
        if let Some(mut solver) = self.nonlinear.take() {
            let t0 = std::time::Instant::now();
            let mut p = StepProblem::new(self, committed, lambda, response, start);
            let solved = solver.solve(&mut p);
            let inside = p.evaluate_seconds();
            let result = p.finish(solved);
            self.stats.solve_seconds += (t0.elapsed().as_secs_f64() - inside).max(0.0);
            self.nonlinear = Some(solver);
            return result;
        }
        let mut p = StepProblem::new(self, committed, lambda, response, start);
        let mut x = p.initial();
        let n = x.len();
        let (mut r, mut du) = (vec![0.0; n], vec![0.0; n]);
        let mut it = 0;
        let solved = loop {
            if !p.evaluate(&x, &mut r) || p.verdict(it) == Verdict::Stop {
                break Ok(());
            }
            // linear solve on the free dofs
            // K du = −r, solved as K y = r, du = −y: the operations SNES does,
            // so both paths take bit-identical iterates (a distributed MUMPS
            // solve of −r is not bitwise the negated solve of r)
            let t1 = std::time::Instant::now();
            if let Err(e) = p.engine.backend.solve(&r, &mut du) {
                break Err(StepFailure::Linear(e));
            }
            for v in du.iter_mut() {
                *v = -*v;
            }
            p.engine.stats.solve_seconds += t1.elapsed().as_secs_f64();
            p.correct(&x, &mut du, true);
            for (xk, dk) in x.iter_mut().zip(&du) {
                *xk += dk;
            }
            it += 1;
        };
        p.finish(solved)
    }

    /// Residual (all dofs) and consistent tangent at displacement `u` from
    /// `committed`; the tangent goes into the backend (serial: its `vals`).
    /// Used by the finite-difference checks of the assembled tangent.
    pub fn linearize(
        &mut self,
        committed: &State,
        u: &[f64],
        lambda: f64,
    ) -> Result<Vec<f64>, StepFailure> {
        let mut trial = committed.clone();
        trial.u.copy_from_slice(u);
        trial.time = lambda;
        self.assemble(
            committed,
            &mut trial,
            lambda,
            Response::Plastic,
            Some(Tangent::Consistent),
            None,
        )?;
        Ok(self.r.clone())
    }

    /// Completes the trial interface states on every rank: each rank updated
    /// only the points it owns. Summed in chunks of [`SHARE_CHUNK`] points.
    /// (Gauss states stay with the rank that owns the element.)
    fn share_state(&self, trial: &mut State) {
        if self.backend.ranks() == 1 {
            return;
        }
        use crate::physics::contact::PointState;
        let twist = self.model.node_dofs().vector_slip();
        let w = PointState::packed_len(twist);
        let mut g = Vec::with_capacity(SHARE_CHUNK * w);
        let mut start = 0;
        while start < trial.contact.len() {
            let end = (start + SHARE_CHUNK).min(trial.contact.len());
            g.clear();
            g.resize((end - start) * w, 0.0);
            for (k, s) in trial.contact[start..end].iter().enumerate() {
                if self.backend.owns_point(start + k) {
                    g[w * k..w * (k + 1)].copy_from_slice(&s.pack_as(twist));
                }
            }
            self.backend.sum(&mut g);
            for (k, s) in trial.contact[start..end].iter_mut().enumerate() {
                *s = PointState::unpack_as(&g[w * k..w * (k + 1)], twist);
            }
            start = end;
        }
    }

    /// Secant start stiffness (eq. 2.8-2.9) for pairs at zero approach, at
    /// the reference pressure of a step to pseudo-time `lambda`
    /// ([`Model::reference_pressure`]).
    pub(super) fn start_stiffness(&self, lambda: f64) -> Vec<f64> {
        let m = self.model;
        (0..m.interfaces.len())
            .map(|i| {
                m.interfaces[i]
                    .law
                    .secant_stiffness(m.reference_pressure(i, lambda))
            })
            .collect()
    }

    /// Residual (into self.r, all dofs, summed over ranks) and the requested
    /// matrix (into the backend). Returns the interface statuses at `trial.u`.
    fn assemble(
        &mut self,
        committed: &State,
        trial: &mut State,
        lambda: f64,
        response: Response,
        solid_tangent: Option<Tangent>,
        floor: Option<Vec<f64>>,
    ) -> Result<Vec<Status>, StepFailure> {
        let root = self.backend.rank() == 0;
        self.load_at(lambda);
        for (r, f) in self.r.iter_mut().zip(&self.load) {
            *r = if root { -f } else { 0.0 };
        }
        // backends keep the solid matrix apart only for the fixed-matrix methods
        // (Backend::reuse_solid): full Newton reassembles it every time
        debug_assert!(solid_tangent.is_some() || self.method != Method::FullNewton);
        let failure = self.assemble_solids(committed, trial, lambda, response, solid_tangent)?;
        self.assemblies += 1;
        // a local failure (return mapping) fails the step on every rank, with its message
        if let Some(msg) = self.backend.share_message(failure) {
            return Err(StepFailure::Element(msg));
        }
        if let Some(t) = solid_tangent {
            // a consistent matrix is never reused; the others are cached
            self.solid_valid = t != Tangent::Consistent;
        }
        let mut codes = self.assemble_interfaces(committed, trial, floor.as_deref())?;
        let be = &mut self.backend;
        be.sum(&mut self.r);
        // r ← Tᵀ r: the slaves' forces onto their masters
        self.model.constraints.condense(&mut self.r);
        if self.assemblies == 1 {
            self.stats
                .memory_mb
                .push(("first_assembly", super::peak_memory_mb()));
        }
        be.sum(&mut codes);
        Ok(codes.iter().map(|&c| Status::from_code(c as u8)).collect())
    }

    /// The spring loop over the interface points this rank owns: contact
    /// forces into `self.r`, tangential states into `trial`, point tangents
    /// (with the stabilization's springs when it has them) into the backend.
    /// `floor`: the secant start stiffness per interface (first iteration).
    /// Returns the status code of every point (0 where another rank owns it).
    fn assemble_interfaces(
        &mut self,
        committed: &State,
        trial: &mut State,
        floor: Option<&[f64]>,
    ) -> Result<Vec<f64>, StepFailure> {
        let m = self.model;
        let be = &mut self.backend;
        let err = StepFailure::Linear;
        be.begin_contact().map_err(err)?;
        let mut codes = vec![0.0; committed.status.len()];
        // local buffers for the largest point (12 dofs but on mortar interfaces)
        let nd_max = m
            .interfaces
            .iter()
            .flat_map(|im| im.points.iter().map(|p| im.point_ndofs(p)))
            .max()
            .unwrap_or(0)
            .max(12);
        let (mut rl, mut kl) = (vec![0.0; nd_max], vec![0.0; nd_max * nd_max]);
        let springs = self.stabilizer.as_ref().and_then(|s| s.springs.as_deref());
        let split = be.splits_coupling();
        let mut q = 0;
        for (i, im) in m.interfaces.iter().enumerate() {
            let kf = floor.map(|f| f[i]);
            let gap = im.gap_at(trial.time);
            for (j, pt) in im.points.iter().enumerate() {
                if !be.owns_point(q) {
                    q += 1;
                    continue;
                }
                let nd = im.point_ndofs(pt);
                let ev = interface_loop::point_parts(
                    im,
                    pt,
                    &trial.u,
                    gap,
                    &committed.u,
                    &committed.contact[q],
                    kf,
                    springs.map(|ks| ks[i]),
                    &mut rl[..nd],
                    &mut kl[..nd * nd],
                    !split,
                );
                codes[q] = ev.status as u8 as f64;
                trial.contact[q] = ev.state;
                let pdofs = im.point_dofs(pt);
                for (k, &d) in pdofs.iter().enumerate() {
                    self.r[d] += rl[k];
                }
                let block = m.interface_block(i, j);
                let x = m.expansion(block);
                match x {
                    None => be.add_contact(block, &pdofs, &kl[..nd * nd]),
                    Some(x) => {
                        be.add_contact(block, &x.dofs, &held_out(x, &self.held, &kl[..nd * nd]))
                    }
                }
                .map_err(err)?;
                if split && (ev.coupling != 0.0 || ev.coupling_hoop != 0.0) {
                    let g = im.point_gradients(pt);
                    let at = PointBlock {
                        block,
                        dofs: &pdofs,
                        expansion: x,
                    };
                    add_coupling(be.as_mut(), &self.held, &at, g, &ev).map_err(err)?;
                }
                q += 1;
            }
        }
        add_held_sections(m, be.as_mut(), &self.held).map_err(err)?;
        Ok(codes)
    }
}

/// A held dof's equation: its row and column are zero ([`held_out`]), its
/// diagonal a stiffness of the model's scale, added once (rank 0), for each
/// pretension section whose dof is `held`.
fn add_held_sections(m: &Model, be: &mut dyn Backend, held: &[usize]) -> crate::error::Result<()> {
    if be.rank() == 0 {
        for (k, s) in m.sections.iter().enumerate() {
            if held.contains(&s.dof) {
                let kh = m.held_stiffness();
                be.add_contact(
                    m.section_block(k),
                    &[s.dof, s.dof + 1],
                    &[kh, 0.0, 0.0, 0.0],
                )?;
            }
        }
    }
    Ok(())
}

/// An interface point's block in the backend: its number, the point's dofs
/// and, where it holds a slave dof, its expansion onto the masters.
struct PointBlock<'a> {
    block: usize,
    dofs: &'a [usize],
    expansion: Option<&'a crate::model::constraint::Expansion>,
}

/// Adds a point's unsymmetric tangent term u vᵀ, u = coupling g_T1
/// (+ coupling_hoop g_θ with twist), v = g_N, to its block (the backend keeps
/// it apart from the factored matrix); the entries of `held` dofs zero.
fn add_coupling(
    be: &mut dyn Backend,
    held: &[usize],
    at: &PointBlock,
    g: crate::model::interface::Gradients,
    ev: &crate::model::interface::PointEval,
) -> crate::error::Result<()> {
    // u = coupling g_T1 (+ coupling_hoop g_θ with twist), v = g_N
    let (coef, g_u) = if g.h.is_empty() {
        (ev.coupling, g.t)
    } else {
        let u = g.t.iter().zip(&g.h);
        let u = u.map(|(t, h)| ev.coupling * t + ev.coupling_hoop * h);
        (1.0, u.collect())
    };
    let g_n = g.n;
    match at.expansion {
        None => be.add_coupling(at.block, at.dofs, coef, &g_u, &g_n),
        Some(x) => {
            let (mut gt, mut gn) = (x.vector(&g_u), x.vector(&g_n));
            for (k, d) in x.dofs.iter().enumerate() {
                if held.contains(d) {
                    gt[k] = 0.0;
                    gn[k] = 0.0;
                }
            }
            be.add_coupling(at.block, &x.dofs, coef, &gt, &gn)
        }
    }
}

/// The block Tᵀ k T of a block that holds a slave dof ([`crate::model::constraint`]),
/// with the rows and columns of the held dofs zero.
fn held_out(x: &crate::model::constraint::Expansion, held: &[usize], k: &[f64]) -> Vec<f64> {
    let mut kx = x.matrix(k);
    let m = x.dofs.len();
    for (i, d) in x.dofs.iter().enumerate() {
        if held.contains(d) {
            for j in 0..m {
                kx[i * m + j] = 0.0;
                kx[j * m + i] = 0.0;
            }
        }
    }
    kx
}
