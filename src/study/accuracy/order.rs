//! The global order of accuracy, measured over a step-size ladder that runs
//! down to the round-off floor.
//!
//! # What a rung measures
//!
//! Each rung runs the scheme over `[0, t_end]` in `N` steps and compares its
//! states at up to [`COMPARISONS`](crate::run::COMPARISONS) step times (every step while `N` is
//! smaller) with a reference: the scene's exact solution where it has one,
//! otherwise the same scheme at half the step, whose states at those times
//! lie on its own grid. The largest phase-space distance is the rung's error.
//! Against the half step the difference `E_h(t) - E_(h/2)(t) = (1 - 2^-p)
//! C(t) h^p (1 + ...)` has the error's order whatever `p` is, because every
//! rung is compared at the same ratio, 2 (Richardson's argument needs that
//! one ratio; rungs rounded to other ratios would not share it).
//!
//! # The ladder
//!
//! The automatic ladder interleaves `m` halving ladders ([`per_octave`]: the
//! claimed order over two, so the error falls about fourfold from rung to
//! rung): step counts `round(N0 2^(j/m)) 2^i`. Every rung's half step is then
//! itself a rung, so comparing with the half step costs only the finest `m`
//! rungs. It starts at [`AUTO_START`] periods and keeps refining past any
//! plateau of local orders, down to the round-off floor or the step cap, so
//! that an order reduction that appears only at fine steps is seen.
//!
//! # Round-off, measured
//!
//! Every rung is run twice, the second time in units of length
//! [`TWIN_SCALE`] smaller: the same motion, rounded differently at every
//! operation, so the distance between the two runs is a sample of the rung's
//! accumulated round-off. A power law in the step count fitted to these
//! samples (see [`RoundOffModel`]) bounds the round-off of every rung, and a
//! rung counts as clean while that bound is below
//! [`tolerance::clean_fraction`] of its error: there round-off cannot move a
//! local order by more than [`tolerance::ORDER_RESOLUTION`]. Rungs past that
//! are on the floor. The floor is a measurement, not a factor.
//!
//! # The verdict
//!
//! Over the clean rungs, the window is the finest plateau of local orders
//! (see [`select_window`]); the order is fitted over it (see
//! [`crate::maths::fit`]) and judged by [`tolerance::order_verdict`]. Without a
//! window, a local order that falls below the claim at the fine end is an
//! order reduction (a failure, with the step where it sets in); anything
//! else the data cannot decide is [`Verdict::Inconclusive`], with the reason
//! and what to change.

use crate::error::Error;
use crate::ladder::{AUTO_START, AutoLadder, LadderChoice, LadderEnd, per_octave, steps_for};
use crate::maths::fit::OrderFit;
use crate::maths::tangent::local_rate;
use crate::run::{Outcome, comparison_steps, integrate, integrate_tallied};
use crate::scene::{Invariant, InvariantValue, Scaled, Scene};
use crate::scheme::{Scheme, SolveTally};
use crate::state::State;
use crate::study::accuracy::invariants::{InvariantRecord, InvariantSample, judge_invariant};
use crate::study::accuracy::probe::{ConditionProbe, probe_conditions};
use crate::study::breakdown::{Breakdown, LadderRun, in_ladder};
use crate::study::verdict::Verdict;
use crate::tolerance::{
    self, ERROR_CEILING, EXACT_SOLUTION_ULPS, MIN_WINDOW, MIN_WINDOW_HALVINGS, TWIN_SCALE,
};
use serde::Serialize;
use std::collections::BTreeMap;

pub use crate::maths::window::{
    Analysis, DropReason, RoundOffModel, RungData, WindowChoice, analyse, local_order,
    select_window,
};
pub use crate::study::accuracy::order_verdict::local_order_limit;
use crate::study::accuracy::order_verdict::{data, judge};
pub use crate::study::accuracy::rung::{OrderReduction, Reference, Rung};

/// What to measure: the end time and the ladder.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OrderSpec {
    /// End time of every rung; `None` for the scene's default.
    pub t_end: Option<f64>,
    /// The step sizes.
    pub ladder: LadderChoice,
}

impl Default for OrderSpec {
    fn default() -> Self {
        Self {
            t_end: None,
            ladder: LadderChoice::Auto,
        }
    }
}

impl OrderSpec {
    /// The end time asked for (`None` for the scene's default), refused
    /// before any run unless it is a finite positive number at least one
    /// step long: at least the fixed ladder's `h0`, or, for the automatic
    /// ladder, its first step of [`AUTO_START`] periods. The ladder's own
    /// settings are checked too ([`AutoLadder::checked`]); the cost of the
    /// rungs is checked when they are laid out.
    pub fn checked(&self, period: f64) -> Result<Option<f64>, Error> {
        if let LadderChoice::AutoWith(settings) = self.ladder {
            settings.checked()?;
        }
        let Some(t_end) = self.t_end else {
            return Ok(None);
        };
        let t_end = crate::scene::positive("t_end", t_end)?;
        let (first, which) = match self.ladder {
            LadderChoice::Fixed(ladder) => (ladder.h0, "the ladder's first step h0"),
            _ => (
                AUTO_START * period,
                "the automatic ladder's first step, 1/8 period",
            ),
        };
        if t_end < first {
            return Err(Error::OutOfRange {
                name: "t_end",
                value: t_end,
                expected: format!(
                    "a finite number of at least {} ({which}): at least one step",
                    crate::wording::exact(first)
                ),
            });
        }
        Ok(Some(t_end))
    }
}

