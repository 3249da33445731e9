//! The accuracy studies: how fast the error falls with the step, and against what.

pub mod invariants;
pub mod order;
pub mod order_verdict;
pub mod phase;
pub mod pin;
pub mod probe;
pub mod quadrature;
pub mod rung;
pub mod scene_check;
pub mod trajectory;
