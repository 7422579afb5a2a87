//! One load step: the Newton iteration with the contact status check (paper
//! section 4, eq. 4.1-4.8), for the three methods.
//!
//! ```text
//!   R(u) = f_int(u) + f_c(u) − λ f_ext           (4.1)
//!   K Δu = −R,  u ← u + Δu                        (4.4, 4.7)
//!   K = K_AB^{E-P}(u) + K_c(u)        full Newton (4.6)
//!     = K_AB^{ep}(start of step) + K_c(u)  modified Newton
//!     = K_AB^{E} + K_c(u)              initial stiffness (4.8)
//! ```
//! The contact matrix is rebuilt every iteration in all three methods, as the
//! paper does. A step converges when the residual and the displacement correction
//! are small and no interface point changed status in the last iteration.

use super::accelerate::Anderson;
use super::State;
use crate::backend::serial::SerialLu;
use crate::case::{Acceleration, Method};
use crate::fem::solid::{element_forces, Response, Tangent};
use crate::interface::Status;
use crate::material::PointState;
use crate::model::Model;

/// Counters over a whole run.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    pub iterations: usize,
    pub factorizations: usize,
    pub assembly_seconds: f64,
    pub solve_seconds: f64,
}

pub struct Engine<'m> {
    pub model: &'m Model,
    pub method: Method,
    lu: SerialLu,
    vals: Vec<f64>,
    solid_vals: Vec<f64>,
    /// The cached solid matrix belongs to this committed state (modified Newton)
    /// or to the whole run (initial stiffness).
    solid_valid: bool,
    r: Vec<f64>,
    pub stats: Stats,
}

impl<'m> Engine<'m> {
    pub fn new(model: &'m Model, method: Method) -> crate::error::Result<Self> {
        let nnz = model.asm.nnz();
        Ok(Engine {
            model,
            method,
            lu: SerialLu::new(&model.asm)?,
            vals: vec![0.0; nnz],
            solid_vals: vec![0.0; nnz],
            solid_valid: false,
            r: vec![0.0; model.mesh.num_dofs()],
            stats: Stats::default(),
        })
    }

    /// Called when a new state is committed: the modified-Newton matrix is stale.
    pub fn committed(&mut self) {
        if self.method == Method::ModifiedNewton {
            self.solid_valid = false;
        }
    }

    /// Solves the step from `committed` to load factor `lambda`. Returns the
    /// converged trial state and the number of iterations, or a reason.
    pub fn step(
        &mut self,
        committed: &State,
        lambda: f64,
        response: Response,
    ) -> Result<(State, usize), String> {
        let m = self.model;
        let spec = &m.case.solver;
        let mut trial = committed.clone();
        for &(d, v) in &m.prescribed {
            trial.u[d] = lambda * v;
        }
        let method = if response == Response::ElasticOnly {
            Method::FullNewton
        } else {
            self.method
        };
        let limit = spec.iteration_limit();
        let mut last_status: Option<Vec<Status>> = None;
        let mut du_inf = f64::INFINITY;
        let mut anderson = (method != Method::FullNewton
            && spec.acceleration == Acceleration::Anderson)
            .then(|| Anderson::new(spec.anderson_depth));
        for it in 0..=limit {
            let t0 = std::time::Instant::now();
            let solid_tangent = match method {
                Method::FullNewton => Some(Tangent::Consistent),
                Method::ModifiedNewton if !self.solid_valid => Some(Tangent::Continuum),
                Method::InitialStiffness if !self.solid_valid => Some(Tangent::Elastic),
                _ => None,
            };
            let floor = (it == 0).then(|| self.start_stiffness(lambda));
            let status = self.assemble(
                committed,
                &mut trial,
                lambda,
                response,
                solid_tangent,
                floor,
            )?;
            self.stats.assembly_seconds += t0.elapsed().as_secs_f64();
            // norms over free dofs; reactions over prescribed dofs
            let (mut r2, mut f2, mut react2) = (0.0, 0.0, 0.0);
            for d in 0..self.r.len() {
                if m.dofs.equation(d).is_some() {
                    r2 += self.r[d] * self.r[d];
                    f2 += (lambda * m.f_ext[d]).powi(2);
                } else {
                    react2 += self.r[d] * self.r[d];
                }
            }
            let reference = f2.sqrt().max(react2.sqrt()).max(m.force_floor);
            let r_norm = r2.sqrt();
            if !r_norm.is_finite() {
                return Err(format!("residual is not finite at iteration {it}"));
            }
            let u_inf = trial
                .u
                .iter()
                .fold(0.0f64, |a, v| a.max(v.abs()))
                .max(1e-30);
            let same_status = last_status.as_ref() == Some(&status);
            let small_r = r_norm <= spec.residual_tolerance * reference;
            let small_du = it > 0 && du_inf <= spec.displacement_tolerance * u_inf;
            if small_r && (small_du || (it == 0 && r_norm == 0.0)) && (same_status || it == 0) {
                trial.status = status;
                trial.prescribed_reaction = m
                    .prescribed
                    .iter()
                    .filter(|(_, v)| *v != 0.0)
                    .map(|&(d, _)| self.r[d])
                    .sum();
                return Ok((trial, it));
            }
            if it == limit {
                return Err(format!(
                    "no convergence in {limit} iterations (|R|/|F| = {:.3e}, |du|/|u| = {:.3e}{})",
                    r_norm / reference,
                    du_inf / u_inf,
                    if same_status {
                        ""
                    } else {
                        ", contact status still changing"
                    }
                ));
            }
            if r_norm > 1e10 * reference && it > 2 {
                return Err(format!(
                    "diverged at iteration {it} (|R|/|F| = {:.3e})",
                    r_norm / reference
                ));
            }
            last_status = Some(status);
            // linear solve on the free dofs
            let t1 = std::time::Instant::now();
            let mut rhs: Vec<f64> = (0..self.r.len())
                .filter(|&d| m.dofs.equation(d).is_some())
                .map(|d| -self.r[d])
                .collect();
            self.lu.factor(&self.vals).map_err(|e| e.to_string())?;
            self.stats.factorizations += 1;
            self.lu.solve(&mut rhs).map_err(|e| e.to_string())?;
            self.stats.solve_seconds += t1.elapsed().as_secs_f64();
            if let Some(acc) = anderson.as_mut() {
                let x: Vec<f64> = (0..trial.u.len())
                    .filter(|&d| m.dofs.equation(d).is_some())
                    .map(|d| trial.u[d])
                    .collect();
                rhs = acc.step(&x, &rhs);
            }
            du_inf = 0.0;
            for d in 0..trial.u.len() {
                if let Some(e) = m.dofs.equation(d) {
                    trial.u[d] += rhs[e];
                    du_inf = du_inf.max(rhs[e].abs());
                }
            }
            self.stats.iterations += 1;
        }
        unreachable!("the loop returns at it == limit")
    }

