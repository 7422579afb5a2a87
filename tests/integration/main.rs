//! Integration tests: the program as a user meets it. The command line and its
//! errors, `--help`, the bad-input corpus, the output files and their schema,
//! interrupts and restarts, Gmsh meshes, `asperity figures`, the VTU output read
//! by a real reader, `asperity report` (in a headless browser too), and the
//! documentation's links. One test binary (it links
//! the crate once); one module per concern. Run with
//! `cargo test --release --test integration`.

#[path = "../common/mod.rs"]
mod common;

mod adapt_stop;
mod architecture;
mod axisymmetric;
mod bad_inputs;
mod calibrate;
mod calibrate_bad;
mod calibrate_roughness;
mod cli;
mod damping;
mod designer;
mod doc_paths;
mod features_together;
mod figures;
mod gmsh;
mod gmsh_surfaces;
mod help;
mod interface3d_restart;
mod joints;
mod links;
mod output_schema;
mod output_writer;
mod overrides;
mod pretension;
mod refine;
mod report;
mod report_browser;
mod restart;
mod robust;
mod tables;
mod torque_limit;
mod twist_restart;
mod vtu_reader;
