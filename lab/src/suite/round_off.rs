//! The round-off studies of the report, run in parallel: floors against the
//! step on the oscillator and the circular orbit, long runs of their
//! exactly conserved quantities, and, as a part of its own so that the
//! report's timings show its cost, Brouwer's law on the outer solar
//! system. Jobs are independent and their results stored by job, so the
//! records do not depend on the thread count.

use stepladder::error::Error;
use stepladder::internals::compensated::{pair_ids, paired_ids};
use stepladder::internals::round_off::floor::{
    PairRecord, RoundoffRecord, RoundoffSpec, assemble, study_pair,
};
use stepladder::internals::round_off::longrun::{LongrunRecord, LongrunSpec, longrun_of};
use stepladder::scene::{AnyScene, Harmonic, KeplerCircular, OuterSolarSystem};
use stepladder::scheme::{Compensated, DPRKN8};
use stepladder::study::{RoundOffRecord, RoundOffSpec, round_off_growth};

/// Every record of the round-off studies.
#[derive(Clone, Debug)]
pub struct RoundoffRecords {
    /// Floors, one record per scene.
    pub floors: Vec<RoundoffRecord>,
    /// Long runs, scene-major, in pair order (plain schemes, then variants).
    pub longrun: Vec<LongrunRecord>,
    /// Brouwer's law on the outer solar system: DPRKN8 plain, then with
    /// compensated sums ([`brouwer_runs`]).
    pub brouwer: Vec<BrouwerRun>,
}

/// One integrator's million-step runs and the verdict on "round-off
/// optimal".
#[derive(Clone, Debug)]
pub struct BrouwerRun {
    /// The scheme sums its coordinates with compensation.
    pub compensated: bool,
    /// The study's record.
    pub record: RoundOffRecord,
}

/// The fixed-step DPRKN8 with compensated sums: the same map as [`DPRKN8`],
/// its coordinates carried with their low parts.
pub const DPRKN8_FIXED_COMPENSATED: Compensated<stepladder::scheme::NystromTable<9>> =
    Compensated {
        meta: DPRKN8.meta,
        plain: DPRKN8,
    };

/// Runs DPRKN8, plain or compensated, for a million steps on the outer
/// solar system, its runs on one thread (the suite runs the two in
/// parallel, [`brouwer_runs`]).
pub fn brouwer_run(compensated: bool) -> Result<BrouwerRun, Error> {
    let spec = RoundOffSpec {
        threads: Some(1),
        ..RoundOffSpec::default()
    };
    let scene = OuterSolarSystem::new();
    let record = if compensated {
        round_off_growth(&DPRKN8_FIXED_COMPENSATED, &scene, &spec)?
    } else {
        round_off_growth(&DPRKN8, &scene, &spec)?
    };
    Ok(BrouwerRun {
        compensated,
        record,
    })
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

/// Brouwer's law for DPRKN8 plain, then compensated, the two on `threads`
/// threads.
pub fn brouwer_runs(threads: usize) -> Result<Vec<BrouwerRun>, Error> {
    stepladder::internals::parallel::parallel_map(
        &[false, true],
        threads,
        |c| brouwer_run(*c),
        &|_, _| {},
    )
    .into_iter()
    .collect()
}

enum Job {
    Floor(usize, &'static str),
    Long(usize, &'static str),
}

enum Done {
    Floor(Result<PairRecord, Error>),
    Long(Result<LongrunRecord, Error>),
}

/// Runs the floors and long runs of the report on `threads` threads, with
/// Brouwer's law ([`brouwer_runs`]) left to the caller.
pub fn run_roundoff_suite(threads: usize) -> Result<RoundoffRecords, Error> {
    let floors = floor_scenes();
    let longs = longrun_scenes();
    // the floor ladders are the longest jobs: first, so the long runs fill in
    let mut jobs: Vec<Job> = Vec::new();
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
    Ok(RoundoffRecords {
        floors,
        longrun,
        brouwer: Vec::new(),
    })
}
