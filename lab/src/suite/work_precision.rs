//! The work-precision study over the catalogue and the built-in scenes:
//! for each scene, every scheme's cost of reaching each target error (from
//! [`stepladder::study::cost::work_points`]), the `ode_solvers` peer beside them
//! ([`crate::peer`]), the cheapest scheme per target, and, apart
//! from these deterministic records, the wall time it all takes here.

use crate::peer::{PeerTimes, PeerWork, peer_work};
use serde::Serialize;
use std::time::Duration;
use stepladder::error::Error;
use stepladder::parallel::parallel_map;
use stepladder::scene::{AnyScene, Scene, SceneVisitor};
use stepladder::scheme::{Scheme, SchemeVisitor, scheme_ids, visit_scheme};
use stepladder::study::accuracy::order::{OrderRecord, OrderSpec};
use stepladder::study::case::case;
use stepladder::study::cost::step_time::{SPEED_STEP, time_run};
use stepladder::study::cost::work_points::{
    ENERGY_PERIODS, Reach, SchemeWork, TARGETS, TargetCost, cheapest, cost_to_reach, scheme_work,
};

/// Steps of one timed run of a scheme on a scene, for its time per force
/// evaluation.
pub const WORK_TIMING_STEPS: u64 = 4_000;

/// Timed runs per scheme and scene; the minimum is kept.
pub const WORK_TIMING_REPEATS: usize = 5;

/// Timed runs of the peer per tolerance; the minimum is kept.
pub const PEER_REPEATS: usize = 3;

/// The cheapest catalogue scheme at one target error, with the peer beside.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Cheapest {
    /// The target error.
    pub target: f64,
    /// The cheapest scheme, if any reaches the target.
    pub scheme: Option<&'static str>,
    /// Its cost.
    pub reach: Reach,
    /// The peer's cost of the same target.
    pub peer: Reach,
}

/// The work-precision study on one scene (deterministic: costs are force
/// evaluations).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WorkRecord {
    /// Scene id.
    pub scene: &'static str,
    /// Its parameters.
    pub scene_parameters: String,
    /// End time of the global-error runs (the order study's).
    pub t_end: f64,
    /// Length of the energy runs, in periods.
    pub energy_periods: f64,
    /// The target errors.
    pub targets: Vec<f64>,
    /// Every scheme, in catalogue order.
    pub schemes: Vec<SchemeWork>,
    /// The peer (`None` only for a scene it cannot run).
    pub peer: Option<PeerWork>,
    /// The cheapest scheme per target global error.
    pub cheapest_global: Vec<Cheapest>,
    /// The cheapest scheme per target energy error.
    pub cheapest_energy: Vec<Cheapest>,
}

/// Wall time of one scheme's steps on one scene (machine-dependent).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SchemeTiming {
    /// Scheme id.
    pub scheme: &'static str,
    /// Nanoseconds per step, the minimum over the repeats.
    pub ns_per_step: f64,
    /// Nanoseconds per force evaluation.
    pub ns_per_evaluation: f64,
}

/// The fastest catalogue scheme at one target error, with the peer beside.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Fastest {
    /// The target error.
    pub target: f64,
    /// The fastest scheme, if any reaches the target.
    pub scheme: Option<&'static str>,
    /// Its time, in seconds.
    pub seconds: Reach,
    /// The peer's time for the same target, in seconds.
    pub peer_seconds: Reach,
}

/// The work-precision study's wall times on one scene (machine-dependent).
/// A scheme's time for a run is its force evaluations times its measured
/// time per evaluation on the scene; the peer's runs are timed directly.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WorkTiming {
    /// Scene id.
    pub scene: &'static str,
    /// Every scheme, in catalogue order.
    pub schemes: Vec<SchemeTiming>,
    /// The peer's run times.
    pub peer: PeerTimes,
    /// The fastest scheme per target global error.
    pub fastest_global: Vec<Fastest>,
    /// The fastest scheme per target energy error.
    pub fastest_energy: Vec<Fastest>,
}

/// One piece of the study: a scheme on a scene, or the peer on a scene.
enum Job<'a> {
    Scheme(&'a AnyScene, &'a OrderRecord),
    Peer(&'a AnyScene),
}

enum Done {
    Scheme(SchemeWork),
    Peer(Option<(PeerWork, PeerTimes)>),
}

struct SchemeOnScene<'a>(&'a AnyScene, &'a OrderRecord);
impl SchemeVisitor for SchemeOnScene<'_> {
    type Output = SchemeWork;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> SchemeWork {
        self.0.visit(WorkOf(scheme, self.1))
    }
}

