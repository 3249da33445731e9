//! The stability study's arithmetic against closed forms: the spectral
//! radius and its excess over 1 for 2x2 maps whose eigenvalues are known,
//! the determinant's round-off bound in proportion to its two products, the
//! growth per period from the growth per step, and explicit Euler's growth
//! law on the oscillator, whose one-step map has `det = 1 + z^2` exactly;
//! and the scan's reach and the growth law's test of one power, on maps
//! whose stable intervals or growth are known by construction (a gap 0.05
//! wide, a limit at `z = 1000`, a growth whose slope bends by 0.45).

use stepladder::internals::stability::{
    determinant_round_off, growth_law, per_period, radius_excess, spectral_radius,
};
use stepladder::nalgebra::Matrix2;
use stepladder::scheme::{Euler, VELOCITY_VERLET};
use stepladder::study::GrowthSource;

/// A rotation by `theta` scaled by `s`: eigenvalues `s e^(+-i theta)`.
fn scaled_rotation(s: f64, theta: f64) -> Matrix2<f64> {
    let (sin, cos) = theta.sin_cos();
    Matrix2::new(s * cos, -s * sin, s * sin, s * cos)
}

#[test]
fn the_spectral_radius_of_maps_with_known_eigenvalues() {
    // real eigenvalues 2 and 1/2: half trace 5/4, discriminant 9/16
    assert_eq!(spectral_radius(&Matrix2::new(2.0, 0.0, 0.0, 0.5)), 2.0);
    // eigenvalues +-2i: complex, the radius is sqrt(det)
    assert_eq!(spectral_radius(&Matrix2::new(0.0, 1.0, -4.0, 0.0)), 2.0);
    // a rotation: radius 1 to round-off
    let r = spectral_radius(&scaled_rotation(1.0, 0.3));
    assert!((r - 1.0).abs() < 4.0 * f64::EPSILON, "{r}");
}

#[test]
fn the_radius_excess_keeps_its_digits_where_sqrt_det_minus_one_loses_them() {
    // rho = 1 + delta exactly in real arithmetic; the determinant's
    // round-off, a few eps, is 1e-6 of delta = 1e-9
    let delta = 1e-9;
    let m = scaled_rotation(1.0 + delta, 0.3);
    let excess = radius_excess(&m);
    assert!(
        ((excess - delta) / delta).abs() < 1e-5,
        "{excess:e} against {delta:e}"
    );
    // real eigenvalues: rho - 1 directly
    assert_eq!(radius_excess(&Matrix2::new(2.0, 0.0, 0.0, 0.5)), 1.0);
}

#[test]
fn the_determinant_round_off_grows_with_its_two_products() {
    // |m11 m22| + |m12 m21| = 4 + 6 = 10, against at least 1 for the identity
    let unit = determinant_round_off(&VELOCITY_VERLET, &Matrix2::identity());
    let ten = determinant_round_off(&VELOCITY_VERLET, &Matrix2::new(1.0, 2.0, 3.0, 4.0));
    assert!(unit > 0.0);
    assert!(((ten / unit) - 10.0).abs() < 1e-12, "{}", ten / unit);
    // products below 1 still count as 1
    let small = determinant_round_off(&VELOCITY_VERLET, &Matrix2::new(0.1, 0.0, 0.0, 0.1));
    assert_eq!(small, unit);
}

#[test]
fn the_growth_per_period_compounds_the_growth_per_step() {
    // 2 pi / z = n steps a period, each multiplying by 1 + g: (1 + g)^n - 1,
    // by powf where 1 + g keeps g's digits, else by the binomial series
    // n g (1 + (n - 1) g / 2) (the next term is below 1e-20 of it)
    for (g, z) in [(1e-3, 0.5), (1e-12, 0.1), (0.25, 2.0)] {
        let n = std::f64::consts::TAU / z;
        let expected = if g > 1e-6 {
            (1.0f64 + g).powf(n) - 1.0
        } else {
            n * g * (1.0 + (n - 1.0) * g / 2.0)
        };
        let got = per_period(g, z);
        assert!(
            ((got - expected) / expected).abs() < 1e-9,
            "g = {g:e}, z = {z}: {got:e} against {expected:e}"
        );
    }
}

#[test]
fn explicit_eulers_growth_law_is_z_squared() {
    // det M(z) = 1 + z^2: power 2, coefficient 1, and at each reported z the
    // growth per step sqrt(1 + z^2) - 1
    let law = growth_law(&Euler).expect("explicit Euler grows at every z");
    assert_eq!(law.power, 2);
    // within the fit's own round-off bound of the exact 1
    assert!(
        (law.coefficient - 1.0).abs() <= law.coefficient_round_off
            && law.coefficient_round_off < 0.01,
        "coefficient {} (round-off {:e})",
        law.coefficient,
        law.coefficient_round_off
    );
    // the window spans a factor 4 of z from where det - 1 is 64 times its
    // round-off: round-off moves the end-to-end slope by at most
    // 2 / (64 ln 4) = 0.023
    let slope_round_off = 2.0 / (64.0 * 4f64.ln());
    assert!(
        (law.power_fitted - 2.0).abs() <= slope_round_off,
        "{}",
        law.power_fitted
    );
    assert!(!law.at.is_empty());
    for at in &law.at {
        let z = at.z;
        let exact = (z * z).ln_1p() / 2.0; // ln(1 + g) = ln(1 + z^2) / 2
        let per_step = at.per_step.expect("resolved");
        assert!(
            (per_step.ln_1p() - exact).abs() < 1e-9 * exact.max(1e-300),
            "z = {z}: {per_step:e} against {:e} ({:?})",
            exact.exp_m1(),
            at.source
        );
        assert!(matches!(
            at.source,
            GrowthSource::Measured | GrowthSource::Law
        ));
    }
    // a symplectic map has det = 1: no growth law
    assert!(growth_law(&VELOCITY_VERLET).is_none());
}

