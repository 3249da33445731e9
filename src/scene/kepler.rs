//! The Kepler problem `r'' = -GM r / |r|^3` in the plane, in astronomical units.

use super::{Invariant, InvariantValue, Parameters, Parametrised, Scene, SceneMeta};
use crate::error::Error;
use crate::maths::dd::Dd;
use crate::state::{Real, State};
use nalgebra::{SVector, Vector2};
use std::f64::consts::{PI, TAU};

/// `GM` of the Sun in AU^3 / yr^2: `v^2 r` for the circular Earth orbit with
/// `r = 1 AU` and `v = 2 pi AU/yr` (the course notes' Earth-Sun system).
pub const GM_SUN: f64 = 4.0 * PI * PI;

/// The Sun's pull, `-GM q / |q|^3`, shared by both orbits.
#[inline(always)]
fn sun_acceleration<R: Real>(q: &SVector<R, 2>) -> SVector<R, 2> {
    let r2 = q.norm_squared();
    q * (-R::of(GM_SUN) / (r2 * r2.sqrt()))
}

/// `-GM / |q|`, the potential both orbits move in.
#[inline(always)]
fn sun_potential<R: Real>(q: &SVector<R, 2>) -> R {
    -R::of(GM_SUN) / q.norm()
}

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
    /// A central force from a fixed centre: the angular momentum about it
    /// is conserved, the linear momentum is not.
    fn invariants(&self) -> &'static [Invariant] {
        &[Invariant::Energy, Invariant::AngularMomentum { axis: 2 }]
    }
    fn invariant(&self, which: Invariant, s: &State<2>) -> Option<InvariantValue> {
        match which {
            Invariant::Energy => Some(InvariantValue::energy(self, s)),
            Invariant::AngularMomentum { axis: 2 } => {
                Some(InvariantValue::planar_angular_momentum(s, self.frequency()))
            }
            _ => None,
        }
    }
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
        sun_acceleration(q)
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 2>) -> R {
        sun_potential(q)
    }

    fn period(&self) -> f64 {
        1.0
    }

    /// The orbit of the doubles the integrators are given (see
    /// `OrbitOfTheDoubles` in this file): the unit circle to within `2e-17`, its phase
    /// `n t` with `n` from `GM` and `v0` as doubles.
    fn exact(&self, t: f64) -> Option<State<2>> {
        Some(OrbitOfTheDoubles::of(&self.initial()).at(t))
    }
}

/// An eccentric orbit of eccentricity `e` about the Sun's `GM = 4 pi^2`, with
/// semi-major axis `a = 1` AU (period one year), started at pericentre:
/// `r0 = (a (1 - e), 0)`, `v0 = (0, sqrt(GM/a (1 + e)/(1 - e)))`.
///
/// The exact solution follows the ellipse through the eccentric anomaly `E`
/// (Murray and Dermott, *Solar System Dynamics*, 2.4):
///
/// - the ellipse with its focus at the origin and pericentre on `+x` is
///   `x = a (cos E - e)`, `y = b sin E`, `b = a sqrt(1 - e^2)`, and then
///   `|r| = a (1 - e cos E)`;
/// - the area law turns time into Kepler's equation `E - e sin E = M`, with
///   mean anomaly `M = n t` and mean motion `n = 2 pi / period`;
/// - differentiating it, `(1 - e cos E) dE/dt = n`, so the velocity is
///   `v = dE/dt (-a sin E, b cos E)`.
///
/// The scene is hard where circular orbits are easy: near pericentre the
/// force is `((1 + e)/(1 - e))^2` times its strength at apocentre and acts
/// over a fraction `~(1 - e)^(3/2)` of the period, so a fixed step resolves
/// that passage poorly. `e = 0.6` is the standard test of geometric
/// integration (Hairer, Lubich and Wanner, *Geometric Numerical Integration*,
/// I.2.3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KeplerEccentric {
    e: f64,
    /// The orbit its double initial state defines, worked out once.
    orbit: OrbitOfTheDoubles,
}

/// The semi-major axis in AU: with `GM = 4 pi^2` it makes the period one year.
const SEMI_MAJOR_AXIS: f64 = 1.0;

impl Default for KeplerEccentric {
    /// `e = 0.6`, the standard eccentric test orbit.
    fn default() -> Self {
        Self::with(0.6)
    }
}

