//! Arbitrary bytes into the Gmsh reader and the mesh builder: no panic, no
//! unbounded allocation, and every error is a single line.
//!
//!   RUSTC_BOOTSTRAP=1 cargo fuzz run gmsh_reader fuzz/corpus/gmsh_reader fuzz/seeds/gmsh_reader \
//!       -- -dict=fuzz/gmsh.dict -max_total_time=600
#![no_main]

use asperity::input::mesh::blocks::InterfaceSpec;
use asperity::input::mesh::gmsh::{build_mesh, parse_msh};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let one_line = |e: asperity::Error| {
        let s = e.to_string();
        assert!(!s.contains('\n') && !s.contains('\r'), "multi-line error: {s:?}");
    };
    match parse_msh(data, "fuzz.msh") {
        Err(e) => one_line(e),
        Ok(msh) => {
            let spec = InterfaceSpec {
                name: "contact".into(),
                upper: None,
                lower: None,
                upper_curve: Some("punch.bottom".into()),
                lower_curve: Some("foundation.top".into()),
                left: None,
                right: None,
            };
            for specs in [&[][..], std::slice::from_ref(&spec)] {
                match build_mesh(&msh, specs, "fuzz.toml") {
                    Err(e) => one_line(e),
                    Ok(mesh) => {
                        let _ = mesh.validate();
                    }
                }
            }
        }
    }
});
