//! The global order of accuracy, measured over a step-size ladder against the
//! scene's exact solution.
//!
//! Each rung runs the scheme to `t_end` and records the largest phase-space
//! error over every step of the trajectory (the global error) and the error
//! at `t_end`. The asymptotic window is chosen from the data alone (see
//! [`select_window`]), the order fitted over it (see [`super::fit`]), and the
//! verdict given by [`tolerance::order_verdict`].

use super::Verdict;
use super::fit::{OrderFit, order_fit};
use crate::error::Error;
use crate::ladder::{
    AUTO_START, AutoLadder, LadderChoice, LadderEnd, RungSize, auto_ratio, steps_for,
};
use crate::run::{Outcome, integrate};
use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::state::State;
use crate::tolerance::{
    self, ERROR_CEILING, FLOOR_FRACTION, FLOOR_MARGIN, MAX_SCATTERED, MIN_WINDOW, REFERENCE_RUNGS,
    ROUND_OFF_CEILING, WINDOW_RUNGS,
};
use serde::Serialize;

/// What to measure: the end time and the ladder.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OrderSpec {
    /// End time of every rung; `None` for the scene's default.
    pub t_end: Option<f64>,
    /// The step sizes.
    pub ladder: LadderChoice,
}

impl Default for OrderSpec {
    fn default() -> Self {
        Self {
            t_end: None,
            ladder: LadderChoice::Auto,
        }
    }
}

/// Why a rung is left out of the fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DropReason {
    /// The run blew up or a step failed.
    Unstable,
    /// The error is not small against the orbit ([`ERROR_CEILING`]).
    AboveCeiling,
    /// The local order has not yet settled (coarse end of the ladder).
    PreAsymptotic,
    /// The error no longer falls at the ladder's rate (fine end): round-off.
    RoundOff,
    /// Asymptotic, but coarser than the window, which uses the finest rungs.
    NotNeeded,
    /// The finest rung of a scene without an exact solution: the rung before
    /// it is measured against it, and nothing finer measures it.
    Reference,
}

impl DropReason {
    /// A short explanation for tables.
    pub fn explain(self) -> &'static str {
        match self {
            DropReason::Unstable => "unstable",
            DropReason::AboveCeiling => "error above 30% of the orbit",
            DropReason::PreAsymptotic => "pre-asymptotic",
            DropReason::RoundOff => "round-off floor",
            DropReason::NotNeeded => "coarser than the window",
            DropReason::Reference => "reference for the rung before",
        }
    }
}

/// One rung as measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Rung {
    /// The step used, `t_end / steps`.
    pub h: f64,
    /// Steps taken to `t_end`.
    pub steps: u64,
    /// Largest phase-space error over every step; `None` if the run blew up.
    pub error: Option<f64>,
    /// Phase-space error at `t_end`; `None` if the run blew up.
    pub final_error: Option<f64>,
    /// `ln(e_prev / e) / ln(h_prev / h)` against the previous rung.
    pub local_order: Option<f64>,
    /// The rung is in the fitted window.
    pub used: bool,
    /// Why it is not, when it was judged.
    pub dropped: Option<DropReason>,
    /// How the run ended.
    pub outcome: Outcome,
}

/// Everything the order study found: the record behind the CLI's `--json`,
/// the snapshots and the report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OrderRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// The scene's parameters.
    pub scene_parameters: String,
    /// The order the scheme claims.
    pub theoretical_order: u32,
    /// End time of every rung.
    pub t_end: f64,
    /// What each rung's error is measured against.
    pub reference: Reference,
    /// How the ladder was chosen.
    pub ladder: LadderChoice,
    /// How it ended.
    pub ladder_end: LadderEnd,
    /// The automatic ladder was refined once between its rungs above the
    /// round-off floor (see [`global_order`]).
    pub refined: bool,
    /// The fitted order, when a window was found.
    pub measured_order: Option<f64>,
    /// Its 95% interval, at least [`tolerance::ORDER_RESOLUTION`] either
    /// side (see [`tolerance::order_interval`]); the verdict uses it.
    pub ci95: Option<[f64; 2]>,
    /// The fit's details.
    pub fit: Option<OrderFit>,
    /// How far the limit of the local orders, extrapolated to `h = 0`, lies
    /// from the fitted order: a systematic the interval includes, which a
    /// window too narrow to show its own curvature cannot reveal.
    pub trend_systematic: Option<f64>,
    /// First and last rung of the window (indices into `rungs`).
    pub window: Option<[usize; 2]>,
    /// The verdict.
    pub verdict: Verdict,
    /// Why, in one line.
    pub reason: String,
    /// Every rung, coarse to fine.
    pub rungs: Vec<Rung>,
}