impl KeplerEccentric {
    /// An orbit of eccentricity `0 <= e < 1` (`e = 0` is the circle of
    /// [`KeplerCircular`]; `e = 1` would be a radial fall into the Sun).
    ///
    /// ```
    /// use stepladder::scene::{KeplerEccentric, Scene};
    /// let orbit = KeplerEccentric::new(0.9).unwrap();
    /// assert_eq!(orbit.period(), 1.0);
    /// assert!((orbit.initial().q[0] - 0.1).abs() < 1e-15);
    /// assert!(KeplerEccentric::new(1.0).is_err());
    /// ```
    pub fn new(e: f64) -> Result<Self, Error> {
        // written so that NaN fails the test as well
        if (0.0..1.0).contains(&e) {
            Ok(Self::with(e))
        } else {
            Err(Error::InvalidParameter {
                name: "e",
                value: e,
                expected: "an eccentricity in [0, 1) (0 is a circle, 1 is no longer an ellipse)",
            })
        }
    }

    /// The orbit of eccentricity `e`, which the caller has checked.
    fn with(e: f64) -> Self {
        let mut orbit = Self {
            e,
            orbit: OrbitOfTheDoubles::default(),
        };
        orbit.orbit = OrbitOfTheDoubles::of(&orbit.initial());
        orbit
    }

    /// The eccentricity `e`.
    pub fn eccentricity(&self) -> f64 {
        self.e
    }
}

impl Parametrised for KeplerEccentric {
    const PARAMETERS: &'static [(&'static str, &'static str)] =
        &[("e", "eccentricity in [0, 1) (default 0.6)")];
    fn with_parameters(p: &Parameters) -> Result<Self, Error> {
        Self::new(p.get("e", Self::default().e))
    }
}

impl Scene<2> for KeplerEccentric {
    fn invariants(&self) -> &'static [Invariant] {
        &[Invariant::Energy, Invariant::AngularMomentum { axis: 2 }]
    }
    fn invariant(&self, which: Invariant, s: &State<2>) -> Option<InvariantValue> {
        match which {
            Invariant::Energy => Some(InvariantValue::energy(self, s)),
            Invariant::AngularMomentum { axis: 2 } => {
                Some(InvariantValue::planar_angular_momentum(s, self.frequency()))
            }
            _ => None,
        }
    }
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "kepler-eccentric",
            name: "eccentric Kepler orbit",
            dimension: 2,
            parameters: format!(
                "GM = 4 pi^2 AU^3/yr^2, a = 1 AU, e = {}, started at pericentre on +x",
                self.e
            ),
            reference: "r'' = -GM r/|r|^3; r = a (cos E - e, sqrt(1-e^2) sin E), E - e sin E = 2 pi t (Murray & Dermott 2.4; Hairer, Lubich, Wanner I.2.3)",
        }
    }

    fn initial(&self) -> State<2> {
        let (a, e) = (SEMI_MAJOR_AXIS, self.e);
        // vis-viva at pericentre: v^2 = GM (2/r - 1/a) with r = a (1 - e)
        let v = (GM_SUN / a * (1.0 + e) / (1.0 - e)).sqrt();
        State::new(Vector2::new(a * (1.0 - e), 0.0), Vector2::new(0.0, v))
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 2>) -> SVector<R, 2> {
        sun_acceleration(q)
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 2>) -> R {
        sun_potential(q)
    }

    fn period(&self) -> f64 {
        // Kepler's third law, 2 pi sqrt(a^3 / GM), with a = 1 and GM = 4 pi^2
        1.0
    }

    /// The orbit of the doubles the integrators are given (see
    /// `OrbitOfTheDoubles` in this file).
    fn exact(&self, t: f64) -> Option<State<2>> {
        Some(self.orbit.at(t))
    }
}

