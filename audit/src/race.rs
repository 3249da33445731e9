//! brahe's RKN12(10) raced against stepladder's own two RKN12(10) pairs on
//! the scenes of the repository's race: the same published tableau
//! (Dormand, El-Mikkawy and Prince 1987) in three implementations, so what
//! separates them is the step control, the error norm, the arithmetic of
//! the state updates and the cost of a step, not the method.
//!
//! Every contender runs the same tolerances, [`PER_DECADE`] a decade,
//! loosest first, and is judged by the same error, the phase-space distance
//! at the end time to the reference: on the Kepler orbits the exact
//! solution (its rounding to doubles its error), on the Pleiades and the
//! outer solar system the reference states of the repository's race. (That
//! race takes the largest error over every accepted step on the Kepler
//! orbits; a black box shows only its end, so here all three are judged
//! there.) The evaluations to reach a target are estimated with their
//! intervals from the runs near it ([`crate::target_cost`]), the seconds
//! are those evaluations at the contender's median seconds per evaluation
//! (each run timed the fastest of [`REPEATS`]): three implementations of
//! one tableau differ by a few percent, less than two bracketing runs'
//! interpolation (the repository's race's `cost_to_reach`) can tell apart.
//! How far that interpolation moves with the grid's offset is measured here
//! too ([`Contender::decade_spread`]), and so is what brahe's default step
//! cap does to its cost: brahe runs the same ladders again with the cap
//! lifted ([`SceneRace::uncapped`]), beside the race, not in it. Beside it
//! too, brahe's own step at equal steps ([`SceneRace::uniform`]): what the
//! step control is worth on each scene.
//!
//! The N-body references are the repository's race's, read from
//! `lab/references/` (written by `stepladder reference`; a harness test
//! keeps them equal to what the lab computes), so this crate races without
//! building the lab: the Pleiades' published state, and for the outer
//! solar system a double-double integration certified to `5e-17`.

use crate::target_cost::{self, Reach, Run, WINDOW_DECADES};
use stepladder::internals::cost::work_points::cost_to_reach;
use stepladder::internals::tolerance::rounding_distance;
use stepladder::scene::{KeplerCircular, KeplerEccentric, OuterSolarSystem, Pleiades, Scene};
use stepladder::scheme::{
    AdaptiveBlackBox, AdaptiveIntegrator, AdaptiveRun, DPRKN12_ADAPTIVE, DPRKN12_COMPENSATED,
    RunEnd,
};
use stepladder::state::State;

/// Tolerances a decade. A pair whose steps scale like `TOL^(-1/(q+1))`
/// (`q + 1 = 11` for RKN12(10)) takes one step more when the tolerance falls
/// by `(1 + 1/N)^(q+1)`, about `e^(11/N)`: an eighth of a decade at `N = 40`
/// steps, a third at `N = 10`. Eight a decade thus meets about every step
/// count at the tightest targets; a finer grid repeats step sequences
/// already run, a coarser one skips some.
pub const PER_DECADE: u32 = 8;

/// The loosest and the tightest tolerance, in decades: below `1e-16` a
/// tolerance is under a unit of round-off of the states' order-one
/// components.
const DECADES: (u32, u32) = (3, 16);

/// The `k`-th tolerance, `10^(-3 - k / PER_DECADE)`.
fn tolerance(k: u32) -> f64 {
    10f64.powf(-(DECADES.0 as f64) - k as f64 / PER_DECADE as f64)
}

/// The target errors, those of the repository's race.
pub const TARGETS: [f64; 4] = [1e-6, 1e-9, 1e-12, 1e-14];

/// Rounds timed per tolerance; each contender's fastest counts (the machine
/// is shared). A run of the outer solar system takes some 100 us, so a
/// slice of the scheduler or a cache refill is a large share of one run
/// and none of the fastest of nine.
pub const REPEATS: usize = 9;

/// A target is judged when the reference's own error is at most this share
/// of it: the measured error is then the true one to within 10%, which
/// moves the interpolated cost of a twelfth-order method by `1.1^(1/12)`,
/// under 1%.
const REFERENCE_SHARE: f64 = 0.1;

