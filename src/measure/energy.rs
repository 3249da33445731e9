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

use super::Verdict;
use super::fit::power_law;
use crate::error::Error;
use crate::ladder::{check_cost, steps_for};
use crate::run::{Outcome, integrate};
use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::tolerance::{
    GROWTH_DECADES, LOST_FRACTION, LOST_GROWTH, classify_growth, round_off_energy,
};
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
/// shrinks by the same factor (to 39 periods, still two decades of time
/// after the first).
pub const MAX_HALVINGS: u32 = 8;

/// The default step halved until the energy's excursion over one period is
/// within [`RESOLVED_EXCURSION`] (at most [`MAX_HALVINGS`] times), and the
/// halvings made.
fn resolving_step<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) -> (f64, u32) {
    let period = scene.period();
    let start = scene.initial();
    let e0 = scene.energy(&start);
    let norm = energy_norm(scene);
    let mut h = DEFAULT_STEP * period;
    for halvings in 0..MAX_HALVINGS {
        let steps = (period / h).round() as u64;
        let mut excursion = 0.0f64;
        let outcome = integrate(scheme, scene, &start, h, steps, |_, _, s| {
            excursion = excursion.max((scene.energy(s) - e0).abs() / norm);
        });
        if outcome.completed() && excursion <= RESOLVED_EXCURSION {
            return (h, halvings);
        }
        h /= 2.0;
    }
    (h, MAX_HALVINGS)
}

/// What relative energy errors are relative to: `|E0|`, or for a scene with
/// zero energy its kinetic energy scale, so the ratio stays finite.
pub fn energy_norm<S: Scene<D>, const D: usize>(scene: &S) -> f64 {
    let e0 = scene.energy(&scene.initial());
    if e0 != 0.0 {
        e0.abs()
    } else {
        0.5 * (scene.frequency() * scene.scale()).powi(2)
    }
}

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
    let periods = crate::scene::positive("periods", spec.periods.unwrap_or(DEFAULT_PERIODS))?;
    let (h, halvings) = match spec.h {
        Some(h) => (crate::scene::positive("h", h)?, 0),
        None if conserves => resolving_step(scheme, scene),
        None => (DEFAULT_STEP * scene.period(), 0),
    };
    let first = energy_at(scheme, scene, h, halvings, periods)?;
    if spec.h.is_some() || !conserves || first.verdict != Verdict::Fail {
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
    let mut record = first;
    let mut notes: Vec<String> = Vec::new();
    for k in halvings + 1..=MAX_HALVINGS {
        notes.push(format!("at h = {:.3e}: {}", record.h, record.summary));
        let finer = energy_at(scheme, scene, record.h / 2.0, k, periods)?;
        let resolved = finer.largest_step_change[0] <= RESOLVED_EXCURSION;
        let (verdict, note) = match (finer.verdict, finer.class) {
            (Verdict::Fail, _) if resolved => (Some(Verdict::Fail), "confirmed at half the step"),
            (Verdict::Fail, _) => (None, ""),
            (Verdict::Pass, Some(EnergyClass::Bounded)) => (
                Some(Verdict::Pass),
                "bounded at half the step: the coarser step did not resolve the motion well \
                 enough for the claim to apply",
            ),
            _ => (
                Some(Verdict::Inconclusive),
                "at half the step the change is within round-off: a drift that small cannot be \
                 told from a step that did not resolve the motion; take a step between the two",
            ),
        };
        record = finer;
        if let Some(v) = verdict {
            record.verdict = v;
            record.reason = format!("{} ({}; {note})", record.reason, notes.join("; "));
            return Ok(record);
        }
    }
    record.verdict = Verdict::Inconclusive;
    record.reason = format!(
        "{}: steps still change the energy by more than {RESOLVED_EXCURSION} of E0 (a close \
         encounter, a pericentre, not resolved) at h = {:.3e}, so the claim cannot be tested \
         ({})",
        record.summary,
        record.h,
        notes.join("; ")
    );
    Ok(record)
}

