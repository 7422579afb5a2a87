//! The 6-node triangle through the whole pipeline: Lamé's thick cylinder
//! meshed in triangles converges at the order of the same mesh in 8-node
//! quads, and a Gmsh mesh of 6-node triangles (the punch of
//! cases/punch-gmsh, meshed without recombination) solves, balances and
//! writes quadratic-triangle cells.

use crate::common::{self, Quiet};
use asperity::input::case::Case;
use asperity::input::mesh::{Element, Family, Mesh};
use asperity::model::{Adapted, Model};

/// Each 8-node quad of `mesh` as two 6-node triangles split along its
/// diagonal 0–2, the diagonal's midside a new node at the quad's centre
/// (the map of ξ = η = 0): the same geometry, the same sides.
fn in_triangles(mesh: &Mesh) -> Mesh {
    let mut out = mesh.clone();
    out.elements.clear();
    for (e, el) in mesh.elements.iter().enumerate() {
        let c = mesh.element_coords(e);
        let n = asperity::physics::element::q8::shape(0.0, 0.0);
        let centre = (0..8).fold([0.0, 0.0], |p, a| {
            [p[0] + n[a] * c[a][0], p[1] + n[a] * c[a][1]]
        });
        out.nodes.push([centre[0], centre[1], 0.0]);
        let d = out.nodes.len() - 1;
        let q = el.nodes();
        out.elements
            .push(Element::t6([q[0], q[1], q[2], q[4], q[5], d], el.body));
        out.elements
            .push(Element::t6([q[0], q[2], q[3], d, q[6], q[7]], el.body));
    }
    out
}

/// A thick tube a ≤ r ≤ b under internal pressure, its ends held axially,
/// nx elements through the wall and two along the axis.
fn tube(nx: usize) -> String {
    common::case()
        .plane("axisymmetric")
        .block("tube", [10.0, 25.0], [nx], [0.0, 4.0], [2])
        .material("tube", 210000.0, 0.3)
        .uy("tube.bottom", 0.0)
        .uy("tube.top", 0.0)
        .pressure("tube.left", 150.0)
        .solver("increments = 1")
        .tolerances(1e-12, 1e-14)
        .no_vtu()
        .build()
}

/// The L2 error of (σ_rr, σ_θθ) over the tube against Lamé's solution
/// (the model's own Gauss points and volume elements), MPa·mm^(3/2).
fn stress_error(model: &Model) -> f64 {
    let r = asperity::app::driver::solve(model, &mut Quiet).unwrap();
    let (a, b, p) = (10.0f64, 25.0f64, 150.0);
    let big_a = p * a * a / (b * b - a * a);
    let big_b = p * a * a * b * b / (b * b - a * a);
    let mut e2 = 0.0;
    for e in 0..model.mesh.elements.len() {
        let g = model.geometry(e);
        for (ip, s) in r
            .final_state
            .gauss
            .range(model.points(e))
            .iter()
            .enumerate()
        {
            let x = g.x[ip][0];
            let (rr, tt) = (big_a - big_b / (x * x), big_a + big_b / (x * x));
            e2 += g.dv[ip] * ((s.stress[0] - rr).powi(2) + (s.stress[3] - tt).powi(2));
        }
    }
    e2.sqrt()
}

