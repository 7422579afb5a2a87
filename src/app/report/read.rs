//! The finished output folder, read as untrusted input: `summary.json`
//! (required), the CSV files the report draws (each optional, its header
//! checked), the last increment's interface file and the last VTU file
//! (named by `results.pvd`, each name of which must be one the writer
//! gives: `vtu/NNNN.vtu`). Every file is opened inside the folder, no link
//! followed, its size bounded ([`crate::files::inside`]).

use super::csv::Table;
use super::vtu::{self, Grid};
use crate::error::{Error, Result};
use crate::files::inside::{read_inside, Folder as Rules};
use crate::files::output::{self, damping, joints_csv};
use crate::files::restart::{interface_name, vtu_increment};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Most bytes of `summary.json`.
const SUMMARY_BYTES: u64 = 64 << 20;
/// Most bytes of a CSV file or `results.pvd`.
const CSV_BYTES: u64 = 512 << 20;
/// Most bytes of the VTU file drawn (a larger one is not drawn).
pub(super) const VTU_BYTES: u64 = 1 << 30;

const RULES: Rules = Rules {
    kind: "output folder",
    bound: "a report reads",
};

/// What the report shows of a folder: each optional part `None` when its
/// file is absent.
pub(super) struct Folder {
    pub dir: PathBuf,
    pub summary: Value,
    pub curve: Option<Table>,
    pub joints: Option<Table>,
    pub pretension: Option<Table>,
    pub cycles: Option<Table>,
    pub backbone: Option<Table>,
    /// The last increment's `interface/NNNN.csv`, with its name.
    pub interface: Option<(String, Table)>,
    /// The mesh of the last VTU file, with its name; or why there is none.
    pub mesh: std::result::Result<(String, Grid), String>,
}

/// Reads the folder `dir`.
pub(super) fn folder(dir: &Path) -> Result<Folder> {
    let summary = summary(dir)?;
    let table = |rel: &str, header: &str| -> Result<Option<Table>> {
        let Some(bytes) = file(dir, rel, CSV_BYTES)? else {
            return Ok(None);
        };
        let place = dir.join(rel).display().to_string();
        let text =
            std::str::from_utf8(&bytes).map_err(|_| Error::input(&place, "not UTF-8 text"))?;
        Table::parse(&place, text, header).map(Some)
    };
    let last = summary
        .get("increments")
        .and_then(Value::as_u64)
        .filter(|&k| k > 0);
    let interface = match last {
        Some(k) => {
            let rel = interface_name(k as usize);
            table(&rel, output::INTERFACE_HEADER)?.map(|t| (rel, t))
        }
        None => None,
    };
    Ok(Folder {
        curve: table("curve.csv", output::CURVE_HEADER)?,
        joints: table("joints.csv", joints_csv::JOINTS_HEADER)?,
        pretension: table("pretension.csv", "increment,load_factor")?,
        cycles: table("cycles.csv", joints_csv::CYCLES_HEADER)?,
        backbone: table("backbone.csv", damping::BACKBONE_HEADER)?,
        interface,
        mesh: mesh(dir)?,
        summary,
        dir: dir.to_path_buf(),
    })
}

/// `summary.json`: a JSON object with the case's name, or the folder is not
/// an output folder.
fn summary(dir: &Path) -> Result<Value> {
    let place = dir.join("summary.json").display().to_string();
    let bytes = file(dir, "summary.json", SUMMARY_BYTES)?.ok_or_else(|| {
        Error::input(
            &place,
            "absent: not the output folder of a run (asperity run CASE --out DIR writes it)",
        )
    })?;
    let v: Value = serde_json::from_slice(&bytes)
        .map_err(|e| Error::input(&place, format!("not valid JSON: {e}")))?;
    if !v.get("case").is_some_and(Value::is_string) {
        return Err(Error::input(
            &place,
            "not the summary of a run: no \"case\" name in a JSON object",
        ));
    }
    super::shape::check(&v, &place)?;
    Ok(v)
}

/// The bytes of `rel` in `dir`, at most `limit`; `None` when it is absent.
fn file(dir: &Path, rel: &str, limit: u64) -> Result<Option<Vec<u8>>> {
    match std::fs::symlink_metadata(dir.join(rel)) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        _ => {}
    }
    read_inside(dir, rel, rel, &RULES, limit)
        .map(Some)
        .map_err(|m| Error::input(dir.display().to_string(), m))
}

/// The last VTU file's mesh: the last entry of `results.pvd`, else the
/// highest-numbered `vtu/NNNN.vtu`. `Err` says why there is none to draw;
/// a file that is there but is not ours is an error.
fn mesh(dir: &Path) -> Result<std::result::Result<(String, Grid), String>> {
    let Some(rel) = last_vtu(dir)? else {
        return Ok(Err(
            "no VTU file: results.pvd and vtu/ are absent or list none".into(),
        ));
    };
    let size = std::fs::symlink_metadata(dir.join(&rel)).map(|m| m.len());
    match size {
        Err(_) => return Ok(Err(format!("{rel} is absent"))),
        Ok(n) if n > VTU_BYTES => {
            return Ok(Err(format!(
                "{rel} has {n} bytes, more than the {VTU_BYTES} a report draws"
            )))
        }
        Ok(_) => {}
    }
    let bytes = file(dir, &rel, VTU_BYTES)?.unwrap_or_default();
    let grid = vtu::parse(&dir.join(&rel).display().to_string(), &bytes)?;
    Ok(Ok((rel, grid)))
}

/// The name of the last VTU file: `results.pvd`'s last entry (every entry
/// must be a name the writer gives), else the highest `vtu/NNNN.vtu`.
fn last_vtu(dir: &Path) -> Result<Option<String>> {
    if let Some(bytes) = file(dir, "results.pvd", CSV_BYTES)? {
        let place = dir.join("results.pvd").display().to_string();
        let text = String::from_utf8_lossy(&bytes);
        let mut last = None;
        for tag in text.split("<DataSet").skip(1) {
            let name = tag
                .split_once("file=\"")
                .and_then(|(_, r)| r.split_once('"'))
                .map(|(name, _)| name)
                .ok_or_else(|| Error::input(&place, "a <DataSet> without a file"))?;
            if vtu_increment(name).is_none() {
                return Err(Error::input(
                    &place,
                    format!(
                        "lists \"{name}\", which is not a file of vtu/ as this program names them (vtu/NNNN.vtu)"
                    ),
                ));
            }
            last = Some(name.to_string());
        }
        return Ok(last);
    }
    let listed = match std::fs::symlink_metadata(dir.join("vtu")) {
        Ok(m) if m.is_dir() => {
            std::fs::read_dir(dir.join("vtu")).map_err(|e| Error::io(dir.join("vtu"), e))?
        }
        _ => return Ok(None),
    };
    let best = listed
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .map(|n| format!("vtu/{n}"))
        .filter_map(|n| vtu_increment(&n).map(|k| (k, n)))
        .max();
    Ok(best.map(|b| b.1))
}
