//! Checks of a parsed case that need no mesh: numbers in range, laws complete,
//! parameters that belong to another law rejected.

use super::ranges;
use super::Weights;
use super::{BackboneKind, Case, InterfaceLawSpec, TangentialSpec};
use crate::error::{Error, Result};
use crate::input::case::settings::FrictionScheme;
use crate::physics::contact::{normal, Backbone, NormalLaw, TangentialLaw};
use std::collections::BTreeMap;

mod tangential;
use tangential::tangential_law;
pub(crate) use tangential::{backbone_keys, memory_error_key};

/// Most elements a case may have (all blocks, after `refine`): far beyond any
/// case this serial-first solver is meant for, and a bound on the memory that a
/// case file can make the model take before anything is solved.
pub(crate) const MAX_ELEMENTS: usize = 250_000;
/// Most scheduled load steps (`increments`, or entries of `load_factors`).
pub(crate) const MAX_INCREMENTS: usize = 100_000;
/// Most halvings of one scheduled step (2^-50 of a step is below any tolerance).
pub(crate) const MAX_CUTBACKS: usize = 50;
/// Most iterations per attempt.
pub(crate) const MAX_ITERATIONS: usize = 100_000;
/// Deepest Anderson history.
pub(crate) const MAX_ANDERSON_DEPTH: usize = 100;

/// What validation derives from the case.
pub struct Checked {
    pub laws: BTreeMap<String, NormalLaw>,
    pub tangential: BTreeMap<String, (TangentialLaw, FrictionScheme)>,
}

/// `plane = "axisymmetric"`: the body is the full revolution, so no thickness,
/// and no half model about x = 0 (the axis is not a symmetry plane).
fn check_axisymmetric(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    if case.model.plane != crate::physics::material::Plane::Axisymmetric {
        return Ok(());
    }
    if let Some(t) = case.model.thickness.0 {
        return Err(Error::input(
            at("[model] thickness"),
            format!("thickness = {t} is not allowed with plane = \"axisymmetric\": the model is the full revolution about x = 0 (forces and areas are for the whole body); remove the key"),
        ));
    }
    if case.model.symmetric_half {
        return Err(Error::input(
            at("[model] symmetric_half"),
            "is true, but plane = \"axisymmetric\": an axisymmetric model is already the whole body of revolution about x = r = 0 (the axis is not a symmetry plane); remove the key",
        ));
    }
    Ok(())
}

/// Validates everything that does not depend on the mesh.
pub fn check_case(case: &Case) -> Result<Checked> {
    // a key the command line set is named by its option (`Case::at`)
    let at = |key: &str| case.at(key);
    check_model_and_mesh(case, &at)?;
    crate::input::case::solid::check_case(case, &at)?;
    crate::input::case::twist::check_case(case, &at)?;
    crate::input::case::cyclic::check_case(case, &at)?;
    check_element_count(case, &at)?;
    check_names(case, &at)?;
    check_block_coordinates(case, &at)?;
    check_curved_sides(case, &at)?;
    check_load_magnitudes(case, &at)?;
    check_materials(case, &at)?;
    let (laws, tangential) = interface_laws(case, &at)?;
    check_solver(case, &at)?;
    super::outputs::check(case, &at)?;
    super::rating::check(&case.rating, &at)?;
    super::adapt::check(case, &at)?;
    Ok(Checked { laws, tangential })
}

/// The case name, the plane and thickness, and how the mesh is given.
fn check_model_and_mesh(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    if let Some(name) = &case.name {
        if !plain_folder_name(name) {
            return Err(Error::input(
                at("name"),
                format!("{name:?} is not a plain folder name (it names out/<name>/: not empty, at most {MAX_NAME_BYTES} bytes, no / or \\, not . or .., no control characters)"),
            ));
        }
    }
    check_axisymmetric(case, &at)?;
    let t = case.model.thickness.value();
    if !(t.is_finite() && t > 0.0) {
        return Err(Error::input(
            at("[model] thickness"),
            format!("{t} must be a positive number (mm)"),
        ));
    }
    ranges::THICKNESS.check(at("[model] thickness"), t)?;
    if case.mesh.refine == 0 {
        return Err(Error::input(at("[mesh] refine"), "must be at least 1"));
    }
    if case.mesh.file.is_some() {
        if !case.mesh.block.is_empty() {
            return Err(Error::input(
                at("[mesh]"),
                "give either file or [[mesh.block]], not both",
            ));
        }
        if case.mesh.refine != 1 {
            return Err(Error::input(
                at("[mesh] refine"),
                match case.option("[mesh] refine") {
                    Some(_) => {
                        "cannot refine a mesh read from a file ([mesh] file); refine it in Gmsh"
                            .to_string()
                    }
                    None => format!(
                        "{} cannot refine a mesh read from a file; refine it in Gmsh",
                        case.mesh.refine
                    ),
                },
            ));
        }
    }
    if let Some(r) = &case.mesh.refine_region {
        check_refine_region(r, &at)?;
    }
    Ok(())
}

