//! The patch test in 3D (issue 44): meshes of several 20-node hexahedra and
//! of 10-node tetrahedra, regular, distorted with straight edges and with
//! curved ones, every boundary node prescribed to a linear displacement
//! field, the interior solved: the interior nodes and every Gauss point's
//! stress and strain are the linear field's (Zienkiewicz, Taylor & Zhu, 7th
//! ed., sec. 9.3, the patch test as the test of consistency and stability).
//!
//! Which rule passes where: the residual of a constant stress at an inner
//! node a is Σₑ ∫ ∂N_a/∂x_j dV σ_ij, which vanishes (each element's integral
//! is ∮ N_a n_j dS, cancelling across shared faces) when the rule integrates
//! the polynomial cof(J) ∂N_a/∂ξ exactly. For the hexahedron that
//! polynomial is of degree ≤ 5 in each of ξ, η, ζ on any element (3×3×3
//! exact) and ≤ 3 on a straight-edged one (trilinear map: 2×2×2 exact); for
//! the tetrahedron of total degree 3 on a curved element (the 14-point rule)
//! and 1 on a straight-sided one (the 4-point rule). docs/elements.md
//! quotes the reduced hexahedron's miss on curved elements.

use crate::common::{self, Quiet};
use asperity::input::mesh::{Element, Family};
use asperity::model::Model;
use asperity::solve::State;

/// The box [0, 3]³: 3 × 3 × 3 hexahedra graded along x and z.
const BOX: f64 = 3.0;

/// The displacement gradient G of [`field`], × 1e-3 (not symmetric: a
/// rotation besides the strain).
const G: [[f64; 3]; 3] = [[2.0, -0.7, 0.5], [0.4, 1.1, -0.3], [-0.6, 0.8, 1.5]];

/// The displacement field u = u₀ + G x.
fn field(x: [f64; 3]) -> [f64; 3] {
    let u0 = [0.01, -0.02, 0.015];
    std::array::from_fn(|i| u0[i] + 1e-3 * (0..3).map(|j| G[i][j] * x[j]).sum::<f64>())
}

/// The field's strain [ε_xx, ε_yy, γ_xy, ε_zz, γ_xz, γ_yz] (the element's
/// Voigt order, engineering shears).
fn field_strain() -> [f64; 6] {
    let g = |i: usize, j: usize| 1e-3 * G[i][j];
    [
        g(0, 0),
        g(1, 1),
        g(0, 1) + g(1, 0),
        g(2, 2),
        g(0, 2) + g(2, 0),
        g(1, 2) + g(2, 1),
    ]
}

const E: f64 = 100000.0;
const NU: f64 = 0.25;

/// Hooke: σ = λ tr ε 1 + 2G ε in the Voigt order (shears γ).
fn hooke(eps: [f64; 6]) -> [f64; 6] {
    let lam = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    let g = E / (2.0 * (1.0 + NU));
    let tr = eps[0] + eps[1] + eps[3];
    [
        lam * tr + 2.0 * g * eps[0],
        lam * tr + 2.0 * g * eps[1],
        g * eps[2],
        lam * tr + 2.0 * g * eps[3],
        g * eps[4],
        g * eps[5],
    ]
}

/// Hooke inverted: ε = ((1 + ν) σ − ν tr σ 1)/E, γ = σ_ij/G.
fn compliance(s: [f64; 6]) -> [f64; 6] {
    let g = E / (2.0 * (1.0 + NU));
    let tr = s[0] + s[1] + s[3];
    let normal = |v: f64| ((1.0 + NU) * v - NU * tr) / E;
    [
        normal(s[0]),
        normal(s[1]),
        s[2] / g,
        normal(s[3]),
        s[4] / g,
        s[5] / g,
    ]
}

