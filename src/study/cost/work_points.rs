//! Work against precision: what it costs each scheme to reach a given error.
//!
//! Two errors, each against the work spent:
//!
//! - the **global error** of the order study, the largest phase-space
//!   distance to the exact solution over `t_end` (2 sqrt(2) periods). Its
//!   rungs are reused as they are (running them again would double the
//!   suite's cost for the same numbers), with their force evaluations added:
//!   counted from the metadata for an explicit scheme, and by running the
//!   rung again on a counting scene for an implicit one, whose iterations
//!   vary from rung to rung. The order study's ladder stops where round-off
//!   would disturb an order fit, which can be above a target the error
//!   itself still reaches: until two successive rungs meet the smallest
//!   target, and while the error is still falling, the ladder goes on at the
//!   same ratio ([`beyond_the_floor`]);
//! - the **energy error on a long run**, the largest `|E - E0|/|E0|` over
//!   [`ENERGY_PERIODS`] periods, on a ladder of its own that halves the step
//!   from 1/8 period until the error is below the smallest target, stops
//!   falling, or a run would exceed [`ENERGY_MAX_STEPS`] steps.
//!
//! The cost of a target error is read off these points by [`cost_to_reach`]:
//! between the two measured rungs that bracket it, on log-log axes, never
//! beyond the rungs measured.

use crate::ladder::steps_for;
use crate::run::integrate;
use crate::scene::{Counted, Scene};
use crate::scheme::Scheme;
use crate::study::accuracy::order::OrderRecord;
use crate::study::geometry::energy::energy_norm;
use serde::Serialize;

/// The target errors of the work-precision tables.
pub const TARGETS: [f64; 4] = [1e-3, 1e-6, 1e-9, 1e-12];

/// Length of an energy run, in periods: long against the order study's
/// 2.8 periods, so a drift shows, and short enough that a ladder of such
/// runs for every scheme and scene costs a fraction of a second.
pub const ENERGY_PERIODS: f64 = 100.0;

/// The energy ladder's first step, in periods: coarse, so that a
/// high-order scheme's cheapest run is not already far below the targets
/// (a coarser start would only blow up the low-order schemes).
pub const ENERGY_START: f64 = 1.0 / 4.0;

/// The energy ladder's longest run, in steps (a step of 1/5243 period over
/// [`ENERGY_PERIODS`]): it bounds a ladder to about a million steps.
pub const ENERGY_MAX_STEPS: u64 = 1 << 19;

/// Below this relative energy error, an error that has not halved over two
/// successive halvings of the step has reached the round-off floor and the
/// ladder stops. Above it, a stalled error is an orbit not yet resolved
/// (an escape, a precessing ellipse), and the ladder goes on.
pub const ENERGY_FLOOR_GUARD: f64 = 1e-6;

/// One measured point: a run's cost and the error it made.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WorkPoint {
    /// The step.
    pub h: f64,
    /// Steps taken (asked for; a run that blew up took fewer).
    pub steps: u64,
    /// Force evaluations spent, start-up included.
    pub evaluations: u64,
    /// The error; `None` when the run blew up or a step failed.
    pub error: Option<f64>,
}

/// The cost of reaching a target error, read off measured points.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", content = "cost", rename_all = "kebab-case")]
pub enum Reach {
    /// Interpolated on log-log axes between the two measured points that
    /// bracket the target.
    Interpolated(f64),
    /// At most this: the first point at or below the target has no measured
    /// point above it to interpolate from (it is the cheapest measured, or
    /// the one before it blew up), so the true cost may be lower.
    AtMost(f64),
    /// No measured point is at or below the target.
    NotReached,
}

impl Reach {
    /// The cost, when the target was reached.
    pub fn cost(self) -> Option<f64> {
        match self {
            Reach::Interpolated(c) | Reach::AtMost(c) => Some(c),
            Reach::NotReached => None,
        }
    }

    /// The same reach with its cost multiplied by `factor` (evaluations to
    /// seconds, say).
    pub fn scaled(self, factor: f64) -> Reach {
        match self {
            Reach::Interpolated(c) => Reach::Interpolated(c * factor),
            Reach::AtMost(c) => Reach::AtMost(c * factor),
            Reach::NotReached => Reach::NotReached,
        }
    }
}