struct WorkOf<'a, M: 'static>(&'static M, &'a OrderRecord);
impl<M: Scheme + Sync + 'static> SceneVisitor for WorkOf<'_, M> {
    type Output = SchemeWork;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> SchemeWork {
        scheme_work(self.0, scene, self.1)
    }
}

struct PeerOn {
    t_end: f64,
}
impl SceneVisitor for PeerOn {
    type Output = Option<(PeerWork, PeerTimes)>;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> Self::Output {
        peer_work(scene, self.t_end, ENERGY_PERIODS, PEER_REPEATS)
    }
}

/// Times one scheme on one scene once: `(time, force evaluations)`.
struct TimeOn<'a>(&'a AnyScene);
impl SchemeVisitor for TimeOn<'_> {
    type Output = (Duration, u64);
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> (Duration, u64) {
        self.0.visit(TimeScheme(scheme))
    }
}

struct TimeScheme<M: 'static>(&'static M);
impl<M: Scheme + Sync + 'static> SceneVisitor for TimeScheme<M> {
    type Output = (Duration, u64);
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> (Duration, u64) {
        let h = SPEED_STEP * scene.period();
        let run = time_run(self.0, scene, &scene.initial(), h, WORK_TIMING_STEPS);
        (run.time, run.evaluations)
    }
}

/// Every scheme's time per step and per evaluation on `scene`: rounds that
/// each time every scheme once, the minimum kept.
pub fn scheme_timings(scene: &AnyScene) -> Vec<SchemeTiming> {
    let ids = scheme_ids();
    let mut best = vec![(Duration::MAX, 1u64); ids.len()];
    for _ in 0..WORK_TIMING_REPEATS {
        for (slot, id) in best.iter_mut().zip(&ids) {
            let run = visit_scheme(id, TimeOn(scene)).expect("catalogue ids");
            if run.0 < slot.0 {
                *slot = run;
            }
        }
    }
    ids.iter()
        .zip(best)
        .map(|(id, (time, evaluations))| {
            let ns = time.as_secs_f64() * 1e9;
            SchemeTiming {
                scheme: id,
                ns_per_step: ns / WORK_TIMING_STEPS as f64,
                ns_per_evaluation: ns / evaluations.max(1) as f64,
            }
        })
        .collect()
}

