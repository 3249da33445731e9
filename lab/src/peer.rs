//! A peer outside the catalogue: the `ode_solvers` crate's `Dop853`, the
//! adaptive eighth-order Dormand-Prince method with step-size control, as a
//! Rust user would call it on `y = (q, v)`, `y' = (v, a(q))`.
//!
//! It is judged exactly as the catalogue is: its global error is the largest
//! phase-space distance to the scene's exact solution over every step it
//! takes to the order study's `t_end`, its energy error the largest
//! `|E - E0|/|E0|` over every step of a long run, and its cost the force
//! evaluations its own statistics report (one evaluation of `y'` is one
//! force evaluation; the count includes rejected steps and the start-up's
//! initial step-size guess). Output is requested at the steps it takes, not
//! interpolated, so no evaluation is spent on dense output.
//!
//! The peer runs through the same [`AdaptiveIntegrator`] trait as the
//! crate's own adaptive pairs, so the tolerance ladder
//! ([`stepladder::study::tolerance_ladder()`]) judges both alike.

use ode_solvers::dop_shared::IntegrationError;
use ode_solvers::{Dop853, OutputType, SVector, System};
use serde::Serialize;
use std::cell::Cell;
use std::time::{Duration, Instant};
use stepladder::error::Error;
use stepladder::scene::Scene;
use stepladder::state::State;
use stepladder::study::adaptive::integrator::{
    AdaptiveClaims, AdaptiveIntegrator, AdaptiveRun, RunEnd, check_request,
};
use stepladder::study::cost::work_points::{TargetCost, WorkPoint, targets_of};
use stepladder::study::geometry::energy::energy_norm;

/// The peer's name in tables.
pub const PEER_NAME: &str = "ode_solvers Dop853";

/// The tolerances the peer is run at (relative and absolute alike, the
/// scenes' states being of order one): one a decade from loose to 1e-15,
/// five units of round-off, the tightest its error control can still
/// resolve, so that no target the peer could reach is denied it.
pub const PEER_TOLERANCES: [f64; 13] = [
    1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15,
];

/// Most steps the peer may take in one run (its own limit, raised from its
/// default of 10^5 so that tight tolerances on long runs are not cut short).
pub const PEER_MAX_STEPS: u32 = 1_000_000;

/// `y' = (v, a(q))` for a `D`-dimensional scene, on the peer's vectors of
/// `N = 2 D` components, counting every evaluation.
struct Newton<'a, S, const D: usize> {
    scene: &'a S,
    evaluations: &'a Cell<u64>,
}

impl<S: Scene<D>, const D: usize, const N: usize> System<f64, SVector<f64, N>>
    for Newton<'_, S, D>
{
    fn system(&self, _t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        self.evaluations.set(self.evaluations.get() + 1);
        let q = nalgebra::SVector::<f64, D>::from_fn(|i, _| y[i]);
        let a = self.scene.acceleration(&q);
        for i in 0..D {
            dy[i] = y[D + i];
            dy[D + i] = a[i];
        }
    }
}

fn pack<const D: usize, const N: usize>(s: &State<D>) -> SVector<f64, N> {
    SVector::<f64, N>::from_fn(|i, _| if i < D { s.q[i] } else { s.v[i - D] })
}

fn unpack<const D: usize, const N: usize>(y: &SVector<f64, N>) -> State<D> {
    State::new(
        nalgebra::SVector::from_fn(|i, _| y[i]),
        nalgebra::SVector::from_fn(|i, _| y[D + i]),
    )
}

/// One run of the peer: its statistics, the evaluations counted by the
/// system itself, and the states at every step it took.
#[derive(Clone, Debug)]
pub struct PeerRun<const D: usize> {
    /// Force evaluations from the solver's statistics.
    pub evaluations: u64,
    /// Force evaluations counted in the system function.
    pub counted: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// `(t, state)` at the start and after every accepted step; empty when
    /// the solver gave up.
    pub trajectory: Vec<(f64, State<D>)>,
    /// How the run ended.
    pub end: RunEnd,
    /// Wall time of the integration (set-up and output included, as a user
    /// would spend it).
    pub time: Duration,
}

/// Runs the peer on `scene` from its initial state to `t_end` at tolerance
/// `tol`. `D` must be 1 or 2 (the peer's state has `2 D` components, and
/// `N = 2 D` is passed explicitly since it cannot be computed from `D` in a
/// type); any other pairing is refused with `None`.
pub fn run_peer<S: Scene<D>, const D: usize, const N: usize>(
    scene: &S,
    t_end: f64,
    tol: f64,
) -> Option<PeerRun<D>> {
    (N == 2 * D).then(|| solve::<S, D, N>(scene, &scene.initial(), t_end, tol))
}

