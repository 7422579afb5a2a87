//! Threads in the one-process path (issue 29): 1 against 2 threads.
//!
//! `cargo bench --bench threads` prints two Markdown tables, 1- and 2-thread
//! trials alternating so that a shared host's drift reaches both:
//!
//! 1. the factorization alone: faer's numeric Cholesky (the frictionless
//!    variant of cases/punch-friction-b: its tangential law removed) and LU
//!    (punch-friction-b, return-mapping friction) and one triangular solve,
//!    on `Par::Seq` and on `Par::rayon(2)`, at refine 1, 2, 4 and 8 (1.6k, 6k, 24k,
//!    94k dofs), of the tangent at a converged plastic state (λ = 0.3);
//! 2. whole runs at 93.5k dofs on 1 and 2 threads: cases/punch-plane-stress-fine
//!    (Cholesky) and punch-friction-b at refine 8 (LU), full Newton,
//!    `--increments 5`: wall time, time per Newton iteration, and its two
//!    parts from the run's stats: assembly (element and spring loops) and
//!    solve (factorization and triangular solves).
//!
//! docs/performance.md ("Threads in the one-process path") quotes the tables.

use asperity::app::driver::{self, RunOptions};
use asperity::input::case::Method;
use asperity::linalg::backend::serial::{Factorization, SerialBackend, SerialDirect};
use asperity::model::Model;
use asperity::physics::element::solid::Response;
use asperity::solve::{RunResult, State};
use std::path::{Path, PathBuf};
use std::time::Instant;

mod common;
use common::{cases_dir, median, without_tangential};

fn scratch() -> PathBuf {
    std::env::temp_dir().join("asperity-bench-threads")
}

/// The tangent (CSC values on the model's pattern) at a converged plastic
/// state at load factor 0.3, reached in three steps on one thread.
fn plastic_tangent(model: &Model) -> Vec<f64> {
    let backend = SerialBackend::new(model).unwrap();
    let mut engine =
        asperity::solve::Engine::with_backend(model, Method::FullNewton, Box::new(backend));
    let mut state = State::initial(model);
    for k in 1..=3 {
        state = engine
            .step(&state, 0.1 * k as f64, Response::Plastic)
            .unwrap_or_else(|e| panic!("step {k}: {e}"))
            .0;
        engine.committed();
    }
    engine.linearize(&state, &state.u, 0.3).unwrap();
    engine.backend.matrix_values().unwrap().to_vec()
}

/// Median seconds of (factorization, solve) on `threads`, `trials` each,
/// 1- and 2-thread trials alternating; returns both thread counts' medians.
fn factor_times(model: &Model, kind: Factorization, trials: usize) -> [(f64, f64); 2] {
    let vals = plastic_tangent(model);
    let pattern = model.pattern();
    let mut direct = [1, 2].map(|t| SerialDirect::new(&pattern, kind, t).unwrap());
    let mut times = [(Vec::new(), Vec::new()), (Vec::new(), Vec::new())];
    let rhs: Vec<f64> = (0..pattern.n).map(|i| 1.0 + (i % 7) as f64).collect();
    for _ in 0..trials {
        for (d, t) in direct.iter_mut().zip(times.iter_mut()) {
            let t0 = Instant::now();
            d.factor(&vals).unwrap();
            t.0.push(t0.elapsed().as_secs_f64());
            let mut x = rhs.clone();
            let t1 = Instant::now();
            d.solve(&mut x).unwrap();
            t.1.push(t1.elapsed().as_secs_f64());
        }
    }
    times.map(|(f, s)| (median(f), median(s)))
}

struct Run {
    wall: f64,
    result: RunResult,
}

impl Run {
    fn per_it(&self, seconds: f64) -> f64 {
        1e3 * seconds / self.result.stats.iterations as f64
    }
}

fn run(case: &Path, tag: &str, refine: Option<usize>, threads: usize) -> Run {
    let opts = RunOptions {
        out: Some(scratch().join("out").join(tag)),
        quiet: true,
        method: Some(Method::FullNewton),
        refine,
        increments: Some(5),
        threads: Some(threads),
        ..RunOptions::default()
    };
    let t = Instant::now();
    let (_, _, result) =
        driver::run(case, &opts).unwrap_or_else(|e| panic!("{}: {e}", case.display()));
    let wall = t.elapsed().as_secs_f64();
    assert!(result.stopped.is_none(), "{tag}: stopped early");
    assert_eq!(result.threads, threads);
    Run { wall, result }
}

