//! A wrapper that counts force evaluations, to check what a scheme's
//! metadata claims and to measure cost in evaluations.

use super::{Scene, SceneMeta};
use crate::state::{Real, State};
use nalgebra::SVector;
use std::cell::Cell;

/// `scene`, counting every call of `acceleration`.
///
/// ```
/// use stepladder::scene::{Counted, Harmonic, Scene};
/// use stepladder::scheme::{Scheme, VELOCITY_VERLET};
/// let scene = Counted::new(Harmonic::default());
/// let mut carry = VELOCITY_VERLET.start(&scene, &scene.initial(), 0.1);
/// for _ in 0..100 {
///     VELOCITY_VERLET.step(&scene, &mut carry, 0.1).unwrap();
/// }
/// // one evaluation to start, then one per step
/// assert_eq!(scene.evaluations(), 101);
/// ```
#[derive(Clone, Debug, Default)]
pub struct Counted<S> {
    inner: S,
    count: Cell<u64>,
}

impl<S> Counted<S> {
    /// Wraps `inner` with the count at zero.
    pub fn new(inner: S) -> Self {
        Self {
            inner,
            count: Cell::new(0),
        }
    }

    /// Force evaluations so far.
    pub fn evaluations(&self) -> u64 {
        self.count.get()
    }

    /// Sets the count back to zero.
    pub fn reset(&self) {
        self.count.set(0);
    }
}

impl<S: Scene<D>, const D: usize> Scene<D> for Counted<S> {
    fn meta(&self) -> SceneMeta {
        self.inner.meta()
    }
    fn initial(&self) -> State<D> {
        self.inner.initial()
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        self.count.set(self.count.get() + 1);
        self.inner.acceleration(q)
    }
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R {
        self.inner.potential(q)
    }
    fn period(&self) -> f64 {
        self.inner.period()
    }
    fn exact(&self, t: f64) -> Option<State<D>> {
        self.inner.exact(t)
    }
    fn invariants(&self) -> &'static [crate::scene::Invariant] {
        self.inner.invariants()
    }
    fn invariant(
        &self,
        which: crate::scene::Invariant,
        s: &State<D>,
    ) -> Option<crate::scene::InvariantValue> {
        self.inner.invariant(which, s)
    }
    fn default_t_end(&self) -> f64 {
        self.inner.default_t_end()
    }
}
