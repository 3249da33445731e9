//! Brouwer's law as a claim: an integrator is *round-off optimal* on a scene
//! when, over a run of a million steps, its energy error is the random walk
//! of the rounding it cannot avoid, `t^(1/2)`, and no more.
//!
//! # What is measured
//!
//! [`RUNS`] runs of `2^20` steps at `h = period / 2000`, where the
//! truncation error of an eighth-order method is some `(2 pi / 2000)^8 =
//! 1e-20` of the energy and every change of the energy is round-off. The
//! energy is read every [`STRIDE`] steps in double-double
//! ([`PreciseEnergy`]) at the scheme's state plus its compensation
//! ([`Scheme::compensation`]): read in doubles it would round by `1e-16` of
//! itself, as much as a compensated run's whole walk.
//!
//! # The exponent: a variogram, not one curve
//!
//! For a random walk `e(t)` the mean square change over a lag `L`,
//! `<(e(t + L) - e(t))^2>`, is `sigma^2 L` wherever in the run it is taken;
//! a drift makes it `c^2 L^2`, a bounded error a constant. Averaged over
//! every start `t` of every run, it uses the whole run at every lag, where
//! the root mean square of `e(t)` over runs uses one number per run and
//! time: eight runs of a million steps fit the walk's exponent to about
//! `0.01` this way, against `0.05` from the ensemble's curve (measured on
//! the outer solar system). The exponent
//! `g` is the slope of `ln rms(L)` over lags from `N/1024` to `N/8` (two
//! decades and a tenth; the longest lag still has eight disjoint windows a
//! run), its standard error by the jackknife over runs, which are
//! independent, and its interval `g -+ t(0.975, runs - 1) se`.
//!
//! # The verdict
//!
//! - The exponent's interval must lie inside [`RANDOM_WALK_BAND`]: `1/2`
//!   within `0.05`. A drift as large as the walk at the longest lag lifts
//!   the interval's top out of the band, and a bounded error as large as
//!   the walk at the shortest lag drops its bottom out (both tested on
//!   simulated paths below): neither passes.
//! - The walk's size per step must be below the rounding floor: the walk a
//!   scheme makes that rounds each coordinate to a double once a step. A
//!   double `x` rounds by a uniform error of width `ulp(x) > u |x|`
//!   (`u = eps/2`), variance at least `(u x)^2 / 12`, and moves the energy
//!   by its gradient times that; independent from step to step, these add
//!   up to a walk of at least `u / sqrt(12) (sum (q_i dE/dq_i)^2 +
//!   sum v_i^4)^(1/2)` a step. A scheme that rounds its coordinates, however
//!   unbiased, sits at or above it; one that compensates them loses only the
//!   rounding of its increments, about `h w` times less.
//!
//! An interval inside the band with the walk above the floor fails: the
//! rounding is unbiased but not the least it can be. An interval across a
//! band's edge is inconclusive.

use crate::error::Error;
use crate::maths::fit::{jackknife_standard_error, power_law, t975};
use crate::parallel::{default_threads, parallel_map};
use crate::run::guarded_step;
use crate::scene::PreciseEnergy;
use crate::scheme::Scheme;
use crate::state::State;
use crate::study::verdict::Verdict;
use crate::wording::figure;
use serde::Serialize;

/// Steps of each run: `2^20`, a million.
pub const DEFAULT_STEPS: u64 = 1 << 20;

/// Fewest steps a run may take: the shortest lag, `N/1024`, must span at
/// least one [`STRIDE`].
pub const MIN_STEPS: u64 = 1024 * STRIDE;

/// Independent runs. With eight, a pure random walk's interval (half-width
/// `t(0.975, 7) se`, about 0.03, itself uncertain from eight runs) fell
/// inside the band in 17 of 20 simulated ensembles; sixteen halve the
/// variance of the jackknife and lower the quantile from 2.36 to 2.13.
pub const RUNS: usize = 16;

/// Steps per period of the scene.
pub const STEPS_PER_PERIOD: f64 = 2000.0;

