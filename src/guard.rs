//! One-line guards for a downstream crate's tests: measure a scheme's claims
//! on a scene and panic, with the figures that decided it, if one fails.
//!
//! ```
//! use stepladder::guard;
//! use stepladder::scene::KeplerCircular;
//! use stepladder::scheme::VELOCITY_VERLET;
//!
//! // order, symplecticity, reversibility and energy, each against its claim
//! guard::assert_claims(&VELOCITY_VERLET, &KeplerCircular);
//! ```
//!
//! Each guard returns the study's record, so a test can also pin it with
//! insta in its own snapshot folder.

use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::study::accuracy::order::{OrderRecord, OrderSpec, global_order};
use crate::study::accuracy::pin::{PinOutcome, check_pin};
use crate::study::adaptive::{ToleranceLadderRecord, ToleranceLadderSpec, tolerance_ladder};
use crate::study::cost::evaluations::{EvaluationRecord, counting_step, evaluations};
use crate::study::geometry::energy::{EnergyRecord, EnergySpec, energy_drift};
use crate::study::geometry::reverse::{ReverseRecord, ReverseSpec, reversibility};
use crate::study::geometry::symplectic::{SymplecticRecord, SymplecticSpec, symplecticity};
use crate::study::verdict::Verdict;

/// Measures the global order with the automatic ladder; panics unless it
/// agrees with `scheme.meta().order`.
pub fn assert_order<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) -> OrderRecord {
    let record = study(global_order(scheme, scene, &OrderSpec::default()));
    if let Some(message) = order_failure(&record) {
        panic!("{message}");
    }
    record
}

/// Takes the exact tangent map of a step; panics unless the measured
/// symplecticity agrees with `scheme.meta().symplectic`.
pub fn assert_symplectic<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> SymplecticRecord {
    let record = study(symplecticity(scheme, scene, &SymplecticSpec::default()));
    if let Some(message) = symplectic_failure(&record) {
        panic!("{message}");
    }
    record
}

/// Runs forward and back; panics unless the measured time symmetry agrees
/// with `scheme.meta().symmetric`.
pub fn assert_reversible<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> ReverseRecord {
    let record = study(reversibility(scheme, scene, &ReverseSpec::default()));
    if let Some(message) = reverse_failure(&record) {
        panic!("{message}");
    }
    record
}

/// Runs for 10^4 periods; panics unless the energy behaves as the scheme's
/// claims imply (bounded if symplectic, drifting otherwise).
pub fn assert_energy<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> EnergyRecord {
    let record = study(energy_drift(scheme, scene, &EnergySpec::default()));
    if let Some(message) = energy_failure(&record) {
        panic!("{message}");
    }
    record
}

/// Counts the force calls a step makes; panics unless they equal
/// `scheme.meta().force_evaluations` per step (an implicit scheme's count
/// is checked against what its solves report, and an implicit black box's
/// is shown, not judged: its iterations are its own).
pub fn assert_evaluations<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> EvaluationRecord {
    let record = evaluations(scheme, scene, counting_step(scene));
    if let Some(message) = evaluation_refuted(&record) {
        panic!("{message}");
    }
    record
}

/// Runs the tolerance ladder of an adaptive integrator (see
/// [`crate::study::tolerance_ladder()`]): the global error must
/// follow the tolerance with the exponent its controller's theory predicts,
/// the accepted steps grow no faster than that controller allows, what it
/// reports it spent equal the calls counted on its force callback, and
/// energy and round trip agree with its symplecticity and symmetry claims.
/// Panics with the figures unless every claim holds.
pub fn assert_adaptive<I, S, const D: usize>(integrator: &I, scene: &S) -> ToleranceLadderRecord
where
    I: crate::study::adaptive::AdaptiveIntegrator,
    S: Scene<D>,
{
    let record = adaptive_ladder(integrator, scene);
    if record.verdict != Verdict::Pass {
        panic!(
            "stepladder: adaptive `{}` on `{}`: {} ({}): {}",
            record.integrator,
            record.scene,
            record.verdict.name(),
            ladder_points(&record),
            record.reason
        );
    }
    record
}

