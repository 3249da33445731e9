//! Implicit schemes: each step solves an equation to round-off, with a
//! bounded number of iterations and a [`StepFailure::NotConverged`] instead
//! of a wrong state when the solve fails.
//!
//! For an implicit scheme [`SchemeMeta::force_evaluations`] counts evaluations
//! per fixed-point iteration: the iterations a step needs depend on the step
//! size and the scene, so no count per step would be true. The evaluations
//! actually spent are read off the carry with [`Scheme::solver_evaluations`].

use super::{PhaseError, Scheme, SchemeMeta, StepFailure};
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::{SMatrix, SVector};

/// Most iterations one step may take. The fixed-point iteration contracts by
/// `rho = h^2 L / 4` (`L` the Lipschitz constant of `a`); once it contracts
/// by less than `SWITCH_RATIO` (one half) per iteration the solve turns to Newton's
/// method, which converges quadratically whatever `rho`. A step that still
/// needs more is far too large for the orbit and is reported as not converged.
pub const MAX_ITERATIONS: u32 = 64;

/// The fixed-point iteration gives way to Newton's method when a correction
/// is more than this fraction of the previous one: `rho > 1/2` would need
/// over 50 iterations to reach round-off, and `rho >= 1` never would (the
/// rule is stable for every step on the oscillator; its solve should be too).
pub const SWITCH_RATIO: f64 = 0.5;

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
/// already `O(h^3)` accurate), turning to Newton's method (with a
/// forward-difference Jacobian, `1 + D` evaluations an iteration) if the
/// iteration contracts slowly, then sets `v1 = v0 + h a(m)`, `q1 = 2 m - q0`.
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
    /// Force evaluations spent by the solves since `start`, failed ones
    /// included.
    pub evaluations: u64,
}

impl ImplicitMidpoint {
    /// What the implicit midpoint rule claims; `force_evaluations` is per
    /// fixed-point iteration of the solve (see the module documentation).
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
            evaluations: 0,
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
        let mut newton = false;
        for k in 1..=MAX_ITERATIONS {
            let a = scene.acceleration(&m);
            c.evaluations += 1;
            // the fixed-point correction; Newton's scales it by (I - c2 A)^-1
            let fixed_point = base + a * c2 - m;
            let delta = if newton {
                c.evaluations += D as u64;
                match (SMatrix::<R, D, D>::identity() - jacobian(scene, &m, &a) * c2).try_inverse()
                {
                    Some(inverse) => inverse * fixed_point,
                    None => return Err(fail(&mut c.last_iterations, k, correction)),
                }
            } else {
                fixed_point
            };
            correction = delta.norm_squared();
            let size = terms + (a * c2).norm_squared();
            // Within round-off, keep iterating while the correction still
            // shrinks: stopping short of the floating-point fixed point
            // leaves a bias of the same sign every step, which adds up to a
            // secular energy drift of the (exactly energy-conserving) rule.
            let settled = correction == R::zero() || previous.is_some_and(|p| correction >= p);
            if correction <= units * units * size && (settled || k == MAX_ITERATIONS) {
                c.last_iterations = k;
                // the midpoint in the rule's own form, so that q1 and v1 use
                // the very same acceleration: q1 = q0 + h (v0 + v1) / 2 exactly
                let m = base + a * c2;
                c.state = State::new(m * R::of(2.0) - q0, v0 + a * h);
                c.a = a;
                return Ok(());
            }
            // an overflowed or NaN iterate never converges: stop spending on it
            if !correction.is_finite() {
                return Err(fail(&mut c.last_iterations, k, correction));
            }
            // a fixed-point iteration contracting by less than SWITCH_RATIO
            // per step is too slow (or diverging): Newton from here on
            if previous.is_some_and(|p| correction > p * R::of(SWITCH_RATIO * SWITCH_RATIO)) {
                newton = true;
            }
            m += delta;
            previous = Some(correction);
        }
        Err(fail(&mut c.last_iterations, MAX_ITERATIONS, correction))
    }

    fn state<R: Real, const D: usize>(&self, c: &MidpointCarry<R, D>, _: R) -> State<D, R> {
        c.state
    }

    fn solver_evaluations<R: Real, const D: usize>(&self, c: &MidpointCarry<R, D>) -> Option<u64> {
        Some(c.evaluations)
    }
}

