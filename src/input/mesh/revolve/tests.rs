use super::*;
// the layout and the face-set resultant of the sweep's tests
use crate::input::mesh::extrude::tests::{layout, pushed};
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
fn a_layout_on_the_axis_is_refused_but_through_a_quarter_in_an_even_number_of_layers() {
    for (angle, n) in [(std::f64::consts::PI, 4), (std::f64::consts::FRAC_PI_2, 3)] {
        let e = revolve(&layout(), angle, n).unwrap_err();
        assert!(e.0.contains("reaches the axis at (x, y) = (0, 0)"), "{e}");
        assert!(
            e.0.contains("through 90° in an even number of layers"),
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
