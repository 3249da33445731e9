//! Nanoseconds per step of every catalogue scheme on the circular orbit,
//! beside a hand-written velocity Verlet loop on plain `f64` (the floor a
//! generic scheme should reach). Run with `cargo bench`; `cargo bench --
//! --quick` for a short run.

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use std::f64::consts::{PI, TAU};
use std::hint::black_box;
use stepladder::scene::{KeplerCircular, Scene};
use stepladder::scheme::{Scheme, SchemeVisitor, scheme_ids, visit_scheme};

/// Steps per measured iteration: long enough that set-up is negligible.
const STEPS: u64 = 10_000;
const H: f64 = 1e-3;

/// Velocity Verlet for `r'' = -4 pi^2 r / |r|^3`, written out by hand.
#[inline(never)]
fn hand_written_verlet(
    mut q: [f64; 2],
    mut v: [f64; 2],
    h: f64,
    steps: u64,
) -> ([f64; 2], [f64; 2]) {
    let gm = 4.0 * PI * PI;
    let accel = |q: [f64; 2]| {
        let r2 = q[0] * q[0] + q[1] * q[1];
        let k = -gm / (r2 * r2.sqrt());
        [k * q[0], k * q[1]]
    };
    let mut a = accel(q);
    for _ in 0..steps {
        v = [v[0] + 0.5 * h * a[0], v[1] + 0.5 * h * a[1]];
        q = [q[0] + h * v[0], q[1] + h * v[1]];
        a = accel(q);
        v = [v[0] + 0.5 * h * a[0], v[1] + 0.5 * h * a[1]];
    }
    (q, v)
}

struct BenchScheme<'a, 'b>(&'a mut criterion::BenchmarkGroup<'b, criterion::measurement::WallTime>);

impl SchemeVisitor for BenchScheme<'_, '_> {
    type Output = ();
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) {
        let scene = KeplerCircular;
        self.0.bench_function(scheme.meta().id, |b| {
            b.iter_batched(
                || scheme.start(&scene, &scene.initial(), H),
                |mut carry| {
                    let h = black_box(H);
                    for _ in 0..STEPS {
                        scheme.step(&scene, &mut carry, h).expect("explicit step");
                    }
                    carry
                },
                BatchSize::SmallInput,
            )
        });
    }
}

fn steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("kepler-circular");
    group.throughput(Throughput::Elements(STEPS));
    group.bench_function("hand-written velocity Verlet", |b| {
        b.iter(|| {
            hand_written_verlet(
                black_box([1.0, 0.0]),
                black_box([0.0, TAU]),
                black_box(H),
                STEPS,
            )
        })
    });
    for id in scheme_ids() {
        visit_scheme(id, BenchScheme(&mut group)).expect("catalogue id");
    }
    group.finish();
}

criterion_group!(benches, steps);
criterion_main!(benches);
