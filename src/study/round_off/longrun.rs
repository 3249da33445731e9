//! Long runs where round-off, not truncation, is all that moves: a quantity
//! each Verlet form conserves exactly in exact arithmetic, followed over
//! millions of steps, with and without compensated summation.
//!
//! # The quantities
//!
//! - On the oscillator `x'' = -w^2 x`, velocity Verlet's one-step map has
//!   determinant 1 and conserves the modified energy
//!   `v^2/2 + w^2 x^2 (1 - (h w)^2/4)/2` exactly (see the geometry tests).
//!   Leap-frog's synchronised `v(n) = v(n+1/2) - h a(n)/2` and the two-step
//!   form's `(q(n+1) - q(n-1))/2h` are the same numbers as velocity Verlet's
//!   `v(n)` in exact arithmetic, so all three conserve it, and so do their
//!   compensated variants. The true energy, by contrast, oscillates by
//!   `(h w)^2/4` of itself, ten orders of magnitude above round-off at
//!   100 steps a period.
//! - On a Kepler orbit, every kick is along `-r` and every drift along `v`,
//!   so `r x v` is unchanged by each: every Verlet form conserves the angular
//!   momentum exactly, whatever the step.
//!
//! Whatever these quantities do in a run is round-off.
//!
//! # What round-off does to them
//!
//! Each step of a plain velocity Verlet or leap-frog rounds `q` and `v` by
//! about `u = eps/2` of themselves, with signs that vary from step to step:
//! the conserved quantity changes by about `u` of itself per step, and after
//! `N` steps by `u N^(1/2)`, a random walk, `t^(1/2)`; a bias in the
//! rounding would add up linearly instead, `t^1`. The two-step form's
//! rounding perturbs the velocity by `u |q| / h` per step, a random walk
//! `1/(h w)` times larger. The compensated variants lose only `u h w` of each
//! quantity per step: the same random walk, `h w` times smaller.

use crate::error::Error;
use crate::ladder::check_count;
use crate::maths::fit::{jackknife_standard_error, power_law};
use crate::run::guarded_step;
use crate::scene::{AnyScene, Harmonic, KeplerCircular, KeplerEccentric, Scene};
use crate::scheme::Scheme;
use crate::scheme::compensated::{PairVisitor, pair_ids, visit_pair};
use crate::study::geometry::energy::classify_growth;
use crate::study::geometry::energy::{EnergyClass, RESOLVED_EXCURSION};
use crate::tolerance::GROWTH_DECADES;
use crate::wording::figure;
use serde::Serialize;

/// Default step, in periods of the scene: 100 steps a period.
pub const DEFAULT_STEP: f64 = 1.0 / 100.0;

/// Default length of each run: `2^18` steps, 2621 periods.
pub const DEFAULT_STEPS: u64 = 1 << 18;

/// Runs per scheme, started at evenly spaced points of the exact orbit: each
/// is an independent realisation of the rounding. The mean square over them
/// follows the growth law far more closely than one run does: a single
/// random walk's size at `t` varies by a factor of about two from one
/// realisation to the next, enough to move a two-decade fit of one run's
/// exponent by 0.15 either way. Sixteen runs of `2^18` steps are 4.2 million
/// steps a scheme.
pub const RUNS: usize = 16;

/// Fewest steps a run may take: the fit needs two decades of time after the
/// first samples.
pub const MIN_STEPS: u64 = 10_000;

/// Sample times per run, log-spaced.
pub const SAMPLES: usize = 200;

/// The exactly conserved quantity followed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ConservedQuantity {
    /// `v^2/2 + w^2 x^2 (1 - (h w)^2/4)/2` on the oscillator.
    ModifiedEnergy,
    /// `x v_y - y v_x` on a Kepler orbit.
    AngularMomentum,
}

impl ConservedQuantity {
    /// The kebab-case name used in records and tables.
    pub fn name(self) -> &'static str {
        match self {
            ConservedQuantity::ModifiedEnergy => "modified energy",
            ConservedQuantity::AngularMomentum => "angular momentum",
        }
    }
}

/// What to measure.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct LongrunSpec {
    /// Steps of the run; `None` for [`DEFAULT_STEPS`].
    pub steps: Option<u64>,
}

