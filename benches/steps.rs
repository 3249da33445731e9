//! Nanoseconds per step of every catalogue scheme on the oscillator and on
//! the circular orbit. On the orbit, beside them: the floor, a hand-written
//! velocity Verlet loop on plain `f64` (one force evaluation a step), and a
//! peer, the `ode_solvers` crate's fixed-step `Rk4` and adaptive `Dop853`
//! on the same problem, which is what a Rust user would otherwise reach for.
//!
//! Throughput is in steps, so criterion reports time per step; set-up (the
//! scheme's start, the peer's construction) is outside the timed routine.
//! `cargo bench` for the full run, `cargo bench -- --quick` for a short one,
//! `cargo bench -- kepler-circular` for one group.

use criterion::{
    BatchSize, BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main,
    measurement::WallTime,
};
use ode_solvers::{Dop853, OutputType, Rk4, System, Vector4};
use std::f64::consts::PI;
use std::hint::black_box;
use stepladder::internals::cost::step_time::{floor_verlet_kepler, run_steps};
use stepladder::scene::{Harmonic, KeplerCircular, Scene};
use stepladder::scheme::{Scheme, SchemeVisitor, scheme_ids, visit_scheme};

/// Steps per measured iteration: long enough that set-up is negligible.
const STEPS: u64 = 10_000;

/// The step, in periods of the scene.
const STEP: f64 = 1e-3;

/// The peer's adaptive tolerance (relative and absolute).
const PEER_TOLERANCE: f64 = 1e-10;

/// Every catalogue scheme on `scene`, `STEPS` steps an iteration.
struct BenchScheme<'a, 'b, S, const D: usize>(&'a mut BenchmarkGroup<'b, WallTime>, S);

impl<S: Scene<D> + Copy, const D: usize> SchemeVisitor for BenchScheme<'_, '_, S, D> {
    type Output = ();
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) {
        let scene = self.1;
        let h = STEP * scene.period();
        self.0.bench_function(scheme.meta().id, |b| {
            b.iter_batched(
                || scheme.start(&scene, &scene.initial(), h),
                |mut carry| {
                    run_steps(scheme, &scene, &mut carry, black_box(h), STEPS)
                        .expect("a small step succeeds");
                    carry
                },
                BatchSize::SmallInput,
            )
        });
    }
}

/// The circular orbit for the peer: `y = (x, y, vx, vy)`,
/// `y' = (vx, vy, -GM r/|r|^3)`.
struct KeplerSystem;

impl System<f64, Vector4<f64>> for KeplerSystem {
    fn system(&self, _t: f64, y: &Vector4<f64>, dy: &mut Vector4<f64>) {
        let r2 = y[0] * y[0] + y[1] * y[1];
        let k = -(4.0 * PI * PI) / (r2 * r2.sqrt());
        dy[0] = y[2];
        dy[1] = y[3];
        dy[2] = k * y[0];
        dy[3] = k * y[1];
    }
}

fn kepler_start() -> Vector4<f64> {
    let s = KeplerCircular.initial();
    Vector4::new(s.q[0], s.q[1], s.v[0], s.v[1])
}

fn peer_rk4(h: f64) -> Rk4<f64, Vector4<f64>, KeplerSystem> {
    Rk4::new(KeplerSystem, 0.0, kepler_start(), STEPS as f64 * h, h)
}

fn peer_dop853(t_end: f64) -> Dop853<f64, Vector4<f64>, KeplerSystem> {
    let mut solver = Dop853::new(
        KeplerSystem,
        0.0,
        t_end,
        t_end,
        kepler_start(),
        PEER_TOLERANCE,
        PEER_TOLERANCE,
    );
    solver.set_output(OutputType::Sparse);
    solver
}

fn harmonic(c: &mut Criterion) {
    let mut group = c.benchmark_group("harmonic");
    group.throughput(Throughput::Elements(STEPS));
    for id in scheme_ids() {
        visit_scheme(id, BenchScheme::<_, 1>(&mut group, Harmonic::default()))
            .expect("catalogue id");
    }
    group.finish();
}

fn kepler(c: &mut Criterion) {
    let mut group = c.benchmark_group("kepler-circular");
    let h = STEP * KeplerCircular.period();
    group.throughput(Throughput::Elements(STEPS));
    group.bench_function("floor: hand-written velocity Verlet", |b| {
        let s = KeplerCircular.initial();
        b.iter(|| {
            floor_verlet_kepler(
                black_box([s.q[0], s.q[1]]),
                black_box([s.v[0], s.v[1]]),
                black_box(h),
                STEPS,
            )
        })
    });
    for id in scheme_ids() {
        visit_scheme(id, BenchScheme::<_, 2>(&mut group, KeplerCircular)).expect("catalogue id");
    }
    // the peer's fixed step: its own count of steps sets the throughput
    let steps = {
        let mut dry = peer_rk4(h);
        dry.integrate().expect("fixed steps").accepted_steps
    };
    group.throughput(Throughput::Elements(steps as u64));
    group.bench_function("ode_solvers Rk4 (fixed step)", |b| {
        b.iter_batched(
            || peer_rk4(black_box(h)),
            |mut solver| {
                solver.integrate().expect("fixed steps");
                solver
            },
            BatchSize::SmallInput,
        )
    });
    // the adaptive peer over the same time, per step it accepts (12 force
    // evaluations each, plus its rejected steps')
    let t_end = STEPS as f64 * h;
    let steps = {
        let mut dry = peer_dop853(t_end);
        dry.integrate().expect("converges").accepted_steps
    };
    group.throughput(Throughput::Elements(steps as u64));
    group.bench_function(
        "ode_solvers Dop853 (tolerance 1e-10, per accepted step)",
        |b| {
            b.iter_batched(
                || peer_dop853(black_box(t_end)),
                |mut solver| {
                    solver.integrate().expect("converges");
                    solver
                },
                BatchSize::SmallInput,
            )
        },
    );
    group.finish();
}

criterion_group!(benches, kepler, harmonic);
criterion_main!(benches);
