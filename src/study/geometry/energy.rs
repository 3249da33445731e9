//! Energy behaviour over long runs: the largest relative energy error and the
//! law by which its running maximum grows with time.
//!
//! A symplectic scheme conserves a modified energy, so its true energy error
//! stays bounded (growth exponent `g ~ 0`) until round-off, a random walk,
//! makes it grow like `t^(1/2)`. A symmetric (time-reversible) scheme, even
//! one that is not symplectic, has no secular drift either on a reversible
//! problem near an integrable one (Hairer, Lubich and Wanner, Geometric
//! Numerical Integration, XI), and every scene here is reversible: `q'' =
//! a(q)` is unchanged by `t -> -t, v -> -v`. A scheme that is neither
//! generally drifts (`g >= 1`), but need not on every scene: a claim of
//! neither property promises nothing, so it is never refuted; the record
//! says what was measured.

use crate::error::Error;
use crate::ladder::{check_cost, check_count, steps_for};
use crate::maths::fit::power_law;
use crate::run::{Outcome, integrate};
use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::study::breakdown::{Breakdown, Probe, probe};
use crate::study::verdict::Verdict;
use crate::tolerance::{
    BOUNDED_BELOW, GROWTH_DECADES, LOST_FRACTION, LOST_GROWTH, RANDOM_WALK_BELOW, round_off_energy,
};
use crate::wording::{figure, vs_upper};
use serde::Serialize;

/// Default step, in periods of the scene: 100 steps a period.
pub const DEFAULT_STEP: f64 = 1.0 / 100.0;

/// Default length of the run, in periods: 10^4 periods, 10^6 steps.
pub const DEFAULT_PERIODS: f64 = 1e4;

/// A conservation claim is tested at a step that resolves the motion: the
/// energy may change by at most this fraction of `E0` over the first period.
/// Backward error analysis, which makes a symplectic (or symmetric) map
/// conserve a modified energy `H + h^p H_p + ...`, holds while the step is
/// small against every local time scale of the motion; its first term is
/// the energy's excursion. Euler-Cromer's on the oscillator is `h w / 2`, so
/// a tenth is `h w = 0.2`, 31 steps a local period, the coarsest at which a
/// first-order map still follows its modified energy; higher orders resolve
/// at coarser steps. At the default step a pericentre of `e = 0.9` is taken
/// in under three steps, and a symplectic scheme's numerical orbit can be
/// thrown off it at once: there is no law to test at that step.
pub const RESOLVED_EXCURSION: f64 = 0.1;

/// Most halvings of the default step made to resolve the motion (a step of
/// 1/25600 period): the run keeps its 10^6 steps, so its length in periods
/// shrinks by the same factor (to 39 periods, whose growth is fitted from
/// the second period on, over 1.3 decades).
pub const MAX_HALVINGS: u32 = 8;

/// How the step of a run was chosen, which its reason states.
#[derive(Clone, Copy, Debug, PartialEq)]
enum StepChoice {
    /// Given by the spec, or the default for a claim of neither property.
    Given,
    /// The default halved `halvings` times, the first step whose energy
    /// excursion over the first period is within [`RESOLVED_EXCURSION`].
    Resolving { halvings: u32, excursion: f64 },
    /// Halved [`MAX_HALVINGS`] times without resolving the first period:
    /// its excursion at the finest step, `None` if that run blew up.
    Unresolved { excursion: Option<f64> },
    /// Halved `halvings` times to confirm a refutation at a coarser step.
    Confirming { halvings: u32 },
}

impl StepChoice {
    fn halvings(self) -> u32 {
        match self {
            StepChoice::Given => 0,
            StepChoice::Resolving { halvings, .. } | StepChoice::Confirming { halvings } => {
                halvings
            }
            StepChoice::Unresolved { .. } => MAX_HALVINGS,
        }
    }
}

/// The default step halved until the energy's excursion over one period is
/// within [`RESOLVED_EXCURSION`] (at most [`MAX_HALVINGS`] times), and how
/// it was found.
fn resolving_step<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> (f64, StepChoice) {
    let period = scene.period();
    let start = scene.initial();
    let e0 = scene.energy(&start);
    let norm = energy_norm(scene);
    let mut h = DEFAULT_STEP * period;
    let mut last = None;
    for halvings in 0..MAX_HALVINGS {
        let steps = (period / h).round() as u64;
        let mut excursion = 0.0f64;
        let outcome = integrate(scheme, scene, &start, h, steps, |_, _, s| {
            excursion = excursion.max((scene.energy(s) - e0).abs() / norm);
        });
        if outcome.completed() && excursion <= RESOLVED_EXCURSION {
            return (
                h,
                StepChoice::Resolving {
                    halvings,
                    excursion,
                },
            );
        }
        last = outcome.completed().then_some(excursion);
        h /= 2.0;
    }
    (h, StepChoice::Unresolved { excursion: last })
}

