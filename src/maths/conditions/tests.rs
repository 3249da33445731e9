//! The checks against tables whose orders are known, against the same
//! tables with one coefficient off in its 8th significant digit, and against
//! input that makes no table.

use super::*;
use crate::scheme::{
    DPRKN6, DPRKN8, FOREST_RUTH, NYSTROM4, SchemeMeta, VELOCITY_VERLET, VerletComposition,
};

/// `x` moved by one unit in its 8th significant digit.
fn eighth_digit(x: f64) -> f64 {
    x + 10f64.powf(x.abs().log10().floor() - 7.0)
}

/// The degree at which a perturbed table first fails: every condition
/// before it holds, and it is clearly violated.
fn fails_first_at(c: &Conditions, degree: usize) {
    assert_eq!(c.order(), degree - 1, "{c}");
    assert!(c.at(degree).unwrap().clearly_fails(), "{c}");
}

const W1: f64 = 1.351_207_191_959_657_5;
const NEAR_FOREST_RUTH: VerletComposition<3, 4> = {
    let w = W1 + 1e-7;
    VerletComposition::new([w, 1.0 - 2.0 * w, w])
};
const RK4_A: [[f64; 4]; 4] = [
    [0.0, 0.0, 0.0, 0.0],
    [0.5, 0.0, 0.0, 0.0],
    [0.0, 0.5, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
];
const RK4_B: [f64; 4] = [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0];

#[test]
fn correct_tables_have_their_order_and_no_more() {
    let c = splitting(&FOREST_RUTH).unwrap();
    println!(
        "forest-ruth general {}\n            Nystrom {}",
        c.general, c.nystrom
    );
    assert!(c.general.confirms(4) && c.nystrom.confirms(4));
    let c = splitting(&VELOCITY_VERLET).unwrap();
    assert!(c.general.confirms(2) && c.nystrom.confirms(2));
    let c = nystrom(&NYSTROM4).unwrap();
    println!("rkn4-nystrom {}", c.main);
    assert!(c.main.confirms(4));
    let c = runge_kutta(&RK4_A, &RK4_B, 5).unwrap();
    println!("rk4 {}", c.by_degree);
    assert!(c.by_degree.confirms(4));
}

/// The sixth- and eighth-order pairs: the main solutions through `h^6` and
/// `h^8`, the estimates through `h^4` and `h^6`, and the condition beyond
/// each clearly violated (an embedded solution as accurate as the main
/// one would make the estimate useless).
#[test]
fn the_nystrom_pairs_have_their_orders() {
    let c = nystrom(&DPRKN6).unwrap();
    let e = c.embedded.unwrap();
    println!("dprkn6 main {}\n       embedded {e}", c.main);
    assert!(c.main.confirms(6) && e.confirms(4));
    let c = nystrom(&DPRKN8).unwrap();
    let e = c.embedded.unwrap();
    println!("dprkn8 main {}\n       embedded {e}", c.main);
    assert!(c.main.confirms(8) && e.confirms(6));
}

/// Forest-Ruth's weights moved in their 8th digit, palindromic and
/// consistent still: `sum w^3 != 0` makes it second order, in both checks.
#[test]
fn a_composition_weight_off_in_its_eighth_digit_fails_at_h3() {
    let t = NEAR_FOREST_RUTH.table(FOREST_RUTH.meta);
    let c = splitting(&t).unwrap();
    println!(
        "near forest-ruth {}\n                 {}",
        c.general, c.nystrom
    );
    fails_first_at(&c.general, 3);
    fails_first_at(&c.nystrom, 3);
    let r = splitting_step_ratio(&t.sequence(), 4);
    assert!(r.as_ref().map_or(true, |r| !r.holds()), "{r:?}");
}

/// One Nyström weight off in its 8th digit: a velocity weight breaks
/// `sum b = 1` (`h^1`), a position weight `sum b_bar = 1/2` (`h^2`), a node
/// the first condition it enters (`sum b c = 1/2`, `h^2`), a stage
/// coefficient of DPRKN6 its row's sum `c^2/2` (the stage position is off
/// at `h^2`, the new velocity at `h^3`).
#[test]
fn a_nystrom_coefficient_off_in_its_eighth_digit_fails_at_the_right_degree() {
    let mut t = NYSTROM4;
    t.b[1] = eighth_digit(t.b[1]);
    fails_first_at(&nystrom(&t).unwrap().main, 1);
    let mut t = NYSTROM4;
    t.b_bar[0] = eighth_digit(t.b_bar[0]);
    fails_first_at(&nystrom(&t).unwrap().main, 2);
    let mut t = NYSTROM4;
    t.c[1] = eighth_digit(t.c[1]);
    fails_first_at(&nystrom(&t).unwrap().main, 2);
    let mut t = DPRKN6;
    t.a[3][2] = eighth_digit(t.a[3][2]);
    fails_first_at(&nystrom(&t).unwrap().main, 3);
}

/// A Runge-Kutta weight off in its 8th digit breaks the first tree, a
/// matrix entry the tree `[τ]` (`sum b c = 1/2`).
#[test]
fn a_runge_kutta_coefficient_off_in_its_eighth_digit_fails_at_the_right_degree() {
    let mut b = RK4_B;
    b[0] = eighth_digit(b[0]);
    fails_first_at(&runge_kutta(&RK4_A, &b, 5).unwrap().by_degree, 1);
    let mut a = RK4_A;
    a[2][1] = eighth_digit(a[2][1]);
    let c = runge_kutta(&a, &RK4_B, 5).unwrap();
    fails_first_at(&c.by_degree, 2);
    let failing: Vec<&str> = c
        .trees
        .iter()
        .filter(|t| t.defect.degree == 2 && !t.defect.holds())
        .map(|t| t.tree.as_str())
        .collect();
    assert_eq!(failing, ["[τ]"]);
}

/// Refused before any work, with the reason, and never a panic.
#[test]
fn bad_input_is_an_error() {
    let invalid_table = |r: Result<Conditions, Error>| {
        let e = r.unwrap_err();
        assert!(matches!(e, Error::InvalidTable(_)), "{e}");
        println!("{e}");
    };
    let verlet = VELOCITY_VERLET.sequence();
    invalid_table(splitting_general(&[], 2));
    invalid_table(splitting_nystrom(&[], 2));
    invalid_table(splitting_general(&[(Flow::Kick, f64::NAN)], 2));
    invalid_table(splitting_nystrom(
        &[(Flow::Drift, 1.0), (Flow::Kick, f64::INFINITY)],
        2,
    ));
    // finite but overflowing: an infinite allowance would pass anything
    invalid_table(splitting_general(
        &[(Flow::Drift, 1e300), (Flow::Kick, 1e300)],
        3,
    ));
    invalid_table(splitting_nystrom(
        &[(Flow::Drift, 1e300), (Flow::Kick, 1e300)],
        3,
    ));
    for degree in [0, MAX_DEGREE + 1, usize::MAX] {
        let e = splitting_general(&verlet, degree).unwrap_err();
        assert!(
            matches!(e, Error::InvalidParameter { name: "degree", .. }),
            "{e}"
        );
        let e = splitting_nystrom(&verlet, degree).unwrap_err();
        assert!(
            matches!(e, Error::InvalidParameter { name: "degree", .. }),
            "{e}"
        );
        assert!(runge_kutta(&RK4_A, &RK4_B, degree).is_err());
    }
    for degree in [0, NYSTROM_MAX_DEGREE + 1, usize::MAX] {
        let e = nystrom_up_to(&NYSTROM4, degree).unwrap_err();
        assert!(
            matches!(e, Error::InvalidParameter { name: "degree", .. }),
            "{e}"
        );
    }
    assert!(splitting_step_ratio(&verlet, MAX_DEGREE).is_err());
    assert!(splitting_step_ratio(&verlet, usize::MAX).is_err());
    assert!(splitting_step_ratio(&[(Flow::Kick, f64::NAN)], 2).is_err());

    // a claimed order beyond what the checks resolve; weights that do not
    // alternate
    let mut t = FOREST_RUTH;
    t.meta.order = MAX_DEGREE as u32;
    assert!(matches!(splitting(&t), Err(Error::InvalidParameter { .. })));
    let t = SplittingTable::new(
        SchemeMeta::new("x", "x", 2),
        Flow::Drift,
        &[1.0],
        &[0.5, 0.5],
    );
    assert!(matches!(splitting(&t), Err(Error::InvalidTable(_))));

    let mut t = NYSTROM4;
    t.b_bar[2] = f64::NAN;
    assert!(matches!(nystrom(&t), Err(Error::InvalidTable(_))));
    let mut t = DPRKN6;
    t.embedded.as_mut().unwrap().b[5] = f64::NEG_INFINITY;
    assert!(matches!(nystrom(&t), Err(Error::InvalidTable(_))));
    let mut t = NYSTROM4;
    t.a[2][1] = 1e300;
    assert!(matches!(nystrom(&t), Err(Error::InvalidTable(_))));
    let empty = NystromTable::<0> {
        meta: SchemeMeta::new("empty", "empty", 1),
        c: [],
        a: [],
        b_bar: [],
        b: [],
        embedded: None,
    };
    assert!(matches!(nystrom(&empty), Err(Error::InvalidTable(_))));

    let mut b = RK4_B;
    b[3] = f64::NAN;
    assert!(matches!(
        runge_kutta(&RK4_A, &b, 4),
        Err(Error::InvalidTable(_))
    ));
    assert!(matches!(
        runge_kutta::<0>(&[], &[], 4),
        Err(Error::InvalidTable(_))
    ));
    let mut a = RK4_A;
    a[3][2] = 1e300;
    assert!(matches!(
        runge_kutta(&a, &RK4_B, 9),
        Err(Error::InvalidTable(_))
    ));
}

/// A flow with a zero weight is a structural zero: exact, not rounded, and
/// no panic moving it.
#[test]
fn zero_weights_are_exact() {
    let mut flows = VELOCITY_VERLET.sequence();
    flows.push((Flow::Drift, 0.0));
    flows.push((Flow::Kick, -0.0));
    let c = splitting_general(&flows, 3).unwrap();
    assert!(c.confirms(2), "{c}");
}

/// A sequence of flows that all have weight zero is the identity map: its
/// weights round nowhere, so each allowance is the double-double noise
/// alone, still positive, and the identity's `h^1` coefficient misses the
/// flow's `A + B` by far more than that: it is not consistent.
#[test]
fn the_identity_map_is_not_consistent() {
    let flows = [(Flow::Drift, 0.0), (Flow::Kick, 0.0), (Flow::Drift, 0.0)];
    let c = splitting_general(&flows, 2).unwrap();
    let first = c.at(1).unwrap();
    assert!(first.allowance > 0.0, "{c}");
    assert!(first.clearly_fails(), "{c}");
    assert_eq!(c.order(), 0, "{c}");
}

/// The same for a Runge-Kutta tableau: zero weights make `y' = y`, and the
/// first tree, `sum b_i = 1`, fails by 1 against an allowance that is the
/// double-double noise alone, still positive.
#[test]
fn a_tableau_with_zero_weights_is_not_consistent() {
    let c = runge_kutta(&[[0.0, 0.0], [0.5, 0.0]], &[0.0, 0.0], 2).unwrap();
    let first = c.by_degree.at(1).unwrap();
    assert!(first.allowance > 0.0, "{}", c.by_degree);
    assert!(first.clearly_fails(), "{}", c.by_degree);
    assert_eq!(c.order(), 0, "{}", c.by_degree);
}