/// The cost of reaching `target`, from `(cost, error)` points ordered from
/// cheap to dear (`None` for a run that blew up):
///
/// - the first point whose error is at or below the target decides;
/// - if the point before it has a larger, finite, positive error, the cost is
///   interpolated linearly in `ln cost` against `ln error` between the two
///   (a power law `error = C cost^-k` is reproduced exactly);
/// - if there is no usable point before it, its own cost is an upper bound;
/// - if no point reaches the target, it is not reached: nothing is ever
///   extrapolated beyond the points measured.
///
/// ```
/// use stepladder::study::cost::work_points::{Reach, cost_to_reach};
/// let pts = [(10.0, Some(1e-2)), (100.0, Some(1e-4)), (1000.0, Some(1e-6))];
/// match cost_to_reach(&pts, 1e-3) {
///     Reach::Interpolated(c) => assert!((c - 31.6227766).abs() < 1e-6),
///     other => panic!("{other:?}"),
/// }
/// assert_eq!(cost_to_reach(&pts, 1e-1), Reach::AtMost(10.0));
/// assert_eq!(cost_to_reach(&pts, 1e-7), Reach::NotReached);
/// ```
pub fn cost_to_reach(points: &[(f64, Option<f64>)], target: f64) -> Reach {
    let Some(k) = points
        .iter()
        .position(|&(_, e)| e.is_some_and(|e| e <= target))
    else {
        return Reach::NotReached;
    };
    let (c1, e1) = (points[k].0, points[k].1.unwrap_or(f64::NAN));
    let bracket = k
        .checked_sub(1)
        .map(|j| points[j])
        .and_then(|(c0, e0)| e0.map(|e0| (c0, e0)))
        .filter(|&(c0, e0)| e0.is_finite() && e0 > target && e1 > 0.0 && c0 > 0.0 && c0 < c1);
    match bracket {
        Some((c0, e0)) => {
            let s = (target.ln() - e0.ln()) / (e1.ln() - e0.ln());
            Reach::Interpolated((c0.ln() + s * (c1.ln() - c0.ln())).exp())
        }
        None => Reach::AtMost(c1),
    }
}

/// The cheapest of `candidates` at reaching a target: the smallest cost among
/// those that reach it (an upper bound counts at its value), the first in
/// order on a tie; `None` when none reaches it.
///
/// ```
/// use stepladder::study::cost::work_points::{Reach, cheapest};
/// let c = [("a", Reach::NotReached), ("b", Reach::Interpolated(50.0)), ("c", Reach::AtMost(40.0))];
/// assert_eq!(cheapest(&c), Some(("c", Reach::AtMost(40.0))));
/// assert_eq!(cheapest(&c[..1]), None);
/// ```
pub fn cheapest<'a>(candidates: &[(&'a str, Reach)]) -> Option<(&'a str, Reach)> {
    candidates
        .iter()
        .filter_map(|&(id, r)| r.cost().map(|c| (id, r, c)))
        .fold(
            None,
            |best: Option<(&str, Reach, f64)>, (id, r, c)| match best {
                Some((_, _, b)) if b <= c => best,
                _ => Some((id, r, c)),
            },
        )
        .map(|(id, r, _)| (id, r))
}

/// The cost of each of [`TARGETS`] from `points`, taking `cost` of each.
pub fn targets(points: &[WorkPoint], cost: impl Fn(&WorkPoint) -> f64) -> Vec<TargetCost> {
    let data: Vec<(f64, Option<f64>)> = points.iter().map(|p| (cost(p), p.error)).collect();
    targets_of(&data)
}

/// The cost of each of [`TARGETS`] from `(cost, error)` points, cheapest
/// first.
pub fn targets_of(data: &[(f64, Option<f64>)]) -> Vec<TargetCost> {
    TARGETS
        .iter()
        .map(|&target| TargetCost {
            target,
            reach: cost_to_reach(data, target),
        })
        .collect()
}

/// The cost of one target error.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TargetCost {
    /// The target error.
    pub target: f64,
    /// Force evaluations to reach it.
    pub reach: Reach,
}

/// Force evaluations a scheme spends in `start` on `scene`.
pub fn start_evaluations<M: Scheme, S: Scene<D> + Clone, const D: usize>(
    scheme: &M,
    scene: &S,
    h: f64,
) -> u64 {
    let counted = Counted::new(scene.clone());
    let _ = scheme.start(&counted, &counted.initial(), h);
    counted.evaluations()
}

/// Most rungs [`beyond_the_floor`] adds: four halvings of the step at the
/// order study's densest ratio.
pub const EXTRA_RUNGS: usize = 16;

