//! Regression gold values: every shipped case (each folder of `cases/`) is run
//! by the built program as a user runs it (`asperity run cases/NAME --out DIR
//! --quiet`) and the `summary.json` it writes is compared with the values the
//! program gave before, kept in the case folder as `expected.json`.
//!
//! **Checked** (`"checked"` in expected.json): the case, plane, method and step
//! control; whether the run is complete and what stopped it; the mesh counts
//! (dofs, equations, elements, interface pairs); the number of increments and
//! of cutbacks; the whole `first_yield` object (load factor, mean pressure,
//! load, x and depth of the Gauss point, body, element) and the whole `final`
//! object (load factor, mean pressure, load, center displacement, max PEEQ).
//!
//! **Tolerances:** integers (counts, the element), strings, booleans and null
//! exactly; arrays entry by entry. Real numbers to 1e-6 relative: |got − want| ≤ 1e-6 · max(|got|,
//! |want|), with an absolute floor of 1e-9 in the value's own unit (mm, MPa,
//! kN, or plastic strain) for values near 0 (it matters only below 1e-3: a
//! PEEQ of a run that barely yields, a first-yield point close to the
//! surface). Why 1e-6: Newton stops at 1e-8 on the residual and on the
//! displacement correction, so a change of the iteration path that is not a
//! change of the answer (a predictor, another linear solver, a reordered sum)
//! moves the converged values at about 1e-8; 1e-6 leaves room for that and
//! nothing more (today an error of 1e-5 fails). Do not tighten it.
//!
//! **Recorded, not checked** (`"not_checked"`): `newton_iterations` and
//! `factorizations`: iteration counts change with any solver speed-up that
//! keeps the answer. Timing and memory fields, the version and the backend
//! description are not recorded.
//!
//! **Prefixes:** a case too slow for CI may be checked on its first
//! increments only (`--stop-after N` in [`CASES`]; its expected.json says so
//! in `"prefix"`). None is today: `punch-plane-stress-fine` (93,508 dofs),
//! checked on 3 of its 4 increments while the serial solver was LU (90 s and
//! 1.5 GB for the whole run), runs whole since the Cholesky path (its 20
//! steps since 2026-11-27: about 50 s of one core, 250 MB).
//!
//! **Regenerating** (only after a change of the answers that is understood and
//! intended; review the diff of every expected.json before committing it):
//!
//! ```sh
//! ASPERITY_BLESS=1 cargo test --release --test verification gold::
//! ```
//!
//! runs every case and rewrites its expected.json from the summary.json it
//! wrote, with a `"source"` field naming the command, the run, the date (UTC)
//! and the commit. The values are never typed by hand.
//!
//! Comparisons with the paper and with peer codes stay separate, with their own
//! documented tolerances (tests/verification/punch.rs, tests/verification/friction.rs, docs/verification.md).

use crate::common;
use serde_json::{json, Map, Value};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Relative tolerance for real numbers.
const REL: f64 = 1e-6;
/// Absolute floor for real numbers near 0, in the value's own unit.
const ABS: f64 = 1e-9;

/// The summary.json fields that are checked (objects: every member).
const CHECKED: [&str; 14] = [
    "case",
    "plane",
    "method",
    "step_control",
    "complete",
    "stopped_by",
    "dofs",
    "equations",
    "elements",
    "interface_pairs",
    "increments",
    "cutbacks",
    "first_yield",
    "final",
];

/// The joint cases (issue 18) also check their `joints` array: per interface
/// the final forces, approach, slip, status measures, dissipation and work,
/// and every closed load cycle. The older cases keep the fields above only.
const JOINT_CASES: [&str; 11] = [
    "bolted-joint",
    "slideway-damping",
    "shrink-fit",
    "slideway-cycles",
    "bolted-flange",
    "shrink-fit-roughness",
    "hertz-cylinder",
    "cattaneo-mindlin",
    "shrink-fit-torque",
    "shrink-fit-combined",
    "face-coupling-torque",
];

/// The damping cases (issue 28) also check the amplitude sweep's fit.
const DAMPING_CASES: [&str; 1] = ["slideway-damping"];

/// The cases with `[[pretension]]` sections.
const PRETENSION_CASES: [&str; 2] = ["bolted-flange", "bolted-joint"];

