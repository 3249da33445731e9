//! The copy-in, call, copy-out glue between stepladder's slices and each
//! crate's own state, system and stepping types. Nothing here integrates:
//! every step and every step-size decision is the crate's.

use nalgebra::SVector;
use std::cell::Cell;
use std::ops::ControlFlow;
use stepladder::scheme::Force;
use stepladder::scheme::{Advance, RunEnd};

/// The scene dimensions the glue instantiates its fixed-size types for
/// (the oscillator is 1, the Kepler orbits 2; for brahe's pair also the
/// race's N-body scenes, 14 and 18).
fn unsupported(d: usize) -> ! {
    panic!("audit glue: scenes of dimension {d} are not wired for this crate")
}

// ----------------------------------------------------------------- utsuroi

/// q'' = a(q) as utsuroi's second-order state (q, v), derivative (v, a).
struct UtsuroiNewton<'a, 'f, const N: usize> {
    force: &'a Force<'f, f64>,
}

impl<const N: usize> utsuroi::DynamicalSystem for UtsuroiNewton<'_, '_, N> {
    type State = utsuroi::State<N, 2>;
    fn derivatives(&self, _t: f64, s: &Self::State) -> Self::State {
        let mut a = SVector::<f64, N>::zeros();
        (self.force)(s.y().as_slice(), a.as_mut_slice());
        utsuroi::State::from_derivative(*s.dy(), a)
    }
}

/// The utsuroi fixed-step methods audited.
#[derive(Clone, Copy, Debug)]
pub enum UtsuroiFixed {
    StormerVerlet,
    Yoshida4,
    Yoshida6,
    Yoshida8,
    Rk4,
}

fn utsuroi_step_n<const N: usize>(
    method: UtsuroiFixed,
    q: &mut [f64],
    v: &mut [f64],
    h: f64,
    force: &Force<f64>,
) {
    use utsuroi::Integrator;
    let system = UtsuroiNewton::<N> { force };
    let s = utsuroi::State::new(SVector::from_column_slice(q), SVector::from_column_slice(v));
    // the scenes are autonomous: the start time is irrelevant, 0 is passed
    let next = match method {
        UtsuroiFixed::StormerVerlet => utsuroi::StormerVerlet.step(&system, 0.0, &s, h),
        UtsuroiFixed::Yoshida4 => utsuroi::Yoshida4.step(&system, 0.0, &s, h),
        UtsuroiFixed::Yoshida6 => utsuroi::Yoshida6.step(&system, 0.0, &s, h),
        UtsuroiFixed::Yoshida8 => utsuroi::Yoshida8.step(&system, 0.0, &s, h),
        UtsuroiFixed::Rk4 => utsuroi::Rk4.step(&system, 0.0, &s, h),
    };
    q.copy_from_slice(next.y().as_slice());
    v.copy_from_slice(next.dy().as_slice());
}

/// One step of a utsuroi fixed-step method.
pub fn utsuroi_step(
    method: UtsuroiFixed,
    q: &mut [f64],
    v: &mut [f64],
    h: f64,
    force: &Force<f64>,
) {
    match q.len() {
        1 => utsuroi_step_n::<1>(method, q, v, h, force),
        2 => utsuroi_step_n::<2>(method, q, v, h, force),
        d => unsupported(d),
    }
}

fn utsuroi_dp45_n<const N: usize>(
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    tol: f64,
    force: &Force<f64>,
) -> Advance {
    let system = UtsuroiNewton::<N> { force };
    let s = utsuroi::State::new(SVector::from_column_slice(q), SVector::from_column_slice(v));
    let tolerances = utsuroi::Tolerances {
        atol: tol,
        rtol: tol,
    };
    // first step guess: utsuroi has no automatic initial step; 1e-3 of the
    // span is what its own examples start from, and the controller corrects it
    let mut stepper = utsuroi::DormandPrince.stepper(&system, s, t0, 1e-3 * (t1 - t0), tolerances);
    let accepted = Cell::new(0u64);
    let outcome = stepper.advance_to(
        t1,
        |_, _| accepted.set(accepted.get() + 1),
        |_, _| ControlFlow::<()>::Continue(()),
    );
    q.copy_from_slice(stepper.state().y().as_slice());
    v.copy_from_slice(stepper.state().dy().as_slice());
    Advance {
        accepted: accepted.get(),
        // the stepper does not tell its rejections
        rejected: 0,
        end: if outcome.is_ok() {
            RunEnd::Reached
        } else {
            RunEnd::GaveUp
        },
        reported_evaluations: None,
    }
}

