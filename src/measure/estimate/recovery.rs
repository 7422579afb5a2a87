//! Superconvergent patch recovery (SPR; Zienkiewicz & Zhu 1992, part 1) of
//! the stress of 8-node quadrilaterals and 6-node triangles, and of 20-node
//! hexahedra and 10-node tetrahedra, body by body.
//!
//! For each vertex (corner) node v interior to its body, the patch is the
//! body's elements that share v. Each stress component is fitted, in the
//! least-squares sense, over the σ_h of the patch's sampling points x_k
//! (the superconvergent points: 2×2 Gauss points of the 8-node element, the
//! 3-point rule's of the 6-node triangle; in a solid the 2×2×2 points of the
//! hexahedron and the 4-point rule's of the tetrahedron) by a complete
//! quadratic polynomial, the degree of the element's displacement:
//! ```text
//!   σ*_p(x) = P(x̂) a,   P = [1, x̂, ŷ, x̂², x̂ŷ, ŷ²],   x̂ = (x − x_v)/h_p
//!   (in a solid P = [1, x̂, ŷ, ẑ, x̂², ŷ², ẑ², x̂ŷ, ŷẑ, ẑx̂], ten terms)
//!   minimise F(a) = Σ_k (σ_h(x_k) − P(x̂_k) a)²   ⇒   A a = b,
//!   A = Σ_k Pᵀ(x̂_k) P(x̂_k),   b = Σ_k Pᵀ(x̂_k) σ_h(x_k)
//! ```
//! (part 1, §2; the coordinates are centred on v and scaled by the patch
//! size h_p so that A is well conditioned). The fit gives values at the
//! central vertex, at the midside nodes of the edges through v and at
//! every node of the patch that lies on the body's boundary (boundary
//! nodes take their values from interior patches, part 1 §2; a boundary
//! node is one of an element side, an edge in the plane or a face in a
//! solid, that no other element of the body shares); a node
//! reached by several patches gets their average. A boundary vertex that
//! no interior patch reaches (a body one element thick, a corner element)
//! is fitted over its own patch when A is regular there (its smallest
//! eigenvalue above 1e-8 of its largest, which takes at least six points
//! off any one conic, or ten off any one quadric in a solid); a node still
//! without a value takes the average of its elements' extrapolations of
//! their sampled values (bilinear from 2×2, linear from the triangle's 3
//! points, trilinear from 2×2×2, linear from the tetrahedron's 4). The field σ* inside an element is
//! Σ N_a σ*_a with the element's shape functions.
//!
//! A linear stress field is reproduced exactly by every branch (the
//! quadratic fit and the bilinear extrapolation): the patch test.
//! Recovery never crosses bodies, so it never smooths across an interface
//! or a change of material.

use crate::input::mesh::{Element, Mesh};
use crate::physics::element::family::Family;
use crate::physics::element::family3::MAX_NODES3;
use nalgebra::{DMatrix, DVector, SymmetricEigen};
use std::collections::HashMap;

/// The stress components recovered (the [`crate::physics::material::PointState::stress`] order).
pub type Stress = [f64; 6];

/// Most sampling points of an element (the hexahedron's 2×2×2).
const MAX_SAMPLES: usize = 8;

/// σ_h of one element at its sampling points (the first `n` used).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Samples {
    /// The points' physical coordinates (z = 0 in a plane model).
    pub points: [[f64; 3]; MAX_SAMPLES],
    /// σ_h there.
    pub values: [Stress; MAX_SAMPLES],
    /// How many (4 for the quad's 2×2, 3 for the triangle's rule, 8 for the
    /// hexahedron's 2×2×2, 4 for the tetrahedron's rule).
    pub n: usize,
}

impl Samples {
    fn each(&self) -> impl Iterator<Item = ([f64; 3], &Stress)> + '_ {
        self.points.iter().copied().zip(&self.values).take(self.n)
    }
}

/// σ* at the nodes of every element: element e's at its nodes in order.
pub(crate) struct Recovered {
    /// Element e's values are `values[start[e]..start[e + 1]]`.
    start: Vec<usize>,
    values: Vec<Stress>,
}

impl Recovered {
    /// σ* at element e's nodes (corners, then midsides).
    pub(crate) fn element(&self, e: usize) -> &[Stress] {
        &self.values[self.start[e]..self.start[e + 1]]
    }
}

