//! The PETSc backend: METIS partition of the elements, equation ownership in
//! contiguous PETSc ranges, an MPIAIJ matrix preallocated exactly for every
//! element and every potential contact coupling, and KSP from the options
//! database (default: MUMPS LU).

use super::{ffi, Ksp, PMat, PVec, Petsc, ToAll};
use crate::error::{Error, Result};
use crate::model::Model;
use mpi::collective::SystemOperation;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

/// Who owns what, identical on every rank.
pub struct Partition {
    pub element_owner: Vec<usize>,
    pub point_owner: Vec<usize>,
    /// Free equation → PETSc global index (rank-contiguous).
    pub petsc_index: Vec<ffi::PetscInt>,
    /// First PETSc index of each rank, and the total (len = ranks + 1).
    pub offsets: Vec<usize>,
}

impl Partition {
    /// (position in this rank's local array, equation) of every equation that
    /// `rank` owns, in equation order.
    pub fn owned(&self, rank: usize) -> Vec<(usize, usize)> {
        let (lo, hi) = (self.offsets[rank], self.offsets[rank + 1]);
        self.petsc_index
            .iter()
            .enumerate()
            .filter(|(_, &p)| (lo..hi).contains(&(p as usize)))
            .map(|(e, &p)| (p as usize - lo, e))
            .collect()
    }

    /// The three in-plane rigid-body modes (x and y translation, rotation about
    /// the centroid) over the free equations, orthonormalized (modified
    /// Gram-Schmidt on the replicated vectors, so every rank gets the same), as
    /// this rank's owned parts in PETSc order: the near-null space that lets
    /// GAMG (`-pc_type gamg`) build coarse spaces for elasticity.
    pub fn rigid_body_modes(&self, model: &Model, rank: usize) -> Vec<Vec<f64>> {
        let nodes = &model.mesh.nodes;
        let n = model.dofs.n_eq;
        let c = nodes
            .iter()
            .fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
        let c = [c[0] / nodes.len() as f64, c[1] / nodes.len() as f64];
        let mut modes = vec![vec![0.0; n]; 3];
        for (i, p) in nodes.iter().enumerate() {
            for comp in 0..2 {
                if let Some(e) = model.dofs.equation(2 * i + comp) {
                    modes[comp][e] = 1.0;
                    modes[2][e] = if comp == 0 {
                        -(p[1] - c[1])
                    } else {
                        p[0] - c[0]
                    };
                }
            }
        }
        for k in 0..3 {
            for j in 0..k {
                let (done, rest) = modes.split_at_mut(k);
                let d: f64 = done[j].iter().zip(&rest[0]).map(|(a, b)| a * b).sum();
                for (b, a) in rest[0].iter_mut().zip(&done[j]) {
                    *b -= d * a;
                }
            }
            let norm = modes[k].iter().map(|v| v * v).sum::<f64>().sqrt();
            if norm > 0.0 {
                modes[k].iter_mut().for_each(|v| *v /= norm);
            }
        }
        let owned = self.owned(rank);
        modes
            .iter()
            .map(|m| {
                let mut local = vec![0.0; owned.len()];
                for &(k, e) in &owned {
                    local[k] = m[e];
                }
                local
            })
            .collect()
    }

    /// METIS k-way partition of the element dual graph (corner nodes); a node
    /// belongs to the lowest rank among its elements, an equation to its node's
    /// rank, an interface point to the rank of its first pair's lower node.
    pub fn new(model: &Model, ranks: usize) -> Result<Self> {
        let mesh = &model.mesh;
        let ne = mesh.elements.len();
        let mut element_owner = vec![0usize; ne];
        if ranks > 1 {
            let eptr: Vec<metis::Idx> = (0..=ne).map(|e| (4 * e) as metis::Idx).collect();
            let eind: Vec<metis::Idx> = mesh
                .elements
                .iter()
                .flat_map(|el| el.nodes[..4].iter().map(|&n| n as metis::Idx))
                .collect();
            let nn = eind.iter().copied().max().unwrap_or(0) as usize + 1;
            let (mut epart, mut npart) = (vec![0; ne], vec![0; nn]);
            metis::Mesh::new(ranks as metis::Idx, &eptr, &eind)
                .map_err(|e| Error::Solver(format!("METIS mesh: {e:?}")))?
                .part_dual(&mut epart, &mut npart)
                .map_err(|e| Error::Solver(format!("METIS partition: {e:?}")))?;
            for (o, p) in element_owner.iter_mut().zip(&epart) {
                *o = *p as usize;
            }
        }
        let mut node_owner = vec![usize::MAX; mesh.nodes.len()];
        for (e, el) in mesh.elements.iter().enumerate() {
            for &n in &el.nodes {
                node_owner[n] = node_owner[n].min(element_owner[e]);
            }
        }
        let point_owner: Vec<usize> = model
            .interfaces
            .iter()
            .flat_map(|im| {
                im.points
                    .iter()
                    .map(|pt| node_owner[im.pairs[pt.pairs[0]].b])
            })
            .collect();
        // equations sorted by (owner, equation)
        let n_eq = model.dofs.n_eq;
        let mut eq_owner = vec![0usize; n_eq];
        for d in 0..mesh.num_dofs() {
            if let Some(e) = model.dofs.equation(d) {
                eq_owner[e] = node_owner[d / 2];
            }
        }
        let mut offsets = vec![0usize; ranks + 1];
        for &o in &eq_owner {
            offsets[o + 1] += 1;
        }
        for r in 0..ranks {
            offsets[r + 1] += offsets[r];
        }
        let mut next = offsets.clone();
        let mut petsc_index = vec![0 as ffi::PetscInt; n_eq];
        for e in 0..n_eq {
            let o = eq_owner[e];
            petsc_index[e] = next[o] as ffi::PetscInt;
            next[o] += 1;
        }
        Ok(Partition {
            element_owner,
            point_owner,
            petsc_index,
            offsets,
        })
    }

