//! Linear stability: for which `z = h w0` do the iterates of a scheme on the
//! oscillator `x'' = -w0^2 x` stay bounded, and how fast do they grow where
//! they do not?
//!
//! The one-step map on the oscillator is a 2x2 matrix `M(z)` (measured from
//! the scheme itself by stepping the basis states, see
//! [`super::accuracy::phase::one_step_matrix`]); its powers stay bounded when its
//! spectral radius is at most one. The boundaries of the stable set are
//! found on a scan and bisected.
//!
//! In double precision "stable" can only mean "no growth resolvable above
//! the round-off of the stepped map". A map whose eigenvalues have modulus
//! `sqrt(det M) = 1 + c z^k / 2 + ..` is unstable at every `z > 0`, but at
//! small `z` its growth sinks below that round-off, and a scan sees a stable
//! interval `[0, b]` whose end `b` is only where the growth crosses the
//! round-off bound. [`growth_law`] tells such a map apart: where `det - 1`
//! is first measured it must follow `c z^k` with `c > 0`, and the law's
//! leading term then carries the growth down to `z -> 0` (see
//! [`GROWTH_POWER_TOLERANCE`]). Such a scheme is *weakly unstable*: its
//! limit is 0, and its record gives the law and the growth per step and per
//! period at a few steps instead.

use crate::scene::Harmonic;
use crate::scheme::Scheme;
use crate::study::accuracy::phase::{one_step_matrix, polynomial_roots, roots_bounded};
use crate::tolerance::{
    GROWTH_POWER_TOLERANCE, GROWTH_VALUE_RESOLUTION, STABILITY_BISECTION,
    STABILITY_SLACK_EPS_PER_EVALUATION,
};
use nalgebra::Matrix2;
use serde::Serialize;
use std::f64::consts::TAU;

/// The scan: `z` from 0 to [`LINEAR_SCAN_END`] in steps of
/// [`LINEAR_SCAN_STEP`], then log-spaced to [`SCAN_END`]; a scheme stable on
/// all of it is reported stable for every step.
pub const LINEAR_SCAN_STEP: f64 = 1e-3;
/// End of the fine linear scan: beyond every explicit scheme's limit.
pub const LINEAR_SCAN_END: f64 = 20.0;
// The scan's ends are thresholds of their own, which the scenes' step checks
// read as well: they live with the other thresholds, below the scenes.
pub use crate::tolerance::{SCAN_END, SCAN_START};

/// The steps `z = h w0` at which the growth of an unstable map is reported:
/// from ten to three steps a radian, where a run of any length sees it.
pub const GROWTH_AT: [f64; 5] = [0.1, 0.5, 1.0, 2.0, 3.0];

/// Points of the growth law's fit window: `z_F 2^(j/4)`, `j = 0..=8`, a
/// factor 4 of `z` in two halves of a factor 2.
const GROWTH_WINDOW: usize = 9;

/// What the stability study found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StabilityRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// The largest `z` up to which every step is stable: `None` when stable
    /// for every scanned step, `Some(0)` when unstable for the smallest
    /// (explicit Euler) or, for a weakly unstable map, for every `z > 0`.
    pub stability_limit: Option<f64>,
    /// Every stable interval `[a, b]` of `z` found (`b = None`: to the end
    /// of the scan and beyond); for a weakly unstable map, without the
    /// intervals below its law's window, where its growth is only below
    /// round-off.
    pub stable_intervals: Vec<[Option<f64>; 2]>,
    /// `stability_limit` divided by the force evaluations of a step: the
    /// stable step a user gets per unit of work.
    pub limit_per_force_evaluation: Option<f64>,
    /// The smallest growth per step, `rho - 1`, that the stepped map
    /// resolves at small `z` (half the round-off bound of its determinant):
    /// a map called stable may still grow by less than this per step.
    /// `None` for a multistep recurrence, whose roots are judged instead.
    pub growth_resolution: Option<f64>,
    /// For a one-step map unstable at every `z > 0`: its growth law and
    /// growth at [`GROWTH_AT`]. `None` for every other scheme.
    pub growth: Option<GrowthLaw>,
}

impl StabilityRecord {
    /// True when the map is unstable at every `z > 0` although a scan in
    /// double precision sees a stable interval at small `z` (its growth
    /// there is below round-off).
    pub fn weakly_unstable(&self) -> bool {
        self.growth
            .as_ref()
            .is_some_and(|g| g.unresolved_below.is_some())
    }
}

