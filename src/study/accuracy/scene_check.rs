//! Is the scene itself right? Its force must be `-grad V` (conservative), and
//! its exact solution must satisfy the equations of motion. A scene that
//! fails here would judge every scheme against a wrong answer.

use crate::maths::tangent::{acceleration_jacobian, potential_gradient};
use crate::scene::Scene;
use crate::study::verdict::Verdict;
use crate::tolerance::SCENE_TOLERANCE;
use nalgebra::SVector;
use serde::Serialize;

/// Times, in periods, at which the exact solution is checked.
const CHECK_TIMES: usize = 16;

/// Factors applied to positions along the orbit to probe the force off it.
const PROBE_SCALES: [f64; 3] = [0.8, 1.0, 1.25];

/// What the scene check found; every residual is relative (see each field).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SceneCheck {
    /// Scene id.
    pub scene: &'static str,
    /// `max |a(q) + grad V(q)| / |a(q)|` over the probe points.
    pub force_residual: f64,
    /// `max |da_x/dy - da_y/dx| / max |da_i/dq_j|` (2-D and up; 0 in 1-D).
    pub curl_residual: f64,
    /// `max |dq/dt - v| / |v|` along the exact solution (`None` without one).
    pub velocity_residual: Option<f64>,
    /// `max |dv/dt - a(q)| / |a|` along the exact solution.
    pub acceleration_residual: Option<f64>,
    /// Every residual is below [`SCENE_TOLERANCE`].
    pub verdict: Verdict,
}

/// Checks `scene`.
pub fn check_scene<S: Scene<D>, const D: usize>(scene: &S) -> SceneCheck {
    let period = scene.period();
    let states: Vec<_> = match scene.exact(0.0) {
        Some(_) => (0..CHECK_TIMES)
            .filter_map(|k| scene.exact(period * (k as f64 + 0.31) / CHECK_TIMES as f64))
            .collect(),
        None => vec![scene.initial()],
    };
    let mut force_residual = 0.0f64;
    let mut curl_residual = 0.0f64;
    for s in &states {
        for f in PROBE_SCALES {
            let q: SVector<f64, D> = s.q * f;
            let a = scene.acceleration(&q);
            let g = potential_gradient(scene, &q);
            force_residual = force_residual.max((a + g).norm() / a.norm().max(f64::MIN_POSITIVE));
            let j = acceleration_jacobian(scene, &q);
            let asym = (&j - j.transpose()).amax();
            curl_residual = curl_residual.max(asym / j.amax().max(f64::MIN_POSITIVE));
        }
    }
    let (velocity_residual, acceleration_residual) = match scene.exact(0.0) {
        Some(_) => {
            let (mut dq, mut dv) = (0.0f64, 0.0f64);
            for k in 0..CHECK_TIMES {
                let t = period * (k as f64 + 0.31) / CHECK_TIMES as f64;
                let s = scene.exact(t).expect("exact exists");
                let a = scene.acceleration(&s.q);
                // a time step small against every time scale of the motion here
                let tau = (s.q.norm() / s.v.norm())
                    .min((s.q.norm() / a.norm()).sqrt())
                    .min(period);
                let dt = 1e-3 * tau;
                let (Some(q_dot), Some(v_dot)) = (
                    derivative(|t| scene.exact(t).map(|s| s.q), t, dt),
                    derivative(|t| scene.exact(t).map(|s| s.v), t, dt),
                ) else {
                    continue;
                };
                dq = dq.max((q_dot - s.v).norm() / s.v.norm().max(f64::MIN_POSITIVE));
                dv = dv.max((v_dot - a).norm() / a.norm().max(f64::MIN_POSITIVE));
            }
            (Some(dq), Some(dv))
        }
        None => (None, None),
    };
    let ok = [
        Some(force_residual),
        Some(curl_residual),
        velocity_residual,
        acceleration_residual,
    ]
    .into_iter()
    .flatten()
    .all(|r| r <= SCENE_TOLERANCE);
    SceneCheck {
        scene: scene.meta().id,
        force_residual,
        curl_residual,
        velocity_residual,
        acceleration_residual,
        verdict: Verdict::from_bool(ok),
    }
}

/// Eighth-order central difference `f'(t)` with step `dt`: truncation
/// `O((dt/tau)^8)`, round-off about `|f| eps / dt`.
fn derivative<const D: usize>(
    f: impl Fn(f64) -> Option<SVector<f64, D>>,
    t: f64,
    dt: f64,
) -> Option<SVector<f64, D>> {
    const W: [f64; 4] = [4.0 / 5.0, -1.0 / 5.0, 4.0 / 105.0, -1.0 / 280.0];
    let mut d = SVector::<f64, D>::zeros();
    for (k, w) in W.iter().enumerate() {
        let s = (k + 1) as f64 * dt;
        d += (f(t + s)? - f(t - s)?) * *w;
    }
    Some(d / dt)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_of_a_polynomial_of_degree_eight_is_exact() {
        let p = |t: f64| Some(SVector::<f64, 1>::new(t.powi(8) - 3.0 * t.powi(5) + t));
        let d = derivative(p, 0.7, 0.01).unwrap()[0];
        let exact = 8.0 * 0.7f64.powi(7) - 15.0 * 0.7f64.powi(4) + 1.0;
        assert!((d - exact).abs() < 1e-10, "{d} vs {exact}");
    }
}
