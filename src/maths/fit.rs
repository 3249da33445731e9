//! Least-squares fits of the global error against the step size.
//!
//! A straight line through `(ln h, ln e)` is the textbook order estimate, but
//! for the smooth, deterministic errors of an exact-solution scene its
//! Student's t interval only measures how far the data bend away from a
//! line: the next terms of the error expansion bias the slope by more than
//! the interval is wide, so a correct scheme would be reported outside its
//! own order. [`order_fit`] therefore fits the first terms of the expansion,
//!
//! `ln e = ln C + p ln h + b (h/H)`   or   `ln e = ln C + p ln h + b (h/H)^2`
//!
//! (`H` the window's largest `h`): `ln(C h^p (1 + c h))` to first order for a
//! scheme whose error expansion has every power, `ln(C h^p (1 + c h^2))` for
//! a symmetric one, whose expansion has only even powers. The correction
//! enters only when the data call for it (a partial F-test at 5% against the
//! straight line): where round-off hides the curvature, it would only trade
//! bias for variance. `p` comes with its Student's t interval, widened by two
//! measured systematics: how far `p` moves when the window loses one or two
//! of its coarsest or its finest rungs (the choice of window), and how far
//! it moves between the two corrections when both pass the test (the choice
//! of model, which two or three halvings of data cannot settle).

use nalgebra::{DMatrix, DVector};
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, FisherSnedecor, StudentsT};

/// Most correction terms the fit may use: one. A window spans two or three
/// halvings of the step, over which `h/H`, `(h/H)^2` and `ln h` are so nearly
/// collinear that a fit with both corrections trades one for the other and
/// moves `p` by tenths; with one, the choice between them is what the data
/// cannot settle, and the interval carries it (see [`order_fit`]).
pub const MAX_CORRECTIONS: usize = 1;

/// Fewest points an order fit takes: two coefficients, the corrections,
/// and two degrees of freedom.
pub const MIN_POINTS: usize = MAX_CORRECTIONS + 4;

/// A correction term the fit may add to `ln e = ln C + p ln h`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Correction {
    /// `b h/H`: the next term of a non-symmetric scheme's error expansion.
    Linear,
    /// `b (h/H)^2`: the next term of a symmetric scheme's.
    Quadratic,
}

/// The order of accuracy fitted over a window of rungs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OrderFit {
    /// The exponent `p` of the expansion fit.
    pub order: f64,
    /// Its standard error.
    pub standard_error: f64,
    /// The correction terms the data called for, in the order they entered.
    pub corrections: [Option<Correction>; MAX_CORRECTIONS],
    /// Student's t quantile at 0.975 for the fit's degrees of freedom.
    pub t_quantile: f64,
    /// Largest shift of `p` when the window loses one or two rungs at
    /// either end, or when the other correction is used, plus the most the
    /// rungs' round-off can move it.
    pub systematic: f64,
    /// `order -+ (t_quantile * standard_error + systematic)`.
    pub ci95: [f64; 2],
    /// Rungs fitted.
    pub points: usize,
    /// The plain straight-line fit over the same rungs, for reference.
    pub line: PowerLaw,
}

/// Fits the order over `points = (h, e)` (positive, finite). Returns `None`
/// with fewer than [`MIN_POINTS`] points or a degenerate design.
pub fn order_fit(points: &[(f64, f64)]) -> Option<OrderFit> {
    order_fit_with_round_off(points, &vec![0.0; points.len()])
}

