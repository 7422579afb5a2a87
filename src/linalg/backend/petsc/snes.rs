//! PETSc's SNES driving a load step (`--nonlinear snes`, the default on the
//! PETSc backend).
//!
//! SNES owns the iteration; the paper's step is a [`Problem`] reached through
//! four `extern "C"` trampolines, each wrapped in `catch_unwind` so that a panic
//! never unwinds into C:
//! * function: gathers the iterate onto every rank, evaluates the residual (and
//!   assembles the step's tangent into the backend's matrix in the same pass),
//!   writes the owned residual entries;
//! * Jacobian: finishes the assembly of that matrix (re-evaluating first if SNES
//!   asks at another iterate than the last one evaluated);
//! * convergence test: the paper's rules (residual, correction, unchanged contact
//!   statuses), decided collectively by the problem;
//! * line-search post-check: hands the Newton correction to the problem, which
//!   counts the iteration and applies Anderson mixing for the fixed-matrix methods.
//!
//! Defaults set before `SNESSetFromOptions`, so that every one can be overridden
//! on the command line: `newtonls` with the `basic` (full-step) line search, the
//! KSP of the linear backend (`preonly` + MUMPS LU). With these defaults SNES
//! takes the same iterates as the built-in loop, to round-off.

use super::solver::Partition;
use super::{chk, default_option, ffi, gamg_defaults, option_given, PVec, Petsc, ToAll};
use crate::error::{Error, Result};
use crate::linalg::failure::StepFailure;
use crate::linalg::nonlinear::{NonlinearSolver, Problem, Verdict};
use std::os::raw::c_void;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// The map between PETSc's distributed vectors and the replicated vectors of
/// free equations (the model's equation order).
struct Layout<'p> {
    to_all: ToAll<'p>,
    petsc_index: Vec<ffi::PetscInt>,
    /// (position in the local array, equation) of every owned equation.
    owned: Vec<(usize, usize)>,
    gathered: Vec<f64>,
    /// The iterate of the last evaluation, and its residual.
    x: Vec<f64>,
    r: Vec<f64>,
    scratch: Vec<f64>,
    du: Vec<f64>,
}

impl Layout<'_> {
    /// Copies a distributed vector into `out` (equation order) on every rank.
    fn gather(&mut self, v: ffi::Vec, which: Which) -> Result<()> {
        self.to_all.gather_raw(v, &mut self.gathered)?;
        let out = match which {
            Which::X => &mut self.x,
            Which::Scratch => &mut self.scratch,
        };
        for (o, &p) in out.iter_mut().zip(&self.petsc_index) {
            *o = self.gathered[p as usize];
        }
        Ok(())
    }

    /// Writes the owned entries of `src` (equation order) into `v`.
    fn write(&self, src: &[f64], v: ffi::Vec) -> Result<()> {
        super::write_owned(v, &self.owned, src)
    }
}

#[derive(Clone, Copy)]
enum Which {
    X,
    Scratch,
}

/// What the trampolines see: the layout, the step, and the first error raised
/// inside a callback (PETSc error or panic), reported after `SNESSolve`.
struct Ctx<'a, 'p> {
    layout: &'a mut Layout<'p>,
    problem: &'a mut dyn Problem,
    /// `layout.x` holds an iterate whose evaluation succeeded.
    evaluated: bool,
    error: Option<String>,
}

