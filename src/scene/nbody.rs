//! The Newtonian N-body problem in mass-weighted coordinates: the force law
//! and the change of coordinates the N-body scenes share.
//!
//! # Why mass-weighted coordinates
//!
//! A scene is `q'' = a(q) = -grad V(q)` with kinetic energy `|q'|^2 / 2`.
//! Bodies of unequal masses in their physical positions `r_i` obey `m_i r_i''
//! = -grad_(r_i) U(r)` with `U = -sum_(i<j) G m_i m_j / |r_i - r_j|`: the
//! acceleration is the gradient of `U` divided by each body's own mass, which
//! is not the gradient of any one function of `r` (its Jacobian is not
//! symmetric), so a scene written in `r` fails the check that its force is
//! `-grad V`. With `Q_i = sqrt(m_i) r_i` the kinetic energy `sum m_i |r_i'|^2
//! / 2` becomes `|Q'|^2 / 2` and `Q_i'' = sqrt(m_i) r_i'' = -grad_(Q_i) U`,
//! since `grad_(Q_i) = grad_(r_i) / sqrt(m_i)`: the equations are a scene's
//! with `V = U` expressed in `Q`. The scene's energy is then the system's
//! total energy, its `sum sqrt(m_i) Q_i'` the total momentum and `sum Q_i x
//! Q_i'` the total angular momentum.
//!
//! States are stored body after body, `K` coordinates each (`x1, y1, x2, y2,
//! ...` in the plane).

use crate::maths::dd::Dd;
use crate::state::{Real, State};
use nalgebra::SVector;

/// `N` point masses in `K` dimensions under their mutual gravity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bodies<const N: usize, const K: usize> {
    g: f64,
    masses: [f64; N],
    sqrt_masses: [f64; N],
}

impl<const N: usize, const K: usize> Bodies<N, K> {
    /// Bodies of these masses with gravitational constant `g`.
    pub(crate) fn new(g: f64, masses: [f64; N]) -> Self {
        Self {
            g,
            masses,
            sqrt_masses: masses.map(f64::sqrt),
        }
    }

    /// `sqrt(m_i)`, the factor from physical to mass-weighted coordinates.
    pub(crate) fn sqrt_masses(&self) -> &[f64; N] {
        &self.sqrt_masses
    }

