//! Peers outside the catalogue: adaptive integrators of other published
//! crates, as a Rust user would call them on `y = (q, v)`, `y' = (v, a(q))`.
//!
//! - `ode_solvers`' `Dop853`, Dormand and Prince's eighth-order method with
//!   its 5(3) error estimate (Hairer, Nørsett, Wanner I, II.10): twelve
//!   evaluations a step.
//! - `numeris`' `RKV98NoInterp`, Verner's "efficient" 9(8) pair (J. H.
//!   Verner, *Numerically optimal Runge-Kutta pairs with interpolants*,
//!   Numer. Algorithms 53 (2010) 383-396): sixteen evaluations a step for
//!   order nine, none of them spent on an interpolant (the crate's `RKV98`
//!   adds five stages a step for one).
//!
//! Each is judged exactly as the catalogue is: its global error is the
//! largest phase-space distance to the scene's exact solution over every step
//! it takes, its energy error the largest `|E - E0|/|E0|` over every step of
//! a long run, and its cost the force evaluations counted in the system
//! function it is handed (one evaluation of `y'` is one force evaluation;
//! rejected steps and the start-up's initial step-size guess included), set
//! beside the count its own statistics report. Output is the state at the
//! steps it takes, not interpolated, so no evaluation is spent on dense
//! output.
//!
//! A peer runs through the same [`AdaptiveIntegrator`] trait as the crate's
//! own adaptive pairs, so the tolerance ladder
//! ([`stepladder::study::tolerance_ladder()`]) judges both alike; what one
//! peer needs is a [`FirstOrder`] solver, and [`Peer`] makes it an
//! integrator.

use numeris::ode::{AdaptiveSettings, OdeError, RKAdaptive, RKV98NoInterp};
use ode_solvers::dop_shared::IntegrationError;
use ode_solvers::{Dop853, OutputType, System};
use serde::Serialize;
use std::cell::Cell;
use std::time::{Duration, Instant};
use stepladder::error::Error;
use stepladder::internals::cost::work_points::{TargetCost, WorkPoint, targets_of};
use stepladder::internals::geometry::energy::energy_norm;
use stepladder::scene::Scene;
use stepladder::scheme::{AdaptiveClaims, AdaptiveIntegrator, AdaptiveRun, RunEnd, check_request};
use stepladder::state::State;

/// Most steps a peer may take in one run (raised from the crates' defaults
/// of 10^5 so that tight tolerances on long runs are not cut short).
pub const PEER_MAX_STEPS: u32 = 1_000_000;

/// The dimensions `D` of the scenes a peer runs on: its state has `N = 2 D`
/// components, and `N` cannot be computed from `D` in a type, so each pair
/// is spelled out once, in [`run_first_order`].
pub const PEER_DIMENSIONS: [usize; 4] = [1, 2, 14, 18];

/// `y' = (v, a(q))` of `y = (q, v)` for a `D`-dimensional scene, counting
/// the evaluation: the one system function every peer is handed, read and
/// written component by component through its own vector type.
#[inline(always)]
fn newton<S: Scene<D>, const D: usize>(
    scene: &S,
    evaluations: &Cell<u64>,
    y: impl Fn(usize) -> f64,
    mut dy: impl FnMut(usize, f64),
) {
    evaluations.set(evaluations.get() + 1);
    let q = nalgebra::SVector::<f64, D>::from_fn(|i, _| y(i));
    let a = scene.acceleration(&q);
    for i in 0..D {
        dy(i, y(D + i));
        dy(D + i, a[i]);
    }
}

/// The scene's state from a peer's `y = (q, v)`.
fn unpack<const D: usize>(y: impl Fn(usize) -> f64) -> State<D> {
    State::new(
        nalgebra::SVector::from_fn(|i, _| y(i)),
        nalgebra::SVector::from_fn(|i, _| y(D + i)),
    )
}

/// `y = (q, v)` component `i` of a state.
fn pack<const D: usize>(s: &State<D>, i: usize) -> f64 {
    if i < D { s.q[i] } else { s.v[i - D] }
}