/// Runs a callback body; a returned error or a panic becomes PETSC_ERR_USER
/// with the message kept in the context.
fn guard(slot: *mut c_void, what: &str, body: impl FnOnce(&mut Ctx) -> Result<()>) -> i32 {
    // SAFETY: `slot` is the solver's boxed `Slot`, registered once and alive as
    // long as the SNES; during `SnesSolver::solve` it points at that call's `Ctx`
    // (on its frame), and it is null at any other time.
    let ctx = unsafe { (*(slot as *const Slot)).get() as *mut Ctx };
    if ctx.is_null() {
        return ffi::PETSC_ERR_USER as i32;
    }
    // SAFETY: see above; only one callback runs at a time.
    let ctx = unsafe { &mut *ctx };
    match catch_unwind(AssertUnwindSafe(|| body(ctx))) {
        Ok(Ok(())) => 0,
        Ok(Err(e)) => {
            ctx.error.get_or_insert(format!("SNES {what}: {e}"));
            ffi::PETSC_ERR_USER as i32
        }
        Err(panic) => {
            let msg = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            ctx.error
                .get_or_insert(format!("SNES {what}: internal error (panic): {msg}"));
            ffi::PETSC_ERR_USER as i32
        }
    }
}

unsafe extern "C" fn function_cb(
    snes: ffi::SNES,
    x: ffi::Vec,
    f: ffi::Vec,
    ctx: *mut c_void,
) -> ffi::PetscErrorCode {
    guard(ctx, "function", |c| {
        c.layout.gather(x, Which::X)?;
        let Layout { x: xv, r, .. } = &mut *c.layout;
        c.evaluated = c.problem.evaluate(xv, r);
        if !c.evaluated {
            // the message is the problem's; SNES stops with DIVERGED_FUNCTION_DOMAIN
            // SAFETY: valid SNES handle from PETSc.
            return chk(
                unsafe { ffi::SNESSetFunctionDomainError(snes) },
                "SNESSetFunctionDomainError",
            );
        }
        c.layout.write(&c.layout.r, f)
    })
}

unsafe extern "C" fn jacobian_cb(
    _snes: ffi::SNES,
    x: ffi::Vec,
    a: ffi::Mat,
    p: ffi::Mat,
    ctx: *mut c_void,
) -> ffi::PetscErrorCode {
    guard(ctx, "Jacobian", |c| {
        // the tangent was assembled with the residual at the same iterate; a
        // solver that asks elsewhere gets a fresh evaluation there
        c.layout.gather(x, Which::Scratch)?;
        if !c.evaluated || c.layout.scratch != c.layout.x {
            c.layout.x.copy_from_slice(&c.layout.scratch);
            let Layout { x: xv, r, .. } = &mut *c.layout;
            c.evaluated = c.problem.evaluate(xv, r);
            if !c.evaluated {
                return Err(Error::Solver(
                    "the tangent could not be evaluated at the requested iterate".into(),
                ));
            }
        }
        let both = [a, p];
        for &m in &both[..if a == p { 1 } else { 2 }] {
            // SAFETY: valid matrix handles from PETSc.
            unsafe {
                chk(
                    ffi::MatAssemblyBegin(m, ffi::MatAssemblyType_MAT_FINAL_ASSEMBLY),
                    "MatAssemblyBegin",
                )?;
                chk(
                    ffi::MatAssemblyEnd(m, ffi::MatAssemblyType_MAT_FINAL_ASSEMBLY),
                    "MatAssemblyEnd",
                )?;
            }
        }
        Ok(())
    })
}

unsafe extern "C" fn converged_cb(
    _snes: ffi::SNES,
    it: ffi::PetscInt,
    _xnorm: f64,
    _snorm: f64,
    _fnorm: f64,
    reason: *mut ffi::SNESConvergedReason,
    ctx: *mut c_void,
) -> ffi::PetscErrorCode {
    guard(ctx, "convergence test", |c| {
        let r = if !c.evaluated {
            ffi::SNESConvergedReason_SNES_DIVERGED_FUNCTION_DOMAIN
        } else {
            match c.problem.verdict(it as usize) {
                Verdict::Continue => ffi::SNESConvergedReason_SNES_CONVERGED_ITERATING,
                Verdict::Stop if c.problem.converged() => {
                    ffi::SNESConvergedReason_SNES_CONVERGED_ITS
                }
                Verdict::Stop => ffi::SNESConvergedReason_SNES_DIVERGED_DTOL,
            }
        };
        // SAFETY: PETSc passes a valid out-pointer.
        unsafe { *reason = r };
        Ok(())
    })
}

