//! Decoding `restart.bin` and checking every section against the case
//! (the list in the module comment of [`super`]).

use super::*;

mod contact;
mod records;
mod stepper;
use records::*;
pub(super) use stepper::*;

pub(super) struct Reader<'a> {
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
pub(super) type Decoded<T> = std::result::Result<T, String>;

/// Decodes and checks a restart file against the model it is meant for.
/// The checksum and the fingerprint only catch accidents (anyone can compute
/// them): every value is also checked against what the case allows.
#[cfg(test)]
pub(crate) fn decode(
    bytes: &[u8],
    model: &Model,
) -> std::result::Result<(Checkpoint, Vec<(f64, String)>), String> {
    decode_with(bytes, model, &Bounds::of(model))
}

pub(super) fn decode_with(
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
    check_curve(&ck, model)?;
    restore_joints(&mut ck, &s, model)?;
    restore_sections(&mut ck, &s, model)?;
    restore_table_reach(&mut ck, &s, model)?;
    ck.first_yield = restore_first_yield(&s, model, &ck.increments)?;
    restore_designer(&mut ck, &s, model)?;
    check_records(&ck, model)?;
    let pvd = restore_vtu_series(&s, model, &ck.increments)?;
    Ok((ck, pvd))
}

/// Checks the magic, the version, the checksum and the fingerprint; the
/// reader is left at the section count, over the bytes before the checksum.
pub(super) fn check_header<'a>(bytes: &'a [u8], model: &Model) -> Decoded<Reader<'a>> {
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
        let (by, then) = if version < VERSION {
            ("an earlier", "run the case again from the start")
        } else {
            (
                "a later",
                "resume it with that build, or run the case again from the start",
            )
        };
        return Err(format!(
            "{FILE} was written by {by} asperity (restart format {version}); this build reads format {VERSION} only: {then}"
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
/// its data is copied); the sections must end where the checksum begins,
/// and they are exactly those of the format ([`SECTIONS`]): one missing or
/// of another name is refused by name.
pub(super) fn read_sections(r: &mut Reader) -> Decoded<BTreeMap<String, Data>> {
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
    if let Some(name) = map.keys().find(|n| !SECTIONS.contains(&n.as_str())) {
        return Err(format!(
            "section {name:?} is no section of restart format {VERSION}"
        ));
    }
    if let Some(name) = SECTIONS.iter().find(|n| !map.contains_key(**n)) {
        return Err(format!(
            "section {name} missing: every restart file of format {VERSION} holds it"
        ));
    }
    Ok(map)
}

/// The decoded sections, looked up by name and kind.
pub(super) struct Sections(BTreeMap<String, Data>);

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
            _ => Err(format!("section {name}: not f64 values")),
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
            _ => Err(format!("section {name}: not u64 values")),
        }
    }
    /// The text section `name`.
    fn text(&self, name: &str) -> Decoded<&str> {
        match self.0.get(name) {
            Some(Data::Text(v)) => Ok(v),
            _ => Err(format!("section {name}: not text")),
        }
    }
}

/// Every value of section `name` finite, else the first one that is not.
pub(super) fn all_finite(name: &str, v: &[f64]) -> Decoded<()> {
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
pub(super) fn whole(v: f64) -> Option<usize> {
    ((0.0..9.007_199_254_740_992e15).contains(&v) && v.fract() == 0.0).then_some(v as usize)
}

/// The load curve: one row of 10 values per converged increment, numbered
/// 1, 2, … in order, with whole iteration and cutback counts and finite
/// load factors and measures.
pub(super) fn restore_curve(s: &Sections, increments: usize) -> Decoded<Vec<Increment>> {
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
                sections: Vec::new(),
                record: Vec::new(),
                von_mises_away: f64::NAN,
            })
        })
        .collect()
}

