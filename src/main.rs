//! The `asperity` command line.

use asperity::app::driver::{self, RunOptions};
use asperity::input::case::Method;
use asperity::progress::{Log, LogFormat};
use asperity::solve::RunResult;
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::process::ExitCode;

/// Elastic-plastic contact across a rough, compliant interface (Buczkowski & Kleiber 1992).
#[derive(Parser)]
#[command(name = "asperity", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a case and write its results (summary.json, curve.csv, interface/, vtu/).
    Run(RunArgs),
    /// Regenerate the paper's Figs 5, 6a/6b, 7a-c and 8 from runs of the shipped
    /// cases, as PNG, SVG and CSV.
    Figures {
        /// Folder holding the cases.
        #[arg(long, default_value = "cases")]
        cases: PathBuf,
        /// Output folder.
        #[arg(long, default_value = "docs/figures")]
        out: PathBuf,
    },
    /// Studies: mesh refinement (accuracy against cost) and load-step stability.
    #[command(subcommand)]
    Study(StudyCommand),
    /// An interface law from the surface: Greenwood-Williamson parameters or a
    /// measured profile → load-approach curve, best power law over a pressure
    /// range, and ready-to-paste [interface.*] tables (docs/calibration.md).
    Calibrate {
        /// Input file (materials, surface, fit range).
        input: PathBuf,
        /// Output folder: curve.csv, curve.svg/.png, fit.json, interface.toml.
        /// Replaced if it exists.
        #[arg(long)]
        out: PathBuf,
    },
    /// The calculation report of a finished run: one self-contained HTML file
    /// (OUT/report.html) with the model, the mesh, the key curves, each
    /// interface, the ratings, the results and the warnings (docs/output.md,
    /// "The calculation report").
    Report {
        /// Output folder of a finished run (what `asperity run CASE --out OUT` wrote).
        out: PathBuf,
        /// Write the HTML here instead of OUT/report.html (replaced if it exists).
        #[arg(long, value_name = "FILE")]
        output: Option<PathBuf>,
        /// Also print it to PDF beside the HTML (report.pdf) with a headless
        /// Chromium (chromium, chromium-browser or google-chrome on PATH).
        #[arg(long)]
        pdf: bool,
    },
    /// Validate a case and print what it would solve (dofs, increments, the
    /// first step), without solving; with `run`'s overrides, what that run
    /// would solve.
    Check {
        /// Case file (case.toml) or the folder that holds it.
        case: PathBuf,
        #[command(flatten)]
        overrides: Overrides,
    },
}

/// The overrides of the case's keys, of `run` and `check` alike
/// (docs/running.md): a refusal of a setting one of them made names it.
#[derive(Args)]
struct Overrides {
    /// Override the solution method of the case.
    #[arg(long, value_enum)]
    method: Option<MethodArg>,
    /// Override the mesh refinement factor of the case.
    #[arg(long)]
    refine: Option<usize>,
    /// An adaptive run to this relative estimate, in (0, 1): solve, estimate
    /// the error, refine where it is, solve again from the start, until the
    /// estimate is below TOL (the case's `[adapt]` table, else the energy norm;
    /// docs/running.md, "Adaptive runs").
    #[arg(long, value_name = "TOL", allow_hyphen_values = true)]
    adapt: Option<String>,
    /// Override: this many equal load steps (fixed steps; with
    /// `--step-control auto`, the size of the automatic control's first step).
    #[arg(long)]
    increments: Option<usize>,
    /// Override: halvings allowed per scheduled step (0: fail at the first failure).
    #[arg(long)]
    max_cutbacks: Option<usize>,
    /// Override: an ungraded mesh with the same element counts.
    #[arg(long)]
    uniform: bool,
    /// Override: no Anderson acceleration of modified Newton / initial stiffness.
    #[arg(long)]
    plain: bool,
    /// Override: load steps `fixed` (the case's schedule) or `auto` (adapted to
    /// iterations and plastic strain; see docs/case-schema.md).
    #[arg(long, value_parser = parse_step_control)]
    step_control: Option<asperity::input::case::StepControl>,
    /// Override: the interface loop of full Newton, `on` or `off` (`[solver]
    /// interface_loop`; unset, on for the serial backend and off on PETSc:
    /// docs/parallel.md).
    #[arg(long, value_name = "on|off", value_parser = parse_on_off)]
    interface_loop: Option<bool>,
    /// Override: friction scheme (return-mapping | stiffness-modification).
    #[arg(long, value_parser = parse_scheme)]
    friction_scheme: Option<asperity::input::case::settings::FrictionScheme>,
}

