//! Symplecticity: the exact tangent map `J` of one step, `det(J) - 1` and
//! `max |J^T Omega J - Omega|`, at several step sizes and states.

use crate::error::Error;
use crate::maths::tangent::{residual_error_bound, symplectic_residual, tangent_map};
use crate::run::caught;
use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::state::State;
use crate::study::verdict::Verdict;
use crate::tolerance::SYMPLECTIC_TOLERANCE;
use crate::wording::{figure, vs_upper};
use serde::Serialize;

/// Step sizes, in periods of the scene, at which the tangent map is taken by
/// default: coarse enough that a non-symplectic scheme's defect stands far
/// above round-off, fine enough that every explicit scheme's step is defined.
pub const DEFAULT_STEPS: [f64; 3] = [1.0 / 10.0, 1.0 / 30.0, 1.0 / 100.0];

/// Times, in periods, of the states along the exact orbit at which the map is
/// taken (the initial state alone when the scene has no exact solution).
pub const SAMPLE_TIMES: [f64; 4] = [0.0, 0.137, 0.412, 0.733];

/// What to measure: one step size, or the default set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct SymplecticSpec {
    /// The step; `None` for [`DEFAULT_STEPS`].
    pub h: Option<f64>,
}

/// The tangent map at one step size and state.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TangentSample {
    /// The step.
    pub h: f64,
    /// Time along the exact orbit of the state the step starts from.
    pub time: f64,
    /// `det(J) - 1`.
    pub det_minus_one: f64,
    /// `max |J^T Omega J - Omega|` in the scaled coordinates `(q, v / w)`,
    /// over `max(1, max |J_ij|^2)`.
    pub symplectic_residual: f64,
    /// For a map taken by finite differences, the bound on the residual's
    /// error that they carry (added to the tolerance).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finite_difference_error: Option<f64>,
}

/// What the symplecticity study found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SymplecticRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// The scheme claims to be symplectic.
    pub claimed: bool,
    /// `det(J) - 1` of largest magnitude over the samples.
    pub det_minus_one: f64,
    /// Largest symplectic residual over the samples.
    pub symplectic_residual: f64,
    /// The largest allowance over the samples. Each sample is judged
    /// against its own: the round-off [`SYMPLECTIC_TOLERANCE`] plus, for a
    /// map taken by finite differences, their error bound at that sample;
    /// so `symplectic_residual` and `tolerance`, two maxima over different
    /// samples, are not to be compared with each other.
    pub tolerance: f64,
    /// The measured residual is below the tolerance.
    pub measured: bool,
    /// Claim and measurement agree.
    pub verdict: Verdict,
    /// Why, in one line.
    pub reason: String,
    /// Every sample.
    pub samples: Vec<TangentSample>,
}

