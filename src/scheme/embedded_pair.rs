//! The crate's own adaptive integrators: embedded Runge-Kutta-Nyström
//! pairs with a predictive step-size controller (Hairer, Nørsett, Wanner I,
//! II.4 and II, IV.2).
//!
//! Each step is tried with the main (order `p`) and the embedded (order `q`)
//! solution from the same stages; their difference `err` estimates the
//! embedded solution's local error, `C h^(q+1)`. Measured in the scaled
//! root-mean-square norm `||e|| = sqrt(mean_i (e_i / sc_i)^2)`, `sc_i = tol
//! (1 + max(|y0_i|, |y1_i|))`, the step is accepted when `||err|| <= 1` and
//! the run continues with the main solution (local extrapolation). Either
//! way the standard next step is
//!
//! `h_new = h min(max_growth, max(max_shrink, safety ||err||^(-1/(q+1))))`,
//!
//! the step at which the estimate would equal `safety^(q+1)` of the
//! tolerance if `C` stayed put. The constants are the textbook ones:
//!
//! - `safety = 0.9` (HNW I, (4.13)): the estimate then aims at `0.9^5 = 0.59`
//!   of the tolerance for DPRKN6(4), so that the variation of `C` from one
//!   step to the next rarely pushes a step over and wastes its stages;
//! - `max_growth = 5` (HNW's advice: between 1.5 and 5), so one step where
//!   the estimate happens to be small (a near-zero of its leading term)
//!   cannot launch a step that the next estimate must undo, and `1` right
//!   after a rejection (HNW), when the estimate has just proved optimistic;
//! - `max_shrink = 0.2`: a rejected step is retried at no less than a fifth,
//!   which for a fifth-power estimate is `0.2^5 = 3e-4` of its error, enough
//!   for any smooth change and still a bounded retreat where the estimate is
//!   non-finite.
//!
//! After the second and later accepted steps the pairs take the smaller of
//! that step and Gustafsson's predicted one (HNW II, IV.2, (2.43); RADAU5
//! does the same):
//!
//! `h_new = h safety ||err_n||^(-1/(q+1)) (h_n / h_(n-1)) (||err_(n-1)|| /
//! ||err_n||)^(1/(q+1))`,
//!
//! with `n - 1` the accepted step before. The standard step assumes `C`
//! stays put; the predicted one extrapolates how `C` moved over the last
//! accepted step (`C_n / C_(n-1)`, read off the two estimates and steps) one
//! step further. Taking the smaller shortens a step only where `C` is
//! growing, which is where the standard step is rejected: on an orbit that
//! falls towards pericentre, and where the estimate swings from step to
//! step as the outer solar system's does at 800-day steps. Where `C` stays
//! put the two agree, so the controller settles at the same fixed point,
//! `||err|| = safety^(q+1)`, and the tolerance proportionality below holds
//! unchanged. Both estimates are taken no smaller than `(safety /
//! max_growth)^(q+1)`, the estimate at which the standard step reaches its
//! cap: below it an estimate no longer steers the step (the cap does), and
//! a near-zero estimate would otherwise predict an arbitrarily steep rise of
//! `C` on the step after it. Measured with DPRKN6(4), DPRKN8(6) and
//! RKN12(10) on both Kepler orbits, the Pleiades and the outer solar system
//! from `1e-6` to `1e-14`, eight tolerances a decade: the evaluations to
//! reach a given error fell by up to a fifth (the eccentric orbit and the
//! Pleiades) and rose beyond the scatter nowhere.
//!
//! The first step is the motion's own time scale, and the pair's estimate
//! corrects it (see `first_trial` below): the trial is `||y0|| /
//! ||f(y0)||`, the time in which the state would change by its own size,
//! each block (positions, velocities) measured by its Euclidean length so
//! that the scale does not depend on how the axes are turned, and when the
//! estimate rejects it, the retry is at the step the estimate asks for,
//! `safety ||err||^(-1/(q+1))` of the trial, however far below a fifth
//! (down to [`FIRST_RETRY_FLOOR`]). The `0.2` limit guards a run whose step
//! is already about right against one odd estimate; the first trial has no
//! such history. A trial shorter than the step `h*` the estimate allows
//! wastes the fraction `1 - h0/h*` of a step (and a second short step below
//! `h*/5`, where growth is capped); a longer one wastes one rejected step.
//! So the trial costs at most about one step whichever side of `h*` it
//! falls, as long as it is not far below it.
//!
//! With compensated sums ([`EmbeddedPair::with_compensated_sums`]) the
//! state is carried as `value + low` and each step's increments are added
//! by Knuth's TwoSum ([`crate::scheme::Kahan`]): the step no longer loses
//! `eps |q|` each time it adds a small increment to a large coordinate,
//! which is what stops an uncompensated pair's error from falling below
//! about `eps |q| sqrt(steps)` however tight the tolerance.
//!
//! The exponent `1/(q+1)` is the one the estimate's power dictates. It
//! sets how fast the feedback settles, not where: whatever the exponent,
//! the accepted steps settle where the estimate is a fixed fraction of the
//! tolerance, so the step scales like `TOL^(1/(q+1))` and the global error
//! like `TOL^(p/(q+1))`. The claimed proportionality is therefore derived
//! from the controller's exponent (what the controller assumes of its
//! estimate): a controller built with `1/p`, or an estimate from wrong
//! embedded weights (whose power is then not `q+1`), claims an exponent
//! the tolerance ladder refutes (see the tests).

