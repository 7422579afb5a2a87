//! Cyclic symmetry of 3D models (issue 47; docs/case-schema.md "Cyclic
//! symmetry", docs/theory.md "Cyclic symmetry"): one sector of N, its cut
//! faces tied by u_s = R(360°/N) u_m.
//!
//! - Lamé's thick tube (cases/tube-revolved-3d) as a 30° sector of 12 tied
//!   instead of held by symmetry planes: u_r at every node against the
//!   closed form, no hoop or axial motion, the whole part's end force N ×
//!   the sector's; and as a 90° sector of 4 beside the quarter with its
//!   symmetry planes: the same displacements to round-off.
//! - A tube sector twisted by a torque on one end, the other clamped:
//!   Saint-Venant's u = φ(y) ŷ × x with φ = T y / (G J) at every node and
//!   τ = T r / J at every Gauss point, the clamp's moment about the axis N
//!   times the sector's torque. Symmetry planes hold the hoop displacement
//!   and cannot carry this; the ties can, so it proves the rotation right.
//! - A solid bar's 90° sector (the O-grid core on the axis, whose nodes are
//!   held across it) under the same torque, against J = π R⁴ / 2.
//! - The ties of a sector of 7 (a non-round angle) under a rigid rotation
//!   about the axis: every tie met to round-off.

use crate::common;
use asperity::model::Model;
use asperity::solve::{RunResult, State};
use common::Quiet;

fn run(text: &str) -> (Model, RunResult) {
    let model = common::model(text);
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap();
    (model, r)
}

fn state(r: &RunResult) -> &State {
    &r.final_state
}

/// The thick tube a = 10 ≤ r ≤ b = 25, 0 ≤ y ≤ 4 of cases/tube-revolved-3d
/// (8 graded elements across, 2 along, 7.5° layers) over `angle`°, under
/// 100 MPa in its bore, its ends held axially, with `hold` appended.
fn lame_tube(angle: f64, layers: usize, cyclic: &str, hold: &str) -> String {
    format!(
        "[model]\nplane = \"3d\"\n{cyclic}\n[mesh]\nrevolve = {{ angle = {angle}, n = {layers} }}\n\
         [[mesh.block]]\nbody = \"tube\"\nx = [10.0, 25.0]\nnx = [8]\nrx = [2.66]\ny = [0.0, 4.0]\nny = [2]\n\
         [materials.tube]\nyoung = 210000.0\npoisson = 0.3\n\
         [[boundary]]\nset = \"tube.bottom\"\nuy = 0.0\n[[boundary]]\nset = \"tube.top\"\nuy = 0.0\n\
         {hold}\
         [[load]]\nfaces = \"tube.left\"\npressure = 100.0\n\
         [solver]\nincrements = 1\nresidual_tolerance = 1e-12\n[output]\nvtu = false\n"
    )
}

/// The rotation about the axis held at the edge of the face θ = 0 on the
/// end y = 0, where u_z is the hoop displacement (0 in Lamé's tube).
const HOOP_HOLD: &str = "[[boundary]]\nset = \"tube.theta0\"\ny_range = [0.0, 0.0]\nuz = 0.0\n";

fn cyclic(sectors: usize) -> String {
    format!("cyclic = {{ sectors = {sectors}, faces = [\"tube.theta0\", \"tube.theta1\"] }}")
}

/// The largest |u1 − u2| over every dof, and the largest |u2|.
fn largest_difference(u1: &[f64], u2: &[f64]) -> (f64, f64) {
    let scale = u2.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let diff = u1
        .iter()
        .zip(u2)
        .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
    (diff, scale)
}

/// Radial, hoop and axial displacement of node n.
fn polar(m: &Model, s: &State, n: usize) -> (f64, [f64; 3]) {
    let x = m.mesh.nodes[n];
    let r = x[0].hypot(x[2]);
    let (ux, uy, uz) = (s.u[3 * n], s.u[3 * n + 1], s.u[3 * n + 2]);
    (
        r,
        [(ux * x[0] + uz * x[2]) / r, (uz * x[0] - ux * x[2]) / r, uy],
    )
}

