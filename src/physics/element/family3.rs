//! The 3D element families' shape: the 20-node hexahedron ([`super::h20`])
//! and the 10-node tetrahedron ([`super::t10`]): nodes, shape functions and
//! derivatives, Gauss rules, the Jacobian, and the extrapolation of Gauss
//! point values to the nodes. The solid element on them is
//! [`super::solid3`].

use super::gauss3::GaussRule3;
use super::{h20, t10};
use crate::numbers::vec3::{cross, dot};

/// Most nodes of a 3D element (H20).
pub(crate) const MAX_NODES3: usize = 20;
/// Most Gauss points of a 3D rule (3×3×3).
pub(crate) const MAX_POINTS3: usize = 27;
/// Most dofs of a 3D element (20 nodes × 3).
#[cfg(test)]
pub(crate) const MAX_DOFS3: usize = 3 * MAX_NODES3;

/// A 3D element family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Family3 {
    /// The 20-node serendipity hexahedron.
    H20,
    /// The 10-node quadratic tetrahedron.
    T10,
}

impl Family3 {
    /// Nodes per element.
    pub(crate) const fn nodes(self) -> usize {
        match self {
            Family3::H20 => 20,
            Family3::T10 => 10,
        }
    }

    /// What a user calls it (messages).
    pub(crate) const fn name(self) -> &'static str {
        match self {
            Family3::H20 => "20-node hexahedron",
            Family3::T10 => "10-node tetrahedron",
        }
    }

    /// Natural coordinates of the nodes.
    pub(crate) fn node_xi(self) -> &'static [[f64; 3]] {
        match self {
            Family3::H20 => &h20::NODE_XI,
            Family3::T10 => &t10::NODE_XI,
        }
    }

    /// The faces, each its local nodes walked counter-clockwise seen from
    /// outside, as the 8-node quadrangle (hexahedron) or the 6-node
    /// triangle (tetrahedron) numbers them ([`h20::FACES`], [`t10::FACES`]).
    pub(crate) fn faces(self) -> Vec<&'static [usize]> {
        match self {
            Family3::H20 => h20::FACES.iter().map(|f| &f[..]).collect(),
            Family3::T10 => t10::FACES.iter().map(|f| &f[..]).collect(),
        }
    }

    /// The edges, each [end, mid, end] in local node numbers
    /// ([`h20::EDGES`], [`t10::EDGES`]).
    pub(crate) fn edges(self) -> &'static [[usize; 3]] {
        match self {
            Family3::H20 => &h20::EDGES,
            Family3::T10 => &t10::EDGES,
        }
    }

    /// Gmsh's node g of an element of this family is local node
    /// `gmsh_to_local()[g]` (Gmsh types 17 and 11).
    pub(crate) fn gmsh_to_local(self) -> &'static [usize] {
        match self {
            Family3::H20 => &h20::GMSH_TO_LOCAL,
            Family3::T10 => &t10::GMSH_TO_LOCAL,
        }
    }

    /// Shape functions at ξ, the first [`Family3::nodes`] used.
    pub(crate) fn shape(self, xi: [f64; 3]) -> [f64; MAX_NODES3] {
        match self {
            Family3::H20 => h20::shape(xi),
            Family3::T10 => {
                let mut n = [0.0; MAX_NODES3];
                n[..10].copy_from_slice(&t10::shape(xi));
                n
            }
        }
    }

    /// ∂N/∂(ξ, η, ζ) at ξ, the first [`Family3::nodes`] used.
    pub(crate) fn shape_derivs(self, xi: [f64; 3]) -> [[f64; 3]; MAX_NODES3] {
        match self {
            Family3::H20 => h20::shape_derivs(xi),
            Family3::T10 => {
                let mut d = [[0.0; 3]; MAX_NODES3];
                d[..10].copy_from_slice(&t10::shape_derivs(xi));
                d
            }
        }
    }

    /// The element's rule, as the plane families choose theirs
    /// ([`super::family::Family::rule`]): `full` 3×3×3 (hexahedron) or the
    /// 14-point degree-5 rule (tetrahedron); otherwise 2×2×2, which
    /// under-integrates the hexahedron, or the 4-point degree-2 rule, exact
    /// for the stiffness of a straight-sided tetrahedron.
    pub(crate) fn rule(self, full: bool) -> GaussRule3 {
        match (self, full) {
            (Family3::H20, true) => h20::gauss_27(),
            (Family3::H20, false) => h20::gauss_8(),
            (Family3::T10, true) => t10::gauss_14(),
            (Family3::T10, false) => t10::gauss_4(),
        }
    }

    /// The points where a valid element has det J > 0: the full rule's
    /// points and the nodes.
    pub(crate) fn check_points(self) -> Vec<[f64; 3]> {
        let mut pts: Vec<[f64; 3]> = self.rule(true).points.iter().map(|p| p.0).collect();
        pts.extend_from_slice(self.node_xi());
        pts
    }

    /// Node values from values at the points of `rule`, as weights: row k
    /// is each node's value for point k at 1 and the others at 0. The
    /// polynomial fitted through the points by least squares (interpolated
    /// where the counts agree) is read at the nodes: for the hexahedron the
    /// tensor polynomials of degree 2 (27 points) or 1 (8) in each
    /// coordinate, for the tetrahedron the complete ones of degree 2 (14
    /// points, a fit) or 1 (4).
    pub(crate) fn extrapolation(self, rule: &GaussRule3) -> Vec<[f64; MAX_NODES3]> {
        let np = rule.points.len();
        let basis = |[x, y, z]: [f64; 3]| -> Vec<f64> {
            match self {
                Family3::H20 => {
                    let d = if np >= 27 { 2 } else { 1 };
                    let mut v = Vec::new();
                    for i in 0..=d {
                        for j in 0..=d {
                            for k in 0..=d {
                                v.push(x.powi(i) * y.powi(j) * z.powi(k));
                            }
                        }
                    }
                    v
                }
                Family3::T10 if np >= 10 => {
                    vec![1.0, x, y, z, x * x, y * y, z * z, x * y, y * z, z * x]
                }
                Family3::T10 => vec![1.0, x, y, z],
            }
        };
        let nb = basis([0.0; 3]).len();
        let v = nalgebra::DMatrix::from_fn(np, nb, |p, b| basis(rule.points[p].0)[b]);
        // coefficients c = (VᵀV)⁻¹ Vᵀ values; node a's value N_a c
        let fit = (v.transpose() * &v)
            .try_inverse()
            .expect("a rule's points are unisolvent for its basis")
            * v.transpose();
        let nodes =
            nalgebra::DMatrix::from_fn(self.nodes(), nb, |a, b| basis(self.node_xi()[a])[b]);
        let w = nodes * fit;
        (0..np)
            .map(|k| {
                let mut row = [0.0; MAX_NODES3];
                for (a, r) in row.iter_mut().enumerate().take(self.nodes()) {
                    *r = w[(a, k)];
                }
                row
            })
            .collect()
    }

    /// The natural coordinates ξ of the point `x` in an element with nodes at
    /// `coords`: Newton on x(ξ) = Σ N_a(ξ) x_a from the element's centre,
    /// J_ij = Σ_a x_a,i ∂N_a/∂ξ_j; `None` when it does not reach
    /// |x(ξ) − x| ≤ 1e-10 × diameter in 30 steps (a point far outside a
    /// curved element may have no preimage).
    pub(crate) fn natural_coords(self, coords: &[[f64; 3]], x: [f64; 3]) -> Option<[f64; 3]> {
        let mut xi = match self {
            Family3::H20 => [0.0; 3],
            Family3::T10 => [0.25; 3],
        };
        let tol = 1e-10 * self.diameter(coords);
        for _ in 0..30 {
            let n = self.shape(xi);
            let d = self.shape_derivs(xi);
            let mut r = [-x[0], -x[1], -x[2]];
            let mut j = nalgebra::Matrix3::zeros();
            for (a, c) in coords.iter().enumerate().take(self.nodes()) {
                for i in 0..3 {
                    r[i] += n[a] * c[i];
                    for k in 0..3 {
                        j[(i, k)] += c[i] * d[a][k];
                    }
                }
            }
            if (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt() <= tol {
                return Some(xi);
            }
            let step = j.try_inverse()? * nalgebra::Vector3::from(r);
            for k in 0..3 {
                xi[k] -= step[k];
            }
            if xi.iter().any(|v| !v.is_finite() || v.abs() > 10.0) {
                return None;
            }
        }
        None
    }

    /// Whether ξ lies in the reference element, or within `tol` of it: the
    /// cube [−1, 1]³ (hexahedron), the tetrahedron ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1.
    pub(crate) fn contains(self, xi: [f64; 3], tol: f64) -> bool {
        match self {
            Family3::H20 => xi.iter().all(|v| v.abs() <= 1.0 + tol),
            Family3::T10 => xi.iter().all(|&v| v >= -tol) && xi.iter().sum::<f64>() <= 1.0 + tol,
        }
    }

    /// The element's diameter from its node coordinates: the longest body
    /// diagonal (hexahedron) or edge between corners (tetrahedron).
    pub(crate) fn diameter(self, c: &[[f64; 3]]) -> f64 {
        let d = |a: usize, b: usize| {
            ((c[a][0] - c[b][0]).powi(2)
                + (c[a][1] - c[b][1]).powi(2)
                + (c[a][2] - c[b][2]).powi(2))
            .sqrt()
        };
        match self {
            Family3::H20 => d(0, 6).max(d(1, 7)).max(d(2, 4)).max(d(3, 5)),
            Family3::T10 => [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
                .into_iter()
                .fold(0.0, |m, (a, b)| m.max(d(a, b))),
        }
    }

    /// det J and the physical derivatives ∂N/∂(x, y, z) at ξ of an element
    /// with nodes at `coords` (module text: the dual basis). Errs when
    /// det J ≤ 1e-12 × diameter³, naming the value and ξ: the element is
    /// inverted or degenerate there.
    pub(crate) fn physical_derivs(
        self,
        coords: &[[f64; 3]],
        xi: [f64; 3],
    ) -> Result<(f64, [[f64; 3]; MAX_NODES3]), String> {
        let nn = self.nodes();
        let d = self.shape_derivs(xi);
        // g[k] = ∂x/∂ξ_k
        let mut g = [[0.0; 3]; 3];
        for a in 0..nn {
            for (k, gk) in g.iter_mut().enumerate() {
                for (i, v) in gk.iter_mut().enumerate() {
                    *v += coords[a][i] * d[a][k];
                }
            }
        }
        let dual_raw: [[f64; 3]; 3] =
            std::array::from_fn(|k| cross(g[(k + 1) % 3], g[(k + 2) % 3]));
        let det = dot(g[0], dual_raw[0]);
        let size = self.diameter(coords);
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // !(x > tol) is meant to be true for NaN
        if !(det > 1e-12 * size * size * size) {
            let [x, e, z] = xi;
            return Err(format!(
                "Jacobian determinant {det:.3e} at (ξ, η, ζ) = ({x:.3}, {e:.3}, {z:.3}): element inverted or degenerate"
            ));
        }
        let dual = dual_raw.map(|r| r.map(|v| v / det));
        let mut out = [[0.0; 3]; MAX_NODES3];
        for a in 0..nn {
            for (i, o) in out[a].iter_mut().enumerate() {
                *o = (0..3).map(|k| d[a][k] * dual[k][i]).sum();
            }
        }
        Ok((det, out))
    }
}
