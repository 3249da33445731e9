//! The race of the crate's best integrator against the peers: by force
//! evaluations (deterministic), with the N-body references it is judged
//! against, and by wall time (machine-dependent).

use super::markdown::{Table, sci};
use super::markdown::{evaluations, time_reach};
use crate::peer::{PEER_TOLERANCES, peer_names};
use crate::suite::ias15::Ias15Row;
use crate::suite::race::{
    DigitCost, DigitRow, NBODY_FIRST_STEPS, NBODY_FIRST_TOLERANCE, NBODY_TOLERANCES, NbodyRecord,
    RACE_TARGETS, REFERENCE_SHARE, RaceRecords, RaceRow,
};
use stepladder::internals::adaptive::ladder::TOLERANCES as ADAPTIVE_TOLERANCES;
use stepladder::internals::cost::work_points::Reach;

/// A contender's name in a table.
fn who(name: Option<&str>) -> String {
    name.map_or("none".into(), |n| {
        if n.contains(' ') {
            n.to_string()
        } else {
            format!("`{n}`")
        }
    })
}

/// `best peer / crate's best`, two decimals.
fn ratio(peer: Option<f64>, best: Option<f64>) -> String {
    match (peer, best) {
        (Some(p), Some(b)) => format!("{:.2}", p / b),
        _ => "-".into(),
    }
}

/// Who wins a row, and by how much, in words.
fn outcome(
    best: Option<f64>,
    peer: Option<(usize, f64)>,
    smallest_error: Option<f64>,
    judged: bool,
) -> String {
    let names = peer_names();
    let verdict = match (best, peer) {
        (None, None) => match smallest_error {
            Some(e) => format!(
                "neither side reaches it: the smallest error of any run is {}",
                sci(e)
            ),
            None => "neither side reaches it".to_string(),
        },
        (Some(_), None) => "won: no peer reaches it".to_string(),
        (None, Some((i, _))) => format!(
            "lost: no integrator of the crate reaches it, {} does",
            names[i]
        ),
        (Some(a), Some((_, b))) if a <= b => "won".to_string(),
        (Some(a), Some((i, b))) => format!("lost by {:.2}x to {}", a / b, names[i]),
    };
    if judged {
        verdict
    } else {
        format!("not judged (the reference is too coarse): {verdict}")
    }
}

/// How a race table speaks of its cost: by force evaluations or by time.
#[derive(Clone, Copy)]
enum Unit {
    Evaluations,
    Seconds,
}

/// The race in one unit: per scene and target, the cheapest (or fastest)
/// fixed-step scheme, the cheapest (or fastest) own pair, every peer, and
/// who wins.
fn rows_table(rows: &[RaceRow], unit: Unit) -> String {
    let (best, cost, show): (&str, &str, fn(Reach) -> String) = match unit {
        Unit::Evaluations => ("cheapest", "evaluations", evaluations),
        Unit::Seconds => ("fastest", "time", time_reach),
    };
    let (fixed, pair) = (format!("{best} fixed step"), format!("{best} own pair"));
    let mut header = vec!["scene", "target", fixed.as_str(), cost, pair.as_str(), cost];
    let peers = peer_names();
    header.extend(&peers);
    header.extend(["best peer / crate's best", "outcome"]);
    let mut t = Table::new(&header);
    for r in rows {
        let fixed_cost = match (r.fixed.reach, r.fixed_searched_to, r.fixed.name) {
            (Reach::NotReached, Some(bound), _) => format!("none below {}", sci(bound)),
            // no scheme was found below the own pair's cost: the table by
            // evaluations says where the search stopped
            (_, _, None) => "-".into(),
            (reach, _, _) => show(reach),
        };
        let mut row = vec![
            format!("`{}`", r.scene),
            format!("{:.0e}", r.target),
            who(r.fixed.name),
            fixed_cost,
            who(r.pair.name),
            show(r.pair.reach),
        ];
        row.extend(r.peers.iter().map(|&p| show(p)));
        row.push(ratio(r.best_peer().map(|p| p.1), r.best()));
        let mut verdict = outcome(r.best(), r.best_peer(), r.smallest_error, r.judged);
        // a contender the ladder's end kept from a target matters only
        // where its last run costs less than every cost reached for good
        let reached = r.best_peer().map(|p| p.1).into_iter().chain(r.best());
        let beaten = reached.fold(f64::INFINITY, f64::min);
        let named: Vec<String> = r
            .unconfirmed
            .iter()
            .filter(|&&(_, cost)| cost < beaten)
            .map(|&(name, cost)| format!("{} ({})", who(Some(name)), sci(cost)))
            .collect();
        if !named.is_empty() {
            verdict.push_str(&format!(
                "; met only by the last run of its ladder, unconfirmed: {}",
                named.join(", ")
            ));
        }
        row.push(verdict);
        t.row(row);
    }
    t.render()
}

