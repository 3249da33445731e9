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
    /// `(t, running maximum)` at log-spaced times.
    pub samples: Vec<[f64; 2]>,
}

/// Runs `scheme` on `scene` for a long time and measures its energy error.
pub fn energy_drift<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    spec: &EnergySpec,
) -> Result<EnergyRecord, Error> {
    let period = scene.period();
    let h = match spec.h {
        Some(h) => crate::scene::positive("h", h)?,
        None => DEFAULT_STEP * period,
    };
    let periods = crate::scene::positive("periods", spec.periods.unwrap_or(DEFAULT_PERIODS))?;
    let t_end = periods * period;
    let steps = steps_for(t_end, h)?;
    check_cost(steps)?;
    let start = scene.initial();
    let e0 = scene.energy(&start);
    // relative to |E0|; a scene with zero energy is judged against its
    // kinetic energy scale instead, so the ratio stays finite
    let norm = if e0 != 0.0 {
        e0.abs()
    } else {
        0.5 * (scene.frequency() * scene.scale()).powi(2)
    };

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
    let outcome = integrate(scheme, scene, &start, h, steps, |n, t, s| {
        let e = scene.energy(s);
        let err = (e - e0).abs() / norm;
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
    let meta = scheme.meta();
    // a symplectic or a symmetric scheme promises no secular drift
    let conserves = meta.symplectic || meta.symmetric;
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
    Ok(EnergyRecord {
        scheme: meta.id,
        scene: scene.meta().id,
        h,
        steps: taken,
        periods,
        outcome,
        initial_energy: e0,
        max_relative_energy_error: running,
        final_relative_energy_error: last,
        lost_at,
        growth_exponent,
        fit_range: fit.map(|_| [t_from.max(t_first), t_stop]),
        class,
        expected,
        verdict,
        reason,
        samples,
    })
}
