//! A held-out batch of the verdict corpus: integrators and scenes written
//! apart from the harness and from the other batches ([`super::correct`],
//! [`super::broken`]), each pair with the verdict theory says a correct
//! harness must give.
//!
//! Scenes (all here, each checked by the scene check in the tests): a
//! Lennard-Jones trimer vibrating about its equilateral minimum (`D = 6`),
//! the three-dimensional Kepler problem on an inclined eccentric orbit with
//! its exact solution from Kepler's equation (`D = 3`), the periodic Toda
//! lattice of three particles (integrable, `D = 3`), the double well
//! `V = (x^2 - 1)^2` on an orbit above the barrier with its exact solution
//! `x = A cn(w t, m)` (`D = 1`), two coupled oscillators with incommensurate
//! normal frequencies and their exact solution (`D = 2`), and a planar star
//! with three planets in mass-weighted coordinates (`D = 8`).
//!
//! Schemes: Beeman's algorithm, the fourth-order Adams-Bashforth-Moulton
//! predictor-corrector with a Runge-Kutta start-up, the three-stage Lobatto
//! IIIA-IIIB partitioned pair, Butcher's sixth-order seven-stage
//! Runge-Kutta method, Runge's third-order method, Kutta's 3/8 rule, the
//! Dormand-Prince RKN6(4)6FD Runge-Kutta-Nyström method, the Candy-Rozmus
//! (drift-first) fourth-order composition and Blanes and Moan's symplectic
//! RKN method `SRKN_6^b`; and plausible bugs in them (a sign typo in Beeman,
//! swapped corrector weights, a cold multistep start, a conjugate pair of
//! weights swapped, a force lagging one drift behind, a flipped weight, the
//! wrong tableau in half a partitioned pair, a stale closing force, swapped
//! stage coefficients, velocities from a first-order difference).
//!
//! Notation: `z = h w` with `w` the scene's angular frequency `2 pi / T`;
//! "relative" errors are phase-space distances divided by the scene's
//! [`Scene::scale`].

use crate::corpus::{Entry, Expect, Expected};
use crate::scene::{Scene, SceneMeta};
use crate::scheme::{OneStep, Rk4, Scheme, SchemeMeta, StepFailure};
use crate::state::{Real, State};
use nalgebra::SVector;
use std::f64::consts::{PI, TAU};

// ======================================================================= scenes

/// The Lennard-Jones trimer in the plane: three atoms of unit mass, each
/// pair bound by `V(r) = eps ((r0/r)^12 - 2 (r0/r)^6)` with `eps = 1`,
/// `r0 = 1` (the pair minimum at `r0`, depth `eps`), positions
/// `q = (x1, y1, x2, y2, x3, y3)`.
///
/// The minimum is the equilateral triangle of side `r0`, energy `-3 eps`.
/// With the pair stiffness `k = V''(r0) = 72 eps / r0^2` the normal modes of
/// an equilateral triangle of equal springs are the breathing mode
/// (`w^2 = 3k`) and a degenerate pair (`w^2 = 3k/2`), besides three zero
/// modes (translations, rotation). The atoms start at rest, displaced from the
/// minimum by a few hundredths of a bond length with their centre of mass
/// fixed: zero momentum and zero angular momentum, a vibration about
/// `0.08 eps` above the minimum (of `1 eps` per bond to break), which excites
/// every mode: a regular, weakly anharmonic, bound motion. No closed form.
///
/// Source: J. E. Lennard-Jones, Proc. R. Soc. A 106, 463 (1924); the modes
/// of the equilateral triangle: H. Goldstein, Classical Mechanics, ch. 6.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LjTrimer;

impl LjTrimer {
    /// The pairs of atoms.
    const PAIRS: [(usize, usize); 3] = [(0, 1), (1, 2), (0, 2)];
    /// The equilateral minimum, centred on the origin (circumradius
    /// `1/sqrt(3)`).
    const MINIMUM: [f64; 6] = [
        0.0,
        0.577_350_269_189_625_8,
        -0.5,
        -0.288_675_134_594_812_9,
        0.5,
        -0.288_675_134_594_812_9,
    ];
    /// The initial displacement from the minimum (summing to zero).
    const DISPLACEMENT: [f64; 6] = [0.04, -0.025, -0.03, 0.035, -0.01, -0.01];
    /// The pair stiffness `V''(r0) = 72 eps / r0^2`.
    pub const STIFFNESS: f64 = 72.0;
}

impl Scene<6> for LjTrimer {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "lj-trimer",
            name: "Lennard-Jones trimer (planar vibration)",
            dimension: 6,
            parameters: "eps = 1, r0 = 1, unit masses, displaced from the equilateral minimum by (0.04, -0.025, -0.03, 0.035, -0.01, -0.01), at rest".into(),
            reference: "J. E. Lennard-Jones, Proc. R. Soc. A 106, 463 (1924); equilateral normal modes w^2 = 3k/2 (twice), 3k with k = 72 eps/r0^2",
        }
    }

    fn initial(&self) -> State<6> {
        State::new(
            SVector::from_fn(|i, _| Self::MINIMUM[i] + Self::DISPLACEMENT[i]),
            SVector::zeros(),
        )
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 6>) -> SVector<R, 6> {
        let mut a = SVector::<R, 6>::zeros();
        for (i, j) in Self::PAIRS {
            let dx = q[2 * i] - q[2 * j];
            let dy = q[2 * i + 1] - q[2 * j + 1];
            let r2 = dx * dx + dy * dy;
            let s2 = R::one() / r2;
            let s6 = s2 * s2 * s2;
            // -V'(r)/r = 12 eps (s^12 - s^6) / r^2
            let f = R::of(12.0) * (s6 * s6 - s6) * s2;
            a[2 * i] += f * dx;
            a[2 * i + 1] += f * dy;
            a[2 * j] -= f * dx;
            a[2 * j + 1] -= f * dy;
        }
        a
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 6>) -> R {
        let mut v = R::zero();
        for (i, j) in Self::PAIRS {
            let dx = q[2 * i] - q[2 * j];
            let dy = q[2 * i + 1] - q[2 * j + 1];
            let s2 = R::one() / (dx * dx + dy * dy);
            let s6 = s2 * s2 * s2;
            v += s6 * s6 - s6 * R::of(2.0);
        }
        v
    }

    /// The linearised period of the slower (degenerate) vibrational mode,
    /// `2 pi / sqrt(3k/2) = 2 pi / sqrt(108) = 0.6046`.
    fn period(&self) -> f64 {
        TAU / (1.5 * Self::STIFFNESS).sqrt()
    }

    fn exact(&self, _: f64) -> Option<State<6>> {
        None
    }
}

/// The Kepler problem `q'' = -mu q / |q|^3` in three dimensions on an
/// inclined eccentric orbit: `mu = 1`, semi-major axis `a = 1`, eccentricity
/// `e = 0.5`, inclination `i = 0.6`, longitude of the node `0.9`, argument of
/// periapsis `1.3`, started at mean anomaly `0.4` (past periapsis).
///
/// Exact solution: the mean anomaly `M = 0.4 + n t` (`n = sqrt(mu/a^3)`),
/// the eccentric anomaly `E` from Kepler's equation `E - e sin E = M`
/// (Newton's method to round-off), the orbital-plane position
/// `a (cos E - e, sqrt(1 - e^2) sin E)` and velocity
/// `a n (-sin E, sqrt(1 - e^2) cos E) / (1 - e cos E)`, rotated to space by
/// `Rz(node) Rx(i) Rz(periapsis)`. Period `2 pi / n = 2 pi`; perihelion
/// distance `0.5`, where the speed is `sqrt(3)`.
///
/// Source: H. D. Curtis, Orbital Mechanics for Engineering Students, ch. 3-4;
/// J. M. A. Danby, Fundamentals of Celestial Mechanics (1988), ch. 6.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Kepler3d;

impl Kepler3d {
    /// Eccentricity.
    pub const E: f64 = 0.5;
    /// Inclination.
    const INCLINATION: f64 = 0.6;
    /// Longitude of the ascending node.
    const NODE: f64 = 0.9;
    /// Argument of periapsis.
    const PERIAPSIS: f64 = 1.3;
    /// Mean anomaly at `t = 0`.
    const M0: f64 = 0.4;

    /// The eccentric anomaly for the mean anomaly `m`: Newton's method on
    /// `E - e sin E = m` from `E = m + e sin m`, with `m` reduced to
    /// `[-pi, pi]`, until the correction stops shrinking.
    pub fn eccentric_anomaly(m: f64, e: f64) -> f64 {
        let m = m - TAU * (m / TAU).round();
        let mut big_e = m + e * m.sin();
        let mut last = f64::INFINITY;
        for _ in 0..60 {
            let step = (big_e - e * big_e.sin() - m) / (1.0 - e * big_e.cos());
            big_e -= step;
            if step.abs() >= last || step == 0.0 {
                break;
            }
            last = step.abs();
        }
        big_e
    }

    /// The unit vectors `P` (to periapsis) and `Q` (90 degrees ahead in the
    /// orbital plane) in space.
    fn frame() -> ([f64; 3], [f64; 3]) {
        let (so, co) = Self::NODE.sin_cos();
        let (sw, cw) = Self::PERIAPSIS.sin_cos();
        let (si, ci) = Self::INCLINATION.sin_cos();
        (
            [co * cw - so * sw * ci, so * cw + co * sw * ci, sw * si],
            [-co * sw - so * cw * ci, -so * sw + co * cw * ci, cw * si],
        )
    }
}

impl Scene<3> for Kepler3d {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "kepler-3d",
            name: "Kepler problem in 3-D (inclined eccentric orbit)",
            dimension: 3,
            parameters: "mu = 1, a = 1, e = 0.5, i = 0.6, node = 0.9, periapsis = 1.3, M0 = 0.4"
                .into(),
            reference: "Kepler's equation E - e sin E = M and the perifocal-to-inertial rotation Rz(node) Rx(i) Rz(periapsis) (Curtis, Orbital Mechanics, ch. 3-4; Danby, Fundamentals of Celestial Mechanics, ch. 6)",
        }
    }

    fn initial(&self) -> State<3> {
        self.exact(0.0).expect("closed form")
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 3>) -> SVector<R, 3> {
        let r2 = q.norm_squared();
        q * -(R::one() / (r2 * r2.sqrt()))
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 3>) -> R {
        -(R::one() / q.norm())
    }

    fn period(&self) -> f64 {
        TAU
    }

    fn exact(&self, t: f64) -> Option<State<3>> {
        let e = Self::E;
        let big_e = Self::eccentric_anomaly(Self::M0 + t, e);
        let (s, c) = big_e.sin_cos();
        let root = (1.0 - e * e).sqrt();
        let (x, y) = (c - e, root * s);
        let den = 1.0 - e * c;
        let (vx, vy) = (-s / den, root * c / den);
        let (p, q) = Self::frame();
        Some(State::new(
            SVector::from_fn(|i, _| x * p[i] + y * q[i]),
            SVector::from_fn(|i, _| vx * p[i] + vy * q[i]),
        ))
    }
}

/// The periodic Toda lattice of three particles of unit mass,
/// `V = exp(q1 - q2) + exp(q2 - q3) + exp(q3 - q1) - 3`.
///
/// Integrable (Hénon's and Flaschka's integrals), reversible, and invariant
/// under translation, so the total momentum is conserved; here it is zero
/// and the centre of mass stays at the origin. Linearised about the
/// equilibrium the lattice is a ring of three unit springs with normal
/// frequencies `0, sqrt(3), sqrt(3)`; this orbit (`q = (0.3, -0.1, -0.2)`,
/// `v = (0.8, -0.2, -0.6)`, energy `0.52 + 0.20 = 0.72` above the minimum)
/// is well into the exponential (anharmonic) regime and quasi-periodic on a
/// two-torus. No elementary closed form (theta functions).
///
/// Source: M. Toda, J. Phys. Soc. Jpn. 22, 431 (1967); M. Hénon, Phys. Rev.
/// B 9, 1921 (1974); H. Flaschka, Phys. Rev. B 9, 1924 (1974).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Toda3;

impl Scene<3> for Toda3 {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "toda-3",
            name: "periodic Toda lattice (3 particles)",
            dimension: 3,
            parameters: "q0 = (0.3, -0.1, -0.2), v0 = (0.8, -0.2, -0.6)".into(),
            reference: "V = sum exp(q_i - q_(i+1)) - 3, periodic (M. Toda, J. Phys. Soc. Jpn. 22, 431 (1967); M. Hénon, Phys. Rev. B 9, 1921 (1974))",
        }
    }

    fn initial(&self) -> State<3> {
        State::new(
            SVector::from([0.3, -0.1, -0.2]),
            SVector::from([0.8, -0.2, -0.6]),
        )
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 3>) -> SVector<R, 3> {
        // the force of bond (i, i+1), exp(q_i - q_(i+1)), pushes i back and i+1 on
        let bond = |i: usize| (q[i] - q[(i + 1) % 3]).exp();
        let (b0, b1, b2) = (bond(0), bond(1), bond(2));
        SVector::from([b2 - b0, b0 - b1, b1 - b2])
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 3>) -> R {
        (q[0] - q[1]).exp() + (q[1] - q[2]).exp() + (q[2] - q[0]).exp() - R::of(3.0)
    }

    /// The linearised period `2 pi / sqrt(3)` (the orbit, deep in the
    /// anharmonic regime, runs somewhat faster).
    fn period(&self) -> f64 {
        TAU / 3f64.sqrt()
    }

    fn exact(&self, _: f64) -> Option<State<3>> {
        None
    }
}

/// The Jacobi elliptic functions `(sn, cn, dn)(u | m)`, `0 <= m < 1`, by the
/// arithmetic-geometric mean and descending Landen transformation
/// (Abramowitz and Stegun 16.4), and the complete integral `K(m)`.
fn jacobi(u: f64, m: f64) -> (f64, f64, f64, f64) {
    let mut a = [0.0; 20];
    let mut c = [0.0; 20];
    a[0] = 1.0;
    c[0] = m.sqrt();
    let mut b = (1.0 - m).sqrt();
    let mut n = 0;
    while c[n].abs() > f64::EPSILON && n < 19 {
        a[n + 1] = 0.5 * (a[n] + b);
        c[n + 1] = 0.5 * (a[n] - b);
        b = (a[n] * b).sqrt();
        n += 1;
    }
    let mut phi = 2f64.powi(n as i32) * a[n] * u;
    for k in (1..=n).rev() {
        phi = 0.5 * (phi + (c[k] / a[k] * phi.sin()).asin());
    }
    let (s, co) = phi.sin_cos();
    (s, co, (1.0 - m * s * s).sqrt(), PI / (2.0 * a[n]))
}

/// The double well `x'' = 4x - 4x^3`, `V = (x^2 - 1)^2`, on an orbit above
/// the barrier (`V(0) = 1`): energy `25/9`, turning points `+-A`,
/// `A = sqrt(8/3)`.
///
/// Exact solution `x = A cn(w t | m)` with `m = 4/5`: `cn'' = (2m - 1) cn -
/// 2m cn^3` gives `w^2 (2m - 1) = 4` and `2 m w^2 / A^2 = 4`, so `w^2 = 20/3`,
/// `A^2 = 2m/(2m - 1) = 8/3`, and the energy `V(A) = (A^2 - 1)^2 = 25/9`;
/// `v = -A w sn dn`. Period `4 K(m) / w = 3.4968`. Started at the turning
/// point `x = A`.
///
/// Source: the Duffing equation with negative linear stiffness (I. Kovacic,
/// M. J. Brennan, The Duffing Equation (2011), ch. 2); Jacobi functions:
/// Abramowitz and Stegun 16.4, 16.16.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DoubleWell;

impl DoubleWell {
    /// The parameter `m` of the elliptic functions.
    pub const M: f64 = 0.8;
    /// The amplitude `A = sqrt(2m / (2m - 1))`.
    pub fn amplitude() -> f64 {
        (2.0 * Self::M / (2.0 * Self::M - 1.0)).sqrt()
    }
    /// The angular frequency of the argument, `w = sqrt(4 / (2m - 1))`.
    pub fn w() -> f64 {
        (4.0 / (2.0 * Self::M - 1.0)).sqrt()
    }
}