/// utsuroi's adaptive Dormand-Prince 5(4) from `t0` to `t1`.
pub fn utsuroi_dp45(
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    tol: f64,
    force: &Force<f64>,
) -> Advance {
    match q.len() {
        1 => utsuroi_dp45_n::<1>(q, v, t0, t1, tol, force),
        2 => utsuroi_dp45_n::<2>(q, v, t0, t1, tol, force),
        d => unsupported(d),
    }
}

// ---------------------------------------------------- differential-equations

/// y = (q, v), y' = (v, a(q)): one force call per `diff`. For the symplectic
/// integrators the crate splits y in halves as (q, p); with unit masses p = v.
struct DeNewton<'a, 'f> {
    force: &'a Force<'f, f64>,
}

impl differential_equations::prelude::ODE<f64, Vec<f64>> for DeNewton<'_, '_> {
    fn diff(&self, _t: f64, y: &Vec<f64>, dydt: &mut Vec<f64>) {
        let d = y.len() / 2;
        dydt[..d].copy_from_slice(&y[d..]);
        (self.force)(&y[..d], &mut dydt[d..]);
    }
}

/// A differential-equations method object kept between steps, with the
/// state and step it was last left at.
#[derive(Clone)]
pub struct DeStepper<M> {
    method: M,
    y: Vec<f64>,
    h: f64,
}

/// One step of a differential-equations fixed-step method through its
/// stepping interface (`OrdinaryNumericalMethod::init` once, then `step`):
/// the crate's explicit Runge-Kutta evaluates f(y0) in `init` and f(y1) at
/// the end of each step for the next one, so a fresh solve per step would
/// charge one call too many. The method is re-initialised whenever the
/// state handed in is not the one it left (a new run).
pub fn de_step<M>(
    make: impl Fn(f64) -> M,
    kept: &mut Option<DeStepper<M>>,
    q: &mut [f64],
    v: &mut [f64],
    h: f64,
    force: &Force<f64>,
) where
    M: differential_equations::ode::OrdinaryNumericalMethod<f64, Vec<f64>>,
{
    let d = q.len();
    let y0: Vec<f64> = q.iter().chain(v.iter()).copied().collect();
    let ode = DeNewton { force };
    let continues = kept.as_ref().is_some_and(|k| k.h == h && k.y == y0);
    if !continues {
        let mut method = make(h);
        // the scenes are autonomous; the end time only bounds the run and
        // gives its direction (the round trip steps with h < 0)
        method
            .init(&ode, 0.0, h.signum() * 1e300, &y0)
            .unwrap_or_else(|e| panic!("differential-equations: init failed: {e:?}"));
        *kept = Some(DeStepper { method, y: y0, h });
    }
    let stepper = kept.as_mut().expect("initialised above");
    stepper
        .method
        .step(&ode)
        .unwrap_or_else(|e| panic!("differential-equations: one step of {h} failed: {e:?}"));
    let y = stepper.method.y().clone();
    q.copy_from_slice(&y[..d]);
    v.copy_from_slice(&y[d..]);
    stepper.y = y;
}

/// One step of a differential-equations method that cannot be kept between
/// steps (its symplectic integrators are not `Clone`): `init` and one `step`
/// per call. Their `init` evaluates nothing (symplectic/velocity_verlet.rs
/// and ruth_forest.rs), so the calls counted are the step's own.
pub fn de_fresh_step<M>(
    make: impl Fn(f64) -> M,
    q: &mut [f64],
    v: &mut [f64],
    h: f64,
    force: &Force<f64>,
) where
    M: differential_equations::ode::OrdinaryNumericalMethod<f64, Vec<f64>>,
{
    de_step(make, &mut None, q, v, h, force);
}

