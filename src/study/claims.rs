//! Every claim of an integrator on a scene from one call: each claim's
//! verdict with the message that states its figures, beside the full
//! records that decided it, as plain serde data for a table, a CI summary
//! or an audit. The guards judge these same verdicts by one rule,
//! [`Verdict::fails_a_guard`].
//!
//! ```
//! use stepladder::scene::Harmonic;
//! use stepladder::scheme::VELOCITY_VERLET;
//! use stepladder::study::claims;
//!
//! let record = claims(&VELOCITY_VERLET, &Harmonic::default())?;
//! for v in &record.verdicts {
//!     println!("{:<12} {:<13} {}", v.claim, v.verdict.name(), v.message);
//! }
//! assert!(record.passed());
//! # Ok::<(), stepladder::error::Error>(())
//! ```

use crate::error::Error;
use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::study::accuracy::order::{OrderRecord, OrderSpec, global_order};
use crate::study::accuracy::rung::Rung;
use crate::study::adaptive::{AdaptiveClaim, ToleranceLadderRecord};
use crate::study::cost::evaluations::{EvaluationRecord, counting_step, evaluations};
use crate::study::geometry::energy::{EnergyRecord, EnergySpec, energy_drift};
use crate::study::geometry::reverse::{ReverseRecord, ReverseSpec, reversibility};
use crate::study::geometry::symplectic::{SymplecticRecord, SymplecticSpec, symplecticity};
use crate::study::verdict::Verdict;
use crate::wording::{figure, order};
use serde::Serialize;

/// One claim's verdict and the message that states it, with the figures
/// that decided it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClaimVerdict {
    /// The claim: `order`, `symplectic`, `reversible`, `energy`,
    /// `evaluations` for a fixed-step scheme; an adaptive integrator's are
    /// [`AdaptiveClaim::name`]'s.
    pub claim: &'static str,
    /// Pass, fail, inconclusive, or not claimed.
    pub verdict: Verdict,
    /// Scheme, scene, claim, verdict, the deciding figures and why.
    pub message: String,
}

impl ClaimVerdict {
    /// The message, when the verdict fails a guard
    /// ([`Verdict::fails_a_guard`]).
    pub fn failure(&self) -> Option<&str> {
        self.verdict
            .fails_a_guard()
            .then_some(self.message.as_str())
    }
}

/// Every claim of a fixed-step scheme on a scene: the verdicts in the order
/// order, symplectic, reversible, energy, evaluations, and the record of
/// each study with every figure it measured. The pin is apart
/// ([`crate::guard::assert_pinned`]): it reads and writes a file.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClaimsRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// Each claim's verdict and message.
    pub verdicts: Vec<ClaimVerdict>,
    /// The global order over the automatic ladder.
    pub order: OrderRecord,
    /// The tangent map of one step.
    pub symplectic: SymplecticRecord,
    /// The round trip.
    pub reversible: ReverseRecord,
    /// The long energy run.
    pub energy: EnergyRecord,
    /// The force evaluations counted in a step.
    pub evaluations: EvaluationRecord,
}

impl ClaimsRecord {
    /// No claim fails its guard.
    pub fn passed(&self) -> bool {
        self.verdicts.iter().all(|v| !v.verdict.fails_a_guard())
    }

    /// The messages of the claims that fail their guard.
    pub fn failures(&self) -> Vec<&str> {
        self.verdicts
            .iter()
            .filter_map(ClaimVerdict::failure)
            .collect()
    }
}

/// Runs every study that judges a claim of `scheme` on `scene`, with the
/// default specs the guards use; an error only if a study cannot run at all
/// (a scene without what it needs). A breakdown or a panic in the scheme is
/// a verdict, not an error.
pub fn claims<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> Result<ClaimsRecord, Error> {
    let order = global_order(scheme, scene, &OrderSpec::default())?;
    let symplectic = symplecticity(scheme, scene, &SymplecticSpec::default())?;
    let reversible = reversibility(scheme, scene, &ReverseSpec::default())?;
    let energy = energy_drift(scheme, scene, &EnergySpec::default())?;
    let evaluations = evaluations(scheme, scene, counting_step(scene));
    Ok(ClaimsRecord {
        scheme: scheme.meta().id,
        scene: scene.meta().id,
        verdicts: vec![
            (&order).into(),
            (&symplectic).into(),
            (&reversible).into(),
            (&energy).into(),
            (&evaluations).into(),
        ],
        order,
        symplectic,
        reversible,
        energy,
        evaluations,
    })
}

impl From<&OrderRecord> for ClaimVerdict {
    fn from(r: &OrderRecord) -> Self {
        let ladder = match (r.rungs.first(), r.rungs.last()) {
            (Some(a), Some(b)) => {
                format!(
                    "{} rungs, h = {} .. {}",
                    r.rungs.len(),
                    figure(a.h),
                    figure(b.h)
                )
            }
            _ => "no rungs".to_string(),
        };
        let message = format!(
            "stepladder: `{}` on `{}`: {} order {} claimed, measured {} in {} over rungs {}; ladder {ladder} to t_end = {}: {}{}",
            r.scheme,
            r.scene,
            r.verdict.name(),
            r.theoretical_order,
            r.measured_order.map_or("nothing".into(), order),
            r.ci95.map_or("no interval".into(), |c| format!(
                "[{}, {}]",
                order(c[0]),
                order(c[1])
            )),
            r.window.map_or("none".into(), |[a, b]| format!("{a}..{b}")),
            figure(r.t_end),
            r.reason,
            r.advice
                .as_ref()
                .map_or(String::new(), |a| format!("; to decide: {a}"))
        ) + &solves_beside_errors(&r.rungs);
        ClaimVerdict {
            claim: "order",
            verdict: r.verdict,
            message,
        }
    }
}

