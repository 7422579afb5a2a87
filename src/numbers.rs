//! How numbers are printed in messages and files: the shortest form that
//! reads back as the value, or a few significant digits; and finite
//! differences ([`fd`]), the one helper of every tangent test.

/// `1e-310` as `1e-310`, `2000` as `2000`, `0.05` as `0.05`: the shortest
/// form that reads back as the value; a value that needs more than 10
/// characters (one computed rather than typed) with 5 significant digits.
pub fn num(v: f64) -> String {
    let short = exact(v);
    if short.len() > 10 {
        sig(v, 5)
    } else {
        short
    }
}

/// The shorter of `v`'s plain and scientific forms, every digit that reads
/// back as `v` (for values typed in and compared: `10.0000000001`).
pub fn exact(v: f64) -> String {
    let plain = format!("{v}");
    let sci = format!("{v:e}");
    if plain.len() <= sci.len() {
        plain
    } else {
        sci
    }
}

/// `v` to `digits` significant digits, in the shorter of plain and scientific
/// form: 4 significant digits of 23.86547 are `23.87`, of 1.2884e-16 `1.288e-16`.
pub fn sig(v: f64, digits: usize) -> String {
    let rounded: f64 = format!("{:.*e}", digits.max(1) - 1, v).parse().unwrap_or(v);
    exact(rounded)
}

/// Vectors in space, [x, y, z].
pub(crate) mod vec3 {
    pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
}

/// Finite differences for checking analytic derivatives and tangents: one
/// helper shared by every tangent test (unit tests in `src/` and the test
/// crates in `tests/`).
///
/// Every difference here is the central one, ∂f_i/∂x_j ≈
/// (f_i(x + h e_j) − f_i(x − h e_j)) / (2h), whose truncation error is O(h²)
/// (h² f‴/6); round-off adds about ε|f|/h, so h is chosen per test. The inputs
/// are perturbed as `x_j + h` and `x_j + (−h)`, the response differenced as
/// `(f₊ − f₋) / (2.0 * h)`.
pub mod fd {
    /// A matrix of differences, row-major: `rows` responses by `cols` inputs;
    /// `self[(i, j)]` ≈ ∂f_i/∂x_j.
    #[derive(Clone, Debug, PartialEq)]
    pub struct Jacobian {
        pub rows: usize,
        pub cols: usize,
        /// `data[i * cols + j]`
        pub data: Vec<f64>,
    }

    impl std::ops::Index<(usize, usize)> for Jacobian {
        type Output = f64;
        fn index(&self, (i, j): (usize, usize)) -> &f64 {
            assert!(
                i < self.rows && j < self.cols,
                "entry ({i}, {j}) of {}×{}",
                self.rows,
                self.cols
            );
            &self.data[i * self.cols + j]
        }
    }

    impl Jacobian {
        fn zeros(rows: usize, cols: usize) -> Jacobian {
            Jacobian {
                rows,
                cols,
                data: vec![0.0; rows * cols],
            }
        }

        fn set_column(&mut self, j: usize, column: impl Iterator<Item = f64>) {
            for (i, v) in column.enumerate() {
                self.data[i * self.cols + j] = v;
            }
        }
    }

    /// df/dx at `x`: (f(x + h) − f(x − h)) / (2h), error O(h²).
    pub fn central_derivative(mut f: impl FnMut(f64) -> f64, x: f64, h: f64) -> f64 {
        (f(x + h) - f(x - h)) / (2.0 * h)
    }

    /// The Jacobian of `f` at `x` by central differences with step `h` on every
    /// input: column j is (f(x + h e_j) − f(x − h e_j)) / (2h), error O(h²).
    pub fn central_jacobian(mut f: impl FnMut(&[f64]) -> Vec<f64>, x: &[f64], h: f64) -> Jacobian {
        central_columns(&vec![h; x.len()], |j, s| {
            let mut y = x.to_vec();
            y[j] += s;
            f(&y)
        })
    }

