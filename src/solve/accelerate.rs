//! Acceleration of the fixed-matrix iterations (modified Newton, initial
//! stiffness). Both converge only linearly; near a limit load the contraction
//! factor tends to one and thousands of iterations are needed.
//!
//! Anderson acceleration (type II, depth m) treats one iteration as a fixed-point
//! map x ↦ x + f(x), f = −K⁻¹R(x), and mixes the last m corrections:
//! ```text
//!   γ = argmin ‖f_k − ΔF γ‖₂,   x_{k+1} = x_k + f_k − (ΔX + ΔF) γ
//! ```
//! with ΔF, ΔX the differences of successive corrections and iterates.

use nalgebra::{DMatrix, DVector};
use std::collections::VecDeque;

pub struct Anderson {
    depth: usize,
    last: Option<(Vec<f64>, Vec<f64>)>,
    dx: VecDeque<Vec<f64>>,
    df: VecDeque<Vec<f64>>,
}

impl Anderson {
    pub fn new(depth: usize) -> Self {
        Anderson {
            depth,
            last: None,
            dx: VecDeque::new(),
            df: VecDeque::new(),
        }
    }

    /// Given the iterate x and its correction f, returns the step to add to x.
    pub fn step(&mut self, x: &[f64], f: &[f64]) -> Vec<f64> {
        if let Some((xl, fl)) = self.last.take() {
            self.dx
                .push_back(x.iter().zip(&xl).map(|(a, b)| a - b).collect());
            self.df
                .push_back(f.iter().zip(&fl).map(|(a, b)| a - b).collect());
            if self.dx.len() > self.depth {
                self.dx.pop_front();
                self.df.pop_front();
            }
        }
        self.last = Some((x.to_vec(), f.to_vec()));
        let m = self.df.len();
        if m == 0 {
            return f.to_vec();
        }
        // normal equations of the small least-squares problem, Tikhonov-guarded
        let mut a = DMatrix::<f64>::zeros(m, m);
        let mut b = DVector::<f64>::zeros(m);
        for i in 0..m {
            for j in 0..=i {
                let v: f64 = self.df[i].iter().zip(&self.df[j]).map(|(p, q)| p * q).sum();
                a[(i, j)] = v;
                a[(j, i)] = v;
            }
            b[i] = self.df[i].iter().zip(f).map(|(p, q)| p * q).sum();
        }
        let trace = (0..m).map(|i| a[(i, i)]).sum::<f64>().max(1e-300);
        for i in 0..m {
            a[(i, i)] += 1e-12 * trace;
        }
        let Some(gamma) = a.cholesky().map(|c| c.solve(&b)) else {
            self.dx.clear();
            self.df.clear();
            return f.to_vec();
        };
        let mut s = f.to_vec();
        for i in 0..m {
            let g = gamma[i];
            for (k, v) in s.iter_mut().enumerate() {
                *v -= g * (self.dx[i][k] + self.df[i][k]);
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anderson_solves_a_slow_linear_fixed_point_fast() {
        // x = G x + c with contraction 0.999 in one mode, 0.99 in another
        let g = [0.999, 0.99, 0.5];
        let c = [1.0, -2.0, 0.5];
        let exact: Vec<f64> = (0..3).map(|i| c[i] / (1.0 - g[i])).collect();
        let mut x = vec![0.0; 3];
        let mut acc = Anderson::new(5);
        let mut n = 0;
        while n < 100 {
            let f: Vec<f64> = (0..3).map(|i| g[i] * x[i] + c[i] - x[i]).collect();
            if f.iter().map(|v| v.abs()).fold(0.0, f64::max) < 1e-10 {
                break;
            }
            let s = acc.step(&x, &f);
            for i in 0..3 {
                x[i] += s[i];
            }
            n += 1;
        }
        assert!(n < 15, "took {n} iterations");
        for i in 0..3 {
            assert!((x[i] - exact[i]).abs() < 1e-6 * exact[i].abs());
        }
    }
}
