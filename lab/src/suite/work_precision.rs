//! The work-precision study over the catalogue and the built-in scenes:
//! for each scene, every scheme's cost of reaching each target error (from
//! [`stepladder::internals::cost::work_points`]), the peers of other crates beside
//! them ([`crate::peer`]), the cheapest scheme per target, and, apart
//! from these deterministic records, the wall time it all takes here.

use crate::case::case;
use crate::peer::{IntegratorVisitor, PEERS, PeerId, PeerTimes, PeerWork, peer_work};
use serde::Serialize;
use std::time::Duration;
use stepladder::error::Error;
use stepladder::internals::accuracy::order::{OrderRecord, OrderSpec};
use stepladder::internals::cost::step_time::{SPEED_STEP, time_run};
use stepladder::internals::cost::work_points::{
    ENERGY_PERIODS, Reach, SchemeWork, TARGETS, TargetCost, cheapest, cost_to_reach, scheme_work,
};
use stepladder::internals::parallel::parallel_map;
use stepladder::scene::{AnyScene, Scene, SceneVisitor};
use stepladder::scheme::AdaptiveIntegrator;
use stepladder::scheme::{Scheme, SchemeVisitor, scheme_ids, visit_scheme};

/// Steps of one timed run of a scheme on a scene, for its time per force
/// evaluation.
pub const WORK_TIMING_STEPS: u64 = 4_000;

/// Timed runs per scheme and scene; the minimum is kept.
pub const WORK_TIMING_REPEATS: usize = 5;

/// Timed runs of a peer per tolerance; the minimum is kept.
pub const PEER_REPEATS: usize = 3;

/// The cheapest catalogue scheme at one target error, with the peers beside.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cheapest {
    /// The target error.
    pub target: f64,
    /// The cheapest scheme, if any reaches the target.
    pub scheme: Option<&'static str>,
    /// Its cost.
    pub reach: Reach,
    /// Each peer's cost of the same target, in the order of
    /// [`crate::peer::PEERS`].
    pub peers: Vec<Reach>,
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
    /// The peers, in the order of [`crate::peer::PEERS`] (none on a scene
    /// without an exact solution).
    pub peers: Vec<PeerWork>,
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

/// The fastest catalogue scheme at one target error, with the peers beside.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Fastest {
    /// The target error.
    pub target: f64,
    /// The fastest scheme, if any reaches the target.
    pub scheme: Option<&'static str>,
    /// Its time, in seconds.
    pub seconds: Reach,
    /// Each peer's time for the same target, in seconds.
    pub peers_seconds: Vec<Reach>,
}

/// The work-precision study's wall times on one scene (machine-dependent).
/// A scheme's time for a run is its force evaluations times its measured
/// time per evaluation on the scene; the peers' runs are timed directly.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WorkTiming {
    /// Scene id.
    pub scene: &'static str,
    /// Every scheme, in catalogue order.
    pub schemes: Vec<SchemeTiming>,
    /// Each peer's run times, in the order of [`WorkRecord::peers`].
    pub peers: Vec<PeerTimes>,
    /// The fastest scheme per target global error.
    pub fastest_global: Vec<Fastest>,
    /// The fastest scheme per target energy error.
    pub fastest_energy: Vec<Fastest>,
}

/// One piece of the study: a scheme on a scene, or a peer on a scene.
enum Job<'a> {
    Scheme(&'a AnyScene, &'a OrderRecord),
    Peer(&'a AnyScene, PeerId),
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

struct PeerOn<'a>(&'a AnyScene);
impl IntegratorVisitor for PeerOn<'_> {
    type Output = Option<(PeerWork, PeerTimes)>;
    fn visit<I: AdaptiveIntegrator>(self, peer: &I) -> Self::Output {
        self.0.visit(PeerOnScene(peer))
    }
}

struct PeerOnScene<'a, I>(&'a I);
impl<I: AdaptiveIntegrator> SceneVisitor for PeerOnScene<'_, I> {
    type Output = Option<(PeerWork, PeerTimes)>;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> Self::Output {
        let t_end = scene.default_t_end();
        peer_work(self.0, scene, t_end, ENERGY_PERIODS, PEER_REPEATS)
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
/// each peer's beside.
pub fn cheapest_per_target(
    schemes: &[(&'static str, &[TargetCost])],
    peers: &[&[TargetCost]],
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
                peers: peers
                    .iter()
                    .map(|p| p.get(i).map_or(Reach::NotReached, |c| c.reach))
                    .collect(),
            }
        })
        .collect()
}

