//! Node-to-segment springs of a non-matching interface (small sliding): each
//! slave spring point projected once onto the closest master quadratic edge.

use super::*;
/// The spring points of a non-matching interface (node-to-segment, small
/// sliding): the slave side's quadrature points (its nodes with tributary
/// areas for lumped weights, 4-point Gauss per slave edge for consistent
/// ones, as on a matching interface) each projected once onto the closest
/// master edge ([`project`]). One pair per point, for the per-point outputs.
/// An error names the interface, the point and the master side's extent if a
/// point projects outside every master edge.
pub(super) fn node_to_segment(
    mesh: &Mesh,
    name: &str,
    nm: &crate::input::mesh::NonMatching,
    weights: Weights,
    section: crate::physics::element::Section,
) -> Result<(Vec<Pair>, Vec<Point>), String> {
    let coords = |e: &[usize; 3]| -> [[f64; 2]; 3] { std::array::from_fn(|i| mesh.xy(e[i])) };
    let slave = slave_points(nm, weights, section, &coords);
    let masters: Vec<[[f64; 2]; 3]> = nm.master.iter().map(coords).collect();
    let ends = ends(&nm.master, &masters);
    let mut pairs = Vec::with_capacity(slave.len());
    let mut points = Vec::with_capacity(slave.len());
    for SlavePoint {
        a,
        na,
        len_a,
        x,
        area,
        s,
        out,
        h,
    } in slave
    {
        let Foot { k, xi, n, gap } = foot(name, &masters, &ends, x, out, h)?;
        let nb = crate::physics::element::edge::shape(xi);
        let b = nm.master[k];
        let near = |nodes: &[usize], vals: &[f64]| {
            let i = (0..vals.len())
                .max_by(|&i, &j| vals[i].abs().total_cmp(&vals[j].abs()))
                .unwrap_or(0);
            nodes[i]
        };
        let normal = [n[0], n[1], 0.0];
        pairs.push(Pair {
            a: near(&a[..len_a], &na[..len_a]),
            b: near(&b, &nb),
            x: [x[0], x[1], 0.0],
            normal,
            area,
            spring: Some(points.len()),
        });
        points.push(Point {
            area,
            normal,
            tangent: [n[1], -n[0], 0.0],
            coupling: Coupling::NodeToSegment {
                pair: pairs.len() - 1,
                segment: Segment {
                    a: side(&a[..len_a]),
                    na: side(&na[..len_a]),
                    len_a,
                    b: side(&b),
                    nb: side(&nb),
                    len_b: 3,
                    gap,
                    s,
                },
            },
        });
    }
    Ok((pairs, points))
}

/// A spring point of the slave side: where it sits, the slave nodes it
/// interpolates, the area it stands for, its arc length and outward normal.
struct SlavePoint {
    a: [usize; 3],
    na: [f64; 3],
    len_a: usize,
    x: [f64; 2],
    area: f64,
    s: f64,
    /// A's outward normal at the point (A lies left of the slave walk).
    out: [f64; 2],
    /// Length of the slave edge the point lies on, mm.
    h: f64,
}

/// The slave side's spring points: at each slave node with Simpson's
/// weights (lumped: a node on two edges gathers from both), or at 4 Gauss
/// points per edge (consistent).
fn slave_points(
    nm: &crate::input::mesh::NonMatching,
    weights: Weights,
    section: crate::physics::element::Section,
    coords: &dyn Fn(&[usize; 3]) -> [[f64; 2]; 3],
) -> Vec<SlavePoint> {
    let mut slave: Vec<SlavePoint> = Vec::new();
    let mut s0 = 0.0;
    let mut node_point = std::collections::HashMap::new();
    for e in &nm.slave {
        let xs = coords(e);
        let half = [
            super::arcs::piece_length(&xs, -1.0, 0.0),
            super::arcs::piece_length(&xs, -1.0, 1.0),
        ];
        match weights {
            Weights::Lumped => {
                for (i, &xi) in [-1.0, 0.0, 1.0].iter().enumerate() {
                    let (nl, ds) = edge_normal(&xs, xi);
                    let w = [1.0 / 3.0, 4.0 / 3.0, 1.0 / 3.0][i] * ds * section.measure(xs[i]);
                    let s = s0 + [0.0, half[0], half[1]][i];
                    let k = *node_point.entry(e[i]).or_insert_with(|| {
                        slave.push(SlavePoint {
                            a: [e[i]; 3],
                            na: [1.0, 0.0, 0.0],
                            len_a: 1,
                            x: xs[i],
                            area: 0.0,
                            s,
                            out: [-nl[0], -nl[1]],
                            h: half[1],
                        });
                        slave.len() - 1
                    });
                    slave[k].area += w;
                }
            }
            // (a mortar interface is built by `mortar`, not here)
            Weights::Consistent | Weights::Mortar => {
                for (xi, wg) in gauss4() {
                    let (nl, ds) = edge_normal(&xs, xi);
                    let shape = crate::physics::element::edge::shape(xi);
                    let x = [0, 1].map(|c| (0..3).map(|k| shape[k] * xs[k][c]).sum::<f64>());
                    let s = s0 + super::arcs::piece_length(&xs, -1.0, xi);
                    slave.push(SlavePoint {
                        a: *e,
                        na: shape,
                        len_a: 3,
                        x,
                        area: wg * ds * section.measure(x),
                        s,
                        out: [-nl[0], -nl[1]],
                        h: half[1],
                    });
                }
            }
        }
        s0 += half[1];
    }
    slave
}

