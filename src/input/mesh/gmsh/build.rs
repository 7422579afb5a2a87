//! A parsed [`MshFile`] to the solver's [`Mesh`]: physical surfaces to bodies,
//! physical curves to node and edge sets, interface curves paired node by node
//! or, with `matching = false`, oriented and chained as the two sides of a
//! non-matching interface.

use super::parse::MshFile;

mod solid;
mod surfaces;
use crate::error::{Error, Result};
use crate::input::mesh::blocks::InterfaceSpec;
use crate::input::mesh::{
    ContactEdge, Element, ElementSource, Family, Interface, Mesh, NonMatching,
};
use std::collections::{BTreeMap, HashMap, HashSet};

pub(super) fn mesh_err<T>(place: &str, message: impl Into<String>) -> Result<T> {
    Err(Error::Mesh {
        place: place.to_string(),
        message: message.into(),
    })
}

/// Builds the mesh from a parsed file.
pub fn build_mesh(msh: &MshFile, interfaces: &[InterfaceSpec], place: &str) -> Result<Mesh> {
    if msh.blocks.iter().any(|b| b.dim == 3) {
        return solid::build_solid_mesh(msh, interfaces, place);
    }
    if let Some((at, tag, z)) = &msh.off_plane {
        return mesh_err(
            at,
            format!("node {tag} has z = {z}: a plane mesh (no volume elements) must lie in the plane z = 0"),
        );
    }
    let file = msh.name.as_str();
    let (mut mesh, new_id, tag_of) = bodies(msh, 2)?;
    let curve_body = add_curve_sets(msh, &new_id, &mut mesh, file)?;
    for spec in interfaces {
        let iface = pair_curves(msh, &mesh, &curve_body, &tag_of, spec, place)?;
        mesh.interfaces.push(iface);
    }
    Ok(mesh)
}

/// The bodies of a mesh (physical surfaces, `dim` 2, or physical volumes,
/// `dim` 3) with their elements, nodes and `<body>.all` sets: the mesh, each
/// file node's new number (`usize::MAX` if unused) and each new node's tag.
pub(super) fn bodies(msh: &MshFile, dim: i32) -> Result<(Mesh, Vec<usize>, Vec<u64>)> {
    let file = msh.name.as_str();
    let (block_body, body_tags) = assign_bodies(msh, dim, file)?;
    let mut mesh = Mesh {
        bodies: body_tags
            .iter()
            .map(|t| msh.physical_names[&(dim, *t)].clone())
            .collect(),
        ..Mesh::default()
    };
    let (new_id, tag_of) = add_body_nodes(msh, &block_body, &mut mesh);
    add_elements(msh, &block_body, &new_id, &mut mesh);
    check_bodies_apart(&mesh, &tag_of, file)?;
    add_body_node_sets(&mut mesh);
    Ok((mesh, new_id, tag_of))
}

/// Physical surfaces (`dim` 2, or physical volumes, `dim` 3) → bodies, in
/// order of their tags: per element block its body index (none for blocks
/// outside the bodies), and the bodies' tags.
fn assign_bodies(msh: &MshFile, dim: i32, file: &str) -> Result<(Vec<Option<usize>>, Vec<i32>)> {
    let what = if dim == 3 { "volume" } else { "surface" };
    let mut block_body: Vec<Option<usize>> = vec![None; msh.blocks.len()];
    let mut body_tags: Vec<i32> = Vec::new();
    for (k, b) in msh.blocks.iter().enumerate() {
        if b.dim != dim || b.tags.is_empty() {
            continue;
        }
        let Some(phys) = msh.entities.get(&(dim, b.entity)) else {
            return mesh_err(
                &b.at,
                format!("{what} entity {} is not listed in $Entities", b.entity),
            );
        };
        match phys.as_slice() {
            [] => {
                return mesh_err(
                    &b.at,
                    format!("{what} entity {} has elements but is in no physical {what} (every body must be a named physical {what})", b.entity),
                )
            }
            [t] => {
                if !msh.physical_names.contains_key(&(dim, *t)) {
                    return mesh_err(
                        file,
                        format!("physical {what} {t} has no name in $PhysicalNames (bodies are named by their physical names)"),
                    );
                }
                if !body_tags.contains(t) {
                    body_tags.push(*t);
                }
                block_body[k] = Some(*t as usize); // replaced by the body index below
            }
            more => {
                return mesh_err(
                    &b.at,
                    format!("{what} entity {} is in physical {what}s {more:?}; it must belong to exactly one (one body)", b.entity),
                )
            }
        }
    }
    if body_tags.is_empty() {
        return mesh_err(
            file,
            "no 8-node quadrangles or 6-node triangles in any physical surface: the mesh has no body",
        );
    }
    body_tags.sort_unstable();
    for body in block_body.iter_mut() {
        if let Some(t) = *body {
            let tag = t as i32;
            *body = body_tags.iter().position(|&x| x == tag);
        }
    }
    Ok((block_body, body_tags))
}

