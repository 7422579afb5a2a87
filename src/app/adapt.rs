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
//! (the settlement, a load, a pressure, a stress away from the singular
//! points), read at the end of the history or as its value farthest from 0
//! over every converged increment (`over`, [`history`]: the run's records,
//! no solve more), the relative change between two
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
use crate::input::case::adapt::{AdaptSpec, Over, Quantity};
use crate::input::case::Case;
use crate::input::mesh::refine::Refined;
use crate::model::outputs::{PER_BODY, PER_INTERFACE};
use crate::model::Model;
use crate::progress::Log;
use crate::solve::{Increment, RunResult};
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
    /// With `max_von_mises`: the largest von Mises stress of every Gauss
    /// point, the excluded ones included, read `over` the history as the
    /// quantity is ([`von_mises_everywhere`]), and how many Gauss points the
    /// discs hold on this cycle's mesh; NaN and 0 with another quantity.
    pub von_mises_all: f64,
    pub excluded_points: usize,
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

/// The value of the quantity `q` of a finished run read `over` the history
/// (NaN when the run has none: no increment, no yield for `first_yield`, no
/// Gauss point left in for `max_von_mises`).
pub fn value(q: Quantity, over: Over, model: &Model, r: &RunResult, eta_relative: f64) -> f64 {
    match q {
        Quantity::Energy => eta_relative,
        Quantity::FirstYield => r.first_yield.as_ref().map_or(f64::NAN, |f| f.total_load_kn),
        _ => read(over, &history(q, model, &r.increments)),
    }
}

/// A quantity's values at every increment read `over` the history: the
/// last, or the one farthest from 0.
fn read(over: Over, values: &[f64]) -> f64 {
    match over {
        Over::End => values.last().copied().unwrap_or(f64::NAN),
        Over::History => farthest_from_zero(values),
    }
}

/// The quantity `q` at every converged increment, in order: what the run's
/// outputs hold per increment (curve.csv's `center_displacement_mm`,
/// `total_load_kn`, `mean_pressure_mpa`; joints.csv's first interface's
/// torque; contact.csv's `max_pressure_mpa`, the largest over the
/// interfaces; the increment's stress away from the singular points). NaN
/// for the quantities that have no value per increment (`energy`,
/// `first_yield`).
pub fn history(q: Quantity, model: &Model, increments: &[Increment]) -> Vec<f64> {
    let layout = &model.plan.layout;
    increments
        .iter()
        .map(|inc| {
            let m = &inc.measures;
            match q {
                Quantity::Settlement => m.center_displacement,
                Quantity::TotalLoad => m.total_load_kn,
                Quantity::MeanPressure => m.mean_pressure,
                Quantity::PeakPressure => {
                    largest(&inc.record, layout.interfaces.clone(), PER_INTERFACE)
                }
                Quantity::Torque => inc.joints.first().map_or(f64::NAN, |j| j.torque),
                Quantity::MaxVonMises => inc.von_mises_away,
                Quantity::Energy | Quantity::FirstYield => f64::NAN,
            }
        })
        .collect()
}

/// The largest von Mises stress of every body, the singular points'
/// Gauss points included (peaks.csv's `von_mises_mpa`), at every converged
/// increment: what `max_von_mises` would chase without its exclusion.
pub fn von_mises_everywhere(model: &Model, increments: &[Increment]) -> Vec<f64> {
    let bodies = model.plan.layout.bodies.clone();
    increments
        .iter()
        .map(|inc| largest(&inc.record, bodies.clone(), PER_BODY))
        .collect()
}

/// The largest of the first value of every `per`-wide entry of `record`'s
/// part `part` (each body's von Mises, each interface's peak pressure); NaN
/// without an entry (or a record not of the model's width).
fn largest(record: &[f64], part: std::ops::Range<usize>, per: usize) -> f64 {
    record.get(part).map_or(f64::NAN, |v| {
        v.chunks_exact(per)
            .map(|c| c[0])
            .fold(f64::NAN, |a, x| if a.is_nan() || x > a { x } else { a })
    })
}

