//! Cost: time per step, and force evaluations against the error they buy.

pub mod count;
pub mod evaluations;
pub mod step_time;
pub mod work_points;
