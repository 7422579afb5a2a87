//! Node-to-surface springs of a 3D interface meshed apart (`matching =
//! false` on faces; small sliding): the 3D form of [`super::segment`]'s
//! node-to-segment springs.
//!
//! ```text
//!   slave point  x_A = Σ_i N_i^A x_{a_i}      (lumped: a slave face node; consistent: a Gauss point)
//!   its foot     x_B(ξ) = Σ_j N_j(ξ) x_{b_j}  the closest point of the master side: one 8-node
//!                                             quadrilateral or 6-node triangle, ξ in the face
//!   n            ∂x/∂ξ × ∂x/∂η / |…| of that face at ξ, from B into A
//!   g₀ = (x_A − x_B(ξ))·n;   u_N = (u_B(ξ) − u_A)·n − g₀ − gap;   u_T1,2 = (u_B(ξ) − u_A)·t₁,₂
//! ```
//!
//! The slave side's points are those of a matching 3D interface
//! ([`super::faces`]): its nodes with the scaled-diagonal areas of its faces
//! (lumped weights, the normal averaged as on a matching face), or the
//! faces' 4 × 4 Gauss points (6 on a triangle; consistent weights). Each is
//! projected once, on the undeformed mesh, onto the closest point of the
//! master side ([`closest`]: Newton on the face's natural coordinates), the
//! candidate faces found by a bounding-box tree ([`tree`]); ξ, n and g₀ are
//! kept for the run. One pair per point (the slave node and the master node
//! that weigh most in it), as in 2D; the point is a
//! [`super::Coupling::NodeToSegment`] with up to 8 slave and 8 master nodes,
//! whose kinematics, gradients and vector tangential law are those of every
//! 3D point ([`super::InterfaceModel::point_kinematics_3d`]). The slave
//! point's arc length [`super::Segment::s`] means nothing on a surface: 0.
//!
//! The foot is the closest point of the whole master side (the nearest over
//! its faces of each face's closest point). Inside a face (within
//! [`closest::XI_TOL`] of it) it takes the face's normal there. On an edge
//! or a corner node that the face shares with another master face (a kink
//! of a curved side: the points in the wedge between the faces' normals
//! project onto neither face) the normal is the direction from the foot to
//! the point (the gradient of the distance, continuous with the faces'
//! normals at the wedge's sides), oriented as the face's. On the master
//! side's free boundary (an edge of one face only) the point lies beyond
//! the master side and is refused, as are sides that do not face each other
//! and an overlap of more than [`OVERLAP_LIMIT`] of the slave face's size
//! (the checks of the plane's [`super::segment`], docs/theory.md,
//! "Non-matching interfaces in 3D").

mod closest;
mod tree;

use super::faces::{face_coords, face_rule, frame, geometry, lumped, unit};
use super::segment::{FACING_TOL, OVERLAP_LIMIT};
use super::{side, Coupling, Pair, Point, Segment, MAX_SIDE};
use crate::input::case::settings::Weights;
use crate::input::mesh::{Face, Family, Mesh, NonMatchingFaces};
use crate::numbers::vec3::{dot, sub};
use closest::{closest, Closest, On};
use std::collections::{HashMap, HashSet};
use tree::{Aabb, Tree};

/// The spring points of a 3D non-matching interface (module text), one
/// pair per point. An error names the interface and the point when it
/// projects outside the master side, the sides do not face each other
/// there, or they overlap.
pub(super) fn node_to_surface(
    mesh: &Mesh,
    name: &str,
    nm: &NonMatchingFaces,
    weights: Weights,
) -> Result<(Vec<Pair>, Vec<Point>), String> {
    let slave = slave_points(mesh, nm, weights);
    let master = Master::new(mesh, &nm.master);
    let mut pairs = Vec::with_capacity(slave.len());
    let mut points = Vec::with_capacity(slave.len());
    for sp in slave {
        let Foot { k, xi, n, gap } = master.foot(name, &sp)?;
        let face = &nm.master[k];
        let b = face.nodes();
        let nb = face.family.shape(xi);
        let near = |nodes: &[usize], vals: &[f64]| {
            let i = (0..vals.len())
                .max_by(|&i, &j| vals[i].abs().total_cmp(&vals[j].abs()))
                .unwrap_or(0);
            nodes[i]
        };
        pairs.push(Pair {
            a: near(&sp.a[..sp.len_a], &sp.na[..sp.len_a]),
            b: near(b, &nb[..b.len()]),
            x: sp.x,
            normal: n,
            area: sp.area,
            spring: Some(points.len()),
        });
        points.push(Point {
            area: sp.area,
            normal: n,
            tangent: frame(n),
            coupling: Coupling::NodeToSegment {
                pair: pairs.len() - 1,
                segment: Segment {
                    a: sp.a,
                    na: sp.na,
                    len_a: sp.len_a,
                    b: side(b),
                    nb: side(&nb[..b.len()]),
                    len_b: b.len(),
                    gap,
                    s: 0.0,
                },
            },
        });
    }
    Ok((pairs, points))
}

