//! The tolerance ladder of every adaptive integrator on every built-in
//! scene: the crate's own pairs (DPRKN6(4), DPRKN8(6) and DPRKN12(10), the
//! last two also with compensated state updates) and the peers of other
//! crates, through the same [`AdaptiveIntegrator`] trait; and
//! [`SLIPPED_PAIR`], whose controller assumes the wrong power, to show what
//! a passing exponent does not rule out.

use crate::peer::{IntegratorVisitor, PEERS, PeerId};
use crate::suite::work_precision::PEER_REPEATS;
use std::time::{Duration, Instant};
use stepladder::error::Error;
use stepladder::internals::adaptive::{
    ToleranceLadderRecord, ToleranceLadderSpec, tolerance_ladder,
};
use stepladder::internals::parallel::parallel_map;
use stepladder::scene::{AnyScene, Scene, SceneVisitor};
use stepladder::scheme::{
    AdaptiveIntegrator, Controller, DPRKN6_ADAPTIVE, DPRKN8_ADAPTIVE, DPRKN8_COMPENSATED,
    DPRKN12_ADAPTIVE, DPRKN12_COMPENSATED, EmbeddedPair,
};

/// DPRKN6(4) with the commonest slip in a pair's step law: its controller
/// built for an estimate of power `q = 4` where the estimate behaves like
/// `h^(q+1) = h^5`, so that it claims `error ~ TOL^(6/4)`. A controller of
/// any power settles where its estimate is a fixed fraction of the
/// tolerance, so its steps, and its error, still follow the estimate's own
/// power: only the tolerance ladder's exponent can refute the claim.
pub const SLIPPED_PAIR: EmbeddedPair<6> = EmbeddedPair {
    name: "DPRKN6(4), controller for h^4",
    controller: Controller::predictive(4),
    ..DPRKN6_ADAPTIVE
};

/// Which adaptive integrator a job runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Adaptive {
    /// [`DPRKN6_ADAPTIVE`].
    OwnPair6,
    /// [`DPRKN8_ADAPTIVE`].
    OwnPair8,
    /// [`DPRKN8_COMPENSATED`].
    OwnPair8Compensated,
    /// [`DPRKN12_ADAPTIVE`].
    OwnPair12,
    /// [`DPRKN12_COMPENSATED`].
    OwnPair12Compensated,
    /// A peer of another crate.
    Peer(PeerId),
}

/// The crate's own pairs, in table order.
pub const OWN_PAIRS: [Adaptive; 5] = [
    Adaptive::OwnPair6,
    Adaptive::OwnPair8,
    Adaptive::OwnPair8Compensated,
    Adaptive::OwnPair12,
    Adaptive::OwnPair12Compensated,
];

/// The integrators of the study, in table order: the own pairs, then the
/// peers.
pub const INTEGRATORS: [Adaptive; OWN_PAIRS.len() + PEERS.len()] = {
    let mut all = [Adaptive::OwnPair6; OWN_PAIRS.len() + PEERS.len()];
    let mut i = 0;
    while i < OWN_PAIRS.len() {
        all[i] = OWN_PAIRS[i];
        i += 1;
    }
    let mut i = 0;
    while i < PEERS.len() {
        all[OWN_PAIRS.len() + i] = Adaptive::Peer(PEERS[i]);
        i += 1;
    }
    all
};

impl Adaptive {
    /// Runs `visitor` on the integrator.
    pub fn visit<V: IntegratorVisitor>(self, visitor: V) -> V::Output {
        match self {
            Adaptive::OwnPair6 => visitor.visit(&DPRKN6_ADAPTIVE),
            Adaptive::OwnPair8 => visitor.visit(&DPRKN8_ADAPTIVE),
            Adaptive::OwnPair8Compensated => visitor.visit(&DPRKN8_COMPENSATED),
            Adaptive::OwnPair12 => visitor.visit(&DPRKN12_ADAPTIVE),
            Adaptive::OwnPair12Compensated => visitor.visit(&DPRKN12_COMPENSATED),
            Adaptive::Peer(p) => p.visit(visitor),
        }
    }

    /// The integrator's name in tables.
    pub fn name(self) -> &'static str {
        match self {
            Adaptive::OwnPair6 => DPRKN6_ADAPTIVE.name,
            Adaptive::OwnPair8 => DPRKN8_ADAPTIVE.name,
            Adaptive::OwnPair8Compensated => DPRKN8_COMPENSATED.name,
            Adaptive::OwnPair12 => DPRKN12_ADAPTIVE.name,
            Adaptive::OwnPair12Compensated => DPRKN12_COMPENSATED.name,
            Adaptive::Peer(p) => p.name(),
        }
    }
}

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
    /// the ladders, so that no run is timed while another job shares the
    /// machine); empty for a peer, whose runs the race times where it needs
    /// them ([`crate::suite::race`]).
    pub point_seconds: Vec<Vec<f64>>,
    /// [`SLIPPED_PAIR`]'s ladder on every built-in scene: how often its
    /// wrong claim passes.
    pub slipped: Vec<ToleranceLadderRecord>,
}

/// The fastest of `repeats` runs of an integrator at each tolerance of a
/// ladder.
struct TimeRuns<'a>(&'a AnyScene, &'a ToleranceLadderRecord);
impl IntegratorVisitor for TimeRuns<'_> {
    type Output = Vec<f64>;
    fn visit<I: AdaptiveIntegrator>(self, integrator: &I) -> Vec<f64> {
        self.0.visit(TimeRunsOn(integrator, self.1))
    }
}

struct TimeRunsOn<'a, I>(&'a I, &'a ToleranceLadderRecord);
impl<I: AdaptiveIntegrator> SceneVisitor for TimeRunsOn<'_, I> {
    type Output = Vec<f64>;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> Self::Output {
        let TimeRunsOn(integrator, ladder) = self;
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

struct LadderOn<'a>(&'a AnyScene, &'a ToleranceLadderSpec);
impl IntegratorVisitor for LadderOn<'_> {
    type Output = Result<ToleranceLadderRecord, Error>;
    fn visit<I: AdaptiveIntegrator>(self, integrator: &I) -> Self::Output {
        self.0.visit(LadderOnScene(integrator, self.1))
    }
}

struct LadderOnScene<'a, I>(&'a I, &'a ToleranceLadderSpec);
impl<I: AdaptiveIntegrator> SceneVisitor for LadderOnScene<'_, I> {
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
    integrator.visit(LadderOn(scene, spec))
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
    let slipped = parallel_map(
        &scenes,
        threads.max(1),
        |s| s.visit(LadderOnScene(&SLIPPED_PAIR, &spec)),
        &|_, _| {},
    );
    let mut records = AdaptiveRecords {
        ladders: Vec::with_capacity(done.len()),
        times: Vec::with_capacity(done.len()),
        point_seconds: Vec::with_capacity(done.len()),
        slipped: slipped.into_iter().collect::<Result<_, _>>()?,
    };
    for (d, (i, s)) in done.into_iter().zip(jobs) {
        let (r, t) = d?;
        records.point_seconds.push(match i {
            Adaptive::Peer(_) => Vec::new(),
            own => own.visit(TimeRuns(s, &r)),
        });
        records.ladders.push(r);
        records.times.push(t);
    }
    Ok(records)
}
