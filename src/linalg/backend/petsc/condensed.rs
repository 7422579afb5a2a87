//! The interface loop's condensation on the PETSc backend
//! ([`crate::linalg::backend::Condensed`]; `solve::newton::interface_loop`).
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
//! MUMPS's selected entries of the inverse where the factor is MUMPS's
//! (`MatMumpsGetInverse`, ICNTL(30): the requested entries I × I held on
//! rank 0 as a sparse matrix, the right-hand sides and the solution entries
//! sparse, so the solves prune the elimination tree), else m right-hand
//! sides in one `MatMatSolve` with the factor; Z is summed onto every rank
//! (each entry from the one rank that holds it), and S = Z⁻¹ by a dense LU,
//! identically on every rank. The lift `x += M⁻¹ [0; e]` is one
//! `MatSolve`. The factor is the one of the KSP that solved the Newton
//! system: SNES's where SNES drives the step ([`PetscBackend::factor_of`]),
//! else the backend's own. Only a factorization (`-pc_type cholesky|lu`)
//! has one: with an iterative solver (GAMG, above
//! [`super::LinearDefault::MULTIGRID_FROM`] rows, or chosen on the command
//! line) the loop does not run and the plain Newton correction stands.
//!
//! **Only where the case asks for it by name** (the backend's construction,
//! [`super::solver`]:
//! `[solver] interface_loop = true` or `--interface-loop on`; unset, the
//! serial backend runs it and PETSc does not). Z costs m pruned solves
//! with the factor, as much as a whole Newton iteration or more: on
//! punch-plane-stress-fine (93,508 dofs, m = 514) 1.4-2.4 s per Newton
//! iteration against a 1.0-1.3 s factorization with Debian's reference
//! BLAS (0.2-0.4 s against 0.4 s with OpenBLAS), at 23,716 dofs 0.19 s
//! against a 0.25 s iteration. It pays where it saves most of the
//! iterations (the elastic Hertz sphere: 48 → 13, 2.4× faster on one
//! rank), not where it saves a quarter (the plastic punches: 31 → 22 and
//! 34 → 26, 1.2-2.6× slower): which, no rule read off the model tells
//! before the run (docs/performance.md, "The interface loop").
//! Where it runs, the equations are the serial backend's
//! ([`crate::linalg::backend::serial::interface_loop_equations`]), so that
//! serial and PETSc runs of a case that asks for the loop take the same
//! iterates to round-off.

use super::owned::{InversePattern, Owned};

