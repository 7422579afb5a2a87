//! Concave fillets (issue 46): a quarter circle of radius r that rounds a
//! re-entrant corner of a body of several blocks, the corner where a bolt's
//! shank meets its head, adding the fillet's material to the body.
//!
//! A fillet is named at the end of a block's side where the block has the
//! corner C: `right = { fillet_top = r }` on the shank (its right side's top
//! end). Two legs leave C along the body's outline: leg A along the named
//! side (unit vector a, away from C), leg B along the block's other side at
//! C produced beyond the corner (unit vector b: the head's underside). The
//! empty quadrant {C + s a + t b : s, t > 0} lies between them; the body
//! fills the three others within r of C. The fillet is the circle of centre
//! O = C + r a + r b from P_A = C + r a to P_B = C + r b:
//! ```text
//!   arc(ψ) = O − r cos ψ · b − r sin ψ · a,   ψ ∈ [0, π/2]   (ψ = 0 at P_A)
//! ```
//! The blocks are meshed as they stand (the sharp corner), merged, and then
//! every node of the body within r of C is moved by one map F(p) = p + D(p)
//! of the plane: with s = (p − C)·a, t = (p − C)·b and the cutoff
//! χ(d) = max(0, 1 − d/r),
//! ```text
//!   leg A's side (s ≥ 0, t ≤ 0):  D = [arc(π/4 (1 − s/r)) − (C + s a)] χ(−t)   (s < r)
//!   leg B's side (t ≥ 0, s ≤ 0):  D = [arc(π/4 (1 + t/r)) − (C + t b)] χ(−s)   (t < r)
//!   opposite quadrant (s, t < 0):  D = [arc(π/4) − C] χ(|p − C|)
//! ```
//! and D = 0 elsewhere. The legs' points s ∈ [0, r] (t ∈ [0, r]) go onto the
//! arc at angles linear in s (t): C to the arc's middle, P_A and P_B stay. A
//! node's place is a function of its place alone, so nodes that two blocks
//! share move alike and the body stays one conforming mesh; the nodes of a
//! leg, midside nodes included, land on the circle (evenly spaced in angle
//! where the leg's segment is uniform, half the arc on each leg). F is
//! continuous, the identity beyond r, and its Jacobian stays positive (0.79
//! at its least, by central differences over the plane in all eight
//! orientations, `tests.rs`, which asserts 0.5): the three elements at the
//! corner node meet at the arc's middle with angles of about 58°, 64° and
//! 58° instead of 90°, 90°, 90° (a flare of one block's side to P_B would
//! meet the shared line tangentially there, a cusp).
//!
//! Checks (with the case, before a mesh is made; each names the block by
//! index, its side and key): the radius a positive length of at least 1e-9
//! of the block's size; not across the axis or a symmetry plane; a block of
//! the body beyond the corner (else there is no re-entrant corner); no
//! block in the empty quadrant within r (the fillet's material goes there);
//! the body's blocks covering the three other quadrants within r, with no
//! arc, rounding or chamfer of theirs there; P_A and P_B breakpoints of the
//! sides they lie on; two fillets of a body whose reaches (the squares of
//! half-side r about their corners) share no area.

use super::BlockSpec;
use crate::error::clip;
use crate::input::mesh::Mesh;
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_4;

/// A block's left or right side: concave fillets at its ends.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SideFillets {
    /// A concave fillet of this radius (mm) at the side's bottom end,
    /// between this side and the block's bottom produced beyond the corner.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fillet_bottom: Option<f64>,
    /// The same at the side's top end (a shank's right side under a head).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fillet_top: Option<f64>,
}

/// One concave fillet where the blocks put it (module text).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Fillet {
    /// The block that names it, its side and the key.
    pub block: usize,
    pub side: &'static str,
    pub key: &'static str,
    /// The radius, mm.
    pub r: f64,
    /// The corner C and the legs' unit vectors a (the named side) and b.
    pub c: [f64; 2],
    pub a: [f64; 2],
    pub b: [f64; 2],
}

/// A broken rule of a fillet: the block (index), side and key, and why.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FilletError {
    pub block: usize,
    pub side: &'static str,
    pub key: &'static str,
    pub message: String,
}

impl Fillet {
    /// C + s a + t b.
    fn at(&self, s: f64, t: f64) -> [f64; 2] {
        [
            self.c[0] + s * self.a[0] + t * self.b[0],
            self.c[1] + s * self.a[1] + t * self.b[1],
        ]
    }