/// The nodes used by body elements, numbered in file order: per file node
/// its new number (`usize::MAX` if unused), and per new node its file tag.
fn add_body_nodes(
    msh: &MshFile,
    block_body: &[Option<usize>],
    mesh: &mut Mesh,
) -> (Vec<usize>, Vec<u64>) {
    let mut new_id = vec![usize::MAX; msh.nodes.len()];
    for (k, b) in msh.blocks.iter().enumerate() {
        if block_body[k].is_some() {
            for &n in &b.conn {
                new_id[n] = 0;
            }
        }
    }
    let mut tag_of = Vec::new();
    for (i, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = mesh.nodes.len();
            mesh.nodes.push(msh.nodes[i]);
            tag_of.push(msh.node_tags[i]);
        }
    }
    (new_id, tag_of)
}

/// The body elements (8-node quadrangles, Gmsh type 16, and 6-node
/// triangles, type 9), counter-clockwise.
pub(super) fn add_elements(
    msh: &MshFile,
    block_body: &[Option<usize>],
    new_id: &[usize],
    mesh: &mut Mesh,
) {
    let mut source = ElementSource {
        // the file's own name: the message's place names its folder
        file: std::path::Path::new(&msh.name)
            .file_name()
            .map_or(msh.name.clone(), |f| f.to_string_lossy().into_owned()),
        tags: Vec::new(),
    };
    for (k, b) in msh.blocks.iter().enumerate() {
        let Some(body) = block_body[k] else { continue };
        if b.dim == 3 {
            source.tags.extend(&b.tags);
            solid::add_elements_of(b, body, new_id, mesh);
            continue;
        }
        let family = if b.etype == 9 { Family::T6 } else { Family::Q8 };
        source.tags.extend(&b.tags);
        for conn in b.conn.chunks_exact(family.nodes()) {
            let n: Vec<usize> = conn.iter().map(|&c| new_id[c]).collect();
            let corners = family.corners();
            let area2: f64 = (0..corners)
                .map(|a| {
                    let (p, q) = (mesh.nodes[n[a]], mesh.nodes[n[(a + 1) % corners]]);
                    p[0] * q[1] - q[0] * p[1]
                })
                .sum();
            // clockwise: walk the corners the other way round
            let n = if area2 < 0.0 {
                family.reversed().iter().map(|&a| n[a]).collect()
            } else {
                n
            };
            mesh.elements.push(Element::new(family, &n, body));
        }
    }
    mesh.source = Some(source);
}

/// Refuses a node shared by two bodies (bodies in contact need their own nodes).
fn check_bodies_apart(mesh: &Mesh, tag_of: &[u64], file: &str) -> Result<()> {
    let mut node_body = vec![usize::MAX; mesh.nodes.len()];
    for el in &mesh.elements {
        for &n in el.nodes() {
            if node_body[n] != usize::MAX && node_body[n] != el.body {
                return mesh_err(
                    file,
                    format!(
                        "node {} at ({}, {}) belongs to both bodies \"{}\" and \"{}\": bodies in contact need their own nodes along the interface (Gmsh: separate points and curves there, Geometry.AutoCoherence = 0)",
                        tag_of[n], mesh.nodes[n][0], mesh.nodes[n][1], mesh.bodies[node_body[n]], mesh.bodies[el.body]
                    ),
                );
            }
            node_body[n] = el.body;
        }
    }
    Ok(())
}

