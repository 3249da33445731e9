//! Adaptive step control measured as a ladder: an adaptive integrator is
//! run at one tolerance a decade, and its global error, cost and geometry
//! are judged against what its controller's theory predicts.
//!
//! The integrators themselves (the [`AdaptiveIntegrator`](crate::scheme::AdaptiveIntegrator) trait, the
//! crate's embedded pairs, the adaptive black box) live with the other
//! integrators in [`crate::scheme`]; here are the study,
//! [`tolerance_ladder`](fn@tolerance_ladder), its judge, record and pins.

mod judge;
pub mod ladder;
pub mod pin;
pub mod record;

pub use ladder::{ToleranceLadderSpec, tolerance_ladder, tolerance_point};
pub use pin::{AdaptivePin, AdaptivePinOutcome, check_adaptive_pin};
pub use record::{AdaptiveClaim, JudgedClaim, ToleranceLadderRecord, TolerancePoint};
