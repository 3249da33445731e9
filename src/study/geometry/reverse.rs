//! Reversibility: `N` steps with `h`, then `N` steps with `-h` from the
//! synchronised end state; a time-symmetric scheme comes back to round-off.

use crate::error::Error;
use crate::ladder::check_count;
use crate::run::{Outcome, integrate};
use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::state::State;
use crate::study::breakdown::{Breakdown, Probe, probe};
use crate::study::geometry::energy::MAX_HALVINGS;
use crate::study::verdict::Verdict;
use crate::tolerance::reverse_tolerance_ulps;
use crate::wording::{figure, vs_upper};
use serde::Serialize;

/// Default step, in periods of the scene.
pub const DEFAULT_STEP: f64 = 1.0 / 100.0;

/// Default number of steps each way: ten periods at the default step.
pub const DEFAULT_STEPS: u64 = 1000;

/// What to measure.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ReverseSpec {
    /// The step; `None` for [`DEFAULT_STEP`] periods.
    pub h: Option<f64>,
    /// Steps each way; `None` for [`DEFAULT_STEPS`].
    pub steps: Option<u64>,
}

impl ReverseSpec {
    /// The step and the steps each way, refused before any run unless the
    /// step is in `[SCAN_START / w, SCAN_END / w]` ([`crate::scene::step`]),
    /// there is at least one step, the round trip's `2 steps` are at most
    /// [`MAX_TOTAL_STEPS`](crate::ladder::MAX_TOTAL_STEPS), and its turning
    /// time `steps * h` is a finite number.
    pub fn checked(&self, period: f64, frequency: f64) -> Result<(f64, u64), Error> {
        let h = match self.h {
            Some(h) => crate::scene::step("h", h, frequency)?,
            None => DEFAULT_STEP * period,
        };
        let steps = self.steps.unwrap_or(DEFAULT_STEPS);
        if steps == 0 {
            return Err(Error::InvalidParameter {
                name: "steps",
                value: 0.0,
                expected: "at least 1",
            });
        }
        // counted in floating point: twice a huge count must not saturate
        check_count(2.0 * steps as f64)?;
        if !(steps as f64 * h).is_finite() {
            return Err(Error::OutOfRange {
                name: "h",
                value: h,
                expected: format!(
                    "a step in (0, {}]: the turning time, {steps} steps of h, must be a finite \
                     number",
                    figure(f64::MAX / steps as f64)
                ),
            });
        }
        Ok((h, steps))
    }
}

/// What the reversibility study found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReverseRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// The step of the round trip judged: the one asked for, or a halving
    /// of it when a claimed-symmetric trip blew up at the larger steps.
    pub h: f64,
    /// Steps each way.
    pub steps: u64,
    /// How the round trip ended.
    pub outcome: Outcome,
    /// Phase-space distance from the start after the round trip (length
    /// units); `None` if it blew up.
    pub return_error: Option<f64>,
    /// The same in units of `eps * scale`, the rounding unit of the motion.
    pub return_ulps: Option<f64>,
    /// How much the run magnifies a small perturbation of its start (1 when
    /// it does not): round-off made along the way is magnified alike.
    pub growth: f64,
    /// Largest return, in those units, that counts as round-off.
    pub tolerance_ulps: f64,
    /// The return is within round-off.
    pub measured: bool,
    /// The scheme claims to be time-symmetric.
    pub claimed: bool,
    /// Claim and measurement agree.
    pub verdict: Verdict,
    /// Why, in one line.
    pub reason: String,
    /// The trip stopped on a defect of the step (a panic, or a stop where a
    /// coarser step ran the same span cleanly; see
    /// [`crate::study::breakdown`]): the verdict fails on it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub breakdown: Option<Breakdown>,
}