pub use crate::scene::energy_norm;

/// Samples of the running maximum kept for the fit and for figures,
/// log-spaced in time.
pub const SAMPLES: usize = 200;

/// What to measure.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct EnergySpec {
    /// The step; `None` for [`DEFAULT_STEP`] periods.
    pub h: Option<f64>,
    /// Length of the run in periods; `None` for [`DEFAULT_PERIODS`].
    pub periods: Option<f64>,
}

impl EnergySpec {
    /// The run's length in periods and the step asked for, refused before
    /// any run unless the run has at least one step and at most
    /// [`MAX_TOTAL_STEPS`](crate::ladder::MAX_TOTAL_STEPS): `periods` finite
    /// and positive with a finite end time `periods * period`; a given `h` in
    /// `(0, periods * period]`; without one, at least [`DEFAULT_STEP`]
    /// periods. The default step resolving the motion is halved with the
    /// run's length, so its count is `periods / DEFAULT_STEP` whatever the
    /// halvings.
    pub fn checked(&self, period: f64) -> Result<(f64, Option<f64>), Error> {
        let periods = crate::scene::positive("periods", self.periods.unwrap_or(DEFAULT_PERIODS))?;
        let t_end = periods * period;
        if !t_end.is_finite() {
            return Err(Error::OutOfRange {
                name: "periods",
                value: periods,
                expected: format!(
                    "a number in (0, {}]: the run's end time, periods times the period {}, must \
                     be a finite number",
                    figure(f64::MAX / period),
                    figure(period)
                ),
            });
        }
        let Some(h) = self.h else {
            if periods < DEFAULT_STEP {
                return Err(Error::OutOfRange {
                    name: "periods",
                    value: periods,
                    expected: format!(
                        "at least {DEFAULT_STEP} periods, one default step (or give the step h)"
                    ),
                });
            }
            check_count(periods / DEFAULT_STEP)?;
            return Ok((periods, None));
        };
        let h = crate::scene::positive("h", h)?;
        if h > t_end {
            return Err(Error::OutOfRange {
                name: "h",
                value: h,
                expected: format!(
                    "a step in (0, {}]: at least one step over the run of {} periods",
                    figure(t_end),
                    crate::wording::exact(periods)
                ),
            });
        }
        check_count(t_end / h)?;
        Ok((periods, Some(h)))
    }
}

/// How the energy error grows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum EnergyClass {
    /// The running maximum stops growing: `g` near 0.
    Bounded,
    /// It grows like `t^(1/2)`: round-off accumulating as a random walk.
    RandomWalk,
    /// It grows like `t` or faster: the scheme does not conserve energy.
    Drifting,
}

impl EnergyClass {
    /// The kebab-case name used in records.
    pub fn name(self) -> &'static str {
        match self {
            EnergyClass::Bounded => "bounded",
            EnergyClass::RandomWalk => "random-walk",
            EnergyClass::Drifting => "drifting",
        }
    }
}

/// What the energy study found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EnergyRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// The step.
    pub h: f64,
    /// Steps taken (fewer than asked if the run blew up).
    pub steps: u64,
    /// Length of the run asked for, in periods.
    pub periods: f64,
    /// How the run ended.
    pub outcome: Outcome,
    /// `E(0)`.
    pub initial_energy: f64,
    /// `max |E(t) - E0| / |E0|` over the run.
    pub max_relative_energy_error: f64,
    /// The relative error at the end of the run.
    pub final_relative_energy_error: f64,
    /// The largest change of the energy in one step, relative to `|E0|`
    /// (with the time it happened): above [`RESOLVED_EXCURSION`] the step
    /// does not resolve the motion there (a close encounter, a pericentre).
    pub largest_step_change: [f64; 2],
    /// When the orbit was lost: the time a bound orbit's energy reached zero
    /// (it escaped), or the relative error first passed [`LOST_FRACTION`] if
    /// it was still growing after the first period.
    pub lost_at: Option<f64>,
    /// Exponent `g` of the growth `~ t^g` over the fit range, of the running
    /// maximum of `|E(t) - E(T)| / |E0|` after the first period `T` (of
    /// `|E(t) - E0| / |E0|` for runs shorter than that).
    pub growth_exponent: Option<f64>,
    /// The time range of that fit.
    pub fit_range: Option<[f64; 2]>,
    /// The class of `g`.
    pub class: Option<EnergyClass>,
    /// What the scheme's claims imply: bounded if symplectic or symmetric
    /// (no secular drift), else drifting.
    pub expected: EnergyClass,
    /// Claim and measurement agree.
    pub verdict: Verdict,
    /// Why, in one line.
    pub reason: String,
    /// What was measured, without the verdict.
    pub summary: String,
    /// The run stopped on a defect of the step (a panic, or a stop where a
    /// coarser step ran the same span cleanly; see
    /// [`crate::study::breakdown`]): the verdict fails on it, and no finer
    /// step is tried.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub breakdown: Option<Breakdown>,
    /// `(t, running maximum)` at log-spaced times.
    pub samples: Vec<[f64; 2]>,
}

