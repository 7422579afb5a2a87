//! The physics of a point and an element: the finite elements (shape
//! functions, Gauss rules, element vectors and tangents), the materials
//! (von Mises plasticity) and the contact laws of the rough interface (normal
//! and tangential laws per unit area, the state of an interface point).
//! Nothing here knows a case, a mesh or a model.

pub mod contact;
pub mod element;
pub mod material;
pub mod range;
