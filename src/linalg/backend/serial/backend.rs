//! The serial backend: the model's assembly on CSC values, solved by
//! [`SerialDirect`] (Cholesky, the split unsymmetric tangent, LU).

use super::{Factorization, SerialDirect, FACTOR_THREADS};
use crate::error::Result;
use crate::linalg::backend::coupling::{Couplings, Outcome};
use crate::model::assembly::{Assembler, Pattern};
use crate::model::Model;

/// The serial backend: CSC values on the fixed pattern, factored by [`SerialDirect`].
pub struct SerialBackend {
    asm: Assembler,
    direct: SerialDirect,
    /// The solid part, kept apart only when a method re-adds the springs to
    /// a reused solid matrix (see [`crate::linalg::backend::Backend::reuse_solid`]).
    solid: Option<Vec<f64>>,
    /// Values of the last system matrix; on the [`Factorization::SymmetricPart`]
    /// path its symmetric part, the rank-one terms held in `terms`.
    pub vals: Vec<f64>,
    /// The free equation of every dof, and the position of every equation
    /// among the interface equations (`u32::MAX`: none), for the rank-one terms.
    eq_of: Vec<u32>,
    pos_of: Vec<u32>,
    /// The interface points' unsymmetric rank-one terms of the last assembly.
    terms: Couplings,
    /// The whole tangent (symmetric part plus terms), formed where needed:
    /// for the LU fallback and for [`crate::linalg::backend::Backend::matrix_values`].
    whole: Vec<f64>,
    stats: CoupledStats,
    /// `[solver] interface_loop` applies to this model: the interface
    /// equations are ordered last where that pays, and the factor's
    /// condensation is offered to the Newton loop.
    interface_loop: bool,
}

/// Counters of the [`Factorization::SymmetricPart`] path.
#[derive(Default)]
struct CoupledStats {
    solves: usize,
    gmres_steps: usize,
    gmres_max: usize,
    terms_max: usize,
    lu_fallbacks: usize,
}

impl SerialBackend {
    /// The backend with the factorization the model's tangent calls for.
    pub fn new(model: &Model) -> Result<Self> {
        Self::with_factorization(model, Factorization::for_model(model))
    }

    /// The backend with a given factorization (LU and SymmetricPart work for
    /// every model; Cholesky only for a symmetric tangent).
    pub fn with_factorization(model: &Model, kind: Factorization) -> Result<Self> {
        let blocks = model.blocks();
        let pattern = &Pattern::new(&model.dofs, &blocks);
        let interface_loop = wants_interface_loop(model) && kind != Factorization::Lu;
        let interface = if kind == Factorization::SymmetricPart || interface_loop {
            interface_equations(model, &blocks, pattern.n)
        } else {
            Vec::new()
        };
        let mut pos_of = vec![u32::MAX; pattern.n];
        for (k, &e) in interface.iter().enumerate() {
            pos_of[e] = k as u32;
        }
        Ok(SerialBackend {
            asm: Assembler::new(pattern, &model.dofs, &blocks),
            direct: SerialDirect::with_interface(
                pattern,
                kind,
                interface,
                interface_loop,
                FACTOR_THREADS,
            )?,
            solid: None,
            vals: vec![0.0; pattern.nnz()],
            eq_of: model.dofs.eq.clone(),
            pos_of,
            terms: Couplings::default(),
            whole: Vec::new(),
            stats: CoupledStats::default(),
            interface_loop,
        })
    }

    /// The whole tangent into `self.whole`.
    fn form_whole(&mut self) {
        self.whole.clear();
        self.whole.extend_from_slice(&self.vals);
        self.terms.add_to(&self.asm, &mut self.whole);
    }
}

impl crate::linalg::backend::Comm for SerialBackend {}