/// The cheapest scheme at each target, from per-scheme target costs, with
/// the peer's beside.
pub fn cheapest_per_target(
    schemes: &[(&'static str, &[TargetCost])],
    peer: Option<&[TargetCost]>,
) -> Vec<Cheapest> {
    TARGETS
        .iter()
        .enumerate()
        .map(|(i, &target)| {
            let candidates: Vec<(&'static str, Reach)> = schemes
                .iter()
                .map(|(id, t)| (*id, t.get(i).map_or(Reach::NotReached, |c| c.reach)))
                .collect();
            let best = cheapest(&candidates);
            Cheapest {
                target,
                scheme: best.map(|b| b.0),
                reach: best.map_or(Reach::NotReached, |b| b.1),
                peer: peer
                    .and_then(|p| p.get(i))
                    .map_or(Reach::NotReached, |c| c.reach),
            }
        })
        .collect()
}

/// The deterministic record of one scene from its schemes' and peer's work.
fn record(
    scene: &AnyScene,
    t_end: f64,
    schemes: Vec<SchemeWork>,
    peer: Option<PeerWork>,
) -> WorkRecord {
    let global: Vec<(&'static str, &[TargetCost])> = schemes
        .iter()
        .map(|s| (s.scheme, s.global_targets.as_slice()))
        .collect();
    let energy: Vec<(&'static str, &[TargetCost])> = schemes
        .iter()
        .map(|s| (s.scheme, s.energy_targets.as_slice()))
        .collect();
    let cheapest_global =
        cheapest_per_target(&global, peer.as_ref().map(|p| p.global_targets.as_slice()));
    let cheapest_energy =
        cheapest_per_target(&energy, peer.as_ref().map(|p| p.energy_targets.as_slice()));
    let meta = scene.meta();
    WorkRecord {
        scene: meta.id,
        scene_parameters: meta.parameters,
        t_end,
        energy_periods: ENERGY_PERIODS,
        targets: TARGETS.to_vec(),
        schemes,
        peer,
        cheapest_global,
        cheapest_energy,
    }
}

/// The fastest scheme at each target, and the peer's time beside: times
/// are evaluations times the scheme's time per evaluation; the peer's are
/// interpolated between its timed runs.
fn timing(record: &WorkRecord, schemes: Vec<SchemeTiming>, peer: PeerTimes) -> WorkTiming {
    let fastest = |targets: &dyn Fn(&SchemeWork) -> &[TargetCost],
                   peer_points: Option<Vec<(f64, Option<f64>)>>| {
        TARGETS
            .iter()
            .enumerate()
            .map(|(i, &target)| {
                let candidates: Vec<(&'static str, Reach)> = record
                    .schemes
                    .iter()
                    .zip(&schemes)
                    .map(|(w, t)| {
                        let reach = targets(w).get(i).map_or(Reach::NotReached, |c| c.reach);
                        (w.scheme, reach.scaled(t.ns_per_evaluation * 1e-9))
                    })
                    .collect();
                let best = cheapest(&candidates);
                Fastest {
                    target,
                    scheme: best.map(|b| b.0),
                    seconds: best.map_or(Reach::NotReached, |b| b.1),
                    peer_seconds: peer_points
                        .as_ref()
                        .map_or(Reach::NotReached, |p| cost_to_reach(p, target)),
                }
            })
            .collect()
    };
    let peer_points = |points: Option<&Vec<crate::peer::PeerPoint>>, times: &[f64]| {
        points.map(|p| {
            p.iter()
                .zip(times)
                .map(|(p, &t)| (t, p.error))
                .collect::<Vec<_>>()
        })
    };
    let fastest_global = fastest(
        &|w| w.global_targets.as_slice(),
        peer_points(record.peer.as_ref().map(|p| &p.global), &peer.global),
    );
    let fastest_energy = fastest(
        &|w| w.energy_targets.as_slice(),
        peer_points(record.peer.as_ref().map(|p| &p.energy), &peer.energy),
    );
    WorkTiming {
        scene: record.scene,
        schemes,
        peer,
        fastest_global,
        fastest_energy,
    }
}

/// The work study on `scenes`, given every scheme's order record on each
/// (`orders[i]` for `scenes[i]`, in catalogue order): the schemes' and the
/// peer's runs in parallel on `threads` threads, then the timings one at a
/// time, so that they do not compete for the machine.
pub fn work_study(
    scenes: &[AnyScene],
    orders: &[Vec<&OrderRecord>],
    threads: usize,
) -> (Vec<WorkRecord>, Vec<WorkTiming>) {
    let ids = scheme_ids();
    let mut jobs: Vec<Job> = Vec::new();
    for (scene, records) in scenes.iter().zip(orders) {
        jobs.push(Job::Peer(scene));
        for r in records {
            jobs.push(Job::Scheme(scene, r));
        }
    }
    let mut done = parallel_map(
        &jobs,
        threads,
        |job| match job {
            Job::Scheme(scene, r) => Done::Scheme(
                visit_scheme(r.scheme, SchemeOnScene(scene, r)).expect("catalogue ids"),
            ),
            Job::Peer(scene) => {
                let t_end = scene.visit(DefaultEnd);
                Done::Peer(scene.visit(PeerOn { t_end }))
            }
        },
        &|_, _| {},
    )
    .into_iter();
    let mut records = Vec::new();
    let mut timings = Vec::new();
    for (scene, r) in scenes.iter().zip(orders) {
        let peer = match done.next() {
            Some(Done::Peer(p)) => p,
            _ => unreachable!("jobs are in order"),
        };
        let schemes: Vec<SchemeWork> = (0..r.len())
            .map(|_| match done.next() {
                Some(Done::Scheme(w)) => w,
                _ => unreachable!("jobs are in order"),
            })
            .collect();
        debug_assert!(schemes.iter().zip(&ids).all(|(w, id)| w.scheme == *id));
        let (peer_work, peer_times) = peer.unzip();
        // the work points are over the scene's default t_end, whatever the
        // order study settled on (see `scheme_work`)
        let t_end = scene.visit(DefaultEnd);
        let rec = record(scene, t_end, schemes, peer_work);
        timings.push(timing(
            &rec,
            scheme_timings(scene),
            peer_times.unwrap_or_default(),
        ));
        records.push(rec);
    }
    (records, timings)
}

struct DefaultEnd;
impl SceneVisitor for DefaultEnd {
    type Output = f64;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(self, s: &S) -> f64 {
        s.default_t_end()
    }
}

/// The work study on one scene from scratch: every scheme's order study on
/// it first (in parallel), then [`work_study`].
pub fn work_on(scene: &AnyScene, threads: usize) -> Result<(WorkRecord, WorkTiming), Error> {
    let ids = scheme_ids();
    let orders = parallel_map(
        &ids,
        threads,
        |id| case(id, scene).and_then(|c| c.order(&OrderSpec::default())),
        &|_, _| {},
    )
    .into_iter()
    .collect::<Result<Vec<OrderRecord>, Error>>()?;
    let refs: Vec<&OrderRecord> = orders.iter().collect();
    let (mut records, mut timings) = work_study(std::slice::from_ref(scene), &[refs], threads);
    Ok((records.remove(0), timings.remove(0)))
}
