use super::*;

fn c(slave: usize, terms: &[(usize, f64)], offset: f64) -> Constraint {
    Constraint {
        slave,
        terms: terms.to_vec(),
        offset,
        history: None,
        origin: format!("test constraint on {slave}"),
    }
}

/// A deterministic pseudo-random number in [-1, 1).
fn rnd(k: usize) -> f64 {
    let x = (k as f64 * 12.9898 + 78.233).sin() * 43758.5453;
    2.0 * (x - x.floor()) - 1.0
}

#[test]
fn the_expanded_block_is_t_transpose_k_t() {
    // dofs 0..6; dof 2 = 0.5 u0 + 0.5 u4 + g, dof 3 = u5 − u6 (a shortening)
    let cs = Constraints::new(
        vec![
            c(2, &[(0, 0.5), (4, 0.5)], 0.1),
            c(3, &[(5, 1.0), (6, -1.0)], 0.0),
        ],
        8,
    )
    .unwrap();
    let dofs = [0, 1, 2, 3];
    let x = cs.expand(&dofs).unwrap();
    assert_eq!(x.dofs, vec![0, 1, 4, 5, 6]);
    let n = dofs.len();
    let k: Vec<f64> = (0..n * n).map(rnd).collect();
    // dense T (all 8 dofs → the block's 4 dofs) and its product
    let m = x.dofs.len();
    let kx = x.matrix(&k);
    for i in 0..m {
        for j in 0..m {
            let mut want = 0.0;
            for a in 0..n {
                for b in 0..n {
                    want += x.t[a * m + i] * k[a * n + b] * x.t[b * m + j];
                }
            }
            assert!((kx[i * m + j] - want).abs() < 1e-14, "({i}, {j})");
        }
    }
    // Tᵀ g and the rows of T
    let g = [1.0, 2.0, 3.0, 4.0];
    assert_eq!(x.vector(&g), vec![1.0 + 1.5, 2.0, 1.5, 4.0, -4.0]);
    assert!(cs.expand(&[0, 1, 4]).is_none());
}

#[test]
fn condensed_residual_is_the_virtual_work_on_the_masters() {
    // r·δu over all dofs equals (Tᵀ r)·δū for every δū (δu = T δū)
    let cs = Constraints::new(
        vec![
            c(1, &[(0, 0.375), (2, 0.75), (3, -0.125)], 0.0),
            c(5, &[(4, 1.0), (6, -1.0)], 0.0),
        ],
        7,
    )
    .unwrap();
    let r: Vec<f64> = (0..7).map(|k| rnd(k + 10)).collect();
    let mut rc = r.clone();
    cs.condense(&mut rc);
    assert_eq!((rc[1], rc[5]), (0.0, 0.0));
    for trial in 0..5 {
        let mut du: Vec<f64> = (0..7).map(|k| rnd(100 * trial + k)).collect();
        cs.fill(&mut du, |_| 0.0);
        let whole: f64 = r.iter().zip(&du).map(|(a, b)| a * b).sum();
        let reduced: f64 = rc.iter().zip(&du).map(|(a, b)| a * b).sum();
        assert!((whole - reduced).abs() < 1e-14 * whole.abs().max(1.0));
    }
}

#[test]
fn chains_are_substituted_and_the_offset_follows_its_history() {
    // 2 = u0 + 0.5 (factor), 3 = 2·u2 → 3 = 2 u0 + 1.0 (factor)
    let mut list = vec![c(2, &[(0, 1.0)], 0.5), c(3, &[(2, 2.0)], 0.0)];
    list[0].history = Some(0);
    let cs = Constraints::new(list, 4).unwrap();
    let third = cs.of(3).unwrap();
    assert_eq!(third.terms, vec![(0, 2.0)]);
    assert_eq!((third.offset, third.history), (1.0, Some(0)));
    let mut u = vec![0.3, 0.0, 0.0, 0.0];
    cs.fill(&mut u, |h| if h == Some(0) { 0.5 } else { 1.0 });
    assert!((u[2] - (0.3 + 0.25)).abs() < 1e-15);
    assert!((u[3] - (0.6 + 0.5)).abs() < 1e-15);
}

#[test]
fn two_values_for_one_dof_and_cycles_are_refused() {
    let twice = Constraints::new(vec![c(2, &[(0, 1.0)], 0.0), c(2, &[(1, 1.0)], 0.0)], 4);
    let msg = twice.unwrap_err();
    assert!(msg.contains("constrained twice"), "{msg}");
    let cycle = Constraints::new(vec![c(2, &[(3, 1.0)], 0.0), c(3, &[(2, 1.0)], 0.0)], 4);
    assert!(cycle.unwrap_err().contains("cycle"));
    let nan = Constraints::new(vec![c(2, &[(3, f64::NAN)], 0.0)], 4);
    assert!(nan.unwrap_err().contains("not finite"));
    let out = Constraints::new(vec![c(9, &[(3, 1.0)], 0.0)], 4);
    assert!(out.unwrap_err().contains("out of range"));
}