    /// (s, t) of a point: its coordinates along a and b from C.
    fn local(&self, p: [f64; 2]) -> (f64, f64) {
        let d = [p[0] - self.c[0], p[1] - self.c[1]];
        (
            d[0] * self.a[0] + d[1] * self.a[1],
            d[0] * self.b[0] + d[1] * self.b[1],
        )
    }

    /// The arc's point at angle ψ from P_A (module text).
    pub(crate) fn arc(&self, psi: f64) -> [f64; 2] {
        let r = self.r;
        self.at(r - r * psi.sin(), r - r * psi.cos())
    }

    /// The circle's centre O.
    #[cfg(test)]
    fn center(&self) -> [f64; 2] {
        self.at(self.r, self.r)
    }

    /// The square [x₀, x₁, y₀, y₁] of the points C + s a + t b with s and t
    /// within the given ranges.
    fn square(&self, s: [f64; 2], t: [f64; 2]) -> [f64; 4] {
        let p = self.at(s[0], t[0]);
        let q = self.at(s[1], t[1]);
        [
            p[0].min(q[0]),
            p[0].max(q[0]),
            p[1].min(q[1]),
            p[1].max(q[1]),
        ]
    }

    /// Where the map F puts point p (module text); None where it leaves it.
    pub(crate) fn place(&self, p: [f64; 2]) -> Option<[f64; 2]> {
        let r = self.r;
        let tol = 1e-9 * r;
        let chi = |d: f64| (1.0 - d / r).max(0.0);
        let (s, t) = self.local(p);
        // a point of a leg's side: its foot on the leg, its distance from it
        let leg = |along: f64, off: f64, psi: f64, foot: [f64; 2]| {
            if along >= r || off >= r {
                return None;
            }
            let arc = self.arc(psi);
            if off <= tol {
                return Some(arc);
            }
            let w = chi(off);
            Some([p[0] + w * (arc[0] - foot[0]), p[1] + w * (arc[1] - foot[1])])
        };
        if s >= -tol && t <= tol {
            let s = s.max(0.0);
            return leg(s, -t, FRAC_PI_4 * (1.0 - s / r), self.at(s, 0.0));
        }
        if t >= -tol && s <= tol {
            let t = t.max(0.0);
            return leg(t, -s, FRAC_PI_4 * (1.0 + t / r), self.at(0.0, t));
        }
        if s < 0.0 && t < 0.0 {
            let d = s.hypot(t);
            if d >= r {
                return None;
            }
            let (m, w) = (self.arc(FRAC_PI_4), chi(d));
            return Some([p[0] + w * (m[0] - self.c[0]), p[1] + w * (m[1] - self.c[1])]);
        }
        // the empty quadrant holds no node of the body (checked)
        None
    }
}

/// The rectangle of a block, [x₀, x₁, y₀, y₁].
fn rect(b: &BlockSpec) -> [f64; 4] {
    [b.x[0], b.x[b.x.len() - 1], b.y[0], b.y[b.y.len() - 1]]
}

/// Breakpoints finite and strictly increasing, at least two (the blocks
/// whose are not are left to the generator's messages).
fn usable(v: &[f64]) -> bool {
    v.len() >= 2 && v.iter().all(|x| x.is_finite()) && v.windows(2).all(|w| w[1] > w[0])
}

/// The fillets the blocks name, in block order (bottom, top, left, right;
/// the left or bottom end first), with the value as given.
pub(crate) fn declared(blocks: &[BlockSpec]) -> Vec<Fillet> {
    let mut out = Vec::new();
    for (i, spec) in blocks.iter().enumerate() {
        if !(usable(&spec.x) && usable(&spec.y)) {
            continue;
        }
        let [x0, x1, y0, y1] = rect(spec);
        let ends = |side: &'static str| -> [(&'static str, Option<f64>); 2] {
            match side {
                "bottom" | "top" => {
                    let s = if side == "bottom" {
                        &spec.bottom
                    } else {
                        &spec.top
                    };
                    let s = s.as_ref();
                    [
                        ("fillet_left", s.and_then(|s| s.fillet_left)),
                        ("fillet_right", s.and_then(|s| s.fillet_right)),
                    ]
                }
                _ => {
                    let s = if side == "left" {
                        &spec.left
                    } else {
                        &spec.right
                    };
                    let s = s.as_ref();
                    [
                        ("fillet_bottom", s.and_then(|s| s.fillet_bottom)),
                        ("fillet_top", s.and_then(|s| s.fillet_top)),
                    ]
                }
            }
        };
        for side in ["bottom", "top", "left", "right"] {
            for (key, r) in ends(side) {
                let Some(r) = r else { continue };
                // the corner and the legs: a along the side, b along the
                // other side at the corner, produced beyond it
                let (c, a, b) = match (side, key) {
                    ("bottom", "fillet_left") => ([x0, y0], [1.0, 0.0], [0.0, -1.0]),
                    ("bottom", _) => ([x1, y0], [-1.0, 0.0], [0.0, -1.0]),
                    ("top", "fillet_left") => ([x0, y1], [1.0, 0.0], [0.0, 1.0]),
                    ("top", _) => ([x1, y1], [-1.0, 0.0], [0.0, 1.0]),
                    ("left", "fillet_bottom") => ([x0, y0], [0.0, 1.0], [-1.0, 0.0]),
                    ("left", _) => ([x0, y1], [0.0, -1.0], [-1.0, 0.0]),
                    ("right", "fillet_bottom") => ([x1, y0], [0.0, 1.0], [1.0, 0.0]),
                    _ => ([x1, y1], [0.0, -1.0], [1.0, 0.0]),
                };
                out.push(Fillet {
                    block: i,
                    side,
                    key,
                    r,
                    c,
                    a,
                    b,
                });
            }
        }
    }
    out
}

