//! Serial sparse direct solver (faer) on the model's fixed pattern: the
//! symbolic analysis is done once per run, the numeric factor is written into
//! buffers that are reused by every Newton iteration.
//!
//! Which factorization runs is decided from the model, not by testing the
//! matrix ([`crate::model::Model::symmetric_tangent`]):
//! * a symmetric tangent (no tangential law, or the stiffness-modification
//!   friction scheme of eq. 2.25) is factored by sparse Cholesky `L Lᵀ` under
//!   an approximate-minimum-degree ordering. It is positive definite wherever
//!   the model is stable; when it is not (a limit load with no hardening, a
//!   body about to lose its support), the Cholesky stops at a non-positive
//!   pivot and the same matrix is factored by LU within the same iteration;
//! * an unsymmetric tangent (the return-mapping friction scheme: p_T^Y depends
//!   on p_N, eq. 2.18-2.21) is the symmetric part plus one rank-one term per
//!   interface point. The symmetric part is factored by Cholesky as above and
//!   the terms are solved for exactly by Woodbury's identity, with GMRES on
//!   the small capacitance system ([`super::coupling`]). Where that fails
//!   (the symmetric part is not positive definite, or GMRES stalls) the whole
//!   tangent is factored by LU with partial pivoting under a COLAMD column
//!   ordering, which is also selectable on its own
//!   ([`Factorization::Lu`]).
//!
//! A singular tangent (a body that can move as a rigid body) gives a
//! non-finite LU solution, reported as such. Measurements: docs/performance.md,
//! "Serial direct solver".

use super::coupling::{self, Couplings, Inverse, Outcome};
use super::trailing::{self as trail, Trailing};
use crate::assembly::{Assembler, Pattern};
use crate::error::{Error, Result};
use crate::model::Model;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};

/// The factorization a symmetric or unsymmetric tangent gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Factorization {
    /// Sparse Cholesky `L Lᵀ` (AMD ordering), LU where it meets a
    /// non-positive pivot.
    Cholesky,
    /// Sparse LU with partial pivoting (COLAMD ordering).
    Lu,
    /// Cholesky of the symmetric part, the interface points' unsymmetric
    /// rank-one terms by Woodbury and GMRES ([`super::coupling`]); LU of the
    /// whole tangent where either fails.
    SymmetricPart,
}

impl Factorization {
    /// How summary.json names it (`linear_solver`).
    pub fn name(self) -> &'static str {
        match self {
            Factorization::Cholesky => "faer sparse Cholesky (LU where not positive definite)",
            Factorization::Lu => "faer sparse LU",
            Factorization::SymmetricPart => {
                "faer sparse Cholesky of the symmetric part + Woodbury-GMRES on the interface coupling (LU where either fails)"
            }
        }
    }
}

/// The Cholesky path: symbolic analysis, factor values and workspace.
struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    /// Values of L, overwritten by every numeric factorization.
    values: Vec<f64>,
    /// Workspace of the numeric factorization and the solve.
    work: MemBuffer,
}

impl Cholesky {
    /// Allocates the factor and workspace of a symbolic analysis, within the
    /// memory budget.
    fn new(symbolic: SymbolicCholesky<usize>, par: Par) -> Result<Self> {
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, par),
        ]);
        check_memory(
            "Cholesky factor and its workspace",
            (symbolic.len_val() * 8 + req.size_bytes()) as f64,
            true,
        )?;
        let mut values = Vec::new();
        values
            .try_reserve_exact(symbolic.len_val())
            .map_err(|_| oom("Cholesky factor"))?;
        values.resize(symbolic.len_val(), 0.0);
        let work = MemBuffer::try_new(req).map_err(|_| oom("Cholesky workspace"))?;
        Ok(Cholesky {
            symbolic,
            values,
            work,
        })
    }
}

