//! A restart folder is input (issue 30): `restart.bin` can be rewritten by
//! anyone into a well-formed file (the checksum and the fingerprint are
//! computable), and the files beside it can be replaced by links. Forged
//! names, links, schedules, states and sizes are refused with one line
//! naming the restart file and exit code 2; nothing outside `--out` is
//! written or truncated, and no output folder is left behind.

use crate::common;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::common::run_asperity as asperity;

/// The case the forgeries start from: punch-plane-stress (both bodies
/// plastic, the power law).
fn punch() -> PathBuf {
    common::root().join("cases/punch-plane-stress")
}

/// `run punch-plane-stress --increments 10 --out OUT --quiet` plus `extra`.
fn run(out: &Path, extra: &[&str]) -> (i32, String) {
    run_case(&punch(), out, extra)
}

/// `run CASE --increments 10 --out OUT --quiet` plus `extra`.
fn run_case(case: &Path, out: &Path, extra: &[&str]) -> (i32, String) {
    let c = case.display().to_string();
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
    stopped_case(&punch(), dir, extra)
}

fn stopped_case(case: &Path, dir: &Path, extra: &[&str]) -> PathBuf {
    let mut args = vec!["--stop-after", "3"];
    args.extend_from_slice(extra);
    let (code, err) = run_case(case, dir, &args);
    assert_eq!(code, 3, "{err}");
    dir.to_path_buf()
}

/// The longest run of characters of a number (digits, `.`, `e`, `-`, `+`)
/// in `s`: a float quoted in a refusal is short (docs/reliability.md: at
/// most 80 characters per quoted value), `1e300`, never 301 digits.
fn longest_number(s: &str) -> usize {
    s.split(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | 'e' | '-' | '+')))
        .map(str::len)
        .max()
        .unwrap_or(0)
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
/// …` line containing `needle` and no number longer than 30 characters,
/// within 20 s, and nothing changed anywhere under `root` (no output, no
/// partial folder, no file outside).
fn refused(root: &Path, restart: &Path, out: &Path, extra: &[&str], needle: &str, what: &str) {
    refused_case(&punch(), root, restart, out, extra, needle, what)
}