use super::adaptive::{
    AdaptiveClaims, AdaptiveIntegrator, AdaptiveRun, RunEnd, check_request,
    proportionality_exponent,
};
use crate::error::Error;
use crate::scene::Scene;
use crate::scheme::{DPRKN6, DPRKN8, DPRKN12, Kahan, NystromTable, SchemeVisitor, Summed};
use crate::state::State;
use std::time::Instant;

/// Most steps (accepted and rejected) one run may take.
pub const MAX_STEPS: u64 = 2_000_000;

/// The smallest ratio of the retry to a rejected first trial. The trial is
/// the motion's time scale; an estimate asking for less than `1e-4` of it
/// (an error `1e4^(q+1)` times the tolerance) is far outside the range where
/// it behaves like `h^(q+1)`, and a second retry from `1e-4` of the scale
/// costs one step where a step too small for good would cost many.
pub const FIRST_RETRY_FLOOR: f64 = 1e-4;

/// The step-size controller's constants (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Controller {
    /// The factor on the optimal step.
    pub safety: f64,
    /// Largest ratio of a step to the one before.
    pub max_growth: f64,
    /// Smallest ratio of a step to the one before.
    pub max_shrink: f64,
    /// The exponent of the error ratio, `1/(q+1)` for an estimate `~ h^(q+1)`.
    pub exponent: f64,
    /// Whether an accepted step's successor is also held to Gustafsson's
    /// predicted step (see the module documentation).
    pub predictive: bool,
}

/// An accepted step and its scaled estimate: what the predictive
/// controller extrapolates from.
#[derive(Clone, Copy, Debug, PartialEq)]
struct AcceptedStep {
    step: f64,
    err: f64,
}

impl Controller {
    /// The standard controller for an estimate behaving like
    /// `h^estimate_power`.
    pub const fn standard(estimate_power: u32) -> Self {
        Self {
            safety: 0.9,
            max_growth: 5.0,
            max_shrink: 0.2,
            exponent: 1.0 / estimate_power as f64,
            predictive: false,
        }
    }

    /// The standard controller held also to Gustafsson's predicted step:
    /// the pairs' controller.
    pub const fn predictive(estimate_power: u32) -> Self {
        Self {
            predictive: true,
            ..Self::standard(estimate_power)
        }
    }

    /// The ratio of the next step to the step `h` just accepted with
    /// estimate `err`, given the accepted step before it (none for the
    /// first), capped at `growth_cap`.
    fn accepted_ratio(
        &self,
        err: f64,
        h: f64,
        before: Option<AcceptedStep>,
        growth_cap: f64,
    ) -> f64 {
        let standard = self.ratio(err, growth_cap);
        let Some(before) = before.filter(|_| self.predictive) else {
            return standard;
        };
        // the estimate at which the standard step reaches its cap
        let floor = (self.safety / self.max_growth).powf(1.0 / self.exponent);
        let now = err.max(floor);
        let then = before.err.max(floor);
        let predicted = self.safety * (h / before.step) * (then / now).powf(self.exponent)
            / now.powf(self.exponent);
        standard.min(predicted.clamp(self.max_shrink, growth_cap))
    }

    /// The ratio of the next step to this one after an estimate `err`
    /// (scaled: 1 is the tolerance), capped at `growth_cap`.
    fn ratio(&self, err: f64, growth_cap: f64) -> f64 {
        if !err.is_finite() {
            return self.max_shrink;
        }
        let optimal = self.safety * err.powf(-self.exponent);
        optimal.clamp(self.max_shrink, growth_cap)
    }

    /// The ratio of the retry to a rejected first trial: the step the
    /// estimate asks for, below a fifth if need be, no less than
    /// [`FIRST_RETRY_FLOOR`]; a non-finite estimate retreats by
    /// `max_shrink` as any other.
    fn first_retry_ratio(&self, err: f64) -> f64 {
        if !err.is_finite() {
            return self.max_shrink;
        }
        (self.safety * err.powf(-self.exponent)).clamp(FIRST_RETRY_FLOOR, 1.0)
    }
}

/// An embedded Runge-Kutta-Nyström pair driven by a [`Controller`].
#[derive(Clone, Copy, Debug)]
pub struct EmbeddedPair<const S: usize> {
    /// Name in tables.
    pub name: &'static str,
    /// The tableau; it must carry an embedded solution.
    pub table: &'static NystromTable<S>,
    /// The controller.
    pub controller: Controller,
    /// Whether the state's updates are compensated sums.
    pub compensated: bool,
}

