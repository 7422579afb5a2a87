//! `asperity report OUT`: the calculation report of a finished output folder.
//! A real run of cases/bolted-joint (and cases/block-3d for a 3D mesh), its
//! summary.json given the keys a later run adds (ratings, applied loads,
//! singular points, warnings, the case's fingerprint: the contract of
//! docs/output.md) as a fixture; the report must be one self-contained file
//! that shows the summary's numbers as `asperity::app::report::figure`
//! prints them. Bad folders (no summary.json, malformed JSON, a CSV of
//! another header, results.pvd naming a file outside vtu/, a link) are
//! refused with exit code 2, a message naming the file, and no report left
//! behind. The browser's side is in `report_browser.rs`.

use crate::common;
use asperity::app::report::figure;
use serde_json::{json, Value};
use std::os::unix::fs::FileTypeExt as _;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The output folder of one run of `case`, made once per test binary.
fn run_once(case: &'static str, cell: &'static OnceLock<PathBuf>) -> &'static Path {
    cell.get_or_init(|| {
        let out = common::scratch(&format!("report-run-{case}")).join("out");
        let case = common::root().join("cases").join(case);
        let (code, e) = common::run_case(&case, &out, &[]);
        assert_eq!(code, 0, "{e}");
        out
    })
}

fn bolted() -> &'static Path {
    static RUN: OnceLock<PathBuf> = OnceLock::new();
    run_once("bolted-joint", &RUN)
}

/// A copy of the folder `from` at `to` (files and folders).
pub fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), &target).unwrap();
        }
    }
}

/// A fresh copy of the bolted joint's folder named `name`.
pub fn bolted_copy(name: &str) -> PathBuf {
    let dir = common::scratch(name).join("out");
    copy_dir(bolted(), &dir);
    dir
}

fn summary(dir: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// The keys of the verdict (docs/output.md) added to a real summary: two
/// ratings (a VDI 2230 one that passes one check and fails two, a DIN 7190
/// one not rated), the applied loads, a singular point, a warning, the
/// fingerprint, a description and each event's meaning.
pub fn add_verdict(dir: &Path) -> Value {
    let mut s = summary(dir);
    s["description"] = json!("An M12 bolt clamping two plates <fixture> & more");
    s["case_fingerprint"] = json!("fnv1a64:0123456789abcdef");
    s["ratings"] = json!([
        {
            "standard": "VDI 2230-1:2015", "name": "bolt", "subject": "M12 8.8 through-bolt",
            "inputs": [
                {"name": "nominal diameter", "symbol": "d", "value": 12.0, "unit": "mm", "from": "mesh"},
                {"name": "thread friction", "symbol": "μ_G", "value": 0.12, "unit": "", "from": "default"}
            ],
            "checks": [
                {"quantity": "assembly preload", "symbol": "F_M", "unit": "kN", "fe": 30.0, "handbook": 29.41,
                 "difference": 0.02006, "required": 25.0, "safety": 1.2, "required_safety": 1.0, "pass": true,
                 "note": "FE: the section's force at the lock"},
                {"quantity": "residual clamp load", "symbol": "F_KR", "unit": "kN", "fe": -3.217, "handbook": 1.874,
                 "difference": null, "required": 2.5, "safety": null, "required_safety": null, "pass": false,
                 "note": "the joint separates"},
                {"quantity": "equivalent bolt stress", "symbol": "σ_red", "unit": "MPa", "fe": 645.28, "handbook": 612.77,
                 "difference": 0.05305, "required": 640.0, "safety": 0.9918, "required_safety": 1.0, "pass": false,
                 "note": ""}
            ]
        },
        {
            "standard": "DIN 7190-1:2017", "name": "fit", "subject": "no fit in this joint",
            "incomplete": "the run stopped early (fixture)",
            "inputs": [],
            "checks": [
                {"quantity": "transmissible torque", "symbol": "M_t", "unit": "N·m", "fe": 182.3, "handbook": 178.0,
                 "difference": 0.024, "required": null, "safety": null, "required_safety": null, "pass": null,
                 "note": "FE: plateau of the interface torque"}
            ]
        }
    ]);
    s["applied_loads"] = json!([
        {"name": "load[0]", "source": "load[0]", "kind": "pressure", "selection": "top_plate.top, x in [8.5, 12.5]",
         "components": ["fx_n", "fy_n"], "final": [0.0, 45000.0], "max": [0.0, 45000.0], "min": [0.0, 0.0]}
    ]);
    s["singular"] = json!([
        {"what": "max_von_mises", "body": "bolt", "x_mm": 6.056, "y_mm": 12.23,
         "corner": "re-entrant corner (270°)", "estimate_share": 0.12,
         "note": "grows with refinement: read a nominal stress or fillet the corner"}
    ]);
    s["warnings"] =
        json!(["interface between: 2 closed cycles of fewer than 4 increments (fixture)"]);
    for e in s["events"].as_array_mut().unwrap() {
        e["meaning"] = json!(format!("the meaning of {}", e["event"].as_str().unwrap()));
    }
    std::fs::write(
        dir.join("summary.json"),
        serde_json::to_string_pretty(&s).unwrap(),
    )
    .unwrap();
    s
}

/// `asperity report ARGS…`: (exit code, stderr, stdout).
pub fn report(args: &[&str]) -> (i32, String, String) {
    let mut all = vec!["report"];
    all.extend_from_slice(args);
    common::run_asperity_out(&all)
}

fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The page's table rows as text, one line per row, cells joined by ` | `
/// (tags dropped, entities decoded).
pub fn rows(html: &str) -> Vec<String> {
    let mut text = String::new();
    let mut rest = html;
    while let Some(open) = rest.find('<') {
        text.push_str(&rest[..open]);
        let close = open + rest[open..].find('>').unwrap();
        let tag = &rest[open..=close];
        if tag == "</td>" || tag == "</th>" {
            text.push_str(" | ");
        } else if tag == "</tr>" {
            text.push('\n');
        }
        rest = &rest[close + 1..];
    }
    let text = text
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&#39;", "'")
        .replace("&amp;", "&");
    text.lines().map(|l| l.trim().to_string()).collect()
}

/// The row whose first cell is `first`.
fn row<'a>(rows: &'a [String], first: &str) -> &'a str {
    let start = format!("{first} | ");
    rows.iter()
        .find(|r| r.starts_with(&start))
        .unwrap_or_else(|| panic!("no row \"{first}\" in\n{}", rows.join("\n")))
}

