//! ARCHITECTURE.md's code map kept true: its layer table names every
//! top-level module of `src/` once, and no `crate::` path in `src/` runs
//! from a layer to one listed after it (a lower layer never calls up).

use crate::common;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The layer table of ARCHITECTURE.md: each top-level module (`physics`,
/// `error`, …) with its row number, bottom up (the ground floor is row 0).
fn layers() -> BTreeMap<String, usize> {
    let text = std::fs::read_to_string(common::root().join("ARCHITECTURE.md")).unwrap();
    let start = text
        .find("<!-- layers")
        .expect("ARCHITECTURE.md has no `<!-- layers` table");
    let rows: Vec<&str> = text[start..]
        .lines()
        .skip(1)
        .take_while(|l| l.starts_with('|'))
        .skip(2) // the header and its rule
        .collect();
    assert!(rows.len() >= 5, "the layer table has {} rows", rows.len());
    let mut out = BTreeMap::new();
    for (row, line) in rows.iter().enumerate() {
        let cell = line.split('|').nth(2).unwrap_or("");
        for path in cell.split('`').skip(1).step_by(2) {
            let name = path
                .strip_prefix("src/")
                .unwrap_or_else(|| panic!("layer row {row}: `{path}` is not under src/"))
                .trim_end_matches('/')
                .trim_end_matches(".rs")
                .to_string();
            assert!(
                out.insert(name.clone(), row).is_none(),
                "`{name}` is in two rows of the layer table"
            );
        }
    }
    out
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The code of a file without its comments, string literals and test
/// module: what it imports and calls.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or("");
    let mut out = String::new();
    for line in text.lines() {
        let line = line.split("//").next().unwrap_or("");
        // drop string literals (a message may quote a path)
        let mut inside = false;
        for (k, part) in line.split('"').enumerate() {
            if k > 0 {
                inside = !inside;
            }
            if !inside {
                out.push_str(part);
            }
        }
        out.push('\n');
    }
    out
}

#[test]
fn the_layer_table_names_every_top_level_module_once() {
    let layers = layers();
    let src = common::root().join("src");
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&src).unwrap() {
        let p = entry.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        let name = name.trim_end_matches(".rs");
        if name == "lib" || name == "main" {
            continue;
        }
        if !layers.contains_key(name) {
            missing.push(name.to_string());
        }
    }
    assert!(
        missing.is_empty(),
        "src/ holds modules ARCHITECTURE.md's layer table does not name: {missing:?}"
    );
    for name in layers.keys() {
        let (dir, file) = (src.join(name), src.join(format!("{name}.rs")));
        assert!(
            dir.is_dir() || file.is_file(),
            "ARCHITECTURE.md names src/{name}, which does not exist"
        );
    }
}

#[test]
fn no_layer_uses_a_layer_above_it() {
    let layers = layers();
    let src = common::root().join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut up = Vec::new();
    for file in &files {
        let rel = file.strip_prefix(&src).unwrap();
        let top = rel.iter().next().unwrap().to_string_lossy();
        let top = top.trim_end_matches(".rs");
        let name = rel.file_name().unwrap().to_string_lossy();
        if name == "tests.rs" || name.ends_with("_tests.rs") {
            continue;
        }
        let Some(&mine) = layers.get(top) else {
            continue; // lib.rs, main.rs
        };
        let text = std::fs::read_to_string(file).unwrap();
        for (k, line) in code(&text).lines().enumerate() {
            for used in line.split("crate::").skip(1) {
                let target: String = used
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if let Some(&theirs) = layers.get(&target) {
                    if theirs > mine {
                        up.push(format!(
                            "src/{}:{}: {top} uses {target}",
                            rel.display(),
                            k + 1
                        ));
                    }
                }
            }
        }
    }
    assert!(up.is_empty(), "lower layers call up:\n{}", up.join("\n"));
}

/// The checker itself: a path up is found, one down or in a comment or a
/// message is not.
#[test]
fn the_checker_sees_a_path_up_and_nothing_else() {
    let text = "use crate::solve::State;\n// crate::app in a comment\nlet m = \"crate::app\";\n#[cfg(test)]\nuse crate::app::x;\n";
    let c = code(text);
    assert!(c.contains("crate::solve::State"));
    assert!(!c.contains("crate::app"), "{c}");
}
