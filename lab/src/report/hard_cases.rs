//! The report's "Hard cases" section: eccentric orbits, the separatrix, and
//! escape or trapped. Every figure comes from a record; numbers are rounded
//! to a few significant digits so the section is the same on any machine.

use super::markdown::{Table, opt, sci};
use crate::suite::hard_cases::{ESCAPE_DELTAS, HardCases, NAIVE_STEP};
use std::fmt::Write as _;
use stepladder::internals::hard::eccentric::{
    ECCENTRICITIES, EccentricEnergyRecord, EccentricOrderRecord, KickLag, OrbitEnergy, OrderStatus,
    RoundOffRecord, kick_lag, short_ratio,
};
use stepladder::internals::hard::escape::{EscapeRecord, Misclassified};
use stepladder::internals::hard::following::{Event, FollowingRecord, LineFit};
use stepladder::internals::tolerance;
use stepladder::scheme::scheme_ids;

/// The whole section.
pub fn hard_cases_section(hard: &HardCases) -> String {
    let mut out = String::from("## Hard cases\n\n");
    let _ = writeln!(
        out,
        "Three problems where a fixed step meets a sharp feature of the flow. They cost {} \
         steps in all, {} of them compared with an exact Kepler orbit (the dearest); the \
         timings below give the seconds.\n",
        hard.steps(),
        hard.exact_steps()
    );
    out.push_str(&summary(hard));
    out.push_str(&eccentric_section(hard));
    out.push_str(&separatrix_section(hard));
    out.push_str(&escape_section(hard));
    out
}

/// One line per study: what it concluded, counted.
fn summary(hard: &HardCases) -> String {
    let count = |status: OrderStatus| hard.orders.iter().filter(|r| r.status == status).count();
    let following = |v: Option<bool>| hard.following.iter().filter(|r| r.consistent == v).count();
    let classified = hard
        .escape
        .iter()
        .filter(|r| r.largest_correct.is_some())
        .count();
    format!(
        "- Eccentric orbits: of {} order studies, {} pass, {} fail, {} are pre-asymptotic and {} \
         unresolved at the affordable steps (each explained below).\n\
         - Separatrix: {} of {} schemes follow it for `ln(64 E_b/|dE|)/(2 lambda)` with `dE ~ \
         h^q`, as the linearised theory says; {} fail; for {} the law in `dE` holds but the \
         offsets reach round-off before their exponent `q` is resolved (undecided).\n\
         - Escape or trapped: {} of {} scheme and gap pairs classify both orbits correctly below \
         a largest step.\n\n",
        hard.orders.len(),
        count(OrderStatus::Pass),
        count(OrderStatus::Fail),
        count(OrderStatus::PreAsymptotic),
        count(OrderStatus::Unresolved),
        following(Some(true)),
        hard.following.len(),
        following(Some(false)),
        following(None),
        classified,
        hard.escape.len(),
    )
}

