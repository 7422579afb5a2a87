//! Structured meshes of rectangular blocks with geometric grading, and
//! contact interfaces between the bottom of one block and the top of another
//! (horizontal) or between the right side of one block and the left side of
//! another (vertical), nodes paired, not merged. Blocks that name the same
//! body are one body: they share sides, whose nodes are merged (`merge`).
//!
//! Each block gets the node sets and edge sets `<block>.bottom`, `.right`,
//! `.top`, `.left` (edges walked with the body on the left; the sides' parts
//! shared with another block of the body are not in them) and the node set
//! `<block>.all`; each body the node set `<body>.all`. A block's name is its
//! body's unless it has a `name`: a body of one block keeps the sets it
//! always had.

use super::{ContactEdge, Element, Interface, Mesh, MeshError, NonMatching};
use crate::error::clip;
use serde::{Deserialize, Serialize};

mod fillet;
mod merge;
mod shape;
pub(crate) use fillet::{check as check_fillets, SideFillets};
pub(crate) use shape::SideShape;

/// A rectangular block; x and y are split into segments at the breakpoints.
/// Its bottom and top sides may be curved (`SideShape`); the block then
/// lies inside its rectangle.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    pub body: String,
    /// The block's name (default: `body`): its sets are `<name>.bottom`,
    /// `.right`, `.top`, `.left`, `.all`, and interfaces name it. The
    /// blocks of a body of several blocks each need their own.
    #[serde(default)]
    pub name: Option<String>,
    /// Breakpoints in x, strictly increasing (mm).
    pub x: Vec<f64>,
    /// Elements per x segment.
    pub nx: Vec<usize>,
    /// Size ratio last/first element per x segment (geometric grading); < 1
    /// refines toward the segment's end, > 1 toward its start. Default 1.
    #[serde(default)]
    pub rx: Vec<f64>,
    pub y: Vec<f64>,
    pub ny: Vec<usize>,
    #[serde(default)]
    pub ry: Vec<f64>,
    /// A curved bottom side (default straight).
    #[serde(default)]
    pub bottom: Option<SideShape>,
    /// A curved top side (default straight).
    #[serde(default)]
    pub top: Option<SideShape>,
    /// Concave fillets at the ends of the left side (`fillet_bottom`,
    /// `fillet_top`; docs/case-schema.md, "Fillets and chamfers").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub left: Option<SideFillets>,
    /// Concave fillets at the ends of the right side.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub right: Option<SideFillets>,
}

impl BlockSpec {
    /// The block's name: `name`, or else the body's.
    pub fn name(&self) -> &str {
        self.name.as_deref().unwrap_or(&self.body)
    }
}

/// Contact between the bottom of block `upper` and the top of block `lower`
/// (generated meshes, a horizontal interface: A = upper, B = lower), between
/// the right side of block `left` and the left side of block `right`
/// (generated meshes, a vertical interface: A = left, B = right), or between the physical curves `upper_curve` and
/// `lower_curve` (plane meshes read from a file; `upper` / `lower` then optional,
/// checked against the bodies the curves lie on), or between the physical
/// surfaces `upper_surface` and `lower_surface` (meshes of volumes read from
/// a file, likewise).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    pub name: String,
    pub upper: Option<String>,
    pub lower: Option<String>,
    /// File meshes: physical curve on the upper body (its bottom).
    pub upper_curve: Option<String>,
    /// File meshes: physical curve on the lower body (its top).
    pub lower_curve: Option<String>,
    /// File meshes of volumes: physical surface on the upper body (body A;
    /// the slave side with `matching = false`). Left out of the case's key
    /// when not given (the key of a case without it stays as it was).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upper_surface: Option<String>,
    /// File meshes of volumes: physical surface on the lower body (body B).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lower_surface: Option<String>,
    /// Generated meshes, vertical interface: the block whose right side is
    /// in contact (body A).
    #[serde(default)]
    pub left: Option<String>,
    /// Generated meshes, vertical interface: the block whose left side is in
    /// contact (body B).
    #[serde(default)]
    pub right: Option<String>,
    /// Generated meshes: `false` lets the two sides have different nodes
    /// along the interface (node-to-segment springs, body A the slave side,
    /// body B the master side); default `true`, coincident node pairs.
    #[serde(default)]
    pub matching: Option<bool>,
}

