//! `restart.bin`: the committed state of a run after a converged increment, so
//! that `asperity run CASE --restart DIR` continues exactly where it stopped.
//!
//! Layout (all integers and floats little-endian; floats as their exact IEEE-754
//! bits, so a resumed run is bit-for-bit the uninterrupted one):
//!
//! ```text
//! magic        8 bytes  "ASPRSTRT"
//! version      u32      1
//! reserved     u32      0
//! fingerprint  u64      FNV-1a of the effective case (after command-line
//!                       overrides) and the mesh; a restart with another case
//!                       or mesh is refused
//! sections     u32      count, then per section:
//!                name   u16 length + UTF-8
//!                kind   u8   1 = f64, 2 = u64, 3 = u8, 4 = UTF-8 text
//!                count  u64  number of elements (bytes for text)
//!                data
//! checksum     u64      FNV-1a (64-bit state, over 64-bit words, see
//!                       [`fnv1a`]) of every byte before it
//! ```
//!
//! Sections: `increment`, `load_factor`, `last_step`, `last_du` (the last
//! increment's displacement change, the predictor's direction; may be absent),
//! `pending_load_factor`,
//! `pending_depth` (fixed schedule), `auto_waypoints`, `auto_step`,
//! `auto_failures` (automatic step control), `cutbacks` (total, since the last increment),
//! `elastic_ratio_prev`, `counters` (Newton iterations, factorizations), `u`,
//! `gauss` (10 per Gauss point: σxx σyy σxy σzz, εᵖ ×4, ε̄ᵖ, yielding),
//! `status` (interface status codes), `contact` (5 per interface point, as
//! [`crate::interface::PointState::pack`] lays them out:
//! plastic slip, max shear memory κ, p_T, u_T, μ_F), `prescribed_reaction`,
//! `curve` (10 per increment: number, load factor, iterations, cutbacks, normal
//! force, mean pressure, load kN, centre displacement, max ε̄ᵖ, prescribed
//! reaction), `first_yield` (load factor, mean pressure, load kN, x, depth,
//! element) with `first_yield_body`, the VTU series `pvd_load_factor`,
//! `pvd_file` (names separated by newlines), `joint_totals` (2 per interface:
//! frictional dissipation and tangential work so far) and `joints` (11 per
//! interface and increment, as [`crate::interface::joint::JointMeasures::pack`]
//! lays them out), `table_reach` (2 per interface: the largest approach u_N
//! and pressure p_N over the converged states so far, see
//! [`crate::interface::extrapolation`]). Unknown sections are ignored;
//! `last_du`, `joint_totals`, `joints` and `table_reach` may be absent (files
//! of earlier builds: the joint energies then restart from zero and the
//! earlier increments have no joint rows, written as NaN rows of `joints`
//! from then on; the reach starts from the restored state's).
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
//! - sizes: the file's size from its metadata against [`Bounds`] (what the
//!   model's dofs, Gauss points, interface points and the case's most
//!   increments need) before it is read; at most [`MAX_SECTIONS`] sections
//!   of distinct names, each count within the bytes that remain before its
//!   data is copied; at most [`Bounds::increments`] increments;
//! - the load history: the `curve` rows are numbered 1, 2, … with finite
//!   values and whole counts, and are replayed from the case's own stepper
//!   ([`Stepper::replay`]: the fixed schedule with each row's cutbacks, bit
//!   for bit; automatic steps towards the case's waypoints, never past one,
//!   never longer than the largest step); `load_factor` and `last_step` are
//!   the last row's, `pending_*` (fixed) or `auto_waypoints` (automatic)
//!   exactly what that replay leaves, the other mode's part untouched, so
//!   the resumed run ends where the case's history ends; `auto_step` within
//!   the case's smallest and largest step; no failures or cutbacks pending
//!   and the cutback total the curve's;
//! - the counters: Newton iterations and factorizations at most what a run
//!   of the case can count after the curve's increments and cutbacks
//!   ([`most_iterations`]: per attempt a predicted and a plain solve, each
//!   with the stabilization's levels and releases, plus one first-yield
//!   search, at the case's iteration limit, × 2);
//! - the state: `u`, `last_du`, `gauss`, `contact`, `joint_totals`,
//!   `prescribed_reaction`, `table_reach` finite; `u` and `last_du` within
//!   ±[`MAX_DISPLACEMENT`] (the displacement range of a case, 10⁴ mm); every
//!   Gauss point a state its body's return mapping can leave
//!   (`check_gauss_point`): ε̄ᵖ ≥ 0, the yielding flag 0 or 1, |σ| ≤
//!   [`MAX_STRESS`], σzz = 0 in plane stress; in an elastic body (no
//!   `yield_stress`) εᵖ, ε̄ᵖ and the flag all 0; otherwise |εᵖ| ≤
//!   [`MAX_PLASTIC_STRAIN`], ε̄ᵖ ≤ [`MAX_PEEQ`], εᵖ deviatoric (trace 0),
//!   ε̄ᵖ ≥ √(2/3)|εᵖ| and σ_eq ≤ σ_Y + H ε̄ᵖ (round-off allowed); every
//!   status code a status ([`Status::checked`]); `joints` rows finite, or all
//!   NaN before the first finite one (the rows of earlier builds);
//!   `first_yield` finite, within the curve's load factors, at an element of
//!   the mesh whose body `first_yield_body` names; every interface's
//!   `table_reach` (u_N, p_N) within [0, [`MAX_DISPLACEMENT`]] ×
//!   [0, [`MAX_PRESSURE`]], p_N the normal law's pressure at u_N, and at
//!   least the restored state's own reach ([`Reach::of`]);
//! - names: every `pvd_file` name is `vtu/NNNN.vtu` exactly as the writer
//!   names an increment ([`vtu_name`]), for increasing converged increments,
//!   with that increment's load factor; every file a resumed run copies
//!   ([`folder_files`]: `restart.bin`, `interface/NNNN.csv`, the VTU series)
//!   is a regular file inside the folder, neither it nor its folder a
//!   symbolic link, within its size bound; the copy ([`copy_in`]) opens it
//!   again without following links and creates each file new in the
//!   temporary output folder.

use crate::case::ranges;
use crate::error::{Error, Result};
use crate::interface::extrapolation::Reach;
use crate::interface::joint::{JointMeasures, JointTotals};
use crate::interface::{PointState as ContactState, Status};
use crate::material::{PointState, VonMises};
use crate::model::Model;
use crate::solve::stepping::Stepper;
use crate::solve::{stabilize, yield_point};
use crate::solve::{Checkpoint, FirstYield, Increment, Measures};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

