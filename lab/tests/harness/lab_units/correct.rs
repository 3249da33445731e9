//! Order conditions of every table and measured orders on the oscillator.
//! The helpers are shared with the tests of [`super::broken`].

use stepladder::scene::Scene;
use stepladder::scheme::{Scheme, SplittingTable, StepFailure};
use stepladder::state::State;

use nalgebra::{Matrix2, Vector1};
use stepladder::conditions;
use stepladder::internals::run::integrate;
use stepladder::scene::{Anharmonic, Harmonic};
use stepladder::scheme::NystromTable;
use stepladder_lab::corpus::correct::*;

// ---------------------------------------------------------------- trees

/// Butcher's tree conditions through `degree`
/// ([`stepladder::conditions::runge_kutta`]).
pub(crate) fn trees<const S: usize>(
    a: &[[f64; S]; S],
    b: &[f64; S],
    degree: usize,
) -> conditions::RungeKuttaConditions {
    conditions::runge_kutta(a, b, degree).unwrap()
}

/// Checks a tableau: `c = A 1`, every condition up to `order` to
/// round-off, and some condition of order `order + 1` clearly violated.
pub(crate) fn check_tableau<const S: usize>(
    name: &str,
    a: &[[f64; S]; S],
    b: &[f64; S],
    c: &[f64; S],
    order: usize,
) {
    for i in 0..S {
        let row: f64 = a[i].iter().sum();
        assert!(
            (row - c[i]).abs() < 1e-15,
            "{name}: c_{i} = {} != {row}",
            c[i]
        );
    }
    let c = trees(a, b, order + 1);
    println!("{name:<18} {}", c.by_degree);
    for t in c.trees.iter().filter(|t| t.defect.degree <= order) {
        assert!(
            t.defect.holds(),
            "{name}: condition of {} off: {t:?}",
            t.tree
        );
    }
    let next = c.by_degree.at(order + 1).unwrap();
    assert!(
        next.clearly_fails(),
        "{name}: order {} conditions hold too ({next:?})",
        order + 1
    );
}

#[test]
fn tree_counts_are_the_known_ones() {
    let c = trees(&HEUN.a, &HEUN.b, 6);
    let of_order = |p: usize| c.trees.iter().filter(move |t| t.defect.degree == p);
    let counts: Vec<usize> = (1..=6).map(|p| of_order(p).count()).collect();
    assert_eq!(counts, [1, 1, 2, 4, 9, 20]);
    // gamma = 1/scale: 3 for the bushy tree, 6 for the tall one
    let gammas: f64 = of_order(3).map(|t| 1.0 / t.defect.scale).sum();
    assert_eq!(gammas, 3.0 + 6.0);
}

#[test]
fn runge_kutta_tableaux_satisfy_their_order_conditions() {
    let t = &HEUN;
    check_tableau("heun", &t.a, &t.b, &t.c, 2);
    let t = &EXPLICIT_MIDPOINT;
    check_tableau("explicit-midpoint", &t.a, &t.b, &t.c, 2);
    let t = &KUTTA3;
    check_tableau("kutta3", &t.a, &t.b, &t.c, 3);
    let t = &DORMAND_PRINCE5;
    check_tableau("dormand-prince5", &t.a, &t.b, &t.c, 5);
    let t = &TRAPEZOIDAL;
    check_tableau("trapezoidal", &t.a, &t.b, &t.c, 2);
    let t = &GAUSS4;
    check_tableau("gauss4", &t.a, &t.b, &t.c, 4);
    let t = &LOBATTO_IIIA4;
    check_tableau("lobatto-iiia4", &t.a, &t.b, &t.c, 4);
    assert!((12.0 * SQRT3_6 * SQRT3_6 - 1.0).abs() < 3e-16);
}

/// `b_i a_ij + b_j a_ji - b_i b_j`, largest in size: zero for a
/// symplectic Runge-Kutta method.
fn symplecticity_defect<const S: usize>(a: &[[f64; S]; S], b: &[f64; S]) -> f64 {
    let mut worst = 0.0_f64;
    for i in 0..S {
        for j in 0..S {
            worst = worst.max((b[i] * a[i][j] + b[j] * a[j][i] - b[i] * b[j]).abs());
        }
    }
    worst
}

