//! A small safe layer over PETSc in the petsc-rs style: one RAII type per object
//! whose `Drop` destroys it, every return code turned into a `Result` at the call
//! site with `chk(…)?`, and start-up order enforced by borrowing: objects borrow
//! the [`Petsc`] guard, which borrows the MPI universe.
//!
//! The crate denies `unsafe` (`#![deny(unsafe_code)]` in lib.rs); this module
//! is allowed it, as are two documented system calls (the signal handler's
//! registration and the output folder's atomic swap).

mod condensed;
pub mod ffi;
mod owned;
pub mod snes;
pub mod solver;

use crate::error::{Error, Result};
use std::ffi::CString;
use std::marker::PhantomData;
use std::os::raw::{c_char, c_int};

/// Turns a PETSc error code into a `Result`, naming the call.
fn chk(code: ffi::PetscErrorCode, call: &str) -> Result<()> {
    if code == 0 {
        Ok(())
    } else {
        // PETSc's text for the code and the message of its last error
        let (mut text, mut specific): (*const c_char, *mut c_char) =
            (std::ptr::null(), std::ptr::null_mut());
        // SAFETY: out-pointers to strings PETSc owns (static or its buffer).
        let known = unsafe { ffi::PetscErrorMessage(code, &mut text, &mut specific) } == 0;
        let say = |p: *const c_char| {
            // SAFETY: null or a NUL-terminated string of PETSc's.
            (!p.is_null())
                .then(|| {
                    unsafe { std::ffi::CStr::from_ptr(p) }
                        .to_string_lossy()
                        .trim()
                        .to_string()
                })
                .filter(|t| !t.is_empty())
        };
        let why = match (known, say(text), say(specific)) {
            (true, Some(t), Some(s)) => format!(": {t}: {s}"),
            (true, Some(t), None) => format!(": {t}"),
            _ => String::new(),
        };
        Err(Error::Solver(format!(
            "PETSc {call} failed with error code {code}{why}"
        )))
    }
}

/// PETSc initialized on an already initialized MPI; finalized on drop (MPI stays up).
pub struct Petsc<'u> {
    _argv: Vec<CString>,
    comm: ffi::MPI_Comm,
    _universe: PhantomData<&'u mpi::environment::Universe>,
}

impl<'u> Petsc<'u> {
    /// `args` are PETSc options (e.g. "-ksp_type", "cg"); the program name is added.
    pub(crate) fn init(universe: &'u mpi::environment::Universe, args: &[String]) -> Result<Self> {
        use mpi::traits::AsRaw;
        let mut argv: Vec<CString> = std::iter::once("asperity".to_string())
            .chain(args.iter().cloned())
            .map(|a| {
                CString::new(a)
                    .map_err(|_| Error::input("PETSc options", "an option holds a NUL byte"))
            })
            .collect::<Result<_>>()?;
        let mut ptrs: Vec<*mut c_char> =
            argv.iter_mut().map(|a| a.as_ptr() as *mut c_char).collect();
        let mut argc = ptrs.len() as c_int;
        let mut p = ptrs.as_mut_ptr();
        // SAFETY: argv strings outlive PETSc (kept in `_argv`); MPI is initialized.
        chk(
            unsafe { ffi::PetscInitialize(&mut argc, &mut p, std::ptr::null(), std::ptr::null()) },
            "PetscInitialize",
        )?;
        // errors come back as codes and become one `error:` line; no tracebacks
        // SAFETY: PETSc is initialized; the handler is a PETSc function.
        chk(
            unsafe {
                ffi::PetscPushErrorHandler(Some(ffi::PetscReturnErrorHandler), std::ptr::null_mut())
            },
            "PetscPushErrorHandler",
        )?;
        Ok(Petsc {
            _argv: argv,
            comm: universe.world().as_raw(),
            _universe: PhantomData,
        })
    }

    pub(crate) fn comm(&self) -> ffi::MPI_Comm {
        self.comm
    }
}

impl Drop for Petsc<'_> {
    fn drop(&mut self) {
        // SAFETY: every PETSc object borrows self and has been dropped before.
        unsafe {
            ffi::PetscFinalize();
        }
    }
}

/// A distributed vector.
pub(crate) struct PVec<'p> {
    raw: ffi::Vec,
    _p: PhantomData<&'p Petsc<'p>>,
}

