//! Each stated defect checked against the tables, and each stated true
//! behaviour measured.

use stepladder::scene::Scene;
use stepladder::scheme::ExplicitRk;
use stepladder::scheme::{Flow, OneStep, Rk4, Scheme, SplittingTable, VELOCITY_VERLET};
use stepladder::state::State;
use stepladder_lab::corpus::correct::DORMAND_PRINCE5;

use super::correct::{
    det_defect, oscillator_error, oscillator_order, return_error, step_jacobian, steps_for, sums,
    trees,
};
use nalgebra::{SMatrix, Vector1};
use stepladder::conditions;
use stepladder::scene::{Anharmonic, Harmonic};
use stepladder_lab::corpus::broken::*;

/// `sum b Phi(t) - 1/gamma(t)` of the tree named `tree` (up to order
/// three), with its sign.
fn defect_of<const S: usize>(t: &ExplicitRk<S>, tree: &str) -> f64 {
    trees(&t.a, &t.b, 3)
        .trees
        .into_iter()
        .find(|x| x.tree == tree)
        .expect("tree")
        .signed
}

/// The tableau's conditions hold through `order` (to the rounding of its
/// coefficients, [`stepladder::conditions::runge_kutta`]).
fn holds_through<const S: usize>(a: &[[f64; S]; S], b: &[f64; S], order: usize) -> bool {
    trees(a, b, order).order() == order
}

// The structure of a stated splitting defect (the matrix itself, not
// only its size, which the order conditions report): the Taylor
// coefficients of one step on `y' = (A + B) y` in doubles.

type Matrix = SMatrix<f64, 5, 5>;

/// A fixed pseudo-random matrix with entries in `[-1, 1]` (SplitMix64).
fn random_matrix(seed: u64) -> Matrix {
    let mut state = seed;
    Matrix::from_fn(|_, _| {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        2.0 * (z >> 11) as f64 / (1u64 << 53) as f64 - 1.0
    })
}

/// The drift generator `A` and kick generator `B`.
fn generators() -> (Matrix, Matrix) {
    (random_matrix(0x5eed_0001), random_matrix(0x5eed_0002))
}

/// The Taylor coefficients in `h`, up to `h^degree`, of one step of the
/// table on `y' = (A + B) y`, minus those of `exp(h (A + B))`.
fn series_defects(table: &SplittingTable, degree: usize) -> Vec<Matrix> {
    let (a, b) = generators();
    let exp = |x: &Matrix, w: f64| -> Vec<Matrix> {
        let mut terms = vec![Matrix::identity()];
        for j in 1..=degree {
            terms.push(terms[j - 1] * x * (w / j as f64));
        }
        terms
    };
    let times = |left: &[Matrix], right: &[Matrix]| -> Vec<Matrix> {
        (0..=degree)
            .map(|n| (0..=n).map(|i| left[i] * right[n - i]).sum())
            .collect()
    };
    let mut product = exp(&Matrix::zeros(), 0.0);
    for (flow, w) in table.sequence() {
        let x = if flow == Flow::Drift { &a } else { &b };
        product = times(&exp(x, w), &product);
    }
    let exact = exp(&(a + b), 1.0);
    product.iter().zip(&exact).map(|(p, e)| p - e).collect()
}

/// The `h^1` defect relative to the size of `h (A + B)`.
fn first_relative_defect(table: &SplittingTable) -> f64 {
    conditions::splitting_general(&table.sequence(), 1)
        .unwrap()
        .defects[0]
        .relative()
}