/// The Kepler orbit an integrator actually solves: `GM` and the initial
/// state are doubles, not the `4 pi^2`, `a = 1` and vis-viva speed they
/// round, and its elements are taken from those doubles in double-double.
///
/// The difference is not academic. On the `e = 0.6` orbit the double
/// pericentre speed makes `a = 1 + 2.2e-16` and the mean motion `n` smaller
/// than `2 pi` by `3.6e-16` of itself: after the accuracy runs' `2.83`
/// periods the mean anomaly is off by `6.4e-15` rad, and at pericentre,
/// where the orbit moves `2` AU per radian of it, the position by `1.3e-14`
/// AU. Evaluated in doubles the closed form adds the rounding of `2 pi t`
/// (`1.8e-15` rad at `t = 2.83`) and of Kepler's equation. In
/// double-double the state is exact to its final rounding to doubles, half
/// a unit in the last place of each coordinate (see the tests, which check
/// it against an independent 40-digit computation).
///
/// Started on `+x` with its velocity along `+y` (both scenes are), the
/// orbit has `1/a = 2/r0 - v0^2/GM`, `r0 = a (1 - e)`, `n = sqrt(GM/a^3)`
/// and `b = a sqrt(1 - e^2)`. A negative `e` (the circle's doubles make
/// `e = -1.5e-17`) is the same ellipse seen from its apocentre, which the
/// formulas below follow unchanged.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct OrbitOfTheDoubles {
    a: Dd,
    e: Dd,
    b: Dd,
    n: Dd,
}

impl OrbitOfTheDoubles {
    fn of(start: &State<2>) -> Self {
        let (r0, v0, gm) = (Dd::of(start.q[0]), Dd::of(start.v[1]), Dd::of(GM_SUN));
        let one = Dd::of(1.0);
        let a = one.div(Dd::of(2.0).div(r0).sub(v0.mul(v0).div(gm)));
        let e = one.sub(r0.div(a));
        let b = a.mul(one.sub(e.mul(e)).sqrt());
        let n = gm.div(a.mul(a).mul(a)).sqrt();
        OrbitOfTheDoubles { a, e, b, n }
    }

    /// The state at `t`: the mean anomaly `n t` reduced to `[-pi, pi]`,
    /// Kepler's equation `E - e sin E = M` by one Newton step in
    /// double-double from the double solution, then the ellipse. The double
    /// solution is within `d = 4 eps (|E| + |M|)`, under `3e-15`
    /// ([`eccentric_anomaly`]'s tests); Newton's error after that step is at
    /// most `e d^2 / (2 (1 - e))`, under `1e-26` even at `e = 0.999`. The
    /// sine and cosine at the corrected anomaly are those at the double one
    /// moved by the step to first order, off by `d^2/2`, under `1e-29`: one
    /// double-double sine and cosine a call.
    fn at(&self, t: f64) -> State<2> {
        const TWO_PI: Dd = Dd {
            hi: TAU,
            lo: 2.449_293_598_294_706_4e-16,
        };
        let one = Dd::of(1.0);
        let m = self.n.mul(Dd::of(t));
        let m = m.sub(TWO_PI.mul(Dd::of((m.hi / TAU).round())));
        let start = Dd::of(if self.e.hi > 0.0 {
            eccentric_anomaly(m.hi, self.e.hi).anomaly
        } else {
            m.hi
        });
        let (sin0, cos0) = start.sin_cos();
        let slope = one.sub(self.e.mul(cos0));
        let step = start.sub(self.e.mul(sin0)).sub(m).div(slope).neg();
        let (sin, cos) = (sin0.add(step.mul(cos0)), cos0.sub(step.mul(sin0)));
        let rate = self.n.div(one.sub(self.e.mul(cos))); // dE/dt
        State::new(
            Vector2::new(
                self.a.mul(cos.sub(self.e)).to_f64(),
                self.b.mul(sin).to_f64(),
            ),
            Vector2::new(
                self.a.mul(sin).mul(rate).neg().to_f64(),
                self.b.mul(cos).mul(rate).to_f64(),
            ),
        )
    }
}

/// Most iterations [`eccentric_anomaly`] takes: a hard stop far above the
/// six its Newton iteration needs (see the tests), leaving room for the
/// bisections round-off might force.
const KEPLER_MAX_ITERATIONS: u32 = 100;

/// A solution of Kepler's equation and what it cost.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Anomaly {
    /// The eccentric anomaly `E`.
    anomaly: f64,
    /// Evaluations of Kepler's equation spent.
    iterations: u32,
    /// The stopping criterion was met within [`KEPLER_MAX_ITERATIONS`].
    converged: bool,
}

