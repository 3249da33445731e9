//! Scenes of the corpus: problems the harness was not built around. All but
//! the Morse oscillator have no exact solution, so the order study measures
//! them against the scheme itself at half the step.

use nalgebra::{SVector, Vector1, Vector2, Vector4, Vector6};
use std::f64::consts::{PI, TAU};
use stepladder::scene::{Invariant, InvariantValue, Scene, SceneMeta};
use stepladder::state::{Real, State};

/// The figure-eight choreography of three equal masses (`G = m = 1`) in the
/// plane, positions `(x1, y1, x2, y2, x3, y3)`: six dimensions, no exact
/// solution, linearly stable (it lies on a KAM torus), so errors grow only
/// polynomially. Initial conditions of C. Moore, Phys. Rev. Lett. 70, 3675
/// (1993) and A. Chenciner, R. Montgomery, Ann. Math. 152, 881 (2000), as
/// given by C. Simó: body 3 at the origin, bodies 1 and 2 opposite, `v1 =
/// v2 = -v3 / 2`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FigureEight;

impl FigureEight {
    /// The period of the choreography (Simó).
    pub const PERIOD: f64 = 6.32591398;
}

/// The vector from body `i` to body `j` in a six-vector of planar positions.
#[inline(always)]
fn separation<R: Real>(q: &SVector<R, 6>, i: usize, j: usize) -> (R, R) {
    (q[2 * j] - q[2 * i], q[2 * j + 1] - q[2 * i + 1])
}

impl Scene<6> for FigureEight {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "figure-eight",
            name: "three-body figure-eight choreography",
            dimension: 6,
            parameters: "G = m = 1, Simó's initial conditions".into(),
            reference: "C. Moore, PRL 70, 3675 (1993); A. Chenciner, R. Montgomery, Ann. Math. 152, 881 (2000)",
        }
    }

    fn initial(&self) -> State<6> {
        let (x, y) = (0.97000436, -0.24308753);
        let (vx, vy) = (-0.93240737, -0.86473146);
        State::new(
            Vector6::new(x, y, -x, -y, 0.0, 0.0),
            Vector6::new(-vx / 2.0, -vy / 2.0, -vx / 2.0, -vy / 2.0, vx, vy),
        )
    }

    fn acceleration<R: Real>(&self, q: &SVector<R, 6>) -> SVector<R, 6> {
        let mut a = SVector::<R, 6>::zeros();
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            let (dx, dy) = separation(q, i, j);
            let r2 = dx * dx + dy * dy;
            let inv3 = R::one() / (r2 * r2.sqrt());
            // body i is pulled towards j, j towards i
            a[2 * i] += dx * inv3;
            a[2 * i + 1] += dy * inv3;
            a[2 * j] -= dx * inv3;
            a[2 * j + 1] -= dy * inv3;
        }
        a
    }

    fn potential<R: Real>(&self, q: &SVector<R, 6>) -> R {
        [(0, 1), (0, 2), (1, 2)]
            .iter()
            .map(|&(i, j)| {
                let (dx, dy) = separation(q, i, j);
                -R::one() / (dx * dx + dy * dy).sqrt()
            })
            .fold(R::zero(), |s, v| s + v)
    }

    fn period(&self) -> f64 {
        Self::PERIOD
    }

    fn exact(&self, _: f64) -> Option<State<6>> {
        None
    }

    /// An isolated system of three equal masses: energy, both components
    /// of the linear momentum and the angular momentum.
    fn invariants(&self) -> &'static [Invariant] {
        &[
            Invariant::Energy,
            Invariant::Momentum { axis: 0 },
            Invariant::Momentum { axis: 1 },
            Invariant::AngularMomentum { axis: 2 },
        ]
    }

    fn invariant(&self, which: Invariant, s: &State<6>) -> Option<InvariantValue> {
        let w = self.frequency();
        match which {
            Invariant::Energy => Some(InvariantValue::energy(self, s)),
            Invariant::Momentum { axis } if axis < 2 => {
                Some(InvariantValue::momentum(s, &[1.0; 3], 2, axis as usize, w))
            }
            Invariant::AngularMomentum { axis: 2 } => {
                Some(InvariantValue::planar_angular_momentum(s, w))
            }
            _ => None,
        }
    }
}

/// The complete elliptic integral of the first kind, `K(m) = pi / (2
/// AGM(1, sqrt(1 - m)))`, by the arithmetic-geometric mean.
fn elliptic_k(m: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// The plane pendulum `x'' = -sin x`, `V = 1 - cos x`, released at rest
/// from the amplitude `x0`; by default 3 rad, close to the separatrix at
/// `pi`, where the motion lingers near the top and the period is `4 K(m)`,
/// `m = sin^2(x0 / 2)`, 2.8 times the small-oscillation period. No exact
/// solution is given (the harness measures it against itself).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pendulum {
    x0: f64,
}

