//! `restart.bin`: the committed state of a run after a converged increment, so
//! that `asperity run CASE --restart DIR` continues exactly where it stopped.
//!
//! Layout (all integers and floats little-endian; floats as their exact IEEE-754
//! bits, so a resumed run is bit-for-bit the uninterrupted one):
//!
//! ```text
//! magic        8 bytes  "ASPRSTRT"
//! version      u32      2
//! reserved     u32      0
//! fingerprint  u64      FNV-1a of the effective case (after command-line
//!                       overrides, as its canonical JSON: Case::key) and the
//!                       mesh; a restart with another case or mesh is refused
//! sections     u32      count, then per section:
//!                name   u16 length + UTF-8
//!                kind   u8   1 = f64, 2 = u64, 3 = u8, 4 = UTF-8 text
//!                count  u64  number of elements (bytes for text)
//!                data
//! checksum     u64      FNV-1a (64-bit state, over 64-bit words, see
//!                       [`fnv1a`]) of every byte before it
//! ```
//!
//! A file of another version is refused before anything else of it is
//! read (its version and this build's named: run the case again from the
//! start); there are no compatibility branches for earlier layouts. A
//! version-2 file holds exactly the sections of `SECTIONS`, each once, in
//! any order: a missing section and one of another name are refused by
//! name. They are `increment`, `load_factor`, `last_step`, `last_du` (the
//! last increment's displacement change, the predictor's direction; empty
//! when the next step starts from the committed state), `pending_load_factor`,
//! `pending_depth` (fixed schedule), `auto_waypoints`, `auto_step`,
//! `auto_failures` (automatic step control), `cutbacks` (total, since the
//! last increment), `elastic_ratio_prev`, `counters` (Newton iterations,
//! factorizations), `interface_counters` (the interface loop's loops,
//! iterations and fallbacks), `event_counters` (the event searches' share
//! of the Newton iterations), `u`,
//! `gauss` (10 per Gauss point: σxx σyy σxy σzz, εᵖ ×4, ε̄ᵖ, yielding),
//! `status` (interface status codes), `contact` (25 per interface point, as
//! [`crate::physics::contact::PointState::pack`] lays them out:
//! plastic slip, max shear memory κ, p_T, u_T, μ_F, the kinematic memory;
//! with twist 56, `crate::physics::contact::PointState::pack_twist`: p_T, u_T,
//! μ_F, p_Tθ, u_Tθ and the vector law's state), `prescribed_reaction`,
//! `curve` (10 per increment: number, load factor, iterations, cutbacks, normal
//! force, mean pressure, load kN, centre displacement, max ε̄ᵖ, prescribed
//! reaction), `first_yield` (load factor, mean pressure, load kN, x, depth,
//! element, z; empty before the first yield) with `first_yield_body` (empty
//! then), the VTU series `pvd_load_factor`, `pvd_file` (names separated by
//! newlines), `joint_totals` (2 per interface: frictional dissipation and
//! tangential work so far), `joints` (11 per interface and increment, as
//! [`crate::measure::joint::JointMeasures::pack`] lays them out),
//! `joints_twist` (with twist 3 per interface and increment: torque,
//! circumferential slip, twist,
//! `crate::measure::joint::JointMeasures::pack_twist`; empty without),
//! `pretension` (2 per pretension section and increment: force,
//! shortening), `table_reach` (2 per interface: the largest approach u_N
//! and pressure p_N over the converged states so far, see
//! [`crate::model::interface::extrapolation`]), `record_width` (the values
//! of one designer's record, [`crate::model::outputs`]: the model's), `records`
//! (the record of every increment) and `events` (the events located so
//! far, [`crate::solve::events::Event::pack`]). Every increment has its
//! curve row, joint rows, pretension row and record.
//!
//! # A restart folder is input
//!
//! Anyone can write a well-formed file (the checksum and the fingerprint are
//! computable), so they only catch accidents; [`read`] checks every value
//! against the case before any of it is used, and refuses a mismatch with
//! one line `<DIR>/restart.bin: <what is wrong>` (exit 2, nothing written;
//! every float of the file it quotes in its shortest form, `num`: `1e300`,
//! never 301 digits):
//!
//! - sizes: the file's size from its metadata against `Bounds` (what the
//!   model's dofs, Gauss points, interface points and the case's most
//!   increments need) before it is read; at most `MAX_SECTIONS` sections
//!   of distinct names, each count within the bytes that remain before its
//!   data is copied; at most `Bounds::increments` increments;
//! - the load history: the `curve` rows are numbered 1, 2, … with finite
//!   values and whole counts, and are replayed from the case's own stepper
//!   (`Stepper::replay`: the fixed schedule with each row's cutbacks, bit
//!   for bit; automatic steps towards the case's waypoints, never past one,
//!   never longer than the largest step); `load_factor` and `last_step` are
//!   the last row's, `pending_*` (fixed) or `auto_waypoints` (automatic)
//!   exactly what that replay leaves, the other mode's part untouched, so
//!   the resumed run ends where the case's history ends; `auto_step` within
//!   the case's smallest and largest step; no failures or cutbacks pending
//!   and the cutback total the curve's;
//! - the counters: Newton iterations (the event searches' share, at most
//!   all of them, set apart) and factorizations at most what a run
//!   of the case can count after the curve's increments and cutbacks
//!   (`most_iterations`: per attempt a predicted and a plain solve, each
//!   with the stabilization's levels and releases, plus one first-yield
//!   search, at the case's iteration limit, × 2);
//! - the state: `u`, `last_du`, `gauss`, `contact`, `joint_totals`,
//!   `prescribed_reaction`, `table_reach` finite; `u` and `last_du` within
//!   ±`MAX_DISPLACEMENT` (the displacement range of a case, 10⁴ mm); every
//!   Gauss point a state its body's return mapping can leave
//!   (`check_gauss_point`): ε̄ᵖ ≥ 0, the yielding flag 0 or 1, |σ| ≤
//!   `MAX_STRESS`, σzz = 0 in plane stress; in an elastic body (no
//!   `yield_stress`) εᵖ, ε̄ᵖ and the flag all 0; otherwise |εᵖ| ≤
//!   `MAX_PLASTIC_STRAIN`, ε̄ᵖ ≤ `MAX_PEEQ`, εᵖ deviatoric (trace 0),
//!   ε̄ᵖ ≥ √(2/3)|εᵖ| and σ_eq ≤ σ_Y + H ε̄ᵖ (round-off allowed); every
//!   status code a status ([`Status::checked`]); `joints` rows finite;
//!   `first_yield` finite, within the curve's load factors, at an element of
//!   the mesh whose body `first_yield_body` names; every interface's
//!   `table_reach` (u_N, p_N) within [0, `MAX_DISPLACEMENT`] ×
//!   [0, `MAX_PRESSURE`], p_N the normal law's pressure at u_N, and at
//!   least the restored state's own reach ([`Reach::of`]);
//! - the records beside the state (`decode/records.rs`): every `curve`
//!   row's normal force within [0, the pressure range × the first
//!   interface's area], its mean pressure and load that force over the area
//!   and in kN, exactly, its displacement and PEEQ within the state's
//!   ranges; the last increment's `curve` row, `joints` / `joints_twist` rows and `records`
//!   from the probes on exactly what the restored state gives
//!   ([`Measures::of`], `crate::solve::joint_measures`,
//!   `crate::model::outputs::Plan::state_part`); every joint row's normal
//!   force within [0, the pressure range × its area], its status measures
//!   ≥ 0 and adding up to the interface's, its tangential force and torque
//!   within μ F_N and μ r_max F_N; every probe value within
//!   ±`MAX_DISPLACEMENT`; `pretension` rows: a free section's force
//!   (force control before its lock) and a prescribed shortening
//!   recomputed from the case (`Model::section_row`), a locked section's
//!   shortening the one at its lock in every later row and in `u`;
//! - names: every `pvd_file` name is `vtu/NNNN.vtu` exactly as the writer
//!   names an increment (`vtu_name`), for increasing converged increments,
//!   with that increment's load factor; every file a resumed run copies
//!   (`folder_files`: `restart.bin`, `interface/NNNN.csv`, the VTU series)
//!   is a regular file inside the folder, neither it nor its folder a
//!   symbolic link, within its size bound; the copy (`copy_in`) opens it
//!   again without following links and creates each file new in the
//!   temporary output folder.