/// `det M(z) - 1 = c z^k (1 + O(z^2))` of a map unstable at every `z > 0`,
/// fitted where it is first measured above round-off.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GrowthLaw {
    /// The leading power `k` (the nearest integer to the fitted slope).
    pub power: u32,
    /// The slope of `ln(det - 1)` against `ln z` over the fit window.
    pub power_fitted: f64,
    /// The leading coefficient `c > 0`: the intercept at `z = 0` of
    /// `(det - 1)/z^k` fitted linearly in `z^2` over the window. The growth
    /// per step is `sqrt(1 + c z^k) - 1 ~ c z^k / 2` at small `z`.
    pub coefficient: f64,
    /// Bound on the round-off in `coefficient`: the fit's weights applied to
    /// the round-off bounds of the window's `det - 1`.
    pub coefficient_round_off: f64,
    /// The fit window `[z_F, 4 z_F]`: `z_F` is the first `z` of the scan
    /// where `det - 1` is measured ([`GROWTH_VALUE_RESOLUTION`] times its
    /// round-off), and it is positive there.
    pub window: [f64; 2],
    /// The end of the interval `[0, b]` a scan calls stable because the
    /// growth there is below round-off (the map is weakly unstable); `None`
    /// when the growth is resolved at every scanned `z`.
    pub unresolved_below: Option<f64>,
    /// The growth at each of [`GROWTH_AT`] where the map exists.
    pub at: Vec<GrowthAt>,
}

/// Where a growth figure comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GrowthSource {
    /// From the stepped map, `det - 1` at least [`GROWTH_VALUE_RESOLUTION`]
    /// times its round-off.
    Measured,
    /// Below that, at a `z` under the fit window: from the law `c z^k`.
    Law,
    /// Below that, above the window, where the law does not reach: no
    /// figure.
    Unresolved,
}

/// The growth of the map at one `z`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GrowthAt {
    /// `z = h w0`.
    pub z: f64,
    /// `rho(z) - 1`, the growth per step (`None`: unresolved).
    pub per_step: Option<f64>,
    /// `rho(z)^(2 pi / z) - 1`, the growth per period of the oscillator.
    pub per_period: Option<f64>,
    /// Where the figures come from.
    pub source: GrowthSource,
}

/// The spectral radius of `M`.
pub fn spectral_radius(m: &Matrix2<f64>) -> f64 {
    let half_trace = 0.5 * (m[(0, 0)] + m[(1, 1)]);
    let det = m.determinant();
    let disc = half_trace * half_trace - det;
    if disc < 0.0 {
        det.max(0.0).sqrt()
    } else {
        half_trace.abs() + disc.sqrt()
    }
}

/// `rho(M) - 1`, without the cancellation of `sqrt(det) - 1` when the
/// eigenvalues are complex (`rho^2 = det`).
pub fn radius_excess(m: &Matrix2<f64>) -> f64 {
    let half_trace = 0.5 * m.trace();
    let det = m.determinant();
    if half_trace * half_trace < det {
        (det - 1.0) / (1.0 + det.sqrt())
    } else {
        spectral_radius(m) - 1.0
    }
}

/// The round-off bound of the determinant of a map stepped by `scheme`:
/// [`STABILITY_SLACK_EPS_PER_EVALUATION`] `eps` per force evaluation, per
/// unit of `|m11 m22| + |m12 m21|` (at least 1), whose difference it is.
pub fn determinant_round_off<M: Scheme>(scheme: &M, m: &Matrix2<f64>) -> f64 {
    let products = (m[(0, 0)] * m[(1, 1)]).abs() + (m[(0, 1)] * m[(1, 0)]).abs();
    slack(scheme) * products.max(1.0)
}

fn slack<M: Scheme>(scheme: &M) -> f64 {
    STABILITY_SLACK_EPS_PER_EVALUATION
        * scheme.epsilon()
        * scheme.meta().force_evaluations.max(1) as f64
}

/// Is the scheme's one-step map on the oscillator power-bounded at `z`?
/// A step that cannot be taken counts as unstable.
///
/// Both roots of `l^2 - tr l + det` lie in the closed unit disc exactly when
/// `det <= 1` and `|tr| <= 1 + det` (Jury's conditions). Unlike the spectral
/// radius, these need no square root, which near a double eigenvalue would
/// turn round-off of `1e-16` into `1e-8`; the slack covers the round-off of
/// the map's entries (see [`STABILITY_SLACK_EPS_PER_EVALUATION`]); for the
/// determinant, in proportion to the size of its two products, whose
/// difference is 1 for an area-preserving map however large the entries.
/// A growth below the slack is not seen here: [`stability`] looks for it
/// with [`growth_law`].
pub fn is_stable<M: Scheme>(scheme: &M, z: f64) -> bool {
    if let Some(polynomial) = scheme.recurrence_on_oscillator(z) {
        return roots_bounded(&polynomial_roots(&polynomial));
    }
    let slack = slack(scheme);
    one_step_matrix(scheme, z).is_some_and(|m| {
        let (trace, det) = (m.trace(), m.determinant());
        // a determinant above 1 by no more than its round-off is 1: it must
        // not widen the trace condition, which stays in units of eps
        det <= 1.0 + determinant_round_off(scheme, &m) && trace.abs() <= 1.0 + det.min(1.0) + slack
    })
}

