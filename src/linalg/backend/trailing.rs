//! The interface equations ordered last, and the trailing block of the
//! Cholesky factor that this ordering makes available.
//!
//! With the equations of the bodies first (each body's own minimum-degree
//! order) and the m interface equations I last, the factor of the symmetric
//! part is `L = [[L_BB, 0], [L_IB, L_II]]` and `L_II L_IIᵀ = M_II − M_IB M_BB⁻¹
//! M_BI`, the Schur complement of M on the interface. Hence for a vector `a`
//! on I, `(M⁻¹ [0; a])_I = L_II⁻ᵀ L_II⁻¹ a`: two dense m × m triangular solves
//! instead of a solve with the whole factor ([`super::coupling::Inverse`]).
//! The interface separates the bodies, so ordering it last costs little
//! fill; the symbolic analysis of both orderings decides
//! (`prefer_interface_last`): a very long interface makes the dense block
//! too costly.

use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::triangular::BlockStructure;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};
use faer::sparse::SymbolicSparseColMat;

/// A fill-reducing ordering with `last` (equations, in this order) at the
/// end: approximate minimum degree on the graph of the other equations.
/// Returns (forward, inverse): `forward[k]` is the equation at position k.
pub(crate) fn ordering_with_last(
    pattern: &SymbolicSparseColMat<usize>,
    last: &[usize],
) -> Result<(Vec<usize>, Vec<usize>)> {
    let n = pattern.nrows();
    let mut sub_of = vec![usize::MAX; n];
    for &e in last {
        sub_of[e] = usize::MAX - 1;
    }
    let mut rest = Vec::with_capacity(n - last.len());
    for (e, s) in sub_of.iter_mut().enumerate() {
        if *s == usize::MAX {
            *s = rest.len();
            rest.push(e);
        }
    }
    let ns = rest.len();
    // the graph of the other equations (both triangles, rows sorted)
    let (mut col_ptr, mut row_idx) = (Vec::with_capacity(ns + 1), Vec::new());
    col_ptr.push(0);
    for &e in &rest {
        let rows = &pattern.row_idx()[pattern.col_ptr()[e]..pattern.col_ptr()[e + 1]];
        row_idx.extend(rows.iter().filter(|&&i| sub_of[i] < n).map(|&i| sub_of[i]));
        col_ptr.push(row_idx.len());
    }
    let nnz = row_idx.len();
    let sub = SymbolicSparseColMat::new_checked(ns, ns, col_ptr, None, row_idx);
    let (mut perm, mut perm_inv) = (vec![0usize; ns], vec![0usize; ns]);
    if ns > 0 {
        let mut work = MemBuffer::try_new(amd::order_maybe_unsorted_scratch::<usize>(ns, nnz))
            .map_err(|_| Error::Memory("the interface-last ordering's workspace".into()))?;
        amd::order_maybe_unsorted(
            &mut perm,
            &mut perm_inv,
            sub.as_ref(),
            amd::Control::default(),
            MemStack::new(&mut work),
        )
        .map_err(|e| Error::Solver(format!("interface-last ordering failed: {e:?}")))?;
    }
    let forward: Vec<usize> = perm
        .iter()
        .map(|&k| rest[k])
        .chain(last.iter().copied())
        .collect();
    let mut inverse = vec![0usize; n];
    for (k, &e) in forward.iter().enumerate() {
        inverse[e] = k;
    }
    Ok((forward, inverse))
}

/// Entries and an estimate of the flops of a supernodal factor:
/// (Σ column counts, Σ column counts²).
pub(crate) fn factor_cost(symbolic: &SymbolicCholesky<usize>) -> (f64, f64) {
    let SymbolicCholeskyRaw::Supernodal(s) = symbolic.raw() else {
        return (symbolic.len_val() as f64, f64::INFINITY);
    };
    let (mut entries, mut flops) = (0.0, 0.0);
    for k in 0..s.n_supernodes() {
        let w = s.supernode_end()[k] - s.supernode_begin()[k];
        let p = s.supernode(k).pattern().len();
        for c in 0..w {
            let count = (w - c + p) as f64;
            entries += count;
            flops += count * count;
        }
    }
    (entries, flops)
}

/// Solve-to-factorization cost weight per factor entry: a pair of triangular
/// solves does 4 flops per entry but streams the factor from memory, about 6
/// times slower per flop than the blocked factorization on this machine
/// (docs/performance.md, "The unsymmetric tangent at Cholesky cost").
pub(crate) const SOLVE_WEIGHT: f64 = 4.0 * 6.0;

/// Whole solves per Newton iteration with the plain ordering: the two of the
/// Woodbury solve and one per GMRES step (5-6 on the friction cases).
pub(crate) const PLAIN_SOLVES: f64 = 8.0;

