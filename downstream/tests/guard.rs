//! Guards for integrators this crate does not control in the same way: its
//! own generic velocity Verlet, an f32 leap-frog as a game engine would
//! write it, and the integrators of three published crates wrapped as black
//! boxes, each claim a separate test named after it:
//!
//! - `ode_solvers` 0.6.2: the fixed-step RK4 (f64 and f32) and the DOPRI5
//!   and DOP853 pairs taken one step at a time, as first-order systems on
//!   slices (its nalgebra is not stepladder's: its vectors lend slices, and
//!   no force call copies);
//! - `utsuroi` 0.2.0: Störmer-Verlet and the fourth-order Yoshida
//!   composition, on its own state type;
//! - `differential-equations` 0.7.0: velocity Verlet on canonical `(q, p)`,
//!   and the RK4 and DOPRI5 solver objects kept from step to step.
//!
//! The claims are each crate's documented ones; `force_evaluations` is what
//! a step spends, counted, with the least the method needs beside it where
//! the crate spends more.

use differential_equations::methods::SymplecticIntegrator;
use differential_equations::methods::{DormandPrince, ExplicitRungeKutta, Fixed, Ordinary};
use differential_equations::ode::OrdinaryNumericalMethod;
use differential_equations::prelude::{HamiltonianSystem, ODE, Status};
use ode_solvers::dop_shared::FloatNumber;
use ode_solvers::{Dop853, Dopri5, OutputType, Rk4, System};
use stepladder::nalgebra::{SVector, Vector1};
use stepladder::prelude::*;
use stepladder::scene::SceneMeta;
use stepladder::scheme::{Advance, AdvanceFn, RunEnd};
use stepladder::scheme::{AnyBlackBox, BlackBoxStep, Float, Hamiltonian, Shape, VectorForce};
use stepladder::study::{OrderSpec, global_order};
use utsuroi::{DynamicalSystem, StormerVerlet, Yoshida4};

/// Claims shared by the tables below: explicit methods whose symplectic
/// ones are also symmetric.
const fn claims(id: &'static str, order: u32, symplectic: bool, evaluations: u32) -> SchemeMeta {
    let meta = SchemeMeta::new(id, id, order)
        .force_evaluations(evaluations)
        .reference("the downstream crate");
    if symplectic {
        meta.symplectic().symmetric()
    } else {
        meta
    }
}

/// The crate's own velocity Verlet, written generically so dual numbers can
/// flow through it.
struct MyVerlet;
impl OneStep for MyVerlet {
    fn meta(&self) -> &SchemeMeta {
        const META: SchemeMeta = claims("my-verlet", 2, true, 2);
        &META
    }
    fn advance<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let half = h * R::of(0.5);
        s.v += scene.acceleration(&s.q) * half;
        s.q += s.v * h;
        s.v += scene.acceleration(&s.q) * half;
        Ok(())
    }
}

/// A game engine's kick-drift-kick leap-frog on its own `f32` vector type.
#[derive(Clone, Copy, Default)]
struct Vec2f {
    x: f32,
    y: f32,
}

fn engine_step(
    pos: &mut [Vec2f],
    vel: &mut [Vec2f],
    dt: f32,
    accel: impl Fn(&[Vec2f]) -> Vec<Vec2f>,
) {
    let a = accel(pos);
    for ((p, v), a) in pos.iter_mut().zip(vel.iter_mut()).zip(&a) {
        v.x += 0.5 * dt * a.x;
        v.y += 0.5 * dt * a.y;
        p.x += dt * v.x;
        p.y += dt * v.y;
    }
    let a = accel(pos);
    for (v, a) in vel.iter_mut().zip(&a) {
        v.x += 0.5 * dt * a.x;
        v.y += 0.5 * dt * a.y;
    }
}

