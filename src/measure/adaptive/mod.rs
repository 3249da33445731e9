//! Adaptive step control measured as a ladder: an adaptive integrator is
//! run at one tolerance a decade, and its global error, cost and geometry
//! are judged against what its controller's theory predicts.
//!
//! - [`integrator`]: the [`AdaptiveIntegrator`] trait every adaptive method
//!   is run through (the crate's own pairs here, the `ode_solvers` peer
//!   in [`crate::measure::cost::peer`]);
//! - [`embedded_pair`]: an embedded Runge-Kutta-Nyström pair with the
//!   standard step-size controller;
//! - [`tolerance_ladder`]: the study.

pub mod embedded_pair;
pub mod integrator;
pub mod tolerance_ladder;

pub use embedded_pair::{Controller, DPRKN6_ADAPTIVE, DPRKN8_ADAPTIVE, EmbeddedPair};
pub use integrator::{AdaptiveClaims, AdaptiveIntegrator, AdaptiveRun, RunEnd};
pub use tolerance_ladder::{
    ToleranceLadderRecord, ToleranceLadderSpec, TolerancePoint, proportionality_exponent,
    tolerance_ladder,
};