/// The energy study at the step `h`, `halvings` times the default: the run
/// keeps its number of steps, `periods` of the default step, so its length
/// in periods shrinks with the step.
fn energy_at<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    h: f64,
    halvings: u32,
    periods: f64,
) -> Result<EnergyRecord, Error> {
    let period = scene.period();
    let meta = scheme.meta();
    let conserves = meta.symplectic || meta.symmetric;
    let periods = periods / f64::from(1u32 << halvings);
    let t_end = periods * period;
    let steps = steps_for(t_end, h)?;
    check_cost(steps)?;
    let start = scene.initial();
    let e0 = scene.energy(&start);
    let norm = energy_norm(scene);

    // log-spaced sample times from 10 steps to the end
    let (t_first, ratio) = (
        10.0 * h,
        (t_end / (10.0 * h)).powf(1.0 / (SAMPLES - 1) as f64),
    );
    let mut next_sample = t_first;
    let mut samples: Vec<[f64; 2]> = Vec::with_capacity(SAMPLES + 1);
    let (mut running, mut last, mut taken) = (0.0f64, 0.0, 0);
    // the energy after the first period, and the running maximum of the
    // change since: the growth law is fitted to it, so that a jump in the
    // first period (a coarse step through a pericentre) cannot mask a drift
    let (mut e_reference, mut drift) = (None, 0.0f64);
    let mut drift_samples: Vec<(f64, f64)> = Vec::with_capacity(SAMPLES + 1);
    let (mut past_lost_fraction, mut after_one_period, mut unbound) = (None, None, None);
    let (mut previous, mut largest_step_change) = (e0, [0.0f64, 0.0]);
    let outcome = integrate(scheme, scene, &start, h, steps, |n, t, s| {
        let e = scene.energy(s);
        let err = (e - e0).abs() / norm;
        let change = (e - previous).abs() / norm;
        if change > largest_step_change[0] {
            largest_step_change = [change, t];
        }
        previous = e;
        // a bound orbit (E0 < 0, as for Kepler) whose energy reaches zero has escaped
        if unbound.is_none() && e0 < 0.0 && e >= 0.0 {
            unbound = Some(t);
        }
        running = running.max(err);
        last = err;
        taken = n;
        if past_lost_fraction.is_none() && running > LOST_FRACTION {
            past_lost_fraction = Some(t);
        }
        if after_one_period.is_none() && t >= period {
            after_one_period = Some(running);
            e_reference = Some(e);
        }
        if let Some(reference) = e_reference {
            drift = drift.max((e - reference).abs() / norm);
        }
        if t >= next_sample {
            samples.push([t, running]);
            if e_reference.is_some() {
                drift_samples.push((t, drift));
            }
            while next_sample <= t {
                next_sample *= ratio;
            }
        }
    });

    // The orbit is lost when a bound orbit escapes, or when an error of the
    // order of the energy itself was still growing after the first period
    // (when a bounded error has sampled its whole oscillation): however flat
    // the error then looks (Euler's expanding Kepler orbit approaches E = 0
    // from below), the energy was not conserved.
    let lost_at = unbound
        .or(past_lost_fraction
            .filter(|_| after_one_period.is_some_and(|m| running > LOST_GROWTH * m)));
    // fit the last GROWTH_DECADES decades of the run
    let t_stop = taken as f64 * h;
    let t_from = t_stop / 10f64.powf(GROWTH_DECADES);
    let growth_samples: Vec<(f64, f64)> = if drift_samples.len() >= 3 {
        drift_samples
    } else {
        samples.iter().map(|&[t, m]| (t, m)).collect()
    };
    let window: Vec<(f64, f64)> = growth_samples
        .iter()
        .copied()
        .filter(|&(t, m)| t >= t_from && t <= t_stop && m > 0.0)
        .collect();
    let all_zero = growth_samples.iter().all(|&(_, m)| m == 0.0);
    let fit = power_law(&window);
    let growth_exponent = if all_zero {
        Some(0.0)
    } else {
        fit.map(|f| f.slope)
    };
    let class = if !outcome.completed() || lost_at.is_some() {
        // an orbit destroyed or blown up has not conserved energy, whatever
        // the slope just before
        Some(EnergyClass::Drifting)
    } else {
        // growth within what round-off alone can produce is round-off,
        // whatever its exponent: a random walk of eps a step, or at worst a
        // linear sum when rounding is biased
        growth_exponent.map(classify_growth).map(|c| {
            if c != EnergyClass::Bounded && running <= round_off_energy(taken) {
                EnergyClass::RandomWalk
            } else {
                c
            }
        })
    };
    let expected = if conserves {
        EnergyClass::Bounded
    } else {
        EnergyClass::Drifting
    };
    let claims = match (meta.symplectic, meta.symmetric) {
        (true, true) => "a symplectic, symmetric scheme",
        (true, false) => "a symplectic scheme",
        (false, true) => "a symmetric scheme",
        (false, false) => "a scheme neither symplectic nor symmetric",
    };
    let measured = match (class, growth_exponent) {
        _ if !outcome.completed() => {
            format!("{outcome}: the energy grew by {running:.2e} of E0 before")
        }
        _ if lost_at.is_some() => format!(
            "orbit lost at t = {:.4} (escaped, or an energy error past {LOST_FRACTION} of E0 \
             that kept growing), to {running:.2e}",
            lost_at.unwrap_or_default(),
        ),
        (Some(c), g) => format!(
            "{}{}, max relative error {running:.2e}",
            c.name(),
            g.map_or(String::new(), |g| format!(" (g = {g:.2})")),
        ),
        (None, _) => "too few samples to fit a growth law".to_string(),
    };
    let (verdict, reason) = match class {
        // a blow-up at this step, before the orbit was lost to a growing
        // error, says nothing about conservation below the scheme's
        // stability limit (past it even an area-preserving map grows
        // exponentially); an orbit lost first was not conserved
        _ if conserves && !outcome.completed() && lost_at.is_none() => (
            Verdict::Inconclusive,
            format!(
                "{measured}; {claims} conserves energy only at stable steps: take a smaller \
                 step (EnergySpec::h), or check that the scene's period is its shortest time \
                 scale"
            ),
        ),
        _ if conserves && !outcome.completed() => (
            Verdict::Fail,
            format!("{measured}: {claims} must not drift"),
        ),
        Some(EnergyClass::Drifting) if conserves => (
            Verdict::Fail,
            format!("{measured}: {claims} must not drift"),
        ),
        // a symplectic map's energy error is bounded; one that wanders like
        // a random walk far above what round-off can do is not conserved
        Some(EnergyClass::RandomWalk) if conserves && running > round_off_energy(taken) => (
            Verdict::Fail,
            format!(
                "{measured}, above what round-off can produce ({:.2e}): {claims} must not wander",
                round_off_energy(taken)
            ),
        ),
        Some(_) if conserves => (
            Verdict::Pass,
            format!("{measured}: no secular drift, as {claims} promises"),
        ),
        Some(EnergyClass::Drifting) => (
            Verdict::Pass,
            format!("{measured}, as expected of {claims}"),
        ),
        Some(EnergyClass::RandomWalk) => (
            Verdict::Pass,
            format!(
                "{measured}: no drift resolved above round-off; {claims} may drift below it \
                 (reported, not a refutation)"
            ),
        ),
        Some(EnergyClass::Bounded) => (
            Verdict::Pass,
            format!(
                "{measured} on this scene; {claims} promises nothing, so one scene where the \
                 energy happens to stay bounded refutes nothing"
            ),
        ),
        None => (Verdict::Inconclusive, measured.clone()),
    };
    let (verdict, reason) = match (halvings, verdict) {
        (k, Verdict::Pass | Verdict::Fail) if k > 0 => (
            verdict,
            format!(
                "{reason} (at h = {h:.3e}, {k} halving{} of the default step, the first \
                 step whose energy excursion over one period is within {RESOLVED_EXCURSION} of \
                 E0)",
                if k > 1 { "s" } else { "" }
            ),
        ),
        _ => (verdict, reason),
    };
    let (verdict, reason) = if conserves && halvings >= MAX_HALVINGS {
        (
            Verdict::Inconclusive,
            format!(
                "{reason}; the motion is not resolved even at h = {h:.3e}: its energy changes by \
                 more than {RESOLVED_EXCURSION} of E0 within a period, so no conservation law \
                 applies yet; check that the scene's period is its shortest time scale"
            ),
        )
    } else {
        (verdict, reason)
    };
    Ok(EnergyRecord {
        scheme: meta.id,
        scene: scene.meta().id,
        h,
        steps: taken,
        periods,
        outcome,
        initial_energy: e0,
        max_relative_energy_error: running,
        largest_step_change,
        final_relative_energy_error: last,
        lost_at,
        growth_exponent,
        fit_range: fit.map(|_| [t_from.max(t_first), t_stop]),
        class,
        expected,
        verdict,
        reason,
        summary: measured,
        samples,
    })
}
