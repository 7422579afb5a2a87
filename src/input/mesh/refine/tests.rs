use super::*;
use crate::input::mesh::blocks;
use crate::input::mesh::Element;

/// A mesh of `nx` × `ny` unit squares from the block generator (with a
/// `bottom` edge set and node set), through the case parser.
fn grid(nx: usize, ny: usize) -> Mesh {
    let text = format!(
        "[[block]]\nbody = \"b\"\nx = [0.0, {nx}.0]\nnx = [{nx}]\ny = [0.0, {ny}.0]\nny = [{ny}]\n"
    );
    let spec: crate::input::case::MeshSpec = toml::from_str(&text).unwrap();
    blocks::generate(&spec.block, &spec.interface, 1).unwrap()
}

#[test]
fn edge_shape_is_the_quadratic_interpolant() {
    assert_eq!(edge_shape(-0.5), [0.375, 0.75, -0.125]);
    assert_eq!(edge_shape(0.5), [-0.125, 0.75, 0.375]);
}

#[test]
fn uniform_refinement_of_a_grid_is_the_doubled_grid() {
    let mesh = grid(2, 2);
    let r = uniform(&mesh).unwrap();
    assert_eq!(r.mesh.elements.len(), 16);
    // a 4 × 4 Q8 grid: 9 × 9 points but the 16 element centres
    assert_eq!(r.mesh.nodes.len(), 81 - 16);
    assert!(r.hanging.is_empty());
    assert!(r.state.level.iter().all(|&l| l == 1));
    r.mesh.validate().unwrap();
}

/// Every hanging node of `r` sits where its coarse edge's quadratic shape
/// puts s = ∓½ (the quarter point of a straight edge).
fn hanging_nodes_lie_on_their_edges(r: &Refined) {
    for h in &r.hanging {
        let w = edge_shape(h.s);
        let x = (0..3).fold([0.0; 2], |x, i| {
            let p = r.mesh.nodes[h.edge[i]];
            [x[0] + w[i] * p[0], x[1] + w[i] * p[1]]
        });
        let q = r.mesh.nodes[h.node];
        assert!(
            (x[0] - q[0]).abs() < 1e-14 && (x[1] - q[1]).abs() < 1e-14,
            "{h:?}"
        );
    }
}

#[test]
fn one_refined_element_hangs_four_nodes_and_a_second_refinement_closes() {
    let mesh = grid(2, 2);
    let r = refine(&mesh, &[0]).unwrap();
    assert_eq!(r.mesh.elements.len(), 7);
    assert_eq!(r.hanging.len(), 4);
    r.mesh.validate().unwrap();
    hanging_nodes_lie_on_their_edges(&r);
    // refining the child at the centre again forces its coarse neighbours
    let centre = (0..7)
        .find(|&e| r.state.level[e] == 1 && r.mesh.element_coords(e)[2] == [1.0, 1.0])
        .unwrap();
    let again = r.refine(&[centre]).unwrap();
    // elements 1 and 2 (the coarse neighbours) were refined, 3 was not
    assert_eq!(again.state.level.iter().filter(|&&l| l == 0).count(), 1);
    assert_eq!(again.state.level.iter().filter(|&&l| l == 2).count(), 4);
    assert_eq!(again.mesh.elements.len(), 1 + 4 * 3 - 1 + 4);
    again.mesh.validate().unwrap();
}