/// What the long runs of one scheme found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LongrunRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// The scheme sums with compensation.
    pub compensated: bool,
    /// Scene id.
    pub scene: &'static str,
    /// The quantity followed.
    pub invariant: ConservedQuantity,
    /// The step.
    pub h: f64,
    /// Steps of each run.
    pub steps: u64,
    /// Runs, from [`RUNS`] evenly spaced points of the exact orbit.
    pub runs: usize,
    /// The largest `|Q(t) - Q(0)| / |Q(0)|` over every run and step.
    pub max_relative_error: f64,
    /// The root mean square over the runs of `(Q(t) - Q(0)) / Q(0)` at the
    /// end.
    pub final_rms: f64,
    /// `final_rms` in units of `eps`, divided by `N^(1/2)`: the size of a
    /// random walk's single step, if it is one.
    pub per_step_ulps: f64,
    /// The exponent `g` of `rms(t) ~ t^g`, fitted over the last
    /// [`GROWTH_DECADES`] decades of the runs: 1/2 for a random walk, 1 for
    /// biased rounding, 0 for an error that does not accumulate.
    pub growth_exponent: Option<f64>,
    /// Its jackknife standard error over the runs (the fit's own interval
    /// would treat the samples of one run as independent, which they are not).
    pub growth_standard_error: Option<f64>,
    /// The class of `g` (bounded, random walk, drifting).
    pub class: Option<EnergyClass>,
    /// `(t, rms over the runs)` at log-spaced times.
    pub samples: Vec<[f64; 2]>,
}

/// The quantity a scene's Verlet runs conserve exactly, as a function of the
/// synchronised state.
pub trait Conserved<const D: usize>: Scene<D> {
    /// Which quantity.
    fn quantity(&self) -> ConservedQuantity;
    /// Its value at `(q, v)` for runs with step `h`.
    fn value(&self, q: &nalgebra::SVector<f64, D>, v: &nalgebra::SVector<f64, D>, h: f64) -> f64;
}

impl Conserved<1> for Harmonic {
    fn quantity(&self) -> ConservedQuantity {
        ConservedQuantity::ModifiedEnergy
    }
    #[inline(always)]
    fn value(&self, q: &nalgebra::Vector1<f64>, v: &nalgebra::Vector1<f64>, h: f64) -> f64 {
        let w = self.w0();
        let z = h * w;
        0.5 * v[0] * v[0] + 0.5 * w * w * q[0] * q[0] * (1.0 - 0.25 * z * z)
    }
}

fn angular_momentum(q: &nalgebra::Vector2<f64>, v: &nalgebra::Vector2<f64>) -> f64 {
    q[0] * v[1] - q[1] * v[0]
}

impl Conserved<2> for KeplerCircular {
    fn quantity(&self) -> ConservedQuantity {
        ConservedQuantity::AngularMomentum
    }
    #[inline(always)]
    fn value(&self, q: &nalgebra::Vector2<f64>, v: &nalgebra::Vector2<f64>, _: f64) -> f64 {
        angular_momentum(q, v)
    }
}

impl Conserved<2> for KeplerEccentric {
    fn quantity(&self) -> ConservedQuantity {
        ConservedQuantity::AngularMomentum
    }
    #[inline(always)]
    fn value(&self, q: &nalgebra::Vector2<f64>, v: &nalgebra::Vector2<f64>, _: f64) -> f64 {
        angular_momentum(q, v)
    }
}