impl OrderRecord {
    /// True when the verdict is a pass.
    pub fn passed(&self) -> bool {
        self.verdict == Verdict::Pass
    }
}

/// Measures the global order of `scheme` on `scene`.
///
/// ```
/// use stepladder::measure::order::{global_order, OrderSpec};
/// use stepladder::scene::Harmonic;
/// use stepladder::scheme::{Scheme, VELOCITY_VERLET};
///
/// let record = global_order(&VELOCITY_VERLET, &Harmonic::default(), &OrderSpec::default()).unwrap();
/// assert!(record.passed(), "{}", record.reason);
/// assert!((record.measured_order.unwrap() - 2.0).abs() < 0.01);
/// ```
pub fn global_order<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    spec: &OrderSpec,
) -> Result<OrderRecord, Error> {
    let meta = scheme.meta();
    let scene_meta = scene.meta();
    let reference = if scene.exact(0.0).is_some() {
        Reference::Exact
    } else {
        Reference::SuccessiveRungs
    };
    let t_end = match spec.t_end {
        Some(t) => crate::scene::positive("t_end", t)?,
        None => scene.default_t_end(),
    };
    let scale = scene.scale();
    let mut rungs: Vec<Rung> = Vec::new();
    let mut samples: Vec<Option<Vec<State<D>>>> = Vec::new();
    let (mut end, mut refined) = (LadderEnd::Fixed, false);
    let mut push = |rungs: &mut Vec<Rung>, size: RungSize| {
        let (rung, sampled) = run_rung(scheme, scene, t_end, size, reference);
        rungs.push(rung);
        samples.push(sampled);
        if reference == Reference::SuccessiveRungs {
            compare_successive(scene, rungs, &samples);
        }
    };
    match spec.ladder {
        LadderChoice::Fixed(ladder) => {
            for size in ladder.rungs(t_end)? {
                let size = reference.align(size, t_end)?;
                if rungs.last().is_some_and(|r: &Rung| r.steps >= size.steps) {
                    return Err(Error::InvalidLadder(format!(
                        "without an exact solution every rung needs a multiple of {SAMPLES} steps, and two rungs round to {}: use a smaller ratio",
                        size.steps
                    )));
                }
                push(&mut rungs, size);
            }
        }
        LadderChoice::Auto | LadderChoice::AutoWith(_) => {
            let settings = match spec.ladder {
                LadderChoice::AutoWith(settings) => settings,
                _ => AutoLadder::default(),
            };
            let ratio = settings.ratio.unwrap_or_else(|| auto_ratio(meta.order));
            if !(ratio > 0.0 && ratio < 1.0) {
                return Err(Error::InvalidParameter {
                    name: "ratio",
                    value: ratio,
                    expected: "a number in (0, 1): each rung's step is ratio times the previous one (0.5 halves)",
                });
            }
            let h0 = AUTO_START * scene.period();
            end = LadderEnd::Cap;
            for k in 0.. {
                let steps = steps_for(t_end, h0 * ratio.powi(k))?;
                let size = reference.align(
                    RungSize {
                        h: t_end / steps as f64,
                        steps,
                    },
                    t_end,
                )?;
                if rungs.last().is_some_and(|r| r.steps >= size.steps) {
                    continue;
                }
                if size.steps > settings.max_rung_steps {
                    break;
                }
                push(&mut rungs, size);
                let choice = select_window(&errors(&rungs, reference), scale);
                let settled = choice.window_len() >= WINDOW_RUNGS
                    && choice.spread
                        <= tolerance::settled_tolerance(choice.median_local_order.unwrap_or(1.0));
                if settled || choice.at_floor >= 2 {
                    end = if settled {
                        LadderEnd::Settled
                    } else {
                        LadderEnd::Floor
                    };
                    break;
                }
            }
            // A scheme of higher order than it claims can fall from the
            // ceiling to the floor within fewer rungs than a window needs:
            // where the ladder ended there without a window, it is refined
            // once between the rungs in between, at the ratio the measured
            // local order calls for (`2^(-2/p)`, as the ladder's own ratio
            // follows the claimed order).
            if end == LadderEnd::Floor
                && reference == Reference::Exact
                && select_window(&errors(&rungs, reference), scale)
                    .window
                    .is_none()
            {
                let floor = rungs
                    .iter()
                    .filter_map(|r| r.error)
                    .fold(f64::INFINITY, f64::min);
                let between = |r: &Rung| {
                    r.error
                        .is_some_and(|e| e <= ERROR_CEILING * scale && e > FLOOR_MARGIN * floor)
                };
                let pairs: Vec<(&Rung, &Rung)> = rungs
                    .windows(2)
                    .filter(|w| between(&w[0]) && between(&w[1]))
                    .map(|w| (&w[0], &w[1]))
                    .collect();
                let local_order = pairs
                    .iter()
                    .filter_map(|(a, b)| local_order((a.h, a.error), (b.h, b.error)))
                    .fold(2.0, f64::max);
                let per_rung = (2.0 / local_order) * std::f64::consts::LN_2;
                let middles: Vec<RungSize> = pairs
                    .iter()
                    .flat_map(|(a, b)| {
                        let parts = ((a.h / b.h).ln() / per_rung).ceil().max(2.0) as u32;
                        (1..parts).filter_map(move |k| {
                            let h = a.h * (b.h / a.h).powf(k as f64 / parts as f64);
                            let steps = steps_for(t_end, h).ok()?;
                            (steps > a.steps && steps < b.steps).then_some(RungSize {
                                h: t_end / steps as f64,
                                steps,
                            })
                        })
                    })
                    .collect();
                refined = !middles.is_empty();
                for size in middles {
                    push(&mut rungs, size);
                }
                rungs.sort_by_key(|r| r.steps);
            }
        }
    }
    fill_local_orders(&mut rungs);
    let analysis = analyse(&errors(&rungs, reference), scale);
    for (rung, reason) in rungs.iter_mut().zip(&analysis.choice.dropped) {
        rung.dropped = *reason;
    }
    if reference == Reference::SuccessiveRungs
        && let Some(finest) = rungs.last_mut()
    {
        finest.dropped = Some(DropReason::Reference);
    }
    let (fit, trend, ci95) = (analysis.fit, analysis.trend_systematic, analysis.ci95);
    let window = fit.and(analysis.choice.window).map(|(a, b)| [a, b]);
    if let Some([a, b]) = window {
        rungs[a..=b].iter_mut().for_each(|r| r.used = true);
    }
    let theoretical = meta.order as f64;
    let (verdict, reason) = match (&fit, ci95, window) {
        (Some(f), Some(ci), Some([a, b])) => {
            match tolerance::order_verdict(theoretical, f.order, ci) {
                Ok(()) => (
                    Verdict::Pass,
                    format!(
                        "order {:.3} in [{:.3}, {:.3}] over rungs {a}..{b}",
                        f.order, ci[0], ci[1]
                    ),
                ),
                Err(why) => (Verdict::Fail, why),
            }
        }
        _ => (
            Verdict::Fail,
            format!(
                "no asymptotic window of {MIN_WINDOW} rungs among {} (see the rungs' drop reasons)",
                rungs.len()
            ),
        ),
    };
    Ok(OrderRecord {
        scheme: meta.id,
        scene: scene_meta.id,
        scene_parameters: scene_meta.parameters,
        theoretical_order: meta.order,
        t_end,
        reference,
        ladder: spec.ladder,
        ladder_end: end,
        refined,
        measured_order: fit.map(|f| f.order),
        ci95,
        fit,
        trend_systematic: trend,
        window,
        verdict,
        reason,
        rungs,
    })
}