/// Everything the order study found: the record behind the CLI's `--json`,
/// the snapshots and the report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OrderRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// The scene's parameters.
    pub scene_parameters: String,
    /// The order the scheme claims.
    pub theoretical_order: u32,
    /// End time of every rung.
    pub t_end: f64,
    /// What each rung's error is measured against.
    pub reference: Reference,
    /// How the ladder was chosen.
    pub ladder: LadderChoice,
    /// Interleaved halving ladders of the automatic ladder (its ratio is
    /// `2^(-1/per_octave)`), after any refinement.
    pub per_octave: Option<u32>,
    /// How it ended.
    pub ladder_end: LadderEnd,
    /// The automatic ladder was refined between its clean rungs because the
    /// error fell faster from rung to rung than a window can follow.
    pub refined: bool,
    /// The default end time, when it left the order undecided and the study
    /// was run again over shorter ones ([`SHORTER_END`]; `t_end` is then the
    /// last one run).
    pub shortened_from: Option<f64>,
    /// The fitted round-off law of the twins.
    pub round_off: Option<RoundOffModel>,
    /// The fitted order, when a window was found.
    pub measured_order: Option<f64>,
    /// Its 95% interval, at least [`tolerance::ORDER_RESOLUTION`] either
    /// side (see [`tolerance::order_interval`]); the verdict uses it.
    pub ci95: Option<[f64; 2]>,
    /// The fit's details.
    pub fit: Option<OrderFit>,
    /// How far the limit of the local orders, extrapolated to `h = 0`, lies
    /// from the fitted order: a systematic the interval includes.
    pub trend_systematic: Option<f64>,
    /// First and last rung of the window (indices into `rungs`).
    pub window: Option<[usize; 2]>,
    /// A fall of the local order below the claim at the fine end.
    pub order_reduction: Option<OrderReduction>,
    /// The verdict.
    pub verdict: Verdict,
    /// Why, in one line.
    pub reason: String,
    /// For an inconclusive verdict, what to change so the data can decide.
    pub advice: Option<String>,
    /// A run that stopped where it should have run (a panic, or a stop at a
    /// finer step than a rung that resolved the motion): the claim fails on
    /// it whatever the rungs before it show (see
    /// [`crate::study::breakdown`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub breakdown: Option<Breakdown>,
    /// For a failed claim, the order conditions of the scheme's one-step
    /// map, probed through the claimed order (see [`probe_conditions`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probe: Option<ConditionProbe>,
    /// Without an exact solution, whether each quantity the scene's exact
    /// flow conserves returns to its initial value as `h -> 0` (see
    /// [`crate::study::accuracy::invariants`]); a failure fails the order
    /// study, whose convergence is then to the solution of another
    /// equation. Empty with an exact solution, which says more.
    pub invariants: Vec<InvariantRecord>,
    /// Every rung, coarse to fine.
    pub rungs: Vec<Rung>,
}

impl OrderRecord {
    /// True when the verdict is a pass.
    pub fn passed(&self) -> bool {
        self.verdict == Verdict::Pass
    }
}

/// Measures the global order of `scheme` on `scene`.
///
/// ```
/// use stepladder::study::{global_order, OrderSpec};
/// use stepladder::scene::Harmonic;
/// use stepladder::scheme::{Scheme, VELOCITY_VERLET};
///
/// let record = global_order(&VELOCITY_VERLET, &Harmonic::default(), &OrderSpec::default()).unwrap();
/// assert!(record.passed(), "{}", record.reason);
/// assert!((record.measured_order.unwrap() - 2.0).abs() < 0.01);
/// ```
pub fn global_order<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    spec: &OrderSpec,
) -> Result<OrderRecord, Error> {
    let t_end = spec
        .checked(scene.period())?
        .unwrap_or_else(|| scene.default_t_end());
    let mut record = order_at(scheme, scene, spec.ladder, t_end)?;
    if spec.t_end.is_some() || matches!(spec.ladder, LadderChoice::Fixed(_)) {
        return Ok(with_probe::<M, D>(scheme, record));
    }
    // The default end time could not decide: the error grows along the run
    // (a phase error linearly, round-off as a random walk magnified by the
    // flow's shear) and the terms of its expansion can cancel at one end
    // time and not at another, while the order is the same at any end time.
    // So the study takes its own advice, at shorter end times.
    let mut shorter = t_end;
    for _ in 0..SHORTER_ENDS {
        if record.verdict != Verdict::Inconclusive {
            break;
        }
        shorter /= SHORTER_END;
        let mut next = order_at(scheme, scene, spec.ladder, shorter)?;
        next.reason = format!(
            "{} (at t_end = {} the data could not decide: {})",
            next.reason,
            crate::wording::figure(record.t_end),
            record.reason
        );
        next.shortened_from = Some(t_end);
        record = next;
    }
    Ok(with_probe::<M, D>(scheme, record))
}

