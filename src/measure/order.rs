//! The global order of accuracy, measured over a step-size ladder that runs
//! down to the round-off floor.
//!
//! # What a rung measures
//!
//! Each rung runs the scheme over `[0, t_end]` in `N` steps and compares its
//! states at up to [`COMPARISONS`] step times (every step while `N` is
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
//! [`super::fit`]) and judged by [`tolerance::order_verdict`]. Without a
//! window, a local order that falls below the claim at the fine end is an
//! order reduction (a failure, with the step where it sets in); anything
//! else the data cannot decide is [`Verdict::Inconclusive`], with the reason
//! and what to change.

use super::Verdict;
use super::fit::{OrderFit, order_fit_with_round_off};
use crate::error::Error;
use crate::ladder::{AUTO_START, AutoLadder, LadderChoice, LadderEnd, per_octave, steps_for};
use crate::run::{Outcome, integrate};
use crate::scene::{Scaled, Scene};
use crate::scheme::Scheme;
use crate::state::State;
use crate::tolerance::{
    self, ERROR_CEILING, EXACT_SOLUTION_ULPS, MIN_WINDOW, MIN_WINDOW_HALVINGS, ORDER_TOLERANCE,
    REFERENCE_RUNGS, TWIN_SCALE, WINDOW_RUNGS,
};
use serde::Serialize;
use std::collections::BTreeMap;

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

/// Why a rung is left out of the fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DropReason {
    /// The run blew up or a step failed.
    Unstable,
    /// The error is not small against the orbit ([`ERROR_CEILING`]).
    AboveCeiling,
    /// The local order has not yet settled (coarse end of the ladder).
    PreAsymptotic,
    /// Round-off is too large a part of the error to leave its local order
    /// within [`tolerance::ORDER_RESOLUTION`]: the floor.
    RoundOff,
    /// Asymptotic, but coarser than the window, which uses the finest rungs.
    NotNeeded,
    /// Run only as the half step of a finer-measured rung.
    Reference,
}

impl DropReason {
    /// A short explanation for tables.
    pub fn explain(self) -> &'static str {
        match self {
            DropReason::Unstable => "unstable",
            DropReason::AboveCeiling => "error above 30% of the orbit",
            DropReason::PreAsymptotic => "pre-asymptotic",
            DropReason::RoundOff => "round-off floor",
            DropReason::NotNeeded => "coarser than the window",
            DropReason::Reference => "half step of another rung",
        }
    }
}

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
    /// The round-off bound the verdict uses: the [`RoundOffModel`]'s upper
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
    /// Every rung, coarse to fine.
    pub rungs: Vec<Rung>,
}

impl OrderRecord {
    /// True when the verdict is a pass.
    pub fn passed(&self) -> bool {
        self.verdict == Verdict::Pass
    }
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

/// Most step times a rung is compared at: every step up to this many steps,
/// else this many equally spaced ones (and `t_end`). The largest distance
/// over them follows the error's law exactly as the largest over every step
/// does, and 4096 times over 2 sqrt(2) periods resolve an error that varies
/// along the orbit to well within a percent.
pub const COMPARISONS: u64 = 4096;

/// The step numbers at which a rung of `steps` steps is compared.
fn comparison_steps(steps: u64) -> impl Iterator<Item = u64> {
    let count = steps.min(COMPARISONS);
    (0..=count).map(move |j| j * steps / count)
}

/// Measures the global order of `scheme` on `scene`.
///
/// ```
/// use stepladder::measure::order::{global_order, OrderSpec};
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
    let t_end = match spec.t_end {
        Some(t) => crate::scene::positive("t_end", t)?,
        None => scene.default_t_end(),
    };
    let mut record = order_at(scheme, scene, spec.ladder, t_end)?;
    if spec.t_end.is_some() || matches!(spec.ladder, LadderChoice::Fixed(_)) {
        return Ok(record);
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
            "{} (at t_end = {:.4} the data could not decide: {})",
            next.reason, record.t_end, record.reason
        );
        next.shortened_from = Some(t_end);
        record = next;
    }
    Ok(record)
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
}

