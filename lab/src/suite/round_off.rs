//! The round-off studies of the report, run in parallel: floors against the
//! step on the oscillator and the circular orbit, and long runs of their
//! exactly conserved quantities. Jobs are independent and their results
//! stored by job, so the records do not depend on the thread count.

use stepladder::error::Error;
use stepladder::internals::compensated::{pair_ids, paired_ids};
use stepladder::internals::round_off::floor::{
    PairRecord, RoundoffRecord, RoundoffSpec, assemble, study_pair,
};
use stepladder::internals::round_off::longrun::{LongrunRecord, LongrunSpec, longrun_of};
use stepladder::scene::{AnyScene, Harmonic, KeplerCircular};

/// Every record of the round-off studies.
#[derive(Clone, Debug)]
pub struct RoundoffRecords {
    /// Floors, one record per scene.
    pub floors: Vec<RoundoffRecord>,
    /// Long runs, scene-major, in pair order (plain schemes, then variants).
    pub longrun: Vec<LongrunRecord>,
}

/// The scenes of the floor study and each one's ladder: the finest step is
/// chosen so that every plain scheme is past its floor, within the report's
/// time budget.
pub fn floor_scenes() -> Vec<(AnyScene, RoundoffSpec)> {
    vec![
        (
            AnyScene::Harmonic(Harmonic::default()),
            RoundoffSpec {
                periods: None,
                max_steps: Some(1 << 24),
            },
        ),
        (
            AnyScene::KeplerCircular(KeplerCircular),
            RoundoffSpec {
                periods: None,
                max_steps: Some(1 << 22),
            },
        ),
    ]
}

/// The scenes of the long runs.
pub fn longrun_scenes() -> Vec<AnyScene> {
    vec![
        AnyScene::Harmonic(Harmonic::default()),
        AnyScene::KeplerCircular(KeplerCircular),
    ]
}

enum Job {
    Floor(usize, &'static str),
    Long(usize, &'static str),
}

enum Done {
    Floor(Result<PairRecord, Error>),
    Long(Result<LongrunRecord, Error>),
}

/// Runs every round-off study of the report on `threads` threads.
pub fn run_roundoff_suite(threads: usize) -> Result<RoundoffRecords, Error> {
    let floors = floor_scenes();
    let longs = longrun_scenes();
    let mut jobs: Vec<Job> = Vec::new();
    // the floor ladders are the longest jobs: first, so the long runs fill in
    for (i, _) in floors.iter().enumerate() {
        jobs.extend(paired_ids().into_iter().map(|id| Job::Floor(i, id)));
    }
    for (i, _) in longs.iter().enumerate() {
        jobs.extend(pair_ids().into_iter().map(|id| Job::Long(i, id)));
    }
    let results = stepladder::internals::parallel::parallel_map(
        &jobs,
        threads,
        |job| match *job {
            Job::Floor(s, id) => Done::Floor(study_pair(&floors[s].0, id, &floors[s].1)),
            Job::Long(s, id) => Done::Long(longrun_of(&longs[s], id, &LongrunSpec::default())),
        },
        &|_, _| {},
    );
    let mut pairs: Vec<Vec<PairRecord>> = floors.iter().map(|_| Vec::new()).collect();
    let mut longrun = Vec::new();
    for (job, done) in jobs.iter().zip(results) {
        match (job, done) {
            (Job::Floor(s, _), Done::Floor(r)) => pairs[*s].push(r?),
            (Job::Long(_, _), Done::Long(r)) => longrun.push(r?),
            _ => unreachable!("every job ran and produced its own kind of record"),
        }
    }
    let floors = floors
        .iter()
        .zip(pairs)
        .map(|((scene, spec), p)| assemble(scene, spec, p))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(RoundoffRecords { floors, longrun })
}
