//! A scene in other units of length and time: the same motion, with every
//! position multiplied by a constant `L` and every time by a constant `T`.
//! Newton's equations are unchanged by it, and so is every scheme that
//! combines states and forces linearly (every Runge-Kutta, splitting,
//! composition and multistep method) when its step is measured in the same
//! units: `h' = T h` gives `h' v' = L h v` and `h'^2 a' = L h^2 a`, so a run
//! in the new units is the same run up to round-off, which it draws anew:
//! every number it computes differs from the original's in all its low bits.
//!
//! Every verdict of the harness is meant to be unit-free (errors are
//! phase-space distances relative to [`Scene::scale`], energies relative to
//! `|E0|`, steps in periods), so a scene in other units must get the same
//! verdicts: that is what this wrapper lets a test check, and what the
//! order study's round-off twins rely on (lengths only, see
//! [`crate::tolerance::TWIN_SCALE`]).

use super::{Invariant, InvariantValue, Scene, SceneMeta};
use crate::error::Error;
use crate::state::{Real, State};
use nalgebra::SVector;

/// `scene` in units of length `L` times smaller and units of time `T` times
/// smaller (a number `L` times, a duration `T` times larger): `q' = L q`,
/// `t' = T t`, `v' = (L / T) v`, `a'(q') = (L / T^2) a(q' / L)`, `V'(q') =
/// (L / T)^2 V(q' / L)`, `period' = T period`, `exact'(t') = exact(t' / T)`
/// mapped, and the invariants mapped by their dimensions (see
/// [`Scene::invariant`] below).
///
/// The Earth's orbit in metres and seconds, from the one in astronomical
/// units and years (`GM = 4 pi^2 AU^3 / yr^2`):
///
/// ```
/// use stepladder::scene::{Harmonic, KeplerCircular, Scaled, Scene};
/// let (au, year) = (1.495978707e11, 3.15576e7); // metres, seconds (Julian year)
/// let si = Scaled::units(KeplerCircular, au, year).unwrap();
/// assert_eq!(si.period(), year);
/// // the Sun's pull at 1 AU is GM_sun / AU^2 (GM_sun = 1.32712440018e20 m^3/s^2),
/// // to the 3e-5 by which the idealised orbit's year is not the Julian one
/// let pull = si.acceleration(&si.initial().q).norm();
/// assert!((pull / (1.32712440018e20 / (au * au)) - 1.0).abs() < 1e-4);
/// // the same state a quarter of a year on, in either units
/// let there = si.exact(0.25 * year).unwrap();
/// assert!(KeplerCircular.phase_distance(&si.back(&there), &KeplerCircular.exact(0.25).unwrap()) < 1e-14);
///
/// // w0 = 1000 is the w0 = 1 oscillator with time in units of 1/1000
/// let fast = Scaled::units(Harmonic::default(), 1.0, 1e-3).unwrap();
/// let direct = Harmonic::new(1000.0, 1.0, 0.0).unwrap();
/// assert!((fast.period() / direct.period() - 1.0).abs() < 1e-15);
/// let t = 0.0123;
/// assert!(direct.phase_distance(&fast.exact(t).unwrap(), &direct.exact(t).unwrap()) < 1e-12);
///
/// assert!(Scaled::units(KeplerCircular, au, 0.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scaled<S> {
    inner: S,
    length: f64,
    time: f64,
    /// `L / T`, the factor on velocities (and momenta per unit mass).
    speed: f64,
    /// `L / T^2`, the factor on accelerations.
    acceleration: f64,
}

impl<S> Scaled<S> {
    /// `inner` in units of length `factor` times smaller, time unchanged.
    ///
    /// ```
    /// use stepladder::scene::{Harmonic, Scaled, Scene};
    /// let osc = Harmonic::default();
    /// let scaled = Scaled::new(osc, 3.0);
    /// assert_eq!(scaled.initial().q[0], 3.0 * osc.initial().q[0]);
    /// let (there, back) = (osc.exact(1.0).unwrap(), scaled.back(&scaled.exact(1.0).unwrap()));
    /// assert!(osc.phase_distance(&there, &back) < 1e-15);
    /// ```
    pub fn new(inner: S, factor: f64) -> Self {
        // with T = 1 every factor below is `factor` exactly, so a scene
        // scaled in length only computes what it did before time entered
        Self::with(inner, factor, 1.0)
    }

