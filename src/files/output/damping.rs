//! What a damping study reads from a run: per interface the closed load
//! cycles' force amplitude F_a, dissipation D, stored energy U and loss factor
//! η = D / (2π U) ([`Cycle::loss_factor`]) in `damping.csv`, the power law
//! D = C F_a^q fitted to them (summary.json `damping`, the figure
//! `damping.svg`/`.png`), and the joint's first-loading curve, its backbone,
//! in `backbone.csv`.
//!
//! The sweep itself (the blocks, the steady cycles, the fit) is
//! [`crate::measure::sweep`]; here, its files.

use super::joints_csv::{csv_field, opt};
use crate::error::Result;
use crate::measure::joint::{Cycle, JointMeasures};
use crate::measure::sweep::{dissipating, Sweep};
use crate::model::Model;
use crate::solve::RunResult;
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A first reversal of F_T is a drop of |F_T| by more than this fraction of
/// the run's largest |F_T| from one increment to the next.
pub(crate) const REVERSAL: f64 = 1e-6;

pub const DAMPING_HEADER: &str = "interface,cycle,block,first_in_block,last_in_block,in_fit,start_time,end_time,force_amplitude_n,slip_amplitude_mm,dissipation_nmm,stored_energy_nmm,loss_factor\n";

/// The columns a twisting model's `damping.csv` adds at the end of a row:
/// the torque-twist loop's amplitudes, stored energy and loss factor.
pub(crate) const DAMPING_TWIST_COLUMNS: &str =
    ",torque_amplitude_nmm,twist_amplitude_rad,torsional_stored_energy_nmm,torsional_loss_factor";

/// `damping.csv`: one row per closed load cycle and interface (the header
/// alone when there is none), the numbers of `cycles.csv` with the sweep's
/// blocks; an empty loss factor where the stored energy is not positive.
/// A twisting model's rows end with [`DAMPING_TWIST_COLUMNS`]
/// ([`Cycle::torsional_loss_factor`]).
pub(crate) fn damping_csv(model: &Model, cycles: &[Vec<Cycle>], sweeps: &[Sweep]) -> String {
    let twist = model.node_dofs().twist();
    let mut s = String::from(DAMPING_HEADER);
    if twist {
        s.pop();
        s += DAMPING_TWIST_COLUMNS;
        s.push('\n');
    }
    for ((im, list), sw) in model.interfaces.iter().zip(cycles).zip(sweeps) {
        for (k, (c, r)) in list.iter().zip(&sw.rows).enumerate() {
            let _ = write!(
                s,
                "{},{},{},{},{},{},{:.9},{:.9},{:.9e},{:.9e},{:.9e},{:.9e},{}",
                csv_field(&im.name),
                k + 1,
                r.block,
                r.first_in_block,
                r.last_in_block,
                r.in_fit,
                c.start_time,
                c.end_time,
                c.force_amplitude(),
                c.slip_amplitude(),
                c.dissipation,
                c.stored_energy(),
                opt(c.loss_factor()),
            );
            if twist {
                let _ = write!(
                    s,
                    ",{:.9e},{:.9e},{:.9e},{}",
                    c.torque_amplitude(),
                    c.twist_amplitude(),
                    c.torsional_stored_energy(),
                    opt(c.torsional_loss_factor()),
                );
            }
            s.push('\n');
        }
    }
    s
}

/// One interface's fit as a `summary.json` object: nulls without a fit.
pub fn fit_json(interface: &str, sweep: &Sweep) -> Value {
    let f = sweep.fit;
    json!({
        "interface": interface,
        "cycles": sweep.rows.len(),
        "blocks": sweep.rows.last().map_or(0, |r| r.block),
        "cycles_used": f.map_or(0, |f| f.points),
        "exponent": f.map(|f| f.exponent),
        "coefficient": f.map(|f| f.coefficient),
        "r_squared": f.map(|f| f.r_squared),
    })
}

/// The `damping` entry of `summary.json`: one object per interface.
pub fn summary(model: &Model, sweeps: &[Sweep]) -> Value {
    Value::Array(
        model
            .interfaces
            .iter()
            .zip(sweeps)
            .map(|(im, s)| fit_json(&im.name, s))
            .collect(),
    )
}

