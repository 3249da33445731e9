//! The full suite: every study on every catalogue scheme and built-in scene.
//! Cases run in parallel on scoped threads, but results are stored by case,
//! so the records are the same whatever the thread count.

use crate::case::{Case, case};
use stepladder::error::Error;

pub mod adaptive;
pub mod dd_reference;
pub mod hard_cases;
pub mod ias15;
pub mod pericentre_lag;
pub mod race;
pub mod reached_for_good;
pub mod round_off;
pub mod work_precision;

use crate::suite::hard_cases::{HardCases, hard_jobs, run_hard_jobs};
use std::time::{Duration, Instant};
use stepladder::internals::accuracy::order::{OrderRecord, OrderSpec};
use stepladder::internals::accuracy::phase::{PhaseRecord, phase_error};
use stepladder::internals::accuracy::scene_check::{SceneCheck, check_scene};
use stepladder::internals::accuracy::trajectory::{TrajectoryRecord, earth_sun_experiments};
use stepladder::internals::geometry::energy::{EnergyRecord, EnergySpec};
use stepladder::internals::geometry::reverse::{ReverseRecord, ReverseSpec};
use stepladder::internals::geometry::symplectic::{SymplecticRecord, SymplecticSpec};
use stepladder::internals::parallel::parallel_map;
use stepladder::internals::stability::{StabilityRecord, stability};
use stepladder::scene::{AnyScene, Scene, SceneVisitor};
use stepladder::scheme::{Scheme, SchemeVisitor, scheme_ids, visit_scheme};
use stepladder::study::Verdict;

/// Every record of one scheme on one scene.
#[derive(Clone, Debug)]
pub struct CaseRecords {
    /// Global order.
    pub order: OrderRecord,
    /// Global order with the exact solution withheld: the twin of `order`,
    /// measured against half-step runs.
    pub hidden_order: OrderRecord,
    /// Energy over a long run.
    pub energy: EnergyRecord,
    /// Tangent map.
    pub symplectic: SymplecticRecord,
    /// Forward and back.
    pub reverse: ReverseRecord,
    /// Wall time of the case's studies (machine-dependent).
    pub time: Duration,
}

/// Every record of a suite run.
#[derive(Clone, Debug)]
pub struct SuiteRecords {
    /// One entry per scheme and scene, catalogue-major, scene-minor.
    pub cases: Vec<CaseRecords>,
    /// Phase error on the oscillator, one per scheme.
    pub phase: Vec<PhaseRecord>,
    /// Linear stability on the oscillator, one per scheme.
    pub stability: Vec<StabilityRecord>,
    /// The check of every scene.
    pub scenes: Vec<SceneCheck>,
    /// The course notes' Earth-Sun experiments (Euler and velocity Verlet).
    pub earth_sun: Vec<TrajectoryRecord>,
    /// Round-off floors and long runs of the Verlet forms and their
    /// compensated variants.
    pub roundoff: crate::suite::round_off::RoundoffRecords,
    /// The hard cases: eccentric orbits, the separatrix, escape or trapped.
    pub hard: HardCases,
    /// The verdict corpus: schemes and scenes outside the catalogue, each
    /// judged against the verdicts it must get.
    pub corpus: Vec<crate::corpus::Outcome>,
    /// The work-precision study, one record per scene.
    pub work: Vec<crate::suite::work_precision::WorkRecord>,
    /// Its wall times, one per scene (machine-dependent).
    pub work_timing: Vec<crate::suite::work_precision::WorkTiming>,
    /// Every scheme's cost of a step against the hand-written floor
    /// (machine-dependent).
    pub speed: stepladder::internals::cost::step_time::SpeedRecord,
    /// The tolerance ladders of the adaptive integrators.
    pub adaptive: crate::suite::adaptive::AdaptiveRecords,
    /// The race of the crate's best against the peers, by force
    /// evaluations, on the Kepler orbits and the N-body scenes.
    pub race: crate::suite::race::RaceRecords,
    /// The same race by wall time (machine-dependent).
    pub race_timing: Vec<crate::suite::race::RaceRow>,
    /// Wall time of each part of the suite, in the order they ran (the
    /// budget of the report command is read off these).
    pub parts: Vec<(&'static str, Duration)>,
    /// Wall time of the whole suite.
    pub total: Duration,
    /// Threads used.
    pub threads: usize,
}

impl SuiteRecords {
    /// The order records, in case order.
    pub fn order(&self) -> Vec<&OrderRecord> {
        self.cases.iter().map(|c| &c.order).collect()
    }