/// Measures the tangent map of `scheme` on `scene`.
pub fn symplecticity<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    spec: &SymplecticSpec,
) -> Result<SymplecticRecord, Error> {
    let period = scene.period();
    let steps: Vec<f64> = match spec.h {
        Some(h) => vec![crate::scene::step("h", h, scene.frequency())?],
        None => DEFAULT_STEPS.iter().map(|f| f * period).collect(),
    };
    let states: Vec<(f64, State<D>)> = match scene.exact(0.0) {
        Some(_) => SAMPLE_TIMES
            .iter()
            .map(|f| (f * period, scene.exact(f * period).expect("exact exists")))
            .collect(),
        None => vec![(0.0, scene.initial())],
    };
    let mut samples = Vec::new();
    // A panic in the step, or a non-finite map from a finite state on the
    // orbit at a step that resolves the motion, is a defect of the step:
    // one such step of a bounded map cannot leave the numbers (see
    // `breakdown.rs`). The first one found decides. At a coarser step a
    // force growing faster than linearly (the anharmonic well's cubic past
    // its barrier) can overflow within one step by itself: no defect, and
    // nothing measured there.
    let resolved = DEFAULT_STEPS[0] * period * (1.0 + 1e-12);
    let mut defect: Option<String> = None;
    let mut overflowed: Option<String> = None;
    'steps: for &h in &steps {
        for (time, s) in &states {
            let at = format!("h = {}, from the state at t = {}", figure(h), figure(*time));
            let (j, entry_error) = match caught(|| tangent_map(scheme, scene, s, h)) {
                Ok(Ok(map)) => map,
                // a step that cannot be taken (an implicit solve failing) has no tangent map
                Ok(Err(_)) => continue,
                Err(message) => {
                    defect = Some(format!("the step panicked at {at}: {message}"));
                    break 'steps;
                }
            };
            if j.iter().any(|x| !x.is_finite()) {
                if h > resolved {
                    overflowed.get_or_insert(at);
                    continue;
                }
                defect = Some(format!(
                    "the tangent map of one step at {at} is not finite: the step returned a \
                     non-finite state from a finite one"
                ));
                break 'steps;
            }
            samples.push(TangentSample {
                h,
                time: *time,
                det_minus_one: j.clone().determinant() - 1.0,
                // relative to the largest entry of J^T Omega J, whose round-off
                // scales with it (see SYMPLECTIC_TOLERANCE)
                symplectic_residual: symplectic_residual(&j) / j.amax().powi(2).max(1.0),
                finite_difference_error: entry_error.map(|e| residual_error_bound(&j, e)),
            });
        }
    }
    let meta = scheme.meta();
    let det_minus_one = samples
        .iter()
        .map(|s| s.det_minus_one)
        .fold(0.0, |a: f64, b| if b.abs() > a.abs() { b } else { a });
    let residual = samples
        .iter()
        .map(|s| s.symplectic_residual)
        .fold(0.0, f64::max);
    let mut judged = judge(&samples, meta.symplectic);
    if let (Some(at), None) = (&overflowed, &defect) {
        let why = format!(
            "the tangent map of one step at {at} is not finite: at a step above {} of the \
             period a force growing faster than linearly can leave the numbers within one step, \
             so nothing is measured there",
            figure(DEFAULT_STEPS[0]),
        );
        if samples.is_empty() {
            judged.verdict = Verdict::Inconclusive;
            judged.measured = false;
            judged.reason = format!(
                "{why}; take a step of at most {}",
                figure(DEFAULT_STEPS[0] * period)
            );
        } else {
            judged.reason = format!("{} ({why})", judged.reason);
        }
    }
    if let Some(defect) = defect {
        judged.verdict = Verdict::Fail;
        judged.measured = false;
        judged.reason = format!("breakdown: {defect}");
    }
    Ok(SymplecticRecord {
        scheme: meta.id,
        scene: scene.meta().id,
        claimed: meta.symplectic,
        det_minus_one,
        symplectic_residual: residual,
        tolerance: judged.tolerance,
        measured: judged.measured,
        verdict: judged.verdict,
        reason: judged.reason,
        samples,
    })
}

/// What the samples say of a claim.
struct Judged {
    tolerance: f64,
    measured: bool,
    verdict: Verdict,
    reason: String,
}

/// Judges a claim of symplecticity (or of its absence) on the samples:
/// each against its own allowance, round-off plus its finite-difference
/// error bound.
fn judge(samples: &[TangentSample], claimed: bool) -> Judged {
    let allowed =
        |s: &TangentSample| SYMPLECTIC_TOLERANCE + s.finite_difference_error.unwrap_or(0.0);
    let tolerance = samples
        .iter()
        .map(allowed)
        .fold(SYMPLECTIC_TOLERANCE, f64::max);
    let measured =
        !samples.is_empty() && samples.iter().all(|s| s.symplectic_residual <= allowed(s));
    // a claim of symplecticity is refuted by one map that is not; a claim
    // that the scheme is not symplectic promises nothing (on a linear scene
    // many non-symplectic schemes coincide with symplectic ones)
    let (verdict, reason) = match worst_sample(samples, allowed) {
        None => (
            Verdict::Inconclusive,
            "no step could be taken: try a smaller step (SymplecticSpec::h)".to_string(),
        ),
        Some(worst) => {
            let found = compared(worst, allowed(worst), samples.len());
            match (claimed, measured) {
                (true, true) => (Verdict::Pass, format!("{found}: symplectic, as claimed")),
                (true, false) => (
                    Verdict::Fail,
                    format!("{found}: not symplectic, though claimed"),
                ),
                (false, false) => (
                    Verdict::Pass,
                    format!("{found}: not symplectic, as claimed"),
                ),
                (false, true) => (
                    Verdict::Pass,
                    format!(
                        "{found}: symplectic on this scene, which does not refute the claim \
                         that the scheme is not"
                    ),
                ),
            }
        }
    };
    Judged {
        tolerance,
        measured,
        verdict,
        reason,
    }
}