/// [`order_fit`] for errors that carry round-off of at most `round_off[i]`
/// times their size: the order's interval is widened by the most that
/// round-off can move it, `sum |dp / d ln e_i| round_off[i]`, a bound since
/// the fit is linear in `ln e` and `|ln(1 + f)| <= f / (1 - f)`.
pub fn order_fit_with_round_off(points: &[(f64, f64)], round_off: &[f64]) -> Option<OrderFit> {
    let n = points.len();
    if n < MIN_POINTS {
        return None;
    }
    let line = power_law(points)?;
    let plain = expansion(points, &[])?;
    // each correction on its own, kept when it explains significantly more
    // than the line (partial F-test at 5%)
    let significant: Vec<(Correction, Expansion)> = [Correction::Linear, Correction::Quadratic]
        .into_iter()
        .filter_map(|c| Some((c, expansion(points, &[c])?)))
        .filter(|(_, richer)| {
            let f = (plain.residual - richer.residual) / (richer.residual / richer.dof as f64);
            let critical = FisherSnedecor::new(1.0, richer.dof as f64)
                .expect("positive degrees of freedom")
                .inverse_cdf(0.95);
            f > critical
        })
        .collect();
    let best = significant
        .iter()
        .min_by(|a, b| a.1.residual.total_cmp(&b.1.residual));
    let (chosen, fit): (Vec<Correction>, &Expansion) = match best {
        Some((c, f)) => (vec![*c], f),
        None => (vec![], &plain),
    };
    let t_quantile = t975(fit.dof);
    // the window's systematic: the fit without one or two of its coarsest
    // rungs (the most pre-asymptotic) or of its finest (the nearest the floor)
    let window = [
        &points[1..],
        &points[2..],
        &points[..n - 1],
        &points[..n - 2],
    ]
    .iter()
    .filter_map(|sub| expansion(sub, &chosen))
    .map(|sub| (sub.order - fit.order).abs())
    .fold(0.0, f64::max);
    // how far the round-off each point may carry (its bound, a fraction of
    // its error) can move a fit's order: the leverages times the bounds
    let rounding = |f: &Expansion| -> f64 {
        f.weights
            .iter()
            .zip(round_off)
            .map(|(w, r)| w.abs() * r / (1.0 - r.min(0.5)))
            .sum()
    };
    // the model's systematic: the next term of the expansion is there in
    // every error, whether or not the window's scatter lets an F-test see
    // it, and `p` depends on whether (and which) term is fitted. Each
    // alternative is itself moved by round-off, the more so as a correction
    // raises the end points' leverage, so its own rounding bound counts too.
    let model = [Correction::Linear, Correction::Quadratic]
        .into_iter()
        .filter_map(|c| expansion(points, &[c]))
        .chain(std::iter::once(plain.clone()))
        .map(|f| (f.order - fit.order).abs() + rounding(&f))
        .fold(0.0, f64::max);
    let systematic = (window + rounding(fit)).max(model);
    let half = t_quantile * fit.standard_error + systematic;
    let mut corrections = [None; MAX_CORRECTIONS];
    for (slot, c) in corrections.iter_mut().zip(&chosen) {
        *slot = Some(*c);
    }
    Some(OrderFit {
        order: fit.order,
        standard_error: fit.standard_error,
        corrections,
        t_quantile,
        systematic,
        ci95: [fit.order - half, fit.order + half],
        points: n,
        line,
    })
}

/// One least-squares fit of the expansion.
#[derive(Clone)]
struct Expansion {
    order: f64,
    standard_error: f64,
    residual: f64,
    dof: usize,
    /// `d p / d ln e_i`: how each point's log error moves the order.
    weights: Vec<f64>,
}

/// Fits `ln e = a + p ln h + sum b_k t_k(h)` over the given corrections;
/// `None` when the design is singular or leaves no degree of freedom.
fn expansion(points: &[(f64, f64)], corrections: &[Correction]) -> Option<Expansion> {
    let n = points.len();
    let terms = 2 + corrections.len();
    if n <= terms {
        return None;
    }
    let h_max = points.iter().map(|p| p.0).fold(0.0, f64::max);
    let mean_ln_h = points.iter().map(|p| p.0.ln()).sum::<f64>() / n as f64;
    let x = DMatrix::from_fn(n, terms, |i, j| {
        let h = points[i].0;
        match j {
            0 => 1.0,
            1 => h.ln() - mean_ln_h, // centred: the slope is unchanged, the design better conditioned
            k => match corrections[k - 2] {
                Correction::Linear => h / h_max,
                Correction::Quadratic => (h / h_max).powi(2),
            },
        }
    });
    let y = DVector::from_fn(n, |i, _| points[i].1.ln());
    if !x.iter().chain(y.iter()).all(|v| v.is_finite()) {
        return None;
    }
    let xt = x.transpose();
    let inverse = (&xt * &x).try_inverse()?;
    let beta = &inverse * (&xt * &y);
    let residual = (&y - &x * &beta).norm_squared();
    let dof = n - terms;
    let standard_error = (residual / dof as f64 * inverse[(1, 1)]).sqrt();
    let weights = (inverse.row(1) * &xt).iter().copied().collect();
    (beta[1].is_finite() && standard_error.is_finite()).then_some(Expansion {
        order: beta[1],
        standard_error,
        residual,
        dof,
        weights,
    })
}

