//! Speed against error: cost figures that agree with the metadata and with
//! counted force evaluations, the interpolation to target errors, the choice
//! of the cheapest scheme, and the peer measured like the catalogue. No
//! assertion here depends on how fast the machine is.

use stepladder::internals::cost::step_time::{floor_verlet_kepler, run_steps, speed, time_run};
use stepladder::internals::cost::work_points::{
    Reach, TARGETS, TargetCost, WorkPoint, cheapest, cost_to_reach, start_evaluations,
};
use stepladder::internals::ladder::AUTO_MAX_RUNG_EVALUATIONS;
use stepladder::internals::run::integrate;
use stepladder::scene::{AnyScene, Counted, Harmonic, KeplerCircular, Scene, SceneVisitor};
use stepladder::scheme::{AdaptiveIntegrator, RunEnd};
use stepladder::scheme::{Scheme, SchemeVisitor, VELOCITY_VERLET, scheme_ids, visit_scheme};
use stepladder_lab::peer::{
    DOP853, NumerisVerner98, OdeSolversDop853, PEERS, PeerId, peer_targets, run_first_order,
};
use stepladder_lab::suite::work_precision::cheapest_per_target;

/// The floor runs the same arithmetic as the catalogue's velocity Verlet, so
/// the two must agree to the last bit: a comparison of their speeds is then
/// a comparison of the code around the arithmetic alone.
#[test]
fn the_floor_is_velocity_verlet_to_the_last_bit() {
    let scene = KeplerCircular;
    let s0 = scene.initial();
    let (h, steps) = (1e-3, 5_000);
    let (q, v) = floor_verlet_kepler([s0.q[0], s0.q[1]], [s0.v[0], s0.v[1]], h, steps);
    let mut carry = VELOCITY_VERLET.start(&scene, &s0, h);
    run_steps(&VELOCITY_VERLET, &scene, &mut carry, h, steps).unwrap();
    let s = VELOCITY_VERLET.state(&carry, h);
    for (a, b) in [
        (q[0], s.q[0]),
        (q[1], s.q[1]),
        (v[0], s.v[0]),
        (v[1], s.v[1]),
    ] {
        assert_eq!(a.to_bits(), b.to_bits(), "floor {q:?} {v:?}, scheme {s:?}");
    }
}

/// A timed run's evaluations against a counting scene's, over the same steps.
struct TimedAgainstCounted;
impl SchemeVisitor for TimedAgainstCounted {
    type Output = ();
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) {
        fn check<M: Scheme, S: Scene<D> + Clone, const D: usize>(scheme: &M, scene: S) {
            let counted = Counted::new(scene.clone());
            let h = 1e-3 * scene.period();
            let steps = 300;
            let run = time_run(scheme, &counted, &counted.initial(), h, steps);
            let start = start_evaluations(scheme, &scene, h);
            assert!(
                run.outcome.completed(),
                "{}: {}",
                scheme.meta().id,
                run.outcome
            );
            assert_eq!(
                run.evaluations,
                counted.evaluations() - start,
                "{} on {}",
                scheme.meta().id,
                scene.meta().id
            );
            if !scheme.meta().implicit {
                assert_eq!(
                    run.evaluations,
                    steps * scheme.meta().force_evaluations as u64
                );
            }
        }
        check(scheme, Harmonic::default());
        check(scheme, KeplerCircular);
    }
}

#[test]
fn timed_runs_count_the_evaluations_a_counting_scene_sees() {
    for id in scheme_ids() {
        visit_scheme(id, TimedAgainstCounted).unwrap();
    }
}

