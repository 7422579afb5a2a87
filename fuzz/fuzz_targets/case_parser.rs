//! Arbitrary bytes through the case path of `asperity run`: TOML parsing,
//! validation and model construction (mesh generation, element geometry,
//! interfaces, supports, loads, sparsity pattern). Nothing is solved and no file
//! is written. Any panic, abort or runaway allocation is a bug: every bad case
//! must come back as an `Err` with a one-line message.
#![no_main]

use asperity::input::case::{check_case, Case};
use asperity::model::Model;
use libfuzzer_sys::fuzz_target;

/// Larger (valid) meshes are only validated, not built: building one exercises
/// the same code as a small mesh, only slower (the 250 000-element cap itself
/// is checked by validation, and by the corpus case 71-elements-too-many).
const BUILD_LIMIT: usize = 20_000;

fn one_line(e: asperity::Error) {
    let line = e.to_string();
    assert!(!line.contains(['\n', '\r']), "multi-line error: {line:?}");
}

fuzz_target!(|data: &[u8]| {
    // a case file is UTF-8 text; the file reader rejects other bytes
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match Case::parse(text, "fuzz.toml") {
        Err(e) => one_line(e),
        Ok(case) if case.element_count().is_some_and(|n| n <= BUILD_LIMIT) => {
            if let Err(e) = Model::parse(text, "fuzz.toml") {
                one_line(e);
            }
        }
        Ok(case) => {
            if let Err(e) = check_case(&case) {
                one_line(e);
            }
        }
    }
});
