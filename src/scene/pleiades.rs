//! The Pleiades: seven stars in the plane, a standard non-stiff test problem
//! with close encounters and a published state at `t = 3`.

use super::nbody::Bodies;
use super::{Invariant, InvariantValue, Parameters, Parametrised, Scene, SceneMeta};
use crate::error::Error;
use crate::state::{Real, State};
use nalgebra::SVector;

/// Seven stars of masses `m_i = i` (`G = 1`) in the plane, from Hairer,
/// Nørsett and Wanner, *Solving Ordinary Differential Equations I*, II.10,
/// problem PLEI of the IVP test set (Mazzia and Magherini, release 2.4),
/// which publishes the state at `t = 3` to 16 digits.
///
/// **Coordinates.** The state is mass-weighted, `Q_i = sqrt(m_i) r_i` and
/// `Q_i' = sqrt(m_i) r_i'` for the physical positions `r_i`, body after body
/// (`x1, y1, ..., x7, y7`): only there is the acceleration `-grad V` with
/// kinetic energy `|Q'|^2 / 2` (see the scene checks). [`Pleiades::physical`]
/// and [`Pleiades::mass_weighted`] convert; the published data enter through
/// them. Phase distances are therefore mass-weighted too: an error of body
/// `i` counts `sqrt(i)` times its physical size.
///
/// **Time scale.** [`Scene::period`] is the Kepler period at the stars'
/// mass-weighted root-mean-square distance from their centre of mass (3.69)
/// about their total mass (28): 8.43, the time a star at the cluster's
/// typical distance takes to go round it. It weighs velocity against
/// position errors in the phase distance as the motion does (speeds about
/// 1-3 against distances about 4). The published interval `[0, 3]` is 0.36
/// of it, and [`Scene::default_t_end`] is that interval, 3, because it is
/// where the published state lies (the stars' close encounters near `t =
/// 1.2` to `1.5` are inside it); the generic `2 sqrt(2)` periods would end
/// far beyond any published truth.
///
/// **Invariants.** An isolated system with pairwise central forces: energy,
/// both components of the linear momentum and the angular momentum.
///
/// ```
/// use stepladder::scene::{Pleiades, Scene};
/// let stars = Pleiades::default();
/// let start = stars.physical(&stars.initial());
/// assert_eq!((start.q[12], start.q[13]), (2.0, 4.0)); // the seventh star
/// assert_eq!(stars.default_t_end(), 3.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pleiades {
    pub(super) bodies: Bodies<7, 2>,
    period: f64,
}

impl Pleiades {
    /// The gravitational constant.
    pub const G: f64 = 1.0;
    /// The masses, `m_i = i`.
    pub const MASSES: [f64; 7] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];
    /// Physical positions at `t = 0`.
    pub const POSITIONS: [[f64; 2]; 7] = [
        [3.0, 3.0],
        [3.0, -3.0],
        [-1.0, 2.0],
        [-3.0, 0.0],
        [2.0, 0.0],
        [-2.0, -4.0],
        [2.0, 4.0],
    ];
    /// Physical velocities at `t = 0`.
    pub const VELOCITIES: [[f64; 2]; 7] = [
        [0.0, 0.0],
        [0.0, 0.0],
        [0.0, 0.0],
        [0.0, -1.25],
        [0.0, 1.0],
        [1.75, 0.0],
        [-1.5, 0.0],
    ];
    /// The time of the published state.
    pub const PUBLISHED_TIME: f64 = 3.0;
    /// Published physical positions at `t = 3` (IVP test set, PLEI).
    #[rustfmt::skip]
    pub const PUBLISHED_POSITIONS: [[f64; 2]; 7] = [
        [0.3706139143970502, -3.943437585517392],
        [3.237284092057233, -3.27138097397255],
        [-3.222559032418324, 5.225081843456543],
        [0.659709145577531, -2.59061243497747],
        [0.3425581707156584, 1.198213693392275],
        [1.562172101400631, -0.2429682344935824],
        [-0.7003092922212495, 1.09144924042898],
    ];
    /// Published physical velocities at `t = 3` (IVP test set, PLEI).
    #[rustfmt::skip]
    pub const PUBLISHED_VELOCITIES: [[f64; 2]; 7] = [
        [3.417003806314313, -3.74124496123401],
        [1.354584501625501, 0.377345968575063],
        [-2.590065597810775, 0.9386858869551073],
        [2.025053734714242, 0.3667922227200571],
        [-1.155815100160448, -0.347404635380849],
        [-0.8072988170223021, 2.344915448180937],
        [0.595239635420871, -1.947020434263292],
    ];

    /// The published problem.
    pub fn new() -> Self {
        let bodies = Bodies::new(Self::G, Self::MASSES);
        Self {
            bodies,
            period: bodies.kepler_period_at_rms_radius(&Self::POSITIONS),
        }
    }

    /// Physical positions and velocities `(x1, y1, ..., x7, y7)` of a
    /// mass-weighted state: each body's pair divided by `sqrt(m_i)`.
    pub fn physical(&self, s: &State<14>) -> State<14> {
        self.bodies.physical(s)
    }

    /// The mass-weighted state of physical positions and velocities
    /// `(x1, y1, ..., x7, y7)`: each body's pair times `sqrt(m_i)`.
    pub fn mass_weighted(&self, physical: &State<14>) -> State<14> {
        self.bodies.mass_weighted(physical)
    }

    /// The published state at [`Pleiades::PUBLISHED_TIME`], mass-weighted.
    /// Its components agree with a quadruple-precision integration
    /// (`tests/harness/nbody.rs`) to within a few units of their 16th digit.
    pub fn published_end(&self) -> State<14> {
        self.mass_weighted(&Bodies::from_bodies(
            &Self::PUBLISHED_POSITIONS,
            &Self::PUBLISHED_VELOCITIES,
        ))
    }
}

