//! Adaptive step control measured as a ladder: an adaptive integrator is
//! run at one tolerance a decade, and its global error, cost and geometry
//! are judged against what its controller's theory predicts.
//!
//! - [`integrator`]: the [`AdaptiveIntegrator`] trait every adaptive method
//!   is run through (the crate's own pairs here, the `ode_solvers` peer
//!   in the lab);
//! - [`embedded_pair`]: an embedded Runge-Kutta-Nyström pair with the
//!   standard step-size controller;
//! - [`black_box`]: an adaptive integrator from any crate, given as a
//!   function from `t0` to `t1` at a tolerance;
//! - [`ladder`]: the study, [`tolerance_ladder`](fn@tolerance_ladder).

pub mod black_box;
pub mod embedded_pair;
pub mod integrator;
mod judge;
pub mod ladder;
pub mod pin;
pub mod record;

pub use black_box::{AdaptiveBlackBox, Advance, AdvanceFn};
pub use embedded_pair::{Controller, DPRKN6_ADAPTIVE, DPRKN8_ADAPTIVE, EmbeddedPair};
pub use integrator::{AdaptiveClaims, AdaptiveIntegrator, AdaptiveRun, RunEnd};
pub use ladder::{ToleranceLadderSpec, proportionality_exponent, tolerance_ladder};
pub use pin::{AdaptivePin, AdaptivePinOutcome, check_adaptive_pin};
pub use record::{AdaptiveClaim, JudgedClaim, ToleranceLadderRecord, TolerancePoint};
