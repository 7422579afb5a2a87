//! Local refinement with hanging nodes (`[mesh] refine_region`,
//! `asperity::input::mesh::refine`): the hanging-node constraints u_q = Σ N_i(s) u_i
//! pass the patch test (plane strain, axisymmetric) and carry an exact
//! quadratic field (pure bending); the closure keeps the mesh 1-irregular;
//! a matching interface stays matching (both sides refined together).

use crate::common::{self, Quiet};
use asperity::input::mesh::refine::{self, edge_shape, Refined};
use asperity::input::mesh::Mesh;
use asperity::model::Model;
use asperity::solve::State;

/// `[mesh] refine_region` as TOML text.
fn region(x: [f64; 2], y: [f64; 2], levels: usize) -> String {
    format!("[mesh]\nrefine_region = {{ x = {x:?}, y = {y:?}, levels = {levels} }}")
}

/// A block [x0, x0 + 4] × [0, 4] of 4 × 4 elements graded in x, the elements
/// in [x0, x0 + 1.5] × [0, 1.5] refined twice (with the closure: levels 0, 1
/// and 2 side by side), held at the bottom only (the test prescribes the
/// whole boundary itself).
fn refined_block(plane: &str, x0: f64) -> Model {
    let text = common::case()
        .plane(plane)
        .raw(&region([x0, x0 + 1.5], [0.0, 1.5], 2))
        .block("b", [x0, x0 + 4.0], [4], [0.0, 4.0], [4])
        .rx([1.4])
        .material("b", 100000.0, 0.25)
        .fixed("b.bottom")
        .uy("b.top", -0.01)
        .solver("load_factors = [1.0]")
        .tolerances(1e-12, 1e-14)
        .no_vtu()
        .build();
    common::model(&text)
}

/// Every boundary node of the block prescribed to `exact` (in place of the
/// case's supports), the constraints and the dof map rebuilt; solved.
fn solve_prescribed(mut model: Model, exact: impl Fn([f64; 2]) -> [f64; 2]) -> (Model, State) {
    let nodes: Vec<[f64; 2]> = (0..model.mesh.nodes.len())
        .map(|n| model.mesh.xy(n))
        .collect();
    let (lo, hi) = nodes
        .iter()
        .fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(l, h), p| {
            (
                [l[0].min(p[0]), l[1].min(p[1])],
                [h[0].max(p[0]), h[1].max(p[1])],
            )
        });
    let on = |p: [f64; 2]| p[0] == lo[0] || p[0] == hi[0] || p[1] == lo[1] || p[1] == hi[1];
    model.prescribed = (0..nodes.len())
        .filter(|&n| on(nodes[n]))
        .flat_map(|n| {
            let u = exact(nodes[n]);
            [(2 * n, u[0]), (2 * n + 1, u[1])]
        })
        .collect();
    model.prescribed_history = vec![None; model.prescribed.len()];
    model
        .set_constraints(model.constraints.list.clone())
        .unwrap();
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"));
    (model, r.final_state)
}

/// The hanging nodes of the model's mesh, checked present.
fn hanging(mesh: &Mesh) -> Vec<usize> {
    let h: Vec<usize> = refine::hanging_nodes(mesh).iter().map(|h| h.node).collect();
    assert!(h.len() >= 8, "the mesh has {} hanging nodes", h.len());
    h
}

/// Every node's displacement equals `exact` to `tol` (relative to the
/// largest displacement).
fn assert_nodes(model: &Model, st: &State, exact: impl Fn([f64; 2]) -> [f64; 2], tol: f64) {
    let scale = model
        .mesh
        .nodes
        .iter()
        .flat_map(|&[x, y, _]| exact([x, y]))
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for (n, &[x, y, _]) in model.mesh.nodes.iter().enumerate() {
        for (c, want) in exact([x, y]).into_iter().enumerate() {
            let got = st.u[2 * n + c];
            assert!(
                (got - want).abs() <= tol * scale,
                "node {n} at ({x}, {y}): u{c} = {got:e}, exact {want:e}"
            );
        }
    }
}