/// Velocity Verlet on slices at the step `step(h)` instead of `h`: a
/// scheme whose stability on the study's oscillator `x'' = -x` (`z = h`) is
/// Verlet's at `z' = step(z)`, stable exactly where `step(z) < 2`.
fn verlet_stepping_at(
    step: fn(f64) -> f64,
) -> stepladder::scheme::BlackBox<f64, impl stepladder::scheme::BlackBoxStep<f64>> {
    use stepladder::scheme::{BlackBox, Force};
    BlackBox::new(
        VELOCITY_VERLET.meta,
        move |q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>| {
            let h = step(h);
            let mut a = [0.0; 8];
            let a = &mut a[..q.len()];
            force(q, a);
            for i in 0..q.len() {
                v[i] += 0.5 * h * a[i];
                q[i] += h * v[i];
            }
            force(q, a);
            for i in 0..q.len() {
                v[i] += 0.5 * h * a[i];
            }
        },
    )
}

/// The stable intervals of `scheme`, an open end as infinity.
fn intervals<M: stepladder::scheme::Scheme>(scheme: &M) -> (Vec<[f64; 2]>, Option<f64>) {
    let r = stepladder::study::stability(scheme);
    let edges = r
        .stable_intervals
        .iter()
        .map(|i| [i[0].unwrap_or(f64::NAN), i[1].unwrap_or(f64::INFINITY)])
        .collect();
    (edges, r.stability_limit)
}

/// Velocity Verlet whose step, for `h w` strictly between 1.2 and 1.25, is
/// taken as `h w = 3`, beyond its limit 2: a gap of instability 0.05 wide
/// inside its stable interval. The scan, in steps of 1e-3 of `z` up to 20,
/// must see the gap and place both of its edges, so the stable intervals
/// are `[0, 1.2]` and `[1.25, 2]` and the limit is 1.2.
#[test]
fn a_narrow_gap_of_instability_is_found_by_the_scan() {
    let gapped = verlet_stepping_at(|h| if h > 1.2 && h < 1.25 { 3.0 } else { h });
    let (edges, limit) = intervals(&gapped);
    let expected = [[0.0, 1.2], [1.25, 2.0]];
    assert_eq!(edges.len(), 2, "{edges:?}");
    for (found, want) in edges.iter().zip(&expected) {
        for k in 0..2 {
            assert!((found[k] - want[k]).abs() < 1e-6, "{edges:?}");
        }
    }
    let limit = limit.expect("a limit");
    assert!((limit - 1.2).abs() < 1e-6, "{limit}");
}

/// A scheme stable up to `h w = 1000` and unstable beyond (Verlet at a
/// thousandth of the step, then at `h w = 3`): the log-spaced part of the
/// scan, from 20 to 1e6, must reach it and place the limit at 1000.
#[test]
fn a_limit_far_beyond_the_linear_scan_is_found() {
    let late = verlet_stepping_at(|h| if h <= 1000.0 { 1e-3 * h } else { 3.0 });
    let (edges, limit) = intervals(&late);
    assert_eq!(edges.len(), 1, "{edges:?}");
    let limit = limit.expect("a limit");
    assert!((limit / 1000.0 - 1.0).abs() < 1e-6, "{limit} {edges:?}");
}

/// Explicit Euler on slices at the step `step(h)` instead of `h`: on the
/// study's oscillator its one-step map has `det = 1 + step(z)^2`.
fn euler_stepping_at(
    step: impl Fn(f64) -> f64 + Sync,
) -> stepladder::scheme::BlackBox<f64, impl stepladder::scheme::BlackBoxStep<f64>> {
    use stepladder::scheme::{BlackBox, Force};
    BlackBox::new(
        Euler::META,
        move |q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>| {
            let h = step(h);
            let mut a = [0.0; 8];
            let a = &mut a[..q.len()];
            force(q, a);
            for i in 0..q.len() {
                q[i] += h * v[i];
                v[i] += h * a[i];
            }
        },
    )
}

/// Explicit Euler at a step bent so that `det - 1 = step(z)^2` has log-slope
/// 2 over the first quarter octave of the growth law's window (which starts
/// at `z = 1e-6`, as for plain Euler), `2 + d` up to its middle, `2 - 3d/4`
/// beyond: the slope over the whole window is still 2, but over each half
/// it is `2 + 3d/4` and `2 - 3d/4`. With `3d/4 = 0.45`, beyond
/// `GROWTH_POWER_TOLERANCE` (0.25), that is no single power and no law
/// may be inferred; with `3d/4 = 0.15`, within it, the law is `z^2`.
#[test]
fn a_growth_that_bends_within_either_half_of_the_window_has_no_law() {
    let window = growth_law(&Euler).expect("a law").window;
    assert_eq!(window, [1e-6, 4e-6]);
    let bent = |d: f64| {
        let (l1, l4) = ((window[0] * 2f64.powf(0.25)).ln(), (2.0 * window[0]).ln());
        move |h: f64| {
            let l = h.ln();
            (l + 0.5 * d * (l.clamp(l1, l4) - l1) - 0.375 * d * (l - l4).max(0.0)).exp()
        }
    };
    assert!(growth_law(&euler_stepping_at(bent(0.6))).is_none());
    let law = growth_law(&euler_stepping_at(bent(0.2))).expect("a law within the tolerance");
    assert_eq!(law.power, 2);
}