/// The LU path (also the Cholesky path's fallback), built when first needed.
struct Lu {
    symbolic: SymbolicLu<usize>,
    /// Reused by every numeric factorization (its buffers grow once).
    numeric: NumericLu<usize, f64>,
    work: MemBuffer,
}

/// Which factor holds the last matrix.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Held {
    None,
    Cholesky,
    Lu,
}

/// A sparse direct solver on a fixed pattern (both triangles stored).
pub struct SerialDirect {
    symbolic_mat: SymbolicSparseColMat<usize>,
    kind: Factorization,
    cholesky: Option<Cholesky>,
    lu: Option<Lu>,
    held: Held,
    /// Numeric factorizations performed (of either kind).
    pub factorizations: usize,
    /// Cholesky factorizations that met a non-positive pivot and were redone by LU.
    pub fallbacks: usize,
    /// faer's parallelism for the numeric factorizations and the solves (and
    /// their workspace sizes): `Seq` on one thread, else `Rayon(threads)`.
    par: Par,
    /// The interface equations ([`Factorization::SymmetricPart`]), in the
    /// order of [`Inverse::interface`].
    interface: Vec<usize>,
    /// The factor's trailing block when the interface is ordered last.
    trailing: Option<Trailing>,
    /// An n-vector for [`Inverse::interface`] without the trailing block.
    scratch: Vec<f64>,
}

fn oom(what: &str) -> Error {
    Error::Memory(format!(
        "allocating the {what} failed: the model is too large for this machine's memory with the serial solver (fewer elements, or the PETSc backend on several ranks)"
    ))
}

/// Environment variable that caps the memory a serial run may plan for, MB
/// (default: the machine's available memory, `MemAvailable` of /proc/meminfo).
pub const MEMORY_LIMIT_VAR: &str = "ASPERITY_MEMORY_LIMIT_MB";

/// The memory a run may plan for, bytes: [`MEMORY_LIMIT_VAR`] if set, else
/// the available memory (Linux), else unbounded.
fn memory_budget() -> Result<Option<f64>> {
    if let Ok(v) = std::env::var(MEMORY_LIMIT_VAR) {
        let mb: f64 = v
            .trim()
            .parse()
            .ok()
            .filter(|m: &f64| *m > 0.0 && m.is_finite())
            .ok_or_else(|| {
                Error::input(
                    MEMORY_LIMIT_VAR,
                    format!("expected a positive number of MB, got \"{v}\""),
                )
            })?;
        return Ok(Some(mb * 1048576.0));
    }
    Ok(std::fs::read_to_string("/proc/meminfo").ok().and_then(|s| {
        s.lines()
            .find(|l| l.starts_with("MemAvailable:"))
            .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
            .map(|kb| kb * 1024.0)
    }))
}

/// Refuses a factorization whose planned memory exceeds the budget, before
/// any of it is allocated.
fn check_memory(what: &str, bytes: f64, exact: bool) -> Result<()> {
    if let Some(budget) = memory_budget()? {
        if bytes > budget {
            let size = |b: f64| {
                if b >= 1073741824.0 {
                    format!("{:.2} GB", b / 1073741824.0)
                } else {
                    format!("{:.1} MB", b / 1048576.0)
                }
            };
            return Err(Error::Memory(format!(
                "the serial {what} {} {}{} (from its symbolic analysis) but {} {}: use fewer elements, or the PETSc backend on several ranks (--features parallel, mpirun)",
                if what.contains(" and ") { "need" } else { "needs" },
                if exact { "" } else { "at least " },
                size(bytes),
                size(budget),
                if std::env::var_os(MEMORY_LIMIT_VAR).is_some() {
                    format!("is allowed ({MEMORY_LIMIT_VAR})")
                } else {
                    "is available".to_string()
                },
            )));
        }
    }
    Ok(())
}

