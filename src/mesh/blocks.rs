//! Structured meshes of rectangular blocks with geometric grading, one body per
//! block, and contact interfaces between the bottom of one block and the top of
//! another (horizontal) or between the right side of one block and the left
//! side of another (vertical), nodes paired, not merged.
//!
//! Each block gets the node sets and edge sets `<body>.bottom`, `.right`, `.top`,
//! `.left` (edges walked with the body on the left) and the node set `<body>.all`.

use super::{ContactEdge, Element, Interface, Mesh, MeshError, NonMatching};
use serde::Deserialize;

/// A rectangular block; x and y are split into segments at the breakpoints.
/// Its bottom and top sides may be curved ([`SideShape`]); the block then
/// lies inside its rectangle.
#[derive(Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    pub body: String,
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
}

/// As derived, but `bottom` / `top` only when given: a case with straight
/// blocks keeps its text and so its restart fingerprint
/// ([`crate::restart::fingerprint`]).
impl std::fmt::Debug for BlockSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut d = f.debug_struct("BlockSpec");
        d.field("body", &self.body)
            .field("x", &self.x)
            .field("nx", &self.nx)
            .field("rx", &self.rx)
            .field("y", &self.y)
            .field("ny", &self.ny)
            .field("ry", &self.ry);
        if let Some(b) = &self.bottom {
            d.field("bottom", b);
        }
        if let Some(t) = &self.top {
            d.field("top", t);
        }
        d.finish()
    }
}

/// The shape of a block's bottom or top side (issue 19: curved contact).
/// The side bulges out of the block's rectangle no further than its straight
/// line: a curved bottom rises from y₀, a curved top falls from y₁, so the
/// block stays inside its rectangle. Interior nodes are placed on the
/// straight line between the (curved) bottom and top point of their column,
/// at the graded height fraction: x(ξ, η) = (1 − η̂) B(ξ) + η̂ T(ξ), the
/// transfinite (Coons) map of a block whose left and right sides are straight.
/// Every node of a curved side, midside nodes included, lies on the curve.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SideShape {
    /// A circular arc of this radius (mm) whose apex is the straight side's
    /// point at x = `center`: a cylinder or a crown,
    /// y = y₀ + R − √(R² − (x − c)²) on a bottom side (mirrored on a top).
    #[serde(default)]
    pub radius: Option<f64>,
    /// x of the arc's apex (mm); default the middle of the block.
    #[serde(default)]
    pub center: Option<f64>,
    /// A quarter-circle rounding of this radius (mm) at the side's left end:
    /// the side is straight up to x₀ + r and turns through 90° to meet the
    /// left side r above (bottom) or below (top) the corner. x₀ + r must be a
    /// breakpoint of `x`; nodes on the rounding are spaced evenly in angle.
    #[serde(default)]
    pub round_left: Option<f64>,
    /// The same rounding at the side's right end (x₁ − r a breakpoint).
    #[serde(default)]
    pub round_right: Option<f64>,
}