/// A failed order claim with the first order condition the scheme's
/// one-step map violates (see [`probe_conditions`]), named in its reason.
/// Not after a breakdown, whose panic or stop the reason already names.
fn with_probe<M: Scheme, const D: usize>(scheme: &M, mut record: OrderRecord) -> OrderRecord {
    if record.verdict != Verdict::Fail || record.breakdown.is_some() {
        return record;
    }
    if let Some(probe) = probe_conditions::<M, D>(scheme, record.theoretical_order) {
        record.reason = format!("{}; {}", record.reason, probe.describe());
        record.probe = Some(probe);
    }
    record
}

/// When an end time leaves the order undecided, the study runs again over
/// this fraction of it: from the default `2 sqrt(2)` periods to
/// `sqrt(2) / 2`, then `sqrt(2) / 8`, irrational numbers of periods still (no
/// cancellation at a half or whole period), with four and sixteen times less
/// time for the error's secular terms and the round-off to grow.
pub const SHORTER_END: f64 = 4.0;

/// How many times the study shortens the end time ([`SHORTER_END`]).
pub const SHORTER_ENDS: usize = 2;

/// The order study at one end time.
fn order_at<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    ladder: LadderChoice,
    t_end: f64,
) -> Result<OrderRecord, Error> {
    let meta = scheme.meta();
    let mut lab = Lab::new(scheme, scene, t_end);
    let (end, per_octave, refined) = match ladder {
        LadderChoice::Fixed(fixed) => {
            for size in &fixed.rungs(t_end)? {
                lab.measure(size.steps);
            }
            lab.complete_references()?;
            (LadderEnd::Fixed, None, false)
        }
        LadderChoice::Auto | LadderChoice::AutoWith(_) => {
            let settings = match ladder {
                LadderChoice::AutoWith(settings) => settings,
                _ => AutoLadder::default(),
            };
            let m = settings
                .per_octave
                .unwrap_or_else(|| per_octave(meta.order));
            if m == 0 {
                return Err(Error::InvalidParameter {
                    name: "per_octave",
                    value: 0.0,
                    expected: "at least 1 rung per halving of the step",
                });
            }
            let n0 = steps_for(t_end, AUTO_START * scene.period())?;
            // the cap is in force evaluations: a scheme's cost
            let cap = settings.max_rung_evaluations / u64::from(meta.force_evaluations.max(1));
            let end = lab.climb(n0, m, cap)?;
            lab.complete_references()?;
            let (m, refined) = lab.refine(n0, m, cap)?;
            (end, Some(m), refined)
        }
    };
    Ok(lab.record(ladder, end, per_octave, refined))
}

/// One run of a rung, and what is kept of it until its comparisons are done.
struct Run<const D: usize> {
    outcome: Outcome,
    /// States at [`comparison_steps`] of its own step count.
    own: Option<Vec<State<D>>>,
    /// States at twice the comparison steps of half its step count, to
    /// measure that coarser rung against (half-step reference only).
    for_coarser: Option<Vec<State<D>>>,
    /// It is a rung of the ladder (not only a half-step reference).
    measured: bool,
    /// Compared with its half step.
    compared: bool,
    error: Option<f64>,
    final_error: Option<f64>,
    /// Largest and final distance to the half step.
    half_step: Option<(f64, f64)>,
    round_off_sample: Option<f64>,
    /// Per invariant of the scene (half-step reference only): the largest
    /// change over the comparison times and the largest sensitivity.
    invariants: Vec<(f64, f64)>,
    /// Per invariant: the largest distance to its twin's value.
    invariant_round_off: Vec<f64>,
    /// What the scheme's solves reported over the run.
    solve: Option<SolveTally>,
    /// How its twin ended, when the twin stopped.
    twin_outcome: Option<Outcome>,
}

/// Times at which [`fastest_rate_along`] samples the exact orbit, the
/// start and the end included: the start, where a Kepler orbit of the
/// catalogue is at its pericentre, and a grid fine enough for any motion
/// whose fast passages last more than a 4096th of the run (a passage
/// between two samples goes unseen, and the verdict stays the stricter).
pub const RATE_SAMPLES: usize = 4096;

/// The motion's fastest local rate ([`local_rate`]) along the exact orbit
/// over `[0, t_end]`, at [`RATE_SAMPLES`] intervals; zero without an exact
/// solution.
fn fastest_rate_along<S: Scene<D>, const D: usize>(scene: &S, t_end: f64) -> f64 {
    (0..=RATE_SAMPLES)
        .filter_map(|k| scene.exact(t_end * k as f64 / RATE_SAMPLES as f64))
        .map(|s| local_rate(scene, &s.q))
        .fold(0.0, f64::max)
}

/// The runs of one order study, keyed by step count.
struct Lab<'a, M, S, const D: usize> {
    scheme: &'a M,
    scene: &'a S,
    t_end: f64,
    reference: Reference,
    scale: f64,
    /// What the scene's exact flow conserves, checked where there is no
    /// exact solution to compare with.
    invariants: &'static [Invariant],
    runs: BTreeMap<u64, Run<D>>,
}

