//! The cut of a pretension section through the mesh: a line x = c or y = h
//! along element edges in a plane mesh, a plane x = c, y = h or z = c along
//! element faces in a 3D one (20-node hexahedra, 10-node tetrahedra).
//!
//! ```text
//!   side(n) = sign(x_axis(n) − c)   (0 within the mesh's tolerance: on the cut)
//!   an element of the body: beyond (some node side +1), before (some −1),
//!                           never both (it would cross the cut)
//!   cut nodes: every node on the cut that elements of both sides hold
//! ```
//!
//! A side of an element on the cut (an edge, or a face: corners and
//! midsides) held by an element of each side is a side of the section; a cut
//! without one misses the body. Every cut node is doubled: the elements
//! beyond take the copy, and so do the sides of sets and interfaces that
//! belong to them ([`carry_to_copies`]).

use crate::error::{Error, Result};
use crate::input::mesh::{Element, Face, Interface, Mesh};
use std::collections::HashMap;

/// The cut x_axis = at through body `body` of a mesh of dimension `dim`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Cut<'a> {
    pub body: usize,
    pub axis: usize,
    pub at: f64,
    pub dim: usize,
    /// The body's name and the section's place (messages).
    pub name: &'a str,
    pub place: &'a str,
}

impl Cut<'_> {
    /// "the line y = 14" or "the plane z = 30".
    fn words(&self) -> String {
        let kind = if self.dim == 3 { "plane" } else { "line" };
        format!("the {kind} {} = {}", ["x", "y", "z"][self.axis], self.at)
    }

    /// What the cut follows: element edges or faces.
    fn sides_word(&self) -> &'static str {
        if self.dim == 3 {
            "face"
        } else {
            "edge"
        }
    }
}

/// An element's sides in global node numbers: its edges [end, mid, end] in
/// a plane mesh, its faces (corners, then midsides; [`crate::physics::element::h20`],
/// [`crate::physics::element::t10`]) in a 3D one.
pub(super) fn element_sides(el: &Element) -> Vec<Vec<usize>> {
    let nodes = el.nodes();
    match el.family.solid() {
        None => el.edges().map(|e| e.to_vec()).collect(),
        Some(solid) => solid
            .faces()
            .iter()
            .map(|f| f.iter().map(|&a| nodes[a]).collect())
            .collect(),
    }
}

/// A side's nodes sorted: the same side seen from either element.
fn key(side: &[usize]) -> Vec<usize> {
    let mut k = side.to_vec();
    k.sort_unstable();
    k
}

/// The pairs of elements that face each other across the cut in the uncut
/// `mesh` (a side of the body on the cut, one element on each side of it).
pub(super) fn facing(mesh: &Mesh, body: usize, axis: usize, at: f64) -> Vec<(usize, usize)> {
    let tol = crate::model::consistency::tolerance(mesh);
    let d = |n: usize| mesh.nodes[n][axis] - at;
    let mut sides: HashMap<Vec<usize>, [Option<usize>; 2]> = HashMap::new();
    for (e, el) in mesh.elements.iter().enumerate() {
        if el.body != body {
            continue;
        }
        let beyond = el.nodes().iter().any(|&n| d(n) > tol);
        for side in element_sides(el) {
            if side.iter().all(|&n| d(n).abs() <= tol) {
                sides.entry(key(&side)).or_default()[usize::from(beyond)] = Some(e);
            }
        }
    }
    sides
        .values()
        .filter_map(|s| Some((s[0]?, s[1]?)))
        .collect()
}

/// Splits the body along the cut: the node pairs (node, its copy), the
/// copies appended to the mesh's nodes.
pub(super) fn split(mesh: &mut Mesh, cut: &Cut<'_>) -> Result<Vec<(usize, usize)>> {
    let (beyond, on_sides) = sides_of_cut(mesh, cut)?;
    let mut nodes: Vec<usize> = on_sides
        .iter()
        .filter(|(_, s)| s[0] && s[1])
        .map(|(&n, _)| n)
        .collect();
    nodes.sort_unstable();
    let copy: HashMap<usize, usize> = nodes
        .iter()
        .enumerate()
        .map(|(i, &n)| (n, mesh.nodes.len() + i))
        .collect();
    let pairs: Vec<(usize, usize)> = nodes.iter().map(|&n| (n, copy[&n])).collect();
    for &n in &nodes {
        let x = mesh.nodes[n];
        mesh.nodes.push(x);
    }
    carry_to_copies(mesh, cut.body, &beyond, &copy);
    Ok(pairs)
}