/// What a rung's error is measured against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reference {
    /// The scene's exact solution, at every step.
    Exact,
    /// The next finer rung, at [`SAMPLES`] equally spaced times: for a scene
    /// without an exact solution. The difference of successive rungs falls
    /// like `C h^p (1 - r^p)` for a ladder of ratio `r`, so it has the order
    /// of the error itself (Richardson's argument).
    SuccessiveRungs,
}

/// Times at which successive rungs are compared when there is no exact
/// solution: `t_end j / SAMPLES`, on the step grid of every rung because
/// every rung then takes a multiple of this many steps.
pub const SAMPLES: u64 = 64;

impl Reference {
    /// `size` with its step count rounded up to a multiple of [`SAMPLES`]
    /// when rungs are compared with each other.
    fn align(self, size: RungSize, t_end: f64) -> Result<RungSize, Error> {
        match self {
            Reference::Exact => Ok(size),
            Reference::SuccessiveRungs => {
                let steps = size.steps.div_ceil(SAMPLES) * SAMPLES;
                crate::ladder::check_cost(steps)?;
                Ok(RungSize {
                    h: t_end / steps as f64,
                    steps,
                })
            }
        }
    }
}

/// Runs one rung: against the exact solution, its global and final errors;
/// without one, its states at the [`SAMPLES`] comparison times.
pub fn run_rung<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    t_end: f64,
    size: RungSize,
    reference: Reference,
) -> (Rung, Option<Vec<State<D>>>) {
    let (mut worst, mut last) = (0.0f64, 0.0);
    let mut sampled: Vec<State<D>> = Vec::new();
    let every = size.steps / SAMPLES;
    let outcome = integrate(
        scheme,
        scene,
        &scene.initial(),
        size.h,
        size.steps,
        |n, t, s| match reference {
            Reference::Exact => {
                // the last step's time is t_end itself, not n h rounded
                let t = if n == size.steps { t_end } else { t };
                let exact = scene.exact(t).expect("the reference is the exact solution");
                last = scene.phase_distance(s, &exact);
                worst = worst.max(last);
            }
            Reference::SuccessiveRungs => {
                if n % every == 0 {
                    sampled.push(*s);
                }
            }
        },
    );
    let done = outcome.completed();
    let exact = reference == Reference::Exact;
    let rung = Rung {
        h: size.h,
        steps: size.steps,
        error: (done && exact).then_some(worst),
        final_error: (done && exact).then_some(last),
        local_order: None,
        used: false,
        dropped: None,
        outcome,
    };
    (rung, (done && !exact).then_some(sampled))
}

