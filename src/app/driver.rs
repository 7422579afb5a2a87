//! The top-level jobs behind the command line: `run` and `check`.

pub use super::options::RunOptions;
use crate::error::Result;
use crate::files::output::{Resume, Writer};
use crate::input::case::{Case, Method};
use crate::model::Model;
use crate::physics::element::family::Family;
use crate::progress::Log;
use crate::solve::{self, Checkpoint, Control, Engine, RunResult};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Refuses an output folder that would destroy input: `--out` replaces the
/// folder it names as a whole, so it must not be (or hold) an input of the
/// run (the case file or folder, its Gmsh mesh), and it must not name an
/// existing file.
pub fn check_out(out: Option<&Path>, inputs: &[&Path]) -> Result<()> {
    let Some(out) = out else { return Ok(()) };
    let err = |msg: String| Err(crate::error::Error::input("--out", msg));
    if out.exists() && !out.is_dir() {
        return err(format!(
            "{} is a file; the output is a folder that the run replaces as a whole: name a folder or a new path",
            out.display()
        ));
    }
    // where `out` is or would be, links resolved
    let resolved = if out.exists() {
        out.canonicalize().ok()
    } else {
        let parent = out
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        match (parent.canonicalize(), out.file_name()) {
            (Ok(p), Some(name)) => Some(p.join(name)),
            _ => None,
        }
    };
    let Some(o) = resolved else { return Ok(()) };
    for input in inputs {
        if input.canonicalize().is_ok_and(|c| c.starts_with(&o)) {
            return err(format!(
                "{} holds {}, an input of this run, and the run replaces that folder as a whole: choose an output folder elsewhere",
                out.display(),
                input.display()
            ));
        }
    }
    Ok(())
}

/// Loads a case and applies command-line overrides.
pub fn load_model(case_path: &Path, opts: &RunOptions) -> Result<Model> {
    Model::build(load_case(case_path, opts)?)
}

/// Reads a case and applies the command-line overrides (not yet checked:
/// [`Model::build`] checks it).
pub(crate) fn load_case(case_path: &Path, opts: &RunOptions) -> Result<Case> {
    let mut case = Case::load(case_path)?;
    if let Some(file) = &case.mesh.file {
        let dir = case.source.parent().unwrap_or(Path::new(""));
        check_out(opts.out.as_deref(), &[&dir.join(file)])?;
    }
    // each override is recorded with the keys it replaces, so that a
    // refusal of the setting names the option, not the case file's key
    // (`Case::at`)
    override_method_and_adapt(&mut case, opts)?;
    override_steps(&mut case, opts)?;
    override_scheme_and_grading(&mut case, opts)?;
    Ok(case)
}

/// `--method`, `--refine` and `--adapt`; refuses an adaptive run resumed
/// from `--restart`.
fn override_method_and_adapt(case: &mut Case, opts: &RunOptions) -> Result<()> {
    let o = &mut case.overrides;
    if let Some(m) = opts.method {
        case.solver.method = m;
        o.set("[solver] method", format!("--method {}", m.name()));
    }
    if let Some(r) = opts.refine {
        case.mesh.refine = r;
        o.set("[mesh] refine", format!("--refine {r}"));
    }
    if let Some(t) = opts.adapt {
        let option = format!("--adapt {}", crate::numbers::exact(t));
        case.adapt = Some(match case.adapt.take() {
            Some(a) => {
                o.set("[adapt] tolerance", option);
                crate::input::case::adapt::AdaptSpec { tolerance: t, ..a }
            }
            None => {
                // every key of the table: the defaults of `--adapt`
                o.set("[adapt]", option);
                crate::input::case::adapt::AdaptSpec::with_tolerance(t)
            }
        });
    }
    if case.adapt.is_some() && opts.restart.is_some() {
        // refused before the restart folder is read: its checkpoint is of
        // one cycle's mesh, and every cycle starts from the beginning
        return Err(crate::error::Error::input(
            case.at("[adapt]"),
            "an adaptive run solves every mesh from the start of the history: it cannot resume (--restart)",
        ));
    }
    Ok(())
}