/// Each element of the body beyond the cut (or before it), and for each
/// node on the cut the sides its elements lie on. Refused: a cut where no
/// node of the body is held by elements of both sides (it misses the body,
/// or only touches its outside: no side of an element, edge or face, on
/// it has the body on both sides), and a cut that an element of the body
/// crosses (through elements alone: it follows no edges or faces; beside
/// such nodes: the body is not cut through, its two sides stay joined by
/// that element).
#[allow(clippy::type_complexity)]
fn sides_of_cut(mesh: &Mesh, cut: &Cut<'_>) -> Result<(Vec<bool>, HashMap<usize, [bool; 2]>)> {
    let tol = crate::model::consistency::tolerance(mesh);
    let side = |n: usize| -> i8 {
        let d = mesh.nodes[n][cut.axis] - cut.at;
        if d > tol {
            1
        } else if d < -tol {
            -1
        } else {
            0
        }
    };
    let mut beyond = vec![false; mesh.elements.len()];
    let mut on_sides: HashMap<usize, [bool; 2]> = HashMap::new();
    let mut crossing = None;
    for (e, el) in mesh.elements.iter().enumerate() {
        if el.body != cut.body {
            continue;
        }
        let s: Vec<i8> = el.nodes().iter().map(|&n| side(n)).collect();
        let (plus, minus) = (s.contains(&1), s.contains(&-1));
        if plus && minus {
            crossing.get_or_insert(e);
            continue;
        }
        beyond[e] = plus;
        for (&n, &sn) in el.nodes().iter().zip(&s) {
            if sn == 0 {
                on_sides.entry(n).or_default()[usize::from(plus)] = true;
            }
        }
    }
    let cut_nodes = on_sides.values().filter(|h| h[0] && h[1]).count();
    if let Some(e) = crossing {
        return Err(crossed(mesh, cut, e, cut_nodes > 0));
    }
    if cut_nodes == 0 {
        return Err(Error::input(
            cut.place,
            format!(
                "does not cut body \"{}\": no element {} of the body on {} has elements of the body on both sides",
                cut.name,
                cut.sides_word(),
                cut.words()
            ),
        ));
    }
    Ok((beyond, on_sides))
}

/// The refusal of a cut that element `e` crosses: `through`, whether the
/// cut holds nodes of both sides elsewhere (then the body is not cut
/// through).
fn crossed(mesh: &Mesh, cut: &Cut<'_>, e: usize, through: bool) -> Error {
    let near = if cut.dim == 3 {
        let c = mesh.corner_mean(e);
        format!("({:.4}, {:.4}, {:.4})", c[0], c[1], c[2])
    } else {
        let c = mesh.node_mean(e);
        format!("({:.4}, {:.4})", c[0], c[1])
    };
    let (name, label, words) = (cut.name, mesh.element_label(e), cut.words());
    let (sides, at) = (cut.sides_word(), ["x", "y", "z"][cut.axis]);
    let message = if through {
        format!(
            "does not cut body \"{name}\" through: element {sides}s of the body lie on {words}, but {label} near {near} crosses it, so the two sides of the cut stay joined there (a section cuts its body across: every element of the body on one side of the cut)"
        )
    } else {
        let mesh_hint = if cut.dim == 3 {
            format!("a block breakpoint or an extrude level at {at} = {}, or a mesh surface there in a Gmsh mesh", cut.at)
        } else {
            format!(
                "a block breakpoint at {at} = {}, or a mesh line there in a Gmsh mesh",
                cut.at
            )
        };
        format!(
            "the cut {at} = {} runs through {label} of body \"{name}\" near {near}: a cut follows element {sides}s ({mesh_hint})",
            cut.at
        )
    };
    Error::input(cut.place, message)
}

/// A side of an element of the cut body, by its sorted nodes: whether it
/// belongs to an element beyond the cut (then it takes the copies).
struct Owned<'a> {
    beyond: HashMap<Vec<usize>, bool>,
    copy: &'a HashMap<usize, usize>,
}