/// A linear field (constant stress) on a mesh with levels 0, 1, 2 side by
/// side is reproduced at every node, hanging ones included, and every Gauss
/// point's stress is the constant one, to 1e-10 relative.
#[test]
fn patch_test_passes_across_hanging_nodes_plane_strain_and_axisymmetric() {
    let (e, nu) = (100000.0, 0.25);
    let (lam, mu) = (
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        e / (2.0 * (1.0 + nu)),
    );
    // plane strain: any linear field ([`strain_field`])
    let (exx, eyy, gxy) = (2e-3, 1.1e-3, 0.4e-3 - 0.7e-3);
    let want_strain = [
        lam * (exx + eyy) + 2.0 * mu * exx,
        lam * (exx + eyy) + 2.0 * mu * eyy,
        mu * gxy,
        lam * (exx + eyy),
    ];
    // axisymmetric (x = r ≥ 1): [`axi_field`]
    let (er, ez) = (1.5e-3, -0.8e-3);
    let want_axi = [
        lam * (2.0 * er + ez) + 2.0 * mu * er,
        lam * (2.0 * er + ez) + 2.0 * mu * ez,
        0.0,
        lam * (2.0 * er + ez) + 2.0 * mu * er,
    ];
    type Field = fn([f64; 2]) -> [f64; 2];
    let cases: [(&str, f64, Field, [f64; 4]); 2] = [
        ("strain", 0.0, strain_field, want_strain),
        ("axisymmetric", 1.0, axi_field, want_axi),
    ];
    for (plane, x0, field, want) in cases {
        let model = refined_block(plane, x0);
        let levels = refine::in_box(
            &base_mesh(plane, x0),
            [x0, x0 + 1.5],
            [0.0, 1.5],
            2,
            1 << 20,
        )
        .unwrap()
        .state
        .level;
        assert!((0..=2).all(|l| levels.contains(&l)), "levels {levels:?}");
        hanging(&model.mesh);
        let (model, st) = solve_prescribed(model, field);
        assert_nodes(&model, &st, field, 1e-12);
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (k, g) in st.gauss.iter().enumerate() {
            for (c, want) in want.iter().enumerate() {
                assert!(
                    (g.stress[c] - want).abs() < 1e-10 * scale,
                    "{plane}: Gauss point {k}: σ{c} = {} vs {want}",
                    g.stress[c]
                );
            }
        }
    }
}

fn strain_field(p: [f64; 2]) -> [f64; 2] {
    [
        1e-3 * (2.0 * p[0] - 0.7 * p[1]) + 0.01,
        1e-3 * (0.4 * p[0] + 1.1 * p[1]) - 0.02,
    ]
}

/// u_r = a r, u_z = c z + d: σ_r = σ_θ and no shear, a constant stress in
/// equilibrium without a body force (u_r linear in z would not be: τ/r).
fn axi_field(p: [f64; 2]) -> [f64; 2] {
    [1.5e-3 * p[0], -0.8e-3 * p[1] + 0.01]
}

/// The block's mesh before refinement (the same case without the region).
fn base_mesh(plane: &str, x0: f64) -> Mesh {
    let text = common::case()
        .plane(plane)
        .block("b", [x0, x0 + 4.0], [4], [0.0, 4.0], [4])
        .rx([1.4])
        .material("b", 100000.0, 0.25)
        .fixed("b.bottom")
        .uy("b.top", -0.01)
        .no_vtu()
        .build();
    common::model(&text).mesh
}