/// `[mesh] refine_region`: a box of finite, increasing bounds and 1 to
/// [`MAX_REFINE_LEVELS`] levels (that it holds an element is checked on the
/// mesh, [`crate::input::mesh::refine`]).
fn check_refine_region(
    r: &crate::input::case::RefineRegion,
    at: &dyn Fn(&str) -> String,
) -> Result<()> {
    let place = at("[mesh] refine_region");
    for (name, [lo, hi]) in [("x", r.x), ("y", r.y)] {
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(Error::input(
                &place,
                format!("{name} = [{lo}, {hi}] must be two finite numbers, the first the smaller"),
            ));
        }
    }
    if !(1..=MAX_REFINE_LEVELS).contains(&r.levels) {
        return Err(Error::input(
            &place,
            format!(
                "levels = {} must be 1 to {MAX_REFINE_LEVELS} (each level splits an element into four)",
                r.levels
            ),
        ));
    }
    Ok(())
}

/// The most levels of `[mesh] refine_region` (4⁶ = 4096 children per element).
pub(crate) const MAX_REFINE_LEVELS: usize = 6;

/// Every block breakpoint within [`ranges::COORDINATE`].
fn check_block_coordinates(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    for b in &case.mesh.block {
        for (axis, v) in
            b.x.iter()
                .map(|v| ("x", v))
                .chain(b.y.iter().map(|v| ("y", v)))
        {
            ranges::COORDINATE.check(
                at(&format!("[[mesh.block]] \"{}\" {axis}", clip(b.name()))),
                *v,
            )?;
        }
    }
    Ok(())
}

/// Prescribed displacements, tractions, forces and the probe within their
/// ranges (their products with a history: [`crate::model::loads`]).
fn check_load_magnitudes(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    for (i, bc) in case.boundary.iter().enumerate() {
        for (k, v) in [("ux", bc.ux), ("uy", bc.uy)] {
            ranges::DISPLACEMENT.check(at(&format!("boundary[{i}] {k}")), v.unwrap_or(0.0))?;
        }
    }
    for (i, ld) in case.load.iter().enumerate() {
        ranges::PRESSURE.check(at(&format!("load[{i}] pressure")), ld.pressure)?;
        ranges::PRESSURE.check(at(&format!("load[{i}] shear")), ld.shear)?;
    }
    for (i, f) in case.force.iter().enumerate() {
        for (k, v) in [("fx", f.fx), ("fy", f.fy)] {
            ranges::FORCE.check(at(&format!("force[{i}] {k}")), v)?;
        }
    }
    for v in case.output.probe {
        ranges::COORDINATE.check(at("[output] probe"), v)?;
    }
    Ok(())
}

