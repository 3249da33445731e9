//! The race's rule for reaching a target: at the first run after which no
//! dearer run misses it, with a dearer run confirming it. The cases are the
//! shapes a ladder takes at the round-off floor, and the properties tie the
//! rule to the first-run-below reading it replaces.

use proptest::prelude::*;
use stepladder::internals::cost::work_points::{Reach, cost_to_reach};
use stepladder_lab::suite::reached_for_good::{
    deciding_runs, met_only_by_last_run, met_since_last_miss, reach_for_good,
};

/// A run's cost and error.
type Run = (f64, Option<f64>);

/// The log-log interpolation between two runs, computed here from the
/// power law through them, not by the crate's reader.
fn power_law(a: Run, b: Run, target: f64) -> f64 {
    let (e0, e1) = (a.1.unwrap(), b.1.unwrap());
    let k = (e1 / e0).ln() / (b.0 / a.0).ln();
    a.0 * (target / e0).powf(1.0 / k)
}

#[test]
fn a_dip_below_the_target_does_not_count_when_a_dearer_run_misses_it() {
    // the eccentric orbit's shape: below at one tolerance, above at the next
    let runs = [
        (100.0, Some(1e-10)),
        (200.0, Some(8.7e-15)),
        (300.0, Some(1.4e-14)),
    ];
    assert_eq!(reach_for_good(&runs, 1e-14), Reach::NotReached);
    assert_eq!(deciding_runs(&runs, 1e-14), Vec::<usize>::new());
    // the last run misses: nothing was met by it alone
    assert_eq!(met_only_by_last_run(&runs, 1e-14), None);
    // the first run below, as the work tables read it, would have counted
    assert!(matches!(
        cost_to_reach(&runs, 1e-14),
        Reach::Interpolated(_)
    ));
}

