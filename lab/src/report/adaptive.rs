//! The report's "Adaptive step control" section: the tolerance ladders of
//! the crate's own pairs and the peers, what a passing exponent tells
//! (with a pair whose controller assumes the wrong power) (deterministic),
//! and their wall times (machine-dependent).

use super::markdown::{Table, opt, order, sci};
use crate::suite::adaptive::{AdaptiveRecords, SLIPPED_PAIR};
use std::fmt::Write as _;
use stepladder::internals::adaptive::ladder::{
    ENERGY_PERIODS, GEOMETRY_TOLERANCE, ROUND_OFF_SHARE,
};
use stepladder::internals::adaptive::record::{MIN_FIT_POINTS, ToleranceLadderRecord};
use stepladder::internals::tolerance::ERROR_CEILING;
use stepladder::scheme::AdaptiveIntegrator;

/// The tolerances whose costs the summary table shows.
pub const SHOWN_TOLERANCES: [f64; 3] = [1e-6, 1e-9, 1e-12];

/// The deterministic section.
pub fn adaptive_section(records: &AdaptiveRecords) -> String {
    let mut out = String::from("\n## Adaptive step control\n\n");
    out.push_str(&method());
    out.push_str(&summary_table(&records.ladders));
    out.push_str(&resolution(&records.ladders, &records.slipped));
    out.push_str("\nEvery tolerance is on [a detail page](details/adaptive-tolerances.md).\n");
    out
}

fn method() -> String {
    format!(
        "Each adaptive integrator runs from the scene's initial state to the order \
         study's `t_end` at relative and absolute tolerance `TOL`, one a decade, and is \
         judged like a fixed-step ladder: its error is the largest phase-space distance \
         to the exact solution over its accepted steps, its cost the force evaluations it \
         spent (rejected steps and the first step's guess included). An error-per-step \
         controller whose estimate behaves like `h^m`, advancing with an order-`p` \
         solution, settles at steps `h ~ TOL^(1/m)` and a global error `~ TOL^(p/m)` \
         (Hairer, Nørsett, Wanner I, II.4): `6/5` for DPRKN6(4) (`m = q + 1 = 5`), `8/7` for \
         DPRKN8(6), `9/9 = 1` for Verner's 9(8) pair (its PID controller, like any, \
         settles where the estimate is a fixed fraction of the tolerance). Where a pair's exponent misses, its accepted steps are fitted against \
         `TOL` (the controller's half of the claim, `N ~ TOL^(-1/m)`) and its method is run \
         at fixed steps over the same step counts (the method's half): a method still above \
         its asymptotic order at those steps, with the exponent that order predicts, leaves \
         the verdict undecided. So does a controller still settling: the exponent is exactly \
         `-p_fix s + rho`, with `s` the steps' law, `p_fix` the method's order at those \
         steps and `rho` the slope of the error over the equal-step error at the same count, \
         which is 0 once the distribution of steps over the run stops changing; an error \
         falling faster than claimed, with `s` nearer `-1/m` than either neighbour's law, \
         `p_fix` reaching `p` and `rho` wholly above 0, is undecided. Anything else fails \
         it. DOP853's \
         estimate `h err5^2 / sqrt(err5^2 + 0.01 err3^2)` behaves like `h^6` while its \
         fifth-order part dominates and like `h^8` once the third-order one does, so its \
         exponent moves from 4/3 towards 1 along the ladder and is measured, not judged. \
         The exponent is fitted as the order study fits an order, in `x = TOL^(1/m)`, with \
         the fit's interval over `m`, over the points that reached `t_end` with an error below {ERROR_CEILING} and at least {} times the \
         round-off bound `8 eps N scale` (at least {MIN_FIT_POINTS} points). At `TOL = \
         {}` an energy run of {ENERGY_PERIODS} periods is classified by the growth of \
         `|E - E(T)|` over its last two decades, and a round trip (to `t_end`, velocities \
         reversed, back) is compared with the reversibility study's round-off bound. \
         None of these integrators claims to be symplectic or symmetric, so the energy is \
         expected to drift and the round trip to miss by about the global error (where the \
         energy stays bounded instead, that is reported, not failed).\n\n",
        1.0 / ROUND_OFF_SHARE,
        sci(GEOMETRY_TOLERANCE),
    )
}

/// Whether the interval `ci` of an exponent holds the claim of a controller
/// that assumes its estimate one power below or above `power`:
/// `order / (power - 1)` (for `power > 1`) or `order / (power + 1)`.
pub fn holds_a_neighbour(order: u32, power: u32, ci: [f64; 2]) -> bool {
    let (p, m) = (f64::from(order), f64::from(power));
    let below = (power > 1).then(|| p / (m - 1.0));
    [below, Some(p / (m + 1.0))]
        .into_iter()
        .flatten()
        .any(|k| ci[0] <= k && k <= ci[1])
}

