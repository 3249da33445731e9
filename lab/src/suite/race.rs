//! The race: the crate's best integrator, fixed-step or adaptive, against
//! every peer at equal error, on the two Kepler orbits and the two N-body
//! scenes.
//!
//! On the Kepler orbits every contender's cost comes from runs made anyway:
//! the cheapest fixed-step scheme from the work study, the adaptive pairs
//! and the peers from their tolerance ladders, all judged by the largest
//! phase-space error over the run against the exact solution. The N-body
//! scenes have no exact solution, so their contenders are run here and
//! judged by the phase-space distance at the end time to a reference state
//! ([`NbodyReference`]); a target below what the reference resolves is
//! marked as not judged. Every contender's cost of a target is read off its
//! runs as the cost of reaching it for good ([`crate::suite::reached_for_good`]):
//! at the first run that meets it after which no dearer run of its ladder
//! misses it, one dearer run confirming it.
//!
//! On the N-body scenes the search for the cheapest fixed-step scheme stops
//! where it can no longer matter to the race: once a scheme's run that
//! misses a target already costs at least what the cheapest own adaptive
//! pair spends on it (every finer run costs more, and an interpolated cost
//! lies between the costs of the two runs that bracket the target), that
//! scheme cannot be the crate's best at that target. Where no own pair
//! reaches a target, the fixed steps are searched as far as the pairs' most
//! expensive run went.

use crate::peer::{IntegratorVisitor, PEER_TOLERANCES, PEERS};
use crate::suite::adaptive::{AdaptiveRecords, INTEGRATORS, OWN_PAIRS};
use crate::suite::dd_reference;
use crate::suite::pericentre_lag::PericentreLag;
use crate::suite::reached_for_good::{
    deciding_runs, met_only_by_last_run, met_since_last_miss, reach_for_good,
};
use crate::suite::work_precision::{PEER_REPEATS, WorkRecord, WorkTiming};
use serde::Serialize;
use stepladder::internals::adaptive::tolerance_point;
use stepladder::internals::cost::step_time::time_run;
use stepladder::internals::cost::work_points::{Reach, cheapest, cost_to_reach};
use stepladder::internals::parallel::parallel_map;
use stepladder::internals::run::counted_end;
use stepladder::internals::tolerance::rounding_distance;
use stepladder::scene::{
    AnyScene, KeplerEccentric, OuterSolarSystem, Pleiades, Scene, SceneVisitor,
};
use stepladder::scheme::{AdaptiveIntegrator, RunEnd};
use stepladder::scheme::{
    Compensated, KAHAN_LI8, Scheme, SchemeVisitor, SplittingTable, scheme_ids, visit_scheme,
};
use stepladder::state::State;

/// The Kepler scenes of the race.
pub const KEPLER_SCENES: [&str; 2] = ["kepler-circular", "kepler-eccentric"];
/// The N-body scenes of the race.
pub const NBODY_SCENES: [&str; 2] = ["pleiades", "outer-solar-system"];
/// The target errors, from a loose one to the accuracy of ephemeris work.
pub const RACE_TARGETS: [f64; 4] = [1e-6, 1e-9, 1e-12, 1e-14];

/// A target is judged when the reference's own error is at most this share
/// of it: the error measured against the reference is then the true error
/// to within 10%, which moves the interpolated cost of an order-`p` method
/// by a factor `1.1^(1/p)`, under 2% for `p >= 6` (the contenders' orders).
pub const REFERENCE_SHARE: f64 = 0.1;

/// The tolerances an adaptive contender's ladder on an N-body scene may
/// use, one a decade, loosest first, each the literal nearest its decade (a
/// tolerance a unit of round-off off its decade moves a run at the floor by
/// as much as the floor itself): below `1e-16` a tolerance is under a unit
/// of round-off of the states' order-one components.
pub const NBODY_TOLERANCES: [f64; 14] = [
    1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15, 1e-16,
];

/// The first of [`NBODY_TOLERANCES`] an adaptive ladder runs. The ladder
/// goes a decade looser a run while its loosest run is already below the
/// largest target, and a decade tighter a run until it has reached the
/// smallest target the reference judges for good (a run below it and a
/// tighter one that stays below, see [`crate::suite::reached_for_good`]), or
/// down to the list's last tolerance. It does not stop where the error seems to have stopped
/// falling: near the round-off floor the end error of one run can fall
/// below the trend by a cancellation of its local errors and the next run's
/// then looks like a floor (near 1e-15 the compensated pairs' end errors
/// on the outer solar system move by up to a factor of ten from one
/// tolerance to the next), and every run is cheap next to the rest of the report.
pub const NBODY_FIRST_TOLERANCE: f64 = 1e-8;

/// Steps of the first run of a fixed-step ladder on an N-body scene; each
/// next run doubles them.
pub const NBODY_FIRST_STEPS: u64 = 16;

/// Most force evaluations one fixed-step run may spend, whatever the
/// bounds.
pub const NBODY_MAX_EVALUATIONS: u64 = 1 << 20;

/// Steps of the double-double eighth-order triple jump that makes the outer
/// solar system's reference over its default end time, 1.5 days a step for
/// Jupiter's 4,332-day orbit. Its truncation error there is about 4e-20,
/// far below its rounding to doubles (4e-17): from 2^10 to 2^14 steps the
/// runs move by 7.2e-13, 2.8e-15, 1.1e-17 and 4.3e-20 a doubling, falling
/// 256-fold as an eighth-order method's must.
pub const OUTER_REFERENCE_STEPS: u64 = 1 << 13;

/// The quadruple-precision state of the Pleiades at `t = 3` (K. J. L. Li,
/// RKAdaptiveMethods, Pleiades reference, stated good to 25 digits), in the
/// IVP test set's order `x1..x7, y1..y7, x'1..x'7, y'1..y'7`: what the
/// published 16-digit state is measured against.
pub const PLEIADES_QUADRUPLE_PRECISION: [&str; 28] = [
    "0.370613914397051269489224978315",
    "3.237284092057233220174339294317",
    "-3.222559032418323532453996449476",
    "0.659709145577530797766030445928",
    "0.342558170715657972493772831513",
    "1.562172101400631119005879554607",
    "-0.700309292221249490850709662482",
    "-3.943437585517392207634657097515",
    "-3.271380973972549899286832442158",
    "5.225081843456544028470034390921",
    "-2.590612434977469291652596439235",
    "1.198213693392274681315257112146",
    "-0.242968234493582346811280103793",
    "1.091449240428979727823843859369",
    "3.417003806314314662273545764037",
    "1.354584501625501147259456047323",
    "-2.590065597810775610554401282570",
    "2.025053734714241215897345682606",
    "-1.155815100160449082622449168412",
    "-0.807298817022302217516482869542",
    "0.595239635420871882054427715047",
    "-3.741244961234008403749839999364",
    "0.377345968575062917782503291164",
    "0.938685886955107906537421058601",
    "0.366792222720056959595069656643",
    "-0.347404635380849424741711573006",
    "2.344915448180937111999355693115",
    "-1.947020434263291965848452491628",
];

