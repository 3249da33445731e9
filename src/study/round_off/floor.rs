//! Round-off floors: the error of the Verlet forms and of their compensated
//! variants against the step, refined until the error stops falling.
//!
//! Each rung runs a plain scheme and its compensated twin side by side with
//! the same step over the same time, and records three maxima over the run:
//! each scheme's phase-space error against the exact solution, and the
//! distance between the two numerical solutions. The twins are the same map
//! in exact arithmetic, so that distance is the plain scheme's round-off
//! error alone, truncation removed: it can be measured at every step, even
//! where truncation hides it, and its growth as the step shrinks is fitted.
//!
//! # Why there is a floor, and how it moves with the step
//!
//! Write `u = eps/2` for the unit round-off, `A` for the size of the motion,
//! `w` for its frequency and `N = T/h` for the steps of a run of length `T`.
//!
//! - Velocity Verlet and leap-frog round each update, `q + h v` and `v + h a`,
//!   to the precision of the coordinate: a perturbation of about `u A` per
//!   step, not magnified by the step itself. On the oscillator the flow turns
//!   a perturbation without growing it, so `N` unbiased roundings add up like
//!   a random walk, `u A N^(1/2)`, which at fixed `T` grows as `h^(-1/2)`
//!   (linearly, `u A N`, if rounding were biased).
//! - The two-step form computes `2 q(n) - q(n-1)` exactly (the operands lie
//!   within a factor two of each other: Sterbenz), so its one rounding is
//!   that of `h^2 a` to the grid of `q`: a perturbation of the second
//!   difference, which is `h` times a velocity, hence a velocity error
//!   `u A / h` per step. A random walk of velocity kicks integrates into a
//!   position error `u A N^(1/2) / (h w)`, `u A N^(3/2) / (w T)` at fixed
//!   `T`: it grows as `h^(-3/2)`, a full power of `h` faster. Its
//!   central-difference velocity adds `u A / h` at each read-out, a rounded
//!   difference divided by `2 h`, which does not accumulate.
//! - The compensated variants keep what each addition drops; what they still
//!   lose is the rounding of the increments and of the force evaluated at the
//!   rounded position, `u h w A` per step, so their accumulated round-off,
//!   `u A h w N^(1/2)`, falls as the step shrinks. Their floor is set by what
//!   does not accumulate: rounding of the output and of the exact solution.
//!
//! With the truncation error `C h^2`, a plain scheme's error
//! `C h^2 + R h^(-g)` is smallest at `h* = (g R / 2C)^(1/(2+g))`, where it is
//! `(1 + 2/g)` times the truncation error alone: a floor `5 C h*^2` for
//! `g = 1/2`, `7/3 C h*^2` for `g = 3/2`.

use crate::error::Error;
use crate::ladder::{check_count, steps_for};
use crate::maths::fit::{PowerLaw, power_law};
use crate::run::guarded_step;
use crate::scene::{AnyScene, Scene, SceneVisitor};
use crate::scheme::Scheme;
use crate::scheme::compensated::{PairVisitor, paired_ids, visit_pair};
use crate::tolerance::{ROUND_OFF_FIT_STEPS, ROUND_OFF_PAST_FLOOR};
use serde::Serialize;

/// The ladder's first step, in periods of the scene.
pub const START: f64 = 1.0 / 8.0;

/// Default length of a rung's run, in periods: one orbit.
pub const DEFAULT_PERIODS: f64 = 1.0;

/// Default finest rung, in steps per period: `2^24`, where the plain
/// velocity Verlet and leap-frog on the oscillator are past their floor.
pub const DEFAULT_MAX_STEPS: u64 = 1 << 24;

/// Points of each run at which the errors are evaluated (evenly spaced, the
/// last at the end): the error of a run varies smoothly between them, and
/// evaluating the exact solution at every step would cost more than the step.
pub const SAMPLES: u64 = 4096;

/// What to measure.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct RoundoffSpec {
    /// Length of each run in periods; `None` for [`DEFAULT_PERIODS`].
    pub periods: Option<f64>,
    /// The finest rung's steps per period; `None` for [`DEFAULT_MAX_STEPS`].
    pub max_steps: Option<u64>,
}