/// The committed state: displacements, Gauss points, interface status and
/// contact state, and the prescribed reaction, each sized for the model,
/// every value finite, the displacements within [`MAX_DISPLACEMENT`],
/// status codes valid, every Gauss point a state the case's return mapping
/// can leave ([`check_gauss_point`]).
pub(super) fn restore_state(ck: &mut Checkpoint, s: &Sections, model: &Model) -> Decoded<()> {
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
    let w = PointState::packed_len(model.node_dofs().six_components());
    let gauss = s.finite("gauss", Some(w * ng))?;
    for (i, v) in gauss.chunks_exact(w).enumerate() {
        check_gauss_point(model, i, v, ck.lambda)?;
        c.gauss.set(i, &PointState::unpack(v, w));
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
    contact::restore(s, model, &c.u, ck.lambda, &mut c.contact)?;
    c.prescribed_reaction = s.finite("prescribed_reaction", Some(1))?[0];
    Ok(())
}

/// Every value of section `name` (finite: checked before) within ±`bound`
/// (`unit`, `what` says whose bound), else the first beyond it.
pub(super) fn all_within(name: &str, v: &[f64], bound: f64, unit: &str, what: &str) -> Decoded<()> {
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
/// material at the committed pseudo-time `time` can leave (its σ_Y read at
/// the point's temperature: [`Model::gauss_material`];
/// [`crate::physics::material`]):
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
pub(super) fn check_gauss_point(model: &Model, i: usize, v: &[f64], time: f64) -> Decoded<()> {
    if v[8] < 0.0 || (v[9] != 0.0 && v[9] != 1.0) {
        return Err(format!(
            "section gauss: Gauss point {}: equivalent plastic strain {} and yielding flag {} (≥ 0, and 0 or 1 expected)",
            i + 1,
            num(v[8]),
            num(v[9])
        ));
    }
    let body = model.mesh.elements[model.element_of_point(i)].body;
    let at = format!(
        "section gauss: Gauss point {} (body {:?})",
        i + 1,
        model.mesh.bodies[body]
    );
    // with twist: σ_rθ, σ_zθ and εᵖ_rθ, εᵖ_zθ follow (0 without it)
    let (ts, te) = if v.len() >= PointState::PACKED_TWIST {
        ([v[10], v[11]], [v[12], v[13]])
    } else {
        ([0.0; 2], [0.0; 2])
    };
    let stress = [v[0], v[1], v[2], v[3], ts[0], ts[1]];
    check_stress(&at, &stress, model.plane)?;
    let plastic = Plastic {
        strain: [v[4], v[5], v[6], v[7]],
        twist: te,
        peeq: v[8],
        yielding: v[9],
    };
    plastic.check(&at, &model.gauss_material(i, time), &stress)
}

/// A stored stress within [`MAX_STRESS`], and σzz = 0 in plane stress.
fn check_stress(at: &str, all: &[f64; 6], plane: crate::physics::material::Plane) -> Decoded<()> {
    const STRESS: [&str; 6] = ["σxx", "σyy", "σxy", "σzz", "σ_rθ", "σ_zθ"];
    if let Some(k) = all.iter().position(|x| x.abs() > MAX_STRESS) {
        return Err(format!(
            "{at}: stress {} = {} MPa, beyond ±{} MPa (10⁴ × the largest Young's modulus of a case)",
            STRESS[k],
            num(all[k]),
            num(MAX_STRESS)
        ));
    }
    if plane == crate::physics::material::Plane::Stress && all[3] != 0.0 {
        return Err(format!(
            "{at}: σzz = {} MPa in plane stress (0 exactly)",
            num(all[3])
        ));
    }
    Ok(())
}

/// The plastic part of a stored Gauss point state, as read.
struct Plastic {
    /// εᵖxx εᵖyy εᵖxy εᵖzz
    strain: [f64; 4],
    /// εᵖ_rθ, εᵖ_zθ (0 without twist)
    twist: [f64; 2],
    peeq: f64,
    yielding: f64,
}

impl Plastic {
    fn strain_text(&self) -> String {
        let parts: Vec<String> = self.strain.iter().map(|&x| num(x)).collect();
        format!("[{}]", parts.join(", "))
    }

    /// The rules of [`check_gauss_point`] for the plastic state, each with
    /// its own message: none at all in an elastic body; else bounded,
    /// deviatoric, ε̄ᵖ ≥ √(2/3)|εᵖ|, and the stress on or inside the yield
    /// surface.
    fn check(&self, at: &str, mat: &VonMises, stress: &[f64; 6]) -> Decoded<()> {
        let (ep, te, peeq) = (&self.strain, &self.twist, self.peeq);
        if !mat.yield_stress.is_finite() {
            if ep.iter().chain(te).any(|&x| x != 0.0) || peeq != 0.0 || self.yielding != 0.0 {
                return Err(format!(
                    "{at}: plastic strain {} (εᵖxx εᵖyy εᵖxy εᵖzz), equivalent plastic strain {} and yielding flag {} in an elastic body (no yield_stress: all 0)",
                    self.strain_text(),
                    num(peeq),
                    num(self.yielding)
                ));
            }
            return Ok(());
        }
        let twist = 2.0 * (te[0] * te[0] + te[1] * te[1]);
        let norm =
            (ep[0] * ep[0] + ep[1] * ep[1] + ep[3] * ep[3] + 2.0 * ep[2] * ep[2] + twist).sqrt();
        if norm > MAX_PLASTIC_STRAIN {
            return Err(format!(
                "{at}: plastic strain {} (εᵖxx εᵖyy εᵖxy εᵖzz) of magnitude {}, beyond {}",
                self.strain_text(),
                num(norm),
                num(MAX_PLASTIC_STRAIN)
            ));
        }
        if peeq > MAX_PEEQ {
            return Err(format!(
                "{at}: equivalent plastic strain {}, beyond {}",
                num(peeq),
                num(MAX_PEEQ)
            ));
        }
        let trace = ep[0] + ep[1] + ep[3];
        if trace.abs() > STRAIN_REL * peeq.max(norm) + STRAIN_ABS {
            return Err(format!(
                "{at}: plastic strain {} (εᵖxx εᵖyy εᵖxy εᵖzz) of trace {} (plastic flow is deviatoric: trace 0)",
                self.strain_text(),
                num(trace)
            ));
        }
        let least = (2.0f64 / 3.0).sqrt() * norm;
        if peeq < least * (1.0 - STRAIN_REL) - STRAIN_ABS {
            return Err(format!(
                "{at}: equivalent plastic strain {} below √(2/3)|εᵖ| = {} of the plastic strain {} (εᵖxx εᵖyy εᵖxy εᵖzz): it accumulates √(2/3)|Δεᵖ| of every increment",
                num(peeq),
                num(least),
                self.strain_text()
            ));
        }
        let q = VonMises::equivalent_stress(stress);
        let y = mat.yield_stress + mat.hardening * peeq;
        if q > y * (1.0 + YIELD_REL) {
            return Err(format!(
                "{at}: equivalent stress {} MPa above the yield stress σ_Y + H ε̄ᵖ = {} MPa (a return mapping leaves it on or inside the yield surface)",
                num(q),
                num(y)
            ));
        }
        Ok(())
    }
}

/// The designer's outputs: each increment's record and the events located
/// so far, in the layout of the model's records (`record_width`, the
/// model's [`crate::model::outputs::Plan::width`]), checked by
/// [`restore_records`].
pub(super) fn restore_designer(ck: &mut Checkpoint, s: &Sections, model: &Model) -> Decoded<()> {
    let width = s.u("record_width", Some(1))?[0];
    let own = model.plan.width();
    if width != own as u64 {
        return Err(format!(
            "section record_width: records of {width} values, but this case's have {own} (reactions, probes, peaks)"
        ));
    }
    restore_records(
        &model.plan,
        ck,
        s.f("records", None)?,
        s.f("events", None)?,
        model,
    )
}

/// How far every interface's laws were used so far.
///
/// A stored reach (u_N, p_N) is a maximum over the converged states, each
/// of them over the interface's points, starting from (0, 0): u_N within
/// [0, [`MAX_DISPLACEMENT`]] and p_N within [0, [`MAX_PRESSURE`]]; p_N the
/// normal law's pressure at u_N (the law is non-decreasing, so the largest
/// pressure is the one at the largest approach); and at least the restored
/// state's own reach ([`Reach::of`]), round-off allowed ([`REACH_REL`],
/// [`REACH_ABS`]). (Which states came before is not in the file: a reach
/// between the restored state's and the ranges cannot be told from a real one.)
pub(super) fn restore_table_reach(ck: &mut Checkpoint, s: &Sections, model: &Model) -> Decoded<()> {
    let own: Vec<Reach> = model
        .interfaces
        .iter()
        .map(|im| Reach::of(im, &ck.committed.u, ck.committed.time))
        .collect();
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

/// The first yield, if the run had reached it (`first_yield` and
/// `first_yield_body` empty otherwise): finite values, a load factor the
/// curve passed, an element of the mesh and the name of its body.
pub(super) fn restore_first_yield(
    s: &Sections,
    model: &Model,
    incs: &[Increment],
) -> Decoded<Option<FirstYield>> {
    if s.f("first_yield", None)?.is_empty() {
        let body = s.text("first_yield_body")?;
        if !body.is_empty() {
            return Err(format!(
                "section first_yield_body: \"{}\" without a first yield (section first_yield is empty)",
                crate::error::clip(body)
            ));
        }
        return Ok(None);
    }
    let v = s.finite("first_yield", Some(7))?;
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
        z: v[6],
        element,
        body: body.to_string(),
    }))
}

