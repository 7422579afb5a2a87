//! The serial backend's factorizations: Cholesky where the model says the
//! tangent is symmetric, LU otherwise, and both on the same iterates.

use crate::common;
use asperity::input::case::Method;
use asperity::linalg::backend::serial::{Factorization, SerialBackend};
use asperity::model::Model;
use asperity::physics::element::solid::Response;
use asperity::solve::{Engine, State};

const PUNCH: &str = include_str!("../../cases/punch-plane-stress/case.toml");
const FRICTION_RM: &str = include_str!("../../cases/punch-friction-b/case.toml");

/// Largest |K_ij − K_ji| over max |K| of the assembled tangent at a plastic
/// state near the full load.
fn asymmetry(model: &Model) -> f64 {
    let mut engine = asperity::app::driver::serial_engine(
        model,
        Method::FullNewton,
        asperity::threads::available(),
    )
    .unwrap();
    let mut committed = State::initial(model);
    let mut state = committed.clone();
    for k in 1..=9 {
        committed = state;
        state = engine
            .step(&committed, 0.1 * k as f64, Response::Plastic)
            .unwrap()
            .0;
    }
    assert!(state.gauss.iter().any(|g| g.yielding), "no plastic point");
    engine.linearize(&committed, &state.u, 0.9).unwrap();
    let vals = engine.backend.matrix_values().unwrap();
    let p = model.pattern();
    let at = |i: usize, j: usize| -> f64 {
        let rows = &p.row_idx[p.col_ptr[j]..p.col_ptr[j + 1]];
        rows.binary_search(&(i as u32))
            .map(|k| vals[p.col_ptr[j] + k])
            .unwrap_or(0.0)
    };
    let kmax = vals.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut worst = 0.0f64;
    for j in 0..p.n {
        for &i in &p.row_idx[p.col_ptr[j]..p.col_ptr[j + 1]] {
            worst = worst.max((at(i as usize, j) - at(j, i as usize)).abs());
        }
    }
    worst / kmax
}

#[test]
fn the_model_states_the_symmetry_the_assembled_tangent_has() {
    let plain = common::model(PUNCH);
    assert!(plain.symmetric_tangent());
    assert!(asymmetry(&plain) < 1e-13, "{}", asymmetry(&plain));
    // return mapping: ∂p_T/∂u_N couples the tangent unsymmetrically
    let rm = common::model(FRICTION_RM);
    assert!(!rm.symmetric_tangent());
    assert!(asymmetry(&rm) > 1e-6, "{}", asymmetry(&rm));
    // stiffness modification (eq. 2.25) has no such coupling
    let sm = common::model(&FRICTION_RM.replace(
        "scheme = \"return-mapping\"",
        "scheme = \"stiffness-modification\"",
    ));
    assert!(sm.symmetric_tangent());
    assert!(asymmetry(&sm) < 1e-13, "{}", asymmetry(&sm));
}

/// Every increment of a run on a given factorization: (load factor,
/// iterations, displacements).
fn run(model: &Model, kind: Factorization) -> (Vec<(f64, usize)>, Vec<f64>, String) {
    let backend = Box::new(SerialBackend::with_factorization(model, kind).unwrap());
    let engine = Engine::with_backend(model, Method::FullNewton, backend);
    struct Keep(Vec<(f64, usize)>);
    impl asperity::solve::Observer for Keep {
        fn increment(
            &mut self,
            _: &Model,
            _: &State,
            inc: &asperity::solve::Increment,
        ) -> asperity::Result<()> {
            self.0.push((inc.load_factor, inc.iterations));
            Ok(())
        }
    }
    let mut keep = Keep(Vec::new());
    let r = asperity::solve::run_with(engine, &mut keep).unwrap();
    (keep.0, r.final_state.u, r.linear_solver)
}

/// The LU path has no interface loop (`[solver] interface_loop`, on by
/// default): the comparisons of the linear solvers' iterates below switch
/// it off on both.
fn plain(text: &str) -> Model {
    common::model(&common::with_interface_loop(text, false))
}

