//! Cyclic symmetry of a 3D model (`[model] cyclic`,
//! [`crate::input::case::cyclic`]): the mesh is one of N equal sectors of a
//! part about the y axis (the axis `[mesh] revolve` sweeps about and
//! `[speed]` spins about), loaded alike in every sector. Its two cut faces
//! are tied by rotational periodicity: every node s of the second face is
//! the image of a node m of the first rotated by the sector's angle α =
//! ±360°/N, and its displacement is the rotated displacement of m,
//!
//! ```text
//!   u_s = R(α) u_m,   R(α) = ⎡cos α  0  −sin α⎤   (the sweep's sense: (r, y, 0)
//!                            ⎢  0    1     0  ⎥    goes to (r cos α, y, r sin α))
//!                            ⎣sin α  0   cos α⎦
//! ```
//!
//! three linear constraints per node pair, each with up to three master
//! terms (a row of R), eliminated as every constraint of the model
//! ([`crate::model::constraint`]; the principle of repeatability of
//! Zienkiewicz & Scott, Int. J. Numer. Methods Eng. 4, 1972: the
//! displacements of corresponding nodes on the two cuts related by the
//! rotation). The rigid rotation about the axis
//! satisfies every tie (R commutes with it), so a cyclic sector is held by
//! its ties against the translations across the axis and the rotations
//! about axes across it, but not against the rotation about the y axis
//! nor the translation along it: the supports hold those.
//!
//! **The axis.** A node on the axis (r = 0) is its own image: u = R u,
//! whose only solutions for α ≠ 0 (N ≥ 2) have u_x = u_z = 0; those two are
//! prescribed 0 there (as the axis of an axisymmetric model), u_y stays
//! free. A `[[boundary]]` may give ux = 0 or uz = 0 there, not another
//! value.
//!
//! **Supports on the faces.** A cut face lies inside the part, so a
//! support holding a whole face (a symmetry plane) is refused. A support
//! on some nodes of the first face carries over to their images through
//! the ties (the part held alike in every sector). A prescribed dof of the
//! second face is kept only where the supports hold its partner alike
//! (its tie is then the supports' own: a clamped end, an end held
//! axially), and is refused otherwise: a slave dof takes no second value.

use crate::error::{clip, Error, Result};
use crate::input::case::Case;
use crate::input::mesh::Mesh;
use crate::model::constraint::Constraint;
use std::collections::HashMap;

/// Partners are sought within this fraction of the model's size (the
/// diagonal of its bounding box).
pub const PARTNER_TOLERANCE: f64 = 1e-6;

/// A cyclic sector's ties, as the model keeps them.
#[derive(Clone, Debug)]
pub struct Cyclic {
    /// N: the part's sectors.
    pub sectors: usize,
    /// The angle (rad) that takes the first face onto the second about the
    /// y axis, in the sweep's sense: 2π/N or −2π/N.
    pub angle: f64,
    /// The two faces' node sets, as the case names them.
    pub faces: [String; 2],
    /// (node of the first face, its image on the second), in the second
    /// face's set order.
    pub pairs: Vec<(usize, usize)>,
    /// The faces' nodes on the axis (r = 0): u_x = u_z = 0 prescribed.
    pub axis: Vec<usize>,
    /// Tie rows the supports hold themselves (both ends prescribed alike),
    /// left out of the constraints.
    pub held_alike: usize,
}

impl Cyclic {
    /// The sector's angle in degrees, signed as [`Cyclic::angle`]: ±360/N.
    pub fn degrees(&self) -> f64 {
        self.angle.signum() * 360.0 / self.sectors as f64
    }
}

/// R(θ): the rotation by θ about the y axis in the sweep's sense, its
/// entries below 1e-15 in magnitude made 0 (cos 90° is 6e-17).
pub fn rotation(theta: f64) -> [[f64; 3]; 3] {
    let snap = |v: f64| if v.abs() < 1e-15 { 0.0 } else { v };
    let (s, c) = theta.sin_cos();
    let (s, c) = (snap(s), snap(c));
    [[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]]
}

fn apply(r: &[[f64; 3]; 3], x: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|k| r[i][k] * x[k]).sum())
}