/// Student's t quantile at 0.975 with `dof` degrees of freedom.
pub(crate) fn t975(dof: usize) -> f64 {
    StudentsT::new(0.0, 1.0, dof as f64)
        .expect("positive degrees of freedom")
        .inverse_cdf(0.975)
}

/// A straight line `ln y = intercept + slope ln x` fitted by least squares.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PowerLaw {
    /// The exponent `p`.
    pub slope: f64,
    /// `ln C`.
    pub intercept: f64,
    /// The 95% confidence interval of the slope, `slope -+ t(0.975, n-2) se`.
    pub ci95: [f64; 2],
    /// The standard error of the slope.
    pub standard_error: f64,
    /// Pearson's correlation of `ln x` with `ln y`.
    pub correlation: f64,
    /// Number of points fitted.
    pub points: usize,
}

/// The jackknife standard error of an estimate from its leave-one-out
/// values (each computed with one of `k` independent samples left out):
/// `sqrt((k - 1)/k sum (x_i - mean)^2)`.
pub(crate) fn jackknife_standard_error(left_out: &[f64]) -> f64 {
    let k = left_out.len() as f64;
    let mean = left_out.iter().sum::<f64>() / k;
    ((k - 1.0) / k * left_out.iter().map(|x| (x - mean).powi(2)).sum::<f64>()).sqrt()
}

