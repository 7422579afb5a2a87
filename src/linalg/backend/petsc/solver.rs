//! The PETSc backend: METIS partition of the elements, equation ownership in
//! contiguous PETSc ranges, an MPIAIJ matrix preallocated exactly for every
//! element and every potential contact coupling, and KSP from the options
//! database (default: [`LinearDefault`], by size).

use super::{chk, ffi, Ksp, LinearDefault, PMat, PVec, Petsc, ToAll};
use crate::error::{Error, Result};
use crate::model::assembly::Pattern;
use crate::model::Model;
use mpi::collective::SystemOperation;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

/// Who owns what, identical on every rank.
pub struct Partition {
    pub element_owner: Vec<usize>,
    pub point_owner: Vec<usize>,
    /// Free equation → PETSc global index (rank-contiguous).
    pub(crate) petsc_index: Vec<ffi::PetscInt>,
    /// Mesh dof → PETSc global index. PETSc numbers every dof, prescribed ones
    /// too (as identity rows), [`crate::input::mesh::NodeDofs`] per node (2, or 3
    /// with twist) in node order within each rank, so the matrix has that
    /// block size and algebraic multigrid aggregates nodes.
    pub dof_index: Vec<ffi::PetscInt>,
    /// First PETSc index of each rank, and the total (len = ranks + 1).
    pub offsets: Vec<usize>,
}

impl Partition {
    /// (position in this rank's local array, equation) of every equation that
    /// `rank` owns, in equation order.
    pub(crate) fn owned(&self, rank: usize) -> Vec<(usize, usize)> {
        let (lo, hi) = (self.offsets[rank], self.offsets[rank + 1]);
        self.petsc_index
            .iter()
            .enumerate()
            .filter(|(_, &p)| (lo..hi).contains(&(p as usize)))
            .map(|(e, &p)| (p as usize - lo, e))
            .collect()
    }

    /// Rows (PETSc indices) `rank` owns.
    pub(crate) fn local_len(&self, rank: usize) -> usize {
        self.offsets[rank + 1] - self.offsets[rank]
    }

    /// Rows of the PETSc system: every dof of the mesh.
    pub(crate) fn global_len(&self) -> usize {
        self.dof_index.len()
    }

    /// PETSc rows of the prescribed dofs `rank` owns: identity rows of the
    /// system, zero in every right-hand side and solution.
    pub(crate) fn prescribed_rows(&self, model: &Model, rank: usize) -> Vec<ffi::PetscInt> {
        let (lo, hi) = (self.offsets[rank], self.offsets[rank + 1]);
        (0..self.dof_index.len())
            .filter(|&d| model.dofs.equation(d).is_none())
            .map(|d| self.dof_index[d])
            .filter(|&p| (lo..hi).contains(&(p as usize)))
            .collect()
    }

