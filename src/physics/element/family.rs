//! The element families: those a plane or axisymmetric mesh may mix, the
//! 8-node serendipity quadrilateral ([`super::q8`]) and the 6-node quadratic
//! triangle ([`super::t6`]), and those of a 3D mesh, the 20-node hexahedron
//! and the 10-node tetrahedron, whose shape lives in `Family3`
//! (`family3.rs`). Methods that take plane natural coordinates are the
//! plane families' alone: a 3D model never reaches them (its model refuses
//! every feature still plane only, `Family::solid` hands out the solid
//! shape). A family answers everything the rest of the
//! code asks of an element's shape: its nodes and their natural coordinates,
//! shape functions and derivatives, the Jacobian, the Gauss rules, the
//! interpolation of Gauss point values (to the nodes, or to other points),
//! its sides (quadratic edges [end, mid, end], [`super::edge`]) and its VTK
//! cell type. Both families have straight or curved quadratic sides with
//! three nodes, so interfaces, edge loads and pretension cuts see one kind of
//! side whichever element it bounds.

use super::family3::Family3;
pub use super::gauss::GaussRule;
use super::{q8, t6};
use nalgebra::{DMatrix, DVector};

/// Most nodes of an element of a plane family (the 8-node quad).
pub(crate) const MAX_NODES: usize = 8;

/// Most Gauss points of a rule of a plane family (3×3).
pub(crate) const MAX_POINTS: usize = 9;

/// Most nodes of an element of any family (the 20-node hexahedron).
pub(crate) const MAX_ELEMENT_NODES: usize = 20;

/// An element family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// The 8-node serendipity quadrilateral.
    Q8,
    /// The 6-node quadratic triangle.
    T6,
    /// The 20-node serendipity hexahedron (3D).
    H20,
    /// The 10-node quadratic tetrahedron (3D).
    T10,
}

impl From<Family3> for Family {
    fn from(f: Family3) -> Family {
        match f {
            Family3::H20 => Family::H20,
            Family3::T10 => Family::T10,
        }
    }
}

/// A plane family's method called on a solid one: a 3D model refuses every
/// feature that would (the model's checks), so this is a bug.
#[cold]
fn plane_only(f: Family) -> ! {
    unreachable!("the {} has no plane natural coordinates", f.name())
}

impl Family {
    /// The plane families, in the order of their index.
    pub(crate) const ALL: [Family; 2] = [Family::Q8, Family::T6];

    /// The solid families, in the order of their index.
    pub(crate) const SOLID: [Family; 2] = [Family::H20, Family::T10];

    /// The dimension of its elements: 2 (plane) or 3 (solid).
    pub const fn dim(self) -> usize {
        match self {
            Family::Q8 | Family::T6 => 2,
            Family::H20 | Family::T10 => 3,
        }
    }

    /// The shape of a solid family (None for a plane one).
    pub(crate) const fn solid(self) -> Option<Family3> {
        match self {
            Family::Q8 | Family::T6 => None,
            Family::H20 => Some(Family3::H20),
            Family::T10 => Some(Family3::T10),
        }
    }

    /// 0 for Q8, 1 for T6, 2 for H20, 3 for T10 (a slot in per-family
    /// tables).
    pub const fn index(self) -> usize {
        self as usize
    }

    /// Nodes per element.
    pub const fn nodes(self) -> usize {
        match self {
            Family::Q8 => 8,
            Family::T6 => 6,
            Family::H20 => 20,
            Family::T10 => 10,
        }
    }

    /// Corner nodes (numbered first, counter-clockwise in a plane family;
    /// the midsides follow).
    pub const fn corners(self) -> usize {
        match self {
            Family::Q8 => 4,
            Family::T6 => 3,
            Family::H20 => 8,
            Family::T10 => 4,
        }
    }