pub const MAGIC: &[u8; 8] = b"ASPRSTRT";
pub const VERSION: u32 = 1;
pub const FILE: &str = "restart.bin";

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
    let mut bytes = model.case_key.clone().into_bytes();
    for n in &model.mesh.nodes {
        for v in n.iter() {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
    }
    for el in &model.mesh.elements {
        bytes.extend_from_slice(&(el.body as u64).to_le_bytes());
        for &n in el.nodes.iter() {
            bytes.extend_from_slice(&(n as u64).to_le_bytes());
        }
    }
    bytes.extend_from_slice(&(model.mesh.num_dofs() as u64).to_le_bytes());
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
pub fn encode_with(fingerprint: u64, ck: &Checkpoint, pvd: &[(f64, String)]) -> Vec<u8> {
    let mut out = Vec::new();
    write_to(&mut out, fingerprint, ck, pvd).expect("writing to memory cannot fail");
    out
}

/// Streams the restart file to `w`: the header (its section count found by a
/// first, counting pass that skips the payloads), the sections and the checksum, hashed on the way,
/// so no copy of the state is built in memory (at 1M dofs it is 130 MB).
pub fn write_to(
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

fn sections(e: &mut Encoder, ck: &Checkpoint, pvd: &[(f64, String)]) -> std::io::Result<()> {
    let s = &ck.committed;
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
    e.f64s("u", &s.u)?;
    e.f64_iter(
        "gauss",
        PointState::PACKED * s.gauss.len(),
        s.gauss.iter().flat_map(PointState::pack),
    )?;
    e.bytes(
        "status",
        &s.status.iter().map(|&st| st as u8).collect::<Vec<_>>(),
    )?;
    e.f64_iter(
        "contact",
        ContactState::PACKED * s.contact.len(),
        s.contact.iter().flat_map(ContactState::pack),
    )?;
    e.f64s("prescribed_reaction", &[s.prescribed_reaction])?;
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
    if let Some(fy) = &ck.first_yield {
        e.f64s(
            "first_yield",
            &[
                fy.load_factor,
                fy.mean_pressure,
                fy.total_load_kn,
                fy.x,
                fy.depth,
                fy.element as f64,
            ],
        )?;
        e.text("first_yield_body", &fy.body)?;
    }
    e.f64s(
        "joint_totals",
        &ck.joint_totals
            .iter()
            .flat_map(|t| [t.dissipation, t.work])
            .collect::<Vec<_>>(),
    )?;
    // an increment without joint measures (restored from a file of an
    // earlier build) is a row of NaN
    let n = ck.joint_totals.len();
    let none = vec![JointMeasures::unpack(&[f64::NAN; JointMeasures::PACKED]); n];
    e.f64_iter(
        "joints",
        JointMeasures::PACKED * n * ck.increments.len(),
        ck.increments
            .iter()
            .map(|i| {
                if i.joints.len() == n {
                    &i.joints
                } else {
                    &none
                }
            })
            .flat_map(|j| j.iter().flat_map(JointMeasures::pack)),
    )?;
    e.f64_iter(
        "table_reach",
        Reach::PACKED * ck.table_reach.len(),
        ck.table_reach.iter().flat_map(Reach::pack),
    )?;
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

/// Most sections a restart file may list (this build writes 26).
pub const MAX_SECTIONS: u32 = 64;
/// Longest section name (this build's longest has 19 bytes).
const MAX_SECTION_NAME: usize = 64;
/// Most converged increments behind a resumed run, whatever the case allows
/// (a run of this many increments writes as many interface CSV files).
pub const MAX_RESUMED_INCREMENTS: usize = 1 << 24;
/// Longest VTU name in the `pvd_file` section: `vtu/` + 20 digits + `.vtu`.
const MAX_VTU_NAME: usize = 28;
/// Largest |u| and |Δu| (`u`, `last_du`) and interface approach u_N
/// (`table_reach`) of a restored state, mm: the displacement range of a
/// case ([`ranges::DISPLACEMENT`], 10 m).
pub const MAX_DISPLACEMENT: f64 = ranges::DISPLACEMENT.hi;
/// Largest interface pressure p_N of `table_reach`, MPa: the pressure range
/// of a case ([`ranges::PRESSURE`]).
pub const MAX_PRESSURE: f64 = ranges::PRESSURE.hi;
/// Largest |σ| component of a Gauss point, MPa: 10⁴ × the largest Young's
/// modulus a case may give ([`ranges::MODULUS`]), 10⁶ × the largest yield
/// stress or pressure.
pub const MAX_STRESS: f64 = 1e4 * ranges::MODULUS.hi;
/// Largest plastic strain |εᵖ| (the tensor norm, √(εᵖ:εᵖ)) of a Gauss
/// point: 1000 %, far beyond what a small-strain model means.
pub const MAX_PLASTIC_STRAIN: f64 = 10.0;
/// Largest accumulated plastic strain ε̄ᵖ of a Gauss point (it grows under
/// cyclic loading where εᵖ does not).
pub const MAX_PEEQ: f64 = 1e4;
/// Round-off allowed in the relations between the stored plastic strains
/// (trace, ε̄ᵖ ≥ √(2/3)|εᵖ|): relative, and absolute (a strain).
const STRAIN_REL: f64 = 1e-9;
const STRAIN_ABS: f64 = 1e-15;
/// Round-off allowed above the yield surface: σ_eq ≤ σ_y(ε̄ᵖ) (1 + this).
const YIELD_REL: f64 = 1e-6;
/// Round-off allowed between `table_reach` and what the restored state
/// and the normal law give: relative, and absolute (mm or MPa).
const REACH_REL: f64 = 1e-9;
const REACH_ABS: f64 = 1e-12;
/// Margin on the most Newton iterations and factorizations a run can have
/// counted ([`most_iterations`]).
const COUNTER_MARGIN: u128 = 2;

/// A float quoted in a refusal: the shortest form that reads back as it,
/// plain or scientific (at most 24 characters: a forged 1e300 is `1e300`,
/// not 301 digits).
fn num(x: f64) -> String {
    crate::calibrate::limits::exact(x)
}

/// The most Newton iterations (and as many factorizations: one per
/// iteration) a run can have counted after `increments` converged
/// increments and `cutbacks` cutbacks: every attempt at a step (each
/// increment or cutback, and one more) is at most a solve from the
/// predictor and one from the committed state ([`crate::solve`]'s predictor
/// restart), each the plain solve and, under the contact stabilization, up
/// to [`stabilize::LEVELS`] stabilized solves each with its release; the
/// first-yield search adds at most 1 + [`yield_point::SEARCH_STEPS`] such
/// steps once. Every solve takes at most the case's iteration limit (PETSc
/// SNES: its cap, 10 more); all of it times [`COUNTER_MARGIN`].
pub fn most_iterations(model: &Model, increments: u64, cutbacks: u64) -> u128 {
    let per_step = 1 + 2 * stabilize::LEVELS as u128;
    let attempts = u128::from(increments) + u128::from(cutbacks) + 1;
    let solves = (2 * attempts + 1 + yield_point::SEARCH_STEPS as u128) * per_step;
    solves * (model.solver.iteration_limit() as u128 + 10) * COUNTER_MARGIN
}

/// What a restart folder can hold for a model, from the model alone: the
/// bounds every size read from the folder is checked against before
/// anything of that size is allocated or copied.
#[derive(Clone, Copy, Debug)]
pub struct Bounds {
    /// Converged increments: what the case's schedule (fixed) or step
    /// control (automatic) can produce ([`Stepper::most_increments`]), at
    /// most [`MAX_RESUMED_INCREMENTS`].
    pub increments: usize,
    /// Bytes of `restart.bin`: the state (dofs, Gauss points, interface
    /// points), the stepping state, and per increment its curve row, joint
    /// rows and VTU entry, with room for the section table.
    pub restart_bytes: u64,
    /// Bytes of one `interface/NNNN.csv` (512 per interface pair and its name).
    pub csv_bytes: u64,
    /// Bytes of one `vtu/NNNN.vtu` (512 per node, 256 per element: at most
    /// 16 numbers of 25 characters per node).
    pub vtu_bytes: u64,
}

impl Bounds {
    pub fn of(model: &Model) -> Bounds {
        let st = Stepper::for_model(model);
        let increments = st.most_increments().min(MAX_RESUMED_INCREMENTS) as u64;
        let nu = model.mesh.num_dofs() as u64;
        let ng = (model.mesh.elements.len() * model.n_gauss()) as u64;
        let np: u64 = model.interfaces.iter().map(|i| i.points.len() as u64).sum();
        let ni = model.interfaces.len() as u64;
        let body = model.mesh.bodies.iter().map(|b| b.len()).max().unwrap_or(0) as u64;
        // 8-byte values besides the per-increment rows: u and last_du, the
        // Gauss and contact states, joint totals and table reach, the
        // pending schedule (its rest and at most one halved target per
        // cutback), the waypoints, and the scalars
        let words = 2 * nu
            + PointState::PACKED as u64 * ng
            + ContactState::PACKED as u64 * np
            + (2 + Reach::PACKED as u64) * ni
            + 2 * (st.pending.len() as u64 + st.max_cutbacks() as u64 + 1)
            + st.waypoints.len() as u64
            + 32;
        let per_increment =
            8 * (10 + JointMeasures::PACKED as u64 * ni + 1) + MAX_VTU_NAME as u64 + 1;
        let table = 36 + u64::from(MAX_SECTIONS) * (11 + MAX_SECTION_NAME as u64);
        let restart_bytes = table
            .saturating_add(8 * words + np + body)
            .saturating_add(per_increment.saturating_mul(increments))
            // unknown sections of a later build
            .saturating_add(64 << 10);
        let pairs: u64 = model.interfaces.iter().map(|i| i.pairs.len() as u64).sum();
        let name = model
            .interfaces
            .iter()
            .map(|i| i.name.len())
            .max()
            .unwrap_or(0) as u64;
        Bounds {
            increments: increments as usize,
            restart_bytes,
            csv_bytes: 1024 + pairs * (512 + 2 * name),
            vtu_bytes: (64 << 10)
                + 512 * model.mesh.nodes.len() as u64
                + 256 * model.mesh.elements.len() as u64,
        }
    }
}

/// The file the writer gives increment `k`'s interface state.
pub fn interface_name(k: usize) -> String {
    format!("interface/{k:04}.csv")
}

/// The file the writer gives increment `k`'s VTU output.
pub fn vtu_name(k: usize) -> String {
    format!("vtu/{k:04}.vtu")
}

/// The increment of a VTU name of exactly the writer's form
/// ([`vtu_name`]); `None` for any other name (`..`, absolute, another
/// folder, leading zeros beyond four digits, …).
fn vtu_increment(name: &str) -> Option<usize> {
    let digits = name.strip_prefix("vtu/")?.strip_suffix(".vtu")?;
    if digits.is_empty() || digits.len() > 20 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let k: usize = digits.parse().ok()?;
    (vtu_name(k) == name).then_some(k)
}

/// The files a resumed run copies from the restart folder, with the size
/// bound of each: the interface CSV of every converged increment, the VTU
/// series, and `restart.bin` itself (kept if no further increment converges).
pub fn folder_files(b: &Bounds, increments: usize, pvd: &[(f64, String)]) -> Vec<(String, u64)> {
    let mut files: Vec<(String, u64)> = (1..=increments)
        .map(|k| (interface_name(k), b.csv_bytes))
        .collect();
    files.extend(pvd.iter().map(|p| (p.1.clone(), b.vtu_bytes)));
    files.push((FILE.to_string(), b.restart_bytes));
    files
}

/// Opens the file `rel` of the restart folder `dir` for reading. `rel` must
/// be a plain relative name (no `..`, not absolute); neither the file nor a
/// folder on the way may be a symbolic link (checked on each component, and
/// the file opened with `O_NOFOLLOW`); the file must be a regular file (not a
/// FIFO or a device: opened non-blocking, checked again on the open file) of
/// at most `limit` bytes. Returns the file and its size; the error is a
/// message for the restart file's line.
fn open_in(dir: &Path, rel: &str, limit: u64) -> Decoded<(std::fs::File, u64)> {
    let what = if rel == FILE {
        "the restart file".to_string()
    } else {
        rel.to_string()
    };
    let parts: Vec<&str> = rel.split('/').collect();
    let plain = |c: &str| !c.is_empty() && c != "." && c != ".." && !c.contains(['\\', '\0']);
    if !parts.iter().all(|c| plain(c)) {
        return Err(format!(
            "{what}: not a plain name inside the restart folder"
        ));
    }
    let mut p = dir.to_path_buf();
    for (i, c) in parts.iter().enumerate() {
        p.push(c);
        let m = std::fs::symlink_metadata(&p).map_err(|e| format!("{what}: {e}"))?;
        let t = m.file_type();
        if t.is_symlink() {
            let link = if i + 1 < parts.len() {
                format!("{what}: its folder {} is", parts[..=i].join("/"))
            } else {
                format!("{what} is")
            };
            return Err(format!(
                "{link} a symbolic link: every file of a restart folder must be a regular file inside it"
            ));
        }
        if i + 1 < parts.len() && !t.is_dir() {
            return Err(format!("{what}: {c} is not a folder"));
        }
    }
    let kind = |m: &std::fs::Metadata| {
        if m.is_dir() {
            "a folder"
        } else {
            "a device, FIFO or socket"
        }
    };
    let check = |m: &std::fs::Metadata| -> Decoded<u64> {
        if !m.is_file() {
            return Err(format!("{what} is {}, not a regular file", kind(m)));
        }
        if m.len() > limit {
            return Err(format!(
                "{what} has {} bytes, more than the {limit} bytes this case can need",
                m.len()
            ));
        }
        Ok(m.len())
    };
    check(&std::fs::symlink_metadata(&p).map_err(|e| format!("{what}: {e}"))?)?;
    let mut opts = std::fs::OpenOptions::new();
    opts.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        opts.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK);
    }
    let f = opts.open(&p).map_err(|e| format!("{what}: {e}"))?;
    // the file opened is the one checked (not one swapped in since)
    let len = check(&f.metadata().map_err(|e| format!("{what}: {e}"))?)?;
    Ok((f, len))
}

/// Copies the restart folder's file `rel` (a name from [`folder_files`],
/// at most `limit` bytes) into the same place under `to` (the fresh
/// temporary output folder): the source is opened as [`open_in`] opens it,
/// the destination created new (an existing file or link there is an error,
/// never followed or truncated).
pub fn copy_in(dir: &Path, rel: &str, limit: u64, to: &Path) -> Result<()> {
    let place = || dir.join(FILE).display().to_string();
    let (from, _) = open_in(dir, rel, limit).map_err(|m| Error::input(place(), m))?;
    let dest = to.join(rel);
    debug_assert!(Path::new(rel)
        .components()
        .all(|c| matches!(c, std::path::Component::Normal(_))));
    let out = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&dest)
        .map_err(|e| Error::io(&dest, e))?;
    let mut w = std::io::BufWriter::new(out);
    let n = std::io::copy(&mut std::io::Read::take(from, limit + 1), &mut w)
        .map_err(|e| Error::io(&dest, e))?;
    if n > limit {
        return Err(Error::input(
            place(),
            format!("{rel} grew beyond {limit} bytes while it was copied"),
        ));
    }
    w.flush().map_err(|e| Error::io(&dest, e))
}