use crate::error::{Error, Result};
use crate::input::case::ranges;
use crate::measure::joint::{JointMeasures, JointTotals};
use crate::model::interface::extrapolation::Reach;
use crate::model::Model;
use crate::physics::contact::{PointState as ContactState, Status};
use crate::physics::material::{PointState, VonMises};
use crate::solve::stepping::Stepper;
use crate::solve::{stabilization as stabilize, yield_point};
use crate::solve::{Checkpoint, FirstYield, Increment, Measures};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

pub(crate) const MAGIC: &[u8; 8] = b"ASPRSTRT";
pub(crate) const VERSION: u32 = 5;
pub(crate) const FILE: &str = "restart.bin";

/// The sections of a restart file of this [`VERSION`], each exactly once
/// (in the order they are written).
pub(crate) const SECTIONS: [&str; 33] = [
    "increment",
    "load_factor",
    "last_step",
    "last_du",
    "pending_load_factor",
    "pending_depth",
    "auto_waypoints",
    "auto_step",
    "auto_failures",
    "cutbacks",
    "elastic_ratio_prev",
    "counters",
    "interface_counters",
    "event_counters",
    "u",
    "gauss",
    "status",
    "contact",
    "prescribed_reaction",
    "curve",
    "first_yield",
    "first_yield_body",
    "joint_totals",
    "joints",
    "joints_twist",
    "joints_space",
    "pretension",
    "record_width",
    "records",
    "events",
    "table_reach",
    "pvd_load_factor",
    "pvd_file",
];

