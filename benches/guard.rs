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

use criterion::{Criterion, criterion_group, criterion_main};
use std::time::Duration;
use stepladder::guard;
use stepladder::scene::{Anharmonic, Harmonic, KeplerCircular, KeplerEccentric, Pleiades, Scene};
use stepladder::scheme::{DPRKN8, KAHAN_LI8, Scheme};

/// Every claim of `scheme` on `scene`, as a downstream test calls it.
fn claims<M: Scheme, S: Scene<D>, const D: usize>(
    c: &mut Criterion,
    group: &str,
    scheme: &M,
    scene: &S,
) {
    let mut g = c.benchmark_group(group);
    // a call takes 0.05 to 3 s: ten samples give the median to a few percent
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(5));
    g.bench_function(scheme.meta().id, |b| {
        b.iter(|| guard::assert_claims(scheme, scene))
    });
    g.finish();
}

fn smooth(c: &mut Criterion) {
    claims(
        c,
        "assert_claims/harmonic",
        &KAHAN_LI8,
        &Harmonic::default(),
    );
    claims(c, "assert_claims/harmonic", &DPRKN8, &Harmonic::default());
    claims(
        c,
        "assert_claims/kepler-circular",
        &KAHAN_LI8,
        &KeplerCircular,
    );
    claims(c, "assert_claims/kepler-circular", &DPRKN8, &KeplerCircular);
    claims(
        c,
        "assert_claims/kepler-eccentric",
        &KAHAN_LI8,
        &KeplerEccentric::default(),
    );
    claims(
        c,
        "assert_claims/kepler-eccentric",
        &DPRKN8,
        &KeplerEccentric::default(),
    );
    claims(
        c,
        "assert_claims/anharmonic",
        &KAHAN_LI8,
        &Anharmonic::default(),
    );
    claims(
        c,
        "assert_claims/anharmonic",
        &DPRKN8,
        &Anharmonic::default(),
    );
}

/// On the Pleiades the guard a user calls is the order: the stars' close
/// encounters near `t = 1.2` to `1.5` leave a fixed step no energy law to
/// keep over the energy study's long run, and the scene's invariants, not an
/// exact solution, are what the order study checks there.
fn seven_bodies(c: &mut Criterion) {
    let scene = Pleiades::default();
    let mut g = c.benchmark_group("assert_order/pleiades");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(10));
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
