//! Phase error on the harmonic oscillator: the frequency of the numerical
//! one-step map against `w0`, and its leading term against the analytic one.

use crate::scene::Harmonic;
use crate::scheme::{PhaseError, Scheme};
use crate::state::State;
use crate::study::verdict::Verdict;
use crate::tolerance::{PHASE_COEFFICIENT_TOLERANCE, PHASE_FLOOR, RECURRENCE_ROOT_SLACK};
use crate::wording::{figure, vs_upper};
use nalgebra::{Complex, DMatrix, Matrix2, Vector1};
use serde::Serialize;

/// `z = h w0` at which the one-step map is taken: from 1.6 down to 1e-4 by
/// factors of `sqrt(2)`; high-order schemes show a phase error above
/// round-off only at the coarse end, low-order ones down to the fine end.
pub fn phase_steps() -> impl Iterator<Item = f64> {
    (0..28).map(|k| 1.6 * 2f64.powf(-0.5 * k as f64))
}

/// The relative phase error at one `z`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PhaseSample {
    /// `h w0`.
    pub z: f64,
    /// `(w_num - w0) / w0`.
    pub relative_phase_error: f64,
}

/// What the phase study found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PhaseRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Every sample, coarse to fine.
    pub samples: Vec<PhaseSample>,
    /// `log2(e(2z) / e(z))` at the finest resolvable pair.
    pub measured_power: Option<f64>,
    /// `e(z) / z^p` there, with `p` the measured power rounded.
    pub measured_coefficient: Option<f64>,
    /// The leading term derived analytically, when the scheme's metadata has it.
    pub analytic: Option<PhaseError>,
    /// Measured against analytic; `None` where there is nothing to compare.
    pub verdict: Option<Verdict>,
    /// Why, in one line.
    pub reason: String,
}

/// The one-step matrix of `scheme` on the oscillator `x'' = -x` at step `z`,
/// obtained by stepping the two basis states (the synchronised map is
/// linear, so its columns are the images of the basis).
pub fn one_step_matrix<M: Scheme>(scheme: &M, z: f64) -> Option<Matrix2<f64>> {
    let osc = Harmonic::default();
    // a step that fails or panics has no matrix
    let image = |x: f64, v: f64| -> Option<State<1>> {
        crate::run::caught(|| {
            let s = State::new(Vector1::new(x), Vector1::new(v));
            let mut carry = scheme.start(&osc, &s, z);
            scheme.step(&osc, &mut carry, z).ok()?;
            Some(scheme.state(&carry, z))
        })
        .ok()
        .flatten()
    };
    let (c1, c2) = (image(1.0, 0.0)?, image(0.0, 1.0)?);
    Some(Matrix2::new(c1.q[0], c2.q[0], c1.v[0], c2.v[0]))
}

/// `w_num h`: the argument of the eigenvalues `(a+d)/2 -+ i sqrt(-bc - (a-d)^2/4)`
/// of `[[a, b], [c, d]]`, written so that no difference of numbers near 1 is
/// formed (`b` and `c` are O(z), `a - d` is O(z^2)); `None` if they are real.
pub fn rotation_angle(m: &Matrix2<f64>) -> Option<f64> {
    let (a, b, c, d) = (m[(0, 0)], m[(0, 1)], m[(1, 0)], m[(1, 1)]);
    let im2 = -b * c - 0.25 * (a - d) * (a - d);
    (im2 > 0.0).then(|| im2.sqrt().atan2(0.5 * (a + d)))
}

/// The roots of the polynomial `sum_j c_j x^j` (coefficients from the
/// constant term up, the last non-zero): the eigenvalues of its companion
/// matrix, computed by nalgebra's real Schur decomposition.
pub fn polynomial_roots(coefficients: &[f64]) -> Vec<Complex<f64>> {
    let n = coefficients.len() - 1;
    let lead = coefficients[n];
    let companion = DMatrix::from_fn(n, n, |i, j| {
        if j == n - 1 {
            -coefficients[i] / lead
        } else if i == j + 1 {
            1.0
        } else {
            0.0
        }
    });
    companion.complex_eigenvalues().iter().copied().collect()
}

/// True when every root lies in the closed unit disc, up to
/// [`RECURRENCE_ROOT_SLACK`].
pub fn roots_bounded(roots: &[Complex<f64>]) -> bool {
    roots
        .iter()
        .all(|r| r.norm() <= 1.0 + RECURRENCE_ROOT_SLACK)
}