/// Pure bending in plane stress, u_x = κ x y, u_y = −κ (x² + ν y²)/2: a
/// quadratic field (in the Q8 space, zero body force, σ_xx = E κ y, σ_yy =
/// τ = 0) prescribed on the boundary of a locally refined mesh is the
/// solution at every node, the hanging nodes (the constraint's values)
/// included, to round-off; so is σ_xx at every Gauss point.
#[test]
fn pure_bending_is_exact_at_every_node_including_hanging_ones() {
    let (e, nu, k) = (100000.0, 0.25, 2e-4);
    let field = move |p: [f64; 2]| {
        [
            k * p[0] * (p[1] - 2.0),
            -0.5 * k * (p[0] * p[0] + nu * (p[1] - 2.0) * (p[1] - 2.0)),
        ]
    };
    let model = refined_block("stress", 0.0);
    let hang = hanging(&model.mesh);
    let (model, st) = solve_prescribed(model, field);
    assert_nodes(&model, &st, field, 1e-11);
    // the hanging nodes' values are the constraint's (filled from the masters)
    for h in refine::hanging_nodes(&model.mesh) {
        let w = edge_shape(h.s);
        for c in 0..2 {
            let from: f64 = (0..3).map(|i| w[i] * st.u[2 * h.edge[i] + c]).sum();
            assert!((st.u[2 * h.node + c] - from).abs() < 1e-15);
        }
    }
    assert!(hang.iter().all(|&n| n < model.mesh.nodes.len()));
    let geo: Vec<_> = (0..model.mesh.elements.len())
        .map(|el| model.geometry(el))
        .collect();
    let ng = model.rule(0).points.len();
    for (g, p) in st.gauss.iter().enumerate() {
        let y = geo[g / ng].x[g % ng][1];
        let want = e * k * (y - 2.0);
        assert!(
            (p.stress[0] - want).abs() < 1e-9 * e * k * 2.0 && p.stress[1].abs() < 1e-9 * e * k,
            "Gauss point {g} at y = {y}: σ = {:?}, σxx exact {want}",
            p.stress
        );
    }
}

/// The constraint coefficients N(∓½) = (3/8, 3/4, −1/8), (−1/8, 3/4, 3/8)
/// reproduce any quadratic along the coarse edge (and only a quadratic's
/// worth: a cubic is off by its cubic part).
#[test]
fn edge_coefficients_reproduce_a_quadratic_along_the_coarse_edge() {
    assert_eq!(edge_shape(-0.5), [3.0 / 8.0, 3.0 / 4.0, -1.0 / 8.0]);
    assert_eq!(edge_shape(0.5), [-1.0 / 8.0, 3.0 / 4.0, 3.0 / 8.0]);
    for (a, b, c) in [(1.0, 0.0, 0.0), (0.3, -2.0, 0.7), (-5.0, 1.25, 3.5)] {
        let f = |s: f64| a + b * s + c * s * s;
        for s in [-0.5, 0.5] {
            let w = edge_shape(s);
            let got = w[0] * f(-1.0) + w[1] * f(0.0) + w[2] * f(1.0);
            assert!((got - f(s)).abs() < 1e-15, "s = {s}: {got} vs {}", f(s));
        }
    }
    // s³ takes the values of s at −1, 0, 1, so its interpolant at ½ is ½,
    // not ⅛
    let w = edge_shape(0.5);
    let cubic = w[2] - w[0];
    assert!((cubic - 0.5).abs() < 1e-15 && (cubic - 0.125).abs() > 0.3);
}

/// A deterministic pseudo-random sequence (LCG).
fn lcg(seed: &mut u64) -> u64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    *seed >> 33
}

