//! The hard cases on the command line: `eccentric`, `separatrix`, `escape`.

use super::{exit_for, print_json};
use crate::report;
use crate::suite::hard_cases::{ESCAPE_DELTAS, HardCases, HardJob, run_hard_jobs};
use clap::Args;
use serde::Serialize;
use std::process::ExitCode;
use stepladder::error::Error;
use stepladder::internals::hard::eccentric::{
    ECCENTRICITIES, EccentricEnergyRecord, EccentricOrderRecord, ORDER_SCHEMES, OrderStatus,
    RoundOffRecord,
};
use stepladder::internals::hard::escape::{EscapeRecord, EscapeSpec};
use stepladder::internals::hard::following::{FollowingRecord, WellSpec};
use stepladder::internals::parallel::default_threads;
use stepladder::internals::tolerance::ECCENTRIC_MAX_RUNG_STEPS;
use stepladder::scene::{KeplerEccentric, Separatrix};
use stepladder::scheme::scheme_ids;

#[derive(Debug, Args)]
pub(super) struct EccentricArgs {
    /// Eccentricity in [0, 1); repeat for several (default: 0.5, 0.6, 0.9
    /// and 0.99).
    #[arg(long = "e", allow_negative_numbers = true)]
    e: Vec<f64>,
    /// Only this scheme (default: every scheme; the order study leaves out
    /// stormer-verlet and leapfrog, velocity Verlet's map, unless named here).
    #[arg(long)]
    scheme: Option<String>,
    /// Largest rung of the order ladders, in steps (default 131072).
    #[arg(long)]
    max_rung_steps: Option<u64>,
    /// Print the records as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Args)]
pub(super) struct SeparatrixArgs {
    /// Only this scheme (default: every scheme).
    #[arg(long)]
    scheme: Option<String>,
    /// Stiffness k of the well (default 1).
    #[arg(long, allow_negative_numbers = true)]
    k: Option<f64>,
    /// Barrier position alpha (default 1).
    #[arg(long, allow_negative_numbers = true)]
    alpha: Option<f64>,
    /// Print the records as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Args)]
pub(super) struct EscapeArgs {
    /// Relative energy gap from the barrier, in (0, 1); repeat for several
    /// (default: 0.01 and 0.001).
    #[arg(long, allow_negative_numbers = true)]
    delta: Vec<f64>,
    /// Only this scheme (default: every scheme).
    #[arg(long)]
    scheme: Option<String>,
    /// Print the records as JSON.
    #[arg(long)]
    json: bool,
}

/// The catalogue id `id` as a static string, or the one-line refusal.
fn scheme_id(id: &str) -> Result<&'static str, Error> {
    scheme_ids()
        .into_iter()
        .find(|s| *s == id)
        .ok_or_else(|| Error::UnknownScheme {
            id: id.to_string(),
            valid: scheme_ids().join(", "),
        })
}

/// The schemes asked for: one, or `default`.
fn schemes(asked: &Option<String>, default: &[&'static str]) -> Result<Vec<&'static str>, Error> {
    match asked {
        Some(id) => Ok(vec![scheme_id(id)?]),
        None => Ok(default.to_vec()),
    }
}

#[derive(Serialize)]
struct EccentricOutput<'a> {
    orders: &'a [EccentricOrderRecord],
    energy: &'a [EccentricEnergyRecord],
    naive_energy: &'a [EccentricEnergyRecord],
    round_off: &'a [RoundOffRecord],
}

pub(super) fn eccentric(a: &EccentricArgs) -> Result<ExitCode, Error> {
    let es: Vec<f64> = if a.e.is_empty() {
        ECCENTRICITIES.to_vec()
    } else {
        a.e.clone()
    };
    for &e in &es {
        KeplerEccentric::new(e)?;
    }
    let cap = a.max_rung_steps.unwrap_or(ECCENTRIC_MAX_RUNG_STEPS);
    // the rung cap in force evaluations, for schemes of up to 17 a step,
    // within the automatic ladder's range (AutoLadder::checked)
    let most = stepladder::internals::ladder::MAX_TOTAL_STEPS / 4 / 17;
    if !(stepladder::internals::ladder::MIN_RUNG_EVALUATIONS..=most).contains(&cap) {
        return Err(Error::OutOfRange {
            name: "max-rung-steps",
            value: cap as f64,
            expected: format!(
                "a number of steps in [{}, {most}]: enough for a window's rungs, and a ladder \
                 within the step limit for a scheme of 17 force evaluations a step",
                stepladder::internals::ladder::MIN_RUNG_EVALUATIONS
            ),
        });
    }
    let order_ids = schemes(&a.scheme, &ORDER_SCHEMES)?;
    let energy_ids = schemes(&a.scheme, &scheme_ids())?;
    let mut jobs = Vec::new();
    for &e in &es {
        jobs.extend(order_ids.iter().map(|id| HardJob::Order(id, e, cap)));
        jobs.extend(energy_ids.iter().map(|id| HardJob::Energy(id, e)));
        jobs.push(HardJob::RoundOff(e));
    }
    let hard = run_hard_jobs(jobs, default_threads())?;
    if a.json {
        print_json(&EccentricOutput {
            orders: &hard.orders,
            energy: &hard.energy,
            naive_energy: &hard.naive_energy,
            round_off: &hard.round_off,
        });
    } else {
        print!("{}", report::eccentric_order_table(&hard.orders));
        println!("\nenergy at h = tau_p/8: class, max dE/E (times (1-e)/2)");
        print!("{}", report::eccentric_energy_grid(&hard.energy));
        println!("\nenergy at h = 0.01 period");
        print!("{}", report::eccentric_energy_grid(&hard.naive_energy));
        println!("\nround-off against velocity Verlet, in eps * scale");
        print!("{}", report::round_off_table(&hard.round_off));
    }
    Ok(exit_for(
        hard.orders.iter().all(|r| r.status != OrderStatus::Fail),
    ))
}

pub(super) fn separatrix(a: &SeparatrixArgs) -> Result<ExitCode, Error> {
    let d = WellSpec::default();
    let well = WellSpec {
        k: a.k.unwrap_or(d.k),
        alpha: a.alpha.unwrap_or(d.alpha),
    };
    Separatrix::new(well.k, well.alpha)?;
    let ids = schemes(&a.scheme, &scheme_ids())?;
    let jobs = ids.iter().map(|id| HardJob::Following(id, well)).collect();
    let hard = run_hard_jobs(jobs, default_threads())?;
    if a.json {
        print_json::<[FollowingRecord]>(&hard.following);
    } else {
        print!("{}", report::following_table(&hard.following));
        for r in &hard.following {
            println!();
            print!("{}", report::following_rungs(r));
        }
    }
    Ok(exit_for(
        hard.following.iter().all(|r| r.consistent != Some(false)),
    ))
}

#[derive(Serialize)]
struct EscapeOutput<'a> {
    escape: &'a [EscapeRecord],
    /// The separatrix records the predicted boundaries come from.
    following: &'a [FollowingRecord],
}

pub(super) fn escape(a: &EscapeArgs) -> Result<ExitCode, Error> {
    let deltas: Vec<f64> = if a.delta.is_empty() {
        ESCAPE_DELTAS.to_vec()
    } else {
        a.delta.clone()
    };
    for &d in &deltas {
        EscapeSpec::new(d)?;
    }
    let ids = schemes(&a.scheme, &scheme_ids())?;
    let mut jobs: Vec<HardJob> = Vec::new();
    for &d in &deltas {
        jobs.extend(ids.iter().map(|id| HardJob::Escape(id, d)));
    }
    jobs.extend(
        ids.iter()
            .map(|id| HardJob::Following(id, WellSpec::default())),
    );
    let hard: HardCases = run_hard_jobs(jobs, default_threads())?;
    if a.json {
        print_json(&EscapeOutput {
            escape: &hard.escape,
            following: &hard.following,
        });
    } else {
        print!("{}", report::escape_table(&hard.escape, &hard.following));
    }
    // a scheme with no correct step fails unless its boundary lies below
    // what the scan could reach (see `escape_undecided`)
    Ok(exit_for(hard.escape.iter().all(|r| {
        r.largest_correct.is_some() || report::escape_undecided(r, &hard.following).is_some()
    })))
}
