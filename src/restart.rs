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

use crate::error::{Error, Result};
use crate::interface::extrapolation::Reach;
use crate::interface::joint::{JointMeasures, JointTotals};
use crate::interface::{PointState as ContactState, Status};
use crate::material::PointState;
use crate::model::Model;
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

/// Reads `restart.bin` in `dir` for `model`: the checkpoint and the VTU series.
pub fn read(dir: &Path, model: &Model) -> Result<(Checkpoint, Vec<(f64, String)>)> {
    let path = dir.join(FILE);
    // a regular file only (not a FIFO or a device that never ends); the bound
    // is far above any checkpoint of a model within the element cap
    let bytes = crate::case::read_input(&path, 64 << 30, "restart file")?;
    decode(&bytes, model).map_err(|m| Error::input(path.display().to_string(), m))
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
pub fn decode(
    bytes: &[u8],
    model: &Model,
) -> std::result::Result<(Checkpoint, Vec<(f64, String)>), String> {
    let mut r = check_header(bytes, model)?;
    let s = Sections(read_sections(&mut r)?);
    let mut ck = Checkpoint::initial(model);
    let increments = *s.u("increment")?.first().ok_or("empty increment")? as usize;
    restore_stepper(&mut ck, &s)?;
    restore_state(&mut ck, &s)?;
    ck.committed.time = ck.lambda;
    ck.increments = restore_curve(&s, increments)?;
    restore_joints(&mut ck, &s, model.interfaces.len())?;
    restore_table_reach(&mut ck, &s, model)?;
    ck.first_yield = restore_first_yield(&s)?;
    let pvd = restore_vtu_series(&s)?;
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

/// Reads the section table by name; the sections must end where the
/// checksum begins.
fn read_sections(r: &mut Reader) -> Decoded<BTreeMap<String, Data>> {
    let n = r.u32()?;
    let mut map: BTreeMap<String, Data> = BTreeMap::new();
    for _ in 0..n {
        let len = r.u16()? as usize;
        let name = String::from_utf8_lossy(r.take(len)?).into_owned();
        let kind = r.take(1)?[0];
        let count = usize::try_from(r.u64()?).map_err(|_| "bad section size")?;
        let width = match kind {
            1 | 2 => 8,
            3 | 4 => 1,
            k => return Err(format!("section {name}: unknown kind {k}")),
        };
        let raw = r.take(count.checked_mul(width).ok_or("bad section size")?)?;
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
        map.insert(name, data);
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
    /// The u64 section `name`.
    fn u(&self, name: &str) -> Decoded<&Vec<u64>> {
        match self.0.get(name) {
            Some(Data::U64(v)) => Ok(v),
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

/// The load stepping: load factor, last step and predictor direction, the
/// pending schedule, the automatic step control, cutbacks and counters.
fn restore_stepper(ck: &mut Checkpoint, s: &Sections) -> Decoded<()> {
    let nu = ck.committed.u.len();
    ck.lambda = s.f("load_factor", Some(1))?[0];
    ck.last_step = s.f("last_step", Some(1))?[0];
    // the predictor's direction; absent from files of earlier builds (the
    // next increment then starts from the committed state)
    if let Some(Data::F64(v)) = s.0.get("last_du") {
        if !v.is_empty() && v.len() != nu {
            return Err(format!(
                "section last_du has {} values, the model needs {nu}",
                v.len()
            ));
        }
        ck.last_du = v.clone();
    }
    let pl = s.f("pending_load_factor", None)?;
    let pd = s.u("pending_depth")?;
    if pl.len() != pd.len() {
        return Err("pending schedule: lengths differ".into());
    }
    ck.stepper.pending = pl.iter().zip(pd).map(|(&l, &d)| (l, d as usize)).collect();
    ck.stepper.waypoints = s.f("auto_waypoints", None)?.clone();
    ck.stepper.step = s.f("auto_step", Some(1))?[0];
    ck.stepper.failures = *s.u("auto_failures")?.first().ok_or("empty auto_failures")? as usize;
    let cb = s.u("cutbacks")?;
    let ct = s.u("counters")?;
    if cb.len() != 2 || ct.len() != 2 {
        return Err("cutbacks/counters: expected 2 values".into());
    }
    (ck.cutbacks_total, ck.cutbacks_here) = (cb[0] as usize, cb[1] as usize);
    (ck.iterations, ck.factorizations) = (ct[0] as usize, ct[1] as usize);
    ck.elastic_ratio_prev = s.f("elastic_ratio_prev", Some(1))?[0];
    Ok(())
}

/// The committed state: displacements, Gauss points, interface status and
/// contact state, and the prescribed reaction, each sized for the model.
fn restore_state(ck: &mut Checkpoint, s: &Sections) -> Decoded<()> {
    let c = &mut ck.committed;
    let (ng, np, nu) = (c.gauss.len(), c.status.len(), c.u.len());
    c.u.copy_from_slice(s.f("u", Some(nu))?);
    for (p, v) in c.gauss.iter_mut().zip(
        s.f("gauss", Some(PointState::PACKED * ng))?
            .chunks_exact(PointState::PACKED),
    ) {
        *p = PointState::unpack(v);
    }
    match s.0.get("status") {
        Some(Data::U8(v)) if v.len() == np => {
            c.status = v.iter().map(|&code| Status::from_code(code)).collect();
        }
        _ => return Err(format!("section status: expected {np} codes")),
    }
    for (p, v) in c.contact.iter_mut().zip(
        s.f("contact", Some(ContactState::PACKED * np))?
            .chunks_exact(ContactState::PACKED),
    ) {
        *p = ContactState::unpack(v);
    }
    c.prescribed_reaction = s.f("prescribed_reaction", Some(1))?[0];
    Ok(())
}

/// The load curve: one row of 10 values per converged increment.
fn restore_curve(s: &Sections, increments: usize) -> Decoded<Vec<Increment>> {
    let rows = s.f("curve", Some(10 * increments))?;
    Ok(rows
        .chunks_exact(10)
        .map(|v| Increment {
            increment: v[0] as usize,
            load_factor: v[1],
            iterations: v[2] as usize,
            cutbacks: v[3] as usize,
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
        .collect())
}

/// The joint energy totals and every increment's joint measures, when the
/// file has them (a file of an earlier build has neither: the totals start
/// from zero, the earlier increments keep no joint measures).
fn restore_joints(ck: &mut Checkpoint, s: &Sections, interfaces: usize) -> Decoded<()> {
    if s.0.contains_key("joint_totals") {
        let v = s.f("joint_totals", Some(2 * interfaces))?;
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
        for (inc, row) in ck.increments.iter_mut().zip(v.chunks_exact(w.max(1))) {
            if !row[0].is_nan() {
                inc.joints = row
                    .chunks_exact(JointMeasures::PACKED)
                    .map(JointMeasures::unpack)
                    .collect();
            }
        }
    }
    Ok(())
}

/// How far every interface's laws were used so far; a file of an earlier
/// build has no such section: the committed state's own reach, then.
fn restore_table_reach(ck: &mut Checkpoint, s: &Sections, model: &Model) -> Decoded<()> {
    if s.0.contains_key("table_reach") {
        let v = s.f("table_reach", Some(Reach::PACKED * model.interfaces.len()))?;
        ck.table_reach = v.chunks_exact(Reach::PACKED).map(Reach::unpack).collect();
    } else {
        ck.table_reach = model
            .interfaces
            .iter()
            .map(|im| Reach::of(im, &ck.committed.u, ck.committed.time))
            .collect();
    }
    Ok(())
}

/// The first yield, if the run had reached it.
fn restore_first_yield(s: &Sections) -> Decoded<Option<FirstYield>> {
    if !s.0.contains_key("first_yield") {
        return Ok(None);
    }
    let v = s.f("first_yield", Some(6))?;
    Ok(Some(FirstYield {
        load_factor: v[0],
        mean_pressure: v[1],
        total_load_kn: v[2],
        x: v[3],
        depth: v[4],
        element: v[5] as usize,
        body: s.text("first_yield_body")?.to_string(),
    }))
}

/// The VTU series written so far: (load factor, file name) pairs.
fn restore_vtu_series(s: &Sections) -> Decoded<Vec<(f64, String)>> {
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
}
