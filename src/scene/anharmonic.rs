//! Trapped orbits of the anharmonic well `x'' = -k x + k x^3 / alpha^2`,
//! exactly, with Jacobi elliptic functions.

use super::elliptic::{Jacobi, incomplete_f};
use super::well::Well;
use super::{Parameters, Parametrised, Scene, SceneMeta, amplitude};
use crate::error::Error;
use crate::state::{Real, State};
use nalgebra::{SVector, Vector1};

/// A particle trapped in the course notes' anharmonic well: `x'' = -k x + k
/// x^3 / alpha^2`, `V = k x^2 / 2 - k x^4 / (4 alpha^2)`, barrier `E_b = k
/// alpha^2 / 4` at `x = -+alpha`, for any start `(x0, v0)` with `|x0| <
/// alpha` and energy `E = v0^2 / 2 + V(x0) < E_b`.
///
/// # The exact solution
///
/// - **Amplitude.** The turning points `-+A` solve `V(A) = E`, a quadratic in
///   `A^2` with roots `A^2 = alpha^2 (1 - s)` and `B^2 = alpha^2 (1 + s)`,
///   `s = sqrt(1 - E / E_b)`; the trapped orbit turns at the inner one.
///   Because `E_b - V(x) = k (alpha^2 - x^2)^2 / (4 alpha^2)`,
///   `s^2 = (1 - x0^2 / alpha^2)^2 - 2 v0^2 / (k alpha^2)`, free of
///   cancellation until the energy nears the barrier.
/// - **Modulus and frequency.** Try `x = A sn(Omega t + u0 | m)`. From `sn' =
///   cn dn`, `cn^2 = 1 - sn^2`, `dn^2 = 1 - m sn^2` follows `sn'' = -(1 + m)
///   sn + 2 m sn^3`; matching the `sn` and `sn^3` terms with the force gives
///   `Omega^2 (1 + m) = k` and `2 m Omega^2 = k A^2 / alpha^2`, so
///   `m = A^2 / B^2 = (1 - s) / (1 + s)` and `Omega^2 = k (1 + s) / 2`.
///   Then `v = A Omega cn dn`, and at `sn = 0` the energy is `A^2 Omega^2 / 2
///   = k A^2 B^2 / (4 alpha^2) = E`, the product of the roots.
/// - **Phase.** `sn u0 = x0 / A` and `cn u0 = v0 / (A Omega dn u0)`, with
///   `dn^2 u0 = 1 - x0^2 / B^2 = (1 - x0^2/alpha^2 + s) / (1 + s) > 0`, fix the
///   amplitude `phi0 = am u0` in `(-pi, pi]` (`dn > 0`, so `cn` has the sign of
///   `v0`), and `u0 = F(phi0 | m)` inverts it.
/// - **Period.** `sn` has period `4 K(m)`, so `T = 4 K(m) / Omega`. For small
///   amplitudes `m ~ A^2 / (2 alpha^2)`, `K ~ (pi/2)(1 + m/4)`, `Omega ~
///   sqrt(k)(1 - m/2)`, and `T ~ (2 pi / sqrt(k))(1 + 3 A^2 / (8 alpha^2))`:
///   the harmonic period with the Lindstedt-Poincaré correction of a
///   softening cubic force. As `E -> E_b`, `m -> 1` and `T` grows like
///   `ln(1 / (1 - m))`.
///
/// The elliptic functions are computed to a few ulps (see the scene folder's
/// `elliptic` module; A&S 16.12, 17.6; DLMF 19.25.5, 19.36.i); the solution is
/// the classical one for a cubic force (Byrd & Friedman, *Handbook of Elliptic
/// Integrals for Engineers and Scientists*).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Anharmonic {
    well: Well,
    x0: f64,
    v0: f64,
    /// The turning point `A`.
    amplitude: f64,
    /// The parameter `m = A^2 / B^2`.
    m: f64,
    /// The angular frequency `Omega` of the elliptic argument.
    omega: f64,
    /// The argument `u0` at `t = 0`.
    phase: f64,
    /// `sn, cn, dn` of parameter `m`.
    jacobi: Jacobi,
    /// `4 K(m) / Omega`.
    period: f64,
}