impl Owned<'_> {
    /// Renumbers a side (an edge or a face, any order) onto the copies if
    /// an element beyond the cut holds it.
    fn renumber(&self, side: &mut [usize]) {
        if self.beyond.get(&key(side)) == Some(&true) {
            for n in side.iter_mut() {
                if let Some(&c) = self.copy.get(n) {
                    *n = c;
                }
            }
        }
    }
}

/// The elements beyond the cut, and the edges, faces, interface sides and
/// node sets that belong to them, take the copies of the cut's nodes.
fn carry_to_copies(mesh: &mut Mesh, body: usize, beyond: &[bool], copy: &HashMap<usize, usize>) {
    // the sides of the elements at the cut: their element decides
    let mut owned = Owned {
        beyond: HashMap::new(),
        copy,
    };
    for (e, el) in mesh.elements.iter().enumerate() {
        if el.body != body || !el.nodes().iter().any(|n| copy.contains_key(n)) {
            continue;
        }
        for side in element_sides(el) {
            owned.beyond.insert(key(&side), beyond[e]);
        }
    }
    for edges in mesh.edge_sets.values_mut() {
        edges.iter_mut().for_each(|e| owned.renumber(e));
    }
    for faces in mesh.face_sets.values_mut() {
        for f in faces.iter_mut() {
            let mut nodes = f.nodes().to_vec();
            owned.renumber(&mut nodes);
            *f = Face::new(f.family, &nodes);
        }
    }
    carry_interfaces(&mut mesh.interfaces, &owned);
    carry_node_sets(mesh, body, beyond, copy);
    for (e, el) in mesh.elements.iter_mut().enumerate() {
        if beyond[e] {
            for n in el.nodes_mut() {
                if let Some(&c) = copy.get(n) {
                    *n = c;
                }
            }
        }
    }
}

/// The interfaces' sides that belong to elements beyond the cut take the
/// copies: each side of an interface renumbered through `owned`
/// ([`Owned::renumber`], which takes an edge or a face).
fn carry_interfaces(interfaces: &mut [Interface], owned: &Owned<'_>) {
    for iface in interfaces {
        for e in &mut iface.edges {
            owned.renumber(&mut e.a);
            owned.renumber(&mut e.b);
        }
        if let Some(nm) = &mut iface.nonmatching {
            nm.slave.iter_mut().for_each(|e| owned.renumber(e));
            nm.master.iter_mut().for_each(|e| owned.renumber(e));
        }
        // 3D: the faces of both sides
        let face = |f: &mut crate::input::mesh::Face| {
            let mut nodes = f.nodes().to_vec();
            owned.renumber(&mut nodes);
            *f = crate::input::mesh::Face::new(f.family, &nodes);
        };
        for cf in &mut iface.faces {
            face(&mut cf.a);
            face(&mut cf.b);
        }
        if let Some(nm) = &mut iface.nonmatching_faces {
            nm.slave
                .iter_mut()
                .chain(nm.master.iter_mut())
                .for_each(face);
        }
    }
}

/// Node sets: a set whose other nodes all lie on the far side (a side of a
/// block beyond the cut) takes the copies; one that reaches the near side,
/// or lies on the cut alone, keeps the nodes (their copies follow them
/// through the constraints).
fn carry_node_sets(mesh: &mut Mesh, body: usize, beyond: &[bool], copy: &HashMap<usize, usize>) {
    let mut far_side = vec![[false; 2]; mesh.nodes.len()];
    for (e, el) in mesh.elements.iter().enumerate() {
        if el.body == body {
            for &n in el.nodes() {
                far_side[n][usize::from(beyond[e])] = true;
            }
        }
    }
    for set in mesh.node_sets.values_mut() {
        if !set.iter().any(|n| copy.contains_key(n)) {
            continue;
        }
        let others = set.iter().filter(|n| !copy.contains_key(n));
        let (near, far) = others.fold((false, false), |(a, b), &n| {
            let s = far_side.get(n).copied().unwrap_or([false; 2]);
            (a || s[0], b || s[1])
        });
        if far && !near {
            for n in set.iter_mut() {
                if let Some(&c) = copy.get(n) {
                    *n = c;
                }
            }
            set.sort_unstable();
        }
    }
}
