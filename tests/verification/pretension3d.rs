//! Pretension sections in 3D models (issue 47, docs/case-schema.md
//! "Pretension sections"): the cut is a plane x = c, y = h or z = c along
//! element faces, its nodes doubled, the copies tied in three components.
//! A bolt shank revolved in 3D (the O-grid core on the axis) against the
//! uniaxial rod and the axisymmetric model of the same layout; a locked
//! section taking its share of a later load (the two springs either side of
//! the load point), in bars lying along x and z, of 20-node hexahedra and of
//! 10-node tetrahedra; two cuts crossing in one block (biaxial, exact).

use crate::common;
use asperity::model::Model;
use asperity::solve::{Increment, Observer, RunResult, State};

const E: f64 = 200_000.0;
const NU: f64 = 0.3;

#[derive(Default)]
struct Capture(Vec<State>);
impl Observer for Capture {
    fn increment(&mut self, _: &Model, s: &State, _: &Increment) -> asperity::error::Result<()> {
        self.0.push(s.clone());
        Ok(())
    }
}

fn solve(model: &Model) -> (RunResult, Vec<State>) {
    let mut c = Capture::default();
    let r = asperity::app::driver::solve(model, &mut c).unwrap_or_else(|e| panic!("{e}"));
    (r, c.0)
}

/// A solid rod of radius `r0`, length 2`l0` along y, held axially at both
/// ends and cut at mid-length by a section of force `f`: axisymmetric
/// (`solid` false), or the same layout revolved through 90° in 6 layers
/// (the O-grid core on the axis) with its symmetry planes held.
fn rod(r0: f64, l0: f64, f: f64, solid: bool) -> String {
    let (model, planes) = if solid {
        (
            "plane = \"3d\"\n[mesh]\nrevolve = { angle = 90.0, n = 6 }",
            "[[boundary]]\nset = \"rod.theta0\"\nuz = 0.0\n[[boundary]]\nset = \"rod.theta1\"\nux = 0.0\n",
        )
    } else {
        ("plane = \"axisymmetric\"", "")
    };
    format!(
        r#"
[model]
{model}
[[mesh.block]]
body = "rod"
x = [0.0, {r0}]
nx = [3]
y = [0.0, {l0}, {}]
ny = [4, 4]
[materials.rod]
young = {E}
poisson = {NU}
[[boundary]]
set = "rod.bottom"
uy = 0.0
[[boundary]]
set = "rod.top"
uy = 0.0
{planes}[[pretension]]
name = "shank"
body = "rod"
y = {l0}
force = {f}
[solver]
residual_tolerance = 1e-12
[output]
vtu = false
"#,
        2.0 * l0
    )
}