    /// `Q_i'' = sqrt(m_i) sum_(j != i) G m_j (r_j - r_i) / |r_j - r_i|^3`
    /// with `r_i = Q_i / sqrt(m_i)`, one pass over the pairs: each pair's
    /// `G / r^3` is computed once and pulls both bodies.
    #[inline(always)]
    pub(crate) fn acceleration<R: Real, const D: usize>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        const {
            assert!(
                D == N * K,
                "a state of N bodies in K dimensions has N K coordinates"
            )
        };
        let r = self.positions(q);
        let mut a = [[R::zero(); K]; N];
        for i in 0..N {
            for j in i + 1..N {
                let mut d = [R::zero(); K];
                let mut r2 = R::zero();
                for k in 0..K {
                    d[k] = r[j][k] - r[i][k];
                    r2 += d[k] * d[k];
                }
                let inv3 = R::of(self.g) / (r2 * r2.sqrt());
                let (pull_i, pull_j) = (R::of(self.masses[j]) * inv3, R::of(self.masses[i]) * inv3);
                for k in 0..K {
                    a[i][k] += d[k] * pull_i;
                    a[j][k] -= d[k] * pull_j;
                }
            }
        }
        SVector::from_fn(|n, _| a[n / K][n % K] * R::of(self.sqrt_masses[n / K]))
    }

    /// `V(Q) = -sum_(i<j) G m_i m_j / |r_i - r_j|`, `r_i = Q_i / sqrt(m_i)`.
    #[inline(always)]
    pub(crate) fn potential<R: Real, const D: usize>(&self, q: &SVector<R, D>) -> R {
        const {
            assert!(
                D == N * K,
                "a state of N bodies in K dimensions has N K coordinates"
            )
        };
        let r = self.positions(q);
        let mut v = R::zero();
        for i in 0..N {
            for j in i + 1..N {
                let mut r2 = R::zero();
                for (&xj, &xi) in r[j].iter().zip(&r[i]) {
                    r2 += (xj - xi) * (xj - xi);
                }
                v -= R::of(self.g * self.masses[i] * self.masses[j]) / r2.sqrt();
            }
        }
        v
    }

    /// The energy of the state `s + low` (a compensated sum's value and low
    /// parts) in double-double, in the form the force law above conserves.
    /// That law gives `Q_i'' = s_i G m_j d / r^3` with `s_i` the double
    /// nearest `sqrt(m_i)`, which is `s_i^2 / m_i` times `-grad_(Q_i) V`:
    /// the conserved kinetic energy is `sum m_i |Q_i' / s_i|^2 / 2`, the
    /// physical one. Written with `|Q_i'|^2 / 2` instead, the energy would
    /// swing by `(s_i^2 / m_i - 1)` of each body's kinetic energy, up to a
    /// unit in the last place, which is what a compensated run's walk is
    /// measured against.
    pub(crate) fn energy_dd<const D: usize>(&self, s: &State<D>, low: &State<D>) -> Dd {
        const {
            assert!(
                D == N * K,
                "a state of N bodies in K dimensions has N K coordinates"
            )
        };
        let exact = |x: f64, l: f64| Dd::of(x).add(Dd::of(l));
        let mut r = [[Dd::default(); K]; N];
        let mut energy = Dd::default();
        for (i, ri) in r.iter_mut().enumerate() {
            let w = Dd::of(self.sqrt_masses[i]);
            for (k, x) in ri.iter_mut().enumerate() {
                let n = K * i + k;
                *x = exact(s.q[n], low.q[n]).div(w);
                let u = exact(s.v[n], low.v[n]).div(w);
                energy = energy.add(Dd::of(0.5 * self.masses[i]).mul(u.mul(u)));
            }
        }
        for i in 0..N {
            for j in i + 1..N {
                let mut r2 = Dd::default();
                for (&xj, &xi) in r[j].iter().zip(&r[i]) {
                    let d = xj.sub(xi);
                    r2 = r2.add(d.mul(d));
                }
                let gmm = Dd::of(self.g)
                    .mul(Dd::of(self.masses[i]))
                    .mul(Dd::of(self.masses[j]));
                energy = energy.sub(gmm.div(r2.sqrt()));
            }
        }
        energy
    }

    /// The physical positions `r_i = Q_i / sqrt(m_i)`.
    #[inline(always)]
    fn positions<R: Real, const D: usize>(&self, q: &SVector<R, D>) -> [[R; K]; N] {
        let mut r = [[R::zero(); K]; N];
        for (i, ri) in r.iter_mut().enumerate() {
            for (k, x) in ri.iter_mut().enumerate() {
                *x = q[K * i + k] / R::of(self.sqrt_masses[i]);
            }
        }
        r
    }

    /// Physical positions and velocities `(Q_i, Q_i') / sqrt(m_i)`.
    pub(crate) fn physical<const D: usize>(&self, s: &State<D>) -> State<D> {
        const {
            assert!(
                D == N * K,
                "a state of N bodies in K dimensions has N K coordinates"
            )
        };
        let w = |n: usize| self.sqrt_masses[n / K];
        State::new(
            SVector::from_fn(|n, _| s.q[n] / w(n)),
            SVector::from_fn(|n, _| s.v[n] / w(n)),
        )
    }

    /// Mass-weighted coordinates `sqrt(m_i) (r_i, r_i')` of a physical state.
    pub(crate) fn mass_weighted<const D: usize>(&self, physical: &State<D>) -> State<D> {
        const {
            assert!(
                D == N * K,
                "a state of N bodies in K dimensions has N K coordinates"
            )
        };
        let w = |n: usize| self.sqrt_masses[n / K];
        State::new(
            SVector::from_fn(|n, _| physical.q[n] * w(n)),
            SVector::from_fn(|n, _| physical.v[n] * w(n)),
        )
    }

    /// The physical state of bodies given by their positions and velocities.
    pub(crate) fn from_bodies<const D: usize>(
        positions: &[[f64; K]; N],
        velocities: &[[f64; K]; N],
    ) -> State<D> {
        const {
            assert!(
                D == N * K,
                "a state of N bodies in K dimensions has N K coordinates"
            )
        };
        State::new(
            SVector::from_fn(|n, _| positions[n / K][n % K]),
            SVector::from_fn(|n, _| velocities[n / K][n % K]),
        )
    }

    /// The Kepler period `2 pi sqrt(R^3 / (G M))` of an orbit whose radius is
    /// the bodies' mass-weighted root-mean-square distance `R` from their
    /// centre of mass, about their total mass `M`: the time a body at the
    /// system's typical distance takes to go round it.
    pub(crate) fn kepler_period_at_rms_radius(&self, positions: &[[f64; K]; N]) -> f64 {
        let total: f64 = self.masses.iter().sum();
        let mut centre = [0.0; K];
        for (m, r) in self.masses.iter().zip(positions) {
            for k in 0..K {
                centre[k] += m * r[k] / total;
            }
        }
        let spread: f64 = self
            .masses
            .iter()
            .zip(positions)
            .map(|(m, r)| m * (0..K).map(|k| (r[k] - centre[k]).powi(2)).sum::<f64>())
            .sum();
        let radius = (spread / total).sqrt();
        std::f64::consts::TAU * (radius.powi(3) / (self.g * total)).sqrt()
    }
}