/// Panics unless `claim` holds in an adaptive integrator's tolerance ladder
/// (`record`, from [`adaptive_ladder`]): the failure names the claim, its
/// figures and the ladder's points. A claim with nothing to judge (an error
/// factor not stated, evaluations not reported) holds.
pub fn assert_adaptive_claim(
    record: &ToleranceLadderRecord,
    claim: crate::study::adaptive::AdaptiveClaim,
) {
    let Some(judged) = record.claim(claim) else {
        return;
    };
    if judged.verdict != Verdict::Pass {
        panic!(
            "stepladder: adaptive `{}` on `{}`: {} {}: {} (ladder: {})",
            record.integrator,
            record.scene,
            claim.name(),
            judged.verdict.name(),
            judged.reason,
            ladder_points(record)
        );
    }
}

/// The tolerance ladder [`assert_adaptive`] and [`guard_adaptive!`](crate::guard_adaptive!) judge,
/// with the default spec; panics if it cannot run.
pub fn adaptive_ladder<I, S, const D: usize>(integrator: &I, scene: &S) -> ToleranceLadderRecord
where
    I: crate::study::adaptive::AdaptiveIntegrator,
    S: Scene<D>,
{
    study(tolerance_ladder(
        integrator,
        scene,
        &ToleranceLadderSpec::default(),
    ))
}

/// Each tolerance's steps and error, for a failure message.
fn ladder_points(record: &ToleranceLadderRecord) -> String {
    record
        .points
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

/// Checks an adaptive integrator's error at its pinned tolerance against
/// the pin in `dir` (see [`crate::study::adaptive::pin`]), writing it if
/// it is missing; panics if the error moved by more than the pin allows.
pub fn assert_adaptive_pinned<I, S, const D: usize>(
    integrator: &I,
    scene: &S,
    record: &ToleranceLadderRecord,
    dir: impl AsRef<std::path::Path>,
) -> crate::study::adaptive::AdaptivePinOutcome
where
    I: crate::study::adaptive::AdaptiveIntegrator,
    S: Scene<D>,
{
    crate::study::adaptive::check_adaptive_pin(integrator, scene, record, dir.as_ref())
        .unwrap_or_else(|message| panic!("{message}"))
}

/// Checks the error at the pinned step against the pin in `dir` (see
/// [`crate::study::accuracy::pin`]), writing the pin if it is missing;
/// panics if the error moved by more than the pin's tolerance (four times
/// the round-off the order study measured on that run, so a changed scheme
/// fails and a reordering of its operations or another platform does not),
/// if the pin is of an earlier format, or if the order study does not pass.
pub fn assert_pinned<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    dir: impl AsRef<std::path::Path>,
) -> PinOutcome {
    check_pin(scheme, scene, dir.as_ref()).unwrap_or_else(|message| panic!("{message}"))
}

