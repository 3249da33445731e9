//! A scene given by its potential alone (`FromPotential`) against the same
//! scene written by hand: the forces from automatic differentiation and
//! their Jacobians (which the tangent map uses) must agree, in `f64` and in
//! `f32`.

use std::f64::consts::PI;
use stepladder::internals::maths::tangent::acceleration_jacobian;
use stepladder::nalgebra::SVector;
use stepladder::prelude::*;
use stepladder::scene::SceneMeta;

/// The eccentric orbit again, given by its potential alone.
#[derive(Clone, Copy)]
struct KeplerPotential(KeplerEccentric);
impl Potential<2> for KeplerPotential {
    fn meta(&self) -> SceneMeta {
        self.0.meta()
    }
    fn potential<R: Real>(&self, q: &SVector<R, 2>) -> R {
        -R::of(4.0 * PI * PI) / q.norm()
    }
    fn initial(&self) -> State<2> {
        self.0.initial()
    }
    fn period(&self) -> f64 {
        self.0.period()
    }
    fn exact(&self, t: f64) -> Option<State<2>> {
        self.0.exact(t)
    }
}

#[test]
fn forces_and_their_jacobians_match_the_hand_written_scene() {
    let hand = KeplerEccentric::new(0.6).unwrap();
    let auto = FromPotential(KeplerPotential(hand));
    for q in [SVector::from([0.4, 0.0]), SVector::from([-0.3, 1.1])] {
        let (a, b) = (hand.acceleration(&q), auto.acceleration(&q));
        assert!((a - b).amax() <= 1e-13 * a.amax(), "{a} vs {b}");
        let (ja, jb) = (
            acceleration_jacobian(&hand, &q),
            acceleration_jacobian(&auto, &q),
        );
        assert!((&ja - &jb).amax() <= 1e-12 * ja.amax(), "{ja} vs {jb}");
        let a32 = auto.acceleration(&q.map(|x| x as f32));
        assert!((a32.map(f64::from) - a).amax() <= 1e-6 * a.amax());
    }
}
