//! Serial sparse direct solver (faer): the symbolic LU factorization is computed
//! once for the fixed pattern and reused for every numeric factorization.
//! LU rather than Cholesky because the tangent is unsymmetric with friction
//! (p_T^Y depends on p_N) and indefinite-singular when a body is unsupported.

use crate::assembly::{Assembler, Pattern};
use crate::error::{Error, Result};
use crate::model::Model;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::MatMut;

pub struct SerialLu {
    symbolic_mat: SymbolicSparseColMat<usize>,
    symbolic_lu: SymbolicLu<usize>,
    lu: Option<Lu<usize, f64>>,
    /// Number of numeric factorizations performed.
    pub factorizations: usize,
}

impl SerialLu {
    /// Symbolic analysis (fill-reducing ordering) of the pattern.
    pub fn new(pattern: &Pattern) -> Result<Self> {
        let symbolic_mat = SymbolicSparseColMat::new_checked(
            pattern.n,
            pattern.n,
            pattern.col_ptr.clone(),
            None,
            pattern.row_idx.iter().map(|&r| r as usize).collect(),
        );
        let symbolic_lu = SymbolicLu::try_new(symbolic_mat.as_ref())
            .map_err(|e| Error::Solver(format!("symbolic LU failed: {e:?}")))?;
        Ok(SerialLu {
            symbolic_mat,
            symbolic_lu,
            lu: None,
            factorizations: 0,
        })
    }

    /// Numeric factorization of the matrix with the given values.
    pub fn factor(&mut self, values: &[f64]) -> Result<()> {
        if values.iter().any(|v| !v.is_finite()) {
            return Err(Error::Solver(
                "the tangent matrix holds NaN or infinite entries".into(),
            ));
        }
        let mat = SparseColMatRef::new(self.symbolic_mat.as_ref(), values);
        let lu = Lu::try_new_with_symbolic(self.symbolic_lu.clone(), mat)
            .map_err(|e| Error::Solver(format!("numeric LU failed: {e:?}")))?;
        self.lu = Some(lu);
        self.factorizations += 1;
        Ok(())
    }

    /// Solves in place with the last factorization. A non-finite solution means a
    /// singular tangent: a body held by nothing (rigid-body motion) or all pairs open.
    pub fn solve(&self, rhs: &mut [f64]) -> Result<()> {
        let lu = self
            .lu
            .as_ref()
            .ok_or_else(|| Error::Solver("solve before factor".into()))?;
        let n = rhs.len();
        let mat = MatMut::from_column_major_slice_mut(rhs, n, 1);
        lu.solve_in_place(mat);
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::Solver(
                "singular tangent matrix: a body can move as a rigid body (missing support, or every interface pair open)".into(),
            ));
        }
        Ok(())
    }
}

/// The serial backend: CSC values on the fixed pattern, factored by [`SerialLu`].
pub struct SerialBackend {
    asm: Assembler,
    lu: SerialLu,
    /// The solid part, kept apart only when a method re-adds the springs to
    /// a reused solid matrix (see [`super::Backend::reuse_solid`]).
    solid: Option<Vec<f64>>,
    /// Values of the last system matrix (for checks of the assembled tangent).
    pub vals: Vec<f64>,
}

impl SerialBackend {
    pub fn new(model: &Model) -> Result<Self> {
        let blocks = model.blocks();
        let pattern = &Pattern::new(&model.dofs, &blocks);
        Ok(SerialBackend {
            asm: Assembler::new(pattern, &model.dofs, &blocks),
            lu: SerialLu::new(pattern)?,
            solid: None,
            vals: vec![0.0; pattern.nnz()],
        })
    }
}

impl super::Backend for SerialBackend {
    fn name(&self) -> &'static str {
        "serial-faer"
    }
    fn reuse_solid(&mut self, reuse: bool) {
        self.solid = reuse.then(|| vec![0.0; self.vals.len()]);
    }
    fn begin_solid(&mut self) -> Result<()> {
        self.solid.as_mut().unwrap_or(&mut self.vals).fill(0.0);
        Ok(())
    }
    fn add_solid(&mut self, block: usize, _dofs: &[usize], k: &[f64]) -> Result<()> {
        self.asm
            .add(block, k, self.solid.as_mut().unwrap_or(&mut self.vals));
        Ok(())
    }
    fn begin_contact(&mut self) -> Result<()> {
        if let Some(solid) = &self.solid {
            self.vals.copy_from_slice(solid);
        }
        Ok(())
    }
    fn add_contact(&mut self, block: usize, _dofs: &[usize], k: &[f64]) -> Result<()> {
        self.asm.add(block, k, &mut self.vals);
        Ok(())
    }
    fn matrix_values(&self) -> Option<&[f64]> {
        Some(&self.vals)
    }
    fn solve(&mut self, rhs: &[f64], x: &mut [f64]) -> Result<()> {
        self.lu.factor(&self.vals)?;
        x.copy_from_slice(rhs);
        self.lu.solve(x)
    }
}
