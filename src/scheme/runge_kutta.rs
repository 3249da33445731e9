//! Explicit Runge-Kutta methods on the first-order system `(q, v)' = (v, a(q))`.

use super::{OneStep, PhaseError, SchemeMeta, StepFailure};
use crate::scene::Scene;
use crate::state::{Real, State};

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