/// The blocks' fillets checked (module text): `axis` names what x = 0 is
/// when it is the axis of a model of revolution or a half model's symmetry
/// plane (no fillet may reach across it).
pub(crate) fn check(blocks: &[BlockSpec], axis: Option<&str>) -> Result<Vec<Fillet>, FilletError> {
    for (i, spec) in blocks.iter().enumerate() {
        for (side, s) in [("left", &spec.left), ("right", &spec.right)] {
            if s.as_ref()
                .is_some_and(|s| s.fillet_bottom.is_none() && s.fillet_top.is_none())
            {
                return Err(FilletError {
                    block: i,
                    side,
                    key: "fillet_top",
                    message: "missing: a left or right side takes fillet_bottom or fillet_top (a concave fillet's radius, mm); leave the table out for a straight side".into(),
                });
            }
        }
    }
    let fillets = declared(blocks);
    let usable_blocks: Vec<usize> = (0..blocks.len())
        .filter(|&k| usable(&blocks[k].x) && usable(&blocks[k].y))
        .collect();
    // the model's geometric tolerance, 1e-9 of its size
    let (lo, hi) = usable_blocks.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), &k| {
            let [x0, x1, y0, y1] = rect(&blocks[k]);
            (
                [lo[0].min(x0), lo[1].min(y0)],
                [hi[0].max(x1), hi[1].max(y1)],
            )
        },
    );
    let tol = 1e-9 * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    for (n, f) in fillets.iter().enumerate() {
        let err = |message: String| FilletError {
            block: f.block,
            side: f.side,
            key: f.key,
            message,
        };
        let spec = &blocks[f.block];
        let body: Vec<usize> = usable_blocks
            .iter()
            .copied()
            .filter(|&k| blocks[k].body == spec.body)
            .collect();
        check_radius(f, spec, axis, tol).map_err(err)?;
        check_quadrants(f, blocks, &body, &usable_blocks, tol).map_err(err)?;
        check_shaped(f, blocks, &body).map_err(err)?;
        check_ends(f, blocks, &body, tol).map_err(err)?;
        for g in &fillets[..n] {
            if blocks[g.block].body != spec.body {
                continue;
            }
            let reach = |h: &Fillet| [h.c[0] - h.r, h.c[0] + h.r, h.c[1] - h.r, h.c[1] + h.r];
            if super::common_area(reach(f), reach(g)).is_some() {
                return Err(err(format!(
                    "this fillet (corner ({}, {}), r = {} mm) and the fillet {}.{} of block \"{}\" (corner ({}, {}), r = {} mm) reach into each other: each moves the body's nodes within its radius of its corner; keep the corners at least the sum of the radii apart in x or y",
                    f.c[0], f.c[1], f.r, g.side, g.key, clip(blocks[g.block].name()), g.c[0], g.c[1], g.r
                )));
            }
        }
    }
    Ok(fillets)
}

