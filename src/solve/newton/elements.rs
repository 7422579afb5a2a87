//! The element loop of an assembly: internal forces, Gauss states and
//! element tangents of the held elements, computed on threads in batches and
//! added in element order, with a result independent of the thread count.

use super::{held_out, Engine};
use crate::input::mesh::NodeDofs;
use crate::linalg::failure::StepFailure;
use crate::model::Model;
use crate::physics::element::solid::{Response, Tangent};
use crate::physics::element::solid3::MAX_POINTS3;
use crate::physics::material::{GaussMut, GaussRef, PointState};
use crate::solve::State;

/// Elements per batch of the element loop ([`Engine::assemble_solids`]): the
/// batch's element forces and tangents (ne + ne² numbers per element, ne the
/// element's dofs: 272 and 4.5 MB with 2 dofs a node, 600 and 9.8 MB with
/// twist) are the only memory the threads add.
pub(super) const ELEMENT_BATCH: usize = 2048;
/// Fewest elements one thread of the element loop is given (a smaller batch
/// takes fewer threads): starting a thread costs about as much as computing
/// a few elastic elements.
const MIN_ELEMENTS_PER_THREAD: usize = 128;

impl Engine<'_> {
    /// The element loop over the held elements: internal forces into
    /// `self.r`, Gauss states into `trial`, element tangents into the backend
    /// when `solid_tangent` asks for them. Returns this rank's failure (a
    /// return mapping, or an injected fault), not yet shared.
    ///
    /// Threaded, with a result independent of the thread count, bit for bit:
    /// the held elements are taken in batches of [`ELEMENT_BATCH`]; a batch is
    /// cut into contiguous chunks, one per thread, and each thread computes
    /// its chunk's element forces and tangents into the batch buffers and its
    /// elements' Gauss states into its own slice of `trial.gauss` (an
    /// element's numbers depend on that element alone). Then this thread adds
    /// them into `self.r` and the backend in element order, as one thread
    /// would. A chunk stops at its first failing element; the first failure
    /// in element order gives the message, the elements before it are added
    /// and no later batch is computed, as on one thread (later elements of
    /// the batch may hold trial Gauss states, in a trial that is discarded).
    pub(super) fn assemble_solids(
        &mut self,
        committed: &State,
        trial: &mut State,
        lambda: f64,
        response: Response,
        solid_tangent: Option<Tangent>,
    ) -> Result<Option<String>, StepFailure> {
        let m = self.model;
        // each body's free thermal strain α ΔT and material at this
        // pseudo-time
        let thermal = m.conditions(lambda);
        let be = &mut self.backend;
        let err = StepFailure::Linear;
        if solid_tangent.is_some() {
            be.begin_solid().map_err(err)?;
        }
        let n = self.held_elements.len();
        let batch = n.min(ELEMENT_BATCH);
        let nd = m.node_dofs();
        // one slot per element, as large as the largest element's
        let (k, ne) = (nd.per_node(), m.max_element_dofs());
        if self.fe_batch.len() < batch * ne {
            self.fe_batch.resize(batch * ne, 0.0);
        }
        if solid_tangent.is_some() && self.ke_batch.len() < batch * ne * ne {
            self.ke_batch.resize(batch * ne * ne, 0.0);
        }
        let mut failure: Option<String> = None;
        let mut dofs = [0usize; NodeDofs::MAX_ELEMENT];
        let mut b0 = 0;
        while b0 < n && failure.is_none() {
            let b1 = (b0 + ELEMENT_BATCH).min(n);
            let len = b1 - b0;
            let fe = &mut self.fe_batch[..len * ne];
            let ke = if solid_tangent.is_some() {
                &mut self.ke_batch[..len * ne * ne]
            } else {
                &mut self.ke_batch[..0]
            };
            let points = &self.held_offsets[b0..=b1];
            let gauss = points[0]..points[len];
            let first = element_batch(
                m,
                &self.held_elements[b0..b1],
                points,
                committed.gauss.range(gauss.clone()),
                trial.gauss.range_mut(gauss),
                &trial.u,
                &thermal,
                response,
                solid_tangent,
                fe,
                ke,
                self.threads,
            );
            let done = first.as_ref().map_or(len, |f| f.0);
            for i in 0..done {
                let el = &m.mesh.elements[self.held_elements[b0 + i] as usize];
                let own = nd.element(el.family.nodes());
                let fe = &self.fe_batch[i * ne..][..own];
                for (a, &n) in el.nodes().iter().enumerate() {
                    for (c, d) in nd.of(n).enumerate() {
                        self.r[d] += fe[k * a + c];
                        dofs[k * a + c] = d;
                    }
                }
                if solid_tangent.is_some() {
                    let b = self.held_elements[b0 + i] as usize;
                    let ke = &self.ke_batch[i * ne * ne..][..own * own];
                    match m.expansion(b) {
                        None => be.add_solid(b, &dofs[..own], ke),
                        Some(x) => be.add_solid(b, &x.dofs, &held_out(x, &self.held, ke)),
                    }
                    .map_err(err)?;
                }
            }
            if let Some((i, msg)) = first {
                let e = self.held_elements[b0 + i] as usize;
                let body = m.mesh.elements[e].body;
                failure = Some(format!(
                    "element {e} (body \"{}\"): {msg}",
                    m.mesh.bodies[body]
                ));
            }
            b0 = b1;
        }
        if self
            .fault
            .is_some_and(|(r, a)| r == be.rank() && self.assemblies >= a)
        {
            failure = Some(format!(
                "fault injected on rank {r} (--inject-fault)",
                r = be.rank()
            ));
        }
        Ok(failure)
    }
}