impl SideShape {
    /// Checks the shape against its block; `side` is "bottom" or "top".
    fn check(&self, body: &str, side: &str, xs: &[f64], height: f64) -> Result<(), MeshError> {
        let err = |m: String| Err(MeshError(format!("block \"{body}\" {side}: {m}")));
        let (x0, x1) = (xs[0], xs[xs.len() - 1]);
        let positive = |name: &str, v: f64| -> Result<(), MeshError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                err(format!("{name} = {v} must be a positive length in mm"))
            }
        };
        let rounded = self.round_left.is_some() || self.round_right.is_some();
        match self.radius {
            Some(r) => {
                if rounded {
                    return err("give either radius (an arc) or round_left / round_right (rounded ends), not both".into());
                }
                positive("radius", r)?;
                let c = self.center.unwrap_or(0.5 * (x0 + x1));
                if !c.is_finite() {
                    return err(format!("center = {c} must be finite"));
                }
                let reach = (x0 - c).abs().max((x1 - c).abs());
                if reach >= 0.9 * r {
                    return err(format!(
                        "the block reaches {reach} mm from the arc's apex at x = {c}; with radius = {r} it must stay within 0.9 R (the arc would turn steeper than 64° from the side)"
                    ));
                }
                let rise = r - (r * r - reach * reach).sqrt();
                if rise >= 0.5 * height {
                    return err(format!(
                        "the arc rises {rise} mm over the block, which is {height} mm high: make the block at least twice as high as the rise"
                    ));
                }
            }
            None => {
                if self.center.is_some() {
                    return err("center belongs to radius (an arc)".into());
                }
                if !rounded {
                    return err(
                        "give radius (an arc) or round_left / round_right (rounded ends)".into(),
                    );
                }
                let l = self.round_left.unwrap_or(0.0);
                let r = self.round_right.unwrap_or(0.0);
                for (name, v) in [
                    ("round_left", self.round_left),
                    ("round_right", self.round_right),
                ] {
                    if let Some(v) = v {
                        positive(name, v)?;
                        if v >= 0.5 * height {
                            return err(format!(
                                "{name} = {v} mm must be less than half the block's height ({height} mm)"
                            ));
                        }
                    }
                }
                if x0 + l > x1 - r + 1e-12 * (x1 - x0) {
                    return err(format!(
                        "the roundings ({l} + {r} mm) are wider than the block ({} mm)",
                        x1 - x0
                    ));
                }
                let near = |v: f64| xs.iter().any(|&b| (b - v).abs() <= 1e-9 * (x1 - x0));
                if self.round_left.is_some() && !near(x0 + l) {
                    return err(format!(
                        "x must have a breakpoint where the left rounding ends, x = {}",
                        x0 + l
                    ));
                }
                if self.round_right.is_some() && !near(x1 - r) {
                    return err(format!(
                        "x must have a breakpoint where the right rounding starts, x = {}",
                        x1 - r
                    ));
                }
            }
        }
        Ok(())
    }

    /// The point of the side for the straight side's abscissa x: (x, drop)
    /// becomes (x', depth), where depth ≥ 0 is how far the curve lies inside
    /// the block from the straight side.
    fn point(&self, x: f64, x0: f64, x1: f64) -> (f64, f64) {
        if let Some(r) = self.radius {
            let c = self.center.unwrap_or(0.5 * (x0 + x1));
            let d = x - c;
            return (x, r - (r * r - d * d).sqrt());
        }
        let quarter = |r: f64, u: f64| {
            // u ∈ [0, 1] along the rounding from its tangent point to the end
            let th = u.clamp(0.0, 1.0) * std::f64::consts::FRAC_PI_2;
            (r * th.sin(), r * (1.0 - th.cos()))
        };
        if let Some(r) = self.round_right {
            if x > x1 - r {
                let (dx, depth) = quarter(r, (x - (x1 - r)) / r);
                return (x1 - r + dx, depth);
            }
        }
        if let Some(r) = self.round_left {
            if x < x0 + r {
                let (dx, depth) = quarter(r, (x0 + r - x) / r);
                return (x0 + r - dx, depth);
            }
        }
        (x, 0.0)
    }
}

/// Contact between the bottom of block `upper` and the top of block `lower`
/// (generated meshes, a horizontal interface: A = upper, B = lower), between
/// the right side of block `left` and the left side of block `right`
/// (generated meshes, a vertical interface: A = left, B = right), or between the physical curves `upper_curve` and
/// `lower_curve` (meshes read from a file; `upper` / `lower` then optional,
/// checked against the bodies the curves lie on).
#[derive(Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    pub name: String,
    pub upper: Option<String>,
    pub lower: Option<String>,
    /// File meshes: physical curve on the upper body (its bottom).
    pub upper_curve: Option<String>,
    /// File meshes: physical curve on the lower body (its top).
    pub lower_curve: Option<String>,
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

/// As derived, but `left` / `right` only when given: the text of a case
/// without them is what it was before they existed, and so is its restart
/// fingerprint ([`crate::restart::fingerprint`]), so that restart files of
/// earlier builds stay usable.
impl std::fmt::Debug for InterfaceSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut d = f.debug_struct("InterfaceSpec");
        d.field("name", &self.name)
            .field("upper", &self.upper)
            .field("lower", &self.lower)
            .field("upper_curve", &self.upper_curve)
            .field("lower_curve", &self.lower_curve);
        if self.left.is_some() || self.right.is_some() {
            d.field("left", &self.left).field("right", &self.right);
        }
        if let Some(m) = self.matching {
            d.field("matching", &m);
        }
        d.finish()
    }
}

/// Corner coordinates along one axis from breakpoints, counts and ratios.
pub fn graded_axis(
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
    ids: Vec<Vec<usize>>, // ids[j][i], usize::MAX for element centres
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Whether the bottom and the top side are curved.
    curved: [bool; 2],
}