/// Every material's constants finite and within their ranges.
fn check_materials(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    for (body, m) in &case.materials {
        let key = format!("[materials.{body}]");
        for (name, v) in [
            ("young", m.young),
            ("poisson", m.poisson),
            ("hardening", m.hardening),
        ] {
            if !v.is_finite() {
                return Err(Error::input(
                    at(&format!("{key} {name}")),
                    format!("{v} is not a finite number"),
                ));
            }
        }
        if let Some(y) = m.yield_stress {
            if !(y.is_finite() && y > 0.0) {
                return Err(Error::input(
                    at(&format!("{key} yield_stress")),
                    format!("{y} must be a positive number (MPa); omit it for an elastic body"),
                ));
            }
        }
        for (name, v, range) in [
            ("young", m.young, &ranges::MODULUS),
            (
                "yield_stress",
                m.yield_stress.unwrap_or(0.0),
                &ranges::YIELD_STRESS,
            ),
            ("hardening", m.hardening, &ranges::HARDENING),
        ] {
            range.check(at(&format!("{key} {name}")), v)?;
        }
        if let Some(a) = m.expansion {
            if !(a.is_finite() && a >= 0.0) {
                return Err(Error::input(
                    at(&format!("{key} expansion")),
                    format!("{a} must be a non-negative number (1/K)"),
                ));
            }
            ranges::EXPANSION.check(at(&format!("{key} expansion")), a)?;
        }
        if let Some(rho) = m.density {
            if !(rho.is_finite() && rho > 0.0) {
                return Err(Error::input(
                    at(&format!("{key} density")),
                    format!("{rho} must be a positive number (kg/m³)"),
                ));
            }
            ranges::DENSITY.check(at(&format!("{key} density")), rho)?;
        }
        for (name, table, range) in [
            ("young_table", &m.young_table, &ranges::MODULUS),
            ("yield_table", &m.yield_table, &ranges::YIELD_STRESS),
        ] {
            if let Some(rows) = table {
                property_table(&at(&format!("{key} {name}")), rows, range)?;
            }
        }
        if m.yield_table.is_some() && m.yield_stress.is_none() {
            return Err(Error::input(
                at(&format!("{key} yield_table")),
                "belongs to a body that yields: give yield_stress (its value at the reference temperature) too",
            ));
        }
    }
    Ok(())
}

/// A material property against temperature: at least two rows [T °C, value],
/// T finite, above absolute zero, at most 10⁴ °C and strictly rising, every
/// value positive and within its range.
fn property_table(at: &str, rows: &[Vec<f64>], range: &ranges::Range) -> Result<()> {
    if let Some(i) = rows.iter().position(|r| r.len() != 2) {
        return Err(Error::input(
            at,
            format!(
                "row {i} has {} number(s): each row is [T °C, value]",
                rows[i].len()
            ),
        ));
    }
    let rows: Vec<[f64; 2]> = rows.iter().map(|r| [r[0], r[1]]).collect();
    if rows.len() < 2 {
        return Err(Error::input(
            at,
            format!(
                "has {} row(s): give at least two [T °C, value] rows",
                rows.len()
            ),
        ));
    }
    for (i, &[t, v]) in rows.iter().enumerate() {
        if !(t.is_finite() && (ranges::ABSOLUTE_ZERO..=1e4).contains(&t)) {
            return Err(Error::input(
                at,
                format!("row {i}: {t} °C is no temperature of a solid (in [-273.15, 1e4] °C)"),
            ));
        }
        if i > 0 && t <= rows[i - 1][0] {
            return Err(Error::input(
                at,
                format!("row {i}: {t} °C does not rise from row {}'s {} °C: give the rows in rising temperature, each once", i - 1, rows[i - 1][0]),
            ));
        }
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::input(
                at,
                format!("row {i}: {v} must be a positive number ({})", range.unit),
            ));
        }
        range.check(format!("{at} row {i}"), v)?;
    }
    Ok(())
}

