//! What the tolerance ladder records: each tolerance's run, the fitted
//! exponent, the energy and round-trip runs, and each claim's verdict; the
//! ladder fills it and the verdicts read it, so it sits below both.

use crate::maths::fit::{MIN_POINTS, OrderFit, PowerLaw};
use crate::scheme::{AdaptiveClaims, RunEnd};
use crate::study::cost::work_points::{TargetCost, targets_of};
use crate::study::geometry::energy::EnergyClass;
use crate::study::verdict::Verdict;
use serde::Serialize;

/// Fewest points the exponent is fitted to: the order fit's own minimum.
pub const MIN_FIT_POINTS: usize = MIN_POINTS;

/// One tolerance's run to `t_end`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TolerancePoint {
    /// The tolerance.
    pub tolerance: f64,
    /// Force evaluations, rejected steps and the first step's guess
    /// included.
    pub evaluations: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// How the run ended.
    pub end: RunEnd,
    /// Largest phase-space distance to the exact solution over the accepted
    /// steps; `None` without an exact solution or when the run did not
    /// finish.
    pub error: Option<f64>,
    /// The round-off the run can have made, `8 eps N scale`.
    pub round_off: f64,
    /// The point entered the exponent's fit.
    pub fitted: bool,
    /// What the integrator reported it spent, where it reports it apart
    /// from the counted `evaluations` (a black box's statistics).
    pub reported_evaluations: Option<u64>,
    /// Where the run broke down: its first accepted state that is not
    /// finite, or a panic in the integrator's code (see
    /// [`crate::study::breakdown`]); the exponent's claim fails on it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub breakdown: Option<String>,
}

/// The fitted exponent of `e ~ TOL^k` against its theory.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Proportionality {
    /// The fitted exponent.
    pub exponent: f64,
    /// Its 95% interval: the order fit's, over `m`.
    pub ci95: [f64; 2],
    /// The power `m` of `h` the estimate is assumed to follow: the fit is
    /// made in `x = TOL^(1/m)`.
    pub estimate_power: u32,
    /// The fit in `x`: its order is `m` times the exponent.
    pub fit: OrderFit,
    /// Loosest and tightest tolerance fitted.
    pub range: [f64; 2],
    /// The exponent theory predicts for the controller, if one.
    pub theory: Option<f64>,
    /// Where the exponent misses the prediction: the order the method
    /// itself shows at fixed steps over the same step counts (fitted in
    /// `h = t_end / N`), which separates a method not yet at its asymptotic
    /// order from a controller that misses its claim.
    pub method_order: Option<OrderFit>,
    /// Beside it, the accepted steps against the tolerance, `N ~ TOL^s`:
    /// the controller's claim is `s = -1/m`.
    pub step_scaling: Option<PowerLaw>,
    /// And the adaptive error over the fixed-step error at the same step
    /// count against the tolerance, `r ~ TOL^rho`: `rho` is 0 once the
    /// controller's distribution of steps over the run has settled, so the
    /// exponent is `-p s + rho` with `p` the method's order (see the
    /// module documentation of the ladder).
    pub error_ratio: Option<PowerLaw>,
}

impl Proportionality {
    /// The theory lies in the interval (true where none is predicted).
    pub fn agrees(&self) -> bool {
        self.theory
            .is_none_or(|k| self.ci95[0] <= k && k <= self.ci95[1])
    }
}

/// The energy error of a long run at a fixed tolerance.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EnergyGrowth {
    /// The tolerance.
    pub tolerance: f64,
    /// Length of the run, in periods.
    pub periods: f64,
    /// Force evaluations of the run.
    pub evaluations: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// How the run ended.
    pub end: RunEnd,
    /// Largest `|E - E0| / norm` over the run.
    pub max_error: f64,
    /// Exponent `g` of `max |E - E(T)| ~ t^g` over the last decades.
    pub growth_exponent: Option<f64>,
    /// Its class; growth within round-off is a random walk whatever `g`.
    pub class: Option<EnergyClass>,
}

