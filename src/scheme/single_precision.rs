//! Any generic scheme, run in single precision: the scheme and the scene's
//! force both compute in `f32`, as a game or graphics engine would.

use crate::scene::Scene;
use crate::scheme::{Scheme, SchemeMeta, StepFailure};
use crate::state::{Real, State, as_f64};
use std::any::Any;

/// Runs the scheme `M` in `f32` whenever a study runs it on `f64` states:
/// the state is rounded to `f32` at the start, every stage and force
/// evaluation is computed in `f32`, and the studies read the result back
/// exactly. Round-off floors and tolerances follow from `f32::EPSILON`.
///
/// In dual numbers (the tangent map) the scheme runs in those, so the
/// symplecticity study measures the map itself, exactly; single precision
/// does not change which map the scheme is.
///
/// ```
/// use stepladder::study::{global_order, OrderSpec};
/// use stepladder::scene::Harmonic;
/// use stepladder::scheme::{SinglePrecision, VELOCITY_VERLET};
///
/// let record = global_order(&SinglePrecision(VELOCITY_VERLET), &Harmonic::default(), &OrderSpec::default())?;
/// assert!(record.passed(), "{}", record.reason);
/// // the ladder stops at the f32 round-off floor, about 1e-7 of the motion
/// let finest = record.rungs.last().unwrap();
/// assert!(finest.error.unwrap() > 1e-9);
/// # Ok::<(), stepladder::error::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct SinglePrecision<M>(pub M);

/// The carry of [`SinglePrecision`]: the inner scheme's carry in `f32` when
/// run on `f64` states, in the study's own scalar otherwise.
#[derive(Clone, Debug)]
pub enum SingleCarry<W, N> {
    /// The inner carry in the study's scalar (dual numbers).
    Wide(W),
    /// The inner carry in `f32`.
    Narrow(N),
}

impl<M: Scheme> Scheme for SinglePrecision<M> {
    type Carry<R: Real, const D: usize> = SingleCarry<M::Carry<R, D>, M::Carry<f32, D>>;

    fn meta(&self) -> &SchemeMeta {
        self.0.meta()
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        state: &State<D, R>,
        h: R,
    ) -> Self::Carry<R, D> {
        match (
            (state as &dyn Any).downcast_ref::<State<D, f64>>(),
            as_f64(h),
        ) {
            (Some(s), Some(h)) => {
                let narrow = State::new(s.q.map(|x| x as f32), s.v.map(|x| x as f32));
                SingleCarry::Narrow(self.0.start(scene, &narrow, h as f32))
            }
            _ => SingleCarry::Wide(self.0.start(scene, state, h)),
        }
    }

    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        carry: &mut Self::Carry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        match carry {
            SingleCarry::Narrow(c) => {
                let h = as_f64(h).expect("a narrow carry is only made for f64 studies");
                self.0.step(scene, c, h as f32)
            }
            SingleCarry::Wide(c) => self.0.step(scene, c, h),
        }
    }

    fn state<R: Real, const D: usize>(&self, carry: &Self::Carry<R, D>, h: R) -> State<D, R> {
        match carry {
            SingleCarry::Narrow(c) => {
                let h = as_f64(h).expect("a narrow carry is only made for f64 studies");
                let s = self.0.state(c, h as f32);
                State::new(s.q.map(|x| R::of(x as f64)), s.v.map(|x| R::of(x as f64)))
            }
            SingleCarry::Wide(c) => self.0.state(c, h),
        }
    }

    fn solver_evaluations<R: Real, const D: usize>(
        &self,
        carry: &Self::Carry<R, D>,
    ) -> Option<u64> {
        match carry {
            SingleCarry::Narrow(c) => self.0.solver_evaluations(c),
            SingleCarry::Wide(c) => self.0.solver_evaluations(c),
        }
    }

    fn epsilon(&self) -> f64 {
        f32::EPSILON as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::KeplerCircular;
    use crate::scheme::Rk4;

    #[test]
    fn single_precision_runs_in_f32_and_reads_back_exactly() {
        let m = SinglePrecision(Rk4);
        let scene = KeplerCircular;
        let h = 0.01;
        let mut c = m.start(&scene, &scene.initial(), h);
        for _ in 0..100 {
            m.step(&scene, &mut c, h).unwrap();
        }
        let s = m.state(&c, h);
        assert!(
            s.q.iter()
                .chain(s.v.iter())
                .all(|&x| x == (x as f32) as f64)
        );
        let exact = scene.exact(1.0).unwrap();
        // RK4's own error at h = 0.01 yr is 1e-8 AU; f32 round-off over 100 steps is ~1e-6
        let d = (s.q - exact.q).amax();
        assert!(d > 1e-9 && d < 1e-4, "{d:e}");
        assert_eq!(m.epsilon(), f32::EPSILON as f64);
    }
}
