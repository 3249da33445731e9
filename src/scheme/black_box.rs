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
//! (see [`crate::maths::tangent::tangent_map`]), and round-off
//! floors and tolerances follow from the scalar's epsilon.
//!
//! ```
//! use stepladder::guard;
//! use stepladder::scene::KeplerCircular;
//! use stepladder::scheme::{BlackBox, Force, SchemeMeta};
//!
//! /// Somebody else's velocity Verlet, on `f64` slices.
//! fn verlet(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
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
//! Integrators in other shapes (a first-order system on `y = [q, v]`, a step
//! on `(q, p)`, a step on the integrator's own vector type, a right-hand
//! side on slices) are adapted by [`BlackBox::first_order`],
//! [`BlackBox::canonical`], [`BlackBox::on_vectors`] and, combined with
//! state kept between steps or a reported solve, by the [`super::Shape`]
//! pieces passed to [`BlackBox::stateful`] and [`BlackBox::implicit`].

use crate::scene::Scene;
use crate::scheme::{Scheme, SchemeMeta, StepFailure};
use crate::state::{Real, State, as_f64};
use nalgebra::SVector;
use serde::Serialize;
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
///
/// It is an `Fn` behind a shared reference, so a crate that calls its
/// right-hand side through `&self` (a `System::system(&self, ..)` trait
/// method) can hold `&Force` in its system type and call it directly.
pub type Force<'a, T> = dyn Fn(&[T], &mut [T]) + 'a;

/// A step function as a plain `fn`: the type of `BlackBox<T, StepFn<T>>`
/// when the step is a named function.
pub type StepFn<T> = fn(&mut [T], &mut [T], T, &Force<'_, T>);

/// A scheme given as a step function `step(q, v, h, force)` on slices of
/// `T` (`f64` or `f32`), with the claims it makes.
///
/// The step advances `q` and `v` in place by one step of size `h`, calling
/// `force(q, a)` for accelerations. A step that keeps something between
/// steps (a last force, a history, a warm start) is built with
/// [`BlackBox::stateful`]; the other constructors adapt the shapes
/// integrators come in (a first-order system, a `(q, p)` step, a step on
/// the integrator's own vector type).
///
/// Every study counts the force calls a step makes and compares them with
/// `force_evaluations` (see [`crate::study::cost::evaluations`]).
pub struct BlackBox<T, F> {
    meta: SchemeMeta,
    step: F,
    scalar: PhantomData<fn() -> T>,
}

/// A black box's step, stateless or with state it keeps between steps.
/// Implemented for every plain step function and for [`Stateful`]; users
/// build one through the [`BlackBox`] constructors.
pub trait BlackBoxStep<T> {
    /// What the step keeps between steps (`()` for a plain step).
    type Kept: Clone + Send + Sync;
    /// The state at the start of a run.
    fn fresh(&self) -> Self::Kept;
    /// One step of size `h`, or why it could not be taken.
    fn advance(
        &self,
        kept: &mut Self::Kept,
        q: &mut [T],
        v: &mut [T],
        h: T,
        force: &Force<'_, T>,
    ) -> Result<(), StepFailure>;
    /// The solves of the run so far, for a step that reports them
    /// ([`BlackBox::implicit`]); `None` otherwise.
    fn tally(&self, _kept: &Self::Kept) -> Option<SolveTally> {
        None
    }
}

/// What one step of an implicit integrator reports of its solve: the
/// iterations it took and the residual it stopped at (in the integrator's
/// own norm). A solve stopped at a fixed tolerance leaves an error of about
/// that residual in every step, which no step size removes: beside the
/// error of each rung, the tally shows where such a floor comes from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Solve {
    /// Iterations of the solve in this step.
    pub iterations: u32,
    /// The residual the solve stopped at.
    pub residual: f64,
}

/// The solves of one run: how many steps reported, their iterations in
/// all, and the largest residual any stopped at (NaN if any was NaN).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct SolveTally {
    /// Steps whose solve was reported.
    pub steps: u64,
    /// Iterations over those steps.
    pub iterations: u64,
    /// The largest final residual.
    pub largest_residual: f64,
}

