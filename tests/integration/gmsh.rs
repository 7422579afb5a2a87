//! Meshes read from Gmsh files: ASCII and binary give the same model, the
//! punch-gmsh case (Gmsh's copy of punch-plane-stress's mesh) gives
//! punch-plane-stress's answer, and broken meshes give one clear error line.
//!
//! `cargo test --release --test integration gmsh::`

use crate::common;
use asperity::app::driver::{self, RunOptions};
use asperity::model::Model;
use asperity::solve::RunResult;
use std::path::{Path, PathBuf};
use std::process::Command;

const CASE: &str = include_str!("../../cases/punch-gmsh/case.toml");

fn data(name: &str) -> PathBuf {
    common::root().join("tests").join("data").join(name)
}

/// punch-gmsh's case reading `mesh` (absolute path), built into a model.
fn model_with_mesh(tag: &str, mesh: &Path) -> Model {
    let text = CASE.replace(
        "file = \"mesh.msh\"",
        &format!("file = {:?}", mesh.display().to_string()),
    );
    let case = common::case_dir(&format!("gmsh-model-{tag}"), &text);
    driver::load_model(&case, &RunOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn ascii_and_binary_files_give_identical_models() {
    let a = model_with_mesh("ascii", &common::root().join("cases/punch-gmsh/mesh.msh"));
    let b = model_with_mesh("binary", &data("punch-bin.msh"));
    let (ma, mb) = (&a.mesh, &b.mesh);
    assert_eq!(ma.nodes.len(), 806);
    assert_eq!(ma.elements.len(), 240);
    // ASCII files hold 16 significant digits (Gmsh's %.16g), binary ones all 17:
    // the coordinates agree to the last printed digit, everything else exactly.
    assert_eq!(ma.nodes.len(), mb.nodes.len());
    for (i, (x, y)) in ma.nodes.iter().zip(&mb.nodes).enumerate() {
        for k in 0..2 {
            let d = (x[k] - y[k]).abs();
            assert!(
                d <= 1e-15 * x[k].abs().max(1.0) * 10.0,
                "node {i}: {x:?} vs {y:?}"
            );
        }
    }
    assert_eq!(ma.bodies, mb.bodies);
    assert_eq!(ma.elements, mb.elements);
    assert_eq!(ma.node_sets, mb.node_sets);
    assert_eq!(ma.edge_sets, mb.edge_sets);
    let pairs = |m: &Model| -> Vec<(usize, usize)> {
        m.interfaces[0].pairs.iter().map(|p| (p.a, p.b)).collect()
    };
    assert_eq!(pairs(&a), pairs(&b));
    assert_eq!(a.prescribed, b.prescribed);
    let fmax = a.f_ext.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let df = a
        .f_ext
        .iter()
        .zip(&b.f_ext)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(
        df <= 1e-12 * fmax,
        "load vectors differ by {df:e} (max {fmax})"
    );
    assert_eq!(a.probe_node, b.probe_node);
}

/// Every node of the Gmsh mesh has a node of the generated mesh within 1e-6 mm
/// and vice versa; returns the largest distance.
fn node_distance(g: &asperity::input::mesh::Mesh, p: &asperity::input::mesh::Mesh) -> f64 {
    let nearest = |x: [f64; 3], m: &asperity::input::mesh::Mesh| {
        m.nodes
            .iter()
            .map(|y| (x[0] - y[0]).hypot(x[1] - y[1]))
            .fold(f64::INFINITY, f64::min)
    };
    let d1 = g.nodes.iter().map(|&x| nearest(x, p)).fold(0.0, f64::max);
    let d2 = p.nodes.iter().map(|&x| nearest(x, g)).fold(0.0, f64::max);
    d1.max(d2)
}

fn run(case: &str) -> RunResult {
    let out = common::scratch(&format!("gmsh-run-{case}")).join("out");
    let opts = RunOptions {
        out: Some(out),
        quiet: true,
        ..RunOptions::default()
    };
    let (_, _, r) = driver::run(&common::root().join("cases").join(case), &opts)
        .unwrap_or_else(|e| panic!("{e}"));
    r
}

#[test]
fn punch_gmsh_gives_the_answer_of_punch_plane_stress() {
    let g = driver::load_model(
        &common::root().join("cases/punch-gmsh"),
        &RunOptions::default(),
    )
    .unwrap();
    let p = driver::load_model(
        &common::root().join("cases/punch-plane-stress"),
        &RunOptions::default(),
    )
    .unwrap();
    assert_eq!(g.mesh.nodes.len(), p.mesh.nodes.len());
    assert_eq!(g.mesh.elements.len(), p.mesh.elements.len());
    assert_eq!(g.dofs.n_eq, p.dofs.n_eq);
    assert_eq!(g.interfaces[0].pairs.len(), p.interfaces[0].pairs.len());
    // Gmsh's geometric progression and its second-order nodes are computed
    // differently from ours: nodes differ by up to ~2.4e-7 mm (measured).
    let d = node_distance(&g.mesh, &p.mesh);
    eprintln!("largest node distance, Gmsh vs generated: {d:.3e} mm");
    assert!(d < 1e-6, "nodes differ by {d:e} mm");
    let (rg, rp) = (run("punch-gmsh"), run("punch-plane-stress"));
    let (fg, fp) = (
        rg.first_yield.clone().unwrap(),
        rp.first_yield.clone().unwrap(),
    );
    // A node perturbation of 2.4e-7 mm against element sizes of 0.5 mm or more
    // moves the answers by ~1e-9 relative (measured: first yield 1.2e-9, centre
    // displacement 2.0e-9); the first-yield load is located to 1e-9 in σ_eq/σ_Y.
    // 2e-8 leaves a margin of 10 and still catches any real difference (one
    // misplaced node or a wrong pairing changes them by 1e-4 or more).
    let rel = common::rel(fg.total_load_kn, fp.total_load_kn);
    assert!(
        rel < 2e-8,
        "first yield {} vs {} kN",
        fg.total_load_kn,
        fp.total_load_kn
    );
    assert_eq!(fg.body, fp.body);
    assert!((fg.x - fp.x).abs() < 1e-6 && (fg.depth - fp.depth).abs() < 1e-6);
    let (ug, up) = (
        rg.final_state_measures().center_displacement,
        rp.final_state_measures().center_displacement,
    );
    let rel = common::rel(ug, up);
    assert!(rel < 2e-8, "centre displacement {ug} vs {up} mm");
    let its = |r: &RunResult| r.increments.iter().map(|i| i.iterations).sum::<usize>();
    assert_eq!(its(&rg), its(&rp), "Newton iterations of the increments");
    // all iterations, the first-yield search included (summary.json's newton_iterations)
    assert_eq!(rg.stats.iterations, rp.stats.iterations);
    assert_eq!(rg.cutbacks + rp.cutbacks, 0);
}

trait LastMeasures {
    fn final_state_measures(&self) -> asperity::solve::Measures;
}

impl LastMeasures for RunResult {
    fn final_state_measures(&self) -> asperity::solve::Measures {
        self.increments.last().unwrap().measures
    }
}

/// Runs the binary on punch-gmsh's case with `mesh` as mesh.msh (and the case
/// text changed by `edit`); expects exit code 2, one `error:` line holding every
/// needle, no panic and no output folder.
fn rejects(name: &str, mesh: &[u8], edit: &dyn Fn(&str) -> String, needles: &[&str]) {
    let case = common::case_dir(&format!("gmsh-bad-{name}"), &edit(CASE));
    let dir = case.parent().unwrap();
    std::fs::write(dir.join("mesh.msh"), mesh).unwrap();
    let out = dir.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args([
            "run",
            dir.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{name}: {err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{name}: expected one line, got: {err}");
    assert!(lines[0].starts_with("error: "), "{name}: {err}");
    assert!(!err.contains("panicked"), "{name}: {err}");
    for n in needles {
        assert!(err.contains(n), "{name}: '{n}' not in: {err}");
    }
    assert!(!out.exists(), "{name}: output folder left behind");
}

fn same(s: &str) -> String {
    s.to_string()
}

fn ascii() -> String {
    std::fs::read_to_string(common::root().join("cases/punch-gmsh/mesh.msh")).unwrap()
}

#[test]
fn truncated_files_are_named_with_line_or_byte() {
    let text = ascii();
    let cut = &text[..text.len() / 2];
    let line = cut.lines().count();
    rejects(
        "truncated",
        cut.as_bytes(),
        &same,
        &["mesh.msh:", "truncated file", &format!(":{line}:")],
    );
    let bin = std::fs::read(data("punch-bin.msh")).unwrap();
    rejects(
        "binary-truncated",
        &bin[..bin.len() * 2 / 3],
        &same,
        &["mesh.msh (byte ", "truncated file"],
    );
    // ends right after the nodes: $Elements missing
    let end = text.find("$Elements").unwrap();
    rejects(
        "no-elements",
        &text.as_bytes()[..end],
        &same,
        &["missing section $Elements"],
    );
}

#[test]
fn missing_physical_group_is_named() {
    rejects(
        "missing-physical",
        ascii().as_bytes(),
        &|s| {
            s.replace(
                "upper_curve = \"punch.bottom\"",
                "upper_curve = \"punch.base\"",
            )
        },
        &[
            "[[mesh.interface]] \"contact\"",
            "physical curve \"punch.base\" not found in",
            "punch.bottom",
        ],
    );
    rejects(
        "surface-as-curve",
        ascii().as_bytes(),
        &|s| {
            s.replace(
                "lower_curve = \"foundation.top\"",
                "lower_curve = \"foundation\"",
            )
        },
        &["\"foundation\" is a physical surface (dimension 2)"],
    );
}

#[test]
fn unpaired_interface_node_is_named_with_tag_and_coordinates() {
    // move the first node of the punch's bottom curve (entity 1 1) by 0.01 mm in x
    let text = ascii();
    let at = text.find("\n1 1 0 15\n").expect("node block of curve 1");
    let lines: Vec<&str> = text[at + 1..].lines().take(31).collect();
    let tag = lines[1];
    let x: f64 = lines[16].split(' ').next().unwrap().parse().unwrap();
    let moved = format!("{} 0 0", x + 0.01);
    let mut block = lines.clone();
    block[16] = &moved;
    let text = text.replacen(&lines.join("\n"), &block.join("\n"), 1);
    rejects(
        "unpaired",
        text.as_bytes(),
        &same,
        &[
            &format!("node {tag} at ({}, 0)", x + 0.01),
            "has no partner on curve \"foundation.top\"",
        ],
    );
}

#[test]
fn unsupported_element_type_is_named_with_line() {
    let text = ascii();
    let at = text.find("\n2 1 16 48\n").expect("quad block of surface 1");
    let line = text[..at + 1].lines().count() + 1;
    let text = text.replacen("\n2 1 16 48\n", "\n2 1 10 48\n", 1);
    rejects(
        "nine-node",
        text.as_bytes(),
        &same,
        &[
            &format!("mesh.msh:{line}:"),
            "element type 10 (9-node quadrangle) not supported",
        ],
    );
}

#[test]
fn file_meshes_refuse_refine_and_uniform() {
    rejects(
        "refine",
        ascii().as_bytes(),
        &|s| s.replace("[mesh]\n", "[mesh]\nrefine = 2\n"),
        &["[mesh] refine", "cannot refine a mesh read from a file"],
    );
    let dir = common::root().join("cases/punch-gmsh");
    let opts = RunOptions {
        uniform: true,
        ..RunOptions::default()
    };
    let e = driver::load_model(&dir, &opts).err().unwrap().to_string();
    assert!(e.contains("--uniform: cannot regrade"), "{e}");
    let opts = RunOptions {
        refine: Some(2),
        ..RunOptions::default()
    };
    let e = driver::load_model(&dir, &opts).err().unwrap().to_string();
    assert!(e.contains("cannot refine a mesh read from a file"), "{e}");
    rejects(
        "unknown-key",
        ascii().as_bytes(),
        &|s| s.replace("upper_curve =", "upper_curv ="),
        &["unknown field `upper_curv`"],
    );
    rejects(
        "blocks-and-file",
        ascii().as_bytes(),
        &|s| {
            s.replace(
                "[[mesh.interface]]",
                "[[mesh.block]]\nbody = \"x\"\nx = [0.0, 1.0]\nnx = [1]\ny = [0.0, 1.0]\nny = [1]\n\n[[mesh.interface]]",
            )
        },
        &["give either file or [[mesh.block]], not both"],
    );
}