/// The bolt shank of tests/verification/pretension.rs's rod of revolution
/// posed in 3D: a quarter of the rod (r = 6, 2L₀ = 40) revolved about its
/// axis, cut by the plane y = 20 and pulled together by F = 7.5 kN (30 kN
/// on the whole rod). Every node of the plane (core and ring, corners and
/// midsides) is doubled; the section force is F; the shank's stress is
/// uniaxial and uniform, σ_yy = F/A_h, and the shortening is that of the two
/// halves in series, s = F 2L₀/(E A_h), both exact (1e-9), with A_h the
/// quarter disk as the mesh has it: its arc r = 6 is six quadratic arcs of
/// φ = 15°, each a parabola through its ends and its middle, enclosing the
/// triangle ½ r² sin φ and the parabolic segment ⅔ c h over its chord
/// (c = 2r sin(φ/2), h = r (1 − cos(φ/2))). The axisymmetric model of the
/// same layout (F = 30 kN on the whole ring) has s = F 2L₀/(E π r²), exact;
/// the two shortenings stand as π r²/4 to A_h (exact, 1e-9): they differ by
/// the discretization of the arc, (π r²/4 − A_h)/A_h = 9.8e-6.
#[test]
fn a_revolved_bolt_shank_cut_in_3d_is_the_uniaxial_rod_and_the_axisymmetric_one() {
    let (r0, l0, f) = (6.0, 20.0, 7_500.0);
    let area = std::f64::consts::PI * r0 * r0 / 4.0;
    let model = common::model(&rod(r0, l0, f, true));
    let cut = &model.sections[0];
    assert_eq!(cut.axis, 1);
    // every node of the plane y = L₀ has its copy, and only those
    let on_plane = |n: usize| (model.mesh.nodes[n][1] - l0).abs() < 1e-9;
    let originals = (0..model.mesh.nodes.len())
        .filter(|&n| on_plane(n) && !cut.pairs.iter().any(|p| p.1 == n))
        .count();
    assert_eq!(originals, cut.pairs.len());
    assert!(cut.pairs.iter().all(|&(n, c)| on_plane(n) && on_plane(c)));
    let (r, states) = solve(&model);
    let [force, s] = r.increments.last().unwrap().sections[0];
    assert!(common::rel(force, f) < 1e-10, "force {force}");
    // the stress: uniaxial and uniform (xx, yy, xy, zz, xz, yz)
    let gauss = &states.last().unwrap().gauss;
    let sigma = gauss.get(0).stress[1];
    for g in gauss {
        assert!(
            common::rel(g.stress[1], sigma) < 1e-9,
            "σ_yy {}",
            g.stress[1]
        );
        for k in [0, 2, 3, 4, 5] {
            assert!(g.stress[k].abs() < 1e-9 * sigma, "σ[{k}] {}", g.stress[k]);
        }
    }
    // the two halves in series, on the mesh's own area F/σ
    assert!(
        common::rel(s, sigma * 2.0 * l0 / E) < 1e-9,
        "shortening {s} vs σ 2L₀/E {}",
        sigma * 2.0 * l0 / E
    );
    // the quarter disk of the mesh: six quadratic arcs of 15°
    let phi = std::f64::consts::FRAC_PI_2 / 6.0;
    let chord = 2.0 * r0 * (phi / 2.0).sin();
    let sagitta = r0 * (1.0 - (phi / 2.0).cos());
    let area_h = 6.0 * (0.5 * r0 * r0 * phi.sin() + 2.0 / 3.0 * chord * sagitta);
    assert!(
        common::rel(sigma, f / area_h) < 1e-9,
        "σ_yy {sigma} vs F/A_h"
    );
    assert!(common::rel(s, f * 2.0 * l0 / (E * area_h)) < 1e-9, "s {s}");
    // the axisymmetric model of the same layout, the whole ring's force
    let plane = common::model(&rod(r0, l0, 4.0 * f, false));
    let (r2, _) = solve(&plane);
    let [force2, s2] = r2.increments.last().unwrap().sections[0];
    assert!(common::rel(force2, 4.0 * f) < 1e-10, "force {force2}");
    assert!(common::rel(s2, 4.0 * f * 2.0 * l0 / (E * 4.0 * area)) < 1e-9);
    assert!(common::rel(s / s2, area / area_h) < 1e-9, "{s} / {s2}");
    println!(
        "revolved shank: A_h {area_h:.6} mm² vs π r²/4 {area:.6} ({:.2e}); σ_yy {sigma:.6} MPa vs F/A {:.6}; s {s:.9} mm, axisymmetric {s2:.9} mm",
        area / area_h - 1.0,
        f / area,
    );
}