/// The radius itself: a positive length, not below the model's tolerance,
/// and not across the axis.
fn check_radius(f: &Fillet, spec: &BlockSpec, axis: Option<&str>, tol: f64) -> Result<(), String> {
    let r = f.r;
    if !(r.is_finite() && r > 0.0) {
        return Err(format!("{r} must be a positive length in mm"));
    }
    let [x0, x1, y0, y1] = rect(spec);
    let size = (x1 - x0).hypot(y1 - y0);
    if r < super::shape::MIN_RELATIVE_CURVE * size {
        return Err(format!(
            "{r:e} mm is a sharp corner to round-off: less than {:e} of the block's size, below which the model cannot tell it from a corner; leave it out",
            super::shape::MIN_RELATIVE_CURVE
        ));
    }
    if let Some(on) = axis {
        if f.c[0].abs() <= tol {
            return Err(format!(
                "the corner ({}, {}) lies on {on}: the fillet would lie at x < 0, where there is no body; a fillet rounds a corner away from {on}",
                f.c[0], f.c[1]
            ));
        }
        if f.c[0] - r < -tol {
            return Err(format!(
                "the fillet reaches across {on}: its corner at x = {} is nearer to it than its radius {r} mm, and the fillet moves the body's nodes within r of the corner; make r at most {}",
                f.c[0], f.c[0]
            ));
        }
    }
    Ok(())
}

/// The quadrants around the corner: a block of the body beyond it, none in
/// the empty quadrant, the body's blocks covering the other three within r.
fn check_quadrants(
    f: &Fillet,
    blocks: &[BlockSpec],
    body: &[usize],
    all: &[usize],
    tol: f64,
) -> Result<(), String> {
    let r = f.r;
    let name = clip(blocks[f.block].name());
    let body_name = clip(&blocks[f.block].body);
    let (c0, c1) = (f.c[0], f.c[1]);
    let beyond = [
        f.square([-r, 0.0], [-r, 0.0]),
        f.square([-r, 0.0], [0.0, r]),
    ];
    let meets = body.iter().any(|&k| {
        k != f.block
            && beyond
                .iter()
                .any(|&q| super::common_area(rect(&blocks[k]), q).is_some())
    });
    if !meets {
        return Err(format!(
            "no other block of body \"{body_name}\" meets the corner ({c0}, {c1}) of \"{name}\": a concave fillet rounds the re-entrant corner where this side meets a block that continues past the corner (a shank's side under its head); a convex corner of the block is rounded with round_* or cut with chamfer_* on its bottom or top"
        ));
    }
    let empty = f.square([0.0, r], [0.0, r]);
    for &k in all {
        if super::common_area(rect(&blocks[k]), empty).is_some() {
            let other = &blocks[k];
            return Err(if other.body == blocks[f.block].body {
                format!(
                    "block \"{}\" of the body fills the quadrant x = {} … {}, y = {} … {} the fillet rounds: the corner ({c0}, {c1}) is not re-entrant there",
                    clip(other.name()), empty[0], empty[1], empty[2], empty[3]
                )
            } else {
                format!(
                    "the fillet's material (x = {} … {}, y = {} … {}) would overlap block \"{}\" of body \"{}\"; make the radius smaller or move the block",
                    empty[0], empty[1], empty[2], empty[3], clip(other.name()), clip(&other.body)
                )
            });
        }
    }
    let rects: Vec<[f64; 4]> = body.iter().map(|&k| rect(&blocks[k])).collect();
    for q in [
        f.square([0.0, r], [-r, 0.0]),
        f.square([-r, 0.0], [-r, 0.0]),
        f.square([-r, 0.0], [0.0, r]),
    ] {
        if let Some(p) = uncovered(&rects, q, tol) {
            return Err(format!(
                "the fillet is larger than the blocks around its corner ({c0}, {c1}): it moves the body's nodes within r = {r} mm of the corner, but the point ({}, {}) within r is in no block of body \"{body_name}\"; make the radius smaller, or the blocks reach at least r beyond the corner",
                p[0], p[1]
            ));
        }
    }
    Ok(())
}

/// A point of the square `q` in none of the rectangles (the centre of a
/// cell the rectangles' sides cut it into), if there is one.
fn uncovered(rects: &[[f64; 4]], q: [f64; 4], tol: f64) -> Option<[f64; 2]> {
    let cuts = |lo: f64, hi: f64, k: [usize; 2]| {
        let mut v = vec![lo, hi];
        for rc in rects {
            for &c in &[rc[k[0]], rc[k[1]]] {
                if c > lo + tol && c < hi - tol {
                    v.push(c);
                }
            }
        }
        v.sort_by(f64::total_cmp);
        v
    };
    let (xs, ys) = (cuts(q[0], q[1], [0, 1]), cuts(q[2], q[3], [2, 3]));
    for w in xs.windows(2).filter(|w| w[1] - w[0] > tol) {
        for v in ys.windows(2).filter(|v| v[1] - v[0] > tol) {
            let p = [0.5 * (w[0] + w[1]), 0.5 * (v[0] + v[1])];
            let inside =
                |rc: &[f64; 4]| p[0] >= rc[0] && p[0] <= rc[1] && p[1] >= rc[2] && p[1] <= rc[3];
            if !rects.iter().any(inside) {
                return Some(p);
            }
        }
    }
    None
}