/// A reference state as `lab/references/<scene>.json` holds it.
#[derive(Clone, Debug, PartialEq)]
struct Reference {
    /// Its time.
    pub t_end: f64,
    /// Where it comes from.
    pub source: String,
    /// The bound or estimate of its phase-space error.
    pub accuracy: f64,
    /// `q` then `v`, in the scene's (mass-weighted) coordinates.
    pub state: Vec<f64>,
}

/// Reads the reference of `scene` from `lab/references/`, checking that
/// it is that scene's and has `2 D` finite components.
fn reference<const D: usize>(scene: &str) -> Result<Reference, String> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../lab/references")
        .join(format!("{scene}.json"));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let json: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let number = |key: &str| json[key].as_f64().filter(|x| x.is_finite());
    let state: Option<Vec<f64>> = json["state"].as_array().and_then(|a| {
        a.iter()
            .map(|x| x.as_f64().filter(|x| x.is_finite()))
            .collect()
    });
    match (
        json["scene"].as_str(),
        number("t_end"),
        number("accuracy"),
        state,
    ) {
        (Some(id), Some(t_end), Some(accuracy), Some(state))
            if id == scene && state.len() == 2 * D && t_end > 0.0 && accuracy >= 0.0 =>
        {
            Ok(Reference {
                t_end,
                source: json["source"].as_str().unwrap_or("-").to_string(),
                accuracy,
                state,
            })
        }
        _ => Err(format!(
            "{}: not a reference of {scene} with {} finite components",
            path.display(),
            2 * D
        )),
    }
}

impl Reference {
    /// The state as the scene's.
    fn state<const D: usize>(&self) -> State<D> {
        State::new(
            brahe_nalgebra::SVector::from_fn(|i, _| self.state[i]),
            brahe_nalgebra::SVector::from_fn(|i, _| self.state[D + i]),
        )
    }
}

/// One tolerance of one contender.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RacePoint {
    pub tolerance: f64,
    /// Force evaluations, counted on the callback.
    pub evaluations: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected attempts.
    pub rejected: u64,
    /// The fastest run's wall time.
    pub seconds: f64,
    /// The error; `None` when the run did not reach the end time.
    pub error: Option<f64>,
}

/// One contender's runs on one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Contender {
    pub name: &'static str,
    /// The order the contender claims, by which its runs predict a
    /// target's cost.
    pub order: f64,
    pub points: Vec<RacePoint>,
}

impl Contender {
    fn runs(&self, cost: impl Fn(&RacePoint) -> f64) -> Vec<Run> {
        self.points
            .iter()
            .filter_map(|p| {
                p.error.map(|error| Run {
                    cost: cost(p),
                    evaluations: p.evaluations,
                    error,
                })
            })
            .collect()
    }

    /// Force evaluations to reach `target`.
    pub fn evaluations(&self, target: f64) -> Reach {
        let runs = self.runs(|p| p.evaluations as f64);
        target_cost::target_cost(&runs, target, self.order)
    }

    /// Seconds to reach `target`: its evaluations times the contender's
    /// seconds per evaluation. A step's cost per evaluation does not depend
    /// on the tolerance (the same stages, the same force, the same
    /// controller), but the machine's slow stretches last longer than one
    /// tolerance's rounds and inflate whole runs of consecutive tolerances,
    /// in or out of a target's window by chance: estimated from the runs'
    /// seconds directly, brahe over stepladder at 1e-6 on the outer solar
    /// system came out 0.93 where the evaluations say 1.27 and both spend
    /// the same per evaluation. The median over all of a contender's runs
    /// votes those stretches out.
    pub fn seconds(&self, target: f64) -> Reach {
        self.evaluations(target)
            .scaled(self.seconds_per_evaluation())
    }

    /// The median over the contender's runs of seconds per evaluation
    /// (`NaN` without runs).
    pub fn seconds_per_evaluation(&self) -> f64 {
        let per = self
            .points
            .iter()
            .map(|p| p.seconds / p.evaluations.max(1) as f64)
            .collect();
        target_cost::median(per).unwrap_or(f64::NAN)
    }