/// The speed record's evaluations per step, times its steps, are what a
/// counting scene sees over the same steps; its ratios are its own figures
/// divided by the floor's.
#[test]
fn speed_record_is_consistent_with_counted_evaluations() {
    let steps = 400;
    let record = speed(steps, 2);
    assert_eq!(
        record.schemes.iter().map(|s| s.id).collect::<Vec<_>>(),
        scheme_ids()
    );
    assert!(record.floor_ns_per_step > 0.0);
    struct Count(f64, u64);
    impl SchemeVisitor for Count {
        type Output = u64;
        fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> u64 {
            let scene = Counted::new(KeplerCircular);
            let mut carry = scheme.start(&scene, &scene.initial(), self.0);
            scene.reset();
            run_steps(scheme, &scene, &mut carry, self.0, self.1).unwrap();
            scene.evaluations()
        }
    }
    for s in &record.schemes {
        let counted = visit_scheme(s.id, Count(record.h, steps)).unwrap();
        assert_eq!(
            (s.force_evaluations_per_step * steps as f64).round() as u64,
            counted,
            "{}",
            s.id
        );
        assert!(s.completed, "{}", s.id);
        let ratio = s.ns_per_step / record.floor_ns_per_step;
        assert!(
            (s.ratio_to_floor - ratio).abs() <= 1e-12 * ratio,
            "{}",
            s.id
        );
        let ns_eval = s.ns_per_step / s.force_evaluations_per_step;
        assert!(
            (s.ns_per_force_evaluation - ns_eval).abs() <= 1e-12 * ns_eval,
            "{}",
            s.id
        );
        let per = s.ns_per_force_evaluation / record.floor_ns_per_step;
        assert!(
            (s.ratio_per_evaluation - per).abs() <= 1e-12 * per,
            "{}",
            s.id
        );
    }
}

/// The work study's points on every scene: the order study's rungs first,
/// unchanged, then its ladder continued; every point's evaluations are what
/// a counting scene sees when the rung is run again.
struct PointsAreCounted<'a>(
    &'a stepladder_lab::suite::work_precision::WorkRecord,
    &'a AnyScene,
);
impl SchemeVisitor for PointsAreCounted<'_> {
    type Output = ();
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) {
        struct On<'b, M: 'static>(&'static M, &'b [WorkPoint]);
        impl<M: Scheme + Sync + 'static> SceneVisitor for On<'_, M> {
            type Output = ();
            fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(self, scene: &S) {
                // the cheap rungs: coarse ones, and those that blew up early
                for p in self.1.iter().filter(|p| p.steps <= 20_000) {
                    let counted = Counted::new(scene.clone());
                    let outcome = integrate(
                        self.0,
                        &counted,
                        &counted.initial(),
                        p.h,
                        p.steps,
                        |_, _, _| {},
                    );
                    assert_eq!(
                        p.evaluations,
                        counted.evaluations(),
                        "{} on {} at {} steps ({outcome})",
                        self.0.meta().id,
                        scene.meta().id,
                        p.steps
                    );
                }
            }
        }
        let work = self
            .0
            .schemes
            .iter()
            .find(|w| w.scheme == scheme.meta().id)
            .expect("every scheme has a work record");
        self.1.visit(On(scheme, &work.global));
        self.1.visit(On(scheme, &work.energy));
    }
}

