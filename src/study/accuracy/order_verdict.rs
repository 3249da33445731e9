//! The verdict on a claimed order from an analysed ladder: pass over a
//! window, fail on an interval below the claim or an order reduction at the
//! fine end, inconclusive (with what to change) when the data cannot decide.

use crate::ladder::LadderEnd;
use crate::maths::fit::OrderFit;
use crate::maths::fit::power_law;
use crate::maths::window::DropReason;
use crate::maths::window::median_of;
use crate::maths::window::{Analysis, RungData, select_window};
use crate::study::accuracy::rung::{OrderReduction, Reference, Rung};
use crate::study::verdict::Verdict;
use crate::tolerance::{
    self, ERROR_CEILING, MIN_WINDOW, MIN_WINDOW_HALVINGS, ORDER_TOLERANCE, REFERENCE_RUNGS,
    RESOLVED_STEP_RADIANS, STALL_ORDER, WINDOW_RUNGS,
};
use crate::wording::{figure, order, vs_lower, vs_upper};

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

/// Judges the claimed order against the analysed rungs. `fastest` gives
/// the motion's fastest local rate along the exact orbit (see
/// [`crate::maths::tangent::local_rate`]), asked for only when every rung
/// blew up.
pub(crate) fn judge(
    claim: f64,
    rungs: &[Rung],
    analysis: &Analysis,
    reference: Reference,
    end: LadderEnd,
    scale: f64,
    fastest: &dyn Fn() -> f64,
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
        return judge_fit(claim, rungs, f, ci, window, reduction, end);
    }
    let finest_h = rungs.last().map_or(f64::NAN, |r| r.h);
    let end_note = match end {
        LadderEnd::Cap => format!(
            "the ladder reached its step cap at h = {}",
            figure(finest_h)
        ),
        LadderEnd::Floor => "the ladder reached the round-off floor".to_string(),
        LadderEnd::Fixed => "a fixed ladder".to_string(),
        LadderEnd::Breakdown => format!(
            "the ladder stopped at a breakdown, h = {}",
            figure(finest_h)
        ),
    };
    if let Some(r) = reduction {
        return Judgement::fail(
            format!("{} ({end_note})", reduction_text(claim, &r)),
            reduction,
        );
    }
    let clean = analysis.choice.clean.map_or(0, |(a, b)| b + 1 - a);
    let floor: Vec<&Rung> = rungs
        .iter()
        .zip(&analysis.choice.dropped)
        .filter(|(_, d)| **d == Some(DropReason::RoundOff))
        .map(|(r, _)| r)
        .collect();
    if clean == 0 && floor.is_empty() {
        return judge_unresolved(rungs, analysis, reference, end, scale, fastest);
    }
    if clean == 0 {
        let smallest = rungs
            .iter()
            .filter_map(|r| r.error)
            .fold(f64::INFINITY, f64::min);
        // the share of its error each rung on the floor owes to round-off
        let shares: Vec<f64> = floor
            .iter()
            .filter_map(|r| Some(r.round_off_bound? / r.error?))
            .filter(|f| f.is_finite())
            .collect();
        let (least, most) = shares.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &f| {
            (lo.min(f), hi.max(f))
        });
        return Judgement::inconclusive(
            format!(
                "round-off is a large part of the error at every rung that resolves the motion: \
                 the round-off bound is {} to {} of the error at the {} rungs on the floor \
                 (smallest error {}, {} of the orbit)",
                figure(least),
                figure(most),
                floor.len(),
                figure(smallest),
                figure(smallest / scale)
            ),
            "an error at round-off everywhere means the scheme is exact on this scene: measure \
             it on one where it is not; a large round-off means the scene magnifies it over \
             t_end: shorten t_end"
                .into(),
        );
    }
    let (a, b) = analysis.choice.clean.expect("clean rungs");
    // the finest local orders, where a window is sought
    let locals: Vec<String> = ((a + 1).max((b + 1).saturating_sub(WINDOW_RUNGS))..=b)
        .filter_map(|i| rungs[i].local_order)
        .map(|l| format!("{l:.2}"))
        .collect();
    let unsettled = format!(
        "no window of {MIN_WINDOW} rungs over {MIN_WINDOW_HALVINGS} halvings with a settled local \
         order: {clean} clean rungs (h = {} .. {}), the finest local orders [{}]",
        figure(rungs[a].h),
        figure(rungs[b].h),
        locals.join(", ")
    );
    if let Some(outlier) = outlying_rung(rungs, analysis, scale) {
        return Judgement::inconclusive(
            format!("{unsettled}: {outlier} ({end_note})"),
            "one rung off its neighbours' trend is a cancellation of the error's terms at that \
             step and end time, not a property of the scheme: measure at another t_end \
             (OrderSpec::t_end) or on another ladder (OrderSpec::ladder)"
                .into(),
        );
    }
    if let Some(cut) = cut_by_round_off(rungs, analysis) {
        return Judgement::inconclusive(
            format!("{unsettled}: {cut}"),
            "shorten t_end, which lowers the round-off a rung accumulates and the magnification \
             of the flow, so that more rungs stand clear of the floor"
                .into(),
        );
    }
    let advice = match end {
        LadderEnd::Cap => {
            "the local order was still moving when the ladder reached its step cap: raise the \
             cap (AutoLadder::max_rung_evaluations) or shorten t_end"
        }
        LadderEnd::Floor => {
            "the local order was still moving when the ladder reached the round-off floor: \
             shorten t_end, which lowers the floor and lets the ladder reach finer steps"
        }
        LadderEnd::Fixed => "use the automatic ladder, which runs to the floor",
        // the breakdown decides before any advice is read
        LadderEnd::Breakdown => "",
    };
    Judgement::inconclusive(format!("{unsettled} ({end_note})"), advice.into())
}

