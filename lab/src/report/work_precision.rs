//! The report's "Speed against error" section: work-precision tables in
//! force evaluations (deterministic), and ns per step and time to target
//! (machine-dependent).

use super::markdown::{Table, sci};
use crate::peer::{PEER_NAME, PEER_TOLERANCES};
use crate::suite::work_precision::{Cheapest, Fastest, WorkRecord, WorkTiming};
use std::fmt::Write as _;
use stepladder::study::adaptive::ToleranceLadderRecord;
use stepladder::study::cost::step_time::SpeedRecord;
use stepladder::study::cost::work_points::{
    ENERGY_FLOOR_GUARD, ENERGY_MAX_STEPS, ENERGY_PERIODS, ENERGY_START, Reach, TARGETS, TargetCost,
};

/// A cost in force evaluations, to three digits; `<=` marks an upper bound.
pub fn evaluations(r: Reach) -> String {
    match r {
        Reach::Interpolated(c) => sci(c),
        Reach::AtMost(c) => format!("<= {}", sci(c)),
        Reach::NotReached => "not reached".into(),
    }
}

/// A duration in seconds with a unit, to three digits.
pub fn duration(seconds: f64) -> String {
    if seconds < 1e-3 {
        format!("{:.3} us", seconds * 1e6)
    } else if seconds < 1.0 {
        format!("{:.3} ms", seconds * 1e3)
    } else {
        format!("{seconds:.3} s")
    }
}

/// A time to target; `<=` marks an upper bound.
pub fn time_reach(r: Reach) -> String {
    match r {
        Reach::Interpolated(c) => duration(c),
        Reach::AtMost(c) => format!("<= {}", duration(c)),
        Reach::NotReached => "not reached".into(),
    }
}

fn target_header() -> Vec<String> {
    TARGETS.iter().map(|t| format!("{t:.0e}")).collect()
}

fn costs(t: &[TargetCost]) -> Vec<String> {
    t.iter().map(|c| evaluations(c.reach)).collect()
}

/// The method, for the deterministic part.
pub fn method() -> String {
    format!(
        "Cost is counted in force evaluations, which are deterministic and do not depend \
         on the machine; wall times are in the machine-dependent part below. Two errors:\n\n\
         - **global error**: the order study's own rungs, reused (the largest phase-space \
         error over `t_end` = 2 sqrt(2) periods), with the force evaluations each rung \
         spent, start-up included (counted by running the rung again on a counting scene \
         for the implicit scheme, whose iterations vary with the step);\n\
         - **energy error**: the largest `|E - E0|/|E0|` over {ENERGY_PERIODS} periods, on a \
         ladder of its own halving the step from {ENERGY_START} period until the error is \
         below the smallest target, has stopped halving below {ENERGY_FLOOR_GUARD:e} \
         (round-off), or a run would take more than {ENERGY_MAX_STEPS} steps.\n\n\
         The cost of a target is interpolated on log-log axes between the two measured \
         runs that bracket it, never extrapolated: `<=` marks a target already met by the \
         cheapest run measured (or by the first run after one that blew up), whose cost is \
         then an upper bound, and `not reached` a target no run met. The cheapest scheme \
         is the one with the fewest evaluations, an upper bound counting at its value. The peer is the `ode_solvers` \
         crate's adaptive `Dop853` (Dormand-Prince 8(5,3)) on `y = (q, v)`, at relative \
         and absolute tolerances {} to {}, one a decade, judged the same way: its error \
         at every step it takes against the exact solution, its force evaluations from its \
         own statistics (rejected steps and the initial step-size guess included).\n\n",
        sci(PEER_TOLERANCES[0]),
        sci(PEER_TOLERANCES[PEER_TOLERANCES.len() - 1]),
    )
}

