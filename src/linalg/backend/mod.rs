//! Linear-algebra backends behind one small trait, so that one Newton loop
//! ([`crate::solve::Engine`]) drives both:
//! * `serial`: faer sparse Cholesky or LU with symbolic reuse, one process;
//! * `petsc` (feature `parallel`): METIS-partitioned elements, an MPIAIJ matrix
//!   with exact preallocation, KSP from the options database, MPI reductions.
//!
//! Every rank holds the whole (replicated) displacement vector and model, and
//! the Gauss states of its own elements only; each assembles only the elements
//! and interface points it owns, and `Backend::sum` adds the partial
//! residuals. Decisions that change control flow go through
//! `Backend::agree`, so all ranks always take the same branch.

pub mod coupling;

/// From this many dofs a 3D model is solved faster iteratively (CG with
/// algebraic multigrid, PETSc) than by a sparse direct factorization: the
/// fill of a 3D factor grows as N^(4/3) and its work as N² (nested
/// dissection). PETSc's default switches to GAMG here for a 3D model, and a
/// serial run of a larger 3D model is told so (docs/performance.md, "3D:
/// choosing the solver").
pub const DIRECT_3D_UP_TO: usize = 20_000;
#[cfg(feature = "parallel")]
#[allow(unsafe_code)] // the FFI layer: every call carries its SAFETY note
pub mod petsc;
pub mod serial;
pub mod trailing;

use crate::error::Result;

/// What the ranks of a run share: the reductions and decisions every layer
/// above the backend needs (the measures, the events, the stepping), and
/// nothing of the matrices. On one process every value is its own.
pub trait Comm {
    fn ranks(&self) -> usize {
        1
    }
    fn rank(&self) -> usize {
        0
    }
    /// Sums a vector over all ranks, in place (replicated result).
    fn sum(&self, _v: &mut [f64]) {}
    /// Element-wise maximum of a vector over all ranks, in place (replicated
    /// result); serial: unchanged. Used for collective stop decisions.
    fn max(&self, _v: &mut [f64]) {}
    /// Rank 0's value of a decision, on every rank.
    fn agree(&self, flag: bool) -> bool {
        flag
    }
    /// The message of the lowest rank that has one, on every rank.
    fn share_message(&self, msg: Option<String>) -> Option<String> {
        msg
    }
}

/// A linear-algebra backend: assembles the tangent block by block and
/// solves; its ranks share through [`Comm`].
pub trait Backend: Comm {
    /// "serial-faer" or "petsc".
    fn name(&self) -> &'static str;
    fn owns_element(&self, _e: usize) -> bool {
        true
    }
    /// Interface point q (numbered over all interfaces).
    fn owns_point(&self, _q: usize) -> bool {
        true
    }
    /// Whether the solid matrix is reused under new spring blocks (modified
    /// Newton, initial stiffness): then it is kept apart from the system
    /// matrix. Without reuse (full Newton, the default) the element blocks go
    /// straight into the system matrix and the second matrix is not held.
    /// Called once, before any assembly.
    fn reuse_solid(&mut self, _reuse: bool) {}
    /// Starts a new solid (bodies) matrix.
    fn begin_solid(&mut self) -> Result<()>;
    /// Adds an element block; `block` is the assembler's block index.
    fn add_solid(&mut self, block: usize, dofs: &[usize], k: &[f64]) -> Result<()>;
    /// The system matrix becomes the last solid matrix; contact blocks follow.
    /// Without reuse it must follow a `begin_solid` and the element blocks.
    fn begin_contact(&mut self) -> Result<()>;
    fn add_contact(&mut self, block: usize, dofs: &[usize], k: &[f64]) -> Result<()>;
    /// Whether interface points hand their unsymmetric tangent term apart, by
    /// [`Backend::add_coupling`], rather than inside their `add_contact` block.
    fn splits_coupling(&self) -> bool {
        false
    }
    /// Adds the rank-one tangent term `coef · g_t g_nᵀ` of interface point
    /// `block` (the same block and dofs as its `add_contact`). By default it
    /// is added to the matrix like any contact block.
    fn add_coupling(
        &mut self,
        block: usize,
        dofs: &[usize],
        coef: f64,
        g_t: &[f64],
        g_n: &[f64],
    ) -> Result<()> {
        self.add_contact(block, dofs, &outer(coef, g_t, g_n))
    }
    /// Solves K x = rhs over the free equations (replicated in and out).
    fn solve(&mut self, rhs: &[f64], x: &mut [f64]) -> Result<()>;
    /// The linear solver, as summary.json reports it.
    fn linear_solver(&self) -> String {
        "faer sparse LU".into()
    }
    /// Counters reported in summary.json under "backend_stats".
    fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        Vec::new()
    }
    /// The assembled system matrix as CSC values on the model's pattern, where
    /// the backend keeps one (serial); for checks of the assembled tangent.
    fn matrix_values(&mut self) -> Option<&[f64]> {
        None
    }
    /// The last factorization's condensation on the interface equations,
    /// where the backend holds one (serial Cholesky with the interface
    /// ordered last, for `[solver] interface_loop`): else `None`, and the
    /// Newton correction is the plain solve's.
    fn condensed(&mut self) -> Option<&mut dyn Condensed> {
        None
    }
}

/// The factored matrix M condensed on the interface equations I (ordered
/// last, [`trailing`]): `S = L_II L_IIᵀ = M_II − M_IB M_BB⁻¹ M_BI`, its Schur
/// complement on I, and the lift of an interface load back to every
/// equation. Used by the interface loop (`solve::newton::interface_loop`).
pub trait Condensed {
    /// The interface equations, in the factor's order (the rows of S).
    fn equations(&self) -> &[usize];
    /// S, dense, column-major m × m (both triangles); `None` where it could
    /// not be formed (the same on every rank).
    fn schur(&mut self) -> Option<Vec<f64>>;
    /// `x ← x + M⁻¹ [0; e]`: e on the interface equations (in their order),
    /// x over every free equation. One solve with the whole factor; false
    /// (x unchanged) where that solve failed.
    fn lift(&mut self, e: &[f64], x: &mut [f64]) -> bool;
}

/// The row-major block `coef · g_t g_nᵀ` of an interface point's rank-one
/// tangent term.
pub fn outer(coef: f64, g_t: &[f64], g_n: &[f64]) -> Vec<f64> {
    let nd = g_t.len();
    (0..nd * nd)
        .map(|ij| coef * g_t[ij / nd] * g_n[ij % nd])
        .collect()
}