impl<'a, M: Scheme, S: Scene<D>, const D: usize> Lab<'a, M, S, D> {
    fn new(scheme: &'a M, scene: &'a S, t_end: f64) -> Self {
        let reference = if scene.exact(0.0).is_some() {
            Reference::Exact
        } else {
            Reference::HalfStep
        };
        Self {
            scheme,
            scene,
            t_end,
            reference,
            scale: scene.scale(),
            invariants: match reference {
                Reference::Exact => &[],
                Reference::HalfStep => scene.invariants(),
            },
            runs: BTreeMap::new(),
        }
    }

    /// Runs `steps` steps from `start`, keeping the states at the
    /// comparison steps (and, for a half-step reference, at twice those of
    /// half the step count).
    fn run(&self, steps: u64) -> (Outcome, Option<SolveTally>, Vec<State<D>>, Vec<State<D>>) {
        let (start, h) = (self.scene.initial(), self.t_end / steps as f64);
        let mut own_at = comparison_steps(steps).peekable();
        let coarser = steps.is_multiple_of(2).then_some(steps / 2);
        let mut coarser_at = coarser
            .into_iter()
            .flat_map(|c| comparison_steps(c).map(|n| 2 * n))
            .peekable();
        let (mut own, mut for_coarser) = (Vec::new(), Vec::new());
        let (outcome, solve) =
            integrate_tallied(self.scheme, self.scene, &start, h, steps, |n, _, s| {
                if own_at.next_if_eq(&n).is_some() {
                    own.push(*s);
                }
                if coarser_at.next_if_eq(&n).is_some() {
                    for_coarser.push(*s);
                }
            });
        (outcome, solve, own, for_coarser)
    }

    /// Runs the rung of `steps` steps and its twin (once each), and compares
    /// it with its reference where that has run.
    fn measure(&mut self, steps: u64) {
        if !self.runs.contains_key(&steps) {
            self.execute(steps);
        }
        let needs_twin = {
            let run = self.runs.get_mut(&steps).expect("just run");
            run.measured = true;
            run.round_off_sample.is_none() && run.outcome.completed()
        };
        if needs_twin {
            let twin_scene = Scaled::new(self.scene, TWIN_SCALE);
            let (twin_outcome, twin) = self.twin(&twin_scene, steps);
            let sample = match (&self.runs[&steps].own, twin_outcome.completed()) {
                (Some(own), true) => own
                    .iter()
                    .zip(&twin)
                    .map(|(a, b)| self.scene.phase_distance(a, &twin_scene.back(b)))
                    .fold(0.0, f64::max),
                // the twin blew up where the run did not: round-off decides the rung
                _ => f64::INFINITY,
            };
            let invariant_round_off = self.invariant_round_off(
                self.runs[&steps].own.as_deref(),
                twin_outcome.completed().then_some(&twin[..]),
                &twin_scene,
            );
            let run = self.runs.get_mut(&steps).expect("run");
            run.round_off_sample = Some(sample);
            run.invariant_round_off = invariant_round_off;
            run.twin_outcome = (!twin_outcome.completed()).then_some(twin_outcome);
        }
        if self.reference == Reference::Exact {
            self.compare_exact(steps);
        }
        self.compare_half_steps();
    }

    /// The rung of `steps` steps on the twin scene, its states at the
    /// comparison steps.
    fn twin(&self, twin: &Scaled<&S>, steps: u64) -> (Outcome, Vec<State<D>>) {
        let h = self.t_end / steps as f64;
        let mut at = comparison_steps(steps).peekable();
        let mut states = Vec::new();
        let outcome = integrate(self.scheme, twin, &twin.initial(), h, steps, |n, _, s| {
            if at.next_if_eq(&n).is_some() {
                states.push(*s);
            }
        });
        (outcome, states)
    }

    /// The value of invariant `k` at `s` (the scene declared it).
    fn invariant(&self, k: usize, s: &State<D>) -> InvariantValue {
        self.scene
            .invariant(self.invariants[k], s)
            .unwrap_or(InvariantValue {
                value: f64::NAN,
                sensitivity: f64::NAN,
            })
    }

    /// Per invariant, the largest change along `own` from the scene's
    /// initial value, and the largest sensitivity.
    fn invariant_changes(&self, own: &[State<D>]) -> Vec<(f64, f64)> {
        let start = self.scene.initial();
        (0..self.invariants.len())
            .map(|k| {
                let initial = self.invariant(k, &start).value;
                own.iter().fold((0.0f64, 0.0f64), |(change, sens), s| {
                    let i = self.invariant(k, s);
                    // a NaN (an undeclared invariant) must not vanish in max
                    let d = (i.value - initial).abs();
                    (
                        if d.is_nan() { f64::NAN } else { change.max(d) },
                        sens.max(i.sensitivity),
                    )
                })
            })
            .collect()
    }