/// The cheapest scheme per target and scene, global and energy error, with
/// the peer beside.
pub fn cheapest_table(records: &[WorkRecord]) -> String {
    let mut t = Table::new(&[
        "scene",
        "target",
        "cheapest (global error)",
        "evaluations",
        PEER_NAME,
        "cheapest (energy error)",
        "evaluations",
        PEER_NAME,
    ]);
    let who = |c: &Cheapest| c.scheme.map_or("none".into(), |s| format!("`{s}`"));
    for r in records {
        for (g, e) in r.cheapest_global.iter().zip(&r.cheapest_energy) {
            t.row(vec![
                format!("`{}`", r.scene),
                format!("{:.0e}", g.target),
                who(g),
                evaluations(g.reach),
                evaluations(g.peer),
                who(e),
                evaluations(e.reach),
                evaluations(e.peer),
            ]);
        }
    }
    t.render()
}

/// One scene's table: force evaluations of every scheme and the peer to
/// reach each target, global and energy error.
pub fn work_table(r: &WorkRecord) -> String {
    let mut header = vec!["scheme".to_string(), "order".to_string()];
    header.extend(target_header().into_iter().map(|t| format!("global {t}")));
    header.extend(target_header().into_iter().map(|t| format!("energy {t}")));
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut t = Table::new(&header);
    for s in &r.schemes {
        let mut row = vec![format!("`{}`", s.scheme), s.order.to_string()];
        row.extend(costs(&s.global_targets));
        row.extend(costs(&s.energy_targets));
        t.row(row);
    }
    if let Some(p) = &r.peer {
        let mut row = vec![PEER_NAME.to_string(), "8".to_string()];
        row.extend(costs(&p.global_targets));
        row.extend(costs(&p.energy_targets));
        t.row(row);
    }
    t.render()
}

/// The peer's runs on one scene, tolerance by tolerance.
pub fn peer_table(r: &WorkRecord) -> String {
    let Some(p) = &r.peer else {
        return String::new();
    };
    let mut t = Table::new(&[
        "tolerance",
        "evaluations",
        "steps (rejected)",
        "global error",
        "energy run: evaluations",
        "energy error",
    ]);
    let opt_err = |e: Option<f64>| e.map_or("failed".into(), sci);
    for (g, e) in p.global.iter().zip(&p.energy) {
        t.row(vec![
            sci(g.tolerance),
            g.evaluations.to_string(),
            format!("{} ({})", g.accepted, g.rejected),
            opt_err(g.error),
            e.evaluations.to_string(),
            opt_err(e.error),
        ]);
    }
    t.render()
}

/// One scene's deterministic tables, as `stepladder work` prints them.
pub fn work_scene(r: &WorkRecord) -> String {
    let mut out = format!(
        "Force evaluations to reach each target on `{}` ({}): global error over t_end = \
         {:.4}, energy error over {} periods.\n\n",
        r.scene, r.scene_parameters, r.t_end, r.energy_periods
    );
    out.push_str(&work_table(r));
    out.push_str("\nCheapest scheme per target:\n\n");
    out.push_str(&cheapest_table(std::slice::from_ref(r)));
    out
}

/// The scenes and targets of the race against the adaptive peer: the two
/// Kepler orbits, from a loose to a tight global error.
pub const RACE_SCENES: [&str; 2] = ["kepler-circular", "kepler-eccentric"];
/// See [`RACE_SCENES`].
pub const RACE_TARGETS: [f64; 3] = [1e-6, 1e-9, 1e-12];

