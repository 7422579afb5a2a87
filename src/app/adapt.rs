//! Adaptive runs (`[adapt]`, `asperity run CASE --adapt TOL`): solve the whole
//! load history, estimate the error ([`crate::measure::estimate`]), mark the elements
//! that hold a share θ of it (Dörfler's bulk criterion), split them with
//! hanging nodes ([`crate::input::mesh::refine`]), and solve again **from the start
//! of the history** on the new mesh, until the estimate is below the
//! tolerance. Re-solving from zero is exact for history-dependent plasticity:
//! no state is transferred between meshes.
//!
//! The estimate of a cycle is, for `quantity = "energy"`, the recovery
//! estimate relative to the energy norm, η / ‖u_h‖_E; for a named answer Q
//! (the settlement, a load, a pressure), the relative change between two
//! successive meshes, |Q_k − Q_(k−1)| / |Q_k| — a difference estimate, which
//! needs two cycles and which, on a mesh sequence converging at a rate
//! r < 1 per cycle, overestimates the remaining error by 1/(1 − r) − 1 … it is
//! the quantity a designer can watch, not a bound (docs/theory.md).
//!
//! Every cycle writes the run's output folder as a plain run does (the
//! folder is replaced as a whole, so it always holds one complete run: the
//! latest mesh that solved), plus `adapt.csv` and summary.json's `adapt`
//! entry for every cycle so far.

use crate::app::options::RunOptions;
use crate::error::{Error, Result};
use crate::input::case::adapt::{AdaptSpec, Quantity};
use crate::input::case::Case;
use crate::input::mesh::refine::Refined;
use crate::model::Model;
use crate::progress::Log;
use crate::solve::RunResult;
use serde_json::json;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// One cycle's record: its mesh, the estimate and the answers.
#[derive(Clone, Debug, PartialEq)]
pub struct Cycle {
    pub cycle: usize,
    pub elements: usize,
    pub nodes: usize,
    pub dofs: usize,
    pub hanging_nodes: usize,
    /// η (√(N·mm)) and η / ‖u_h‖_E.
    pub eta: f64,
    pub relative_eta: f64,
    /// The quantity's value (NaN: not found, e.g. no yield).
    pub value: f64,
    /// The estimate the tolerance is compared with (NaN: not yet known).
    pub estimate: f64,
    pub iterations: usize,
    pub increments: usize,
    pub(crate) wall_s: f64,
    /// The answers of every run, whatever the quantity: the probe node's
    /// settlement (mm) and the first-yield load (kN, NaN: no yield).
    pub settlement_mm: f64,
    pub(crate) first_yield_kn: f64,
    /// The sum of the applied nodal forces in x and in y at the end of the
    /// history (N, the model as meshed; pretension forces, internal to
    /// their bodies, apart): the same on every cycle ([`applied_force`]).
    pub(crate) applied_n: [f64; 2],
}

/// How an adaptive run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum End {
    /// The estimate is at most the tolerance.
    Reached,
    /// `max_cycles` solves without reaching it.
    Cycles,
    /// The next mesh would exceed `max_dofs`.
    Dofs,
    /// The next mesh would exceed the element limit of every mesh
    /// (`crate::input::case::MAX_ELEMENTS`).
    Elements,
    /// Nothing left to refine (no element marked).
    Nothing,
}

impl End {
    pub fn name(self) -> &'static str {
        match self {
            End::Reached => "reached",
            End::Cycles => "max_cycles",
            End::Dofs => "max_dofs",
            End::Elements => "max_elements",
            End::Nothing => "nothing_to_refine",
        }
    }
}

