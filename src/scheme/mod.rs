//! Schemes: one step of a time integrator for `q'' = a(q)`, with the
//! metadata that says what the scheme claims to be.
//!
//! A scheme may carry more than `(q, v)` between steps (the two-step Störmer
//! form keeps the previous position, leap-frog a half-step velocity, Verlet
//! the acceleration it will reuse); [`Scheme::state`] hands studies a
//! synchronised `(q, v)` at whole steps so they compare like with like.

mod adapter;
mod adaptive;
mod adaptive_black_box;
mod black_box;
mod catalogue;
#[doc(hidden)]
pub mod compensated;
mod composition;
mod embedded_pair;
mod euler;
mod implicit;
mod multistep;
mod nystrom_rk;
mod nystrom_splitting;
mod nystrom_tables;
mod runge_kutta;
mod single_precision;
mod splitting;
mod summation;
mod verlet;

pub use adapter::{Hamiltonian, Rhs, Shape, Vector, VectorForce};
pub use adaptive::{
    AdaptiveClaims, AdaptiveIntegrator, AdaptiveRun, RunEnd, check_request,
    proportionality_exponent,
};
pub use adaptive_black_box::{AdaptiveBlackBox, Advance, AdvanceFn};
pub use black_box::{
    AnyBlackBox, AnyKept, AnyStep, BlackBox, BlackBoxCarry, BlackBoxStep, Float, Force, Implicit,
    Solve, SolveTally, Stateful, StepFn, StepReturn,
};
pub use catalogue::{SchemeVisitor, TABLES, catalogue, scheme_ids, visit_scheme};
pub use compensated::{
    LEAPFROG_COMPENSATED, STORMER_VERLET_COMPENSATED, VELOCITY_VERLET_COMPENSATED,
};
pub use composition::{FOREST_RUTH, KAHAN_LI8, VerletComposition, YOSHIDA6};
pub use embedded_pair::{
    Controller, DPRKN6_ADAPTIVE, DPRKN8_ADAPTIVE, DPRKN8_COMPENSATED, DPRKN12_ADAPTIVE,
    DPRKN12_COMPENSATED, EmbeddedPair,
};
pub use euler::Euler;
pub use implicit::{
    ImplicitMidpoint, ImplicitRk, MAX_ITERATIONS, MidpointCarry, ROUND_OFF_UNITS, StageCarry,
};
pub use multistep::{MultistepCarry, QUINLAN_TREMAINE8, SymmetricMultistep};
pub use nystrom_rk::{Embedded, NystromStep, NystromTable, SummedCarry, SummedStep};
pub use nystrom_splitting::{
    BLANES_MOAN_SRKN11, MCLACHLAN_ATELA4, MCLACHLAN_SB3A4, MCLACHLAN_SB3A5,
};
pub use nystrom_tables::{DPRKN6, DPRKN8, DPRKN12, NYSTROM4};
pub use runge_kutta::{ExplicitRk, Rk4};
pub use single_precision::{SingleCarry, SinglePrecision};
pub use splitting::{
    EULER_CROMER, Flow, KickDrift, PEFRL, POSITION_VERLET, SplittingTable, VELOCITY_VERLET,
};
pub use summation::{Compensated, Kahan, Rounded, Summable, Summation, Summed};
pub use verlet::{Leapfrog, Staggered, StormerVerlet, TwoStep};

use crate::scene::Scene;
use crate::state::{Real, State};
use serde::Serialize;

/// What a scheme claims to be. Studies measure each claim; the report and the
/// tests compare the measurement with it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SchemeMeta {
    /// Kebab-case identifier used on the command line.
    pub id: &'static str,
    /// Human-readable name.
    pub name: &'static str,
    /// Theoretical global order of accuracy.
    pub order: u32,
    /// The one-step map preserves the symplectic form.
    pub symplectic: bool,
    /// Stepping with `-h` undoes a step with `h` (time-symmetric, reversible).
    pub symmetric: bool,
    /// Force evaluations per step, once the scheme has started; for an
    /// implicit scheme, per iteration of its solve, since the iterations a
    /// step needs depend on the step and the scene (they are read off the
    /// carry with [`Scheme::solver_evaluations`]).
    pub force_evaluations: u32,
    /// The step solves an equation (implicit scheme).
    pub implicit: bool,
    /// Where the scheme is published or derived.
    pub reference: &'static str,
    /// The leading relative phase error on the harmonic oscillator, where it
    /// has been derived analytically.
    pub phase_error: Option<PhaseError>,
}

/// The leading term of the relative phase error of a scheme on the harmonic
/// oscillator: `(w_num - w0) / w0 = coefficient * (h w0)^power + ...`, with
/// `w_num` the frequency of the numerical one-step map's eigenvalues.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PhaseError {
    /// The coefficient.
    pub coefficient: f64,
    /// The power of `h w0`.
    pub power: u32,
}

