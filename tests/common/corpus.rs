//! The bad-input corpus as files on disk: a folder of `tests/bad_inputs/` holds
//! `expect.txt` (and perhaps `note.txt`, `args.txt`, `env.txt`), raw input files,
//! and patches: `NAME.patch` makes the input file `NAME` from a base case of
//! `tests/bad_inputs/base/` and a few line-oriented directives. The format is
//! described in `tests/bad_inputs/README.md`; [`assemble`] writes a folder's
//! case into a scratch folder, which is what `asperity` runs.

use std::path::{Path, PathBuf};

/// Files of a corpus folder that are about the case, not part of it.
pub const NOT_INPUT: [&str; 4] = ["expect.txt", "note.txt", "args.txt", "env.txt"];

/// The corpus root, `tests/bad_inputs`.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_inputs")
}

/// The folder of base cases the patches start from.
pub fn base_dir() -> PathBuf {
    root().join("base")
}

/// The corpus folders (every folder of `tests/bad_inputs` but `base`), sorted.
pub fn folders() -> Vec<PathBuf> {
    let root = root();
    let mut v: Vec<PathBuf> = std::fs::read_dir(&root)
        .unwrap_or_else(|e| panic!("{}: {e}", root.display()))
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.is_dir() && p.file_name().is_some_and(|n| n != "base"))
        .collect();
    v.sort();
    v
}

/// Assembles the corpus folder `name` into a scratch folder of its own under
/// the target directory (made afresh) and returns its path; the folder is
/// named `name` too. Panics, naming the folder, when a patch is malformed.
pub fn bad_input(name: &str) -> PathBuf {
    let dest = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("bad_input_cases")
        .join(name)
        .join(name);
    let _ = std::fs::remove_dir_all(&dest);
    assemble(&root().join(name), &dest).unwrap_or_else(|e| panic!("tests/bad_inputs/{name}: {e}"));
    dest
}

/// Writes the case of the corpus folder `folder` into `dest` (created; it must
/// not exist yet): every patch applied to its base, every other input file or
/// folder copied as it is. Returns the base files used. Errors name the patch
/// and its line.
pub fn assemble(folder: &Path, dest: &Path) -> Result<Vec<String>, String> {
    std::fs::create_dir_all(dest).map_err(|e| format!("{}: {e}", dest.display()))?;
    let mut entries: Vec<PathBuf> = std::fs::read_dir(folder)
        .map_err(|e| format!("{}: {e}", folder.display()))?
        .map(|e| e.map(|e| e.path()).map_err(|e| e.to_string()))
        .collect::<Result<_, _>>()?;
    entries.sort();
    let names: Vec<String> = entries
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    let mut bases = Vec::new();
    let mut inputs = 0;
    for (path, name) in entries.iter().zip(&names) {
        if NOT_INPUT.contains(&name.as_str()) {
            continue;
        }
        inputs += 1;
        if let Some(target) = name.strip_suffix(".patch") {
            if names.iter().any(|n| n == target) {
                return Err(format!("both {name} and {target}: which one is the input?"));
            }
            let text = std::fs::read_to_string(path).map_err(|e| format!("{name}: {e}"))?;
            let (base, bytes) =
                apply_patch(&text, &base_dir()).map_err(|e| format!("{name}: {e}"))?;
            std::fs::write(dest.join(target), bytes).map_err(|e| format!("{target}: {e}"))?;
            bases.push(base);
        } else {
            copy(path, &dest.join(name))?;
        }
    }
    if inputs == 0 {
        return Err("no input: neither a patch nor a case file".into());
    }
    Ok(bases)
}

/// Copies a file, or a folder with everything in it.
fn copy(from: &Path, to: &Path) -> Result<(), String> {
    if from.is_dir() {
        std::fs::create_dir_all(to).map_err(|e| format!("{}: {e}", to.display()))?;
        for e in std::fs::read_dir(from).map_err(|e| format!("{}: {e}", from.display()))? {
            let e = e.map_err(|e| e.to_string())?;
            copy(&e.path(), &to.join(e.file_name()))?;
        }
        Ok(())
    } else {
        std::fs::copy(from, to)
            .map(|_| ())
            .map_err(|e| format!("{}: {e}", from.display()))
    }
}

