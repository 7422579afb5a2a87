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
use crate::error::{Error, Result};
use crate::model::assembly::Pattern;
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
    /// The factorization a model's tangent calls for: Cholesky where it is
    /// symmetric, else the symmetric part with the interface terms apart.
    pub fn for_model(model: &crate::model::Model) -> Factorization {
        if model.symmetric_tangent() {
            Factorization::Cholesky
        } else {
            Factorization::SymmetricPart
        }
    }

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
pub(crate) const MEMORY_LIMIT_VAR: &str = "ASPERITY_MEMORY_LIMIT_MB";

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

/// The pattern as faer's symbolic matrix.
fn symbolic_of(pattern: &Pattern) -> SymbolicSparseColMat<usize> {
    SymbolicSparseColMat::new_checked(
        pattern.n,
        pattern.n,
        pattern.col_ptr.clone(),
        None,
        pattern.row_idx.iter().map(|&r| r as usize).collect(),
    )
}

fn symbolic_cholesky(
    mat: &SymbolicSparseColMat<usize>,
    ordering: SymmetricOrdering<usize>,
) -> Result<SymbolicCholesky<usize>> {
    factorize_symbolic_cholesky(
        mat.as_ref(),
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

/// The interface-last analysis where it pays against the plain one, else
/// `None`. Which cost decides: [`trail::prefer_interface_last`] for the
/// Woodbury-GMRES steps of [`Factorization::SymmetricPart`] (or, `for_loop`:
/// the interface loop runs, the loop's rule as well),
/// [`trail::prefer_condensed`] for the interface loop on a symmetric tangent.
fn interface_last_pays(
    mat: &SymbolicSparseColMat<usize>,
    interface: &[usize],
    kind: Factorization,
    plain: &SymbolicCholesky<usize>,
    for_loop: bool,
) -> Result<Option<SymbolicCholesky<usize>>> {
    let n = mat.nrows();
    let (fwd, inv) = trail::ordering_with_last(mat, interface)?;
    let perm = PermRef::new_checked(&fwd, &inv, n);
    let last = symbolic_cholesky(mat, SymmetricOrdering::Custom(perm))?;
    let (c_last, c_plain) = (trail::factor_cost(&last), trail::factor_cost(plain));
    let condensed = || trail::prefer_condensed(interface.len(), c_last, c_plain);
    let pays = match kind {
        // the unsymmetric tangent: the trailing block serves the Woodbury
        // GMRES steps, and with the interface loop the loop as well, which
        // the Cholesky rule prices (a friction case on a mesh whose
        // interface-last factor costs more than the GMRES steps save still
        // gets the loop when the Cholesky case would)
        Factorization::SymmetricPart => {
            trail::prefer_interface_last(c_last, c_plain) || (for_loop && condensed())
        }
        _ => condensed(),
    };
    Ok(pays.then_some(last))
}

impl SerialDirect {
    /// Symbolic analysis (fill-reducing ordering, elimination tree, factor
    /// structure) of the pattern for the given factorization, whose numeric
    /// factorizations and solves use `threads` threads (faer's parallel
    /// kernels on rayon's global pool; a run uses [`FACTOR_THREADS`]).
    pub fn new(pattern: &Pattern, kind: Factorization, threads: usize) -> Result<Self> {
        Self::with_interface(pattern, kind, Vec::new(), false, threads)
    }

    /// [`SerialDirect::new`] given the interface equations (for
    /// [`Factorization::SymmetricPart`], or for the interface loop,
    /// `for_loop`): they are ordered last where the symbolic analysis finds
    /// that pays ([`interface_last_pays`]).
    pub(crate) fn with_interface(
        pattern: &Pattern,
        kind: Factorization,
        interface: Vec<usize>,
        for_loop: bool,
        threads: usize,
    ) -> Result<Self> {
        let symbolic_mat = symbolic_of(pattern);
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
            Factorization::Cholesky | Factorization::SymmetricPart => {
                let plain = symbolic_cholesky(&s.symbolic_mat, SymmetricOrdering::Amd)?;
                let chosen = if s.interface.is_empty() || s.interface.len() >= pattern.n {
                    plain
                } else {
                    s.with_interface_last(plain, kind, for_loop)?
                };
                s.cholesky = Some(Cholesky::new(chosen, s.par)?);
            }
            Factorization::Lu => s.lu = Some(s.analyse_lu()?),
        }
        Ok(s)
    }

    /// The interface-last analysis where it pays against the plain one
    /// (with its trailing block), else the plain one ([`interface_last_pays`]).
    fn with_interface_last(
        &mut self,
        plain: SymbolicCholesky<usize>,
        kind: Factorization,
        for_loop: bool,
    ) -> Result<SymbolicCholesky<usize>> {
        let Some(last) =
            interface_last_pays(&self.symbolic_mat, &self.interface, kind, &plain, for_loop)?
        else {
            return Ok(plain);
        };
        let m = self.interface.len();
        // the dense block and the map into the factor
        check_memory(
            "Cholesky factor's interface block",
            16.0 * (m as f64).powi(2),
            false,
        )?;
        self.trailing = Trailing::new(&last, m);
        Ok(if self.trailing.is_some() { last } else { plain })
    }

    /// Whether [`SerialDirect::with_interface`] on this pattern orders the
    /// interface last with its trailing block, from the symbolic analyses
    /// alone (no numeric storage): the PETSc backend asks it so that both
    /// backends run the interface loop on the same models.
    #[cfg(feature = "parallel")]
    pub(crate) fn plans_trailing(
        pattern: &Pattern,
        kind: Factorization,
        interface: &[usize],
    ) -> Result<bool> {
        if kind == Factorization::Lu || interface.is_empty() || interface.len() >= pattern.n {
            return Ok(false);
        }
        let mat = symbolic_of(pattern);
        let plain = symbolic_cholesky(&mat, SymmetricOrdering::Amd)?;
        Ok(interface_last_pays(&mat, interface, kind, &plain, true)?
            .is_some_and(|last| Trailing::new(&last, interface.len()).is_some()))
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
    pub(crate) fn factor_mb(&self) -> f64 {
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
    pub(crate) fn factor_cholesky(&mut self, values: &[f64]) -> Result<bool> {
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
    pub(crate) fn factor_lu(&mut self, values: &[f64]) -> Result<()> {
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

impl SerialDirect {
    /// The condensation of the last factorization: where it is a Cholesky
    /// factor with the interface ordered last.
    pub fn condensed(&mut self) -> Option<&mut dyn crate::linalg::backend::Condensed> {
        (self.held == Held::Cholesky && self.trailing.is_some()).then_some(self)
    }
}

impl crate::linalg::backend::Condensed for SerialDirect {
    fn equations(&self) -> &[usize] {
        &self.interface
    }
    fn schur(&mut self) -> Option<Vec<f64>> {
        self.trailing.as_ref().map(Trailing::schur)
    }
    fn lift(&mut self, e: &[f64], x: &mut [f64]) -> bool {
        let mut w = std::mem::take(&mut self.scratch);
        w.clear();
        w.resize(self.symbolic_mat.nrows(), 0.0);
        for (k, &eq) in self.interface.iter().enumerate() {
            w[eq] = e[k];
        }
        self.apply(&mut w);
        for (xi, wi) in x.iter_mut().zip(&w) {
            *xi += wi;
        }
        self.scratch = w;
        true
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

mod backend;
#[cfg(feature = "parallel")]
pub(crate) use backend::interface_loop_equations;
pub use backend::SerialBackend;

#[cfg(test)]
mod tests;
