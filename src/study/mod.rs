//! The studies, each a function from a scheme (or an adaptive integrator)
//! and a scene to a record: plain serde data with a verdict and the figures
//! that decided it. Every study sits here under one name, beside its spec
//! (what to run) and its record (what was measured):
//!
//! | question | study | spec | record |
//! |---|---|---|---|
//! | global order, with a 95% interval | [`global_order`] | [`OrderSpec`] | [`OrderRecord`] |
//! | the order conditions a step breaks | [`probe_conditions`] | | [`ConditionProbe`] |
//! | a step's weights and nodes | [`recover_quadrature`] | | [`RecoveredQuadrature`] |
//! | phase error on the oscillator | [`phase_error`] | | [`PhaseRecord`] |
//! | energy over long runs | [`energy_drift`] | [`EnergySpec`] | [`EnergyRecord`] |
//! | symplecticity of the tangent map | [`symplecticity`] | [`SymplecticSpec`] | [`SymplecticRecord`] |
//! | time reversibility | [`reversibility`] | [`ReverseSpec`] | [`ReverseRecord`] |
//! | linear stability interval | [`fn@stability`] | | [`StabilityRecord`] |
//! | force evaluations a step | [`evaluations`] | | [`EvaluationRecord`] |
//! | round-off floor | [`roundoff`] | [`RoundoffSpec`] | [`RoundoffRecord`] |
//! | round-off growth over long runs | [`longrun`] | [`LongrunSpec`] | [`LongrunRecord`] |
//! | orders on eccentric orbits | [`eccentric_order`] | | [`EccentricOrderRecord`] |
//! | energy on eccentric orbits | [`eccentric_energy`] | | [`EccentricEnergyRecord`] |
//! | following the separatrix | [`following`] | [`WellSpec`] | [`FollowingRecord`] |
//! | escape or trapped near the barrier | [`escape_or_trapped`] | [`EscapeSpec`] | [`EscapeRecord`] |
//! | time per step | [`speed`] | | [`SpeedRecord`] |
//! | force evaluations against error | [`scheme_work`] | | [`SchemeWork`] |
//! | an adaptive integrator over tolerances | [`tolerance_ladder()`] | [`ToleranceLadderSpec`] | [`ToleranceLadderRecord`] |
//! | a scene's exact solution | [`check_scene`] | | [`SceneCheck`] |
//! | every claim of a scheme at once | [`fn@claims`] | | [`ClaimsRecord`] |
//!
//! and the pins, which hold a coarse-step error to its round-off between
//! versions: [`check_pin`] and [`check_adaptive_pin`].

#[doc(hidden)]
pub mod accuracy;
#[doc(hidden)]
pub mod adaptive;
#[doc(hidden)]
pub mod breakdown;
mod claims;
#[doc(hidden)]
pub mod cost;
#[doc(hidden)]
pub mod geometry;
#[doc(hidden)]
pub mod hard;
#[doc(hidden)]
pub mod round_off;
#[doc(hidden)]
pub mod stability;
#[doc(hidden)]
pub mod verdict;

pub use accuracy::order::{
    DropReason, OrderRecord, OrderReduction, OrderSpec, Reference, Rung, global_order,
};
pub use accuracy::phase::{PhaseRecord, phase_error};
pub use accuracy::pin::{Pin, PinOutcome, check_pin};
pub use accuracy::probe::{ConditionProbe, ProbedCondition, probe_conditions};
pub use accuracy::quadrature::{RecoveredQuadrature, recover_quadrature};
pub use accuracy::scene_check::{SceneCheck, check_scene};
pub use adaptive::{
    AdaptiveClaim, AdaptivePin, AdaptivePinOutcome, JudgedClaim, ToleranceLadderRecord,
    ToleranceLadderSpec, TolerancePoint, check_adaptive_pin, tolerance_ladder,
};
pub use cost::evaluations::{EvaluationRecord, evaluations};
pub use cost::step_time::{SpeedRecord, speed};
pub use cost::work_points::{SchemeWork, scheme_work};
pub use geometry::energy::{EnergyClass, EnergyRecord, EnergySpec, energy_drift};
pub use geometry::reverse::{ReverseRecord, ReverseSpec, reversibility};
pub use geometry::symplectic::{SymplecticRecord, SymplecticSpec, symplecticity};
pub use hard::eccentric::{
    EccentricEnergyRecord, EccentricOrderRecord, eccentric_energy, eccentric_order,
};
pub use hard::escape::{EscapeRecord, EscapeSpec, escape_or_trapped};
pub use hard::following::{FollowingRecord, WellSpec, following};
pub use round_off::brouwer::{RoundOffRecord, RoundOffSpec, round_off_growth};
pub use round_off::floor::{RoundoffRecord, RoundoffSpec, roundoff};
pub use round_off::longrun::{LongrunRecord, LongrunSpec, longrun};
pub use stability::{StabilityRecord, stability};

pub use breakdown::Breakdown;

// What the records above hold, so that every field can be named.
pub use crate::ladder::{AutoLadder, Ladder, LadderChoice, LadderEnd, RungSize};
pub use crate::maths::fit::{Correction, OrderFit, PowerLaw};
pub use crate::maths::window::RoundOffModel;
pub use crate::run::Outcome;
pub use accuracy::invariants::{InvariantRecord, InvariantRung};
pub use accuracy::phase::PhaseSample;
pub use adaptive::record::{EnergyGrowth, Proportionality, RoundTrip};
pub use claims::{ClaimVerdict, ClaimsRecord, claims};
pub use cost::step_time::SchemeSpeed;
pub use cost::work_points::{Reach, TargetCost, WorkPoint};
pub use geometry::symplectic::TangentSample;
pub use hard::eccentric::{OrbitEnergy, OrderStatus, Pericentre};
pub use hard::escape::{Classification, Misclassified, OrbitRun};
pub use hard::following::{Event, FollowingRung, LineFit};
pub use round_off::floor::{Floor, PairRecord, RoundoffRung};
pub use round_off::longrun::{Conserved, ConservedQuantity};
pub use stability::{GrowthAt, GrowthLaw, GrowthSource};
pub use verdict::Verdict;