/// Dormand and Prince's RKN6(4) with the predictive controller.
pub const DPRKN6_ADAPTIVE: EmbeddedPair<6> = EmbeddedPair::new("DPRKN6(4) adaptive", &DPRKN6);

/// Dormand, El-Mikkawy and Prince's RKN8(6) with the predictive controller:
/// eight force evaluations a step for order eight, against the twelve of
/// DOP853 on `(q, v)`.
pub const DPRKN8_ADAPTIVE: EmbeddedPair<9> = EmbeddedPair::new("DPRKN8(6) adaptive", &DPRKN8);

/// DPRKN8(6) with compensated state updates.
pub const DPRKN8_COMPENSATED: EmbeddedPair<9> =
    EmbeddedPair::new("DPRKN8(6) compensated", &DPRKN8).with_compensated_sums();

/// Dormand, El-Mikkawy and Prince's RKN12(10) with the predictive controller:
/// seventeen force evaluations a step for order twelve.
pub const DPRKN12_ADAPTIVE: EmbeddedPair<17> = EmbeddedPair::new("DPRKN12(10) adaptive", &DPRKN12);

/// RKN12(10) with compensated state updates: the pair for tolerances near
/// the round-off of the state.
pub const DPRKN12_COMPENSATED: EmbeddedPair<17> =
    EmbeddedPair::new("DPRKN12(10) compensated", &DPRKN12).with_compensated_sums();

impl<const S: usize> EmbeddedPair<S> {
    /// The pair of `table` with the predictive controller for its estimate.
    /// A table without an embedded solution is refused at compile time.
    pub const fn new(name: &'static str, table: &'static NystromTable<S>) -> Self {
        let Some(embedded) = table.embedded else {
            panic!("an adaptive pair needs an embedded solution")
        };
        Self {
            name,
            table,
            controller: Controller::predictive(embedded.order + 1),
            compensated: false,
        }
    }

    /// The same pair with its state carried as compensated sums.
    pub const fn with_compensated_sums(self) -> Self {
        Self {
            compensated: true,
            ..self
        }
    }
}

/// The scaled RMS norm of `e` against `tol (1 + max(|y0_i|, |y1_i|))`.
fn scaled_norm<const D: usize>(e: &State<D>, y0: &State<D>, y1: &State<D>, tol: f64) -> f64 {
    let mut sum = 0.0;
    let parts = [(&e.q, &y0.q, &y1.q), (&e.v, &y0.v, &y1.v)];
    for (e, a, b) in parts {
        for i in 0..D {
            let sc = tol * (1.0 + a[i].abs().max(b[i].abs()));
            sum += (e[i] / sc).powi(2);
        }
    }
    (sum / (2 * D) as f64).sqrt()
}

impl<const S: usize> EmbeddedPair<S> {
    /// The first step to try: `||y0|| / ||f(y0)||`, the time in which the
    /// state would change by its own size (HNW I, II.4: `100 h0`, their
    /// starting step's upper bound), or `1e-4` when the state or its rate is
    /// too small to measure (their `h0 = 1e-6`), no longer than the run. No
    /// force evaluation.
    ///
    /// The norm is the scaled one with each block's length in place of each
    /// component's: every position component weighs `1 / (TOL (1 + |q0|))`
    /// and every velocity component `1 / (TOL (1 + |v0|))`, with `|.|` the
    /// Euclidean length of the block. A motion's time scale does not depend
    /// on the orientation of the axes, and per component it does: a
    /// component passing through zero is measured against the absolute unit
    /// of the tolerance, and its rate then sets the scale. The circular
    /// orbit started on the x axis (`v0_x = 0`, `a0_x = -4 pi^2`) gave 0.025
    /// of a year that way, and the same orbit started at 45 degrees 0.159,
    /// its `1 / omega`; with block lengths both give `1 / omega` exactly
    /// (`|v0| = omega |q0|`, `|a0| = omega |v0|`). DPRKN12(10) then steps
    /// 0.36 of a year at tolerance `1e-6`, and the trial of 0.025 had cost
    /// it two steps short of that (0.025, and 0.125 where growth is capped
    /// at five).
    ///
    /// HNW's own guess, `h1 = (0.01 / max(||f0||, ||f'||))^(1/(q+1))`, is not
    /// used: it takes the local error of a step `h` to be about `h^(q+1)`
    /// times the state's first or second derivative, which holds in units
    /// where the motion's time scale is one. In units where it is `tau`, the
    /// `(q+1)`-th derivative is `tau^(q-1)` times smaller than the second,
    /// and the guess that much too short: on the outer solar system in days
    /// (`tau` about 700 days) DPRKN12(10)'s first step at tolerance `1e-12`
    /// was 0.7 days, and growth by at most five a step took five steps to
    /// reach the 400-day steps its estimate allows.
    fn first_trial<const D: usize>(
        &self,
        y0: &State<D>,
        a0: &nalgebra::SVector<f64, D>,
        tol: f64,
        t_end: f64,
    ) -> f64 {
        // block weights; the mean over the 2D components cancels in d0 / d1
        // but is kept so that the thresholds below read as in the error norm
        let wq = 1.0 / (tol * (1.0 + y0.q.norm()));
        let wv = 1.0 / (tol * (1.0 + y0.v.norm()));
        let mean = |q: f64, v: f64| ((q * wq).powi(2) + (v * wv).powi(2)) / (2 * D) as f64;
        let d0 = mean(y0.q.norm(), y0.v.norm()).sqrt();
        let d1 = mean(y0.v.norm(), a0.norm()).sqrt();
        let scale = if d0 < 1e-5 || d1 < 1e-5 {
            1e-4
        } else {
            d0 / d1
        };
        scale.min(t_end)
    }
}

