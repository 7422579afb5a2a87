//! The benchmark of issue 29: friction against frictionless.
//!
//! `cargo bench --bench friction` prints three Markdown tables, every ratio
//! measured in this one run (friction and frictionless runs alternate, so the
//! drift of a shared host reaches both):
//!
//! 1. time per Newton iteration of cases/punch-friction-b (return-mapping
//!    friction: unsymmetric tangent, Cholesky of its symmetric part with the
//!    interface coupling by Woodbury-GMRES) against the same case text with
//!    its tangential law removed (symmetric tangent, Cholesky), at refine 2,
//!    4, 8 and 12 (6k, 24k, 94k, 210k dofs); full Newton, 5 equal increments
//!    each; at refine 2 and 4 also the friction case on faer's LU of the whole
//!    tangent (the option the split replaced);
//! 2. Newton iterations per increment and cutbacks of every shipped case and
//!    of the force-controlled Hertzian sphere (tests/data/hertz-sphere);
//! 3. whole-run wall time of the 50-increment plane-strain punch
//!    (cases/punch-plane-strain `--increments 50`) against the same case with
//!    the tangential law of punch-friction-b added, at refine 1 and 2;
//! 4. in 3D: time per Newton iteration of cases/punch-slab-3d (the punch as
//!    a slab, friction on faces: 4 × 4 points per face, a slip vector in the
//!    tangent plane) against the same case without its tangential law, at
//!    refine 1 and 2, and the same with `--interface-loop off`.
//!
//! `cargo bench --bench friction -- 3d` prints table 4 alone.
//!
//! docs/performance.md ("Friction against frictionless") quotes the tables.

use asperity::app::driver::{self, RunOptions};
use asperity::input::case::Method;
use asperity::linalg::backend::serial::Factorization;
use asperity::solve::RunResult;
use std::path::{Path, PathBuf};
use std::time::Instant;

mod common;
use common::{cases_dir, median, tangential_block, without_tangential};

fn scratch() -> PathBuf {
    std::env::temp_dir().join("asperity-bench-friction")
}

/// Writes a case folder `name` holding `text` as case.toml.
fn write_case(name: &str, text: &str) -> PathBuf {
    let dir = scratch().join("cases").join(name);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("case.toml"), text).unwrap();
    dir
}

struct Run {
    dofs: usize,
    wall: f64,
    result: RunResult,
}

impl Run {
    fn iterations(&self) -> usize {
        self.result.stats.iterations
    }
    fn ms_per_it(&self, seconds: f64) -> f64 {
        1e3 * seconds / self.iterations() as f64
    }
    fn wall_per_it(&self) -> f64 {
        self.ms_per_it(self.wall)
    }
    fn work_per_it(&self) -> f64 {
        self.ms_per_it(self.result.stats.assembly_seconds + self.result.stats.solve_seconds)
    }
    fn solve_per_it(&self) -> f64 {
        self.ms_per_it(self.result.stats.solve_seconds)
    }
}

fn run(case: &Path, tag: &str, refine: Option<usize>, increments: Option<usize>) -> Run {
    run_on(case, tag, refine, increments, None)
}

fn run_on(
    case: &Path,
    tag: &str,
    refine: Option<usize>,
    increments: Option<usize>,
    factorization: Option<Factorization>,
) -> Run {
    let opts = RunOptions {
        hooks: asperity::app::options::Hooks {
            factorization,
            ..Default::default()
        },
        out: Some(scratch().join("out").join(tag)),
        quiet: true,
        method: Some(Method::FullNewton),
        refine,
        increments,
        ..RunOptions::default()
    };
    let t = Instant::now();
    let (_, model, result) =
        driver::run(case, &opts).unwrap_or_else(|e| panic!("{}: {e}", case.display()));
    let wall = t.elapsed().as_secs_f64();
    assert!(result.stopped.is_none(), "{tag}: stopped early");
    Run {
        dofs: model.mesh.num_dofs(),
        wall,
        result,
    }
}

/// `pairs` runs of `fric` and of `plain` at `refine` in `increments` equal
/// steps, alternating (friction first), so a shared host's drift reaches
/// both; tagged `TAG-f-REFINE-K` and `TAG-s-REFINE-K`.
fn alternate(
    fric: &Path,
    plain: &Path,
    tag: &str,
    refine: usize,
    increments: usize,
    pairs: usize,
) -> (Vec<Run>, Vec<Run>) {
    let mut f = Vec::new();
    let mut s = Vec::new();
    for k in 0..pairs {
        let at = |side: &str| format!("{tag}-{side}-{refine}-{k}");
        f.push(run(fric, &at("f"), Some(refine), Some(increments)));
        s.push(run(plain, &at("s"), Some(refine), Some(increments)));
    }
    (f, s)
}