/// The runs of one order study, keyed by step count.
struct Lab<'a, M, S, const D: usize> {
    scheme: &'a M,
    scene: &'a S,
    t_end: f64,
    reference: Reference,
    scale: f64,
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
            runs: BTreeMap::new(),
        }
    }

    /// Runs `steps` steps from `start`, keeping the states at the
    /// comparison steps (and, for a half-step reference, at twice those of
    /// half the step count).
    fn run(&self, steps: u64) -> (Outcome, Vec<State<D>>, Vec<State<D>>) {
        let (start, h) = (self.scene.initial(), self.t_end / steps as f64);
        let mut own_at = comparison_steps(steps).peekable();
        let coarser = steps.is_multiple_of(2).then_some(steps / 2);
        let mut coarser_at = coarser
            .into_iter()
            .flat_map(|c| comparison_steps(c).map(|n| 2 * n))
            .peekable();
        let (mut own, mut for_coarser) = (Vec::new(), Vec::new());
        let outcome = integrate(self.scheme, self.scene, &start, h, steps, |n, _, s| {
            if own_at.next_if_eq(&n).is_some() {
                own.push(*s);
            }
            if coarser_at.next_if_eq(&n).is_some() {
                for_coarser.push(*s);
            }
        });
        (outcome, own, for_coarser)
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
            self.runs.get_mut(&steps).expect("run").round_off_sample = Some(sample);
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

    /// Runs `steps` steps from the scene's start and stores the run (as a
    /// reference only, until [`Lab::measure`] makes it a rung).
    fn execute(&mut self, steps: u64) {
        let (outcome, own, for_coarser) = self.run(steps);
        let done = outcome.completed();
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
        let judgement = judge(
            meta.order as f64,
            &rungs,
            &analysis,
            self.reference,
            end,
            self.scale,
        );
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

/// A ladder's data as the window selection reads it.
fn data(rungs: &[Rung]) -> Vec<RungData> {
    rungs
        .iter()
        .map(|r| RungData {
            h: r.h,
            error: r.error,
            round_off: r.round_off_bound.unwrap_or(0.0),
        })
        .collect()
}

/// The accumulated round-off of a rung against its step count `N`, fitted
/// to the twins' samples: `ln r = ln c + g ln N` by least squares, with the
/// upper 95% prediction bound used as the bound. Round-off grows with the
/// steps taken (a random walk `N^(1/2)` of unbiased roundings, up to `N^(3/2)`
/// where a velocity error feeds a drift of the phase, as for the two-step
/// Störmer form), and one sample scatters by a factor of about two about its
/// mean, which the prediction bound absorbs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RoundOffModel {
    /// `c`.
    pub coefficient: f64,
    /// `g`, at least 0 (round-off does not shrink with more steps).
    pub exponent: f64,
    /// Residual standard deviation of `ln r`.
    pub log_scatter: f64,
    /// Samples fitted.
    pub samples: usize,
    /// Mean `ln N` of the samples.
    mean_ln_steps: f64,
    /// `sum (ln N - mean)^2`.
    spread: f64,
    /// Student's t quantile at 0.975 for `samples - 2` degrees of freedom.
    t_quantile: f64,
}

impl RoundOffModel {
    /// Fits the law to `(N, sample)` pairs (non-finite samples, which come
    /// from a twin that blew up, and zeros are left out). With fewer than
    /// three usable samples the largest is extended by the steepest law,
    /// `N^(3/2)`.
    pub fn fit(samples: &[(u64, f64)]) -> Option<Self> {
        let points: Vec<(f64, f64)> = samples
            .iter()
            .filter(|(_, r)| r.is_finite() && *r > 0.0)
            .map(|&(n, r)| ((n as f64).ln(), r.ln()))
            .collect();
        let n = points.len();
        if n == 0 {
            return None;
        }
        if n < 3 {
            let &(x, y) = points
                .iter()
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .expect("non-empty");
            return Some(Self {
                coefficient: (y - 1.5 * x).exp(),
                exponent: 1.5,
                log_scatter: 0.0,
                samples: n,
                mean_ln_steps: x,
                spread: 0.0,
                t_quantile: 0.0,
            });
        }
        let nf = n as f64;
        let mx = points.iter().map(|p| p.0).sum::<f64>() / nf;
        let my = points.iter().map(|p| p.1).sum::<f64>() / nf;
        let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
        let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let exponent = if sxx > 0.0 { (sxy / sxx).max(0.0) } else { 0.0 };
        let intercept = my - exponent * mx;
        let residual: f64 = points
            .iter()
            .map(|p| (p.1 - intercept - exponent * p.0).powi(2))
            .sum();
        Some(Self {
            coefficient: intercept.exp(),
            exponent,
            log_scatter: (residual / (nf - 2.0)).sqrt(),
            samples: n,
            mean_ln_steps: mx,
            spread: sxx,
            t_quantile: super::fit::t975(n - 2),
        })
    }

    /// The fitted law at `steps`.
    pub fn mean(&self, steps: u64) -> f64 {
        self.coefficient * (steps as f64).powf(self.exponent)
    }

    /// The upper 95% prediction bound at `steps`.
    pub fn bound(&self, steps: u64) -> f64 {
        let x = (steps as f64).ln();
        let leverage = if self.spread > 0.0 {
            1.0 / self.samples as f64 + (x - self.mean_ln_steps).powi(2) / self.spread
        } else {
            0.0
        };
        self.mean(steps) * (self.t_quantile * self.log_scatter * (1.0 + leverage).sqrt()).exp()
    }
}

/// One rung's data as the window selection reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RungData {
    /// The step.
    pub h: f64,
    /// The error; `None` for a run that blew up.
    pub error: Option<f64>,
    /// A bound on the round-off in that error.
    pub round_off: f64,
}

