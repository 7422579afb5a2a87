//! Structured meshes of rectangular blocks with geometric grading, one body per
//! block, and contact interfaces between the bottom of one block and the top of
//! another (nodes paired, not merged).
//!
//! Each block gets the node sets and edge sets `<body>.bottom`, `.right`, `.top`,
//! `.left` (edges walked with the body on the left) and the node set `<body>.all`.

use super::{ContactEdge, Element, Interface, Mesh, MeshError};
use serde::Deserialize;

/// A rectangular block; x and y are split into segments at the breakpoints.
#[derive(Clone, Debug, Deserialize)]
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
}

/// Contact between the bottom of block `upper` and the top of block `lower`
/// (generated meshes), or between the physical curves `upper_curve` and
/// `lower_curve` (meshes read from a file; `upper` / `lower` then optional,
/// checked against the bodies the curves lie on).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    pub name: String,
    pub upper: Option<String>,
    pub lower: Option<String>,
    /// File meshes: physical curve on the upper body (its bottom).
    pub upper_curve: Option<String>,
    /// File meshes: physical curve on the lower body (its top).
    pub lower_curve: Option<String>,
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
    first: usize,
    ids: Vec<Vec<usize>>, // ids[j][i], usize::MAX for element centres
    xs: Vec<f64>,
    ys: Vec<f64>,
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
        grids.push(add_block(&mut mesh, b, xs, ys));
    }
    for spec in interfaces {
        let iface = pair_blocks(&mesh, &grids, spec)?;
        mesh.interfaces.push(iface);
    }
    Ok(mesh)
}

fn add_block(mesh: &mut Mesh, body: usize, xs: Vec<f64>, ys: Vec<f64>) -> Grid {
    let (ni, nj) = (2 * (xs.len() - 1) + 1, 2 * (ys.len() - 1) + 1);
    let coord = |v: &[f64], k: usize| {
        if k % 2 == 0 {
            v[k / 2]
        } else {
            0.5 * (v[k / 2] + v[k / 2 + 1])
        }
    };
    let first = mesh.nodes.len();
    let mut ids = vec![vec![usize::MAX; ni]; nj];
    for (j, row) in ids.iter_mut().enumerate() {
        for (i, id) in row.iter_mut().enumerate() {
            if i % 2 == 1 && j % 2 == 1 {
                continue;
            }
            *id = mesh.nodes.len();
            mesh.nodes.push([coord(&xs, i), coord(&ys, j)]);
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
    Grid { first, ids, xs, ys }
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
    if spec.upper_curve.is_some() || spec.lower_curve.is_some() {
        return Err(MeshError(format!(
            "interface \"{}\": upper_curve / lower_curve name physical curves of a mesh file ([mesh] file); generated blocks use upper / lower",
            spec.name
        )));
    }
    let (Some(upper), Some(lower)) = (&spec.upper, &spec.lower) else {
        return Err(MeshError(format!(
            "interface \"{}\": give upper and lower (block names)",
            spec.name
        )));
    };
    let (ua, lb) = (find(upper)?, find(lower)?);
    if ua == lb {
        return Err(MeshError(format!(
            "interface \"{}\": upper and lower are the same block",
            spec.name
        )));
    }
    let (gu, gl) = (&grids[ua], &grids[lb]);
    let (yu, yl) = (gu.ys[0], *gl.ys.last().unwrap_or(&f64::NAN));
    let size = (gu.xs[gu.xs.len() - 1] - gu.xs[0]).max(gl.xs[gl.xs.len() - 1] - gl.xs[0]);
    let tol = 1e-9 * size;
    if (yu - yl).abs() > tol {
        return Err(MeshError(format!(
            "interface \"{}\": the bottom of \"{}\" is at y = {yu} but the top of \"{}\" is at y = {yl}",
            spec.name, upper, lower
        )));
    }
    let lo = gu.xs[0].max(gl.xs[0]);
    let hi = gu.xs[gu.xs.len() - 1].min(gl.xs[gl.xs.len() - 1]);
    if hi - lo <= tol {
        return Err(MeshError(format!(
            "interface \"{}\": the blocks do not overlap in x",
            spec.name
        )));
    }
    let inside = |x: f64| x >= lo - tol && x <= hi + tol;
    let upper_row: Vec<usize> = gu.ids[0].clone();
    let lower_row: Vec<usize> = gl.ids[gl.ids.len() - 1].clone();
    let partner = |n: usize, row: &[usize], body: &str| -> Result<usize, MeshError> {
        let x = mesh.nodes[n][0];
        // the rows run in increasing x: binary search, not a scan (large meshes)
        let first = row.partition_point(|&m| mesh.nodes[m][0] < x - tol);
        row.get(first)
            .copied()
            .filter(|&m| (mesh.nodes[m][0] - x).abs() <= tol)
            .ok_or_else(|| {
                MeshError(format!(
                    "interface \"{}\": node at x = {x} on \"{body}\" has no partner on the other side (the two meshes must match along the interface)",
                    spec.name
                ))
            })
    };
    for &n in lower_row.iter().filter(|&&n| inside(mesh.nodes[n][0])) {
        partner(n, &upper_row, lower)?;
    }
    let mut edges = Vec::new();
    for w in upper_row.windows(3).step_by(2) {
        if !(inside(mesh.nodes[w[0]][0]) && inside(mesh.nodes[w[2]][0])) {
            if inside(mesh.nodes[w[1]][0]) {
                return Err(MeshError(format!(
                    "interface \"{}\": an element edge of \"{}\" straddles the end of the overlap at x = {}",
                    spec.name, upper, mesh.nodes[w[1]][0]
                )));
            }
            continue;
        }
        let a = [w[0], w[1], w[2]];
        let b = [
            partner(a[0], &lower_row, upper)?,
            partner(a[1], &lower_row, upper)?,
            partner(a[2], &lower_row, upper)?,
        ];
        edges.push(ContactEdge { a, b });
    }
    let _ = (gu.first, gl.first);
    Ok(Interface {
        name: spec.name.clone(),
        body_a: ua,
        body_b: lb,
        edges,
    })
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

    #[test]
    fn inverted_element_is_detected() {
        let (bl, ifs) = punch();
        let mut m = generate(&bl, &ifs, 1).unwrap();
        m.elements[3].nodes.swap(1, 3);
        let e = m.validate().unwrap_err();
        assert!(e.0.contains("element 3") && e.0.contains("inverted"), "{e}");
    }
}