impl<'p> PVec<'p> {
    pub fn new(petsc: &'p Petsc, local: usize, global: usize) -> Result<Self> {
        let mut raw = std::ptr::null_mut();
        // SAFETY: out-pointer to a fresh handle.
        chk(
            unsafe {
                ffi::VecCreateMPI(
                    petsc.comm(),
                    local as ffi::PetscInt,
                    global as ffi::PetscInt,
                    &mut raw,
                )
            },
            "VecCreateMPI",
        )?;
        Ok(PVec {
            raw,
            _p: PhantomData,
        })
    }

    /// Writes the owned entries of `src` (equation order) into this vector:
    /// `owned` pairs each local position with its equation; the other local
    /// entries (prescribed dofs) become zero.
    pub(crate) fn write_owned(&mut self, owned: &[(usize, usize)], src: &[f64]) -> Result<()> {
        write_owned(self.raw, owned, src)
    }
}

/// [`PVec::write_owned`] for a vector handle PETSc passed to a callback.
pub(crate) fn write_owned(v: ffi::Vec, owned: &[(usize, usize)], src: &[f64]) -> Result<()> {
    let mut a: *mut f64 = std::ptr::null_mut();
    let mut n: ffi::PetscInt = 0;
    // SAFETY: v is a valid vector with `n` local entries, every position in
    // `owned` below n; the array is restored before return.
    unsafe {
        chk(ffi::VecGetLocalSize(v, &mut n), "VecGetLocalSize")?;
        chk(ffi::VecGetArray(v, &mut a), "VecGetArray")?;
        let local = std::slice::from_raw_parts_mut(a, n as usize);
        // prescribed dofs (not in `owned`) are zero
        local.fill(0.0);
        for &(k, e) in owned {
            local[k] = src[e];
        }
        chk(ffi::VecRestoreArray(v, &mut a), "VecRestoreArray")
    }
}

impl Drop for PVec<'_> {
    fn drop(&mut self) {
        // SAFETY: raw was created by VecCreate* and is destroyed once.
        unsafe {
            ffi::VecDestroy(&mut self.raw);
        }
    }
}

/// Gathers a distributed vector onto every rank (VecScatterCreateToAll).
pub(crate) struct ToAll<'p> {
    scatter: ffi::VecScatter,
    all: ffi::Vec,
    _p: PhantomData<&'p Petsc<'p>>,
}

impl<'p> ToAll<'p> {
    pub fn new(v: &PVec<'p>) -> Result<Self> {
        let (mut scatter, mut all) = (std::ptr::null_mut(), std::ptr::null_mut());
        // SAFETY: v.raw is valid; out-pointers.
        chk(
            unsafe { ffi::VecScatterCreateToAll(v.raw, &mut scatter, &mut all) },
            "VecScatterCreateToAll",
        )?;
        Ok(ToAll {
            scatter,
            all,
            _p: PhantomData,
        })
    }

    /// Copies the whole of `v` (in PETSc order) into `out`.
    pub(crate) fn gather(&mut self, v: &PVec<'p>, out: &mut [f64]) -> Result<()> {
        self.gather_raw(v.raw, out)
    }

    /// As [`ToAll::gather`], for a vector handle PETSc passed to a callback
    /// (same layout as the vector the scatter was made for). Crate-private: it
    /// takes a raw handle, which safe code outside could not vouch for.
    pub(crate) fn gather_raw(&mut self, v: ffi::Vec, out: &mut [f64]) -> Result<()> {
        // SAFETY: scatter created for v's layout; the array is restored before return.
        unsafe {
            chk(
                ffi::VecScatterBegin(
                    self.scatter,
                    v,
                    self.all,
                    ffi::InsertMode_INSERT_VALUES,
                    ffi::ScatterMode_SCATTER_FORWARD,
                ),
                "VecScatterBegin",
            )?;
            chk(
                ffi::VecScatterEnd(
                    self.scatter,
                    v,
                    self.all,
                    ffi::InsertMode_INSERT_VALUES,
                    ffi::ScatterMode_SCATTER_FORWARD,
                ),
                "VecScatterEnd",
            )?;
            let mut a: *const f64 = std::ptr::null();
            chk(ffi::VecGetArrayRead(self.all, &mut a), "VecGetArrayRead")?;
            out.copy_from_slice(std::slice::from_raw_parts(a, out.len()));
            chk(
                ffi::VecRestoreArrayRead(self.all, &mut a),
                "VecRestoreArrayRead",
            )
        }
    }
}

