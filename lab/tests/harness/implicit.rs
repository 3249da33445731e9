//! The implicit midpoint rule's solve: it reaches round-off in a few
//! iterations on ordinary steps, reports a step it cannot solve instead of
//! returning a wrong state, and gives the map the theory says.

use stepladder::scene::{Counted, Harmonic, KeplerCircular, Scene};
use stepladder::scheme::{ImplicitMidpoint, MAX_ITERATIONS, Scheme, StepFailure};

/// On `x'' = -w^2 x` the implicit midpoint rule is the Cayley transform
/// `y1 = (1 - h J/2)^-1 (1 + h J/2) y0` of `J = [[0, 1], [-w^2, 0]]`:
/// with `z = (h w / 2)^2`, `x1 = ((1 - z) x0 + h v0) / (1 + z)` and
/// `v1 = ((1 - z) v0 - h w^2 x0) / (1 + z)`. The solved step must match it to
/// round-off, and conserve the energy.
#[test]
fn one_step_on_the_oscillator_is_the_cayley_transform() {
    for (w, h) in [(1.0, 0.1), (1.0, 0.7), (3.0, 0.05), (0.2, 2.0)] {
        let osc = Harmonic::new(w, 0.8, -0.3).unwrap();
        let s0 = osc.initial();
        let (x0, v0) = (s0.q[0], s0.v[0]);
        let z = (h * w / 2.0) * (h * w / 2.0);
        let x1 = ((1.0 - z) * x0 + h * v0) / (1.0 + z);
        let v1 = ((1.0 - z) * v0 - h * w * w * x0) / (1.0 + z);
        // the cold start's predictor, and a warm one from a previous midpoint:
        // the solved step must not depend on where the iteration starts
        for predictor in [0.0, -w * w * x0] {
            let mut c = ImplicitMidpoint.start(&osc, &s0, h);
            c.a[0] = predictor;
            ImplicitMidpoint.step(&osc, &mut c, h).unwrap();
            let s1 = ImplicitMidpoint.state(&c, h);
            let tol = 8.0 * f64::EPSILON * (x0.abs() + v0.abs() / w);
            assert!(
                (s1.q[0] - x1).abs() <= tol,
                "w {w} h {h}: x {} vs {x1}",
                s1.q[0]
            );
            assert!(
                (s1.v[0] - v1).abs() <= tol * w,
                "w {w} h {h}: v {} vs {v1}",
                s1.v[0]
            );
            let (e0, e1) = (osc.energy(&s0), osc.energy(&s1));
            assert!((e1 - e0).abs() <= 16.0 * f64::EPSILON * e0, "{e0} -> {e1}");
        }
    }
}

/// Stepping with `-h` undoes a step with `h` (the rule is symmetric), to
/// round-off, on the nonlinear orbit.
#[test]
fn a_step_back_undoes_a_step_on_the_orbit() {
    let scene = KeplerCircular;
    let s0 = scene.initial();
    let h = 0.01;
    let mut c = ImplicitMidpoint.start(&scene, &s0, h);
    ImplicitMidpoint.step(&scene, &mut c, h).unwrap();
    let s1 = ImplicitMidpoint.state(&c, h);
    let mut back = ImplicitMidpoint.start(&scene, &s1, -h);
    ImplicitMidpoint.step(&scene, &mut back, -h).unwrap();
    let d = scene.phase_distance(&ImplicitMidpoint.state(&back, -h), &s0);
    assert!(d < 1e-14, "{d}");
}

/// On the orbit the fixed-point map contracts by `rho = h^2 L / 4` with
/// `L = 2 GM / r^3 = 8 pi^2`, and the predictor from the previous midpoint's
/// acceleration is off by about `h^3 |da/dt| / 4 = 62 h^3` (`|da/dt| = GM w`
/// on the unit circle): from there round-off (2e-16) is `ln(2e-16 / (62 h^3))
/// / ln(rho)` iterations away, plus the one that finds the correction below
/// round-off. The mean over a whole orbit must not exceed that by more than one.
#[test]
fn iterations_per_step_are_what_the_contraction_predicts() {
    // counted independently of the scheme's own tally
    let scene = Counted::new(KeplerCircular);
    for steps in [100u64, 1000, 10000] {
        let h = 1.0 / steps as f64;
        let mut c = ImplicitMidpoint.start(&scene, &scene.initial(), h);
        scene.reset();
        ImplicitMidpoint.step(&scene, &mut c, h).unwrap(); // the cold start
        let first = c.evaluations;
        for _ in 1..steps {
            ImplicitMidpoint.step(&scene, &mut c, h).unwrap();
        }
        // the fixed-point iteration contracts fast here, so every iteration is
        // one evaluation
        let mean = (c.evaluations - first) as f64 / (steps - 1) as f64;
        let rho = h * h * 8.0 * std::f64::consts::PI.powi(2) / 4.0;
        let predicted = (2e-16 / (62.0 * h.powi(3))).ln() / rho.ln() + 1.0;
        println!("h = {h}: {mean:.2} iterations per step, predicted {predicted:.2}");
        assert!(
            mean <= predicted.ceil() + 1.0 && mean >= 1.0,
            "h = {h}: {mean} iterations per step, predicted {predicted}"
        );
        assert_eq!(
            ImplicitMidpoint.solver_evaluations(&c),
            Some(scene.evaluations())
        );
    }
}

/// Steps far beyond the fixed-point iteration's reach (`rho = h^2 w^2 / 4`
/// up to 100) are solved by Newton's method: the rule is stable for every
/// step on the oscillator, and its solve must be too. Each step is the
/// Cayley transform, to round-off.
#[test]
fn large_steps_on_the_oscillator_are_solved_by_newton() {
    let osc = Harmonic::default();
    let s0 = osc.initial();
    for h in [2.0, 4.0, 20.0] {
        let z = (h / 2.0) * (h / 2.0);
        let mut c = ImplicitMidpoint.start(&osc, &s0, h);
        ImplicitMidpoint.step(&osc, &mut c, h).unwrap();
        let s1 = ImplicitMidpoint.state(&c, h);
        assert!(
            (s1.q[0] - (1.0 - z) / (1.0 + z)).abs() < 1e-14,
            "h = {h}: {s1:?}"
        );
        assert!((s1.v[0] + h / (1.0 + z)).abs() < 1e-14, "h = {h}: {s1:?}");
        assert!(
            c.last_iterations < MAX_ITERATIONS,
            "h = {h}: {} iterations",
            c.last_iterations
        );
    }
}

/// A step through a singular force (the Kepler orbit's midpoint pulled onto
/// the Sun) cannot be solved: it fails with `NotConverged` within the
/// iteration budget, leaves the state as it was, and says so.
#[test]
fn an_unsolvable_step_fails_cleanly() {
    let scene = KeplerCircular;
    let s0 = scene.initial();
    let h = 0.5;
    let mut c = ImplicitMidpoint.start(&scene, &s0, h);
    let err = ImplicitMidpoint.step(&scene, &mut c, h).unwrap_err();
    let StepFailure::NotConverged { iterations, .. } = err else {
        panic!("a failed solve is reported as one, not as {err:?}");
    };
    assert!((1..=MAX_ITERATIONS).contains(&iterations), "{iterations}");
    assert_eq!(ImplicitMidpoint.state(&c, h), s0);
    assert_eq!(c.last_iterations, iterations);
    assert!(err.to_string().contains("did not converge"), "{err}");
}