    /// The largest over the smallest evaluations to reach `target` when they
    /// are interpolated between the two runs that bracket it on a grid of
    /// one tolerance a decade, over the grid's [`PER_DECADE`] offsets;
    /// `None` unless every offset reaches it.
    pub fn decade_spread(&self, target: f64) -> Option<f64> {
        let costs: Option<Vec<f64>> = (0..PER_DECADE as usize)
            .map(|offset| {
                let data: Vec<(f64, Option<f64>)> = self
                    .points
                    .iter()
                    .skip(offset)
                    .step_by(PER_DECADE as usize)
                    .map(|p| (p.evaluations as f64, p.error))
                    .collect();
                cost_to_reach(&data, target).cost()
            })
            .collect();
        let costs = costs?;
        let lo = costs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = costs.iter().copied().fold(0.0, f64::max);
        Some(hi / lo)
    }
}

/// Every contender on one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneRace {
    pub scene: &'static str,
    pub t_end: f64,
    /// What the errors are measured against.
    pub reference: String,
    /// The reference's own error (for an exact solution, its rounding to
    /// doubles).
    pub reference_error: f64,
    /// brahe first, then stepladder's pairs.
    pub contenders: Vec<Contender>,
    /// brahe with its step cap lifted, run alongside the contenders but not
    /// one of them: the race takes each crate as its defaults leave it, and
    /// this measures what one of brahe's defaults does to its cost.
    pub uncapped: Contender,
    /// brahe's step at equal steps, beside the race too.
    pub uniform: UniformLadder,
    /// stepladder's estimate along the run at one fixed step.
    pub estimate: EstimateAlong,
}

/// The tolerance at which [`EstimateAlong`] takes its step and reads its
/// estimate: the middle target of the race.
pub const ESTIMATE_TOLERANCE: f64 = 1e-9;

/// Start points a step, for [`EstimateAlong`]: a quarter step apart, so that
/// the start points one step on are among them.
pub const STARTS_PER_STEP: usize = 4;

/// stepladder's plain pair's own estimate for one step of a fixed size,
/// from start points along the run: what a step controller follows. A
/// controller sets each step from the estimates it has already seen; it
/// aims at `safety^(q+1)` of the tolerance, so a step of the size it holds
/// is rejected where the estimate one step on is more than its margin,
/// `safety^-(q+1)`, above the last.
#[derive(Clone, Debug, PartialEq)]
pub struct EstimateAlong {
    /// The step: the run's length over the steps the pair accepts at
    /// [`ESTIMATE_TOLERANCE`].
    pub step: f64,
    /// The estimate in units of [`ESTIMATE_TOLERANCE`] from each start point,
    /// [`STARTS_PER_STEP`] a step from the run's start, every one from which
    /// a whole step stays within the run.
    pub estimates: Vec<f64>,
    /// The controller's margin, `safety^-(q+1)`.
    pub margin: f64,
}

impl EstimateAlong {
    /// The smallest and the largest estimate.
    pub fn range(&self) -> (f64, f64) {
        self.estimates
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &e| {
                (lo.min(e), hi.max(e))
            })
    }

    /// The estimate one step on over the estimate here, from every start
    /// point that has one.
    pub fn rises(&self) -> Vec<f64> {
        self.estimates
            .iter()
            .zip(self.estimates.iter().skip(STARTS_PER_STEP))
            .map(|(now, next)| next / now)
            .collect()
    }
}