/// differential-equations' adaptive Dormand-Prince 5(4) from `t0` to `t1`.
pub fn de_dopri5(
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    tol: f64,
    force: &Force<f64>,
) -> Advance {
    use differential_equations::prelude::*;
    let d = q.len();
    let y0: Vec<f64> = q.iter().chain(v.iter()).copied().collect();
    let ode = DeNewton { force };
    let method = ExplicitRungeKutta::dopri5().rtol(tol).atol(tol);
    match IVP::ode(&ode, t0, t1, y0).method(method).solve() {
        Ok(solution) => {
            let y = solution.y.last().expect("the solution holds t1");
            q.copy_from_slice(&y[..d]);
            v.copy_from_slice(&y[d..]);
            Advance {
                accepted: solution.steps.accepted as u64,
                rejected: solution.steps.rejected as u64,
                end: RunEnd::Reached,
                reported_evaluations: Some(solution.evals.function as u64),
            }
        }
        Err(_) => Advance {
            end: RunEnd::GaveUp,
            ..Advance::reached()
        },
    }
}

// ------------------------------------------------------------- ode_solvers

/// y = (q, v) on ode_solvers' (nalgebra) vectors.
struct OsNewton<'a, 'f, const N: usize> {
    force: &'a Force<'f, f64>,
}

macro_rules! os_system {
    ($n:literal, $m:literal) => {
        impl ode_solvers::System<f64, ode_solvers::SVector<f64, $m>> for OsNewton<'_, '_, $n> {
            fn system(
                &self,
                _x: f64,
                y: &ode_solvers::SVector<f64, $m>,
                dy: &mut ode_solvers::SVector<f64, $m>,
            ) {
                let (y, dy) = (y.as_slice(), dy.as_mut_slice());
                dy[..$n].copy_from_slice(&y[$n..]);
                (self.force)(&y[..$n], &mut dy[$n..]);
            }
        }
    };
}
os_system!(1, 2);
os_system!(2, 4);

/// One step of ode_solvers' Rk4: its solver from 0 to h at step h (it
/// takes ceil(span / h) = 1 step).
pub fn os_rk4(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    macro_rules! run {
        ($n:literal, $m:literal) => {{
            let y0 =
                ode_solvers::SVector::<f64, $m>::from_iterator(q.iter().chain(v.iter()).copied());
            let mut solver = ode_solvers::Rk4::new(OsNewton::<$n> { force }, 0.0, y0, h, h);
            solver.integrate().expect("one fixed step");
            let y = solver.y_out().last().expect("the step's end");
            q.copy_from_slice(&y.as_slice()[..$n]);
            v.copy_from_slice(&y.as_slice()[$n..]);
        }};
    }
    match q.len() {
        1 => run!(1, 2),
        2 => run!(2, 4),
        d => unsupported(d),
    }
}

/// The ode_solvers embedded pairs audited.
#[derive(Clone, Copy, Debug)]
pub enum OsPair {
    Dopri5,
    Dop853,
}