    /// `inner` with lengths multiplied by `length` and times by `time`, both
    /// finite and positive.
    pub fn units(inner: S, length: f64, time: f64) -> Result<Self, Error> {
        let length = crate::scene::positive("length", length)?;
        let time = crate::scene::positive("time", time)?;
        Ok(Self::with(inner, length, time))
    }

    fn with(inner: S, length: f64, time: f64) -> Self {
        Self {
            inner,
            length,
            time,
            speed: length / time,
            acceleration: length / (time * time),
        }
    }

    /// The factor on lengths, `L`.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The factor on times, `T`.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// A state of the original scene in these units.
    pub fn there<const D: usize>(&self, s: &State<D>) -> State<D> {
        State::new(s.q * self.length, s.v * self.speed)
    }

    /// A state of the scaled scene in the original units.
    pub fn back<const D: usize>(&self, s: &State<D>) -> State<D> {
        State::new(s.q / self.length, s.v / self.speed)
    }

    /// The power of `T` an invariant scales with (see
    /// [`Invariant::length_power`] for `L`): energy per unit mass is a
    /// velocity squared, `(L / T)^2`; momentum per unit mass a velocity,
    /// `L / T`; angular momentum a length times a velocity, `L^2 / T`.
    pub fn time_power(which: Invariant) -> i32 {
        match which {
            Invariant::Energy => -2,
            Invariant::Momentum { .. } | Invariant::AngularMomentum { .. } => -1,
        }
    }
}

