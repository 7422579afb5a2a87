//! What a damping study reads from a run: per interface the closed load
//! cycles' force amplitude F_a, dissipation D, stored energy U and loss factor
//! η = D / (2π U) ([`Cycle::loss_factor`]) in `damping.csv`, the power law
//! D = C F_a^q fitted to them (summary.json `damping`, the figure
//! `damping.svg`/`.png`), and the joint's first-loading curve, its backbone,
//! in `backbone.csv`.
//!
//! Which cycles enter the fit: consecutive cycles whose force amplitudes agree
//! within `SAME_AMPLITUDE` form a block (a constant-amplitude block of a
//! load program); the last cycle of each block is its steady value, and only
//! those that dissipate (`DISSIPATES`) are fitted. A first cycle also
//! carries the loading from the state before it (from the virgin joint: more
//! slip, more dissipation than the repeats): a block of two or more cycles
//! keeps it out of the fit. A single cycle per amplitude is its own block and
//! enters. With the isotropic memory of section 2.2 a repeat below the
//! friction cap is elastic (it shakes down): only macro-slip dissipates in it.

use super::joints_csv::{csv_field, opt};
use crate::error::Result;
use crate::measure::joint::{Cycle, JointMeasures};
use crate::model::Model;
use crate::solve::RunResult;
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Force amplitudes within this fraction of the larger are the same amplitude.
pub(crate) const SAME_AMPLITUDE: f64 = 1e-2;

/// A cycle dissipates when its D exceeds this fraction of the largest D of
/// its interface's cycles: below it, D is the round-off of the solver on an
/// elastic cycle (a joint that has shaken down).
pub(crate) const DISSIPATES: f64 = 1e-6;

/// A first reversal of F_T is a drop of |F_T| by more than this fraction of
/// the run's largest |F_T| from one increment to the next.
pub(crate) const REVERSAL: f64 = 1e-6;

/// Whether two force amplitudes are the same within [`SAME_AMPLITUDE`].
fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME_AMPLITUDE * a.abs().max(b.abs())
}

/// A least-squares power law y = C x^q.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerFit {
    /// The exponent q.
    pub exponent: f64,
    /// The coefficient C (units of y over units of x to the q).
    pub coefficient: f64,
    /// The points fitted.
    pub points: usize,
    /// The coefficient of determination R² of the fit in logarithms.
    pub r_squared: f64,
}

/// The least-squares line log y = log C + q log x through `points` (x, y > 0):
/// with X = ln x, Y = ln y and their means X̄, Ȳ,
/// q = Σ (X − X̄)(Y − Ȳ) / Σ (X − X̄)², ln C = Ȳ − q X̄ and
/// R² = 1 − Σ (Y − ln C − q X)² / Σ (Y − Ȳ)² (1 when every Y is the same: the
/// line passes through every point). None with fewer than two distinct x
/// (within [`SAME_AMPLITUDE`]) or any x or y not positive and finite.
pub(crate) fn power_fit(points: &[(f64, f64)]) -> Option<PowerFit> {
    let ok = |v: f64| v > 0.0 && v.is_finite();
    if points.iter().any(|&(x, y)| !ok(x) || !ok(y)) {
        return None;
    }
    let x0 = points.first()?.0;
    if points.iter().all(|p| same(p.0, x0)) {
        return None;
    }
    let n = points.len() as f64;
    let logs: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    let xm = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let ym = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - xm).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - xm) * (p.1 - ym)).sum();
    let q = sxy / sxx;
    let ln_c = ym - q * xm;
    let ss_res: f64 = logs.iter().map(|p| (p.1 - ln_c - q * p.0).powi(2)).sum();
    let ss_tot: f64 = logs.iter().map(|p| (p.1 - ym).powi(2)).sum();
    Some(PowerFit {
        exponent: q,
        coefficient: ln_c.exp(),
        points: points.len(),
        r_squared: if ss_tot > 0.0 {
            1.0 - ss_res / ss_tot
        } else {
            1.0
        },
    })
}

/// One cycle as the sweep reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepRow {
    /// The amplitude block, from 1 (consecutive cycles of the same F_a).
    pub block: usize,
    pub first_in_block: bool,
    pub last_in_block: bool,
    /// The cycle entered the fit.
    pub in_fit: bool,
}

/// One interface's amplitude sweep: a row per cycle and the fit.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    pub rows: Vec<SweepRow>,
    pub fit: Option<PowerFit>,
}

/// Per cycle of `cycles`, whether it dissipates (`DISSIPATES`) with
/// F_a > 0 and a force-slip loop (stored energy above round-off,
/// [`Cycle::floor`]): the cycles a logarithmic plot and the fit can take. A
/// loop driven by a torque with the axial force held (a twisting model)
/// has F_a at round-off: it would fit D against noise.
pub fn dissipating(cycles: &[Cycle]) -> Vec<bool> {
    let top = cycles.iter().fold(0.0f64, |m, c| m.max(c.dissipation));
    cycles
        .iter()
        .map(|c| {
            c.dissipation > (DISSIPATES * top).max(c.floor)
                && c.force_amplitude() > 0.0
                && c.stored_energy() > c.floor
        })
        .collect()
}

/// The amplitude a cycle's block is told by: F_a when the cycle has a
/// force-slip loop (U above [`Cycle::floor`]), else the torque amplitude T_a
/// (a torque cycled under a held axial force, whose F_a is round-off; 0
/// without twist, so loop-less cycles of a plane model share a block).
fn block_amplitude(c: &Cycle) -> f64 {
    if c.stored_energy() > c.floor {
        c.force_amplitude()
    } else {
        c.torque_amplitude()
    }
}

/// The amplitude sweep of one interface's cycles: the blocks (a cycle joins
/// the block of the one before when its amplitude (`block_amplitude`) is
/// the same as the block's first within `SAME_AMPLITUDE`) and the `power_fit` of D against F_a over the
/// last cycle of each block that dissipates ([`dissipating`]).
pub fn sweep(cycles: &[Cycle]) -> Sweep {
    let mut rows: Vec<SweepRow> = Vec::with_capacity(cycles.len());
    let mut block_start = 0;
    for (k, c) in cycles.iter().enumerate() {
        let first = k == 0 || !same(block_amplitude(c), block_amplitude(&cycles[block_start]));
        if first {
            block_start = k;
        }
        if let (true, Some(prev)) = (first, rows.last_mut()) {
            prev.last_in_block = true;
        }
        rows.push(SweepRow {
            block: rows.last().map_or(1, |r| r.block + usize::from(first)),
            first_in_block: first,
            last_in_block: k + 1 == cycles.len(),
            in_fit: false,
        });
    }
    let live = dissipating(cycles);
    let points: Vec<(f64, f64)> = rows
        .iter()
        .zip(cycles)
        .zip(&live)
        .filter(|((r, _), &d)| r.last_in_block && d)
        .map(|((_, c), _)| (c.force_amplitude(), c.dissipation))
        .collect();
    let fit = power_fit(&points);
    if fit.is_some() {
        for (r, &d) in rows.iter_mut().zip(&live) {
            r.in_fit = r.last_in_block && d;
        }
    }
    Sweep { rows, fit }
}

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

/// The sweeps of every interface.
pub(crate) fn sweeps(cycles: &[Vec<Cycle>]) -> Vec<Sweep> {
    cycles.iter().map(|c| sweep(c)).collect()
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