/// Steps between readings of the energy.
pub const STRIDE: u64 = 16;

/// Steps between the starts of successive runs: a prime, so no two runs
/// start at the same phase of any commensurate period.
pub const SPACING: u64 = 7919;

/// The random walk's exponent, `1/2`, within `0.05`.
pub const RANDOM_WALK_BAND: [f64; 2] = [0.45, 0.55];

/// What to run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct RoundOffSpec {
    /// Steps of each run; `None` for [`DEFAULT_STEPS`].
    pub steps: Option<u64>,
    /// Runs; `None` for [`RUNS`].
    pub runs: Option<usize>,
    /// Steps per period; `None` for [`STEPS_PER_PERIOD`].
    pub steps_per_period: Option<f64>,
    /// Threads; `None` for what the machine offers.
    pub threads: Option<usize>,
}

/// What the long runs found, and the verdict on "round-off optimal".
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RoundOffRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// The step.
    pub h: f64,
    /// Steps of each run.
    pub steps: u64,
    /// Runs.
    pub runs: usize,
    /// `(lag in steps, rms change of the relative energy over it)`.
    pub lags: Vec<[f64; 2]>,
    /// The fitted exponent `g` of `rms(L) ~ L^g`.
    pub growth_exponent: Option<f64>,
    /// Its jackknife standard error.
    pub standard_error: Option<f64>,
    /// `g -+ t(0.975, runs - 1) se`.
    pub ci95: Option<[f64; 2]>,
    /// The walk's size per step, `rms(L) / sqrt(L)` at the longest lag.
    pub per_step: f64,
    /// The rounding floor (see the module documentation) along the runs.
    pub rounding_floor: f64,
    /// The largest relative energy error in any run.
    pub max_relative_error: f64,
    /// Pass, fail or inconclusive.
    pub verdict: Verdict,
    /// Why, with the figures.
    pub reason: String,
}

/// The relative energy errors of one run at every [`STRIDE`]-th step, and
/// the mean of the floor's squared terms over them.
struct Run {
    errors: Vec<f64>,
    floor_squared: f64,
}