impl<const S: usize> EmbeddedPair<S> {
    /// The estimate the controller would weigh for one step of `h` from
    /// `state`, in units of the tolerance `tol`: a step is accepted when it
    /// is at most 1. It is that of the plain state update; compensated sums
    /// change the state by a rounding, not the estimate. It costs a step's
    /// force evaluations: it is for studying a controller along a
    /// trajectory, not for running one.
    ///
    /// ```
    /// use stepladder::scene::{KeplerCircular, Scene};
    /// use stepladder::scheme::DPRKN12_ADAPTIVE;
    /// let scene = KeplerCircular;
    /// // a quarter of the period is too long a step at TOL 1e-9 and short
    /// // enough at 1e-6
    /// let quarter = 0.25 * scene.period();
    /// assert!(DPRKN12_ADAPTIVE.estimate(&scene, &scene.initial(), quarter, 1e-9) > 1.0);
    /// assert!(DPRKN12_ADAPTIVE.estimate(&scene, &scene.initial(), quarter, 1e-6) < 1.0);
    /// ```
    pub fn estimate<P: Scene<D>, const D: usize>(
        &self,
        scene: &P,
        state: &State<D>,
        h: f64,
        tol: f64,
    ) -> f64 {
        let step = self
            .table
            .attempt(scene, state, scene.acceleration(&state.q), h);
        scaled_norm(&step.error, state, &step.state, tol)
    }
}