    /// The three in-plane rigid-body modes of the assembly (x and y
    /// translation, rotation about the centroid of the nodes), and with twist
    /// the rotation about the axis (u_θ = r), in 3D the six (translations
    /// and rotations about the centroid along x, y, z), over every dof in
    /// PETSc order, orthonormalized (modified Gram-Schmidt on the replicated
    /// vectors, so every rank gets the same), as this rank's owned parts: the
    /// near-null space for algebraic multigrid (`-pc_type gamg`).
    ///
    /// Of the assembly, not of each body, although the soft interface lets one
    /// body move almost rigidly against the other: GAMG builds its coarse space
    /// aggregate by aggregate from these vectors restricted to the aggregate,
    /// and with [`super::GAMG_THRESHOLD`] dropping the interface springs from
    /// the aggregation graph every aggregate lies in one body, where the three
    /// restricted modes are that body's rigid motions. Per-body vectors (six)
    /// gave every aggregate six coarse unknowns, three of them zero on it:
    /// twice the coarse unknowns and operator complexity 1.44 against 1.15
    /// (docs/performance.md, "GAMG settings", has the measurements).
    pub fn rigid_body_modes(&self, model: &Model, rank: usize) -> Vec<Vec<f64>> {
        let nodes = &model.mesh.nodes;
        let n = self.global_len();
        let m = nodes.len().max(1) as f64;
        let c = nodes.iter().fold([0.0f64; 3], |c, p| {
            [c[0] + p[0] / m, c[1] + p[1] / m, c[2] + p[2] / m]
        });
        let nd = model.node_dofs();
        let solid = model.mesh.dim() == 3;
        let count = match (nd.twist(), solid) {
            (true, _) => 4,
            (false, true) => 6,
            (false, false) => 3,
        };
        let mut modes = vec![vec![0.0; n]; count];
        for (i, p) in nodes.iter().enumerate() {
            let at = |c: usize| self.dof_index[nd.dof(i, c)] as usize;
            let (ix, iy) = (at(0), at(1));
            let r = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
            modes[0][ix] = 1.0;
            modes[1][iy] = 1.0;
            // the rotation about z
            modes[2][ix] = -r[1];
            modes[2][iy] = r[0];
            if nd.twist() {
                // the rotation about the axis: u_θ = r
                modes[3][at(2)] = p[0];
            } else if solid {
                // u_z, then the rotations about x and y (ω × r)
                let iz = at(2);
                modes[3][iz] = 1.0;
                modes[4][iy] = -r[2];
                modes[4][iz] = r[1];
                modes[5][ix] = r[2];
                modes[5][iz] = -r[0];
            }
        }
        // an empty mesh gives zero vectors: drop them
        modes.retain(|m| m.iter().any(|&v| v != 0.0));
        for k in 0..modes.len() {
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
        let lo = self.offsets[rank];
        modes
            .iter()
            .map(|m| m[lo..lo + self.local_len(rank)].to_vec())
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
            let eptr: Vec<metis::Idx> = std::iter::once(0)
                .chain(mesh.elements.iter().scan(0, |at, el| {
                    *at += el.corners().len();
                    Some(*at as metis::Idx)
                }))
                .collect();
            let eind: Vec<metis::Idx> = mesh
                .elements
                .iter()
                .flat_map(|el| el.corners().iter().map(|&n| n as metis::Idx))
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
            for &n in el.nodes() {
                node_owner[n] = node_owner[n].min(element_owner[e]);
            }
        }
        let point_owner: Vec<usize> = model
            .interfaces
            .iter()
            .flat_map(|im| {
                im.points
                    .iter()
                    .map(|pt| node_owner[im.pairs[pt.coupling.first_pair()].b])
            })
            .collect();
        // dofs sorted by (owner, node, component); every node has an owner
        // because Mesh::validate refuses nodes that belong to no element
        // a pretension section's reference node belongs to rank 0
        node_owner.resize(mesh.nodes.len() + model.sections.len(), 0);
        let nd = model.num_dofs();
        let k = model.node_dofs().per_node();
        let mut offsets = vec![0usize; ranks + 1];
        for &o in &node_owner {
            offsets[o + 1] += k;
        }
        for r in 0..ranks {
            offsets[r + 1] += offsets[r];
        }
        let mut next = offsets.clone();
        let mut dof_index = vec![0 as ffi::PetscInt; nd];
        for (v, &o) in node_owner.iter().enumerate() {
            for (c, d) in model.node_dofs().of(v).enumerate() {
                dof_index[d] = (next[o] + c) as ffi::PetscInt;
            }
            next[o] += k;
        }
        let mut petsc_index = vec![0 as ffi::PetscInt; model.dofs.n_eq];
        for (d, &p) in dof_index.iter().enumerate() {
            if let Some(e) = model.dofs.equation(d) {
                petsc_index[e] = p;
            }
        }
        Ok(Partition {
            element_owner,
            point_owner,
            petsc_index,
            dof_index,
            offsets,
        })
    }

    /// The columns of the tangent's pattern whose equations `rank` owns (by
    /// symmetry, the couplings of its rows): built for preallocation and
    /// dropped, so no rank holds the whole pattern.
    pub(crate) fn owned_pattern(&self, model: &Model, rank: usize) -> Pattern {
        let (lo, hi) = (self.offsets[rank], self.offsets[rank + 1]);
        model.pattern_of(|c| (lo..hi).contains(&(self.petsc_index[c] as usize)))
    }

    /// Exact diagonal / off-diagonal nonzeros per owned row of `rank`, from
    /// its [`Partition::owned_pattern`] (a column's rows are the row's columns);
    /// `prescribed`: this rank's [`Partition::prescribed_rows`], one entry each.
    pub(crate) fn preallocation(
        &self,
        pattern: &Pattern,
        rank: usize,
        prescribed: &[ffi::PetscInt],
    ) -> (Vec<ffi::PetscInt>, Vec<ffi::PetscInt>) {
        let (lo, hi) = (self.offsets[rank], self.offsets[rank + 1]);
        let (mut d, mut o) = (vec![0; hi - lo], vec![0; hi - lo]);
        for c in 0..pattern.n {
            let row = self.petsc_index[c] as usize;
            if row < lo || row >= hi {
                continue;
            }
            for &r in pattern.rows(c) {
                let col = self.petsc_index[r as usize] as usize;
                if col >= lo && col < hi {
                    d[row - lo] += 1;
                } else {
                    o[row - lo] += 1;
                }
            }
        }
        for &p in prescribed {
            d[p as usize - lo] = 1;
        }
        (d, o)
    }
}

