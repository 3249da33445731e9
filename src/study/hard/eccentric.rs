//! Eccentric Kepler orbits: how the order and the energy of a scheme hold up
//! as the pericentre passage sharpens.
//!
//! Near pericentre the orbit turns through most of its angle in a few
//! `tau_p = r_p / v_p = (1 - e)^(3/2) / ((1 + e)^(1/2) n)` (`n = 2 pi /
//! period`), 0.046 periods at `e = 0.5` and `1.1e-4` at `e = 0.99`. A fixed
//! step that is not small against `tau_p` mistimes the passage; the numerical
//! and exact orbits then pass pericentre at different times, and while one
//! swings round and the other has not, their velocities differ by about the
//! pericentre speed: the phase-space error saturates near `v_p / w`, whatever
//! the order of the scheme. The order study here says so instead of fitting
//! an order through such rungs.
//!
//! Two further measurements:
//!
//! - **Energy** at a step of `tau_p / 8`: the energy error of a scheme of
//!   order `p` during a passage is a fixed fraction of the pericentre's
//!   kinetic energy `GM / r_p` once the step is scaled to `tau_p` (the
//!   passage is self-similar as `e -> 1`), so relative to `|E| = GM / 2a` it
//!   grows like `2 / (1 - e)`; away from pericentre a symplectic scheme's
//!   energy returns to the same value after every passage, a non-symplectic
//!   one's changes by the same amount at each.
//! - **Round-off of the two-step Störmer form**: it is the same map as
//!   velocity Verlet and leap-frog, so its distance from them is round-off
//!   alone, measured across the first full passage.

use crate::error::Error;
use crate::ladder::{AutoLadder, LadderChoice, LadderEnd, steps_for};
use crate::run::{Outcome, integrate};
use crate::scene::{KeplerEccentric, Scene};
use crate::scheme::{Leapfrog, Scheme, StormerVerlet, VELOCITY_VERLET};
use crate::state::State;
use crate::study::accuracy::order::{Analysis, OrderSpec, Rung, RungData, analyse, global_order};
use crate::tolerance::{
    self, ECCENTRIC_DRIFT_FRACTION, ERROR_CEILING, MIN_WINDOW, round_off_energy,
};
use serde::Serialize;

/// The eccentricities of the study: the standard test orbit's neighbours
/// (0.5, 0.6) and two ever sharper passages (0.9, 0.99).
pub const ECCENTRICITIES: [f64; 4] = [0.5, 0.6, 0.9, 0.99];

/// The schemes of the order study: the catalogue less the two-step Störmer
/// form and leap-frog, which compute the same map as velocity Verlet (same
/// positions at whole steps, same synchronised velocities) and so have the
/// same truncation error on every rung; what tells them apart is round-off,
/// which [`stormer_round_off`] measures directly. Each rung to the cap costs
/// about a tenth of a second, so the two ladders saved per eccentricity are
/// worth having.
pub const ORDER_SCHEMES: [&str; 10] = [
    "euler",
    "euler-cromer",
    "velocity-verlet",
    "position-verlet",
    "implicit-midpoint",
    "rk4",
    "forest-ruth",
    "pefrl",
    "yoshida6",
    "kahan-li8",
];

/// The pericentre's scales, read off the orbit's initial state (it starts
/// at pericentre).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Pericentre {
    /// Eccentricity.
    pub e: f64,
    /// `r_p = a (1 - e)`.
    pub radius: f64,
    /// `v_p = sqrt(GM (1 + e) / r_p)`.
    pub speed: f64,
    /// `tau_p = r_p / v_p`.
    pub time_scale: f64,
    /// `v_p / w`, the pericentre speed in the phase-space error's length
    /// units (`w = 2 pi / period`).
    pub speed_in_phase_units: f64,
}