/// A ladder's data analysed: the window, the fit over it, the trend of the
/// local orders, and the interval a verdict uses.
#[derive(Clone, Debug, PartialEq)]
pub struct Analysis {
    /// The window and why other rungs are out.
    pub choice: WindowChoice,
    /// The fit over the window.
    pub fit: Option<OrderFit>,
    /// See [`OrderRecord::trend_systematic`].
    pub trend_systematic: Option<f64>,
    /// The fit's interval widened by the trend and by
    /// [`tolerance::ORDER_RESOLUTION`].
    pub ci95: Option<[f64; 2]>,
}

/// Chooses the window of the data (coarse to fine), fits the order over it
/// and forms its interval.
pub fn analyse(data: &[RungData], scale: f64) -> Analysis {
    let choice = select_window(data, scale);
    let fit = choice.window.and_then(|(a, b)| {
        let pts: Vec<(f64, f64)> = data[a..=b]
            .iter()
            .map(|d| (d.h, d.error.unwrap_or(f64::NAN)))
            .collect();
        let round_off: Vec<f64> = data[a..=b]
            .iter()
            .map(|d| d.error.map_or(0.0, |e| d.round_off / e))
            .collect();
        order_fit_with_round_off(&pts, &round_off)
    });
    let trend_systematic = choice
        .window
        .zip(choice.median_local_order)
        .zip(fit)
        .and_then(|(((a, b), median), f)| {
            let locals: Vec<(f64, Option<f64>)> = (a..=b)
                .map(|i| {
                    (
                        data[i].h,
                        (i > a).then(|| local_order_of(data, i)).flatten(),
                    )
                })
                .collect();
            local_order_trend(&locals, median).map(|limit| (limit - f.order).abs())
        });
    let ci95 = fit.map(|f| {
        let t = trend_systematic.unwrap_or(0.0);
        tolerance::order_interval(f.order, [f.ci95[0] - t, f.ci95[1] + t])
    });
    Analysis {
        choice,
        fit,
        trend_systematic,
        ci95,
    }
}