/// Reads `restart.bin` in `dir` for `model`: the checkpoint and the VTU
/// series. Everything read from the folder is checked against the model
/// before it is used: the file's size (against [`Bounds`], before it is
/// read), every section ([`decode`]), and every file a resumed run copies
/// ([`folder_files`]: regular files inside the folder, no links, bounded
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

struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> std::result::Result<&'a [u8], String> {
        if n > self.b.len() - self.at {
            return Err("truncated restart file".into());
        }
        let s = &self.b[self.at..self.at + n];
        self.at += n;
        Ok(s)
    }
    fn u16(&mut self) -> std::result::Result<u16, String> {
        Ok(u16::from_le_bytes(self.take(2)?.try_into().unwrap()))
    }
    fn u32(&mut self) -> std::result::Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().unwrap()))
    }
    fn u64(&mut self) -> std::result::Result<u64, String> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().unwrap()))
    }
}

/// A decoding step's outcome: the error is the message shown to the user.
type Decoded<T> = std::result::Result<T, String>;

/// Decodes and checks a restart file against the model it is meant for.
/// The checksum and the fingerprint only catch accidents (anyone can compute
/// them): every value is also checked against what the case allows.
pub fn decode(
    bytes: &[u8],
    model: &Model,
) -> std::result::Result<(Checkpoint, Vec<(f64, String)>), String> {
    decode_with(bytes, model, &Bounds::of(model))
}

