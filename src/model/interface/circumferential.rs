//! The interface of a twisting axisymmetric model (`[model] twist = true`,
//! issue 26): every node carries (u_r, u_z, u_θ), so a point's local dofs
//! are its nodes' three components, node-major, and its slip is a 2-vector
//! of the tangent plane,
//!
//! ```text
//!   u_T = (u_T1, u_Tθ),  u_T1 = (u_B − u_A)·t   (along the meridian, as without twist)
//!                        u_Tθ = u_θB − u_θA     (around the axis: r Δφ)
//!   r  = a (p_N g_N + p_T1 g_T1 + p_Tθ g_θ)
//!   k  = a (k_N g_N g_Nᵀ + Σ_ij ∂p_i/∂u_j g_i g_jᵀ) + a (∂p_1/∂u_N g_T1 + ∂p_θ/∂u_N g_θ) g_Nᵀ
//! ```
//!
//! g_N, g_T1 are the in-plane gradients of [`super::Point::gradients`] with a
//! zero θ entry per node, g_θ has only θ entries: the shape weight of the
//! node in the relative displacement B − A (−N_i on A's side, +N_j on B's;
//! on a mortar spring (1/A_i) ∫ N_i (±N_j) dA, [`super::Mortar::dh`]). The
//! point evaluates the vector law ([`super::TangentialLaw::eval_vector`]);
//! its tangent's unsymmetric part is still one rank-one term u g_Nᵀ per
//! point, u = a (∂p_1/∂u_N g_T1 + ∂p_θ/∂u_N g_θ), the vector form of
//! [`super::PointEval::coupling`] that the serial backend keeps out of its
//! Cholesky factor. All three couplings (coincident pairs, node-to-segment,
//! mortar) carry the circumferential slip; the stiffness-modification
//! scheme, a secant of one scalar slip, is refused with twist
//! ([`crate::input::case::twist`]).

use super::{Coupling, InterfaceModel, Point, PointEval, PointState, Slip, Status};

/// The gradients of a point's approach u_N, meridional slip u_T1 and
/// circumferential slip u_Tθ with respect to its local dofs.
pub(crate) struct Gradients {
    pub n: Vec<f64>,
    pub t: Vec<f64>,
    /// Empty without twist.
    pub h: Vec<f64>,
}

impl InterfaceModel {
    /// Whether the model twists (its nodes carry u_θ).
    pub fn twist(&self) -> bool {
        self.node_dofs.twist()
    }

    /// The nodes of a point in local order: A pairs then B pairs; on a
    /// non-matching interface the slave nodes, then the master edge's; on a
    /// mortar spring its nodes.
    pub(crate) fn point_nodes(&self, pt: &Point) -> Vec<usize> {
        match &pt.coupling {
            Coupling::Mortar { mortar: m, .. } => m.nodes.clone(),
            Coupling::NodeToSegment { segment: g, .. } => g.a[..g.len_a]
                .iter()
                .chain(&g.b[..g.len_b])
                .copied()
                .collect(),
            Coupling::Coincident { pairs, len, .. } => {
                let pairs = || pairs[..*len].iter().map(|&p| &self.pairs[p]);
                pairs().map(|p| p.a).chain(pairs().map(|p| p.b)).collect()
            }
        }
    }

    /// The weight of each local node's displacement in the relative
    /// displacement B − A at the point (−N_i on A's side, +N_j on B's; the
    /// weight of its u_θ in u_Tθ with twist), order of
    /// [`InterfaceModel::point_nodes`].
    pub(crate) fn node_weights(&self, pt: &Point) -> Vec<f64> {
        match &pt.coupling {
            Coupling::Mortar { mortar: m, .. } => m.dh.clone(),
            Coupling::NodeToSegment { segment: g, .. } => {
                let a = g.na[..g.len_a].iter().map(|v| -v);
                a.chain(g.nb[..g.len_b].iter().copied()).collect()
            }
            Coupling::Coincident { shape, len, .. } => {
                let s = &shape[..*len];
                s.iter().map(|v| -v).chain(s.iter().copied()).collect()
            }
        }
    }

    /// The radius of every point (index as `points`), mm: on coincident
    /// pairs interpolated from the pairs' positions by the point's shape
    /// values, on a non-matching interface the slave point's (its pair's),
    /// on a mortar spring [`super::Mortar::radius`] (the arm of its force,
    /// so that Σ A r p_Tθ is the torque on the slave nodes and a rigid twist
    /// Δφ gives u_Tθ / r = Δφ).
    pub fn point_radii(&self) -> Vec<f64> {
        self.points
            .iter()
            .map(|pt| match &pt.coupling {
                Coupling::Coincident { pairs, shape, len } => (0..*len)
                    .map(|i| shape[i] * self.pairs[pairs[i]].x[0])
                    .sum(),
                Coupling::NodeToSegment { pair, .. } => self.pairs[*pair].x[0],
                Coupling::Mortar { mortar: m, .. } => m.radius,
            })
            .collect()
    }

    /// Number of a point's local dofs: [`Point::ndofs`] without twist, 3 per
    /// node with it.
    pub(crate) fn point_ndofs(&self, pt: &Point) -> usize {
        pt.ndofs() / 2 * self.node_dofs.per_node()
    }