/// The values of a reaction group's components by label.
fn reaction(m: &Model, s: &State, group: &str, label: &str) -> f64 {
    let g = (m.plan.reactions.iter())
        .find(|g| g.name == group)
        .unwrap_or_else(|| panic!("no group {group}"));
    let k = (g.components.iter())
        .position(|c| c.label == label)
        .unwrap_or_else(|| panic!("{group} has no {label}"));
    g.values(&s.reactions).nth(k).unwrap()
}

/// Lamé's tube (plane strain, 100 MPa in the bore) as a 30° sector of 12:
/// u_r at every node as the quarter with symmetry planes has it against the
/// closed form, u_θ and u_y at the solve's tolerance, and the whole part's
/// axial end force 2ν A π (b² − a²), twelve times the sector's.
#[test]
fn a_tube_sector_tied_cyclically_is_lame() {
    let (a, b, p, e, nu): (f64, f64, f64, f64, f64) = (10.0, 25.0, 100.0, 210000.0, 0.3);
    let (m, r) = run(&lame_tube(30.0, 4, &cyclic(12), HOOP_HOLD));
    let s = state(&r);
    let big_a = p * a * a / (b * b - a * a);
    let big_b = p * a * a * b * b / (b * b - a * a);
    let u_r = |r: f64| (1.0 + nu) / e * ((1.0 - 2.0 * nu) * big_a * r + big_b / r);
    let (mut radial, mut around, mut axial): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for n in 0..m.mesh.nodes.len() {
        let (rr, [ur, ut, uy]) = polar(&m, s, n);
        radial = radial.max((ur - u_r(rr)).abs() / u_r(a));
        around = around.max(ut.abs() / u_r(a));
        axial = axial.max(uy.abs() / u_r(a));
    }
    let sector = reaction(&m, s, "tube.bottom", "fy_n");
    let part = reaction(&m, s, "tube.bottom", "fy_part_n");
    let want = 2.0 * nu * big_a * std::f64::consts::PI * (b * b - a * a);
    println!(
        "tube sector of 12: |u_r − Lamé| / u_r(a) {radial:.2e}, |u_θ| {around:.2e}, |u_y| {axial:.2e}; end force of the part {part:.4} N (Lamé {want:.4}), of the sector {sector:.4} N"
    );
    // measured 7.4e-6, as the quarter of cases/tube-revolved-3d (the same
    // layers of 7.5°)
    assert!(radial < 1e-4, "{radial:e}");
    assert!(around < 1e-9 && axial < 1e-9, "{around:e} {axial:e}");
    // the end pulls the tube's axial tension 2ν A back: −y at y = 0;
    // measured 6.1e-7 (the discretization's, as the quarter's 4,712.386 N)
    assert!((part + want).abs() < 1e-5 * want, "{part} vs {want}");
    assert_eq!(part, 12.0 * sector);
    // no moment about the axis anywhere: the hoop hold carries nothing
    let held = reaction(&m, s, "tube.theta0", "my_part_nmm");
    assert!(held.abs() < 1e-9 * want * b, "{held}");
}

/// The quarter of cases/tube-revolved-3d tied as a sector of 4 (its hoop
/// held on one edge) and the same quarter on its two symmetry planes give
/// the same displacements to round-off: the layers are mirror-symmetric
/// about 45°, so the tied solution has no hoop displacement on the cuts,
/// and the planes' solution meets the ties.
#[test]
fn a_quarter_tied_cyclically_equals_the_quarter_on_symmetry_planes() {
    let planes = "[[boundary]]\nset = \"tube.theta0\"\nuz = 0.0\n[[boundary]]\nset = \"tube.theta1\"\nux = 0.0\n";
    let (m1, r1) = run(&lame_tube(90.0, 12, &cyclic(4), HOOP_HOLD));
    let (m2, r2) = run(&lame_tube(90.0, 12, "", planes));
    assert_eq!(m1.mesh.nodes, m2.mesh.nodes);
    let (diff, scale) = largest_difference(&state(&r1).u, &state(&r2).u);
    println!(
        "quarter: tied against symmetry planes, largest difference {diff:.2e} of {scale:.4e} mm"
    );
    // measured 1.1e-16 mm of 7.8e-3 (the residual tolerance is 1e-12)
    assert!(diff < 1e-12 * scale, "{diff:e}");
}