impl Pericentre {
    /// The scales of `orbit`.
    pub fn of(orbit: &KeplerEccentric) -> Self {
        let s = orbit.initial();
        let (radius, speed) = (s.q.norm(), s.v.norm());
        Self {
            e: orbit.eccentricity(),
            radius,
            speed,
            time_scale: radius / speed,
            speed_in_phase_units: speed / orbit.frequency(),
        }
    }
}

/// What the order study concluded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum OrderStatus {
    /// A window was found and the claimed order lies in its interval.
    Pass,
    /// A window was found and the claimed order does not.
    Fail,
    /// Some rungs resolve the passage, but too few are asymptotic for a fit.
    PreAsymptotic,
    /// No rung resolves the passage: every error exceeds the ceiling.
    Unresolved,
}

impl OrderStatus {
    /// The kebab-case name.
    pub fn name(self) -> &'static str {
        match self {
            OrderStatus::Pass => "pass",
            OrderStatus::Fail => "fail",
            OrderStatus::PreAsymptotic => "pre-asymptotic",
            OrderStatus::Unresolved => "unresolved",
        }
    }
}

/// The order of one scheme on one eccentric orbit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EccentricOrderRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// The order it claims.
    pub theoretical_order: u32,
    /// The orbit's pericentre.
    pub pericentre: Pericentre,
    /// End time of every rung.
    pub t_end: f64,
    /// Largest rung allowed, in steps.
    pub max_rung_steps: u64,
    /// Why the ladder stopped.
    pub stopped: LadderEnd,
    /// The fitted order of the largest error over the trajectory.
    pub measured_order: Option<f64>,
    /// Its interval (see [`tolerance::order_interval`]).
    pub ci95: Option<[f64; 2]>,
    /// First and last rung fitted.
    pub window: Option<[usize; 2]>,
    /// The order fitted, the same way, to the error at `t_end` alone.
    pub final_order: Option<f64>,
    /// Its interval.
    pub final_ci95: Option<[f64; 2]>,
    /// The largest step from which every finer rung keeps its error below
    /// [`ERROR_CEILING`] of the orbit; `None` when the finest does not.
    pub resolved_below: Option<f64>,
    /// The conclusion.
    pub status: OrderStatus,
    /// Why, in one line, with the numbers.
    pub reason: String,
    /// Every rung, coarse to fine.
    pub rungs: Vec<Rung>,
    /// Steps taken over the whole ladder (each compared with the exact orbit).
    pub steps: u64,
}