/// The diagonal of the mesh's bounding box (mm).
fn size(mesh: &Mesh) -> f64 {
    let (lo, hi) = mesh.nodes.iter().fold(
        ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
        |(lo, hi), x| {
            (
                std::array::from_fn(|c| lo[c].min(x[c])),
                std::array::from_fn(|c| hi[c].max(x[c])),
            )
        },
    );
    (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt()
}

/// The node's distance from the y axis.
fn radius(x: [f64; 3]) -> f64 {
    x[0].hypot(x[2])
}

fn at_key(place: &str, key: &str) -> String {
    format!("{place}: [model] cyclic {key}")
}

/// The case's cyclic sector on its mesh (None: the case has none): the
/// faces' nodes, each node of the second paired with the node of the first
/// it is the image of, the nodes on the axis. Refused: an unknown face set,
/// a face with no node off the axis, a node off the axis on both faces, a
/// sector whose angle is not 360°/N, a node without a partner of its body
/// within [`PARTNER_TOLERANCE`] of the model's size; and a support or a load
/// on a cut face (`check_faces_free`).
pub(crate) fn build(case: &Case, mesh: &Mesh, place: &str) -> Result<Option<Cyclic>> {
    let Some(spec) = &case.model.cyclic else {
        return Ok(None);
    };
    let faces = [spec.faces[0].clone(), spec.faces[1].clone()];
    let mut sets: [&[usize]; 2] = [&[], &[]];
    for (k, name) in faces.iter().enumerate() {
        sets[k] = mesh.node_sets.get(name).ok_or_else(|| {
            Error::input(
                at_key(place, "faces"),
                format!(
                    "no node set \"{}\" (sets: {})",
                    clip(name),
                    crate::model::loads::names(mesh.node_sets.keys())
                ),
            )
        })?;
    }
    let size = size(mesh);
    let on_axis = |n: usize| radius(mesh.nodes[n]) <= 1e-9 * size;
    let mut axis: Vec<usize> = sets.iter().flat_map(|s| s.iter().copied()).collect();
    axis.retain(|&n| on_axis(n));
    axis.sort_unstable();
    axis.dedup();
    let off: [Vec<usize>; 2] = sets.map(|s| s.iter().copied().filter(|&n| !on_axis(n)).collect());
    for (k, nodes) in off.iter().enumerate() {
        if nodes.is_empty() {
            return Err(Error::input(
                at_key(place, "faces"),
                format!(
                    "\"{}\" has no node off the y axis: a cut face of a sector reaches out from the axis",
                    clip(&faces[k])
                ),
            ));
        }
    }
    if let Some(&n) = off[1].iter().find(|n| off[0].contains(n)) {
        return Err(Error::input(
            at_key(place, "faces"),
            format!(
                "node {n} at {} lies on both faces \"{}\" and \"{}\" off the y axis: the second face is the first rotated by 360°/N, they meet on the axis only",
                crate::model::loads::point(mesh.nodes[n], true),
                clip(&faces[0]),
                clip(&faces[1])
            ),
        ));
    }
    let tol = PARTNER_TOLERANCE * size;
    let alpha = std::f64::consts::TAU / spec.sectors as f64;
    let grid = Grid::new(mesh, &off[0], tol);
    let body = mesh.node_bodies();
    // the sense in which the first face turns onto the second
    let tries = [alpha, -alpha].map(|a| partners(mesh, &grid, &body, &off[1], a, tol));
    let Some(k) = (0..2).find(|&k| tries[k].iter().all(Option::is_some)) else {
        let best = usize::from(count(&tries[1]) > count(&tries[0]));
        let a = [alpha, -alpha][best];
        return Err(unmatched(
            mesh,
            &faces,
            &off,
            &tries[best],
            spec.sectors,
            a,
            tol,
            place,
        ));
    };
    let angle = [alpha, -alpha][k];
    let pairs: Vec<(usize, usize)> = (off[1].iter())
        .zip(&tries[k])
        .map(|(&s, m)| (m.unwrap_or(s), s))
        .collect();
    check_pairs(mesh, &faces, &off, &pairs, angle, tol, place)?;
    let c = Cyclic {
        sectors: spec.sectors,
        angle,
        faces,
        pairs,
        axis,
        held_alike: 0,
    };
    check_faces_free(&c, case, mesh, place)?;
    Ok(Some(c))
}

fn count(found: &[Option<usize>]) -> usize {
    found.iter().filter(|m| m.is_some()).count()
}

/// For each node of `second`, the node of the first face (in `grid`) of
/// its body within `tol` of its image rotated back by `angle`, the nearest
/// (a sector's body turns onto itself in the next sector; two bodies may
/// have nodes at one place).
fn partners(
    mesh: &Mesh,
    grid: &Grid,
    body: &[usize],
    second: &[usize],
    angle: f64,
    tol: f64,
) -> Vec<Option<usize>> {
    let back = rotation(-angle);
    second
        .iter()
        .map(|&s| {
            let within = |m: usize| body[m] == body[s];
            grid.nearest(mesh, apply(&back, mesh.nodes[s]), tol, within)
        })
        .collect()
}

/// Every node of the first face is the partner of exactly one node of the
/// second (the faces are images, not one a part of the other).
fn check_pairs(
    mesh: &Mesh,
    faces: &[String; 2],
    off: &[Vec<usize>; 2],
    pairs: &[(usize, usize)],
    angle: f64,
    tol: f64,
    place: &str,
) -> Result<()> {
    let tol_mm = crate::numbers::num(tol);
    let mut taken: HashMap<usize, usize> = HashMap::new();
    for &(m, s) in pairs {
        if let Some(&other) = taken.get(&m) {
            return Err(Error::input(
                at_key(place, "faces"),
                format!(
                    "nodes {other} and {s} of \"{}\" are both the image of node {m} at {} of \"{}\": two nodes of the second face at one place (within {tol_mm} mm)",
                    clip(&faces[1]),
                    crate::model::loads::point(mesh.nodes[m], true),
                    clip(&faces[0])
                ),
            ));
        }
        taken.insert(m, s);
    }
    if let Some(&m) = off[0].iter().find(|m| !taken.contains_key(m)) {
        let image = apply(&rotation(angle), mesh.nodes[m]);
        return Err(Error::input(
            at_key(place, "faces"),
            format!(
                "node {m} at {} of \"{}\" has no image on \"{}\" (no node within {tol_mm} mm of {}, the node rotated by {}° about the y axis): every node of one cut face has its partner on the other",
                crate::model::loads::point(mesh.nodes[m], true),
                clip(&faces[0]),
                clip(&faces[1]),
                crate::model::loads::point(image.map(round), true),
                crate::numbers::num(angle.to_degrees())
            ),
        ));
    }
    Ok(())
}

/// A coordinate for a message: 9 significant digits.
fn round(v: f64) -> f64 {
    if v.abs() < 1e-100 {
        return 0.0;
    }
    let e = 10f64.powi(8 - v.abs().log10().floor() as i32);
    (v * e).round() / e
}

/// The refusal of faces some of whose nodes have no partner at ±360°/N:
/// the sector's angle is another (the faces' farthest nodes from the axis
/// tell it), or the angle is right and a node is off.
#[allow(clippy::too_many_arguments)]
fn unmatched(
    mesh: &Mesh,
    faces: &[String; 2],
    off: &[Vec<usize>; 2],
    found: &[Option<usize>],
    sectors: usize,
    angle: f64,
    tol: f64,
    place: &str,
) -> Error {
    let theta = |nodes: &[usize]| {
        let far = (nodes.iter()).copied().fold(nodes[0], |a, n| {
            if radius(mesh.nodes[n]) > radius(mesh.nodes[a]) {
                n
            } else {
                a
            }
        });
        let x = mesh.nodes[far];
        (x[2].atan2(x[0]), radius(x))
    };
    let ((t0, r0), (t1, _)) = (theta(&off[0]), theta(&off[1]));
    let mut apart = (t1 - t0).abs();
    if apart > std::f64::consts::PI {
        apart = std::f64::consts::TAU - apart;
    }
    let want = std::f64::consts::TAU / sectors as f64;
    if (apart - want).abs() * r0 > tol {
        let deg = apart.to_degrees();
        let n = 360.0 / deg;
        let advice = if (n - n.round()).abs() < 1e-6 && n.round() >= 2.0 {
            format!("give sectors = {}", n.round())
        } else {
            format!(
                "{}° does not divide 360°: no whole number of such sectors makes the part",
                crate::numbers::num(round(deg))
            )
        };
        return Error::input(
            at_key(place, "sectors"),
            format!(
                "is {sectors} (sectors of {}°), but the faces \"{}\" and \"{}\" are {}° apart about the y axis (from the mesh: their nodes farthest from the axis); {advice}",
                crate::numbers::num(round(want.to_degrees())),
                clip(&faces[0]),
                clip(&faces[1]),
                crate::numbers::num(round(deg))
            ),
        );
    }
    let tol_mm = crate::numbers::num(tol);
    let k = found.iter().position(Option::is_none).unwrap_or(0);
    let s = off[1][k];
    let image = apply(&rotation(-angle), mesh.nodes[s]);
    Error::input(
        at_key(place, "faces"),
        format!(
            "node {s} at {} of \"{}\" has no partner on \"{}\": no node within {tol_mm} mm of {}, the node rotated back by {}° about the y axis (every node of one cut face has its partner on the other)",
            crate::model::loads::point(mesh.nodes[s], true),
            clip(&faces[1]),
            clip(&faces[0]),
            crate::model::loads::point(image.map(round), true),
            crate::numbers::num(round(angle.to_degrees()))
        ),
    )
}

/// The nodes of a face hashed into cubes of side 2 tol: a point's
/// neighbours within tol lie in its cube or the 26 around it.
struct Grid {
    cell: f64,
    cubes: HashMap<[i64; 3], Vec<usize>>,
}

impl Grid {
    fn new(mesh: &Mesh, nodes: &[usize], tol: f64) -> Grid {
        let cell = 2.0 * tol.max(f64::MIN_POSITIVE);
        let mut cubes: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for &n in nodes {
            cubes.entry(cube(mesh.nodes[n], cell)).or_default().push(n);
        }
        Grid { cell, cubes }
    }

    /// The node nearest to `x` within `tol` that `take` takes (the lowest
    /// index among equals).
    fn nearest(
        &self,
        mesh: &Mesh,
        x: [f64; 3],
        tol: f64,
        take: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        let c = cube(x, self.cell);
        let mut best: Option<(f64, usize)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let key = [c[0] + dx, c[1] + dy, c[2] + dz];
                    for &n in self
                        .cubes
                        .get(&key)
                        .into_iter()
                        .flatten()
                        .filter(|&&n| take(n))
                    {
                        let p = mesh.nodes[n];
                        let d = (0..3).map(|k| (p[k] - x[k]).powi(2)).sum::<f64>().sqrt();
                        if d <= tol && best.is_none_or(|(bd, bn)| (d, n) < (bd, bn)) {
                            best = Some((d, n));
                        }
                    }
                }
            }
        }
        best.map(|b| b.1)
    }
}