/// A torque on the end of a tube sector, the other end clamped: the sector
/// carries 1/N of the part's torque T, and Saint-Venant's solution u = φ(y)
/// ŷ × x, φ = T y / (G J), J = π (b⁴ − a⁴)/2, vanishes at the clamp, so it
/// is the exact answer: at every node, and τ = T r / J at every Gauss
/// point. The clamp's moment about the axis is −T over the part.
fn twisted(text: &str, radii: [f64; 2], length: f64, sectors: f64, torque: f64) -> [f64; 3] {
    let (e, nu) = (210000.0, 0.3);
    let g = e / (2.0 * (1.0 + nu));
    let [a, b] = radii;
    let j = std::f64::consts::PI * (b.powi(4) - a.powi(4)) / 2.0;
    let t_part = sectors * torque;
    let phi = |y: f64| t_part * y / (g * j);
    let (m, r) = run(text);
    let s = state(&r);
    let mut nodes: f64 = 0.0;
    for (n, x) in m.mesh.nodes.iter().enumerate() {
        let want = [phi(x[1]) * x[2], 0.0, -phi(x[1]) * x[0]];
        for (c, w) in want.iter().enumerate() {
            nodes = nodes.max((s.u[3 * n + c] - w).abs() / (phi(length) * b));
        }
    }
    let mut shear: f64 = 0.0;
    for el in 0..m.mesh.elements.len() {
        for (ip, k) in m.points(el).enumerate() {
            let x = m.point_x(el, ip);
            let rr = x[0].hypot(x[2]);
            let sg = s.gauss.get(k).stress;
            // e_θ · σ · ŷ, e_θ = (z, 0, −x)/r: σ_xy = s[2], σ_yz = s[5]
            let tau = (x[2] * sg[2] - x[0] * sg[5]) / rr.max(1e-300);
            shear = shear.max((tau - t_part * rr / j).abs() / (t_part * b / j));
        }
    }
    let clamp = reaction(
        &m,
        s,
        &format!("{}.bottom", m.mesh.bodies[0]),
        "my_part_nmm",
    );
    let sector = reaction(&m, s, &format!("{}.bottom", m.mesh.bodies[0]), "my_nmm");
    println!(
        "twisted sector of {sectors}: φ(L) = {:.6e} rad, τ(b) = {:.4} MPa; largest |u − u_exact| / (φ(L) b) {nodes:.2e}, |τ − T r/J| / τ(b) {shear:.2e}; the clamp's moment {clamp:.6e} N·mm (part), {sector:.6e} (sector)",
        phi(length),
        t_part * b / j
    );
    assert!(
        (clamp + t_part).abs() < 1e-8 * t_part,
        "{clamp} vs {}",
        -t_part
    );
    assert!((clamp - sectors * sector).abs() <= 1e-12 * t_part);
    [nodes, shear, phi(length)]
}

/// cases/tube-sector-cyclic: a 30° sector of 12 (2 layers), and a finer
/// one (4 layers, 8 elements across): the error is the revolution's
/// quadratic arcs', and falls with the layers.
#[test]
fn a_twisted_tube_sector_is_saint_venants_shaft() {
    let case =
        std::fs::read_to_string(common::root().join("cases/tube-sector-cyclic/case.toml")).unwrap();
    let [nodes, shear, phi] = twisted(&case, [10.0, 25.0], 20.0, 12.0, 2.0e5);
    // measured 1.95e-5 and 1.92e-5 (the case's README)
    assert!(nodes < 1e-4 && shear < 1e-4, "{nodes:e} {shear:e}");
    // φ(L) = 2.4e6 · 20 / (G J): the README's hand value
    assert!((phi - 9.9399e-4).abs() < 1e-7, "{phi}");
    let fine = case
        .replace("n = 2 }", "n = 4 }")
        .replace("nx = [4]", "nx = [8]");
    assert!(fine.contains("n = 4 }") && fine.contains("nx = [8]"));
    let [fine_nodes, fine_shear, _] = twisted(&fine, [10.0, 25.0], 20.0, 12.0, 2.0e5);
    // measured 1.22e-6 and 1.21e-6: 16 times smaller at twice the layers
    // (the arcs' error, order 4)
    assert!(fine_nodes < nodes / 8.0, "{fine_nodes:e} vs {nodes:e}");
    assert!(fine_shear < shear / 8.0, "{fine_shear:e} vs {shear:e}");
}

