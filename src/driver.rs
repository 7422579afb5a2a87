//! The top-level jobs behind the command line: `run` and `check`.

use crate::case::{Case, Method};
use crate::error::Result;
use crate::model::Model;
use crate::output::Writer;
use crate::solve::{self, Engine, RunResult};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of `asperity run`.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    pub out: Option<PathBuf>,
    pub quiet: bool,
    pub method: Option<Method>,
    pub refine: Option<usize>,
    /// Test hook: make the element loop fail on (rank, assembly number).
    pub fault: Option<(usize, usize)>,
    /// Override: equal load steps (drops the case's first_increment / load_factors).
    pub increments: Option<usize>,
    pub max_cutbacks: Option<usize>,
    /// Override: ungraded mesh (every size ratio 1) with the same element counts.
    pub uniform: bool,
    /// Override: plain fixed-matrix iterations (no Anderson acceleration).
    pub plain: bool,
    /// Override: friction scheme of every tangential law.
    pub friction_scheme: Option<crate::interface::FrictionScheme>,
}

/// Loads a case and applies command-line overrides.
pub fn load_model(case_path: &Path, opts: &RunOptions) -> Result<Model> {
    let mut case = Case::load(case_path)?;
    if let Some(m) = opts.method {
        case.solver.method = m;
    }
    if let Some(r) = opts.refine {
        case.mesh.refine = r;
    }
    if let Some(n) = opts.increments {
        case.solver.increments = n;
        case.solver.first_increment = None;
        case.solver.load_factors = None;
    }
    if let Some(c) = opts.max_cutbacks {
        case.solver.max_cutbacks = c;
    }
    if opts.plain {
        case.solver.acceleration = crate::case::Acceleration::None;
    }
    if let Some(fs) = opts.friction_scheme {
        for spec in case.interface.values_mut() {
            if let Some(t) = spec.tangential.as_mut() {
                t.scheme = fs;
            }
        }
    }
    if opts.uniform {
        if case.mesh.file.is_some() {
            return Err(crate::error::Error::input(
                format!("{}: [mesh] file", case.source.display()),
                "--uniform cannot regrade a mesh read from a file",
            ));
        }
        for b in &mut case.mesh.block {
            b.rx.clear();
            b.ry.clear();
        }
    }
    Model::build(case)
}

/// Runs a case to completion on the serial backend and writes its output
/// folder. Returns the folder, the model and the result.
pub fn run(case_path: &Path, opts: &RunOptions) -> Result<(PathBuf, Model, RunResult)> {
    let started = Instant::now();
    let model = load_model(case_path, opts)?;
    let mut engine = Engine::new(&model, model.case.solver.method)?;
    engine.fault = opts.fault;
    let (dir, result) = run_model(&model, engine, opts, true, started)?;
    Ok((dir, model, result))
}

/// Runs a built model with an engine. `write`: this process writes the output
/// and prints progress (rank 0 under MPI).
pub fn run_model(
    model: &Model,
    engine: Engine,
    opts: &RunOptions,
    write: bool,
    started: Instant,
) -> Result<(PathBuf, RunResult)> {
    let dir = opts
        .out
        .clone()
        .unwrap_or_else(|| Path::new("out").join(&model.name));
    let planned = model.case.solver.schedule().len();
    if !write {
        let result = solve::run_with(engine, &mut Silent)?;
        return Ok((dir, result));
    }
    if !opts.quiet {
        eprintln!(
            "asperity: {} — {} dofs, {} elements, {} interface pairs, {}, {} on {} rank(s) ({} increments planned)",
            model.name,
            model.mesh.num_dofs(),
            model.mesh.elements.len(),
            model.interfaces.iter().map(|i| i.pairs.len()).sum::<usize>(),
            model.case.solver.method.name(),
            engine.backend.name(),
            engine.backend.ranks(),
            planned
        );
    }
    let mut writer = Writer::new(&dir, opts.quiet, planned)?;
    match solve::run_with(engine, &mut writer) {
        Ok(result) => {
            let wall = started.elapsed().as_secs_f64();
            let dir = writer.finish(model, &result, wall)?;
            Ok((dir, result))
        }
        Err(e) => {
            writer.abandon();
            Err(e)
        }
    }
}

/// An observer that does nothing (ranks other than 0).
struct Silent;

impl crate::solve::Observer for Silent {
    fn increment(
        &mut self,
        _: &Model,
        _: &crate::solve::State,
        _: &crate::solve::Increment,
    ) -> Result<()> {
        Ok(())
    }
}

/// `asperity check`: validates a case and describes what would be solved.
pub fn check(case_path: &Path) -> Result<String> {
    let model = load_model(case_path, &RunOptions::default())?;
    let c = &model.case;
    let mut s = format!("{}: valid\n", model.name);
    if let Some(d) = &c.description {
        s += &format!("  {}\n", d.trim());
    }
    s += &format!(
        "  plane {:?}, thickness {} mm, {:?} integration ({} Gauss points per element)\n",
        model.plane,
        model.thickness,
        c.model.integration,
        model.n_gauss()
    );
    s += &format!(
        "  mesh: {} nodes, {} elements, {} dofs ({} free), {} nonzeros in the tangent\n",
        model.mesh.nodes.len(),
        model.mesh.elements.len(),
        model.mesh.num_dofs(),
        model.dofs.n_eq,
        model.asm.nnz()
    );
    for (b, name) in model.mesh.bodies.iter().enumerate() {
        let m = &model.materials[b];
        s += &format!(
            "  body {name}: E = {} MPa, ν = {}, σ_Y = {} MPa, H = {} MPa\n",
            m.young, m.poisson, m.yield_stress, m.hardening
        );
    }
    for im in &model.interfaces {
        s += &format!(
            "  interface {}: {} pairs, {} points, area {:.4} mm², law {:?}\n",
            im.name,
            im.pairs.len(),
            im.points.len(),
            im.area(),
            im.law
        );
    }
    let sched = c.solver.schedule();
    s += &format!(
        "  solver: {}, {} increments (first {:.4}, last {:.4}), ≤ {} iterations each, ≤ {} cutbacks\n",
        c.solver.method.name(),
        sched.len(),
        sched[0],
        sched[sched.len() - 1],
        c.solver.iteration_limit(),
        c.solver.max_cutbacks
    );
    Ok(s)
}