/// Runs the round trip.
pub fn reversibility<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    spec: &ReverseSpec,
) -> Result<ReverseRecord, Error> {
    let (h, steps) = spec.checked(scene.period(), scene.frequency())?;
    let start = scene.initial();
    let meta = scheme.meta();
    // A time-symmetric scheme returns from every step at which it is stable
    // (and its implicit stages solvable); a blow-up at the first step says
    // nothing about symmetry. So a claimed-symmetric round trip that blows
    // up is repeated with the step halved, the number of steps kept, up to
    // MAX_HALVINGS times: the symmetry is a property of each step, and a
    // defect that is invisible only because the run blew up shows at the
    // first completed round trip.
    let mut h = h;
    let mut halvings = 0;
    let first_h = h;
    let (there, back, outcome, leg) = loop {
        let (there, back, outcome, leg) = round_trip(scheme, scene, &start, h, steps);
        if outcome.completed() || outcome.defect() || !meta.symmetric || halvings == MAX_HALVINGS {
            break (there, back, outcome, leg);
        }
        h /= 2.0;
        halvings += 1;
    };
    // A trip that stopped: instability at this step, or a defect (a panic,
    // or a stop below a step that runs the same span cleanly). Halving has
    // tried the finer steps of a symmetric claim; the probe tries the
    // coarser ones too, from the original step.
    let stopped = (!outcome.completed()).then(|| {
        // the trip at the step asked for, whose stop the probe explains
        let (first_stop, (leg_start, leg_h)) = if halvings > 0 && !outcome.defect() {
            let (_, _, stop, leg) = round_trip(scheme, scene, &start, first_h, steps);
            (stop, leg)
        } else {
            (outcome.clone(), leg)
        };
        let probe = probe(scheme, scene, &leg_start, leg_h, &first_stop);
        Stop {
            finding: probe.describe(leg_h.abs(), &first_stop),
            breakdown: probe.breakdown().cloned(),
            unstable: matches!(probe, Probe::Unstable { .. }),
        }
    });
    let scale = scene.scale();
    let return_error = outcome
        .completed()
        .then(|| scene.phase_distance(&back, &start));
    let return_ulps = return_error.map(|e| e / (scheme.epsilon() * scale));
    let growth = perturbation_growth(scheme, scene, &there, h, steps);
    let tolerance_ulps = reverse_tolerance_ulps(steps, growth);
    let measured = return_ulps.is_some_and(|u| u <= tolerance_ulps);
    let halved = if halvings > 0 {
        format!(
            " at h = {}, the round trip having blown up at {}",
            figure(h),
            if halvings > 1 {
                format!("each of the {halvings} coarser steps")
            } else {
                "twice that step".to_string()
            }
        )
    } else {
        String::new()
    };
    let (verdict, reason) = judge(
        return_ulps,
        meta.symmetric,
        Allowance {
            ulps: tolerance_ulps,
            steps,
            growth,
        },
        h,
        &halved,
        stopped.as_ref(),
    );
    Ok(ReverseRecord {
        breakdown: stopped.and_then(|s| s.breakdown),
        scheme: meta.id,
        scene: scene.meta().id,
        h,
        steps,
        outcome,
        return_error,
        return_ulps,
        growth,
        tolerance_ulps,
        measured,
        claimed: meta.symmetric,
        verdict,
        reason,
    })
}

/// What the runs at other steps made of a round trip that stopped.
struct Stop {
    /// The finding in words, with its figures.
    finding: String,
    /// A defect: a panic, or a stop below a step that runs cleanly.
    breakdown: Option<Breakdown>,
    /// Instability at the step: a finer one ran the same span.
    unstable: bool,
}

/// The round-off a round trip may return with, and what it is made of
/// (see [`reverse_tolerance_ulps`]).
struct Allowance {
    ulps: f64,
    steps: u64,
    growth: f64,
}