/// σ* at the nodes of every element, from each element's sampled σ_h.
pub(crate) fn recover(mesh: &Mesh, samples: &[Samples]) -> Recovered {
    let mut r = Recovery::new(mesh, samples);
    let mut start = Vec::with_capacity(mesh.elements.len() + 1);
    start.push(0);
    for el in &mesh.elements {
        start.push(start.last().copied().unwrap_or(0) + el.nodes().len());
    }
    let mut out = Recovered {
        values: vec![[0.0; 6]; start.last().copied().unwrap_or(0)],
        start,
    };
    for body in 0..mesh.bodies.len().max(1) {
        r.body(body, &mut out);
    }
    out
}

/// The recovery's working state: the node → elements adjacency, the
/// boundary nodes, and each node's sum and count of fitted values (reset
/// body by body).
struct Recovery<'a> {
    mesh: &'a Mesh,
    samples: &'a [Samples],
    /// Node n's elements are `adj[start[n]..start[n + 1]]` (CSR).
    start: Vec<usize>,
    adj: Vec<usize>,
    boundary: Vec<bool>,
    sum: Vec<Stress>,
    count: Vec<u32>,
    /// 2 or 3: the fit's polynomial ([`basis`]).
    dim: usize,
    /// Each solid family's extrapolation from its sampling points
    /// ([`crate::physics::element::family::Family::SOLID`] order), made once.
    solid_weights: Vec<Vec<[f64; MAX_NODES3]>>,
}