/// The deterministic record of one scene from its schemes' and peers' work.
fn record(
    scene: &AnyScene,
    t_end: f64,
    schemes: Vec<SchemeWork>,
    peers: Vec<PeerWork>,
) -> WorkRecord {
    let global: Vec<(&'static str, &[TargetCost])> = schemes
        .iter()
        .map(|s| (s.scheme, s.global_targets.as_slice()))
        .collect();
    let energy: Vec<(&'static str, &[TargetCost])> = schemes
        .iter()
        .map(|s| (s.scheme, s.energy_targets.as_slice()))
        .collect();
    let peer_global: Vec<&[TargetCost]> =
        peers.iter().map(|p| p.global_targets.as_slice()).collect();
    let peer_energy: Vec<&[TargetCost]> =
        peers.iter().map(|p| p.energy_targets.as_slice()).collect();
    let cheapest_global = cheapest_per_target(&global, &peer_global);
    let cheapest_energy = cheapest_per_target(&energy, &peer_energy);
    let meta = scene.meta();
    WorkRecord {
        scene: meta.id,
        scene_parameters: meta.parameters,
        t_end,
        energy_periods: ENERGY_PERIODS,
        targets: TARGETS.to_vec(),
        schemes,
        peers,
        cheapest_global,
        cheapest_energy,
    }
}

/// The fastest scheme at each target, and each peer's time beside: times
/// are evaluations times the scheme's time per evaluation; a peer's are
/// interpolated between its timed runs.
fn timing(record: &WorkRecord, schemes: Vec<SchemeTiming>, peers: Vec<PeerTimes>) -> WorkTiming {
    let fastest = |targets: &dyn Fn(&SchemeWork) -> &[TargetCost],
                   peer_points: &[Vec<(f64, Option<f64>)>]| {
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
                    peers_seconds: peer_points
                        .iter()
                        .map(|p| cost_to_reach(p, target))
                        .collect(),
                }
            })
            .collect()
    };
    // each peer's run seconds against their errors, global or energy runs
    let timed = |runs: fn(&PeerWork) -> &[crate::peer::PeerPoint],
                 times: fn(&PeerTimes) -> &[f64]|
     -> Vec<Vec<(f64, Option<f64>)>> {
        record
            .peers
            .iter()
            .zip(&peers)
            .map(|(w, t)| {
                runs(w)
                    .iter()
                    .zip(times(t))
                    .map(|(p, &t)| (t, p.error))
                    .collect()
            })
            .collect()
    };
    let global = timed(|w| &w.global, |t| &t.global);
    let energy = timed(|w| &w.energy, |t| &t.energy);
    let fastest_global = fastest(&|w| w.global_targets.as_slice(), &global);
    let fastest_energy = fastest(&|w| w.energy_targets.as_slice(), &energy);
    WorkTiming {
        scene: record.scene,
        schemes,
        peers,
        fastest_global,
        fastest_energy,
    }
}

/// The work study on `scenes`, given every scheme's order record on each
/// (`orders[i]` for `scenes[i]`, in catalogue order): the schemes' and the
/// peers' runs in parallel on `threads` threads, then the timings one at a
/// time, so that they do not compete for the machine.
pub fn work_study(
    scenes: &[AnyScene],
    orders: &[Vec<&OrderRecord>],
    threads: usize,
) -> (Vec<WorkRecord>, Vec<WorkTiming>) {
    let ids = scheme_ids();
    let mut jobs: Vec<Job> = Vec::new();
    for (scene, records) in scenes.iter().zip(orders) {
        jobs.extend(PEERS.iter().map(|&p| Job::Peer(scene, p)));
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
            Job::Peer(scene, peer) => Done::Peer(peer.visit(PeerOn(scene))),
        },
        &|_, _| {},
    )
    .into_iter();
    let mut records = Vec::new();
    let mut timings = Vec::new();
    for (scene, r) in scenes.iter().zip(orders) {
        let (peer_work, peer_times): (Vec<PeerWork>, Vec<PeerTimes>) = PEERS
            .iter()
            .filter_map(|_| match done.next() {
                Some(Done::Peer(p)) => p,
                _ => unreachable!("jobs are in order"),
            })
            .unzip();
        let schemes: Vec<SchemeWork> = (0..r.len())
            .map(|_| match done.next() {
                Some(Done::Scheme(w)) => w,
                _ => unreachable!("jobs are in order"),
            })
            .collect();
        debug_assert!(schemes.iter().zip(&ids).all(|(w, id)| w.scheme == *id));
        // the work points are over the scene's default t_end, whatever the
        // order study settled on (see `scheme_work`)
        let t_end = scene.visit(DefaultEnd);
        let rec = record(scene, t_end, schemes, peer_work);
        timings.push(timing(&rec, scheme_timings(scene), peer_times));
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