/// The verdict on a symmetry claim from the return error in ulps (`None`
/// when the round trip blew up). A claim of time symmetry is refuted by one
/// round trip that does not return; a claim that the scheme is not
/// symmetric promises nothing.
fn judge(
    return_ulps: Option<f64>,
    claimed_symmetric: bool,
    allowance: Allowance,
    h: f64,
    halved: &str,
    stopped: Option<&Stop>,
) -> (Verdict, String) {
    let measured = return_ulps.is_some_and(|u| u <= allowance.ulps);
    let (steps, growth) = (allowance.steps as f64, allowance.growth.max(1.0));
    match (return_ulps, claimed_symmetric, stopped) {
        // a defect of the step fails whatever is claimed
        (None, _, Some(stop)) if stop.breakdown.is_some() => (
            Verdict::Fail,
            format!("the round trip did not complete: {}", stop.finding),
        ),
        (None, true, stop) => (
            Verdict::Inconclusive,
            format!(
                "the round trip did not complete at any step down to h = {} ({MAX_HALVINGS} \
                 halvings): {}; a time-symmetric scheme returns only from steps it runs \
                 cleanly, and the scene gave none here",
                figure(h),
                stop.map_or("", |s| s.finding.as_str()),
            ),
        ),
        (None, false, stop) => (
            Verdict::Pass,
            format!(
                "the round trip did not complete ({}): not time-symmetric, as claimed{}",
                stop.map_or("", |s| s.finding.as_str()),
                if stop.is_some_and(|s| s.unstable) {
                    ""
                } else {
                    " (and no step tried ran it cleanly)"
                }
            ),
        ),
        (Some(u), claimed, _) => {
            let found = format!(
                "return error in units of eps x scale {} ({} a step over {} steps there and \
                 back, magnified {} times by the flow){halved}",
                vs_upper(u, "allowance", allowance.ulps),
                figure(allowance.ulps / (2.0 * steps * growth)),
                2 * allowance.steps,
                figure(growth),
            );
            match (claimed, measured) {
                (true, true) => (
                    Verdict::Pass,
                    format!("{found}: time-symmetric, as claimed"),
                ),
                (true, false) => (
                    Verdict::Fail,
                    format!("{found}: not time-symmetric, though claimed"),
                ),
                (false, false) => (
                    Verdict::Pass,
                    format!("{found}: not time-symmetric, as claimed"),
                ),
                (false, true) => (
                    Verdict::Pass,
                    format!(
                        "{found}: time-symmetric on this scene, which does not refute the claim \
                     that the scheme is not"
                    ),
                ),
            }
        }
    }
}

/// `steps` steps with `h` from `start`, then as many with `-h` from where
/// they ended: the end state, the state returned to, how the trip ended and
/// the start and step of its last leg.
fn round_trip<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    start: &State<D>,
    h: f64,
    steps: u64,
) -> (State<D>, State<D>, Outcome, (State<D>, f64)) {
    let mut there = *start;
    let mut outcome = integrate(scheme, scene, start, h, steps, |_, _, s| there = *s);
    let mut back = there;
    if !outcome.completed() {
        return (there, back, outcome, (*start, h));
    }
    outcome = integrate(scheme, scene, &there, -h, steps, |_, _, s| back = *s);
    (there, back, outcome, (there, -h))
}

/// How much `steps` steps magnify a small perturbation of the start: the
/// phase-space distance between the runs from `s0` and from `s0` moved by
/// 1e-7 of the scene's size (along every coordinate alike, in the scaled
/// coordinates `(q, v/w)`), over that displacement. Shear near a Kepler
/// pericentre magnifies errors by tens to hundreds over ten periods, and the
/// round-off a symmetric scheme makes on the way out is magnified alike.
fn perturbation_growth<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    end: &State<D>,
    h: f64,
    steps: u64,
) -> f64 {
    let start = scene.initial();
    let size = 1e-7 * scene.scale();
    let unit = size / ((2 * D) as f64).sqrt();
    let mut moved = start;
    moved.q.iter_mut().for_each(|x| *x += unit);
    moved
        .v
        .iter_mut()
        .for_each(|x| *x += unit * scene.frequency());
    let displacement = scene.phase_distance(&moved, &start);
    let mut there = moved;
    let outcome = integrate(scheme, scene, &moved, h, steps, |_, _, s| there = *s);
    if !outcome.completed() {
        return 1.0;
    }
    (scene.phase_distance(&there, end) / displacement).max(1.0)
}
