//! The verdict on a claimed order from an analysed ladder: pass over a
//! window, fail on an interval below the claim or an order reduction at the
//! fine end, inconclusive (with what to change) when the data cannot decide.

use crate::ladder::LadderEnd;
use crate::measure::Verdict;
use crate::measure::accuracy::fit::OrderFit;
use crate::measure::accuracy::fit::power_law;
use crate::measure::accuracy::rung::{DropReason, OrderReduction, Reference, Rung};
use crate::measure::accuracy::window::Analysis;
use crate::measure::accuracy::window::median_of;
use crate::tolerance::{
    self, ERROR_CEILING, MIN_WINDOW, MIN_WINDOW_HALVINGS, ORDER_TOLERANCE, REFERENCE_RUNGS,
    STALL_ORDER,
};

/// The verdict on a ladder, why, and what to change when inconclusive.
pub(crate) struct Judgement {
    pub(crate) verdict: Verdict,
    pub(crate) reason: String,
    pub(crate) advice: Option<String>,
    pub(crate) reduction: Option<OrderReduction>,
}

impl Judgement {
    fn inconclusive(reason: String, advice: String) -> Self {
        Self {
            verdict: Verdict::Inconclusive,
            reason,
            advice: Some(advice),
            reduction: None,
        }
    }

    fn fail(reason: String, reduction: Option<OrderReduction>) -> Self {
        Self {
            verdict: Verdict::Fail,
            reason,
            advice: None,
            reduction,
        }
    }
}

/// Judges the claimed order against the analysed rungs.
pub(crate) fn judge(
    claim: f64,
    rungs: &[Rung],
    analysis: &Analysis,
    reference: Reference,
    end: LadderEnd,
    scale: f64,
) -> Judgement {
    if let Some(stalled) = analysis.choice.clean.and_then(|(a, b)| stall(rungs, a, b)) {
        return Judgement::fail(stalled, None);
    }
    let reduction = analysis
        .choice
        .clean
        .and_then(|(a, b)| order_reduction(claim, rungs, a, b));
    if let (Some(f), Some(ci), Some(window)) = (analysis.fit, analysis.ci95, analysis.choice.window)
    {
        return judge_fit(claim, rungs, f, ci, window, reduction);
    }
    let finest_h = rungs.last().map_or(f64::NAN, |r| r.h);
    let end_note = match end {
        LadderEnd::Cap => format!("the ladder reached its step cap at h = {finest_h:.3e}"),
        LadderEnd::Floor => "the ladder reached the round-off floor".to_string(),
        LadderEnd::Fixed => "a fixed ladder".to_string(),
    };
    if let Some(r) = reduction {
        return Judgement::fail(
            format!(
                "order reduction: the local order falls from {:.2} towards {:.2} below h = {:.3e}, \
                 under the claimed {claim} ({end_note})",
                r.from, r.to, r.sets_in_at
            ),
            reduction,
        );
    }
    let clean = analysis.choice.clean.map_or(0, |(a, b)| b + 1 - a);
    let at_floor = analysis
        .choice
        .dropped
        .iter()
        .filter(|d| **d == Some(DropReason::RoundOff))
        .count();
    if clean == 0 && at_floor == 0 {
        return judge_unresolved(rungs, analysis, reference, end, scale);
    }
    if clean == 0 {
        let smallest = rungs
            .iter()
            .filter_map(|r| r.error)
            .fold(f64::INFINITY, f64::min);
        return Judgement::inconclusive(
            format!(
                "round-off is a large part of the error at every rung that resolves the motion \
                 (smallest error {smallest:.3e}, {:.1e} of the orbit)",
                smallest / scale
            ),
            "an error at round-off everywhere means the scheme is exact on this scene: measure \
             it on one where it is not; a large round-off means the scene magnifies it over \
             t_end: shorten t_end"
                .into(),
        );
    }
    let (a, b) = analysis.choice.clean.expect("clean rungs");
    let locals: Vec<String> = (a + 1..=b)
        .filter_map(|i| rungs[i].local_order)
        .map(|l| format!("{l:.2}"))
        .collect();
    let advice = match end {
        LadderEnd::Cap => {
            "the local order was still moving when the ladder reached its step cap: raise the \
             cap (AutoLadder::max_rung_evaluations) or shorten t_end"
        }
        LadderEnd::Floor => {
            "round-off leaves too few clean rungs above it: shorten t_end, which lowers the \
             round-off a rung accumulates and the magnification of the flow"
        }
        LadderEnd::Fixed => "use the automatic ladder, which runs to the floor",
    };
    Judgement::inconclusive(
        format!(
            "no window of {MIN_WINDOW} rungs with a settled local order: {clean} clean rungs, \
             local orders [{}] ({end_note})",
            locals.join(", ")
        ),
        advice.into(),
    )
}