/// A bar of 20-node hexahedra lying along `axis` (0: x, 2: z): 100 mm long,
/// a 10 × 10 mm section, its ends held along the axis and two of its
/// sides on symmetry planes, cut by the plane at 30 mm (section "bolt",
/// `section` its force and history keys), `more` after.
fn bar(axis: usize, section: &str, more: &str) -> String {
    let (layout, extrude, ends, sym, cut) = if axis == 0 {
        (
            "x = [0.0, 30.0, 60.0, 100.0]\nnx = [3, 3, 4]\ny = [0.0, 10.0]\nny = [2]",
            "z = [0.0, 10.0], nz = [2]",
            ["bar.left", "bar.right", "ux"],
            "[[boundary]]\nset = \"bar.bottom\"\nuy = 0.0\n[[boundary]]\nset = \"bar.zmin\"\nuz = 0.0\n",
            "x",
        )
    } else {
        (
            "x = [0.0, 10.0]\nnx = [2]\ny = [0.0, 10.0]\nny = [2]",
            "z = [0.0, 30.0, 60.0, 100.0], nz = [3, 3, 4]",
            ["bar.zmin", "bar.zmax", "uz"],
            "[[boundary]]\nset = \"bar.bottom\"\nuy = 0.0\n[[boundary]]\nset = \"bar.left\"\nux = 0.0\n",
            "z",
        )
    };
    let [a, b, u] = ends;
    format!(
        r#"
[model]
plane = "3d"
[mesh]
extrude = {{ {extrude} }}
[[mesh.block]]
body = "bar"
{layout}
[materials.bar]
young = {E}
poisson = {NU}
[[boundary]]
set = "{a}"
{u} = 0.0
[[boundary]]
set = "{b}"
{u} = 0.0
{sym}[[pretension]]
name = "bolt"
body = "bar"
{cut} = 30.0
{section}
[solver]
residual_tolerance = 1e-12
[output]
vtu = false
{more}
"#
    )
}

/// The service load of [`locked_share`]: a force of `p_node` along the
/// bar's axis at every node of the plane at 60 mm, after the preload.
fn service(axis: usize, p_node: f64) -> String {
    let (c, range) = if axis == 0 {
        ("fx", "x_range")
    } else {
        ("fz", "z_range")
    };
    format!(
        "[history]\npreload = [[0, 0], [1, 1]]\nservice = [[1, 0], [2, 1]]\n\
         [[force]]\nnodes = \"bar.all\"\n{c} = {p_node}\n{range} = [60.0, 60.0]\nhistory = \"service\"\n"
    )
}

/// A bar along `axis` of `text` (its cut at 30 mm, the load at b = 60 mm
/// of L = 100) preloaded to F through its section, locked, then pulled at
/// b by P (the sum of its nodal forces): at the lock the force is F and the
/// shortening F L/(E A) of the two parts in series (uniaxial, exact); after
/// it the locked cut is a rigid tie and the bar either side of the load
/// point a spring, k₁ = EA/b and k₂ = EA/(L − b), the part holding the
/// section taking Φ P, Φ = k₁/(k₁ + k₂) = (L − b)/L, the shortening held (exact: the field of a unit shortening is uniaxial, so
/// the share is the same for any distribution of P over the plane).
fn locked_share(model: &Model, axis: usize, f: f64, p_node: f64) {
    assert_eq!(model.sections[0].axis, axis);
    assert_eq!(model.sections[0].lock_after, 1.0);
    let at_b = (model.mesh.nodes.iter())
        .filter(|x| (x[axis] - 60.0).abs() < 1e-9)
        .count();
    let (r, states) = solve(model);
    let lock = r.increments.iter().find(|i| i.load_factor == 1.0).unwrap();
    let [f_lock, s_lock] = lock.sections[0];
    let (l, area) = (100.0, 100.0);
    assert!(common::rel(f_lock, f) < 1e-10, "{f_lock}");
    assert!(common::rel(s_lock, f * l / (E * area)) < 1e-9, "{s_lock}");
    let p = at_b as f64 * p_node;
    let phi = (l - 60.0) / l;
    let mut after = 0;
    for inc in r.increments.iter().filter(|i| i.load_factor > 1.0) {
        let [force, s] = inc.sections[0];
        assert_eq!(s, s_lock, "t = {}", inc.load_factor);
        let want = f + phi * p * (inc.load_factor - 1.0);
        assert!(
            common::rel(force, want) < 1e-9,
            "t = {}: {force} vs {want}",
            inc.load_factor
        );
        after += 1;
    }
    assert!(after >= 2, "{after} increments after the lock");
    // at the lock: σ along the axis F/A at every Gauss point (the stress
    // in the order xx, yy, xy, zz, xz, yz)
    let k = [0, 1, 3][axis];
    let i = r
        .increments
        .iter()
        .position(|i| i.load_factor == 1.0)
        .unwrap();
    for g in &states[i].gauss {
        assert!(common::rel(g.stress[k], f / area) < 1e-9, "{:?}", g.stress);
    }
}

