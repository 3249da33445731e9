//! The tolerance ladders of the suite: the catalogue's own adaptive pair
//! against its controller's theory, the peer measured alike.

use stepladder::measure::Verdict;
use stepladder::measure::adaptive::RunEnd;
use stepladder::measure::geometry::energy::EnergyClass;

/// DPRKN6(4) with local extrapolation: error ~ TOL^(6/5) on both orbits,
/// its energy drifting and its round trip missing the start, as a
/// non-symplectic, non-symmetric method's must.
#[test]
fn the_own_pair_is_tolerance_proportional_with_exponent_six_fifths_on_the_orbits() {
    let ladders = &super::common::suite().adaptive.ladders;
    for scene in ["kepler-circular", "kepler-eccentric"] {
        let r = ladders
            .iter()
            .find(|r| r.integrator == "DPRKN6(4) adaptive" && r.scene == scene)
            .expect("the own pair on every scene");
        let p = r.proportionality.expect("an exponent");
        assert_eq!(p.theory, Some(1.2));
        assert!(p.agrees(), "{scene}: {}", r.reason);
        assert_eq!(r.verdict, Verdict::Pass, "{scene}: {}", r.reason);
        assert_eq!(
            r.energy.unwrap().class,
            Some(EnergyClass::Drifting),
            "{scene}"
        );
        assert!(!r.round_trip.unwrap().returns, "{scene}");
    }
}

/// Every ladder runs every tolerance to its end, and tighter tolerances
/// never cost fewer evaluations.
#[test]
fn every_ladder_reaches_t_end_and_costs_more_as_the_tolerance_tightens() {
    let ladders = &super::common::suite().adaptive.ladders;
    assert_eq!(ladders.len(), 8);
    for r in ladders {
        assert!(
            r.points.iter().all(|p| p.end == RunEnd::Reached),
            "{} {}",
            r.integrator,
            r.scene
        );
        assert!(
            r.points
                .windows(2)
                .all(|w| w[1].evaluations >= w[0].evaluations),
            "{} {}",
            r.integrator,
            r.scene
        );
    }
}