impl Default for Anharmonic {
    /// `k = 1, alpha = 1, x0 = 0.5, v0 = 0`: energy `0.109375`, under half the
    /// barrier, yet `m = 1/7` and a period 11% longer than the harmonic `2 pi`.
    fn default() -> Self {
        Self::new(1.0, 1.0, 0.5, 0.0).expect("the default start is trapped")
    }
}

impl Anharmonic {
    /// The orbit of the well with stiffness `k > 0` and barriers at
    /// `-+alpha` (`alpha > 0`) started at `(x0, v0)`, which must be trapped:
    /// `|x0| < alpha` and energy below the barrier `k alpha^2 / 4`.
    ///
    /// ```
    /// use stepladder::scene::{Anharmonic, Scene};
    /// let orbit = Anharmonic::new(1.0, 1.0, 0.5, 0.0).unwrap();
    /// assert!(orbit.period() > 2.0 * std::f64::consts::PI);
    /// // started at the bottom with the barrier's energy: not trapped
    /// assert!(Anharmonic::new(1.0, 1.0, 0.0, 0.5f64.sqrt()).is_err());
    /// assert!(Anharmonic::new(1.0, 1.0, 1.2, 0.0).is_err());
    /// ```
    pub fn new(k: f64, alpha: f64, x0: f64, v0: f64) -> Result<Self, Error> {
        let well = Well::new(k, alpha)?;
        let (x0, v0) = (amplitude("x0", x0)?, amplitude("v0", v0)?);
        if x0 == 0.0 && v0 == 0.0 {
            return Err(Error::InvalidScene(
                "a particle at rest at the bottom of the well never moves: give x0 or v0 a non-zero value"
                    .into(),
            ));
        }
        if x0.abs() >= alpha {
            return Err(Error::InvalidScene(format!(
                "x0 = {x0} is not inside the well: |x0| must be below alpha = {alpha}, where the barrier tops are"
            )));
        }
        let (xr, vr) = (x0 / alpha, v0 / alpha);
        let g = 1.0 - xr * xr;
        // kinetic energy over the barrier height
        let kinetic = 2.0 * vr * vr / k;
        let s2 = g * g - kinetic;
        // never NaN: g <= 1, and an overflowing speed makes s2 = -inf
        if s2 <= 0.0 {
            let energy = 0.5 * v0 * v0 + well.potential(x0);
            return Err(Error::InvalidScene(format!(
                "energy E = {energy} is not below the barrier k alpha^2/4 = {}: the orbit is not trapped (E = barrier from x0 = 0 is the separatrix scene)",
                well.barrier()
            )));
        }
        let s = s2.sqrt();
        // 1 - s as (1 - s^2) / (1 + s): small amplitudes keep their digits
        let one_minus_s = (xr * xr * (2.0 - xr * xr) + kinetic) / (1.0 + s);
        let m = one_minus_s / (1.0 + s);
        if m >= 1.0 {
            return Err(Error::InvalidScene(format!(
                "x0 = {x0}, v0 = {v0} is within rounding of the barrier energy {}: the period is not representable",
                well.barrier()
            )));
        }
        let amplitude = alpha * one_minus_s.sqrt();
        let omega = (0.5 * k * (1.0 + s)).sqrt();
        let jacobi = Jacobi::new(m);
        // sin(phi0) = x0 / A and cos(phi0) = v0 / (A Omega dn0), both scaled
        // by A Omega dn0 > 0, which leaves the angle alone
        let dn0 = ((g + s) / (1.0 + s)).sqrt();
        let phi0 = (x0 * omega * dn0).atan2(v0);
        let phase = incomplete_f(phi0, m);
        let period = 4.0 * jacobi.quarter_period() / omega;
        Ok(Self {
            well,
            x0,
            v0,
            amplitude,
            m,
            omega,
            phase,
            jacobi,
            period,
        })
    }

