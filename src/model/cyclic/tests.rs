use super::*;
use crate::model::Model;

/// A tube a = 10 ≤ r ≤ b = 25, 0 ≤ y ≤ 8, revolved through `angle`° in
/// `n` layers, one of `sectors`; its bottom clamped, `extra` appended.
fn tube(angle: f64, n: usize, sectors: usize, extra: &str) -> String {
    format!(
        "[model]\nplane = \"3d\"\ncyclic = {{ sectors = {sectors}, faces = [\"tube.theta0\", \"tube.theta1\"] }}\n\
         [mesh]\nrevolve = {{ angle = {angle}, n = {n} }}\n\
         [[mesh.block]]\nbody = \"tube\"\nx = [10.0, 25.0]\nnx = [2]\ny = [0.0, 8.0]\nny = [2]\n\
         [materials.tube]\nyoung = 210000.0\npoisson = 0.3\n\
         [[boundary]]\nset = \"tube.bottom\"\nux = 0.0\nuy = 0.0\nuz = 0.0\n\
         [[load]]\nfaces = \"tube.top\"\ntorque = 1e5\n{extra}"
    )
}

fn model(text: &str) -> Model {
    Model::parse(text, "test.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn refusal(text: &str) -> String {
    match Model::parse(text, "test.toml") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// R(α)ᴺ = I for α = 360°/N, R(α) takes (r, y, 0) to the sweep's (r cos
/// α, y, r sin α), and its exact zeros are zeros (cos 90° = 6e-17 is not a
/// coefficient).
#[test]
fn the_rotation_is_the_sweeps_and_n_of_them_are_the_identity() {
    for n in [2usize, 3, 4, 7, 12, 360] {
        let a = std::f64::consts::TAU / n as f64;
        let r = rotation(a);
        let mut p = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        for _ in 0..n {
            p = std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..3).map(|k| r[i][k] * p[k][j]).sum())
            });
        }
        for (i, row) in p.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((v - want).abs() < 1e-12, "N = {n}: {p:?}");
            }
        }
        let x = apply(&r, [2.0, 3.0, 0.0]);
        let want = [2.0 * a.cos(), 3.0, 2.0 * a.sin()];
        assert!((0..3).all(|c| (x[c] - want[c]).abs() < 1e-15), "{x:?}");
    }
    assert_eq!(rotation(std::f64::consts::FRAC_PI_2)[0][0], 0.0);
    assert_eq!(rotation(std::f64::consts::PI)[2][0], 0.0);
}

/// Every tie of a 30° sector is met exactly by the rigid rotation about
/// the y axis, u = ω ŷ × x, and by a translation along it (R commutes with
/// both), and broken by a translation across the axis and a rotation
/// about an axis across it (which the ties hold).
#[test]
fn a_rigid_rotation_about_the_axis_satisfies_every_tie() {
    let m = model(&tube(30.0, 3, 12, ""));
    let c = m.cyclic.as_ref().unwrap();
    // 3 rows of 5 nodes (the elements' corner y) and 2 of 3 (their
    // midside y) on each face
    assert_eq!(c.pairs.len(), 5 * 3 + 3 * 2, "{:?}", c.pairs);
    assert!(c.axis.is_empty());
    assert_eq!(c.sectors, 12);
    assert!((c.angle - 30f64.to_radians()).abs() < 1e-15);
    let ties = &m.constraints.list;
    // the clamped bottom holds both ends of its pairs alike: 3 of 5 rows along
    // y per face are free
    assert_eq!(c.held_alike, 3 * 5);
    assert_eq!(ties.len(), 3 * c.pairs.len() - c.held_alike);
    let nd = m.mesh.node_dofs;
    let residual = |u: &dyn Fn([f64; 3]) -> [f64; 3]| {
        let mut v = vec![0.0; m.n_dofs()];
        for (n, x) in m.mesh.nodes.iter().enumerate() {
            let un = u(*x);
            for k in 0..3 {
                v[nd.dof(n, k)] = un[k];
            }
        }
        ties.iter()
            .map(|t| (v[t.slave] - t.terms.iter().map(|&(d, a)| a * v[d]).sum::<f64>()).abs())
            .fold(0.0f64, f64::max)
    };
    let w = 1e-3;
    // ŷ × x = (z, 0, −x)
    let spin = residual(&|x| [w * x[2], 0.0, -w * x[0]]);
    let along = residual(&|_| [0.0, w, 0.0]);
    assert!(spin <= 1e-15 * 25.0 * 4.0, "{spin:e}");
    assert_eq!(along, 0.0);
    let across = residual(&|_| [w, 0.0, 0.0]);
    let tilt = residual(&|x| [0.0, w * x[2], -w * x[1]]);
    assert!(across > 0.1 * w && tilt > 0.1 * w, "{across} {tilt}");
}