    /// Per invariant, the largest distance between its values along the run
    /// and along the twin (mapped back to the scene's units); infinite when
    /// the twin blew up where the run did not.
    fn invariant_round_off(
        &self,
        own: Option<&[State<D>]>,
        twin: Option<&[State<D>]>,
        twin_scene: &Scaled<&S>,
    ) -> Vec<f64> {
        (0..self.invariants.len())
            .map(|k| match (own, twin) {
                (Some(own), Some(twin)) => own
                    .iter()
                    .zip(twin)
                    .map(|(a, b)| {
                        (self.invariant(k, a).value - self.invariant(k, &twin_scene.back(b)).value)
                            .abs()
                    })
                    .fold(0.0, f64::max),
                _ => f64::INFINITY,
            })
            .collect()
    }

    /// Runs `steps` steps from the scene's start and stores the run (as a
    /// reference only, until [`Lab::measure`] makes it a rung).
    fn execute(&mut self, steps: u64) {
        let (outcome, solve, own, for_coarser) = self.run(steps);
        let done = outcome.completed();
        let invariants = if done {
            self.invariant_changes(&own)
        } else {
            Vec::new()
        };
        self.runs.insert(
            steps,
            Run {
                outcome,
                own: done.then_some(own),
                for_coarser: (done && !for_coarser.is_empty()).then_some(for_coarser),
                measured: false,
                compared: false,
                half_step: None,
                error: None,
                final_error: None,
                round_off_sample: None,
                invariants,
                invariant_round_off: Vec::new(),
                solve,
                twin_outcome: None,
            },
        );
    }

    fn compare_exact(&mut self, steps: u64) {
        let h = self.t_end / steps as f64;
        let run = self.runs.get_mut(&steps).expect("run");
        if let Some(own) = &run.own {
            let distances: Vec<f64> = comparison_steps(steps)
                .zip(own)
                .map(|(n, s)| {
                    // the last step's time is t_end itself, not n h rounded
                    let t = if n == steps { self.t_end } else { n as f64 * h };
                    let exact = self.scene.exact(t).expect("the reference is exact");
                    self.scene.phase_distance(s, &exact)
                })
                .collect();
            run.error = Some(distances.iter().copied().fold(0.0, f64::max));
            run.final_error = distances.last().copied();
        }
    }

    /// Measures every rung whose half step has run against it: the rung's
    /// error where there is no exact solution, and in any case whether the
    /// scheme converges at all (to the exact solution or not).
    fn compare_half_steps(&mut self) {
        let pending: Vec<u64> = self
            .runs
            .iter()
            .filter(|(n, r)| r.measured && !r.compared && self.runs.contains_key(&(2 * **n)))
            .map(|(n, _)| *n)
            .collect();
        for n in pending {
            let finer = &self.runs[&(2 * n)];
            let coarse = &self.runs[&n];
            let distances: Option<Vec<f64>> = match (&coarse.own, &finer.for_coarser) {
                (Some(a), Some(b)) => Some(
                    a.iter()
                        .zip(b)
                        .map(|(x, y)| self.scene.phase_distance(x, y))
                        .collect(),
                ),
                _ => None,
            };
            // a half step that blew up leaves the rung without a difference
            let difference = distances.map(|d| {
                (
                    d.iter().copied().fold(0.0, f64::max),
                    d.last().copied().unwrap_or(0.0),
                )
            });
            let coarse = self.runs.get_mut(&n).expect("run");
            coarse.compared = true;
            coarse.half_step = difference;
            if self.reference == Reference::HalfStep {
                coarse.error = difference.map(|d| d.0);
                coarse.final_error = difference.map(|d| d.1);
            }
            // its twin was compared when it was measured
            coarse.own = None;
            self.runs.get_mut(&(2 * n)).expect("run").for_coarser = None;
        }
    }

    /// Runs the half step of every measured rung that lacks it.
    fn complete_references(&mut self) -> Result<(), Error> {
        if self.reference != Reference::HalfStep {
            return Ok(());
        }
        let missing: Vec<u64> = self
            .runs
            .iter()
            .filter(|(n, r)| r.measured && r.own.is_some() && !self.runs.contains_key(&(2 * **n)))
            .map(|(n, _)| 2 * n)
            .collect();
        for n in missing {
            crate::ladder::check_cost(n)?;
            self.execute(n);
        }
        self.compare_half_steps();
        Ok(())
    }

    /// The automatic ladder: interleaved halvings from `n0` until the floor
    /// or the cap.
    fn climb(&mut self, n0: u64, m: u32, cap: u64) -> Result<LadderEnd, Error> {
        for steps in interleaved(n0, m) {
            if steps > cap {
                return Ok(LadderEnd::Cap);
            }
            crate::ladder::check_cost(steps)?;
            self.measure(steps);
            if self.at_floor() {
                return Ok(LadderEnd::Floor);
            }
            // finer rungs cannot undo a breakdown (see `breakdown.rs`)
            if self.breakdown().is_some() {
                return Ok(LadderEnd::Breakdown);
            }
        }
        unreachable!("the interleaved ladder is endless")
    }

