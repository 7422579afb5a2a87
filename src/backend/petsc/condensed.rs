//! The interface loop's condensation on the PETSc backend
//! ([`crate::backend::Condensed`]; `solve::newton::interface_loop`).
//!
//! The serial backend reads the Schur complement of its factor on the
//! interface equations I off the trailing block of a Cholesky factor with I
//! ordered last. PETSc 3.18 offers MUMPS's own Schur complement on one rank
//! only ("parallel Schur complements not yet supported"), so here it comes
//! from the inverse: with M the factored matrix and E_I the columns of the
//! identity on I,
//!
//! ```text
//!   Z = E_Iᵀ M⁻¹ E_I = (M⁻¹)_II = (M_II − M_IB M_BB⁻¹ M_BI)⁻¹ = S⁻¹,
//! ```
//!
//! m right-hand sides in one `MatMatSolve` with the factor (MUMPS solves them
//! as a block), the rows on I gathered onto every rank, and S = Z⁻¹ by a dense
//! LU, identically on every rank. The lift `x += M⁻¹ [0; e]` is one
//! `MatSolve`. The factor is the one of the KSP that solved the Newton
//! system: SNES's where SNES drives the step ([`PetscBackend::factor_of`]),
//! else the backend's own. Only a factorization (`-pc_type cholesky|lu`)
//! has one: with an iterative solver (GAMG, above
//! [`super::LinearDefault::MULTIGRID_FROM`] rows, or chosen on the command
//! line) the loop does not run and the plain Newton correction stands.
//!
//! Which models run the loop is the serial backend's rule
//! ([`crate::backend::serial::plans_interface_loop`]), so that a model runs it
//! on both backends or on neither: then serial and PETSc runs take the same
//! iterates to round-off.

use super::solver::PetscBackend;
use super::{chk, ffi, type_is};
use crate::error::Result;
use mpi::collective::SystemOperation;
use mpi::traits::*;

/// A dense PETSc matrix, destroyed on drop.
struct Dense(ffi::Mat);

impl Drop for Dense {
    fn drop(&mut self) {
        // SAFETY: created by MatCreateDense, destroyed once.
        unsafe {
            ffi::MatDestroy(&mut self.0);
        }
    }
}