impl SerialDirect {
    /// Symbolic analysis (fill-reducing ordering, elimination tree, factor
    /// structure) of the pattern for the given factorization, whose numeric
    /// factorizations and solves use `threads` threads (faer's parallel
    /// kernels on rayon's global pool; a run uses [`FACTOR_THREADS`]).
    pub fn new(pattern: &Pattern, kind: Factorization, threads: usize) -> Result<Self> {
        Self::with_interface(pattern, kind, Vec::new(), threads)
    }

    /// [`SerialDirect::new`] given the interface equations (for
    /// [`Factorization::SymmetricPart`]): they are ordered last where the
    /// symbolic analysis finds that costs little fill ([`trail`]).
    pub fn with_interface(
        pattern: &Pattern,
        kind: Factorization,
        interface: Vec<usize>,
        threads: usize,
    ) -> Result<Self> {
        let symbolic_mat = SymbolicSparseColMat::new_checked(
            pattern.n,
            pattern.n,
            pattern.col_ptr.clone(),
            None,
            pattern.row_idx.iter().map(|&r| r as usize).collect(),
        );
        let mut s = SerialDirect {
            symbolic_mat,
            kind,
            cholesky: None,
            lu: None,
            held: Held::None,
            factorizations: 0,
            fallbacks: 0,
            par: if threads > 1 {
                Par::rayon(threads)
            } else {
                Par::Seq
            },
            interface,
            trailing: None,
            scratch: Vec::new(),
        };
        match kind {
            Factorization::Cholesky => {
                let symbolic = s.symbolic_cholesky(SymmetricOrdering::Amd)?;
                s.cholesky = Some(Cholesky::new(symbolic, s.par)?);
            }
            Factorization::SymmetricPart => {
                let plain = s.symbolic_cholesky(SymmetricOrdering::Amd)?;
                let mut chosen = plain;
                if !s.interface.is_empty() && s.interface.len() < pattern.n {
                    let (fwd, inv) = trail::ordering_with_last(&s.symbolic_mat, &s.interface)?;
                    let perm = PermRef::new_checked(&fwd, &inv, pattern.n);
                    let last = s.symbolic_cholesky(SymmetricOrdering::Custom(perm))?;
                    if trail::prefer_interface_last(
                        trail::factor_cost(&last),
                        trail::factor_cost(&chosen),
                    ) {
                        // the dense block and the map into the factor
                        let m = s.interface.len() as f64;
                        check_memory("Cholesky factor's interface block", 16.0 * m * m, false)?;
                        s.trailing = Trailing::new(&last, s.interface.len());
                        if s.trailing.is_some() {
                            chosen = last;
                        }
                    }
                }
                s.cholesky = Some(Cholesky::new(chosen, s.par)?);
            }
            Factorization::Lu => s.lu = Some(s.analyse_lu()?),
        }
        Ok(s)
    }

    fn symbolic_cholesky(
        &self,
        ordering: SymmetricOrdering<usize>,
    ) -> Result<SymbolicCholesky<usize>> {
        factorize_symbolic_cholesky(
            self.symbolic_mat.as_ref(),
            Side::Lower,
            ordering,
            // supernodal at every size: faer's automatic choice takes the
            // simplicial (column by column) factorization for the default
            // punch (1,541 equations), 2.8x slower there (docs/performance.md)
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|e| Error::Solver(format!("symbolic Cholesky failed: {e:?}")))
    }

    /// Whether the interface equations are ordered last (the trailing block
    /// serves the GMRES steps).
    pub fn interface_last(&self) -> bool {
        self.trailing.is_some()
    }

