//! Linear stability against its analytic values, and runs above the limit
//! that must end early with a clear verdict.

use stepladder::measure::accuracy::phase::one_step_matrix;
use stepladder::measure::geometry::energy::{EnergySpec, energy_drift};
use stepladder::measure::stability::{StabilityRecord, spectral_radius, stability};
use stepladder::run::Outcome;
use stepladder::scene::Harmonic;
use stepladder::scheme::{Scheme, SchemeVisitor, VELOCITY_VERLET, scheme_ids, visit_scheme};

struct Stability;
impl SchemeVisitor for Stability {
    type Output = StabilityRecord;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> StabilityRecord {
        stability(scheme)
    }
}

fn limit(id: &str) -> StabilityRecord {
    visit_scheme(id, Stability).unwrap()
}

/// Every scheme whose one-step map on the oscillator has determinant 1 and
/// trace `2 - z^2` (the Verlet family and Euler-Cromer) is stable exactly
/// while `|2 - z^2| < 2`, that is for `z < 2`.
#[test]
fn verlet_family_and_euler_cromer_are_stable_up_to_two() {
    for id in [
        "euler-cromer",
        "stormer-verlet",
        "leapfrog",
        "velocity-verlet",
        "position-verlet",
    ] {
        let r = limit(id);
        let z = r.stability_limit.expect("a finite limit");
        assert!((z - 2.0).abs() < 1e-9, "{id}: {z}");
        assert_eq!(
            r.stable_intervals.len(),
            1,
            "{id}: {:?}",
            r.stable_intervals
        );
    }
}

/// Explicit Euler's eigenvalues `1 -+ i z` have modulus `sqrt(1 + z^2) > 1`
/// for every `z > 0`: stable for no step.
#[test]
fn explicit_euler_is_stable_for_no_step() {
    let r = limit("euler");
    assert_eq!(r.stability_limit, Some(0.0));
    assert!(r.stable_intervals.is_empty());
}

/// RK4: `|R(iz)|^2 = 1 - z^6/72 + z^8/576 <= 1` exactly while `z^2 <= 8`.
#[test]
fn rk4_is_stable_up_to_two_root_two() {
    let r = limit("rk4");
    let z = r.stability_limit.expect("a finite limit");
    assert!((z - 8f64.sqrt()).abs() < 1e-9, "{z}");
    assert!((r.limit_per_force_evaluation.unwrap() - 8f64.sqrt() / 4.0).abs() < 1e-9);
}

/// The implicit midpoint rule's eigenvalues `(1 + iz/2)/(1 - iz/2)` have
/// modulus one for every `z`: stable for every step, reported as no limit.
#[test]
fn implicit_midpoint_is_stable_for_every_step() {
    let r = limit("implicit-midpoint");
    assert_eq!(r.stability_limit, None, "{r:?}");
    assert_eq!(r.stable_intervals, vec![[Some(0.0), None]]);
}

/// Every gap between two stable intervals is a real instability, not
/// round-off splitting one interval: somewhere inside it the spectral radius
/// exceeds 1 by far more than the `1e-13` a many-stage map's rounding gives.
struct Gaps;
impl SchemeVisitor for Gaps {
    type Output = Vec<String>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Vec<String> {
        let r = stability(scheme);
        r.stable_intervals
            .windows(2)
            .filter_map(|w| {
                let (b, c) = (
                    w[0][1].expect("a closed interval"),
                    w[1][0].expect("a start"),
                );
                let worst = (1..16)
                    .map(|k| b + (c - b) * k as f64 / 16.0)
                    .filter_map(|z| one_step_matrix(scheme, z).map(|m| spectral_radius(&m)))
                    .fold(0.0, f64::max);
                (worst < 1.0 + 1e-8)
                    .then(|| format!("{}: gap ({b}, {c}) peaks at radius {worst}", r.scheme))
            })
            .collect()
    }
}

#[test]
fn gaps_between_stable_intervals_are_real_instabilities() {
    let spurious: Vec<String> = scheme_ids()
        .into_iter()
        .flat_map(|id| visit_scheme(id, Gaps).unwrap())
        .collect();
    assert!(spurious.is_empty(), "{spurious:#?}");
}

/// `h w0 = 2.5` is beyond velocity Verlet's limit 2: the run must stop as
/// soon as the state leaves the bound, and say so.
#[test]
fn a_stiff_oscillator_above_the_limit_ends_early_with_a_clear_verdict() {
    let stiff = Harmonic::new(50.0, 1.0, 0.0).unwrap();
    let r = energy_drift(
        &VELOCITY_VERLET,
        &stiff,
        &EnergySpec {
            h: Some(0.05),
            periods: None,
        },
    )
    .unwrap();
    let Outcome::Unstable { h, step, .. } = r.outcome else {
        panic!("{:?}", r.outcome)
    };
    assert_eq!(h, 0.05);
    // the larger eigenvalue is 2.67 in modulus (2.5^2/2 - 1 + sqrt(...)): the
    // state grows by 1e6 within about 15 steps
    assert!(step < 30, "stopped only after {step} steps");
    assert!(
        r.reason.starts_with("unstable at h = 0.05, after"),
        "{}",
        r.reason
    );
}
