//! A scene with its exact solution withheld, so that a study measures it the
//! way it measures a scene that has none: against the scheme itself at half
//! the step. Comparing the two measurements tests the harness, not the scheme.

use super::{Scene, SceneMeta};
use crate::state::{Real, State};
use nalgebra::SVector;

/// `scene` without its exact solution.
///
/// ```
/// use stepladder::scene::{Harmonic, Hidden, Scene};
/// let hidden = Hidden(Harmonic::default());
/// assert!(Harmonic::default().exact(1.0).is_some());
/// assert!(hidden.exact(1.0).is_none());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Hidden<S>(pub S);

impl<S: Scene<D>, const D: usize> Scene<D> for Hidden<S> {
    fn meta(&self) -> SceneMeta {
        self.0.meta()
    }
    fn initial(&self) -> State<D> {
        self.0.initial()
    }
    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        self.0.acceleration(q)
    }
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R {
        self.0.potential(q)
    }
    fn period(&self) -> f64 {
        self.0.period()
    }
    fn exact(&self, _: f64) -> Option<State<D>> {
        None
    }
    fn invariants(&self) -> &'static [crate::scene::Invariant] {
        self.0.invariants()
    }
    fn invariant(
        &self,
        which: crate::scene::Invariant,
        s: &State<D>,
    ) -> Option<crate::scene::InvariantValue> {
        self.0.invariant(which, s)
    }
    fn default_t_end(&self) -> f64 {
        self.0.default_t_end()
    }
    fn phase_distance(&self, a: &State<D>, b: &State<D>) -> f64 {
        self.0.phase_distance(a, b)
    }
    fn scale(&self) -> f64 {
        self.0.scale()
    }
}