fn decode_with(
    bytes: &[u8],
    model: &Model,
    b: &Bounds,
) -> std::result::Result<(Checkpoint, Vec<(f64, String)>), String> {
    if bytes.len() as u64 > b.restart_bytes {
        return Err(format!(
            "{} bytes, more than the {} bytes a restart file of this case can have",
            bytes.len(),
            b.restart_bytes
        ));
    }
    let mut r = check_header(bytes, model)?;
    let s = Sections(read_sections(&mut r)?);
    let mut ck = Checkpoint::initial(model);
    let increments = s.u("increment", Some(1))?[0];
    if increments > b.increments as u64 {
        return Err(format!(
            "section increment: {increments} increments, more than this case can take ({})",
            b.increments
        ));
    }
    ck.increments = restore_curve(&s, increments as usize)?;
    restore_stepper(&mut ck, &s, model)?;
    restore_state(&mut ck, &s, model)?;
    ck.committed.time = ck.lambda;
    restore_joints(&mut ck, &s, model.interfaces.len())?;
    restore_table_reach(&mut ck, &s, model)?;
    ck.first_yield = restore_first_yield(&s, model, &ck.increments)?;
    let pvd = restore_vtu_series(&s, model, &ck.increments)?;
    Ok((ck, pvd))
}

/// Checks the magic, the version, the checksum and the fingerprint; the
/// reader is left at the section count, over the bytes before the checksum.
fn check_header<'a>(bytes: &'a [u8], model: &Model) -> Decoded<Reader<'a>> {
    if bytes.len() < 8 || &bytes[..8] != MAGIC {
        return Err("not an asperity restart file (bad magic)".into());
    }
    if bytes.len() < 36 {
        return Err("truncated restart file".into());
    }
    let (body, tail) = bytes.split_at(bytes.len() - 8);
    let stored = u64::from_le_bytes(tail.try_into().unwrap());
    let mut r = Reader { b: body, at: 8 };
    let version = r.u32()?;
    if version != VERSION {
        return Err(format!(
            "restart file version {version}, this build reads version {VERSION}"
        ));
    }
    if stored != fnv1a(body) {
        return Err("checksum mismatch: the restart file is corrupted or truncated".into());
    }
    let _reserved = r.u32()?;
    let fp = r.u64()?;
    if fp != fingerprint(model) {
        return Err(
            "written for a different case or mesh (fingerprint mismatch): restart with the same case file and the same command-line overrides".into(),
        );
    }
    Ok(r)
}

/// Reads the section table by name: at most [`MAX_SECTIONS`] sections of
/// distinct UTF-8 names, each within the bytes that remain (checked before
/// its data is copied); the sections must end where the checksum begins.
fn read_sections(r: &mut Reader) -> Decoded<BTreeMap<String, Data>> {
    let n = r.u32()?;
    if n > MAX_SECTIONS {
        return Err(format!(
            "{n} sections, more than the {MAX_SECTIONS} a restart file may have"
        ));
    }
    let mut map: BTreeMap<String, Data> = BTreeMap::new();
    for i in 0..n {
        let len = r.u16()? as usize;
        if len > MAX_SECTION_NAME {
            return Err(format!(
                "section {}: a name of {len} bytes, more than {MAX_SECTION_NAME}",
                i + 1
            ));
        }
        let name = std::str::from_utf8(r.take(len)?)
            .map_err(|_| format!("section {}: the name is not UTF-8", i + 1))?
            .to_string();
        let kind = r.take(1)?[0];
        let count = r.u64()?;
        let width = match kind {
            1 | 2 => 8,
            3 | 4 => 1,
            k => return Err(format!("section {name}: unknown kind {k}")),
        };
        let size = count
            .checked_mul(width)
            .filter(|&s| s <= (r.b.len() - r.at) as u64)
            .ok_or_else(|| {
                format!("section {name}: {count} values, more than the file holds (truncated?)")
            })?;
        let raw = r.take(size as usize)?;
        let data = match kind {
            1 => Data::F64(
                raw.chunks_exact(8)
                    .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                    .collect(),
            ),
            2 => Data::U64(
                raw.chunks_exact(8)
                    .map(|c| u64::from_le_bytes(c.try_into().unwrap()))
                    .collect(),
            ),
            3 => Data::U8(raw.to_vec()),
            _ => Data::Text(
                String::from_utf8(raw.to_vec()).map_err(|_| format!("section {name}: bad text"))?,
            ),
        };
        if map.insert(name.clone(), data).is_some() {
            return Err(format!("section {name} appears twice"));
        }
    }
    if r.at != r.b.len() {
        return Err("trailing bytes after the last section".into());
    }
    Ok(map)
}

/// The decoded sections, looked up by name and kind.
struct Sections(BTreeMap<String, Data>);

impl Sections {
    /// The f64 section `name`, of exactly `len` values when given.
    fn f(&self, name: &str, len: Option<usize>) -> Decoded<&Vec<f64>> {
        match self.0.get(name) {
            Some(Data::F64(v)) if len.is_none_or(|l| l == v.len()) => Ok(v),
            Some(Data::F64(v)) => Err(format!(
                "section {name} has {} values, the model needs {}",
                v.len(),
                len.unwrap_or(0)
            )),
            _ => Err(format!("section {name} (f64) missing")),
        }
    }
    /// [`Sections::f`] with every value finite.
    fn finite(&self, name: &str, len: Option<usize>) -> Decoded<&Vec<f64>> {
        let v = self.f(name, len)?;
        all_finite(name, v)?;
        Ok(v)
    }
    /// The u64 section `name`, of exactly `len` values when given.
    fn u(&self, name: &str, len: Option<usize>) -> Decoded<&Vec<u64>> {
        match self.0.get(name) {
            Some(Data::U64(v)) if len.is_none_or(|l| l == v.len()) => Ok(v),
            Some(Data::U64(v)) => Err(format!(
                "section {name} has {} values, expected {}",
                v.len(),
                len.unwrap_or(0)
            )),
            _ => Err(format!("section {name} (u64) missing")),
        }
    }
    /// The text section `name`.
    fn text(&self, name: &str) -> Decoded<&str> {
        match self.0.get(name) {
            Some(Data::Text(v)) => Ok(v),
            _ => Err(format!("section {name} (text) missing")),
        }
    }
}

/// Every value of section `name` finite, else the first one that is not.
fn all_finite(name: &str, v: &[f64]) -> Decoded<()> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(format!(
            "section {name}: value {} is not finite ({})",
            i + 1,
            num(v[i])
        )),
        None => Ok(()),
    }
}

/// A count stored as a float in the curve: a whole number ≥ 0 (below 2^53,
/// where floats hold every integer).
fn whole(v: f64) -> Option<usize> {
    ((0.0..9.007_199_254_740_992e15).contains(&v) && v.fract() == 0.0).then_some(v as usize)
}

/// The load curve: one row of 10 values per converged increment, numbered
/// 1, 2, … in order, with whole iteration and cutback counts and finite
/// load factors and measures.
fn restore_curve(s: &Sections, increments: usize) -> Decoded<Vec<Increment>> {
    let rows = s.finite("curve", Some(10 * increments))?;
    rows.chunks_exact(10)
        .enumerate()
        .map(|(i, v)| {
            let k = i + 1;
            if whole(v[0]) != Some(k) {
                return Err(format!("section curve: row {k} is numbered {}", num(v[0])));
            }
            let (Some(iterations), Some(cutbacks)) = (whole(v[2]), whole(v[3])) else {
                return Err(format!(
                    "section curve: row {k}: {} iterations, {} cutbacks (not whole numbers)",
                    num(v[2]),
                    num(v[3])
                ));
            };
            Ok(Increment {
                increment: k,
                load_factor: v[1],
                iterations,
                cutbacks,
                measures: Measures {
                    normal_force: v[4],
                    mean_pressure: v[5],
                    total_load_kn: v[6],
                    center_displacement: v[7],
                    max_peeq: v[8],
                    prescribed_reaction: v[9],
                },
                joints: Vec::new(),
            })
        })
        .collect()
}

