//! The work study's fixed-step ladder past the order study's rungs
//! (`beyond_the_floor`): it goes on until two successive rungs meet the
//! smallest target, so that a reading which counts a target as reached only
//! once a finer run confirms it (the race's) has the run that confirms it,
//! or the run that takes it back.

use stepladder::internals::cost::work_points::{
    EXTRA_RUNGS, SchemeWork, TARGETS, WorkPoint, beyond_the_floor, scheme_work,
};
use stepladder::internals::ladder::AUTO_MAX_RUNG_EVALUATIONS;
use stepladder::scene::{KeplerCircular, KeplerEccentric, Scene};
use stepladder::scheme::{DPRKN6, ImplicitMidpoint, KAHAN_LI8, PEFRL, Rk4, Scheme, YOSHIDA6};
use stepladder::study::{OrderRecord, OrderSpec, global_order};

fn smallest() -> f64 {
    TARGETS.iter().copied().fold(f64::INFINITY, f64::min)
}

fn meets(p: &WorkPoint) -> bool {
    p.error.is_some_and(|e| e <= smallest())
}

/// RKN6(4)'s order study on the circular orbit and its work points.
fn rkn6_on_the_circular_orbit() -> (OrderRecord, SchemeWork) {
    let record = global_order(&DPRKN6, &KeplerCircular, &OrderSpec::default()).unwrap();
    let work = scheme_work(&DPRKN6, &KeplerCircular, &record);
    (record, work)
}

/// RKN6(4) on the circular orbit from its coarsest rung (23 steps, far
/// above the target): the order study's record, that rung, the first rung
/// the ladder adds after it, and the order study's ratio of steps between
/// its two finest measured rungs (the ladder's ratio).
fn rkn6_past_its_coarsest_rung() -> (OrderRecord, WorkPoint, WorkPoint, f64) {
    let scene = KeplerCircular;
    let (record, work) = rkn6_on_the_circular_orbit();
    let coarsest = work.global[0];
    let first = beyond_the_floor(&DPRKN6, &scene, &record, scene.default_t_end(), &[coarsest])[0];
    let rungs: Vec<_> = record.rungs.iter().filter(|r| r.error.is_some()).collect();
    let [.., coarser, last] = rungs.as_slice() else {
        panic!("fewer than two rungs")
    };
    let ratio = last.steps as f64 / coarser.steps as f64;
    (record, coarsest, first, ratio)
}

/// RKN6(4)'s error on the circular orbit falls like `h^6` down to about
/// `1e-14` (the round-off of some `1e4` steps), so `1e-12` lies on the
/// truncation slope: the ladder stops at the first pair of rungs that both
/// meet it, and not before.
#[test]
fn the_ladder_stops_at_the_first_two_rungs_that_meet_the_smallest_target() {
    let (record, work) = rkn6_on_the_circular_orbit();
    let g = &work.global;
    assert!(
        g.len() > record.rungs.len(),
        "the order study alone reaches {:?}",
        g.last().and_then(|p| p.error)
    );
    let n = g.len();
    assert!(meets(&g[n - 1]) && meets(&g[n - 2]), "{:?}", g[n - 1]);
    // the first rung that meets is the one before the last: no earlier rung
    // of the ladder meets the target
    assert!(g[..n - 2].iter().all(|p| !meets(p)));
}

/// A finest rung that meets the target alone is followed by one more rung,
/// even where the error no longer falls as the order promises; a rung that
/// misses after such a stall ends the ladder. The meet is forged (an error
/// of `0.9e-12` at a step where RKN6(4) makes some `1e-10`), so the real
/// rung after it takes the target back.
#[test]
fn a_lone_meet_is_followed_by_the_rung_that_confirms_or_takes_it_back() {
    let scene = KeplerCircular;
    let (record, work) = rkn6_on_the_circular_orbit();
    let t_end = scene.default_t_end();
    // the ladder's rungs over the race's t_end while the error is above
    // 1e-10, a hundred times the target: the rung after them still misses
    // it by far (a rung's ratio of steps is at most two, 2^6 in the error)
    let measured: Vec<WorkPoint> = work
        .global
        .iter()
        .take_while(|p| p.error.is_none_or(|e| e > 1e2 * smallest()))
        .copied()
        .collect();
    let last = *measured.iter().rev().find(|p| p.error.is_some()).unwrap();
    assert!(last.error.unwrap() > 1e2 * smallest(), "{:?}", last.error);

    let mut forged = measured.clone();
    forged.push(WorkPoint {
        error: Some(0.9 * smallest()),
        ..last
    });
    let beyond = beyond_the_floor(&DPRKN6, &scene, &record, t_end, &forged);
    assert_eq!(beyond.len(), 1, "{beyond:?}");
    assert!(!meets(&beyond[0]), "{:?}", beyond[0]);
    assert!(beyond[0].steps > last.steps);

    // two forged rungs that meet: nothing left to confirm
    forged.push(WorkPoint {
        error: Some(0.8 * smallest()),
        ..last
    });
    assert!(beyond_the_floor(&DPRKN6, &scene, &record, t_end, &forged).is_empty());

    // one that meets and one that does not: the miss takes it back, so the
    // ladder goes on from the miss
    forged.pop();
    forged.insert(forged.len() - 1, forged[forged.len() - 1]);
    let n = forged.len();
    forged[n - 1].error = Some(2.0 * smallest());
    assert!(meets(&forged[n - 2]) && !meets(&forged[n - 1]));
    assert!(!beyond_the_floor(&DPRKN6, &scene, &record, t_end, &forged).is_empty());
}