/// Runs `scheme` on `scene` for a long time and measures its energy error.
pub fn energy_drift<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    spec: &EnergySpec,
) -> Result<EnergyRecord, Error> {
    let meta = scheme.meta();
    // a symplectic or a symmetric scheme promises no secular drift
    let conserves = meta.symplectic || meta.symmetric;
    let (periods, given) = spec.checked(scene.period())?;
    let (h, choice) = match given {
        Some(h) => (h, StepChoice::Given),
        None if conserves => resolving_step(scheme, scene),
        None => (DEFAULT_STEP * scene.period(), StepChoice::Given),
    };
    let first = energy_at(scheme, scene, h, choice, periods)?;
    if spec.h.is_some() || !conserves || first.verdict != Verdict::Fail || first.breakdown.is_some()
    {
        return Ok(first);
    }
    // A conservation claim refuted at the first step that resolves the
    // first period. Backward error analysis makes a symplectic (or
    // symmetric) map follow a modified energy only while the step resolves
    // the motion all along: a close encounter later on, a resonance near
    // the limit, can let the energy jump or wander. The refutation stands
    // only if the energy still drifts at half the step, in a run whose every
    // step changed the energy by less than RESOLVED_EXCURSION; while steps
    // jump by more, the step is halved again.
    let claims = Claims::of(meta.symplectic, meta.symmetric);
    let first_h = first.h;
    let mut record = first;
    for k in choice.halvings() + 1..=MAX_HALVINGS {
        let finer = energy_at(
            scheme,
            scene,
            record.h / 2.0,
            StepChoice::Confirming { halvings: k },
            periods,
        )?;
        match confirm(&record, finer, scheme.epsilon()) {
            Weighed::Decided(decided) => return Ok(decided),
            Weighed::HalveAgain(finer) => record = finer,
        }
    }
    let [change, at] = record.largest_step_change;
    record.verdict = Verdict::Inconclusive;
    record.reason = format!(
        "{} at h = {}: one step changes the energy by {} of E0 (at t = {}; a close \
         encounter, a pericentre, not resolved), and so did a step at every step size tried \
         from h = {} down, so {} cannot be tested; take a smaller step (EnergySpec::h)",
        record.summary,
        figure(record.h),
        vs_upper(change, "", RESOLVED_EXCURSION),
        figure(at),
        figure(first_h),
        claims.name,
    );
    Ok(record)
}

/// What the run at half the step makes of a refutation.
enum Weighed {
    /// The verdict is reached, with the record that states it.
    Decided(EnergyRecord),
    /// The finer run failed too without resolving every step: halve again.
    HalveAgain(EnergyRecord),
}

/// A refutation at the step of `coarser` weighed by the run at half that
/// step.
fn confirm(coarser: &EnergyRecord, finer: EnergyRecord, epsilon: f64) -> Weighed {
    let at_coarser = format!("at h = {}: {}", figure(coarser.h), coarser.summary);
    let [change, _] = finer.largest_step_change;
    let (verdict, reason) = match (finer.verdict, finer.class) {
        (Verdict::Fail, _) if change <= RESOLVED_EXCURSION => (
            Verdict::Fail,
            format!(
                "{}; confirmed at half the step, h = {}, where one step changes the energy by \
                 {} of E0 ({at_coarser})",
                finer.reason,
                figure(finer.h),
                vs_upper(change, "", RESOLVED_EXCURSION),
            ),
        ),
        (Verdict::Fail, _) => return Weighed::HalveAgain(finer),
        (Verdict::Pass, Some(EnergyClass::Bounded)) => (
            Verdict::Pass,
            format!(
                "{}: bounded at half the step, h = {}, so the coarser step did not resolve the \
                 motion well enough for the claim to apply ({at_coarser})",
                finer.reason,
                figure(finer.h),
            ),
        ),
        // a conserving claim passes a run that is not bounded only when its
        // growth stays within round-off: neither run decides
        (Verdict::Pass, _) => (
            Verdict::Inconclusive,
            format!(
                "{at_coarser}; at half the step, h = {}: {}, {}: a change that small cannot be \
                 told from round-off, nor the coarser step's drift from a step that did not \
                 resolve the motion; take a step between the two (EnergySpec::h)",
                figure(finer.h),
                class_head(finer.class, finer.growth_exponent),
                round_off_comparison(finer.max_relative_energy_error, finer.steps, epsilon),
            ),
        ),
        // (an energy record judges every scheme: it is never "not claimed")
        (Verdict::Inconclusive | Verdict::NotClaimed, _) => (
            Verdict::Inconclusive,
            format!(
                "at half the step, h = {}: {} ({at_coarser})",
                figure(finer.h),
                finer.reason
            ),
        ),
    };
    Weighed::Decided(EnergyRecord {
        verdict,
        reason,
        ..finer
    })
}