/// Corner coordinates along one axis from breakpoints, counts and ratios.
pub(crate) fn graded_axis(
    body: &str,
    axis: &str,
    breaks: &[f64],
    counts: &[usize],
    ratios: &[f64],
    refine: usize,
) -> Result<Vec<f64>, MeshError> {
    let err = |m: String| Err(MeshError(format!("block \"{body}\": {m}")));
    if breaks.len() < 2 {
        return err(format!("{axis} needs at least two breakpoints"));
    }
    if breaks.iter().any(|v| !v.is_finite()) || breaks.windows(2).any(|w| w[1] <= w[0]) {
        return err(format!(
            "{axis} = {breaks:?} must be finite and strictly increasing"
        ));
    }
    let segs = breaks.len() - 1;
    if counts.len() != segs {
        return err(format!(
            "n{axis} has {} entries but {axis} has {segs} segments",
            counts.len()
        ));
    }
    if !ratios.is_empty() && ratios.len() != segs {
        return err(format!(
            "r{axis} has {} entries but {axis} has {segs} segments",
            ratios.len()
        ));
    }
    let mut out = vec![breaks[0]];
    for s in 0..segs {
        let Some(n) = counts[s].checked_mul(refine) else {
            return err(format!("n{axis}[{s}] × refine overflows"));
        };
        if n == 0 {
            return err(format!("n{axis}[{s}] must be at least 1"));
        }
        let r = ratios.get(s).copied().unwrap_or(1.0);
        if !(r.is_finite() && r > 0.0) {
            return err(format!("r{axis}[{s}] = {r} must be a positive number"));
        }
        let (a, len) = (breaks[s], breaks[s + 1] - breaks[s]);
        let q = if n > 1 {
            r.powf(1.0 / (n - 1) as f64)
        } else {
            1.0
        };
        let sizes: Vec<f64> = (0..n).map(|i| q.powi(i as i32)).collect();
        let total: f64 = sizes.iter().sum();
        let mut x = a;
        for h in &sizes[..n - 1] {
            x += len * h / total;
            out.push(x);
        }
        out.push(breaks[s + 1]);
    }
    Ok(out)
}

struct Grid {
    /// The block's name and its body's index.
    name: String,
    body: usize,
    ids: Vec<Vec<usize>>, // ids[j][i], usize::MAX for element centres
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Whether the bottom and the top side are curved.
    curved: [bool; 2],
}

/// Generates the mesh of all blocks and their interfaces.
pub(crate) fn generate(
    blocks: &[BlockSpec],
    interfaces: &[InterfaceSpec],
    refine: usize,
) -> Result<Mesh, MeshError> {
    if refine == 0 {
        return Err(MeshError("refine must be at least 1".into()));
    }
    if blocks.is_empty() {
        return Err(MeshError(
            "no [[mesh.block]] given (and no `file`): give one or the other".into(),
        ));
    }
    merge::check_names(blocks)?;
    let mut mesh = Mesh::default();
    let mut grids = Vec::new();
    for spec in blocks {
        let body = match mesh.bodies.iter().position(|b| *b == spec.body) {
            Some(b) => b,
            None => {
                mesh.bodies.push(spec.body.clone());
                mesh.bodies.len() - 1
            }
        };
        let name = spec.name();
        let xs = graded_axis(name, "x", &spec.x, &spec.nx, &spec.rx, refine)?;
        let ys = graded_axis(name, "y", &spec.y, &spec.ny, &spec.ry, refine)?;
        for (side, shape) in [("bottom", &spec.bottom), ("top", &spec.top)] {
            if let Some(sh) = shape {
                // the rules that need the model (the axis, a symmetry plane)
                // are checked with the case ([`crate::input::case::validate`])
                sh.check(&spec.x, [ys[0], ys[ys.len() - 1]], None)
                    .map_err(|e| {
                        MeshError(format!(
                            "block \"{}\" {side}.{}: {}",
                            clip(name),
                            e.key,
                            e.message
                        ))
                    })?;
            }
        }
        grids.push(add_block(&mut mesh, body, xs, ys, spec));
    }
    // the concave fillets' rules that need no model (the axis is checked
    // with the case, [`crate::input::case::validate`])
    let fillets = fillet::check(blocks, None).map_err(|e| {
        MeshError(format!(
            "block \"{}\" {}.{}: {}",
            clip(blocks[e.block].name()),
            e.side,
            e.key,
            e.message
        ))
    })?;
    // the shared sides first (the body as a whole), then the interfaces on
    // the blocks' own node ids, then the merge renumbers them all
    let plan = merge::plan(&mesh, &grids)?;
    for spec in interfaces {
        let iface = pair_blocks(&mesh, &grids, spec)?;
        mesh.interfaces.push(iface);
    }
    merge::apply(&mut mesh, &plan);
    fillet::apply(&mut mesh, &fillets, blocks);
    Ok(mesh)
}