/// An order reduction in words, with the limit the local orders head for
/// against the bound it falls below.
fn reduction_text(claim: f64, r: &OrderReduction) -> String {
    let margin = tolerance::plateau_tolerance(claim).max(ORDER_TOLERANCE);
    format!(
        "order reduction: below h = {} the local order falls from {} towards {} (the claimed \
         {claim} less {})",
        figure(r.sets_in_at),
        figure(r.from),
        vs_lower(r.to, "", claim - margin),
        figure(margin)
    )
}

/// The ladder data the window is chosen from.
pub(crate) fn data(rungs: &[Rung]) -> Vec<RungData> {
    rungs
        .iter()
        .map(|r| RungData {
            h: r.h,
            error: r.error,
            round_off: r.round_off_bound.unwrap_or(0.0),
        })
        .collect()
}

/// One rung whose error alone keeps the window from forming: without it,
/// the window selection finds a window through its neighbours. Such a rung
/// moves two neighbouring local orders in opposite directions (its error is
/// off its neighbours' trend); round-off, which grows steadily along the
/// ladder, does not do that to one rung, and the rung is clean (its
/// round-off bound a small part of its error). Searched from the fine end.
fn outlying_rung(rungs: &[Rung], analysis: &Analysis, scale: f64) -> Option<String> {
    let (a, b) = analysis.choice.clean?;
    let all = data(rungs);
    (a..=b).rev().find_map(|j| {
        let mut without = all.clone();
        without.remove(j);
        let (first, last) = select_window(&without, scale).window?;
        // the window must reach the clean rungs on both sides of the gap,
        // or past it (the finest rung left out)
        let spans = first < j && (last >= j || j == b);
        let round_off = rungs[j].round_off_bound.unwrap_or(0.0);
        let error = rungs[j].error?;
        spans.then(|| {
            let side = |i: usize| rungs.get(i).and_then(|r| r.local_order);
            let sides: Vec<String> = [side(j), side(j + 1).filter(|_| j < b)]
                .into_iter()
                .flatten()
                .map(|l| format!("{l:.2}"))
                .collect();
            format!(
                "one outlying rung, at h = {} (local orders {} on either side), whose error {} \
                 is clear of its round-off bound {}; without it the rungs from h = {} to {} \
                 form a window",
                figure(rungs[j].h),
                sides.join(" and "),
                figure(error),
                figure(round_off),
                figure(without[first].h),
                figure(without[last].h)
            )
        })
    })
}

