//! The sensitivity map, checked on cases whose answer is known from the
//! analysis, and its committed page checked for staleness (it takes too
//! long to make in CI).

use std::path::PathBuf;
use stepladder::scene::{Harmonic, KeplerCircular, Scene};
use stepladder::scheme::{Rk4, Scheme, VELOCITY_VERLET};
use stepladder_lab::fingerprint::fingerprint_of;
use stepladder_lab::sensitivity::tables::{
    Coefficients, EULER_TABLE, MIDPOINT_TABLE, RK4_TABLE, TableVisitor, rk4_family, visit_tables,
};
use stepladder_lab::sensitivity::{
    CLAIMS, DIGITS, Rejected, SOURCES, Threshold, bisect, pin_unmoved, rejections,
};

#[test]
fn the_committed_map_was_made_from_these_sources() {
    let root = crate::common::root();
    let page = std::fs::read_to_string(root.join(stepladder_lab::sensitivity::page::PAGE))
        .expect("the sensitivity map is committed");
    let recorded = page
        .split("fingerprint `")
        .nth(1)
        .and_then(|rest| rest.split('`').next())
        .expect("the page records the fingerprint of its sources");
    let now = fingerprint_of(&root, &SOURCES, &[]).expect("the sources can be read");
    assert_eq!(
        recorded, now,
        "lab/SENSITIVITY.md was made from other sources (fingerprint {recorded}; this tree's is \
         {now}): make it again with `cargo run --release -- sensitivity` and commit it"
    );
}

/// A scratch folder holding `table`'s pin on `scene`.
fn pinned<T: Coefficients, S: Scene<D>, const D: usize>(
    table: &T,
    scene: &S,
    name: &str,
) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stepladder-map-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    pin_unmoved(table, scene, &dir).expect("the unmoved pin");
    dir
}

fn claim(name: &str) -> usize {
    CLAIMS.iter().position(|&c| c == name).unwrap()
}

