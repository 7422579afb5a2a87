//! Every source path the documentation names exists: README.md, docs/*.md,
//! cases/*/README.md and ARCHITECTURE.md (when there is one). A path is any
//! `src/…` in the text, code spans and code blocks included, wherever it
//! stands: in a link (`../src/x.rs`), in code, in a sentence. Trailing
//! punctuation, a `:line` suffix and a `#anchor` are stripped; `{a,b}` names
//! several (`src/model/interface/{table,normal}.rs`); a path ending in `/` must be a
//! folder, any other a file or a folder. Inside a fenced code block a line
//! that starts with a `src/` path is an entry of a code map: the bare file
//! and folder names of its description (`mod.rs`, `newton/step.rs`,
//! `serial/`), on its line and on the indented lines that continue it, are
//! resolved against the entry's folder. A path in a URL (`…/blob/main/src/…`)
//! or under another folder (`fuzz/src/…`) is not one of ours and is skipped.
//! The paths are read from the documents every run, so a file that moves
//! makes this test name the documents that still point at its old place.

use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The documents whose paths are checked, in a fixed order.
fn documents(root: &Path) -> Vec<PathBuf> {
    let mut files = vec![root.join("README.md")];
    let architecture = root.join("ARCHITECTURE.md");
    if architecture.is_file() {
        files.push(architecture);
    }
    let sorted = |dir: PathBuf| {
        let mut found: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .collect();
        found.sort();
        found
    };
    files.extend(
        sorted(root.join("docs"))
            .into_iter()
            .filter(|p| p.extension().is_some_and(|x| x == "md")),
    );
    files.extend(
        sorted(root.join("cases"))
            .into_iter()
            .map(|p| p.join("README.md"))
            .filter(|p| p.is_file()),
    );
    files
}

/// A character that can continue a path.
fn path_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '/' | ':' | '#' | '{' | '}' | ',')
}

/// The raw `src/…` tokens of one line, before cleaning.
fn src_tokens(line: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut from = 0;
    while let Some(at) = line[from..].find("src/") {
        let start = from + at;
        from = start + 4;
        let before = &line[..start];
        let prev = before.chars().next_back();
        let ours = match prev {
            None => true,
            // ../src/x.rs or ./src/x.rs: relative to a document, still ours
            Some('/') => {
                let dirs = before.trim_end_matches(['.', '/']);
                let rel = &before[dirs.len()..];
                !rel.is_empty()
                    && rel
                        .split('/')
                        .all(|p| p.is_empty() || p == "." || p == "..")
                    && !dirs.ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-')
            }
            Some(c) => !(c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.')),
        };
        if !ours {
            continue;
        }
        let mut end = start;
        let mut depth = 0usize;
        for (i, c) in line[start..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth > 0 => depth -= 1,
                ',' if depth == 0 => break,
                c if !path_char(c) => break,
                _ => {}
            }
            end = start + i + c.len_utf8();
        }
        // `src/…`, `src/<name>.rs`, `src/*.rs`: a placeholder, not a path
        if matches!(line[end..].chars().next(), Some('…' | '<' | '*')) {
            continue;
        }
        found.push(line[start..end].to_string());
    }
    found
}

/// A raw token made a path (or several, for `{a,b}`): `#anchor` and `:line`
/// cut, trailing punctuation stripped. None for a placeholder.
fn clean(token: &str) -> Vec<String> {
    let mut t = token;
    if let Some(i) = t.find('#') {
        t = &t[..i];
    }
    if let Some(i) = t.find(':') {
        t = &t[..i];
    }
    let t = t.trim_end_matches(['.', ',', ';', ':', '!', '?', '-']);
    if t.contains("..") {
        // `src/…/x` written with dots: a placeholder, not a path
        return Vec::new();
    }
    match (t.find('{'), t.find('}')) {
        (Some(open), Some(close)) if open < close => t[open + 1..close]
            .split(',')
            .map(|alt| format!("{}{}{}", &t[..open], alt.trim(), &t[close + 1..]))
            .collect(),
        (None, None) => vec![t.to_string()],
        _ => Vec::new(),
    }
}

