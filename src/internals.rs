//! The harness's inner workings, for this repository's own lab, tests and
//! audit: the modules behind the studies (ladders, fits, tolerances, runs,
//! wording) and the studies' own modules, each under one name here.
//!
//! Not part of the public API. Everything a user needs is in
//! [`crate::prelude`], [`crate::guard`], [`crate::scene`], [`crate::scheme`]
//! and [`crate::study`]; no path below is promised to stay. The repository's
//! tests check that code outside the core reaches the inner modules through
//! this door only.

pub use crate::ladder;
pub use crate::maths;
pub use crate::parallel;
pub use crate::run;
pub use crate::scheme::compensated;
pub use crate::study::{
    accuracy, adaptive, breakdown, cost, geometry, hard, round_off, stability, verdict,
};
pub use crate::tolerance;
pub use crate::wording;