impl Scene<1> for DoubleWell {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "double-well-above-barrier",
            name: "double well (x^2 - 1)^2 above the barrier",
            dimension: 1,
            parameters: "x0 = sqrt(8/3), v0 = 0 (E = 25/9, m = 4/5)".into(),
            reference: "x'' = 4x - 4x^3; x = A cn(w t | m), m = 4/5, w^2 = 20/3, A^2 = 8/3 (Kovacic and Brennan, The Duffing Equation, ch. 2; Abramowitz and Stegun 16.4)",
        }
    }

    fn initial(&self) -> State<1> {
        self.exact(0.0).expect("closed form")
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 1>) -> SVector<R, 1> {
        let x = q[0];
        SVector::from([(x - x * x * x) * R::of(4.0)])
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        let u = q[0] * q[0] - R::one();
        u * u
    }

    fn period(&self) -> f64 {
        4.0 * jacobi(0.0, Self::M).3 / Self::w()
    }

    fn exact(&self, t: f64) -> Option<State<1>> {
        let (a, w) = (Self::amplitude(), Self::w());
        let (sn, cn, dn, _) = jacobi(w * t, Self::M);
        Some(State::new(
            SVector::from([a * cn]),
            SVector::from([-a * w * sn * dn]),
        ))
    }
}

/// The golden ratio `(1 + sqrt(5))/2`, the nearest double.
const GOLDEN: f64 = 1.618_033_988_749_895;

/// Two unit masses between two walls, each tied to its wall by a spring
/// `k = 1` and to the other by a spring `kappa = phi/2` (`phi` the golden
/// ratio): `q1'' = -(k + kappa) q1 + kappa q2`, `q2'' = kappa q1 - (k +
/// kappa) q2`.
///
/// Linear, with normal modes `s = (q1 + q2)/sqrt(2)` at `w1 = sqrt(k) = 1`
/// and `d = (q1 - q2)/sqrt(2)` at `w2 = sqrt(k + 2 kappa) = sqrt(1 + phi) =
/// phi`: incommensurate frequencies (their ratio is the golden ratio, the
/// worst-approximable irrational), so the orbit never closes. Exact solution:
/// each mode `y(t) = y0 cos(w t) + (y0'/w) sin(w t)`. Started at
/// `q = (1, 0)`, `v = (0, 0.4)`, which excites both modes. Period: the slow
/// mode's `2 pi`.
///
/// Source: H. Goldstein, Classical Mechanics, ch. 6; J. R. Taylor, Classical
/// Mechanics, 11.2.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CoupledOscillators;

impl CoupledOscillators {
    /// The coupling spring `kappa = phi/2`.
    const KAPPA: f64 = 0.5 * GOLDEN;
}

impl Scene<2> for CoupledOscillators {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "coupled-oscillators",
            name: "two coupled oscillators with incommensurate frequencies",
            dimension: 2,
            parameters: "k = 1, kappa = phi/2 (w1 = 1, w2 = phi), q0 = (1, 0), v0 = (0, 0.4)"
                .into(),
            reference: "normal modes (q1 +- q2)/sqrt(2) at w^2 = k and k + 2 kappa (Goldstein, Classical Mechanics, ch. 6; Taylor, Classical Mechanics, 11.2)",
        }
    }

    fn initial(&self) -> State<2> {
        State::new(SVector::from([1.0, 0.0]), SVector::from([0.0, 0.4]))
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 2>) -> SVector<R, 2> {
        let (d, k) = (R::of(1.0 + Self::KAPPA), R::of(Self::KAPPA));
        SVector::from([-d * q[0] + k * q[1], k * q[0] - d * q[1]])
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 2>) -> R {
        let (d, k) = (R::of(1.0 + Self::KAPPA), R::of(Self::KAPPA));
        (q[0] * q[0] + q[1] * q[1]) * d * R::of(0.5) - k * q[0] * q[1]
    }

    fn period(&self) -> f64 {
        TAU
    }

    fn exact(&self, t: f64) -> Option<State<2>> {
        let s0 = self.initial();
        let r = std::f64::consts::FRAC_1_SQRT_2;
        let mode = |y: f64, v: f64, w: f64| {
            let (s, c) = (w * t).sin_cos();
            (y * c + v / w * s, v * c - y * w * s)
        };
        let (s, sv) = mode((s0.q[0] + s0.q[1]) * r, (s0.v[0] + s0.v[1]) * r, 1.0);
        let (d, dv) = mode((s0.q[0] - s0.q[1]) * r, (s0.v[0] - s0.v[1]) * r, GOLDEN);
        Some(State::new(
            SVector::from([(s + d) * r, (s - d) * r]),
            SVector::from([(sv + dv) * r, (sv - dv) * r]),
        ))
    }
}

/// A planar star (mass 1) with three planets (masses `1e-3`, `5e-4`,
/// `3e-4`, `G = 1`) on near-circular orbits of radii 1, 2 and 4, in
/// mass-weighted barycentric coordinates `x_i = sqrt(m_i) r_i`
/// (`q = (x_star, x_1, x_2, x_3)`, two components each), so that the
/// kinetic energy is `|x'|^2/2` and `x'' = -grad V(x)` with the Newtonian
/// potential `V = -sum G m_i m_j / |r_i - r_j|`: the scene's energy is the
/// physical one.
///
/// A hierarchical four-body problem: neighbouring planets are 8.4 and 10.4
/// mutual Hill radii apart (more than twice the two-planet Hill-stability
/// threshold `2 sqrt(3)`), with period ratios 2.8 and 2.8, clear of the 2:1
/// and 3:1 resonances: a regular, stable configuration (the tests follow it
/// for 10^4 inner periods). The planets start on the Keplerian circular
/// speeds about the star at angles 0.3, 2.5, 4.4, and the whole system is
/// moved to its barycentre at rest. No closed form; period: the inner
/// planet's Keplerian period `2 pi / sqrt(1 + 1e-3)`.
///
/// Source: C. D. Murray, S. F. Dermott, Solar System Dynamics (1999), ch.
/// 6 and 9; J. E. Chambers, G. W. Wetherill, A. P. Boss, Icarus 119, 261
/// (1996) (spacing in mutual Hill radii).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Planets4;

impl Planets4 {
    /// Masses: the star, then the planets from the inside out.
    pub const MASSES: [f64; 4] = [1.0, 1e-3, 5e-4, 3e-4];
    /// The planets' initial distances from the star.
    const RADII: [f64; 3] = [1.0, 2.0, 4.0];
    /// The planets' initial angles.
    const ANGLES: [f64; 3] = [0.3, 2.5, 4.4];

    /// The physical positions `r_i = x_i / sqrt(m_i)` of the four bodies.
    #[inline(always)]
    fn positions<R: Real>(x: &SVector<R, 8>) -> [[R; 2]; 4] {
        let mut r = [[R::zero(); 2]; 4];
        for (i, ri) in r.iter_mut().enumerate() {
            let w = R::of(1.0 / Self::MASSES[i].sqrt());
            *ri = [x[2 * i] * w, x[2 * i + 1] * w];
        }
        r
    }

    /// Distance between two bodies' physical positions.
    pub fn separation(s: &State<8>, i: usize, j: usize) -> f64 {
        let r = Self::positions(&s.q);
        ((r[i][0] - r[j][0]).powi(2) + (r[i][1] - r[j][1]).powi(2)).sqrt()
    }
}

impl Scene<8> for Planets4 {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "planets-4",
            name: "star and three planets (planar, mass-weighted)",
            dimension: 8,
            parameters: "G = 1, masses (1, 1e-3, 5e-4, 3e-4), radii (1, 2, 4), angles (0.3, 2.5, 4.4), circular speeds, barycentric".into(),
            reference: "Newtonian N-body problem in mass-weighted coordinates x = sqrt(m) r (Murray and Dermott, Solar System Dynamics, ch. 6, 9; Chambers, Wetherill and Boss, Icarus 119, 261 (1996))",
        }
    }

    fn initial(&self) -> State<8> {
        let m = Self::MASSES;
        let mut r = [[0.0; 2]; 4];
        let mut v = [[0.0; 2]; 4];
        for p in 1..4 {
            let (s, c) = Self::ANGLES[p - 1].sin_cos();
            let radius = Self::RADII[p - 1];
            let speed = ((m[0] + m[p]) / radius).sqrt();
            r[p] = [radius * c, radius * s];
            v[p] = [-speed * s, speed * c];
        }
        let total: f64 = m.iter().sum();
        for k in 0..2 {
            let rc: f64 = (0..4).map(|i| m[i] * r[i][k]).sum::<f64>() / total;
            let vc: f64 = (0..4).map(|i| m[i] * v[i][k]).sum::<f64>() / total;
            for i in 0..4 {
                r[i][k] -= rc;
                v[i][k] -= vc;
            }
        }
        State::new(
            SVector::from_fn(|n, _| r[n / 2][n % 2] * m[n / 2].sqrt()),
            SVector::from_fn(|n, _| v[n / 2][n % 2] * m[n / 2].sqrt()),
        )
    }

    #[inline(always)]
    fn acceleration<R: Real>(&self, q: &SVector<R, 8>) -> SVector<R, 8> {
        let m = Self::MASSES;
        let r = Self::positions(q);
        let mut g = [[R::zero(); 2]; 4];
        for i in 0..4 {
            for j in i + 1..4 {
                let dx = r[i][0] - r[j][0];
                let dy = r[i][1] - r[j][1];
                let d2 = dx * dx + dy * dy;
                let inv3 = R::one() / (d2 * d2.sqrt());
                let (mi, mj) = (R::of(m[i]) * inv3, R::of(m[j]) * inv3);
                g[i][0] -= dx * mj;
                g[i][1] -= dy * mj;
                g[j][0] += dx * mi;
                g[j][1] += dy * mi;
            }
        }
        // x_i'' = sqrt(m_i) r_i''
        SVector::from_fn(|n, _| g[n / 2][n % 2] * R::of(m[n / 2].sqrt()))
    }

    #[inline(always)]
    fn potential<R: Real>(&self, q: &SVector<R, 8>) -> R {
        let m = Self::MASSES;
        let r = Self::positions(q);
        let mut v = R::zero();
        for i in 0..4 {
            for j in i + 1..4 {
                let dx = r[i][0] - r[j][0];
                let dy = r[i][1] - r[j][1];
                v -= R::of(m[i] * m[j]) / (dx * dx + dy * dy).sqrt();
            }
        }
        v
    }

    fn period(&self) -> f64 {
        TAU / (Self::MASSES[0] + Self::MASSES[1]).sqrt()
    }

    fn exact(&self, _: f64) -> Option<State<8>> {
        None
    }
}

// ====================================================================== schemes

/// The claims of an explicit scheme with no hand-derived phase error.
const fn explicit(
    id: &'static str,
    name: &'static str,
    order: u32,
    symplectic: bool,
    symmetric: bool,
    force_evaluations: u32,
    reference: &'static str,
) -> SchemeMeta {
    SchemeMeta {
        id,
        name,
        order,
        symplectic,
        symmetric,
        force_evaluations,
        implicit: false,
        reference,
        phase_error: None,
    }
}

/// The same claims under another id and name (what a buggy copy claims).
const fn posing_as(base: SchemeMeta, id: &'static str, name: &'static str) -> SchemeMeta {
    SchemeMeta {
        id,
        name,
        phase_error: None,
        ..base
    }
}

// ------------------------------------------------------------ explicit Runge-Kutta

/// An explicit Runge-Kutta method with Butcher tableau `(a, b, c)` on the
/// first-order system `y = (q, v)`, `y' = (v, a(q))`: stage `i` is
/// `Y_i = y + h sum_(j<i) a_ij k_j`, `k_i = f(Y_i)`, the step
/// `y' = y + h sum b_i k_i`. The entries on and above the diagonal are
/// ignored; `c` (the row sums) documents the tableau and serves the tests.
/// One force evaluation per stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ButcherRk<const S: usize> {
    /// The claims.
    pub meta: SchemeMeta,
    /// The Runge-Kutta matrix (strictly lower triangle used).
    pub a: [[f64; S]; S],
    /// The weights.
    pub b: [f64; S],
    /// The nodes.
    pub c: [f64; S],
}

impl<const S: usize> OneStep for ButcherRk<S> {
    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    #[inline(always)]
    fn advance<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let mut kq = [SVector::<R, D>::zeros(); S];
        let mut kv = [SVector::<R, D>::zeros(); S];
        for i in 0..S {
            let (mut q, mut v) = (s.q, s.v);
            for j in 0..i {
                let aij = self.a[i][j];
                if aij != 0.0 {
                    let w = h * R::of(aij);
                    q += kq[j] * w;
                    v += kv[j] * w;
                }
            }
            kq[i] = v;
            kv[i] = scene.acceleration(&q);
        }
        let (mut dq, mut dv) = (SVector::<R, D>::zeros(), SVector::<R, D>::zeros());
        for ((bi, q), v) in self.b.iter().zip(&kq).zip(&kv) {
            if *bi != 0.0 {
                dq += q * R::of(*bi);
                dv += v * R::of(*bi);
            }
        }
        s.q += dq * h;
        s.v += dv * h;
        Ok(())
    }
}

/// Butcher's sixth-order method with seven stages (1964):
/// `c = (0, 1/3, 2/3, 1/3, 1/2, 1/2, 1)`, `b = (11/120, 0, 27/40, 27/40,
/// -4/15, -4/15, 11/120)`.
///
/// Order six (all 37 Butcher trees of order up to six hold in exact
/// rationals; checked in the tests), the fewest stages for order six;
/// neither symplectic nor symmetric (explicit).
pub const BUTCHER6: ButcherRk<7> = ButcherRk {
    meta: explicit(
        "butcher6",
        "Butcher's sixth-order Runge-Kutta method (7 stages)",
        6,
        false,
        false,
        7,
        "J. C. Butcher, J. Austral. Math. Soc. 4, 179 (1964); J. C. Butcher, Numerical Methods for Ordinary Differential Equations (2016), 325",
    ),
    a: BUTCHER6_A,
    b: [
        11.0 / 120.0,
        0.0,
        27.0 / 40.0,
        27.0 / 40.0,
        -4.0 / 15.0,
        -4.0 / 15.0,
        11.0 / 120.0,
    ],
    c: [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0, 0.5, 0.5, 1.0],
};

/// Butcher's sixth-order matrix.
const BUTCHER6_A: [[f64; 7]; 7] = [
    [0.0; 7],
    [1.0 / 3.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.0, 2.0 / 3.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0 / 12.0, 1.0 / 3.0, -1.0 / 12.0, 0.0, 0.0, 0.0, 0.0],
    [
        -1.0 / 16.0,
        9.0 / 8.0,
        -3.0 / 16.0,
        -3.0 / 8.0,
        0.0,
        0.0,
        0.0,
    ],
    [0.0, 9.0 / 8.0, -3.0 / 8.0, -3.0 / 4.0, 0.5, 0.0, 0.0],
    [
        9.0 / 44.0,
        -9.0 / 11.0,
        63.0 / 44.0,
        18.0 / 11.0,
        0.0,
        -16.0 / 11.0,
        0.0,
    ],
];

