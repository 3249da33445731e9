//! Explicit Runge-Kutta methods on the first-order system `(q, v)' = (v, a(q))`:
//! the classical RK4, written out, and any explicit method as data, one
//! stepper over a Butcher tableau.

use super::{OneStep, PhaseError, SchemeMeta, StepFailure};
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;

/// The classical fourth-order Runge-Kutta method (RK4) on `y = (q, v)`,
/// `y' = f(y) = (v, a(q))`:
/// `k1 = f(y)`, `k2 = f(y + h/2 k1)`, `k3 = f(y + h/2 k2)`, `k4 = f(y + h k3)`,
/// `y' = y + h/6 (k1 + 2 k2 + 2 k3 + k4)`.
///
/// Fourth order with four force evaluations, neither symplectic nor symmetric:
/// on the oscillator each step multiplies the energy by
/// `1 - (h w0)^6/72 + (h w0)^8/576`, so orbits slowly spiral inwards: the
/// non-geometric baseline for the compositions of the same order.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rk4;

impl Rk4 {
    /// What RK4 claims.
    pub const META: SchemeMeta = SchemeMeta {
        id: "rk4",
        name: "classical Runge-Kutta (RK4)",
        order: 4,
        symplectic: false,
        symmetric: false,
        force_evaluations: 4,
        implicit: false,
        reference: "W. Kutta, Z. Math. Phys. 46, 435 (1901); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.1",
        // eigenvalue R(iz) = (1 - z^2/2 + z^4/24) + i (z - z^3/6): its real and
        // imaginary parts are cos z + z^6/720 and sin z - z^5/120 to leading
        // order, so w_num h = z - z^5/120 + ...
        phase_error: Some(PhaseError {
            coefficient: -1.0 / 120.0,
            power: 4,
        }),
    };
}

impl OneStep for Rk4 {
    fn meta(&self) -> &SchemeMeta {
        &Self::META
    }

    #[inline(always)]
    fn advance<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let half = h * R::of(0.5);
        // the q-slopes are velocities, the v-slopes accelerations
        let (k1q, k1v) = (s.v, scene.acceleration(&s.q));
        let k2q = s.v + k1v * half;
        let k2v = scene.acceleration(&(s.q + k1q * half));
        let k3q = s.v + k2v * half;
        let k3v = scene.acceleration(&(s.q + k2q * half));
        let k4q = s.v + k3v * h;
        let k4v = scene.acceleration(&(s.q + k3q * h));
        let sixth = h / R::of(6.0);
        let two = R::of(2.0);
        s.q += (k1q + (k2q + k3q) * two + k4q) * sixth;
        s.v += (k1v + (k2v + k3v) * two + k4v) * sixth;
        Ok(())
    }
}

/// An explicit Runge-Kutta method given by its Butcher tableau `(A, b, c)`,
/// applied to the first-order system `y = (q, v)`, `y' = f(y) = (v, a(q))`:
/// stage `i` is `Y_i = y + h sum_j a_ij k_j` with `k_j = f(Y_j)`, and the step
/// `y' = y + h sum_i b_i k_i`. `A` is strictly lower triangular (checked
/// when the constant is built by [`ExplicitRk::new`]); the system is
/// autonomous, so `c` only documents the tableau (`c_i = sum_j a_ij`) and is
/// used by the tests of the order conditions.
///
/// One force evaluation per stage; a zero entry costs nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExplicitRk<const S: usize> {
    /// The scheme's claims; `force_evaluations` is `S`, set by `new`.
    pub meta: SchemeMeta,
    /// The Runge-Kutta matrix, strictly lower triangular.
    pub a: [[f64; S]; S],
    /// The weights.
    pub b: [f64; S],
    /// The nodes.
    pub c: [f64; S],
}

impl<const S: usize> ExplicitRk<S> {
    /// The method with this tableau and these claims (`force_evaluations`
    /// replaced by the number of stages). Fails to compile if `a` is not
    /// strictly lower triangular.
    pub const fn new(mut meta: SchemeMeta, a: [[f64; S]; S], b: [f64; S], c: [f64; S]) -> Self {
        let mut i = 0;
        while i < S {
            let mut j = i;
            while j < S {
                assert!(
                    a[i][j] == 0.0,
                    "an explicit tableau is strictly lower triangular"
                );
                j += 1;
            }
            i += 1;
        }
        meta.force_evaluations = S as u32;
        Self { meta, a, b, c }
    }
}

impl<const S: usize> OneStep for ExplicitRk<S> {
    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    #[inline(always)]
    fn advance<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        // the q-slopes are the stage velocities, the v-slopes accelerations
        let mut kq = [SVector::<R, D>::zeros(); S];
        let mut kv = [SVector::<R, D>::zeros(); S];
        for i in 0..S {
            let (mut q, mut v) = (s.q, s.v);
            for j in 0..i {
                if self.a[i][j] != 0.0 {
                    let w = h * R::of(self.a[i][j]);
                    q += kq[j] * w;
                    v += kv[j] * w;
                }
            }
            kq[i] = v;
            kv[i] = scene.acceleration(&q);
        }
        let (mut dq, mut dv) = (SVector::<R, D>::zeros(), SVector::<R, D>::zeros());
        for i in 0..S {
            if self.b[i] != 0.0 {
                dq += kq[i] * R::of(self.b[i]);
                dv += kv[i] * R::of(self.b[i]);
            }
        }
        s.q += dq * h;
        s.v += dv * h;
        Ok(())
    }
}
