//! Superconvergent patch recovery (SPR; Zienkiewicz & Zhu 1992, part 1) of
//! the stress of 8-node quadrilaterals and 6-node triangles, body by body.
//!
//! For each vertex (corner) node v interior to its body, the patch is the
//! body's elements that share v. Each stress component is fitted, in the
//! least-squares sense, over the σ_h of the patch's sampling points x_k
//! (the superconvergent points: 2×2 Gauss points of the 8-node element, the
//! 3-point rule's of the 6-node triangle) by a complete
//! quadratic polynomial, the degree of the element's displacement:
//! ```text
//!   σ*_p(x) = P(x̂) a,   P = [1, x̂, ŷ, x̂², x̂ŷ, ŷ²],   x̂ = (x − x_v)/h_p
//!   minimise F(a) = Σ_k (σ_h(x_k) − P(x̂_k) a)²   ⇒   A a = b,
//!   A = Σ_k Pᵀ(x̂_k) P(x̂_k),   b = Σ_k Pᵀ(x̂_k) σ_h(x_k)
//! ```
//! (part 1, §2; the coordinates are centred on v and scaled by the patch
//! size h_p so that A is well conditioned). The fit gives values at the
//! central vertex, at the midside nodes of the edges through v and at
//! every node of the patch that lies on the body's boundary (boundary
//! nodes take their values from interior patches, part 1 §2); a node
//! reached by several patches gets their average. A boundary vertex that
//! no interior patch reaches (a body one element thick, a corner element)
//! is fitted over its own patch when A is regular there (its smallest
//! eigenvalue above 1e-8 of its largest, which takes at least six points
//! off any one conic); a node still without a value takes the average of
//! its elements' extrapolations of their sampled values (bilinear from 2×2,
//! linear from the triangle's 3 points). The field σ* inside an element is
//! Σ N_a σ*_a with the element's shape functions.
//!
//! A linear stress field is reproduced exactly by every branch (the
//! quadratic fit and the bilinear extrapolation): the patch test.
//! Recovery never crosses bodies, so it never smooths across an interface
//! or a change of material.

use crate::input::mesh::{Element, Mesh};
use crate::physics::element::family::MAX_NODES;
use nalgebra::{Matrix6, SymmetricEigen, Vector6};
use std::collections::HashMap;

/// The stress components recovered (the [`crate::physics::material::PointState::stress`] order).
pub type Stress = [f64; 6];

/// σ_h of one element at its sampling points (the first `n` used).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Samples {
    /// The points' physical coordinates.
    pub points: [[f64; 2]; 4],
    /// σ_h there.
    pub values: [Stress; 4],
    /// How many (4 for the quad's 2×2, 3 for the triangle's rule).
    pub n: usize,
}

impl Samples {
    fn each(&self) -> impl Iterator<Item = ([f64; 2], &Stress)> + '_ {
        self.points.iter().copied().zip(&self.values).take(self.n)
    }
}

