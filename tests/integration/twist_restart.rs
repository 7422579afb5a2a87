//! Interfaces of a twisting model across a restart (issue 26): the vector
//! friction states (56 values a point) and the joints' torque rows resume a
//! stopped `shrink-fit-torque` run to the uninterrupted run's files, and a
//! twisting model's `contact` section in the scalar layout of the builds
//! before its interfaces carried the circumferential slip (25 values a
//! point) is refused.

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

/// Twist with pretension (issue 46): `cases/bolted-hub-torque` stopped in its
/// turn (after the lock, its seat sliding around the axis, its end plate
/// still sticking), resumed: the section's locked shortening and force, the
/// faces' torques and the supports' (the nut's is the torque through the
/// cut) as the uninterrupted run's, to the byte.
#[test]
fn a_stopped_bolted_hub_resumes_to_the_same_torques_and_bolt_force() {
    let case = common::root().join("cases/bolted-hub-torque");
    resume(
        "twist-pretension-restart",
        &case,
        "25",
        |f| {
            // force and shortening of one section per increment
            let p = f.f64s("pretension");
            assert_eq!(p.len(), 2 * 25);
            assert!(p[2 * 24] < 50_000.0 && p[2 * 24 + 1] == p[2 * 19 + 1]);
        },
        &[
            "pretension.csv",
            "joints.csv",
            "reactions.csv",
            "curve.csv",
            "interface/0040.csv",
        ],
    );
}

/// The scalar layout the earlier builds wrote for a twisting model without
/// a tangential law (u_p, κ, p_T, u_T, μ_F and 20 memory values a point) is
/// refused by its size: exit 2, one line naming restart.bin, no output.
#[test]
fn a_twisting_models_contact_section_of_the_earlier_layout_is_refused() {
    let case = common::root().join("tests/data/axisymmetric-punch-twist");
    let scalar = |f: &mut common::Forge| {
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
    };
    refused(
        "twist-restart-earlier",
        &case,
        "3",
        &[("section contact has ", &scalar)],
    );
}

/// A torque-driven face coupling (cases/face-coupling-torque) with a point
/// probe on the disk's top rim: its records carry u_θ as a third value per
/// probe, so a stopped run resumes to the same probes.csv; while the face
/// sticks that u_θ is the closed form R [T 2h/(G J) + T/(k_T^e J)]
/// (tests/verification/face_coupling.rs).
#[test]
fn a_torque_driven_face_coupling_resumes_with_its_probe_around_the_axis() {
    let case = common::root().join("cases/face-coupling-torque");
    resume(
        "twist-restart-probe",
        &case,
        "30",
        |_| {},
        &["probes.csv", "joints.csv", "reactions.csv", "curve.csv"],
    );
    let whole = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("twist-restart-probe")
        .join("whole");
    let csv = read(&whole, "probes.csv");
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("increment,time,probe,ux_mm,uy_mm,utheta_mm")
    );
    // t = 1.6: T = 7200 N·mm, below the micro-slip onset 7363 N·mm
    let row = lines.find(|l| l.starts_with("32,1.600000000,")).unwrap();
    let v: Vec<f64> = row.split(',').skip(3).map(|x| x.parse().unwrap()).collect();
    let (t, r, h, p): (f64, f64, f64, f64) = (7200.0, 10.0, 10.0, 50.0);
    let g = 206_000.0 / 2.6;
    let j = std::f64::consts::PI * r.powi(4) / 2.0;
    let kt = 1000.0 * p.sqrt() / 0.9;
    let want = r * (t * 2.0 * h / (g * j) + t / (kt * j));
    assert!(
        (v[2] - want).abs() <= 1e-8 * want,
        "u_θ at the rim {} vs {want}",
        v[2]
    );
}