/// Element forces (and tangents, when `tangent` asks and `ke` has room) of
/// the elements `ids` into `fe`/`ke` (one slot of ne and ne² numbers per
/// element, in order, ne = [`NodeDofs::element`] of the largest element; an
/// element fills the front of its slot), their Gauss states into `trial`
/// (element i's at `points[i] − points[0]..points[i + 1] − points[0]`, as
/// `committed`), on up to `threads` threads: contiguous chunks, the first on
/// this thread. Returns the first failing element in order (its position in
/// `ids`) and the message.
#[allow(clippy::too_many_arguments)]
fn element_batch(
    m: &Model,
    ids: &[u32],
    points: &[usize],
    committed: GaussRef<'_>,
    trial: GaussMut<'_>,
    u: &[f64],
    thermal: &crate::model::Conditions<'_>,
    response: Response,
    tangent: Option<Tangent>,
    fe: &mut [f64],
    ke: &mut [f64],
    threads: usize,
) -> Option<(usize, String)> {
    let len = ids.len();
    let ne = m.max_element_dofs();
    let t = threads.min(len.div_ceil(MIN_ELEMENTS_PER_THREAD)).max(1);
    if t == 1 {
        let work = (ids, points, committed, trial);
        return element_chunk(m, work, u, thermal, response, tangent, fe, ke);
    }
    let per = len.div_ceil(t);
    // ke is empty without a tangent: every chunk then gets an empty slice
    let ke_per = if ke.is_empty() {
        usize::MAX
    } else {
        per * ne * ne
    };
    let mut ke_chunks: Vec<&mut [f64]> = ke.chunks_mut(ke_per).collect();
    ke_chunks.resize_with(ids.chunks(per).len(), || &mut []);
    // each chunk's Gauss states: its elements' points, in order
    let mut gauss = Vec::new();
    let (mut rest_c, mut rest_t) = (committed, trial);
    for c in 0..ids.chunks(per).len() {
        let (i0, i1) = (c * per, ((c + 1) * per).min(len));
        let n = points[i1] - points[i0];
        let (cg, rc) = rest_c.split_at(n);
        let (tg, rt) = std::mem::take(&mut rest_t).split_at_mut(n);
        (rest_c, rest_t) = (rc, rt);
        gauss.push((&points[i0..=i1], cg, tg));
    }
    let mut chunks = ids
        .chunks(per)
        .zip(gauss)
        .zip(fe.chunks_mut(per * ne))
        .zip(ke_chunks)
        .enumerate()
        .map(|(c, (((ids, (p, cg, tg)), fe), ke))| (c * per, (ids, p, cg, tg), fe, ke));
    let (_, work0, fe0, ke0) = chunks.next().expect("a batch holds an element");
    std::thread::scope(|s| {
        let others: Vec<_> = chunks
            .map(|(at, work, fe, ke)| {
                s.spawn(move || {
                    element_chunk(m, work, u, thermal, response, tangent, fe, ke)
                        .map(|(i, msg)| (at + i, msg))
                })
            })
            .collect();
        let first = element_chunk(m, work0, u, thermal, response, tangent, fe0, ke0);
        // every thread is joined; the earliest chunk that failed holds the
        // first failing element
        let rest: Vec<_> = others
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .collect();
        first.or_else(|| rest.into_iter().flatten().next())
    })
}

/// One chunk of [`element_batch`]: its elements, their Gauss point offsets,
/// and their committed and trial states.
type Work<'a> = (&'a [u32], &'a [usize], GaussRef<'a>, GaussMut<'a>);

/// [`element_batch`] on one thread: stops at the first failing element.
#[allow(clippy::too_many_arguments)]
fn element_chunk(
    m: &Model,
    (ids, points, committed, mut trial): Work<'_>,
    u: &[f64],
    thermal: &crate::model::Conditions<'_>,
    response: Response,
    tangent: Option<Tangent>,
    fe: &mut [f64],
    ke: &mut [f64],
) -> Option<(usize, String)> {
    let nd = m.node_dofs();
    let slot = m.max_element_dofs();
    let mut scratch = vec![0.0; slot * slot];
    // an element's committed and trial states, as the material computes them
    let mut c_buf = [PointState::default(); MAX_POINTS3];
    let mut t_buf = [PointState::default(); MAX_POINTS3];
    // each point's material, where a temperature field varies it (filled
    // only there: the uniform path takes the body's)
    let mut m_buf = Vec::new();
    for (i, &e) in ids.iter().enumerate() {
        let e = e as usize;
        let el = &m.mesh.elements[e];
        let ne = nd.element(el.family.nodes());
        let ue = m.element_u(e, u);
        let gs = points[i] - points[0]..points[i + 1] - points[0];
        let ke = match ke.get_mut(i * slot * slot..(i + 1) * slot * slot) {
            Some(ke) => &mut ke[..ne * ne],
            None => &mut scratch[..ne * ne],
        };
        let np = gs.len();
        committed.range(gs.clone()).load(&mut c_buf[..np]);
        let mut tg = trial.range_mut(gs);
        tg.load(&mut t_buf[..np]);
        let geo = m.element_geometry(e);
        let th = thermal.point_thermal(el.body, &geo);
        let done = geo.forces(
            thermal.point_materials(el.body, &geo, &mut m_buf),
            &th,
            &ue[..ne],
            &c_buf[..np],
            &mut t_buf[..np],
            response,
            tangent,
            &mut fe[i * slot..][..ne],
            ke,
        );
        tg.store(&t_buf[..np]);
        if let Err(msg) = done {
            return Some((i, msg));
        }
    }
    None
}