/// `--increments`, `--max-cutbacks` and `--step-control`: the load steps;
/// a fixed schedule asked for drops the keys of the automatic control.
fn override_steps(case: &mut Case, opts: &RunOptions) -> Result<()> {
    if let Some(n) = opts.increments {
        // fixed steps: N equal steps replace the case's schedule, which must
        // not be an explicit list (the case file refuses `increments` beside
        // `load_factors` too); automatic steps: `load_factors` are the
        // waypoints, kept, and N sizes the first step
        let auto = opts.step_control == Some(crate::input::case::StepControl::Auto);
        if case.solver.load_factors.is_some() && !auto {
            return Err(crate::error::Error::input(
                format!("--increments {n}"),
                format!(
                    "{} gives its load steps as [solver] load_factors: edit them, or add \
                     --step-control auto (the load factors as waypoints, 1/{n} the first step)",
                    case.source.display()
                ),
            ));
        }
        case.solver.increments = Some(n);
        case.solver.first_increment = None;
        case.overrides
            .set("[solver] increments", format!("--increments {n}"));
    }
    if let Some(c) = opts.max_cutbacks {
        case.solver.max_cutbacks = c;
        case.overrides
            .set("[solver] max_cutbacks", format!("--max-cutbacks {c}"));
    }
    match (opts.step_control, opts.increments) {
        (Some(sc), _) => {
            case.solver.step_control = Some(sc);
            case.overrides.set(
                "[solver] step_control",
                format!("--step-control {}", step_name(sc)),
            );
        }
        // `--increments N` alone: N equal steps, as its help says, also in a
        // case whose `[solver]` asks for automatic steps (which would take
        // N only as the size of its first step)
        (None, Some(n)) => {
            case.solver.step_control = Some(crate::input::case::StepControl::Fixed);
            case.overrides
                .set("[solver] step_control", format!("--increments {n}"));
        }
        (None, None) => {}
    }
    if (opts.increments.is_some() || opts.step_control.is_some())
        && case.solver.step_mode() == crate::input::case::StepControl::Fixed
    {
        // a fixed schedule asked for on the command line: the case's keys of
        // the automatic control no longer apply (a case refuses them beside
        // fixed steps)
        case.solver.max_increment = None;
        case.solver.plastic_strain_step = crate::input::case::default_plastic_strain_step();
    }
    Ok(())
}

/// `--plain`, `--interface-loop`, `--friction-scheme` and `--uniform` (the generated blocks
/// without their grading).
fn override_scheme_and_grading(case: &mut Case, opts: &RunOptions) -> Result<()> {
    if opts.plain {
        case.solver.acceleration = crate::input::case::Acceleration::None;
        case.overrides.set("[solver] acceleration", "--plain");
    }
    if let Some(on) = opts.interface_loop {
        case.solver.interface_loop = Some(on);
        case.overrides.set(
            "[solver] interface_loop",
            format!("--interface-loop {}", on_off(on)),
        );
    }
    if let Some(fs) = opts.friction_scheme {
        let option = format!("--friction-scheme {}", scheme_name(fs));
        for (name, spec) in case.interface.iter_mut() {
            if let Some(t) = spec.tangential.as_mut() {
                t.scheme = fs;
                case.overrides
                    .set(format!("[interface.{name}.tangential] scheme"), &option);
            }
        }
    }
    if opts.uniform {
        if case.mesh.file.is_some() {
            return Err(crate::error::Error::input(
                "--uniform",
                format!(
                    "cannot regrade a mesh read from a file ({}: [mesh] file)",
                    case.source.display()
                ),
            ));
        }
        case.overrides.graded_blocks = Some(case.mesh.block.clone());
        for b in &mut case.mesh.block {
            b.rx.clear();
            b.ry.clear();
        }
    }
    Ok(())
}

/// The serial backend's engine for a model, with the given method, its
/// element loop on `threads` threads (the factorization on
/// [`crate::linalg::backend::serial::FACTOR_THREADS`]): the backend factory of a run
/// on one process (the factorization follows the model's
/// [`Model::symmetric_tangent`]).
pub fn serial_engine(model: &Model, method: Method, threads: usize) -> Result<Engine<'_>> {
    let backend = crate::linalg::backend::serial::SerialBackend::new(model)?;
    let mut engine = Engine::with_backend(model, method, Box::new(backend));
    engine.set_threads(threads);
    Ok(engine)
}

/// [`serial_engine`] on a given factorization (benchmarks, tests).
pub(crate) fn serial_engine_on(
    model: &Model,
    method: Method,
    threads: usize,
    kind: crate::linalg::backend::serial::Factorization,
) -> Result<Engine<'_>> {
    let backend = crate::linalg::backend::serial::SerialBackend::with_factorization(model, kind)?;
    let mut engine = Engine::with_backend(model, method, Box::new(backend));
    engine.set_threads(threads);
    Ok(engine)
}

/// Runs the whole load history of a built model on the serial backend, with
/// the model's method, on every core, reporting to `observer` (no output
/// folder).
pub fn solve(model: &Model, observer: &mut dyn solve::Observer) -> Result<RunResult> {
    let threads = crate::threads::available();
    solve::run_with(
        serial_engine(model, model.solver.method, threads)?,
        observer,
    )
}

/// The one place an engine is made ready for a run, whatever its backend:
/// the memory stages so far ("model" when the model was built, "setup" now,
/// after the backend and solver objects) and the fault-injection test hook.
pub(crate) fn prepare(engine: &mut Engine, opts: &RunOptions, at_model: f64) {
    engine.stats.memory_mb = vec![
        ("model", at_model),
        ("setup", crate::solve::peak_memory_mb()),
    ];
    engine.fault = opts.hooks.fault;
}