/// One rung of a pair's ladder.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RoundoffRung {
    /// The step.
    pub h: f64,
    /// Steps to the end of the run.
    pub steps: u64,
    /// The plain scheme's largest phase-space error against the exact solution.
    pub plain_error: Option<f64>,
    /// The compensated variant's.
    pub compensated_error: Option<f64>,
    /// The largest distance between the two numerical solutions: the plain
    /// scheme's round-off, truncation removed.
    pub round_off: Option<f64>,
}

/// Where a scheme's error stopped falling.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Floor {
    /// Scheme id.
    pub scheme: &'static str,
    /// The smallest error over the ladder.
    pub floor: f64,
    /// The step at which it was reached.
    pub h: f64,
    /// A finer rung followed it and did not improve on it: the scheme stopped
    /// improving at `h`. When false, the floor lies below the smallest error
    /// measured and `h` is the finest step.
    pub stopped: bool,
}

/// One plain Verlet form and its compensated variant on one scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PairRecord {
    /// The plain scheme's id.
    pub plain: &'static str,
    /// The compensated variant's id.
    pub compensated: &'static str,
    /// Every rung, coarse to fine.
    pub rungs: Vec<RoundoffRung>,
    /// Where the plain scheme stopped improving.
    pub plain_floor: Option<Floor>,
    /// Where the compensated variant did (or the finest step, if it did not).
    pub compensated_floor: Option<Floor>,
    /// The coarsest step at which the plain scheme's round-off reached its
    /// truncation error (the compensated variant's error): from there on,
    /// halving the step no longer cuts the error by four.
    pub crossover_h: Option<f64>,
    /// `ln(round_off) = ln R + slope ln h` over the rungs of at least
    /// [`ROUND_OFF_FIT_STEPS`] steps: `slope = -g`.
    pub round_off_fit: Option<PowerLaw>,
    /// `ln(error) = ln C + slope ln h` of the compensated variant over the same
    /// rungs, while its error falls at the second-order rate: the truncation.
    pub truncation_fit: Option<PowerLaw>,
    /// `h* = (g R / 2C)^(1/(2+g))` from the two fits: where the model
    /// `C h^2 + R h^(-g)` is smallest.
    pub predicted_h: Option<f64>,
    /// The model's minimum, `(1 + 2/g) C h*^2`.
    pub predicted_floor: Option<f64>,
}

/// The round-off study on one scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RoundoffRecord {
    /// Scene id.
    pub scene: &'static str,
    /// The scene's parameters.
    pub scene_parameters: String,
    /// Length of each run.
    pub t_end: f64,
    /// The same in periods of the scene.
    pub periods: f64,
    /// The finest rung allowed, in steps.
    pub max_steps: u64,
    /// One entry per pair.
    pub pairs: Vec<PairRecord>,
}

/// The run length and step cap a spec means on a scene of this period.
fn resolve(spec: &RoundoffSpec, period: f64) -> Result<(f64, u64), Error> {
    let periods = crate::scene::positive("periods", spec.periods.unwrap_or(DEFAULT_PERIODS))?;
    // the ladder's first rung is one step of START periods
    if periods < START || !(periods * period).is_finite() {
        return Err(Error::OutOfRange {
            name: "periods",
            value: periods,
            expected: format!(
                "a number in [{START}, {}]: at least the ladder's first step of {START} period, \
                 and a finite end time",
                crate::wording::figure(f64::MAX / period)
            ),
        });
    }
    let per_period = spec.max_steps.unwrap_or(DEFAULT_MAX_STEPS);
    let too_few = || Error::InvalidParameter {
        name: "max_steps",
        value: per_period as f64,
        expected: "at least 64 steps per period, so the ladder has a few rungs",
    };
    if per_period < 64 {
        return Err(too_few());
    }
    // the ladder halves the step, so its rungs add up to at most twice the
    // finest, and each step is taken by two schemes; counted in floating
    // point, so that a refusal prints the true count
    check_count(4.0 * periods * per_period as f64)?;
    let first = steps_for(periods * period, START * period)?;
    let max_steps = steps_for(periods * period, period / per_period as f64)?;
    if max_steps < first << 3 {
        return Err(too_few());
    }
    Ok((periods * period, max_steps))
}