fn main() {
    let started = Instant::now();
    let _ = std::fs::remove_dir_all(scratch());
    let fric_b = cases_dir().join("punch-friction-b");
    let text_b = std::fs::read_to_string(fric_b.join("case.toml")).unwrap();
    let dir = scratch().join("cases/punch-friction-b-frictionless");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("case.toml"), without_tangential(&text_b)).unwrap();
    let frictionless_b = dir;
    println!(
        "machine: {} cores available to this process (std::thread::available_parallelism)",
        asperity::threads::available()
    );
    println!();

    // 1. The factorization alone.
    println!("## 1. Numeric factorization and one solve, Par::Seq against Par::rayon(2)");
    println!();
    println!("tangent at a converged plastic state (λ = 0.3, full Newton); medians of alternating trials");
    println!();
    println!("| case | refine | dofs | factorization | trials | factor ms 1 thread | factor ms 2 threads | speed-up | solve ms 1 thread | solve ms 2 threads | speed-up |");
    println!("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|");
    for (case, kind, name) in [
        (
            &frictionless_b,
            Factorization::Cholesky,
            "punch-friction-b without friction",
        ),
        (&fric_b, Factorization::Lu, "punch-friction-b"),
    ] {
        for (refine, trials) in [(1, 41), (2, 21), (4, 11), (8, 5)] {
            let opts = RunOptions {
                refine: Some(refine),
                ..RunOptions::default()
            };
            let model = driver::load_model(&case.join("case.toml"), &opts).unwrap();
            let [(f1, s1), (f2, s2)] = factor_times(&model, kind, trials);
            println!(
                "| {name} | {refine} | {} | {} | {trials} | {:.1} | {:.1} | {:.2} | {:.2} | {:.2} | {:.2} |",
                model.mesh.num_dofs(),
                if kind == Factorization::Cholesky { "Cholesky" } else { "LU" },
                1e3 * f1,
                1e3 * f2,
                f1 / f2,
                1e3 * s1,
                1e3 * s2,
                s1 / s2,
            );
        }
    }

    // 2. Whole runs at 93.5k dofs.
    println!();
    println!("## 2. Whole runs at 93.5k dofs, 1 and 2 threads (`--increments 5`, full Newton)");
    println!();
    println!("ms/it = time / Newton iterations; assembly = element and spring loops, solve = factorization + triangular solves (the run's stats); wall = driver::run (model, solve, output)");
    println!();
    println!("| case | threads | iterations | wall s | wall ms/it | assembly ms/it | solve ms/it | speed-up wall | speed-up assembly | speed-up solve |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let fine = cases_dir().join("punch-plane-stress-fine");
    for (case, refine, name) in [
        (&fine, None, "punch-plane-stress-fine"),
        (&fric_b, Some(8), "punch-friction-b refine 8"),
    ] {
        let runs: Vec<Run> = [1, 2]
            .iter()
            .map(|&t| run(case, &format!("{name}-{t}"), refine, t))
            .collect();
        let (one, two) = (&runs[0], &runs[1]);
        for (t, r) in [(1, one), (2, two)] {
            let s = &r.result.stats;
            let speed = |f: fn(&Run) -> f64| {
                if t == 1 {
                    String::new()
                } else {
                    format!("{:.2}", f(one) / f(two))
                }
            };
            println!(
                "| {name} | {t} | {} | {:.2} | {:.1} | {:.1} | {:.1} | {} | {} | {} |",
                s.iterations,
                r.wall,
                r.per_it(r.wall),
                r.per_it(s.assembly_seconds),
                r.per_it(s.solve_seconds),
                speed(|r| r.per_it(r.wall)),
                speed(|r| r.per_it(r.result.stats.assembly_seconds)),
                speed(|r| r.per_it(r.result.stats.solve_seconds)),
            );
        }
    }
    println!();
    println!("bench total: {:.0} s", started.elapsed().as_secs_f64());
}