/// One run of a peer: the evaluations its system function saw and those its
/// statistics report, its steps, and the states at every step it took.
#[derive(Clone, Debug)]
pub struct PeerRun<const D: usize> {
    /// Force evaluations counted in the system function.
    pub counted: u64,
    /// Force evaluations from the solver's own statistics (`None` when it
    /// gave up without reporting any).
    pub reported: Option<u64>,
    /// Accepted steps (0 when the solver gave up without reporting).
    pub accepted: u64,
    /// Rejected steps (likewise).
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

impl<const D: usize> PeerRun<D> {
    /// A run the solver gave up on: no statistics, no trajectory.
    fn gave_up(counted: u64, end: RunEnd, time: Duration) -> Self {
        PeerRun {
            counted,
            reported: None,
            accepted: 0,
            rejected: 0,
            trajectory: Vec::new(),
            end,
            time,
        }
    }
}

/// The claims of an explicit first-order pair, which has no geometry: its
/// order, the power of `h` its error estimate follows, and the exponent of
/// its global error against the tolerance where theory predicts one.
const fn pair_claims(
    order: u32,
    estimate_power: u32,
    proportionality: Option<f64>,
) -> AdaptiveClaims {
    AdaptiveClaims {
        order,
        estimate_power,
        proportionality,
        symplectic: false,
        symmetric: false,
        error_factor: None,
    }
}

/// An adaptive solver for first-order systems from another crate, run at
/// relative and absolute tolerance `tol` on `y = (q, v)` of `N = 2 D`
/// components.
pub trait FirstOrder: Sync {
    /// Its name in tables.
    const NAME: &'static str;

    /// What its theory predicts.
    fn claims(&self) -> AdaptiveClaims;

    /// One run from `start` at `t = 0` to `t_end`; `N = 2 D` (the caller
    /// checks, see [`run_first_order`]).
    fn solve<S: Scene<D>, const D: usize, const N: usize>(
        &self,
        scene: &S,
        start: &State<D>,
        t_end: f64,
        tol: f64,
    ) -> PeerRun<D>;
}

/// Runs `solver` with `N = 2 D` chosen from `D`, refusing a request the
/// solver cannot take (a tolerance or end time that is not a finite positive
/// number, a dimension outside [`PEER_DIMENSIONS`]) instead of passing it on.
pub fn run_first_order<P: FirstOrder, S: Scene<D>, const D: usize>(
    solver: &P,
    scene: &S,
    start: &State<D>,
    t_end: f64,
    tol: f64,
) -> Result<PeerRun<D>, Error> {
    check_request(t_end, tol)?;
    Ok(match D {
        1 => solver.solve::<S, D, 2>(scene, start, t_end, tol),
        2 => solver.solve::<S, D, 4>(scene, start, t_end, tol),
        14 => solver.solve::<S, D, 28>(scene, start, t_end, tol),
        18 => solver.solve::<S, D, 36>(scene, start, t_end, tol),
        _ => {
            return Err(Error::InvalidScene(format!(
                "{} is run on scenes of dimension {PEER_DIMENSIONS:?}, not {D}",
                P::NAME
            )));
        }
    })
}

/// A [`FirstOrder`] solver as an [`AdaptiveIntegrator`]: its run's
/// evaluations are the ones counted, its statistics' count set beside them
/// for the tolerance ladder to compare.
#[derive(Clone, Copy, Debug, Default)]
pub struct Peer<P>(pub P);

impl<P: FirstOrder> AdaptiveIntegrator for Peer<P> {
    fn name(&self) -> &'static str {
        P::NAME
    }

    fn claims(&self) -> AdaptiveClaims {
        self.0.claims()
    }

    fn integrate<S: Scene<D>, const D: usize>(
        &self,
        scene: &S,
        start: &State<D>,
        t_end: f64,
        tol: f64,
    ) -> Result<AdaptiveRun<D>, Error> {
        let run = run_first_order(&self.0, scene, start, t_end, tol)?;
        Ok(AdaptiveRun {
            trajectory: run.trajectory,
            evaluations: run.counted,
            accepted: run.accepted,
            rejected: run.rejected,
            end: run.end,
            time: run.time,
            reported_evaluations: run.reported,
        })
    }
}