impl Drop for ToAll<'_> {
    fn drop(&mut self) {
        // SAFETY: created by VecScatterCreateToAll, destroyed once.
        unsafe {
            ffi::VecScatterDestroy(&mut self.scatter);
            ffi::VecDestroy(&mut self.all);
        }
    }
}

/// A distributed AIJ matrix with exact preallocation; a new nonzero is an error.
pub(crate) struct PMat<'p> {
    pub raw: ffi::Mat,
    _p: PhantomData<&'p Petsc<'p>>,
}

impl<'p> PMat<'p> {
    /// `local` of `global` rows on this rank, block size `bs` (dofs per node,
    /// for multigrid), `d_nnz`/`o_nnz` nonzeros per owned row in the diagonal
    /// and off-diagonal blocks.
    pub(crate) fn aij(
        petsc: &'p Petsc,
        local: usize,
        global: usize,
        bs: usize,
        d_nnz: &[ffi::PetscInt],
        o_nnz: &[ffi::PetscInt],
    ) -> Result<Self> {
        let mut raw = std::ptr::null_mut();
        let (l, g) = (local as ffi::PetscInt, global as ffi::PetscInt);
        // SAFETY: out-pointer to a fresh handle (kept in `mat` at once, so an
        // early return destroys it); nnz arrays have `local` entries.
        unsafe {
            chk(ffi::MatCreate(petsc.comm(), &mut raw), "MatCreate")?;
            let mat = PMat {
                raw,
                _p: PhantomData,
            };
            chk(ffi::MatSetSizes(raw, l, l, g, g), "MatSetSizes")?;
            chk(
                ffi::MatSetBlockSize(raw, bs as ffi::PetscInt),
                "MatSetBlockSize",
            )?;
            chk(ffi::MatSetType(raw, c"aij".as_ptr()), "MatSetType")?;
            chk(
                ffi::MatSeqAIJSetPreallocation(raw, 0, d_nnz.as_ptr()),
                "MatSeqAIJSetPreallocation",
            )?;
            chk(
                ffi::MatMPIAIJSetPreallocation(raw, 0, d_nnz.as_ptr(), 0, o_nnz.as_ptr()),
                "MatMPIAIJSetPreallocation",
            )?;
            chk(
                ffi::MatSetOption(
                    raw,
                    ffi::MatOption_MAT_NEW_NONZERO_ALLOCATION_ERR,
                    ffi::PetscBool_PETSC_TRUE,
                ),
                "MatSetOption",
            )?;
            Ok(mat)
        }
    }

    /// Declares the matrix symmetric for good (every assembly keeps it so):
    /// MUMPS's Cholesky then reads one triangle, GAMG and CG may rely on it.
    pub(crate) fn set_symmetric(&mut self) -> Result<()> {
        for option in [
            ffi::MatOption_MAT_SYMMETRIC,
            ffi::MatOption_MAT_SYMMETRY_ETERNAL,
        ] {
            // SAFETY: valid matrix handle.
            chk(
                unsafe { ffi::MatSetOption(self.raw, option, ffi::PetscBool_PETSC_TRUE) },
                "MatSetOption",
            )?;
        }
        Ok(())
    }

    /// Attaches a near-null space (e.g. rigid-body modes) for algebraic multigrid:
    /// `local[k]` is this rank's owned part of vector k, which must be orthonormal
    /// over all ranks. The matrix keeps its own reference; ours are released.
    pub(crate) fn set_near_null_space(
        &mut self,
        petsc: &'p Petsc,
        local: &[Vec<f64>],
    ) -> Result<()> {
        let n_local = local.first().map_or(0, |v| v.len());
        let mut vecs = Vec::with_capacity(local.len());
        for part in local {
            let mut v = std::ptr::null_mut();
            // SAFETY: out-pointer to a fresh vector with `n_local` owned entries,
            // filled through its array and restored before use.
            unsafe {
                chk(
                    ffi::VecCreateMPI(
                        petsc.comm(),
                        n_local as ffi::PetscInt,
                        ffi::PETSC_DETERMINE as ffi::PetscInt,
                        &mut v,
                    ),
                    "VecCreateMPI",
                )?;
                vecs.push(v);
                let mut a: *mut f64 = std::ptr::null_mut();
                chk(ffi::VecGetArray(v, &mut a), "VecGetArray")?;
                std::slice::from_raw_parts_mut(a, n_local).copy_from_slice(part);
                chk(ffi::VecRestoreArray(v, &mut a), "VecRestoreArray")?;
            }
        }
        let mut nsp = std::ptr::null_mut();
        // SAFETY: `vecs` holds valid vectors; the null space references them, the
        // matrix references the null space, so destroying ours afterwards is safe.
        let result = unsafe {
            chk(
                ffi::MatNullSpaceCreate(
                    petsc.comm(),
                    ffi::PetscBool_PETSC_FALSE,
                    vecs.len() as ffi::PetscInt,
                    vecs.as_ptr(),
                    &mut nsp,
                ),
                "MatNullSpaceCreate",
            )
            .and_then(|_| {
                chk(
                    ffi::MatSetNearNullSpace(self.raw, nsp),
                    "MatSetNearNullSpace",
                )
            })
        };
        // SAFETY: each handle is destroyed once (null handles are ignored).
        unsafe {
            if !nsp.is_null() {
                ffi::MatNullSpaceDestroy(&mut nsp);
            }
            for mut v in vecs {
                ffi::VecDestroy(&mut v);
            }
        }
        result
    }

