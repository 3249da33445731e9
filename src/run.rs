//! The integration loop every study uses: fixed steps, synchronised output at
//! every step, and a blow-up, a failed step or a panic in the scheme's code
//! detected as a measured outcome, with where it happened.

use crate::scene::Scene;
use crate::scheme::{Scheme, SolveTally, StepFailure};
use crate::state::State;
use crate::tolerance;
use serde::Serialize;

/// How a run ended.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Outcome {
    /// Every step was taken and the state stayed bounded.
    Completed,
    /// The state left the blow-up bound or stopped being finite.
    Unstable {
        /// The step size.
        h: f64,
        /// The step at which the state was first out of bounds.
        step: u64,
        /// Its time.
        time: f64,
        /// The coordinate that did it (`q[i]` or `v[i]`): the first that is
        /// not finite, else the largest in the scaled phase space `(q, v/w)`.
        coordinate: String,
        /// Its value there (`NaN` prints as `null` in JSON).
        value: f64,
    },
    /// A step could not be carried out.
    Failed {
        /// The step size.
        h: f64,
        /// The step that failed.
        step: u64,
        /// Its time.
        time: f64,
        /// Why.
        failure: StepFailure,
    },
}

impl Outcome {
    /// True for a run that went to the end.
    pub fn completed(&self) -> bool {
        matches!(self, Outcome::Completed)
    }

    /// The step size of a run that stopped (`None` for a completed one).
    pub fn h(&self) -> Option<f64> {
        match self {
            Outcome::Completed => None,
            Outcome::Unstable { h, .. } | Outcome::Failed { h, .. } => Some(*h),
        }
    }

    /// The step at which a run stopped (`None` for a completed one).
    pub fn step(&self) -> Option<u64> {
        match self {
            Outcome::Completed => None,
            Outcome::Unstable { step, .. } | Outcome::Failed { step, .. } => Some(*step),
        }
    }

    /// True for a run stopped by a panic in the scheme's code.
    pub fn panicked(&self) -> bool {
        matches!(self, Outcome::Failed { failure, .. } if failure.panicked())
    }

    /// True for a failure no step size excuses ([`StepFailure::defect`]).
    pub fn defect(&self) -> bool {
        matches!(self, Outcome::Failed { failure, .. } if failure.defect())
    }

    /// Where a run stopped and why, without the step size: `step 4 (t =
    /// 28): v[0] = NaN`.
    pub fn where_and_why(&self) -> String {
        use crate::wording::figure;
        match self {
            Outcome::Completed => "no step (it completed)".to_string(),
            Outcome::Unstable {
                step,
                time,
                coordinate,
                value,
                ..
            } => format!(
                "step {step} (t = {}): {coordinate} = {}{}",
                figure(*time),
                figure(*value),
                if value.is_finite() {
                    ", past the blow-up bound"
                } else {
                    ""
                }
            ),
            Outcome::Failed {
                step,
                time,
                failure,
                ..
            } => format!("step {step} (t = {}): {failure}", figure(*time)),
        }
    }

    /// The outcome in a few words with three-digit figures and without the
    /// step, for a reason that states the step already: "unstable: blew up
    /// at step 57702 (t = 14.2)".
    pub fn brief(&self) -> String {
        use crate::wording::figure;
        match self {
            Outcome::Completed => "completed".to_string(),
            Outcome::Unstable {
                step,
                time,
                coordinate,
                value,
                ..
            } => {
                format!(
                    "{}: {coordinate} = {} at step {step} (t = {})",
                    if value.is_finite() {
                        "unstable"
                    } else {
                        "not finite"
                    },
                    figure(*value),
                    figure(*time)
                )
            }
            Outcome::Failed {
                step,
                time,
                failure,
                ..
            } => format!("step {step} failed (t = {}): {failure}", figure(*time)),
        }
    }
}

