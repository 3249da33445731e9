//! "Round-off optimal" on the outer solar system over a million steps: the
//! compensated DPRKN8 passes, the plain one fails, and a compensated
//! composition whose weights do not sum to one in doubles is not passed.

use stepladder::internals::round_off::brouwer::RANDOM_WALK_BAND;
use stepladder::internals::verdict::Verdict;
use stepladder::scene::OuterSolarSystem;
use stepladder::scheme::{Compensated, DPRKN8, KAHAN_LI8};
use stepladder::study::{RoundOffSpec, round_off_growth};

/// With compensated sums DPRKN8's energy error is a random walk some
/// `h w = 2 pi/2000` times smaller than one rounding of the coordinates a
/// step; plain, it is a random walk too (rounding to nearest is unbiased),
/// but above that floor, and the claim fails on the floor, not the exponent.
#[test]
fn compensated_dprkn8_is_round_off_optimal_and_plain_is_not() {
    let scene = OuterSolarSystem::new();
    let spec = RoundOffSpec::default();
    let compensated = Compensated {
        meta: DPRKN8.meta,
        plain: DPRKN8,
    };
    let c = round_off_growth(&compensated, &scene, &spec).unwrap();
    assert_eq!(c.verdict, Verdict::Pass, "{}", c.reason);
    let p = round_off_growth(&DPRKN8, &scene, &spec).unwrap();
    assert_eq!(p.verdict, Verdict::Fail, "{}", p.reason);
    assert!(p.per_step > p.rounding_floor, "{p:?}");
    let [a, b] = p.ci95.unwrap();
    assert!(
        a < RANDOM_WALK_BAND[1] && b > RANDOM_WALK_BAND[0],
        "plain DPRKN8's error walks too: [{a}, {b}]"
    );
}

/// Kahan and Li's composition, compensated, is symplectic whatever its
/// weights, but its 17 drift weights sum to `1 - 1.1e-16` in doubles and
/// its kicks to `1 - 1.4e-16`: it conserves `(1 + d) T + (1 + k) V`, not the
/// energy, which therefore swings by about `1e-16` of the kinetic energy's
/// variation along the orbits, some `1e-17` of the energy. That is as large
/// as its compensated walk at the shortest lag, so the variogram's bottom
/// is flat and the claim is not passed, though the walk is below the floor.
#[test]
fn a_compensated_composition_with_rounded_weights_is_not_passed() {
    let scene = OuterSolarSystem::new();
    let compensated = Compensated {
        meta: KAHAN_LI8.meta,
        plain: KAHAN_LI8,
    };
    let r = round_off_growth(&compensated, &scene, &RoundOffSpec::default()).unwrap();
    assert_ne!(r.verdict, Verdict::Pass, "{}", r.reason);
    assert!(r.per_step < r.rounding_floor, "{r:?}");
    let [a, _] = r.ci95.unwrap();
    assert!(a < RANDOM_WALK_BAND[0], "{}", r.reason);
}