fn eccentric_section(hard: &HardCases) -> String {
    let mut out = String::from("### Eccentric Kepler orbits\n\n");
    let _ = writeln!(
        out,
        "The orbit of the order table (`GM = 4 pi^2`, `a = 1`, started at pericentre) at \
         `e = {}`. Near pericentre it turns within a few `tau_p = r_p/v_p = (1-e)^(3/2) / \
         ((1+e)^(1/2) n)` (`n = 2 pi` per year); a step that is not small against `tau_p` \
         mistimes the passage, and while one orbit swings round and the other has not, the \
         phase-space error is of the order of the pericentre speed `v_p/w = sqrt((1+e)/(1-e))` \
         in the error's length units, whatever the scheme's order.\n",
        ECCENTRICITIES.map(|e| e.to_string()).join(", ")
    );
    let _ = writeln!(
        out,
        "- **Orders.** The automatic ladder of the order table over {:.4} periods (one full \
         passage after the start's half passage), with `max(2, ceil(p/2))` rungs a halving as \
         there, down to the round-off floor or until a rung would exceed {} steps. `pass`/`fail` is the order table's verdict; \
         `unresolved` means every rung's largest error exceeds {} of the orbit (the passage \
         is not resolved at any affordable step), `pre-asymptotic` that too few resolved \
         rungs settle on one order to fit. The order of the error at `t_end` alone is shown \
         beside. The two-step Störmer form and leap-frog are velocity Verlet's map (same \
         positions at whole steps, same synchronised velocities), so their ladders would \
         repeat velocity Verlet's; their round-off is measured below instead.",
        tolerance::ECCENTRIC_PERIODS,
        tolerance::ECCENTRIC_MAX_RUNG_STEPS,
        tolerance::ERROR_CEILING,
    );
    let _ = writeln!(
        out,
        "- **Energy.** {} periods at `h = tau_p/{}` (the same resolution of every passage) \
         and at the main energy study's step of {} period. The energy at each numerical \
         apocentre is compared along the run: `bounded` when it returns to the same value \
         after every passage (within {} of its offset from `E0`, plus round-off), `drifting` \
         when it changes, `lost` when the orbit becomes unbound or stops returning. \
         `max dE/E` is the largest relative error over the run; in brackets the same times \
         `(1-e)/2`, the error relative to the pericentre's energy scale `GM/r_p`: a passage \
         resolved by a fixed number of steps per `tau_p` is self-similar as `e -> 1`, so \
         this figure should not depend on `e` while `max dE/E` grows like `2/(1-e)`.\n",
        tolerance::ECCENTRIC_ENERGY_PERIODS,
        tolerance::ENERGY_STEPS_PER_PERICENTRE,
        NAIVE_STEP,
        tolerance::ECCENTRIC_DRIFT_FRACTION,
    );
    out.push_str(&eccentric_order_table(&hard.orders));
    for r in &hard.orders {
        if let Some(k) = kick_lag(r) {
            out.push_str(&kick_lag_note(r, &k));
        }
    }
    out.push_str("\n#### Energy at `h = tau_p/8`\n\n");
    out.push_str(&eccentric_energy_grid(&hard.energy));
    let _ = writeln!(
        out,
        "\n#### Energy at the main study's step, `h = {NAIVE_STEP}` period\n"
    );
    out.push_str(&eccentric_energy_grid(&hard.naive_energy));
    out.push_str("\n#### Round-off of the two-step Störmer form\n\n");
    out.push_str(
        "Störmer-Verlet, leap-frog and velocity Verlet run side by side at `h = tau_p/8`; \
         in exact arithmetic they coincide, so their phase-space distance is round-off alone, \
         shown in units of `eps * scale` before the first full pericentre passage (first 3/4 \
         period) and after it.\n\n",
    );
    out.push_str(&round_off_table(&hard.round_off));
    out.push('\n');
    out
}

/// Why Euler-Cromer measures second order on an eccentric orbit where it
/// claims first.
fn kick_lag_note(r: &EccentricOrderRecord, k: &KickLag) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\nEuler-Cromer at `e = {}` shows second order where it claims first: its \
         whole-step velocities are leap-frog's half-step ones and lag by `h a/2`, at \
         pericentre a first-order error `L h` with `L = a_p/(2w) = {:.1}` in phase units, \
         while the second-order error of the passage is `C h^2` with `C = {}` (the \
         window's finest rung). The first-order term can dominate only below `h = L/C = \
         {}` (tau_p/{}), a rung of {} steps, beyond the cap. An order above the \
         claim refutes nothing, so the verdict passes; the table's order is this, not a \
         more accurate scheme.",
        r.pericentre.e,
        k.lag_coefficient,
        sci(k.second_order_coefficient),
        sci(k.crossover),
        short_ratio(r.pericentre.time_scale / k.crossover),
        sci(k.crossover_steps),
    );
    out
}

/// One row per scheme and eccentricity.
pub fn eccentric_order_table(records: &[EccentricOrderRecord]) -> String {
    let mut t = Table::new(&[
        "scheme",
        "e",
        "tau_p",
        "theory",
        "status",
        "order",
        "interval",
        "order at t_end",
        "resolved below h",
        "finest h",
        "why",
    ]);
    for r in records {
        let p = &r.pericentre;
        let tau = |h: f64| format!("{} (tau_p/{})", sci(h), short_ratio(p.time_scale / h));
        t.row(vec![
            format!("`{}`", r.scheme),
            p.e.to_string(),
            sci(p.time_scale),
            r.theoretical_order.to_string(),
            match r.status.name() {
                "fail" => "**fail**".to_string(),
                s => s.to_string(),
            },
            opt(r.measured_order, |x| format!("{x:.3}")),
            r.ci95
                .map_or("-".into(), |c| format!("[{:.3}, {:.3}]", c[0], c[1])),
            opt(r.final_order, |x| format!("{x:.3}")),
            opt(r.resolved_below, tau),
            opt(r.rungs.last().map(|g| g.h), tau),
            r.reason.clone(),
        ]);
    }
    t.render()
}

