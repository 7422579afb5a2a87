//! Non-matching block interfaces (`matching = false`, issue 19): node-to-
//! segment springs from the slave side (body A) onto the master side's
//! quadratic edges (docs/theory.md, "Non-matching interfaces"). A matching
//! mesh declared non-matching reproduces the matching run; uniform pressure
//! through a non-matching horizontal and vertical interface (patch test);
//! the force balance when the slave side is the coarser; finite-difference
//! checks of the node-to-segment point tangent. The same on Gmsh meshes
//! (tests/data/nonmatching-*.geo): the patch test across unstructured
//! quads, swapped curves, an arc.

use crate::common;
use asperity::app::driver::{self, RunOptions};
use asperity::model::interface::{Coupling, InterfaceModel, Point, Segment};
use asperity::model::Model;
use asperity::numbers::fd;
use asperity::physics::contact::Status;
use asperity::solve::{RunResult, State};

/// A node-to-segment point's coupling.
fn segment_of(p: &Point) -> Segment {
    match &p.coupling {
        Coupling::NodeToSegment { segment, .. } => *segment,
        c => panic!("not a node-to-segment point: {c:?}"),
    }
}

fn run(name: &str, text: &str) -> (Model, RunResult) {
    let case = common::case_dir(name, text);
    let opts = RunOptions {
        out: Some(case.parent().unwrap().join("out")),
        quiet: true,
        ..RunOptions::default()
    };
    let (_, model, r) = driver::run(&case, &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
    (model, r)
}

/// p_N at every spring point of an interface, with the point's area.
fn pressures(im: &InterfaceModel, state: &State) -> Vec<(f64, f64)> {
    let gap = im.gap_at(state.time);
    im.points
        .iter()
        .map(|pt| {
            let u_n = im.point_kinematics_at(pt, &state.u, gap).0;
            (im.law.pressure(u_n).0, pt.area)
        })
        .collect()
}

const PUNCH: &str = include_str!("../../cases/punch-plane-stress/case.toml");
const PAIRED: &str = "upper = \"punch\"\nlower = \"foundation\"\n";

#[test]
fn a_matching_mesh_declared_non_matching_reproduces_the_matching_run() {
    for weights in ["lumped", "consistent"] {
        let base = PUNCH.replace(
            "law = \"power\"",
            &format!("weights = \"{weights}\"\nlaw = \"power\""),
        );
        let nm = base.replace(PAIRED, &format!("{PAIRED}matching = false\n"));
        assert!(nm.contains("matching = false") && base.contains(weights));
        let (m0, r0) = run(&format!("nm-punch-{weights}-matching"), &base);
        let (m1, r1) = run(&format!("nm-punch-{weights}-nonmatching"), &nm);
        assert!(m0.mesh.interfaces[0].nonmatching.is_none());
        assert!(m1.mesh.interfaces[0].nonmatching.is_some());
        let close = |a: f64, b: f64, what: &str| {
            assert!(
                common::rel(a, b) <= 1e-10 || (a - b).abs() < 1e-12,
                "{weights}: {what}: matching {a} non-matching {b}"
            );
        };
        let (f0, f1) = (r0.first_yield.unwrap(), r1.first_yield.unwrap());
        close(f0.total_load_kn, f1.total_load_kn, "first-yield load");
        close(f0.x, f1.x, "first-yield x");
        assert_eq!(r0.increments.len(), r1.increments.len());
        for (a, b) in r0.increments.iter().zip(&r1.increments) {
            let (a, b) = (&a.measures, &b.measures);
            close(a.center_displacement, b.center_displacement, "settlement");
            close(a.mean_pressure, b.mean_pressure, "mean pressure");
            close(a.normal_force, b.normal_force, "normal force");
        }
        let p0 = pressures(&m0.interfaces[0], &r0.final_state);
        let p1 = pressures(&m1.interfaces[0], &r1.final_state);
        assert_eq!(p0.len(), p1.len(), "{weights}: one spring point per point");
        let pmax = p0.iter().fold(0.0f64, |a, p| a.max(p.0));
        let dp = p0
            .iter()
            .zip(&p1)
            .fold(0.0f64, |a, (x, y)| a.max((x.0 - y.0).abs()));
        eprintln!(
            "{weights}: first yield {} vs {} kN, max |Δp_N| = {dp:.2e} of p_max {pmax:.1} MPa",
            f0.total_load_kn, f1.total_load_kn
        );
        for (k, (a, b)) in p0.iter().zip(&p1).enumerate() {
            assert!(
                (a.0 - b.0).abs() <= 1e-10 * pmax,
                "{weights}: point {k}: p_N {} vs {}",
                a.0,
                b.0
            );
            close(a.1, b.1, "point area");
        }
    }
}

/// A tangential law on a matching interface with consistent weights (issue
/// 46; refused before, as "one slip history per pair"): every Gauss point of
/// an edge keeps its own slip history, as a non-matching interface's spring
/// does. cases/punch-friction-b (micro-slip) with consistent weights, matching and
/// declared non-matching (the same 4 Gauss points per edge on the same
/// nodes): the same settlement, normal and tangential force and slip
/// measures every increment, and the same shear at every point, to 1e-9.
#[test]
fn friction_with_consistent_weights_on_a_matching_mesh_is_the_non_matching_run() {
    let base = include_str!("../../cases/punch-friction-b/case.toml").replace(
        "law = \"power\"",
        "weights = \"consistent\"\nlaw = \"power\"",
    );
    let nm = base.replace(PAIRED, &format!("{PAIRED}matching = false\n"));
    assert!(nm.contains("matching = false") && base.contains("[interface.contact.tangential]"));
    let (m0, r0) = run("nm-friction-consistent-matching", &base);
    let (_, r1) = run("nm-friction-consistent-nonmatching", &nm);
    assert_eq!(
        m0.interfaces[0].points.len(),
        4 * 8,
        "4 Gauss points on each of 8 edges"
    );
    assert_eq!(r0.increments.len(), r1.increments.len());
    let f_max = r0
        .increments
        .iter()
        .fold(0.0f64, |a, i| a.max(i.joints[0].normal_force));
    let mut worst = 0.0f64;
    for (a, b) in r0.increments.iter().zip(&r1.increments) {
        let (ja, jb) = (a.joints[0], b.joints[0]);
        for (what, x, y, scale) in [
            (
                "settlement",
                a.measures.center_displacement,
                b.measures.center_displacement,
                a.measures.center_displacement.abs(),
            ),
            ("normal force", ja.normal_force, jb.normal_force, f_max),
            (
                "tangential force",
                ja.tangential_force,
                jb.tangential_force,
                f_max,
            ),
            ("micro-slip measure", ja.micro_slip, jb.micro_slip, 20.0),
            ("macro-slip measure", ja.macro_slip, jb.macro_slip, 20.0),
        ] {
            worst = worst.max((x - y).abs() / scale);
            assert!(
                (x - y).abs() <= 1e-9 * scale,
                "t = {}: {what}: matching {x}, non-matching {y}",
                a.load_factor
            );
        }
    }
    let (s0, s1) = (&r0.final_state, &r1.final_state);
    let t_max = s0.contact.iter().fold(0.0f64, |a, c| a.max(c.p_t.abs()));
    assert!(t_max > 1.0, "no shear: {t_max}");
    for (k, (a, b)) in s0.contact.iter().zip(&s1.contact).enumerate() {
        assert!(
            (a.p_t - b.p_t).abs() <= 1e-9 * t_max,
            "point {k}: p_T {} vs {}",
            a.p_t,
            b.p_t
        );
    }
    let j = r0.increments.last().unwrap().joints[0];
    assert!(j.micro_slip + j.macro_slip > 0.0, "nothing slips: {j:?}");
    eprintln!(
        "friction, consistent weights: matching = non-matching to {worst:.1e}; F_T {:.3} N of F_N {:.3} N, {:.3} mm micro-slipping",
        j.tangential_force, j.normal_force, j.micro_slip
    );
}

/// Two elastic blocks through a non-matching interface, loaded by a uniform
/// pressure `q` = 100 MPa; `vertical`: side by side, else one on the other.
/// `slave` and `master` are the mesh keys along the interface (breakpoints,
/// counts, grading) of body A and body B.
fn patch(vertical: bool, weights: &str, slave: &str, master: &str) -> String {
    let (a, b) = if vertical {
        ("left", "right")
    } else {
        ("upper", "lower")
    };
    let (along, across) = if vertical { ("y", "x") } else { ("x", "y") };
    let (a_at, b_at) = if vertical {
        ("[0.0, 5.0]", "[5.0, 10.0]")
    } else {
        ("[0.0, 5.0]", "[-5.0, 0.0]")
    };
    let n = if vertical { "nx" } else { "ny" };
    let material = "young = 206000.0\npoisson = 0.3\nyield_stress = 1e5\nhardening = 0.0\n";
    let bcs = if vertical {
        "[[boundary]]\nset = \"left.bottom\"\nuy = 0.0\n[[boundary]]\nset = \"right.bottom\"\nuy = 0.0\n[[boundary]]\nset = \"right.right\"\nux = 0.0\n[[load]]\nedges = \"left.left\"\npressure = 100.0\n"
    } else {
        "[[boundary]]\nset = \"upper.left\"\nux = 0.0\n[[boundary]]\nset = \"lower.left\"\nux = 0.0\n[[boundary]]\nset = \"lower.bottom\"\nuy = 0.0\n[[load]]\nedges = \"upper.top\"\npressure = 100.0\n"
    };
    let (a_side, b_side) = (slave.replace("@", along), master.replace("@", along));
    format!(
        "description = \"non-matching patch\"\n[model]\nplane = \"strain\"\nthickness = 2.0\n[mesh]\nrefine = 1\n\
         [[mesh.block]]\nbody = \"{a}\"\n{a_side}\n{across} = {a_at}\n{n} = [2]\n\
         [[mesh.block]]\nbody = \"{b}\"\n{b_side}\n{across} = {b_at}\n{n} = [2]\n\
         [[mesh.interface]]\nname = \"contact\"\n{a} = \"{a}\"\n{b} = \"{b}\"\nmatching = false\n\
         [materials.{a}]\n{material}[materials.{b}]\n{material}\
         [interface.contact]\nweights = \"{weights}\"\nlaw = \"power\"\nc_n = 0.001\nm = 0.5\n\
         {bcs}[solver]\nmethod = \"full-newton\"\nincrements = 2\n"
    )
}

/// The slave side refines the master side (every master edge end is a slave
/// node), graded differently on each side.
const FINE_SLAVE: &str = "@ = [0.0, 4.0, 10.0]\nn@ = [3, 5]\nr@ = [0.5, 2.0]";
const COARSE_MASTER: &str = "@ = [0.0, 4.0, 10.0]\nn@ = [1, 1]";

/// p_N = q at every spring point and F_N = q × width × thickness.
fn check_uniform(name: &str, text: &str) {
    let (model, r) = run(name, text);
    let im = &model.interfaces[0];
    assert!(model.mesh.interfaces[0].nonmatching.is_some());
    let p = pressures(im, &r.final_state);
    for (k, &(pn, _)) in p.iter().enumerate() {
        assert!(
            (pn - 100.0).abs() <= 1e-9 * 100.0,
            "{name}: point {k}: p_N = {pn}"
        );
    }
    let force: f64 = p.iter().map(|(pn, a)| pn * a).sum();
    let want = 100.0 * 10.0 * 2.0;
    let dev = p.iter().fold(0.0f64, |a, q| a.max((q.0 - 100.0).abs()));
    eprintln!(
        "{name}: {} points, max |p_N - q| = {dev:.2e} MPa, F_N = {force} N",
        p.len()
    );
    assert!(
        common::rel(force, want) <= 1e-9,
        "{name}: F_N = {force}, want {want}"
    );
    let measured = r.increments.last().unwrap().measures.normal_force;
    assert!(
        common::rel(measured, want) <= 1e-9,
        "{name}: measured F_N = {measured}"
    );
}

#[test]
fn uniform_pressure_crosses_a_non_matching_horizontal_interface_exactly() {
    for w in ["lumped", "consistent"] {
        check_uniform(
            &format!("nm-patch-h-{w}"),
            &patch(false, w, FINE_SLAVE, COARSE_MASTER),
        );
    }
}

#[test]
fn uniform_pressure_crosses_a_non_matching_vertical_interface_exactly() {
    for w in ["lumped", "consistent"] {
        check_uniform(
            &format!("nm-patch-v-{w}"),
            &patch(true, w, FINE_SLAVE, COARSE_MASTER),
        );
    }
}

/// Mortar coupling (`weights = "mortar"`) passes the patch test whatever the
/// two divisions: a slave side refining the master, a coarser slave side
/// whose nodes fall anywhere on the master edges (where node-to-segment
/// springs scatter by 1-3 %), and a vertical interface.
#[test]
fn mortar_coupling_passes_the_patch_test_whatever_the_divisions() {
    let coarse_slave = "@ = [0.0, 10.0]\nn@ = [6]\nr@ = [0.5]";
    let fine_master = "@ = [0.0, 4.0, 10.0]\nn@ = [4, 6]\nr@ = [2.0, 0.7]";
    check_uniform(
        "nm-mortar-fine-slave",
        &patch(false, "mortar", FINE_SLAVE, COARSE_MASTER),
    );
    check_uniform(
        "nm-mortar-coarse-slave",
        &patch(false, "mortar", coarse_slave, fine_master),
    );
    check_uniform(
        "nm-mortar-vertical",
        &patch(true, "mortar", coarse_slave, fine_master),
    );
    // in axisymmetry (x = r: the blocks are discs on the axis, the weights
    // 2π r): N_i N_k^B r is still integrated exactly on each piece
    let axi = patch(false, "mortar", coarse_slave, fine_master).replace(
        "plane = \"strain\"\nthickness = 2.0",
        "plane = \"axisymmetric\"",
    );
    assert!(axi.contains("axisymmetric"));
    let (model, r) = run("nm-mortar-axisymmetric", &axi);
    let p = pressures(&model.interfaces[0], &r.final_state);
    let dev = p.iter().fold(0.0f64, |a, q| a.max((q.0 - 100.0).abs()));
    let force: f64 = p.iter().map(|(pn, a)| pn * a).sum();
    eprintln!("nm-mortar-axisymmetric: max |p_N - q| = {dev:.2e} MPa, F_N = {force} N");
    assert!(dev <= 1e-9 * 100.0, "axisymmetric mortar: {dev}");
    assert!(common::rel(force, 100.0 * std::f64::consts::PI * 100.0) <= 1e-9);
    // one spring per slave node, coupled to the master nodes its edges face
    let model = common::model(&patch(false, "mortar", coarse_slave, fine_master));
    let im = &model.interfaces[0];
    assert_eq!(im.points.len(), 2 * 6 + 1);
    assert!(im.points.iter().all(|p| p.coupling.is_mortar()));
    // a slave node couples its edges' slave nodes and every master edge they
    // face: wider than a node-to-segment spring's 12 dofs
    let widest = im.points.iter().map(|p| p.ndofs()).max().unwrap();
    assert!(widest > 12, "widest mortar spring {widest} dofs");
}

/// A slave side coarser than the master side (6 slave edges over 10 master
/// edges): node-to-segment springs do not pass the patch test there (the
/// master's nodal forces are not the consistent ones), but the interface
/// still carries the whole load.
#[test]
fn a_coarser_slave_side_still_carries_the_whole_load() {
    let slave = "@ = [0.0, 10.0]\nn@ = [6]\nr@ = [0.5]";
    let master = "@ = [0.0, 4.0, 10.0]\nn@ = [4, 6]\nr@ = [2.0, 0.7]";
    for w in ["lumped", "consistent"] {
        let name = format!("nm-coarse-slave-{w}");
        let (model, r) = run(&name, &patch(false, w, slave, master));
        let p = pressures(&model.interfaces[0], &r.final_state);
        let force: f64 = p.iter().map(|(pn, a)| pn * a).sum();
        assert!(common::rel(force, 2000.0) <= 1e-9, "{name}: F_N = {force}");
        let dev = p.iter().fold(0.0f64, |a, q| a.max((q.0 - 100.0).abs()));
        eprintln!("{name}: max |p_N - q| = {dev:.3e} MPa");
    }
}

/// The patch case of [`patch`] (horizontal, body "upper" on body "lower",
/// the same supports and load) on a Gmsh mesh of tests/data, its interface
/// between the physical curves `upper.bottom` (slave) and `lower.top`.
fn gmsh_patch(mesh: &str, weights: &str) -> String {
    let path = common::root().join("tests/data").join(mesh);
    let text = patch(false, weights, "", "");
    let (head, rest) = text.split_once("[mesh]\n").unwrap();
    let (_, tail) = rest.split_once("[materials.").unwrap();
    format!(
        "{head}[mesh]\nfile = {:?}\n\
         [[mesh.interface]]\nname = \"contact\"\nupper_curve = \"upper.bottom\"\nlower_curve = \"lower.top\"\nmatching = false\n\
         [materials.{tail}",
        path.display().to_string()
    )
}

/// A Gmsh mesh meshed apart along y = 0 (tests/data/nonmatching-line.geo:
/// unstructured quadrangles of size 1.5 on size 2.5, the slave side two graded
/// edges per master edge, its curve's pieces out of order and in alternating
/// directions in the file): the same patch test as on blocks.
#[test]
fn uniform_pressure_crosses_a_non_matching_gmsh_interface_exactly() {
    for w in ["lumped", "consistent"] {
        let text = gmsh_patch("nonmatching-line.msh", w);
        assert!(text.contains("matching = false") && !text.contains("[[mesh.block]]"));
        check_uniform(&format!("nm-gmsh-patch-{w}"), &text);
    }
}

/// The line mesh with its curves swapped (upper_curve on the lower body and
/// no `upper` / `lower` body names): body A, the slave side, is then the
/// coarser lower body, walked with it on the left (−x), the master normals
/// pointing down into it. A coarser slave does not pass the patch test, but
/// the interface carries the whole load (as on blocks).
#[test]
fn swapped_gmsh_curves_make_the_coarser_side_the_slave_and_still_carry_the_load() {
    for w in ["lumped", "consistent"] {
        let name = format!("nm-gmsh-swapped-{w}");
        let text = gmsh_patch("nonmatching-line.msh", w)
            .replace(
                "upper_curve = \"upper.bottom\"",
                "upper_curve = \"lower.top\"",
            )
            .replace(
                "lower_curve = \"lower.top\"",
                "lower_curve = \"upper.bottom\"",
            );
        let (model, r) = run(&name, &text);
        let im = &model.interfaces[0];
        assert_eq!(model.mesh.bodies[im.body_a], "lower");
        assert!(im.points.iter().all(|pt| pt.normal == [0.0, -1.0, 0.0]));
        let p = pressures(im, &r.final_state);
        let force: f64 = p.iter().map(|(pn, a)| pn * a).sum();
        let dev = p.iter().fold(0.0f64, |a, q| a.max((q.0 - 100.0).abs()));
        eprintln!("{name}: {} points, max |p_N - q| = {dev:.3e} MPa", p.len());
        assert!(common::rel(force, 2000.0) <= 1e-9, "{name}: F_N = {force}");
        assert!(dev > 0.1, "{name}: a coarser slave is not exact");
    }
}

/// The sides of tests/data/nonmatching-arc.msh meet along a circular arc
/// (R = 25.25 mm, 0.5 mm high). Uniform pressure is not an exact solution
/// there (frictionless springs carry no shear), but the springs must hold
/// the upper body up: Σ p_N n_y A = q × width × thickness, every point closed,
/// the normals pointing up into the upper body; the output's s_mm runs along
/// the slave curve from 0 to its length.
#[test]
fn a_curved_non_matching_gmsh_interface_carries_the_load() {
    let name = "nm-gmsh-arc";
    let (model, r) = run(name, &gmsh_patch("nonmatching-arc.msh", "consistent"));
    let im = &model.interfaces[0];
    let p = pressures(im, &r.final_state);
    let mut lift = 0.0;
    for (pt, &(pn, area)) in im.points.iter().zip(&p) {
        assert!(
            pt.normal[1] > 0.98 && pn > 80.0 && pn < 120.0,
            "{pt:?}: {pn}"
        );
        assert!(segment_of(pt).gap.abs() < 1e-5, "{pt:?}");
        lift += pn * area * pt.normal[1];
    }
    let want = 100.0 * 10.0 * 2.0;
    eprintln!("{name}: {} points, Σ p_N n_y A = {lift} N", p.len());
    assert!(
        common::rel(lift, want) <= 1e-9,
        "{name}: {lift} N, want {want}"
    );
    // s_mm of the last increment's interface file
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(name)
        .join("out/interface/0002.csv");
    let csv = std::fs::read_to_string(&out).unwrap_or_else(|e| panic!("{}: {e}", out.display()));
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |c: &str| head.iter().position(|h| *h == c).unwrap();
    let (cx, cs) = (col("x_mm"), col("s_mm"));
    let rows: Vec<(f64, f64)> = lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[cx].parse().unwrap(), f[cs].parse().unwrap())
        })
        .collect();
    assert_eq!(rows.len(), p.len());
    for w in rows.windows(2) {
        assert!(w[1].0 > w[0].0 && w[1].1 > w[0].1, "{w:?}");
    }
    // the slave curve's length is the arc's, 2 R asin(5 / R)
    let rad = 25.25f64;
    let len = 2.0 * rad * (5.0 / rad).asin();
    let (first, last) = (rows[0].1, rows[rows.len() - 1].1);
    assert!(
        first > 0.0 && first < 0.1 && last < len && last > len - 0.1,
        "{first} {last} of {len}"
    );
}