unsafe extern "C" fn postcheck_cb(
    ls: ffi::SNESLineSearch,
    x: ffi::Vec,
    y: ffi::Vec,
    w: ffi::Vec,
    changed_y: *mut ffi::PetscBool,
    changed_w: *mut ffi::PetscBool,
    ctx: *mut c_void,
) -> ffi::PetscErrorCode {
    guard(ctx, "line-search post-check", |c| {
        let mut lambda = 1.0;
        // SAFETY: valid line search; out-pointer.
        chk(
            unsafe { ffi::SNESLineSearchGetLambda(ls, &mut lambda) },
            "SNESLineSearchGetLambda",
        )?;
        // w = x − λ y; the problem sees the correction du = −λ y (exactly −y for a
        // full step, as the built-in loop computes it) and may change it
        c.layout.gather(y, Which::Scratch)?;
        let l = &mut *c.layout;
        for (d, s) in l.du.iter_mut().zip(&l.scratch) {
            *d = if lambda == 1.0 { -s } else { -lambda * s };
        }
        l.gather(x, Which::Scratch)?;
        let Layout { scratch, du, .. } = &mut *c.layout;
        c.problem.correct(scratch, du, lambda == 1.0);
        for (s, d) in scratch.iter_mut().zip(du.iter()) {
            *s += d;
        }
        c.layout.write(&c.layout.scratch, w)?;
        // SAFETY: PETSc passes valid out-pointers.
        unsafe {
            *changed_y = ffi::PetscBool_PETSC_FALSE;
            *changed_w = ffi::PetscBool_PETSC_TRUE;
        }
        Ok(())
    })
}

/// Where the callbacks find the current solve's [`Ctx`]: registered with PETSc
/// once (so that options such as `-snes_fd` that replace a callback stick) and
/// pointed at the context for the duration of each `SNESSolve`.
type Slot = std::cell::Cell<*mut c_void>;

/// A SNES bound to the backend's system matrix.
pub(crate) struct SnesSolver<'p> {
    raw: ffi::SNES,
    slot: Box<Slot>,
    x: PVec<'p>,
    f: PVec<'p>,
    layout: Layout<'p>,
    linear_iterations: usize,
    nonlinear_iterations: usize,
    /// `--memory lean` took effect (the preconditioner is GAMG); reported
    /// with the linear solver.
    lean_memory: bool,
}

/// PETSc's Newton iterations per preconditioner build within one load step
/// under [`lean_multigrid`] (SNES rebuilds at the first Jacobian of every
/// solve, and the lag does not persist across solves).
pub(crate) const MULTIGRID_LAG: ffi::PetscInt = 1000;

/// The Chebyshev smoothers' eigenvalue interval under [`lean_multigrid`]
/// (`-mg_levels_ksp_chebyshev_esteig a,b,c,d`: [b λ, d λ] for the estimate λ):
/// 1.5 λ at the top instead of PETSc's 1.1 λ, because the preconditioner
/// lags: within a load step the tangent drifts from the one whose largest
/// eigenvalue was estimated (plastic unloading, contact closing), and a
/// smoother whose interval ends below it amplifies those modes. With 1.1 (and
/// 1.25) CG met an indefinite preconditioner in the plastic steps of
/// `cases/punch-plane-stress-fine` at refine 4 and gave up at 99% of the load
/// at refine 8; with 1.5 the iterates follow MUMPS's.
pub(crate) const LEAN_ESTEIG: &std::ffi::CStr = c"0,0.1,0,1.5";