/// A solid bar r ≤ 5, 20 long, revolved through 90° with its O-grid core
/// and tied as a sector of 4 (its axis nodes held across the axis),
/// clamped at y = 0 and twisted at y = 20: Saint-Venant with J = π R⁴/2.
#[test]
fn a_solid_bar_sector_through_the_axis_twists_as_saint_venants_shaft() {
    let text = "[model]\nplane = \"3d\"\ncyclic = { sectors = 4, faces = [\"bar.theta0\", \"bar.theta1\"] }\n\
         [mesh]\nrevolve = { angle = 90.0, n = 4 }\n\
         [[mesh.block]]\nbody = \"bar\"\nx = [0.0, 5.0]\nnx = [3]\ny = [0.0, 20.0]\nny = [4]\n\
         [materials.bar]\nyoung = 210000.0\npoisson = 0.3\n\
         [[boundary]]\nset = \"bar.bottom\"\nux = 0.0\nuy = 0.0\nuz = 0.0\n\
         [[load]]\nfaces = \"bar.top\"\ntorque = 1.0e4\n\
         [solver]\nincrements = 1\nresidual_tolerance = 1e-12\n[output]\nvtu = false\n";
    let [nodes, shear, _] = twisted(text, [0.0, 5.0], 20.0, 4.0, 1.0e4);
    // measured 9.9e-5 and 9.5e-5 (the ring's quadratic arcs)
    assert!(nodes < 5e-4 && shear < 5e-4, "{nodes:e} {shear:e}");
}

/// Every tie of a sector of 7 (51.43°, no round cosine) is met by the rigid
/// rotation about the y axis u = ω ŷ × x to round-off, and broken by a
/// rotation about the x axis, which the ties hold.
#[test]
fn a_rigid_rotation_about_the_axis_meets_every_tie_of_a_sector_of_seven() {
    let angle = 360.0 / 7.0;
    let text = format!(
        "[model]\nplane = \"3d\"\n{}\n[mesh]\nrevolve = {{ angle = {angle}, n = 3 }}\n\
         [[mesh.block]]\nbody = \"tube\"\nx = [10.0, 25.0]\nnx = [3]\ny = [0.0, 8.0]\nny = [2]\n\
         [materials.tube]\nyoung = 210000.0\npoisson = 0.3\n\
         [[boundary]]\nset = \"tube.bottom\"\nux = 0.0\nuy = 0.0\nuz = 0.0\n\
         [[load]]\nfaces = \"tube.top\"\ntorque = 1.0e5\n",
        cyclic(7)
    );
    let m = common::model(&text);
    let ties = &m.constraints.list;
    let c = m.cyclic.as_ref().unwrap();
    assert_eq!(m.cyclic_sectors(), Some(7));
    assert_eq!(ties.len(), 3 * c.pairs.len() - c.held_alike);
    assert!(ties.len() > 40, "{}", ties.len());
    let broken = |u: &dyn Fn([f64; 3]) -> [f64; 3]| {
        let mut v = vec![0.0; m.n_dofs()];
        for (n, x) in m.mesh.nodes.iter().enumerate() {
            v[3 * n..3 * n + 3].copy_from_slice(&u(*x));
        }
        ties.iter()
            .map(|t| (v[t.slave] - t.terms.iter().map(|&(d, a)| a * v[d]).sum::<f64>()).abs())
            .fold(0.0f64, f64::max)
    };
    let w = 1e-3;
    let spin = broken(&|x| [w * x[2], 0.0, -w * x[0]]);
    let tilt = broken(&|x| [0.0, -w * x[2], w * x[1]]);
    println!(
        "sector of 7: a rigid rotation breaks a tie by {spin:.2e} mm, a tilt by {tilt:.2e} mm"
    );
    // measured 1.7e-18 mm
    assert!(spin < 1e-16 * 25.0 * 8.0, "{spin:e}");
    assert!(tilt > 1e-3 * w * 25.0, "{tilt:e}");
}

