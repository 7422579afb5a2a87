//! Serial faer, PETSc on 1 rank and PETSc on 2 ranks on twisting models
//! (issue 26): the twist's own fields, the joint rows with torque and twist,
//! and the closed torque-twist cycle.

use crate::agreement::compare;
use crate::common;
use crate::support::*;

/// Twist (issue 26): three dofs per node (PETSc block size 3, the
/// near-null space gains the rotation about the axis), the six-component
/// return, a circumferential shear on the foundation's outer surface with
/// the punch pressing it; the twist's own fields (u_θ, σ_rθ, σ_zθ) and
/// the torque reactions agree as well.
#[test]
fn serial_petsc1_and_petsc2_agree_on_a_twisting_model() {
    let case = "tests/data/axisymmetric-punch-twist";
    compare(case, "1");
    // compare's folder (not common::scratch, which empties it)
    let root = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("parallel-tests-data-axisymmetric-punch-twist-1-2");
    for field in ["displacement", "twist_shear"] {
        let a = last_vtu_array(&root.join("serial"), field);
        assert!(a.iter().any(|&v| v != 0.0), "{field} is all zero");
        for run in ["petsc1", "petsc2"] {
            let b = last_vtu_array(&root.join(run), field);
            assert_eq!(a.len(), b.len(), "{run}: {field} length");
            let scale = a.iter().fold(1e-30f64, |m, v| m.max(v.abs()));
            for (i, (x, y)) in a.iter().zip(&b).enumerate() {
                assert!(close(*x, *y, scale), "{run}: {field}[{i}] {x} vs {y}");
            }
        }
    }
}

/// Interfaces of a twisting model (issue 26): the shipped shrink fit turned
/// to full slip, every interface point on the vector friction law (its
/// 56-double states exchanged between the ranks, its vector coupling in the
/// point blocks); the joint rows, torque and twist included, as the serial
/// run's.
#[test]
fn serial_petsc1_and_petsc2_agree_on_a_twisted_shrink_fit() {
    twisted_joints_agree("shrink-fit-torque", 1e5);
}

/// A disk held about the axis only by the friction of its face
/// (cases/face-coupling-torque), clamped and twisted at once across a 2 µm
/// gap: its first step is solved with the stabilization's springs, around the
/// axis too, each rank assembling those of its own points, then released; the
/// joint rows as the serial run's. 9 N·m keeps the face's rim in micro-slip
/// from the first step (T R/J = 1.22 × 0.625 μ p_N at every load factor):
/// sticking throughout, the fields would be exact (every stress uniform or
/// linear in r) and the error estimate a field of round-off, 1e-29.
#[test]
fn serial_petsc1_and_petsc2_agree_on_a_disk_held_about_the_axis_only_by_friction() {
    let text = std::fs::read_to_string(common::root().join("cases/face-coupling-torque/case.toml"))
        .unwrap()
        .replace(
            "weights = \"consistent\"",
            "weights = \"consistent\"\ngap = 0.002",
        )
        .replace(
            "torque = 12000.0\nhistory = \"turn\"",
            "torque = 9000.0\nhistory = \"clamp\"",
        )
        .replace("turn  = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]", "");
    assert!(text.contains("gap = 0.002") && !text.contains("\"turn\""));
    let case = common::case_dir("parallel-face-coupling-case", &text);
    twisted_joints_agree(case.to_str().unwrap(), 1e3);
}