/// The rungs added past the order study's, each `ratio` times the steps of
/// the one before (the order study's last ratio), where `ratio` is read
/// off the order study's two finest measured rungs.
fn added_rungs<M: Scheme, S: Scene<D> + Clone, const D: usize>(
    scheme: &M,
    scene: &S,
) -> (f64, Vec<WorkPoint>, WorkPoint) {
    let record = global_order(scheme, scene, &OrderSpec::default()).unwrap();
    assert_eq!(record.t_end, scene.default_t_end(), "{}", scheme.meta().id);
    let measured: Vec<_> = record.rungs.iter().filter(|r| r.error.is_some()).collect();
    let [.., coarser, last] = measured.as_slice() else {
        panic!("{}: fewer than two rungs", scheme.meta().id)
    };
    let ratio = last.steps as f64 / coarser.steps as f64;
    let work = scheme_work(scheme, scene, &record);
    let n = record.rungs.len();
    (ratio, work.global[n..].to_vec(), work.global[n - 1])
}

/// PEFRL on the circular orbit: the order study ends at 7.9e-12. The first
/// rung past it still misses 1e-12 while the error falls as fourth order
/// promises, so the ladder goes on past a miss; it stops at the first two
/// rungs that meet the target, each rung at the order study's ratio.
#[test]
fn the_ladder_goes_on_past_a_miss_at_the_order_studys_ratio() {
    let (ratio, added, finest) = added_rungs(&PEFRL, &KeplerCircular);
    assert!(!meets(&finest));
    assert!(added.len() >= 3, "{added:?}");
    let n = added.len();
    assert!(meets(&added[n - 1]) && meets(&added[n - 2]));
    assert!(added[..n - 2].iter().all(|p| !meets(p)), "{added:?}");
    let mut steps = finest.steps;
    for p in &added {
        steps = (steps as f64 * ratio).round() as u64;
        assert_eq!(p.steps, steps, "{added:?}");
    }
}

/// RK4 on the eccentric orbit, a case the rule was not designed on: its
/// error meets 1e-12 on one rung (9.8e-13) and the next, finer rung is
/// already at the round-off floor (9.2e-12), so the rung that was added to
/// confirm the target takes it back, and a stalled miss ends the ladder.
/// Read off the first rung below, RK4 would be said to reach 1e-12.
#[test]
fn the_rung_after_a_first_meet_can_take_the_target_back() {
    let (_, added, _) = added_rungs(&Rk4, &KeplerEccentric::default());
    let n = added.len();
    assert!(n >= 2, "{added:?}");
    assert!(meets(&added[n - 2]) && !meets(&added[n - 1]), "{added:?}");
    assert!(added[n - 1].error > added[n - 2].error);
    assert!(added[..n - 2].iter().all(|p| !meets(p)), "{added:?}");
}

/// No rung the ladder adds breaks the order study's cap on a rung's force
/// evaluations: the implicit midpoint rule (two evaluations a step here,
/// second order) ends its order study near the cap with its error far
/// above the smallest target, and the ladder adds nothing.
#[test]
fn no_added_rung_breaks_the_cap_on_evaluations() {
    let (ratio, added, finest) = added_rungs(&ImplicitMidpoint, &KeplerCircular);
    assert!(finest.error.is_some_and(|e| e > 1e-9), "{finest:?}");
    // the next rung would cost more than the cap allows
    assert!(finest.evaluations as f64 * ratio > AUTO_MAX_RUNG_EVALUATIONS as f64);
    assert!(added.is_empty(), "{added:?}");
}