/// The normal law of every `[interface.<name>]`, and its tangential law if it
/// has one, each checked.
#[allow(clippy::type_complexity)]
fn interface_laws(
    case: &Case,
    at: &dyn Fn(&str) -> String,
) -> Result<(
    BTreeMap<String, NormalLaw>,
    BTreeMap<String, (TangentialLaw, FrictionScheme)>,
)> {
    let mut laws = BTreeMap::new();
    let mut tangential = BTreeMap::new();
    for (name, spec) in &case.interface {
        let key = format!("[interface.{name}]");
        if spec.weights == Weights::Mortar
            && !case
                .mesh
                .interface
                .iter()
                .any(|i| &i.name == name && i.matching == Some(false))
        {
            return Err(Error::input(
                at(&format!("{key} weights")),
                "\"mortar\" couples two sides meshed apart: it needs matching = false on the [[mesh.interface]] of that name (a matching interface takes \"lumped\" or \"consistent\")",
            ));
        }
        // every column within the range of its scalar parameter, before the
        // table is interpolated (a 1e-300 pressure would otherwise surface as
        // a slope message, or not at all)
        let given = spec.law_params();
        for p in normal::all_params() {
            if let normal::Holds::Rows(columns) = p.holds {
                for (i, row) in given.rows(p.key).iter().enumerate() {
                    if let [u, v] = row.as_slice() {
                        for ((name, range), x) in columns.iter().zip([u, v]) {
                            range
                                .check(at(&format!("{key} {} row {} {name}", p.key, i + 1)), *x)?;
                        }
                    }
                }
            }
        }
        let law = normal_law(spec).map_err(|m| Error::input(at(&key), m))?;
        if !spec.gap.is_finite() {
            return Err(Error::input(
                at(&format!("{key} gap")),
                "must be a finite number (mm)",
            ));
        }
        if let Some(p) = spec.start_pressure {
            if !(p.is_finite() && p > 0.0) {
                return Err(Error::input(
                    at(&format!("{key} start_pressure")),
                    format!("{p} must be positive (MPa)"),
                ));
            }
        }
        // the law's numbers within their ranges (another law's keys were refused)
        for p in normal::all_params() {
            if let normal::Holds::Number(Some(range)) = p.holds {
                if given.has(p.key) {
                    range.check(at(&format!("{key} {}", p.key)), given.number(p.key))?;
                }
            }
        }
        for (k, v, range) in [
            ("gap", Some(spec.gap), &ranges::DISPLACEMENT),
            ("start_pressure", spec.start_pressure, &ranges::PRESSURE),
        ] {
            range.check(at(&format!("{key} {k}")), v.unwrap_or(0.0))?;
        }
        laws.insert(name.clone(), law);
        if let Some(t) = &spec.tangential {
            let law = tangential_law(name, t, at)?;
            tangential.insert(name.clone(), (law, t.scheme));
        }
    }
    Ok((laws, tangential))
}

/// The curved bottom and top sides of the blocks ([`SideShape::check`]) and
/// their concave fillets ([`crate::input::mesh::blocks::check_fillets`]),
/// each refusal naming `mesh.block[i].<side>.<key>`: the rules of the shape
/// against its block (of a fillet: against the blocks of its body), and, in
/// a model of revolution or a symmetric half, no rounding or chamfer at a
/// left side that lies on the axis or the symmetry plane, no fillet across
/// it. Blocks whose
/// breakpoints are themselves broken are left to the mesh generator's
/// messages.
fn check_curved_sides(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let usable = |v: &[f64]| {
        v.len() >= 2 && v.iter().all(|x| x.is_finite()) && v.windows(2).all(|w| w[1] > w[0])
    };
    let blocks: Vec<_> = case
        .mesh
        .block
        .iter()
        .filter(|b| usable(&b.x) && usable(&b.y))
        .collect();
    // the model's geometric tolerance (1e-9 of its size, as for its mesh)
    let (lo, hi) = blocks.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), b| {
            (
                [lo[0].min(b.x[0]), lo[1].min(b.y[0])],
                [hi[0].max(b.x[b.x.len() - 1]), hi[1].max(b.y[b.y.len() - 1])],
            )
        },
    );
    let tol = 1e-9 * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let axis = if case.model.plane == crate::physics::material::Plane::Axisymmetric {
        Some("the axis r = 0")
    } else if case.model.symmetric_half {
        Some("the symmetry plane x = 0")
    } else {
        None
    };
    for (i, b) in case.mesh.block.iter().enumerate() {
        if !(usable(&b.x) && usable(&b.y)) {
            continue;
        }
        let on_axis = axis.filter(|_| b.x[0].abs() <= tol);
        for (side, shape) in [("bottom", &b.bottom), ("top", &b.top)] {
            let Some(sh) = shape else { continue };
            sh.check(&b.x, [b.y[0], b.y[b.y.len() - 1]], on_axis)
                .map_err(|e| {
                    Error::input(
                        at(&format!("mesh.block[{i}].{side}.{}", e.key)),
                        format!("block \"{}\": {}", clip(b.name()), e.message),
                    )
                })?;
        }
    }
    // the concave fillets, which need the other blocks of their body
    crate::input::mesh::blocks::check_fillets(&case.mesh.block, axis).map_err(|e| {
        Error::input(
            at(&format!("mesh.block[{}].{}.{}", e.block, e.side, e.key)),
            format!(
                "block \"{}\": {}",
                clip(case.mesh.block[e.block].name()),
                e.message
            ),
        )
    })?;
    Ok(())
}

