//! A restart folder is input (issue 30): `restart.bin` can be rewritten by
//! anyone into a well-formed file (the checksum and the fingerprint are
//! computable), and the files beside it can be replaced by links. Forged
//! names, links, schedules, states and sizes are refused with one line
//! naming the restart file and exit code 2; nothing outside `--out` is
//! written or truncated, and no output folder is left behind.

use crate::common;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

fn asperity(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// `run punch-plane-stress --increments 10 --out OUT --quiet` plus `extra`.
fn run(out: &Path, extra: &[&str]) -> (i32, String) {
    let c = common::root()
        .join("cases/punch-plane-stress")
        .display()
        .to_string();
    let o = out.display().to_string();
    let mut args = vec!["run", &c, "--increments", "10", "--out", &o, "--quiet"];
    args.extend_from_slice(extra);
    asperity(&args)
}

/// A run stopped after 3 increments, in `dir`: the restart folder the
/// forgeries start from.
fn stopped(dir: &Path) -> PathBuf {
    stopped_with(dir, &[])
}

fn stopped_with(dir: &Path, extra: &[&str]) -> PathBuf {
    let mut args = vec!["--stop-after", "3"];
    args.extend_from_slice(extra);
    let (code, err) = run(dir, &args);
    assert_eq!(code, 3, "{err}");
    dir.to_path_buf()
}

/// What a folder holds, without following links: files by content, links by
/// target, folders as such.
#[derive(Debug, PartialEq)]
enum Entry {
    File(Vec<u8>),
    /// A file too large to hold (the sparse one): its length.
    Large(u64),
    Link(PathBuf),
    Dir,
}

fn tree(dir: &Path) -> BTreeMap<PathBuf, Entry> {
    fn walk(d: &Path, m: &mut BTreeMap<PathBuf, Entry>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            let t = std::fs::symlink_metadata(&p).unwrap().file_type();
            if t.is_symlink() {
                m.insert(p.clone(), Entry::Link(std::fs::read_link(&p).unwrap()));
            } else if t.is_dir() {
                m.insert(p.clone(), Entry::Dir);
                walk(&p, m);
            } else {
                let len = std::fs::symlink_metadata(&p).unwrap().len();
                let e = if len > 64 << 20 {
                    Entry::Large(len)
                } else {
                    Entry::File(std::fs::read(&p).unwrap())
                };
                m.insert(p.clone(), e);
            }
        }
    }
    let mut m = BTreeMap::new();
    walk(dir, &mut m);
    m
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let q = to.join(p.file_name().unwrap());
        if p.is_dir() {
            copy_dir(&p, &q);
        } else {
            std::fs::copy(&p, &q).unwrap();
        }
    }
}

/// Resumes from `restart` into `out` (with the options `extra` of the
/// stopped run) and checks the refusal: exit 2, one `error: <restart file>:
/// …` line containing `needle`, within 20 s, and nothing changed anywhere
/// under `root` (no output, no partial folder, no file outside).
fn refused(root: &Path, restart: &Path, out: &Path, extra: &[&str], needle: &str, what: &str) {
    let before = tree(root);
    let t = Instant::now();
    let r = restart.display().to_string();
    let mut args = vec!["--restart", &r];
    args.extend_from_slice(extra);
    let (code, err) = run(out, &args);
    let secs = t.elapsed().as_secs_f64();
    assert_eq!(code, 2, "{what}: {err}");
    let file = restart.join("restart.bin").display().to_string();
    assert!(
        err.starts_with(&format!("error: {file}: ")) && err.lines().count() == 1,
        "{what}: {err}"
    );
    assert!(err.contains(needle), "{what}: {err}");
    assert!(secs < 20.0, "{what}: refused after {secs:.1} s");
    assert!(
        tree(root) == before,
        "{what}: files changed under {}",
        root.display()
    );
}

/// The message for a VTU name not of the writer's form.
const NOT_OURS: &str = "is not a name this program writes";

