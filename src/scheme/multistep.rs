//! Symmetric linear multistep methods for `q'' = a(q)` (Quinlan and
//! Tremaine 1990): one force evaluation per step at any order.
//!
//! A `K`-step method advances positions only,
//! `sum_j alpha_j q_(n+j) = h^2 sum_j beta_j a(q_(n+j))`, `j = 0..=K`, with
//! `alpha_K = 1` and `beta_K = beta_0 = 0` (explicit). Both coefficient lists
//! are palindromes, and the roots of `rho(x) = sum alpha_j x^j` lie on the
//! unit circle: a double root at 1 (the motion) and `K - 2` simple spurious
//! ones. Quinlan and Tremaine chose the spurious roots spread round the
//! circle; the `beta_j` then follow uniquely from the order conditions
//! `sum_j alpha_j j^m = m (m - 1) sum_j beta_j j^(m-2)`, `m = 0..=K+1`, so a
//! symmetric `K`-step method has order `K`.
//!
//! Their weakness is resonance. On the oscillator the roots of
//! `rho(x) + z^2 sigma(x)` (`z = h w0`, `sigma(x) = sum beta_j x^j`) move
//! along the circle as `z` grows; where the motion's root meets a spurious
//! one they leave it and the method is unstable, at a far smaller `z` than a
//! one-step method of the same order: the stability study measures it from
//! [`Scheme::recurrence_on_oscillator`]. On an eccentric orbit the force
//! carries every harmonic of the orbital frequency, and a harmonic that meets
//! a spurious root at some step excites it.
//!
//! What the harness sees: the scheme keeps its window of `K` positions and
//! their accelerations, reports the newest, and carries the velocity along
//! by quadrature of the accelerations it has anyway,
//! `v_n = v_(n-1) + h sum_j w_j a_(n+1-K+j)` with the Adams-Moulton weights
//! of the window's `K` nodes (exact for polynomials of degree `K - 1`, so
//! order `K` like the positions, at no force evaluation). A velocity from
//! differences of positions would be simpler but divides the spurious roots'
//! small oscillation by `h`; in accelerations it enters multiplied by `h`.
//! The start-up fills the window from `(q0, v0)` with [`KAHAN_LI8`] steps
//! backwards, substepped so that its error stays below the method's own
//! ([`SymmetricMultistep::startup_substeps`]); its force evaluations are the
//! start's. The recurrence is time-symmetric, but the harness's round trip
//! restarts from a synchronised state, which builds a new window, so as a
//! map of `(q, v)` the scheme is neither symmetric nor symplectic, and it
//! claims neither.
//!
//! Not in the catalogue (yet): on the circular orbit, the oscillator and the
//! anharmonic well its order is measured (8.05, 8.00, 8.07), but on the
//! eccentric orbit the steps between the resonances of the pericentre
//! passage and the round-off floor span only one and a half halvings, too
//! few for the order study to decide, and the separatrix study finds too
//! few runs between round-off and its offset ceiling; the harness promises a
//! verdict on every built-in scene for every catalogue scheme.

use super::composition::KAHAN_LI8;
use super::{PhaseError, Scheme, SchemeMeta, StepFailure};
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;

/// Bound on the start-up method's relative phase error per `z^8`
/// ([`KAHAN_LI8`] on the oscillator: the angle of its one-step matrix gives
/// `1.2306e-6 z^8` as `z -> 0`, `1.259e-6 z^8` at `z = 0.4` and
/// `1.311e-6 z^8` at `z = 0.8`; a test checks it up to there).
pub const STARTUP_PHASE_COEFFICIENT: f64 = 1.4e-6;

/// How far below the method's own error the start-up's is kept. The
/// start-up shifts the phase of the whole run by about
/// `STARTUP_PHASE_COEFFICIENT (z/m)^8` (times the few steps of the window)
/// and perturbs the energy alike, which on a nonlinear orbit becomes a phase
/// drift of the same size per unit `w t`; the method's own phase error is
/// `|c_p| z^p` per unit `w t`. Asking the first to be at most a twentieth of
/// the second over `w t >= 1` keeps the start-up out of the measured order.
pub const STARTUP_MARGIN: f64 = 20.0;