    /// Residual (all dofs) and consistent tangent values (CSC over the free
    /// equations, pattern of `model.asm`) at displacement `u` from `committed`.
    /// Used by the finite-difference checks of the assembled tangent.
    pub fn linearize(
        &mut self,
        committed: &State,
        u: &[f64],
        lambda: f64,
    ) -> Result<(Vec<f64>, Vec<f64>), String> {
        let mut trial = committed.clone();
        trial.u.copy_from_slice(u);
        self.assemble(
            committed,
            &mut trial,
            lambda,
            Response::Plastic,
            Some(Tangent::Consistent),
            None,
        )?;
        Ok((self.r.clone(), self.vals.clone()))
    }

    /// Secant start stiffness (eq. 2.8-2.9) for pairs at zero approach.
    fn start_stiffness(&self, lambda: f64) -> Vec<f64> {
        let m = self.model;
        m.interfaces
            .iter()
            .map(|im| {
                let p_ref = im.start_pressure.unwrap_or_else(|| {
                    // mean interface pressure of the applied load at this load factor
                    let n = im.pairs.first().map_or([0.0, 1.0], |p| p.normal);
                    let f: f64 = (0..m.mesh.nodes.len())
                        .map(|i| m.f_ext[2 * i] * n[0] + m.f_ext[2 * i + 1] * n[1])
                        .sum();
                    (lambda * f.abs() / im.area()).max(1.0)
                });
                im.law.secant_stiffness(p_ref)
            })
            .collect()
    }

    /// Residual (into self.r, all dofs) and the requested matrix (into self.vals).
    /// Returns the interface statuses at `trial.u`.
    fn assemble(
        &mut self,
        committed: &State,
        trial: &mut State,
        lambda: f64,
        response: Response,
        solid_tangent: Option<Tangent>,
        floor: Option<Vec<f64>>,
    ) -> Result<Vec<Status>, String> {
        let m = self.model;
        let ng = m.n_gauss();
        for (r, f) in self.r.iter_mut().zip(&m.f_ext) {
            *r = -lambda * f;
        }
        let target = solid_tangent;
        if target.is_some() {
            self.solid_vals.fill(0.0);
        }
        let (mut fe, mut ke) = ([0.0; 16], [0.0; 256]);
        for (e, el) in m.mesh.elements.iter().enumerate() {
            let ue = m.element_u(e, &trial.u);
            let gs = e * ng..(e + 1) * ng;
            let committed_gp: &[PointState] = &committed.gauss[gs.clone()];
            element_forces(
                &m.geom[e],
                &m.materials[el.body],
                &ue,
                committed_gp,
                &mut trial.gauss[gs],
                response,
                target,
                &mut fe,
                &mut ke,
            )
            .map_err(|msg| format!("element {e} (body \"{}\"): {msg}", m.mesh.bodies[el.body]))?;
            for (a, &n) in el.nodes.iter().enumerate() {
                self.r[2 * n] += fe[2 * a];
                self.r[2 * n + 1] += fe[2 * a + 1];
            }
            if target.is_some() {
                m.asm.add(e, &ke, &mut self.solid_vals);
            }
        }
        if let Some(t) = solid_tangent {
            // a consistent matrix is never reused; the others are cached
            self.solid_valid = t != Tangent::Consistent;
        }
        self.vals.copy_from_slice(&self.solid_vals);
        let mut status = Vec::new();
        let (mut rl, mut kl) = ([0.0; 12], [0.0; 144]);
        let mut q = 0;
        for (i, im) in m.interfaces.iter().enumerate() {
            let kf = floor.as_ref().map(|f| f[i]);
            for (j, pt) in im.points.iter().enumerate() {
                let nd = 4 * pt.len;
                let un = im.point_kinematics(pt, &trial.u).0;
                let kfloor = kf.filter(|_| un > -1e-12);
                let ev = im.eval_point(
                    pt,
                    &trial.u,
                    &committed.contact[q],
                    kfloor,
                    &mut rl[..nd],
                    Some(&mut kl[..nd * nd]),
                );
                status.push(ev.status);
                trial.contact[q] = ev.state;
                q += 1;
                let dofs = im.point_dofs(pt);
                for (k, &d) in dofs.iter().enumerate() {
                    self.r[d] += rl[k];
                }
                m.asm.add(
                    m.interface_block_base[i] + j,
                    &kl[..nd * nd],
                    &mut self.vals,
                );
            }
        }
        Ok(status)
    }
}