fn add_block(mesh: &mut Mesh, body: usize, xs: Vec<f64>, ys: Vec<f64>, spec: &BlockSpec) -> Grid {
    let (ni, nj) = (2 * (xs.len() - 1) + 1, 2 * (ys.len() - 1) + 1);
    let coord = |v: &[f64], k: usize| {
        if k % 2 == 0 {
            v[k / 2]
        } else {
            0.5 * (v[k / 2] + v[k / 2 + 1])
        }
    };
    let first = mesh.nodes.len();
    let (x0, x1) = (xs[0], xs[xs.len() - 1]);
    let (y0, y1) = (ys[0], ys[ys.len() - 1]);
    // the bottom and top point of each node column (straight sides: the
    // rectangle's), see [`SideShape`]
    let ends = |i: usize| -> ([f64; 2], [f64; 2]) {
        let x = coord(&xs, i);
        let b = spec
            .bottom
            .as_ref()
            .map_or((x, 0.0), |s| s.point(x, x0, x1));
        let t = spec.top.as_ref().map_or((x, 0.0), |s| s.point(x, x0, x1));
        ([b.0, y0 + b.1], [t.0, y1 - t.1])
    };
    let cuts = |s: &Option<SideShape>| s.as_ref().is_some_and(SideShape::cuts);
    let curved = cuts(&spec.bottom) || cuts(&spec.top);
    let mut ids = vec![vec![usize::MAX; ni]; nj];
    for (j, row) in ids.iter_mut().enumerate() {
        for (i, id) in row.iter_mut().enumerate() {
            if i % 2 == 1 && j % 2 == 1 {
                continue;
            }
            *id = mesh.nodes.len();
            let (x, y) = (coord(&xs, i), coord(&ys, j));
            if curved {
                let (b, t) = ends(i);
                let f = (y - y0) / (y1 - y0);
                mesh.nodes
                    .push([b[0] + f * (t[0] - b[0]), b[1] + f * (t[1] - b[1]), 0.0]);
            } else {
                mesh.nodes.push([x, y, 0.0]);
            }
        }
    }
    for ej in 0..(nj - 1) / 2 {
        for ei in 0..(ni - 1) / 2 {
            let (i, j) = (2 * ei, 2 * ej);
            let n = |di: usize, dj: usize| ids[j + dj][i + di];
            let nodes = [
                n(0, 0),
                n(2, 0),
                n(2, 2),
                n(0, 2),
                n(1, 0),
                n(2, 1),
                n(1, 2),
                n(0, 1),
            ];
            mesh.elements.push(Element::q8(nodes, body));
        }
    }
    let name = spec.name();
    let (il, jl) = (ni - 1, nj - 1);
    let side = |pts: Vec<(usize, usize)>| -> Vec<usize> {
        pts.into_iter().map(|(i, j)| ids[j][i]).collect()
    };
    let sides: [(&str, Vec<usize>); 4] = [
        ("bottom", side((0..ni).map(|i| (i, 0)).collect())),
        ("right", side((0..nj).map(|j| (il, j)).collect())),
        ("top", side((0..ni).rev().map(|i| (i, jl)).collect())),
        ("left", side((0..nj).rev().map(|j| (0, j)).collect())),
    ];
    for (s, nodes) in sides {
        let edges: Vec<[usize; 3]> = nodes
            .windows(3)
            .step_by(2)
            .map(|w| [w[0], w[1], w[2]])
            .collect();
        let mut set = nodes.clone();
        set.sort_unstable();
        mesh.node_sets.insert(format!("{name}.{s}"), set);
        mesh.edge_sets.insert(format!("{name}.{s}"), edges);
    }
    mesh.node_sets
        .insert(format!("{name}.all"), (first..mesh.nodes.len()).collect());
    Grid {
        name: name.to_string(),
        body,
        ids,
        xs,
        ys,
        curved: [cuts(&spec.bottom), cuts(&spec.top)],
    }
}

