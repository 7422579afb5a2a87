//! The output writer's thread and the VTU encodings (docs/output.md, "VTU"):
//! both encodings hold the same numbers bit for bit; the first and last
//! states and every history breakpoint get a VTU file whatever `vtu_every`
//! says, a stopped run its last state too; a folder the threaded writer left
//! at a stop lists only complete files and resumes to the uninterrupted
//! result; a write that fails in the middle of a run ends it with one error
//! line, exit code 2, no panic, no hang and no output folder.

use crate::common;
use std::collections::BTreeSet;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_asperity"))
}

/// A copy of `cases/NAME` with `[output]` settings appended, in its own
/// scratch folder; the path of its case.toml.
fn case_with_output(tag: &str, name: &str, output: &str) -> PathBuf {
    let text =
        std::fs::read_to_string(common::root().join("cases").join(name).join("case.toml")).unwrap();
    assert!(!text.contains("[output]"), "{name} has an [output] table");
    common::case_dir(tag, &format!("{text}\n[output]\n{output}\n"))
}

/// Exit code and stderr of `asperity run CASE --quiet --out OUT EXTRA…`.
fn run(case: &Path, out: &Path, extra: &[&str]) -> (i32, String) {
    let o = bin()
        .arg("run")
        .arg(case)
        .args(["--quiet", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

/// The increments of the VTU series of an output folder (results.pvd), with
/// their time values; each listed file must exist.
fn series(out: &Path) -> Vec<(usize, f64)> {
    let pvd = std::fs::read_to_string(out.join("results.pvd")).unwrap();
    pvd.lines()
        .filter(|l| l.starts_with("<DataSet"))
        .map(|l| {
            let attr = |k: &str| {
                let v = &l[l.find(&format!("{k}=\"")).unwrap() + k.len() + 2..];
                v[..v.find('"').unwrap()].to_string()
            };
            let file = attr("file");
            assert!(out.join(&file).is_file(), "{file} listed but missing");
            let k = file
                .strip_prefix("vtu/")
                .and_then(|f| f.strip_suffix(".vtu"))
                .unwrap()
                .parse()
                .unwrap();
            (k, attr("timestep").parse().unwrap())
        })
        .collect()
}

/// (increment, load factor) of every row of curve.csv.
fn curve(out: &Path) -> Vec<(usize, f64)> {
    std::fs::read_to_string(out.join("curve.csv"))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            let mut f = l.split(',');
            (
                f.next().unwrap().parse().unwrap(),
                f.next().unwrap().parse().unwrap(),
            )
        })
        .collect()
}

const POINT_ARRAYS: [&str; 7] = [
    "displacement",
    "stress",
    "von_mises",
    "peeq",
    "contact_pressure",
    "contact_shear",
    "contact_closed",
];

/// Every array of a VTU file has the size of the mesh: the file is complete.
fn check_complete(file: &Path, nodes: usize, cells: usize) {
    assert_eq!(common::vtu_array(file, "connectivity").len(), 8 * cells);
    assert_eq!(common::vtu_array(file, "types").len(), cells);
    for name in POINT_ARRAYS {
        let comps = match name {
            "displacement" => 3,
            "stress" => 4,
            _ => 1,
        };
        let v = common::vtu_array(file, name);
        assert_eq!(v.len(), comps * nodes, "{}: {name}", file.display());
        assert!(v.iter().all(|x| x.is_finite()));
    }
    for name in ["body", "max_peeq"] {
        assert_eq!(common::vtu_array(file, name).len(), cells);
    }
}

fn mesh_size(out: &Path) -> (usize, usize) {
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    (
        s["dofs"].as_u64().unwrap() as usize / 2,
        s["elements"].as_u64().unwrap() as usize,
    )
}

#[test]
fn binary_and_ascii_vtu_hold_the_same_numbers_and_everything_else_is_identical() {
    let dir = common::scratch("vtu-formats");
    let mut outs = Vec::new();
    for format in ["binary", "ascii"] {
        let case = case_with_output(
            &format!("vtu-formats-{format}"),
            "punch-plane-stress",
            &format!("vtu_format = \"{format}\""),
        );
        let out = dir.join(format);
        let (code, err) = run(&case, &out, &["--increments", "6"]);
        assert_eq!(code, 0, "{err}");
        outs.push(out);
    }
    let (nodes, cells) = mesh_size(&outs[0]);
    assert_eq!(series(&outs[0]), series(&outs[1]));
    for (k, _) in series(&outs[0]) {
        let f = format!("vtu/{k:04}.vtu");
        let (b, a) = (outs[0].join(&f), outs[1].join(&f));
        let bytes = std::fs::read(&b).unwrap();
        assert!(bytes
            .windows(29)
            .any(|w| w == b"<AppendedData encoding=\"raw\">"));
        let text = std::fs::read_to_string(&a).expect("an ASCII VTU file is text");
        assert!(!text.contains("AppendedData") && text.contains("format=\"ascii\""));
        check_complete(&b, nodes, cells);
        check_complete(&a, nodes, cells);
        for name in
            POINT_ARRAYS
                .iter()
                .chain(&["connectivity", "offsets", "types", "body", "max_peeq"])
        {
            let (x, y) = (common::vtu_array(&b, name), common::vtu_array(&a, name));
            assert_eq!(x.len(), y.len());
            for (i, (p, q)) in x.iter().zip(&y).enumerate() {
                // the text is the shortest form that reads back as the value
                assert_eq!(p.to_bits(), q.to_bits(), "{f} {name}[{i}]: {p} vs {q}");
            }
        }
        // binary is the smaller
        assert!(bytes.len() < text.len());
    }
    // the encoding changes nothing else
    for f in [
        "curve.csv",
        "joints.csv",
        "results.pvd",
        "interface/0006.csv",
    ] {
        assert_eq!(
            std::fs::read(outs[0].join(f)).unwrap(),
            std::fs::read(outs[1].join(f)).unwrap(),
            "{f}"
        );
    }
}

#[test]
fn first_last_and_turning_points_are_written_whatever_vtu_every_says() {
    // three load cycles under automatic steps: breakpoints at t = 1, 2, …, 10
    let case = case_with_output("vtu-every-cycles", "slideway-cycles", "vtu_every = 7");
    let out = common::scratch("vtu-every-cycles-out").join("out");
    let (code, err) = run(&case, &out, &[]);
    assert_eq!(code, 0, "{err}");
    let rows = curve(&out);
    let last = rows.len();
    let expected: BTreeSet<usize> = rows
        .iter()
        .filter(|&&(k, t)| k == 1 || k % 7 == 0 || k == last || t == t.round())
        .map(|&(k, _)| k)
        .collect();
    // the ten turning points (and the end) are among them
    assert!(rows.iter().filter(|r| r.1 == r.1.round()).count() >= 10);
    let written = series(&out);
    assert_eq!(
        written.iter().map(|w| w.0).collect::<BTreeSet<_>>(),
        expected
    );
    // each at its increment's load factor (curve.csv has 9 decimals), in order
    for (k, t) in &written {
        assert!((t - rows[k - 1].1).abs() <= 1e-9, "increment {k}: {t}");
    }
    assert!(written.windows(2).all(|w| w[0].0 < w[1].0));
    let (nodes, cells) = mesh_size(&out);
    for (k, _) in &written {
        check_complete(&out.join(format!("vtu/{k:04}.vtu")), nodes, cells);
    }
}

#[test]
fn a_stopped_run_writes_its_last_state_and_resumes_to_the_uninterrupted_result() {
    let case = case_with_output("vtu-stopped", "punch-plane-stress", "vtu_every = 4");
    let root = common::scratch("vtu-stopped-out");
    let full = root.join("full");
    let (code, err) = run(&case, &full, &["--increments", "12"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        series(&full).iter().map(|s| s.0).collect::<Vec<_>>(),
        [1, 4, 8, 12]
    );
    let stopped = root.join("stopped");
    let (code, err) = run(
        &case,
        &stopped,
        &["--increments", "12", "--stop-after", "6"],
    );
    assert_eq!(code, 3, "{err}");
    // increment 6, the last state, is written although 6 is not a multiple of 4
    assert_eq!(
        series(&stopped).iter().map(|s| s.0).collect::<Vec<_>>(),
        [1, 4, 6]
    );
    let (nodes, cells) = mesh_size(&stopped);
    for k in [1, 4, 6] {
        check_complete(&stopped.join(format!("vtu/{k:04}.vtu")), nodes, cells);
    }
    // the checkpoint lists it: the resumed run copies it and goes on
    let resumed = root.join("resumed");
    let (code, err) = run(
        &case,
        &resumed,
        &["--increments", "12", "--restart", stopped.to_str().unwrap()],
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        series(&resumed).iter().map(|s| s.0).collect::<Vec<_>>(),
        [1, 4, 6, 8, 12]
    );
    for f in [
        "curve.csv",
        "joints.csv",
        "interface/0012.csv",
        "vtu/0012.vtu",
    ] {
        assert_eq!(
            std::fs::read(full.join(f)).unwrap(),
            std::fs::read(resumed.join(f)).unwrap(),
            "{f}"
        );
    }
}

/// Starts a run with JSON progress lines; once increment `after` is
/// reported, `sabotage` gets the run's hidden temporary folder. Returns exit
/// code, stderr and the seconds from the sabotage to the exit.
fn sabotaged_run(
    tag: &str,
    extra: &[&str],
    after: usize,
    sabotage: impl FnOnce(&Path),
) -> (i32, String, f64, PathBuf) {
    let dir = common::scratch(tag);
    let out = dir.join("out");
    let mut child = bin()
        .arg("run")
        .arg(common::root().join("cases/punch-plane-strain"))
        .args(extra)
        .args(["--log-format", "json", "--out"])
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let mut log = String::new();
    let mut seen = 0;
    for line in lines.by_ref() {
        let line = line.unwrap();
        log += &line;
        log.push('\n');
        if line.contains("\"event\":\"increment\"") {
            seen += 1;
            if seen == after {
                break;
            }
        }
    }
    assert_eq!(seen, after, "the run ended early: {log}");
    let tmp = dir.join(format!(".out.partial-{}", child.id()));
    assert!(tmp.is_dir(), "no {}", tmp.display());
    let t = Instant::now();
    sabotage(&tmp);
    let mut err = String::new();
    for line in lines {
        err += &line.unwrap();
        err.push('\n');
    }
    let code = child.wait().unwrap().code().unwrap_or(-1);
    (code, err, t.elapsed().as_secs_f64(), out)
}

/// The folder `sub` of the temporary output folder replaced by a file: every
/// later file in it fails to be created (root ignores permissions, not this).
fn replace_by_file(tmp: &Path, sub: &str) {
    std::fs::rename(tmp.join(sub), tmp.join(format!("{sub}-moved"))).unwrap();
    std::fs::write(tmp.join(sub), b"not a folder").unwrap();
}

fn assert_one_clean_error(code: i32, err: &str, secs: f64, out: &Path, needle: &str) {
    assert_eq!(code, 2, "{err}");
    let errors: Vec<&str> = err.lines().filter(|l| l.contains("\"error\"")).collect();
    assert_eq!(errors.len(), 1, "{err}");
    assert!(errors[0].contains(needle), "{err}");
    assert!(!err.contains("panick"), "{err}");
    // the run ended at its next increment or so, not at its end
    assert!(secs < 20.0, "took {secs} s after the failure");
    let parent = out.parent().unwrap();
    let left: Vec<_> = std::fs::read_dir(parent)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

#[test]
fn a_vtu_write_that_fails_mid_run_ends_it_with_one_error() {
    let (code, err, secs, out) = sabotaged_run(
        "vtu-write-fails",
        &["--refine", "2", "--increments", "60"],
        3,
        |tmp| replace_by_file(tmp, "vtu"),
    );
    assert_one_clean_error(code, &err, secs, &out, "vtu/00");
    // the run did not go on to the end
    assert!(err.matches("\"event\":\"increment\"").count() < 20, "{err}");
}

#[test]
fn an_interface_csv_write_that_fails_mid_run_ends_it_with_one_error() {
    let (code, err, secs, out) = sabotaged_run(
        "csv-write-fails",
        &["--refine", "2", "--increments", "60"],
        3,
        |tmp| replace_by_file(tmp, "interface"),
    );
    assert_one_clean_error(code, &err, secs, &out, "interface/00");
}

#[test]
fn a_removed_output_folder_mid_run_ends_it_with_one_error() {
    let (code, err, secs, out) = sabotaged_run(
        "folder-removed",
        &["--refine", "2", "--increments", "60"],
        3,
        |tmp| {
            // files of the moment may still be created while it goes
            for _ in 0..50 {
                if std::fs::remove_dir_all(tmp).is_ok() {
                    return;
                }
                std::thread::sleep(Duration::from_millis(2));
            }
            panic!("cannot remove {}", tmp.display());
        },
    );
    assert_one_clean_error(code, &err, secs, &out, ".out.partial-");
}
