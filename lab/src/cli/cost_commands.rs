//! The cost and round-off studies on the command line: `roundoff`,
//! `speed`, `longrun`, `work`.

use super::print_json;
use crate::report;
use clap::Args;
use serde::Serialize;
use std::process::ExitCode;
use stepladder::error::Error;
use stepladder::internals::parallel::default_threads;
use stepladder::scene::AnyScene;

#[derive(Debug, Args)]
pub(super) struct RoundoffArgs {
    /// Scene id, optionally with parameters (default harmonic).
    #[arg(long, default_value = "harmonic")]
    scene: String,
    /// Only the pair of this scheme (plain or compensated id; default: all three).
    #[arg(long)]
    scheme: Option<String>,
    /// Length of each run in periods (default 1).
    #[arg(long, allow_negative_numbers = true)]
    periods: Option<f64>,
    /// Finest step of the ladder, in steps per period (default 2^24).
    #[arg(long)]
    max_steps: Option<u64>,
    /// Print the record as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Args)]
pub(super) struct SpeedArgs {
    /// Timed runs per scheme; the fastest is kept.
    #[arg(long, default_value_t = stepladder::internals::cost::step_time::SPEED_REPEATS)]
    repeats: usize,
    /// Steps per timed run.
    #[arg(long, default_value_t = stepladder::internals::cost::step_time::SPEED_STEPS)]
    steps: u64,
    /// Print the record as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Args)]
pub(super) struct LongrunArgs {
    /// Scheme id: a Verlet form or its compensated variant (default: all six).
    #[arg(long)]
    scheme: Option<String>,
    /// Scene id: harmonic (modified energy), kepler-circular or
    /// kepler-eccentric (angular momentum); default harmonic.
    #[arg(long, default_value = "harmonic")]
    scene: String,
    /// Steps of each run (default 2^18).
    #[arg(long)]
    steps: Option<u64>,
    /// Print the records as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Args)]
pub(super) struct WorkArgs {
    /// Scene id (see `stepladder list`), optionally with parameters:
    /// `kepler-eccentric:e=0.9`.
    #[arg(long)]
    scene: String,
    /// Worker threads (default: every core); results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Print the record (and the timings) as JSON.
    #[arg(long)]
    json: bool,
}

pub(super) fn roundoff(args: &RoundoffArgs) -> Result<ExitCode, Error> {
    use stepladder::internals::round_off::floor::{RoundoffSpec, assemble, roundoff, study_pair};
    let scene = AnyScene::parse(&args.scene)?;
    let spec = RoundoffSpec {
        periods: args.periods,
        max_steps: args.max_steps,
    };
    let record = match &args.scheme {
        Some(id) => assemble(&scene, &spec, vec![study_pair(&scene, id, &spec)?])?,
        None => roundoff(&scene, &spec)?,
    };
    if args.json {
        print_json(&record);
    } else {
        println!(
            "{} ({}), {} periods, up to {} steps",
            record.scene,
            record.scene_parameters,
            stepladder::internals::wording::exact(record.periods),
            record.max_steps
        );
        print!("{}", report::round_off::floor_table(&record));
        println!();
        print!("{}", report::round_off::law_table(&record));
        for p in &record.pairs {
            print!("{}", report::round_off::pair_rungs(p));
        }
    }
    Ok(ExitCode::SUCCESS)
}

pub(super) fn speed(args: &SpeedArgs) -> Result<ExitCode, Error> {
    if args.repeats == 0 {
        return Err(Error::InvalidParameter {
            name: "repeats",
            value: 0.0,
            expected: "at least 1",
        });
    }
    if args.steps == 0 {
        return Err(Error::InvalidParameter {
            name: "steps",
            value: 0.0,
            expected: "at least 1",
        });
    }
    // counted in floating point, so that a refusal prints the true count
    let runs = args.repeats as f64 * (stepladder::scheme::scheme_ids().len() + 1) as f64;
    stepladder::internals::ladder::check_count(args.steps as f64 * runs)?;
    let record = stepladder::internals::cost::step_time::speed(args.steps, args.repeats);
    if args.json {
        print_json(&record);
    } else {
        print!("{}", report::speed_table(&record));
    }
    Ok(ExitCode::SUCCESS)
}

pub(super) fn longrun(args: &LongrunArgs) -> Result<ExitCode, Error> {
    use stepladder::internals::round_off::longrun::{LongrunSpec, longrun_of};
    let scene = AnyScene::parse(&args.scene)?;
    let spec = LongrunSpec { steps: args.steps };
    let ids = match &args.scheme {
        Some(id) => vec![id.as_str()],
        None => stepladder::internals::compensated::pair_ids(),
    };
    // refuse the whole request up front, not after some runs
    let per_scheme =
        args.steps
            .unwrap_or(stepladder::internals::round_off::longrun::DEFAULT_STEPS) as f64
            * stepladder::internals::round_off::longrun::RUNS as f64;
    stepladder::internals::ladder::check_count(per_scheme * ids.len() as f64)?;
    let records = ids
        .into_iter()
        .map(|id| longrun_of(&scene, id, &spec))
        .collect::<Result<Vec<_>, _>>()?;
    if args.json {
        print_json(&records);
    } else {
        print!("{}", report::round_off::longrun_table(&records));
    }
    Ok(ExitCode::SUCCESS)
}

/// The `work` command's JSON: the deterministic record and the timings.
#[derive(Serialize)]
struct WorkOutput {
    #[serde(flatten)]
    record: crate::suite::work_precision::WorkRecord,
    timing: crate::suite::work_precision::WorkTiming,
    /// The tolerance ladders of the adaptive integrators on the same scene.
    adaptive: Vec<stepladder::internals::adaptive::ToleranceLadderRecord>,
}

pub(super) fn work(args: &WorkArgs) -> Result<ExitCode, Error> {
    if args.threads == Some(0) {
        return Err(Error::InvalidParameter {
            name: "threads",
            value: 0.0,
            expected: "at least 1",
        });
    }
    let scene = AnyScene::parse(&args.scene)?;
    let (record, timing) = crate::suite::work_precision::work_on(
        &scene,
        args.threads.unwrap_or_else(default_threads),
    )?;
    let adaptive = crate::suite::adaptive::INTEGRATORS
        .iter()
        .map(|&i| {
            crate::suite::adaptive::ladder_of(
                i,
                &scene,
                &stepladder::internals::adaptive::ToleranceLadderSpec::default(),
            )
        })
        .collect::<Result<Vec<_>, Error>>()?;
    if args.json {
        print_json(&WorkOutput {
            record,
            timing,
            adaptive,
        });
    } else {
        print!("{}", report::work_scene(&record));
        println!();
        print!("{}", report::adaptive_summary_table(&adaptive));
        println!();
        print!("{}", report::time_to_target_table(&timing));
    }
    Ok(ExitCode::SUCCESS)
}