/// RK4 moved along its family of fourth-order methods is a correct method
/// of order 4: the order conditions hold (checked independently of the
/// ladder, on the trees), the order claim lets it through even at a move of
/// 1e-1, and only the pin, which sees the error constant change on the
/// orbit, catches it, at 1e-3 as at 1e-1. On the oscillator nothing can:
/// every explicit four-stage method of order 4 has the same stability
/// polynomial `1 + z + z^2/2 + z^3/6 + z^4/24`, so on a linear force the
/// moved method is the same map.
#[test]
fn a_move_that_keeps_every_order_condition_passes_the_order_claim_and_not_the_pin() {
    for delta in [1e-1, 1e-3] {
        let moved = RK4_TABLE.with(&rk4_family(delta));
        assert_eq!(moved.conditions_order(), Some(4), "delta {delta}");
    }
    let kepler = KeplerCircular;
    let dir = pinned(&RK4_TABLE, &kepler, "family");
    for delta in [1e-1, 1e-3] {
        let r = rejections(&RK4_TABLE.with(&rk4_family(delta)), &kepler, &dir);
        assert!(!r[claim("order")], "delta {delta}: {r:?}");
        assert!(r[claim("pin")], "delta {delta}: {r:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    let osc = Harmonic::default();
    let dir = pinned(&RK4_TABLE, &osc, "family-linear");
    let r = rejections(&RK4_TABLE.with(&rk4_family(1e-1)), &osc, &dir);
    assert_eq!(r, [false; 6], "{CLAIMS:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A move that breaks consistency (velocity Verlet's drift lengthened by
/// 1e-4: the step advances positions by `1.0001 h v`) is rejected by every
/// claim that can see it, the order and the pin; the others cannot see it,
/// by the analysis: the moved table is still a splitting of exact flows
/// (symplectic, so its energy stays bounded), still a palindrome
/// (symmetric), and makes the same force calls.
#[test]
fn a_move_that_breaks_consistency_is_caught_by_every_claim_that_can_see_it() {
    let kepler = KeplerCircular;
    let values: Vec<f64> = VELOCITY_VERLET.coefficients().iter().map(|c| c.1).collect();
    let drift = VELOCITY_VERLET
        .coefficients()
        .iter()
        .position(|c| c.0 == "drift[1]")
        .unwrap();
    let mut moved = values.clone();
    moved[drift] *= 1.0 + 1e-4;
    let table = VELOCITY_VERLET.with(&moved);
    assert_eq!(table.conditions_order(), Some(0));
    let dir = pinned(&VELOCITY_VERLET, &kepler, "consistency");
    let r = rejections(&table, &kepler, &dir);
    let expected: Rejected = [true, false, false, false, false, true];
    assert_eq!(r, expected, "{CLAIMS:?}");
    // and the unmoved table passes everything against its own pin
    assert_eq!(rejections(&VELOCITY_VERLET, &kepler, &dir), [false; 6]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The position after `steps` steps of `h` on the oscillator.
fn end<M: Scheme>(scheme: &M, h: f64, steps: u64) -> f64 {
    let osc = Harmonic::default();
    let mut last = osc.initial();
    let outcome =
        stepladder::internals::run::integrate(scheme, &osc, &osc.initial(), h, steps, |_, _, s| {
            last = *s;
        });
    assert!(outcome.completed(), "{outcome:?}");
    last.q[0]
}

struct Rebuilt;

impl TableVisitor for Rebuilt {
    type Output = ();

    /// A table rebuilt from its own coefficients is the same table: the
    /// same coefficients, the same claims, and, on a step, the same state
    /// to the last bit.
    fn visit<T: Coefficients>(&mut self, table: &T) {
        let values: Vec<f64> = table.coefficients().iter().map(|c| c.1).collect();
        let again = table.with(&values);
        assert_eq!(
            again.coefficients(),
            table.coefficients(),
            "{}",
            table.meta().id
        );
        assert_eq!(again.meta(), table.meta(), "{}", table.meta().id);
        let run = |t: &T| end(t, 0.05, 40);
        assert_eq!(
            run(&again).to_bits(),
            run(table).to_bits(),
            "{}",
            table.meta().id
        );
    }
}

#[test]
fn every_table_rebuilt_from_its_coefficients_is_the_same_scheme() {
    visit_tables(&mut Rebuilt);
}

/// The twins are the written-out schemes as data: the same error on the
/// oscillator to round-off, and the same claims.
#[test]
fn the_tableau_twins_are_the_schemes_they_stand_for() {
    use stepladder::scheme::{Euler, ImplicitMidpoint};
    let pairs = [
        (
            end(&Euler, 0.01, 500),
            end(&EULER_TABLE, 0.01, 500),
            Euler.meta(),
            EULER_TABLE.meta(),
        ),
        (
            end(&Rk4, 0.01, 500),
            end(&RK4_TABLE, 0.01, 500),
            Rk4.meta(),
            RK4_TABLE.meta(),
        ),
        (
            end(&ImplicitMidpoint, 0.01, 500),
            end(&MIDPOINT_TABLE, 0.01, 500),
            ImplicitMidpoint.meta(),
            MIDPOINT_TABLE.meta(),
        ),
    ];
    for (written, twin, a, b) in pairs {
        assert!(
            (written - twin).abs() <= 1e-13,
            "{}: {written} {twin}",
            a.id
        );
        assert_eq!(a, b);
    }
}

/// The bisection finds the boundary of a monotone rejection with each `k`
/// judged once, and reports the two ends when nothing or everything is
/// rejected.
#[test]
fn the_bisection_finds_each_claims_boundary() {
    let mut judged = Vec::new();
    let (claims, guard) = bisect(&mut |k| {
        judged.push(k);
        // order rejects down to 1e-9, the pin to 1e-13, the rest nothing
        [k <= 9, false, false, false, false, k <= 13]
    });
    let at = |caught, passed| Threshold { caught, passed };
    assert_eq!(claims[0], at(Some(9), Some(10)));
    assert_eq!(claims[1], at(None, Some(DIGITS[0])));
    assert_eq!(claims[5], at(Some(13), Some(14)));
    assert_eq!(guard, at(Some(13), Some(14)));
    let mut unique = judged.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(unique.len(), judged.len(), "{judged:?}");
    assert!(judged.len() <= 10, "{judged:?}");
    let (all, _) = bisect(&mut |_| [true; 6]);
    assert_eq!(all[0], at(Some(DIGITS[1]), None));
}