/// Runs `scheme` on `scene` [`RUNS`] times for a million steps and judges
/// whether its energy error is the random walk of unavoidable rounding.
///
/// ```no_run
/// use stepladder::scene::OuterSolarSystem;
/// use stepladder::scheme::{Compensated, DPRKN8};
/// use stepladder::study::{RoundOffSpec, round_off_growth};
///
/// let compensated = Compensated { meta: DPRKN8.meta, plain: DPRKN8 };
/// let record = round_off_growth(&compensated, &OuterSolarSystem::new(), &RoundOffSpec::default())?;
/// println!("{}: {}", record.verdict.name(), record.reason);
/// # Ok::<(), stepladder::error::Error>(())
/// ```
pub fn round_off_growth<M, S, const D: usize>(
    scheme: &M,
    scene: &S,
    spec: &RoundOffSpec,
) -> Result<RoundOffRecord, Error>
where
    M: Scheme + Sync,
    S: PreciseEnergy<D> + Sync,
{
    let steps = spec.steps.unwrap_or(DEFAULT_STEPS);
    let runs = spec.runs.unwrap_or(RUNS);
    let per_period = spec.steps_per_period.unwrap_or(STEPS_PER_PERIOD);
    if steps < MIN_STEPS {
        return Err(Error::InvalidParameter {
            name: "steps",
            value: steps as f64,
            expected: "at least 16384, so the shortest lag spans a reading",
        });
    }
    if !(3..=1024).contains(&runs) {
        return Err(Error::InvalidParameter {
            name: "runs",
            value: runs as f64,
            expected: "3 to 1024 runs, so the jackknife has runs to leave out",
        });
    }
    if !(per_period.is_finite() && per_period >= 1.0) {
        return Err(Error::InvalidParameter {
            name: "steps_per_period",
            value: per_period,
            expected: "a finite number of steps per period, at least 1",
        });
    }
    crate::ladder::check_count(steps as f64 * runs as f64)?;
    let h = scene.period() / per_period;
    let failed = |n: u64, failure: crate::scheme::StepFailure| {
        Error::InvalidScene(format!(
            "step {n} of h = {h:e} failed in a long run: {failure}"
        ))
    };
    let mut starts = vec![scene.initial()];
    let mut carry = scheme.start(scene, &starts[0], h);
    for n in 1..runs as u64 * SPACING {
        guarded_step(scheme, scene, &mut carry, h).map_err(|f| failed(n, f))?;
        if n % SPACING == 0 {
            starts.push(scheme.state(&carry, h));
        }
    }
    let results = parallel_map(
        &starts,
        spec.threads.unwrap_or_else(default_threads),
        |start| one_run(scheme, scene, start, h, steps),
        &|_, _| {},
    );
    let runs_done: Vec<Run> = results
        .into_iter()
        .collect::<Result<_, (u64, crate::scheme::StepFailure)>>()
        .map_err(|(n, f)| failed(n, f))?;
    let u = scheme.epsilon() / 2.0;
    let floor_squared =
        runs_done.iter().map(|r| r.floor_squared).sum::<f64>() / runs_done.len() as f64;
    let rounding_floor = u / 12f64.sqrt() * floor_squared.sqrt();
    let max_relative_error = runs_done
        .iter()
        .flat_map(|r| r.errors.iter())
        .fold(0.0f64, |m, e| m.max(e.abs()));
    let paths: Vec<&[f64]> = runs_done.iter().map(|r| r.errors.as_slice()).collect();
    let fit = variogram_growth(&paths, steps);
    let lags = fit.lags.clone();
    let per_step = lags.last().map_or(0.0, |&[l, rms]| rms / l.sqrt());
    let ci95 = fit.exponent.map(|(g, se)| {
        let half = t975(runs - 1) * se;
        [g - half, g + half]
    });
    let (verdict, reason) = judge(ci95, per_step, rounding_floor);
    Ok(RoundOffRecord {
        scheme: scheme.meta().id,
        scene: scene.meta().id,
        h,
        steps,
        runs,
        lags,
        growth_exponent: fit.exponent.map(|e| e.0),
        standard_error: fit.exponent.map(|e| e.1),
        ci95,
        per_step,
        rounding_floor,
        max_relative_error,
        verdict,
        reason,
    })
}

/// One run from `start`: the relative energy error every [`STRIDE`] steps
/// and the floor's squared terms averaged over the same readings.
fn one_run<M: Scheme, S: PreciseEnergy<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    start: &State<D>,
    h: f64,
    steps: u64,
) -> Result<Run, (u64, crate::scheme::StepFailure)> {
    let mut carry = scheme.start(scene, start, h);
    let e0 = scene.precise_energy(&scheme.state(&carry, h), &scheme.compensation(&carry, h));
    let scale = e0.to_f64().abs();
    let mut errors = Vec::with_capacity((steps / STRIDE) as usize + 1);
    errors.push(0.0);
    let mut floor_sum = 0.0;
    for n in 1..=steps {
        guarded_step(scheme, scene, &mut carry, h).map_err(|f| (n, f))?;
        if n % STRIDE == 0 {
            let s = scheme.state(&carry, h);
            let energy = scene.precise_energy(&s, &scheme.compensation(&carry, h));
            errors.push(energy.sub(e0).to_f64() / scale);
            let a = scene.acceleration(&s.q);
            let terms: f64 = (0..D)
                .map(|i| (s.q[i] * a[i]).powi(2) + s.v[i].powi(4))
                .sum();
            floor_sum += terms / (scale * scale);
        }
    }
    Ok(Run {
        floor_squared: floor_sum / (errors.len() - 1) as f64,
        errors,
    })
}

/// The variogram of the runs and its fitted exponent.
struct Growth {
    /// `(lag in steps, rms change over it)`.
    lags: Vec<[f64; 2]>,
    /// `(exponent, jackknife standard error)`.
    exponent: Option<(f64, f64)>,
}