/// The race by force evaluations.
pub fn race_table(rows: &[RaceRow]) -> String {
    rows_table(rows, Unit::Evaluations)
}

/// The N-body references: where each comes from, how well it is known,
/// which targets it judges, and how closely the adaptive contenders'
/// tightest runs agree with it and with each other.
pub fn reference_table(records: &[NbodyRecord]) -> String {
    let mut t = Table::new(&[
        "scene",
        "t_end",
        "reference",
        "its error",
        "targets judged",
        "tightest runs: distance to it",
        "largest distance between two of them",
    ]);
    for r in records {
        let judged: Vec<String> = RACE_TARGETS
            .iter()
            .filter(|&&x| r.reference.judges(x))
            .map(|x| format!("{x:.0e}"))
            .collect();
        let tightest: Vec<String> = r
            .adaptive
            .iter()
            .filter_map(|l| {
                let p = l.points.last()?;
                Some(format!(
                    "{} {} (TOL {})",
                    l.contender,
                    p.error.map_or("failed".into(), sci),
                    sci(p.setting)
                ))
            })
            .collect();
        t.row(vec![
            format!("`{}`", r.reference.scene),
            format!("{}", r.reference.t_end),
            r.reference.source.to_string(),
            format!(
                "{} ({})",
                sci(r.reference.accuracy),
                r.reference.accuracy_source
            ),
            if judged.is_empty() {
                "none".into()
            } else {
                judged.join(", ")
            },
            tightest.join("; "),
            sci(r.spread),
        ]);
    }
    t.render()
}

/// `per_digit [low, high]`, or `<= high` without a run that missed.
fn per_digit(d: Option<DigitCost>) -> String {
    match d {
        None => "not reached".into(),
        Some(DigitCost {
            per_digit,
            low: Some(low),
            high,
        }) => format!("{} [{}, {}]", sci(per_digit), sci(low), sci(high)),
        Some(DigitCost { high, .. }) => format!("<= {}", sci(high)),
    }
}

/// Evaluations per correct digit: the cheapest own pair's and each peer's.
pub fn digits_table(rows: &[DigitRow]) -> String {
    let peers = peer_names();
    let mut header = vec![
        "scene",
        "target",
        "cheapest own pair",
        "evaluations per digit",
    ];
    header.extend(&peers);
    let mut t = Table::new(&header);
    for r in rows {
        let target = if r.judged {
            format!("{:.0e}", r.target)
        } else {
            format!("{:.0e} (not judged)", r.target)
        };
        let mut row = vec![
            format!("`{}`", r.scene),
            target,
            who(r.pair.map(|p| p.0)),
            per_digit(r.pair.map(|p| p.1)),
        ];
        row.extend(r.peers.iter().map(|&p| per_digit(p)));
        t.row(row);
    }
    t.render()
}

/// IAS15's reference row: its cost and cost per digit at each N-body
/// target, against the crate's best.
pub fn ias15_table(rows: &[Ias15Row]) -> String {
    let mut t = Table::new(&[
        "scene",
        "target",
        "IAS15 evaluations",
        "per digit",
        "crate's best",
        "IAS15 / crate's best",
    ]);
    for r in rows {
        let target = if r.judged {
            format!("{:.0e}", r.target)
        } else {
            format!("{:.0e} (not judged)", r.target)
        };
        t.row(vec![
            format!("`{}`", r.scene),
            target,
            evaluations(r.reach),
            per_digit(r.digits),
            r.best.map_or("not reached".into(), sci),
            ratio(r.reach.cost(), r.best),
        ]);
    }
    t.render()
}

