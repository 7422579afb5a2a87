//! The corner finder on hand-made meshes: an L (its re-entrant corner
//! found, its straight and convex corners not), a quarter ring (a curved
//! boundary: no corner; the same ring drawn by chords: its vertices), a
//! punch on a block (the contact's edge, not its mirrored middle), and
//! supports (a clamped stretch's end, a roller's right-angled corner).

use super::{find, Support};
use crate::input::mesh::{ContactEdge, Element, Interface, Mesh};
use std::collections::HashMap;

/// Q8 elements of `body` from quads given by their corners (counter-
/// clockwise) in a parameter plane, midsides halfway in that plane, every
/// node then placed by `map`; nodes shared within a body.
struct Build {
    mesh: Mesh,
    ids: HashMap<(usize, i64, i64), usize>,
}

impl Build {
    fn new(bodies: &[&str]) -> Build {
        let mesh = Mesh {
            bodies: bodies.iter().map(|b| b.to_string()).collect(),
            ..Mesh::default()
        };
        Build {
            mesh,
            ids: HashMap::new(),
        }
    }

    fn node(&mut self, body: usize, p: [f64; 2], map: &dyn Fn([f64; 2]) -> [f64; 2]) -> usize {
        let key = (
            body,
            (p[0] * 1e6).round() as i64,
            (p[1] * 1e6).round() as i64,
        );
        if let Some(&n) = self.ids.get(&key) {
            return n;
        }
        let x = map(p);
        self.mesh.nodes.push([x[0], x[1], 0.0]);
        self.ids.insert(key, self.mesh.nodes.len() - 1);
        self.mesh.nodes.len() - 1
    }

    fn quad(&mut self, body: usize, c: [[f64; 2]; 4], map: &dyn Fn([f64; 2]) -> [f64; 2]) {
        let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let mut n = [0; 8];
        for k in 0..4 {
            n[k] = self.node(body, c[k], map);
            n[4 + k] = self.node(body, mid(c[k], c[(k + 1) % 4]), map);
        }
        self.mesh.elements.push(Element::q8(n, body));
    }

    /// The unit square with lower left corner (x, y).
    fn square(&mut self, body: usize, x: f64, y: f64) {
        self.quad(
            body,
            [[x, y], [x + 1.0, y], [x + 1.0, y + 1.0], [x, y + 1.0]],
            &|p| p,
        );
    }

    /// The node of `body` at `p` (parameter plane).
    fn at(&self, body: usize, p: [f64; 2]) -> usize {
        self.ids[&(
            body,
            (p[0] * 1e6).round() as i64,
            (p[1] * 1e6).round() as i64,
        )]
    }
}

fn identity(mesh: &Mesh) -> Vec<usize> {
    (0..mesh.nodes.len()).collect()
}

/// The nodes of `mesh` where `pick` holds.
fn nodes_where(mesh: &Mesh, pick: impl Fn([f64; 3]) -> bool) -> Vec<usize> {
    (0..mesh.nodes.len())
        .filter(|&n| pick(mesh.nodes[n]))
        .collect()
}

#[test]
fn the_l_has_one_re_entrant_corner_and_no_other() {
    let mut b = Build::new(&["l"]);
    b.square(0, 0.0, 0.0);
    b.square(0, 1.0, 0.0);
    b.square(0, 0.0, 1.0);
    let found = find(&b.mesh, &identity(&b.mesh), false, &[]);
    assert_eq!(found.len(), 1, "{found:?}");
    let p = &found[0];
    assert_eq!(p.x, [1.0, 1.0, 0.0]);
    assert_eq!(p.corner, "re-entrant corner (270°)");
    assert_eq!(p.bodies, vec![0]);
    // every element touches it; the size is their diagonal
    assert_eq!(p.elements, vec![0, 1, 2]);
    assert!((p.size - 2f64.sqrt()).abs() < 1e-12);
    // its mirror image (the L turned the other way) is found alike: the
    // walk's orientation is the element's, not the picture's
    let mut b = Build::new(&["l"]);
    b.square(0, 0.0, 0.0);
    b.square(0, 1.0, 0.0);
    b.square(0, 1.0, 1.0);
    let found = find(&b.mesh, &identity(&b.mesh), false, &[]);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].x, [1.0, 1.0, 0.0]);
}

