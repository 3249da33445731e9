//! Counting the force calls a scheme makes: the counting step, the counted
//! runs, and the evaluations per step cost figures charge. The claim is
//! judged above this, in `evaluations.rs`; the stability and cost studies
//! read the count from here.

use crate::run::{Outcome, caught, integrate};
use crate::scene::{Counted, Scene};
use crate::scheme::Scheme;

/// Steps of the shorter counting run; the longer one takes twice as many.
/// 60 = 3 x 4 x 5: every cost period up to 6 divides it.
pub const COUNT_STEPS: u64 = 60;

/// The step [`crate::study::evaluations()`] counts at in the guards: `10^-4` of the
/// scene's period. An explicit scheme's count does not depend on the step,
/// and over the `2 x 60` steps of the longer run (1.2% of a period) no
/// scheme leaves the scene's bounds: even explicit Euler, whose energy grows
/// by a factor `1 + (h w)^2` a step, grows it by `1 + 120 (2 pi 10^-4)^2 =
/// 1 + 5e-5`, while a hundredth of the period let it escape the anharmonic
/// well. An implicit scheme's iterations do depend on the step; they are
/// checked against its own report, at whatever step.
pub fn counting_step<S: Scene<D>, const D: usize>(scene: &S) -> f64 {
    scene.period() * 1e-4
}

/// The evaluations of `steps` steps from the scene's start, counted, and
/// what an implicit scheme's solves report; how the run stopped when a step
/// failed, panicked or the run blew up.
pub(crate) fn counted_run<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    h: f64,
    steps: u64,
) -> Result<(u64, Option<u64>), Outcome> {
    let counted = Counted::new(scene);
    let outcome = integrate(scheme, &counted, &counted.initial(), h, steps, |_, _, _| {});
    if !outcome.completed() {
        return Err(outcome);
    }
    let total = counted.evaluations();
    if !scheme.meta().implicit {
        return Ok((total, None));
    }
    // an implicit scheme's own report of what its solves spent, over the
    // same run (which completed above, so its steps succeed again)
    let reported = caught(|| {
        let mut carry = scheme.start(scene, &scene.initial(), h);
        let before = scheme.solver_evaluations(&carry);
        for _ in 0..steps {
            scheme.step(scene, &mut carry, h).ok()?;
        }
        match (before, scheme.solver_evaluations(&carry)) {
            (Some(b), Some(a)) => Some(a - b),
            _ => None,
        }
    })
    .ok()
    .flatten();
    Ok((total, reported))
}

/// The evaluations per step cost figures charge an explicit scheme: the
/// counted ones (see [`crate::study::evaluations()`], which judges the same count), or the claim where nothing could be
/// counted (a scheme unstable at the counting step).
pub fn per_step_charged<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) -> f64 {
    let h = counting_step(scene);
    match (
        counted_run(scheme, scene, h, COUNT_STEPS),
        counted_run(scheme, scene, h, 2 * COUNT_STEPS),
    ) {
        (Ok((short, _)), Ok((long, _))) => (long - short) as f64 / COUNT_STEPS as f64,
        _ => f64::from(scheme.meta().force_evaluations),
    }
}