#[test]
fn a_tied_pair_is_split_together() {
    // elements 0 and 2 of a 2 × 2 grid face each other across y = 1 (a
    // pretension cut's line): marking one splits both, so no node hangs
    // on that line
    let mesh = grid(2, 2);
    let below = (0..4)
        .find(|&e| mesh.element_coords(e)[0] == [0.0, 0.0])
        .unwrap();
    let above = (0..4)
        .find(|&e| mesh.element_coords(e)[0] == [0.0, 1.0])
        .unwrap();
    let alone = refine(&mesh, &[below]).unwrap();
    let on_line = |r: &Refined| {
        r.hanging
            .iter()
            .filter(|h| (r.mesh.nodes[h.node][1] - 1.0).abs() < 1e-12)
            .count()
    };
    assert_eq!(on_line(&alone), 2);
    let start = Refined::start(&mesh);
    let tied = start.refine_tied(&[below], &[(below, above)]).unwrap();
    assert_eq!(tied.mesh.elements.len(), 4 + 2 * 3);
    assert_eq!(on_line(&tied), 0);
    // the pair is refined whichever of the two is marked
    let other = start.refine_tied(&[above], &[(below, above)]).unwrap();
    assert_eq!(other.mesh.elements.len(), 10);
    assert!(start.refine_tied(&[0], &[(0, 9)]).is_err());
}

/// [`grid`] with every quad split into two 6-node triangles along its
/// diagonal 0–2 (the diagonal's midside a new node at the square's centre)
/// except the last quad: a mixed mesh.
fn triangles(nx: usize, ny: usize) -> Mesh {
    let mut mesh = grid(nx, ny);
    let quads = std::mem::take(&mut mesh.elements);
    let last = quads.len() - 1;
    for (e, el) in quads.into_iter().enumerate() {
        if e == last {
            mesh.elements.push(el);
            continue;
        }
        let q = el.nodes().to_vec();
        let (a, c) = (mesh.nodes[q[0]], mesh.nodes[q[2]]);
        mesh.nodes
            .push([(a[0] + c[0]) / 2.0, (a[1] + c[1]) / 2.0, 0.0]);
        let d = mesh.nodes.len() - 1;
        mesh.elements
            .push(Element::t6([q[0], q[1], q[2], q[4], q[5], d], el.body));
        mesh.elements
            .push(Element::t6([q[0], q[2], q[3], d, q[6], q[7]], el.body));
    }
    mesh.validate().unwrap();
    mesh
}

/// The area of a mesh by its elements' full Gauss rules.
fn area(mesh: &Mesh) -> f64 {
    (0..mesh.elements.len())
        .map(|e| {
            let f = mesh.elements[e].family;
            let c = mesh.element_coords(e);
            f.rule(true)
                .points
                .iter()
                .map(|&(xi, w)| w * f.physical_derivs(&c[..f.nodes()], xi).unwrap().0)
                .sum::<f64>()
        })
        .sum()
}

#[test]
fn uniform_refinement_of_triangles_and_quads_keeps_the_area_and_hangs_nothing() {
    let mesh = triangles(2, 2);
    assert_eq!(mesh.elements.len(), 7);
    let r = uniform(&mesh).unwrap();
    assert_eq!(r.mesh.elements.len(), 28);
    let t6 = r
        .mesh
        .elements
        .iter()
        .filter(|el| el.family == Family::T6)
        .count();
    assert_eq!(t6, 24);
    assert!(r.hanging.is_empty());
    r.mesh.validate().unwrap();
    assert!((area(&r.mesh) - 4.0).abs() < 1e-13);
    // every node once: 9 × 9 grid points less the centres of the last
    // quad's four children
    assert_eq!(r.mesh.nodes.len(), 81 - 4);
}

#[test]
fn a_refined_triangle_hangs_nodes_on_its_unrefined_neighbours() {
    let mesh = triangles(2, 2);
    // triangle 1 (upper left of the first square) borders triangle 0
    // across the diagonal and the square above it (triangle 4) and the
    // boundary
    let r = refine(&mesh, &[1]).unwrap();
    r.mesh.validate().unwrap();
    assert_eq!(r.mesh.elements.len(), 7 + 3);
    assert!((area(&r.mesh) - 4.0).abs() < 1e-13);
    assert_eq!(r.hanging.len(), 4, "{:?}", r.hanging);
    hanging_nodes_lie_on_their_edges(&r);
}
