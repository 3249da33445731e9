//! What a step costs in wall time, measured in this process: nanoseconds per
//! step of each scheme, beside a hand-written velocity Verlet loop on plain
//! `f64` for the circular orbit, the floor a generic scheme should reach.
//!
//! Each figure is the minimum over repeated runs of a fixed number of steps:
//! the run least disturbed by the rest of the machine. Rounds interleave the
//! floor and every scheme, so a slow spell of the machine hits them alike.
//! The step's inputs pass through [`std::hint::black_box`], so the compiler
//! can neither fold the loop away nor specialise it on the step size.
//!
//! Nothing here is deterministic: records of this module feed the
//! machine-dependent part of the report and the `speed` command only.

use crate::run::Outcome;
use crate::scene::{KeplerCircular, Scene};
use crate::scheme::{Scheme, SchemeVisitor, StepFailure, scheme_ids, visit_scheme};
use crate::state::State;
use serde::Serialize;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// Steps of one timed run: long enough that reading the clock is
/// negligible (a microsecond against tens of microseconds at the floor's
/// speed), short enough for many repeats in a fraction of a second.
pub const SPEED_STEPS: u64 = 20_000;

/// Timed runs per scheme; the minimum is kept.
pub const SPEED_REPEATS: usize = 15;

/// The step of a timed run, in periods of the scene: fine enough that every
/// scheme is stable and the implicit solve converges in a few iterations.
pub const SPEED_STEP: f64 = 1e-3;

/// Velocity Verlet for the circular orbit `r'' = -4 pi^2 r / |r|^3`, written
/// out by hand on plain `f64`: one force evaluation a step, no generics, no
/// vectors. `steps` steps of size `h` from `(q, v)`; the final state.
///
/// It runs the same arithmetic, in the same order, as the catalogue's
/// `velocity-verlet` on [`KeplerCircular`], so the two agree to the last bit
/// (a test checks it): what separates their speeds is the code around the
/// arithmetic, not the arithmetic.
#[inline(never)]
pub fn floor_verlet_kepler(
    mut q: [f64; 2],
    mut v: [f64; 2],
    h: f64,
    steps: u64,
) -> ([f64; 2], [f64; 2]) {
    use std::f64::consts::PI;
    let minus_gm = -(4.0 * PI * PI);
    let accel = |q: [f64; 2]| {
        let r2 = q[0] * q[0] + q[1] * q[1];
        let k = minus_gm / (r2 * r2.sqrt());
        [q[0] * k, q[1] * k]
    };
    let half = h * 0.5;
    let mut a = accel(q);
    for _ in 0..steps {
        v = [v[0] + a[0] * half, v[1] + a[1] * half];
        q = [q[0] + v[0] * h, q[1] + v[1] * h];
        a = accel(q);
        v = [v[0] + a[0] * half, v[1] + a[1] * half];
    }
    (q, v)
}

/// `steps` steps of `scheme` on `scene`, nothing else: the loop that is
/// timed. Not inlined, so that it is compiled once per scheme and scene as a
/// loop of its own, like [`floor_verlet_kepler`]. A failed step ends the run
/// with its number.
#[inline(never)]
pub fn run_steps<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    carry: &mut M::Carry<f64, D>,
    h: f64,
    steps: u64,
) -> Result<(), (u64, StepFailure)> {
    for n in 1..=steps {
        if let Err(failure) = scheme.step(scene, carry, h) {
            return Err((n, failure));
        }
    }
    Ok(())
}

/// One timed run of a scheme: its wall time and the force evaluations its
/// steps took (the start-up, which is not timed, excluded).
#[derive(Clone, Debug, PartialEq)]
pub struct TimedRun {
    /// Wall time of the steps.
    pub time: Duration,
    /// Force evaluations of the steps: the counted evaluations per step for
    /// an explicit scheme, the solver's iterations for an implicit one.
    pub evaluations: u64,
    /// How the run ended ([`Outcome::Completed`] or a failed step).
    pub outcome: Outcome,
}

/// Times `steps` steps of `scheme` from `start` (the start-up is not timed).
pub fn time_run<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    start: &State<D>,
    h: f64,
    steps: u64,
) -> TimedRun {
    let mut carry = scheme.start(scene, start, h);
    let before = scheme.solver_evaluations(&carry);
    let h = black_box(h);
    let clock = Instant::now();
    let result = run_steps(scheme, scene, black_box(&mut carry), h, black_box(steps));
    let time = clock.elapsed();
    black_box(&carry);
    let evaluations = match (before, scheme.solver_evaluations(&carry)) {
        (Some(b), Some(a)) => a - b,
        // counted on the oscillator, not on `scene`: an explicit step's count
        // does not depend on the scene, and counting runs on `scene` itself
        // would add to the calls a caller counts there
        _ => (steps as f64
            * crate::study::cost::count::per_step_charged(
                scheme,
                &crate::scene::Harmonic::default(),
            ))
        .round() as u64,
    };
    let outcome = match result {
        Ok(()) => Outcome::Completed,
        Err((step, failure)) => Outcome::Failed {
            h,
            step,
            time: step as f64 * h,
            failure,
        },
    };
    TimedRun {
        time,
        evaluations,
        outcome,
    }
}

