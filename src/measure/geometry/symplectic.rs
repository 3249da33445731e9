//! Symplecticity: the exact tangent map `J` of one step, `det(J) - 1` and
//! `max |J^T Omega J - Omega|`, at several step sizes and states.

use crate::error::Error;
use crate::measure::Verdict;
use crate::measure::geometry::tangent::{residual_error_bound, symplectic_residual, tangent_map};
use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::state::State;
use crate::tolerance::SYMPLECTIC_TOLERANCE;
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
    /// The residual below which the map counts as symplectic.
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
        Some(h) => vec![crate::scene::positive("h", h)?],
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
    for &h in &steps {
        for (time, s) in &states {
            // a step that cannot be taken (an implicit solve failing) has no tangent map
            let Ok((j, entry_error)) = tangent_map(scheme, scene, s, h) else {
                continue;
            };
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
    // each sample is judged against round-off plus its own finite-difference
    // error; the record states the largest tolerance used
    let allowed =
        |s: &TangentSample| SYMPLECTIC_TOLERANCE + s.finite_difference_error.unwrap_or(0.0);
    let tolerance = samples
        .iter()
        .map(allowed)
        .fold(SYMPLECTIC_TOLERANCE, f64::max);
    let measured =
        !samples.is_empty() && samples.iter().all(|s| s.symplectic_residual <= allowed(s));
    let (shown, differenced) = if scheme.differentiable() {
        (format!("{tolerance:e}"), "")
    } else {
        (
            format!("{tolerance:.2e}"),
            " (tangent map by finite differences, tolerance including their error bound)",
        )
    };
    // a claim of symplecticity is refuted by one map that is not; a claim
    // that the scheme is not symplectic promises nothing (on a linear scene
    // many non-symplectic schemes coincide with symplectic ones)
    let (verdict, reason) = if samples.is_empty() {
        (
            Verdict::Inconclusive,
            "no step could be taken: try a smaller step (SymplecticSpec::h)".to_string(),
        )
    } else {
        let found = format!(
            "residual {residual:.2e} {} {shown}{differenced}",
            if measured { "<=" } else { ">" }
        );
        match (meta.symplectic, measured) {
            (true, true) => (Verdict::Pass, format!("{found}: symplectic, as claimed")),
            (true, false) => (
                Verdict::Fail,
                format!("{found}: not symplectic, though claimed"),
            ),
            (false, false) => (Verdict::Pass, format!("{found}: not symplectic")),
            (false, true) => (
                Verdict::Pass,
                format!(
                    "{found}: symplectic on this scene, which does not refute the claim that \
                     the scheme is not"
                ),
            ),
        }
    };
    Ok(SymplecticRecord {
        scheme: meta.id,
        scene: scene.meta().id,
        claimed: meta.symplectic,
        det_minus_one,
        symplectic_residual: residual,
        tolerance,
        measured,
        verdict,
        reason,
        samples,
    })
}
