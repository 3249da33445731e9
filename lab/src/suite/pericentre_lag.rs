//! Why the eccentric Kepler orbit's tightest race target is out of reach in
//! doubles: the error of the best runs is a lag along the orbit, and the
//! lag a unit of round-off in the energy makes is, at pericentre, larger
//! than the target.
//!
//! An error in the energy `E = -GM/(2a)` is an error in the mean motion
//! `n = sqrt(GM/a^3)`, `dn/n = (3/2) dE/|E|`: the computed body runs early
//! or late by `dt = (dn/n) t`, and at a time `t` its phase-space distance to
//! the exact state is `S dt`, `S` the phase-space speed `(|v|^2 +
//! |a/w|^2)^(1/2)` there, largest at pericentre. A target `T` at a
//! pericentre passage at time `t` therefore needs the energy within
//! `(2/3) T / (S t)` of itself. The force is evaluated at stage positions
//! rounded to doubles, and one such rounding at pericentre (half an ulp of
//! `r_p`, at most `u r_p`, `u = 2^-53`) moves the potential the force
//! derives from by up to `u |V_p|` with `V_p = -GM/r_p`: `u |V_p|/|E| =
//! 2u/(1-e)` of the energy, `5u` at `e = 0.6`.

use serde::Serialize;
use stepladder::scene::{KeplerEccentric, Scene};
use stepladder::scheme::{AdaptiveIntegrator, DPRKN12_COMPENSATED, RunEnd};

/// The tolerance of the run analysed: the tightest the Kepler race uses.
pub const LAG_TOLERANCE: f64 = 1e-14;

/// The worst point of the compensated twelfth-order pair on the eccentric
/// orbit, split into a lag along the orbit and the rest, and what the
/// target would need.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PericentreLag {
    /// The time of the worst point.
    pub time: f64,
    /// Its phase-space distance to the exact state.
    pub error: f64,
    /// The time shift that best explains it (positive: the run is ahead).
    pub shift: f64,
    /// The share of the error that shift leaves unexplained (the error
    /// across the orbit over the whole error).
    pub across_share: f64,
    /// The phase-space speed `S` at the worst point.
    pub speed: f64,
    /// The relative energy error the shift amounts to, `(2/3) |shift| / t`.
    pub energy_offset: f64,
    /// `2/(1-e)`: one stage position's rounding at pericentre, as a share
    /// of the energy, in units of `u = 2^-53`.
    pub stage_rounding_units: f64,
}

impl PericentreLag {
    /// Runs the pair and measures its worst point; `None` if the run fails.
    pub fn measure(orbit: &KeplerEccentric) -> Option<PericentreLag> {
        let run = DPRKN12_COMPENSATED
            .run(orbit, orbit.default_t_end(), LAG_TOLERANCE)
            .ok()
            .filter(|r| r.end == RunEnd::Reached)?;
        let w = orbit.frequency();
        let (error, t, s, exact) = run
            .trajectory
            .iter()
            .filter_map(|(t, s)| {
                let exact = orbit.exact(*t)?;
                Some((orbit.phase_distance(s, &exact), t, s, exact))
            })
            .max_by(|a, b| a.0.total_cmp(&b.0))?;
        let (dq, dv) = (s.q - exact.q, (s.v - exact.v) / w);
        let (tq, tv) = (exact.v, orbit.acceleration(&exact.q) / w);
        let speed = (tq.norm_squared() + tv.norm_squared()).sqrt();
        let shift = (dq.dot(&tq) + dv.dot(&tv)) / (speed * speed);
        let across = ((dq - tq * shift).norm_squared() + (dv - tv * shift).norm_squared()).sqrt();
        // the orbit starts at pericentre
        let start = orbit.initial();
        let (energy, pericentre_potential) = (orbit.energy(&start), orbit.potential(&start.q));
        Some(PericentreLag {
            time: *t,
            error,
            shift,
            across_share: across / error,
            speed,
            energy_offset: 2.0 / 3.0 * shift.abs() / t,
            stage_rounding_units: pericentre_potential.abs() / energy.abs(),
        })
    }

    /// The relative energy error a target at the worst point allows,
    /// `(2/3) T / (S t)`.
    pub fn energy_allowed(&self, target: f64) -> f64 {
        2.0 / 3.0 * target / (self.speed * self.time)
    }
}