/// Runs the order study of `scheme` on the orbit of eccentricity `e`: the
/// automatic ladder of the main study (from 1/8 period and its
/// [`crate::ladder::per_octave`] rungs a halving, down to the round-off
/// floor), with rungs capped at `max_rung_steps`, over
/// [`tolerance::ECCENTRIC_PERIODS`] periods.
pub fn eccentric_order<M: Scheme>(
    scheme: &M,
    e: f64,
    max_rung_steps: u64,
) -> Result<EccentricOrderRecord, Error> {
    let orbit = KeplerEccentric::new(e)?;
    let peri = Pericentre::of(&orbit);
    let meta = scheme.meta();
    let t_end = tolerance::ECCENTRIC_PERIODS * orbit.period();
    let scale = orbit.scale();
    let spec = OrderSpec {
        t_end: Some(t_end),
        ladder: LadderChoice::AutoWith(AutoLadder {
            per_octave: None,
            max_rung_evaluations: max_rung_steps * u64::from(meta.force_evaluations.max(1)),
        }),
    };
    let record = global_order(scheme, &orbit, &spec)?;
    let stopped = record.ladder_end;
    let refined = record.refined;
    let window = record.window;
    let rungs = record.rungs;
    // finer rungs left out of a window that did not end at the floor were
    // touched by round-off (see `select_window`)
    let left_out = match (window, stopped) {
        (Some([_, b]), LadderEnd::Cap) => rungs.len() - 1 - b,
        _ => 0,
    };
    let final_analysis = final_error_analysis(&rungs, scale);
    let ceiling = ERROR_CEILING * scale;
    let resolved = |r: &Rung| r.error.is_some_and(|x| x <= ceiling);
    let resolved_below = rungs
        .iter()
        .rev()
        .take_while(|r| resolved(r))
        .last()
        .map(|r| r.h);
    let measured_order = record.measured_order;
    let theoretical = meta.order as f64;
    let finest = rungs.last().map_or(f64::NAN, |r| r.h);
    let cap_note = ladder_end_note(stopped, refined, max_rung_steps, finest, &peri);
    let final_note = final_analysis.fit.map_or(String::new(), |f| {
        format!("; the error at t_end alone falls as h^{:.2}", f.order)
    });
    let (status, reason) = match (record.fit, record.ci95, window) {
        (Some(f), Some(ci), Some(w)) => windowed_status(
            theoretical,
            (f.order, ci),
            &rungs[w[0]..=w[1]],
            left_out,
            &peri,
            &cap_note,
            &final_note,
        ),
        _ if record.verdict == crate::study::verdict::Verdict::Fail => {
            (OrderStatus::Fail, format!("{}; {cap_note}", record.reason))
        }
        _ if resolved_below.is_none() => (
            OrderStatus::Unresolved,
            unresolved_reason(&rungs, &peri, finest),
        ),
        _ => {
            let h = resolved_below.unwrap_or(f64::NAN);
            (
                OrderStatus::PreAsymptotic,
                format!(
                    "{}: {cap_note}{final_note}",
                    pre_asymptotic_reason(&rungs, h, &peri)
                ),
            )
        }
    };
    let steps = rungs.iter().map(|r| r.steps).sum();
    Ok(EccentricOrderRecord {
        scheme: meta.id,
        theoretical_order: meta.order,
        pericentre: peri,
        t_end,
        max_rung_steps,
        stopped,
        measured_order,
        ci95: record.ci95,
        window,
        final_order: final_analysis.fit.map(|f| f.order),
        final_ci95: final_analysis.ci95,
        resolved_below,
        status,
        reason,
        rungs,
        steps,
    })
}

/// The ladder analysed on the error at `t_end` alone, as a second view
/// beside the largest error over the run.
fn final_error_analysis(rungs: &[Rung], scale: f64) -> Analysis {
    let finals: Vec<RungData> = rungs
        .iter()
        .map(|r| RungData {
            h: r.h,
            error: r.final_error,
            round_off: r.round_off_bound.unwrap_or(0.0),
        })
        .collect();
    analyse(&finals, scale)
}

/// The verdict over a window of rungs (`window`, coarse to fine): the
/// measured order and its interval against the claim.
fn windowed_status(
    theoretical: f64,
    (order, ci): (f64, [f64; 2]),
    window: &[Rung],
    left_out: usize,
    peri: &Pericentre,
    cap_note: &str,
    final_note: &str,
) -> (OrderStatus, String) {
    let in_tau = |h: f64| short_ratio(peri.time_scale / h);
    let left_note = match left_out {
        0 => String::new(),
        1 => " (the finest rung left out: round-off)".to_string(),
        k => format!(" (the finest {k} rungs left out: round-off)"),
    };
    let (first, last) = (window[0].h, window[window.len() - 1].h);
    let span = format!(
        "over h = {} .. {} (tau_p/{} .. tau_p/{}){left_note}",
        short(first),
        short(last),
        in_tau(first),
        in_tau(last)
    );
    match tolerance::order_verdict(theoretical, order, ci) {
        Ok(note) => (
            OrderStatus::Pass,
            format!(
                "order {order:.3} in [{:.3}, {:.3}] {span}{}; {cap_note}",
                ci[0],
                ci[1],
                note.map_or(String::new(), |n| format!(": {n}"))
            ),
        ),
        Err(why) => (
            OrderStatus::Fail,
            format!(
                "{why}, {span}; the error falls more slowly than claimed at these \
                 steps; {cap_note}{final_note}"
            ),
        ),
    }
}