/// Runge's third-order method (1895), four stages: `k1 = f(y)`,
/// `k2 = f(y + h/2 k1)`, `k3 = f(y + h k2)`, `k4 = f(y + h k3)`,
/// `y' = y + h (k1 + 4 k2 + k4)/6`.
///
/// Third order: `sum b c^2 = 1/3` and `sum b a c = b4 a43 c3 = 1/6`; of the
/// fourth-order trees `sum b c^3 = 1/4` holds but `sum b c a c = 1/6`, not
/// 1/8. Neither symplectic nor symmetric.
pub const RUNGE3: ButcherRk<4> = ButcherRk {
    meta: explicit(
        "runge3",
        "Runge's third-order method (4 stages)",
        3,
        false,
        false,
        4,
        "C. Runge, Math. Ann. 46, 167 (1895); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.1",
    ),
    a: [
        [0.0; 4],
        [0.5, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ],
    b: [1.0 / 6.0, 2.0 / 3.0, 0.0, 1.0 / 6.0],
    c: [0.0, 0.5, 1.0, 1.0],
};

/// Kutta's 3/8 rule: `c = (0, 1/3, 2/3, 1)`, `a21 = 1/3`, `a31 = -1/3`,
/// `a32 = 1`, `a41 = 1`, `a42 = -1`, `a43 = 1`, `b = (1, 3, 3, 1)/8`.
///
/// Fourth order (all eight trees of order up to four), a different map from
/// the classical RK4 on nonlinear problems (on linear ones both are the
/// Taylor polynomial of degree four); neither symplectic nor symmetric.
pub const KUTTA38: ButcherRk<4> = ButcherRk {
    meta: explicit(
        "kutta-3-8",
        "Kutta's 3/8 rule (fourth order)",
        4,
        false,
        false,
        4,
        "W. Kutta, Z. Math. Phys. 46, 435 (1901); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.1",
    ),
    a: [
        [0.0; 4],
        [1.0 / 3.0, 0.0, 0.0, 0.0],
        [-1.0 / 3.0, 1.0, 0.0, 0.0],
        [1.0, -1.0, 1.0, 0.0],
    ],
    b: [0.125, 0.375, 0.375, 0.125],
    c: [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0],
};

/// BROKEN: [`BUTCHER6`] with the two inner entries of its fourth row
/// swapped, `a42 = -1/12`, `a43 = 1/3` (instead of `1/3, -1/12`).
///
/// The row sum `c4 = 1/3` is kept, so every condition built from row sums
/// alone still holds (`sum b = 1`, `sum b c = 1/2`, `sum b c^2 = 1/3`), but
/// the tall third-order tree `sum b_i a_ij c_j = 1/6` gains
/// `b4 (a42' - a42)(c2 - c3) = (27/40)(-5/12)(-1/3) = 3/32`: ORDER 2 (the
/// local error gains `(3/32) h^3 f' f' f`, the tall tree, which linear
/// problems see too). Neither symplectic nor symmetric, as claimed. Claims
/// order 6.
pub const BUTCHER6_SWAPPED: ButcherRk<7> = {
    let mut t = BUTCHER6;
    t.a[3][1] = -1.0 / 12.0;
    t.a[3][2] = 1.0 / 3.0;
    t.meta = posing_as(
        BUTCHER6.meta,
        "butcher6-swapped-a42-a43",
        "Butcher's sixth order with a42 and a43 swapped",
    );
    t
};

/// What [`DifferencedVelocity`] carries: the inner scheme's state, the
/// position one step earlier, and whether a step has been taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PositionHistory<R: Real, const D: usize> {
    /// The inner scheme's synchronised state (its velocity is correct).
    pub state: State<D, R>,
    /// `q(n-1)`.
    pub previous: SVector<R, D>,
    /// At least one step has been taken.
    pub stepped: bool,
}

/// BROKEN: a correct explicit Runge-Kutta method whose output velocity is
/// the backward difference `(q(n) - q(n-1))/h` of its positions, not the
/// velocity it integrates (the stored state stays correct: the error does
/// not feed back).
///
/// `(q(n) - q(n-1))/h = v(n) - h/2 a(q(n)) + O(h^2)`: the output velocity is
/// off by `h/2 |a|`, ORDER 1 in phase space whatever the inner order, with
/// the relative error `z/2 |a|/(w |v|)` (`7.8e-3` at `T/1000` on the
/// eccentric Kepler orbit, where `|a|` peaks at perihelion).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DifferencedVelocity<const S: usize> {
    /// The (false) claims.
    pub meta: SchemeMeta,
    /// The correct stepper.
    pub inner: ButcherRk<S>,
}

impl<const S: usize> Scheme for DifferencedVelocity<S> {
    type Carry<R: Real, const D: usize> = PositionHistory<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        _: &P,
        s: &State<D, R>,
        _: R,
    ) -> PositionHistory<R, D> {
        PositionHistory {
            state: *s,
            previous: s.q,
            stepped: false,
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut PositionHistory<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        c.previous = c.state.q;
        self.inner.advance(scene, &mut c.state, h)?;
        c.stepped = true;
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &PositionHistory<R, D>, h: R) -> State<D, R> {
        if c.stepped {
            State::new(c.state.q, (c.state.q - c.previous) / h)
        } else {
            c.state
        }
    }
}

/// BROKEN: [`BUTCHER6`]'s positions with backward-difference velocities
/// (see [`DifferencedVelocity`]): ORDER 1, claims order 6.
pub const BUTCHER6_DIFFERENCED: DifferencedVelocity<7> = DifferencedVelocity {
    meta: posing_as(
        BUTCHER6.meta,
        "butcher6-differenced-velocity",
        "Butcher's sixth order reporting (q(n) - q(n-1))/h as the velocity",
    ),
    inner: BUTCHER6,
};

// ------------------------------------------------------------ Runge-Kutta-Nyström

/// An explicit Runge-Kutta-Nyström method for `q'' = a(q)`:
/// `k_i = a(q + c_i h v + h^2 sum_(j<i) a_ij k_j)`,
/// `q' = q + h v + h^2 sum b_bar_i k_i`, `v' = v + h sum b_i k_i`.
/// One force evaluation per stage (no first-same-as-last saving).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rkn<const S: usize> {
    /// The claims.
    pub meta: SchemeMeta,
    /// The nodes.
    pub c: [f64; S],
    /// The stage matrix of the `h^2` terms (strictly lower triangle used).
    pub a: [[f64; S]; S],
    /// The position weights.
    pub b_bar: [f64; S],
    /// The velocity weights.
    pub b: [f64; S],
}

impl<const S: usize> OneStep for Rkn<S> {
    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    #[inline(always)]
    fn advance<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let h2 = h * h;
        let mut k = [SVector::<R, D>::zeros(); S];
        for i in 0..S {
            let mut q = s.q + s.v * (h * R::of(self.c[i]));
            for (kj, &aij) in k[..i].iter().zip(&self.a[i]) {
                if aij != 0.0 {
                    q += kj * (h2 * R::of(aij));
                }
            }
            k[i] = scene.acceleration(&q);
        }
        let (mut dq, mut dv) = (SVector::<R, D>::zeros(), SVector::<R, D>::zeros());
        for ((ki, bb), b) in k.iter().zip(&self.b_bar).zip(&self.b) {
            dq += ki * R::of(*bb);
            dv += ki * R::of(*b);
        }
        s.q += s.v * h + dq * h2;
        s.v += dv * h;
        Ok(())
    }
}

/// The nodes of RKN6(4)6FD: `(0, (209 - r)/900, (209 - r)/450,
/// (209 + r)/450, 9/10, 1)`, `r = sqrt(8581)`, each the nearest double (from
/// 25 digits).
const DPRKN6_C: [f64; 6] = [
    0.0,
    0.129_295_903_136_704_42,
    0.258_591_806_273_408_83,
    0.670_297_082_615_48,
    0.9,
    1.0,
];

/// `b_bar_3 = (84119543 + 366727 r)/409622616` of RKN6(4)6FD.
const DPRKN6_BB3: f64 = 0.288_291_741_189_766_8;
/// `b_bar_4 = (84119543 - 366727 r)/409622616` of RKN6(4)6FD.
const DPRKN6_BB4: f64 = 0.122_425_537_174_570_41;

/// The sixth-order solution of Dormand and Prince's RKN6(4)6FD triple at
/// fixed step (the embedded fourth-order solution and the dense output
/// unused). Six stages, the last at `c = 1` with `a_6j = b_bar_j` (first
/// same as last, not exploited here: six force evaluations).
///
/// Coefficients in `r = sqrt(8581)`, as published, typed as the nearest
/// doubles (the tests recompute them from the closed forms). Sixth order:
/// the quadrature conditions `sum b c^k = 1/(k+1)` (`k <= 5`) and `sum b_bar
/// c^k = 1/((k+1)(k+2))` (`k <= 4`) and the row sums `sum_j a_ij = c_i^2/2`
/// hold to round-off (tests), and the measured order on the 3-D Kepler orbit
/// is six. Neither symplectic nor symmetric.
pub const DPRKN6: Rkn<6> = Rkn {
    meta: explicit(
        "dprkn6",
        "Dormand-Prince RKN6(4)6FD (sixth-order Runge-Kutta-Nystrom, fixed step)",
        6,
        false,
        false,
        6,
        "J. R. Dormand, P. J. Prince, Comput. Math. Appl. 13, 937 (1987) (RKN6(4)6FD); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.14",
    ),
    c: DPRKN6_C,
    a: [
        [0.0; 6],
        [0.008_358_715_283_968_025, 0.0, 0.0, 0.0, 0.0, 0.0],
        [
            0.011_144_953_711_957_367,
            0.022_289_907_423_914_734,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.145_474_742_801_091_8,
            -0.229_860_640_522_647_49,
            0.309_034_987_202_967_5,
            0.0,
            0.0,
            0.0,
        ],
        [
            -0.207_668_262_950_789_97,
            0.686_366_784_292_514_3,
            -0.199_549_277_872_349_25,
            0.125_850_756_530_624_89,
            0.0,
            0.0,
        ],
        [
            0.078_110_161_443_494_78,
            0.0,
            DPRKN6_BB3,
            DPRKN6_BB4,
            0.011_172_560_192_168_035,
            0.0,
        ],
    ],
    b_bar: [
        0.078_110_161_443_494_78,
        0.0,
        DPRKN6_BB3,
        DPRKN6_BB4,
        0.011_172_560_192_168_035,
        0.0,
    ],
    b: [
        0.078_110_161_443_494_78,
        0.0,
        0.388_843_478_705_982_6,
        0.371_320_757_928_842_3,
        0.111_725_601_921_680_35,
        0.05,
    ],
};

/// BROKEN: [`DPRKN6`] with the sign of `r = sqrt(8581)` typed the wrong
/// way in its position weights: `b_bar_3` and `b_bar_4`, the conjugate pair
/// `(84119543 +- 366727 r)/409622616`, swapped (the stage matrix, the
/// velocity weights and so the sixth stage are untouched).
///
/// `sum b_bar = 1/2` is kept (the pair's sum is symmetric in the sign), but
/// `sum b_bar c`, which must be `1/6`, gains `(b_bar_4 - b_bar_3)(c_3 -
/// c_4) = (-0.1659)(-0.4117) = +0.0683`: every step adds `0.0683 h^3 a'(q)
/// v` to the position, a local error `O(h^3)`: ORDER 2. Neither symplectic
/// nor symmetric, as claimed. Claims order 6.
pub const DPRKN6_SWAPPED: Rkn<6> = {
    let mut t = DPRKN6;
    t.b_bar[2] = DPRKN6_BB4;
    t.b_bar[3] = DPRKN6_BB3;
    t.meta = posing_as(
        DPRKN6.meta,
        "dprkn6-conjugate-swap",
        "Dormand-Prince RKN6 with the sign of sqrt(8581) flipped in b_bar",
    );
    t
};

// --------------------------------------------------------------------- splittings

/// One sub-step of a splitting method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sub {
    /// `q += w h v`.
    Drift,
    /// `v += w h a(q)`.
    Kick,
}

/// A splitting method: a sequence of drifts and kicks with weights. With
/// `lagged_force` (a bug) every kick uses the force at the position where
/// the preceding drift started (computed before the drift and not
/// refreshed after it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Splitting<const N: usize> {
    /// The claims; `force_evaluations` is the number of kicks.
    pub meta: SchemeMeta,
    /// The sub-steps, applied first to last.
    pub sequence: [(Sub, f64); N],
    /// Kicks use the force before the preceding drift (the bug).
    pub lagged_force: bool,
}

impl<const N: usize> Splitting<N> {
    /// The method with these claims and sub-steps; `force_evaluations` is
    /// set to the number of kicks.
    pub const fn new(mut meta: SchemeMeta, sequence: [(Sub, f64); N], lagged_force: bool) -> Self {
        let mut kicks = 0;
        let mut i = 0;
        while i < N {
            if matches!(sequence[i].0, Sub::Kick) {
                kicks += 1;
            }
            i += 1;
        }
        meta.force_evaluations = kicks;
        Self {
            meta,
            sequence,
            lagged_force,
        }
    }
}

impl<const N: usize> OneStep for Splitting<N> {
    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    #[inline(always)]
    fn advance<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let mut before_drift = s.q;
        for &(sub, w) in &self.sequence {
            match sub {
                Sub::Drift => {
                    before_drift = s.q;
                    s.q += s.v * (h * R::of(w));
                }
                Sub::Kick => {
                    let at = if self.lagged_force { before_drift } else { s.q };
                    s.v += scene.acceleration(&at) * (h * R::of(w));
                }
            }
        }
        Ok(())
    }
}

/// The triple-jump weight `x1 = 1/(2 - 2^(1/3))`, the nearest double (from
/// 25 digits, `1.351207191959657634047688`).
pub const TRIPLE_X1: f64 = 1.351_207_191_959_657_5;
/// The triple-jump weight `x0 = -2^(1/3)/(2 - 2^(1/3)) = 1 - 2 x1`, the
/// nearest double (`-1.702414383919315268095376`).
pub const TRIPLE_X0: f64 = -1.702_414_383_919_315_3;

/// The Candy-Rozmus sub-steps: position Verlet (`D(1/2) K(1) D(1/2)`)
/// composed with the triple jump `x1, x0, x1`.
const CANDY_ROZMUS_SEQUENCE: [(Sub, f64); 7] = [
    (Sub::Drift, 0.5 * TRIPLE_X1),
    (Sub::Kick, TRIPLE_X1),
    (Sub::Drift, 0.5 * (TRIPLE_X1 + TRIPLE_X0)),
    (Sub::Kick, TRIPLE_X0),
    (Sub::Drift, 0.5 * (TRIPLE_X1 + TRIPLE_X0)),
    (Sub::Kick, TRIPLE_X1),
    (Sub::Drift, 0.5 * TRIPLE_X1),
];

/// Candy and Rozmus's fourth-order symplectic integrator, drift first:
/// `D(x1/2) K(x1) D((x1+x0)/2) K(x0) D((x1+x0)/2) K(x1) D(x1/2)`, the
/// triple jump of POSITION Verlet (the catalogue's Forest-Ruth composes
/// velocity Verlet; the two are different maps with different error
/// constants).
///
/// Fourth order (`2 x1 + x0 = 1`, `2 x1^3 + x0^3 = 0`, and the palindrome
/// cancels the even terms; the tests check the series up to `h^4` on random
/// matrices), symplectic (exact flows), symmetric (a palindrome). Three
/// force evaluations per step.
pub const CANDY_ROZMUS4: Splitting<7> = Splitting::new(
    explicit(
        "candy-rozmus4",
        "Candy-Rozmus fourth order (drift-first triple jump)",
        4,
        true,
        true,
        0,
        "J. Candy, W. Rozmus, J. Comput. Phys. 92, 230 (1991); E. Forest, R. D. Ruth, Physica D 43, 105 (1990)",
    ),
    CANDY_ROZMUS_SEQUENCE,
    false,
);

/// BROKEN: [`CANDY_ROZMUS4`] whose kicks use the force computed before the
/// preceding drift (the loop evaluates `a(q)`, drifts, then kicks with the
/// stale value): kick `i` uses `a(q - d_i h v)` where it needs `a(q)`.
///
/// The total impulse is off by `h^2 a'(q) v sum_i c_i d_i` to leading order,
/// `sum c_i d_i = x1 (x1/2) + x0 (x1 + x0)/2 + x1 (x1 + x0)/2 = 0.97455`,
/// so the velocity takes a local error `O(h^2)`: ORDER 1. The kicks are no
/// longer flows of the potential at the current position, so NOT
/// symplectic: on the oscillator `x'' = -w^2 x` the step's determinant is
/// `1 + 0.97455 z^2 + O(z^4)` (the tests measure `0.9746 z^2` at `z =
/// 0.01`), an exponential growth of the energy by `e^(0.97 z^2)` a step,
/// which the long run (`z = 2 pi/100`, `10^6` steps) cannot survive (the
/// Toda lattice blows up, the trimer dissociates); and NOT symmetric.
/// Claims order 4, symplectic, symmetric.
pub const CANDY_ROZMUS4_LAGGED: Splitting<7> = Splitting::new(
    posing_as(
        CANDY_ROZMUS4.meta,
        "candy-rozmus4-lagged-force",
        "Candy-Rozmus fourth order kicking with the force from before each drift",
    ),
    CANDY_ROZMUS_SEQUENCE,
    true,
);

/// Blanes-Moan `SRKN_6^b` drift weights `a1, a2` (to the published 15
/// digits); `a3 = 1/2 - a1 - a2`.
const SRKN6B_A: [f64; 2] = [0.245_298_957_184_271, 0.604_872_665_711_080];
/// Blanes-Moan `SRKN_6^b` kick weights `b1, b2, b3`; `b4 = 1 - 2 (b1 + b2 +
/// b3)`.
const SRKN6B_B: [f64; 3] = [
    0.082_984_406_417_405_2,
    0.396_309_801_498_368,
    -0.039_056_304_922_348_6,
];