pub(crate) struct PetscBackend<'p> {
    pub(super) world: SimpleCommunicator,
    pub(super) rank: usize,
    ranks: usize,
    model: &'p Model,
    pub part: Partition,
    /// (local position, equation) of this rank's equations.
    pub(super) owned: Vec<(usize, usize)>,
    /// Owned rows of prescribed dofs: 1 on the diagonal, nothing else.
    prescribed: Vec<ffi::PetscInt>,
    pub(super) petsc: &'p Petsc<'p>,
    /// The solid part, kept apart only when a method reuses it under new
    /// springs ([`crate::linalg::backend::Backend::reuse_solid`]); otherwise element
    /// blocks go straight into `mat` and this second matrix is not held.
    solid: Option<PMat<'p>>,
    mat: PMat<'p>,
    pub(super) ksp: Ksp<'p>,
    pub(super) b: PVec<'p>,
    pub(super) x: PVec<'p>,
    pub(super) to_all: ToAll<'p>,
    pub(super) gathered: Vec<f64>,
    idx: Vec<ffi::PetscInt>,
    /// Krylov iterations over the run.
    pub ksp_iterations: usize,
    keep_solid: bool,
    /// The interface equations where the interface loop runs on this model
    /// (asked for by name, `[solver] interface_loop = true`, and the serial
    /// backend's rule), increasing; else empty ([`super::condensed`]).
    pub(super) loop_equations: Vec<usize>,
    /// The KSP whose factor the interface loop uses when SNES solves the
    /// Newton systems ([`PetscBackend::factor_of`]); else the backend's own.
    pub(super) factor_ksp: Option<HeldKsp>,
    /// The requested entries of the inverse for MUMPS, built at the first
    /// condensation ([`super::condensed`]).
    pub(super) inverse_pattern: Option<super::owned::InversePattern>,
}

/// A reference to a KSP that another object owns, released on drop.
pub(super) struct HeldKsp(pub(super) ffi::KSP);

impl Drop for HeldKsp {
    fn drop(&mut self) {
        // SAFETY: referenced in `PetscBackend::factor_of`; released once.
        unsafe {
            ffi::KSPDestroy(&mut self.0);
        }
    }
}

/// Fixes a matrix's nonzero structure once: explicit zeros over the whole
/// pattern of this rank's rows, 1 on the prescribed rows' diagonal.
fn fix_pattern(
    mat: &mut PMat<'_>,
    pattern: &Pattern,
    part: &Partition,
    rank: usize,
    prescribed: &[ffi::PetscInt],
) -> Result<()> {
    let (lo, hi) = (part.offsets[rank], part.offsets[rank + 1]);
    let mut cols = Vec::new();
    let mut zeros = Vec::new();
    for c in 0..pattern.n {
        let row = part.petsc_index[c];
        if (row as usize) < lo || (row as usize) >= hi {
            continue;
        }
        cols.clear();
        cols.extend(
            pattern
                .rows(c)
                .iter()
                .map(|&r| part.petsc_index[r as usize]),
        );
        zeros.resize(cols.len(), 0.0);
        mat.set_row(row, &cols, &zeros)?;
    }
    for &p in prescribed {
        mat.set_row(p, &[p], &[1.0])?;
    }
    mat.assemble()
}

/// Doubles per MPI reduction in [`PetscBackend::reduce`].
const REDUCE_CHUNK: usize = 1 << 16;

impl<'p> PetscBackend<'p> {
    /// Reduces `v` over all ranks in place, in chunks of [`REDUCE_CHUNK`], so
    /// the send copy (and MPI's temporaries) stay small for long vectors.
    pub(super) fn reduce(&self, v: &mut [f64], op: SystemOperation) {
        let mut send = Vec::with_capacity(REDUCE_CHUNK.min(v.len()));
        for chunk in v.chunks_mut(REDUCE_CHUNK) {
            send.clear();
            send.extend_from_slice(chunk);
            self.world.all_reduce_into(&send[..], chunk, op);
        }
    }