/// [`PLEIADES_QUADRUPLE_PRECISION`] as a mass-weighted state (each value
/// correctly rounded to f64).
pub fn pleiades_quadruple_precision(stars: &Pleiades) -> State<14> {
    let x: Vec<f64> = PLEIADES_QUADRUPLE_PRECISION
        .iter()
        .map(|s| s.parse().expect("decimal literals"))
        .collect();
    let physical = State::new(
        nalgebra::SVector::from_fn(|n, _| x[7 * (n % 2) + n / 2]),
        nalgebra::SVector::from_fn(|n, _| x[14 + 7 * (n % 2) + n / 2]),
    );
    stars.mass_weighted(&physical)
}

/// An upper bound on the published Pleiades state's own error: its phase
/// distance to the quadruple-precision state plus the latter's rounding to
/// f64.
pub fn pleiades_published_accuracy(stars: &Pleiades) -> f64 {
    let quad = pleiades_quadruple_precision(stars);
    stars.phase_distance(&stars.published_end(), &quad) + rounding_to_doubles(stars, &quad)
}

/// A bound on the phase-space distance between a state and its coordinates
/// rounded to doubles: half an ulp a coordinate, at most `2^-53` of it,
/// weighted as the phase distance weighs it.
fn rounding_to_doubles<S: Scene<D>, const D: usize>(scene: &S, s: &State<D>) -> f64 {
    let w = scene.frequency();
    0.5 * f64::EPSILON * (s.q.norm_squared() + (s.v / w).norm_squared()).sqrt()
}

/// Kahan and Li's eighth-order composition with compensated sums: the
/// reference's method, whose round-off over thousands of steps stays near a
/// unit of the states.
pub const KAHAN_LI8_COMPENSATED: Compensated<SplittingTable> = Compensated {
    meta: KAHAN_LI8.meta,
    plain: KAHAN_LI8,
};

/// The state the N-body contenders are judged against, and how well it is
/// known.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NbodyReference {
    /// Scene id.
    pub scene: &'static str,
    /// The time of the state.
    pub t_end: f64,
    /// Where the state comes from.
    pub source: &'static str,
    /// How its error is bounded or estimated.
    pub accuracy_source: &'static str,
    /// The bound or estimate of its phase-space error.
    pub accuracy: f64,
    /// The state, `q` then `v`, mass-weighted.
    pub state: Vec<f64>,
}

impl NbodyReference {
    /// The state as the scene's.
    fn state<const D: usize>(&self) -> State<D> {
        State::new(
            nalgebra::SVector::from_fn(|i, _| self.state[i]),
            nalgebra::SVector::from_fn(|i, _| self.state[D + i]),
        )
    }

    /// Whether a target is above what the reference resolves.
    pub fn judges(&self, target: f64) -> bool {
        self.accuracy <= REFERENCE_SHARE * target
    }
}

/// The reference of the N-body scene `scene` as pretty JSON, every number
/// written so that it parses back to the same double: what
/// `stepladder reference` prints, and what the audit of published crates
/// reads from `lab/references/` to judge its race without building the lab.
pub fn reference_json(scene: &str) -> Result<String, stepladder::error::Error> {
    let reference = NbodyScene::all()
        .into_iter()
        .find(|s| s.id() == scene)
        .ok_or_else(|| {
            stepladder::error::Error::InvalidScene(format!(
                "no reference for {scene:?}: the N-body scenes of the race are {NBODY_SCENES:?}"
            ))
        })?
        .reference();
    serde_json::to_string_pretty(&reference)
        .map_err(|e| stepladder::error::Error::InvalidScene(format!("{scene}: {e}")))
}

fn flat<const D: usize>(s: &State<D>) -> Vec<f64> {
    s.q.iter().chain(s.v.iter()).copied().collect()
}

/// An N-body scene of the race.
#[derive(Clone, Copy, Debug)]
pub enum NbodyScene {
    /// [`Pleiades`].
    Pleiades(Pleiades),
    /// [`OuterSolarSystem`].
    OuterSolarSystem(OuterSolarSystem),
}

impl NbodyScene {
    /// Both, in race order.
    pub fn all() -> [NbodyScene; 2] {
        [
            NbodyScene::Pleiades(Pleiades::default()),
            NbodyScene::OuterSolarSystem(OuterSolarSystem::default()),
        ]
    }

    /// The scene's id.
    pub fn id(&self) -> &'static str {
        match self {
            NbodyScene::Pleiades(s) => s.meta().id,
            NbodyScene::OuterSolarSystem(s) => s.meta().id,
        }
    }

    /// Runs `visitor` on the scene.
    pub fn visit<V: SceneVisitor>(&self, visitor: V) -> V::Output {
        match self {
            NbodyScene::Pleiades(s) => visitor.visit::<Pleiades, 14>(s),
            NbodyScene::OuterSolarSystem(s) => visitor.visit::<OuterSolarSystem, 18>(s),
        }
    }

    /// The reference state at the scene's default end time: for the
    /// Pleiades the published one, for the outer solar system the
    /// double-double triple jump at [`OUTER_REFERENCE_STEPS`], its error
    /// bounded by its distance to the same run at half the steps (an
    /// eighth-order run's own error is about `1/255` of that) plus its
    /// rounding to doubles.
    pub fn reference(&self) -> NbodyReference {
        match self {
            NbodyScene::Pleiades(stars) => NbodyReference {
                scene: "pleiades",
                t_end: Pleiades::PUBLISHED_TIME,
                source: "the published state (IVP test set, PLEI)",
                accuracy_source: "its distance to a quadruple-precision integration",
                accuracy: pleiades_published_accuracy(stars),
                state: flat(&stars.published_end()),
            },
            NbodyScene::OuterSolarSystem(planets) => {
                let t_end = planets.default_t_end();
                let start = dd_reference::initial(planets);
                let [fine, halved] =
                    [OUTER_REFERENCE_STEPS, OUTER_REFERENCE_STEPS / 2].map(|steps| {
                        dd_reference::mass_weighted_dd(&dd_reference::integrate(
                            &start, t_end, steps,
                        ))
                    });
                let state = dd_reference::rounded(&fine);
                NbodyReference {
                    scene: "outer-solar-system",
                    t_end,
                    source: "Yoshida's eighth-order triple jump of Verlet steps in double-double arithmetic, 8192 steps",
                    accuracy_source: "its distance to the same run at half the steps, plus its rounding to doubles",
                    accuracy: dd_reference::distance(planets, &fine, &halved)
                        + rounding_to_doubles(planets, &state),
                    state: flat(&state),
                }
            }
        }
    }
}