/// The shipped shrink fit pushed and turned back and forth (issue 26, the
/// kinematic memory's vector Jenkins elements exchanged between the ranks),
/// cut to its first closed cycle and steps of 0.2 to keep the test short
/// (the whole case takes about 19 s per PETSc run): the joint rows and the
/// closed cycle (torque-twist loop, torsional loss factor) as the serial run's.
#[test]
fn serial_petsc1_and_petsc2_agree_on_a_pushed_and_cycled_shrink_fit() {
    let text = std::fs::read_to_string(common::root().join("cases/shrink-fit-combined/case.toml"))
        .unwrap();
    let turn = "turn  = [[2.0, 0.0], [3.0, 1.0], [5.0, -1.0], [7.0, 1.0], [9.0, -1.0], [11.0, 1.0], [13.0, -1.0], [15.0, 1.0]]";
    assert!(text.contains(turn) && text.contains("max_increment = 0.1"));
    let text = text
        .replacen(
            turn,
            "turn = [[2.0, 0.0], [3.0, 1.0], [5.0, -1.0], [7.0, 1.0]]",
            1,
        )
        .replacen("max_increment = 0.1", "max_increment = 0.2", 1);
    let case = common::case_dir("parallel-combined-case", &text);
    let case = case.to_str().unwrap().to_string();
    twisted_joints_agree(&case, 1e5);
    let root = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("parallel-{}-1-2", case.replace('/', "-")));
    // the torque-twist loop's numbers (the force-slip loop's amplitudes are
    // round-off here: the axial force is held)
    let columns = [
        "dissipation_nmm",
        "work_nmm",
        "torque_min_nmm",
        "torque_max_nmm",
        "twist_min_rad",
        "twist_max_rad",
        "torque_amplitude_nmm",
        "twist_amplitude_rad",
        "torsional_stored_energy_nmm",
        "torsional_loss_factor",
    ];
    let rows = |run: &str| -> Vec<Vec<f64>> {
        let text = std::fs::read_to_string(root.join(run).join("cycles.csv")).unwrap();
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let at: Vec<usize> = columns
            .iter()
            .map(|c| header.iter().position(|h| h == c).unwrap())
            .collect();
        lines
            .map(|l| {
                let v: Vec<&str> = l.split(',').collect();
                at.iter().map(|&k| v[k].parse().unwrap()).collect()
            })
            .collect()
    };
    let s = rows("serial");
    assert_eq!(s.len(), 1, "{s:?}");
    for run in ["petsc1", "petsc2"] {
        let p = rows(run);
        assert_eq!(p.len(), s.len(), "{run}");
        for (a, b) in s.iter().zip(&p) {
            for (c, (x, y)) in a.iter().zip(b).enumerate() {
                assert!(
                    close(*x, *y, x.abs()),
                    "{run}: {}: {a:?} vs {b:?}",
                    columns[c]
                );
            }
        }
    }
}

/// Serial, PETSc on 1 and on 2 ranks give `case`'s joint rows (torque and
/// twist included, the torque reaching `min_torque` N·mm) to round-off.
fn twisted_joints_agree(case: &str, min_torque: f64) {
    compare(case, "1");
    let root = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("parallel-{}-1-2", case.replace('/', "-")));
    let rows = |run: &str| -> (String, Vec<Vec<f64>>) {
        let text = std::fs::read_to_string(root.join(run).join("joints.csv")).unwrap();
        let mut lines = text.lines();
        let header = lines.next().unwrap().to_string();
        let rows = lines
            .map(|l| l.split(',').skip(3).map(|v| v.parse().unwrap()).collect())
            .collect();
        (header, rows)
    };
    let (hs, s) = rows("serial");
    assert!(
        hs.ends_with("torque_nmm,mean_hoop_slip_mm,mean_twist_rad"),
        "{hs}"
    );
    // each column to 1e-6 of the largest value of its kind over the run:
    // forces (a tangential force of 1e-14 N beside 196 N of normal force is
    // round-off of zero), lengths, status measures, energies, torque, twist
    let kinds: [&[usize]; 6] = [
        &[0, 1],
        &[2, 3, 12],
        &[4, 5, 6, 7, 8],
        &[9, 10],
        &[11],
        &[13],
    ];
    assert_eq!(s[0].len(), 14, "{hs}");
    let mut scale = vec![1e-30f64; 14];
    for kind in kinds {
        let m = (kind.iter())
            .flat_map(|&c| s.iter().map(move |r| r[c].abs()))
            .fold(1e-30f64, f64::max);
        for &c in kind {
            scale[c] = m;
        }
    }
    assert!(scale[11] > min_torque, "no torque: {scale:?}");
    for run in ["petsc1", "petsc2"] {
        let (hp, p) = rows(run);
        assert_eq!(hp, hs, "{run}");
        assert_eq!(p.len(), s.len(), "{run}");
        for (a, b) in s.iter().zip(&p) {
            for (c, (x, y)) in a.iter().zip(b).enumerate() {
                assert!(close(*x, *y, scale[c]), "{run}: column {c}: {a:?} vs {b:?}");
            }
        }
    }
}

