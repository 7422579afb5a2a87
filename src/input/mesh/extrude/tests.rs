use super::*;
use crate::input::mesh::blocks::{self, BlockSpec};
use crate::physics::element::face::face_forces;
use crate::physics::element::solid3::{ElementGeometry3, Family3};

/// Two blocks of one body side by side (x in [0, 10] and [10, 16]),
/// y in [0, 4], graded.
fn layout() -> Mesh {
    let block = |name: &str, x: [f64; 2], nx: usize| {
        let toml = format!(
            "body = \"part\"\nname = \"{name}\"\nx = [{}, {}]\nnx = [{nx}]\nrx = [1.5]\ny = [0.0, 4.0]\nny = [3]\n",
            x[0], x[1]
        );
        toml::from_str::<BlockSpec>(&toml).unwrap()
    };
    blocks::generate(
        &[block("a", [0.0, 10.0], 4), block("b", [10.0, 16.0], 2)],
        &[],
        1,
    )
    .unwrap()
}

#[test]
fn a_swept_layout_is_a_valid_mesh_of_the_right_volume() {
    let plane = layout();
    let zs = [0.0, 1.0, 3.0];
    let mesh = extrude(&plane, &zs).unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.dim(), 3);
    assert_eq!(mesh.elements.len(), 2 * plane.elements.len());
    let corners = plane
        .nodes
        .iter()
        .enumerate()
        .filter(|(n, _)| plane.elements.iter().any(|el| el.corners().contains(n)))
        .count();
    // every plane node on the 3 planes, the corners also on the 2 midplanes
    assert_eq!(mesh.nodes.len(), 3 * plane.nodes.len() + 2 * corners);
    let rule = Family3::H20.rule(true);
    let volume: f64 = (0..mesh.elements.len())
        .map(|e| {
            let c = mesh.element_coords3(e);
            ElementGeometry3::new(Family3::H20, &c[..20], &rule)
                .unwrap()
                .volume()
        })
        .sum();
    assert!((volume - 16.0 * 4.0 * 3.0).abs() < 1e-10, "{volume}");
}

/// The resultant of a unit pressure on a face set: −(outward normal) ×
/// its area.
fn pushed(mesh: &Mesh, set: &str) -> [f64; 3] {
    let mut total = [0.0; 3];
    for face in &mesh.face_sets[set] {
        let x: Vec<[f64; 3]> = face.nodes().iter().map(|&n| mesh.nodes[n]).collect();
        let f = face_forces(face.family, &x, 1.0, [0.0; 3]);
        for fa in f.iter().take(face.nodes().len()) {
            for c in 0..3 {
                total[c] += fa[c];
            }
        }
    }
    total
}

#[test]
fn face_sets_are_the_swept_sides_and_the_ends_walked_outward() {
    let mesh = extrude(&layout(), &[0.0, 1.0, 3.0]).unwrap();
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|c| (a[c] - b[c]).abs() < 1e-10);
    // sides: a.left at x = 0 (outward −x), b.right at x = 16, the tops
    assert!(close(pushed(&mesh, "a.left"), [4.0 * 3.0, 0.0, 0.0]));
    assert!(close(pushed(&mesh, "b.right"), [-4.0 * 3.0, 0.0, 0.0]));
    assert!(close(pushed(&mesh, "a.top"), [0.0, -10.0 * 3.0, 0.0]));
    assert!(close(pushed(&mesh, "b.bottom"), [0.0, 6.0 * 3.0, 0.0]));
    // ends of each block and of the body
    assert!(close(pushed(&mesh, "a.zmin"), [0.0, 0.0, 10.0 * 4.0]));
    assert!(close(pushed(&mesh, "b.zmax"), [0.0, 0.0, -6.0 * 4.0]));
    assert!(close(pushed(&mesh, "part.zmax"), [0.0, 0.0, -16.0 * 4.0]));
    // a node set is its nodes through the whole depth
    let left = &mesh.node_sets["a.left"];
    assert!(left.iter().all(|&n| mesh.nodes[n][0].abs() < 1e-12));
    assert_eq!(left.len(), 7 * 3 + 4 * 2);
    let zmax = &mesh.node_sets["part.zmax"];
    assert!(zmax.iter().all(|&n| (mesh.nodes[n][2] - 3.0).abs() < 1e-12));
}

#[test]
fn a_layout_with_a_triangle_is_refused() {
    let mut plane = layout();
    plane.elements[0] = Element::t6([0, 1, 2, 3, 4, 5], 0);
    let e = extrude(&plane, &[0.0, 1.0]).unwrap_err();
    assert!(e.0.contains("6-node triangle"), "{e}");
}

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
fn a_layout_on_the_axis_is_refused_by_the_revolution() {
    let e = revolve(&layout(), std::f64::consts::FRAC_PI_2, 4).unwrap_err();
    assert!(e.0.contains("reaches the axis at (x, y) = (0,"), "{e}");
}
