//! Does the limit solve the scene's equations? On a scene without an exact
//! solution the order study compares each rung with the run at half its
//! step, which shows that the scheme converges, not to what: a force with a
//! wrong component converges at the claimed order to the solution of another
//! equation. What the exact flow conserves is the absolute truth left
//! ([`crate::scene::Invariant`]), and this study checks it on every rung.
//!
//! # The bound
//!
//! A run whose global error is `e(t)` (phase-space distance to the exact
//! solution) has, for an invariant `I` with sensitivity `S` (the norm of its
//! gradient in the same metric), `|I(x_h(t)) - I(x(0))| = |I(x_h(t)) -
//! I(x(t))| <= S e(t)` to first order, since `I(x(t)) = I(x(0))`. The run's
//! global error is estimated from the half-step difference
//! `d = max_t |x_h - x_(h/2)|`: in the asymptotic range `x_h - x = C h^p +
//! ...`, so `d = (1 - 2^-p) e` and `e <= d / (1 - 2^-lo)` for an order in
//! the fitted interval `[lo, hi]`. The change a solution of the scene's
//! equations allows at a rung is therefore
//!
//! ```text
//! allowed = max_t S(t) * d / (1 - 2^-lo) + R(N)
//! ```
//!
//! with `R(N)` the invariant's round-off at `N` steps: the distance between
//! the invariant along the rung and along its twin (the same run in other
//! units of length, rounded differently at every operation), fitted by the
//! same power law in `N` as the state's round-off and taken at its upper 95%
//! prediction bound ([`RoundOffModel`]). No factor is tuned: `S` is
//! Cauchy-Schwarz, `1 / (1 - 2^-lo)` the error estimate's own theory, `R`
//! measured. The bound is far from tight for a correct scheme (its error is
//! mostly a phase error along the flow, which conserved quantities do not
//! see), so it cannot raise a false alarm; it only has to be finite.
//!
//! A scheme that converges to the solution of another equation changes the
//! invariant by an amount that tends to a non-zero limit, while `d`, and so
//! the allowance, falls like `h^p`: at fine enough steps the change exceeds
//! the allowance. The verdict fails when it does at the two finest rungs
//! that have a half-step difference (one rung could be a chance sample of
//! round-off above its 95% bound).
//!
//! What this cannot see: a scheme that runs the exact flow at the wrong
//! speed (every weight of a composition scaled by `1 + 1e-8`, a step passed
//! through `f32`) conserves every invariant exactly as the true flow does;
//! only an exact solution, or a scene whose time scale is known, reveals it.

use crate::maths::window::RoundOffModel;
use crate::scene::Invariant;
use crate::study::verdict::Verdict;
use crate::wording::{figure, vs_upper};
use serde::Serialize;

/// One rung's account of one invariant.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct InvariantRung {
    /// The step.
    pub h: f64,
    /// Steps taken.
    pub steps: u64,
    /// Largest change `|I(x_n) - I(x_0)|` over the comparison times.
    pub change: f64,
    /// Largest sensitivity of the invariant along the run.
    pub sensitivity: f64,
    /// Largest distance between the invariant along the run and along its
    /// twin: a sample of its round-off.
    pub round_off_sample: Option<f64>,
    /// The rung's global error estimated from its half-step difference,
    /// `d / (1 - 2^-lo)`.
    pub error_estimate: Option<f64>,
    /// The invariant's round-off bound at this rung.
    pub round_off_bound: Option<f64>,
    /// What a solution of the scene's equations allows (see the module
    /// documentation), where the rung has a half-step difference and the
    /// order an interval.
    pub allowed: Option<f64>,
}

/// What the invariant study found for one invariant.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct InvariantRecord {
    /// The invariant.
    pub invariant: Invariant,
    /// Its round-off law fitted to the twins.
    pub round_off: Option<RoundOffModel>,
    /// Pass: the change stays within what a solution allows at the finest
    /// rungs; fail: it exceeds it at both; inconclusive: not judged (no
    /// order interval, no round-off law, or fewer than two rungs with a
    /// half-step difference).
    pub verdict: Verdict,
    /// Why, in one line.
    pub reason: String,
    /// Every measured rung, coarse to fine.
    pub rungs: Vec<InvariantRung>,
}

/// A rung's raw measurements, before the allowance is formed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct InvariantSample {
    pub(crate) h: f64,
    pub(crate) steps: u64,
    pub(crate) change: f64,
    pub(crate) sensitivity: f64,
    pub(crate) round_off_sample: Option<f64>,
    /// The rung's largest distance to its half step.
    pub(crate) half_step_difference: Option<f64>,
}

/// `1 / (1 - 2^-lo)`: how much larger than the half-step difference the
/// error can be for an order of at least `lo`; `None` for `lo <= 0`, where
/// the difference bounds nothing.
pub fn error_estimate_factor(lo: f64) -> Option<f64> {
    (lo > 0.0).then(|| 1.0 / (1.0 - 2f64.powf(-lo)))
}