impl SolveTally {
    /// Adds one step's solve.
    pub fn add(&mut self, solve: Solve) {
        self.steps += 1;
        self.iterations += u64::from(solve.iterations);
        // a NaN residual stays, rather than vanishing into the maximum
        if !self.largest_residual.is_nan()
            && (solve.residual.is_nan() || solve.residual > self.largest_residual)
        {
            self.largest_residual = solve.residual;
        }
    }

    /// Mean iterations per step (NaN before the first step).
    pub fn iterations_per_step(&self) -> f64 {
        self.iterations as f64 / self.steps as f64
    }
}

/// What a wrapped step returns: nothing (`()`), its solve ([`Solve`], for
/// [`BlackBox::implicit`]), or either in a `Result` whose `Err` says why the
/// step could not be taken (a solve that did not converge, a vector type
/// that cannot hold the scene's state). A failed step ends the run and is
/// reported as a breakdown at that step, never as instability.
pub trait StepReturn<R> {
    /// The step's result.
    fn into_step(self) -> Result<R, StepFailure>;
}

impl StepReturn<()> for () {
    fn into_step(self) -> Result<(), StepFailure> {
        Ok(())
    }
}

impl StepReturn<Solve> for Solve {
    fn into_step(self) -> Result<Solve, StepFailure> {
        Ok(self)
    }
}

impl<R> StepReturn<R> for Result<R, StepFailure> {
    fn into_step(self) -> Result<R, StepFailure> {
        self
    }
}