/// σ* at the nodes of every element (the first `family.nodes()` of each),
/// from each element's sampled σ_h.
pub(crate) fn recover(mesh: &Mesh, samples: &[Samples]) -> Vec<[Stress; MAX_NODES]> {
    let mut r = Recovery::new(mesh, samples);
    let mut out = vec![[[0.0; 6]; MAX_NODES]; mesh.elements.len()];
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

    /// The recovery of one body (module text) into `out`: the interior
    /// patches, then boundary vertices no interior patch reached, then the
    /// elements' own extrapolation for what is left.
    fn body(&mut self, body: usize, out: &mut [[Stress; MAX_NODES]]) {
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
            for (a, &n) in mesh.elements[e].nodes().iter().enumerate() {
                let k = f64::from(self.count[n].max(1));
                out[e][a] = self.sum[n].map(|s| s / k);
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
            let Some(fit) = Fit::new(mesh.xy(v), &pe, self.samples) else {
                continue;
            };
            for &e in &pe {
                let el = &mesh.elements[e];
                for &n in el.nodes() {
                    if n == v || self.boundary[n] || on_edge_through(el, n, v) {
                        self.add(n, fit.at(mesh.xy(n)));
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
            if let Some(fit) = Fit::new(mesh.xy(v), &pe, self.samples) {
                second.push((v, fit.at(mesh.xy(v))));
                for &e in &pe {
                    let el = &mesh.elements[e];
                    for [_, m, _] in el.edges() {
                        if self.count[m] == 0 && on_edge_through(el, m, v) {
                            second.push((m, fit.at(mesh.xy(m))));
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
            let rule = el.family.sampling_rule();
            let mut ex = [[0.0; 6]; MAX_NODES];
            for c in 0..6 {
                let v: Vec<f64> = self.samples[e].each().map(|(_, s)| s[c]).collect();
                let x = el.family.extrapolate_to_nodes(&rule, &v);
                for a in 0..en.len() {
                    ex[a][c] = x[a];
                }
            }
            for (a, &n) in en.iter().enumerate() {
                if self.count[n] == 0 {
                    third.push((n, ex[a]));
                }
            }
        }
        third
    }
}

/// Whether node `n` is the midside of an edge of `el` that ends at node v.
fn on_edge_through(el: &Element, n: usize, v: usize) -> bool {
    el.edges().any(|[a, m, b]| m == n && (a == v || b == v))
}

/// Nodes on the boundary of their body: those of an element edge that no
/// other element of the same body shares.
fn boundary_nodes(mesh: &Mesh) -> Vec<bool> {
    let mut edges: HashMap<(usize, usize, usize), u32> = HashMap::new();
    for el in &mesh.elements {
        for [a, _, b] in el.edges() {
            *edges.entry((el.body, a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut boundary = vec![false; mesh.nodes.len()];
    for el in &mesh.elements {
        for [a, m, b] in el.edges() {
            if edges[&(el.body, a.min(b), a.max(b))] == 1 {
                boundary[a] = true;
                boundary[b] = true;
                boundary[m] = true;
            }
        }
    }
    boundary
}

/// The least-squares quadratic of one patch (module text), all six
/// components at once (one matrix A, six right-hand sides).
struct Fit {
    centre: [f64; 2],
    h: f64,
    coef: [Vector6<f64>; 6],
}

impl Fit {
    /// The fit over the sampling points of `elems`; `None` when A is
    /// singular or nearly so (too few points, or all on one conic).
    fn new(centre: [f64; 2], elems: &[usize], samples: &[Samples]) -> Option<Fit> {
        let h = elems
            .iter()
            .flat_map(|&e| samples[e].each())
            .map(|(x, _)| (x[0] - centre[0]).hypot(x[1] - centre[1]))
            .fold(0.0f64, f64::max);
        let count: usize = elems.iter().map(|&e| samples[e].n).sum();
        if count < 6 || h <= 0.0 {
            return None;
        }
        let mut a = Matrix6::zeros();
        let mut b = [Vector6::zeros(); 6];
        for &e in elems {
            for (x, v) in samples[e].each() {
                let p = basis(centre, h, x);
                a += p * p.transpose();
                for (c, bc) in b.iter_mut().enumerate() {
                    *bc += p * v[c];
                }
            }
        }
        let eig = SymmetricEigen::new(a);
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
            coef: b.map(|bc| chol.solve(&bc)),
        })
    }

    /// σ*_p at x.
    fn at(&self, x: [f64; 2]) -> Stress {
        let p = basis(self.centre, self.h, x);
        self.coef.map(|a| a.dot(&p))
    }
}

/// P(x̂) = [1, x̂, ŷ, x̂², x̂ŷ, ŷ²] with x̂ = (x − centre)/h.
fn basis(centre: [f64; 2], h: f64, x: [f64; 2]) -> Vector6<f64> {
    let (u, v) = ((x[0] - centre[0]) / h, (x[1] - centre[1]) / h);
    Vector6::new(1.0, u, v, u * u, u * v, v * v)
}