    pub fn zero(&mut self) -> Result<()> {
        // SAFETY: valid matrix.
        chk(unsafe { ffi::MatZeroEntries(self.raw) }, "MatZeroEntries")
    }

    /// Adds a dense row-major block; negative indices (prescribed dofs) are skipped by PETSc.
    pub fn add(&mut self, idx: &[ffi::PetscInt], vals: &[f64]) -> Result<()> {
        let n = idx.len() as ffi::PetscInt;
        // SAFETY: vals has n·n entries.
        chk(
            unsafe {
                ffi::MatSetValues(
                    self.raw,
                    n,
                    idx.as_ptr(),
                    n,
                    idx.as_ptr(),
                    vals.as_ptr(),
                    ffi::InsertMode_ADD_VALUES,
                )
            },
            "MatSetValues",
        )
    }

    /// Inserts one row (global indices).
    pub(crate) fn set_row(
        &mut self,
        row: ffi::PetscInt,
        cols: &[ffi::PetscInt],
        vals: &[f64],
    ) -> Result<()> {
        // SAFETY: cols and vals have the same length.
        chk(
            unsafe {
                ffi::MatSetValues(
                    self.raw,
                    1,
                    &row,
                    cols.len() as ffi::PetscInt,
                    cols.as_ptr(),
                    vals.as_ptr(),
                    ffi::InsertMode_INSERT_VALUES,
                )
            },
            "MatSetValues",
        )
    }

    pub fn assemble(&mut self) -> Result<()> {
        // SAFETY: valid matrix.
        unsafe {
            chk(
                ffi::MatAssemblyBegin(self.raw, ffi::MatAssemblyType_MAT_FINAL_ASSEMBLY),
                "MatAssemblyBegin",
            )?;
            chk(
                ffi::MatAssemblyEnd(self.raw, ffi::MatAssemblyType_MAT_FINAL_ASSEMBLY),
                "MatAssemblyEnd",
            )
        }
    }

    /// self ← other (same nonzero pattern).
    pub(crate) fn copy_from(&mut self, other: &PMat<'p>) -> Result<()> {
        // SAFETY: both valid, same layout and pattern.
        chk(
            unsafe { ffi::MatCopy(other.raw, self.raw, ffi::MatStructure_SAME_NONZERO_PATTERN) },
            "MatCopy",
        )
    }

    /// Mallocs PETSc needed during assembly (0 with exact preallocation).
    pub fn mallocs(&self) -> Result<f64> {
        let mut info = ffi::MatInfo::default();
        // SAFETY: out-pointer.
        chk(
            unsafe { ffi::MatGetInfo(self.raw, ffi::MatInfoType_MAT_GLOBAL_SUM, &mut info) },
            "MatGetInfo",
        )?;
        Ok(info.mallocs)
    }
}

impl Drop for PMat<'_> {
    fn drop(&mut self) {
        // SAFETY: destroyed once.
        unsafe {
            ffi::MatDestroy(&mut self.raw);
        }
    }
}

/// A Krylov solver configured from the options database.
pub(crate) struct Ksp<'p> {
    raw: ffi::KSP,
    _p: PhantomData<&'p Petsc<'p>>,
}

/// GAMG's default `-pc_gamg_threshold`: graph couplings weaker than 0.01 of
/// the geometric mean of their two diagonal entries are left out of the
/// aggregation graph. That cuts the soft rough-interface springs, so no
/// aggregate spans the interface and the three rigid-body modes of the
/// assembly ([`solver::Partition::rigid_body_modes`]), restricted to an
/// aggregate, are the rigid motions of the body it lies in. At 209k dofs on
/// two ranks (fast GAMG) this took CG from 134 to 86-121 iterations per solve
/// and the operator complexity from 1.44 (per-body modes, threshold 0) to
/// 1.15 (docs/performance.md, "GAMG settings").
pub const GAMG_THRESHOLD: f64 = 0.01;