/// The adapter: slices of `f32` (x, y) pairs to the engine's type and back.
fn engine_adapter(q: &mut [f32], v: &mut [f32], h: f32, force: &Force<f32>) {
    let to = |s: &[f32]| {
        s.chunks(2)
            .map(|c| Vec2f { x: c[0], y: c[1] })
            .collect::<Vec<_>>()
    };
    let (mut pos, mut vel) = (to(q), to(v));
    engine_step(&mut pos, &mut vel, h, |p: &[Vec2f]| {
        let flat: Vec<f32> = p.iter().flat_map(|p| [p.x, p.y]).collect();
        let mut a = vec![0.0; flat.len()];
        force(&flat, &mut a);
        to(&a)
    });
    for (i, (p, w)) in pos.iter().zip(&vel).enumerate() {
        (q[2 * i], q[2 * i + 1], v[2 * i], v[2 * i + 1]) = (p.x, p.y, w.x, w.y);
    }
}

// ode_solvers and utsuroi are written on nalgebra 0.34, stepladder on 0.35:
// their vector types meet as arrays.

/// A stepladder vector as theirs.
fn theirs<T: Float, const N: usize>(x: SVector<T, N>) -> OdeVector<T, N> {
    <[T; N]>::from(x).into()
}

/// Their vector as stepladder's.
fn ours<T: Float, const N: usize>(x: OdeVector<T, N>) -> SVector<T, N> {
    <[T; N]>::from(x).into()
}

/// nalgebra 0.34's static vector (ode_solvers re-exports it; utsuroi's
/// `State` is made of it).
type OdeVector<T, const M: usize> = ode_solvers::SVector<T, M>;

// ode_solvers: first-order systems on nalgebra 0.34's vectors, which lend
// their elements as slices: through `Shape::first_order_on_slices`, with
// nothing copied per force call.

/// The adapter's right-hand side on slices, `y = [q, v]`, as
/// `ode_solvers`' `System` on its vectors of any length (and as
/// differential-equations' `ODE` on `Vec<f64>`, below).
struct FirstOrder<'f, T>(&'f Force<'f, T>);

impl<T: FloatNumber + Float, const M: usize> System<T, OdeVector<T, M>> for FirstOrder<'_, T> {
    fn system(&self, _: T, y: &OdeVector<T, M>, dy: &mut OdeVector<T, M>) {
        (self.0)(y.as_slice(), dy.as_mut_slice());
    }
}

/// A first-order step on slices, `step(y, h, f)`, as a black box keeping
/// nothing between steps.
fn on_slices<T: Float>(
    meta: SchemeMeta,
    step: fn(&mut [T], T, &Force<T>),
) -> BlackBox<T, impl BlackBoxStep<T, Kept = ()>> {
    let step = move |_: &mut (), y: &mut [T], h: T, f: &Force<T>| step(y, h, f);
    BlackBox::stateful(meta, || (), Shape::first_order_on_slices(step))
}

/// One step of `ode_solvers::Rk4` of size `h` on `y` of length `M`: a
/// solver from 0 to `h`.
fn ode_solvers_rk4<T: FloatNumber + Float, const M: usize>(y: &mut [T], h: T, rhs: &Force<T>) {
    let start = OdeVector::<T, M>::from_column_slice(y);
    let mut solver = Rk4::new(FirstOrder(rhs), T::zero(), start, h, h);
    solver.integrate().expect("one fixed step");
    y.copy_from_slice(solver.y_out().last().expect("the step's output").as_slice());
}

