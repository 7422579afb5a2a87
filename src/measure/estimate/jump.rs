//! The interface's part of the estimate: the traction jump across the
//! contact, weighted as in Kelly's indicator.
//!
//! At each spring point of an interface (where the law is evaluated, with
//! its integration weight dA: the area the point stands for, thickness or
//! 2π r included) the traction the recovered stress puts on each side is
//! compared with the spring's:
//! ```text
//!   τ    = p_N n + p_T t (+ p_Tθ e_θ)       on body A (n from B into A, t = (n_y, −n_x))
//!   r_A  = σ*_A (−n) − τ,    r_B = σ*_B n + τ                (B carries −τ)
//!   η²_I,K = h_K / (24 E_K) ∫_{Γ ∩ ∂K} |r_K|² dA
//! ```
//! p_N is the normal law at the point's approach, p_T and p_Tθ the
//! committed shears. The weight h_K/24 is Kelly's (Kelly, Gago,
//! Zienkiewicz & Babuška 1983, IJNME 19, the jump of the flux across an
//! element side weighted by the element size, the weight deal.II's
//! KellyErrorEstimator uses and step-42 refines by); 1/E_K turns a squared
//! traction (MPa²) times a length (mm) times an area (mm²) into energy
//! (N·mm), the units of the element's ∫ eᵀ C⁻¹ e dΩ. σ*_K at the point is
//! the side's recovered nodal stress interpolated with the point's weights
//! on that side's nodes (the edge's shape functions, or the mortar weights
//! ∫ N_i N_k dA / A_i); each side's ∫ |r_K|² dA goes to the elements of
//! that side holding the nodes, by the same weights.

use super::recovery::{Recovered, Stress};
use crate::model::interface::{Coupling, InterfaceModel, Point};
use crate::model::state::State;
use crate::model::Model;
use std::collections::{HashMap, HashSet};

/// Adds each interface's jump term to `out` (per element, N·mm), from the
/// recovered nodal stress of every element.
pub fn add(model: &Model, state: &State, recovered: &Recovered, out: &mut [f64]) {
    let mesh = &model.mesh;
    let twist = model.node_dofs().twist();
    let mut base = 0;
    for im in &model.interfaces {
        let sides: Vec<[Vec<(usize, f64)>; 2]> = im.points.iter().map(|p| sides(im, p)).collect();
        let maps = [im.body_a, im.body_b].map(|body| {
            let side = if body == im.body_a { 0 } else { 1 };
            let set: HashSet<usize> = sides
                .iter()
                .flat_map(|s| s[side].iter().map(|&(n, _)| n))
                .collect();
            let mut map: HashMap<usize, Vec<(usize, usize)>> = HashMap::new();
            for (e, el) in mesh.elements.iter().enumerate() {
                if el.body != body || el.nodes().iter().filter(|n| set.contains(n)).count() < 2 {
                    continue;
                }
                for (a, &n) in el.nodes().iter().enumerate() {
                    if set.contains(&n) {
                        map.entry(n).or_default().push((e, a));
                    }
                }
            }
            map
        });
        let gap = im.gap_at(state.time);
        for (k, pt) in im.points.iter().enumerate() {
            let (u_n, _) = im.point_kinematics_at(pt, &state.u, gap);
            let p_n = im.law.pressure(u_n).0;
            let cs = &state.contact[base + k];
            let (n, t) = (pt.normal, pt.tangent);
            // the second shear's direction: e_θ with twist, t₂ in 3D
            let h = match (twist, model.mesh.dim()) {
                (true, _) => [0.0, 0.0, 1.0],
                (_, 3) => pt.binormal(),
                _ => [0.0; 3],
            };
            let tau: [f64; 3] = std::array::from_fn(|c| p_n * n[c] + cs.p_t * t[c] + cs.p_h * h[c]);
            for side in 0..2 {
                let map = &maps[side];
                let weights = &sides[k][side];
                let mut sigma = [0.0; 6];
                for &(node, w) in weights {
                    let s = mean(map.get(&node).map_or(&[][..], |v| v), recovered);
                    for c in 0..6 {
                        sigma[c] += w * s[c];
                    }
                }
                // the outward normal of the side and the traction on it
                let (m, sign) = if side == 0 { (-1.0, 1.0) } else { (1.0, -1.0) };
                // σ n in the Voigt order (xx, yy, xy, zz, xz, yz) = (rr, zz,
                // rz, θθ, rθ, zθ); n_z = 0 in a plane
                let tr = [
                    m * (sigma[0] * n[0] + sigma[2] * n[1] + sigma[4] * n[2]),
                    m * (sigma[2] * n[0] + sigma[1] * n[1] + sigma[5] * n[2]),
                    m * (sigma[4] * n[0] + sigma[5] * n[1] + sigma[3] * n[2]),
                ];
                let r2: f64 = (0..3).map(|c| (tr[c] - sign * tau[c]).powi(2)).sum();
                let jump = pt.area * r2;
                for &(node, w) in weights {
                    let Some(els) = map.get(&node) else { continue };
                    let share = w * jump / els.len() as f64;
                    for &(e, _) in els {
                        let young = model.materials[mesh.elements[e].body].young;
                        out[e] += share * diameter(mesh, e) / (24.0 * young);
                    }
                }
            }
        }
        base += im.points.len();
    }
}