/// The springs of a mortar non-matching interface (`weights = "mortar"`,
/// see [`Mortar`]): one per slave node, its approach and slip the slave
/// side's averaged with the node's shape function. Each slave edge is cut
/// where the master side's corner nodes project onto it; each piece gets
/// 4-point Gauss, each Gauss point its closest master point (with the checks
/// of [`foot`]). One pair per spring (the slave node and the master node
/// that weighs most in its coupling), for the per-point outputs. A slave
/// node on the axis in axisymmetry (its ring has no area; ∫ N_i 2π r ds is
/// 0 on a straight edge and a small number of either sign on a curved one)
/// hands its weight function to the edge's other nodes in proportion to
/// their areas (the weights still sum to 1, so the patch test holds) and
/// carries no spring.
pub(super) fn mortar(
    mesh: &Mesh,
    name: &str,
    nm: &crate::input::mesh::NonMatching,
    section: crate::physics::element::Section,
) -> Result<(Vec<Pair>, Vec<Point>), String> {
    let coords = |e: &[usize; 3]| -> [[f64; 2]; 3] { std::array::from_fn(|i| mesh.xy(e[i])) };
    let masters: Vec<[[f64; 2]; 3]> = nm.master.iter().map(coords).collect();
    let ends = ends(&nm.master, &masters);
    let corners: Vec<[f64; 2]> = masters.iter().flat_map(|xe| [xe[0], xe[2]]).collect();
    let mut acc: Vec<MortarSum> = Vec::new();
    let mut index: std::collections::HashMap<usize, usize> = Default::default();
    let mut s0 = 0.0;
    for e in &nm.slave {
        let xs = coords(e);
        let half = [
            super::arcs::piece_length(&xs, -1.0, 0.0),
            super::arcs::piece_length(&xs, -1.0, 1.0),
        ];
        let ids: [usize; 3] = std::array::from_fn(|i| {
            *index.entry(e[i]).or_insert_with(|| {
                acc.push(MortarSum {
                    node: e[i],
                    x: xs[i],
                    s: s0 + [0.0, half[0], half[1]][i],
                    ..Default::default()
                });
                acc.len() - 1
            })
        });
        s0 += half[1];
        // an edge along the axis has no area: nothing to average over
        let Some(handed) = AxisWeights::of(section, &xs) else {
            continue;
        };
        for w in pieces(&xs, &corners).windows(2) {
            let (lo, hi) = (w[0], w[1]);
            for (g, wg) in gauss4() {
                let xi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * g;
                let (nl, ds) = edge_normal(&xs, xi);
                let shape = crate::physics::element::edge::shape(xi);
                let x = point_on(&xs, xi);
                let wq = 0.5 * (hi - lo) * wg * ds * section.measure(x);
                let f = foot(name, &masters, &ends, x, [-nl[0], -nl[1]], half[1])?;
                let weight = handed.apply(&shape);
                let sides = [
                    (*e, shape, -1.0),
                    (
                        nm.master[f.k],
                        crate::physics::element::edge::shape(f.xi),
                        1.0,
                    ),
                ];
                for i in 0..3 {
                    acc[ids[i]].add(wq, weight[i], x, &f, &sides);
                }
            }
        }
    }
    let slave_nodes: std::collections::HashSet<usize> = index.keys().copied().collect();
    let mut pairs = Vec::with_capacity(acc.len());
    let mut points = Vec::with_capacity(acc.len());
    let largest = acc.iter().fold(0.0f64, |m, a| m.max(a.area));
    for a in acc {
        // a corner node on the axis in axisymmetry (∫ N_i 2π r ds = 0: its
        // weight went to its edge's other nodes) carries no spring
        if a.area.abs() <= 1e-12 * largest {
            continue;
        }
        if a.area.is_nan() || a.area < 0.0 {
            return Err(format!(
                "interface \"{name}\" (weights = \"mortar\"): the slave node at ({}, {}) has a negative area ∫ N dA = {}",
                a.x[0], a.x[1], a.area
            ));
        }
        let (pair, point) = a.spring(&slave_nodes, points.len());
        pairs.push(pair);
        points.push(point);
    }
    Ok((pairs, points))
}