/// Every `src=` and `href=` of the page points at `data:` or an anchor; no
/// script, stylesheet link, import or CSS url; the policy is there.
pub fn assert_self_contained(html: &str) {
    let lower = html.to_ascii_lowercase();
    for attr in ["src=", "href="] {
        for (at, _) in lower.match_indices(attr) {
            let value = lower[at + attr.len()..].trim_start_matches(['"', '\'']);
            assert!(
                value.starts_with("data:") || value.starts_with('#'),
                "{attr} to something else: {}",
                &html[at..(at + 80).min(html.len())]
            );
        }
    }
    for bad in [
        "<script", "<link", "@import", "url(", "<iframe", "<object", "<embed",
    ] {
        assert!(!lower.contains(bad), "the page holds {bad}");
    }
    assert!(html.contains("<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'; img-src data:\">"));
}

#[test]
fn the_report_of_a_bolted_joint_is_one_self_contained_file_with_its_numbers() {
    let dir = bolted_copy("report-bolted");
    let s = add_verdict(&dir);
    let before = listing(&dir);
    let (code, e, out) = report(&[&dir.display().to_string()]);
    assert_eq!(code, 0, "{e}");
    let page = dir.join("report.html");
    assert_eq!(out.trim(), page.display().to_string());
    let mut after = listing(&dir);
    after.retain(|n| !before.contains(n));
    assert_eq!(after, ["report.html"], "one new file, no temporary left");
    let html = std::fs::read_to_string(&page).unwrap();
    assert_self_contained(&html);
    assert!(html.contains("<title>Calculation report: bolted-joint</title>"));
    assert!(html.contains("An M12 bolt clamping two plates &lt;fixture&gt; &amp; more"));
    // the sections in order, each picture inline: the mesh and the charts
    let order = [
        "id=\"run\"",
        "id=\"mesh\"",
        "id=\"curves\"",
        "id=\"interfaces\"",
        "id=\"ratings\"",
        "id=\"warnings\"",
    ];
    let at: Vec<usize> = order
        .iter()
        .map(|k| html.find(k).unwrap_or_else(|| panic!("{k}")))
        .collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "{at:?}");
    let svgs = html.matches("<svg").count();
    // mesh, 3 of curve.csv, 3 interfaces' forces, bolt force, 3 pressures, 1 slip
    assert!(svgs >= 12, "{svgs} pictures");
    assert!(html.contains("font-family=\"sans-serif\""));
    let rows = rows(&html);
    let t = |v: &Value| figure(v.as_f64().unwrap());
    // the model and the run
    assert!(row(&rows, "case fingerprint").contains("fnv1a64:0123456789abcdef"));
    assert!(row(&rows, "elements").contains(&format!("| {} |", s["elements"])));
    assert!(row(&rows, "program version").contains(s["asperity_version"].as_str().unwrap()));
    // the final state and the first yield
    let load = row(&rows, "total load (first interface's normal force)");
    assert!(
        load.contains(&format!(
            "| {} kN | {} kN |",
            t(&s["final"]["total_load_kn"]),
            t(&s["first_yield"]["total_load_kn"])
        )),
        "{load}"
    );
    let lf = row(&rows, "load factor (pseudo-time)");
    assert!(
        lf.contains(&format!("| {} |", t(&s["first_yield"]["load_factor"]))),
        "{lf}"
    );
    let p = row(&rows, "mean contact pressure");
    assert!(
        p.contains(&format!("| {} MPa |", t(&s["final"]["mean_pressure_mpa"]))),
        "{p}"
    );
    let lock = row(&rows, "bolt | bolt, y = 0");
    assert!(
        lock.contains(&format!(
            "{} kN",
            figure(s["pretension"][0]["force_at_lock_n"].as_f64().unwrap() / 1000.0)
        )),
        "{lock}"
    );
    let vm = s["peaks"][0]["max_von_mises"]["value_mpa"]
        .as_f64()
        .unwrap();
    assert!(rows
        .iter()
        .any(|r| r.starts_with("bolt | largest von Mises stress | ")
            && r.contains(&format!("{} MPa", figure(vm)))));
    // every rating check: FE and handbook values with the unit, PASS / FAIL in words
    for rating in s["ratings"].as_array().unwrap() {
        for c in rating["checks"].as_array().unwrap() {
            let r = row(&rows, c["quantity"].as_str().unwrap());
            let unit = c["unit"].as_str().unwrap();
            for key in ["fe", "handbook"] {
                assert!(
                    r.contains(&format!("| {} {unit} |", t(&c[key]))),
                    "{key} in {r}"
                );
            }
            let word = match c["pass"].as_bool() {
                Some(true) => "| PASS |",
                Some(false) => "| FAIL |",
                None => "| not rated |",
            };
            assert!(r.contains(word), "{word} in {r}");
        }
    }
    assert!(
        html.contains("<td class=\"pass\">PASS</td>")
            && html.contains("<td class=\"fail\">FAIL</td>")
    );
    // a rating without a verdict says why (summary.json `incomplete`)
    assert!(html.contains("NOT RATED: the run stopped early (fixture)."));
    assert!(row(&rows, "assembly preload").contains("| +2.006 % |"));
    assert!(row(&rows, "equivalent bolt stress").contains("| 0.9918 (required ≥ 1) |"));
    assert!(row(&rows, "thread friction").contains("| 0.12 | default |"));
    assert!(html.contains("Rating fit lists no inputs."));
    // applied loads, singular points, events with their meaning, warnings
    assert!(rows.iter().any(|r| r.starts_with(
        "load[0] | pressure | top_plate.top, x in [8.5, 12.5] | F_y | 45 kN | 45 kN | 0 kN |"
    )));
    assert!(row(&rows, "max_von_mises").contains("re-entrant corner (270°)"));
    for ev in s["events"].as_array().unwrap() {
        let name = ev["event"].as_str().unwrap();
        // an event during the preload is named with its phase: `first_opening (preload)`
        let r = rows
            .iter()
            .find(|r| r.starts_with(&format!("{name} ")))
            .unwrap_or_else(|| panic!("no row {name}"));
        assert!(r.contains(&format!("the meaning of {name}")), "{r}");
    }
    let warnings = &html[html.find("id=\"warnings\"").unwrap()..];
    assert!(warnings.contains("2 closed cycles of fewer than 4 increments (fixture)"));
    assert!(warnings.contains("at a singular point, re-entrant corner (270°)"));
    assert!(html.contains("2 warnings qualify these results"));
}