    fn analyse_lu(&self) -> Result<Lu> {
        // L and U hold at least the fill of a Cholesky factor of the pattern
        // under its best ordering (the pattern is structurally symmetric):
        // a lower bound of the LU factor, refused up front if even that
        // does not fit
        if let Ok(chol) = factorize_symbolic_cholesky(
            self.symbolic_mat.as_ref(),
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        ) {
            check_memory("LU factor", (2 * chol.len_val() * 8) as f64, false)?;
        }
        let symbolic = factorize_symbolic_lu(self.symbolic_mat.as_ref(), Default::default())
            .map_err(|e| Error::Solver(format!("symbolic LU failed: {e:?}")))?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_lu_scratch::<f64>(self.par, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, self.par),
        ]);
        let work = MemBuffer::try_new(req).map_err(|_| oom("LU workspace"))?;
        Ok(Lu {
            symbolic,
            numeric: NumericLu::new(),
            work,
        })
    }

    /// The factorization chosen for this pattern.
    pub fn kind(&self) -> Factorization {
        self.kind
    }

    /// Size of the Cholesky factor's values (0 on the LU path), MB.
    pub fn factor_mb(&self) -> f64 {
        self.cholesky
            .as_ref()
            .map_or(0.0, |c| c.values.len() as f64 * 8.0 / 1e6)
    }

    /// Numeric factorization of the matrix with the given values (CSC on the
    /// pattern, both triangles). The Cholesky path reads the lower triangle.
    pub fn factor(&mut self, values: &[f64]) -> Result<()> {
        if self.factor_cholesky(values)? {
            return Ok(());
        }
        // not positive definite (or no Cholesky path): the same matrix by LU,
        // this iteration
        self.factor_lu(values)
    }

    /// The Cholesky factorization of the matrix's lower triangle, where this
    /// solver has a Cholesky path: whether it succeeded (false: not positive
    /// definite, counted as a fallback, or no Cholesky path).
    pub fn factor_cholesky(&mut self, values: &[f64]) -> Result<bool> {
        check_finite(values)?;
        self.held = Held::None;
        let Some(c) = self.cholesky.as_mut() else {
            return Ok(false);
        };
        let mat = SparseColMatRef::new(self.symbolic_mat.as_ref(), values);
        self.factorizations += 1;
        let done = c.symbolic.factorize_numeric_llt::<f64>(
            &mut c.values,
            mat,
            Side::Lower,
            LltRegularization::default(),
            self.par,
            MemStack::new(&mut c.work),
            Default::default(),
        );
        if done.is_ok() {
            self.held = Held::Cholesky;
            if let Some(t) = self.trailing.as_mut() {
                t.extract(&c.values);
            }
            return Ok(true);
        }
        self.fallbacks += 1;
        Ok(false)
    }

    /// The LU factorization of the matrix (analysed when first needed).
    pub fn factor_lu(&mut self, values: &[f64]) -> Result<()> {
        check_finite(values)?;
        self.held = Held::None;
        let mat = SparseColMatRef::new(self.symbolic_mat.as_ref(), values);
        self.factorizations += 1;
        if self.lu.is_none() {
            self.lu = Some(self.analyse_lu()?);
        }
        let lu = self.lu.as_mut().expect("LU analysed above");
        lu.symbolic
            .factorize_numeric_lu::<f64>(
                &mut lu.numeric,
                mat,
                self.par,
                MemStack::new(&mut lu.work),
                Default::default(),
            )
            .map_err(|e| match e {
                faer::sparse::linalg::LuError::Generic(faer::sparse::FaerError::OutOfMemory) => {
                    oom("LU factor")
                }
                e => Error::Solver(format!("numeric LU failed: {e:?}")),
            })?;
        self.held = Held::Lu;
        Ok(())
    }

    /// Applies the last factorization's inverse in place, without checks.
    fn apply(&mut self, rhs: &mut [f64]) {
        let n = rhs.len();
        let mat = MatMut::from_column_major_slice_mut(rhs, n, 1);
        match self.held {
            Held::None => unreachable!("apply before factor"),
            Held::Cholesky => {
                let c = self.cholesky.as_mut().expect("held");
                LltRef::new(&c.symbolic, &c.values).solve_in_place_with_conj(
                    Conj::No,
                    mat,
                    self.par,
                    MemStack::new(&mut c.work),
                );
            }
            Held::Lu => {
                let lu = self.lu.as_mut().expect("held");
                LuRef::new_unchecked(&lu.symbolic, &lu.numeric).solve_in_place_with_conj(
                    Conj::No,
                    mat,
                    self.par,
                    MemStack::new(&mut lu.work),
                );
            }
        }
    }

    /// Solves in place with the last factorization. A non-finite solution means a
    /// singular tangent: a body held by nothing (rigid-body motion) or all pairs open.
    pub fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        if self.held == Held::None {
            return Err(Error::Solver("solve before factor".into()));
        }
        self.apply(rhs);
        check_solution(rhs)
    }

    /// Solves `(M + U Vᵀ) x = rhs` in place where the last factorization is
    /// the Cholesky factor of M: Woodbury with GMRES ([`super::coupling`]).
    fn solve_coupled(&mut self, terms: &Couplings, rhs: &mut [f64]) -> Result<Outcome> {
        if self.held != Held::Cholesky {
            return Err(Error::Solver(
                "coupled solve without a Cholesky factor".into(),
            ));
        }
        let m = self.interface.len();
        let out = coupling::solve(terms, m, self, rhs);
        if out != Outcome::Stalled {
            check_solution(rhs)?;
        }
        Ok(out)
    }
}

