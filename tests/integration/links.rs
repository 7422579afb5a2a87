//! Every relative link in the documentation resolves: README.md, docs/*.md and
//! cases/*/README.md. Markdown links `[text](target)`, reference definitions
//! `[label]: target` and HTML `src="…"` / `href="…"` attributes are checked;
//! web and mail links and pure `#anchor` links are skipped, a `#fragment` is
//! stripped, and the target is resolved against the folder of the file that
//! links to it. Links inside fenced code blocks and inline code are not links.

use std::path::{Path, PathBuf};

/// The markdown files whose links are checked.
fn documentation_files(root: &Path) -> Vec<PathBuf> {
    let mut files = vec![root.join("README.md")];
    let mut in_dir = |dir: PathBuf, only: Option<&str>| {
        let mut found: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .collect();
        found.sort();
        for p in found {
            match only {
                Some(name) if p.is_dir() => {
                    let readme = p.join(name);
                    if readme.is_file() {
                        files.push(readme);
                    }
                }
                None if p.extension().is_some_and(|x| x == "md") => files.push(p),
                _ => {}
            }
        }
    };
    in_dir(root.join("docs"), None);
    in_dir(root.join("cases"), Some("README.md"));
    files
}

/// Removes inline code spans (`…`, ``…``) from one line.
fn without_code_spans(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(start) = rest.find('`') {
        out.push_str(&rest[..start]);
        let ticks = rest[start..].chars().take_while(|&c| c == '`').count();
        let fence = "`".repeat(ticks);
        let after = &rest[start + ticks..];
        match after.find(&fence) {
            Some(end) => rest = &after[end + ticks..],
            None => {
                // an unmatched backtick is literal text
                out.push_str(&rest[start..start + ticks]);
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// The target of a markdown link starting right after `](`: up to the
/// matching `)`, without an optional title; `<…>` for targets with spaces.
fn link_target(s: &str) -> Option<String> {
    let s = s.trim_start();
    if let Some(inner) = s.strip_prefix('<') {
        return inner.find('>').map(|end| inner[..end].to_string());
    }
    let mut depth = 0usize;
    for (i, c) in s.char_indices() {
        match c {
            '(' => depth += 1,
            ')' if depth == 0 => {
                let target = s[..i].split_whitespace().next().unwrap_or("");
                return Some(target.to_string());
            }
            ')' => depth -= 1,
            _ => {}
        }
    }
    None
}

/// Every link target in a markdown text, with its 1-based line number.
fn links(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let mut fenced = false;
    for (n, raw) in text.lines().enumerate() {
        let trimmed = raw.trim_start();
        if trimmed.starts_with("```") || trimmed.starts_with("~~~") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let line = without_code_spans(raw);
        let mut rest = line.as_str();
        while let Some(at) = rest.find("](") {
            rest = &rest[at + 2..];
            if let Some(t) = link_target(rest).filter(|t| !t.is_empty()) {
                found.push((n + 1, t));
            }
        }
        for attr in ["src=", "href="] {
            let mut rest = line.as_str();
            while let Some(at) = rest.find(attr) {
                rest = &rest[at + attr.len()..];
                let Some(quote) = rest.chars().next().filter(|c| *c == '"' || *c == '\'') else {
                    continue;
                };
                if let Some(end) = rest[1..].find(quote) {
                    found.push((n + 1, rest[1..1 + end].to_string()));
                }
            }
        }
        // reference definition: [label]: target
        let t = line.trim_start();
        if t.starts_with('[') && !t.starts_with("[^") {
            if let Some(end) = t.find("]:") {
                if let Some(target) = t[end + 2..].split_whitespace().next() {
                    found.push((n + 1, target.trim_matches(['<', '>']).to_string()));
                }
            }
        }
    }
    found
}

/// A target to check on disk, or None for web, mail and same-page links.
fn local_path(target: &str) -> Option<String> {
    let lower = target.to_ascii_lowercase();
    let external = ["http://", "https://", "mailto:", "ftp://", "tel:", "data:"];
    if target.is_empty() || target.starts_with('#') || external.iter().any(|p| lower.starts_with(p))
    {
        return None;
    }
    let path = target.split(['#', '?']).next().unwrap_or("");
    Some(path.replace("%20", " "))
}

/// The broken links of one file: "file:line: target".
fn broken_links(file: &Path, text: &str) -> Vec<String> {
    let dir = file.parent().unwrap();
    links(text)
        .into_iter()
        .filter_map(|(line, target)| {
            let path = local_path(&target)?;
            let resolved = if let Some(abs) = path.strip_prefix('/') {
                // repository-absolute, as GitHub renders it
                Path::new(env!("CARGO_MANIFEST_DIR")).join(abs)
            } else {
                dir.join(&path)
            };
            let shown = file
                .strip_prefix(env!("CARGO_MANIFEST_DIR"))
                .unwrap_or(file);
            (!resolved.exists()).then(|| format!("{}:{line}: {target}", shown.display()))
        })
        .collect()
}

#[test]
fn every_relative_link_in_the_documentation_resolves() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = documentation_files(root);
    assert!(
        files.len() > 5 && files.iter().any(|f| f.ends_with("docs/theory.md")),
        "documentation files not found: {files:?}"
    );
    let mut broken = Vec::new();
    let mut checked = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        checked += links(&text)
            .iter()
            .filter(|(_, t)| local_path(t).is_some())
            .count();
        broken.extend(broken_links(file, &text));
    }
    assert!(
        checked > 20,
        "only {checked} relative links found: is the parser broken?"
    );
    assert!(
        broken.is_empty(),
        "{} broken relative link(s):\n{}",
        broken.len(),
        broken.join("\n")
    );
}

#[test]
fn the_parser_finds_links_and_skips_what_is_not_a_local_link() {
    let text = "\
See [the schema](docs/case-schema.md#conventions) and ![fig](docs/figures/fig5.png \"Fig. 5\").
A [web](https://example.org/x) link, [mail](mailto:a@b.c), [anchor](#top), [code](`x`).
Inline `[not](a-link.md)` code; <img src=\"docs/figures/p.png\" width=300>.
[ref]: cases/punch-gmsh/README.md
```toml
x = \"[not](either.md)\"
```
[nested](docs/a(1).md) and [spaced](<docs/my file.md>)
";
    let found: Vec<String> = links(text).into_iter().map(|(_, t)| t).collect();
    assert_eq!(
        found,
        [
            "docs/case-schema.md#conventions",
            "docs/figures/fig5.png",
            "https://example.org/x",
            "mailto:a@b.c",
            "#top",
            "docs/figures/p.png",
            "cases/punch-gmsh/README.md",
            "docs/a(1).md",
            "docs/my file.md",
        ]
    );
    let local: Vec<String> = found.iter().filter_map(|t| local_path(t)).collect();
    assert_eq!(
        local,
        [
            "docs/case-schema.md",
            "docs/figures/fig5.png",
            "docs/figures/p.png",
            "cases/punch-gmsh/README.md",
            "docs/a(1).md",
            "docs/my file.md",
        ]
    );
}

#[test]
fn a_broken_link_is_reported_with_its_file_and_line() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = "\
[fine](docs/case-schema.md) and [fine too](cases/punch-plane-stress/case.toml#L3)
[gone](docs/no-such-page.md#section)
<img src=\"docs/figures/no-such-figure.png\">
[outside](../asperity-no-such-file.md)
";
    let broken = broken_links(&root.join("README.md"), text);
    assert_eq!(broken.len(), 3, "{broken:?}");
    assert!(
        broken[0].ends_with("README.md:2: docs/no-such-page.md#section"),
        "{broken:?}"
    );
    assert!(
        broken[1].ends_with("README.md:3: docs/figures/no-such-figure.png"),
        "{broken:?}"
    );
    // resolved against the linking file's folder: from docs/, ../README.md exists
    assert!(broken_links(&root.join("docs/x.md"), "[up](../README.md)").is_empty());
    assert!(
        broken[2].ends_with("README.md:4: ../asperity-no-such-file.md"),
        "{broken:?}"
    );
}

/// The README is for users and stays short: at most 10 KB (measurements and
/// their history live in docs/performance.md).
#[test]
fn the_readme_is_at_most_10_kb() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let n = std::fs::metadata(root.join("README.md")).unwrap().len();
    assert!(n <= 10 * 1024, "README.md is {n} bytes, more than 10 KB");
}