#[test]
fn a_3d_report_draws_the_boundary_and_says_what_an_older_run_lacks() {
    static RUN: OnceLock<PathBuf> = OnceLock::new();
    let dir = run_once("block-3d", &RUN);
    // an older run's summary: written before runs recorded these keys
    let path = dir.join("summary.json");
    let mut s: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    for key in ["case_fingerprint", "applied_loads"] {
        s.as_object_mut().unwrap().remove(key);
    }
    std::fs::write(&path, serde_json::to_string_pretty(&s).unwrap()).unwrap();
    let page = common::scratch("report-block-3d").join("block.html");
    let (code, e, _) = report(&[
        &dir.display().to_string(),
        "--output",
        &page.display().to_string(),
    ]);
    assert_eq!(code, 0, "{e}");
    assert!(
        !dir.join("report.html").exists(),
        "--output puts it elsewhere"
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert_self_contained(&html);
    assert!(html.contains("the undeformed mesh, isometric view"));
    assert!(html.contains("of 238 boundary faces seen from the direction (1, 1, 1)"));
    let rows = rows(&html);
    assert!(row(&rows, "case fingerprint").contains("not recorded"));
    assert!(row(&rows, "model").contains("3D"));
    assert!(html.contains("summary.json has no ratings"));
    assert!(html.contains("summary.json has no applied_loads"));
    assert!(html.contains("pretension.csv is absent"));
    assert!(html.contains("summary.json records no warning for this run."));
    let s = summary(dir);
    let fy = row(&rows, "first yield: Gauss point (mm)");
    let at = ["x_mm", "y_mm", "z_mm"].map(|k| figure(s["first_yield"][k].as_f64().unwrap()));
    assert!(
        fy.contains(&format!("({}, {}, {})", at[0], at[1], at[2])),
        "{fy}"
    );
}

#[test]
fn absent_optional_files_leave_their_part_out_with_a_line() {
    let dir = bolted_copy("report-absent");
    for f in [
        "joints.csv",
        "pretension.csv",
        "cycles.csv",
        "backbone.csv",
        "results.pvd",
    ] {
        std::fs::remove_file(dir.join(f)).unwrap();
    }
    std::fs::remove_dir_all(dir.join("vtu")).unwrap();
    std::fs::remove_dir_all(dir.join("interface")).unwrap();
    let (code, e, _) = report(&[&dir.display().to_string()]);
    assert_eq!(code, 0, "{e}");
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    for line in [
        "joints.csv is absent: no interface forces.",
        "pretension.csv is absent",
        "No mesh picture: no VTU file",
        "The last increment&#39;s interface file (interface/NNNN.csv) is absent.",
        "cycles.csv is absent: no load cycles.",
    ] {
        assert!(html.contains(line), "{line}");
    }
}

/// `report` on `dir` fails with exit code 2, its message names `file`, and
/// neither the report nor a temporary is left.
fn refused(dir: &Path, file: &str, why: &str) {
    let before = listing(dir);
    let (code, e, out) = report(&[&dir.display().to_string()]);
    assert_eq!(code, 2, "{why}: {e}{out}");
    assert!(
        e.starts_with("error: ") && e.trim().lines().count() == 1,
        "{why}: {e}"
    );
    assert!(e.contains(file), "{why}: the message names {file}: {e}");
    assert_eq!(listing(dir), before, "{why}: nothing written");
}

#[test]
fn a_folder_that_is_not_a_finished_output_folder_is_refused_naming_the_file() {
    let empty = common::scratch("report-bad-empty");
    refused(&empty, "summary.json", "no summary.json");

    let dir = bolted_copy("report-bad-json");
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    std::fs::write(dir.join("summary.json"), &text[..text.len() / 2]).unwrap();
    refused(&dir, "summary.json", "truncated JSON");
    std::fs::write(dir.join("summary.json"), "[1, 2]").unwrap();
    refused(&dir, "summary.json", "JSON that is no summary");
    // a member of another type than the program writes: refused, named
    // (before: drawn as a blank, a page that read like a run with less)
    for (path, forged) in [
        ("events", json!({"event": "full_slip"})),
        ("ratings", json!([{"checks": [{"pass": "yes"}]}])),
        ("first_yield", json!(12.5)),
    ] {
        let mut s: Value = serde_json::from_str(&text).unwrap();
        s[path] = forged;
        std::fs::write(dir.join("summary.json"), s.to_string()).unwrap();
        refused(&dir, "summary.json", &format!("{path} of another type"));
        let (_, e, _) = report(&[&dir.display().to_string()]);
        assert!(
            e.contains(path) && e.contains("where the report reads"),
            "{e}"
        );
    }
    let mut s: Value = serde_json::from_str(&text).unwrap();
    s["events"][0]["load_factor"] = json!("0.5");
    std::fs::write(dir.join("summary.json"), s.to_string()).unwrap();
    refused(
        &dir,
        "events[0].load_factor is a string",
        "a string for a number",
    );

    let dir = bolted_copy("report-bad-header");
    let curve = std::fs::read_to_string(dir.join("curve.csv")).unwrap();
    std::fs::write(
        dir.join("curve.csv"),
        curve.replacen("total_load_kn", "load", 1),
    )
    .unwrap();
    refused(&dir, "curve.csv", "a header not ours");

    let dir = bolted_copy("report-bad-field");
    let joints = std::fs::read_to_string(dir.join("joints.csv")).unwrap();
    let broken = joints.replacen("\n1,", "\n1,x,", 1);
    std::fs::write(dir.join("joints.csv"), broken).unwrap();
    refused(&dir, "joints.csv", "a row of another width");

    let dir = bolted_copy("report-bad-pvd");
    let pvd = std::fs::read_to_string(dir.join("results.pvd")).unwrap();
    std::fs::write(
        dir.join("results.pvd"),
        pvd.replace("vtu/0040.vtu", "vtu/../../secret.vtu"),
    )
    .unwrap();
    refused(&dir, "results.pvd", "a VTU name that leaves the folder");

    let dir = bolted_copy("report-bad-vtu");
    std::fs::write(
        dir.join("vtu/0040.vtu"),
        "<VTKFile type=\"UnstructuredGrid\"><Piece NumberOfPoints=\"3\"",
    )
    .unwrap();
    refused(&dir, "0040.vtu", "a VTU that is not ours");

    #[cfg(unix)]
    {
        let dir = bolted_copy("report-bad-link");
        std::fs::remove_file(dir.join("curve.csv")).unwrap();
        std::os::unix::fs::symlink("/etc/hostname", dir.join("curve.csv")).unwrap();
        refused(&dir, "curve.csv", "a link out of the folder");
    }
}

#[test]
fn pdf_without_a_browser_is_refused_before_anything_is_written() {
    let dir = bolted_copy("report-no-browser");
    let before = listing(&dir);
    let empty = common::scratch("report-no-browser-path");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_asperity"))
        .args(["report", "--pdf"])
        .arg(&dir)
        .env("PATH", &empty)
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{e}");
    assert!(
        e.contains("--pdf: no headless Chromium found on PATH (looked for chromium"),
        "{e}"
    );
    assert_eq!(listing(&dir), before);
}

#[test]
fn an_ascii_vtu_draws_the_same_mesh_as_a_binary_one() {
    let text =
        std::fs::read_to_string(common::root().join("cases/punch-plane-stress/case.toml")).unwrap();
    let mut figures = Vec::new();
    for format in ["binary", "ascii"] {
        let case = common::case_dir(
            &format!("report-vtu-{format}-case"),
            &format!("{text}\n[output]\nvtu_format = \"{format}\"\n"),
        );
        let out = common::scratch(&format!("report-vtu-{format}")).join("out");
        let (code, e) = common::run_case(&case, &out, &[]);
        assert_eq!(code, 0, "{e}");
        let (code, e, _) = report(&[&out.display().to_string()]);
        assert_eq!(code, 0, "{e}");
        let html = std::fs::read_to_string(out.join("report.html")).unwrap();
        let mesh = &html[html.find("id=\"mesh\"").unwrap()..html.find("id=\"curves\"").unwrap()];
        figures.push(mesh.to_string());
    }
    assert!(figures[0].contains("<path d=\"M"), "the elements are drawn");
    assert!(
        figures[0].contains("stroke=\"#d62728\""),
        "the interface is drawn"
    );
    assert_eq!(figures[0], figures[1]);
}

/// `--output` never replaces what is not a report: a file of the run's own
/// folder (summary.json), a folder, a named pipe; a missing folder is named
/// as such; with `--pdf` an HTML name ending in .pdf is refused (the PDF
/// would print over it). Each exits 2 and leaves everything as it was.
#[test]
fn the_report_refuses_to_replace_what_is_not_a_report() {
    let dir = bolted();
    let scratch = common::scratch("report-output-targets");
    let fifo = scratch.join("pipe");
    let _ = std::fs::remove_file(&fifo);
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success());
    let summary = std::fs::read(dir.join("summary.json")).unwrap();
    let mut cases = vec![
        (
            dir.join("summary.json"),
            false,
            "is inside the output folder",
        ),
        (scratch.clone(), false, "is not a regular file"),
        (
            scratch.join("missing").join("r.html"),
            false,
            "in a folder that does not exist",
        ),
        (scratch.join("r.pdf"), true, "ends in .pdf"),
    ];
    if made {
        cases.push((fifo.clone(), false, "is not a regular file"));
    }
    for (target, pdf, want) in cases {
        let t = target.display().to_string();
        let mut args = vec![dir.to_str().unwrap(), "--output", &t];
        if pdf {
            args.push("--pdf");
        }
        let (code, e, _) = report(&args);
        if pdf && e.contains("chromium") && !e.contains(".pdf") {
            continue; // no browser here: refused before the target is looked at
        }
        assert_eq!(code, 2, "{t}: {e}");
        assert!(e.contains(want) && e.lines().count() == 1, "{t}: {e}");
    }
    assert_eq!(std::fs::read(dir.join("summary.json")).unwrap(), summary);
    if made {
        assert!(
            std::fs::symlink_metadata(&fifo)
                .unwrap()
                .file_type()
                .is_fifo(),
            "the pipe stays a pipe"
        );
    }
}