/// The energy study at the step `h`, chosen as `choice` says: the run
/// keeps its number of steps, `periods` of the default step, so its length
/// in periods shrinks with the step.
fn energy_at<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    h: f64,
    choice: StepChoice,
    periods: f64,
) -> Result<EnergyRecord, Error> {
    let meta = scheme.meta();
    let periods = periods / f64::from(1u32 << choice.halvings());
    let t_end = periods * scene.period();
    let steps = steps_for(t_end, h)?;
    check_cost(steps)?;
    let trace = trace_energy(scheme, scene, h, steps, t_end);
    let lost_at = trace.lost_at();
    let growth = trace.growth_law(h, scene.period());
    let class = trace.class(lost_at, growth.exponent);
    let claims = Claims::of(meta.symplectic, meta.symmetric);
    let measured = trace.describe(lost_at, class, growth.exponent);
    let (mut verdict, mut reason) =
        claims.judge(&trace, lost_at, class, growth.exponent, &measured);
    // A run that stopped before its orbit was lost: instability at this
    // step, or a defect of the step (see `breakdown.rs`), which fails
    // whatever the claims.
    let stopped = (!trace.outcome.completed())
        .then(|| probe(scheme, scene, &scene.initial(), h, &trace.outcome));
    if let Some(p) = &stopped {
        let finding = p.describe(h, &trace.outcome);
        (verdict, reason) = match p {
            _ if p.is_defect() => (verdict, reason),
            // Past the linear stability limit even an area-preserving map
            // grows exponentially: instability, whatever the energy did on
            // the way. Within it, an orbit lost before the stop drifted (a
            // finer step would drift less, so a probe cannot tell drift from
            // instability there), and that verdict stands.
            Probe::Unstable { limit: Some(_), .. } if claims.conserves => (
                Verdict::Inconclusive,
                format!(
                    "{finding}: {} conserves energy only at steps where it is stable; take a \
                     smaller step (EnergySpec::h)",
                    claims.name
                ),
            ),
            _ if claims.conserves && lost_at.is_some() => (verdict, reason),
            Probe::Unstable { .. } if claims.conserves => (
                Verdict::Inconclusive,
                format!(
                    "{finding}: {} conserves energy only at steps where it is stable; take a \
                     smaller step (EnergySpec::h)",
                    claims.name
                ),
            ),
            _ if claims.conserves => (
                Verdict::Inconclusive,
                format!(
                    "{finding}: no conservation law applies to a run that stops; check that \
                     the scene's period is its shortest time scale"
                ),
            ),
            _ => (verdict, format!("{reason} ({finding})")),
        };
    }
    // A given step that does not resolve the first period, by the rule the
    // default step is halved by, tests no conservation law either: an orbit
    // lost at it is the step's doing, not a drift the claims forbid.
    if choice == StepChoice::Given && claims.conserves && verdict == Verdict::Fail {
        let excursion = trace.after_one_period.unwrap_or(trace.running);
        if excursion > RESOLVED_EXCURSION {
            verdict = Verdict::Inconclusive;
            reason = format!(
                "{measured} at h = {}; but the energy's excursion over the first period is {} \
                 of E0 at this step, so the step does not resolve the motion and no \
                 conservation law applies at it; take a smaller step (EnergySpec::h)",
                figure(h),
                vs_upper(excursion, "", RESOLVED_EXCURSION),
            );
        }
    }
    let (mut verdict, mut reason) =
        at_chosen_step(claims.conserves, verdict, reason, &measured, h, choice);
    let breakdown = stopped.as_ref().and_then(Probe::breakdown).cloned();
    if let Some(b) = &breakdown {
        verdict = Verdict::Fail;
        reason = format!("the run did not complete: {}", b.describe());
    }
    Ok(EnergyRecord {
        scheme: meta.id,
        scene: scene.meta().id,
        h,
        steps: trace.taken,
        periods,
        outcome: trace.outcome,
        initial_energy: trace.e0,
        max_relative_energy_error: trace.running,
        largest_step_change: trace.largest_step_change,
        final_relative_energy_error: trace.last,
        lost_at,
        growth_exponent: growth.exponent,
        fit_range: growth.range,
        class,
        expected: claims.expected(),
        verdict,
        reason,
        summary: measured,
        breakdown,
        samples: trace.samples,
    })
}