impl std::fmt::Display for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let what = match self {
            Outcome::Completed => return write!(f, "completed"),
            Outcome::Unstable { value, .. } if value.is_finite() => "unstable",
            Outcome::Unstable { .. } => "not finite",
            Outcome::Failed { .. } => "failed",
        };
        write!(
            f,
            "{what} at h = {}, {}",
            crate::wording::figure(self.h().unwrap_or(f64::NAN)),
            self.where_and_why()
        )
    }
}

/// Runs `steps` steps of size `h` from `start`, calling `observe(n, t, state)`
/// with the synchronised state at every whole step `n = 0..=steps`, `t = n h`.
///
/// Stops early, without calling `observe` on the bad state, when the state is
/// non-finite or farther than [`tolerance::blow_up_bound`] from the origin in
/// phase space.
pub fn integrate<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    start: &State<D>,
    h: f64,
    steps: u64,
    observe: impl FnMut(u64, f64, &State<D>),
) -> Outcome {
    integrate_tallied(scheme, scene, start, h, steps, observe).0
}

/// The state at `t_end` after `steps` equal steps from the scene's start,
/// and the force evaluations they took, counted on the force (`None` for
/// the state when the run did not complete).
pub fn counted_end<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    t_end: f64,
    steps: u64,
) -> (Option<State<D>>, u64) {
    let counted = crate::scene::Counted::new(scene);
    let mut last = None;
    let outcome = integrate(
        scheme,
        &counted,
        &scene.initial(),
        t_end / steps as f64,
        steps,
        |n, _, s| {
            if n == steps {
                last = Some(*s);
            }
        },
    );
    (last.filter(|_| outcome.completed()), counted.evaluations())
}

/// [`integrate`], returning as well what the scheme's solves reported over
/// the run ([`Scheme::solve_tally`]; `None` for a scheme that reports none).
pub fn integrate_tallied<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    start: &State<D>,
    h: f64,
    steps: u64,
    mut observe: impl FnMut(u64, f64, &State<D>),
) -> (Outcome, Option<SolveTally>) {
    let bound = tolerance::blow_up_bound(scene.scale());
    let w = scene.frequency();
    let failed = |step: u64, failure: StepFailure| Outcome::Failed {
        h,
        step,
        time: step as f64 * h,
        failure,
    };
    // The scheme's start, step and state are the user's code: a panic there
    // is caught and becomes this run's outcome, with where it happened.
    let mut carry = match caught(|| scheme.start(scene, start, h)) {
        Ok(carry) => carry,
        Err(message) => return (failed(0, StepFailure::Panicked { message }), None),
    };
    observe(0, 0.0, start);
    for n in 1..=steps {
        let stepped = caught(|| {
            scheme.step(scene, &mut carry, h)?;
            Ok(scheme.state(&carry, h))
        });
        let s = match stepped {
            Ok(Ok(s)) => s,
            Ok(Err(failure)) => return (failed(n, failure), scheme.solve_tally(&carry)),
            Err(message) => return (failed(n, StepFailure::Panicked { message }), None),
        };
        let size2 = s.q.norm_squared() + (s.v / w).norm_squared();
        if size2.is_nan() || size2 > bound * bound {
            let (coordinate, value) = culprit(&s, w);
            let outcome = Outcome::Unstable {
                h,
                step: n,
                time: n as f64 * h,
                coordinate,
                value,
            };
            return (outcome, scheme.solve_tally(&carry));
        }
        observe(n, n as f64 * h, &s);
    }
    (Outcome::Completed, scheme.solve_tally(&carry))
}

/// The coordinate of a state that has left the bound: the first that is not
/// finite, else the largest in the scaled phase space `(q, v/w)`.
fn culprit<const D: usize>(s: &State<D>, w: f64) -> (String, f64) {
    let coordinates = (0..D)
        .map(|i| (format!("q[{i}]"), s.q[i], s.q[i]))
        .chain((0..D).map(|i| (format!("v[{i}]"), s.v[i], s.v[i] / w)));
    let mut largest = (String::new(), 0.0, -1.0);
    for (name, value, scaled) in coordinates {
        if !value.is_finite() {
            return (name, value);
        }
        if scaled.abs() > largest.2 {
            largest = (name, value, scaled.abs());
        }
    }
    (largest.0, largest.1)
}

