use super::*;
use crate::input::mesh::blocks::{self, BlockSpec};
use crate::physics::element::face::face_forces;
use crate::physics::element::solid3::{ElementGeometry3, Family3};

/// Two blocks of one body side by side (x in [0, 10] and [10, 16]),
/// y in [0, 4], graded.
pub(crate) fn layout() -> Mesh {
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
pub(crate) fn pushed(mesh: &Mesh, set: &str) -> [f64; 3] {
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