#[test]
fn forged_names_and_links_in_a_restart_folder_write_nothing_outside_the_output() {
    let dir = common::scratch("restart-forged-names");
    let good = stopped(&dir.join("good"));
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, "precious\n").unwrap();
    let secret = dir.join("secret.txt");
    std::fs::write(&secret, "secret\n").unwrap();
    let bin = std::fs::read(good.join("restart.bin")).unwrap();
    let forge = common::Forge::parse(&bin);
    let names = forge.clone().text("pvd_file");
    assert_eq!(names, "vtu/0001.vtu\nvtu/0002.vtu\nvtu/0003.vtu");
    // the first VTU name replaced
    let renamed = |name: &str| {
        let mut f = forge.clone();
        f.set_bytes(
            "pvd_file",
            names.replacen("vtu/0001.vtu", name, 1).as_bytes(),
        );
        f.bytes()
    };
    let v = victim.display().to_string();
    type Change = Box<dyn Fn(&Path)>;
    let write = |bytes: Vec<u8>| -> Change {
        Box::new(move |r: &Path| std::fs::write(r.join("restart.bin"), &bytes).unwrap())
    };
    let link = |target: PathBuf, at: &'static str| -> Change {
        Box::new(move |r: &Path| {
            let p = r.join(at);
            if p.is_dir() {
                std::fs::remove_dir_all(&p).unwrap();
            } else {
                std::fs::remove_file(&p).unwrap();
            }
            std::os::unix::fs::symlink(&target, &p).unwrap();
        })
    };
    // a copy of the VTU folder outside the restart folder, and of restart.bin
    copy_dir(&good.join("vtu"), &dir.join("elsewhere-vtu"));
    std::fs::copy(good.join("restart.bin"), dir.join("elsewhere.bin")).unwrap();
    let variants: Vec<(&str, Change, &str)> = vec![
        ("dotdot", write(renamed("../../victim.txt")), NOT_OURS),
        ("absolute", write(renamed(&v)), NOT_OURS),
        (
            "inner-dotdot",
            write(renamed("vtu/../../../victim.txt")),
            NOT_OURS,
        ),
        (
            "other-folder",
            write(renamed("interface/0001.csv")),
            NOT_OURS,
        ),
        (
            "vtu-link",
            link(secret.clone(), "vtu/0002.vtu"),
            "vtu/0002.vtu is a symbolic link",
        ),
        (
            "vtu-folder-link",
            link(dir.join("elsewhere-vtu"), "vtu"),
            "vtu/0001.vtu: its folder vtu is a symbolic link",
        ),
        (
            "interface-link",
            link(secret.clone(), "interface/0002.csv"),
            "interface/0002.csv is a symbolic link",
        ),
        (
            "restart-link",
            link(dir.join("elsewhere.bin"), "restart.bin"),
            "the restart file is a symbolic link",
        ),
    ];
    let runs = dir.join("runs");
    for (name, change, needle) in variants {
        let r = runs.join(name);
        copy_dir(&good, &r);
        change(&r);
        refused(
            &dir,
            &r,
            &runs.join(format!("out-{name}")),
            &[],
            needle,
            name,
        );
        assert_eq!(std::fs::read(&victim).unwrap(), b"precious\n", "{name}");
    }
}

#[test]
fn a_forged_schedule_state_or_section_table_is_refused() {
    let dir = common::scratch("restart-forged-state");
    let good = stopped(&dir.join("good"));
    let bin = std::fs::read(good.join("restart.bin")).unwrap();
    let forge = common::Forge::parse(&bin);
    let with = |edit: &dyn Fn(&mut common::Forge)| {
        let mut f = forge.clone();
        edit(&mut f);
        f.bytes()
    };
    // the pending schedule, last target first: [1.0, 0.9, …, 0.4]
    let pending = forge.clone().f64s("pending_load_factor");
    assert_eq!(pending.len(), 7);
    assert_eq!(pending[0], 1.0);
    let variants: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "empty-schedule",
            with(&|f| {
                f.set_f64s("pending_load_factor", &[]);
                f.set_u64s("pending_depth", &[]);
            }),
            "pending schedule",
        ),
        (
            "shortened-schedule",
            with(&|f| {
                let l = f.f64s("pending_load_factor");
                let d = f.u64s("pending_depth");
                f.set_f64s("pending_load_factor", &l[1..]);
                f.set_u64s("pending_depth", &d[1..]);
            }),
            "6 targets to λ = 0.9 found, 7 targets to λ = 1 expected",
        ),
        (
            "later-load-factor",
            with(&|f| f.set_f64s("load_factor", &[0.9])),
            "section load_factor: load factor 0.9, but increment 3 ended at 0.3",
        ),
        (
            "curve-cutback",
            with(&|f| {
                let mut c = f.f64s("curve");
                c[10 + 3] = 1.0;
                f.set_f64s("curve", &c);
            }),
            "increment 2: load factor 0.2, where the case's schedule (with 1 cutbacks) gives 0.15",
        ),
        (
            "nan-in-u",
            with(&|f| {
                let mut u = f.f64s("u");
                u[17] = f64::NAN;
                f.set_f64s("u", &u);
            }),
            "section u: value 18 is not finite (NaN)",
        ),
        (
            "inf-in-gauss",
            with(&|f| {
                let mut g = f.f64s("gauss");
                g[3] = f64::INFINITY;
                f.set_f64s("gauss", &g);
            }),
            "section gauss: value 4 is not finite (inf)",
        ),
        (
            "status-code",
            with(&|f| {
                let mut s = f.get("status").data.clone();
                s[0] = 9;
                f.set_bytes("status", &s);
            }),
            "interface point 1: code 9 is no status",
        ),
        (
            "vtu-load-factor",
            with(&|f| {
                let mut l = f.f64s("pvd_load_factor");
                l[1] = 0.5;
                f.set_f64s("pvd_load_factor", &l);
            }),
            "VTU series entry 2: load factor 0.5, but increment 2 is at 0.2",
        ),
        (
            "increment-count",
            with(&|f| f.set_u64s("increment", &[u64::MAX / 4])),
            "increments, more than this case can take",
        ),
        (
            "section-count",
            forge.bytes_with_count(u32::MAX),
            "4294967295 sections, more than the 64",
        ),
        (
            "section-size",
            with(&|f| f.get("u").count = 1 << 60),
            "section u: 1152921504606846976 values, more than the file holds",
        ),
    ];
    let runs = dir.join("runs");
    for (name, bytes, needle) in variants {
        let r = runs.join(name);
        copy_dir(&good, &r);
        std::fs::write(r.join("restart.bin"), &bytes).unwrap();
        refused(
            &dir,
            &r,
            &runs.join(format!("out-{name}")),
            &[],
            needle,
            name,
        );
    }
    // the unchanged file still resumes, in place, to the end
    let r = runs.join("genuine");
    copy_dir(&good, &r);
    std::fs::write(r.join("restart.bin"), forge.bytes()).unwrap();
    let (code, err) = run(&r, &["--restart", &r.display().to_string()]);
    assert_eq!(code, 0, "{err}");
    let curve = std::fs::read_to_string(r.join("curve.csv")).unwrap();
    assert_eq!(curve.lines().count(), 1 + 10);
}

