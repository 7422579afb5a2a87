//! A pretension section through a stop and a restart (issue 27): a run
//! stopped in its preload, resumed with `--restart`, writes the same
//! pretension.csv as the run that was not stopped, the locked phase included
//! (the section's rows and its shortening travel in restart.bin).

use crate::common;
use common::run_asperity as asperity;

/// The bar of tests/common (held at both ends, cut at x = 30), preloaded by
/// 1 kN over t ∈ [0, 1], locked, then pulled at x = 60 over t ∈ [1, 2].
fn bar() -> String {
    common::pretension_bar(
        "force = 1000.0\nhistory = \"preload\"",
        r#"
[history]
preload = [[0, 0], [1, 1]]
service = [[1, 0], [2, 1]]
[[force]]
nodes = "bar.all"
fx = 100.0
x_range = [60.0, 60.0]
history = "service""#,
    )
}

#[test]
fn a_stopped_pretension_run_resumes_to_the_same_section_forces() {
    let case = common::case_dir("pretension-restart-case", &bar());
    let root = common::scratch("pretension-restart");
    let (c, o) = (case.display().to_string(), |n: &str| {
        root.join(n).display().to_string()
    });
    let (full, stopped, resumed) = (o("full"), o("stopped"), o("resumed"));
    let (code, e) = asperity(&["run", &c, "--out", &full, "--quiet"]);
    assert_eq!(code, 0, "{e}");
    // a stopped run exits with 3 (docs/running.md)
    let (code, e) = asperity(&["run", &c, "--out", &stopped, "--quiet", "--stop-after", "3"]);
    assert_eq!(code, 3, "{e}");
    let (code, e) = asperity(&[
        "run",
        &c,
        "--out",
        &resumed,
        "--quiet",
        "--restart",
        &stopped,
    ]);
    assert_eq!(code, 0, "{e}");
    let read =
        |d: &str| std::fs::read_to_string(std::path::Path::new(d).join("pretension.csv")).unwrap();
    let (a, b) = (read(&full), read(&resumed));
    assert!(a.lines().count() > 4, "{a}");
    assert_eq!(a, b, "pretension.csv differs after a restart");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("full/summary.json")).unwrap())
            .unwrap();
    let p = &s["pretension"][0];
    assert_eq!(p["name"], "bolt");
    assert_eq!(p["control"], "force");
    assert_eq!(p["locked_after"], 1.0);
    assert!((p["force_at_lock_n"].as_f64().unwrap() - 1000.0).abs() < 1e-7);
}

/// cases/bolt-pretension-3d (a revolved shank, 3D) stopped after 6 of its
/// 8 increments, past the lock at t = 1, and resumed: its pretension.csv
/// and reactions.csv byte for byte those of the run that was not stopped
/// (the section's shortening, locked, travels in restart.bin with the three
/// components of every node and copy).
#[test]
fn a_stopped_3d_pretension_run_resumes_byte_for_byte() {
    let case = common::root().join("cases/bolt-pretension-3d");
    let root = common::scratch("pretension-3d-restart");
    let (c, o) = (case.display().to_string(), |n: &str| {
        root.join(n).display().to_string()
    });
    let (full, stopped, resumed) = (o("full"), o("stopped"), o("resumed"));
    let (code, e) = asperity(&["run", &c, "--out", &full, "--quiet"]);
    assert_eq!(code, 0, "{e}");
    let (code, e) = asperity(&["run", &c, "--out", &stopped, "--quiet", "--stop-after", "6"]);
    assert_eq!(code, 3, "{e}");
    let (code, e) = asperity(&[
        "run",
        &c,
        "--out",
        &resumed,
        "--quiet",
        "--restart",
        &stopped,
    ]);
    assert_eq!(code, 0, "{e}");
    for file in ["pretension.csv", "reactions.csv"] {
        let read = |d: &str| std::fs::read(std::path::Path::new(d).join(file)).unwrap();
        let (a, b) = (read(&full), read(&resumed));
        assert!(a.len() > 200, "{file}");
        assert_eq!(a, b, "{file} differs after a restart");
    }
}