/// The phase error of every scheme whose one-step map on the oscillator has
/// trace `2 - z^2` and determinant 1 (`z = h w0`): the Verlet family and
/// Euler-Cromer. Then `cos(w_num h) = 1 - z^2/2`, so `w_num h = 2 asin(z/2)
/// = z + z^3/24 + ...`: the numerical oscillator runs slow by `z^2/24`.
pub const VERLET_PHASE: Option<PhaseError> = Some(PhaseError {
    coefficient: 1.0 / 24.0,
    power: 2,
});

impl SchemeMeta {
    /// The claims of an explicit scheme of global order `order` that makes
    /// one force evaluation a step and claims no geometry; the builder
    /// methods below add the rest, and every one is `const`, so a scheme's
    /// metadata can be a `static`:
    ///
    /// ```
    /// use stepladder::scheme::SchemeMeta;
    ///
    /// const META: SchemeMeta = SchemeMeta::new("my-verlet", "My velocity Verlet", 2)
    ///     .symplectic()
    ///     .symmetric()
    ///     .reference("Swope, Andersen, Berens & Wilson, J. Chem. Phys. 76, 637 (1982)");
    /// assert_eq!((META.order, META.force_evaluations, META.implicit), (2, 1, false));
    /// assert!(META.symplectic && META.symmetric);
    /// ```
    pub const fn new(id: &'static str, name: &'static str, order: u32) -> Self {
        SchemeMeta {
            id,
            name,
            order,
            symplectic: false,
            symmetric: false,
            force_evaluations: 1,
            implicit: false,
            reference: "",
            phase_error: None,
        }
    }

    /// Claims that the one-step map preserves the symplectic form.
    pub const fn symplectic(mut self) -> Self {
        self.symplectic = true;
        self
    }

    /// Claims that stepping with `-h` undoes a step with `h`.
    pub const fn symmetric(mut self) -> Self {
        self.symmetric = true;
        self
    }

    /// Claims `n` force evaluations a step (a solve's iteration, if implicit).
    pub const fn force_evaluations(mut self, n: u32) -> Self {
        self.force_evaluations = n;
        self
    }

    /// Claims that the step solves an equation.
    pub const fn implicit(mut self) -> Self {
        self.implicit = true;
        self
    }

    /// Where the scheme is published or derived.
    pub const fn reference(mut self, reference: &'static str) -> Self {
        self.reference = reference;
        self
    }

    /// The leading relative phase error on the harmonic oscillator.
    pub const fn phase_error(mut self, phase_error: PhaseError) -> Self {
        self.phase_error = Some(phase_error);
        self
    }

    /// `force_evaluations` with its unit: "4" per step, or "1 per iteration"
    /// for an implicit scheme.
    pub fn forces_label(&self) -> String {
        if self.implicit {
            format!("{} per iteration", self.force_evaluations)
        } else {
            self.force_evaluations.to_string()
        }
    }
}

/// Why a single step could not be completed (an implicit solve that did not
/// converge, say, or a panic in the scheme's own code, caught by the run). A
/// blow-up is not a failure of the step: it is detected by the run and
/// reported as instability.
#[derive(Clone, Debug, PartialEq, Serialize, thiserror::Error)]
pub enum StepFailure {
    /// The implicit equation of the step was not solved to tolerance.
    #[error(
        "implicit solve did not converge after {iterations} iterations (residual {residual:e})"
    )]
    NotConverged {
        /// Iterations spent.
        iterations: u32,
        /// The last correction's size.
        residual: f64,
    },
    /// The scheme's code panicked (caught by the run, see
    /// [`crate::run::caught`]): a defect of the step at any step size, since a
    /// run only ever hands a step a finite state within the blow-up bound.
    #[error("the step panicked: {message}")]
    Panicked {
        /// The panic's message.
        message: String,
    },
    /// The step cannot run on this scene at all (an adapter's fixed-size
    /// vector type of another length than the scene's state, masses for
    /// another dimension): a defect of the wrapping, at every step size.
    #[error("the step cannot run on this scene: {message}")]
    Unfit {
        /// What does not fit.
        message: String,
    },
}

impl StepFailure {
    /// True for a panic in the scheme's code.
    pub fn panicked(&self) -> bool {
        matches!(self, StepFailure::Panicked { .. })
    }

    /// True for a failure no step size excuses: a panic, or a step that
    /// cannot run on the scene. A solve that did not converge may be the
    /// step's size at work (a stiff step), and is judged like a blow-up.
    pub fn defect(&self) -> bool {
        matches!(
            self,
            StepFailure::Panicked { .. } | StepFailure::Unfit { .. }
        )
    }
}

/// A time integrator for `q'' = a(q)` on any scene and in any scalar type.
///
/// Implementations are a few lines: see [`Euler`] for the simplest. Every
/// method is generic so that the step is monomorphised for each scene (no
/// dynamic dispatch, no allocation in a step) and can be run in dual numbers
/// to differentiate it.
pub trait Scheme {
    /// What the scheme keeps between steps.
    type Carry<R: Real, const D: usize>: Clone + std::fmt::Debug;

    /// The scheme's claims.
    fn meta(&self) -> &SchemeMeta;

