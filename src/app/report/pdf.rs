//! The report printed to PDF by a headless Chromium (`--print-to-pdf`), when
//! one is installed: found on PATH by its usual names, run with a profile
//! folder of its own (removed after), its background networking off, and a
//! time limit.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The names a Chromium is installed under, in the order they are tried.
const BROWSERS: [&str; 4] = [
    "chromium",
    "chromium-browser",
    "google-chrome",
    "google-chrome-stable",
];
/// The longest a print may take.
const TIME_LIMIT: Duration = Duration::from_secs(180);

/// The first Chromium on PATH, or an error naming what is missing.
pub(super) fn browser() -> Result<PathBuf> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    for name in BROWSERS {
        for dir in std::env::split_paths(&path) {
            let p = dir.join(name);
            if executable(&p) {
                return Ok(p);
            }
        }
    }
    Err(Error::input(
        "--pdf",
        format!(
            "no headless Chromium found on PATH (looked for {}): install one (Debian: apt-get install chromium) or leave out --pdf; the HTML report needs no browser",
            BROWSERS.join(", ")
        ),
    ))
}

/// A regular file with an execute bit.
fn executable(p: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::metadata(p).is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
    }
    #[cfg(not(unix))]
    {
        p.is_file()
    }
}

/// `file://` and the absolute path, each byte that is not unreserved or
/// `/` percent-encoded.
fn file_url(path: &Path) -> String {
    let mut url = String::from("file://");
    for &b in path.as_os_str().as_encoded_bytes() {
        if b.is_ascii_alphanumeric() || b"/-._~".contains(&b) {
            url.push(b as char);
        } else {
            url.push_str(&format!("%{b:02X}"));
        }
    }
    url
}

/// Prints the HTML file `html` to `pdf` with `browser`: into a temporary
/// file beside `pdf`, checked to be a PDF, then renamed.
pub(super) fn print(browser: &Path, html: &Path, pdf: &Path) -> Result<()> {
    let html = std::fs::canonicalize(html).map_err(|e| Error::io(html, e))?;
    let tmp = super::partial(pdf);
    let profile = std::env::temp_dir().join(format!("asperity-chromium-{}", std::process::id()));
    let outcome = run(browser, &html, &tmp, &profile);
    let _ = std::fs::remove_dir_all(&profile);
    let checked = outcome.and_then(|()| {
        let head = std::fs::read(&tmp).map_err(|e| Error::io(&tmp, e))?;
        if !head.starts_with(b"%PDF") {
            return Err(Error::Output(format!(
                "{} printed no PDF",
                browser.display()
            )));
        }
        std::fs::rename(&tmp, pdf).map_err(|e| Error::io(pdf, e))
    });
    if checked.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    checked
}

/// Runs the browser once to print `html` into `out`; its output is kept
/// for the message of a failure.
fn run(browser: &Path, html: &Path, out: &Path, profile: &Path) -> Result<()> {
    let mut child = std::process::Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-extensions",
            "--no-pdf-header-footer",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--print-to-pdf={}", out.display()))
        .arg(file_url(html))
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .map_err(|e| Error::io(browser, e))?;
    let stderr = child.stderr.take();
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        if let Some(mut s) = stderr {
            let _ = std::io::Read::read_to_string(&mut s, &mut text);
        }
        text
    });
    let start = Instant::now();
    let status = loop {
        match child.try_wait().map_err(|e| Error::io(browser, e))? {
            Some(status) => break Some(status),
            None if start.elapsed() > TIME_LIMIT => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            None => std::thread::sleep(Duration::from_millis(50)),
        }
    };
    let log = reader.join().unwrap_or_default();
    match status {
        Some(s) if s.success() => Ok(()),
        Some(s) => Err(Error::Output(format!(
            "{} failed to print the PDF ({s}): {}",
            browser.display(),
            log.lines().rev().take(3).collect::<Vec<_>>().join(" | ")
        ))),
        None => Err(Error::Output(format!(
            "{} did not print the PDF within {} s",
            browser.display(),
            TIME_LIMIT.as_secs()
        ))),
    }
}
