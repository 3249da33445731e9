//! A scene given by its potential alone: the force is `-grad V` by automatic
//! differentiation, so a user models only the energy, the start and the time
//! scale.

use crate::scene::{Scene, SceneMeta};
use crate::state::{Real, State};
use nalgebra::SVector;
use num_dual::{Dual64, HyperDual64};
use std::any::Any;

/// What a user states about a problem `q'' = -grad V(q)`: the potential,
/// generic in the scalar so that it can be differentiated, where it starts,
/// its time scale and, if known, its exact solution.
///
/// ```
/// use nalgebra::{SVector, Vector1};
/// use stepladder::guard;
/// use stepladder::scene::{FromPotential, Potential, SceneMeta};
/// use stepladder::scheme::VELOCITY_VERLET;
/// use stepladder::state::{Real, State};
///
/// /// The pendulum `V = -cos q` started at 1 radian.
/// struct Pendulum;
/// impl Potential<1> for Pendulum {
///     fn meta(&self) -> SceneMeta {
///         SceneMeta {
///             id: "pendulum",
///             name: "pendulum from 1 rad",
///             dimension: 1,
///             parameters: "q0 = 1".into(),
///             reference: "V = -cos q",
///         }
///     }
///     fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
///         -q[0].cos()
///     }
///     fn initial(&self) -> State<1> {
///         State::new(Vector1::new(1.0), Vector1::new(0.0))
///     }
///     fn period(&self) -> f64 {
///         6.70 // 2 pi / w0 lengthened by the amplitude; a time scale is enough
///     }
/// }
///
/// let scene = FromPotential(Pendulum);
/// guard::assert_order(&VELOCITY_VERLET, &scene); // no exact solution: half-step references
/// guard::assert_energy(&VELOCITY_VERLET, &scene);
/// ```
pub trait Potential<const D: usize> {
    /// Identity and parameters.
    fn meta(&self) -> SceneMeta;

    /// The potential energy per unit mass.
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R;

    /// The state at `t = 0`.
    fn initial(&self) -> State<D>;

    /// The natural time scale (the period of the motion, or of small
    /// oscillations about it): steps are chosen as fractions of it.
    fn period(&self) -> f64;

    /// The exact state at time `t`, if known; without it the studies use
    /// half-step references and Richardson estimates.
    fn exact(&self, _t: f64) -> Option<State<D>> {
        None
    }
}

/// The scene of a [`Potential`]: its acceleration `-grad V` is computed by
/// forward-mode automatic differentiation, `D` passes of `V` in dual numbers
/// per force evaluation (in hyper-dual numbers when a study takes the
/// tangent map, which needs the force's own derivative).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FromPotential<P>(pub P);

impl<P: Potential<D>, const D: usize> Scene<D> for FromPotential<P> {
    fn meta(&self) -> SceneMeta {
        self.0.meta()
    }

    fn initial(&self) -> State<D> {
        self.0.initial()
    }

    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        let mut a = SVector::<R, D>::zeros();
        let out = &mut a as &mut dyn Any;
        let q = q as &dyn Any;
        if let (Some(q), Some(out)) = (
            q.downcast_ref::<SVector<f64, D>>(),
            out.downcast_mut::<SVector<f64, D>>(),
        ) {
            *out = gradient(&self.0, q).map(|g| -g);
        } else if let (Some(q), Some(out)) = (
            q.downcast_ref::<SVector<f32, D>>(),
            out.downcast_mut::<SVector<f32, D>>(),
        ) {
            // a single-precision scheme's force: computed in f64, rounded once
            *out = gradient(&self.0, &q.map(f64::from)).map(|g| -g as f32);
        } else if let (Some(q), Some(out)) = (
            q.downcast_ref::<SVector<Dual64, D>>(),
            out.downcast_mut::<SVector<Dual64, D>>(),
        ) {
            *out = dual_gradient(&self.0, q).map(|g| -g);
        } else {
            panic!(
                "stepladder: a scene from a potential differentiates V in f64, f32 and Dual64, \
                 not in {}",
                std::any::type_name::<R>()
            );
        }
        a
    }

    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R {
        self.0.potential(q)
    }

    fn period(&self) -> f64 {
        self.0.period()
    }

    fn exact(&self, t: f64) -> Option<State<D>> {
        self.0.exact(t)
    }
}

/// `grad V(q)`, one dual-number pass per component.
fn gradient<P: Potential<D>, const D: usize>(p: &P, q: &SVector<f64, D>) -> SVector<f64, D> {
    SVector::from_fn(|i, _| {
        let mut x = q.map(Dual64::from_re);
        x[i].eps = 1.0;
        p.potential(&x).eps
    })
}

/// `grad V` at a dual-number position `q + eps dq`: each component's value
/// and its derivative along `dq`, `d/dq_i V` and `sum_j d2V/dq_i dq_j dq_j`,
/// from one hyper-dual pass (`eps1` along `e_i`, `eps2` along `dq`).
fn dual_gradient<P: Potential<D>, const D: usize>(
    p: &P,
    q: &SVector<Dual64, D>,
) -> SVector<Dual64, D> {
    SVector::from_fn(|i, _| {
        let x = SVector::<HyperDual64, D>::from_fn(|j, _| {
            HyperDual64::new(q[j].re, if i == j { 1.0 } else { 0.0 }, q[j].eps, 0.0)
        });
        let v = p.potential(&x);
        Dual64::new(v.eps1, v.eps1eps2)
    })
}
