//! The calculation report in a real browser: a headless Chromium renders it
//! (its DOM holds the title, every table and every inline picture), fetches
//! nothing while it does, and prints it to PDF (`asperity report --pdf`).
//!
//! "Fetches nothing" is read from two signals, each shown to work on a
//! control page in the same run:
//! - Chromium's network log (`--log-net-log`): every request the network
//!   stack starts is a `URL_REQUEST_START_JOB` event whose
//!   `network_isolation_key` names the page's site (`file://` for a local
//!   page); Chromium's own background requests (updates, accounts) carry
//!   other keys. The report must start none; a control page without the
//!   policy, with `<img src="http://127.0.0.1:9/x.png">`, must show that
//!   request.
//! - the console (`--enable-logging=stderr --v=1`): a load the page's
//!   Content-Security-Policy blocks never reaches the network, but is logged
//!   as a violation of a "Content Security Policy directive". The report
//!   must log none; a control page with the report's policy and the same
//!   image must log one.
//!
//! Skipped (with a note) when `chromium` is not on PATH, unless
//! ASPERITY_REQUIRE_CHROMIUM is set (ci/test installs Chromium and sets it).

use crate::common;
use crate::report::{add_verdict, bolted_copy, report};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// `chromium` on PATH; None (after saying so) when absent and not required.
fn chromium() -> Option<PathBuf> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    let found = std::env::split_paths(&path)
        .map(|d| d.join("chromium"))
        .find(|p| p.is_file());
    if found.is_none() {
        assert!(
            std::env::var_os("ASPERITY_REQUIRE_CHROMIUM").is_none(),
            "ASPERITY_REQUIRE_CHROMIUM is set but chromium is not on PATH"
        );
        println!("SKIPPED: chromium is not on PATH (apt-get install chromium)");
        eprintln!("report_browser: SKIPPED: chromium is not on PATH");
    }
    found
}

/// Runs the headless browser on `page` with `args`: (stdout, stderr).
fn browse(chromium: &Path, profile: &Path, args: &[String], page: &Path) -> (String, String) {
    let out = std::process::Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    );
    assert!(out.status.success(), "chromium failed: {stderr}");
    (stdout, stderr)
}

/// The bolted joint's report (with the fixture's ratings) in `scratch`.
fn page(scratch: &str) -> PathBuf {
    let dir = bolted_copy(scratch);
    add_verdict(&dir);
    let (code, e, _) = report(&[&dir.display().to_string()]);
    assert_eq!(code, 0, "{e}");
    std::fs::canonicalize(dir.join("report.html")).unwrap()
}

#[test]
fn a_headless_chromium_renders_the_report() {
    let Some(chromium) = chromium() else { return };
    let page = page("report-browser-dom");
    let html = std::fs::read_to_string(&page).unwrap();
    let profile = common::scratch("report-browser-dom-profile");
    let (dom, _) = browse(&chromium, &profile, &["--dump-dom".into()], &page);
    assert!(
        dom.contains("<title>Calculation report: bolted-joint</title>"),
        "{}",
        &dom[..dom.len().min(500)]
    );
    let count = |text: &str, tag: &str| text.matches(tag).count();
    for tag in [
        "<table",
        "<svg",
        "<h2",
        "<figure",
        "<td class=\"pass\">PASS</td>",
        "<td class=\"fail\">FAIL</td>",
    ] {
        assert!(count(&html, tag) > 0, "{tag}");
        assert_eq!(
            count(&dom, tag),
            count(&html, tag),
            "{tag}: the DOM holds as many as the file"
        );
    }
    for caption in [
        "Rating bolt: checks (VDI 2230-1:2015)",
        "Rating fit: checks (DIN 7190-1:2017)",
        "Applied loads (summary.json applied_loads)",
        "Events located (summary.json events)",
    ] {
        assert!(dom.contains(caption), "{caption}");
    }
    // the page was read to its end
    assert!(dom.contains("interface between: 2 closed cycles of fewer than 4 increments (fixture)"));
}