/// One step of an `ode_solvers` embedded pair (`Dop853`, `Dopri5`) of size
/// `h`: the first step set to `h`, the largest to `h`, and tolerances so
/// loose that the step is accepted, so the call is one step of the pair's
/// high-order formula. (At working tolerances the solver would subdivide
/// `h`, and the ladder would measure its step control instead.)
macro_rules! ode_solvers_pair {
    ($name:ident, $pair:ident) => {
        fn $name<const M: usize>(y: &mut [f64], h: f64, rhs: &Force<f64>) {
            let loose = 1e30;
            let start = OdeVector::<f64, M>::from_column_slice(y);
            #[rustfmt::skip]
            let mut solver = $pair::from_param(
                FirstOrder(rhs), 0.0, h, h, start, // f, x, x_end, dx, y
                loose, loose, 0.9, 0.0, 0.333, 6.0, // rtol, atol, safety, beta, fac_min, fac_max
                h, h, 10, 1000, OutputType::Sparse, // h_max, h, n_max, n_stiff, output
            );
            let stats = solver.integrate().expect("one step");
            assert_eq!(stats.accepted_steps, 1, "{stats:?}");
            y.copy_from_slice(solver.y_out().last().expect("the step's output").as_slice());
        }
    };
}
ode_solvers_pair!(ode_solvers_dop853, Dop853);
ode_solvers_pair!(ode_solvers_dopri5, Dopri5);

/// Classical RK4, order 4, four evaluations a step (the least RK4 needs).
const RK4_CLAIMS: SchemeMeta = claims("ode-solvers-rk4", 4, false, 4);
/// DOP853 (order 8) rebuilt every step spends f(y0), eleven further stages
/// and, once the step is accepted, f(y1) for a next step that never comes:
/// 13; kept from step to step, f(y1) is the next f(y0): the 12 the method
/// needs.
const DOP853_CLAIMS: SchemeMeta = claims("ode-solvers-dop853", 8, false, 13);
/// DOPRI5 (order 5) rebuilt every step spends f(y0) and six further stages:
/// 7; the method needs 6, its last stage being the next step's first.
const DOPRI5_CLAIMS: SchemeMeta = claims("ode-solvers-dopri5", 5, false, 7);

// utsuroi: symplectic steps on its own `State<D, 2>` = (q, v), through
// `BlackBox::on_vectors`.

/// `q'' = a(q)` as utsuroi's `DynamicalSystem`, which returns the
/// derivative `(v, a(q))` packed as a state.
struct Accelerations<'f, const D: usize>(&'f VectorForce<'f, SVector<f64, D>>);

impl<const D: usize> DynamicalSystem for Accelerations<'_, D> {
    type State = utsuroi::State<D, 2>;
    fn derivatives(&self, _: f64, s: &Self::State) -> Self::State {
        let mut a = SVector::zeros();
        (self.0)(&ours(*s.y()), &mut a);
        utsuroi::State::from_derivative(*s.dy(), theirs(a))
    }
}