/// What a mortar spring gathers over the slave edges its node is on.
#[derive(Default)]
struct MortarSum {
    node: usize,
    x: [f64; 2],
    s: f64,
    area: f64,
    /// ∫ N_i r dA: the moment arm of the spring's force, times its area
    moment: f64,
    gap: f64,
    normal: [f64; 2],
    /// node → (∂u_N/∂u, ∂u_T/∂u, ∂h/∂u), before the division by the area
    coef: std::collections::BTreeMap<usize, ([f64; 2], [f64; 2], f64)>,
}

impl MortarSum {
    /// One Gauss point of weight `wq` and this node's weight function
    /// `weight` there, at x with its foot `f` on the master side; `sides`:
    /// the slave edge's and the master edge's nodes and shape values, −1
    /// and +1.
    fn add(
        &mut self,
        wq: f64,
        weight: f64,
        x: [f64; 2],
        f: &Foot,
        sides: &[([usize; 3], [f64; 3], f64); 2],
    ) {
        let (n, t) = (f.n, [f.n[1], -f.n[0]]);
        let wi = wq * weight;
        self.area += wi;
        self.moment += wi * x[0];
        self.gap += wi * f.gap;
        let wn = wq * weight.abs();
        self.normal = [self.normal[0] + wn * n[0], self.normal[1] + wn * n[1]];
        for (nodes, vals, sign) in sides {
            for j in 0..3 {
                let c = sign * wi * vals[j];
                let d = self.coef.entry(nodes[j]).or_default();
                d.0 = [d.0[0] + c * n[0], d.0[1] + c * n[1]];
                d.1 = [d.1[0] + c * t[0], d.1[1] + c * t[1]];
                d.2 += c;
            }
        }
    }

    /// Its spring (point `index`) and the pair that stands for it: the slave
    /// node and the master node (not one of `slave_nodes`) that weighs most
    /// in its approach.
    fn spring(self, slave_nodes: &std::collections::HashSet<usize>, index: usize) -> (Pair, Point) {
        let l = self.normal[0].hypot(self.normal[1]);
        let normal = [self.normal[0] / l, self.normal[1] / l, 0.0];
        let inv = 1.0 / self.area;
        let nodes: Vec<usize> = self.coef.keys().copied().collect();
        let dn: Vec<[f64; 2]> = self.coef.values().map(|c| c.0.map(|v| v * inv)).collect();
        let dt: Vec<[f64; 2]> = self.coef.values().map(|c| c.1.map(|v| v * inv)).collect();
        let dh: Vec<f64> = self.coef.values().map(|c| c.2 * inv).collect();
        let b = nodes
            .iter()
            .zip(&dn)
            .filter(|(k, _)| !slave_nodes.contains(k))
            .max_by(|p, q| p.1[0].hypot(p.1[1]).total_cmp(&q.1[0].hypot(q.1[1])))
            .map_or(self.node, |(&k, _)| k);
        let pair = Pair {
            a: self.node,
            b,
            x: [self.x[0], self.x[1], 0.0],
            normal,
            area: self.area,
            spring: Some(index),
        };
        let mortar = Mortar {
            nodes,
            dn,
            dt,
            dh,
            gap: self.gap / self.area,
            s: self.s,
            radius: self.moment / self.area,
        };
        let point = Point {
            area: self.area,
            normal,
            tangent: [normal[1], -normal[0], 0.0],
            coupling: Coupling::Mortar {
                pair: index,
                mortar: std::sync::Arc::new(mortar),
            },
        };
        (pair, point)
    }
}