/// The race's part of the deterministic section.
pub fn race_section(race: &RaceRecords) -> String {
    let mut out = String::from("### The race\n\n");
    out.push_str(&format!(
        "The crate's best integrator against every peer at equal error, by force \
         evaluations (the same race by wall time is in the machine-dependent part): the \
         cheapest fixed-step catalogue scheme and the cheapest of the crate's own adaptive \
         pairs on one side, each peer on the other. On the Kepler orbits the error is the \
         largest phase-space error over the run against the exact solution (the work \
         study's rungs, the tolerance ladders' runs for the own pairs and the peers' runs \
         of the work study, the own pairs' carried on to the peers' tightest tolerance), \
         and a target is judged \
         where the exact solution itself is within a tenth of it: it is the orbit of the \
         doubles the integrators are given (`GM` and the initial state as doubles, which \
         on the eccentric orbit shift the mean motion by 3.6e-16 of itself from the ideal \
         `2 pi`), computed in double-double and rounded once, about 2e-16 off. The \
         adaptive pairs end each step on a double and take the step as its difference \
         from the last, so their states are at the times they are reported at: at the \
         eccentric orbit's pericentre half an ulp of `t = 2` is 9e-15 of phase-space \
         distance. The N-body scenes have \
         no exact solution: there the error is the phase-space distance at the end time to \
         a reference state, each adaptive contender run from a tolerance of {} a decade at \
         a time until it has reached the smallest target the reference judges (in the \
         sense below), or down to a tolerance of {}, each fixed-step scheme from {} steps \
         doubling until it reaches every target for good or its run that missed one already cost \
         what the cheapest own pair spends there, after which it cannot be the crate's best \
         (`none below N` says where the search stopped). A target is judged only where the \
         reference's own error is at most {} of it.\n\n\
         Every contender's runs go from cheap to dear, and a target counts as reached at the \
         first run that meets it after which no dearer run of the same contender misses it, \
         with at least one dearer run confirming it; the cost is interpolated between that \
         run and the last one that missed (`<=` where no run before it measured an error). \
         Far above round-off the error falls with the cost and this is \
         the first run below the target. At the round-off floor it is not: one run's error \
         can land below the trend by a cancellation of its roundings while the next \
         tolerance's is above the target again, and a cost read off the first run below \
         would be a draw of where a decade ladder's rungs happen to fall. So that both \
         sides are read over the same tolerances, the own pairs' Kepler ladders (which end \
         at {own_last:.0e}) are carried on here to the peers' tightest, {peer_last:.0e}. The \
         fixed steps' runs on the Kepler orbits are the work study's rungs, which go on until \
         two successive rungs meet its smallest target, 1e-12, or until the error no longer \
         falls as the order promises (one rung more after a first meet, to confirm it or take \
         it back), so a target a fixed step first meets on its last rung counts as not \
         reached. Where a \
         contender meets a target only with the last run of its ladder, and that run costs \
         less than what reached it for good, the outcome names it as unconfirmed.\n\n\
         A fixed step pays everywhere for the orbit's fastest part, an adaptive one only \
         there. Where the own pairs win, the reason is the equation: for `q'' = a(q)` a \
         Nyström method spends no stages on the velocity's own derivative, so DPRKN8(6) \
         reaches order eight with eight force evaluations a step and RKN12(10) order \
         twelve with seventeen, where DOP853, written for any first-order system and run \
         on `(q, v)`, spends twelve for order eight, and Verner's 9(8) pair sixteen for \
         order nine. At the tight targets the second reason is round-off: a plain pair \
         adds each step's small increment to a coordinate of order one and loses about \
         `eps/2` of the coordinate each time, which on the Pleiades' close encounters \
         stops every plain contender above 1e-12; the compensated pairs carry what each \
         addition drops (Knuth's TwoSum) and lose only the rounding of the increments \
         themselves. Where neither side reaches a target the reference resolves, the \
         outcome gives the smallest error any run reached.\n\n\
         One published twelfth-order integrator is raced elsewhere: brahe's experimental \
         RKN12(10), whose build (over three hundred crates) does not fit this one, runs in \
         `audit/AUDIT.md` against the crate's two RKN12(10) pairs on these four scenes and \
         references (`lab/references/`, written by `stepladder reference`), each judged by \
         its error at the end time, and also with its default step cap lifted (900 time \
         units, which on the outer solar system in days sets brahe's steps at the middle \
         tolerances).\n\n",
        sci(NBODY_FIRST_TOLERANCE),
        sci(NBODY_TOLERANCES[NBODY_TOLERANCES.len() - 1]),
        NBODY_FIRST_STEPS,
        REFERENCE_SHARE,
        own_last = ADAPTIVE_TOLERANCES[ADAPTIVE_TOLERANCES.len() - 1],
        peer_last = PEER_TOLERANCES[PEER_TOLERANCES.len() - 1],
    ));
    out.push_str(&race_table(&race.rows));
    out.push_str(&pericentre_lag_note(race));
    out.push_str(
        "\nThe N-body references, how well each is known, and how closely the adaptive \
         contenders' tightest runs come to it and to each other:\n\n",
    );
    out.push_str(&reference_table(&race.nbody));
    out.push_str(
        "\nWhat each digit of accuracy costs: the force evaluations to reach a target \
         divided by the digits it asks for (`-log10` of the target), for the cheapest own \
         pair at that target and for each peer, read off the same runs as the race. In \
         brackets, the same figure for the last run that missed the target and the first \
         that reached it for good: where the error falls as the cost grows, the true cost lies \
         between them (`<=` where the cheapest run already reached it).\n\n",
    );
    out.push_str(&digits_table(&race.digits));
    let (version, command) = crate::suite::ias15::provenance();
    out.push_str(&format!(
        "\nIAS15, REBOUND's 15th-order Gauss-Radau integrator and the reference integrator of \
         N-body work, as a reference row (not a contender: it runs outside the crate's \
         build): REBOUND {version} itself ran it on the same initial states to the same end \
         times, at its accuracy parameter `epsilon` from 1e-1 to 1e-12 (`{command}`, \
         output in `lab/ias15/ias15.json`); its end states are judged here against the \
         same references, and its evaluations are REBOUND's calls of the force, counted \
         through a force term that adds nothing.\n\n",
    ));
    out.push_str(&ias15_table(&race.ias15));
    out.push_str(&ias15_cheaper_note(race));
    out
}