/// No arc, rounding or chamfer of the body's blocks within r of the corner:
/// the map takes the blocks' sides there for straight.
fn check_shaped(f: &Fillet, blocks: &[BlockSpec], body: &[usize]) -> Result<(), String> {
    let r = f.r;
    let reach = [f.c[0] - r, f.c[0] + r, f.c[1] - r, f.c[1] + r];
    for &k in body {
        let b = &blocks[k];
        let ys = [b.y[0], b.y[b.y.len() - 1]];
        for (side, shape, bottom) in [("bottom", &b.bottom, true), ("top", &b.top, false)] {
            let Some(sh) = shape else { continue };
            if sh
                .cut_boxes(&b.x, ys, bottom)
                .into_iter()
                .any(|q| super::common_area(q, reach).is_some())
            {
                return Err(format!(
                    "the {side} of block \"{}\" is curved, rounded or cut within r = {r} mm of the fillet's corner ({}, {}): the fillet needs the sides around its corner straight; keep them apart",
                    clip(b.name()), f.c[0], f.c[1]
                ));
            }
        }
    }
    Ok(())
}

/// P_A and P_B, where the arc meets the straight sides, are breakpoints of
/// the block sides they lie on (so a node is there at every refinement).
fn check_ends(f: &Fillet, blocks: &[BlockSpec], body: &[usize], tol: f64) -> Result<(), String> {
    // (the leg's direction, the empty side's normal: the other leg's)
    for (d, n) in [(f.a, f.b), (f.b, f.a)] {
        let p = [f.c[0] + f.r * d[0], f.c[1] + f.r * d[1]];
        // the sides facing n on the leg's line: x = const when n is ±x
        let k_along = if n[0] != 0.0 { 1 } else { 0 };
        let k_across = 1 - k_along;
        let mut hosts = Vec::new();
        for &k in body {
            let b = &blocks[k];
            let [x0, x1, y0, y1] = rect(b);
            let (at, side) = match (k_across, n[k_across] > 0.0) {
                (0, true) => (x1, "right side"),
                (0, false) => (x0, "left side"),
                (_, true) => (y1, "top"),
                (_, false) => (y0, "bottom"),
            };
            let range = if k_along == 1 { [y0, y1] } else { [x0, x1] };
            let v = p[k_along];
            if (at - f.c[k_across]).abs() <= tol && v >= range[0] - tol && v <= range[1] + tol {
                hosts.push((k, side));
            }
        }
        let ok = hosts.iter().any(|&(k, _)| {
            let breaks = if k_along == 1 {
                &blocks[k].y
            } else {
                &blocks[k].x
            };
            breaks.iter().any(|&w| (w - p[k_along]).abs() <= tol)
        });
        if let (false, Some(&(k, side))) = (ok, hosts.first()) {
            let axis = ["x", "y"][k_along];
            return Err(format!(
                "the fillet ends at {axis} = {} on the {side} of block \"{}\", which has no breakpoint there: add {} to its {axis} (the arc's nodes are that side's nodes between the corner and the breakpoint)",
                p[k_along],
                clip(blocks[k].name()),
                p[k_along]
            ));
        }
    }
    Ok(())
}

/// Moves the nodes of each fillet's body by its map (module text). No
/// interface can use a node it moves: the fillet moves the body's outline
/// only on its two legs, and a body facing a leg would lie in the empty
/// quadrant, which [`check`] refuses.
pub(crate) fn apply(mesh: &mut Mesh, fillets: &[Fillet], blocks: &[BlockSpec]) {
    for f in fillets {
        let Some(nodes) = mesh.node_sets.get(&format!("{}.all", blocks[f.block].body)) else {
            continue;
        };
        let moved: Vec<(usize, [f64; 2])> = nodes
            .iter()
            .filter_map(|&n| {
                let x = mesh.nodes[n];
                f.place([x[0], x[1]]).map(|q| (n, q))
            })
            .collect();
        for (n, q) in moved {
            mesh.nodes[n] = [q[0], q[1], 0.0];
        }
    }
}

#[cfg(test)]
mod tests;
