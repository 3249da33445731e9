//! Breakdowns: runs that stopped being runs (a non-finite state or one past
//! the blow-up bound, a failed step, a panic in the scheme's code), and the
//! rule that tells a defect from instability.
//!
//! # The rule
//!
//! 1. **A panic is a defect at any step.** A run hands a step only finite
//!    states within [`crate::tolerance::blow_up_bound`] and a finite,
//!    nonzero step; code that panics there has no answer for a legitimate
//!    input. The claim that depends on the run fails, with where it happened.
//!    So does a step that cannot run on the scene at all
//!    ([`crate::scheme::StepFailure::Unfit`]: a wrapped integrator's vector
//!    type of another length than the scene's state), which no step size
//!    changes.
//! 2. **A breakdown at a finer step than a resolved run is a defect.** Linear
//!    instability grows with the step: a one-step map applied to `y' = L y`
//!    multiplies each mode by `R(h lambda)`, and every consistent method has
//!    `|R(z)| <= 1 + C |z|` near `z = 0`, so over a fixed span `T` the growth
//!    `|R|^(T/h) <= exp(C |lambda| T)` stays bounded as `h -> 0` (zero
//!    stability, which every method the harness accepts has). An
//!    unconditionally unstable scheme (explicit Euler on an oscillator,
//!    `|R| = sqrt(1 + z^2)`) grows by `exp(h w^2 T / 2)` over `T`: less at a
//!    finer step, never more. A stiff scene (a fast mode `Omega`) breaks an
//!    explicit scheme at `h Omega` past its limit and not below it: again
//!    only the coarse steps. So a run that resolved the motion (its error,
//!    or its half-step difference, within [`ERROR_CEILING`] of the orbit)
//!    shows its step inside the region where the scheme follows the flow,
//!    and a run at a finer step over the same span that blows up, produces
//!    a non-finite number or fails its step has met a defect of the step
//!    (an overflow guard, a division by a small `h`, a units helper), not
//!    instability. A stability interval can have gaps beyond its first
//!    limit (a composition's islands of stability), but a step in an island
//!    has `h w` past the first limit, a phase error of order one a period,
//!    and no resolved run: the ceiling keeps it out of the rule.
//! 3. **Otherwise a run that stops is instability**, and only at steps
//!    coarser than every resolved one: advice to take a smaller step is
//!    given only where a finer step was seen to run the same span (to
//!    completion: that instability shrinks with the step needs no resolved
//!    run, while a clean coarser run must have resolved the motion to rule
//!    out an island of stability).
//!
//! Single-step studies (energy, round trip) have no ladder; `probe` runs
//! the same span at finer and then at coarser steps to find out which case
//! a stopped run is.

use crate::run::{Outcome, integrate};
use crate::scene::{Scene, energy_norm};
use crate::scheme::Scheme;
use crate::state::State;
use crate::study::stability::stability;
use crate::tolerance::ERROR_CEILING;
use crate::wording::figure;
use serde::Serialize;

/// A run that stopped at a step where it should have run: a panic in the
/// scheme's code (at any step), or a stop at a finer step than a run that
/// resolved the motion.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Breakdown {
    /// Steps of the run that stopped (over the span it was asked for).
    pub steps: u64,
    /// How it stopped, with the step size, the step index, the time and the
    /// coordinate or the failure.
    pub outcome: Outcome,
    /// A coarser step that ran the same span and resolved the motion (none
    /// for a panic, which needs no comparison).
    pub clean_h: Option<f64>,
    /// That run's error (or half-step difference, or largest relative
    /// energy error for a probe), the evidence that it resolved the motion.
    pub clean_error: Option<f64>,
    /// What the run was: "the rung", "its half-step reference", "its twin in
    /// other units", "the run forward".
    pub run: &'static str,
}

impl Breakdown {
    /// The breakdown in one sentence, with its figures and the rule.
    pub fn describe(&self) -> String {
        let h = self.outcome.h().unwrap_or(f64::NAN);
        let head = format!(
            "breakdown: {} at h = {} ({} steps) stopped at {}",
            self.run,
            figure(h),
            self.steps,
            self.outcome.where_and_why()
        );
        match (self.defect(), self.clean_h) {
            (true, _) if self.outcome.panicked() => format!(
                "{head}: a panic in the scheme's code, which no finite state within the blow-up \
                 bound excuses"
            ),
            (true, _) => format!("{head}: the step does not fit the scene, at any step size"),
            (false, Some(clean)) => format!(
                "{head}, while the coarser h = {} ran cleanly (error {} of the orbit, within the \
                 ceiling {ERROR_CEILING}): instability grows with the step, so a run that stops \
                 at a finer step is a defect of the step, not instability",
                figure(clean),
                self.clean_error.map_or("-".to_string(), figure)
            ),
            (false, None) => head,
        }
    }

