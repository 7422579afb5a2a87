use super::*;
// the layout and the face-set resultant of the sweep's tests
use crate::input::mesh::blocks::{self, BlockSpec};
use crate::input::mesh::extrude::tests::{layout, pushed};
use crate::input::mesh::Face;
use crate::physics::element::solid3::{ElementGeometry3, Family3};

/// [`layout`] moved off the axis: x in [5, 21] (radii), y in [0, 4].
fn hollow() -> Mesh {
    let mut plane = layout();
    for x in &mut plane.nodes {
        x[0] += 5.0;
    }
    plane
}

/// The volume of a 3D mesh by 3×3×3 Gauss.
fn volume(mesh: &Mesh) -> f64 {
    let rule = Family3::H20.rule(true);
    (0..mesh.elements.len())
        .map(|e| {
            let c = mesh.element_coords3(e);
            ElementGeometry3::new(Family3::H20, &c[..20], &rule)
                .unwrap()
                .volume()
        })
        .sum()
}

#[test]
fn a_revolved_layout_is_a_valid_sector_whose_volume_converges_at_order_four() {
    let exact = std::f64::consts::FRAC_PI_4 * (21.0f64.powi(2) - 5.0f64.powi(2)) * 4.0;
    let mut errors = Vec::new();
    for n in [3, 6, 12] {
        let mesh = revolve(&hollow(), std::f64::consts::FRAC_PI_2, n).unwrap();
        mesh.validate().unwrap();
        assert_eq!(mesh.elements.len(), n * layout().elements.len());
        // every node on its circle: the radius of its layout node
        for x in &mesh.nodes {
            let r = x[0].hypot(x[2]);
            assert!((5.0 - 1e-12..=21.0 + 1e-12).contains(&r), "{x:?}");
            assert!(x[0] >= -1e-12 && x[2] >= -1e-12, "{x:?}");
        }
        errors.push((volume(&mesh) - exact).abs() / exact);
    }
    // the quadratic arcs cut the circle: the volume's error falls as Δθ⁴
    let order = (errors[1] / errors[2]).log2();
    println!("revolved volume: relative errors {errors:?}, order {order:.2}");
    assert!(errors[2] < 1e-5, "{errors:?}");
    assert!((3.5..4.5).contains(&order), "{errors:?}");
}

#[test]
fn a_revolved_layouts_face_sets_are_walked_outward() {
    let mesh = revolve(&hollow(), std::f64::consts::FRAC_PI_2, 12).unwrap();
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|c| (a[c] - b[c]).abs() < 1e-3 * 64.0);
    // the bore r = 5 (outward −r̂): a unit pressure pushes it out, ∫ r̂ dA = (a h, 0, a h)
    let bore = pushed(&mesh, "a.left");
    assert!(close(bore, [20.0, 0.0, 20.0]), "{bore:?}");
    // the outside r = 21, the same inward
    assert!(close(pushed(&mesh, "b.right"), [-84.0, 0.0, -84.0]));
    // the ends: θ = 0 is the plane z = 0 (outward −z), θ = 90° the plane x = 0
    // (the sector lies at x ≥ 0: outward −x)
    let start = pushed(&mesh, "part.theta0");
    assert!(close(start, [0.0, 0.0, 64.0]), "{start:?}");
    let end = pushed(&mesh, "part.theta1");
    assert!(close(end, [64.0, 0.0, 0.0]), "{end:?}");
    assert!(!mesh.node_sets.contains_key("part.zmin"));
    let end = &mesh.node_sets["part.theta1"];
    assert!(end.iter().all(|&n| mesh.nodes[n][0].abs() < 1e-12));
}

#[test]
fn a_layout_on_the_axis_is_refused_but_through_a_quarter_or_a_half() {
    for (angle, n) in [
        (std::f64::consts::PI, 6),
        (std::f64::consts::FRAC_PI_2, 3),
        (std::f64::consts::FRAC_PI_3, 4),
    ] {
        let e = revolve(&layout(), angle, n).unwrap_err();
        assert!(e.0.contains("reaches the axis at (x, y) = (0, 0)"), "{e}");
        assert!(
            e.0.contains("a quarter through 90° in an even number of layers or a half through 180° in a multiple of 4"),
            "{e}"
        );
    }
}

