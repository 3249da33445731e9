//! The race of the crate's best integrator against the peers: its rows,
//! the N-body references it is judged against, and the search rules that
//! keep it cheap.

use stepladder::internals::cost::work_points::Reach;
use stepladder::scene::{OuterSolarSystem, Pleiades, Scene};
use stepladder::scheme::AdaptiveIntegrator;
use stepladder::state::State;
use stepladder_lab::peer::{PEERS, VERNER98};
use stepladder_lab::suite::race::{
    KAHAN_LI8_COMPENSATED, KEPLER_SCENES, NBODY_FIRST_STEPS, NBODY_MAX_EVALUATIONS, NBODY_SCENES,
    NBODY_TOLERANCES, OUTER_CHECK_TOLERANCE, OUTER_REFERENCE_STEPS, RACE_TARGETS, REFERENCE_SHARE,
    pleiades_published_accuracy,
};

fn smallest_target() -> f64 {
    RACE_TARGETS.iter().copied().fold(f64::INFINITY, f64::min)
}

fn state<const D: usize>(x: &[f64]) -> State<D> {
    State::new(
        nalgebra::SVector::from_fn(|i, _| x[i]),
        nalgebra::SVector::from_fn(|i, _| x[D + i]),
    )
}

/// Every race scene at every target, with every peer; against an exact
/// solution every target is judged.
#[test]
fn the_race_covers_every_scene_target_and_peer() {
    let race = &super::common::suite().race;
    let scenes: Vec<&str> = KEPLER_SCENES.iter().chain(&NBODY_SCENES).copied().collect();
    assert_eq!(race.rows.len(), scenes.len() * RACE_TARGETS.len());
    for (row, (scene, target)) in race.rows.iter().zip(
        scenes
            .iter()
            .flat_map(|s| RACE_TARGETS.iter().map(move |t| (*s, *t))),
    ) {
        assert_eq!((row.scene, row.target), (scene, target));
        assert_eq!(row.peers.len(), PEERS.len());
        if KEPLER_SCENES.contains(&scene) {
            assert!(row.judged, "{scene} {target}");
        }
    }
    let timing = &super::common::suite().race_timing;
    assert_eq!(timing.len(), race.rows.len());
}

/// The project's claim, on the deterministic half of the race: wherever the
/// reference judges a target and some peer reaches it, the crate's best
/// integrator reaches it with no more force evaluations.
#[test]
fn the_crate_needs_no_more_evaluations_than_any_peer_where_judged() {
    for row in &super::common::suite().race.rows {
        let Some((peer, cost)) = row.best_peer() else {
            continue;
        };
        if !row.judged {
            continue;
        }
        let best = row.best();
        assert!(
            best.is_some_and(|b| b <= cost),
            "{} at {:e}: the crate's best {best:?}, {} {cost}",
            row.scene,
            row.target,
            PEERS[peer].name()
        );
    }
}

/// The Pleiades are judged against the published state, whose own error
/// (against a quadruple-precision integration) is far enough below every
/// target for all of them to be judged.
#[test]
fn the_pleiades_reference_is_the_published_state_and_judges_every_target() {
    let stars = Pleiades::default();
    let record = &super::common::suite().race.nbody[0];
    let reference = &record.reference;
    assert_eq!(reference.scene, "pleiades");
    assert_eq!(reference.t_end, Pleiades::PUBLISHED_TIME);
    assert_eq!(state::<14>(&reference.state), stars.published_end());
    assert_eq!(reference.accuracy, pleiades_published_accuracy(&stars));
    assert!(reference.accuracy <= REFERENCE_SHARE * smallest_target());
    assert!(RACE_TARGETS.iter().all(|&t| reference.judges(t)));
}