/// The bare file and folder names of a code map entry's description:
/// `name.rs`, `dir/name.rs`, `dir/`, stripped of brackets and punctuation.
fn bare_names(description: &str) -> Vec<String> {
    description
        .split_whitespace()
        .map(|w| w.trim_matches(|c: char| matches!(c, '(' | ')' | ',' | ';' | ':' | '.' | '`')))
        .filter(|w| {
            !w.is_empty()
                && !w.starts_with("src/")
                && w.chars().all(|c| {
                    c.is_ascii_lowercase() || c.is_ascii_digit() || matches!(c, '_' | '/' | '.')
                })
                && !w.starts_with('/')
                && (w.ends_with(".rs") || (w.ends_with('/') && w.len() > 1))
        })
        .map(str::to_string)
        .collect()
}

/// Every path a document names, with its 1-based line: `src/…` anywhere, and
/// the bare names of code map entries resolved against the entry's folder.
fn named_paths(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let mut fenced = false;
    // the folder of the code map entry that the current line may continue
    let mut entry: Option<String> = None;
    for (n, raw) in text.lines().enumerate() {
        let trimmed = raw.trim_start();
        if trimmed.starts_with("```") || trimmed.starts_with("~~~") {
            fenced = !fenced;
            entry = None;
            continue;
        }
        for token in src_tokens(raw) {
            for path in clean(&token) {
                found.push((n + 1, path));
            }
        }
        if !fenced {
            continue;
        }
        let description = if raw.starts_with("src/") {
            let first = raw.split_whitespace().next().unwrap_or("");
            let first = first.trim_end_matches(',');
            let folder = match first.rfind('/') {
                Some(i) => &first[..=i],
                None => "src/",
            };
            entry = Some(folder.to_string());
            // the rest of the line after the entry's own paths
            raw.split_whitespace()
                .skip_while(|w| w.starts_with("src/"))
                .collect::<Vec<_>>()
                .join(" ")
        } else if raw.starts_with(char::is_whitespace) && !trimmed.is_empty() {
            raw.to_string()
        } else {
            entry = None;
            continue;
        };
        let Some(folder) = &entry else {
            continue;
        };
        for name in bare_names(&description) {
            found.push((n + 1, format!("{folder}{name}")));
        }
    }
    found
}

/// Whether a named path exists: a folder for `x/`, a file or folder else.
fn exists(root: &Path, path: &str) -> bool {
    let p = root.join(path.trim_end_matches('/'));
    if path.ends_with('/') {
        p.is_dir()
    } else {
        p.exists()
    }
}

/// A hint for a missing path: the module's other form where it exists.
fn hint(root: &Path, path: &str) -> String {
    let other = path
        .strip_suffix(".rs")
        .map(|stem| format!("{stem}/mod.rs"))
        .or_else(|| path.strip_suffix('/').map(|dir| format!("{dir}.rs")));
    match other {
        Some(o) if exists(root, &o) => format!(" (there is {o})"),
        _ => String::new(),
    }
}

/// The missing paths of one document: "doc:line: path".
fn missing_paths(root: &Path, doc: &Path, text: &str) -> Vec<String> {
    let shown = doc.strip_prefix(root).unwrap_or(doc);
    named_paths(text)
        .into_iter()
        .filter(|(_, path)| !exists(root, path))
        .map(|(line, path)| {
            let hint = hint(root, &path);
            format!("{}:{line}: {path}{hint}", shown.display())
        })
        .collect()
}

#[test]
fn every_src_path_named_in_the_documentation_exists() {
    let root = root();
    let docs = documents(root);
    assert!(
        docs.len() > 5 && docs.iter().any(|f| f.ends_with("docs/theory.md")),
        "documentation files not found: {docs:?}"
    );
    let mut missing = Vec::new();
    let mut checked = 0;
    for doc in &docs {
        let text = std::fs::read_to_string(doc).unwrap();
        checked += named_paths(&text).len();
        missing.extend(missing_paths(root, doc, &text));
    }
    assert!(
        checked > 50,
        "only {checked} src paths found: is the parser broken?"
    );
    assert!(
        missing.is_empty(),
        "{} src path(s) named in the documentation do not exist:\n{}",
        missing.len(),
        missing.join("\n")
    );
}