impl Overrides {
    /// The run's options with these overrides (`--adapt` checked).
    fn options(&self) -> asperity::error::Result<RunOptions> {
        let adapt = match self.adapt.as_deref() {
            None => None,
            Some(text) => Some(parse_adapt(text)?),
        };
        Ok(RunOptions {
            adapt,
            method: self.method.map(Into::into),
            refine: self.refine,
            increments: self.increments,
            max_cutbacks: self.max_cutbacks,
            uniform: self.uniform,
            plain: self.plain,
            step_control: self.step_control,
            friction_scheme: self.friction_scheme,
            interface_loop: self.interface_loop,
            ..RunOptions::default()
        })
    }
}

/// The arguments of `asperity run`.
#[derive(Args)]
struct RunArgs {
    /// Case file (case.toml) or the folder that holds it.
    case: PathBuf,
    /// Output folder (default: out/<case name>). Replaced if it exists.
    #[arg(long)]
    out: Option<PathBuf>,
    /// No progress lines (a stop or an error is still reported).
    #[arg(long)]
    quiet: bool,
    /// Format of the progress lines on stderr: text, or json (one object per line).
    #[arg(long, value_enum, default_value = "text")]
    log_format: LogFormatArg,
    /// Continue the stopped run whose output folder is DIR (its restart.bin).
    #[arg(long, value_name = "DIR")]
    restart: Option<PathBuf>,
    /// Test hook: stop like SIGINT after N converged increments (exit 3).
    #[arg(long, value_name = "N", hide = true)]
    stop_after: Option<usize>,
    #[command(flatten)]
    overrides: Overrides,
    /// Threads of this process's element loop, 1 to 1024. Default: the
    /// ASPERITY_THREADS environment variable, else every core on one process
    /// and 1 per rank under MPI. Results do not depend on it (docs/running.md).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    threads: Option<String>,
    /// Linear-algebra backend: serial (faer), petsc (MPI; needs the `parallel`
    /// feature), or auto: petsc when started by mpirun (with the feature built
    /// in), else serial, which is faster on one process at every size and
    /// needs about 3 KB per dof (docs/performance.md, "Choosing the backend").
    #[arg(long, value_enum, default_value = "auto")]
    backend: BackendArg,
    /// Test hook: make the element loop fail on RANK at its N-th assembly
    /// (every later attempt too), e.g. `1:5`.
    #[arg(long, value_name = "RANK:N", value_parser = parse_fault, hide = true)]
    inject_fault: Option<(usize, usize)>,
    /// PETSc backend: the nonlinear solver of each load step. snes (default):
    /// PETSc's SNES (newtonls, full steps) calling our residual, tangent and
    /// convergence rules, so `-snes_monitor`, `-snes_linesearch_type` … apply;
    /// builtin: our own Newton loop calling KSP. Both take the same iterates.
    #[arg(long, value_enum, default_value = "snes")]
    nonlinear: NonlinearArg,
    /// PETSc backend with GAMG: lean trades time for memory (on more than
    /// one rank all-at-once Galerkin products, paid for by building the
    /// preconditioner once per load step, with a wider smoother interval);
    /// docs/performance.md has the measurements. Needs `--nonlinear snes`.
    #[arg(long, value_enum, default_value = "fast")]
    memory: MemoryArg,
    /// PETSc options after `--`, e.g. `-- -ksp_type cg -pc_type gamg -log_view`.
    #[arg(last = true)]
    petsc_options: Vec<String>,
}

