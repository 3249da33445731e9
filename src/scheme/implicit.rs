//! Implicit schemes: each step solves an equation, here by fixed-point
//! iteration to round-off, with a bounded number of iterations and a
//! [`StepFailure::NotConverged`] instead of a wrong state when the solve fails.
//!
//! For an implicit scheme [`SchemeMeta::force_evaluations`] counts evaluations
//! per iteration of the solve: the iterations a step needs depend on the step
//! size and the scene, so no count per step would be true. The iterations
//! actually spent are read off the carry with [`Scheme::solver_iterations`], and
//! evaluations = iterations x `force_evaluations`.

use super::{PhaseError, Scheme, SchemeMeta, StepFailure};
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;

/// Most fixed-point iterations one step may take. The iteration contracts by
/// `rho = h^2 L / 4` (`L` the Lipschitz constant of `a`); from a predictor
/// whose error is a fraction of the orbit, 64 iterations reach round-off for
/// any `rho < 0.55`. A step that needs more is far too large for this solve
/// and is reported as not converged.
pub const MAX_ITERATIONS: u32 = 64;

/// A correction below this many units of round-off of the terms that make
/// the midpoint means the iterate has stopped moving by more than the
/// rounding of its own formula: the iteration then ends as soon as the
/// correction stops shrinking (the floating-point fixed point).
pub const ROUND_OFF_UNITS: f64 = 8.0;

/// The implicit midpoint rule, `y1 = y0 + h f((y0 + y1)/2)` on `y = (q, v)`:
/// `q1 = q0 + h (v0 + v1)/2`, `v1 = v0 + h a((q0 + q1)/2)`.
///
/// Second order, symplectic and symmetric (the one-stage Gauss method); on the
/// oscillator it is the Cayley transform of the rotation and conserves the
/// energy exactly. The step solves for the midpoint `m = (q0 + q1)/2`,
/// `m = q0 + h/2 v0 + h^2/4 a(m)`, by fixed-point iteration (one force
/// evaluation per iteration) from the predictor `q0 + h/2 v0 + h^2/4 a_prev`
/// (`a_prev` the previous step's midpoint acceleration, so the predictor is
/// already `O(h^3)` accurate), then sets `v1 = v0 + h a(m)`, `q1 = 2 m - q0`.
#[derive(Clone, Copy, Debug, Default)]
pub struct ImplicitMidpoint;

/// What the implicit midpoint rule carries between steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MidpointCarry<R: Real, const D: usize> {
    /// The synchronised state.
    pub state: State<D, R>,
    /// The acceleration at the last step's midpoint, the next predictor's
    /// (zero before the first step: no force evaluation to start).
    pub a: SVector<R, D>,
    /// Iterations the last step took, converged or not (0 before the first).
    pub last_iterations: u32,
    /// Iterations since `start`, failed solves included: every iteration is
    /// one force evaluation.
    pub iterations: u64,
}

impl ImplicitMidpoint {
    /// What the implicit midpoint rule claims; `force_evaluations` is per
    /// iteration of the solve (see the module documentation).
    pub const META: SchemeMeta = SchemeMeta {
        id: "implicit-midpoint",
        name: "implicit midpoint rule (fixed-point solve)",
        order: 2,
        symplectic: true,
        symmetric: true,
        force_evaluations: 1,
        implicit: true,
        reference: "E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration (2006), I.1.2 and VI.3",
        // eigenvalues (1 + i z/2) / (1 - i z/2): w_num h = 2 atan(z/2) = z - z^3/12 + ...
        phase_error: Some(PhaseError {
            coefficient: -1.0 / 12.0,
            power: 2,
        }),
    };
}

impl Scheme for ImplicitMidpoint {
    type Carry<R: Real, const D: usize> = MidpointCarry<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &Self::META
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        _: &S,
        s: &State<D, R>,
        _: R,
    ) -> MidpointCarry<R, D> {
        MidpointCarry {
            state: *s,
            a: SVector::zeros(),
            last_iterations: 0,
            iterations: 0,
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut MidpointCarry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        let (q0, v0) = (c.state.q, c.state.v);
        let base = q0 + v0 * (h * R::of(0.5));
        let c2 = h * h * R::of(0.25);
        let mut m = base + c.a * c2;
        // the rounding of `base + c2 a` is at most a few units of this size
        let terms = q0.norm_squared() + base.norm_squared();
        let units = R::of(ROUND_OFF_UNITS) * R::default_epsilon();
        let mut correction = R::zero();
        let mut previous: Option<R> = None;
        for k in 1..=MAX_ITERATIONS {
            let a = scene.acceleration(&m);
            let next = base + a * c2;
            correction = (next - m).norm_squared();
            m = next;
            let size = terms + (a * c2).norm_squared();
            // Within round-off, keep iterating while the correction still
            // shrinks: stopping short of the floating-point fixed point
            // leaves a bias of the same sign every step, which adds up to a
            // secular energy drift of the (exactly energy-conserving) rule.
            let settled = correction == R::zero() || previous.is_some_and(|p| correction >= p);
            if correction <= units * units * size && (settled || k == MAX_ITERATIONS) {
                c.last_iterations = k;
                c.iterations += k as u64;
                c.state = State::new(m * R::of(2.0) - q0, v0 + a * h);
                c.a = a;
                return Ok(());
            }
            // an overflowed or NaN iterate never converges: stop spending on it
            if !correction.is_finite() {
                c.last_iterations = k;
                c.iterations += k as u64;
                return Err(not_converged(k, correction));
            }
            previous = Some(correction);
        }
        c.last_iterations = MAX_ITERATIONS;
        c.iterations += MAX_ITERATIONS as u64;
        Err(not_converged(MAX_ITERATIONS, correction))
    }

    fn state<R: Real, const D: usize>(&self, c: &MidpointCarry<R, D>, _: R) -> State<D, R> {
        c.state
    }

    fn solver_iterations<R: Real, const D: usize>(&self, c: &MidpointCarry<R, D>) -> Option<u64> {
        Some(c.iterations)
    }
}

/// The failure after `iterations`, with the last correction's size.
fn not_converged<R: Real>(iterations: u32, correction_squared: R) -> StepFailure {
    StepFailure::NotConverged {
        iterations,
        residual: correction_squared.sqrt().to_subset().unwrap_or(f64::NAN),
    }
}