    /// The second component of a point's slip, mm: with twist the
    /// circumferential slip u_Tθ = u_θB − u_θA, in 3D the slip along t₂
    /// ([`Point::binormal`]); 0 in a plane model.
    pub(crate) fn point_second_slip(&self, pt: &Point, u: &[f64]) -> f64 {
        if self.node_dofs.solid() {
            return self.point_kinematics_3d(pt, u, 0.0)[2];
        }
        if !self.twist() {
            return 0.0;
        }
        let nd = self.node_dofs;
        let nodes = self.point_nodes(pt);
        let w = self.node_weights(pt);
        nodes
            .iter()
            .zip(&w)
            .map(|(&n, w)| w * u[nd.dof(n, 2)])
            .sum()
    }

    /// The second slip at a pair (nodal value, 0 in a plane model): with
    /// twist u_θB − u_θA, in 3D (u_B − u_A)·t₂ of the pair's own point (a
    /// pair of lumped weights); on a non-matching interface that of the
    /// pair's spring point.
    pub(crate) fn pair_second_slip(&self, pair: &super::Pair, u: &[f64]) -> f64 {
        if let Some(j) = pair.spring {
            return self.point_second_slip(&self.points[j], u);
        }
        if self.node_dofs.solid() {
            return self.pair_slip_3d(pair, u)[1];
        }
        if !self.twist() {
            return 0.0;
        }
        let nd = self.node_dofs;
        u[nd.dof(pair.b, 2)] - u[nd.dof(pair.a, 2)]
    }

    /// g_N, g_T1 (and g_θ with twist) over the point's local dofs
    /// ([`InterfaceModel::point_dofs`]); without twist exactly
    /// [`Point::gradients`].
    pub(crate) fn point_gradients(&self, pt: &Point) -> Gradients {
        if self.node_dofs.solid() {
            return self.gradients_3d(pt);
        }
        let (n, t) = pt.gradients();
        if !self.twist() {
            return Gradients {
                n,
                t,
                h: Vec::new(),
            };
        }
        let widen =
            |v: &[f64]| -> Vec<f64> { v.chunks_exact(2).flat_map(|c| [c[0], c[1], 0.0]).collect() };
        let h = self
            .node_weights(pt)
            .iter()
            .flat_map(|&w| [0.0, 0.0, w])
            .collect();
        Gradients {
            n: widen(&n),
            t: widen(&t),
            h,
        }
    }

    /// [`InterfaceModel::eval_point_parts`] of a twisting or a 3D model
    /// (see the module comment): the vector law on (u_T1, u_Tθ), or in 3D
    /// on (u_T1, u_T2) with g_θ read as g_T2 (`crate::model::interface::faces`).
    #[allow(clippy::too_many_arguments)] // eval_point_parts' arguments
    pub(super) fn eval_point_vector(
        &self,
        pt: &Point,
        u: &[f64],
        gap: f64,
        committed: &PointState,
        k_floor: Option<f64>,
        r: &mut [f64],
        k: Option<&mut [f64]>,
        with_coupling: bool,
    ) -> PointEval {
        let [u_n, u_t, u_h] = if self.node_dofs.solid() {
            self.point_kinematics_3d(pt, u, gap)
        } else {
            let (u_n, u_t) = self.point_kinematics_at(pt, u, gap);
            [u_n, u_t, self.point_second_slip(pt, u)]
        };
        let (p_n, k_law) = self.law.pressure(u_n);
        let k_n = match k_floor {
            Some(kf) if u_n <= 0.0 => kf,
            _ => k_law,
        };
        let g = self.point_gradients(pt);
        let mut status = if u_n > 0.0 {
            Status::Closed
        } else {
            Status::Open
        };
        let (mut p, mut d_ut, mut d_un) = ([0.0; 2], [[0.0; 2]; 2], [0.0; 2]);
        let mut state = PointState {
            u_t,
            u_h,
            ..*committed
        };
        if let Some(law) = &self.tangential {
            let ev = law.eval_vector(p_n, k_law, [u_t, u_h], &committed.slip2);
            (p, d_ut, d_un) = (ev.p_t, ev.d_ut, ev.d_un);
            state = PointState {
                slip: Default::default(),
                p_t: p[0],
                u_t,
                mu_f: ev.mu_f,
                p_h: p[1],
                u_h,
                slip2: ev.state,
            };
            if u_n > 0.0 {
                status = match ev.slip {
                    Slip::Stick => Status::Stick,
                    Slip::MicroSlip => Status::MicroSlip,
                    Slip::MacroSlip => Status::MacroSlip,
                };
            }
        }
        let nd = self.point_ndofs(pt);
        let a = pt.area;
        for (i, ri) in r[..nd].iter_mut().enumerate() {
            *ri = a * (p_n * g.n[i] + p[0] * g.t[i] + p[1] * g.h[i]);
        }
        if let Some(k) = k {
            let kept = if with_coupling { d_un } else { [0.0; 2] };
            let d = d_ut;
            // the plane point's operations, term for term, when g_θ = 0
            for i in 0..nd {
                for j in 0..nd {
                    k[i * nd + j] = a
                        * (k_n * g.n[i] * g.n[j]
                            + g.t[i] * (d[0][0] * g.t[j] + d[0][1] * g.h[j] + kept[0] * g.n[j])
                            + g.h[i] * (d[1][0] * g.t[j] + d[1][1] * g.h[j] + kept[1] * g.n[j]));
                }
            }
        }
        PointEval {
            u_n,
            p_n,
            status,
            state,
            coupling: a * d_un[0],
            coupling_hoop: a * d_un[1],
        }
    }
}

#[cfg(test)]
mod tests;