/// Without an exact solution, the rung before the newest one is measured
/// against it: the largest and the final distance over the sample times.
fn compare_successive<S: Scene<D>, const D: usize>(
    scene: &S,
    rungs: &mut [Rung],
    samples: &[Option<Vec<State<D>>>],
) {
    let k = rungs.len();
    if k < 2 {
        return;
    }
    if let (Some(coarse), Some(fine)) = (&samples[k - 2], &samples[k - 1]) {
        let distances: Vec<f64> = coarse
            .iter()
            .zip(fine)
            .map(|(a, b)| scene.phase_distance(a, b))
            .collect();
        rungs[k - 2].error = Some(distances.iter().copied().fold(0.0, f64::max));
        rungs[k - 2].final_error = distances.last().copied();
    }
}

/// The `(h, error)` data of the measured rungs (all but the finest when
/// rungs are compared with each other).
fn errors(rungs: &[Rung], reference: Reference) -> Vec<(f64, Option<f64>)> {
    let measured = match reference {
        Reference::Exact => rungs,
        Reference::SuccessiveRungs => &rungs[..rungs.len().saturating_sub(1)],
    };
    measured.iter().map(|r| (r.h, r.error)).collect()
}

fn fill_local_orders(rungs: &mut [Rung]) {
    for k in 1..rungs.len() {
        rungs[k].local_order = local_order(
            (rungs[k - 1].h, rungs[k - 1].error),
            (rungs[k].h, rungs[k].error),
        );
    }
}

/// A ladder's data analysed: the window, the fit over it, the trend of the
/// local orders, and the interval a verdict uses.
#[derive(Clone, Debug, PartialEq)]
pub struct Analysis {
    /// The window and why other rungs are out.
    pub choice: WindowChoice,
    /// The fit over the window.
    pub fit: Option<OrderFit>,
    /// See [`OrderRecord::trend_systematic`].
    pub trend_systematic: Option<f64>,
    /// The fit's interval widened by the trend and by
    /// [`tolerance::ORDER_RESOLUTION`].
    pub ci95: Option<[f64; 2]>,
}

