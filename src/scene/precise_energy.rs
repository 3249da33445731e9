//! The energy beyond double precision, for the long runs that measure
//! round-off: evaluated in doubles, the energy rounds by about `1e-16` of
//! itself at every reading, which is as large as a compensated integrator's
//! whole random walk over a million steps.

use super::kepler::GM_SUN;
use super::{KeplerCircular, KeplerEccentric, OuterSolarSystem, Pleiades, Scene};
use crate::maths::dd::Dd;
use crate::state::State;

/// A scene whose energy is evaluated in double-double (about 32 digits), in
/// the form its double-precision force law conserves exactly, so that what
/// a run does to it is the integrator's doing and not the reading's.
pub trait PreciseEnergy<const D: usize>: Scene<D> {
    /// The energy at `s + low`, where `low` holds a compensated scheme's
    /// low parts ([`crate::scheme::Scheme::compensation`]), zero otherwise.
    fn precise_energy(&self, s: &State<D>, low: &State<D>) -> Dd;
}

/// `|v|^2 / 2 - GM / |q|` with the double `GM` the force law uses.
fn kepler_energy(s: &State<2>, low: &State<2>) -> Dd {
    let x = |i: usize| Dd::of(s.q[i]).add(Dd::of(low.q[i]));
    let u = |i: usize| Dd::of(s.v[i]).add(Dd::of(low.v[i]));
    let r2 = x(0).mul(x(0)).add(x(1).mul(x(1)));
    let v2 = u(0).mul(u(0)).add(u(1).mul(u(1)));
    v2.mul(Dd::of(0.5)).sub(Dd::of(GM_SUN).div(r2.sqrt()))
}

impl PreciseEnergy<2> for KeplerCircular {
    fn precise_energy(&self, s: &State<2>, low: &State<2>) -> Dd {
        kepler_energy(s, low)
    }
}

impl PreciseEnergy<2> for KeplerEccentric {
    fn precise_energy(&self, s: &State<2>, low: &State<2>) -> Dd {
        kepler_energy(s, low)
    }
}

impl PreciseEnergy<18> for OuterSolarSystem {
    fn precise_energy(&self, s: &State<18>, low: &State<18>) -> Dd {
        self.bodies.energy_dd(s, low)
    }
}

impl PreciseEnergy<14> for Pleiades {
    fn precise_energy(&self, s: &State<14>, low: &State<14>) -> Dd {
        self.bodies.energy_dd(s, low)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::SVector;

    /// At a double state with no low part the precise energy rounds to the
    /// scene's own double evaluation within a few units of `1e-16`, and a
    /// low part of one unit in the last place of every velocity moves it by
    /// `v . low`, which the double evaluation cannot see.
    #[test]
    fn the_precise_energy_is_the_energy_and_sees_the_low_parts() {
        fn check<S: PreciseEnergy<D>, const D: usize>(scene: &S) {
            let s = scene.initial();
            let none = State::new(SVector::zeros(), SVector::zeros());
            let e = scene.precise_energy(&s, &none).to_f64();
            let plain = scene.energy(&s);
            assert!(
                (e - plain).abs() <= 1e-14 * plain.abs(),
                "{}: {e} against {plain}",
                scene.meta().id
            );
            let low = State::new(SVector::zeros(), s.v.map(|v| v * f64::EPSILON));
            let moved = scene
                .precise_energy(&s, &low)
                .sub(scene.precise_energy(&s, &none));
            let expected = s.v.dot(&low.v);
            assert!(
                (moved.to_f64() - expected).abs() <= 1e-6 * expected.abs(),
                "{}: moved {moved:?}, expected {expected}",
                scene.meta().id
            );
        }
        check(&KeplerCircular);
        check(&KeplerEccentric::default());
        check(&OuterSolarSystem::new());
        check(&Pleiades::new());
    }
}