/// A round trip: to `t_end`, velocities reversed, on for `t_end` again,
/// velocities reversed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RoundTrip {
    /// The tolerance.
    pub tolerance: f64,
    /// Length of each leg.
    pub t_end: f64,
    /// Phase-space distance of the return to the start; `None` when a leg
    /// did not finish.
    pub distance: Option<f64>,
    /// The most round-off alone could make of it (the reversibility
    /// study's bound, `16 eps N scale`).
    pub round_off: f64,
    /// The return is within round-off.
    pub returns: bool,
}

/// The tolerance ladder of one adaptive integrator on one scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ToleranceLadderRecord {
    /// The integrator's name.
    pub integrator: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// What the integrator's theory predicts.
    pub claims: AdaptiveClaims,
    /// End time of the global-error runs.
    pub t_end: f64,
    /// Every tolerance, loosest first.
    pub points: Vec<TolerancePoint>,
    /// The exponent, when enough points are clean.
    pub proportionality: Option<Proportionality>,
    /// The long energy run.
    pub energy: Option<EnergyGrowth>,
    /// The round trip.
    pub round_trip: Option<RoundTrip>,
    /// Each claim against its measurement, in the order of
    /// [`AdaptiveClaim`]'s variants (a claim with nothing to judge is
    /// absent).
    pub judged: Vec<JudgedClaim>,
    /// All claims together: a failure if any failed, else inconclusive if
    /// any was, else a pass.
    pub verdict: Verdict,
    /// Why, in one line: the judged claims' reasons in turn.
    pub reason: String,
}

/// One claim an adaptive integrator is judged on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AdaptiveClaim {
    /// The global error follows `TOL^(p/(q+1))`.
    Exponent,
    /// The global error stays within the stated factor of the tolerance.
    ErrorFactor,
    /// The accepted steps grow no faster than the controller allows.
    Cost,
    /// What the integrator reports it spent equals the calls counted.
    Evaluations,
    /// The energy of a long run, against a symplecticity or symmetry claim.
    Energy,
    /// The round trip, against a symmetry claim.
    RoundTrip,
}

impl AdaptiveClaim {
    /// Every claim, in the order the ladder judges them.
    pub const ALL: [AdaptiveClaim; 6] = [
        AdaptiveClaim::Exponent,
        AdaptiveClaim::ErrorFactor,
        AdaptiveClaim::Cost,
        AdaptiveClaim::Evaluations,
        AdaptiveClaim::Energy,
        AdaptiveClaim::RoundTrip,
    ];

    /// Its name in test names and messages.
    pub fn name(self) -> &'static str {
        match self {
            AdaptiveClaim::Exponent => "exponent",
            AdaptiveClaim::ErrorFactor => "error factor",
            AdaptiveClaim::Cost => "cost",
            AdaptiveClaim::Evaluations => "evaluations",
            AdaptiveClaim::Energy => "energy",
            AdaptiveClaim::RoundTrip => "round trip",
        }
    }
}

/// One claim's verdict with its figures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct JudgedClaim {
    /// The claim.
    pub claim: AdaptiveClaim,
    /// Pass, fail or inconclusive.
    pub verdict: Verdict,
    /// Why, with the figures.
    pub reason: String,
}

impl ToleranceLadderRecord {
    /// The verdict on one claim, if it had anything to judge.
    pub fn claim(&self, claim: AdaptiveClaim) -> Option<&JudgedClaim> {
        self.judged.iter().find(|j| j.claim == claim)
    }

    /// The force evaluations to reach each of the work-precision study's
    /// target global errors ([`crate::study::cost::work_points::TARGETS`]),
    /// interpolated between the tolerances that bracket each, as for the
    /// catalogue's step ladders and the peer.
    pub fn global_targets(&self) -> Vec<TargetCost> {
        let data: Vec<(f64, Option<f64>)> = self
            .points
            .iter()
            .map(|p| (p.evaluations as f64, p.error))
            .collect();
        targets_of(&data)
    }

    /// The point at this tolerance, if the ladder has it.
    pub fn at(&self, tolerance: f64) -> Option<&TolerancePoint> {
        self.points
            .iter()
            .find(|p| (p.tolerance / tolerance - 1.0).abs() < 1e-9)
    }
}