/// The linear solver a KSP starts from, before the options database (any
/// `-ksp_*`/`-pc_*` option on the command line overrides it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LinearDefault {
    /// Sparse direct factorization by MUMPS, one application (`preonly`):
    /// Cholesky (MUMPS's symmetric LDLᵀ with pivoting, so an indefinite
    /// tangent near collapse is still factored) when the model states a
    /// symmetric tangent ([`crate::model::Model::symmetric_tangent`]), LU
    /// otherwise (docs/performance.md, "MUMPS Cholesky").
    Direct { symmetric: bool },
    /// Smoothed-aggregation multigrid (GAMG, with the rigid-body near-null
    /// space and [`GAMG_THRESHOLD`]) inside CG when the tangent is symmetric (no
    /// tangential interface law), GMRES otherwise; relative tolerance 1e-10
    /// so that the Newton iterates match a direct solve to round-off.
    Multigrid { symmetric: bool },
}

impl LinearDefault {
    /// Plane and axisymmetric systems of at least this many rows (all dofs)
    /// get multigrid: below it MUMPS is faster on this machine, above it GAMG
    /// is faster and needs less than half the memory (docs/performance.md,
    /// "MUMPS LU").
    pub const MULTIGRID_FROM: usize = 400_000;

    /// 3D systems of at least this many rows get multigrid
    /// ([`super::DIRECT_3D_UP_TO`]).
    pub const MULTIGRID_FROM_3D: usize = super::DIRECT_3D_UP_TO;

    pub fn for_model(model: &crate::model::Model) -> Self {
        let symmetric = model.symmetric_tangent();
        let from = match model.mesh.dim() {
            3 => Self::MULTIGRID_FROM_3D,
            _ => Self::MULTIGRID_FROM,
        };
        if model.mesh.num_dofs() >= from {
            LinearDefault::Multigrid { symmetric }
        } else {
            LinearDefault::Direct { symmetric }
        }
    }
}

/// Applies a [`LinearDefault`] to a KSP (before KSPSetFromOptions).
///
/// # Safety
/// `ksp` must be a valid KSP handle.
unsafe fn linear_defaults(ksp: ffi::KSP, choice: LinearDefault) -> Result<()> {
    // SAFETY: valid KSP (caller); the PC handle is owned by the KSP.
    unsafe {
        let mut pc = std::ptr::null_mut();
        chk(ffi::KSPGetPC(ksp, &mut pc), "KSPGetPC")?;
        match choice {
            LinearDefault::Direct { symmetric } => {
                let t = if symmetric { c"cholesky" } else { c"lu" };
                chk(ffi::KSPSetType(ksp, c"preonly".as_ptr()), "KSPSetType")?;
                chk(ffi::PCSetType(pc, t.as_ptr()), "PCSetType")?;
                chk(
                    ffi::PCFactorSetMatSolverType(pc, c"mumps".as_ptr()),
                    "PCFactorSetMatSolverType",
                )
            }
            LinearDefault::Multigrid { symmetric } => {
                let t = if symmetric { c"cg" } else { c"gmres" };
                chk(ffi::KSPSetType(ksp, t.as_ptr()), "KSPSetType")?;
                chk(ffi::PCSetType(pc, c"gamg".as_ptr()), "PCSetType")?;
                chk(
                    ffi::KSPSetTolerances(
                        ksp,
                        1e-10,
                        ffi::PETSC_DEFAULT as f64,
                        ffi::PETSC_DEFAULT as f64,
                        2000,
                    ),
                    "KSPSetTolerances",
                )
            }
        }
    }
}

/// Whether `name` (e.g. `c"-pc_gamg_use_sa_esteig"`) was given in the options
/// database (the command line after `--`).
fn option_given(name: &std::ffi::CStr) -> Result<bool> {
    let mut has = ffi::PetscBool_PETSC_FALSE;
    // SAFETY: NUL-terminated name; out-pointer.
    chk(
        unsafe {
            ffi::PetscOptionsHasName(
                std::ptr::null_mut(),
                std::ptr::null(),
                name.as_ptr(),
                &mut has,
            )
        },
        "PetscOptionsHasName",
    )?;
    Ok(has == ffi::PetscBool_PETSC_TRUE)
}