/// Random markings over six rounds: the mesh stays valid, its area stays
/// the area, and it stays 1-irregular: every hanging node's coarse element
/// is exactly one level coarser than the two elements on the halves, and no
/// master of a hanging node hangs.
#[test]
fn closure_keeps_random_refinements_one_irregular() {
    let start = base_mesh("strain", 0.0);
    let area = |m: &Mesh| -> f64 {
        (0..m.elements.len())
            .map(|e| {
                let g = asperity::physics::element::solid::ElementGeometry::new(
                    asperity::physics::element::family::Family::Q8,
                    &m.element_coords(e),
                    &asperity::physics::element::q8::gauss_3x3(),
                    1.0,
                )
                .unwrap();
                g.dv[..g.n].iter().sum::<f64>()
            })
            .sum()
    };
    let a0 = area(&start);
    let mut seed = 7u64;
    let mut max_level = 0;
    for trial in 0..4 {
        let mut r = Refined::start(&start);
        for round in 0..6 {
            let n = r.mesh.elements.len();
            let marked: Vec<usize> = (0..1 + lcg(&mut seed) as usize % 3)
                .map(|_| lcg(&mut seed) as usize % n)
                .collect();
            r = r.refine(&marked).unwrap();
            r.mesh.validate().unwrap();
            let at = format!("trial {trial} round {round}");
            assert!((area(&r.mesh) - a0).abs() < 1e-10 * a0, "{at}: area");
            let hanging = refine::hanging_nodes(&r.mesh);
            let slaves: std::collections::HashSet<usize> = hanging.iter().map(|h| h.node).collect();
            for h in &hanging {
                assert!(h.edge.iter().all(|m| !slaves.contains(m)), "{at}: chain");
                let coarse = r.state.level[h.element];
                // the elements holding the hanging node are on the halves
                for (e, el) in r.mesh.elements.iter().enumerate() {
                    if el.nodes().contains(&h.node) {
                        assert_eq!(r.state.level[e], coarse + 1, "{at}: node {}", h.node);
                    }
                }
            }
            max_level = max_level.max(*r.state.level.iter().max().unwrap());
        }
    }
    assert!(
        max_level >= 3,
        "the markings reached level {max_level} only"
    );
}

/// The case text of `cases/<name>` with `[mesh] refine = 1` replaced.
fn shipped(name: &str, mesh: &str) -> String {
    let text =
        std::fs::read_to_string(common::root().join("cases").join(name).join("case.toml")).unwrap();
    assert!(text.contains("\n[mesh]\nrefine = 1\n"));
    text.replacen("\n[mesh]\nrefine = 1\n", &format!("\n[mesh]\n{mesh}\n"), 1)
}

/// The punch's settlement (mm), its dof count, and whether the run ended.
fn settle(text: &str) -> (f64, usize) {
    let model = common::model(text);
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap_or_else(|e| panic!("{e}"));
    let last = r.increments.last().unwrap();
    assert!((last.load_factor - 1.0).abs() < 1e-12, "the run stopped");
    (last.measures.center_displacement, model.num_dofs())
}

/// cases/punch-plane-stress (elastic-plastic, contact) refined twice around
/// the punch corner (x = 20, y = 0, where the pressure and the plastic zone
/// peak) converges through the load history and settles within 0.2 % of the
/// uniform 4× mesh, closer than the uniform 2× mesh that has more dofs.
#[test]
fn punch_corner_refined_locally_settles_as_the_fine_uniform_mesh() {
    let region = "refine = 1\nrefine_region = { x = [15.0, 25.0], y = [-5.0, 5.0], levels = 2 }";
    let (local, n_local) = settle(&shipped("punch-plane-stress", region));
    let (u2, n2) = settle(&shipped("punch-plane-stress", "refine = 2"));
    let (u4, n4) = settle(&shipped("punch-plane-stress", "refine = 4"));
    let (e_local, e2) = (((local - u4) / u4).abs(), ((u2 - u4) / u4).abs());
    eprintln!(
        "punch settlement: local {local:.6} mm ({n_local} dofs), uniform 2x {u2:.6} ({n2}), 4x {u4:.6} ({n4}); \
         errors against 4x: local {e_local:.2e}, 2x {e2:.2e}"
    );
    assert!(n_local < n2 && n2 < n4);
    assert!(
        e_local < 2e-3,
        "local refinement off the 4x mesh by {e_local:.2e}"
    );
    assert!(
        e_local < e2 / 3.0,
        "local {e_local:.2e} against 2x {e2:.2e}"
    );
}