/// The value farthest from 0 of `values`, its sign kept: the largest over
/// a history of a quantity that may be negative (a settlement is) or change
/// sign (a torque under a reversed twist), the largest for one that is not
/// (a pressure, a stress). NaN values are skipped; of two equally far the
/// first is kept; NaN when none is left.
pub fn farthest_from_zero(values: &[f64]) -> f64 {
    values
        .iter()
        .copied()
        .filter(|v| !v.is_nan())
        .fold(f64::NAN, |a, v| {
            if a.is_nan() || v.abs() > a.abs() {
                v
            } else {
                a
            }
        })
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

/// `adapt.csv`: one row per cycle (with `max_von_mises`, two columns more:
/// the stress everywhere and the excluded Gauss points).
pub fn csv(spec: &AdaptSpec, cycles: &[Cycle]) -> String {
    let stress = spec.quantity == Quantity::MaxVonMises;
    let mut s = format!(
        "cycle,elements,nodes,dofs,hanging_nodes,eta,relative_eta,{},estimate,tolerance,increments,newton_iterations,wall_s,settlement_mm,first_yield_kn,applied_fx_n,applied_fy_n{}\n",
        spec.quantity.name(),
        if stress { ",max_von_mises_all_mpa,excluded_points" } else { "" }
    );
    for c in cycles {
        let _ = write!(
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
        if stress {
            let _ = write!(s, ",{:.9e},{}", c.von_mises_all, c.excluded_points);
        }
        s.push('\n');
    }
    s.replace("NaN", "")
}

/// summary.json's `adapt` entry (the wall times and Newton iterations are in
/// adapt.csv only: the gold values compare the entry whole, and a solver
/// speed-up changes those without changing an answer). With
/// `max_von_mises`, `excluded` lists the discs left out (`model`'s, the
/// same on every cycle) and each cycle its stress everywhere and excluded
/// points.
pub fn summary(
    spec: &AdaptSpec,
    model: &Model,
    cycles: &[Cycle],
    end: Option<End>,
) -> serde_json::Value {
    let num = |x: f64| if x.is_finite() { json!(x) } else { json!(null) };
    let mut s = json!({
        "tolerance": spec.tolerance,
        "quantity": spec.quantity.name(),
        "over": spec.over.name(),
        "fraction": spec.fraction,
        "max_cycles": spec.max_cycles,
        "max_dofs": spec.max_dofs,
        "end": end.map(End::name),
        "reached": end == Some(End::Reached),
        "cycles": cycles.iter().map(|c| {
            let mut o = json!({
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
            });
            if spec.quantity == Quantity::MaxVonMises {
                o["max_von_mises_all_mpa"] = num(c.von_mises_all);
                o["excluded_points"] = json!(c.excluded_points);
            }
            o
        }).collect::<Vec<_>>(),
    });
    if let Some(x) = model.excluded.as_ref() {
        s["excluded"] = discs_json(model, &x.discs);
    }
    s
}

/// The discs `max_von_mises` leaves out, as summary.json lists them.
fn discs_json(model: &Model, discs: &[crate::model::excluded::Disc]) -> serde_json::Value {
    json!(discs
        .iter()
        .map(|d| json!({
            "corner": d.corner,
            "x_mm": d.x[0],
            "y_mm": d.x[1],
            "radius_mm": d.radius,
            "bodies": d.bodies.iter().map(|&b| &model.mesh.bodies[b]).collect::<Vec<_>>(),
        }))
        .collect::<Vec<_>>())
}

/// Adds `adapt.csv` and summary.json's `adapt` entry to a finished cycle's
/// output folder (each file written beside and renamed into place); `model`
/// is the cycle's.
pub fn record(
    dir: &Path,
    spec: &AdaptSpec,
    model: &Model,
    cycles: &[Cycle],
    end: Option<End>,
) -> Result<()> {
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
    s["adapt"] = summary(spec, model, cycles, end);
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
    // the start mesh's discs that max_von_mises leaves out, on every cycle
    let mut discs = None;
    loop {
        let started = Instant::now();
        // the first cycle on the case's own mesh: its checks as a plain run's
        // (the dof cap against the start mesh among them)
        let given = (!cycles.is_empty()).then(|| crate::model::Adapted {
            mesh: mesh.mesh.clone(),
            start_nodes,
            excluded: discs.clone(),
        });
        let model = Model::build_on(case.clone(), given)?;
        if cycles.is_empty() {
            discs = model.excluded.as_ref().map(|x| x.discs.clone());
        }
        let (dir, result) = solve(&model, started)?;
        if let Some(stop) = result.stopped {
            // the cycle wrote nothing (driver::run_cycle): the folder holds
            // the previous cycle's complete run, or nothing; at a torque
            // limit it holds this cycle's run
            if root {
                stopped(&log, stop, cycles.len() + 1, &result, &dir);
            }
            return Ok((dir, model, result));
        }
        let numbers = run.shared_numbers(&model, &result, share)?;
        let c = run.cycle(
            &model,
            &result,
            &numbers,
            &cycles,
            mesh.hanging.len(),
            started,
        );
        cycles.push(c);
        let end = run.next(&model, &mut mesh, &cycles, &numbers[3..], per_node, &dir)?;
        if root {
            run.report(&dir, &model, &cycles, end)?;
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
    /// The record of a cycle solved on `model` after `cycles`: its mesh,
    /// `numbers` (shared: [η, ‖u‖, Q, …]), the estimate from the previous
    /// cycle's value, and the answers of every run.
    fn cycle(
        &self,
        model: &Model,
        result: &RunResult,
        numbers: &[f64],
        cycles: &[Cycle],
        hanging_nodes: usize,
        started: Instant,
    ) -> Cycle {
        let spec = self.spec;
        let (eta, norm, q) = (numbers[0], numbers[1], numbers[2]);
        let relative_eta = if norm > 0.0 { eta / norm } else { 0.0 };
        let estimate = cycle_estimate(
            spec.quantity,
            relative_eta,
            q,
            cycles.last().map(|c| c.value),
        );
        let stress = spec.quantity == Quantity::MaxVonMises;
        let at_end = |q| value(q, Over::End, model, result, 0.0);
        Cycle {
            cycle: cycles.len() + 1,
            elements: model.mesh.elements.len(),
            nodes: model.mesh.nodes.len(),
            dofs: model.mesh.num_dofs(),
            hanging_nodes,
            eta,
            relative_eta,
            value: q,
            estimate,
            iterations: result.stats.run_iterations(),
            increments: result.increments.len(),
            wall_s: started.elapsed().as_secs_f64(),
            settlement_mm: at_end(Quantity::Settlement),
            first_yield_kn: at_end(Quantity::FirstYield),
            applied_n: applied_force(model, result.final_state.time),
            von_mises_all: if stress {
                read(spec.over, &von_mises_everywhere(model, &result.increments))
            } else {
                f64::NAN
            },
            excluded_points: model.excluded.as_ref().map_or(0, |x| x.count()),
        }
    }

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
            let spec = self.spec;
            numbers[2] = value(spec.quantity, spec.over, model, result, est.relative());
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
        model: &Model,
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
                        record(dir, spec, model, cycles, None)?;
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
    fn report(&self, dir: &Path, model: &Model, cycles: &[Cycle], end: Option<End>) -> Result<()> {
        let (spec, log) = (self.spec, self.log);
        let c = cycles.last().expect("pushed above");
        record(dir, spec, model, cycles, end)?;
        log.progress(
            "adapt",
            json!({
                "cycle": c.cycle,
                "dofs": c.dofs,
                "elements": c.elements,
                "hanging_nodes": c.hanging_nodes,
                "relative_eta": c.relative_eta,
                "quantity": spec.quantity.name(),
                "over": spec.over.name(),
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
                    label(spec),
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

/// The quantity as the progress line names it: `peak_pressure`, or
/// `peak_pressure (largest over the history)`.
fn label(spec: &AdaptSpec) -> String {
    match spec.over {
        Over::End => spec.quantity.name().to_string(),
        Over::History => format!("{} (largest over the history)", spec.quantity.name()),
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
    if !stop.resumable() {
        // written whole by the driver, its own stop line said so
        let w = format!("[adapt] ends with cycle {cycle}: its run ended at its torque limit ({}), past which the load history has no equilibrium to refine; {} holds that cycle's run", stop.name(), dir.display());
        log.always("warning", json!({ "message": w }), || {
            format!("warning: {w}")
        });
        return;
    }
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
            excluded: None,
        };
        Model::build_on(case, Some(given)).unwrap();
    }

    /// Three blocks stacked, two interfaces (`a` above, `b` below).
    const STACK: &str = r#"
[model]
plane = "strain"
[[mesh.block]]
body = "upper"
x = [0.0, 2.0]
nx = [1]
y = [1.0, 2.0]
ny = [1]
[[mesh.block]]
body = "middle"
x = [0.0, 2.0]
nx = [1]
y = [0.0, 1.0]
ny = [1]
[[mesh.block]]
body = "lower"
x = [0.0, 2.0]
nx = [1]
y = [-1.0, 0.0]
ny = [1]
[[mesh.interface]]
name = "a"
upper = "upper"
lower = "middle"
[[mesh.interface]]
name = "b"
upper = "middle"
lower = "lower"
[materials.upper]
young = 200000.0
poisson = 0.3
[materials.middle]
young = 200000.0
poisson = 0.3
[materials.lower]
young = 200000.0
poisson = 0.3
[interface.a]
law = "power"
c_n = 0.001
m = 0.5
[interface.b]
law = "power"
c_n = 0.001
m = 0.5
[[boundary]]
set = "upper.top"
ux = 0.0
uy = -0.001
[[boundary]]
set = "middle.left"
ux = 0.0
[[boundary]]
set = "lower.bottom"
ux = 0.0
uy = 0.0
"#;

    #[test]
    fn the_farthest_from_zero_keeps_its_sign_skips_nan_and_the_first_of_a_tie() {
        assert_eq!(farthest_from_zero(&[1.0, -3.0, 2.0]), -3.0);
        assert_eq!(farthest_from_zero(&[0.5, 4.0, -2.0]), 4.0);
        assert_eq!(farthest_from_zero(&[f64::NAN, 2.0, -2.0, f64::NAN]), 2.0);
        assert_eq!(farthest_from_zero(&[-2.0, 2.0]), -2.0);
        assert!(farthest_from_zero(&[]).is_nan());
        assert!(farthest_from_zero(&[f64::NAN]).is_nan());
        assert_eq!(read(Over::End, &[1.0, 5.0, 2.0]), 2.0);
        assert_eq!(read(Over::History, &[1.0, 5.0, 2.0]), 5.0);
        assert!(read(Over::End, &[]).is_nan());
    }

    /// Every quantity's value per increment is read from the increment's
    /// rows (curve's measures, the first joint, the record's peaks), and
    /// `over` takes the last or the one farthest from 0: four increments
    /// whose largest values lie inside the history, not at its end.
    #[test]
    fn each_quantity_is_folded_over_the_increments_records() {
        let model = Model::parse(STACK, "stack").unwrap_or_else(|e| panic!("{e}"));
        let layout = model.plan.layout.clone();
        assert_eq!(layout.interfaces.len(), 2 * PER_INTERFACE);
        assert_eq!(layout.bodies.len(), 3 * PER_BODY);
        let (pa, pb) = ([1.0, 5.0, 2.0, 3.0], [2.0, 1.0, 7.0, 0.5]);
        let vm = [
            [10.0, 20.0, 5.0],
            [12.0, 8.0, 30.0],
            [9.0, 9.0, 9.0],
            [1.0, 2.0, 3.0],
        ];
        let settle = [-0.1, -0.4, 0.3, -0.2];
        let load = [1.0, 4.0, 3.0, 2.5];
        let torque = [1.0, -5.0, 4.0, 2.0];
        let away = [f64::NAN, 3.0, 2.0, 1.0];
        let increments: Vec<Increment> = (0..4)
            .map(|k| {
                let mut record = vec![f64::NAN; model.plan.width()];
                record[layout.interfaces.start] = pa[k];
                record[layout.interfaces.start + PER_INTERFACE] = pb[k];
                for (b, v) in vm[k].iter().enumerate() {
                    record[layout.bodies.start + b * PER_BODY] = *v;
                }
                let joint = crate::measure::joint::JointMeasures {
                    torque: torque[k],
                    ..Default::default()
                };
                Increment {
                    increment: k + 1,
                    load_factor: (k + 1) as f64 / 4.0,
                    iterations: 1,
                    cutbacks: 0,
                    measures: crate::measure::Measures {
                        center_displacement: settle[k],
                        total_load_kn: load[k],
                        mean_pressure: 10.0 * load[k],
                        ..Default::default()
                    },
                    joints: vec![joint, Default::default()],
                    sections: Vec::new(),
                    record,
                    von_mises_away: away[k],
                }
            })
            .collect();
        let both = |q: Quantity| {
            let h = history(q, &model, &increments);
            (read(Over::End, &h), read(Over::History, &h))
        };
        assert_eq!(both(Quantity::PeakPressure), (3.0, 7.0));
        assert_eq!(both(Quantity::Settlement), (-0.2, -0.4));
        assert_eq!(both(Quantity::TotalLoad), (2.5, 4.0));
        assert_eq!(both(Quantity::MeanPressure), (25.0, 40.0));
        assert_eq!(both(Quantity::Torque), (2.0, -5.0));
        assert_eq!(both(Quantity::MaxVonMises), (1.0, 3.0));
        let all = von_mises_everywhere(&model, &increments);
        assert_eq!(all, vec![20.0, 30.0, 9.0, 3.0]);
        for q in [Quantity::Energy, Quantity::FirstYield] {
            assert!(history(q, &model, &increments).iter().all(|v| v.is_nan()));
        }
    }
}
