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
    /// from the user) are written as escapes such as `\n` or `\u{1b}`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&escape_controls(&self.raw()))
    }
}

/// `text` with every control character escaped (`\n`, `\t`, `\u{7}` …), so that
/// it prints as one line and cannot drive a terminal.
pub fn escape_controls(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            s.extend(c.escape_default());
        } else {
            s.push(c);
        }
    }
    s
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
            Error::Io { path, source } => format!("{}: {source}", path.display()),
        }
    }
}

impl std::error::Error for Error {}