/// An ode_solvers pair from `t0` to `t1` with its documented defaults
/// (`new`), sparse output so no dense stages are added.
pub fn os_pair(
    pair: OsPair,
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    tol: f64,
    force: &Force<f64>,
) -> Advance {
    use ode_solvers::OutputType::Sparse;
    macro_rules! run {
        ($n:literal, $m:literal, $solver:ident, $beta:expr, $fac_min:expr, $fac_max:expr) => {{
            let y0 =
                ode_solvers::SVector::<f64, $m>::from_iterator(q.iter().chain(v.iter()).copied());
            // the parameters of `new` (dopri5.rs:76-96, dop853.rs:76-100), with
            // the output sparse instead of dense
            let mut solver = ode_solvers::$solver::from_param(
                OsNewton::<$n> { force },
                t0,
                t1,
                t1 - t0,
                y0,
                tol,
                tol,
                0.9,
                $beta,
                $fac_min,
                $fac_max,
                t1 - t0,
                0.0,
                100_000,
                1000,
                Sparse,
            );
            let result = solver.integrate();
            let y = *solver.y_out().last().expect("the run's end");
            q.copy_from_slice(&y.as_slice()[..$n]);
            v.copy_from_slice(&y.as_slice()[$n..]);
            match result {
                Ok(stats) => Advance {
                    accepted: stats.accepted_steps as u64,
                    rejected: stats.rejected_steps as u64,
                    end: RunEnd::Reached,
                    reported_evaluations: Some(stats.num_eval as u64),
                },
                Err(ode_solvers::dop_shared::IntegrationError::MaxNumStepReached { .. }) => {
                    Advance {
                        end: RunEnd::StepLimit,
                        ..Advance::reached()
                    }
                }
                Err(_) => Advance {
                    end: RunEnd::GaveUp,
                    ..Advance::reached()
                },
            }
        }};
    }
    match (pair, q.len()) {
        (OsPair::Dopri5, 1) => run!(1, 2, Dopri5, 0.04, 0.2, 10.0),
        (OsPair::Dopri5, 2) => run!(2, 4, Dopri5, 0.04, 0.2, 10.0),
        (OsPair::Dop853, 1) => run!(1, 2, Dop853, 0.0, 0.333, 6.0),
        (OsPair::Dop853, 2) => run!(2, 4, Dop853, 0.0, 0.333, 6.0),
        (_, d) => unsupported(d),
    }
}

// ---------------------------------------------------------------- peroxide

/// y = (q, v) on slices.
struct PxNewton<'a, 'f> {
    force: &'a Force<'f, f64>,
}

impl peroxide::fuga::ODEProblem for PxNewton<'_, '_> {
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) -> anyhow::Result<()> {
        let d = y.len() / 2;
        dy[..d].copy_from_slice(&y[d..]);
        (self.force)(&y[..d], &mut dy[d..]);
        Ok(())
    }
}

/// One step of a peroxide integrator (its `ODEIntegrator::step`).
pub fn px_step<I: peroxide::fuga::ODEIntegrator>(
    integrator: &I,
    q: &mut [f64],
    v: &mut [f64],
    h: f64,
    force: &Force<f64>,
) {
    let d = q.len();
    let mut y: Vec<f64> = q.iter().chain(v.iter()).copied().collect();
    integrator
        .step(&PxNewton { force }, 0.0, &mut y, h)
        .unwrap_or_else(|e| panic!("peroxide: one step of {h} failed: {e}"));
    q.copy_from_slice(&y[..d]);
    v.copy_from_slice(&y[d..]);
}

/// Most attempts an adaptive peroxide run may make: the crate's driver has
/// no limit of its own, and an estimator that scales like `h` (TSIT45)
/// would need ~10^14 steps at the tightest tolerances.
pub const PEROXIDE_STEP_LIMIT: u64 = 1_000_000;

/// A peroxide adaptive pair from `t0` to `t1`, driven step by step through
/// `ODEIntegrator::step`. Its own `BasicODESolver` advances the clock by the
/// requested `dt`, not by the step taken after internal rejections (source
/// ode.rs:240-244), so it cannot be used to reach `t1`. Built with
/// `max_step_iter = 1`, a rejected step returns an error without touching
/// `y` and the loop retries with half the step (the error carries no
/// proposal); an accepted step returns the next proposal.
pub fn px_adaptive<I: peroxide::fuga::ODEIntegrator>(
    make: impl Fn(f64) -> I,
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    tol: f64,
    force: &Force<f64>,
) -> Advance {
    let d = q.len();
    let integrator = make(tol);
    let problem = PxNewton { force };
    let mut y: Vec<f64> = q.iter().chain(v.iter()).copied().collect();
    let (mut t, mut dt) = (t0, 1e-3 * (t1 - t0));
    let mut run = Advance::reached();
    while t < t1 {
        if run.accepted + run.rejected >= PEROXIDE_STEP_LIMIT {
            run.end = RunEnd::StepLimit;
            break;
        }
        let h = dt.min(t1 - t);
        let before = y.clone();
        match integrator.step(&problem, t, &mut y, h) {
            Ok(next) => {
                t = if h == t1 - t { t1 } else { t + h };
                dt = next;
                run.accepted += 1;
            }
            Err(_) => {
                y.copy_from_slice(&before);
                dt = 0.5 * h;
                run.rejected += 1;
            }
        }
        if t + dt == t {
            run.end = RunEnd::StepUnderflow;
            break;
        }
    }
    q.copy_from_slice(&y[..d]);
    v.copy_from_slice(&y[d..]);
    run
}