/// Solves Kepler's equation `f(E) = E - e sin E - M = 0` for `0 <= e < 1` and
/// `M` in `[-pi, pi]`, to round-off.
///
/// `f` is odd, so the iteration runs on `|M|`. On `[0, pi]` `f` is increasing
/// (`f' = 1 - e cos E >= 1 - e > 0`) and convex (`f'' = e sin E >= 0`), so
/// Newton's method started at a point where `f >= 0` decreases monotonically
/// onto the root and never overshoots (Fourier's condition). The start is the
/// smallest of four such points, with `M = |M|`:
///
/// - `pi`: `f(pi) = pi - M`;
/// - `M + e`: `f = e (1 - sin(M + e))`;
/// - `M / (1 - e)`, tight where `E ~ M / (1 - e)` (near pericentre, `e`
///   well below 1): `f = e (x - sin x)` at `x = M / (1 - e)`;
/// - `(12 M / e)^(1/3)`, tight near pericentre as `e -> 1`, where
///   `E - e sin E ~ E^3 / 6`: `x - sin x >= x^3/6 (1 - x^2/20) >= x^3 / 12`
///   for `x <= pi`, so `f >= e x^3 / 12 - M = 0`.
///
/// Convergence: Newton's error after a step `s` is at most
/// `max f'' / (2 f') s^2 <= e s^2 / (2 f')`; the iteration stops once that is
/// below `eps |E|`. It also stops when `f <= 0`, which exact arithmetic never
/// reaches from above: only round-off does. `f` and `f'` are evaluated without
/// cancellation (see [`kepler_function`]), so both tests are reachable. Should
/// round-off ever push an iterate out of the bracket `[|M|, start]`, that
/// iteration bisects instead.
fn eccentric_anomaly(m: f64, e: f64) -> Anomaly {
    if m.is_nan() {
        // a NaN time has no anomaly; the bracket below would invent one
        return Anomaly {
            anomaly: f64::NAN,
            iterations: 0,
            converged: false,
        };
    }
    let target = m.abs();
    let mut lo = target; // f(|M|) = -e sin |M| <= 0
    let mut hi = [
        PI,
        target + e,
        target / (1.0 - e),
        (12.0 * target / e).cbrt(),
    ]
    .into_iter()
    .filter(|x| !x.is_nan())
    .fold(f64::INFINITY, f64::min);
    let mut x = hi;
    for iterations in 1..=KEPLER_MAX_ITERATIONS {
        let (f, slope) = kepler_function(x, e, target);
        if f > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let step = f / slope;
        let mut next = x - step;
        if !(lo <= next && next <= hi) {
            next = 0.5 * (lo + hi);
        }
        let converged = f <= 0.0
            || e * step * step <= 2.0 * slope * f64::EPSILON * next
            || hi - lo <= f64::EPSILON * hi;
        x = next;
        if converged {
            return Anomaly {
                anomaly: x.copysign(m),
                iterations,
                converged: true,
            };
        }
    }
    Anomaly {
        anomaly: x.copysign(m),
        iterations: KEPLER_MAX_ITERATIONS,
        converged: false,
    }
}

/// Kepler's function `f(E) = E - e sin E - M` and its slope `f'(E) = 1 - e cos E`
/// for `E >= 0`, as sums of non-negative terms:
/// `f = (1 - e) E + e (E - sin E) - M` and `f' = (1 - e) + 2 e sin^2(E/2)`.
///
/// Written directly, `E - e sin E` near pericentre at `e -> 1` is the small
/// difference of two nearly equal numbers and loses `-log10(1 - e)` digits;
/// so would `1 - e cos E`. Here only the final `- M` cancels, leaving an error
/// of a few `eps M`, and `M / f' <= E` on `[0, pi]`, so Newton's step is
/// accurate to a few `eps E`.
fn kepler_function(x: f64, e: f64, m: f64) -> (f64, f64) {
    let f = (1.0 - e) * x + e * x_minus_sin(x) - m;
    let slope = (1.0 - e) + 2.0 * e * (0.5 * x).sin().powi(2);
    (f, slope)
}