/// One run of a contender.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RacePoint {
    /// The tolerance of an adaptive run, the steps of a fixed-step one.
    pub setting: f64,
    /// Force evaluations.
    pub evaluations: u64,
    /// Its error (on an N-body scene the phase-space distance at the end
    /// time to the reference); `None` when the run did not reach the end.
    pub error: Option<f64>,
}

/// A contender's runs on one scene, cheapest first.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RaceLadder {
    /// The integrator's name or the scheme's id.
    pub contender: &'static str,
    /// The runs.
    pub points: Vec<RacePoint>,
    /// The end state of the last run (`q` then `v`), where it reached the
    /// end on an N-body scene.
    #[serde(skip)]
    pub last_end: Option<Vec<f64>>,
}

impl RaceLadder {
    fn data(&self) -> Vec<(f64, Option<f64>)> {
        self.points
            .iter()
            .map(|p| (p.evaluations as f64, p.error))
            .collect()
    }

    /// The evaluations to reach `target` for good (see
    /// [`crate::suite::reached_for_good`]).
    pub fn reach(&self, target: f64) -> Reach {
        reach_for_good(&self.data(), target)
    }

    /// The indices of the runs that decide the cost of `target`, the only
    /// runs the time race needs.
    pub(crate) fn deciding(&self, target: f64) -> Vec<usize> {
        deciding_runs(&self.data(), target)
    }
}

/// The adaptive contender's ladder (see [`NBODY_FIRST_TOLERANCE`]).
fn adaptive_ladder<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    integrator: &I,
    scene: &S,
    reference: &NbodyReference,
) -> RaceLadder {
    let mut ends: Vec<(f64, Option<State<D>>)> = Vec::new();
    let mut run = |tol: f64| {
        let (evaluations, state) = match integrator.run(scene, reference.t_end, tol) {
            Ok(r) => (
                r.evaluations,
                r.trajectory
                    .last()
                    .filter(|_| r.end == RunEnd::Reached)
                    .map(|x| x.1),
            ),
            Err(_) => (0, None),
        };
        ends.push((tol, state));
        RacePoint {
            setting: tol,
            evaluations,
            error: state
                .map(|s| scene.phase_distance(&s, &reference.state()))
                .filter(|e| e.is_finite()),
        }
    };
    let largest = RACE_TARGETS[0];
    let smallest = RACE_TARGETS
        .iter()
        .copied()
        .filter(|&t| reference.judges(t))
        .fold(largest, f64::min);
    let first = NBODY_TOLERANCES
        .iter()
        .position(|&t| t == NBODY_FIRST_TOLERANCE)
        .expect("the first tolerance is on the list");
    let mut points = vec![run(NBODY_TOLERANCES[first])];
    let mut k = first;
    while points[0].error.is_none_or(|e| e <= largest) && k > 0 {
        k -= 1;
        points.insert(0, run(NBODY_TOLERANCES[k]));
    }
    let settled = |points: &[RacePoint]| {
        let data: Vec<(f64, Option<f64>)> = points
            .iter()
            .map(|p| (p.evaluations as f64, p.error))
            .collect();
        reach_for_good(&data, smallest) != Reach::NotReached
    };
    let mut k = first;
    while k + 1 < NBODY_TOLERANCES.len() && !settled(&points) {
        k += 1;
        points.push(run(NBODY_TOLERANCES[k]));
    }
    let last = points.last().map(|p| p.setting);
    let last_end = ends
        .iter()
        .find(|(tol, _)| Some(*tol) == last)
        .and_then(|(_, s)| s.as_ref().map(flat));
    RaceLadder {
        contender: integrator.name(),
        points,
        last_end,
    }
}

/// The fixed-step contender's ladder: steps doubling from
/// [`NBODY_FIRST_STEPS`] until every target is reached for good, or until
/// every target not yet reached is one the run just made missed and cannot
/// beat `bounds` at (see the module documentation), or a run would exceed
/// [`NBODY_MAX_EVALUATIONS`].
fn fixed_ladder<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    reference: &NbodyReference,
    bounds: &[Option<f64>],
) -> RaceLadder {
    let mut points: Vec<RacePoint> = Vec::new();
    let mut steps = NBODY_FIRST_STEPS;
    loop {
        let (end, evaluations) = counted_end(scheme, scene, reference.t_end, steps);
        let error = end
            .map(|s| scene.phase_distance(&s, &reference.state()))
            .filter(|e| e.is_finite());
        points.push(RacePoint {
            setting: steps as f64,
            evaluations,
            error,
        });
        let cost = evaluations as f64;
        let data: Vec<(f64, Option<f64>)> = points
            .iter()
            .map(|p| (p.evaluations as f64, p.error))
            .collect();
        let open: Vec<usize> = (0..RACE_TARGETS.len())
            .filter(|&i| reach_for_good(&data, RACE_TARGETS[i]) == Reach::NotReached)
            .collect();
        // a target no run has met since the last miss can only be reached
        // from a dearer run, at a cost of at least this one's; one met since
        // still needs a dearer run to confirm it, and its cost may lie below
        // this one's
        let hopeless = open.iter().all(|&i| {
            !met_since_last_miss(&data, RACE_TARGETS[i])
                && bounds.get(i).copied().flatten().is_some_and(|b| cost >= b)
        });
        if open.is_empty() || hopeless || 2 * evaluations > NBODY_MAX_EVALUATIONS {
            break;
        }
        steps *= 2;
    }
    RaceLadder {
        contender: scheme.meta().id,
        points,
        last_end: None,
    }
}