/// Why the ladder stopped where it did, in units of the pericentre time.
fn ladder_end_note(
    stopped: LadderEnd,
    refined: bool,
    max_rung_steps: u64,
    finest: f64,
    peri: &Pericentre,
) -> String {
    match stopped {
        LadderEnd::Cap | LadderEnd::Fixed => format!(
            "the ladder stopped at the cap of {max_rung_steps} steps a rung (h = {} = tau_p/{})",
            short(finest),
            short_ratio(peri.time_scale / finest)
        ),
        LadderEnd::Floor if refined => "the ladder reached the round-off floor and was \
                                         refined between its resolved rungs"
            .to_string(),
        LadderEnd::Floor => "the ladder reached the round-off floor".to_string(),
        LadderEnd::Breakdown => format!(
            "the ladder stopped at a breakdown at h = {} = tau_p/{}",
            short(finest),
            short_ratio(peri.time_scale / finest)
        ),
    }
}

/// No rung resolved the orbit: say how far down the ladder went and how large
/// the error stayed on the rungs finer than the pericentre time.
fn unresolved_reason(rungs: &[Rung], peri: &Pericentre, finest: f64) -> String {
    let fine: Vec<f64> = rungs
        .iter()
        .filter(|r| r.h <= peri.time_scale)
        .filter_map(|r| r.error)
        .map(|x| x / peri.speed_in_phase_units)
        .collect();
    let saturation = if fine.is_empty() {
        String::new()
    } else {
        format!(
            "; on the {} rungs finer than tau_p it lies between {:.2} and {:.2} v_p/w",
            fine.len(),
            fine.iter().copied().fold(f64::INFINITY, f64::min),
            fine.iter().copied().fold(0.0, f64::max)
        )
    };
    format!(
        "unresolved: the largest error exceeds {ERROR_CEILING} of the orbit for every \
         step down to h = {} = tau_p/{} (tau_p = r_p/v_p = {}; the pericentre \
         speed is v_p/w = {:.3} in phase units){saturation}",
        short(finest),
        short_ratio(peri.time_scale / finest),
        short(peri.time_scale),
        peri.speed_in_phase_units
    )
}

/// Resolved below `h` but without a window of rungs on one order: list the
/// local orders there.
fn pre_asymptotic_reason(rungs: &[Rung], h: f64, peri: &Pericentre) -> String {
    let locals: Vec<String> = rungs
        .iter()
        .filter(|r| r.h <= h)
        .filter_map(|r| r.local_order)
        .map(|p| format!("{p:.2}"))
        .collect();
    format!(
        "resolved only below h = {} = tau_p/{}, and fewer than {MIN_WINDOW} rungs \
         there settle on one order (local orders {}); no verdict",
        short(h),
        short_ratio(peri.time_scale / h),
        if locals.is_empty() {
            "-".to_string()
        } else {
            locals.join(", ")
        }
    )
}

/// Where Euler-Cromer's first-order error overtakes the second-order one of
/// a pericentre passage.
///
/// Euler-Cromer's kick-then-drift step is leap-frog's, with its whole-step
/// velocities being leap-frog's half-step ones: they lag the synchronised
/// velocity by `h a(q) / 2 + O(h^2)`, most at pericentre, `h a_p / 2` with
/// `a_p = GM / r_p^2 = v_p^2 / ((1 + e) r_p)`: a first-order error of `L h`,
/// `L = a_p / (2 w)` in phase units. Its remaining error is that of the
/// second-order map, `C h^2` once the passage is resolved, with `C` read off
/// the finest rung of the fitted window. The first-order term can dominate
/// only below `h = L / C`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct KickLag {
    /// `L = a_p / (2 w)`.
    pub lag_coefficient: f64,
    /// `C = error / h^2` at the window's finest rung.
    pub second_order_coefficient: f64,
    /// `L / C`.
    pub crossover: f64,
    /// Steps a rung at that step would take over the run.
    pub crossover_steps: f64,
}

