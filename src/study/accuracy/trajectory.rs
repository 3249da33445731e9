//! A run sampled at equally spaced times, for figures and for the course
//! notes' Earth-Sun experiments: explicit Euler with `dt = 0.001` and
//! velocity Verlet with `dt = 0.01`, ten years each.

use crate::error::Error;
use crate::ladder::{check_cost, steps_for};
use crate::run::{Outcome, integrate};
use crate::scene::Scene;
use crate::scheme::Scheme;
use serde::Serialize;

/// A sampled run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TrajectoryRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// The step.
    pub h: f64,
    /// How the run ended.
    pub outcome: Outcome,
    /// Sample times.
    pub times: Vec<f64>,
    /// Positions at the sample times (one vector per time).
    pub positions: Vec<Vec<f64>>,
    /// `(E(t) - E0) / |E0|` at the sample times.
    pub relative_energy_error: Vec<f64>,
}

/// Runs `scheme` on `scene` with step `h` to `t_end`, sampling `samples + 1`
/// equally spaced times (the step count is rounded up so that every sample
/// time is a step time).
pub fn sample_trajectory<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    h: f64,
    t_end: f64,
    samples: u64,
) -> Result<TrajectoryRecord, Error> {
    let h = crate::scene::positive("h", h)?;
    let t_end = crate::scene::positive("t_end", t_end)?;
    let samples = samples.max(1);
    let steps = steps_for(t_end, h)?.div_ceil(samples) * samples;
    check_cost(steps)?;
    let every = steps / samples;
    let h = t_end / steps as f64;
    let start = scene.initial();
    let e0 = scene.energy(&start);
    let norm = if e0 != 0.0 { e0.abs() } else { 1.0 };
    let mut record = TrajectoryRecord {
        scheme: scheme.meta().id,
        scene: scene.meta().id,
        h,
        outcome: Outcome::Completed,
        times: Vec::new(),
        positions: Vec::new(),
        relative_energy_error: Vec::new(),
    };
    record.outcome = integrate(scheme, scene, &start, h, steps, |n, t, s| {
        if n % every == 0 {
            record.times.push(t);
            record.positions.push(s.q.iter().copied().collect());
            record
                .relative_energy_error
                .push((scene.energy(s) - e0) / norm);
        }
    });
    Ok(record)
}

/// The course notes' two Earth-Sun experiments on the circular orbit, ten
/// years each: explicit Euler with `dt = 0.001`, velocity Verlet with
/// `dt = 0.01`, sampled every hundredth of a year.
pub fn earth_sun_experiments() -> Vec<TrajectoryRecord> {
    use crate::scene::KeplerCircular;
    use crate::scheme::{Euler, VELOCITY_VERLET};
    let (years, samples) = (10.0, 1000);
    vec![
        sample_trajectory(&Euler, &KeplerCircular, 0.001, years, samples).expect("valid constants"),
        sample_trajectory(&VELOCITY_VERLET, &KeplerCircular, 0.01, years, samples)
            .expect("valid constants"),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Harmonic;
    use crate::scheme::VELOCITY_VERLET;

    #[test]
    fn samples_fall_on_step_times_and_follow_the_run() {
        let osc = Harmonic::default();
        let r = sample_trajectory(&VELOCITY_VERLET, &osc, 0.01, 6.0, 60).unwrap();
        assert_eq!(r.times.len(), 61);
        assert!((r.times[60] - 6.0).abs() < 1e-12);
        // a tenth of a unit apart, and the oscillator near cos t
        for (t, q) in r.times.iter().zip(&r.positions) {
            assert!((q[0] - t.cos()).abs() < 1e-4, "{t}: {q:?}");
        }
        assert!(r.relative_energy_error.iter().all(|e| e.abs() < 1e-4));
    }
}