/// FNV-1a with 64-bit state applied to 64-bit little-endian words (8× fewer
/// multiplications than byte-wise FNV-1a), the last `len % 8` bytes one by one.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    let mut f = Fnv::default();
    f.update(bytes);
    f.finish()
}

const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// [`fnv1a`] fed in pieces: the same value for any split of the same bytes.
struct Fnv {
    h: u64,
    pending: [u8; 8],
    n: usize,
}

impl Default for Fnv {
    fn default() -> Self {
        Fnv {
            h: 0xcbf2_9ce4_8422_2325,
            pending: [0; 8],
            n: 0,
        }
    }
}

impl Fnv {
    fn word(&mut self, w: [u8; 8]) {
        self.h ^= u64::from_le_bytes(w);
        self.h = self.h.wrapping_mul(FNV_PRIME);
    }

    fn update(&mut self, mut b: &[u8]) {
        if self.n > 0 {
            let take = (8 - self.n).min(b.len());
            self.pending[self.n..self.n + take].copy_from_slice(&b[..take]);
            self.n += take;
            b = &b[take..];
            if self.n < 8 {
                return;
            }
            self.word(self.pending);
            self.n = 0;
        }
        let words = b.chunks_exact(8);
        let tail = words.remainder();
        for w in words {
            self.word(w.try_into().expect("8 bytes"));
        }
        self.pending[..tail.len()].copy_from_slice(tail);
        self.n = tail.len();
    }

    fn finish(&self) -> u64 {
        let mut h = self.h;
        for &b in &self.pending[..self.n] {
            h ^= u64::from(b);
            h = h.wrapping_mul(FNV_PRIME);
        }
        h
    }
}