/// A symmetric multistep method with `K` steps, as integer coefficients.
#[derive(Clone, Copy, Debug)]
pub struct SymmetricMultistep<const K: usize> {
    /// The scheme's claims.
    pub meta: SchemeMeta,
    /// `alpha_0..=alpha_K`, integers (a palindrome, `alpha_0 = alpha_K = 1`).
    pub alpha: &'static [i64],
    /// `beta_0..=beta_K` times [`Self::beta_denominator`] (a palindrome,
    /// zero at both ends).
    pub beta: &'static [i64],
    /// The common denominator of the `beta_j`.
    pub beta_denominator: i64,
    /// `rho(x) / (x - 1)^2`, from the constant term up (monic, degree
    /// `K - 2`): the recurrence in second differences (see [`MultistepCarry`]).
    pub reduced_alpha: &'static [i64],
    /// The velocity quadrature's weights `w_0..w_(K-1)` times
    /// [`Self::velocity_denominator`]: the integrals over the last step of
    /// the Lagrange basis on the window's nodes (the `K`-point Adams-Moulton
    /// weights, oldest node first).
    pub velocity_weights: &'static [i64],
    /// The common denominator of the velocity weights.
    pub velocity_denominator: i64,
    /// The leading relative phase error on the oscillator, `c_p z^p`, of the
    /// motion's root: `-C_(p+2)/2` for `p = 0 mod 4`, with `C_(p+2)` the
    /// error constant (derived from the coefficients by a test).
    pub phase: PhaseError,
}

