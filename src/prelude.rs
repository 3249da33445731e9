//! What a test needs to guard an integrator, in one `use`: thirty names,
//! listed here by hand, so that a glob import brings nothing unexpected.
//!
//! ```
//! use stepladder::prelude::*;
//!
//! let record = assert_claims(&stepladder::scheme::Leapfrog, &KeplerCircular);
//! assert!(record.passed());
//! ```
//!
//! - the guards, one per claim and one for every claim ([`assert_claims`]),
//!   the call that returns every verdict ([`claims`]), and the macros that
//!   write one `#[test]` per claim;
//! - what bringing an integrator takes: [`OneStep`] or [`Scheme`] with its
//!   [`SchemeMeta`] and [`StepFailure`], [`Real`] and [`State`] for a generic
//!   step, [`BlackBox`] with its [`Force`] callback and an implicit step's
//!   [`Solve`], and [`AdaptiveBlackBox`] with its [`AdaptiveClaims`];
//! - the scenes the guards are most often run on, and [`Scene`],
//!   [`Potential`] and [`FromPotential`] to bring one;
//! - [`Error`] and [`Verdict`].
//!
//! Everything else (the catalogue, the other scenes, each study with its
//! spec and record) is one `use` away in [`crate::scheme`], [`crate::scene`]
//! and [`crate::study`].

pub use crate::error::Error;
pub use crate::guard::{
    assert_adaptive, assert_claims, assert_energy, assert_evaluations, assert_order, assert_pinned,
    assert_reversible, assert_symplectic,
};
pub use crate::scene::{
    FromPotential, Harmonic, KeplerCircular, KeplerEccentric, Potential, Scene,
};
pub use crate::scheme::{
    AdaptiveBlackBox, AdaptiveClaims, BlackBox, Force, OneStep, Scheme, SchemeMeta, Solve,
    StepFailure,
};
pub use crate::state::{Real, State};
pub use crate::study::{Verdict, claims};
pub use crate::{guard_adaptive, guard_claims};
