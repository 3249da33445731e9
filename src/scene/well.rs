//! The course notes' anharmonic well: the force law shared by every orbit in
//! it, trapped ([`super::Anharmonic`]) or on the separatrix
//! ([`super::Separatrix`]).

use super::scale;
use crate::error::Error;
use crate::state::Real;

/// The force `F = -k x + k x^3 / alpha^2` per unit mass, from the potential
/// `V = k x^2 / 2 - k x^4 / (4 alpha^2)`: a well of small-oscillation
/// frequency `sqrt(k)` between two maxima of height `E_b = k alpha^2 / 4` at
/// `x = -+alpha`, beyond which the particle escapes.
///
/// `E_b - V(x) = k (alpha^2 - x^2)^2 / (4 alpha^2)`, a perfect square, which
/// is how the orbits measure their distance from the barrier without
/// cancellation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Well {
    /// Stiffness at the bottom, `V''(0)`.
    k: f64,
    /// Position of the barrier tops.
    alpha: f64,
    /// `k / alpha^2`, the coefficient of the cubic force.
    quartic: f64,
}

impl Well {
    /// The well with stiffness `k > 0` and barriers at `-+alpha`, `alpha > 0`.
    pub(crate) fn new(k: f64, alpha: f64) -> Result<Self, Error> {
        let (k, alpha) = (scale("k", k)?, scale("alpha", alpha)?);
        let quartic = k / alpha / alpha;
        let barrier = 0.25 * k * alpha * alpha;
        // both coefficients enter every force and energy: a well whose
        // coefficients overflow or underflow cannot be computed with
        if !(quartic.is_normal() && barrier.is_normal()) {
            return Err(Error::InvalidScene(format!(
                "k = {k} with alpha = {alpha} puts k/alpha^2 = {quartic:e} or k alpha^2/4 = {barrier:e} outside double precision's normal range"
            )));
        }
        Ok(Self { k, alpha, quartic })
    }

    /// The stiffness `k`.
    pub(crate) fn k(&self) -> f64 {
        self.k
    }

    /// The barrier position `alpha`.
    pub(crate) fn alpha(&self) -> f64 {
        self.alpha
    }

    /// The barrier height `E_b = V(-+alpha) = k alpha^2 / 4`.
    pub(crate) fn barrier(&self) -> f64 {
        0.25 * self.k * self.alpha * self.alpha
    }

    /// `a(x) = x (k x^2 / alpha^2 - k)`.
    #[inline(always)]
    pub(crate) fn acceleration<R: Real>(&self, x: R) -> R {
        x * (R::of(self.quartic) * x * x - R::of(self.k))
    }

    /// `V(x) = x^2 (k/2 - k x^2 / (4 alpha^2))`.
    #[inline(always)]
    pub(crate) fn potential<R: Real>(&self, x: R) -> R {
        let x2 = x * x;
        x2 * (R::of(0.5 * self.k) - R::of(0.25 * self.quartic) * x2)
    }

    /// `k = .., alpha = ..` for a scene's parameter list.
    pub(crate) fn parameters(&self) -> String {
        format!("k = {}, alpha = {}", self.k, self.alpha)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn force_is_minus_the_slope_of_the_potential_and_vanishes_at_the_barrier() {
        let well = Well::new(2.5, 0.7).unwrap();
        let h = 1e-3;
        for i in -20..=20 {
            let x = 0.05 * i as f64;
            // fourth-order central difference of V
            let slope = (8.0 * (well.potential(x + h) - well.potential(x - h))
                - (well.potential(x + 2.0 * h) - well.potential(x - 2.0 * h)))
                / (12.0 * h);
            assert!((well.acceleration(x) + slope).abs() < 1e-11, "x = {x}");
        }
        let (a, b) = (well.alpha(), well.barrier());
        assert!(well.acceleration(a).abs() < 1e-15 && well.acceleration(-a).abs() < 1e-15);
        assert!((well.potential(a) - b).abs() <= 2.0 * f64::EPSILON * b);
        assert!((b - 2.5 * 0.49 / 4.0).abs() <= f64::EPSILON * b);
    }

    #[test]
    fn rejects_bad_parameters() {
        assert!(Well::new(0.0, 1.0).is_err());
        assert!(Well::new(-1.0, 1.0).is_err());
        assert!(Well::new(1.0, f64::NAN).is_err());
        assert!(Well::new(f64::INFINITY, 1.0).is_err());
        assert!(Well::new(1.0, 1e-200).is_err());
        assert!(Well::new(1e300, 1e200).is_err());
    }
}
