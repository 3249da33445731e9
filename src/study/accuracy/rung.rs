//! What one rung of the order study's ladder records, and why a rung is
//! left out of the fit: the data the ladder (`order.rs`), the window
//! (`window.rs`) and the verdict (`order_verdict.rs`) share.

use crate::maths::window::DropReason;
use crate::run::Outcome;
use serde::Serialize;

/// One rung as measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Rung {
    /// The step used, `t_end / steps`.
    pub h: f64,
    /// Steps taken to `t_end`.
    pub steps: u64,
    /// Largest phase-space distance to the reference over the comparison
    /// times; `None` if the run (or its reference) blew up, or for a rung
    /// run only as a reference.
    pub error: Option<f64>,
    /// The distance at `t_end`.
    pub final_error: Option<f64>,
    /// The largest distance to the same scheme at half the step (the error
    /// itself without an exact solution): it falls whenever the scheme
    /// converges, to the exact solution or to anything else.
    pub half_step_difference: Option<f64>,
    /// The distance between this run and its twin started one unit of
    /// round-off away: a sample of the rung's round-off.
    pub round_off_sample: Option<f64>,
    /// The round-off bound the verdict uses: the round-off model's (`window.rs`) upper
    /// bound at this step count (plus the half step's, and the exact
    /// solution's own accuracy).
    pub round_off_bound: Option<f64>,
    /// `ln(e_prev / e) / ln(h_prev / h)` against the previous rung.
    pub local_order: Option<f64>,
    /// The rung is in the fitted window.
    pub used: bool,
    /// Why it is not, when it was judged.
    pub dropped: Option<DropReason>,
    /// How the run ended.
    pub outcome: Outcome,
    /// What an implicit scheme's solves reported over the run (iterations
    /// per step, largest residual); absent for a scheme that reports none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solve: Option<crate::scheme::SolveTally>,
}

/// A fall of the local order below the claim at the fine end of the clean
/// rungs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OrderReduction {
    /// The order the local orders fell from (the claim they reached).
    pub from: f64,
    /// The limit the finest local orders are heading for (at most).
    pub to: f64,
    /// The largest step at which the local order has left `from`'s plateau.
    pub sets_in_at: f64,
}

/// What a rung's error is measured against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reference {
    /// The scene's exact solution.
    Exact,
    /// The same scheme at half the step, for a scene without an exact
    /// solution (see the module documentation).
    HalfStep,
}