    /// Prepares the carry from a synchronised state for steps of size `h`
    /// (this is where a two-step or staggered scheme does its start-up).
    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        state: &State<D, R>,
        h: R,
    ) -> Self::Carry<R, D>;

    /// Advances the carry by one step of size `h`.
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        carry: &mut Self::Carry<R, D>,
        h: R,
    ) -> Result<(), StepFailure>;

    /// The synchronised `(q, v)` at the carry's whole step, without a force
    /// evaluation.
    fn state<R: Real, const D: usize>(&self, carry: &Self::Carry<R, D>, h: R) -> State<D, R>;

    /// What a compensated scheme carries beyond [`Scheme::state`]: the low
    /// parts its sums kept, so that `state + compensation` is its state to
    /// about twice the working precision. Zero for a scheme that rounds its
    /// state, which is every scheme unless it says otherwise; a long run
    /// reads a compensated scheme's energy at the sum, not at its rounding.
    fn compensation<R: Real, const D: usize>(
        &self,
        _carry: &Self::Carry<R, D>,
        _h: R,
    ) -> State<D, R> {
        State::new(nalgebra::SVector::zeros(), nalgebra::SVector::zeros())
    }

    /// Force evaluations an implicit scheme's solves have spent since
    /// `start`, read off the carry; `None` for an explicit scheme, whose cost
    /// per step is fixed by its metadata.
    fn solver_evaluations<R: Real, const D: usize>(
        &self,
        _carry: &Self::Carry<R, D>,
    ) -> Option<u64> {
        None
    }

    /// The iterations and residuals of an implicit scheme's solves since
    /// `start`, where it reports them ([`BlackBox::implicit`]); `None`
    /// otherwise.
    fn solve_tally<R: Real, const D: usize>(
        &self,
        _carry: &Self::Carry<R, D>,
    ) -> Option<SolveTally> {
        None
    }

    /// The step runs in any [`Real`], dual numbers included, so studies can
    /// take its exact tangent map; `false` for a scheme that only runs on
    /// plain floats (a [`BlackBox`]), whose tangent map is then taken by
    /// finite differences with a bounded error.
    fn differentiable(&self) -> bool {
        true
    }

    /// The unit round-off of the arithmetic the step is computed in:
    /// `f64::EPSILON` unless the scheme rounds to a narrower type (an `f32`
    /// [`BlackBox`], [`SinglePrecision`]). Round-off floors and tolerances
    /// scale with it.
    fn epsilon(&self) -> f64 {
        f64::EPSILON
    }

    /// For a multistep scheme, whose state is more than `(q, v)`: the
    /// characteristic polynomial of its recurrence on the oscillator
    /// `x'' = -x` at `h = z`, coefficients from the constant term up. Its
    /// iterates are combinations of `x^n` over the polynomial's roots, so
    /// stability and phase are read off the roots. `None` for a one-step
    /// scheme, whose one-step matrix the studies measure directly.
    fn recurrence_on_oscillator(&self, _z: f64) -> Option<Vec<f64>> {
        None
    }
}

/// The simplest kind of scheme: it carries nothing but the synchronised state
/// from one step to the next. Implementing this is enough to be a
/// [`Scheme`] (the carry is the [`State`], starting and reading it back are
/// the identity).
///
/// ```
/// use stepladder::scene::Scene;
/// use stepladder::scheme::{OneStep, Scheme, SchemeMeta, StepFailure, Euler};
/// use stepladder::state::{Real, State};
///
/// /// Symplectic Euler, drift first.
/// struct DriftKick;
/// impl OneStep for DriftKick {
///     fn meta(&self) -> &SchemeMeta {
///         &Euler::META // a real scheme states its own claims
///     }
///     fn advance<R: Real, const D: usize, S: Scene<D>>(&self, scene: &S, s: &mut State<D, R>, h: R) -> Result<(), StepFailure> {
///         s.q += s.v * h;
///         s.v += scene.acceleration(&s.q) * h;
///         Ok(())
///     }
/// }
/// assert_eq!(Scheme::meta(&DriftKick).id, "euler");
/// ```
pub trait OneStep {
    /// The scheme's claims.
    fn meta(&self) -> &SchemeMeta;

    /// Advances the state by one step of size `h`.
    fn advance<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        state: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure>;
}

impl<T: OneStep> Scheme for T {
    type Carry<R: Real, const D: usize> = State<D, R>;

    fn meta(&self) -> &SchemeMeta {
        OneStep::meta(self)
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        _: &S,
        state: &State<D, R>,
        _: R,
    ) -> State<D, R> {
        *state
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        state: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        self.advance(scene, state, h)
    }

    fn state<R: Real, const D: usize>(&self, state: &State<D, R>, _: R) -> State<D, R> {
        *state
    }
}

/// The carry of a one-step scheme that reuses the last acceleration: the
/// state and `a(q)` at it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WithAcceleration<R: Real, const D: usize> {
    /// The synchronised state.
    pub state: State<D, R>,
    /// `a(state.q)`, kept so the next step need not evaluate it again.
    pub a: nalgebra::SVector<R, D>,
}
