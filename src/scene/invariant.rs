//! What the exact flow of a scene conserves: the energy always, linear and
//! angular momentum where the scene has the symmetry (an isolated N-body
//! problem has all three, a body around a fixed centre only the angular
//! momentum). On a scene without an exact solution these are the only
//! absolute truth a study has: a scheme that converges to the solution of
//! another equation converges, but its invariants do not return to their
//! initial values as `h -> 0`.
//!
//! Each value comes with its **sensitivity**: the largest change of the
//! invariant per unit phase-space distance at that state (the norm of its
//! gradient in the metric of [`Scene::phase_distance`], `sqrt(|dq|^2 +
//! |dv / w|^2)`). A state error `d` can move the invariant by at most
//! `sensitivity * d` to first order, so a run whose global error is `e`
//! cannot change the invariant by more than `max sensitivity * e` (plus
//! round-off) if it approximates a solution of the scene's equations.

use super::Scene;
use crate::state::State;
use serde::Serialize;

/// A quantity the exact flow of a scene conserves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Invariant {
    /// The total energy `|v|^2 / 2 + V(q)`.
    Energy,
    /// Component `axis` of the total linear momentum.
    Momentum {
        /// The Cartesian axis: 0 for x, 1 for y, 2 for z.
        axis: u8,
    },
    /// Component `axis` of the total angular momentum about the origin
    /// (`axis = 2`, the normal, for motion in the plane).
    AngularMomentum {
        /// The Cartesian axis: 0 for x, 1 for y, 2 for z.
        axis: u8,
    },
}

impl Invariant {
    /// A short name for messages and tables: `energy`, `momentum-x`,
    /// `angular-momentum-z`.
    pub fn name(&self) -> String {
        let axis = |a: u8| ["x", "y", "z"].get(a as usize).copied().unwrap_or("?");
        match self {
            Invariant::Energy => "energy".into(),
            Invariant::Momentum { axis: a } => format!("momentum-{}", axis(*a)),
            Invariant::AngularMomentum { axis: a } => format!("angular-momentum-{}", axis(*a)),
        }
    }

    /// The power of a length unit the invariant scales with when every
    /// position and velocity is multiplied by a constant (energy and
    /// angular momentum 2, momentum 1).
    pub fn length_power(&self) -> i32 {
        match self {
            Invariant::Momentum { .. } => 1,
            Invariant::Energy | Invariant::AngularMomentum { .. } => 2,
        }
    }
}

/// An invariant's value at one state, and how much a phase-space error can
/// move it there.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct InvariantValue {
    /// The value.
    pub value: f64,
    /// The norm of its gradient in the phase-space metric: `|dI| <=
    /// sensitivity * d` to first order for a phase-space distance `d`.
    pub sensitivity: f64,
}

/// The invariants' values at a state, each with its sensitivity.
impl InvariantValue {
    /// The energy and its sensitivity:
    /// `dE = v . dv - a . dq = (w v) . (dv / w) - a . dq`, so by Cauchy-Schwarz
    /// `|dE| <= sqrt(w^2 |v|^2 + |a|^2) d`.
    pub fn energy<S: Scene<D> + ?Sized, const D: usize>(scene: &S, s: &State<D>) -> InvariantValue {
        let w = scene.frequency();
        let a = scene.acceleration(&s.q);
        InvariantValue {
            value: scene.energy(s),
            sensitivity: (w * w * s.v.norm_squared() + a.norm_squared()).sqrt(),
        }
    }

    /// Component `axis` of the linear momentum of bodies in `dims` dimensions,
    /// stored body after body (`x1, y1, x2, y2, ...`) in mass-weighted
    /// coordinates `Q_i = sqrt(m_i) q_i`: `P = sum_i sqrt(m_i) Q_i'`. Its
    /// gradient is `sqrt(m_i)` on each body's velocity component, so in the
    /// phase-space metric `|dP| <= w sqrt(sum_i m_i) d`.
    pub fn momentum<const D: usize>(
        s: &State<D>,
        sqrt_masses: &[f64],
        dims: usize,
        axis: usize,
        w: f64,
    ) -> InvariantValue {
        let value = sqrt_masses
            .iter()
            .enumerate()
            .map(|(i, m)| m * s.v[dims * i + axis])
            .sum();
        let total: f64 = sqrt_masses.iter().map(|m| m * m).sum();
        InvariantValue {
            value,
            sensitivity: w * total.sqrt(),
        }
    }

    /// The angular momentum about the origin, normal to the plane, of bodies in
    /// the plane stored `x1, y1, x2, y2, ...` in mass-weighted coordinates:
    /// `L = sum_i (X_i Y_i' - Y_i X_i')` (the masses are inside the
    /// coordinates). `dL = sum (Y' dX - X' dY + w X (dY'/w) - w Y (dX'/w))`,
    /// so `|dL| <= sqrt(|Q'|^2 + w^2 |Q|^2) d`.
    pub fn planar_angular_momentum<const D: usize>(s: &State<D>, w: f64) -> InvariantValue {
        let value = (0..D / 2)
            .map(|i| s.q[2 * i] * s.v[2 * i + 1] - s.q[2 * i + 1] * s.v[2 * i])
            .sum();
        InvariantValue {
            value,
            sensitivity: (s.v.norm_squared() + w * w * s.q.norm_squared()).sqrt(),
        }
    }