/// Schemes down, eccentricities across.
pub fn eccentric_energy_grid(records: &[EccentricEnergyRecord]) -> String {
    // the eccentricities run, in the order first met (the defaults, or what
    // the command asked for)
    let mut eccentricities: Vec<f64> = Vec::new();
    for r in records {
        if !eccentricities.contains(&r.pericentre.e) {
            eccentricities.push(r.pericentre.e);
        }
    }
    let mut header = vec!["scheme".to_string()];
    header.extend(eccentricities.iter().map(|e| format!("e = {e}")));
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut t = Table::new(&header);
    let mut ids: Vec<&str> = Vec::new();
    for r in records {
        if !ids.contains(&r.scheme) {
            ids.push(r.scheme);
        }
    }
    for id in ids {
        let mut row = vec![format!("`{id}`")];
        for &e in &eccentricities {
            let cell = records
                .iter()
                .find(|r| r.scheme == id && r.pericentre.e == e)
                .map_or("-".to_string(), energy_cell);
            row.push(cell);
        }
        t.row(row);
    }
    t.render()
}

fn energy_cell(r: &EccentricEnergyRecord) -> String {
    match (r.lost_at, r.class) {
        (Some(t), _) => format!("lost at t = {}", sci(t)),
        (None, OrbitEnergy::Lost) => format!(
            "lost: {} apocentre{} in {} periods, {}",
            r.apocentres,
            if r.apocentres == 1 { "" } else { "s" },
            r.periods,
            sci(r.max_relative_error)
        ),
        _ => format!(
            "{} {} ({})",
            r.class.name(),
            sci(r.max_relative_error),
            sci(r.max_pericentre_relative_error)
        ),
    }
}

/// One row per eccentricity.
pub fn round_off_table(records: &[RoundOffRecord]) -> String {
    let mut t = Table::new(&[
        "e",
        "h",
        "Störmer - Verlet, before",
        "after",
        "leap-frog - Verlet, before",
        "after",
    ]);
    for r in records {
        let u = |d: f64| sci(d / (f64::EPSILON * r.scale));
        t.row(vec![
            r.pericentre.e.to_string(),
            sci(r.h),
            u(r.stormer_before),
            u(r.stormer_after),
            u(r.leapfrog_before),
            u(r.leapfrog_after),
        ]);
    }
    t.render()
}