#[test]
fn runge_kutta_typos_break_the_stated_conditions() {
    // the base tableau is RK4
    assert!(holds_through(&RK4_A, &RK4_B, 4));
    // stage-3 typo: order 2 holds, the tall order-3 tree fails by -1/12
    let t = &RK4_STAGE3_TYPO;
    assert!(holds_through(&t.a, &t.b, 2));
    assert!(defect_of(t, "[τ,τ]").abs() < 3e-16);
    assert!((defect_of(t, "[[τ]]") + 1.0 / 12.0).abs() < 3e-16);
    // weights typo: sum b = 1, sum b c off by +1/12
    let t = &RK4_WEIGHTS_TYPO;
    assert!(holds_through(&t.a, &t.b, 1));
    assert!((defect_of(t, "[τ]") - 1.0 / 12.0).abs() < 3e-16);
    // rounded Dormand-Prince weight: sum b - 1 = -11/240000
    let t = &DORMAND_PRINCE5_ROUNDED_WEIGHT;
    assert!((defect_of(t, "τ") + 11.0 / 240000.0).abs() < 3e-16);
    assert_eq!(t.a, DORMAND_PRINCE5.a);
    // rounded Gauss: order 2 holds, both order-3 conditions off by
    // -+(s^2 - 1/12) = 1.43567e-5
    let g = &GAUSS4_ROUNDED;
    let off = SQRT3_6_TYPED * SQRT3_6_TYPED - 1.0 / 12.0;
    assert!((off - 1.435666666e-5).abs() < 1e-13, "{off:e}");
    let c = trees(&g.a, &g.b, 3);
    assert_eq!(c.order(), 2, "{}", c.by_degree);
    for t in c.trees.iter().filter(|t| t.defect.degree == 3) {
        let expected = if t.tree == "[τ,τ]" { off } else { -off };
        assert!((t.signed - expected).abs() < 1e-16, "{t:?}");
    }
    // still symplectic and symmetric
    for i in 0..2 {
        for j in 0..2 {
            let s = g.b[i] * g.a[i][j] + g.b[j] * g.a[j][i] - g.b[i] * g.b[j];
            assert!(s.abs() < 1e-16);
            assert!((g.a[1 - i][1 - j] + g.a[i][j] - g.b[j]).abs() < 1e-16);
        }
    }
}

#[test]
fn rk4_claiming_symplectic_steps_like_the_catalogue() {
    let scene = Anharmonic::default();
    let (mut a, mut b) = (scene.initial(), scene.initial());
    for _ in 0..100 {
        OneStep::advance(&Rk4, &scene, &mut a, 0.1).unwrap();
        OneStep::advance(&RK4_CLAIMS_SYMPLECTIC, &scene, &mut b, 0.1).unwrap();
    }
    assert!(scene.phase_distance(&a, &b) < 1e-14);
}

