//! The asymptotic window of a ladder: the round-off each rung carries, the
//! local orders between rungs, and the run of clean rungs on one order over
//! which the order is fitted.

use crate::maths::fit::{OrderFit, order_fit_with_round_off};
use crate::tolerance::{
    self, ERROR_CEILING, MIN_WINDOW, MIN_WINDOW_HALVINGS, REFERENCE_RUNGS, WINDOW_RUNGS,
};
use serde::Serialize;

/// The accumulated round-off of a rung against its step count `N`, fitted
/// to the twins' samples: `ln r = ln c + g ln N` by least squares, with the
/// upper 95% prediction bound used as the bound. Round-off grows with the
/// steps taken (a random walk `N^(1/2)` of unbiased roundings, up to `N^(3/2)`
/// where a velocity error feeds a drift of the phase, as for the two-step
/// Störmer form), and one sample scatters by a factor of about two about its
/// mean, which the prediction bound absorbs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RoundOffModel {
    /// `c`.
    pub coefficient: f64,
    /// `g`, at least 0 (round-off does not shrink with more steps).
    pub exponent: f64,
    /// Residual standard deviation of `ln r`.
    pub log_scatter: f64,
    /// Samples fitted.
    pub samples: usize,
    /// Mean `ln N` of the samples.
    mean_ln_steps: f64,
    /// `sum (ln N - mean)^2`.
    spread: f64,
    /// Student's t quantile at 0.975 for `samples - 2` degrees of freedom.
    t_quantile: f64,
}

impl RoundOffModel {
    /// Fits the law to `(N, sample)` pairs (non-finite samples, which come
    /// from a twin that blew up, and zeros are left out). With fewer than
    /// three usable samples the largest is extended by the steepest law,
    /// `N^(3/2)`.
    pub fn fit(samples: &[(u64, f64)]) -> Option<Self> {
        let points: Vec<(f64, f64)> = samples
            .iter()
            .filter(|(_, r)| r.is_finite() && *r > 0.0)
            .map(|&(n, r)| ((n as f64).ln(), r.ln()))
            .collect();
        let n = points.len();
        if n == 0 {
            return None;
        }
        if n < 3 {
            let &(x, y) = points
                .iter()
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .expect("non-empty");
            return Some(Self {
                coefficient: (y - 1.5 * x).exp(),
                exponent: 1.5,
                log_scatter: 0.0,
                samples: n,
                mean_ln_steps: x,
                spread: 0.0,
                t_quantile: 0.0,
            });
        }
        let nf = n as f64;
        let mx = points.iter().map(|p| p.0).sum::<f64>() / nf;
        let my = points.iter().map(|p| p.1).sum::<f64>() / nf;
        let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
        let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let exponent = if sxx > 0.0 { (sxy / sxx).max(0.0) } else { 0.0 };
        let intercept = my - exponent * mx;
        let residual: f64 = points
            .iter()
            .map(|p| (p.1 - intercept - exponent * p.0).powi(2))
            .sum();
        Some(Self {
            coefficient: intercept.exp(),
            exponent,
            log_scatter: (residual / (nf - 2.0)).sqrt(),
            samples: n,
            mean_ln_steps: mx,
            spread: sxx,
            t_quantile: crate::maths::fit::t975(n - 2),
        })
    }

    /// The fitted law at `steps`.
    pub fn mean(&self, steps: u64) -> f64 {
        self.coefficient * (steps as f64).powf(self.exponent)
    }

    /// The upper 95% prediction bound at `steps`.
    pub fn bound(&self, steps: u64) -> f64 {
        let x = (steps as f64).ln();
        let leverage = if self.spread > 0.0 {
            1.0 / self.samples as f64 + (x - self.mean_ln_steps).powi(2) / self.spread
        } else {
            0.0
        };
        self.mean(steps) * (self.t_quantile * self.log_scatter * (1.0 + leverage).sqrt()).exp()
    }
}