/// The value of the quantity of a finished run (NaN when the run has none:
/// no increment, or no yield for `first_yield`).
pub fn value(q: Quantity, model: &Model, r: &RunResult, eta_relative: f64) -> f64 {
    let last = r.increments.last().map(|i| i.measures);
    match q {
        Quantity::Energy => eta_relative,
        Quantity::Settlement => last.map_or(f64::NAN, |m| m.center_displacement),
        Quantity::TotalLoad => last.map_or(f64::NAN, |m| m.total_load_kn),
        Quantity::MeanPressure => last.map_or(f64::NAN, |m| m.mean_pressure),
        Quantity::PeakPressure => peak_pressure(model, &r.final_state),
        Quantity::FirstYield => r.first_yield.as_ref().map_or(f64::NAN, |f| f.total_load_kn),
        Quantity::Torque => r
            .increments
            .last()
            .and_then(|i| i.joints.first())
            .map_or(f64::NAN, |j| j.torque),
    }
}

/// The sum of the applied nodal forces of the mesh's nodes at pseudo-time
/// t, per direction x, y (N).
pub(crate) fn applied_force(model: &Model, t: f64) -> [f64; 2] {
    let mut f = vec![0.0; model.n_dofs()];
    model.external_force(t, &mut f);
    let nd = model.node_dofs();
    (0..model.mesh.nodes.len()).fold([0.0, 0.0], |s, n| {
        [s[0] + f[nd.dof(n, 0)], s[1] + f[nd.dof(n, 1)]]
    })
}

/// The largest contact pressure of a state over every interface's points.
fn peak_pressure(model: &Model, state: &crate::solve::State) -> f64 {
    let mut peak = f64::NAN;
    for im in &model.interfaces {
        let gap = im.gap_at(state.time);
        for pt in &im.points {
            let p = im
                .law
                .pressure(im.point_kinematics_at(pt, &state.u, gap).0)
                .0;
            peak = if peak.is_nan() { p } else { peak.max(p) };
        }
    }
    peak
}

/// The estimate compared with the tolerance: η/‖u‖ for the energy norm,
/// else the relative change of the quantity since the previous cycle.
pub(crate) fn cycle_estimate(
    q: Quantity,
    relative_eta: f64,
    value: f64,
    previous: Option<f64>,
) -> f64 {
    match (q, previous) {
        (Quantity::Energy, _) => relative_eta,
        (_, Some(p)) if value.is_finite() && p.is_finite() && value != 0.0 => {
            ((value - p) / value).abs()
        }
        (_, Some(p)) if value == 0.0 && p == 0.0 => 0.0,
        _ => f64::NAN,
    }
}

/// `adapt.csv`: one row per cycle.
pub fn csv(spec: &AdaptSpec, cycles: &[Cycle]) -> String {
    let mut s = format!(
        "cycle,elements,nodes,dofs,hanging_nodes,eta,relative_eta,{},estimate,tolerance,increments,newton_iterations,wall_s,settlement_mm,first_yield_kn,applied_fx_n,applied_fy_n\n",
        spec.quantity.name()
    );
    for c in cycles {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{:.9e},{:.9e},{:.9e},{:.9e},{:e},{},{},{:.3},{:.9e},{:.9e},{:.9e},{:.9e}",
            c.cycle,
            c.elements,
            c.nodes,
            c.dofs,
            c.hanging_nodes,
            c.eta,
            c.relative_eta,
            c.value,
            c.estimate,
            spec.tolerance,
            c.increments,
            c.iterations,
            c.wall_s,
            c.settlement_mm,
            c.first_yield_kn,
            c.applied_n[0],
            c.applied_n[1]
        );
    }
    s.replace("NaN", "")
}

/// summary.json's `adapt` entry (the wall times and Newton iterations are in
/// adapt.csv only: the gold values compare the entry whole, and a solver
/// speed-up changes those without changing an answer).
pub fn summary(spec: &AdaptSpec, cycles: &[Cycle], end: Option<End>) -> serde_json::Value {
    let num = |x: f64| if x.is_finite() { json!(x) } else { json!(null) };
    json!({
        "tolerance": spec.tolerance,
        "quantity": spec.quantity.name(),
        "fraction": spec.fraction,
        "max_cycles": spec.max_cycles,
        "max_dofs": spec.max_dofs,
        "end": end.map(End::name),
        "reached": end == Some(End::Reached),
        "cycles": cycles.iter().map(|c| json!({
            "cycle": c.cycle,
            "elements": c.elements,
            "nodes": c.nodes,
            "dofs": c.dofs,
            "hanging_nodes": c.hanging_nodes,
            "eta": num(c.eta),
            "relative_eta": num(c.relative_eta),
            "value": num(c.value),
            "estimate": num(c.estimate),
            "increments": c.increments,
            "settlement_mm": num(c.settlement_mm),
            "first_yield_kn": num(c.first_yield_kn),
        })).collect::<Vec<_>>(),
    })
}

