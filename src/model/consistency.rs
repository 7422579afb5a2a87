//! Checks of the model as a whole, after parsing and meshing.
//!
//! Every key can be valid on its own and the model still wrong: two interfaces
//! over the same node pairs (every spring twice), an empty body name, two
//! bodies covering the same area, a "symmetric half" that is not the half
//! x ≥ 0, coordinates and element sizes far outside any engineering use.
//! `check_mesh` runs on the mesh before anything is derived from it and
//! `check_symmetry_supports` once the prescribed dofs are known; both from
//! [`crate::model::Model::build`], which `asperity check`, `asperity run` and
//! every MPI rank go through alike.

use crate::error::{clip, Error, Result};
use crate::input::case::ranges;
use crate::input::case::{Case, MAX_ELEMENTS};
use crate::input::mesh::Mesh;
use std::collections::{BTreeMap, HashMap, HashSet};

mod faces;

fn mesh_err(place: &str, message: String) -> Error {
    Error::Mesh {
        place: place.to_string(),
        message,
    }
}

/// Bounding box of the nodes: (lower corner, upper corner).
fn extent(mesh: &Mesh) -> ([f64; 2], [f64; 2]) {
    mesh.nodes.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), x| {
            (
                [lo[0].min(x[0]), lo[1].min(x[1])],
                [hi[0].max(x[0]), hi[1].max(x[1])],
            )
        },
    )
}

