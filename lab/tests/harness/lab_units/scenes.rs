use stepladder::internals::accuracy::scene_check::check_scene;
use stepladder::internals::run::integrate;
use stepladder::scene::Scene;
use stepladder::scheme::{KAHAN_LI8, VELOCITY_VERLET};
use stepladder::study::Verdict;
use stepladder_lab::corpus::scenes::*;

#[test]
fn every_scene_is_conservative_and_the_morse_solution_solves_it() {
    assert_eq!(check_scene(&FigureEight).verdict, Verdict::Pass);
    assert_eq!(check_scene(&Pendulum::default()).verdict, Verdict::Pass);
    assert_eq!(check_scene(&HenonHeiles).verdict, Verdict::Pass);
    assert_eq!(check_scene(&FputChain).verdict, Verdict::Pass);
    let morse = check_scene(&Morse::default());
    assert_eq!(morse.verdict, Verdict::Pass, "{morse:?}");
    assert!(morse.acceleration_residual.unwrap() < 1e-8);
}

/// Energy along a fine Verlet run: a wrong force would not conserve the
/// potential's energy.
fn energy_drift<S: Scene<D>, const D: usize>(scene: &S) -> f64 {
    let e0 = scene.energy(&scene.initial());
    let steps = 4000;
    let h = 2.0 * scene.period() / steps as f64;
    let mut worst = 0.0f64;
    integrate(
        &VELOCITY_VERLET,
        scene,
        &scene.initial(),
        h,
        steps,
        |_, _, s| {
            worst = worst.max(((scene.energy(s) - e0) / e0).abs());
        },
    );
    worst
}

#[test]
fn a_fine_verlet_run_conserves_each_scenes_energy() {
    assert!(energy_drift(&FigureEight) < 1e-4);
    assert!(energy_drift(&Pendulum::default()) < 1e-4);
    assert!(energy_drift(&HenonHeiles) < 1e-5);
    assert!(energy_drift(&FputChain) < 1e-5);
    assert!(energy_drift(&Morse::default()) < 1e-5);
}

#[test]
fn the_figure_eight_closes_after_its_period() {
    // three bodies back at their start after one period, to the 8 digits
    // of the published initial conditions
    let s = FigureEight;
    let steps = 20_000;
    let mut last = s.initial();
    integrate(
        &KAHAN_LI8,
        &s,
        &s.initial(),
        FigureEight::PERIOD / steps as f64,
        steps,
        |_, _, x| last = *x,
    );
    assert!(
        (last.q - s.initial().q).amax() < 1e-6,
        "{:?}",
        last.q - s.initial().q
    );
}

#[test]
fn the_pendulum_period_is_four_k() {
    // half periods from velocity sign changes of a fine run
    let p = Pendulum::default();
    let h = 1e-4;
    let (mut last_v, mut crossings, mut last_t) = (0.0f64, Vec::new(), 0.0);
    integrate(&KAHAN_LI8, &p, &p.initial(), h, 400_000, |_, t, s| {
        if last_v < 0.0 && s.v[0] >= 0.0 || last_v > 0.0 && s.v[0] <= 0.0 {
            // interpolated zero of v between the steps
            crossings.push(last_t + h * last_v / (last_v - s.v[0]));
        }
        (last_v, last_t) = (s.v[0], t);
    });
    let period = crossings[2] - crossings[0];
    assert!(
        (period / p.period() - 1.0).abs() < 1e-6,
        "{period} vs {}",
        p.period()
    );
    // 4 K(m) at m = sin^2(1.5) = 0.99499 from tables: 4 * 3.3456 (A&S 17.1)
    assert!((p.period() - 16.6).abs() < 0.5);
}

#[test]
fn the_henon_heiles_orbit_is_regular() {
    // two orbits 1e-9 apart separate linearly on a torus (by a factor of
    // the order of the time), exponentially in a chaotic layer (Lyapunov
    // exponents there are about 0.1: e^100 over this run)
    let s = HenonHeiles;
    let mut moved = s.initial();
    moved.q[1] += 1e-9;
    let steps = 100_000;
    let h = 1000.0 / steps as f64;
    let (mut a, mut b) = (Vec::new(), Vec::new());
    integrate(&KAHAN_LI8, &s, &s.initial(), h, steps, |_, _, x| a.push(*x));
    integrate(&KAHAN_LI8, &s, &moved, h, steps, |_, _, x| b.push(*x));
    let separation = a
        .iter()
        .zip(&b)
        .map(|(x, y)| s.phase_distance(x, y))
        .fold(0.0, f64::max);
    assert!(separation < 1e-5, "separation {separation}");
}

#[test]
fn the_morse_orbit_starts_at_its_turning_point_and_closes() {
    let m = Morse::default();
    let s = m.initial();
    assert_eq!(s.v[0], 0.0);
    assert!((s.q[0] + (1.0 + 0.5f64.sqrt()).ln()).abs() < 1e-15);
    let back = m.exact(m.period()).unwrap();
    assert!(m.phase_distance(&s, &back) < 1e-12);
    assert!((m.energy(&m.exact(1.234).unwrap()) - 0.5).abs() < 1e-14);
}
