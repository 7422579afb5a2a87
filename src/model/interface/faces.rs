//! The interface of a 3D model: the paper's springs per unit area on
//! contact faces (8-node quadrilaterals of hexahedra, 6-node triangles of
//! tetrahedra), with the slip a 2-vector of the tangent plane.
//!
//! ```text
//!   u_B − u_A = Σ_i w_i u_i           (w_i = −N_i on A's nodes, +N_j on B's)
//!   u_N  = (u_B − u_A)·n − g₀         n from B into A: ∂x/∂ξ × ∂x/∂η of B's face
//!   u_T1 = (u_B − u_A)·t₁,  u_T2 = (u_B − u_A)·t₂,   t₂ = n × t₁
//!   Π = ∫ φ(u_N) dA;  r = a (p_N g_N + p_T1 g_T1 + p_T2 g_T2)   per point
//! ```
//!
//! The energy of the paper's eq. 3.29-3.31 over a face instead of an edge:
//! * **consistent** weights integrate it by the tensor product of the
//!   4-point Gauss rule of the plane interface's edges on a quadrilateral
//!   face (so a face swept from a plane contact edge integrates exactly as
//!   the edge does: a slab in plane strain equals the plane run), by the
//!   6-point degree-4 rule on a triangle; u_N and u_T interpolated by the
//!   face's shape functions;
//! * **lumped** weights put one spring on each node pair. The row sums of
//!   the consistent matrix, which give the edge Simpson's 1/6, 2/3, 1/6,
//!   are negative at a serendipity face's corners (−A/12, midsides A/3;
//!   0 at a 6-node triangle's corners), which no spring can carry; the
//!   nodes take instead the diagonal of the consistent matrix scaled to
//!   the face's area (Hinton, Rock & Zienkiewicz 1976, "A note on mass
//!   lumping and related processes", Earthq. Eng. Struct. Dyn. 4:245-249):
//!   w_a = A ∫N_a² dA / Σ_b ∫N_b² dA, positive on every face.
//!
//! The slip frame t₁ = n × e_z / |n × e_z| (the plane interface's own
//! t = (n_y, −n_x) on a face swept along z), or e_y × n / |e_y × n| where
//! the normal is within 25° of the z axis; the vector tangential law is
//! isotropic in the tangent plane, so the frame orients only the outputs.
//! The vector law and its tangent are the twisting model's
//! ([`super::circumferential`]) with g_θ read as g_T2.

use super::circumferential::Gradients;
use super::{gauss4, Coupling, InterfaceModel, Pair, Point, MAX_SIDE};
use crate::input::case::settings::Weights;
use crate::input::mesh::{Face, Family, Interface, Mesh};
use crate::numbers::vec3::{cross, dot};

impl InterfaceModel {
    /// The spatial dimension the interface lives in: 3 in a 3D model, else 2.
    pub(crate) fn dim(&self) -> usize {
        if self.node_dofs.solid() {
            3
        } else {
            2
        }
    }

    /// The pairs and points of a matching 3D interface (coincident face
    /// nodes): pairs in the order the faces first name them.
    pub(super) fn coincident_faces(
        mesh: &Mesh,
        iface: &Interface,
        weights: Weights,
    ) -> (Vec<Pair>, Vec<Point>) {
        let mut pairs: Vec<Pair> = Vec::new();
        let mut index = std::collections::HashMap::new();
        let mut points = Vec::new();
        for f in &iface.faces {
            let (a, b) = (f.a.nodes(), f.b.nodes());
            let ids: Vec<usize> = (0..b.len())
                .map(|i| {
                    *index.entry((a[i], b[i])).or_insert_with(|| {
                        pairs.push(Pair {
                            a: a[i],
                            b: b[i],
                            x: mesh.nodes[b[i]],
                            normal: [0.0; 3],
                            area: 0.0,
                            spring: None,
                        });
                        pairs.len() - 1
                    })
                })
                .collect();
            let x = face_coords(mesh, &f.b);
            for (k, (w, n)) in lumped(f.b.family, &x).into_iter().enumerate() {
                let p = &mut pairs[ids[k]];
                p.area += w;
                for (pc, nc) in p.normal.iter_mut().zip(n) {
                    *pc += w * nc;
                }
            }
            if weights == Weights::Consistent {
                for (xi, wg) in face_rule(f.b.family) {
                    let (shape, n, da) = geometry(f.b.family, &x, xi);
                    points.push(Point {
                        area: wg * da,
                        normal: n,
                        tangent: frame(n),
                        coupling: Coupling::Coincident {
                            pairs: super::side(&ids),
                            shape: super::side(&shape[..ids.len()]),
                            len: ids.len(),
                        },
                    });
                }
            }
        }
        for p in &mut pairs {
            p.normal = unit(p.normal);
        }
        if weights == Weights::Lumped {
            points = super::lumped_points(&pairs, frame);
        }
        (pairs, points)
    }

    /// u_N, u_T1 and u_T2 at a point of a 3D interface (module text), across
    /// the given gap and, on a non-matching interface, the spring's own
    /// geometric gap.
    pub(crate) fn point_kinematics_3d(&self, pt: &Point, u: &[f64], gap: f64) -> [f64; 3] {
        let nd = self.node_dofs;
        let mut du = [0.0f64; 3];
        for (&node, w) in self.point_nodes(pt).iter().zip(self.node_weights(pt)) {
            for (c, d) in du.iter_mut().enumerate() {
                *d += w * u[nd.dof(node, c)];
            }
        }
        let g0 = pt.geometric_gap().unwrap_or(0.0);
        [
            dot(du, pt.normal) - g0 - gap,
            dot(du, pt.tangent),
            dot(du, pt.binormal()),
        ]
    }