/// A column across a compliant joint (tests/verification/column.rs's) with
/// the upper block refined next to the joint only: the closure refines the
/// lower block's facing elements (the pairs stay coincident pairs, checked
/// by the mesh's validation), and the stress stays the uniform σ_yy = −q at
/// every Gauss point, the settlement the closed form q (h₁ + h₂)/E + c_N q^m.
#[test]
fn a_matching_interface_stays_matching_under_one_sided_refinement() {
    let (q, e, c, m, h1, h2) = (120.0, 70000.0, 0.002, 0.5, 15.0, 25.0);
    let text = common::case()
        .plane("stress")
        .raw(&region([0.0, 6.0], [0.0, 4.0], 2))
        .block("top", [0.0, 10.0], [3], [0.0, h1], [3])
        .block("bottom", [0.0, 10.0], [3], [-h2, 0.0], [4])
        .interface("joint", "top", "bottom")
        .material("top", e, 0.33)
        .material("bottom", e, 0.33)
        .law("joint", "power", c, m)
        .ux("top.left", 0.0)
        .ux("bottom.left", 0.0)
        .uy("bottom.bottom", 0.0)
        .pressure("top.top", q)
        .solver("increments = 4")
        .tolerances(1e-12, 1e-12)
        .no_vtu()
        .build();
    let model = common::model(&text);
    let joint = &model.mesh.interfaces[0];
    // 3 edges at the start: the two under the box split twice on both
    // sides (8); the third once, its upper element refined by the closure (a
    // level-2 child beside it would otherwise hang two levels on its side)
    assert_eq!(joint.edges.len(), 2 * 4 + 2);
    let bottom = model
        .mesh
        .bodies
        .iter()
        .position(|b| b == "bottom")
        .unwrap();
    let fine_below = (0..model.mesh.elements.len())
        .filter(|&el| model.mesh.elements[el].body == bottom)
        .count();
    assert!(fine_below > 12, "the lower block was not refined");
    hanging(&model.mesh);
    let r = asperity::app::driver::solve(&model, &mut Quiet).unwrap();
    let st = r.final_state;
    for (g, p) in st.gauss.iter().enumerate() {
        assert!(
            (p.stress[1] + q).abs() < 1e-9 * q && p.stress[0].abs() < 1e-9 * q,
            "Gauss point {g}: σ = {:?}",
            p.stress
        );
    }
    let top = (0..model.mesh.nodes.len())
        .filter(|&n| model.mesh.nodes[n][0] == 0.0)
        .max_by(|&a, &b| model.mesh.nodes[a][1].total_cmp(&model.mesh.nodes[b][1]))
        .unwrap();
    let want = q * (h1 + h2) / e + c * q.powf(m);
    let got = -st.u[2 * top + 1];
    assert!((got - want).abs() < 1e-9 * want, "{got} vs {want}");
}