/// Where IAS15 costs less than the crate's best, from which tolerance the
/// crate's best pair reaches that target for good, and the smallest error
/// any run of the crate's pairs reached on the scene: figures, read off the
/// same runs as the race.
fn ias15_cheaper_note(race: &RaceRecords) -> String {
    let own = crate::suite::adaptive::OWN_PAIRS.len();
    let mut out = String::new();
    for r in race.ias15.iter().filter(|r| r.judged) {
        let (Some(cost), Some(best)) = (r.reach.cost(), r.best) else {
            continue;
        };
        if cost >= best {
            continue;
        }
        let Some(record) = race.nbody.iter().find(|n| n.reference.scene == r.scene) else {
            continue;
        };
        let pairs = &record.adaptive[..own];
        let best_pair = race
            .rows
            .iter()
            .find(|row| row.scene == r.scene && row.target == r.target)
            .and_then(|row| row.pair.name);
        let first_below = best_pair.and_then(|name| {
            let ladder = pairs.iter().find(|l| l.contender == name)?;
            let run = *ladder.deciding(r.target).last()?;
            Some((name, ladder.points[run].setting))
        });
        let smallest = pairs
            .iter()
            .flat_map(|l| {
                l.points
                    .iter()
                    .filter_map(move |p| p.error.map(|e| (l.contender, p.setting, e)))
            })
            .min_by(|a, b| a.2.total_cmp(&b.2));
        let (Some((name, tol)), Some((who, at, floor))) = (first_below, smallest) else {
            continue;
        };
        out.push_str(&format!(
            "\nIAS15 costs less than the crate's best on `{scene}` at {target:.0e} ({ratio:.2}). \
             The crate's best there, {name}, reaches that target for good from its run at TOL \
             {tol:.0e}, {decades:.0} decades tighter than the target, and the smallest error any \
             run of the crate's pairs reached there is {floor} ({who} at TOL {at:.0e}), {above:.1} \
             times below it.\n",
            scene = r.scene,
            target = r.target,
            ratio = cost / best,
            decades = (r.target / tol).log10(),
            above = r.target / floor,
            floor = sci(floor),
        ));
    }
    out
}