    /// True for a failure no step size excuses: a panic in the scheme's
    /// code, or a step that cannot run on the scene at all.
    pub fn defect(&self) -> bool {
        self.outcome.defect()
    }
}

/// One run as the ladder rule sees it.
pub(crate) struct LadderRun<'a> {
    pub(crate) steps: u64,
    pub(crate) h: f64,
    pub(crate) outcome: &'a Outcome,
    /// Its error against its reference when it was judged, relative to the
    /// scene's scale (`None` when it has none).
    pub(crate) relative_error: Option<f64>,
    pub(crate) run: &'static str,
}

/// The ladder rule: the coarsest panic anywhere, else the coarsest stopped
/// run finer than the coarsest run that resolved the motion.
pub(crate) fn in_ladder(runs: &[LadderRun<'_>]) -> Option<Breakdown> {
    let breakdown = |r: &LadderRun<'_>, clean: Option<&LadderRun<'_>>| Breakdown {
        steps: r.steps,
        outcome: r.outcome.clone(),
        clean_h: clean.map(|c| c.h),
        clean_error: clean.and_then(|c| c.relative_error),
        run: r.run,
    };
    let coarsest_first = |a: &&LadderRun<'_>, b: &&LadderRun<'_>| b.h.total_cmp(&a.h);
    if let Some(p) = runs
        .iter()
        .filter(|r| r.outcome.defect())
        .min_by(coarsest_first)
    {
        return Some(breakdown(p, None));
    }
    let resolved = |r: &&LadderRun<'_>| {
        r.outcome.completed() && r.relative_error.is_some_and(|e| e <= ERROR_CEILING)
    };
    let coarsest_resolved = runs.iter().filter(resolved).min_by(coarsest_first)?;
    let stopped = runs
        .iter()
        .filter(|r| !r.outcome.completed() && r.h < coarsest_resolved.h)
        .min_by(coarsest_first)?;
    // the evidence: the finest resolved run still coarser than the stop
    let clean = runs
        .iter()
        .filter(resolved)
        .filter(|r| r.h > stopped.h)
        .max_by(coarsest_first)
        .unwrap_or(coarsest_resolved);
    Some(breakdown(stopped, Some(clean)))
}

/// What the runs at other steps over the same span make of a run that
/// stopped.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Probe {
    /// A panic or an unfit step: a defect at any step.
    Defect(Breakdown),
    /// A finer step ran the same span: the stop is instability at this
    /// step.
    Unstable {
        /// The coarsest finer step that ran cleanly.
        finer: f64,
        /// `h w`, with `w` the scene's frequency.
        z: f64,
        /// The scheme's linear stability limit in `h w`, measured on the
        /// oscillator (see [`crate::study::stability()`]), where it is
        /// positive and `z` is past it.
        limit: Option<f64>,
    },
    /// No finer step ran the span, a coarser one did and resolved the
    /// motion: a defect of the step.
    Breakdown(Breakdown),
    /// Neither a finer nor a coarser step ran the span cleanly.
    Unexplained {
        /// The finest and the coarsest step tried.
        tried: [f64; 2],
    },
}

impl Probe {
    /// The probe's finding as a clause for a study's reason.
    pub(crate) fn describe(&self, h: f64, stop: &Outcome) -> String {
        match self {
            Probe::Defect(b) | Probe::Breakdown(b) => b.describe(),
            Probe::Unstable { finer, z, limit } => format!(
                "{}: unstable at h = {}, where h/{} = {} runs the same span cleanly{}",
                stop.brief(),
                figure(h),
                figure(h / finer),
                figure(*finer),
                limit.map_or(String::new(), |limit| format!(
                    "; h w = {} is past the scheme's linear stability limit h w = {} \
                     (measured on the harmonic oscillator)",
                    figure(*z),
                    figure(limit)
                ))
            ),
            Probe::Unexplained { tried } => format!(
                "{}; no step from h = {} to {} ran the same span cleanly either",
                stop.brief(),
                figure(tried[0]),
                figure(tried[1])
            ),
        }
    }

    /// The stop is a defect (a panic, or a breakdown below a clean step).
    pub(crate) fn is_defect(&self) -> bool {
        self.breakdown().is_some()
    }

    /// The defect, where the stop is one.
    pub(crate) fn breakdown(&self) -> Option<&Breakdown> {
        match self {
            Probe::Defect(b) | Probe::Breakdown(b) => Some(b),
            _ => None,
        }
    }
}

/// Finer steps a probe tries: `h/2` to `h/2^PROBE_HALVINGS`, each over the
/// same span. Instability at `h` that persists at `h/8` is not the kind a
/// smaller step cures at a cost worth advising.
pub const PROBE_HALVINGS: u32 = 3;

