//! The tolerance ladder of every adaptive integrator on every built-in
//! scene: the catalogue's own DPRKN6(4) pair and the `ode_solvers` peer,
//! through the same [`AdaptiveIntegrator`] trait.

use crate::error::Error;
use crate::measure::adaptive::{
    AdaptiveIntegrator, DPRKN6_ADAPTIVE, ToleranceLadderRecord, ToleranceLadderSpec,
    tolerance_ladder,
};
use crate::measure::cost::peer::Dop853Peer;
use crate::parallel::parallel_map;
use crate::scene::{AnyScene, Scene, SceneVisitor};
use std::time::{Duration, Instant};

/// Which adaptive integrator a job runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Adaptive {
    /// [`DPRKN6_ADAPTIVE`].
    OwnPair,
    /// [`Dop853Peer`].
    Peer,
}

/// The integrators of the study, in table order.
pub const INTEGRATORS: [Adaptive; 2] = [Adaptive::OwnPair, Adaptive::Peer];

/// The tolerance ladders, one per integrator and scene (integrator-major),
/// and the wall time they took (machine-dependent).
#[derive(Clone, Debug)]
pub struct AdaptiveRecords {
    /// The records.
    pub ladders: Vec<ToleranceLadderRecord>,
    /// Wall time of each ladder, in the same order.
    pub times: Vec<Duration>,
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
        Adaptive::OwnPair => scene.visit(LadderOn(&DPRKN6_ADAPTIVE, spec)),
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
    };
    for d in done {
        let (r, t) = d?;
        records.ladders.push(r);
        records.times.push(t);
    }
    Ok(records)
}
