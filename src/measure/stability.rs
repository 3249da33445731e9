//! Linear stability: for which `z = h w0` do the iterates of a scheme on the
//! oscillator `x'' = -w0^2 x` stay bounded?
//!
//! The one-step map on the oscillator is a 2x2 matrix `M(z)` (measured from
//! the scheme itself by stepping the basis states, see
//! [`super::accuracy::phase::one_step_matrix`]); its powers stay bounded when its
//! spectral radius is at most one. The boundaries of the stable set are
//! found on a scan and bisected.

use crate::measure::accuracy::phase::{one_step_matrix, polynomial_roots, roots_bounded};
use crate::scheme::Scheme;
use crate::tolerance::{STABILITY_BISECTION, STABILITY_SLACK_EPS_PER_EVALUATION};
use nalgebra::Matrix2;
use serde::Serialize;

/// The scan: `z` from 0 to [`LINEAR_SCAN_END`] in steps of
/// [`LINEAR_SCAN_STEP`], then log-spaced to [`SCAN_END`]; a scheme stable on
/// all of it is reported stable for every step.
pub const LINEAR_SCAN_STEP: f64 = 1e-3;
/// End of the fine linear scan: beyond every explicit scheme's limit.
pub const LINEAR_SCAN_END: f64 = 20.0;
/// End of the log-spaced scan.
pub const SCAN_END: f64 = 1e6;

/// What the stability study found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StabilityRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// The largest `z` up to which every step is stable: `None` when stable
    /// for every scanned step, `Some(0)` when unstable for the smallest.
    pub stability_limit: Option<f64>,
    /// Every stable interval `[a, b]` of `z` found (`b = None`: to the end
    /// of the scan and beyond).
    pub stable_intervals: Vec<[Option<f64>; 2]>,
    /// `stability_limit` divided by the force evaluations of a step: the
    /// stable step a user gets per unit of work.
    pub limit_per_force_evaluation: Option<f64>,
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
pub fn is_stable<M: Scheme>(scheme: &M, z: f64) -> bool {
    if let Some(polynomial) = scheme.recurrence_on_oscillator(z) {
        return roots_bounded(&polynomial_roots(&polynomial));
    }
    let slack = STABILITY_SLACK_EPS_PER_EVALUATION
        * scheme.epsilon()
        * scheme.meta().force_evaluations.max(1) as f64;
    one_step_matrix(scheme, z).is_some_and(|m| {
        let (trace, det) = (m.trace(), m.determinant());
        let products = (m[(0, 0)] * m[(1, 1)]).abs() + (m[(0, 1)] * m[(1, 0)]).abs();
        // a determinant above 1 by no more than its round-off is 1: it must
        // not widen the trace condition, which stays in units of eps
        det <= 1.0 + slack * products.max(1.0) && trace.abs() <= 1.0 + det.min(1.0) + slack
    })
}

/// Measures the stable intervals and the limit of `scheme`.
pub fn stability<M: Scheme>(scheme: &M) -> StabilityRecord {
    let mut grid: Vec<f64> = vec![1e-6];
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
    let stability_limit = match intervals.first() {
        Some([Some(a), b]) if *a == 0.0 => *b,
        _ => Some(0.0),
    };
    let evaluations = scheme.meta().force_evaluations.max(1) as f64;
    StabilityRecord {
        scheme: scheme.meta().id,
        stability_limit,
        stable_intervals: intervals,
        limit_per_force_evaluation: stability_limit.map(|z| z / evaluations),
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