/// For a scheme that reports its solves: the iterations per step and the
/// largest residual beside the error at the coarsest and the finest rungs
/// measured, so that a floor set by the solve's own tolerance shows where
/// it comes from. Empty for a scheme that reports none.
fn solves_beside_errors(rungs: &[Rung]) -> String {
    let reported: Vec<(f64, f64, crate::scheme::SolveTally)> = rungs
        .iter()
        .filter_map(|g| Some((g.h, g.error.or(g.half_step_difference)?, g.solve?)))
        .collect();
    let one = |&(h, error, tally): &(f64, f64, crate::scheme::SolveTally)| {
        format!(
            "at h = {}, error {}: {:.1} iterations a step, largest residual {}",
            figure(h),
            figure(error),
            tally.iterations_per_step(),
            figure(tally.largest_residual)
        )
    };
    match reported.as_slice() {
        [] => String::new(),
        [only] => format!("; its solves {}", one(only)),
        [first, .., last] => format!("; its solves {}; {}", one(first), one(last)),
    }
}

impl From<&SymplecticRecord> for ClaimVerdict {
    fn from(r: &SymplecticRecord) -> Self {
        ClaimVerdict {
            claim: "symplectic",
            verdict: r.verdict,
            message: format!(
                "stepladder: `{}` on `{}`: symplectic claimed {}, {}: {}",
                r.scheme,
                r.scene,
                r.claimed,
                r.verdict.name(),
                r.reason,
            ),
        }
    }
}

impl From<&ReverseRecord> for ClaimVerdict {
    fn from(r: &ReverseRecord) -> Self {
        ClaimVerdict {
            claim: "reversible",
            verdict: r.verdict,
            message: format!(
                "stepladder: `{}` on `{}`: time-symmetric claimed {}, {}: {} steps of h = {} and back: {}",
                r.scheme,
                r.scene,
                r.claimed,
                r.verdict.name(),
                r.steps,
                figure(r.h),
                r.reason
            ),
        }
    }
}

impl From<&EnergyRecord> for ClaimVerdict {
    fn from(r: &EnergyRecord) -> Self {
        ClaimVerdict {
            claim: "energy",
            verdict: r.verdict,
            message: format!(
                "stepladder: `{}` on `{}`: energy expected {}, {} over {} steps of h = {}: {}",
                r.scheme,
                r.scene,
                r.expected.name(),
                r.verdict.name(),
                r.steps,
                figure(r.h),
                r.reason
            ),
        }
    }
}

impl From<&EvaluationRecord> for ClaimVerdict {
    fn from(r: &EvaluationRecord) -> Self {
        ClaimVerdict {
            claim: "evaluations",
            verdict: r.verdict,
            message: format!(
                "stepladder: `{}` on `{}`: {} force-evaluation claim: {}",
                r.scheme,
                r.scene,
                r.verdict.name(),
                r.reason
            ),
        }
    }
}

impl ToleranceLadderRecord {
    /// Every claim of the adaptive integrator, in the order of
    /// [`AdaptiveClaim`]'s variants; a claim it does not make (an error
    /// factor it does not state, evaluations it does not report) is
    /// [`Verdict::NotClaimed`].
    pub fn verdicts(&self) -> Vec<ClaimVerdict> {
        AdaptiveClaim::ALL
            .iter()
            .map(|&claim| match self.claim(claim) {
                Some(judged) => ClaimVerdict {
                    claim: claim.name(),
                    verdict: judged.verdict,
                    message: format!(
                        "stepladder: adaptive `{}` on `{}`: {} {}: {} (ladder: {})",
                        self.integrator,
                        self.scene,
                        claim.name(),
                        judged.verdict.name(),
                        judged.reason,
                        self.ladder_points()
                    ),
                },
                None => ClaimVerdict {
                    claim: claim.name(),
                    verdict: Verdict::NotClaimed,
                    message: format!(
                        "stepladder: adaptive `{}` on `{}`: {} not claimed",
                        self.integrator,
                        self.scene,
                        claim.name()
                    ),
                },
            })
            .collect()
    }

    /// No claim fails its guard.
    pub fn passed(&self) -> bool {
        self.verdicts().iter().all(|v| !v.verdict.fails_a_guard())
    }

    /// Each tolerance's steps and error, for a message.
    fn ladder_points(&self) -> String {
        self.points
            .iter()
            .map(|p| {
                format!(
                    "TOL {:.0e}: {} steps, error {}",
                    p.tolerance,
                    p.accepted,
                    p.error.map_or("-".into(), |e| format!("{e:.2e}"))
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    }
}