/// Fits `ln y = a + p ln x` to the points (all `x`, `y` must be positive and
/// finite). Returns `None` with fewer than three points or no spread in `x`,
/// where no interval can be formed.
pub fn power_law(points: &[(f64, f64)]) -> Option<PowerLaw> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let logs: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    if logs.iter().any(|(x, y)| !x.is_finite() || !y.is_finite()) {
        return None;
    }
    let nf = n as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / nf;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / nf;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let syy: f64 = logs.iter().map(|p| (p.1 - my).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let residual: f64 = logs
        .iter()
        .map(|p| (p.1 - intercept - slope * p.0).powi(2))
        .sum();
    let standard_error = (residual / (nf - 2.0) / sxx).sqrt();
    let t = t975(n - 2);
    let correlation = if syy > 0.0 {
        sxy / (sxx * syy).sqrt()
    } else {
        0.0
    };
    Some(PowerLaw {
        slope,
        intercept,
        ci95: [slope - t * standard_error, slope + t * standard_error],
        standard_error,
        correlation,
        points: n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ladder(h0: f64, n: i32, e: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
        (0..n)
            .map(|k| h0 / 2f64.powi(k))
            .map(|h| (h, e(h)))
            .collect()
    }

    /// The jackknife of the mean is the textbook standard error: leaving
    /// `x_i` out moves the mean to `m_i` with `m_i - mean(m) = -(x_i -
    /// xbar)/(n-1)`, so `(n-1)/n sum (m_i - mean(m))^2 = s^2/n` exactly,
    /// `s^2` the sample variance with `n - 1` in its denominator.
    #[test]
    fn the_jackknife_of_the_mean_is_the_sample_deviation_over_root_n() {
        let x = [2.5, -1.0, 4.0, 0.5, 9.25, 3.0, 1.75];
        let n = x.len() as f64;
        let sum: f64 = x.iter().sum();
        let xbar = sum / n;
        let s2 = x.iter().map(|v| (v - xbar).powi(2)).sum::<f64>() / (n - 1.0);
        let left_out: Vec<f64> = x.iter().map(|v| (sum - v) / (n - 1.0)).collect();
        let se = jackknife_standard_error(&left_out);
        // each leave-one-out mean carries about three roundings of numbers
        // up to 3.5 (1e-15 absolute); against deviations |m_i - mean(m)|
        // that sum to 2.56 (squares to 1.78) that is about 1.4e-15 relative in
        // the standard error, and as much in the reference s / sqrt(n):
        // 3e-15 in all, so 1e-14 is three times the bound, and the
        // `(k + 1)` slip in the formula moves the ratio by 15%
        assert!((se / (s2 / n).sqrt() - 1.0).abs() < 1e-14, "{se}");
    }

    #[test]
    fn exact_power_law_is_recovered_with_a_vanishing_interval() {
        let f = power_law(&ladder(0.1, 6, |h| 3.0 * h * h)).unwrap();
        assert!((f.slope - 2.0).abs() < 1e-12);
        assert!((f.intercept - 3f64.ln()).abs() < 1e-10);
        assert!(f.ci95[1] - f.ci95[0] < 1e-10);
        assert!((f.correlation - 1.0).abs() < 1e-12);
    }

    #[test]
    fn line_interval_matches_a_hand_computed_regression() {
        // ln y at ln x = 0, 1, 2, 3: slope = S_xy / S_xx with S_xx = 5
        let ly: [f64; 4] = [1.0, 2.1, 2.9, 4.2];
        let pts: Vec<_> = ly
            .iter()
            .enumerate()
            .map(|(k, &l)| ((k as f64).exp(), l.exp()))
            .collect();
        let f = power_law(&pts).unwrap();
        let my = ly.iter().sum::<f64>() / 4.0;
        let slope = ly
            .iter()
            .enumerate()
            .map(|(k, l)| (k as f64 - 1.5) * (l - my))
            .sum::<f64>()
            / 5.0;
        let icpt = my - slope * 1.5;
        let ssr: f64 = ly
            .iter()
            .enumerate()
            .map(|(k, l)| (l - icpt - slope * k as f64).powi(2))
            .sum();
        // t(0.975) with 2 degrees of freedom is 4.302652729911275 (tables)
        let half = 4.302652729911275 * (ssr / 2.0 / 5.0).sqrt();
        assert!((f.slope - slope).abs() < 1e-12);
        assert!((f.ci95[0] - (slope - half)).abs() < 1e-9);
        assert!((f.ci95[1] - (slope + half)).abs() < 1e-9);
    }

    #[test]
    fn expansion_fit_removes_the_bias_a_straight_line_keeps() {
        // a first-order method with a 5% relative correction at the coarsest rung
        let pts = ladder(0.01, 8, |h| 0.7 * h * (1.0 + 5.0 * h - 30.0 * h * h));
        let line = power_law(&pts).unwrap();
        assert!(
            !(line.ci95[0] <= 1.0 && 1.0 <= line.ci95[1]),
            "the straight line's interval should miss order 1: {line:?}"
        );
        // one correction leaves the h^2 term's bias, a few 1e-4 at most here
        let fit = order_fit(&pts).unwrap();
        assert!((fit.order - 1.0).abs() < 1e-3, "{fit:?}");
        assert!(fit.ci95[0] <= 1.0 && 1.0 <= fit.ci95[1], "{fit:?}");
    }

    /// A uniform deviate in [-1, 1) from a 64-bit linear congruential generator.
    fn uniform(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    #[test]
    fn interval_covers_the_order_at_least_as_often_as_it_claims() {
        // fourth order with an h^2 correction and 1e-6 relative scatter, as
        // round-off leaves it; the 95% interval must cover p = 4 in at least
        // 93% of 400 independent ladders (Student's t alone gives 95%; a
        // normal quantile or a forgotten t factor would fall well short)
        let mut seed = 2024;
        let trials = 400;
        let covered = (0..trials)
            .filter(|_| {
                let pts: Vec<_> = (0..10)
                    .map(|k| {
                        let h = 0.05 / 2f64.powi(k);
                        let noise = 1.0 + 1e-6 * uniform(&mut seed);
                        (h, 2.0 * h.powi(4) * (1.0 + 0.3 * h * h) * noise)
                    })
                    .collect();
                let fit = order_fit(&pts).unwrap();
                fit.ci95[0] <= 4.0 && 4.0 <= fit.ci95[1]
            })
            .count();
        assert!(
            covered as f64 >= 0.93 * trials as f64,
            "covered {covered} of {trials}"
        );
    }

    #[test]
    fn too_few_or_degenerate_points_give_no_fit() {
        assert!(power_law(&[(1.0, 1.0), (2.0, 4.0)]).is_none());
        assert!(power_law(&[(1.0, 1.0), (1.0, 2.0), (1.0, 3.0)]).is_none());
        assert!(power_law(&[(1.0, 1.0), (2.0, 0.0), (3.0, 3.0)]).is_none());
        assert!(order_fit(&ladder(0.1, MIN_POINTS as i32 - 1, |h| h)).is_none());
        assert!(order_fit(&ladder(0.1, MIN_POINTS as i32, |h| h)).is_some());
        assert!(order_fit(&[(0.1, 1.0); 8]).is_none());
    }
}