/// Fingerprint of what a run solves: the effective case (without its file
/// location and free-text description) and the mesh.
pub fn fingerprint(model: &Model) -> u64 {
    let mut bytes = model.case_key().as_bytes().to_vec();
    for n in &model.mesh.nodes {
        for v in n.iter() {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
    }
    for el in &model.mesh.elements {
        bytes.extend_from_slice(&(el.body as u64).to_le_bytes());
        for &n in el.nodes().iter() {
            bytes.extend_from_slice(&(n as u64).to_le_bytes());
        }
    }
    bytes.extend_from_slice(&(model.num_dofs() as u64).to_le_bytes());
    fnv1a(&bytes)
}

enum Data {
    F64(Vec<f64>),
    U64(Vec<u64>),
    U8(Vec<u8>),
    Text(String),
}

/// Writes sections to a writer, hashing them on the way; without a writer it
/// only counts the sections (and skips the payloads).
struct Encoder<'w> {
    out: Option<(&'w mut dyn Write, Fnv)>,
    sections: u32,
}

impl Encoder<'_> {
    fn put(&mut self, b: &[u8]) -> std::io::Result<()> {
        match &mut self.out {
            Some((w, f)) => {
                f.update(b);
                w.write_all(b)
            }
            None => Ok(()),
        }
    }
    fn section(&mut self, name: &str, kind: u8, count: usize) -> std::io::Result<()> {
        self.sections += 1;
        self.put(&(name.len() as u16).to_le_bytes())?;
        self.put(name.as_bytes())?;
        self.put(&[kind])?;
        self.put(&(count as u64).to_le_bytes())
    }
    /// `count` values from `v`, converted in chunks (nothing held whole).
    fn f64_iter(
        &mut self,
        name: &str,
        count: usize,
        v: impl Iterator<Item = f64>,
    ) -> std::io::Result<()> {
        self.section(name, 1, count)?;
        if self.out.is_none() {
            return Ok(());
        }
        let mut chunk = [0u8; 8 * 512];
        let mut k = 0;
        for x in v {
            chunk[8 * k..8 * k + 8].copy_from_slice(&x.to_le_bytes());
            k += 1;
            if k == 512 {
                self.put(&chunk)?;
                k = 0;
            }
        }
        self.put(&chunk[..8 * k])
    }
    fn f64s(&mut self, name: &str, v: &[f64]) -> std::io::Result<()> {
        self.f64_iter(name, v.len(), v.iter().copied())
    }
    fn u64s(&mut self, name: &str, v: &[u64]) -> std::io::Result<()> {
        self.section(name, 2, v.len())?;
        for x in v {
            self.put(&x.to_le_bytes())?;
        }
        Ok(())
    }
    fn bytes(&mut self, name: &str, v: &[u8]) -> std::io::Result<()> {
        self.section(name, 3, v.len())?;
        self.put(v)
    }
    fn text(&mut self, name: &str, v: &str) -> std::io::Result<()> {
        self.section(name, 4, v.len())?;
        self.put(v.as_bytes())
    }
}

/// Serializes a checkpoint and the VTU series written so far.
pub fn encode(model: &Model, ck: &Checkpoint, pvd: &[(f64, String)]) -> Vec<u8> {
    encode_with(fingerprint(model), ck, pvd)
}

/// [`encode`] with the model's fingerprint computed once by the caller.
pub(crate) fn encode_with(fingerprint: u64, ck: &Checkpoint, pvd: &[(f64, String)]) -> Vec<u8> {
    let mut out = Vec::new();
    write_to(&mut out, fingerprint, ck, pvd).expect("writing to memory cannot fail");
    out
}

/// Streams the restart file to `w`: the header (its section count found by a
/// first, counting pass that skips the payloads), the sections and the checksum, hashed on the way,
/// so no copy of the state is built in memory (at 1M dofs it is 130 MB).
pub(crate) fn write_to(
    w: &mut dyn Write,
    fingerprint: u64,
    ck: &Checkpoint,
    pvd: &[(f64, String)],
) -> std::io::Result<()> {
    let mut count = Encoder {
        out: None,
        sections: 0,
    };
    sections(&mut count, ck, pvd)?;
    let n = count.sections;
    let mut e = Encoder {
        out: Some((w, Fnv::default())),
        sections: 0,
    };
    e.put(MAGIC)?;
    e.put(&VERSION.to_le_bytes())?;
    e.put(&0u32.to_le_bytes())?;
    e.put(&fingerprint.to_le_bytes())?;
    e.put(&n.to_le_bytes())?;
    sections(&mut e, ck, pvd)?;
    match e.out {
        Some((w, f)) => w.write_all(&f.finish().to_le_bytes()),
        None => Ok(()),
    }
}

/// The sections of a restart file, in the order the decoder reads them:
/// the load stepping ([`decode`]'s stepper), the committed state, the
/// records every increment added, and the VTU series.
fn sections(e: &mut Encoder, ck: &Checkpoint, pvd: &[(f64, String)]) -> std::io::Result<()> {
    stepper_sections(e, ck)?;
    state_sections(e, ck)?;
    record_sections(e, ck)?;
    pvd_sections(e, pvd)
}