/// Adds `adapt.csv` and summary.json's `adapt` entry to a finished cycle's
/// output folder (each file written beside and renamed into place).
pub fn record(dir: &Path, spec: &AdaptSpec, cycles: &[Cycle], end: Option<End>) -> Result<()> {
    let put = |name: &str, text: String| -> Result<()> {
        let tmp = dir.join(format!(".{name}.partial"));
        std::fs::write(&tmp, text).map_err(|e| Error::io(&tmp, e))?;
        let to = dir.join(name);
        std::fs::rename(&tmp, &to).map_err(|e| Error::io(&to, e))
    };
    put("adapt.csv", csv(spec, cycles))?;
    let path = dir.join("summary.json");
    let text = std::fs::read_to_string(&path).map_err(|e| Error::io(&path, e))?;
    let mut s: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| Error::io(&path, std::io::Error::other(e.to_string())))?;
    s["adapt"] = summary(spec, cycles, end);
    put(
        "summary.json",
        serde_json::to_string_pretty(&s).unwrap_or_default() + "\n",
    )
}

/// A backend's solve of one cycle: the whole history of a built model, its
/// output folder written on the writing process.
pub(crate) type SolveCycle<'a> = dyn FnMut(&Model, Instant) -> Result<(PathBuf, RunResult)> + 'a;

/// Runs an adaptive case on any backend. `solve` runs the whole history of
/// a built model and writes its output folder on the writing process
/// (`root`); `share` hands rank 0's numbers to every rank (nothing to do on
/// one process), so that every rank marks and refines alike. Returns the last
/// cycle's folder, model and result.
pub fn run(
    case: Case,
    opts: &RunOptions,
    root: bool,
    solve: &mut SolveCycle<'_>,
    share: &dyn Fn(&mut [f64]),
) -> Result<(PathBuf, Model, RunResult)> {
    let spec = case.adapt.clone().expect("an adaptive run has [adapt]");
    let place = case.source.display().to_string();
    let log = Log::new(opts.log_format, opts.quiet || !root);
    let per_node = if case.model.twist { 3 } else { 2 };
    let mut mesh = Refined::start(&Model::mesh_of(&case)?);
    let start_nodes = mesh.mesh.nodes.len();
    let run = Adaptive {
        case: &case,
        spec: &spec,
        place: &place,
        log: &log,
        root,
    };
    let mut cycles: Vec<Cycle> = Vec::new();
    loop {
        let started = Instant::now();
        // the first cycle on the case's own mesh: its checks as a plain run's
        // (the dof cap against the start mesh among them)
        let given = (!cycles.is_empty()).then(|| crate::model::Adapted {
            mesh: mesh.mesh.clone(),
            start_nodes,
        });
        let model = Model::build_on(case.clone(), given)?;
        let (dir, result) = solve(&model, started)?;
        if let Some(stop) = result.stopped {
            // the cycle wrote nothing (driver::run_cycle): the folder holds
            // the previous cycle's complete run, or nothing
            if root {
                stopped(&log, stop, cycles.len() + 1, &result, &dir);
            }
            return Ok((dir, model, result));
        }
        let numbers = run.shared_numbers(&model, &result, share)?;
        let (eta, norm, q) = (numbers[0], numbers[1], numbers[2]);
        let relative_eta = if norm > 0.0 { eta / norm } else { 0.0 };
        let estimate = cycle_estimate(
            spec.quantity,
            relative_eta,
            q,
            cycles.last().map(|c| c.value),
        );
        cycles.push(Cycle {
            cycle: cycles.len() + 1,
            elements: model.mesh.elements.len(),
            nodes: model.mesh.nodes.len(),
            dofs: model.mesh.num_dofs(),
            hanging_nodes: mesh.hanging.len(),
            eta,
            relative_eta,
            value: q,
            estimate,
            iterations: result.stats.run_iterations(),
            increments: result.increments.len(),
            wall_s: started.elapsed().as_secs_f64(),
            settlement_mm: value(Quantity::Settlement, &model, &result, 0.0),
            first_yield_kn: value(Quantity::FirstYield, &model, &result, 0.0),
            applied_n: applied_force(&model, result.final_state.time),
        });
        let end = run.next(&mut mesh, &cycles, &numbers[3..], per_node, &dir)?;
        if root {
            run.report(&dir, &cycles, end)?;
        }
        if end.is_some() {
            return Ok((dir, model, result));
        }
    }
}