/// `asperity check` of a twisting model says so, and names the bodies that
/// only the friction of an interface holds about the axis (the face
/// coupling's disk), not those with a rotation of their own (its base; both
/// bodies of shrink-fit-torque).
#[test]
fn check_names_the_bodies_only_friction_holds_about_the_axis() {
    let face = common::root().join("cases/face-coupling-torque");
    let (code, err, out) = common::run_asperity_out(&["check", face.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("plane Axisymmetric with twist"), "{out}");
    let held: Vec<&str> = out
        .lines()
        .filter(|l| l.contains("held only by the friction of interface \"face\""))
        .collect();
    assert_eq!(held.len(), 1, "{out}");
    let disk = out.find("  body disk:").unwrap();
    let base = out.find("  body base:").unwrap();
    let line = out.find(held[0]).unwrap();
    assert!(disk < line && line < base, "{out}");
    let fit = common::root().join("cases/shrink-fit-torque");
    let (code, err, out) = common::run_asperity_out(&["check", fit.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("with twist") && !out.contains("held only by"),
        "{out}"
    );
}

/// A forgery: the text its refusal must contain, and the edit.
type Forgery<'a> = (&'a str, &'a dyn Fn(&mut common::Forge));

/// Stops `case` after `stop` increments, lets each forgery edit a copy of
/// the restart file, and asserts that resuming from it is refused: exit 2,
/// one line naming restart.bin and the forgery's text, no output folder.
fn refused(tag: &str, case: &Path, stop: &str, forgeries: &[Forgery]) {
    let dir = common::scratch(tag);
    let part = dir.join("part");
    let (code, err) = run(case, &part, &["--stop-after", stop]);
    assert_eq!(code, 3, "{err}");
    let bin = std::fs::read(part.join("restart.bin")).unwrap();
    for (needle, forge) in forgeries {
        let mut f = common::Forge::parse(&bin);
        forge(&mut f);
        std::fs::write(part.join("restart.bin"), f.bytes()).unwrap();
        let out = dir.join("resumed");
        let r = part.display().to_string();
        let (code, err) = run(case, &out, &["--restart", &r]);
        assert_eq!(code, 2, "{needle}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(
            err.contains("restart.bin") && err.contains(needle),
            "{needle}: {err}"
        );
        assert!(!out.exists(), "{needle}: output left behind");
    }
}

/// A torque spike in a twisted fit's restart file: an earlier row's torque
/// beyond what the fit's friction holds at that row's normal force, and the
/// last row's anything but the restored state's own, are refused (they
/// were written out into joints.csv as the run's torque).
#[test]
fn a_forged_torque_row_is_refused() {
    let case = common::root().join("cases/shrink-fit-torque");
    // increment 20: 1000 mm times the row's normal force, past any μ r F_N;
    // the last: the torque changed in its ninth digit
    let early = |f: &mut common::Forge| {
        let normal = f.f64s("joints")[11 * 19];
        assert!(normal > 0.0);
        let mut t = f.f64s("joints_twist");
        assert_eq!(t.len(), 3 * 30, "one interface, 30 increments");
        t[3 * 19] = 1e3 * normal;
        f.set_f64s("joints_twist", &t);
    };
    let last = |f: &mut common::Forge| {
        let mut t = f.f64s("joints_twist");
        assert!(t[3 * 29] != 0.0);
        t[3 * 29] *= 1.0 + 1e-9;
        f.set_f64s("joints_twist", &t);
    };
    refused(
        "twist-forged-torque",
        &case,
        "30",
        &[
            (
                "section joints_twist: increment 20: interface \"fit\": torque",
                &early,
            ),
            (
                "section joints_twist: increment 30 (the last): interface \"fit\": torque = ",
                &last,
            ),
        ],
    );
}

/// A probe spike in the face coupling's restart file: a probe value beyond
/// the displacement range in an earlier record, and the last record's
/// probe anything but the restored displacement, are refused (probes.csv
/// showed them).
#[test]
fn a_forged_probe_is_refused() {
    let case = common::root().join("cases/face-coupling-torque");
    let model = common::model(&std::fs::read_to_string(case.join("case.toml")).unwrap());
    let (width, probe) = (model.plan.width(), model.plan.layout.probes.start);
    let set = move |row: usize, k: usize, v: f64| {
        move |f: &mut common::Forge| {
            let mut r = f.f64s("records");
            assert_eq!(r.len(), width * 10);
            r[width * row + probe + k] = v;
            f.set_f64s("records", &r);
        }
    };
    let (early, last) = (set(4, 2, 1e5), set(9, 2, 0.125));
    refused(
        "twist-forged-probe",
        &case,
        "10",
        &[
            (
                "section records: increment 5: probe value 3 is 1e5 mm",
                &early,
            ),
            ("section records: increment 10 (the last): value", &last),
        ],
    );
}