/// The coarsest step a probe tries, in periods of the scene: a quarter
/// period is `h w = pi/2`, past which no scheme here resolves the motion.
pub const PROBE_COARSEST: f64 = 0.25;

/// The fewest steps a coarser probe takes: a span of at least this many
/// coarse steps, so that a breakdown at the first fine step is weighed
/// against more than one coarse one.
pub const PROBE_MIN_STEPS: u64 = 8;

/// Runs `scheme` over the span of a run from `start` at step `h` that
/// stopped with `stop`, at finer and then coarser steps, and says which
/// kind of stop it was (see the module documentation).
pub(crate) fn probe<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    start: &State<D>,
    h: f64,
    stop: &Outcome,
) -> Probe {
    let steps_run = stop.step().unwrap_or(0).max(1);
    let broken = |run: &'static str| Breakdown {
        steps: steps_run,
        outcome: stop.clone(),
        clean_h: None,
        clean_error: None,
        run,
    };
    if stop.defect() {
        return Probe::Defect(broken("the run"));
    }
    let span = steps_run as f64 * h.abs();
    // a panic in a probe's run is a defect as much as one in the run itself
    let panicked = |steps: u64, outcome: Outcome| {
        Probe::Defect(Breakdown {
            steps,
            outcome,
            clean_h: None,
            clean_error: None,
            run: "a run at another step over the same span",
        })
    };
    for k in 1..=PROBE_HALVINGS {
        let finer = h / f64::from(1u32 << k);
        // completing the span is enough this way: instability needs no
        // resolved run to show that it shrinks with the step
        match run_over(scheme, scene, start, finer, steps_run << k) {
            Ok(ProbeRun {
                completed: true, ..
            }) => {
                let z = h.abs() * scene.frequency();
                return Probe::Unstable {
                    finer: finer.abs(),
                    z,
                    // a limit of 0 (unstable at every step, as explicit
                    // Euler) is no step to stay below: there a finer step
                    // only grows more slowly
                    limit: stability(scheme)
                        .stability_limit
                        .filter(|&limit| limit > 0.0 && z > limit),
                };
            }
            Ok(_) => {}
            Err(p) => return panicked(steps_run << k, p),
        }
    }
    let coarsest = PROBE_COARSEST * scene.period();
    let mut coarser = 2.0 * h;
    while coarser.abs() <= coarsest {
        let steps = ((span / coarser.abs()).ceil() as u64).max(PROBE_MIN_STEPS);
        match run_over(scheme, scene, start, coarser, steps) {
            Ok(ProbeRun {
                resolved: Some(error),
                ..
            }) => {
                let mut b = broken("the run");
                b.clean_h = Some(coarser.abs());
                b.clean_error = Some(error);
                return Probe::Breakdown(b);
            }
            Ok(_) => {}
            Err(p) => return panicked(steps, p),
        }
        coarser *= 2.0;
    }
    Probe::Unexplained {
        tried: [
            h.abs() / f64::from(1u32 << PROBE_HALVINGS),
            (coarser / 2.0).abs().max(h.abs()),
        ],
    }
}

/// How a probe's run went: whether it completed, and the largest error it
/// made when that is within [`ERROR_CEILING`] (it resolved the motion).
struct ProbeRun {
    completed: bool,
    resolved: Option<f64>,
}

/// Runs `steps` steps of `h` from `start`, its error measured as a fraction
/// (of the orbit against the exact solution where the scene has one and the
/// run starts on it, and of the energy always); the outcome of a run that
/// panicked as the error.
fn run_over<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    start: &State<D>,
    h: f64,
    steps: u64,
) -> Result<ProbeRun, Outcome> {
    let (e0, norm, scale) = (scene.energy(start), energy_norm(scene), scene.scale());
    let on_exact = scene.exact(0.0).is_some_and(|s| s == *start);
    let mut worst = 0.0f64;
    let outcome = integrate(scheme, scene, start, h, steps, |n, _, s| {
        let energy = (scene.energy(s) - e0).abs() / norm;
        let phase = if on_exact {
            scene
                .exact(n as f64 * h)
                .map_or(0.0, |x| scene.phase_distance(s, &x) / scale)
        } else {
            0.0
        };
        // a NaN must not vanish in max
        worst = if energy.is_nan() || phase.is_nan() {
            f64::NAN
        } else {
            worst.max(energy).max(phase)
        };
    });
    if outcome.defect() {
        return Err(outcome);
    }
    Ok(ProbeRun {
        completed: outcome.completed(),
        resolved: (outcome.completed() && worst <= ERROR_CEILING).then_some(worst),
    })
}