#[test]
fn the_parser_finds_src_paths_and_skips_what_is_not_one() {
    let text = "\
See `src/solve/newton/step.rs:120` and [the code](../src/model/constraint.rs#L3), src/lib.rs.
Unit tests (`src/physics/contact/{table,normal}.rs`); touch src/lib.rs; `src/physics/material/`.
Not ours: https://github.com/o/r/blob/main/src/x.rs, fuzz/src/y.rs, mysrc/z.rs, `src/…/x.rs`.
```
src/solve/       the loop (mod.rs: phases; newton/step.rs), settings (settings.rs)
                 automatic steps (stepping.rs); Cholesky (serial/), restart.bin
src/app/driver.rs    one run (parallel.rs makes PETSc's)
cases/           case files (mod.rs is not a code map entry here)
```
";
    let found = named_paths(text);
    let paths: Vec<&str> = found.iter().map(|(_, p)| p.as_str()).collect();
    assert_eq!(
        paths,
        [
            "src/solve/newton/step.rs",
            "src/model/constraint.rs",
            "src/lib.rs",
            "src/physics/contact/table.rs",
            "src/physics/contact/normal.rs",
            "src/lib.rs",
            "src/physics/material/",
            "src/solve/",
            "src/solve/mod.rs",
            "src/solve/newton/step.rs",
            "src/solve/settings.rs",
            "src/solve/stepping.rs",
            "src/solve/serial/",
            "src/app/driver.rs",
            "src/app/parallel.rs",
        ]
    );
    let lines: Vec<usize> = found.iter().map(|(l, _)| *l).collect();
    assert_eq!(lines, [1, 1, 1, 2, 2, 2, 2, 5, 5, 5, 5, 6, 6, 7, 7]);
}

/// A folder of its own with a small source tree, for the tests of the
/// checker (the real tree moves).
fn fixture(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("asperity-doc-paths-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("src/solve/newton")).unwrap();
    for f in ["src/lib.rs", "src/solve/mod.rs", "src/solve/newton/step.rs"] {
        std::fs::write(dir.join(f), "").unwrap();
    }
    dir
}

#[test]
fn a_missing_path_is_reported_with_its_document_line_and_path() {
    let root = fixture("missing");
    let text = "\
Fine: `src/lib.rs`, `src/solve/`, `src/solve/newton/step.rs:10`, ../src/solve/mod.rs#L2.
Gone: `src/no_such_module.rs` and src/lib.rs/ (a file named as a folder).
```
src/solve/       its settings (no_such_file.rs), the step (newton/step.rs)
```
";
    let missing = missing_paths(&root, &root.join("docs/example.md"), text);
    assert_eq!(
        missing,
        [
            "docs/example.md:2: src/no_such_module.rs",
            "docs/example.md:2: src/lib.rs/",
            "docs/example.md:4: src/solve/no_such_file.rs",
        ]
    );
    // a module named in its other form gets a hint
    assert_eq!(
        missing_paths(&root, &root.join("README.md"), "`src/solve.rs`, `src/lib/`"),
        [
            "README.md:1: src/solve.rs (there is src/solve/mod.rs)",
            "README.md:1: src/lib/ (there is src/lib.rs)",
        ]
    );
    std::fs::remove_dir_all(&root).unwrap();
}

/// docs/performance.md holds the current figures only, at most 40 KB; the
/// dated measurements and their history live in docs/performance-log.md.
#[test]
fn performance_md_is_at_most_40_kb_and_links_its_log() {
    let root = root();
    let n = std::fs::metadata(root.join("docs/performance.md"))
        .unwrap()
        .len();
    assert!(
        n <= 40 * 1024,
        "docs/performance.md is {n} bytes, more than 40 KB"
    );
    let text = std::fs::read_to_string(root.join("docs/performance.md")).unwrap();
    assert!(
        text.contains("(performance-log.md"),
        "docs/performance.md does not link docs/performance-log.md"
    );
}