impl<const K: usize> SymmetricMultistep<K> {
    /// A method from its claims and coefficients; the lengths are checked
    /// when the constant is evaluated, so a mismatch does not compile.
    pub const fn new(
        meta: SchemeMeta,
        (alpha, reduced_alpha): (&'static [i64], &'static [i64]),
        (beta, beta_denominator): (&'static [i64], i64),
        (velocity_weights, velocity_denominator): (&'static [i64], i64),
        phase: PhaseError,
    ) -> Self {
        assert!(alpha.len() == K + 1 && beta.len() == K + 1 && velocity_weights.len() == K);
        assert!(alpha[K] == 1 && beta[0] == 0 && beta[K] == 0);
        assert!(reduced_alpha.len() == K - 1 && reduced_alpha[K - 2] == 1);
        Self {
            meta,
            alpha,
            reduced_alpha,
            beta,
            beta_denominator,
            velocity_weights,
            velocity_denominator,
            phase,
        }
    }

    /// Substeps `m` of the start-up per step at `z = |h| w`: the smallest
    /// with `STARTUP_PHASE_COEFFICIENT (z/m)^8 <= |c_p| z^p / STARTUP_MARGIN`,
    /// so `m = 1` for an eighth-order method (its start-up has the same order
    /// and a constant 5000 times smaller) and `m ~ z^(-1/2)` for order 12.
    pub fn startup_substeps<R: Real>(&self, z: R) -> u32 {
        let need = R::of(STARTUP_MARGIN * STARTUP_PHASE_COEFFICIENT / self.phase.coefficient.abs());
        let excess = z.powi(self.phase.power as i32 - 8);
        let mut m = 1u32;
        // m^8 z^(p-8) >= need; compared in R so dual numbers take the same path
        while R::of((m as f64).powi(8)) * excess < need && m < 1 << 16 {
            m += 1;
        }
        m
    }

    fn ratio<R: Real>(numerator: i64, denominator: i64) -> R {
        R::of(numerator as f64 / denominator as f64)
    }
}

/// The window of a [`SymmetricMultistep`], in the differences the
/// recurrence is run in.
///
/// Since `rho(x) = (x - 1)^2 rho~(x)`, the recurrence reads
/// `sum_i rho~_i s_(n+i) = h^2 sum_j beta_j a_(n+j)` in the second
/// differences `s_m = q_(m+2) - 2 q_(m+1) + q_m`, which are `O(h^2)`: the new
/// one is computed to round-off of its own size, then summed into the last
/// difference and the position. Run on positions directly, every step would
/// add a round-off of `eps |q|` (times the sum of `|alpha_j|`) that the double
/// root at 1 turns into a velocity error, a random walk growing like
/// `N^(3/2)`; in differences that walk starts from `eps h |v|` instead.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultistepCarry<R: Real, const D: usize, const K: usize> {
    /// The newest position `q_m`.
    pub q: SVector<R, D>,
    /// `q_m - q_(m-1)`.
    pub d: SVector<R, D>,
    /// Second differences, newest `s_(m-2)` last; the recurrence reads the
    /// last `K - 2`.
    pub s: [SVector<R, D>; K],
    /// Accelerations at `q_(m+1-K) ..= q_m`, newest last.
    pub a: [SVector<R, D>; K],
    /// `v_m`, by quadrature of the accelerations.
    pub v: SVector<R, D>,
}

impl<const K: usize> Scheme for SymmetricMultistep<K> {
    type Carry<R: Real, const D: usize> = MultistepCarry<R, D, K>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        state: &State<D, R>,
        h: R,
    ) -> MultistepCarry<R, D, K> {
        let m = self.startup_substeps(h.abs() * R::of(scene.frequency()));
        let sub = h / R::of(m as f64);
        // positions backwards from the start to the window's oldest entry;
        // an explicit splitting step cannot fail (a blow-up shows in the run)
        let mut q = [state.q; K];
        let mut a = [SVector::zeros(); K];
        let mut behind = KAHAN_LI8.start(scene, state, sub);
        a[K - 1] = behind.a;
        for i in (0..K - 1).rev() {
            for _ in 0..m {
                let _ = KAHAN_LI8.step(scene, &mut behind, -sub);
            }
            q[i] = behind.q;
            a[i] = behind.a;
        }
        let mut s = [SVector::zeros(); K];
        for i in 2..K {
            s[i] = (q[i] - q[i - 1]) - (q[i - 1] - q[i - 2]);
        }
        MultistepCarry {
            q: q[K - 1],
            d: q[K - 1] - q[K - 2],
            s,
            a,
            v: state.v,
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut MultistepCarry<R, D, K>,
        h: R,
    ) -> Result<(), StepFailure> {
        // s_new = h^2 sum_j beta_j a_j - sum_(i < K-2) rho~_i s_i
        let (mut kick, mut older) = (SVector::<R, D>::zeros(), SVector::<R, D>::zeros());
        for j in 1..K {
            kick += c.a[j] * Self::ratio::<R>(self.beta[j], self.beta_denominator);
        }
        for i in 0..K - 2 {
            older += c.s[i + 2] * R::of(self.reduced_alpha[i] as f64);
        }
        let newest = kick * (h * h) - older;
        c.d += newest;
        c.q += c.d;
        c.s.rotate_left(1);
        c.s[K - 1] = newest;
        c.a.rotate_left(1);
        c.a[K - 1] = scene.acceleration(&c.q);
        let mut dv = SVector::<R, D>::zeros();
        for j in 0..K {
            dv += c.a[j] * Self::ratio::<R>(self.velocity_weights[j], self.velocity_denominator);
        }
        c.v += dv * h;
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &MultistepCarry<R, D, K>, _: R) -> State<D, R> {
        State::new(c.q, c.v)
    }

    fn recurrence_on_oscillator(&self, z: f64) -> Option<Vec<f64>> {
        Some(
            (0..=K)
                .map(|j| {
                    self.alpha[j] as f64
                        + z * z * Self::ratio::<f64>(self.beta[j], self.beta_denominator)
                })
                .collect(),
        )
    }
}

/// Quinlan and Tremaine's eighth-order method: spurious roots of `rho` at
/// the sixth, fourth and third roots of unity (`alpha` = 1, -2, 2, -1, 0,
/// -1, 2, -2, 1); stable on the oscillator up to `z = 0.7185`.
pub const QUINLAN_TREMAINE8: SymmetricMultistep<8> = SymmetricMultistep::new(
    SchemeMeta {
        id: "quinlan-tremaine8",
        name: "Quinlan-Tremaine symmetric 8-step (SY8)",
        order: 8,
        symplectic: false,
        symmetric: false, // the recurrence is; the restarted round trip is not
        reference: "G. D. Quinlan, S. Tremaine, Astron. J. 100, 1694 (1990), Table 1",
        force_evaluations: 1,
        implicit: false,
        phase_error: None, // the next term is 2 z^2 of it: see `phase`
    },
    (&[1, -2, 2, -1, 0, -1, 2, -2, 1], &[1, 0, 1, 1, 1, 0, 1]),
    (
        &[0, 17671, -23622, 61449, -50516, 61449, -23622, 17671, 0],
        12096,
    ),
    (
        &[1375, -11351, 41499, -88547, 123133, -121797, 139849, 36799],
        120960,
    ),
    PhaseError {
        coefficient: -0.006_306_079_144_620_811,
        power: 8,
    },
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::integrate;
    use crate::scene::Harmonic;
    use crate::study::accuracy::phase::{polynomial_roots, rotation_at};
    use crate::study::stability::{is_stable, stability};

    const SY8: SymmetricMultistep<8> = QUINLAN_TREMAINE8;

    fn power(x: i128, m: u32) -> i128 {
        x.pow(m)
    }

    /// `den sum_j alpha_j j^m - m (m-1) sum_j beta_j j^(m-2)`, exactly.
    fn order_residual<const K: usize>(s: &SymmetricMultistep<K>, m: u32) -> i128 {
        let den = s.beta_denominator as i128;
        let lhs: i128 = (0..=K)
            .map(|j| den * s.alpha[j] as i128 * power(j as i128, m))
            .sum();
        let rhs: i128 = if m < 2 {
            0
        } else {
            (0..=K)
                .map(|j| (m * (m - 1)) as i128 * s.beta[j] as i128 * power(j as i128, m - 2))
                .sum()
        };
        lhs - rhs
    }

    #[test]
    fn coefficients_satisfy_the_order_conditions_exactly_to_order_eight_and_no_further() {
        for m in 0..=9 {
            assert_eq!(order_residual(&SY8, m), 0, "condition m = {m}");
        }
        assert_ne!(order_residual(&SY8, 10), 0, "order would exceed 8");
        // symmetric palindromes; consistency rho''(1) = 2 sigma(1) is m = 2
        let (a, b) = (SY8.alpha, SY8.beta);
        assert!((0..=8).all(|j| a[j] == a[8 - j] && b[j] == b[8 - j]));
    }

    #[test]
    fn reduced_alpha_times_the_double_root_is_alpha() {
        // (x - 1)^2 = x^2 - 2x + 1
        let r = SY8.reduced_alpha;
        let product: Vec<i64> = (0..=8)
            .map(|j| {
                let at = |i: i64| usize::try_from(i).ok().and_then(|i| r.get(i)).copied();
                let j = j as i64;
                at(j).unwrap_or(0) - 2 * at(j - 1).unwrap_or(0) + at(j - 2).unwrap_or(0)
            })
            .collect();
        assert_eq!(product, SY8.alpha);
    }

    #[test]
    fn velocity_weights_integrate_polynomials_of_degree_seven_over_the_last_step() {
        // nodes at -(K-1)..=0, interval [-1, 0]: sum w_j x_j^m = (-1)^m / (m+1)
        let den = SY8.velocity_denominator as i128;
        for m in 0..8u32 {
            let sum: i128 = (0..8)
                .map(|j| SY8.velocity_weights[j] as i128 * power(j as i128 - 7, m))
                .sum();
            let expected = if m % 2 == 0 { den } else { -den };
            assert_eq!((m as i128 + 1) * sum, expected, "degree {m}");
        }
        let m = 8u32;
        let sum: i128 = (0..8)
            .map(|j| SY8.velocity_weights[j] as i128 * power(j as i128 - 7, m))
            .sum();
        assert_ne!((m as i128 + 1) * sum, den, "exact beyond degree 7");
    }

    #[test]
    fn phase_coefficient_is_half_the_error_constant_and_matches_the_principal_root() {
        // C_(p+2) = (sum alpha_j j^10 / 10! - sum beta_j j^8 / 8!) / sum beta_j
        let den = SY8.beta_denominator as f64;
        let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
        let sigma_1 = SY8.beta.iter().sum::<i64>() as f64 / den;
        let c: f64 = (0..=8)
            .map(|j| {
                SY8.alpha[j] as f64 * (j as f64).powi(10) / fact(10)
                    - SY8.beta[j] as f64 / den * (j as f64).powi(8) / fact(8)
            })
            .sum::<f64>()
            / sigma_1;
        // theta - z = C (i z)^10 / (2 z) on the circle: -C z^9 / 2
        assert!((SY8.phase.coefficient + c / 2.0).abs() < 1e-12, "{c}");
        // the root, at two steps, extrapolated in z^2 (the next term)
        let at = |z: f64| (rotation_at(&SY8, z).unwrap() / z - 1.0) / z.powi(8);
        let (c1, c2) = (at(0.2), at(0.1));
        let extrapolated = (4.0 * c2 - c1) / 3.0;
        assert!(
            (extrapolated / SY8.phase.coefficient - 1.0).abs() < 1e-3,
            "{c1} {c2} {extrapolated}"
        );
    }

    #[test]
    fn the_start_up_phase_bound_holds_for_its_method() {
        // up to beyond the multistep method's own stability limit, 0.718
        for z in [0.1, 0.2, 0.4, 0.6, 0.8] {
            let c = (rotation_at(&KAHAN_LI8, z).unwrap() / z - 1.0) / z.powi(8);
            assert!(c.abs() <= STARTUP_PHASE_COEFFICIENT, "z = {z}: {c:e}");
        }
        assert_eq!(SY8.startup_substeps(0.5), 1);
        assert_eq!(SY8.startup_substeps(0.001), 1);
    }

    #[test]
    fn global_error_on_the_oscillator_is_the_predicted_phase_drift() {
        // x = cos t; a phase lag c z^8 per unit time gives |error| ~ |c| z^8 t
        let osc = Harmonic::default();
        let (z, t_end) = (0.1, 200.0);
        let steps = (t_end / z) as u64;
        let mut last = osc.initial();
        integrate(&SY8, &osc, &osc.initial(), z, steps, |_, _, s| last = *s);
        let t = steps as f64 * z;
        let exact = osc.exact(t).unwrap();
        let error = osc.phase_distance(&last, &exact);
        let predicted = SY8.phase.coefficient.abs() * z.powi(8) * t;
        assert!(
            (error / predicted - 1.0).abs() < 0.05,
            "{error:e} vs {predicted:e}"
        );
    }

    #[test]
    fn resonance_ends_stability_where_the_motion_meets_a_spurious_root() {
        let record = stability(&SY8);
        let limit = record.stability_limit.expect("a limit");
        assert!((0.70..0.74).contains(&limit), "{limit}");
        assert!(is_stable(&SY8, limit - 1e-3) && !is_stable(&SY8, limit + 1e-3));
        // at the edge two roots meet on the circle: their distance shrinks to 0
        let gap = |z: f64| {
            let r = polynomial_roots(&SY8.recurrence_on_oscillator(z).unwrap());
            let mut d = f64::INFINITY;
            for i in 0..r.len() {
                for j in i + 1..r.len() {
                    d = d.min((r[i] - r[j]).norm());
                }
            }
            d
        };
        assert!(
            gap(limit - 1e-6) < 1e-2 && gap(0.3) > 0.1,
            "{} {}",
            gap(limit),
            gap(0.3)
        );
    }
}
