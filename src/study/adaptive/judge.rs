//! The verdicts of the tolerance ladder: each claim of an adaptive
//! integrator judged against the figures the ladder measured.

use super::record::{
    AdaptiveClaim, EnergyGrowth, JudgedClaim, MIN_FIT_POINTS, Proportionality, RoundTrip,
    TolerancePoint,
};
use crate::maths::fit::power_law;
use crate::scheme::{AdaptiveClaims, RunEnd};
use crate::study::geometry::energy::EnergyClass;
use crate::study::verdict::Verdict;

fn pre_asymptotic_method(claims: &AdaptiveClaims, f: &Proportionality) -> Option<String> {
    let method = f.method_order.as_ref()?;
    let m = f.estimate_power.max(1) as f64;
    // the controller's half of the claim, checked on its own: the accepted
    // steps grow like TOL^(-1/m) (a controller assuming the wrong power
    // still steps by its estimate's, and is refuted here)
    let steps = f.step_scaling.as_ref()?;
    // and the interval must be narrow enough to tell m from its neighbours:
    // -1/m and -1/(m + 1) are 1/(m (m + 1)) apart (-1/(m - 1) is farther), so
    // an interval narrower than that which holds -1/m holds neither of them
    let sharp = steps.ci95[1] - steps.ci95[0] < 1.0 / (m * (m + 1.0));
    let controller = sharp && steps.ci95[0] <= -1.0 / m && -1.0 / m <= steps.ci95[1];
    let above = controller && method.ci95[0] > claims.order as f64;
    let predicted = [method.ci95[0] / m, method.ci95[1] / m];
    let agrees = predicted[0] <= f.ci95[1] && f.ci95[0] <= predicted[1];
    (above && agrees).then(|| {
        format!(
            "the accepted steps grow like TOL^{:.4} [{:.4}, {:.4}], as the controller claims \
             (-1/{}), and at fixed steps over the same step counts the method shows order {:.2} \
             [{:.2}, {:.2}], above its asymptotic {}: its higher error terms still dominate \
             there, and that order over m predicts [{:.3}, {:.3}], which the exponent meets \
             (the asymptotic exponent is beyond the ladder's reach)",
            steps.slope,
            steps.ci95[0],
            steps.ci95[1],
            f.estimate_power,
            method.order,
            method.ci95[0],
            method.ci95[1],
            claims.order,
            predicted[0],
            predicted[1]
        )
    })
}

/// Where the exponent misses from above while the controller is still
/// settling (see the module documentation of the ladder): `k = -p_fix s +
/// rho` with the steps' law nearer the claimed `-1/m` than either
/// neighbour's, the method's fixed-step order reaching `p`, and `rho` wholly
/// above 0. The halfway points are where a measured `s` stops being nearer
/// `-1/m` than `-1/(m - 1)` (below) or `-1/(m + 1)` (above).
fn settling_controller(claims: &AdaptiveClaims, f: &Proportionality) -> Option<String> {
    let theory = f.theory?;
    let method = f.method_order.as_ref()?;
    let steps = f.step_scaling.as_ref()?;
    let ratio = f.error_ratio.as_ref()?;
    let m = f64::from(f.estimate_power.max(1));
    // for m = 1, 1 / (m - 1) is +inf and the lower bound -inf
    let lower = -0.5 * (1.0 / m + 1.0 / (m - 1.0));
    let upper = -0.5 * (1.0 / m + 1.0 / (m + 1.0));
    let faster = f.ci95[0] > theory;
    let controller = lower < steps.ci95[0] && steps.ci95[1] < upper;
    let method_holds = method.ci95[1] >= claims.order as f64;
    let reshaping = ratio.ci95[0] > 0.0;
    (faster && controller && method_holds && reshaping).then(|| {
        format!(
            "the accepted steps grow like TOL^{:.4} [{:.4}, {:.4}], nearer the controller's \
             -1/{} than its neighbours' laws (halfway points {:.4} and {:.4}); at fixed steps \
             over the same step counts the method shows order {:.2} [{:.2}, {:.2}], reaching \
             its {}; and the error over the fixed-step error at the same count goes like \
             TOL^{:.3} [{:.3}, {:.3}]: the controller's distribution of steps is still \
             changing with the tolerance, which makes the error fall faster than its limit \
             law (the asymptotic exponent is beyond the ladder's reach)",
            steps.slope,
            steps.ci95[0],
            steps.ci95[1],
            f.estimate_power,
            lower,
            upper,
            method.order,
            method.ci95[0],
            method.ci95[1],
            claims.order,
            ratio.slope,
            ratio.ci95[0],
            ratio.ci95[1],
        )
    })
}