/// The outer solar system's reference, Kahan and Li's composition with
/// compensated sums, against an independent method (Verner's 9(8) pair,
/// another family with its own error control): their distance is the
/// reference's stated error, and it is small enough to judge every target.
/// The composition also agrees with itself at half its steps as an
/// eighth-order method must: its error at `N` steps is about `d / (2^8 -
/// 1)`, `d` the distance between the `N/2`- and `N`-step runs, and that too
/// is below a tenth of the smallest target.
#[test]
fn the_outer_solar_system_reference_is_two_independent_methods_agreeing() {
    let planets = OuterSolarSystem::default();
    let record = &super::common::suite().race.nbody[1];
    let reference = &record.reference;
    assert_eq!(reference.scene, "outer-solar-system");
    assert_eq!(reference.t_end, planets.default_t_end());
    let end = |steps: u64| {
        let mut last = planets.initial();
        let outcome = stepladder::internals::run::integrate(
            &KAHAN_LI8_COMPENSATED,
            &planets,
            &planets.initial(),
            reference.t_end / steps as f64,
            steps,
            |_, _, s| last = *s,
        );
        assert!(outcome.completed());
        last
    };
    let composition = end(OUTER_REFERENCE_STEPS);
    assert_eq!(state::<18>(&reference.state), composition);
    let verner = VERNER98
        .run(&planets, reference.t_end, OUTER_CHECK_TOLERANCE)
        .unwrap();
    let check = verner.trajectory.last().unwrap().1;
    let agreement = planets.phase_distance(&composition, &check);
    assert_eq!(reference.accuracy, agreement);
    assert!(
        agreement <= REFERENCE_SHARE * smallest_target(),
        "the two methods agree to {agreement:e}"
    );
    let halved = planets.phase_distance(&end(OUTER_REFERENCE_STEPS / 2), &composition);
    assert!(
        halved / 255.0 <= REFERENCE_SHARE * smallest_target(),
        "half the steps move it by {halved:e}"
    );
    // and the check can fail: a composition at far fewer steps is not
    // within the bound of Verner's pair
    let coarse = planets.phase_distance(&end(OUTER_REFERENCE_STEPS / 64), &check);
    assert!(coarse > REFERENCE_SHARE * smallest_target(), "{coarse:e}");
}

/// An adaptive contender's N-body ladder brackets every target it reaches
/// (so its cost is interpolated, not bounded), and one that does not reach
/// the smallest target stopped only at its floor (its last error not below
/// half of the best before) or at the tightest tolerance.
#[test]
fn the_nbody_adaptive_ladders_bracket_the_targets_or_stop_at_their_floor() {
    for record in &super::common::suite().race.nbody {
        for ladder in &record.adaptive {
            let who = format!("{} on {}", ladder.contender, record.reference.scene);
            // consecutive decades of the list, each exactly its literal
            let first = NBODY_TOLERANCES
                .iter()
                .position(|&t| t == ladder.points[0].setting)
                .expect("a listed tolerance");
            for (p, &t) in ladder.points.iter().zip(&NBODY_TOLERANCES[first..]) {
                assert_eq!(p.setting, t, "{who}");
            }
            for target in RACE_TARGETS {
                match ladder.reach(target) {
                    Reach::Interpolated(_) | Reach::NotReached => {}
                    Reach::AtMost(c) => panic!("{who}: {target:e} only bounded by {c}"),
                }
            }
            let last = ladder.points.last().unwrap();
            if last.error.is_none_or(|e| e > smallest_target()) {
                let before = ladder.points[..ladder.points.len() - 1]
                    .iter()
                    .filter_map(|p| p.error)
                    .fold(f64::INFINITY, f64::min);
                let at_floor = last.error.is_some_and(|e| e >= 0.5 * before);
                let tightest = last.setting == NBODY_TOLERANCES[NBODY_TOLERANCES.len() - 1];
                assert!(at_floor || tightest, "{who}: {:?}", ladder.points);
            }
        }
    }
}

/// The search for a fixed-step scheme on an N-body scene doubles the steps
/// from the first rung, and gives up on a target only once the run that
/// missed it cost at least the bound (the cheapest own pair's cost there),
/// or the next run would pass the cap: any later run would cost more, so
/// the scheme could not have been the crate's best at that target.
#[test]
fn the_fixed_step_search_stops_only_where_a_scheme_cannot_win() {
    for record in &super::common::suite().race.nbody {
        for ladder in &record.fixed {
            let who = format!("{} on {}", ladder.contender, record.reference.scene);
            assert_eq!(ladder.points[0].setting, NBODY_FIRST_STEPS as f64, "{who}");
            for w in ladder.points.windows(2) {
                assert_eq!(w[1].setting, 2.0 * w[0].setting, "{who}");
            }
            let last = ladder.points.last().unwrap();
            let capped = 2 * last.evaluations > NBODY_MAX_EVALUATIONS;
            for (i, &target) in RACE_TARGETS.iter().enumerate() {
                let reached = ladder
                    .points
                    .iter()
                    .any(|p| p.error.is_some_and(|e| e <= target));
                if reached || capped {
                    continue;
                }
                let bound = record.fixed_bounds[i].expect("every scene has a bound");
                assert!(
                    last.evaluations as f64 >= bound,
                    "{who}: stopped at {} evaluations, short of {bound} for {target:e}",
                    last.evaluations
                );
            }
        }
    }
}