/// A solid quarter cylinder r ≤ 16, 0 ≤ y ≤ 4 ([`layout`], two blocks, the
/// first on the axis) revolved with its O-grid core: a valid mesh whose
/// volume converges to π/4 · 16² · 4, its faces pushed outward by a unit
/// pressure (top and bottom, the ends θ = 0 and 90°, the outside).
#[test]
fn a_solid_layout_revolves_with_an_o_grid_core() {
    let exact = std::f64::consts::FRAC_PI_4 * 256.0 * 4.0;
    let mut errors = Vec::new();
    for n in [4, 8, 16] {
        let mesh = revolve(&layout(), std::f64::consts::FRAC_PI_2, n).unwrap();
        mesh.validate().unwrap();
        let rule = Family3::H20.rule(true);
        for e in 0..mesh.elements.len() {
            let c = mesh.element_coords3(e);
            ElementGeometry3::new(Family3::H20, &c[..20], &rule).unwrap();
        }
        // every node used, none twice
        let mut used = vec![false; mesh.nodes.len()];
        for el in &mesh.elements {
            for &k in el.nodes() {
                used[k] = true;
            }
        }
        assert!(used.iter().all(|&u| u), "n = {n}: unused nodes");
        let mut places: Vec<[i64; 3]> = mesh
            .nodes
            .iter()
            .map(|x| x.map(|v| (v * 1e6).round() as i64))
            .collect();
        places.sort_unstable();
        places.dedup();
        assert_eq!(places.len(), mesh.nodes.len(), "n = {n}: coincident nodes");
        errors.push((volume(&mesh) - exact).abs() / exact);
        let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|c| (a[c] - b[c]).abs() < 2e-3 * 64.0);
        let top = pushed(&mesh, "a.top");
        assert!(
            close(top, [0.0, -std::f64::consts::FRAC_PI_4 * 100.0, 0.0]),
            "n = {n}: {top:?}"
        );
        let bottom = pushed(&mesh, "a.bottom");
        assert!(
            close(bottom, [0.0, std::f64::consts::FRAC_PI_4 * 100.0, 0.0]),
            "n = {n}: {bottom:?}"
        );
        let start = pushed(&mesh, "part.theta0");
        assert!(close(start, [0.0, 0.0, 64.0]), "n = {n}: {start:?}");
        let end = pushed(&mesh, "part.theta1");
        assert!(close(end, [64.0, 0.0, 0.0]), "n = {n}: {end:?}");
        let outside = pushed(&mesh, "b.right");
        assert!(close(outside, [-64.0, 0.0, -64.0]), "n = {n}: {outside:?}");
        // the axis: the block's left side becomes the nodes on the y axis
        let axis = &mesh.node_sets["a.left"];
        assert!(!axis.is_empty());
        assert!(axis
            .iter()
            .all(|&k| mesh.nodes[k][0] == 0.0 && mesh.nodes[k][2] == 0.0));
    }
    println!("solid quarter cylinder: relative volume errors {errors:?}");
    assert!(errors[2] < errors[1] && errors[1] < errors[0], "{errors:?}");
    assert!(errors[2] < 1e-5, "{errors:?}");
}

/// The solid half cylinder r ≤ 16, 0 ≤ y ≤ 4 revolved through 180° with
/// its O-grid core (a rectangle of 2m × m elements and a ring of 4m): a
/// valid mesh whose volume converges to π/2 · 16² · 4, its two ends in the
/// plane z = 0 (θ = 0 at x > 0, θ = 180° at x < 0) pushed out along −z.
#[test]
fn a_solid_layout_revolves_through_a_half_with_its_core() {
    let exact = std::f64::consts::FRAC_PI_2 * 256.0 * 4.0;
    let mut errors = Vec::new();
    for n in [4, 8, 16] {
        let mesh = revolve(&layout(), std::f64::consts::PI, n).unwrap();
        mesh.validate().unwrap();
        let mut places: Vec<[i64; 3]> = mesh
            .nodes
            .iter()
            .map(|x| x.map(|v| (v * 1e6).round() as i64))
            .collect();
        places.sort_unstable();
        places.dedup();
        assert_eq!(places.len(), mesh.nodes.len(), "n = {n}: coincident nodes");
        errors.push((volume(&mesh) - exact).abs() / exact);
        let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|c| (a[c] - b[c]).abs() < 2e-3 * 64.0);
        for end in ["part.theta0", "part.theta1"] {
            let f = pushed(&mesh, end);
            assert!(close(f, [0.0, 0.0, 64.0]), "n = {n} {end}: {f:?}");
        }
        let side = |end: &str| mesh.node_sets[end].iter().map(|&k| mesh.nodes[k]);
        assert!(side("part.theta0").all(|x| x[2].abs() < 1e-12 && x[0] >= -1e-12));
        assert!(side("part.theta1").all(|x| x[2].abs() < 1e-12 && x[0] <= 1e-12));
        let top = pushed(&mesh, "a.top");
        let want = -std::f64::consts::FRAC_PI_2 * 100.0;
        assert!(close(top, [0.0, want, 0.0]), "n = {n}: {top:?}");
    }
    println!("solid half cylinder: relative volume errors {errors:?}");
    assert!(errors[2] < errors[1] && errors[1] < errors[0], "{errors:?}");
    assert!(errors[2] < 1e-5, "{errors:?}");
}

