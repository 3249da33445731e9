//! Scenes: Newtonian problems `q'' = a(q)` with a potential, a time scale and,
//! where one exists, an exact solution to judge a scheme against.
//!
//! A scene models only what it needs: the oscillator is 1-D, the orbit 2-D,
//! and a force evaluation is a handful of flops on stack vectors.

mod anharmonic;
mod counted;
mod elliptic;
mod harmonic;
mod hidden;
mod invariant;
mod kepler;
mod potential;
mod precise_energy;
mod scaled;
mod separatrix;
mod well;
mod well_orbit;

pub use anharmonic::Anharmonic;
pub use counted::Counted;
pub use harmonic::Harmonic;
pub use hidden::Hidden;
pub use invariant::{Invariant, InvariantValue};
pub use kepler::{KeplerCircular, KeplerEccentric};
pub use potential::{FromPotential, Potential};
pub use precise_energy::PreciseEnergy;
pub use scaled::Scaled;
pub use separatrix::Separatrix;
pub use well_orbit::WellOrbit;

use crate::error::Error;
use crate::state::{Real, State};
use nalgebra::SVector;
use serde::Serialize;
use std::f64::consts::TAU;

/// What a scene is, for listings, records and the report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SceneMeta {
    /// Kebab-case identifier used on the command line.
    pub id: &'static str,
    /// Human-readable name.
    pub name: &'static str,
    /// Degrees of freedom of the position (1 for the oscillator, 2 for the orbit).
    pub dimension: usize,
    /// The parameters this instance was built with, as `name = value` pairs.
    pub parameters: String,
    /// Where the problem and its exact solution come from.
    pub reference: &'static str,
}

/// A conservative Newtonian problem `q'' = a(q) = -grad V(q)` in `D` dimensions.
///
/// `acceleration` and `potential` are generic over the scalar so that studies
/// can differentiate them (tangent maps, force against `-grad V`); for `f64`
/// they compile to plain arithmetic.
pub trait Scene<const D: usize> {
    /// Identity and parameters.
    fn meta(&self) -> SceneMeta;

    /// The state at `t = 0`.
    fn initial(&self) -> State<D>;

    /// The acceleration `a(q)`; one call is one force evaluation.
    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D>;

    /// The potential energy per unit mass `V(q)`.
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R;

    /// The natural time scale: the period of the motion.
    fn period(&self) -> f64;

    /// The exact state at time `t`, when the scene has a closed form.
    fn exact(&self, t: f64) -> Option<State<D>>;

    /// The total energy per unit mass `|v|^2 / 2 + V(q)`.
    fn energy(&self, s: &State<D>) -> f64 {
        0.5 * s.v.norm_squared() + self.potential(&s.q)
    }

    /// What the exact flow conserves (see [`Invariant`]): the energy
    /// always; linear and angular momentum where the scene has the
    /// symmetry. On a scene without an exact solution the order study
    /// checks that each returns to its initial value as `h -> 0`.
    fn invariants(&self) -> &'static [Invariant] {
        &[Invariant::Energy]
    }

    /// The value of `which` at `s` with its sensitivity to a phase-space
    /// error; `None` for an invariant the scene does not declare. Scenes
    /// with momenta override this and [`Scene::invariants`] together.
    fn invariant(&self, which: Invariant, s: &State<D>) -> Option<InvariantValue> {
        match which {
            Invariant::Energy => Some(InvariantValue::energy(self, s)),
            _ => None,
        }
    }

    /// The angular frequency `2 pi / period` that turns velocities into lengths.
    fn frequency(&self) -> f64 {
        TAU / self.period()
    }

    /// Phase-space distance between two states, in length units:
    /// `sqrt(|dq|^2 + |dv / w|^2)` with `w = 2 pi / period`, so position and
    /// velocity errors weigh alike whatever the units of time.
    fn phase_distance(&self, a: &State<D>, b: &State<D>) -> f64 {
        let w = self.frequency();
        ((a.q - b.q).norm_squared() + ((a.v - b.v) / w).norm_squared()).sqrt()
    }

    /// The size of the motion in the same units: the phase-space norm of the
    /// initial state. Errors are judged small or large against it.
    fn scale(&self) -> f64 {
        let s = self.initial();
        (s.q.norm_squared() + (s.v / self.frequency()).norm_squared()).sqrt()
    }

    /// The default end time of an accuracy run: 2 sqrt(2) periods, an
    /// irrational multiple, so no error cancellation at a half or whole period
    /// can flatter a scheme.
    fn default_t_end(&self) -> f64 {
        2.0 * std::f64::consts::SQRT_2 * self.period()
    }
}