// ------------------------------------------------------------- russell_ode

/// The force reaches russell_ode's right-hand side through the solver's
/// argument (`System::new` wants a `Send + Sync` closure, which a borrowed
/// `&Force` is not).
pub struct RussellArgs<'a, 'f> {
    force: &'a Force<'f, f64>,
}

/// y = (q, v), y' = (v, a(q)).
fn russell_system<'a, 'f: 'a>(d: usize) -> russell_ode::System<'a, RussellArgs<'a, 'f>> {
    russell_ode::System::new(
        2 * d,
        move |f: &mut russell_lab::Vector,
              _x: f64,
              y: &russell_lab::Vector,
              args: &mut RussellArgs<'a, 'f>| {
            let (y, f) = (y.as_data(), f.as_mut_data());
            f[..d].copy_from_slice(&y[d..]);
            (args.force)(&y[..d], &mut f[d..]);
            Ok(())
        },
    )
}

/// One step of russell_ode's fixed-step `Rk4`: its solver over [0, |h|] with
/// `h_equal = |h|` (one step). The solver refuses `x1 < x0`, so a backward
/// step is taken as `R forward(|h|) R` with `R(q, v) = (q, -v)`: for
/// `f(q, v) = (v, a(q))`, `f(R y) = -R f(y)`, so the stages of the forward
/// step from `R y` are `R` of the backward step's, exactly (negation is
/// exact in floating point).
pub fn russell_rk4(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    let d = q.len();
    let backward = h < 0.0;
    let sign = if backward { -1.0 } else { 1.0 };
    let mut y = russell_lab::Vector::new(2 * d);
    for i in 0..d {
        y[i] = q[i];
        y[d + i] = sign * v[i];
    }
    let params = russell_ode::Params::new(russell_ode::Method::Rk4);
    let mut solver = russell_ode::OdeSolver::new(params, russell_system(d))
        .unwrap_or_else(|e| panic!("russell_ode Rk4: {e}"));
    let mut args = RussellArgs { force };
    solver
        .solve(&mut y, 0.0, h.abs(), Some(h.abs()), &mut args, None)
        .unwrap_or_else(|e| panic!("russell_ode Rk4: one step of {h} failed: {e}"));
    for i in 0..d {
        q[i] = y[i];
        v[i] = sign * y[d + i];
    }
}

/// russell_ode's adaptive `DoPri5` from `t0` to `t1`, absolute and relative
/// tolerance `tol`.
pub fn russell_dopri5(
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    tol: f64,
    force: &Force<f64>,
) -> Advance {
    let d = q.len();
    let mut y = russell_lab::Vector::new(2 * d);
    for i in 0..d {
        y[i] = q[i];
        y[d + i] = v[i];
    }
    let mut params = russell_ode::Params::new(russell_ode::Method::DoPri5);
    if let Err(e) = params.set_tolerances(tol, tol, None) {
        panic!("russell_ode DoPri5: tolerance {tol:e} refused: {e}");
    }
    let mut solver = russell_ode::OdeSolver::new(params, russell_system(d))
        .unwrap_or_else(|e| panic!("russell_ode DoPri5: {e}"));
    let mut args = RussellArgs { force };
    let result = solver.solve(&mut y, t0, t1, None, &mut args, None);
    for i in 0..d {
        q[i] = y[i];
        v[i] = y[d + i];
    }
    let stats = solver.stats();
    Advance {
        accepted: stats.n_accepted as u64,
        rejected: stats.n_rejected as u64,
        end: if result.is_ok() {
            RunEnd::Reached
        } else {
            RunEnd::GaveUp
        },
        reported_evaluations: Some(stats.n_function as u64),
    }
}

// ------------------------------------------------------------------ brahe