/// tests/data/nonmatching-arc-offset.msh: the same arc divided into 4 slave
/// and 3 master edges per quarter, so that the sides' nodes do not nest.
/// The elements' straight-sided polygons overlap by their chords' sagitta,
/// which the model accepts between bodies joined by a non-matching interface
/// (up to `OVERLAP_LIMIT` of the element); every spring point's gap is that
/// of the two quadratic curves, a few µm at most, and the springs hold the
/// upper body up.
#[test]
fn an_offset_division_of_a_curve_is_accepted_and_carries_the_load() {
    let name = "nm-gmsh-arc-offset";
    let (model, r) = run(
        name,
        &gmsh_patch("nonmatching-arc-offset.msh", "consistent"),
    );
    let im = &model.interfaces[0];
    let p = pressures(im, &r.final_state);
    let mut lift = 0.0;
    let mut widest = 0.0f64;
    for (pt, &(pn, area)) in im.points.iter().zip(&p) {
        assert!(pt.normal[1] > 0.98 && pn > 0.0, "{pt:?}: {pn}");
        widest = widest.max(segment_of(pt).gap.abs());
        lift += pn * area * pt.normal[1];
    }
    eprintln!("{name}: {} points, largest |gap| {widest:.3e} mm", p.len());
    assert!(widest > 0.0 && widest < 1e-3, "{widest}");
    assert!(common::rel(lift, 2000.0) <= 1e-9, "{name}: {lift} N");
}