/// [`EstimateAlong`] on `scene` to `t_end`; the states along the run are the
/// compensated pair's at a tolerance five decades below the estimate's, a
/// quarter step at a time (the estimate of a step hardly depends on an
/// error of its start that small).
fn estimate_along<S: Scene<D>, const D: usize>(scene: &S, t_end: f64) -> EstimateAlong {
    let pair = DPRKN12_ADAPTIVE;
    let accepted = pair
        .run(scene, t_end, ESTIMATE_TOLERANCE)
        .map_or(0, |r| r.accepted)
        .max(1);
    let step = t_end / accepted as f64;
    let quarter = step / STARTS_PER_STEP as f64;
    let mut state = scene.initial();
    let mut estimates = Vec::new();
    for k in 0.. {
        if k as f64 * quarter + step > t_end * (1.0 + 1e-12) {
            break;
        }
        estimates.push(pair.estimate(scene, &state, step, ESTIMATE_TOLERANCE));
        let Some(next) = DPRKN12_COMPENSATED
            .integrate(scene, &state, quarter, ESTIMATE_TOLERANCE * 1e-5)
            .ok()
            .and_then(|r| r.trajectory.last().map(|(_, s)| *s))
        else {
            break;
        };
        state = next;
    }
    let c = pair.controller;
    EstimateAlong {
        step,
        estimates,
        margin: c.safety.powf(-1.0 / c.exponent),
    }
}

impl SceneRace {
    /// Whether the reference resolves `target`.
    pub fn judges(&self, target: f64) -> bool {
        judged(self.reference_error, target)
    }
}

/// Whether a reference whose own error is `reference_error` judges `target`.
fn judged(reference_error: f64, target: f64) -> bool {
    reference_error <= REFERENCE_SHARE * target
}

/// The order by which equal steps of the tableau predict a target's cost.
const UNIFORM_ORDER: f64 = 12.0;

/// One run at equal steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UniformPoint {
    pub steps: u64,
    /// Force evaluations, counted on the force.
    pub evaluations: u64,
    /// The error; `None` when the run did not reach the end time.
    pub error: Option<f64>,
}

/// brahe's own step (every step accepted, the glue's
/// `brahe_rkn1210_step`) at `N` equal steps over the scene's interval,
/// `N = 1, 2, ...`: the tableau without its step control, so that the
/// race's costs can be read against what equal steps cost. Each next count
/// is the larger of `N + 1` and `10^(1 / (8 * 12)) N` rounded down: the
/// error of a twelfth-order step falls like `N^-12`, so consecutive counts
/// are at most an eighth of a decade of error apart (or one step), as dense
/// as the race's [`PER_DECADE`] tolerances. The
/// ladder ends at the first run whose error is [`WINDOW_DECADES`] below the
/// smallest judged target (as the race's ladders do), that fails to reach
/// the end, or before a run that would spend more evaluations than the
/// dearest run of any contender on the scene: equal steps that cost more
/// than every adaptive run are cheaper nowhere the race looks.
#[derive(Clone, Debug, PartialEq)]
pub struct UniformLadder {
    pub points: Vec<UniformPoint>,
}

impl UniformLadder {
    /// Force evaluations to reach `target`, estimated as the contenders'
    /// are.
    pub fn evaluations(&self, target: f64) -> Reach {
        let runs: Vec<Run> = self
            .points
            .iter()
            .filter_map(|p| {
                p.error.map(|error| Run {
                    cost: p.evaluations as f64,
                    evaluations: p.evaluations,
                    error,
                })
            })
            .collect();
        target_cost::target_cost(&runs, target, UNIFORM_ORDER)
    }
}

/// The step count after `steps` on the equal-step ladder (see
/// [`UniformLadder`]).
fn next_count(steps: u64) -> u64 {
    let ratio = 10f64.powf(1.0 / (PER_DECADE as f64 * UNIFORM_ORDER));
    (steps + 1).max((steps as f64 * ratio).floor() as u64)
}

/// The equal-step ladder on `scene` (see [`UniformLadder`]), spending at
/// most `budget` evaluations a run.
fn uniform_ladder<S: Scene<D>, const D: usize>(
    scene: &S,
    t_end: f64,
    smallest: f64,
    budget: u64,
    error: &impl Fn(&State<D>) -> Option<f64>,
) -> UniformLadder {
    let step = crate::methods::brahe_rkn1210_step();
    let per_step = stepladder::scheme::Scheme::meta(&step).force_evaluations as u64;
    let mut points = Vec::new();
    let mut steps = 1;
    while steps * per_step <= budget {
        let (end, evaluations) =
            stepladder::internals::run::counted_end(&step, scene, t_end, steps);
        let error = end.and_then(|s| error(&s));
        points.push(UniformPoint {
            steps,
            evaluations,
            error,
        });
        if error.is_none_or(|e| e <= smallest * 10f64.powf(-WINDOW_DECADES)) {
            break;
        }
        steps = next_count(steps);
    }
    UniformLadder { points }
}