/// The load stepping, checked against the case: the curve's increments are
/// replayed from the case's own stepper ([`Stepper::replay`]), and the
/// stored load factor, last step, pending schedule (fixed) or waypoints
/// (automatic) must be what that leaves, so a resumed run always continues
/// to the end of the case's load history. The automatic step size must lie
/// between the case's smallest and largest step; there are no failures or
/// cutbacks pending after a converged increment, and the total of cutbacks
/// is the curve's.
fn restore_stepper(ck: &mut Checkpoint, s: &Sections, model: &Model) -> Decoded<()> {
    let nu = ck.committed.u.len();
    let incs = &ck.increments;
    let path: Vec<(f64, usize)> = incs.iter().map(|i| (i.load_factor, i.cutbacks)).collect();
    let mut expect = Stepper::for_model(model);
    let initial = expect.clone();
    expect
        .replay(&path)
        .map_err(|m| format!("section curve: {m}"))?;
    let n = incs.len();
    let at = |k: usize| if k == 0 { 0.0 } else { incs[k - 1].load_factor };
    ck.lambda = s.finite("load_factor", Some(1))?[0];
    if ck.lambda.to_bits() != at(n).to_bits() {
        return Err(format!(
            "section load_factor: load factor {}, but increment {n} ended at {}",
            num(ck.lambda),
            num(at(n))
        ));
    }
    ck.last_step = s.finite("last_step", Some(1))?[0];
    let step = if n == 0 { 0.0 } else { at(n) - at(n - 1) };
    if ck.last_step.to_bits() != step.to_bits() {
        return Err(format!(
            "section last_step: {}, but the curve's last step is {}",
            num(ck.last_step),
            num(step)
        ));
    }
    // the predictor's direction; absent from files of earlier builds (the
    // next increment then starts from the committed state)
    if let Some(Data::F64(v)) = s.0.get("last_du") {
        if !v.is_empty() && v.len() != nu {
            return Err(format!(
                "section last_du has {} values, the model needs {nu}",
                v.len()
            ));
        }
        all_finite("last_du", v)?;
        all_within(
            "last_du",
            v,
            MAX_DISPLACEMENT,
            "mm",
            "the displacement range of a case",
        )?;
        ck.last_du = v.clone();
    }
    let pl = s.f("pending_load_factor", None)?;
    let pd = s.u("pending_depth", None)?;
    if pl.len() != pd.len() {
        return Err("pending schedule: lengths differ".into());
    }
    let pending: Vec<(f64, usize)> = pl.iter().zip(pd).map(|(&l, &d)| (l, d as usize)).collect();
    let waypoints = s.f("auto_waypoints", None)?;
    let auto = expect.mode() == crate::case::StepControl::Auto;
    // the mode not in force never changes its part of the stepper
    let (want_pending, want_waypoints) = if auto {
        (&initial.pending, &expect.waypoints)
    } else {
        (&expect.pending, &initial.waypoints)
    };
    if !same_schedule(&pending, want_pending) {
        return Err(format!(
            "the pending schedule (section pending_load_factor) is not what the case's schedule leaves after increment {n}: {} found, {} expected",
            describe(pending.iter().map(|p| p.0)),
            describe(want_pending.iter().map(|p| p.0))
        ));
    }
    if !same_values(waypoints, want_waypoints) {
        return Err(format!(
            "the waypoints (section auto_waypoints) are not the case's load history after increment {n}: {} found, {} expected",
            describe(waypoints.iter().copied()),
            describe(want_waypoints.iter().copied())
        ));
    }
    ck.stepper = expect;
    let step = s.f("auto_step", Some(1))?[0];
    let (lo, hi) = ck.stepper.step_bounds();
    let fits = if auto {
        step.is_finite() && step >= lo * 0.999_999 && step <= hi
    } else {
        step.to_bits() == initial.step.to_bits()
    };
    if !fits {
        return Err(if auto {
            format!(
                "section auto_step: step {}, outside the case's steps [{}, {}]",
                num(step),
                num(lo),
                num(hi)
            )
        } else {
            format!(
                "section auto_step: {}, but fixed steps leave it at {}",
                num(step),
                num(initial.step)
            )
        });
    }
    ck.stepper.step = step;
    let failures = s.u("auto_failures", Some(1))?[0];
    let cb = s.u("cutbacks", Some(2))?;
    let total: u64 = incs.iter().map(|i| i.cutbacks as u64).sum();
    if failures != 0 || cb[1] != 0 || cb[0] != total {
        return Err(format!(
            "sections auto_failures/cutbacks: {failures} failures and {} cutbacks pending, {} cutbacks in all, where a converged increment leaves none pending and the curve counts {total}",
            cb[1], cb[0]
        ));
    }
    ck.stepper.failures = 0;
    (ck.cutbacks_total, ck.cutbacks_here) = (total as usize, 0);
    let ct = s.u("counters", Some(2))?;
    let most = most_iterations(model, n as u64, total);
    for (v, what) in [(ct[0], "Newton iterations"), (ct[1], "factorizations")] {
        if u128::from(v) > most {
            return Err(format!(
                "section counters: {v} {what}, more than a run of this case can count after {n} increments and {total} cutbacks ({most}: per step attempt a predicted and a plain solve, each with {} stabilization levels, and a first-yield search, at the iteration limit {}, × {COUNTER_MARGIN})",
                stabilize::LEVELS,
                model.solver.iteration_limit()
            ));
        }
    }
    (ck.iterations, ck.factorizations) = (ct[0] as usize, ct[1] as usize);
    ck.elastic_ratio_prev = s.finite("elastic_ratio_prev", Some(1))?[0];
    if ck.elastic_ratio_prev < 0.0 {
        return Err(format!(
            "section elastic_ratio_prev: {} is negative",
            num(ck.elastic_ratio_prev)
        ));
    }
    Ok(())
}

fn same_values(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

fn same_schedule(a: &[(f64, usize)], b: &[(f64, usize)]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| x.0.to_bits() == y.0.to_bits() && x.1 == y.1)
}

/// "N targets, last L" of a list stored last first.
fn describe(v: impl Iterator<Item = f64>) -> String {
    let v: Vec<f64> = v.collect();
    match v.first() {
        Some(&l) => format!("{} targets to λ = {}", v.len(), num(l)),
        None => "none".into(),
    }
}

/// The committed state: displacements, Gauss points, interface status and
/// contact state, and the prescribed reaction, each sized for the model,
/// every value finite, the displacements within [`MAX_DISPLACEMENT`],
/// status codes valid, every Gauss point a state the case's return mapping
/// can leave ([`check_gauss_point`]).
fn restore_state(ck: &mut Checkpoint, s: &Sections, model: &Model) -> Decoded<()> {
    let c = &mut ck.committed;
    let (ng, np, nu) = (c.gauss.len(), c.status.len(), c.u.len());
    let u = s.finite("u", Some(nu))?;
    all_within(
        "u",
        u,
        MAX_DISPLACEMENT,
        "mm",
        "the displacement range of a case",
    )?;
    c.u.copy_from_slice(u);
    let gauss = s.finite("gauss", Some(PointState::PACKED * ng))?;
    for (i, (p, v)) in c
        .gauss
        .iter_mut()
        .zip(gauss.chunks_exact(PointState::PACKED))
        .enumerate()
    {
        check_gauss_point(model, i, v)?;
        *p = PointState::unpack(v);
    }
    match s.0.get("status") {
        Some(Data::U8(v)) if v.len() == np => {
            for (i, (st, &code)) in c.status.iter_mut().zip(v).enumerate() {
                *st = Status::checked(code).ok_or_else(|| {
                    format!(
                        "section status: interface point {}: code {code} is no status",
                        i + 1
                    )
                })?;
            }
        }
        _ => return Err(format!("section status: expected {np} codes")),
    }
    for (p, v) in c.contact.iter_mut().zip(
        s.finite("contact", Some(ContactState::PACKED * np))?
            .chunks_exact(ContactState::PACKED),
    ) {
        *p = ContactState::unpack(v);
    }
    c.prescribed_reaction = s.finite("prescribed_reaction", Some(1))?[0];
    Ok(())
}