/// A tie row of the second face that a support prescribes is left out
/// only when the supports hold its partner alike: values and histories.
#[test]
fn a_tie_is_the_supports_own_only_when_they_hold_both_ends_alike() {
    let r = rotation(30f64.to_radians());
    let row: Vec<(usize, f64)> = vec![(0, r[0][0]), (2, r[0][2])];
    let given = |v: &[(usize, f64, Option<usize>)]| -> HashMap<usize, (f64, Option<usize>)> {
        v.iter().map(|&(d, x, h)| (d, (x, h))).collect()
    };
    // u_x(s) = cos α u_x(m) − sin α u_z(m)
    let (c, s) = (r[0][0], -r[0][2]);
    let held = given(&[(0, 0.2, None), (2, 0.1, None)]);
    assert!(held_alike(&row, c * 0.2 - s * 0.1, None, &held));
    assert!(!held_alike(&row, c * 0.2, None, &held));
    // a master not prescribed
    assert!(!held_alike(&row, 0.0, None, &given(&[(0, 0.0, None)])));
    // zeros on any history, values on the slave's
    assert!(held_alike(
        &row,
        0.0,
        Some(1),
        &given(&[(0, 0.0, None), (2, 0.0, Some(2))])
    ));
    let on = given(&[(0, 0.2, Some(1)), (2, 0.0, None)]);
    assert!(held_alike(&row, c * 0.2, Some(1), &on));
    assert!(!held_alike(&row, c * 0.2, Some(2), &on));
}

/// Faces given the other way round turn by −α; a solid bar's sector (the
/// O-grid core) has its axis nodes held in x and z, and is held by its
/// ties, an end and one hoop displacement.
#[test]
fn the_faces_turn_either_way_and_the_axis_is_held_across() {
    let text = tube(30.0, 3, 12, "").replace(
        "[\"tube.theta0\", \"tube.theta1\"]",
        "[\"tube.theta1\", \"tube.theta0\"]",
    );
    let m = model(&text);
    let c = m.cyclic.as_ref().unwrap();
    assert!((c.angle + 30f64.to_radians()).abs() < 1e-15);
    let bar = "[model]\nplane = \"3d\"\ncyclic = { sectors = 4, faces = [\"bar.theta0\", \"bar.theta1\"] }\n\
         [mesh]\nrevolve = { angle = 90.0, n = 4 }\n\
         [[mesh.block]]\nbody = \"bar\"\nx = [0.0, 5.0]\nnx = [2]\ny = [0.0, 10.0]\nny = [2]\n\
         [materials.bar]\nyoung = 210000.0\npoisson = 0.3\n\
         [[boundary]]\nset = \"bar.bottom\"\nux = 0.0\nuy = 0.0\nuz = 0.0\n\
         [[load]]\nfaces = \"bar.top\"\ntorque = 1e5\n";
    let m = model(bar);
    let c = m.cyclic.as_ref().unwrap();
    // the axis' 5 nodes along y
    assert_eq!(c.axis.len(), 5);
    for &n in &c.axis {
        for k in [0, 2] {
            let d = m.mesh.node_dofs.dof(n, k);
            assert!(m.prescribed.iter().any(|p| p.0 == d), "node {n}");
        }
        // u_y stays free off the clamped end
        let d = m.mesh.node_dofs.dof(n, 1);
        let held = m.prescribed.iter().any(|p| p.0 == d);
        assert_eq!(held, m.mesh.nodes[n][1] == 0.0, "node {n}");
    }
    // an end held axially only, the rotation by uz at one node: held;
    // without that node, the rotation about y is free
    let axial = bar.replace("ux = 0.0\nuy = 0.0\nuz = 0.0", "uy = 0.0");
    let hoop = "[[boundary]]\nset = \"bar.theta0\"\nx_range = [5.0, 5.0]\ny_range = [0.0, 0.0]\nuz = 0.0\n";
    model(&format!("{axial}{hoop}"));
    let e = refusal(&axial);
    assert!(
        e.contains("a rotation about the axis along (0, -1, 0) through (0.0000, 5.0000, 0.0000)")
            && e.contains("cyclic ties"),
        "{e}"
    );
}
