//! Serial faer, PETSc on 1 rank and PETSc on 2 ranks with the interface
//! loop: the same loops and the same answers.

use crate::common;
use crate::support::*;

/// The interface loop on the force-controlled Hertzian sphere, where it
/// takes 13 Newton iterations instead of 48: PETSc (which runs it only where
/// asked for by name, here `--interface-loop on`) forms the condensed
/// tangent from its factor, the serial backend (which runs it by default)
/// reads it off its Cholesky factor; the same loops, the same answers.
/// Without the option PETSc runs plain Newton: no loop, the same answer.
#[test]
fn serial_petsc1_and_petsc2_agree_with_the_interface_loop_on_the_hertz_sphere() {
    let root = common::scratch("parallel-loop-sphere");
    let case = common::root().join("tests/data/hertz-sphere");
    run_serial(&case, &root.join("serial"), &[]);
    let s = json(&root.join("serial"));
    assert!(s["interface_loops"].as_u64().unwrap() > 0, "the loop ran");
    assert!(
        s["newton_iterations"].as_u64().unwrap() <= 4 * s["increments"].as_u64().unwrap(),
        "{s}"
    );
    let s_if = interfaces(&root.join("serial"));
    let u = |v: &serde_json::Value| v["final"]["center_displacement_mm"].as_f64().unwrap();
    // MUMPS on 1 and 2 ranks (the condensation from its selected inverse
    // entries), and PETSc's own LU on 1 (by MatMatSolve)
    #[rustfmt::skip]
    let runs: [(&str, usize, &[&str]); 3] = [
        ("petsc1", 1, &["--interface-loop", "on"]),
        ("petsc2", 2, &["--interface-loop", "on"]),
        ("petsc-lu", 1, &["--interface-loop", "on", "--",
                          "-pc_type", "lu", "-pc_factor_mat_solver_type", "petsc"]),
    ];
    for (name, n, extra) in runs {
        let dir = root.join(name);
        run_on(n, &case, &dir, extra);
        let p = json(&dir);
        for k in [
            "increments",
            "newton_iterations",
            "interface_loops",
            "interface_iterations",
            "interface_fallbacks",
        ] {
            assert_eq!(p[k], s[k], "{name}: {k}");
        }
        assert!(
            close(u(&s), u(&p), u(&s).abs()),
            "{name}: {} vs {}",
            u(&s),
            u(&p)
        );
        let p_if = interfaces(&dir);
        assert_eq!(p_if.len(), s_if.len());
        for (a, b) in s_if.iter().zip(&p_if) {
            let p_scale = a.iter().fold(1e-30f64, |m, r| m.max(r.1.abs()));
            for (ra, rb) in a.iter().zip(b) {
                assert_eq!(ra.3, rb.3, "{name}: status at x = {}", ra.0);
                assert!(close(ra.1, rb.1, p_scale), "{name}: p_n at x = {}", ra.0);
            }
        }
        if name == "petsc-lu" {
            assert_eq!(p["linear_solver"], "preonly + lu (petsc)");
        }
    }
    // by default PETSc runs plain Newton (the loop's condensation costs
    // about a Newton iteration there): no loop, the same answer
    let dir = root.join("petsc-default");
    run_on(1, &case, &dir, &[]);
    let p = json(&dir);
    assert_eq!(p["interface_loops"], 0);
    assert_eq!(p["increments"], s["increments"]);
    assert!(
        p["newton_iterations"].as_u64().unwrap() > s["newton_iterations"].as_u64().unwrap(),
        "{p}"
    );
    assert!(
        close(u(&s), u(&p), u(&s).abs()),
        "default: {} vs {}",
        u(&s),
        u(&p)
    );
}