/// Work points past the `measured` ones (the order study's rungs as work
/// points), until two successive rungs meet the smallest target: the same
/// error (against the exact solution, at the same comparison steps), each
/// rung `ratio` times the previous one's steps, while the error falls by at
/// least a tenth of what the scheme's order promises per rung (past that it
/// is round-off, not truncation, and stepping finer only costs more) or has
/// just met the target, and while the cost stays under the order study's
/// cap.
///
/// Why two: near the round-off floor an error can dip below a target on one
/// rung and rise above it on the next. A reading that counts a target as
/// reached only once a finer run confirms it needs the rung after the first
/// that meets it; [`cost_to_reach`] reads the first crossing either way, so
/// the extra rung changes no cost it reads.
pub fn beyond_the_floor<M: Scheme, S: Scene<D> + Clone, const D: usize>(
    scheme: &M,
    scene: &S,
    record: &OrderRecord,
    t_end: f64,
    measured: &[WorkPoint],
) -> Vec<WorkPoint> {
    let smallest = TARGETS.iter().copied().fold(f64::INFINITY, f64::min);
    let rungs: Vec<_> = record.rungs.iter().filter(|r| r.error.is_some()).collect();
    let with_error: Vec<&WorkPoint> = measured.iter().filter(|p| p.error.is_some()).collect();
    let (Some(finest), [.., coarser, last]) = (with_error.last(), rungs.as_slice()) else {
        return Vec::new();
    };
    let meets = |p: &WorkPoint| p.error.is_some_and(|e| e <= smallest);
    // how many of the finest rungs in a row meet the smallest target
    let mut met_in_a_row = with_error
        .iter()
        .rev()
        .take(2)
        .take_while(|p| meets(p))
        .count();
    let ratio = last.steps as f64 / coarser.steps as f64;
    let promised = ratio.powi(scheme.meta().order as i32);
    let per_step = finest.evaluations as f64 / finest.steps as f64;
    let mut points = Vec::new();
    let (mut steps, mut previous) = (finest.steps, finest.error.unwrap_or(f64::INFINITY));
    while met_in_a_row < 2 && points.len() < EXTRA_RUNGS {
        steps = ((steps as f64 * ratio).round() as u64).max(steps + 1);
        if per_step * steps as f64 > crate::ladder::AUTO_MAX_RUNG_EVALUATIONS as f64 {
            break;
        }
        let Some(point) = exact_point(scheme, scene, t_end, steps) else {
            break;
        };
        let error = point.error.unwrap_or(f64::INFINITY);
        met_in_a_row = if meets(&point) { met_in_a_row + 1 } else { 0 };
        points.push(point);
        // a stalled error stops the ladder, except on a rung that has just
        // met the target: the next one confirms it or takes it back
        if error > previous / (1.0 + 0.1 * (promised - 1.0)) && met_in_a_row != 1 {
            break;
        }
        previous = error;
    }
    points
}

/// One rung measured afresh over `t_end` against the exact solution, with
/// its force evaluations; `None` without an exact solution.
fn exact_point<M: Scheme, S: Scene<D> + Clone, const D: usize>(
    scheme: &M,
    scene: &S,
    t_end: f64,
    steps: u64,
) -> Option<WorkPoint> {
    scene.exact(0.0)?;
    let error = crate::run::exact_rung_error(scheme, scene, t_end, steps);
    let h = t_end / steps as f64;
    let evaluations = if scheme.meta().implicit {
        let counted = Counted::new(scene.clone());
        let _ = integrate(scheme, &counted, &counted.initial(), h, steps, |_, _, _| {});
        counted.evaluations()
    } else {
        let per_step = crate::study::cost::count::per_step_charged(scheme, scene);
        start_evaluations(scheme, scene, h) + (steps as f64 * per_step).round() as u64
    };
    Some(WorkPoint {
        h,
        steps,
        evaluations,
        error,
    })
}

/// The order study's rungs as work points: the steps and errors of `record`
/// with the force evaluations each rung spent. For an explicit scheme they
/// are the start-up's plus the counted evaluations per step
/// ([`crate::study::cost::evaluations`]) per step taken; an implicit
/// scheme's rungs are run again on a counting scene, since the iterations of
/// its solve vary with the step.
pub fn global_points<M: Scheme, S: Scene<D> + Clone, const D: usize>(
    scheme: &M,
    scene: &S,
    record: &OrderRecord,
) -> Vec<WorkPoint> {
    let meta = scheme.meta();
    let per_step = crate::study::cost::count::per_step_charged(scheme, scene);
    record
        .rungs
        .iter()
        .filter(|rung| rung.error.is_some() || !rung.outcome.completed())
        .map(|rung| {
            let taken = match rung.outcome {
                crate::run::Outcome::Completed => rung.steps,
                crate::run::Outcome::Unstable { step, .. } => step,
                crate::run::Outcome::Failed { step, .. } => step,
            };
            let evaluations = if meta.implicit {
                let counted = Counted::new(scene.clone());
                let _ = integrate(
                    scheme,
                    &counted,
                    &counted.initial(),
                    rung.h,
                    taken,
                    |_, _, _| {},
                );
                counted.evaluations()
            } else {
                start_evaluations(scheme, scene, rung.h) + (taken as f64 * per_step).round() as u64
            };
            WorkPoint {
                h: rung.h,
                steps: rung.steps,
                evaluations,
                error: rung.error,
            }
        })
        .collect()
}