    /// What a user calls it (messages).
    pub const fn name(self) -> &'static str {
        match self {
            Family::Q8 => "8-node quadrilateral",
            Family::T6 => "6-node triangle",
            Family::H20 => "20-node hexahedron",
            Family::T10 => "10-node tetrahedron",
        }
    }

    /// Natural coordinates of the nodes.
    pub(crate) fn node_xi(self) -> &'static [[f64; 2]] {
        match self {
            Family::Q8 => &q8::NODE_XI,
            Family::T6 => &t6::NODE_XI,
            Family::H20 | Family::T10 => plane_only(self),
        }
    }

    /// The natural coordinates of the element's centre.
    pub(crate) fn centre_xi(self) -> [f64; 2] {
        match self {
            Family::Q8 => [0.0, 0.0],
            Family::T6 => [1.0 / 3.0, 1.0 / 3.0],
            Family::H20 | Family::T10 => plane_only(self),
        }
    }

    /// The sides, each [end, mid, end] in local node numbers, walked
    /// counter-clockwise (the element on the left).
    pub fn edges(self) -> &'static [[usize; 3]] {
        match self {
            Family::Q8 => &[[0, 4, 1], [1, 5, 2], [2, 6, 3], [3, 7, 0]],
            Family::T6 => &[[0, 3, 1], [1, 4, 2], [2, 5, 0]],
            Family::H20 | Family::T10 => plane_only(self),
        }
    }

    /// The VTK cell type: VTK_QUADRATIC_QUAD (23), VTK_QUADRATIC_TRIANGLE
    /// (22), VTK_QUADRATIC_HEXAHEDRON (25), VTK_QUADRATIC_TETRA (24); each
    /// numbers the nodes as this code does.
    pub(crate) const fn vtk_cell(self) -> u8 {
        match self {
            Family::Q8 => 23,
            Family::T6 => 22,
            Family::H20 => 25,
            Family::T10 => 24,
        }
    }

    /// The element's local nodes in the order that walks it the other way
    /// round (a clockwise element given to the reader, turned).
    pub fn reversed(self) -> &'static [usize] {
        match self {
            Family::Q8 => &[0, 3, 2, 1, 7, 6, 5, 4],
            Family::T6 => &[0, 2, 1, 5, 4, 3],
            Family::H20 | Family::T10 => plane_only(self),
        }
    }

    /// The element's diameter from its node coordinates: the longer diagonal
    /// between its corners (a quad), its longest side (a triangle).
    pub fn diameter(self, c: &[[f64; 2]]) -> f64 {
        let d = |a: usize, b: usize| (c[a][0] - c[b][0]).hypot(c[a][1] - c[b][1]);
        match self {
            Family::Q8 => d(0, 2).max(d(1, 3)),
            Family::T6 => d(0, 1).max(d(1, 2)).max(d(2, 0)),
            Family::H20 | Family::T10 => plane_only(self),
        }
    }

    /// Where a message places the element: the middle of its first
    /// diagonal (a quad), the mean of its corners (a triangle).
    pub(crate) fn label_point(self, c: &[[f64; 2]]) -> [f64; 2] {
        match self {
            Family::Q8 => [(c[0][0] + c[2][0]) / 2.0, (c[0][1] + c[2][1]) / 2.0],
            Family::T6 => [
                (c[0][0] + c[1][0] + c[2][0]) / 3.0,
                (c[0][1] + c[1][1] + c[2][1]) / 3.0,
            ],
            Family::H20 | Family::T10 => plane_only(self),
        }
    }

    /// Shape functions at ξ, the first [`Family::nodes`] used.
    pub fn shape(self, [xi, eta]: [f64; 2]) -> [f64; MAX_NODES] {
        let mut n = [0.0; MAX_NODES];
        match self {
            Family::Q8 => n = q8::shape(xi, eta),
            Family::T6 => n[..6].copy_from_slice(&t6::shape(xi, eta)),
            Family::H20 | Family::T10 => plane_only(self),
        }
        n
    }

    /// Shape function derivatives (∂N/∂ξ, ∂N/∂η) at ξ.
    pub(crate) fn shape_derivs(self, [xi, eta]: [f64; 2]) -> [[f64; 2]; MAX_NODES] {
        let mut d = [[0.0; 2]; MAX_NODES];
        match self {
            Family::Q8 => d = q8::shape_derivs(xi, eta),
            Family::T6 => d[..6].copy_from_slice(&t6::shape_derivs(xi, eta)),
            Family::H20 | Family::T10 => plane_only(self),
        }
        d
    }

    /// The element's rule: `full` 3×3 (quad) or the 6-point degree-4 rule
    /// (triangle); otherwise 2×2 or the 3-point degree-2 rule, which
    /// integrate the stiffness of an undistorted element exactly for the
    /// triangle and under-integrate the quad (no volumetric locking in
    /// plane-strain plastic flow).
    pub fn rule(self, full: bool) -> GaussRule {
        match (self, full) {
            (Family::Q8, true) => q8::gauss_3x3(),
            (Family::Q8, false) => q8::gauss_2x2(),
            (Family::T6, true) => t6::gauss_6(),
            (Family::T6, false) => t6::gauss_3(),
            (Family::H20 | Family::T10, _) => plane_only(self),
        }
    }

    /// The points where the stresses of the element are most accurate
    /// (superconvergent), sampled by the recovery of the error estimate:
    /// 2×2 for the quad, the 3-point rule for the triangle.
    pub(crate) fn sampling_rule(self) -> GaussRule {
        self.rule(false)
    }

    /// The points where a valid element has det J > 0: the full rule's points
    /// and the nodes.
    pub(crate) fn check_points(self) -> Vec<[f64; 2]> {
        let rule = self.rule(true);
        let mut pts: Vec<[f64; 2]> = rule.points.into_iter().map(|p| p.0).collect();
        pts.extend_from_slice(self.node_xi());
        pts
    }

    /// det J and the physical derivatives dN/dx at ξ of an element with
    /// nodes at `coords` (the family's count). Errs when det J ≤ 1e-12 ×
    /// (element size)², naming the value: the element is inverted or
    /// degenerate.
    pub(crate) fn physical_derivs(
        self,
        coords: &[[f64; 2]],
        xi: [f64; 2],
    ) -> Result<(f64, [[f64; 2]; MAX_NODES]), String> {
        let nn = self.nodes();
        let d = self.shape_derivs(xi);
        let mut j = [[0.0; 2]; 2]; // j[i][k] = ∂x_i/∂ξ_k
        for a in 0..nn {
            for i in 0..2 {
                for k in 0..2 {
                    j[i][k] += coords[a][i] * d[a][k];
                }
            }
        }
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let dist2 = |p: usize, q: usize| {
            (coords[q][0] - coords[p][0]).powi(2) + (coords[q][1] - coords[p][1]).powi(2)
        };
        let size2 = match self {
            Family::Q8 => dist2(0, 2),
            Family::T6 => dist2(0, 1).max(dist2(1, 2)).max(dist2(2, 0)),
            Family::H20 | Family::T10 => plane_only(self),
        };
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // !(x > tol) is meant to be true for NaN
        if !(det > 1e-12 * size2) {
            let [x, e] = xi;
            return Err(format!(
                "Jacobian determinant {det:.3e} at (ξ, η) = ({x:.3}, {e:.3}): element inverted or degenerate"
            ));
        }
        let inv = [
            [j[1][1] / det, -j[0][1] / det],
            [-j[1][0] / det, j[0][0] / det],
        ];
        let mut out = [[0.0; 2]; MAX_NODES];
        for a in 0..nn {
            // dN/dx_i = Σ_k dN/dξ_k ∂ξ_k/∂x_i
            for i in 0..2 {
                out[a][i] = d[a][0] * inv[0][i] + d[a][1] * inv[1][i];
            }
        }
        Ok((det, out))
    }

    /// The weights w with Σ wᵢ vᵢ the value at ξ of the polynomial through
    /// values vᵢ at the points of `rule`: the tensor Lagrange interpolant of a
    /// quad's 2×2 or 3×3 rule (bilinear, biquadratic), the complete linear
    /// (3 points) or quadratic (6 points) polynomial in (ξ, η) of the
    /// triangle's.
    pub(crate) fn interpolation_weights(self, rule: &GaussRule, xi: [f64; 2]) -> [f64; MAX_POINTS] {
        let n = rule.points.len();
        let mut w = [0.0; MAX_POINTS];
        match self {
            Family::Q8 => {
                let mut unit = [0.0; MAX_POINTS];
                for k in 0..n {
                    unit[k] = 1.0;
                    w[k] = q8::interpolate(rule, &unit[..n], xi);
                    unit[k] = 0.0;
                }
            }
            Family::T6 => {
                // the monomials 1, ξ, η (, ξ², ξη, η²) at the points: V c = v,
                // value at ξ = m(ξ)ᵀ V⁻¹ v, so w = V⁻ᵀ m(ξ)
                let mono = |[x, y]: [f64; 2]| [1.0, x, y, x * x, x * y, y * y];
                let v = DMatrix::from_fn(n, n, |i, k| mono(rule.points[i].0)[k]);
                let m = DVector::from_fn(n, |k, _| mono(xi)[k]);
                let solved = v
                    .transpose()
                    .lu()
                    .solve(&m)
                    .expect("a triangle rule's points are unisolvent");
                w[..n].copy_from_slice(solved.as_slice());
            }
            Family::H20 | Family::T10 => plane_only(self),
        }
        w
    }

    /// Values at the nodes from values at the points of `rule`
    /// ([`Family::interpolation_weights`] at each node).
    pub(crate) fn extrapolate_to_nodes(self, rule: &GaussRule, values: &[f64]) -> [f64; MAX_NODES] {
        let mut out = [0.0; MAX_NODES];
        if self == Family::Q8 {
            return q8::extrapolate_to_nodes(rule, values);
        }
        for (a, &x) in self.node_xi().iter().enumerate() {
            let w = self.interpolation_weights(rule, x);
            out[a] = values.iter().zip(w).map(|(v, w)| v * w).sum();
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_reproduces_the_rules_polynomials() {
        let linear = |[x, y]: [f64; 2]| 1.0 + 2.0 * x - 0.5 * y;
        let quadratic = |[x, y]: [f64; 2]| linear([x, y]) + x * x - 3.0 * x * y + 0.7 * y * y;
        for (family, full, f) in [
            (Family::T6, false, &linear as &dyn Fn([f64; 2]) -> f64),
            (Family::T6, true, &quadratic),
            (Family::Q8, false, &|[x, y]: [f64; 2]| {
                1.0 + x - y + 0.3 * x * y
            }),
        ] {
            let rule = family.rule(full);
            let v: Vec<f64> = rule.points.iter().map(|p| f(p.0)).collect();
            let nodes = family.extrapolate_to_nodes(&rule, &v);
            for (a, &x) in family.node_xi().iter().enumerate() {
                assert!((nodes[a] - f(x)).abs() < 1e-12, "{family:?} node {a}");
            }
        }
    }

    #[test]
    fn edges_walk_around_the_element_counter_clockwise() {
        for family in Family::ALL {
            let xi = family.node_xi();
            let edges = family.edges();
            assert_eq!(edges.len(), family.corners());
            let mut twice_area = 0.0;
            for (k, e) in edges.iter().enumerate() {
                // consecutive, the midside halfway
                assert_eq!(e[2], edges[(k + 1) % edges.len()][0]);
                let mid = [
                    (xi[e[0]][0] + xi[e[2]][0]) / 2.0,
                    (xi[e[0]][1] + xi[e[2]][1]) / 2.0,
                ];
                assert_eq!(xi[e[1]], mid);
                twice_area += xi[e[0]][0] * xi[e[2]][1] - xi[e[2]][0] * xi[e[0]][1];
            }
            assert!(twice_area > 0.0, "{family:?}");
        }
    }

    #[test]
    fn a_straight_sided_triangles_area_and_inversion() {
        let c = [[0.0, 0.0], [3.0, 0.5], [0.8, 2.0]];
        let mut x = [[0.0; 2]; 6];
        x[..3].copy_from_slice(&c);
        for (k, (a, b)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
            x[3 + k] = [(c[a][0] + c[b][0]) / 2.0, (c[a][1] + c[b][1]) / 2.0];
        }
        let area: f64 = t6::gauss_3()
            .points
            .iter()
            .map(|&(p, w)| w * Family::T6.physical_derivs(&x, p).unwrap().0)
            .sum();
        let exact = 0.5
            * ((c[1][0] - c[0][0]) * (c[2][1] - c[0][1])
                - (c[2][0] - c[0][0]) * (c[1][1] - c[0][1]));
        assert!((area - exact).abs() < 1e-12);
        x.swap(1, 2);
        x.swap(3, 5);
        assert!(Family::T6.physical_derivs(&x, [0.2, 0.2]).is_err());
    }
}