/// Each body's own node set, `<body>.all`.
fn add_body_node_sets(mesh: &mut Mesh) {
    for (b, name) in mesh.bodies.iter().enumerate() {
        let mut set: Vec<usize> = mesh
            .elements
            .iter()
            .filter(|e| e.body == b)
            .flat_map(|e| e.nodes().iter().copied())
            .collect();
        set.sort_unstable();
        set.dedup();
        mesh.node_sets.insert(format!("{name}.all"), set);
    }
}

/// The element edges: sorted corner pair → (element, the edge [end, mid,
/// end] as the element walks it).
fn edge_index(mesh: &Mesh) -> HashMap<(usize, usize), (usize, [usize; 3])> {
    let mut edge_of = HashMap::new();
    for (e, el) in mesh.elements.iter().enumerate() {
        for edge @ [p, _, q] in el.edges() {
            edge_of.entry((p.min(q), p.max(q))).or_insert((e, edge));
        }
    }
    edge_of
}

/// Physical curves → node sets and edge sets (edges walked with the body on
/// the left); returns the body each curve lies on.
fn add_curve_sets(
    msh: &MshFile,
    new_id: &[usize],
    mesh: &mut Mesh,
    file: &str,
) -> Result<BTreeMap<String, usize>> {
    let edge_of = edge_index(mesh);
    let mut curve_body: BTreeMap<String, usize> = BTreeMap::new();
    for b in msh.blocks.iter().filter(|b| b.dim == 1) {
        let Some(phys) = msh.entities.get(&(1, b.entity)) else {
            return mesh_err(
                &b.at,
                format!("curve entity {} is not listed in $Entities", b.entity),
            );
        };
        for t in phys {
            let Some(name) = msh.physical_names.get(&(1, *t)) else {
                return mesh_err(
                    file,
                    format!("physical curve {t} has no name in $PhysicalNames (node sets are named by physical names)"),
                );
            };
            if mesh.bodies.iter().any(|b| format!("{b}.all") == *name) {
                return mesh_err(
                    file,
                    format!("physical curve \"{name}\" has the name of a body's own node set"),
                );
            }
            let mut edges = Vec::new();
            let mut nodes = Vec::new();
            for (k, conn) in b.conn.chunks_exact(3).enumerate() {
                let ids: [usize; 3] = std::array::from_fn(|a| new_id[conn[a]]);
                if let Some(a) = ids.iter().position(|&i| i == usize::MAX) {
                    return mesh_err(
                        &b.at,
                        format!(
                            "line element {} of physical curve \"{name}\": node {} is on no body element (is its surface in a physical surface?)",
                            b.tags[k], msh.node_tags[conn[a]]
                        ),
                    );
                }
                let [p, q, mid] = ids;
                let edge = edge_of
                    .get(&(p.min(q), p.max(q)))
                    .and_then(|&(e, edge)| (edge[1] == mid).then(|| (edge, mesh.elements[e].body)));
                let Some((edge, body)) = edge else {
                    return mesh_err(
                        &b.at,
                        format!(
                            "line element {} of physical curve \"{name}\" is not an edge of any quadrangle or triangle",
                            b.tags[k]
                        ),
                    );
                };
                if *curve_body.entry(name.clone()).or_insert(body) != body {
                    return mesh_err(
                        file,
                        format!(
                            "physical curve \"{name}\" lies on two bodies; a set must be on one"
                        ),
                    );
                }
                edges.push(edge);
                nodes.extend(edge);
            }
            let set = mesh.node_sets.entry(name.clone()).or_default();
            set.extend(nodes);
            set.sort_unstable();
            set.dedup();
            mesh.edge_sets
                .entry(name.clone())
                .or_default()
                .extend(edges);
        }
    }
    Ok(curve_body)
}