impl Default for Pleiades {
    fn default() -> Self {
        Self::new()
    }
}

impl Parametrised for Pleiades {
    const PARAMETERS: &'static [(&'static str, &'static str)] = &[];
    fn with_parameters(_: &Parameters) -> Result<Self, Error> {
        Ok(Self::new())
    }
}

impl Scene<14> for Pleiades {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "pleiades",
            name: "Pleiades, seven stars in the plane (mass-weighted)",
            dimension: 14,
            parameters: "G = 1, m_i = i, published initial state; state sqrt(m_i) (r_i, r_i')"
                .into(),
            reference: "Hairer, Nørsett, Wanner, Solving ODEs I, II.10; IVP test set (Mazzia, Magherini, Bari, release 2.4), problem PLEI, state at t = 3",
        }
    }

    fn initial(&self) -> State<14> {
        self.mass_weighted(&Bodies::from_bodies(&Self::POSITIONS, &Self::VELOCITIES))
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 14>) -> SVector<R, 14> {
        self.bodies.acceleration(q)
    }

    fn potential<R: Real>(&self, q: &SVector<R, 14>) -> R {
        self.bodies.potential(q)
    }

    fn period(&self) -> f64 {
        self.period
    }

    fn exact(&self, _: f64) -> Option<State<14>> {
        None
    }

    fn default_t_end(&self) -> f64 {
        Self::PUBLISHED_TIME
    }

    fn invariants(&self) -> &'static [Invariant] {
        &[
            Invariant::Energy,
            Invariant::Momentum { axis: 0 },
            Invariant::Momentum { axis: 1 },
            Invariant::AngularMomentum { axis: 2 },
        ]
    }

    fn invariant(&self, which: Invariant, s: &State<14>) -> Option<InvariantValue> {
        let w = self.frequency();
        match which {
            Invariant::Energy => Some(InvariantValue::energy(self, s)),
            Invariant::Momentum { axis } if axis < 2 => Some(InvariantValue::momentum(
                s,
                self.bodies.sqrt_masses(),
                2,
                axis as usize,
                w,
            )),
            Invariant::AngularMomentum { axis: 2 } => {
                Some(InvariantValue::planar_angular_momentum(s, w))
            }
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The IVP test set lists the state as `x1..x7, y1..y7, x'1..x'7,
    /// y'1..y'7`; the tables here are body after body. Both transcriptions
    /// must be the same 28 numbers.
    #[test]
    fn published_tables_are_the_test_sets_list_body_by_body() {
        #[rustfmt::skip]
        const LISTED: [f64; 28] = [
            0.3706139143970502, 3.237284092057233, -3.222559032418324, 0.659709145577531,
            0.3425581707156584, 1.562172101400631, -0.7003092922212495,
            -3.943437585517392, -3.27138097397255, 5.225081843456543, -2.59061243497747,
            1.198213693392275, -0.2429682344935824, 1.09144924042898,
            3.417003806314313, 1.354584501625501, -2.590065597810775, 2.025053734714242,
            -1.155815100160448, -0.8072988170223021, 0.595239635420871,
            -3.74124496123401, 0.377345968575063, 0.9386858869551073, 0.3667922227200571,
            -0.347404635380849, 2.344915448180937, -1.947020434263292,
        ];
        for i in 0..7 {
            for k in 0..2 {
                assert_eq!(Pleiades::PUBLISHED_POSITIONS[i][k], LISTED[7 * k + i]);
                assert_eq!(Pleiades::PUBLISHED_VELOCITIES[i][k], LISTED[14 + 7 * k + i]);
            }
        }
    }

    #[test]
    fn period_is_the_kepler_period_at_the_rms_radius() {
        // centre of mass (6, 7) / 28; sum m_i |r_i - c|^2 = 385 - 28 |c|^2
        let c2 = (36.0 + 49.0) / (28.0 * 28.0);
        let radius = ((385.0 - 28.0 * c2) / 28.0f64).sqrt();
        let period = std::f64::consts::TAU * (radius.powi(3) / 28.0).sqrt();
        assert!((Pleiades::new().period() - period).abs() <= 1e-14 * period);
    }
}