/// The 3D model of the swept box (27 hexahedra, 208 nodes), elastic, at
/// `integration`; its own supports (a face held, the opposite one moved) are replaced
/// by the test.
fn box_model(integration: &str) -> Model {
    common::model(&format!(
        r#"
[model]
plane = "3d"
integration = "{integration}"
[mesh]
extrude = {{ z = [0.0, {BOX}], nz = [3], rz = [0.6] }}
[[mesh.block]]
body = "b"
x = [0.0, {BOX}]
nx = [3]
rx = [1.8]
y = [0.0, {BOX}]
ny = [3]
[materials.b]
young = {E}
poisson = {NU}
[[boundary]]
set = "b.left"
ux = 0.0
uy = 0.0
uz = 0.0
[[boundary]]
set = "b.right"
ux = 0.01
[solver]
load_factors = [1.0]
residual_tolerance = 1e-13
displacement_tolerance = 1e-14
[output]
vtu = false
"#
    ))
}

/// Whether x lies on the box's boundary.
fn on_boundary(x: [f64; 3]) -> bool {
    x.iter().any(|&v| v == 0.0 || v == BOX)
}

/// A smooth displacement of the box's interior, 0 on its boundary, up to
/// about a quarter of an element.
fn warp(x: [f64; 3]) -> [f64; 3] {
    let bubble = x.iter().map(|&v| v * (BOX - v)).product::<f64>() / (BOX / 2.0).powi(6);
    let [p, q, r] = x;
    [
        0.28 * bubble * (1.3 * p + 0.7 * q + 2.1 * r).sin(),
        0.25 * bubble * (0.9 * p - 1.7 * q + 0.4 * r).cos(),
        0.27 * bubble * (2.3 * p + 1.1 * q - 0.8 * r).sin(),
    ]
}

/// How the mesh is moved off the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Shape {
    /// As made (the hexahedra graded, their faces flat).
    Regular,
    /// Every inner corner node moved by [`warp`], each midside node at the
    /// middle of its moved edge: distorted, straight edges.
    Straight,
    /// Every inner node moved by [`warp`], midsides included: curved edges
    /// and faces.
    Curved,
}

/// Moves the model's nodes as `shape` says; the boundary stays (its faces
/// are planes, [`warp`] vanishes there). Each midside node's edge is found
/// as the pair of its element's corners it lies midway between on the
/// unmoved mesh (checked to be there). Returns the largest move.
fn distort(model: &mut Model, shape: Shape) -> f64 {
    let x0 = model.mesh.nodes.clone();
    if shape == Shape::Regular {
        return 0.0;
    }
    let mut moved = x0.clone();
    for (n, x) in moved.iter_mut().enumerate() {
        if !on_boundary(x0[n]) {
            let d = warp(x0[n]);
            *x = std::array::from_fn(|i| x0[n][i] + d[i]);
        }
    }
    if shape == Shape::Straight {
        let mut edge_of = std::collections::HashMap::new();
        for el in &model.mesh.elements {
            let (corners, nodes) = (el.corners(), el.nodes());
            for &m in &nodes[corners.len()..] {
                let pair = corners
                    .iter()
                    .flat_map(|&i| corners.iter().map(move |&j| (i, j)))
                    .find(|&(i, j)| {
                        i < j
                            && (0..3)
                                .all(|k| (0.5 * (x0[i][k] + x0[j][k]) - x0[m][k]).abs() < 1e-12)
                    })
                    .unwrap_or_else(|| panic!("midside node {m} is no edge's middle"));
                edge_of.insert(m, pair);
            }
        }
        for (&m, &(i, j)) in &edge_of {
            moved[m] = std::array::from_fn(|k| 0.5 * (moved[i][k] + moved[j][k]));
        }
    }
    let shift = moved
        .iter()
        .zip(&x0)
        .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
        .fold(0.0f64, f64::max);
    assert!(shift > 0.1, "{shape:?}: largest move {shift}");
    model.mesh.nodes = moved;
    shift
}