/// Records a failed solve of `iterations` iterations in the carry's count
/// (its state stays as it was) and describes it.
fn fail<R: Real>(last_iterations: &mut u32, iterations: u32, correction_squared: R) -> StepFailure {
    *last_iterations = iterations;
    StepFailure::NotConverged {
        iterations,
        residual: correction_squared.sqrt().to_subset().unwrap_or(f64::NAN),
    }
}

/// `da/dq` at `m` by forward differences (`a = a(m)` given), `D` force
/// evaluations. Newton needs only an approximation of it: the residual it
/// drives to zero is exact, so the solve still ends at round-off.
fn jacobian<R: Real, const D: usize, S: Scene<D>>(
    scene: &S,
    m: &SVector<R, D>,
    a: &SVector<R, D>,
) -> SMatrix<R, D, D> {
    let size = m.norm() / R::of((D as f64).sqrt());
    let mut j = SMatrix::<R, D, D>::zeros();
    for col in 0..D {
        let step = R::of(f64::EPSILON.sqrt()) * (m[col].abs() + size + R::of(f64::MIN_POSITIVE));
        let mut shifted = *m;
        shifted[col] += step;
        j.set_column(col, &((scene.acceleration(&shifted) - a) / step));
    }
    j
}

/// An implicit Runge-Kutta method given by its tableau `(A, b, c)`, applied
/// to `y = (q, v)`, `y' = (v, a(q))`: the stages solve
/// `V_i = v + h sum_j a_ij k_j`, `Q_i = q + h sum_j a_ij V_j`, `k_i = a(Q_i)`,
/// and the step is `v' = v + h sum_i b_i k_i`, `q' = q + h sum_i b_i V_i`.
///
/// The stage equations are solved by fixed-point iteration on the stage
/// accelerations `k`, starting from the previous step's (zero before the
/// first step: no force evaluation to start). Each iteration evaluates every
/// stage (`S` force evaluations, which is what `meta.force_evaluations`
/// counts) and contracts by about `h^2 L rho(A^2)` (`L` the Lipschitz
/// constant of `a`). The iteration ends like [`ImplicitMidpoint`]'s: once the stage positions move by less than
/// [`ROUND_OFF_UNITS`] units of round-off and the moves stop shrinking. A
/// solve that has not reached round-off after [`MAX_ITERATIONS`] iterations
/// (a step too large for a contraction, there is no Newton fallback here) is
/// a [`StepFailure::NotConverged`] and leaves the state unchanged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImplicitRk<const S: usize> {
    /// The scheme's claims; `force_evaluations` is `S` (per iteration).
    pub meta: SchemeMeta,
    /// The Runge-Kutta matrix.
    pub a: [[f64; S]; S],
    /// The weights.
    pub b: [f64; S],
    /// The nodes (`c_i = sum_j a_ij`), for the tests of the order conditions.
    pub c: [f64; S],
}

impl<const S: usize> ImplicitRk<S> {
    /// The method with this tableau and these claims; `force_evaluations`
    /// and `implicit` are set here (`S` evaluations per iteration).
    pub const fn new(mut meta: SchemeMeta, a: [[f64; S]; S], b: [f64; S], c: [f64; S]) -> Self {
        meta.force_evaluations = S as u32;
        meta.implicit = true;
        Self { meta, a, b, c }
    }

