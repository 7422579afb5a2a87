//! The kinematic slip memory across a restart (issue 28): a stopped
//! `slideway-damping` run resumes to the uninterrupted run's joint, cycle and
//! damping files, and a restart file whose memory is no stretch function,
//! or that gives a memory to an interface without one, is refused.

use crate::common;
use std::path::{Path, PathBuf};

/// The layout of one interface point in the `contact` section:
/// u_p, κ, p_T, u_T, μ_F, then η₁ … η₁₀ and e₁ … e₁₀.
const PACKED: usize = 25;

fn case(name: &str) -> PathBuf {
    common::root().join("cases").join(name)
}

use common::run_case as run;

use common::read_out as read;

#[test]
fn a_stopped_damping_run_resumes_to_the_same_loops() {
    let dir = common::scratch("damping-restart");
    let slideway = case("slideway-damping");
    let whole = dir.join("whole");
    assert_eq!(run(&slideway, &whole, &[]).0, 0);
    // stopped inside the first cycle at 50 %, where every point keeps a stretch function
    let part = dir.join("part");
    let (code, err) = run(&slideway, &part, &["--stop-after", "45"]);
    assert_eq!(code, 3, "{err}");
    let bin = std::fs::read(part.join("restart.bin")).unwrap();
    let contact = common::Forge::parse(&bin).f64s("contact");
    assert!(
        contact.chunks(PACKED).any(|p| p[5] > 0.0 && p[5] < 1.0),
        "a point with a breakpoint inside (0, 1)"
    );
    let resumed = dir.join("resumed");
    let r = part.display().to_string();
    let (code, err) = run(&slideway, &resumed, &["--restart", &r]);
    assert_eq!(code, 0, "{err}");
    for file in ["joints.csv", "cycles.csv", "damping.csv", "backbone.csv"] {
        assert_eq!(read(&whole, file), read(&resumed, file), "{file}");
    }
}

/// Resumes `case` from the stopped run in `good` with its `contact` point
/// `point` edited; the refusal names the section and the point.
fn refused(
    case: &Path,
    good: &Path,
    name: &str,
    point: usize,
    edit: &dyn Fn(&mut [f64]),
    needle: &str,
) {
    let bin = std::fs::read(good.join("restart.bin")).unwrap();
    let mut forge = common::Forge::parse(&bin);
    let mut contact = forge.f64s("contact");
    edit(&mut contact[point * PACKED..(point + 1) * PACKED]);
    forge.set_f64s("contact", &contact);
    let forged = good.parent().unwrap().join(name);
    let _ = std::fs::remove_dir_all(&forged);
    std::fs::create_dir_all(&forged).unwrap();
    std::fs::write(forged.join("restart.bin"), forge.bytes()).unwrap();
    let out = good.parent().unwrap().join(format!("{name}-out"));
    let r = forged.display().to_string();
    let (code, err) = run(case, &out, &["--restart", &r]);
    assert_eq!(code, 2, "{name}: {err}");
    assert_eq!(err.lines().count(), 1, "{name}: {err}");
    assert!(
        err.contains(&format!("section contact: interface point {}", point + 1)),
        "{name}: {err}"
    );
    assert!(err.contains(needle), "{name}: {err}");
    assert!(!out.exists(), "{name}: no output");
}

#[test]
fn a_forged_slip_memory_is_refused() {
    let dir = common::scratch("damping-forged");
    let good = dir.join("good");
    let slideway = case("slideway-damping");
    let (code, err) = run(&slideway, &good, &["--stop-after", "45"]);
    assert_eq!(code, 3, "{err}");
    let stretch = "no stretch function";
    refused(
        &slideway,
        &good,
        "eta-falling",
        3,
        &|p| {
            p[5] = 0.5;
            p[6] = 0.25;
            p[7] = 1.0;
        },
        stretch,
    );
    refused(
        &slideway,
        &good,
        "eta-beyond-one",
        3,
        &|p| p[5] = 1.5,
        stretch,
    );
    refused(
        &slideway,
        &good,
        "no-end",
        0,
        &|p| {
            for k in 0..10 {
                p[5 + k] = 0.05 * (k + 1) as f64;
            }
        },
        stretch,
    );
    refused(
        &slideway,
        &good,
        "kappa-negative",
        2,
        &|p| p[1] = -1e-3,
        "κ = -1e-3 (≥ 0 expected)",
    );
    // a shear or a slip the displacements and the law do not give
    refused(
        &slideway,
        &good,
        "shear-forged",
        5,
        &|p| p[2] = 1e6,
        "shear p_T = 1e6 MPa",
    );
    refused(
        &slideway,
        &good,
        "u-t-forged",
        6,
        &|p| p[3] += 0.5,
        "but the displacements (section u) give",
    );
    // an isotropic interface (punch-friction-a) given a memory
    let punch = case("punch-friction-a");
    let iso = dir.join("iso");
    let (code, err) = run(&punch, &iso, &["--stop-after", "2"]);
    assert_eq!(code, 3, "{err}");
    refused(
        &punch,
        &iso,
        "memory-in-isotropic",
        1,
        &|p| {
            p[5] = 1.0;
            p[15] = 1e-4;
        },
        "a kinematic slip memory in an interface without one",
    );
}