/// [`KickLag`] for an order record of Euler-Cromer whose window measured
/// (about) second order; `None` otherwise.
pub fn kick_lag(r: &EccentricOrderRecord) -> Option<KickLag> {
    let p = r.measured_order?;
    if r.scheme != "euler-cromer" || (p - 2.0).abs() > tolerance::ORDER_TOLERANCE {
        return None;
    }
    let [_, b] = r.window?;
    let finest = &r.rungs[b];
    let peri = &r.pericentre;
    let w = peri.speed / peri.speed_in_phase_units;
    let a_p = peri.speed * peri.speed / ((1.0 + peri.e) * peri.radius);
    let lag_coefficient = a_p / (2.0 * w);
    let second_order_coefficient = finest.error? / (finest.h * finest.h);
    let crossover = lag_coefficient / second_order_coefficient;
    Some(KickLag {
        lag_coefficient,
        second_order_coefficient,
        crossover,
        crossover_steps: r.t_end / crossover,
    })
}

/// Three significant digits.
fn short(x: f64) -> String {
    format!("{x:.2e}")
}

/// A ratio to three significant digits, without an exponent from 0.1 up.
pub fn short_ratio(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0}")
    } else if x >= 10.0 {
        format!("{x:.1}")
    } else if x >= 0.1 {
        format!("{x:.2}")
    } else {
        format!("{x:.2e}")
    }
}

/// How an eccentric orbit's energy behaved.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum OrbitEnergy {
    /// The energy at apocentre returns to the same value after every passage.
    Bounded,
    /// It changes from passage to passage.
    Drifting,
    /// The orbit became unbound (energy >= 0), blew up, or stopped returning
    /// to apocentre.
    Lost,
}

impl OrbitEnergy {
    /// The kebab-case name.
    pub fn name(self) -> &'static str {
        match self {
            OrbitEnergy::Bounded => "bounded",
            OrbitEnergy::Drifting => "drifting",
            OrbitEnergy::Lost => "lost",
        }
    }
}

/// The energy of one scheme on one eccentric orbit at one step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EccentricEnergyRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// The orbit's pericentre.
    pub pericentre: Pericentre,
    /// The step.
    pub h: f64,
    /// Steps taken.
    pub steps: u64,
    /// Periods asked for.
    pub periods: f64,
    /// How the run ended.
    pub outcome: Outcome,
    /// `max |E - E0| / |E0|` over the run.
    pub max_relative_error: f64,
    /// The same times `(1 - e) / 2`: relative to the pericentre's kinetic
    /// energy scale `GM / r_p` instead of `|E0| = GM / 2a`.
    pub max_pericentre_relative_error: f64,
    /// Numerical apocentre passages seen.
    pub apocentres: usize,
    /// `(E - E0) / |E0|` at the first apocentre.
    pub apocentre_offset: Option<f64>,
    /// The change of `E / |E0|` at apocentre per orbit, first to last.
    pub change_per_orbit: Option<f64>,
    /// When the orbit was lost (energy >= 0 or a blow-up).
    pub lost_at: Option<f64>,
    /// The behaviour.
    pub class: OrbitEnergy,
    /// Why, in one line.
    pub reason: String,
}