impl Inverse for SerialDirect {
    fn full(&mut self, v: &mut [f64]) {
        self.apply(v);
    }
    fn interface(&mut self, v: &mut [f64]) {
        if let Some(t) = &self.trailing {
            return t.solve(v);
        }
        let mut w = std::mem::take(&mut self.scratch);
        w.clear();
        w.resize(self.symbolic_mat.nrows(), 0.0);
        for (k, &e) in self.interface.iter().enumerate() {
            w[e] = v[k];
        }
        self.apply(&mut w);
        for (k, &e) in self.interface.iter().enumerate() {
            v[k] = w[e];
        }
        self.scratch = w;
    }
}

/// Threads of a run's numeric factorizations and solves: one, whatever
/// `--threads` says. faer's parallel kernels (`Par::rayon(2)`) made them
/// slower on every model measured, 1.6k to 209k dofs, Cholesky and LU
/// (0.35-0.85x on 2 cores; docs/performance.md, "Threads in the one-process
/// path"): a 2D mesh's factor is mostly small supernodes, too small to
/// split, and the idle pool's spinning slows the threaded element loop.
pub const FACTOR_THREADS: usize = 1;

fn check_finite(values: &[f64]) -> Result<()> {
    if values.iter().any(|v| !v.is_finite()) {
        return Err(Error::Solver(
            "the tangent matrix holds NaN or infinite entries".into(),
        ));
    }
    Ok(())
}

fn check_solution(x: &[f64]) -> Result<()> {
    if x.iter().any(|v| !v.is_finite()) {
        return Err(Error::Solver(
            "singular tangent matrix: a body can move as a rigid body (missing support, or every interface pair open)".into(),
        ));
    }
    Ok(())
}