/// `--memory lean` with GAMG as the preconditioner: three settings, each of
/// which the options database can override (docs/performance.md, "GAMG,
/// `--memory lean`", has the measurements). The caller has checked that the
/// PC is GAMG.
/// * on more than one rank, Galerkin products by the all-at-once algorithm,
///   `-matptap_via allatonce`: PETSc's default parallel product keeps A·P and
///   explicit transposes of P for reuse (570 B per dof over two ranks at 1.05M
///   dofs); the all-at-once numeric product is slower (+4 s of 14 per Newton
///   iteration there when redone every iteration). (PETSc's sequential
///   product has no such variant.)
/// * which the preconditioner built once per load step pays for,
///   `-snes_lag_preconditioner` [`MULTIGRID_LAG`]: the Newton step still
///   solves the current tangent to the Krylov tolerance, only the
///   preconditioner lags;
/// * the Chebyshev smoothers' eigenvalue interval widened to cover the drift
///   of the tangent within the step ([`LEAN_ESTEIG`]), read only when the
///   command line chooses Chebyshev: asperity's Gauss-Seidel smoothers need
///   no eigenvalue and stay positive definite under a lagged preconditioner.
///
/// # Safety
/// `snes` must be a valid handle, after SNESSetFromOptions.
unsafe fn lean_multigrid(snes: ffi::SNES, ranks: usize) -> Result<()> {
    // SAFETY: valid handle (caller); NUL-terminated option names.
    unsafe {
        // read when GAMG sets up its levels' smoothers and per product
        default_option(c"-mg_levels_ksp_chebyshev_esteig", LEAN_ESTEIG)?;
        if ranks > 1 {
            default_option(c"-matptap_via", c"allatonce")?;
        }
        if !option_given(c"-snes_lag_preconditioner")? {
            chk(
                ffi::SNESSetLagPreconditioner(snes, MULTIGRID_LAG),
                "SNESSetLagPreconditioner",
            )?;
        }
        Ok(())
    }
}

impl<'p> SnesSolver<'p> {
    /// `mat`: the backend's system matrix (SNES takes a reference to it);
    /// `part`: the backend's partition; `rank`: this process. Crate-private: it
    /// takes a raw matrix handle, which safe code outside could not vouch for.
    #[allow(clippy::too_many_arguments)] // FFI-facing: the SNES set-up reads each one once
    pub(crate) fn new(
        petsc: &'p Petsc,
        mat: ffi::Mat,
        part: &Partition,
        rank: usize,
        ranks: usize,
        max_iterations: usize,
        linear: super::LinearDefault,
        lean: bool,
    ) -> Result<Self> {
        let n = part.petsc_index.len();
        let owned = part.owned(rank);
        let (local, global) = (part.local_len(rank), part.global_len());
        let x = PVec::new(petsc, local, global)?;
        let f = PVec::new(petsc, local, global)?;
        let to_all = ToAll::new(&x)?;
        let mut raw = std::ptr::null_mut();
        // SAFETY: out-pointers to fresh handles; the KSP and PC belong to the SNES.
        unsafe {
            chk(ffi::SNESCreate(petsc.comm(), &mut raw), "SNESCreate")?;
            let mut solver = SnesSolver {
                raw,
                slot: Box::new(Slot::new(std::ptr::null_mut())),
                x,
                f,
                layout: Layout {
                    to_all,
                    petsc_index: part.petsc_index.clone(),
                    owned,
                    gathered: vec![0.0; global],
                    x: vec![0.0; n],
                    r: vec![0.0; n],
                    scratch: vec![0.0; n],
                    du: vec![0.0; n],
                },
                linear_iterations: 0,
                nonlinear_iterations: 0,
                lean_memory: false,
            };
            chk(ffi::SNESSetType(raw, c"newtonls".as_ptr()), "SNESSetType")?;
            let mut ls = std::ptr::null_mut();
            chk(ffi::SNESGetLineSearch(raw, &mut ls), "SNESGetLineSearch")?;
            chk(
                ffi::SNESLineSearchSetType(ls, c"basic".as_ptr()),
                "SNESLineSearchSetType",
            )?;
            // our convergence test decides; PETSc's iteration and evaluation caps
            // sit above the case's limit
            let cap = (max_iterations + 10) as ffi::PetscInt;
            chk(
                ffi::SNESSetTolerances(raw, 0.0, 0.0, 0.0, cap, 1_000_000_000),
                "SNESSetTolerances",
            )?;
            let mut ksp = std::ptr::null_mut();
            chk(ffi::SNESGetKSP(raw, &mut ksp), "SNESGetKSP")?;
            super::linear_defaults(ksp, linear)?;
            let p = &*solver.slot as *const Slot as *mut c_void;
            chk(
                ffi::SNESSetFunction(raw, solver.f.raw, Some(function_cb), p),
                "SNESSetFunction",
            )?;
            chk(
                ffi::SNESSetJacobian(raw, mat, mat, Some(jacobian_cb), p),
                "SNESSetJacobian",
            )?;
            chk(ffi::SNESSetFromOptions(raw), "SNESSetFromOptions")?;
            let gamg = gamg_defaults(ksp)?;
            if lean && gamg {
                lean_multigrid(raw, ranks)?;
            }
            solver.lean_memory = lean && gamg;
            // after the options: the convergence test and the post-check belong
            // to the SNES and line search the options chose
            chk(
                ffi::SNESSetConvergenceTest(raw, Some(converged_cb), p, None),
                "SNESSetConvergenceTest",
            )?;
            let mut ls = std::ptr::null_mut();
            chk(ffi::SNESGetLineSearch(raw, &mut ls), "SNESGetLineSearch")?;
            chk(
                ffi::SNESLineSearchSetPostCheck(ls, Some(postcheck_cb), p),
                "SNESLineSearchSetPostCheck",
            )?;
            Ok(solver)
        }
    }
}