/// Chooses the window of `(h, error)` data (coarse to fine, `None` for a rung
/// that blew up), fits the order over it and forms its interval.
pub fn analyse(data: &[(f64, Option<f64>)], scale: f64) -> Analysis {
    let choice = select_window(data, scale);
    let fit = choice.window.and_then(|(a, b)| {
        let pts: Vec<(f64, f64)> = data[a..=b]
            .iter()
            .map(|&(h, e)| (h, e.unwrap_or(f64::NAN)))
            .collect();
        order_fit(&pts)
    });
    let trend_systematic = choice
        .window
        .zip(choice.median_local_order)
        .zip(fit)
        .and_then(|(((_, b), median), f)| {
            let locals: Vec<(f64, Option<f64>)> = (0..=b)
                .map(|i| {
                    (
                        data[i].0,
                        (i > 0).then(|| local_order(data[i - 1], data[i])).flatten(),
                    )
                })
                .collect();
            local_order_trend(&locals, median).map(|limit| (limit - f.order).abs())
        });
    let ci95 = fit.map(|f| {
        let t = trend_systematic.unwrap_or(0.0);
        tolerance::order_interval(f.order, [f.ci95[0] - t, f.ci95[1] + t])
    });
    Analysis {
        choice,
        fit,
        trend_systematic,
        ci95,
    }
}

/// The limit at `h = 0` of the local orders approaching the window's end:
/// `l = p + c h` fitted over the finest run of rungs (ending at the last of
/// `rungs`) whose local orders all lie within
/// [`tolerance::pre_asymptotic_tolerance`] of `median`; `None` with fewer
/// than four.
fn local_order_trend(locals: &[(f64, Option<f64>)], median: f64) -> Option<f64> {
    let near = tolerance::pre_asymptotic_tolerance(median);
    let points: Vec<(f64, f64)> = locals
        .iter()
        .rev()
        .map_while(|&(h, l)| l.filter(|l| (l - median).abs() <= near).map(|l| (h, l)))
        .collect();
    if points.len() < 4 {
        return None;
    }
    let n = points.len() as f64;
    let (mh, ml) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = points.iter().map(|p| (p.0 - mh).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mh) * (p.1 - ml)).sum();
    (sxx > 0.0).then(|| ml - sxy / sxx * mh)
}

/// The local order between two rungs, `ln(e1/e2) / ln(h1/h2)`.
pub fn local_order(coarse: (f64, Option<f64>), fine: (f64, Option<f64>)) -> Option<f64> {
    let (e1, e2) = (coarse.1?, fine.1?);
    let p = (e1 / e2).ln() / (coarse.0 / fine.0).ln();
    p.is_finite().then_some(p)
}

/// The asymptotic window chosen from a ladder's data.
#[derive(Clone, Debug, PartialEq)]
pub struct WindowChoice {
    /// Per rung: why it is left out, if it is.
    pub dropped: Vec<Option<DropReason>>,
    /// First and last rung of the window, if one of [`MIN_WINDOW`] rungs exists.
    pub window: Option<(usize, usize)>,
    /// The median local order the window was judged against.
    pub median_local_order: Option<f64>,
    /// How many rungs at the fine end sit on the round-off floor.
    pub at_floor: usize,
    /// Largest minus smallest local order inside the window.
    pub spread: f64,
}

impl WindowChoice {
    /// Rungs in the window (0 without one).
    pub fn window_len(&self) -> usize {
        self.window.map_or(0, |(a, b)| b - a + 1)
    }
}

