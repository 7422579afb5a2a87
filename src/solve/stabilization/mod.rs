//! Force control across gaps and floating bodies: contact stabilization that is
//! released before a step is accepted.
//!
//! Under a pressure load, a body held only through the interface (the punch:
//! its supports fix x, nothing fixes y) has no stiffness in its free rigid
//! motion while every pair it touches is open, an initial gap g₀ > 0; at zero
//! load its position is not fixed by equilibrium at all (unloading to λ = 0).
//! Newton's matrix is then singular. The remedy is the contact stabilization
//! of Abaqus (Abaqus Analysis User's Guide, "Automatic stabilization of rigid
//! body motions in contact problems", *CONTACT CONTROLS, STABILIZE): a damping
//! layer across the interface. With the pseudo-time of a static step that
//! damper is a spring to the last converged position: at every interface point
//!
//! ```text
//!   f_s = k_s A (Δd_N n + Δd_T t),   Δd = (u_B − u_A) − (u_B − u_A)_committed
//!   K_s = k_s A (g_N g_Nᵀ + g_T g_Tᵀ)   (g: derivatives of d_N, d_T, as for the law)
//! ```
//!
//! integrated with the interface's own quadrature. With twist the springs act
//! around the axis too, k_s A Δu_Tθ g_θ (u_Tθ = u_θB − u_θA): a body that only
//! the friction of an interface holds about the axis (no rotation of its
//! own) has no stiffness in that rotation either while its pairs are open. Abaqus ramps that damping
//! to zero by the end of its step; here it is removed outright, so that the
//! accepted answer never depends on it:
//!
//! 1. *stabilized solve* with k_s = k₀, k₀ = p_ref / (g_open + u(p_ref)) (the
//!    secant that closes the largest opening g_open and compresses the
//!    asperities to the step's mean pressure p_ref, as in the secant start of
//!    eq. 2.8-2.9); then k₀/10², k₀/10⁴, k₀/10⁶, each from the previous solution;
//! 2. *release*: as soon as a stabilized solution holds every body through
//!    closed pairs and boundary conditions, the same step is solved again
//!    without the springs, from that solution. If it converges, that is the
//!    step's answer, to the Newton tolerance the answer of any other path to
//!    the same equilibrium (displacement control included).
//! 3. When no release is possible — no body held only through interfaces
//!    carries a load at this load factor (the force of a pretension section
//!    counts as a load of the body it cuts), so nothing presses the floating
//!    body into place and its position is indeterminate — the last
//!    stabilized solution is accepted if the energy the springs dissipated
//!    over the run, W_s = Σ k_s A |Δd|² per accepted step (the work of a
//!    damper moving at constant rate over the step), stays below
//!    `stabilization_energy` times the largest internal energy of the run;
//!    otherwise the step fails with the body named. A step in which such a
//!    body carries a load is accepted released only: when no release
//!    converges it fails (and is cut back), since the springs would carry
//!    part of that load and the answer would depend on them.
//!
//! A pretension section that cuts its body in two leaves it one rigid motion
//! more while the section is force-controlled and not yet locked: its
//! shortening moves the side beyond the cut along the normal, so the body is
//! held only when both sides are (a bolt with a gap under its head floats on
//! its nut until the head touches down; [`mechanism`]).
//!
//! Which steps use it: those whose committed state leaves a body held only
//! through open pairs (approach below −1e-12 mm, where the secant start does
//! not reach) or pairs touching without pressure (`SUPPORT` in [`mechanism`]). Every other step is the plain step, exactly as without this
//! module; only if it fails when it takes a body held only through an
//! interface to zero load is it retried stabilized. A loaded body is accepted
//! released only; the stabilized answer itself only at zero load (3. above). All
//! decisions are taken from replicated data and confirmed through
//! `Backend::agree`; the springs are assembled with the interface points each
//! rank owns.

pub mod mechanism;

use crate::physics::element::solid::Response;
use crate::solve::newton::Engine;
use crate::solve::{State, StepFailure};
use mechanism::increment;
pub(crate) use mechanism::Report;

/// Stabilized solves before giving up: k₀, k₀/10², k₀/10⁴, k₀/10⁶ (each
/// followed by at most one release; a restart file's counters are bounded
/// by it, [`crate::files::restart`]).
pub const LEVELS: i32 = 4;