/// The clean rungs are too few, and the rung below them is on the
/// round-off floor: its round-off bound reaches the part of its error that
/// would leave its local order resolved ([`tolerance::clean_fraction`]).
/// Only then does round-off cut the window short.
fn cut_by_round_off(rungs: &[Rung], analysis: &Analysis) -> Option<String> {
    let (a, b) = analysis.choice.clean?;
    let halvings = (rungs[a].h / rungs[b].h).log2();
    let too_few = b + 1 - a < MIN_WINDOW || halvings < MIN_WINDOW_HALVINGS;
    let below = rungs.get(b + 1)?;
    if !too_few || analysis.choice.dropped.get(b + 1)? != &Some(DropReason::RoundOff) {
        return None;
    }
    let (error, round_off) = (below.error?, below.round_off_bound?);
    let local = below.local_order.filter(|l| l.is_finite()).unwrap_or(1.0);
    let share = tolerance::clean_fraction((rungs[b].h / below.h).ln(), local);
    Some(format!(
        "{} rungs over {:.1} halvings stand above the round-off floor, which begins at h = {}: \
         there the round-off bound {}, the part of the error {} that round-off may be on a \
         clean rung",
        b + 1 - a,
        halvings,
        figure(below.h),
        vs_lower(round_off, "", share * error),
        figure(error),
    ))
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
    end: LadderEnd,
) -> Judgement {
    let span = format!(
        "over rungs {a}..{b} (h {} .. {})",
        figure(rungs[a].h),
        figure(rungs[b].h)
    );
    let over = format!(
        "order {} in [{}, {}] {span}",
        order(f.order),
        order(ci[0]),
        order(ci[1])
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
                        "{why}, {span}, but the finest local orders still rise towards the \
                         claim (heading for {limit:.2}): a cancellation in the leading error \
                         term not yet passed at these steps"
                    ),
                    match end {
                        LadderEnd::Cap => {
                            "raise the step cap (AutoLadder::max_rung_evaluations) or shorten \
                             t_end, so that the ladder reaches the steps where the claimed \
                             order's term dominates"
                        }
                        LadderEnd::Floor => {
                            "shorten t_end, which lowers the round-off floor and lets the \
                             ladder reach the steps where the claimed order's term dominates"
                        }
                        LadderEnd::Fixed => {
                            "use the automatic ladder, which runs on to where the claimed \
                             order's term dominates"
                        }
                        LadderEnd::Breakdown => "",
                    }
                    .into(),
                ),
                None => Judgement::fail(format!("{why}, {span}"), reduction),
            }
        }
        Err(why) => {
            let fell = reduction.map_or(String::new(), |r| {
                format!("; {}", reduction_text(claim, &r))
            });
            Judgement::fail(format!("{why}, {span}{fell}"), reduction)
        }
    }
}

