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

use crate::measure::Verdict;
use crate::measure::accuracy::order::{OrderRecord, OrderSpec, global_order};
use crate::measure::accuracy::pin::{PinOutcome, check_pin};
use crate::measure::geometry::energy::{EnergyRecord, EnergySpec, energy_drift};
use crate::measure::geometry::reverse::{ReverseRecord, ReverseSpec, reversibility};
use crate::measure::geometry::symplectic::{SymplecticRecord, SymplecticSpec, symplecticity};
use crate::scene::Scene;
use crate::scheme::Scheme;

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

/// Checks the error at the pinned step against the pin in `dir` (see
/// [`crate::measure::accuracy::pin`]), writing the pin if it is missing;
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
    (r.verdict != Verdict::Pass).then(|| {
        let ladder = match (r.rungs.first(), r.rungs.last()) {
            (Some(a), Some(b)) => format!("{} rungs, h = {:.3e} .. {:.3e}", r.rungs.len(), a.h, b.h),
            _ => "no rungs".to_string(),
        };
        format!(
            "stepladder: `{}` on `{}`: {} order {} claimed, measured {} in {} over rungs {}; ladder {ladder} to t_end = {}: {}{}",
            r.scheme,
            r.scene,
            r.verdict.name(),
            r.theoretical_order,
            r.measured_order.map_or("nothing".into(), |p| format!("{p:.4}")),
            r.ci95.map_or("no interval".into(), |c| format!("[{:.4}, {:.4}]", c[0], c[1])),
            r.window.map_or("none".into(), |[a, b]| format!("{a}..{b}")),
            r.t_end,
            r.reason,
            r.advice.as_ref().map_or(String::new(), |a| format!("; to decide: {a}"))
        )
    })
}

/// The failure message of a symplecticity record, or `None` if it passed.
pub fn symplectic_failure(r: &SymplecticRecord) -> Option<String> {
    (r.verdict != Verdict::Pass).then(|| {
        format!(
            "stepladder: `{}` on `{}`: symplectic claimed {}, measured residual {:.3e} (tolerance {:e}), det(J) - 1 = {:.3e} over {} samples: {}",
            r.scheme,
            r.scene,
            r.claimed,
            r.symplectic_residual,
            r.tolerance,
            r.det_minus_one,
            r.samples.len(),
            r.reason
        )
    })
}

/// The failure message of a reversibility record, or `None` if it passed.
pub fn reverse_failure(r: &ReverseRecord) -> Option<String> {
    (r.verdict != Verdict::Pass).then(|| {
        format!(
            "stepladder: `{}` on `{}`: time-symmetric claimed {}, {} steps of h = {} and back return within {} ulps (tolerance {:.3e}): {}",
            r.scheme,
            r.scene,
            r.claimed,
            r.steps,
            r.h,
            r.return_ulps.map_or("-".into(), |u| format!("{u:.3e}")),
            r.tolerance_ulps,
            r.reason
        )
    })
}

/// The failure message of an energy record, or `None` if it passed.
pub fn energy_failure(r: &EnergyRecord) -> Option<String> {
    (r.verdict != Verdict::Pass).then(|| {
        format!(
            "stepladder: `{}` on `{}`: energy expected {}, measured {} (growth exponent {}, max relative error {:.3e}) over {} steps of h = {}: {}",
            r.scheme,
            r.scene,
            r.expected.name(),
            r.class.map_or("-", |c| c.name()),
            r.growth_exponent.map_or("-".into(), |g| format!("{g:.3}")),
            r.max_relative_energy_error,
            r.steps,
            r.h,
            r.reason
        )
    })
}

/// One `#[test]` per claim, per scheme and scene: `order`, `symplectic`,
/// `reversible`, `energy` and `pinned` (the error at a coarse step, pinned
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