    /// The two finest judged rungs that resolve the motion are both on the
    /// round-off floor by their own twins' samples: finer rungs only have
    /// more round-off and less error. (A rung above the ceiling is never the
    /// floor, whatever its twin says: coarse steps can be chaotic.)
    fn at_floor(&self) -> bool {
        let ceiling = ERROR_CEILING * self.scale;
        let sample = |n: u64| self.runs.get(&n).and_then(|r| r.round_off_sample);
        let floor = |n: u64, e: f64| {
            let noise = match self.reference {
                Reference::Exact => sample(n).map(|s| s + self.exact_allowance()),
                Reference::HalfStep => sample(n).map(|s| s.hypot(sample(2 * n).unwrap_or(0.0))),
            };
            let (ratio, local) = self.neighbour(n, e);
            e == 0.0 || noise.is_some_and(|s| s >= tolerance::clean_fraction(ratio, local) * e)
        };
        let judged: Vec<(u64, f64)> = self
            .runs
            .iter()
            .filter(|(_, r)| r.measured)
            .filter_map(|(&n, r)| Some((n, r.error.filter(|&e| e <= ceiling)?)))
            .collect();
        judged.len() >= 2 && judged.iter().rev().take(2).all(|&(n, e)| floor(n, e))
    }

    /// `ln(h_coarser / h)` to the next coarser measured rung and the local
    /// order against it, for a rung of error `e` (`ln 2` and 1 for the
    /// coarsest).
    fn neighbour(&self, steps: u64, e: f64) -> (f64, f64) {
        let coarser = self
            .runs
            .range(..steps)
            .rev()
            .find(|(_, r)| r.measured)
            .map(|(n, r)| (*n, r.error));
        match coarser {
            Some((c, error)) => {
                let ratio = (steps as f64 / c as f64).ln();
                let local = error.map_or(1.0, |prev| (prev / e).ln() / ratio);
                (ratio, if local.is_finite() { local } else { 1.0 })
            }
            None => (std::f64::consts::LN_2, 1.0),
        }
    }

    /// The breakdown among the runs so far (every rung, half-step reference
    /// and twin), by the rule of [`crate::study::breakdown`].
    fn breakdown(&self) -> Option<Breakdown> {
        let mut runs = Vec::with_capacity(2 * self.runs.len());
        for (&steps, r) in &self.runs {
            let h = self.t_end / steps as f64;
            runs.push(LadderRun {
                steps,
                h,
                outcome: &r.outcome,
                relative_error: r.error.filter(|_| r.measured).map(|e| e / self.scale),
                run: if r.measured {
                    "the rung"
                } else {
                    "a half-step reference"
                },
            });
            if let Some(twin) = &r.twin_outcome {
                runs.push(LadderRun {
                    steps,
                    h,
                    outcome: twin,
                    relative_error: None,
                    run: "the rung's twin (the same motion in other units)",
                });
            }
        }
        in_ladder(&runs)
    }

    /// The exact solution's own inaccuracy, which every rung's error carries.
    fn exact_allowance(&self) -> f64 {
        match self.reference {
            Reference::Exact => EXACT_SOLUTION_ULPS * f64::EPSILON * self.scale,
            Reference::HalfStep => 0.0,
        }
    }

    /// When the clean rungs fall faster than a window can follow (a scheme
    /// of higher order than claimed, or a ladder whose ratio was set too
    /// coarse), refines the ladder between them once, to twice the density.
    /// Returns the rungs per halving used and whether it refined.
    fn refine(&mut self, n0: u64, m: u32, cap: u64) -> Result<(u32, bool), Error> {
        let rungs = judged(self.rungs());
        let analysis = analyse(&data(&rungs), self.scale);
        if analysis.choice.window.is_some() {
            return Ok((m, false));
        }
        let Some((a, b)) = analysis.choice.clean else {
            return Ok((m, false));
        };
        // refine where the clean rungs span enough halvings for a window but
        // are too few to fill one: the error fell faster from rung to rung
        // than the ladder's density was chosen for (an order above the claim)
        let span = (rungs[a].h / rungs[b].h).log2();
        if span < MIN_WINDOW_HALVINGS || b + 1 - a >= MIN_WINDOW + 2 {
            return Ok((m, false));
        }
        let needed = 2 * m;
        let mut finer = m;
        while finer < needed.min(MAX_PER_OCTAVE) {
            finer *= 2;
        }
        let (lo, hi) = (
            rungs[a.saturating_sub(1)].steps,
            rungs[(b + 1).min(rungs.len() - 1)].steps,
        );
        let new: Vec<u64> = interleaved(n0, finer)
            .take_while(|&n| n <= hi)
            .filter(|&n| n > lo && n <= cap && !self.runs.get(&n).is_some_and(|r| r.measured))
            .collect();
        for n in &new {
            crate::ladder::check_cost(*n)?;
            self.measure(*n);
        }
        self.complete_references()?;
        Ok((finer, !new.is_empty()))
    }