/// Every contender on one N-body scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NbodyRecord {
    /// The reference the runs are judged against.
    pub reference: NbodyReference,
    /// The adaptive integrators, in the order of
    /// [`crate::suite::adaptive::INTEGRATORS`].
    pub adaptive: Vec<RaceLadder>,
    /// The catalogue's fixed-step schemes, in catalogue order.
    pub fixed: Vec<RaceLadder>,
    /// For each target, where the search for a fixed step stops: the
    /// cheapest own pair's cost, or where no pair reaches the target, the
    /// most evaluations a pair's run spent.
    pub fixed_bounds: Vec<Option<f64>>,
    /// The largest phase distance between the end states of any two
    /// adaptive contenders at their tightest run: how well the methods
    /// agree among themselves, apart from the reference.
    pub spread: f64,
}

/// A contender's cost of one target, and who it is.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Entry {
    /// The contender (the cheapest of its kind), if any reaches the target.
    pub name: Option<&'static str>,
    /// Its cost.
    pub reach: Reach,
}

/// One scene and target of the race: in force evaluations
/// (deterministic), or in seconds (machine-dependent).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RaceRow {
    /// Scene id.
    pub scene: &'static str,
    /// The target error.
    pub target: f64,
    /// The cheapest (or fastest) fixed-step catalogue scheme.
    pub fixed: Entry,
    /// Where the search for a fixed step stopped without finding one (the
    /// own pair's cost, on the N-body scenes).
    pub fixed_searched_to: Option<f64>,
    /// The cheapest (or fastest) of the crate's own adaptive pairs.
    pub pair: Entry,
    /// Each peer's cost, in the order of [`PEERS`].
    pub peers: Vec<Reach>,
    /// The smallest error any contender's run reached (by evaluations; not
    /// kept in the race by time).
    pub smallest_error: Option<f64>,
    /// The contenders, of either side, that meet the target only with the
    /// last run of their ladder, and that run's cost: not reached for good,
    /// for want of a dearer run (by evaluations; not kept in the race by
    /// time).
    pub unconfirmed: Vec<(&'static str, f64)>,
    /// The reference resolves the target (against an exact solution: its
    /// rounding in doubles, [`exact_rounding`], is at most
    /// [`REFERENCE_SHARE`] of the target).
    pub judged: bool,
}

/// The smallest of some costs.
fn least(costs: impl IntoIterator<Item = Option<f64>>) -> Option<f64> {
    costs.into_iter().flatten().reduce(f64::min)
}

impl RaceRow {
    /// The crate's best cost: fixed step or own pair.
    pub fn best(&self) -> Option<f64> {
        least([self.fixed.reach.cost(), self.pair.reach.cost()])
    }

    /// The cheapest peer's index and cost.
    pub fn best_peer(&self) -> Option<(usize, f64)> {
        self.peers
            .iter()
            .enumerate()
            .filter_map(|(i, r)| r.cost().map(|c| (i, c)))
            .reduce(|a, b| if b.1 < a.1 { b } else { a })
    }
}

/// The race's records.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RaceRecords {
    /// By force evaluations, Kepler scenes then N-body scenes, targets in
    /// order.
    pub rows: Vec<RaceRow>,
    /// The N-body scenes' runs.
    pub nbody: Vec<NbodyRecord>,
    /// Evaluations per correct digit, one row per race row.
    pub digits: Vec<DigitRow>,
    /// IAS15, measured by REBOUND, on the N-body scenes.
    pub ias15: Vec<crate::suite::ias15::Ias15Row>,
    /// Why the eccentric orbit's smallest target is out of reach.
    pub pericentre_lag: Option<PericentreLag>,
    /// The own pairs' runs on the Kepler orbits, by scene: each pair's
    /// tolerance ladder carried on to the peers' tightest tolerance
    /// ([`kepler_pair_ladders`]).
    pub kepler_pairs: Vec<(&'static str, RaceLadder)>,
}