    /// Exact diagonal / off-diagonal nonzeros per owned row of `rank`, from the
    /// model's pattern (symmetric, so a column's rows are the row's columns).
    pub fn preallocation(
        &self,
        model: &Model,
        rank: usize,
    ) -> (Vec<ffi::PetscInt>, Vec<ffi::PetscInt>) {
        let (lo, hi) = (self.offsets[rank], self.offsets[rank + 1]);
        let (mut d, mut o) = (vec![0; hi - lo], vec![0; hi - lo]);
        let asm = &model.asm;
        for c in 0..asm.n {
            let row = self.petsc_index[c] as usize;
            if row < lo || row >= hi {
                continue;
            }
            for k in asm.col_ptr[c]..asm.col_ptr[c + 1] {
                let col = self.petsc_index[asm.row_idx[k]] as usize;
                if col >= lo && col < hi {
                    d[row - lo] += 1;
                } else {
                    o[row - lo] += 1;
                }
            }
        }
        (d, o)
    }
}

pub struct PetscBackend<'p> {
    world: SimpleCommunicator,
    rank: usize,
    ranks: usize,
    model: &'p Model,
    pub part: Partition,
    /// (local position, equation) of this rank's equations.
    owned: Vec<(usize, usize)>,
    solid: PMat<'p>,
    mat: PMat<'p>,
    ksp: Ksp<'p>,
    b: PVec<'p>,
    x: PVec<'p>,
    to_all: ToAll<'p>,
    gathered: Vec<f64>,
    idx: Vec<ffi::PetscInt>,
    /// Krylov iterations over the run.
    pub ksp_iterations: usize,
}

impl<'p> PetscBackend<'p> {
    pub fn new(petsc: &'p Petsc, world: SimpleCommunicator, model: &'p Model) -> Result<Self> {
        let (rank, ranks) = (world.rank() as usize, world.size() as usize);
        let part = Partition::new(model, ranks)?;
        let (d, o) = part.preallocation(model, rank);
        let local = part.offsets[rank + 1] - part.offsets[rank];
        let n = model.dofs.n_eq;
        let mut solid = PMat::aij(petsc, local, n, &d, &o)?;
        let mut mat = PMat::aij(petsc, local, n, &d, &o)?;
        // fix the nonzero structure once: explicit zeros over the whole pattern
        let asm = &model.asm;
        let (lo, hi) = (part.offsets[rank], part.offsets[rank + 1]);
        for c in 0..asm.n {
            let row = part.petsc_index[c];
            if (row as usize) < lo || (row as usize) >= hi {
                continue;
            }
            let cols: Vec<ffi::PetscInt> = asm.row_idx[asm.col_ptr[c]..asm.col_ptr[c + 1]]
                .iter()
                .map(|&r| part.petsc_index[r])
                .collect();
            let zeros = vec![0.0; cols.len()];
            solid.set_row(row, &cols, &zeros)?;
            mat.set_row(row, &cols, &zeros)?;
        }
        solid.assemble()?;
        mat.assemble()?;
        mat.set_near_null_space(petsc, &part.rigid_body_modes(model, rank))?;
        let b = PVec::new(petsc, local, n)?;
        let x = PVec::new(petsc, local, n)?;
        let to_all = ToAll::new(&x)?;
        Ok(PetscBackend {
            world,
            rank,
            ranks,
            model,
            owned: part.owned(rank),
            part,
            solid,
            mat,
            ksp: Ksp::new(petsc)?,
            b,
            x,
            to_all,
            gathered: vec![0.0; n],
            idx: Vec::with_capacity(24),
            ksp_iterations: 0,
        })
    }