/// The verdict when a window was found: the claim against the fitted
/// interval, with the order reduction named when there is one.
fn judge_fit(
    claim: f64,
    rungs: &[Rung],
    f: OrderFit,
    ci: [f64; 2],
    (a, b): (usize, usize),
    reduction: Option<OrderReduction>,
) -> Judgement {
    let over = format!(
        "order {:.3} in [{:.3}, {:.3}] over rungs {a}..{b} (h {:.3e} .. {:.3e})",
        f.order, ci[0], ci[1], rungs[a].h, rungs[b].h
    );
    match tolerance::order_verdict(claim, f.order, ci) {
        Ok(note) => Judgement {
            verdict: Verdict::Pass,
            reason: note.map_or(over.clone(), |n| format!("{over}: {n}")),
            advice: None,
            reduction: None,
        },
        Err(why) if ci[1] >= claim && reduction.is_none() => {
            match still_rising_to(claim, rungs, a, b) {
                Some(limit) => Judgement::inconclusive(
                    format!(
                        "{why}: {over}, but the finest local orders still rise towards the \
                         claim (heading for {limit:.2}): a cancellation in the leading error \
                         term not yet passed at these steps"
                    ),
                    "shorten t_end, which lowers the round-off floor and lets the ladder reach \
                     the steps where the claimed order's term dominates"
                        .into(),
                ),
                None => Judgement::fail(format!("{why}: {over}"), reduction),
            }
        }
        Err(why) => {
            let fell = reduction.map_or(String::new(), |r| {
                format!(
                    "; the local order falls from {:.2} towards {:.2} below h = {:.3e} (order reduction)",
                    r.from, r.to, r.sets_in_at
                )
            });
            Judgement::fail(format!("{why}: {over}{fell}"), reduction)
        }
    }
}

/// The verdict when no rung resolved the motion and none sat at round-off:
/// every rung blew up or stayed far from its reference down to the finest
/// step.
fn judge_unresolved(
    rungs: &[Rung],
    analysis: &Analysis,
    reference: Reference,
    end: LadderEnd,
    scale: f64,
) -> Judgement {
    let count = |reason| {
        analysis
            .choice
            .dropped
            .iter()
            .filter(|d| **d == Some(reason))
            .count()
    };
    let (unstable, above) = (count(DropReason::Unstable), count(DropReason::AboveCeiling));
    let finest_h = rungs.last().map_or(f64::NAN, |r| r.h);
    if reference == Reference::Exact && unstable == rungs.len() {
        return Judgement::fail(
            format!(
                "no convergence: every rung blew up, down to h = {finest_h:.3e}, though \
                 the exact motion stays bounded"
            ),
            None,
        );
    }
    if let Some(elsewhere) = converges_elsewhere(rungs, scale) {
        return Judgement::fail(elsewhere, None);
    }
    Judgement::inconclusive(
        format!(
            "no rung resolved the motion ({unstable} unstable, {above} with errors above \
             {ERROR_CEILING} of the orbit, down to h = {finest_h:.3e})"
        ),
        match end {
            LadderEnd::Fixed => "a correct scheme needs finer steps here: give the ladder \
                                 more levels or a smaller h0, or use the automatic one"
                .into(),
            _ => "a correct scheme needs finer steps here: raise the step cap \
                  (AutoLadder::max_rung_evaluations) or shorten t_end; if the motion itself runs \
                  away, shorten t_end"
                .into(),
        },
    )
}