impl<'a> Recovery<'a> {
    fn new(mesh: &'a Mesh, samples: &'a [Samples]) -> Self {
        let nn = mesh.nodes.len();
        let mut start = vec![0usize; nn + 1];
        for el in &mesh.elements {
            for &n in el.nodes() {
                start[n + 1] += 1;
            }
        }
        for i in 0..nn {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut adj = vec![0usize; start[nn]];
        for (e, el) in mesh.elements.iter().enumerate() {
            for &n in el.nodes() {
                adj[fill[n]] = e;
                fill[n] += 1;
            }
        }
        Recovery {
            mesh,
            samples,
            start,
            adj,
            boundary: boundary_nodes(mesh),
            sum: vec![[0.0f64; 6]; nn],
            count: vec![0u32; nn],
            dim: mesh.dim(),
            solid_weights: Family::SOLID
                .iter()
                .map(|f| {
                    let solid = f.solid().expect("a solid family");
                    solid.extrapolation(&solid.rule(false))
                })
                .collect(),
        }
    }

    /// The patch of vertex v in `body`: its elements of that body.
    fn patch(&self, v: usize, body: usize) -> Vec<usize> {
        self.adj[self.start[v]..self.start[v + 1]]
            .iter()
            .copied()
            .filter(|&e| self.mesh.elements[e].body == body)
            .collect()
    }

    fn add(&mut self, n: usize, s: Stress) {
        for (t, v) in self.sum[n].iter_mut().zip(s) {
            *t += v;
        }
        self.count[n] += 1;
    }

    /// The fit over the patch of vertex v.
    fn fit(&self, v: usize, patch: &[usize]) -> Option<Fit> {
        Fit::new(self.mesh.nodes[v], patch, self.samples, self.dim)
    }

    /// The recovery of one body (module text) into `out`: the interior
    /// patches, then boundary vertices no interior patch reached, then the
    /// elements' own extrapolation for what is left.
    fn body(&mut self, body: usize, out: &mut Recovered) {
        let mesh = self.mesh;
        let elems: Vec<usize> = (0..mesh.elements.len())
            .filter(|&e| mesh.elements[e].body == body)
            .collect();
        if elems.is_empty() {
            return;
        }
        let mut nodes: Vec<usize> = elems
            .iter()
            .flat_map(|&e| mesh.elements[e].nodes().iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        let vertices: Vec<usize> = nodes
            .iter()
            .copied()
            .filter(|&n| {
                self.patch(n, body)
                    .iter()
                    .any(|&e| mesh.elements[e].corners().contains(&n))
            })
            .collect();
        self.interior_patches(&vertices, body);
        let second = self.boundary_patches(&vertices, body);
        for (n, s) in second {
            self.add(n, s);
        }
        let third = self.extrapolated(&elems);
        for (n, s) in third {
            self.add(n, s);
        }
        for &e in &elems {
            let at = out.start[e];
            for (a, &n) in mesh.elements[e].nodes().iter().enumerate() {
                let k = f64::from(self.count[n].max(1));
                out.values[at + a] = self.sum[n].map(|s| s / k);
            }
        }
        for &n in &nodes {
            (self.sum[n], self.count[n]) = ([0.0; 6], 0);
        }
    }

    /// Each interior vertex's patch fit, at the vertex, the midsides of the
    /// edges through it and the patch's boundary nodes.
    fn interior_patches(&mut self, vertices: &[usize], body: usize) {
        let mesh = self.mesh;
        for &v in vertices {
            if self.boundary[v] {
                continue;
            }
            let pe = self.patch(v, body);
            let Some(fit) = self.fit(v, &pe) else {
                continue;
            };
            for &e in &pe {
                let el = &mesh.elements[e];
                for &n in el.nodes() {
                    if n == v || self.boundary[n] || on_edge_through(el, n, v) {
                        self.add(n, fit.at(mesh.nodes[n]));
                    }
                }
            }
        }
    }

    /// Boundary vertices no interior patch reached: their own patch's fit
    /// at the vertex and the midsides through it still without a value.
    fn boundary_patches(&self, vertices: &[usize], body: usize) -> Vec<(usize, Stress)> {
        let mesh = self.mesh;
        let mut second = Vec::new();
        for &v in vertices
            .iter()
            .filter(|&&v| self.boundary[v] && self.count[v] == 0)
        {
            let pe = self.patch(v, body);
            if let Some(fit) = self.fit(v, &pe) {
                second.push((v, fit.at(mesh.nodes[v])));
                for &e in &pe {
                    let el = &mesh.elements[e];
                    for [_, m, _] in edges(el) {
                        if self.count[m] == 0 && on_edge_through(el, m, v) {
                            second.push((m, fit.at(mesh.nodes[m])));
                        }
                    }
                }
            }
        }
        second
    }

    /// The nodes still without a value: their elements' own extrapolation
    /// of the sampled values.
    fn extrapolated(&self, elems: &[usize]) -> Vec<(usize, Stress)> {
        let mut third = Vec::new();
        for &e in elems {
            let el = &self.mesh.elements[e];
            let en = el.nodes();
            if en.iter().all(|&n| self.count[n] > 0) {
                continue;
            }
            let ex = self.extrapolate(el, &self.samples[e]);
            for (a, &n) in en.iter().enumerate() {
                if self.count[n] == 0 {
                    third.push((n, ex[a]));
                }
            }
        }
        third
    }
}

impl Recovery<'_> {
    /// An element's own extrapolation of its sampled values to its nodes
    /// (the polynomial through the sampling points read at the nodes).
    fn extrapolate(&self, el: &Element, samples: &Samples) -> Vec<Stress> {
        let mut ex = vec![[0.0; 6]; el.nodes().len()];
        if el.family.solid().is_some() {
            let k = Family::SOLID
                .iter()
                .position(|&f| f == el.family)
                .unwrap_or(0);
            let w = &self.solid_weights[k];
            for (k, (_, s)) in samples.each().enumerate() {
                for (a, x) in ex.iter_mut().enumerate() {
                    for c in 0..6 {
                        x[c] += w[k][a] * s[c];
                    }
                }
            }
            return ex;
        }
        let rule = el.family.sampling_rule();
        for c in 0..6 {
            let v: Vec<f64> = samples.each().map(|(_, s)| s[c]).collect();
            let x = el.family.extrapolate_to_nodes(&rule, &v);
            for (a, e) in ex.iter_mut().enumerate() {
                e[c] = x[a];
            }
        }
        ex
    }
}

/// The element's edges [end, mid, end] in global node numbers (a plane
/// element's sides, a solid's twelve or six edges).
fn edges(el: &Element) -> impl Iterator<Item = [usize; 3]> + '_ {
    let local = match el.family.solid() {
        Some(solid) => solid.edges(),
        None => el.family.edges(),
    };
    let nodes = el.nodes();
    local.iter().map(move |e| e.map(|a| nodes[a]))
}

/// Whether node `n` is the midside of an edge of `el` that ends at node v.
fn on_edge_through(el: &Element, n: usize, v: usize) -> bool {
    edges(el).any(|[a, m, b]| m == n && (a == v || b == v))
}