/// The race at equal global error on the Kepler orbits: the cheapest
/// catalogue scheme (fixed step) and the cheapest of the crate's own adaptive
/// pairs against the peer, who wins, and the evidence why.
///
/// Where the catalogue loses on the eccentric orbit, the evidence is what
/// the eccentricity costs each side: the cheapest fixed-step cost on the
/// eccentric orbit over that on the circular one at the same target,
/// against the same ratio for the peer, whose step follows the pericentre.
pub fn race_table(records: &[WorkRecord], adaptive: &[ToleranceLadderRecord]) -> String {
    let mut t = Table::new(&[
        "scene",
        "target",
        "cheapest fixed step",
        "evaluations",
        "own adaptive pair",
        PEER_NAME,
        "peer / best",
        "outcome",
    ]);
    let find = |scene: &str, target: f64| {
        records
            .iter()
            .find(|r| r.scene == scene)
            .and_then(|r| r.cheapest_global.iter().find(|c| c.target == target))
    };
    // the cheapest of the crate's own pairs that reaches the target
    let own = |scene: &str, target: f64| {
        adaptive
            .iter()
            .filter(|l| l.scene == scene && l.integrator != PEER_NAME)
            .filter_map(|l| {
                let reach = l
                    .global_targets()
                    .into_iter()
                    .find(|c| c.target == target)?
                    .reach;
                Some((reach.cost()?, reach, l.integrator))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map_or((Reach::NotReached, None), |(_, reach, name)| {
                (reach, Some(name))
            })
    };
    for scene in RACE_SCENES {
        for target in RACE_TARGETS {
            let Some(c) = find(scene, target) else {
                continue;
            };
            let (pair, pair_name) = own(scene, target);
            let best = [c.reach.cost(), pair.cost()]
                .into_iter()
                .flatten()
                .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.min(x))));
            let ratio = match (best, c.peer.cost()) {
                (Some(a), Some(b)) => format!("{:.2}", b / a),
                _ => "-".into(),
            };
            let outcome = match (best, c.peer.cost()) {
                (Some(_), None) => "won: the peer does not reach it".to_string(),
                (None, _) => {
                    "lost: neither a catalogue scheme nor an own pair reaches it".to_string()
                }
                (Some(a), Some(b)) if a <= b => "won".to_string(),
                (Some(a), Some(b)) => {
                    let circular = find(RACE_SCENES[0], target)
                        .filter(|_| scene != RACE_SCENES[0])
                        .and_then(|k| k.reach.cost().zip(k.peer.cost()));
                    match (circular, c.reach.cost()) {
                        (Some((ka, kb)), Some(fixed)) => format!(
                            "lost by {:.2}x: the eccentricity costs fixed steps {:.1}x the \
                             circular orbit's evaluations, the adaptive peer {:.1}x",
                            a / b,
                            fixed / ka,
                            b / kb
                        ),
                        _ => format!("lost by {:.2}x", a / b),
                    }
                }
            };
            t.row(vec![
                format!("`{scene}`"),
                format!("{target:.0e}"),
                c.scheme.map_or("none".into(), |s| format!("`{s}`")),
                evaluations(c.reach),
                match pair_name {
                    Some(name) => format!("{} ({name})", evaluations(pair)),
                    None => evaluations(pair),
                },
                evaluations(c.peer),
                ratio,
                outcome,
            ]);
        }
    }
    t.render()
}

/// The deterministic part of the section.
pub fn deterministic_section(records: &[WorkRecord], adaptive: &[ToleranceLadderRecord]) -> String {
    let mut out = String::from("\n## Speed against error\n\n");
    out.push_str(&method());
    out.push_str(
        "### The race on the Kepler orbits\n\nThe cheapest fixed-step catalogue scheme and \
         the cheapest of the crate's own adaptive pairs (see the tolerance ladders) against the adaptive \
         peer at equal global error, by force evaluations (the same race by wall \
         time is the race-by-time table in the machine-dependent part). \
         A fixed step pays everywhere for the orbit's fastest part, an adaptive one only \
         there: where a fixed-step scheme loses on the eccentric orbit, the outcome says \
         what the eccentricity costs each side. Where DPRKN8(6) wins, the reason is the \
         equation: for `q'' = a(q)` a Nyström method spends no stages on the velocity's \
         own derivative, so it reaches order eight with eight force evaluations a step, \
         where DOP853, written for any first-order system and run on `(q, v)`, spends \
         twelve.\n\n",
    );
    out.push_str(&race_table(records, adaptive));
    out.push_str("\n### Cheapest scheme per target\n\n");
    out.push_str(&cheapest_table(records));
    out.push_str(
        "\nThe work-precision figures are in the summary; the force evaluations each \
         scheme needs for each target are on \
         [a detail page](details/work-evaluations.md).\n",
    );
    out
}