/// A point's nodes on side A and on side B with their weights (summing to
/// 1 on each side): the edge's shape functions, the node-to-segment
/// weights, or a mortar spring's |∂u_N/∂u_node · n| (the weights
/// ∫ N_i N_k dA / A_i, negative on the slave side).
fn sides(im: &InterfaceModel, pt: &Point) -> [Vec<(usize, f64)>; 2] {
    let mut out: [Vec<(usize, f64)>; 2] = [Vec::new(), Vec::new()];
    match &pt.coupling {
        Coupling::Mortar { mortar: m, .. } => {
            for (j, &node) in m.nodes.iter().enumerate() {
                let d = m.dn[j][0] * pt.normal[0] + m.dn[j][1] * pt.normal[1];
                out[usize::from(d > 0.0)].push((node, d.abs()));
            }
        }
        Coupling::NodeToSegment { segment: g, .. } => {
            out[0] = (0..g.len_a).map(|i| (g.a[i], g.na[i])).collect();
            out[1] = (0..g.len_b).map(|j| (g.b[j], g.nb[j])).collect();
        }
        Coupling::Coincident { .. } => {
            for (pair, w) in pt.coupling.pairs() {
                let pr = &im.pairs[pair];
                out[0].push((pr.a, w));
                out[1].push((pr.b, w));
            }
        }
    }
    for side in out.iter_mut() {
        let total: f64 = side.iter().map(|p| p.1).sum();
        if total.abs() > 0.0 {
            side.iter_mut().for_each(|p| p.1 /= total);
        }
    }
    out
}

/// The mean of the recovered stress at (element, local node) entries.
fn mean(at: &[(usize, usize)], recovered: &Recovered) -> Stress {
    let mut s = [0.0; 6];
    for &(e, a) in at {
        for (t, v) in s.iter_mut().zip(recovered.element(e)[a]) {
            *t += v / at.len() as f64;
        }
    }
    s
}

/// The element's diameter: the longer diagonal between its corners (a
/// quad), its longest side (a triangle); in 3D the largest distance
/// between two of its corners.
pub fn diameter(mesh: &crate::input::mesh::Mesh, e: usize) -> f64 {
    if mesh.dim() == 3 {
        let c = mesh.elements[e].corners();
        let x = |a: usize| mesh.nodes[c[a]];
        let d = |a: usize, b: usize| {
            let v = crate::numbers::vec3::sub(x(a), x(b));
            crate::numbers::vec3::dot(v, v).sqrt()
        };
        return (0..c.len())
            .flat_map(|a| (a + 1..c.len()).map(move |b| (a, b)))
            .fold(0.0, |m, (a, b)| m.max(d(a, b)));
    }
    mesh.elements[e].family.diameter(&mesh.element_coords(e))
}