/// Puts `name value` into the options database unless the command line gave
/// `name`: a default for an option that PETSc reads only when it sets up.
fn default_option(name: &std::ffi::CStr, value: &std::ffi::CStr) -> Result<()> {
    if !option_given(name)? {
        // SAFETY: NUL-terminated strings; PETSc copies them.
        chk(
            unsafe {
                ffi::PetscOptionsSetValue(std::ptr::null_mut(), name.as_ptr(), value.as_ptr())
            },
            "PetscOptionsSetValue",
        )?;
    }
    Ok(())
}

/// Whether a PETSc type name (from `KSPGetType`, `PCGetType`; null when unset)
/// is `name`.
///
/// # Safety
/// `p` is null or a NUL-terminated string.
unsafe fn type_is(p: *const std::os::raw::c_char, name: &[u8]) -> bool {
    // SAFETY: checked non-null; NUL-terminated (caller).
    !p.is_null() && unsafe { std::ffi::CStr::from_ptr(p) }.to_bytes() == name
}

/// asperity's default for GAMG, whichever way GAMG was chosen (the size
/// default or `-pc_type gamg`), unless the command line sets it: the levels
/// smooth by Gauss-Seidel ([`gauss_seidel_smoothers`]), under CG one
/// symmetric sweep, under GMRES two ([`unsymmetric_smoothers`]).
/// When the command line chooses PETSc's Chebyshev smoothers instead, they
/// estimate their own eigenvalue bounds
/// (`-pc_gamg_use_sa_esteig false`) instead of reusing the estimate made while
/// smoothing the prolongators. With the reused estimate, CG + GAMG met an
/// indefinite preconditioner (`DIVERGED_INDEFINITE_PC`) in the plastic steps of
/// `cases/punch-plane-stress-fine` (twice at refine 4, a run given up after 8
/// cutbacks at 99% of the load at refine 8) where MUMPS converged; with the
/// smoothers' own estimates the iterates follow MUMPS's (docs/performance.md,
/// "GAMG settings").
/// When the outer Krylov method is CG (the tangent is symmetric), those
/// estimates are made by CG too (`-mg_levels_esteig_ksp_type cg`) instead of
/// PETSc's GMRES, whose basis vectors every level's estimator keeps after
/// setup: at 209k dofs on two ranks the peak fell from 544 to 519 MB with the
/// same Krylov iterations and time (docs/performance.md, "GAMG settings").
/// And the aggregation graph drops couplings weaker than [`GAMG_THRESHOLD`]
/// (`-pc_gamg_threshold`).
/// Returns whether the preconditioner is GAMG.
///
/// # Safety
/// `ksp` must be a valid KSP handle, after KSPSetFromOptions.
unsafe fn gamg_defaults(ksp: ffi::KSP) -> Result<bool> {
    // SAFETY: valid KSP (caller); the PC and its type string belong to PETSc.
    unsafe {
        let mut pc = std::ptr::null_mut();
        chk(ffi::KSPGetPC(ksp, &mut pc), "KSPGetPC")?;
        let mut pt = std::ptr::null();
        chk(ffi::PCGetType(pc, &mut pt), "PCGetType")?;
        if !type_is(pt, b"gamg") {
            return Ok(false);
        }
        if !option_given(c"-pc_gamg_use_sa_esteig")? {
            chk(
                ffi::PCGAMGSetUseSAEstEig(pc, ffi::PetscBool_PETSC_FALSE),
                "PCGAMGSetUseSAEstEig",
            )?;
        }
        let mut kt = std::ptr::null();
        chk(ffi::KSPGetType(ksp, &mut kt), "KSPGetType")?;
        if type_is(kt, b"cg") {
            default_option(c"-mg_levels_esteig_ksp_type", c"cg")?;
            gauss_seidel_smoothers(Some(c"1"))?;
        }
        if type_is(kt, b"gmres") {
            unsymmetric_smoothers(ksp)?;
        }
        if !option_given(c"-pc_gamg_threshold")? {
            let mut th = [GAMG_THRESHOLD];
            chk(
                ffi::PCGAMGSetThreshold(pc, th.as_mut_ptr(), 1),
                "PCGAMGSetThreshold",
            )?;
        }
        Ok(true)
    }
}

