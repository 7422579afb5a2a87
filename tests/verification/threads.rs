//! The thread count changes no answer (issue 29, docs/running.md "Threads").
//!
//! * The element loop is bit-identical on 1, 2 and 3 threads: residual,
//!   assembled tangent and the first failing element's message. Each
//!   element's forces depend on that element alone and are added in element
//!   order by one thread, whatever the count.
//! * Whole plastic runs on 1, 2 and 3 threads are bit-identical too:
//!   displacements, stresses, plastic strains and iterations (a run's
//!   factorization stays on one thread, `backend::serial::FACTOR_THREADS`).
//! * faer's factorization on several threads (`SerialDirect` with threads > 1,
//!   as the benchmark uses it) agrees with one thread's to round-off, not bit
//!   for bit: its parallel kernels sum some updates in another order.

use crate::common;
use asperity::app::driver::{self, RunOptions};
use asperity::input::case::Method;
use asperity::model::Model;
use asperity::physics::element::solid::Response;
use asperity::solve::{RunResult, State};

const PUNCH: &str = include_str!("../../cases/punch-plane-stress/case.toml");

/// The plane-stress punch at refine 4: 3,072 elements, so the element loop
/// takes two batches and gives each of 3 threads several hundred elements.
fn refined_punch() -> Model {
    let text = PUNCH.replacen("refine = 1", "refine = 4", 1);
    assert_ne!(text, PUNCH, "the case no longer says refine = 1");
    let model = common::model(&text);
    assert!(model.mesh.elements.len() > 2048 + 2 * 128);
    model
}

/// A converged plastic state at 0.8 of the full load (solved on one thread).
fn plastic_state(model: &Model) -> State {
    let mut engine = driver::serial_engine(model, Method::FullNewton, 1).unwrap();
    let mut state = State::initial(model);
    for k in 1..=8 {
        state = engine
            .step(&state, 0.1 * k as f64, Response::Plastic)
            .unwrap()
            .0;
        engine.committed();
    }
    assert!(
        state.gauss.iter().filter(|g| g.yielding).count() > 10,
        "too few yielding points to test the return mapping"
    );
    state
}

#[test]
fn the_element_loop_is_bit_identical_on_any_number_of_threads() {
    let model = refined_punch();
    let state = plastic_state(&model);
    let assemble = |threads: usize| {
        let mut engine = driver::serial_engine(&model, Method::FullNewton, threads).unwrap();
        assert_eq!(engine.threads(), threads);
        let r = engine.linearize(&state, &state.u, 0.8).unwrap();
        let k = engine.backend.matrix_values().unwrap().to_vec();
        (r, k)
    };
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let (r1, k1) = assemble(1);
    assert!(r1.iter().any(|v| *v != 0.0) && k1.iter().any(|v| *v != 0.0));
    for threads in [2, 3] {
        let (r, k) = assemble(threads);
        assert!(bits(&r) == bits(&r1), "{threads} threads: residual differs");
        assert!(bits(&k) == bits(&k1), "{threads} threads: tangent differs");
    }
}

#[test]
fn the_first_failing_element_in_element_order_gives_the_message() {
    let model = refined_punch();
    let state = plastic_state(&model);
    let ne = model.mesh.elements.len();
    // a displacement no return mapping survives, at a node of some elements:
    // 300 is in the first thread's chunk of the first batch, 1500 in a later
    // thread's (2 or 3 threads), the last element in the second batch
    for elements in [vec![300, 1500, ne - 1], vec![1500, ne - 1], vec![ne - 1]] {
        let bad: Vec<usize> = elements
            .iter()
            .map(|&e| model.mesh.elements[e].nodes()[2])
            .collect();
        let mut u = state.u.clone();
        for &n in &bad {
            u[2 * n + 1] = -1e140;
        }
        let first = (0..ne)
            .find(|&e| {
                model.mesh.elements[e]
                    .nodes()
                    .iter()
                    .any(|n| bad.contains(n))
            })
            .unwrap();
        assert!(first <= elements[0]);
        let message = |threads: usize| {
            let mut engine = driver::serial_engine(&model, Method::FullNewton, threads).unwrap();
            match engine.linearize(&state, &u, 0.8) {
                Ok(_) => panic!("{threads} threads: no element failed"),
                Err(e) => e.to_string(),
            }
        };
        let one = message(1);
        println!("{one}");
        assert!(
            one.contains(&format!("element {first} (body")) && one.contains("return mapping"),
            "{one}"
        );
        for threads in [2, 3] {
            assert_eq!(message(threads), one, "{threads} threads, {elements:?}");
        }
    }
}