/// The weight functions of a slave edge's nodes: their shape functions N_k,
/// but a node on the axis in axisymmetry hands its N to the others in
/// proportion to their areas ∫ N_k 2π r ds: still Σ = 1, so the patch test
/// holds, and no spring divides by its area. That area is 0 only on a
/// straight edge with its midside node in the middle; on a curved one (a
/// sphere's meridian) ds/dξ varies and it is O((h/R)²) of the edge's area,
/// of either sign (−6.7e-8 of it on an R = 50 mm sphere with 0.1 mm edges):
/// not round-off, so the node is recognised by its position ([`on_axis`]),
/// not by the sign of its area.
struct AxisWeights {
    own: [f64; 3],
    void: Vec<usize>,
    live: f64,
}

impl AxisWeights {
    /// None for an edge whose three nodes are on the axis.
    fn of(section: crate::physics::element::Section, xs: &[[f64; 2]; 3]) -> Option<AxisWeights> {
        let mut own = [0.0f64; 3];
        for (xi, wg) in gauss4() {
            let sh = crate::physics::element::edge::shape(xi);
            let wq = wg * edge_normal(xs, xi).1 * section.measure(point_on(xs, xi));
            for k in 0..3 {
                own[k] += wq * sh[k];
            }
        }
        let void: Vec<usize> = (0..3).filter(|&k| on_axis(section, xs, k)).collect();
        if void.len() == 3 {
            return None;
        }
        let live: f64 = (0..3).filter(|k| !void.contains(k)).map(|k| own[k]).sum();
        Some(AxisWeights { own, void, live })
    }

    fn apply(&self, sh: &[f64; 3]) -> [f64; 3] {
        let handed: f64 = self.void.iter().map(|&k| sh[k]).sum();
        std::array::from_fn(|k| {
            if self.void.contains(&k) {
                0.0
            } else {
                sh[k] + handed * self.own[k] / self.live
            }
        })
    }
}

/// The pieces of a slave edge: cut where a master corner projects inside it.
fn pieces(xs: &[[f64; 2]; 3], corners: &[[f64; 2]]) -> Vec<f64> {
    let mut cuts = vec![-1.0, 1.0];
    cuts.extend(
        corners
            .iter()
            .filter_map(|&c| project(xs, c))
            .filter(|xi| xi.abs() < 1.0 - 1e-9),
    );
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    cuts
}

/// Is node `k` of the slave edge `xs` on the axis of an axisymmetric model
/// (|r| within 1e-9 of the edge's chord)? Its ring has no area: it hands its
/// mortar weight function to the edge's other nodes ([`mortar`]).
fn on_axis(section: crate::physics::element::Section, xs: &[[f64; 2]; 3], k: usize) -> bool {
    let chord = (xs[2][0] - xs[0][0]).hypot(xs[2][1] - xs[0][1]);
    section.axisymmetric && xs[k][0].abs() <= 1e-9 * chord
}

/// Where a slave point meets the master side: the master edge `k`, the
/// parameter ξ of the closest point on it, the master normal there and the
/// geometric gap (x − x_B(ξ))·n.
#[derive(Debug)]
struct Foot {
    k: usize,
    xi: f64,
    n: [f64; 2],
    gap: f64,
}

/// An end node of the master side's edges: a corner node where two or more
/// edges meet, or one of the side's two free ends. The quadratic edges of a
/// curve meet at a corner at a small kink (on a convex side the points in
/// the wedge between the two end normals project onto neither edge); such a
/// node is a slave point's closest master point for the whole wedge. A
/// point closest to a free end lies beyond the master side.
struct End {
    /// The lowest-numbered master edge ending at the node and the end's ξ
    /// (±1): the one edge a foot at the node belongs to.
    k: usize,
    xi: f64,
    x: [f64; 2],
    /// The mean of the end normals of the edges meeting there.
    n: [f64; 2],
    /// The edges that end there, with the end's ξ; two or more at a corner,
    /// one at a free end.
    meet: Vec<(usize, f64)>,
}

/// The end nodes of the master side's edges (`edges` their node ids,
/// `masters` their coordinates), by node id.
fn ends(edges: &[[usize; 3]], masters: &[[[f64; 2]; 3]]) -> Vec<End> {
    let mut at: std::collections::BTreeMap<usize, Vec<(usize, f64)>> = Default::default();
    for (k, e) in edges.iter().enumerate() {
        at.entry(e[0]).or_default().push((k, -1.0));
        at.entry(e[2]).or_default().push((k, 1.0));
    }
    at.into_values()
        .map(|meet| {
            let (k, xi) = meet[0];
            let mut n = [0.0; 2];
            for &(j, s) in &meet {
                let nj = edge_normal(&masters[j], s).0;
                n = [n[0] + nj[0], n[1] + nj[1]];
            }
            let l = n[0].hypot(n[1]);
            let n = if l > 1e-6 {
                [n[0] / l, n[1] / l]
            } else {
                edge_normal(&masters[k], xi).0
            };
            End {
                k,
                xi,
                x: point_on(&masters[k], xi),
                n,
                meet,
            }
        })
        .collect()
}