#[test]
fn after_the_last_miss_the_cost_is_read_between_it_and_the_next_run() {
    let runs = [
        (100.0, Some(1e-10)),
        (200.0, Some(8.7e-15)),
        (300.0, Some(1.4e-14)),
        (400.0, Some(6e-15)),
        (500.0, Some(9e-15)),
    ];
    let expected = power_law(runs[2], runs[3], 1e-14);
    match reach_for_good(&runs, 1e-14) {
        Reach::Interpolated(c) => assert!((c / expected - 1.0).abs() < 1e-12, "{c} {expected}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(deciding_runs(&runs, 1e-14), vec![2, 3]);
    // a looser target, met from the second run on, keeps its first reading
    assert_eq!(reach_for_good(&runs, 1e-12), cost_to_reach(&runs, 1e-12));
}

#[test]
fn an_error_equal_to_the_target_meets_it() {
    // as the first-run-below reading has it: at or below the target
    let runs = [
        (10.0, Some(1e-2)),
        (100.0, Some(1e-6)),
        (1000.0, Some(1e-6)),
    ];
    assert_eq!(reach_for_good(&runs, 1e-6), cost_to_reach(&runs, 1e-6));
    assert!(matches!(
        reach_for_good(&runs, 1e-6),
        Reach::Interpolated(_)
    ));
    assert!(met_since_last_miss(&runs[..2], 1e-6));
}

#[test]
fn the_last_run_alone_confirms_nothing() {
    let runs = [
        (10.0, Some(1e-2)),
        (100.0, Some(1e-4)),
        (1000.0, Some(1e-6)),
    ];
    assert_eq!(reach_for_good(&runs, 1e-5), Reach::NotReached);
    assert_eq!(met_only_by_last_run(&runs, 1e-5), Some(1000.0));
    // met by the last two: the last confirms the one before
    assert_eq!(met_only_by_last_run(&runs, 1e-3), None);
    let expected = power_law(runs[0], runs[1], 1e-3);
    match reach_for_good(&runs, 1e-3) {
        Reach::Interpolated(c) => assert!((c / expected - 1.0).abs() < 1e-12),
        other => panic!("{other:?}"),
    }
    // a single run decides nothing, whatever its error
    assert_eq!(reach_for_good(&runs[..1], 1.0), Reach::NotReached);
    assert_eq!(met_only_by_last_run(&runs[..1], 1.0), Some(10.0));
    assert_eq!(reach_for_good(&[], 1.0), Reach::NotReached);
}

#[test]
fn a_run_that_measured_nothing_neither_confirms_nor_takes_back() {
    // refused at the tightest tolerance: the two runs before still settle it
    let refused_last = [
        (10.0, Some(1e-2)),
        (100.0, Some(1e-7)),
        (200.0, Some(1e-8)),
        (0.0, None),
    ];
    assert!(matches!(
        reach_for_good(&refused_last, 1e-6),
        Reach::Interpolated(_)
    ));
    // but it does not confirm a target only the run before it met, which
    // is then the last run that measured anything
    assert_eq!(reach_for_good(&refused_last, 5e-8), Reach::NotReached);
    assert_eq!(met_only_by_last_run(&refused_last, 5e-8), Some(200.0));
    assert!(met_since_last_miss(&refused_last, 5e-8));
    // nothing met since the last miss, and nothing met at all
    assert!(!met_since_last_miss(&refused_last, 5e-9));
    assert_eq!(met_only_by_last_run(&refused_last, 5e-9), None);
    assert!(!met_since_last_miss(&[(0.0, None)], 1.0));
    // a blow-up before the first run below leaves only a bound
    let blown = [(10.0, None), (100.0, Some(1e-7)), (200.0, Some(1e-8))];
    assert_eq!(reach_for_good(&blown, 1e-6), Reach::AtMost(100.0));
    assert_eq!(deciding_runs(&blown, 1e-6), vec![0, 1]);
    // a NaN error is a miss, not a measurement to skip
    let nan = [
        (10.0, Some(1e-7)),
        (20.0, Some(f64::NAN)),
        (40.0, Some(1e-8)),
    ];
    assert_eq!(reach_for_good(&nan, 1e-6), Reach::NotReached);
    assert_eq!(met_only_by_last_run(&nan, 1e-6), Some(40.0));
}

/// Ladders of a few runs, costs rising, errors anywhere over ten decades,
/// some runs blown up.
fn ladder() -> impl Strategy<Value = Vec<Run>> {
    prop::collection::vec(
        (1.0f64..3.0, prop::option::weighted(0.9, -16.0f64..-6.0)),
        0..9,
    )
    .prop_map(|steps| {
        let mut cost = 10.0;
        steps
            .into_iter()
            .map(|(growth, log_error)| {
                cost *= growth;
                (cost, log_error.map(|l| 10f64.powf(l)))
            })
            .collect()
    })
}

proptest! {
    /// On a ladder whose error falls run by run, the rule reads what the
    /// first run below reads, except where that run is the last.
    #[test]
    fn on_a_falling_ladder_it_is_the_first_run_below(
        n in 2usize..10, first in -7.0f64..-3.0, slope in 0.2f64..2.0, target in -12.0f64..-3.0,
    ) {
        let runs: Vec<Run> = (0..n)
            .map(|i| (10.0 * 2f64.powi(i as i32), Some(10f64.powf(first - slope * i as f64))))
            .collect();
        let target = 10f64.powf(target);
        let last_only = runs[..n - 1].iter().all(|r| r.1.unwrap() > target)
            && runs[n - 1].1.unwrap() <= target;
        if last_only {
            prop_assert_eq!(reach_for_good(&runs, target), Reach::NotReached);
        } else {
            prop_assert_eq!(reach_for_good(&runs, target), cost_to_reach(&runs, target));
        }
    }

    /// A run that misses the target, added at the dear end, takes it back.
    #[test]
    fn a_dearer_miss_takes_the_target_back(runs in ladder(), target in -14.0f64..-8.0, over in 1.0f64..100.0) {
        let target = 10f64.powf(target);
        let mut more = runs.clone();
        let cost = more.last().map_or(1.0, |r| r.0) * 2.0;
        more.push((cost, Some(target * over * (1.0 + 1e-9))));
        prop_assert_eq!(reach_for_good(&more, target), Reach::NotReached);
    }

    /// The two deciding runs alone give the same cost, and the cost is
    /// never below the first run below's reading.
    #[test]
    fn the_deciding_runs_carry_the_cost(runs in ladder(), target in -14.0f64..-8.0) {
        let target = 10f64.powf(target);
        let reach = reach_for_good(&runs, target);
        let decide: Vec<Run> = deciding_runs(&runs, target).into_iter().map(|k| runs[k]).collect();
        prop_assert_eq!(reach.cost().is_some(), !decide.is_empty());
        if let Some(cost) = reach.cost() {
            prop_assert_eq!(cost_to_reach(&decide, target), reach);
            let first = cost_to_reach(&runs, target).cost().unwrap();
            prop_assert!(cost >= first * (1.0 - 1e-12), "{} < {}", cost, first);
            // and a settled target is met by the last run and the one it confirms
            prop_assert_eq!(met_only_by_last_run(&runs, target), None);
        }
    }
}