/// The rms change of the paths (read every [`STRIDE`] steps of runs of
/// `steps`) over lags doubling from `steps/1024` to `steps/8`, and the
/// exponent of its power law with the jackknife error over paths.
fn variogram_growth(paths: &[&[f64]], steps: u64) -> Growth {
    let (shortest, longest) = (steps / 1024 / STRIDE, steps / 8 / STRIDE);
    let lags: Vec<usize> = std::iter::successors(Some(shortest.max(1) as usize), |&m| Some(2 * m))
        .take_while(|&m| m as u64 <= longest)
        .collect();
    // mean square change per path and lag
    let table: Vec<Vec<f64>> = paths
        .iter()
        .map(|p| {
            lags.iter()
                .map(|&m| {
                    let n = p.len().saturating_sub(m).max(1);
                    p.windows(m + 1).map(|w| (w[m] - w[0]).powi(2)).sum::<f64>() / n as f64
                })
                .collect()
        })
        .collect();
    let rms_over = |kept: &dyn Fn(usize) -> bool| -> Vec<f64> {
        let k = (0..table.len()).filter(|&i| kept(i)).count().max(1);
        (0..lags.len())
            .map(|j| {
                ((0..table.len())
                    .filter(|&i| kept(i))
                    .map(|i| table[i][j])
                    .sum::<f64>()
                    / k as f64)
                    .sqrt()
            })
            .collect()
    };
    let slope = |rms: &[f64]| {
        let points: Vec<(f64, f64)> = lags
            .iter()
            .zip(rms)
            .filter(|&(_, &r)| r > 0.0 && r.is_finite())
            .map(|(&m, &r)| ((m as u64 * STRIDE) as f64, r))
            .collect();
        (points.len() == lags.len())
            .then(|| power_law(&points).map(|f| f.slope))
            .flatten()
    };
    let all = rms_over(&|_| true);
    let lag_table = lags
        .iter()
        .zip(&all)
        .map(|(&m, &r)| [(m as u64 * STRIDE) as f64, r])
        .collect();
    let k = paths.len();
    let exponent = slope(&all).and_then(|g| {
        let left_out: Option<Vec<f64>> = (0..k).map(|i| slope(&rms_over(&|j| j != i))).collect();
        Some((g, jackknife_standard_error(&left_out?)))
    });
    Growth {
        lags: lag_table,
        exponent,
    }
}

