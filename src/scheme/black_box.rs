//! Integrators that only run on plain floats: a step function on position and
//! velocity slices, written for `f64` or `f32`, from any crate.
//!
//! Most integrators in the wild are not generic over the scalar: they are
//! written on `f64` (or `f32` in games and graphics), on their own vector
//! types, often inside a library the user does not control. [`BlackBox`]
//! turns such a step into a [`Scheme`]: the studies hand it the position and
//! velocity as slices and a force callback, and read the result back. Every
//! study works on it; the tangent map, which the generic schemes give exactly
//! through dual numbers, is taken by finite differences with a bounded error
//! (see [`crate::measure::geometry::tangent::tangent_map`]), and round-off
//! floors and tolerances follow from the scalar's epsilon.
//!
//! ```
//! use stepladder::guard;
//! use stepladder::scene::KeplerCircular;
//! use stepladder::scheme::{BlackBox, Force, SchemeMeta};
//!
//! /// Somebody else's velocity Verlet, on `f64` slices.
//! fn verlet(q: &mut [f64], v: &mut [f64], h: f64, force: &mut Force<f64>) {
//!     let mut a = [0.0; 2];
//!     force(q, &mut a);
//!     for i in 0..q.len() {
//!         v[i] += 0.5 * h * a[i];
//!         q[i] += h * v[i];
//!     }
//!     force(q, &mut a);
//!     for i in 0..q.len() {
//!         v[i] += 0.5 * h * a[i];
//!     }
//! }
//!
//! let theirs = BlackBox::new(
//!     SchemeMeta {
//!         id: "their-verlet",
//!         name: "velocity Verlet from another crate",
//!         order: 2,
//!         symplectic: true,
//!         symmetric: true,
//!         force_evaluations: 2, // it does not reuse the last force
//!         implicit: false,
//!         reference: "their crate",
//!         phase_error: None,
//!     },
//!     verlet,
//! );
//! guard::assert_order(&theirs, &KeplerCircular);
//! guard::assert_symplectic(&theirs, &KeplerCircular);
//! ```
//!
//! An integrator on its own vector type needs a small adapter: copy the
//! slices into the type, call the step, copy back. The copies cost a few
//! loads and stores per step, and nothing is allocated.

use crate::scene::Scene;
use crate::scheme::{Scheme, SchemeMeta, StepFailure};
use crate::state::{Real, State, as_f64};
use nalgebra::SVector;
use std::any::Any;
use std::fmt::Debug;
use std::marker::PhantomData;

/// The plain floating-point types a black-box step may be written in.
pub trait Float: Copy + Default + Debug + PartialOrd + Send + Sync + 'static {
    /// The unit round-off of the type, as an `f64`.
    const EPSILON: f64;
    /// `x` rounded to this type.
    fn from_f64(x: f64) -> Self;
    /// The value as an `f64` (exact for `f32` and `f64`).
    fn to_f64(self) -> f64;
}

impl Float for f64 {
    const EPSILON: f64 = f64::EPSILON;
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
}

impl Float for f32 {
    const EPSILON: f64 = f32::EPSILON as f64;
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
}

/// The force callback a black-box step receives: writes the acceleration at
/// the positions in the first slice into the second. One call is one force
/// evaluation. The scene computes it in `f64` and rounds it to `T`.
pub type Force<'a, T> = dyn FnMut(&[T], &mut [T]) + 'a;

