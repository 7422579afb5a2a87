//! Results on disk: `summary.json`, `curve.csv`, `interface/<increment>.csv`,
//! the joint outputs (`joints.csv`, `cycles.csv`, the hysteresis figure:
//! `joints`; `damping.csv`, `backbone.csv`, the damping figure: [`damping`]), the designer's outputs (`reactions.csv`, `probes.csv`,
//! `peaks.csv`, `contact.csv` and the events: `plan`, [`events`]), a 3D run's
//! contact maps ([`contact_map`]) and a
//! VTU/PVD series. Everything is written into a hidden sibling folder that is
//! renamed into place only when the run succeeds, so a failed run leaves no
//! partial output folder behind. The per-increment files are encoded and
//! written by a thread of their own, in order (`background`).

mod applied;
mod background;
pub mod contact_map;
pub mod damping;
pub mod events;
pub mod joints_csv;
pub mod json;
pub mod peaks;
pub mod probes;
pub mod ratings_csv;
pub mod reactions;
pub mod singular;
pub mod vtu;

use crate::error::{Error, Result};
use crate::model::interface::extrapolation::table_uses;
use crate::model::Model;
use crate::physics::contact::Status;
use crate::progress::Log;
use crate::solve::{Checkpoint, Increment, Observer, RunResult, State};
use serde_json::json;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Writes the per-increment files of a run and reports progress.
pub(crate) struct Writer {
    final_dir: PathBuf,
    tmp_dir: PathBuf,
    pvd: Vec<(f64, String)>,
    log: Log,
    planned: usize,
    /// The load factor the history ends at (its increment always gets a VTU).
    pub(crate) final_load_factor: f64,
    /// The temporary folder was moved into place (or must not be removed).
    done: bool,
    /// Fingerprint of the model for restart.bin (computed once).
    fingerprint: Option<u64>,
    /// The thread that writes the per-increment files.
    background: background::Background,
    /// The unchanging part of the VTU documents (made at the first one).
    layout: Option<std::sync::Arc<vtu::Layout>>,
    /// The increment of the last VTU file queued (0: none this run).
    last_vtu: usize,
    /// The error estimate of the last increment that got one (the VTU
    /// increments and the last one; [`crate::measure::estimate`]), with that
    /// increment and its load factor: summary.json's `estimate`.
    estimate: Option<(usize, f64, crate::measure::estimate::Estimate)>,
    /// A 3D run's contact maps of the last converged state (made at the
    /// history's last increment or a stopped run's last state, drawn at the end).
    maps: Vec<contact_map::ContactMap>,
}

/// Where a resumed run takes its earlier increments from.
pub(crate) struct Resume<'a> {
    /// The output folder of the stopped run (holds restart.bin).
    pub dir: &'a Path,
    /// The files to copy from it, each with its size bound
    /// ([`crate::files::restart::folder_files`]: names checked by
    /// [`crate::files::restart::read`]).
    pub files: Vec<(String, u64)>,
    /// Its VTU series so far.
    pub pvd: Vec<(f64, String)>,
}

impl Writer {
    /// Prepares a fresh temporary folder `.NAME.partial-PID` next to `dir`;
    /// with `resume`, copies the earlier increments' files into it.
    pub fn new(dir: &Path, log: Log, planned: usize, resume: Option<Resume>) -> Result<Writer> {
        let parent = dir
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        let name = dir
            .file_name()
            .map_or("out".into(), |n| n.to_string_lossy().into_owned());
        let tmp_dir = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if tmp_dir.exists() {
            std::fs::remove_dir_all(&tmp_dir).map_err(|e| Error::io(&tmp_dir, e))?;
        }
        for d in [
            tmp_dir.clone(),
            tmp_dir.join("interface"),
            tmp_dir.join("vtu"),
        ] {
            std::fs::create_dir_all(&d).map_err(|e| Error::io(&d, e))?;
        }
        let mut w = Writer {
            final_dir: dir.to_path_buf(),
            tmp_dir,
            pvd: Vec::new(),
            log,
            planned,
            final_load_factor: f64::NAN,
            done: false,
            fingerprint: None,
            background: background::Background::start()?,
            layout: None,
            last_vtu: 0,
            estimate: None,
            maps: Vec::new(),
        };
        if let Some(r) = resume {
            // restart.bin is kept as is if no further increment converges;
            // each file is opened again as the restart folder's rules say
            // (no link, a regular file, bounded) and created new here
            for (f, limit) in &r.files {
                crate::files::restart::copy_in(r.dir, f, *limit, &w.tmp_dir)?;
            }
            w.pvd = r.pvd;
        }
        Ok(w)
    }