#[test]
fn cholesky_and_lu_take_the_same_iterates_on_a_symmetric_case() {
    let model = plain(PUNCH);
    let (inc_c, u_c, name_c) = run(&model, Factorization::Cholesky);
    let (inc_l, u_l, name_l) = run(&model, Factorization::Lu);
    assert_eq!(inc_c, inc_l, "increments and their iteration counts");
    let umax = u_l.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let worst = u_c
        .iter()
        .zip(&u_l)
        .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
    assert!(worst <= 1e-12 * umax, "{worst:e} of {umax:e}");
    assert!(name_c.contains("Cholesky"), "{name_c}");
    assert_eq!(name_l, "faer sparse LU");
}

/// The return-mapping tangent solved as Cholesky of its symmetric part plus
/// the interface points' rank-one terms (Woodbury with GMRES) takes the
/// iterates of the LU of the whole tangent: the same increments, the same
/// iteration counts, the same answer to round-off.
#[test]
fn the_split_tangent_takes_the_lu_iterates() {
    for case in [
        FRICTION_RM,
        include_str!("../../cases/punch-friction-a/case.toml"),
        include_str!("../../cases/punch-friction-c/case.toml"),
    ] {
        let model = plain(case);
        assert!(!model.symmetric_tangent());
        let (inc_s, u_s, name_s) = run(&model, Factorization::SymmetricPart);
        let (inc_l, u_l, _) = run(&model, Factorization::Lu);
        assert_eq!(
            inc_s, inc_l,
            "{}: increments and their iteration counts",
            model.name
        );
        let umax = u_l.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let worst = u_s
            .iter()
            .zip(&u_l)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        assert!(
            worst <= 1e-10 * umax,
            "{}: {worst:e} of {umax:e}",
            model.name
        );
        assert!(name_s.contains("Woodbury-GMRES"), "{name_s}");
    }
}

#[test]
fn summary_json_names_the_factorization() {
    let root = common::root();
    let bin = env!("CARGO_BIN_EXE_asperity");
    for (case, expect) in [
        ("punch-plane-stress", "Cholesky"),
        ("punch-friction-b", "Woodbury-GMRES"),
    ] {
        let out = common::scratch(&format!("factorization-{case}"));
        let st = std::process::Command::new(bin)
            .args(["run", "--quiet", "--increments", "2", "--out"])
            .arg(&out)
            .arg(root.join("cases").join(case))
            .status()
            .unwrap();
        assert!(st.success());
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let name = s["linear_solver"].as_str().unwrap();
        assert!(name.contains(expect), "{case}: {name}");
        if expect != "sparse LU" {
            assert_eq!(s["backend_stats"]["lu_fallbacks"], 0.0, "{case}");
        }
    }
}

/// A factorization that does not fit the memory budget is refused before the
/// first increment, with the estimate in one clear line (exit code 2, no
/// output folder); `ASPERITY_MEMORY_LIMIT_MB` sets the budget (default: the
/// machine's available memory).
#[test]
fn a_factor_that_does_not_fit_is_refused_up_front() {
    let root = common::root();
    let bin = env!("CARGO_BIN_EXE_asperity");
    for (case, limit, expect) in [
        (
            "punch-plane-stress",
            "0.3",
            "memory: the serial Cholesky factor and its workspace need 1.",
        ),
        (
            "punch-friction-b",
            "0.3",
            "memory: the serial Cholesky factor and its workspace need 1.",
        ),
        (
            "punch-plane-stress",
            "abc",
            "ASPERITY_MEMORY_LIMIT_MB: expected a positive number",
        ),
        (
            "punch-plane-stress",
            "-5",
            "ASPERITY_MEMORY_LIMIT_MB: expected a positive number",
        ),
    ] {
        let out = common::scratch(&format!("memory-{case}-{limit}")).join("out");
        let o = std::process::Command::new(bin)
            .args(["run", "--quiet", "--out"])
            .arg(&out)
            .arg(root.join("cases").join(case))
            .env("ASPERITY_MEMORY_LIMIT_MB", limit)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{case} {limit}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(expect), "{case} {limit}: {err}");
        assert!(
            !out.exists(),
            "{case} {limit}: an output folder was written"
        );
    }
    // a budget that fits runs
    let out = common::scratch("memory-fits").join("out");
    let o = std::process::Command::new(bin)
        .args(["run", "--quiet", "--increments", "2", "--out"])
        .arg(&out)
        .arg(root.join("cases/punch-plane-stress"))
        .env("ASPERITY_MEMORY_LIMIT_MB", "50")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