/// The blocks an interface pairs: body A, body B and whether the interface is
/// vertical (`left` / `right`) rather than horizontal (`upper` / `lower`).
fn sides_of(spec: &InterfaceSpec) -> Result<(&str, &str, bool), MeshError> {
    let err = |m: &str| Err(MeshError(format!("interface \"{}\": {m}", spec.name)));
    if spec.upper_curve.is_some() || spec.lower_curve.is_some() {
        return err("upper_curve / lower_curve name physical curves of a mesh file ([mesh] file); generated blocks use upper / lower or left / right");
    }
    if spec.upper_surface.is_some() || spec.lower_surface.is_some() {
        return err("upper_surface / lower_surface name physical surfaces of a mesh file of volumes ([mesh] file); generated blocks (swept or not) use upper / lower or left / right");
    }
    let horizontal = spec.upper.is_some() || spec.lower.is_some();
    let vertical = spec.left.is_some() || spec.right.is_some();
    if horizontal && vertical {
        return err("give either upper and lower (a horizontal interface: the bottom of upper on the top of lower) or left and right (a vertical one: the right side of left against the left side of right), not both");
    }
    match (&spec.upper, &spec.lower, &spec.left, &spec.right) {
        (Some(a), Some(b), None, None) => Ok((a, b, false)),
        (None, None, Some(a), Some(b)) => Ok((a, b, true)),
        _ if vertical => err("give left and right (block names: the right side of left against the left side of right)"),
        _ => err("give upper and lower (block names) for a horizontal interface, or left and right for a vertical one"),
    }
}

/// The facing sides of two blocks: A's and B's nodes along the interface in
/// walk order (B on the right: increasing x on a horizontal interface,
/// increasing y on a vertical one), and what the messages call them.
struct Facing<'a> {
    a: &'a str,
    b: &'a str,
    a_line: Vec<usize>,
    b_line: Vec<usize>,
    /// The coordinate along the interface: 0 (x, horizontal) or 1 (y, vertical).
    along: usize,
    /// Where each side lies across the interface (y or x).
    a_at: f64,
    b_at: f64,
    /// "the bottom" / "the top", or "the right side" / "the left side".
    a_side: &'static str,
    b_side: &'static str,
    /// The blocks' extents along the interface.
    a_range: [f64; 2],
    b_range: [f64; 2],
}