/// `ode_solvers`' `Dop853`.
#[derive(Clone, Copy, Debug, Default)]
pub struct OdeSolversDop853;

/// [`OdeSolversDop853`] as an integrator.
pub const DOP853: Peer<OdeSolversDop853> = Peer(OdeSolversDop853);

/// The system `ode_solvers` is handed.
struct Newton<'a, S, const D: usize> {
    scene: &'a S,
    evaluations: &'a Cell<u64>,
}

impl<S: Scene<D>, const D: usize, const N: usize> System<f64, ode_solvers::SVector<f64, N>>
    for Newton<'_, S, D>
{
    fn system(
        &self,
        _t: f64,
        y: &ode_solvers::SVector<f64, N>,
        dy: &mut ode_solvers::SVector<f64, N>,
    ) {
        newton(self.scene, self.evaluations, |i| y[i], |i, x| dy[i] = x);
    }
}

impl FirstOrder for OdeSolversDop853 {
    const NAME: &'static str = "ode_solvers Dop853";

    /// Its order-8 solution is advanced with an estimate `h err5^2 /
    /// sqrt(err5^2 + 0.01 err3^2)` that behaves like `h^6` while the
    /// fifth-order difference dominates and like `h^8` once the third-order
    /// one does (see [`stepladder::study::tolerance_ladder()`]): the exponent
    /// of its global error against the tolerance moves from `4/3` towards 1
    /// along the ladder, so no single value is predicted and it is measured
    /// only.
    fn claims(&self) -> AdaptiveClaims {
        pair_claims(8, 8, None)
    }

    fn solve<S: Scene<D>, const D: usize, const N: usize>(
        &self,
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
        let y0 = ode_solvers::SVector::<f64, N>::from_fn(|i, _| pack(start, i));
        // the crate's documented defaults (safety 0.9, step ratios 0.333 to
        // 6, beta 0, stiffness test every 1000 steps), the maximal step the
        // interval and output at every step taken
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
        match result {
            Ok(stats) => {
                let t = solver.x_out().iter().copied();
                let y = solver.y_out().iter().map(|y| unpack::<D>(|i| y[i]));
                PeerRun {
                    counted,
                    reported: Some(stats.num_eval as u64),
                    accepted: stats.accepted_steps as u64,
                    rejected: stats.rejected_steps as u64,
                    trajectory: t.zip(y).collect(),
                    end: RunEnd::Reached,
                    time,
                }
            }
            Err(e) => {
                let end = match e {
                    IntegrationError::MaxNumStepReached { .. } => RunEnd::StepLimit,
                    IntegrationError::StepSizeUnderflow { .. } => RunEnd::StepUnderflow,
                    IntegrationError::StiffnessDetected { .. } => RunEnd::GaveUp,
                };
                PeerRun::gave_up(counted, end, time)
            }
        }
    }
}

/// `numeris`' `RKV98NoInterp`: Verner's 9(8) pair without the five stages
/// its interpolant would need.
#[derive(Clone, Copy, Debug, Default)]
pub struct NumerisVerner98;

/// [`NumerisVerner98`] as an integrator.
pub const VERNER98: Peer<NumerisVerner98> = Peer(NumerisVerner98);

impl FirstOrder for NumerisVerner98 {
    const NAME: &'static str = "numeris RKV98NoInterp";

    /// It advances with the ninth-order solution and estimates the error by
    /// the difference to the eighth-order one, `~ h^9`. Its PID controller
    /// (Söderlind and Wang) multiplies the step by `(0.9 / e_n^0.7 e_(n-1)^-0.4
    /// e_(n-2)^0.1)^(1/9)`, which is 1 where successive estimates are equal
    /// (`e = 0.9^(9/0.4)`): like any controller it settles where the
    /// estimate is a fixed fraction of the tolerance, so the steps go like
    /// `TOL^(1/9)` and the global error like `TOL^(9/9) = TOL`.
    fn claims(&self) -> AdaptiveClaims {
        pair_claims(9, 9, Some(1.0))
    }

