//! # asperity
//!
//! Finite-element analysis of elastic-plastic plane contact across a rough,
//! compliant interface, after R. Buczkowski and M. Kleiber, "Finite element
//! analysis of elastic-plastic plane contact problem with nonlinear interface
//! compliance", J. Theor. Appl. Mech. 30(4), 1992.
//!
//! | paper | module |
//! |---|---|
//! | 3.2, 3.32: 8-node serendipity quad (and the 6-node triangle) | [`physics::element`] |
//! | 3.8-3.14: von Mises, linear isotropic hardening | [`physics::material`] |
//! | 2.1-2.11, 3.29-3.31: interface laws and spring pairs | [`physics::contact`], [`model`] |
//! | 4.1-4.8: increments, Newton variants, status loop | [`solve`] |
//! | eq. 2.1 from the surface (Greenwood-Williamson, McCool) | [`app`] (`calibrate`) |
//!
//! Units: mm, N, MPa everywhere.
//!
//! `unsafe` is denied in the whole crate except the PETSc layer
//! ([`linalg`]`::backend::petsc`, feature `parallel`) and two documented system calls:
//! the signal handler's registration ([`interrupt::install`]) and the atomic
//! swap of the output folder (`renameat2`, [`files`]).

#![deny(unsafe_code)]

// The ground floor, used by every layer: errors, interrupts, threads, log lines.
pub mod error;
pub mod interrupt;
pub mod numbers;
pub mod progress;
pub mod threads;

// The pipeline, from the bottom up (ARCHITECTURE.md): each layer uses only
// the layers above it in this list and the ground floor.

// the laws of a point and an element
pub mod physics;

// what the user gives: the case file and the meshes
pub mod input;

// the discrete model built from them, fixed for the run
pub mod model;

// linear algebra: the backends, the nonlinear seam
pub mod linalg;

// what a converged state measures
pub mod measure;

// the increment loop: stepping, Newton, stabilization, events
pub mod solve;

// what a designer concludes from a run: the handbook's ratings (DIN 7190-1, VDI 2230-1) beside
// the FE's numbers, and the warnings that qualify them
pub mod verdict;

// the files a run writes and reads back
pub mod files;

// the jobs behind the command line
pub mod app;

pub use error::{Error, Result};
