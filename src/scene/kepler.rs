//! The Kepler problem `r'' = -GM r / |r|^3` in the plane, in astronomical units.

use super::{Parameters, Parametrised, Scene, SceneMeta};
use crate::error::Error;
use crate::state::{Real, State};
use nalgebra::{SVector, Vector2};
use std::f64::consts::{PI, TAU};

/// `GM` of the Sun in AU^3 / yr^2: `v^2 r` for the circular Earth orbit with
/// `r = 1 AU` and `v = 2 pi AU/yr` (the course notes' Earth-Sun system).
pub const GM_SUN: f64 = 4.0 * PI * PI;

/// The Earth-Sun system of the course notes: `GM = 4 pi^2`, `r0 = (1, 0)` AU,
/// `v0 = (0, 2 pi)` AU/yr. The orbit is the unit circle run once a year:
/// `r(t) = (cos 2 pi t, sin 2 pi t)`, energy `|v|^2/2 - GM/|r| = -2 pi^2`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct KeplerCircular;

impl Parametrised for KeplerCircular {
    const PARAMETERS: &'static [(&'static str, &'static str)] = &[];
    fn with_parameters(_: &Parameters) -> Result<Self, Error> {
        Ok(Self)
    }
}

impl Scene<2> for KeplerCircular {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "kepler-circular",
            name: "circular Earth-Sun orbit",
            dimension: 2,
            parameters: "GM = 4 pi^2 AU^3/yr^2, r0 = (1, 0) AU, v0 = (0, 2 pi) AU/yr".into(),
            reference: "r'' = -GM r/|r|^3; r(t) = (cos 2 pi t, sin 2 pi t) (course notes' Earth-Sun system, Taylor 4.8)",
        }
    }

    fn initial(&self) -> State<2> {
        State::new(Vector2::new(1.0, 0.0), Vector2::new(0.0, TAU))
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 2>) -> SVector<R, 2> {
        let r2 = q.norm_squared();
        q * (-R::of(GM_SUN) / (r2 * r2.sqrt()))
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 2>) -> R {
        -R::of(GM_SUN) / q.norm()
    }

    fn period(&self) -> f64 {
        1.0
    }

    fn exact(&self, t: f64) -> Option<State<2>> {
        let (s, c) = (TAU * t).sin_cos();
        Some(State::new(
            Vector2::new(c, s),
            Vector2::new(-TAU * s, TAU * c),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circular_orbit_balances_gravity_and_has_the_textbook_energy() {
        let k = KeplerCircular;
        for i in 0..50 {
            let s = k.exact(0.173 * i as f64).unwrap();
            // centripetal acceleration of uniform circular motion: -w^2 r
            let centripetal = -s.q * (TAU * TAU);
            assert!((k.acceleration(&s.q) - centripetal).norm() < 1e-12);
            assert!((k.energy(&s) + 2.0 * PI * PI).abs() < 1e-12);
        }
        assert_eq!(k.exact(0.0).unwrap(), k.initial());
        assert!((k.scale() - 2f64.sqrt()).abs() < 1e-15);
    }
}
