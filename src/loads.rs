//! What loads a model, as read from the case: the histories, the load
//! patterns (edge tractions and concentrated forces grouped by history), the
//! prescribed displacements and the gap histories (docs/case-schema.md,
//! "Loads" and "Load histories").
//!
//! A pattern is one force vector at factor 1 with one history; the force at
//! pseudo-time t is Σ_p h_p(t) f_p ([`crate::model::Model::external_force`]).
//! Pattern 0 always exists and has no history of its own (the load factor
//! t, or the default ramp when the case has histories): in a case without
//! histories it holds every load, in the order of the case, so that the force
//! at t is t · f exactly as before histories existed.

use crate::case::{Case, HistoryRef};
use crate::error::{Error, Result};
use crate::fem::{q8, Section};
use crate::history::History;
use crate::mesh::Mesh;
use std::collections::BTreeMap;

/// One force vector (all dofs, at factor 1) and its history (`None`: the
/// load factor, or the default ramp).
#[derive(Clone, Debug)]
pub struct LoadPattern {
    pub history: Option<usize>,
    pub f: Vec<f64>,
}

/// Everything that loads a model.
#[derive(Clone, Debug)]
pub struct Loads {
    /// The named histories (in name order), then the tables given in place
    /// (loads, boundaries, forces, gaps, in the order of the case).
    pub histories: Vec<History>,
    /// Pattern 0 first (no history of its own), then one per history used.
    pub patterns: Vec<LoadPattern>,
    /// Prescribed dofs, their values at factor 1 and their histories.
    pub prescribed: Vec<(usize, f64)>,
    pub prescribed_history: Vec<Option<usize>>,
    /// The gap history of each `[interface.<name>]` that has one.
    pub gap_history: BTreeMap<String, usize>,
}

/// Resolves history references while the loads are read.
struct Resolver<'c> {
    named: Vec<&'c String>,
    histories: Vec<History>,
}