/// A step function as a plain `fn`: the type of `BlackBox<T, StepFn<T>>`
/// when the step is a named function.
pub type StepFn<T> = fn(&mut [T], &mut [T], T, &mut Force<'_, T>);

/// A scheme given as a step function `step(q, v, h, force)` on slices of
/// `T` (`f64` or `f32`), with the claims it makes.
///
/// The step advances `q` and `v` in place by one step of size `h`, calling
/// `force(q, a)` for accelerations. It carries nothing else between steps: a
/// scheme that reuses its last force should declare the evaluations it
/// actually makes per step in `force_evaluations`.
pub struct BlackBox<T, F> {
    meta: SchemeMeta,
    step: F,
    scalar: PhantomData<fn() -> T>,
}

impl<T, F> BlackBox<T, F>
where
    T: Float,
    F: Fn(&mut [T], &mut [T], T, &mut Force<'_, T>),
{
    /// Wraps `step` with its claims.
    pub fn new(meta: SchemeMeta, step: F) -> Self {
        Self {
            meta,
            step,
            scalar: PhantomData,
        }
    }
}

impl<T, F> Scheme for BlackBox<T, F>
where
    T: Float,
    F: Fn(&mut [T], &mut [T], T, &mut Force<'_, T>),
{
    type Carry<R: Real, const D: usize> = State<D, R>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        _: &S,
        state: &State<D, R>,
        _: R,
    ) -> State<D, R> {
        *state
    }

    fn state<R: Real, const D: usize>(&self, state: &State<D, R>, _: R) -> State<D, R> {
        *state
    }

    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        state: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let state = plain::<State<D, R>, State<D, f64>>(state);
        let h = as_f64(h).expect("an f64 state comes with an f64 step");
        let mut q = [T::default(); D];
        let mut v = [T::default(); D];
        for i in 0..D {
            q[i] = T::from_f64(state.q[i]);
            v[i] = T::from_f64(state.v[i]);
        }
        let mut force = |x: &[T], a: &mut [T]| {
            assert!(
                x.len() == D && a.len() == D,
                "stepladder: a black-box force call needs slices of the scene's dimension {D}, \
                 got {} and {}",
                x.len(),
                a.len()
            );
            let acceleration =
                scene.acceleration(&SVector::<f64, D>::from_fn(|i, _| x[i].to_f64()));
            for i in 0..D {
                a[i] = T::from_f64(acceleration[i]);
            }
        };
        (self.step)(&mut q, &mut v, T::from_f64(h), &mut force);
        for i in 0..D {
            state.q[i] = q[i].to_f64();
            state.v[i] = v[i].to_f64();
        }
        Ok(())
    }

    fn differentiable(&self) -> bool {
        false
    }

    fn epsilon(&self) -> f64 {
        T::EPSILON
    }
}

/// `value` as the plain-float type `P` it must be: a black box cannot run
/// in dual numbers, and the studies never ask it to (they check
/// [`crate::scheme::Scheme::differentiable`] first).
fn plain<A: 'static, P: 'static>(value: &mut A) -> &mut P {
    (value as &mut dyn Any)
        .downcast_mut::<P>()
        .unwrap_or_else(|| {
            panic!(
                "stepladder: a black-box scheme runs on f64 states only, not on {}; \
             its tangent map is taken by finite differences",
                std::any::type_name::<A>()
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Harmonic, KeplerCircular};
    use crate::scheme::VELOCITY_VERLET;

    fn kick_drift_kick<T: Float + std::ops::Mul<Output = T> + std::ops::AddAssign>(
        q: &mut [T],
        v: &mut [T],
        h: T,
        force: &mut Force<T>,
    ) {
        let half = T::from_f64(0.5) * h;
        let mut a = [T::default(); 4];
        let a = &mut a[..q.len()];
        force(q, a);
        for i in 0..q.len() {
            v[i] += half * a[i];
            q[i] += h * v[i];
        }
        force(q, a);
        for i in 0..q.len() {
            v[i] += half * a[i];
        }
    }

    fn run<M: Scheme, S: Scene<D>, const D: usize>(m: &M, scene: &S, h: f64, n: usize) -> State<D> {
        let mut c = m.start(scene, &scene.initial(), h);
        for _ in 0..n {
            m.step(scene, &mut c, h).unwrap();
        }
        m.state(&c, h)
    }

    #[test]
    fn an_f64_black_box_reproduces_the_generic_scheme_bit_for_bit() {
        // same operations in the same order: the same rounding
        let bb = BlackBox::new(*VELOCITY_VERLET.meta(), kick_drift_kick::<f64>);
        let h = 0.01;
        let a = run(&bb, &KeplerCircular, h, 1000);
        let b = run(&VELOCITY_VERLET, &KeplerCircular, h, 1000);
        assert_eq!(a, b);
        assert_eq!(bb.epsilon(), f64::EPSILON);
        assert!(!bb.differentiable());
    }

    #[test]
    fn the_other_studies_see_the_same_method_through_the_black_box() {
        use crate::measure::accuracy::phase::phase_error;
        use crate::measure::hard::eccentric::{OrderStatus, eccentric_order};
        use crate::measure::stability::stability;
        let mut meta = *VELOCITY_VERLET.meta();
        meta.force_evaluations = 2;
        meta.phase_error = crate::scheme::VERLET_PHASE;
        let bb = BlackBox::new(meta, kick_drift_kick::<f64>);
        // the linear stability limit of the Verlet family is z = 2
        let (a, b) = (stability(&bb), stability(&VELOCITY_VERLET));
        assert_eq!(a.stability_limit, b.stability_limit);
        assert!(
            (a.stability_limit.unwrap() - 2.0).abs() < 1e-3,
            "{:?}",
            a.stability_limit
        );
        // the phase error, against its analytic z^2 / 24
        let phase = phase_error(&bb);
        assert_eq!(
            phase.verdict,
            Some(crate::measure::Verdict::Pass),
            "{}",
            phase.reason
        );
        // a hard case: the order on the eccentric orbit
        let ecc = eccentric_order(&bb, 0.6, 1 << 20).unwrap();
        assert_eq!(ecc.status, OrderStatus::Pass, "{}", ecc.reason);
    }

    #[test]
    fn an_f32_black_box_rounds_to_single_precision() {
        let bb = BlackBox::new(*VELOCITY_VERLET.meta(), kick_drift_kick::<f32>);
        let osc = Harmonic::default();
        let s = run(&bb, &osc, 0.01, 10);
        // every component is an f32
        assert!(
            s.q.iter()
                .chain(s.v.iter())
                .all(|&x| x == (x as f32) as f64)
        );
        let exact = run(&VELOCITY_VERLET, &osc, 0.01, 10);
        let d = (s.q - exact.q).amax();
        assert!(d > 0.0 && d < 1e-5, "f32 against f64 after 10 steps: {d:e}");
        assert_eq!(bb.epsilon(), f32::EPSILON as f64);
    }

    #[test]
    #[should_panic(expected = "runs on f64 states only")]
    fn a_black_box_refuses_dual_numbers_with_a_clear_message() {
        let bb = BlackBox::new(*VELOCITY_VERLET.meta(), kick_drift_kick::<f64>);
        let s: State<1, num_dual::Dual64> = Harmonic::default().initial().to();
        let mut c = bb.start(&Harmonic::default(), &s, num_dual::Dual64::from_re(0.1));
        let _ = bb.step(&Harmonic::default(), &mut c, num_dual::Dual64::from_re(0.1));
    }
}