/// Runs `scheme` [`RUNS`] times for a long time on `scene`, from evenly
/// spaced points of the exact orbit, and follows the conserved quantity.
pub fn longrun<M: Scheme, S: Conserved<D>, const D: usize>(
    scheme: &M,
    compensated: bool,
    scene: &S,
    spec: &LongrunSpec,
) -> Result<LongrunRecord, Error> {
    let steps = spec.steps.unwrap_or(DEFAULT_STEPS);
    if steps < MIN_STEPS {
        return Err(Error::InvalidParameter {
            name: "steps",
            value: steps as f64,
            expected: "at least 10000, so two decades of growth can be fitted",
        });
    }
    check_count(steps as f64 * RUNS as f64)?;
    let period = scene.period();
    let h = DEFAULT_STEP * period;
    let times = sample_steps(steps);
    let mut max_relative_error = 0.0f64;
    let mut paths: Vec<Vec<f64>> = Vec::with_capacity(RUNS);
    for k in 0..RUNS {
        let start = scene
            .exact(period * k as f64 / RUNS as f64)
            .ok_or(Error::NoExactSolution(scene.meta().id))?;
        let q0 = scene.value(&start.q, &start.v, h);
        let (e0, norm) = (scene.energy(&start), crate::scene::energy_norm(scene));
        let mut excursion = 0.0f64;
        let mut carry = scheme.start(scene, &start, h);
        let mut path = Vec::with_capacity(times.len());
        let mut next = times.iter().copied().peekable();
        for n in 1..=steps {
            guarded_step(scheme, scene, &mut carry, h).map_err(|failure| {
                Error::InvalidScene(format!(
                    "step {n} of h = {h:e} failed in a long run: {failure}"
                ))
            })?;
            let s = scheme.state(&carry, h);
            // the step must resolve the motion for its round-off to mean
            // anything: the energy study's rule, over the first period
            if n as f64 * h <= period {
                excursion = excursion.max((scene.energy(&s) - e0).abs() / norm);
            } else if excursion > RESOLVED_EXCURSION {
                return Err(Error::InvalidScene(format!(
                    "at the long runs' step, {DEFAULT_STEP} of a period, the energy moves by \
                     {} of itself over the first period from t = {}: the step does not \
                     resolve the motion, and what a conserved quantity does there is the \
                     orbit being lost, not round-off",
                    figure(excursion),
                    figure(period * k as f64 / RUNS as f64),
                )));
            }
            let change = (scene.value(&s.q, &s.v, h) - q0) / q0.abs();
            max_relative_error = max_relative_error.max(change.abs());
            if next.peek() == Some(&n) {
                path.push(change);
                next.next();
            }
        }
        paths.push(path);
    }
    let t: Vec<f64> = times.iter().map(|&n| n as f64 * h).collect();
    let growth = ensemble_growth(&t, &paths);
    let rms = rms_over_runs(&paths);
    let final_rms = rms.last().copied().unwrap_or(0.0);
    Ok(LongrunRecord {
        scheme: scheme.meta().id,
        compensated,
        scene: scene.meta().id,
        invariant: scene.quantity(),
        h,
        steps,
        runs: RUNS,
        max_relative_error,
        final_rms,
        per_step_ulps: final_rms / f64::EPSILON / (steps as f64).sqrt(),
        growth_exponent: growth.map(|g| g.0),
        growth_standard_error: growth.map(|g| g.1),
        class: growth.map(|g| classify_growth(g.0)),
        samples: t.iter().zip(&rms).map(|(&t, &r)| [t, r]).collect(),
    })
}

/// [`SAMPLES`] distinct steps, log-spaced from 10 to `steps`, the last `steps`.
pub fn sample_steps(steps: u64) -> Vec<u64> {
    let ratio = (steps as f64 / 10.0).powf(1.0 / (SAMPLES - 1) as f64);
    let mut out: Vec<u64> = (0..SAMPLES)
        .map(|i| ((10.0 * ratio.powi(i as i32)).round() as u64).clamp(1, steps))
        .collect();
    out.dedup();
    if out.last() != Some(&steps) {
        out.push(steps);
    }
    out
}

/// The root mean square over the paths at each sample.
pub fn rms_over_runs(paths: &[Vec<f64>]) -> Vec<f64> {
    let n = paths.iter().map(Vec::len).min().unwrap_or(0);
    (0..n)
        .map(|i| (paths.iter().map(|p| p[i] * p[i]).sum::<f64>() / paths.len() as f64).sqrt())
        .collect()
}

/// The exponent `g` of `rms(t) ~ t^g` over the last [`GROWTH_DECADES`]
/// decades of `times`, with its jackknife standard error over the paths
/// (each path left out in turn); `None` with fewer than three paths or
/// samples.
pub fn ensemble_growth(times: &[f64], paths: &[Vec<f64>]) -> Option<(f64, f64)> {
    let t_stop = *times.last()?;
    let t_from = t_stop / 10f64.powf(GROWTH_DECADES);
    let slope = |paths: &[&Vec<f64>]| -> Option<f64> {
        let owned: Vec<Vec<f64>> = paths.iter().map(|p| (*p).clone()).collect();
        let points: Vec<(f64, f64)> = times
            .iter()
            .zip(rms_over_runs(&owned))
            .filter(|&(&t, r)| t >= t_from && r > 0.0)
            .map(|(&t, r)| (t, r))
            .collect();
        power_law(&points).map(|f| f.slope)
    };
    let all: Vec<&Vec<f64>> = paths.iter().collect();
    let g = slope(&all)?;
    let k = paths.len();
    if k < 3 {
        return None;
    }
    let leave_one_out: Vec<f64> = (0..k)
        .filter_map(|i| {
            let rest: Vec<&Vec<f64>> = (0..k).filter(|&j| j != i).map(|j| &paths[j]).collect();
            slope(&rest)
        })
        .collect();
    if leave_one_out.len() < k {
        return None;
    }
    Some((g, jackknife_standard_error(&leave_one_out)))
}

