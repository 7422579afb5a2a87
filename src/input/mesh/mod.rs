//! Meshes of 8-node quads and 6-node triangles (mixed as a mesh likes), or
//! of 20-node hexahedra and 10-node tetrahedra (a 3D mesh, mixed likewise):
//! bodies, named node, edge and face sets, and (plane meshes) contact
//! interfaces made of paired (coincident, distinct) nodes, or of two sides
//! meshed apart ([`NonMatching`]).

pub mod blocks;
pub(crate) mod box3;
pub(crate) mod extrude;
pub mod gmsh;
pub mod refine;
pub(crate) mod revolve;

pub(crate) use crate::physics::element::dofs::NodeDofs;

use crate::physics::element::edge;
pub use crate::physics::element::family::Family;
use crate::physics::element::family::{MAX_ELEMENT_NODES, MAX_NODES};
use std::collections::BTreeMap;
use std::fmt;

/// One element: its family, its nodes (corners counter-clockwise, then
/// midsides; [`crate::physics::element::q8`], [`crate::physics::element::t6`];
/// in 3D VTK's order, `physics::element::h20`,
/// `physics::element::t10`) and its body.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Element {
    pub family: Family,
    /// The first `family.nodes()` are the element's, the rest usize::MAX.
    slots: [usize; MAX_ELEMENT_NODES],
    pub body: usize,
}

impl Element {
    /// An element of `family` with `nodes` (the family's count).
    pub fn new(family: Family, nodes: &[usize], body: usize) -> Element {
        assert_eq!(
            nodes.len(),
            family.nodes(),
            "a {} has {} nodes",
            family.name(),
            family.nodes()
        );
        let mut slots = [usize::MAX; MAX_ELEMENT_NODES];
        slots[..nodes.len()].copy_from_slice(nodes);
        Element {
            family,
            slots,
            body,
        }
    }

    /// An 8-node quadrilateral.
    pub fn q8(nodes: [usize; 8], body: usize) -> Element {
        Element::new(Family::Q8, &nodes, body)
    }

    /// A 6-node triangle.
    pub fn t6(nodes: [usize; 6], body: usize) -> Element {
        Element::new(Family::T6, &nodes, body)
    }

    /// The element's nodes: corners, then midsides.
    pub fn nodes(&self) -> &[usize] {
        &self.slots[..self.family.nodes()]
    }

    /// The element's nodes, to renumber.
    pub(crate) fn nodes_mut(&mut self) -> &mut [usize] {
        let n = self.family.nodes();
        &mut self.slots[..n]
    }

    /// The corner nodes.
    pub fn corners(&self) -> &[usize] {
        &self.slots[..self.family.corners()]
    }

    /// The sides [end, mid, end] in global node numbers, counter-clockwise.
    pub fn edges(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        self.family.edges().iter().map(|e| e.map(|a| self.slots[a]))
    }
}

/// A boundary face of a 3D mesh: an 8-node quad or a 6-node triangle
/// (corners, then midsides, in [`Family::Q8`] or [`Family::T6`] order),
/// walked counter-clockwise seen from outside the body.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Face {
    pub family: Family,
    slots: [usize; MAX_NODES],
}

impl Face {
    /// A face of `family` (Q8 or T6) with `nodes` (the family's count).
    pub fn new(family: Family, nodes: &[usize]) -> Face {
        assert!(family.dim() == 2 && nodes.len() == family.nodes());
        let mut slots = [usize::MAX; MAX_NODES];
        slots[..nodes.len()].copy_from_slice(nodes);
        Face { family, slots }
    }

    /// The face's nodes: corners, then midsides.
    pub fn nodes(&self) -> &[usize] {
        &self.slots[..self.family.nodes()]
    }
}

/// One contact edge: a quadratic edge [end, mid, end] of body A (upper) and the
/// facing edge of body B (lower); `a[i]` and `b[i]` are paired nodes, both
/// ordered along the interface with B on the right (increasing x for a
/// horizontal interface with A on top).
#[derive(Clone, Debug)]
pub struct ContactEdge {
    pub a: [usize; 3],
    pub b: [usize; 3],
}