/// Work of the springs `ks` over the step from `committed` to `u`, N·mm:
/// Σ k_s A |Δd|² over the points this rank owns, summed over ranks.
fn spring_work(engine: &Engine, ks: &[f64], committed: &[f64], u: &[f64]) -> f64 {
    let m = engine.model;
    let mut w = 0.0;
    let mut q = 0;
    for (i, im) in m.interfaces.iter().enumerate() {
        for pt in &im.points {
            if engine.backend.owns_point(q) {
                let [dn, dt, dh] = increment(im, pt, committed, u);
                w += ks[i] * pt.area * (dn * dn + dt * dt + dh * dh);
            }
            q += 1;
        }
    }
    let mut v = [w];
    engine.backend.sum(&mut v);
    v[0]
}

/// Internal energy of a state, N·mm: elastic strain energy ½ σ:C⁻¹:σ and
/// plastic work σ_Y ε̄ᵖ + ½ H (ε̄ᵖ)² (linear isotropic hardening, associated
/// von Mises flow: the dissipation rate is σ_y dε̄ᵖ) over the Gauss points
/// this rank holds, plus the energy stored in the normal springs of the
/// interface, ∫ φ(u_N) dA with φ' = p_N; summed over ranks.
fn internal_energy(engine: &Engine, state: &State) -> f64 {
    let m = engine.model;
    let mut w = 0.0;
    for (e, local) in m.held_points(engine.held_elements()) {
        let mats = m.element_materials(e, state.time);
        let geo = m.element_geometry(e);
        let dv = geo.dv();
        for (ip, g) in state.gauss.range(local).iter().enumerate() {
            let mat = mats.at(ip);
            let s = g.stress;
            let nu = mat.poisson;
            let elastic = (s[0] * s[0] + s[1] * s[1] + s[3] * s[3]
                - 2.0 * nu * (s[0] * s[1] + s[1] * s[3] + s[3] * s[0])
                + 2.0 * (1.0 + nu) * s[2] * s[2]
                + 2.0 * (1.0 + nu) * (s[4] * s[4] + s[5] * s[5]))
                / (2.0 * mat.young);
            let plastic = if mat.yield_stress.is_finite() {
                mat.yield_stress * g.peeq + 0.5 * mat.hardening * g.peeq * g.peeq
            } else {
                0.0
            };
            w += (elastic + plastic) * dv[ip];
        }
    }
    let mut q = 0;
    for im in &m.interfaces {
        let gap = im.gap_at(state.time);
        for pt in &im.points {
            if engine.backend.owns_point(q) {
                w += pt.area * im.law.energy(im.point_kinematics_at(pt, &state.u, gap).0);
            }
            q += 1;
        }
    }
    let mut v = [w];
    engine.backend.sum(&mut v);
    v[0]
}

/// The account of a run for summary.json, with the internal energy of the
/// final state taken into the reference (collective); `None` when no step
/// used the stabilization.
pub(crate) fn final_report(engine: &Engine, last: &State) -> Option<Report> {
    let st = engine.stabilizer.as_ref().filter(|s| s.used > 0)?;
    let mut report = st.report.clone();
    report.internal = report.internal.max(internal_energy(engine, last));
    Some(report)
}

/// The base spring stiffness of every interface for a step from `committed`
/// to `lambda` (MPa/mm): k₀ = p_ref / (g_open + u(p_ref)).
fn base_springs(engine: &Engine, committed: &State, lambda: f64) -> Vec<f64> {
    let m = engine.model;
    m.interfaces
        .iter()
        .enumerate()
        .map(|(i, im)| {
            // the secant start's reference pressure (eq. 2.8-2.9, `Engine`)
            let p_ref = m.reference_pressure(i, lambda);
            let gap = im.gap_at(lambda);
            let open = im
                .pairs
                .iter()
                .map(|p| -im.pair_approach_at(p, &committed.u, gap))
                .fold(0.0f64, f64::max);
            p_ref / (open + im.law.approach(p_ref))
        })
        .collect()
}

/// The steps of an engine, defined here, above the Newton iteration: the
/// engine itself knows only its plain step (`Engine::plain_step`).
impl Engine<'_> {
    /// Solves the step from `committed` to load factor `lambda`. Returns the
    /// converged trial state and the number of iterations, or a reason. Every
    /// branch is taken on all ranks alike. The iterations are the built-in loop
    /// below, or the engine's `NonlinearSolver` (PETSc SNES) when it has one;
    /// both call the same `StepProblem`.
    ///
    /// A step that would leave a body floating goes through the contact
    /// stabilization (this module); every other step is the plain one.
    pub fn step(
        &mut self,
        committed: &State,
        lambda: f64,
        response: Response,
    ) -> Result<(State, usize), StepFailure> {
        self.step_from(committed, lambda, response, None)
    }

    /// [`Engine::step`] with the iteration started at `start` (all dofs; its
    /// free dofs are used, the prescribed ones take their values at `lambda`)
    /// instead of at the committed displacements: the predictor of
    /// [`super::predict`]. A step that this module takes over starts
    /// from its own states instead.
    pub fn step_from(
        &mut self,
        committed: &State,
        lambda: f64,
        response: Response,
        start: Option<&[f64]>,
    ) -> Result<(State, usize), StepFailure> {
        step(self, committed, lambda, response, start)
    }
}

