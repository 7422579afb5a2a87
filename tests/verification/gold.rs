//! Regression gold values: every shipped case (each folder of `cases/`) is run
//! by the built program as a user runs it (`asperity run cases/NAME --out DIR
//! --quiet`) and the `summary.json` it writes is compared with the values the
//! program gave before, kept in the case folder as `expected.json`; and
//! `asperity report` makes its calculation report (exit 0, a page with its
//! ratings section).
//!
//! **What is compared lives in each case's expected.json**, not here; this file
//! only reads and compares, so a new case needs no edit of it:
//!
//! - `"fields"`: `"checked"`, the summary.json members compared (an object or
//!   an array member by member), and `"not_checked"`, members recorded for the
//!   reader only;
//! - `"checked"` and `"not_checked"`: their values;
//! - `"tolerance"`: `"relative"` and `"absolute_floor"` for real numbers;
//! - `"args"`: more arguments of the run (after `--out DIR --quiet`), and
//!   `"prefix"`: null, or why only the first increments are checked (a case
//!   too slow for CI run with `--stop-after N`; then the run exits with 3);
//! - `"source"`: the command, run, date and commit that wrote the values.
//!
//! Every case checks the case, plane, method and step control; whether the run
//! is complete and what stopped it; the mesh counts (dofs, equations, elements,
//! interface pairs); the number of increments and of cutbacks; the whole
//! `first_yield` object (load factor, mean pressure, load, x and depth of the
//! Gauss point, body, element) and the whole `final` object (load factor, mean
//! pressure, load, center displacement, max PEEQ). The joint cases (issue 18)
//! add `joints` (per interface the final forces, approach, slip, status
//! measures, dissipation and work, and every closed load cycle), the cases with
//! `[[pretension]]` sections (issue 27) `pretension` and `events`, the damping
//! case (issue 28) `damping`, the adaptive case (issue 31) `adapt`.
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
//! nothing more (today an error of 1e-5 fails). Do not tighten it. Every case
//! holds these two numbers in its `"tolerance"`; one may hold tighter ones, and
//! one looser than [`REL_MAX`] or [`ABS_MAX`] fails the test.
//!
//! **Recorded, not checked** (`"not_checked"`): `newton_iterations` and
//! `factorizations`: iteration counts change with any solver speed-up that
//! keeps the answer. Timing and memory fields, the version and the backend
//! description are not recorded.
//!
//! **Prefixes:** none today: `punch-plane-stress-fine` (93,508 dofs), checked
//! on 3 of its 4 increments while the serial solver was LU (90 s and 1.5 GB for
//! the whole run), runs whole since the Cholesky path (its 20 steps since
//! 2026-11-27: about 50 s of one core, 250 MB).
//!
//! **Regenerating** (only after a change of the answers that is understood and
//! intended; review the diff of every expected.json before committing it):
//!
//! ```sh
//! ASPERITY_BLESS=1 cargo test --release --test verification gold::
//! ```
//!
//! runs every case and rewrites the values of its expected.json (`"checked"`,
//! `"not_checked"`) from the summary.json it wrote, with a `"source"` field
//! naming the command, the run, the date (UTC) and the commit; `"fields"`,
//! `"tolerance"`, `"args"` and `"prefix"` stay as the file has them. The values
//! are never typed by hand. `ASPERITY_GOLD=NAME,NAME` limits the test (and the
//! blessing) to those cases. A new case starts from an expected.json holding
//! `"case"`, `"args"`, `"fields"`, `"prefix"` and `"tolerance"` (copy them from
//! a case like it), blessed once.
//!
//! Comparisons with the paper and with peer codes stay separate, with their own
//! documented tolerances (tests/verification/punch.rs, tests/verification/friction.rs, docs/verification.md).

use crate::common;
use serde_json::{json, Map, Value};
use std::path::PathBuf;
use std::process::Command;

/// The loosest relative tolerance a case may hold for real numbers.
const REL_MAX: f64 = 1e-6;
/// The loosest absolute floor a case may hold for real numbers near 0, in the
/// value's own unit.
const ABS_MAX: f64 = 1e-9;