/// Past the order study, a rung whose error falls by less than a tenth of
/// what the order promises per rung (`ratio^p`) is round-off, not
/// truncation: it ends the ladder, unless it has just met the target (then
/// one more rung confirms it or takes it back). On the eccentric orbit four
/// schemes end their ladders each way: PEFRL on a rung that fell 1.2 times
/// where fourth order promises 4.2 (a ratio of 1.43 in steps), Yoshida's
/// sixth order on a rung that rose, RK4 on the miss after a first meet,
/// Kahan and Li's eighth order on two meets.
#[test]
fn a_rung_that_no_longer_falls_as_the_order_promises_ends_the_ladder() {
    fn check<M: Scheme>(scheme: &M, ends_stalled: bool) {
        let scene = KeplerEccentric::default();
        let (ratio, added, finest) = added_rungs(scheme, &scene);
        let promised = ratio.powi(scheme.meta().order as i32);
        let stalled = |before: f64, e: f64| e > before / (1.0 + 0.1 * (promised - 1.0));
        assert!(!added.is_empty(), "{}", scheme.meta().id);
        let mut before = finest;
        let mut met_in_a_row = 0;
        for (i, p) in added.iter().enumerate() {
            met_in_a_row = if meets(p) { met_in_a_row + 1 } else { 0 };
            let e = p.error.unwrap();
            let last = i + 1 == added.len();
            let ends =
                met_in_a_row == 2 || (stalled(before.error.unwrap(), e) && met_in_a_row != 1);
            assert_eq!(ends, last, "{} rung {i}: {added:?}", scheme.meta().id);
            before = *p;
        }
        assert_eq!(met_in_a_row != 2, ends_stalled, "{}", scheme.meta().id);
    }
    check(&PEFRL, true);
    check(&YOSHIDA6, true);
    check(&Rk4, true);
    check(&KAHAN_LI8, false);
}

/// The ladder's two limits, on forged finest rungs of RKN6(4) on the
/// circular orbit. Started from its coarsest rung (23 steps, 1.7e-3), the
/// ladder first meets 1e-12 near 740 steps, some sixteen rungs at the order
/// study's ratio of 1.24, so it cannot meet it twice before it stops at
/// [`EXTRA_RUNGS`]. A finest rung whose
/// cost per step puts the next rung just over the cap on evaluations adds
/// nothing, whatever its error.
#[test]
fn the_ladder_stops_at_its_rung_limit_and_at_the_cap() {
    let scene = KeplerCircular;
    let (record, work) = rkn6_on_the_circular_orbit();
    let t_end = scene.default_t_end();
    let coarsest = work.global[0];
    assert!(coarsest.error.is_some_and(|e| e > 1e-3), "{coarsest:?}");
    let beyond = beyond_the_floor(&DPRKN6, &scene, &record, t_end, &[coarsest]);
    assert_eq!(beyond.len(), EXTRA_RUNGS, "{beyond:?}");
    // the limit stopped it, not two rungs that meet
    assert!(!beyond[EXTRA_RUNGS - 2..].iter().all(meets), "{beyond:?}");

    // 0.9 of the cap at this rung's steps: the next rung, 1.25 times the
    // steps, would spend 1.12 times the cap
    let per_step = 0.9 * AUTO_MAX_RUNG_EVALUATIONS as f64 / coarsest.steps as f64;
    let dear = WorkPoint {
        evaluations: (per_step * coarsest.steps as f64) as u64,
        ..coarsest
    };
    assert!(beyond_the_floor(&DPRKN6, &scene, &record, t_end, &[dear]).is_empty());
}

/// Where the stall threshold lies: a rung that fell by just more than a
/// tenth of what the order promises (`1 + 0.1 (ratio^p - 1)`) keeps the
/// ladder going, and one that fell by just less ends it. The error before
/// the first added rung is forged: RKN6(4)'s coarsest rung on the circular
/// orbit (23 steps, far above the target) with its error set to the first
/// added rung's times a factor `0.01` either side of the threshold (a
/// threshold of `1 + 0.1 (ratio^p + 1)` or `1 + 0.1 ratio^p` would lie
/// `0.2` or `0.1` above it).
#[test]
fn the_stall_threshold_is_a_tenth_of_what_the_order_promises() {
    let scene = KeplerCircular;
    let t_end = scene.default_t_end();
    let (record, coarsest, first, ratio) = rkn6_past_its_coarsest_rung();
    let e1 = first.error.expect("an error");
    assert!(e1 > 1e-6, "{first:?}");
    let promised = ratio.powi(6);
    let threshold = 1.0 + 0.1 * (promised - 1.0);
    for (fell, goes_on) in [(threshold + 0.01, true), (threshold - 0.01, false)] {
        let forged = WorkPoint {
            error: Some(e1 * fell),
            ..coarsest
        };
        let beyond = beyond_the_floor(&DPRKN6, &scene, &record, t_end, &[forged]);
        assert_eq!(beyond[0], first, "the same first rung");
        assert_eq!(
            beyond.len() > 1,
            goes_on,
            "fell {fell}, threshold {threshold}: {beyond:?}"
        );
    }
}