/// [`refused`] for the run of `case`.
fn refused_case(
    case: &Path,
    root: &Path,
    restart: &Path,
    out: &Path,
    extra: &[&str],
    needle: &str,
    what: &str,
) {
    let before = tree(root);
    let t = Instant::now();
    let r = restart.display().to_string();
    let mut args = vec!["--restart", &r];
    args.extend_from_slice(extra);
    let (code, err) = run_case(case, out, &args);
    let secs = t.elapsed().as_secs_f64();
    assert_eq!(code, 2, "{what}: {err}");
    let file = restart.join("restart.bin").display().to_string();
    assert!(
        err.starts_with(&format!("error: {file}: ")) && err.lines().count() == 1,
        "{what}: {err}"
    );
    assert!(err.contains(needle), "{what}: {err}");
    assert!(longest_number(&err) <= 30, "{what}: a long number in {err}");
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
        // counters beyond what the case can count (they wrapped around in
        // summary.json)
        (
            "counters-max",
            with(&|f| f.set_u64s("counters", &[u64::MAX, u64::MAX])),
            "section counters: 18446744073709551615 Newton iterations, more than a run of this case can count after 3 increments and 0 cutbacks",
        ),
        (
            "counters-1e15",
            with(&|f| {
                let c = f.u64s("counters");
                f.set_u64s("counters", &[c[0], 1_000_000_000_000_000]);
            }),
            "section counters: 1000000000000000 factorizations, more than",
        ),
        // finite, but no displacement of a case (the run ended "did not
        // converge … NaN" instead of naming the file)
        (
            "u-1e300",
            with(&|f| {
                let n = f.f64s("u").len();
                f.set_f64s("u", &vec![1e300; n]);
            }),
            "section u: value 1 is 1e300 mm, beyond the ±1e4 mm of the displacement range of a case",
        ),
        (
            "last-du-beyond",
            with(&|f| {
                let mut d = f.f64s("last_du");
                d[4] = -2e4;
                f.set_f64s("last_du", &d);
            }),
            "section last_du: value 5 is -2e4 mm, beyond the ±1e4 mm",
        ),
        // forged floats are quoted short: 1e300, 1e-300, not 300 digits
        (
            "load-factor-1e300",
            with(&|f| f.set_f64s("load_factor", &[1e300])),
            "section load_factor: load factor 1e300, but increment 3 ended at 0.3",
        ),
        (
            "curve-1e-300",
            with(&|f| {
                let mut c = f.f64s("curve");
                c[1] = 1e-300;
                f.set_f64s("curve", &c);
            }),
            "increment 1: load factor 1e-300, where the case's schedule (with 0 cutbacks) gives 0.1",
        ),
        (
            "elastic-ratio-1e-300",
            with(&|f| f.set_f64s("elastic_ratio_prev", &[-1e-300])),
            "section elastic_ratio_prev: -1e-300 is negative",
        ),
        // another format: refused from the header, naming both versions
        (
            "format-1",
            with(&|f| f.head[8..12].copy_from_slice(&1u32.to_le_bytes())),
            "restart.bin was written by an earlier asperity (restart format 1); this build reads format 5 only: run the case again from the start",
        ),
        (
            "format-6",
            with(&|f| f.head[8..12].copy_from_slice(&6u32.to_le_bytes())),
            "restart.bin was written by a later asperity (restart format 6); this build reads format 5 only",
        ),
        // every section of the format is required, none other allowed
        (
            "no-event-counters",
            with(&|f| f.sections.retain(|s| s.name != "event_counters")),
            "section event_counters missing: every restart file of format 5 holds it",
        ),
        (
            "no-last-du",
            with(&|f| f.sections.retain(|s| s.name != "last_du")),
            "section last_du missing: every restart file of format 5 holds it",
        ),
        (
            "unknown-section",
            with(&|f| {
                let mut s = f.get("increment").clone();
                s.name = "later_section".into();
                f.sections.push(s);
            }),
            "section \"later_section\" is no section of restart format 5",
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

/// Resumes every variant (a forged `restart.bin` in a copy of `good`) of
/// the run of `case` and checks its refusal ([`refused_case`]); then the
/// unchanged file resumes to the end.
fn refuse_all(case: &Path, dir: &Path, good: &Path, variants: Vec<(&str, Vec<u8>, String)>) {
    let runs = dir.join("runs");
    for (name, bytes, needle) in variants {
        let r = runs.join(name);
        copy_dir(good, &r);
        std::fs::write(r.join("restart.bin"), &bytes).unwrap();
        refused_case(
            case,
            dir,
            &r,
            &runs.join(format!("out-{name}")),
            &[],
            &needle,
            name,
        );
    }
    let r = runs.join("genuine");
    copy_dir(good, &r);
    let (code, err) = run_case(case, &r, &["--restart", &r.display().to_string()]);
    assert_eq!(code, 0, "{err}");
}

/// Gauss states the case's return mapping cannot leave (issue 30, red
/// team: εᵖxy = −1 at every point moved the punch 35 mm instead of
/// 0.057 mm). punch-plane-stress with an elastic punch (no yield_stress):
/// any plastic strain, ε̄ᵖ or yielding flag in the punch; in the plastic
/// foundation ε̄ᵖ below √(2/3)|εᵖ|, a plastic strain with a trace or beyond
/// 10, ε̄ᵖ beyond 10⁴, a stress beyond 10¹² MPa or above the yield surface,
/// and σzz ≠ 0 in plane stress are refused, naming the point and its body.
#[test]
fn a_forged_gauss_state_is_refused() {
    let text = std::fs::read_to_string(punch().join("case.toml")).unwrap();
    let plastic = "[materials.punch]\nyoung = 206000.0\npoisson = 0.3\nyield_stress = 1960.0\nhardening = 2060.0\n";
    assert!(text.contains(plastic));
    let case = common::case_dir(
        "restart-forged-gauss",
        &text.replace(
            plastic,
            "[materials.punch]\nyoung = 206000.0\npoisson = 0.3\n",
        ),
    );
    let dir = case.parent().unwrap().to_path_buf();
    let good = stopped_case(&case, &dir.join("good"), &[]);
    let forge = common::Forge::parse(&std::fs::read(good.join("restart.bin")).unwrap());
    let g = forge.clone().f64s("gauss");
    let n = g.len() / 10;
    // the last point is the foundation's, elastic at λ = 0.3
    assert_eq!(&g[10 * (n - 1) + 4..], &[0.0; 6]);
    // `edit` changes the packed state (σ ×4, εᵖ ×4, ε̄ᵖ, yielding) of the
    // points `points`
    let with = |points: &[usize], edit: &dyn Fn(&mut [f64])| {
        let mut f = forge.clone();
        let mut g = g.clone();
        for &p in points {
            edit(&mut g[10 * p..10 * p + 10]);
        }
        f.set_f64s("gauss", &g);
        f.bytes()
    };
    let every: Vec<usize> = (0..n).collect();
    let last = [n - 1];
    let foundation = format!("section gauss: Gauss point {n} (body \"foundation\"): ");
    let punch = "section gauss: Gauss point 1 (body \"punch\"): ";
    let variants: Vec<(&str, Vec<u8>, String)> = vec![
        (
            "minus-one-everywhere",
            with(&every, &|v| v[6] = -1.0),
            format!("{punch}plastic strain [0, 0, -1, 0] (εᵖxx εᵖyy εᵖxy εᵖzz), equivalent plastic strain 0 and yielding flag 0 in an elastic body (no yield_stress: all 0)"),
        ),
        (
            "elastic-peeq",
            with(&[0], &|v| v[8] = 0.5),
            format!("{punch}plastic strain [0, 0, 0, 0] (εᵖxx εᵖyy εᵖxy εᵖzz), equivalent plastic strain 0.5 and yielding flag 0 in an elastic body"),
        ),
        (
            "elastic-yielding",
            with(&[0], &|v| v[9] = 1.0),
            "equivalent plastic strain 0 and yielding flag 1 in an elastic body".into(),
        ),
        (
            "peeq-below",
            with(&last, &|v| {
                v[4..9].copy_from_slice(&[0.01, -0.01, 0.0, 0.0, 1e-3]);
            }),
            format!("{foundation}equivalent plastic strain 1e-3 below √(2/3)|εᵖ| = "),
        ),
        (
            "trace",
            with(&last, &|v| {
                v[4..9].copy_from_slice(&[0.01, 0.0, 0.0, 0.0, 0.02]);
            }),
            format!("{foundation}plastic strain [0.01, 0, 0, 0] (εᵖxx εᵖyy εᵖxy εᵖzz) of trace 0.01 (plastic flow is deviatoric: trace 0)"),
        ),
        (
            "plastic-strain-20",
            with(&last, &|v| {
                v[4..9].copy_from_slice(&[20.0, -20.0, 0.0, 0.0, 40.0]);
            }),
            format!("{foundation}plastic strain [20, -20, 0, 0] (εᵖxx εᵖyy εᵖxy εᵖzz) of magnitude 28.2"),
        ),
        (
            "peeq-1e5",
            with(&last, &|v| v[8] = 1e5),
            format!("{foundation}equivalent plastic strain 1e5, beyond 1e4"),
        ),
        (
            "stress-1e300",
            with(&[0], &|v| v[1] = 1e300),
            format!("{punch}stress σyy = 1e300 MPa, beyond ±1e12 MPa"),
        ),
        (
            "above-yield",
            with(&last, &|v| v[..4].copy_from_slice(&[1000.0, 0.0, 0.0, 0.0])),
            format!("{foundation}equivalent stress 1e3 MPa above the yield stress σ_Y + H ε̄ᵖ = 196 MPa"),
        ),
        (
            "plane-stress-szz",
            with(&last, &|v| v[3] = 5.0),
            format!("{foundation}σzz = 5 MPa in plane stress (0 exactly)"),
        ),
    ];
    refuse_all(&case, &dir, &good, variants);
}

/// How far the tables were used (`table_reach`, issue 30): a reach outside
/// the displacement and pressure ranges (−1 mm, 1e300 MPa), a pressure that
/// is not the law's at the approach (1e3 mm with 1e5 MPa: a false warning of
/// extrapolation followed), or one below the restored state's own reach is
/// refused.
#[test]
fn a_forged_table_reach_is_refused() {
    let text = std::fs::read_to_string(punch().join("case.toml")).unwrap();
    let power =
        "law = \"power\"\nc_n = 0.001          # mm/MPa^m: 14 µm of approach at 200 MPa\nm = 0.5";
    assert!(text.contains(power));
    // the power law sampled at 5, 10, 20 MPa
    let case = common::case_dir(
        "restart-forged-reach",
        &text.replace(
            power,
            "law = \"table\"\ntable = [[2.23606797749979e-3, 5.0], [3.1622776601683794e-3, 10.0], [4.47213595499958e-3, 20.0]]",
        ),
    );
    let dir = case.parent().unwrap().to_path_buf();
    let good = stopped_case(&case, &dir.join("good"), &[]);
    let forge = common::Forge::parse(&std::fs::read(good.join("restart.bin")).unwrap());
    let reach = forge.clone().f64s("table_reach");
    assert!(reach[0] > 0.0 && reach[1] > 0.0, "{reach:?}");
    let with = |v: [f64; 2]| {
        let mut f = forge.clone();
        f.set_f64s("table_reach", &v);
        f.bytes()
    };
    let at = "section table_reach: interface \"contact\": largest approach u_N = ";
    let variants: Vec<(&str, Vec<u8>, String)> = vec![
        (
            "outside",
            with([-1.0, 1e300]),
            format!("{at}-1 mm and pressure p_N = 1e300 MPa, outside [0, 1e4] mm and [0, 1e6] MPa"),
        ),
        (
            "beyond-pressure",
            with([reach[0], 2e6]),
            "MPa, outside [0, 1e4] mm and [0, 1e6] MPa".into(),
        ),
        (
            "not-the-law",
            with([1e3, 1e5]),
            format!("{at}1e3 mm and pressure p_N = 1e5 MPa, but the normal law gives "),
        ),
        (
            "below-own",
            with([0.0, 0.0]),
            format!("{at}0 mm and pressure p_N = 0 MPa, below the restored state's own u_N = "),
        ),
        (
            "nan",
            with([f64::NAN, reach[1]]),
            "section table_reach: value 1 is not finite (NaN)".into(),
        ),
    ];
    refuse_all(&case, &dir, &good, variants);
}

/// A run under automatic step control stopped exactly at a breakpoint of its
/// load history (slideway-cycles after increment 11 is at t = 1; shrink-fit
/// after 20) resumes and ends as the uninterrupted run. The stepper drops a
/// reached waypoint only when it picks the next step, so the file may hold
/// it or not; the restart used to refuse its own file there.
#[test]
fn a_run_stopped_at_a_breakpoint_resumes() {
    let dir = common::scratch("restart-at-breakpoint");
    // (block-3d: a 3D model's six-component Gauss states and its peaks' z)
    for (case, stop) in [
        ("slideway-cycles", "11"),
        ("shrink-fit", "20"),
        ("block-3d", "3"),
    ] {
        let c = common::root().join("cases").join(case);
        let c = c.to_str().unwrap();
        let out = |n: &str| dir.join(format!("{case}-{n}"));
        let (s, r, full) = (out("stopped"), out("resumed"), out("full"));
        let (code, err) = asperity(&[
            "run",
            c,
            "--quiet",
            "--out",
            s.to_str().unwrap(),
            "--stop-after",
            stop,
        ]);
        assert_eq!(code, 3, "{case}: {err}");
        let (code, err) = asperity(&[
            "run",
            c,
            "--quiet",
            "--out",
            r.to_str().unwrap(),
            "--restart",
            s.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{case}: {err}");
        let (code, err) = asperity(&["run", c, "--quiet", "--out", full.to_str().unwrap()]);
        assert_eq!(code, 0, "{case}: {err}");
        for f in [
            "curve.csv",
            "joints.csv",
            "restart.bin",
            "reactions.csv",
            "peaks.csv",
            "contact.csv",
            "probes.csv",
        ] {
            assert!(
                std::fs::read(r.join(f)).unwrap() == std::fs::read(full.join(f)).unwrap(),
                "{case}: {f} of the resumed run differs"
            );
        }
    }
}

/// A restart continues the VTU series in its own encoding: a case that
/// changed `vtu_format` since the stop is refused (the folder would mix
/// binary and ASCII files); the same encoding resumes.
#[test]
fn a_restart_keeps_the_vtu_encoding() {
    let dir = common::scratch("restart-vtu-format");
    let text =
        std::fs::read_to_string(common::root().join("cases/slideway-cycles/case.toml")).unwrap();
    let (bin, asc) = (dir.join("binary"), dir.join("ascii"));
    for (d, t) in [
        (&bin, text.clone()),
        (&asc, format!("{text}\n[output]\nvtu_format = \"ascii\"\n")),
    ] {
        std::fs::create_dir_all(d).unwrap();
        std::fs::write(d.join("case.toml"), t).unwrap();
    }
    let s = |p: &Path| p.to_str().unwrap().to_string();
    let stop = dir.join("stopped");
    let (code, err) = asperity(&[
        "run",
        &s(&bin),
        "--quiet",
        "--out",
        &s(&stop),
        "--stop-after",
        "5",
    ]);
    assert_eq!(code, 3, "{err}");
    let out = dir.join("resumed");
    let (code, err) = asperity(&[
        "run",
        &s(&asc),
        "--quiet",
        "--out",
        &s(&out),
        "--restart",
        &s(&stop),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("fingerprint"), "{err}");
    assert!(!out.exists());
    let (code, err) = asperity(&[
        "run",
        &s(&bin),
        "--quiet",
        "--out",
        &s(&out),
        "--restart",
        &s(&stop),
    ]);
    assert_eq!(code, 0, "{err}");
}

/// A restart folder of an earlier asperity (a genuine `restart.bin` of
/// restart format 1, written by the build before format 2 after increment
/// 2 of the coarse punch; the bad-input corpus's folder 584) is refused
/// with one line naming the file and both formats, whether the run would
/// write into a new folder or continue in the restart folder itself: exit
/// 2, nothing written, no partial folder left.
#[test]
fn a_restart_file_of_format_1_is_refused() {
    let corpus = common::root().join("tests/bad_inputs/584-restart-format-1");
    let dir = common::scratch("restart-format-1");
    let old = dir.join("old");
    copy_dir(&corpus.join("stopped"), &old);
    let bin = std::fs::read(old.join("restart.bin")).unwrap();
    assert_eq!(&bin[..12], b"ASPRSTRT\x01\0\0\0", "a file of format 1");
    let needle = "restart.bin was written by an earlier asperity (restart format 1); this build reads format 5 only: run the case again from the start";
    for out in [dir.join("new"), old.clone()] {
        refused_case(&corpus, &dir, &old, &out, &[], needle, "format 1");
    }
}

/// A restart of a body whose σ_Y follows a temperature field
/// (`yield_table`, `field`): each stored Gauss state is checked against the
/// yield stress of its own point at the committed pseudo-time, not the
/// case's `yield_stress`. A block held everywhere and cooled by up to 100 K
/// (ΔT = −100 K × x/20) is stressed in tension E α |ΔT|/(1 − ν): 260.4 MPa
/// at its coldest Gauss point when stopped (8 of 10 increments), above
/// σ_Y = 250 MPa at the 20 °C reference (checked against that, the restart
/// was refused) and below σ_Y(T) = 250 + (20 − T) MPa there (325.5 MPa).
/// The resumed run is the uninterrupted one, bit for bit.
#[test]
fn a_run_with_a_yield_stress_following_a_temperature_field_resumes() {
    let text = common::case()
        .plane("stress")
        .block("bar", [0.0, 20.0], [2], [0.0, 6.0], [1])
        .material("bar", 210000.0, 0.3)
        .plastic(250.0, 0.0)
        .with("expansion", 11.5e-6)
        .with(
            "yield_table",
            [[-100.0, 370.0], [20.0, 250.0], [100.0, 170.0]],
        )
        .ux("bar.all", 0.0)
        .uy("bar.all", 0.0)
        .raw("[[temperature]]")
        .with("body", "bar")
        .with("change", -100.0)
        .with("reference", 20.0)
        .raw("field = \"x/20\"")
        .solver("")
        .no_vtu()
        .build();
    let case = common::case_dir("restart-field-tables", &text);
    let dir = case.parent().unwrap().to_path_buf();
    let (s, r, full) = (dir.join("stopped"), dir.join("resumed"), dir.join("full"));
    let (code, err) = run_case(&case, &s, &["--stop-after", "8"]);
    assert_eq!(code, 3, "{err}");
    let (code, err) = run_case(&case, &r, &["--restart", s.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = run_case(&case, &full, &[]);
    assert_eq!(code, 0, "{err}");
    for f in ["curve.csv", "restart.bin", "peaks.csv"] {
        assert!(
            std::fs::read(r.join(f)).unwrap() == std::fs::read(full.join(f)).unwrap(),
            "{f} of the resumed run differs"
        );
    }
}

/// A cyclic sector (cases/tube-sector-cyclic, its torque in 10 steps)
/// stopped after 3 resumes to the bit: its ties are the case's and the
/// mesh's, which the restart file's fingerprint identifies. The same sector
/// with its faces named the other way round (ties turned by −30°, the same
/// mesh) is another model: its restart from that file is refused.
#[test]
fn a_cyclic_sector_resumes_and_a_restart_with_other_ties_is_refused() {
    let text =
        std::fs::read_to_string(common::root().join("cases/tube-sector-cyclic/case.toml")).unwrap();
    let case = common::case_dir("restart-cyclic", &text);
    let dir = case.parent().unwrap().to_path_buf();
    let (s, r, full) = (dir.join("stopped"), dir.join("resumed"), dir.join("full"));
    stopped_case(&case, &s, &[]);
    let (code, err) = run_case(&case, &r, &["--restart", s.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = run_case(&case, &full, &[]);
    assert_eq!(code, 0, "{err}");
    for f in ["restart.bin", "reactions.csv", "probes.csv", "peaks.csv"] {
        assert!(
            std::fs::read(r.join(f)).unwrap() == std::fs::read(full.join(f)).unwrap(),
            "{f} of the resumed run differs"
        );
    }
    let turned = text.replace(
        "faces = [\"tube.theta0\", \"tube.theta1\"]",
        "faces = [\"tube.theta1\", \"tube.theta0\"]",
    );
    assert_ne!(turned, text);
    let other = common::case_dir("restart-cyclic-turned", &turned);
    let out = other.parent().unwrap().join("out");
    refused_case(
        &other,
        &dir,
        &s,
        &out,
        &[],
        "fingerprint mismatch",
        "faces turned",
    );
}