impl<const S: usize> AdaptiveIntegrator for EmbeddedPair<S> {
    fn name(&self) -> &'static str {
        self.name
    }

    fn claims(&self) -> AdaptiveClaims {
        let p = self.table.meta.order;
        // the power of h the controller assumes its estimate follows
        let power = (1.0 / self.controller.exponent).round() as u32;
        AdaptiveClaims {
            order: p,
            estimate_power: power,
            proportionality: Some(proportionality_exponent(p, power)),
            symplectic: self.table.meta.symplectic,
            symmetric: self.table.meta.symmetric,
            error_factor: None,
        }
    }

    fn visit_fixed_step<V: SchemeVisitor>(&self, visitor: V) -> Option<V::Output> {
        Some(visitor.visit(self.table))
    }

    fn integrate<P: Scene<D>, const D: usize>(
        &self,
        scene: &P,
        start: &State<D>,
        t_end: f64,
        tol: f64,
    ) -> Result<AdaptiveRun<D>, Error> {
        check_request(t_end, tol)?;
        let clock = Instant::now();
        let fsal = self.table.first_same_as_last();
        let mut y = *start;
        // what rounding y dropped, with compensated sums (else zero)
        let mut low = State::new(nalgebra::SVector::zeros(), nalgebra::SVector::zeros());
        let mut a = scene.acceleration(&y.q);
        let mut evaluations = 1u64;
        let mut h = self.first_trial(&y, &a, tol, t_end);
        let mut run = AdaptiveRun {
            trajectory: vec![(0.0, y)],
            evaluations: 0,
            accepted: 0,
            rejected: 0,
            end: RunEnd::Reached,
            time: Default::default(),
            reported_evaluations: None,
        };
        let mut t = 0.0;
        let mut just_rejected = false;
        let mut before: Option<AcceptedStep> = None;
        while t < t_end {
            if run.accepted + run.rejected >= MAX_STEPS {
                run.end = RunEnd::StepLimit;
                break;
            }
            // the last step lands on t_end; a step within 1% of the rest is
            // stretched to it rather than leaving a sliver
            let last = t + 1.01 * h >= t_end;
            // the step ends on a double and is that double less `t`: exact
            // once `t >= h` (Sterbenz), so the state is the solution at the
            // time it is recorded with, and no rounding of `t + h`
            // accumulates in the clock (at the eccentric orbit's pericentre
            // half an ulp of t = 2 is 9e-15 of phase-space distance)
            let t_next = if last { t_end } else { t + h };
            if t_next == t {
                run.end = RunEnd::StepUnderflow;
                break;
            }
            h = t_next - t;
            let trial = if self.compensated {
                let mut q = Summed {
                    value: y.q,
                    low: low.q,
                };
                let mut v = Summed {
                    value: y.v,
                    low: low.v,
                };
                let step = self
                    .table
                    .attempt_summed::<Kahan, f64, D, P>(scene, &mut q, &mut v, a, h);
                (
                    State::new(q.value, v.value),
                    State::new(q.low, v.low),
                    step.a_end,
                    step.error,
                )
            } else {
                let step = self.table.attempt(scene, &y, a, h);
                (step.state, low, step.a_end, step.error)
            };
            let (state, new_low, a_end, error) = trial;
            evaluations += S as u64 - 1;
            let err = scaled_norm(&error, &y, &state, tol);
            let finite = state.is_finite();
            if err <= 1.0 && finite {
                let cap = if just_rejected {
                    1.0
                } else {
                    self.controller.max_growth
                };
                t = t_next;
                y = state;
                low = new_low;
                a = if fsal {
                    a_end
                } else {
                    evaluations += 1;
                    scene.acceleration(&y.q)
                };
                run.trajectory.push((t, y));
                run.accepted += 1;
                let ratio = self.controller.accepted_ratio(err, h, before, cap);
                before = Some(AcceptedStep { step: h, err });
                h *= ratio;
                just_rejected = false;
            } else {
                run.rejected += 1;
                let err = if finite { err } else { f64::INFINITY };
                h *= if run.accepted == 0 {
                    self.controller.first_retry_ratio(err)
                } else {
                    self.controller.ratio(err, 1.0)
                };
                just_rejected = true;
            }
        }
        run.evaluations = evaluations;
        run.time = clock.elapsed();
        Ok(run)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Counted, KeplerCircular, KeplerEccentric};

    /// Each step ends on a double and is that double less `t`, so a state
    /// is the solution at the time it is recorded with. Summing `t + h`
    /// instead rounds the clock by up to half an ulp a step (`2.2e-16` for
    /// `t` in [2, 4)); over the two hundred-odd steps of the compensated
    /// pair on the circular orbit to `t = 2 sqrt(2)` that walks to some
    /// `2e-15` of time, `1.6e-14` of phase-space distance at the orbit's
    /// phase-space speed `2 pi sqrt(2)`. The compensated state's own
    /// round-off is a few `1e-16`: the largest error over the run stays below
    /// `1e-14` only with the clock exact (measured: 1.5e-15, and 1.7e-14
    /// with `t + h`).
    #[test]
    fn states_are_at_the_times_they_are_recorded_with() {
        let scene = KeplerCircular;
        let run = DPRKN8_COMPENSATED
            .run(&scene, scene.default_t_end(), 1e-12)
            .unwrap();
        assert_eq!(run.end, RunEnd::Reached);
        let worst = run
            .trajectory
            .iter()
            .map(|(t, s)| scene.phase_distance(s, &scene.exact(*t).unwrap()))
            .fold(0.0f64, f64::max);
        assert!(worst < 1e-14, "largest error {worst:e}");
    }

    /// A rejected first trial is retried at the step its estimate asks for:
    /// `0.9 err^(-1/5)` for a fifth-power estimate, below a fifth when the
    /// estimate is far over, down to the floor; a later rejection never
    /// retreats by more than a fifth.
    #[test]
    fn a_rejected_first_trial_is_retried_where_its_estimate_points() {
        let c = Controller::standard(5);
        assert!((c.first_retry_ratio(1e10) - 0.9e-2).abs() < 1e-15);
        assert_eq!(c.first_retry_ratio(1e40), FIRST_RETRY_FLOOR);
        assert_eq!(c.first_retry_ratio(0.5), 1.0);
        assert_eq!(c.first_retry_ratio(f64::INFINITY), c.max_shrink);
        assert_eq!(c.ratio(1e10, 1.0), c.max_shrink);
    }

    /// The first trial on the circular orbit is its `1 / omega = 1 / (2 pi)`
    /// of a year, whatever the tolerance: `|v0| = omega |q0|` and `|a0| =
    /// omega |v0|`, so the rate's norm is `omega` times the state's. No
    /// longer than the run; `1e-4` where the state or its rate is too small
    /// to measure.
    #[test]
    fn the_first_trial_is_the_states_size_over_its_rate() {
        let scene = KeplerCircular;
        let y0 = scene.initial();
        let a0 = scene.acceleration(&y0.q);
        let expected = 1.0 / (2.0 * std::f64::consts::PI);
        for tol in [1e-6, 1e-14] {
            let trial = DPRKN6_ADAPTIVE.first_trial(&y0, &a0, tol, 10.0);
            assert!((trial / expected - 1.0).abs() < 1e-12, "{trial} {expected}");
        }
        assert_eq!(DPRKN6_ADAPTIVE.first_trial(&y0, &a0, 1e-10, 0.01), 0.01);
        // at the eccentric orbit's pericentre the blocks' own scales differ
        // (`|q|/|v| = 0.032`, `|v|/|a| = 0.051`), and the trial weighs them
        // by the blocks' lengths: `r = 0.4`, `v = 4 pi`, `a = 4 pi^2 / r^2`
        let scene = KeplerEccentric::default();
        let (y0, a0) = (scene.initial(), scene.acceleration(&scene.initial().q));
        let (r, v) = (0.4, 4.0 * std::f64::consts::PI);
        let a = std::f64::consts::PI.powi(2) * 4.0 / (r * r);
        let expected = (((r / (1.0 + r)).powi(2) + (v / (1.0 + v)).powi(2))
            / ((v / (1.0 + r)).powi(2) + (a / (1.0 + v)).powi(2)))
        .sqrt();
        let trial = DPRKN6_ADAPTIVE.first_trial(&y0, &a0, 1e-8, 10.0);
        assert!((trial / expected - 1.0).abs() < 1e-12, "{trial} {expected}");
        // too small to measure means a root mean square of the scaled
        // components below 1e-5: here 0.8e-5 (their root sum square, twice
        // that, would be measured)
        let x = 1.6e-5 / (1.0 - 1.6e-5);
        let tiny = State::new(
            nalgebra::SVector::from([x, 0.0]),
            nalgebra::SVector::zeros(),
        );
        let pull = nalgebra::SVector::from([-1.0, 0.0]);
        assert_eq!(DPRKN6_ADAPTIVE.first_trial(&tiny, &pull, 1.0, 10.0), 1e-4);
        let rest = State::new(nalgebra::SVector::zeros(), nalgebra::SVector::zeros());
        let zero = nalgebra::SVector::<f64, 2>::zeros();
        assert_eq!(DPRKN6_ADAPTIVE.first_trial(&rest, &zero, 1e-10, 10.0), 1e-4);
        // at rest at the origin but pushed: a rate and no size, whose
        // quotient, zero, is no step
        let push = nalgebra::SVector::from([1.0, 0.0]);
        assert_eq!(DPRKN6_ADAPTIVE.first_trial(&rest, &push, 1e-10, 10.0), 1e-4);
        // at rest away from the origin with no force: no rate to measure
        let still = State::new(nalgebra::SVector::from([1.0, 0.0]), zero);
        assert_eq!(
            DPRKN6_ADAPTIVE.first_trial(&still, &zero, 1e-10, 10.0),
            1e-4
        );
    }

    /// Turning the axes turns every body's position, velocity and force
    /// alike and leaves the first trial where it was. Per component it did
    /// not: the circular orbit started on the x axis got 0.0249 of a year
    /// (its `v0_x = 0` measured against the tolerance's absolute unit), the
    /// same orbit started at 45 degrees 0.159.
    #[test]
    fn the_first_trial_does_not_depend_on_the_orientation_of_the_axes() {
        fn turned<const D: usize>(
            x: &nalgebra::SVector<f64, D>,
            angle: f64,
        ) -> nalgebra::SVector<f64, D> {
            let (s, c) = angle.sin_cos();
            let mut out = *x;
            for body in 0..D / 2 {
                let (a, b) = (x[2 * body], x[2 * body + 1]);
                out[2 * body] = c * a - s * b;
                out[2 * body + 1] = s * a + c * b;
            }
            out
        }
        fn check<P: Scene<D>, const D: usize>(scene: &P) {
            let y0 = scene.initial();
            let a0 = scene.acceleration(&y0.q);
            let trial = DPRKN8_ADAPTIVE.first_trial(&y0, &a0, 1e-9, 1e9);
            for angle in [0.3, std::f64::consts::FRAC_PI_4, 2.0, -1.1] {
                let y = State::new(turned(&y0.q, angle), turned(&y0.v, angle));
                let a = scene.acceleration(&y.q);
                let t = DPRKN8_ADAPTIVE.first_trial(&y, &a, 1e-9, 1e9);
                assert!((t / trial - 1.0).abs() < 1e-12, "{angle}: {t} {trial}");
            }
        }
        check(&KeplerCircular);
        check(&KeplerEccentric::default());
        check(&crate::scene::Pleiades::default());
    }

    /// On the circular orbit the first trial is `1 / (2 pi) = 0.159` of a
    /// year, and DPRKN6(4) at tolerance `1e-14` steps `t_end / 3189 =
    /// 8.9e-4`, 179 times shorter: the trial's estimate is about `0.59 *
    /// 179^5 = 1e11` times the tolerance. Retreats by a fifth would need four
    /// rejections (`0.2^3 = 0.008 > 1/179`); the estimate's own step needs
    /// one, two where the trial is outside the estimate's asymptotic range.
    /// The orbit needs no other rejection.
    #[test]
    fn the_first_step_costs_at_most_two_rejections_on_the_circular_orbit() {
        let scene = KeplerCircular;
        let run = DPRKN6_ADAPTIVE
            .run(&scene, scene.default_t_end(), 1e-14)
            .unwrap();
        assert_eq!(run.end, RunEnd::Reached);
        assert!(run.rejected <= 2, "{} rejections", run.rejected);
    }

    /// The circular orbit is the same seen from any point of it, turned.
    /// The scaled norm weighs each component by `1 / (1 + |y_i|)`, which a
    /// quarter turn permutes with the components (`(x, y) -> (-y, x)`), so
    /// the estimate from the state a quarter period on is the same number;
    /// other turns move the weights within `[1 / (1 + |block|), 1]`, so
    /// along the orbit it varies by at most `1 + |v| = 1 + 2 pi`. The step,
    /// a quarter period, puts the estimate (some `1e-8`) far above the
    /// round-off of the two solutions it is the difference of.
    #[test]
    fn the_estimate_is_the_controllers_and_has_the_orbits_symmetry() {
        let scene = KeplerCircular;
        let period = scene.period();
        let at = |t: f64| {
            DPRKN12_ADAPTIVE.estimate(&scene, &scene.exact(t).unwrap(), 0.25 * period, 1.0)
        };
        let along: Vec<f64> = (0..16).map(|k| at(k as f64 / 16.0)).collect();
        for (k, e) in along.iter().enumerate() {
            let turned = at(k as f64 / 16.0 + 0.25);
            assert!(*e > 1e-9, "{k}: {e:e}");
            assert!((turned / e - 1.0).abs() < 1e-6, "{k}: {turned:e} vs {e:e}");
        }
        let (lo, hi) = along.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &e| {
            (lo.min(e), hi.max(e))
        });
        assert!(hi / lo <= 1.0 + std::f64::consts::TAU, "{lo:e} .. {hi:e}");
        // in units of the tolerance: a thousand times tighter, a thousand
        // times larger (the scale is `tol (1 + |y_i|)`)
        let start = scene.initial();
        let relative = |tol| DPRKN12_ADAPTIVE.estimate(&scene, &start, 0.25 * period, tol);
        assert!((relative(1e-9) / relative(1e-6) / 1e3 - 1.0).abs() < 1e-12);
        // and it is the number the controller weighs: every step a run
        // accepted has it at most 1
        let run = DPRKN12_ADAPTIVE.run(&scene, 3.0 * period, 1e-9).unwrap();
        assert!(run.accepted > 10, "{} steps", run.accepted);
        for w in run.trajectory.windows(2) {
            let ((t0, y0), (t1, _)) = (w[0], w[1]);
            let e = DPRKN12_ADAPTIVE.estimate(&scene, &y0, t1 - t0, 1e-9);
            assert!(e > 0.0 && e <= 1.0, "the step from t = {t0}: {e}");
        }
    }

    #[test]
    fn bad_requests_are_refused_not_panicked_on() {
        let scene = KeplerCircular;
        for (t_end, tol) in [
            (1.0, 0.0),
            (1.0, -1e-6),
            (1.0, f64::NAN),
            (0.0, 1e-6),
            (f64::INFINITY, 1e-6),
        ] {
            assert!(
                DPRKN6_ADAPTIVE.run(&scene, t_end, tol).is_err(),
                "{t_end} {tol}"
            );
        }
    }

    /// Every evaluation is counted: the scene's own count equals the run's,
    /// five a step tried (first same as last) and one for the start (the
    /// first trial needs none); the run ends exactly at `t_end`.
    #[test]
    fn evaluations_are_counted_and_the_run_ends_at_t_end() {
        let scene = Counted::new(KeplerEccentric::default());
        let t_end = 3.3 * scene.period();
        let run = DPRKN6_ADAPTIVE.run(&scene, t_end, 1e-8).unwrap();
        assert_eq!(run.end, RunEnd::Reached);
        assert_eq!(run.evaluations, scene.evaluations());
        assert_eq!(run.evaluations, 1 + 5 * (run.accepted + run.rejected));
        assert_eq!(run.trajectory.len() as u64, run.accepted + 1);
        assert_eq!(run.trajectory.last().unwrap().0, t_end);
        assert!(run.rejected > 0, "an eccentric orbit needs a few retries");
        let ts: Vec<f64> = run.trajectory.iter().map(|x| x.0).collect();
        assert!(ts.windows(2).all(|w| w[1] > w[0]));
    }

    /// The controller's fixed point: with an estimate `C h^5` held
    /// constant, `h_new = 0.9 h err^(-1/5)` settles at `err = 0.9^5`, and
    /// the predictive controller at the same point (its predicted step is
    /// the standard one when `C` stays put).
    #[test]
    fn the_controller_settles_at_safety_to_the_estimate_power() {
        for c in [Controller::standard(5), Controller::predictive(5)] {
            let mut h: f64 = 1.0;
            let mut before = None;
            for _ in 0..200 {
                let err = 3.0 * h.powi(5);
                let ratio = c.accepted_ratio(err, h, before, c.max_growth);
                before = Some(AcceptedStep { step: h, err });
                h *= ratio;
            }
            assert!((3.0 * h.powi(5) / 0.9f64.powi(5) - 1.0).abs() < 1e-12);
        }
        let c = Controller::standard(5);
        assert_eq!(c.ratio(f64::INFINITY, 5.0), 0.2);
        assert_eq!(c.ratio(0.0, 5.0), 5.0);
    }

    /// Where `C` grows by a factor `g` each step, the standard step lags:
    /// `h_(n+1) = 0.9 h_n err_n^(-1/5)` meets `C_(n+1) = g C_n`, so its
    /// estimates settle at `g 0.9^5`, and for `g > 0.9^(-5) = 1.69` every
    /// step is rejected. The predicted step reads `g` off the last two
    /// estimates: `(err_(n-1) / err_n)^(1/5) = g^(-1/5) h_(n-1) / h_n`, so
    /// `h_(n+1) = 0.9 h_n (g err_n)^(-1/5)` and `err_(n+1) = 0.9^5` exactly
    /// from the third step on. Where `C` falls, the standard step is the
    /// smaller and is kept: the estimates settle at `g 0.9^5`, below the
    /// aim.
    #[test]
    fn the_predicted_step_follows_an_estimate_that_grows() {
        let aim = 0.9f64.powi(5);
        for g in [3.0, 1.3, 0.5] {
            for c in [Controller::standard(5), Controller::predictive(5)] {
                let (mut h, mut constant) = (0.1f64, 1.0);
                let mut before = None;
                let mut err = 0.0;
                for _ in 0..20 {
                    err = constant * h.powi(5);
                    let ratio = c.accepted_ratio(err, h, before, 100.0);
                    before = Some(AcceptedStep { step: h, err });
                    h *= ratio;
                    constant *= g;
                }
                let settled = if c.predictive && g > 1.0 {
                    aim
                } else {
                    g * aim
                };
                assert!((err / settled - 1.0).abs() < 1e-12, "{g} {c:?} {err}");
            }
        }
    }

    /// The predicted step: the standard one times `(h_n / h_(n-1))
    /// (err_(n-1) / err_n)^(1/5)`, kept when smaller; a controller without
    /// prediction ignores the history; an estimate below the one at which
    /// the standard step reaches its cap, `(0.9 / 5)^5`, counts as that one,
    /// so a previous estimate of zero does not predict a collapse.
    #[test]
    fn the_predicted_step_is_taken_only_when_smaller() {
        let c = Controller::predictive(5);
        let standard = |err: f64| 0.9 * err.powf(-0.2);
        let before = |step, err| Some(AcceptedStep { step, err });
        let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-14;
        let rising = c.accepted_ratio(0.4, 1.0, before(1.0, 0.1), 5.0);
        assert!(close(rising, standard(0.4) * 0.25f64.powf(0.2)));
        assert!(close(
            c.accepted_ratio(0.1, 1.0, before(1.0, 0.4), 5.0),
            standard(0.1)
        ));
        assert!(close(
            c.accepted_ratio(0.4, 2.0, before(1.0, 0.4), 5.0),
            standard(0.4)
        ));
        let shrunk = c.accepted_ratio(0.4, 0.5, before(1.0, 0.4), 5.0);
        assert!(close(shrunk, 0.5 * standard(0.4)));
        assert!(close(c.accepted_ratio(0.4, 1.0, None, 5.0), standard(0.4)));
        let plain = Controller::standard(5);
        assert!(close(
            plain.accepted_ratio(0.4, 1.0, before(1.0, 0.1), 5.0),
            standard(0.4)
        ));
        let floor = 0.18f64.powi(5);
        let from_zero = c.accepted_ratio(0.4, 1.0, before(1.0, 0.0), 5.0);
        assert!(close(from_zero, standard(0.4) * (floor / 0.4).powf(0.2)));
        assert_eq!(
            c.accepted_ratio(0.4, 1.0, before(1.0, floor / 10.0), 5.0),
            from_zero
        );
        // two estimates of zero: both steps at the cap
        assert!(close(
            c.accepted_ratio(0.0, 1.0, before(1.0, 0.0), 5.0),
            5.0
        ));
    }

    /// On the eccentric orbit `C` rises on every fall towards pericentre,
    /// where the standard step lags (see above) and is rejected. Each pair
    /// with the predictive controller is rejected at no tolerance more often
    /// than with the standard one and less often over the ladder
    /// (measured: DPRKN8(6) 31 rejections against 123 from `1e-6` to
    /// `1e-12`, RKN12(10) 39 against 103, DPRKN6(4) 7 against 34).
    #[test]
    fn the_predictive_controller_is_rejected_less_on_the_eccentric_orbit() {
        fn rejections<const S: usize>(pair: EmbeddedPair<S>, tol: f64) -> u64 {
            let scene = KeplerEccentric::default();
            let run = pair.run(&scene, scene.default_t_end(), tol).unwrap();
            assert_eq!(run.end, RunEnd::Reached);
            run.rejected
        }
        fn compare<const S: usize>(pair: EmbeddedPair<S>, power: u32) {
            let standard = EmbeddedPair {
                controller: Controller::standard(power),
                ..pair
            };
            let (mut fewer, mut more) = (0, 0);
            for k in 6..=12 {
                let tol = 10f64.powi(-k);
                let (p, s) = (rejections(pair, tol), rejections(standard, tol));
                assert!(p <= s, "{} at {tol:e}: {p} > {s}", pair.name);
                fewer += p;
                more += s;
            }
            assert!(fewer < more, "{}: {fewer} against {more}", pair.name);
        }
        compare(DPRKN6_ADAPTIVE, 5);
        compare(DPRKN8_ADAPTIVE, 7);
        compare(DPRKN12_ADAPTIVE, 11);
    }
}
