//! How many threads one process computes with: the element loop
//! (`crate::solve::Engine::set_threads`). The serial factorization stays on
//! one ([`crate::linalg::backend::serial::FACTOR_THREADS`]).
//!
//! Chosen by `asperity run --threads N`, else by the environment variable
//! `VAR`, else all the cores this process may run on on one process and one
//! thread per rank under MPI (the ranks already share the cores).

use crate::error::{Error, Result};

/// Environment variable giving the thread count when `--threads` is not set.
pub(crate) const VAR: &str = "ASPERITY_THREADS";

/// The largest count accepted: more is a typing error, not a machine.
pub const MAX: usize = 1024;

/// A thread count as written by the user, from 1 to [`MAX`]; `option` names
/// where it was written (`--threads`, `VAR`).
pub fn parse(option: &str, text: &str) -> Result<usize> {
    let bad = || {
        Error::input(
            option,
            format!("expected a whole number of threads from 1 to {MAX}, got \"{text}\""),
        )
    };
    let n: usize = text.trim().parse().map_err(|_| bad())?;
    if n == 0 || n > MAX {
        return Err(bad());
    }
    Ok(n)
}

/// The count asked for: the command line's `--threads` value, else `VAR`
/// when set (both validated), else `None` (the default of the backend).
pub fn requested(option: Option<&str>) -> Result<Option<usize>> {
    if let Some(text) = option {
        return parse("--threads", text).map(Some);
    }
    match std::env::var_os(VAR) {
        Some(v) => parse(VAR, &v.to_string_lossy()).map(Some),
        None => Ok(None),
    }
}

/// The cores this process may run on (1 where unknown): the default on one
/// process.
pub fn available() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_from_1_to_the_maximum_are_accepted() {
        assert_eq!(parse("--threads", "1").unwrap(), 1);
        assert_eq!(parse("--threads", " 8 ").unwrap(), 8);
        assert_eq!(parse("--threads", "1024").unwrap(), MAX);
    }

    #[test]
    fn zero_absurd_and_non_numeric_counts_name_the_option() {
        for text in [
            "0",
            "1025",
            "100000000000000000000000",
            "-1",
            "two",
            "1.5",
            "",
        ] {
            let msg = parse("--threads", text).unwrap_err().to_string();
            assert!(
                msg.starts_with("--threads: expected a whole number of threads from 1 to 1024"),
                "{text}: {msg}"
            );
        }
    }
}