/// Each added rung has more steps than the one before, even where the order
/// study's ratio would round back to the same count: on a record whose two
/// finest rungs are 1% apart, rung after rung from the coarsest rung (23
/// steps, where `round(23 x 1.01) = 23`) is one step more, not the same run
/// again.
#[test]
fn every_added_rung_has_more_steps_than_the_one_before() {
    let scene = KeplerCircular;
    let (mut record, work) = rkn6_on_the_circular_orbit();
    let t_end = scene.default_t_end();
    let coarsest = work.global[0];
    // the premise: at this ratio the count rounds back to itself
    assert_eq!(
        (coarsest.steps as f64 * 1.01).round() as u64,
        coarsest.steps,
        "{coarsest:?}"
    );
    let measured: Vec<usize> = (0..record.rungs.len())
        .filter(|&i| record.rungs[i].error.is_some())
        .collect();
    let [.., coarser, last] = measured.as_slice() else {
        panic!("fewer than two rungs")
    };
    record.rungs[*coarser].steps = 100;
    record.rungs[*last].steps = 101;
    let beyond = beyond_the_floor(&DPRKN6, &scene, &record, t_end, &[coarsest]);
    assert!(beyond.len() >= 2, "{beyond:?}");
    for (k, p) in beyond.iter().enumerate() {
        assert_eq!(p.steps, coarsest.steps + 1 + k as u64, "{beyond:?}");
    }
}

/// The cap on a rung's force evaluations is the order study's: a rung
/// whose predicted cost is the cap exactly is run (the order study refuses
/// only a rung above it), and one a count above it is not. The finest rung
/// is forged: its step count is one whose next rung at the order study's
/// ratio is a power of two, `2^k`, so that a cost of `2^21 / 2^k` a step
/// puts that rung on the cap to the last bit.
#[test]
fn a_rung_that_costs_the_cap_exactly_is_run() {
    let scene = KeplerCircular;
    let t_end = scene.default_t_end();
    let (record, coarsest, _, ratio) = rkn6_past_its_coarsest_rung();
    let (steps, next) = (2..1000u64)
        .map(|s| (s, (s as f64 * ratio).round() as u64))
        .find(|&(s, n)| n > s && n.is_power_of_two())
        .expect("a step count whose next rung is a power of two");
    let cap = AUTO_MAX_RUNG_EVALUATIONS;
    let on_the_cap = steps * (cap / next);
    assert_eq!(on_the_cap as f64 / steps as f64 * next as f64, cap as f64);
    for (evaluations, runs) in [(on_the_cap, true), (on_the_cap + 1, false)] {
        let forged = WorkPoint {
            steps,
            h: t_end / steps as f64,
            evaluations,
            ..coarsest
        };
        let beyond = beyond_the_floor(&DPRKN6, &scene, &record, t_end, &[forged]);
        assert_eq!(
            beyond.first().map(|p| p.steps),
            runs.then_some(next),
            "{evaluations} evaluations over {steps} steps: {beyond:?}"
        );
    }
}

/// A rung that fell by exactly a tenth of what the order promises has
/// fallen by at least that much: the ladder goes on. The error before it
/// is forged so that the threshold lands on the first added rung's error
/// to the last bit.
#[test]
fn a_rung_that_fell_by_exactly_the_threshold_keeps_the_ladder_going() {
    let scene = KeplerCircular;
    let t_end = scene.default_t_end();
    let (record, coarsest, first, ratio) = rkn6_past_its_coarsest_rung();
    let e1 = first.error.expect("an error");
    let promised = ratio.powi(6);
    let divisor = 1.0 + 0.1 * (promised - 1.0);
    // the doubles around e1 times the divisor, one whose quotient is e1
    let mut before = e1 * divisor;
    for _ in 0..8 {
        if before / divisor == e1 {
            break;
        }
        before = if before / divisor > e1 {
            before.next_down()
        } else {
            before.next_up()
        };
    }
    assert_eq!(
        before / divisor,
        e1,
        "no double lands the threshold on {e1}"
    );
    let forged = WorkPoint {
        error: Some(before),
        ..coarsest
    };
    let beyond = beyond_the_floor(&DPRKN6, &scene, &record, t_end, &[forged]);
    assert!(beyond.len() > 1, "{beyond:?}");
}