/// One contact face of a 3D interface: a face of body A and the facing
/// face of body B (8-node quadrilaterals or 6-node triangles), node i of
/// one paired with node i of the other (coincident), both numbered so that
/// ∂x/∂ξ × ∂x/∂η points from B into A.
#[derive(Clone, Debug)]
pub struct ContactFace {
    pub a: Face,
    pub b: Face,
}

#[derive(Clone, Debug, Default)]
pub struct Interface {
    pub name: String,
    pub body_a: usize,
    pub body_b: usize,
    /// Coincident node pairs (a matching interface of a plane model); empty
    /// when the sides are meshed apart ([`Interface::nonmatching`]) or in 3D.
    pub edges: Vec<ContactEdge>,
    /// A non-matching interface (`matching = false`): the two sides' edges,
    /// node-to-segment springs instead of node pairs ([`crate::model::interface`]).
    pub nonmatching: Option<NonMatching>,
    /// A 3D interface: its coincident faces (matching); empty when the
    /// sides are meshed apart ([`Interface::nonmatching_faces`]).
    pub faces: Vec<ContactFace>,
    /// A 3D interface meshed apart: the slave faces (body A) and the master
    /// faces (body B), node-to-surface springs.
    pub nonmatching_faces: Option<NonMatchingFaces>,
}

/// The two sides of a 3D non-matching interface: faces of body A (slave,
/// where the spring points live) and of body B (master, onto which they are
/// projected), each numbered so that ∂x/∂ξ × ∂x/∂η points from B into A.
#[derive(Clone, Debug)]
pub struct NonMatchingFaces {
    pub slave: Vec<Face>,
    pub master: Vec<Face>,
}

impl Interface {
    /// Whether the interface lies on faces (a 3D model).
    pub fn on_faces(&self) -> bool {
        !self.faces.is_empty() || self.nonmatching_faces.is_some()
    }
}

/// The two sides of a non-matching interface: quadratic edges [end, mid,
/// end], both walked in the interface's walk direction (slave edges with A
/// on the left, master edges with B on the right: increasing x on a
/// horizontal block interface, increasing y on a vertical one). The slave
/// edges follow one another end to start (their arc length is accumulated).
/// The spring points live on the slave side (body A) and are projected onto
/// the master side (body B).
#[derive(Clone, Debug)]
pub struct NonMatching {
    pub slave: Vec<[usize; 3]>,
    pub master: Vec<[usize; 3]>,
}

#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Node coordinates (x, y, z), mm; z = 0 in a plane or axisymmetric
    /// model ([`Mesh::xy`] reads its plane).
    pub nodes: Vec<[f64; 3]>,
    pub elements: Vec<Element>,
    pub bodies: Vec<String>,
    /// Sorted, unique node ids.
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Boundary edges [end, mid, end], walked with the body on the left
    /// (plane meshes).
    pub edge_sets: BTreeMap<String, Vec<[usize; 3]>>,
    /// Boundary faces, each walked counter-clockwise seen from outside (3D
    /// meshes).
    pub face_sets: BTreeMap<String, Vec<Face>>,
    pub interfaces: Vec<Interface>,
    /// Dofs per node and their numbering ([`NodeDofs`]): set by the model
    /// (3 with twist), 2 otherwise.
    pub node_dofs: NodeDofs,
    /// A mesh read from a file: the file's name and each element's tag in it,
    /// for messages ([`Mesh::element_label`]); none for a generated or
    /// refined mesh.
    pub(crate) source: Option<ElementSource>,
}

/// Where the elements of a mesh read from a file come from.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct ElementSource {
    pub(crate) file: String,
    /// The file's tag of each element, in the mesh's order.
    pub(crate) tags: Vec<u64>,
}

/// A broken mesh or mesh specification; the text names what and where.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshError(pub String);

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for MeshError {}