/// Runs the ladder of one pair on one scene.
pub fn pair_floors<P: Scheme, C: Scheme, S: Scene<D>, const D: usize>(
    plain: &P,
    compensated: &C,
    scene: &S,
    spec: &RoundoffSpec,
) -> Result<PairRecord, Error> {
    if scene.exact(0.0).is_none() {
        return Err(Error::NoExactSolution(scene.meta().id));
    }
    let period = scene.period();
    let (t_end, max_steps) = resolve(spec, period)?;
    let first = steps_for(t_end, START * period)?;
    let mut rungs: Vec<RoundoffRung> = Vec::new();
    let mut steps = first;
    while steps <= max_steps {
        rungs.push(run_pair(plain, compensated, scene, t_end, steps));
        if stopped(rungs.iter().map(|r| r.plain_error)) >= ROUND_OFF_PAST_FLOOR {
            break;
        }
        steps *= 2;
    }
    let plain_floor = floor(plain.meta().id, &rungs, |r| r.plain_error);
    let compensated_floor = floor(compensated.meta().id, &rungs, |r| r.compensated_error);
    let fitted: Vec<&RoundoffRung> = rungs
        .iter()
        .filter(|r| r.steps >= ROUND_OFF_FIT_STEPS)
        .collect();
    let round_off_fit = power_law(
        &fitted
            .iter()
            .filter_map(|r| r.round_off.map(|d| (r.h, d)))
            .collect::<Vec<_>>(),
    );
    // the compensated error is truncation while it keeps falling like h^2:
    // fit it up to its own minimum
    let last_falling = compensated_floor
        .as_ref()
        .map_or(0.0, |f| if f.stopped { f.h } else { 0.0 });
    let truncation_fit = power_law(
        &fitted
            .iter()
            .filter(|r| r.h >= last_falling)
            .filter_map(|r| r.compensated_error.map(|e| (r.h, e)))
            .collect::<Vec<_>>(),
    );
    let (predicted_h, predicted_floor) = match (round_off_fit, truncation_fit) {
        (Some(r), Some(c)) if r.slope < 0.0 && c.slope > 0.0 => {
            // e = C h^p + R h^(-g): minimum at h* = (g R / (p C))^(1/(p+g)),
            // where e = (1 + p/g) C h*^p
            let (g, p) = (-r.slope, c.slope);
            let (big_r, big_c) = (r.intercept.exp(), c.intercept.exp());
            let h = (g * big_r / (p * big_c)).powf(1.0 / (p + g));
            (Some(h), Some((1.0 + p / g) * big_c * h.powf(p)))
        }
        _ => (None, None),
    };
    let crossover_h = rungs
        .iter()
        .find(|r| matches!((r.round_off, r.compensated_error), (Some(d), Some(e)) if d >= e))
        .map(|r| r.h);
    Ok(PairRecord {
        plain: plain.meta().id,
        compensated: compensated.meta().id,
        rungs,
        plain_floor,
        compensated_floor,
        crossover_h,
        round_off_fit,
        truncation_fit,
        predicted_h,
        predicted_floor,
    })
}

/// Rungs since the smallest error so far (0 when the last rung is the smallest).
fn stopped(errors: impl Iterator<Item = Option<f64>>) -> usize {
    let mut best = f64::INFINITY;
    let mut since = 0;
    for e in errors {
        match e {
            Some(e) if e < best => {
                best = e;
                since = 0;
            }
            _ => since += 1,
        }
    }
    since
}