/// The checked fields of a case.
fn checked(case: &str) -> Vec<&'static str> {
    let mut keys = CHECKED.to_vec();
    if JOINT_CASES.contains(&case) {
        keys.push("joints");
    }
    // a case with pretension sections (issue 27) checks their account
    // (force and shortening at the end, at the lock and their extremes)
    // and the bracketed events (the bolted joint's separation load)
    if PRETENSION_CASES.contains(&case) {
        keys.push("pretension");
        keys.push("events");
    }
    if DAMPING_CASES.contains(&case) {
        keys.push("damping");
    }
    // an adaptive case (issue 31) checks every cycle's mesh and estimate
    if case == "punch-adaptive" {
        keys.push("adapt");
    }
    keys
}

/// Recorded for the reader, not checked: a solver speed-up changes them.
const NOT_CHECKED: [&str; 2] = ["newton_iterations", "factorizations"];

/// A shipped case: its folder under cases/, extra arguments of the run, and why
/// (a prefix: what part of the run is checked and why not all of it).
struct Gold {
    case: &'static str,
    args: &'static [&'static str],
    prefix: Option<&'static str>,
}

const CASES: [Gold; 23] = [
    Gold {
        case: "bolted-joint",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-plane-stress",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-plane-strain",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-friction-a",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-friction-b",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-friction-c",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-gmsh",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "strip-lift-off",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-plane-stress-fine",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-gap",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "shrink-fit",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "slideway-cycles",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "slideway-damping",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "bolted-flange",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "shrink-fit-roughness",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "hertz-cylinder",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "cattaneo-mindlin",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-rounded-stress",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-rounded-strain",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "shrink-fit-torque",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "shrink-fit-combined",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "punch-adaptive",
        args: &[],
        prefix: None,
    },
    Gold {
        case: "face-coupling-torque",
        args: &[],
        prefix: None,
    },
];

fn bless() -> bool {
    std::env::var_os("ASPERITY_BLESS").is_some_and(|v| v == "1")
}

fn expected_path(case: &str) -> PathBuf {
    common::root()
        .join("cases")
        .join(case)
        .join("expected.json")
}

/// Runs the case with the built program; returns its summary.json and the
/// command line (as a user would type it).
fn run(g: &Gold) -> (Value, String) {
    let case = common::root().join("cases").join(g.case);
    let out = common::scratch(&format!("gold-{}", g.case)).join("out");
    let mut args: Vec<String> = vec![
        "run".into(),
        case.display().to_string(),
        "--out".into(),
        out.display().to_string(),
        "--quiet".into(),
    ];
    args.extend(g.args.iter().map(|s| s.to_string()));
    let res = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(&args)
        .output()
        .unwrap();
    // 3: stopped by --stop-after with the converged increments written
    let want_code = if g.args.contains(&"--stop-after") {
        3
    } else {
        0
    };
    assert_eq!(
        res.status.code(),
        Some(want_code),
        "{}: {}",
        g.case,
        String::from_utf8_lossy(&res.stderr)
    );
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let summary: Value = serde_json::from_str(&text).unwrap();
    let mut shown = format!("asperity run cases/{} --out DIR --quiet", g.case);
    for a in g.args {
        shown.push(' ');
        shown.push_str(a);
    }
    (summary, shown)
}

/// `out` = the members of `summary` named in `keys` (missing keys are an error).
fn pick(summary: &Value, keys: &[&str], case: &str) -> Map<String, Value> {
    keys.iter()
        .map(|k| {
            let v = summary
                .get(*k)
                .unwrap_or_else(|| panic!("{case}: summary.json has no `{k}`"));
            (k.to_string(), v.clone())
        })
        .collect()
}

/// Compares `got` with `want` at key path `path`; pushes each difference.
#[test]
fn the_comparator_reads_arrays_entry_by_entry() {
    let want = serde_json::json!({"a": [1.0, {"b": 2.0, "c": "x"}]});
    let errs = |got: Value| {
        let mut e = Vec::new();
        compare("", &want, &got, &mut e);
        e
    };
    // round-off in an array entry passes, a real difference does not
    assert!(errs(serde_json::json!({"a": [1.0 + 1e-15, {"b": 2.0, "c": "x"}]})).is_empty());
    let e = errs(serde_json::json!({"a": [1.0, {"b": 2.1, "c": "x"}]}));
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(e[0].starts_with(".a[1].b:"), "{e:?}");
    assert_eq!(
        errs(serde_json::json!({"a": [1.0, {"b": 2.0, "c": "y"}]})).len(),
        1
    );
    assert_eq!(errs(serde_json::json!({"a": [1.0]})).len(), 1);
}