    /// Central differences when the caller applies the perturbation: column
    /// j is (f(j, +h_j) − f(j, −h_j)) / (2h_j) with `h_j = steps[j]`, where
    /// `f(j, s)` is the response with input j moved by s (for inputs that
    /// live inside a larger vector, or directional derivatives: one column,
    /// `x + s v`). Every call must return the same number of responses.
    pub fn central_columns(steps: &[f64], mut f: impl FnMut(usize, f64) -> Vec<f64>) -> Jacobian {
        let mut jac: Option<Jacobian> = None;
        for (j, &h) in steps.iter().enumerate() {
            let (p, m) = (f(j, h), f(j, -h));
            assert_eq!(
                p.len(),
                m.len(),
                "column {j}: responses of different lengths"
            );
            let jac = jac.get_or_insert_with(|| Jacobian::zeros(p.len(), steps.len()));
            assert_eq!(
                p.len(),
                jac.rows,
                "column {j}: responses of different lengths"
            );
            jac.set_column(j, p.iter().zip(&m).map(|(a, b)| (a - b) / (2.0 * h)));
        }
        jac.unwrap_or_else(|| Jacobian::zeros(0, 0))
    }

    /// Central and one-sided differences together, to tell a kink from a
    /// wrong tangent: where `forward` and `backward` disagree the response
    /// is not smooth within the step and the central difference means
    /// nothing there.
    #[cfg(test)]
    #[derive(Clone, Debug, PartialEq)]
    pub(crate) struct Sided {
        /// (f(x + h e_j) − f(x − h e_j)) / (2h)
        pub central: Jacobian,
        /// (f(x + h e_j) − f(x)) / h
        pub(crate) forward: Jacobian,
        /// (f(x) − f(x − h e_j)) / h
        pub backward: Jacobian,
    }

    #[cfg(test)]
    impl Sided {
        /// |forward − backward| at (i, j): about h |f″| where f is smooth.
        pub fn kink(&self, i: usize, j: usize) -> f64 {
            (self.forward[(i, j)] - self.backward[(i, j)]).abs()
        }
    }

    /// [`central_columns`] plus the one-sided differences; `f(0, 0.0)` is
    /// taken as the response at x.
    #[cfg(test)]
    pub(crate) fn sided_columns(steps: &[f64], mut f: impl FnMut(usize, f64) -> Vec<f64>) -> Sided {
        let at = f(0, 0.0);
        let n = at.len();
        let (mut central, mut forward, mut backward) = (
            Jacobian::zeros(n, steps.len()),
            Jacobian::zeros(n, steps.len()),
            Jacobian::zeros(n, steps.len()),
        );
        for (j, &h) in steps.iter().enumerate() {
            let (p, m) = (f(j, h), f(j, -h));
            assert!(
                p.len() == n && m.len() == n,
                "column {j}: responses of different lengths"
            );
            central.set_column(j, (0..n).map(|i| (p[i] - m[i]) / (2.0 * h)));
            forward.set_column(j, (0..n).map(|i| (p[i] - at[i]) / h));
            backward.set_column(j, (0..n).map(|i| (at[i] - m[i]) / h));
        }
        Sided {
            central,
            forward,
            backward,
        }
    }