/// Where the load stepping stands: the increment, the load factor and the
/// last step, the pending schedule, the automatic control, the counters.
fn stepper_sections(e: &mut Encoder, ck: &Checkpoint) -> std::io::Result<()> {
    e.u64s("increment", &[ck.increments.len() as u64])?;
    e.f64s("load_factor", &[ck.lambda])?;
    e.f64s("last_step", &[ck.last_step])?;
    e.f64s("last_du", &ck.last_du)?;
    e.f64s(
        "pending_load_factor",
        &ck.stepper.pending.iter().map(|p| p.0).collect::<Vec<_>>(),
    )?;
    e.u64s(
        "pending_depth",
        &ck.stepper
            .pending
            .iter()
            .map(|p| p.1 as u64)
            .collect::<Vec<_>>(),
    )?;
    e.f64s("auto_waypoints", &ck.stepper.waypoints)?;
    e.f64s("auto_step", &[ck.stepper.step])?;
    e.u64s("auto_failures", &[ck.stepper.failures as u64])?;
    e.u64s(
        "cutbacks",
        &[ck.cutbacks_total as u64, ck.cutbacks_here as u64],
    )?;
    e.f64s("elastic_ratio_prev", &[ck.elastic_ratio_prev])?;
    e.u64s(
        "counters",
        &[ck.iterations as u64, ck.factorizations as u64],
    )?;
    e.u64s(
        "interface_counters",
        &[
            ck.interface.loops as u64,
            ck.interface.iterations as u64,
            ck.interface.fallbacks as u64,
        ],
    )?;
    e.u64s("event_counters", &[ck.event_iterations as u64])?;
    Ok(())
}

/// The committed state: displacements, Gauss points, the interface points'
/// statuses and tangential states, the prescribed reaction.
fn state_sections(e: &mut Encoder, ck: &Checkpoint) -> std::io::Result<()> {
    let s = &ck.committed;
    e.f64s("u", &s.u)?;
    // six stress components with twist and in 3D
    let w = PointState::packed_len(s.gauss.twist());
    e.f64_iter(
        "gauss",
        w * s.gauss.len(),
        s.gauss.iter().flat_map(|g| g.pack().into_iter().take(w)),
    )?;
    e.bytes(
        "status",
        &s.status.iter().map(|&st| st as u8).collect::<Vec<_>>(),
    )?;
    // with twist and in 3D the vector law's layout (ContactState::pack_twist)
    let wc = ContactState::packed_len(ck.vector_slip);
    e.f64_iter(
        "contact",
        wc * s.contact.len(),
        s.contact.iter().flat_map(|c| c.pack_as(ck.vector_slip)),
    )?;
    e.f64s("prescribed_reaction", &[s.prescribed_reaction])?;
    Ok(())
}

