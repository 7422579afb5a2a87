//! `asperity report OUT`: the calculation report of a finished output
//! folder, one self-contained HTML file a designer can hand on (and a PDF
//! of it, printed by a headless Chromium, on request).
//!
//! The entry point is [`report`]. The folder is untrusted input
//! (`read`): a file that is absent leaves its part of the report out with
//! a line saying so; one that is there but is not what the program writes
//! (malformed JSON, a CSV with another header, a VTU that is not ours, a
//! `results.pvd` naming a file outside `vtu/`) is an input error naming it,
//! and nothing is written. The page (`html`) holds everything inline, its
//! pictures as SVG (the mesh: `mesh`, from `vtu`; the charts: the
//! crate's [`crate::files::plot`]), under a policy that lets it fetch
//! nothing; it is written to a temporary file beside its place and renamed.
//!
//! The sections, in order: the model and the run (`overview`), the mesh,
//! the key curves and the interfaces (`curves`), the ratings and the
//! results beside them (`ratings`, `results`), the warnings
//! (`warnings`). Numbers: `format`.

mod csv;
mod curves;
mod format;
mod html;
mod mesh;
mod overview;
mod pdf;
mod ratings;
mod read;
mod results;
mod shape;
mod vtu;
mod warnings;

pub use format::figure;

use crate::error::{Error, Result};
use serde_json::Value;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// What `asperity report` was asked for.
pub struct Request {
    /// The output folder of a finished run.
    pub dir: PathBuf,
    /// Where the HTML goes (default `dir/report.html`).
    pub output: Option<PathBuf>,
    /// Also print a PDF (beside the HTML, `.pdf`).
    pub pdf: bool,
}

/// Writes the report; returns the files written (the HTML, then the PDF).
/// With `pdf`, a missing browser is refused before anything is read.
pub fn report(r: &Request) -> Result<Vec<PathBuf>> {
    let browser = if r.pdf { Some(pdf::browser()?) } else { None };
    let folder = read::folder(&r.dir)?;
    let html = page(&folder)?;
    let target = r
        .output
        .clone()
        .unwrap_or_else(|| r.dir.join("report.html"));
    check_target(&target, &r.dir, r.pdf)?;
    write_atomic(&target, html.as_bytes())?;
    let mut written = vec![target.clone()];
    if let Some(b) = browser {
        let pdf = target.with_extension("pdf");
        pdf::print(&b, &target, &pdf)?;
        written.push(pdf);
    }
    Ok(written)
}

/// The whole page of a folder, in memory.
fn page(f: &read::Folder) -> Result<String> {
    let s = &f.summary;
    let warnings = warnings::collect(s);
    let charts = curves::Charts {
        font: crate::files::plot::load_font(),
    };
    let mut page = html::Page::default();
    overview::section(&mut page, s);
    mesh::section(&mut page, f);
    curves::key_curves(&mut page, f, &charts)?;
    curves::interfaces(&mut page, f, &charts)?;
    page.section("ratings", "Ratings and results");
    ratings::ratings(&mut page, s);
    ratings::applied_loads(&mut page, s);
    ratings::singular(&mut page, s);
    results::state(&mut page, s);
    results::reactions(&mut page, s);
    results::peaks(&mut page, s);
    results::pretension(&mut page, s);
    results::events(&mut page, s);
    warnings::section(&mut page, &warnings);
    let folder = f
        .dir
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    let lead = format!(
        "{}<p>From the output folder <code>{}</code>, by <code>asperity report</code>.</p>",
        overview::lead(s, warnings.len()),
        html::esc(&folder)
    );
    Ok(page.finish(&overview::title(s), &lead))
}

/// Where the report may go: a new file or an existing regular file (or a
/// link to one is replaced, never followed) in a folder that exists; inside
/// the output folder only `report.html` (the run's own files stay as they
/// are); with `--pdf` not a name the PDF would overwrite (`.pdf`).
fn check_target(target: &Path, dir: &Path, pdf: bool) -> Result<()> {
    let refuse = |m: &str| Err(Error::input(format!("--output {}", target.display()), m));
    if let Ok(meta) = std::fs::symlink_metadata(target) {
        if !meta.is_file() && !meta.file_type().is_symlink() {
            return refuse("exists and is not a regular file (a folder, a device, a pipe): name a new file or a report of your own");
        }
    }
    let parent = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if !parent.is_dir() {
        return refuse("is in a folder that does not exist: make the folder first");
    }
    let same_folder = parent.canonicalize().ok() == dir.canonicalize().ok();
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    if same_folder && name != "report.html" {
        return refuse("is inside the output folder: the run's files there are not the report's to replace; name report.html or a file elsewhere");
    }
    if pdf
        && target
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("pdf"))
    {
        return refuse(
            "ends in .pdf, where --pdf prints the PDF beside the HTML: give the HTML an .html name",
        );
    }
    Ok(())
}

/// The temporary name beside `target`: `.NAME.partial-PID`.
fn partial(target: &Path) -> PathBuf {
    let name = target
        .file_name()
        .map_or("report".into(), |n| n.to_string_lossy().into_owned());
    target.with_file_name(format!(".{name}.partial-{}", std::process::id()))
}

/// Writes `bytes` to `target` whole or not at all: a new temporary file in
/// the same folder (never an existing file or link), synced, renamed over.
fn write_atomic(target: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = partial(target);
    let _ = std::fs::remove_file(&tmp);
    let written = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .and_then(|mut f| {
            f.write_all(bytes)?;
            f.sync_all()
        })
        .map_err(|e| Error::io(&tmp, e))
        .and_then(|()| std::fs::rename(&tmp, target).map_err(|e| Error::io(target, e)));
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

/// A number of `v`'s key (JSON numbers only).
fn num(v: &Value, key: &str) -> Option<f64> {
    v.get(key).and_then(Value::as_f64)
}

/// A text of `v`'s key (strings; a number as the report prints it).
fn text(v: &Value, key: &str) -> Option<String> {
    match v.get(key)? {
        Value::String(s) => Some(s.clone()),
        Value::Number(n) => n.as_f64().map(figure),
        Value::Bool(b) => Some(b.to_string()),
        _ => None,
    }
}