/// What every cycle of an adaptive run reads: the case, its `[adapt]`
/// table, the place that messages name, the log and whether this process
/// writes (`root`).
struct Adaptive<'a> {
    case: &'a Case,
    spec: &'a AdaptSpec,
    place: &'a str,
    log: &'a Log,
    root: bool,
}

impl Adaptive<'_> {
    /// Rank 0's estimate and answer, on every rank: [η, ‖u‖, Q, η_e²…]
    /// (the last, per element); refuses a run that made no estimate.
    fn shared_numbers(
        &self,
        model: &Model,
        result: &RunResult,
        share: &dyn Fn(&mut [f64]),
    ) -> Result<Vec<f64>> {
        let ne = model.mesh.elements.len();
        let mut numbers = vec![0.0; 3 + ne];
        if let Some(est) = result.estimate.as_ref().filter(|_| self.root) {
            numbers[0] = est.total;
            numbers[1] = est.norm;
            numbers[2] = value(self.spec.quantity, model, result, est.relative());
            numbers[3..].copy_from_slice(&est.element);
        } else if self.root {
            return Err(Error::input(
                self.place,
                "[adapt] needs the error estimate of the last increment, which this run did not make",
            ));
        }
        share(&mut numbers);
        Ok(numbers)
    }

    /// Whether the run ends after the last of `cycles` (the tolerance
    /// reached, or no further cycle allowed); if not, `mesh` becomes the next
    /// cycle's mesh, refined where `eta_sq` (per element) is largest. A mesh
    /// that cannot be refined is an error, `dir`'s record written first.
    fn next(
        &self,
        mesh: &mut Refined,
        cycles: &[Cycle],
        eta_sq: &[f64],
        per_node: usize,
        dir: &Path,
    ) -> Result<Option<End>> {
        let spec = self.spec;
        let estimate = cycles.last().expect("pushed above").estimate;
        Ok(if estimate <= spec.tolerance {
            Some(End::Reached)
        } else if cycles.len() >= spec.max_cycles {
            Some(End::Cycles)
        } else {
            let limits = [crate::input::case::MAX_ELEMENTS, spec.max_dofs];
            match next_mesh(self.case, spec.fraction, mesh, eta_sq, per_node, limits) {
                Ok(Ok(next)) => {
                    *mesh = next;
                    None
                }
                Ok(Err(end)) => Some(end),
                Err(e) => {
                    // the folder holds this cycle's run: its record too
                    if self.root {
                        record(dir, spec, cycles, None)?;
                    }
                    return Err(Error::Mesh {
                        place: format!("{}: [adapt]", self.place),
                        message: e.to_string(),
                    });
                }
            }
        })
    }

    /// The writing process's record of the last cycle: `adapt.csv` and
    /// summary.json in `dir`, the `adapt` event and, when the run ends short
    /// of the tolerance, a warning.
    fn report(&self, dir: &Path, cycles: &[Cycle], end: Option<End>) -> Result<()> {
        let (spec, log) = (self.spec, self.log);
        let c = cycles.last().expect("pushed above");
        record(dir, spec, cycles, end)?;
        log.progress(
            "adapt",
            json!({
                "cycle": c.cycle,
                "dofs": c.dofs,
                "elements": c.elements,
                "hanging_nodes": c.hanging_nodes,
                "relative_eta": c.relative_eta,
                "quantity": spec.quantity.name(),
                "value": if c.value.is_finite() { json!(c.value) } else { json!(null) },
                "estimate": if c.estimate.is_finite() { json!(c.estimate) } else { json!(null) },
                "tolerance": spec.tolerance,
                "end": end.map(End::name),
            }),
            || {
                format!(
                    "adapt: cycle {} — {} dofs, {} elements, {} hanging nodes: η/‖u‖ = {:.3e}, {} = {:.6e}, estimate {} (tolerance {:e}){}",
                    c.cycle,
                    c.dofs,
                    c.elements,
                    c.hanging_nodes,
                    c.relative_eta,
                    spec.quantity.name(),
                    c.value,
                    if c.estimate.is_finite() { format!("{:.3e}", c.estimate) } else { "not yet known".into() },
                    spec.tolerance,
                    match end {
                        None => String::new(),
                        Some(e) => format!("; {}", e.name()),
                    }
                )
            },
        );
        if let Some(e) = end.filter(|&e| e != End::Reached) {
            log.always(
                "warning",
                json!({ "message": not_reached(e, spec, c) }),
                || format!("warning: {}", not_reached(e, spec, c)),
            );
        }
        Ok(())
    }
}