/// Chooses the asymptotic window from `(h, error)` data ordered coarse to
/// fine (`None` for a rung that blew up), using the data alone, never the
/// order the scheme claims:
///
/// 1. rungs that blew up, or whose error exceeds [`ERROR_CEILING`] times the
///    scene's `scale`, are out; the longest run of consecutive remaining rungs
///    is kept;
/// 2. if the error stops falling (or the local order collapses below
///    [`FLOOR_FRACTION`] of the median), the ladder has reached the round-off
///    floor: rungs past it, and rungs within [`tolerance::floor_margin`] of the floor's
///    error, are out;
/// 3. the reference order is the median local order of the
///    [`REFERENCE_RUNGS`] finest rungs left (the most asymptotic); the
///    window is the longest run of finest rungs, at most [`WINDOW_RUNGS`],
///    whose local orders all lie within [`tolerance::plateau_tolerance`] of it.
pub fn select_window(data: &[(f64, Option<f64>)], scale: f64) -> WindowChoice {
    let mut dropped: Vec<Option<DropReason>> = data
        .iter()
        .map(|&(_, e)| match e {
            Some(e) if e.is_nan() || e.is_infinite() => Some(DropReason::Unstable),
            Some(e) if e > ERROR_CEILING * scale => Some(DropReason::AboveCeiling),
            Some(e) if e > 0.0 => None,
            Some(_) => Some(DropReason::RoundOff), // exactly zero: nothing left to resolve
            None => Some(DropReason::Unstable),
        })
        .collect();
    let none = |dropped| WindowChoice {
        dropped,
        window: None,
        median_local_order: None,
        at_floor: 0,
        spread: f64::NAN,
    };
    // the longest run of candidates; ties go to the finer run
    let Some((mut a, mut b)) = longest_run(&dropped) else {
        return none(dropped);
    };
    for (i, d) in dropped.iter_mut().enumerate() {
        if d.is_none() && (i < a || i > b) {
            *d = Some(if i < a {
                DropReason::PreAsymptotic
            } else {
                DropReason::RoundOff
            });
        }
    }
    let local = |i: usize| {
        local_order((data[i - 1].0, data[i - 1].1), (data[i].0, data[i].1)).unwrap_or(f64::NAN)
    };
    let error = |i: usize| data[i].1.unwrap_or(f64::NAN);
    let round_off_level = ROUND_OFF_CEILING * scale;
    // 0. A stall: a rung coarser than the smallest error whose local order
    //    collapses while its error is far above any round-off. That is no
    //    floor but a pre-asymptotic accident (a coarse step whose mistimed
    //    pericentre passage lands close to the exact one); the search starts
    //    after the last one.
    let smallest = (a..=b)
        .min_by(|&i, &j| error(i).total_cmp(&error(j)))
        .unwrap_or(b);
    let typical = median_of((a + 1..=smallest).map(local).filter(|p| *p > 0.0).collect());
    if typical.is_finite()
        && let Some(stall) = (a + 1..=smallest).rev().find(|&i| {
            (local(i).is_nan() || local(i) < FLOOR_FRACTION * typical) && error(i) > round_off_level
        })
    {
        for d in &mut dropped[a..stall] {
            *d = Some(DropReason::PreAsymptotic);
        }
        a = stall;
    }
    // 1. The round-off floor, where errors are small enough to be round-off:
    //    where the error stops falling (its minimum is not the finest rung),
    //    every finer rung is on the floor; so is every rung from a collapse
    //    of the local order on; and so is every rung whose error is within
    //    the floor margin (FLOOR_MARGIN, more at high order) of the floor's.
    let lowest = (a..=b)
        .min_by(|&i, &j| error(i).total_cmp(&error(j)))
        .unwrap_or(b);
    let median_all = median_of((a + 1..=lowest).map(local).collect());
    if lowest == a || median_all.is_nan() || median_all <= 0.0 {
        for d in &mut dropped[a..=b] {
            *d = Some(DropReason::PreAsymptotic);
        }
        return none(dropped);
    }
    let collapse =
        (a + 1..=lowest).find(|&i| local(i).is_nan() || local(i) < FLOOR_FRACTION * median_all);
    let mut at_floor = 0;
    if (lowest < b || collapse.is_some()) && error(lowest) <= round_off_level {
        let floor = error(lowest);
        let mut last = collapse.map_or(lowest, |c| c - 1);
        while last > a && error(last) < tolerance::floor_margin(median_all) * floor {
            last -= 1;
        }
        at_floor = b - last;
        for d in &mut dropped[last + 1..=b] {
            *d = Some(DropReason::RoundOff);
        }
        b = last;
    }
    // 2. The window: the finest rungs (at most WINDOW_RUNGS) whose local
    //    orders all stay near the reference, the median local order of the
    //    finest REFERENCE_RUNGS (the most asymptotic). Where the finest one or
    //    two rungs scatter (round-off magnified by a sharp feature of the
    //    flow jitters the largest error by a few percent) and break a window
    //    the coarser rungs form, they are left out as touched by round-off.
    //    Coarser rungs that stray are pre-asymptotic; coarser ones that do
    //    not are simply not needed.
    let mut best: Option<(usize, usize, f64)> = None;
    for skip in 0..=MAX_SCATTERED {
        let Some(end) = b.checked_sub(skip).filter(|&e| e > a) else {
            break;
        };
        let median = median_of(
            (a + 1..=end)
                .rev()
                .take(REFERENCE_RUNGS)
                .map(local)
                .collect(),
        );
        if median.is_nan() || median <= 0.0 {
            continue;
        }
        let tolerance = tolerance::plateau_tolerance(median);
        let mut first = end;
        while first > a
            && end - first + 1 < WINDOW_RUNGS
            && (local(first) - median).abs() <= tolerance
        {
            first -= 1;
        }
        if skip == 0 || end + 1 - first >= MIN_WINDOW {
            best = Some((first, end, median));
        }
        if end + 1 - first >= MIN_WINDOW {
            break;
        }
    }
    let Some((first, end, median)) = best else {
        for d in &mut dropped[a..=b] {
            *d = Some(DropReason::PreAsymptotic);
        }
        return WindowChoice {
            at_floor,
            ..none(dropped)
        };
    };
    for d in &mut dropped[end + 1..=b] {
        *d = Some(DropReason::RoundOff);
    }
    let b = end;
    let tolerance = tolerance::plateau_tolerance(median);
    for (i, d) in dropped.iter_mut().enumerate().take(first).skip(a) {
        let strays = (local(i + 1) - median).abs() > tolerance;
        *d = Some(if strays {
            DropReason::PreAsymptotic
        } else {
            DropReason::NotNeeded
        });
    }
    let window = (b + 1 - first >= MIN_WINDOW).then_some((first, b));
    let inside: Vec<f64> = (first + 1..=b).map(local).collect();
    let spread = inside.iter().copied().fold(f64::MIN, f64::max)
        - inside.iter().copied().fold(f64::MAX, f64::min);
    WindowChoice {
        dropped,
        window,
        median_local_order: Some(median),
        at_floor,
        spread,
    }
}