/// A utsuroi step, `method(system, state, h)`.
type UtsuroiStep<const D: usize> =
    fn(&Accelerations<'_, D>, &utsuroi::State<D, 2>, f64) -> utsuroi::State<D, 2>;

fn utsuroi<const D: usize>(
    meta: SchemeMeta,
    method: UtsuroiStep<D>,
) -> BlackBox<f64, impl BlackBoxStep<f64, Kept = ()>> {
    BlackBox::on_vectors(meta, move |q: &mut SVector<f64, D>, v, h, force| {
        let start = utsuroi::State::new(theirs(*q), theirs(*v));
        let end = method(&Accelerations(force), &start, h);
        (*q, *v) = (ours(*end.y()), ours(*end.dy()));
    })
}

/// Störmer-Verlet, order 2, symplectic and time-reversible (documented and
/// tested by the crate); it evaluates a(q_n) again although the step before
/// ended with it: 2 evaluations a step, where 1 would do.
fn utsuroi_stormer_verlet<const D: usize>() -> BlackBox<f64, impl BlackBoxStep<f64, Kept = ()>> {
    utsuroi::<D>(
        claims("utsuroi-stormer-verlet", 2, true, 2),
        |system, s, h| StormerVerlet.step(system, 0.0, s, h),
    )
}

/// Yoshida's triple jump of Störmer-Verlet, order 4, symplectic and
/// time-reversible: three full Verlet steps, 6 evaluations ("6 force
/// evaluations per step", its documentation says), where merging the
/// adjacent half-kicks needs 4, and 3 with the last force reused.
fn utsuroi_yoshida4<const D: usize>() -> BlackBox<f64, impl BlackBoxStep<f64, Kept = ()>> {
    utsuroi::<D>(claims("utsuroi-yoshida4", 4, true, 6), |system, s, h| {
        Yoshida4.step(system, 0.0, s, h)
    })
}

// differential-equations: its own `Hamiltonian` and `ODE` traits on
// `Vec<f64>`, and solver objects stepped through `OrdinaryNumericalMethod`.

/// Hamilton's equations as differential-equations' `Hamiltonian`, which
/// hands `q` and `p` over as vectors as long as `y = [q, p]`, the first half
/// of each meaningful.
struct Canonical<'h>(&'h Hamiltonian<'h, Vec<f64>>);

/// `rate` at the first half of `x`, into the first half of `out`.
fn on_first_halves(rate: impl Fn(&Vec<f64>, &mut Vec<f64>), x: &[f64], out: &mut [f64]) {
    let mut r = vec![0.0; x.len() / 2];
    rate(&x[..r.len()].to_vec(), &mut r);
    out[..r.len()].copy_from_slice(&r);
}

impl differential_equations::prelude::Hamiltonian<f64, Vec<f64>> for Canonical<'_> {
    fn velocity(&self, _: f64, _: &Vec<f64>, p: &Vec<f64>, dq: &mut Vec<f64>) {
        on_first_halves(|p, rate| self.0.dq_dt(p, rate), p, dq);
    }
    fn force(&self, _: f64, q: &Vec<f64>, _: &Vec<f64>, dp: &mut Vec<f64>) {
        on_first_halves(|q, rate| self.0.dp_dt(q, rate), q, dp);
    }
}

/// One step of differential-equations' velocity Verlet on `(q, p)`.
fn velocity_verlet(q: &mut Vec<f64>, p: &mut Vec<f64>, h: f64, ham: &Hamiltonian<Vec<f64>>) {
    let system = HamiltonianSystem::new(Canonical(ham));
    let mut verlet = SymplecticIntegrator::velocity_verlet(h);
    let y0 = [&q[..], &p[..]].concat();
    verlet.init(&system, 0.0, h, &y0).expect("a step of h");
    verlet.step(&system).expect("one fixed step");
    let (q1, p1) = verlet.y().split_at(q.len());
    (*q, *p) = (q1.to_vec(), p1.to_vec());
}

/// Velocity Verlet, order 2 and symplectic as documented, time-symmetric by
/// its documented coefficients (c = 0, 1; d = 1/2, 1/2). Each of its three
/// evaluations of the whole right-hand side costs a force: the middle one is
/// wanted for dq/dt alone, so 2 would do, and 1 with the last force reused.
const VELOCITY_VERLET_CLAIMS: SchemeMeta =
    claims("differential-equations-velocity-verlet", 2, true, 3);

impl ODE<f64, Vec<f64>> for FirstOrder<'_, f64> {
    fn diff(&self, _: f64, y: &Vec<f64>, dy: &mut Vec<f64>) {
        (self.0)(y, dy);
    }
}

/// A differential-equations solver object on first-order systems, kept
/// from step to step (with its last derivative): made by `method(h)` and
/// initialised on the first step of a run, and again should it be handed a
/// state other than its own (which the evaluation count would show as one
/// more call a step). The shape (`y = [q, v]` on slices) and the kept
/// object combine: `Shape::first_order_on_slices` inside
/// `BlackBox::stateful`.
fn kept<M>(meta: SchemeMeta, method: fn(f64) -> M) -> BlackBox<f64, impl BlackBoxStep<f64>>
where
    M: OrdinaryNumericalMethod<f64, Vec<f64>> + Clone + Send + Sync,
{
    let step = move |kept: &mut Option<M>, y: &mut [f64], h: f64, f: &Force<f64>| {
        let ode = FirstOrder(f);
        let solver = kept.get_or_insert_with(|| method(h));
        if *solver.status() == Status::Uninitialized || solver.y().as_slice() != y {
            solver.init(&ode, 0.0, h, &y.to_vec()).expect("a step of h");
        }
        solver.set_h(h);
        solver.step(&ode).expect("one step");
        y.copy_from_slice(solver.y());
    };
    BlackBox::stateful(meta, || None, Shape::first_order_on_slices(step))
}