/// One rung's data as the window selection reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RungData {
    /// The step.
    pub h: f64,
    /// The error; `None` for a run that blew up.
    pub error: Option<f64>,
    /// A bound on the round-off in that error.
    pub round_off: f64,
}

/// A ladder's data analysed: the window, the fit over it, the trend of the
/// local orders, and the interval a verdict uses.
#[derive(Clone, Debug, PartialEq)]
pub struct Analysis {
    /// The window and why other rungs are out.
    pub choice: WindowChoice,
    /// The fit over the window.
    pub fit: Option<OrderFit>,
    /// See [`crate::study::OrderRecord::trend_systematic`].
    pub trend_systematic: Option<f64>,
    /// The fit's interval widened by the trend and by
    /// [`tolerance::ORDER_RESOLUTION`].
    pub ci95: Option<[f64; 2]>,
}

/// Chooses the window of the data (coarse to fine), fits the order over it
/// and forms its interval.
pub fn analyse(data: &[RungData], scale: f64) -> Analysis {
    let choice = select_window(data, scale);
    let fit = choice.window.and_then(|(a, b)| {
        let pts: Vec<(f64, f64)> = data[a..=b]
            .iter()
            .map(|d| (d.h, d.error.unwrap_or(f64::NAN)))
            .collect();
        let round_off: Vec<f64> = data[a..=b]
            .iter()
            .map(|d| d.error.map_or(0.0, |e| d.round_off / e))
            .collect();
        order_fit_with_round_off(&pts, &round_off)
    });
    let trend_systematic = choice
        .window
        .zip(choice.median_local_order)
        .zip(fit)
        .and_then(|(((a, b), median), f)| {
            let locals: Vec<(f64, Option<f64>)> = (a..=b)
                .map(|i| {
                    (
                        data[i].h,
                        (i > a).then(|| local_order_of(data, i)).flatten(),
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

/// The limit at `h = 0` of the local orders in the window: `l = p + c h`
/// fitted over them; `None` with fewer than four.
fn local_order_trend(locals: &[(f64, Option<f64>)], median: f64) -> Option<f64> {
    let near = tolerance::plateau_tolerance(median);
    let points: Vec<(f64, f64)> = locals
        .iter()
        .filter_map(|&(h, l)| l.filter(|l| (l - median).abs() <= near).map(|l| (h, l)))
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

fn local_order_of(data: &[RungData], i: usize) -> Option<f64> {
    local_order(
        (data[i - 1].h, data[i - 1].error),
        (data[i].h, data[i].error),
    )
}

/// The asymptotic window chosen from a ladder's data.
#[derive(Clone, Debug, PartialEq)]
pub struct WindowChoice {
    /// Per rung: why it is left out, if it is.
    pub dropped: Vec<Option<DropReason>>,
    /// The clean rungs the window is sought among: the longest run of
    /// consecutive rungs that are stable, below the ceiling and above the
    /// round-off floor (ties go to the finer run).
    pub clean: Option<(usize, usize)>,
    /// First and last rung of the window, if one of [`MIN_WINDOW`] rungs exists.
    pub window: Option<(usize, usize)>,
    /// The median local order of the finest [`REFERENCE_RUNGS`] clean rungs,
    /// which the window was judged against.
    pub median_local_order: Option<f64>,
}

impl WindowChoice {
    /// Rungs in the window (0 without one).
    pub fn window_len(&self) -> usize {
        self.window.map_or(0, |(a, b)| b - a + 1)
    }
}

/// The highest power of `h` whose settling lets a window reach back past
/// its plateau (see [`select_window`]).
pub const MAX_SETTLING_POWER: i32 = 4;

/// Chooses the asymptotic window from the data (coarse to fine), from the
/// data alone, never from the order the scheme claims:
///
/// 1. a rung that blew up is out; so is one whose round-off bound exceeds
///    [`tolerance::clean_fraction`] of its error (the floor), and one whose
///    error exceeds [`ERROR_CEILING`] times the scene's `scale`;
/// 2. of the longest run of consecutive remaining rungs, the window is the
///    finest ones (at most [`WINDOW_RUNGS`], unless more are needed to span
///    [`MIN_WINDOW_HALVINGS`]) whose local orders all lie within
///    [`tolerance::plateau_tolerance`] of the median of the finest
///    [`REFERENCE_RUNGS`]: the asymptotic regime at the finest steps the
///    ladder resolved. It needs [`MIN_WINDOW`] rungs over
///    [`MIN_WINDOW_HALVINGS`] halvings. Coarser rungs that stray are
///    pre-asymptotic.
pub fn select_window(data: &[RungData], scale: f64) -> WindowChoice {
    // each rung against its coarser neighbour (the coarsest against its finer)
    let pair = |i: usize| {
        let (a, b) = if i > 0 { (i - 1, i) } else { (0, 1) };
        match data.get(b) {
            Some(d) => {
                let ratio = (data[a].h / d.h).ln();
                let local = local_order_of(data, b)
                    .filter(|l| l.is_finite())
                    .unwrap_or(1.0);
                (ratio, local)
            }
            None => (std::f64::consts::LN_2, 1.0),
        }
    };
    let mut dropped: Vec<Option<DropReason>> = data
        .iter()
        .enumerate()
        .map(|(i, d)| match d.error {
            Some(e) if !e.is_finite() => Some(DropReason::Unstable),
            None => Some(DropReason::Unstable),
            Some(e)
                if e == 0.0 || {
                    let (ratio, local) = pair(i);
                    d.round_off >= tolerance::clean_fraction(ratio, local) * e
                } =>
            {
                Some(DropReason::RoundOff)
            }
            Some(e) if e > ERROR_CEILING * scale => Some(DropReason::AboveCeiling),
            Some(_) => None,
        })
        .collect();
    let none = |dropped, clean| WindowChoice {
        dropped,
        clean,
        window: None,
        median_local_order: None,
    };
    let Some((a, b)) = longest_run(&dropped) else {
        return none(dropped, None);
    };
    for (i, d) in dropped.iter_mut().enumerate() {
        if d.is_none() && (i < a || i > b) {
            // clean rungs cut off from the run by an unstable or saturated one
            *d = Some(if i < a {
                DropReason::PreAsymptotic
            } else {
                DropReason::NotNeeded
            });
        }
    }
    let local = |i: usize| local_order_of(data, i).unwrap_or(f64::NAN);
    if b == a {
        dropped[a] = Some(DropReason::PreAsymptotic);
        return none(dropped, Some((a, b)));
    }
    let median = median_of((a + 1..=b).rev().take(REFERENCE_RUNGS).map(local).collect());
    let tolerance = tolerance::plateau_tolerance(median);
    let halvings = |first: usize| (data[first].h / data[b].h).log2();
    let mut first = b;
    while first > a
        && (b - first + 1 < WINDOW_RUNGS || halvings(first) < MIN_WINDOW_HALVINGS)
        && (local(first) - median).abs() <= tolerance
    {
        first -= 1;
    }
    // Too short to decide, the window may still reach back along a settling
    // next term. A term `b h^q` of the error expansion moves the local order
    // by about `q b h^q`: the local orders approach their limit
    // geometrically, each difference of neighbours `r^q` times the coarser
    // one (`r = h_(i+1)/h_i`), with `q` from 1 (a general method) to
    // [`MAX_SETTLING_POWER`] (the expansions here go in h or h^2, a symmetric
    // method's in h^2 and h^4). A larger drop is a jump out of a
    // pre-asymptotic bump onto the plateau, not a term settling. A curved error drifting
    // through the plateau changes its local order by equal differences per
    // rung (or sweeps back through a cancellation), which this rejects; so is
    // a step away from the plateau. Rungs join only while the window needs
    // them, and the fit then models the term.
    let short = |first: usize| b + 1 - first < MIN_WINDOW || halvings(first) < MIN_WINDOW_HALVINGS;
    while first > a && first + 2 <= b && short(first) {
        let step = local(first + 1) - local(first);
        let next = local(first + 2) - local(first + 1);
        let shrink = data[first + 1].h / data[first].h;
        let settling = (local(first) - median).abs() > tolerance
            && step * (median - local(first)) > 0.0
            && step * next > 0.0
            && (shrink.powi(MAX_SETTLING_POWER)..=shrink).contains(&(next / step));
        if !settling {
            break;
        }
        first -= 1;
    }
    let window = (!short(first)).then_some((first, b));
    for (i, slot) in dropped.iter_mut().enumerate().take(first).skip(a) {
        let strays = (local(i + 1) - median).abs() > tolerance;
        *slot = Some(if strays || window.is_none() {
            DropReason::PreAsymptotic
        } else {
            DropReason::NotNeeded
        });
    }
    if window.is_none() {
        for d in &mut dropped[first..=b] {
            *d = Some(DropReason::PreAsymptotic);
        }
    }
    WindowChoice {
        dropped,
        clean: Some((a, b)),
        window,
        median_local_order: median.is_finite().then_some(median),
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

pub(crate) fn median_of(mut v: Vec<f64>) -> f64 {
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

/// Why a rung is left out of the fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DropReason {
    /// The run blew up or a step failed.
    Unstable,
    /// The run stopped at a finer step than a rung that resolved the
    /// motion: a defect, which fails the claim (see
    /// [`crate::study::breakdown`]).
    Breakdown,
    /// The error is not small against the orbit ([`crate::tolerance::ERROR_CEILING`]).
    AboveCeiling,
    /// The local order has not yet settled (coarse end of the ladder).
    PreAsymptotic,
    /// Round-off is too large a part of the error to leave its local order
    /// within [`crate::tolerance::ORDER_RESOLUTION`]: the floor.
    RoundOff,
    /// Asymptotic, but coarser than the window, which uses the finest rungs.
    NotNeeded,
    /// Run only as the half step of a finer-measured rung.
    Reference,
}

impl DropReason {
    /// A short explanation for tables.
    pub fn explain(self) -> &'static str {
        match self {
            DropReason::Unstable => "unstable",
            DropReason::Breakdown => "broke down below a clean step",
            DropReason::AboveCeiling => "error above 30% of the orbit",
            DropReason::PreAsymptotic => "pre-asymptotic",
            DropReason::RoundOff => "round-off floor",
            DropReason::NotNeeded => "coarser than the window",
            DropReason::Reference => "half step of another rung",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ladder(
        e: impl Fn(f64) -> Option<f64>,
        round_off: impl Fn(f64) -> f64,
        n: i32,
    ) -> Vec<RungData> {
        (0..n)
            .map(|k| 0.5 / 2f64.powi(k))
            .map(|h| RungData {
                h,
                error: e(h),
                round_off: round_off(h),
            })
            .collect()
    }

    #[test]
    fn window_excludes_blow_ups_coarse_errors_and_the_floor() {
        // second order, blows up at the coarsest rung, error above the
        // ceiling at the next, and round-off of 1e-13 / h
        let data = ladder(
            |h| (h <= 0.4).then_some(2.0 * h * h + 1e-13 / h),
            |h| 1e-13 / h,
            20,
        );
        let w = select_window(&data, 0.3);
        assert_eq!(w.dropped[0], Some(DropReason::Unstable));
        assert_eq!(w.dropped[1], Some(DropReason::AboveCeiling));
        // clean while 1e-13/h <= 0.01 ln2 / 2 * 2 h^2, i.e. h^3 >= 1.44e-11:
        // h >= 2.4e-4, rung 11 (h = 2.44e-4) is the finest clean one
        let (_, b) = w.window.expect("a window");
        assert_eq!(b, 11, "{w:?}");
        assert!(
            w.dropped[12..]
                .iter()
                .all(|d| *d == Some(DropReason::RoundOff))
        );
    }

    /// A ladder of four rungs per halving from `h0`, as the order study
    /// builds for an eighth-order claim.
    fn quarter_ladder(h0: f64, e: impl Fn(f64) -> f64, round_off: f64, n: i32) -> Vec<RungData> {
        (0..n)
            .map(|k| h0 * 2f64.powf(-0.25 * k as f64))
            .map(|h| RungData {
                h,
                error: Some(e(h)),
                round_off,
            })
            .collect()
    }

    #[test]
    fn a_settling_next_term_extends_a_window_the_floor_cut_short() {
        // e = h^8 (1 - 7 h^2), the shape of a symmetric multistep method's
        // error on the circular orbit (h in units of 1/w): the local order
        // climbs from 7.4 to 7.97 while the round-off floor (1e-12) stops
        // the ladder; the plateau alone spans 1.75 halvings, too few
        let data = quarter_ladder(0.23, |h| h.powi(8) * (1.0 - 7.0 * h * h), 1e-12, 16);
        let a = analyse(&data, 1.0);
        let (first, last) = a.choice.window.expect("a window along the settling term");
        let median = a.choice.median_local_order.unwrap();
        let coarsest = local_order_of(&data, first + 1).unwrap();
        assert!(
            (coarsest - median).abs() > tolerance::plateau_tolerance(median),
            "the settling rule was not needed: {coarsest} vs {median}"
        );
        assert!((data[first].h / data[last].h).log2() >= MIN_WINDOW_HALVINGS);
        let [lo, hi] = a.ci95.unwrap();
        assert!(lo <= 8.0 && 8.0 <= hi, "[{lo}, {hi}]");
        assert!((a.fit.unwrap().order - 8.0).abs() <= tolerance::ORDER_TOLERANCE);
    }

    #[test]
    fn deviations_shrinking_slower_than_the_step_do_not_join_a_window() {
        // local orders drifting linearly in ln h, 8 + ln(h / 0.05): a curved
        // error, its local order changing by equal differences per rung
        let data = quarter_ladder(
            0.23,
            |h: f64| h.powi(8) * (0.5 * (h / 0.05).ln().powi(2)).exp(),
            1e-12,
            16,
        );
        let w = select_window(&data, 1.0);
        assert!(w.window.is_none(), "{:?}", w.window);
        // nor is a sweep through a cancellation: e = h^8 |1 - 10 h| vanishes
        // at h = 0.1 inside the ladder, its local orders running off to
        // -inf and back from +inf; no window may reach across the zero
        let data = quarter_ladder(0.23, |h| h.powi(8) * (1.0 - 10.0 * h).abs(), 1e-14, 24);
        let w = select_window(&data, 1.0);
        if let Some((first, _)) = w.window {
            assert!(
                data[first].h < 0.1,
                "window from h = {} spans the zero",
                data[first].h
            );
        }
    }

    #[test]
    fn no_window_when_the_error_does_not_converge() {
        let w = select_window(&ladder(|_| Some(0.01), |_| 1e-16, 10), 1.0);
        // a flat error is clean (far above round-off) and its local order 0
        assert_eq!(w.median_local_order, Some(0.0));
    }

    #[test]
    fn local_order_of_a_power_law() {
        let p = local_order((0.1, Some(3e-4)), (0.05, Some(3e-4 / 8.0))).unwrap();
        assert!((p - 3.0).abs() < 1e-12);
        assert!(local_order((0.1, None), (0.05, Some(1.0))).is_none());
    }

    #[test]
    fn round_off_model_recovers_a_power_law_and_bounds_its_scatter() {
        // sqrt(N) law with a factor-two scatter; the bound must lie above
        // every sample and within a small factor of the law
        let samples: Vec<(u64, f64)> = (0..14)
            .map(|k| {
                let n = 23u64 << k;
                let wobble = if k % 2 == 0 { 2.0 } else { 0.5 };
                (n, 1e-16 * (n as f64).sqrt() * wobble)
            })
            .collect();
        let m = RoundOffModel::fit(&samples).unwrap();
        assert!((m.exponent - 0.5).abs() < 0.05, "{m:?}");
        for &(n, r) in &samples {
            assert!(m.bound(n) >= r, "{n}: {} < {r}", m.bound(n));
            assert!(m.bound(n) < 20.0 * r, "{n}");
        }
    }
}
