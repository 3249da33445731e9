//! Derivatives: the tangent map of one step, the gradient of a potential,
//! the Jacobian of a force.
//!
//! Each derivative runs the generic scheme or scene once per input direction
//! in dual numbers `x + eps dx` ([`num_dual::Dual64`]), so it is exact to
//! round-off; finite differences could not tell a 1e-15 defect from 1e-11.
//! A scheme that only runs on plain floats (a
//! [`crate::scheme::BlackBox`]) gets its tangent map by Richardson-extrapolated
//! central differences instead, with the error of every entry bounded
//! ([`finite_difference_jacobian`]).

use crate::scene::Scene;
use crate::scheme::{Scheme, StepFailure};
use crate::state::State;
use nalgebra::{DMatrix, DVector, SVector};
use num_dual::Dual64;

/// The Jacobian of the synchronised one-step map `(q, v) -> (q', v')` at
/// `state`, in the scaled coordinates `(q, v / w)` with `w` the scene's
/// frequency, so that its entries are dimensionless and comparable.
///
/// The map is the scheme's `start`, one `step` and `state`: for a two-step or
/// staggered scheme it includes the start-up and the synchronisation, which
/// is the map a user's `(q, v)` actually undergoes.
pub fn step_jacobian<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    state: &State<D>,
    h: f64,
) -> Result<DMatrix<f64>, StepFailure> {
    let w = scene.frequency();
    let mut jacobian = DMatrix::zeros(2 * D, 2 * D);
    for col in 0..2 * D {
        let mut s: State<D, Dual64> = state.to();
        // direction col of the scaled coordinates: dq = e_col or dv = w e_(col-D)
        if col < D {
            s.q[col].eps = 1.0;
        } else {
            s.v[col - D].eps = w;
        }
        let h = Dual64::from_re(h);
        let mut carry = scheme.start(scene, &s, h);
        scheme.step(scene, &mut carry, h)?;
        let out = scheme.state(&carry, h);
        for row in 0..D {
            jacobian[(row, col)] = out.q[row].eps;
            jacobian[(row + D, col)] = out.v[row].eps / w;
        }
    }
    Ok(jacobian)
}

/// The tangent map of one step in scaled coordinates, and a bound on the
/// error of each of its entries: exact (`None`) for a scheme that runs in
/// dual numbers, by [`finite_difference_jacobian`] otherwise.
pub fn tangent_map<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    state: &State<D>,
    h: f64,
) -> Result<(DMatrix<f64>, Option<f64>), StepFailure> {
    if scheme.differentiable() {
        Ok((step_jacobian(scheme, scene, state, h)?, None))
    } else {
        let (j, error) = finite_difference_jacobian(scheme, scene, state, h)?;
        Ok((j, Some(error)))
    }
}

/// Round-off of one step's output, in units of the epsilon of the scheme's
/// arithmetic times the size of the state, per force evaluation of the step
/// (plus one for the update itself): every stage rounds the state's
/// components and adds a rounded force, at most a couple of roundings each.
pub const STEP_ROUNDING_UNITS_PER_EVALUATION: f64 = 4.0;

