//! The phase-space point a scheme advances, and the scalar it is made of.

use nalgebra::{RealField, SVector};
use serde::{Deserialize, Serialize};

/// The scalar a step is computed in.
///
/// Plain `f64` for every trajectory; a dual number (any `nalgebra::RealField`
/// that is `Copy`) when a study differentiates a step, so schemes and scenes are
/// written once, generically, and monomorphised to the same machine code as a
/// hand-written `f64` loop.
pub trait Real: RealField + Copy {
    /// The constant `x` in this scalar type (exact for `f64`).
    #[inline(always)]
    fn of(x: f64) -> Self {
        nalgebra::convert(x)
    }
}

impl<T: RealField + Copy> Real for T {}

/// Position `q` and velocity `v` of a `D`-dimensional scene at one instant.
///
/// Time is not stored: runs use `t = n h` exactly, so nothing accumulates
/// round-off in the clock. The oscillator is `State<1>`, the orbit `State<2>`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct State<const D: usize, R: Real = f64> {
    /// Position.
    pub q: SVector<R, D>,
    /// Velocity.
    pub v: SVector<R, D>,
}

impl<const D: usize, R: Real> State<D, R> {
    /// A state from its position and velocity.
    pub fn new(q: SVector<R, D>, v: SVector<R, D>) -> Self {
        Self { q, v }
    }
}

impl<const D: usize> State<D> {
    /// True when every component is finite (no overflow, no NaN).
    pub fn is_finite(&self) -> bool {
        self.q.iter().chain(self.v.iter()).all(|x| x.is_finite())
    }

    /// The same state in another scalar type (into dual numbers, say).
    pub fn to<R: Real>(&self) -> State<D, R> {
        State::new(self.q.map(R::of), self.v.map(R::of))
    }
}

/// `x` as a plain `f64` when `R` is `f64` (a study's trajectory), `None` in
/// any other scalar (dual numbers): for schemes that compute in a type of
/// their own and must know whether they are being differentiated.
#[doc(hidden)]
pub fn as_f64<R: Real>(x: R) -> Option<f64> {
    (&x as &dyn std::any::Any).downcast_ref::<f64>().copied()
}
