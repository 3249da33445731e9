//! Guards for three integrators this crate does not control in the same
//! way: its own generic velocity Verlet, an f32 leap-frog as a game engine
//! would write it, and `ode_solvers`' fixed-step RK4 (f64 and f32) and its
//! DOP853 and DOPRI5 pairs taken one step at a time, each claim a separate
//! test named after it.

use ode_solvers::{Dop853, Dopri5, OutputType, Rk4, System, Vector2, Vector4};
use std::cell::RefCell;
use stepladder::nalgebra::{SVector, Vector1};
use stepladder::scene::{
    FromPotential, Harmonic, KeplerCircular, KeplerEccentric, Potential, Scene, SceneMeta,
};
use stepladder::scheme::{BlackBox, Float, Force, OneStep, SchemeMeta, StepFailure, StepFn};
use stepladder::state::{Real, State};

/// Claims shared by the tables below.
const fn claims(id: &'static str, order: u32, symplectic: bool, evaluations: u32) -> SchemeMeta {
    SchemeMeta {
        id,
        name: id,
        order,
        symplectic,
        symmetric: symplectic,
        force_evaluations: evaluations,
        implicit: false,
        reference: "the downstream crate",
        phase_error: None,
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
fn engine_adapter(q: &mut [f32], v: &mut [f32], h: f32, force: &mut Force<f32>) {
    let force = RefCell::new(force);
    let to = |s: &[f32]| {
        s.chunks(2)
            .map(|c| Vec2f { x: c[0], y: c[1] })
            .collect::<Vec<_>>()
    };
    let (mut pos, mut vel) = (to(q), to(v));
    engine_step(&mut pos, &mut vel, h, |p: &[Vec2f]| {
        let flat: Vec<f32> = p.iter().flat_map(|p| [p.x, p.y]).collect();
        let mut a = vec![0.0; flat.len()];
        (force.borrow_mut())(&flat, &mut a);
        to(&a)
    });
    for (i, (p, w)) in pos.iter().zip(&vel).enumerate() {
        (q[2 * i], q[2 * i + 1], v[2 * i], v[2 * i + 1]) = (p.x, p.y, w.x, w.y);
    }
}

/// `ode_solvers`' RK4 takes first-order systems `y' = f(x, y)`; this is
/// `y = (q, v)`, `y' = (v, a(q))` with the force the studies hand in.
struct Newton<'f, 'a, T: Float> {
    force: RefCell<&'f mut Force<'a, T>>,
}

macro_rules! newton_system {
    ($t:ty, $vector:ident, $n:literal) => {
        impl System<$t, $vector<$t>> for Newton<'_, '_, $t> {
            fn system(&self, _: $t, y: &$vector<$t>, dy: &mut $vector<$t>) {
                let mut a = [0.0; $n];
                (self.force.borrow_mut())(&y.as_slice()[..$n], &mut a);
                for i in 0..$n {
                    dy[i] = y[$n + i];
                    dy[$n + i] = a[i];
                }
            }
        }
    };
}
newton_system!(f64, Vector2, 1);
newton_system!(f64, Vector4, 2);
newton_system!(f32, Vector2, 1);
newton_system!(f32, Vector4, 2);

/// One step of `ode_solvers::Rk4` of size `h`: a solver from 0 to `h`.
macro_rules! ode_solvers_rk4 {
    ($name:ident, $t:ty, $vector:ident, $n:literal) => {
        fn $name(q: &mut [$t], v: &mut [$t], h: $t, force: &mut Force<$t>) {
            let y0 = $vector::<$t>::from_fn(|i, _| if i < $n { q[i] } else { v[i - $n] });
            let system = Newton {
                force: RefCell::new(force),
            };
            let mut solver = Rk4::new(system, 0.0, y0, h, h);
            solver.integrate().expect("one fixed step");
            let y = solver.y_out().last().expect("the step's output");
            for i in 0..$n {
                q[i] = y[i];
                v[i] = y[$n + i];
            }
        }
    };
}
/// One step of an `ode_solvers` embedded pair (`Dop853`, `Dopri5`) of size
/// `h`: the first step set to `h`, the largest to `h`, and tolerances so
/// loose that the step is accepted, so the call is one step of the pair's
/// high-order formula. (At working tolerances the solver would subdivide
/// `h`, and the ladder would measure its step control instead.)
macro_rules! ode_solvers_pair {
    ($name:ident, $solver:ident, $n:literal, $vector:ident) => {
        fn $name(q: &mut [f64], v: &mut [f64], h: f64, force: &mut Force<f64>) {
            let y0 = $vector::<f64>::from_fn(|i, _| if i < $n { q[i] } else { v[i - $n] });
            let system = Newton {
                force: RefCell::new(force),
            };
            let mut solver = $solver::from_param(
                system,
                0.0,
                h,
                h,
                y0,
                1e30,
                1e30,
                0.9,
                0.0,
                0.333,
                6.0,
                h,
                h,
                10,
                1000,
                OutputType::Sparse,
            );
            let stats = solver.integrate().expect("one step");
            assert_eq!(stats.accepted_steps, 1, "{stats:?}");
            let y = solver.y_out().last().expect("the step's output");
            for i in 0..$n {
                q[i] = y[i];
                v[i] = y[$n + i];
            }
        }
    };
}
ode_solvers_pair!(dop853_2d, Dop853, 2, Vector4);
ode_solvers_pair!(dop853_1d, Dop853, 1, Vector2);
ode_solvers_pair!(dopri5_2d, Dopri5, 2, Vector4);

ode_solvers_rk4!(rk4_f64_1d, f64, Vector2, 1);
ode_solvers_rk4!(rk4_f64_2d, f64, Vector4, 2);
ode_solvers_rk4!(rk4_f32_2d, f32, Vector4, 2);

const RK4_CLAIMS: SchemeMeta = claims("ode-solvers-rk4", 4, false, 4);

fn ode_solvers_rk4_1d() -> BlackBox<f64, StepFn<f64>> {
    BlackBox::new(RK4_CLAIMS, rk4_f64_1d)
}
fn ode_solvers_rk4_2d() -> BlackBox<f64, StepFn<f64>> {
    BlackBox::new(RK4_CLAIMS, rk4_f64_2d)
}
fn ode_solvers_rk4_f32() -> BlackBox<f32, StepFn<f32>> {
    BlackBox::new(claims("ode-solvers-rk4-f32", 4, false, 4), rk4_f32_2d)
}
fn ode_solvers_dop853() -> BlackBox<f64, StepFn<f64>> {
    BlackBox::new(claims("ode-solvers-dop853", 8, false, 12), dop853_2d)
}
fn ode_solvers_dop853_1d() -> BlackBox<f64, StepFn<f64>> {
    BlackBox::new(claims("ode-solvers-dop853", 8, false, 12), dop853_1d)
}
fn ode_solvers_dopri5() -> BlackBox<f64, StepFn<f64>> {
    BlackBox::new(claims("ode-solvers-dopri5", 5, false, 7), dopri5_2d)
}
fn engine() -> BlackBox<f32, StepFn<f32>> {
    BlackBox::new(claims("engine-leapfrog-f32", 2, true, 2), engine_adapter)
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
    ode_solvers_rk4: ode_solvers_rk4_2d() => {
        kepler_circular: KeplerCircular,
        kepler_eccentric: KeplerEccentric::new(0.6).unwrap(),
    }
    ode_solvers_rk4_oscillator: ode_solvers_rk4_1d() => {
        harmonic: Harmonic::default(),
        pendulum: FromPotential(Pendulum),
    }
    ode_solvers_dop853: ode_solvers_dop853() => {
        kepler_circular: KeplerCircular,
    }
    ode_solvers_dop853_oscillator: ode_solvers_dop853_1d() => {
        harmonic: Harmonic::default(),
    }
    ode_solvers_dopri5: ode_solvers_dopri5() => {
        kepler_circular: KeplerCircular,
    }
    engine_leapfrog_f32: engine() => {
        kepler_circular: KeplerCircular,
    }
}

/// Guards a broken variant must fail, named after the claim that catches it.
mod caught {
    use super::*;
    use stepladder::guard;

    /// `ode_solvers`' RK4 claimed symplectic: the finite-difference tangent
    /// map refutes it.
    #[test]
    #[should_panic(expected = "not symplectic, though claimed")]
    fn rk4_claimed_symplectic() {
        let liar = BlackBox::new(claims("rk4-liar", 4, true, 4), rk4_f64_2d);
        guard::assert_symplectic(&liar, &KeplerCircular);
    }

    /// The same in single precision, where the tangent map's error bound is
    /// about 1e-3 against RK4's defect of 3.5e-3 at ten steps a period.
    #[test]
    #[should_panic(expected = "not symplectic, though claimed")]
    fn rk4_f32_claimed_symplectic() {
        let liar = BlackBox::new(claims("rk4-f32-liar", 4, true, 4), rk4_f32_2d);
        guard::assert_symplectic(&liar, &KeplerCircular);
    }

    /// The engine's leap-frog with a full first kick (a classic slip): first
    /// order, not second.
    #[test]
    #[should_panic(expected = "order 2 claimed")]
    fn engine_with_a_full_first_kick() {
        fn full_kick(q: &mut [f32], v: &mut [f32], h: f32, force: &mut Force<f32>) {
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
        guard::assert_order(
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
        fn reordered(q: &mut [f64], v: &mut [f64], h: f64, force: &mut Force<f64>) {
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
        guard::assert_order(
            &BlackBox::new(claims("rk4-reordered", 4, false, 4), reordered),
            &KeplerCircular,
        );
    }
}

/// DOP853 on the eccentric orbit: its local orders approach eight from
/// above (8.67 down to 8.02 over the last clean rungs before the f64
/// floor) without settling within the plateau tolerance, so the order
/// study cannot decide; it must say so, never refute the claim.
#[test]
fn ode_solvers_dop853_on_the_eccentric_orbit_is_never_refuted() {
    use stepladder::measure::Verdict;
    use stepladder::measure::accuracy::order::{OrderSpec, global_order};
    let orbit = KeplerEccentric::new(0.6).unwrap();
    let record = global_order(&ode_solvers_dop853(), &orbit, &OrderSpec::default()).unwrap();
    assert_ne!(record.verdict, Verdict::Fail, "{}", record.reason);
    stepladder::guard::assert_symplectic(&ode_solvers_dop853(), &orbit);
    stepladder::guard::assert_energy(&ode_solvers_dop853(), &orbit);
}

/// The f32 RK4 of ode_solvers: a fourth-order method in single precision
/// has little room between its asymptotic range and the f32 floor, so on
/// the orbit the order study may not find a window; it must then say
/// "inconclusive", never refute the claim.
#[test]
fn ode_solvers_rk4_in_f32_is_never_refuted() {
    use stepladder::measure::Verdict;
    use stepladder::measure::accuracy::order::{OrderSpec, global_order};
    let record = global_order(
        &ode_solvers_rk4_f32(),
        &KeplerCircular,
        &OrderSpec::default(),
    )
    .unwrap();
    assert_ne!(record.verdict, Verdict::Fail, "{}", record.reason);
    stepladder::guard::assert_symplectic(&ode_solvers_rk4_f32(), &KeplerCircular);
}
