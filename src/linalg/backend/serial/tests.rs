//! Tests of the serial direct solver.

use super::*;

/// A dense n×n pattern (both triangles), column by column.
fn dense(n: usize) -> Pattern {
    Pattern {
        n,
        col_ptr: (0..=n).map(|j| j * n).collect(),
        row_idx: (0..n * n).map(|k| (k % n) as u32).collect(),
    }
}

fn solve(kind: Factorization, a: &[f64], b: &[f64]) -> (Result<Vec<f64>>, usize) {
    let n = b.len();
    let mut d = SerialDirect::new(&dense(n), kind, 1).unwrap();
    let mut x = b.to_vec();
    let r = d.factor(a).and_then(|()| d.solve(&mut x)).map(|()| x);
    (r, d.fallbacks)
}

/// A 5-point Laplacian on a g×g grid plus 4 on the diagonal (SPD):
/// pattern (both triangles) and values.
fn grid(g: usize) -> (Pattern, Vec<f64>) {
    let n = g * g;
    let (mut col_ptr, mut row_idx, mut vals) = (vec![0], Vec::new(), Vec::new());
    for j in 0..n {
        let (x, y) = (j % g, j / g);
        let mut col = vec![(j, 8.0)];
        if x > 0 {
            col.push((j - 1, -1.0));
        }
        if x + 1 < g {
            col.push((j + 1, -1.0));
        }
        if y > 0 {
            col.push((j - g, -1.0));
        }
        if y + 1 < g {
            col.push((j + g, -1.0));
        }
        col.sort_by_key(|c| c.0);
        for (i, v) in col {
            row_idx.push(i as u32);
            vals.push(v);
        }
        col_ptr.push(row_idx.len());
    }
    (
        Pattern {
            n,
            col_ptr,
            row_idx,
        },
        vals,
    )
}

#[test]
fn the_trailing_block_gives_the_interface_part_of_the_inverse() {
    // the "interface": one grid row across the middle, which separates
    // the grid as a contact interface separates two bodies
    let g = 9;
    let (pattern, vals) = grid(g);
    let iface: Vec<usize> = (0..g).map(|x| 4 * g + x).collect();
    let mut d = SerialDirect::with_interface(
        &pattern,
        Factorization::SymmetricPart,
        iface.clone(),
        false,
        1,
    )
    .unwrap();
    assert!(d.interface_last(), "a separator is cheap to order last");
    assert!(d.factor_cholesky(&vals).unwrap());
    let a: Vec<f64> = (0..g).map(|k| 1.0 + (k as f64).sin()).collect();
    let mut by_block = a.clone();
    Inverse::interface(&mut d, &mut by_block);
    // the same without the trailing block: a solve with the whole factor
    d.trailing = None;
    let mut by_solve = a.clone();
    Inverse::interface(&mut d, &mut by_solve);
    let big = by_solve.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (p, q) in by_block.iter().zip(&by_solve) {
        assert!((p - q).abs() < 1e-14 * big, "{by_block:?} {by_solve:?}");
    }
    // and the whole-factor solve is M⁻¹ itself: M (M⁻¹ [0; a]) = [0; a]
    let mut w = vec![0.0; g * g];
    for (k, &e) in iface.iter().enumerate() {
        w[e] = a[k];
    }
    d.apply(&mut w);
    let mut back = vec![0.0; g * g];
    for (j, wj) in w.iter().enumerate() {
        for p in pattern.col_ptr[j]..pattern.col_ptr[j + 1] {
            back[pattern.row_idx[p] as usize] += vals[p] * wj;
        }
    }
    for (e, v) in back.iter().enumerate() {
        let want = iface.iter().position(|&i| i == e).map_or(0.0, |k| a[k]);
        assert!((v - want).abs() < 1e-12, "row {e}: {v} against {want}");
    }
}

#[test]
fn cholesky_solves_a_positive_definite_system() {
    // column-major [[4, 1, 0], [1, 3, 1], [0, 1, 2]]
    let a = [4.0, 1.0, 0.0, 1.0, 3.0, 1.0, 0.0, 1.0, 2.0];
    let x_true = [1.0, -2.0, 0.5];
    let b: Vec<f64> = (0..3)
        .map(|i| (0..3).map(|j| a[j * 3 + i] * x_true[j]).sum())
        .collect();
    let (x, fallbacks) = solve(Factorization::Cholesky, &a, &b);
    let x = x.unwrap();
    assert_eq!(fallbacks, 0);
    for (u, v) in x.iter().zip(x_true) {
        assert!((u - v).abs() < 1e-14, "{x:?}");
    }
}