    /// `(passed, total)` over every verdict of the suite (phase records
    /// without an analytic value have none).
    pub fn verdicts(&self) -> (usize, usize) {
        let mut all: Vec<Verdict> = Vec::new();
        for c in &self.cases {
            all.extend([
                c.order.verdict,
                c.energy.verdict,
                c.symplectic.verdict,
                c.reverse.verdict,
            ]);
        }
        all.extend(self.phase.iter().filter_map(|p| p.verdict));
        all.extend(self.scenes.iter().map(|s| s.verdict));
        (
            all.iter().filter(|v| **v == Verdict::Pass).count(),
            all.len(),
        )
    }
}

/// Every catalogue scheme bound to every built-in scene.
pub fn all_cases() -> Vec<Box<dyn Case>> {
    let scenes = AnyScene::all();
    scheme_ids()
        .into_iter()
        .flat_map(|id| {
            scenes
                .iter()
                .map(move |s| case(id, s).expect("catalogue ids are valid"))
        })
        .collect()
}

/// Runs every study of one case with default settings.
pub fn run_case(c: &dyn Case) -> Result<CaseRecords, Error> {
    let t = Instant::now();
    Ok(CaseRecords {
        order: c.order(&OrderSpec::default())?,
        hidden_order: c.hidden_order(&OrderSpec::default())?,
        energy: c.energy(&EnergySpec::default())?,
        symplectic: c.symplectic(&SymplecticSpec::default())?,
        reverse: c.reverse(&ReverseSpec::default())?,
        time: t.elapsed(),
    })
}

/// Where a suite run has got to, for a progress display: the part running,
/// how many of its items are done, of how many, and the last one finished.
#[derive(Clone, Copy, Debug)]
pub struct Progress<'a> {
    /// The part of the suite: "cases", "hard cases", "corpus", ...
    pub part: &'static str,
    /// Items of the part finished so far.
    pub done: usize,
    /// Items of the part.
    pub total: usize,
    /// The item that just finished (empty when a part starts).
    pub item: &'a str,
}

/// Runs the suite on `threads` threads (at least one), calling `progress`
/// as each part starts and as each case or corpus entry finishes.
pub fn run_suite(
    threads: usize,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<SuiteRecords, Error> {
    let cases = all_cases();
    let start = Instant::now();
    let mut parts = Vec::new();
    let mut lap = Instant::now();
    let mut part_done = |part: &'static str| {
        parts.push((part, lap.elapsed()));
        lap = Instant::now();
    };
    let threads = threads.clamp(1, cases.len().max(1));
    let total = cases.len();
    let cases = parallel_map(&cases, threads, |c| run_case(c.as_ref()), &|done, c| {
        let item = format!("{} on {}", c.scheme().id, c.scene().id);
        progress(Progress {
            part: "cases",
            done,
            total,
            item: &item,
        })
    })
    .into_iter()
    .collect::<Result<Vec<_>, Error>>()?;
    let (phase, stability) = scheme_ids()
        .into_iter()
        .map(|id| visit_scheme(id, SchemeStudies).expect("catalogue ids are valid"))
        .unzip();
    let scenes = AnyScene::all().iter().map(|s| s.visit(CheckOf)).collect();
    part_done("cases, phase, stability and scene checks");
    let starting = |part| {
        progress(Progress {
            part,
            done: 0,
            total: 1,
            item: "",
        })
    };
    starting("hard cases");
    let hard = run_hard_jobs(hard_jobs(), threads)?;
    part_done("hard cases");
    let entries = crate::corpus::entries();
    let corpus = crate::corpus::judge_all(&entries, threads, &|done, e| {
        let item = format!("{} on {}", e.case.scheme().id, e.case.scene().id);
        progress(Progress {
            part: "verdict corpus",
            done,
            total: entries.len(),
            item: &item,
        })
    })?;
    part_done("verdict corpus");
    starting("round-off floors");
    let mut roundoff = crate::suite::round_off::run_roundoff_suite(threads)?;
    part_done("round-off floors and long runs");
    starting("Brouwer's law");
    roundoff.brouwer = crate::suite::round_off::brouwer_runs(threads)?;
    part_done("Brouwer's law (a million steps, plain and compensated)");
    starting("speed against error");
    let (work, work_timing, speed) = speed_against_error(&cases, threads);
    part_done("speed against error");
    starting("adaptive step control");
    let adaptive = crate::suite::adaptive::adaptive_study(threads)?;
    part_done("adaptive step control");
    starting("the race against the peers");
    let nbody = crate::suite::race::nbody_study(threads);
    let race = crate::suite::race::race(&work, &adaptive, nbody);
    let race_timing = crate::suite::race::race_times(&race, &work, &work_timing, &adaptive);
    part_done("the race against the peers");
    Ok(SuiteRecords {
        cases,
        phase,
        stability,
        scenes,
        earth_sun: earth_sun_experiments(),
        roundoff,
        hard,
        corpus,
        work,
        work_timing,
        speed,
        adaptive,
        race,
        race_timing,
        parts,
        total: start.elapsed(),
        threads,
    })
}

/// The work-precision study on every scene from the cases' order records,
/// then the cost of a step against the floor.
fn speed_against_error(
    cases: &[CaseRecords],
    threads: usize,
) -> (
    Vec<crate::suite::work_precision::WorkRecord>,
    Vec<crate::suite::work_precision::WorkTiming>,
    stepladder::internals::cost::step_time::SpeedRecord,
) {
    let scenes = AnyScene::all();
    let orders: Vec<Vec<&OrderRecord>> = scenes
        .iter()
        .map(|s| {
            let id = s.meta().id;
            cases
                .iter()
                .map(|c| &c.order)
                .filter(|o| o.scene == id)
                .collect()
        })
        .collect();
    let (work, timing) = crate::suite::work_precision::work_study(&scenes, &orders, threads);
    let speed = stepladder::internals::cost::step_time::speed(
        stepladder::internals::cost::step_time::SPEED_STEPS,
        stepladder::internals::cost::step_time::SPEED_REPEATS,
    );
    (work, timing, speed)
}

/// The studies of a scheme alone, on the oscillator.
struct SchemeStudies;
impl SchemeVisitor for SchemeStudies {
    type Output = (PhaseRecord, StabilityRecord);
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        (phase_error(scheme), stability(scheme))
    }
}

struct CheckOf;
impl SceneVisitor for CheckOf {
    type Output = SceneCheck;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> SceneCheck {
        check_scene(scene)
    }
}