/// Two tubes fitted one in the other (10 ≤ r ≤ 17.5 in 17.5 ≤ r ≤ 25, a
/// radial interference of 0.01 mm through the paper's rough interface)
/// revolved through 90°: tied as a sector of 4 on the mesh-wide cut faces
/// `theta0` / `theta1` (every body's cut at once), or on two symmetry
/// planes through the same sets. The same displacements to the solve's
/// tolerance: both bodies' cuts are tied (a body left untied would be free
/// about the axis and refused), and the fit's pressure is the same.
#[test]
fn a_sector_of_two_bodies_is_tied_on_the_mesh_wide_cut_faces() {
    let text = |model: &str, hold: &str| {
        format!(
            "[model]\nplane = \"3d\"\n{model}\n[mesh]\nrevolve = {{ angle = 90.0, n = 6 }}\n\
             [[mesh.block]]\nbody = \"inner\"\nx = [10.0, 17.5]\nnx = [4]\ny = [0.0, 4.0]\nny = [2]\n\
             [[mesh.block]]\nbody = \"outer\"\nx = [17.5, 25.0]\nnx = [4]\ny = [0.0, 4.0]\nny = [2]\n\
             [[mesh.interface]]\nname = \"fit\"\nleft = \"inner\"\nright = \"outer\"\n\
             [interface.fit]\nlaw = \"power\"\nc_n = 0.001\nm = 0.5\ngap = -0.01\n\
             [materials.inner]\nyoung = 210000.0\npoisson = 0.3\n\
             [materials.outer]\nyoung = 210000.0\npoisson = 0.3\n\
             [[boundary]]\nset = \"inner.bottom\"\nuy = 0.0\n[[boundary]]\nset = \"inner.top\"\nuy = 0.0\n\
             [[boundary]]\nset = \"outer.bottom\"\nuy = 0.0\n[[boundary]]\nset = \"outer.top\"\nuy = 0.0\n\
             {hold}\
             [solver]\nincrements = 2\nresidual_tolerance = 1e-12\n[output]\nvtu = false\n"
        )
    };
    let hoop = "[[boundary]]\nset = \"inner.theta0\"\ny_range = [0.0, 0.0]\nuz = 0.0\n\
                [[boundary]]\nset = \"outer.theta0\"\ny_range = [0.0, 0.0]\nuz = 0.0\n";
    let planes =
        "[[boundary]]\nset = \"theta0\"\nuz = 0.0\n[[boundary]]\nset = \"theta1\"\nux = 0.0\n";
    let tied = "cyclic = { sectors = 4, faces = [\"theta0\", \"theta1\"] }";
    let (m1, r1) = run(&text(tied, hoop));
    let (m2, r2) = run(&text("", planes));
    assert_eq!(m1.mesh.nodes, m2.mesh.nodes);
    // every node of both cuts is tied (the ties are the cyclic constraints)
    let cut = m1.mesh.node_sets["theta1"].len();
    let bodies = m1.mesh.node_bodies();
    let ties = (m1.constraints.list.iter())
        .filter(|c| c.origin.starts_with("cyclic"))
        .map(|c| m1.mesh.node_dofs.node_of(c.slave).0)
        .collect::<std::collections::BTreeSet<_>>();
    assert_eq!(ties.len(), cut);
    for b in 0..2 {
        assert!(ties.iter().any(|&n| bodies[n] == b), "body {b} untied");
    }
    let (diff, scale) = largest_difference(&state(&r1).u, &state(&r2).u);
    println!(
        "two bodies: tied against symmetry planes, largest difference {diff:.2e} of {scale:.4e} mm"
    );
    assert!(scale > 1e-3, "{scale}");
    assert!(diff < 1e-9 * scale, "{diff:e}");
}
