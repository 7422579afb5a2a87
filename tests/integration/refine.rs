//! A locally refined run through the program (`[mesh] refine_region`): the
//! VTU holds every child element and, at each hanging node, the displacement
//! its constraint gives; a stopped run resumes to the uninterrupted one, and
//! a restart of it with another refinement is refused by the fingerprint;
//! a Gmsh mesh refines the same way.

use crate::common;
use asperity::input::mesh::refine::{edge_shape, hanging_nodes};

/// cases/punch-plane-stress with its punch corner refined `levels` times.
fn punch(levels: usize) -> String {
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    text.replacen(
        "\n[mesh]\nrefine = 1\n",
        &format!(
            "\n[mesh]\nrefine = 1\nrefine_region = {{ x = [15.0, 25.0], y = [-5.0, 5.0], levels = {levels} }}\n"
        ),
        1,
    )
}

#[test]
fn hanging_nodes_are_written_constrained_and_a_refined_run_restarts_only_itself() {
    let case = common::case_dir("refine-punch-2", &punch(2));
    let other = common::case_dir("refine-punch-1", &punch(1));
    let root = common::scratch("refine-restart");
    let (full, part, resumed, refused) = (
        root.join("full"),
        root.join("part"),
        root.join("resumed"),
        root.join("refused"),
    );
    let (code, err) = common::run_case(&case, &full, &[]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = common::run_case(&case, &part, &["--stop-after", "5"]);
    assert_eq!(code, 3, "{err}");
    let p = part.to_str().unwrap();
    let (code, err) = common::run_case(&case, &resumed, &["--restart", p]);
    assert_eq!(code, 0, "{err}");
    for f in ["curve.csv", "restart.bin", "vtu/0020.vtu"] {
        assert!(
            std::fs::read(resumed.join(f)).unwrap() == std::fs::read(full.join(f)).unwrap(),
            "{f} of the resumed run differs"
        );
    }
    let (code, err) = common::run_case(&other, &refused, &["--restart", p]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("fingerprint mismatch"), "{err}");
    assert!(!refused.exists());

    // the VTU: every child, and the hanging nodes' constrained values
    let model = common::model(&punch(2));
    let vtu = full.join("vtu/0020.vtu");
    let u = common::vtu_array(&vtu, "displacement");
    let nodes = model.mesh.nodes.len();
    assert_eq!(u.len() % nodes, 0);
    let k = u.len() / nodes;
    let types = common::vtu_array(&vtu, "types");
    assert_eq!(types.len(), model.mesh.elements.len());
    let hanging = hanging_nodes(&model.mesh);
    assert!(hanging.len() >= 8, "{} hanging nodes", hanging.len());
    let scale = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for h in &hanging {
        let w = edge_shape(h.s);
        for c in 0..2 {
            let want: f64 = (0..3).map(|i| w[i] * u[k * h.edge[i] + c]).sum();
            let got = u[k * h.node + c];
            assert!(
                (got - want).abs() < 1e-12 * scale,
                "hanging node {}: u{c} {got} written, {want} from its edge",
                h.node
            );
        }
    }
}

/// cases/punch-gmsh (the punch's mesh read from Gmsh) with the same
/// `refine_region` gives the block mesh's refined run: the same dof count
/// and settlement (to 1e-8, as the unrefined pair in gmsh.rs).
#[test]
fn a_gmsh_mesh_refines_as_the_block_mesh() {
    let dir = common::root().join("cases/punch-gmsh");
    let text = std::fs::read_to_string(dir.join("case.toml")).unwrap();
    let line = "file = \"mesh.msh\"";
    assert!(text.contains(line));
    let text = text.replacen(
        line,
        "refine_region = { x = [15.0, 25.0], y = [-5.0, 5.0], levels = 2 }\nfile = \"mesh.msh\"",
        1,
    );
    let case = common::case_dir("refine-gmsh", &text);
    std::fs::copy(dir.join("mesh.msh"), case.with_file_name("mesh.msh")).unwrap();
    let root = common::scratch("refine-gmsh-runs");
    let (code, err) = common::run_case(&case, &root.join("gmsh"), &[]);
    assert_eq!(code, 0, "{err}");
    let block = common::case_dir("refine-block", &punch(2));
    let (code, err) = common::run_case(&block, &root.join("block"), &[]);
    assert_eq!(code, 0, "{err}");
    let json = |d: &str| -> serde_json::Value {
        serde_json::from_str(&common::read_out(&root.join(d), "summary.json")).unwrap()
    };
    let (g, b) = (json("gmsh"), json("block"));
    assert_eq!(g["dofs"], b["dofs"]);
    assert_eq!(g["elements"], b["elements"]);
    let u = |v: &serde_json::Value| v["final"]["center_displacement_mm"].as_f64().unwrap();
    assert!(
        ((u(&g) - u(&b)) / u(&b)).abs() < 1e-8,
        "{} vs {}",
        u(&g),
        u(&b)
    );
}