/// A flat punch over a foundation whose top is rounded at its right end
/// (`round_right = 2.0`: a quarter circle about (18, −2)), non-matching.
/// With the rounding meshed as two quadratic edges their node lies on the
/// 45° ray through the punch corner (20, 0); the edges meet there at a
/// kink of 1.6°, and the corner projects onto neither (ξ = ±1.0105): the
/// case was refused as "projects outside every edge of the master side".
/// Its closest master point is that node, 2√2 − 2 mm away along the 45°
/// ray. With one or three rounding edges a midside node lies on that ray
/// and the corner projects onto it (ξ = 0), with the same gap and normal.
#[test]
fn a_slave_point_facing_the_node_between_two_rounding_edges_is_accepted() {
    for nx in [1, 2, 3] {
        let text = format!(
            "[model]\nplane = \"stress\"\nthickness = 1.0\nsymmetric_half = true\n\
             [[mesh.block]]\nbody = \"punch\"\nx = [0.0, 20.0]\nnx = [4]\ny = [0.0, 20.0]\nny = [2]\n\
             [[mesh.block]]\nbody = \"foundation\"\nx = [0.0, 18.0, 20.0]\nnx = [4, {nx}]\n\
             y = [-60.0, 0.0]\nny = [3]\ntop = {{ round_right = 2.0 }}\n\
             [[mesh.interface]]\nname = \"contact\"\nupper = \"punch\"\nlower = \"foundation\"\nmatching = false\n\
             [materials.punch]\nyoung = 206000.0\npoisson = 0.3\n\
             [materials.foundation]\nyoung = 206000.0\npoisson = 0.3\n\
             [interface.contact]\nlaw = \"power\"\nc_n = 0.001\nm = 0.5\nweights = \"lumped\"\n\
             [[boundary]]\nset = \"punch.left\"\nux = 0.0\n[[boundary]]\nset = \"foundation.left\"\nux = 0.0\n\
             [[boundary]]\nset = \"foundation.bottom\"\nuy = 0.0\n\
             [[load]]\nedges = \"punch.top\"\npressure = 250.0\n"
        );
        let model = common::model(&text);
        let im = &model.interfaces[0];
        let corner = im
            .points
            .iter()
            .zip(&im.pairs)
            .find(|(_, pr)| pr.x == [20.0, 0.0, 0.0])
            .map(|(pt, _)| pt)
            .expect("a spring at the punch corner");
        let g = segment_of(corner);
        let want = 2.0 * std::f64::consts::SQRT_2 - 2.0;
        let r2 = std::f64::consts::FRAC_1_SQRT_2;
        eprintln!(
            "round_right on {nx} edges: corner gap {} mm, normal {:?}, N(ξ) {:?}",
            g.gap, corner.normal, g.nb
        );
        assert!((g.gap - want).abs() < 1e-12, "{nx} edges: gap {}", g.gap);
        assert!(
            (corner.normal[0] - r2).abs() < 1e-12 && (corner.normal[1] - r2).abs() < 1e-12,
            "{nx} edges: normal {:?}",
            corner.normal
        );
        let on_node = if nx == 2 {
            [0.0, 0.0, 1.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        assert!(
            (0..3).all(|j| (g.nb[j] - on_node[j]).abs() < 1e-12),
            "{nx} edges: N(ξ) {:?}",
            g.nb
        );
    }
}

const FRICTION: &str = "law = \"power\"\nc_n = 0.001\nm = 0.5\n[interface.contact.tangential]\nr = 0.9\ns = 0.5\nkp_ratio = 0.05\nmu = 0.2\nbeta = 0.2\nn = 275.0";

#[test]
fn non_matching_point_tangents_match_finite_differences() {
    let slave = "@ = [0.0, 10.0]\nn@ = [6]\nr@ = [0.5]";
    let master = "@ = [0.0, 4.0, 10.0]\nn@ = [4, 6]\nr@ = [2.0, 0.7]";
    let law = "law = \"power\"\nc_n = 0.001\nm = 0.5";
    let mut seen = [false; 3]; // stick, slip, normal only
    for (weights, l) in [
        ("lumped", law),
        ("consistent", law),
        ("lumped", FRICTION),
        ("mortar", law),
        ("mortar", FRICTION),
    ] {
        let text = patch(false, weights, slave, master).replace(law, l);
        let model = common::model(&text);
        let im = &model.interfaces[0];
        assert!(im
            .points
            .iter()
            .all(|p| !matches!(p.coupling, Coupling::Coincident { .. })));
        let mut u = vec![0.0; model.mesh.num_dofs()];
        for (i, v) in u.iter_mut().enumerate() {
            *v = 0.004 * ((i as f64 * 0.37).sin() + 0.8);
        }
        // the upper block pushed down, and slid by amounts from far below to
        // far above the stick limit along the interface
        for (n, x) in model.mesh.nodes.iter().enumerate() {
            if x[1] >= 0.0 && model.mesh.node_sets["upper.all"].binary_search(&n).is_ok() {
                u[2 * n + 1] -= 0.01 * (1.0 + 0.5 * (x[0] * 0.7).sin());
                u[2 * n] += 1e-6 * 10f64.powf(0.5 * x[0]);
            }
        }
        for pt in &im.points {
            let nd = pt.ndofs();
            let dofs = im.point_dofs(pt);
            assert_eq!(dofs.len(), nd);
            let (mut r, mut k) = (vec![0.0; nd], vec![0.0; nd * nd]);
            let ev = im.eval_point(pt, &u, &Default::default(), None, &mut r, Some(&mut k));
            assert!(
                ev.u_n > 1e-6,
                "{weights}: the point should be closed: {}",
                ev.u_n
            );
            match ev.status {
                Status::Stick => seen[0] = true,
                Status::MicroSlip | Status::MacroSlip => seen[1] = true,
                _ => seen[2] = true,
            }
            let kmax = k.iter().fold(1e-30f64, |a, v| a.max(v.abs()));
            let h = 1e-9;
            let jac = fd::central_columns(&vec![h; nd], |j, s| {
                let mut up = u.clone();
                up[dofs[j]] += s;
                let mut rp = vec![0.0; nd];
                im.eval_point(pt, &up, &Default::default(), None, &mut rp, None);
                rp
            });
            let worst = fd::worst(&jac, |i, j| k[i * nd + j], fd::Scale::Of(kmax));
            assert!(
                worst.ratio < 1e-5,
                "{weights} {l}: point {:?} {worst}",
                ev.status,
            );
        }
    }
    assert!(
        seen.iter().all(|&s| s),
        "stick, slip and frictionless points all checked: {seen:?}"
    );
}