/// Longest case name in bytes (a folder name; most file systems stop at 255).
pub(crate) const MAX_NAME_BYTES: usize = 255;

/// A name that can only mean one folder under out/.
fn plain_folder_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= MAX_NAME_BYTES
        && name != "."
        && name != ".."
        && !name
            .chars()
            .any(|c| c == '/' || c == '\\' || c.is_control())
}

/// At most [`crate::error::MAX_QUOTE`] characters of a name, for messages.
pub fn clip(name: &str) -> String {
    crate::error::clip(name)
}

/// Body, block and interface names of the mesh specification: not empty (a
/// body "" would make sets named ".left"), no surrounding blanks, and every interface
/// name once (two interfaces of one name would both take the law of that
/// name: every pair twice).
fn check_names(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let blank = |n: &str| n.trim().is_empty() || n.trim() != n;
    for (i, b) in case.mesh.block.iter().enumerate() {
        if blank(&b.body) {
            return Err(Error::input(
                at(&format!("mesh.block[{i}] body")),
                format!(
                    "\"{}\" is not a usable body name (empty, blank, or with blanks around it): it names the sets <body>.left, .right, .top, .bottom, .all and [materials.<body>]",
                    clip(&b.body)
                ),
            ));
        }
        if let Some(name) = b.name.as_deref().filter(|n| blank(n)) {
            return Err(Error::input(
                at(&format!("mesh.block[{i}] name")),
                format!(
                    "\"{}\" is not a usable block name (empty, blank, or with blanks around it): it names the sets <block>.left, .right, .top, .bottom, .all and the block in interfaces",
                    clip(name)
                ),
            ));
        }
    }
    let mut seen = std::collections::BTreeSet::new();
    for (i, spec) in case.mesh.interface.iter().enumerate() {
        if blank(&spec.name) {
            return Err(Error::input(
                at(&format!("mesh.interface[{i}] name")),
                format!(
                    "\"{}\" is not a usable interface name (empty, blank, or with blanks around it): it keys [interface.<name>]",
                    clip(&spec.name)
                ),
            ));
        }
        if !seen.insert(spec.name.as_str()) {
            return Err(Error::input(
                at(&format!("mesh.interface[{i}] name")),
                format!(
                    "two [[mesh.interface]] entries are named \"{}\": each would take the law [interface.{}] and every pair would get its springs twice; give each interface its own name",
                    clip(&spec.name),
                    clip(&spec.name)
                ),
            ));
        }
    }
    Ok(())
}

/// The total element count must not pass [`MAX_ELEMENTS`]: the mesh is never
/// generated for an absurd case.
fn check_element_count(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let mut total: usize = 0;
    for b in &case.mesh.block {
        let block = format!("[[mesh.block]] \"{}\" nx, ny", clip(b.name()));
        let key = match case.option("[mesh] refine") {
            Some(o) => format!("{o} ({})", at(&block)),
            None => at(&format!("{block}, [mesh] refine")),
        };
        match block_elements(b, case.mesh.refine).and_then(|n| total.checked_add(n)) {
            Some(n) if n <= MAX_ELEMENTS => total = n,
            Some(n) => {
                return Err(Error::input(
                    key,
                    format!("{n} elements in all, more than {MAX_ELEMENTS} elements (the limit)"),
                ))
            }
            None => {
                return Err(Error::input(
                    key,
                    format!(
                        "the element count overflows: more than {MAX_ELEMENTS} elements (the limit)"
                    ),
                ))
            }
        }
    }
    let swept = match (&case.mesh.extrude, &case.mesh.revolve) {
        (Some(e), _) => Some((
            "[mesh] extrude nz",
            e.nz.iter().try_fold(0usize, |acc, &n| {
                acc.checked_add(n.checked_mul(case.mesh.refine)?)
            }),
        )),
        (None, Some(r)) => Some(("[mesh] revolve n", r.n.checked_mul(case.mesh.refine))),
        (None, None) => None,
    };
    if let Some((key, layers)) = swept {
        // the layout's count times the layers
        match layers.and_then(|l| total.checked_mul(l)) {
            Some(n) if n <= MAX_ELEMENTS => {}
            _ => {
                return Err(Error::input(
                    at(key),
                    format!(
                        "the blocks swept through the layers make more than {MAX_ELEMENTS} elements (the limit)"
                    ),
                ))
            }
        }
    }
    Ok(())
}

