//! The rigid motions of one body and the rows that hold them: a Gram
//! matrix Σ r rᵀ over the rows r its supports (and supporting interface
//! pairs) impose on the motions t_x, t_y, θ·L, and one motion more per
//! pretension section that cuts the body in two while the section is free
//! (its shortening moves the side beyond the cut rigidly along the cut's
//! normal, [`crate::model::pretension::sides`]).

/// A symmetric positive semi-definite matrix over a body's rigid motions,
/// dense (3 + the body's cuts)².
#[derive(Clone, Debug)]
pub(super) struct Gram {
    n: usize,
    g: Vec<f64>,
}

impl Gram {
    /// No row yet, over `n` rigid motions.
    pub(super) fn new(n: usize) -> Gram {
        Gram {
            n,
            g: vec![0.0; n * n],
        }
    }

    /// Adds the row `r` (one value per motion).
    pub(super) fn add(&mut self, r: &[f64]) {
        let n = self.n;
        for (i, &a) in r.iter().enumerate().take(n) {
            if a == 0.0 {
                continue;
            }
            for (j, &b) in r.iter().enumerate().take(n) {
                self.g[i * n + j] += a * b;
            }
        }
    }

    /// Whether the rows fix every motion: the determinant above 1e-9 of the
    /// mean diagonal's n-th power (the three in-plane motions alone: the
    /// determinant of 3 × 3 written out, as it always was).
    pub(super) fn fixes_all(&self) -> bool {
        let n = self.n;
        let tr: f64 = (0..n).map(|i| self.g[i * n + i]).sum();
        tr > 0.0 && self.det() > 1e-9 * (tr / n as f64).powi(n as i32)
    }

    fn det(&self) -> f64 {
        let g = &self.g;
        if self.n == 3 {
            let (a, b, c, d, e, f) = (g[0], g[1], g[2], g[4], g[5], g[8]);
            return a * (d * f - e * e) - b * (b * f - e * c) + c * (b * e - d * c);
        }
        // Gaussian elimination with partial pivoting
        let n = self.n;
        let mut m = g.clone();
        let mut det = 1.0;
        for k in 0..n {
            let p = (k..n)
                .max_by(|&i, &j| m[i * n + k].abs().total_cmp(&m[j * n + k].abs()))
                .unwrap_or(k);
            if m[p * n + k] == 0.0 {
                return 0.0;
            }
            if p != k {
                for j in 0..n {
                    m.swap(p * n + j, k * n + j);
                }
                det = -det;
            }
            det *= m[k * n + k];
            for i in k + 1..n {
                let f = m[i * n + k] / m[k * n + k];
                for j in k..n {
                    m[i * n + j] -= f * m[k * n + j];
                }
            }
        }
        det
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fourth_motion_needs_a_row_of_its_own() {
        // the three in-plane motions held, a cut's motion not
        let mut g = Gram::new(4);
        g.add(&[1.0, 0.0, 0.0, 0.0]);
        g.add(&[0.0, 0.0, 1.0, 0.0]);
        g.add(&[0.0, 1.0, 0.5, 0.0]);
        assert!(!g.fixes_all());
        // a support on the side beyond the cut, along its normal
        let mut h = g.clone();
        h.add(&[0.0, 1.0, -0.5, 1.0]);
        assert!(h.fixes_all());
        // the same support as the first: still free
        g.add(&[0.0, 1.0, 0.5, 0.0]);
        assert!(!g.fixes_all());
    }
}