/// Every boundary node of the model prescribed to [`field`] in place of the
/// case's supports (and no load); solved.
fn solve_field(mut model: Model) -> (Model, State) {
    let nodes = model.mesh.nodes.clone();
    model.prescribed = (0..nodes.len())
        .filter(|&n| on_boundary(nodes[n]))
        .flat_map(|n| {
            let u = field(nodes[n]);
            (0..3).map(move |c| (3 * n + c, u[c]))
        })
        .collect();
    model.prescribed_history = vec![None; model.prescribed.len()];
    model.loads.clear();
    model.f_ext = vec![0.0; 3 * nodes.len()];
    model.probe_node = 0;
    model.set_constraints(Vec::new()).unwrap();
    let free = nodes.iter().filter(|&&x| !on_boundary(x)).count();
    assert!(free >= 8, "{free} inner nodes");
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"));
    (model, r.final_state)
}

/// The largest errors of a solved patch: of the nodes' displacements
/// relative to the largest |u|, of the Gauss points' stresses relative to
/// the largest |σ|, of their strains relative to the largest |ε| (the
/// state keeps the stress: the strain is the stress through the inverse of
/// Hooke's law, the body being elastic).
fn errors(model: &Model, s: &State) -> [f64; 3] {
    let eps = field_strain();
    let sig = hooke(eps);
    let amax = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let u_scale = amax(
        &model
            .mesh
            .nodes
            .iter()
            .flat_map(|&x| field(x))
            .collect::<Vec<_>>(),
    );
    let mut du: f64 = 0.0;
    for (n, &x) in model.mesh.nodes.iter().enumerate() {
        for (c, want) in field(x).into_iter().enumerate() {
            du = du.max((s.u[3 * n + c] - want).abs() / u_scale);
        }
    }
    let (mut ds, mut de): (f64, f64) = (0.0, 0.0);
    let mut points = 0;
    for g in s.gauss.iter() {
        let got_eps = compliance(g.stress);
        for k in 0..6 {
            ds = ds.max((g.stress[k] - sig[k]).abs() / amax(&sig));
            de = de.max((got_eps[k] - eps[k]).abs() / amax(&eps));
        }
        points += 1;
    }
    let per = model.points(0).len();
    assert_eq!(points, model.mesh.elements.len() * per);
    [du, ds, de]
}

/// Several 20-node hexahedra (the swept box, 27 elements graded along x and
/// z), regular, distorted with straight edges, and curved: a linear field
/// at every inner node and the constant stress and strain at every Gauss
/// point to 1e-10, with 3×3×3 points on all three, with 2×2×2 on the
/// straight-edged two. The control: 2×2×2 on the curved mesh, which it does
/// not integrate exactly (module text), misses by far more.
#[test]
fn solid_patch_of_hexahedra_reproduces_a_linear_field() {
    // measured: exact cases at most 3.5e-15, 4.3e-14, 9.9e-14 (nodes, stress,
    // strain); the control 8.6e-4, 8.3e-3, 2.9e-2
    patch_runs("H20", 27, &|m| {
        assert!(m.mesh.elements.iter().all(|e| e.family == Family::H20))
    });
}