/// One step of the scheme's own code, a panic in it reported as
/// [`StepFailure::Panicked`]: for the studies that step a carry themselves.
pub(crate) fn guarded_step<M: Scheme, S: Scene<D>, R: crate::state::Real, const D: usize>(
    scheme: &M,
    scene: &S,
    carry: &mut M::Carry<R, D>,
    h: R,
) -> Result<(), StepFailure> {
    caught(|| scheme.step(scene, carry, h))
        .unwrap_or_else(|message| Err(StepFailure::Panicked { message }))
}

/// Runs `f`, a call into a scheme's or an integrator's own code, and turns a
/// panic in it into the panic's message. Only user code runs inside: a
/// panic of the harness itself is a bug of the harness and propagates. (A
/// crate built with `panic = "abort"` aborts instead; nothing can catch that.)
pub fn caught<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|payload| {
        if let Some(text) = payload.downcast_ref::<&str>() {
            (*text).to_string()
        } else if let Some(text) = payload.downcast_ref::<String>() {
            text.clone()
        } else {
            "a panic whose payload is not text".to_string()
        }
    })
}

/// Most step times a rung is compared at: every step up to this many steps,
/// else this many equally spaced ones (and `t_end`). The largest distance
/// over them follows the error's law exactly as the largest over every step
/// does, and 4096 times over 2 sqrt(2) periods resolve an error that varies
/// along the orbit to well within a percent.
pub const COMPARISONS: u64 = 4096;

/// The step numbers at which a rung of `steps` steps is compared.
pub(crate) fn comparison_steps(steps: u64) -> impl Iterator<Item = u64> {
    let count = steps.min(COMPARISONS);
    (0..=count).map(move |j| j * steps / count)
}

/// The error of one rung measured as the order study measures it against
/// an exact solution: the largest phase-space distance to it at the
/// comparison steps of `steps` steps over `t_end`. `None` when the scene has
/// no exact solution or the run does not complete.
pub fn exact_rung_error<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    t_end: f64,
    steps: u64,
) -> Option<f64> {
    scene.exact(0.0)?;
    let h = t_end / steps as f64;
    let mut at = comparison_steps(steps).peekable();
    let mut worst = 0.0f64;
    let outcome = integrate(scheme, scene, &scene.initial(), h, steps, |n, _, s| {
        if at.next_if_eq(&n).is_some() {
            let t = if n == steps { t_end } else { n as f64 * h };
            if let Some(exact) = scene.exact(t) {
                worst = worst.max(scene.phase_distance(s, &exact));
            }
        }
    });
    outcome.completed().then_some(worst)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Harmonic;
    use crate::scheme::Leapfrog;

    /// Leap-frog at `h w0 = 7` multiplies the oscillator's amplitude by the
    /// larger root of `l^2 - (2 - 49) l + 1`, `|l| = 46.98`, each step: the
    /// state leaves a million times the orbit at the first `n` with
    /// `47^n > 1e6` (`47^3 = 1.0e5`, `47^4 = 4.9e6`; the prefactor would have
    /// to be off by ten to move it), so the run stops at step 4.
    #[test]
    fn an_unstable_run_stops_where_the_growth_says_and_says_so() {
        let scene = Harmonic::default();
        let h = 7.0 / scene.frequency();
        let outcome = integrate(&Leapfrog, &scene, &scene.initial(), h, 100, |_, _, _| {});
        assert!(matches!(outcome, Outcome::Unstable { .. }), "{outcome:?}");
        assert_eq!(outcome.step(), Some(4), "{outcome:?}");
        assert_eq!(outcome.h(), Some(h));
        assert!(!outcome.completed() && !outcome.panicked());
        assert!(
            outcome.where_and_why().starts_with("step 4 "),
            "{}",
            outcome.where_and_why()
        );
        let calm = integrate(&Leapfrog, &scene, &scene.initial(), 0.1, 100, |_, _, _| {});
        assert_eq!((calm.step(), calm.h()), (None, None));
    }
}