    fn solve<S: Scene<D>, const D: usize, const N: usize>(
        &self,
        scene: &S,
        start: &State<D>,
        t_end: f64,
        tol: f64,
    ) -> PeerRun<D> {
        let evaluations = Cell::new(0);
        let clock = Instant::now();
        let y0 = numeris::Vector::<f64, N>::from_fn(|i, _| pack(start, i));
        let f = |_t: f64, y: &numeris::Vector<f64, N>| {
            let mut dy = numeris::Vector::<f64, N>::zeros();
            newton(scene, &evaluations, |i| y[i], |i, x| dy[i] = x);
            dy
        };
        let settings = AdaptiveSettings {
            abs_tol: tol,
            rel_tol: tol,
            max_steps: PEER_MAX_STEPS as usize,
            // the default 1e-6 would accept any step that short whatever its
            // error; no step is accepted here unless it meets the tolerance
            min_step: 0.0,
            // the one way the crate hands back the state at every step it
            // takes: kept with that step's stages, no interpolant evaluated
            // (the stages are stored, which costs time, not evaluations)
            dense_output: true,
            ..AdaptiveSettings::default()
        };
        let result = RKV98NoInterp::integrate(0.0, t_end, &y0, f, &settings);
        let time = clock.elapsed();
        let counted = evaluations.get();
        match result {
            Ok(sol) => {
                let mut trajectory: Vec<(f64, State<D>)> = sol
                    .dense
                    .iter()
                    .flat_map(|d| d.t.iter().zip(&d.y))
                    .map(|(&t, y)| (t, unpack::<D>(|i| y[i])))
                    .collect();
                trajectory.push((sol.t, unpack::<D>(|i| sol.y[i])));
                PeerRun {
                    counted,
                    reported: Some(sol.evals as u64),
                    accepted: sol.accepted as u64,
                    rejected: sol.rejected as u64,
                    trajectory,
                    end: RunEnd::Reached,
                    time,
                }
            }
            Err(OdeError::MaxStepsExceeded) => PeerRun::gave_up(counted, RunEnd::StepLimit, time),
            Err(_) => PeerRun::gave_up(counted, RunEnd::GaveUp, time),
        }
    }
}

/// The peers, in table order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum PeerId {
    /// [`DOP853`].
    Dop853,
    /// [`VERNER98`].
    Verner98,
}

/// Every peer, in table order.
pub const PEERS: [PeerId; 2] = [PeerId::Dop853, PeerId::Verner98];

/// Something to do with one adaptive integrator (a peer or one of the
/// crate's own pairs), whatever its type.
pub trait IntegratorVisitor {
    /// What the visit produces.
    type Output;
    /// Called with the chosen integrator.
    fn visit<I: AdaptiveIntegrator>(self, integrator: &I) -> Self::Output;
}

impl PeerId {
    /// Runs `visitor` on the peer.
    pub fn visit<V: IntegratorVisitor>(self, visitor: V) -> V::Output {
        match self {
            PeerId::Dop853 => visitor.visit(&DOP853),
            PeerId::Verner98 => visitor.visit(&VERNER98),
        }
    }

    /// The peer's name in tables.
    pub fn name(self) -> &'static str {
        match self {
            PeerId::Dop853 => OdeSolversDop853::NAME,
            PeerId::Verner98 => NumerisVerner98::NAME,
        }
    }

    /// Its order, for the tables.
    pub fn order(self) -> u32 {
        struct Order;
        impl IntegratorVisitor for Order {
            type Output = u32;
            fn visit<I: AdaptiveIntegrator>(self, peer: &I) -> u32 {
                peer.claims().order
            }
        }
        self.visit(Order)
    }
}

/// The names of every peer, in table order.
pub fn peer_names() -> Vec<&'static str> {
    PEERS.iter().map(|p| p.name()).collect()
}

/// The tolerances a peer is run at in the work-precision study (relative
/// and absolute alike, the scenes' states being of order one): one a decade
/// from loose to 1e-16, under a unit of round-off, so that no target a peer
/// could reach is denied it: the race counts a target reached only from a
/// run that a dearer one confirms, and the tightest error control can still
/// resolve, about 1e-15, then has a run after it.
pub const PEER_TOLERANCES: [f64; 14] = [
    1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15, 1e-16,
];

