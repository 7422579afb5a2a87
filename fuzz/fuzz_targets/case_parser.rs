//! Arbitrary bytes through the case path of `asperity run`: TOML parsing,
//! validation and model construction (mesh generation, element geometry,
//! interfaces, boundary conditions, loads, sparsity pattern). Nothing is solved
//! and no file is written. Any panic, abort or runaway allocation is a bug:
//! every bad case must come back as an `Err` with a one-line message.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // a case file is UTF-8 text; other bytes are rejected before parsing
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Err(e) = asperity::model::Model::parse(text, "fuzz.toml") {
        let line = e.to_string();
        assert!(!line.contains('\n'), "multi-line error: {line:?}");
    }
});