#[test]
fn rounded_and_perturbed_weights_have_the_stated_defects() {
    let x3 = series_defects(&VELOCITY_VERLET, 3)[3]; // Verlet's own h^3 field
    let (drift, kick) = sums(&VELOCITY_VERLET);
    assert_eq!((drift, kick), (1.0, 1.0));

    // Forest-Ruth to four decimals: sum w = 1, h^3 term = sum w^3 X3
    let t = &FOREST_RUTH_4_DECIMALS;
    let (d, k) = sums(t);
    assert!(
        (d - 1.0).abs() < 3e-16 && (k - 1.0).abs() < 3e-16,
        "{d} {k}"
    );
    let cubes: f64 = t.drift.iter().map(|w| w.powi(3)).sum();
    assert!((cubes - 4.6277632e-5).abs() < 1e-15, "{cubes:e}");
    let s = series_defects(t, 3);
    assert!(s[1].amax() < 1e-15 && s[2].amax() < 1e-14);
    assert!((s[3] - x3 * cubes).amax() < 1e-6 * (x3 * cubes).amax());

    // Yoshida, first weight + 1e-8: sums 1 + 1e-8, h term 1e-8 (A + B)
    let t = &YOSHIDA6_FIRST_WEIGHT;
    let (d, k) = sums(t);
    assert!((d - 1.0 - 1e-8).abs() < 1e-15 && (k - 1.0 - 1e-8).abs() < 1e-15);
    let rel = first_relative_defect(t);
    assert!((rel / 1e-8 - 1.0).abs() < 1e-6, "{rel:e}");

    // Yoshida, palindromic perturbation: sums kept, h^3 term -6.6855e-8 X3
    let t = &YOSHIDA6_PALINDROME;
    let (d, k) = sums(t);
    assert!((d - 1.0).abs() < 1e-15 && (k - 1.0).abs() < 1e-15);
    let cubes: f64 = t.drift.iter().map(|w| w.powi(3)).sum();
    assert!((cubes + 6.6855e-8).abs() < 1e-12, "{cubes:e}");
    let s = series_defects(t, 3);
    assert!(
        s[1].amax() < 1e-14 && s[2].amax() < 1e-13,
        "{:e}",
        s[2].amax()
    );
    assert!((s[3] - x3 * cubes).amax() < 1e-4 * (x3 * cubes).amax());

    // Kahan-Li to 8 digits: sum w - 1 = 1e-8 exactly in decimals
    let t = &KAHAN_LI8_8_DIGITS;
    let (d, k) = sums(t);
    assert!(
        (d - 1.0 - 1e-8).abs() < 1e-15 && (k - 1.0 - 1e-8).abs() < 1e-15,
        "{d}"
    );
    let cubes: f64 = t.drift.iter().map(|w| w.powi(3)).sum();
    assert!((cubes - 6.2024e-9).abs() < 1e-12, "{cubes:e}");
    let rel = first_relative_defect(t);
    assert!((rel / 1e-8 - 1.0).abs() < 1e-6, "{rel:e}");

    // Ruth with swapped drifts: sums kept, h^2 term (sigma - 1/2)[A, B], sigma = 3/2
    let t = &RUTH3_SWAPPED_DRIFTS;
    let (d, k) = sums(t);
    assert!((d - 1.0).abs() < 1e-15 && (k - 1.0).abs() < 1e-15);
    let sigma: f64 = (0..3)
        .map(|i| t.kick[i] * t.drift[i..].iter().sum::<f64>())
        .sum();
    assert!((sigma - 1.5).abs() < 1e-15, "{sigma}");
    let (a, b) = generators();
    let s = series_defects(t, 2);
    assert!(s[1].amax() < 1e-15);
    assert!((s[2] - (a * b - b * a) * (sigma - 0.5)).amax() < 1e-14);

    // the sign flip: kicks sum to -1
    assert_eq!(sums(&VERLET_SIGN_FLIPPED), (1.0, -1.0));
}

/// Prints and returns the measured order between `T/per_period` and half
/// that step.
fn measure<M: Scheme>(scheme: &M, per_period: f64) -> f64 {
    let (coarse, fine, p) = oscillator_order(scheme, steps_for(per_period));
    println!(
        "{:<40} h = T/{per_period:<6} e(h) = {coarse:.3e}  e(h/2) = {fine:.3e}  order {p:.3}",
        scheme.meta().id
    );
    p
}