/// A restart file is input: a locked shortening that disagrees with the
/// file's own record and a section force out of any range are refused
/// (exit 2, one line naming restart.bin); a forged locked shortening would
/// otherwise never be corrected by Newton.
#[test]
fn a_forged_section_in_a_restart_file_is_refused() {
    let case = common::case_dir("pretension-forged-case", &bar());
    let root = common::scratch("pretension-forged");
    let c = case.display().to_string();
    let stopped = root.join("stopped");
    let s = stopped.display().to_string();
    // past the lock at t = 1 (0.05, 0.15, 0.35, 0.6, 0.85, 1, ...)
    let (code, e) = asperity(&["run", &c, "--out", &s, "--quiet", "--stop-after", "8"]);
    assert_eq!(code, 3, "{e}");
    let bin = std::fs::read(stopped.join("restart.bin")).unwrap();
    type Edit = Box<dyn Fn(&mut common::Forge)>;
    let forgeries: Vec<(&str, Edit, &str)> = vec![
        (
            "locked shortening",
            Box::new(|f: &mut common::Forge| {
                let mut u = f.f64s("u");
                let k = u.len() - 2;
                u[k] = 1e3;
                f.set_f64s("u", &u);
            }),
            "the shortening of pretension \"bolt\"",
        ),
        (
            "section force",
            Box::new(|f: &mut common::Forge| {
                let mut v = f.f64s("pretension");
                v[0] = 1e300;
                f.set_f64s("pretension", &v);
            }),
            "outside any engineering use",
        ),
        // the state and its last row moved together: the locked section
        // shortened after its lock, which Newton never does
        (
            "locked shortening and its row",
            Box::new(|f: &mut common::Forge| {
                let mut u = f.f64s("u");
                let k = u.len() - 2;
                u[k] += 1e-3;
                f.set_f64s("u", &u);
                let mut v = f.f64s("pretension");
                let last = v.len() - 1;
                v[last] = u[k];
                f.set_f64s("pretension", &v);
            }),
            "section pretension: increment 8: the shortening of pretension \"bolt\" is",
        ),
        // a row after the lock (increment 7, t = 1.15) alone
        (
            "locked row",
            Box::new(|f: &mut common::Forge| {
                let mut v = f.f64s("pretension");
                v[2 * 6 + 1] *= 1.5;
                f.set_f64s("pretension", &v);
            }),
            "section pretension: increment 7: the shortening of pretension \"bolt\" is",
        ),
    ];
    for (what, edit, needle) in forgeries {
        let mut f = common::Forge::parse(&bin);
        edit(&mut f);
        let dir = root.join(what.replace(' ', "-"));
        let _ = std::fs::remove_dir_all(&dir);
        for entry in std::fs::read_dir(&stopped).unwrap() {
            let p = entry.unwrap().path();
            if p.is_file() {
                std::fs::create_dir_all(&dir).unwrap();
                std::fs::copy(&p, dir.join(p.file_name().unwrap())).unwrap();
            }
        }
        std::fs::create_dir_all(dir.join("vtu")).unwrap();
        for entry in std::fs::read_dir(stopped.join("vtu")).unwrap() {
            let p = entry.unwrap().path();
            std::fs::copy(&p, dir.join("vtu").join(p.file_name().unwrap())).unwrap();
        }
        std::fs::write(dir.join("restart.bin"), f.bytes()).unwrap();
        let out = root.join(format!("{}-out", what.replace(' ', "-")));
        let (d, o) = (dir.display().to_string(), out.display().to_string());
        let (code, e) = asperity(&["run", &c, "--out", &o, "--quiet", "--restart", &d]);
        assert_eq!(code, 2, "{what}: {e}");
        assert_eq!(e.trim().lines().count(), 1, "{what}: {e}");
        assert!(
            e.contains("restart.bin") && e.contains(needle),
            "{what}: {e}"
        );
        if needle.contains("increment") {
            assert!(
                e.contains("but it is locked from t = 1 on at"),
                "{what}: {e}"
            );
        }
        assert!(!out.exists(), "{what}: output left behind");
    }
}

/// Before its lock a force-controlled section's force is the case's F h(t)
/// (its equation makes it so): a restart file's row of it is recomputed, so
/// a forged pre-lock force (3 kN at t = 0.35 for 350 N) changes nothing:
/// the resumed run writes the uninterrupted run's pretension.csv and
/// summary, the force at the lock exactly 1 kN. (It was written out as
/// forged, and summary.json's force_at_lock_n and force_max_n with it.)
#[test]
fn a_forged_pre_lock_force_is_recomputed_from_the_case() {
    let case = common::case_dir("pretension-prelock-case", &bar());
    let root = common::scratch("pretension-prelock");
    let c = case.display().to_string();
    let o = |n: &str| root.join(n).display().to_string();
    let (full, stopped, resumed) = (o("full"), o("stopped"), o("resumed"));
    let (code, e) = asperity(&["run", &c, "--out", &full, "--quiet"]);
    assert_eq!(code, 0, "{e}");
    let (code, e) = asperity(&["run", &c, "--out", &stopped, "--quiet", "--stop-after", "4"]);
    assert_eq!(code, 3, "{e}");
    let bin = root.join("stopped/restart.bin");
    let mut f = common::Forge::parse(&std::fs::read(&bin).unwrap());
    let mut v = f.f64s("pretension");
    assert_eq!(v.len(), 8);
    assert!(
        common::rel(v[4], 350.0) < 1e-15,
        "t = 0.35: F h(t) {}",
        v[4]
    );
    v[4] = 3000.0;
    f.set_f64s("pretension", &v);
    std::fs::write(&bin, f.bytes()).unwrap();
    let (code, e) = asperity(&[
        "run",
        &c,
        "--out",
        &resumed,
        "--quiet",
        "--restart",
        &stopped,
    ]);
    assert_eq!(code, 0, "{e}");
    let read = |d: &str, n: &str| std::fs::read_to_string(std::path::Path::new(d).join(n)).unwrap();
    assert_eq!(
        read(&full, "pretension.csv"),
        read(&resumed, "pretension.csv")
    );
    let s: serde_json::Value = serde_json::from_str(&read(&resumed, "summary.json")).unwrap();
    let p = &s["pretension"][0];
    assert_eq!(p["force_at_lock_n"], 1000.0);
    let whole: serde_json::Value = serde_json::from_str(&read(&full, "summary.json")).unwrap();
    assert_eq!(p["force_max_n"], whole["pretension"][0]["force_max_n"]);
}

