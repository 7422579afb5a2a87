//! The cut through a 3D mesh: the sets and elements on either side of it.

use crate::input::case::Case;
use crate::model::Model;

/// A bar of 20-node hexahedra, [0, 100] × [0, 10] × [0, 10], cut by the
/// plane x = 30.
fn bar() -> Model {
    let text = r#"
[model]
plane = "3d"
[mesh]
extrude = { z = [0.0, 10.0], nz = [2] }
[[mesh.block]]
body = "bar"
x = [0.0, 30.0, 100.0]
nx = [3, 7]
y = [0.0, 10.0]
ny = [2]
[materials.bar]
young = 200000.0
poisson = 0.3
[[boundary]]
set = "bar.left"
ux = 0.0
[[boundary]]
set = "bar.right"
ux = 0.0
[[boundary]]
set = "bar.bottom"
uy = 0.0
[[boundary]]
set = "bar.zmin"
uz = 0.0
[[pretension]]
name = "bolt"
body = "bar"
x = 30.0
force = 1000.0
"#;
    Model::build(Case::parse(text, "case.toml").unwrap()).unwrap()
}

/// Every face of every face set is still a face of an element after the
/// cut (the faces beyond it take the copies with their elements), and the
/// face sets that span the cut hold faces on both sides of it.
#[test]
fn the_face_sets_across_a_cut_stay_faces_of_their_elements() {
    let m = bar();
    let mut faces = std::collections::HashSet::new();
    for el in &m.mesh.elements {
        for f in super::cut::element_sides(el) {
            let mut k = f.clone();
            k.sort_unstable();
            faces.insert(k);
        }
    }
    let copies: Vec<usize> = m.sections[0].pairs.iter().map(|p| p.1).collect();
    for name in ["bar.bottom", "bar.top", "bar.zmin", "bar.zmax"] {
        let set = &m.mesh.face_sets[name];
        let mut with_copies = 0;
        for f in set {
            let mut k = f.nodes().to_vec();
            k.sort_unstable();
            assert!(faces.contains(&k), "{name}: {k:?} is no element's face");
            with_copies += usize::from(k.iter().any(|n| copies.contains(n)));
        }
        // the faces beyond x = 30 next to the cut hold copies
        assert!(with_copies > 0, "{name}");
    }
}

/// The elements on the two sides of the cut share no node: every node of
/// the plane x = 30 (the 3 × 3 corners and 12 midsides of its four faces)
/// is doubled, and the two sides are [`super::sides`]' two pieces.
#[test]
fn the_two_sides_of_a_3d_cut_share_no_node() {
    let m = bar();
    let s = &m.sections[0];
    assert_eq!(s.pairs.len(), 21);
    let beyond = super::sides(&m.mesh, s).expect("the cut divides the bar in two");
    for (e, el) in m.mesh.elements.iter().enumerate() {
        let far = m.mesh.corner_mean(e)[0] > 30.0;
        assert!(el.nodes().iter().all(|&n| beyond[n] == far));
    }
}