/// A scheme that converges, but not to the exact solution: at its two finest
/// rungs with a half-step difference, that difference is within the
/// ceiling (the runs at `h` and `h/2` agree on the motion) while the error is
/// more than four times it. Were the scheme converging to the exact solution
/// with any order `p >= 1`, its error would be `1 / (1 - 2^-p) <= 2` times
/// the difference; four leaves a factor two for the pre-asymptotic rungs.
/// It is the signature of a scheme that solves another equation (a wrong
/// sign, a wrong coefficient) or a wrong initial state.
fn converges_elsewhere(rungs: &[Rung], scale: f64) -> Option<String> {
    let pairs: Vec<(f64, f64, f64)> = rungs
        .iter()
        .filter_map(|r| Some((r.h, r.error?, r.half_step_difference?)))
        .collect();
    let finest = pairs.get(pairs.len().checked_sub(2)?..)?;
    let elsewhere = finest
        .iter()
        .all(|&(_, e, d)| d <= ERROR_CEILING * scale && e > 4.0 * d);
    elsewhere.then(|| {
        let (h, e, d) = finest[1];
        format!(
            "converges, but not to the exact solution: at h = {h:.3e} the run differs from its \
             half step by {d:.3e} and from the exact motion by {e:.3e} (the scheme solves \
             another problem, or starts from another state)"
        )
    })
}

/// A stall: over the finest clean rungs the error stops falling, at a
/// level far above the round-off those rungs carry (they are clean: their
/// round-off bound is a small fraction of their error).
///
/// Every claim is an order of at least 1, and a convergent scheme's error
/// falls at least like `h` once asymptotic, so over [`MIN_WINDOW_HALVINGS`]
/// halvings it falls at least fourfold; round-off cannot hold it up on clean
/// rungs. An error that does not fall is a bias of the scheme: a step
/// rounded to `f32`, a coefficient or a force off by a constant. The stall
/// is the longest run of clean rungs at the fine end, spanning at least
/// [`MIN_WINDOW_HALVINGS`] halvings, over which the error falls slower than
/// `h^s`, `s =` [`STALL_ORDER`] (halfway between order 0 and order 1), by
/// two measures: the least-squares slope of `ln e` on `ln h`, whose 95%
/// interval lies wholly below `s`, and the medians of its coarser and finer
/// halves, which differ by less than an order-`s` fall between them. The
/// slope alone could be dragged down by one rung in a cancellation of the
/// leading error term (a deep dip at the coarse end of the run); the
/// medians are not moved by one rung, and past a cancellation a correct
/// scheme's error falls again at its order.
fn stall(rungs: &[Rung], a: usize, b: usize) -> Option<String> {
    let points: Vec<(f64, f64, f64)> = rungs[a..=b]
        .iter()
        .filter_map(|r| Some((r.h, r.error?, r.round_off_bound.unwrap_or(0.0))))
        .filter(|&(_, e, _)| e > 0.0 && e.is_finite())
        .collect();
    let finest_h = points.last()?.0;
    // the coarsest start whose run to the fine end falls slower than h^1
    (0..points.len()).find_map(|start| {
        let run = &points[start..];
        let halvings = (run[0].0 / finest_h).log2();
        if run.len() < MIN_WINDOW || halvings < MIN_WINDOW_HALVINGS {
            return None;
        }
        let line = power_law(&run.iter().map(|&(h, e, _)| (h, e)).collect::<Vec<_>>())?;
        let half = run.len() / 2;
        let median = |part: &[(f64, f64, f64)]| {
            (
                median_of(part.iter().map(|p| p.0.ln()).collect()).exp(),
                median_of(part.iter().map(|p| p.1).collect()),
            )
        };
        let ((h1, e1), (h2, e2)) = (median(&run[..half]), median(&run[half..]));
        // a fall at STALL_ORDER from the coarser half's median to the finer's
        let falls = e2 < e1 * (h2 / h1).powf(STALL_ORDER);
        (line.ci95[1] < STALL_ORDER && !falls).then(|| {
            let round_off = run.iter().map(|p| p.2).fold(0.0, f64::max);
            format!(
                "the error stops falling: from h = {:.3e} to {finest_h:.3e} ({} clean rungs, \
                 {halvings:.1} halvings) it falls only at order {:.2} in [{:.2}, {:.2}] and \
                 ends near {e2:.3e} (median of the finer half), while round-off there is at \
                 most {round_off:.1e}: the scheme carries an error that does not shrink with \
                 the step (a step, a coefficient or a force rounded or off by a constant)",
                run[0].0,
                run.len(),
                line.slope,
                line.ci95[0],
                line.ci95[1]
            )
        })
    })
}