/// What one run records of its energy error.
struct EnergyTrace {
    outcome: Outcome,
    e0: f64,
    /// `(t, running maximum of |E - E0| / norm)` at log-spaced times
    samples: Vec<[f64; 2]>,
    /// `(t, running maximum of |E - E(T)| / norm)` after the first period
    /// `T`: the growth law is fitted to it, so that a jump in the first
    /// period (a coarse step through a pericentre) cannot mask a drift
    drift_samples: Vec<(f64, f64)>,
    running: f64,
    last: f64,
    taken: u64,
    /// the unit round-off of the scheme's arithmetic
    epsilon: f64,
    t_first: f64,
    /// the running maximum when the first period ended
    after_one_period: Option<f64>,
    /// when the error first passed [`LOST_FRACTION`]
    past_lost_fraction: Option<f64>,
    /// when a bound orbit's energy reached zero
    unbound: Option<f64>,
    /// the largest change in one step, and when
    largest_step_change: [f64; 2],
}

/// Runs `steps` steps of `h` and samples the energy error at log-spaced
/// times from 10 steps to `t_end`.
fn trace_energy<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    h: f64,
    steps: u64,
    t_end: f64,
) -> EnergyTrace {
    let period = scene.period();
    let start = scene.initial();
    let e0 = scene.energy(&start);
    let norm = energy_norm(scene);
    let t_first = 10.0 * h;
    let ratio = (t_end / t_first).powf(1.0 / (SAMPLES - 1) as f64);
    let mut next_sample = t_first;
    let mut trace = EnergyTrace {
        outcome: Outcome::Completed,
        e0,
        samples: Vec::with_capacity(SAMPLES + 1),
        drift_samples: Vec::with_capacity(SAMPLES + 1),
        running: 0.0,
        last: 0.0,
        taken: 0,
        epsilon: scheme.epsilon(),
        t_first,
        after_one_period: None,
        past_lost_fraction: None,
        unbound: None,
        largest_step_change: [0.0, 0.0],
    };
    let (mut previous, mut e_reference, mut drift) = (e0, None, 0.0f64);
    let outcome = integrate(scheme, scene, &start, h, steps, |n, t, s| {
        let e = scene.energy(s);
        let err = (e - e0).abs() / norm;
        let change = (e - previous).abs() / norm;
        if change > trace.largest_step_change[0] {
            trace.largest_step_change = [change, t];
        }
        previous = e;
        // a bound orbit (E0 < 0, as for Kepler) whose energy reaches zero has escaped
        if trace.unbound.is_none() && e0 < 0.0 && e >= 0.0 {
            trace.unbound = Some(t);
        }
        trace.running = trace.running.max(err);
        trace.last = err;
        trace.taken = n;
        if trace.past_lost_fraction.is_none() && trace.running > LOST_FRACTION {
            trace.past_lost_fraction = Some(t);
        }
        if trace.after_one_period.is_none() && t >= period {
            trace.after_one_period = Some(trace.running);
            e_reference = Some(e);
        }
        if let Some(reference) = e_reference {
            drift = drift.max((e - reference).abs() / norm);
        }
        if t >= next_sample {
            trace.samples.push([t, trace.running]);
            if e_reference.is_some() {
                trace.drift_samples.push((t, drift));
            }
            while next_sample <= t {
                next_sample *= ratio;
            }
        }
    });
    trace.outcome = outcome;
    trace
}

/// A growth law `max|dE| ~ t^g` fitted over the end of a run.
struct GrowthLaw {
    exponent: Option<f64>,
    range: Option<[f64; 2]>,
}

impl EnergyTrace {
    /// The orbit is lost when a bound orbit escapes, or when an error of
    /// the order of the energy itself was still growing after the first
    /// period (when a bounded error has sampled its whole oscillation):
    /// however flat the error then looks (Euler's expanding Kepler orbit
    /// approaches E = 0 from below), the energy was not conserved.
    fn lost_at(&self) -> Option<f64> {
        self.unbound.or(self.past_lost_fraction.filter(|_| {
            self.after_one_period
                .is_some_and(|m| self.running > LOST_GROWTH * m)
        }))
    }