fn main() {
    let started = Instant::now();
    let _ = std::fs::remove_dir_all(scratch());
    if std::env::args().any(|a| a == "3d") {
        slab_3d();
        println!();
        println!("bench total: {:.0} s", started.elapsed().as_secs_f64());
        return;
    }
    let fric_b = cases_dir().join("punch-friction-b");
    let text_b = std::fs::read_to_string(fric_b.join("case.toml")).unwrap();
    let frictionless_b = write_case(
        "punch-friction-b-frictionless",
        &without_tangential(&text_b),
    );

    // 1. Per-iteration time, friction against frictionless.
    println!(
        "## 1. Time per Newton iteration: punch-friction-b with and without its tangential law"
    );
    println!();
    println!("full Newton, 5 equal increments (first-yield search included); ms per iteration =");
    println!("time / Newton iterations (failed attempts of cutbacks included); work = assembly + solve (factorization + triangular");
    println!("solves) from the run's stats; medians over alternating pairs, ratio = median of the");
    println!("pairs' ratios.");
    println!();
    println!(
        "| refine | dofs | pairs | iterations fric / frictionless | cutbacks fric / frictionless | wall ms/it fric | wall ms/it frictionless | work ms/it fric | work ms/it frictionless | solve ms/it fric | solve ms/it frictionless | solve share fric / frictionless | ratio wall | ratio work | ratio solve | wall ms/it fric on LU |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut last_solvers = (String::new(), String::new());
    let mut stats = Vec::new();
    for (refine, pairs) in [(2, 3), (4, 3), (8, 1), (12, 1)] {
        let (f, s) = alternate(&fric_b, &frictionless_b, "it", refine, 5, pairs);
        let med = |v: &[Run], g: fn(&Run) -> f64| median(v.iter().map(g).collect());
        let ratio =
            |g: fn(&Run) -> f64| median(f.iter().zip(&s).map(|(a, b)| g(a) / g(b)).collect());
        let share = |v: &[Run]| {
            median(
                v.iter()
                    .map(|r| r.result.stats.solve_seconds / r.wall)
                    .collect(),
            )
        };
        // the whole tangent on LU, once, where it takes less than a minute
        let lu = (refine <= 4).then(|| {
            run_on(
                &fric_b,
                &format!("it-lu-{refine}"),
                Some(refine),
                Some(5),
                Some(Factorization::Lu),
            )
        });
        println!(
            "| {refine} | {} | {pairs} | {} / {} | {} / {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.0}% / {:.0}% | {:.2} | {:.2} | {:.2} | {} |",
            f[0].dofs,
            f[0].iterations(),
            s[0].iterations(),
            f[0].result.cutbacks,
            s[0].result.cutbacks,
            med(&f, Run::wall_per_it),
            med(&s, Run::wall_per_it),
            med(&f, Run::work_per_it),
            med(&s, Run::work_per_it),
            med(&f, Run::solve_per_it),
            med(&s, Run::solve_per_it),
            100.0 * share(&f),
            100.0 * share(&s),
            ratio(Run::wall_per_it),
            ratio(Run::work_per_it),
            ratio(Run::solve_per_it),
            lu.map_or("—".to_string(), |r| format!(
                "{:.1} ({} it)",
                r.wall_per_it(),
                r.iterations()
            )),
        );
        last_solvers = (
            f[0].result.linear_solver.clone(),
            s[0].result.linear_solver.clone(),
        );
        let stat = |k: &str| {
            f[0].result
                .backend_stats
                .iter()
                .find(|(n, _)| n == k)
                .map_or(f64::NAN, |(_, v)| *v)
        };
        stats.push(format!(
            "refine {refine}: interface equations {}, ordered last {}, coupling terms at most {}, GMRES steps mean {:.2} max {}, LU fallbacks {}, Cholesky factor {:.1} MB",
            stat("interface_equations"),
            stat("interface_last") == 1.0,
            stat("coupling_terms_max"),
            stat("gmres_steps_mean"),
            stat("gmres_steps_max"),
            stat("lu_fallbacks"),
            stat("cholesky_factor_mb"),
        ));
    }
    println!();
    println!(
        "linear solvers: friction {}, frictionless {}",
        last_solvers.0, last_solvers.1
    );
    println!();
    for line in &stats {
        println!("- {line}");
    }

    // 2. Iterations per increment and cutbacks of every shipped case.
    println!();
    println!("## 2. Newton iterations per increment and cutbacks, shipped cases (as shipped)");
    println!();
    println!(
        "it/inc = all Newton iterations of the run (first-yield search included) / increments;"
    );
    println!("max = the most iterations of one increment.");
    println!();
    println!("| case | dofs | linear solver | increments | iterations | it/inc | max it in an increment | cutbacks | wall time |");
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|");
    let mut shipped: Vec<PathBuf> = std::fs::read_dir(cases_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("case.toml").is_file())
        .collect();
    shipped.sort();
    shipped.push(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/hertz-sphere"));
    for case in &shipped {
        let name = case.file_name().unwrap().to_string_lossy().to_string();
        let opts = RunOptions {
            out: Some(scratch().join("out").join(format!("ship-{name}"))),
            quiet: true,
            ..RunOptions::default()
        };
        let t = Instant::now();
        let (_, model, r) = driver::run(case, &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
        let wall = t.elapsed().as_secs_f64();
        let n = r.increments.len();
        let max = r.increments.iter().map(|i| i.iterations).max().unwrap_or(0);
        println!(
            "| {name} | {} | {} | {n} | {} | {:.2} | {max} | {} | {:.2} s |",
            model.mesh.num_dofs(),
            r.linear_solver,
            r.stats.iterations,
            r.stats.iterations as f64 / n as f64,
            r.cutbacks,
            wall
        );
    }

    // 3. Whole run of the 50-increment plane-strain punch, with and without friction.
    let strain = cases_dir().join("punch-plane-strain");
    let text_s = std::fs::read_to_string(strain.join("case.toml")).unwrap();
    assert!(!text_s.contains("tangential]"));
    let friction_s = write_case(
        "punch-plane-strain-friction",
        &format!("{text_s}\n{}", tangential_block(&text_b)),
    );
    println!();
    println!("## 3. Whole run, punch-plane-strain --increments 50, with the tangential law of punch-friction-b and without");
    println!();
    println!("full Newton; wall time of driver::run (model, solve, output); median of alternating pairs.");
    println!();
    println!("| refine | dofs | pairs | iterations fric / frictionless | it/inc fric / frictionless | cutbacks fric / frictionless | wall fric | wall frictionless | ratio |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (refine, pairs) in [(1, 3), (2, 3)] {
        let (f, s) = alternate(&friction_s, &strain, "x50", refine, 50, pairs);
        let per_inc = |r: &Run| r.iterations() as f64 / r.result.increments.len() as f64;
        println!(
            "| {refine} | {} | {pairs} | {} / {} | {:.2} / {:.2} | {} / {} | {:.2} s | {:.2} s | {:.2} |",
            f[0].dofs,
            f[0].iterations(),
            s[0].iterations(),
            per_inc(&f[0]),
            per_inc(&s[0]),
            f[0].result.cutbacks,
            s[0].result.cutbacks,
            median(f.iter().map(|r| r.wall).collect()),
            median(s.iter().map(|r| r.wall).collect()),
            median(f.iter().zip(&s).map(|(a, b)| a.wall / b.wall).collect()),
        );
    }
    slab_3d();
    println!();
    println!("bench total: {:.0} s", started.elapsed().as_secs_f64());
}

/// Table 4: friction against frictionless in 3D, cases/punch-slab-3d, serial.
fn slab_3d() {
    let slab = cases_dir().join("punch-slab-3d");
    let text = std::fs::read_to_string(slab.join("case.toml")).unwrap();
    let frictionless = write_case("punch-slab-3d-frictionless", &without_tangential(&text));
    let looped = |on: bool| {
        let t = text.replace("[solver]\n", &format!("[solver]\ninterface_loop = {on}\n"));
        assert_ne!(t, text, "punch-slab-3d has a [solver] table");
        t
    };
    let loop_off = write_case("punch-slab-3d-loop-off", &looped(false));
    println!();
    println!(
        "## 4. 3D: time per Newton iteration, punch-slab-3d with and without its tangential law"
    );
    println!();
    println!("serial, full Newton, 5 equal increments; ms per iteration as in table 1 (work = assembly +");
    println!(
        "solve); medians over alternating pairs, ratio = median of the pairs' ratios; the friction"
    );
    println!("case also with `interface_loop = false` (one run).");
    println!();
    println!("| refine | dofs | pairs | iterations fric / frictionless | work ms/it fric | work ms/it frictionless | ratio work | ratio wall | loop off: iterations, work ms/it |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (refine, pairs) in [(1, 3), (2, 1)] {
        let (f, s) = alternate(&slab, &frictionless, "3d", refine, 5, pairs);
        let off = run(
            &loop_off,
            &format!("3d-off-{refine}"),
            Some(refine),
            Some(5),
        );
        let med = |v: &[Run], g: fn(&Run) -> f64| median(v.iter().map(g).collect());
        let ratio =
            |g: fn(&Run) -> f64| median(f.iter().zip(&s).map(|(a, b)| g(a) / g(b)).collect());
        println!(
            "| {refine} | {} | {pairs} | {} / {} | {:.1} | {:.1} | {:.2} | {:.2} | {}, {:.1} |",
            f[0].dofs,
            f[0].iterations(),
            s[0].iterations(),
            med(&f, Run::work_per_it),
            med(&s, Run::work_per_it),
            ratio(Run::work_per_it),
            ratio(Run::wall_per_it),
            off.iterations(),
            off.work_per_it(),
        );
    }
}