/// The limit the finest [`REFERENCE_RUNGS`] local orders of the window
/// `a..=b` head for, when they rise steadily towards the claim: each above
/// the last by less than the one before (a trend `l = p + c h` on a ladder
/// of constant ratio gives increments shrinking like the steps), with
/// Aitken's limit `l3 + d2 r / (1 - r)`, `r = d2 / d1`, within
/// [`ORDER_TOLERANCE`] of the claim or above it.
///
/// The converse of [`order_reduction`]: past a cancellation of its leading
/// error term a correct scheme's local order lies below its order for a
/// while and rises back (`e = C h^p (1 + c h)`, `c < 0`, has local order
/// `p + c h / (1 + c h)`); a fit over such a window is biased low however
/// its interval is widened, so an estimate below the claim there does not
/// refute it. The data cannot decide at these steps: the verdict is
/// inconclusive, and the order study shortens `t_end` to reach finer ones.
/// A scheme of lower order has local orders that settle below the claim
/// (no steady rise, or a limit below it).
fn still_rising_to(claim: f64, rungs: &[Rung], a: usize, b: usize) -> Option<f64> {
    let locals: Vec<f64> = (a + 1..=b).filter_map(|i| rungs[i].local_order).collect();
    let [l1, l2, l3] = *locals.get(locals.len().checked_sub(REFERENCE_RUNGS)?..)? else {
        return None;
    };
    let (d1, d2) = (l2 - l1, l3 - l2);
    if !(d1 > 0.0 && d2 > 0.0 && d2 < d1) {
        return None;
    }
    let r = d2 / d1;
    let limit = l3 + d2 * r / (1.0 - r);
    (limit >= claim - ORDER_TOLERANCE).then_some(limit)
}

/// An order reduction at the fine end of the clean rungs `a..=b`: the local
/// orders reached the claim (two in a row within the plateau tolerance of
/// it), and the finest [`REFERENCE_RUNGS`] of them lie more than the plateau
/// tolerance and [`ORDER_TOLERANCE`] below it, converging to a limit below
/// it too (see [`local_order_limit`]).
///
/// A correct scheme's local order tends to its order as `h -> 0`, from above
/// or below. Past a cancellation of its leading error term it can lie far
/// below it for a while, but rising back towards it; what it does not do is
/// settle below it. The limit tells the two apart.
fn order_reduction(claim: f64, rungs: &[Rung], a: usize, b: usize) -> Option<OrderReduction> {
    let locals: Vec<(usize, f64)> = (a + 1..=b)
        .filter_map(|i| Some((i, rungs[i].local_order?)))
        .collect();
    let tolerance = tolerance::plateau_tolerance(claim);
    let on_claim = |l: f64| (l - claim).abs() <= tolerance;
    // the finest pair of consecutive local orders on the claim
    let seen = (1..locals.len())
        .rev()
        .find(|&k| on_claim(locals[k - 1].1) && on_claim(locals[k].1))?;
    let tail = &locals[seen..];
    if tail.len() <= REFERENCE_RUNGS {
        return None;
    }
    let fine: Vec<f64> = tail[tail.len() - REFERENCE_RUNGS..]
        .iter()
        .map(|&(_, l)| l)
        .collect();
    let below = |l: f64| l < claim - tolerance.max(ORDER_TOLERANCE);
    let limit = local_order_limit(&fine)?;
    if !(fine.iter().all(|&l| below(l)) && below(limit)) {
        return None;
    }
    let (first_off, _) = tail.iter().copied().find(|&(_, l)| !on_claim(l))?;
    Some(OrderReduction {
        from: claim,
        to: limit,
        sets_in_at: rungs[first_off - 1].h,
    })
}