/// The limit at `h = 0` of the local orders in the window: `l = p + c h`
/// fitted over them; `None` with fewer than four.
fn local_order_trend(locals: &[(f64, Option<f64>)], median: f64) -> Option<f64> {
    let near = tolerance::plateau_tolerance(median);
    let points: Vec<(f64, f64)> = locals
        .iter()
        .filter_map(|&(h, l)| l.filter(|l| (l - median).abs() <= near).map(|l| (h, l)))
        .collect();
    if points.len() < 4 {
        return None;
    }
    let n = points.len() as f64;
    let (mh, ml) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = points.iter().map(|p| (p.0 - mh).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mh) * (p.1 - ml)).sum();
    (sxx > 0.0).then(|| ml - sxy / sxx * mh)
}

/// The local order between two rungs, `ln(e1/e2) / ln(h1/h2)`.
pub fn local_order(coarse: (f64, Option<f64>), fine: (f64, Option<f64>)) -> Option<f64> {
    let (e1, e2) = (coarse.1?, fine.1?);
    let p = (e1 / e2).ln() / (coarse.0 / fine.0).ln();
    p.is_finite().then_some(p)
}

fn local_order_of(data: &[RungData], i: usize) -> Option<f64> {
    local_order(
        (data[i - 1].h, data[i - 1].error),
        (data[i].h, data[i].error),
    )
}

/// The asymptotic window chosen from a ladder's data.
#[derive(Clone, Debug, PartialEq)]
pub struct WindowChoice {
    /// Per rung: why it is left out, if it is.
    pub dropped: Vec<Option<DropReason>>,
    /// The clean rungs the window is sought among: the longest run of
    /// consecutive rungs that are stable, below the ceiling and above the
    /// round-off floor (ties go to the finer run).
    pub clean: Option<(usize, usize)>,
    /// First and last rung of the window, if one of [`MIN_WINDOW`] rungs exists.
    pub window: Option<(usize, usize)>,
    /// The median local order of the finest [`REFERENCE_RUNGS`] clean rungs,
    /// which the window was judged against.
    pub median_local_order: Option<f64>,
}

impl WindowChoice {
    /// Rungs in the window (0 without one).
    pub fn window_len(&self) -> usize {
        self.window.map_or(0, |(a, b)| b - a + 1)
    }
}