/// What a case's expected.json says about its comparison.
struct Gold {
    case: String,
    /// More arguments of the run.
    args: Vec<String>,
    /// The summary.json members compared, and those recorded only.
    checked: Vec<String>,
    not_checked: Vec<String>,
    /// Relative tolerance and absolute floor for real numbers.
    tol: (f64, f64),
    /// Null, or why only a prefix of the run is checked.
    prefix: Value,
    /// The whole file as read.
    doc: Value,
}

fn bless() -> bool {
    std::env::var_os("ASPERITY_BLESS").is_some_and(|v| v == "1")
}

fn expected_path(case: &str) -> PathBuf {
    common::root()
        .join("cases")
        .join(case)
        .join("expected.json")
}

/// The folders of cases/, sorted.
fn shipped_cases() -> Vec<String> {
    let mut folders: Vec<String> = std::fs::read_dir(common::root().join("cases"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    folders.sort();
    folders
}

/// A list of strings of the file at `path` (`.a.b`), or what is wrong.
fn strings(doc: &Value, path: &[&str]) -> Result<Vec<String>, String> {
    let v = path.iter().fold(doc, |v, k| &v[*k]);
    let where_ = format!(".{}", path.join("."));
    let list = v
        .as_array()
        .ok_or_else(|| format!("{where_}: not an array of strings"))?;
    list.iter()
        .map(|s| {
            s.as_str()
                .map(str::to_string)
                .ok_or_else(|| format!("{where_}: {s} is not a string"))
        })
        .collect()
}

/// Reads what a case's expected.json says about its comparison, checking that
/// it is complete and coherent: the case's name, the lists of fields (some
/// checked, none twice, none both checked and recorded), the arguments, a
/// tolerance no looser than [`REL_MAX`] and [`ABS_MAX`], and a prefix given
/// exactly when the run stops early.
fn read_gold(case: &str) -> Result<Gold, String> {
    let path = expected_path(case);
    let text = std::fs::read_to_string(&path).map_err(|e| {
        format!("{e}; write one with \"case\", \"args\", \"fields\", \"prefix\" and \"tolerance\", then bless it")
    })?;
    let doc: Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    if doc["case"] != case {
        return Err(format!(".case: {}, expected {case:?}", doc["case"]));
    }
    let checked = strings(&doc, &["fields", "checked"])?;
    let not_checked = strings(&doc, &["fields", "not_checked"])?;
    if checked.is_empty() {
        return Err(".fields.checked: empty".into());
    }
    let mut all = checked.clone();
    all.extend(not_checked.iter().cloned());
    all.sort();
    if let Some(w) = all.windows(2).find(|w| w[0] == w[1]) {
        return Err(format!(".fields: {:?} listed twice", w[0]));
    }
    let args = strings(&doc, &["args"])?;
    let tol = (
        doc["tolerance"]["relative"].as_f64(),
        doc["tolerance"]["absolute_floor"].as_f64(),
    );
    let tol = match tol {
        (Some(r), Some(a)) if r > 0.0 && r <= REL_MAX && a > 0.0 && a <= ABS_MAX => (r, a),
        _ => {
            return Err(format!(
                ".tolerance: relative {} and absolute_floor {}: each must be a number above 0 and at most {REL_MAX:e} and {ABS_MAX:e}",
                doc["tolerance"]["relative"], doc["tolerance"]["absolute_floor"]
            ))
        }
    };
    let prefix = doc["prefix"].clone();
    let stops = args.iter().any(|a| a.starts_with("--stop-after"));
    match (&prefix, stops) {
        (Value::Null, false) | (Value::String(_), true) => {}
        _ => {
            return Err(format!(
                ".prefix: {prefix}: a string saying why exactly when the run stops early (--stop-after in .args), null otherwise"
            ))
        }
    }
    Ok(Gold {
        case: case.to_string(),
        args,
        checked,
        not_checked,
        tol,
        prefix,
        doc,
    })
}

/// Runs the case with the built program; returns its summary.json and the
/// command line (as a user would type it).
fn run(g: &Gold) -> Result<(Value, String), String> {
    let case = common::root().join("cases").join(&g.case);
    let out = common::scratch(&format!("gold-{}", g.case)).join("out");
    let mut args: Vec<String> = vec![
        "run".into(),
        case.display().to_string(),
        "--out".into(),
        out.display().to_string(),
        "--quiet".into(),
    ];
    args.extend(g.args.iter().cloned());
    let res = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(&args)
        .output()
        .unwrap();
    // 3: stopped by --stop-after with the converged increments written;
    // 4: ended at a torque limit, which summary.json says (a case's gold
    // values hold its `stopped_by`)
    let written = std::fs::read_to_string(out.join("summary.json")).unwrap_or_default();
    let limited =
        serde_json::from_str::<Value>(&written).is_ok_and(|s| s["stopped_by"] == "torque_limit");
    let want_code = match (g.prefix.is_string(), limited) {
        (true, _) => 3,
        (false, true) => 4,
        (false, false) => 0,
    };
    if res.status.code() != Some(want_code) {
        return Err(format!(
            "exit code {:?}, expected {want_code}: {}",
            res.status.code(),
            String::from_utf8_lossy(&res.stderr)
        ));
    }
    let text = std::fs::read_to_string(out.join("summary.json")).map_err(|e| e.to_string())?;
    let summary: Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    // and its calculation report, as a user would hand it on
    let page = Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(["report", &out.display().to_string()])
        .output()
        .unwrap();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap_or_default();
    if page.status.code() != Some(0) || !html.contains("id=\"ratings\"") {
        return Err(format!(
            "asperity report: exit code {:?}: {}",
            page.status.code(),
            String::from_utf8_lossy(&page.stderr)
        ));
    }
    let mut shown = format!("asperity run cases/{} --out DIR --quiet", g.case);
    for a in &g.args {
        shown.push(' ');
        shown.push_str(a);
    }
    Ok((summary, shown))
}

/// `out` = the members of `summary` named in `keys` (missing keys are an error).
fn pick(summary: &Value, keys: &[String]) -> Result<Map<String, Value>, String> {
    keys.iter()
        .map(|k| {
            summary
                .get(k)
                .map(|v| (k.clone(), v.clone()))
                .ok_or_else(|| format!("summary.json has no `{k}`"))
        })
        .collect()
}

#[test]
fn the_comparator_reads_arrays_entry_by_entry() {
    let want = serde_json::json!({"a": [1.0, {"b": 2.0, "c": "x"}]});
    let errs = |got: Value| {
        let mut e = Vec::new();
        compare("", &want, &got, (REL_MAX, ABS_MAX), &mut e);
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

/// Compares `got` with `want` at key path `path` with the tolerance
/// `(relative, absolute floor)` for real numbers; pushes each difference.
fn compare(path: &str, want: &Value, got: &Value, tol: (f64, f64), errors: &mut Vec<String>) {
    match (want, got) {
        (Value::Object(w), Value::Object(g)) => {
            for (k, wv) in w {
                let p = format!("{path}.{k}");
                match g.get(k) {
                    Some(gv) => compare(&p, wv, gv, tol, errors),
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
                compare(&format!("{path}[{i}]"), wv, gv, tol, errors);
            }
        }
        (Value::Number(w), Value::Number(g)) if w.is_f64() || g.is_f64() => {
            let (w, g) = (w.as_f64().unwrap(), g.as_f64().unwrap());
            let tol = (tol.0 * w.abs().max(g.abs())).max(tol.1);
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

/// Rewrites the values of the case's expected.json from a run's summary.json;
/// what the file says about the comparison stays.
fn write_expected(g: &Gold, summary: &Value, shown: &str) -> Result<(), String> {
    let not_checked = {
        let mut m = pick(summary, &g.not_checked)?;
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
        "args": g.args,
        "fields": g.doc["fields"],
        "source": {
            "command": "ASPERITY_BLESS=1 cargo test --release --test verification gold::",
            "run": shown,
            "date": utc_now(),
            "commit": commit(),
            "asperity_version": summary["asperity_version"],
        },
        "tolerance": {
            "relative": g.tol.0,
            "absolute_floor": g.tol.1,
            "rule": "real numbers: |got - want| <= max(relative * max(|got|, |want|), absolute_floor), \
                     the floor in the value's own unit; integers, strings, booleans and null exactly",
        },
        "prefix": g.prefix,
        "checked": pick(summary, &g.checked)?,
        "not_checked": not_checked,
    });
    let text = serde_json::to_string_pretty(&doc).unwrap() + "\n";
    std::fs::write(expected_path(&g.case), text).map_err(|e| e.to_string())
}

/// Runs one case and compares it with its expected.json (or blesses it):
/// the differences, one a line.
fn check(case: &str) -> Result<(), String> {
    let g = read_gold(case)?;
    let started = std::time::Instant::now();
    let (summary, shown) = run(&g)?;
    eprintln!("{case}: ran in {:.1} s", started.elapsed().as_secs_f64());
    // issue 29's target on this same run
    crate::status_convergence::target(case, &summary)?;
    if bless() {
        write_expected(&g, &summary, &shown)?;
        eprintln!("{case}: wrote {}", expected_path(case).display());
        return Ok(());
    }
    if g.doc["source"]["run"] != shown.as_str() {
        return Err(format!(
            "made by another run than the test's ({}, not {shown:?}); bless again",
            g.doc["source"]["run"]
        ));
    }
    let want = g.doc["checked"]
        .as_object()
        .ok_or("expected.json has no `checked` object")?;
    let mut keys: Vec<&String> = want.keys().collect();
    keys.sort_unstable();
    let mut listed: Vec<&String> = g.checked.iter().collect();
    listed.sort_unstable();
    if keys != listed {
        return Err(format!(
            "the values of `checked` are for {keys:?}, `fields.checked` lists {listed:?}"
        ));
    }
    let got = Value::Object(pick(&summary, &g.checked)?);
    let mut errors = Vec::new();
    compare("", &g.doc["checked"], &got, g.tol, &mut errors);
    if errors.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "summary.json differs:\n    {}",
            errors.join("\n    ")
        ))
    }
}

/// Every folder of cases/ (or those `ASPERITY_GOLD` names, comma-separated)
/// run and compared with its expected.json, one after the other; every
/// difference of every case is reported.
#[test]
fn every_shipped_case_gives_its_gold_values() {
    let all = shipped_cases();
    let only = std::env::var("ASPERITY_GOLD").unwrap_or_default();
    let chosen: Vec<&String> = if only.is_empty() {
        all.iter().collect()
    } else {
        let names: Vec<&str> = only.split(',').map(str::trim).collect();
        for n in &names {
            assert!(
                all.iter().any(|c| c == n),
                "ASPERITY_GOLD: no case {n:?} in cases/"
            );
        }
        all.iter().filter(|c| names.contains(&c.as_str())).collect()
    };
    let started = std::time::Instant::now();
    let failures: Vec<String> = chosen
        .iter()
        .filter_map(|case| check(case).err().map(|e| format!("cases/{case}: {e}")))
        .collect();
    eprintln!(
        "{} cases in {:.0} s",
        chosen.len(),
        started.elapsed().as_secs_f64()
    );
    assert!(
        failures.is_empty(),
        "{} of {} cases differ from their expected.json:\n{}",
        failures.len(),
        chosen.len(),
        failures.join("\n")
    );
}

/// Every folder of cases/ has an expected.json that says what is compared (so
/// a new case cannot go unchecked), and its README says where its gold values
/// are.
#[test]
fn every_shipped_case_has_gold_values() {
    let all = shipped_cases();
    assert!(all.len() >= 20, "only {} cases", all.len());
    let mut problems = Vec::new();
    for case in &all {
        if let Err(e) = read_gold(case) {
            problems.push(format!("cases/{case}/expected.json: {e}"));
        }
        let readme =
            std::fs::read_to_string(common::root().join("cases").join(case).join("README.md"))
                .unwrap_or_default();
        if !(readme.contains("expected.json") && readme.contains("tests/verification/gold.rs")) {
            problems.push(format!(
                "cases/{case}/README.md does not point to expected.json and tests/verification/gold.rs"
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_comparison_catches_a_small_drift_and_allows_round_off() {
    let want = json!({"a": 1.0, "n": 20, "s": "x", "o": {"z": 0.0}});
    let mut errors = Vec::new();
    // 1e-7 relative and 1e-10 absolute at 0: inside
    let near = json!({"a": 1.0 + 1e-7, "n": 20, "s": "x", "o": {"z": 1e-10}});
    compare("", &want, &near, (REL_MAX, ABS_MAX), &mut errors);
    assert!(errors.is_empty(), "{errors:?}");
    // 1e-5 relative, another count, another string, a near-0 value off by 1e-8
    let far = json!({"a": 1.0 + 1e-5, "n": 21, "s": "y", "o": {"z": 1e-8}});
    compare("", &want, &far, (REL_MAX, ABS_MAX), &mut errors);
    assert_eq!(errors.len(), 4, "{errors:?}");
}