/// The peer from `start` over `[0, t_end]`, `N = 2 D`.
fn solve<S: Scene<D>, const D: usize, const N: usize>(
    scene: &S,
    start: &State<D>,
    t_end: f64,
    tol: f64,
) -> PeerRun<D> {
    let evaluations = Cell::new(0);
    let clock = Instant::now();
    let system = Newton {
        scene,
        evaluations: &evaluations,
    };
    let y0: SVector<f64, N> = pack(start);
    let mut solver = Dop853::from_param(
        system,
        0.0,
        t_end,
        t_end,
        y0,
        tol,
        tol,
        0.9,
        0.0,
        0.333,
        6.0,
        t_end,
        0.0,
        PEER_MAX_STEPS,
        1000,
        OutputType::Sparse,
    );
    let result = solver.integrate();
    let time = clock.elapsed();
    let counted = evaluations.get();
    let (stats, trajectory, end) = match result {
        Ok(stats) => {
            let t = solver.x_out().iter().copied();
            let y = solver.y_out().iter().map(unpack::<D, N>);
            (Some(stats), t.zip(y).collect(), RunEnd::Reached)
        }
        Err(e) => {
            let end = match e {
                IntegrationError::MaxNumStepReached { .. } => RunEnd::StepLimit,
                IntegrationError::StepSizeUnderflow { .. } => RunEnd::StepUnderflow,
                IntegrationError::StiffnessDetected { .. } => RunEnd::GaveUp,
            };
            (None, Vec::new(), end)
        }
    };
    PeerRun {
        evaluations: stats.map_or(counted, |s| s.num_eval as u64),
        counted,
        accepted: stats.map_or(0, |s| s.accepted_steps as u64),
        rejected: stats.map_or(0, |s| s.rejected_steps as u64),
        trajectory,
        end,
        time,
    }
}

/// The peer as an [`AdaptiveIntegrator`]. Its order-8 solution is advanced
/// with an estimate `h err5^2 / sqrt(err5^2 + 0.01 err3^2)` that behaves
/// like `h^6` while the fifth-order difference dominates and like `h^8`
/// once the third-order one does (see
/// [`stepladder::study::tolerance_ladder()`]): the exponent of its
/// global error against the tolerance moves from `4/3` towards 1 along the
/// ladder, so no single value is predicted and it is measured only.
#[derive(Clone, Copy, Debug, Default)]
pub struct Dop853Peer;

impl AdaptiveIntegrator for Dop853Peer {
    fn name(&self) -> &'static str {
        PEER_NAME
    }

    fn claims(&self) -> AdaptiveClaims {
        AdaptiveClaims {
            order: 8,
            estimate_power: 8,
            proportionality: None,
            symplectic: false,
            symmetric: false,
            error_factor: None,
        }
    }

    fn integrate<S: Scene<D>, const D: usize>(
        &self,
        scene: &S,
        start: &State<D>,
        t_end: f64,
        tol: f64,
    ) -> Result<AdaptiveRun<D>, Error> {
        check_request(t_end, tol)?;
        let run = match D {
            1 => solve::<S, D, 2>(scene, start, t_end, tol),
            2 => solve::<S, D, 4>(scene, start, t_end, tol),
            _ => {
                return Err(Error::InvalidScene(format!(
                    "{PEER_NAME} is run on scenes of one or two dimensions, not {D}"
                )));
            }
        };
        Ok(AdaptiveRun {
            trajectory: run.trajectory,
            evaluations: run.evaluations,
            accepted: run.accepted,
            rejected: run.rejected,
            end: run.end,
            time: run.time,
            reported_evaluations: None,
        })
    }
}

/// One tolerance of the peer, as measured.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PeerPoint {
    /// Relative and absolute tolerance.
    pub tolerance: f64,
    /// Force evaluations, from the solver's statistics.
    pub evaluations: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// The error; `None` when the solver gave up.
    pub error: Option<f64>,
}

impl PeerPoint {
    /// The point as a [`WorkPoint`] (its step is the mean step).
    pub fn work(&self, t_end: f64) -> WorkPoint {
        WorkPoint {
            h: t_end / self.accepted.max(1) as f64,
            steps: self.accepted,
            evaluations: self.evaluations,
            error: self.error,
        }
    }
}

/// What the peer did on one scene at every tolerance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PeerWork {
    /// [`PEER_NAME`].
    pub peer: &'static str,
    /// Global error against evaluations, loosest tolerance first.
    pub global: Vec<PeerPoint>,
    /// Evaluations to reach each target global error.
    pub global_targets: Vec<TargetCost>,
    /// Energy error over the long run against evaluations.
    pub energy: Vec<PeerPoint>,
    /// Evaluations to reach each target energy error.
    pub energy_targets: Vec<TargetCost>,
}

/// Wall times of the peer's runs (machine-dependent), in the order of
/// [`PeerWork::global`] and [`PeerWork::energy`].
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PeerTimes {
    /// Seconds per global-error run, the minimum over the repeats.
    pub global: Vec<f64>,
    /// Seconds per energy run, the minimum over the repeats.
    pub energy: Vec<f64>,
}