/// One tolerance of a peer, as measured.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PeerPoint {
    /// Relative and absolute tolerance.
    pub tolerance: f64,
    /// Force evaluations, counted.
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

/// What one peer did on one scene at every tolerance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PeerWork {
    /// The peer's name.
    pub peer: &'static str,
    /// Its order.
    pub order: u32,
    /// Global error against evaluations, loosest tolerance first.
    pub global: Vec<PeerPoint>,
    /// Evaluations to reach each target global error.
    pub global_targets: Vec<TargetCost>,
    /// Energy error over the long run against evaluations.
    pub energy: Vec<PeerPoint>,
    /// Evaluations to reach each target energy error.
    pub energy_targets: Vec<TargetCost>,
}

/// Wall times of a peer's runs (machine-dependent), in the order of
/// [`PeerWork::global`] and [`PeerWork::energy`].
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PeerTimes {
    /// Seconds per global-error run, the minimum over the repeats.
    pub global: Vec<f64>,
    /// Seconds per energy run, the minimum over the repeats.
    pub energy: Vec<f64>,
}

/// The fastest of `repeats` runs of `peer` at `tol`: `None` when the request
/// is refused.
pub fn fastest_run<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    peer: &I,
    scene: &S,
    t_end: f64,
    tol: f64,
    repeats: usize,
) -> Option<AdaptiveRun<D>> {
    let mut best: Option<AdaptiveRun<D>> = None;
    for _ in 0..repeats.max(1) {
        let run = peer.run(scene, t_end, tol).ok()?;
        if best.as_ref().is_none_or(|b| run.time < b.time) {
            best = Some(run);
        }
    }
    best
}

/// One tolerance's point and the fastest of `repeats` runs, the error of
/// each state measured by `error(t, state)` and maximised over the run.
fn measure<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    peer: &I,
    scene: &S,
    t_end: f64,
    tol: f64,
    repeats: usize,
    error: impl Fn(f64, &State<D>) -> f64,
) -> Option<(PeerPoint, f64)> {
    let run = fastest_run(peer, scene, t_end, tol, repeats)?;
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

/// `peer` on `scene` at every tolerance of [`PEER_TOLERANCES`]: its global
/// error to `t_end` against the exact solution and its energy error over
/// `energy_periods` periods, each run timed `repeats` times. `None` when the
/// scene has no exact solution or a dimension the peer is not run at.
pub fn peer_work<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    peer: &I,
    scene: &S,
    t_end: f64,
    energy_periods: f64,
    repeats: usize,
) -> Option<(PeerWork, PeerTimes)> {
    scene.exact(0.0)?;
    let (e0, norm) = (scene.energy(&scene.initial()), energy_norm(scene));
    let long = energy_periods * scene.period();
    let mut work = PeerWork {
        peer: peer.name(),
        order: peer.claims().order,
        global: Vec::new(),
        global_targets: Vec::new(),
        energy: Vec::new(),
        energy_targets: Vec::new(),
    };
    let mut times = PeerTimes::default();
    for tol in PEER_TOLERANCES {
        let (p, t) = measure(peer, scene, t_end, tol, repeats, |t, s| {
            scene
                .exact(t)
                .map_or(f64::NAN, |x| scene.phase_distance(s, &x))
        })?;
        work.global.push(p);
        times.global.push(t);
        let (p, t) = measure(peer, scene, long, tol, repeats, |_, s| {
            (scene.energy(s) - e0).abs() / norm
        })?;
        work.energy.push(p);
        times.energy.push(t);
    }
    work.global_targets = peer_targets(&work.global);
    work.energy_targets = peer_targets(&work.energy);
    Some((work, times))
}

/// The evaluations to reach each of
/// [`stepladder::internals::cost::work_points::TARGETS`] from a peer's points,
/// loosest tolerance first.
pub fn peer_targets(points: &[PeerPoint]) -> Vec<TargetCost> {
    let data: Vec<(f64, Option<f64>)> = points
        .iter()
        .map(|p| (p.evaluations as f64, p.error))
        .collect();
    targets_of(&data)
}