/// A spring point of the slave side: the slave nodes it interpolates, where
/// it sits, the area it stands for, body A's outward normal there and the
/// size of its slave face.
#[derive(Clone, Debug)]
struct SlavePoint {
    a: [usize; MAX_SIDE],
    na: [f64; MAX_SIDE],
    len_a: usize,
    x: [f64; 3],
    area: f64,
    out: [f64; 3],
    /// The slave face's size (the largest distance between two of its
    /// corners; a node's smallest over its faces), mm.
    h: f64,
}

/// The largest distance between two corners of a face.
fn size(family: Family, x: &[[f64; 3]]) -> f64 {
    let c = &x[..family.corners()];
    let mut d: f64 = 0.0;
    for (i, p) in c.iter().enumerate() {
        for q in &c[i + 1..] {
            let v = sub(*p, *q);
            d = d.max(dot(v, v).sqrt());
        }
    }
    d
}

/// The slave side's spring points (module text): at each slave node with
/// the scaled-diagonal area of every face around it (lumped), or at each
/// slave face's Gauss points (consistent).
fn slave_points(mesh: &Mesh, nm: &NonMatchingFaces, weights: Weights) -> Vec<SlavePoint> {
    let mut out: Vec<SlavePoint> = Vec::new();
    let mut at_node: HashMap<usize, usize> = HashMap::new();
    for f in &nm.slave {
        let x = face_coords(mesh, f);
        let h = size(f.family, &x);
        if weights == Weights::Lumped {
            for (k, (w, n)) in lumped(f.family, &x).into_iter().enumerate() {
                let node = f.nodes()[k];
                let i = *at_node.entry(node).or_insert_with(|| {
                    out.push(SlavePoint {
                        a: side(&[node]),
                        na: side(&[1.0]),
                        len_a: 1,
                        x: x[k],
                        area: 0.0,
                        out: [0.0; 3],
                        h,
                    });
                    out.len() - 1
                });
                let sp = &mut out[i];
                sp.area += w;
                // the face's normal points into A: A's outward normal is −n
                sp.out = std::array::from_fn(|c| sp.out[c] - w * n[c]);
                sp.h = sp.h.min(h);
            }
        } else {
            for (xi, wg) in face_rule(f.family) {
                let (shape, n, da) = geometry(f.family, &x, xi);
                let len = x.len();
                out.push(SlavePoint {
                    a: side(f.nodes()),
                    na: side(&shape[..len]),
                    len_a: len,
                    x: std::array::from_fn(|c| (0..len).map(|a| shape[a] * x[a][c]).sum()),
                    area: wg * da,
                    out: n.map(|v| -v),
                    h,
                });
            }
        }
    }
    for sp in &mut out {
        sp.out = unit(sp.out);
    }
    out
}

/// Where a slave point meets the master side: master face `k`, the natural
/// coordinates ξ of the foot on it, the normal there (from B into A) and the
/// geometric gap (x − x_B(ξ))·n.
#[derive(Debug)]
struct Foot {
    k: usize,
    xi: [f64; 2],
    n: [f64; 3],
    gap: f64,
}

/// The master side: its faces, their coordinates and bounding-box tree, and
/// its free boundary.
struct Master<'a> {
    faces: &'a [Face],
    coords: Vec<Vec<[f64; 3]>>,
    tree: Tree,
    /// The mid nodes of the edges of one master face only (the side's free
    /// boundary; an edge is known by its mid node).
    free_edges: HashSet<usize>,
    /// The nodes on those edges.
    free_nodes: HashSet<usize>,
    /// The box of the side's nodes (for messages).
    extent: Aabb,
}