/// A quarter ring r in [1, 2], θ in [0, 90°] of two elements along θ;
/// `curved`: its midsides on the arcs, else halfway along the chords.
fn ring(curved: bool) -> Mesh {
    let polar = |p: [f64; 2]| [p[0] * p[1].cos(), p[0] * p[1].sin()];
    let mut b = Build::new(&["ring"]);
    let h = std::f64::consts::FRAC_PI_4;
    for k in 0..2 {
        let (t0, t1) = (k as f64 * h, (k + 1) as f64 * h);
        b.quad(0, [[1.0, t0], [2.0, t0], [2.0, t1], [1.0, t1]], &polar);
    }
    if !curved {
        // every midside on its chord
        for el in b.mesh.elements.clone() {
            let n = el.nodes();
            for k in 0..4 {
                let (a, c) = (b.mesh.nodes[n[k]], b.mesh.nodes[n[(k + 1) % 4]]);
                b.mesh.nodes[n[4 + k]] = [(a[0] + c[0]) / 2.0, (a[1] + c[1]) / 2.0, 0.0];
            }
        }
    }
    b.mesh
}

#[test]
fn a_curved_boundary_has_no_corner_but_its_polygon_has() {
    // the inner arc bends away from the body (a fillet's shape): its middle
    // node is no corner, and the ring's four right angles are convex
    let mesh = ring(true);
    let found = find(&mesh, &identity(&mesh), false, &[]);
    assert!(found.is_empty(), "{found:?}");
    // drawn by chords, the inner arc's middle vertex turns by 45°: 225°
    let mesh = ring(false);
    let found = find(&mesh, &identity(&mesh), false, &[]);
    assert_eq!(found.len(), 1, "{found:?}");
    let x = found[0].x;
    assert!((x[0] - 0.5f64.sqrt()).abs() < 1e-12 && (x[1] - 0.5f64.sqrt()).abs() < 1e-12);
    assert_eq!(found[0].corner, "re-entrant corner (225°)");
}

#[test]
fn a_punch_on_a_block_is_singular_at_its_edge_not_on_its_mirror() {
    // punch (body 1) [0, 1] × [0, 1] on a block (body 0) [0, 2] × [−1, 0],
    // the interface along y = 0 from x = 0 to 1, a symmetry line at x = 0
    let mut b = Build::new(&["block", "punch"]);
    b.square(0, 0.0, -1.0);
    b.square(0, 1.0, -1.0);
    b.square(1, 0.0, 0.0);
    let pair = |body: usize, b: &Build| [0.0, 0.5, 1.0].map(|x| b.at(body, [x, 0.0]));
    let edges = vec![ContactEdge {
        a: pair(1, &b),
        b: pair(0, &b),
    }];
    b.mesh.interfaces.push(Interface {
        name: "contact".into(),
        body_a: 1,
        body_b: 0,
        edges,
        nonmatching: None,
        ..Default::default()
    });
    let mesh = &b.mesh;
    let left = nodes_where(mesh, |x| x[0] == 0.0);
    let bottom = nodes_where(mesh, |x| x[1] == -1.0);
    let supports = [
        Support {
            name: "boundary[0]".into(),
            nodes: left.clone(),
            held: [true, false, false],
        },
        Support {
            name: "boundary[1]".into(),
            nodes: bottom,
            held: [false, true, false],
        },
    ];
    let found = find(mesh, &identity(mesh), false, &supports);
    assert_eq!(found.len(), 1, "{found:?}");
    let p = &found[0];
    assert_eq!(p.x, [1.0, 0.0, 0.0]);
    assert_eq!(p.corner, "end of contact interface contact");
    // both bodies; the punch's element and the block's two
    let mut bodies = p.bodies.clone();
    bodies.sort_unstable();
    assert_eq!(bodies, vec![0, 1]);
    assert_eq!(p.elements, vec![0, 1, 2]);
    // without the symmetry line the punch's other edge is singular too
    let found = find(mesh, &identity(mesh), false, &supports[1..]);
    let places: Vec<[f64; 3]> = found.iter().map(|p| p.x).collect();
    assert!(places.contains(&[0.0, 0.0, 0.0]), "{found:?}");
}