/// Chooses the asymptotic window from the data (coarse to fine), from the
/// data alone, never from the order the scheme claims:
///
/// 1. a rung that blew up is out; so is one whose round-off bound exceeds
///    [`tolerance::clean_fraction`] of its error (the floor), and one whose
///    error exceeds [`ERROR_CEILING`] times the scene's `scale`;
/// 2. of the longest run of consecutive remaining rungs, the window is the
///    finest ones (at most [`WINDOW_RUNGS`], unless more are needed to span
///    [`MIN_WINDOW_HALVINGS`]) whose local orders all lie within
///    [`tolerance::plateau_tolerance`] of the median of the finest
///    [`REFERENCE_RUNGS`]: the asymptotic regime at the finest steps the
///    ladder resolved. It needs [`MIN_WINDOW`] rungs over
///    [`MIN_WINDOW_HALVINGS`] halvings. Coarser rungs that stray are
///    pre-asymptotic.
pub fn select_window(data: &[RungData], scale: f64) -> WindowChoice {
    // each rung against its coarser neighbour (the coarsest against its finer)
    let pair = |i: usize| {
        let (a, b) = if i > 0 { (i - 1, i) } else { (0, 1) };
        match data.get(b) {
            Some(d) => {
                let ratio = (data[a].h / d.h).ln();
                let local = local_order_of(data, b)
                    .filter(|l| l.is_finite())
                    .unwrap_or(1.0);
                (ratio, local)
            }
            None => (std::f64::consts::LN_2, 1.0),
        }
    };
    let mut dropped: Vec<Option<DropReason>> = data
        .iter()
        .enumerate()
        .map(|(i, d)| match d.error {
            Some(e) if !e.is_finite() => Some(DropReason::Unstable),
            None => Some(DropReason::Unstable),
            Some(e)
                if e == 0.0 || {
                    let (ratio, local) = pair(i);
                    d.round_off >= tolerance::clean_fraction(ratio, local) * e
                } =>
            {
                Some(DropReason::RoundOff)
            }
            Some(e) if e > ERROR_CEILING * scale => Some(DropReason::AboveCeiling),
            Some(_) => None,
        })
        .collect();
    let none = |dropped, clean| WindowChoice {
        dropped,
        clean,
        window: None,
        median_local_order: None,
    };
    let Some((a, b)) = longest_run(&dropped) else {
        return none(dropped, None);
    };
    for (i, d) in dropped.iter_mut().enumerate() {
        if d.is_none() && (i < a || i > b) {
            // clean rungs cut off from the run by an unstable or saturated one
            *d = Some(if i < a {
                DropReason::PreAsymptotic
            } else {
                DropReason::NotNeeded
            });
        }
    }
    let local = |i: usize| local_order_of(data, i).unwrap_or(f64::NAN);
    if b == a {
        dropped[a] = Some(DropReason::PreAsymptotic);
        return none(dropped, Some((a, b)));
    }
    let median = median_of((a + 1..=b).rev().take(REFERENCE_RUNGS).map(local).collect());
    let tolerance = tolerance::plateau_tolerance(median);
    let halvings = |first: usize| (data[first].h / data[b].h).log2();
    let mut first = b;
    while first > a
        && (b - first + 1 < WINDOW_RUNGS || halvings(first) < MIN_WINDOW_HALVINGS)
        && (local(first) - median).abs() <= tolerance
    {
        first -= 1;
    }
    let window = (b + 1 - first >= MIN_WINDOW && halvings(first) >= MIN_WINDOW_HALVINGS)
        .then_some((first, b));
    for (i, slot) in dropped.iter_mut().enumerate().take(first).skip(a) {
        let strays = (local(i + 1) - median).abs() > tolerance;
        *slot = Some(if strays || window.is_none() {
            DropReason::PreAsymptotic
        } else {
            DropReason::NotNeeded
        });
    }
    if window.is_none() {
        for d in &mut dropped[first..=b] {
            *d = Some(DropReason::PreAsymptotic);
        }
    }
    WindowChoice {
        dropped,
        clean: Some((a, b)),
        window,
        median_local_order: median.is_finite().then_some(median),
    }
}

fn longest_run(dropped: &[Option<DropReason>]) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    let mut start = None;
    for i in 0..=dropped.len() {
        let candidate = dropped.get(i).is_some_and(|d| d.is_none());
        match (candidate, start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                if best.is_none_or(|(a, b)| i - s >= b + 1 - a) {
                    best = Some((s, i - 1));
                }
                start = None;
            }
            _ => {}
        }
    }
    best
}