/// The box's 3 × 3 × 3 cells (graded breakpoints) each cut into the six
/// tetrahedra about its diagonal from the low corner (Freudenthal: the cuts
/// of neighbouring cells meet on their common face), 162 10-node
/// tetrahedra, each midside node at its edge's middle: in place of the
/// swept hexahedra of `model`.
fn tetrahedra(model: &mut Model) {
    let grid = [
        [0.0, 0.8, 1.8, BOX],
        [0.0, 1.0, 2.0, BOX],
        [0.0, 1.3, 2.2, BOX],
    ];
    let corner = |i: [usize; 3]| i[0] + 4 * i[1] + 16 * i[2];
    let mut nodes: Vec<[f64; 3]> = (0..64)
        .map(|n| [grid[0][n % 4], grid[1][(n / 4) % 4], grid[2][n / 16]])
        .collect();
    let mut mids = std::collections::HashMap::new();
    let mut tets = Vec::new();
    for cell in 0..27 {
        let low = [cell % 3, (cell / 3) % 3, cell / 9];
        for axes in [
            [0, 1, 2],
            [0, 2, 1],
            [1, 0, 2],
            [1, 2, 0],
            [2, 0, 1],
            [2, 1, 0],
        ] {
            let mut at = low;
            let mut c = vec![corner(at)];
            for a in axes {
                at[a] += 1;
                c.push(corner(at));
            }
            // positive volume: (x1 − x0) × (x2 − x0) · (x3 − x0) > 0
            let d =
                |k: usize| -> [f64; 3] { std::array::from_fn(|i| nodes[c[k]][i] - nodes[c[0]][i]) };
            let (e1, e2, e3) = (d(1), d(2), d(3));
            let volume = e3[0] * (e1[1] * e2[2] - e1[2] * e2[1])
                + e3[1] * (e1[2] * e2[0] - e1[0] * e2[2])
                + e3[2] * (e1[0] * e2[1] - e1[1] * e2[0]);
            if volume < 0.0 {
                c.swap(1, 2);
            }
            // midsides 0–1, 1–2, 2–0, 0–3, 1–3, 2–3 (VTK's quadratic tetra)
            for (i, j) in [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)] {
                let key = (c[i].min(c[j]), c[i].max(c[j]));
                let m = *mids.entry(key).or_insert_with(|| {
                    nodes.push(std::array::from_fn(|k| {
                        0.5 * (nodes[c[i]][k] + nodes[c[j]][k])
                    }));
                    nodes.len() - 1
                });
                c.push(m);
            }
            tets.push(Element::new(Family::T10, &c, 0));
        }
    }
    model.mesh.nodes = nodes;
    model.set_elements(tets);
    model.mesh.node_sets.clear();
    model.mesh.edge_sets.clear();
    model.mesh.face_sets.clear();
}

/// 162 10-node tetrahedra filling the box (six per graded cell), regular,
/// distorted with straight edges, and curved: a linear field at every inner
/// node and the constant stress and strain at every Gauss point to 1e-10,
/// with 14 points on all three, with 4 on the straight-sided two. The
/// control: 4 points on the curved mesh (degree 2, the integrand's 3)
/// miss by far more.
#[test]
fn solid_patch_of_tetrahedra_reproduces_a_linear_field() {
    // measured: exact cases at most 1.9e-15, 4.5e-14, 9.5e-14 (nodes, stress,
    // strain); the control 2.1e-4, 5.0e-3, 9.8e-3
    patch_runs("T10", 162, &tetrahedra);
}

/// Both rules on the three shapes of the box made by `make` (`count`
/// elements): every run exact to 1e-10 but the reduced rule on the curved
/// mesh, which must miss (nodes above 1e-5, stress above 1e-4).
fn patch_runs(label: &str, count: usize, make: &dyn Fn(&mut Model)) {
    let runs = [
        ("full", Shape::Regular),
        ("full", Shape::Straight),
        ("full", Shape::Curved),
        ("reduced", Shape::Regular),
        ("reduced", Shape::Straight),
        ("reduced", Shape::Curved),
    ];
    for (integration, shape) in runs {
        let mut model = box_model(integration);
        make(&mut model);
        assert_eq!(model.mesh.elements.len(), count);
        let shift = distort(&mut model, shape);
        let (model, s) = solve_field(model);
        let [du, ds, de] = errors(&model, &s);
        println!(
            "{label} patch, {integration}, {shape:?} (moved up to {shift:.3} mm): nodes {du:.1e}, stress {ds:.1e}, strain {de:.1e}"
        );
        if (integration, shape) == ("reduced", Shape::Curved) {
            assert!(
                du > 1e-5 && ds > 1e-4,
                "{label}: the reduced rule on a curved mesh"
            );
        } else {
            assert!(
                du < 1e-10 && ds < 1e-10 && de < 1e-10,
                "{label} {integration} {shape:?}"
            );
        }
    }
}