impl Default for Pendulum {
    fn default() -> Self {
        Self { x0: 3.0 }
    }
}

impl Pendulum {
    /// The pendulum released at rest from `x0`, `0 < |x0| < pi`.
    pub fn new(x0: f64) -> Result<Self, stepladder::error::Error> {
        if x0.is_finite() && x0 != 0.0 && x0.abs() < PI {
            Ok(Self { x0 })
        } else {
            Err(stepladder::error::Error::InvalidParameter {
                name: "x0",
                value: x0,
                expected: "an amplitude with 0 < |x0| < pi",
            })
        }
    }
}

impl Scene<1> for Pendulum {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "pendulum",
            name: "plane pendulum at large amplitude",
            dimension: 1,
            parameters: format!("x0 = {} rad, v0 = 0", self.x0),
            reference: "x'' = -sin x; period 4 K(sin^2(x0/2)) (Landau & Lifshitz, Mechanics, 11)",
        }
    }
    fn initial(&self) -> State<1> {
        State::new(Vector1::new(self.x0), Vector1::new(0.0))
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, 1>) -> SVector<R, 1> {
        Vector1::new(-q[0].sin())
    }
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        R::one() - q[0].cos()
    }
    fn period(&self) -> f64 {
        4.0 * elliptic_k((0.5 * self.x0).sin().powi(2))
    }
    fn exact(&self, _: f64) -> Option<State<1>> {
        None
    }
}

/// The Hénon-Heiles potential `V = (x^2 + y^2)/2 + x^2 y - y^3/3` (M. Hénon,
/// C. Heiles, Astron. J. 69, 73 (1964)) on a regular orbit of energy 1/12:
/// `(x, y) = (0, 0.1)`, `v_y = 0`, `v_x` from the energy. Non-integrable, but
/// this orbit lies on an invariant torus (a test checks that neighbouring
/// orbits separate linearly, not exponentially). Both small-oscillation
/// frequencies are 1, so the time scale is `2 pi`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HenonHeiles;

impl HenonHeiles {
    /// The orbit's energy.
    pub const ENERGY: f64 = 1.0 / 12.0;
    const Y0: f64 = 0.1;
}

impl Scene<2> for HenonHeiles {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "henon-heiles",
            name: "Hénon-Heiles, regular orbit",
            dimension: 2,
            parameters: "E = 1/12, x0 = 0, y0 = 0.1, vy0 = 0".into(),
            reference: "M. Hénon, C. Heiles, Astron. J. 69, 73 (1964)",
        }
    }
    fn initial(&self) -> State<2> {
        let y = Self::Y0;
        let v = y * y / 2.0 - y * y * y / 3.0;
        State::new(
            Vector2::new(0.0, y),
            Vector2::new((2.0 * (Self::ENERGY - v)).sqrt(), 0.0),
        )
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, 2>) -> SVector<R, 2> {
        let (x, y) = (q[0], q[1]);
        Vector2::new(-x - R::of(2.0) * x * y, -y - x * x + y * y)
    }
    fn potential<R: Real>(&self, q: &SVector<R, 2>) -> R {
        let (x, y) = (q[0], q[1]);
        R::of(0.5) * (x * x + y * y) + x * x * y - y * y * y / R::of(3.0)
    }
    fn period(&self) -> f64 {
        TAU
    }
    fn exact(&self, _: f64) -> Option<State<2>> {
        None
    }
}

/// A Fermi-Pasta-Ulam-Tsingou beta chain of four unit masses between fixed
/// walls, `V = sum_(i=0..4) (d_i^2/2 + beta d_i^4/4)` with `d_i = q_(i+1) -
/// q_i`, `q_0 = q_5 = 0`, `beta = 1`, started at rest in the shape of the
/// lowest linear mode with amplitude 0.5 (E. Fermi, J. Pasta, S. Ulam, Los
/// Alamos report LA-1940 (1955)). Its time scale is the lowest mode's
/// period, `2 pi / (2 sin(pi/10))`; the quartic coupling shares the energy
/// with the other modes slowly.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FputChain;

impl FputChain {
    const BETA: f64 = 1.0;
    const AMPLITUDE: f64 = 0.5;
}