/// Judges one invariant over a ladder's rungs (coarse to fine) given the
/// lower end of the order's interval.
pub(crate) fn judge_invariant(
    invariant: Invariant,
    samples: &[InvariantSample],
    order_lo: Option<f64>,
) -> InvariantRecord {
    let round_off = RoundOffModel::fit(
        &samples
            .iter()
            .filter_map(|s| Some((s.steps, s.round_off_sample?)))
            .collect::<Vec<_>>(),
    );
    let factor = order_lo.and_then(error_estimate_factor);
    let rungs: Vec<InvariantRung> = samples
        .iter()
        .map(|s| {
            let error_estimate = factor
                .zip(s.half_step_difference)
                .map(|(f, d)| f * d)
                .filter(|e| e.is_finite());
            let round_off_bound = round_off.map(|m| m.bound(s.steps));
            InvariantRung {
                h: s.h,
                steps: s.steps,
                change: s.change,
                sensitivity: s.sensitivity,
                round_off_sample: s.round_off_sample,
                error_estimate,
                round_off_bound,
                allowed: error_estimate
                    .zip(round_off_bound)
                    .map(|(e, r)| s.sensitivity * e + r),
            }
        })
        .collect();
    let name = invariant.name();
    let judged: Vec<&InvariantRung> = rungs.iter().filter(|r| r.allowed.is_some()).collect();
    let (verdict, reason) = match judged.get(judged.len().saturating_sub(2)..) {
        Some(&[a, b]) => {
            let over = |r: &InvariantRung| r.change > r.allowed.expect("judged");
            let limit = |r: &InvariantRung| {
                format!(
                    "at h = {} the {name} changes by {} over the run (sensitivity {} x error \
                     estimate {} + round-off {}, the most a solution of the scene's equations \
                     changes it by)",
                    figure(r.h),
                    vs_upper(r.change, "allowance", r.allowed.expect("judged")),
                    figure(r.sensitivity),
                    figure(r.error_estimate.expect("judged")),
                    figure(r.round_off_bound.expect("judged")),
                )
            };
            if over(a) && over(b) {
                (
                    Verdict::Fail,
                    format!(
                        "converges, but not to a solution of the scene's equations: the {name} \
                         does not return to its initial value as h -> 0: {}; at h = {}, {}",
                        limit(b),
                        figure(a.h),
                        vs_upper(a.change, "allowance", a.allowed.expect("judged")),
                    ),
                )
            } else {
                // the rung that is within its allowance (the finer if both)
                let within = if over(b) { a } else { b };
                (
                    Verdict::Pass,
                    format!("{name} conserved: {}", limit(within)),
                )
            }
        }
        _ => (
            Verdict::Inconclusive,
            format!(
                "{name} not judged: {}",
                if factor.is_none() {
                    "no order interval to estimate the error from"
                } else if round_off.is_none() {
                    "no round-off samples"
                } else {
                    "fewer than two rungs with a half-step difference"
                }
            ),
        ),
    };
    InvariantRecord {
        invariant,
        round_off,
        verdict,
        reason,
        rungs,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ladder(
        change: impl Fn(f64) -> f64,
        difference: impl Fn(f64) -> f64,
    ) -> Vec<InvariantSample> {
        (0..10)
            .map(|k| {
                let steps = 100u64 << k;
                let h = 1.0 / steps as f64;
                InvariantSample {
                    h,
                    steps,
                    change: change(h),
                    sensitivity: 2.0,
                    round_off_sample: Some(1e-16 * (steps as f64).sqrt()),
                    half_step_difference: Some(difference(h)),
                }
            })
            .collect()
    }

    #[test]
    fn the_error_estimate_factor_is_the_half_step_theory() {
        assert_eq!(error_estimate_factor(1.0), Some(2.0));
        assert!((error_estimate_factor(2.0).unwrap() - 4.0 / 3.0).abs() < 1e-15);
        assert_eq!(error_estimate_factor(0.0), None);
        assert_eq!(error_estimate_factor(-1.0), None);
    }

    #[test]
    fn a_change_that_falls_with_the_error_passes() {
        // second order: d = (3/4) C h^2, the change a tenth of S e
        let record = judge_invariant(
            Invariant::Energy,
            &ladder(|h| 0.1 * 2.0 * h * h, |h| 0.75 * h * h),
            Some(1.98),
        );
        assert_eq!(record.verdict, Verdict::Pass, "{}", record.reason);
    }

    #[test]
    fn a_change_that_tends_to_a_constant_fails() {
        let record = judge_invariant(
            Invariant::Momentum { axis: 0 },
            &ladder(|h| 1e-7 + h * h, |h| 0.75 * h * h),
            Some(1.98),
        );
        assert_eq!(record.verdict, Verdict::Fail, "{}", record.reason);
        assert!(record.reason.contains("converges, but not to a solution"));
        assert!(record.reason.contains("momentum-x"));
    }

    #[test]
    fn one_rung_over_its_allowance_is_not_enough() {
        // only the finest rung exceeds: a chance sample, not a limit
        let record = judge_invariant(
            Invariant::Energy,
            &ladder(|h| if h < 3e-5 { 1e-3 } else { 0.0 }, |h| 0.75 * h * h),
            Some(2.0),
        );
        assert_eq!(record.verdict, Verdict::Pass, "{}", record.reason);
        let finest = record.rungs.last().unwrap();
        assert!(finest.change > finest.allowed.unwrap());
    }

    #[test]
    fn no_interval_or_no_differences_leave_it_undecided() {
        let samples = ladder(|h| h, |h| h);
        assert_eq!(
            judge_invariant(Invariant::Energy, &samples, None).verdict,
            Verdict::Inconclusive
        );
        let mut without = samples.clone();
        without
            .iter_mut()
            .for_each(|s| s.half_step_difference = None);
        assert_eq!(
            judge_invariant(Invariant::Energy, &without, Some(1.0)).verdict,
            Verdict::Inconclusive
        );
    }

    #[test]
    fn round_off_raises_the_allowance() {
        // a change at the twins' level, far above S e at the finest rungs
        let samples: Vec<InvariantSample> = ladder(|_| 0.0, |h| 1e-3 * h.powi(4))
            .into_iter()
            .map(|mut s| {
                s.change = 0.9 * s.round_off_sample.unwrap();
                s
            })
            .collect();
        let record = judge_invariant(Invariant::Energy, &samples, Some(4.0));
        assert_eq!(record.verdict, Verdict::Pass, "{}", record.reason);
    }
}
