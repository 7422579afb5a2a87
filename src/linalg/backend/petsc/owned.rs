//! Matrices the interface loop's condensation owns on PETSc ([`super::condensed`]):
//! an owned `Mat`, and the pattern of the condensed inverse (built once per
//! run, kept by the backend).

use super::ffi;

/// A PETSc matrix, destroyed on drop.
pub(super) struct Owned(pub(super) ffi::Mat);

impl Drop for Owned {
    fn drop(&mut self) {
        // SAFETY: created by this module, destroyed once (MatDestroy of a
        // null handle does nothing).
        unsafe {
            ffi::MatDestroy(&mut self.0);
        }
    }
}

/// The entries I × I of the inverse that `MatMumpsGetInverse` computes: a
/// sparse matrix whose rows all sit on rank 0 (MUMPS wants its sparse
/// right-hand sides on the host), and its transpose (the form PETSc passes
/// to MUMPS); after the call the sparse matrix holds (M⁻¹)ᵀ on that
/// pattern. Built once per run.
pub(super) struct InversePattern {
    pub(super) sparse: Owned,
    pub(super) transpose: Owned,
}