    /// The measured rungs and the half-step references, coarse to fine,
    /// with their round-off bounds.
    fn rungs(&self) -> Vec<Rung> {
        let model = self.round_off_model();
        self.runs
            .iter()
            .map(|(&steps, r)| {
                let bound = match self.reference {
                    Reference::Exact => model.map(|m| m.bound(steps) + self.exact_allowance()),
                    // the two runs' round-off is independent
                    Reference::HalfStep => model.map(|m| m.bound(steps).hypot(m.bound(2 * steps))),
                };
                Rung {
                    h: self.t_end / steps as f64,
                    steps,
                    error: r.error.filter(|_| r.measured),
                    final_error: r.final_error.filter(|_| r.measured),
                    half_step_difference: r.half_step.map(|d| d.0).filter(|_| r.measured),
                    round_off_sample: r.round_off_sample,
                    round_off_bound: bound.filter(|_| r.measured),
                    local_order: None,
                    used: false,
                    dropped: (!r.measured).then_some(DropReason::Reference),
                    outcome: r.outcome.clone(),
                    solve: r.solve,
                }
            })
            .collect()
    }

    /// The round-off law fitted to the twins of the rungs that resolve the
    /// motion (error below the ceiling). A coarser rung's twin measures how
    /// sensitive an unresolved numerical map is (a pericentre passage taken
    /// in a step or two scatters the orbit), not the round-off of the steps
    /// the window is sought among; without three resolved rungs every twin
    /// is used.
    fn round_off_model(&self) -> Option<RoundOffModel> {
        let ceiling = ERROR_CEILING * self.scale;
        let samples = |resolved_only: bool| -> Vec<(u64, f64)> {
            self.runs
                .iter()
                .filter(|(_, r)| r.measured)
                .filter(|(_, r)| !resolved_only || r.error.is_some_and(|e| e <= ceiling))
                .filter_map(|(&n, r)| Some((n, r.round_off_sample?)))
                .collect()
        };
        let resolved = samples(true);
        if resolved
            .iter()
            .filter(|s| s.1 > 0.0 && s.1.is_finite())
            .count()
            >= 3
        {
            RoundOffModel::fit(&resolved)
        } else {
            RoundOffModel::fit(&samples(false))
        }
    }

    /// Each invariant of the scene judged over the measured rungs, given the
    /// lower end of the order's interval.
    fn invariant_records(&self, order_lo: Option<f64>) -> Vec<InvariantRecord> {
        (0..self.invariants.len())
            .map(|k| {
                let samples: Vec<InvariantSample> = self
                    .runs
                    .iter()
                    .filter(|(_, r)| r.measured && r.invariants.len() > k)
                    .map(|(&steps, r)| InvariantSample {
                        h: self.t_end / steps as f64,
                        steps,
                        change: r.invariants[k].0,
                        sensitivity: r.invariants[k].1,
                        round_off_sample: r.invariant_round_off.get(k).copied(),
                        half_step_difference: r.half_step.map(|d| d.0),
                    })
                    .collect();
                judge_invariant(self.invariants[k], &samples, order_lo)
            })
            .collect()
    }

    /// The record: rungs, analysis and verdict.
    fn record(
        &self,
        ladder: LadderChoice,
        end: LadderEnd,
        per_octave: Option<u32>,
        refined: bool,
    ) -> OrderRecord {
        let meta = self.scheme.meta();
        let scene_meta = self.scene.meta();
        let mut all = self.rungs();
        // the judged rungs are the measured ones; references keep their rows
        let measured: Vec<usize> = (0..all.len())
            .filter(|&i| all[i].dropped != Some(DropReason::Reference))
            .collect();
        let mut rungs = judged(all.clone());
        let analysis = analyse(&data(&rungs), self.scale);
        for (rung, reason) in rungs.iter_mut().zip(&analysis.choice.dropped) {
            rung.dropped = *reason;
        }
        if let Some((a, b)) = analysis.choice.window.filter(|_| analysis.fit.is_some()) {
            rungs[a..=b].iter_mut().for_each(|r| r.used = true);
        }
        let mut judgement = judge(
            meta.order as f64,
            &rungs,
            &analysis,
            self.reference,
            end,
            self.scale,
            &|| fastest_rate_along(self.scene, self.t_end),
        );
        let breakdown = self.breakdown();
        if let Some(b) = &breakdown {
            // no claim passes on the rungs before a breakdown
            judgement.verdict = Verdict::Fail;
            judgement.reason = b.describe();
            judgement.advice = None;
            let clean = b.clean_h.unwrap_or(f64::INFINITY);
            for rung in rungs
                .iter_mut()
                .filter(|r| !r.outcome.completed() && r.h < clean)
            {
                rung.dropped = Some(DropReason::Breakdown);
            }
        }
        let invariants = self.invariant_records(analysis.ci95.map(|ci| ci[0]));
        if judgement.verdict == Verdict::Pass
            && let Some(broken) = invariants.iter().find(|r| r.verdict == Verdict::Fail)
        {
            judgement.verdict = Verdict::Fail;
            judgement.reason = format!("{} (though {})", broken.reason, judgement.reason);
        }
        // put the judged rungs back among the references, by step count
        for (slot, rung) in measured.iter().zip(rungs) {
            all[*slot] = rung;
        }
        let window = analysis
            .fit
            .and(analysis.choice.window)
            .map(|(a, b)| [measured[a], measured[b]]);
        OrderRecord {
            scheme: meta.id,
            scene: scene_meta.id,
            scene_parameters: scene_meta.parameters,
            theoretical_order: meta.order,
            t_end: self.t_end,
            reference: self.reference,
            ladder,
            per_octave,
            ladder_end: end,
            refined,
            shortened_from: None,
            round_off: self.round_off_model(),
            measured_order: analysis.fit.map(|f| f.order),
            ci95: analysis.ci95,
            fit: analysis.fit,
            trend_systematic: analysis.trend_systematic,
            window,
            order_reduction: judgement.reduction,
            verdict: judgement.verdict,
            reason: judgement.reason,
            advice: judgement.advice,
            breakdown,
            probe: None,
            invariants,
            rungs: all,
        }
    }
}