/// Where three successive local orders `l1, l2, l3` (coarse to fine) are
/// heading, when the data say: their common value if they agree to within
/// half the plateau tolerance (what round-off may move each); the limit of
/// the geometric sequence they start if their steps shrink with one sign
/// (`l3 + d2 r / (1 - r)`, `r = d2 / d1`: Aitken's extrapolation, exact for
/// a local order `L + c h^s` on a ladder of constant ratio); at most `l3` if
/// they fall faster and faster. Otherwise `None`: rising ever faster, or
/// wobbling, they could be heading anywhere.
pub fn local_order_limit(fine: &[f64]) -> Option<f64> {
    let [l1, l2, l3] = *fine else {
        return None;
    };
    let (d1, d2) = (l2 - l1, l3 - l2);
    let half = tolerance::plateau_tolerance(l3) / 2.0;
    if d1.abs() <= half && d2.abs() <= half {
        return Some(median_of(fine.to_vec()));
    }
    if d1 * d2 > 0.0 && d2.abs() < d1.abs() {
        let r = d2 / d1;
        return Some(l3 + d2 * r / (1.0 - r));
    }
    (d1 <= 0.0 && d2 <= 0.0).then_some(l3)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::Outcome;

    /// A halving ladder at two rungs a halving with errors `error(h)` and a
    /// round-off bound far below them.
    fn ladder(error: impl Fn(f64) -> f64) -> Vec<Rung> {
        (0..30)
            .map(|k| {
                let h = 0.1 * 2f64.powf(-(k as f64) / 2.0);
                Rung {
                    h,
                    steps: (10.0 / h).round() as u64,
                    error: Some(error(h)),
                    final_error: None,
                    half_step_difference: None,
                    round_off_sample: Some(1e-15),
                    round_off_bound: Some(1e-15),
                    local_order: None,
                    used: false,
                    dropped: None,
                    outcome: Outcome::Completed,
                }
            })
            .collect()
    }

    #[test]
    fn an_error_held_up_by_a_bias_is_a_stall() {
        // h^2 down to a floor of 1e-8 with a wobble of a factor 6 between
        // neighbouring rungs, as a step rounded to f32 gives
        let rungs =
            ladder(|h| 0.5 * h * h + 1e-8 * (1.0 + 5.0 * ((1.0 / h).ln() * 7.0).sin().abs()));
        let found = stall(&rungs, 0, rungs.len() - 1).expect("a stall");
        assert!(found.contains("stops falling"), "{found}");
        assert!(found.contains("1.0e-15"), "{found}");
    }

    #[test]
    fn first_order_convergence_is_no_stall() {
        // order 1 with a small wobble: the fit's interval may dip below 1
        let rungs = ladder(|h| h * (1.0 + 0.02 * ((1.0 / h).ln() * 5.0).sin()));
        assert_eq!(stall(&rungs, 0, rungs.len() - 1), None);
        // and a slow order-1 fall with a settling correction
        let rungs = ladder(|h| h * (1.0 + 3.0 * h));
        assert_eq!(stall(&rungs, 0, rungs.len() - 1), None);
    }

    #[test]
    fn a_cancellation_of_the_leading_term_is_no_stall() {
        // e = |h^2 - 400 h^4|: a zero near h = 0.05, then order 2 again
        let rungs = ladder(|h| (h * h - 400.0 * h.powi(4)).abs().max(1e-14));
        assert_eq!(stall(&rungs, 0, rungs.len() - 1), None);
        // a cancellation two halvings before the finest rung
        let h0 = 0.1 * 2f64.powf(-13.5);
        let rungs = ladder(|h| (h * h * (1.0 - (h / h0).powi(2))).abs().max(1e-300));
        assert_eq!(stall(&rungs, 0, rungs.len() - 1), None);
    }

    #[test]
    fn a_floor_reached_only_at_the_fine_end_is_not_yet_a_stall() {
        // h^2 meets a constant at the third-finest rung: too few halvings
        // past it to tell a floor from a slowing fall
        let floor = 0.01 * 2f64.powi(-27);
        let rungs = ladder(|h| h * h + floor);
        assert_eq!(stall(&rungs, 0, rungs.len() - 1), None);
        // the same constant met five halvings earlier is a stall
        let rungs = ladder(|h| h * h + 1e-8);
        assert!(stall(&rungs, 0, rungs.len() - 1).is_some());
    }
}