fn cube(x: [f64; 3], cell: f64) -> [i64; 3] {
    x.map(|v| (v / cell).floor() as i64)
}

/// The prescribed dofs with u_x = u_z = 0 added at every node of the faces
/// on the axis (sorted by dof); a non-zero prescribed value there is
/// refused, naming its `[[boundary]]` entry.
pub(crate) fn hold_axis(
    cyclic: Option<&Cyclic>,
    case: &Case,
    mesh: &Mesh,
    mut prescribed: Vec<(usize, f64)>,
    place: &str,
) -> Result<Vec<(usize, f64)>> {
    let Some(c) = cyclic else {
        return Ok(prescribed);
    };
    let given: HashMap<usize, f64> = prescribed.iter().copied().collect();
    for &n in &c.axis {
        for comp in [0, 2] {
            let d = mesh.node_dofs.dof(n, comp);
            match given.get(&d) {
                None => prescribed.push((d, 0.0)),
                Some(&v) if v != 0.0 => {
                    let (at, _) = entry_at(case, mesh, n, comp, place);
                    return Err(Error::input(
                        at,
                        format!(
                            "gives u{} = {v} to node {n} at {} on the y axis of a cyclic sector: a node on the axis is its own image, u = R(360°/N) u, so its u_x and u_z are 0 (prescribed there automatically; give 0 or nothing)",
                            ["x", "y", "z"][comp],
                            crate::model::loads::point(mesh.nodes[n], true)
                        ),
                    ));
                }
                Some(_) => {}
            }
        }
    }
    prescribed.sort_by_key(|&(d, _)| d);
    Ok(prescribed)
}

