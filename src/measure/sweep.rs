//! A joint's amplitude sweep: its closed load cycles ([`Cycle`]) grouped in
//! blocks of one amplitude, the last cycle of each block its steady value,
//! and the power law D = C F_a^q fitted to the steady cycles that dissipate.
//! `damping.csv`, summary.json `damping` and the damping figure
//! ([`crate::files::output::damping`]) write it; a joint-cycles rating
//! ([`crate::verdict::cycles`]) rates the steady cycles.
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

use super::joint::Cycle;

/// Force amplitudes within this fraction of the larger are the same amplitude.
pub(crate) const SAME_AMPLITUDE: f64 = 1e-2;

/// A cycle dissipates when its D exceeds this fraction of the largest D of
/// its interface's cycles: below it, D is the round-off of the solver on an
/// elastic cycle (a joint that has shaken down).
pub(crate) const DISSIPATES: f64 = 1e-6;

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

/// The sweeps of every interface.
pub(crate) fn sweeps(cycles: &[Vec<Cycle>]) -> Vec<Sweep> {
    cycles.iter().map(|c| sweep(c)).collect()
}

#[cfg(test)]
mod tests;