/// The shipped fit and slideway (besides the bolt above) write their report
/// as they come, their ratings in it: every check's row holds its symbol,
/// its FE number as the report prints it and the verdict in words; the
/// holding plateau is among the events with its torque.
#[test]
fn the_shipped_fit_and_slideway_reports_show_their_ratings() {
    static FIT: OnceLock<PathBuf> = OnceLock::new();
    static SLIDE: OnceLock<PathBuf> = OnceLock::new();
    for (case, dir) in [
        ("shrink-fit-torque", run_once("shrink-fit-torque", &FIT)),
        ("slideway-damping", run_once("slideway-damping", &SLIDE)),
    ] {
        let target = common::scratch(&format!("report-shipped-{case}")).join("page.html");
        let t = target.display().to_string();
        let (code, e, _) = report(&[&dir.display().to_string(), "--output", &t]);
        assert_eq!(code, 0, "{case}: {e}");
        let html = std::fs::read_to_string(&target).unwrap();
        assert_self_contained(&html);
        let rows = rows(&html);
        let s = summary(dir);
        let rating = &s["ratings"][0];
        for c in rating["checks"].as_array().unwrap() {
            let symbol = c["symbol"].as_str().unwrap();
            let quantity = c["quantity"].as_str().unwrap();
            let r = row(&rows, quantity);
            assert!(r.contains(&format!("| {symbol} |")), "{case}: {r}");
            if let Some(fe) = c["fe"].as_f64() {
                assert!(r.contains(&figure(fe)), "{case}: {r} lacks {}", figure(fe));
            }
            let words = match c["pass"].as_bool() {
                Some(true) => "PASS",
                Some(false) => "FAIL",
                None => "not rated",
            };
            assert!(r.contains(words), "{case}: {r}");
        }
        if case == "shrink-fit-torque" {
            let plateau = rows
                .iter()
                .find(|r| r.starts_with("holding_plateau of torque"))
                .expect("the plateau among the events");
            let t = s["events"]
                .as_array()
                .unwrap()
                .iter()
                .find(|e| e["event"] == "holding_plateau")
                .unwrap()["torque_nm"]
                .as_f64()
                .unwrap();
            assert!(plateau.contains(&format!("{} N·m", figure(t))), "{plateau}");
        }
    }
}

