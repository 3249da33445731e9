//! Verlet's two original formulations, which carry more than `(q, v)`.
//!
//! Both are algebraically the same map as velocity Verlet once their velocities
//! are synchronised; they differ in what they store and so in round-off.

use super::{Scheme, SchemeMeta, StepFailure, VERLET_PHASE};
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;

/// The original two-step Störmer-Verlet scheme: positions only,
/// `q(n+1) = 2 q(n) - q(n-1) + h^2 a(q(n))`.
///
/// Start-up: the carry at step 0 holds the fictitious previous position
/// `q(-1) = q0 - h v0 + h^2/2 a(q0)` (a second-order Taylor step backwards), so
/// the first step reproduces the Taylor start `q(1) = q0 + h v0 + h^2/2 a(q0)`.
/// Output velocities are central differences `(q(n+1) - q(n-1)) / 2h`, with
/// `q(n+1)` formed from the stored `a(q(n))`: no extra force evaluation.
#[derive(Clone, Copy, Debug, Default)]
pub struct StormerVerlet;

/// Two successive positions and the acceleration at the later one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoStep<R: Real, const D: usize> {
    /// `q(n-1)`.
    pub previous: SVector<R, D>,
    /// `q(n)`.
    pub current: SVector<R, D>,
    /// `a(q(n))`.
    pub a: SVector<R, D>,
}

impl<R: Real, const D: usize> TwoStep<R, D> {
    /// `q(n+1) = 2 q(n) - q(n-1) + h^2 a(q(n))`.
    #[inline(always)]
    fn next(&self, h: R) -> SVector<R, D> {
        (self.current * R::of(2.0) - self.previous) + self.a * (h * h)
    }
}

impl StormerVerlet {
    /// What the two-step scheme claims.
    pub const META: SchemeMeta = SchemeMeta {
        id: "stormer-verlet",
        name: "Störmer-Verlet (two-step, positions only)",
        order: 2,
        symplectic: true,
        symmetric: true,
        force_evaluations: 1,
        implicit: false,
        reference: "L. Verlet, Phys. Rev. 159, 98 (1967); C. Störmer (1907); the lecture's original Verlet",
        phase_error: VERLET_PHASE,
    };
}

impl Scheme for StormerVerlet {
    type Carry<R: Real, const D: usize> = TwoStep<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &Self::META
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &State<D, R>,
        h: R,
    ) -> TwoStep<R, D> {
        let a = scene.acceleration(&s.q);
        TwoStep {
            previous: s.q - s.v * h + a * (h * h * R::of(0.5)),
            current: s.q,
            a,
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut TwoStep<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        let next = c.next(h);
        c.previous = c.current;
        c.current = next;
        c.a = scene.acceleration(&next);
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &TwoStep<R, D>, h: R) -> State<D, R> {
        State::new(c.current, (c.next(h) - c.previous) / (h * R::of(2.0)))
    }
}

/// Leap-frog as in the lecture: positions at whole steps, velocities at half
/// steps, `q(n+1) = q(n) + h v(n+1/2)`, `v(n+3/2) = v(n+1/2) + h a(q(n+1))`.
///
/// Start-up: `v(1/2) = v0 + h/2 a(q0)`. Output velocities are synchronised to
/// whole steps as `v(n) = v(n+1/2) - h/2 a(q(n))`, with the stored acceleration.
#[derive(Clone, Copy, Debug, Default)]
pub struct Leapfrog;

/// A whole-step position, the velocity half a step later, and `a(q)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Staggered<R: Real, const D: usize> {
    /// `q(n)`.
    pub q: SVector<R, D>,
    /// `v(n + 1/2)`.
    pub v_half: SVector<R, D>,
    /// `a(q(n))`.
    pub a: SVector<R, D>,
}

impl Leapfrog {
    /// What leap-frog claims.
    pub const META: SchemeMeta = SchemeMeta {
        id: "leapfrog",
        name: "leap-frog (half-step velocities)",
        order: 2,
        symplectic: true,
        symmetric: true,
        force_evaluations: 1,
        implicit: false,
        reference: "R. W. Hockney, J. W. Eastwood, Computer Simulation Using Particles (1981); the lecture's leap-frog",
        phase_error: VERLET_PHASE,
    };
}

impl Scheme for Leapfrog {
    type Carry<R: Real, const D: usize> = Staggered<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &Self::META
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &State<D, R>,
        h: R,
    ) -> Staggered<R, D> {
        let a = scene.acceleration(&s.q);
        Staggered {
            q: s.q,
            v_half: s.v + a * (h * R::of(0.5)),
            a,
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut Staggered<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        c.q += c.v_half * h;
        c.a = scene.acceleration(&c.q);
        c.v_half += c.a * h;
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &Staggered<R, D>, h: R) -> State<D, R> {
        State::new(c.q, c.v_half - c.a * (h * R::of(0.5)))
    }
}