impl crate::linalg::backend::Backend for SerialBackend {
    fn name(&self) -> &'static str {
        "serial-faer"
    }
    fn reuse_solid(&mut self, reuse: bool) {
        self.solid = reuse.then(|| vec![0.0; self.vals.len()]);
    }
    fn begin_solid(&mut self) -> Result<()> {
        self.solid.as_mut().unwrap_or(&mut self.vals).fill(0.0);
        Ok(())
    }
    fn add_solid(&mut self, block: usize, _dofs: &[usize], k: &[f64]) -> Result<()> {
        self.asm
            .add(block, k, self.solid.as_mut().unwrap_or(&mut self.vals));
        Ok(())
    }
    fn begin_contact(&mut self) -> Result<()> {
        if let Some(solid) = &self.solid {
            self.vals.copy_from_slice(solid);
        }
        self.terms.clear();
        Ok(())
    }
    fn add_contact(&mut self, block: usize, _dofs: &[usize], k: &[f64]) -> Result<()> {
        self.asm.add(block, k, &mut self.vals);
        Ok(())
    }
    fn splits_coupling(&self) -> bool {
        self.direct.kind() == Factorization::SymmetricPart
    }
    fn add_coupling(
        &mut self,
        block: usize,
        dofs: &[usize],
        coef: f64,
        g_t: &[f64],
        g_n: &[f64],
    ) -> Result<()> {
        if self.splits_coupling() {
            self.terms
                .push(&self.eq_of, &self.pos_of, block, dofs, coef, g_t, g_n);
        } else {
            self.asm.add(
                block,
                &crate::linalg::backend::outer(coef, g_t, g_n),
                &mut self.vals,
            );
        }
        Ok(())
    }
    fn matrix_values(&mut self) -> Option<&[f64]> {
        if self.terms.is_empty() {
            return Some(&self.vals);
        }
        self.form_whole();
        Some(&self.whole)
    }
    fn solve(&mut self, rhs: &[f64], x: &mut [f64]) -> Result<()> {
        x.copy_from_slice(rhs);
        if self.direct.kind() != Factorization::SymmetricPart {
            self.direct.factor(&self.vals)?;
            return self.direct.solve(x);
        }
        self.stats.solves += 1;
        self.stats.terms_max = self.stats.terms_max.max(self.terms.len());
        if self.direct.factor_cholesky(&self.vals)? {
            match self.direct.solve_coupled(&self.terms, x)? {
                Outcome::Converged(steps) => {
                    self.stats.gmres_steps += steps;
                    self.stats.gmres_max = self.stats.gmres_max.max(steps);
                    return Ok(());
                }
                Outcome::Stalled => x.copy_from_slice(rhs),
            }
        }
        // the symmetric part is not positive definite, or GMRES stalled:
        // the whole tangent by LU
        self.stats.lu_fallbacks += 1;
        self.form_whole();
        self.direct.factor_lu(&self.whole)?;
        self.direct.solve(x)
    }
    fn condensed(&mut self) -> Option<&mut dyn crate::linalg::backend::Condensed> {
        if !self.interface_loop {
            return None;
        }
        self.direct.condensed()
    }
    fn linear_solver(&self) -> String {
        self.direct.kind().name().into()
    }
    fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        match self.direct.kind() {
            Factorization::Cholesky if self.interface_loop => vec![
                ("lu_fallbacks", self.direct.fallbacks as f64),
                ("cholesky_factor_mb", self.direct.factor_mb()),
                (
                    "interface_equations",
                    self.pos_of.iter().filter(|&&p| p != u32::MAX).count() as f64,
                ),
                (
                    "interface_last",
                    f64::from(u8::from(self.direct.interface_last())),
                ),
            ],
            Factorization::Cholesky => vec![
                ("lu_fallbacks", self.direct.fallbacks as f64),
                ("cholesky_factor_mb", self.direct.factor_mb()),
            ],
            Factorization::Lu => Vec::new(),
            Factorization::SymmetricPart => {
                let st = &self.stats;
                vec![
                    ("lu_fallbacks", st.lu_fallbacks as f64),
                    ("cholesky_factor_mb", self.direct.factor_mb()),
                    ("coupling_terms_max", st.terms_max as f64),
                    (
                        "gmres_steps_mean",
                        st.gmres_steps as f64 / (st.solves - st.lu_fallbacks).max(1) as f64,
                    ),
                    ("gmres_steps_max", st.gmres_max as f64),
                    (
                        "interface_equations",
                        self.pos_of.iter().filter(|&&p| p != u32::MAX).count() as f64,
                    ),
                    (
                        "interface_last",
                        f64::from(u8::from(self.direct.interface_last())),
                    ),
                ]
            }
        }
    }
}

/// The free equations of every interface point's block (over their masters
/// where a point holds a constrained dof: what `add_coupling` touches), in
/// increasing order.
fn interface_equations(
    model: &Model,
    blocks: &crate::model::assembly::Blocks,
    n: usize,
) -> Vec<usize> {
    let mut on = vec![false; n];
    for b in model.interface_blocks() {
        for &d in blocks.get(b) {
            if let Some(e) = model.dofs.equation(d as usize) {
                on[e] = true;
            }
        }
    }
    (0..n).filter(|&e| on[e]).collect()
}

/// The interface equations where the serial backend of this model offers
/// the interface loop the condensation of its factor (`[solver]
/// interface_loop` applies and the interface-last ordering pays,
/// [`SerialDirect::plans_trailing`]), from the symbolic analyses alone; else
/// none. The PETSc backend runs the loop on exactly these models, so that
/// both take the same iterates.
#[cfg(feature = "parallel")]
pub(crate) fn interface_loop_equations(model: &Model) -> Result<Vec<usize>> {
    if !wants_interface_loop(model) {
        return Ok(Vec::new());
    }
    let kind = Factorization::for_model(model);
    let blocks = model.blocks();
    let pattern = Pattern::new(&model.dofs, &blocks);
    let interface = interface_equations(model, &blocks, pattern.n);
    Ok(
        if SerialDirect::plans_trailing(&pattern, kind, &interface)? {
            interface
        } else {
            Vec::new()
        },
    )
}

/// Whether `[solver] interface_loop` applies to a model: asked for, full
/// Newton, interface points, none of them on a constrained dof (an
/// interface point's block expanded over masters, [`crate::model::constraint`]).
pub(crate) fn wants_interface_loop(model: &Model) -> bool {
    let blocks = model.interface_blocks();
    model.solver.interface_loop()
        && model.solver.method == crate::input::case::Method::FullNewton
        && !blocks.is_empty()
        && !blocks.into_iter().any(|b| model.expansion(b).is_some())
}