impl<'c> Resolver<'c> {
    fn new(case: &'c Case, place: &str) -> Result<Resolver<'c>> {
        let mut histories = Vec::new();
        for (name, table) in &case.history {
            let h = History::new(table)
                .map_err(|m| Error::input(format!("{place}: [history] {}", clip(name)), m))?;
            histories.push(h);
        }
        Ok(Resolver {
            named: case.history.keys().collect(),
            histories,
        })
    }

    /// The index of a load's history (`None`: it has none); `at` names the
    /// key in errors.
    fn resolve(&mut self, r: Option<&HistoryRef>, at: &str) -> Result<Option<usize>> {
        match r {
            None => Ok(None),
            Some(HistoryRef::Name(name)) => match self.named.iter().position(|n| *n == name) {
                Some(i) => Ok(Some(i)),
                None => Err(Error::input(
                    at,
                    format!(
                        "no history named \"{}\" in [history] ({})",
                        clip(name),
                        if self.named.is_empty() {
                            "the case has no [history] table".to_string()
                        } else {
                            format!(
                                "histories: {}",
                                self.named
                                    .iter()
                                    .map(|n| clip(n))
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            )
                        }
                    ),
                )),
            },
            Some(HistoryRef::Table(table)) => {
                let h = History::new(table).map_err(|m| Error::input(at, m))?;
                self.histories.push(h);
                Ok(Some(self.histories.len() - 1))
            }
        }
    }
}

fn clip(s: &str) -> String {
    crate::error::clip(s)
}

/// Reads every load of the case on its mesh; `section` gives the
/// out-of-plane measure of the edge tractions.
pub fn build(case: &Case, mesh: &Mesh, section: Section, place: &str) -> Result<Loads> {
    let mut res = Resolver::new(case, place)?;
    let mut patterns = vec![LoadPattern {
        history: None,
        f: vec![0.0; mesh.num_dofs()],
    }];
    for (i, ld) in case.load.iter().enumerate() {
        let at = format!("{place}: load[{i}] (edges \"{}\")", ld.edges);
        let h = res.resolve(ld.history.as_ref(), &format!("{at} history"))?;
        let f = pattern(&mut patterns, h, mesh.num_dofs());
        edge_traction(ld, mesh, section, &at, f)?;
    }
    let prescribed = boundary_conditions(case, mesh, place, &mut res)?;
    for (i, fs) in case.force.iter().enumerate() {
        let at = format!("{place}: force[{i}] (nodes \"{}\")", fs.nodes);
        let h = res.resolve(fs.history.as_ref(), &format!("{at} history"))?;
        let f = pattern(&mut patterns, h, mesh.num_dofs());
        concentrated_force(fs, mesh, &at, f)?;
    }
    let mut gap_history = BTreeMap::new();
    for (name, spec) in &case.interface {
        let at = format!("{place}: [interface.{}] gap_history", clip(name));
        if let Some(h) = res.resolve(spec.gap_history.as_ref(), &at)? {
            gap_history.insert(name.clone(), h);
        }
    }
    let histories = res.histories;
    if !histories.is_empty() && case.solver.load_factors.is_some() {
        return Err(Error::input(
            format!("{place}: [solver] load_factors"),
            "cannot be given with load histories ([history], or `history` / `gap_history` on a load, boundary, force or interface): the histories say how the loads change; remove load_factors",
        ));
    }
    let breakpoints = crate::history::breakpoints(&histories);
    if let Some(n) = crate::solve::stepping::Stepper::planned(&case.solver, &breakpoints) {
        if n > crate::case::MAX_INCREMENTS {
            return Err(Error::input(
                format!("{place}: [solver] increments"),
                format!(
                    "{} steps per unit of pseudo-time through the histories (to t = {}) make {n} increments, more than {}",
                    case.solver.n_increments(),
                    breakpoints.last().copied().unwrap_or(1.0),
                    crate::case::MAX_INCREMENTS
                ),
            ));
        }
    }
    let (prescribed, prescribed_history) = prescribed.into_iter().unzip();
    Ok(Loads {
        histories,
        patterns,
        prescribed,
        prescribed_history,
        gap_history,
    })
}

/// The force vector of the pattern with history `h`, added if new.
fn pattern(patterns: &mut Vec<LoadPattern>, h: Option<usize>, n: usize) -> &mut Vec<f64> {
    let k = match patterns.iter().position(|p| p.history == h) {
        Some(k) => k,
        None => {
            patterns.push(LoadPattern {
                history: h,
                f: vec![0.0; n],
            });
            patterns.len() - 1
        }
    };
    &mut patterns[k].f
}

fn in_range(v: f64, r: &Option<[f64; 2]>) -> bool {
    r.is_none_or(|[lo, hi]| v >= lo - 1e-9 && v <= hi + 1e-9)
}

/// A uniform pressure and shear on an edge set, integrated consistently
/// (3-point Gauss on the quadratic edge) into `f`.
fn edge_traction(
    ld: &crate::case::LoadSpec,
    mesh: &Mesh,
    section: Section,
    at: &str,
    f: &mut [f64],
) -> Result<()> {
    let edges = mesh.edge_sets.get(&ld.edges).ok_or_else(|| {
        Error::input(
            at,
            format!(
                "no edge set \"{}\" (sets: {})",
                ld.edges,
                names(mesh.edge_sets.keys())
            ),
        )
    })?;
    let (p, tau) = (ld.pressure, ld.shear);
    if !p.is_finite() || (p == 0.0 && tau == 0.0) {
        return Err(Error::input(
            at,
            format!(
                "pressure {p} must be a finite, non-zero number (MPa), unless a shear is given"
            ),
        ));
    }
    if !tau.is_finite() {
        return Err(Error::input(
            format!("{at} shear"),
            format!("{tau} must be a finite number (MPa)"),
        ));
    }
    let gp = q8::gauss_1d(3);
    let mut count = 0;
    for edge in edges {
        let x: Vec<[f64; 2]> = edge.iter().map(|&n| mesh.nodes[n]).collect();
        if !(in_range(x[1][0], &ld.x_range) && in_range(x[1][1], &ld.y_range)) {
            continue;
        }
        count += 1;
        for &(s, w) in &gp {
            let n = q8::edge_shape(s);
            let dn = [s - 0.5, -2.0 * s, s + 0.5];
            let (mut tx, mut ty) = (0.0, 0.0);
            let mut xg = [0.0; 2];
            for k in 0..3 {
                tx += dn[k] * x[k][0];
                ty += dn[k] * x[k][1];
                xg[0] += n[k] * x[k][0];
                xg[1] += n[k] * x[k][1];
            }
            let measure = section.measure(xg);
            // body on the left: outward normal × ds = (t_y, −t_x) dξ; pressure
            // pushes inward; the shear direction (n_y, −n_x) × ds = (−t_x, −t_y) dξ
            for k in 0..3 {
                if p != 0.0 {
                    f[2 * edge[k]] -= p * n[k] * ty * w * measure;
                    f[2 * edge[k] + 1] += p * n[k] * tx * w * measure;
                }
                if tau != 0.0 {
                    f[2 * edge[k]] -= tau * n[k] * tx * w * measure;
                    f[2 * edge[k] + 1] -= tau * n[k] * ty * w * measure;
                }
            }
        }
    }
    if count == 0 {
        return Err(Error::input(
            at,
            "selects no edge (check x_range / y_range)",
        ));
    }
    Ok(())
}

/// A force (fx, fy) at every selected node of a node set, into `f`.
fn concentrated_force(
    fs: &crate::case::ForceSpec,
    mesh: &Mesh,
    at: &str,
    f: &mut [f64],
) -> Result<()> {
    let nodes = mesh.node_sets.get(&fs.nodes).ok_or_else(|| {
        Error::input(
            at,
            format!(
                "no node set \"{}\" (sets: {})",
                fs.nodes,
                names(mesh.node_sets.keys())
            ),
        )
    })?;
    for (key, v) in [("fx", fs.fx), ("fy", fs.fy)] {
        if !v.is_finite() {
            return Err(Error::input(
                format!("{at} {key}"),
                format!("{v} is not a finite number (N)"),
            ));
        }
    }
    if fs.fx == 0.0 && fs.fy == 0.0 {
        return Err(Error::input(
            at,
            "fx and fy are both 0: give a non-zero force (N)",
        ));
    }
    let mut count = 0;
    for &n in nodes {
        let x = mesh.nodes[n];
        if in_range(x[0], &fs.x_range) && in_range(x[1], &fs.y_range) {
            f[2 * n] += fs.fx;
            f[2 * n + 1] += fs.fy;
            count += 1;
        }
    }
    if count == 0 {
        return Err(Error::input(
            at,
            "selects no node (check x_range / y_range)",
        ));
    }
    Ok(())
}

/// A prescribed dof and its value at factor 1, and its history.
type Prescribed = ((usize, f64), Option<usize>);

/// The prescribed dofs, their values and histories. A dof may be named by
/// several `[[boundary]]` entries only with the same value and history (a
/// corner in two fixed sets); two different ones for one node and direction
/// are refused, naming both entries (docs/case-schema.md, "Prescribed values").
fn boundary_conditions(
    case: &Case,
    mesh: &Mesh,
    place: &str,
    res: &mut Resolver,
) -> Result<Vec<Prescribed>> {
    // dof → (value, history, index of the first entry that set it)
    let mut out: BTreeMap<usize, (f64, Option<usize>, usize)> = Default::default();
    for (i, bc) in case.boundary.iter().enumerate() {
        let at = format!("{place}: boundary[{i}] (set \"{}\")", bc.set);
        let nodes = mesh.node_sets.get(&bc.set).ok_or_else(|| {
            Error::input(
                &at,
                format!(
                    "no node set \"{}\" (sets: {})",
                    bc.set,
                    names(mesh.node_sets.keys())
                ),
            )
        })?;
        if bc.ux.is_none() && bc.uy.is_none() {
            return Err(Error::input(&at, "give ux and/or uy"));
        }
        let h = res.resolve(bc.history.as_ref(), &format!("{at} history"))?;
        let mut count = 0;
        for &n in nodes {
            let x = mesh.nodes[n];
            if !(in_range(x[0], &bc.x_range) && in_range(x[1], &bc.y_range)) {
                continue;
            }
            count += 1;
            for (c, v) in [bc.ux, bc.uy].iter().enumerate() {
                let Some(v) = *v else { continue };
                if !v.is_finite() {
                    return Err(Error::input(&at, format!("displacement {v} is not finite")));
                }
                let (first, fh, j) = *out.entry(2 * n + c).or_insert((v, h, i));
                if first != v || fh != h {
                    let axis = ["x", "y"][c];
                    let what = if first != v {
                        format!("u{axis} = {v}, but boundary[{j}] (set \"{}\") already gives it {first}", clip(&case.boundary[j].set))
                    } else {
                        format!(
                            "u{axis} with another history than boundary[{j}] (set \"{}\")",
                            clip(&case.boundary[j].set)
                        )
                    };
                    return Err(Error::input(
                        format!("{at} u{axis}"),
                        format!(
                            "gives node {n} at ({}, {}) {what}: one prescribed value per node and direction",
                            x[0], x[1]
                        ),
                    ));
                }
            }
        }
        if count == 0 {
            return Err(Error::input(
                &at,
                "selects no node (check x_range / y_range)",
            ));
        }
    }
    Ok(out.into_iter().map(|(d, (v, h, _))| ((d, v), h)).collect())
}

/// A list of names for a message: each clipped, at most 30 of them.
pub fn names<'a>(it: impl Iterator<Item = &'a String>) -> String {
    let all: Vec<&String> = it.collect();
    let mut s: Vec<String> = all.iter().take(30).map(|n| clip(n)).collect();
    if all.len() > 30 {
        s.push(format!("… {} more", all.len() - 30));
    }
    s.join(", ")
}