/// brahe's pair as the race runs it.
fn brahe() -> AdaptiveBlackBox<stepladder::scheme::AdvanceFn> {
    AdaptiveBlackBox::new(
        "brahe RKN1210",
        stepladder::scheme::AdaptiveClaims::pair(12, 10),
        crate::glue::brahe_rkn1210,
    )
}

/// brahe's pair with its step cap lifted (`max_step: None`).
fn brahe_uncapped() -> AdaptiveBlackBox<stepladder::scheme::AdvanceFn> {
    AdaptiveBlackBox::new(
        "brahe RKN1210 without its step cap",
        stepladder::scheme::AdaptiveClaims::pair(12, 10),
        crate::glue::brahe_rkn1210_uncapped,
    )
}

/// One contender as the ladders run it: its name, its claimed order and a
/// run at a tolerance.
struct Runner<'a, const D: usize> {
    name: &'static str,
    order: f64,
    run: Box<dyn Fn(f64) -> Option<AdaptiveRun<D>> + 'a>,
}

impl<'a, const D: usize> Runner<'a, D> {
    fn new<I: AdaptiveIntegrator, S: Scene<D>>(
        integrator: &'a I,
        scene: &'a S,
        t_end: f64,
    ) -> Self {
        Runner {
            name: integrator.name(),
            order: integrator.claims().order as f64,
            run: Box::new(move |tol| integrator.run(scene, t_end, tol).ok()),
        }
    }
}