/// The smoothers of GAMG, unless the command line names the levels' KSP or
/// PC type (then they are its own, e.g. PETSc's Chebyshev with Jacobi):
/// symmetric Gauss-Seidel, each rank's rows swept forward and back
/// (`-mg_levels_ksp_type richardson -mg_levels_pc_type sor`), `sweeps` times
/// per smoothing (`-mg_levels_ksp_max_it`; `None`: PETSc's two). GAMG's
/// coarse operators may have zero rows (an aggregate of fewer dofs than
/// near-null modes gives P a zero column); Gauss-Seidel divides by the
/// diagonal, so it is shifted by [`SOR_DIAGONAL_SHIFT`]: no change to any
/// nonzero diagonal, and a zero row's unknown stays zero (its right-hand side
/// is zero too). The V-cycle is symmetric positive definite for a symmetric
/// positive definite tangent, also when it lags (`--memory lean`), and needs
/// no eigenvalue estimate.
/// Under CG one sweep ([`gamg_defaults`]), measured against PETSc's Chebyshev
/// (docs/performance.md, "GAMG settings"): the 3D block at 395k dofs on two
/// ranks 40-75 CG iterations a solve against 63-120, 25.2 against 41.0 s a
/// Newton iteration; the plastic fine punch at 93.5k dofs 2,830 against 4,033
/// CG iterations, 32 against 62 s of solves, 102 against 105 Newton
/// iterations (MUMPS 96), the same answer. Under GMRES two
/// ([`unsymmetric_smoothers`]).
fn gauss_seidel_smoothers(sweeps: Option<&std::ffi::CStr>) -> Result<()> {
    if option_given(c"-mg_levels_ksp_type")? || option_given(c"-mg_levels_pc_type")? {
        return Ok(());
    }
    default_option(c"-mg_levels_ksp_type", c"richardson")?;
    default_option(c"-mg_levels_pc_type", c"sor")?;
    if let Some(n) = sweeps {
        default_option(c"-mg_levels_ksp_max_it", n)?;
    }
    default_option(c"-mg_levels_pc_sor_diagonal_shift", SOR_DIAGONAL_SHIFT)
}

/// GMRES's restart under GAMG unless `-ksp_gmres_restart` is given: the
/// flange sector (issue 47's benchmark) needs 70-80 iterations a solve at
/// 29k dofs, past PETSc's 30, where a restart loses what the basis held.
pub(crate) const GMRES_RESTART: i32 = 150;

/// GAMG under GMRES (an unsymmetric tangent: friction): two Gauss-Seidel
/// sweeps per smoothing ([`gauss_seidel_smoothers`]) instead of PETSc's
/// Chebyshev, whose polynomial is fitted to an interval of the real axis that
/// an unsymmetric operator's spectrum does not keep to (forward sweeps before
/// the coarse correction and backward after it, half the work, were faster
/// up to 90k dofs and slower at 387k: the log of docs/performance.md); and
/// GMRES restarts after [`GMRES_RESTART`] iterations.
/// Measured (docs/performance.md, "3D: the flange sector"): GMRES + GAMG
/// iterations per solve 130-230 → 68-81 on the flange sector at 29k dofs
/// (solve time 55 → 27 s, 2 ranks), 36 → 20 on the plane punch with friction
/// at 94k.
///
/// # Safety
/// `ksp` must be a valid KSP handle whose PC is GAMG, after KSPSetFromOptions.
unsafe fn unsymmetric_smoothers(ksp: ffi::KSP) -> Result<()> {
    gauss_seidel_smoothers(None)?;
    if !option_given(c"-ksp_gmres_restart")? {
        // SAFETY: valid KSP of type GMRES (caller).
        chk(
            unsafe { ffi::KSPGMRESSetRestart(ksp, GMRES_RESTART) },
            "KSPGMRESSetRestart",
        )?;
    }
    Ok(())
}

/// The shift of the Gauss-Seidel smoothers' diagonal ([`gauss_seidel_smoothers`]):
/// far below any stiffness (N/mm) a model can have, so only a zero diagonal
/// feels it.
const SOR_DIAGONAL_SHIFT: &std::ffi::CStr = c"1e-100";

