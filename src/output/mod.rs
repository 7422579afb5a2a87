//! Results on disk: `summary.json`, `curve.csv`, `interface/<increment>.csv` and
//! a VTU/PVD series. Everything is written into a hidden sibling folder that is
//! renamed into place only when the run succeeds, so a failed run leaves no
//! partial output folder behind.

pub mod vtu;

use crate::error::{Error, Result};
use crate::interface::Status;
use crate::model::Model;
use crate::solve::{Increment, Observer, RunResult, State};
use serde_json::json;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Writes the per-increment files of a run and reports progress.
pub struct Writer {
    final_dir: PathBuf,
    tmp_dir: PathBuf,
    pvd: Vec<(f64, String)>,
    quiet: bool,
    started: Instant,
    planned: usize,
}

impl Writer {
    /// Prepares a fresh temporary folder next to `dir`.
    pub fn new(dir: &Path, quiet: bool, planned: usize) -> Result<Writer> {
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
        Ok(Writer {
            final_dir: dir.to_path_buf(),
            tmp_dir,
            pvd: Vec::new(),
            quiet,
            started: Instant::now(),
            planned,
        })
    }

    fn write(&self, rel: &str, text: &str) -> Result<()> {
        let p = self.tmp_dir.join(rel);
        std::fs::write(&p, text).map_err(|e| Error::io(&p, e))
    }

    /// Writes the summary and the curve, then moves the folder into place.
    pub fn finish(self, model: &Model, result: &RunResult, wall: f64) -> Result<PathBuf> {
        let summary = summary(model, result, wall);
        self.write(
            "summary.json",
            &(serde_json::to_string_pretty(&summary).unwrap_or_default() + "\n"),
        )?;
        self.write("curve.csv", &curve(result))?;
        self.write("results.pvd", &vtu::pvd(&self.pvd))?;
        if self.final_dir.exists() {
            std::fs::remove_dir_all(&self.final_dir).map_err(|e| Error::io(&self.final_dir, e))?;
        }
        std::fs::rename(&self.tmp_dir, &self.final_dir)
            .map_err(|e| Error::io(&self.final_dir, e))?;
        Ok(self.final_dir)
    }

    /// Removes the temporary folder (failed run).
    pub fn abandon(self) {
        let _ = std::fs::remove_dir_all(&self.tmp_dir);
    }
}

impl Observer for Writer {
    fn increment(&mut self, model: &Model, state: &State, inc: &Increment) -> Result<()> {
        self.write(
            &format!("interface/{:04}.csv", inc.increment),
            &interface_csv(model, state),
        )?;
        let every = model.case.output.vtu_every;
        let last = inc.increment >= self.planned;
        if model.case.output.vtu && (inc.increment % every == 0 || last) {
            let f = format!("vtu/{:04}.vtu", inc.increment);
            self.write(&f, &vtu::vtu(model, state))?;
            self.pvd.push((inc.load_factor, f));
        }
        if !self.quiet {
            let el = self.started.elapsed().as_secs_f64();
            let done = inc.increment as f64 / self.planned.max(inc.increment) as f64;
            let eta = el / done * (1.0 - done);
            eprintln!(
                "  increment {:>3}/{}  λ = {:.4}  load {:8.3} kN  p_mean {:7.2} MPa  iterations {:>3}  peeq {:.2e}  {:6.2} s (≈{:.1} s left)",
                inc.increment,
                self.planned.max(inc.increment),
                inc.load_factor,
                inc.measures.total_load_kn,
                inc.measures.mean_pressure,
                inc.iterations,
                inc.measures.max_peeq,
                el,
                eta
            );
        }
        Ok(())
    }

    fn cutback(&mut self, from: f64, to: f64, reason: &str) {
        if !self.quiet {
            eprintln!("  cutback: step {from:.4} → {to:.4} failed ({reason}); halving it");
        }
    }
}

/// One row per interface pair, ordered along the interface. With lumped weights
/// each pair is one integration point and carries its own tangential state.
pub fn interface_csv(model: &Model, state: &State) -> String {
    let mut s = String::from(
        "x_mm,p_n_mpa,u_n_mm,status,p_t_mpa,u_t_mm,u_t_plastic_mm,mu_f,tangential_status\n",
    );
    let mut base = 0;
    for im in &model.interfaces {
        let lumped = im.points.len() == im.pairs.len();
        let mut rows: Vec<usize> = (0..im.pairs.len()).collect();
        rows.sort_by(|&a, &b| im.pairs[a].x[0].total_cmp(&im.pairs[b].x[0]));
        for i in rows {
            let pr = &im.pairs[i];
            let un = im.pair_approach(pr, &state.u);
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
            let _ = writeln!(
                s,
                "{},{:.9e},{:.9e},{},{:.9e},{:.9e},{:.9e},{:.6},{}",
                pr.x[0],
                p,
                un,
                st.name(),
                c.p_t,
                c.u_t,
                c.slip.u_p,
                c.mu_f,
                st.tangential_name()
            );
        }
        base += im.points.len();
    }
    s
}

pub fn curve(result: &RunResult) -> String {
    let fy = result.first_yield.as_ref().map(|f| f.total_load_kn);
    let mut s = String::from(
        "increment,load_factor,total_load_kn,mean_pressure_mpa,load_ratio,center_displacement_mm,max_peeq,iterations\n",
    );
    for inc in &result.increments {
        let m = &inc.measures;
        let ratio = fy.map_or(f64::NAN, |f| m.total_load_kn / f);
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

pub fn summary(model: &Model, r: &RunResult, wall: f64) -> serde_json::Value {
    let last = r.increments.last().map(|i| i.measures).unwrap_or_default();
    let fy = r.first_yield.as_ref().map(|f| {
        json!({
            "load_factor": f.load_factor,
            "mean_pressure_mpa": f.mean_pressure,
            "total_load_kn": f.total_load_kn,
            "x_mm": f.x,
            "depth_mm": f.depth,
            "body": f.body,
            "element": f.element,
        })
    });
    json!({
        "schema": 1,
        "asperity_version": env!("CARGO_PKG_VERSION"),
        "step_control": match model.case.solver.step_mode() {
            crate::case::StepControl::Fixed => "fixed",
            crate::case::StepControl::Auto => "auto",
        },
        "case": model.name,
        "plane": format!("{:?}", model.plane).to_lowercase(),
        "method": model.case.solver.method.name(),
        "backend": r.backend,
        "ranks": r.ranks,
        "backend_stats": r.backend_stats.iter().cloned().collect::<std::collections::BTreeMap<_, _>>(),
        "dofs": model.mesh.num_dofs(),
        "equations": model.dofs.n_eq,
        "elements": model.mesh.elements.len(),
        "interface_pairs": model.interfaces.iter().map(|i| i.pairs.len()).sum::<usize>(),
        "increments": r.increments.len(),
        "cutbacks": r.cutbacks,
        "newton_iterations": r.stats.iterations,
        "factorizations": r.stats.factorizations,
        "wall_seconds": wall,
        "peak_memory_mb": r.peak_memory_mb,
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
