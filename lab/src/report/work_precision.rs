//! The report's "Speed against error" section: work-precision tables in
//! force evaluations (deterministic), and ns per step and time to target
//! (machine-dependent).

use super::markdown::{Table, evaluations, sci, time_reach};
use crate::peer::{PEER_TOLERANCES, peer_names};
use crate::suite::race::RaceRecords;
use crate::suite::work_precision::{Cheapest, Fastest, WorkRecord, WorkTiming};
use std::fmt::Write as _;
use stepladder::internals::cost::step_time::SpeedRecord;
use stepladder::internals::cost::work_points::{
    ENERGY_FLOOR_GUARD, ENERGY_MAX_STEPS, ENERGY_PERIODS, ENERGY_START, Reach, TARGETS, TargetCost,
};

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
         for the implicit scheme, whose iterations vary with the step), and where they \
         stop above the smallest target, further rungs at the same ratio against the \
         exact solution until two successive rungs meet it, the error no longer falls as \
         the order promises (one rung more after a first meet, which confirms it or takes \
         it back), or a rung would break the order study's cap;\n\
         - **energy error**: the largest `|E - E0|/|E0|` over {ENERGY_PERIODS} periods, on a \
         ladder of its own halving the step from {ENERGY_START} period until the error is \
         below the smallest target, has stopped halving below {ENERGY_FLOOR_GUARD:e} \
         (round-off), or a run would take more than {ENERGY_MAX_STEPS} steps.\n\n\
         The cost of a target is interpolated on log-log axes between the two measured \
         runs that bracket it, never extrapolated: `<=` marks a target already met by the \
         cheapest run measured (or by the first run after one that blew up), whose cost is \
         then an upper bound, and `not reached` a target no run met. The cheapest scheme \
         is the one with the fewest evaluations, an upper bound counting at its value. The peers \
         are adaptive integrators of other published crates on `y = (q, v)`: the `ode_solvers` \
         crate's `Dop853` (Dormand-Prince 8(5,3), twelve evaluations a step) and the \
         `numeris` crate's `RKV98NoInterp` (Verner's 9(8) pair without interpolant stages, \
         sixteen), at relative and absolute tolerances {} to {}, one a decade, judged the \
         same way: the error at every step each takes against the exact solution, the force \
         evaluations counted in the system function it is handed (rejected steps and the \
         initial step-size guess included; each crate's own statistics report the same \
         count).\n\n",
        sci(PEER_TOLERANCES[0]),
        sci(PEER_TOLERANCES[PEER_TOLERANCES.len() - 1]),
    )
}

/// The cheapest scheme per target and scene, global and energy error, with
/// the peers beside.
pub fn cheapest_table(records: &[WorkRecord]) -> String {
    let header = by_target_header("cheapest", "evaluations");
    let mut t = Table::new(&header.iter().map(String::as_str).collect::<Vec<_>>());
    let who = |c: &Cheapest| c.scheme.map_or("none".into(), |s| format!("`{s}`"));
    for r in records {
        for (g, e) in r.cheapest_global.iter().zip(&r.cheapest_energy) {
            let mut row = vec![
                format!("`{}`", r.scene),
                format!("{:.0e}", g.target),
                who(g),
                evaluations(g.reach),
            ];
            row.extend(peer_cells(&g.peers, evaluations));
            row.extend([who(e), evaluations(e.reach)]);
            row.extend(peer_cells(&e.peers, evaluations));
            t.row(row);
        }
    }
    t.render()
}

/// The header of a per-target table: scene and target, then for the global
/// and the energy error the `best` scheme, its `cost` and every peer's.
fn by_target_header(best: &str, cost: &str) -> Vec<String> {
    let mut header = vec!["scene".to_string(), "target".to_string()];
    for error in ["global", "energy"] {
        header.extend([format!("{best} ({error} error)"), cost.to_string()]);
        header.extend(peer_names().iter().map(|p| p.to_string()));
    }
    header
}

/// One cell per peer, `-` where a scene had no peer run.
fn peer_cells(reaches: &[Reach], show: fn(Reach) -> String) -> Vec<String> {
    (0..peer_names().len())
        .map(|i| reaches.get(i).map_or("-".into(), |&r| show(r)))
        .collect()
}

/// One scene's table: force evaluations of every scheme and every peer to
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
    for p in &r.peers {
        let mut row = vec![p.peer.to_string(), p.order.to_string()];
        row.extend(costs(&p.global_targets));
        row.extend(costs(&p.energy_targets));
        t.row(row);
    }
    t.render()
}

/// One peer's runs on one scene, tolerance by tolerance.
pub fn peer_table(p: &crate::peer::PeerWork) -> String {
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

/// The deterministic part of the section.
pub fn deterministic_section(records: &[WorkRecord], race: &RaceRecords) -> String {
    let mut out = String::from("\n## Speed against error\n\n");
    out.push_str(&method());
    out.push_str(&super::race::race_section(race));
    out.push_str("\n### Cheapest scheme per target\n\n");
    out.push_str(&cheapest_table(records));
    out.push_str(
        "\nThe work-precision figures are in the summary; the force evaluations each \
         scheme needs for each target are on \
         [a detail page](details/work-evaluations.md).\n",
    );
    out
}

/// Force evaluations to reach each target, per scene, with each peer's
/// tolerances: the numbers behind the work-precision figures.
pub fn evaluations_by_target(records: &[WorkRecord]) -> String {
    let mut out = String::new();
    for r in records {
        let _ = writeln!(out, "\n## {}\n", r.scene);
        out.push_str(&work_table(r));
        for p in &r.peers {
            let _ = writeln!(
                out,
                "\n<details><summary>{} on <code>{}</code>, tolerance by \
                 tolerance</summary>\n",
                p.peer, r.scene
            );
            out.push_str(&peer_table(p));
            out.push_str("\n</details>\n");
        }
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

/// The fastest scheme per target on one or more scenes, with the peers.
pub fn time_to_target_table(timing: &WorkTiming) -> String {
    time_to_target(std::slice::from_ref(timing))
}

fn time_to_target(timings: &[WorkTiming]) -> String {
    let header = by_target_header("fastest", "time");
    let mut t = Table::new(&header.iter().map(String::as_str).collect::<Vec<_>>());
    let who = |f: &Fastest| f.scheme.map_or("none".into(), |s| format!("`{s}`"));
    for w in timings {
        for (g, e) in w.fastest_global.iter().zip(&w.fastest_energy) {
            let mut row = vec![
                format!("`{}`", w.scene),
                format!("{:.0e}", g.target),
                who(g),
                time_reach(g.seconds),
            ];
            row.extend(peer_cells(&g.peers_seconds, time_reach));
            row.extend([who(e), time_reach(e.seconds)]);
            row.extend(peer_cells(&e.peers_seconds, time_reach));
            t.row(row);
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
         several runs); a peer's runs are timed whole (set-up and output included, \
         fastest of several, while other jobs of the suite share the machine) and \
         interpolated like its evaluations.\n\n",
    );
    out.push_str(&time_to_target(timings));
    out
}