/// The most interleaved halving ladders a refinement uses (a ratio of
/// `2^(-1/16)`, 4% a rung): beyond it neighbouring rungs differ by less than
/// their error's own wobble along the orbit.
pub const MAX_PER_OCTAVE: u32 = 16;

/// Step counts `round(n0 2^(j/m)) 2^i` in increasing order, `i = 0, 1, ...`,
/// `j = 0..m`: `m` interleaved halving ladders, each rung's half step a rung.
/// With `m` a power of two times `m'`, every rung of the `m'` ladder is one
/// of them. Below `4m` steps the bases would round onto each other, so the
/// ladder starts with every distinct `round(n0 2^(k/m))` below that, as
/// dense as whole step counts allow (their half steps, where not rungs, are
/// run as references).
pub fn interleaved(n0: u64, m: u32) -> impl Iterator<Item = u64> {
    let n0 = n0.max(1);
    let shift = (0..64).find(|&s| n0 << s >= 4 * m as u64).unwrap_or(0);
    let start = n0 << shift;
    let mut low: Vec<u64> = (0..shift * m)
        .map(|k| (n0 as f64 * 2f64.powf(k as f64 / m as f64)).round() as u64)
        .filter(|&n| n < start)
        .collect();
    low.dedup();
    let bases: Vec<u64> = (0..m)
        .map(|j| (start as f64 * 2f64.powf(j as f64 / m as f64)).round() as u64)
        .collect();
    low.into_iter().chain((0u32..).flat_map(move |i| {
        let bases = bases.clone();
        bases.into_iter().map(move |b| b << i)
    }))
}

/// The measured rungs (not the half-step references), with their local orders.
fn judged(mut rungs: Vec<Rung>) -> Vec<Rung> {
    rungs.retain(|r| r.dropped != Some(DropReason::Reference));
    for k in 1..rungs.len() {
        rungs[k].local_order = local_order(
            (rungs[k - 1].h, rungs[k - 1].error),
            (rungs[k].h, rungs[k].error),
        );
    }
    rungs
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The samples run from the start to `t_end` and no further. On the
    /// separatrix `x = tanh(t / sqrt 2)` (`k = alpha = 1`) the force's slope
    /// `-1 + 3 x^2` has magnitude 1 at the start and grows from `x^2 = 1/3`
    /// on towards 2, so past `x^2 = 2/3` the fastest rate over `[0, t_end]`
    /// is the one at `t_end` itself, exactly; a sample beyond `t_end` would
    /// find a faster one.
    #[test]
    fn the_fastest_rate_is_sampled_from_the_start_to_the_end() {
        let scene = crate::scene::Separatrix::default();
        for t_end in [3.0, 10.0] {
            let at_end = local_rate(&scene, &scene.exact(t_end).unwrap().q);
            assert!(at_end > 1.0 && at_end < 2f64.sqrt());
            assert_eq!(fastest_rate_along(&scene, t_end), at_end);
        }
        // early on, the start's rate of one is the fastest
        assert_eq!(fastest_rate_along(&scene, 0.5), 1.0);
    }

    #[test]
    fn interleaved_ladders_contain_every_half_step() {
        for (n0, m) in [(23, 4), (23, 8), (3, 2), (1, 4)] {
            let steps: Vec<u64> = interleaved(n0, m).take(60).collect();
            assert!(steps.windows(2).all(|w| w[0] < w[1]), "{steps:?}");
            // from the first base on, the ratio is 2^(-1/m) but for the
            // rounding of the bases to whole steps (half a step of at least
            // 4m, each end), and every rung's half step is a rung
            let start = (0..).map(|s| n0 << s).find(|&n| n >= 4 * m as u64).unwrap();
            let dense: Vec<u64> = steps.iter().copied().filter(|&n| n >= start).collect();
            let rounding = 1.0 / (4 * m) as f64;
            for w in dense.windows(2) {
                let ratio = w[1] as f64 / w[0] as f64 / 2f64.powf(1.0 / m as f64);
                assert!((ratio - 1.0).abs() <= rounding, "{w:?}");
            }
            for &n in &dense[..dense.len() - m as usize] {
                assert!(steps.contains(&(2 * n)), "{n} of {steps:?}");
            }
        }
    }
}