/// Runs a case to completion on the serial backend and writes its output
/// folder. Returns the folder, the model and the result.
pub fn run(case_path: &Path, opts: &RunOptions) -> Result<(PathBuf, Model, RunResult)> {
    let started = Instant::now();
    let case = load_case(case_path, opts)?;
    if case.adapt.is_some() {
        let mut solve = |model: &Model, started: Instant| {
            let mut engine = serial_engine(
                model,
                model.solver.method,
                opts.threads.unwrap_or_else(crate::threads::available),
            )?;
            prepare(&mut engine, opts, crate::solve::peak_memory_mb());
            run_cycle(model, engine, opts, true, started)
        };
        return crate::app::adapt::run(case, opts, true, &mut solve, &|_| {});
    }
    let model = Model::build(case)?;
    let at_model = crate::solve::peak_memory_mb();
    let threads = opts.threads.unwrap_or_else(crate::threads::available);
    let mut engine = match opts.hooks.factorization {
        Some(kind) => serial_engine_on(&model, model.solver.method, threads, kind)?,
        None => serial_engine(&model, model.solver.method, threads)?,
    };
    prepare(&mut engine, opts, at_model);
    let (dir, result) = run_model(&model, engine, opts, true, started)?;
    Ok((dir, model, result))
}

/// Runs a built model with an engine. `write`: this process writes the output
/// and prints progress (rank 0 under MPI). With `opts.restart` every rank reads
/// the checkpoint and continues from it.
pub(crate) fn run_model(
    model: &Model,
    engine: Engine,
    opts: &RunOptions,
    write: bool,
    started: Instant,
) -> Result<(PathBuf, RunResult)> {
    run_model_as(model, engine, opts, write, started, false)
}

/// [`run_model`] for one cycle of an adaptive run ([`crate::app::adapt`]): a
/// cycle stopped early (SIGINT, SIGTERM, `--stop-after`) writes nothing, so
/// the output folder keeps the previous cycle's complete run; the caller
/// reports the stop.
pub(crate) fn run_cycle(
    model: &Model,
    engine: Engine,
    opts: &RunOptions,
    write: bool,
    started: Instant,
) -> Result<(PathBuf, RunResult)> {
    run_model_as(model, engine, opts, write, started, true)
}

fn run_model_as(
    model: &Model,
    engine: Engine,
    opts: &RunOptions,
    write: bool,
    started: Instant,
    cycle: bool,
) -> Result<(PathBuf, RunResult)> {
    crate::verdict::prepare(model)?;
    let dir = opts
        .out
        .clone()
        .unwrap_or_else(|| Path::new("out").join(&model.name));
    // 0: automatic step control, the count is not known in advance
    let planned =
        solve::stepping::Stepper::planned(&model.solver, &model.breakpoints()).unwrap_or(0);
    let control = Control {
        stop_after: opts.hooks.stop_after,
    };
    let (start, pvd) = match &opts.restart {
        Some(from) => crate::files::restart::read(from, model)?,
        None => (Checkpoint::initial(model), Vec::new()),
    };
    if !write {
        let result = solve::run_from(engine, &mut Silent, start, control)?;
        return Ok((dir, result));
    }
    let mut log = Log::new(opts.log_format, opts.quiet);
    let lambda_end = start.stepper.final_target(start.lambda);
    log.range(start.lambda, lambda_end);
    let resumed = start.increments.len();
    let run = RunStart {
        model,
        opts,
        dir: &dir,
        planned,
    };
    run.log_start(&log, &engine, &start);
    let resume = opts.restart.as_deref().map(|d| Resume {
        dir: d,
        files: crate::files::restart::folder_files(
            &crate::files::restart::Bounds::of(model),
            resumed,
            &pvd,
        ),
        pvd,
    });
    let mut writer = Writer::new(&dir, log.clone(), planned, resume)?;
    writer.final_load_factor = lambda_end;
    match solve::run_from(engine, &mut writer, start, control) {
        Ok(result) if cycle && result.stopped.is_some_and(|s| s.resumable()) => {
            // not a result of the history: no partial folder replaces the
            // previous cycle's complete one (and none could be resumed)
            writer.abandon();
            Ok((dir, result))
        }
        Ok(result) => run.finish(&log, writer, result, started),
        Err(e) => {
            writer.abandon();
            Err(e)
        }
    }
}

/// What a written run starts from: the model, the options, its output
/// folder and the increments planned (0: automatic steps).
struct RunStart<'a> {
    model: &'a Model,
    opts: &'a RunOptions,
    dir: &'a Path,
    planned: usize,
}