/// The figure `damping.svg` / `.png` in `dir`: log₁₀ D against log₁₀ F_a,
/// per interface the last cycle of each amplitude block joined by a line,
/// the fitted line, and the other cycles as crosses (the cycles that
/// dissipate only, [`dissipating`]). Nothing when none does; nothing without a font (`damping.csv` holds the
/// numbers).
pub fn figure(
    model: &Model,
    cycles: &[Vec<Cycle>],
    sweeps: &[Sweep],
    dir: &Path,
) -> Result<Vec<PathBuf>> {
    use crate::files::plot::{load_font, save_pictures, Chart, Series};
    let log = |c: &Cycle| (c.force_amplitude().log10(), c.dissipation.log10());
    let mut chart = Chart {
        title: format!(
            "{}: dissipation per cycle against force amplitude",
            model.name
        ),
        x_label: "log₁₀ F_a: force amplitude (N)".into(),
        y_label: "log₁₀ D: dissipation per cycle (N·mm)".into(),
        ..Chart::default()
    };
    for ((im, list), sw) in model.interfaces.iter().zip(cycles).zip(sweeps) {
        let live = dissipating(list);
        let mut steady = Vec::new();
        for ((c, r), _) in list.iter().zip(&sw.rows).zip(&live).filter(|x| *x.1) {
            if r.last_in_block {
                steady.push(log(c));
            } else {
                let (x, y) = log(c);
                chart.marks.push((x, y, String::new()));
            }
        }
        steady.sort_by(|a, b| a.0.total_cmp(&b.0));
        if let (Some(f), Some(lo), Some(hi)) = (sw.fit, steady.first(), steady.last()) {
            let line = |x: f64| (x, f.coefficient.log10() + f.exponent * x);
            chart.series.push(Series {
                label: format!(
                    "{}: fit D = C F_a^q, q = {:.3}, R² = {:.4}",
                    im.name, f.exponent, f.r_squared
                ),
                points: vec![line(lo.0), line(hi.0)],
            });
        }
        if !steady.is_empty() {
            chart.series.push(Series {
                label: format!("{}: last cycle of each amplitude", im.name),
                points: steady,
            });
        }
    }
    if chart.series.is_empty() {
        return Ok(Vec::new());
    }
    let stem = dir.join("damping");
    let pictures = load_font();
    save_pictures(&chart, &stem, pictures)?;
    Ok(if pictures {
        vec![stem.with_extension("svg"), stem.with_extension("png")]
    } else {
        Vec::new()
    })
}

/// The index of the last row of the first loading: the first k with
/// |F_{k+1}| < |F_k| − [`REVERSAL`] · max |F| (the first reversal of the
/// tangential force), the last row when |F| never drops.
pub(crate) fn backbone_end(forces: &[f64]) -> usize {
    let top = forces.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let tol = REVERSAL * top;
    forces
        .windows(2)
        .position(|w| w[1].abs() < w[0].abs() - tol)
        .unwrap_or(forces.len().saturating_sub(1))
}

pub const BACKBONE_HEADER: &str =
    "interface,increment,time,tangential_force_n,mean_slip_mm,normal_force_n\n";

/// `backbone.csv`: per interface (in order) the rows of `joints.csv` from the
/// first increment to the first reversal of F_T ([`backbone_end`]), the
/// same numbers in the same format; the header alone without increments.
pub(crate) fn backbone_csv(model: &Model, r: &RunResult) -> String {
    let mut s = String::from(BACKBONE_HEADER);
    for (k, im) in model.interfaces.iter().enumerate() {
        let rows: Vec<(usize, f64, JointMeasures)> = r
            .increments
            .iter()
            .filter_map(|i| i.joints.get(k).map(|m| (i.increment, i.load_factor, *m)))
            .collect();
        if rows.is_empty() {
            continue;
        }
        let forces: Vec<f64> = rows.iter().map(|r| r.2.tangential_force).collect();
        for (inc, time, m) in &rows[..=backbone_end(&forces)] {
            let _ = writeln!(
                s,
                "{},{inc},{time:.9},{:.9e},{:.9e},{:.9e}",
                csv_field(&im.name),
                m.tangential_force,
                m.mean_slip,
                m.normal_force
            );
        }
    }
    s
}

#[cfg(test)]
mod tests;