/// A sphere's layout on a flat, both reaching the axis: the ball (x ≤ 3,
/// 0 ≤ y ≤ 3, its bottom the arc of radius 10 with its apex at the origin)
/// and the flat (x ≤ 4, −2 ≤ y ≤ 0) meshed apart, joined by a non-matching
/// interface, or a punch on the flat meshed alike (matching).
fn sphere_on_flat(matching: bool) -> Mesh {
    let block = |text: &str| toml::from_str::<BlockSpec>(text).unwrap();
    let ball = if matching {
        block("body = \"ball\"\nx = [0.0, 4.0]\nnx = [4]\ny = [0.0, 3.0]\nny = [2]\n")
    } else {
        block("body = \"ball\"\nx = [0.0, 3.0]\nnx = [5]\ny = [0.0, 3.0]\nny = [2]\nbottom = { radius = 10.0, center = 0.0 }\n")
    };
    let flat = block("body = \"flat\"\nx = [0.0, 4.0]\nnx = [4]\ny = [-2.0, 0.0]\nny = [2]\n");
    let contact: blocks::InterfaceSpec = toml::from_str(&format!(
        "name = \"contact\"\nupper = \"ball\"\nlower = \"flat\"\nmatching = {matching}\n"
    ))
    .unwrap();
    blocks::generate(&[ball, flat], &[contact], 1).unwrap()
}

/// The area of faces and Σ n dA over them.
fn face_area(mesh: &Mesh, faces: &[Face]) -> (f64, [f64; 3]) {
    let (mut area, mut n_da) = (0.0, [0.0; 3]);
    for f in faces {
        let x: Vec<[f64; 3]> = f.nodes().iter().map(|&k| mesh.nodes[k]).collect();
        let force = crate::physics::element::face::face_forces(f.family, &x, 1.0, [0.0; 3]);
        // a unit pressure pushes against the walked normal: −∫ n dA
        for fa in force.iter().take(f.nodes().len()) {
            for c in 0..3 {
                n_da[c] -= fa[c];
            }
        }
        for (xi, w) in f.family.rule(true).points {
            let d = f.family.shape_derivs(xi);
            let g: [[f64; 3]; 2] = std::array::from_fn(|k| {
                std::array::from_fn(|c| (0..x.len()).map(|a| d[a][k] * x[a][c]).sum())
            });
            let n = crate::numbers::vec3::cross(g[0], g[1]);
            area += w * crate::numbers::vec3::dot(n, n).sqrt();
        }
    }
    (area, n_da)
}