impl RunStart<'_> {
    /// The `start` event: the problem's size, the backend, the increments
    /// planned and where a resumed run continues from.
    fn log_start(&self, log: &Log, engine: &Engine, start: &Checkpoint) {
        let (model, opts, dir, planned) = (self.model, self.opts, self.dir, self.planned);
        let pairs: usize = model.interfaces.iter().map(|i| i.pairs.len()).sum();
        let resumed = start.increments.len();
        log.progress(
        "start",
        json!({
            "case": model.name,
            "dofs": model.mesh.num_dofs(),
            "elements": model.mesh.elements.len(),
            "interface_pairs": pairs,
            "method": model.solver.method.name(),
            "backend": engine.backend.name(),
            "ranks": engine.backend.ranks(),
            "threads": engine.threads(),
            "planned": planned,
            "resumed_from": resumed,
            "load_factor": start.lambda,
            "output": dir.display().to_string(),
        }),
        || {
            let mut line = format!(
                "asperity: {} — {} dofs, {} elements, {} interface pairs, {}, {} on {} rank(s) × {} thread(s) ({})",
                model.name,
                model.mesh.num_dofs(),
                model.mesh.elements.len(),
                pairs,
                model.solver.method.name(),
                engine.backend.name(),
                engine.backend.ranks(),
                engine.threads(),
                if planned > 0 {
                    format!("{planned} increments planned")
                } else {
                    "automatic steps".to_string()
                }
            );
            if let Some(from) = &opts.restart {
                line += &format!(
                    "; resuming after increment {resumed} (λ = {:.4}) from {}",
                    start.lambda,
                    from.display()
                );
            }
            let dofs = model.mesh.num_dofs();
            if model.mesh.dim() == 3
                && engine.backend.ranks() == 1
                && engine.backend.name().starts_with("serial")
                && dofs > crate::linalg::backend::DIRECT_3D_UP_TO
            {
                line += &format!(
                    "\nnote: a 3D model of {dofs} dofs on the serial direct solver: its factor grows fast in 3D (89,364 dofs: 2.0 GB, 38 s an iteration); `mpirun -n 2 asperity run …` solves it with CG + GAMG, 6 times faster there (docs/performance.md, \"3D: choosing the solver\")"
                );
            }
            line
        },
    );
    }

    /// A run that reached the end of its history (or stopped where it may be
    /// resumed): the output folder finished, the `finish` or `stop` event
    /// and the warnings of its result.
    fn finish(
        &self,
        log: &Log,
        writer: Writer,
        mut result: RunResult,
        started: Instant,
    ) -> Result<(PathBuf, RunResult)> {
        let (model, opts) = (self.model, self.opts);
        let wall = started.elapsed().as_secs_f64();
        result.estimate = writer.last_estimate().cloned();
        let dir = writer.finish(model, &result, wall)?;
        // a stopped run continues where it was written (`--out` may
        // name the restart folder itself)
        let mut again = override_args(opts);
        if opts.out.is_some() {
            again += &format!(" --out {}", dir.display());
        }
        // the peaks at singular points qualify the numbers the end prints:
        // said before them, not as warnings (summary.json `singular`)
        let singular = crate::files::output::singular::run_flags(model, &result);
        for w in crate::files::output::singular::lines(model, &singular) {
            log.progress("singular", json!({ "message": w }), || {
                format!("singular: {w}")
            });
        }
        report_end(log, model, &dir, &result, wall, &again);
        for w in crate::files::output::warnings(model, &result) {
            log.always("warning", json!({ "message": w }), || {
                format!("warning: {w}")
            });
        }
        Ok((dir, result))
    }
}

/// The overrides of the model given on the command line, as `asperity run`
/// arguments (each with a leading space): a restart must be given the same
/// ones (the restart file's fingerprint), so the suggested command repeats
/// them.
fn override_args(o: &RunOptions) -> String {
    let mut a = String::new();
    if let Some(m) = o.method {
        a += &format!(" --method {}", m.name());
    }
    if let Some(r) = o.refine {
        a += &format!(" --refine {r}");
    }
    if o.uniform {
        a += " --uniform";
    }
    if let Some(n) = o.increments {
        a += &format!(" --increments {n}");
    }
    if let Some(sc) = o.step_control {
        a += &format!(" --step-control {}", step_name(sc));
    }
    if let Some(c) = o.max_cutbacks {
        a += &format!(" --max-cutbacks {c}");
    }
    if o.plain {
        a += " --plain";
    }
    if let Some(fs) = o.friction_scheme {
        a += &format!(" --friction-scheme {}", scheme_name(fs));
    }
    if let Some(on) = o.interface_loop {
        a += &format!(" --interface-loop {}", on_off(on));
    }
    a
}

/// `--interface-loop`'s value.
fn on_off(on: bool) -> &'static str {
    if on {
        "on"
    } else {
        "off"
    }
}

/// `--step-control`'s value for a step control.
fn step_name(sc: crate::input::case::StepControl) -> &'static str {
    match sc {
        crate::input::case::StepControl::Fixed => "fixed",
        crate::input::case::StepControl::Auto => "auto",
    }
}

/// `--friction-scheme`'s value for a scheme.
fn scheme_name(fs: crate::input::case::settings::FrictionScheme) -> &'static str {
    match fs {
        crate::input::case::settings::FrictionScheme::ReturnMapping => "return-mapping",
        crate::input::case::settings::FrictionScheme::StiffnessModification => {
            "stiffness-modification"
        }
    }
}

