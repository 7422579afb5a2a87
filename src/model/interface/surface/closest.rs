//! The closest point of one quadratic face (an 8-node quadrilateral or a
//! 6-node triangle) to a point in space, in the face's natural coordinates.
//!
//! ```text
//!   x(ξ) = Σ_a N_a(ξ) x_a,   r(ξ) = x(ξ) − p
//!   g = Jᵀ r = 0,            J = [∂x/∂ξ  ∂x/∂η]            (3 × 2)
//!   H = JᵀJ + Σ_c r_c ∂²x_c/∂ξ∂ξ                            (2 × 2)
//!   ξ ← ξ − H⁻¹ g            (Newton; Gauss-Newton, H = JᵀJ, where H is not positive definite)
//! ```
//!
//! from the face's centre; the root is the closest point when it lies in the
//! face (within [`XI_TOL`]): on [−1, 1]² for a quadrilateral, on ξ, η ≥ 0,
//! ξ + η ≤ 1 for a triangle. Otherwise the closest point of the face lies
//! on its boundary: the closest point of each of its quadratic edges
//! (Newton on f(s) = r(s)·x'(s), s ∈ [−1, 1], and the two ends), the nearest
//! of them. The face's shape functions restricted to an edge are the edge's
//! N(s) = (s(s−1)/2, 1 − s², s(s+1)/2) in both families, so a point of an
//! edge is the face's at ξ(s) = ((1 − s)/2) ξ_a + ((1 + s)/2) ξ_b between the
//! edge's corners.

use crate::input::mesh::Family;
use crate::model::interface::MAX_SIDE;
use crate::numbers::vec3::{dot, sub};

/// Tolerance in natural coordinates on a foot at a face's boundary: a
/// projection this far beyond it lies in the face (shared by its
/// neighbour, or a slave side flush with the master side's end).
pub(super) const XI_TOL: f64 = 1e-9;

/// Where the closest point of a face lies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum On {
    /// Inside the face (within [`XI_TOL`] of it).
    Inside,
    /// On the face's edge `edge` (index into `Family::edges`), strictly
    /// between its corners.
    Edge(usize),
    /// On the face's corner node `corner` (local index).
    Corner(usize),
}

/// The closest point of a face to a point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Closest {
    /// Natural coordinates of the closest point (in the face).
    pub xi: [f64; 2],
    /// The closest point x(ξ).
    pub at: [f64; 3],
    /// Its squared distance from the point.
    pub d2: f64,
    pub on: On,
}

/// The point of the face with node coordinates `x` at ξ.
pub(crate) fn point_at(family: Family, x: &[[f64; 3]], xi: [f64; 2]) -> [f64; 3] {
    let n = family.shape(xi);
    std::array::from_fn(|c| x.iter().enumerate().map(|(a, xa)| n[a] * xa[c]).sum())
}

/// The second derivatives (∂²N/∂ξ², ∂²N/∂ξ∂η, ∂²N/∂η²) of the shape
/// functions at ξ: of the serendipity quadrilateral's (ZTZ eq. 6.14-6.15,
/// differentiated twice; `q8` module text) and of the quadratic triangle's
/// (constant: N = L(2L − 1) and 4 L_i L_j, ZTZ eq. 6.27).
pub(crate) fn shape_second(family: Family, [xi, eta]: [f64; 2]) -> [[f64; 3]; MAX_SIDE] {
    let mut d = [[0.0; 3]; MAX_SIDE];
    match family {
        Family::Q8 => {
            for (a, &[xa, ya]) in crate::physics::element::q8::NODE_XI.iter().enumerate() {
                d[a] = if a < 4 {
                    [
                        0.5 * (1.0 + eta * ya),
                        0.25 * xa * ya * (2.0 * xi * xa + 2.0 * eta * ya + 1.0),
                        0.5 * (1.0 + xi * xa),
                    ]
                } else if xa == 0.0 {
                    [-(1.0 + eta * ya), -xi * ya, 0.0]
                } else {
                    [0.0, -eta * xa, -(1.0 + xi * xa)]
                };
            }
        }
        _ => {
            d[..6].copy_from_slice(&[
                [4.0, 4.0, 4.0],
                [4.0, 0.0, 0.0],
                [0.0, 0.0, 4.0],
                [-8.0, -4.0, 0.0],
                [0.0, 4.0, 0.0],
                [0.0, -4.0, -8.0],
            ]);
        }
    }
    d
}

/// Is ξ in the reference face, within `tol`?
fn inside(family: Family, [xi, eta]: [f64; 2], tol: f64) -> bool {
    match family {
        Family::Q8 => xi.abs() <= 1.0 + tol && eta.abs() <= 1.0 + tol,
        _ => xi >= -tol && eta >= -tol && xi + eta <= 1.0 + tol,
    }
}

/// ξ moved onto the reference face (a point within [`XI_TOL`] of it).
fn onto(family: Family, [xi, eta]: [f64; 2]) -> [f64; 2] {
    match family {
        Family::Q8 => [xi.clamp(-1.0, 1.0), eta.clamp(-1.0, 1.0)],
        _ => {
            let (a, b) = (xi.max(0.0), eta.max(0.0));
            let over = (a + b - 1.0).max(0.0);
            [a - 0.5 * over, b - 0.5 * over]
        }
    }
}

