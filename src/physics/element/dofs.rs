//! Dofs per node, one value of the model, and their numbering.
//!
//! Every node carries the same number k of displacement components: k = 2
//! (u_x, u_y; u_r, u_z in axisymmetry), k = 3 in an axisymmetric model with
//! twist (u_r, u_z, u_θ) or in a 3D model (u_x, u_y, u_z). Node n's component c is the global dof k·n + c, and
//! the extra nodes after the mesh's (a pretension section's reference node)
//! are numbered the same way. Everything that indexes a global vector by node
//! (assembly, loads, supports, both backends, restart, output) goes through
//! [`NodeDofs`], so a model with three dofs is the same code as one with two.
//!
//! ```text
//!   dof(n, c) = k·n + c          element dofs: nodes·k, node-major
//! ```

use std::ops::Range;

/// The number of dofs per node (2, or 3 with twist or in 3D), whether the
/// third is twist's u_θ, and the numbering dof(n, c) = k·n + c.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeDofs(usize, bool);

impl Default for NodeDofs {
    fn default() -> Self {
        Self::PLANE
    }
}

impl NodeDofs {
    /// u_x, u_y (u_r, u_z in axisymmetry).
    pub(crate) const PLANE: NodeDofs = NodeDofs(2, false);
    /// u_r, u_z, u_θ: an axisymmetric model with twist.
    pub(crate) const TWIST: NodeDofs = NodeDofs(3, true);
    /// u_x, u_y, u_z: a 3D model.
    pub(crate) const SOLID: NodeDofs = NodeDofs(3, false);
    /// The most dofs a node can have.
    pub const MAX: usize = 3;
    /// The most dofs an element of any family can have (20 nodes × 3).
    pub(crate) const MAX_ELEMENT: usize =
        crate::physics::element::family::MAX_ELEMENT_NODES * Self::MAX;

    /// Dofs per node, k.
    pub fn per_node(self) -> usize {
        self.0
    }

    /// The global dof of node `node`'s component `c` (0: x or r, 1: y or z,
    /// 2: θ).
    pub fn dof(self, node: usize, c: usize) -> usize {
        debug_assert!(c < self.0);
        self.0 * node + c
    }

    /// Every dof of node `node`.
    pub fn of(self, node: usize) -> Range<usize> {
        self.0 * node..self.0 * (node + 1)
    }

    /// The node and component of a global dof.
    pub fn node_of(self, dof: usize) -> (usize, usize) {
        (dof / self.0, dof % self.0)
    }

    /// The number of dofs of `nodes` nodes.
    pub fn count(self, nodes: usize) -> usize {
        self.0 * nodes
    }

    /// Dofs of one element of `nodes` nodes (16 or 24 for the quad, 12 or
    /// 18 for the triangle, 60 for the hexahedron, 30 for the tetrahedron).
    pub fn element(self, nodes: usize) -> usize {
        nodes * self.0
    }

    /// Whether the nodes carry the circumferential displacement u_θ.
    pub fn twist(self) -> bool {
        self.1
    }

    /// Whether the nodes are a 3D model's (u_x, u_y, u_z).
    pub fn solid(self) -> bool {
        self.0 == 3 && !self.1
    }

    /// Whether an interface point's slip is a 2-vector of its tangent plane
    /// (twist: meridian and hoop; 3D: t₁ and t₂), so it carries the vector
    /// tangential law's state.
    pub fn vector_slip(self) -> bool {
        self.0 == 3
    }

    /// Whether a Gauss point carries all six stress components (twist, 3D).
    pub(crate) fn six_components(self) -> bool {
        self.0 == 3
    }
}

#[cfg(test)]
mod tests {
    use super::NodeDofs;

    #[test]
    fn numbering_round_trips() {
        for nd in [NodeDofs::PLANE, NodeDofs::TWIST, NodeDofs::SOLID] {
            let k = nd.per_node();
            for n in 0..5 {
                for c in 0..k {
                    let d = nd.dof(n, c);
                    assert_eq!(nd.node_of(d), (n, c));
                    assert!(nd.of(n).contains(&d));
                }
            }
            assert_eq!(nd.count(4), 4 * k);
            assert_eq!(nd.element(8), 8 * k);
            assert!(nd.element(8) <= NodeDofs::MAX_ELEMENT);
        }
        assert_eq!(NodeDofs::default(), NodeDofs::PLANE);
        assert!(NodeDofs::TWIST.twist() && !NodeDofs::PLANE.twist() && !NodeDofs::SOLID.twist());
        assert!(NodeDofs::SOLID.six_components() && !NodeDofs::PLANE.six_components());
        assert!(NodeDofs::SOLID.solid() && !NodeDofs::TWIST.solid() && !NodeDofs::PLANE.solid());
        assert!(NodeDofs::SOLID.vector_slip() && NodeDofs::TWIST.vector_slip());
        assert!(!NodeDofs::PLANE.vector_slip());
    }
}
