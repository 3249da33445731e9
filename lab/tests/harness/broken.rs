//! The harness must catch schemes that do not do what they claim: each
//! scheme here is a plausible bug, defined outside the crate through the
//! public trait, and each must get a failing verdict with the right
//! measured order.

use stepladder::internals::accuracy::order::{OrderSpec, global_order};
use stepladder::scene::{Harmonic, KeplerCircular, KeplerEccentric, Scene};
use stepladder::scheme::{
    Flow, KAHAN_LI8, Leapfrog, Scheme, SchemeMeta, SplittingTable, StepFailure, VELOCITY_VERLET,
};
use stepladder::state::{Real, State};
use stepladder::study::Verdict;

/// Velocity Verlet with the kick weights 0.6 / 0.4 instead of 1/2 / 1/2: still
/// consistent and symplectic, but no longer symmetric, hence first order.
const LOPSIDED_VERLET: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "lopsided-verlet",
        ..VELOCITY_VERLET.meta
    },
    Flow::Kick,
    &[1.0],
    &[0.6, 0.4],
);

/// Leap-frog that hands out its half-step velocity as if it were the
/// whole-step one (the classic output bug): positions are second order, the
/// reported velocities only first.
struct UnsynchronisedLeapfrog;

const UNSYNC_META: SchemeMeta = SchemeMeta {
    id: "unsynchronised-leapfrog",
    ..Leapfrog::META
};

impl Scheme for UnsynchronisedLeapfrog {
    type Carry<R: Real, const D: usize> = <Leapfrog as Scheme>::Carry<R, D>;
    fn meta(&self) -> &SchemeMeta {
        &UNSYNC_META
    }
    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &State<D, R>,
        h: R,
    ) -> Self::Carry<R, D> {
        Leapfrog.start(scene, s, h)
    }
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut Self::Carry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        Leapfrog.step(scene, c, h)
    }
    fn state<R: Real, const D: usize>(&self, c: &Self::Carry<R, D>, _: R) -> State<D, R> {
        State::new(c.q, c.v_half)
    }
}

fn assert_caught<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S, true_order: f64) {
    let r = global_order(scheme, scene, &OrderSpec::default()).unwrap();
    assert_eq!(
        r.verdict,
        Verdict::Fail,
        "{} on {} passed: {}",
        r.scheme,
        r.scene,
        r.reason
    );
    let p = r.measured_order.expect("the order is still measured");
    assert!(
        (p - true_order).abs() < 0.05,
        "{} on {}: measured {p}, expected {true_order}",
        r.scheme,
        r.scene
    );
}

#[test]
fn wrong_kick_weights_are_measured_first_order_and_fail() {
    assert_caught(&LOPSIDED_VERLET, &Harmonic::default(), 1.0);
    assert_caught(&LOPSIDED_VERLET, &KeplerCircular, 1.0);
}

#[test]
fn unsynchronised_leapfrog_velocities_are_measured_first_order_and_fail() {
    assert_caught(&UnsynchronisedLeapfrog, &Harmonic::default(), 1.0);
    assert_caught(&UnsynchronisedLeapfrog, &KeplerCircular, 1.0);
}

/// A correct scheme whose metadata overclaims is caught as well.
#[test]
fn an_overclaimed_order_fails() {
    const OVERCLAIMED: SplittingTable = SplittingTable::new(
        SchemeMeta {
            id: "overclaimed-verlet",
            order: 3,
            ..VELOCITY_VERLET.meta
        },
        Flow::Kick,
        &[1.0],
        &[0.5, 0.5],
    );
    assert_caught(&OVERCLAIMED, &KeplerCircular, 2.0);
}

/// A correct scheme under claimed metadata: every step is the inner scheme's.
struct Claiming<M: 'static> {
    inner: &'static M,
    meta: SchemeMeta,
}

impl<M: Scheme> Scheme for Claiming<M> {
    type Carry<R: Real, const D: usize> = M::Carry<R, D>;
    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }
    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &State<D, R>,
        h: R,
    ) -> Self::Carry<R, D> {
        self.inner.start(scene, s, h)
    }
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut Self::Carry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        self.inner.step(scene, c, h)
    }
    fn state<R: Real, const D: usize>(&self, c: &Self::Carry<R, D>, h: R) -> State<D, R> {
        self.inner.state(c, h)
    }
}

/// An eighth-order scheme claiming second order: a claim of order `p` says
/// the error falls at least as fast as `h^p`, and an error that falls as
/// `h^8` refutes nothing, so the verdict passes, with the true order measured
/// and said. On the orbit of eccentricity 0.9 the coarse rungs miss the
/// pericentre, so the ladder also has rungs above the ceiling.
#[test]
fn an_underclaimed_order_passes_at_its_true_order() {
    let underclaimed = Claiming {
        inner: &KAHAN_LI8,
        meta: SchemeMeta {
            id: "underclaimed-kahan-li8",
            order: 2,
            ..*KAHAN_LI8.meta()
        },
    };
    let spec = OrderSpec::default();
    for r in [
        global_order(&underclaimed, &Harmonic::default(), &spec).unwrap(),
        global_order(&underclaimed, &KeplerCircular, &spec).unwrap(),
        global_order(&underclaimed, &KeplerEccentric::new(0.9).unwrap(), &spec).unwrap(),
    ] {
        assert_eq!(r.verdict, Verdict::Pass, "{}: {}", r.scene, r.reason);
        assert!(
            r.reason.contains("falls faster than the claimed order"),
            "{}",
            r.reason
        );
        let p = r
            .measured_order
            .unwrap_or_else(|| panic!("{}: {}", r.scene, r.reason));
        assert!((p - 8.0).abs() < 0.3, "{}: measured {p}", r.scene);
    }
}