    fn write(&self, rel: &str, text: &str) -> Result<()> {
        let p = self.tmp_dir.join(rel);
        std::fs::write(&p, text).map_err(|e| Error::io(&p, e))
    }

    /// The error estimate of the last increment that got one.
    pub(crate) fn last_estimate(&self) -> Option<&crate::measure::estimate::Estimate> {
        self.estimate.as_ref().map(|e| &e.2)
    }

    /// Writes the summary and the curve, then moves the folder into place:
    /// `.NAME.partial-PID` replaces NAME in one rename (an existing NAME is
    /// swapped out atomically where the system allows it, then removed).
    pub fn finish(mut self, model: &Model, result: &RunResult, wall: f64) -> Result<PathBuf> {
        // every increment's files are on disk before the summary
        self.background.drain()?;
        let mut summary = summary(model, result, wall);
        if let Some((k, t, est)) = &self.estimate {
            let mut e = est.summary(model);
            e["increment"] = json!(k);
            e["load_factor"] = json!(t);
            summary["estimate"] = e;
        }
        self.write(
            "summary.json",
            &(serde_json::to_string_pretty(&summary).unwrap_or_default() + "\n"),
        )?;
        self.write("curve.csv", &curve(result))?;
        let cycles = result.cycles(model);
        self.write("joints.csv", &joints_csv::joints_csv(model, result))?;
        self.write("cycles.csv", &joints_csv::cycles_csv(model, &cycles))?;
        joints_csv::hysteresis(model, result, &cycles, &self.tmp_dir)?;
        joints_csv::torsion(model, result, &cycles, &self.tmp_dir)?;
        let sweeps = crate::measure::sweep::sweeps(&cycles);
        self.write(
            "damping.csv",
            &damping::damping_csv(model, &cycles, &sweeps),
        )?;
        damping::figure(model, &cycles, &sweeps, &self.tmp_dir)?;
        contact_map::save_maps(&self.maps, &self.tmp_dir)?;
        self.write("backbone.csv", &damping::backbone_csv(model, result))?;
        if !model.sections.is_empty() {
            self.write("pretension.csv", &pretension_csv(model, result))?;
        }
        let plan = &model.plan;
        let l = &plan.layout;
        self.write(
            "reactions.csv",
            &reactions::csv(&plan.reactions, result, |v| plan.part(v, &l.reactions)),
        )?;
        self.write(
            "probes.csv",
            &probes::csv(&plan.probes, &model.mesh, result, |v| {
                plan.part(v, &l.probes)
            }),
        )?;
        self.write(
            "peaks.csv",
            &peaks::bodies_csv(model, result, |v| plan.part(v, &l.bodies)),
        )?;
        self.write(
            "contact.csv",
            &peaks::contact_csv(model, result, |v| plan.part(v, &l.interfaces)),
        )?;
        self.write("loads.csv", &applied::csv(model, result))?;
        if !model.ratings.is_empty() {
            self.write("ratings.csv", &ratings_csv::csv(model, result)?)?;
        }
        self.write("results.pvd", &vtu::pvd(&self.pvd))?;
        replace_dir(&self.tmp_dir, &self.final_dir)?;
        self.done = true;
        Ok(self.final_dir.clone())
    }

    /// Removes the temporary folder (failed run).
    pub(crate) fn abandon(self) {}

    /// Whether increment `inc` gets a VTU file: every `vtu_every`-th, and
    /// always the first, the last of the history and every increment that
    /// ends at a breakpoint of a load history (where a cycle turns).
    fn vtu_due(&self, model: &Model, inc: &Increment) -> bool {
        inc.increment == 1
            || inc.increment % model.output.vtu_every == 0
            || self.is_last(inc)
            || model.breakpoints().contains(&inc.load_factor)
    }