/// Runs the peer at `tol` with `N = 2 D` chosen from `D`; `None` for a
/// dimension other than 1 or 2.
pub fn run_peer_any<S: Scene<D>, const D: usize>(
    scene: &S,
    t_end: f64,
    tol: f64,
) -> Option<PeerRun<D>> {
    match D {
        1 => run_peer::<S, D, 2>(scene, t_end, tol),
        2 => run_peer::<S, D, 4>(scene, t_end, tol),
        _ => None,
    }
}

/// One tolerance's point and the fastest of `repeats` runs, the error of
/// each state measured by `error(t, state)` and maximised over the run.
fn measure<S: Scene<D>, const D: usize>(
    scene: &S,
    t_end: f64,
    tol: f64,
    repeats: usize,
    error: impl Fn(f64, &State<D>) -> f64,
) -> Option<(PeerPoint, f64)> {
    let mut best: Option<AdaptiveRun<D>> = None;
    for _ in 0..repeats.max(1) {
        let run = Dop853Peer.run(scene, t_end, tol).ok()?;
        if best.as_ref().is_none_or(|b| run.time < b.time) {
            best = Some(run);
        }
    }
    let run = best?;
    let worst = (!run.trajectory.is_empty()).then(|| {
        run.trajectory
            .iter()
            .map(|(t, s)| error(*t, s))
            .fold(0.0, f64::max)
    });
    let point = PeerPoint {
        tolerance: tol,
        evaluations: run.evaluations,
        accepted: run.accepted,
        rejected: run.rejected,
        error: worst.filter(|e| e.is_finite()),
    };
    Some((point, run.time.as_secs_f64()))
}

/// The peer on `scene` at every tolerance of [`PEER_TOLERANCES`]: its global
/// error to `t_end` against the exact solution and its energy error over
/// `energy_periods` periods, each run timed `repeats` times. `None` when the
/// scene has no exact solution or a dimension other than 1 or 2.
pub fn peer_work<S: Scene<D>, const D: usize>(
    scene: &S,
    t_end: f64,
    energy_periods: f64,
    repeats: usize,
) -> Option<(PeerWork, PeerTimes)> {
    scene.exact(0.0)?;
    let (e0, norm) = (scene.energy(&scene.initial()), energy_norm(scene));
    let long = energy_periods * scene.period();
    let mut work = PeerWork {
        peer: PEER_NAME,
        global: Vec::new(),
        global_targets: Vec::new(),
        energy: Vec::new(),
        energy_targets: Vec::new(),
    };
    let mut times = PeerTimes::default();
    for tol in PEER_TOLERANCES {
        let (p, t) = measure(scene, t_end, tol, repeats, |t, s| {
            scene
                .exact(t)
                .map_or(f64::NAN, |x| scene.phase_distance(s, &x))
        })?;
        work.global.push(p);
        times.global.push(t);
        let (p, t) = measure(scene, long, tol, repeats, |_, s| {
            (scene.energy(s) - e0).abs() / norm
        })?;
        work.energy.push(p);
        times.energy.push(t);
    }
    work.global_targets = peer_targets(&work.global);
    work.energy_targets = peer_targets(&work.energy);
    Some((work, times))
}

/// The evaluations to reach each of [`stepladder::study::cost::work_points::TARGETS`] from the peer's points,
/// loosest tolerance first.
pub fn peer_targets(points: &[PeerPoint]) -> Vec<TargetCost> {
    let data: Vec<(f64, Option<f64>)> = points
        .iter()
        .map(|p| (p.evaluations as f64, p.error))
        .collect();
    targets_of(&data)
}

#[cfg(test)]
mod tests {
    use super::*;
    use stepladder::scene::KeplerEccentric;

    /// The trait runs the very solver the work tables use, and refuses what
    /// the solver cannot take instead of passing it on.
    #[test]
    fn the_trait_runs_the_same_solver_and_refuses_bad_requests() {
        let scene = KeplerEccentric::default();
        let direct = run_peer_any(&scene, 10.0, 1e-8).unwrap();
        let through = Dop853Peer.run(&scene, 10.0, 1e-8).unwrap();
        assert_eq!(direct.evaluations, through.evaluations);
        assert_eq!(direct.evaluations, direct.counted);
        assert_eq!(
            (direct.accepted, direct.rejected),
            (through.accepted, through.rejected)
        );
        assert_eq!(direct.trajectory, through.trajectory);
        assert_eq!(through.end, RunEnd::Reached);
        for (t_end, tol) in [(10.0, 0.0), (10.0, -1.0), (f64::NAN, 1e-8)] {
            assert!(Dop853Peer.run(&scene, t_end, tol).is_err());
        }
    }
}
