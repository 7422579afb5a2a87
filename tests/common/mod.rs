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