    /// Where a point is: its pairs' places interpolated by its shape values
    /// (coincident pairs), or its slave point (a spring).
    pub(crate) fn point_position(&self, pt: &Point) -> [f64; 3] {
        match &pt.coupling {
            Coupling::Coincident { pairs, shape, len } => std::array::from_fn(|c| {
                (0..*len)
                    .map(|i| shape[i] * self.pairs[pairs[i]].x[c])
                    .sum()
            }),
            Coupling::NodeToSegment { pair, .. } | Coupling::Mortar { pair, .. } => {
                self.pairs[*pair].x
            }
        }
    }

    /// The area-weighted centroid of the interface's points.
    pub(crate) fn centroid(&self) -> [f64; 3] {
        let mut c = [0.0; 3];
        let mut area = 0.0;
        for pt in &self.points {
            let x = self.point_position(pt);
            area += pt.area;
            for k in 0..3 {
                c[k] += pt.area * x[k];
            }
        }
        c.map(|v| if area > 0.0 { v / area } else { 0.0 })
    }

    /// The slip (u_T1, u_T2) at a coincident pair of a 3D interface, in the
    /// frame of its normal (a point of lumped weights).
    pub(super) fn pair_slip_3d(&self, pair: &Pair, u: &[f64]) -> [f64; 2] {
        let nd = self.node_dofs;
        let du: [f64; 3] = std::array::from_fn(|c| u[nd.dof(pair.b, c)] - u[nd.dof(pair.a, c)]);
        tangents(pair.normal).map(|t| dot(du, t))
    }

    /// g_N, g_T1 and g_T2 (as `h`) of a 3D point over its local dofs, three
    /// per node in the order of [`InterfaceModel::point_nodes`].
    pub(super) fn gradients_3d(&self, pt: &Point) -> Gradients {
        let w = self.node_weights(pt);
        let t2 = pt.binormal();
        let spread =
            |d: [f64; 3]| -> Vec<f64> { w.iter().flat_map(|&w| d.map(|v| w * v)).collect() };
        Gradients {
            n: spread(pt.normal),
            t: spread(pt.tangent),
            h: spread(t2),
        }
    }
}

/// The slip frame's first tangent t₁ at unit normal n (module text).
pub(crate) fn frame(n: [f64; 3]) -> [f64; 3] {
    if n[2].abs() < 0.9 {
        unit(cross(n, [0.0, 0.0, 1.0]))
    } else {
        unit(cross([0.0, 1.0, 0.0], n))
    }
}

/// The slip frame's two tangents at unit normal n: t₁ ([`frame`]) and
/// t₂ = n × t₁.
pub(crate) fn tangents(n: [f64; 3]) -> [[f64; 3]; 2] {
    let t1 = frame(n);
    [t1, cross(n, t1)]
}

pub(super) fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    v.map(|c| c / l)
}

/// The coordinates of a face's nodes.
pub(super) fn face_coords(mesh: &Mesh, face: &Face) -> Vec<[f64; 3]> {
    face.nodes().iter().map(|&n| mesh.nodes[n]).collect()
}

/// The consistent rule of an interface face: 4 × 4 Gauss on a
/// quadrilateral (the plane edge's 4-point rule in both directions), the
/// 6-point degree-4 rule on a triangle; (ξ, weight).
pub(super) fn face_rule(family: Family) -> Vec<([f64; 2], f64)> {
    match family {
        Family::Q8 => {
            let g = gauss4();
            g.iter()
                .flat_map(|&(eta, we)| g.iter().map(move |&(xi, wx)| ([xi, eta], wx * we)))
                .collect()
        }
        _ => family.rule(true).points,
    }
}

/// The shape values, the unit normal ∂x/∂ξ × ∂x/∂η / |…| and the area
/// element |∂x/∂ξ × ∂x/∂η| of a face at ξ.
pub(super) fn geometry(
    family: Family,
    x: &[[f64; 3]],
    xi: [f64; 2],
) -> ([f64; MAX_SIDE], [f64; 3], f64) {
    let (n, d) = (family.shape(xi), family.shape_derivs(xi));
    let mut g = [[0.0; 3]; 2];
    for (a, xa) in x.iter().enumerate() {
        for (k, gk) in g.iter_mut().enumerate() {
            for c in 0..3 {
                gk[c] += d[a][k] * xa[c];
            }
        }
    }
    let normal = cross(g[0], g[1]);
    let da = dot(normal, normal).sqrt();
    let shape = std::array::from_fn(|a| if a < x.len() { n[a] } else { 0.0 });
    (shape, normal.map(|c| c / da), da)
}

/// Each node's lumped area (the scaled diagonal of the module text) and
/// its normal there, for a face with node coordinates x.
pub(super) fn lumped(family: Family, x: &[[f64; 3]]) -> Vec<(f64, [f64; 3])> {
    let nn = x.len();
    let (mut diag, mut area) = (vec![0.0; nn], 0.0);
    for (xi, wg) in face_rule(family) {
        let (shape, _, da) = geometry(family, x, xi);
        area += wg * da;
        for a in 0..nn {
            diag[a] += wg * da * shape[a] * shape[a];
        }
    }
    let total: f64 = diag.iter().sum();
    (0..nn)
        .map(|a| {
            let (_, n, _) = geometry(family, x, family.node_xi()[a]);
            (area * diag[a] / total, n)
        })
        .collect()
}

#[cfg(test)]
mod tests;