fn facing<'a>(
    grids: &[Grid],
    ia: usize,
    ib: usize,
    a: &'a str,
    b: &'a str,
    vertical: bool,
) -> Facing<'a> {
    let (ga, gb) = (&grids[ia], &grids[ib]);
    let range = |v: &[f64]| [v[0], v[v.len() - 1]];
    if vertical {
        // A's right column and B's left column, bottom to top
        let il = ga.ids[0].len() - 1;
        Facing {
            a,
            b,
            a_line: ga.ids.iter().map(|row| row[il]).collect(),
            b_line: gb.ids.iter().map(|row| row[0]).collect(),
            along: 1,
            a_at: ga.xs[ga.xs.len() - 1],
            b_at: gb.xs[0],
            a_side: "the right side",
            b_side: "the left side",
            a_range: range(&ga.ys),
            b_range: range(&gb.ys),
        }
    } else {
        // A's bottom row and B's top row, left to right
        Facing {
            a,
            b,
            a_line: ga.ids[0].clone(),
            b_line: gb.ids[gb.ids.len() - 1].clone(),
            along: 0,
            a_at: ga.ys[0],
            b_at: gb.ys[gb.ys.len() - 1],
            a_side: "the bottom",
            b_side: "the top",
            a_range: range(&ga.xs),
            b_range: range(&gb.xs),
        }
    }
}

fn pair_blocks(mesh: &Mesh, grids: &[Grid], spec: &InterfaceSpec) -> Result<Interface, MeshError> {
    let find = |name: &str| {
        grids.iter().position(|g| g.name == name).ok_or_else(|| {
            MeshError(format!(
                "interface \"{}\": no block named \"{name}\"",
                spec.name
            ))
        })
    };
    let (a, b, vertical) = sides_of(spec)?;
    let (ia, ib) = (find(a)?, find(b)?);
    if ia == ib {
        let what = if vertical {
            "left and right"
        } else {
            "upper and lower"
        };
        return Err(MeshError(format!(
            "interface \"{}\": {what} are the same block",
            spec.name
        )));
    }
    let (body_a, body_b) = (grids[ia].body, grids[ib].body);
    if body_a == body_b {
        return Err(MeshError(format!(
            "interface \"{}\": blocks \"{}\" and \"{}\" are both of body \"{}\": an interface joins two bodies (the blocks of one body share their sides, merged node for node)",
            clip(&spec.name),
            clip(a),
            clip(b),
            clip(&mesh.bodies[body_a])
        )));
    }
    let f = facing(grids, ia, ib, a, b, vertical);
    if !vertical && spec.matching != Some(false) {
        let curved = [
            (a, grids[ia].curved[0], "bottom"),
            (b, grids[ib].curved[1], "top"),
        ];
        if let Some((block, _, side)) = curved.iter().find(|c| c.1) {
            return Err(MeshError(format!(
                "interface \"{}\": the {side} of block \"{block}\" is curved; a curved side has no partner nodes on the other: set matching = false (node-to-segment springs)",
                spec.name
            )));
        }
    }
    if spec.matching == Some(false) {
        return Ok(Interface {
            name: spec.name.clone(),
            body_a,
            body_b,
            edges: Vec::new(),
            nonmatching: Some(nonmatching_sides(mesh, &spec.name, &f)?),
            ..Default::default()
        });
    }
    Ok(Interface {
        name: spec.name.clone(),
        body_a,
        body_b,
        edges: match_sides(mesh, &spec.name, &f)?,
        nonmatching: None,
        ..Default::default()
    })
}

/// The checks both kinds of interface share: the two sides lie on one line
/// (within 1e-9 of their size) and overlap along it. Returns the tolerance
/// and the overlap [lo, hi].
fn facing_overlap(name: &str, f: &Facing) -> Result<(f64, [f64; 2]), MeshError> {
    let k = f.along;
    let (along, across) = (["x", "y"][k], ["x", "y"][1 - k]);
    let err = |m: String| Err(MeshError(format!("interface \"{name}\": {m}")));
    let size = (f.a_range[1] - f.a_range[0]).max(f.b_range[1] - f.b_range[0]);
    let tol = 1e-9 * size;
    if (f.a_at - f.b_at).abs() > tol {
        return err(format!(
            "{} of \"{}\" is at {across} = {} but {} of \"{}\" is at {across} = {} (the sides do not face each other)",
            f.a_side, f.a, f.a_at, f.b_side, f.b, f.b_at
        ));
    }
    let lo = f.a_range[0].max(f.b_range[0]);
    let hi = f.a_range[1].min(f.b_range[1]);
    if hi - lo <= tol {
        return err(format!("the blocks do not overlap in {along}"));
    }
    Ok((tol, [lo, hi]))
}

