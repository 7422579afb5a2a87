//! Small dense solves (the interface loop's condensed Jacobian).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::{Conj, MatMut, MatRef, Par};

/// `x ← J⁻¹ x` by a dense LU with partial pivoting, on one thread (`j`
/// overwritten; x column-major with `cols` columns); false where J is
/// singular.
pub(crate) fn dense_solve(j: &mut [f64], x: &mut [f64], cols: usize) -> bool {
    let m = x.len() / cols.max(1);
    let (mut perm, mut perm_inv) = (vec![0usize; m], vec![0usize; m]);
    let req = factor::lu_in_place_scratch::<usize, f64>(m, m, Par::Seq, Default::default()).or(
        solve::solve_in_place_scratch::<usize, f64>(m, cols, Par::Seq),
    );
    let Ok(mut buf) = MemBuffer::try_new(req) else {
        return false;
    };
    let stack = MemStack::new(&mut buf);
    let mut a = MatMut::from_column_major_slice_mut(j, m, m);
    let (_, p) = factor::lu_in_place(
        a.as_mut(),
        &mut perm,
        &mut perm_inv,
        Par::Seq,
        stack,
        Default::default(),
    );
    let a = MatRef::from_column_major_slice(j, m, m);
    if (0..m).any(|i| a[(i, i)] == 0.0 || !a[(i, i)].is_finite()) {
        return false;
    }
    let rhs = MatMut::from_column_major_slice_mut(x, m, cols);
    solve::solve_in_place_with_conj(a, a, p, Conj::No, rhs, Par::Seq, stack);
    x.iter().all(|v| v.is_finite())
}
