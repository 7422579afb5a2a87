//! The `asperity` command line.

use asperity::case::Method;
use asperity::driver::{self, RunOptions};
use clap::{Parser, Subcommand, ValueEnum};
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
    Run {
        /// Case file (case.toml) or the folder that holds it.
        case: PathBuf,
        /// Output folder (default: out/<case name>). Replaced if it exists.
        #[arg(long)]
        out: Option<PathBuf>,
        /// No progress lines.
        #[arg(long)]
        quiet: bool,
        /// Override the solution method of the case.
        #[arg(long, value_enum)]
        method: Option<MethodArg>,
        /// Override the mesh refinement factor of the case.
        #[arg(long)]
        refine: Option<usize>,
        /// Linear-algebra backend: serial (faer), petsc (MPI; needs the `parallel`
        /// feature), or auto: petsc when started by mpirun with the feature built in.
        #[arg(long, value_enum, default_value = "auto")]
        backend: BackendArg,
        /// Test hook: make the element loop fail on RANK at its N-th assembly
        /// (every later attempt too), e.g. `1:5`.
        #[arg(long, value_name = "RANK:N", value_parser = parse_fault, hide = true)]
        inject_fault: Option<(usize, usize)>,
        /// PETSc options after `--`, e.g. `-- -ksp_type cg -pc_type gamg -log_view`.
        #[arg(last = true)]
        petsc_options: Vec<String>,
    },
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
    /// Validate a case and print what it would solve (dofs, increments), without solving.
    Check {
        /// Case file (case.toml) or the folder that holds it.
        case: PathBuf,
    },
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum BackendArg {
    Auto,
    Serial,
    Petsc,
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
    let cli = Cli::parse();
    let outcome = match cli.command {
        Command::Run {
            case,
            out,
            quiet,
            method,
            refine,
            backend,
            inject_fault,
            petsc_options,
        } => {
            let opts = RunOptions {
                out,
                quiet,
                method: method.map(Into::into),
                refine,
                fault: inject_fault,
            };
            let petsc = backend == BackendArg::Petsc
                || (backend == BackendArg::Auto && cfg!(feature = "parallel") && under_mpirun());
            if petsc {
                return run_petsc(&case, &opts, &petsc_options);
            }
            if !petsc_options.is_empty() {
                eprintln!(
                    "error: PETSc options given but the serial backend runs (use --backend petsc)"
                );
                return ExitCode::from(2);
            }
            driver::run(&case, &opts).map(|(dir, _model, result)| {
                if !quiet {
                    let last = result.increments.last().map(|i| i.measures).unwrap_or_default();
                    if let Some(fy) = &result.first_yield {
                        eprintln!(
                            "first yield: {:.4} kN ({:.2} MPa mean pressure) in {} at x = {:.3} mm, depth {:.3} mm",
                            fy.total_load_kn, fy.mean_pressure, fy.body, fy.x, fy.depth
                        );
                    }
                    eprintln!(
                        "final: {:.4} kN, mean pressure {:.2} MPa, center displacement {:.5} mm; {} increments, {} iterations",
                        last.total_load_kn,
                        last.mean_pressure,
                        last.center_displacement,
                        result.increments.len(),
                        result.stats.iterations
                    );
                }
                println!("{}", dir.display());
            })
        }
        Command::Check { case } => driver::check(&case).map(|s| print!("{s}")),
        Command::Figures { cases, out } => asperity::study::figures::figures(&cases, &out).map(|files| {
            for f in files {
                println!("{}", f.display());
            }
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

#[cfg(feature = "parallel")]
fn run_petsc(case: &std::path::Path, opts: &RunOptions, petsc_options: &[String]) -> ExitCode {
    let (outcome, root) = asperity::parallel::run(case, opts, petsc_options);
    match outcome {
        Ok(dir) => {
            if root {
                println!("{}", dir.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            if root {
                eprintln!("error: {e}");
            }
            ExitCode::from(2)
        }
    }
}

#[cfg(not(feature = "parallel"))]
fn run_petsc(_: &std::path::Path, _: &RunOptions, _: &[String]) -> ExitCode {
    eprintln!("error: this build has no PETSc backend; rebuild with `cargo build --release --features parallel`");
    ExitCode::from(2)
}