impl<S: Scene<D>, const D: usize> Scene<D> for Scaled<S> {
    fn meta(&self) -> SceneMeta {
        let mut meta = self.inner.meta();
        if self.length != 1.0 || self.time != 1.0 {
            meta.parameters = format!(
                "{}; lengths x {}, times x {}",
                meta.parameters, self.length, self.time
            );
        }
        meta
    }
    fn initial(&self) -> State<D> {
        self.there(&self.inner.initial())
    }
    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        self.inner.acceleration(&(q / R::of(self.length))) * R::of(self.acceleration)
    }
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R {
        let v = R::of(self.speed);
        self.inner.potential(&(q / R::of(self.length))) * v * v
    }
    fn period(&self) -> f64 {
        self.inner.period() * self.time
    }
    fn frequency(&self) -> f64 {
        self.inner.frequency() / self.time
    }
    fn exact(&self, t: f64) -> Option<State<D>> {
        self.inner.exact(t / self.time).map(|s| self.there(&s))
    }
    fn default_t_end(&self) -> f64 {
        self.inner.default_t_end() * self.time
    }
    /// A phase-space distance is a length (`dv / w` is one): `L` times the
    /// inner scene's.
    fn scale(&self) -> f64 {
        self.inner.scale() * self.length
    }
    fn invariants(&self) -> &'static [Invariant] {
        self.inner.invariants()
    }
    /// The inner scene's invariant, in these units: its value times `L^k
    /// T^m` for an invariant of dimension `L^k T^m` ([`Invariant::length_power`],
    /// [`Scaled::time_power`]). Its sensitivity bounds `|dI|` per unit of
    /// phase-space distance, and a distance is a length (`d' = L d`: `dq' =
    /// L dq`, `dv' / w' = (L / T) dv / (w / T) = L dv / w`), so `|dI'| = L^k
    /// T^m |dI| <= L^k T^m s d = L^(k-1) T^m s d'`: the sensitivity scales
    /// with `L^(k-1) T^m`.
    fn invariant(&self, which: Invariant, s: &State<D>) -> Option<InvariantValue> {
        let (k, m) = (which.length_power(), Self::time_power(which));
        let t = self.time.powi(m);
        self.inner
            .invariant(which, &self.back(s))
            .map(|i| InvariantValue {
                value: i.value * self.length.powi(k) * t,
                sensitivity: i.sensitivity * self.length.powi(k - 1) * t,
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Anharmonic, Harmonic, InvariantValue, KeplerCircular, KeplerEccentric};

    /// The mapped invariants are what the scene's own formulas give in the
    /// new units: the energy and sensitivity from `InvariantValue::energy` on the
    /// scaled scene (its potential and frequency), the angular momentum from
    /// `planar_angular_momentum` on the scaled state and frequency.
    #[test]
    fn invariants_are_the_formulas_in_the_new_units() {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * a.abs().max(b.abs());
        for (l, t) in [(1.495978707e11, 3.15576e7), (1e-6, 1e6), (7.0, 1e-3)] {
            let orbit = Scaled::units(KeplerEccentric::default(), l, t).unwrap();
            let s = orbit.exact(0.3 * orbit.period()).unwrap();
            let mapped = orbit.invariant(Invariant::Energy, &s).unwrap();
            let direct = InvariantValue::energy(&orbit, &s);
            assert!(close(mapped.value, direct.value), "{mapped:?} {direct:?}");
            assert!(close(mapped.sensitivity, direct.sensitivity));
            let which = Invariant::AngularMomentum { axis: 2 };
            let mapped = orbit.invariant(which, &s).unwrap();
            let direct = InvariantValue::planar_angular_momentum(&s, orbit.frequency());
            assert!(close(mapped.value, direct.value), "{mapped:?} {direct:?}");
            assert!(close(mapped.sensitivity, direct.sensitivity));
            assert!(
                orbit
                    .invariant(Invariant::Momentum { axis: 0 }, &s)
                    .is_none()
            );
        }
    }

    /// The scaled exact solution solves the scaled equations: `q'' = a(q)`
    /// by a central difference of the exact solution in the new units, and
    /// the energy in the new units is constant along it.
    #[test]
    fn the_exact_solution_solves_the_scaled_equations() {
        fn check<S: Scene<D>, const D: usize>(scene: &S) {
            let (period, scale) = (scene.period(), scene.scale());
            let w = scene.frequency();
            let dt = 1e-3 * period;
            let e0 = scene.energy(&scene.initial());
            for k in 1..8 {
                let t = 0.113 * k as f64 * period;
                let [before, at, after] =
                    [t - dt, t, t + dt].map(|t| scene.exact(t).expect("exact"));
                let second = (after.q - at.q * 2.0 + before.q) / (dt * dt);
                // in units of the motion's acceleration scale w^2 L: the
                // difference's truncation is (w dt)^2 / 12 ~ 3e-6 of it
                let miss = (second - scene.acceleration(&at.q)).norm() / (w * w * scale);
                assert!(miss < 1e-4, "{}: {miss:e}", scene.meta().parameters);
                let drift = (scene.energy(&at) - e0).abs() / e0.abs();
                assert!(drift < 1e-12, "{drift:e}");
            }
        }
        for (l, t) in [(1.495978707e11, 3.15576e7), (1e-6, 1e6), (3e5, 1e-4)] {
            check(&Scaled::units(KeplerCircular, l, t).unwrap());
            check(&Scaled::units(KeplerEccentric::default(), l, t).unwrap());
            check(&Scaled::units(Harmonic::new(2.0, 0.3, -1.0).unwrap(), l, t).unwrap());
        }
    }

    /// Rescaling the time of the `w0 = 1` oscillator by `1 / w0` gives the
    /// `w0` oscillator: the same equation `x'' = -w0^2 x` and start.
    #[test]
    fn a_time_unit_is_a_frequency() {
        let w0 = 1000.0;
        let fast = Scaled::units(Harmonic::default(), 1.0, 1.0 / w0).unwrap();
        let direct = Harmonic::new(w0, 1.0, 0.0).unwrap();
        assert_eq!(fast.initial(), direct.initial());
        let q = nalgebra::Vector1::new(0.37f64);
        let (a, b) = (fast.acceleration(&q)[0], direct.acceleration(&q)[0]);
        assert!((a - b).abs() <= 4.0 * f64::EPSILON * b.abs(), "{a} {b}");
        assert!((fast.period() / direct.period() - 1.0).abs() < 1e-15);
    }

    /// A length-only scale computes what it did before time entered: every
    /// factor is the length factor exactly.
    #[test]
    fn a_length_scale_is_bit_identical_to_multiplying_by_the_factor() {
        let f = 1.0 + 1.0 / (1u64 << 20) as f64;
        let well = Anharmonic::default();
        let scaled = Scaled::new(well, f);
        let q = nalgebra::Vector1::new(0.731f64);
        assert_eq!(
            scaled.acceleration(&q),
            well.acceleration(&(q / f)) * f,
            "acceleration"
        );
        assert_eq!(scaled.potential(&q), well.potential(&(q / f)) * f * f);
        let s = well.initial();
        assert_eq!(scaled.initial(), State::new(s.q * f, s.v * f));
        assert_eq!(scaled.period(), well.period());
    }

    #[test]
    fn rejects_units_that_are_not_finite_and_positive() {
        for (l, t) in [
            (0.0, 1.0),
            (1.0, -2.0),
            (f64::NAN, 1.0),
            (1.0, f64::INFINITY),
        ] {
            assert!(Scaled::units(Harmonic::default(), l, t).is_err(), "{l} {t}");
        }
    }
}