/// The serial backend: CSC values on the fixed pattern, factored by [`SerialDirect`].
pub struct SerialBackend {
    asm: Assembler,
    direct: SerialDirect,
    /// The solid part, kept apart only when a method re-adds the springs to
    /// a reused solid matrix (see [`super::Backend::reuse_solid`]).
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
    /// for the LU fallback and for [`super::Backend::matrix_values`].
    whole: Vec<f64>,
    stats: CoupledStats,
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
        let kind = if model.symmetric_tangent() {
            Factorization::Cholesky
        } else {
            Factorization::SymmetricPart
        };
        Self::with_factorization(model, kind)
    }

    /// The backend with a given factorization (LU and SymmetricPart work for
    /// every model; Cholesky only for a symmetric tangent).
    pub fn with_factorization(model: &Model, kind: Factorization) -> Result<Self> {
        let blocks = model.blocks();
        let pattern = &Pattern::new(&model.dofs, &blocks);
        // the free equations of every interface point, in increasing order
        let mut pos_of = vec![u32::MAX; pattern.n];
        let mut interface = Vec::new();
        if kind == Factorization::SymmetricPart {
            for im in &model.interfaces {
                for pt in &im.points {
                    for d in im.point_dofs(pt) {
                        if let Some(e) = model.dofs.equation(d) {
                            pos_of[e] = 0;
                        }
                    }
                }
            }
            for (e, p) in pos_of.iter_mut().enumerate() {
                if *p == 0 {
                    *p = interface.len() as u32;
                    interface.push(e);
                }
            }
        }
        Ok(SerialBackend {
            asm: Assembler::new(pattern, &model.dofs, &blocks),
            direct: SerialDirect::with_interface(pattern, kind, interface, FACTOR_THREADS)?,
            solid: None,
            vals: vec![0.0; pattern.nnz()],
            eq_of: model.dofs.eq.clone(),
            pos_of,
            terms: Couplings::default(),
            whole: Vec::new(),
            stats: CoupledStats::default(),
        })
    }

    /// The whole tangent into `self.whole`.
    fn form_whole(&mut self) {
        self.whole.clear();
        self.whole.extend_from_slice(&self.vals);
        self.terms.add_to(&self.asm, &mut self.whole);
    }
}