use super::solver::PetscBackend;
use super::{chk, ffi, type_is};
use crate::error::Result;
use mpi::collective::SystemOperation;
use mpi::traits::*;

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
    pub(super) fn condensation(&mut self) -> Option<&mut dyn crate::linalg::backend::Condensed> {
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

    /// Whether `f` is a MUMPS factor.
    fn is_mumps(f: ffi::Mat) -> bool {
        let mut kind = std::ptr::null();
        // SAFETY: valid factor; out-pointer to a string PETSc owns.
        unsafe { ffi::MatFactorGetSolverType(f, &mut kind) == 0 && type_is(kind, b"mumps") }
    }

    /// The pattern I × I of [`InversePattern`] (the interface equations'
    /// PETSc indices, every row on rank 0).
    fn build_inverse_pattern(&self) -> Result<InversePattern> {
        let global = self.part.global_len();
        let rows = if self.rank == 0 { global } else { 0 };
        let mut idx: Vec<ffi::PetscInt> = self
            .loop_equations
            .iter()
            .map(|&e| self.part.petsc_index[e])
            .collect();
        idx.sort_unstable();
        let mut nnz = vec![0 as ffi::PetscInt; rows];
        for &p in &idx {
            if self.rank == 0 {
                nnz[p as usize] = idx.len() as ffi::PetscInt;
            }
        }
        let ones = vec![1.0; idx.len()];
        let mut sparse = Owned(std::ptr::null_mut());
        let mut transpose = Owned(std::ptr::null_mut());
        // SAFETY: a fresh matrix on the backend's communicator, preallocated
        // for exactly the entries set below; out-pointers.
        unsafe {
            chk(
                ffi::MatCreate(self.petsc.comm(), &mut sparse.0),
                "MatCreate",
            )?;
            let (n, g) = (rows as ffi::PetscInt, global as ffi::PetscInt);
            chk(ffi::MatSetSizes(sparse.0, n, n, g, g), "MatSetSizes")?;
            chk(ffi::MatSetType(sparse.0, c"aij".as_ptr()), "MatSetType")?;
            chk(
                ffi::MatSeqAIJSetPreallocation(sparse.0, 0, nnz.as_ptr()),
                "MatSeqAIJSetPreallocation",
            )?;
            chk(
                ffi::MatMPIAIJSetPreallocation(sparse.0, 0, nnz.as_ptr(), 0, std::ptr::null()),
                "MatMPIAIJSetPreallocation",
            )?;
            if self.rank == 0 {
                for &p in &idx {
                    chk(
                        ffi::MatSetValues(
                            sparse.0,
                            1,
                            &p,
                            idx.len() as ffi::PetscInt,
                            idx.as_ptr(),
                            ones.as_ptr(),
                            ffi::InsertMode_INSERT_VALUES,
                        ),
                        "MatSetValues",
                    )?;
                }
            }
            let fin = ffi::MatAssemblyType_MAT_FINAL_ASSEMBLY;
            chk(ffi::MatAssemblyBegin(sparse.0, fin), "MatAssemblyBegin")?;
            chk(ffi::MatAssemblyEnd(sparse.0, fin), "MatAssemblyEnd")?;
            chk(
                ffi::MatCreateTranspose(sparse.0, &mut transpose.0),
                "MatCreateTranspose",
            )?;
        }
        Ok(InversePattern { sparse, transpose })
    }

    /// Z = (M⁻¹)_II by MUMPS's selected entries of the inverse, on every rank.
    fn inverse_entries(&mut self, f: ffi::Mat) -> Result<Vec<f64>> {
        if self.inverse_pattern.is_none() {
            self.inverse_pattern = Some(self.build_inverse_pattern()?);
        }
        let m = self.loop_equations.len();
        let mut z = vec![0.0; m * m];
        let pat = self.inverse_pattern.as_ref().expect("built above");
        // position in I of each PETSc index of an interface equation
        let pos: std::collections::HashMap<ffi::PetscInt, usize> = self
            .loop_equations
            .iter()
            .enumerate()
            .map(|(k, &e)| (self.part.petsc_index[e], k))
            .collect();
        // SAFETY: valid MUMPS factor and the pattern built for it; the rows
        // read on rank 0, which holds them all, and restored.
        unsafe {
            // MatMumpsGetInverse switches MUMPS to sparse right-hand sides,
            // a centralized solution and selected entries (ICNTL(20), (21),
            // (30)) and leaves them so: restored after, for the Newton solves
            // that follow (without, the next solve fails on two ranks)
            let mut saved = [(20, 0), (21, 0), (30, 0)];
            for (k, v) in saved.iter_mut() {
                chk(ffi::MatMumpsGetIcntl(f, *k, v), "MatMumpsGetIcntl")?;
            }
            let got = chk(
                ffi::MatMumpsGetInverse(f, pat.transpose.0),
                "MatMumpsGetInverse",
            );
            for (k, v) in saved {
                chk(ffi::MatMumpsSetIcntl(f, k, v), "MatMumpsSetIcntl")?;
            }
            got?;
            if self.rank == 0 {
                for (&p, &ki) in &pos {
                    let (mut ncols, mut cols, mut vals) = (0, std::ptr::null(), std::ptr::null());
                    chk(
                        ffi::MatGetRow(pat.sparse.0, p, &mut ncols, &mut cols, &mut vals),
                        "MatGetRow",
                    )?;
                    let (c, v) = (
                        std::slice::from_raw_parts(cols, ncols as usize),
                        std::slice::from_raw_parts(vals, ncols as usize),
                    );
                    // the sparse matrix holds (M⁻¹)ᵀ: its (p_i, p_j) is Z(j, i)
                    for (cj, vj) in c.iter().zip(v) {
                        if let Some(&kj) = pos.get(cj) {
                            z[ki * m + kj] = *vj;
                        }
                    }
                    chk(
                        ffi::MatRestoreRow(pat.sparse.0, p, &mut ncols, &mut cols, &mut vals),
                        "MatRestoreRow",
                    )?;
                }
            }
        }
        self.reduce(&mut z, SystemOperation::sum());
        Ok(z)
    }

    /// Z = (M⁻¹)_II on every rank (dense, column-major m × m).
    fn inverse_block(&mut self, f: ffi::Mat) -> Result<Vec<f64>> {
        if Self::is_mumps(f) {
            return self.inverse_entries(f);
        }
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
        let dense = |what: &str| -> Result<Owned> {
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
            Ok(Owned(raw))
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

impl crate::linalg::backend::Condensed for PetscBackend<'_> {
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
        crate::linalg::dense::dense_solve(&mut z, &mut s, m).then_some(s)
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