/// The `SRKN_6^b` sequence with the kick weights `b1, b2, b3` (so that a
/// typo can be made in one of them).
const fn srkn6b(b: [f64; 3]) -> [(Sub, f64); 13] {
    let a3 = 0.5 - (SRKN6B_A[0] + SRKN6B_A[1]);
    let b4 = 1.0 - 2.0 * (b[0] + b[1] + b[2]);
    [
        (Sub::Kick, b[0]),
        (Sub::Drift, SRKN6B_A[0]),
        (Sub::Kick, b[1]),
        (Sub::Drift, SRKN6B_A[1]),
        (Sub::Kick, b[2]),
        (Sub::Drift, a3),
        (Sub::Kick, b4),
        (Sub::Drift, a3),
        (Sub::Kick, b[2]),
        (Sub::Drift, SRKN6B_A[1]),
        (Sub::Kick, b[1]),
        (Sub::Drift, SRKN6B_A[0]),
        (Sub::Kick, b[0]),
    ]
}

/// Blanes and Moan's symplectic Runge-Kutta-Nyström splitting `SRKN_6^b`:
/// the palindrome `K(b1) D(a1) K(b2) D(a2) K(b3) D(a3) K(b4) D(a3) K(b3)
/// D(a2) K(b2) D(a1) K(b1)`, six force evaluations with first same as last
/// (seven here, without the saving).
///
/// Fourth order even for general splittings `A + B` (the tests check the
/// series up to `h^4` on random matrices, `h^5` not), optimised for `q'' =
/// a(q)` where its fifth- and sixth-order error terms are small;
/// symplectic, symmetric.
pub const SRKN6B: Splitting<13> = Splitting::new(
    explicit(
        "blanes-moan-srkn6b",
        "Blanes-Moan symplectic RKN splitting SRKN6b (order 4)",
        4,
        true,
        true,
        0,
        "S. Blanes, P. C. Moan, J. Comput. Appl. Math. 142, 313 (2002), table 3 (SRKN_6^b)",
    ),
    srkn6b(SRKN6B_B),
    false,
);

/// BROKEN: [`SRKN6B`] with the small negative kick weight `b3 =
/// -0.0391` typed positive (in both of its places, so the palindrome stays),
/// the middle weight `b4 = 1 - 2 (b1 + b2 + b3)` computed from the typed
/// ones as the paper prescribes (`-0.0367` instead of `0.1195`).
///
/// The weights still sum to one in drifts and in kicks (consistent), the
/// sequence is still a palindrome of exact flows: SYMPLECTIC and SYMMETRIC,
/// so the even-order terms of the error vanish and the energy stays bounded.
/// But the third-order conditions, which need the original `b3`, fail (the
/// tests find the `h^3` Taylor coefficient off by 3% of its size on random
/// matrices, 11% with the Nyström structure): ORDER 2. Claims order 4.
pub const SRKN6B_SIGN_FLIPPED: Splitting<13> = Splitting::new(
    posing_as(
        SRKN6B.meta,
        "blanes-moan-srkn6b-b3-sign",
        "Blanes-Moan SRKN6b with the sign of b3 flipped",
    ),
    srkn6b([SRKN6B_B[0], SRKN6B_B[1], -SRKN6B_B[2]]),
    false,
);

// --------------------------------------------------------------------- Beeman

/// What Beeman's algorithm carries: the state, `a(q(n))` and `a(q(n-1))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BeemanCarry<R: Real, const D: usize> {
    /// The synchronised state.
    pub state: State<D, R>,
    /// `a(q(n))`.
    pub a: SVector<R, D>,
    /// `a(q(n-1))`.
    pub a_previous: SVector<R, D>,
}

/// Beeman's algorithm (1976), as used in molecular dynamics:
/// `q(n+1) = q(n) + h v(n) + h^2 (p0 a(n) + p1 a(n-1))`,
/// `v(n+1) = v(n) + h (w0 a(n+1) + w1 a(n) + w2 a(n-1))`, with Beeman's
/// `p = (4, -1)/6`, `w = (2, 5, -1)/6`.
///
/// Start-up: `a(-1) = a(q0 - h v0 + h^2/2 a(q0))`, a second-order Taylor
/// step back (two force evaluations at the start, one a step after).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beeman {
    /// The claims.
    pub meta: SchemeMeta,
    /// The position weights `(p0, p1)` of `a(n)` and `a(n-1)`.
    pub position: [f64; 2],
    /// The velocity weights `(w0, w1, w2)` of `a(n+1)`, `a(n)`, `a(n-1)`.
    pub velocity: [f64; 3],
}

impl Scheme for Beeman {
    type Carry<R: Real, const D: usize> = BeemanCarry<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        h: R,
    ) -> BeemanCarry<R, D> {
        let a = scene.acceleration(&s.q);
        let back = s.q - s.v * h + a * (h * h * R::of(0.5));
        BeemanCarry {
            state: *s,
            a,
            a_previous: scene.acceleration(&back),
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut BeemanCarry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        let [p0, p1] = self.position.map(R::of);
        let [w0, w1, w2] = self.velocity.map(R::of);
        let q = c.state.q + c.state.v * h + (c.a * p0 + c.a_previous * p1) * (h * h);
        let a = scene.acceleration(&q);
        let v = c.state.v + (a * w0 + c.a * w1 + c.a_previous * w2) * h;
        c.state = State::new(q, v);
        c.a_previous = c.a;
        c.a = a;
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &BeemanCarry<R, D>, _: R) -> State<D, R> {
        c.state
    }
}

/// Beeman's algorithm with its published coefficients.
///
/// Global ORDER 2: eliminating the velocities gives exactly the two-step
/// Störmer-Verlet recursion `q(n+1) - 2 q(n) + q(n-1) = h^2 a(n)` for the
/// positions (from the second step on), whose global error is `O(h^2)`;
/// the velocities are a local third-order formula of those positions
/// (local error `h^3 a''/12`). As a map of `(q, v)` (start-up, one step,
/// output) neither symplectic nor symmetric (on the double well the step's
/// determinant is `1 - 0.40` at `h = 0.3`, and 50 steps of `h = 0.1` there
/// and back miss by 0.18), and it claims neither.
pub const BEEMAN: Beeman = Beeman {
    meta: explicit(
        "beeman",
        "Beeman's algorithm",
        2,
        false,
        false,
        1,
        "D. Beeman, J. Comput. Phys. 20, 130 (1976); M. P. Allen, D. J. Tildesley, Computer Simulation of Liquids (2017), 3.2.2",
    ),
    position: [4.0 / 6.0, -1.0 / 6.0],
    velocity: [2.0 / 6.0, 5.0 / 6.0, -1.0 / 6.0],
};

/// BROKEN: Beeman with a sign typo in the position update, `h^2 (4 a(n) +
/// a(n-1))/6` instead of `(4 a(n) - a(n-1))/6`.
///
/// The `h^2` coefficient sums to `5/6`, not `1/2`; eliminating the
/// velocities, the positions obey `q(n+1) - 2 q(n) + q(n-1) = h^2 (a(n) +
/// (a(n-1) - a(n-2))/3)`: Störmer's recursion with the force perturbed by
/// `-(h/3) da/dt`, and the first step's `q1` is `h^2/3 a(q0)` too far (a
/// velocity error `h/3 a(q0)` carried along). ORDER 1, with a relative
/// error of order `z w t / 3` (`1.1e-3` on the trimer and `2.3e-2` on the
/// Toda lattice at `T/1000`). Claims order 2.
pub const BEEMAN_SIGN_TYPO: Beeman = Beeman {
    meta: posing_as(
        BEEMAN.meta,
        "beeman-sign-typo",
        "Beeman's algorithm with +a(n-1) in the position update",
    ),
    position: [4.0 / 6.0, 1.0 / 6.0],
    velocity: BEEMAN.velocity,
};

/// BROKEN (a false claim): Beeman's algorithm, correct, claiming to be
/// time-symmetric because its positions are Störmer-Verlet's.
///
/// The positions are symmetric in that sense, but the scheme's map of
/// `(q, v)` is not: its velocity formula `v(n+1) = v(n) + h (2 a(n+1) +
/// 5 a(n) - a(n-1))/6` is not invariant under exchanging past and future,
/// and its start-up extrapolates `a(n-1)`; `h` then `-h` misses the start
/// (by 0.18 after 50 steps of `h = 0.1` each way on the double well, whose
/// scale is 1.6). Its energy does not drift: the positions are those of
/// the Störmer-Verlet recursion (bounded modified-energy error), and the
/// velocities a fixed local formula of three consecutive positions, so the
/// energy error stays an `O(h^2)` oscillation. Second order, not symplectic
/// (not claimed).
pub const BEEMAN_CLAIMS_SYMMETRIC: Beeman = Beeman {
    meta: SchemeMeta {
        symmetric: true,
        ..posing_as(
            BEEMAN.meta,
            "beeman-claims-symmetric",
            "Beeman's algorithm claiming time symmetry",
        )
    },
    ..BEEMAN
};

// ------------------------------------------------------ Adams-Bashforth-Moulton

/// What the Adams-Bashforth-Moulton scheme carries: the state and the last
/// four slopes `f = (v, a(q))`, newest first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdamsCarry<R: Real, const D: usize> {
    /// The synchronised state.
    pub state: State<D, R>,
    /// Velocity slopes `v(n), v(n-1), v(n-2), v(n-3)`.
    pub fv: [SVector<R, D>; 4],
    /// Acceleration slopes `a(n), ..., a(n-3)`.
    pub fa: [SVector<R, D>; 4],
}

/// The Adams-Bashforth-Moulton predictor-corrector in PECE mode on
/// `y = (q, v)`, `y' = f(y) = (v, a(q))`: predict with the four-step
/// Adams-Bashforth formula `y~ = y(n) + h/24 (55 f(n) - 59 f(n-1) + 37
/// f(n-2) - 9 f(n-3))`, evaluate, correct with a three-step Adams-Moulton
/// formula `y(n+1) = y(n) + h (g0 f~ + g1 f(n) + g2 f(n-1) + g3 f(n-2))`,
/// evaluate: two force evaluations per step.
///
/// Start-up: the history `y(-1), y(-2), y(-3)` from three classical RK4
/// steps of `-h` (local errors `O(h^5)`), or, with `cold_start` (a bug),
/// every past slope set to `f(y0)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Abm4 {
    /// The claims.
    pub meta: SchemeMeta,
    /// The corrector weights `(g0, g1, g2, g3)`.
    pub corrector: [f64; 4],
    /// Fill the history with `f(y0)` instead of computing it.
    pub cold_start: bool,
}

impl Scheme for Abm4 {
    type Carry<R: Real, const D: usize> = AdamsCarry<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        h: R,
    ) -> AdamsCarry<R, D> {
        let a0 = scene.acceleration(&s.q);
        let mut c = AdamsCarry {
            state: *s,
            fv: [s.v; 4],
            fa: [a0; 4],
        };
        if !self.cold_start {
            let mut y = *s;
            for k in 1..4 {
                // the classical RK4 never fails
                let _ = OneStep::advance(&Rk4, scene, &mut y, -h);
                c.fv[k] = y.v;
                c.fa[k] = scene.acceleration(&y.q);
            }
        }
        c
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut AdamsCarry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        const BASHFORTH: [f64; 4] = [55.0 / 24.0, -59.0 / 24.0, 37.0 / 24.0, -9.0 / 24.0];
        let (q0, v0) = (c.state.q, c.state.v);
        let (mut qp, mut vp) = (q0, v0);
        for (k, beta) in BASHFORTH.iter().enumerate() {
            let w = h * R::of(*beta);
            qp += c.fv[k] * w;
            vp += c.fa[k] * w;
        }
        let ap = scene.acceleration(&qp);
        let g = self.corrector.map(|x| h * R::of(x));
        let q = q0 + vp * g[0] + c.fv[0] * g[1] + c.fv[1] * g[2] + c.fv[2] * g[3];
        let v = v0 + ap * g[0] + c.fa[0] * g[1] + c.fa[1] * g[2] + c.fa[2] * g[3];
        let a = scene.acceleration(&q);
        c.fv = [v, c.fv[0], c.fv[1], c.fv[2]];
        c.fa = [a, c.fa[0], c.fa[1], c.fa[2]];
        c.state = State::new(q, v);
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &AdamsCarry<R, D>, _: R) -> State<D, R> {
        c.state
    }
}

/// The three-step Adams-Moulton weights `(9, 19, -5, 1)/24` (order 4).
const MOULTON4: [f64; 4] = [9.0 / 24.0, 19.0 / 24.0, -5.0 / 24.0, 1.0 / 24.0];

/// The fourth-order Adams-Bashforth-Moulton pair (AB4 predictor, AM4
/// corrector, PECE) with an RK4 start-up.
///
/// ORDER 4: both formulas have order four, and in PECE mode the order is
/// `min(p_corrector, p_predictor + 1) = 4`; the start-up's local errors
/// `O(h^5)` keep it. Zero-stable (Adams: `rho(x) = x^3 (x - 1)`). Neither
/// symplectic nor symmetric, as claimed (a multistep method is not a
/// one-step map; its energy is not promised).
pub const ABM4: Abm4 = Abm4 {
    meta: explicit(
        "abm4-pece",
        "Adams-Bashforth-Moulton 4 (PECE, RK4 start-up)",
        4,
        false,
        false,
        2,
        "F. Bashforth, J. C. Adams (1883); F. R. Moulton, New Methods in Exterior Ballistics (1926); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), III.1",
    ),
    corrector: MOULTON4,
    cold_start: false,
};

/// BROKEN: [`ABM4`] with the first two corrector weights swapped,
/// `(19, 9, -5, 1)/24`.
///
/// The weights still sum to one (consistent, zero-stable), but the
/// first-moment condition `19 - 5 (-1) + 1 (-2) = 22` (in 24ths), not `12`
/// (`int_0^1 t dt = 1/2`): each corrected step carries a local error
/// `(22/24 - 1/2) h^2 f' = (5/12) h^2 f'`. ORDER 1, a relative error of
/// order `(5/12) z w t` (`5e-2` to `0.12` at `T/1000` on the paired scenes).
/// Claims order 4.
pub const ABM4_SWAPPED: Abm4 = Abm4 {
    meta: posing_as(
        ABM4.meta,
        "abm4-swapped-corrector",
        "Adams-Bashforth-Moulton 4 with the corrector weights 19 and 9 swapped",
    ),
    corrector: [19.0 / 24.0, 9.0 / 24.0, -5.0 / 24.0, 1.0 / 24.0],
    cold_start: false,
};

/// BROKEN: [`ABM4`] started cold, every past slope `f(-1), f(-2), f(-3)`
/// set to `f(y0)` (a start-up of order zero instead of RK4).
///
/// The past slopes are off by `-k h f'`, and they enter the first three
/// steps multiplied by `h`: with a constant history the predictor is
/// Euler's step and the first corrected step misses by `h^2 f'/8`, the next
/// two by similar amounts; those `O(h^2)` errors are then carried along like
/// a perturbed initial condition. ORDER 2 (capped by the start-up, the
/// formulas being fourth order), with a relative error of order `z^2` times
/// the orbit's sensitivity (`1.7e-4` on the planets, `3.9e-3` on the
/// eccentric Kepler orbit at `T/1000`). Claims order 4.
pub const ABM4_COLD_START: Abm4 = Abm4 {
    meta: posing_as(
        ABM4.meta,
        "abm4-cold-start",
        "Adams-Bashforth-Moulton 4 with the history filled with f(y0)",
    ),
    corrector: MOULTON4,
    cold_start: true,
};

// ------------------------------------------------------------- Lobatto IIIA-IIIB

/// Iterations an implicit solve may take.
pub const SOLVE_ITERATIONS: u32 = 60;

/// Units of round-off at which a solve counts as converged.
const SOLVE_UNITS: f64 = 8.0;

/// What an implicit partitioned Runge-Kutta method carries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartitionedCarry<R: Real, const D: usize, const S: usize> {
    /// The synchronised state.
    pub state: State<D, R>,
    /// The last stage accelerations, the next solve's guess.
    pub k: [SVector<R, D>; S],
    /// Force evaluations spent since `start` (the start's one included).
    pub evaluations: u64,
}

/// An implicit partitioned Runge-Kutta method for `q' = v`, `v' = a(q)`:
/// `Q_i = q + h sum_j aq_ij V_j`, `V_i = v + h sum_j av_ij k_j`,
/// `k_i = a(Q_i)`, `q' = q + h sum b_i V_i`, `v' = v + h sum b_i k_i`. The
/// stage accelerations are found by fixed-point iteration from the previous
/// step's (`a(q0)` at the start), each iteration evaluating every stage,
/// until the stage positions stop moving at round-off; a solve that does not
/// get there in [`SOLVE_ITERATIONS`] fails and leaves the state unchanged.
///
/// With `closing_force_from_start` (a bug) the velocity update uses the
/// first stage's force `k_1` in place of the last stage's `k_S`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartitionedRk<const S: usize> {
    /// The claims; `force_evaluations` is `S` per iteration.
    pub meta: SchemeMeta,
    /// The matrix of the position stages.
    pub aq: [[f64; S]; S],
    /// The matrix of the velocity stages.
    pub av: [[f64; S]; S],
    /// The weights (shared).
    pub b: [f64; S],
    /// The nodes.
    pub c: [f64; S],
    /// Close the step with `k_1` instead of `k_S` (the bug).
    pub closing_force_from_start: bool,
}