/// Projects the slave point `x` (body A's outward normal `out`, on a slave
/// edge of length `h`) onto the closest point of the master side and checks
/// the geometry there: the point projects inside the master side, the sides
/// face each other, and they overlap by at most [`OVERLAP_LIMIT`] × h.
/// The closest point is the closest foot inside a master edge
/// ([`project`]), unless an edge's end node ([`ends`]) is closer by more
/// than round-off (1e-9 h): a point in the wedge between the end normals of
/// two edges that meet at a kink projects onto neither, and its foot is
/// their corner node. So is a foot within round-off of a corner node
/// (|ξ| ≥ 1 − 1e-9), whichever of the two edges found it. A foot at a
/// corner belongs to the node's lowest-numbered edge, at its end, with the
/// normal along the direction from the node to the point (the gradient of
/// the distance, continuous with the end normals at the wedge's sides; the
/// mean of the end normals for a point on the node). A point closest to one
/// of the side's free ends lies beyond the master side and is refused.
fn foot(
    name: &str,
    masters: &[[[f64; 2]; 3]],
    ends: &[End],
    x: [f64; 2],
    out: [f64; 2],
    h: f64,
) -> Result<Foot, String> {
    let dist = |p: [f64; 2]| (p[0] - x[0]).hypot(p[1] - x[1]);
    let mut inside = masters
        .iter()
        .enumerate()
        .filter_map(|(k, xe)| project(xe, x).map(|xi| (k, xi, dist(point_on(xe, xi)))))
        .min_by(|p, q| p.2.total_cmp(&q.2));
    let corner = |e: &End| e.meet.len() > 1;
    let end = ends
        .iter()
        .map(|e| (e, dist(e.x)))
        .min_by(|p, q| p.1.total_cmp(&q.1))
        .filter(|&(_, d)| inside.is_none_or(|f| d + 1e-9 * h < f.2))
        .or_else(|| {
            // a foot at an edge's end within round-off is at the corner node
            // there: the same foot whichever edge's projection found it
            let (k, xi, _) = inside?;
            let e = (xi.abs() >= 1.0 - XI_TOL)
                .then(|| ends.iter().find(|e| e.meet.contains(&(k, xi.signum()))))??;
            corner(e).then(|| (e, dist(e.x)))
        });
    match end {
        Some((e, d)) if corner(e) => {
            let v = [x[0] - e.x[0], x[1] - e.x[1]];
            let n = if d > 1e-9 * h {
                // oriented as the end normals: a point inside body B has a
                // negative gap along it
                let s = if v[0] * e.n[0] + v[1] * e.n[1] < 0.0 {
                    -1.0
                } else {
                    1.0
                };
                [s * v[0] / d, s * v[1] / d]
            } else {
                e.n
            };
            return check(name, masters, e.k, e.xi, n, x, out, h);
        }
        // beyond a free end of the master side
        Some(_) => inside = None,
        None => {}
    }
    let Some((k, xi, _)) = inside else {
        let ends = masters.iter().flat_map(|xe| [xe[0], xe[2]]);
        let (lo, hi) = ends.fold(
            ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
            |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1])],
                    [hi[0].max(p[0]), hi[1].max(p[1])],
                )
            },
        );
        return Err(format!(
            "interface \"{name}\" (matching = false): the slave point at ({}, {}) of body A projects outside every edge of the master side (body B), which spans x ∈ [{}, {}], y ∈ [{}, {}]; the slave side must lie within the master side",
            x[0], x[1], lo[0], hi[0], lo[1], hi[1]
        ));
    };
    let n = edge_normal(&masters[k], xi).0;
    check(name, masters, k, xi, n, x, out, h)
}