fn compare(path: &str, want: &Value, got: &Value, errors: &mut Vec<String>) {
    match (want, got) {
        (Value::Object(w), Value::Object(g)) => {
            for (k, wv) in w {
                let p = format!("{path}.{k}");
                match g.get(k) {
                    Some(gv) => compare(&p, wv, gv, errors),
                    None => errors.push(format!("{p}: missing from summary.json")),
                }
            }
            for k in g.keys().filter(|k| !w.contains_key(*k)) {
                errors.push(format!("{path}.{k}: in summary.json, not in expected.json"));
            }
        }
        (Value::Array(w), Value::Array(g)) => {
            if w.len() != g.len() {
                errors.push(format!("{path}: {} entries, expected {}", g.len(), w.len()));
            }
            for (i, (wv, gv)) in w.iter().zip(g).enumerate() {
                compare(&format!("{path}[{i}]"), wv, gv, errors);
            }
        }
        (Value::Number(w), Value::Number(g)) if w.is_f64() || g.is_f64() => {
            let (w, g) = (w.as_f64().unwrap(), g.as_f64().unwrap());
            let tol = (REL * w.abs().max(g.abs())).max(ABS);
            if (g - w).abs() > tol || !g.is_finite() {
                errors.push(format!(
                    "{path}: {g:e}, expected {w:e} (difference {:.3e}, relative {:.3e}, tolerance {tol:.3e})",
                    g - w,
                    common::rel(g, w)
                ));
            }
        }
        _ => {
            if want != got {
                errors.push(format!("{path}: {got}, expected {want} (exact)"));
            }
        }
    }
}

/// The date and time now, UTC, as `YYYY-MM-DDTHH:MMZ`.
fn utc_now() -> String {
    let s = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_secs() as i64;
    let (days, sec) = (s.div_euclid(86_400), s.rem_euclid(86_400));
    // days since 1970-01-01 to the civil date (H. Hinnant's algorithm)
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}Z",
        sec / 3600,
        sec % 3600 / 60
    )
}

/// The commit the program was built from, "+ uncommitted changes" when the
/// tracked files (other than the expected.json being written) differ from it.
fn commit() -> String {
    let git = |args: &[&str]| {
        Command::new("git")
            .arg("-C")
            .arg(common::root())
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    let Some(head) = git(&["rev-parse", "--short=12", "HEAD"]) else {
        return "unknown (no git)".into();
    };
    let dirty = git(&[
        "status",
        "--porcelain",
        "--untracked-files=no",
        "--",
        ".",
        ":(exclude)cases/*/expected.json",
    ])
    .is_none_or(|s| !s.is_empty());
    if dirty {
        format!("{head} + uncommitted changes")
    } else {
        head
    }
}

fn write_expected(g: &Gold, summary: &Value, shown: &str) {
    let not_checked = {
        let mut m = pick(summary, &NOT_CHECKED, g.case);
        m.insert(
            "why".into(),
            "iteration counts: recorded for the reader, not asserted (a solver speed-up that keeps \
             the answer changes them)"
                .into(),
        );
        m
    };
    let doc = json!({
        "case": g.case,
        "source": {
            "command": "ASPERITY_BLESS=1 cargo test --release --test verification gold::",
            "run": shown,
            "date": utc_now(),
            "commit": commit(),
            "asperity_version": summary["asperity_version"],
        },
        "tolerance": {
            "relative": REL,
            "absolute_floor": ABS,
            "rule": "real numbers: |got - want| <= max(relative * max(|got|, |want|), absolute_floor), \
                     the floor in the value's own unit; integers, strings, booleans and null exactly",
        },
        "prefix": g.prefix,
        "checked": pick(summary, &checked(g.case), g.case),
        "not_checked": not_checked,
    });
    let text = serde_json::to_string_pretty(&doc).unwrap() + "\n";
    std::fs::write(expected_path(g.case), text).unwrap();
}

fn check(case: &str) {
    let g = CASES.iter().find(|g| g.case == case).unwrap();
    let started = std::time::Instant::now();
    let (summary, shown) = run(g);
    eprintln!("{case}: ran in {:.1} s", started.elapsed().as_secs_f64());
    if bless() {
        write_expected(g, &summary, &shown);
        eprintln!("{case}: wrote {}", expected_path(case).display());
        return;
    }
    let path = expected_path(case);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e}; generate it with ASPERITY_BLESS=1 cargo test --release --test verification gold::",
            path.display()
        )
    });
    let expected: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(expected["case"], case);
    assert_eq!(expected["tolerance"]["relative"], REL, "{}", path.display());
    assert_eq!(expected["tolerance"]["absolute_floor"], ABS);
    assert_eq!(
        expected["source"]["run"],
        shown,
        "{}: made by another run than the test's; bless again",
        path.display()
    );
    let want = expected["checked"]
        .as_object()
        .expect("expected.json has a `checked` object");
    let mut keys: Vec<&str> = want.keys().map(String::as_str).collect();
    keys.sort_unstable();
    let mut sorted = checked(case);
    sorted.sort_unstable();
    assert_eq!(keys, sorted, "{}: checked fields", path.display());
    let got = Value::Object(pick(&summary, &checked(case), case));
    let mut errors = Vec::new();
    compare("", &expected["checked"], &got, &mut errors);
    assert!(
        errors.is_empty(),
        "{case}: summary.json differs from {}:\n  {}",
        path.display(),
        errors.join("\n  ")
    );
}