    /// Component `axis` of the angular momentum about the origin of bodies in
    /// space stored `x1, y1, z1, x2, ...` in mass-weighted coordinates: `L =
    /// sum_i Q_i x Q_i'` (the masses are inside the coordinates). With `(a, b,
    /// c)` the axes in cyclic order from `axis`, `L_a = sum_i (Q_ib Q_ic' -
    /// Q_ic Q_ib')`, so `dL_a = sum (Q_ic' dQ_ib - Q_ib' dQ_ic + w Q_ib
    /// (dQ_ic'/w) - w Q_ic (dQ_ib'/w))`: each term has a coordinate of its own,
    /// and the gradient's norm in the phase-space metric is `sqrt(sum_i (Q_ib'^2
    /// + Q_ic'^2 + w^2 (Q_ib^2 + Q_ic^2)))`, the motion across the axis only.
    pub fn spatial_angular_momentum<const D: usize>(
        s: &State<D>,
        axis: usize,
        w: f64,
    ) -> InvariantValue {
        let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
        let (mut value, mut gradient) = (0.0, 0.0);
        for i in 0..D / 3 {
            let (qb, qc) = (s.q[3 * i + b], s.q[3 * i + c]);
            let (vb, vc) = (s.v[3 * i + b], s.v[3 * i + c]);
            value += qb * vc - qc * vb;
            gradient += vb * vb + vc * vc + w * w * (qb * qb + qc * qc);
        }
        InvariantValue {
            value,
            sensitivity: gradient.sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Harmonic, KeplerCircular};
    use nalgebra::SVector;

    /// The sensitivity bounds a small change of the state, and is nearly
    /// attained along the gradient: checked by finite differences.
    fn check_bound<const D: usize>(f: impl Fn(&State<D>) -> InvariantValue, s: &State<D>, w: f64) {
        let base = f(s);
        let eps = 1e-7;
        let mut largest = 0.0f64;
        for k in 0..2 * D {
            let mut dq = SVector::<f64, D>::zeros();
            let mut dv = SVector::<f64, D>::zeros();
            // a unit step in the metric: dq = eps, or dv / w = eps
            if k < D {
                dq[k] = eps;
            } else {
                dv[k - D] = eps * w;
            }
            let moved = f(&State::new(s.q + dq, s.v + dv));
            let slope = (moved.value - base.value).abs() / eps;
            assert!(
                slope <= base.sensitivity * (1.0 + 1e-5) + 1e-9,
                "{slope} > {}",
                base.sensitivity
            );
            largest = largest.hypot(slope);
        }
        // along the axes the slopes are the gradient's components
        assert!(
            (largest - base.sensitivity).abs() <= 1e-5 * base.sensitivity,
            "{largest} vs {}",
            base.sensitivity
        );
    }

    #[test]
    fn sensitivities_are_the_gradients_norms() {
        let orbit = KeplerCircular;
        let s = orbit.exact(0.3).unwrap();
        check_bound(|s| InvariantValue::energy(&orbit, s), &s, orbit.frequency());
        check_bound(|s| InvariantValue::planar_angular_momentum(s, 2.5), &s, 2.5);
        let osc = Harmonic::default();
        check_bound(
            |s| InvariantValue::energy(&osc, s),
            &osc.exact(1.0).unwrap(),
            1.0,
        );
        let bodies = State::<4>::new(
            SVector::from([1.0, 2.0, -0.5, 0.3]),
            SVector::from([0.2, -0.1, 0.7, 0.4]),
        );
        let m = [1.0f64.sqrt(), 3.0f64.sqrt()];
        check_bound(|s| InvariantValue::momentum(s, &m, 2, 0, 1.7), &bodies, 1.7);
        check_bound(|s| InvariantValue::momentum(s, &m, 2, 1, 1.7), &bodies, 1.7);
        check_bound(
            |s| InvariantValue::planar_angular_momentum(s, 1.7),
            &bodies,
            1.7,
        );
        // two bodies in space, each component of L, and the spatial helper
        // on a planar motion (z = 0) is the planar one
        let spatial = State::<6>::new(
            SVector::from([1.0, 2.0, -0.5, 0.3, -1.1, 0.8]),
            SVector::from([0.2, -0.1, 0.7, 0.4, 0.9, -0.6]),
        );
        for axis in 0..3 {
            check_bound(
                |s| InvariantValue::spatial_angular_momentum(s, axis, 1.7),
                &spatial,
                1.7,
            );
        }
        let flat = State::<6>::new(
            SVector::from([1.0, 2.0, 0.0, -0.5, 0.3, 0.0]),
            SVector::from([0.2, -0.1, 0.0, 0.7, 0.4, 0.0]),
        );
        let (l3, l2) = (
            InvariantValue::spatial_angular_momentum(&flat, 2, 1.7),
            InvariantValue::planar_angular_momentum(&bodies, 1.7),
        );
        assert_eq!(l3.value, l2.value);
        // the same sum of squares, added in another order: a few roundings
        assert!((l3.sensitivity - l2.sensitivity).abs() <= 4.0 * f64::EPSILON * l2.sensitivity);
    }

    #[test]
    fn names_and_length_powers() {
        assert_eq!(Invariant::Energy.name(), "energy");
        assert_eq!(Invariant::Momentum { axis: 1 }.name(), "momentum-y");
        assert_eq!(
            Invariant::AngularMomentum { axis: 2 }.name(),
            "angular-momentum-z"
        );
        assert_eq!(Invariant::Momentum { axis: 0 }.length_power(), 1);
        assert_eq!(Invariant::Energy.length_power(), 2);
    }
}