/// Twist with pretension (issue 46), `cases/bolted-hub-torque`: the section's
/// reference node (three dofs, two held) on rank 0, its copies tied to their
/// nodes in u_θ too on whichever rank owns them; a hub turned past gross
/// slip of both its faces. The joint rows (the torque of each face, the end
/// plate's going down the bolt across the cut), the bolt's force and
/// shortening of every increment and the supports' torques as the serial
/// run's, to round-off.
#[test]
fn serial_petsc1_and_petsc2_agree_on_a_bolted_hub_under_torque() {
    twisted_joints_agree("bolted-hub-torque", 2e5);
    let root = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("parallel-bolted-hub-torque-1-2");
    let rows = |run: &str, file: &str| -> Vec<Vec<f64>> {
        std::fs::read_to_string(root.join(run).join(file))
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect()
    };
    for file in ["pretension.csv", "reactions.csv"] {
        let s = rows("serial", file);
        assert!(s.len() > 20, "{file}: {} rows", s.len());
        // each column to 1e-6 of its largest value over the run, at least
        // 1e-6 of the file's (the shoulder's axial reaction under a clamp
        // that is in equilibrium by itself is a column of round-off, 1e-11 N)
        let top = (s.iter().flatten()).fold(1e-30f64, |m, v| m.max(v.abs()));
        let scale: Vec<f64> = (0..s[0].len())
            .map(|c| s.iter().fold(1e-6 * top, |m, r| m.max(r[c].abs())))
            .collect();
        for run in ["petsc1", "petsc2"] {
            let p = rows(run, file);
            assert_eq!(p.len(), s.len(), "{run}: {file}");
            for (a, b) in s.iter().zip(&p) {
                for (c, (x, y)) in a.iter().zip(b).enumerate() {
                    assert!(
                        close(*x, *y, scale[c]),
                        "{run}: {file}: column {c}: {a:?} vs {b:?}"
                    );
                }
            }
        }
    }
}

/// The torque limit (issue 46), `cases/fit-speed-limit`: a hub held about
/// the axis by its fit's friction alone, spun up under 350 N·m until it lets
/// go. The search for the limit is collective (every rank takes each
/// bisection step and its verdict alike): on two ranks the run ends as the
/// serial one, exit code 4 and one stop line (rank 0's), the same increments
/// and the event within its tolerance, the torque held there to 1e-6.
#[test]
fn serial_and_petsc2_end_a_spinning_fit_at_the_same_torque_limit() {
    let case = common::root().join("cases/fit-speed-limit");
    let root = common::scratch("parallel-torque-limit");
    let (s_dir, p_dir) = (root.join("serial"), root.join("petsc2"));
    let args = |dir: &std::path::Path, backend: &'static str| {
        vec![
            "run".to_string(),
            case.display().to_string(),
            "--quiet".into(),
            "--backend".into(),
            backend.into(),
            "--out".into(),
            dir.display().to_string(),
        ]
    };
    let s_args = args(&s_dir, "serial");
    let (code, err) = serial(&s_args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(code, 4, "serial: {err}");
    let p_args = args(&p_dir, "petsc");
    let (code, err) = mpirun(2, &p_args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(code, 4, "two ranks: {err}");
    let stops = err
        .lines()
        .filter(|l| l.starts_with("ended at the torque limit"))
        .count();
    assert_eq!(stops, 1, "{err}");
    let (s, p) = (json(&s_dir), json(&p_dir));
    assert_eq!(p["ranks"], 2);
    assert_eq!(p["stopped_by"], "torque_limit");
    assert_eq!(p["increments"], s["increments"]);
    let event = |v: &serde_json::Value| {
        (v["events"].as_array().unwrap().iter())
            .find(|e| e["event"] == "torque_limit")
            .cloned()
            .expect("a torque_limit event")
    };
    let (es, ep) = (event(&s), event(&p));
    // each bisection step's verdict is the same on one rank or two but for
    // a midpoint within round-off of the limit: the brackets overlap
    let (ls, lp) = (
        es["load_factor"].as_f64().unwrap(),
        ep["load_factor"].as_f64().unwrap(),
    );
    let tol = es["tolerance"].as_f64().unwrap();
    assert!((ls - lp).abs() <= 2.0 * tol, "{ep} vs {es}");
    let (ts, tp) = (
        es["torque_nm"].as_f64().unwrap(),
        ep["torque_nm"].as_f64().unwrap(),
    );
    assert!((ts - tp).abs() <= 1e-6 * ts.abs(), "{ts} vs {tp}");
}