/// A square plate of four blocks held on its four sides, cut by two
/// sections that cross at (10, 10), "a" along x = 10 and "b" along y = 10,
/// each loaded with 1 kN; the crossing node is also held in ux from the
/// blocks `holds` name (their `all` sets: before both cuts, LL, the original
/// node; beyond both, RU, the copy of its copy).
fn crossing(holds: &[&str]) -> String {
    let mut s = String::from("[model]\nplane = \"stress\"\nthickness = 2.0\n");
    for (name, x, y) in [
        ("LL", [0.0, 10.0], [0.0, 10.0]),
        ("RL", [10.0, 20.0], [0.0, 10.0]),
        ("LU", [0.0, 10.0], [10.0, 20.0]),
        ("RU", [10.0, 20.0], [10.0, 20.0]),
    ] {
        s += &format!(
            "[[mesh.block]]\nname = \"{name}\"\nbody = \"plate\"\nx = {x:?}\nnx = [2]\ny = {y:?}\nny = [2]\n"
        );
    }
    s += "[materials.plate]\nyoung = 200000.0\npoisson = 0.3\n";
    for (set, key) in [
        ("LL.left", "ux"),
        ("LU.left", "ux"),
        ("RL.right", "ux"),
        ("RU.right", "ux"),
        ("LL.bottom", "uy"),
        ("RL.bottom", "uy"),
        ("LU.top", "uy"),
        ("RU.top", "uy"),
    ] {
        s += &format!("[[boundary]]\nset = \"{set}\"\n{key} = 0.0\n");
    }
    for b in holds {
        s += &format!(
            "[[boundary]]\nset = \"{b}.all\"\nux = 0.0\nx_range = [10.0, 10.0]\ny_range = [10.0, 10.0]\n"
        );
    }
    for (name, line) in [("a", "x"), ("b", "y")] {
        s += &format!(
            "[[pretension]]\nname = \"{name}\"\nbody = \"plate\"\n{line} = 10.0\nforce = 1000.0\n"
        );
    }
    s
}

/// Two crossing sections whose crossing node is held beyond both cuts (the
/// copy of its copy) solve, to the shortenings of the mirror image, the
/// node held before both cuts (the plate turned by 180° about the crossing:
/// the same shortenings). The hold beyond both cuts was refused as "dof N
/// is constrained twice": the copy between followed both its node and, the
/// other way round, the held copy of it. Held on both sides, the node is
/// refused naming the sections and the node (tests/bad_inputs/580).
#[test]
fn crossing_sections_held_beyond_both_cuts_solve_as_their_mirror_image() {
    let root = common::scratch("pretension-crossing");
    let mut shortenings = Vec::new();
    for hold in ["LL", "RU"] {
        let case = common::case_dir(&format!("pretension-crossing-{hold}"), &crossing(&[hold]));
        let out = root.join(hold);
        common::run_ok(&case, &out);
        let csv = out.join("pretension.csv");
        let last = |c: &str| *common::csv_column(&csv, c).last().unwrap();
        assert!((last("a_force_n") - 1000.0).abs() < 1e-6);
        assert!((last("b_force_n") - 1000.0).abs() < 1e-6);
        shortenings.push([last("a_shortening_mm"), last("b_shortening_mm")]);
    }
    let [before, beyond] = [shortenings[0], shortenings[1]];
    assert!(before[0] > 0.0 && before[1] > 0.0, "{before:?}");
    // the holds break the square's symmetry about its diagonal: a ≠ b
    assert!(common::rel(before[0], before[1]) > 0.1, "{before:?}");
    for k in 0..2 {
        assert!(
            common::rel(before[k], beyond[k]) < 1e-9,
            "{before:?} vs {beyond:?}"
        );
    }
    let case = common::case_dir("pretension-crossing-both", &crossing(&["LL", "RU"]));
    let (code, e) = common::run_asperity(&["check", case.to_str().unwrap()]);
    assert_eq!(code, 2, "{e}");
    assert!(
        e.contains("node 20 at (10, 10), where the cuts of pretension \"a\" and \"b\" meet")
            && e.contains("held in ux on both sides of the cut of pretension \"a\""),
        "{e}"
    );
}