/// The `finish` (progress) or `stop` (always) event of a run that wrote
/// `dir`; `overrides`: [`override_args`] of the run.
fn report_end(log: &Log, model: &Model, dir: &Path, r: &RunResult, wall: f64, overrides: &str) {
    let last = r.increments.last();
    let m = last.map(|i| i.measures).unwrap_or_default();
    let lambda = last.map_or(0.0, |i| i.load_factor);
    let fy = r.first_yield.as_ref();
    if let Some(stop) = r.stopped.filter(|s| s.resumable()) {
        stop_end(log, model, dir, r, (stop, overrides));
        return;
    }
    log.progress(
        "finish",
        json!({
            "output": dir.display().to_string(),
            "increments": r.increments.len(),
            "newton_iterations": r.stats.iterations,
            "cutbacks": r.cutbacks,
            "load_factor": lambda,
            "total_load_kn": m.total_load_kn,
            "mean_pressure_mpa": m.mean_pressure,
            "center_displacement_mm": m.center_displacement,
            "first_yield_kn": fy.map(|f| f.total_load_kn),
            "wall_seconds": crate::progress::round3(wall),
        }),
        || {
            let mut s = String::new();
            let contact = !model.interfaces.is_empty();
            match fy {
                Some(fy) if contact => {
                    s += &format!(
                        "first yield: {:.4} kN ({:.2} MPa mean pressure) in {} at x = {:.3} mm, depth {:.3} mm\n",
                        fy.total_load_kn, fy.mean_pressure, fy.body, fy.x, fy.depth
                    );
                }
                // no interface force to name: the load factor and the place
                Some(fy) => {
                    let y = model.surface_y - fy.depth;
                    let at = if model.mesh.dim() == 3 {
                        format!("(x, y, z) = ({:.3}, {y:.3}, {:.3}) mm", fy.x, fy.z)
                    } else {
                        format!("(x, y) = ({:.3}, {y:.3}) mm", fy.x)
                    };
                    s += &format!(
                        "first yield: λ = {:.4} in {} at {at}\n",
                        fy.load_factor, fy.body
                    );
                }
                None => {}
            }
            for e in r.events.iter().filter(|e| e.interface.is_some()) {
                s += &crate::files::output::events::line(model, e);
                s.push('\n');
            }
            s += &crate::app::applied::end_text(model, lambda);
            s += &crate::app::ratings::end_text(model, r);
            if contact {
                s += &format!(
                    "final: {:.4} kN, mean pressure {:.2} MPa, center displacement {:.5} mm; ",
                    m.total_load_kn, m.mean_pressure, m.center_displacement,
                );
            } else {
                s += &format!("final: λ = {lambda:.4}; ");
            }
            s += &format!(
                "{} increments, {} iterations",
                r.increments.len(),
                r.stats.iterations
            );
            s
        },
    );
    if let Some(stop) = r.stopped {
        limit_end(log, model, dir, r, stop);
    }
}

/// The `stop` event of a run stopped where it may be resumed (a signal,
/// `--stop-after`): where its partial results are and how to continue.
fn stop_end(
    log: &Log,
    model: &Model,
    dir: &Path,
    r: &RunResult,
    (stop, overrides): (crate::interrupt::Stop, &str),
) {
    let last = r.increments.last();
    let m = last.map(|i| i.measures).unwrap_or_default();
    let lambda = last.map_or(0.0, |i| i.load_factor);
    let planned = solve::stepping::Stepper::planned(&model.solver, &model.breakpoints());
    let case = model.source.display().to_string();
    log.always(
        "stop",
        json!({
            "stopped_by": stop.name(),
            "increments": r.increments.len(),
            "planned": planned,
            "load_factor": lambda,
            "total_load_kn": m.total_load_kn,
            "output": dir.display().to_string(),
            "restart": dir.join(crate::files::restart::FILE).display().to_string(),
            "exit_code": stop.exit_code(),
        }),
        || {
            format!(
                "stopped by {} after increment {}/{} (λ = {:.4}, {:.3} kN): partial results in {}; continue with `asperity run {}{} --restart {}`",
                stop.name(),
                r.increments.len(),
                planned.map_or("auto".into(), |p| p.max(r.increments.len()).to_string()),
                lambda,
                m.total_load_kn,
                dir.display(),
                case,
                overrides,
                dir.display()
            )
        },
    );
}

