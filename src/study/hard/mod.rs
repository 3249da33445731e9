//! The hard cases: eccentric orbits, the separatrix of the well, escape or trapped.

pub mod eccentric;
pub mod escape;
pub mod following;