/// Whether the interface-last factor is worth it against the plain minimum
/// degree one, from their (entries, flops): estimated cost of one Newton
/// iteration, factorization plus solves; the interface-last factor needs two
/// whole solves, the plain one [`PLAIN_SOLVES`].
pub(crate) fn prefer_interface_last(last: (f64, f64), plain: (f64, f64)) -> bool {
    let cost = |(entries, flops): (f64, f64), solves: f64| flops + SOLVE_WEIGHT * solves * entries;
    cost(last, 2.0) <= cost(plain, PLAIN_SOLVES)
}

/// Largest cost of an interface-last iteration against a plain one that the
/// interface loop accepts ([`prefer_condensed`]). Every shipped case is
/// within it (the largest, punch-rounded-*, 3.3, where the run's wall time
/// with the interface loop equals the plain run's: docs/performance.md,
/// "Contact status convergence").
pub(crate) const CONDENSED_COST: f64 = 4.0;

/// Whether the interface-last factor is worth it for the interface loop
/// (`solve::newton::interface_loop`) on a symmetric tangent, from both
/// factors' (entries, flops) and the m interface equations: the
/// interface-last factorization plus the dense work of one loop iteration
/// (S = L_II L_IIᵀ, m³/3 flops, and a dense LU of an m × m matrix, 2m³/3)
/// may cost at most [`CONDENSED_COST`] times the plain factorization. The
/// loop saves whole Newton iterations (assembly, factorization, solves)
/// where contact statuses change, hence the generous bound; a very long
/// interface (m³ beyond the factor's flops) gets the plain factor and no
/// loop.
pub(crate) fn prefer_condensed(m: usize, last: (f64, f64), plain: (f64, f64)) -> bool {
    let m = m as f64;
    last.1 + m * m * m <= CONDENSED_COST * plain.1
}

/// The trailing m × m block of the factor, dense (column-major, lower), with
/// where each of its entries sits in the factor's values.
pub struct Trailing {
    m: usize,
    /// (index into the factor's values, index into `l`).
    map: Vec<(usize, usize)>,
    l: Vec<f64>,
}

impl Trailing {
    /// The map of the last m columns of a supernodal factor.
    pub fn new(symbolic: &SymbolicCholesky<usize>, m: usize) -> Option<Trailing> {
        let SymbolicCholeskyRaw::Supernodal(s) = symbolic.raw() else {
            return None;
        };
        let n = symbolic.nrows();
        let first = n - m;
        let mut map = Vec::new();
        for k in 0..s.n_supernodes() {
            let (begin, end) = (s.supernode_begin()[k], s.supernode_end()[k]);
            if end <= first {
                continue;
            }
            let pattern = s.supernode(k).pattern();
            let w = end - begin;
            let rows = w + pattern.len();
            let base = s.col_ptr_for_val()[k];
            for c in 0..w {
                let j = begin + c;
                if j < first {
                    continue;
                }
                let col = (j - first) * m;
                for r in c..w {
                    map.push((base + c * rows + r, col + begin + r - first));
                }
                for (p, &i) in pattern.iter().enumerate() {
                    map.push((base + c * rows + w + p, col + i - first));
                }
            }
        }
        Some(Trailing {
            m,
            map,
            l: vec![0.0; m * m],
        })
    }

    pub fn m(&self) -> usize {
        self.m
    }

    /// Copies the block out of a numeric factor's values.
    pub(crate) fn extract(&mut self, values: &[f64]) {
        self.l.fill(0.0);
        for &(v, d) in &self.map {
            self.l[d] = values[v];
        }
    }

    /// `S = L_II L_IIᵀ`, the Schur complement of the factored matrix on the
    /// interface, dense column-major (both triangles): m³/3 flops.
    pub(crate) fn schur(&self) -> Vec<f64> {
        let m = self.m;
        let mut s = vec![0.0; m * m];
        let l = faer::MatRef::from_column_major_slice(&self.l, m, m);
        let mut dst = faer::MatMut::from_column_major_slice_mut(&mut s, m, m);
        faer::linalg::matmul::triangular::matmul(
            dst.as_mut(),
            BlockStructure::TriangularLower,
            faer::Accum::Replace,
            l,
            BlockStructure::TriangularLower,
            l.transpose(),
            BlockStructure::TriangularUpper,
            1.0,
            faer::Par::Seq,
        );
        for j in 0..m {
            for i in j + 1..m {
                s[i * m + j] = s[j * m + i];
            }
        }
        s
    }

    /// `v ← L_II⁻ᵀ L_II⁻¹ v`.
    pub fn solve(&self, v: &mut [f64]) {
        let (m, l) = (self.m, &self.l);
        for j in 0..m {
            let col = &l[j * m..(j + 1) * m];
            v[j] /= col[j];
            let vj = v[j];
            for i in j + 1..m {
                v[i] -= col[i] * vj;
            }
        }
        for j in (0..m).rev() {
            let col = &l[j * m..(j + 1) * m];
            let s: f64 = (j + 1..m).map(|i| col[i] * v[i]).sum();
            v[j] = (v[j] - s) / col[j];
        }
    }
}