/// Elements of one block after refinement, by checked arithmetic (None: overflow).
fn block_elements(b: &crate::input::mesh::blocks::BlockSpec, refine: usize) -> Option<usize> {
    let side = |counts: &[usize]| {
        counts
            .iter()
            .try_fold(0usize, |acc, &n| acc.checked_add(n.checked_mul(refine)?))
    };
    side(&b.nx)?.checked_mul(side(&b.ny)?)
}

impl Case {
    /// The number of elements the mesh would have (None: it overflows), without
    /// generating it.
    pub fn element_count(&self) -> Option<usize> {
        self.mesh.block.iter().try_fold(0usize, |acc, b| {
            acc.checked_add(block_elements(b, self.mesh.refine)?)
        })
    }
}

/// The normal law of an interface: its kind by name ([`normal::KINDS`]), its
/// own keys needed and every other law's refused, then built and checked by
/// its file.
fn normal_law(s: &InterfaceLawSpec) -> std::result::Result<NormalLaw, String> {
    normal::kind(&s.law)?.law_from(&s.law_params())
}

/// Checks `[solver]` (and the `[output]` keys beside it), key by key in
/// the order of the phases below.
fn check_solver(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    check_counts_and_method(case, at)?;
    check_schedule(case, at)?;
    check_step_keys(case, at)?;
    check_step_limits(case, at)?;
    check_output_keys(case, at)
}

/// The counts of increments and cutbacks, and the method's keys (the
/// interface loop needs full Newton, Anderson's depth).
fn check_counts_and_method(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let s = &case.solver;
    if let Some(n) = s.increments.filter(|&n| n == 0 || n > MAX_INCREMENTS) {
        return Err(Error::input(
            at("[solver] increments"),
            format!("{n} must be in 1..={MAX_INCREMENTS}"),
        ));
    }
    if s.max_cutbacks > MAX_CUTBACKS {
        return Err(Error::input(
            at("[solver] max_cutbacks"),
            format!("{} must be at most {MAX_CUTBACKS}", s.max_cutbacks),
        ));
    }
    if s.interface_loop == Some(true) && s.method != super::Method::FullNewton {
        let why = "the loop condenses the consistent tangent";
        return Err(match case.option("[solver] method") {
            Some(o) => Error::input(
                o,
                match case.option("[solver] interface_loop") {
                    Some(l) => format!("{l} needs full-newton ({why})"),
                    None => format!(
                        "{} sets [solver] interface_loop = true, which needs full-newton ({why})",
                        case.source.display()
                    ),
                },
            ),
            None => Error::input(
                at("[solver] interface_loop"),
                format!(
                    "{} needs method = \"full-newton\" ({why}), not \"{}\"",
                    match case.option("[solver] interface_loop") {
                        Some(_) => "the interface loop",
                        None => "true",
                    },
                    s.method.name()
                ),
            ),
        });
    }
    if s.anderson_depth > MAX_ANDERSON_DEPTH {
        return Err(Error::input(
            at("[solver] anderson_depth"),
            format!("{} must be at most {MAX_ANDERSON_DEPTH}", s.anderson_depth),
        ));
    }
    Ok(())
}

/// The schedule: the first increment, the list of load factors, and the
/// convergence tolerances.
fn check_schedule(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let s = &case.solver;
    if let Some(f) = s.first_increment {
        if !(f.is_finite() && f > 0.0 && f <= 1.0) {
            return Err(Error::input(
                at("[solver] first_increment"),
                format!("{f} must be in (0, 1]"),
            ));
        }
    }
    if let Some(l) = &s.load_factors {
        let ok = !l.is_empty()
            && l.len() <= MAX_INCREMENTS
            && l.iter().all(|v| v.is_finite())
            && l[0] != 0.0
            && l.windows(2).all(|w| w[1] != w[0]);
        if !ok {
            return Err(Error::input(
                at("[solver] load_factors"),
                format!("must be a non-empty list (at most {MAX_INCREMENTS}) of finite numbers, the first non-zero and no two neighbours equal (it may go down: unloading)"),
            ));
        }
    }
    for (name, v) in [
        ("residual_tolerance", s.residual_tolerance),
        ("displacement_tolerance", s.displacement_tolerance),
    ] {
        if !(v.is_finite() && v > 0.0 && v < 1.0) {
            return Err(Error::input(
                at(&format!("[solver] {name}")),
                format!("{v} must be in (0, 1)"),
            ));
        }
    }
    Ok(())
}