/// The interface between the upper and lower physical curves: paired node
/// by node, or with `matching = false` as two sides meshed apart
/// ([`nonmatching_curves`]).
fn pair_curves(
    msh: &MshFile,
    mesh: &Mesh,
    curve_body: &BTreeMap<String, usize>,
    tag_of: &[u64],
    spec: &InterfaceSpec,
    place: &str,
) -> Result<Interface> {
    let at = format!("{place}: [[mesh.interface]] \"{}\"", spec.name);
    let bad = |m: String| Error::input(&at, m);
    if spec.left.is_some() || spec.right.is_some() {
        return Err(bad(
            "left / right name blocks of a generated mesh ([[mesh.block]]); a mesh read from a file pairs upper_curve (body A) with lower_curve (body B)"
                .into(),
        ));
    }
    if spec.upper_surface.is_some() || spec.lower_surface.is_some() {
        return Err(bad(format!(
            "upper_surface / lower_surface name physical surfaces of a mesh of volumes; {} is a plane mesh (its physical surfaces are bodies): give upper_curve and lower_curve (physical curves)",
            msh.name
        )));
    }
    let (Some(upper), Some(lower)) = (&spec.upper_curve, &spec.lower_curve) else {
        return Err(bad(
            "a mesh read from a file needs upper_curve and lower_curve (physical curve names)"
                .into(),
        ));
    };
    let (ua, lb) = (
        curve_on_body(msh, curve_body, upper, &at)?,
        curve_on_body(msh, curve_body, lower, &at)?,
    );
    let swapped = spec.upper.as_deref() == Some(mesh.bodies[lb].as_str())
        && spec.lower.as_deref() == Some(mesh.bodies[ua].as_str());
    for (given, body, side, curve) in [
        (&spec.upper, ua, "upper", upper),
        (&spec.lower, lb, "lower", lower),
    ] {
        if let Some(g) = given {
            if *g != mesh.bodies[body] {
                let hint = if swapped {
                    format!(": upper_curve and lower_curve are swapped (upper_curve must lie on body A, \"{}\", the slave side with matching = false)", mesh.bodies[lb])
                } else {
                    String::new()
                };
                return Err(bad(format!(
                    "{side} = \"{g}\" but {side}_curve \"{curve}\" lies on body \"{}\"{hint}",
                    mesh.bodies[body]
                )));
            }
        }
    }
    if ua == lb {
        return Err(bad(format!(
            "upper_curve \"{upper}\" and lower_curve \"{lower}\" are on the same body \"{}\"",
            mesh.bodies[ua]
        )));
    }
    if spec.matching == Some(false) {
        let sides = nonmatching_curves(mesh, tag_of, &msh.name, upper, lower).map_err(bad)?;
        return Ok(Interface {
            name: spec.name.clone(),
            body_a: ua,
            body_b: lb,
            edges: vec![],
            nonmatching: Some(sides),
            ..Default::default()
        });
    }
    Ok(Interface {
        name: spec.name.clone(),
        body_a: ua,
        body_b: lb,
        edges: coincident_edges(msh, mesh, tag_of, upper, lower, &at)?,
        nonmatching: None,
        ..Default::default()
    })
}

/// The two sides of a non-matching interface (`matching = false`) from the
/// physical curves `upper` (body A, the slave side) and `lower` (body B, the
/// master side), which need not share a node nor lie on one line.
///
/// Every edge is oriented by the quadrangle it belongs to, not by its
/// coordinates or by the direction of Gmsh's line elements: the edge sets
/// are already walked with their body on the left ([`add_curve_sets`]),
/// which is the slave side's walk (A on the left); the master edges are
/// turned round (B on the right), so both sides are walked the same way
/// along the interface and the master's left normal points from B into A.
/// An edge must therefore lie on its body's boundary (one quadrangle); an
/// edge between two quadrangles of the body has no side and is refused.
///
/// The slave edges are chained end to start into one piece ([`chain`]: the
/// slave side's arc length runs along it); the master edges stay in file
/// order (each spring point looks for its closest master edge).
fn nonmatching_curves(
    mesh: &Mesh,
    tag_of: &[u64],
    file: &str,
    upper: &str,
    lower: &str,
) -> std::result::Result<NonMatching, String> {
    let inner = inner_edges(mesh);
    for name in [upper, lower] {
        on_boundary(mesh, tag_of, &inner, name, file, &mesh.edge_sets[name])?;
    }
    let slave = chain(mesh, tag_of, upper, file, &mesh.edge_sets[upper])?;
    let master = mesh.edge_sets[lower]
        .iter()
        .map(|e| [e[2], e[1], e[0]])
        .collect();
    Ok(NonMatching { slave, master })
}