#[test]
fn an_indefinite_tangent_falls_back_to_lu_in_the_same_factorization() {
    // symmetric, eigenvalues 3 and −1: Cholesky meets a negative pivot
    let a = [1.0, 2.0, 2.0, 1.0];
    let x_true = [0.25, -1.5];
    let b = [
        a[0] * x_true[0] + a[2] * x_true[1],
        a[1] * x_true[0] + a[3] * x_true[1],
    ];
    let (x, fallbacks) = solve(Factorization::Cholesky, &a, &b);
    let x = x.unwrap();
    assert_eq!(fallbacks, 1);
    for (u, v) in x.iter().zip(x_true) {
        assert!((u - v).abs() < 1e-14, "{x:?}");
    }
}

#[test]
fn a_singular_tangent_is_named_not_solved() {
    // a rigid-body mode: [[1, −1], [−1, 1]]
    let a = [1.0, -1.0, -1.0, 1.0];
    for kind in [Factorization::Cholesky, Factorization::Lu] {
        let msg = solve(kind, &a, &[1.0, 0.0]).0.unwrap_err().to_string();
        assert!(msg.contains("singular tangent"), "{kind:?}: {msg}");
    }
}

#[test]
fn the_cholesky_path_reads_only_the_lower_triangle() {
    // the upper triangle holds garbage: the symmetric lower one is solved
    let a = [2.0, 1.0, 99.0, 2.0];
    let (x, _) = solve(Factorization::Cholesky, &a, &[3.0, 3.0]);
    let x = x.unwrap();
    assert!(
        (x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14,
        "{x:?}"
    );
}

/// The condensation the interface loop uses, against closed forms on a
/// small SPD matrix: `schur()` is `K_II − K_IB K_BB⁻¹ K_BI` (dense, by
/// nalgebra), and `lift(e)` adds `K⁻¹ [0; e]` (a dense solve).
#[test]
fn the_condensation_is_the_schur_complement_and_its_lift_the_solve() {
    let g = 7;
    let (pattern, vals) = grid(g);
    let n = g * g;
    let iface: Vec<usize> = (0..g).map(|x| 3 * g + x).collect();
    let mut d =
        SerialDirect::with_interface(&pattern, Factorization::Cholesky, iface.clone(), true, 1)
            .unwrap();
    assert!(d.interface_last(), "a separator is cheap to order last");
    assert!(d.factor_cholesky(&vals).unwrap());
    let mut k = nalgebra::DMatrix::<f64>::zeros(n, n);
    for j in 0..n {
        for p in pattern.col_ptr[j]..pattern.col_ptr[j + 1] {
            k[(pattern.row_idx[p] as usize, j)] = vals[p];
        }
    }
    let bulk: Vec<usize> = (0..n).filter(|e| !iface.contains(e)).collect();
    let pick = |rows: &[usize], cols: &[usize]| {
        nalgebra::DMatrix::from_fn(rows.len(), cols.len(), |i, j| k[(rows[i], cols[j])])
    };
    let kbb = pick(&bulk, &bulk);
    let schur = pick(&iface, &iface)
        - pick(&iface, &bulk) * kbb.clone().lu().solve(&pick(&bulk, &iface)).unwrap();
    let c = d.condensed().expect("Cholesky with the interface last");
    assert_eq!(c.equations(), &iface[..]);
    let s = c.schur().expect("the trailing block");
    for i in 0..g {
        for j in 0..g {
            let (got, want) = (s[j * g + i], schur[(i, j)]);
            assert!(
                (got - want).abs() < 1e-13 * 8.0,
                "S[{i},{j}] {got} vs {want}"
            );
        }
    }
    let e: Vec<f64> = (0..g).map(|q| (q as f64 * 0.9).cos()).collect();
    let mut x = vec![1.0; n];
    c.lift(&e, &mut x);
    let mut rhs = nalgebra::DVector::zeros(n);
    for (q, &eq) in iface.iter().enumerate() {
        rhs[eq] = e[q];
    }
    let want = k.lu().solve(&rhs).unwrap();
    for i in 0..n {
        assert!((x[i] - 1.0 - want[i]).abs() < 1e-14, "x[{i}]");
    }
    // the plain ordering (no interface given) offers no condensation
    let mut plain = SerialDirect::new(&pattern, Factorization::Cholesky, 1).unwrap();
    assert!(plain.factor_cholesky(&vals).unwrap());
    assert!(plain.condensed().is_none());
}
