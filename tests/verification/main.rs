//! Verification tests: the numbers. Closed forms (column, patch, limit load),
//! the paper's punch and friction conclusions, finite-difference checks of the
//! tangents, step control, the serial factorizations and the regression gold
//! values of every shipped case (docs/verification.md has the table). One test
//! binary (it links the crate once); one module per concern. Run with
//! `cargo test --release --test verification`.

#[path = "../common/mod.rs"]
mod common;

mod adapt;
mod adapt_over;
mod axisymmetric;
mod blocks;
mod bolted_hub;
mod calibration;
mod column;
mod cycles;
mod cyclic;
mod damping_line;
mod dissipation;
mod estimate;
mod events;
mod events3d;
mod face_coupling;
mod factorization;
mod fillet;
mod flange3d;
mod friction;
mod gap;
mod gmsh_interface3d;
mod gold;
mod hanging;
mod hertz;
mod hertz3d;
mod histories;
mod interface3d;
mod joints;
mod lapjoint3d;
mod limit_load;
mod memory;
mod nonmatching;
mod patch;
mod pretension;
mod pretension3d;
mod punch;
mod punch_rounded;
mod ratings;
mod roughness;
mod service;
mod service_rating;
mod shrink_fit;
mod singular;
mod solid;
mod solid_patch;
mod status_convergence;
mod stepping;
mod surface3d;
mod tables;
mod tangents;
mod thermal;
mod threads;
mod torque_fit;
mod torsion;
mod triangles;
