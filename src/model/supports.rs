//! Whether every body is held against its rigid-body motions by the
//! prescribed dofs and the interfaces (a body free to move would make the
//! tangent singular).

use crate::error::{Error, Result};
use crate::input::mesh::Mesh;
use crate::model::constraint::Constraint;
use crate::model::interface::InterfaceModel;

/// Every body must be held in x and in y, by its own prescribed dofs or through
/// an interface (along the interface normal) to a body held in that direction;
/// in axisymmetry every body is held in x = r.
/// Otherwise it could move as a rigid body and the tangent would be singular.
pub(super) fn check_supports(
    mesh: &Mesh,
    prescribed: &[(usize, f64)],
    ties: &[Constraint],
    interfaces: &[InterfaceModel],
    axisymmetric: bool,
    place: &str,
) -> Result<()> {
    if mesh.dim() == 3 {
        return check_solid_supports(mesh, prescribed, ties, interfaces, place);
    }
    // a body of revolution cannot move rigidly in r: u_r = c strains it by c/r
    // in the hoop direction (and nodes on the axis are held by u_r = 0)
    let mut held = vec![[axisymmetric, false]; mesh.bodies.len()];
    let node_body = mesh.node_bodies();
    // (a pretension section's reference node is no node of a body)
    for &(d, _) in prescribed.iter().filter(|p| p.0 < mesh.num_dofs()) {
        let (n, c) = mesh.node_dofs.node_of(d);
        if c < 2 {
            held[node_body[n]][c] = true;
        }
    }
    // propagate along each interface's dominant normal direction to a fixed point
    loop {
        let mut changed = false;
        for im in interfaces {
            let n = im.pairs.first().map_or([0.0, 1.0, 0.0], |p| p.normal);
            let normal = usize::from(n[1].abs() >= n[0].abs());
            // springs carry the normal direction, and with friction the tangential one too
            let dirs: &[usize] = if im.tangential.is_some() {
                &[0, 1]
            } else {
                std::slice::from_ref(&normal)
            };
            let (a, b) = (im.body_a, im.body_b);
            for &c in dirs {
                if held[a][c] != held[b][c] {
                    held[a][c] = true;
                    held[b][c] = true;
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    // twist: a body turns rigidly about the axis (u_θ = ω r, zero on the
    // axis) unless a prescribed u_θ at r > 0 holds it, or the friction of an
    // interface (a tangential law) to a body that is held: that friction
    // holds nothing before the first contact, when the contact stabilization
    // holds the rotation too ([`crate::solve::stabilization`])
    if mesh.node_dofs.twist() {
        let mut turns: Vec<bool> = own_rotation(mesh, prescribed).iter().map(|h| !h).collect();
        loop {
            let mut changed = false;
            for im in interfaces.iter().filter(|im| im.tangential.is_some()) {
                let (a, b) = (im.body_a, im.body_b);
                if turns[a] != turns[b] {
                    turns[a] = false;
                    turns[b] = false;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        if let Some(b) = turns.iter().position(|&t| t) {
            return Err(Error::input(
                place,
                format!(
                    "body \"{}\" is held by nothing about the axis: no [[boundary]] rotation on a node at r > 0 (the axis holds u_θ = 0 but not the rigid rotation u_θ = ω r) and no interface with a tangential law to a body that is held; give a rotation (0: fixed) on a set of the body, or friction to a held body",
                    mesh.bodies[b]
                ),
            ));
        }
    }
    for (b, h) in held.iter().enumerate() {
        for (c, axis) in ["x", "y"].iter().enumerate() {
            if !h[c] {
                return Err(Error::input(
                    place,
                    format!(
                        "body \"{}\" is held by nothing in {axis}: no boundary condition on u{axis} and no interface to a body held in {axis} (rigid-body motion)",
                        mesh.bodies[b]
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// A 3D body is held when its prescribed dofs and its ties stop all six
/// rigid motions: with x̄ its nodes' centroid and L its size, the rows
/// ```text
///   r(n, c) = [e_c, (e_c × (x_n − x̄)) / L]     (u_c of the motion u = a + ω × (x − x̄))
/// ```
/// of its prescribed dofs, and r(s) − Σ c_i r(m_i) of each tie u_s = Σ c_i
/// u_(m_i) within it (a cyclic sector's: the motions that break it), span
/// R⁶ (RᵀR, 6 × 6, has no eigenvalue below 1e-10 of the largest); an
/// eigenvector of a smaller one is a motion they leave free, and is named:
/// a translation, a rotation about an axis through the centroid, or both.
/// An interface to a body that is held adds its pairs' rows along the
/// normal (and the tangent plane's two directions with a tangential law),
/// as the springs would once closed.
fn check_solid_supports(
    mesh: &Mesh,
    prescribed: &[(usize, f64)],
    ties: &[Constraint],
    interfaces: &[InterfaceModel],
    place: &str,
) -> Result<()> {
    let node_body = mesh.node_bodies();
    let nb = mesh.bodies.len();
    let (centre, size) = body_boxes(mesh, &node_body);
    let mut rtr = vec![nalgebra::Matrix6::<f64>::zeros(); nb];
    let vector = |b: usize, x: [f64; 3], e: [f64; 3]| {
        let r: [f64; 3] = std::array::from_fn(|k| (x[k] - centre[b][k]) / size[b]);
        let w = crate::numbers::vec3::cross(r, e);
        nalgebra::Vector6::new(e[0], e[1], e[2], w[0], w[1], w[2])
    };
    // the row of dof d, and its node's body
    let dof_row = |d: usize| {
        let (n, c) = mesh.node_dofs.node_of(d);
        let mut e = [0.0; 3];
        e[c] = 1.0;
        (node_body[n], vector(node_body[n], mesh.nodes[n], e))
    };
    for &(d, _) in prescribed.iter().filter(|p| p.0 < mesh.num_dofs()) {
        let (b, r) = dof_row(d);
        rtr[b] += r * r.transpose();
    }
    let n_dofs = mesh.num_dofs();
    for t in ties.iter().filter(|t| t.slave < n_dofs) {
        let (b, mut r) = dof_row(t.slave);
        let within = t.terms.iter().all(|&(d, c)| {
            d < n_dofs && {
                let (bm, rm) = dof_row(d);
                r -= c * rm;
                bm == b
            }
        });
        if within {
            rtr[b] += r * r.transpose();
        }
    }
    let free = |m: &nalgebra::Matrix6<f64>| {
        let eig = m.symmetric_eigen();
        let largest = eig.eigenvalues.max().max(1.0);
        (0..6)
            .find(|&k| eig.eigenvalues[k] < 1e-10 * largest)
            .map(|k| eig.eigenvectors.column(k).into_owned())
    };
    let mut held: Vec<bool> = rtr.iter().map(|m| free(m).is_none()).collect();
    loop {
        let mut changed = false;
        for im in interfaces {
            let (a, b) = (im.body_a, im.body_b);
            if held[a] == held[b] {
                continue;
            }
            let (loose, node) = if held[a] { (b, 1) } else { (a, 0) };
            for pr in &im.pairs {
                let x = mesh.nodes[if node == 0 { pr.a } else { pr.b }];
                let mut dirs = vec![pr.normal];
                if im.tangential.is_some() {
                    dirs.extend(crate::model::interface::tangents(pr.normal));
                }
                for e in dirs {
                    let r = vector(loose, x, e);
                    rtr[loose] += r * r.transpose();
                }
            }
            held[loose] = free(&rtr[loose]).is_none();
            changed |= held[loose];
        }
        if !changed {
            break;
        }
    }
    // the bodies some cyclic tie holds
    let mut cyclic_tied = vec![false; rtr.len()];
    for t in ties.iter().filter(|t| cyclic(t) && t.slave < n_dofs) {
        cyclic_tied[dof_row(t.slave).0] = true;
    }
    for (b, m) in rtr.iter().enumerate() {
        let Some(v) = free(m) else {
            continue;
        };
        return Err(Error::input(
            place,
            format!(
                "body \"{}\" is held by nothing against {} (a rigid-body motion: a 3D body needs its six held by [[boundary]] ux, uy, uz, or through an interface to a body that is held); {}",
                mesh.bodies[b],
                motion([v[0], v[1], v[2]], [v[3], v[4], v[5]], centre[b], size[b]),
                rigid_hint(cyclic_tied[b], ties),
            ),
        ));
    }
    Ok(())
}

/// Each body's centroid (of its nodes) and size (its box's diagonal): the
/// origin and scale of the rows of its rigid motions.
fn body_boxes(mesh: &Mesh, node_body: &[usize]) -> (Vec<[f64; 3]>, Vec<f64>) {
    let nb = mesh.bodies.len();
    let mut centre = vec![[0.0; 3]; nb];
    let mut count = vec![0usize; nb];
    let mut lo = vec![[f64::INFINITY; 3]; nb];
    let mut hi = vec![[f64::NEG_INFINITY; 3]; nb];
    for (n, x) in mesh.nodes.iter().enumerate() {
        let b = node_body[n];
        for c in 0..3 {
            centre[b][c] += x[c];
            lo[b][c] = lo[b][c].min(x[c]);
            hi[b][c] = hi[b][c].max(x[c]);
        }
        count[b] += 1;
    }
    for (c, k) in centre.iter_mut().zip(&count) {
        *c = c.map(|v| v / (*k).max(1) as f64);
    }
    let size = (0..nb)
        .map(|b| {
            (0..3)
                .map(|k| (hi[b][k] - lo[b][k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    (centre, size)
}

/// A free rigid motion u = t + (ω / L) × (x − c) in words (ω scaled by the
/// body's size L, as the rows): a translation along t, a rotation about the
/// axis along ω through the centroid `c`, a rotation about a parallel axis
/// through p = c + L ω × t / |ω|² when t ⟂ ω (a cyclic sector turning about
/// the y axis), or a translation with a rotation.
fn motion(t: [f64; 3], w: [f64; 3], c: [f64; 3], size: f64) -> String {
    let norm = |v: [f64; 3]| crate::numbers::vec3::dot(v, v).sqrt();
    let dir = |v: [f64; 3]| {
        let n = norm(v);
        let r = v.map(|x| {
            let y = x / n;
            if y.abs() < 1e-6 {
                0.0
            } else {
                (y * 1e3).round() / 1e3
            }
        });
        format!("({}, {}, {})", r[0], r[1], r[2])
    };
    let point = |c: [f64; 3]| {
        let c = c.map(|v| if v.abs() < 1e-9 * size { 0.0 } else { v });
        format!("({:.4}, {:.4}, {:.4})", c[0], c[1], c[2])
    };
    let centre = point(c);
    let (nt, nw) = (norm(t), norm(w));
    if nt > 1e-3 && nw > 1e-3 && crate::numbers::vec3::dot(t, w).abs() < 1e-6 * nt * nw {
        let wt = crate::numbers::vec3::cross(w, t);
        let p: [f64; 3] = std::array::from_fn(|k| c[k] + size * wt[k] / (nw * nw));
        return format!(
            "a rotation about the axis along {} through {}",
            dir(w),
            point(p)
        );
    }
    match (nt > 1e-3, nw > 1e-3) {
        (true, false) => format!("a translation along {}", dir(t)),
        (false, _) => format!(
            "a rotation about the axis along {} through {centre}",
            dir(w)
        ),
        (true, true) => format!(
            "a translation along {} with a rotation about the axis along {} through {centre}",
            dir(t),
            dir(w)
        ),
    }
}

/// Twist: whether each body is held about the axis by a prescribed u_θ of its
/// own at r > 0 (without one only the friction of an interface can hold it).
pub(crate) fn own_rotation(mesh: &Mesh, prescribed: &[(usize, f64)]) -> Vec<bool> {
    let node_body = mesh.node_bodies();
    let tol = crate::model::consistency::tolerance(mesh);
    let mut own = vec![false; mesh.bodies.len()];
    for &(d, _) in prescribed.iter().filter(|p| p.0 < mesh.num_dofs()) {
        let (n, c) = mesh.node_dofs.node_of(d);
        if c == 2 && node_body[n] < own.len() && mesh.nodes[n][0].abs() > tol {
            own[node_body[n]] = true;
        }
    }
    own
}

/// Every force-controlled pretension section that cuts its body in two
/// ([`crate::model::pretension::sides`]) needs something on each side of the cut
/// to pull against: the section's force moves the two sides apart or
/// together by any amount (its shortening is free until it is locked), so a
/// side without a prescribed dof along the cut's normal and without an
/// interface that can carry that direction (its normal along it, or a
/// tangential law) is a mechanism the section force drives, whatever the
/// loads: a bolt without an interface under its head. Refused, naming the
/// section and the side. (A side with an interface whose pairs are open
/// is held, or not, at run time: [`crate::solve::stabilization`].)
/// And a body held along the normal by friction alone (no support along
/// it, no interface of the body bearing along it, no fit's interference to
/// clamp one) is refused too: friction holds nothing before a normal force
/// clamps its faces, and nothing would (a cut through a bolt's axis, where
/// its head and nut bear across the cut's normal).
pub(super) fn check_sections_held(
    mesh: &Mesh,
    sections: &[crate::model::pretension::Section],
    prescribed: &[(usize, f64)],
    interfaces: &[InterfaceModel],
    place: &str,
) -> Result<()> {
    for s in sections.iter().filter(|s| s.control == "force") {
        let Some(beyond) = crate::model::pretension::sides(mesh, s) else {
            continue;
        };
        let h = Holds::of(mesh, s, &beyond, prescribed, interfaces);
        let line = ["x", "y", "z"][s.axis];
        let at = || format!("{place}: pretension \"{}\"", crate::error::clip(&s.name));
        if let Some(side) = h.held.iter().position(|h| !h) {
            return Err(Error::input(
                at(),
                format!(
                    "cuts body \"{}\" in two at {line} = {}, and its side {line} {} {} has no support in u{line} and no interface that carries u{line}: nothing holds that side against the section's force, which moves it freely (force control); give that side an interface (a bolt needs one under its head and one under its nut) or a support",
                    mesh.bodies[s.body],
                    s.at,
                    if side == 1 { ">" } else { "<" },
                    s.at,
                ),
            ));
        }
        if !h.bears {
            let most = (0..3).fold(0, |m, k| if h.across[k] > h.across[m] { k } else { m });
            let most = ["x", "y", "z"][most];
            return Err(Error::input(
                at(),
                format!(
                    "cuts body \"{}\" at {line} = {}, but the body bears on its interfaces ({}) along {most} and nothing holds it along {line} but their friction, which holds nothing before a normal force clamps them: the section's force would pull its two sides sideways; cut across the bolt's axis ({most} = c), where its head and its nut bear",
                    mesh.bodies[s.body],
                    s.at,
                    h.names.join(", "),
                ),
            ));
        }
    }
    Ok(())
}

/// What holds the body of a section along the cut's normal.
struct Holds {
    /// Each side (before, beyond the cut): a support along the normal, or
    /// an interface that carries it (its normal along it, or friction).
    held: [bool; 2],
    /// Anything but friction: a support along the normal, an interface of
    /// the body bearing along it, or a fit's interference clamping one.
    bears: bool,
    /// The largest |n_x|, |n_y|, |n_z| of the body's interface pairs.
    across: [f64; 3],
    /// The body's interfaces, quoted.
    names: Vec<String>,
}

impl Holds {
    fn of(
        mesh: &Mesh,
        s: &crate::model::pretension::Section,
        beyond: &[bool],
        prescribed: &[(usize, f64)],
        interfaces: &[InterfaceModel],
    ) -> Holds {
        let node_body = mesh.node_bodies();
        let mut h = Holds {
            held: [false; 2],
            bears: false,
            across: [0.0; 3],
            names: Vec::new(),
        };
        for &(d, _) in prescribed.iter().filter(|p| p.0 < mesh.num_dofs()) {
            let (n, c) = mesh.node_dofs.node_of(d);
            if c == s.axis && node_body[n] == s.body {
                h.held[usize::from(beyond[n])] = true;
                h.bears = true;
            }
        }
        for im in interfaces {
            let mut touches = false;
            for p in &im.pairs {
                // the normal's largest component along the cut's normal
                let along = p.normal.get(s.axis).map_or(0.0, |v| v.abs());
                let normal = p.normal.iter().all(|v| v.abs() <= along);
                for (body, n) in [(im.body_a, p.a), (im.body_b, p.b)] {
                    if body == s.body {
                        touches = true;
                        h.held[usize::from(beyond[n])] |= im.tangential.is_some() || normal;
                        h.bears |= normal || im.gap < 0.0;
                        for (m, v) in h.across.iter_mut().zip(p.normal) {
                            *m = m.max(v.abs());
                        }
                    }
                }
            }
            if touches {
                h.names
                    .push(format!("\"{}\"", crate::error::clip(&im.name)));
            }
        }
        h
    }
}

fn cyclic(t: &Constraint) -> bool {
    t.origin.starts_with("cyclic")
}

/// What to do about a 3D body left free: hold the rotation and axial
/// translation the ties of a cyclic sector leave, tie the body's own cut
/// faces, or hold it.
fn rigid_hint(cyclic_tied: bool, ties: &[Constraint]) -> &'static str {
    if cyclic_tied {
        "the cyclic ties hold a sector but for its rotation about the y axis and its translation along it: hold those (an end's uy, and one node's hoop displacement, e.g. uz at a node of the face in the plane z = 0)"
    } else if ties.iter().any(cyclic) {
        "the cyclic faces ([model] cyclic faces) name no node of this body, so no tie holds its cut faces: name node sets that hold every body's cut (in a Gmsh mesh one physical surface per side over all bodies), or hold it"
    } else {
        "hold it, e.g. fix a corner, or give symmetry planes"
    }
}