/// The verdict from the exponent's interval and the walk's size per step.
fn judge(ci95: Option<[f64; 2]>, per_step: f64, floor: f64) -> (Verdict, String) {
    let [low, high] = RANDOM_WALK_BAND;
    let Some([a, b]) = ci95 else {
        return (
            Verdict::Inconclusive,
            "the energy's change is zero or not finite at some lag, so no exponent can be fitted"
                .into(),
        );
    };
    let growth = format!(
        "the energy error grows as L^g with g in [{a:.3}, {b:.3}] (random walk: [{low}, {high}])"
    );
    let size = format!(
        "its walk takes {} of the energy a step, against {} for rounding each coordinate once a step",
        figure(per_step),
        figure(floor)
    );
    let outside = b < low || a > high;
    let inside = a >= low && b <= high;
    if outside || per_step > floor {
        let why = match (outside, per_step > floor) {
            (true, true) => "neither a random walk nor below the rounding of the coordinates",
            (true, false) => "not a random walk",
            _ => "a random walk, but no smaller than rounding the coordinates gives",
        };
        (Verdict::Fail, format!("{why}: {growth}; {size}"))
    } else if inside {
        (
            Verdict::Pass,
            format!("a random walk below the rounding of the coordinates: {growth}; {size}"),
        )
    } else {
        (
            Verdict::Inconclusive,
            format!(
                "the interval crosses the band's edge; more runs or longer runs narrow it: {growth}; {size}"
            ),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A standard normal deviate from a 64-bit linear congruential generator
    /// (Box-Muller).
    fn normal(state: &mut u64) -> f64 {
        let mut uniform = || {
            *state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((*state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        };
        let (u1, u2) = (uniform(), uniform());
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }

    /// [`RUNS`] simulated paths read like the long runs: a walk of unit
    /// steps per step, plus a drift of `drift` a step, plus a bounded white
    /// error of size `bounded` at each reading.
    fn simulated(seed: &mut u64, drift: f64, bounded: f64) -> Option<[f64; 2]> {
        let steps = DEFAULT_STEPS;
        let paths: Vec<Vec<f64>> = (0..RUNS)
            .map(|_| {
                let mut walk = 0.0;
                (0..=steps / STRIDE)
                    .map(|n| {
                        if n > 0 {
                            walk += normal(seed) * (STRIDE as f64).sqrt() + drift * STRIDE as f64;
                        }
                        walk + bounded * normal(seed)
                    })
                    .collect()
            })
            .collect();
        let refs: Vec<&[f64]> = paths.iter().map(Vec::as_slice).collect();
        let (g, se) = variogram_growth(&refs, steps).exponent?;
        let half = t975(RUNS - 1) * se;
        Some([g - half, g + half])
    }

    /// The band and the fit are calibrated on simulated paths, apart from
    /// any scheme. A pure random walk's interval lies inside the band in at
    /// least 18 of 20 ensembles (20 of 20 when written). A drift as large as
    /// the walk at the longest lag bends the variogram's top octave to a
    /// slope of 3/4 and lifts the interval's upper end out of the band (not
    /// a pass); one as large as the walk at a sixteenth of that lag puts the
    /// whole interval above it (a fail). A bounded error as large as the
    /// walk at the shortest lag flattens the bottom of the variogram, and
    /// one four times that puts the whole interval below the band.
    #[test]
    fn the_band_holds_random_walks_and_refuses_drift_and_bounded_error() {
        let [low, high] = RANDOM_WALK_BAND;
        let mut seed = 11;
        let inside = (0..20)
            .filter(|_| {
                let [a, b] = simulated(&mut seed, 0.0, 0.0).unwrap();
                a >= low && b <= high
            })
            .count();
        assert!(inside >= 18, "{inside} of 20 walks inside the band");
        let longest = (DEFAULT_STEPS / 8) as f64;
        let shortest = (DEFAULT_STEPS / 1024) as f64;
        let [_, b] = simulated(&mut seed, 1.0 / longest.sqrt(), 0.0).unwrap();
        assert!(b > high, "drift at the longest lag: interval up to {b}");
        let [a, _] = simulated(&mut seed, 4.0 / longest.sqrt(), 0.0).unwrap();
        assert!(a > high, "drift at a sixteenth of it: interval from {a}");
        let [a, _] = simulated(&mut seed, 0.0, shortest.sqrt()).unwrap();
        assert!(a < low, "bounded at the shortest lag: interval from {a}");
        let [_, b] = simulated(&mut seed, 0.0, 4.0 * shortest.sqrt()).unwrap();
        assert!(b < low, "bounded four times larger: interval up to {b}");
    }

    #[test]
    fn the_verdict_needs_both_the_band_and_the_floor() {
        assert_eq!(judge(Some([0.48, 0.52]), 1e-19, 1e-17).0, Verdict::Pass);
        assert_eq!(judge(Some([0.48, 0.52]), 1e-16, 1e-17).0, Verdict::Fail);
        assert_eq!(judge(Some([0.60, 0.70]), 1e-19, 1e-17).0, Verdict::Fail);
        assert_eq!(judge(Some([0.30, 0.44]), 1e-19, 1e-17).0, Verdict::Fail);
        assert_eq!(
            judge(Some([0.44, 0.52]), 1e-19, 1e-17).0,
            Verdict::Inconclusive
        );
        assert_eq!(
            judge(Some([0.52, 0.56]), 1e-19, 1e-17).0,
            Verdict::Inconclusive
        );
        assert_eq!(judge(None, 0.0, 1e-17).0, Verdict::Inconclusive);
    }
}