fn median_of(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

/// The verdict on a ladder, why, and what to change when inconclusive.
struct Judgement {
    verdict: Verdict,
    reason: String,
    advice: Option<String>,
    reduction: Option<OrderReduction>,
}

/// Judges the claimed order against the analysed rungs.
fn judge(
    claim: f64,
    rungs: &[Rung],
    analysis: &Analysis,
    reference: Reference,
    end: LadderEnd,
    scale: f64,
) -> Judgement {
    let count = |reason| {
        analysis
            .choice
            .dropped
            .iter()
            .filter(|d| **d == Some(reason))
            .count()
    };
    let reduction = analysis
        .choice
        .clean
        .and_then(|(a, b)| order_reduction(claim, rungs, a, b));
    let finest_h = rungs.last().map_or(f64::NAN, |r| r.h);
    let end_note = match end {
        LadderEnd::Cap => format!("the ladder reached its step cap at h = {finest_h:.3e}"),
        LadderEnd::Floor => "the ladder reached the round-off floor".to_string(),
        LadderEnd::Fixed => "a fixed ladder".to_string(),
    };
    let inconclusive = |reason: String, advice: String| Judgement {
        verdict: Verdict::Inconclusive,
        reason,
        advice: Some(advice),
        reduction: None,
    };
    let fail = |reason: String, reduction| Judgement {
        verdict: Verdict::Fail,
        reason,
        advice: None,
        reduction,
    };
    if let (Some(f), Some(ci), Some((a, b))) = (analysis.fit, analysis.ci95, analysis.choice.window)
    {
        let over = format!(
            "order {:.3} in [{:.3}, {:.3}] over rungs {a}..{b} (h {:.3e} .. {:.3e})",
            f.order, ci[0], ci[1], rungs[a].h, rungs[b].h
        );
        return match tolerance::order_verdict(claim, f.order, ci) {
            Ok(note) => Judgement {
                verdict: Verdict::Pass,
                reason: note.map_or(over.clone(), |n| format!("{over}: {n}")),
                advice: None,
                reduction: None,
            },
            Err(why) => {
                let fell = reduction.map_or(String::new(), |r| {
                    format!(
                        "; the local order falls from {:.2} towards {:.2} below h = {:.3e} (order reduction)",
                        r.from, r.to, r.sets_in_at
                    )
                });
                fail(format!("{why}: {over}{fell}"), reduction)
            }
        };
    }
    if let Some(r) = reduction {
        return fail(
            format!(
                "order reduction: the local order falls from {:.2} towards {:.2} below h = {:.3e}, \
                 under the claimed {claim} ({end_note})",
                r.from, r.to, r.sets_in_at
            ),
            reduction,
        );
    }
    let (unstable, above, floor) = (
        count(DropReason::Unstable),
        count(DropReason::AboveCeiling),
        count(DropReason::RoundOff),
    );
    let clean = analysis.choice.clean.map_or(0, |(a, b)| b + 1 - a);
    if clean == 0 && floor == 0 {
        // nothing resolved, nothing at round-off: every rung blew up or
        // stayed far from its reference down to the finest step
        if reference == Reference::Exact && unstable == rungs.len() {
            return fail(
                format!(
                    "no convergence: every rung blew up, down to h = {finest_h:.3e}, though \
                     the exact motion stays bounded"
                ),
                None,
            );
        }
        if let Some(elsewhere) = converges_elsewhere(rungs, scale) {
            return fail(elsewhere, None);
        }
        return inconclusive(
            format!(
                "no rung resolved the motion ({unstable} unstable, {above} with errors above \
                 {ERROR_CEILING} of the orbit, down to h = {finest_h:.3e})"
            ),
            match end {
                LadderEnd::Fixed => "a correct scheme needs finer steps here: give the ladder \
                                     more levels or a smaller h0, or use the automatic one"
                    .into(),
                _ => "a correct scheme needs finer steps here: raise the step cap \
                      (AutoLadder::max_rung_evaluations) or shorten t_end; if the motion itself runs \
                      away, shorten t_end"
                    .into(),
            },
        );
    }
    if clean == 0 {
        let smallest = rungs
            .iter()
            .filter_map(|r| r.error)
            .fold(f64::INFINITY, f64::min);
        return inconclusive(
            format!(
                "round-off is a large part of the error at every rung that resolves the motion \
                 (smallest error {smallest:.3e}, {:.1e} of the orbit)",
                smallest / scale
            ),
            "an error at round-off everywhere means the scheme is exact on this scene: measure \
             it on one where it is not; a large round-off means the scene magnifies it over \
             t_end: shorten t_end"
                .into(),
        );
    }
    let (a, b) = analysis.choice.clean.expect("clean rungs");
    let locals: Vec<String> = (a + 1..=b)
        .filter_map(|i| rungs[i].local_order)
        .map(|l| format!("{l:.2}"))
        .collect();
    let advice = match end {
        LadderEnd::Cap => {
            "the local order was still moving when the ladder reached its step cap: raise the \
             cap (AutoLadder::max_rung_evaluations) or shorten t_end"
        }
        LadderEnd::Floor => {
            "round-off leaves too few clean rungs above it: shorten t_end, which lowers the \
             round-off a rung accumulates and the magnification of the flow"
        }
        LadderEnd::Fixed => "use the automatic ladder, which runs to the floor",
    };
    inconclusive(
        format!(
            "no window of {MIN_WINDOW} rungs with a settled local order: {clean} clean rungs, \
             local orders [{}] ({end_note})",
            locals.join(", ")
        ),
        advice.into(),
    )
}

/// A scheme that converges, but not to the exact solution: at its two finest
/// rungs with a half-step difference, that difference is within the
/// ceiling (the runs at `h` and `h/2` agree on the motion) while the error is
/// more than four times it. Were the scheme converging to the exact solution
/// with any order `p >= 1`, its error would be `1 / (1 - 2^-p) <= 2` times
/// the difference; four leaves a factor two for the pre-asymptotic rungs.
/// It is the signature of a scheme that solves another equation (a wrong
/// sign, a wrong coefficient) or a wrong initial state.
fn converges_elsewhere(rungs: &[Rung], scale: f64) -> Option<String> {
    let pairs: Vec<(f64, f64, f64)> = rungs
        .iter()
        .filter_map(|r| Some((r.h, r.error?, r.half_step_difference?)))
        .collect();
    let finest = pairs.get(pairs.len().checked_sub(2)?..)?;
    let elsewhere = finest
        .iter()
        .all(|&(_, e, d)| d <= ERROR_CEILING * scale && e > 4.0 * d);
    elsewhere.then(|| {
        let (h, e, d) = finest[1];
        format!(
            "converges, but not to the exact solution: at h = {h:.3e} the run differs from its \
             half step by {d:.3e} and from the exact motion by {e:.3e} (the scheme solves \
             another problem, or starts from another state)"
        )
    })
}

/// An order reduction at the fine end of the clean rungs `a..=b`: the local
/// orders reached the claim (two in a row within the plateau tolerance of
/// it), and the finest [`REFERENCE_RUNGS`] of them lie more than the plateau
/// tolerance and [`ORDER_TOLERANCE`] below it, converging to a limit below
/// it too (see [`local_order_limit`]).
///
/// A correct scheme's local order tends to its order as `h -> 0`, from above
/// or below. Past a cancellation of its leading error term it can lie far
/// below it for a while, but rising back towards it; what it does not do is
/// settle below it. The limit tells the two apart.
fn order_reduction(claim: f64, rungs: &[Rung], a: usize, b: usize) -> Option<OrderReduction> {
    let locals: Vec<(usize, f64)> = (a + 1..=b)
        .filter_map(|i| Some((i, rungs[i].local_order?)))
        .collect();
    let tolerance = tolerance::plateau_tolerance(claim);
    let on_claim = |l: f64| (l - claim).abs() <= tolerance;
    // the finest pair of consecutive local orders on the claim
    let seen = (1..locals.len())
        .rev()
        .find(|&k| on_claim(locals[k - 1].1) && on_claim(locals[k].1))?;
    let tail = &locals[seen..];
    if tail.len() <= REFERENCE_RUNGS {
        return None;
    }
    let fine: Vec<f64> = tail[tail.len() - REFERENCE_RUNGS..]
        .iter()
        .map(|&(_, l)| l)
        .collect();
    let below = |l: f64| l < claim - tolerance.max(ORDER_TOLERANCE);
    let limit = local_order_limit(&fine)?;
    if !(fine.iter().all(|&l| below(l)) && below(limit)) {
        return None;
    }
    let (first_off, _) = tail.iter().copied().find(|&(_, l)| !on_claim(l))?;
    Some(OrderReduction {
        from: claim,
        to: limit,
        sets_in_at: rungs[first_off - 1].h,
    })
}

/// Where three successive local orders `l1, l2, l3` (coarse to fine) are
/// heading, when the data say: their common value if they agree to within
/// half the plateau tolerance (what round-off may move each); the limit of
/// the geometric sequence they start if their steps shrink with one sign
/// (`l3 + d2 r / (1 - r)`, `r = d2 / d1`: Aitken's extrapolation, exact for
/// a local order `L + c h^s` on a ladder of constant ratio); at most `l3` if
/// they fall faster and faster. Otherwise `None`: rising ever faster, or
/// wobbling, they could be heading anywhere.
pub fn local_order_limit(fine: &[f64]) -> Option<f64> {
    let [l1, l2, l3] = *fine else {
        return None;
    };
    let (d1, d2) = (l2 - l1, l3 - l2);
    let half = tolerance::plateau_tolerance(l3) / 2.0;
    if d1.abs() <= half && d2.abs() <= half {
        return Some(median_of(fine.to_vec()));
    }
    if d1 * d2 > 0.0 && d2.abs() < d1.abs() {
        let r = d2 / d1;
        return Some(l3 + d2 * r / (1.0 - r));
    }
    (d1 <= 0.0 && d2 <= 0.0).then_some(l3)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ladder(
        e: impl Fn(f64) -> Option<f64>,
        round_off: impl Fn(f64) -> f64,
        n: i32,
    ) -> Vec<RungData> {
        (0..n)
            .map(|k| 0.5 / 2f64.powi(k))
            .map(|h| RungData {
                h,
                error: e(h),
                round_off: round_off(h),
            })
            .collect()
    }

    #[test]
    fn window_excludes_blow_ups_coarse_errors_and_the_floor() {
        // second order, blows up at the coarsest rung, error above the
        // ceiling at the next, and round-off of 1e-13 / h
        let data = ladder(
            |h| (h <= 0.4).then_some(2.0 * h * h + 1e-13 / h),
            |h| 1e-13 / h,
            20,
        );
        let w = select_window(&data, 0.3);
        assert_eq!(w.dropped[0], Some(DropReason::Unstable));
        assert_eq!(w.dropped[1], Some(DropReason::AboveCeiling));
        // clean while 1e-13/h <= 0.01 ln2 / 2 * 2 h^2, i.e. h^3 >= 1.44e-11:
        // h >= 2.4e-4, rung 11 (h = 2.44e-4) is the finest clean one
        let (_, b) = w.window.expect("a window");
        assert_eq!(b, 11, "{w:?}");
        assert!(
            w.dropped[12..]
                .iter()
                .all(|d| *d == Some(DropReason::RoundOff))
        );
    }

    #[test]
    fn no_window_when_the_error_does_not_converge() {
        let w = select_window(&ladder(|_| Some(0.01), |_| 1e-16, 10), 1.0);
        // a flat error is clean (far above round-off) and its local order 0
        assert_eq!(w.median_local_order, Some(0.0));
    }

    #[test]
    fn local_order_of_a_power_law() {
        let p = local_order((0.1, Some(3e-4)), (0.05, Some(3e-4 / 8.0))).unwrap();
        assert!((p - 3.0).abs() < 1e-12);
        assert!(local_order((0.1, None), (0.05, Some(1.0))).is_none());
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

    #[test]
    fn round_off_model_recovers_a_power_law_and_bounds_its_scatter() {
        // sqrt(N) law with a factor-two scatter; the bound must lie above
        // every sample and within a small factor of the law
        let samples: Vec<(u64, f64)> = (0..14)
            .map(|k| {
                let n = 23u64 << k;
                let wobble = if k % 2 == 0 { 2.0 } else { 0.5 };
                (n, 1e-16 * (n as f64).sqrt() * wobble)
            })
            .collect();
        let m = RoundOffModel::fit(&samples).unwrap();
        assert!((m.exponent - 0.5).abs() < 0.05, "{m:?}");
        for &(n, r) in &samples {
            assert!(m.bound(n) >= r, "{n}: {} < {r}", m.bound(n));
            assert!(m.bound(n) < 20.0 * r, "{n}");
        }
    }
}