/// The largest relative energy error of one run of `steps` steps of `h`,
/// with the force evaluations it spent; `None` for the error when the run
/// blew up or a step failed.
pub fn energy_run<M: Scheme, S: Scene<D> + Clone, const D: usize>(
    scheme: &M,
    scene: &S,
    h: f64,
    steps: u64,
) -> WorkPoint {
    let counted = Counted::new(scene.clone());
    let start = scene.initial();
    let (e0, norm) = (scene.energy(&start), energy_norm(scene));
    let mut worst = 0.0f64;
    let outcome = integrate(scheme, &counted, &start, h, steps, |_, _, s| {
        worst = worst.max((scene.energy(s) - e0).abs() / norm);
    });
    WorkPoint {
        h,
        steps,
        evaluations: counted.evaluations(),
        error: outcome.completed().then_some(worst),
    }
}

/// The energy ladder of `scheme` on `scene` (see the module documentation).
pub fn energy_points<M: Scheme, S: Scene<D> + Clone, const D: usize>(
    scheme: &M,
    scene: &S,
) -> Vec<WorkPoint> {
    let period = scene.period();
    let t_end = ENERGY_PERIODS * period;
    let smallest = TARGETS.iter().copied().fold(f64::INFINITY, f64::min);
    let mut points: Vec<WorkPoint> = Vec::new();
    for k in 0.. {
        let Ok(steps) = steps_for(t_end, ENERGY_START * period * 0.5f64.powi(k)) else {
            break;
        };
        if steps > ENERGY_MAX_STEPS {
            break;
        }
        let p = energy_run(scheme, scene, t_end / steps as f64, steps);
        points.push(p);
        if p.error.is_some_and(|e| e <= smallest) || at_floor(&points) {
            break;
        }
    }
    points
}

/// The last three points' errors have not halved twice, below
/// [`ENERGY_FLOOR_GUARD`]: round-off, which finer steps only make worse.
fn at_floor(points: &[WorkPoint]) -> bool {
    let [.., a, b, c] = points else {
        return false;
    };
    match (a.error, b.error, c.error) {
        (Some(a), Some(b), Some(c)) => c < ENERGY_FLOOR_GUARD && b > 0.5 * a && c > 0.5 * b,
        _ => false,
    }
}

/// What the work study found for one scheme on one scene. Deterministic:
/// costs are force evaluations, never times.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SchemeWork {
    /// Scheme id.
    pub scheme: &'static str,
    /// Its claimed order.
    pub order: u32,
    /// The order study's rungs with their force evaluations.
    pub global: Vec<WorkPoint>,
    /// Evaluations to reach each target global error.
    pub global_targets: Vec<TargetCost>,
    /// The energy ladder over [`ENERGY_PERIODS`] periods.
    pub energy: Vec<WorkPoint>,
    /// Evaluations to reach each target relative energy error.
    pub energy_targets: Vec<TargetCost>,
}

/// Measures the work study of one scheme on one scene, reusing its order
/// study's `record`.
pub fn scheme_work<M: Scheme, S: Scene<D> + Clone, const D: usize>(
    scheme: &M,
    scene: &S,
    record: &OrderRecord,
) -> SchemeWork {
    // every scheme is raced over the same time: where the order study had
    // to shorten its runs to decide, its steps are run again over the
    // scene's default t_end
    let t_end = scene.default_t_end();
    let mut global = if (record.t_end - t_end).abs() <= 1e-12 * t_end {
        global_points(scheme, scene, record)
    } else {
        record
            .rungs
            .iter()
            .filter_map(|r| {
                exact_point(scheme, scene, t_end, (t_end / r.h).round().max(1.0) as u64)
            })
            .collect()
    };
    let beyond = beyond_the_floor(scheme, scene, record, t_end, &global);
    global.extend(beyond);
    let energy = energy_points(scheme, scene);
    let evaluations = |p: &WorkPoint| p.evaluations as f64;
    SchemeWork {
        scheme: scheme.meta().id,
        order: scheme.meta().order,
        global_targets: targets(&global, evaluations),
        energy_targets: targets(&energy, evaluations),
        global,
        energy,
    }
}