fn separatrix_section(hard: &HardCases) -> String {
    let mut out = String::from("### Following the separatrix\n\n");
    let lambda = hard.following.first().map_or(f64::NAN, |r| r.lambda);
    let well = hard.following.first().map(|r| r.well);
    let _ = writeln!(
        out,
        "The anharmonic well at exactly the barrier energy ({}), started at the bottom: \
         `x = alpha tanh(lambda t/2)` creeps up to the barrier top for ever. Linearising the \
         force at `x = alpha` gives `u'' = lambda^2 u` with `lambda = sqrt(2k) = {lambda:.4}` \
         (the slope of `-k x + k x^3/alpha^2` there is `2k`; `sqrt(k)` is the frequency at the \
         bottom). A numerical orbit that reaches the top with an energy error `dE` turns back \
         (`dE < 0`: the velocity reaches zero with `x < alpha`, **falls back**) or crosses \
         (`dE > 0`: `x` reaches `alpha`, **escapes**) at its closest approach, at `T = \
         ln(64 E_b/|dE|) / (2 lambda)` (the leading term of the trapped quarter period \
         `K(m)/Omega`); its distance from the separatrix reaches a fixed size `D = {}` alpha \
         at `T_D = ln(const/|dE|)/lambda`. With `dE ~ E_b c h^q` the following time grows like \
         `(q/(2 lambda)) ln(1/h)` and the departure time like `(q/lambda) ln(1/h)`. For a \
         symplectic splitting `q` is its order unless the leading term of its modified \
         Hamiltonian vanishes at the start as it does at the top (`v = 0`, `V' = 0`): Euler-Cromer's \
         first-order term is proportional to `V'(x) v`, zero at both ends, so its `q` is 2. \
         Velocity Verlet's `H_2 = V''(v,v)/12 - |V'|^2/24` predicts `c = +k/6` (it escapes), \
         position Verlet's `-V''(v,v)/24 + |V'|^2/12` predicts `c = -k/12` (it falls back). \
         RK4 is not symplectic; its measured `q` is one more than its order.\n",
        well.map_or(String::new(), |w| format!(
            "`k = {}`, `alpha = {}`",
            w.k, w.alpha
        )),
        tolerance::DEPARTURE_FRACTION,
    );
    let _ = writeln!(
        out,
        "The ladder runs from `h = 1/sqrt(k)` by `2^(-1/2)` (`2^(-2/p)` above fourth order) \
         until the energy offsets' local exponents settle or reach round-off; the fits use the \
         window of rungs (chosen as in the order table) whose offset is below {} `E_b`. \
         `consistent` requires the slope against `ln(E_b/|dE|)` within {}% of `1/(2 lambda) \
         = {:.4}` and the slope against `ln(1/h)` within as much of `q/(2 lambda)` with the \
         measured `q`. `longest T` is the longest following time measured; where a ladder \
         reached the round-off floor, it is the limit round-off sets: an energy error of a \
         few `eps E_b` gives about `ln(64/eps)/(2 lambda)` = {:.1}.\n",
        tolerance::SEPARATRIX_OFFSET_CEILING,
        100.0 * tolerance::SEPARATRIX_SLOPE_TOLERANCE,
        1.0 / (2.0 * lambda),
        (64.0 / f64::EPSILON).ln() / (2.0 * lambda),
    );
    out.push_str(&following_table(&hard.following));
    out.push_str("\nEvery rung is on [a detail page](details/separatrix-rungs.md).\n");
    out
}

/// Four significant digits, without an exponent from 0.1 to 1000.
fn num(x: f64) -> String {
    let a = x.abs();
    if (0.1..1000.0).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.3e}")
    }
}

/// A number as given when it reads well that way, else with an exponent.
fn plain(x: f64) -> String {
    if (1e-3..1e4).contains(&x.abs()) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}

fn slope(f: Option<LineFit>) -> String {
    f.map_or("-".into(), |f| {
        format!("{} [{}, {}]", num(f.slope), num(f.ci95[0]), num(f.ci95[1]))
    })
}

/// One row per scheme.
pub fn following_table(records: &[FollowingRecord]) -> String {
    let mut t = Table::new(&[
        "scheme",
        "p",
        "event",
        "dE/E_b = c h^q",
        "T vs ln(1/h)",
        "q/(2 lambda)",
        "p/(2 lambda)",
        "T vs ln(E_b/dE)",
        "T_D vs ln(1/h)",
        "q/lambda",
        "window h",
        "longest T",
        "consistent",
    ]);
    for r in records {
        let two_l = 2.0 * r.lambda;
        let q = r.offset_law.map(|l| l.slope);
        t.row(vec![
            format!("`{}`", r.scheme),
            r.order.to_string(),
            r.event.map_or("mixed".into(), |e| e.name().to_string()),
            match (r.offset_coefficient, q) {
                (Some(c), Some(q)) => format!("c = {c:+.3e}, q = {q:.3}"),
                _ => "-".into(),
            },
            slope(r.slope_in_step),
            opt(q, |q| num(q / two_l)),
            num(r.order as f64 / two_l),
            slope(r.slope_in_offset),
            slope(r.departure_slope),
            opt(q, |q| num(q / r.lambda)),
            r.window.map_or("-".into(), |[a, b]| {
                format!("{} .. {}", sci(r.rungs[a].h), sci(r.rungs[b].h))
            }),
            opt(r.longest_time, num),
            match r.consistent {
                Some(true) => "yes".into(),
                Some(false) => format!("**no**: {}", r.reason),
                None => format!("undecided: {}", r.reason),
            },
        ]);
    }
    t.render()
}