/// The `stop` event of a run that ended at its torque limit (not to be
/// resumed: the history has no equilibrium past it).
fn limit_end(log: &Log, model: &Model, dir: &Path, r: &RunResult, stop: crate::interrupt::Stop) {
    let Some(e) = (r.events.iter()).find(|e| e.kind == solve::events::Kind::TorqueLimit) else {
        return;
    };
    let body = (e.body())
        .and_then(|b| model.mesh.bodies.get(b))
        .cloned()
        .unwrap_or_default();
    let lambda = r.increments.last().map_or(0.0, |i| i.load_factor);
    let speed = model
        .rpm(e.load_factor)
        .map_or(String::new(), |n| format!(" at {n:.6e} rpm"));
    log.always(
        "stop",
        json!({
            "stopped_by": stop.name(),
            "body": body,
            "event_load_factor": e.load_factor,
            "speed_rpm": model.rpm(e.load_factor),
            "increments": r.increments.len(),
            "load_factor": lambda,
            "output": dir.display().to_string(),
            "exit_code": stop.exit_code(),
        }),
        || {
            format!(
                "ended at the torque limit: body \"{body}\" can no longer hold the torque on it past λ = {:.6}{speed} (event torque_limit): the load history has no equilibrium beyond; results up to increment {} (λ = {lambda:.6}) in {}",
                e.load_factor,
                r.increments.len(),
                dir.display()
            )
        },
    );
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

/// `asperity check`: validates a case with the overrides of `opts` (the
/// others are `run`'s alone) and describes what that run would solve.
pub fn check(case_path: &Path, opts: &RunOptions) -> Result<String> {
    let case = load_case(case_path, opts)?;
    let adapt = case.adapt.clone();
    let model = Model::build(case)?;
    let ratings = crate::verdict::prepare(&model)?;
    // a table the applied load alone takes far beyond its data
    let place = model.source.display().to_string();
    for t in predicted(&model) {
        if t.far() {
            eprintln!(
                "warning: {}",
                t.warning(&place, "the applied load's mean pressure alone needs")
            );
        }
    }
    let mut s = format!("{}: valid", model.name);
    let overrides = override_args(opts);
    if !overrides.is_empty() {
        s += &format!(" with{overrides}");
    }
    s.push('\n');
    if let Some(d) = &model.description {
        s += &format!("  {}\n", d.trim());
    }
    s += &plane_text(&model);
    s += &bodies_text(&model);
    s += &interfaces_text(&model);
    s += &crate::app::applied::check_text(&model);
    for line in ratings {
        s += &format!("  {line}\n");
    }
    s += &outputs_text(&model);
    s += &steps_text(&model);
    if let Some(a) = &adapt {
        s += &adapt_text(a, &model);
    }
    Ok(s)
}

/// `check`'s lines of the plane (or axisymmetry), the integration and the
/// mesh's size.
/// "9 Gauss points per element", or per family in a mixed mesh.
fn points_per_element(model: &Model) -> String {
    let present: Vec<Family> = Family::ALL
        .into_iter()
        .chain(Family::SOLID)
        .filter(|&f| model.mesh.elements.iter().any(|el| el.family == f))
        .collect();
    match present.as_slice() {
        [f] => format!("{} Gauss points per element", model.points_of(*f)),
        _ => {
            let each: Vec<String> = present
                .iter()
                .map(|&f| format!("{} per {}", model.points_of(f), f.name()))
                .collect();
            format!("Gauss points: {}", each.join(", "))
        }
    }
}

fn plane_text(model: &Model) -> String {
    let mut s = String::new();
    if model.section.axisymmetric {
        s += &format!(
            "  plane Axisymmetric{} (x = r, y = z; forces, areas and kN for the full revolution), {:?} integration ({})\n",
            if model.node_dofs().twist() {
                " with twist (u_θ, torques about the axis)"
            } else {
                ""
            },
            model.integration,
            points_per_element(model)
        );
    } else if model.mesh.dim() == 3 {
        s += &format!(
            "  3D solids (u_x, u_y, u_z), {:?} integration ({})\n",
            model.integration,
            points_per_element(model)
        );
    } else {
        s += &format!(
            "  plane {:?}, thickness {} mm, {:?} integration ({})\n",
            model.plane,
            model.thickness,
            model.integration,
            points_per_element(model)
        );
    }
    s += &format!(
        "  mesh: {} nodes, {} elements, {} dofs ({} free), {} nonzeros in the tangent\n",
        model.mesh.nodes.len(),
        model.mesh.elements.len(),
        model.mesh.num_dofs(),
        model.dofs.n_eq,
        model.pattern().nnz()
    );
    if let Some(c) = &model.cyclic {
        s += &cyclic_text(c);
    }
    s
}

/// `check`'s line of a cyclic sector: its angle, its faces, its ties, and
/// which numbers are the whole part's.
fn cyclic_text(c: &crate::model::cyclic::Cyclic) -> String {
    let ties = 3 * c.pairs.len() - c.held_alike;
    format!(
        "  cyclic sector, 1 of {n}: \"{}\" turned {}° about the y axis is \"{}\"; {} node pairs tied (u = R u, {ties} constraints{}), {} nodes on the axis (u_x = u_z = 0); loads and reactions are the sector's, a reaction's fy_part_n and my_part_nmm the whole part's ({n} ×)\n",
        c.faces[0],
        crate::numbers::num(c.degrees()),
        c.faces[1],
        c.pairs.len(),
        match c.held_alike {
            0 => String::new(),
            k => format!(", {k} held alike by the supports"),
        },
        c.axis.len(),
        n = c.sectors,
    )
}

/// `check`'s line of each body: its material, and a body held about the
/// axis only by friction.
fn bodies_text(model: &Model) -> String {
    let mut s = String::new();
    let own = crate::model::supports::own_rotation(&model.mesh, &model.prescribed);
    for (b, name) in model.mesh.bodies.iter().enumerate() {
        let m = &model.materials[b];
        s += &format!(
            "  body {name}: E = {} MPa, ν = {}, σ_Y = {} MPa, H = {} MPa\n",
            m.young, m.poisson, m.yield_stress, m.hardening
        );
        if let Some(t) = model.temperatures.iter().find(|t| t.body == b) {
            let from = t
                .reference
                .map_or(String::new(), |r| format!(" from {r} °C"));
            let by = match t.history {
                Some(_) => "its history",
                None => "the load factor",
            };
            s += &format!(
                "    temperature: ΔT = {} K{from} (× {by}), free thermal strain α ΔT = {:e}\n",
                t.change, t.strain
            );
            s += &field_text(t.field.as_ref());
            if t.varies() {
                s += "    E and σ_Y read off their tables at each Gauss point's temperature (its field)\n";
            } else if t.young.is_some() || t.yield_stress.is_some() {
                s += "    E and σ_Y read off their tables at the body's temperature\n";
            }
        }
        if let Some(sp) = &model.speed {
            s += &speed_text(model, sp, b);
        }
        if model.node_dofs().twist() && !own[b] {
            let by: Vec<&str> = (model.interfaces.iter())
                .filter(|im| im.tangential.is_some() && (im.body_a == b || im.body_b == b))
                .map(|im| im.name.as_str())
                .collect();
            s += &format!(
                "    about the axis: no rotation of its own, held only by the friction of interface \"{}\" (past Σ μ p_N r dA a torque on it has no equilibrium)\n",
                by.join("\", \"")
            );
        }
    }
    s
}

/// `check`'s line of a body's temperature field, if it has one.
fn field_text(field: Option<&crate::model::loads::thermal::Field>) -> String {
    use crate::model::loads::thermal::Field;
    match field {
        None => String::new(),
        Some(Field::Profile(p)) => {
            let rows: Vec<String> = (p.rows.iter())
                .map(|r| format!("{} at {}", r[1], r[0]))
                .collect();
            format!(
                "    temperature field: ΔT × the factor along {} (mm): {}\n",
                p.along.name(),
                rows.join(", ")
            )
        }
        Some(f @ Field::Formula(_)) => {
            let (lo, hi) = f.extremes();
            format!("    temperature field: ΔT × the factor given by `field`, {lo} … {hi} over the body\n")
        }
    }
}

/// `check`'s line of a spinning body: its density, the speed, and the scale
/// ρ ω² r² of its hoop stress at its largest radius.
fn speed_text(model: &Model, sp: &crate::model::loads::speed::Speed, b: usize) -> String {
    let dim = model.mesh.dim();
    let axi = model.section.axisymmetric;
    let r = (model.mesh.elements.iter())
        .filter(|e| e.body == b)
        .flat_map(|e| e.nodes().iter())
        .map(|&n| crate::model::loads::speed::radius(model.mesh.nodes[n], dim, axi))
        .fold(0.0f64, f64::max);
    let by = match sp.history {
        Some(_) => "its history",
        None => "the load factor",
    };
    format!(
        "    spinning: ρ = {} kg/m³ at n = {} rpm (ω = {:.6e} rad/s, × {by}); out to r = {r} mm, ρ ω² r² = {:.4e} MPa\n",
        sp.density[b],
        sp.rpm,
        sp.omega(),
        sp.hoop_scale(b, r)
    )
}

/// `check`'s lines of each interface: its size, laws and joint direction,
/// and the coupling and gaps of one meshed apart.
fn interfaces_text(model: &Model) -> String {
    let mut s = String::new();
    for im in &model.interfaces {
        let t = crate::model::interface::arcs::direction(im);
        s += &format!(
            "  interface {}: {} pairs, {} points, area {:.4} mm², law {}; A = {}, B = {}, joint direction t = ({}, {})\n",
            im.name,
            im.pairs.len(),
            im.points.len(),
            im.area(),
            im.law.describe(),
            model.mesh.bodies[im.body_a],
            model.mesh.bodies[im.body_b],
            t[0],
            t[1]
        );
        if let Some(law) = &im.tangential {
            s += &format!("    friction: {}\n", tangential_text(law, im.scheme));
        }
        // a non-matching interface: its coupling and the geometric gaps
        let gaps: Vec<f64> = im.points.iter().filter_map(|p| p.geometric_gap()).collect();
        if !gaps.is_empty() {
            let kind = if im.points.iter().any(|p| p.coupling.is_mortar()) {
                "mortar springs at A's nodes"
            } else if model.mesh.dim() == 3 {
                "node-to-surface springs at A's quadrature points"
            } else {
                "node-to-segment springs at A's quadrature points"
            };
            let widest = im
                .points
                .iter()
                .map(|p| im.point_ndofs(p))
                .max()
                .unwrap_or(0);
            let (lo, hi) = gaps
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &g| {
                    (l.min(g), h.max(g))
                });
            s += &format!(
                "    meshed apart (matching = false): {kind} (slave A, master B), up to {widest} dofs each; geometric gaps {lo:.4e} … {hi:.4e} mm\n"
            );
        }
    }
    s
}