/// `a_(s+1-i, s+1-j) + a_ij - b_j` and `b_(s+1-i) - b_i`, largest in
/// size: zero for a symmetric Runge-Kutta method.
fn symmetry_defect<const S: usize>(a: &[[f64; S]; S], b: &[f64; S]) -> f64 {
    let mut worst = 0.0_f64;
    for i in 0..S {
        worst = worst.max((b[S - 1 - i] - b[i]).abs());
        for j in 0..S {
            worst = worst.max((a[S - 1 - i][S - 1 - j] + a[i][j] - b[j]).abs());
        }
    }
    worst
}

#[test]
fn implicit_tableaux_are_as_geometric_as_they_claim() {
    assert!(symplecticity_defect(&GAUSS4.a, &GAUSS4.b) < 1e-16);
    assert!(symmetry_defect(&GAUSS4.a, &GAUSS4.b) < 1e-16);
    assert_eq!(symplecticity_defect(&TRAPEZOIDAL.a, &TRAPEZOIDAL.b), 0.25);
    assert_eq!(symmetry_defect(&TRAPEZOIDAL.a, &TRAPEZOIDAL.b), 0.0);
    // at i = j = 1, 2 b1 a11 - b1^2 = -1/36, and at (1, 2) b2 a21 - b1 b2 = 1/36
    let d = symplecticity_defect(&LOBATTO_IIIA4.a, &LOBATTO_IIIA4.b);
    assert!((d - 1.0 / 36.0).abs() < 1e-16, "{d}");
    assert!(symmetry_defect(&LOBATTO_IIIA4.a, &LOBATTO_IIIA4.b) < 1e-16);
}

/// Every Nyström condition through `h^5`
/// ([`stepladder::conditions::nystrom_up_to`]): fourth order, not fifth
/// (`sum b c^4 = 5/24`, not 1/5), and the rows summing to `c^2/2`.
#[test]
fn nystrom_tableau_satisfies_its_order_conditions() {
    let t = &RKN4;
    let table = NystromTable::new(t.meta, t.c, t.a, t.b_bar, t.b, None);
    let c = conditions::nystrom_up_to(&table, 5).unwrap().main;
    println!("rkn4 {c}");
    assert!(c.confirms(4), "{c}");
    for i in 0..3 {
        let row = t.a[i].iter().sum::<f64>() - t.c[i] * t.c[i] / 2.0;
        assert!(row.abs() < 3e-16, "row {i}: {row:e}");
    }
    let fifth = (0..3).map(|i| t.b[i] * t.c[i].powi(4)).sum::<f64>() - 1.0 / 5.0;
    assert!((fifth - 1.0 / 120.0).abs() < 1e-16, "{fifth}");
}

// ------------------------------------------------------------ splittings

/// Sums of the drift and kick weights.
pub(crate) fn sums(table: &SplittingTable) -> (f64, f64) {
    (table.drift.iter().sum(), table.kick.iter().sum())
}

fn check_splitting(table: &SplittingTable) {
    let meta = &table.meta;
    let order = meta.order as usize;
    let (d, k) = sums(table);
    assert!(
        (d - 1.0).abs() < 1e-15 && (k - 1.0).abs() < 1e-15,
        "{}: {d} {k}",
        meta.id
    );
    let c = conditions::splitting_general(&table.sequence(), order + 1).unwrap();
    println!("{:<22} {c}", meta.id);
    assert!(c.confirms(order), "{}: {c}", meta.id);
    let sequence = table.sequence();
    let palindrome = sequence
        .iter()
        .zip(sequence.iter().rev())
        .all(|((f, a), (g, b))| f == g && a == b);
    assert_eq!(palindrome, meta.symmetric, "{}", meta.id);
}

#[test]
fn splittings_satisfy_their_order_conditions() {
    // the series code against the catalogue first
    check_splitting(&stepladder::scheme::VELOCITY_VERLET);
    check_splitting(&stepladder::scheme::FOREST_RUTH);
    check_splitting(&RUTH3);
    check_splitting(&SUZUKI4);
    check_splitting(&YOSHIDA6_RECURSIVE);
    assert_eq!(SUZUKI4.meta.force_evaluations, 5);
    assert_eq!(YOSHIDA6_RECURSIVE.meta.force_evaluations, 9);
    assert_eq!(RUTH3.meta.force_evaluations, 3);
}