type Rk4Object = ExplicitRungeKutta<Ordinary, Fixed, f64, Vec<f64>, 4, 4, 4>;
type Dopri5Object = ExplicitRungeKutta<Ordinary, DormandPrince, f64, Vec<f64>, 5, 7, 7>;

/// Fixed-step RK4: three new stages a step and the derivative at its end,
/// kept as the next step's first stage: 4, the least RK4 needs.
fn differential_equations_rk4() -> BlackBox<f64, impl BlackBoxStep<f64>> {
    kept(
        claims("differential-equations-rk4", 4, false, 4),
        |h| -> Rk4Object { ExplicitRungeKutta::rk4(h).max_steps(usize::MAX) },
    )
}

/// DOPRI5 at a fixed step (tolerances so loose every step is accepted; the
/// step is set to `h` before each): six new stages, the last at the new
/// point, then that derivative computed again for the next step: 7, where
/// the method needs 6.
fn differential_equations_dopri5(evaluations: u32) -> BlackBox<f64, impl BlackBoxStep<f64>> {
    kept(
        claims("differential-equations-dopri5", 5, false, evaluations),
        |h| -> Dopri5Object {
            ExplicitRungeKutta::dopri5()
                .rtol(1e30)
                .atol(1e30)
                .h0(h)
                .max_steps(usize::MAX)
        },
    )
}

/// A user scene from its potential alone: the pendulum `V = -cos q` from
/// one radian (no exact solution; the studies use half-step references).
#[derive(Clone, Copy)]
struct Pendulum;
impl Potential<1> for Pendulum {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "pendulum",
            name: "pendulum from 1 rad",
            dimension: 1,
            parameters: "q0 = 1".into(),
            reference: "V = -cos q",
        }
    }
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        -q[0].cos()
    }
    fn initial(&self) -> State<1> {
        State::new(Vector1::new(1.0), Vector1::new(0.0))
    }
    fn period(&self) -> f64 {
        // 4 K(sin^2(1/2)) for the amplitude 1 rad
        6.6993
    }
}

