//! Interfaces on a Gmsh mesh of volumes refused where a patch of the
//! bad-input corpus cannot make the mesh: two surfaces meshed unlike over
//! their common part, and the surface keys on a generated layout.
//!
//! `cargo test --release --test integration gmsh_surfaces::`

use crate::common;
use crate::common::msh::{boxes_msh, cells, Box3};
use asperity::app::driver::{self, RunOptions};

/// The error of loading the corpus's stacked-boxes case (its interface
/// between top.bottom and base.top) on `msh`, with the case text edited.
fn refusal(tag: &str, msh: &str, edit: &dyn Fn(String) -> String) -> String {
    let text =
        std::fs::read_to_string(common::root().join("tests/bad_inputs/base/stacked-h20.toml"))
            .unwrap();
    let case = common::case_dir(&format!("gmsh-surfaces-{tag}"), &edit(text));
    std::fs::write(case.with_file_name("mesh.msh"), msh).unwrap();
    let e = driver::load_model(&case, &RunOptions::default())
        .err()
        .unwrap_or_else(|| panic!("{tag}: must be refused"))
        .to_string();
    assert!(!e.contains('\n'), "{e}");
    e
}

/// The top on a base meshed twice as fine along x: every node of the top's
/// bottom has a partner (its midsides fall on the base's corners), but no
/// face of the base is made of them.
#[test]
fn surfaces_meshed_unlike_are_refused_naming_the_face() {
    let msh = boxes_msh(&[
        Box3 {
            name: "top",
            axes: [cells(0.0, 20.0, 2), vec![0.0, 10.0], vec![0.0, 10.0]],
        },
        Box3 {
            name: "base",
            axes: [cells(0.0, 30.0, 6), vec![-10.0, 0.0], vec![0.0, 10.0]],
        },
    ]);
    let e = refusal("unlike", &msh, &|t| t);
    assert!(
        e.contains("the face of \"top.bottom\" with corners at nodes")
            && e.contains("are not the nodes of one face of it")
            && e.contains("[[mesh.interface]] \"contact\""),
        "{e}"
    );
}

/// The same with the base coarser than the top: a node of the top has no
/// partner, named by its tag and place.
#[test]
fn a_coarser_lower_surface_leaves_a_node_without_partner() {
    let msh = boxes_msh(&[
        Box3 {
            name: "top",
            axes: [cells(0.0, 20.0, 4), vec![0.0, 10.0], vec![0.0, 10.0]],
        },
        Box3 {
            name: "base",
            axes: [cells(0.0, 30.0, 3), vec![-10.0, 0.0], vec![0.0, 10.0]],
        },
    ]);
    let e = refusal("coarser", &msh, &|t| t);
    assert!(
        e.contains("of surface \"top.bottom\"")
            && e.contains("has no partner on surface \"base.top\""),
        "{e}"
    );
}

/// upper_surface / lower_surface on a generated layout (swept or not).
#[test]
fn surface_keys_on_generated_blocks_are_refused() {
    let text = std::fs::read_to_string(common::root().join("tests/bad_inputs/base/punch-3d.toml"))
        .unwrap()
        .replace(
            "lower = \"foundation\"",
            "lower = \"foundation\"\nupper_surface = \"punch.bottom\"",
        );
    let case = common::case_dir("gmsh-surfaces-layout", &text);
    let e = driver::load_model(&case, &RunOptions::default())
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains(
            "upper_surface / lower_surface name physical surfaces of a mesh file of volumes"
        ),
        "{e}"
    );
}
