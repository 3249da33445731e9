//! The held-out batch's scenes.

use nalgebra::SVector;
use std::f64::consts::{PI, TAU};
use stepladder::scene::{Invariant, InvariantValue, Scene, SceneMeta};
use stepladder::state::{Real, State};

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
    pub(super) const PAIRS: [(usize, usize); 3] = [(0, 1), (1, 2), (0, 2)];
    /// The equilateral minimum, centred on the origin (circumradius
    /// `1/sqrt(3)`).
    pub const MINIMUM: [f64; 6] = [
        0.0,
        0.577_350_269_189_625_8,
        -0.5,
        -0.288_675_134_594_812_9,
        0.5,
        -0.288_675_134_594_812_9,
    ];
    /// The initial displacement from the minimum (summing to zero).
    pub(super) const DISPLACEMENT: [f64; 6] = [0.04, -0.025, -0.03, 0.035, -0.01, -0.01];
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

    /// Three unit masses, isolated: energy, both momenta and the angular
    /// momentum.
    fn invariants(&self) -> &'static [Invariant] {
        &PLANAR_BODY_INVARIANTS
    }

    fn invariant(&self, which: Invariant, s: &State<6>) -> Option<InvariantValue> {
        planar_bodies(self, which, s, &[1.0; 3])
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
    pub(super) const INCLINATION: f64 = 0.6;
    /// Longitude of the ascending node.
    pub(super) const NODE: f64 = 0.9;
    /// Argument of periapsis.
    pub(super) const PERIAPSIS: f64 = 1.3;
    /// Mean anomaly at `t = 0`.
    pub(super) const M0: f64 = 0.4;

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
    pub(super) fn frame() -> ([f64; 3], [f64; 3]) {
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
pub(super) fn jacobi(u: f64, m: f64) -> (f64, f64, f64, f64) {
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
pub(super) const GOLDEN: f64 = 1.618_033_988_749_895;

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
    pub(super) const KAPPA: f64 = 0.5 * GOLDEN;
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
    pub(super) const RADII: [f64; 3] = [1.0, 2.0, 4.0];
    /// The planets' initial angles.
    pub(super) const ANGLES: [f64; 3] = [0.3, 2.5, 4.4];

    /// The physical positions `r_i = x_i / sqrt(m_i)` of the four bodies.
    #[inline(always)]
    pub(super) fn positions<R: Real>(x: &SVector<R, 8>) -> [[R; 2]; 4] {
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

    /// An isolated system in mass-weighted coordinates: energy, both
    /// momenta and the angular momentum.
    fn invariants(&self) -> &'static [Invariant] {
        &PLANAR_BODY_INVARIANTS
    }

    fn invariant(&self, which: Invariant, s: &State<8>) -> Option<InvariantValue> {
        planar_bodies(self, which, s, &Self::MASSES.map(f64::sqrt))
    }
}

/// What an isolated system of bodies in the plane conserves.
const PLANAR_BODY_INVARIANTS: [Invariant; 4] = [
    Invariant::Energy,
    Invariant::Momentum { axis: 0 },
    Invariant::Momentum { axis: 1 },
    Invariant::AngularMomentum { axis: 2 },
];

/// The invariants of bodies in the plane stored `x1, y1, x2, y2, ...` in
/// mass-weighted coordinates with these `sqrt(m_i)`.
fn planar_bodies<S: Scene<D>, const D: usize>(
    scene: &S,
    which: Invariant,
    s: &State<D>,
    sqrt_masses: &[f64],
) -> Option<InvariantValue> {
    let w = scene.frequency();
    match which {
        Invariant::Energy => Some(InvariantValue::energy(scene, s)),
        Invariant::Momentum { axis } if axis < 2 => Some(InvariantValue::momentum(
            s,
            sqrt_masses,
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