/// `w_num h` of a multistep scheme at `z`: the argument of the root of its
/// recurrence nearest `exp(i z)`, the one that carries the motion; `None`
/// where some root leaves the unit disc (no bounded motion to measure).
pub fn recurrence_rotation(polynomial: &[f64], z: f64) -> Option<f64> {
    let roots = polynomial_roots(polynomial);
    let motion = Complex::from_polar(1.0, z);
    let principal = roots
        .iter()
        .min_by(|a, b| (*a - motion).norm().total_cmp(&(*b - motion).norm()))?;
    roots_bounded(&roots).then(|| principal.arg())
}

/// The rotation per step of `scheme` on the oscillator at `z`: from its
/// recurrence's roots for a multistep scheme, from its one-step matrix
/// otherwise.
pub fn rotation_at<M: Scheme>(scheme: &M, z: f64) -> Option<f64> {
    match scheme.recurrence_on_oscillator(z) {
        Some(polynomial) => recurrence_rotation(&polynomial, z),
        None => rotation_angle(&one_step_matrix(scheme, z)?),
    }
}

/// Measures the phase error of `scheme`.
pub fn phase_error<M: Scheme>(scheme: &M) -> PhaseRecord {
    let samples: Vec<PhaseSample> = phase_steps()
        .filter_map(|z| {
            let theta = rotation_at(scheme, z)?;
            Some(PhaseSample {
                z,
                relative_phase_error: theta / z - 1.0,
            })
        })
        .collect();
    // The leading term C z^p: p is the typical local power log(e(2z)/e(z)) /
    // log 2 over the resolvable samples, rounded; C is read where successive
    // estimates e(z) / z^p change least, between the coarse samples (where
    // the next term of the series still shows) and the fine ones (where
    // round-off does; the two-step Störmer form amplifies it by 1/z).
    let resolvable: Vec<PhaseSample> = samples
        .iter()
        .copied()
        .filter(|s| s.relative_phase_error.abs() >= PHASE_FLOOR)
        .collect();
    let powers: Vec<f64> = resolvable
        .windows(2)
        .map(|w| {
            (w[0].relative_phase_error / w[1].relative_phase_error)
                .abs()
                .ln()
                / (w[0].z / w[1].z).ln()
        })
        .collect();
    let p = median(&powers).map(f64::round);
    let best = p.and_then(|p| {
        let c: Vec<f64> = resolvable
            .iter()
            .map(|s| s.relative_phase_error / s.z.powi(p as i32))
            .collect();
        (1..c.len())
            .min_by(|&i, &j| (c[i] - c[i - 1]).abs().total_cmp(&(c[j] - c[j - 1]).abs()))
            .map(|k| (k, c[k]))
    });
    let measured_power = best.map(|(k, _)| powers[k - 1]);
    let measured_coefficient = best.map(|(_, c)| c);
    let meta = scheme.meta();
    let (verdict, reason) = match (meta.phase_error, measured_power, measured_coefficient) {
        (Some(a), Some(p), Some(c)) => {
            let allowance = PHASE_COEFFICIENT_TOLERANCE * a.coefficient.abs();
            let power_ok = p.round() as u32 == a.power;
            let ok = power_ok && (c - a.coefficient).abs() <= allowance;
            (
                Some(Verdict::from_bool(ok)),
                format!(
                    "measured {} z^{p:.2}, analytic {} z^{}: {}",
                    figure(c),
                    figure(a.coefficient),
                    a.power,
                    if power_ok {
                        format!(
                            "|C - C_analytic| = {} ({PHASE_COEFFICIENT_TOLERANCE} of the \
                             analytic coefficient)",
                            vs_upper((c - a.coefficient).abs(), "allowance", allowance)
                        )
                    } else {
                        format!("the power {p:.2} is not the analytic {}", a.power)
                    }
                ),
            )
        }
        (None, Some(p), Some(c)) => (
            None,
            format!("measured {} z^{p:.2}; no analytic value", figure(c)),
        ),
        // a high-order scheme may have no phase error above the floor at any
        // step where it is stable: nothing is claimed, so nothing fails
        (None, _, _) => (
            None,
            format!(
                "below {PHASE_FLOOR:e} at every stable step sampled (z = 1.6 / sqrt(2)^k): \
                 not resolvable in double precision"
            ),
        ),
        _ => (
            Some(Verdict::Fail),
            "no phase error above round-off could be measured".to_string(),
        ),
    };
    PhaseRecord {
        scheme: meta.id,
        samples,
        measured_power,
        measured_coefficient,
        analytic: meta.phase_error,
        verdict,
        reason,
    }
}

fn median(v: &[f64]) -> Option<f64> {
    let mut v: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    (!v.is_empty()).then(|| v[v.len() / 2])
}