impl SnesSolver<'_> {
    /// The KSP that solves the Newton systems (owned by the SNES).
    pub fn ksp(&self) -> Result<ffi::KSP> {
        let mut ksp = std::ptr::null_mut();
        // SAFETY: valid SNES; out-pointer; the KSP belongs to it.
        chk(unsafe { ffi::SNESGetKSP(self.raw, &mut ksp) }, "SNESGetKSP")?;
        Ok(ksp)
    }
}

impl NonlinearSolver for SnesSolver<'_> {
    fn name(&self) -> &'static str {
        "snes"
    }

    fn solve(&mut self, problem: &mut dyn Problem) -> std::result::Result<(), StepFailure> {
        let start = problem.initial();
        let err = |e: Error| StepFailure::Solver(e.to_string());
        self.layout.write(&start, self.x.raw).map_err(err)?;
        let mut ctx = Ctx {
            layout: &mut self.layout,
            problem,
            evaluated: false,
            error: None,
        };
        let raw = self.raw;
        self.slot.set(&mut ctx as *mut Ctx as *mut c_void);
        // SAFETY: `ctx` lives on this frame for the whole SNESSolve call and is
        // reached only through the callbacks during it (the slot is cleared
        // after); the handles are valid.
        let solved = unsafe {
            (|| -> Result<ffi::SNESConvergedReason> {
                chk(
                    ffi::SNESSolve(raw, std::ptr::null_mut(), self.x.raw),
                    "SNESSolve",
                )?;
                let mut reason = 0;
                chk(
                    ffi::SNESGetConvergedReason(raw, &mut reason),
                    "SNESGetConvergedReason",
                )?;
                let (mut its, mut lits) = (0, 0);
                chk(
                    ffi::SNESGetIterationNumber(raw, &mut its),
                    "SNESGetIterationNumber",
                )?;
                chk(
                    ffi::SNESGetLinearSolveIterations(raw, &mut lits),
                    "SNESGetLinearSolveIterations",
                )?;
                self.nonlinear_iterations += its as usize;
                self.linear_iterations += lits as usize;
                Ok(reason)
            })()
        };
        self.slot.set(std::ptr::null_mut());
        if let Some(e) = ctx.error.take() {
            return Err(StepFailure::Solver(e));
        }
        let reason = solved.map_err(err)?;
        if reason > 0 && !ctx.problem.converged() {
            return Err(StepFailure::Solver(format!(
                "SNES stopped ({}) before the step's convergence rules were met",
                reason_name(reason)
            )));
        }
        if reason < 0 && !ctx.problem.stopped() {
            let mut ksp = std::ptr::null_mut();
            // SAFETY: valid SNES; the KSP belongs to it.
            let oom =
                unsafe { ffi::SNESGetKSP(self.raw, &mut ksp) == 0 && super::pc_out_of_memory(ksp) };
            if oom {
                return Err(StepFailure::Linear(super::out_of_memory_error()));
            }
            return Err(StepFailure::Solver(format!(
                "SNES diverged: {}",
                reason_name(reason)
            )));
        }
        Ok(())
    }

    fn linear_solver(&self) -> Option<String> {
        let mut ksp = std::ptr::null_mut();
        // SAFETY: valid SNES; the KSP belongs to it.
        unsafe {
            if ffi::SNESGetKSP(self.raw, &mut ksp) != 0 {
                return None;
            }
            let kind = super::describe(ksp);
            Some(if self.lean_memory {
                kind + " (memory lean)"
            } else {
                kind
            })
        }
    }

    fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("ksp_iterations", self.linear_iterations as f64),
            ("snes_iterations", self.nonlinear_iterations as f64),
        ]
    }
}