/// The foot at ξ on master edge `k` with normal `n` of the slave point `x`
/// ([`foot`]), if the sides face each other there and overlap by at most
/// [`OVERLAP_LIMIT`] × h.
#[allow(clippy::too_many_arguments)] // the foot and the slave point's data, as `foot` has them
fn check(
    name: &str,
    masters: &[[[f64; 2]; 3]],
    k: usize,
    xi: f64,
    n: [f64; 2],
    x: [f64; 2],
    out: [f64; 2],
    h: f64,
) -> Result<Foot, String> {
    let xb = point_on(&masters[k], xi);
    let gap = (x[0] - xb[0]) * n[0] + (x[1] - xb[1]) * n[1];
    let facing = out[0] * n[0] + out[1] * n[1];
    if facing > FACING_TOL {
        let deg = facing.clamp(-1.0, 1.0).acos().to_degrees();
        return Err(format!(
            "interface \"{name}\" (matching = false): at ({}, {}) the two sides do not face each other: body A's outward normal ({:.3}, {:.3}) makes {deg:.1}° with body B's outward normal ({:.3}, {:.3}) at ({}, {}), where facing sides make more than 90° (are upper and lower, or the curves, swapped?)",
            x[0], x[1], out[0], out[1], n[0], n[1], xb[0], xb[1]
        ));
    }
    if gap < -OVERLAP_LIMIT * h {
        return Err(format!(
            "interface \"{name}\" (matching = false): at ({}, {}) body A overlaps body B by {:.4e} mm, more than {OVERLAP_LIMIT} of the slave edge's length ({h:.4e} mm): the meshes overlap. An interference is a load: give the interface a negative `gap` (with a `gap_history` to press it in) on meshes that touch",
            x[0], x[1], -gap
        ));
    }
    Ok(Foot { k, xi, n, gap })
}

/// A slave point whose outward normal has a positive component larger than
/// this along the master's outward normal faces away from the master side
/// (the angle between the two is below 90°, about 89.9° at the limit; the
/// end of a quarter-circle rounding sits at exactly 90°).
pub(super) const FACING_TOL: f64 = 1e-3;

/// The largest initial overlap of the two sides at a spring point, as a
/// fraction of the slave edge's length: more is two meshes that overlap,
/// not curves meshed apart (quadratic edges of one circle meshed twice
/// differ by far less).
pub const OVERLAP_LIMIT: f64 = 0.01;

/// x(ξ) on a quadratic edge.
fn point_on(xe: &[[f64; 2]; 3], xi: f64) -> [f64; 2] {
    let n = crate::physics::element::edge::shape(xi);
    [0, 1].map(|c| (0..3).map(|k| n[k] * xe[k][c]).sum())
}

/// Tolerance on ξ for a projection at an edge's end (shared by two edges).
const XI_TOL: f64 = 1e-9;