#[test]
fn true_orders_on_the_oscillator() {
    let near = |p: f64, q: f64| (p - q).abs() <= 0.15;
    // (scheme, steps per period where the true order is asymptotic, true order)
    let order = |p: f64, per_period: f64, truth: f64| {
        assert!(
            near(p, truth),
            "measured {p:.3} at T/{per_period}, true order {truth}"
        );
    };
    order(measure(&RK4_STAGE3_TYPO, 50.0), 50.0, 2.0);
    order(measure(&RK4_WEIGHTS_TYPO, 50.0), 50.0, 1.0);
    order(measure(&MIDPOINT_TWO_ITERATIONS, 50.0), 50.0, 2.0);
    order(measure(&RK4_CLAIMS_SYMPLECTIC, 50.0), 50.0, 4.0);
    order(measure(&EULER_CROMER_CLAIMS_SYMMETRIC, 50.0), 50.0, 1.0);
    order(measure(&TRAPEZOIDAL_CLAIMS_SYMPLECTIC, 50.0), 50.0, 2.0);
    order(measure(&VERLET_CLAIMS_ORDER3, 50.0), 50.0, 2.0);
    order(measure(&VERLET_CLAIMS_ORDER1, 50.0), 50.0, 2.0);
    order(measure(&DORMAND_PRINCE5_ROUNDED_WEIGHT, 50.0), 50.0, 0.0);
    order(measure(&KAHAN_LI8_8_DIGITS, 50.0), 50.0, 0.0);
    measure(&YOSHIDA6_FIRST_WEIGHT, 50.0);
    order(measure(&YOSHIDA6_FIRST_WEIGHT, 100.0), 100.0, 0.0);
    // first-order bugs whose runs at T/50 are not yet asymptotic (the
    // stale kick's energy grows by 1 + z^2/2 a step, e^1.1 by the end)
    for per_period in [50.0, 400.0] {
        let p = [
            measure(&STALE_KICK_VERLET, per_period),
            measure(&LEAPFROG_HALF_STEP_OUTPUT, per_period),
            measure(&STORMER_EULER_START, per_period),
            measure(&LEAPFROG_NO_HALF_KICK, per_period),
            measure(&RUTH3_SWAPPED_DRIFTS, per_period),
        ];
        if per_period == 400.0 {
            p.iter().for_each(|&p| order(p, per_period, 1.0));
        }
    }
    // the small second-order terms show below their crossover steps
    measure(&GAUSS4_ROUNDED, 50.0);
    measure(&GAUSS4_ROUNDED, 100.0);
    order(measure(&GAUSS4_ROUNDED, 400.0), 400.0, 2.0);
    measure(&FOREST_RUTH_4_DECIMALS, 50.0);
    measure(&FOREST_RUTH_4_DECIMALS, 400.0);
    measure(&FOREST_RUTH_4_DECIMALS, 1600.0);
    order(measure(&FOREST_RUTH_4_DECIMALS, 6400.0), 6400.0, 2.0);
    measure(&YOSHIDA6_PALINDROME, 50.0);
    measure(&YOSHIDA6_PALINDROME, 200.0);
    order(measure(&YOSHIDA6_PALINDROME, 800.0), 800.0, 2.0);
    // the sign flip blows up on the oscillator
    assert_eq!(
        oscillator_error(&VERLET_SIGN_FLIPPED, steps_for(50.0)),
        None
    );
}

#[test]
fn the_sign_flip_converges_to_the_wrong_orbit() {
    let scene = Anharmonic::default();
    let t_end = scene.default_t_end();
    let exact = scene.exact(t_end).unwrap();
    let errors: Vec<f64> = [100u64, 1000, 10000]
        .iter()
        .map(|&n| {
            let mut last = scene.initial();
            let h = t_end / n as f64;
            stepladder::internals::run::integrate(
                &VERLET_SIGN_FLIPPED,
                &scene,
                &scene.initial(),
                h,
                n,
                |_, _, s| last = *s,
            );
            scene.phase_distance(&last, &exact)
        })
        .collect();
    println!("verlet-sign-flipped on the well: errors {errors:?} at T_end/100, /1000, /10000");
    assert!(errors.iter().all(|e| *e > 0.1), "{errors:?}");
    assert!((errors[2] / errors[1] - 1.0).abs() < 0.01);
}

