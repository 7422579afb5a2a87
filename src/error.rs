//! One error type for the whole crate.
//!
//! Every variant renders as a single line that names the problem and where it is
//! (file and key, element and Gauss point, increment and load factor). The binary
//! prints it as `error: …` and exits with code 2.

use std::fmt;
use std::path::PathBuf;

/// Crate-wide result.
pub type Result<T> = std::result::Result<T, Error>;

#[derive(Debug)]
pub enum Error {
    /// A case file that cannot be read, parsed or that holds impossible values.
    /// `place` is `file` or `file: key`.
    Input { place: String, message: String },
    /// A mesh that is broken (inverted element, unpaired interface node …).
    Mesh { place: String, message: String },
    /// A load increment that did not converge even after every allowed cutback.
    Convergence {
        increment: usize,
        load_factor: f64,
        message: String,
    },
    /// A singular or otherwise failed linear solve.
    Solver(String),
    /// Results that could not be written or drawn (a failed write on another
    /// rank, a figure the plotting library refused).
    Output(String),
    /// MPI or the parallel set-up failed.
    Parallel(String),
    /// A study (refine, stability, figures) whose runs did not give what it needs.
    Study(String),
    /// The run needs more memory than the machine has (estimated up front from
    /// the factorization's symbolic analysis, or an allocation that failed).
    Memory(String),
    /// A file system failure.
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
}

impl Error {
    pub fn input(place: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Input {
            place: place.into(),
            message: message.into(),
        }
    }

    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

impl fmt::Display for Error {
    /// One line: control characters (from file names, keys and values that came
    /// from the user) are written as escapes such as `\n` or `\u{1b}`; a quoted
    /// value longer than `MAX_QUOTE` characters is cut to that, and the whole
    /// line to `MAX_LINE` (a 10 MB string in a case file is not echoed).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&bounded(&escape_controls(&self.raw())))
    }
}

/// Most characters of one value (a name, a string, a key) quoted in a message.
pub(crate) const MAX_QUOTE: usize = 80;
/// Most characters of a whole error line.
pub(crate) const MAX_LINE: usize = 2000;

/// `text` cut to `MAX_QUOTE` characters, with `…(N characters)` when cut.
pub fn clip(text: &str) -> String {
    let n = text.chars().count();
    if n <= MAX_QUOTE {
        return text.to_string();
    }
    let head: String = text.chars().take(MAX_QUOTE).collect();
    format!("{head}…({n} characters)")
}

/// A message with every quoted run (between `"` or between backticks) clipped
/// to [`MAX_QUOTE`] characters, then the whole cut to [`MAX_LINE`].
pub(crate) fn bounded(text: &str) -> String {
    let mut out = String::with_capacity(text.len().min(4 * MAX_LINE));
    let mut rest = text;
    while let Some(open) = rest.find(['"', '`']) {
        let q = rest.as_bytes()[open] as char;
        out.push_str(&rest[..=open]);
        rest = &rest[open + 1..];
        // the closing quote: not one escaped by a backslash (Debug-quoted strings)
        let mut close = None;
        let mut escaped = false;
        for (i, c) in rest.char_indices() {
            if escaped {
                escaped = false;
            } else if c == '\\' && q == '"' {
                escaped = true;
            } else if c == q {
                close = Some(i);
                break;
            }
        }
        let end = close.unwrap_or(rest.len());
        out.push_str(&clip(&rest[..end]));
        match close {
            Some(i) => {
                out.push(q);
                rest = &rest[i + 1..];
            }
            None => rest = "",
        }
    }
    out.push_str(rest);
    let n = out.chars().count();
    if n > MAX_LINE {
        let head: String = out.chars().take(MAX_LINE).collect();
        return format!("{head}…({} more characters)", n - MAX_LINE);
    }
    out
}