#[test]
fn work_points_reuse_the_order_rungs_and_count_their_evaluations() {
    let suite = super::common::suite();
    assert_eq!(suite.work.len(), AnyScene::all().len());
    for (record, scene) in suite.work.iter().zip(AnyScene::all()) {
        assert_eq!(record.scene, scene.meta().id);
        for id in scheme_ids() {
            visit_scheme(id, PointsAreCounted(record, &scene)).unwrap();
        }
        for w in &record.schemes {
            let order = suite
                .order()
                .into_iter()
                .find(|o| o.scene == record.scene && o.scheme == w.scheme)
                .unwrap();
            assert!(w.global.len() >= order.rungs.len(), "{}", w.scheme);
            for (p, r) in w.global.iter().zip(&order.rungs) {
                if order.t_end == record.t_end {
                    assert_eq!(
                        (p.h, p.steps, p.error),
                        (r.h, r.steps, r.error),
                        "{}",
                        w.scheme
                    );
                } else {
                    // the order study settled on a shorter t_end: the same
                    // steps are run again over the race's t_end
                    let steps = (record.t_end / r.h).round().max(1.0) as u64;
                    assert_eq!(p.steps, steps, "{}", w.scheme);
                    assert_eq!(p.h, record.t_end / steps as f64, "{}", w.scheme);
                }
            }
            // the continuation only ever refines, and only until two
            // successive rungs meet the smallest target
            for pair in w.global.windows(2) {
                assert!(pair[1].steps > pair[0].steps, "{}", w.scheme);
            }
            let smallest = TARGETS.iter().copied().fold(f64::INFINITY, f64::min);
            let meets = |p: &WorkPoint| p.error.is_some_and(|e| e <= smallest);
            let first_added = order.rungs.len();
            for i in first_added..w.global.len() {
                let before = &w.global[..i];
                let settled = before.len() >= 2 && before.iter().rev().take(2).all(meets);
                assert!(!settled, "{} rung {i} after two that meet", w.scheme);
            }
            // and a rung that meets it for the first time is followed by one
            // that confirms it or takes it back, unless that one would
            // break the order study's cap on a rung's evaluations
            if let [.., before, last] = w.global.as_slice() {
                let added = w.global.len() > first_added;
                if added && meets(last) && !meets(before) {
                    let ratio = last.steps as f64 / before.steps as f64;
                    assert!(
                        last.evaluations as f64 * ratio > 0.9 * AUTO_MAX_RUNG_EVALUATIONS as f64,
                        "{} on {}: {:?} met at the last rung and was not confirmed",
                        w.scheme,
                        record.scene,
                        last.error
                    );
                }
            }
        }
    }
}

#[test]
fn the_cheapest_scheme_is_no_dearer_than_any_other() {
    for record in &super::common::suite().work {
        for (i, c) in record.cheapest_global.iter().enumerate() {
            for w in &record.schemes {
                if let (Some(best), Some(other)) =
                    (c.reach.cost(), w.global_targets[i].reach.cost())
                {
                    assert!(
                        best <= other,
                        "{} at {}: {}",
                        record.scene,
                        c.target,
                        w.scheme
                    );
                }
            }
            let reached = record
                .schemes
                .iter()
                .any(|w| w.global_targets[i].reach.cost().is_some());
            assert_eq!(
                c.scheme.is_some(),
                reached,
                "{} at {}",
                record.scene,
                c.target
            );
        }
    }
}

/// Errors `C cost^-2` at costs 10, 100, 1000: an exact power law, which
/// log-log interpolation must reproduce exactly between the points.
fn power_law() -> Vec<(f64, Option<f64>)> {
    [10.0f64, 100.0, 1000.0]
        .iter()
        .map(|&c| (c, Some(3.0 / (c * c))))
        .collect()
}