/// [`Engine::step`]: the plain step, or the stabilized one when the committed
/// state leaves a body floating (or follows an accepted stabilized state);
/// a plain step to zero load on an interface-held body that fails is retried
/// stabilized. With `stabilization = "off"` a failure names the floating body.
fn step(
    engine: &mut Engine,
    committed: &State,
    lambda: f64,
    response: Response,
    start: Option<&[f64]>,
) -> Result<(State, usize), StepFailure> {
    let Some(st) = engine.stabilizer.as_mut() else {
        return engine.plain_step(committed, lambda, response, start);
    };
    // the account follows the steps that may be committed (the run's own);
    // the elastic sub-steps that locate first yield leave it alone
    let main = response == Response::Plastic;
    if main {
        st.pending = None;
    }
    let needed = st.enabled && !st.floating(engine.model, &committed.u, lambda).is_empty();
    if engine.backend.agree(needed) {
        return stabilized_step(engine, committed, lambda, response, main, None);
    }
    let plain = engine.plain_step(committed, lambda, response, start);
    let Err(e) = plain else { return plain };
    if e.signal().is_some() || e.is_fatal() {
        return Err(e);
    }
    let st = engine.stabilizer.as_ref().expect("checked above");
    // only at zero load: any other failure is cut back exactly as before
    let retry = st.enabled && st.unloaded(engine.model, lambda).is_some();
    if engine.backend.agree(retry) {
        return stabilized_step(
            engine,
            committed,
            lambda,
            response,
            main,
            Some(e.to_string()),
        );
    }
    match st.explain(engine.model, committed, lambda) {
        Some(why) => Err(StepFailure::Unheld(format!("{why} ({e})"))),
        None => Err(e),
    }
}

/// A step solved with the contact stabilization's springs on the bodies not
/// held: the springs softened level by level until the answer can be
/// released (solved again without them) or, at zero load, kept if the
/// springs' work stays within `stabilization_energy`. `prior`: why the
/// plain step failed, if it was tried.
fn stabilized_step(
    engine: &mut Engine,
    committed: &State,
    lambda: f64,
    response: Response,
    main: bool,
    prior: Option<String>,
) -> Result<(State, usize), StepFailure> {
    let m = engine.model;
    let base = base_springs(engine, committed, lambda);
    let st = engine.stabilizer.as_mut().expect("checked by the caller");
    st.used += 1;
    let loaded = st.unloaded(m, lambda).is_none();
    // a body without a load of its own may be pressed into place by one that
    // has (a stack held about the axis by friction): released when it can be
    let pressed = loaded || st.any_loaded(m, lambda);
    let step = Stabilized {
        committed,
        lambda,
        response,
        main,
    };
    let Descended {
        last,
        iterations,
        failure,
    } = match step.descend(engine, &base, pressed)? {
        Descent::Released(exact, its) => return Ok((exact, its)),
        Descent::Held(d) => d,
    };
    let st = engine.stabilizer.as_ref().expect("checked");
    let why = st.explain(m, committed, lambda);
    let (Some((state, ks)), false) = (last, pressed) else {
        // a loaded body (a section's force included): only a released
        // answer is accepted, whichever body the springs hold
        let failure = if failure.is_empty() {
            "no stabilized solution rested on closed pairs".to_string()
        } else {
            failure
        };
        return Err(StepFailure::Unheld(match (why, prior) {
            (Some(why), Some(prior)) => format!("{why} ({prior}; with stabilization: {failure})"),
            (Some(why), None) => format!("{why} ({failure})"),
            (None, Some(prior)) => format!("{prior} (retried with stabilization: {failure})"),
            (None, None) => failure,
        }));
    };
    let why = why.unwrap_or_else(|| "a body is held only by the contact stabilization".into());
    let held = Descended {
        last: Some((state, ks)),
        iterations,
        failure,
    };
    step.within_energy(engine, held, &why)
}

/// The step that [`stabilized_step`] solves.
struct Stabilized<'a> {
    committed: &'a State,
    lambda: f64,
    response: Response,
    /// The run's own step (not a search's): the stabilization it used is
    /// reported.
    main: bool,
}

/// How the stabilized solves of [`Stabilized::descend`] ended.
enum Descent {
    /// Released: the exact answer without springs, and its iterations.
    Released(State, usize),
    /// Not released.
    Held(Descended),
}

