//! The outer solar system: the Sun (with the inner planets) and the five
//! outer planets in space, as in Hairer, Lubich and Wanner's *Geometric
//! Numerical Integration*, I.2.4.

use super::nbody::Bodies;
use super::{Invariant, InvariantValue, Parameters, Parametrised, Scene, SceneMeta};
use crate::error::Error;
use crate::state::{Real, State};
use nalgebra::SVector;

/// Six bodies in space under their mutual gravity: the Sun with the inner
/// planets' masses added, Jupiter, Saturn, Uranus, Neptune and Pluto, with
/// the initial state of 5 September 1994 in astronomical units, Earth days
/// and solar masses (Hairer, Lubich and Wanner, *Geometric Numerical
/// Integration*, I.2.4).
///
/// **All six bodies move.** The published data place the Sun at rest at the
/// origin and give the planets relative to it; here the Sun starts there and
/// is then a body like the others. The system is isolated, so the total
/// linear momentum (not zero: the centre of mass drifts at `6.8e-6`
/// AU/day) and the angular momentum about the origin (any fixed point, for
/// pairwise central forces) are conserved, all three components of each.
///
/// **Coordinates.** As for every scene of unequal masses the state is
/// mass-weighted, `sqrt(m_i) (r_i, r_i')` body after body (`x, y, z` each),
/// so that the acceleration is `-grad V` (see [`super::Pleiades`]);
/// [`OuterSolarSystem::physical`] and [`OuterSolarSystem::mass_weighted`]
/// convert. Phase distances weigh each body by `sqrt(m_i)`: Jupiter's and
/// Saturn's errors dominate them, Pluto's (`sqrt(m) ~ 1e-4`) hardly counts.
///
/// **Time scale.** [`Scene::period`] is Jupiter's Kepler period about the
/// Sun from its initial heliocentric state (semi-major axis by vis-viva),
/// 4332 days: the fastest orbit, which sets the step. The default end time is
/// the generic `2 sqrt(2)` of them, 12,254 days: 1.14 of Saturn's orbits,
/// 0.14 of Pluto's. The orbits are nearly circular and far
/// apart, so a fixed step of a few tens of days resolves them and an order
/// study costs little; over the millions of days of GNI's long runs it would
/// measure the slow growth of phase errors, not the scheme's order.
///
/// ```
/// use stepladder::scene::{OuterSolarSystem, Scene};
/// let system = OuterSolarSystem::default();
/// assert!((system.period() - 4332.3).abs() < 0.1);
/// let sun = system.physical(&system.initial());
/// assert_eq!((sun.q[0], sun.v[2]), (0.0, 0.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OuterSolarSystem {
    pub(super) bodies: Bodies<6, 3>,
    period: f64,
}

impl OuterSolarSystem {
    /// The gravitational constant in AU^3 / (solar mass day^2).
    pub const G: f64 = 2.95912208286e-4;
    /// Masses in solar masses: the Sun with the inner planets, Jupiter,
    /// Saturn, Uranus, Neptune, Pluto.
    pub const MASSES: [f64; 6] = [
        1.00000597682,
        0.000954786104043,
        0.000285583733151,
        0.0000437273164546,
        0.0000517759138449,
        1.0 / 1.3e8,
    ];
    /// Physical positions at `t = 0` in AU, the Sun at the origin.
    pub const POSITIONS: [[f64; 3]; 6] = [
        [0.0, 0.0, 0.0],
        [-3.5023653, -3.8169847, -1.5507963],
        [9.0755314, -3.0458353, -1.6483708],
        [8.3101420, -16.2901086, -7.2521278],
        [11.4707666, -25.7294829, -10.8169456],
        [-15.5387357, -25.2225594, -3.1902382],
    ];
    /// Physical velocities at `t = 0` in AU/day, the Sun at rest.
    pub const VELOCITIES: [[f64; 3]; 6] = [
        [0.0, 0.0, 0.0],
        [0.00565429, -0.00412490, -0.00190589],
        [0.00168318, 0.00483525, 0.00192462],
        [0.00354178, 0.00137102, 0.00055029],
        [0.00288930, 0.00114527, 0.00039677],
        [0.00276725, -0.00170702, -0.00136504],
    ];