fn reason_name(r: ffi::SNESConvergedReason) -> String {
    let name = match r {
        ffi::SNESConvergedReason_SNES_CONVERGED_FNORM_ABS => "CONVERGED_FNORM_ABS",
        ffi::SNESConvergedReason_SNES_CONVERGED_FNORM_RELATIVE => "CONVERGED_FNORM_RELATIVE",
        ffi::SNESConvergedReason_SNES_CONVERGED_SNORM_RELATIVE => "CONVERGED_SNORM_RELATIVE",
        ffi::SNESConvergedReason_SNES_CONVERGED_ITS => "CONVERGED_ITS",
        ffi::SNESConvergedReason_SNES_DIVERGED_FUNCTION_DOMAIN => "DIVERGED_FUNCTION_DOMAIN",
        ffi::SNESConvergedReason_SNES_DIVERGED_FUNCTION_COUNT => "DIVERGED_FUNCTION_COUNT",
        ffi::SNESConvergedReason_SNES_DIVERGED_LINEAR_SOLVE => {
            "DIVERGED_LINEAR_SOLVE (the linear solver failed: singular tangent or KSP not converged)"
        }
        ffi::SNESConvergedReason_SNES_DIVERGED_FNORM_NAN => {
            "DIVERGED_FNORM_NAN (residual is not finite)"
        }
        ffi::SNESConvergedReason_SNES_DIVERGED_MAX_IT => "DIVERGED_MAX_IT",
        ffi::SNESConvergedReason_SNES_DIVERGED_LINE_SEARCH => "DIVERGED_LINE_SEARCH",
        ffi::SNESConvergedReason_SNES_DIVERGED_LOCAL_MIN => "DIVERGED_LOCAL_MIN",
        ffi::SNESConvergedReason_SNES_DIVERGED_DTOL => "DIVERGED_DTOL",
        _ => "",
    };
    format!("reason {r} {name}").trim_end().to_string()
}

impl Drop for SnesSolver<'_> {
    fn drop(&mut self) {
        // SAFETY: created by SNESCreate, destroyed once; it releases its
        // reference to the matrix, which the backend still owns.
        unsafe {
            ffi::SNESDestroy(&mut self.raw);
        }
    }
}