/// Where a message names the support of node n's component `comp`: the
/// first `[[boundary]]` entry that selects it (its place and index).
fn entry_at(case: &Case, mesh: &Mesh, n: usize, comp: usize, place: &str) -> (String, usize) {
    let x = mesh.nodes[n];
    let found = case
        .boundary
        .iter()
        .enumerate()
        .find(|(_, bc)| [bc.ux, bc.uy, bc.uz][comp].is_some() && selects(bc, mesh, n, x));
    let axis = ["x", "y", "z"][comp];
    match found {
        Some((i, bc)) => (
            format!("{place}: boundary[{i}] (set \"{}\") u{axis}", clip(&bc.set)),
            i,
        ),
        None => (format!("{place}: [[boundary]] u{axis}"), usize::MAX),
    }
}

/// Whether `[[boundary]]` entry `bc` selects node n at x (its set and ranges).
fn selects(bc: &crate::input::case::BoundarySpec, mesh: &Mesh, n: usize, x: [f64; 3]) -> bool {
    in_ranges(bc, x) && mesh.node_sets.get(&bc.set).is_some_and(|s| s.contains(&n))
}

/// Whether x passes the ranges of `[[boundary]]` entry `bc`.
fn in_ranges(bc: &crate::input::case::BoundarySpec, x: [f64; 3]) -> bool {
    let ranges = [&bc.x_range, &bc.y_range, &bc.z_range];
    (0..3).all(|c| crate::model::loads::in_range(x[c], ranges[c]))
}