impl Mesh {
    /// The body of every node (the last element's that holds it; usize::MAX
    /// for a node of no element).
    pub fn node_bodies(&self) -> Vec<usize> {
        let mut node_body = vec![usize::MAX; self.nodes.len()];
        for el in &self.elements {
            for &n in el.nodes() {
                node_body[n] = el.body;
            }
        }
        node_body
    }

    /// How messages name element `e`: by its tag in the file it was read
    /// from (what Gmsh shows), else by its index.
    pub(crate) fn element_label(&self, e: usize) -> String {
        match self
            .source
            .as_ref()
            .and_then(|s| Some((s.tags.get(e)?, &s.file)))
        {
            Some((tag, file)) => format!("{file} element {tag}"),
            None => format!("element {e}"),
        }
    }

    /// 3 for a mesh of solid elements, else 2.
    pub fn dim(&self) -> usize {
        self.elements.first().map_or(2, |el| el.family.dim())
    }

    /// The coordinates of element e's nodes in space (3D meshes; the first
    /// `family.nodes()` used, the rest zero).
    pub(crate) fn element_coords3(&self, e: usize) -> [[f64; 3]; MAX_ELEMENT_NODES] {
        let mut x = [[0.0; 3]; MAX_ELEMENT_NODES];
        for (a, &n) in self.elements[e].nodes().iter().enumerate() {
            x[a] = self.nodes[n];
        }
        x
    }

    /// Node `n` in the plane of a 2D model (x, y; x = r in axisymmetry).
    pub fn xy(&self, n: usize) -> [f64; 2] {
        let [x, y, _] = self.nodes[n];
        [x, y]
    }

    pub fn num_dofs(&self) -> usize {
        self.node_dofs.count(self.nodes.len())
    }

    /// The coordinates of element e's nodes (the first `family.nodes()`
    /// used, the rest zero).
    pub fn element_coords(&self, e: usize) -> [[f64; 2]; MAX_NODES] {
        let mut x = [[0.0; 2]; MAX_NODES];
        for (a, &n) in self.elements[e].nodes().iter().enumerate() {
            x[a] = self.xy(n);
        }
        x
    }

    /// Length of a quadratic edge by 3-point Gauss.
    pub(crate) fn edge_length(&self, edge: &[usize; 3]) -> f64 {
        let x: [[f64; 2]; 3] = std::array::from_fn(|i| self.xy(edge[i]));
        edge::gauss_1d(3)
            .iter()
            .map(|&(s, w)| {
                let dn = [s - 0.5, -2.0 * s, s + 0.5];
                let t = (0..3).fold([0.0, 0.0], |t, i| {
                    [t[0] + dn[i] * x[i][0], t[1] + dn[i] * x[i][1]]
                });
                w * t[0].hypot(t[1])
            })
            .sum()
    }

    /// Element e's outline through its nodes: corner, midside, corner, …
    /// counter-clockwise.
    pub fn outline(&self, e: usize) -> Vec<[f64; 2]> {
        self.elements[e]
            .edges()
            .flat_map(|[a, m, _]| [self.xy(a), self.xy(m)])
            .collect()
    }

    /// The mean of all of element e's nodes (where a message places it).
    pub(crate) fn node_mean(&self, e: usize) -> [f64; 2] {
        let nodes = self.elements[e].nodes();
        let k = nodes.len() as f64;
        let s = nodes.iter().fold([0.0, 0.0], |s, &n| {
            [s[0] + self.nodes[n][0], s[1] + self.nodes[n][1]]
        });
        [s[0] / k, s[1] / k]
    }

    /// det J > 0 at element e's check points (its full rule's points and its
    /// nodes), else the message naming where it is not.
    fn check_jacobian(&self, e: usize) -> Result<(), String> {
        let family = self.elements[e].family;
        match family.solid() {
            None => {
                let coords = self.element_coords(e);
                for xi in family.check_points() {
                    family.physical_derivs(&coords, xi)?;
                }
            }
            Some(solid) => {
                let coords = self.element_coords3(e);
                for xi in solid.check_points() {
                    solid.physical_derivs(&coords, xi)?;
                }
            }
        }
        Ok(())
    }

