//! The tolerance ladder of every adaptive integrator on every built-in
//! scene: the crate's own DPRKN6(4) and DPRKN8(6) pairs and the
//! `ode_solvers` peer, through the same [`AdaptiveIntegrator`] trait.

use crate::peer::Dop853Peer;
use crate::suite::work_precision::PEER_REPEATS;
use std::time::{Duration, Instant};
use stepladder::error::Error;
use stepladder::parallel::parallel_map;
use stepladder::scene::{AnyScene, Scene, SceneVisitor};
use stepladder::study::adaptive::{
    AdaptiveIntegrator, DPRKN6_ADAPTIVE, DPRKN8_ADAPTIVE, ToleranceLadderRecord,
    ToleranceLadderSpec, tolerance_ladder,
};

/// Which adaptive integrator a job runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Adaptive {
    /// [`DPRKN6_ADAPTIVE`].
    OwnPair6,
    /// [`DPRKN8_ADAPTIVE`].
    OwnPair8,
    /// [`Dop853Peer`].
    Peer,
}

/// The integrators of the study, in table order.
pub const INTEGRATORS: [Adaptive; 3] = [Adaptive::OwnPair6, Adaptive::OwnPair8, Adaptive::Peer];

/// The tolerance ladders, one per integrator and scene (integrator-major),
/// and the wall time they took (machine-dependent).
#[derive(Clone, Debug)]
pub struct AdaptiveRecords {
    /// The records.
    pub ladders: Vec<ToleranceLadderRecord>,
    /// Wall time of each ladder, in the same order.
    pub times: Vec<Duration>,
    /// For the crate's own pairs, the seconds of each tolerance's run to
    /// `t_end` (the fastest of [`PEER_REPEATS`], timed one at a time after
    /// the ladders, as the peer's runs are); empty for the peer, whose runs
    /// the work study times.
    pub point_seconds: Vec<Vec<f64>>,
}

/// The fastest of `repeats` runs of `integrator` at each tolerance.
struct TimeRuns<'a, I>(&'a I, &'a ToleranceLadderRecord);
impl<I: AdaptiveIntegrator> SceneVisitor for TimeRuns<'_, I> {
    type Output = Vec<f64>;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> Self::Output {
        let TimeRuns(integrator, ladder) = self;
        ladder
            .points
            .iter()
            .map(|p| {
                // NaN when no run succeeded: the race leaves such points out
                (0..PEER_REPEATS)
                    .filter_map(|_| integrator.run(scene, ladder.t_end, p.tolerance).ok())
                    .map(|run| run.time.as_secs_f64())
                    .reduce(f64::min)
                    .unwrap_or(f64::NAN)
            })
            .collect()
    }
}

/// Times the runs of an own pair's ladder (empty for the peer).
fn point_seconds(
    integrator: Adaptive,
    scene: &AnyScene,
    ladder: &ToleranceLadderRecord,
) -> Vec<f64> {
    match integrator {
        Adaptive::OwnPair6 => scene.visit(TimeRuns(&DPRKN6_ADAPTIVE, ladder)),
        Adaptive::OwnPair8 => scene.visit(TimeRuns(&DPRKN8_ADAPTIVE, ladder)),
        Adaptive::Peer => Vec::new(),
    }
}

struct LadderOn<'a, I>(&'a I, &'a ToleranceLadderSpec);
impl<I: AdaptiveIntegrator> SceneVisitor for LadderOn<'_, I> {
    type Output = Result<ToleranceLadderRecord, Error>;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> Self::Output {
        tolerance_ladder(self.0, scene, self.1)
    }
}

/// One integrator's ladder on one scene.
pub fn ladder_of(
    integrator: Adaptive,
    scene: &AnyScene,
    spec: &ToleranceLadderSpec,
) -> Result<ToleranceLadderRecord, Error> {
    match integrator {
        Adaptive::OwnPair6 => scene.visit(LadderOn(&DPRKN6_ADAPTIVE, spec)),
        Adaptive::OwnPair8 => scene.visit(LadderOn(&DPRKN8_ADAPTIVE, spec)),
        Adaptive::Peer => scene.visit(LadderOn(&Dop853Peer, spec)),
    }
}

/// Every integrator on every built-in scene, with default settings.
pub fn adaptive_study(threads: usize) -> Result<AdaptiveRecords, Error> {
    let scenes = AnyScene::all();
    let jobs: Vec<(Adaptive, &AnyScene)> = INTEGRATORS
        .iter()
        .flat_map(|&i| scenes.iter().map(move |s| (i, s)))
        .collect();
    let spec = ToleranceLadderSpec::default();
    let done = parallel_map(
        &jobs,
        threads.max(1),
        |&(i, s)| {
            let t = Instant::now();
            ladder_of(i, s, &spec).map(|r| (r, t.elapsed()))
        },
        &|_, _| {},
    );
    let mut records = AdaptiveRecords {
        ladders: Vec::with_capacity(done.len()),
        times: Vec::with_capacity(done.len()),
        point_seconds: Vec::with_capacity(done.len()),
    };
    for (d, (i, s)) in done.into_iter().zip(jobs) {
        let (r, t) = d?;
        records.point_seconds.push(point_seconds(i, s, &r));
        records.ladders.push(r);
        records.times.push(t);
    }
    Ok(records)
}