/// The element edges (sorted corner pairs) shared by two or more elements.
fn inner_edges(mesh: &Mesh) -> HashSet<(usize, usize)> {
    let mut seen = HashSet::new();
    let mut inner = HashSet::new();
    for el in &mesh.elements {
        for [p, _, q] in el.edges() {
            let key = (p.min(q), p.max(q));
            if !seen.insert(key) {
                inner.insert(key);
            }
        }
    }
    inner
}

/// "node 12 at (2.5, 0)": a node by its tag in the file and its position.
fn node_at(mesh: &Mesh, tag_of: &[u64], n: usize) -> String {
    let x = mesh.nodes[n];
    format!("node {} at ({}, {})", tag_of[n], x[0], x[1])
}

/// Refuses an edge of curve `name` that two quadrangles share (inside its
/// body: which side faces the other body is undefined there).
fn on_boundary(
    mesh: &Mesh,
    tag_of: &[u64],
    inner: &HashSet<(usize, usize)>,
    name: &str,
    file: &str,
    edges: &[[usize; 3]],
) -> std::result::Result<(), String> {
    for e in edges {
        if inner.contains(&(e[0].min(e[2]), e[0].max(e[2]))) {
            return Err(format!(
                "curve \"{name}\" in {file} runs inside its body between two of its elements, from {} to {}: an interface curve must lie on the body's boundary",
                node_at(mesh, tag_of, e[0]),
                node_at(mesh, tag_of, e[2])
            ));
        }
    }
    Ok(())
}

/// The slave curve's edges (each walked with body A on the left) as one
/// chain, every edge starting where the one before ends. An open chain
/// starts at its free end; a closed loop (a body all round the other) is
/// accepted and starts with the curve's first line element in the file.
/// Refused, naming the node: two edges starting or ending at one node (the
/// curve branches, or touches itself), and a curve in several pieces.
fn chain(
    mesh: &Mesh,
    tag_of: &[u64],
    name: &str,
    file: &str,
    edges: &[[usize; 3]],
) -> std::result::Result<Vec<[usize; 3]>, String> {
    let mut by_start: HashMap<usize, usize> = HashMap::with_capacity(edges.len());
    let mut ends: HashSet<usize> = HashSet::with_capacity(edges.len());
    for (k, e) in edges.iter().enumerate() {
        if by_start.insert(e[0], k).is_some() {
            return Err(format!(
                "upper_curve \"{name}\" in {file} (the slave side) branches at {}: two of its edges start there (it must be one chain of edges)",
                node_at(mesh, tag_of, e[0])
            ));
        }
        if !ends.insert(e[2]) {
            return Err(format!(
                "upper_curve \"{name}\" in {file} (the slave side) branches at {}: two of its edges end there (it must be one chain of edges)",
                node_at(mesh, tag_of, e[2])
            ));
        }
    }
    let head = edges
        .iter()
        .position(|e| !ends.contains(&e[0]))
        .unwrap_or(0);
    let mut done = vec![false; edges.len()];
    let mut order = Vec::with_capacity(edges.len());
    let mut k = head;
    while !done[k] {
        done[k] = true;
        order.push(edges[k]);
        match by_start.get(&edges[k][2]) {
            Some(&next) => k = next,
            None => break,
        }
    }
    if order.len() < edges.len() {
        // another piece: preferably its free start
        let rest = (0..edges.len()).filter(|&j| !done[j]);
        let other = rest
            .clone()
            .find(|&j| !ends.contains(&edges[j][0]))
            .or_else(|| rest.min())
            .unwrap_or(0);
        let last = order.last().map_or(edges[head][2], |e| e[2]);
        return Err(format!(
            "upper_curve \"{name}\" in {file} (the slave side) is not one connected chain of edges: it breaks off at {} and goes on at {} ({} of its {} edges are in other pieces; give each piece an interface of its own)",
            node_at(mesh, tag_of, last),
            node_at(mesh, tag_of, edges[other][0]),
            edges.len() - order.len(),
            edges.len()
        ));
    }
    Ok(order)
}