/// A reference to a scene is the scene, so wrappers can borrow it.
impl<S: Scene<D>, const D: usize> Scene<D> for &S {
    fn meta(&self) -> SceneMeta {
        (**self).meta()
    }
    fn initial(&self) -> State<D> {
        (**self).initial()
    }
    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        (**self).acceleration(q)
    }
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R {
        (**self).potential(q)
    }
    fn period(&self) -> f64 {
        (**self).period()
    }
    fn exact(&self, t: f64) -> Option<State<D>> {
        (**self).exact(t)
    }
    fn energy(&self, s: &State<D>) -> f64 {
        (**self).energy(s)
    }
    fn invariants(&self) -> &'static [Invariant] {
        (**self).invariants()
    }
    fn invariant(&self, which: Invariant, s: &State<D>) -> Option<InvariantValue> {
        (**self).invariant(which, s)
    }
    fn frequency(&self) -> f64 {
        (**self).frequency()
    }
    fn phase_distance(&self, a: &State<D>, b: &State<D>) -> f64 {
        (**self).phase_distance(a, b)
    }
    fn scale(&self) -> f64 {
        (**self).scale()
    }
    fn default_t_end(&self) -> f64 {
        (**self).default_t_end()
    }
}

/// Rejects a parameter that must be a finite, strictly positive number.
#[doc(hidden)]
pub fn positive(name: &'static str, value: f64) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            expected: "a finite number > 0",
        })
    }
}

/// The range of a scene parameter's magnitude, `[1e-50, 1e50]`: forces,
/// energies and the squared distances the studies take of errors are
/// products of up to four such quantities, which then stay within
/// `[1e-200, 1e200]`, inside the doubles' normal range `[2.2e-308,
/// 1.8e308]` with a hundred decades for an error to grow before it
/// overflows, or to shrink before it underflows.
pub const MAGNITUDES: [f64; 2] = [1e-50, 1e50];

/// Rejects a scale (a frequency, a stiffness, a length) that is not a
/// finite positive number within [`MAGNITUDES`].
#[doc(hidden)]
pub fn scale(name: &'static str, value: f64) -> Result<f64, Error> {
    if (MAGNITUDES[0]..=MAGNITUDES[1]).contains(&value) {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            expected: "a number in [1e-50, 1e50], so that forces, energies and squared errors \
                       stay within double precision",
        })
    }
}

/// Rejects an initial coordinate that is not zero or of a magnitude within
/// [`MAGNITUDES`].
#[doc(hidden)]
pub fn amplitude(name: &'static str, value: f64) -> Result<f64, Error> {
    if value == 0.0 || (value.abs() >= MAGNITUDES[0] && value.abs() <= MAGNITUDES[1]) {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            expected: "0 or a number of magnitude in [1e-50, 1e50], so that forces, energies \
                       and squared errors stay within double precision",
        })
    }
}

/// Rejects a step that is not in `[SCAN_START / w, SCAN_END / w]`, `w` the
/// scene's angular frequency: the stability study's scan. Above it, it
/// calls a scheme stable at every step, so a step beyond tests nothing the
/// scan has not, and a tangent map or state growing like a power of `h w`
/// soon leaves the doubles; below it a step changes the state by less than
/// its rounding can show over a study's run, so any scheme would look exact.
#[doc(hidden)]
pub fn step(name: &'static str, h: f64, frequency: f64) -> Result<f64, Error> {
    use crate::tolerance::{SCAN_END, SCAN_START};
    use crate::wording::figure;
    let h = positive(name, h)?;
    let (smallest, largest) = (SCAN_START / frequency, SCAN_END / frequency);
    if !(smallest..=largest).contains(&h) {
        return Err(Error::OutOfRange {
            name,
            value: h,
            expected: format!(
                "a step in [{}, {}]: h w in [{}, {}] (w = {} the scene's angular frequency), \
                 the stability scan's range",
                figure(smallest),
                figure(largest),
                figure(SCAN_START),
                figure(SCAN_END),
                figure(frequency),
            ),
        });
    }
    Ok(h)
}

