//! The 1-D harmonic oscillator `x'' = -w0^2 x`.

use super::{Parameters, Parametrised, Scene, SceneMeta, amplitude, scale};
use crate::error::Error;
use crate::state::{Real, State};
use nalgebra::{SVector, Vector1};
use std::f64::consts::TAU;

/// The harmonic oscillator `x'' = -w0^2 x`, `V = w0^2 x^2 / 2`, with exact
/// solution `x(t) = A cos(w0 t) + B sin(w0 t)`, `A = x0`, `B = v0 / w0`.
///
/// Source: the course notes' harmonic oscillator (Taylor, *Classical
/// Mechanics*, 5.1-5.2). A large `w0` at a fixed step makes it stiff.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Harmonic {
    w0: f64,
    x0: f64,
    v0: f64,
}

impl Default for Harmonic {
    /// `x0 = 1, v0 = 0, w0 = 1`: the solution is `cos t`, the period `2 pi`.
    fn default() -> Self {
        Self {
            w0: 1.0,
            x0: 1.0,
            v0: 0.0,
        }
    }
}

impl Harmonic {
    /// An oscillator with angular frequency `w0 > 0` started at `(x0, v0)`.
    ///
    /// ```
    /// use stepladder::scene::{Harmonic, Scene};
    /// let osc = Harmonic::new(2.0, 1.0, 0.0).unwrap();
    /// assert_eq!(osc.period(), std::f64::consts::PI);
    /// assert!(Harmonic::new(-1.0, 1.0, 0.0).is_err());
    /// ```
    pub fn new(w0: f64, x0: f64, v0: f64) -> Result<Self, Error> {
        let (w0, x0, v0) = (scale("w0", w0)?, amplitude("x0", x0)?, amplitude("v0", v0)?);
        if x0 == 0.0 && v0 == 0.0 {
            return Err(Error::InvalidScene(
                "the oscillator at rest at x = 0 never moves: give x0 or v0 a non-zero value"
                    .into(),
            ));
        }
        Ok(Self { w0, x0, v0 })
    }

    /// The angular frequency `w0`.
    pub fn w0(&self) -> f64 {
        self.w0
    }
}

impl Parametrised for Harmonic {
    const PARAMETERS: &'static [(&'static str, &'static str)] = &[
        ("w0", "angular frequency (default 1)"),
        ("x0", "initial position (default 1)"),
        ("v0", "initial velocity (default 0)"),
    ];
    fn with_parameters(p: &Parameters) -> Result<Self, Error> {
        let d = Self::default();
        Self::new(p.get("w0", d.w0), p.get("x0", d.x0), p.get("v0", d.v0))
    }
}

impl Scene<1> for Harmonic {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "harmonic",
            name: "harmonic oscillator",
            dimension: 1,
            parameters: format!("w0 = {}, x0 = {}, v0 = {}", self.w0, self.x0, self.v0),
            reference: "x'' = -w0^2 x; x(t) = x0 cos(w0 t) + (v0/w0) sin(w0 t) (Taylor, Classical Mechanics, 5.2)",
        }
    }

    fn initial(&self) -> State<1> {
        State::new(Vector1::new(self.x0), Vector1::new(self.v0))
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 1>) -> SVector<R, 1> {
        q * -R::of(self.w0 * self.w0)
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        R::of(0.5 * self.w0 * self.w0) * q[0] * q[0]
    }

    fn period(&self) -> f64 {
        TAU / self.w0
    }

    fn exact(&self, t: f64) -> Option<State<1>> {
        let (a, b) = (self.x0, self.v0 / self.w0);
        let (s, c) = (self.w0 * t).sin_cos();
        Some(State::new(
            Vector1::new(a * c + b * s),
            Vector1::new(self.w0 * (b * c - a * s)),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_solution_starts_at_the_initial_state_and_conserves_energy() {
        let osc = Harmonic::new(3.0, 0.5, -2.0).unwrap();
        let s0 = osc.exact(0.0).unwrap();
        assert_eq!(s0, osc.initial());
        let e0 = osc.energy(&s0);
        for k in 0..100 {
            let s = osc.exact(0.37 * k as f64).unwrap();
            assert!((osc.energy(&s) - e0).abs() <= 4.0 * f64::EPSILON * e0);
        }
    }

    #[test]
    fn exact_solution_is_periodic() {
        let osc = Harmonic::new(1.7, 1.0, 0.3).unwrap();
        let p = osc.period();
        let (a, b) = (osc.exact(0.2).unwrap(), osc.exact(0.2 + p).unwrap());
        assert!(osc.phase_distance(&a, &b) < 1e-14);
    }

    #[test]
    fn rejects_bad_parameters() {
        assert!(Harmonic::new(0.0, 1.0, 0.0).is_err());
        assert!(Harmonic::new(f64::NAN, 1.0, 0.0).is_err());
        assert!(Harmonic::new(1.0, f64::INFINITY, 0.0).is_err());
        assert!(Harmonic::new(1.0, 0.0, 0.0).is_err());
    }
}
