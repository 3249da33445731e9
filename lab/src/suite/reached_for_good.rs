//! When a ladder of runs has reached a target error for good.
//!
//! A contender's runs in the race go from cheap to dear: a tolerance a decade
//! tighter, or twice the steps. Far above round-off the error falls with the
//! cost, and the first run at or below a target decides what the target
//! costs. At the round-off floor it no longer falls: one run's end error can
//! land below the trend by a cancellation of its roundings, and the next,
//! dearer run is above the target again. Reading the cost off the first run
//! below would make a row at the floor a draw of where a decade ladder's
//! rungs happen to fall, and would promise a user something the next
//! tolerance does not keep.
//!
//! So a target counts as reached at the first run that meets it after which
//! no run of the ladder misses it, and only when at least one dearer run
//! confirms it:
//! without that, the last rung of a ladder would count whatever the next one
//! would have done. The cost is then read off as [`cost_to_reach`] reads it,
//! between that run and the one before it, the ladder's last run above the
//! target. A run that blew up or was refused measures no error: it neither
//! confirms a target nor takes it back, but no cost is interpolated across
//! it.
//!
//! Where the error falls steadily, the first run below a target is followed
//! only by runs below it, and the rule reads the same cost as the first run
//! below; it differs only where a dearer run misses a target a cheaper one
//! met, or where the first run below is the ladder's last.

use stepladder::internals::cost::work_points::{Reach, cost_to_reach};

/// A run's error misses `target`: above it, or not a number.
fn misses(error: Option<f64>, target: f64) -> bool {
    error.is_some_and(|e| e.is_nan() || e > target)
}

/// A run's error meets `target`.
fn meets(error: Option<f64>, target: f64) -> bool {
    error.is_some_and(|e| e <= target)
}

/// The index of the first run after the ladder's last miss of `target`
/// (the first run, when none misses).
fn after_last_miss(data: &[(f64, Option<f64>)], target: f64) -> usize {
    data.iter()
        .rposition(|&(_, e)| misses(e, target))
        .map_or(0, |j| j + 1)
}

/// How many runs meet `target` after the ladder's last miss of it.
fn meeting_since_last_miss(data: &[(f64, Option<f64>)], target: f64) -> usize {
    data[after_last_miss(data, target)..]
        .iter()
        .filter(|&&(_, e)| meets(e, target))
        .count()
}

/// The index from which the cost of `target` is read (the ladder's last run
/// that misses it, or its first run when none does), provided at least two
/// runs after the last miss meet the target; `None` otherwise.
fn settled_from(data: &[(f64, Option<f64>)], target: f64) -> Option<usize> {
    (meeting_since_last_miss(data, target) >= 2)
        .then(|| after_last_miss(data, target).saturating_sub(1))
}

/// The cost of reaching `target` for good, from `(cost, error)` runs ordered
/// from cheap to dear (`None` for a run that blew up or was refused).
///
/// ```
/// use stepladder_lab::suite::reached_for_good::reach_for_good;
/// use stepladder::internals::cost::work_points::Reach;
/// // a falling error: the same cost as the first run below
/// let falling = [(10.0, Some(1e-2)), (100.0, Some(1e-4)), (1000.0, Some(1e-6))];
/// assert!(matches!(reach_for_good(&falling, 1e-3), Reach::Interpolated(_)));
/// // below at 100, above again at 1000, below at 10000 and 100000
/// let floor = [
///     (10.0, Some(1e-2)),
///     (100.0, Some(5e-7)),
///     (1000.0, Some(2e-6)),
///     (10000.0, Some(4e-7)),
///     (100000.0, Some(8e-7)),
/// ];
/// match reach_for_good(&floor, 1e-6) {
///     Reach::Interpolated(c) => assert!(c > 1000.0 && c < 10000.0),
///     other => panic!("{other:?}"),
/// }
/// // the first run below is the last: nothing confirms it
/// assert_eq!(reach_for_good(&falling, 1e-5), Reach::NotReached);
/// ```
pub fn reach_for_good(data: &[(f64, Option<f64>)], target: f64) -> Reach {
    settled_from(data, target).map_or(Reach::NotReached, |s| cost_to_reach(&data[s..], target))
}

/// The indices of the runs that decide the cost of `target` (the first run
/// reaching it for good, and the one before it when there is one), the only
/// runs a race by time needs to time; empty where it is not reached for good.
pub fn deciding_runs(data: &[(f64, Option<f64>)], target: f64) -> Vec<usize> {
    let Some(s) = settled_from(data, target) else {
        return Vec::new();
    };
    let k = s + data[s..]
        .iter()
        .position(|&(_, e)| meets(e, target))
        .expect("a settled target has a run meeting it");
    if k > s { vec![k - 1, k] } else { vec![k] }
}

/// Some run has met `target` since the ladder's last miss of it: the
/// target is reached for good, or waits for a dearer run to confirm it.
pub fn met_since_last_miss(data: &[(f64, Option<f64>)], target: f64) -> bool {
    meeting_since_last_miss(data, target) >= 1
}

/// The cost of the ladder's last measured run where that run is the only
/// one to meet `target` after the ladder's last miss: the target may well
/// be reached, but the ladder ends before a dearer run can confirm it.
/// `None` where the target is reached for good, or the last measured run
/// misses it.
pub fn met_only_by_last_run(data: &[(f64, Option<f64>)], target: f64) -> Option<f64> {
    let &(cost, error) = data.iter().rev().find(|(_, e)| e.is_some())?;
    (meets(error, target) && meeting_since_last_miss(data, target) == 1).then_some(cost)
}