/// Every value of section `name` (finite: checked before) within ±`bound`
/// (`unit`, `what` says whose bound), else the first beyond it.
fn all_within(name: &str, v: &[f64], bound: f64, unit: &str, what: &str) -> Decoded<()> {
    match v.iter().position(|x| x.abs() > bound) {
        Some(i) => Err(format!(
            "section {name}: value {} is {} {unit}, beyond the ±{} {unit} of {what}",
            i + 1,
            num(v[i]),
            num(bound)
        )),
        None => Ok(()),
    }
}

/// A Gauss point's state `v` (`i`-th of the model, laid out as
/// [`PointState::pack`]: σxx σyy σxy σzz, εᵖxx εᵖyy εᵖxy εᵖzz (tensor
/// shear), ε̄ᵖ, yielding) against what the return mapping of its body's
/// material can leave ([`crate::material`]):
///
/// - ε̄ᵖ ≥ 0 and the yielding flag 0 or 1;
/// - every stress component within ±[`MAX_STRESS`]; σzz = 0 in plane stress;
/// - in an elastic body (no `yield_stress`) no plastic strain, ε̄ᵖ and
///   yielding flag at all (exactly 0: the return mapping never leaves the
///   elastic branch);
/// - otherwise |εᵖ| = √(εᵖ:εᵖ) ≤ [`MAX_PLASTIC_STRAIN`], ε̄ᵖ ≤ [`MAX_PEEQ`];
///   εᵖ deviatoric (trace εᵖxx + εᵖyy + εᵖzz = 0: plane stress sets εᵖzz =
///   −(εᵖxx + εᵖyy), plane strain and axisymmetry flow along the deviatoric
///   trial stress); ε̄ᵖ ≥ √(2/3)|εᵖ| (every increment adds √(2/3)|Δεᵖ| to
///   ε̄ᵖ, and |Σ Δεᵖ| ≤ Σ |Δεᵖ|); the equivalent stress on or inside the
///   yield surface, σ_eq ≤ σ_Y + H ε̄ᵖ. Round-off is allowed for
///   ([`STRAIN_REL`], [`STRAIN_ABS`], [`YIELD_REL`]).
fn check_gauss_point(model: &Model, i: usize, v: &[f64]) -> Decoded<()> {
    if v[8] < 0.0 || (v[9] != 0.0 && v[9] != 1.0) {
        return Err(format!(
            "section gauss: Gauss point {}: equivalent plastic strain {} and yielding flag {} (≥ 0, and 0 or 1 expected)",
            i + 1,
            num(v[8]),
            num(v[9])
        ));
    }
    let body = model.mesh.elements[i / model.n_gauss()].body;
    let mat = &model.materials[body];
    let at = || {
        format!(
            "section gauss: Gauss point {} (body {:?})",
            i + 1,
            model.mesh.bodies[body]
        )
    };
    let (sig, ep, peeq) = (&v[0..4], &v[4..8], v[8]);
    const STRESS: [&str; 4] = ["σxx", "σyy", "σxy", "σzz"];
    if let Some(k) = sig.iter().position(|x| x.abs() > MAX_STRESS) {
        return Err(format!(
            "{}: stress {} = {} MPa, beyond ±{} MPa (10⁴ × the largest Young's modulus of a case)",
            at(),
            STRESS[k],
            num(sig[k]),
            num(MAX_STRESS)
        ));
    }
    if model.plane == crate::material::Plane::Stress && sig[3] != 0.0 {
        return Err(format!(
            "{}: σzz = {} MPa in plane stress (0 exactly)",
            at(),
            num(sig[3])
        ));
    }
    let strain = || {
        format!(
            "[{}]",
            ep.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ")
        )
    };
    if !mat.yield_stress.is_finite() {
        if ep.iter().any(|&x| x != 0.0) || peeq != 0.0 || v[9] != 0.0 {
            return Err(format!(
                "{}: plastic strain {} (εᵖxx εᵖyy εᵖxy εᵖzz), equivalent plastic strain {} and yielding flag {} in an elastic body (no yield_stress: all 0)",
                at(),
                strain(),
                num(peeq),
                num(v[9])
            ));
        }
        return Ok(());
    }
    let norm = (ep[0] * ep[0] + ep[1] * ep[1] + ep[3] * ep[3] + 2.0 * ep[2] * ep[2]).sqrt();
    if norm > MAX_PLASTIC_STRAIN {
        return Err(format!(
            "{}: plastic strain {} (εᵖxx εᵖyy εᵖxy εᵖzz) of magnitude {}, beyond {}",
            at(),
            strain(),
            num(norm),
            num(MAX_PLASTIC_STRAIN)
        ));
    }
    if peeq > MAX_PEEQ {
        return Err(format!(
            "{}: equivalent plastic strain {}, beyond {}",
            at(),
            num(peeq),
            num(MAX_PEEQ)
        ));
    }
    let trace = ep[0] + ep[1] + ep[3];
    if trace.abs() > STRAIN_REL * peeq.max(norm) + STRAIN_ABS {
        return Err(format!(
            "{}: plastic strain {} (εᵖxx εᵖyy εᵖxy εᵖzz) of trace {} (plastic flow is deviatoric: trace 0)",
            at(),
            strain(),
            num(trace)
        ));
    }
    let least = (2.0f64 / 3.0).sqrt() * norm;
    if peeq < least * (1.0 - STRAIN_REL) - STRAIN_ABS {
        return Err(format!(
            "{}: equivalent plastic strain {} below √(2/3)|εᵖ| = {} of the plastic strain {} (εᵖxx εᵖyy εᵖxy εᵖzz): it accumulates √(2/3)|Δεᵖ| of every increment",
            at(),
            num(peeq),
            num(least),
            strain()
        ));
    }
    let q = VonMises::equivalent_stress(&[sig[0], sig[1], sig[2], sig[3]]);
    let y = mat.yield_stress + mat.hardening * peeq;
    if q > y * (1.0 + YIELD_REL) {
        return Err(format!(
            "{}: equivalent stress {} MPa above the yield stress σ_Y + H ε̄ᵖ = {} MPa (a return mapping leaves it on or inside the yield surface)",
            at(),
            num(q),
            num(y)
        ));
    }
    Ok(())
}

/// The joint energy totals and every increment's joint measures, when the
/// file has them (a file of an earlier build has neither: the totals start
/// from zero, the earlier increments keep no joint measures). Totals are
/// finite; an increment's row is either finite or all NaN (an increment
/// restored from a file of an earlier build), and NaN rows come first.
fn restore_joints(ck: &mut Checkpoint, s: &Sections, interfaces: usize) -> Decoded<()> {
    if s.0.contains_key("joint_totals") {
        let v = s.finite("joint_totals", Some(2 * interfaces))?;
        ck.joint_totals = v
            .chunks_exact(2)
            .map(|t| JointTotals {
                dissipation: t[0],
                work: t[1],
            })
            .collect();
    }
    if s.0.contains_key("joints") {
        let w = JointMeasures::PACKED * interfaces;
        let v = s.f("joints", Some(w * ck.increments.len()))?;
        let mut measured = false;
        for (inc, row) in ck.increments.iter_mut().zip(v.chunks_exact(w.max(1))) {
            if row.iter().all(|x| x.is_nan()) && !measured {
                continue;
            }
            if let Some(x) = row.iter().find(|x| !x.is_finite()) {
                return Err(format!(
                    "section joints: increment {}: a value {} (a row is finite, or all NaN before the first finite one)",
                    inc.increment,
                    num(*x)
                ));
            }
            measured = true;
            inc.joints = row
                .chunks_exact(JointMeasures::PACKED)
                .map(JointMeasures::unpack)
                .collect();
        }
    }
    Ok(())
}