#[test]
fn geometry_is_what_the_documentation_says() {
    let report = |id: &str, det: f64, back: f64| {
        println!("{id:<40} det - 1 = {det:+.2e}   return = {back:.2e}");
    };
    // stale kick: det = 1 + z^2/2 on the oscillator, not symmetric
    let osc = Harmonic::default();
    let s = State::new(Vector1::new(0.3), Vector1::new(0.4));
    let h = 0.2;
    let det = step_jacobian(&STALE_KICK_VERLET, &osc, &s, h).determinant() - 1.0;
    assert!((det - h * h / 2.0).abs() < 1e-9, "{det:e}");
    let back = return_error(&STALE_KICK_VERLET, 0.1, 50);
    report(STALE_KICK_VERLET.meta.id, det, back);
    assert!(back > 1e-6);
    // the truncated midpoint rule: det = 1 - z^4/4 + z^6/16 on the oscillator
    let det = step_jacobian(&MIDPOINT_TWO_ITERATIONS, &osc, &s, h).determinant() - 1.0;
    let z4 = h.powi(4);
    assert!(
        (det - (-z4 / 4.0 + z4 * h * h / 16.0)).abs() < 1e-9,
        "{det:e}"
    );
    let (det, back) = (
        det_defect(&MIDPOINT_TWO_ITERATIONS, 0.3),
        return_error(&MIDPOINT_TWO_ITERATIONS, 0.1, 50),
    );
    report(MIDPOINT_TWO_ITERATIONS.meta.id, det, back);
    assert!(det.abs() > 1e-6 && back > 1e-9);
    // symplectic but not symmetric
    for (id, det, back) in [
        (
            LEAPFROG_HALF_STEP_OUTPUT.meta.id,
            det_defect(&LEAPFROG_HALF_STEP_OUTPUT, 0.3),
            return_error(&LEAPFROG_HALF_STEP_OUTPUT, 0.1, 50),
        ),
        (
            LEAPFROG_NO_HALF_KICK.meta.id,
            det_defect(&LEAPFROG_NO_HALF_KICK, 0.3),
            return_error(&LEAPFROG_NO_HALF_KICK, 0.1, 50),
        ),
        (
            STORMER_EULER_START.meta.id,
            det_defect(&STORMER_EULER_START, 0.3),
            return_error(&STORMER_EULER_START, 0.1, 50),
        ),
        (
            EULER_CROMER_CLAIMS_SYMMETRIC.meta.id,
            det_defect(&EULER_CROMER_CLAIMS_SYMMETRIC, 0.3),
            return_error(&EULER_CROMER_CLAIMS_SYMMETRIC, 0.1, 50),
        ),
        (
            RUTH3_SWAPPED_DRIFTS.meta.id,
            det_defect(&RUTH3_SWAPPED_DRIFTS, 0.3),
            return_error(&RUTH3_SWAPPED_DRIFTS, 0.1, 50),
        ),
    ] {
        report(id, det, back);
        assert!(det.abs() < 1e-9, "{id}: {det:e}");
        assert!(back > 1e-13, "{id}: {back:e}");
    }
    // the broken palindrome of Yoshida's weights shows at O(1e-8 h^4) a step
    let (det, back) = (
        det_defect(&YOSHIDA6_FIRST_WEIGHT, 0.3),
        return_error(&YOSHIDA6_FIRST_WEIGHT, 0.1, 50),
    );
    let wide = return_error(&YOSHIDA6_FIRST_WEIGHT, 0.4, 50);
    report(YOSHIDA6_FIRST_WEIGHT.meta.id, det, back);
    println!("{:<40} return at h = 0.4: {wide:.2e}", "");
    assert!(det.abs() < 1e-9 && back > 1e-13 && wide > 1e-11 && wide < 1e-8);
    // symplectic and symmetric still
    for (id, det, back) in [
        (
            FOREST_RUTH_4_DECIMALS.meta.id,
            det_defect(&FOREST_RUTH_4_DECIMALS, 0.3),
            return_error(&FOREST_RUTH_4_DECIMALS, 0.1, 50),
        ),
        (
            YOSHIDA6_PALINDROME.meta.id,
            det_defect(&YOSHIDA6_PALINDROME, 0.3),
            return_error(&YOSHIDA6_PALINDROME, 0.1, 50),
        ),
        (
            KAHAN_LI8_8_DIGITS.meta.id,
            det_defect(&KAHAN_LI8_8_DIGITS, 0.3),
            return_error(&KAHAN_LI8_8_DIGITS, 0.1, 50),
        ),
        (
            GAUSS4_ROUNDED.meta.id,
            det_defect(&GAUSS4_ROUNDED, 0.3),
            return_error(&GAUSS4_ROUNDED, 0.1, 50),
        ),
        (
            VERLET_SIGN_FLIPPED.meta.id,
            det_defect(&VERLET_SIGN_FLIPPED, 0.3),
            return_error(&VERLET_SIGN_FLIPPED, 0.1, 50),
        ),
    ] {
        report(id, det, back);
        assert!(det.abs() < 1e-9, "{id}: {det:e}");
        assert!(back < 1e-13, "{id}: {back:e}");
    }
    // neither: RK4 and the trapezoidal rule on the nonlinear well
    for (id, det) in [
        (
            RK4_CLAIMS_SYMPLECTIC.meta.id,
            det_defect(&RK4_CLAIMS_SYMPLECTIC, 0.3),
        ),
        (
            TRAPEZOIDAL_CLAIMS_SYMPLECTIC.meta.id,
            det_defect(&TRAPEZOIDAL_CLAIMS_SYMPLECTIC, 0.3),
        ),
    ] {
        report(id, det, f64::NAN);
        assert!(det.abs() > 1e-7, "{id}: {det:e}");
    }
    // while on the oscillator the trapezoidal rule is symplectic
    let det = step_jacobian(&TRAPEZOIDAL_CLAIMS_SYMPLECTIC, &osc, &s, 0.3).determinant();
    assert!((det - 1.0).abs() < 1e-9, "{det}");
}

