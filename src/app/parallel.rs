//! `asperity run` under MPI with the PETSc backend (feature `parallel`).
//!
//! Start-up order: MPI → PETSc (with the options after `--`) → model (built on
//! every rank from the same case file, so input errors are found by all ranks
//! alike) → backend → run. Objects drop in reverse order: PETSc finalizes before
//! MPI. Only rank 0 writes output and prints; every error ends every rank.

use crate::app::driver::{self, RunOptions};
use crate::error::{Error, Result};
use crate::linalg::backend::petsc::{snes::SnesSolver, solver::PetscBackend, LinearDefault, Petsc};
use crate::linalg::nonlinear::NonlinearSolver;
use crate::solve::Engine;
use mpi::traits::*;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Runs a case on the PETSc backend. Returns the output folder (on rank 0) and
/// whether this process is rank 0. On an error, rank 0 calls `report` and every
/// rank waits for it at a barrier before MPI finalizes: a rank that exited with
/// code 2 first would make mpirun kill rank 0 before its message is out. (Errors
/// are collective by construction, so every rank reaches the barrier.)
pub fn run(
    case_path: &Path,
    opts: &RunOptions,
    petsc_args: &[String],
    report: &dyn Fn(&Error),
) -> (Result<(PathBuf, crate::solve::RunResult)>, bool) {
    let started = Instant::now();
    let Some(universe) = mpi::initialize() else {
        let e = Error::Parallel("MPI could not be initialized".into());
        report(&e);
        return (Err(e), true);
    };
    let world = universe.world();
    let root = world.rank() == 0;
    let outcome = (|| {
        if opts.lean_memory && !opts.snes {
            return Err(Error::Input {
                place: "command line".into(),
                message: "--memory lean needs the SNES nonlinear solver (drop --nonlinear builtin)"
                    .into(),
            });
        }
        let petsc = Petsc::init(&universe, petsc_args)?;
        let case = driver::load_case(case_path, opts)?;
        if case.adapt.is_some() {
            let mut solve = |model: &crate::model::Model, started: Instant| {
                let engine = engine(&petsc, &world, model, opts)?;
                driver::run_cycle(model, engine, opts, root, started)
            };
            let share = |numbers: &mut [f64]| {
                world.process_at_rank(0).broadcast_into(numbers);
            };
            let result = crate::app::adapt::run(case, opts, root, &mut solve, &share)
                .map(|(dir, _, result)| (dir, result));
            drop(petsc);
            return result;
        }
        let result = {
            let model = crate::model::Model::build(case)?;
            let engine = engine(&petsc, &world, &model, opts)?;
            driver::run_model(&model, engine, opts, root, started)
        };
        drop(petsc);
        result
    })();
    if let Err(e) = &outcome {
        if root {
            report(e);
        }
        world.barrier();
    }
    (outcome, root)
}

/// The PETSc engine of a built model: the backend on `world`, SNES unless
/// `--nonlinear builtin`, one thread per rank unless asked.
fn engine<'m>(
    petsc: &'m Petsc,
    world: &mpi::topology::SimpleCommunicator,
    model: &'m crate::model::Model,
    opts: &RunOptions,
) -> Result<Engine<'m>> {
    let at_model = crate::solve::peak_memory_mb();
    let linear = LinearDefault::for_model(model);
    let mut backend = PetscBackend::new(petsc, world.duplicate(), model, linear)?;
    let snes = if opts.snes {
        let snes = SnesSolver::new(
            petsc,
            backend.system_matrix(),
            &backend.part,
            world.rank() as usize,
            world.size() as usize,
            model.solver.iteration_limit(),
            linear,
            opts.lean_memory,
        )?;
        // the interface loop condenses the factor that solved the Newton system
        backend.factor_of(snes.ksp()?)?;
        Some(snes)
    } else {
        None
    };
    let mut engine = Engine::with_backend(model, model.solver.method, Box::new(backend));
    engine.nonlinear = snes.map(|s| Box::new(s) as Box<dyn NonlinearSolver>);
    // the ranks share the cores: one thread each unless asked
    engine.set_threads(opts.threads.unwrap_or(1));
    driver::prepare(&mut engine, opts, at_model);
    Ok(engine)
}