    /// `linear`: the KSP's starting point (the options database overrides it).
    pub fn new(
        petsc: &'p Petsc,
        world: SimpleCommunicator,
        model: &'p Model,
        linear: LinearDefault,
    ) -> Result<Self> {
        let (rank, ranks) = (world.rank() as usize, world.size() as usize);
        let part = Partition::new(model, ranks)?;
        let prescribed = part.prescribed_rows(model, rank);
        let pattern = part.owned_pattern(model, rank);
        let (d, o) = part.preallocation(&pattern, rank, &prescribed);
        let local = part.local_len(rank);
        let n = part.global_len();
        let bs = model.node_dofs().per_node();
        let mut mat = PMat::aij(petsc, local, n, bs, &d, &o)?;
        fix_pattern(&mut mat, &pattern, &part, rank, &prescribed)?;
        if model.symmetric_tangent() {
            mat.set_symmetric()?;
        }
        drop(pattern);
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
            prescribed,
            petsc,
            part,
            solid: None,
            mat,
            ksp: Ksp::new(petsc, linear)?,
            b,
            x,
            to_all,
            gathered: vec![0.0; n],
            idx: Vec::with_capacity(24),
            ksp_iterations: 0,
            keep_solid: false,
            loop_equations: match linear {
                // only where the case (or `--interface-loop on`) asks for it by
                // name: on PETSc it seldom pays ([`super::condensed`])
                LinearDefault::Direct { .. } if model.solver.interface_loop == Some(true) => {
                    crate::linalg::backend::serial::interface_loop_equations(model)?
                }
                _ => Vec::new(),
            },
            factor_ksp: None,
            inverse_pattern: None,
        })
    }

    /// The interface loop uses the factor of `ksp` (SNES's, which solves the
    /// Newton systems when SNES drives the steps) instead of the backend's
    /// own; the backend holds a reference to it.
    pub(crate) fn factor_of(&mut self, ksp: ffi::KSP) -> Result<()> {
        // SAFETY: a valid KSP (the caller's SNES's); the reference is
        // released by `HeldKsp`'s drop.
        chk(
            unsafe { ffi::PetscObjectReference(ksp as ffi::PetscObject) },
            "PetscObjectReference",
        )?;
        self.factor_ksp = Some(HeldKsp(ksp));
        Ok(())
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
    pub(crate) fn system_matrix(&self) -> ffi::Mat {
        self.mat.raw
    }

    /// Mallocs during assembly of the system matrix (0 with exact preallocation).
    pub fn mallocs(&self) -> Result<f64> {
        let solid = match &self.solid {
            Some(s) => s.mallocs()?,
            None => 0.0,
        };
        Ok(self.mat.mallocs()? + solid)
    }
}

impl crate::linalg::backend::Comm for PetscBackend<'_> {
    fn ranks(&self) -> usize {
        self.ranks
    }
    fn rank(&self) -> usize {
        self.rank
    }
    fn sum(&self, v: &mut [f64]) {
        self.reduce(v, SystemOperation::sum());
    }
    fn max(&self, v: &mut [f64]) {
        self.reduce(v, SystemOperation::max());
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

impl crate::linalg::backend::Backend for PetscBackend<'_> {
    fn name(&self) -> &'static str {
        "petsc"
    }
    fn owns_element(&self, e: usize) -> bool {
        self.part.element_owner[e] == self.rank
    }
    fn owns_point(&self, q: usize) -> bool {
        self.part.point_owner[q] == self.rank
    }
    fn reuse_solid(&mut self, reuse: bool) {
        self.keep_solid = reuse;
    }
    fn begin_solid(&mut self) -> Result<()> {
        if self.keep_solid && self.solid.is_none() {
            let pattern = self.part.owned_pattern(self.model, self.rank);
            let (d, o) = self
                .part
                .preallocation(&pattern, self.rank, &self.prescribed);
            let local = self.part.local_len(self.rank);
            let mut solid = PMat::aij(self.petsc, local, self.part.global_len(), 2, &d, &o)?;
            fix_pattern(
                &mut solid,
                &pattern,
                &self.part,
                self.rank,
                &self.prescribed,
            )?;
            self.solid = Some(solid);
        }
        let target = self.solid.as_mut().unwrap_or(&mut self.mat);
        // values may be pending from an attempt that failed midway
        target.assemble()?;
        target.zero()?;
        // added (not inserted): element blocks are added next, and PETSc
        // does not mix the two modes between assemblies
        for &p in &self.prescribed {
            target.add(&[p], &[1.0])?;
        }
        Ok(())
    }
    fn add_solid(&mut self, _block: usize, dofs: &[usize], k: &[f64]) -> Result<()> {
        self.indices(dofs);
        self.solid
            .as_mut()
            .unwrap_or(&mut self.mat)
            .add(&self.idx, k)
    }
    fn begin_contact(&mut self) -> Result<()> {
        // without a kept solid matrix the element blocks are already in `mat`
        // (the engine reassembles them before every contact pass then)
        match &mut self.solid {
            Some(solid) => {
                solid.assemble()?;
                self.mat.assemble()?;
                self.mat.copy_from(solid)
            }
            None => Ok(()),
        }
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
    fn linear_solver(&self) -> String {
        self.ksp.describe()
    }
    fn condensed(&mut self) -> Option<&mut dyn crate::linalg::backend::Condensed> {
        self.condensation()
    }
    fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("ksp_iterations", self.ksp_iterations as f64),
            ("assembly_mallocs", self.mallocs().unwrap_or(f64::NAN)),
            ("owned_equations_rank0", self.part.owned(0).len() as f64),
        ]
    }
}