/// The element's sides, each its nodes and its key (the sorted corners;
/// `usize::MAX` pads a side of fewer): the edges of a plane element, the
/// faces of a solid.
fn sides(el: &Element) -> Vec<(Vec<usize>, [usize; 4])> {
    let nodes = el.nodes();
    let key = |corners: &[usize]| {
        let mut k = [usize::MAX; 4];
        k[..corners.len()].copy_from_slice(corners);
        k.sort_unstable();
        k
    };
    match el.family.solid() {
        Some(solid) => solid
            .faces()
            .into_iter()
            .map(|f| {
                let global: Vec<usize> = f.iter().map(|&a| nodes[a]).collect();
                // a face's corners come first: 4 of a quadrangle's 8, 3 of a triangle's 6
                let k = key(&global[..f.len() / 2]);
                (global, k)
            })
            .collect(),
        None => edges(el)
            .map(|e| (e.to_vec(), key(&[e[0], e[2]])))
            .collect(),
    }
}

/// Nodes on the boundary of their body: those of an element side (edge in
/// the plane, face in a solid) that no other element of the same body
/// shares.
fn boundary_nodes(mesh: &Mesh) -> Vec<bool> {
    let mut count: HashMap<(usize, [usize; 4]), u32> = HashMap::new();
    for el in &mesh.elements {
        for (_, k) in sides(el) {
            *count.entry((el.body, k)).or_default() += 1;
        }
    }
    let mut boundary = vec![false; mesh.nodes.len()];
    for el in &mesh.elements {
        for (nodes, k) in sides(el) {
            if count[&(el.body, k)] == 1 {
                for n in nodes {
                    boundary[n] = true;
                }
            }
        }
    }
    boundary
}

/// The least-squares quadratic of one patch (module text), all six
/// components at once (one matrix A, six right-hand sides).
struct Fit {
    centre: [f64; 3],
    h: f64,
    dim: usize,
    coef: [DVector<f64>; 6],
}

impl Fit {
    /// The fit over the sampling points of `elems`; `None` when A is
    /// singular or nearly so (too few points, or all on one conic or
    /// quadric).
    fn new(centre: [f64; 3], elems: &[usize], samples: &[Samples], dim: usize) -> Option<Fit> {
        let h = elems
            .iter()
            .flat_map(|&e| samples[e].each())
            .map(|(x, _)| distance(x, centre))
            .fold(0.0f64, f64::max);
        let terms = basis(centre, 1.0, [0.0; 3], dim).len();
        let count: usize = elems.iter().map(|&e| samples[e].n).sum();
        if count < terms || h <= 0.0 {
            return None;
        }
        let mut a = DMatrix::zeros(terms, terms);
        let mut b: [DVector<f64>; 6] = std::array::from_fn(|_| DVector::zeros(terms));
        for &e in elems {
            for (x, v) in samples[e].each() {
                let p = basis(centre, h, x, dim);
                a += &p * p.transpose();
                for (c, bc) in b.iter_mut().enumerate() {
                    *bc += &p * v[c];
                }
            }
        }
        let eig = SymmetricEigen::new(a.clone());
        let (lo, hi) = eig
            .eigenvalues
            .iter()
            .fold((f64::MAX, 0.0f64), |(lo, hi), &l| (lo.min(l), hi.max(l)));
        if lo <= 1e-8 * hi {
            return None;
        }
        let chol = a.cholesky()?;
        Some(Fit {
            centre,
            h,
            dim,
            coef: b.map(|bc| chol.solve(&bc)),
        })
    }

    /// σ*_p at x.
    fn at(&self, x: [f64; 3]) -> Stress {
        let p = basis(self.centre, self.h, x, self.dim);
        std::array::from_fn(|c| self.coef[c].dot(&p))
    }
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// P(x̂) with x̂ = (x − centre)/h: [1, x̂, ŷ, x̂², x̂ŷ, ŷ²] in the plane,
/// [1, x̂, ŷ, ẑ, x̂², ŷ², ẑ², x̂ŷ, ŷẑ, ẑx̂] in a solid (`dim` 3).
fn basis(centre: [f64; 3], h: f64, x: [f64; 3], dim: usize) -> DVector<f64> {
    let [u, v, w] = std::array::from_fn(|i| (x[i] - centre[i]) / h);
    if dim == 3 {
        DVector::from_row_slice(&[1.0, u, v, w, u * u, v * v, w * w, u * v, v * w, w * u])
    } else {
        DVector::from_row_slice(&[1.0, u, v, u * u, u * v, v * v])
    }
}