/// The Jacobian of the one-step map (as [`step_jacobian`]) by central
/// differences, for schemes that cannot run in dual numbers, with a bound on
/// the error of every entry.
///
/// Coordinates are scaled, `y = (q, v / w) / L` with `L` the scene's
/// [`Scene::scale`], so that all components are of order one. With the
/// step's output rounded to `K eps` (`K` from
/// [`STEP_ROUNDING_UNITS_PER_EVALUATION`] and the scheme's force evaluations,
/// `eps` from [`Scheme::epsilon`]), a central difference `D(d)` carries
///
/// - truncation `c3 d^2 + c5 d^4 + ...` (the map is smooth), and
/// - round-off at most `K eps / d`.
///
/// Richardson's `R(d) = (4 D(d) - D(2d)) / 3` cancels `d^2`, leaving
/// `c5 d^4` and round-off `(4 + 1/2) / 3 K eps / d = 1.5 K eps / d`. The
/// truncation left is estimated from the next coarser extrapolation,
/// `|R(2d) - R(d)| / 15` (the `d^4` term grows 16-fold), taken twice for
/// safety; the bound is that plus the round-off term. Where the two balance
/// depends on the map's fifth derivative, which is not known in advance, so
/// `d` runs down from `1/4` by halves and the `d` with the smallest bound is
/// kept (the search stops once round-off alone exceeds the best bound).
///
/// Measured for RK4 in `f64` on the circular orbit at 100 steps a period:
/// entries off by 3.6e-13 against a bound of 1.4e-11, a symplectic-residual
/// bound of 1.1e-10 against RK4's defect of 5.9e-9 there; on the oscillator
/// (a linear map, no truncation) the residual bound is 2.6e-13 against a
/// defect of 8.6e-10. In `f32` the residual bound is about 1e-3 on the orbit
/// and 2e-4 on the oscillator, below RK4's defect at ten steps a period
/// (3.5e-3 and 8.1e-4), which the symplecticity study's coarsest step
/// samples.
pub fn finite_difference_jacobian<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    state: &State<D>,
    h: f64,
) -> Result<(DMatrix<f64>, f64), StepFailure> {
    let n = 2 * D;
    let w = scene.frequency();
    let size = scene.scale().max(f64::MIN_POSITIVE);
    let units = STEP_ROUNDING_UNITS_PER_EVALUATION * (scheme.meta().force_evaluations as f64 + 1.0);
    let rounding = units * scheme.epsilon();
    let y0: SVector<f64, D> = state.q / size;
    let u0: SVector<f64, D> = state.v / (size * w);
    // the scaled output of one step from the scaled input
    let map = |y: &SVector<f64, D>, u: &SVector<f64, D>| -> Result<DVector<f64>, StepFailure> {
        let s = State::new(y * size, u * (size * w));
        let mut carry = scheme.start(scene, &s, h);
        scheme.step(scene, &mut carry, h)?;
        let out = scheme.state(&carry, h);
        Ok(DVector::from_fn(n, |i, _| {
            if i < D {
                out.q[i] / size
            } else {
                out.v[i - D] / (size * w)
            }
        }))
    };
    // every column's central difference at step d
    let differences = |d: f64| -> Result<DMatrix<f64>, StepFailure> {
        let mut m = DMatrix::zeros(n, n);
        for col in 0..n {
            let (mut yp, mut up, mut ym, mut um) = (y0, u0, y0, u0);
            let taken = if col < D {
                yp[col] += d;
                ym[col] -= d;
                yp[col] - ym[col]
            } else {
                up[col - D] += d;
                um[col - D] -= d;
                up[col - D] - um[col - D]
            };
            m.set_column(col, &((map(&yp, &up)? - map(&ym, &um)?) / taken));
        }
        Ok(m)
    };
    let mut d = 0.25;
    let mut middle = differences(d / 2.0)?;
    let mut previous = (&middle * 4.0 - differences(d)?) / 3.0;
    let mut best: Option<(DMatrix<f64>, f64)> = None;
    loop {
        d /= 2.0;
        let round_off = 1.5 * rounding / (d / 2.0);
        if best.as_ref().is_some_and(|(_, b)| round_off > *b) || d < f64::EPSILON {
            break;
        }
        let fine = differences(d / 2.0)?;
        let extrapolated = (&fine * 4.0 - &middle) / 3.0;
        let bound = 2.0 * (&extrapolated - &previous).amax() / 15.0 + round_off;
        if bound.is_finite() && best.as_ref().is_none_or(|(_, b)| bound < *b) {
            best = Some((extrapolated.clone(), bound));
        }
        (middle, previous) = (fine, extrapolated);
    }
    Ok(best.unwrap_or((previous, f64::INFINITY)))
}

/// A bound on the error of [`symplectic_residual`]`(J) / max(1, max|J|^2)`
/// when every entry of `J` is off by at most `e`: each entry of `J^T Omega
/// J` sums `n = 2D` products of two entries, each off by at most
/// `2 max|J| e + e^2`.
pub fn residual_error_bound(j: &DMatrix<f64>, e: f64) -> f64 {
    let largest = j.amax();
    j.nrows() as f64 * (2.0 * largest * e + e * e) / largest.powi(2).max(1.0)
}

/// `max |J^T Omega J - Omega|` with `Omega = [[0, I], [-I, 0]]`: zero exactly
/// when `J` is symplectic.
pub fn symplectic_residual(j: &DMatrix<f64>) -> f64 {
    let n = j.nrows() / 2;
    let omega = DMatrix::from_fn(2 * n, 2 * n, |r, c| {
        if c == r + n {
            1.0
        } else if r == c + n {
            -1.0
        } else {
            0.0
        }
    });
    (j.transpose() * &omega * j - omega).amax()
}

/// `grad V(q)`, exactly.
pub fn potential_gradient<S: Scene<D>, const D: usize>(
    scene: &S,
    q: &SVector<f64, D>,
) -> SVector<f64, D> {
    SVector::from_fn(|i, _| {
        let mut x: SVector<Dual64, D> = q.map(Dual64::from_re);
        x[i].eps = 1.0;
        scene.potential(&x).eps
    })
}

/// The motion's fastest local rate at `q`: `sqrt(max |lambda|)` over the
/// eigenvalues `lambda` of the force's Jacobian `d a / d q` (symmetric where
/// `a = -grad V`; its symmetric part is taken). Near a minimum of the
/// potential it is the fastest local angular frequency; where the force
/// pulls nearby orbits apart (`lambda > 0`, radially near a Kepler
/// pericentre, `lambda = 2 GM / r^3`) the rate at which they e-fold.
pub fn local_rate<S: Scene<D>, const D: usize>(scene: &S, q: &SVector<f64, D>) -> f64 {
    let jacobian = acceleration_jacobian(scene, q);
    let symmetric = (&jacobian + jacobian.transpose()) * 0.5;
    symmetric.symmetric_eigenvalues().amax().sqrt()
}

