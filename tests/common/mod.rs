//! Helpers shared by the integration tests.
#![allow(dead_code)]

use asperity::case::Case;
use asperity::model::Model;
use std::path::PathBuf;

/// A fresh, empty scratch folder under the target directory.
pub fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Builds a model from case text.
pub fn model(text: &str) -> Model {
    let case = Case::parse(text, "test.toml").unwrap_or_else(|e| panic!("{e}"));
    Model::build(case).unwrap_or_else(|e| panic!("{e}"))
}

/// Writes a case folder and returns the path of its case.toml.
pub fn case_dir(name: &str, text: &str) -> PathBuf {
    let dir = scratch(name);
    let p = dir.join("case.toml");
    std::fs::write(&p, text).unwrap();
    p
}

/// The project root (for cases/).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Relative difference |a − b| / max(|a|, |b|, tiny).
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-300)
}

/// A restart file without the named sections, as an earlier build wrote it
/// (checksum recomputed); every name must be a section of the file.
pub fn strip_restart_sections(bytes: &[u8], names: &[&str]) -> Vec<u8> {
    let body = &bytes[..bytes.len() - 8];
    let n = u32::from_le_bytes(body[24..28].try_into().unwrap());
    let mut at = 28;
    let mut kept = Vec::new();
    let mut count = 0u32;
    for _ in 0..n {
        let start = at;
        let len = u16::from_le_bytes(body[at..at + 2].try_into().unwrap()) as usize;
        let name = std::str::from_utf8(&body[at + 2..at + 2 + len])
            .unwrap()
            .to_string();
        let kind = body[at + 2 + len];
        let cnt =
            u64::from_le_bytes(body[at + 3 + len..at + 11 + len].try_into().unwrap()) as usize;
        at += 11 + len + cnt * if kind <= 2 { 8 } else { 1 };
        if !names.contains(&name.as_str()) {
            kept.extend_from_slice(&body[start..at]);
            count += 1;
        }
    }
    assert_eq!(at, body.len());
    assert_eq!(
        count as usize + names.len(),
        n as usize,
        "the file had every section of {names:?}"
    );
    let mut out = body[..24].to_vec();
    out.extend_from_slice(&count.to_le_bytes());
    out.extend_from_slice(&kept);
    let sum = asperity::restart::fnv1a(&out);
    out.extend_from_slice(&sum.to_le_bytes());
    out
}
