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

use crate::error::{Error, Result};
use crate::input::case::ranges::{self, Range};
use crate::input::case::{Case, HistoryRef};
use crate::input::mesh::Mesh;
use crate::model::history::History;
use crate::physics::element::Section;
use resultant::what;
use std::collections::BTreeMap;

mod adaptive;
mod faces;
pub mod field;
pub mod resultant;
pub mod speed;
pub mod thermal;

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
    pub(crate) patterns: Vec<LoadPattern>,
    /// Prescribed dofs, their values at factor 1 and their histories.
    pub prescribed: Vec<(usize, f64)>,
    pub prescribed_history: Vec<Option<usize>>,
    /// The gap history of each `[interface.<name>]` that has one.
    pub gap_history: BTreeMap<String, usize>,
    /// Every `[[load]]` and `[[force]]` with the dofs it loads, for
    /// `check_acting` once the prescribed dofs are known.
    pub acting: Vec<Acting>,
    /// The history of each `[[pretension]]` section's force or shortening.
    pub(crate) pretension_history: Vec<Option<usize>>,
    /// Every `[[load]]` and `[[force]]` as a whole: its resultant at factor 1,
    /// in these components.
    pub applied: Vec<Applied>,
    pub components: resultant::Components,
    /// Every `[[temperature]]`: a body's uniform temperature change.
    pub temperatures: Vec<thermal::BodyTemperature>,
    /// The `[speed]`, with its centrifugal nodal forces.
    pub speed: Option<speed::Speed>,
}

/// One `[[load]]` or `[[force]]` as a designer names it, with its resultant
/// at factor 1 ([`resultant::resultant`]); at pseudo-time t it applies
/// `factor(history, t)` times that.
#[derive(Clone, Debug)]
pub struct Applied {
    /// `load[0]`, `force[1]`: where it is in the case.
    pub name: String,
    /// What it applies, in words: "pressure -170.5 MPa", "force (0, 100) N".
    pub kind: String,
    /// Where it acts, in words: "edges top_plate.top, x in [8.5, 12.5]".
    pub selection: String,
    pub history: Option<usize>,
    /// Force (N) and moment (N·mm) components at factor 1.
    pub resultant: Vec<f64>,
}

/// One `[[load]]` or `[[force]]`: where it is written and the dofs it loads
/// (non-zero entries at factor 1).
#[derive(Clone, Debug)]
pub struct Acting {
    pub at: String,
    pub dofs: Vec<usize>,
    /// A `[[force]]` (each of its dofs must be free), else an edge traction
    /// (at least one of its dofs must be free).
    pub concentrated: bool,
}