/// How far every interface's laws were used so far; a file of an earlier
/// build has no such section: the committed state's own reach, then.
///
/// A stored reach (u_N, p_N) is a maximum over the converged states, each
/// of them over the interface's points, starting from (0, 0): u_N within
/// [0, [`MAX_DISPLACEMENT`]] and p_N within [0, [`MAX_PRESSURE`]]; p_N the
/// normal law's pressure at u_N (the law is non-decreasing, so the largest
/// pressure is the one at the largest approach); and at least the restored
/// state's own reach ([`Reach::of`]), round-off allowed ([`REACH_REL`],
/// [`REACH_ABS`]). (Which states came before is not in the file: a reach
/// between the restored state's and the ranges cannot be told from a real one.)
fn restore_table_reach(ck: &mut Checkpoint, s: &Sections, model: &Model) -> Decoded<()> {
    let own: Vec<Reach> = model
        .interfaces
        .iter()
        .map(|im| Reach::of(im, &ck.committed.u, ck.committed.time))
        .collect();
    if !s.0.contains_key("table_reach") {
        ck.table_reach = own;
        return Ok(());
    }
    let v = s.finite("table_reach", Some(Reach::PACKED * model.interfaces.len()))?;
    let below = |a: f64, b: f64| a < b - REACH_REL * b.abs() - REACH_ABS;
    for ((im, r), own) in model
        .interfaces
        .iter()
        .zip(v.chunks_exact(Reach::PACKED).map(Reach::unpack))
        .zip(&own)
    {
        let at = format!(
            "section table_reach: interface {:?}: largest approach u_N = {} mm and pressure p_N = {} MPa",
            im.name,
            num(r.u_n),
            num(r.p_n)
        );
        if !((0.0..=MAX_DISPLACEMENT).contains(&r.u_n) && (0.0..=MAX_PRESSURE).contains(&r.p_n)) {
            return Err(format!(
                "{at}, outside [0, {}] mm and [0, {}] MPa (the displacement and pressure ranges of a case)",
                num(MAX_DISPLACEMENT),
                num(MAX_PRESSURE)
            ));
        }
        let law = im.law.pressure(r.u_n).0;
        if (r.p_n - law).abs() > REACH_REL * law.abs().max(r.p_n) + REACH_ABS {
            return Err(format!(
                "{at}, but the normal law gives {} MPa at that approach (the largest pressure is the law's at the largest approach)",
                num(law)
            ));
        }
        if below(r.u_n, own.u_n) || below(r.p_n, own.p_n) {
            return Err(format!(
                "{at}, below the restored state's own u_N = {} mm, p_N = {} MPa (a largest value so far)",
                num(own.u_n),
                num(own.p_n)
            ));
        }
    }
    ck.table_reach = v.chunks_exact(Reach::PACKED).map(Reach::unpack).collect();
    Ok(())
}

/// The first yield, if the run had reached it: finite values, a load factor
/// the curve passed, an element of the mesh and the name of its body.
fn restore_first_yield(
    s: &Sections,
    model: &Model,
    incs: &[Increment],
) -> Decoded<Option<FirstYield>> {
    if !s.0.contains_key("first_yield") {
        return Ok(None);
    }
    let v = s.finite("first_yield", Some(6))?;
    let (lo, hi) = incs.iter().fold((0.0f64, 0.0f64), |(l, h), i| {
        (l.min(i.load_factor), h.max(i.load_factor))
    });
    if !(lo..=hi).contains(&v[0]) {
        return Err(format!(
            "section first_yield: load factor {}, outside the curve's [{}, {}]",
            num(v[0]),
            num(lo),
            num(hi)
        ));
    }
    let element = whole(v[5])
        .filter(|&e| e < model.mesh.elements.len())
        .ok_or_else(|| {
            format!(
                "section first_yield: element {}, the mesh has {}",
                num(v[5]),
                model.mesh.elements.len()
            )
        })?;
    let body = s.text("first_yield_body")?;
    let expect = &model.mesh.bodies[model.mesh.elements[element].body];
    if body != expect {
        return Err(format!(
            "section first_yield_body: \"{body}\", but element {element} is in \"{expect}\""
        ));
    }
    Ok(Some(FirstYield {
        load_factor: v[0],
        mean_pressure: v[1],
        total_load_kn: v[2],
        x: v[3],
        depth: v[4],
        element,
        body: body.to_string(),
    }))
}