    /// The growth law over the last [`GROWTH_DECADES`] decades of the run,
    /// from no earlier than where the quantity fitted has reached its
    /// plateau if it is bounded: an error that oscillates with the orbit
    /// reaches its largest value within one period, so the running maximum
    /// of `|E - E0|` has by the end of the first period, and the drift from
    /// the state after it by the end of the second. Before that a bounded
    /// error is still rising, which a fit reads as growth: velocity Verlet's
    /// over 14 periods, fitted from 0.14 of a period, came out `g = 1.5`,
    /// and its drift over 10 periods, fitted from the first, `g = 0.33`,
    /// both failing a correct scheme. A window left shorter than a decade
    /// cannot tell `t^(1/2)` from `t`: no exponent.
    fn growth_law(&self, h: f64, period: f64) -> GrowthLaw {
        let t_stop = self.taken as f64 * h;
        let (growth_samples, plateau): (Vec<(f64, f64)>, f64) = if self.drift_samples.len() >= 3 {
            (self.drift_samples.clone(), 2.0 * period)
        } else {
            (self.samples.iter().map(|&[t, m]| (t, m)).collect(), period)
        };
        let t_from = (t_stop / 10f64.powf(GROWTH_DECADES)).max(plateau);
        let too_short = t_stop < 10.0 * t_from;
        let window: Vec<(f64, f64)> = growth_samples
            .iter()
            .copied()
            .filter(|&(t, m)| t >= t_from && t <= t_stop && m > 0.0)
            .collect();
        let fit = power_law(&window).filter(|_| !too_short);
        let exponent = if growth_samples.iter().all(|&(_, m)| m == 0.0) {
            Some(0.0)
        } else {
            fit.map(|f| f.slope)
        };
        GrowthLaw {
            exponent,
            range: fit.map(|_| [t_from.max(self.t_first), t_stop]),
        }
    }

    fn class(&self, lost_at: Option<f64>, growth_exponent: Option<f64>) -> Option<EnergyClass> {
        if !self.outcome.completed() || lost_at.is_some() {
            // an orbit destroyed or blown up has not conserved energy,
            // whatever the slope just before
            return Some(EnergyClass::Drifting);
        }
        // growth within what round-off alone can produce is round-off,
        // whatever its exponent: a random walk of eps a step, or at worst a
        // linear sum when rounding is biased
        growth_exponent.map(classify_growth).map(|c| {
            if c != EnergyClass::Bounded
                && self.running <= round_off_energy(self.taken, self.epsilon)
            {
                EnergyClass::RandomWalk
            } else {
                c
            }
        })
    }

    /// One line on what was measured.
    fn describe(
        &self,
        lost_at: Option<f64>,
        class: Option<EnergyClass>,
        growth_exponent: Option<f64>,
    ) -> String {
        let running = figure(self.running);
        match (class, lost_at) {
            _ if !self.outcome.completed() => format!(
                "{}, the energy error having reached {running} of E0",
                self.outcome.brief()
            ),
            (_, Some(t)) => format!(
                "orbit lost at t = {} (escaped, or an energy error past {LOST_FRACTION} of E0 \
                 that kept growing), max relative error {running}",
                figure(t),
            ),
            (Some(_), None) => format!(
                "{}, max relative error {running}",
                class_head(class, growth_exponent)
            ),
            (None, None) => "too few samples to fit a growth law".to_string(),
        }
    }
}

/// The class and exponent of a growth law: "drifting (g = 1.00)". A
/// drift-like exponent classed as round-off (its error within what
/// round-off can produce) is called so, not a random walk.
fn class_head(class: Option<EnergyClass>, growth_exponent: Option<f64>) -> String {
    let exponent = growth_exponent.map_or(String::new(), |g| format!(" (g = {g:.2})"));
    match class {
        Some(EnergyClass::RandomWalk)
            if growth_exponent.map(classify_growth) == Some(EnergyClass::Drifting) =>
        {
            format!("drift-like growth{exponent}")
        }
        Some(c) => format!("{}{exponent}", c.name()),
        None => format!("no class{exponent}"),
    }
}

/// The largest relative energy error against what round-off alone can
/// produce in `steps` steps ([`round_off_energy`]).
fn round_off_comparison(running: f64, steps: u64, epsilon: f64) -> String {
    let allowance = round_off_energy(steps, epsilon);
    format!(
        "max relative error {} ({} eps a step over {steps} steps)",
        vs_upper(running, "round-off allowance", allowance),
        figure(allowance / (epsilon * steps.max(1) as f64)),
    )
}

/// What a scheme's two geometric claims promise of its energy.
struct Claims {
    conserves: bool,
    name: &'static str,
}

impl Claims {
    fn of(symplectic: bool, symmetric: bool) -> Self {
        let name = match (symplectic, symmetric) {
            (true, true) => "a symplectic, symmetric scheme",
            (true, false) => "a symplectic scheme",
            (false, true) => "a symmetric scheme",
            (false, false) => "a scheme neither symplectic nor symmetric",
        };
        Claims {
            conserves: symplectic || symmetric,
            name,
        }
    }

    fn expected(&self) -> EnergyClass {
        if self.conserves {
            EnergyClass::Bounded
        } else {
            EnergyClass::Drifting
        }
    }