#[derive(Subcommand)]
enum StudyCommand {
    /// The case on a sequence of meshes for each method and backend; Richardson
    /// reference; error against dofs and against wall time.
    Refine {
        /// Case file (case.toml) or the folder that holds it.
        case: PathBuf,
        /// Refinement factors, at least three, e.g. 1,2,3,4.
        #[arg(long, value_delimiter = ',', default_value = "1,2,3,4")]
        levels: Vec<usize>,
        /// Methods to compare.
        #[arg(
            long,
            value_delimiter = ',',
            value_enum,
            default_value = "full-newton,modified-newton,initial-stiffness"
        )]
        methods: Vec<MethodArg>,
        /// Levels for modified Newton and initial stiffness (default: --levels);
        /// they reach the same answers as full Newton at several times the cost.
        #[arg(long, value_delimiter = ',')]
        slow_levels: Option<Vec<usize>>,
        /// Also run PETSc on 1 and 2 ranks (needs the parallel build and mpirun).
        #[arg(long)]
        petsc: bool,
        /// Also run the ungraded mesh (full Newton, serial).
        #[arg(long)]
        uniform: bool,
        /// Also an adaptive run from the case's mesh (full Newton, serial, 8
        /// cycles): a point per cycle, its wall time summed over the cycles.
        #[arg(long)]
        adapt: bool,
        /// Folder for the pictures (PNG, SVG) and their CSV data.
        #[arg(long, default_value = "docs/figures")]
        out: PathBuf,
    },
    /// Load-step size × method (× friction scheme): converged or not, iterations,
    /// cutbacks, time; a map of where each method fails.
    Stability {
        /// Case file (case.toml) or the folder that holds it.
        case: PathBuf,
        /// Numbers of equal load steps.
        #[arg(long, value_delimiter = ',', default_value = "1,2,5,10,20,40")]
        steps: Vec<usize>,
        /// Methods to compare (each also without acceleration: `plain`).
        #[arg(
            long,
            value_delimiter = ',',
            value_enum,
            default_value = "full-newton,modified-newton,initial-stiffness"
        )]
        methods: Vec<MethodArg>,
        /// Also vary the friction scheme (cases with a tangential law).
        #[arg(long)]
        schemes: bool,
        /// Stop a run after this many seconds and count it as failed.
        #[arg(long, default_value_t = 120.0)]
        time_limit: f64,
        /// Folder for the map (PNG, SVG) and its CSV data.
        #[arg(long, default_value = "docs/figures")]
        out: PathBuf,
    },
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum LogFormatArg {
    Text,
    Json,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum MemoryArg {
    Fast,
    Lean,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum NonlinearArg {
    Snes,
    Builtin,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum BackendArg {
    Auto,
    Serial,
    Petsc,
}

fn parse_scheme(s: &str) -> Result<asperity::input::case::settings::FrictionScheme, String> {
    match s {
        "return-mapping" => Ok(asperity::input::case::settings::FrictionScheme::ReturnMapping),
        "stiffness-modification" => {
            Ok(asperity::input::case::settings::FrictionScheme::StiffnessModification)
        }
        _ => Err("expected return-mapping or stiffness-modification".into()),
    }
}

fn parse_step_control(s: &str) -> Result<asperity::input::case::StepControl, String> {
    match s {
        "fixed" => Ok(asperity::input::case::StepControl::Fixed),
        "auto" => Ok(asperity::input::case::StepControl::Auto),
        _ => Err("expected fixed or auto".into()),
    }
}

fn parse_on_off(s: &str) -> Result<bool, String> {
    match s {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err("expected on or off".into()),
    }
}

fn parse_fault(s: &str) -> Result<(usize, usize), String> {
    let (r, n) = s.split_once(':').ok_or("expected RANK:N")?;
    Ok((
        r.parse().map_err(|_| "bad rank")?,
        n.parse().map_err(|_| "bad N")?,
    ))
}

/// Launched by mpirun (Open MPI or MPICH/Hydra)?
fn under_mpirun() -> bool {
    ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE"]
        .iter()
        .any(|v| std::env::var_os(v).is_some())
}

/// What an MPI launcher told this process: the world size it announced (at
/// least rank + 1 when only a rank is set), this process's rank, and the
/// variable that said so. None when no launcher variable is set. Open MPI sets
/// OMPI_COMM_WORLD_SIZE / _RANK, MPICH's Hydra (and Slurm's PMI) PMI_SIZE /
/// PMI_RANK, PMIx launchers PMIX_RANK.
fn launcher() -> Option<(usize, usize, String)> {
    let num = |v: &str| {
        std::env::var(v)
            .ok()
            .and_then(|s| s.trim().parse::<usize>().ok())
    };
    let mut found: Option<(usize, usize, String)> = None;
    for (size_var, rank_var) in [
        (Some("OMPI_COMM_WORLD_SIZE"), "OMPI_COMM_WORLD_RANK"),
        (Some("PMI_SIZE"), "PMI_RANK"),
        (None, "PMIX_RANK"),
    ] {
        let size = size_var.and_then(num);
        let rank = num(rank_var);
        if size.is_none() && rank.is_none() {
            continue;
        }
        let rank = rank.unwrap_or(0);
        let size = size.unwrap_or(0).max(rank + 1);
        let said = match size_var.filter(|v| num(v).is_some()) {
            Some(v) => format!("{v}={size}"),
            None => format!("{rank_var}={rank}"),
        };
        if found.as_ref().is_none_or(|f| size > f.0) {
            found = Some((size, rank, said));
        }
    }
    found
}

/// A build without the `parallel` feature started as several MPI processes
/// would run that many independent serial solves into one output folder:
/// refused (exit 2), the message printed once, by rank 0.
fn refuse_serial_build_under_mpi() -> Option<ExitCode> {
    if cfg!(feature = "parallel") {
        return None;
    }
    let (size, rank, said) = launcher().filter(|l| l.0 > 1)?;
    if rank > 0 {
        return Some(ExitCode::from(2));
    }
    // before the command line is parsed: `--log-format json` looked up by hand
    let args: Vec<String> = std::env::args().collect();
    let json = args
        .windows(2)
        .any(|w| w[0] == "--log-format" && w[1] == "json")
        || args.iter().any(|a| a == "--log-format=json");
    let format = if json {
        LogFormat::Json
    } else {
        LogFormat::Text
    };
    Some(fail(
        format,
        &format!("started by an MPI launcher as {size} processes ({said}), but this asperity was built without the `parallel` feature: each process would run its own serial solve into the same output folder; build it with `cargo build --release --features parallel`, or start it without mpirun"),
    ))
}

#[derive(Clone, Copy, ValueEnum)]
enum MethodArg {
    FullNewton,
    ModifiedNewton,
    InitialStiffness,
}

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Method {
        match m {
            MethodArg::FullNewton => Method::FullNewton,
            MethodArg::ModifiedNewton => Method::ModifiedNewton,
            MethodArg::InitialStiffness => Method::InitialStiffness,
        }
    }
}

fn main() -> ExitCode {
    if let Some(code) = refuse_serial_build_under_mpi() {
        return code;
    }
    let cli = Cli::parse();
    let outcome = match cli.command {
        Command::Run(args) => return run(args),
        Command::Check { case, overrides } => overrides
            .options()
            .and_then(|opts| driver::check(&case, &opts))
            .map(|s| print!("{s}")),
        Command::Study(StudyCommand::Refine {
            case,
            levels,
            methods,
            slow_levels,
            petsc,
            uniform,
            adapt,
            out,
        }) => study_refine(
            &case,
            &levels,
            &methods,
            slow_levels,
            StudyLines {
                petsc,
                uniform,
                adapt,
            },
            &out,
        ),
        Command::Study(StudyCommand::Stability {
            case,
            steps,
            methods,
            schemes,
            time_limit,
            out,
        }) => study_stability(&case, &steps, methods, schemes, time_limit, &out),
        Command::Figures { cases, out } => figures(&cases, &out),
        Command::Report { out, output, pdf } => {
            asperity::app::report::report(&asperity::app::report::Request {
                dir: out,
                output,
                pdf,
            })
            .map(|files| {
                for f in files {
                    println!("{}", f.display());
                }
            })
        }
        Command::Calibrate { input, out } => asperity::app::calibrate::run(&input, &out).map(|w| {
            for warning in &w.warnings {
                eprintln!("warning: {warning}");
            }
            println!("{}", w.summary);
        }),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

impl From<LogFormatArg> for LogFormat {
    fn from(f: LogFormatArg) -> LogFormat {
        match f {
            LogFormatArg::Text => LogFormat::Text,
            LogFormatArg::Json => LogFormat::Json,
        }
    }
}

impl RunArgs {
    /// The run's settings, as the driver takes them (the thread count
    /// validated: `--threads`, else `ASPERITY_THREADS`).
    fn options(&self) -> asperity::error::Result<RunOptions> {
        asperity::app::driver::check_out(self.out.as_deref(), &[&self.case])?;
        if self.stop_after == Some(0) {
            return Err(asperity::error::Error::input(
                "--stop-after",
                "must be at least 1 (a run stopped before its first increment has nothing to resume)",
            ));
        }
        let overrides = self.overrides.options()?;
        if overrides.adapt.is_some() && self.restart.is_some() {
            return Err(asperity::error::Error::input(
                "--adapt",
                "an adaptive run solves every mesh from the start of the history: it cannot resume (--restart)",
            ));
        }
        Ok(RunOptions {
            out: self.out.clone(),
            quiet: self.quiet,
            restart: self.restart.clone(),
            hooks: asperity::app::options::Hooks {
                fault: self.inject_fault,
                stop_after: self.stop_after,
                factorization: None,
            },
            log_format: self.log_format.into(),
            snes: self.nonlinear == NonlinearArg::Snes,
            lean_memory: self.memory == MemoryArg::Lean,
            threads: asperity::threads::requested(self.threads.as_deref())?,
            ..overrides
        })
    }
}

/// The value of `--adapt`: a relative tolerance in [1e-6, 1).
fn parse_adapt(text: &str) -> asperity::error::Result<f64> {
    let bad = |why: &str| {
        asperity::error::Error::input(
            "--adapt",
            format!(
                "\"{}\" {why}: the relative estimate to reach, e.g. 0.01",
                asperity::error::clip(text)
            ),
        )
    };
    let t: f64 = text.trim().parse().map_err(|_| bad("is not a number"))?;
    if !(t.is_finite() && t > 0.0 && t < 1.0) {
        return Err(bad("must be in (0, 1)"));
    }
    if t < 1e-6 {
        return Err(bad(
            "is below 1e-6, which no mesh this program can hold reaches",
        ));
    }
    Ok(t)
}

/// `asperity run`: the interrupt handler, then the backend's solve.
fn run(args: RunArgs) -> ExitCode {
    let opts = match args.options() {
        Ok(opts) => opts,
        Err(e) => return fail(args.log_format.into(), &e.to_string()),
    };
    if let Err(e) = asperity::interrupt::install() {
        eprintln!("warning: no SIGINT/SIGTERM handler ({e}); an interrupt kills the run");
    }
    if petsc_chosen(args.backend) {
        return run_petsc(&args.case, &opts, &args.petsc_options);
    }
    if let Some(code) = refuse_serial(&opts, &args.petsc_options) {
        return code;
    }
    match driver::run(&args.case, &opts) {
        Ok((dir, _model, result)) => {
            // (an adaptive run stopped in its first cycle wrote no folder)
            if dir.exists() {
                println!("{}", dir.display());
            }
            exit_code(&result)
        }
        Err(e) => fail(opts.log_format, &e.to_string()),
    }
}

/// Does `--backend` pick PETSc? auto: PETSc only under mpirun; on one process
/// the serial Cholesky is 3-6x faster than PETSc at every size up to the
/// element cap, in about as much memory (docs/performance.md, "Choosing the
/// backend").
fn petsc_chosen(backend: BackendArg) -> bool {
    backend == BackendArg::Petsc
        || (backend == BackendArg::Auto && cfg!(feature = "parallel") && under_mpirun())
}

/// The serial backend refuses several MPI processes (every process exits 2;
/// rank 0 alone says why) and options that only PETSc takes (exit 2).
fn refuse_serial(opts: &RunOptions, petsc_options: &[String]) -> Option<ExitCode> {
    if let Some((size, rank, said)) = launcher().filter(|l| l.0 > 1) {
        if rank > 0 {
            return Some(ExitCode::from(2));
        }
        return Some(fail(
            opts.log_format,
            &format!("the serial backend under an MPI launcher with {size} processes ({said}) would run {size} independent solves into one output folder; use --backend petsc (or auto)"),
        ));
    }
    if opts.lean_memory {
        return Some(fail(
            opts.log_format,
            "--memory lean applies to the PETSc backend, but the serial backend runs (use --backend petsc)",
        ));
    }
    if !petsc_options.is_empty() {
        return Some(fail(
            opts.log_format,
            "PETSc options given but the serial backend runs (use --backend petsc)",
        ));
    }
    None
}

/// The lines `study refine` adds beside the serial methods.
struct StudyLines {
    /// PETSc on 1 and 2 ranks.
    petsc: bool,
    /// The ungraded mesh.
    uniform: bool,
    /// An adaptive run.
    adapt: bool,
}

/// `asperity study refine`: every method asked for on the serial backend
/// (modified Newton and initial stiffness on `slow_levels` when given), then
/// PETSc on 1 and 2 ranks and the ungraded mesh when asked for; prints the
/// summary and the files written.
fn study_refine(
    case: &std::path::Path,
    levels: &[usize],
    methods: &[MethodArg],
    slow_levels: Option<Vec<usize>>,
    lines: StudyLines,
    out: &std::path::Path,
) -> asperity::error::Result<()> {
    use asperity::app::study::refine::{refine, Config};
    let StudyLines {
        petsc,
        uniform,
        adapt,
    } = lines;
    use asperity::app::study::runner::Which;
    let mut configs: Vec<Config> = methods
        .iter()
        .map(|&m| Config {
            method: m.into(),
            levels: (!matches!(m, MethodArg::FullNewton))
                .then(|| slow_levels.clone())
                .flatten(),
            which: Which::Serial,
            uniform: false,
            adapt: false,
        })
        .collect();
    if petsc {
        for n in [1, 2] {
            configs.push(Config {
                method: Method::FullNewton,
                levels: None,
                which: Which::Petsc(n),
                uniform: false,
                adapt: false,
            });
        }
    }
    if uniform {
        configs.push(Config {
            method: Method::FullNewton,
            levels: None,
            which: Which::Serial,
            uniform: true,
            adapt: false,
        });
    }
    if adapt {
        configs.push(Config {
            method: Method::FullNewton,
            levels: None,
            which: Which::Serial,
            uniform: false,
            adapt: true,
        });
    }
    refine(case, levels, &configs, out).map(|(files, summary)| {
        print!("{summary}");
        for f in files {
            println!("{}", f.display());
        }
    })
}

/// `asperity study stability`: prints the recommendation and the files written.
fn study_stability(
    case: &std::path::Path,
    steps: &[usize],
    methods: Vec<MethodArg>,
    schemes: bool,
    time_limit: f64,
    out: &std::path::Path,
) -> asperity::error::Result<()> {
    let methods: Vec<Method> = methods.into_iter().map(Into::into).collect();
    let sch: &[&str] = if schemes {
        &["return-mapping", "stiffness-modification"]
    } else {
        &[]
    };
    asperity::app::study::stability::stability(
        case,
        steps,
        &methods,
        sch,
        out,
        (time_limit > 0.0).then(|| std::time::Duration::from_secs_f64(time_limit)),
    )
    .map(|(files, _, best)| {
        println!("{best}");
        for f in files {
            println!("{}", f.display());
        }
    })
}

/// `asperity figures`: prints the files written.
fn figures(cases: &std::path::Path, out: &std::path::Path) -> asperity::error::Result<()> {
    asperity::app::study::figures::figures(cases, out).map(|files| {
        for f in files {
            println!("{}", f.display());
        }
    })
}

/// 0 for a complete run; 130 / 143 after SIGINT / SIGTERM; 3 after --stop-after.
fn exit_code(result: &RunResult) -> ExitCode {
    result
        .stopped
        .map_or(ExitCode::SUCCESS, |s| ExitCode::from(s.exit_code()))
}

/// Reports an error (one `error: …` line, or an `error` JSON event) and exits 2.
fn fail(format: LogFormat, message: &str) -> ExitCode {
    Log::new(format, false).always(
        "error",
        serde_json::json!({"message": message, "exit_code": 2}),
        || format!("error: {message}"),
    );
    ExitCode::from(2)
}

#[cfg(feature = "parallel")]
fn run_petsc(case: &std::path::Path, opts: &RunOptions, petsc_options: &[String]) -> ExitCode {
    let report = |e: &asperity::error::Error| {
        fail(opts.log_format, &e.to_string());
    };
    let (outcome, root) = asperity::app::parallel::run(case, opts, petsc_options, &report);
    match outcome {
        Ok((dir, result)) => {
            if root && dir.exists() {
                println!("{}", dir.display());
            }
            exit_code(&result)
        }
        Err(_) => ExitCode::from(2),
    }
}

#[cfg(not(feature = "parallel"))]
fn run_petsc(_: &std::path::Path, opts: &RunOptions, _: &[String]) -> ExitCode {
    fail(
        opts.log_format,
        "this build has no PETSc backend; rebuild with `cargo build --release --features parallel`",
    )
}
