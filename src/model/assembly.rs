//! DOF map and sparse assembly.
//!
//! Every node has two dofs (2i, 2i+1). Dofs with a prescribed displacement are
//! eliminated: the remaining "equations" are numbered 0..n_eq. The sparsity
//! pattern (CSC, n_eq × n_eq) is built once from every element and every
//! interface point, including all potential contact couplings, so it never
//! changes: the serial backend keeps its symbolic factorization for the whole run.
//! It is built by the backend that needs it (not held by the model): the serial
//! backend builds it whole, each PETSc rank only the columns it owns.
//!
//! For the serial backend each local block (element or interface point) gets a
//! precomputed list of positions into the value array (`Assembler`), so
//! assembly is a gather-free scatter. The PETSc backend hands blocks to
//! MatSetValues and needs only the pattern, for exact preallocation.

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

/// The dof lists of all local blocks (elements, then interface points), stored
/// flat: block b is `dofs[ptr[b]..ptr[b + 1]]`.
#[derive(Clone, Debug, Default)]
pub struct Blocks {
    pub(crate) ptr: Vec<usize>,
    pub dofs: Vec<u32>,
}

impl Blocks {
    pub fn new() -> Self {
        Blocks {
            ptr: vec![0],
            dofs: Vec::new(),
        }
    }

    pub fn push(&mut self, dofs: impl IntoIterator<Item = usize>) {
        self.dofs.extend(dofs.into_iter().map(|d| d as u32));
        self.ptr.push(self.dofs.len());
    }

    pub fn len(&self) -> usize {
        self.ptr.len() - 1
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn get(&self, b: usize) -> &[u32] {
        &self.dofs[self.ptr[b]..self.ptr[b + 1]]
    }
}

/// The compressed-column sparsity pattern (n_eq × n_eq) of every block.
/// Built column by column from an equation → block incidence, so the only
/// transient memory is that incidence and one column: no per-column lists of
/// duplicates (which fragmented the heap and stayed resident).
#[derive(Clone, Debug)]
pub struct Pattern {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<u32>,
}

impl Pattern {
    /// Every column.
    pub fn new(map: &DofMap, blocks: &Blocks) -> Self {
        Self::columns(map, blocks, |_| true)
    }

    /// Only the columns `keep` selects (the others are empty): a rank's part
    /// of the (symmetric) pattern, whose column c lists row c's couplings.
    pub fn columns(map: &DofMap, blocks: &Blocks, keep: impl Fn(usize) -> bool) -> Self {
        let n = map.n_eq;
        // equation → blocks that hold it (counting sort), kept columns only
        let mut inc_ptr = vec![0usize; n + 1];
        for &d in &blocks.dofs {
            let e = map.eq[d as usize];
            if e != NONE && keep(e as usize) {
                inc_ptr[e as usize + 1] += 1;
            }
        }
        for c in 0..n {
            inc_ptr[c + 1] += inc_ptr[c];
        }
        let mut next = inc_ptr.clone();
        let mut inc = vec![0u32; inc_ptr[n]];
        for b in 0..blocks.len() {
            for &d in blocks.get(b) {
                let e = map.eq[d as usize];
                if e != NONE && keep(e as usize) {
                    inc[next[e as usize]] = b as u32;
                    next[e as usize] += 1;
                }
            }
        }
        drop(next);
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        let mut col = Vec::new();
        for c in 0..n {
            col.clear();
            for &b in &inc[inc_ptr[c]..inc_ptr[c + 1]] {
                col.extend(
                    blocks
                        .get(b as usize)
                        .iter()
                        .map(|&d| map.eq[d as usize])
                        .filter(|&r| r != NONE),
                );
            }
            col.sort_unstable();
            col.dedup();
            row_idx.extend_from_slice(&col);
            col_ptr.push(row_idx.len());
        }
        row_idx.shrink_to_fit();
        Pattern {
            n,
            col_ptr,
            row_idx,
        }
    }

    pub(crate) fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Row indices of column c (sorted).
    pub fn rows(&self, c: usize) -> &[u32] {
        &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]]
    }
}

/// Value positions of each block in a CSC value array on a [`Pattern`]: the
/// serial backend's gather-free scatter (the PETSc backend needs none).
#[derive(Clone, Debug)]
pub(crate) struct Assembler {
    /// For block b, `positions[offsets[b]..offsets[b+1]]` holds, row-major over its
    /// local (i, j), the index into the value array (or NONE).
    positions: Vec<u32>,
    offsets: Vec<usize>,
}

impl Assembler {
    pub fn new(pattern: &Pattern, map: &DofMap, blocks: &Blocks) -> Self {
        let mut positions = Vec::new();
        let mut offsets = vec![0];
        for b in 0..blocks.len() {
            let dofs = blocks.get(b);
            for &dr in dofs {
                for &dc in dofs {
                    let (r, c) = (map.eq[dr as usize], map.eq[dc as usize]);
                    if r == NONE || c == NONE {
                        positions.push(NONE);
                        continue;
                    }
                    let k = pattern
                        .rows(c as usize)
                        .binary_search(&r)
                        .expect("every block coupling is in the pattern");
                    positions.push((pattern.col_ptr[c as usize] + k) as u32);
                }
            }
            offsets.push(positions.len());
        }
        Assembler { positions, offsets }
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
        let mut blocks = Blocks::new();
        blocks.push([0, 1, 2]);
        blocks.push([2, 3]);
        let pattern = Pattern::new(&map, &blocks);
        let asm = Assembler::new(&pattern, &map, &blocks);
        let mut vals = vec![0.0; pattern.nnz()];
        asm.add(0, &[1., 2., 3., 4., 5., 6., 7., 8., 9.], &mut vals);
        asm.add(1, &[10., 20., 30., 40.], &mut vals);
        // dense reconstruction over equations (dof 0 → 0, dof 2 → 1, dof 3 → 2)
        let mut dense = [[0.0; 3]; 3];
        for (c, col) in pattern.col_ptr.windows(2).enumerate() {
            for k in col[0]..col[1] {
                dense[pattern.row_idx[k] as usize][c] += vals[k];
            }
        }
        assert_eq!(dense, [[1., 3., 0.], [7., 19., 20.], [0., 30., 40.]]);
        // a part holds exactly the selected columns of the whole
        let part = Pattern::columns(&map, &blocks, |c| c != 1);
        assert_eq!(part.rows(0), pattern.rows(0));
        assert!(part.rows(1).is_empty());
        assert_eq!(part.rows(2), pattern.rows(2));
        assert_eq!(part.nnz(), pattern.nnz() - pattern.rows(1).len());
    }
}