impl super::Backend for SerialBackend {
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
            self.asm
                .add(block, &super::outer(coef, g_t, g_n), &mut self.vals);
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
    fn linear_solver(&self) -> String {
        self.direct.kind().name().into()
    }
    fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        match self.direct.kind() {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A dense n×n pattern (both triangles), column by column.
    fn dense(n: usize) -> Pattern {
        Pattern {
            n,
            col_ptr: (0..=n).map(|j| j * n).collect(),
            row_idx: (0..n * n).map(|k| (k % n) as u32).collect(),
        }
    }

    fn solve(kind: Factorization, a: &[f64], b: &[f64]) -> (Result<Vec<f64>>, usize) {
        let n = b.len();
        let mut d = SerialDirect::new(&dense(n), kind, 1).unwrap();
        let mut x = b.to_vec();
        let r = d.factor(a).and_then(|()| d.solve(&mut x)).map(|()| x);
        (r, d.fallbacks)
    }

    /// A 5-point Laplacian on a g×g grid plus 4 on the diagonal (SPD):
    /// pattern (both triangles) and values.
    fn grid(g: usize) -> (Pattern, Vec<f64>) {
        let n = g * g;
        let (mut col_ptr, mut row_idx, mut vals) = (vec![0], Vec::new(), Vec::new());
        for j in 0..n {
            let (x, y) = (j % g, j / g);
            let mut col = vec![(j, 8.0)];
            if x > 0 {
                col.push((j - 1, -1.0));
            }
            if x + 1 < g {
                col.push((j + 1, -1.0));
            }
            if y > 0 {
                col.push((j - g, -1.0));
            }
            if y + 1 < g {
                col.push((j + g, -1.0));
            }
            col.sort_by_key(|c| c.0);
            for (i, v) in col {
                row_idx.push(i as u32);
                vals.push(v);
            }
            col_ptr.push(row_idx.len());
        }
        (
            Pattern {
                n,
                col_ptr,
                row_idx,
            },
            vals,
        )
    }

    #[test]
    fn the_trailing_block_gives_the_interface_part_of_the_inverse() {
        // the "interface": one grid row across the middle, which separates
        // the grid as a contact interface separates two bodies
        let g = 9;
        let (pattern, vals) = grid(g);
        let iface: Vec<usize> = (0..g).map(|x| 4 * g + x).collect();
        let mut d =
            SerialDirect::with_interface(&pattern, Factorization::SymmetricPart, iface.clone(), 1)
                .unwrap();
        assert!(d.interface_last(), "a separator is cheap to order last");
        assert!(d.factor_cholesky(&vals).unwrap());
        let a: Vec<f64> = (0..g).map(|k| 1.0 + (k as f64).sin()).collect();
        let mut by_block = a.clone();
        Inverse::interface(&mut d, &mut by_block);
        // the same without the trailing block: a solve with the whole factor
        d.trailing = None;
        let mut by_solve = a.clone();
        Inverse::interface(&mut d, &mut by_solve);
        let big = by_solve.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (p, q) in by_block.iter().zip(&by_solve) {
            assert!((p - q).abs() < 1e-14 * big, "{by_block:?} {by_solve:?}");
        }
        // and the whole-factor solve is M⁻¹ itself: M (M⁻¹ [0; a]) = [0; a]
        let mut w = vec![0.0; g * g];
        for (k, &e) in iface.iter().enumerate() {
            w[e] = a[k];
        }
        d.apply(&mut w);
        let mut back = vec![0.0; g * g];
        for (j, wj) in w.iter().enumerate() {
            for p in pattern.col_ptr[j]..pattern.col_ptr[j + 1] {
                back[pattern.row_idx[p] as usize] += vals[p] * wj;
            }
        }
        for (e, v) in back.iter().enumerate() {
            let want = iface.iter().position(|&i| i == e).map_or(0.0, |k| a[k]);
            assert!((v - want).abs() < 1e-12, "row {e}: {v} against {want}");
        }
    }

    #[test]
    fn cholesky_solves_a_positive_definite_system() {
        // column-major [[4, 1, 0], [1, 3, 1], [0, 1, 2]]
        let a = [4.0, 1.0, 0.0, 1.0, 3.0, 1.0, 0.0, 1.0, 2.0];
        let x_true = [1.0, -2.0, 0.5];
        let b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| a[j * 3 + i] * x_true[j]).sum())
            .collect();
        let (x, fallbacks) = solve(Factorization::Cholesky, &a, &b);
        let x = x.unwrap();
        assert_eq!(fallbacks, 0);
        for (u, v) in x.iter().zip(x_true) {
            assert!((u - v).abs() < 1e-14, "{x:?}");
        }
    }

    #[test]
    fn an_indefinite_tangent_falls_back_to_lu_in_the_same_factorization() {
        // symmetric, eigenvalues 3 and −1: Cholesky meets a negative pivot
        let a = [1.0, 2.0, 2.0, 1.0];
        let x_true = [0.25, -1.5];
        let b = [
            a[0] * x_true[0] + a[2] * x_true[1],
            a[1] * x_true[0] + a[3] * x_true[1],
        ];
        let (x, fallbacks) = solve(Factorization::Cholesky, &a, &b);
        let x = x.unwrap();
        assert_eq!(fallbacks, 1);
        for (u, v) in x.iter().zip(x_true) {
            assert!((u - v).abs() < 1e-14, "{x:?}");
        }
    }

    #[test]
    fn a_singular_tangent_is_named_not_solved() {
        // a rigid-body mode: [[1, −1], [−1, 1]]
        let a = [1.0, -1.0, -1.0, 1.0];
        for kind in [Factorization::Cholesky, Factorization::Lu] {
            let msg = solve(kind, &a, &[1.0, 0.0]).0.unwrap_err().to_string();
            assert!(msg.contains("singular tangent"), "{kind:?}: {msg}");
        }
    }

    #[test]
    fn the_cholesky_path_reads_only_the_lower_triangle() {
        // the upper triangle holds garbage: the symmetric lower one is solved
        let a = [2.0, 1.0, 99.0, 2.0];
        let (x, _) = solve(Factorization::Cholesky, &a, &[3.0, 3.0]);
        let x = x.unwrap();
        assert!(
            (x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14,
            "{x:?}"
        );
    }
}