/// The URLs of the requests the network log shows the page (a `file://`
/// site) starting.
fn page_requests(net_log: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(net_log).unwrap();
    let log: Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", net_log.display()));
    let start = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"]
        .as_u64()
        .expect("the net log names URL_REQUEST_START_JOB");
    let events = log["events"].as_array().expect("the net log's events");
    events
        .iter()
        .filter(|e| e["type"].as_u64() == Some(start))
        .filter(|e| {
            e["params"]["network_isolation_key"]
                .as_str()
                .is_some_and(|k| k.starts_with("file://"))
        })
        .map(|e| e["params"]["url"].as_str().unwrap_or("").to_string())
        .collect()
}

/// The console's Content-Security-Policy violations.
fn blocked(stderr: &str) -> Vec<&str> {
    stderr
        .lines()
        .filter(|l| l.contains("Content Security Policy directive"))
        .collect()
}

#[test]
fn the_report_fetches_nothing_in_a_browser() {
    let Some(chromium) = chromium() else { return };
    let page = page("report-browser-net");
    let dir = page.parent().unwrap().to_path_buf();
    let policy = "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'; img-src data:\">";
    let image = "<img src=\"http://127.0.0.1:9/x.png\" alt=\"\">";
    let guarded = dir.join("control-guarded.html");
    let open = dir.join("control-open.html");
    std::fs::write(
        &guarded,
        format!("<!DOCTYPE html><html><head>{policy}</head><body>{image}</body></html>"),
    )
    .unwrap();
    std::fs::write(
        &open,
        format!("<!DOCTYPE html><html><head></head><body>{image}</body></html>"),
    )
    .unwrap();
    let run = |p: &Path, name: &str| {
        let log = dir.join(format!("{name}.netlog.json"));
        let profile = common::scratch(&format!("report-browser-net-{name}"));
        let args = [
            "--enable-logging=stderr".to_string(),
            "--v=1".to_string(),
            format!("--log-net-log={}", log.display()),
            "--dump-dom".to_string(),
        ];
        let (_, stderr) = browse(&chromium, &profile, &args, p);
        (page_requests(&log), stderr)
    };
    // the controls: each signal sees what it must
    let (requests, _) = run(&open, "open");
    assert!(
        requests.iter().any(|u| u == "http://127.0.0.1:9/x.png"),
        "the net log shows a page's request: {requests:?}"
    );
    let (requests, stderr) = run(&guarded, "guarded");
    assert!(requests.is_empty(), "{requests:?}");
    assert!(
        !blocked(&stderr).is_empty(),
        "the console shows a blocked load"
    );
    // the report: no request started, none blocked
    let (requests, stderr) = run(&page, "report");
    assert!(requests.is_empty(), "the report requested {requests:?}");
    assert!(
        blocked(&stderr).is_empty(),
        "the report tried to load: {:?}",
        blocked(&stderr)
    );
}

#[test]
fn pdf_prints_the_report_with_a_headless_chromium() {
    if chromium().is_none() {
        return;
    }
    let dir = bolted_copy("report-browser-pdf");
    add_verdict(&dir);
    let html = common::scratch("report-browser-pdf-out").join("joint report.html");
    let (code, e, out) = report(&[
        &dir.display().to_string(),
        "--pdf",
        "--output",
        &html.display().to_string(),
    ]);
    assert_eq!(code, 0, "{e}");
    let pdf = html.with_extension("pdf");
    assert_eq!(
        out.lines().collect::<Vec<_>>(),
        [html.display().to_string(), pdf.display().to_string()]
    );
    let bytes = std::fs::read(&pdf).unwrap();
    assert!(
        bytes.starts_with(b"%PDF"),
        "{:?}",
        &bytes[..bytes.len().min(16)]
    );
    assert!(bytes.len() > 10_000, "{} bytes", bytes.len());
    let names: Vec<String> = std::fs::read_dir(html.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "no temporary left: {names:?}");
}