#[test]
fn bolted_joint() {
    check("bolted-joint");
}

#[test]
fn punch_plane_stress() {
    check("punch-plane-stress");
}

#[test]
fn punch_plane_strain() {
    check("punch-plane-strain");
}

#[test]
fn punch_friction_a() {
    check("punch-friction-a");
}

#[test]
fn punch_friction_b() {
    check("punch-friction-b");
}

#[test]
fn punch_friction_c() {
    check("punch-friction-c");
}

#[test]
fn punch_gmsh() {
    check("punch-gmsh");
}

#[test]
fn strip_lift_off() {
    check("strip-lift-off");
}

#[test]
fn punch_plane_stress_fine() {
    check("punch-plane-stress-fine");
}

#[test]
fn punch_gap() {
    check("punch-gap");
}

/// Every folder of cases/ is in [`CASES`] (so a new case cannot go unchecked)
/// and its README says where its gold values are.
#[test]
fn every_shipped_case_has_gold_values() {
    let mut folders: Vec<String> = std::fs::read_dir(common::root().join("cases"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    folders.sort();
    let mut listed: Vec<String> = CASES.iter().map(|g| g.case.to_string()).collect();
    listed.sort();
    assert_eq!(
        folders, listed,
        "cases/ and tests/verification/gold.rs CASES differ"
    );
    for g in &CASES {
        let dir: &Path = &common::root().join("cases").join(g.case);
        if !bless() {
            assert!(
                expected_path(g.case).is_file(),
                "{}: no expected.json",
                g.case
            );
        }
        let readme = std::fs::read_to_string(dir.join("README.md"))
            .unwrap_or_else(|e| panic!("cases/{}/README.md: {e}", g.case));
        assert!(
            readme.contains("expected.json") && readme.contains("tests/verification/gold.rs"),
            "cases/{}/README.md does not point to expected.json and tests/verification/gold.rs",
            g.case
        );
    }
}

#[test]
fn the_comparison_catches_a_small_drift_and_allows_round_off() {
    let want = json!({"a": 1.0, "n": 20, "s": "x", "o": {"z": 0.0}});
    let mut errors = Vec::new();
    // 1e-7 relative and 1e-10 absolute at 0: inside
    let near = json!({"a": 1.0 + 1e-7, "n": 20, "s": "x", "o": {"z": 1e-10}});
    compare("", &want, &near, &mut errors);
    assert!(errors.is_empty(), "{errors:?}");
    // 1e-5 relative, another count, another string, a near-0 value off by 1e-8
    let far = json!({"a": 1.0 + 1e-5, "n": 21, "s": "y", "o": {"z": 1e-8}});
    compare("", &want, &far, &mut errors);
    assert_eq!(errors.len(), 4, "{errors:?}");
}

#[test]
fn shrink_fit() {
    check("shrink-fit");
}

#[test]
fn slideway_cycles() {
    check("slideway-cycles");
}

#[test]
fn slideway_damping() {
    check("slideway-damping");
}

#[test]
fn bolted_flange() {
    check("bolted-flange");
}

#[test]
fn punch_adaptive() {
    check("punch-adaptive");
}

#[test]
fn shrink_fit_torque() {
    check("shrink-fit-torque");
}

#[test]
fn shrink_fit_combined() {
    check("shrink-fit-combined");
}

#[test]
fn shrink_fit_roughness() {
    check("shrink-fit-roughness");
}

#[test]
fn hertz_cylinder() {
    check("hertz-cylinder");
}

#[test]
fn cattaneo_mindlin() {
    check("cattaneo-mindlin");
}

#[test]
fn punch_rounded_stress() {
    check("punch-rounded-stress");
}

#[test]
fn punch_rounded_strain() {
    check("punch-rounded-strain");
}

#[test]
fn face_coupling_torque() {
    check("face-coupling-torque");
}