stepladder::guard_claims! {
    my_verlet: MyVerlet => {
        kepler_circular: KeplerCircular,
        kepler_eccentric: KeplerEccentric::new(0.6).unwrap(),
        pendulum: FromPotential(Pendulum),
    }
    engine_leapfrog_f32: BlackBox::new(claims("engine-leapfrog-f32", 2, true, 2), engine_adapter) => {
        kepler_circular: KeplerCircular,
    }
    ode_solvers_rk4: on_slices(RK4_CLAIMS, ode_solvers_rk4::<f64, 4>) => {
        kepler_circular: KeplerCircular,
        kepler_eccentric: KeplerEccentric::new(0.6).unwrap(),
    }
    ode_solvers_rk4_oscillator: on_slices(RK4_CLAIMS, ode_solvers_rk4::<f64, 2>) => {
        harmonic: Harmonic::default(),
        pendulum: FromPotential(Pendulum),
    }
    ode_solvers_dop853: on_slices(DOP853_CLAIMS, ode_solvers_dop853::<4>) => {
        kepler_circular: KeplerCircular,
    }
    ode_solvers_dop853_oscillator: on_slices(DOP853_CLAIMS, ode_solvers_dop853::<2>) => {
        harmonic: Harmonic::default(),
    }
    ode_solvers_dopri5: on_slices(DOPRI5_CLAIMS, ode_solvers_dopri5::<4>) => {
        kepler_circular: KeplerCircular,
    }
    utsuroi_stormer_verlet: utsuroi_stormer_verlet::<2>() => {
        kepler_circular: KeplerCircular,
        kepler_eccentric: KeplerEccentric::new(0.6).unwrap(),
    }
    utsuroi_stormer_verlet_oscillator: utsuroi_stormer_verlet::<1>() => {
        harmonic: Harmonic::default(),
    }
    utsuroi_yoshida4: utsuroi_yoshida4::<2>() => {
        kepler_circular: KeplerCircular,
        kepler_eccentric: KeplerEccentric::new(0.6).unwrap(),
    }
    utsuroi_yoshida4_oscillator: utsuroi_yoshida4::<1>() => {
        harmonic: Harmonic::default(),
    }
    differential_equations_velocity_verlet: BlackBox::canonical(VELOCITY_VERLET_CLAIMS, &[], velocity_verlet) => {
        harmonic: Harmonic::default(),
        kepler_circular: KeplerCircular,
        kepler_eccentric: KeplerEccentric::new(0.6).unwrap(),
    }
    differential_equations_rk4: differential_equations_rk4() => {
        harmonic: Harmonic::default(),
        kepler_circular: KeplerCircular,
        kepler_eccentric: KeplerEccentric::new(0.6).unwrap(),
    }
    differential_equations_dopri5: differential_equations_dopri5(7) => {
        harmonic: Harmonic::default(),
        kepler_circular: KeplerCircular,
        kepler_eccentric: KeplerEccentric::new(0.6).unwrap(),
    }
}

/// Integrators of three crates, wrapped by three different constructors
/// (one of them a solver object kept between steps), held in one list and
/// judged in one loop, each record's verdicts printed as a table row.
#[test]
fn integrators_of_three_crates_in_one_list_are_guarded_in_one_loop() {
    let all: Vec<AnyBlackBox> = vec![
        on_slices(RK4_CLAIMS, ode_solvers_rk4::<f64, 4>).boxed(),
        utsuroi_stormer_verlet::<2>().boxed(),
        utsuroi_yoshida4::<2>().boxed(),
        BlackBox::canonical(VELOCITY_VERLET_CLAIMS, &[], velocity_verlet).boxed(),
        differential_equations_rk4().boxed(),
    ];
    let mut table = String::from(
        "| integrator | order | symplectic | reversible | energy | evaluations |\n|---|---|---|---|---|---|\n",
    );
    for integrator in &all {
        let record = stepladder::study::claims(integrator, &KeplerCircular).unwrap();
        let verdicts: Vec<&str> = record.verdicts.iter().map(|v| v.verdict.name()).collect();
        table += &format!("| `{}` | {} |\n", record.scheme, verdicts.join(" | "));
        assert!(record.passed(), "{}", record.failures().join("\n"));
    }
    println!("{table}");
    assert_eq!(table.lines().count(), 2 + all.len());
}

/// Guards a broken variant must fail, named after the claim that catches it.
mod caught {
    use super::*;

    /// `ode_solvers`' RK4 claimed symplectic: the finite-difference tangent
    /// map refutes it.
    #[test]
    #[should_panic(expected = "not symplectic, though claimed")]
    fn rk4_claimed_symplectic() {
        let liar = on_slices(claims("rk4-liar", 4, true, 4), ode_solvers_rk4::<f64, 4>);
        assert_symplectic(&liar, &KeplerCircular);
    }

    /// The same in single precision, where the tangent map's error bound is
    /// about 1e-3 against RK4's defect of 3.5e-3 at ten steps a period.
    #[test]
    #[should_panic(expected = "not symplectic, though claimed")]
    fn rk4_f32_claimed_symplectic() {
        let liar = on_slices(
            claims("rk4-f32-liar", 4, true, 4),
            ode_solvers_rk4::<f32, 4>,
        );
        assert_symplectic(&liar, &KeplerCircular);
    }