/// The cheapest of the named reaches.
fn entry(candidates: &[(&'static str, Reach)]) -> Entry {
    match cheapest(candidates) {
        Some((name, reach)) => Entry {
            name: Some(name),
            reach,
        },
        None => Entry {
            name: None,
            reach: Reach::NotReached,
        },
    }
}

/// The peers' runs on a Kepler scene in the work study (at every one of
/// [`PEER_TOLERANCES`], so that no target a peer could reach is denied it),
/// in the order of [`PEERS`].
fn kepler_peers(w: &WorkRecord) -> Vec<RaceLadder> {
    w.peers
        .iter()
        .map(|p| RaceLadder {
            contender: p.peer,
            last_end: None,
            points: p
                .global
                .iter()
                .map(|x| RacePoint {
                    setting: x.tolerance,
                    evaluations: x.evaluations,
                    error: x.error,
                })
                .collect(),
        })
        .collect()
}

/// How far a Kepler scene's exact solution can be from the orbit the
/// integrators are given (the one the doubles `GM` and initial state
/// define): the scene computes it in double-double and rounds it once, by
/// at most half an ulp of each coordinate (its tests check the rounded
/// state against an independent 40-digit computation). In phase-space
/// distance, the largest over 4096 points of a period: about 2e-16 on both
/// orbits, so both judge every target down to 1e-14.
pub fn exact_rounding(scene: &str) -> Option<f64> {
    struct Bound;
    impl SceneVisitor for Bound {
        type Output = Option<f64>;
        fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
            self,
            scene: &S,
        ) -> Option<f64> {
            let mut worst = 0.0f64;
            for k in 0..4096 {
                let s = scene.exact(scene.period() * k as f64 / 4096.0)?;
                worst = worst.max(rounding_distance(scene, &s));
            }
            Some(worst)
        }
    }
    AnyScene::all()
        .into_iter()
        .find(|s| s.meta().id == scene)?
        .visit(Bound)
}

/// The Kepler rows: the cheapest fixed step from the work study's rungs,
/// the own pairs from their tolerance ladders, the peers from the work
/// study, each read off its runs at every target (the work study's own
/// targets stop at 1e-12).
fn kepler_rows(work: &[WorkRecord], pairs: &[(&'static str, RaceLadder)]) -> Vec<RaceRow> {
    let mut rows = Vec::new();
    for scene in KEPLER_SCENES {
        let Some(w) = work.iter().find(|w| w.scene == scene) else {
            continue;
        };
        let peers = kepler_peers(w);
        // the smallest error of any run on the scene: fixed steps, own
        // pairs, peers
        let smallest = w
            .schemes
            .iter()
            .flat_map(|s| s.global.iter().map(|p| p.error))
            .chain(
                pairs
                    .iter()
                    .filter(|(s, _)| *s == scene)
                    .flat_map(|(_, l)| l.points.iter().map(|p| p.error)),
            )
            .chain(peers.iter().flat_map(|l| l.points.iter().map(|p| p.error)))
            .flatten()
            .reduce(f64::min);
        let ladder_reach = |name: &str, target: f64| {
            pairs
                .iter()
                .find(|(s, l)| *s == scene && l.contender == name)
                .map_or(Reach::NotReached, |(_, l)| l.reach(target))
        };
        for target in RACE_TARGETS {
            let schemes: Vec<(&'static str, Reach)> = w
                .schemes
                .iter()
                .map(|s| {
                    let data: Vec<(f64, Option<f64>)> = s
                        .global
                        .iter()
                        .map(|p| (p.evaluations as f64, p.error))
                        .collect();
                    (s.scheme, reach_for_good(&data, target))
                })
                .collect();
            let mut row = kepler_row(
                scene,
                target,
                entry(&schemes),
                |name| ladder_reach(name, target),
                peers.iter().map(|l| l.reach(target)).collect(),
            );
            row.smallest_error = smallest;
            let fixed_runs = w.schemes.iter().map(|s| {
                let data: Vec<(f64, Option<f64>)> = s
                    .global
                    .iter()
                    .map(|p| (p.evaluations as f64, p.error))
                    .collect();
                (s.scheme, data)
            });
            let own_runs = pairs
                .iter()
                .filter(|(s, _)| *s == scene)
                .map(|(_, l)| (l.contender, l.data()));
            let peer_runs = peers.iter().map(|l| (l.contender, l.data()));
            row.unconfirmed = unconfirmed(fixed_runs.chain(own_runs).chain(peer_runs), target);
            rows.push(row);
        }
    }
    rows
}

/// The contenders among `runs` that meet `target` only with the last run of
/// their ladder, and that run's cost.
fn unconfirmed(
    runs: impl IntoIterator<Item = (&'static str, Vec<(f64, Option<f64>)>)>,
    target: f64,
) -> Vec<(&'static str, f64)> {
    runs.into_iter()
        .filter_map(|(name, data)| Some((name, met_only_by_last_run(&data, target)?)))
        .collect()
}

/// A Kepler row, in evaluations or seconds: the fixed step's entry, each
/// own pair's reach by name, each peer's.
fn kepler_row(
    scene: &'static str,
    target: f64,
    fixed: Entry,
    pair: impl Fn(&str) -> Reach,
    peers: Vec<Reach>,
) -> RaceRow {
    let pairs: Vec<(&'static str, Reach)> = OWN_PAIRS
        .iter()
        .map(|p| (p.name(), pair(p.name())))
        .collect();
    RaceRow {
        scene,
        target,
        fixed,
        fixed_searched_to: None,
        pair: entry(&pairs),
        peers,
        smallest_error: None,
        unconfirmed: Vec::new(),
        judged: exact_rounding(scene).is_some_and(|e| e <= REFERENCE_SHARE * target),
    }
}

/// The N-body rows from their records.
fn nbody_rows(records: &[NbodyRecord]) -> Vec<RaceRow> {
    let mut rows = Vec::new();
    for r in records {
        for (i, &target) in RACE_TARGETS.iter().enumerate() {
            let named = |ladders: &[RaceLadder]| -> Vec<(&'static str, Reach)> {
                ladders
                    .iter()
                    .map(|l| (l.contender, l.reach(target)))
                    .collect()
            };
            let pairs: Vec<(&'static str, Reach)> = named(&r.adaptive)[..OWN_PAIRS.len()].to_vec();
            let pair = entry(&pairs);
            // the search stops for a target once no scheme can beat the
            // bound there, the cheapest own pair's cost, so a scheme that
            // reached it only at a cost above that bound (its ladder went
            // on for another target) is not the cheapest fixed step: others
            // were not searched that far. Where no own pair reaches the
            // target, a fixed step that does is the crate's best, and stays
            let fixed = Some(entry(&named(&r.fixed)))
                .filter(|e| {
                    let bound = r.fixed_bounds[i].filter(|_| pair.name.is_some());
                    e.reach
                        .cost()
                        .is_none_or(|c| c < bound.unwrap_or(f64::INFINITY))
                })
                .unwrap_or(Entry {
                    name: None,
                    reach: Reach::NotReached,
                });
            rows.push(RaceRow {
                scene: r.reference.scene,
                target,
                fixed,
                fixed_searched_to: r.fixed_bounds[i].filter(|_| fixed.name.is_none()),
                pair,
                peers: r.adaptive[OWN_PAIRS.len()..]
                    .iter()
                    .map(|l| l.reach(target))
                    .collect(),
                smallest_error: r
                    .adaptive
                    .iter()
                    .chain(&r.fixed)
                    .flat_map(|l| &l.points)
                    .filter_map(|p| p.error)
                    .reduce(f64::min),
                unconfirmed: unconfirmed(
                    r.adaptive
                        .iter()
                        .chain(&r.fixed)
                        .map(|l| (l.contender, l.data())),
                    target,
                ),
                judged: r.reference.judges(target),
            });
        }
    }
    rows
}

struct AdaptiveOn<'a>(&'a NbodyScene, &'a NbodyReference);
impl IntegratorVisitor for AdaptiveOn<'_> {
    type Output = RaceLadder;
    fn visit<I: AdaptiveIntegrator>(self, integrator: &I) -> RaceLadder {
        self.0.visit(AdaptiveOnScene(integrator, self.1))
    }
}

struct AdaptiveOnScene<'a, I>(&'a I, &'a NbodyReference);
impl<I: AdaptiveIntegrator> SceneVisitor for AdaptiveOnScene<'_, I> {
    type Output = RaceLadder;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> RaceLadder {
        adaptive_ladder(self.0, scene, self.1)
    }
}

struct FixedOn<'a>(&'a NbodyScene, &'a NbodyReference, &'a [Option<f64>]);
impl SchemeVisitor for FixedOn<'_> {
    type Output = RaceLadder;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> RaceLadder {
        self.0.visit(FixedOnScene(scheme, self.1, self.2))
    }
}

struct FixedOnScene<'a, M: 'static>(&'static M, &'a NbodyReference, &'a [Option<f64>]);
impl<M: Scheme + Sync + 'static> SceneVisitor for FixedOnScene<'_, M> {
    type Output = RaceLadder;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> RaceLadder {
        fixed_ladder(self.0, scene, self.1, self.2)
    }
}

/// Phase distance between two flat states of a scene.
struct Distance<'a>(&'a [f64], &'a [f64]);
impl SceneVisitor for Distance<'_> {
    type Output = f64;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(self, scene: &S) -> f64 {
        let state = |x: &[f64]| {
            State::<D>::new(
                nalgebra::SVector::from_fn(|i, _| x[i]),
                nalgebra::SVector::from_fn(|i, _| x[D + i]),
            )
        };
        scene.phase_distance(&state(self.0), &state(self.1))
    }
}

/// Every contender on both N-body scenes, on `threads` threads: the
/// references, then the adaptive ladders, then the fixed-step ladders
/// (bounded by the own pairs' costs).
pub fn nbody_study(threads: usize) -> Vec<NbodyRecord> {
    let scenes = NbodyScene::all();
    let references = parallel_map(&scenes, threads, NbodyScene::reference, &|_, _| {});
    let jobs: Vec<(usize, crate::suite::adaptive::Adaptive)> = (0..scenes.len())
        .flat_map(|s| INTEGRATORS.iter().map(move |&i| (s, i)))
        .collect();
    let mut adaptive = parallel_map(
        &jobs,
        threads,
        |&(s, i)| i.visit(AdaptiveOn(&scenes[s], &references[s])),
        &|_, _| {},
    )
    .into_iter();
    let per_scene: Vec<Vec<RaceLadder>> = scenes
        .iter()
        .map(|_| adaptive.by_ref().take(INTEGRATORS.len()).collect())
        .collect();
    let bounds: Vec<Vec<Option<f64>>> = per_scene
        .iter()
        .map(|ladders| {
            let pairs = &ladders[..OWN_PAIRS.len()];
            // where no pair reaches a target, the fixed steps get as much as
            // the pairs spent trying
            let spent = pairs
                .iter()
                .flat_map(|l| &l.points)
                .map(|p| p.evaluations as f64)
                .reduce(f64::max);
            RACE_TARGETS
                .iter()
                .map(|&t| least(pairs.iter().map(|l| l.reach(t).cost())).or(spent))
                .collect()
        })
        .collect();
    let ids = scheme_ids();
    let jobs: Vec<(usize, &'static str)> = (0..scenes.len())
        .flat_map(|s| ids.iter().map(move |&id| (s, id)))
        .collect();
    let mut fixed = parallel_map(
        &jobs,
        threads,
        |&(s, id)| {
            visit_scheme(id, FixedOn(&scenes[s], &references[s], &bounds[s]))
                .expect("catalogue ids")
        },
        &|_, _| {},
    )
    .into_iter();
    scenes
        .iter()
        .zip(references)
        .zip(per_scene)
        .zip(bounds)
        .map(|(((scene, reference), adaptive), fixed_bounds)| {
            // how far apart the adaptive contenders' tightest runs end
            let ends: Vec<&Vec<f64>> = adaptive
                .iter()
                .filter_map(|l| l.last_end.as_ref())
                .collect();
            let mut spread: f64 = 0.0;
            for (k, a) in ends.iter().enumerate() {
                for b in &ends[k + 1..] {
                    spread = spread.max(scene.visit(Distance(a, b)));
                }
            }
            NbodyRecord {
                reference,
                adaptive,
                fixed: fixed.by_ref().take(ids.len()).collect(),
                fixed_bounds,
                spread,
            }
        })
        .collect()
}

/// The race by force evaluations, from the work study, the tolerance
/// ladders and the N-body study.
pub fn race(
    work: &[WorkRecord],
    adaptive: &AdaptiveRecords,
    nbody: Vec<NbodyRecord>,
) -> RaceRecords {
    let kepler_pairs = kepler_pair_ladders(adaptive);
    let mut rows = kepler_rows(work, &kepler_pairs);
    rows.extend(nbody_rows(&nbody));
    let digits = digit_rows(&rows, work, &kepler_pairs, &nbody);
    let ias15 = crate::suite::ias15::rows(&nbody, &rows);
    RaceRecords {
        rows,
        nbody,
        digits,
        ias15,
        pericentre_lag: PericentreLag::measure(&KeplerEccentric::default()),
        kepler_pairs,
    }
}

/// The own pairs' ladders on the Kepler orbits for the race: each pair's
/// tolerance ladder (whose tolerances end a decade or two before the
/// peers') carried on at the rest of [`PEER_TOLERANCES`], each run judged as
/// the ladders judge theirs, so that both sides of the race are read over
/// the same tolerances. A target counts only once a dearer run confirms it
/// ([`crate::suite::reached_for_good`]): over a shorter span a pair would be
/// spared the runs that could take a target back, and denied the one that
/// could confirm its last.
pub fn kepler_pair_ladders(adaptive: &AdaptiveRecords) -> Vec<(&'static str, RaceLadder)> {
    let mut out = Vec::new();
    for scene in KEPLER_SCENES {
        let Some(any) = AnyScene::all().into_iter().find(|s| s.meta().id == scene) else {
            continue;
        };
        for pair in OWN_PAIRS {
            let Some(l) = adaptive
                .ladders
                .iter()
                .find(|l| l.scene == scene && l.integrator == pair.name())
            else {
                continue;
            };
            let mut points: Vec<RacePoint> = l
                .points
                .iter()
                .map(|p| RacePoint {
                    setting: p.tolerance,
                    evaluations: p.evaluations,
                    error: p.error,
                })
                .collect();
            let last = points.last().map_or(f64::INFINITY, |p| p.setting);
            for tol in PEER_TOLERANCES.into_iter().filter(|&t| t < last) {
                points.push(pair.visit(ExactRun(&any, l.t_end, tol)));
            }
            out.push((
                scene,
                RaceLadder {
                    contender: l.integrator,
                    points,
                    last_end: None,
                },
            ));
        }
    }
    out
}

/// One run of an adaptive integrator on a scene with an exact solution,
/// judged as a tolerance ladder judges its runs: the largest phase-space
/// error over the run against the exact solution, where the run reaches
/// its end (a NaN anywhere makes it no measurement).
struct ExactRun<'a>(&'a AnyScene, f64, f64);
impl IntegratorVisitor for ExactRun<'_> {
    type Output = RacePoint;
    fn visit<I: AdaptiveIntegrator>(self, integrator: &I) -> RacePoint {
        self.0.visit(ExactRunOn(integrator, self.1, self.2))
    }
}

struct ExactRunOn<'a, I>(&'a I, f64, f64);
impl<I: AdaptiveIntegrator> SceneVisitor for ExactRunOn<'_, I> {
    type Output = RacePoint;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> RacePoint {
        let (t_end, tol) = (self.1, self.2);
        // a refused request measured nothing, as a run that gave up
        let point = tolerance_point(self.0, scene, t_end, tol).ok();
        RacePoint {
            setting: tol,
            evaluations: point.as_ref().map_or(0, |p| p.evaluations),
            error: point.and_then(|p| p.error),
        }
    }
}

