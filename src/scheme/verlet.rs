//! Verlet's two original formulations, which carry more than `(q, v)`.
//!
//! Both are algebraically the same map as velocity Verlet once their velocities
//! are synchronised; they differ in what they store and so in round-off.

use super::summation::{Rounded, Summable, Summation, rounded_scheme};
use super::{Scheme, SchemeMeta, StepFailure, VERLET_PHASE};
use crate::scene::Scene;
use crate::state::{Real, State};

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

/// Two successive positions, summed by `S`, and the acceleration at the
/// later one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoStep<R: Real, const D: usize, S: Summation = Rounded> {
    /// `q(n-1)`.
    pub previous: S::Sum<R, D>,
    /// `q(n)`.
    pub current: S::Sum<R, D>,
    /// `a(q(n))`, at the rounded position.
    pub a: nalgebra::SVector<R, D>,
}

impl<R: Real, const D: usize, S: Summation> TwoStep<R, D, S> {
    /// `q(n+1) = 2 q(n) - q(n-1) + h^2 a(q(n))`.
    #[inline(always)]
    fn next(&self, h: R) -> S::Sum<R, D> {
        S::two_step(&self.current, &self.previous, self.a * (h * h))
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

impl Summable for StormerVerlet {
    type Carry<R: Real, const D: usize, S: Summation> = TwoStep<R, D, S>;

    fn start_summed<S: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        s: &State<D, R>,
        h: R,
    ) -> TwoStep<R, D, S> {
        let a = scene.acceleration(&s.q);
        let mut previous = S::new(s.q);
        S::add(&mut previous, -(s.v * h));
        S::add(&mut previous, a * (h * h * R::of(0.5)));
        TwoStep {
            previous,
            current: S::new(s.q),
            a,
        }
    }

    #[inline(always)]
    fn step_summed<S: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        c: &mut TwoStep<R, D, S>,
        h: R,
    ) -> Result<(), StepFailure> {
        let next = c.next(h);
        c.previous = c.current;
        c.current = next;
        c.a = scene.acceleration(&S::value(&next));
        Ok(())
    }

    fn state_summed<S: Summation, R: Real, const D: usize>(
        &self,
        c: &TwoStep<R, D, S>,
        h: R,
    ) -> State<D, R> {
        let difference = S::difference(&c.next(h), &c.previous);
        State::new(S::value(&c.current), difference / (h * R::of(2.0)))
    }

    /// The velocity is a difference already taken with the low parts.
    fn compensation_summed<S: Summation, R: Real, const D: usize>(
        &self,
        c: &TwoStep<R, D, S>,
        _: R,
    ) -> State<D, R> {
        State::new(S::low(&c.current), nalgebra::SVector::zeros())
    }
}

/// Leap-frog as in the lecture: positions at whole steps, velocities at half
/// steps, `q(n+1) = q(n) + h v(n+1/2)`, `v(n+3/2) = v(n+1/2) + h a(q(n+1))`.
///
/// Start-up: `v(1/2) = v0 + h/2 a(q0)`. Output velocities are synchronised to
/// whole steps as `v(n) = v(n+1/2) - h/2 a(q(n))`, with the stored acceleration.
#[derive(Clone, Copy, Debug, Default)]
pub struct Leapfrog;

/// A whole-step position, the velocity half a step later, both summed by
/// `S`, and `a(q)` at the rounded position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Staggered<R: Real, const D: usize, S: Summation = Rounded> {
    /// `q(n)`.
    pub q: S::Sum<R, D>,
    /// `v(n + 1/2)`.
    pub v_half: S::Sum<R, D>,
    /// `a(q(n))`.
    pub a: nalgebra::SVector<R, D>,
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

impl Summable for Leapfrog {
    type Carry<R: Real, const D: usize, S: Summation> = Staggered<R, D, S>;

    fn start_summed<S: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        s: &State<D, R>,
        h: R,
    ) -> Staggered<R, D, S> {
        let a = scene.acceleration(&s.q);
        let mut v_half = S::new(s.v);
        S::add(&mut v_half, a * (h * R::of(0.5)));
        Staggered {
            q: S::new(s.q),
            v_half,
            a,
        }
    }

    #[inline(always)]
    fn step_summed<S: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        c: &mut Staggered<R, D, S>,
        h: R,
    ) -> Result<(), StepFailure> {
        S::add(&mut c.q, S::value(&c.v_half) * h);
        c.a = scene.acceleration(&S::value(&c.q));
        S::add(&mut c.v_half, c.a * h);
        Ok(())
    }

    fn state_summed<S: Summation, R: Real, const D: usize>(
        &self,
        c: &Staggered<R, D, S>,
        h: R,
    ) -> State<D, R> {
        State::new(
            S::value(&c.q),
            S::plus(&c.v_half, -(c.a * (h * R::of(0.5)))),
        )
    }

    /// The synchronised velocity is a sum already taken with the low part.
    fn compensation_summed<S: Summation, R: Real, const D: usize>(
        &self,
        c: &Staggered<R, D, S>,
        _: R,
    ) -> State<D, R> {
        State::new(S::low(&c.q), nalgebra::SVector::zeros())
    }
}

rounded_scheme!(StormerVerlet, |_scheme| &StormerVerlet::META);
rounded_scheme!(Leapfrog, |_scheme| &Leapfrog::META);