/// `d a_i / d q_j`, exactly.
pub fn acceleration_jacobian<S: Scene<D>, const D: usize>(
    scene: &S,
    q: &SVector<f64, D>,
) -> DMatrix<f64> {
    let mut jac = DMatrix::zeros(D, D);
    for j in 0..D {
        let mut x: SVector<Dual64, D> = q.map(Dual64::from_re);
        x[j].eps = 1.0;
        let a = scene.acceleration(&x);
        for i in 0..D {
            jac[(i, j)] = a[i].eps;
        }
    }
    jac
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Harmonic, KeplerCircular};
    use crate::scheme::Euler;
    use nalgebra::{Vector1, Vector2};

    #[test]
    fn euler_tangent_map_on_the_oscillator_is_its_matrix() {
        // x' = x + h v, v' = v - h w^2 x; scaled by w: [[1, z], [-z, 1]], z = h w
        let osc = Harmonic::new(3.0, 1.0, 0.0).unwrap();
        let (h, z) = (0.1, 0.3);
        let j = step_jacobian(&Euler, &osc, &osc.initial(), h).unwrap();
        let expected = DMatrix::from_row_slice(2, 2, &[1.0, z, -z, 1.0]);
        assert!((j - expected).amax() < 1e-15);
    }

    #[test]
    fn finite_differences_agree_with_the_exact_tangent_map_within_their_bound() {
        use crate::scene::KeplerEccentric;
        use crate::scheme::{Rk4, VELOCITY_VERLET};
        let ecc = KeplerEccentric::new(0.6).unwrap();
        for h in [0.1, 0.01] {
            for s in [KeplerCircular.initial(), ecc.initial()] {
                let exact = step_jacobian(&Rk4, &KeplerCircular, &s, h).unwrap();
                let (fd, bound) = finite_difference_jacobian(&Rk4, &KeplerCircular, &s, h).unwrap();
                let off = (&fd - &exact).amax();
                let defect = symplectic_residual(&exact) / exact.amax().powi(2).max(1.0);
                let residual_bound = residual_error_bound(&fd, bound);
                assert!(off <= bound, "h {h}: off {off:e} > bound {bound:e}");
                // the bound is useful: RK4's defect stands far above it
                assert!(
                    residual_bound < defect / 10.0,
                    "bound {residual_bound:e} vs defect {defect:e}"
                );
            }
            let exact = step_jacobian(&VELOCITY_VERLET, &ecc, &ecc.initial(), h).unwrap();
            let (fd, bound) =
                finite_difference_jacobian(&VELOCITY_VERLET, &ecc, &ecc.initial(), h).unwrap();
            assert!((&fd - &exact).amax() <= bound);
        }
    }

    /// The oscillator's rate is its `w0` everywhere; the Kepler force's
    /// Jacobian at radius `r` has the eigenvalues `-GM / r^3` (along the
    /// orbit) and `2 GM / r^3` (radially), so its rate is `sqrt(2 GM /
    /// r^3)`, at the pericentre `r_p = 1 - e` of an orbit of `a = 1`.
    #[test]
    fn the_local_rate_is_the_forces_closed_form() {
        let w = local_rate(&Harmonic::new(3.0, 1.0, 0.0).unwrap(), &Vector1::new(0.4));
        assert!((w - 3.0).abs() < 1e-14);
        let gm = 4.0 * std::f64::consts::PI.powi(2);
        for e in [0.0, 0.6, 0.9, 0.999999] {
            let orbit = crate::scene::KeplerEccentric::new(e).unwrap();
            let rp: f64 = 1.0 - e;
            let w = local_rate(&orbit, &orbit.initial().q);
            let expected = (2.0 * gm / rp.powi(3)).sqrt();
            assert!(
                (w / expected - 1.0).abs() < 1e-9,
                "e {e}: {w} vs {expected}"
            );
        }
    }

    #[test]
    fn gradients_match_hand_derivatives() {
        let g = potential_gradient(&Harmonic::new(2.0, 1.0, 0.0).unwrap(), &Vector1::new(0.7));
        assert!((g[0] - 4.0 * 0.7).abs() < 1e-15);
        // V = -GM/r: grad V = GM r / r^3
        let q = Vector2::new(0.6, -0.8);
        let g = potential_gradient(&KeplerCircular, &q);
        let gm = 4.0 * std::f64::consts::PI.powi(2);
        assert!((g - q * gm).amax() < 1e-13);
        let j = acceleration_jacobian(&KeplerCircular, &q);
        // d/dq of -GM q/r^3 = -GM (I - 3 q q^T) at r = 1
        let qqt = DMatrix::<f64>::from_row_slice(2, 2, &[0.36, -0.48, -0.48, 0.64]);
        let expected = (DMatrix::<f64>::identity(2, 2) - qqt * 3.0) * -gm;
        assert!((j - expected).amax() < 1e-12);
    }
}