#[test]
fn composition_weights_solve_their_defining_equations() {
    let p = SUZUKI_P;
    assert!((p * (4.0 - 4f64.cbrt()) - 1.0).abs() < 3e-16);
    let w = SUZUKI4.drift;
    let cubes: f64 = w.iter().map(|x| x.powi(3)).sum();
    assert!(cubes.abs() < 1e-15, "{cubes:e}");
    let (z1, z0) = (YOSHIDA_Z1, YOSHIDA_Z0);
    assert!((2.0 * z1 + z0 - 1.0).abs() < 3e-16);
    assert!((2.0 * z1.powi(5) + z0.powi(5)).abs() < 1e-14);
    assert!((z1 * (2.0 - 2f64.powf(0.2)) - 1.0).abs() < 3e-16);
    let w = YOSHIDA6_RECURSIVE.drift;
    for odd in [3, 5] {
        let s: f64 = w.iter().map(|x| x.powi(odd)).sum();
        assert!(s.abs() < 1e-13, "sum w^{odd} = {s:e}");
    }
}

// -------------------------------------------------- orders on the oscillator

/// Steps to `2 sqrt(2) T` at about `T / per_period`.
pub(crate) fn steps_for(per_period: f64) -> u64 {
    (2.0 * std::f64::consts::SQRT_2 * per_period).round() as u64
}

/// The phase-space error of `steps` equal steps to `t = 2 sqrt(2) T` on
/// the default oscillator (`x = cos t`), or `None` if the run did not
/// complete.
pub(crate) fn oscillator_error<M: Scheme>(scheme: &M, steps: u64) -> Option<f64> {
    let scene = Harmonic::default();
    let t_end = scene.default_t_end();
    let h = t_end / steps as f64;
    let mut last = scene.initial();
    let outcome = integrate(scheme, &scene, &scene.initial(), h, steps, |_, _, s| {
        last = *s
    });
    let exact = State::new(Vector1::new(t_end.cos()), Vector1::new(-t_end.sin()));
    outcome
        .completed()
        .then(|| scene.phase_distance(&last, &exact))
}

/// `(e(h), e(h/2), log2 of their ratio)` with `h = t_end / steps`.
pub(crate) fn oscillator_order<M: Scheme>(scheme: &M, steps: u64) -> (f64, f64, f64) {
    let coarse = oscillator_error(scheme, steps).expect("coarse run completes");
    let fine = oscillator_error(scheme, 2 * steps).expect("fine run completes");
    (coarse, fine, (coarse / fine).log2())
}

fn check_order<M: Scheme>(scheme: &M, per_period: f64) {
    let meta = scheme.meta();
    let (coarse, fine, p) = oscillator_order(scheme, steps_for(per_period));
    println!(
        "{:<20} h = T/{per_period:<4} e(h) = {coarse:.3e}  e(h/2) = {fine:.3e}  order {p:.3}",
        meta.id
    );
    assert!(
        (p - meta.order as f64).abs() <= 0.15,
        "{}: measured order {p:.3}, claimed {}",
        meta.id,
        meta.order
    );
}

#[test]
fn every_correct_scheme_has_its_order_on_the_oscillator() {
    check_order(&HEUN, 50.0);
    check_order(&EXPLICIT_MIDPOINT, 50.0);
    check_order(&KUTTA3, 50.0);
    check_order(&RUTH3, 50.0);
    check_order(&DORMAND_PRINCE5, 50.0);
    check_order(&RKN4, 50.0);
    check_order(&TRAPEZOIDAL, 50.0);
    check_order(&GAUSS4, 50.0);
    check_order(&LOBATTO_IIIA4, 50.0);
    check_order(&SUZUKI4, 50.0);
    check_order(&YOSHIDA6_RECURSIVE, 50.0);
}

// ------------------------------------------------------------- geometry