/// What every increment recorded: the curve, first yield, the joints'
/// totals and rows, the pretension rows, the designer's records, the
/// events and the tables' reach.
fn record_sections(e: &mut Encoder, ck: &Checkpoint) -> std::io::Result<()> {
    let mut rows = Vec::with_capacity(10 * ck.increments.len());
    for inc in &ck.increments {
        let m = &inc.measures;
        rows.extend_from_slice(&[
            inc.increment as f64,
            inc.load_factor,
            inc.iterations as f64,
            inc.cutbacks as f64,
            m.normal_force,
            m.mean_pressure,
            m.total_load_kn,
            m.center_displacement,
            m.max_peeq,
            m.prescribed_reaction,
        ]);
    }
    e.f64s("curve", &rows)?;
    // empty before the first yield
    let fy = ck.first_yield.as_ref();
    e.f64s(
        "first_yield",
        &fy.map_or(Vec::new(), |fy| {
            vec![
                fy.load_factor,
                fy.mean_pressure,
                fy.total_load_kn,
                fy.x,
                fy.depth,
                fy.element as f64,
                fy.z,
            ]
        }),
    )?;
    e.text("first_yield_body", fy.map_or("", |fy| &fy.body))?;
    e.f64s(
        "joint_totals",
        &ck.joint_totals
            .iter()
            .flat_map(|t| [t.dissipation, t.work])
            .collect::<Vec<_>>(),
    )?;
    // every increment's rows: one per interface (the decoder checks the
    // count against the model)
    let joints = || ck.increments.iter().flat_map(|i| &i.joints);
    let n = joints().count();
    e.f64_iter(
        "joints",
        JointMeasures::PACKED * n,
        joints().flat_map(JointMeasures::pack),
    )?;
    // twist: T, ū_θ, φ̄ per interface and increment; empty without twist
    let twist = if ck.twist { n } else { 0 };
    e.f64_iter(
        "joints_twist",
        JointMeasures::PACKED_TWIST * twist,
        joints().take(twist).flat_map(JointMeasures::pack_twist),
    )?;
    // 3D: F_T2, ū_T2, the force and moment on A; empty in 2D
    let space = if ck.vector_slip && !ck.twist { n } else { 0 };
    e.f64_iter(
        "joints_space",
        JointMeasures::PACKED_SPACE * space,
        joints().take(space).flat_map(JointMeasures::pack_space),
    )?;
    // every pretension section's force and shortening per increment (empty
    // in a model without sections)
    let rows = || ck.increments.iter().flat_map(|i| &i.sections);
    e.f64_iter("pretension", 2 * rows().count(), rows().flatten().copied())?;
    // the designer's outputs: each increment's record, in the layout of
    // the model's plan
    e.u64s("record_width", &[ck.record_width as u64])?;
    let records = || ck.increments.iter().flat_map(|i| &i.record);
    e.f64_iter("records", records().count(), records().copied())?;
    e.f64_iter(
        "events",
        ck.events.iter().map(|v| v.pack().len()).sum(),
        ck.events.iter().flat_map(|v| v.pack()),
    )?;
    e.f64_iter(
        "table_reach",
        Reach::PACKED * ck.table_reach.len(),
        ck.table_reach.iter().flat_map(Reach::pack),
    )?;
    Ok(())
}

/// The VTU series written so far (`result.pvd`'s entries).
fn pvd_sections(e: &mut Encoder, pvd: &[(f64, String)]) -> std::io::Result<()> {
    e.f64s(
        "pvd_load_factor",
        &pvd.iter().map(|p| p.0).collect::<Vec<_>>(),
    )?;
    e.text(
        "pvd_file",
        &pvd.iter()
            .map(|p| p.1.as_str())
            .collect::<Vec<_>>()
            .join("\n"),
    )
}

mod decode;
mod folder;
#[cfg(test)]
mod tests;

use decode::*;
use folder::*;
pub(crate) use folder::{
    copy_in, folder_files, interface_name, most_iterations, vtu_increment, vtu_name, Bounds,
    MAX_DISPLACEMENT, MAX_PEEQ, MAX_PLASTIC_STRAIN, MAX_PRESSURE, MAX_SECTIONS, MAX_STRESS,
};

/// Reads `restart.bin` in `dir` for `model`: the checkpoint and the VTU
/// series. Everything read from the folder is checked against the model
/// before it is used: the file's size (against `Bounds`, before it is
/// read), every section (`decode`), and every file a resumed run copies
/// (`folder_files`: regular files inside the folder, no links, bounded
/// sizes). Any mismatch is an input error naming the restart file.
pub fn read(dir: &Path, model: &Model) -> Result<(Checkpoint, Vec<(f64, String)>)> {
    let place = dir.join(FILE).display().to_string();
    let refuse = |m: String| Error::input(place.clone(), m);
    let b = Bounds::of(model);
    let (file, len) = open_in(dir, FILE, b.restart_bytes).map_err(refuse)?;
    let mut bytes = Vec::with_capacity(len as usize);
    std::io::Read::read_to_end(
        &mut std::io::Read::take(file, b.restart_bytes + 1),
        &mut bytes,
    )
    .map_err(|e| Error::io(dir.join(FILE), e))?;
    let (ck, pvd) = decode_with(&bytes, model, &b).map_err(refuse)?;
    for (rel, limit) in folder_files(&b, ck.increments.len(), &pvd) {
        open_in(dir, &rel, limit).map_err(refuse)?;
    }
    Ok((ck, pvd))
}