/// The next mesh: the elements that hold the share `fraction` (θ) of the
/// estimate (`eta_sq`, per element) split, with the two sides of every
/// pretension cut split together ([`crate::model::pretension::facing`]); or why
/// there is none (nothing left to mark, or a mesh beyond `limits`, the
/// element limit and `max_dofs`, found here before it is built or solved).
fn next_mesh(
    case: &Case,
    fraction: f64,
    mesh: &Refined,
    eta_sq: &[f64],
    per_node: usize,
    [max_elements, max_dofs]: [usize; 2],
) -> std::result::Result<std::result::Result<Refined, End>, crate::input::mesh::MeshError> {
    // an element at the deepest level is not split again
    let marked: Vec<usize> = crate::measure::estimate::doerfler_mark(eta_sq, fraction)
        .into_iter()
        .filter(|&e| mesh.state.level[e] < crate::input::mesh::refine::MAX_LEVEL)
        .collect();
    if marked.is_empty() {
        return Ok(Err(End::Nothing));
    }
    let tied = crate::model::pretension::facing(case, &mesh.mesh);
    let next = mesh.refine_tied(&marked, &tied)?;
    Ok(if next.mesh.elements.len() > max_elements {
        Err(End::Elements)
    } else if next.mesh.nodes.len() * per_node > max_dofs {
        Err(End::Dofs)
    } else {
        Ok(next)
    })
}

/// The stop line of an adaptive run interrupted in cycle `cycle` (its
/// partial run was not written).
fn stopped(log: &Log, stop: crate::interrupt::Stop, cycle: usize, r: &RunResult, dir: &Path) {
    let kept = if cycle > 1 {
        format!(
            "{} holds cycle {}'s complete run and adapt.csv",
            dir.display(),
            cycle - 1
        )
    } else {
        "no output was written (an adaptive run cannot be resumed)".to_string()
    };
    log.always(
        "stop",
        json!({
            "stopped_by": stop.name(),
            "adapt_cycle": cycle,
            "increments": r.increments.len(),
            "output": (cycle > 1).then(|| dir.display().to_string()),
            "exit_code": stop.exit_code(),
        }),
        || {
            format!(
                "stopped by {} in adaptive cycle {cycle} after increment {}: the cycle is dropped; {kept}",
                stop.name(),
                r.increments.len()
            )
        },
    );
}