#[test]
fn a_support_is_singular_where_it_ends_on_a_straight_or_clamped_edge() {
    // a block [0, 2] × [0, 1] of two elements
    let mut b = Build::new(&["block"]);
    b.square(0, 0.0, 0.0);
    b.square(0, 1.0, 0.0);
    let mesh = &b.mesh;
    let run = |nodes: Vec<usize>, held: [bool; 3]| {
        let s = [Support {
            name: "boundary[0]".into(),
            nodes,
            held,
        }];
        let found = find(mesh, &identity(mesh), false, &s);
        found
            .into_iter()
            .map(|p| (p.x[0], p.x[1], p.corner))
            .collect::<Vec<_>>()
    };
    let bottom = nodes_where(mesh, |x| x[1] == 0.0);
    // a roller under the whole bottom meets the free sides at right angles
    assert!(run(bottom.clone(), [false, true, false]).is_empty());
    // clamped, its ends at the corners are singular
    let got = run(bottom.clone(), [true, true, false]);
    assert_eq!(got.len(), 2, "{got:?}");
    assert!(got.contains(&(0.0, 0.0, "edge of support boundary[0]".into())));
    assert!(got.contains(&(2.0, 0.0, "edge of support boundary[0]".into())));
    // a roller under half the bottom ends on the straight edge at x = 1
    let half = nodes_where(mesh, |x| x[1] == 0.0 && x[0] <= 1.0);
    let got = run(half, [false, true, false]);
    assert_eq!(got, vec![(1.0, 0.0, "edge of support boundary[0]".into())]);
    // one node held alone is a point support
    let one = nodes_where(mesh, |x| x[1] == 0.0 && x[0] == 1.0);
    let got = run(one, [false, true, false]);
    assert_eq!(got, vec![(1.0, 0.0, "point support boundary[0]".into())]);
}

#[test]
fn the_axis_is_no_corner_and_a_cut_is_no_outline() {
    // the L with its arm along the axis x = 0, a support point on the axis
    let mut b = Build::new(&["l"]);
    b.square(0, 0.0, 0.0);
    b.square(0, 1.0, 0.0);
    b.square(0, 0.0, 1.0);
    // cut the L between its lower squares: the right square takes copies
    // of the nodes on x = 1, y in [0, 1]
    let mut origin = identity(&b.mesh);
    let on_cut: Vec<usize> = nodes_where(&b.mesh, |x| x[0] == 1.0 && x[1] <= 1.0);
    for &n in &on_cut {
        let copy = b.mesh.nodes.len();
        b.mesh.nodes.push(b.mesh.nodes[n]);
        origin.push(n);
        for v in b.mesh.elements[1].nodes_mut() {
            if *v == n {
                *v = copy;
            }
        }
    }
    let found = find(&b.mesh, &origin, true, &[]);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].x, [1.0, 1.0, 0.0]);
    let axis = nodes_where(&b.mesh, |x| x[0] == 0.0 && x[1] == 0.0);
    let s = [Support {
        name: "boundary[0]".into(),
        nodes: axis,
        held: [false, true, false],
    }];
    // the point support on the axis is no singular point there
    assert_eq!(find(&b.mesh, &origin, true, &s).len(), 1);
    // in a plane model it is
    assert_eq!(find(&b.mesh, &origin, false, &s).len(), 2);
}

#[test]
fn hanging_nodes_leave_the_outline_as_it_was() {
    // the L with its corner square split in four: the split edges (a coarse
    // side beside two fine ones) are inside, the corner still found alone
    let mut b = Build::new(&["l"]);
    for (x, y) in [(0.0, 0.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)] {
        b.quad(
            0,
            [[x, y], [x + 0.5, y], [x + 0.5, y + 0.5], [x, y + 0.5]],
            &|p| p,
        );
    }
    b.square(0, 1.0, 0.0);
    b.square(0, 0.0, 1.0);
    let found = find(&b.mesh, &identity(&b.mesh), false, &[]);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].x, [1.0, 1.0, 0.0]);
    assert_eq!(found[0].corner, "re-entrant corner (270°)");
}