    /// Whether increment `inc` ends the planned history.
    fn is_last(&self, inc: &Increment) -> bool {
        (self.planned > 0 && inc.increment >= self.planned)
            || (inc.load_factor - self.final_load_factor).abs() <= 1e-12
    }

    /// The error estimate of increment `inc` (computed once per increment).
    fn estimate_of(&mut self, model: &Model, state: &State, inc: &Increment) {
        if self.estimate.as_ref().is_none_or(|e| e.0 != inc.increment) {
            let est = crate::measure::estimate::estimate(model, state);
            self.estimate = Some((inc.increment, inc.load_factor, est));
        }
    }

    /// Whether the VTU series already lists increment `k` (a resumed run's
    /// last one, copied in).
    fn pvd_has(&self, k: usize) -> bool {
        let name = crate::files::restart::vtu_name(k);
        self.pvd.iter().any(|(_, f)| *f == name)
    }

    fn queue_text(&mut self, rel: String, text: String) -> Result<()> {
        self.background.send(background::Job::Text {
            path: self.tmp_dir.join(rel),
            text,
        })
    }

    /// Takes the state's arrays ([`vtu::Frame`], with the increment's error
    /// estimate) and queues its VTU file.
    fn queue_vtu(&mut self, model: &Model, state: &State, inc: &Increment) -> Result<()> {
        self.estimate_of(model, state, inc);
        let est = self.estimate.as_ref().map(|e| &e.2);
        let frame = Box::new(vtu::Frame::with(model, state, est));
        let layout = self
            .layout
            .get_or_insert_with(|| background::layout(model))
            .clone();
        let f = crate::files::restart::vtu_name(inc.increment);
        self.background.send(background::Job::Vtu {
            path: self.tmp_dir.join(&f),
            layout,
            frame,
        })?;
        self.pvd.push((inc.load_factor, f));
        self.last_vtu = inc.increment;
        Ok(())
    }
}

impl Drop for Writer {
    fn drop(&mut self) {
        // nothing is left writing into the folder (its errors no longer matter)
        let _ = self.background.drain();
        if !self.done {
            let _ = std::fs::remove_dir_all(&self.tmp_dir);
        }
    }
}

/// Moves folder `from` to `to`, replacing `to` if it exists. On Linux the two
/// are exchanged with one `renameat2(RENAME_EXCHANGE)`, so `to` is at every
/// moment either the old or the new complete folder; elsewhere the old folder
/// is first renamed aside (a crash in between leaves it as `.NAME.old-PID`).
#[allow(unsafe_code)] // renameat2(RENAME_EXCHANGE), see the SAFETY note
pub(crate) fn replace_dir(from: &Path, to: &Path) -> Result<()> {
    if !to.exists() {
        return std::fs::rename(from, to).map_err(|e| Error::io(to, e));
    }
    #[cfg(target_os = "linux")]
    {
        use std::ffi::CString;
        use std::os::unix::ffi::OsStrExt;
        let a = CString::new(from.as_os_str().as_bytes()).ok();
        let b = CString::new(to.as_os_str().as_bytes()).ok();
        if let (Some(a), Some(b)) = (a, b) {
            // SAFETY: two valid NUL-terminated paths; no memory is shared.
            let rc = unsafe {
                libc::renameat2(
                    libc::AT_FDCWD,
                    a.as_ptr(),
                    libc::AT_FDCWD,
                    b.as_ptr(),
                    libc::RENAME_EXCHANGE,
                )
            };
            if rc == 0 {
                // `from` now holds the old folder
                let _ = std::fs::remove_dir_all(from);
                return Ok(());
            }
        }
    }
    let name = to
        .file_name()
        .map_or("out".into(), |n| n.to_string_lossy().into_owned());
    let old = to
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .join(format!(".{name}.old-{}", std::process::id()));
    std::fs::rename(to, &old).map_err(|e| Error::io(to, e))?;
    if let Err(e) = std::fs::rename(from, to) {
        let _ = std::fs::rename(&old, to);
        return Err(Error::io(to, e));
    }
    let _ = std::fs::remove_dir_all(&old);
    Ok(())
}