    /// The engine's leap-frog with a full first kick (a classic slip): first
    /// order, not second.
    #[test]
    #[should_panic(expected = "order 2 claimed")]
    fn engine_with_a_full_first_kick() {
        fn full_kick(q: &mut [f32], v: &mut [f32], h: f32, force: &Force<f32>) {
            let mut a = [0.0f32; 2];
            force(q, &mut a);
            for i in 0..2 {
                v[i] += h * a[i];
                q[i] += h * v[i];
            }
            force(q, &mut a);
            for i in 0..2 {
                v[i] += 0.5 * h * a[i];
            }
        }
        assert_order(
            &BlackBox::new(claims("full-kick", 2, true, 2), full_kick),
            &KeplerCircular,
        );
    }

    /// RK4 with its weights 1, 2, 2, 1 reordered to 2, 1, 1, 2 (a refactor
    /// slip): still consistent and even second order (b.c = 1/2), but
    /// b.c^2 = 5/12, not 1/3, so not third; the order guard
    /// names it.
    #[test]
    #[should_panic(expected = "order 4 claimed")]
    fn rk4_with_reordered_weights() {
        fn reordered(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
            let (q0, v0) = ([q[0], q[1]], [v[0], v[1]]);
            let mut k = [[0.0; 4]; 4];
            let (mut x, mut u) = (q0, v0);
            for (stage, c) in [0.5, 0.5, 1.0, 1.0].into_iter().enumerate() {
                let mut a = [0.0; 2];
                force(&x, &mut a);
                k[stage] = [u[0], u[1], a[0], a[1]];
                // the next stage's point (unused after the last)
                for i in 0..2 {
                    x[i] = q0[i] + c * h * k[stage][i];
                    u[i] = v0[i] + c * h * k[stage][2 + i];
                }
            }
            let w = [2.0, 1.0, 1.0, 2.0];
            for i in 0..2 {
                q[i] = q0[i] + h / 6.0 * (0..4).map(|s| w[s] * k[s][i]).sum::<f64>();
                v[i] = v0[i] + h / 6.0 * (0..4).map(|s| w[s] * k[s][2 + i]).sum::<f64>();
            }
        }
        assert_order(
            &BlackBox::new(claims("rk4-reordered", 4, false, 4), reordered),
            &KeplerCircular,
        );
    }

    /// DOPRI5 is known for six evaluations a step (its last stage is the
    /// next step's first); differential-equations' object computes that
    /// derivative again, 7 a step. Wrapped with the textbook claim, the
    /// count names both figures.
    #[test]
    #[should_panic(expected = "7.00 force evaluations per step counted over 60 steps, 6 claimed")]
    fn dopri5_claimed_with_its_textbook_cost() {
        assert_evaluations(&differential_equations_dopri5(6), &KeplerCircular);
    }

    /// utsuroi's Störmer-Verlet claimed at the one evaluation a step of a
    /// Verlet that reuses its last force (the catalogue's claim): it spends
    /// two.
    #[test]
    #[should_panic(expected = "2.00 force evaluations per step counted over 60 steps, 1 claimed")]
    fn stormer_verlet_claimed_with_a_reused_force() {
        let under = utsuroi::<2>(claims("sv-under", 2, true, 1), |system, s, h| {
            StormerVerlet.step(system, 0.0, s, h)
        });
        assert_evaluations(&under, &KeplerCircular);
    }
}

/// DOP853 on the eccentric orbit: its local orders approach eight from
/// above (8.67 down to 8.02 over the last clean rungs before the f64
/// floor) without settling within the plateau tolerance, so the order
/// study cannot decide; it must say so, never refute the claim.
#[test]
fn ode_solvers_dop853_on_the_eccentric_orbit_is_never_refuted() {
    let dop853 = on_slices(DOP853_CLAIMS, ode_solvers_dop853::<4>);
    let orbit = KeplerEccentric::new(0.6).unwrap();
    let record = global_order(&dop853, &orbit, &OrderSpec::default()).unwrap();
    assert_ne!(record.verdict, Verdict::Fail, "{}", record.reason);
    assert_symplectic(&dop853, &orbit);
    assert_energy(&dop853, &orbit);
}

