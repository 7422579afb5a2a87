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
        assert!(!out.exists(), "{what}: output left behind");
    }
}
