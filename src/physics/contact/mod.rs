//! The laws of the rough interface per unit area (paper sections 2.1-2.6):
//! the normal law ([`normal`], tables in [`table`]), the tangential law with
//! its memories ([`tangential`]), the state of an interface point
//! ([`state`]).

pub mod normal;
pub mod state;
pub mod table;
pub mod tangential;

pub(crate) use normal::NormalLaw;
pub use state::{PointState, Status};
pub(crate) use tangential::{Backbone, Stretch, MEMORY_POINTS};
pub use tangential::{Memory, Slip, TangentialLaw};