/// `check`'s lines of the probes, the reaction groups and the load
/// histories' breakpoints.
fn outputs_text(model: &Model) -> String {
    let mut s = String::new();
    for p in &model.plan.probes {
        s += &format!("  probe {}: {}\n", p.name, p.describe(&model.mesh));
    }
    s += &format!(
        "  outputs: reactions of {} group(s) ({}); events bracketed to {} in load factor\n",
        model.plan.reactions.len(),
        model
            .plan
            .reactions
            .iter()
            .map(|g| g.name.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        model.plan.event_tolerance
    );
    let breakpoints = model.breakpoints();
    if !breakpoints.is_empty() {
        s += &format!(
            "  load histories: {}, breakpoints at t = {}; the run ends at t = {}\n",
            model.histories.len(),
            breakpoints
                .iter()
                .map(|t| t.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            solve::stepping::waypoints(&breakpoints)
                .last()
                .copied()
                .unwrap_or(1.0)
        );
    }
    s
}

/// `check`'s line of the adaptive run (and, with `max_von_mises`, the
/// line of the discs it leaves out).
fn adapt_text(a: &crate::input::case::adapt::AdaptSpec, model: &Model) -> String {
    use crate::input::case::adapt::{Over, Quantity};
    let what = match (a.quantity, a.over) {
        (Quantity::Energy, _) => "η/‖u_h‖_E".to_string(),
        (q, Over::End) => format!("the change of {} between two meshes", q.name()),
        (q, Over::History) => format!(
            "the change of {} (its largest over the history) between two meshes",
            q.name()
        ),
    };
    let mut s = format!(
        "  adaptive: the whole history solved again on each refined mesh until the estimate of {what} is at most {:e} (at most {} solves and {} dofs, refining the elements that hold {} of η²); the mesh above is the first\n",
        a.tolerance,
        a.max_cycles,
        a.max_dofs,
        a.fraction
    );
    if let Some(x) = &model.excluded {
        let discs: Vec<String> = x
            .discs
            .iter()
            .map(|d| {
                format!(
                    "{} at ({}, {}) within {:.4} mm",
                    d.corner,
                    crate::numbers::exact(d.x[0]),
                    crate::numbers::exact(d.x[1]),
                    d.radius
                )
            })
            .collect();
        s += &if discs.is_empty() {
            "  max_von_mises: no singular point, no Gauss point left out\n".to_string()
        } else {
            format!(
                "  max_von_mises leaves out {} of {} Gauss points, those of: {}\n",
                x.count(),
                x.points.len(),
                discs.join("; ")
            )
        };
    }
    s
}

/// The load steps as `check` prints them: the first increment's target as
/// the run takes it (the case's initial stepper asked from λ = 0,
/// [`solve::stepping::Stepper::first_target`]), then the fixed schedule's
/// length and end, or the automatic control's end and step bounds.
fn steps_text(model: &Model) -> String {
    let stepper = solve::stepping::Stepper::for_model(model);
    let first = stepper.first_target().unwrap_or(0.0);
    let solver = &model.solver;
    match stepper.mode() {
        crate::input::case::StepControl::Fixed => format!(
            "  solver: {}, {} increments (first to λ = {first}, last to λ = {}), ≤ {} iterations each, ≤ {} cutbacks\n",
            solver.method.name(),
            solve::stepping::Stepper::planned(solver, &model.breakpoints()).unwrap_or(0),
            stepper.final_target(0.0),
            solver.iteration_limit(),
            solver.max_cutbacks
        ),
        crate::input::case::StepControl::Auto => format!(
            "  solver: {}, automatic steps to λ = {} (first to λ = {first}, steps of at most {}, plastic strain ≈ {} per step), ≤ {} iterations each, ≤ {} cutbacks in a row\n",
            solver.method.name(),
            stepper.final_target(0.0),
            stepper.step_bounds().1,
            solver.plastic_strain_step,
            solver.iteration_limit(),
            solver.max_cutbacks
        ),
    }
}

/// The tangential law as `check` prints it: stiffness, backbone, memory
/// ([`crate::physics::contact::TangentialLaw::describe`]), then the scheme.
fn tangential_text(
    law: &crate::physics::contact::TangentialLaw,
    scheme: crate::input::case::settings::FrictionScheme,
) -> String {
    let scheme = match scheme {
        crate::input::case::settings::FrictionScheme::ReturnMapping => "return mapping",
        crate::input::case::settings::FrictionScheme::StiffnessModification => {
            "stiffness modification"
        }
    };
    format!("{}, {scheme}", law.describe())
}

/// The tables' use the applied loads alone predict, for `asperity check`:
/// at every waypoint of the load path (the load factors, or every history
/// breakpoint: the loads are linear between them, so their extremes are
/// there) the mean pressure p̄ of the applied loads on each interface
/// ([`crate::model::Model::applied_pressure`]) stands for p_N and, through
/// the normal law's inverse, for u_N. Where the applied load crosses the
/// interface, its largest point pressure is at least p̄: a far use predicted
/// here is certain. Loads the model does not apply (a prescribed
/// displacement) predict nothing; the run reports what it met.
fn predicted(model: &Model) -> Vec<crate::model::interface::extrapolation::TableUse> {
    let times = if model.histories.is_empty() {
        model
            .solver
            .load_factors
            .clone()
            .unwrap_or_else(|| vec![1.0])
    } else {
        crate::solve::stepping::waypoints(&model.breakpoints())
    };
    let reach: Vec<crate::model::interface::extrapolation::Reach> = model
        .interfaces
        .iter()
        .enumerate()
        .map(|(i, im)| {
            let p = times
                .iter()
                .map(|&t| model.applied_pressure(i, t))
                .fold(0.0, f64::max);
            crate::model::interface::extrapolation::Reach {
                u_n: im.law.approach(p),
                p_n: p,
            }
        })
        .collect();
    crate::model::interface::extrapolation::table_uses(&model.interfaces, &reach)
}
