//! IAS15, the reference integrator of N-body work, as a reference row of
//! the race: measured by REBOUND itself (`lab/ias15/ias15.py`, run outside
//! the crate's build, its output committed as `lab/ias15/ias15.json`), on
//! the same initial states and end times as the race's N-body scenes, and
//! judged here against the same references as every contender.
//!
//! Only the N-body scenes: on the Kepler orbits the race's error is the
//! largest over every step of a run, which the committed end states do not
//! give.

use crate::suite::race::{
    DigitCost, NbodyRecord, NbodyScene, RACE_TARGETS, RaceLadder, RacePoint, RaceRow, digit_cost,
};
use serde::{Deserialize, Serialize};
use stepladder::internals::cost::work_points::Reach;
use stepladder::scene::Scene;
use stepladder::state::State;

/// REBOUND's output, committed.
const RUNS: &str = include_str!("../../ias15/ias15.json");

/// One IAS15 run as REBOUND reported it: physical coordinates, body by body.
#[derive(Clone, Debug, Deserialize)]
struct Run {
    epsilon: f64,
    t: f64,
    evaluations: u64,
    positions: Vec<Vec<f64>>,
    velocities: Vec<Vec<f64>>,
}

#[derive(Clone, Debug, Deserialize)]
struct Runs {
    rebound: String,
    command: String,
    pleiades: Vec<Run>,
    #[serde(rename = "outer-solar-system")]
    outer_solar_system: Vec<Run>,
}

fn runs() -> Runs {
    serde_json::from_str(RUNS).expect("the committed IAS15 runs parse")
}

/// The REBOUND version and the command that made the runs.
pub fn provenance() -> (String, String) {
    let r = runs();
    (r.rebound, r.command)
}

/// One scene and target of the IAS15 row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Ias15Row {
    /// Scene id.
    pub scene: &'static str,
    /// The target error.
    pub target: f64,
    /// The reference resolves the target.
    pub judged: bool,
    /// IAS15's evaluations to reach it, read off its runs.
    pub reach: Reach,
    /// Per correct digit.
    pub digits: Option<DigitCost>,
    /// The crate's best evaluations at the target (the race row's).
    pub best: Option<f64>,
}

/// A run's end state, physical coordinates body by body, as a state.
fn physical<const D: usize>(run: &Run) -> Option<State<D>> {
    let k = run.positions.first()?.len();
    let flat = |x: &[Vec<f64>]| -> Option<Vec<f64>> {
        let v: Vec<f64> = x.iter().flatten().copied().collect();
        (v.len() == D && x.iter().all(|b| b.len() == k)).then_some(v)
    };
    let (q, v) = (flat(&run.positions)?, flat(&run.velocities)?);
    Some(State::new(
        nalgebra::SVector::from_fn(|i, _| q[i]),
        nalgebra::SVector::from_fn(|i, _| v[i]),
    ))
}

/// The state of `x` (`q` then `v`).
fn state<const D: usize>(x: &[f64]) -> State<D> {
    State::new(
        nalgebra::SVector::from_fn(|i, _| x[i]),
        nalgebra::SVector::from_fn(|i, _| x[D + i]),
    )
}

/// A run's distance to the reference state: its end state mass-weighted
/// like the scene's; `None` for a run that does not describe the scene.
fn distance(scene: &NbodyScene, run: &Run, reference: &[f64]) -> Option<f64> {
    match scene {
        NbodyScene::Pleiades(s) => {
            Some(s.phase_distance(&s.mass_weighted(&physical::<14>(run)?), &state(reference)))
        }
        NbodyScene::OuterSolarSystem(s) => {
            Some(s.phase_distance(&s.mass_weighted(&physical::<18>(run)?), &state(reference)))
        }
    }
}

/// IAS15's runs on one scene as a race ladder (loosest `epsilon` first),
/// each judged by its distance to the scene's reference; a run that did
/// not end at the reference's time counts as failed.
pub fn ladder(scene: &NbodyScene, record: &NbodyRecord) -> RaceLadder {
    let all = runs();
    let list = match scene {
        NbodyScene::Pleiades(_) => all.pleiades,
        NbodyScene::OuterSolarSystem(_) => all.outer_solar_system,
    };
    let points = list
        .iter()
        .map(|run| {
            let error = (run.t == record.reference.t_end)
                .then(|| distance(scene, run, &record.reference.state))
                .flatten()
                .filter(|e| e.is_finite());
            RacePoint {
                setting: run.epsilon,
                evaluations: run.evaluations,
                error,
            }
        })
        .collect();
    RaceLadder {
        contender: "IAS15 (REBOUND)",
        points,
        last_end: None,
    }
}

/// The IAS15 rows beside the race's N-body rows.
pub fn rows(records: &[NbodyRecord], race: &[RaceRow]) -> Vec<Ias15Row> {
    let mut out = Vec::new();
    for (scene, record) in NbodyScene::all().iter().zip(records) {
        let l = ladder(scene, record);
        let data: Vec<(f64, Option<f64>)> = l
            .points
            .iter()
            .map(|p| (p.evaluations as f64, p.error))
            .collect();
        for target in RACE_TARGETS {
            let best = race
                .iter()
                .find(|r| r.scene == record.reference.scene && r.target == target)
                .and_then(RaceRow::best);
            out.push(Ias15Row {
                scene: record.reference.scene,
                target,
                judged: record.reference.judges(target),
                reach: l.reach(target),
                digits: digit_cost(&data, target),
                best,
            });
        }
    }
    out
}