/// Whether the KSP's preconditioner failed for want of memory: a direct
/// factorization (MUMPS) that could not allocate its factor or work arrays
/// (`PC_FACTOR_OUTMEMORY`, from MUMPS's INFOG(1) = −8, −9, −11…−15). A smaller
/// load step would need the same factor, so the run ends instead of cutting
/// back.
///
/// # Safety
/// `ksp` must be a valid KSP handle.
pub(crate) unsafe fn pc_out_of_memory(ksp: ffi::KSP) -> bool {
    // SAFETY: valid KSP (caller); out-pointers; the PC belongs to the KSP.
    unsafe {
        let mut pc = std::ptr::null_mut();
        let mut reason: ffi::PCFailedReason = 0;
        ffi::KSPGetPC(ksp, &mut pc) == 0
            && ffi::PCGetFailedReason(pc, &mut reason) == 0
            && reason == ffi::PCFailedReason_PC_FACTOR_OUTMEMORY
    }
}

/// The message of a factorization that ran out of memory under PETSc.
pub(crate) fn out_of_memory_error() -> Error {
    Error::Memory(
        "the direct factorization (MUMPS) could not allocate its factor: the model is too large for the memory of these ranks (more ranks, or -pc_type gamg)"
            .into(),
    )
}

/// "ksp type + pc type" of a configured KSP, e.g. "preonly + lu (mumps)", "cg + gamg".
///
/// # Safety
/// `ksp` must be a valid KSP handle.
unsafe fn describe(ksp: ffi::KSP) -> String {
    let text = |p: *const std::os::raw::c_char| {
        if p.is_null() {
            "?".to_string()
        } else {
            // SAFETY: PETSc type names are NUL-terminated static strings.
            unsafe { std::ffi::CStr::from_ptr(p) }
                .to_string_lossy()
                .into_owned()
        }
    };
    // SAFETY: valid KSP (caller); out-pointers; strings owned by PETSc.
    unsafe {
        let (mut kt, mut pt) = (std::ptr::null(), std::ptr::null());
        let mut pc = std::ptr::null_mut();
        if ffi::KSPGetType(ksp, &mut kt) != 0 || ffi::KSPGetPC(ksp, &mut pc) != 0 {
            return "?".into();
        }
        if ffi::PCGetType(pc, &mut pt) != 0 {
            return text(kt);
        }
        let mut out = format!("{} + {}", text(kt), text(pt));
        let mut st = std::ptr::null();
        if matches!(text(pt).as_str(), "lu" | "cholesky")
            && ffi::PCFactorGetMatSolverType(pc, &mut st) == 0
            && !st.is_null()
        {
            out += &format!(" ({})", text(st));
        }
        out
    }
}

impl<'p> Ksp<'p> {
    /// Starts from `choice`; `-ksp_type`, `-pc_type` … override it.
    pub fn new(petsc: &'p Petsc, choice: LinearDefault) -> Result<Self> {
        let mut raw = std::ptr::null_mut();
        // SAFETY: out-pointer; PC handle owned by the KSP.
        unsafe {
            chk(ffi::KSPCreate(petsc.comm(), &mut raw), "KSPCreate")?;
            linear_defaults(raw, choice)?;
            chk(ffi::KSPSetFromOptions(raw), "KSPSetFromOptions")?;
            gamg_defaults(raw)?;
        }
        Ok(Ksp {
            raw,
            _p: PhantomData,
        })
    }

    /// The configured solver, e.g. "preonly + lu (mumps)".
    pub(crate) fn describe(&self) -> String {
        // SAFETY: valid KSP.
        unsafe { describe(self.raw) }
    }

    /// Solves A x = b; errors if the solve diverged.
    pub fn solve(&mut self, a: &PMat<'p>, b: &PVec<'p>, x: &mut PVec<'p>) -> Result<usize> {
        // SAFETY: valid handles with matching layouts.
        unsafe {
            chk(
                ffi::KSPSetOperators(self.raw, a.raw, a.raw),
                "KSPSetOperators",
            )?;
            chk(ffi::KSPSolve(self.raw, b.raw, x.raw), "KSPSolve")?;
            let mut reason = 0;
            chk(
                ffi::KSPGetConvergedReason(self.raw, &mut reason),
                "KSPGetConvergedReason",
            )?;
            let mut its = 0;
            chk(
                ffi::KSPGetIterationNumber(self.raw, &mut its),
                "KSPGetIterationNumber",
            )?;
            if reason < 0 {
                if pc_out_of_memory(self.raw) {
                    return Err(out_of_memory_error());
                }
                return Err(Error::Solver(format!(
                    "KSP diverged (reason {reason}) after {its} iterations"
                )));
            }
            Ok(its as usize)
        }
    }
}

impl Drop for Ksp<'_> {
    fn drop(&mut self) {
        // SAFETY: destroyed once.
        unsafe {
            ffi::KSPDestroy(&mut self.raw);
        }
    }
}