/// The warning of an adaptive run that stopped above its tolerance.
fn not_reached(end: End, spec: &AdaptSpec, c: &Cycle) -> String {
    let why = match end {
        End::Cycles => format!("after max_cycles = {} solves", spec.max_cycles),
        End::Dofs => format!("the next mesh would exceed max_dofs = {}", spec.max_dofs),
        End::Elements => format!(
            "the next mesh would have more than {} elements (the limit of every mesh)",
            crate::input::case::MAX_ELEMENTS
        ),
        End::Nothing => "no element is left to refine".into(),
        End::Reached => String::new(),
    };
    let unknown = if c.value.is_nan() && spec.quantity == Quantity::FirstYield {
        "(not known: no Gauss point yields in the load history on the last mesh)".to_string()
    } else if c.value.is_nan() {
        format!("(not known: the last run has no {})", spec.quantity.name())
    } else {
        "(not known: it needs two cycles)".to_string()
    };
    format!(
        "[adapt] stopped at an estimate of {} above the tolerance {:e}: {why}; the output is the last mesh's ({} dofs)",
        if c.estimate.is_finite() { format!("{:.3e}", c.estimate) } else { unknown },
        spec.tolerance,
        c.dofs
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stepped bolt of revolution cut along its step (y = 0): the
    /// re-entrant corner (4, 0) lies on the cut.
    const BOLT: &str = r#"
[model]
plane = "axisymmetric"
[[mesh.block]]
body = "bolt"
name = "head"
x = [0.0, 4.0, 6.0]
nx = [2, 1]
y = [0.0, 6.0]
ny = [3]
[[mesh.block]]
body = "bolt"
name = "shank"
x = [0.0, 4.0]
nx = [2]
y = [-6.0, 0.0]
ny = [3]
[materials.bolt]
young = 206000.0
poisson = 0.3
[[pretension]]
name = "cut"
body = "bolt"
y = 0.0
force = 1000.0
[[boundary]]
set = "shank.bottom"
uy = 0.0
[[boundary]]
set = "head.top"
uy = 0.0
"#;

    fn start() -> (Case, Refined) {
        let case = Case::parse(BOLT, "bolt").unwrap();
        let mesh = Refined::start(&Model::mesh_of(&case).unwrap());
        (case, mesh)
    }

    #[test]
    fn the_next_mesh_is_refused_beyond_either_limit_before_it_is_built() {
        let (case, mesh) = start();
        let n = mesh.mesh.elements.len();
        let all = vec![1.0; n];
        let next = |limits| next_mesh(&case, 1.0, &mesh, &all, 2, limits).unwrap();
        // every element split in four
        let fine = next([4 * n, usize::MAX]).unwrap();
        assert_eq!(fine.mesh.elements.len(), 4 * n);
        let dofs = 2 * fine.mesh.nodes.len();
        assert_eq!(next([4 * n - 1, usize::MAX]).unwrap_err(), End::Elements);
        assert_eq!(next([4 * n, dofs - 1]).unwrap_err(), End::Dofs);
        assert!(next([4 * n, dofs]).is_ok());
        assert_eq!(
            next_mesh(&case, 1.0, &mesh, &vec![0.0; n], 2, [usize::MAX; 2])
                .unwrap()
                .unwrap_err(),
            End::Nothing
        );
    }

    #[test]
    fn an_element_on_a_pretension_cut_is_split_with_the_one_across() {
        let (case, mesh) = start();
        // the estimate in the head's element at the corner of the shank
        let n = mesh.mesh.elements.len();
        let corner = (0..n)
            .find(|&e| mesh.mesh.element_coords(e)[0] == [2.0, 0.0])
            .unwrap();
        let mut eta = vec![0.0; n];
        eta[corner] = 1.0;
        let next = next_mesh(&case, 0.5, &mesh, &eta, 2, [usize::MAX; 2])
            .unwrap()
            .unwrap();
        // it and the shank's element below it: 8 children
        assert_eq!(next.mesh.elements.len(), n + 6);
        let on_cut = next
            .hanging
            .iter()
            .filter(|h| next.mesh.nodes[h.node][1].abs() < 1e-12)
            .count();
        assert_eq!(on_cut, 0, "{:?}", next.hanging);
        // and the cycle's model builds on it
        let given = crate::model::Adapted {
            start_nodes: mesh.mesh.nodes.len(),
            mesh: next.mesh,
        };
        Model::build_on(case, Some(given)).unwrap();
    }
}