/// Something to do with one scene, whatever its type and dimension.
pub trait SceneVisitor {
    /// What the visit produces.
    type Output;
    /// Called with the chosen scene.
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> Self::Output;
}

macro_rules! scenes {
    ($($variant:ident($ty:ty, $dim:literal)),* $(,)?) => {
        /// Any built-in scene: the registry the CLI, the report and the tests
        /// loop over. Adding a scene is one file plus one line here.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum AnyScene {
            $(
                #[doc = concat!("[`", stringify!($ty), "`]")]
                $variant($ty),
            )*
        }

        impl AnyScene {
            /// Every built-in scene with its default parameters.
            pub fn all() -> Vec<AnyScene> {
                vec![$(AnyScene::$variant(<$ty>::default())),*]
            }

            /// The scene a command line names: an id, optionally followed by
            /// `:name=value,name=value` to change parameters from their defaults.
            ///
            /// ```
            /// use stepladder::scene::AnyScene;
            /// let stiff = AnyScene::parse("harmonic:w0=50").unwrap();
            /// assert!((stiff.period() - std::f64::consts::TAU / 50.0).abs() < 1e-15);
            /// assert!(AnyScene::parse("harmonic:w0=-1").is_err());
            /// assert!(AnyScene::parse("harmonic:spring=3").is_err());
            /// assert!(AnyScene::parse("saturn").is_err());
            /// ```
            pub fn parse(spec: &str) -> Result<AnyScene, Error> {
                let (id, rest) = spec.split_once(':').unwrap_or((spec, ""));
                let params = Parameters::parse(rest)?;
                $(
                    if id == <$ty>::default().meta().id {
                        params.only(id, <$ty>::PARAMETERS)?;
                        return Ok(AnyScene::$variant(<$ty>::with_parameters(&params)?));
                    }
                )*
                Err(Error::UnknownScene { id: id.to_string(), valid: scene_ids().join(", ") })
            }

            /// The parameters this scene accepts, with their meanings.
            pub fn accepts(&self) -> &'static [(&'static str, &'static str)] {
                match self {
                    $(AnyScene::$variant(_) => <$ty>::PARAMETERS,)*
                }
            }

            /// Runs `visitor` on the scene.
            pub fn visit<V: SceneVisitor>(&self, visitor: V) -> V::Output {
                match self {
                    $(AnyScene::$variant(s) => visitor.visit::<$ty, $dim>(s),)*
                }
            }
        }
    };
}

// `Separatrix` is left out on purpose: its orbit creeps up to the unstable
// barrier top, where any error grows exponentially, so an order study there
// would measure the instability rather than the scheme.
scenes![
    Harmonic(Harmonic, 1),
    KeplerCircular(KeplerCircular, 2),
    KeplerEccentric(KeplerEccentric, 2),
    Anharmonic(Anharmonic, 1),
];

/// Reads `(metadata, period)` off any scene.
struct Describe;
impl SceneVisitor for Describe {
    type Output = (SceneMeta, f64);
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        s: &S,
    ) -> (SceneMeta, f64) {
        (s.meta(), s.period())
    }
}

impl AnyScene {
    /// The scene's metadata.
    pub fn meta(&self) -> SceneMeta {
        self.visit(Describe).0
    }

    /// The scene's period.
    pub fn period(&self) -> f64 {
        self.visit(Describe).1
    }
}

/// A scene that can be built from named numeric parameters.
pub trait Parametrised: Sized + Default {
    /// Every parameter's name and meaning.
    const PARAMETERS: &'static [(&'static str, &'static str)];
    /// The scene with these parameters, the others at their defaults.
    fn with_parameters(params: &Parameters) -> Result<Self, Error>;
}

/// Named values from a scene specification such as `w0=50,x0=2`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Parameters(Vec<(String, f64)>);