/// A restart file in the layout of the builds before the kinematic memory
/// (5 values per interface point in `contact`) is refused: the section's
/// size is not the model's, and no output is written.
#[test]
fn a_contact_section_of_the_earlier_layout_is_refused() {
    let dir = common::scratch("damping-earlier-build");
    let punch = case("punch-friction-a");
    let part = dir.join("part");
    let (code, err) = run(&punch, &part, &["--stop-after", "2"]);
    assert_eq!(code, 3, "{err}");
    let bin = std::fs::read(part.join("restart.bin")).unwrap();
    let mut forge = common::Forge::parse(&bin);
    let contact = forge.f64s("contact");
    let old: Vec<f64> = contact
        .chunks(PACKED)
        .flat_map(|p| p[..5].to_vec())
        .collect();
    forge.set_f64s("contact", &old);
    std::fs::write(part.join("restart.bin"), forge.bytes()).unwrap();
    let resumed = dir.join("resumed");
    let r = part.display().to_string();
    let (code, err) = run(&punch, &resumed, &["--restart", &r]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains(&format!(
            "restart.bin: section contact has {} values, the model needs {}",
            old.len(),
            contact.len()
        )),
        "{err}"
    );
    assert!(!resumed.exists());
}

/// One increment a leg: the trapezoid sums of a cycle see the shear at its
/// turning points only (D = 0 whatever the loop), and the run says so on
/// stderr and in summary.json; the shipped case's cycles (ten increments a
/// leg) draw no warning.
#[test]
fn cycles_of_too_few_increments_are_warned_about() {
    let dir = common::scratch("damping-coarse");
    let text = std::fs::read_to_string(case("slideway-damping").join("case.toml"))
        .unwrap()
        .replace("max_increment = 0.1", "max_increment = 1.0");
    let path = common::case_dir("damping-coarse", &text);
    let out = dir.join("out");
    let (code, err) = run(path.parent().unwrap(), &out, &[]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("warning: ")).collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].contains("interface \"way\": 11 closed cycle(s) of fewer than 4 increments"),
        "{err}"
    );
    // the advice names the key that sets the step under this step control
    assert!(lines[0].ends_with("set [solver] max_increment to a quarter of a leg or less"));
    let summary: serde_json::Value = serde_json::from_str(&read(&out, "summary.json")).unwrap();
    assert_eq!(summary["warnings"].as_array().unwrap().len(), 1);
    // fixed steps, one a unit of pseudo-time: max_increment would be refused;
    // given on the command line, the advice names the option (it named the
    // case file's key, which the option overrides, until issue 42)
    let (code, err) = run(
        &case("slideway-damping"),
        &dir.join("fixed"),
        &["--increments", "1"],
    );
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("; raise --increments 1 to 4 or more per unit of pseudo-time"),
        "{err}"
    );
    let fixed = text.replace(
        "step_control = \"auto\"\nmax_increment = 1.0",
        "increments = 1",
    );
    let path = common::case_dir("damping-coarse-fixed", &fixed);
    let (code, err) = run(path.parent().unwrap(), &dir.join("fixed-file"), &[]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("; set [solver] increments to 4 or more per unit of pseudo-time"),
        "{err}"
    );
    let (code, err) = run(&case("slideway-damping"), &dir.join("shipped"), &[]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("warning"), "{err}");
}