/// What reaching a target costs per correct digit, `evaluations / d` with
/// `d = -log10(target)` the digits the target asks for, read off one
/// contender's runs.
///
/// The interval: the runs are cheapest first, and where the error falls as
/// the cost grows, the cost of the target lies between the last run that
/// missed it and the first that reached it for good (see
/// [`crate::suite::reached_for_good`]); divided by `d`, those bound the
/// figure. Interpolating between them on log-log axes gives the estimate.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DigitCost {
    /// Evaluations per digit, from the interpolated cost.
    pub per_digit: f64,
    /// From the last run that missed the target; `None` when the first run
    /// already reached it (the figure is then at most `high`).
    pub low: Option<f64>,
    /// From the first run that reached it for good.
    pub high: f64,
}

/// A contender's cost per digit at `target`, from its `(evaluations,
/// error)` runs, cheapest first; `None` where the target is not reached for
/// good.
pub fn digit_cost(data: &[(f64, Option<f64>)], target: f64) -> Option<DigitCost> {
    let digits = -target.log10();
    let reach = reach_for_good(data, target);
    let cost = reach.cost()?;
    let runs = deciding_runs(data, target);
    let k = *runs.last()?;
    let low = (runs.len() == 2)
        .then(|| data[runs[0]].0)
        .filter(|_| matches!(reach, Reach::Interpolated(_)));
    Some(DigitCost {
        per_digit: cost / digits,
        low: low.map(|c| c / digits),
        high: data[k].0 / digits,
    })
}