    /// The published system.
    pub fn new() -> Self {
        let bodies = Bodies::new(Self::G, Self::MASSES);
        // Jupiter about the Sun: vis-viva 1/a = 2/r - v^2/mu, period 2 pi sqrt(a^3/mu)
        let mu = Self::G * (Self::MASSES[0] + Self::MASSES[1]);
        let norm = |x: &[f64; 3]| x.iter().map(|c| c * c).sum::<f64>().sqrt();
        let (r, v) = (norm(&Self::POSITIONS[1]), norm(&Self::VELOCITIES[1]));
        let a = 1.0 / (2.0 / r - v * v / mu);
        Self {
            bodies,
            period: std::f64::consts::TAU * (a.powi(3) / mu).sqrt(),
        }
    }

    /// Physical positions and velocities of a mass-weighted state: each
    /// body's six numbers divided by `sqrt(m_i)`.
    pub fn physical(&self, s: &State<18>) -> State<18> {
        self.bodies.physical(s)
    }

    /// The mass-weighted state of physical positions and velocities: each
    /// body's six numbers times `sqrt(m_i)`.
    pub fn mass_weighted(&self, physical: &State<18>) -> State<18> {
        self.bodies.mass_weighted(physical)
    }
}

impl Default for OuterSolarSystem {
    fn default() -> Self {
        Self::new()
    }
}

impl Parametrised for OuterSolarSystem {
    const PARAMETERS: &'static [(&'static str, &'static str)] = &[];
    fn with_parameters(_: &Parameters) -> Result<Self, Error> {
        Ok(Self::new())
    }
}

impl Scene<18> for OuterSolarSystem {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "outer-solar-system",
            name: "Sun and the five outer planets (mass-weighted)",
            dimension: 18,
            parameters: "G = 2.95912208286e-4 AU^3/(M_sun day^2), epoch 1994-09-05, Sun at rest at the origin at t = 0; state sqrt(m_i) (r_i, r_i')".into(),
            reference: "Hairer, Lubich, Wanner, Geometric Numerical Integration (2006), I.2.4",
        }
    }

    fn initial(&self) -> State<18> {
        self.mass_weighted(&Bodies::from_bodies(&Self::POSITIONS, &Self::VELOCITIES))
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 18>) -> SVector<R, 18> {
        self.bodies.acceleration(q)
    }

    fn potential<R: Real>(&self, q: &SVector<R, 18>) -> R {
        self.bodies.potential(q)
    }

    fn period(&self) -> f64 {
        self.period
    }

    fn exact(&self, _: f64) -> Option<State<18>> {
        None
    }

    fn invariants(&self) -> &'static [Invariant] {
        &[
            Invariant::Energy,
            Invariant::Momentum { axis: 0 },
            Invariant::Momentum { axis: 1 },
            Invariant::Momentum { axis: 2 },
            Invariant::AngularMomentum { axis: 0 },
            Invariant::AngularMomentum { axis: 1 },
            Invariant::AngularMomentum { axis: 2 },
        ]
    }

    fn invariant(&self, which: Invariant, s: &State<18>) -> Option<InvariantValue> {
        let w = self.frequency();
        match which {
            Invariant::Energy => Some(InvariantValue::energy(self, s)),
            Invariant::Momentum { axis } if axis < 3 => Some(InvariantValue::momentum(
                s,
                self.bodies.sqrt_masses(),
                3,
                axis as usize,
                w,
            )),
            Invariant::AngularMomentum { axis } if axis < 3 => Some(
                InvariantValue::spatial_angular_momentum(s, axis as usize, w),
            ),
            _ => None,
        }
    }
}