/// Resolves history references while the loads are read.
struct Resolver<'c> {
    named: Vec<&'c String>,
    /// Which named histories something refers to.
    used: Vec<bool>,
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
            used: vec![false; case.history.len()],
            histories,
        })
    }

    /// The index of a load's history (`None`: it has none); `at` names the
    /// key in errors.
    fn resolve(&mut self, r: Option<&HistoryRef>, at: &str) -> Result<Option<usize>> {
        match r {
            None => Ok(None),
            Some(HistoryRef::Name(name)) => match self.named.iter().position(|n| *n == name) {
                Some(i) => {
                    self.used[i] = true;
                    Ok(Some(i))
                }
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
/// out-of-plane measure of the edge tractions. A `[[force]]` acts on the
/// nodes of its selection that `start` marks (an adaptive run's start mesh:
/// every node of a plain run), so that refinement adds none to it.
pub fn build(
    case: &Case,
    mesh: &Mesh,
    start: &[bool],
    section: Section,
    place: &str,
) -> Result<Loads> {
    let mut res = Resolver::new(case, place)?;
    // the mesh's dofs, then each pretension section's reference node
    let nd = crate::model::pretension::total_dofs(case, mesh);
    let mut g = Gathered {
        patterns: vec![LoadPattern {
            history: None,
            f: vec![0.0; nd],
        }],
        nd,
        acting: Vec::new(),
        scaled: Vec::new(),
        applied: Vec::new(),
        components: resultant::Components::of(mesh, section.axisymmetric),
    };
    g.edge_loads(case, mesh, section, place, &mut res)?;
    let mut prescribed = boundary_conditions(case, mesh, place, &mut res, &mut g.scaled)?;
    g.forces(case, mesh, start, place, &mut res)?;
    let pretension_history = g.pretension(case, mesh, place, &mut res, &mut prescribed)?;
    let gap_history = g.gap_histories(case, place, &mut res)?;
    let temperatures = thermal::read(case, (mesh, &section), place, &mut res, &mut g.scaled)?;
    let speed = speed::read(case, mesh, (section, nd), place, &mut res, &mut g.scaled)?;
    if let Some(k) = res.used.iter().position(|&u| !u) {
        return Err(Error::input(
            format!("{place}: [history] {}", clip(res.named[k])),
            "is never used: no load, boundary, force, temperature, speed or gap_history names it (a misspelt name?); use it or remove it",
        ));
    }
    let histories = res.histories;
    if !histories.is_empty() && case.solver.load_factors.is_some() {
        return Err(Error::input(
            format!("{place}: [solver] load_factors"),
            "cannot be given with load histories ([history], or `history` / `gap_history` on a load, boundary, force or interface): the histories say how the loads change; remove load_factors",
        ));
    }
    for (at, v, range, h) in g.scaled {
        let peak = match h {
            Some(h) => histories[h].peak(),
            None => largest_factor(case, &histories),
        };
        check_scaled(range, &at, v, peak, h.is_some())?;
    }
    let largest = largest_factor(case, &histories);
    thermal::check_absolute(&temperatures, &histories, largest, place, &mesh.bodies)?;
    thermal::check_tables(&temperatures, &histories, largest, place, &mesh.bodies)?;
    let breakpoints = crate::model::history::breakpoints(&histories);
    check_step_count(case, &breakpoints, place)?;
    let (prescribed, prescribed_history) = prescribed.into_iter().unzip();
    Ok(Loads {
        histories,
        patterns: g.patterns,
        prescribed,
        prescribed_history,
        gap_history,
        acting: g.acting,
        pretension_history,
        applied: g.applied,
        components: g.components,
        temperatures,
        speed,
    })
}

/// What [`build`] gathers load by load: the patterns (one per history),
/// where each load acts, and every value a history scales, to be checked
/// against its range once the histories are known.
struct Gathered {
    patterns: Vec<LoadPattern>,
    /// Dofs of a pattern (the mesh's and the sections' reference nodes).
    nd: usize,
    acting: Vec<Acting>,
    scaled: Vec<Scaled>,
    applied: Vec<Applied>,
    components: resultant::Components,
}

impl Gathered {
    /// The `[[load]]` edge tractions.
    fn edge_loads(
        &mut self,
        case: &Case,
        mesh: &Mesh,
        section: Section,
        place: &str,
        res: &mut Resolver<'_>,
    ) -> Result<()> {
        for (i, ld) in case.load.iter().enumerate() {
            let at = match &ld.faces {
                Some(f) => format!("{place}: load[{i}] (faces \"{}\")", clip(f)),
                None => format!("{place}: load[{i}] (edges \"{}\")", clip(&ld.edges)),
            };
            let h = res.resolve(ld.history.as_ref(), &format!("{at} history"))?;
            let terms = match mesh.dim() {
                3 => faces::face_traction(ld, mesh, &at)?,
                _ => edge_traction(case, ld, mesh, section, &at)?,
            };
            add(pattern(&mut self.patterns, h, self.nd), &terms);
            self.applied.push(Applied {
                name: format!("load[{i}]"),
                kind: what::load(ld),
                selection: what::selection(
                    ld.faces.as_ref().unwrap_or(&ld.edges),
                    ld.faces.is_some(),
                    [&ld.x_range, &ld.y_range, &ld.z_range],
                ),
                history: h,
                resultant: resultant::resultant(&terms, mesh, self.components),
            });
            let scaled = &mut self.scaled;
            scaled.push((format!("{at} pressure"), ld.pressure, &ranges::PRESSURE, h));
            scaled.push((format!("{at} shear"), ld.shear, &ranges::PRESSURE, h));
            for &v in ld.traction.iter().flatten() {
                scaled.push((format!("{at} traction"), v, &ranges::PRESSURE, h));
            }
            // twist's loads about the axis, alike
            if let Some(v) = ld.hoop_shear {
                scaled.push((format!("{at} hoop_shear"), v, &ranges::PRESSURE, h));
            }
            if let Some(v) = ld.torque {
                let range = &crate::input::case::twist::TORQUE;
                scaled.push((format!("{at} torque"), v, range, h));
            }
            // a straight edge's round-off along its own direction is no load
            let big = terms.iter().fold(0.0f64, |a, t| a.max(t.1.abs()));
            self.acting.push(Acting {
                at,
                dofs: terms
                    .iter()
                    .filter(|t| t.1.abs() > 1e-12 * big)
                    .map(|t| t.0)
                    .collect(),
                concentrated: false,
            });
        }
        Ok(())
    }

    /// The `[[force]]` concentrated forces, on the nodes `start` marks.
    fn forces(
        &mut self,
        case: &Case,
        mesh: &Mesh,
        start: &[bool],
        place: &str,
        res: &mut Resolver<'_>,
    ) -> Result<()> {
        for (i, fs) in case.force.iter().enumerate() {
            let at = format!("{place}: force[{i}] (nodes \"{}\")", fs.nodes);
            let h = res.resolve(fs.history.as_ref(), &format!("{at} history"))?;
            let terms = concentrated_force(fs, mesh, start, &at)?;
            add(pattern(&mut self.patterns, h, self.nd), &terms);
            self.applied.push(Applied {
                name: format!("force[{i}]"),
                kind: what::force(fs, mesh.dim() == 3),
                selection: format!(
                    "nodes {}{}",
                    fs.nodes,
                    what::ranges([&fs.x_range, &fs.y_range, &fs.z_range])
                ),
                history: h,
                resultant: resultant::resultant(&terms, mesh, self.components),
            });
            self.scaled
                .push((format!("{at} fx"), fs.fx, &ranges::FORCE, h));
            self.scaled
                .push((format!("{at} fy"), fs.fy, &ranges::FORCE, h));
            self.scaled
                .push((format!("{at} fz"), fs.fz, &ranges::FORCE, h));
            self.acting.push(Acting {
                at,
                dofs: terms.iter().filter(|t| t.1 != 0.0).map(|t| t.0).collect(),
                concentrated: true,
            });
        }
        Ok(())
    }

    /// Each pretension section's force (a load on its reference node) or
    /// shortening (prescribed); its history.
    fn pretension(
        &mut self,
        case: &Case,
        mesh: &Mesh,
        place: &str,
        res: &mut Resolver<'_>,
        prescribed: &mut Vec<Prescribed>,
    ) -> Result<Vec<Option<usize>>> {
        let mut histories = Vec::new();
        for (k, ps) in case.pretension.iter().enumerate() {
            let at = format!("{place}: pretension[{k}] (\"{}\")", clip(&ps.name));
            let h = res.resolve(ps.history.as_ref(), &format!("{at} history"))?;
            let d = crate::model::pretension::dof(mesh.node_dofs, mesh.nodes.len(), k);
            if let Some(f) = ps.force {
                add(pattern(&mut self.patterns, h, self.nd), &[(d, f)]);
                self.scaled
                    .push((format!("{at} force"), f, &ranges::FORCE, h));
            }
            if let Some(v) = ps.shortening {
                prescribed.push(((d, v), h));
                let range = &ranges::DISPLACEMENT;
                self.scaled.push((format!("{at} shortening"), v, range, h));
            }
            // the reference node's other dofs (its second, and with twist
            // its third) are no unknowns
            for c in 1..mesh.node_dofs.per_node() {
                prescribed.push(((d + c, 0.0), None));
            }
            histories.push(h);
        }
        Ok(histories)
    }

    /// Each interface's gap history (a gap it scales must be given).
    fn gap_histories(
        &mut self,
        case: &Case,
        place: &str,
        res: &mut Resolver<'_>,
    ) -> Result<BTreeMap<String, usize>> {
        let mut gap_history = BTreeMap::new();
        for (name, spec) in &case.interface {
            let at = format!("{place}: [interface.{}] gap_history", clip(name));
            if let Some(h) = res.resolve(spec.gap_history.as_ref(), &at)? {
                if spec.gap == 0.0 {
                    return Err(Error::input(
                        at,
                        "is given, but the interface has no gap (gap = 0): a gap history scales `gap`; give the gap (negative: an interference) or remove gap_history",
                    ));
                }
                gap_history.insert(name.clone(), h);
                let at = format!("{place}: [interface.{}] gap", clip(name));
                self.scaled
                    .push((at, spec.gap, &ranges::DISPLACEMENT, Some(h)));
            }
        }
        Ok(gap_history)
    }
}

/// The largest magnitude a load without a history of its own reaches: the
/// largest load factor (a case without histories), or 1 (the default ramp).
fn largest_factor(case: &Case, histories: &[History]) -> f64 {
    match &case.solver.load_factors {
        Some(l) if histories.is_empty() => l.iter().fold(0.0, |a: f64, v| a.max(v.abs())),
        _ => 1.0,
    }
}

/// A load's value times the largest factor it is scaled by must still lie
/// within the range of its quantity (a history value of 10⁵ on a pressure of
/// 100 MPa is a pressure of 10⁷ MPa).
fn check_scaled(range: &Range, at: &str, v: f64, peak: f64, history: bool) -> Result<()> {
    let top = v.abs() * peak;
    if v == 0.0 || !v.is_finite() || range.admits(top) {
        return Ok(());
    }
    let by = if history {
        "the largest value of its history"
    } else {
        "the largest load factor"
    };
    Err(Error::input(
        at,
        format!("{v:e} times {peak:e} ({by}) = {}", range.refusal(top)),
    ))
}

/// A bound on the number of increments of any schedule: every history
/// breakpoint is an increment, and an automatic step control takes at least
/// (end time) / max_increment of them. At most
/// [`crate::model::history::MAX_BREAKPOINTS`] breakpoints and
/// [`crate::input::case::MAX_INCREMENTS`] increments (a run of 150 000 breakpoints
/// would run for hours).
fn check_step_count(case: &Case, breakpoints: &[f64], place: &str) -> Result<()> {
    let most = crate::input::case::MAX_INCREMENTS;
    let times = breakpoints.len().saturating_sub(1);
    if times > crate::model::history::MAX_BREAKPOINTS {
        return Err(Error::input(
            format!("{place}: [history]"),
            format!(
                "the histories have {times} distinct times after 0, each an increment of the run: at most {} (a thousand load cycles take 4 000)",
                crate::model::history::MAX_BREAKPOINTS
            ),
        ));
    }
    let end = breakpoints.last().copied().unwrap_or(1.0).max(1.0);
    if let Some(n) = crate::model::schedule::planned(&case.solver, breakpoints) {
        if n > most {
            // the steps per unit of pseudo-time: `--increments`, else the
            // case's (or the default) under fixed steps `--step-control`
            // may have asked for
            let key = "[solver] increments";
            let at = match (case.option(key), case.option("[solver] step_control")) {
                (Some(o), _) => o.to_string(),
                (None, Some(o)) => format!("{o} ({place}: {key})"),
                (None, None) => case.at(key),
            };
            return Err(Error::input(
                at,
                format!(
                    "{} steps per unit of pseudo-time through the histories (to t = {end}) make {n} increments, more than {most}",
                    case.solver.n_increments(),
                ),
            ));
        }
    } else if let Some(m) = case.solver.max_increment {
        let n = (end / m).ceil();
        if n > most as f64 {
            return Err(Error::input(
                case.at("[solver] max_increment"),
                format!(
                    "{m} takes at least {n} increments to reach t = {end}, more than {most}: raise max_increment"
                ),
            ));
        }
    }
    Ok(())
}

/// Adds (dof, value) terms to a force vector.
fn add(f: &mut [f64], terms: &[(usize, f64)]) {
    for &(d, v) in terms {
        f[d] += v;
    }
}

/// Every load acts once the prescribed dofs are known: a `[[force]]` on a
/// prescribed dof (a radial force on the axis of an axisymmetric model
/// included, where u_r = 0 holds) goes straight into the reaction, and an
/// edge traction all of whose dofs are prescribed never acts; both are
/// refused, naming the load and the node.
pub(crate) fn check_acting(
    acting: &[Acting],
    mesh: &Mesh,
    prescribed: &[(usize, f64)],
    axisymmetric: bool,
) -> Result<()> {
    let held: std::collections::HashSet<usize> = prescribed.iter().map(|p| p.0).collect();
    for a in acting {
        if a.concentrated {
            if let Some(&d) = a.dofs.iter().find(|d| held.contains(d)) {
                let (n, c) = mesh.node_dofs.node_of(d);
                let x = mesh.nodes[n];
                let on_axis = axisymmetric
                    && c == 0
                    && x[0].abs() <= crate::model::consistency::tolerance(mesh);
                let what = if on_axis {
                    format!(
                        "acts along r on node {n} at ({}, {}) on the axis r = 0, where u_r = 0 holds by symmetry: a radial force there acts on nothing; remove fx or select nodes off the axis (x_range)",
                        x[0], x[1]
                    )
                } else {
                    format!(
                        "acts on node {n} at {}, whose u{} is prescribed by a [[boundary]] (or the symmetry plane): a force on a prescribed displacement goes into the reaction and never acts; remove the force or the support there (x_range / y_range select nodes)",
                        point(x, mesh.dim() == 3),
                        ["x", "y", "z"][c]
                    )
                };
                return Err(Error::input(
                    format!("{} f{}", a.at, ["x", "y", "z"][c]),
                    what,
                ));
            }
        } else if !a.dofs.is_empty() && a.dofs.iter().all(|d| held.contains(d)) {
            return Err(Error::input(
                    &a.at,
                    "loads only prescribed displacements: every node and direction it pushes is held by a [[boundary]] (or the axis / symmetry plane), so it goes into the reactions and never acts",
                ));
        }
    }
    Ok(())
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

pub(crate) fn in_range(v: f64, r: &Option<[f64; 2]>) -> bool {
    r.is_none_or(|[lo, hi]| v >= lo - 1e-9 && v <= hi + 1e-9)
}

/// A uniform pressure and shear on an edge set, integrated consistently
/// (3-point Gauss on the quadratic edge): its (dof, force) terms at factor 1.
/// Refused where it cannot act as written: every selected edge on the axis
/// r = 0 of an axisymmetric model (no area), or, on a symmetric half model, a
/// traction with an x-component at the symmetry plane x = 0 (its mirror image
/// carries the opposite one: an antisymmetric load the half does not model).
fn edge_traction(
    case: &Case,
    ld: &crate::input::case::LoadSpec,
    mesh: &Mesh,
    section: Section,
    at: &str,
) -> Result<Vec<(usize, f64)>> {
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
    if case.adapt.is_some() {
        adaptive::check_edges(mesh, edges, [&ld.x_range, &ld.y_range], at)?;
    }
    let (p, tau) = (ld.pressure, ld.shear);
    // twist: τ_θ given, or a torque (τ_θ = T r / ∫ r² dA below)
    let hoop = ld.hoop_shear.or(ld.torque);
    if !p.is_finite() || (p == 0.0 && tau == 0.0 && hoop.is_none()) {
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
    let tol = crate::model::consistency::tolerance(mesh);
    let mut acc = Traction::default();
    let (mut count, mut on_axis) = (0, 0);
    for edge in edges {
        let x: Vec<[f64; 2]> = edge.iter().map(|&n| mesh.xy(n)).collect();
        if !(in_range(x[1][0], &ld.x_range) && in_range(x[1][1], &ld.y_range)) {
            continue;
        }
        count += 1;
        if section.axisymmetric && x.iter().all(|y| y[0].abs() <= tol) {
            on_axis += 1;
            continue;
        }
        if case.model.symmetric_half {
            if x.iter().all(|y| y[0].abs() <= tol) {
                return Err(Error::input(
                    at,
                    format!(
                        "loads the edge from ({}, {}) to ({}, {}) on the symmetry plane x = 0 of a symmetric_half model: the plane is inside the whole body, not a surface of it; load a surface of the body",
                        x[0][0], x[0][1], x[2][0], x[2][1]
                    ),
                ));
            }
            symmetric_traction(ld, &x, tol, at)?;
        }
        acc.add_edge(edge, &x, [p, tau], hoop.is_some(), section, mesh.node_dofs);
    }
    let Traction {
        mut terms,
        hoop_terms,
        torque_terms,
        moment,
    } = acc;
    if count == 0 {
        return Err(Error::input(
            at,
            selects_none("edge", edges.is_empty(), false),
        ));
    }
    if on_axis == count {
        return Err(Error::input(
            at,
            if ld.torque.is_some() {
                "is a torque on the axis: every edge it selects lies on the axis r = 0, where a traction acts on no area and has no lever arm; load a surface of the body instead"
            } else {
                "every edge it selects lies on the axis r = 0 of the axisymmetric model, where a traction acts on no area: load a surface of the body instead"
            },
        ));
    }
    if let Some(h) = hoop {
        // a uniform τ_θ, or the torque's τ_θ = T r / ∫ r² dA: ∫ r τ_θ dA = T,
        // the end face shear of an elastic shaft (uniform on a cylinder)
        let (per, scale) = match ld.torque {
            Some(t) => (torque_terms, t / moment),
            None => (hoop_terms, h),
        };
        terms.extend(per.into_iter().map(|(d, v)| (d, scale * v)));
    }
    Ok(terms)
}

/// The nodal forces of an edge load, gathered edge by edge; with twist also
/// the u_θ forces of a unit τ_θ and of a unit τ_θ / r (a torque's traction),
/// and ∫ r² dA of the edges.
#[derive(Default)]
struct Traction {
    terms: Vec<(usize, f64)>,
    hoop_terms: Vec<(usize, f64)>,
    torque_terms: Vec<(usize, f64)>,
    moment: f64,
}

impl Traction {
    /// Adds the edge [end, mid, end] at `x` under pressure p and shear τ
    /// (`[p, tau]`), by 3-point Gauss along it: with the body on the left,
    /// the outward normal × ds is (t_y, −t_x) dξ, the pressure pushes
    /// inward, the shear direction (n_y, −n_x) × ds is (−t_x, −t_y) dξ.
    fn add_edge(
        &mut self,
        edge: &[usize; 3],
        x: &[[f64; 2]],
        [p, tau]: [f64; 2],
        hoop: bool,
        section: Section,
        nd: crate::input::mesh::NodeDofs,
    ) {
        for (s, w) in crate::physics::element::edge::gauss_1d(3) {
            let n = crate::physics::element::edge::shape(s);
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
            for k in 0..3 {
                if p != 0.0 {
                    self.terms
                        .push((nd.dof(edge[k], 0), -p * n[k] * ty * w * measure));
                    self.terms
                        .push((nd.dof(edge[k], 1), p * n[k] * tx * w * measure));
                }
                if tau != 0.0 {
                    self.terms
                        .push((nd.dof(edge[k], 0), -tau * n[k] * tx * w * measure));
                    self.terms
                        .push((nd.dof(edge[k], 1), -tau * n[k] * ty * w * measure));
                }
                if hoop {
                    let ds = tx.hypot(ty) * w;
                    self.hoop_terms
                        .push((nd.dof(edge[k], 2), n[k] * ds * measure));
                    let lever = n[k] * xg[0] * ds * measure;
                    self.torque_terms.push((nd.dof(edge[k], 2), lever));
                    self.moment += n[k] * xg[0] * xg[0] * ds * measure;
                }
            }
        }
    }
}

/// On a symmetric half model, the traction at an edge end on the plane x = 0
/// must have no x-component (the symmetric whole body's traction is odd in
/// x there).
fn symmetric_traction(
    ld: &crate::input::case::LoadSpec,
    x: &[[f64; 2]],
    tol: f64,
    at: &str,
) -> Result<()> {
    for (k, s) in [(0, -1.0), (2, 1.0)] {
        if x[k][0].abs() > tol {
            continue;
        }
        let dn = [s - 0.5, -2.0 * s, s + 0.5];
        let (mut tx, mut ty) = (0.0, 0.0);
        for j in 0..3 {
            tx += dn[j] * x[j][0];
            ty += dn[j] * x[j][1];
        }
        let len = tx.hypot(ty);
        let t_x = (-ld.pressure * ty - ld.shear * tx) / len;
        if t_x.abs() > 1e-9 * (ld.pressure.abs() + ld.shear.abs()) {
            return Err(Error::input(
                at,
                format!(
                    "pushes along x ({t_x:.4} MPa) at ({}, {}) on the symmetry plane x = 0 of a symmetric_half model: the mirrored half would carry the opposite traction, an antisymmetric load the half model does not represent; model the whole body (symmetric_half = false)",
                    x[k][0], x[k][1]
                ),
            ));
        }
    }
    Ok(())
}

/// A force (fx, fy) at every selected node of a node set that `start`
/// marks: its (dof, force) terms at factor 1. An adaptive run's refined
/// set holds more nodes than its start mesh's, but the force stays on the
/// start mesh's nodes: the same load on every cycle.
fn concentrated_force(
    fs: &crate::input::case::ForceSpec,
    mesh: &Mesh,
    start: &[bool],
    at: &str,
) -> Result<Vec<(usize, f64)>> {
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
    for (key, v) in [("fx", fs.fx), ("fy", fs.fy), ("fz", fs.fz)] {
        if !v.is_finite() {
            return Err(Error::input(
                format!("{at} {key}"),
                format!("{v} is not a finite number (N)"),
            ));
        }
    }
    let solid = mesh.dim() == 3;
    if fs.fx == 0.0 && fs.fy == 0.0 && fs.fz == 0.0 {
        return Err(Error::input(
            at,
            if solid {
                "fx, fy and fz are all 0: give a non-zero force (N)"
            } else {
                "fx and fy are both 0: give a non-zero force (N)"
            },
        ));
    }
    let mut terms = Vec::new();
    let ranges = [&fs.x_range, &fs.y_range, &fs.z_range];
    for &n in nodes.iter().filter(|&&n| start[n]) {
        let x = mesh.nodes[n];
        if (0..3).all(|c| in_range(x[c], ranges[c])) {
            let nd = mesh.node_dofs;
            terms.extend([(nd.dof(n, 0), fs.fx), (nd.dof(n, 1), fs.fy)]);
            if solid {
                terms.push((nd.dof(n, 2), fs.fz));
            }
        }
    }
    if terms.is_empty() {
        return Err(Error::input(
            at,
            selects_none("node", nodes.is_empty(), mesh.dim() == 3),
        ));
    }
    Ok(terms)
}

/// A value that a factor scales: where it is written, the value, its range
/// and its history.
type Scaled = (String, f64, &'static Range, Option<usize>);

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
    scaled: &mut Vec<Scaled>,
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
        if bc.ux.is_none() && bc.uy.is_none() && bc.uz.is_none() && bc.rotation.is_none() {
            return Err(Error::input(
                &at,
                if case.model.twist {
                    "give ux, uy and/or rotation"
                } else if mesh.dim() == 3 {
                    "give ux, uy and/or uz"
                } else {
                    "give ux and/or uy"
                },
            ));
        }
        if case.adapt.is_some() {
            adaptive::check_nodes(mesh, nodes, [&bc.x_range, &bc.y_range], &at)?;
        }
        let h = res.resolve(bc.history.as_ref(), &format!("{at} history"))?;
        if h.is_some()
            && [bc.ux, bc.uy, bc.uz, bc.rotation]
                .iter()
                .flatten()
                .all(|&v| v == 0.0)
        {
            return Err(Error::input(
                format!("{at} history"),
                "is given, but every displacement of this boundary is 0: a history scales the prescribed value and scales nothing here (a support stays fixed without one); remove it, or give the history to the load it belongs to",
            ));
        }
        for (k, v) in [("ux", bc.ux), ("uy", bc.uy), ("uz", bc.uz)] {
            if let Some(v) = v.filter(|v| v.is_finite()) {
                scaled.push((format!("{at} {k}"), v, &ranges::DISPLACEMENT, h));
            }
        }
        if let Some(phi) = bc.rotation {
            scaled.push((
                format!("{at} rotation"),
                phi,
                &crate::input::case::twist::ROTATION,
                h,
            ));
        }
        let mut count = 0;
        let ranges = [&bc.x_range, &bc.y_range, &bc.z_range];
        for &n in nodes {
            let x = mesh.nodes[n];
            if !(0..3).all(|c| in_range(x[c], ranges[c])) {
                continue;
            }
            count += 1;
            // a prescribed rotation φ about the axis is u_θ = φ r (twist);
            // the third dof is u_z in 3D
            let third = bc.rotation.map(|phi| phi * x[0]).or(bc.uz);
            for (c, v) in [bc.ux, bc.uy, third].iter().enumerate() {
                let Some(v) = *v else { continue };
                if !v.is_finite() {
                    return Err(Error::input(&at, format!("displacement {v} is not finite")));
                }
                let (first, fh, j) = *out.entry(mesh.node_dofs.dof(n, c)).or_insert((v, h, i));
                if first != v || fh != h {
                    let set = clip(&case.boundary[j].set);
                    let solid = mesh.dim() == 3;
                    return Err(twice_prescribed(&at, n, x, c, (v, first), j, &set, solid));
                }
            }
        }
        if count == 0 {
            return Err(Error::input(
                &at,
                selects_none("node", nodes.is_empty(), mesh.dim() == 3),
            ));
        }
    }
    Ok(out.into_iter().map(|(d, (v, h, _))| ((d, v), h)).collect())
}

/// The refusal of a node and direction prescribed twice: by `at` with v,
/// and before by boundary[j] (set `set`) with `first` (another value, or
/// the same with another history).
#[allow(clippy::too_many_arguments)]
fn twice_prescribed(
    at: &str,
    n: usize,
    x: [f64; 3],
    c: usize,
    (v, first): (f64, f64),
    j: usize,
    set: &str,
    solid: bool,
) -> Error {
    let axis = if solid {
        ["x", "y", "z"][c]
    } else {
        ["x", "y", "θ"][c]
    };
    // the key of u_θ is the rotation (u_θ = φ r)
    let key = if c == 2 && !solid {
        "rotation".to_string()
    } else {
        format!("u{axis}")
    };
    let what = if first != v {
        format!("u{axis} = {v}, but boundary[{j}] (set \"{set}\") already gives it {first}")
    } else {
        format!("u{axis} with another history than boundary[{j}] (set \"{set}\")")
    };
    Error::input(
        format!("{at} {key}"),
        format!(
            "gives node {n} at {} {what}: one prescribed value per node and direction",
            point(x, solid)
        ),
    )
}

/// A node's position in a message: (x, y), or (x, y, z) in 3D.
pub(crate) fn point(x: [f64; 3], solid: bool) -> String {
    if solid {
        format!("({}, {}, {})", x[0], x[1], x[2])
    } else {
        format!("({}, {})", x[0], x[1])
    }
}

/// Why a load or support selects nothing: its filters, or a set that is
/// empty (a side of a block wholly shared with another block of its body,
/// [`crate::input::mesh::blocks`]).
fn selects_none(what: &str, empty_set: bool, solid: bool) -> String {
    if empty_set {
        format!("selects no {what}: the set is empty (a side that another block of its body shares all along is inside the body)")
    } else {
        format!(
            "selects no {what} (check x_range / y_range{})",
            if solid { " / z_range" } else { "" }
        )
    }
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

#[cfg(test)]
mod tests {
    use crate::model::Model;

    /// A twisting shaft off the axis, held at its bottom, loaded by `load`
    /// (a `[[load]]`, `[[force]]` or `[[boundary]]` table) and `solver`.
    fn shaft(load: &str, solver: &str) -> crate::error::Result<Model> {
        let text = format!(
            r#"
[model]
plane = "axisymmetric"
twist = true

[[mesh.block]]
body = "shaft"
x = [1.0, 10.0]
nx = [2]
y = [0.0, 20.0]
ny = [2]

[materials.shaft]
young = 206000.0
poisson = 0.3

[[boundary]]
set = "shaft.bottom"
uy = 0.0
rotation = 0.0

{load}

[solver]
{solver}
"#
        );
        Model::parse(&text, "case.toml")
    }

    /// Every value a history or a load factor scales is range-checked times
    /// the largest of them, twist's torque and hoop shear as the pressure
    /// (they escaped the check until issue 42): each value below is within
    /// its range and 10⁵ times it is not.
    #[test]
    fn every_scaled_load_is_range_checked_times_its_largest_factor() {
        let loads = [
            (
                "pressure",
                "[[load]]\nedges = \"shaft.top\"\npressure = 100.0",
            ),
            ("shear", "[[load]]\nedges = \"shaft.top\"\nshear = 100.0"),
            (
                "hoop_shear",
                "[[load]]\nedges = \"shaft.top\"\nhoop_shear = 100.0",
            ),
            ("torque", "[[load]]\nedges = \"shaft.top\"\ntorque = 1e14"),
            ("fx", "[[force]]\nnodes = \"shaft.top\"\nfx = 1e8"),
            ("uy", "[[boundary]]\nset = \"shaft.top\"\nuy = 1.0"),
            (
                "rotation",
                "[[boundary]]\nset = \"shaft.top\"\nrotation = 0.1",
            ),
        ];
        for (key, load) in loads {
            // the value alone is sound
            shaft(load, "increments = 1").unwrap_or_else(|e| panic!("{key}: {e}"));
            for (by, with, solver) in [
                (
                    "history",
                    "\nhistory = [[0.0, 0.0], [1.0, 1e5]]",
                    "increments = 1",
                ),
                ("load factor", "", "load_factors = [1.0, 1e5]"),
            ] {
                let e = shaft(&format!("{load}{with}"), solver)
                    .err()
                    .unwrap_or_else(|| panic!("{key} times a {by} of 1e5 was accepted"))
                    .to_string();
                assert!(
                    e.contains(&format!("{key}: ")) && e.contains("times 1e5"),
                    "{key} by a {by}: {e}"
                );
            }
        }
    }

    /// Each load's resultant is its closed form: an axial pressure on the
    /// annulus r ∈ [1, 10] is p π (10² − 1²) along z, a torque load its
    /// torque, a hoop shear τ 2π ∫ r² dr, a radial force per node n f; with
    /// a history the resultant at t is h(t) times it (`Model::applied_at`).
    #[test]
    fn resultants_of_axisymmetric_loads_are_their_closed_forms() {
        let pi = std::f64::consts::PI;
        let cases: [(&str, [f64; 3]); 4] = [
            (
                "[[load]]\nedges = \"shaft.top\"\npressure = 2.0",
                [0.0, -2.0 * pi * 99.0, 0.0],
            ),
            (
                "[[load]]\nedges = \"shaft.top\"\ntorque = 5e5",
                [0.0, 0.0, 5e5],
            ),
            (
                "[[load]]\nedges = \"shaft.top\"\nhoop_shear = 3.0",
                [0.0, 0.0, 3.0 * 2.0 * pi * (1000.0 - 1.0) / 3.0],
            ),
            (
                "[[force]]\nnodes = \"shaft.top\"\nfy = 7.0",
                [0.0, 7.0 * 5.0, 0.0],
            ),
        ];
        for (load, want) in cases {
            let text = format!("{load}\nhistory = [[0.0, 0.0], [2.0, 1.0]]");
            let m =
                shaft(&text, "step_control = \"auto\"").unwrap_or_else(|e| panic!("{load}: {e}"));
            assert_eq!(m.applied.len(), 1);
            let r = &m.applied[0].resultant;
            for c in 0..3 {
                let scale = want.iter().fold(1.0f64, |a, w| a.max(w.abs()));
                assert!(
                    (r[c] - want[c]).abs() <= 1e-12 * scale,
                    "{load}: {r:?} against {want:?}"
                );
            }
            let half = m.applied_at(0, 1.0);
            assert!(
                (half[1] - 0.5 * r[1]).abs() <= 1e-15 * r[1].abs() + 1e-300,
                "{load}: {half:?}"
            );
        }
    }

    /// In 3D a uniform traction t on a face of area A is F = t A and its
    /// moment about the origin x_c × F (the face's centre x_c).
    #[test]
    fn a_traction_on_a_face_in_space_has_force_and_moment() {
        let text = r#"
[model]
plane = "3d"

[[mesh.block]]
body = "b"
x = [1.0, 3.0]
nx = [2]
y = [0.0, 4.0]
ny = [2]

[mesh.extrude]
z = [0.0, 5.0]
nz = [2]

[materials.b]
young = 206000.0
poisson = 0.3

[[boundary]]
set = "b.bottom"
ux = 0.0
uy = 0.0
uz = 0.0

[[load]]
faces = "b.top"
traction = [1.0, 0.0, 2.0]
"#;
        let m = Model::parse(text, "case.toml").unwrap();
        let r = &m.applied[0].resultant;
        // the top face y = 4: x in [1, 3], z in [0, 5], area 10, centre (2, 4, 2.5)
        let f = [10.0, 0.0, 20.0];
        let c = [2.0, 4.0, 2.5];
        let moment = [
            c[1] * f[2] - c[2] * f[1],
            c[2] * f[0] - c[0] * f[2],
            c[0] * f[1] - c[1] * f[0],
        ];
        let want = [f[0], f[1], f[2], moment[0], moment[1], moment[2]];
        for k in 0..6 {
            assert!((r[k] - want[k]).abs() < 1e-10, "{r:?} against {want:?}");
        }
    }
}
