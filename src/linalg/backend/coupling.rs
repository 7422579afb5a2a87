//! The unsymmetric interface tangent at Cholesky cost.
//!
//! Under the return-mapping friction scheme the tangent of an interface point
//! is `a (k_N g_N g_Nᵀ + ∂p_T/∂u_T g_T g_Tᵀ) + a ∂p_T/∂u_N g_T g_Nᵀ`
//! (eq. 2.18-2.21 linearized): a symmetric part and one rank-one unsymmetric
//! term per point. The whole tangent is therefore
//!
//! ```text
//! K = M + U Vᵀ,   M symmetric (bodies + symmetric spring parts),
//!                 U = [a_q ∂p_T/∂u_N g_T,q],  V = [g_N,q],  r = rank ≤ points
//! ```
//!
//! and by the Sherman-Morrison-Woodbury identity
//!
//! ```text
//! K⁻¹ b = M⁻¹ b − M⁻¹ U C⁻¹ Vᵀ M⁻¹ b,   C = I_r + Vᵀ M⁻¹ U   (r × r).
//! ```
//!
//! M is factored once by sparse Cholesky. The small capacitance system
//! `C z = Vᵀ M⁻¹ b` is solved by GMRES without ever forming C: a product with
//! C needs `(M⁻¹)_II`, M's inverse between the interface equations I (U and V
//! live there only). When the interface equations are ordered last, that is
//! two dense triangular solves with the trailing m × m block of the Cholesky
//! factor (`L_II L_IIᵀ` is the Schur complement of M on I), a few hundred
//! microseconds; otherwise it is one solve with the whole factor
//! ([`Inverse`]). Forming C instead would cost r solves, one per interface
//! point. The answer then takes one more whole solve, `x = M⁻¹ (b − U z)`.
//! The residual of the full system is exactly `K x − b = U (C z − c)`, so
//! GMRES stops on a bound of the true residual, `‖U‖_F ‖C z − c‖ ≤ 10⁻¹² ‖b‖`:
//! the Newton correction is that of the exact tangent to round-off, and the
//! Newton iterates with it (test `the_split_tangent_takes_the_lu_iterates`).
//! In exact arithmetic GMRES ends in at most r steps; it is given at most
//! `MAX_KRYLOV`, after which (or if M is not positive definite) the solver
//! factors the whole K by LU instead. Measurements: docs/performance.md,
//! "The unsymmetric tangent at Cholesky cost".

use crate::model::assembly::Assembler;

/// Most GMRES steps on the capacitance system before the LU of the whole
/// tangent takes over.
pub(crate) const MAX_KRYLOV: usize = 60;

/// Relative residual of the full system at which GMRES stops.
pub(crate) const RTOL: f64 = 1e-12;

/// The inverse of the symmetric part M, as the solve needs it.
pub trait Inverse {
    /// `v ← M⁻¹ v` over all free equations.
    fn full(&mut self, v: &mut [f64]);
    /// `v ← (M⁻¹)_II v` over the interface equations (in their order).
    fn interface(&mut self, v: &mut [f64]);
}

/// The rank-one terms `coef · g_t g_nᵀ` of one assembly, with their blocks
/// (for adding them to a matrix), their free equations and their positions
/// among the interface equations (for the Woodbury solve).
#[derive(Default)]
pub struct Couplings {
    /// Per term: its assembler block and where its local dofs start.
    blocks: Vec<usize>,
    start: Vec<usize>,
    /// Local dofs of all terms, flat: equation, or `u32::MAX` where prescribed.
    eq: Vec<u32>,
    /// Position among the interface equations (`u32::MAX` where prescribed).
    pos: Vec<u32>,
    /// `coef · g_t` and `g_n` over the local dofs, flat.
    u: Vec<f64>,
    v: Vec<f64>,
}

impl Couplings {
    pub fn clear(&mut self) {
        self.blocks.clear();
        self.start.clear();
        self.eq.clear();
        self.pos.clear();
        self.u.clear();
        self.v.clear();
    }

    /// Number of terms (the rank r of `U Vᵀ`, at most).
    pub fn len(&self) -> usize {
        self.blocks.len()
    }

    pub fn is_empty(&self) -> bool {
        self.blocks.is_empty()
    }

    /// Adds a term. `eq_of`: the equation of every dof (`u32::MAX` where
    /// prescribed); `pos_of`: the interface position of every equation.
    #[allow(clippy::too_many_arguments)] // the term, its block and two maps
    pub fn push(
        &mut self,
        eq_of: &[u32],
        pos_of: &[u32],
        block: usize,
        dofs: &[usize],
        coef: f64,
        g_t: &[f64],
        g_n: &[f64],
    ) {
        self.blocks.push(block);
        self.start.push(self.eq.len());
        for (k, &d) in dofs.iter().enumerate() {
            let e = eq_of[d];
            self.eq.push(e);
            self.pos
                .push(if e == u32::MAX { e } else { pos_of[e as usize] });
            self.u.push(coef * g_t[k]);
            self.v.push(g_n[k]);
        }
    }