/// The last stabilized solve not released: its state and springs (none if
/// the first failed), its iterations and why a solve failed ("" if none did).
struct Descended {
    last: Option<(State, Vec<f64>)>,
    iterations: usize,
    failure: String,
}

impl Stabilized<'_> {
    /// Solves with the springs `base` softened by 10⁻² per level; after each
    /// solve that holds every body, where the bodies are `pressed` (loaded,
    /// or by a loaded one), the step is solved again without the springs
    /// from it (the release).
    fn descend(
        &self,
        engine: &mut Engine,
        base: &[f64],
        pressed: bool,
    ) -> Result<Descent, StepFailure> {
        let (m, committed, lambda, response) =
            (engine.model, self.committed, self.lambda, self.response);
        let mut guess: Option<Vec<f64>> = None;
        // the iterations reported (curve.csv, automatic step control) are those
        // of the solve whose answer is kept: the release, or the last stabilized
        // solve at zero load; summary.json's newton_iterations counts them all
        let mut iterations = 0;
        let mut last: Option<(State, Vec<f64>)> = None;
        let mut failure = String::new();
        for level in 0..LEVELS {
            let ks: Vec<f64> = base.iter().map(|k| k * 1e-2f64.powi(level)).collect();
            let st = engine.stabilizer.as_mut().expect("checked");
            st.springs = Some(ks.clone());
            st.guess = guess.take();
            let solved = engine.plain_step(committed, lambda, response, None);
            let st = engine.stabilizer.as_mut().expect("checked");
            st.springs = None;
            let (state, its) = match solved {
                Ok(s) => s,
                Err(e) if e.signal().is_some() || e.is_fatal() => return Err(e),
                Err(e) => {
                    failure = format!("stabilized solve (k_s = {:.3e} MPa/mm) failed: {e}", ks[0]);
                    break;
                }
            };
            iterations = its;
            let held = st.floating(m, &state.u, lambda).is_empty();
            if engine.backend.agree(pressed && held) {
                engine.stabilizer.as_mut().expect("checked").guess = Some(state.u.clone());
                match engine.plain_step(committed, lambda, response, None) {
                    Ok((exact, its)) => {
                        if self.main {
                            engine.stabilizer.as_mut().expect("checked").pending =
                                Some((false, 0.0));
                        }
                        return Ok(Descent::Released(exact, its));
                    }
                    Err(e) if e.signal().is_some() || e.is_fatal() => return Err(e),
                    Err(e) => failure = format!("release of the stabilization failed: {e}"),
                }
            }
            guess = Some(state.u.clone());
            last = Some((state, ks));
        }
        Ok(Descent::Held(Descended {
            last,
            iterations,
            failure,
        }))
    }

    /// Keeps the last stabilized solve of an unloaded step if the springs'
    /// work, with that of the run so far, stays within
    /// `stabilization_energy` × the internal energy; else refuses it
    /// (`why`: the body the springs hold).
    fn within_energy(
        &self,
        engine: &mut Engine,
        held: Descended,
        why: &str,
    ) -> Result<(State, usize), StepFailure> {
        let committed = self.committed;
        let Descended {
            last,
            iterations,
            failure,
        } = held;
        let (state, ks) = last.expect("a stabilized solve to keep");
        let w = spring_work(engine, &ks, &committed.u, &state.u);
        let e_now = internal_energy(engine, committed).max(internal_energy(engine, &state));
        let st = engine.stabilizer.as_mut().expect("checked");
        st.report.internal = st.report.internal.max(e_now);
        let total = st.report.dissipated + w;
        let limit = st.report.limit * st.report.internal;
        if engine
            .backend
            .agree(total <= limit && st.report.internal > 0.0)
        {
            if self.main {
                st.pending = Some((true, w));
            }
            Ok((state, iterations))
        } else {
            let failure = if failure.is_empty() {
                String::new()
            } else {
                format!(" ({failure})")
            };
            Err(StepFailure::Unheld(if st.report.internal > 0.0 {
                format!(
                    "{why}; holding it would take the contact stabilization {total:.3e} N·mm of \
                     dissipated energy, above stabilization_energy = {} × the internal energy \
                     {:.3e} N·mm{failure}",
                    st.report.limit, st.report.internal,
                )
            } else {
                // "0 N·mm above 0 × 0 N·mm" would say nothing: nothing is loaded
                format!(
                    "{why}; nothing in the model has been loaded yet (internal energy 0 N·mm), so \
                     no contact force fixes its position, and the contact stabilization holds a \
                     body only against a positive internal energy (stabilization_energy = {} × \
                     it){failure}",
                    st.report.limit,
                )
            }))
        }
    }
}