/// Generates the mesh of all blocks and their interfaces.
pub fn generate(
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
    let mut mesh = Mesh::default();
    let mut grids = Vec::new();
    for (b, spec) in blocks.iter().enumerate() {
        if mesh.bodies.contains(&spec.body) {
            return Err(MeshError(format!("two blocks are named \"{}\"", spec.body)));
        }
        mesh.bodies.push(spec.body.clone());
        let xs = graded_axis(&spec.body, "x", &spec.x, &spec.nx, &spec.rx, refine)?;
        let ys = graded_axis(&spec.body, "y", &spec.y, &spec.ny, &spec.ry, refine)?;
        let height = ys[ys.len() - 1] - ys[0];
        for (side, shape) in [("bottom", &spec.bottom), ("top", &spec.top)] {
            if let Some(sh) = shape {
                sh.check(&spec.body, side, &spec.x, height)?;
            }
        }
        grids.push(add_block(&mut mesh, b, xs, ys, spec));
    }
    for spec in interfaces {
        let iface = pair_blocks(&mesh, &grids, spec)?;
        mesh.interfaces.push(iface);
    }
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
    let curved = spec.bottom.is_some() || spec.top.is_some();
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
                    .push([b[0] + f * (t[0] - b[0]), b[1] + f * (t[1] - b[1])]);
            } else {
                mesh.nodes.push([x, y]);
            }
        }
    }
    for ej in 0..(nj - 1) / 2 {
        for ei in 0..(ni - 1) / 2 {
            let (i, j) = (2 * ei, 2 * ej);
            let n = |di: usize, dj: usize| ids[j + dj][i + di];
            mesh.elements.push(Element {
                nodes: [
                    n(0, 0),
                    n(2, 0),
                    n(2, 2),
                    n(0, 2),
                    n(1, 0),
                    n(2, 1),
                    n(1, 2),
                    n(0, 1),
                ],
                body,
            });
        }
    }
    let name = mesh.bodies[body].clone();
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
        ids,
        xs,
        ys,
        curved: [spec.bottom.is_some(), spec.top.is_some()],
    }
}