/// The sample whose residual is the largest multiple of its own allowance:
/// the one past it, if any map is not symplectic, else the nearest to it.
fn worst_sample(
    samples: &[TangentSample],
    allowed: impl Fn(&TangentSample) -> f64,
) -> Option<&TangentSample> {
    samples.iter().max_by(|a, b| {
        (a.symplectic_residual / allowed(a)).total_cmp(&(b.symplectic_residual / allowed(b)))
    })
}

/// One sample's residual against its own allowance, with where the
/// allowance comes from and where the sample was taken.
fn compared(s: &TangentSample, allowance: f64, count: usize) -> String {
    let source = match s.finite_difference_error {
        None => "the round-off of J^T Omega J, the tangent map being exact".to_string(),
        Some(e) => format!(
            "round-off {} plus the error bound {} of the tangent map by finite differences",
            figure(SYMPLECTIC_TOLERANCE),
            figure(e)
        ),
    };
    format!(
        "max |J^T Omega J - Omega| / max(1, max |J_ij|^2) = {} ({source}) at h = {}, t = {}, \
         the worst of {count} samples",
        vs_upper(s.symplectic_residual, "allowance", allowance),
        figure(s.h),
        figure(s.time),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wording::comparisons;

    fn sample(h: f64, residual: f64, finite_difference_error: Option<f64>) -> TangentSample {
        TangentSample {
            h,
            time: 0.137,
            det_minus_one: 0.0,
            symplectic_residual: residual,
            finite_difference_error,
        }
    }

    /// A map by finite differences whose error bound is large at the
    /// coarse step (2.7) and small at the fine one: the largest residual
    /// (6.97e-2, coarse, within its bound) and the largest allowance (2.7)
    /// belong to one sample, the refuting residual (1e-2 against 3.1e-12)
    /// to another. The reason must print the refuting sample against its
    /// own allowance, so the inequality it prints holds.
    #[test]
    fn a_refutation_prints_the_refuting_sample_against_its_own_allowance() {
        let samples = [
            sample(0.1, 6.97e-2, Some(2.7)),
            sample(0.01, 1e-2, Some(2.1e-12)),
        ];
        let judged = judge(&samples, true);
        assert_eq!(judged.verdict, Verdict::Fail, "{}", judged.reason);
        // the two maxima, which the old reason printed as "6.97e-2 > 2.70e0"
        assert!(judged.tolerance > 6.97e-2);
        let printed = comparisons(&judged.reason).expect("readable comparisons");
        assert_eq!(printed.len(), 1, "{}", judged.reason);
        let c = &printed[0];
        assert!(c.holds(), "{}", judged.reason);
        assert_eq!(
            (c.left, c.operator, c.right),
            (1e-2, ">", 3.1e-12),
            "{}",
            judged.reason
        );
        assert!(
            judged.reason.contains("finite differences"),
            "{}",
            judged.reason
        );
        assert!(judged.reason.contains("h = 1.00e-2"), "{}", judged.reason);
    }

    #[test]
    fn a_pass_prints_the_sample_nearest_its_allowance() {
        // exact maps: one allowance, the round-off, for every sample
        let samples = [sample(0.1, 3e-15, None), sample(0.01, 4e-13, None)];
        let judged = judge(&samples, true);
        assert_eq!(judged.verdict, Verdict::Pass);
        let c = &comparisons(&judged.reason).expect("readable")[0];
        assert_eq!(
            (c.left, c.operator, c.right),
            (4e-13, "<=", SYMPLECTIC_TOLERANCE)
        );
        assert!(judged.reason.contains("exact"), "{}", judged.reason);
    }
}