/// Every rung of one scheme's separatrix ladder.
pub fn following_rungs(r: &FollowingRecord) -> String {
    let mut out = format!(
        "<details><summary><code>{}</code>: {}</summary>\n\n",
        r.scheme, r.reason
    );
    let mut t = Table::new(&[
        "rung",
        "h",
        "steps",
        "event",
        "T",
        "dE/E_b",
        "predicted T",
        "T_D",
        "local q",
        "status",
    ]);
    for (i, g) in r.rungs.iter().enumerate() {
        t.row(vec![
            i.to_string(),
            sci(g.h),
            g.steps.to_string(),
            g.event.name().to_string(),
            opt(g.time, num),
            opt(g.barrier_offset, |x| format!("{x:+.2e}")),
            opt(g.predicted_time, num),
            opt(g.departure, num),
            opt(g.local_exponent, |x| format!("{x:.3}")),
            match (g.used, g.dropped) {
                (true, _) => "fitted".to_string(),
                (false, Some(d)) => match d {
                    stepladder::internals::accuracy::order::DropReason::AboveCeiling => {
                        "offset above the ceiling".to_string()
                    }
                    d => d.explain().to_string(),
                },
                (false, None) => "unused".to_string(),
            },
        ]);
    }
    out.push_str(&t.render());
    out.push_str("\n</details>\n\n");
    out
}

fn escape_section(hard: &HardCases) -> String {
    let mut out = String::from("### Escape or trapped\n\n");
    let _ = writeln!(
        out,
        "Two orbits start at the bottom of the same well with energies `E_b (1 - delta)` \
         (trapped for ever) and `E_b (1 + delta)` (escapes within its first quarter period), \
         for `delta = {}`, and run for {} periods of the trapped orbit. A scheme classifies \
         them correctly when the first keeps `|x| < alpha` throughout and the second reaches \
         `|x| = alpha`. The largest correct step is scanned down from `h = 4/sqrt(k)` by \
         `2^(-1/4)` to the first correct step whose every scan point down to half of it is \
         correct too, then bisected {} times against the failing scan point above it. At the \
         boundary the misclassified orbit meets the barrier with an energy error of about \
         `delta E_b` of the wrong sign (in units of `delta E_b`, where the trapped orbit \
         crosses or where the escaping one first turns back). The separatrix study's `dE/E_b = \
         c h^q` predicts the boundary `(delta/|c|)^(1/q)` where the sign of `c` is the failure \
         seen and the energy error the scheme carries to the barrier decides: at the first \
         approach, or at any for a symplectic scheme, whose error returns to the same value \
         each time up to the step's phase; explicit Euler instead fails by its energy drift \
         over the run. Runs are capped at {} steps.\n",
        ESCAPE_DELTAS.map(plain).join(" and "),
        tolerance::ESCAPE_PERIODS,
        tolerance::ESCAPE_BISECTIONS,
        tolerance::ESCAPE_MAX_STEPS,
    );
    out.push_str(&escape_table(&hard.escape, &hard.following));
    let [wide, narrow] = ESCAPE_DELTAS;
    let _ = writeln!(
        out,
        "\nWith `h* = (delta/|c|)^(1/q)`, narrowing the gap from {wide} to {narrow} divides \
         the largest correct step by `({wide}/{narrow})^(1/q)`:\n"
    );
    out.push_str(&escape_scaling_table(
        &hard.escape,
        &hard.following,
        wide,
        narrow,
    ));
    out.push('\n');
    out
}

/// `h*(wide) / h*(narrow)` against `(wide/narrow)^(1/q)`, one row per scheme.
pub fn escape_scaling_table(
    records: &[EscapeRecord],
    following: &[FollowingRecord],
    wide: f64,
    narrow: f64,
) -> String {
    let mut t = Table::new(&[
        "scheme",
        "h* ratio",
        "q (separatrix)",
        "(wide/narrow)^(1/q)",
    ]);
    for id in scheme_ids() {
        let h = |d: f64| {
            records
                .iter()
                .find(|r| r.scheme == id && r.spec.delta == d)
                .filter(|r| r.bracket.is_some())
                .and_then(|r| r.largest_correct)
        };
        let q = following
            .iter()
            .find(|f| f.scheme == id)
            .and_then(|f| f.offset_law)
            .map(|l| l.slope);
        t.row(vec![
            format!("`{id}`"),
            match (h(wide), h(narrow)) {
                (Some(a), Some(b)) => format!("{:.3}", a / b),
                _ => "-".into(),
            },
            opt(q, |q| format!("{q:.3}")),
            opt(q, |q| format!("{:.3}", (wide / narrow).powf(1.0 / q))),
        ]);
    }
    t.render()
}