impl Observer for Writer {
    fn increment(&mut self, model: &Model, state: &State, inc: &Increment) -> Result<()> {
        // a file of an earlier increment that could not be written ends the run here
        self.background.check()?;
        // the maps of the state the run ends on (a stopped run's come
        // through last_state)
        if self.is_last(inc) {
            self.maps = contact_map::contact_maps(model, state);
        }
        self.queue_text(
            crate::files::restart::interface_name(inc.increment),
            interface_csv(model, state),
        )?;
        if model.output.vtu && self.vtu_due(model, inc) {
            self.queue_vtu(model, state, inc)?;
        } else if self.is_last(inc) {
            self.estimate_of(model, state, inc);
        }
        let el = self.log.elapsed();
        let eta = self.log.eta(inc.load_factor);
        let planned = (self.planned > 0).then(|| self.planned.max(inc.increment));
        self.log.progress(
            "increment",
            json!({
                "increment": inc.increment,
                "planned": planned,
                "load_factor": inc.load_factor,
                "total_load_kn": inc.measures.total_load_kn,
                "mean_pressure_mpa": inc.measures.mean_pressure,
                "iterations": inc.iterations,
                "cutbacks": inc.cutbacks,
                "max_peeq": inc.measures.max_peeq,
                "elapsed_s": crate::progress::round3(el),
                "eta_s": eta.map(crate::progress::round3),
            }),
            || {
                // the interface's force and mean pressure, where there is one
                let contact = if model.interfaces.is_empty() {
                    String::new()
                } else {
                    format!(
                        "  load {:8.3} kN  p_mean {:7.2} MPa",
                        inc.measures.total_load_kn, inc.measures.mean_pressure
                    )
                };
                format!(
                    "  increment {:>3}/{}  λ = {:.4}{contact}  iterations {:>3}  peeq {:.2e}  {:6.2} s (≈{} left)",
                    inc.increment,
                    planned.map_or("auto".to_string(), |p| p.to_string()),
                    inc.load_factor,
                    inc.iterations,
                    inc.measures.max_peeq,
                    el,
                    eta.map_or("?".into(), |t| format!("{t:.1} s"))
                )
            },
        );
        Ok(())
    }

    fn cutback(&mut self, from: f64, to: f64, next: f64, reason: &str) {
        self.log.progress(
            "cutback",
            json!({"from": from, "to": to, "next_to": next, "reason": reason}),
            || format!("  cutback: step {from:.4} → {to:.4} not taken ({reason}); next {from:.4} → {next:.4}"),
        );
    }

    fn checkpoint(&mut self, model: &Model, ck: &Checkpoint) -> Result<()> {
        let fingerprint = *self
            .fingerprint
            .get_or_insert_with(|| crate::files::restart::fingerprint(model));
        // queued after the increment's own files: restart.bin is replaced
        // only once everything it lists is written
        self.background.send(background::Job::Checkpoint {
            tmp: self.tmp_dir.join(".restart.bin.tmp"),
            path: self.tmp_dir.join(crate::files::restart::FILE),
            fingerprint,
            ck: Box::new(ck.clone()),
            pvd: self.pvd.clone(),
        })
    }

    fn last_state(&mut self, model: &Model, state: &State, inc: &Increment) -> Result<()> {
        if model.output.vtu && self.last_vtu != inc.increment && !self.pvd_has(inc.increment) {
            self.queue_vtu(model, state, inc)?;
        }
        self.estimate_of(model, state, inc);
        self.maps = contact_map::contact_maps(model, state);
        Ok(())
    }

    fn flush(&mut self) -> Result<()> {
        self.background.drain()
    }
}

/// The columns of `interface/NNNN.csv` (without the line's end).
pub const INTERFACE_HEADER: &str = "x_mm,p_n_mpa,u_n_mm,status,p_t_mpa,u_t_mm,u_t_plastic_mm,mu_f,tangential_status,y_mm,s_mm,interface";

