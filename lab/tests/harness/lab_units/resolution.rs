//! What a passing tolerance-ladder exponent tells: whether its interval
//! also holds the claim of a controller one estimate power away, and the
//! slipped controller's claim.

use stepladder::scheme::AdaptiveIntegrator;
use stepladder_lab::report::holds_a_neighbour;
use stepladder_lab::suite::adaptive::SLIPPED_PAIR;

/// DPRKN6(4): `p = 6`, `m = 5`; the neighbours' claims are `6/4 = 1.5` and
/// `6/6 = 1`. An interval around `6/5` narrower than the gaps holds
/// neither; one reaching either holds it, the ends included.
#[test]
fn an_interval_holds_a_neighbour_when_it_reaches_p_over_m_plus_or_minus_one() {
    assert!(!holds_a_neighbour(6, 5, [1.152, 1.285]));
    assert!(holds_a_neighbour(6, 5, [0.974, 1.1]));
    assert!(holds_a_neighbour(6, 5, [1.3, 1.5]));
    assert!(holds_a_neighbour(6, 5, [1.0, 1.1]));
    assert!(!holds_a_neighbour(6, 5, [1.001, 1.499]));
    // m = 1 has only the neighbour above, p / 2: no `p / 0 = inf` below,
    // even for an interval open above
    assert!(!holds_a_neighbour(2, 1, [1.5, f64::INFINITY]));
    assert!(holds_a_neighbour(2, 1, [0.9, 1.1]));
}

/// The slipped controller claims what its power implies, `6/4`, and its
/// estimate power, 4; the method is DPRKN6(4)'s.
#[test]
fn the_slipped_pair_claims_six_fourths() {
    let claims = SLIPPED_PAIR.claims();
    assert_eq!(claims.order, 6);
    assert_eq!(claims.estimate_power, 4);
    assert_eq!(claims.proportionality, Some(1.5));
}