/// What a passing exponent tells: the ladders whose interval holds a
/// neighbouring power's claim as well, and the slipped controller's
/// ladders.
fn resolution(ladders: &[ToleranceLadderRecord], slipped: &[ToleranceLadderRecord]) -> String {
    // the ladders whose exponent agrees with a claimed one, with its interval
    let agreeing: Vec<(&ToleranceLadderRecord, [f64; 2])> = ladders
        .iter()
        .filter_map(|r| {
            let p = r.proportionality.as_ref()?;
            (p.theory.is_some() && p.agrees()).then_some((r, p.ci95))
        })
        .collect();
    // grouped by integrator, in table order
    let mut unresolved: Vec<(&str, Vec<String>)> = Vec::new();
    for &(r, ci) in &agreeing {
        if !holds_a_neighbour(r.claims.order, r.claims.estimate_power, ci) {
            continue;
        }
        let scene = format!("`{}`", r.scene);
        match unresolved
            .iter_mut()
            .find(|(name, _)| *name == r.integrator)
        {
            Some((_, scenes)) => scenes.push(scene),
            None => unresolved.push((r.integrator, vec![scene])),
        }
    }
    let count: usize = unresolved.iter().map(|(_, scenes)| scenes.len()).sum();
    let unresolved: Vec<String> = unresolved
        .into_iter()
        .map(|(name, scenes)| format!("{name} on {}", scenes.join(", ")))
        .collect();
    let slips: Vec<String> = slipped
        .iter()
        .map(|r| {
            let k = r
                .proportionality
                .as_ref()
                .map_or("no exponent".into(), |p| {
                    format!(
                        "{} [{}, {}]",
                        order(p.exponent),
                        order(p.ci95[0]),
                        order(p.ci95[1])
                    )
                });
            format!("`{}` {k}, {}", r.scene, r.verdict.name())
        })
        .collect();
    let slipped_claims = SLIPPED_PAIR.claims();
    format!(
        "\nWhat a pass tells. A controller that assumed its estimate one power lower or higher \
         would claim `p/(m-1)` or `p/(m+1)`, `p/(m(m-1))` and `p/(m(m+1))` away from `p/m`, and \
         its steps would follow the estimate's own power just the same (a controller of any \
         power settles where its estimate is a fixed fraction of the tolerance): only the \
         exponent's interval tells those claims apart. Of the {} ladders above whose exponent \
         agrees with its claim, {} have an interval that holds a neighbour's claim as well: \
         {}. There the errors agree with the claim without telling the controller's power from \
         its neighbours'. DPRKN6(4) built with a controller for `h^{m}` (claiming `{p}/{m}`: \
         the estimate's order taken for its power) shows what that lets through; its exponent \
         and verdict on each scene: {}.\n",
        agreeing.len(),
        count,
        if unresolved.is_empty() {
            "none".to_string()
        } else {
            unresolved.join("; ")
        },
        slips.join("; "),
        p = slipped_claims.order,
        m = slipped_claims.estimate_power,
    )
}

/// One line per integrator and scene: exponent against theory, cost and
/// error at a few tolerances, energy class and round trip.
pub fn summary_table(records: &[ToleranceLadderRecord]) -> String {
    let mut header: Vec<String> = [
        "integrator",
        "scene",
        "error ~ TOL^k",
        "95% interval",
        "theory",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    for tol in SHOWN_TOLERANCES {
        header.push(format!("evals / error at {tol:.0e}"));
    }
    header.extend([
        "energy at 1e-8".to_string(),
        "round trip".into(),
        "verdict".into(),
    ]);
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut t = Table::new(&header);
    for r in records {
        let mut row = vec![r.integrator.to_string(), format!("`{}`", r.scene)];
        match &r.proportionality {
            Some(p) => row.extend([
                order(p.exponent),
                format!("[{}, {}]", order(p.ci95[0]), order(p.ci95[1])),
                p.theory.map_or("measured only".into(), order),
            ]),
            None => row.extend([
                "-".into(),
                "-".into(),
                r.claims
                    .proportionality
                    .map_or("measured only".into(), order),
            ]),
        }
        for tol in SHOWN_TOLERANCES {
            row.push(r.at(tol).map_or("-".into(), |p| {
                format!("{} / {}", p.evaluations, opt(p.error, sci))
            }));
        }
        row.push(r.energy.map_or("-".into(), |e| {
            format!(
                "{} (g = {})",
                e.class.map_or("-", |c| c.name()),
                opt(e.growth_exponent, |g| format!("{g:.2}"))
            )
        }));
        row.push(r.round_trip.map_or("-".into(), |rt| {
            format!(
                "{} ({})",
                opt(rt.distance, sci),
                if rt.returns { "returns" } else { "misses" }
            )
        }));
        row.push(r.verdict.name().to_string());
        t.row(row);
    }
    t.render()
}

/// Every tolerance of one ladder.
pub fn ladder_table(r: &ToleranceLadderRecord) -> String {
    let mut t = Table::new(&[
        "TOL",
        "evaluations",
        "accepted",
        "rejected",
        "end",
        "error",
        "round-off bound",
        "fitted",
    ]);
    for p in &r.points {
        t.row(vec![
            sci(p.tolerance),
            p.evaluations.to_string(),
            p.accepted.to_string(),
            p.rejected.to_string(),
            p.end.name().to_string(),
            opt(p.error, sci),
            sci(p.round_off),
            if p.fitted { "yes" } else { "no" }.to_string(),
        ]);
    }
    let mut out = t.render();
    let _ = writeln!(out, "\n{}: {}.", r.verdict.name(), r.reason);
    out
}

/// The wall time of each ladder (machine-dependent).
pub fn timing_section(records: &AdaptiveRecords) -> String {
    let mut out = String::from("\n### Adaptive tolerance ladders\n\n");
    let mut t = Table::new(&["integrator", "scene", "wall time"]);
    for (r, time) in records.ladders.iter().zip(&records.times) {
        t.row(vec![
            r.integrator.to_string(),
            format!("`{}`", r.scene),
            format!("{:.1} ms", time.as_secs_f64() * 1e3),
        ]);
    }
    out.push_str(&t.render());
    out
}
