//! The geometric studies: what a scheme preserves of the flow.

pub mod energy;
pub mod reverse;
pub mod symplectic;
