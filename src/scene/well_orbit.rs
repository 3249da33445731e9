//! Any orbit of the anharmonic well, trapped or not, started at its bottom:
//! the scene of the escape-or-trapped study, which needs energies on both
//! sides of the barrier.

use super::well::Well;
use super::{Scene, SceneMeta, positive};
use crate::error::Error;
use crate::state::{Real, State};
use nalgebra::{SVector, Vector1};
use std::f64::consts::TAU;

/// The anharmonic well `x'' = -k x + k x^3 / alpha^2` (barrier `E_b = k
/// alpha^2 / 4` at `x = -+alpha`) with the particle started at the bottom,
/// `x(0) = 0`, moving right with the speed `v0 = sqrt(2 E)` of a chosen
/// energy `E`, which may lie above the barrier.
///
/// Below the barrier the orbit is that of [`super::Anharmonic`], periodic
/// between `-+A`; above it the particle reaches `x = alpha` at a finite time
/// and then runs away (the force `k x^3 / alpha^2` wins, and `x` blows up in
/// finite time). No closed form is kept for either: the studies that use this
/// scene only ask where the numerical orbit goes. Like [`super::Separatrix`],
/// its [`Scene::period`] is the well's time scale `2 pi / sqrt(k)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WellOrbit {
    well: Well,
    energy: f64,
}

impl WellOrbit {
    /// The orbit of energy `energy > 0` started at the bottom of the well
    /// with stiffness `k > 0` and barriers at `-+alpha`.
    ///
    /// ```
    /// use stepladder::scene::{Scene, WellOrbit};
    /// let above = WellOrbit::new(1.0, 1.0, 0.2525).unwrap();
    /// assert!(above.energy(&above.initial()) > above.barrier());
    /// assert!(WellOrbit::new(1.0, 1.0, 0.0).is_err());
    /// ```
    pub fn new(k: f64, alpha: f64, energy: f64) -> Result<Self, Error> {
        let well = Well::new(k, alpha)?;
        let energy = positive("energy", energy)?;
        if !(2.0 * energy).sqrt().is_finite() {
            return Err(Error::InvalidScene(format!(
                "energy {energy:e} gives no finite starting speed"
            )));
        }
        Ok(Self { well, energy })
    }

    /// The orbit of energy `E_b (1 + offset)`: `offset < 0` trapped,
    /// `offset > 0` escaping (`offset > -1`).
    pub fn relative_to_barrier(k: f64, alpha: f64, offset: f64) -> Result<Self, Error> {
        let well = Well::new(k, alpha)?;
        if !(offset.is_finite() && offset > -1.0) {
            return Err(Error::InvalidParameter {
                name: "offset",
                value: offset,
                expected: "a relative energy offset above -1 (the energy must stay positive)",
            });
        }
        Self::new(k, alpha, well.barrier() * (1.0 + offset))
    }

    /// The barrier height `E_b = k alpha^2 / 4`.
    pub fn barrier(&self) -> f64 {
        self.well.barrier()
    }

    /// The barrier position `alpha`.
    pub fn alpha(&self) -> f64 {
        self.well.alpha()
    }

    /// The stiffness `k`.
    pub fn k(&self) -> f64 {
        self.well.k()
    }
}

impl Scene<1> for WellOrbit {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "well-orbit",
            name: "anharmonic well from its bottom",
            dimension: 1,
            parameters: format!(
                "{}, x0 = 0, v0 = sqrt(2 E), E = {} E_b",
                self.well.parameters(),
                self.energy / self.well.barrier()
            ),
            reference: "x'' = -k x + k x^3/alpha^2 at any energy, trapped below E_b = k alpha^2/4 and escaping above (course notes' anharmonic well)",
        }
    }

    fn initial(&self) -> State<1> {
        State::new(Vector1::new(0.0), Vector1::new((2.0 * self.energy).sqrt()))
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 1>) -> SVector<R, 1> {
        Vector1::new(self.well.acceleration(q[0]))
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        self.well.potential(q[0])
    }

    /// The time scale `2 pi / sqrt(k)` of the well's bottom.
    fn period(&self) -> f64 {
        TAU / self.well.k().sqrt()
    }

    fn exact(&self, _t: f64) -> Option<State<1>> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn starts_at_the_bottom_with_the_asked_energy() {
        for (k, alpha) in [(1.0, 1.0), (2.0, 0.5), (0.3, 3.0)] {
            for offset in [-0.5, -1e-3, 0.0, 1e-3, 2.0] {
                let o = WellOrbit::relative_to_barrier(k, alpha, offset).unwrap();
                let s = o.initial();
                assert_eq!(s.q[0], 0.0);
                assert!(s.v[0] > 0.0);
                let e = o.energy(&s) / o.barrier() - 1.0;
                assert!((e - offset).abs() < 4.0 * f64::EPSILON, "{e} vs {offset}");
            }
        }
    }

    #[test]
    fn same_force_as_the_trapped_scene() {
        let o = WellOrbit::new(2.0, 0.7, 0.1).unwrap();
        let t = crate::scene::Anharmonic::new(2.0, 0.7, 0.3, 0.1).unwrap();
        for i in -20..=20 {
            let q = Vector1::new(0.05 * i as f64);
            assert_eq!(o.acceleration(&q), t.acceleration(&q));
            assert_eq!(o.potential(&q), t.potential(&q));
        }
        assert!(o.exact(1.0).is_none());
    }

    #[test]
    fn rejects_bad_energies() {
        assert!(WellOrbit::new(1.0, 1.0, -1.0).is_err());
        assert!(WellOrbit::new(1.0, 1.0, f64::NAN).is_err());
        assert!(WellOrbit::new(1.0, 1.0, f64::MAX).is_err());
        assert!(WellOrbit::relative_to_barrier(1.0, 1.0, -1.0).is_err());
        assert!(WellOrbit::relative_to_barrier(1.0, 1.0, f64::INFINITY).is_err());
        assert!(WellOrbit::relative_to_barrier(0.0, 1.0, 0.1).is_err());
    }
}