#[test]
fn a_target_between_rungs_is_interpolated_on_log_log_axes() {
    let pts = power_law();
    for target in [1e-3f64, 3e-4, 1e-5, 3e-6] {
        let exact = (3.0 / target).sqrt();
        match cost_to_reach(&pts, target) {
            Reach::Interpolated(c) => assert!((c - exact).abs() <= 1e-9 * exact, "{target}: {c}"),
            other => panic!("{target}: {other:?}"),
        }
    }
    // a target met exactly at a rung costs that rung
    match cost_to_reach(&pts, 3e-4) {
        Reach::Interpolated(c) => assert!((c - 100.0).abs() < 1e-9),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_target_beyond_the_rungs_is_not_reached_and_never_extrapolated() {
    let pts = power_law();
    assert_eq!(cost_to_reach(&pts, 1e-6), Reach::NotReached);
    assert_eq!(cost_to_reach(&pts, 2.9e-6), Reach::NotReached);
    // met already by the cheapest rung: that rung's cost is an upper bound
    assert_eq!(cost_to_reach(&pts, 0.1), Reach::AtMost(10.0));
    assert_eq!(cost_to_reach(&[], 0.1), Reach::NotReached);
}

#[test]
fn blow_ups_and_round_off_floors_are_handled_honestly() {
    // a blown-up rung gives nothing to interpolate from
    let pts = [(10.0, None), (100.0, Some(1e-4)), (1000.0, Some(1e-6))];
    assert_eq!(cost_to_reach(&pts, 1e-3), Reach::AtMost(100.0));
    // the error stops falling at a floor of 1e-10 and rises again: the first
    // crossing decides, and a target below the floor is not reached
    let pts = [
        (10.0, Some(1e-6)),
        (100.0, Some(1e-9)),
        (1000.0, Some(1e-10)),
        (10_000.0, Some(3e-10)),
    ];
    match cost_to_reach(&pts, 5e-10) {
        Reach::Interpolated(c) => assert!(c > 100.0 && c < 1000.0, "{c}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(cost_to_reach(&pts, 1e-11), Reach::NotReached);
    // an error of exactly zero cannot be placed on log axes
    let pts = [(10.0, Some(1e-3)), (100.0, Some(0.0))];
    assert_eq!(cost_to_reach(&pts, 1e-6), Reach::AtMost(100.0));
}

#[test]
fn the_cheapest_choice_on_synthetic_data() {
    let r = |c| Reach::Interpolated(c);
    assert_eq!(cheapest(&[]), None);
    assert_eq!(cheapest(&[("a", Reach::NotReached)]), None);
    assert_eq!(
        cheapest(&[("a", r(30.0)), ("b", r(20.0)), ("c", r(25.0))]),
        Some(("b", r(20.0)))
    );
    // a tie goes to the first in catalogue order
    assert_eq!(
        cheapest(&[("a", r(20.0)), ("b", r(20.0))]),
        Some(("a", r(20.0)))
    );
    // an upper bound competes at its value
    assert_eq!(
        cheapest(&[("a", r(20.0)), ("b", Reach::AtMost(15.0))]),
        Some(("b", Reach::AtMost(15.0)))
    );
    // per target: each target has its own winner, and the peers ride along
    let costs = |cs: [Reach; 4]| -> Vec<TargetCost> {
        TARGETS
            .iter()
            .zip(cs)
            .map(|(&target, reach)| TargetCost { target, reach })
            .collect()
    };
    let low = costs([r(10.0), r(1000.0), Reach::NotReached, Reach::NotReached]);
    let high = costs([r(50.0), r(200.0), r(800.0), Reach::NotReached]);
    let peer = costs([r(5.0), r(100.0), r(300.0), r(900.0)]);
    let other = costs([r(6.0), Reach::NotReached, r(400.0), r(700.0)]);
    let table = cheapest_per_target(&[("low", &low), ("high", &high)], &[&peer, &other]);
    let winners: Vec<Option<&str>> = table.iter().map(|c| c.scheme).collect();
    assert_eq!(winners, [Some("low"), Some("high"), Some("high"), None]);
    assert_eq!(table[3].reach, Reach::NotReached);
    assert_eq!(table[3].peers, [r(900.0), r(700.0)]);
    assert_eq!(table[1].peers, [r(100.0), Reach::NotReached]);
}

/// Each peer's own statistics count what its system function sees, it ends
/// at `t_end`, and its error falls with its tolerance.
#[test]
fn the_peers_are_counted_and_judged_like_the_catalogue() {
    let scene = KeplerCircular;
    let t_end = scene.default_t_end();
    let start = scene.initial();
    for (peer, stages) in [(PeerId::Dop853, 12), (PeerId::Verner98, 16)] {
        let mut errors = Vec::new();
        for tol in [1e-6, 1e-9, 1e-12] {
            let run = match peer {
                PeerId::Dop853 => run_first_order(&OdeSolversDop853, &scene, &start, t_end, tol),
                PeerId::Verner98 => run_first_order(&NumerisVerner98, &scene, &start, t_end, tol),
            }
            .unwrap();
            assert_eq!(run.end, RunEnd::Reached, "{} at {tol}", peer.name());
            assert_eq!(run.reported, Some(run.counted), "{} at {tol}", peer.name());
            assert!(
                run.counted >= stages * run.accepted,
                "{} at {tol}",
                peer.name()
            );
            let (t, _) = run.trajectory.last().unwrap();
            assert!((t - t_end).abs() <= 1e-12 * t_end);
            let worst = run
                .trajectory
                .iter()
                .map(|(t, s)| scene.phase_distance(s, &scene.exact(*t).unwrap()))
                .fold(0.0, f64::max);
            errors.push(worst);
        }
        assert!(
            errors[0] > 10.0 * errors[1] && errors[1] > 10.0 * errors[2],
            "{}: {errors:?}",
            peer.name()
        );
    }
    // a three-dimensional scene has no peer vector here: refused, not run
    struct Three;
    impl Scene<3> for Three {
        fn meta(&self) -> stepladder::scene::SceneMeta {
            KeplerCircular.meta()
        }
        fn initial(&self) -> stepladder::state::State<3> {
            stepladder::state::State::new(nalgebra::Vector3::x(), nalgebra::Vector3::y())
        }
        fn acceleration<R: stepladder::state::Real>(
            &self,
            q: &nalgebra::SVector<R, 3>,
        ) -> nalgebra::SVector<R, 3> {
            -q
        }
        fn potential<R: stepladder::state::Real>(&self, q: &nalgebra::SVector<R, 3>) -> R {
            q.norm_squared() * R::of(0.5)
        }
        fn period(&self) -> f64 {
            std::f64::consts::TAU
        }
        fn exact(&self, _: f64) -> Option<stepladder::state::State<3>> {
            None
        }
    }
    assert!(DOP853.run(&Three, 1.0, 1e-6).is_err());
    assert!(run_first_order(&NumerisVerner98, &Three, &Three.initial(), 1.0, 1e-6).is_err());
}

#[test]
fn the_peer_targets_follow_its_points() {
    for record in &super::common::suite().work {
        assert_eq!(record.peers.len(), PEERS.len(), "{}", record.scene);
        for (peer, id) in record.peers.iter().zip(PEERS) {
            assert_eq!(peer.peer, id.name());
            assert_eq!(peer.global.len(), peer.energy.len());
            assert_eq!(peer_targets(&peer.global), peer.global_targets);
            // no fewer evaluations than the stages of its accepted steps
            let stages = match id {
                PeerId::Dop853 => 12,
                PeerId::Verner98 => 16,
            };
            for p in &peer.global {
                assert!(
                    p.evaluations >= stages * p.accepted,
                    "{} on {}",
                    peer.peer,
                    record.scene
                );
            }
        }
    }
}

/// Force evaluations go in the report's deterministic part, times only
/// below the machine-dependent marker.
#[test]
fn the_report_keeps_times_below_the_marker() {
    use stepladder_lab::report::{MACHINE_MARKER, deterministic, render};
    let suite = super::common::suite();
    let text = render(suite);
    let (fixed, machine) = text.split_once(MACHINE_MARKER).unwrap();
    assert_eq!(fixed, deterministic(suite));
    assert!(fixed.contains("## Speed against error"));
    assert!(fixed.contains("### Cheapest scheme per target"));
    assert!(!fixed.contains("ns/step") && !fixed.contains(" us |"));
    assert!(machine.contains("### Cost of a step") && machine.contains("### Time to target"));
    for id in scheme_ids() {
        assert!(machine.contains(&format!("| `{id}` |")), "{id}");
    }
}