/// `det M(z) - 1` and its round-off bound; `None` where no step is taken.
fn determinant_excess<M: Scheme>(scheme: &M, z: f64) -> Option<(Matrix2<f64>, f64, f64)> {
    let m = one_step_matrix(scheme, z)?;
    Some((m, m.determinant() - 1.0, determinant_round_off(scheme, &m)))
}

/// The leading law of a one-step map's growth, when the map grows at every
/// `z > 0`; `None` for a multistep recurrence, a map whose determinant is 1
/// to round-off at every scanned `z`, one that is damped where `det - 1` is
/// first measured (RK4: `det - 1 = -z^6/72 + z^8/576`), and one whose
/// `det - 1` is not a clean power of `z` there (a boundary at a zero of
/// `det - 1`).
///
/// The scan runs log-spaced (`2^(1/4)` apart) from [`SCAN_START`] to
/// [`LINEAR_SCAN_END`]; `z_F` is its first point where `|det - 1|` is
/// [`GROWTH_VALUE_RESOLUTION`] times its round-off. Below `z_F` nothing is
/// measured, so nothing there contradicts the law. At `z_F` `det - 1` must be
/// positive, and over `[z_F, 4 z_F]` its log-slope must stay within
/// [`GROWTH_POWER_TOLERANCE`] of one integer `k` on both halves; then the
/// leading term `c z^k` carries `det - 1 > 0` from `z_F` down to 0. That
/// inference assumes no term smaller than round-off everywhere on the scan
/// changes sign below it, and nothing in double precision can see one; a
/// map whose growth is below round-off at every scanned `z` has no law and
/// is called stable, within [`StabilityRecord::growth_resolution`].
pub fn growth_law<M: Scheme>(scheme: &M) -> Option<GrowthLaw> {
    if scheme.recurrence_on_oscillator(SCAN_START).is_some() {
        return None;
    }
    let point = |j: usize| SCAN_START * 2f64.powf(j as f64 / 4.0);
    let measured = |e: f64, round_off: f64| e.abs() >= GROWTH_VALUE_RESOLUTION * round_off;
    let first = (0..)
        .map(point)
        .take_while(|z| *z <= LINEAR_SCAN_END)
        .position(|z| determinant_excess(scheme, z).is_some_and(|(_, e, r)| measured(e, r)))?;
    let window: Vec<(f64, f64, f64)> = (first..first + GROWTH_WINDOW)
        .map(|j| {
            let z = point(j);
            determinant_excess(scheme, z).map(|(_, e, r)| (z, e, r))
        })
        .collect::<Option<_>>()?;
    if window.iter().any(|&(_, e, r)| e <= 0.0 || !measured(e, r)) {
        return None;
    }
    let slope = |a: usize, b: usize| {
        let ((za, ea, _), (zb, eb, _)) = (window[a], window[b]);
        (eb / ea).ln() / (zb / za).ln()
    };
    let (mid, last) = (GROWTH_WINDOW / 2, GROWTH_WINDOW - 1);
    let power_fitted = slope(0, last);
    let k = power_fitted.round();
    if k < 0.0
        || (slope(0, mid) - k).abs() > GROWTH_POWER_TOLERANCE
        || (slope(mid, last) - k).abs() > GROWTH_POWER_TOLERANCE
    {
        return None;
    }
    // (det - 1)/z^k = c + d z^2: least squares in x = z^2, intercept c
    let n = window.len() as f64;
    let xs: Vec<f64> = window.iter().map(|w| w.0 * w.0).collect();
    let mean = xs.iter().sum::<f64>() / n;
    let sxx: f64 = xs.iter().map(|x| (x - mean) * (x - mean)).sum();
    let weights: Vec<f64> = xs
        .iter()
        .map(|x| 1.0 / n - mean * (x - mean) / sxx)
        .collect();
    let scaled = |v: f64, z: f64| v / z.powi(k as i32);
    let coefficient: f64 = weights
        .iter()
        .zip(&window)
        .map(|(w, &(z, e, _))| w * scaled(e, z))
        .sum();
    let coefficient_round_off: f64 = weights
        .iter()
        .zip(&window)
        .map(|(w, &(z, _, r))| w.abs() * scaled(r, z))
        .sum();
    if coefficient <= coefficient_round_off {
        return None;
    }
    let window_range = [window[0].0, window[last].0];
    let law_excess = |z: f64| {
        let e = coefficient * z.powi(k as i32);
        e / (1.0 + (1.0 + e).sqrt())
    };
    let at = GROWTH_AT
        .iter()
        .filter_map(|&z| {
            let (m, e, r) = determinant_excess(scheme, z)?;
            let (source, per_step) = if measured(e, r) {
                (GrowthSource::Measured, Some(radius_excess(&m)))
            } else if z < window_range[0] {
                (GrowthSource::Law, Some(law_excess(z)))
            } else {
                (GrowthSource::Unresolved, None)
            };
            Some(GrowthAt {
                z,
                per_step,
                per_period: per_step.map(|g| per_period(g, z)),
                source,
            })
        })
        .collect();
    Some(GrowthLaw {
        power: k as u32,
        power_fitted,
        coefficient,
        coefficient_round_off,
        window: window_range,
        unresolved_below: None,
        at,
    })
}