impl PetscBackend<'_> {
    /// The factored matrix of the KSP that solves the Newton system, where
    /// its preconditioner is a factorization.
    fn factor(&self) -> Option<ffi::Mat> {
        let ksp = self.factor_ksp.as_ref().map_or(self.ksp.raw, |k| k.0);
        let (mut pc, mut kind, mut f) =
            (std::ptr::null_mut(), std::ptr::null(), std::ptr::null_mut());
        // SAFETY: valid KSP (the backend's, or SNES's held by a reference);
        // out-pointers; the PC, its type string and the factor belong to PETSc.
        unsafe {
            if ffi::KSPGetPC(ksp, &mut pc) != 0 || ffi::PCGetType(pc, &mut kind) != 0 {
                return None;
            }
            if !(type_is(kind, b"cholesky") || type_is(kind, b"lu")) {
                return None;
            }
            if ffi::PCFactorGetMatrix(pc, &mut f) != 0 || f.is_null() {
                return None;
            }
        }
        Some(f)
    }

    /// The backend offers the interface loop its condensation: the model is
    /// one the serial backend condenses, and the Newton system is factored.
    pub(super) fn condensation(&mut self) -> Option<&mut dyn crate::backend::Condensed> {
        if self.loop_equations.is_empty() {
            return None;
        }
        let factored = self.factor().is_some();
        // a rank without a factor would leave the others in a collective
        self.agree_all(factored).then_some(self)
    }

    /// Whether `flag` holds on every rank.
    fn agree_all(&self, flag: bool) -> bool {
        let mut all = 0;
        self.world
            .all_reduce_into(&i32::from(flag), &mut all, SystemOperation::min());
        all == 1
    }

    /// Z = (M⁻¹)_II on every rank (dense, column-major m × m).
    fn inverse_block(&mut self, f: ffi::Mat) -> Result<Vec<f64>> {
        let m = self.loop_equations.len();
        let local = self.part.local_len(self.rank);
        let global = self.part.global_len();
        // the owned interface equations: (local row, position in I)
        let mut rows = Vec::new();
        for &(pos, e) in &self.owned {
            if let Ok(k) = self.loop_equations.binary_search(&e) {
                rows.push((pos, k));
            }
        }
        let comm = self.petsc.comm();
        let dense = |what: &str| -> Result<Dense> {
            let mut raw = std::ptr::null_mut();
            // SAFETY: out-pointer; PETSc allocates the storage.
            chk(
                unsafe {
                    ffi::MatCreateDense(
                        comm,
                        local as ffi::PetscInt,
                        ffi::PETSC_DECIDE,
                        global as ffi::PetscInt,
                        m as ffi::PetscInt,
                        std::ptr::null_mut(),
                        &mut raw,
                    )
                },
                what,
            )?;
            Ok(Dense(raw))
        };
        let (b, x) = (dense("MatCreateDense (B)")?, dense("MatCreateDense (X)")?);
        let mut z = vec![0.0; m * m];
        // SAFETY: valid dense matrices of `local` rows and m columns with
        // leading dimension `lda` ≥ local; arrays restored before use of the
        // matrices; the factor is valid (from the KSP's PC).
        unsafe {
            let mut lda: ffi::PetscInt = 0;
            chk(ffi::MatDenseGetLDA(b.0, &mut lda), "MatDenseGetLDA")?;
            let mut a: *mut f64 = std::ptr::null_mut();
            chk(
                ffi::MatDenseGetArrayWrite(b.0, &mut a),
                "MatDenseGetArrayWrite",
            )?;
            let lda = lda as usize;
            if !a.is_null() {
                let cols = std::slice::from_raw_parts_mut(a, lda * m);
                cols.fill(0.0);
                for &(pos, k) in &rows {
                    cols[k * lda + pos] = 1.0;
                }
            }
            chk(
                ffi::MatDenseRestoreArrayWrite(b.0, &mut a),
                "MatDenseRestoreArrayWrite",
            )?;
            chk(ffi::MatMatSolve(f, b.0, x.0), "MatMatSolve")?;
            let mut lda_x: ffi::PetscInt = 0;
            chk(ffi::MatDenseGetLDA(x.0, &mut lda_x), "MatDenseGetLDA")?;
            let lda_x = lda_x as usize;
            let mut r: *const f64 = std::ptr::null();
            chk(
                ffi::MatDenseGetArrayRead(x.0, &mut r),
                "MatDenseGetArrayRead",
            )?;
            if !r.is_null() {
                let cols = std::slice::from_raw_parts(r, lda_x * m);
                for &(pos, k) in &rows {
                    for c in 0..m {
                        z[c * m + k] = cols[c * lda_x + pos];
                    }
                }
            }
            chk(
                ffi::MatDenseRestoreArrayRead(x.0, &mut r),
                "MatDenseRestoreArrayRead",
            )?;
        }
        // each entry from the one rank that owns its row: the sum is exact,
        // so every rank holds the same Z
        self.reduce(&mut z, SystemOperation::sum());
        Ok(z)
    }

    /// `x += M⁻¹ [0; e]` with the factor `f`.
    fn solve_lift(&mut self, f: ffi::Mat, e: &[f64], x: &mut [f64]) -> Result<()> {
        let mut w = vec![0.0; x.len()];
        for (&eq, &v) in self.loop_equations.iter().zip(e) {
            w[eq] = v;
        }
        self.b.write_owned(&self.owned, &w)?;
        // SAFETY: valid factor and vectors of the system's layout.
        chk(
            unsafe { ffi::MatSolve(f, self.b.raw, self.x.raw) },
            "MatSolve",
        )?;
        self.to_all.gather(&self.x, &mut self.gathered)?;
        for (e, xe) in x.iter_mut().enumerate() {
            *xe += self.gathered[self.part.petsc_index[e] as usize];
        }
        Ok(())
    }
}

impl crate::backend::Condensed for PetscBackend<'_> {
    fn equations(&self) -> &[usize] {
        &self.loop_equations
    }

    fn schur(&mut self) -> Option<Vec<f64>> {
        let f = self.factor()?;
        let z = self.inverse_block(f);
        if !self.agree_all(z.is_ok()) {
            return None;
        }
        let mut z = z.ok()?;
        // S = Z⁻¹, the same dense LU on every rank
        let m = self.loop_equations.len();
        let mut s = vec![0.0; m * m];
        for k in 0..m {
            s[k * m + k] = 1.0;
        }
        crate::solve::newton::interface_loop::dense_solve(&mut z, &mut s, m).then_some(s)
    }

    fn lift(&mut self, e: &[f64], x: &mut [f64]) -> bool {
        let Some(f) = self.factor() else {
            return false;
        };
        let mut y = x.to_vec();
        let ok = self.solve_lift(f, e, &mut y).is_ok() && y.iter().all(|v| v.is_finite());
        let ok = self.agree_all(ok);
        if ok {
            x.copy_from_slice(&y);
        }
        ok
    }
}