/// The long run of a Verlet form or compensated variant, named by id, on a
/// built-in scene that has a quantity the Verlet forms conserve exactly.
pub fn longrun_of(
    scene: &AnyScene,
    scheme_id: &str,
    spec: &LongrunSpec,
) -> Result<LongrunRecord, Error> {
    if !pair_ids().contains(&scheme_id) {
        return Err(Error::UnknownScheme {
            id: scheme_id.to_string(),
            valid: pair_ids().join(", "),
        });
    }
    visit_pair(
        scheme_id,
        OnScene {
            scene,
            id: scheme_id,
            spec,
        },
    )?
}

struct OnScene<'a> {
    scene: &'a AnyScene,
    id: &'a str,
    spec: &'a LongrunSpec,
}

impl PairVisitor for OnScene<'_> {
    type Output = Result<LongrunRecord, Error>;
    fn visit<P: Scheme + Sync + 'static, C: Scheme + Sync + 'static>(
        self,
        plain: &'static P,
        compensated: &'static C,
    ) -> Self::Output {
        let is_compensated = compensated.meta().id == self.id;
        macro_rules! run {
            ($scene:expr) => {
                if is_compensated {
                    longrun(compensated, true, $scene, self.spec)
                } else {
                    longrun(plain, false, $scene, self.spec)
                }
            };
        }
        match self.scene {
            AnyScene::Harmonic(s) => run!(s),
            AnyScene::KeplerCircular(s) => run!(s),
            AnyScene::KeplerEccentric(s) => run!(s),
            other => Err(Error::InvalidScene(format!(
                "'{}' has no quantity the Verlet forms conserve exactly; long runs use harmonic (modified energy), kepler-circular or kepler-eccentric (angular momentum)",
                other.meta().id
            ))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::RANDOM_WALK_EXPONENT_TOLERANCE;

    /// A uniform deviate in [-1, 1) from a 64-bit linear congruential generator.
    fn uniform(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// The exponent fitted to `RUNS` random walks of `steps` unbiased steps,
    /// sampled like a long run.
    fn simulated_exponent(seed: &mut u64, steps: u64, bias: f64) -> (f64, f64) {
        let times = sample_steps(steps);
        let paths: Vec<Vec<f64>> = (0..RUNS)
            .map(|_| {
                let (mut x, mut next) = (0.0, times.iter().copied().peekable());
                let mut path = Vec::new();
                for n in 1..=steps {
                    x += uniform(seed) + bias;
                    if next.peek() == Some(&n) {
                        path.push(x);
                        next.next();
                    }
                }
                path
            })
            .collect();
        let t: Vec<f64> = times.iter().map(|&n| n as f64).collect();
        ensemble_growth(&t, &paths).unwrap()
    }

    /// The bound the harness puts on a random walk's fitted exponent is
    /// calibrated here, independently of any scheme: over 200 ensembles of
    /// simulated unbiased walks, sampled and fitted exactly like the long
    /// runs, the exponent stays within the tolerance of 1/2 every time, and
    /// a walk whose steps are biased by 5% of their standard deviation (a
    /// linear drift that overtakes the walk within the run) is told apart.
    #[test]
    fn the_exponent_of_simulated_random_walks_lies_within_the_tolerance() {
        let mut seed = 7;
        let mut worst = 0.0f64;
        let mut se_max = 0.0f64;
        let mut all = Vec::new();
        for _ in 0..200 {
            let (g, se) = simulated_exponent(&mut seed, 1 << 14, 0.0);
            worst = worst.max((g - 0.5).abs());
            se_max = se_max.max(se);
            all.push((g, se));
        }
        // the spread itself: a standard deviation near 0.06, which the
        // jackknife error estimates run by run
        let mean = all.iter().map(|a| a.0).sum::<f64>() / all.len() as f64;
        let sd = (all.iter().map(|a| (a.0 - mean).powi(2)).sum::<f64>() / all.len() as f64).sqrt();
        assert!((mean - 0.5).abs() < 0.02, "mean exponent {mean}");
        assert!(
            sd < 0.1 && se_max < 0.15,
            "spread {sd}, jackknife up to {se_max}"
        );
        assert!(
            worst < RANDOM_WALK_EXPONENT_TOLERANCE,
            "largest deviation from 1/2: {worst} (largest jackknife error {se_max})"
        );
        let (g, _) = simulated_exponent(&mut seed, 1 << 14, 0.03);
        assert!(g > 0.5 + RANDOM_WALK_EXPONENT_TOLERANCE, "biased walk: {g}");
    }

    #[test]
    fn sample_steps_are_distinct_and_end_at_the_run() {
        let s = sample_steps(1 << 18);
        assert!(s.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(s.last(), Some(&(1 << 18)));
        assert_eq!(s[0], 10);
    }
}
