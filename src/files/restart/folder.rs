//! The limits a restart folder is held to and the files a resumed run
//! copies from it: [`Bounds`] (what the case can need), the writer's own
//! names, and the link-free, size-bounded open and copy.

use super::*;

/// Most sections a restart file may list (the format has 32, [`SECTIONS`]:
/// a count beyond this is refused before any section is read).
pub(crate) const MAX_SECTIONS: u32 = 64;
/// Longest section name (this build's longest has 19 bytes).
pub(super) const MAX_SECTION_NAME: usize = 64;
/// Most converged increments behind a resumed run, whatever the case allows
/// (a run of this many increments writes as many interface CSV files).
pub(crate) const MAX_RESUMED_INCREMENTS: usize = 1 << 24;
/// Longest VTU name in the `pvd_file` section: `vtu/` + 20 digits + `.vtu`.
pub(super) const MAX_VTU_NAME: usize = 28;
/// Largest |u| and |Δu| (`u`, `last_du`) and interface approach u_N
/// (`table_reach`) of a restored state, mm: the displacement range of a
/// case ([`ranges::DISPLACEMENT`], 10 m).
pub(crate) const MAX_DISPLACEMENT: f64 = ranges::DISPLACEMENT.hi;
/// Largest interface pressure p_N of `table_reach`, MPa: the pressure range
/// of a case ([`ranges::PRESSURE`]).
pub(crate) const MAX_PRESSURE: f64 = ranges::PRESSURE.hi;
/// Largest |σ| component of a Gauss point, MPa: 10⁴ × the largest Young's
/// modulus a case may give ([`ranges::MODULUS`]), 10⁶ × the largest yield
/// stress or pressure.
pub(crate) const MAX_STRESS: f64 = 1e4 * ranges::MODULUS.hi;
/// Largest plastic strain |εᵖ| (the tensor norm, √(εᵖ:εᵖ)) of a Gauss
/// point: 1000 %, far beyond what a small-strain model means.
pub(crate) const MAX_PLASTIC_STRAIN: f64 = 10.0;
/// Largest accumulated plastic strain ε̄ᵖ of a Gauss point (it grows under
/// cyclic loading where εᵖ does not).
pub(crate) const MAX_PEEQ: f64 = 1e4;
/// Round-off allowed in the relations between the stored plastic strains
/// (trace, ε̄ᵖ ≥ √(2/3)|εᵖ|): relative, and absolute (a strain).
pub(super) const STRAIN_REL: f64 = 1e-9;
pub(super) const STRAIN_ABS: f64 = 1e-15;
/// Round-off allowed above the yield surface: σ_eq ≤ σ_y(ε̄ᵖ) (1 + this).
pub(super) const YIELD_REL: f64 = 1e-6;
/// Round-off allowed between `table_reach` and what the restored state
/// and the normal law give: relative, and absolute (mm or MPa).
pub(super) const REACH_REL: f64 = 1e-9;
pub(super) const REACH_ABS: f64 = 1e-12;
/// Margin on the most Newton iterations and factorizations a run can have
/// counted ([`most_iterations`]).
pub(super) const COUNTER_MARGIN: u128 = 2;

/// A float quoted in a refusal: the shortest form that reads back as it,
/// plain or scientific (at most 24 characters: a forged 1e300 is `1e300`,
/// not 301 digits).
pub(super) fn num(x: f64) -> String {
    crate::numbers::exact(x)
}

/// The most Newton iterations (and as many factorizations: one per
/// iteration) a run can have counted after `increments` converged
/// increments and `cutbacks` cutbacks: every attempt at a step (each
/// increment or cutback, and one more) is at most a solve from the
/// predictor and one from the committed state ([`crate::solve`]'s predictor
/// restart), each the plain solve and, under the contact stabilization, up
/// to [`stabilize::LEVELS`] stabilized solves each with its release; the
/// first-yield search adds at most 1 + [`yield_point::SEARCH_STEPS`] such
/// steps once, and each of the three events of every interface at most
/// [`crate::solve::events::MAX_SOLVES`] once. Every solve takes at most the
/// case's iteration limit (PETSc SNES: its cap, 10 more); all of it times
/// [`COUNTER_MARGIN`].
pub(crate) fn most_iterations(model: &Model, increments: u64, cutbacks: u64) -> u128 {
    let per_step = 1 + 2 * stabilize::LEVELS as u128;
    let attempts = u128::from(increments) + u128::from(cutbacks) + 1;
    let events = 3 * model.interfaces.len() as u128 * crate::solve::events::MAX_SOLVES as u128;
    let solves = (2 * attempts + 1 + yield_point::SEARCH_STEPS as u128 + events) * per_step;
    solves * (model.solver.iteration_limit() as u128 + 10) * COUNTER_MARGIN
}