/// The accepted steps against the tolerance, `N ~ TOL^s`, judged against
/// the controller's `s = -1/m` (steps settle at `h ~ TOL^(1/m)`, see the
/// module documentation): `None` where no exponent is claimed or fewer than
/// three tolerances reached `t_end`. An estimate that shrinks like a lower
/// power `m' < m` of `h` makes the steps grow like `TOL^(-1/m')`; the
/// nearest such law is `m' = m - 1`, so the cost fails when its whole
/// interval lies below the halfway point between `-1/m` and `-1/(m - 1)`:
/// it grows faster than the claimed controller can, and as fast as one
/// with a worse estimate. (Growing slower is cheaper, and refutes nothing.)
pub(super) fn cost_growth(
    claims: &AdaptiveClaims,
    points: &[TolerancePoint],
) -> Option<JudgedClaim> {
    claims.proportionality?;
    let m = f64::from(claims.estimate_power.max(2));
    let steps: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.end == RunEnd::Reached && p.accepted > 0)
        .map(|p| (p.tolerance, p.accepted as f64))
        .collect();
    let fit = power_law(&steps)?;
    let halfway = -0.5 * (1.0 / m + 1.0 / (m - 1.0));
    let refuted = fit.ci95[1] < halfway;
    let why = format!(
        "accepted steps ~ TOL^{:.3} [{:.3}, {:.3}] over {} tolerances, against the controller's TOL^{:.3}{}",
        fit.slope,
        fit.ci95[0],
        fit.ci95[1],
        fit.points,
        -1.0 / m,
        if refuted {
            format!(
                ": the cost grows faster than an estimate of power {m} allows (the whole interval below {halfway:.3}, halfway to power {})",
                m - 1.0
            )
        } else {
            String::new()
        }
    );
    Some(JudgedClaim {
        claim: AdaptiveClaim::Cost,
        verdict: Verdict::from_bool(!refuted),
        reason: why,
    })
}

/// Where the integrator reports what it spent: the report against the
/// calls counted on its force callback. A count is exact, so any
/// difference refutes the report.
pub(super) fn bookkeeping(points: &[TolerancePoint]) -> Option<JudgedClaim> {
    let reported: Vec<_> = points
        .iter()
        .filter_map(|p| p.reported_evaluations.map(|r| (p, r)))
        .collect();
    if reported.is_empty() {
        return None;
    }
    let (verdict, reason) = match reported.iter().find(|(p, r)| *r != p.evaluations) {
        Some((p, r)) => (
            Verdict::Fail,
            format!(
                "at TOL = {:.0e} it reports {r} force evaluations and made {}",
                p.tolerance, p.evaluations
            ),
        ),
        None => (
            Verdict::Pass,
            "its reported force evaluations equal the counted ones".to_string(),
        ),
    };
    Some(JudgedClaim {
        claim: AdaptiveClaim::Evaluations,
        verdict,
        reason,
    })
}

/// The achieved error against the stated bound `error <= factor x TOL`, at
/// every tolerance whose error the ladder resolves (the points the exponent
/// is fitted on: the run reached `t_end`, the error is below the ceiling and
/// at least `1 / ROUND_OFF_SHARE` times the round-off the run can have
/// made). A bound is a bound: the worst ratio above it refutes the claim,
/// and no point resolved leaves it undecided.
pub(super) fn error_factor(
    claims: &AdaptiveClaims,
    points: &[TolerancePoint],
) -> Option<JudgedClaim> {
    let factor = claims.error_factor?;
    let resolved: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.fitted)
        .filter_map(|p| Some((p.tolerance, p.error?)))
        .collect();
    let worst = resolved
        .iter()
        .copied()
        .max_by(|a, b| (a.1 / a.0).total_cmp(&(b.1 / b.0)));
    let (verdict, reason) = match worst {
        None => (
            Verdict::Inconclusive,
            format!(
                "error <= {factor} x TOL claimed, but no tolerance's error is resolved above round-off"
            ),
        ),
        Some((tol, e)) => {
            let ratio = e / tol;
            let holds = ratio <= factor;
            (
                Verdict::from_bool(holds),
                format!(
                    "the error is at most {ratio:.3} x TOL over {} resolved tolerances (at TOL = {tol:.0e}: {e:.3e}), {} the claimed {factor}",
                    resolved.len(),
                    if holds { "within" } else { "above" }
                ),
            )
        }
    };
    Some(JudgedClaim {
        claim: AdaptiveClaim::ErrorFactor,
        verdict,
        reason,
    })
}