    /// What a difference `|fd − analytic|` is measured against.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub enum Scale {
        /// the difference itself (scale 1)
        Absolute,
        /// one number for every entry (the tangent's largest entry, say)
        Of(f64),
        /// per entry: max(|analytic|, |fd|, floor)
        Relative(f64),
    }

    /// The worst entry of a comparison: which one, both values, the
    /// difference, what it was measured against and their ratio.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Mismatch {
        pub row: usize,
        pub col: usize,
        pub analytic: f64,
        pub fd: f64,
        /// |fd − analytic|
        pub diff: f64,
        pub scale: f64,
        /// diff / scale
        pub ratio: f64,
    }

    impl Mismatch {
        /// One entry measured against `scale`.
        pub fn of(row: usize, col: usize, analytic: f64, fd: f64, scale: Scale) -> Mismatch {
            let diff = (fd - analytic).abs();
            let scale = match scale {
                Scale::Absolute => 1.0,
                Scale::Of(s) => s,
                Scale::Relative(floor) => analytic.abs().max(fd.abs()).max(floor),
            };
            Mismatch {
                row,
                col,
                analytic,
                fd,
                diff,
                scale,
                ratio: diff / scale,
            }
        }
    }

    impl std::fmt::Display for Mismatch {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            write!(
                f,
                "entry ({}, {}): analytic {:e} vs FD {:e}, off by {:e} of {:e} ({:e})",
                self.row, self.col, self.analytic, self.fd, self.diff, self.scale, self.ratio
            )
        }
    }

    /// The entry of `fd` farthest from `analytic(i, j)` relative to `scale`
    /// (largest `ratio`; a NaN on either side is the worst). An empty matrix
    /// gives a zero mismatch at (0, 0).
    pub fn worst(fd: &Jacobian, analytic: impl Fn(usize, usize) -> f64, scale: Scale) -> Mismatch {
        if fd.rows == 0 || fd.cols == 0 {
            return Mismatch::of(0, 0, 0.0, 0.0, Scale::Absolute);
        }
        let mut worst = Mismatch::of(0, 0, analytic(0, 0), fd[(0, 0)], scale);
        for i in 0..fd.rows {
            for j in 0..fd.cols {
                let m = Mismatch::of(i, j, analytic(i, j), fd[(i, j)], scale);
                if m.ratio.is_nan() {
                    return m;
                }
                if m.ratio > worst.ratio {
                    worst = m;
                }
            }
        }
        worst
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        /// f(x, y, z) = (x² y, sin z + x, e^{y z}): J = [[2xy, x², 0],
        /// [1, 0, cos z], [0, z e^{yz}, y e^{yz}]].
        fn f(x: &[f64]) -> Vec<f64> {
            vec![x[0] * x[0] * x[1], x[2].sin() + x[0], (x[1] * x[2]).exp()]
        }

        fn exact(x: &[f64], i: usize, j: usize) -> f64 {
            let e = (x[1] * x[2]).exp();
            [
                [2.0 * x[0] * x[1], x[0] * x[0], 0.0],
                [1.0, 0.0, x[2].cos()],
                [0.0, x[2] * e, x[1] * e],
            ][i][j]
        }

        #[test]
        fn the_central_jacobian_is_the_known_one_to_order_h_squared() {
            let x = [0.7, -1.2, 0.4];
            let mut errs = Vec::new();
            for h in [1e-2, 1e-3] {
                let j = central_jacobian(f, &x, h);
                assert_eq!((j.rows, j.cols), (3, 3));
                let m = worst(&j, |r, c| exact(&x, r, c), Scale::Absolute);
                assert!(m.diff < 2.0 * h * h, "h = {h}: {m}");
                errs.push(m.diff);
            }
            // ten times smaller a step, about a hundred times smaller an error
            assert!(errs[1] < errs[0] / 50.0, "{errs:?}");
            // a wrong tangent is named by its entry
            let j = central_jacobian(f, &x, 1e-5);
            let m = worst(
                &j,
                |r, c| exact(&x, r, c) + if (r, c) == (2, 1) { 1e-3 } else { 0.0 },
                Scale::Relative(1.0),
            );
            assert_eq!((m.row, m.col), (2, 1));
            assert!(m.ratio > 1e-4 && m.ratio < 2e-3, "{m}");
            assert!(m.to_string().starts_with("entry (2, 1)"), "{m}");
        }

        #[test]
        fn the_scalar_derivative_and_the_sided_differences() {
            let d = central_derivative(f64::exp, 1.0, 1e-4);
            assert!((d - 1f64.exp()).abs() < 1e-8 * 1f64.exp(), "{d}");
            // |x| has a kink at 0 but not at 1
            let s = sided_columns(&[1e-6, 1e-6], |j, h| {
                let x = [
                    0.0 + if j == 0 { h } else { 0.0 },
                    1.0 + if j == 1 { h } else { 0.0 },
                ];
                vec![x[0].abs(), x[1].abs()]
            });
            assert!((s.kink(0, 0) - 2.0).abs() < 1e-9);
            assert!(s.kink(1, 1) < 1e-9);
            assert_eq!(s.central[(0, 0)], 0.0);
            assert!((s.central[(1, 1)] - 1.0).abs() < 1e-9);
            assert!((s.forward[(0, 0)] - 1.0).abs() < 1e-9);
        }

        #[test]
        fn a_nan_difference_is_the_worst() {
            let j = central_columns(&[1.0, 1.0], |j, s| vec![if j == 1 { f64::NAN } else { s }]);
            let m = worst(&j, |_, _| 1.0, Scale::Absolute);
            assert_eq!((m.row, m.col), (0, 1));
            assert!(m.ratio.is_nan());
            let m = worst(
                &j,
                |_, c| if c == 0 { 1.0 } else { f64::NAN },
                Scale::Absolute,
            );
            assert_eq!((m.row, m.col), (0, 1));
        }
    }
}
