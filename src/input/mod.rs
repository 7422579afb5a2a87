//! What the user gives: the case file ([`case`]: its schema, the checks that
//! need no mesh) and the meshes ([`mesh`]: generated blocks or Gmsh files,
//! and their local refinement).

pub mod case;
pub mod mesh;