/// One scene and target of the evaluations-per-digit table: the cheapest
/// own pair and every peer.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DigitRow {
    /// Scene id.
    pub scene: &'static str,
    /// The target error.
    pub target: f64,
    /// The reference resolves the target.
    pub judged: bool,
    /// The cheapest own pair at the target, and its cost per digit.
    pub pair: Option<(&'static str, DigitCost)>,
    /// Each peer's, in the order of [`PEERS`].
    pub peers: Vec<Option<DigitCost>>,
}

/// A contender's `(evaluations, error)` runs, cheapest first.
type Runs = Vec<(f64, Option<f64>)>;

/// The evaluations-per-digit rows, one per race row, from the same runs
/// the race reads its costs off.
fn digit_rows(
    rows: &[RaceRow],
    work: &[WorkRecord],
    kepler_pairs: &[(&'static str, RaceLadder)],
    nbody: &[NbodyRecord],
) -> Vec<DigitRow> {
    let points = |l: &RaceLadder| l.data();
    rows.iter()
        .map(|row| {
            // every adaptive contender's runs on the scene, own pairs first
            let runs: Vec<(&'static str, Runs)> =
                if let Some(r) = nbody.iter().find(|r| r.reference.scene == row.scene) {
                    r.adaptive
                        .iter()
                        .map(|l| (l.contender, points(l)))
                        .collect()
                } else {
                    let own = OWN_PAIRS.iter().map(|p| {
                        let data = kepler_pairs
                            .iter()
                            .find(|(s, l)| *s == row.scene && l.contender == p.name())
                            .map(|(_, l)| points(l))
                            .unwrap_or_default();
                        (p.name(), data)
                    });
                    let peers = work
                        .iter()
                        .find(|w| w.scene == row.scene)
                        .map(kepler_peers)
                        .unwrap_or_default()
                        .into_iter()
                        .map(|l| (l.contender, points(&l)));
                    own.chain(peers).collect()
                };
            let (own, peers) = runs.split_at(OWN_PAIRS.len().min(runs.len()));
            let pair = row.pair.name.and_then(|name| {
                let (_, data) = own.iter().find(|(n, _)| *n == name)?;
                Some((name, digit_cost(data, row.target)?))
            });
            DigitRow {
                scene: row.scene,
                target: row.target,
                judged: row.judged,
                pair,
                peers: peers
                    .iter()
                    .map(|(_, data)| digit_cost(data, row.target))
                    .collect(),
            }
        })
        .collect()
}

/// A scene of any dimension that a visitor can be run on.
trait AnyDimension {
    fn visit_scene<V: SceneVisitor>(&self, visitor: V) -> V::Output;
}

impl AnyDimension for NbodyScene {
    fn visit_scene<V: SceneVisitor>(&self, visitor: V) -> V::Output {
        self.visit(visitor)
    }
}

impl AnyDimension for AnyScene {
    fn visit_scene<V: SceneVisitor>(&self, visitor: V) -> V::Output {
        self.visit(visitor)
    }
}

/// The fastest of [`PEER_REPEATS`] runs of an adaptive integrator.
struct TimeAdaptive<'a, A>(&'a A, f64, f64);
impl<A: AnyDimension> IntegratorVisitor for TimeAdaptive<'_, A> {
    type Output = f64;
    fn visit<I: AdaptiveIntegrator>(self, integrator: &I) -> f64 {
        self.0
            .visit_scene(TimeAdaptiveOn(integrator, self.1, self.2))
    }
}

struct TimeAdaptiveOn<'a, I>(&'a I, f64, f64);
impl<I: AdaptiveIntegrator> SceneVisitor for TimeAdaptiveOn<'_, I> {
    type Output = f64;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(self, scene: &S) -> f64 {
        (0..PEER_REPEATS)
            .filter_map(|_| self.0.run(scene, self.1, self.2).ok())
            .map(|r| r.time.as_secs_f64())
            .reduce(f64::min)
            .unwrap_or(f64::NAN)
    }
}

/// The fastest of [`PEER_REPEATS`] fixed-step runs.
struct TimeFixed<'a>(&'a NbodyScene, f64, u64);
impl SchemeVisitor for TimeFixed<'_> {
    type Output = f64;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> f64 {
        self.0.visit(TimeFixedOn(scheme, self.1, self.2))
    }
}

