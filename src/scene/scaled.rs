//! A scene in other units of length: the same motion, with every position
//! and velocity multiplied by a constant. Newton's equations are unchanged by
//! it, and so is every scheme that combines states and forces linearly (every
//! Runge-Kutta, splitting, composition and multistep method), so a run in the
//! scaled units is the same run up to round-off, which it draws anew: every
//! number it computes differs from the original's in all its low bits.

use super::{Scene, SceneMeta};
use crate::state::{Real, State};
use nalgebra::SVector;

/// `scene` with lengths multiplied by `factor`: `q' = factor q`, `v' =
/// factor v`, `a'(q') = factor a(q' / factor)`, `V'(q') = factor^2 V(q' /
/// factor)`.
///
/// ```
/// use stepladder::scene::{Harmonic, Scaled, Scene};
/// let osc = Harmonic::default();
/// let scaled = Scaled::new(osc, 3.0);
/// assert_eq!(scaled.initial().q[0], 3.0 * osc.initial().q[0]);
/// let (there, back) = (osc.exact(1.0).unwrap(), scaled.back(&scaled.exact(1.0).unwrap()));
/// assert!(osc.phase_distance(&there, &back) < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scaled<S> {
    inner: S,
    factor: f64,
}

impl<S> Scaled<S> {
    /// `inner` in units `factor` times smaller.
    pub fn new(inner: S, factor: f64) -> Self {
        Self { inner, factor }
    }

    /// A state of the scaled scene in the original units.
    pub fn back<const D: usize>(&self, s: &State<D>) -> State<D> {
        State::new(s.q / self.factor, s.v / self.factor)
    }
}

impl<S: Scene<D>, const D: usize> Scene<D> for Scaled<S> {
    fn meta(&self) -> SceneMeta {
        self.inner.meta()
    }
    fn initial(&self) -> State<D> {
        let s = self.inner.initial();
        State::new(s.q * self.factor, s.v * self.factor)
    }
    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        let f = R::of(self.factor);
        self.inner.acceleration(&(q / f)) * f
    }
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R {
        let f = R::of(self.factor);
        self.inner.potential(&(q / f)) * f * f
    }
    fn period(&self) -> f64 {
        self.inner.period()
    }
    fn exact(&self, t: f64) -> Option<State<D>> {
        self.inner
            .exact(t)
            .map(|s| State::new(s.q * self.factor, s.v * self.factor))
    }
    fn default_t_end(&self) -> f64 {
        self.inner.default_t_end()
    }
    fn scale(&self) -> f64 {
        self.inner.scale() * self.factor
    }
    fn invariants(&self) -> &'static [crate::scene::Invariant] {
        self.inner.invariants()
    }
    /// The inner scene's invariant, in these units: its value times
    /// `factor^k` for an invariant of length power `k`, its sensitivity (per
    /// unit of the scaled distance) times `factor^(k - 1)`.
    fn invariant(
        &self,
        which: crate::scene::Invariant,
        s: &State<D>,
    ) -> Option<crate::scene::InvariantValue> {
        let k = which.length_power();
        self.inner
            .invariant(which, &self.back(s))
            .map(|i| crate::scene::InvariantValue {
                value: i.value * self.factor.powi(k),
                sensitivity: i.sensitivity * self.factor.powi(k - 1),
            })
    }
}
