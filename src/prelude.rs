//! Everything a test needs to guard an integrator, in one `use`:
//!
//! ```
//! use stepladder::prelude::*;
//!
//! assert_claims(&Leapfrog, &KeplerCircular);
//! ```
//!
//! the guards and their macros, the scheme traits, the catalogue and
//! [`BlackBox`], [`SchemeMeta`], the scenes, [`State`] and [`Real`] (and
//! nalgebra's [`SVector`], [`Vector1`] and [`Vector2`], which states hold), every
//! study with its spec and record and [`Error`].

pub use crate::conditions::{
    self, Conditions, Defect, NystromConditions, RungeKuttaConditions, SplittingConditions,
    StepRatio, TreeDefect,
};
pub use crate::error::Error;
pub use crate::guard::*;
pub use crate::nalgebra::{SVector, Vector1, Vector2};
pub use crate::scene::*;
pub use crate::scheme::*;
pub use crate::state::{Real, State};
pub use crate::study::{
    AdaptiveBlackBox, AdaptiveClaim, AdaptiveClaims, AdaptiveIntegrator, AdaptivePin,
    AdaptivePinOutcome, AdaptiveRun, Advance, AdvanceFn, Controller, DPRKN6_ADAPTIVE,
    DPRKN8_ADAPTIVE, DropReason, EccentricEnergyRecord, EccentricOrderRecord, EmbeddedPair,
    EnergyClass, EnergyRecord, EnergySpec, EscapeRecord, EscapeSpec, EvaluationRecord,
    FollowingRecord, JudgedClaim, LongrunRecord, LongrunSpec, OrderRecord, OrderReduction,
    OrderSpec, PhaseRecord, Pin, PinOutcome, Reference, ReverseRecord, ReverseSpec, RoundoffRecord,
    RoundoffSpec, RunEnd, Rung, SceneCheck, SchemeWork, SpeedRecord, StabilityRecord,
    SymplecticRecord, SymplecticSpec, ToleranceLadderRecord, ToleranceLadderSpec, TolerancePoint,
    Verdict, WellSpec, check_adaptive_pin, check_pin, check_scene, eccentric_energy,
    eccentric_order, energy_drift, escape_or_trapped, evaluations, following, global_order,
    longrun, phase_error, reversibility, roundoff, scheme_work, speed, stability, symplecticity,
    tolerance_ladder,
};
pub use crate::{guard_adaptive, guard_claims};
