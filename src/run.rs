//! The integration loop every study uses: fixed steps, synchronised output at
//! every step, and a blow-up detected as a measured outcome.

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

    /// The outcome in a few words with three-digit figures and without the
    /// step, for a reason that states the step already: "unstable: blew up
    /// at step 57702 (t = 14.2)".
    pub fn brief(&self) -> String {
        use crate::wording::figure;
        match self {
            Outcome::Completed => "completed".to_string(),
            Outcome::Unstable { step, time, .. } => {
                format!("unstable: blew up at step {step} (t = {})", figure(*time))
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
        match self {
            Outcome::Completed => write!(f, "completed"),
            Outcome::Unstable { h, step, time } => {
                write!(f, "unstable at h = {h}, after {step} steps (t = {time:.6})")
            }
            Outcome::Failed {
                h,
                step,
                time,
                failure,
            } => {
                write!(
                    f,
                    "step {step} at h = {h} failed (t = {time:.6}): {failure}"
                )
            }
        }
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
    let mut carry = scheme.start(scene, start, h);
    observe(0, 0.0, start);
    for n in 1..=steps {
        let time = n as f64 * h;
        if let Err(failure) = scheme.step(scene, &mut carry, h) {
            let outcome = Outcome::Failed {
                h,
                step: n,
                time,
                failure,
            };
            return (outcome, scheme.solve_tally(&carry));
        }
        let s = scheme.state(&carry, h);
        let size2 = s.q.norm_squared() + (s.v / w).norm_squared();
        if size2.is_nan() || size2 > bound * bound {
            let outcome = Outcome::Unstable { h, step: n, time };
            return (outcome, scheme.solve_tally(&carry));
        }
        observe(n, time, &s);
    }
    (Outcome::Completed, scheme.solve_tally(&carry))
}