/// The force callback as brahe's dynamics closure must hold it: brahe boxes
/// its dynamics as `'static + Send + Sync`, and the callback is borrowed for
/// one call of the glue.
struct BorrowedForce(*const Force<'static, f64>);

// SAFETY: the pointer is dereferenced only inside brahe's `step`, which
// evaluates its stages one after another on the calling thread (rkn1210.rs,
// `step_internal`), and the integrator holding it is built and dropped
// within the glue call that borrows the force: it never outlives the
// borrow, and no other thread sees it.
unsafe impl Send for BorrowedForce {}
unsafe impl Sync for BorrowedForce {}

impl BorrowedForce {
    fn new(force: &Force<'_, f64>) -> Self {
        // SAFETY: only the lifetime is erased; see the impls above.
        Self(unsafe {
            std::mem::transmute::<*const Force<'_, f64>, *const Force<'static, f64>>(force)
        })
    }

    fn call(&self, q: &[f64], a: &mut [f64]) {
        // SAFETY: the force outlives every call (see above).
        unsafe { (*self.0)(q, a) }
    }
}

/// brahe's `RKN1210SIntegrator` with state `y = (q, v)` of `M = 2 N`
/// components, its dynamics `(v, a(q))`. `attempts` counts the step
/// attempts from the times brahe passes: every attempt evaluates its first
/// stage at the step's start (node `c1 = 0`), no other stage does.
macro_rules! brahe_rkn1210 {
    ($n:literal, $m:literal, $force:expr, $config:expr) => {{
        use std::sync::Arc;
        use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
        let force = BorrowedForce::new($force);
        let start = Arc::new(AtomicU64::new(f64::NAN.to_bits()));
        let attempts = Arc::new(AtomicU64::new(0));
        let (seen, counted) = (start.clone(), attempts.clone());
        let dynamics = move |t: f64,
                             y: &brahe_nalgebra::SVector<f64, $m>,
                             _: Option<&brahe_nalgebra::SVector<f64, 0>>|
              -> Result<
            brahe_nalgebra::SVector<f64, $m>,
            brahe::utils::errors::BraheError,
        > {
            if t.to_bits() == seen.load(Relaxed) {
                counted.fetch_add(1, Relaxed);
            }
            let mut dy = brahe_nalgebra::SVector::<f64, $m>::zeros();
            dy.as_mut_slice()[..$n].copy_from_slice(&y.as_slice()[$n..]);
            force.call(&y.as_slice()[..$n], &mut dy.as_mut_slice()[$n..]);
            Ok(dy)
        };
        use brahe::integrators::SIntegratorConstructor;
        let integrator = brahe::integrators::RKN1210SIntegrator::<$m, 0>::with_config(
            Box::new(dynamics),
            None,
            None,
            None,
            $config,
        );
        (integrator, start, attempts)
    }};
}

/// One step of brahe's RKN12(10) at `h`, its estimate never rejecting:
/// with both tolerances infinite every component's allowance is infinite,
/// the normalised error 0 (rkn1210.rs, `compute_normalized_error_s`), and
/// the step is accepted at the `h` given. What remains is the method
/// itself, twelfth order by its claim.
pub fn brahe_rkn1210_step(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    use brahe::integrators::{IntegratorConfig, SIntegrator};
    macro_rules! run {
        ($n:literal, $m:literal) => {{
            let config = IntegratorConfig::adaptive(f64::INFINITY, f64::INFINITY);
            let (integrator, _, _) = brahe_rkn1210!($n, $m, force, config);
            let y = brahe_nalgebra::SVector::<f64, $m>::from_iterator(
                q.iter().chain(v.iter()).copied(),
            );
            let step = integrator
                .step(0.0, y, None, Some(h))
                .unwrap_or_else(|e| panic!("brahe RKN1210: one step of {h} failed: {e}"));
            assert_eq!(
                step.dt_used, h,
                "brahe RKN1210 changed a step it cannot reject"
            );
            q.copy_from_slice(&step.state.as_slice()[..$n]);
            v.copy_from_slice(&step.state.as_slice()[$n..]);
        }};
    }
    match q.len() {
        1 => run!(1, 2),
        2 => run!(2, 4),
        14 => run!(14, 28),
        18 => run!(18, 36),
        d => unsupported(d),
    }
}

/// brahe's RKN12(10) from `t0` to `t1` at absolute and relative tolerance
/// `tol`, its other settings the documented defaults
/// (`IntegratorConfig::adaptive`, config.rs). brahe steps one accepted step
/// a call (`SIntegrator::step`, retrying rejected attempts inside) and
/// leaves the driving to the caller: the glue starts with the whole
/// interval as the proposal, as ode_solvers' `new` does, takes each next
/// proposal brahe returns (`dt_next`), and shortens only the last step to
/// land on `t1`. The crate keeps no statistics: the accepted steps are
/// counted here, the attempts from the times of its first stages.
pub fn brahe_rkn1210(
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    tol: f64,
    force: &Force<f64>,
) -> Advance {
    let config = brahe::integrators::IntegratorConfig::adaptive(tol, tol);
    brahe_rkn1210_with(config, q, v, t0, t1, force)
}

/// [`brahe_rkn1210`] with the step cap lifted (`max_step: None`), every
/// other setting the default: what the cap of 900 time units
/// (`IntegratorConfig::default`, config.rs) does to a scene whose steps
/// would exceed it, the outer solar system in days.
pub(crate) fn brahe_rkn1210_uncapped(
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    tol: f64,
    force: &Force<f64>,
) -> Advance {
    let config = brahe::integrators::IntegratorConfig {
        max_step: None,
        ..brahe::integrators::IntegratorConfig::adaptive(tol, tol)
    };
    brahe_rkn1210_with(config, q, v, t0, t1, force)
}

/// brahe's default step cap (`IntegratorConfig::default().max_step`).
pub(crate) fn brahe_max_step() -> Option<f64> {
    brahe::integrators::IntegratorConfig::default().max_step
}

/// brahe's RKN12(10) under `config`, driven from `t0` to `t1` as
/// [`brahe_rkn1210`] says.
fn brahe_rkn1210_with(
    config: brahe::integrators::IntegratorConfig,
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    force: &Force<f64>,
) -> Advance {
    use brahe::integrators::SIntegrator;
    use std::sync::atomic::Ordering::Relaxed;
    let mut run = Advance::reached();
    macro_rules! run {
        ($n:literal, $m:literal) => {{
            let config = config.clone();
            let (integrator, start, attempts) = brahe_rkn1210!($n, $m, force, config);
            let mut y = brahe_nalgebra::SVector::<f64, $m>::from_iterator(
                q.iter().chain(v.iter()).copied(),
            );
            let (mut t, mut dt) = (t0, t1 - t0);
            while t < t1 {
                let h = dt.min(t1 - t);
                start.store(t.to_bits(), Relaxed);
                match integrator.step(t, y, None, Some(h)) {
                    Ok(step) if step.state.iter().all(|x| x.is_finite()) => {
                        t = if step.dt_used == t1 - t {
                            t1
                        } else {
                            t + step.dt_used
                        };
                        y = step.state;
                        dt = step.dt_next;
                        run.accepted += 1;
                    }
                    _ => {
                        run.end = RunEnd::GaveUp;
                        break;
                    }
                }
                if t < t1 && run.accepted >= BRAHE_STEP_LIMIT {
                    run.end = RunEnd::StepLimit;
                    break;
                }
            }
            q.copy_from_slice(&y.as_slice()[..$n]);
            v.copy_from_slice(&y.as_slice()[$n..]);
            run.rejected = attempts.load(Relaxed).saturating_sub(run.accepted);
        }};
    }
    match q.len() {
        1 => run!(1, 2),
        2 => run!(2, 4),
        14 => run!(14, 28),
        18 => run!(18, 36),
        d => unsupported(d),
    }
    run
}

/// Most steps a brahe run may accept before the glue stops it and reports
/// the step limit. brahe accepts any step once it has shrunk to its minimum
/// (`min_step`, 1e-12 time units by default, config.rs; rkn1210.rs accepts
/// when `error <= 1.0 || min_step_reached`), so a run stuck there would not
/// end; the audit's longest runs accept under 2,500 steps (the Pleiades at
/// 1e-16).
pub const BRAHE_STEP_LIMIT: u64 = 1_000_000;