/// The ladders of every contender, run together: at each tolerance the
/// contenders take turns, [`REPEATS`] rounds, so that whatever else the
/// machine does at that moment slows them alike (with one contender's
/// whole ladder run after another's, brahe's time over stepladder's at
/// 1e-9 on the outer solar system was 1.07 in one run of the audit and 1.37
/// in the next). A contender's ladder ends at the first
/// run whose error is [`WINDOW_DECADES`] below the smallest target the
/// reference judges (so that runs on both sides of it predict its cost), or
/// that fails to reach the end.
fn ladders<const D: usize>(
    runners: &[Runner<'_, D>],
    smallest: f64,
    error: &impl Fn(&State<D>) -> Option<f64>,
) -> Vec<Contender> {
    let mut contenders: Vec<Contender> = runners
        .iter()
        .map(|r| Contender {
            name: r.name,
            order: r.order,
            points: Vec::new(),
        })
        .collect();
    let mut running = vec![true; runners.len()];
    let last = (DECADES.1 - DECADES.0) * PER_DECADE;
    for tol in (0..=last).map(tolerance) {
        let mut fastest: Vec<Option<(AdaptiveRun<D>, f64)>> =
            runners.iter().map(|_| None).collect();
        for _ in 0..REPEATS {
            for (i, runner) in runners.iter().enumerate() {
                if !running[i] {
                    continue;
                }
                let Some(run) = (runner.run)(tol) else {
                    running[i] = false;
                    continue;
                };
                let seconds = run.time.as_secs_f64();
                if fastest[i].as_ref().is_none_or(|(_, s)| seconds < *s) {
                    fastest[i] = Some((run, seconds));
                }
            }
        }
        for (i, best) in fastest.into_iter().enumerate() {
            let Some((run, seconds)) = best else {
                running[i] = false;
                continue;
            };
            let reached = run.end == RunEnd::Reached;
            let point = RacePoint {
                tolerance: tol,
                evaluations: run.evaluations,
                accepted: run.accepted,
                rejected: run.rejected,
                seconds,
                error: run
                    .trajectory
                    .last()
                    .filter(|_| reached)
                    .and_then(|(_, end)| error(end)),
            };
            contenders[i].points.push(point);
            if point
                .error
                .is_none_or(|e| e <= smallest * 10f64.powf(-WINDOW_DECADES))
            {
                running[i] = false;
            }
        }
        if !running.iter().any(|&r| r) {
            break;
        }
    }
    contenders
}

fn race_on<S: Scene<D>, const D: usize>(
    scene: &S,
    t_end: f64,
    reference: String,
    reference_error: f64,
    reference_state: &State<D>,
) -> SceneRace {
    let error =
        |end: &State<D>| Some(scene.phase_distance(end, reference_state)).filter(|e| e.is_finite());
    let smallest = TARGETS
        .iter()
        .copied()
        .filter(|&t| judged(reference_error, t))
        .fold(TARGETS[0], f64::min);
    let (brahe, uncapped) = (brahe(), brahe_uncapped());
    let runners = [
        Runner::new(&brahe, scene, t_end),
        Runner::new(&DPRKN12_ADAPTIVE, scene, t_end),
        Runner::new(&DPRKN12_COMPENSATED, scene, t_end),
        Runner::new(&uncapped, scene, t_end),
    ];
    let mut contenders = ladders(&runners, smallest, &error);
    let budget = contenders
        .iter()
        .flat_map(|c| &c.points)
        .map(|p| p.evaluations)
        .max()
        .unwrap_or(0);
    let uniform = uniform_ladder(scene, t_end, smallest, budget, &error);
    let uncapped = contenders.pop().expect("the uncapped runner's ladder");
    SceneRace {
        scene: scene.meta().id,
        t_end,
        reference,
        reference_error,
        contenders,
        uncapped,
        uniform,
        estimate: estimate_along(scene, t_end),
    }
}

/// The race on every scene, Kepler orbits first; an error when a
/// reference cannot be read.
pub fn race() -> Result<Vec<SceneRace>, String> {
    fn exact<S: Scene<D>, const D: usize>(scene: &S, t_end: f64) -> State<D> {
        scene.exact(t_end).expect("a Kepler orbit's exact solution")
    }
    let circular = KeplerCircular;
    let eccentric = KeplerEccentric::default();
    let (circular_end, eccentric_end) = (circular.default_t_end(), eccentric.default_t_end());
    let exact_circular = exact(&circular, circular_end);
    let exact_eccentric = exact(&eccentric, eccentric_end);
    let stars = Pleiades::default();
    let planets = OuterSolarSystem::default();
    let star_reference = reference::<14>(stars.meta().id)?;
    let planet_reference = reference::<18>(planets.meta().id)?;
    let (star_end, planet_end) = (star_reference.state(), planet_reference.state());
    Ok(vec![
        race_on(
            &circular,
            circular_end,
            "the exact solution, rounded to doubles".to_string(),
            rounding_distance(&circular, &exact_circular),
            &exact_circular,
        ),
        race_on(
            &eccentric,
            eccentric_end,
            "the exact solution, rounded to doubles".to_string(),
            rounding_distance(&eccentric, &exact_eccentric),
            &exact_eccentric,
        ),
        race_on(
            &stars,
            star_reference.t_end,
            star_reference.source.clone(),
            star_reference.accuracy,
            &star_end,
        ),
        race_on(
            &planets,
            planet_reference.t_end,
            planet_reference.source.clone(),
            planet_reference.accuracy,
            &planet_end,
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Consecutive counts of the equal-step ladder are at most an eighth
    /// of a decade of a twelfth-order error apart, `(N / next)^12 >=
    /// 10^(-1/8)`, except below `1 / (10^(1/96) - 1) = 41.2` steps, where
    /// one step is more than that and the next count is `N + 1`; and no
    /// closer than they need be: one count further would be more than an
    /// eighth apart.
    #[test]
    fn equal_step_counts_are_an_eighth_of_a_decade_apart() {
        let eighth = 10f64.powf(-1.0 / PER_DECADE as f64);
        let fall = |n: u64, m: u64| (n as f64 / m as f64).powf(UNIFORM_ORDER);
        let mut n = 1;
        while n < 100_000 {
            let next = next_count(n);
            if n <= 41 {
                assert_eq!(next, n + 1);
                assert!(fall(n, next) < eighth, "{n} -> {next}");
            } else {
                assert!(fall(n, next) >= eighth, "{n} -> {next}");
                assert!(fall(n, next + 1) < eighth, "{n} -> {next}");
            }
            n = next;
        }
    }

    /// The rise over one step compares start points a step apart, and the
    /// range spans every start point.
    #[test]
    fn rises_are_one_step_apart() {
        let along = EstimateAlong {
            step: 1.0,
            estimates: vec![1.0, 2.0, 3.0, 4.0, 8.0, 2.0],
            margin: 3.0,
        };
        assert_eq!(along.rises(), vec![8.0, 1.0]);
        assert_eq!(along.range(), (1.0, 8.0));
    }

    /// On the circular orbit the estimate from any point is the one from
    /// the start turned, so it moves only with the norm's per-component
    /// weights, by at most `1 + |v| = 1 + 2 pi`, and nowhere rises by the
    /// margin; the start points cover the run a quarter step apart, and the
    /// margin is `0.9^-11`.
    #[test]
    fn the_estimate_on_the_circular_orbit_follows_its_symmetry() {
        let scene = KeplerCircular;
        let t_end = scene.default_t_end();
        let along = estimate_along(&scene, t_end);
        let (lo, hi) = along.range();
        assert!(
            lo > 0.0 && hi / lo <= 1.0 + std::f64::consts::TAU,
            "{lo} .. {hi}"
        );
        assert!(along.rises().iter().all(|&r| r < along.margin));
        let quarter = along.step / STARTS_PER_STEP as f64;
        assert_eq!(
            along.estimates.len(),
            ((t_end - along.step) / quarter * (1.0 + 1e-12)).floor() as usize + 1
        );
        assert!((along.margin - 0.9f64.powi(-11)).abs() < 1e-12);
        // the step is the run's length over its accepted steps at the tolerance
        let run = DPRKN12_ADAPTIVE
            .run(&scene, t_end, ESTIMATE_TOLERANCE)
            .unwrap();
        assert_eq!(along.step, t_end / run.accepted as f64);
    }

    /// brahe's step and stepladder's own DPRKN12 table, the same tableau in
    /// two implementations, end the outer solar system at 16 equal steps
    /// within rounding of each other, far closer than either is to the
    /// reference: the equal-step figures are the tableau's, not one
    /// implementation's.
    #[test]
    fn equal_steps_of_brahe_and_of_stepladder_agree() {
        let scene = OuterSolarSystem::default();
        let reference = reference::<18>(scene.meta().id).expect("the reference");
        let steps = 16;
        let h = reference.t_end / steps as f64;
        let end = |scheme: &dyn Fn(&mut Option<State<18>>)| {
            let mut end = None;
            scheme(&mut end);
            end.expect("the run reaches the end")
        };
        let brahe = end(&|out| {
            let step = crate::methods::brahe_rkn1210_step();
            stepladder::internals::run::integrate(
                &step,
                &scene,
                &scene.initial(),
                h,
                steps,
                |n, _, s| {
                    if n == steps {
                        *out = Some(*s);
                    }
                },
            );
        });
        let own = end(&|out| {
            stepladder::internals::run::integrate(
                &stepladder::scheme::DPRKN12,
                &scene,
                &scene.initial(),
                h,
                steps,
                |n, _, s| {
                    if n == steps {
                        *out = Some(*s);
                    }
                },
            );
        });
        let apart = scene.phase_distance(&brahe, &own);
        let error = scene.phase_distance(&brahe, &reference.state());
        // 16 steps of 17 stages over states of order 30 AU: rounding of a
        // few hundred operations, 1e-13 at most
        assert!(apart < 1e-12, "{apart:e}");
        assert!(error > 1e3 * apart, "{error:e} against {apart:e}");
    }
}