/// What a restart folder can hold for a model, from the model alone: the
/// bounds every size read from the folder is checked against before
/// anything of that size is allocated or copied.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bounds {
    /// Converged increments: what the case's schedule (fixed) or step
    /// control (automatic) can produce ([`Stepper::most_increments`]), at
    /// most [`MAX_RESUMED_INCREMENTS`].
    pub increments: usize,
    /// Bytes of `restart.bin`: the state (dofs, Gauss points, interface
    /// points), the stepping state, and per increment its curve row, joint
    /// rows, pretension row, record and VTU entry, with room for the
    /// section table.
    pub(crate) restart_bytes: u64,
    /// Bytes of one `interface/NNNN.csv` (512 per interface pair and its name).
    pub(crate) csv_bytes: u64,
    /// Bytes of one `vtu/NNNN.vtu` (512 per node, 256 per element: at most
    /// 16 numbers of 25 characters per node in ASCII; a binary file holds 8
    /// bytes per number and a block header per array).
    pub(crate) vtu_bytes: u64,
}

impl Bounds {
    pub fn of(model: &Model) -> Bounds {
        let st = Stepper::for_model(model);
        let increments = st.most_increments().min(MAX_RESUMED_INCREMENTS) as u64;
        let nu = model.num_dofs() as u64;
        let ng = model.n_points() as u64;
        let np: u64 = model.interfaces.iter().map(|i| i.points.len() as u64).sum();
        let ni = model.interfaces.len() as u64;
        let body = model.mesh.bodies.iter().map(|b| b.len()).max().unwrap_or(0) as u64;
        // 8-byte values besides the per-increment rows: u and last_du, the
        // Gauss and contact states, joint totals and table reach, the
        // pending schedule (its rest and at most one halved target per
        // cutback), the waypoints, and the scalars
        // the designer's record of every event (first yield, three per interface)
        let record = model.plan.width() as u64;
        let events = (1 + 3 * ni) * (crate::solve::events::FIXED as u64 + record);
        let words = 2 * nu
            + PointState::packed_len(model.node_dofs().six_components()) as u64 * ng
            + ContactState::packed_len(model.node_dofs().vector_slip()) as u64 * np
            + (2 + Reach::PACKED as u64) * ni
            + 2 * (st.pending.len() as u64 + st.max_cutbacks() as u64 + 1)
            + st.waypoints.len() as u64
            + events
            + 32;
        // the curve's row, the joints' rows, the VTU series' load factor,
        // the pretension sections' row and the designer's record of every
        // increment, and its VTU name
        let joints = (JointMeasures::PACKED + JointMeasures::PACKED_TWIST) as u64 * ni;
        let sections = 2 * model.sections.len() as u64;
        let per_increment = 8 * (10 + joints + 1 + sections + record) + MAX_VTU_NAME as u64 + 1;

        let table = 36 + u64::from(MAX_SECTIONS) * (11 + MAX_SECTION_NAME as u64);
        let restart_bytes = table
            .saturating_add(8 * words + np + body)
            .saturating_add(per_increment.saturating_mul(increments));
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
pub(crate) fn interface_name(k: usize) -> String {
    format!("interface/{k:04}.csv")
}

/// The file the writer gives increment `k`'s VTU output.
pub(crate) fn vtu_name(k: usize) -> String {
    format!("vtu/{k:04}.vtu")
}

/// The increment of a VTU name of exactly the writer's form
/// ([`vtu_name`]); `None` for any other name (`..`, absolute, another
/// folder, leading zeros beyond four digits, …).
pub(crate) fn vtu_increment(name: &str) -> Option<usize> {
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
pub(crate) fn folder_files(
    b: &Bounds,
    increments: usize,
    pvd: &[(f64, String)],
) -> Vec<(String, u64)> {
    let mut files: Vec<(String, u64)> = (1..=increments)
        .map(|k| (interface_name(k), b.csv_bytes))
        .collect();
    files.extend(pvd.iter().map(|p| (p.1.clone(), b.vtu_bytes)));
    files.push((FILE.to_string(), b.restart_bytes));
    files
}

/// Opens the file `rel` of the restart folder `dir` for reading, as
/// [`crate::files::inside::open_inside`] opens a file of a folder not ours
/// (a plain relative name, no link on the way, a regular file of at most
/// `limit` bytes). Returns the file and its size; the error is a message for
/// the restart file's line.
pub(super) fn open_in(dir: &Path, rel: &str, limit: u64) -> Decoded<(std::fs::File, u64)> {
    let what = if rel == FILE {
        "the restart file".to_string()
    } else {
        rel.to_string()
    };
    let rules = crate::files::inside::Folder {
        kind: "restart folder",
        bound: "this case can need",
    };
    crate::files::inside::open_inside(dir, rel, &what, &rules, limit)
}

/// Copies the restart folder's file `rel` (a name from [`folder_files`],
/// at most `limit` bytes) into the same place under `to` (the fresh
/// temporary output folder): the source is opened as [`open_in`] opens it,
/// the destination created new (an existing file or link there is an error,
/// never followed or truncated).
pub(crate) fn copy_in(dir: &Path, rel: &str, limit: u64, to: &Path) -> Result<()> {
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
