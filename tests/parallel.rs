//! Serial faer against PETSc on 1 and on 2 MPI ranks, on a refined case with
//! plasticity and contact opening (`cases/strip-lift-off`, refine 3) and on the
//! friction punch: same increments, same contact statuses, same first-yield
//! increment, displacements and interface pressures equal to 1e-6 relative
//! (the direct solvers agree to round-off; 1e-6 leaves room for Newton stopping
//! one iteration apart). Also: no mallocs during PETSc assembly, and an error on
//! one rank ends every rank with one message and exit code 2. The tests live in
//! `tests/parallel/`, one file per concern (one test target, so `cargo test
//! --test parallel` runs them all).
#![cfg(feature = "parallel")]

#[path = "parallel/agreement.rs"]
mod agreement;
mod common;
#[path = "parallel/failures.rs"]
mod failures;
#[path = "parallel/interface_loop.rs"]
mod interface_loop;
#[path = "parallel/solvers.rs"]
mod solvers;
#[path = "parallel/support.rs"]
mod support;
#[path = "parallel/twist.rs"]
mod twist;