/// The columns a twisting model's `interface/NNNN.csv` adds, and the line's end.
pub const INTERFACE_TWIST_COLUMNS: &str = ",p_t_theta_mpa,u_t_theta_mm,u_t_theta_plastic_mm\n";

/// The columns a 3D model's `interface/NNNN.csv` adds, and the line's end:
/// the pair's z, and the shear, slip and plastic slip along t₂.
pub const INTERFACE_SPACE_COLUMNS: &str = ",z_mm,p_t2_mpa,u_t2_mm,u_t2_plastic_mm\n";

/// The header of `curve.csv`.
pub const CURVE_HEADER: &str = "increment,load_factor,total_load_kn,mean_pressure_mpa,load_ratio,center_displacement_mm,max_peeq,iterations\n";

/// One row per interface pair, interface by interface, each ordered along
/// the interface by its arc length s (from its first pair, in the walk
/// direction: increasing x on a horizontal interface, increasing y on a
/// vertical one). With lumped weights each pair is one integration point and
/// carries its own tangential state (internal convention,
/// [`crate::measure::joint`]). A twisting model's rows end with the
/// circumferential shear, slip and plastic slip (p_Tθ, u_Tθ, u_Tθ^p), and
/// its u_t_plastic_mm is the meridional component of the vector plastic slip.
pub fn interface_csv(model: &Model, state: &State) -> String {
    let twist = model.node_dofs().twist();
    let space = model.node_dofs().solid();
    let mut s = String::from(INTERFACE_HEADER);
    s += match (twist, space) {
        (true, _) => INTERFACE_TWIST_COLUMNS,
        (_, true) => INTERFACE_SPACE_COLUMNS,
        _ => "\n",
    };
    let mut base = 0;
    for (im, iface) in model.interfaces.iter().zip(&model.mesh.interfaces) {
        let lumped = im.points.len() == im.pairs.len();
        let arc = crate::model::interface::arcs::arc_lengths(&model.mesh, iface, im);
        let name = joints_csv::csv_field(&im.name);
        let mut rows: Vec<usize> = (0..im.pairs.len()).collect();
        rows.sort_by(|&a, &b| arc[a].total_cmp(&arc[b]));
        for i in rows {
            let pr = &im.pairs[i];
            let un = im.pair_approach_at(pr, &state.u, im.gap_at(state.time));
            let p = im.law.pressure(un).0;
            let (c, st) = if lumped && im.tangential.is_some() {
                (state.contact[base + i], state.status[base + i])
            } else {
                let st = if un > 0.0 {
                    Status::Closed
                } else {
                    Status::Open
                };
                (Default::default(), st)
            };
            let u_p = if twist || space {
                c.slip2.u_p[0]
            } else {
                c.slip.u_p
            };
            let _ = write!(
                s,
                "{},{:.9e},{:.9e},{},{:.9e},{:.9e},{:.9e},{:.6},{},{},{:.9e},{name}",
                pr.x[0],
                p,
                un,
                st.name(),
                c.p_t,
                c.u_t,
                u_p,
                c.mu_f,
                st.tangential_name(),
                pr.x[1],
                arc[i],
            );
            if twist || space {
                // u_Tθ (u_T2) from the displacements where the pair carries no state
                let u_h = if lumped && im.tangential.is_some() {
                    c.u_h
                } else {
                    im.pair_second_slip(pr, &state.u)
                };
                if space {
                    let _ = write!(s, ",{}", pr.x[2]);
                }
                let _ = write!(s, ",{:.9e},{:.9e},{:.9e}", c.p_h, u_h, c.slip2.u_p[1]);
            }
            s.push('\n');
        }
        base += im.points.len();
    }
    s
}

pub fn curve(result: &RunResult) -> String {
    let fy = result.first_yield.as_ref();
    let mut s = String::from(CURVE_HEADER);
    for inc in &result.increments {
        let m = &inc.measures;
        // docs/output.md: 0 when the run never yields (no first-yield load);
        // without an interface force (0 at first yield) the load factors'
        // ratio
        let ratio = fy.map_or(0.0, |f| {
            if f.total_load_kn != 0.0 {
                m.total_load_kn / f.total_load_kn
            } else {
                inc.load_factor / f.load_factor
            }
        });
        let _ = writeln!(
            s,
            "{},{:.9},{:.9e},{:.9e},{:.9},{:.9e},{:.9e},{}",
            inc.increment,
            inc.load_factor,
            m.total_load_kn,
            m.mean_pressure,
            ratio,
            m.center_displacement,
            m.max_peeq,
            inc.iterations
        );
    }
    s
}