/// Times the floor once: `steps` steps of [`floor_verlet_kepler`] from the
/// circular orbit's initial state.
pub fn time_floor(h: f64, steps: u64) -> Duration {
    let s = KeplerCircular.initial();
    let (q, v) = ([s.q[0], s.q[1]], [s.v[0], s.v[1]]);
    let clock = Instant::now();
    let out = floor_verlet_kepler(black_box(q), black_box(v), black_box(h), black_box(steps));
    let time = clock.elapsed();
    black_box(out);
    time
}

/// What a step of one scheme costs on the circular orbit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SchemeSpeed {
    /// Scheme id.
    pub id: &'static str,
    /// Force evaluations per step, as counted in the timed run.
    pub force_evaluations_per_step: f64,
    /// Nanoseconds per step, the minimum over the repeats.
    pub ns_per_step: f64,
    /// `ns_per_step` over the floor's.
    pub ratio_to_floor: f64,
    /// Nanoseconds per force evaluation.
    pub ns_per_force_evaluation: f64,
    /// `ns_per_force_evaluation` over the floor's (one evaluation a step):
    /// above 1 is time spent around the force, not in it.
    pub ratio_per_evaluation: f64,
    /// Every step was taken in every run.
    pub completed: bool,
}

/// The `speed` command's record: every scheme against the floor on the
/// circular orbit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SpeedRecord {
    /// Scene id.
    pub scene: &'static str,
    /// The step.
    pub h: f64,
    /// Steps per timed run.
    pub steps: u64,
    /// Timed runs per scheme (the minimum is kept).
    pub repeats: usize,
    /// The floor's nanoseconds per step (one force evaluation a step).
    pub floor_ns_per_step: f64,
    /// Every scheme, in catalogue order.
    pub schemes: Vec<SchemeSpeed>,
}

/// Times a catalogue scheme on the circular orbit once.
struct TimeOnKepler {
    h: f64,
    steps: u64,
}

impl SchemeVisitor for TimeOnKepler {
    type Output = TimedRun;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> TimedRun {
        let scene = KeplerCircular;
        time_run(scheme, &scene, &scene.initial(), self.h, self.steps)
    }
}

/// Measures every catalogue scheme and the floor on the circular orbit:
/// `repeats` rounds, each timing the floor and then every scheme once over
/// `steps` steps of [`SPEED_STEP`] periods; the minimum of each is kept.
pub fn speed(steps: u64, repeats: usize) -> SpeedRecord {
    let (steps, repeats) = (steps.max(1), repeats.max(1));
    let h = SPEED_STEP * KeplerCircular.period();
    let ids = scheme_ids();
    let mut floor = Duration::MAX;
    let mut best: Vec<Option<TimedRun>> = vec![None; ids.len()];
    for _ in 0..repeats {
        floor = floor.min(time_floor(h, steps));
        for (slot, id) in best.iter_mut().zip(&ids) {
            let run = visit_scheme(id, TimeOnKepler { h, steps }).expect("catalogue ids");
            let keep = match slot {
                Some(b) => run.time < b.time && run.outcome.completed(),
                None => true,
            };
            if keep {
                *slot = Some(run);
            }
        }
    }
    let per_step = |d: Duration| d.as_secs_f64() * 1e9 / steps as f64;
    let floor_ns = per_step(floor);
    let schemes = ids
        .iter()
        .zip(best)
        .map(|(id, run)| {
            let run = run.expect("at least one repeat");
            let ns = per_step(run.time);
            let per = run.evaluations as f64 / steps as f64;
            let ns_eval = ns / per;
            SchemeSpeed {
                id,
                force_evaluations_per_step: per,
                ns_per_step: ns,
                ratio_to_floor: ns / floor_ns,
                ns_per_force_evaluation: ns_eval,
                ratio_per_evaluation: ns_eval / floor_ns,
                completed: run.outcome.completed(),
            }
        })
        .collect();
    SpeedRecord {
        scene: KeplerCircular.meta().id,
        h,
        steps,
        repeats,
        floor_ns_per_step: floor_ns,
        schemes,
    }
}