/// The blocks an interface pairs: body A, body B and whether the interface is
/// vertical (`left` / `right`) rather than horizontal (`upper` / `lower`).
fn sides_of(spec: &InterfaceSpec) -> Result<(&str, &str, bool), MeshError> {
    let err = |m: &str| Err(MeshError(format!("interface \"{}\": {m}", spec.name)));
    if spec.upper_curve.is_some() || spec.lower_curve.is_some() {
        return err("upper_curve / lower_curve name physical curves of a mesh file ([mesh] file); generated blocks use upper / lower or left / right");
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
        mesh.bodies.iter().position(|b| b == name).ok_or_else(|| {
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
            body_a: ia,
            body_b: ib,
            edges: Vec::new(),
            nonmatching: Some(nonmatching_sides(mesh, &spec.name, &f)?),
        });
    }
    Ok(Interface {
        name: spec.name.clone(),
        body_a: ia,
        body_b: ib,
        edges: match_sides(mesh, &spec.name, &f)?,
        nonmatching: None,
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
/// springs are built ([`crate::interface::InterfaceModel::new`]).
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
mod tests {
    use super::*;

    fn punch() -> (Vec<BlockSpec>, Vec<InterfaceSpec>) {
        let b = |body: &str, x: Vec<f64>, nx, rx, y: Vec<f64>, ny, ry| BlockSpec {
            body: body.into(),
            x,
            nx,
            rx,
            y,
            ny,
            ry,
            bottom: None,
            top: None,
        };
        (
            vec![
                b(
                    "punch",
                    vec![0., 20.],
                    vec![4],
                    vec![0.25],
                    vec![0., 20.],
                    vec![4],
                    vec![4.0],
                ),
                b(
                    "foundation",
                    vec![0., 20., 60.],
                    vec![4, 5],
                    vec![0.25, 8.0],
                    vec![-60., 0.],
                    vec![6],
                    vec![0.1],
                ),
            ],
            vec![InterfaceSpec {
                name: "contact".into(),
                upper: Some("punch".into()),
                lower: Some("foundation".into()),
                upper_curve: None,
                lower_curve: None,
                left: None,
                right: None,
                matching: None,
            }],
        )
    }

    #[test]
    fn punch_mesh_counts_grading_and_interface() {
        let (bl, ifs) = punch();
        let m = generate(&bl, &ifs, 1).unwrap();
        m.validate().unwrap();
        // Q8 nodes per block: (2nx+1)(2ny+1) − nx·ny
        assert_eq!(m.nodes.len(), (9 * 9 - 16) + (19 * 13 - 54));
        assert_eq!(m.elements.len(), 16 + 54);
        let xs = graded_axis("f", "x", &[0., 20., 60.], &[4, 5], &[0.25, 8.0], 1).unwrap();
        let h: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
        assert!((h[3] / h[0] - 0.25).abs() < 1e-12 && (h[8] / h[4] - 8.0).abs() < 1e-12);
        let iface = &m.interfaces[0];
        assert_eq!(iface.edges.len(), 4);
        for e in &iface.edges {
            for i in 0..3 {
                assert_eq!(m.nodes[e.a[i]], m.nodes[e.b[i]]);
                assert_ne!(e.a[i], e.b[i]);
            }
            assert!(m.nodes[e.a[0]][0] < m.nodes[e.a[2]][0]);
        }
        // top edge walked with the body on the left: outward normal (dy, −dx) points up
        let top = &m.edge_sets["punch.top"][0];
        let (x0, x2) = (m.nodes[top[0]], m.nodes[top[2]]);
        assert!(-(x2[0] - x0[0]) > 0.0);
        let r2 = generate(&bl, &ifs, 2).unwrap();
        assert_eq!(r2.elements.len(), 4 * m.elements.len());
    }

    #[test]
    fn mismatched_interface_and_bad_specs_are_named() {
        let (mut bl, ifs) = punch();
        bl[0].nx = vec![3];
        let e = generate(&bl, &ifs, 1).unwrap_err();
        assert!(
            e.0.contains("interface \"contact\"") && e.0.contains("partner"),
            "{e}"
        );
        let (mut bl, ifs) = punch();
        bl[1].rx = vec![1.0];
        assert!(generate(&bl, &ifs, 1)
            .unwrap_err()
            .0
            .contains("rx has 1 entries"));
        let (mut bl, ifs) = punch();
        bl[1].x = vec![0.0, 30.0, 20.0];
        assert!(generate(&bl, &ifs, 1)
            .unwrap_err()
            .0
            .contains("strictly increasing"));
    }

    fn block(body: &str, x: Vec<f64>, nx: Vec<usize>, y: Vec<f64>, ny: Vec<usize>) -> BlockSpec {
        BlockSpec {
            body: body.into(),
            x,
            nx,
            rx: Vec::new(),
            y,
            ny,
            ry: Vec::new(),
            bottom: None,
            top: None,
        }
    }

    fn iface(name: &str, sides: [Option<&str>; 4]) -> InterfaceSpec {
        let s = |i: usize| sides[i].map(String::from);
        InterfaceSpec {
            name: name.into(),
            upper: s(0),
            lower: s(1),
            upper_curve: None,
            lower_curve: None,
            left: s(2),
            right: s(3),
            matching: None,
        }
    }

    /// A shaft (x ≤ 10) in a hub (x ≥ 10, 10 ≤ y ≤ 30) that sits on a base
    /// (y ≤ 10): one vertical and one horizontal interface.
    fn shaft_hub_base() -> (Vec<BlockSpec>, Vec<InterfaceSpec>) {
        (
            vec![
                block(
                    "shaft",
                    vec![0., 10.],
                    vec![2],
                    vec![0., 10., 30., 40.],
                    vec![2, 4, 1],
                ),
                block("hub", vec![10., 30.], vec![4], vec![10., 30.], vec![4]),
                block(
                    "base",
                    vec![10., 20., 30.],
                    vec![2, 2],
                    vec![-10., 10.],
                    vec![2],
                ),
            ],
            vec![
                iface("fit", [None, None, Some("shaft"), Some("hub")]),
                iface("seat", [Some("hub"), Some("base"), None, None]),
            ],
        )
    }

    #[test]
    fn a_vertical_interface_pairs_the_right_side_of_left_with_the_left_side_of_right() {
        let (bl, ifs) = shaft_hub_base();
        let m = generate(&bl, &ifs, 1).unwrap();
        m.validate().unwrap();
        assert_eq!(m.interfaces.len(), 2);
        let fit = &m.interfaces[0];
        assert_eq!((fit.body_a, fit.body_b), (0, 1));
        // four hub elements along 10 ≤ y ≤ 30, walked upwards (B on the right)
        assert_eq!(fit.edges.len(), 4);
        let mut last_y = 10.0;
        for e in &fit.edges {
            let y = e.a.map(|n| m.nodes[n][1]);
            assert!(
                y[0] == last_y && y[0] < y[1] && y[1] < y[2],
                "{y:?} after {last_y}"
            );
            last_y = y[2];
            for i in 0..3 {
                let (xa, xb) = (m.nodes[e.a[i]], m.nodes[e.b[i]]);
                assert_eq!(xa, xb);
                assert_ne!(e.a[i], e.b[i]);
                assert_eq!(xa[0], 10.0);
                assert!(m.node_sets["shaft.right"].binary_search(&e.a[i]).is_ok());
                assert!(m.node_sets["hub.left"].binary_search(&e.b[i]).is_ok());
            }
        }
        assert_eq!(last_y, 30.0);
        assert_eq!(m.nodes[fit.edges[0].a[0]][1], 10.0);
        assert_eq!(m.nodes[fit.edges[3].a[2]][1], 30.0);
        // the horizontal one as before: hub bottom on base top, increasing x
        let seat = &m.interfaces[1];
        assert_eq!((seat.body_a, seat.body_b), (1, 2));
        assert_eq!(seat.edges.len(), 4);
        for w in seat.edges.windows(2) {
            assert!(m.nodes[w[0].a[2]][0] <= m.nodes[w[1].a[0]][0]);
        }
        assert!(seat
            .edges
            .iter()
            .all(|e| e.a.iter().all(|&n| m.nodes[n][1] == 10.0)));
    }

    #[test]
    fn vertical_interface_errors_are_named() {
        let check = |bl: &[BlockSpec], ifs: &[InterfaceSpec], want: &[&str]| {
            let e = generate(bl, ifs, 1).unwrap_err().0;
            for w in want {
                assert!(e.contains(w), "{e:?} lacks {w:?}");
            }
        };
        // the hub moved away from the shaft: the sides do not face each other
        let (mut bl, ifs) = shaft_hub_base();
        bl[1].x = vec![11., 30.];
        check(
            &bl,
            &ifs[..1],
            &[
                "interface \"fit\"",
                "the right side of \"shaft\" is at x = 10",
                "the left side of \"hub\" is at x = 11",
            ],
        );
        // the hub above the shaft: no overlap in y
        let (mut bl, ifs) = shaft_hub_base();
        bl[1].y = vec![40., 60.];
        check(&bl, &ifs[..1], &["do not overlap in y"]);
        // a coarser hub: unmatched nodes
        let (mut bl, ifs) = shaft_hub_base();
        bl[1].ny = vec![3];
        check(&bl, &ifs[..1], &["node at y = ", "no partner"]);
        // the shaft's element edge crosses the hub's end
        let (mut bl, ifs) = shaft_hub_base();
        bl[0].ny = vec![1, 4, 1];
        bl[1].y = vec![5., 15., 30.];
        bl[1].ny = vec![1, 3];
        check(
            &bl,
            &ifs[..1],
            &["straddles the end of the overlap at y = "],
        );
        // mixed and incomplete specifications
        let (bl, _) = shaft_hub_base();
        let mixed = iface("fit", [Some("shaft"), None, None, Some("hub")]);
        check(&bl, &[mixed], &["interface \"fit\"", "not both"]);
        let half = iface("fit", [None, None, Some("shaft"), None]);
        check(&bl, &[half], &["give left and right"]);
        let none = iface("fit", [None, None, None, None]);
        check(&bl, &[none], &["give upper and lower", "or left and right"]);
        let same = iface("fit", [None, None, Some("hub"), Some("hub")]);
        check(&bl, &[same], &["left and right are the same block"]);
        let unknown = iface("fit", [None, None, Some("shaft"), Some("sleeve")]);
        check(&bl, &[unknown], &["no block named \"sleeve\""]);
    }

    #[test]
    fn the_debug_text_of_a_horizontal_spec_is_unchanged_by_left_and_right() {
        let (_, ifs) = punch();
        assert_eq!(
            format!("{:?}", ifs[0]),
            "InterfaceSpec { name: \"contact\", upper: Some(\"punch\"), lower: Some(\"foundation\"), upper_curve: None, lower_curve: None }"
        );
        let v = iface("fit", [None, None, Some("shaft"), Some("hub")]);
        assert!(format!("{v:?}").ends_with("left: Some(\"shaft\"), right: Some(\"hub\") }"));
    }

    #[test]
    fn curved_sides_put_every_side_node_on_the_curve() {
        // a cylinder segment: bottom arc of radius 50 with its apex at x = 0
        let mut cyl = block(
            "cyl",
            vec![-10., -2., 2., 10.],
            vec![3, 4, 3],
            vec![0., 20.],
            vec![4],
        );
        cyl.bottom = Some(SideShape {
            radius: Some(50.0),
            center: Some(0.0),
            round_left: None,
            round_right: None,
        });
        // a punch with a 1 mm rounding at its right end, and a crowned top
        let mut punch = block(
            "punch",
            vec![0., 19., 20.],
            vec![4, 3],
            vec![30., 50.],
            vec![4],
        );
        punch.bottom = Some(SideShape {
            radius: None,
            center: None,
            round_left: None,
            round_right: Some(1.0),
        });
        punch.top = Some(SideShape {
            radius: Some(100.0),
            center: None,
            round_left: None,
            round_right: None,
        });
        let m = generate(&[cyl, punch], &[], 1).unwrap();
        m.validate().unwrap();
        for &n in &m.node_sets["cyl.bottom"] {
            let [x, y] = m.nodes[n];
            assert!(
                (x * x + (y - 50.0).powi(2) - 2500.0).abs() < 1e-9,
                "{x} {y}"
            );
        }
        let bottom = &m.node_sets["punch.bottom"];
        let mut on_round = 0;
        for &n in bottom {
            let [x, y] = m.nodes[n];
            if x > 19.0 + 1e-12 {
                on_round += 1;
                assert!(((x - 19.0).powi(2) + (y - 31.0).powi(2) - 1.0).abs() < 1e-12);
            } else {
                assert_eq!(y, 30.0);
            }
        }
        assert_eq!(on_round, 6); // 3 elements: 2 corners, 3 midsides, the end
                                 // the rounding's nodes are evenly spaced in angle, the last at 90°
        let end = m.node_sets["punch.right"]
            .iter()
            .map(|&n| m.nodes[n])
            .min_by(|a, b| a[1].total_cmp(&b[1]))
            .unwrap();
        assert!((end[0] - 20.0).abs() < 1e-12 && (end[1] - 31.0).abs() < 1e-12);
        // the crowned top: highest at the middle (x = 10), 100 mm radius
        for &n in &m.node_sets["punch.top"] {
            let [x, y] = m.nodes[n];
            assert!(((x - 10.0).powi(2) + (y - (50.0 - 100.0)).powi(2) - 1e4).abs() < 1e-8);
        }
    }

    #[test]
    fn curved_side_errors_are_named() {
        let shape = |radius, round_right| SideShape {
            radius,
            center: None,
            round_left: None,
            round_right,
        };
        let check = |b: BlockSpec, ifs: &[InterfaceSpec], want: &str| {
            let e = generate(&[b], ifs, 1).unwrap_err().0;
            assert!(e.contains(want), "{e:?} lacks {want:?}");
        };
        let base = || block("p", vec![0., 19., 20.], vec![2, 1], vec![0., 10.], vec![2]);
        let mut b = base();
        b.bottom = Some(shape(Some(5.0), None));
        check(b, &[], "must stay within 0.9 R");
        let mut b = base();
        b.bottom = Some(shape(Some(50.0), Some(1.0)));
        check(b, &[], "not both");
        let mut b = base();
        b.bottom = Some(shape(None, Some(2.0)));
        check(b, &[], "breakpoint where the right rounding starts, x = 18");
        let mut b = base();
        b.bottom = Some(shape(None, Some(-1.0)));
        check(b, &[], "round_right = -1 must be a positive length");
        let mut b = base();
        b.top = Some(shape(None, None));
        check(b, &[], "block \"p\" top: give radius");
        // a curved side on a matching interface
        let mut up = block("up", vec![0., 20.], vec![2], vec![0., 10.], vec![2]);
        up.bottom = Some(shape(Some(100.0), None));
        let low = block("low", vec![0., 20.], vec![2], vec![-10., 0.], vec![2]);
        let e = generate(
            &[up, low],
            &[iface("c", [Some("up"), Some("low"), None, None])],
            1,
        )
        .unwrap_err()
        .0;
        assert!(
            e.contains("the bottom of block \"up\" is curved") && e.contains("matching = false"),
            "{e}"
        );
    }

    #[test]
    fn inverted_element_is_detected() {
        let (bl, ifs) = punch();
        let mut m = generate(&bl, &ifs, 1).unwrap();
        m.elements[3].nodes.swap(1, 3);
        let e = m.validate().unwrap_err();
        assert!(e.0.contains("element 3") && e.0.contains("inverted"), "{e}");
    }
}