/// The automatic control's limits, the stabilization's energy and the
/// iterations of a step.
fn check_step_limits(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let s = &case.solver;
    if let Some(v) = s.max_increment {
        if !(v.is_finite() && v > 0.0 && v <= 1.0) {
            return Err(Error::input(
                at("[solver] max_increment"),
                format!("{v} must be in (0, 1]"),
            ));
        }
    }
    let v = s.stabilization_energy;
    if !(v.is_finite() && v > 0.0 && v <= 1.0) {
        return Err(Error::input(
            at("[solver] stabilization_energy"),
            format!("{v} must be in (0, 1]"),
        ));
    }
    let v = s.plastic_strain_step;
    if !(v.is_finite() && v > 0.0 && v < 1.0) {
        return Err(Error::input(
            at("[solver] plastic_strain_step"),
            format!("{v} must be in (0, 1)"),
        ));
    }
    if let Some(n) = s.max_iterations {
        if n == 0 || n > MAX_ITERATIONS {
            return Err(Error::input(
                at("[solver] max_iterations"),
                format!("{n} must be in 1..={MAX_ITERATIONS}"),
            ));
        }
    }
    Ok(())
}

/// `[output]`: how often a VTU file is written and the probe point.
fn check_output_keys(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    if case.output.vtu_every == 0 {
        return Err(Error::input(at("[output] vtu_every"), "must be at least 1"));
    }
    let p = case.output.probe;
    if !(p[0].is_finite() && p[1].is_finite()) {
        return Err(Error::input(
            at("[output] probe"),
            format!("{p:?} must be two finite numbers (mm)"),
        ));
    }
    Ok(())
}

/// Keys of one step control given to the other, where they would be ignored:
/// under fixed steps `load_factors` is the whole schedule (`increments` and
/// `first_increment` beside it say nothing), and `max_increment` and
/// `plastic_strain_step` steer only the automatic control.
fn check_step_keys(case: &Case, at: &dyn Fn(&str) -> String) -> Result<()> {
    let s = &case.solver;
    if s.step_mode() != super::StepControl::Fixed {
        return Ok(());
    }
    // fixed steps asked for on the command line (whose keys of the
    // automatic control are dropped, `driver::load_case`)
    let option = case.option("[solver] step_control");
    let why = if s.step_control.is_some() {
        "step_control = \"fixed\""
    } else {
        "fixed steps (the default when increments, first_increment or load_factors is given)"
    };
    if s.load_factors.is_some() {
        for (key, given) in [
            ("increments", s.increments.is_some()),
            ("first_increment", s.first_increment.is_some()),
        ] {
            if !given {
                continue;
            }
            return Err(match option {
                Some(o) => Error::input(
                    o,
                    format!("leaves [solver] {key} of {} without effect beside load_factors: under fixed steps load_factors is the whole schedule; keep the case's automatic steps (load_factors are their waypoints), or remove {key}", case.source.display()),
                ),
                None => Error::input(
                    at(&format!("[solver] {key}")),
                    format!("has no effect beside load_factors under {why}: load_factors is the whole schedule; remove {key}, or set step_control = \"auto\" (load_factors are then waypoints)"),
                ),
            });
        }
    }
    for (key, given) in [
        ("max_increment", s.max_increment.is_some()),
        (
            "plastic_strain_step",
            s.plastic_strain_step != super::default_plastic_strain_step(),
        ),
    ] {
        if given {
            return Err(Error::input(
                at(&format!("[solver] {key}")),
                format!("steers the automatic step control only, but the case has {why}; remove {key}, or set step_control = \"auto\""),
            ));
        }
    }
    Ok(())
}