/// The smallest error of one scheme over the ladder.
fn floor(
    scheme: &'static str,
    rungs: &[RoundoffRung],
    error: impl Fn(&RoundoffRung) -> Option<f64>,
) -> Option<Floor> {
    let (i, e) = rungs
        .iter()
        .enumerate()
        .filter_map(|(i, r)| error(r).map(|e| (i, e)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    Some(Floor {
        scheme,
        floor: e,
        h: rungs[i].h,
        stopped: i + 1 < rungs.len(),
    })
}

/// Runs both schemes `steps` steps to `t_end`, evaluating the errors at
/// [`SAMPLES`] evenly spaced steps.
fn run_pair<P: Scheme, C: Scheme, S: Scene<D>, const D: usize>(
    plain: &P,
    compensated: &C,
    scene: &S,
    t_end: f64,
    steps: u64,
) -> RoundoffRung {
    let h = t_end / steps as f64;
    let start = scene.initial();
    let mut p = plain.start(scene, &start, h);
    let mut c = compensated.start(scene, &start, h);
    let stride = (steps / SAMPLES).max(1);
    let (mut ep, mut ec, mut d) = (0.0f64, 0.0f64, 0.0f64);
    let mut failed = (false, false);
    for n in 1..=steps {
        failed.0 |= guarded_step(plain, scene, &mut p, h).is_err();
        failed.1 |= guarded_step(compensated, scene, &mut c, h).is_err();
        if n % stride == 0 || n == steps {
            let t = if n == steps { t_end } else { n as f64 * h };
            let exact = scene.exact(t).expect("checked before the ladder");
            let (sp, sc) = (plain.state(&p, h), compensated.state(&c, h));
            // a NaN distance propagates through max only if it comes first:
            // flag non-finite states instead
            failed.0 |= !sp.is_finite();
            failed.1 |= !sc.is_finite();
            ep = ep.max(scene.phase_distance(&sp, &exact));
            ec = ec.max(scene.phase_distance(&sc, &exact));
            d = d.max(scene.phase_distance(&sp, &sc));
        }
    }
    let ok = |bad: bool, x: f64| (!bad && x.is_finite()).then_some(x);
    RoundoffRung {
        h,
        steps,
        plain_error: ok(failed.0, ep),
        compensated_error: ok(failed.1, ec),
        round_off: ok(failed.0 || failed.1, d),
    }
}

/// The study of one pair, named by either member's id, on a built-in scene.
pub fn study_pair(
    scene: &AnyScene,
    scheme_id: &str,
    spec: &RoundoffSpec,
) -> Result<PairRecord, Error> {
    visit_pair(scheme_id, PairOn { scene, spec })?
}

struct PairOn<'a> {
    scene: &'a AnyScene,
    spec: &'a RoundoffSpec,
}

impl PairVisitor for PairOn<'_> {
    type Output = Result<PairRecord, Error>;
    fn visit<P: Scheme + Sync + 'static, C: Scheme + Sync + 'static>(
        self,
        plain: &'static P,
        compensated: &'static C,
    ) -> Self::Output {
        self.scene.visit(SceneOf {
            plain,
            compensated,
            spec: self.spec,
        })
    }
}

struct SceneOf<'a, P: 'static, C: 'static> {
    plain: &'static P,
    compensated: &'static C,
    spec: &'a RoundoffSpec,
}

impl<P: Scheme, C: Scheme> SceneVisitor for SceneOf<'_, P, C> {
    type Output = Result<PairRecord, Error>;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> Self::Output {
        pair_floors(self.plain, self.compensated, scene, self.spec)
    }
}

/// The study of every pair on one scene, assembled from per-pair records
/// (which a caller may have computed in parallel).
pub fn assemble(
    scene: &AnyScene,
    spec: &RoundoffSpec,
    pairs: Vec<PairRecord>,
) -> Result<RoundoffRecord, Error> {
    let meta = scene.meta();
    let period = scene.period();
    let (t_end, max_steps) = resolve(spec, period)?;
    Ok(RoundoffRecord {
        scene: meta.id,
        scene_parameters: meta.parameters,
        t_end,
        periods: t_end / period,
        max_steps,
        pairs,
    })
}

/// The study of every pair on one scene, one pair after the other.
pub fn roundoff(scene: &AnyScene, spec: &RoundoffSpec) -> Result<RoundoffRecord, Error> {
    let pairs = paired_ids()
        .into_iter()
        .map(|id| study_pair(scene, id, spec))
        .collect::<Result<Vec<_>, _>>()?;
    assemble(scene, spec, pairs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scheme_has_stopped_once_no_finer_rung_improves() {
        let e = |v: &[f64]| stopped(v.iter().map(|&x| Some(x)));
        assert_eq!(e(&[4.0, 2.0, 1.0]), 0);
        assert_eq!(e(&[4.0, 1.0, 2.0, 3.0]), 2);
        assert_eq!(e(&[4.0, 1.0, 2.0, 0.5]), 0);
        assert_eq!(stopped([Some(1.0), None].into_iter()), 1);
    }
}