/// The run's warnings, one line each (without `warning: `): every tabulated
/// law evaluated beyond `crate::physics::contact::table::EXTRAPOLATION_LIMIT`
/// times its last row ([`crate::model::interface::extrapolation`]). The driver
/// prints them on stderr; summary.json holds them as `warnings`.
pub fn warnings(model: &Model, r: &RunResult) -> Vec<String> {
    let place = model.source.display().to_string();
    let mut w: Vec<String> = table_uses(&model.interfaces, &r.table_reach)
        .iter()
        .filter(|t| t.far())
        .map(|t| t.warning(&place, "the run evaluated it up to"))
        .collect();
    w.extend(coarse_cycles(model, r, &place));
    w
}

/// Increments a closed cycle needs for its energies: with one increment a
/// leg the trapezoid sums see the shear at the two turning points only
/// (equal and opposite: D = 0 whatever the loop).
const CYCLE_INCREMENTS: usize = 4;

/// One warning per interface with a closed cycle of fewer than
/// [`CYCLE_INCREMENTS`] increments.
fn coarse_cycles(model: &Model, r: &RunResult, place: &str) -> Vec<String> {
    let cycles = r.cycles(model);
    model
        .interfaces
        .iter()
        .zip(&cycles)
        .filter_map(|(im, list)| {
            let coarse: Vec<usize> = list
                .iter()
                .enumerate()
                .filter(|(_, c)| c.end_increment - c.start_increment < CYCLE_INCREMENTS)
                .map(|(k, _)| k + 1)
                .collect();
            let first = *coarse.first()?;
            let c = &list[first - 1];
            // the key that sets the step under the run's step control, or
            // the option that set it for this run
            let o = &model.overrides;
            let fix = match model.solver.step_mode() {
                crate::input::case::StepControl::Auto => {
                    "set [solver] max_increment to a quarter of a leg or less".to_string()
                }
                crate::input::case::StepControl::Fixed => match o.option("[solver] increments") {
                    Some(given) => format!("raise {given} to 4 or more per unit of pseudo-time"),
                    None => "set [solver] increments to 4 or more per unit of pseudo-time".to_string(),
                },
            };
            Some(format!(
                "{place}: interface {:?}: {} closed cycle(s) of fewer than {CYCLE_INCREMENTS} increments (cycle {first}: {} increments, t = {} … {}): their dissipation and loss factor are trapezoid sums over too few steps (0 with one step a leg); {fix}",
                im.name,
                coarse.len(),
                c.end_increment - c.start_increment,
                c.start_time,
                c.end_time
            ))
        })
        .collect()
}