/// Runs `scheme` on the orbit of eccentricity `e` with step `h` for
/// `periods` periods and classifies its energy from the apocentre passages.
pub fn eccentric_energy<M: Scheme>(
    scheme: &M,
    e: f64,
    h: f64,
    periods: f64,
) -> Result<EccentricEnergyRecord, Error> {
    let orbit = KeplerEccentric::new(e)?;
    let peri = Pericentre::of(&orbit);
    let h = crate::scene::positive("h", h)?;
    let periods = crate::scene::positive("periods", periods)?;
    let steps = steps_for(periods * orbit.period(), h)?;
    crate::ladder::check_cost(steps)?;
    let start = orbit.initial();
    let e0 = orbit.energy(&start);
    let norm = e0.abs();
    let (mut worst, mut taken) = (0.0f64, 0u64);
    let mut apocentre: Vec<f64> = Vec::new();
    let mut unbound: Option<f64> = None;
    let mut outward = true; // leaves pericentre moving outwards
    let outcome = integrate(scheme, &orbit, &start, h, steps, |n, t, s: &State<2>| {
        let energy = orbit.energy(s);
        worst = worst.max((energy - e0).abs() / norm);
        taken = n;
        if unbound.is_none() && energy >= 0.0 {
            unbound = Some(t);
        }
        let radial = s.q.dot(&s.v);
        if outward && radial <= 0.0 && n > 0 {
            apocentre.push((energy - e0) / norm);
        }
        outward = radial > 0.0;
    });
    let lost_at = unbound.or(match outcome {
        Outcome::Completed => None,
        Outcome::Unstable { time, .. } | Outcome::Failed { time, .. } => Some(time),
    });
    let offset = apocentre.first().copied();
    let change = (apocentre.len() >= 2)
        .then(|| (apocentre[apocentre.len() - 1] - apocentre[0]) / (apocentre.len() - 1) as f64);
    let (class, reason) = classify(
        scheme.epsilon(),
        lost_at,
        unbound.is_some(),
        &apocentre,
        taken,
        periods,
    );
    Ok(EccentricEnergyRecord {
        scheme: scheme.meta().id,
        pericentre: peri,
        h,
        steps: taken,
        periods,
        outcome,
        max_relative_error: worst,
        max_pericentre_relative_error: worst * (1.0 - e) / 2.0,
        apocentres: apocentre.len(),
        apocentre_offset: offset,
        change_per_orbit: change,
        lost_at,
        class,
        reason,
    })
}

/// The orbit's energy class from the energy offsets at successive
/// apocentres: lost when it became unbound or blew up, drifting when the
/// apocentre energy moves by more than ECCENTRIC_DRIFT_FRACTION of its offset
/// plus round-off over the run, bounded otherwise.
fn classify(
    epsilon: f64,
    lost_at: Option<f64>,
    unbound: bool,
    apocentre: &[f64],
    taken: u64,
    periods: f64,
) -> (OrbitEnergy, String) {
    let offset = apocentre.first().copied();
    let change = (apocentre.len() >= 2)
        .then(|| (apocentre[apocentre.len() - 1] - apocentre[0]) / (apocentre.len() - 1) as f64);
    match (lost_at, offset, change) {
        (Some(t), _, _) => (
            OrbitEnergy::Lost,
            format!(
                "orbit lost at t = {t:.4} ({})",
                if unbound {
                    "energy reached zero: unbound"
                } else {
                    "the run blew up or a step failed"
                }
            ),
        ),
        (None, Some(offset), Some(change)) => {
            let total = (change * (apocentre.len() - 1) as f64).abs();
            let allowed =
                ECCENTRIC_DRIFT_FRACTION * offset.abs() + round_off_energy(taken, epsilon);
            if total > allowed {
                (
                    OrbitEnergy::Drifting,
                    format!(
                        "the apocentre energy changes by {change:.2e} of |E0| per orbit \
                     ({total:.2e} over {} orbits, against an offset of {offset:.2e})",
                        apocentre.len() - 1
                    ),
                )
            } else {
                (
                    OrbitEnergy::Bounded,
                    format!(
                        "the apocentre energy stays {offset:.2e} of |E0| from E0 within {total:.2e} \
                     over {} orbits",
                        apocentre.len() - 1
                    ),
                )
            }
        }
        _ => (
            OrbitEnergy::Lost,
            format!(
                "fewer than two apocentre passages in {periods} periods: the orbit no longer \
             returns"
            ),
        ),
    }
}