impl<T, F, O> BlackBoxStep<T> for F
where
    F: Fn(&mut [T], &mut [T], T, &Force<'_, T>) -> O,
    O: StepReturn<()>,
{
    type Kept = ();
    fn fresh(&self) {}
    #[inline(always)]
    fn advance(
        &self,
        _: &mut (),
        q: &mut [T],
        v: &mut [T],
        h: T,
        force: &Force<'_, T>,
    ) -> Result<(), StepFailure> {
        (self)(q, v, h, force).into_step()
    }
}

/// A step with state kept between steps: `fresh()` makes the state a run
/// starts from, `step(state, q, v, h, force)` advances by one step. Built by
/// [`BlackBox::stateful`].
pub struct Stateful<I, F> {
    fresh: I,
    step: F,
}

impl<T, K, I, F, O> BlackBoxStep<T> for Stateful<I, F>
where
    K: Clone + Send + Sync,
    I: Fn() -> K,
    F: Fn(&mut K, &mut [T], &mut [T], T, &Force<'_, T>) -> O,
    O: StepReturn<()>,
{
    type Kept = K;
    fn fresh(&self) -> K {
        (self.fresh)()
    }
    #[inline(always)]
    fn advance(
        &self,
        kept: &mut K,
        q: &mut [T],
        v: &mut [T],
        h: T,
        force: &Force<'_, T>,
    ) -> Result<(), StepFailure> {
        (self.step)(kept, q, v, h, force).into_step()
    }
}

impl<T: Float, F> BlackBox<T, F> {
    /// Wraps `step` with its claims. The step returns nothing, or
    /// `Result<(), StepFailure>` to say why it could not be taken.
    pub const fn new<O>(meta: SchemeMeta, step: F) -> Self
    where
        F: Fn(&mut [T], &mut [T], T, &Force<'_, T>) -> O,
        O: StepReturn<()>,
    {
        Self {
            meta,
            step,
            scalar: PhantomData,
        }
    }
}

impl<T: Float> BlackBox<T, ()> {
    /// Wraps a step that keeps state between steps: a first-same-as-last
    /// force, a multistep history, a warm-started implicit solve, an
    /// integrator object with its caches. Every run (each rung of a ladder,
    /// each twin of a round-off estimate, each direction of a round trip)
    /// starts from `fresh()`, so no run sees another's state.
    ///
    /// ```
    /// use stepladder::guard;
    /// use stepladder::scene::Harmonic;
    /// use stepladder::scheme::{BlackBox, Force, VELOCITY_VERLET};
    ///
    /// /// Velocity Verlet that reuses the force of the step before: one
    /// /// evaluation per step once it has started.
    /// fn reusing(last: &mut Option<[f64; 1]>, q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    ///     let mut a = last.unwrap_or_else(|| {
    ///         let mut a = [0.0];
    ///         force(q, &mut a);
    ///         a
    ///     });
    ///     v[0] += 0.5 * h * a[0];
    ///     q[0] += h * v[0];
    ///     force(q, &mut a);
    ///     v[0] += 0.5 * h * a[0];
    ///     *last = Some(a);
    /// }
    /// let theirs = BlackBox::stateful(*VELOCITY_VERLET.meta(), || None, reusing);
    /// guard::assert_order(&theirs, &Harmonic::default());
    /// guard::assert_evaluations(&theirs, &Harmonic::default());
    /// # use stepladder::scheme::Scheme;
    /// ```
    pub const fn stateful<K, I, S, O>(
        meta: SchemeMeta,
        fresh: I,
        step: S,
    ) -> BlackBox<T, Stateful<I, S>>
    where
        K: Clone + Send + Sync,
        I: Fn() -> K,
        S: Fn(&mut K, &mut [T], &mut [T], T, &Force<'_, T>) -> O,
        O: StepReturn<()>,
    {
        BlackBox {
            meta,
            step: Stateful { fresh, step },
            scalar: PhantomData,
        }
    }
}

/// An implicit step that reports its solve, with state kept between steps:
/// `step(state, q, v, h, force)` advances by one step and returns the
/// [`Solve`]. Built by [`BlackBox::implicit`].
pub struct Implicit<I, F> {
    fresh: I,
    step: F,
}

impl<T, K, I, F, O> BlackBoxStep<T> for Implicit<I, F>
where
    K: Clone + Send + Sync,
    I: Fn() -> K,
    F: Fn(&mut K, &mut [T], &mut [T], T, &Force<'_, T>) -> O,
    O: StepReturn<Solve>,
{
    type Kept = (K, SolveTally);
    fn fresh(&self) -> Self::Kept {
        ((self.fresh)(), SolveTally::default())
    }
    #[inline(always)]
    fn advance(
        &self,
        kept: &mut Self::Kept,
        q: &mut [T],
        v: &mut [T],
        h: T,
        force: &Force<'_, T>,
    ) -> Result<(), StepFailure> {
        let solve = (self.step)(&mut kept.0, q, v, h, force).into_step()?;
        kept.1.add(solve);
        Ok(())
    }
    fn tally(&self, kept: &Self::Kept) -> Option<SolveTally> {
        Some(kept.1)
    }
}

impl<T: Float> BlackBox<T, ()> {
    /// Wraps an implicit step that reports its solve (iterations and final
    /// residual) each step, with state kept between steps as in
    /// [`BlackBox::stateful`]. The claims are marked implicit, and
    /// `force_evaluations` is read per iteration: the evaluations claim
    /// compares the calls counted with the iterations reported times that
    /// claim, and the order study shows each rung's iterations per step and
    /// largest residual beside its error.
    ///
    /// ```
    /// use stepladder::guard;
    /// use stepladder::scene::Harmonic;
    /// use stepladder::scheme::{BlackBox, Force, SchemeMeta, Solve};
    ///
    /// /// The implicit midpoint rule, its stage solved by fixed-point
    /// /// iteration to round-off: one force evaluation per iteration.
    /// fn midpoint(_: &mut (), q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) -> Solve {
    ///     let (q0, v0) = (q[0], v[0]);
    ///     let (mut vm, mut a) = (v0, [0.0]);
    ///     for iterations in 1..=100 {
    ///         force(&[q0 + 0.5 * h * vm], &mut a);
    ///         let next = v0 + 0.5 * h * a[0];
    ///         let residual = (next - vm).abs();
    ///         vm = next;
    ///         if residual <= 4.0 * f64::EPSILON * vm.abs().max(1.0) {
    ///             q[0] = q0 + h * vm;
    ///             v[0] = 2.0 * vm - v0;
    ///             return Solve { iterations, residual };
    ///         }
    ///     }
    ///     Solve { iterations: 100, residual: f64::NAN }
    /// }
    /// let theirs = BlackBox::implicit(
    ///     SchemeMeta {
    ///         id: "their-midpoint",
    ///         name: "implicit midpoint, fixed-point iteration",
    ///         order: 2,
    ///         symplectic: true,
    ///         symmetric: true,
    ///         force_evaluations: 1, // per iteration
    ///         implicit: true,
    ///         reference: "their crate",
    ///         phase_error: None,
    ///     },
    ///     || (),
    ///     midpoint,
    /// );
    /// guard::assert_order(&theirs, &Harmonic::default());
    /// guard::assert_evaluations(&theirs, &Harmonic::default());
    /// ```
    pub const fn implicit<K, I, S, O>(
        meta: SchemeMeta,
        fresh: I,
        step: S,
    ) -> BlackBox<T, Implicit<I, S>>
    where
        K: Clone + Send + Sync,
        I: Fn() -> K,
        S: Fn(&mut K, &mut [T], &mut [T], T, &Force<'_, T>) -> O,
        O: StepReturn<Solve>,
    {
        BlackBox {
            meta: SchemeMeta {
                implicit: true,
                ..meta
            },
            step: Implicit { fresh, step },
            scalar: PhantomData,
        }
    }
}

/// The carry of a black box: the synchronised state and what the step
/// keeps.
#[derive(Clone)]
pub struct BlackBoxCarry<R: Real, const D: usize, K> {
    state: State<D, R>,
    kept: K,
}

impl<R: Real, const D: usize, K> Debug for BlackBoxCarry<R, D, K> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // the kept state is the integrator's own business
        f.debug_struct("BlackBoxCarry")
            .field("state", &self.state)
            .finish_non_exhaustive()
    }
}

impl<T: Float, F: BlackBoxStep<T>> BlackBox<T, F> {
    /// One step of the wrapped integrator from `(q, v)`, in place, with the
    /// force `force` and what a run keeps starting fresh: a wrapped step
    /// probed directly, without a scene or a study.
    ///
    /// ```
    /// use stepladder::scheme::{BlackBox, Force, SchemeMeta};
    ///
    /// let verlet = BlackBox::new(
    ///     SchemeMeta::new("their-verlet", "velocity Verlet", 2).force_evaluations(2),
    ///     |q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>| {
    ///         let mut a = [0.0];
    ///         force(q, &mut a);
    ///         v[0] += 0.5 * h * a[0];
    ///         q[0] += h * v[0];
    ///         force(q, &mut a);
    ///         v[0] += 0.5 * h * a[0];
    ///     },
    /// );
    /// let (mut q, mut v) = ([1.0], [0.0]);
    /// verlet.step_once(&mut q, &mut v, 0.5, &|x: &[f64], a: &mut [f64]| a[0] = -x[0])?;
    /// // on q'' = -q from (1, 0): q = 1 - h^2/2, v = -h (1 - h^2/4)
    /// assert_eq!((q[0], v[0]), (0.875, -0.46875));
    /// # Ok::<(), stepladder::scheme::StepFailure>(())
    /// ```
    pub fn step_once(
        &self,
        q: &mut [T],
        v: &mut [T],
        h: T,
        force: &Force<'_, T>,
    ) -> Result<(), StepFailure> {
        let mut kept = self.step.fresh();
        self.step.advance(&mut kept, q, v, h, force)
    }
}

/// A black box's step with the type of its step and of what it keeps
/// hidden, so that black boxes of every shape and from every crate are one
/// type, [`AnyBlackBox`], and fit one `Vec` (see [`BlackBox::boxed`]).
/// What the step keeps is boxed once per run, at its start; a step makes one
/// dynamic call and allocates nothing.
pub struct AnyStep<T>(Box<dyn ErasedStep<T> + Send + Sync>);

/// What an [`AnyStep`] keeps between steps: the wrapped step's state.
pub struct AnyKept(Box<dyn KeptState>);

/// A kept state that can be cloned behind a box.
trait KeptState: Any + Send + Sync {
    fn clone_box(&self) -> Box<dyn KeptState>;
    fn as_any_mut(&mut self) -> &mut dyn Any;
    fn as_any(&self) -> &dyn Any;
}

impl<K: Clone + Send + Sync + 'static> KeptState for K {
    fn clone_box(&self) -> Box<dyn KeptState> {
        Box::new(self.clone())
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
}

impl Clone for AnyKept {
    fn clone(&self) -> Self {
        AnyKept(self.0.clone_box())
    }
}

/// [`BlackBoxStep`] with its kept state behind [`AnyKept`].
trait ErasedStep<T> {
    fn fresh(&self) -> AnyKept;
    fn advance(
        &self,
        kept: &mut AnyKept,
        q: &mut [T],
        v: &mut [T],
        h: T,
        force: &Force<'_, T>,
    ) -> Result<(), StepFailure>;
    fn tally(&self, kept: &AnyKept) -> Option<SolveTally>;
}

impl<T, F> ErasedStep<T> for F
where
    F: BlackBoxStep<T>,
    F::Kept: 'static,
{
    fn fresh(&self) -> AnyKept {
        AnyKept(Box::new(BlackBoxStep::fresh(self)))
    }
    fn advance(
        &self,
        kept: &mut AnyKept,
        q: &mut [T],
        v: &mut [T],
        h: T,
        force: &Force<'_, T>,
    ) -> Result<(), StepFailure> {
        // the kept state was made by this step's `fresh`: its type is F::Kept
        let kept = kept
            .0
            .as_any_mut()
            .downcast_mut::<F::Kept>()
            .expect("the kept state of this step");
        BlackBoxStep::advance(self, kept, q, v, h, force)
    }
    fn tally(&self, kept: &AnyKept) -> Option<SolveTally> {
        let kept = kept.0.as_any().downcast_ref::<F::Kept>()?;
        BlackBoxStep::tally(self, kept)
    }
}

impl<T> BlackBoxStep<T> for AnyStep<T> {
    type Kept = AnyKept;
    fn fresh(&self) -> AnyKept {
        self.0.fresh()
    }
    fn advance(
        &self,
        kept: &mut AnyKept,
        q: &mut [T],
        v: &mut [T],
        h: T,
        force: &Force<'_, T>,
    ) -> Result<(), StepFailure> {
        self.0.advance(kept, q, v, h, force)
    }
    fn tally(&self, kept: &AnyKept) -> Option<SolveTally> {
        self.0.tally(kept)
    }
}

/// A black box of any shape: what [`BlackBox::boxed`] returns, so that
/// integrators wrapped by different constructors, from different crates,
/// are held in one `Vec` and guarded in one loop.
pub type AnyBlackBox<T = f64> = BlackBox<T, AnyStep<T>>;

impl<T: 'static, F> BlackBox<T, F>
where
    F: BlackBoxStep<T> + Send + Sync + 'static,
    F::Kept: 'static,
{
    /// The same black box with its step's type hidden: every constructor's
    /// result becomes an [`AnyBlackBox`], whatever its shape and whatever it
    /// keeps between steps.
    ///
    /// ```
    /// use stepladder::scene::Harmonic;
    /// use stepladder::scheme::{AnyBlackBox, BlackBox, Force, SchemeMeta};
    /// use stepladder::study::claims;
    ///
    /// fn euler_cromer(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    ///     let mut a = [0.0];
    ///     force(q, &mut a);
    ///     v[0] += h * a[0];
    ///     q[0] += h * v[0];
    /// }
    /// let kept_force = BlackBox::stateful(
    ///     SchemeMeta::new("kept-force-verlet", "velocity Verlet, last force kept", 2)
    ///         .symplectic()
    ///         .symmetric(),
    ///     || None::<f64>,
    ///     |last: &mut Option<f64>, q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>| {
    ///         let mut a = [0.0];
    ///         let first = last.unwrap_or_else(|| {
    ///             force(q, &mut a);
    ///             a[0]
    ///         });
    ///         v[0] += 0.5 * h * first;
    ///         q[0] += h * v[0];
    ///         force(q, &mut a);
    ///         v[0] += 0.5 * h * a[0];
    ///         *last = Some(a[0]);
    ///     },
    /// );
    /// let all: Vec<AnyBlackBox> = vec![
    ///     BlackBox::new(
    ///         SchemeMeta::new("their-euler-cromer", "Euler-Cromer", 1).symplectic(),
    ///         euler_cromer as fn(&mut [f64], &mut [f64], f64, &Force<f64>),
    ///     )
    ///     .boxed(),
    ///     kept_force.boxed(),
    /// ];
    /// for integrator in &all {
    ///     let record = claims(integrator, &Harmonic::default())?;
    ///     assert!(record.passed(), "{:?}", record.failures());
    /// }
    /// # Ok::<(), stepladder::error::Error>(())
    /// ```
    pub fn boxed(self) -> AnyBlackBox<T> {
        BlackBox {
            meta: self.meta,
            step: AnyStep(Box::new(self.step)),
            scalar: PhantomData,
        }
    }
}

impl<T, F> Scheme for BlackBox<T, F>
where
    T: Float,
    F: BlackBoxStep<T>,
{
    type Carry<R: Real, const D: usize> = BlackBoxCarry<R, D, F::Kept>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        _: &S,
        state: &State<D, R>,
        _: R,
    ) -> Self::Carry<R, D> {
        BlackBoxCarry {
            state: *state,
            kept: self.step.fresh(),
        }
    }

    fn state<R: Real, const D: usize>(&self, carry: &Self::Carry<R, D>, _: R) -> State<D, R> {
        carry.state
    }

    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        carry: &mut Self::Carry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        let state = plain::<State<D, R>, State<D, f64>>(&mut carry.state);
        let h = as_f64(h).expect("an f64 state comes with an f64 step");
        let mut q = [T::default(); D];
        let mut v = [T::default(); D];
        for i in 0..D {
            q[i] = T::from_f64(state.q[i]);
            v[i] = T::from_f64(state.v[i]);
        }
        let force = |x: &[T], a: &mut [T]| {
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
        self.step
            .advance(&mut carry.kept, &mut q, &mut v, T::from_f64(h), &force)?;
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

    /// For an implicit black box that reports its solves: the iterations
    /// reported times the evaluations claimed per iteration.
    fn solver_evaluations<R: Real, const D: usize>(
        &self,
        carry: &Self::Carry<R, D>,
    ) -> Option<u64> {
        let tally = self.step.tally(&carry.kept)?;
        Some(tally.iterations * u64::from(self.meta.force_evaluations))
    }

    fn solve_tally<R: Real, const D: usize>(
        &self,
        carry: &Self::Carry<R, D>,
    ) -> Option<SolveTally> {
        self.step.tally(&carry.kept)
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
        force: &Force<T>,
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
        use crate::study::accuracy::phase::phase_error;
        use crate::study::hard::eccentric::{OrderStatus, eccentric_order};
        use crate::study::stability::stability;
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
            Some(crate::study::verdict::Verdict::Pass),
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
    fn a_tally_keeps_the_largest_residual_and_a_nan() {
        let mut t = SolveTally::default();
        for (iterations, residual) in [(3, 1e-9), (5, 4e-9), (1, 2e-9)] {
            t.add(Solve {
                iterations,
                residual,
            });
        }
        assert_eq!((t.steps, t.iterations, t.largest_residual), (3, 9, 4e-9));
        assert_eq!(t.iterations_per_step(), 3.0);
        // a solve that ended on NaN is not hidden by a later finite one
        t.add(Solve {
            iterations: 2,
            residual: f64::NAN,
        });
        t.add(Solve {
            iterations: 2,
            residual: 1.0,
        });
        assert!(t.largest_residual.is_nan());
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