/// summary.json: the run's numbers (`run_summary`), then its joints,
/// damping, pretension, events, the places at singular points
/// (`singular`), tables, warnings and stabilization.
pub fn summary(model: &Model, r: &RunResult, wall: f64) -> serde_json::Value {
    let mut s = run_summary(model, r, wall);
    if model.section.axisymmetric {
        s["forces"] = json!(
            "full revolution: forces, areas and kN are for the whole body of revolution (2π r)"
        );
    }
    if let Some(c) = &model.cyclic {
        s["forces"] = json!(format!(
            "cyclic sector, 1 of {}: forces, moments and loads are the sector's as meshed, but the reactions' fy_part_n and my_part_nmm, the whole part's ({} × the sector's fy_n and my_nmm; the sector's fx_n and fz_n sum to zero over the part)",
            c.sectors, c.sectors
        ));
        s["cyclic"] = json!({
            "sectors": c.sectors,
            "angle_deg": c.degrees(),
            "faces": c.faces,
            "node_pairs": c.pairs.len(),
            "axis_nodes": c.axis.len(),
        });
    }
    let cycles = r.cycles(model);
    s["joints"] = joints_csv::summary(model, r, &cycles);
    s["damping"] = damping::summary(model, &crate::measure::sweep::sweeps(&cycles));
    if !model.sections.is_empty() {
        s["pretension"] = pretension_summary(model, r);
    }
    let plan = &model.plan;
    s["applied_loads"] =
        applied::summary(model, r, |v| plan.part(v, &plan.layout.reactions).to_vec());
    events::summary(model, r, &mut s);
    let flags = singular::flags(model, r, &s["peaks"]);
    if let Some(v) = singular::summary(model, &flags) {
        s["singular"] = v;
    }
    if !model.ratings.is_empty() {
        s["ratings"] = match crate::verdict::rate(model, r) {
            Ok(ratings) => serde_json::to_value(ratings).unwrap_or_default(),
            Err(e) => json!([{"error": e.to_string()}]),
        };
    }
    // only cases with a tabulated law (the others write what they always did)
    let uses = table_uses(&model.interfaces, &r.table_reach);
    if !uses.is_empty() {
        s["tables"] = tables_summary(&uses);
    }
    let w = warnings(model, r);
    if !w.is_empty() {
        s["warnings"] = json!(w);
    }
    // only runs where some step needed it (a case without one writes what it always did)
    if let Some(st) = &r.stabilization {
        s["stabilization"] = stabilization_summary(st);
    }
    s
}

/// summary.json's numbers of the run: what was solved and how (backend,
/// counts, time, memory), first yield and the final state.
fn run_summary(model: &Model, r: &RunResult, wall: f64) -> serde_json::Value {
    let last = r.increments.last().map(|i| i.measures).unwrap_or_default();
    // the interface's force and pressure: none without an interface
    let contact = |v: f64| {
        if model.interfaces.is_empty() {
            json!(null)
        } else {
            json!(v)
        }
    };
    let fy = r.first_yield.as_ref().map(|f| {
        json!({
            "load_factor": f.load_factor,
            "mean_pressure_mpa": contact(f.mean_pressure),
            "total_load_kn": contact(f.total_load_kn),
            "x_mm": f.x,
            "depth_mm": f.depth,
            "body": f.body,
            "element": f.element,
        })
    });
    // a 3D model's first yield: its place in space
    let fy = fy.map(|mut o| {
        if let (3, Some(f)) = (model.mesh.dim(), &r.first_yield) {
            o["y_mm"] = json!(model.surface_y - f.depth);
            o["z_mm"] = json!(f.z);
        }
        o
    });
    json!({
        "schema": 1,
        "asperity_version": env!("CARGO_PKG_VERSION"),
        "step_control": match model.solver.step_mode() {
            crate::input::case::StepControl::Fixed => "fixed",
            crate::input::case::StepControl::Auto => "auto",
        },
        "case": model.name,
        "description": model.description.as_deref().map(str::trim),
        "case_fingerprint": format!("fnv1a64:{:016x}", crate::files::restart::fnv1a(model.case_key().as_bytes())),
        "complete": r.stopped.is_none(),
        "stopped_by": r.stopped.map(|s| s.name()),
        // what the case calls it (serde's name: `3d`, not `solid`)
        "plane": serde_json::to_value(model.plane).unwrap_or_default(),
        "method": model.solver.method.name(),
        "backend": r.backend,
        "ranks": r.ranks,
        "threads": r.threads,
        "nonlinear_solver": r.nonlinear_solver,
        "linear_solver": r.linear_solver,
        "backend_stats": r.backend_stats.iter().cloned().collect::<std::collections::BTreeMap<_, _>>(),
        "dofs": model.mesh.num_dofs(),
        "equations": model.dofs.n_eq,
        "elements": model.mesh.elements.len(),
        "interface_pairs": model.interfaces.iter().map(|i| i.pairs.len()).sum::<usize>(),
        "increments": r.increments.len(),
        "cutbacks": r.cutbacks,
        "newton_iterations": r.stats.run_iterations(),
        "event_search_iterations": r.stats.event_iterations,
        "factorizations": r.stats.factorizations,
        "predictor_restarts": r.stats.predictor_restarts,
        "interface_loops": r.stats.interface.loops,
        "interface_iterations": r.stats.interface.iterations,
        "interface_fallbacks": r.stats.interface.fallbacks,
        "wall_seconds": wall,
        "peak_memory_mb": r.peak_memory_mb,
        "memory_stages_mb": r.stats.memory_mb.iter().map(|&(k, v)| (k, v)).collect::<std::collections::BTreeMap<_, _>>(),
        "assembly_seconds": r.stats.assembly_seconds,
        "solve_seconds": r.stats.solve_seconds,
        "first_yield": fy,
        "final": {
            "load_factor": r.increments.last().map_or(0.0, |i| i.load_factor),
            "mean_pressure_mpa": last.mean_pressure,
            "total_load_kn": last.total_load_kn,
            "center_displacement_mm": last.center_displacement,
            "max_peeq": last.max_peeq,
        },
    })
}