/// A spinning model's events carry their speed (summary.json
/// `events[].speed_rpm`) into the report's events table, in a column `n`
/// only such a run has: cases/hub-in-service slips at 6000 rpm.
#[test]
fn the_events_of_a_spinning_run_show_their_speed() {
    static RUN: OnceLock<PathBuf> = OnceLock::new();
    let out = run_once("hub-in-service", &RUN);
    let page = out.parent().unwrap().join("page.html");
    let (code, e, _) = report(&[out.to_str().unwrap(), "--output", page.to_str().unwrap()]);
    assert_eq!(code, 0, "{e}");
    let html = std::fs::read_to_string(&page).unwrap();
    let rows = rows(&html);
    let head = rows
        .iter()
        .find(|r| r.contains("event | interface or body | "))
        .expect("the events' head");
    assert!(head.contains(" | T | n | "), "{head}");
    let slip = row(&rows, "full_slip");
    assert!(slip.contains("6000 rpm"), "{slip}");
    // a run standing still has no such column
    let (code, e, _) = report(&[
        bolted().to_str().unwrap(),
        "--output",
        out.parent().unwrap().join("b.html").to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{e}");
    let b = std::fs::read_to_string(out.parent().unwrap().join("b.html")).unwrap();
    assert!(
        !b.contains(" rpm<"),
        "a bolt that does not spin shows no speed"
    );
}