/// The body the physical curve `name` lies on; an error naming what `name`
/// is instead, or the curves there are, if it is not a physical curve.
fn curve_on_body(
    msh: &MshFile,
    curve_body: &BTreeMap<String, usize>,
    name: &str,
    at: &str,
) -> Result<usize> {
    if let Some(&b) = curve_body.get(name) {
        return Ok(b);
    }
    if let Some((&(d, _), _)) = msh.physical_names.iter().find(|(_, n)| *n == name) {
        if d == 1 {
            return Err(Error::input(
                at,
                format!(
                    "physical curve \"{name}\" in {} is empty: it holds no line elements (is its curve meshed?)",
                    msh.name
                ),
            ));
        }
        let what = [
            "a physical point",
            "a physical curve",
            "a physical surface",
            "a physical volume",
        ][d.clamp(0, 3) as usize];
        return Err(Error::input(
            at,
            format!(
                "\"{name}\" is {what} (dimension {d}) in {}, not a physical curve of 3-node lines",
                msh.name
            ),
        ));
    }
    Err(Error::input(
        at,
        format!(
            "physical curve \"{name}\" not found in {} (physical curves: {})",
            msh.name,
            curve_body.keys().cloned().collect::<Vec<_>>().join(", ")
        ),
    ))
}

/// The contact edges: each edge of the upper curve with the coincident nodes
/// of the lower one (within 1e-9 of the shortest edge); the lower curve's
/// nodes within the extent of the upper one must all have a partner too.
fn coincident_edges(
    msh: &MshFile,
    mesh: &Mesh,
    tag_of: &[u64],
    upper: &str,
    lower: &str,
    at: &str,
) -> Result<Vec<ContactEdge>> {
    let a_edges = &mesh.edge_sets[upper];
    let b_edges = &mesh.edge_sets[lower];
    let h = a_edges
        .iter()
        .chain(b_edges)
        .map(|e| {
            let (p, q) = (mesh.nodes[e[0]], mesh.nodes[e[2]]);
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .fold(f64::INFINITY, f64::min);
    let tol = 1e-9 * h;
    let b_nodes = &mesh.node_sets[lower];
    let a_nodes = &mesh.node_sets[upper];
    let near = |x: [f64; 2], set: &[usize]| {
        set.iter()
            .copied()
            .find(|&m| (mesh.nodes[m][0] - x[0]).hypot(mesh.nodes[m][1] - x[1]) <= tol)
    };
    let unpaired = |n: usize, on: &str, other: &str| -> Result<Vec<ContactEdge>> {
        let x = mesh.nodes[n];
        Err(Error::input(at, format!(
            "node {} at ({}, {}) of curve \"{on}\" in {} has no partner on curve \"{other}\" within {tol:.1e} mm (the two sides must have coincident nodes; an interference is the law's negative `gap`, not an overlap in the mesh, and sides meshed apart take `matching = false`)",
            tag_of[n], x[0], x[1], msh.name
        )))
    };
    let mut edges = Vec::with_capacity(a_edges.len());
    for e in a_edges {
        let mut b = [0; 3];
        for i in 0..3 {
            match near(mesh.xy(e[i]), b_nodes) {
                Some(m) => b[i] = m,
                None => return unpaired(e[i], upper, lower),
            }
        }
        edges.push(ContactEdge { a: *e, b });
    }
    // nodes of the lower curve within the extent of the upper one must be paired too
    let (lo, hi) = a_nodes.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), &n| {
            let x = mesh.nodes[n];
            (
                [lo[0].min(x[0]), lo[1].min(x[1])],
                [hi[0].max(x[0]), hi[1].max(x[1])],
            )
        },
    );
    for &n in b_nodes {
        let x = mesh.xy(n);
        let inside = (0..2).all(|k| x[k] >= lo[k] - tol && x[k] <= hi[k] + tol);
        if inside && near(x, a_nodes).is_none() {
            return unpaired(n, lower, upper);
        }
    }
    Ok(edges)
}

#[cfg(test)]
mod tests;