/// Every guard above; panics once, listing every claim that failed.
pub fn assert_claims<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) {
    let failures: Vec<String> = [
        order_failure(&study(global_order(scheme, scene, &OrderSpec::default()))),
        symplectic_failure(&study(symplecticity(
            scheme,
            scene,
            &SymplecticSpec::default(),
        ))),
        reverse_failure(&study(reversibility(
            scheme,
            scene,
            &ReverseSpec::default(),
        ))),
        energy_failure(&study(energy_drift(scheme, scene, &EnergySpec::default()))),
        evaluation_refuted(&evaluations(scheme, scene, counting_step(scene))),
    ]
    .into_iter()
    .flatten()
    .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A study that could not even run is a failure of the guard's setup.
fn study<T>(result: Result<T, crate::error::Error>) -> T {
    result.unwrap_or_else(|e| panic!("stepladder: the study could not run: {e}"))
}

/// The failure message of an order record, or `None` if it passed.
pub fn order_failure(r: &OrderRecord) -> Option<String> {
    use crate::wording::{figure, order};
    (r.verdict != Verdict::Pass).then(|| {
        let ladder = match (r.rungs.first(), r.rungs.last()) {
            (Some(a), Some(b)) => {
                format!("{} rungs, h = {} .. {}", r.rungs.len(), figure(a.h), figure(b.h))
            }
            _ => "no rungs".to_string(),
        };
        format!(
            "stepladder: `{}` on `{}`: {} order {} claimed, measured {} in {} over rungs {}; ladder {ladder} to t_end = {}: {}{}",
            r.scheme,
            r.scene,
            r.verdict.name(),
            r.theoretical_order,
            r.measured_order.map_or("nothing".into(), order),
            r.ci95.map_or("no interval".into(), |c| format!("[{}, {}]", order(c[0]), order(c[1]))),
            r.window.map_or("none".into(), |[a, b]| format!("{a}..{b}")),
            figure(r.t_end),
            r.reason,
            r.advice.as_ref().map_or(String::new(), |a| format!("; to decide: {a}"))
        ) + &solves_beside_errors(&r.rungs)
    })
}

/// For a scheme that reports its solves: the iterations per step and the
/// largest residual beside the error at the coarsest and the finest rungs
/// measured, so that a floor set by the solve's own tolerance shows where
/// it comes from. Empty for a scheme that reports none.
fn solves_beside_errors(rungs: &[crate::study::accuracy::rung::Rung]) -> String {
    use crate::wording::figure;
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

/// The failure message of a symplecticity record, or `None` if it passed.
pub fn symplectic_failure(r: &SymplecticRecord) -> Option<String> {
    (r.verdict != Verdict::Pass).then(|| {
        format!(
            "stepladder: `{}` on `{}`: symplectic claimed {}, {}: {}",
            r.scheme,
            r.scene,
            r.claimed,
            r.verdict.name(),
            r.reason,
        )
    })
}

/// The failure message of a reversibility record, or `None` if it passed.
pub fn reverse_failure(r: &ReverseRecord) -> Option<String> {
    (r.verdict != Verdict::Pass).then(|| {
        format!(
            "stepladder: `{}` on `{}`: time-symmetric claimed {}, {}: {} steps of h = {} and back: {}",
            r.scheme,
            r.scene,
            r.claimed,
            r.verdict.name(),
            r.steps,
            crate::wording::figure(r.h),
            r.reason
        )
    })
}

/// The failure message of an energy record, or `None` if it passed.
pub fn energy_failure(r: &EnergyRecord) -> Option<String> {
    (r.verdict != Verdict::Pass).then(|| {
        format!(
            "stepladder: `{}` on `{}`: energy expected {}, {} over {} steps of h = {}: {}",
            r.scheme,
            r.scene,
            r.expected.name(),
            r.verdict.name(),
            r.steps,
            crate::wording::figure(r.h),
            r.reason
        )
    })
}

/// The failure message of an evaluation count, or `None` if it passed.
pub fn evaluation_failure(r: &EvaluationRecord) -> Option<String> {
    (r.verdict != Verdict::Pass).then(|| {
        format!(
            "stepladder: `{}` on `{}`: {} force-evaluation claim: {}",
            r.scheme,
            r.scene,
            r.verdict.name(),
            r.reason
        )
    })
}

/// The message of a refuted evaluation count: the guards fail on it alone,
/// since an implicit black box's count is inconclusive by construction (its
/// iterations are its own).
fn evaluation_refuted(r: &EvaluationRecord) -> Option<String> {
    evaluation_failure(r).filter(|_| r.verdict == Verdict::Fail)
}

/// One `#[test]` per claim, per scheme and scene: `order`, `symplectic`,
/// `reversible`, `energy`, `evaluations` and `pinned` (the error at a coarse step, pinned
/// to its round-off in `snapshots/stepladder/` under the calling crate's
/// root), in modules named
/// after the scheme and the scene, so that `cargo test` lists
/// `my_verlet::kepler_circular::order` and a failure names its claim.
///
/// Each line is `module_name: scheme_expression => { scene_module:
/// scene_expression, ... }`; the expressions are evaluated in the calling
/// module's scope.
///
/// ```
/// # mod doc {
/// use stepladder::scene::{Harmonic, KeplerCircular};
/// use stepladder::scheme::{Rk4, VELOCITY_VERLET};
///
/// stepladder::guard_claims! {
///     velocity_verlet: VELOCITY_VERLET => {
///         kepler_circular: KeplerCircular,
///         harmonic: Harmonic::default(),
///     }
///     rk4: Rk4 => { harmonic: Harmonic::default() }
/// }
/// # }
/// ```
#[macro_export]
macro_rules! guard_claims {
    ($($scheme_module:ident : $scheme:expr => { $($scene_module:ident : $scene:expr),* $(,)? })*) => {
        $(
            mod $scheme_module {
                #[allow(unused_imports)]
                use super::*;
                $(
                    mod $scene_module {
                        #[allow(unused_imports)]
                        use super::*;

                        #[test]
                        fn order() {
                            $crate::guard::assert_order(&$scheme, &$scene);
                        }

                        #[test]
                        fn symplectic() {
                            $crate::guard::assert_symplectic(&$scheme, &$scene);
                        }

                        #[test]
                        fn reversible() {
                            $crate::guard::assert_reversible(&$scheme, &$scene);
                        }

                        #[test]
                        fn energy() {
                            $crate::guard::assert_energy(&$scheme, &$scene);
                        }

                        #[test]
                        fn evaluations() {
                            $crate::guard::assert_evaluations(&$scheme, &$scene);
                        }

                        #[test]
                        fn pinned() {
                            $crate::guard::assert_pinned(
                                &$scheme,
                                &$scene,
                                ::std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                                    .join("snapshots")
                                    .join("stepladder"),
                            );
                        }
                    }
                )*
            }
        )*
    };
}

/// One `#[test]` per adaptive integrator, scene and claim, named after all
/// three (`dprkn6::kepler_eccentric::exponent`), as [`guard_claims!`] does
/// for a fixed-step scheme: `exponent` (the global error follows
/// `TOL^(p/(q+1))`), `error_factor` (within the stated factor of the
/// tolerance, where one is stated with [`crate::study::adaptive::AdaptiveClaims::within`]),
/// `cost` (the accepted steps grow no faster than the controller allows),
/// `evaluations` (what it reports it spent equals the calls counted),
/// `energy` and `round_trip` (against the geometric claims) and `pinned`
/// (the error at one tolerance against the pin committed in
/// `snapshots/stepladder/`). The claims of one scene share one tolerance
/// ladder, run once by whichever of its tests comes first.
///
/// ```
/// # mod doc {
/// use stepladder::study::adaptive::DPRKN6_ADAPTIVE;
/// use stepladder::scene::KeplerEccentric;
///
/// stepladder::guard_adaptive! {
///     dprkn6: DPRKN6_ADAPTIVE => { kepler_eccentric: KeplerEccentric::default() }
/// }
/// # }
/// ```
#[macro_export]
macro_rules! guard_adaptive {
    ($($module:ident : $integrator:expr => { $($scene_module:ident : $scene:expr),* $(,)? })*) => {
        $(
            mod $module {
                #[allow(unused_imports)]
                use super::*;
                $(
                    mod $scene_module {
                        #[allow(unused_imports)]
                        use super::*;
                        use $crate::study::adaptive::AdaptiveClaim;

                        fn ladder() -> &'static $crate::study::adaptive::ToleranceLadderRecord {
                            static LADDER: ::std::sync::OnceLock<
                                $crate::study::adaptive::ToleranceLadderRecord,
                            > = ::std::sync::OnceLock::new();
                            LADDER.get_or_init(|| $crate::guard::adaptive_ladder(&$integrator, &$scene))
                        }

                        #[test]
                        fn exponent() {
                            $crate::guard::assert_adaptive_claim(ladder(), AdaptiveClaim::Exponent);
                        }

                        #[test]
                        fn error_factor() {
                            $crate::guard::assert_adaptive_claim(ladder(), AdaptiveClaim::ErrorFactor);
                        }

                        #[test]
                        fn cost() {
                            $crate::guard::assert_adaptive_claim(ladder(), AdaptiveClaim::Cost);
                        }

                        #[test]
                        fn evaluations() {
                            $crate::guard::assert_adaptive_claim(ladder(), AdaptiveClaim::Evaluations);
                        }

                        #[test]
                        fn energy() {
                            $crate::guard::assert_adaptive_claim(ladder(), AdaptiveClaim::Energy);
                        }

                        #[test]
                        fn round_trip() {
                            $crate::guard::assert_adaptive_claim(ladder(), AdaptiveClaim::RoundTrip);
                        }

                        #[test]
                        fn pinned() {
                            $crate::guard::assert_adaptive_pinned(
                                &$integrator,
                                &$scene,
                                ladder(),
                                ::std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                                    .join("snapshots")
                                    .join("stepladder"),
                            );
                        }
                    }
                )*
            }
        )*
    };
}
