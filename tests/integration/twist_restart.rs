//! Interfaces of a twisting model across a restart (issue 26): the vector
//! friction states (56 values a point) and the joints' torque rows resume a
//! stopped `shrink-fit-torque` run to the uninterrupted run's files, and a
//! twisting model's restart file of the builds before its interfaces
//! carried the circumferential slip (25 values a point, no tangential law)
//! still resumes.

use crate::common;
use std::path::Path;

use common::run_case as run;

use common::read_out as read;

/// Stops `case` after `stop` increments, lets `forge` edit the restart
/// file, resumes, and compares `files` with the uninterrupted run.
fn resume(tag: &str, case: &Path, stop: &str, forge: impl Fn(&mut common::Forge), files: &[&str]) {
    let dir = common::scratch(tag);
    let whole = dir.join("whole");
    assert_eq!(run(case, &whole, &[]).0, 0);
    let part = dir.join("part");
    let (code, err) = run(case, &part, &["--stop-after", stop]);
    assert_eq!(code, 3, "{err}");
    let bin = std::fs::read(part.join("restart.bin")).unwrap();
    let mut f = common::Forge::parse(&bin);
    forge(&mut f);
    std::fs::write(part.join("restart.bin"), f.bytes()).unwrap();
    let resumed = dir.join("resumed");
    let r = part.display().to_string();
    let (code, err) = run(case, &resumed, &["--restart", &r]);
    assert_eq!(code, 0, "{err}");
    for file in files {
        assert_eq!(read(&whole, file), read(&resumed, file), "{file}");
    }
}

#[test]
fn a_stopped_twisted_fit_resumes_to_the_same_torque() {
    let case = common::root().join("cases/shrink-fit-torque");
    resume(
        "twist-restart",
        &case,
        "30",
        |f| {
            // the vector layout, a state in macro-slip around the axis
            let c = f.f64s("contact");
            assert_eq!(c.len() % 56, 0);
            assert!(c.chunks(56).any(|p| p[3] != 0.0 && p[4] != 0.0));
            assert!(!f.f64s("joints_twist").is_empty());
        },
        &[
            "joints.csv",
            "curve.csv",
            "reactions.csv",
            "interface/0040.csv",
        ],
    );
}

#[test]
fn a_twisting_models_restart_file_of_an_earlier_build_resumes() {
    let case = common::root().join("tests/data/axisymmetric-punch-twist");
    resume(
        "twist-restart-earlier",
        &case,
        "3",
        |f| {
            // the scalar layout the earlier builds wrote: u_p, κ, p_T, u_T,
            // μ_F and 20 memory values (no tangential law could act)
            let c = f.f64s("contact");
            let old: Vec<f64> = c
                .chunks(56)
                .flat_map(|p| {
                    let mut v = vec![0.0; 25];
                    v[2..5].copy_from_slice(&p[..3]);
                    v
                })
                .collect();
            f.set_f64s("contact", &old);
        },
        &["joints.csv", "curve.csv", "interface/0008.csv"],
    );
}