/// The round-off of the two-step Störmer form (and of leap-frog), measured
/// as its distance from velocity Verlet, the same map in exact arithmetic.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RoundOffRecord {
    /// The orbit's pericentre.
    pub pericentre: Pericentre,
    /// The step.
    pub h: f64,
    /// Steps taken.
    pub steps: u64,
    /// The orbit's size `scale` (phase-space norm of the initial state).
    pub scale: f64,
    /// Largest Störmer-to-Verlet phase-space distance before the first full
    /// pericentre passage (the first 3/4 period).
    pub stormer_before: f64,
    /// Largest over the whole run, through the passage.
    pub stormer_after: f64,
    /// The same for leap-frog.
    pub leapfrog_before: f64,
    /// The same for leap-frog.
    pub leapfrog_after: f64,
}

/// Runs the two-step Störmer form, leap-frog and velocity Verlet side by side
/// on the orbit of eccentricity `e` with step `h` for
/// [`tolerance::ECCENTRIC_PERIODS`] periods.
pub fn stormer_round_off(e: f64, h: f64) -> Result<RoundOffRecord, Error> {
    let orbit = KeplerEccentric::new(e)?;
    let h = crate::scene::positive("h", h)?;
    let period = orbit.period();
    let steps = steps_for(tolerance::ECCENTRIC_PERIODS * period, h)?;
    crate::ladder::check_cost(steps)?;
    let s0 = orbit.initial();
    let (mut sv, mut lf, mut vv) = (
        StormerVerlet.start(&orbit, &s0, h),
        Leapfrog.start(&orbit, &s0, h),
        VELOCITY_VERLET.start(&orbit, &s0, h),
    );
    let mut record = RoundOffRecord {
        pericentre: Pericentre::of(&orbit),
        h,
        steps,
        scale: orbit.scale(),
        stormer_before: 0.0,
        stormer_after: 0.0,
        leapfrog_before: 0.0,
        leapfrog_after: 0.0,
    };
    for n in 1..=steps {
        // explicit schemes: their steps cannot fail
        let ok = StormerVerlet.step(&orbit, &mut sv, h).is_ok()
            && Leapfrog.step(&orbit, &mut lf, h).is_ok()
            && VELOCITY_VERLET.step(&orbit, &mut vv, h).is_ok();
        let reference = VELOCITY_VERLET.state(&vv, h);
        let a = orbit.phase_distance(&StormerVerlet.state(&sv, h), &reference);
        let b = orbit.phase_distance(&Leapfrog.state(&lf, h), &reference);
        if !(ok && a.is_finite() && b.is_finite()) {
            record.steps = n;
            break;
        }
        if (n as f64) * h < 0.75 * period {
            record.stormer_before = record.stormer_before.max(a);
            record.leapfrog_before = record.leapfrog_before.max(b);
        }
        record.stormer_after = record.stormer_after.max(a);
        record.leapfrog_after = record.leapfrog_after.max(b);
    }
    Ok(record)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn pericentre_scales_match_the_closed_forms() {
        for e in ECCENTRICITIES {
            let p = Pericentre::of(&KeplerEccentric::new(e).unwrap());
            // tau_p = (1 - e)^(3/2) / ((1 + e)^(1/2) n), n = 2 pi per year
            let tau = (1.0 - e).powf(1.5) / ((1.0 + e).sqrt() * TAU);
            assert!((p.time_scale / tau - 1.0).abs() < 1e-14, "e = {e}");
            // v_p / n = a sqrt((1 + e) / (1 - e))
            let vw = ((1.0 + e) / (1.0 - e)).sqrt();
            assert!((p.speed_in_phase_units / vw - 1.0).abs() < 1e-14);
        }
    }
}