/// `rho^(2 pi / z) - 1` from `rho - 1`, without cancellation.
pub fn per_period(per_step: f64, z: f64) -> f64 {
    (TAU / z * per_step.ln_1p()).exp_m1()
}

/// Measures the stable intervals and the limit of `scheme`, and the growth
/// law of a map unstable at every `z > 0`.
pub fn stability<M: Scheme>(scheme: &M) -> StabilityRecord {
    let mut grid: Vec<f64> = vec![SCAN_START];
    grid.extend(
        (1..)
            .map(|k| k as f64 * LINEAR_SCAN_STEP)
            .take_while(|z| *z <= LINEAR_SCAN_END),
    );
    let decades = (SCAN_END / LINEAR_SCAN_END).log10();
    grid.extend(
        (1..=(200.0 * decades) as usize).map(|k| LINEAR_SCAN_END * 10f64.powf(k as f64 / 200.0)),
    );

    let mut intervals: Vec<[Option<f64>; 2]> = Vec::new();
    let mut open: Option<f64> = None;
    let mut prev = (0.0, true); // z -> 0 is stable for every consistent scheme
    let mut first = true;
    for &z in &grid {
        let stable = is_stable(scheme, z);
        if first {
            first = false;
            if stable {
                open = Some(0.0);
            }
            prev = (z, stable);
            continue;
        }
        if stable != prev.1 {
            let edge = bisect(scheme, prev.0, z, prev.1);
            if stable {
                open = Some(edge);
            } else if let Some(a) = open.take() {
                intervals.push([Some(a), Some(edge)]);
            }
        }
        prev = (z, stable);
    }
    if let Some(a) = open {
        intervals.push([Some(a), None]);
    }
    let mut growth = growth_law(scheme);
    if let Some(law) = &mut growth {
        // below the window the law's growth is under the round-off bound:
        // an interval there is where it is unresolved, not where it is absent
        // (at `z_F` itself the map is unstable by the scan's own test, so no
        // interval straddles it)
        let below = |i: &[Option<f64>; 2]| i[1].is_some_and(|b| b < law.window[0]);
        law.unresolved_below = intervals
            .iter()
            .filter(|i| below(i))
            .filter_map(|i| i[1])
            .next_back();
        intervals.retain(|i| !below(i));
    }
    let stability_limit = match intervals.first() {
        Some([Some(a), b]) if *a == 0.0 => *b,
        _ => Some(0.0),
    };
    // per evaluation actually spent: counted on the oscillator the scan runs on
    let evaluations =
        crate::study::cost::count::per_step_charged(scheme, &Harmonic::default()).max(1.0);
    let growth_resolution = scheme
        .recurrence_on_oscillator(SCAN_START)
        .is_none()
        .then(|| 0.5 * slack(scheme));
    StabilityRecord {
        scheme: scheme.meta().id,
        stability_limit,
        stable_intervals: intervals,
        limit_per_force_evaluation: stability_limit.map(|z| z / evaluations),
        growth_resolution,
        growth,
    }
}

/// The boundary between `lo` (stability `lo_stable`) and `hi` (the other).
fn bisect<M: Scheme>(scheme: &M, mut lo: f64, mut hi: f64, lo_stable: bool) -> f64 {
    while hi - lo > STABILITY_BISECTION {
        let mid = 0.5 * (lo + hi);
        if is_stable(scheme, mid) == lo_stable {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