/// A support on a whole cut face (a symmetry plane) and a load on a cut
/// face are refused: the cut lies inside the part.
fn check_faces_free(c: &Cyclic, case: &Case, mesh: &Mesh, place: &str) -> Result<()> {
    let mut on: [Vec<bool>; 2] = [vec![false; mesh.nodes.len()], vec![false; mesh.nodes.len()]];
    for &(m, s) in &c.pairs {
        on[0][m] = true;
        on[1][s] = true;
    }
    let faces: [Vec<usize>; 2] = [
        c.pairs.iter().map(|p| p.0).collect(),
        c.pairs.iter().map(|p| p.1).collect(),
    ];
    for (i, bc) in case.boundary.iter().enumerate() {
        let Some(set) = mesh.node_sets.get(&bc.set) else {
            continue;
        };
        let mut held = vec![false; mesh.nodes.len()];
        for &n in set.iter().filter(|&&n| in_ranges(bc, mesh.nodes[n])) {
            held[n] = true;
        }
        for (k, face) in faces.iter().enumerate() {
            if face.iter().all(|&n| held[n]) {
                return Err(Error::input(
                    format!("{place}: boundary[{i}] (set \"{}\")", clip(&bc.set)),
                    format!(
                        "holds every node of the cyclic face \"{}\": a cut face of a cyclic sector lies inside the part, where the ties carry its forces on to the next sector; a support there (a symmetry plane) conflicts with the ties and takes what they carry (a torque); remove it, and hold the part elsewhere (an end; one node's hoop displacement against the rotation about the axis)",
                        clip(&c.faces[k])
                    ),
                ));
            }
        }
    }
    for (i, ld) in case.load.iter().enumerate() {
        let Some(name) = &ld.faces else { continue };
        let ranges = [&ld.x_range, &ld.y_range, &ld.z_range];
        for f in mesh.face_sets.get(name).into_iter().flatten() {
            let nodes = f.nodes();
            let k = nodes.len() as f64;
            let centre: [f64; 3] =
                std::array::from_fn(|c| nodes.iter().map(|&n| mesh.nodes[n][c]).sum::<f64>() / k);
            if !(0..3).all(|c| crate::model::loads::in_range(centre[c], ranges[c])) {
                continue;
            }
            let cut = (0..2).find(|&k| {
                nodes
                    .iter()
                    .all(|&n| on[k][n] || c.axis.binary_search(&n).is_ok())
            });
            if let Some(k) = cut {
                return Err(Error::input(
                    format!("{place}: load[{i}] (faces \"{}\")", clip(name)),
                    format!(
                        "loads a face on the cyclic face \"{}\" (centre {}): a cut face of a cyclic sector lies inside the part, not on its surface; load a surface of the part",
                        clip(&c.faces[k]),
                        crate::model::loads::point(centre.map(round), true)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The ties u_s = R u_m of every pair, one per component of the second
/// face's node. A component the supports prescribe there is left out when
/// they hold its partner alike (every master term prescribed on the same
/// history, Σ R v_m = v_s), and refused otherwise. Returns the ties and
/// how many were left out.
pub(crate) fn ties(
    c: &Cyclic,
    case: &Case,
    mesh: &Mesh,
    prescribed: &[(usize, f64)],
    histories: &[Option<usize>],
    place: &str,
) -> Result<(Vec<Constraint>, usize)> {
    let given: HashMap<usize, (f64, Option<usize>)> = prescribed
        .iter()
        .zip(histories)
        .map(|(&(d, v), &h)| (d, (v, h)))
        .collect();
    let r = rotation(c.angle);
    let nd = mesh.node_dofs;
    let (mut out, mut alike) = (Vec::new(), 0);
    for &(m, s) in &c.pairs {
        for (j, row) in r.iter().enumerate() {
            let terms: Vec<(usize, f64)> = (0..3)
                .filter(|&k| row[k] != 0.0)
                .map(|k| (nd.dof(m, k), row[k]))
                .collect();
            let slave = nd.dof(s, j);
            let Some(&(v, h)) = given.get(&slave) else {
                out.push(Constraint {
                    slave,
                    terms,
                    offset: 0.0,
                    history: None,
                    origin: format!("cyclic tie of node {s} to node {m}"),
                });
                continue;
            };
            if !held_alike(&terms, v, h, &given) {
                return Err(conflict(c, case, mesh, (m, s), j, place));
            }
            alike += 1;
        }
    }
    Ok((out, alike))
}

/// Whether the supports give the tie u_s = Σ c u_m itself at every time:
/// every master prescribed, and on each history h the values it scales
/// balance, Σ_(m on h) c v_m = v_s if s is on h else 0 (to 1e-9 of the
/// values: the rotation's round-off).
fn held_alike(
    terms: &[(usize, f64)],
    v: f64,
    h: Option<usize>,
    given: &HashMap<usize, (f64, Option<usize>)>,
) -> bool {
    let mut sums: Vec<(Option<usize>, f64)> = vec![(h, -v)];
    let mut scale = v.abs();
    for &(d, w) in terms {
        let Some(&(vm, hm)) = given.get(&d) else {
            return false;
        };
        scale = scale.max(vm.abs());
        match sums.iter_mut().find(|(k, _)| *k == hm) {
            Some(e) => e.1 += w * vm,
            None => sums.push((hm, w * vm)),
        }
    }
    sums.iter().all(|&(_, s)| s.abs() <= 1e-9 * scale)
}

/// The refusal of a prescribed component `j` of the second face's node s
/// whose partner m the supports do not hold alike.
fn conflict(
    c: &Cyclic,
    case: &Case,
    mesh: &Mesh,
    (m, s): (usize, usize),
    j: usize,
    place: &str,
) -> Error {
    let (at, _) = entry_at(case, mesh, s, j, place);
    let p = |n: usize| crate::model::loads::point(mesh.nodes[n], true);
    Error::input(
        at,
        format!(
            "prescribes u{} of node {s} at {} on the cyclic face \"{}\", which the ties make the image of node {m} at {} on \"{}\" (u = R({}°) u_m): that component follows from node {m}, which the supports do not hold alike, and a tied dof takes no second value; hold node {m} so that its image is held as this (a clamped end: both faces' nodes fixed), or remove this support (one on node {m} carries over to its image)",
            ["x", "y", "z"][j],
            p(s),
            clip(&c.faces[1]),
            p(m),
            clip(&c.faces[0]),
            crate::numbers::num(round(c.angle.to_degrees()))
        ),
    )
}

#[cfg(test)]
mod tests;