#[test]
fn ids_are_unique_and_kebab_case() {
    let ids = [
        FOREST_RUTH_4_DECIMALS.meta.id,
        YOSHIDA6_FIRST_WEIGHT.meta.id,
        YOSHIDA6_PALINDROME.meta.id,
        KAHAN_LI8_8_DIGITS.meta.id,
        RUTH3_SWAPPED_DRIFTS.meta.id,
        RK4_STAGE3_TYPO.meta.id,
        RK4_WEIGHTS_TYPO.meta.id,
        DORMAND_PRINCE5_ROUNDED_WEIGHT.meta.id,
        GAUSS4_ROUNDED.meta.id,
        STALE_KICK_VERLET.meta.id,
        LEAPFROG_HALF_STEP_OUTPUT.meta.id,
        LEAPFROG_NO_HALF_KICK.meta.id,
        STORMER_EULER_START.meta.id,
        MIDPOINT_TWO_ITERATIONS.meta.id,
        VERLET_SIGN_FLIPPED.meta.id,
        RK4_CLAIMS_SYMPLECTIC.meta.id,
        EULER_CROMER_CLAIMS_SYMMETRIC.meta.id,
        TRAPEZOIDAL_CLAIMS_SYMPLECTIC.meta.id,
        VERLET_CLAIMS_ORDER3.meta.id,
        VERLET_CLAIMS_ORDER1.meta.id,
    ];
    use stepladder_lab::corpus::correct as c;
    let mut all: Vec<&str> = ids.to_vec();
    all.extend(stepladder::scheme::scheme_ids());
    all.extend([
        c::HEUN.meta.id,
        c::EXPLICIT_MIDPOINT.meta.id,
        c::KUTTA3.meta.id,
        c::RUTH3.meta.id,
        c::DORMAND_PRINCE5.meta.id,
        c::RKN4.meta.id,
        c::TRAPEZOIDAL.meta.id,
        c::GAUSS4.meta.id,
        c::LOBATTO_IIIA4.meta.id,
        c::SUZUKI4.meta.id,
        c::YOSHIDA6_RECURSIVE.meta.id,
    ]);
    let set: std::collections::BTreeSet<&str> = all.iter().copied().collect();
    assert_eq!(set.len(), all.len());
    for id in ids {
        assert!(
            id.chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-')
        );
    }
}