    /// PETSc indices of local dofs; −1 for prescribed ones (ignored by PETSc).
    fn indices(&mut self, dofs: &[usize]) {
        self.idx.clear();
        for &d in dofs {
            self.idx.push(
                self.model
                    .dofs
                    .equation(d)
                    .map_or(-1, |e| self.part.petsc_index[e]),
            );
        }
    }

    /// The system matrix (solid + contact), for a SNES that solves with it.
    pub fn system_matrix(&self) -> ffi::Mat {
        self.mat.raw
    }

    /// Mallocs during assembly of the system matrix (0 with exact preallocation).
    pub fn mallocs(&self) -> Result<f64> {
        Ok(self.mat.mallocs()? + self.solid.mallocs()?)
    }
}

impl crate::backend::Backend for PetscBackend<'_> {
    fn name(&self) -> &'static str {
        "petsc"
    }
    fn ranks(&self) -> usize {
        self.ranks
    }
    fn rank(&self) -> usize {
        self.rank
    }
    fn owns_element(&self, e: usize) -> bool {
        self.part.element_owner[e] == self.rank
    }
    fn owns_point(&self, q: usize) -> bool {
        self.part.point_owner[q] == self.rank
    }
    fn begin_solid(&mut self) -> Result<()> {
        // values may be pending from an attempt that failed midway
        self.solid.assemble()?;
        self.solid.zero()
    }
    fn add_solid(&mut self, _block: usize, dofs: &[usize], k: &[f64]) -> Result<()> {
        self.indices(dofs);
        self.solid.add(&self.idx, k)
    }
    fn begin_contact(&mut self) -> Result<()> {
        self.solid.assemble()?;
        self.mat.assemble()?;
        self.mat.copy_from(&self.solid)
    }
    fn add_contact(&mut self, _block: usize, dofs: &[usize], k: &[f64]) -> Result<()> {
        self.indices(dofs);
        self.mat.add(&self.idx, k)
    }
    fn solve(&mut self, rhs: &[f64], x: &mut [f64]) -> Result<()> {
        self.mat.assemble()?;
        self.b.write_owned(&self.owned, rhs)?;
        let result = self.ksp.solve(&self.mat, &self.b, &mut self.x);
        // the outcome is collective: fail everywhere if it failed anywhere
        let ok = i32::from(result.is_ok());
        let mut all_ok = 0;
        self.world
            .all_reduce_into(&ok, &mut all_ok, SystemOperation::min());
        let its = match result {
            Ok(its) if all_ok == 1 => its,
            Err(e) => return Err(e),
            Ok(_) => {
                return Err(Error::Solver(
                    "the linear solve failed on another rank".into(),
                ))
            }
        };
        self.ksp_iterations += its;
        self.to_all.gather(&self.x, &mut self.gathered)?;
        for (e, xe) in x.iter_mut().enumerate() {
            *xe = self.gathered[self.part.petsc_index[e] as usize];
        }
        if !x.iter().all(|v| v.is_finite()) {
            return Err(Error::Solver(
                "singular tangent matrix: non-finite solution".into(),
            ));
        }
        Ok(())
    }
    fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("ksp_iterations", self.ksp_iterations as f64),
            ("assembly_mallocs", self.mallocs().unwrap_or(f64::NAN)),
            (
                "owned_equations_rank0",
                (self.part.offsets[1] - self.part.offsets[0]) as f64,
            ),
        ]
    }
    fn sum(&self, v: &mut [f64]) {
        let send = v.to_vec();
        self.world
            .all_reduce_into(&send[..], v, SystemOperation::sum());
    }
    fn max(&self, v: &mut [f64]) {
        let send = v.to_vec();
        self.world
            .all_reduce_into(&send[..], v, SystemOperation::max());
    }
    fn share_message(&self, msg: Option<String>) -> Option<String> {
        let mine = if msg.is_some() {
            self.rank as i32
        } else {
            i32::MAX
        };
        let mut first = i32::MAX;
        self.world
            .all_reduce_into(&mine, &mut first, SystemOperation::min());
        if first == i32::MAX {
            return None;
        }
        let root = self.world.process_at_rank(first);
        let mut bytes = msg.map(String::into_bytes).unwrap_or_default();
        let mut len = bytes.len() as u64;
        root.broadcast_into(&mut len);
        bytes.resize(len as usize, 0);
        root.broadcast_into(&mut bytes[..]);
        let text = String::from_utf8_lossy(&bytes).into_owned();
        Some(if first == 0 {
            text
        } else {
            format!("rank {first}: {text}")
        })
    }
    fn agree(&self, flag: bool) -> bool {
        let mut f = i32::from(flag);
        self.world.process_at_rank(0).broadcast_into(&mut f);
        f == 1
    }
}
