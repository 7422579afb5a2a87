//! DOF map and sparse assembly.
//!
//! Every node has two dofs (2i, 2i+1). Dofs with a prescribed displacement are
//! eliminated: the remaining "equations" are numbered 0..n_eq. The sparsity
//! pattern (CSC, n_eq × n_eq) is built once from every element and every
//! interface point, including all potential contact couplings, so it never
//! changes: the serial backend keeps its symbolic factorization for the whole run.
//!
//! Each local block (element or interface point) gets a precomputed list of
//! positions into the value array, so assembly is a gather-free scatter.

const NONE: u32 = u32::MAX;

/// dof → equation number (or none when the dof is prescribed).
#[derive(Clone, Debug)]
pub struct DofMap {
    pub eq: Vec<u32>,
    pub n_eq: usize,
}

impl DofMap {
    /// Numbers the free dofs in increasing dof order.
    pub fn new(n_dofs: usize, prescribed: &[bool]) -> Self {
        let mut eq = vec![NONE; n_dofs];
        let mut n = 0u32;
        for (d, e) in eq.iter_mut().enumerate() {
            if !prescribed[d] {
                *e = n;
                n += 1;
            }
        }
        DofMap {
            eq,
            n_eq: n as usize,
        }
    }

    pub fn equation(&self, dof: usize) -> Option<usize> {
        let e = self.eq[dof];
        (e != NONE).then_some(e as usize)
    }
}

/// A compressed-column sparsity pattern with value positions for each local block.
#[derive(Clone, Debug)]
pub struct Assembler {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    /// For block b, `positions[offsets[b]..offsets[b+1]]` holds, row-major over its
    /// local (i, j), the index into the value array (or NONE).
    positions: Vec<u32>,
    offsets: Vec<usize>,
}

impl Assembler {
    /// Builds the pattern from the dof lists of all blocks.
    pub fn new(map: &DofMap, blocks: &[Vec<usize>]) -> Self {
        let n = map.n_eq;
        let mut cols: Vec<Vec<u32>> = vec![Vec::new(); n];
        for dofs in blocks {
            let eqs: Vec<u32> = dofs.iter().map(|&d| map.eq[d]).collect();
            for &c in &eqs {
                if c == NONE {
                    continue;
                }
                let col = &mut cols[c as usize];
                col.extend(eqs.iter().copied().filter(|&r| r != NONE));
            }
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for mut col in cols {
            col.sort_unstable();
            col.dedup();
            row_idx.extend(col.iter().map(|&r| r as usize));
            col_ptr.push(row_idx.len());
        }
        let mut positions = Vec::new();
        let mut offsets = vec![0];
        for dofs in blocks {
            for &dr in dofs {
                for &dc in dofs {
                    let (r, c) = (map.eq[dr], map.eq[dc]);
                    if r == NONE || c == NONE {
                        positions.push(NONE);
                        continue;
                    }
                    let rows = &row_idx[col_ptr[c as usize]..col_ptr[c as usize + 1]];
                    let k = rows
                        .binary_search(&(r as usize))
                        .expect("every block coupling is in the pattern");
                    positions.push((col_ptr[c as usize] + k) as u32);
                }
            }
            offsets.push(positions.len());
        }
        Assembler {
            n,
            col_ptr,
            row_idx,
            positions,
            offsets,
        }
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Adds a local row-major matrix of block `b` into `values`.
    pub fn add(&self, b: usize, local: &[f64], values: &mut [f64]) {
        let pos = &self.positions[self.offsets[b]..self.offsets[b + 1]];
        debug_assert_eq!(pos.len(), local.len());
        for (&p, &v) in pos.iter().zip(local) {
            if p != NONE {
                values[p as usize] += v;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pattern_and_scatter_match_a_dense_sum() {
        // 4 dofs, dof 1 prescribed; two overlapping blocks
        let map = DofMap::new(4, &[false, true, false, false]);
        assert_eq!(map.n_eq, 3);
        let blocks = vec![vec![0, 1, 2], vec![2, 3]];
        let asm = Assembler::new(&map, &blocks);
        let mut vals = vec![0.0; asm.nnz()];
        asm.add(0, &[1., 2., 3., 4., 5., 6., 7., 8., 9.], &mut vals);
        asm.add(1, &[10., 20., 30., 40.], &mut vals);
        // dense reconstruction over equations (dof 0 → 0, dof 2 → 1, dof 3 → 2)
        let mut dense = [[0.0; 3]; 3];
        for c in 0..3 {
            for k in asm.col_ptr[c]..asm.col_ptr[c + 1] {
                dense[asm.row_idx[k]][c] += vals[k];
            }
        }
        assert_eq!(dense, [[1., 3., 0.], [7., 19., 20.], [0., 30., 40.]]);
    }
}