/// The VTU series written so far: (load factor, file name) pairs. Every name
/// is of the writer's form `vtu/NNNN.vtu` for a converged increment (in
/// increasing order, none with `vtu = false`), its load factor that
/// increment's.
fn restore_vtu_series(
    s: &Sections,
    model: &Model,
    incs: &[Increment],
) -> Decoded<Vec<(f64, String)>> {
    let pl = s.f("pvd_load_factor", None)?;
    let pf = s.text("pvd_file")?;
    let files: Vec<&str> = if pf.is_empty() {
        Vec::new()
    } else {
        pf.split('\n').collect()
    };
    if files.len() != pl.len() {
        return Err("VTU series: lengths differ".into());
    }
    if !model.output.vtu && !files.is_empty() {
        return Err("VTU series: the case writes no VTU files ([output] vtu = false)".into());
    }
    let mut last = 0;
    for (i, (&l, f)) in pl.iter().zip(&files).enumerate() {
        let k = vtu_increment(f)
            .filter(|&k| k > last && k <= incs.len())
            .ok_or_else(|| {
                format!(
                    "VTU series entry {}: {f:?} is not a name this program writes here (vtu/NNNN.vtu for an increment after {last}, at most {})",
                    i + 1,
                    incs.len()
                )
            })?;
        if l.to_bits() != incs[k - 1].load_factor.to_bits() {
            return Err(format!(
                "VTU series entry {}: load factor {}, but increment {k} is at {}",
                i + 1,
                num(l),
                num(incs[k - 1].load_factor)
            ));
        }
        last = k;
    }
    Ok(pl
        .iter()
        .zip(files)
        .map(|(&l, f)| (l, f.to_string()))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The streamed checksum equals the one-shot checksum for any split of
    /// the bytes, word-aligned or not.
    #[test]
    fn the_streamed_checksum_does_not_depend_on_the_split() {
        let bytes: Vec<u8> = (0..1000u32).map(|i| (i * 37 % 251) as u8).collect();
        let whole = fnv1a(&bytes);
        for step in [1, 3, 7, 8, 9, 64, 999] {
            let mut f = Fnv::default();
            for piece in bytes.chunks(step) {
                f.update(piece);
            }
            assert_eq!(f.finish(), whole, "pieces of {step}");
        }
        // and a change anywhere changes it
        let mut other = bytes.clone();
        other[997] ^= 1;
        assert_ne!(fnv1a(&other), whole);
    }

    fn model() -> Model {
        Model::parse(
            include_str!("../cases/punch-plane-stress/case.toml"),
            "case.toml",
        )
        .unwrap()
    }

    /// A checkpoint after `n` increments of the case's schedule, as a run
    /// leaves it (no solve: the state stays the initial one), with a VTU
    /// file per increment.
    fn checkpoint(model: &Model, n: usize) -> (Checkpoint, Vec<(f64, String)>) {
        let mut ck = Checkpoint::initial(model);
        let mut pvd = Vec::new();
        for k in 1..=n {
            let t = ck.stepper.next(ck.lambda).unwrap();
            ck.stepper.accepted(ck.lambda, t, 3, 0.0);
            ck.last_step = t - ck.lambda;
            ck.lambda = t;
            ck.increments.push(Increment {
                increment: k,
                load_factor: t,
                iterations: 3,
                cutbacks: 0,
                measures: Measures::default(),
                joints: vec![JointMeasures::default(); model.interfaces.len()],
            });
            pvd.push((t, vtu_name(k)));
        }
        (ck, pvd)
    }

    #[test]
    fn vtu_names_are_only_the_writers_own() {
        for (k, name) in [
            (1, "vtu/0001.vtu"),
            (12, "vtu/0012.vtu"),
            (12345, "vtu/12345.vtu"),
        ] {
            assert_eq!(vtu_name(k), name);
            assert_eq!(vtu_increment(name), Some(k));
        }
        for bad in [
            "vtu/001.vtu",
            "vtu/00001.vtu",
            "vtu/+001.vtu",
            "vtu/0001.vtu/",
            "vtu//0001.vtu",
            "vtu/../0001.vtu",
            "/vtu/0001.vtu",
            "./vtu/0001.vtu",
            "vtu\\0001.vtu",
            "interface/0001.csv",
            "vtu/0001.VTU",
            "vtu/99999999999999999999999.vtu",
            "",
        ] {
            assert_eq!(vtu_increment(bad), None, "{bad}");
        }
    }

    /// The checks of [`decode`] on checkpoints that encode cleanly (as a
    /// forger would write them): each one changed field is refused with
    /// its own message, the unchanged one restores exactly.
    #[test]
    fn decode_refuses_what_the_case_cannot_have_produced() {
        let model = model();
        let (ck, pvd) = checkpoint(&model, 4);
        let (back, series) = decode(&encode(&model, &ck, &pvd), &model).unwrap();
        assert_eq!(series, pvd);
        assert_eq!(back.lambda.to_bits(), ck.lambda.to_bits());
        assert_eq!(back.stepper.pending, ck.stepper.pending);
        assert_eq!(back.increments.len(), 4);
        let refused = |ck: &Checkpoint, pvd: &[(f64, String)], needle: &str| {
            let e = decode(&encode(&model, ck, pvd), &model).unwrap_err();
            assert!(e.contains(needle), "{needle}: {e}");
        };
        // names: a path outside, an increment not converged, out of order
        for name in ["../x.vtu", "vtu/0005.vtu", "vtu/0001.vtu"] {
            let mut p = pvd.clone();
            p[1].1 = name.into();
            refused(&ck, &p, "is not a name this program writes");
        }
        let mut c = ck.clone();
        c.stepper.pending.remove(0);
        refused(&c, &pvd, "pending schedule");
        let mut c = ck.clone();
        c.stepper.pending.last_mut().unwrap().1 = 1;
        refused(&c, &pvd, "pending schedule");
        let mut c = ck.clone();
        c.last_step = 0.5;
        refused(&c, &pvd, "section last_step");
        let mut c = ck.clone();
        c.cutbacks_total = 3;
        refused(&c, &pvd, "cutbacks in all");
        let mut c = ck.clone();
        c.last_du = vec![0.0; c.committed.u.len()];
        c.last_du[5] = f64::NAN;
        refused(&c, &pvd, "section last_du: value 6 is not finite");
        let mut c = ck.clone();
        c.committed.gauss[2].peeq = -1e-3;
        refused(&c, &pvd, "Gauss point 3: equivalent plastic strain -1e-3");
        let mut c = ck.clone();
        c.committed.contact[0].mu_f = f64::INFINITY;
        refused(&c, &pvd, "section contact: value 5 is not finite");
        let mut c = ck.clone();
        c.joint_totals[0].work = f64::NAN;
        refused(&c, &pvd, "section joint_totals");
        // an increment without joint rows after one with them (NaN rows
        // only come first, from a file of an earlier build)
        let mut c = ck.clone();
        c.increments[2].joints.clear();
        refused(&c, &pvd, "section joints: increment 3");
        let mut c = ck.clone();
        c.increments[0].joints.clear();
        c.increments[1].joints.clear();
        let (back, _) = decode(&encode(&model, &c, &pvd), &model).unwrap();
        assert!(back.increments[1].joints.is_empty() && !back.increments[2].joints.is_empty());
        let mut c = ck.clone();
        c.increments[3].measures.max_peeq = f64::NAN;
        refused(&c, &pvd, "section curve: value 39 is not finite");
        let mut c = ck.clone();
        c.elastic_ratio_prev = -1.0;
        refused(&c, &pvd, "section elastic_ratio_prev");
        // forged floats are quoted short
        let mut c = ck.clone();
        c.lambda = 1e300;
        refused(&c, &pvd, "section load_factor: load factor 1e300, but");
        // counters beyond what the case can count
        let most = most_iterations(&model, 4, 0);
        let mut c = ck.clone();
        c.iterations = most as usize;
        c.factorizations = most as usize;
        assert!(decode(&encode(&model, &c, &pvd), &model).is_ok());
        c.factorizations += 1;
        refused(&c, &pvd, "section counters: ");
        // displacements beyond the displacement range
        let mut c = ck.clone();
        c.committed.u[3] = -2e4;
        refused(
            &c,
            &pvd,
            "section u: value 4 is -2e4 mm, beyond the ±1e4 mm",
        );
        let mut c = ck.clone();
        c.last_du = vec![0.0; c.committed.u.len()];
        c.last_du[0] = 1e300;
        refused(&c, &pvd, "section last_du: value 1 is 1e300 mm");
        // a plastic state no return mapping leaves: radial (plane strain
        // numbers) with ε̄ᵖ = √(2/3)|εᵖ| is accepted, a little less is not
        let mut c = ck.clone();
        let ep: [f64; 4] = [2e-3, -1e-3, 5e-4, -1e-3];
        let norm = (ep[0] * ep[0] + ep[1] * ep[1] + ep[3] * ep[3] + 2.0 * ep[2] * ep[2]).sqrt();
        c.committed.gauss[5].plastic_strain = ep;
        c.committed.gauss[5].peeq = (2.0f64 / 3.0).sqrt() * norm;
        assert!(decode(&encode(&model, &c, &pvd), &model).is_ok());
        c.committed.gauss[5].peeq *= 1.0 - 1e-6;
        refused(
            &c,
            &pvd,
            "Gauss point 6 (body \"punch\"): equivalent plastic strain",
        );
        // a reach the normal law does not give, or below the state's own
        let mut c = ck.clone();
        c.table_reach[0] = Reach { u_n: 1.0, p_n: 1.0 };
        refused(&c, &pvd, "but the normal law gives 1e6 MPa");
        c.table_reach[0] = Reach { u_n: 1.0, p_n: 1e6 };
        assert!(decode(&encode(&model, &c, &pvd), &model).is_ok());
        c.table_reach[0] = Reach {
            u_n: -1e-3,
            p_n: 0.0,
        };
        refused(&c, &pvd, "outside [0, 1e4] mm");
        let fy = FirstYield {
            load_factor: 0.1,
            mean_pressure: 1.0,
            total_load_kn: 1.0,
            x: 0.0,
            depth: 0.0,
            body: model.mesh.bodies[model.mesh.elements[7].body].clone(),
            element: 7,
        };
        let mut c = ck.clone();
        c.first_yield = Some(fy.clone());
        assert!(decode(&encode(&model, &c, &pvd), &model).is_ok());
        c.first_yield = Some(FirstYield {
            element: model.mesh.elements.len(),
            ..fy.clone()
        });
        refused(&c, &pvd, "section first_yield: element");
        c.first_yield = Some(FirstYield {
            body: "elsewhere".into(),
            ..fy.clone()
        });
        refused(&c, &pvd, "section first_yield_body");
        c.first_yield = Some(FirstYield {
            load_factor: 0.9,
            ..fy
        });
        refused(&c, &pvd, "outside the curve's");
        // more bytes than the case can need, refused before anything is decoded
        let mut big = encode(&model, &ck, &pvd);
        big.resize(Bounds::of(&model).restart_bytes as usize + 1, 0);
        let e = decode(&big, &model).unwrap_err();
        assert!(e.contains("bytes, more than the"), "{e}");
    }
}