/// A sparse restart.bin of 8 GB (a valid file's length set with `set_len`)
/// is refused by its size, before anything of it is read.
#[test]
fn a_sparse_restart_file_of_8_gb_is_refused_by_its_size() {
    let dir = common::scratch("restart-sparse");
    let good = stopped(&dir.join("good"));
    let r = dir.join("runs/sparse");
    copy_dir(&good, &r);
    let f = std::fs::OpenOptions::new()
        .write(true)
        .open(r.join("restart.bin"))
        .unwrap();
    f.set_len(8 << 30).unwrap();
    drop(f);
    refused(
        &dir,
        &r,
        &dir.join("runs/out"),
        &[],
        "the restart file has 8589934592 bytes, more than the",
        "sparse",
    );
}

/// Automatic step control: emptied or shortened waypoints (which would end
/// the run early, "complete"), a step beyond the case's largest, and a
/// curve step past the next waypoint are refused.
#[test]
fn a_forged_automatic_step_state_is_refused() {
    let dir = common::scratch("restart-forged-auto");
    let auto = ["--step-control", "auto"];
    let good = stopped_with(&dir.join("good"), &auto);
    let forge = common::Forge::parse(&std::fs::read(good.join("restart.bin")).unwrap());
    assert_eq!(forge.clone().f64s("auto_waypoints"), [1.0]);
    let with = |edit: &dyn Fn(&mut common::Forge)| {
        let mut f = forge.clone();
        edit(&mut f);
        f.bytes()
    };
    let variants: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "no-waypoints",
            with(&|f| f.set_f64s("auto_waypoints", &[])),
            "none found, 1 targets to λ = 1 expected",
        ),
        (
            "nearer-waypoint",
            with(&|f| f.set_f64s("auto_waypoints", &[0.5])),
            "1 targets to λ = 0.5 found, 1 targets to λ = 1 expected",
        ),
        (
            "large-step",
            with(&|f| f.set_f64s("auto_step", &[2.0])),
            "section auto_step: step 2, outside the case's steps",
        ),
        (
            "past-the-end",
            with(&|f| {
                let mut c = f.f64s("curve");
                c[10 + 1] = 1.5;
                f.set_f64s("curve", &c);
            }),
            "increment 2: a step from",
        ),
    ];
    let runs = dir.join("runs");
    for (name, bytes, needle) in variants {
        let r = runs.join(name);
        copy_dir(&good, &r);
        std::fs::write(r.join("restart.bin"), &bytes).unwrap();
        refused(
            &dir,
            &r,
            &runs.join(format!("out-{name}")),
            &auto,
            needle,
            name,
        );
    }
}