    /// The stage values `(Q_i, V_i)` given the stage accelerations `k`.
    #[inline(always)]
    fn stages<R: Real, const D: usize>(
        &self,
        q: &SVector<R, D>,
        v: &SVector<R, D>,
        k: &[SVector<R, D>; S],
        h: R,
    ) -> ([SVector<R, D>; S], [SVector<R, D>; S]) {
        let mut vs = [*v; S];
        let mut qs = [*q; S];
        for (vi, row) in vs.iter_mut().zip(&self.a) {
            for (kj, &aij) in k.iter().zip(row) {
                if aij != 0.0 {
                    *vi += kj * (h * R::of(aij));
                }
            }
        }
        for (qi, row) in qs.iter_mut().zip(&self.a) {
            for (vj, &aij) in vs.iter().zip(row) {
                if aij != 0.0 {
                    *qi += vj * (h * R::of(aij));
                }
            }
        }
        (qs, vs)
    }
}

/// What an implicit Runge-Kutta method carries between steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StageCarry<R: Real, const D: usize, const S: usize> {
    /// The synchronised state.
    pub state: State<D, R>,
    /// The last step's stage accelerations, the next solve's starting guess.
    pub k: [SVector<R, D>; S],
    /// Iterations the last step took, converged or not (0 before the first).
    pub last_iterations: u32,
    /// Force evaluations spent by the solves since `start`, failed ones
    /// included.
    pub evaluations: u64,
}

impl<const S: usize> Scheme for ImplicitRk<S> {
    type Carry<R: Real, const D: usize> = StageCarry<R, D, S>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        _: &P,
        s: &State<D, R>,
        _: R,
    ) -> StageCarry<R, D, S> {
        StageCarry {
            state: *s,
            k: [SVector::zeros(); S],
            last_iterations: 0,
            evaluations: 0,
        }
    }

    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut StageCarry<R, D, S>,
        h: R,
    ) -> Result<(), StepFailure> {
        let (q0, v0) = (c.state.q, c.state.v);
        let units = R::of(ROUND_OFF_UNITS) * R::default_epsilon();
        let mut k = c.k;
        let (mut qs, _) = self.stages(&q0, &v0, &k, h);
        let mut correction = R::zero();
        let mut previous: Option<R> = None;
        for iteration in 1..=MAX_ITERATIONS {
            for i in 0..S {
                k[i] = scene.acceleration(&qs[i]);
            }
            c.evaluations += S as u64;
            let (next, vs) = self.stages(&q0, &v0, &k, h);
            // how far the stage positions moved, against the rounding of
            // the terms they are made of
            correction = R::zero();
            let mut size = R::zero();
            for i in 0..S {
                correction += (next[i] - qs[i]).norm_squared();
                size += q0.norm_squared() + next[i].norm_squared();
            }
            qs = next;
            // an overflowed or NaN iterate never converges (and an infinite
            // correction would pass the test below against an infinite size)
            if !(correction.is_finite() && size.is_finite()) {
                return Err(fail(&mut c.last_iterations, iteration, correction));
            }
            let settled = correction == R::zero() || previous.is_some_and(|p| correction >= p);
            if correction <= units * units * size && (settled || iteration == MAX_ITERATIONS) {
                c.last_iterations = iteration;
                let (mut dq, mut dv) = (SVector::<R, D>::zeros(), SVector::<R, D>::zeros());
                for i in 0..S {
                    dq += vs[i] * (h * R::of(self.b[i]));
                    dv += k[i] * (h * R::of(self.b[i]));
                }
                c.state = State::new(q0 + dq, v0 + dv);
                c.k = k;
                return Ok(());
            }
            previous = Some(correction);
        }
        Err(fail(&mut c.last_iterations, MAX_ITERATIONS, correction))
    }

    fn state<R: Real, const D: usize>(&self, c: &StageCarry<R, D, S>, _: R) -> State<D, R> {
        c.state
    }

    fn solver_evaluations<R: Real, const D: usize>(&self, c: &StageCarry<R, D, S>) -> Option<u64> {
        Some(c.evaluations)
    }
}