/// Force evaluations to reach each target, per scene, with the peer's
/// tolerances: the numbers behind the work-precision figures.
pub fn evaluations_by_target(records: &[WorkRecord]) -> String {
    let mut out = String::new();
    for r in records {
        let _ = writeln!(out, "\n## {}\n", r.scene);
        out.push_str(&work_table(r));
        let _ = writeln!(
            out,
            "\n<details><summary>{PEER_NAME} on <code>{}</code>, tolerance by \
             tolerance</summary>\n",
            r.scene
        );
        out.push_str(&peer_table(r));
        out.push_str("\n</details>\n");
    }
    out
}

/// Nanoseconds per step of every scheme against the floor.
pub fn speed_table(r: &SpeedRecord) -> String {
    let mut out = format!(
        "On `{}`, h = {}, {} steps a run, fastest of {} runs; the floor is a hand-written \
         velocity Verlet loop on plain f64 (one force evaluation a step): {:.2} ns a step.\n\n",
        r.scene, r.h, r.steps, r.repeats, r.floor_ns_per_step
    );
    let mut t = Table::new(&[
        "scheme",
        "forces/step",
        "ns/step",
        "ratio to floor",
        "ns/evaluation",
        "ratio per evaluation",
    ]);
    t.row(vec![
        "floor (hand-written velocity Verlet)".into(),
        "1".into(),
        format!("{:.2}", r.floor_ns_per_step),
        "1.00".into(),
        format!("{:.2}", r.floor_ns_per_step),
        "1.00".into(),
    ]);
    for s in &r.schemes {
        t.row(vec![
            format!("`{}`", s.id),
            format!("{:.2}", s.force_evaluations_per_step),
            format!("{:.2}", s.ns_per_step),
            format!("{:.2}", s.ratio_to_floor),
            format!("{:.2}", s.ns_per_force_evaluation),
            format!("{:.2}", s.ratio_per_evaluation),
        ]);
    }
    out.push_str(&t.render());
    out
}

/// The fastest scheme per target on one or more scenes, with the peer.
pub fn time_to_target_table(timing: &WorkTiming) -> String {
    time_to_target(std::slice::from_ref(timing))
}

fn time_to_target(timings: &[WorkTiming]) -> String {
    let mut t = Table::new(&[
        "scene",
        "target",
        "fastest (global error)",
        "time",
        PEER_NAME,
        "fastest (energy error)",
        "time",
        PEER_NAME,
    ]);
    let who = |f: &Fastest| f.scheme.map_or("none".into(), |s| format!("`{s}`"));
    for w in timings {
        for (g, e) in w.fastest_global.iter().zip(&w.fastest_energy) {
            t.row(vec![
                format!("`{}`", w.scene),
                format!("{:.0e}", g.target),
                who(g),
                time_reach(g.seconds),
                time_reach(g.peer_seconds),
                who(e),
                time_reach(e.seconds),
                time_reach(e.peer_seconds),
            ]);
        }
    }
    t.render()
}

/// The machine-dependent part of the section.
pub fn timing_section(speed: &SpeedRecord, timings: &[WorkTiming]) -> String {
    let mut out =
        String::from("\n## Speed against error (machine-dependent)\n\n### Cost of a step\n\n");
    out.push_str(&speed_table(speed));
    out.push_str(
        "\n### Time to target\n\nA scheme's time is its force evaluations to the target \
         times its time per evaluation on the scene (steps of 1/1000 period, fastest of \
         several runs); the peer's runs are timed whole (set-up and output included, \
         fastest of several) and interpolated like its evaluations.\n\n",
    );
    out.push_str(&time_to_target(timings));
    out
}