/// The f32 RK4 of ode_solvers: a fourth-order method in single precision
/// has little room between its asymptotic range and the f32 floor, so on
/// the orbit the order study may not find a window; it must then say
/// "inconclusive", never refute the claim.
#[test]
fn ode_solvers_rk4_in_f32_is_never_refuted() {
    let rk4_f32 = on_slices(
        claims("ode-solvers-rk4-f32", 4, false, 4),
        ode_solvers_rk4::<f32, 4>,
    );
    let record = global_order(&rk4_f32, &KeplerCircular, &OrderSpec::default()).unwrap();
    assert_ne!(record.verdict, Verdict::Fail, "{}", record.reason);
    assert_symplectic(&rk4_f32, &KeplerCircular);
    assert_evaluations(&rk4_f32, &KeplerCircular);
}

// ode_solvers' DOPRI5 as users run it: adaptive, from t0 to t1 at a
// tolerance, through `AdaptiveBlackBox`. The same first-order system as
// above, on ode_solvers' vectors, from the force alone.
struct Newton<'f>(&'f Force<'f, f64>);

impl System<f64, OdeVector<f64, 4>> for Newton<'_> {
    fn system(&self, _: f64, y: &OdeVector<f64, 4>, dy: &mut OdeVector<f64, 4>) {
        let mut a = [0.0; 2];
        (self.0)(&y.as_slice()[..2], &mut a);
        *dy = OdeVector::<f64, 4>::new(y[2], y[3], a[0], a[1]);
    }
}

/// DOPRI5 with the defaults of `Dopri5::new` from `t0` to `t1` at `tol`
/// (relative and absolute), its statistics reported for the count's check;
/// output at the accepted steps (`new`'s dense output at a spacing of the
/// whole span stores only the start).
fn dopri5_adaptive(
    q: &mut [f64],
    v: &mut [f64],
    t0: f64,
    t1: f64,
    tol: f64,
    force: &Force<f64>,
) -> Advance {
    let y0 = OdeVector::<f64, 4>::new(q[0], q[1], v[0], v[1]);
    let span = t1 - t0;
    let mut solver = Dopri5::from_param(
        Newton(force),
        t0,
        t1,
        span,
        y0,
        tol,
        tol, // f, x, x_end, dx, y, rtol, atol
        0.9,
        0.04,
        0.2,
        10.0,
        span,
        0.0, // safety, beta, fac_min, fac_max, h_max, h
        100_000,
        1000,
        OutputType::Sparse, // n_max, n_stiff, output
    );
    let Ok(stats) = solver.integrate() else {
        return Advance {
            end: RunEnd::GaveUp,
            ..Advance::reached()
        };
    };
    let y = solver.y_out().last().expect("the run's end");
    q.copy_from_slice(&y.as_slice()[..2]);
    v.copy_from_slice(&y.as_slice()[2..]);
    Advance {
        accepted: stats.accepted_steps as u64,
        rejected: stats.rejected_steps as u64,
        end: RunEnd::Reached,
        reported_evaluations: Some(stats.num_eval as u64),
    }
}

/// DOPRI5: order 5, its embedded solution order 4 (estimate ~ h^5).
static DOPRI5_ADAPTIVE: AdaptiveBlackBox<AdvanceFn> = AdaptiveBlackBox::new(
    "ode-solvers-dopri5-adaptive",
    AdaptiveClaims::pair(5, 4),
    dopri5_adaptive,
);

stepladder::guard_adaptive! {
    ode_solvers_dopri5_adaptive: DOPRI5_ADAPTIVE => { kepler_circular: KeplerCircular }
}