/// The Jacobian of the map `start`, one step of `h`, `state` at `s`, by
/// central differences.
pub(crate) fn step_jacobian<M: Scheme, P: Scene<1>>(
    scheme: &M,
    scene: &P,
    s: &State<1>,
    h: f64,
) -> Matrix2<f64> {
    let map = |q: f64, v: f64| {
        let mut c = scheme.start(scene, &State::new(Vector1::new(q), Vector1::new(v)), h);
        scheme.step(scene, &mut c, h).expect("step");
        let out = scheme.state(&c, h);
        (out.q[0], out.v[0])
    };
    let e = 1e-5;
    let (q, v) = (s.q[0], s.v[0]);
    let (qp, vp) = map(q + e, v);
    let (qm, vm) = map(q - e, v);
    let (qp2, vp2) = map(q, v + e);
    let (qm2, vm2) = map(q, v - e);
    Matrix2::new(
        (qp - qm) / (2.0 * e),
        (qp2 - qm2) / (2.0 * e),
        (vp - vm) / (2.0 * e),
        (vp2 - vm2) / (2.0 * e),
    )
}

/// `det - 1` of the step's Jacobian at a point of the anharmonic orbit
/// (zero for a symplectic map in one dimension).
/// The step is run in dual numbers (the harness's tangent map), and
/// checked against central differences.
pub(crate) fn det_defect<M: Scheme>(scheme: &M, h: f64) -> f64 {
    let scene = Anharmonic::default();
    let s = State::new(Vector1::new(0.45), Vector1::new(0.2));
    let differences = step_jacobian(scheme, &scene, &s, h).determinant();
    let dual = stepladder::internals::maths::tangent::step_jacobian(scheme, &scene, &s, h)
        .expect("step")
        .determinant();
    assert!(
        (dual - differences).abs() < 1e-8,
        "{dual} against {differences}"
    );
    dual - 1.0
}

/// Phase-space distance after `n` steps of `h` then `n` of `-h`, each run
/// started afresh from the synchronised state, on the anharmonic well.
pub(crate) fn return_error<M: Scheme>(scheme: &M, h: f64, n: u64) -> f64 {
    let scene = Anharmonic::default();
    let start = scene.initial();
    let mut there = start;
    integrate(scheme, &scene, &start, h, n, |_, _, s| there = *s);
    let mut back = there;
    integrate(scheme, &scene, &there, -h, n, |_, _, s| back = *s);
    scene.phase_distance(&back, &start)
}

fn check_geometry<M: Scheme>(scheme: &M) {
    let meta = scheme.meta();
    let det = det_defect(scheme, 0.3);
    let back = return_error(scheme, 0.1, 50);
    println!(
        "{:<20} det - 1 = {det:+.2e}   return after 50 steps there and back = {back:.2e}",
        meta.id
    );
    assert_eq!(
        det.abs() < 1e-9,
        meta.symplectic,
        "{}: det - 1 = {det:e}",
        meta.id
    );
    assert_eq!(back < 1e-13, meta.symmetric, "{}: return {back:e}", meta.id);
}

#[test]
fn every_correct_scheme_is_as_geometric_as_it_claims_on_a_nonlinear_scene() {
    check_geometry(&HEUN);
    check_geometry(&EXPLICIT_MIDPOINT);
    check_geometry(&KUTTA3);
    check_geometry(&RUTH3);
    check_geometry(&DORMAND_PRINCE5);
    check_geometry(&RKN4);
    check_geometry(&TRAPEZOIDAL);
    check_geometry(&GAUSS4);
    check_geometry(&LOBATTO_IIIA4);
    check_geometry(&SUZUKI4);
    check_geometry(&YOSHIDA6_RECURSIVE);
}

#[test]
fn implicit_solves_converge_and_count_their_evaluations() {
    let scene = Anharmonic::default();
    let h = scene.period() / 50.0;
    for (scheme, stages) in [(&TRAPEZOIDAL, 2u64), (&GAUSS4, 2)] {
        let mut c = scheme.start(&scene, &scene.initial(), h);
        for _ in 0..100 {
            scheme.step(&scene, &mut c, h).unwrap();
            assert!(
                (2..=12).contains(&c.last_iterations),
                "{}",
                c.last_iterations
            );
        }
        assert_eq!(c.evaluations % stages, 0);
        assert_eq!(scheme.solver_evaluations(&c), Some(c.evaluations));
    }
    // a step far too large for the contraction fails instead of lying
    let stiff = Harmonic::new(100.0, 1.0, 0.0).unwrap();
    let mut c = GAUSS4.start(&stiff, &stiff.initial(), 1.0);
    let before = c.state;
    assert!(matches!(
        GAUSS4.step(&stiff, &mut c, 1.0),
        Err(StepFailure::NotConverged { .. })
    ));
    assert_eq!(c.state, before);
}