    /// The verdict on one run: a conserving claim is refuted by drift, by a
    /// wander above round-off or by a lost orbit; a claim of neither
    /// property by nothing.
    fn judge(
        &self,
        trace: &EnergyTrace,
        lost_at: Option<f64>,
        class: Option<EnergyClass>,
        growth_exponent: Option<f64>,
        measured: &str,
    ) -> (Verdict, String) {
        let (conserves, claims) = (self.conserves, self.name);
        let completed = trace.outcome.completed();
        let round_off = round_off_energy(trace.taken, trace.epsilon);
        // the growth law beside the round-off it was classed against
        let against_round_off = format!(
            "{}, {}",
            class_head(class, growth_exponent),
            round_off_comparison(trace.running, trace.taken, trace.epsilon)
        );
        match class {
            // a blow-up at this step, before the orbit was lost to a growing
            // error, says nothing about conservation below the scheme's
            // stability limit (past it even an area-preserving map grows
            // exponentially); an orbit lost first was not conserved
            _ if conserves && !completed && lost_at.is_none() => (
                Verdict::Inconclusive,
                format!(
                    "{measured}; {claims} conserves energy only at stable steps: take a smaller \
                     step (EnergySpec::h), or check that the scene's period is its shortest \
                     time scale"
                ),
            ),
            _ if conserves && (!completed || lost_at.is_some()) => (
                Verdict::Fail,
                format!("{measured}: {claims} must not drift"),
            ),
            Some(EnergyClass::Drifting) if conserves => (
                Verdict::Fail,
                format!("{against_round_off}: {claims} must not drift"),
            ),
            // a symplectic map's energy error is bounded; one that wanders
            // like a random walk far above what round-off can do is not
            // conserved
            Some(EnergyClass::RandomWalk) if conserves && trace.running > round_off => (
                Verdict::Fail,
                format!("{against_round_off}: {claims} must not wander"),
            ),
            // in f32 the allowance 10 eps N reaches 1 at 10^6 steps, so a
            // slow drift can hide in it: say so rather than "no drift"
            Some(EnergyClass::RandomWalk) if conserves => (
                Verdict::Pass,
                format!(
                    "{against_round_off}: a growth this small cannot be told from the round-off \
                     of this arithmetic, so this run cannot refute the claims of \
                     {claims}; the symplecticity study decides"
                ),
            ),
            Some(_) if conserves => (
                Verdict::Pass,
                format!("{measured}: no secular drift, as {claims} promises"),
            ),
            _ if !completed || lost_at.is_some() => (
                Verdict::Pass,
                format!("{measured}, as expected of {claims}"),
            ),
            Some(EnergyClass::Drifting) => (
                Verdict::Pass,
                format!("{against_round_off}, as expected of {claims}"),
            ),
            Some(EnergyClass::RandomWalk) if trace.running > round_off => (
                Verdict::Pass,
                format!(
                    "{against_round_off}: a growth slower than a drift; {claims} promises \
                     nothing (reported, not a refutation)"
                ),
            ),
            Some(EnergyClass::RandomWalk) => (
                Verdict::Pass,
                format!(
                    "{against_round_off}: no drift resolved above round-off; {claims} may \
                     drift below it (reported, not a refutation)"
                ),
            ),
            Some(EnergyClass::Bounded) => (
                Verdict::Pass,
                format!(
                    "{measured} on this scene; {claims} promises nothing, so one scene where \
                     the energy happens to stay bounded refutes nothing"
                ),
            ),
            None => (
                Verdict::Inconclusive,
                format!("{measured}: run longer (EnergySpec::periods)"),
            ),
        }
    }
}

/// Says how the step was chosen when the default step was halved to
/// resolve the first period, and makes a conservation claim inconclusive
/// when even the finest step did not resolve it.
fn at_chosen_step(
    conserves: bool,
    verdict: Verdict,
    reason: String,
    measured: &str,
    h: f64,
    choice: StepChoice,
) -> (Verdict, String) {
    match choice {
        StepChoice::Resolving {
            halvings,
            excursion,
        } if halvings > 0 && verdict != Verdict::Inconclusive => (
            verdict,
            format!(
                "{reason} (at h = {}, {halvings} halving{} of the default step, the first at \
                 which the energy's excursion over the first period is {} of E0)",
                figure(h),
                if halvings > 1 { "s" } else { "" },
                vs_upper(excursion, "", RESOLVED_EXCURSION),
            ),
        ),
        StepChoice::Unresolved { excursion } if conserves => (
            Verdict::Inconclusive,
            format!(
                "{measured} at h = {}; but {} at h = {}, the finest step tried ({} halvings of \
                 the default), so the step does not resolve the motion and no conservation law \
                 applies yet; check that the scene's period is its shortest time scale",
                figure(h),
                excursion.map_or("the first period blows up".to_string(), |e| format!(
                    "the energy's excursion over the first period is {} of E0",
                    vs_upper(e, "", RESOLVED_EXCURSION)
                )),
                figure(2.0 * h),
                MAX_HALVINGS - 1,
            ),
        ),
        _ => (verdict, reason),
    }
}