fn longest_run(dropped: &[Option<DropReason>]) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    let mut start = None;
    for i in 0..=dropped.len() {
        let candidate = dropped.get(i).is_some_and(|d| d.is_none());
        match (candidate, start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                if best.is_none_or(|(a, b)| i - s >= b + 1 - a) {
                    best = Some((s, i - 1));
                }
                start = None;
            }
            _ => {}
        }
    }
    best
}

fn median_of(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ladder(e: impl Fn(f64) -> Option<f64>, n: i32) -> Vec<(f64, Option<f64>)> {
        (0..n)
            .map(|k| 0.5 / 2f64.powi(k))
            .map(|h| (h, e(h)))
            .collect()
    }

    #[test]
    fn window_excludes_blow_ups_coarse_errors_and_the_floor() {
        // second order, blows up at the coarsest rung, error above the
        // ceiling at the next, and a round-off floor of 1e-9 growing as 1/h
        let data = ladder(
            |h| {
                if h > 0.4 {
                    None
                } else {
                    Some(2.0 * h * h + 1e-13 / h)
                }
            },
            20,
        );
        // scale 0.3: the ceiling is 0.09, above rung 1's error of 0.125
        let w = select_window(&data, 0.3);
        assert_eq!(w.dropped[0], Some(DropReason::Unstable));
        assert_eq!(w.dropped[1], Some(DropReason::AboveCeiling));
        // the smallest error, 5.1e-9, is at h = (1e-13/4)^(1/3) = 2.9e-5; rungs
        // within a factor 100 of it (2 h^2 < 5.1e-7, h < 5.1e-4) are out,
        // so the last rung kept is 9 (h = 9.8e-4) and the window its finest 8
        assert_eq!(w.window, Some((2, 9)), "{w:?}");
        let b = 9;
        assert!(
            w.dropped[b + 1..]
                .iter()
                .all(|d| *d == Some(DropReason::RoundOff))
        );
        assert!(w.at_floor >= 2);
    }

    #[test]
    fn no_window_when_the_error_does_not_converge() {
        let w = select_window(&ladder(|_| Some(0.01), 10), 1.0);
        assert!(w.window.is_none());
    }

    #[test]
    fn local_order_of_a_power_law() {
        let p = local_order((0.1, Some(3e-4)), (0.05, Some(3e-4 / 8.0))).unwrap();
        assert!((p - 3.0).abs() < 1e-12);
        assert!(local_order((0.1, None), (0.05, Some(1.0))).is_none());
    }
}
