//! brahe's RKN12(10) raced against stepladder's own two RKN12(10) pairs on
//! the scenes of the repository's race: the same published tableau
//! (Dormand, El-Mikkawy and Prince 1987) in three implementations, so what
//! separates them is the step control, the error norm, the arithmetic of
//! the state updates and the cost of a step, not the method.
//!
//! Every contender runs the same tolerances, one a decade, loosest first,
//! and is judged by the same error, the phase-space distance at the end
//! time to the reference: on the Kepler orbits the exact solution (its
//! rounding to doubles its error), on the Pleiades and the outer solar
//! system the reference states of the repository's race. (That race takes
//! the largest error over every accepted step on the Kepler orbits; a
//! black box shows only its end, so here all three are judged there.)
//! The evaluations to reach a target are interpolated on log-log axes
//! between the two runs that bracket it (stepladder's `cost_to_reach`, as
//! the repository's race does), the seconds the same way from the fastest
//! of [`REPEATS`] runs of each tolerance.
//!
//! The N-body references are the repository's race's, read from
//! `lab/references/` (written by `stepladder reference`; a harness test
//! keeps them equal to what the lab computes), so this crate races without
//! building the lab: the Pleiades' published state, and for the outer
//! solar system a double-double integration certified to `5e-17`.

use stepladder::internals::cost::work_points::{Reach, cost_to_reach};
use stepladder::internals::tolerance::rounding_distance;
use stepladder::scene::{KeplerCircular, KeplerEccentric, OuterSolarSystem, Pleiades, Scene};
use stepladder::scheme::{
    AdaptiveBlackBox, AdaptiveIntegrator, AdaptiveRun, DPRKN12_ADAPTIVE, DPRKN12_COMPENSATED,
    RunEnd,
};
use stepladder::state::State;

/// The tolerances each contender runs, one a decade, each the literal
/// nearest its decade; below `1e-16` a tolerance is under a unit of
/// round-off of the states' order-one components.
const TOLERANCES: [f64; 14] = [
    1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15, 1e-16,
];

/// The target errors, those of the repository's race.
pub const TARGETS: [f64; 4] = [1e-6, 1e-9, 1e-12, 1e-14];

/// Runs timed per tolerance; the fastest counts (the machine is shared).
pub const REPEATS: usize = 5;

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
    pub points: Vec<RacePoint>,
}

impl Contender {
    fn reach(&self, cost: impl Fn(&RacePoint) -> f64, target: f64) -> Reach {
        let data: Vec<(f64, Option<f64>)> =
            self.points.iter().map(|p| (cost(p), p.error)).collect();
        cost_to_reach(&data, target)
    }

    /// Force evaluations to reach `target`.
    pub fn evaluations(&self, target: f64) -> Reach {
        self.reach(|p| p.evaluations as f64, target)
    }

    /// Seconds to reach `target`.
    pub fn seconds(&self, target: f64) -> Reach {
        self.reach(|p| p.seconds, target)
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
}

impl SceneRace {
    /// Whether the reference resolves `target`.
    pub fn judges(&self, target: f64) -> bool {
        self.reference_error <= REFERENCE_SHARE * target
    }
}

/// brahe's pair as the race runs it.
fn brahe() -> AdaptiveBlackBox<stepladder::scheme::AdvanceFn> {
    AdaptiveBlackBox::new(
        "brahe RKN1210",
        stepladder::scheme::AdaptiveClaims::pair(12, 10),
        crate::glue::brahe_rkn1210,
    )
}

/// The ladder of one contender: every tolerance until a run's error is at
/// most the smallest target the reference judges, or a run fails to reach
/// the end. Tighter runs cannot change any cost: a target's cost comes from
/// the first run at or below it and the one before (`cost_to_reach`).
fn ladder<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    integrator: &I,
    scene: &S,
    t_end: f64,
    smallest: f64,
    error: &impl Fn(&AdaptiveRun<D>) -> Option<f64>,
) -> Contender {
    let mut points = Vec::new();
    for tol in TOLERANCES {
        let mut fastest: Option<(AdaptiveRun<D>, f64)> = None;
        for _ in 0..REPEATS {
            let Ok(run) = integrator.run(scene, t_end, tol) else {
                break;
            };
            let seconds = run.time.as_secs_f64();
            if fastest.as_ref().is_none_or(|(_, s)| seconds < *s) {
                fastest = Some((run, seconds));
            }
        }
        let Some((run, seconds)) = fastest else { break };
        let reached = run.end == RunEnd::Reached;
        let point = RacePoint {
            tolerance: tol,
            evaluations: run.evaluations,
            accepted: run.accepted,
            rejected: run.rejected,
            seconds,
            error: if reached { error(&run) } else { None },
        };
        points.push(point);
        if point.error.is_none_or(|e| e <= smallest) {
            break;
        }
    }
    Contender {
        name: integrator.name(),
        points,
    }
}

fn race_on<S: Scene<D>, const D: usize>(
    scene: &S,
    t_end: f64,
    reference: String,
    reference_error: f64,
    error: impl Fn(&AdaptiveRun<D>) -> Option<f64>,
) -> SceneRace {
    let mut race = SceneRace {
        scene: scene.meta().id,
        t_end,
        reference,
        reference_error,
        contenders: Vec::new(),
    };
    let smallest = TARGETS
        .iter()
        .copied()
        .filter(|&t| race.judges(t))
        .fold(TARGETS[0], f64::min);
    race.contenders = vec![
        ladder(&brahe(), scene, t_end, smallest, &error),
        ladder(&DPRKN12_ADAPTIVE, scene, t_end, smallest, &error),
        ladder(&DPRKN12_COMPENSATED, scene, t_end, smallest, &error),
    ];
    race
}

/// The distance at the end time to `reference`.
fn at_end<S: Scene<D>, const D: usize>(
    scene: &S,
    run: &AdaptiveRun<D>,
    reference: &State<D>,
) -> Option<f64> {
    let (_, end) = run.trajectory.last()?;
    Some(scene.phase_distance(end, reference)).filter(|e| e.is_finite())
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
            |run| at_end(&circular, run, &exact_circular),
        ),
        race_on(
            &eccentric,
            eccentric_end,
            "the exact solution, rounded to doubles".to_string(),
            rounding_distance(&eccentric, &exact_eccentric),
            |run| at_end(&eccentric, run, &exact_eccentric),
        ),
        race_on(
            &stars,
            star_reference.t_end,
            star_reference.source.clone(),
            star_reference.accuracy,
            |run| at_end(&stars, run, &star_end),
        ),
        race_on(
            &planets,
            planet_reference.t_end,
            planet_reference.source.clone(),
            planet_reference.accuracy,
            |run| at_end(&planets, run, &planet_end),
        ),
    ])
}
