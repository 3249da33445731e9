//! Exact derivatives by forward-mode automatic differentiation: the tangent
//! map of one step, the gradient of a potential, the Jacobian of a force.
//!
//! Each derivative runs the generic scheme or scene once per input direction
//! in dual numbers `x + eps dx` ([`num_dual::Dual64`]), so it is exact to
//! round-off; finite differences could not tell a 1e-15 defect from 1e-11.

use crate::scene::Scene;
use crate::scheme::{Scheme, StepFailure};
use crate::state::State;
use nalgebra::{DMatrix, SVector};
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