    fn range(&self, q: usize) -> std::ops::Range<usize> {
        self.start[q]..self.start.get(q + 1).copied().unwrap_or(self.eq.len())
    }

    /// Adds every term, as a dense local block, to CSC `values`.
    pub(crate) fn add_to(&self, asm: &Assembler, values: &mut [f64]) {
        for q in 0..self.len() {
            let r = self.range(q);
            let block = super::outer(1.0, &self.u[r.clone()], &self.v[r]);
            asm.add(self.blocks[q], &block, values);
        }
    }

    /// `w = U z`, indexed by `idx` (equations or interface positions).
    fn scatter_u(&self, idx: &[u32], z: &[f64], w: &mut [f64]) {
        w.fill(0.0);
        for (q, &zq) in z.iter().enumerate() {
            for k in self.range(q) {
                if idx[k] != u32::MAX {
                    w[idx[k] as usize] += self.u[k] * zq;
                }
            }
        }
    }

    /// `c = Vᵀ y`, `y` indexed by `idx`.
    fn gather_v(&self, idx: &[u32], y: &[f64], c: &mut [f64]) {
        for (q, cq) in c.iter_mut().enumerate() {
            *cq = self
                .range(q)
                .filter(|&k| idx[k] != u32::MAX)
                .map(|k| self.v[k] * y[idx[k] as usize])
                .sum();
        }
    }

    /// Frobenius norm of U over the free equations.
    fn u_norm(&self) -> f64 {
        self.u
            .iter()
            .zip(&self.eq)
            .filter(|(_, &e)| e != u32::MAX)
            .map(|(u, _)| u * u)
            .sum::<f64>()
            .sqrt()
    }
}

/// What one Woodbury-GMRES solve did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Converged in this many GMRES steps (0 without coupling terms).
    Converged(usize),
    /// No convergence within `MAX_KRYLOV` steps (or a breakdown without
    /// convergence): the caller solves by LU.
    Stalled,
}