    /// The mean of element e's corners in space.
    pub(crate) fn corner_mean(&self, e: usize) -> [f64; 3] {
        let corners = self.elements[e].corners();
        let s = corners.iter().fold([0.0; 3], |s, &n| {
            let x = self.nodes[n];
            [s[0] + x[0], s[1] + x[1], s[2] + x[2]]
        });
        s.map(|v| v / corners.len() as f64)
    }

    /// Checks the mesh for everything that would make the model meaningless:
    /// bad node ids, NaN coordinates, repeated nodes in an element, inverted or
    /// degenerate elements (det J ≤ 0 at a 3×3 Gauss point or a node), unused
    /// nodes, and interface pairs that are not coincident or not on their bodies.
    pub fn validate(&self) -> Result<(), MeshError> {
        let err = |s: String| Err(MeshError(s));
        for (n, x) in self.nodes.iter().enumerate() {
            if !x.iter().all(|v| v.is_finite()) {
                return err(format!("node {n} has a non-finite coordinate {x:?}"));
            }
        }
        let dim = self.dim();
        if let Some(el) = self.elements.iter().find(|el| el.family.dim() != dim) {
            return err(format!(
                "a mesh of {dim}D elements also holds a {}: plane and solid elements do not mix",
                el.family.name()
            ));
        }
        let mut used = vec![false; self.nodes.len()];
        for (e, el) in self.elements.iter().enumerate() {
            if el.body >= self.bodies.len() {
                return err(format!(
                    "element {e} refers to body {} which does not exist",
                    el.body
                ));
            }
            for (a, &n) in el.nodes().iter().enumerate() {
                if n >= self.nodes.len() {
                    return err(format!("element {e}: node {n} does not exist"));
                }
                if el.nodes()[..a].contains(&n) {
                    return err(format!("element {e}: node {n} appears twice"));
                }
                used[n] = true;
            }
            if let Err(m) = self.check_jacobian(e) {
                let c = self.corner_mean(e);
                let at: Vec<String> = c[..dim].iter().map(|v| format!("{v:.4}")).collect();
                let at = at.join(", ");
                return err(format!(
                    "{} of body \"{}\" near ({at}): {m}",
                    self.element_label(e),
                    self.bodies[el.body],
                ));
            }
        }
        if let Some(n) = used.iter().position(|u| !u) {
            return err(format!(
                "node {n} at {:?} belongs to no element",
                self.xy(n)
            ));
        }
        let node_body = self.node_bodies();
        for iface in &self.interfaces {
            for (k, edge) in iface.edges.iter().enumerate() {
                for i in 0..3 {
                    let (a, b) = (edge.a[i], edge.b[i]);
                    let (xa, xb) = (self.nodes[a], self.nodes[b]);
                    let scale = self.edge_length(&edge.b).max(1e-300);
                    if (xa[0] - xb[0]).hypot(xa[1] - xb[1]) > 1e-9 * scale {
                        return err(format!(
                            "interface \"{}\" edge {k}: nodes {a} at {xa:?} and {b} at {xb:?} are paired but not coincident",
                            iface.name
                        ));
                    }
                    if node_body[a] != iface.body_a || node_body[b] != iface.body_b {
                        return err(format!(
                            "interface \"{}\" edge {k}: pair ({a}, {b}) is not on bodies \"{}\" / \"{}\"",
                            iface.name, self.bodies[iface.body_a], self.bodies[iface.body_b]
                        ));
                    }
                }
            }
            if let Some(nm) = &iface.nonmatching {
                let sides = [(&nm.slave, iface.body_a), (&nm.master, iface.body_b)];
                for (edges, body) in sides {
                    if let Some(&n) = edges.iter().flatten().find(|&&n| node_body[n] != body) {
                        return err(format!(
                            "interface \"{}\": node {n} at {:?} is not on body \"{}\"",
                            iface.name,
                            self.xy(n),
                            self.bodies[body]
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}