/// The table header a line is, `[name]` or `[[name]]` (spaces and a comment
/// around it dropped), or `None`.
pub fn header_of(line: &str) -> Option<String> {
    let s = line.trim_start();
    let open = if s.starts_with("[[") {
        2
    } else if s.starts_with('[') {
        1
    } else {
        return None;
    };
    let s = s[open..].trim_start();
    let first = s.chars().next()?;
    if !(first.is_ascii_alphabetic() || first == '_') {
        return None;
    }
    let end = s
        .find(|c: char| !(c.is_ascii_alphanumeric() || "_.-".contains(c)))
        .unwrap_or(s.len());
    let name = &s[..end];
    let s = s[end..].trim_start();
    let close = if s.starts_with("]]") {
        2
    } else if s.starts_with(']') {
        1
    } else {
        return None;
    };
    let rest = s[close..].trim_start();
    if close != open || !(rest.is_empty() || rest.starts_with('#')) {
        return None;
    }
    Some(format!("{}{name}{}", &"[["[..open], &"]]"[..open]))
}

/// The key of a `key = value` line (not a header), or `None`.
pub fn key_of(line: &str) -> Option<&str> {
    if header_of(line).is_some() {
        return None;
    }
    let s = line.trim_start();
    let end = s
        .find(|c: char| !(c.is_ascii_alphanumeric() || "_.-".contains(c)))
        .unwrap_or(s.len());
    (end > 0 && s[end..].trim_start().starts_with('=')).then_some(&s[..end])
}

/// A table of the text: its header (empty for the top level) and its lines
/// `start..end` (the header's line first; up to the next header).
struct Table {
    header: String,
    start: usize,
    end: usize,
}

fn tables(lines: &[(Option<usize>, String)]) -> Vec<Table> {
    let starts: Vec<usize> = (0..lines.len())
        .filter(|&i| header_of(&lines[i].1).is_some())
        .collect();
    let mut out = vec![Table {
        header: String::new(),
        start: 0,
        end: starts.first().copied().unwrap_or(lines.len()),
    }];
    for (k, &s) in starts.iter().enumerate() {
        out.push(Table {
            header: header_of(&lines[s].1).unwrap(),
            start: s,
            end: starts.get(k + 1).copied().unwrap_or(lines.len()),
        });
    }
    out
}

/// The table a selector names: `[a.b]`, `[[a]]`, `[[a]]#2` (the second of
/// them: needed when there are several), or the empty selector for the top level.
fn find_table(lines: &[(Option<usize>, String)], selector: &str) -> Result<Table, String> {
    let (header, nth) = match selector.split_once('#') {
        Some((h, n)) => match n.parse::<usize>() {
            Ok(k) if k >= 1 && n.bytes().all(|b| b.is_ascii_digit()) => (h, Some(k)),
            _ => return Err(format!("bad table number in {selector}")),
        },
        None => (selector, None),
    };
    let mut all = tables(lines);
    if header.is_empty() {
        return if nth.is_none() {
            Ok(all.swap_remove(0))
        } else {
            Err(format!("no table {selector}"))
        };
    }
    let mut found: Vec<Table> = all.into_iter().filter(|t| t.header == header).collect();
    match nth {
        _ if found.is_empty() => Err(format!("no table {header}")),
        None if found.len() > 1 => Err(format!(
            "{} tables {header}: say which with {header}#N",
            found.len()
        )),
        None => Ok(found.swap_remove(0)),
        Some(n) if n > found.len() => {
            Err(format!("no table {header}#{n} (there are {})", found.len()))
        }
        Some(n) => Ok(found.swap_remove(n - 1)),
    }
}

/// The one line of `key` in a table.
fn key_line(lines: &[(Option<usize>, String)], t: &Table, key: &str) -> Result<usize, String> {
    let hits: Vec<usize> = (t.start..t.end)
        .filter(|&i| key_of(&lines[i].1) == Some(key))
        .collect();
    let place = if t.header.is_empty() {
        "the top level"
    } else {
        &t.header
    };
    match hits.len() {
        1 => Ok(hits[0]),
        0 => Err(format!("no line of key {key} in {place}")),
        n => Err(format!("{n} lines of key {key} in {place}")),
    }
}

/// Where line `n` (from 1) of the base is now.
fn by_origin(lines: &[(Option<usize>, String)], n: usize) -> Result<usize, String> {
    lines
        .iter()
        .position(|(o, _)| *o == Some(n))
        .ok_or_else(|| format!("line {n} of the base is not there (removed, or past its end)"))
}

/// A line number of a directive.
fn number(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n >= 1 && s.bytes().all(|b| b.is_ascii_digit()) => Ok(n),
        _ => Err(format!("bad line number {s:?}")),
    }
}