/// A bolt lying along x: the plane x = 30 cuts it, the share of a later
/// load is (L − b)/L, and `lock = false` keeps the force.
#[test]
fn a_locked_section_normal_to_x_takes_its_share_of_a_later_load() {
    let (f, p_node) = (1000.0, 100.0);
    let keys = format!("force = {f}\nhistory = \"preload\"");
    let model = common::model(&bar(0, &keys, &service(0, p_node)));
    locked_share(&model, 0, f, p_node);
    let model = common::model(&bar(
        0,
        &format!("{keys}\nlock = false"),
        &service(0, p_node),
    ));
    let (r, _) = solve(&model);
    let [force, _] = r.increments.last().unwrap().sections[0];
    assert!(common::rel(force, f) < 1e-9, "unlocked: {force}");
}

/// A bolt lying along z (the cut z = 30 across the extrusion's layers):
/// the same closed forms, so the cut is no y-only or x-only code.
#[test]
fn a_locked_section_normal_to_z_takes_its_share_of_a_later_load() {
    let (f, p_node) = (1000.0, 100.0);
    let keys = format!("force = {f}\nhistory = \"preload\"");
    let model = common::model(&bar(2, &keys, &service(2, p_node)));
    locked_share(&model, 2, f, p_node);
}

/// The bar along x in 10-node tetrahedra: a Gmsh 4.1 mesh written here,
/// each cell of the box [0, 100] × [0, 10] × [0, 10] (cells 10 mm along x,
/// 5 mm across) split into six tetrahedra about its diagonal (Kuhn: the
/// face diagonals of neighbouring cells agree), midside nodes at the
/// edges' middles, its faces x = 0, x = 100, y = 0 and z = 0 physical
/// surfaces. The plane x = 30 is made of the cells' faces (corners and
/// midsides of 6-node triangles): the same closed forms as the hexahedra.
#[test]
fn a_section_of_tetrahedra_takes_its_share_of_a_later_load() {
    let dir = common::scratch("pretension3d-tetrahedra");
    std::fs::write(
        dir.join("bar.msh"),
        tet_bar_msh([10, 2, 2], [10.0, 5.0, 5.0]),
    )
    .unwrap();
    let (f, p_node) = (1000.0, 100.0);
    let text = bar(
        0,
        &format!("force = {f}\nhistory = \"preload\""),
        &service(0, p_node),
    )
    .replace("extrude = { z = [0.0, 10.0], nz = [2] }", "file = \"bar.msh\"")
    .replace(
        "[[mesh.block]]\nbody = \"bar\"\nx = [0.0, 30.0, 60.0, 100.0]\nnx = [3, 3, 4]\ny = [0.0, 10.0]\nny = [2]\n",
        "",
    )
    .replace("bar.left", "bar.xmin")
    .replace("bar.right", "bar.xmax")
    .replace("bar.bottom", "bar.ymin");
    std::fs::write(dir.join("case.toml"), &text).unwrap();
    let case = asperity::input::case::Case::load(&dir.join("case.toml")).unwrap();
    let model = Model::build(case).unwrap_or_else(|e| panic!("{e}"));
    // the plane x = 30: 5 × 5 points of the half-cell lattice, all doubled
    assert_eq!(model.sections[0].pairs.len(), 25);
    assert!(model
        .mesh
        .elements
        .iter()
        .all(|e| e.family == asperity::input::mesh::Family::T10));
    locked_share(&model, 0, f, p_node);
}