/// The fitted exponent against the controller's theory; where it misses,
/// undecided only when the method is shown to be above its order at the
/// ladder's steps, or the controller's steps to be still settling (see the
/// module documentation of the ladder).
pub(super) fn judge_exponent(
    claims: &AdaptiveClaims,
    fit: Option<&Proportionality>,
) -> JudgedClaim {
    let (verdict, reason) = match fit {
        Some(f) if f.theory.is_none() => (
            Verdict::Pass,
            format!(
                "error ~ TOL^{:.3} [{:.3}, {:.3}], measured only: the estimate's power of h \
                 changes along the ladder, so no single exponent is predicted",
                f.exponent, f.ci95[0], f.ci95[1]
            ),
        ),
        // the claim's negation is an error that does not follow the
        // tolerance at all (a controller stuck at one step, say: exponent
        // 0); an interval holding both cannot tell the claim from it
        Some(f) if f.agrees() && f.ci95[0] <= 0.0 && 0.0 <= f.ci95[1] => (
            Verdict::Inconclusive,
            format!(
                "error ~ TOL^{:.3} [{:.3}, {:.3}] contains the predicted {:.3} and 0 too: \
                 the ladder resolves too little of the error's fall (too few tolerances \
                 above round-off, or too short a span of them) to tell the claimed law \
                 from an error that does not follow the tolerance",
                f.exponent,
                f.ci95[0],
                f.ci95[1],
                f.theory.unwrap_or(f64::NAN)
            ),
        ),
        Some(f) if f.agrees() => (
            Verdict::Pass,
            format!(
                "error ~ TOL^{:.3} [{:.3}, {:.3}] contains the predicted {:.3}",
                f.exponent,
                f.ci95[0],
                f.ci95[1],
                f.theory.unwrap_or(f64::NAN)
            ),
        ),
        Some(f) => {
            let missed = format!(
                "error ~ TOL^{:.3} [{:.3}, {:.3}] excludes the predicted {:.3}",
                f.exponent,
                f.ci95[0],
                f.ci95[1],
                f.theory.unwrap_or(f64::NAN)
            );
            match pre_asymptotic_method(claims, f).or_else(|| settling_controller(claims, f)) {
                Some(why) => (Verdict::Inconclusive, format!("{missed}, but {why}")),
                None => (Verdict::Fail, missed),
            }
        }
        None => (
            Verdict::Inconclusive,
            format!("fewer than {MIN_FIT_POINTS} clean tolerances: no exponent fitted"),
        ),
    };
    JudgedClaim {
        claim: AdaptiveClaim::Exponent,
        verdict,
        reason,
    }
}

/// The long run's energy: a drift refutes a symplecticity or symmetry
/// claim; without one, nothing is claimed and the class is only shown.
pub(super) fn judge_energy(claims: &AdaptiveClaims, e: &EnergyGrowth) -> JudgedClaim {
    let class = e.class.map_or("unclassified", |c| c.name());
    let conserves = claims.symplectic || claims.symmetric;
    let (verdict, reason) = if conserves && e.class == Some(EnergyClass::Drifting) {
        (
            Verdict::Fail,
            format!("energy {class}, against a conservation claim"),
        )
    } else {
        (Verdict::Pass, format!("energy {class} (nothing claimed)"))
    };
    JudgedClaim {
        claim: AdaptiveClaim::Energy,
        verdict,
        reason,
    }
}