/// Geometric tolerance: 1e-9 of the model's size.
pub(crate) fn tolerance(mesh: &Mesh) -> f64 {
    let (lo, hi) = extent(mesh);
    1e-9 * (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}

/// The whole-mesh checks (see the module text). `place` names the case file.
pub(crate) fn check_mesh(case: &Case, mesh: &Mesh, place: &str) -> Result<()> {
    if mesh.elements.len() > MAX_ELEMENTS {
        return Err(mesh_err(
            place,
            format!(
                "{} elements, more than {MAX_ELEMENTS} elements (the limit)",
                mesh.elements.len()
            ),
        ));
    }
    names(mesh, place)?;
    magnitudes(case, mesh, place)?;
    gaps_within_bodies(case, mesh)?;
    match &case.mesh.file {
        None => blocks_overlap(case, place)?,
        Some(_) if mesh.dim() == 3 => crate::model::solid_overlap::check(mesh, place)?,
        Some(_) => elements_overlap(mesh, place)?,
    }
    if case.model.symmetric_half {
        symmetric_half(mesh, place)?;
    }
    if case.model.plane == crate::physics::material::Plane::Axisymmetric {
        axisymmetric_half_plane(mesh, place)?;
    }
    Ok(())
}

/// `plane = "axisymmetric"`: x is the radius, so no node may lie at r < 0
/// (beyond the geometric tolerance: such a node is on the axis).
fn axisymmetric_half_plane(mesh: &Mesh, place: &str) -> Result<()> {
    let tol = tolerance(mesh);
    let Some(n) = mesh.nodes.iter().position(|x| x[0] < -tol) else {
        return Ok(());
    };
    let x = mesh.nodes[n];
    let body = mesh
        .elements
        .iter()
        .find(|el| el.nodes().contains(&n))
        .map_or("?", |el| mesh.bodies[el.body].as_str());
    Err(Error::input(
        format!("{place}: [model] plane"),
        format!(
            "is \"axisymmetric\" (x is the radius r ≥ 0), but body \"{}\" has node {n} at (x = {}, y = {}), r < 0: mesh the half plane x ≥ 0 only, with the axis at x = 0",
            clip(body),
            x[0],
            x[1]
        ),
    ))
}

/// The node pairs at the ends of an interface's edges that end one edge
/// only: the ends of its runs of edges.
fn run_ends(iface: &crate::input::mesh::Interface) -> HashSet<(usize, usize)> {
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    for e in &iface.edges {
        for i in [0, 2] {
            *count.entry((e.a[i], e.b[i])).or_default() += 1;
        }
    }
    count
        .into_iter()
        .filter(|&(_, c)| c == 1)
        .map(|(p, _)| p)
        .collect()
}

/// Body and interface names: not empty, unique; no node pair in two
/// interfaces, but where the edges of both end (two blocks of one body side
/// by side under one face, each with its interface, meet at one node; each
/// interface springs its own edges' share of it).
fn names(mesh: &Mesh, place: &str) -> Result<()> {
    for (b, name) in mesh.bodies.iter().enumerate() {
        if name.trim().is_empty() || name.trim() != name {
            return Err(mesh_err(
                place,
                format!(
                    "body {b} is named \"{}\": a body name must not be empty or blank or have blanks around it (it names its sets and [materials.<body>])",
                    clip(name)
                ),
            ));
        }
        if mesh.bodies[..b].contains(name) {
            return Err(mesh_err(
                place,
                format!("two bodies are named \"{}\"", clip(name)),
            ));
        }
    }
    let mut owner: HashMap<(usize, usize), usize> = HashMap::new();
    let ends: Vec<_> = mesh.interfaces.iter().map(run_ends).collect();
    for (k, iface) in mesh.interfaces.iter().enumerate() {
        if iface.name.trim().is_empty() {
            return Err(mesh_err(place, format!("interface {k} has an empty name")));
        }
        if mesh.interfaces[..k].iter().any(|i| i.name == iface.name) {
            return Err(mesh_err(
                place,
                format!(
                    "two interfaces are named \"{}\": every pair would get its springs twice",
                    clip(&iface.name)
                ),
            ));
        }
        for e in &iface.edges {
            for i in 0..3 {
                let pair = (e.a[i], e.b[i]);
                match owner.get(&pair) {
                    Some(&j) if j != k && !(ends[j].contains(&pair) && ends[k].contains(&pair)) => {
                        let x = mesh.nodes[pair.0];
                        return Err(mesh_err(
                            place,
                            format!(
                                "interfaces \"{}\" and \"{}\" both pair the nodes at ({}, {}) of bodies \"{}\" / \"{}\": the same contact twice would get its springs twice",
                                clip(&mesh.interfaces[j].name),
                                clip(&iface.name),
                                x[0],
                                x[1],
                                clip(&mesh.bodies[iface.body_a]),
                                clip(&mesh.bodies[iface.body_b])
                            ),
                        ));
                    }
                    _ => {
                        owner.insert(pair, k);
                    }
                }
            }
        }
    }
    shared_sides(mesh, place)?;
    faces::shared_faces(mesh, place)
}

/// No boundary edge on a side of two interfaces, whatever their coupling: two
/// non-matching interfaces over the same sides, or a matching and a
/// non-matching one, would spring the same contact twice (and halve the load
/// each reports). An edge is known by its mid node, which belongs to one edge.
fn shared_sides(mesh: &Mesh, place: &str) -> Result<()> {
    let mut side: HashMap<usize, usize> = HashMap::new();
    for (k, iface) in mesh.interfaces.iter().enumerate() {
        let edges: Vec<[usize; 3]> = match &iface.nonmatching {
            Some(nm) => {
                // the master side may reach beyond the slave side (a block's
                // whole top under a narrower punch): only its edges facing
                // the slave side are in contact, those whose mid node lies
                // within half the shortest slave edge of the slave side's
                // box (across a gap as well)
                let (lo, hi) = nm.slave.iter().flatten().fold(
                    ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
                    |(lo, hi), &n| {
                        let x = mesh.nodes[n];
                        (
                            [lo[0].min(x[0]), lo[1].min(x[1])],
                            [hi[0].max(x[0]), hi[1].max(x[1])],
                        )
                    },
                );
                let shortest = nm.slave.iter().fold(f64::INFINITY, |m, e| {
                    let (a, b) = (mesh.nodes[e[0]], mesh.nodes[e[2]]);
                    m.min((b[0] - a[0]).hypot(b[1] - a[1]))
                });
                let pad = 0.5 * shortest;
                let faces = |e: &&[usize; 3]| {
                    let x = mesh.nodes[e[1]];
                    (0..2).all(|c| x[c] > lo[c] - pad && x[c] < hi[c] + pad)
                };
                nm.slave
                    .iter()
                    .chain(nm.master.iter().filter(faces))
                    .copied()
                    .collect()
            }
            None => iface.edges.iter().flat_map(|e| [e.a, e.b]).collect(),
        };
        for e in edges {
            match side.insert(e[1], k) {
                Some(j) if j != k => {
                    let x = mesh.nodes[e[1]];
                    return Err(mesh_err(
                        place,
                        format!(
                            "interfaces \"{}\" and \"{}\" both use the edge with mid node {} at ({}, {}): the same contact would get its springs twice and each would report half the load; pose one interface per pair of sides",
                            clip(&mesh.interfaces[j].name),
                            clip(&iface.name),
                            e[1],
                            x[0],
                            x[1]
                        ),
                    ));
                }
                _ => {}
            }
        }
    }
    Ok(())
}

/// Node coordinates and element sizes within [`ranges::COORDINATE`] and
/// [`ranges::ELEMENT_SIZE`]; an element size, which no key gives, is refused
/// at the keys that made it ([`sized_by`]).
fn magnitudes(case: &Case, mesh: &Mesh, place: &str) -> Result<()> {
    for (n, x) in mesh.nodes.iter().enumerate() {
        for v in x {
            if !ranges::COORDINATE.admits(*v) {
                return Err(mesh_err(
                    place,
                    format!(
                        "node {n} at ({}, {}): {}",
                        x[0],
                        x[1],
                        ranges::COORDINATE.refusal(*v)
                    ),
                ));
            }
        }
    }
    for (e, el) in mesh.elements.iter().enumerate() {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for x in el.corners().iter().map(|&n| mesh.nodes[n]) {
            for k in 0..2 {
                lo[k] = lo[k].min(x[k]);
                hi[k] = hi[k].max(x[k]);
            }
        }
        let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
        if !ranges::ELEMENT_SIZE.admits(size) || size == 0.0 {
            let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
            return Err(Error::input(
                sized_by(case, el.body, mesh, centre, place),
                format!(
                    "{} of body \"{}\" near ({}, {}): {}",
                    mesh.element_label(e),
                    clip(&mesh.bodies[el.body]),
                    mesh.nodes[el.nodes()[0]][0],
                    mesh.nodes[el.nodes()[0]][1],
                    ranges::ELEMENT_SIZE.refusal(size)
                ),
            ));
        }
    }
    Ok(())
}

/// The largest interference a small-strain model of a body can close, as a
/// share of the body's size (the diagonal of its bounding box): 10 %, a
/// strain far beyond any metal's yield and near the end of small strain
/// for a polymer (fits are 0.1-0.2 %).
const MAX_INTERFERENCE_SHARE: f64 = 0.1;

/// Each interface's `gap` against the sizes of the bodies it joins: an
/// interference above [`MAX_INTERFERENCE_SHARE`] of the smaller body, or a
/// clearance larger than the smaller body itself, is refused. Either is what
/// a mesh in metres under a case in millimetres gives (the gap then
/// matches or dwarfs the part), and the run would answer without a hint.
fn gaps_within_bodies(case: &Case, mesh: &Mesh) -> Result<()> {
    let mut lo = vec![[f64::INFINITY; 2]; mesh.bodies.len()];
    let mut hi = vec![[f64::NEG_INFINITY; 2]; mesh.bodies.len()];
    for el in &mesh.elements {
        for &n in el.corners() {
            for k in 0..2 {
                lo[el.body][k] = lo[el.body][k].min(mesh.nodes[n][k]);
                hi[el.body][k] = hi[el.body][k].max(mesh.nodes[n][k]);
            }
        }
    }
    let size = |b: usize| (hi[b][0] - lo[b][0]).hypot(hi[b][1] - lo[b][1]);
    for iface in &mesh.interfaces {
        let Some(law) = case.interface.get(&iface.name) else {
            continue;
        };
        let (a, b) = (iface.body_a, iface.body_b);
        let (smaller, body) = if size(a) <= size(b) {
            (size(a), a)
        } else {
            (size(b), b)
        };
        let (limit, what, beyond) = if law.gap < 0.0 {
            let beyond = format!(
                "more than the {} % small strain can close",
                100.0 * MAX_INTERFERENCE_SHARE
            );
            (MAX_INTERFERENCE_SHARE * smaller, "an interference", beyond)
        } else {
            (
                smaller,
                "a clearance",
                "larger than the body itself".to_string(),
            )
        };
        if law.gap.abs() > limit {
            return Err(Error::input(
                case.at(&format!("[interface.{}] gap", clip(&iface.name))),
                format!(
                    "gap = {} mm is {what} of {} % of body \"{}\" ({} mm across), {beyond}: \
                     are the case and the mesh in the same unit (mm; a mesh in metres is 1000 \
                     times too small)?",
                    law.gap,
                    crate::numbers::sig(100.0 * law.gap.abs() / smaller, 3),
                    clip(&mesh.bodies[body]),
                    crate::numbers::sig(smaller, 4),
                ),
            ));
        }
    }
    Ok(())
}

/// The keys that sized an element of `body` centred at `centre`: the Gmsh
/// file, or its block's breakpoints, counts and ratios (the block whose
/// rectangle holds the centre, else every block of the body), with the
/// refinement (`[mesh] refine`, `--refine`, `refine_region`) when there is
/// one.
fn sized_by(case: &Case, body: usize, mesh: &Mesh, centre: [f64; 2], place: &str) -> String {
    if case.mesh.file.is_some() {
        return case.at("[mesh] file");
    }
    let name = &mesh.bodies[body];
    let of_body: Vec<_> = case.mesh.block.iter().filter(|b| b.body == *name).collect();
    let within = |v: f64, at: &[f64]| {
        let (a, b) = (at.first().copied(), at.last().copied());
        a.zip(b)
            .is_some_and(|(a, b)| v >= a.min(b) && v <= a.max(b))
    };
    let mut keys = match of_body
        .iter()
        .find(|b| within(centre[0], &b.x) && within(centre[1], &b.y))
    {
        Some(b) => {
            let mut k = vec!["x", "nx"];
            k.extend((!b.rx.is_empty()).then_some("rx"));
            k.extend(["y", "ny"]);
            k.extend((!b.ry.is_empty()).then_some("ry"));
            format!("[[mesh.block]] \"{}\" {}", clip(b.name()), k.join(", "))
        }
        None => format!("the [[mesh.block]] entries of body \"{}\"", clip(name)),
    };
    if let Some(r) = &case.mesh.refine_region {
        let inside = centre[0] >= r.x[0]
            && centre[0] <= r.x[1]
            && centre[1] >= r.y[0]
            && centre[1] <= r.y[1];
        if inside {
            keys += ", [mesh] refine_region";
        }
    }
    match case.option("[mesh] refine") {
        Some(o) => format!("{place}: {keys} (refined by {o})"),
        None if case.mesh.refine != 1 => format!("{place}: {keys}, [mesh] refine"),
        None => format!("{place}: {keys}"),
    }
}

/// Generated blocks: no two rectangles share area.
fn blocks_overlap(case: &Case, place: &str) -> Result<()> {
    let rect = |b: &crate::input::mesh::blocks::BlockSpec| {
        let (x, y) = (&b.x, &b.y);
        [x[0], x[x.len() - 1], y[0], y[y.len() - 1]]
    };
    let blocks: Vec<_> = case
        .mesh
        .block
        .iter()
        .filter(|b| b.x.len() >= 2 && b.y.len() >= 2)
        .collect();
    for (j, b) in blocks.iter().enumerate() {
        let r = rect(b);
        for a in &blocks[..j] {
            if let Some([x0, x1, y0, y1]) = crate::input::mesh::blocks::common_area(r, rect(a)) {
                return Err(Error::input(
                    format!("{place}: [[mesh.block]]"),
                    format!(
                        "blocks \"{}\" and \"{}\" overlap in x = {x0} … {x1}, y = {y0} … {y1}: two bodies cannot fill the same area",
                        clip(a.name()),
                        clip(b.name())
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The points of element e that must not lie inside an element of another
/// body: its nodes, its reduced rule's Gauss points and its centre.
fn samples(mesh: &Mesh, e: usize) -> Vec<[f64; 2]> {
    let el = &mesh.elements[e];
    let c = mesh.element_coords(e);
    let mut pts: Vec<[f64; 2]> = c[..el.nodes().len()].to_vec();
    let rule = el.family.rule(false);
    for xi in rule
        .points
        .iter()
        .map(|p| p.0)
        .chain([el.family.centre_xi()])
    {
        let nn = el.family.shape(xi);
        let mut p = [0.0; 2];
        for a in 0..el.nodes().len() {
            p[0] += nn[a] * c[a][0];
            p[1] += nn[a] * c[a][1];
        }
        pts.push(p);
    }
    pts
}

/// Do elements a and b share area by more than `tol` (a sample point of one
/// strictly inside the other, or two sides crossing)? `h` is the smaller
/// element's size.
fn share_area(mesh: &Mesh, a: usize, b: usize, tol: f64, h: f64) -> bool {
    let (pa, pb) = (mesh.outline(a), mesh.outline(b));
    let (na, nb) = (pa.len(), pb.len());
    samples(mesh, a)
        .iter()
        .any(|&p| strictly_inside(p, &pb, tol))
        || samples(mesh, b)
            .iter()
            .any(|&p| strictly_inside(p, &pa, tol))
        || (0..na).any(|i| {
            (0..nb).any(|j| {
                properly_cross(
                    [pa[i], pa[(i + 1) % na]],
                    [pb[j], pb[(j + 1) % nb]],
                    tol * h,
                )
            })
        })
}

/// Where a message places element e ([`crate::input::mesh::Family::label_point`]).
fn near(mesh: &Mesh, e: usize) -> [f64; 2] {
    mesh.elements[e].family.label_point(&mesh.element_coords(e))
}

fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

/// Is `p` inside the polygon by more than `tol` from its boundary?
fn strictly_inside(p: [f64; 2], poly: &[[f64; 2]], tol: f64) -> bool {
    let mut inside = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        // distance to the segment
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (qx, qy) = (a[0] + t * dx, a[1] + t * dy);
        if (p[0] - qx).hypot(p[1] - qy) <= tol {
            return false;
        }
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Do two segments cross at a point inside both (not at an end, not collinear)?
fn properly_cross(p: [[f64; 2]; 2], q: [[f64; 2]; 2], tol2: f64) -> bool {
    let d1 = cross(p[0], p[1], q[0]);
    let d2 = cross(p[0], p[1], q[1]);
    let d3 = cross(q[0], q[1], p[0]);
    let d4 = cross(q[0], q[1], p[1]);
    d1.abs() > tol2
        && d2.abs() > tol2
        && d3.abs() > tol2
        && d4.abs() > tol2
        && (d1 > 0.0) != (d2 > 0.0)
        && (d3 > 0.0) != (d4 > 0.0)
}

/// File meshes: no element of one body overlaps an element of another (a node,
/// a Gauss point or the centre of one strictly inside the other, or two edges
/// crossing) by more than 1e-6 of the element's size, or by more than
/// [`crate::model::interface::OVERLAP_LIMIT`] of it between two bodies joined by a
/// non-matching interface (their sides are two meshes of one curve; the
/// springs check the overlap at each of their points). Candidates come from
/// a uniform grid of element boxes.
fn elements_overlap(mesh: &Mesh, place: &str) -> Result<()> {
    let n = mesh.elements.len();
    if n == 0 {
        return Ok(());
    }
    let (lo, hi) = extent(mesh);
    let size = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
    // about one element per cell, at most 4n cells
    let side = ((n as f64).sqrt().ceil() as usize).clamp(1, 2048);
    let cell = |x: f64, k: usize| (((x - lo[k]) / size[k] * side as f64) as usize).min(side - 1);
    let boxes: Vec<([f64; 2], [f64; 2])> = (0..n)
        .map(|e| {
            let c = mesh.element_coords(e);
            c[..mesh.elements[e].nodes().len()].iter().fold(
                ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
                |(l, h), x| {
                    (
                        [l[0].min(x[0]), l[1].min(x[1])],
                        [h[0].max(x[0]), h[1].max(x[1])],
                    )
                },
            )
        })
        .collect();
    let mut grid: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
    for (e, (l, h)) in boxes.iter().enumerate() {
        for i in cell(l[0], 0)..=cell(h[0], 0) {
            for j in cell(l[1], 1)..=cell(h[1], 1) {
                grid.entry((i, j)).or_default().push(e);
            }
        }
    }
    // bodies joined by a non-matching interface were meshed apart: their
    // curved sides meet chord against chord, and up to the overlap the
    // node-to-segment springs accept (a fraction of the element) is the
    // two discretisations of one curve, not two bodies in one place
    let apart: std::collections::HashSet<(usize, usize)> = mesh
        .interfaces
        .iter()
        .filter(|i| i.nonmatching.is_some())
        .map(|i| (i.body_a.min(i.body_b), i.body_a.max(i.body_b)))
        .collect();
    let mut seen = std::collections::HashSet::new();
    for cands in grid.values() {
        for (ia, &a) in cands.iter().enumerate() {
            for &b0 in &cands[..ia] {
                // the lower-numbered element first (messages independent of the order)
                let (a, b) = (a.min(b0), a.max(b0));
                let (ea, eb) = (&mesh.elements[a], &mesh.elements[b]);
                if ea.body == eb.body {
                    continue;
                }
                let (ba, bb) = (boxes[a], boxes[b]);
                let h = (ba.1[0] - ba.0[0])
                    .max(ba.1[1] - ba.0[1])
                    .min((bb.1[0] - bb.0[0]).max(bb.1[1] - bb.0[1]));
                let key = (ea.body.min(eb.body), ea.body.max(eb.body));
                let tol = if apart.contains(&key) {
                    crate::model::interface::OVERLAP_LIMIT * h
                } else {
                    1e-6 * h
                };
                if ba.0[0] >= bb.1[0] - tol
                    || bb.0[0] >= ba.1[0] - tol
                    || ba.0[1] >= bb.1[1] - tol
                    || bb.0[1] >= ba.1[1] - tol
                {
                    continue;
                }
                if !seen.insert((a.min(b), a.max(b))) {
                    continue;
                }
                if share_area(mesh, a, b, tol, h) {
                    let m = near(mesh, a);
                    return Err(mesh_err(
                        place,
                        format!(
                            "bodies \"{}\" and \"{}\" overlap: {} of \"{}\" near ({:.4}, {:.4}) and {} of \"{}\" share area (two bodies cannot fill the same area){}",
                            clip(&mesh.bodies[ea.body]),
                            clip(&mesh.bodies[eb.body]),
                            mesh.element_label(a),
                            clip(&mesh.bodies[ea.body]),
                            m[0],
                            m[1],
                            mesh.element_label(b),
                            clip(&mesh.bodies[eb.body]),
                            if apart.contains(&key) {
                                format!("; bodies joined by a non-matching interface may overlap by {} of an element (two meshes of one curve), no more: an interference is a negative `gap` on meshes that touch", crate::model::interface::OVERLAP_LIMIT)
                            } else {
                                String::new()
                            }
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// `symmetric_half`: the mesh is the half x ≥ 0 and reaches the plane x = 0.
fn symmetric_half(mesh: &Mesh, place: &str) -> Result<()> {
    let tol = tolerance(mesh);
    let (lo, _) = extent(mesh);
    if let Some(n) = mesh.nodes.iter().position(|x| x[0] < -tol) {
        let x = mesh.nodes[n];
        return Err(Error::input(
            format!("{place}: [model] symmetric_half"),
            format!(
                "is true, but node {n} at ({}, {}) lies at x < 0: the mesh must be the half x ≥ 0 of a body symmetric about x = 0 (whole-body loads are reported twice the half model's)",
                x[0], x[1]
            ),
        ));
    }
    if lo[0] > tol {
        return Err(Error::input(
            format!("{place}: [model] symmetric_half"),
            format!(
                "is true, but the mesh starts at x = {} > 0: a half model must reach the symmetry plane x = 0",
                lo[0]
            ),
        ));
    }
    Ok(())
}

/// `symmetric_half`: every node on the plane x = 0 is held by ux = 0 (the
/// symmetry condition); otherwise the half model is not half of anything.
///
/// `tied` maps a pretension section's copy of a node to the node: the copy
/// follows the node's ux through the section's tie, so it is held when the
/// node is.
pub(crate) fn check_symmetry_supports(
    case: &Case,
    mesh: &Mesh,
    prescribed: &[(usize, f64)],
    tied: &HashMap<usize, usize>,
    place: &str,
) -> Result<()> {
    if !case.model.symmetric_half {
        return Ok(());
    }
    let tol = tolerance(mesh);
    let ux: HashMap<usize, f64> = prescribed
        .iter()
        .filter(|(d, _)| mesh.node_dofs.node_of(*d).1 == 0)
        .map(|&(d, v)| (mesh.node_dofs.node_of(d).0, v))
        .collect();
    for (n, x) in mesh.nodes.iter().enumerate() {
        let held = tied.get(&n).copied().unwrap_or(n);
        if x[0].abs() <= tol && ux.get(&held) != Some(&0.0) {
            let what = match ux.get(&n) {
                Some(v) => format!("has ux = {v}"),
                None => "has no ux".to_string(),
            };
            return Err(Error::input(
                format!("{place}: [model] symmetric_half"),
                format!(
                    "is true, but node {n} at ({}, {}) on the symmetry plane x = 0 {what}: give ux = 0 on the plane (a [[boundary]] on <body>.left)",
                    x[0], x[1]
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::mesh::blocks::{generate, BlockSpec};

    fn block(body: &str, x: [f64; 2], nx: usize, y: [f64; 2], ny: usize) -> BlockSpec {
        BlockSpec {
            body: body.into(),
            name: None,
            x: x.to_vec(),
            nx: vec![nx],
            rx: vec![],
            y: y.to_vec(),
            ny: vec![ny],
            ry: vec![],
            bottom: None,
            top: None,
            left: None,
            right: None,
        }
    }

    #[test]
    fn touching_bodies_pass_overlapping_ones_are_found_even_as_a_sliver() {
        let touching = generate(
            &[
                block("a", [0.0, 20.0], 4, [0.0, 10.0], 2),
                block("b", [0.0, 40.0], 8, [-10.0, 0.0], 2),
            ],
            &[],
            1,
        )
        .unwrap();
        elements_overlap(&touching, "t").unwrap();
        // a strip 0.1 thick, node columns aligned: no Gauss point inside, but
        // nodes of one are strictly inside elements of the other
        for (dy, dx) in [(0.1, 0.0), (5.0, 0.0), (0.1, 1.3), (10.0, 0.0)] {
            let m = generate(
                &[
                    block("a", [dx, 20.0 + dx], 4, [-dy, 10.0 - dy], 2),
                    block("b", [0.0, 40.0], 8, [-10.0, 0.0], 2),
                ],
                &[],
                1,
            )
            .unwrap();
            let e = elements_overlap(&m, "t").unwrap_err().to_string();
            assert!(e.contains("overlap"), "{dy} {dx}: {e}");
        }
    }

    /// The overlap search at the element cap: 250 000 elements, two bodies.
    #[test]
    fn the_overlap_search_is_fast_at_the_element_cap() {
        let m = generate(
            &[
                block("a", [0.0, 100.0], 500, [0.0, 50.0], 250),
                block("b", [0.0, 100.0], 500, [-50.0, 0.0], 250),
            ],
            &[],
            1,
        )
        .unwrap();
        assert_eq!(m.elements.len(), 250_000);
        let t = std::time::Instant::now();
        elements_overlap(&m, "t").unwrap();
        let s = t.elapsed().as_secs_f64();
        println!("overlap search, 250 000 elements: {s:.2} s");
        assert!(s < 20.0, "{s} s");
    }
}