/// The tetrahedra of `cells` cells (module text of the test above), as
/// points of the half-cell lattice: each in Gmsh's node order (corners,
/// then the midsides of 0–1, 1–2, 2–0, 0–3, 2–3, 1–3), with a positive
/// volume; and the 6-node triangles on the box's sides x = 0, x = max,
/// y = 0, z = 0.
#[allow(clippy::type_complexity)]
fn kuhn_tetrahedra(cells: [usize; 3]) -> (Vec<[[usize; 3]; 10]>, [Vec<[[usize; 3]; 6]>; 4]) {
    let mut tets = Vec::new();
    let mut tris: [Vec<[[usize; 3]; 6]>; 4] = Default::default();
    let sides = [(0, 0), (0, 2 * cells[0]), (1, 0), (2, 0)];
    for k in 0..cells[2] {
        for j in 0..cells[1] {
            for i in 0..cells[0] {
                for path in [
                    [0, 1, 2],
                    [0, 2, 1],
                    [1, 0, 2],
                    [1, 2, 0],
                    [2, 0, 1],
                    [2, 1, 0],
                ] {
                    let mut c = [[2 * i, 2 * j, 2 * k]; 4];
                    for s in 0..3 {
                        c[s + 1] = c[s];
                        c[s + 1][path[s]] += 2;
                    }
                    // a positive volume: (x1 − x0) × (x2 − x0) · (x3 − x0) > 0 on the
                    // lattice (the box's cells are all alike)
                    let d = |a: usize| -> [i64; 3] {
                        std::array::from_fn(|q| c[a][q] as i64 - c[0][q] as i64)
                    };
                    let (a, b, e) = (d(1), d(2), d(3));
                    let vol = e[0] * (a[1] * b[2] - a[2] * b[1])
                        + e[1] * (a[2] * b[0] - a[0] * b[2])
                        + e[2] * (a[0] * b[1] - a[1] * b[0]);
                    if vol < 0 {
                        c.swap(1, 2);
                    }
                    let mid = |u: usize, v: usize| -> [usize; 3] {
                        std::array::from_fn(|q| (c[u][q] + c[v][q]) / 2)
                    };
                    tets.push([
                        c[0],
                        c[1],
                        c[2],
                        c[3],
                        mid(0, 1),
                        mid(1, 2),
                        mid(2, 0),
                        mid(0, 3),
                        mid(2, 3),
                        mid(1, 3),
                    ]);
                    for [u, v, w] in [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]] {
                        let on = |q: usize, at: usize| [u, v, w].iter().all(|&a| c[a][q] == at);
                        if let Some(s) = sides.iter().position(|&(q, at)| on(q, at)) {
                            tris[s].push([c[u], c[v], c[w], mid(u, v), mid(v, w), mid(w, u)]);
                        }
                    }
                }
            }
        }
    }
    (tets, tris)
}

/// A Gmsh 4.1 mesh of 10-node tetrahedra ([`kuhn_tetrahedra`]) of
/// `cells` cells of size `h` along x, y, z from the origin: physical volume
/// "bar" and surfaces "bar.xmin", "bar.xmax", "bar.ymin", "bar.zmin"
/// (6-node triangles); every point of the half-cell lattice a node.
fn tet_bar_msh(cells: [usize; 3], h: [f64; 3]) -> String {
    let m = cells.map(|c| 2 * c + 1);
    let id = |p: [usize; 3]| 1 + p[0] + m[0] * (p[1] + m[1] * p[2]);
    let (tets, tris) = kuhn_tetrahedra(cells);
    let names = ["bar.xmin", "bar.xmax", "bar.ymin", "bar.zmin"];
    let points = m[0] * m[1] * m[2];
    let mut out = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n5\n");
    for (s, name) in names.iter().enumerate() {
        out += &format!("2 {} \"{name}\"\n", s + 1);
    }
    out += "3 10 \"bar\"\n$EndPhysicalNames\n$Entities\n0 0 4 1\n";
    let big = 1e3;
    for s in 0..4 {
        out += &format!(
            "{} -{big} -{big} -{big} {big} {big} {big} 1 {} 0\n",
            s + 1,
            s + 1
        );
    }
    out += &format!("1 -{big} -{big} -{big} {big} {big} {big} 1 10 0\n$EndEntities\n");
    out += &format!("$Nodes\n1 {points} 1 {points}\n3 1 0 {points}\n");
    for n in 1..=points {
        out += &format!("{n}\n");
    }
    for k in 0..m[2] {
        for j in 0..m[1] {
            for i in 0..m[0] {
                let [a, b, c] = [i, j, k].map(|v| v as f64);
                out += &format!("{} {} {}\n", 0.5 * h[0] * a, 0.5 * h[1] * b, 0.5 * h[2] * c);
            }
        }
    }
    let count = tets.len() + tris.iter().map(Vec::len).sum::<usize>();
    out += &format!("$EndNodes\n$Elements\n5 {count} 1 {count}\n");
    let mut tag = 0;
    let mut block = |out: &mut String, head: String, list: Vec<Vec<usize>>| {
        *out += &head;
        for nodes in list {
            tag += 1;
            let nodes: Vec<String> = nodes.iter().map(usize::to_string).collect();
            *out += &format!("{tag} {}\n", nodes.join(" "));
        }
    };
    for (s, list) in tris.iter().enumerate() {
        let head = format!("2 {} 9 {}\n", s + 1, list.len());
        block(
            &mut out,
            head,
            list.iter().map(|t| t.map(id).to_vec()).collect(),
        );
    }
    let head = format!("3 1 11 {}\n", tets.len());
    block(
        &mut out,
        head,
        tets.iter().map(|t| t.map(id).to_vec()).collect(),
    );
    out + "$EndElements\n"
}