/// Whether a scheme that classified no scanned step correctly is left
/// undecided rather than failed: the scan stops at the step its budget
/// allows ([`stepladder::internals::tolerance::ESCAPE_MAX_STEPS`] a run),
/// and where the separatrix study's law puts the boundary,
/// `(delta / |c|)^(1/q)`, below the finest step scanned, no correct step
/// was to be found above it. Without a law (a scheme whose offset the
/// separatrix study could not fit) a scheme with no correct step fails, as
/// it does when the law says the boundary was within reach.
pub fn escape_undecided(r: &EscapeRecord, following: &[FollowingRecord]) -> Option<f64> {
    if r.largest_correct.is_some() {
        return None;
    }
    let f = following.iter().find(|f| f.scheme == r.scheme)?;
    let (c, q) = (f.offset_coefficient?, f.offset_law?.slope);
    let predicted = (r.spec.delta / c.abs()).powf(1.0 / q);
    (predicted.is_finite() && predicted < r.finest_scanned).then_some(predicted)
}

/// The boundary `(delta / |c|)^(1/q)` the separatrix study predicts for the
/// escape study, when the misclassification is the one the sign of `c` says
/// and happens at the first approach.
pub fn predicted_boundary(r: &EscapeRecord, f: &FollowingRecord) -> Option<f64> {
    let (c, q) = (f.offset_coefficient?, f.offset_law?.slope);
    let agrees = match r.fails_by? {
        Misclassified::TrappedEscapes => c > 0.0,
        Misclassified::EscapingTrapped => c < 0.0,
        Misclassified::Both => false,
    };
    // a non-symplectic scheme that fails at a later approach does so by
    // drifting, which one passage of the separatrix does not measure
    let applies = r.first_approach == Some(true) || r.symplectic;
    (agrees && applies && f.event != Some(Event::Followed))
        .then(|| (r.spec.delta / c.abs()).powf(1.0 / q))
}

/// One row per scheme and gap.
pub fn escape_table(records: &[EscapeRecord], following: &[FollowingRecord]) -> String {
    let mut t = Table::new(&[
        "scheme",
        "delta",
        "largest correct h",
        "scan bracket",
        "above it",
        "barrier dE / (delta E_b)",
        "predicted",
    ]);
    let order: Vec<&str> = scheme_ids();
    let mut rows: Vec<&EscapeRecord> = records.iter().collect();
    rows.sort_by_key(|r| order.iter().position(|id| *id == r.scheme));
    for r in rows {
        let f = following.iter().find(|f| f.scheme == r.scheme);
        let misfit = r
            .at_boundary
            .and_then(|[_, bad]| r.fails_by?.barrier_error(&bad));
        t.row(vec![
            format!("`{}`", r.scheme),
            plain(r.spec.delta),
            match (r.largest_correct, r.bracket) {
                (Some(h), Some(_)) => format!("{h:.3e}"),
                (Some(h), None) => format!(">= {h:.3e} (coarsest scanned)"),
                (None, _) => format!("none down to {}", sci(r.finest_scanned)),
            },
            r.bracket
                .map_or("-".into(), |[a, b]| format!("{} .. {}", sci(a), sci(b))),
            match (r.fails_by, r.first_approach) {
                (Some(m), Some(false)) if r.symplectic => {
                    format!("{}, at a later approach", m.describe())
                }
                (Some(m), Some(false)) => {
                    format!("{}, at a later approach: the energy drifts", m.describe())
                }
                (Some(m), _) => m.describe().to_string(),
                (None, _) => "-".into(),
            },
            opt(misfit, |x| format!("{x:+.3}")),
            f.and_then(|f| predicted_boundary(r, f))
                .or_else(|| escape_undecided(r, following))
                .map_or("-".into(), |h| format!("{h:.3e}")),
        ]);
    }
    let mut out = t.render();
    for r in records {
        if let Some(predicted) = escape_undecided(r, following) {
            let _ = writeln!(
                out,
                "\n`{}` at delta {}: no correct step down to {}, the finest the scan's budget of \
                 {} steps a run allows; the separatrix law puts its boundary near {predicted:.3e}, \
                 below that, so this is undecided, not a failure.",
                r.scheme,
                plain(r.spec.delta),
                sci(r.finest_scanned),
                stepladder::internals::tolerance::ESCAPE_MAX_STEPS,
            );
        }
    }
    out
}