impl<'a> Master<'a> {
    fn new(mesh: &Mesh, faces: &'a [Face]) -> Master<'a> {
        let coords: Vec<Vec<[f64; 3]>> = faces.iter().map(|f| face_coords(mesh, f)).collect();
        let boxes: Vec<Aabb> = faces
            .iter()
            .zip(&coords)
            .map(|(f, x)| face_box(f.family, x))
            .collect();
        let mut count: HashMap<usize, usize> = HashMap::new();
        let mut extent = Aabb::EMPTY;
        for f in faces {
            for e in f.family.edges() {
                *count.entry(f.nodes()[e[1]]).or_default() += 1;
            }
            for &n in f.nodes() {
                extent.grow(mesh.nodes[n]);
            }
        }
        let mut free_edges = HashSet::new();
        let mut free_nodes = HashSet::new();
        for f in faces {
            for e in f.family.edges() {
                if count[&f.nodes()[e[1]]] == 1 {
                    free_edges.insert(f.nodes()[e[1]]);
                    free_nodes.extend(e.iter().map(|&a| f.nodes()[a]));
                }
            }
        }
        Master {
            faces,
            tree: Tree::new(&boxes),
            coords,
            free_edges,
            free_nodes,
            extent,
        }
    }

    /// The closest master face's closest point to `p`: the face and the
    /// point (the nearest; at equal distance an inside foot before one on a
    /// face's boundary, then the lower-numbered face).
    fn nearest(&self, p: [f64; 3]) -> Option<(usize, Closest)> {
        let mut best: Option<(usize, Closest)> = None;
        self.tree.nearest(p, |f| {
            let c = closest(self.faces[f].family, &self.coords[f], p);
            let better = match &best {
                None => true,
                Some((g, b)) => {
                    let tie = (c.d2 - b.d2).abs() <= 1e-24 + 1e-12 * b.d2;
                    let rank = |c: &Closest, f: usize| (c.on != On::Inside, f);
                    if tie {
                        rank(&c, f) < rank(b, *g)
                    } else {
                        c.d2 < b.d2
                    }
                }
            };
            if better {
                best = Some((f, c));
            }
            c.d2
        });
        best
    }

    /// The foot of slave point `sp` (module text), checked.
    fn foot(&self, name: &str, sp: &SlavePoint) -> Result<Foot, String> {
        let outside = || self.outside(name, sp.x);
        let Some((k, c)) = self.nearest(sp.x) else {
            return Err(outside());
        };
        let face = &self.faces[k];
        let nf = geometry(face.family, &self.coords[k], c.xi).1;
        let n = match c.on {
            On::Inside => nf,
            On::Edge(e)
                if self
                    .free_edges
                    .contains(&face.nodes()[face.family.edges()[e][1]]) =>
            {
                return Err(outside())
            }
            On::Corner(a) if self.free_nodes.contains(&face.nodes()[a]) => return Err(outside()),
            // at a kink of the side: along the distance's gradient
            On::Edge(_) | On::Corner(_) => {
                let v = sub(sp.x, c.at);
                let d = dot(v, v).sqrt();
                if d > 1e-9 * sp.h {
                    let s = if dot(v, nf) < 0.0 { -1.0 } else { 1.0 };
                    v.map(|x| s * x / d)
                } else {
                    nf
                }
            }
        };
        let gap = dot(sub(sp.x, c.at), n);
        check(name, sp, n, c.at, gap)?;
        Ok(Foot {
            k,
            xi: c.xi,
            n,
            gap,
        })
    }

    /// The message of a slave point that projects outside the master side.
    fn outside(&self, name: &str, x: [f64; 3]) -> String {
        let (lo, hi) = (self.extent.lo, self.extent.hi);
        format!(
            "interface \"{name}\" (matching = false): the slave point at ({}, {}, {}) of body A projects outside every face of the master side (body B), which spans x ∈ [{}, {}], y ∈ [{}, {}], z ∈ [{}, {}]; the slave side must lie within the master side",
            x[0], x[1], x[2], lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]
        )
    }
}

/// The box of a face (module text of [`tree`]): its nodes and a 5 × 5
/// sample of its surface, padded by 5 % of its diagonal.
fn face_box(family: Family, x: &[[f64; 3]]) -> Aabb {
    let mut b = Aabb::EMPTY;
    for &p in x {
        b.grow(p);
    }
    for i in 0..=4 {
        for j in 0..=4 {
            let (u, v) = (i as f64 / 4.0, j as f64 / 4.0);
            let xi = match family {
                Family::Q8 => [2.0 * u - 1.0, 2.0 * v - 1.0],
                _ if u + v <= 1.0 => [u, v],
                _ => continue,
            };
            b.grow(closest::point_at(family, x, xi));
        }
    }
    b.padded(0.05 * b.diagonal())
}

/// The checks of a foot at `at` with normal `n` and gap `gap` of the slave
/// point `sp`: the sides face each other (A's outward normal makes more than
/// about 90° with n) and overlap by at most [`OVERLAP_LIMIT`] of the slave
/// face's size.
fn check(name: &str, sp: &SlavePoint, n: [f64; 3], at: [f64; 3], gap: f64) -> Result<(), String> {
    let x = sp.x;
    let facing = dot(sp.out, n);
    if facing > FACING_TOL {
        let deg = facing.clamp(-1.0, 1.0).acos().to_degrees();
        let o = sp.out;
        return Err(format!(
            "interface \"{name}\" (matching = false): at ({}, {}, {}) the two sides do not face each other: body A's outward normal ({:.3}, {:.3}, {:.3}) makes {deg:.1}° with body B's outward normal ({:.3}, {:.3}, {:.3}) at ({}, {}, {}), where facing sides make more than 90° (are upper and lower swapped?)",
            x[0], x[1], x[2], o[0], o[1], o[2], n[0], n[1], n[2], at[0], at[1], at[2]
        ));
    }
    if gap < -OVERLAP_LIMIT * sp.h {
        return Err(format!(
            "interface \"{name}\" (matching = false): at ({}, {}, {}) body A overlaps body B by {:.4e} mm, more than {OVERLAP_LIMIT} of the slave face's size ({:.4e} mm): the meshes overlap. An interference is a load: give the interface a negative `gap` (with a `gap_history` to press it in) on meshes that touch",
            x[0], x[1], x[2], -gap, sp.h
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests;