impl<const S: usize> PartitionedRk<S> {
    /// The stage positions and velocities for stage accelerations `k`.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn stages<R: Real, const D: usize>(
        &self,
        q: &SVector<R, D>,
        v: &SVector<R, D>,
        k: &[SVector<R, D>; S],
        h: R,
    ) -> ([SVector<R, D>; S], [SVector<R, D>; S]) {
        let mut vs = [*v; S];
        for (vi, row) in vs.iter_mut().zip(&self.av) {
            for (kj, &a) in k.iter().zip(row) {
                if a != 0.0 {
                    *vi += kj * (h * R::of(a));
                }
            }
        }
        let mut qs = [*q; S];
        for (qi, row) in qs.iter_mut().zip(&self.aq) {
            for (vj, &a) in vs.iter().zip(row) {
                if a != 0.0 {
                    *qi += vj * (h * R::of(a));
                }
            }
        }
        (qs, vs)
    }
}

impl<const S: usize> Scheme for PartitionedRk<S> {
    type Carry<R: Real, const D: usize> = PartitionedCarry<R, D, S>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        _: R,
    ) -> PartitionedCarry<R, D, S> {
        PartitionedCarry {
            state: *s,
            k: [scene.acceleration(&s.q); S],
            evaluations: 1,
        }
    }

    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut PartitionedCarry<R, D, S>,
        h: R,
    ) -> Result<(), StepFailure> {
        let (q0, v0) = (c.state.q, c.state.v);
        let units = R::of(SOLVE_UNITS) * R::default_epsilon();
        let mut k = c.k;
        let (mut qs, _) = self.stages(&q0, &v0, &k, h);
        let mut previous: Option<R> = None;
        let mut correction = R::zero();
        for _ in 0..SOLVE_ITERATIONS {
            for (ki, qi) in k.iter_mut().zip(&qs) {
                *ki = scene.acceleration(qi);
            }
            c.evaluations += S as u64;
            let (next, vs) = self.stages(&q0, &v0, &k, h);
            correction = R::zero();
            let mut size = (v0 * h).norm_squared();
            for (n, q) in next.iter().zip(&qs) {
                correction += (n - q).norm_squared();
                size += q0.norm_squared() + n.norm_squared();
            }
            qs = next;
            if !(correction.is_finite() && size.is_finite()) {
                break;
            }
            let settled = correction == R::zero() || previous.is_some_and(|p| correction >= p);
            if correction <= units * units * size && settled {
                let (mut dq, mut dv) = (SVector::<R, D>::zeros(), SVector::<R, D>::zeros());
                for i in 0..S {
                    let ki = if self.closing_force_from_start && i == S - 1 {
                        k[0]
                    } else {
                        k[i]
                    };
                    dq += vs[i] * (h * R::of(self.b[i]));
                    dv += ki * (h * R::of(self.b[i]));
                }
                c.state = State::new(q0 + dq, v0 + dv);
                c.k = k;
                return Ok(());
            }
            previous = Some(correction);
        }
        Err(StepFailure::NotConverged {
            iterations: SOLVE_ITERATIONS,
            residual: correction.sqrt().to_subset().unwrap_or(f64::NAN),
        })
    }

    fn state<R: Real, const D: usize>(&self, c: &PartitionedCarry<R, D, S>, _: R) -> State<D, R> {
        c.state
    }

    fn solver_evaluations<R: Real, const D: usize>(
        &self,
        c: &PartitionedCarry<R, D, S>,
    ) -> Option<u64> {
        Some(c.evaluations)
    }
}