    /// The turning point `A`: the orbit spans `[-A, A]`.
    pub fn amplitude(&self) -> f64 {
        self.amplitude
    }

    /// The elliptic parameter `m = A^2 / B^2` in `[0, 1)`: 0 in the harmonic
    /// limit, 1 on the separatrix.
    pub fn parameter(&self) -> f64 {
        self.m
    }

    /// The barrier height `k alpha^2 / 4`.
    pub fn barrier(&self) -> f64 {
        self.well.barrier()
    }
}

impl Parametrised for Anharmonic {
    const PARAMETERS: &'static [(&'static str, &'static str)] = &[
        ("k", "stiffness (default 1)"),
        ("alpha", "position of the barrier tops (default 1)"),
        ("x0", "initial position, inside the well (default 0.5)"),
        (
            "v0",
            "initial velocity, below the barrier's energy (default 0)",
        ),
    ];
    fn with_parameters(p: &Parameters) -> Result<Self, Error> {
        let d = Self::default();
        Self::new(
            p.get("k", d.well.k()),
            p.get("alpha", d.well.alpha()),
            p.get("x0", d.x0),
            p.get("v0", d.v0),
        )
    }
}

impl Scene<1> for Anharmonic {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "anharmonic",
            name: "anharmonic well",
            dimension: 1,
            parameters: format!(
                "{}, x0 = {}, v0 = {}",
                self.well.parameters(),
                self.x0,
                self.v0
            ),
            reference: "x'' = -k x + k x^3/alpha^2; x(t) = A sn(Omega t + u0 | m), T = 4 K(m)/Omega (course notes' anharmonic well; A&S 16.12, 17.6)",
        }
    }

    fn initial(&self) -> State<1> {
        State::new(Vector1::new(self.x0), Vector1::new(self.v0))
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 1>) -> SVector<R, 1> {
        Vector1::new(self.well.acceleration(q[0]))
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        self.well.potential(q[0])
    }

    /// The true period `4 K(m) / Omega`, longer than the harmonic `2 pi /
    /// sqrt(k)`.
    fn period(&self) -> f64 {
        self.period
    }

    fn exact(&self, t: f64) -> Option<State<1>> {
        let (sn, cn, dn) = self.jacobi.sn_cn_dn(self.omega * t + self.phase);
        Some(State::new(
            Vector1::new(self.amplitude * sn),
            Vector1::new(self.amplitude * self.omega * cn * dn),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Harmonic;
    use std::f64::consts::TAU;

    const EPS: f64 = f64::EPSILON;

    /// Trapped starts of every kind: the default, moving either way, from
    /// the bottom, from a turning point, tiny, close to the barrier in
    /// energy and close to it in position.
    fn orbits() -> Vec<Anharmonic> {
        [
            (1.0, 1.0, 0.5, 0.0),
            (2.0, 0.8, -0.3, 0.4),
            (2.0, 0.8, -0.3, -0.4),
            (1.0, 1.0, 0.0, 0.5),
            (0.3, 2.0, 0.0, -0.5),
            (9.0, 1.5, 1.2, 0.0),
            (1.0, 1.0, 1e-3, 0.0),
            (1.0, 1.0, 0.0, 0.999 * 0.5f64.sqrt()),
            (1.0, 1.0, 0.99, 1e-3),
            (4.0, 0.5, -0.2, 0.5),
        ]
        .iter()
        .map(|&(k, a, x, v)| Anharmonic::new(k, a, x, v).unwrap())
        .collect()
    }

    /// The phase-space size `A + A Omega / w` of the orbit: the unit errors
    /// are judged in.
    fn size(o: &Anharmonic) -> f64 {
        o.amplitude * (1.0 + o.omega / o.frequency())
    }

    /// Eighth-order central difference, as in the elliptic tests.
    fn derivative(f: impl Fn(f64) -> f64, t: f64, h: f64) -> f64 {
        const C: [f64; 4] = [4.0 / 5.0, -1.0 / 5.0, 4.0 / 105.0, -1.0 / 280.0];
        C.iter()
            .enumerate()
            .map(|(i, c)| {
                let dh = (i + 1) as f64 * h;
                c * (f(t + dh) - f(t - dh))
            })
            .sum::<f64>()
            / h
    }

    #[test]
    fn exact_solution_starts_at_the_initial_state() {
        for o in orbits() {
            let d = o.phase_distance(&o.exact(0.0).unwrap(), &o.initial());
            // u0 = F(phi0) is good to a few ulps of K and sn moves at most
            // A per unit of u: a few ulps of the orbit's size
            assert!(
                d <= 16.0 * EPS * size(&o),
                "{:?}: {d:e}",
                o.meta().parameters
            );
        }
    }

    #[test]
    fn energy_is_conserved_along_the_exact_solution() {
        for o in orbits() {
            let e0 = o.energy(&o.initial());
            for i in 0..300 {
                let t = 3.0 * o.period() * i as f64 / 299.0 * (1.0 - 1e-3 * 2f64.sqrt());
                let e = o.energy(&o.exact(t).unwrap());
                // x and v to a few ulps make E good to a few ulps of itself
                assert!(
                    (e - e0).abs() <= 16.0 * EPS * e0,
                    "{}: E({t}) = {e}, E0 = {e0}",
                    o.meta().parameters
                );
            }
        }
    }

    #[test]
    fn exact_solution_satisfies_the_equation_of_motion() {
        for o in orbits() {
            let k = o.well.k();
            // a step on the time scale of the well's bottom, 1/sqrt(k),
            // which is also the fastest the orbit ever changes: truncation
            // h^8 |x^(9)| / 630 and round-off 2 eps |x| / h both near 1e-13
            let h = 0.02 / k.sqrt();
            let x = |t| o.exact(t).unwrap().q[0];
            let v = |t| o.exact(t).unwrap().v[0];
            let (vmax, amax) = (o.amplitude * o.omega, o.amplitude * k);
            for i in 0..100 {
                let t = 2.0 * o.period() * i as f64 / 99.0 - 0.3 * o.period();
                let s = o.exact(t).unwrap();
                let a = o.acceleration(&s.q)[0];
                let (rx, rv) = (derivative(x, t, h) - s.v[0], derivative(v, t, h) - a);
                assert!(
                    rx.abs() <= 2e-12 * vmax && rv.abs() <= 2e-12 * amax,
                    "{} at t = {t}: x' - v = {rx:e}, v' - a = {rv:e}",
                    o.meta().parameters
                );
            }
        }
    }

    #[test]
    fn exact_solution_is_periodic_and_odd_over_half_a_period() {
        for o in orbits() {
            let p = o.period();
            for i in 0..20 {
                let t = 0.37 * p * i as f64;
                let s = o.exact(t).unwrap();
                let full = o.exact(t + p).unwrap();
                // the force is odd, so half a period later the state is mirrored
                let half = o.exact(t + 0.5 * p).unwrap();
                let mirrored = State::new(-half.q, -half.v);
                // the argument t + p is rounded: a few ulps of the phase
                let tol = 8.0 * EPS * size(&o) * (1.0 + o.omega * (t + p));
                assert!(
                    o.phase_distance(&s, &full) <= tol,
                    "{}",
                    o.meta().parameters
                );
                assert!(
                    o.phase_distance(&s, &mirrored) <= tol,
                    "{}",
                    o.meta().parameters
                );
            }
        }
    }

    #[test]
    fn default_orbit_is_clearly_anharmonic() {
        // E = 1/8 - 1/64 = 7/64, E_b = 1/4, s = sqrt(1 - 7/16) = 3/4,
        // m = (1/4)/(7/4) = 1/7, Omega^2 = (1 + 3/4)/2 = 7/8, A^2 = 1/4
        let o = Anharmonic::default();
        assert!((o.parameter() - 1.0 / 7.0).abs() <= 2.0 * EPS);
        assert!((o.amplitude() - 0.5).abs() <= 2.0 * EPS);
        assert!((o.omega - (7.0f64 / 8.0).sqrt()).abs() <= 2.0 * EPS);
        assert!((o.barrier() - 0.25).abs() <= EPS);
        assert!(o.period() > 1.1 * TAU, "T = {}", o.period());
        assert_eq!(o.meta().id, "anharmonic");
    }

    #[test]
    fn small_amplitudes_approach_the_harmonic_period() {
        for (k, alpha) in [(1.0, 1.0), (4.0, 0.3)] {
            let harmonic = TAU / f64::sqrt(k);
            for x0 in [1e-2, 1e-3] {
                let o = Anharmonic::new(k, alpha, x0 * alpha, 0.0).unwrap();
                let r2 = (o.amplitude() / alpha).powi(2);
                // T = (2 pi / sqrt(k)) (1 + 3 A^2 / (8 alpha^2) + O(A^4))
                let correction = (o.period() / harmonic - 1.0) / r2;
                assert!(
                    (correction - 3.0 / 8.0).abs() < 2.0 * r2 + 1e-14 / r2,
                    "k = {k}, x0 = {x0}: (T/T0 - 1) alpha^2/A^2 = {correction}"
                );
            }
        }
        // and the motion itself becomes the oscillator's, phase included
        let (k, x0, v0) = (2.0, 1e-4, -3e-4);
        let o = Anharmonic::new(k, 1.0, x0, v0).unwrap();
        let h = Harmonic::new(k.sqrt(), x0, v0).unwrap();
        for i in 0..50 {
            let t = 0.29 * i as f64;
            let d = o.phase_distance(&o.exact(t).unwrap(), &h.exact(t).unwrap());
            // the cubic force shifts the phase by about (3/8)(A/alpha)^2 per radian
            assert!(d < 1e-6 * size(&o), "t = {t}: {d:e}");
        }
    }

    #[test]
    fn rejects_untrapped_and_bad_input() {
        let barrier_speed = 0.5f64.sqrt(); // v0 with E = E_b from x0 = 0, k = alpha = 1
        for (k, alpha, x0, v0) in [
            (0.0, 1.0, 0.5, 0.0),
            (-1.0, 1.0, 0.5, 0.0),
            (f64::NAN, 1.0, 0.5, 0.0),
            (1.0, 0.0, 0.5, 0.0),
            (1.0, f64::INFINITY, 0.5, 0.0),
            (1.0, 1.0, f64::NAN, 0.0),
            (1.0, 1.0, 0.5, f64::NEG_INFINITY),
            (1.0, 1.0, 0.0, 0.0),
            (1.0, 1.0, 1.0, 0.0),
            (1.0, 1.0, -1.5, 0.0),
            (1.0, 1.0, 0.0, barrier_speed),
            (1.0, 1.0, 0.0, -1.01 * barrier_speed),
            (1.0, 1.0, 0.9, 0.3),
            (1.0, 1.0, 0.5, 1e200),
        ] {
            let r = Anharmonic::new(k, alpha, x0, v0);
            assert!(
                r.is_err(),
                "accepted k = {k}, alpha = {alpha}, x0 = {x0}, v0 = {v0}"
            );
        }
        let message = Anharmonic::new(1.0, 1.0, 0.0, 1.0).unwrap_err().to_string();
        assert!(message.contains("not below the barrier"), "{message}");
        let message = Anharmonic::new(1.0, 1.0, 1.0, 0.0).unwrap_err().to_string();
        assert!(message.contains("not inside the well"), "{message}");
    }
}