/// The VTU series written so far: (load factor, file name) pairs. Every name
/// is of the writer's form `vtu/NNNN.vtu` for a converged increment (in
/// increasing order, none with `vtu = false`), its load factor that
/// increment's.
pub(super) fn restore_vtu_series(
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

/// Restores a restart file's designer sections into a checkpoint whose
/// curve is restored: `records`, each increment's record (`plan`'s width
/// per increment: finite or NaN, no infinity), and `events`
/// ([`crate::solve::events::Event::unpack`]). The error is a message for
/// the restart file's line.
fn restore_records(
    plan: &crate::model::outputs::Plan,
    ck: &mut crate::solve::Checkpoint,
    records: &[f64],
    events: &[f64],
    model: &crate::model::Model,
) -> std::result::Result<(), String> {
    let w = plan.width();
    if records.len() != w * ck.increments.len() {
        return Err(format!(
            "section records has {} values, the model needs {}",
            records.len(),
            w * ck.increments.len()
        ));
    }
    if let Some(i) = records.iter().position(|x| x.is_infinite()) {
        return Err(format!(
            "section records: value {} is infinite ({})",
            i + 1,
            records[i]
        ));
    }
    for (k, inc) in ck.increments.iter_mut().enumerate() {
        inc.record = records[w * k..w * (k + 1)].to_vec();
    }
    let load_factors: Vec<f64> = ck.increments.iter().map(|i| i.load_factor).collect();
    ck.events = crate::solve::events::Event::unpack(events, w, model, &load_factors)?;
    Ok(())
}