/// The closest point of the quadratic edge `xe` to `x`: ξ ∈ [−1, 1] where
/// f(ξ) = (x(ξ) − x)·x'(ξ) = 0, by Newton from ξ = 0
/// (f' = x'·x' + (x(ξ) − x)·x''); `None` if the foot lies beyond the edge's
/// ends (|ξ| > 1 + 1e-9). If Newton does not converge, bisection on f over
/// [−1, 1] when f changes sign there, else `None`.
pub fn project(xe: &[[f64; 2]; 3], x: [f64; 2]) -> Option<f64> {
    let f = |xi: f64| {
        let p = point_on(xe, xi);
        let dn = [xi - 0.5, -2.0 * xi, xi + 0.5];
        let d = [0, 1].map(|c| (0..3).map(|k| dn[k] * xe[k][c]).sum::<f64>());
        let dd = [0, 1].map(|c| xe[0][c] - 2.0 * xe[1][c] + xe[2][c]);
        let r = [p[0] - x[0], p[1] - x[1]];
        (
            r[0] * d[0] + r[1] * d[1],
            d[0] * d[0] + d[1] * d[1] + r[0] * dd[0] + r[1] * dd[1],
        )
    };
    let mut xi = 0.0f64;
    for _ in 0..50 {
        let (v, dv) = f(xi);
        if dv <= 0.0 || !dv.is_finite() {
            break;
        }
        let step = v / dv;
        xi = (xi - step).clamp(-3.0, 3.0);
        if step.abs() < 1e-14 {
            return (xi.abs() <= 1.0 + XI_TOL).then(|| xi.clamp(-1.0, 1.0));
        }
    }
    // fallback: bisection on f over [−1, 1]
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    if !(f(lo).0 <= 0.0 && f(hi).0 >= 0.0) {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid).0 < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A node-to-segment point's coupling.
    fn segment_of(p: &Point) -> Segment {
        match &p.coupling {
            Coupling::NodeToSegment { segment, .. } => *segment,
            c => panic!("not a node-to-segment point: {c:?}"),
        }
    }

    /// A slave edge along y = `ys` from x = 0 to 2 (walked toward `dir`)
    /// over a master edge along y = 0 from −1 to 3, walked in +x (B below).
    fn springs(ys: f64, dir: f64) -> Result<(Vec<Pair>, Vec<Point>), String> {
        let xs = if dir > 0.0 {
            [0.0, 1.0, 2.0]
        } else {
            [2.0, 1.0, 0.0]
        };
        let mesh = Mesh {
            nodes: vec![
                [xs[0], ys, 0.0],
                [xs[1], ys, 0.0],
                [xs[2], ys, 0.0],
                [-1.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [3.0, 0.0, 0.0],
            ],
            ..Default::default()
        };
        let nm = crate::input::mesh::NonMatching {
            slave: vec![[0, 1, 2]],
            master: vec![[3, 4, 5]],
        };
        let section = crate::physics::element::Section {
            axisymmetric: false,
            thickness: 1.0,
        };
        node_to_segment(&mesh, "c", &nm, Weights::Consistent, section)
    }

    #[test]
    fn gaps_come_from_the_geometry_and_overlap_and_facing_away_are_refused() {
        let (_, points) = springs(0.3, 1.0).unwrap();
        for p in &points {
            let g = segment_of(p);
            assert!((g.gap - 0.3).abs() < 1e-14, "{}", g.gap);
            assert_eq!(p.normal, [0.0, 1.0, 0.0]);
        }
        // an overlap up to 1 % of the slave edge (2 mm) is geometry round-off
        assert!(springs(-0.019, 1.0).is_ok());
        let e = springs(-0.05, 1.0).unwrap_err();
        assert!(
            e.contains("interface \"c\"")
                && e.contains("overlaps body B by 5.0000e-2 mm")
                && e.contains("negative `gap`"),
            "{e}"
        );
        // the slave side walked the other way has body A below it: it faces
        // away from B's top
        let e = springs(0.3, -1.0).unwrap_err();
        assert!(
            e.contains("do not face each other") && e.contains("makes 0.0°"),
            "{e}"
        );
    }

    /// The top of a foundation with `round_right = 2.0` on two edges
    /// (the red team's case c21): a straight edge to (18, 0), then a quarter
    /// circle about (18, −2) down to (20, −2) meshed as two quadratic edges
    /// meeting at 45°, walked in +x; the slave side a flat edge along y = 0
    /// from x = 18.5 to 20 (lumped: its nodes are the spring points).
    fn rounded(slave_end: f64) -> Result<(Vec<Pair>, Vec<Point>), String> {
        let arc = |deg: f64| {
            let t = deg.to_radians();
            [18.0 + 2.0 * t.cos(), -2.0 + 2.0 * t.sin(), 0.0]
        };
        let mesh = Mesh {
            nodes: vec![
                [18.5, 0.0, 0.0],
                [0.5 * (18.5 + slave_end), 0.0, 0.0],
                [slave_end, 0.0, 0.0],
                [16.0, 0.0, 0.0],
                [17.0, 0.0, 0.0],
                arc(90.0),
                arc(67.5),
                arc(45.0),
                arc(22.5),
                arc(0.0),
            ],
            ..Default::default()
        };
        let nm = crate::input::mesh::NonMatching {
            slave: vec![[0, 1, 2]],
            master: vec![[3, 4, 5], [5, 6, 7], [7, 8, 9]],
        };
        let section = crate::physics::element::Section {
            axisymmetric: false,
            thickness: 1.0,
        };
        node_to_segment(&mesh, "c", &nm, Weights::Lumped, section)
    }

    #[test]
    fn a_point_in_the_wedge_of_a_kink_between_two_master_edges_takes_their_node() {
        // (20, 0) lies on the 45° ray through the node between the two arc
        // edges; the quadratic edges meet there at a kink and the point
        // projects onto neither (ξ = ±1.0105): it was refused as "outside
        // every edge of the master side"
        let arc = |xe: &[[f64; 2]; 3], xi| point_on(xe, xi);
        let r2 = std::f64::consts::FRAC_1_SQRT_2;
        let node = [18.0 + 2.0 * r2, -2.0 + 2.0 * r2];
        let (_, points) = rounded(20.0).expect("the corner is inside the master side");
        let p = &points[2];
        let g = segment_of(p);
        // the node's lower-numbered edge, at its end ξ = 1, normal along
        // the 45° ray, gap the distance to the node
        assert_eq!(g.b[..g.len_b], [5, 6, 7]);
        assert_eq!(g.nb[..g.len_b], [0.0, 0.0, 1.0]);
        assert!((p.normal[0] - r2).abs() < 1e-12 && (p.normal[1] - r2).abs() < 1e-12);
        let d = (20.0 - node[0]).hypot(node[1]);
        assert!((g.gap - d).abs() < 1e-12, "gap {} vs {d}", g.gap);
        // across the wedge: accepted by the same edge, the normal turning
        // continuously from one edge's end normal to the other's
        let masters = [
            [[16.0, 0.0], [17.0, 0.0], [18.0, 0.0]],
            [
                [18.0, 0.0],
                [
                    18.0 + 2.0 * 67.5f64.to_radians().cos(),
                    -2.0 + 2.0 * 67.5f64.to_radians().sin(),
                ],
                node,
            ],
            [
                node,
                [
                    18.0 + 2.0 * 22.5f64.to_radians().cos(),
                    -2.0 + 2.0 * 22.5f64.to_radians().sin(),
                ],
                [20.0, -2.0],
            ],
        ];
        let ends = ends(&[[3, 4, 5], [5, 6, 7], [7, 8, 9]], &masters);
        assert_eq!(ends.iter().filter(|e| e.meet.len() > 1).count(), 2);
        let (n1, n2) = (
            edge_normal(&masters[1], 1.0).0,
            edge_normal(&masters[2], -1.0).0,
        );
        let (a1, a2) = (n1[1].atan2(n1[0]), n2[1].atan2(n2[0]));
        assert!(a1 - a2 > 0.01, "a kink of {} rad", a1 - a2);
        for i in 0..=20 {
            let a = a2 + (a1 - a2) * i as f64 / 20.0;
            let x = [node[0] + 0.5 * a.cos(), node[1] + 0.5 * a.sin()];
            let f = foot("c", &masters, &ends, x, [0.0, -1.0], 0.75).unwrap();
            let on = arc(&masters[f.k], f.xi);
            assert!((on[0] - node[0]).abs() < 1e-12 && (on[1] - node[1]).abs() < 1e-12);
            let fa = f.n[1].atan2(f.n[0]);
            assert!((fa - a).abs() < 1e-9, "{i}: normal at {fa} rad, ray at {a}");
            assert!((f.gap - 0.5).abs() < 1e-12, "{i}: gap {}", f.gap);
        }
        // a point on the node: the feet of both edges, the first one
        let f = foot("c", &masters, &ends, node, [0.0, -1.0], 0.75).unwrap();
        assert_eq!((f.k, f.xi), (1, 1.0));
        assert!(f.gap.abs() < 1e-12);
        // beyond the master side's free end (20, −2): no edge takes it and
        // its closest master point is that end (1.12 mm; the corner at 45°
        // is 2.65 mm away, the one at (18, 0) 3.9 mm): still outside
        let e = foot("c", &masters, &ends, [20.5, -3.0], [-r2, r2], 0.75).unwrap_err();
        assert!(e.contains("projects outside every edge"), "{e}");
        // a slave side reaching past x = 20 at y = 0 still lies over the arc
        assert!(rounded(20.4).is_ok());
    }

    #[test]
    fn projection_finds_the_closest_point_of_a_curved_edge_and_refuses_beyond_its_ends() {
        // a bowed edge: x(ξ) = (2ξ, 0.3(1 − ξ²))
        let xe = [[-2.0, 0.0], [0.0, 0.3], [2.0, 0.0]];
        for x in [[0.7, 1.0], [-1.3, -0.4], [1.9, 0.2], [0.0, 0.3]] {
            let xi = project(&xe, x).expect("the foot lies on the edge");
            let p = point_on(&xe, xi);
            let d = [2.0, -0.6 * xi];
            let f = (p[0] - x[0]) * d[0] + (p[1] - x[1]) * d[1];
            assert!(f.abs() < 1e-12, "{x:?}: ξ = {xi}, f = {f}");
            // closer than any other point of the edge
            for k in 0..=200 {
                let q = point_on(&xe, -1.0 + 0.01 * k as f64);
                let dq = (q[0] - x[0]).hypot(q[1] - x[1]);
                assert!((p[0] - x[0]).hypot(p[1] - x[1]) <= dq + 1e-12);
            }
        }
        assert_eq!(project(&xe, [2.5, 0.0]), None);
        assert_eq!(project(&xe, [-2.4, -0.1]), None);
        // an end shared with the next edge is inside (both edges find it)
        assert_eq!(project(&xe, [2.0, 0.0]), Some(1.0));
    }
}