/// summary.json's `tables`: how far each tabulated law was evaluated.
fn tables_summary(uses: &[crate::model::interface::extrapolation::TableUse]) -> serde_json::Value {
    uses.iter()
        .map(|t| {
            json!({
                "interface": t.interface,
                "key": t.key,
                "argument": t.argument,
                "unit": t.unit,
                "last_row": t.last_row,
                "largest": t.largest,
                "ratio": t.ratio(),
                "beyond_limit": t.far(),
            })
        })
        .collect()
}

/// summary.json's `stabilization`: the steps it held or released and its
/// energy against the limit.
fn stabilization_summary(st: &crate::solve::stabilization::Report) -> serde_json::Value {
    json!({
        "steps_released": st.released,
        "steps_stabilized": st.stabilized,
        "dissipated_energy_nmm": st.dissipated,
        "internal_energy_nmm": st.internal,
        "energy_ratio": if st.internal > 0.0 { st.dissipated / st.internal } else { 0.0 },
        "energy_limit": st.limit,
    })
}

/// `pretension.csv`: every increment's section force (N, tension positive;
/// the whole ring in axisymmetry) and shortening (mm) of every pretension
/// section (docs/output.md).
fn pretension_csv(model: &Model, r: &RunResult) -> String {
    let mut out = String::from("increment,load_factor");
    for s in &model.sections {
        let _ = write!(out, ",{0}_force_n,{0}_shortening_mm", s.name);
    }
    out.push('\n');
    for inc in &r.increments {
        let _ = write!(out, "{},{:.10e}", inc.increment, inc.load_factor);
        for k in 0..model.sections.len() {
            let [f, s] = inc.sections.get(k).copied().unwrap_or([f64::NAN; 2]);
            let _ = write!(out, ",{f:.10e},{s:.10e}");
        }
        out.push('\n');
    }
    out
}

/// summary.json's `pretension`: each section's control, lock time and its
/// force and shortening at the end of the run, at the lock and their
/// extremes.
fn pretension_summary(model: &Model, r: &RunResult) -> serde_json::Value {
    model
        .sections
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let at = |inc: &Increment| inc.sections.get(k).copied().unwrap_or([f64::NAN; 2]);
            let last = r.increments.last().map_or([f64::NAN; 2], at);
            let locked = r
                .increments
                .iter()
                .rev()
                .find(|i| i.load_factor <= s.lock_after)
                .filter(|_| s.lock_after.is_finite())
                .map(at);
            let forces = r.increments.iter().map(|i| at(i)[0]);
            let (lo, hi) = forces.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), f| {
                (a.min(f), b.max(f))
            });
            json!({
                "name": s.name,
                "body": model.mesh.bodies[s.body],
                "cut": format!("{} = {}", ["x", "y", "z"][s.axis], s.at),
                "control": s.control,
                "locked_after": s.lock_after.is_finite().then_some(s.lock_after),
                "force_n": last[0],
                "shortening_mm": last[1],
                "force_at_lock_n": locked.map(|v| v[0]),
                "shortening_at_lock_mm": locked.map(|v| v[1]),
                "force_min_n": lo,
                "force_max_n": hi,
            })
        })
        .collect()
}