/// `refine::uniform` of an ungraded two-body mesh is the mesh `[mesh]
/// refine = 2` generates: the same points (to 1e-12), element count, edge
/// and node sets (sizes) and interface pairs; and it hangs no node.
#[test]
fn uniform_split_is_the_generators_doubled_mesh() {
    let text = |refine: usize| {
        common::case()
            .plane("stress")
            .refine(refine)
            .block("top", [0.0, 10.0], [3], [0.0, 6.0], [2])
            .block("bottom", [0.0, 10.0], [3], [-9.0, 0.0], [3])
            .interface("joint", "top", "bottom")
            .material("top", 70000.0, 0.3)
            .material("bottom", 70000.0, 0.3)
            .law("joint", "power", 0.002, 0.5)
            .ux("top.left", 0.0)
            .ux("bottom.left", 0.0)
            .uy("bottom.bottom", 0.0)
            .pressure("top.top", 10.0)
            .no_vtu()
            .build()
    };
    let one = common::model(&text(1)).mesh;
    let two = common::model(&text(2)).mesh;
    let split = refine::uniform(&one).unwrap();
    assert!(split.hanging.is_empty());
    let m = &split.mesh;
    assert_eq!(m.elements.len(), two.elements.len());
    assert_eq!(m.nodes.len(), two.nodes.len());
    let sorted = |mesh: &Mesh| {
        let mut p = mesh.nodes.clone();
        // by position rounded to 1e-9 mm (x of a generated and a mapped
        // point may differ in the last bit)
        p.sort_by_key(|a| ((a[0] * 1e9).round() as i64, (a[1] * 1e9).round() as i64));
        p
    };
    for (a, b) in sorted(m).iter().zip(sorted(&two)) {
        assert!(
            (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12,
            "{a:?} vs {b:?}"
        );
    }
    for (name, edges) in &two.edge_sets {
        assert_eq!(m.edge_sets[name].len(), edges.len(), "edge set {name}");
    }
    for (name, nodes) in &two.node_sets {
        assert_eq!(m.node_sets[name].len(), nodes.len(), "node set {name}");
    }
    assert_eq!(m.interfaces[0].edges.len(), two.interfaces[0].edges.len());
    m.validate().unwrap();
}

/// With twist (3 dofs a node) the constraint ties u_θ too: elastic torsion
/// u_θ = k r z with u_r = a r, u_z = c z (bilinear: in the Q8 space, in
/// equilibrium: τ_zθ = G k r, τ_rθ = 0) prescribed on the boundary of the
/// locally refined block is the solution at every node, hanging ones
/// included, to 1e-11.
#[test]
fn twist_ties_the_third_component_of_a_hanging_node() {
    let text = common::case()
        .plane("axisymmetric")
        .with("twist", true)
        .raw(&region([1.0, 2.5], [0.0, 1.5], 2))
        .block("b", [1.0, 5.0], [4], [0.0, 4.0], [4])
        .rx([1.4])
        .material("b", 100000.0, 0.25)
        .fixed("b.bottom")
        .with("rotation", 0.0)
        .uy("b.top", -0.01)
        .solver("load_factors = [1.0]")
        .tolerances(1e-12, 1e-14)
        .no_vtu()
        .build();
    let mut model = common::model(&text);
    let nd = model.mesh.node_dofs;
    assert_eq!(nd.per_node(), 3);
    hanging(&model.mesh);
    let field = |p: [f64; 2]| [1.5e-3 * p[0], -0.8e-3 * p[1], 2e-3 * p[0] * p[1]];
    let nodes: Vec<[f64; 2]> = (0..model.mesh.nodes.len())
        .map(|n| model.mesh.xy(n))
        .collect();
    let on = |p: [f64; 2]| p[0] == 1.0 || p[0] == 5.0 || p[1] == 0.0 || p[1] == 4.0;
    model.prescribed = (0..nodes.len())
        .filter(|&n| on(nodes[n]))
        .flat_map(|n| (0..3).map(move |c| (n, c)))
        .map(|(n, c)| (nd.dof(n, c), field(nodes[n])[c]))
        .collect();
    model.prescribed_history = vec![None; model.prescribed.len()];
    model
        .set_constraints(model.constraints.list.clone())
        .unwrap();
    let st = asperity::app::driver::solve(&model, &mut Quiet)
        .unwrap_or_else(|e| panic!("{e}"))
        .final_state;
    let scale = 2e-3 * 5.0 * 4.0;
    for (n, &p) in nodes.iter().enumerate() {
        for (c, want) in field(p).into_iter().enumerate() {
            let got = st.u[nd.dof(n, c)];
            assert!(
                (got - want).abs() < 1e-11 * scale,
                "node {n} at {p:?}: u{c} = {got:e}, exact {want:e}"
            );
        }
    }
}