struct TimeFixedOn<M: 'static>(&'static M, f64, u64);
impl<M: Scheme + Sync + 'static> SceneVisitor for TimeFixedOn<M> {
    type Output = f64;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(self, scene: &S) -> f64 {
        let h = self.1 / self.2 as f64;
        (0..PEER_REPEATS)
            .map(|_| {
                time_run(self.0, scene, &scene.initial(), h, self.2)
                    .time
                    .as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// The seconds to reach each target from a ladder, timing with `time` only
/// the runs that decide some target, each once.
fn seconds_to_reach(ladder: &RaceLadder, time: impl Fn(&RacePoint) -> f64) -> Vec<Reach> {
    let mut needed: Vec<usize> = RACE_TARGETS
        .iter()
        .flat_map(|&t| ladder.deciding(t))
        .collect();
    needed.sort_unstable();
    needed.dedup();
    let seconds: Vec<(usize, f64)> = needed
        .into_iter()
        .map(|k| (k, time(&ladder.points[k])))
        .collect();
    RACE_TARGETS
        .iter()
        .map(|&target| {
            let data: Vec<(f64, Option<f64>)> = ladder
                .deciding(target)
                .into_iter()
                .map(|k| {
                    let t = seconds.iter().find(|x| x.0 == k).map_or(f64::NAN, |x| x.1);
                    (t, ladder.points[k].error)
                })
                .collect();
            cost_to_reach(&data, target)
        })
        .collect()
}

/// The race by wall time: on the Kepler orbits the fixed steps from the
/// work study's time-to-target and the own pairs from their ladders' timed
/// runs; everywhere else (the peers on the Kepler orbits, every contender on
/// the N-body scenes) the runs that decide each target are timed here, one
/// at a time, the fastest of [`PEER_REPEATS`] each.
pub fn race_times(
    records: &RaceRecords,
    work: &[WorkRecord],
    timings: &[WorkTiming],
    adaptive: &AdaptiveRecords,
) -> Vec<RaceRow> {
    let mut rows = Vec::new();
    for scene in KEPLER_SCENES {
        let Some(w) = timings.iter().find(|w| w.scene == scene) else {
            continue;
        };
        let any = AnyScene::all().into_iter().find(|s| s.meta().id == scene);
        // the own pairs' runs that decide a target: timed with the ladders
        // where the ladder has the run, timed here where the race carried
        // the ladder on
        let own: Vec<(&'static str, Vec<Reach>)> = records
            .kepler_pairs
            .iter()
            .filter(|(s, _)| *s == scene)
            .filter_map(|(_, l)| {
                let (ladder, seconds) = adaptive
                    .ladders
                    .iter()
                    .zip(&adaptive.point_seconds)
                    .find(|(x, _)| x.scene == scene && x.integrator == l.contender)?;
                let pair = OWN_PAIRS.iter().find(|p| p.name() == l.contender)?;
                let any = any.as_ref()?;
                let reaches = seconds_to_reach(l, |x| {
                    ladder
                        .points
                        .iter()
                        .zip(seconds)
                        .find(|(p, _)| p.tolerance == x.setting)
                        .map_or_else(
                            || pair.visit(TimeAdaptive(any, ladder.t_end, x.setting)),
                            |(_, &t)| t,
                        )
                });
                Some((l.contender, reaches))
            })
            .collect();
        let timed = |name: &str, k: usize| {
            own.iter()
                .find(|(n, _)| *n == name)
                .map_or(Reach::NotReached, |(_, r)| r[k])
        };
        // the peers' runs that decide a target, timed here one at a time
        let peers: Vec<Vec<Reach>> = match (work.iter().find(|w| w.scene == scene), any) {
            (Some(record), Some(any)) => {
                let t_end = record.t_end;
                kepler_peers(record)
                    .iter()
                    .zip(PEERS)
                    .map(|(l, p)| {
                        seconds_to_reach(l, |x| p.visit(TimeAdaptive(&any, t_end, x.setting)))
                    })
                    .collect()
            }
            _ => Vec::new(),
        };
        for (k, target) in RACE_TARGETS.into_iter().enumerate() {
            // a scheme's time is its evaluations at its measured time per
            // evaluation (as in the work study's time to target), read off
            // the same rungs and by the same rule as the race by evaluations
            let fixed = match work.iter().find(|r| r.scene == scene) {
                Some(record) => {
                    let candidates: Vec<(&'static str, Reach)> = record
                        .schemes
                        .iter()
                        .filter_map(|s| {
                            let t = w.schemes.iter().find(|t| t.scheme == s.scheme)?;
                            let data: Vec<(f64, Option<f64>)> = s
                                .global
                                .iter()
                                .map(|p| (p.evaluations as f64, p.error))
                                .collect();
                            let reach = reach_for_good(&data, target);
                            Some((s.scheme, reach.scaled(t.ns_per_evaluation * 1e-9)))
                        })
                        .collect();
                    entry(&candidates)
                }
                None => Entry {
                    name: None,
                    reach: Reach::NotReached,
                },
            };
            rows.push(kepler_row(
                scene,
                target,
                fixed,
                |name| timed(name, k),
                peers.iter().map(|s| s[k]).collect(),
            ));
        }
    }
    for (scene, r) in NbodyScene::all().iter().zip(&records.nbody) {
        let t_end = r.reference.t_end;
        let adaptive: Vec<Vec<Reach>> = r
            .adaptive
            .iter()
            .zip(INTEGRATORS)
            .map(|(l, i)| seconds_to_reach(l, |p| i.visit(TimeAdaptive(scene, t_end, p.setting))))
            .collect();
        let fixed: Vec<Vec<Reach>> = r
            .fixed
            .iter()
            .map(|l| {
                seconds_to_reach(l, |p| {
                    visit_scheme(l.contender, TimeFixed(scene, t_end, p.setting as u64))
                        .expect("catalogue ids")
                })
            })
            .collect();
        for (k, &target) in RACE_TARGETS.iter().enumerate() {
            let named =
                |ladders: &[RaceLadder], seconds: &[Vec<Reach>]| -> Vec<(&'static str, Reach)> {
                    ladders
                        .iter()
                        .zip(seconds)
                        .map(|(l, s)| (l.contender, s[k]))
                        .collect()
                };
            let pairs = OWN_PAIRS.len();
            rows.push(RaceRow {
                scene: r.reference.scene,
                target,
                // only where the race by evaluations found the cheapest
                // fixed step (see `nbody_rows`)
                fixed: records
                    .rows
                    .iter()
                    .find(|x| x.scene == r.reference.scene && x.target == target)
                    .filter(|x| x.fixed.name.is_some())
                    .map_or(
                        Entry {
                            name: None,
                            reach: Reach::NotReached,
                        },
                        |_| entry(&named(&r.fixed, &fixed)),
                    ),
                fixed_searched_to: None,
                pair: entry(&named(&r.adaptive[..pairs], &adaptive[..pairs])),
                peers: adaptive[pairs..].iter().map(|s| s[k]).collect(),
                smallest_error: None,
                unconfirmed: Vec::new(),
                judged: r.reference.judges(target),
            });
        }
    }
    rows
}