/// Both meshes of the same quads converge at the rate of quadratic
/// elements, h² in the stress (Zienkiewicz, Taylor & Zhu, 7th ed., sec.
/// 14.2): the triangles' observed order is within 0.3 of the quads', both
/// between 1.7 and 2.6, and every error falls with h.
#[test]
fn lames_cylinder_on_triangles_converges_at_the_order_of_quads() {
    let mut errors = [Vec::new(), Vec::new()];
    for nx in [2, 4, 8, 16] {
        let text = tube(nx);
        let quads = common::model(&text);
        let case = Case::parse(&text, "tube.toml").unwrap();
        let mesh = in_triangles(&quads.mesh);
        let start_nodes = mesh.nodes.len();
        let tris = Model::build_on(
            case,
            Some(Adapted {
                mesh,
                start_nodes,
                excluded: None,
            }),
        )
        .unwrap();
        assert!(tris.mesh.elements.iter().all(|el| el.family == Family::T6));
        errors[0].push(stress_error(&quads));
        errors[1].push(stress_error(&tris));
    }
    println!(
        "Lamé cylinder, L2 stress error: nx = 2, 4, 8, 16\n  Q8: {:?}\n  T6: {:?}",
        errors[0], errors[1]
    );
    let orders: Vec<f64> = errors
        .iter()
        .map(|e| {
            assert!(e.windows(2).all(|w| w[1] < w[0]), "{e:?}");
            (e[2] / e[3]).log2()
        })
        .collect();
    println!(
        "  orders (last halving): Q8 {:.3}, T6 {:.3}",
        orders[0], orders[1]
    );
    for o in &orders {
        assert!((1.7..2.6).contains(o), "order {o}");
    }
    assert!(orders[1] > orders[0] - 0.3, "{orders:?}");
}

/// The punch of cases/punch-gmsh meshed by Gmsh in 6-node triangles
/// (tests/data/tiny-t6.msh): the run completes, the reactions balance the
/// applied load, every cell of the VTU is a quadratic triangle (type 22),
/// and the error estimate is written for every cell.
#[test]
fn a_gmsh_mesh_of_triangles_solves_and_writes_quadratic_triangles() {
    let root = common::root();
    let text = std::fs::read_to_string(root.join("cases/punch-gmsh/case.toml")).unwrap();
    let case = common::case_dir("t6-punch", &text);
    let dir = case.parent().unwrap();
    std::fs::copy(root.join("tests/data/tiny-t6.msh"), dir.join("mesh.msh")).unwrap();
    let model = Model::build(Case::load(&case).unwrap()).unwrap();
    assert_eq!(model.mesh.elements.len(), 20);
    assert!(model.mesh.elements.iter().all(|el| el.family == Family::T6));
    // written as text, to read the cells below
    std::fs::write(&case, format!("{text}\n[output]\nvtu_format = \"ascii\"\n")).unwrap();
    let out = dir.join("out");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(["run", "--quiet", case.to_str().unwrap(), "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["complete"], true, "{summary}");
    // 250 MPa on the half punch's 20 mm × 1 mm: the foundation's base
    // carries 5,000 N, and the interface the same mean pressure
    let base = summary["reactions"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["name"] == "foundation.bottom")
        .expect("the base's reaction");
    let fy = base["final"][0].as_f64().unwrap();
    assert!(common::rel(fy, 250.0 * 20.0) < 1e-9, "base reaction {fy} N");
    let p = summary["final"]["mean_pressure_mpa"].as_f64().unwrap();
    assert!(common::rel(p, 250.0) < 1e-6, "mean pressure {p} MPa");
    // the last increment's VTU: 20 cells, each of type 22, each with its
    // share of the error estimate
    let vtu = std::fs::read_dir(out.join("vtu"))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "vtu"))
        .max()
        .expect("a VTU file");
    let doc = std::fs::read_to_string(&vtu).unwrap();
    let array = |name: &str| -> Vec<f64> {
        let at = doc
            .find(&format!("Name=\"{name}\""))
            .unwrap_or_else(|| panic!("{name}"));
        let body = &doc[at..];
        let body = &body[body.find('>').unwrap() + 1..body.find("</").unwrap()];
        body.split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect()
    };
    assert_eq!(array("types"), vec![22.0; 20]);
    assert_eq!(
        array("offsets"),
        (1..=20).map(|k| 6.0 * k as f64).collect::<Vec<_>>()
    );
    let eta = array("error_estimate");
    assert_eq!(eta.len(), 20);
    assert!(eta.iter().all(|v| v.is_finite() && *v >= 0.0) && eta.iter().any(|v| *v > 0.0));
}
