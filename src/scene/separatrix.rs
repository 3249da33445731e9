//! The separatrix of the anharmonic well: the orbit with exactly the
//! barrier's energy, which climbs towards the barrier top forever.

use super::well::Well;
use super::{Scene, SceneMeta};
use crate::error::Error;
use crate::state::{Real, State};
use nalgebra::{SVector, Vector1};
use std::f64::consts::TAU;

/// The orbit of the anharmonic well `x'' = -k x + k x^3 / alpha^2` with
/// exactly the barrier energy `E_b = k alpha^2 / 4`, started at the bottom
/// moving right: `x(0) = 0`, `v(0) = alpha lambda`, `lambda = sqrt(k / 2)`.
///
/// # The exact solution
///
/// `x(t) = alpha tanh(lambda t)`, `v(t) = alpha lambda sech^2(lambda t)`.
/// Check: `x'' = -2 alpha lambda^2 sech^2 tanh = -k alpha tanh (1 - tanh^2)
/// = -k x + k x^3 / alpha^2`, and `v(0)^2 / 2 = k alpha^2 / 4 = E_b`. It is
/// the `m -> 1` limit of [`super::Anharmonic`] (`sn -> tanh`, `cn dn ->
/// sech^2`, `A -> alpha`, `Omega -> lambda`; A&S 16.15).
///
/// The orbit joins the two saddles at `-+alpha`: it leaves `-alpha` as
/// `t -> -inf` and reaches `alpha` only as `t -> inf`, approaching it like
/// `e^(-2 lambda t)`. Near a saddle, neighbouring orbits separate like
/// `e^(sqrt(2k) t)` (`V''(alpha) = -2k`), and any energy error sends a
/// numerical orbit back into the well or over the barrier: a global error here
/// measures that instability as much as the scheme, which is why this scene
/// is left out of the order studies' registry.
///
/// # Period
///
/// The motion is not periodic: the true period is infinite. [`Scene::period`]
/// returns instead the natural time scale `2 pi / sqrt(k)`, the
/// small-oscillation period at the bottom of the same well, because every
/// study needs a finite one: it converts velocity errors into lengths (the
/// frequency `sqrt(k)` is the well's own, and the same order as the saddle's
/// rate `sqrt(2k)`), and it sets where step-size ladders start and when runs
/// end. Within one such period the orbit covers all but `1 - tanh(pi
/// sqrt(2)) = 3e-4` of the way to the barrier top.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Separatrix {
    well: Well,
    /// `lambda = sqrt(k / 2)`, half the saddle's rate.
    rate: f64,
}

impl Default for Separatrix {
    /// `k = 1, alpha = 1`: `x(t) = tanh(t / sqrt(2))`.
    fn default() -> Self {
        Self::new(1.0, 1.0).expect("the default well is valid")
    }
}

impl Separatrix {
    /// The separatrix of the well with stiffness `k > 0` and barriers at
    /// `-+alpha`, `alpha > 0`.
    ///
    /// ```
    /// use stepladder::scene::{Scene, Separatrix};
    /// let s = Separatrix::new(2.0, 1.0).unwrap();
    /// assert_eq!(s.exact(0.0).unwrap().v[0], 1.0);
    /// assert!(s.period().is_finite());
    /// assert!(Separatrix::new(2.0, -1.0).is_err());
    /// ```
    pub fn new(k: f64, alpha: f64) -> Result<Self, Error> {
        let well = Well::new(k, alpha)?;
        Ok(Self {
            well,
            rate: (0.5 * well.k()).sqrt(),
        })
    }

    /// The barrier height `k alpha^2 / 4`, which is also the orbit's energy.
    pub fn barrier(&self) -> f64 {
        self.well.barrier()
    }
}