/// Why the eccentric orbit's smallest target lies at the round-off floor,
/// whether or not a run of the ladder happens to fall below it: the figures
/// of [`PericentreLag`](crate::suite::pericentre_lag::PericentreLag).
fn pericentre_lag_note(race: &RaceRecords) -> String {
    let target = RACE_TARGETS.iter().copied().fold(f64::INFINITY, f64::min);
    let Some(row) = race
        .rows
        .iter()
        .find(|r| r.scene == "kepler-eccentric" && r.target == target && r.judged)
    else {
        return String::new();
    };
    let Some(lag) = race.pericentre_lag.as_ref() else {
        return String::new();
    };
    let who = match row.pair.name.filter(|_| row.best().is_some()) {
        Some(pair) => format!(
            "{pair}'s ladder reaches {target:.0e} for good, but that target lies at the round-off \
             floor: whether a run ends below it is decided by how its roundings fall, not by its \
             tolerance. The error at that level is a lag along the orbit."
        ),
        None => match row.smallest_error.filter(|&e| e <= target) {
            Some(e) => format!(
                "no ladder reaches {target:.0e} for good: runs end on both sides of it (the \
                 smallest error of any run is {}), as they do where how a run's roundings fall \
                 decides, not its tolerance. The error at that level is a lag along the orbit.",
                sci(e)
            ),
            None => format!(
                "no run reaches {target:.0e}, and the error at that level is a lag along the orbit."
            ),
        },
    };
    let u = f64::EPSILON / 2.0;
    let allowed = lag.energy_allowed(target);
    format!(
        "\nOn the eccentric orbit {who} The compensated DPRKN12(10) pair at TOL {tol:.0e} is worst at \
         t = {t:.4}, by {error}, of which a shift in time of {shift} yr at the phase-space \
         speed there, {speed:.1} AU/yr, explains all but {across:.1}%. Such a shift is a mean \
         motion off by `|shift| / t` on average, an energy off by `(2/3) |shift| / t` = \
         {offset} ({offset_u:.1} u, `u = 2^-53`). To be within {target:.0e} at that point a \
         run must keep its energy within `(2/3) T / (S t)` = {allowed} ({allowed_u:.2} u) all \
         along, finer than one rounding of the position to doubles at pericentre changes \
         the energy (the potential by up to `u |V_p|`, {stage:.1} u of the energy, `|V_p| / \
         |E| = 2 / (1 - e)`); the force is evaluated at positions so rounded.\n",
        tol = crate::suite::pericentre_lag::LAG_TOLERANCE,
        t = lag.time,
        error = sci(lag.error),
        shift = sci(lag.shift),
        speed = lag.speed,
        across = 100.0 * lag.across_share,
        offset = sci(lag.energy_offset),
        offset_u = lag.energy_offset / u,
        allowed = sci(allowed),
        allowed_u = allowed / u,
        stage = lag.stage_rounding_units,
    )
}

/// The race by wall time.
pub fn timing_section(rows: &[RaceRow]) -> String {
    let mut out = String::from(
        "\n### The race by time\n\nThe race of the deterministic part, by wall time, \
         interpolated to each target like the evaluations: the own pairs on the Kepler \
         orbits from their tolerance ladders (each tolerance's run timed whole after the \
         ladders, one at a time, fastest of several, and the runs the race carried the \
         ladders on with timed the same way where they decide a target); every other adaptive run that \
         decides a target (the peers' on the Kepler orbits, every contender's on the \
         N-body scenes) timed the same way, set-up and output included; the fixed steps on \
         the Kepler orbits at their evaluations times their measured time per evaluation \
         (as in the time-to-target table), on the N-body scenes their runs \
         that decide a target timed whole. A fixed step shown as `-` was not searched \
         beyond the own pair's evaluations (see the race by evaluations), or reaches no \
         target for good on its runs (on the Kepler orbits the work study's rungs end at \
         the first below 1e-12).\n\n",
    );
    out.push_str(&rows_table(rows, Unit::Seconds));
    out
}