/// The round trip: missing the start refutes a symmetry claim.
pub(super) fn judge_round_trip(claims: &AdaptiveClaims, r: &RoundTrip) -> JudgedClaim {
    let (verdict, reason) = if claims.symmetric && !r.returns {
        (
            Verdict::Fail,
            "the round trip misses the start, against a symmetry claim".to_string(),
        )
    } else if r.returns {
        (
            Verdict::Pass,
            "the round trip returns to round-off".to_string(),
        )
    } else {
        (
            Verdict::Pass,
            "the round trip misses the start (not symmetric, as claimed)".to_string(),
        )
    };
    JudgedClaim {
        claim: AdaptiveClaim::RoundTrip,
        verdict,
        reason,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maths::fit::{OrderFit, PowerLaw};

    /// A 4(5) pair's claims: order 4, an estimate like `h^5`.
    const CLAIMS: AdaptiveClaims = AdaptiveClaims {
        order: 4,
        estimate_power: 5,
        proportionality: Some(0.8),
        symplectic: false,
        symmetric: false,
        error_factor: None,
    };

    fn order_fit(ci95: [f64; 2]) -> OrderFit {
        OrderFit {
            order: 0.5 * (ci95[0] + ci95[1]),
            standard_error: 0.0,
            corrections: [None],
            t_quantile: 2.0,
            systematic: 0.0,
            ci95,
            points: 6,
            line: power_law_with(ci95),
        }
    }

    fn power_law_with(ci95: [f64; 2]) -> PowerLaw {
        PowerLaw {
            slope: 0.5 * (ci95[0] + ci95[1]),
            intercept: 0.0,
            ci95,
            standard_error: 0.0,
            correlation: -1.0,
            points: 6,
        }
    }

    /// A fit of `error ~ TOL^k` whose method shows order [5.2, 5.6] at fixed
    /// steps (above its asymptotic 4, so `k` near 5.4 / 5), and whose
    /// accepted steps follow `TOL^s` with `s` in `steps`.
    fn fitted(steps: [f64; 2]) -> Proportionality {
        Proportionality {
            exponent: 1.05,
            ci95: [1.0, 1.1],
            estimate_power: 5,
            fit: order_fit([5.0, 5.5]),
            range: [1e-4, 1e-10],
            theory: Some(0.8),
            method_order: Some(order_fit([5.2, 5.6])),
            step_scaling: Some(power_law_with(steps)),
            error_ratio: None,
        }
    }

    /// The controller's `-1/5` is told from its neighbours only by an
    /// interval narrower than `1/5 - 1/6 = 1/30`: [-0.205, -0.195] confirms
    /// it, but [-0.21, -0.16] also holds `-1/6`, a controller of power 6,
    /// and so cannot excuse the exponent.
    #[test]
    fn only_a_step_law_sharper_than_its_neighbours_excuses_the_exponent() {
        assert!(pre_asymptotic_method(&CLAIMS, &fitted([-0.205, -0.195])).is_some());
        let wide = [-0.21, -0.16];
        assert!(wide[0] <= -1.0 / 6.0 && -1.0 / 6.0 <= wide[1]);
        assert!(pre_asymptotic_method(&CLAIMS, &fitted(wide)).is_none());
    }

    /// A 6(4) pair with local extrapolation: order 6, an estimate like
    /// `h^5`, error `~ TOL^(6/5)`.
    const CLAIMS_6: AdaptiveClaims = AdaptiveClaims {
        order: 6,
        estimate_power: 5,
        proportionality: Some(1.2),
        ..CLAIMS
    };

    /// A miss of the 6(4) pair's `6/5` with the exponent in `exponent`, the
    /// steps' law in `steps`, the method's fixed-step order in `method` and
    /// the error ratio's slope in `ratio` (each an interval). `settled()`
    /// is DPRKN6(4) on the oscillator, as the ladder measures it: steps
    /// [-0.1967, -0.1845] over the six fitted tolerances, order [5.99,
    /// 6.01], ratio [0.045, 0.124], exponent [1.201, 1.252].
    fn missed(
        exponent: [f64; 2],
        steps: [f64; 2],
        method: [f64; 2],
        ratio: [f64; 2],
    ) -> Proportionality {
        Proportionality {
            exponent: 0.5 * (exponent[0] + exponent[1]),
            ci95: exponent,
            estimate_power: 5,
            fit: order_fit([5.0 * exponent[0], 5.0 * exponent[1]]),
            range: [1e-3, 1e-8],
            theory: Some(1.2),
            method_order: Some(order_fit(method)),
            step_scaling: Some(power_law_with(steps)),
            error_ratio: Some(power_law_with(ratio)),
        }
    }

    const SETTLING: [[f64; 2]; 4] = [
        [1.201, 1.252],
        [-0.1967, -0.1845],
        [5.99, 6.01],
        [0.045, 0.124],
    ];

    fn settling_with(i: usize, interval: [f64; 2]) -> Option<String> {
        let mut x = SETTLING;
        x[i] = interval;
        settling_controller(&CLAIMS_6, &missed(x[0], x[1], x[2], x[3]))
    }

    /// The settling controller is excused only with all three halves shown;
    /// each defect the module documentation names removes one of them.
    #[test]
    fn a_controller_still_settling_is_told_from_each_defect() {
        let why = settling_with(0, SETTLING[0]).expect("DPRKN6 on the oscillator");
        assert!(why.contains("-0.2250") && why.contains("-0.1833"), "{why}");
        // the tolerance scaled as TOL^1.1: steps like TOL^-0.22, inside the
        // halfway points, but the distribution of steps does not change
        assert!(settling_with(3, [-0.01, 0.02]).is_none());
        assert!(settling_with(3, [0.0, 0.02]).is_none());
        // a controller of power 6 (steps like TOL^-1/6) or 4 (TOL^-1/4)
        assert!(settling_with(1, [-0.19, -0.18]).is_none());
        assert!(settling_with(1, [-0.26, -0.24]).is_none());
        assert!(settling_with(1, [-0.224, -0.19]).is_some());
        // an interval reaching a halfway point is as near the neighbour
        let halfway = [
            -0.5 * (1.0 / 5.0 + 1.0 / 4.0),
            -0.5 * (1.0 / 5.0 + 1.0 / 6.0),
        ];
        assert!(settling_with(1, [halfway[0], -0.19]).is_none());
        assert!(settling_with(1, [-0.21, halfway[1]]).is_none());
        // a method below its order
        assert!(settling_with(2, [5.5, 5.9]).is_none());
        assert!(settling_with(2, [5.5, 6.0]).is_some());
        // an error falling slower than claimed: advancing with the fourth
        // order solution against a sixth-order fixed-step method
        assert!(settling_with(0, [0.78, 0.82]).is_none());
        assert!(settling_with(0, [1.2, 1.3]).is_none());
        // for m = 1 only the upper neighbour -1/2 bounds the steps
        let one = AdaptiveClaims {
            estimate_power: 1,
            ..CLAIMS_6
        };
        let mut p = missed(SETTLING[0], [-3.0, -0.8], SETTLING[2], SETTLING[3]);
        p.estimate_power = 1;
        assert!(settling_controller(&one, &p).is_some());
        p.step_scaling = Some(power_law_with([-3.0, -0.7]));
        assert!(settling_controller(&one, &p).is_none());
    }

    /// Accepted steps `N = 1e6 (TOL / 1e-3)^s` at eight tolerances, 1e-3 to
    /// 1e-10.
    fn steps_like(s: f64) -> Vec<TolerancePoint> {
        (3..11)
            .map(|k| {
                let tolerance = 10f64.powi(-k);
                let accepted = (1e6 * (tolerance / 1e-3).powf(s)).round() as u64;
                TolerancePoint {
                    tolerance,
                    evaluations: 6 * accepted,
                    accepted,
                    rejected: 0,
                    end: RunEnd::Reached,
                    error: None,
                    round_off: 0.0,
                    fitted: true,
                    reported_evaluations: None,
                    breakdown: None,
                }
            })
            .collect()
    }

    /// With an estimate like `h^5` the steps grow like `TOL^(-1/5)`; an
    /// estimate that is really `h^4` makes them grow like `TOL^(-1/4)`,
    /// past the halfway point -0.225, and refutes the cost.
    #[test]
    fn steps_growing_as_a_lower_power_s_refute_the_cost() {
        let claimed = cost_growth(&CLAIMS, &steps_like(-0.2)).unwrap();
        assert_eq!(claimed.verdict, Verdict::Pass, "{}", claimed.reason);
        let slower = cost_growth(&CLAIMS, &steps_like(-0.22)).unwrap();
        assert_eq!(slower.verdict, Verdict::Pass, "{}", slower.reason);
        let lower = cost_growth(&CLAIMS, &steps_like(-0.25)).unwrap();
        assert_eq!(lower.verdict, Verdict::Fail, "{}", lower.reason);
        assert!(lower.reason.contains("-0.225"), "{}", lower.reason);
    }
}