/// Two cuts crossing in one block [0, 20] × [0, 10] × [0, 20]: x = 10 with
/// force F_x and z = 10 with F_z, the faces x = 0, 20 held in u_x and
/// z = 0, 20 in u_z (the bottom in u_y). The node on both cuts has a copy
/// per quarter, the one beyond both moved by both shortenings. The answer
/// is the uniform biaxial state σ_xx = F_x/(10 · 20), σ_zz = F_z/(10 · 20),
/// and each shortening closes its strained length,
/// s_x = 20 (σ_xx − ν σ_zz)/E, s_z = 20 (σ_zz − ν σ_xx)/E (exact).
#[test]
fn two_cuts_crossing_in_a_block_give_the_biaxial_closed_form() {
    let (fx, fz) = (20_000.0, 8_000.0);
    let text = format!(
        r#"
[model]
plane = "3d"
[mesh]
extrude = {{ z = [0.0, 10.0, 20.0], nz = [2, 2] }}
[[mesh.block]]
body = "block"
x = [0.0, 10.0, 20.0]
nx = [2, 2]
y = [0.0, 10.0]
ny = [2]
[materials.block]
young = {E}
poisson = {NU}
[[boundary]]
set = "block.left"
ux = 0.0
[[boundary]]
set = "block.right"
ux = 0.0
[[boundary]]
set = "block.zmin"
uz = 0.0
[[boundary]]
set = "block.zmax"
uz = 0.0
[[boundary]]
set = "block.bottom"
uy = 0.0
[[pretension]]
name = "x"
body = "block"
x = 10.0
force = {fx}
[[pretension]]
name = "z"
body = "block"
z = 10.0
force = {fz}
[solver]
increments = 1
residual_tolerance = 1e-12
[output]
vtu = false
"#
    );
    let model = common::model(&text);
    // the nodes on both planes: one mesh node and three copies each
    let both = |x: &[f64; 3]| (x[0] - 10.0).abs() < 1e-9 && (x[2] - 10.0).abs() < 1e-9;
    let line = model.mesh.nodes.iter().filter(|x| both(x)).count();
    assert_eq!(line, 4 * 5, "{line} nodes on the line x = z = 10");
    let (r, states) = solve(&model);
    let [[f1, s1], [f2, s2]] = r.increments.last().unwrap().sections[..] else {
        panic!("two sections")
    };
    let (sx, sz) = (fx / 200.0, fz / 200.0);
    assert!(common::rel(f1, fx) < 1e-10 && common::rel(f2, fz) < 1e-10);
    assert!(common::rel(s1, 20.0 * (sx - NU * sz) / E) < 1e-9, "{s1}");
    assert!(common::rel(s2, 20.0 * (sz - NU * sx) / E) < 1e-9, "{s2}");
    for g in &states.last().unwrap().gauss {
        let s = g.stress;
        // xx, yy, xy, zz, xz, yz
        assert!(
            common::rel(s[0], sx) < 1e-9 && common::rel(s[3], sz) < 1e-9,
            "{s:?}"
        );
        for k in [1, 2, 4, 5] {
            assert!(s[k].abs() < 1e-9 * sx, "{s:?}");
        }
    }
}