#[test]
fn a_sphere_on_a_flat_meshed_apart_revolves_with_its_interface_through_the_cores() {
    for (angle, n) in [(std::f64::consts::FRAC_PI_2, 4), (std::f64::consts::PI, 8)] {
        let mesh = revolve(&sphere_on_flat(false), angle, n).unwrap();
        mesh.validate().unwrap();
        // the apex of the ball and the flat's point under it: two nodes
        let bodies = mesh.node_bodies();
        let at_origin: Vec<usize> = (0..mesh.nodes.len())
            .filter(|&k| mesh.nodes[k].iter().all(|v| v.abs() < 1e-12))
            .collect();
        assert_eq!(at_origin.len(), 2, "{at_origin:?}");
        assert_ne!(bodies[at_origin[0]], bodies[at_origin[1]]);
        // every node of one body at its own place
        let mut places: Vec<(usize, [i64; 3])> = (0..mesh.nodes.len())
            .map(|k| (bodies[k], mesh.nodes[k].map(|v| (v * 1e6).round() as i64)))
            .collect();
        places.sort_unstable();
        places.dedup();
        assert_eq!(places.len(), mesh.nodes.len());
        let iface = &mesh.interfaces[0];
        assert!(iface.faces.is_empty());
        let nm = iface.nonmatching_faces.as_ref().unwrap();
        // the slave faces: the ball's cap, on its bodies' nodes, walked into
        // the ball (+y); the master faces the flat's top, walked out of it
        let a = mesh.bodies.iter().position(|b| b == "ball").unwrap();
        assert!(nm
            .slave
            .iter()
            .flat_map(|f| f.nodes())
            .all(|&k| bodies[k] == a));
        assert!(nm
            .master
            .iter()
            .flat_map(|f| f.nodes())
            .all(|&k| bodies[k] != a));
        let share = angle / (2.0 * std::f64::consts::PI);
        let (r, h) = (10.0f64, 10.0 - (100.0f64 - 9.0).sqrt());
        let (cap, n_cap) = face_area(&mesh, &nm.slave);
        let want = share * 2.0 * std::f64::consts::PI * r * h;
        assert!((cap - want).abs() < 1e-3 * want, "cap {cap} vs {want}");
        // Σ n dA over the cap: its projection on y = 0, the disk of radius 3
        let disk = share * std::f64::consts::PI * 9.0;
        assert!((n_cap[1] - disk).abs() < 1e-3 * disk, "{n_cap:?}");
        let (top, n_top) = face_area(&mesh, &nm.master);
        let want = share * std::f64::consts::PI * 16.0;
        assert!((top - want).abs() < 1e-3 * want, "top {top} vs {want}");
        assert!((n_top[1] - want).abs() < 1e-3 * want, "{n_top:?}");
        // the cap's nodes lie on the sphere about (0, 10, 0): the revolved
        // part's exactly, the core's on the layout's quadratic side through
        // the arc's three nodes
        for &k in nm.slave.iter().flat_map(|f| f.nodes()) {
            let x = mesh.nodes[k];
            let d = (x[0] * x[0] + (x[1] - 10.0).powi(2) + x[2] * x[2]).sqrt();
            let r = x[0].hypot(x[2]);
            let tol = if r < 0.6 - 1e-9 { 1e-5 } else { 1e-12 };
            assert!((d - 10.0).abs() < tol, "{x:?} at {d}");
        }
    }
}

#[test]
fn a_matching_interface_through_the_cores_pairs_their_faces_node_for_node() {
    let mesh = revolve(&sphere_on_flat(true), std::f64::consts::FRAC_PI_2, 4).unwrap();
    mesh.validate().unwrap();
    let iface = &mesh.interfaces[0];
    assert!(iface.nonmatching_faces.is_none());
    for f in &iface.faces {
        for (&a, &b) in f.a.nodes().iter().zip(f.b.nodes()) {
            assert_ne!(a, b);
            let (xa, xb) = (mesh.nodes[a], mesh.nodes[b]);
            assert!(
                (0..3).all(|c| (xa[c] - xb[c]).abs() < 1e-12),
                "{xa:?} {xb:?}"
            );
        }
    }
    // the punch's whole bottom, walked from the flat into the punch (+y)
    let faces: Vec<Face> = iface.faces.iter().map(|f| f.b.clone()).collect();
    let (area, n_da) = face_area(&mesh, &faces);
    let want = std::f64::consts::FRAC_PI_4 * 16.0;
    assert!((area - want).abs() < 1e-3 * want, "{area} vs {want}");
    assert!((n_da[1] - want).abs() < 1e-3 * want, "{n_da:?}");
}

/// `theta0` and `theta1` name every body's end at once: the union of the
/// bodies' `<body>.theta0` / `.theta1` (through the O-grid cores too), nodes
/// and faces, each face once, all in its plane (z = 0, and x = 0 for a
/// quarter), and nodes of both bodies.
#[test]
fn the_mesh_wide_end_sets_are_every_bodys_ends() {
    let mesh = revolve(&sphere_on_flat(true), std::f64::consts::FRAC_PI_2, 4).unwrap();
    let bodies = mesh.node_bodies();
    for (end, c) in [("theta0", 2), ("theta1", 0)] {
        let mut union: Vec<usize> = mesh
            .bodies
            .iter()
            .flat_map(|b| mesh.node_sets[&format!("{b}.{end}")].clone())
            .collect();
        union.sort_unstable();
        union.dedup();
        assert_eq!(mesh.node_sets[end], union, "{end}");
        let faces: usize = (mesh.bodies.iter())
            .map(|b| mesh.face_sets[&format!("{b}.{end}")].len())
            .sum();
        assert_eq!(mesh.face_sets[end].len(), faces, "{end}");
        assert!(mesh.node_sets[end]
            .iter()
            .all(|&n| mesh.nodes[n][c].abs() < 1e-9));
        for b in 0..mesh.bodies.len() {
            assert!(
                mesh.node_sets[end].iter().any(|&n| bodies[n] == b),
                "{end} {b}"
            );
        }
    }
}