/// The stationary point of the distance from `p` on the face's surface
/// (module text), if Newton converges to one (|Δξ| < 1e-14).
pub(crate) fn project(family: Family, x: &[[f64; 3]], p: [f64; 3]) -> Option<[f64; 2]> {
    let mut xi = family.centre_xi();
    for _ in 0..60 {
        let (n, d, dd) = (
            family.shape(xi),
            family.shape_derivs(xi),
            shape_second(family, xi),
        );
        let (mut r, mut j, mut h2) = ([0.0; 3], [[0.0; 3]; 2], [[0.0; 3]; 3]);
        for (a, xa) in x.iter().enumerate() {
            for c in 0..3 {
                r[c] += n[a] * xa[c];
                j[0][c] += d[a][0] * xa[c];
                j[1][c] += d[a][1] * xa[c];
                for k in 0..3 {
                    h2[k][c] += dd[a][k] * xa[c];
                }
            }
        }
        let r = sub(r, p);
        let g = [dot(j[0], r), dot(j[1], r)];
        let gn = [dot(j[0], j[0]), dot(j[0], j[1]), dot(j[1], j[1])];
        let curv = [dot(h2[0], r), dot(h2[1], r), dot(h2[2], r)];
        let full = [gn[0] + curv[0], gn[1] + curv[1], gn[2] + curv[2]];
        let det = |h: [f64; 3]| h[0] * h[2] - h[1] * h[1];
        let h = if full[0] > 0.0 && det(full) > 0.0 {
            full
        } else {
            gn
        };
        let dh = det(h);
        if dh.is_nan() || dh <= 0.0 || !dh.is_finite() {
            return None;
        }
        let step = [
            (h[2] * g[0] - h[1] * g[1]) / dh,
            (h[0] * g[1] - h[1] * g[0]) / dh,
        ];
        xi = [
            (xi[0] - step[0]).clamp(-3.0, 3.0),
            (xi[1] - step[1]).clamp(-3.0, 3.0),
        ];
        if step[0].abs().max(step[1].abs()) < 1e-14 {
            return Some(xi);
        }
    }
    None
}

/// The closest point of the quadratic edge through `e` (end, mid, end) to
/// `p`: its parameter s ∈ [−1, 1] (the interior root of f(s) = r·x' by
/// Newton from 0 when it is closer than the ends) and squared distance.
fn on_edge(e: [[f64; 3]; 3], p: [f64; 3]) -> (f64, f64) {
    let at = |s: f64| -> [f64; 3] {
        let n = crate::physics::element::edge::shape(s);
        std::array::from_fn(|c| n[0] * e[0][c] + n[1] * e[1][c] + n[2] * e[2][c])
    };
    let d2 = |s: f64| {
        let r = sub(at(s), p);
        dot(r, r)
    };
    let mut best = [-1.0, 1.0]
        .into_iter()
        .map(|s| (s, d2(s)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((-1.0, f64::INFINITY));
    let dd: [f64; 3] = std::array::from_fn(|c| e[0][c] - 2.0 * e[1][c] + e[2][c]);
    let mut s = 0.0f64;
    for _ in 0..50 {
        let dn = [s - 0.5, -2.0 * s, s + 0.5];
        let d: [f64; 3] =
            std::array::from_fn(|c| dn[0] * e[0][c] + dn[1] * e[1][c] + dn[2] * e[2][c]);
        let r = sub(at(s), p);
        let (f, df) = (dot(r, d), dot(d, d) + dot(r, dd));
        if df.is_nan() || df <= 0.0 {
            break;
        }
        let step = f / df;
        s = (s - step).clamp(-3.0, 3.0);
        if step.abs() < 1e-14 {
            if s.abs() < 1.0 {
                let q = d2(s);
                if q < best.1 {
                    best = (s, q);
                }
            }
            break;
        }
    }
    best
}

/// The closest point of the face with node coordinates `x` to `p` (module
/// text).
pub(crate) fn closest(family: Family, x: &[[f64; 3]], p: [f64; 3]) -> Closest {
    if let Some(xi) = project(family, x, p).filter(|&xi| inside(family, xi, XI_TOL)) {
        let xi = onto(family, xi);
        let at = point_at(family, x, xi);
        let r = sub(at, p);
        return Closest {
            xi,
            at,
            d2: dot(r, r),
            on: On::Inside,
        };
    }
    let nodes = family.node_xi();
    let mut best: Option<Closest> = None;
    for (k, &[a, m, b]) in family.edges().iter().enumerate() {
        let (s, d2) = on_edge([x[a], x[m], x[b]], p);
        if best.is_some_and(|c| c.d2 <= d2) {
            continue;
        }
        let (u, v) = (0.5 * (1.0 - s), 0.5 * (1.0 + s));
        let xi = [
            u * nodes[a][0] + v * nodes[b][0],
            u * nodes[a][1] + v * nodes[b][1],
        ];
        let on = if s == -1.0 {
            On::Corner(a)
        } else if s == 1.0 {
            On::Corner(b)
        } else {
            On::Edge(k)
        };
        best = Some(Closest {
            xi,
            at: point_at(family, x, xi),
            d2,
            on,
        });
    }
    best.expect("a face has edges")
}