/// The three-stage Lobatto IIIA matrix.
const LOBATTO_IIIA: [[f64; 3]; 3] = [
    [0.0, 0.0, 0.0],
    [5.0 / 24.0, 1.0 / 3.0, -1.0 / 24.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
];

/// The three-stage Lobatto IIIB matrix.
const LOBATTO_IIIB: [[f64; 3]; 3] = [
    [1.0 / 6.0, -1.0 / 6.0, 0.0],
    [1.0 / 6.0, 1.0 / 3.0, 0.0],
    [1.0 / 6.0, 5.0 / 6.0, 0.0],
];

/// The claims of the Lobatto IIIA-IIIB pair.
const LOBATTO_PAIR_META: SchemeMeta = SchemeMeta {
    id: "lobatto-iiia-iiib3",
    name: "Lobatto IIIA-IIIB partitioned pair (3 stages, order 4)",
    order: 4,
    symplectic: true,
    symmetric: true,
    force_evaluations: 3,
    implicit: true,
    reference: "L. O. Jay, SIAM J. Numer. Anal. 33, 368 (1996); E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration (2006), II.2.2 and VI.4",
    phase_error: None,
};

/// The three-stage Lobatto IIIA-IIIB pair: positions by Lobatto IIIA,
/// velocities by Lobatto IIIB, `b = (1, 4, 1)/6`, `c = (0, 1/2, 1)`.
///
/// On `q'' = a(q)` it reduces to an implicit Runge-Kutta-Nyström method
/// with `k1 = a(q)`, `k2 = a(q + h/2 v + h^2 (k1/12 + k2/24))` (the only
/// implicit stage), `q' = q + h v + h^2 (k1/6 + k2/3)`, `k3 = a(q')`,
/// `v' = v + h (k1 + 4 k2 + k3)/6`. ORDER 4 (`2s - 2`), SYMPLECTIC (`b_i
/// av_ij + b_j aq_ji = b_i b_j` for all `i, j`; as an RKN, `b_bar_i =
/// b_i (1 - c_i)` and `b_i (b_bar_j - a_ij) = b_j (b_bar_i - a_ji)`),
/// SYMMETRIC (the pair is its own adjoint), implicit: the partitioned
/// analogue of Störmer-Verlet, which is the two-stage pair.
pub const LOBATTO_IIIA_IIIB: PartitionedRk<3> = PartitionedRk {
    meta: LOBATTO_PAIR_META,
    aq: LOBATTO_IIIA,
    av: LOBATTO_IIIB,
    b: [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    c: [0.0, 0.5, 1.0],
    closing_force_from_start: false,
};

/// BROKEN: the Lobatto IIIA-IIIB pair with the IIIA matrix typed for the
/// velocity stages too: the (non-partitioned) three-stage Lobatto IIIA
/// collocation method, claiming the pair's symplecticity.
///
/// Lobatto IIIA is still ORDER 4 and SYMMETRIC (a symmetric collocation
/// method), so its energy does not drift on reversible integrable scenes,
/// but it is NOT symplectic: `2 b1 a11 = 0`, not `b1^2 = 1/36`. On linear
/// problems it is the (2,2) Padé approximant of the exponential, which is
/// symplectic: the defect shows only through the force's curvature (the
/// tests measure `det - 1 = 6.4e-4` at `h = 0.3` on the double well and
/// `|J^T W J - W| = 3e-4` at `h = T/10` on the Toda lattice). Claims order
/// 4, symplectic, symmetric.
pub const LOBATTO_IIIA_BOTH: PartitionedRk<3> = PartitionedRk {
    meta: posing_as(
        LOBATTO_PAIR_META,
        "lobatto-iiia-for-both",
        "Lobatto IIIA-IIIB with the IIIA matrix used for the velocities too",
    ),
    av: LOBATTO_IIIA,
    ..LOBATTO_IIIA_IIIB
};

/// BROKEN: the Lobatto IIIA-IIIB pair closing its velocity update with the
/// force at the start of the step, `v' = v + h (k1 + 4 k2 + k1)/6`, instead
/// of the force `k3 = a(q')` at its end (a first-same-as-last cache read
/// before it is refreshed).
///
/// The velocity weights become `(1/3, 2/3, 0)` at nodes `(0, 1/2, 1)`:
/// `sum b c = 1/3`, not `1/2`, a local velocity error `-h^2/6 da/dt`:
/// ORDER 1. The force at the end no longer enters, so the step is NOT
/// symmetric, and NOT symplectic (`b_bar_1 = 1/6` against `b_1 (1 - c_1) =
/// 1/3`): on the oscillator the step's determinant is `1 + z^2/6 + O(z^4)`,
/// an exponential energy growth of `e^(z^2/6)` a step, which the long run
/// (`z = 2 pi/100`, `10^6` steps) turns into a blow-up. Claims order 4,
/// symplectic, symmetric.
pub const LOBATTO_STALE_CLOSING_FORCE: PartitionedRk<3> = PartitionedRk {
    meta: posing_as(
        LOBATTO_PAIR_META,
        "lobatto-iiia-iiib-stale-closing-force",
        "Lobatto IIIA-IIIB closing the velocity with the start-of-step force",
    ),
    closing_force_from_start: true,
    ..LOBATTO_IIIA_IIIB
};

// ======================================================================= entries

/// Broken on the order claim only; the other claims not judged.
const ORDER_FAILS: Expected = Expected::ANY.order(Expect::Fail);

/// Broken on the order, symplecticity and symmetry claims; the energy not
/// judged (the long run blows up or its solve fails).
const STALE_FORCE: Expected = Expected::ANY
    .order(Expect::Fail)
    .symplectic(Expect::Fail)
    .reversible(Expect::Fail);

/// The held-out entries: 17 correct pairs and 20 broken ones.
pub fn entries() -> Vec<Entry> {
    vec![
        // ------------------------------------------------------------ correct
        Entry::correct(
            &BEEMAN,
            LjTrimer,
            "Beeman's positions are exactly the Störmer-Verlet recursion and its velocities a local formula of them: global order 2 (measured 2.00 on the trimer); it claims neither symplecticity nor symmetry, so nothing is promised of its energy or tangent map and every claim must pass.",
        ),
        Entry::correct(
            &BEEMAN,
            DoubleWell,
            "Order 2 on any smooth scene (measured 2.00 against the cn solution); its one-step map is neither symplectic (det - 1 = -0.40 at h = 0.3) nor reversible, but it claims neither, so every claim must pass.",
        ),
        Entry::correct(
            &ABM4,
            Kepler3d,
            "AB4 predictor, AM4 corrector (PECE) with an RK4 start-up of local order 5: global order 4 (4.03 on the oscillator, 4.7 pre-asymptotically on this orbit); a multistep method claiming nothing geometric, so even its energy wander over 10^4 periods (|dE| up to 0.5) must not fail it.",
        ),
        Entry::correct(
            &ABM4,
            CoupledOscillators,
            "Order 4 on this linear scene (measured 4.1); PECE Adams methods are weakly unstable on the imaginary axis and its energy creeps up over the long run, but it claims neither symplecticity nor symmetry: every claim must pass.",
        ),
        Entry::correct(
            &LOBATTO_IIIA_IIIB,
            DoubleWell,
            "The three-stage Lobatto IIIA-IIIB pair is order 4, symplectic (b_i av_ij + b_j aq_ji = b_i b_j exactly) and symmetric, its implicit stage solved to round-off (det - 1 = 4e-12, return 7e-15); the energy error stays bounded (7.7e-6 in the first and last thousand periods): every claim must pass.",
        ),
        Entry::correct(
            &LOBATTO_IIIA_IIIB,
            Toda3,
            "Order 4 (measured 4.00), symplectic and symmetric; on the integrable Toda lattice its energy error stays bounded (6.6e-8 over 10^4 linearised periods): every claim must pass.",
        ),
        Entry::correct(
            &BUTCHER6,
            CoupledOscillators,
            "Butcher's seven-stage method satisfies all 37 order conditions up to six exactly and fails at seven: order 6 (measured 6.00 on this linear scene); explicit, it claims neither symplecticity nor symmetry.",
        ),
        Entry::correct(
            &BUTCHER6,
            Planets4,
            "Order 6 on a smooth, collision-free four-body orbit (measured 6.4 against a fine reference between T/25 and T/50); it claims nothing geometric, so every claim must pass.",
        ),
        Entry::correct(
            &RUNGE3,
            Kepler3d,
            "Runge's four-stage method is exactly third order (sum b c a c = 1/6, not 1/8, blocks order four; measured 3.01 on the orbit); it claims nothing geometric.",
        ),
        Entry::correct(
            &RUNGE3,
            LjTrimer,
            "Third order (measured 3.02 on the trimer vibration); explicit, claiming neither symplecticity nor symmetry: every claim must pass.",
        ),
        Entry::correct(
            &CANDY_ROZMUS4,
            Kepler3d,
            "The drift-first triple jump of position Verlet is order 4 (its series matches exp(h(A+B)) to h^4), symplectic and symmetric; on the eccentric orbit its energy error stays bounded (5.3e-5 in the first and last thousand periods).",
        ),
        Entry::correct(
            &CANDY_ROZMUS4,
            Planets4,
            "Order 4 (measured 3.96), symplectic, symmetric; the hierarchical system stays regular (neighbouring planets never closer than 1.0 over 10^4 inner periods) and the energy error bounded (1e-11).",
        ),
        Entry::correct(
            &DPRKN6,
            Kepler3d,
            "Dormand-Prince RKN6(4)6FD, coefficients matching the published closed forms in sqrt(8581) to round-off: order 6 (6.00 on the oscillator, 6.8 pre-asymptotically on this orbit); it claims nothing geometric.",
        ),
        Entry::correct(
            &DPRKN6,
            Toda3,
            "Order 6 (measured 6.06 against a fine reference); an explicit Nyström method claiming neither symplecticity nor symmetry: every claim must pass.",
        ),
        Entry::correct(
            &SRKN6B,
            LjTrimer,
            "Blanes-Moan SRKN_6^b is a palindromic composition of exact flows of order 4 (series checked to h^4): symplectic and symmetric, with a bounded energy error (1e-10) on the regular small-amplitude vibration.",
        ),
        Entry::correct(
            &SRKN6B,
            DoubleWell,
            "Order 4 (measured 4.09), symplectic and symmetric; on the 1-D orbit above the barrier its energy error stays bounded (4.2e-8 over 10^4 periods): every claim must pass.",
        ),
        Entry::correct(
            &KUTTA38,
            Toda3,
            "Kutta's 3/8 rule satisfies all eight trees up to order four and fails at five: order 4 (measured 4.04 on the lattice); it claims nothing geometric.",
        ),
        // ------------------------------------------------------------- broken
        Entry::broken(
            &BEEMAN_SIGN_TYPO,
            LjTrimer,
            ORDER_FAILS,
            "Typing +a(n-1) in Beeman's position update makes the h^2 coefficient 5/6: Störmer's recursion perturbed by -(h/3) da/dt plus an O(h) start error, ORDER 1 < 2, with a relative error of 1.1e-3 at T/1000 (measured order 0.99), far above 1e-7.",
        ),
        Entry::broken(
            &BEEMAN_SIGN_TYPO,
            Toda3,
            ORDER_FAILS,
            "The +a(n-1) typo makes Beeman first order (an -(h/3) da/dt force perturbation): relative error 2.3e-2 at T/1000, measured order 0.97, so the claim of order 2 must fail.",
        ),
        Entry::broken(
            &BEEMAN_CLAIMS_SYMMETRIC,
            DoubleWell,
            Expected::PASS.reversible(Expect::Fail),
            "Beeman's (q, v) map is not time-symmetric (50 steps of h = 0.1 there and back miss by 0.18 on a scale of 1.6), so the claim must fail; its positions are Störmer-Verlet's and its velocities a local formula of them, so the energy error stays a bounded oscillation (7.5e-3 in the first and last thousand periods) and order 2 and the energy pass, symplecticity not being claimed.",
        ),
        Entry::broken(
            &ABM4_SWAPPED,
            CoupledOscillators,
            ORDER_FAILS,
            "Corrector weights (19, 9, -5, 1)/24 still sum to one but have first moment 22/24, not 1/2: a local error (5/12) h^2 f', ORDER 1 < 4 (relative error 0.12 at T/1000, measured order 0.92).",
        ),
        Entry::broken(
            &ABM4_SWAPPED,
            Toda3,
            ORDER_FAILS,
            "The swapped corrector weights leave a consistent but first-order method: relative error 5.4e-2 at T/1000, measured order 0.95, against the claimed 4.",
        ),
        Entry::broken(
            &ABM4_COLD_START,
            Kepler3d,
            ORDER_FAILS,
            "Past slopes set to f(y0) are O(h) wrong and enter the first steps multiplied by h: O(h^2) start errors carried along the orbit, ORDER 2 < 4 (relative error 3.9e-3 at T/1000, measured order 2.00).",
        ),
        Entry::broken(
            &ABM4_COLD_START,
            Planets4,
            ORDER_FAILS,
            "The cold start caps the fourth-order Adams pair at ORDER 2: relative error 1.7e-4 at T/1000 against a fine reference, measured order 2.00.",
        ),
        Entry::broken(
            &DPRKN6_SWAPPED,
            Kepler3d,
            ORDER_FAILS,
            "Swapping the conjugate weights (84119543 +- 366727 sqrt(8581))/409622616 of b_bar keeps sum b_bar = 1/2 but makes sum b_bar c = 1/6 + 0.068: a local position error 0.068 h^3 a' v, ORDER 2 < 6 (relative error 6.1e-4 at T/1000, measured order 1.84).",
        ),
        Entry::broken(
            &DPRKN6_SWAPPED,
            LjTrimer,
            ORDER_FAILS,
            "The b_bar sign typo leaves ORDER 2: relative error 1.3e-6 at T/1000 (measured order 2.00), thirteen times the 1e-7 threshold and far above round-off.",
        ),
        Entry::broken(
            &CANDY_ROZMUS4_LAGGED,
            Toda3,
            STALE_FORCE,
            "Kicks with the force from before the preceding drift miss the impulse by 0.9746 h^2 a' v a step: ORDER 1 < 4 (relative error 6.7e-2 at T/1000, order 1.06), and no longer exact flows, so NOT symplectic and NOT symmetric (det = 1 + 0.975 z^2 on the oscillator); the long run blows up, so its energy verdict is left open.",
        ),
        Entry::broken(
            &CANDY_ROZMUS4_LAGGED,
            LjTrimer,
            STALE_FORCE.energy(Expect::Fail),
            "The lagged force makes the composition ORDER 1 (relative error 3.2e-3 at T/1000, order 1.07), neither symplectic nor symmetric; its determinant above one pumps energy in until the trimer dissociates within the long run (|dE| = 3.2 against a vibrational energy of 0.086), so the energy claim fails too.",
        ),
        Entry::broken(
            &SRKN6B_SIGN_FLIPPED,
            Kepler3d,
            ORDER_FAILS
                .energy(Expect::Pass)
                .symplectic(Expect::Pass)
                .reversible(Expect::Pass),
            "Flipping b3 (with b4 recomputed from the sum) keeps consistency, the palindrome and exact flows, hence symplecticity, symmetry and a bounded energy, but breaks the third-order condition: ORDER 2 < 4, relative error 2.9e-4 at T/1000 (measured order 2.00); only the order must fail.",
        ),
        Entry::broken(
            &SRKN6B_SIGN_FLIPPED,
            Planets4,
            ORDER_FAILS
                .energy(Expect::Pass)
                .symplectic(Expect::Pass)
                .reversible(Expect::Pass),
            "Still a symplectic, symmetric palindrome of exact flows (energy error bounded at 3e-10) but only ORDER 2 after the sign flip: relative error 3.0e-5 at T/1000, measured order 2.00, against the claimed 4.",
        ),
        Entry::broken(
            &LOBATTO_IIIA_BOTH,
            DoubleWell,
            Expected::PASS.symplectic(Expect::Fail),
            "Lobatto IIIA alone is order 4 and symmetric but not symplectic (2 b1 a11 = 0 against b1^2 = 1/36; det - 1 = 6.4e-4 at h = 0.3 on this nonlinear well): the symplectic claim must fail, while the order, reversibility and energy (a symmetric method on a reversible periodic orbit: bounded, 4.9e-6) pass.",
        ),
        Entry::broken(
            &LOBATTO_IIIA_BOTH,
            Toda3,
            Expected::PASS.symplectic(Expect::Fail),
            "IIIA for the velocities too: order 4 and symmetric, but its tangent map is not symplectic on the nonlinear lattice (|J^T W J - W| = 3e-4 at h = T/10); symmetric on a reversible integrable scene, so no energy drift (4.1e-8 over 10^4 periods): only symplecticity must fail.",
        ),
        Entry::broken(
            &BUTCHER6_SWAPPED,
            CoupledOscillators,
            ORDER_FAILS,
            "Swapping a42 and a43 keeps the row sums but breaks the tall third-order tree sum b a c by 3/32, which linear problems see: ORDER 2 < 6 (relative error 3.0e-4 at T/1000, measured order 2.00).",
        ),
        Entry::broken(
            &BUTCHER6_SWAPPED,
            Planets4,
            ORDER_FAILS,
            "The a42/a43 swap leaves ORDER 2 (the tall third-order tree off by 3/32): relative error 1.6e-4 at T/1000 against a fine reference, measured order 1.99, against the claimed 6.",
        ),
        Entry::broken(
            &BUTCHER6_DIFFERENCED,
            Kepler3d,
            ORDER_FAILS,
            "Positions from the sixth-order method but velocities reported as (q(n) - q(n-1))/h = v - h/2 a + O(h^2): ORDER 1 < 6 in phase space (relative error 7.8e-3 at T/1000, measured order 1.00).",
        ),
        Entry::broken(
            &LOBATTO_STALE_CLOSING_FORCE,
            Toda3,
            STALE_FORCE,
            "Closing the velocity with k1 in place of k3 makes the velocity weights (1/3, 2/3, 0): sum b c = 1/3, ORDER 1 < 4 (relative error 1.1e-2 at T/1000, measured order 1.01), and the step is neither symplectic nor symmetric (det = 1 + z^2/6 on the oscillator); the long run blows up until the solve fails, so the energy is left open.",
        ),
        Entry::broken(
            &LOBATTO_STALE_CLOSING_FORCE,
            DoubleWell,
            STALE_FORCE,
            "The start-of-step closing force leaves ORDER 1 (relative error 0.27 at T/1000, measured order 0.98) and destroys symplecticity (det - 1 = 0.12 at h = 0.3) and symmetry (return error 4.7 after 50 steps there and back); energy left open (the run blows up).",
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::Verdict;
    use crate::measure::scene_check::check_scene;
    use crate::run::integrate;
    use crate::scene::Harmonic;
    use nalgebra::{DMatrix, SMatrix, SymmetricEigen};

    /// Numbers in scientific notation.
    fn sci(v: &[f64]) -> String {
        let items: Vec<String> = v.iter().map(|x| format!("{x:.1e}")).collect();
        format!("[{}]", items.join(", "))
    }

    // ------------------------------------------------------------------ scenes

    fn checked<S: Scene<D>, const D: usize>(scene: &S) {
        let r = check_scene(scene);
        println!(
            "{:<28} force {:.1e} curl {:.1e} velocity {:?} acceleration {:?}",
            r.scene,
            r.force_residual,
            r.curl_residual,
            r.velocity_residual,
            r.acceleration_residual
        );
        assert_eq!(r.verdict, Verdict::Pass, "{r:?}");
    }

    #[test]
    fn every_scene_passes_the_scene_check() {
        checked(&LjTrimer);
        checked(&Kepler3d);
        checked(&Toda3);
        checked(&DoubleWell);
        checked(&CoupledOscillators);
        checked(&Planets4);
    }

    /// `-da/dq` by central differences.
    fn hessian<S: Scene<D>, const D: usize>(scene: &S, q: &SVector<f64, D>) -> SMatrix<f64, D, D> {
        let e = 1e-6;
        SMatrix::from_fn(|i, j| {
            let mut p = *q;
            let mut m = *q;
            p[j] += e;
            m[j] -= e;
            -(scene.acceleration(&p)[i] - scene.acceleration(&m)[i]) / (2.0 * e)
        })
    }

    fn sorted_eigenvalues<const D: usize>(h: SMatrix<f64, D, D>) -> Vec<f64> {
        let sym = (h + h.transpose()) * 0.5;
        let dynamic = DMatrix::from_iterator(D, D, sym.iter().copied());
        let mut ev: Vec<f64> = SymmetricEigen::new(dynamic)
            .eigenvalues
            .iter()
            .copied()
            .collect();
        ev.sort_by(f64::total_cmp);
        ev
    }

    #[test]
    fn the_trimer_minimum_has_the_equilateral_normal_modes() {
        let s = LjTrimer;
        let q = SVector::<f64, 6>::from(LjTrimer::MINIMUM);
        assert!(s.acceleration(&q).norm() < 1e-12);
        assert!((s.potential(&q) + 3.0).abs() < 1e-14);
        let ev = sorted_eigenvalues(hessian(&s, &q));
        println!("trimer Hessian eigenvalues {ev:?}");
        let expected = [0.0, 0.0, 0.0, 108.0, 108.0, 216.0];
        for (e, x) in ev.iter().zip(expected) {
            assert!((e - x).abs() < 1e-4, "{ev:?}");
        }
        assert!((s.period() - TAU / 108f64.sqrt()).abs() < 1e-15);
        let s0 = s.initial();
        let excitation = s.energy(&s0) + 3.0;
        println!("trimer vibrational energy {excitation:.4}");
        assert!(excitation > 0.02 && excitation < 0.2);
        // centre of mass at the origin, at rest
        for k in 0..2 {
            assert!((s0.q[k] + s0.q[k + 2] + s0.q[k + 4]).abs() < 1e-15);
        }
    }

    #[test]
    fn the_toda_lattice_linearises_to_a_ring_of_springs() {
        let ev = sorted_eigenvalues(hessian(&Toda3, &SVector::zeros()));
        println!("Toda Hessian eigenvalues {ev:?}");
        for (e, x) in ev.iter().zip([0.0, 3.0, 3.0]) {
            assert!((e - x).abs() < 1e-6, "{ev:?}");
        }
        let s = Toda3.initial();
        assert!(s.v.sum().abs() < 1e-15 && s.q.sum().abs() < 1e-15);
        println!("Toda energy {:.4}", Toda3.energy(&s));
    }

    #[test]
    fn exact_solutions_are_periodic_and_conserve_their_integrals() {
        // Kepler: energy -1/2, |L| = sqrt(1 - e^2), L_z/|L| = cos i, period 2 pi
        let k = Kepler3d;
        for j in 0..40 {
            let t = 0.37 * j as f64;
            let s = k.exact(t).unwrap();
            assert!((k.energy(&s) + 0.5).abs() < 1e-14, "{}", k.energy(&s));
            let l = s.q.cross(&s.v);
            assert!((l.norm() - 0.75f64.sqrt()).abs() < 1e-14);
            assert!((l[2] / l.norm() - 0.6f64.cos()).abs() < 1e-14);
            let later = k.exact(t + k.period()).unwrap();
            assert!(k.phase_distance(&s, &later) < 1e-13);
        }
        // the double well: energy 25/9, x = -A at T/2, x = 0 at T/4
        let w = DoubleWell;
        let (a, t) = (DoubleWell::amplitude(), w.period());
        println!("double well: A = {a}, T = {t}");
        assert!((t - 3.496_847_455_899).abs() < 1e-11);
        for j in 0..40 {
            let s = w.exact(0.11 * j as f64).unwrap();
            assert!((w.energy(&s) - 25.0 / 9.0).abs() < 1e-13);
        }
        assert!((w.exact(t / 2.0).unwrap().q[0] + a).abs() < 1e-13);
        assert!(w.exact(t / 4.0).unwrap().q[0].abs() < 1e-13);
        assert!(w.phase_distance(&w.exact(t).unwrap(), &w.initial()) < 1e-13);
        // the coupled oscillators: energy
        let c = CoupledOscillators;
        let e0 = c.energy(&c.initial());
        for j in 0..40 {
            let s = c.exact(0.7 * j as f64).unwrap();
            assert!((c.energy(&s) - e0).abs() < 1e-14);
        }
        assert!(c.phase_distance(&c.exact(0.0).unwrap(), &c.initial()) < 1e-15);
    }

    /// The largest phase-space distance to the exact solution over the
    /// default run, or `None` if the run did not complete.
    fn exact_error<M: Scheme, P: Scene<D>, const D: usize>(
        scheme: &M,
        scene: &P,
        steps: u64,
    ) -> Option<f64> {
        let h = scene.default_t_end() / steps as f64;
        let mut worst = 0.0f64;
        let outcome = integrate(scheme, scene, &scene.initial(), h, steps, |_, t, s| {
            worst = worst.max(scene.phase_distance(s, &scene.exact(t).expect("exact")));
        });
        outcome.completed().then_some(worst)
    }

    /// The state at the end of the default run.
    fn final_state<M: Scheme, P: Scene<D>, const D: usize>(
        scheme: &M,
        scene: &P,
        steps: u64,
    ) -> Option<State<D>> {
        let h = scene.default_t_end() / steps as f64;
        let mut last = None;
        let outcome = integrate(scheme, scene, &scene.initial(), h, steps, |_, _, s| {
            last = Some(*s)
        });
        if outcome.completed() { last } else { None }
    }

    /// The error of a run of `steps` steps: against the exact solution over
    /// the run where there is one, else at the end against Butcher's sixth
    /// order at 40 000 steps.
    fn error<M: Scheme, P: Scene<D>, const D: usize>(
        scheme: &M,
        scene: &P,
        steps: u64,
    ) -> Option<f64> {
        if scene.exact(0.0).is_some() {
            return exact_error(scheme, scene, steps);
        }
        let reference = final_state(&BUTCHER6, scene, 40_000).expect("reference");
        final_state(scheme, scene, steps).map(|s| scene.phase_distance(&s, &reference))
    }

    #[test]
    fn exact_solutions_agree_with_a_fine_integration() {
        // Butcher's sixth order at T/4000 is exact to round-off
        for (name, e) in [
            ("kepler-3d", error(&BUTCHER6, &Kepler3d, 11_314)),
            ("double-well", error(&BUTCHER6, &DoubleWell, 11_314)),
            ("coupled", error(&BUTCHER6, &CoupledOscillators, 11_314)),
        ] {
            let e = e.unwrap();
            println!("{name:<12} exact against Butcher 6 at T/4000: {e:.2e}");
            assert!(e < 1e-11, "{name}: {e:e}");
        }
    }

    // ------------------------------------------------------ Butcher trees

    /// Every rooted tree up to `max` vertices: sizes and children (indices
    /// of smaller trees, a non-decreasing multiset).
    struct Trees {
        size: Vec<usize>,
        children: Vec<Vec<usize>>,
    }

    fn trees(max: usize) -> Trees {
        fn pick(
            t: &Trees,
            below: usize,
            from: usize,
            left: usize,
            current: &mut Vec<usize>,
            out: &mut Vec<Vec<usize>>,
        ) {
            if left == 0 {
                out.push(current.clone());
                return;
            }
            for i in from..below {
                if t.size[i] <= left {
                    current.push(i);
                    pick(t, below, i, left - t.size[i], current, out);
                    current.pop();
                }
            }
        }
        let mut t = Trees {
            size: vec![1],
            children: vec![vec![]],
        };
        for n in 2..=max {
            let below = t.size.len();
            let mut out = Vec::new();
            pick(&t, below, 0, n - 1, &mut Vec::new(), &mut out);
            for ch in out {
                t.size.push(n);
                t.children.push(ch);
            }
        }
        t
    }

    /// `(order, sum b Phi(t) - 1/gamma(t))` for every tree.
    fn rk_defects<const S: usize>(m: &ButcherRk<S>, t: &Trees) -> Vec<(usize, f64)> {
        let mut phi: Vec<[f64; S]> = Vec::new();
        let mut gamma: Vec<f64> = Vec::new();
        let mut out = Vec::new();
        for n in 0..t.size.len() {
            let mut p = [1.0; S];
            let mut g = t.size[n] as f64;
            for &ch in &t.children[n] {
                for (i, pi) in p.iter_mut().enumerate() {
                    *pi *= (0..i).map(|j| m.a[i][j] * phi[ch][j]).sum::<f64>();
                }
                g *= gamma[ch];
            }
            let weight: f64 = m.b.iter().zip(&p).map(|(b, x)| b * x).sum();
            out.push((t.size[n], weight - 1.0 / g));
            phi.push(p);
            gamma.push(g);
        }
        out
    }

    /// The largest `p` such that every tree up to order `p` holds.
    fn rk_order<const S: usize>(m: &ButcherRk<S>, t: &Trees) -> usize {
        let d = rk_defects(m, t);
        let max = *t.size.last().unwrap();
        (1..=max)
            .take_while(|&p| d.iter().filter(|x| x.0 == p).all(|x| x.1.abs() < 1e-14))
            .last()
            .unwrap_or(0)
    }

    #[test]
    fn runge_kutta_tableaux_satisfy_exactly_their_order_conditions() {
        let t = trees(7);
        let counts: Vec<usize> = (1..=7)
            .map(|n| t.size.iter().filter(|&&s| s == n).count())
            .collect();
        assert_eq!(counts, [1, 1, 2, 4, 9, 20, 48]);
        for (m, claimed) in [(&RUNGE3, 3), (&KUTTA38, 4)] {
            assert_eq!(rk_order(m, &t), claimed, "{}", m.meta.id);
        }
        assert_eq!(rk_order(&BUTCHER6, &t), 6);
        assert_eq!(rk_order(&BUTCHER6_SWAPPED, &t), 2);
        // the failing third-order tree is the tall one, off by 3/32
        let d = rk_defects(&BUTCHER6_SWAPPED, &t);
        let third: Vec<f64> = d.iter().filter(|x| x.0 == 3).map(|x| x.1).collect();
        println!("butcher6-swapped third-order defects {third:?}");
        assert!(third.iter().any(|x| (x - 3.0 / 32.0).abs() < 1e-15));
        // nodes are the row sums
        fn rows<const S: usize>(m: &ButcherRk<S>) -> f64 {
            (0..S)
                .map(|i| (m.a[i].iter().sum::<f64>() - m.c[i]).abs())
                .fold(0.0, f64::max)
        }
        assert!(rows(&BUTCHER6) < 1e-15 && rows(&RUNGE3) < 1e-15 && rows(&KUTTA38) < 1e-15);
        assert!(rows(&BUTCHER6_SWAPPED) < 1e-15);
    }

    // ---------------------------------------------------- Nyström tableaux

    #[test]
    fn the_nystrom_tableau_is_the_published_one_and_satisfies_its_conditions() {
        let r = 8581f64.sqrt();
        let closed = [
            (DPRKN6.c[1], (209.0 - r) / 900.0),
            (DPRKN6.c[2], (209.0 - r) / 450.0),
            (DPRKN6.c[3], (209.0 + r) / 450.0),
            (DPRKN6.a[1][0], (26131.0 - 209.0 * r) / 810_000.0),
            (DPRKN6.a[2][0], (26131.0 - 209.0 * r) / 607_500.0),
            (DPRKN6.a[2][1], (26131.0 - 209.0 * r) / 303_750.0),
            (
                DPRKN6.a[3][0],
                (980_403_512_254.0 + 7_781_688_431.0 * r) / 11_694_469_921_875.0,
            ),
            (
                DPRKN6.a[3][1],
                -(1_262_884_486_208.0 + 15_385_481_287.0 * r) / 11_694_469_921_875.0,
            ),
            (
                DPRKN6.a[3][2],
                (7_166_233_891_441.0 + 78_694_563_299.0 * r) / 46_777_879_687_500.0,
            ),
            (
                DPRKN6.a[4][0],
                -9.0 * (329_260.0 + 3181.0 * r) / 27_040_000.0,
            ),
            (DPRKN6.a[4][1], 27.0 * (35129.0 + 3331.0 * r) / 13_520_000.0),
            (
                DPRKN6.a[4][2],
                -27.0 * (554_358_343.0 + 31_040_327.0 * r) / 464_060_480_000.0,
            ),
            (
                DPRKN6.a[4][3],
                153.0 * (8_555_257.0 - 67973.0 * r) / 2_745_920_000.0,
            ),
            (DPRKN6.b_bar[0], 329.0 / 4212.0),
            (
                DPRKN6.b_bar[2],
                (84_119_543.0 + 366_727.0 * r) / 409_622_616.0,
            ),
            (
                DPRKN6.b_bar[3],
                (84_119_543.0 - 366_727.0 * r) / 409_622_616.0,
            ),
            (DPRKN6.b_bar[4], 200.0 / 17901.0),
            (DPRKN6.b[2], (389_225_579.0 + 96856.0 * r) / 1_024_056_540.0),
            (DPRKN6.b[3], (389_225_579.0 - 96856.0 * r) / 1_024_056_540.0),
            (DPRKN6.b[4], 2000.0 / 17901.0),
        ];
        for (k, (typed, formula)) in closed.iter().enumerate() {
            assert!((typed - formula).abs() < 2e-15, "{k}: {typed} {formula}");
        }
        // row 6 is b_bar (first same as last), rows sum to c^2/2
        assert_eq!(DPRKN6.a[5], DPRKN6.b_bar);
        let quadrature = |t: &Rkn<6>| -> (Vec<f64>, Vec<f64>, f64) {
            let b: Vec<f64> = (0..7)
                .map(|k| {
                    (0..6).map(|i| t.b[i] * t.c[i].powi(k)).sum::<f64>() - 1.0 / (k + 1) as f64
                })
                .collect();
            let bb: Vec<f64> = (0..6)
                .map(|k| {
                    (0..6).map(|i| t.b_bar[i] * t.c[i].powi(k)).sum::<f64>()
                        - 1.0 / ((k + 1) * (k + 2)) as f64
                })
                .collect();
            let rows = (0..6)
                .map(|i| (t.a[i].iter().sum::<f64>() - t.c[i] * t.c[i] / 2.0).abs())
                .fold(0.0, f64::max);
            (b, bb, rows)
        };
        let (b, bb, rows) = quadrature(&DPRKN6);
        println!(
            "dprkn6: b c^k defects {}\n        b_bar c^k defects {}, rows {rows:.1e}",
            sci(&b),
            sci(&bb)
        );
        assert!(b[..6].iter().all(|x| x.abs() < 1e-15) && b[6].abs() > 1e-4);
        assert!(bb[..5].iter().all(|x| x.abs() < 1e-15) && bb[5].abs() > 1e-4);
        assert!(rows < 1e-15);
        let (_, bb, _) = quadrature(&DPRKN6_SWAPPED);
        println!("dprkn6-conjugate-swap: b_bar c^k defects {}", sci(&bb));
        assert!(bb[0].abs() < 1e-15 && (bb[1] - 0.0683).abs() < 1e-4);
    }

    #[test]
    fn the_lobatto_pair_is_symplectic_and_symmetric_and_iiia_alone_is_not_symplectic() {
        let symplectic = |m: &PartitionedRk<3>| {
            let mut worst = 0.0f64;
            for i in 0..3 {
                for j in 0..3 {
                    let d = m.b[i] * m.av[i][j] + m.b[j] * m.aq[j][i] - m.b[i] * m.b[j];
                    worst = worst.max(d.abs());
                }
            }
            worst
        };
        let symmetric = |a: &[[f64; 3]; 3], b: &[f64; 3]| {
            let mut worst = 0.0f64;
            for i in 0..3 {
                for j in 0..3 {
                    worst = worst.max((a[2 - i][2 - j] + a[i][j] - b[j]).abs());
                }
            }
            worst
        };
        let pair = &LOBATTO_IIIA_IIIB;
        assert!(symplectic(pair) < 1e-16);
        assert!(symmetric(&pair.aq, &pair.b) < 3e-16 && symmetric(&pair.av, &pair.b) < 3e-16);
        // IIIA for both: at i = j = 1, 2 b1 a11 - b1^2 = -1/36
        assert!((symplectic(&LOBATTO_IIIA_BOTH) - 1.0 / 36.0).abs() < 1e-16);
        for m in [pair, &LOBATTO_IIIA_BOTH] {
            for (row, c) in m.aq.iter().zip(&m.c) {
                assert!((row.iter().sum::<f64>() - c).abs() < 2e-16);
            }
        }
    }

    // ------------------------------------------------------------- splittings

    /// A fixed pseudo-random matrix with entries in `[-1, 1]` (SplitMix64).
    fn random_matrix<const N: usize>(seed: u64) -> SMatrix<f64, N, N> {
        let mut state = seed;
        SMatrix::from_fn(|_, _| {
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^= z >> 31;
            2.0 * (z >> 11) as f64 / (1u64 << 53) as f64 - 1.0
        })
    }

    /// Relative defects, degree by degree in `h` up to `degree`, of the
    /// Taylor series of the splitting applied to `y' = (A + B) y` (drift
    /// `A`, kick `B`) against `exp(h (A + B))`.
    fn series_defects<const N: usize, const L: usize>(
        sequence: &[(Sub, f64); L],
        drift: &SMatrix<f64, N, N>,
        kick: &SMatrix<f64, N, N>,
        degree: usize,
    ) -> Vec<f64> {
        type Series<const N: usize> = Vec<SMatrix<f64, N, N>>;
        let exp = |x: &SMatrix<f64, N, N>, w: f64| -> Series<N> {
            let mut terms = vec![SMatrix::<f64, N, N>::identity()];
            for j in 1..=degree {
                terms.push(terms[j - 1] * x * (w / j as f64));
            }
            terms
        };
        let times = |l: &Series<N>, r: &Series<N>| -> Series<N> {
            (0..=degree)
                .map(|n| (0..=n).map(|i| l[i] * r[n - i]).sum())
                .collect()
        };
        let mut product = exp(&SMatrix::zeros(), 0.0);
        for &(sub, w) in sequence {
            let x = if sub == Sub::Drift { drift } else { kick };
            product = times(&exp(x, w), &product);
        }
        let exact = exp(&(drift + kick), 1.0);
        (1..=degree)
            .map(|j| (product[j] - exact[j]).amax() / exact[j].amax())
            .collect()
    }

    #[test]
    fn splittings_satisfy_their_order_conditions() {
        let (a, b) = (
            random_matrix::<5>(0x4e1d_0001),
            random_matrix::<5>(0x4e1d_0002),
        );
        // the Nyström structure: drift q' = v, kick v' = K q
        let k = random_matrix::<3>(0x4e1d_0003);
        let rkn_drift = SMatrix::<f64, 6, 6>::from_fn(|i, j| f64::from(u8::from(j == i + 3)));
        let rkn_kick =
            SMatrix::<f64, 6, 6>::from_fn(|i, j| if i >= 3 && j < 3 { k[(i - 3, j)] } else { 0.0 });
        for (id, seq) in [
            ("candy-rozmus4", &CANDY_ROZMUS4.sequence[..]),
            ("srkn6b", &SRKN6B.sequence[..]),
        ] {
            let general = match seq.len() {
                7 => series_defects(&CANDY_ROZMUS_SEQUENCE, &a, &b, 5),
                _ => series_defects(&SRKN6B.sequence, &a, &b, 5),
            };
            let nystrom = match seq.len() {
                7 => series_defects(&CANDY_ROZMUS_SEQUENCE, &rkn_drift, &rkn_kick, 5),
                _ => series_defects(&SRKN6B.sequence, &rkn_drift, &rkn_kick, 5),
            };
            println!(
                "{id:<14} general {}\n{:<14} Nystrom {}",
                sci(&general),
                "",
                sci(&nystrom)
            );
            assert!(general[..4].iter().all(|x| *x < 1e-13), "{id}");
            assert!(general[4] > 1e-4, "{id}");
            assert!(nystrom[..4].iter().all(|x| *x < 1e-13), "{id}");
            // a palindrome
            assert!(
                seq.iter().zip(seq.iter().rev()).all(|(x, y)| x == y),
                "{id}"
            );
        }
        let flipped = series_defects(&SRKN6B_SIGN_FLIPPED.sequence, &a, &b, 4);
        let flipped_rkn = series_defects(&SRKN6B_SIGN_FLIPPED.sequence, &rkn_drift, &rkn_kick, 4);
        println!(
            "srkn6b-b3-sign general {}\n               Nystrom {}",
            sci(&flipped),
            sci(&flipped_rkn)
        );
        assert!(flipped[..2].iter().all(|x| *x < 1e-14) && flipped[2] > 1e-3);
        assert!(flipped_rkn[..2].iter().all(|x| *x < 1e-14) && flipped_rkn[2] > 1e-3);
        let kicks: f64 = SRKN6B_SIGN_FLIPPED
            .sequence
            .iter()
            .filter(|x| x.0 == Sub::Kick)
            .map(|x| x.1)
            .sum();
        assert!((kicks - 1.0).abs() < 1e-15);
        let b4 = |m: &Splitting<13>| m.sequence[6].1;
        println!(
            "srkn6b b4 = {}, with b3 flipped b4 = {}",
            b4(&SRKN6B),
            b4(&SRKN6B_SIGN_FLIPPED)
        );
        // Candy-Rozmus's triple jump
        assert!((2.0 * TRIPLE_X1 + TRIPLE_X0 - 1.0).abs() < 1e-15);
        assert!((2.0 * TRIPLE_X1.powi(3) + TRIPLE_X0.powi(3)).abs() < 1e-14);
        assert_eq!(CANDY_ROZMUS4.meta.force_evaluations, 3);
        assert_eq!(SRKN6B.meta.force_evaluations, 7);
        // the lagged force's leading impulse error, sum of c_i d_i
        let (mut d, mut sum) = (0.0, 0.0);
        for &(sub, w) in &CANDY_ROZMUS_SEQUENCE {
            match sub {
                Sub::Drift => d = w,
                Sub::Kick => sum += w * d,
            }
        }
        println!("candy-rozmus sum c_i d_i = {sum}");
        assert!((sum - 0.974_55).abs() < 1e-5);
    }

    // ---------------------------------------------------------------- orders

    /// `log2 (e(n) / e(2n))` and the errors.
    fn measured_order<M: Scheme, P: Scene<D>, const D: usize>(
        scheme: &M,
        scene: &P,
        n: u64,
    ) -> (f64, f64, f64) {
        let coarse = error(scheme, scene, n).expect("coarse run");
        let fine = error(scheme, scene, 2 * n).expect("fine run");
        ((coarse / fine).log2(), coarse, fine)
    }

    /// Steps over the default run (`2 sqrt(2)` periods) at `T / per_period`.
    fn steps(per_period: f64) -> u64 {
        (2.0 * std::f64::consts::SQRT_2 * per_period).round() as u64
    }

    fn self_check<M: Scheme, P: Scene<D>, const D: usize>(scheme: &M, scene: &P, per_period: f64) {
        let (p, coarse, fine) = measured_order(scheme, scene, steps(per_period));
        let claimed = scheme.meta().order as f64;
        println!(
            "{:<24} {:<22} T/{per_period:<5} e = {coarse:.2e} -> {fine:.2e}  order {p:.2} (claims {claimed})",
            scheme.meta().id,
            scene.meta().id
        );
        // at least the claimed order; a little more before the asymptotic
        // regime is reached
        assert!(
            p > claimed - 0.25 && p < claimed + 1.0,
            "{}: {p}",
            scheme.meta().id
        );
    }

    #[test]
    fn correct_schemes_have_their_order_on_the_oscillator_and_the_3d_orbit() {
        let osc = Harmonic::default();
        self_check(&BEEMAN, &osc, 100.0);
        self_check(&BEEMAN, &Kepler3d, 400.0);
        self_check(&ABM4, &osc, 100.0);
        self_check(&ABM4, &Kepler3d, 400.0);
        self_check(&LOBATTO_IIIA_IIIB, &osc, 50.0);
        self_check(&LOBATTO_IIIA_IIIB, &Kepler3d, 200.0);
        self_check(&LOBATTO_IIIA_IIIB, &DoubleWell, 100.0);
        self_check(&BUTCHER6, &osc, 25.0);
        self_check(&BUTCHER6, &Kepler3d, 100.0);
        self_check(&RUNGE3, &osc, 100.0);
        self_check(&RUNGE3, &Kepler3d, 400.0);
        self_check(&KUTTA38, &osc, 50.0);
        self_check(&KUTTA38, &Kepler3d, 200.0);
        self_check(&DPRKN6, &osc, 25.0);
        self_check(&DPRKN6, &Kepler3d, 200.0);
        self_check(&CANDY_ROZMUS4, &osc, 50.0);
        self_check(&CANDY_ROZMUS4, &Kepler3d, 200.0);
        self_check(&SRKN6B, &osc, 50.0);
        self_check(&SRKN6B, &Kepler3d, 200.0);
        self_check(&SRKN6B, &DoubleWell, 100.0);
        self_check(&BEEMAN_CLAIMS_SYMMETRIC, &DoubleWell, 400.0);
        self_check(&LOBATTO_IIIA_BOTH, &DoubleWell, 100.0);
    }

    /// The error at `T/1000` relative to the scene's scale, and the order
    /// measured between `T/500` and `T/1000`.
    fn defect<M: Scheme, P: Scene<D>, const D: usize>(
        scheme: &M,
        scene: &P,
        true_order: f64,
    ) -> f64 {
        let (p, _, fine) = measured_order(scheme, scene, steps(500.0));
        let relative = fine / scene.scale();
        println!(
            "{:<40} {:<26} at T/1000 relative error {relative:.2e}, order {p:.2} (theory {true_order})",
            scheme.meta().id,
            scene.meta().id
        );
        assert!(
            (p - true_order).abs() < 0.3,
            "{}: order {p}",
            scheme.meta().id
        );
        assert!(relative > 1e-6, "{}: {relative:e}", scheme.meta().id);
        relative
    }

    #[test]
    fn broken_schemes_have_their_true_order_with_a_visible_defect() {
        defect(&BEEMAN_SIGN_TYPO, &LjTrimer, 1.0);
        defect(&BEEMAN_SIGN_TYPO, &Toda3, 1.0);
        defect(&ABM4_SWAPPED, &CoupledOscillators, 1.0);
        defect(&ABM4_SWAPPED, &Toda3, 1.0);
        defect(&ABM4_COLD_START, &Kepler3d, 2.0);
        defect(&ABM4_COLD_START, &Planets4, 2.0);
        defect(&DPRKN6_SWAPPED, &Kepler3d, 2.0);
        defect(&DPRKN6_SWAPPED, &LjTrimer, 2.0);
        defect(&CANDY_ROZMUS4_LAGGED, &Toda3, 1.0);
        defect(&CANDY_ROZMUS4_LAGGED, &LjTrimer, 1.0);
        defect(&SRKN6B_SIGN_FLIPPED, &Kepler3d, 2.0);
        defect(&SRKN6B_SIGN_FLIPPED, &Planets4, 2.0);
        defect(&BUTCHER6_SWAPPED, &CoupledOscillators, 2.0);
        defect(&BUTCHER6_SWAPPED, &Planets4, 2.0);
        defect(&BUTCHER6_DIFFERENCED, &Kepler3d, 1.0);
        defect(&LOBATTO_STALE_CLOSING_FORCE, &Toda3, 1.0);
        defect(&LOBATTO_STALE_CLOSING_FORCE, &DoubleWell, 1.0);
    }

    #[test]
    fn correct_pairs_converge_on_their_scenes() {
        fn show<M: Scheme, P: Scene<D>, const D: usize>(m: &M, s: &P, per_period: f64) {
            let (p, coarse, fine) = measured_order(m, s, steps(per_period));
            println!(
                "{:<22} {:<26} T/{per_period:<5} relative {:.2e} -> {:.2e} order {p:.2}",
                m.meta().id,
                s.meta().id,
                coarse / s.scale(),
                fine / s.scale()
            );
            assert!(p > m.meta().order as f64 - 0.3, "{}", m.meta().id);
        }
        show(&BEEMAN, &LjTrimer, 200.0);
        show(&BEEMAN, &DoubleWell, 200.0);
        show(&ABM4, &Kepler3d, 200.0);
        show(&ABM4, &CoupledOscillators, 100.0);
        show(&LOBATTO_IIIA_IIIB, &DoubleWell, 100.0);
        show(&LOBATTO_IIIA_IIIB, &Toda3, 50.0);
        show(&BUTCHER6, &CoupledOscillators, 25.0);
        show(&BUTCHER6, &Planets4, 25.0);
        show(&RUNGE3, &Kepler3d, 200.0);
        show(&RUNGE3, &LjTrimer, 200.0);
        show(&CANDY_ROZMUS4, &Kepler3d, 100.0);
        show(&CANDY_ROZMUS4, &Planets4, 50.0);
        show(&DPRKN6, &Kepler3d, 50.0);
        show(&DPRKN6, &Toda3, 25.0);
        show(&SRKN6B, &LjTrimer, 50.0);
        show(&SRKN6B, &DoubleWell, 50.0);
        show(&KUTTA38, &Toda3, 50.0);
        show(&BEEMAN_CLAIMS_SYMMETRIC, &DoubleWell, 200.0);
        show(&LOBATTO_IIIA_BOTH, &DoubleWell, 100.0);
        show(&LOBATTO_IIIA_BOTH, &Toda3, 50.0);
    }

    // -------------------------------------------------------------- geometry

    /// `det - 1` of the Jacobian of `start`, one step, `state` at a point of
    /// the double well's orbit, by central differences.
    fn det_defect<M: Scheme>(scheme: &M, h: f64) -> f64 {
        let scene = DoubleWell;
        let s = scene.exact(0.4).unwrap();
        let map = |q: f64, v: f64| {
            let start = State::new(SVector::from([q]), SVector::from([v]));
            let mut c = scheme.start(&scene, &start, h);
            scheme.step(&scene, &mut c, h).expect("step");
            let out = scheme.state(&c, h);
            (out.q[0], out.v[0])
        };
        let e = 1e-5;
        let (q, v) = (s.q[0], s.v[0]);
        let (qp, vp) = map(q + e, v);
        let (qm, vm) = map(q - e, v);
        let (qp2, vp2) = map(q, v + e);
        let (qm2, vm2) = map(q, v - e);
        let j = nalgebra::Matrix2::new(qp - qm, qp2 - qm2, vp - vm, vp2 - vm2) / (2.0 * e);
        j.determinant() - 1.0
    }

    /// `h` then `-h`, 50 steps each, runs started afresh, on the double well.
    fn return_error<M: Scheme>(scheme: &M, h: f64) -> f64 {
        let scene = DoubleWell;
        let start = scene.initial();
        let mut there = start;
        integrate(scheme, &scene, &start, h, 50, |_, _, s| there = *s);
        let mut back = there;
        integrate(scheme, &scene, &there, -h, 50, |_, _, s| back = *s);
        scene.phase_distance(&back, &start)
    }

    fn geometry<M: Scheme>(scheme: &M, symplectic: bool, symmetric: bool) {
        let (det, back) = (det_defect(scheme, 0.3), return_error(scheme, 0.1));
        println!(
            "{:<40} det - 1 = {det:+.2e}  return = {back:.2e}",
            scheme.meta().id
        );
        assert_eq!(
            det.abs() < 1e-9,
            symplectic,
            "{}: {det:e}",
            scheme.meta().id
        );
        assert_eq!(back < 1e-13, symmetric, "{}: {back:e}", scheme.meta().id);
    }

    #[test]
    fn every_scheme_is_as_geometric_as_theory_says_on_the_double_well() {
        geometry(&CANDY_ROZMUS4, true, true);
        geometry(&SRKN6B, true, true);
        // still symplectic and symmetric (the palindrome of exact flows kept)
        geometry(&SRKN6B_SIGN_FLIPPED, true, true);
        // neither, since the force lags
        geometry(&CANDY_ROZMUS4_LAGGED, false, false);
        geometry(&LOBATTO_IIIA_IIIB, true, true);
        geometry(&LOBATTO_IIIA_BOTH, false, true);
        geometry(&LOBATTO_STALE_CLOSING_FORCE, false, false);
        geometry(&BEEMAN, false, false);
        geometry(&BEEMAN_CLAIMS_SYMMETRIC, false, false);
        geometry(&ABM4, false, false);
        geometry(&BUTCHER6, false, false);
        geometry(&RUNGE3, false, false);
        geometry(&KUTTA38, false, false);
        geometry(&DPRKN6, false, false);
        // on the oscillator: the leading determinants of the two stale forces
        let osc = Harmonic::default();
        for (id, coefficient, det) in [
            ("lagged", 0.9744, osc_det(&CANDY_ROZMUS4_LAGGED, &osc, 0.01)),
            (
                "stale closing",
                1.0 / 6.0,
                osc_det(&LOBATTO_STALE_CLOSING_FORCE, &osc, 0.01),
            ),
        ] {
            println!("{id}: (det - 1)/z^2 = {:.4} at z = 0.01", det / 1e-4);
            assert!((det / 1e-4 - coefficient).abs() < 0.01, "{id}: {det:e}");
        }
    }

    fn osc_det<M: Scheme>(scheme: &M, osc: &Harmonic, h: f64) -> f64 {
        let map = |q: f64, v: f64| {
            let start = State::new(SVector::from([q]), SVector::from([v]));
            let mut c = scheme.start(osc, &start, h);
            scheme.step(osc, &mut c, h).expect("step");
            let out = scheme.state(&c, h);
            (out.q[0], out.v[0])
        };
        let (q1, v1) = map(1.0, 0.0);
        let (q2, v2) = map(0.0, 1.0);
        q1 * v2 - q2 * v1 - 1.0
    }

    /// `max |J^T Omega J - Omega|` of the Jacobian `J` of `start`, one step,
    /// `state` at the scene's initial state, by central differences.
    fn symplectic_residual<M: Scheme, P: Scene<D>, const D: usize>(
        scheme: &M,
        scene: &P,
        h: f64,
    ) -> f64 {
        let s0 = scene.initial();
        let map = |x: &[f64]| -> Vec<f64> {
            let s = State::new(
                SVector::from_fn(|i, _| x[i]),
                SVector::from_fn(|i, _| x[D + i]),
            );
            let mut c = scheme.start(scene, &s, h);
            scheme.step(scene, &mut c, h).expect("step");
            let out = scheme.state(&c, h);
            out.q.iter().chain(out.v.iter()).copied().collect()
        };
        let x0: Vec<f64> = s0.q.iter().chain(s0.v.iter()).copied().collect();
        let n = 2 * D;
        let e = 1e-5;
        let mut j = DMatrix::<f64>::zeros(n, n);
        for col in 0..n {
            let (mut p, mut m) = (x0.clone(), x0.clone());
            p[col] += e;
            m[col] -= e;
            let (fp, fm) = (map(&p), map(&m));
            for row in 0..n {
                j[(row, col)] = (fp[row] - fm[row]) / (2.0 * e);
            }
        }
        let omega = DMatrix::<f64>::from_fn(n, n, |r, c| {
            if c == r + D {
                1.0
            } else if r == c + D {
                -1.0
            } else {
                0.0
            }
        });
        (j.transpose() * &omega * &j - omega).amax()
    }

    #[test]
    fn symplecticity_in_several_dimensions() {
        let toda = Toda3.period() / 10.0;
        let planets = Planets4.period() / 20.0;
        let trimer = LjTrimer.period() / 20.0;
        let kepler = Kepler3d.period() / 20.0;
        let rows = [
            (
                "lobatto-iiia-iiib3 toda",
                symplectic_residual(&LOBATTO_IIIA_IIIB, &Toda3, toda),
                true,
            ),
            (
                "lobatto-iiia-for-both toda",
                symplectic_residual(&LOBATTO_IIIA_BOTH, &Toda3, toda),
                false,
            ),
            (
                "stale-closing toda",
                symplectic_residual(&LOBATTO_STALE_CLOSING_FORCE, &Toda3, toda),
                false,
            ),
            (
                "lagged toda",
                symplectic_residual(&CANDY_ROZMUS4_LAGGED, &Toda3, toda),
                false,
            ),
            (
                "candy-rozmus4 planets",
                symplectic_residual(&CANDY_ROZMUS4, &Planets4, planets),
                true,
            ),
            (
                "srkn6b-b3-sign planets",
                symplectic_residual(&SRKN6B_SIGN_FLIPPED, &Planets4, planets),
                true,
            ),
            (
                "srkn6b trimer",
                symplectic_residual(&SRKN6B, &LjTrimer, trimer),
                true,
            ),
            (
                "lagged trimer",
                symplectic_residual(&CANDY_ROZMUS4_LAGGED, &LjTrimer, trimer),
                false,
            ),
            (
                "candy-rozmus4 kepler",
                symplectic_residual(&CANDY_ROZMUS4, &Kepler3d, kepler),
                true,
            ),
            (
                "srkn6b-b3-sign kepler",
                symplectic_residual(&SRKN6B_SIGN_FLIPPED, &Kepler3d, kepler),
                true,
            ),
        ];
        for (id, r, symplectic) in rows {
            println!("{id:<28} |J^T W J - W| = {r:.2e} (central differences)");
            // central differences are good to about 1e-7 here
            assert!(if symplectic { r < 1e-6 } else { r > 1e-5 }, "{id}: {r:e}");
        }
    }

    // ------------------------------------------------------------- long runs

    /// Energy errors over `periods` periods at 100 steps a period: the
    /// largest in the first tenth, the largest in the last tenth, and
    /// whether the run completed.
    fn long_run<M: Scheme, P: Scene<D>, const D: usize>(
        scheme: &M,
        scene: &P,
        periods: u64,
    ) -> (f64, f64, bool) {
        let n = 100 * periods;
        let h = scene.period() / 100.0;
        let e0 = scene.energy(&scene.initial());
        let (mut early, mut late) = (0.0f64, 0.0f64);
        let outcome = integrate(scheme, scene, &scene.initial(), h, n, |k, _, s| {
            let de = (scene.energy(s) - e0).abs();
            if k <= n / 10 {
                early = early.max(de);
            }
            if k >= n - n / 10 {
                late = late.max(de);
            }
        });
        println!(
            "{:<40} {:<26} |dE| first tenth {early:.2e}, last tenth {late:.2e}, {}",
            scheme.meta().id,
            scene.meta().id,
            outcome
        );
        (early, late, outcome.completed())
    }

    fn bounded<M: Scheme, P: Scene<D>, const D: usize>(scheme: &M, scene: &P) {
        let (early, late, done) = long_run(scheme, scene, 10_000);
        assert!(done && late < 2.0 * early + 1e-12, "{}", scheme.meta().id);
    }

    fn drifts<M: Scheme, P: Scene<D>, const D: usize>(scheme: &M, scene: &P) {
        let (early, late, done) = long_run(scheme, scene, 10_000);
        let e0 = scene.energy(&scene.initial()).abs();
        assert!(
            !done || late > 0.1 * e0,
            "{}: {early:e} {late:e}",
            scheme.meta().id
        );
    }

    #[test]
    fn long_runs_drift_or_not_as_theory_says() {
        // symplectic or symmetric, correct: bounded
        bounded(&CANDY_ROZMUS4, &Kepler3d);
        bounded(&CANDY_ROZMUS4, &Planets4);
        bounded(&LOBATTO_IIIA_IIIB, &DoubleWell);
        bounded(&LOBATTO_IIIA_IIIB, &Toda3);
        bounded(&SRKN6B, &LjTrimer);
        bounded(&SRKN6B, &DoubleWell);
        // symmetric but not symplectic, or with a false claim of symmetry:
        // bounded on these reversible integrable scenes
        bounded(&LOBATTO_IIIA_BOTH, &DoubleWell);
        bounded(&LOBATTO_IIIA_BOTH, &Toda3);
        bounded(&BEEMAN_CLAIMS_SYMMETRIC, &DoubleWell);
        // the stale forces: exponential growth
        drifts(&CANDY_ROZMUS4_LAGGED, &Toda3);
        drifts(&CANDY_ROZMUS4_LAGGED, &LjTrimer);
        drifts(&LOBATTO_STALE_CLOSING_FORCE, &Toda3);
        drifts(&LOBATTO_STALE_CLOSING_FORCE, &DoubleWell);
        // claiming nothing: shown, not judged
        long_run(&BEEMAN, &LjTrimer, 10_000);
        long_run(&ABM4, &Kepler3d, 10_000);
        long_run(&ABM4, &CoupledOscillators, 10_000);
        // flipped but still symplectic and symmetric: bounded
        bounded(&SRKN6B_SIGN_FLIPPED, &Kepler3d);
        bounded(&SRKN6B_SIGN_FLIPPED, &Planets4);
    }

    #[test]
    fn the_planets_keep_apart_for_ten_thousand_inner_periods() {
        let scene = Planets4;
        let h = scene.period() / 100.0;
        let mut closest = [f64::INFINITY; 3];
        let outcome = integrate(
            &CANDY_ROZMUS4,
            &scene,
            &scene.initial(),
            h,
            1_000_000,
            |_, _, s| {
                for (k, (i, j)) in [(1, 2), (2, 3), (1, 0)].into_iter().enumerate() {
                    closest[k] = closest[k].min(Planets4::separation(s, i, j));
                }
            },
        );
        println!("closest approaches (1-2, 2-3, 1-star): {closest:?}");
        assert!(outcome.completed());
        assert!(closest[0] > 0.8 && closest[1] > 1.6 && closest[2] > 0.9);
    }

    // ---------------------------------------------------------------- entries

    #[test]
    fn entries_are_many_enough_and_ids_unique() {
        let e = entries();
        let correct = e
            .iter()
            .filter(|x| x.truth == crate::corpus::Truth::Correct)
            .count();
        let broken = e.len() - correct;
        println!("{correct} correct, {broken} broken");
        assert!(correct >= 15 && broken >= 15);
    }
}
