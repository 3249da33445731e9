//! What one guard call costs a downstream test suite: `assert_claims`
//! (order, symplecticity, reversibility, energy, force evaluations) on the
//! smooth built-in scenes and on the seven-body Pleiades, for the
//! eighth-order schemes of the catalogue, and `assert_order` on the
//! Pleiades.
//!
//! The budgets these keep visible (README, "Speed"): under 1 s for an
//! eighth-order scheme on a smooth scene of dimension up to 6, under 3 s on
//! the seven-body scene. A budget is read off the median here, never
//! asserted in a test: the machines that run tests are shared and noisy.
//!
//! `cargo bench --bench guard` for the full run (about two minutes);
//! `cargo bench --bench guard -- pleiades` for one scene.

use criterion::{
    BenchmarkGroup, Criterion, criterion_group, criterion_main, measurement::WallTime,
};
use std::time::Duration;
use stepladder::guard;
use stepladder::scene::{Anharmonic, Harmonic, KeplerCircular, KeplerEccentric, Pleiades, Scene};
use stepladder::scheme::{DPRKN8, KAHAN_LI8, Scheme};

/// A group for calls of 0.05 to 3 s: ten samples give the median to a few
/// percent.
fn guard_group<'a>(c: &'a mut Criterion, name: &str) -> BenchmarkGroup<'a, WallTime> {
    let mut g = c.benchmark_group(name);
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(5));
    g
}

/// Every claim of both eighth-order schemes on `scene`, as a downstream
/// test calls it.
fn claims<S: Scene<D>, const D: usize>(c: &mut Criterion, scene: &S) {
    let mut g = guard_group(c, &format!("assert_claims/{}", scene.meta().id));
    g.bench_function(KAHAN_LI8.meta().id, |b| {
        b.iter(|| guard::assert_claims(&KAHAN_LI8, scene))
    });
    g.bench_function(DPRKN8.meta().id, |b| {
        b.iter(|| guard::assert_claims(&DPRKN8, scene))
    });
    g.finish();
}

fn smooth(c: &mut Criterion) {
    claims(c, &Harmonic::default());
    claims(c, &KeplerCircular);
    claims(c, &KeplerEccentric::default());
    claims(c, &Anharmonic::default());
}

/// On the Pleiades the guard a user calls is the order: the stars' close
/// encounters near `t = 1.2` to `1.5` leave a fixed step no energy law to
/// keep over the energy study's long run, and the scene's invariants, not an
/// exact solution, are what the order study checks there.
fn seven_bodies(c: &mut Criterion) {
    let scene = Pleiades::default();
    let mut g = guard_group(c, "assert_order/pleiades");
    g.bench_function(KAHAN_LI8.meta().id, |b| {
        b.iter(|| guard::assert_order(&KAHAN_LI8, &scene))
    });
    g.bench_function(DPRKN8.meta().id, |b| {
        b.iter(|| guard::assert_order(&DPRKN8, &scene))
    });
    g.finish();
}

criterion_group!(benches, smooth, seven_bodies);
criterion_main!(benches);
