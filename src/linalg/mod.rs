//! Linear algebra: the dof map and sparse pattern (`assembly`) and the
//! backends that factor and solve (the serial faer one, PETSc under MPI;
//! [`backend`]).

pub mod backend;
pub mod dense;
pub mod failure;
pub mod nonlinear;
