//! Helpers shared by the benchmarks (a module of each bench, not a target).
#![allow(dead_code)] // each bench uses a part

use std::path::PathBuf;

/// The shipped cases.
pub fn cases_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases")
}

/// The `[interface.contact.tangential]` table of `text`, up to the next blank line.
pub fn tangential_block(text: &str) -> String {
    let mut out = String::new();
    let mut inside = false;
    for line in text.lines() {
        if line.trim_start().starts_with('[') {
            inside = line.trim() == "[interface.contact.tangential]";
        } else if line.trim().is_empty() {
            inside = false;
        }
        if inside {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// `text` without its `[interface.contact.tangential]` table.
pub fn without_tangential(text: &str) -> String {
    let block = tangential_block(text);
    assert!(!block.is_empty(), "no tangential law to remove");
    let out = text.replacen(&block, "", 1);
    assert!(!out.contains("tangential]"), "tangential law not removed");
    out
}

/// The median (the mean of the middle two for an even count).
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}