/// Applies a patch (the text of a `.patch` file) to its base, read from
/// `base_dir`; returns the base's name and the file made. Errors name the
/// line of the patch.
pub fn apply_patch(patch: &str, base_dir: &Path) -> Result<(String, Vec<u8>), String> {
    let mut directives = patch
        .split('\n')
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let base = match directives.next() {
        Some((_, l)) if l.starts_with("base ") => l["base ".len()..].to_string(),
        Some((n, l)) => {
            return Err(format!(
                "line {n}: {l:?}: the first line must be `base NAME`"
            ))
        }
        None => return Err("empty patch: the first line must be `base NAME`".into()),
    };
    if base.is_empty() || base.contains(['/', '\\']) || base.starts_with('.') {
        return Err(format!(
            "line 1: base {base:?} is not a file name of {}",
            base_dir.display()
        ));
    }
    let text = std::fs::read_to_string(base_dir.join(&base))
        .map_err(|e| format!("line 1: unknown base {base:?} ({e})"))?;
    let body = text
        .strip_suffix('\n')
        .ok_or_else(|| format!("base {base}: does not end with a newline"))?;
    let mut lines: Vec<(Option<usize>, String)> = body
        .split('\n')
        .enumerate()
        .map(|(i, l)| (Some(i + 1), l.to_string()))
        .collect();
    let mut truncate: Option<usize> = None;
    for (n, d) in directives {
        let at = |e: String| format!("line {n}: {d:?}: {e}");
        if truncate.is_some() {
            return Err(at("truncate must be the last directive".into()));
        }
        step(&mut lines, d, &mut truncate).map_err(at)?;
    }
    let mut out = lines
        .iter()
        .map(|(_, l)| l.as_str())
        .collect::<Vec<_>>()
        .join("\n")
        .into_bytes();
    out.push(b'\n');
    if let Some(t) = truncate {
        if t >= out.len() {
            return Err(format!("truncate {t}: past the end ({} bytes)", out.len()));
        }
        out.truncate(t);
    }
    Ok((base, out))
}

/// One directive.
fn step(
    lines: &mut Vec<(Option<usize>, String)>,
    d: &str,
    truncate: &mut Option<usize>,
) -> Result<(), String> {
    let (word, rest) = d.split_once(' ').unwrap_or((d, ""));
    match word {
        "set" | "add" | "add-first" | "delete" | "before" => {
            let (selector, line) = if rest.starts_with('[') {
                rest.split_once(' ').unwrap_or((rest, ""))
            } else {
                ("", rest)
            };
            let t = find_table(lines, selector)?;
            let new = (None, line.to_string());
            match word {
                "before" if selector.is_empty() => return Err("before needs a table".into()),
                "before" => lines.insert(t.start, new),
                "delete" if line.is_empty() => {
                    if selector.is_empty() {
                        return Err("delete needs a key or a table".into());
                    }
                    lines.drain(t.start..t.end);
                }
                "delete" => {
                    let i = key_line(lines, &t, line)?;
                    lines.remove(i);
                }
                "set" => {
                    let key = key_of(line).ok_or("not a `key = value` line")?;
                    let i = key_line(lines, &t, key)?;
                    lines[i].1 = line.to_string();
                }
                "add" => {
                    let after = (t.start..t.end)
                        .rev()
                        .find(|&i| !lines[i].1.trim().is_empty())
                        .map_or(t.start, |i| i + 1);
                    lines.insert(after, new);
                }
                _ => lines.insert(if selector.is_empty() { 0 } else { t.start + 1 }, new),
            }
        }
        "replace" | "insert" => {
            let (num, text) = rest.split_once(' ').unwrap_or((rest, ""));
            let i = by_origin(lines, number(num)?)?;
            if word == "replace" {
                lines[i].1 = text.to_string();
            } else {
                lines.insert(i, (None, text.to_string()));
            }
        }
        "remove" => {
            let (a, b) = rest.split_once('-').unwrap_or((rest, rest));
            let (a, b) = (number(a)?, number(b)?);
            if b < a {
                return Err(format!("bad line range {rest:?}"));
            }
            for k in a..=b {
                let i = by_origin(lines, k)?;
                lines.remove(i);
            }
        }
        "append" => lines.push((None, rest.to_string())),
        "truncate" => match rest.parse::<usize>() {
            Ok(t) if rest.bytes().all(|b| b.is_ascii_digit()) => *truncate = Some(t),
            _ => return Err(format!("bad byte count {rest:?}")),
        },
        _ => return Err(format!("unknown directive {word:?}")),
    }
    Ok(())
}