/// The verdict when no rung resolved the motion and none sat at round-off:
/// every rung blew up or stayed far from its reference down to the finest
/// step. A blow-up at every rung of a bounded exact motion is a defect
/// where the finest rung resolves the motion's fastest local rate (at most
/// [`RESOLVED_STEP_RADIANS`] of it a step); where it does not, a correct
/// scheme can blow up there too, and the ladder has not reached the steps
/// that would tell.
fn judge_unresolved(
    rungs: &[Rung],
    analysis: &Analysis,
    reference: Reference,
    end: LadderEnd,
    scale: f64,
    fastest: &dyn Fn() -> f64,
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
    let advice = match end {
        LadderEnd::Fixed => "a correct scheme needs finer steps here: give the ladder \
                             more levels or a smaller h0, or use the automatic one"
            .to_string(),
        _ => "a correct scheme needs finer steps here: raise the step cap \
              (AutoLadder::max_rung_evaluations) or shorten t_end; if the motion itself runs \
              away, shorten t_end"
            .to_string(),
    };
    if reference == Reference::Exact && unstable == rungs.len() {
        let rate = fastest();
        if finest_h * rate > RESOLVED_STEP_RADIANS {
            return Judgement::inconclusive(
                format!(
                    "every rung blew up, down to h = {}, but none resolves the motion's fastest \
                     time scale: its fastest local rate along the exact orbit is {} per unit \
                     time, {} radians a step at the finest rung (a step resolves it at {} \
                     radian or less)",
                    figure(finest_h),
                    figure(rate),
                    figure(finest_h * rate),
                    figure(RESOLVED_STEP_RADIANS),
                ),
                advice,
            );
        }
        return Judgement::fail(
            format!(
                "no convergence: every rung blew up, down to h = {}, though the exact \
                 motion stays bounded",
                figure(finest_h)
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
             {ERROR_CEILING} of the orbit, down to h = {})",
            figure(finest_h)
        ),
        advice,
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
            "converges, but not to the exact solution: at h = {} the run differs from its half \
             step by {} and from the exact motion by {}, four times that difference (were it \
             converging to the exact motion at any order, at most twice): the scheme solves \
             another problem, or starts from another state",
            figure(h),
            figure(d),
            vs_upper(e, "", 4.0 * d),
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
                "the error stops falling: from h = {} to {} ({} clean rungs, {halvings:.1} \
                 halvings) it falls at order {:.2} in [{:.2}, {:.2}], the interval's upper end {} \
                 (halfway between orders 0 and 1), and ends near {} (median of the finer \
                 half): the scheme carries an error that does not shrink with the step (a \
                 step, a coefficient or a force rounded or off by a constant)",
                figure(run[0].0),
                figure(finest_h),
                run.len(),
                line.slope,
                line.ci95[0],
                line.ci95[1],
                vs_lower(line.ci95[1], "", STALL_ORDER),
                vs_upper(e2, "round-off bound", round_off),
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
                    solve: None,
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
        assert!(found.contains("round-off bound 1.00e-15"), "{found}");
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

    /// The rungs as the order study judges them: local orders set, the
    /// window chosen, and the claim judged at the round-off floor.
    fn judged_at_floor(claim: f64, mut rungs: Vec<Rung>) -> (Vec<Rung>, Judgement) {
        for k in 1..rungs.len() {
            rungs[k].local_order = crate::maths::window::local_order(
                (rungs[k - 1].h, rungs[k - 1].error),
                (rungs[k].h, rungs[k].error),
            );
        }
        let analysis = crate::maths::window::analyse(&data(&rungs), 1.0);
        let judgement = judge(
            claim,
            &rungs,
            &analysis,
            Reference::Exact,
            LadderEnd::Floor,
            1.0,
            &|| 0.0,
        );
        (rungs, judgement)
    }

    /// A clean second-order ladder run to the floor with one rung, three
    /// from the fine end, whose error is three times its neighbours' trend:
    /// the two local orders beside it (5.2 and -1.2) keep any window from
    /// forming. Round-off (1e-15 against errors above 1e-11) is nowhere
    /// near those rungs, so the advice must name the outlying rung and its
    /// step, and must not blame round-off.
    #[test]
    fn one_outlying_rung_is_named_and_not_blamed_on_round_off() {
        let outlier = 27;
        let mut rungs = ladder(|h| h * h);
        let e = rungs[outlier].error.expect("an error");
        rungs[outlier].error = Some(3.0 * e);
        let h = rungs[outlier].h;
        let (rungs, j) = judged_at_floor(2.0, rungs);
        assert_eq!(j.verdict, Verdict::Inconclusive, "{}", j.reason);
        let advice = j.advice.expect("advice when inconclusive");
        assert!(!advice.contains("round-off"), "{advice}");
        assert!(j.reason.contains("one outlying rung"), "{}", j.reason);
        assert!(
            j.reason.contains(&format!("h = {}", figure(h))),
            "{}",
            j.reason
        );
        // the local orders named are the two beside the rung, the one at it
        // and the one after it
        let beside = |i: usize| format!("{:.2}", rungs[i].local_order.expect("a local order"));
        let sides = format!(
            "local orders {} and {}",
            beside(outlier),
            beside(outlier + 1)
        );
        assert!(j.reason.contains(&sides), "{sides} in {}", j.reason);
        // round-off is indeed far below the error at every rung
        assert!(
            rungs
                .iter()
                .all(|r| r.round_off_bound.unwrap() < 1e-3 * r.error.unwrap())
        );
    }

    /// The converse: the clean rungs (above the ceiling at the coarse end)
    /// are too few because the round-off bound reaches the error below
    /// them; then the reason says so, with a comparison that holds.
    #[test]
    fn too_few_rungs_above_the_floor_are_blamed_on_round_off() {
        let mut rungs = ladder(|h| 1500.0 * h * h);
        for r in rungs.iter_mut().skip(10) {
            r.round_off_bound = r.error;
            r.round_off_sample = r.error;
        }
        let (_, j) = judged_at_floor(2.0, rungs);
        assert_eq!(j.verdict, Verdict::Inconclusive, "{}", j.reason);
        assert!(
            j.reason.contains("round-off floor, which begins at"),
            "{}",
            j.reason
        );
        let printed = crate::wording::comparisons(&j.reason).expect("readable");
        assert!(
            !printed.is_empty() && printed.iter().all(|c| c.holds()),
            "{}",
            j.reason
        );
        assert!(j.advice.expect("advice").contains("shorten t_end"));
    }

    /// `rungs` with these local orders set from rung `first` on.
    fn with_locals(mut rungs: Vec<Rung>, first: usize, locals: &[f64]) -> Vec<Rung> {
        for (r, &l) in rungs[first..].iter_mut().zip(locals) {
            r.local_order = Some(l);
        }
        rungs
    }

    /// Local orders 1, 1.5, 1.75 rise by steps that halve: the geometric
    /// sequence they start ends at 1.75 + 0.25 (0.5 / 0.5) = 2, exactly the
    /// claim, so a second-order claim is still being approached. Falling
    /// steps or a limit below the claim say nothing of the kind.
    #[test]
    fn local_orders_rising_by_halving_steps_are_heading_for_their_aitken_limit() {
        let rising = with_locals(ladder(|h| h * h), 1, &[0.5, 1.0, 1.5, 1.75]);
        let limit = still_rising_to(2.0, &rising, 0, 4).expect("still rising");
        assert!((limit - 2.0).abs() < 1e-12, "{limit}");
        // heading for 2, which is below a claim of 3 less its tolerance
        assert_eq!(still_rising_to(3.0, &rising, 0, 4), None);
        // the same steps falling are no rise
        let falling = with_locals(ladder(|h| h * h), 1, &[2.5, 2.0, 1.5, 1.25]);
        assert_eq!(still_rising_to(2.0, &falling, 0, 4), None);
    }

    /// Where three local orders are heading, in closed form: steps of 0.5
    /// and 0.25 extrapolate to 4 (Aitken); steps within half the plateau
    /// tolerance are a plateau at their median; steps of 0.9 and 0.6 of the
    /// tolerance, beyond that half, still extrapolate (to `l3 + 1.2 tol`);
    /// steps that grow say nothing.
    #[test]
    fn the_limit_of_three_local_orders_is_aitken_s_or_their_plateau() {
        let limit = local_order_limit(&[3.0, 3.5, 3.75]).expect("a limit");
        assert!((limit - 4.0).abs() < 1e-12, "{limit}");
        let tol = tolerance::plateau_tolerance(4.0);
        let plateau = [4.0, 4.0 + 0.4 * tol, 4.0 + 0.2 * tol];
        assert_eq!(local_order_limit(&plateau), Some(4.0 + 0.2 * tol));
        let l3 = 4.0 + 1.5 * tol;
        let beyond = local_order_limit(&[4.0, 4.0 + 0.9 * tol, l3]).expect("a limit");
        assert!(
            (beyond - (l3 + 1.2 * tol)).abs() < 1e-12,
            "{beyond} against {}",
            l3 + 1.2 * tol
        );
        assert_eq!(local_order_limit(&[3.0, 3.25, 3.75]), None);
        // falling ever faster: at most the last
        assert_eq!(local_order_limit(&[3.0, 2.9, 2.5]), Some(2.5));
    }

    /// A fourth-order claim whose local orders reach 4 on rungs 3 and 4 and
    /// settle at 3 from rung 5 on: an order reduction from 4 to 3 setting in
    /// after rung 4, the last rung on the claim. Local orders on the claim
    /// outside the clean rungs `a..=b` are not read.
    #[test]
    fn local_orders_that_settle_below_the_claim_are_an_order_reduction() {
        let locals = [4.0, 4.0, 3.0, 3.0, 3.0, 3.0, 3.0, 3.0];
        let rungs = with_locals(ladder(|h| h.powi(4)), 3, &locals);
        let found = order_reduction(4.0, &rungs, 2, 10).expect("a reduction");
        assert_eq!(found.from, 4.0);
        assert_eq!(found.to, 3.0);
        assert_eq!(found.sets_in_at, rungs[4].h);
        // the rungs on the claim coarser than the clean ones
        assert_eq!(order_reduction(4.0, &rungs, 4, 10), None);
    }

    /// `rungs` at these steps with errors `h^2`, the clean ones `a..=b` and
    /// the rung after `b` on the round-off floor.
    fn cut_at(hs: &[f64], a: usize, b: usize) -> (Vec<Rung>, Analysis) {
        let mut rungs = ladder(|h| h * h);
        rungs.truncate(hs.len());
        for (r, &h) in rungs.iter_mut().zip(hs) {
            r.h = h;
            r.error = Some(h * h);
            r.round_off_bound = Some(1e-3 * h * h);
        }
        rungs[b + 1].round_off_bound = rungs[b + 1].error;
        let mut dropped = vec![None; hs.len()];
        dropped[b + 1] = Some(DropReason::RoundOff);
        let choice = crate::maths::window::WindowChoice {
            dropped,
            clean: Some((a, b)),
            window: None,
            median_local_order: None,
        };
        let analysis = Analysis {
            choice,
            fit: None,
            trend_systematic: None,
            ci95: None,
        };
        (rungs, analysis)
    }

    /// Round-off cuts the window short when the clean rungs are too few in
    /// number or in halvings: seven rungs over 1.5 halvings are too few
    /// (enough rungs, not enough halvings), seven over exactly
    /// [`MIN_WINDOW_HALVINGS`] are enough.
    #[test]
    fn round_off_cuts_a_window_short_of_rungs_or_of_halvings() {
        let quarter: Vec<f64> = (0..8).map(|k| 2f64.powf(-(k as f64) / 4.0)).collect();
        let (rungs, analysis) = cut_at(&quarter, 0, 6);
        let cut = cut_by_round_off(&rungs, &analysis).expect("cut short");
        assert!(cut.contains("7 rungs over 1.5 halvings"), "{cut}");
        let two = [1.0, 0.9, 0.8, 0.6, 0.4, 0.3, 0.25, 0.2];
        let (rungs, analysis) = cut_at(&two, 0, 6);
        assert_eq!((rungs[0].h / rungs[6].h).log2(), MIN_WINDOW_HALVINGS);
        assert_eq!(cut_by_round_off(&rungs, &analysis), None);
    }

    /// A run converging to the exact motion at order `p >= 1` differs from
    /// its half step by at least a quarter of its error
    /// (`e / d = 1 / (1 - 2^-p) <= 2`, and a factor two for pre-asymptotic
    /// rungs): an error of exactly four differences is still that; more is
    /// convergence to something else.
    #[test]
    fn an_error_more_than_four_half_step_differences_is_convergence_elsewhere() {
        let with_difference = |ratio: f64| {
            let mut rungs = ladder(|h| h * h);
            for r in &mut rungs {
                r.half_step_difference = r.error.map(|e| e / ratio);
            }
            rungs
        };
        assert_eq!(converges_elsewhere(&with_difference(4.0), 1.0), None);
        let found = converges_elsewhere(&with_difference(4.5), 1.0).expect("elsewhere");
        assert!(found.contains("not to the exact solution"), "{found}");
    }

    /// Every rung blew up on a bounded exact motion: a defect where the
    /// finest rung takes at most one radian of the motion's fastest rate a
    /// step, undecided where it takes more (the finest step here is `0.1
    /// 2^-14.5 = 4.3e-6`, so a rate of `2.3e5` is one radian a step).
    #[test]
    fn a_blow_up_on_every_rung_is_a_defect_only_where_the_finest_resolves_the_motion() {
        let mut rungs = ladder(|_| f64::NAN);
        for r in &mut rungs {
            r.error = None;
            r.outcome = Outcome::Unstable {
                h: r.h,
                step: 1,
                time: r.h,
                coordinate: "q[0]".into(),
                value: f64::NAN,
            };
        }
        let analysis = crate::maths::window::analyse(&data(&rungs), 1.0);
        let finest = rungs.last().unwrap().h;
        let at = |rate: f64| {
            judge(
                2.0,
                &rungs,
                &analysis,
                Reference::Exact,
                LadderEnd::Cap,
                1.0,
                &|| rate,
            )
        };
        // the rate at which the finest rung takes exactly the bound, to the bit
        let mut rate = RESOLVED_STEP_RADIANS / finest;
        while finest * rate > RESOLVED_STEP_RADIANS {
            rate = rate.next_down();
        }
        while finest * rate.next_up() <= RESOLVED_STEP_RADIANS {
            rate = rate.next_up();
        }
        assert_eq!(finest * rate, RESOLVED_STEP_RADIANS);
        let resolved = at(rate);
        assert_eq!(resolved.verdict, Verdict::Fail, "{}", resolved.reason);
        assert!(
            resolved.reason.contains("every rung blew up"),
            "{}",
            resolved.reason
        );
        let unresolved = at(rate.next_up());
        assert_eq!(
            unresolved.verdict,
            Verdict::Inconclusive,
            "{}",
            unresolved.reason
        );
        assert!(
            unresolved
                .reason
                .contains("none resolves the motion's fastest time scale"),
            "{}",
            unresolved.reason
        );
        assert!(unresolved.advice.unwrap().contains("raise the step cap"));
    }

    /// No rung resolved the motion (every error ten times the orbit): the
    /// advice depends on what ended the ladder, levels for a fixed one, the
    /// step cap for an automatic one.
    #[test]
    fn unresolved_motion_is_advised_by_how_the_ladder_ended() {
        let rungs = ladder(|_| 10.0);
        let analysis = crate::maths::window::analyse(&data(&rungs), 1.0);
        let advice = |end| {
            // the fastest rate is asked for only when every rung blew up
            let never = || -> f64 { unreachable!("no rung blew up") };
            let j = judge(2.0, &rungs, &analysis, Reference::Exact, end, 1.0, &never);
            assert_eq!(j.verdict, Verdict::Inconclusive, "{}", j.reason);
            assert!(
                j.reason.contains("no rung resolved the motion"),
                "{}",
                j.reason
            );
            j.advice.expect("advice")
        };
        assert!(advice(LadderEnd::Fixed).contains("more levels or a smaller h0"));
        assert!(advice(LadderEnd::Cap).contains("raise the step cap"));
    }

    /// Every rung on the round-off floor, its bound half its error: the
    /// reason gives the share, 0.5 at each of them.
    #[test]
    fn a_ladder_all_on_the_floor_reports_round_off_s_share_of_the_error() {
        let mut rungs = ladder(|h| h * h);
        for r in &mut rungs {
            r.round_off_bound = r.error.map(|e| 0.5 * e);
            r.round_off_sample = r.round_off_bound;
        }
        let (_, j) = judged_at_floor(2.0, rungs);
        assert_eq!(j.verdict, Verdict::Inconclusive, "{}", j.reason);
        let share = format!(
            "the round-off bound is {} to {} of the error",
            figure(0.5),
            figure(0.5)
        );
        assert!(j.reason.contains(&share), "{share} in {}", j.reason);
    }
}