/// `text` with every control character escaped (`\n`, `\t`, `\u{7}` …), so that
/// it prints as one line and cannot drive a terminal; so are the characters
/// that print as nothing or as a plain space ([`invisible`]): a byte-order
/// mark left in front of a number shows as `\u{feff}`, not as an empty spot.
pub(crate) fn escape_controls(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() || invisible(c) {
            s.extend(c.escape_default());
        } else {
            s.push(c);
        }
    }
    s
}

/// Characters that a terminal shows as nothing, as a plain space or that
/// reorder the text around them: every white space but the ASCII space (no-break
/// and typographic spaces, the line and paragraph separators), and Unicode's
/// default-ignorable code points (byte-order mark / zero-width no-break space,
/// zero-width spaces and joiners, the bidirectional marks and overrides, soft
/// hyphen, variation selectors, tags).
pub fn invisible(c: char) -> bool {
    (c.is_whitespace() && c != ' ')
        || matches!(
            c,
            '\u{00AD}'
                | '\u{034F}'
                | '\u{061C}'
                | '\u{115F}'..='\u{1160}'
                | '\u{17B4}'..='\u{17B5}'
                | '\u{180B}'..='\u{180F}'
                | '\u{200B}'..='\u{200F}'
                | '\u{202A}'..='\u{202E}'
                | '\u{2060}'..='\u{206F}'
                | '\u{3164}'
                | '\u{FE00}'..='\u{FE0F}'
                | '\u{FEFF}'
                | '\u{FFA0}'
                | '\u{FFF0}'..='\u{FFFB}'
                | '\u{1BCA0}'..='\u{1BCA3}'
                | '\u{1D173}'..='\u{1D17A}'
                | '\u{E0000}'..='\u{E0FFF}'
        )
}

impl Error {
    /// The message before escaping.
    fn raw(&self) -> String {
        match self {
            Error::Input { place, message } => format!("{place}: {message}"),
            Error::Mesh { place, message } => format!("mesh {place}: {message}"),
            Error::Convergence {
                increment,
                load_factor,
                message,
            } => format!(
                "increment {increment} (load factor {load_factor:.6}) did not converge: {message}"
            ),
            Error::Solver(message) => format!("linear solver: {message}"),
            Error::Output(message) => format!("output: {message}"),
            Error::Parallel(message) => format!("MPI: {message}"),
            Error::Study(message) => format!("study: {message}"),
            Error::Memory(message) => format!("memory: {message}"),
            Error::Io { path, source } => format!("{}: {source}", path.display()),
        }
    }
}

impl std::error::Error for Error {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_values_are_clipped_short_ones_kept() {
        let long = "x".repeat(10_000_000);
        let e = Error::input(
            "case.toml:3:13",
            format!("invalid type: string \"{long}\", expected f64"),
        );
        let s = e.to_string();
        assert!(s.len() < 300, "{}", s.len());
        assert!(s.contains("…(10000000 characters)\", expected f64"), "{s}");
        let e = Error::input("case.toml", "no node set \"a.left\" (sets: `b`)");
        assert_eq!(
            e.to_string(),
            "case.toml: no node set \"a.left\" (sets: `b`)"
        );
        // an escaped quote inside a Debug-quoted value does not end it
        let v = format!("{:?}", format!("ab\"{}", "y".repeat(200)));
        let s = Error::input("p", format!("name {v} bad")).to_string();
        assert!(s.ends_with("characters)\" bad"), "{s}");
        // invisible characters are escaped like control characters
        let s = Error::input(
            "p.csv:1",
            "\"\u{feff}1.5\u{a0}\u{200b}\u{202e}x\" is not a number",
        )
        .to_string();
        assert_eq!(
            s,
            "p.csv:1: \"\\u{feff}1.5\\u{a0}\\u{200b}\\u{202e}x\" is not a number"
        );
        let s = Error::input("p", "µm σ_s η ≤ é ").to_string();
        assert_eq!(s, "p: µm σ_s η ≤ é ");
        // unquoted text: the line is cut
        let s = Error::input("p", "z ".repeat(5000)).to_string();
        assert!(s.chars().count() < MAX_LINE + 40, "{}", s.len());
    }
}