impl Parameters {
    /// Reads `name=value` pairs separated by commas (an empty text is none).
    /// A name given twice is refused, not settled by the last one, and so is
    /// an empty item between commas: either is more likely a typing slip
    /// than a choice, and a run with a parameter the user did not mean is a
    /// silently wrong number.
    ///
    /// ```
    /// use stepladder::scene::Parameters;
    /// assert_eq!(Parameters::parse("w0=50, x0=2").unwrap().get("x0", 1.0), 2.0);
    /// assert!(Parameters::parse("").is_ok());
    /// assert!(Parameters::parse("w0=50,w0=5").is_err());
    /// assert!(Parameters::parse("w0=50,,x0=2").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Self, Error> {
        let mut out: Vec<(String, f64)> = Vec::new();
        if text.trim().is_empty() {
            return Ok(Self(out));
        }
        for item in text.split(',').map(str::trim) {
            let parsed = item
                .split_once('=')
                .and_then(|(n, v)| Some((n.trim(), v.trim().parse::<f64>().ok()?)));
            match parsed {
                Some((name, _)) if out.iter().any(|(n, _)| n == name) => {
                    return Err(Error::InvalidScene(format!(
                        "'{name}' is given twice in '{text}'"
                    )));
                }
                Some((name, value)) if !name.is_empty() => out.push((name.to_string(), value)),
                _ if item.is_empty() => {
                    return Err(Error::InvalidScene(format!(
                        "'{text}' has an empty item: expected name=number between commas"
                    )));
                }
                _ => {
                    return Err(Error::InvalidScene(format!(
                        "cannot read '{item}': expected name=number"
                    )));
                }
            }
        }
        Ok(Self(out))
    }

    /// The value given for `name`, or `default`.
    pub fn get(&self, name: &str, default: f64) -> f64 {
        self.0
            .iter()
            .rev()
            .find(|(n, _)| n == name)
            .map_or(default, |(_, v)| *v)
    }

    /// Refuses names that `scene` does not have.
    pub fn only(&self, scene: &str, allowed: &[(&str, &str)]) -> Result<(), Error> {
        for (name, _) in &self.0 {
            if !allowed.iter().any(|(a, _)| a == name) {
                let valid: Vec<&str> = allowed.iter().map(|(a, _)| *a).collect();
                return Err(Error::InvalidScene(format!(
                    "'{scene}' has no parameter '{name}'; its parameters: {}",
                    if valid.is_empty() {
                        "none".to_string()
                    } else {
                        valid.join(", ")
                    }
                )));
            }
        }
        Ok(())
    }
}

/// Every built-in scene id, in registry order.
pub fn scene_ids() -> Vec<&'static str> {
    AnyScene::all().iter().map(|s| s.meta().id).collect()
}

mod nbody;
mod outer_solar_system;
mod pleiades;
pub use outer_solar_system::OuterSolarSystem;
pub use pleiades::Pleiades;

/// What relative energy errors are relative to: `|E0|`, or for a scene with
/// zero energy its kinetic energy scale, so the ratio stays finite.
pub fn energy_norm<S: Scene<D>, const D: usize>(scene: &S) -> f64 {
    let e0 = scene.energy(&scene.initial());
    if e0 != 0.0 {
        e0.abs()
    } else {
        0.5 * (scene.frequency() * scene.scale()).powi(2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Names and values are trimmed, an empty text has none, and a
    /// parameter given twice or an empty item between commas is refused
    /// with what was typed; a name with no number is refused as before.
    #[test]
    fn parameters_refuse_a_name_twice_and_an_empty_item() {
        let p = Parameters::parse(" w0 = 50 , x0=2").unwrap();
        assert_eq!(
            (p.get("w0", 1.0), p.get("x0", 1.0), p.get("v0", 7.0)),
            (50.0, 2.0, 7.0)
        );
        assert_eq!(Parameters::parse("  ").unwrap(), Parameters::default());
        let refused = |text: &str| match Parameters::parse(text) {
            Err(Error::InvalidScene(m)) => m,
            other => panic!("{text}: {other:?}"),
        };
        assert!(refused("w0=1,x0=2,w0=3").contains("'w0' is given twice in 'w0=1,x0=2,w0=3'"));
        for text in ["w0=1,,x0=2", "w0=1,", ",w0=1"] {
            assert!(refused(text).contains("has an empty item"), "{text}");
        }
        assert!(refused("w0").contains("cannot read 'w0'"));
        assert!(refused("=3").contains("cannot read '=3'"));
    }
}