impl Scene<1> for Separatrix {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "separatrix",
            name: "anharmonic well separatrix",
            dimension: 1,
            parameters: format!("{}, x0 = 0, v0 = alpha sqrt(k/2)", self.well.parameters()),
            reference: "x'' = -k x + k x^3/alpha^2 at the barrier energy; x(t) = alpha tanh(sqrt(k/2) t) (course notes' anharmonic well; A&S 16.15)",
        }
    }

    fn initial(&self) -> State<1> {
        State::new(
            Vector1::new(0.0),
            Vector1::new(self.well.alpha() * self.rate),
        )
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 1>) -> SVector<R, 1> {
        Vector1::new(self.well.acceleration(q[0]))
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        self.well.potential(q[0])
    }

    /// Not the period, which is infinite, but the time scale `2 pi /
    /// sqrt(k)` of the well's bottom (see the type's documentation).
    fn period(&self) -> f64 {
        TAU / self.well.k().sqrt()
    }

    fn exact(&self, t: f64) -> Option<State<1>> {
        let u = self.rate * t;
        // sech^2 as 1 / cosh^2, not 1 - tanh^2, which cancels as x -> alpha
        let sech = 1.0 / u.cosh();
        let alpha = self.well.alpha();
        Some(State::new(
            Vector1::new(alpha * u.tanh()),
            Vector1::new(alpha * self.rate * sech * sech),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Anharmonic;

    const EPS: f64 = f64::EPSILON;

    fn separatrices() -> Vec<Separatrix> {
        [(1.0, 1.0), (2.0, 1.0), (0.3, 2.5), (50.0, 0.1)]
            .iter()
            .map(|&(k, a)| Separatrix::new(k, a).unwrap())
            .collect()
    }

    #[test]
    fn starts_at_the_bottom_with_the_barrier_energy_and_keeps_it() {
        for s in separatrices() {
            let s0 = s.initial();
            assert_eq!(s.exact(0.0).unwrap(), s0);
            assert_eq!(s0.q[0], 0.0);
            assert!(s0.v[0] > 0.0, "moves right");
            let eb = s.barrier();
            assert!((s.energy(&s0) - eb).abs() <= 2.0 * EPS * eb);
            for i in -300..=300 {
                // out to lambda t = 30, where x is alpha to round-off
                let t = 0.1 * i as f64 / s.rate;
                let e = s.energy(&s.exact(t).unwrap());
                assert!((e - eb).abs() <= 8.0 * EPS * eb, "E({t}) = {e}, E_b = {eb}");
            }
        }
    }

    #[test]
    fn exact_solution_satisfies_the_equation_of_motion() {
        const C: [f64; 4] = [4.0 / 5.0, -1.0 / 5.0, 4.0 / 105.0, -1.0 / 280.0];
        for s in separatrices() {
            let h = 0.02 / s.rate;
            let derivative = |f: &dyn Fn(f64) -> f64, t: f64| {
                C.iter()
                    .enumerate()
                    .map(|(i, c)| {
                        let dh = (i + 1) as f64 * h;
                        c * (f(t + dh) - f(t - dh))
                    })
                    .sum::<f64>()
                    / h
            };
            let x = |t| s.exact(t).unwrap().q[0];
            let v = |t| s.exact(t).unwrap().v[0];
            let alpha = s.well.alpha();
            let (vmax, amax) = (alpha * s.rate, alpha * s.well.k());
            for i in -50..=50 {
                let t = 0.1 * i as f64 / s.rate;
                let st = s.exact(t).unwrap();
                let a = s.acceleration(&st.q)[0];
                let (rx, rv) = (derivative(&x, t) - st.v[0], derivative(&v, t) - a);
                assert!(
                    rx.abs() <= 2e-12 * vmax && rv.abs() <= 2e-12 * amax,
                    "k = {}, t = {t}: x' - v = {rx:e}, v' - a = {rv:e}",
                    s.well.k()
                );
            }
        }
    }

    #[test]
    fn climbs_monotonically_from_one_barrier_top_towards_the_other() {
        for s in separatrices() {
            let alpha = s.well.alpha();
            let mut last = -alpha;
            for i in -400..=400 {
                let x = s.exact(0.1 * i as f64 / s.rate).unwrap().q[0];
                assert!(x >= last && x.abs() <= alpha, "x = {x}");
                last = x;
            }
            let far = 40.0 / s.rate;
            assert_eq!(s.exact(far).unwrap().q[0], alpha);
            assert_eq!(s.exact(-far).unwrap().q[0], -alpha);
        }
    }

    /// Orbits started the same way with a speed short by a fraction `delta`
    /// follow the separatrix. Over a fixed time the flow is smooth in the
    /// initial speed, so their distance from it is linear in `delta`, although
    /// the amplitude `alpha sqrt(1 - s)`, frequency `lambda sqrt(1 + s)` and
    /// `1 - m ~ 2 s` move like `s = sqrt(1 - E/E_b) ~ sqrt(2 delta)`: the
    /// first-order changes in `s` must cancel (A&S 16.15), which checks the
    /// three against each other.
    #[test]
    fn trapped_orbits_near_the_barrier_energy_follow_it() {
        let sep = Separatrix::new(2.0, 0.7).unwrap();
        let v_sep = sep.initial().v[0];
        let largest_gap = |delta: f64| {
            let trapped = Anharmonic::new(2.0, 0.7, 0.0, v_sep * (1.0 - delta)).unwrap();
            (0..=100)
                .map(|i| 0.03 * i as f64 / sep.rate)
                .map(|t| sep.phase_distance(&trapped.exact(t).unwrap(), &sep.exact(t).unwrap()))
                .fold(0.0, f64::max)
        };
        let (near, nearer) = (largest_gap(1e-10), largest_gap(1e-14));
        assert!(near < 1e-7 * sep.scale(), "gap {near:e}");
        let ratio = near / nearer;
        assert!(
            (5e3..2e4).contains(&ratio),
            "gap ratio {ratio}, expected 1e4"
        );
    }

    #[test]
    fn period_is_the_finite_time_scale_of_the_well() {
        let s = Separatrix::new(4.0, 1.0).unwrap();
        assert_eq!(s.period(), std::f64::consts::PI);
        assert_eq!(s.meta().id, "separatrix");
        assert!(s.default_t_end().is_finite());
        assert!(Separatrix::new(0.0, 1.0).is_err());
        assert!(Separatrix::new(1.0, f64::NAN).is_err());
        assert!(Separatrix::new(f64::INFINITY, 1.0).is_err());
    }
}
