//! The peers' adapters: counting, refusals, accuracy.

use stepladder::scene::{KeplerEccentric, OuterSolarSystem, Pleiades};
use stepladder::scheme::{AdaptiveIntegrator, AdaptiveRun, RunEnd};
use stepladder_lab::peer::*;

/// Every peer: the evaluations its system function saw are the ones its
/// statistics report, it ends at `t_end` with one state per accepted
/// step, and a request it cannot take is refused with an error.
fn counted_and_refusing<I: AdaptiveIntegrator>(peer: &I) {
    let scene = KeplerEccentric::default();
    let t_end = 10.0;
    let run = peer.run(&scene, t_end, 1e-8).unwrap();
    assert_eq!(run.end, RunEnd::Reached, "{}", peer.name());
    assert_eq!(
        run.reported_evaluations,
        Some(run.evaluations),
        "{}",
        peer.name()
    );
    assert_eq!(run.trajectory.len() as u64, run.accepted + 1);
    assert!(run.rejected > 0, "an eccentric orbit needs a few retries");
    assert_eq!(run.trajectory.last().unwrap().0, t_end);
    let ts: Vec<f64> = run.trajectory.iter().map(|x| x.0).collect();
    assert!(ts.windows(2).all(|w| w[1] > w[0]), "{}", peer.name());
    for (t_end, tol) in [
        (10.0, 0.0),
        (10.0, -1.0),
        (10.0, f64::NAN),
        (f64::NAN, 1e-8),
        (f64::INFINITY, 1e-8),
        (0.0, 1e-8),
    ] {
        assert!(
            peer.run(&scene, t_end, tol).is_err(),
            "{} at t_end {t_end}, tol {tol}",
            peer.name()
        );
    }
}

#[test]
fn both_peers_are_counted_and_refuse_bad_requests() {
    counted_and_refusing(&DOP853);
    counted_and_refusing(&VERNER98);
}

/// The count follows each solver's loop: `Dop853` spends two
/// evaluations on its step-size guess and one on `y'(0)`, eleven on every
/// step tried (its first stage is the last step's end) and one more on
/// `y'` at the end of an accepted one; `RKV98NoInterp` two on its guess
/// and all sixteen stages on every step tried (it keeps no stage).
#[test]
fn the_evaluations_are_the_stages_of_every_step_tried() {
    struct Run;
    impl IntegratorVisitor for Run {
        type Output = AdaptiveRun<2>;
        fn visit<I: AdaptiveIntegrator>(self, peer: &I) -> AdaptiveRun<2> {
            peer.run(&KeplerEccentric::default(), 7.0, 1e-9).unwrap()
        }
    }
    for peer in PEERS {
        let run = peer.visit(Run);
        let expected = match peer {
            PeerId::Dop853 => 3 + 12 * run.accepted + 11 * run.rejected,
            PeerId::Verner98 => 2 + 16 * (run.accepted + run.rejected),
        };
        assert!(run.rejected > 0, "{}: no step rejected", peer.name());
        assert_eq!(run.evaluations, expected, "{}", peer.name());
    }
}

/// The N-body scenes' dimensions are run, and one outside the list is
/// refused.
#[test]
fn the_n_body_dimensions_run() {
    let stars = Pleiades::default();
    let run = VERNER98.run(&stars, 0.5, 1e-8).unwrap();
    assert_eq!(run.end, RunEnd::Reached);
    let planets = OuterSolarSystem::default();
    let run = DOP853.run(&planets, 100.0, 1e-8).unwrap();
    assert_eq!(run.end, RunEnd::Reached);
    assert_eq!(run.reported_evaluations, Some(run.evaluations));
}