/// The two sides of a non-matching interface (`matching = false`): they
/// must lie on one line and overlap, like matching ones, but their nodes
/// need not coincide. The slave side is A's edges that reach into B's
/// extent along the interface (edges wholly beyond it are free surface, as
/// on a matching interface); the master side is all of B's facing edges.
/// Whether every spring point finds a master edge is checked when the
/// springs are built ([`crate::model::interface::InterfaceModel::new`]).
fn nonmatching_sides(mesh: &Mesh, name: &str, f: &Facing) -> Result<NonMatching, MeshError> {
    let k = f.along;
    let (tol, _) = facing_overlap(name, f)?;
    let at = |n: usize| mesh.nodes[n][k];
    let edges = |line: &[usize]| -> Vec<[usize; 3]> {
        line.windows(3)
            .step_by(2)
            .map(|w| [w[0], w[1], w[2]])
            .collect()
    };
    let slave = edges(&f.a_line)
        .into_iter()
        .filter(|e| at(e[2]) > f.b_range[0] + tol && at(e[0]) < f.b_range[1] - tol)
        .collect();
    Ok(NonMatching {
        slave,
        master: edges(&f.b_line),
    })
}

/// The contact edges between two facing sides: A's edges within the overlap
/// of the two sides, each with B's nodes at the same positions.
fn match_sides(mesh: &Mesh, name: &str, f: &Facing) -> Result<Vec<ContactEdge>, MeshError> {
    let k = f.along;
    let along = ["x", "y"][k];
    let err = |m: String| Err(MeshError(format!("interface \"{name}\": {m}")));
    let (tol, [lo, hi]) = facing_overlap(name, f)?;
    let at = |n: usize| mesh.nodes[n][k];
    let inside = |v: f64| v >= lo - tol && v <= hi + tol;
    let partner = |n: usize, line: &[usize], body: &str| -> Result<usize, MeshError> {
        let v = at(n);
        // the lines run in increasing coordinate: binary search, not a scan (large meshes)
        let first = line.partition_point(|&m| at(m) < v - tol);
        line.get(first)
            .copied()
            .filter(|&m| (at(m) - v).abs() <= tol)
            .ok_or_else(|| {
                MeshError(format!(
                    "interface \"{name}\": node at {along} = {v} on \"{body}\" has no partner on the other side (the two meshes must match along the interface)"
                ))
            })
    };
    for &n in f.b_line.iter().filter(|&&n| inside(at(n))) {
        partner(n, &f.a_line, f.b)?;
    }
    let mut edges = Vec::new();
    for w in f.a_line.windows(3).step_by(2) {
        if !(inside(at(w[0])) && inside(at(w[2]))) {
            if inside(at(w[1])) {
                return err(format!(
                    "an element edge of \"{}\" straddles the end of the overlap at {along} = {}",
                    f.a,
                    at(w[1])
                ));
            }
            continue;
        }
        let a = [w[0], w[1], w[2]];
        let b = [
            partner(a[0], &f.b_line, f.a)?,
            partner(a[1], &f.b_line, f.a)?,
            partner(a[2], &f.b_line, f.a)?,
        ];
        edges.push(ContactEdge { a, b });
    }
    Ok(edges)
}

#[cfg(test)]
mod tests;

/// The area two rectangles [x0, x1, y0, y1] share, if any: more than 1e-9
/// of the larger side in both directions (rectangles that touch share none).
pub(crate) fn common_area(r: [f64; 4], s: [f64; 4]) -> Option<[f64; 4]> {
    let size = (r[1] - r[0])
        .max(r[3] - r[2])
        .max(s[1] - s[0])
        .max(s[3] - s[2]);
    let tol = 1e-9 * size;
    let (x0, x1) = (r[0].max(s[0]), r[1].min(s[1]));
    let (y0, y1) = (r[2].max(s[2]), r[3].min(s[3]));
    (x1 - x0 > tol && y1 - y0 > tol).then_some([x0, x1, y0, y1])
}