impl Scene<4> for FputChain {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "fput-chain",
            name: "FPUT beta chain of four masses",
            dimension: 4,
            parameters: "beta = 1, lowest mode, amplitude 0.5".into(),
            reference: "E. Fermi, J. Pasta, S. Ulam, LA-1940 (1955)",
        }
    }
    fn initial(&self) -> State<4> {
        let q = Vector4::from_fn(|i, _| Self::AMPLITUDE * (PI * (i + 1) as f64 / 5.0).sin());
        State::new(q, Vector4::zeros())
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, 4>) -> SVector<R, 4> {
        let beta = R::of(Self::BETA);
        let at = |i: i32| -> R {
            if (0..4).contains(&i) {
                q[i as usize]
            } else {
                R::zero()
            }
        };
        // the spring force f(d) = d + beta d^3 of the bond d = q_(i+1) - q_i
        let f = |d: R| d + beta * d * d * d;
        Vector4::from_fn(|k, _| {
            let k = k as i32;
            f(at(k + 1) - at(k)) - f(at(k) - at(k - 1))
        })
    }
    fn potential<R: Real>(&self, q: &SVector<R, 4>) -> R {
        let beta = R::of(Self::BETA);
        let at = |i: i32| -> R {
            if (0..4).contains(&i) {
                q[i as usize]
            } else {
                R::zero()
            }
        };
        (-1..4)
            .map(|i| {
                let d = at(i + 1) - at(i);
                R::of(0.5) * d * d + beta * R::of(0.25) * d * d * d * d
            })
            .fold(R::zero(), |s, v| s + v)
    }
    fn period(&self) -> f64 {
        TAU / (2.0 * (PI / 10.0).sin())
    }
    fn exact(&self, _: f64) -> Option<State<4>> {
        None
    }
}

/// The Morse oscillator `V = D (1 - e^(-a x))^2` (P. M. Morse, Phys. Rev. 34,
/// 57 (1929)), a model of a molecular bond, on a bound orbit of energy `E <
/// D` started at the inner turning point, with its exact solution:
/// `e^(a x) = (1 - eps cos(w t)) / (1 - eps^2)`, `eps = sqrt(E / D)`, `w = a
/// sqrt(2 (D - E))`, so `v = eps w sin(w t) / (a (1 - eps cos(w t)))`.
/// Default `D = a = 1`, `E = D/2`: strongly anharmonic, the orbit spans
/// `x` from `-ln(1 + eps)` to `-ln(1 - eps)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Morse {
    depth: f64,
    width: f64,
    energy: f64,
}

impl Default for Morse {
    fn default() -> Self {
        Self {
            depth: 1.0,
            width: 1.0,
            energy: 0.5,
        }
    }
}

impl Morse {
    /// The oscillator of well depth `D`, width parameter `a` and energy `E`
    /// (all finite and positive, `E < D`).
    pub fn new(depth: f64, width: f64, energy: f64) -> Result<Self, stepladder::error::Error> {
        let depth = stepladder::scene::positive("depth", depth)?;
        let width = stepladder::scene::positive("width", width)?;
        let energy = stepladder::scene::positive("energy", energy)?;
        if energy >= depth {
            return Err(stepladder::error::Error::InvalidScene(format!(
                "a Morse orbit of energy {energy} >= depth {depth} is not bound"
            )));
        }
        Ok(Self {
            depth,
            width,
            energy,
        })
    }

    fn eps(&self) -> f64 {
        (self.energy / self.depth).sqrt()
    }

    fn w(&self) -> f64 {
        self.width * (2.0 * (self.depth - self.energy)).sqrt()
    }
}

impl Scene<1> for Morse {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "morse",
            name: "Morse oscillator",
            dimension: 1,
            parameters: format!(
                "D = {}, a = {}, E = {}",
                self.depth, self.width, self.energy
            ),
            reference: "P. M. Morse, Phys. Rev. 34, 57 (1929); e^(a x) = (1 - eps cos w t)/(1 - eps^2)",
        }
    }
    fn initial(&self) -> State<1> {
        self.exact(0.0).expect("closed form")
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, 1>) -> SVector<R, 1> {
        let e = (-R::of(self.width) * q[0]).exp();
        Vector1::new(-R::of(2.0 * self.depth * self.width) * (R::one() - e) * e)
    }
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        let d = R::one() - (-R::of(self.width) * q[0]).exp();
        R::of(self.depth) * d * d
    }
    fn period(&self) -> f64 {
        TAU / self.w()
    }
    fn exact(&self, t: f64) -> Option<State<1>> {
        let (eps, w, a) = (self.eps(), self.w(), self.width);
        let (s, c) = (w * t).sin_cos();
        let denominator = 1.0 - eps * c;
        Some(State::new(
            Vector1::new(((denominator) / (1.0 - eps * eps)).ln() / a),
            Vector1::new(eps * w * s / (a * denominator)),
        ))
    }
}