/// `x - sin x` for `x >= 0` without cancellation: below 1 by its Taylor series
/// `x^3/3! - x^5/5! + ...`, summed in nested form to the `x^21` term (the
/// first term left out, `x^23/23!`, is below `1e-22 x^3` there); above 1
/// directly, where it loses at most a factor `1 / (1 - sin 1) ~ 6` in
/// relative accuracy.
fn x_minus_sin(x: f64) -> f64 {
    if x >= 1.0 {
        return x - x.sin();
    }
    let x2 = x * x;
    // the term x^(2k+1)/(2k+1)! times -x^2 / ((2k+2)(2k+3)) gives the next one
    let series = [20.0, 42.0, 72.0, 110.0, 156.0, 210.0, 272.0, 342.0, 420.0]
        .iter()
        .rev()
        .fold(1.0, |acc, d| 1.0 - x2 / d * acc);
    x * x2 / 6.0 * series
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact states of the orbits the doubles define, from an
    /// independent 40-digit computation (`tests/check_kepler_exact.py
    /// --rust`: mpmath, elements from vis-viva, Kepler's equation by Newton
    /// from `E = pi`), rounded to doubles. The double-double solution
    /// rounds to the same doubles, within one unit in the last place.
    #[test]
    fn exact_states_are_the_forty_digit_ones_rounded() {
        let cases: [(Option<f64>, f64, [f64; 4]); 4] = [
            (
                None,
                2.8284271247461903,
                [
                    0.47307004268787006,
                    -0.8810248207123887,
                    5.535642208760611,
                    2.9723867414832448,
                ],
            ),
            (
                Some(0.6),
                2.8284271247461903,
                [
                    -0.7037994839614435,
                    -0.7956785952649327,
                    5.882862235218245,
                    -0.49116359725411696,
                ],
            ),
            (
                Some(0.6),
                1.37,
                [
                    -1.4682481614858667,
                    0.3969041234969779,
                    -2.049561101470946,
                    -2.86945293290694,
                ],
            ),
            (
                Some(0.9),
                10.001,
                [
                    0.09804961467317508,
                    0.027210726995765395,
                    -3.8546590862703733,
                    26.862817487602843,
                ],
            ),
        ];
        for (e, t, expected) in cases {
            let s = match e {
                None => KeplerCircular.exact(t),
                Some(e) => KeplerEccentric::new(e).unwrap().exact(t),
            }
            .unwrap();
            for (got, want) in [s.q[0], s.q[1], s.v[0], s.v[1]].into_iter().zip(expected) {
                let ulps = (got.to_bits() as i64 - want.to_bits() as i64).abs();
                assert!(ulps <= 1, "e = {e:?}, t = {t}: {got} against {want}");
            }
        }
    }

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

    /// The eccentricities the solution is checked at: the circle, the default,
    /// and ever more demanding pericentre passages.
    const ECCENTRICITIES: [f64; 6] = [0.0, 0.1, 0.6, 0.9, 0.99, 0.999];

    const EPS: f64 = f64::EPSILON;

    fn orbit(e: f64) -> KeplerEccentric {
        KeplerEccentric::new(e).unwrap()
    }

    /// Times spread over three periods, plus a cluster around pericentre
    /// (t = 0 and t = 1), where the high-eccentricity orbits change fastest.
    fn times() -> impl Iterator<Item = f64> {
        let spread = (0..3000).map(|k| 3.0 * k as f64 / 3000.0 + 1e-3 * (k % 7) as f64);
        let pericentre = (-200..=200).flat_map(|k| [1e-6 * k as f64, 1.0 + 3e-5 * k as f64]);
        spread.chain(pericentre)
    }

    #[test]
    fn zero_eccentricity_is_the_circular_orbit() {
        let (e0, circle) = (orbit(0.0), KeplerCircular);
        assert_eq!(e0.initial(), circle.initial());
        assert_eq!(e0.period(), circle.period());
        for t in times() {
            let (a, b) = (e0.exact(t).unwrap(), circle.exact(t).unwrap());
            // the circle's sin(2 pi t) carries the rounding of its argument,
            // about eps 2 pi t; the reduced anomaly here carries eps pi
            assert!(
                circle.phase_distance(&a, &b) <= 4.0 * EPS * (1.0 + TAU * t.abs()),
                "t = {t}: {a:?} against {b:?}"
            );
            assert_eq!(e0.acceleration(&a.q), circle.acceleration(&a.q));
            assert_eq!(e0.potential(&a.q), circle.potential(&a.q));
        }
    }

    #[test]
    fn exact_solution_starts_at_pericentre_with_the_vis_viva_speed() {
        for e in ECCENTRICITIES {
            let k = orbit(e);
            // pericentre r = a (1 - e); vis-viva v^2 = GM (2/r - 1/a), a = 1
            let r = 1.0 - e;
            let v = (GM_SUN * (2.0 / r - 1.0)).sqrt();
            for s in [k.initial(), k.exact(0.0).unwrap()] {
                assert_eq!(s.q, Vector2::new(r, 0.0), "e = {e}");
                assert_eq!(s.v[0], 0.0, "e = {e}");
                assert!(
                    (s.v[1] - v).abs() <= 4.0 * EPS * v,
                    "e = {e}: {s:?}, v = {v}"
                );
            }
        }
    }

    #[test]
    fn exact_solution_conserves_energy_and_angular_momentum() {
        for e in [0.1, 0.6, 0.9, 0.99] {
            let k = orbit(e);
            // the orbit's own energy and angular momentum, those of its
            // double initial state, in double-double: the ideal `-GM / 2`
            // and `sqrt(GM (1 - e^2))` differ from them by the rounding of
            // the pericentre speed, 1e-13 of the energy at e = 0.9
            let start = k.initial();
            let (r0, v0) = (Dd::of(start.q[0]), Dd::of(start.v[1]));
            let energy = v0
                .mul(v0)
                .mul(Dd::of(0.5))
                .sub(Dd::of(GM_SUN).div(r0))
                .to_f64();
            let momentum = r0.mul(v0).to_f64();
            for t in times() {
                let s = k.exact(t).unwrap();
                let (kinetic, potential) = (0.5 * s.v.norm_squared(), GM_SUN / s.q.norm());
                // each component carries a few eps of relative error (sin, cos,
                // sqrt, a division), the invariants a few more roundings: 8 eps
                // of the terms summed, which near pericentre cancel to 1/200
                let de = (kinetic - potential - energy).abs();
                assert!(
                    de <= 8.0 * EPS * (kinetic + potential),
                    "e = {e}, t = {t}: energy off by {de:e}"
                );
                let l = s.q[0] * s.v[1] - s.q[1] * s.v[0];
                let dl = (l - momentum).abs();
                assert!(
                    dl <= 8.0 * EPS * s.q.norm() * s.v.norm(),
                    "e = {e}, t = {t}: angular momentum off by {dl:e}"
                );
            }
        }
    }

    /// Mean anomalies over a dense grid of `(-pi, pi]`, plus tiny ones of both
    /// signs down to 1e-300, where the anomaly near pericentre is hardest.
    fn mean_anomalies(n: usize) -> impl Iterator<Item = f64> {
        let grid = (1..=n).map(move |k| -PI + TAU * k as f64 / n as f64);
        let tiny = (0..=300).flat_map(|p| {
            let m = 10f64.powi(-p);
            [m, -0.37 * m]
        });
        grid.chain(tiny).chain([0.0, PI])
    }

    #[test]
    fn keplers_equation_is_solved_to_round_off() {
        for e in [0.0, 0.1, 0.3, 0.5, 0.6, 0.9, 0.99, 0.999] {
            for m in mean_anomalies(20_000) {
                let big_e = eccentric_anomaly(m, e).anomaly;
                // E - M = e sin E lies in [0, e] with the sign of M
                assert!(
                    (big_e - m) * m.signum() >= 0.0 && (big_e - m).abs() <= e,
                    "e = {e}, M = {m}: E = {big_e}"
                );
                // evaluating E - e sin E - M in floating point costs about
                // 1.5 eps |E| + 0.5 eps |M|, and E within an ulp or two of the
                // root adds (1 + e) 2 eps |E|: 4 eps (|E| + |M|) bounds both
                let residual = big_e - e * big_e.sin() - m;
                assert!(
                    residual.abs() <= 4.0 * EPS * (big_e.abs() + m.abs()),
                    "e = {e}, M = {m}: residual {residual:e}"
                );
            }
        }
    }

    /// Near pericentre at high eccentricity `E - e sin E` is the small
    /// difference of two nearly equal numbers: solved from it naively, `E`
    /// would be off by some `eps E / (1 - e cos E)`, a thousand times round-off
    /// at `e = 0.999`. Here `M` is formed from a known `E` as
    /// `(1 - e) E + e (E - sin E)`, a sum of positive terms with the sine's
    /// Taylor series summed term by term, so it is good to 2 eps; since
    /// `dE/dM = 1 / (1 - e cos E)` and `M / (1 - e cos E) <= E`, that moves `E`
    /// by at most 2 eps E, and the solver's own few eps come on top.
    #[test]
    fn eccentric_anomaly_is_accurate_near_pericentre_at_high_eccentricity() {
        let x_minus_sin_by_terms = |x: f64| {
            let (mut term, mut sum) = (x * x * x / 6.0, 0.0);
            for k in 2..30 {
                sum += term;
                term *= -x * x / ((2 * k) as f64 * (2 * k + 1) as f64);
            }
            sum
        };
        for e in [0.9, 0.99, 0.999, 0.9999] {
            for j in 0..=400 {
                let big_e = 10f64.powf(-8.0 + 8.0 * j as f64 / 400.0); // 1e-8 .. 1
                let m = (1.0 - e) * big_e + e * x_minus_sin_by_terms(big_e);
                let solved = eccentric_anomaly(m, e).anomaly;
                assert!(
                    (solved - big_e).abs() <= 8.0 * EPS * big_e,
                    "e = {e}, E = {big_e}: solved {solved}, off by {:.1} eps E",
                    (solved - big_e).abs() / (EPS * big_e)
                );
            }
        }
    }

    #[test]
    fn newton_iteration_converges_in_few_steps_for_any_anomaly() {
        // From the start, within a factor 2^(1/3) of the root where the cubic
        // bound is used and closer elsewhere, Newton's relative error goes
        // roughly 0.3, 0.1, 1e-2, 1e-4, 1e-8, 1e-16: six steps. One more, two
        // for slack: eight.
        for e in [
            0.0,
            0.01,
            0.1,
            0.3,
            0.5,
            0.6,
            0.8,
            0.9,
            0.95,
            0.99,
            0.995,
            0.999,
            0.9999,
            1.0 - 1e-9,
        ] {
            let mut worst = 0;
            for m in mean_anomalies(100_000) {
                let s = eccentric_anomaly(m, e);
                assert!(
                    s.converged && s.anomaly.is_finite(),
                    "e = {e}, M = {m}: {s:?}"
                );
                worst = worst.max(s.iterations);
            }
            assert!(worst <= 8, "e = {e}: {worst} iterations");
        }
        let nan = eccentric_anomaly(f64::NAN, 0.5);
        assert!(nan.anomaly.is_nan() && !nan.converged);
    }

    #[test]
    fn x_minus_sin_agrees_with_its_definition() {
        for k in 0..=4000 {
            let x = PI * k as f64 / 4000.0;
            // the direct difference is off by at most eps x (the rounding of
            // sin x and of the subtraction); a wrong series term is off by
            // x^(2k+1)/(2k+1)!, far more near x = 1
            assert!((x_minus_sin(x) - (x - x.sin())).abs() <= EPS * x, "x = {x}");
        }
        // and for small x it is x^3/6 (1 - x^2/20), up to x^7/5040
        for x in [1e-100, 1e-8, 1e-3, 0.1] {
            let leading = x * x * x / 6.0 * (1.0 - x * x / 20.0);
            assert!((x_minus_sin(x) - leading).abs() <= x.powi(7) / 5040.0 + 2.0 * EPS * leading);
        }
    }

    #[test]
    fn exact_solution_is_periodic_and_stays_accurate_for_long_times() {
        for e in ECCENTRICITIES {
            let k = orbit(e);
            // the doubles' orbit has the period 2 pi / n, not 1: a shift by
            // whole periods of 1 moves along the orbit by that difference
            let orbit_of_doubles = OrbitOfTheDoubles::of(&k.initial());
            let period = Dd::of(TAU).div(orbit_of_doubles.n).to_f64();
            // a time far out keeps the state on the orbit: energy and
            // angular momentum as at the start, to the states' rounding
            for t in [2f64.powi(40) + 0.25, 1e6 + 1.0 / 3.0] {
                let (a, b) = (k.initial(), k.exact(t).unwrap());
                let energy = |s: &State<2>| 0.5 * s.v.norm_squared() - GM_SUN / s.q.norm();
                let terms = |s: &State<2>| 0.5 * s.v.norm_squared() + GM_SUN / s.q.norm();
                let size = terms(&a).max(terms(&b));
                assert!(
                    (energy(&a) - energy(&b)).abs() <= 16.0 * EPS * size,
                    "e = {e}, t = {t}"
                );
            }
            // other times: t + 1 rounds by up to eps/2 in t, so the states may
            // differ by the phase-space speed sqrt(|v|^2 + |a/w|^2) times that,
            // plus their own round-off
            for j in 0..1000 {
                let t = 0.001 * j as f64 + 1.0 / 3.0e3;
                let (a, b) = (k.exact(t).unwrap(), k.exact(t + 1.0).unwrap());
                let w = k.frequency();
                let speed = (a.v.norm_squared() + (k.acceleration(&a.q) / w).norm_squared()).sqrt();
                let bound = speed * (EPS + (1.0 - period).abs()) + 16.0 * EPS * k.scale();
                assert!(k.phase_distance(&a, &b) <= bound, "e = {e}, t = {t}");
            }
        }
    }

    /// `r'' = a(r)`: the eighth-order central difference of the exact
    /// velocity must give the acceleration.
    ///
    /// The orbit is analytic in time up to complex collisions `1 = e cos E` at
    /// `E = +-i arccosh(1/e)`, i.e. at times `+-i rho` from each pericentre,
    /// `n rho = arccosh(1/e) - sqrt(1 - e^2)`. Derivatives then grow like
    /// `|v^(9)| ~ 9! |a| / rho^8`, so the formula's truncation error
    /// `h^8 |v^(9)| / 630` is about `576 (h / rho)^8 |a|`; with `h = rho / 64`
    /// that is `2e-12 |a|`, allowed ten times over at the pericentre `|a|`, the
    /// largest. Round-off: each velocity is off by some `8 eps |v|`, and by
    /// `|a| eps t` through the rounding of its time; the stencil's weights sum
    /// to 2.08 in magnitude and are divided by `h`. The force itself is off by
    /// some `10 eps |a|`.
    #[test]
    fn exact_solution_satisfies_newtons_equation() {
        const WEIGHTS: [f64; 4] = [4.0 / 5.0, -1.0 / 5.0, 4.0 / 105.0, -1.0 / 280.0];
        for e in [0.1, 0.6, 0.9, 0.99] {
            let k = orbit(e);
            let n = k.frequency();
            let rho = ((1.0 / e).acosh() - (1.0 - e * e).sqrt()) / n;
            let h = rho / 64.0;
            let peri = k.initial();
            let (v_max, a_max) = (peri.v.norm(), k.acceleration(&peri.q).norm());
            let pericentre = (-64..=64).map(|j| j as f64 * rho / 16.0);
            let spread = (0..200).map(|j| 0.005 * j as f64 + 0.0013);
            for t in pericentre.chain(spread) {
                let s = k.exact(t).unwrap();
                let dv = (1..=4).fold(Vector2::zeros(), |acc, j| {
                    let dt = j as f64 * h;
                    acc + (k.exact(t + dt).unwrap().v - k.exact(t - dt).unwrap().v) * WEIGHTS[j - 1]
                }) / h;
                let a = k.acceleration(&s.q);
                let truncation = 10.0 * 576.0 * 64f64.powi(-8) * a_max;
                let round_off = 2.08 * (8.0 * EPS * v_max + a_max * EPS * (t.abs() + 4.0 * h)) / h
                    + 10.0 * EPS * a.norm();
                let miss = (dv - a).norm();
                assert!(
                    miss <= truncation + round_off,
                    "e = {e}, t = {t}: {miss:e} against {:e} + {:e}",
                    truncation,
                    round_off
                );
            }
        }
    }

    #[test]
    fn rejects_eccentricities_that_are_not_ellipses() {
        for e in [
            -0.1,
            -1e-300,
            1.0,
            1.5,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            let err = KeplerEccentric::new(e).unwrap_err().to_string();
            assert!(err.contains("[0, 1)"), "e = {e}: {err}");
        }
        for e in [0.0, 0.6, 1.0 - 1e-12] {
            assert_eq!(KeplerEccentric::new(e).unwrap().eccentricity(), e);
        }
        assert_eq!(KeplerEccentric::default().eccentricity(), 0.6);
        assert_eq!(KeplerEccentric::default().meta().id, "kepler-eccentric");
    }
}
