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
use crate::study::{ClaimVerdict, ClaimsRecord, claims};

/// Panics with the claim's message if its verdict fails a guard: a
/// refutation or an inconclusive measurement, never a claim not made (the
/// rule and its argument: [`crate::study::Verdict::fails_a_guard`]).
fn hold(verdict: ClaimVerdict) {
    if let Some(message) = verdict.failure() {
        panic!("{message}");
    }
}

/// Measures the global order with the automatic ladder; panics unless it
/// agrees with `scheme.meta().order`.
pub fn assert_order<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) -> OrderRecord {
    let record = study(global_order(scheme, scene, &OrderSpec::default()));
    hold((&record).into());
    record
}

/// Takes the exact tangent map of a step; panics unless the measured
/// symplecticity agrees with `scheme.meta().symplectic`.
pub fn assert_symplectic<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> SymplecticRecord {
    let record = study(symplecticity(scheme, scene, &SymplecticSpec::default()));
    hold((&record).into());
    record
}

/// Runs forward and back; panics unless the measured time symmetry agrees
/// with `scheme.meta().symmetric`.
pub fn assert_reversible<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> ReverseRecord {
    let record = study(reversibility(scheme, scene, &ReverseSpec::default()));
    hold((&record).into());
    record
}

/// Runs for 10^4 periods; panics unless the energy behaves as the scheme's
/// claims imply (bounded if symplectic, drifting otherwise).
pub fn assert_energy<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> EnergyRecord {
    let record = study(energy_drift(scheme, scene, &EnergySpec::default()));
    hold((&record).into());
    record
}

/// Counts the force calls a step makes; panics unless they equal
/// `scheme.meta().force_evaluations` per step (an implicit scheme's count
/// is checked against what its solves report; an implicit black box that
/// reports none makes no count to check, and is shown, not judged).
pub fn assert_evaluations<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> EvaluationRecord {
    let record = evaluations(scheme, scene, counting_step(scene));
    hold((&record).into());
    record
}

/// Runs the tolerance ladder of an adaptive integrator (see
/// [`crate::study::tolerance_ladder()`]): the global error must
/// follow the tolerance with the exponent its controller's theory predicts,
/// the accepted steps grow no faster than that controller allows, what it
/// reports it spent equal the calls counted on its force callback, and
/// energy and round trip agree with its symplecticity and symmetry claims.
/// Panics with the figures unless every claim holds
/// ([`ToleranceLadderRecord::verdicts`]).
pub fn assert_adaptive<I, S, const D: usize>(integrator: &I, scene: &S) -> ToleranceLadderRecord
where
    I: crate::scheme::AdaptiveIntegrator,
    S: Scene<D>,
{
    let record = adaptive_ladder(integrator, scene);
    let verdicts = record.verdicts();
    let failures: Vec<&str> = verdicts.iter().filter_map(ClaimVerdict::failure).collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    record
}

/// Panics unless `claim` holds in an adaptive integrator's tolerance ladder
/// (`record`, from [`adaptive_ladder`]): the failure names the claim, its
/// figures and the ladder's points. A claim the integrator does not make
/// (an error factor not stated, evaluations not reported) holds.
pub fn assert_adaptive_claim(record: &ToleranceLadderRecord, claim: crate::study::AdaptiveClaim) {
    let verdicts = record.verdicts();
    let position = crate::study::AdaptiveClaim::ALL
        .iter()
        .position(|&c| c == claim)
        .expect("every claim is in ALL");
    hold(verdicts[position].clone());
}

/// The tolerance ladder [`assert_adaptive`] and [`guard_adaptive!`](crate::guard_adaptive!) judge,
/// with the default spec; panics if it cannot run.
pub fn adaptive_ladder<I, S, const D: usize>(integrator: &I, scene: &S) -> ToleranceLadderRecord
where
    I: crate::scheme::AdaptiveIntegrator,
    S: Scene<D>,
{
    study(tolerance_ladder(
        integrator,
        scene,
        &ToleranceLadderSpec::default(),
    ))
}

/// Checks an adaptive integrator's error at its pinned tolerance against
/// the pin in `dir` (see [`crate::study::adaptive::pin`]), writing it if
/// it is missing; panics if the error moved by more than the pin allows.
pub fn assert_adaptive_pinned<I, S, const D: usize>(
    integrator: &I,
    scene: &S,
    record: &ToleranceLadderRecord,
    dir: impl AsRef<std::path::Path>,
) -> crate::study::AdaptivePinOutcome
where
    I: crate::scheme::AdaptiveIntegrator,
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

/// Every claim at once ([`crate::study::claims()`]); panics once, listing
/// every claim that fails its guard, and otherwise returns the record.
pub fn assert_claims<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
) -> ClaimsRecord {
    let record = study(claims(scheme, scene));
    assert!(record.passed(), "{}", record.failures().join("\n"));
    record
}

/// A study that could not even run is a failure of the guard's setup.
fn study<T>(result: Result<T, crate::error::Error>) -> T {
    result.unwrap_or_else(|e| panic!("stepladder: the study could not run: {e}"))
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
/// tolerance, where one is stated with [`crate::scheme::AdaptiveClaims::within`]),
/// `cost` (the accepted steps grow no faster than the controller allows),
/// `evaluations` (what it reports it spent equals the calls counted),
/// `energy` and `round_trip` (against the geometric claims) and `pinned`
/// (the error at one tolerance against the pin committed in
/// `snapshots/stepladder/`). The claims of one scene share one tolerance
/// ladder, run once by whichever of its tests comes first.
///
/// ```
/// # mod doc {
/// use stepladder::scheme::DPRKN6_ADAPTIVE;
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