/// The energy class of a growth exponent `g`: the boundaries sit halfway
/// between the three laws, `g = 0` (bounded), `1/2` (random walk) and `1`
/// (drift).
pub fn classify_growth(g: f64) -> EnergyClass {
    if g < BOUNDED_BELOW {
        EnergyClass::Bounded
    } else if g < RANDOM_WALK_BELOW {
        EnergyClass::RandomWalk
    } else {
        EnergyClass::Drifting
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wording::comparisons;

    /// A completed run of `steps` steps in `f64` whose running maximum
    /// ends at `running`.
    fn trace(running: f64, steps: u64) -> EnergyTrace {
        EnergyTrace {
            outcome: Outcome::Completed,
            e0: -0.5,
            samples: Vec::new(),
            drift_samples: Vec::new(),
            running,
            last: running,
            taken: steps,
            epsilon: f64::EPSILON / 2.0,
            t_first: 0.1,
            after_one_period: Some(running / 100.0),
            past_lost_fraction: None,
            unbound: None,
            largest_step_change: [running / steps as f64, 1.0],
        }
    }

    /// The record `energy_at` makes of `trace` with growth exponent `g`,
    /// judged as the claims of a symplectic scheme.
    fn judged(trace: EnergyTrace, g: f64, h: f64) -> EnergyRecord {
        let claims = Claims::of(true, false);
        let class = trace.class(None, Some(g));
        let measured = trace.describe(None, class, Some(g));
        let (verdict, reason) = claims.judge(&trace, None, class, Some(g), &measured);
        EnergyRecord {
            scheme: "test",
            scene: "test",
            h,
            steps: trace.taken,
            periods: 1e4,
            outcome: Outcome::Completed,
            initial_energy: trace.e0,
            max_relative_energy_error: trace.running,
            final_relative_energy_error: trace.last,
            largest_step_change: trace.largest_step_change,
            lost_at: None,
            growth_exponent: Some(g),
            fit_range: None,
            class,
            expected: claims.expected(),
            verdict,
            reason,
            summary: measured,
            breakdown: None,
            samples: Vec::new(),
        }
    }

    /// A drift (g = 1.00, far above round-off) at the first resolving step,
    /// and at half the step the same exponent within round-off: the run at
    /// half the step passes on its own, and neither decides. The reason
    /// must say what was measured at both steps, set the error against the
    /// round-off allowance it is within, and must not carry the passing
    /// run's "does not refute" into an inconclusive verdict.
    #[test]
    fn a_drift_at_one_step_and_round_off_at_half_of_it_is_inconclusive_and_says_why() {
        let steps = 1_000_000;
        let coarser = judged(trace(3.4e-2, steps), 1.0, 0.01);
        assert_eq!(coarser.verdict, Verdict::Fail, "{}", coarser.reason);
        let allowance = round_off_energy(steps, f64::EPSILON / 2.0);
        let finer = judged(trace(0.5 * allowance, steps), 1.0, 0.005);
        assert_eq!(finer.verdict, Verdict::Pass, "{}", finer.reason);
        assert_eq!(finer.growth_exponent, Some(1.0));
        let Weighed::Decided(decided) = confirm(&coarser, finer, f64::EPSILON / 2.0) else {
            panic!("a pass at half the step decides")
        };
        let reason = &decided.reason;
        assert_eq!(decided.verdict, Verdict::Inconclusive, "{reason}");
        assert!(!reason.contains("refute"), "{reason}");
        assert!(
            reason.contains("at h = 1.00e-2") && reason.contains("h = 5.00e-3"),
            "{reason}"
        );
        let printed = comparisons(reason).expect("readable");
        assert!(printed.iter().all(|c| c.holds()), "{reason}");
        // the finer run's error within the allowance, as the advice says
        assert!(
            printed
                .iter()
                .any(|c| c.operator == "<=" && c.right > c.left),
            "{reason}"
        );
    }

    /// A run at a step that never resolved the first period: whatever the
    /// run's own verdict said ("no secular drift, as ... promises"), the
    /// inconclusive reason states what was measured and why no law applies.
    #[test]
    fn an_unresolved_step_does_not_repeat_a_passing_verdict() {
        let (verdict, reason) = at_chosen_step(
            true,
            Verdict::Pass,
            "bounded (g = 0.05), max relative error 2.57: no secular drift, as a symplectic \
             scheme promises"
                .to_string(),
            "bounded (g = 0.05), max relative error 2.57",
            2.7e-4,
            StepChoice::Unresolved {
                excursion: Some(2.5),
            },
        );
        assert_eq!(verdict, Verdict::Inconclusive);
        assert!(!reason.contains("promises"), "{reason}");
        let printed = comparisons(&reason).expect("readable");
        assert_eq!(printed.len(), 1, "{reason}");
        assert!(printed[0].holds() && printed[0].left == 2.5, "{reason}");
    }
}