/// `case` run by the driver on `threads` threads, 4 equal increments.
fn run(case: &str, refine: Option<usize>, threads: usize) -> RunResult {
    let opts = RunOptions {
        out: Some(common::scratch(&format!("threads-{case}-{threads}")).join("out")),
        quiet: true,
        refine,
        increments: Some(4),
        threads: Some(threads),
        ..RunOptions::default()
    };
    let (_, _, r) = driver::run(&common::root().join("cases").join(case), &opts)
        .unwrap_or_else(|e| panic!("{case} on {threads} threads: {e}"));
    assert_eq!(r.threads, threads);
    r
}

/// Largest |a − b| over the largest |a| (0: bit-identical, as the sign of a
/// zero does not matter here).
fn spread(a: impl Iterator<Item = f64> + Clone, b: impl Iterator<Item = f64>) -> f64 {
    let scale = a.clone().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(scale > 0.0);
    a.zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

fn agree(case: &str, refine: Option<usize>) {
    let one = run(case, refine, 1);
    let s1 = &one.final_state;
    assert!(s1.gauss.iter().any(|g| g.peeq > 0.0), "{case}: not plastic");
    for threads in [2, 3] {
        let r = run(case, refine, threads);
        let s = &r.final_state;
        let its = |r: &RunResult| {
            r.increments
                .iter()
                .map(|i| i.iterations)
                .collect::<Vec<_>>()
        };
        assert_eq!(
            its(&r),
            its(&one),
            "{case}: iterations on {threads} threads"
        );
        assert_eq!(r.cutbacks, one.cutbacks);
        let du = spread(s1.u.iter().copied(), s.u.iter().copied());
        let stress = |s: &State| {
            s.gauss
                .iter()
                .flat_map(|g| g.stress)
                .collect::<Vec<_>>()
                .into_iter()
        };
        let ds = spread(stress(s1), stress(s));
        let dp = spread(
            s1.gauss.iter().map(|g| g.peeq),
            s.gauss.iter().map(|g| g.peeq),
        );
        println!(
            "{case} on {threads} threads: displacements {du:.1e}, stresses {ds:.1e}, peeq {dp:.1e}"
        );
        for (what, d) in [("displacements", du), ("stresses", ds), ("peeq", dp)] {
            assert!(
                d == 0.0,
                "{case}, {threads} threads: {what} differ by {d:e}"
            );
        }
    }
}

#[test]
fn a_plastic_run_does_not_depend_on_the_thread_count_cholesky() {
    agree("punch-rounded-stress", None);
}

#[test]
fn a_plastic_run_does_not_depend_on_the_thread_count_lu() {
    // return-mapping friction: the unsymmetric tangent, faer's LU
    agree("punch-friction-b", Some(3));
}

/// faer's parallel kernels act on large dense blocks only (with them a run
/// at 53k dofs moved 3e-15 of its centre displacement; at 8k and 24k none):
/// a dense 600×600 system is one large supernode, so its Cholesky and LU on
/// 2 and 3 threads split the work, and agree with one thread's to round-off.
#[test]
fn the_parallel_factorization_agrees_to_round_off() {
    use asperity::linalg::backend::serial::{Factorization, SerialDirect};
    use asperity::model::assembly::Pattern;
    let n = 600;
    let pattern = Pattern {
        n,
        col_ptr: (0..=n).map(|j| j * n).collect(),
        row_idx: (0..n * n).map(|k| (k % n) as u32).collect(),
    };
    // symmetric positive definite: a diagonal of n + 1 over entries in (−1, 1)
    let entry = |i: usize, j: usize| {
        if i == j {
            n as f64 + 1.0
        } else {
            (((i.min(j) * 7919 + i.max(j) * 104729) % 2001) as f64 - 1000.0) / 1000.0
        }
    };
    let a: Vec<f64> = (0..n * n).map(|k| entry(k % n, k / n)).collect();
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    for kind in [Factorization::Cholesky, Factorization::Lu] {
        let solve = |threads: usize| {
            let mut d = SerialDirect::new(&pattern, kind, threads).unwrap();
            let mut x = b.clone();
            d.factor(&a).unwrap();
            d.solve(&mut x).unwrap();
            x
        };
        let x1 = solve(1);
        // the solution solves the system (a check of the comparison's base)
        let residual = (0..n)
            .map(|i| ((0..n).map(|j| a[j * n + i] * x1[j]).sum::<f64>() - b[i]).abs())
            .fold(0.0, f64::max);
        assert!(residual < 1e-12, "{kind:?}: residual {residual:e}");
        for threads in [2, 3] {
            let x = solve(threads);
            let d = spread(x1.iter().copied(), x.iter().copied());
            println!("dense {n}×{n} {kind:?} on {threads} threads: {d:.1e}");
            assert!(d <= 1e-12, "{kind:?} on {threads} threads: {d:e}");
        }
    }
}