/// Solves `(M + U Vᵀ) x = b` in place (`x` holds b on entry); `m`: the
/// number of interface equations. On `Stalled`, `x` is meaningless.
pub fn solve(terms: &Couplings, m: usize, inv: &mut dyn Inverse, x: &mut [f64]) -> Outcome {
    let n = x.len();
    let r = terms.len();
    let b_norm = norm(x);
    // y0 = M⁻¹ b
    inv.full(x);
    if r == 0 || b_norm == 0.0 {
        return Outcome::Converged(0);
    }
    let mut c = vec![0.0; r];
    terms.gather_v(&terms.eq, x, &mut c);
    let beta = norm(&c);
    let u_norm = terms.u_norm();
    let goal = RTOL * b_norm;
    if u_norm * beta <= goal {
        return Outcome::Converged(0);
    }
    let most = MAX_KRYLOV.min(r);
    // Arnoldi on C (modified Gram-Schmidt), H reduced by Givens rotations
    let mut h = vec![vec![0.0; most]; most + 1]; // h[i][j]: row i, column j
    let (mut cs, mut sn) = (vec![0.0; most], vec![0.0; most]);
    let mut g = vec![0.0; most + 1];
    g[0] = beta;
    let mut q: Vec<Vec<f64>> = vec![c.iter().map(|v| v / beta).collect()];
    let mut t = vec![0.0; m];
    let mut done = 0;
    let mut converged = false;
    for j in 0..most {
        // C q_j = q_j + V_Iᵀ (M⁻¹)_II U_I q_j
        terms.scatter_u(&terms.pos, &q[j], &mut t);
        inv.interface(&mut t);
        let mut p = vec![0.0; r];
        terms.gather_v(&terms.pos, &t, &mut p);
        for (pk, qk) in p.iter_mut().zip(&q[j]) {
            *pk += qk;
        }
        for (i, qi) in q.iter().enumerate() {
            let hij = dot(&p, qi);
            h[i][j] = hij;
            for (pk, qk) in p.iter_mut().zip(qi) {
                *pk -= hij * qk;
            }
        }
        let next = norm(&p);
        h[j + 1][j] = next;
        // the earlier rotations on the new column, then its own
        for i in 0..j {
            let (a, b) = (h[i][j], h[i + 1][j]);
            h[i][j] = cs[i] * a + sn[i] * b;
            h[i + 1][j] = -sn[i] * a + cs[i] * b;
        }
        let (a, b) = (h[j][j], h[j + 1][j]);
        let d = a.hypot(b);
        if d == 0.0 || !d.is_finite() {
            break;
        }
        cs[j] = a / d;
        sn[j] = b / d;
        h[j][j] = d;
        h[j + 1][j] = 0.0;
        g[j + 1] = -sn[j] * g[j];
        g[j] *= cs[j];
        done = j + 1;
        // next == 0: an invariant subspace, the solution is exact in it
        if u_norm * g[j + 1].abs() <= goal || next == 0.0 {
            converged = true;
            break;
        }
        q.push(p.iter().map(|v| v / next).collect());
    }
    if !converged {
        return Outcome::Stalled;
    }
    // z = Q y with H y = g (upper triangular), then x = y0 − M⁻¹ U z
    let mut y = vec![0.0; done];
    for i in (0..done).rev() {
        let s: f64 = (i + 1..done).map(|k| h[i][k] * y[k]).sum();
        y[i] = (g[i] - s) / h[i][i];
    }
    let mut z = vec![0.0; r];
    for (yk, qk) in y.iter().zip(&q) {
        for (zi, qi) in z.iter_mut().zip(qk) {
            *zi += yk * qi;
        }
    }
    let mut w = vec![0.0; n];
    terms.scatter_u(&terms.eq, &z, &mut w);
    inv.full(&mut w);
    for (xi, wi) in x.iter_mut().zip(&w) {
        *xi -= wi;
    }
    if x.iter().any(|v| !v.is_finite()) {
        return Outcome::Stalled;
    }
    Outcome::Converged(done)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::assembly::{Assembler, Blocks, DofMap, Pattern};

    /// M⁻¹ by a dense LU; the interface equations: `iface`.
    struct Dense {
        m: nalgebra::DMatrix<f64>,
        iface: Vec<usize>,
    }

    impl Inverse for Dense {
        fn full(&mut self, v: &mut [f64]) {
            let s = self
                .m
                .clone()
                .lu()
                .solve(&nalgebra::DVector::from_column_slice(v));
            v.copy_from_slice(s.unwrap().as_slice());
        }
        fn interface(&mut self, v: &mut [f64]) {
            let mut w = vec![0.0; self.m.nrows()];
            for (k, &e) in self.iface.iter().enumerate() {
                w[e] = v[k];
            }
            self.full(&mut w);
            for (k, &e) in self.iface.iter().enumerate() {
                v[k] = w[e];
            }
        }
    }

    /// A dense SPD M (n×n) with r rank-one terms on blocks of 3 dofs among
    /// the interface equations (every other one, reversed); checks the
    /// Woodbury-GMRES result against a dense solve of the whole K.
    fn check(n: usize, r: usize, strength: f64) -> (Outcome, f64) {
        let map = DofMap::new(n, &vec![false; n]);
        let iface: Vec<usize> = (0..n).rev().step_by(2).collect();
        let mut pos_of = vec![u32::MAX; n];
        for (k, &e) in iface.iter().enumerate() {
            pos_of[e] = k as u32;
        }
        let mut m = nalgebra::DMatrix::<f64>::zeros(n, n);
        for i in 0..n {
            m[(i, i)] = 4.0;
            if i + 1 < n {
                m[(i, i + 1)] = -1.0;
                m[(i + 1, i)] = -1.0;
            }
        }
        let mut k = m.clone();
        let mut terms = Couplings::default();
        let mut blocks = Blocks::new();
        for q in 0..r {
            let dofs = [
                iface[q % iface.len()],
                iface[(q + 1) % iface.len()],
                iface[(q + 4) % iface.len()],
            ];
            blocks.push(dofs);
            let g_t = [1.0, -0.5 + 0.1 * q as f64, 0.25];
            let g_n = [0.3, 1.0, -0.7 * (q as f64).sin()];
            terms.push(&map.eq, &pos_of, q, &dofs, strength, &g_t, &g_n);
            for a in 0..3 {
                for b in 0..3 {
                    k[(dofs[a], dofs[b])] += strength * g_t[a] * g_n[b];
                }
            }
        }
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
        let mut x = b.clone();
        let mut inv = Dense {
            m: m.clone(),
            iface: iface.clone(),
        };
        let out = solve(&terms, iface.len(), &mut inv, &mut x);
        let exact = k
            .clone()
            .lu()
            .solve(&nalgebra::DVector::from_column_slice(&b))
            .unwrap();
        let err = x
            .iter()
            .zip(exact.iter())
            .fold(0.0f64, |a, (p, q)| a.max((p - q).abs()))
            / exact.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        // the terms added to a matrix are K − M
        let pattern = Pattern::new(&map, &blocks);
        let asm = Assembler::new(&pattern, &map, &blocks);
        let mut vals = vec![0.0; pattern.nnz()];
        terms.add_to(&asm, &mut vals);
        for j in 0..n {
            let range = pattern.col_ptr[j]..pattern.col_ptr[j + 1];
            for (&i, &v) in pattern.row_idx[range.clone()].iter().zip(&vals[range]) {
                let i = i as usize;
                assert!((v - (k[(i, j)] - m[(i, j)])).abs() < 1e-14, "({i}, {j})");
            }
        }
        (out, err)
    }

    #[test]
    fn woodbury_gmres_solves_the_whole_unsymmetric_system() {
        for (r, strength) in [(1, 0.5), (4, 0.3), (10, 1.5)] {
            let (out, err) = check(40, r, strength);
            let Outcome::Converged(steps) = out else {
                panic!("r = {r}: {out:?}")
            };
            assert!(steps <= r, "r = {r}: {steps} steps");
            assert!(err < 1e-11, "r = {r}: error {err:e}");
        }
    }

    #[test]
    fn without_coupling_terms_it_is_the_symmetric_solve() {
        let (out, err) = check(12, 0, 0.0);
        assert_eq!(out, Outcome::Converged(0));
        assert!(err < 1e-14, "{err:e}");
    }
}
