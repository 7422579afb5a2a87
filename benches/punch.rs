//! Benchmark of the two punch cases and their mesh sequence.
//!
//! `cargo bench --bench punch` prints two Markdown tables: timings of the shipped
//! cases (best of 5 runs, all three methods) and the first-yield loads of the
//! refinement sequence beside the paper's values. docs/performance.md quotes the
//! first, docs/verification.md the second.

use asperity::app::driver::{self, RunOptions};
use asperity::input::case::Method;
use std::path::PathBuf;

fn run(
    case: &str,
    method: Method,
    refine: usize,
) -> (asperity::model::Model, asperity::solve::RunResult, f64) {
    let out =
        std::env::temp_dir().join(format!("asperity-bench-{case}-{}-{refine}", method.name()));
    let opts = RunOptions {
        out: Some(out),
        quiet: true,
        method: Some(method),
        refine: Some(refine),
        ..RunOptions::default()
    };
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("cases")
        .join(case);
    let t = std::time::Instant::now();
    let (_, model, result) = driver::run(&path, &opts).unwrap_or_else(|e| panic!("{case}: {e}"));
    (model, result, t.elapsed().as_secs_f64())
}

fn main() {
    let cases = ["punch-plane-stress", "punch-plane-strain"];
    println!("| case | method | dofs | increments | iterations | wall time (best of 5) |");
    println!("|---|---|---:|---:|---:|---:|");
    for case in cases {
        for method in [
            Method::FullNewton,
            Method::ModifiedNewton,
            Method::InitialStiffness,
        ] {
            let mut best = f64::INFINITY;
            let mut info = (0, 0, 0);
            for _ in 0..5 {
                let (m, r, t) = run(case, method, 1);
                best = best.min(t);
                info = (m.mesh.num_dofs(), r.increments.len(), r.stats.iterations);
            }
            println!(
                "| {case} | {} | {} | {} | {} | {:.3} s |",
                method.name(),
                info.0,
                info.1,
                info.2,
                best
            );
        }
    }
    println!();
    println!("| case | refine | dofs | first yield (kN) | depth (mm) | x (mm) | wall time |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for case in cases {
        for refine in 1..=4 {
            let (m, r, t) = run(case, Method::FullNewton, refine);
            let fy = r.first_yield.expect("the punch cases yield");
            println!(
                "| {case} | {refine} | {} | {:.3} | {:.3} | {:.3} | {:.2} s |",
                m.mesh.num_dofs(),
                fy.total_load_kn,
                fy.depth,
                fy.x,
                t
            );
        }
    }
}
