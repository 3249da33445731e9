//! What an adaptive integrator is, to the studies: something that, given a
//! scene, a start, an end time and a tolerance, chooses its own steps and
//! reports every accepted one with what it cost.

use crate::error::Error;
use crate::scene::Scene;
use crate::scheme::SchemeVisitor;
use crate::state::State;
use serde::Serialize;
use std::time::Duration;

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RunEnd {
    /// It reached `t_end`.
    Reached,
    /// It took the most steps it may take.
    StepLimit,
    /// Its step fell below what the clock can resolve (`t + h == t`).
    StepUnderflow,
    /// It gave up for another reason of its own (a stiffness detector).
    GaveUp,
}

impl RunEnd {
    /// The kebab-case name used in tables.
    pub fn name(self) -> &'static str {
        match self {
            RunEnd::Reached => "reached",
            RunEnd::StepLimit => "step-limit",
            RunEnd::StepUnderflow => "step-underflow",
            RunEnd::GaveUp => "gave-up",
        }
    }
}

/// One adaptive run.
#[derive(Clone, Debug)]
pub struct AdaptiveRun<const D: usize> {
    /// `(t, state)` at the start and after every accepted step.
    pub trajectory: Vec<(f64, State<D>)>,
    /// Force evaluations, rejected steps and the initial step guess
    /// included.
    pub evaluations: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// How the run ended.
    pub end: RunEnd,
    /// Wall time of the run (machine-dependent; never in a deterministic
    /// record).
    pub time: Duration,
    /// What the integrator reported it spent, where that differs in source
    /// from `evaluations` (a black box's own statistics, against the calls
    /// counted on its force callback); `None` where the count is the only
    /// figure.
    pub reported_evaluations: Option<u64>,
}

/// What an adaptive integrator's theory predicts, for the studies to check.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AdaptiveClaims {
    /// Order `p` of the solution it advances with.
    pub order: u32,
    /// The power of `h` its error estimate behaves like, asymptotically:
    /// `q + 1` for an estimate from an embedded solution of order `q`.
    pub estimate_power: u32,
    /// The global error against the tolerance it should show, `~ TOL^k`
    /// (`None` where theory predicts no single exponent over the ladder):
    /// see [`proportionality_exponent`].
    pub proportionality: Option<f64>,
    /// The method is symplectic (no adaptive pair here is).
    pub symplectic: bool,
    /// The method is time-symmetric (no adaptive pair here is).
    pub symmetric: bool,
    /// A bound the user states on the achieved error: at every tolerance
    /// the ladder resolves, the global error is at most `factor x TOL`
    /// (`None`: nothing claimed). Set with [`AdaptiveClaims::within`].
    pub error_factor: Option<f64>,
}

impl AdaptiveClaims {
    /// The same claims with the achieved-error bound `error <= factor x
    /// TOL` stated.
    pub const fn within(self, factor: f64) -> Self {
        Self {
            error_factor: Some(factor),
            ..self
        }
    }
}

/// An integrator that chooses its own steps for a tolerance. Relative and
/// absolute tolerance are the same `tol` (the scenes' states are of order
/// one), each component's error measured against `tol (1 + max(|y0|,
/// |y1|))`, as the classical codes do.
pub trait AdaptiveIntegrator: Sync {
    /// Its name in tables.
    fn name(&self) -> &'static str;

    /// What its theory predicts.
    fn claims(&self) -> AdaptiveClaims;

    /// Runs from `start` at `t = 0` to `t_end` at tolerance `tol`. A
    /// non-positive or non-finite `tol` or `t_end` is refused, as is a scene
    /// the integrator cannot represent.
    fn integrate<S: Scene<D>, const D: usize>(
        &self,
        scene: &S,
        start: &State<D>,
        t_end: f64,
        tol: f64,
    ) -> Result<AdaptiveRun<D>, Error>;

    /// The fixed-step method this integrator advances with, handed to
    /// `visitor` (`None` where it has none). The tolerance ladder runs it at
    /// the ladder's steps, against the scene's exact solution, to tell a
    /// method not yet at its asymptotic order there from a controller that
    /// misses its claim.
    fn visit_fixed_step<V: SchemeVisitor>(&self, _visitor: V) -> Option<V::Output> {
        None
    }

    /// [`AdaptiveIntegrator::integrate`] from the scene's initial state.
    fn run<S: Scene<D>, const D: usize>(
        &self,
        scene: &S,
        t_end: f64,
        tol: f64,
    ) -> Result<AdaptiveRun<D>, Error> {
        self.integrate(scene, &scene.initial(), t_end, tol)
    }
}

/// Refuses a tolerance or end time that is not a finite positive number.
pub fn check_request(t_end: f64, tol: f64) -> Result<(), Error> {
    crate::scene::positive("t_end", t_end)?;
    crate::scene::positive("tolerance", tol)?;
    Ok(())
}

/// The exponent `k` of `e ~ TOL^k` for an error-per-step controller whose
/// estimate behaves like `h^estimate_power`, advancing with an order-`order`
/// solution: `k = order / estimate_power` (see the tolerance ladder's documentation).
pub fn proportionality_exponent(order: u32, estimate_power: u32) -> f64 {
    order as f64 / estimate_power.max(1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_exponent_follows_the_powers() {
        // order 6 with an estimate of power 5 (error per step): 6/5
        assert_eq!(proportionality_exponent(6, 5), 1.2);
        assert_eq!(proportionality_exponent(8, 8), 1.0);
        // a power of 0 is read as 1, never a division by zero
        assert_eq!(proportionality_exponent(4, 0), 4.0);
    }
}
