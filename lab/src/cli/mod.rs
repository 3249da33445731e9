//! The command-line front end: each subcommand maps onto one study (or the
//! whole suite). Exit status: 0 success, 1 a verdict failed, 2 bad input or
//! an error, with a one-line message on stderr.

use crate::case::case;
use crate::report;
use crate::suite::run_suite;
use clap::{Args, Parser, Subcommand};
use cost_commands::{LongrunArgs, RoundoffArgs, SpeedArgs, WorkArgs};
use serde::Serialize;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use stepladder::error::Error;
use stepladder::internals::accuracy::order::{OrderRecord, OrderSpec};
use stepladder::internals::geometry::energy::EnergySpec;
use stepladder::internals::geometry::reverse::ReverseSpec;
use stepladder::internals::geometry::symplectic::SymplecticSpec;
use stepladder::internals::ladder::{AUTO_START, Ladder, LadderChoice};
use stepladder::internals::parallel::default_threads;
use stepladder::internals::stability::{StabilityRecord, stability};
use stepladder::internals::wording::exact;
use stepladder::scene::AnyScene;
use stepladder::scheme::catalogue;
use stepladder::study::Verdict;

mod cost_commands;
mod hard_commands;
mod sensitivity_command;

/// Is your time integrator as accurate, stable and geometric as it claims?
#[derive(Debug, Parser)]
#[command(name = "stepladder", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run every study on every scheme and scene, print the order table and
    /// write the report (the default command).
    Report(ReportArgs),
    /// List the schemes and scenes with their metadata.
    List {
        /// Print JSON instead of tables.
        #[arg(long)]
        json: bool,
    },
    /// Measure the global order of one scheme on one scene over a ladder of
    /// step sizes (exit status 1 when the verdict fails).
    Order(OrderArgs),
    /// Run one scheme for a long time and classify how its energy error grows.
    Energy(EnergyArgs),
    /// Take the exact tangent map of one step and test it for symplecticity.
    Symplectic(SymplecticArgs),
    /// Run forward, then back with -h, and measure how far from the start it ends.
    Reverse(ReverseArgs),
    /// Error against the step down to the round-off floor, for the Verlet
    /// forms beside their compensated-summation variants.
    Roundoff(RoundoffArgs),
    /// Follow a quantity the Verlet forms conserve exactly over millions of
    /// steps: how round-off grows, with and without compensated summation.
    Longrun(LongrunArgs),
    /// Orders and energy on eccentric Kepler orbits (e = 0.5, 0.6, 0.9, 0.99),
    /// and where a fixed step cannot resolve the pericentre (exit status 1
    /// when an order verdict fails).
    Eccentric(hard_commands::EccentricArgs),
    /// How long each scheme follows the separatrix of the anharmonic well
    /// before falling back or escaping, against the step (exit status 1 when
    /// the following times disagree with the linearised theory).
    Separatrix(hard_commands::SeparatrixArgs),
    /// Does each scheme tell an orbit just below the well's barrier from one
    /// just above it, and from which step down (exit status 1 when a scheme
    /// has no correct step down to where the separatrix law puts one)?
    Escape(hard_commands::EscapeArgs),
    /// Find the steps z = h w0 for which a scheme is stable on the oscillator.
    Stability {
        /// Scheme id (see `stepladder list`).
        #[arg(long)]
        scheme: String,
        /// Print the record as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Time a step of every scheme on the circular orbit against a
    /// hand-written velocity Verlet loop on plain f64 (machine-dependent).
    Speed(SpeedArgs),
    /// Judge the verdict corpus: schemes and scenes outside the catalogue,
    /// each with the verdicts it must get; print the confusion matrix (exit
    /// status 1 when any verdict is wrong).
    Corpus {
        /// Worker threads (default: every core); results do not depend on it.
        #[arg(long)]
        threads: Option<usize>,
        /// Print every outcome as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Error against cost on one scene: force evaluations and wall time each
    /// scheme (and each peer: ode_solvers' Dop853, numeris' Verner 9(8))
    /// needs to reach target errors.
    Work(WorkArgs),
    /// The reference state the race judges an N-body scene against at its
    /// end time, with where it comes from and its error bound, as JSON
    /// (`pleiades` or `outer-solar-system`).
    Reference {
        /// Scene id: `pleiades` or `outer-solar-system`.
        #[arg(long)]
        scene: String,
    },
    /// The sensitivity map: every coefficient of every catalogue table
    /// moved in turn, and the smallest change each claim of the guard
    /// rejects; writes lab/SENSITIVITY.md.
    Sensitivity(sensitivity_command::SensitivityArgs),
}

/// The scheme and scene every single-case study takes.
#[derive(Debug, Args)]
struct CaseArgs {
    /// Scheme id (see `stepladder list`).
    #[arg(long)]
    scheme: String,
    /// Scene id (see `stepladder list`), optionally with parameters:
    /// `harmonic:w0=50,x0=2`.
    #[arg(long)]
    scene: String,
    /// Print the record as JSON.
    #[arg(long)]
    json: bool,
}

impl CaseArgs {
    fn case(&self) -> Result<Box<dyn crate::case::Case>, Error> {
        case(&self.scheme, &AnyScene::parse(&self.scene)?)
    }
}

#[derive(Debug, Args)]
struct EnergyArgs {
    #[command(flatten)]
    case: CaseArgs,
    /// Step size (default: 1/100 of a period).
    #[arg(long, allow_negative_numbers = true)]
    h: Option<f64>,
    /// Length of the run in periods (default 10000).
    #[arg(long, allow_negative_numbers = true)]
    periods: Option<f64>,
}

#[derive(Debug, Args)]
struct SymplecticArgs {
    #[command(flatten)]
    case: CaseArgs,
    /// Step size (default: 1/10, 1/30 and 1/100 of a period).
    #[arg(long, allow_negative_numbers = true)]
    h: Option<f64>,
}

#[derive(Debug, Args)]
struct ReverseArgs {
    #[command(flatten)]
    case: CaseArgs,
    /// Step size (default: 1/100 of a period).
    #[arg(long, allow_negative_numbers = true)]
    h: Option<f64>,
    /// Steps each way (default 1000).
    #[arg(long)]
    steps: Option<u64>,
}

#[derive(Debug, Args)]
struct ReportArgs {
    /// Where to write the report.
    #[arg(long, default_value = DEFAULT_REPORT)]
    output: PathBuf,
    /// Worker threads (default: every core); results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Where to draw the figures (SVG); default: `figures/` beside the report,
    /// where the report's links point.
    #[arg(long)]
    figures: Option<PathBuf>,
}

impl Default for ReportArgs {
    fn default() -> Self {
        Self {
            output: PathBuf::from(DEFAULT_REPORT),
            threads: None,
            figures: None,
        }
    }
}

/// Where the report goes unless told otherwise.
const DEFAULT_REPORT: &str = "REPORT.md";

#[derive(Debug, Args)]
struct OrderArgs {
    /// Scheme id (see `stepladder list`).
    #[arg(long)]
    scheme: String,
    /// Scene id (see `stepladder list`), optionally with parameters:
    /// `harmonic:w0=50,x0=2`.
    #[arg(long)]
    scene: String,
    /// End time of every rung (default: 2 sqrt(2) periods of the scene).
    #[arg(long, allow_negative_numbers = true)]
    t_end: Option<f64>,
    /// Coarsest step of a fixed ladder (default: 1/8 of a period). Giving
    /// any of --h0, --levels, --ratio replaces the automatic ladder.
    #[arg(long, allow_negative_numbers = true)]
    h0: Option<f64>,
    /// Rungs of a fixed ladder (default 10).
    #[arg(long)]
    levels: Option<usize>,
    /// Each rung's step over the previous one, in (0, 1) (default 0.5).
    #[arg(long, allow_negative_numbers = true)]
    ratio: Option<f64>,
    /// Print the record as JSON.
    #[arg(long)]
    json: bool,
}

/// Parses the arguments and runs the command; the process's exit status.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => e.exit(), // --help, --version
        Err(e) => {
            // clap's message without its usage block, on one line like every other error
            let text = e.render().to_string();
            let message: Vec<&str> = text
                .lines()
                .map(str::trim)
                .take_while(|l| !l.is_empty() && !l.starts_with("Usage:"))
                .collect();
            eprintln!("stepladder: {} (see --help)", message.join(" "));
            return ExitCode::from(2);
        }
    };
    // the report and the map print their own progress
    if !matches!(
        cli.command,
        None | Some(Command::Report(_) | Command::Sensitivity(_))
    ) {
        heartbeat(std::env::args().skip(1).collect::<Vec<_>>().join(" "));
    }
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("stepladder: error: {e}");
            ExitCode::from(2)
        }
    }
}

/// Seconds of silence after which a command says it is still working, and
/// then again as often: the step limit bounds a request at about a minute of
/// a cheap step, but a scheme of many stages or an implicit one steps up to
/// ten times slower, and a study prints nothing until its table.
const HEARTBEAT_SECONDS: u64 = 10;

/// Tells the user on stderr, every [`HEARTBEAT_SECONDS`], that `what` is
/// still running; the thread ends with the process.
fn heartbeat(what: String) {
    let start = std::time::Instant::now();
    std::thread::spawn(move || {
        loop {
            std::thread::sleep(std::time::Duration::from_secs(HEARTBEAT_SECONDS));
            eprintln!(
                "stepladder {what}: still working ({:.0} s)",
                start.elapsed().as_secs_f64()
            );
        }
    });
}

fn run(cli: Cli) -> Result<ExitCode, Error> {
    match cli
        .command
        .unwrap_or(Command::Report(ReportArgs::default()))
    {
        Command::Report(args) => report(&args),
        Command::List { json } => {
            list(json);
            Ok(ExitCode::SUCCESS)
        }
        Command::Order(args) => order(&args),
        Command::Roundoff(args) => cost_commands::roundoff(&args),
        Command::Longrun(args) => cost_commands::longrun(&args),
        Command::Eccentric(a) => hard_commands::eccentric(&a),
        Command::Separatrix(a) => hard_commands::separatrix(&a),
        Command::Escape(a) => hard_commands::escape(&a),
        Command::Stability { scheme, json } => {
            let r = stepladder::scheme::visit_scheme(&scheme, StabilityOf)?;
            if json {
                print_json(&r);
            } else {
                print!("{}", report::stability_table(std::slice::from_ref(&r)));
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Speed(a) => cost_commands::speed(&a),
        Command::Work(a) => cost_commands::work(&a),
        Command::Sensitivity(a) => sensitivity_command::sensitivity(&a),
        Command::Reference { scene } => {
            println!("{}", crate::suite::race::reference_json(&scene)?);
            Ok(ExitCode::SUCCESS)
        }
        Command::Corpus { threads, json } => corpus(threads, json),
        Command::Energy(a) => {
            let r = a.case.case()?.energy(&EnergySpec {
                h: a.h,
                periods: a.periods,
            })?;
            let text = format!(
                "{} on {}: h = {}, {} steps, max relative energy error {:.3e}, g = {}, {}",
                r.scheme,
                r.scene,
                exact(r.h),
                r.steps,
                r.max_relative_energy_error,
                // a run that stopped has no growth law, whatever a fit to
                // its few samples gives
                r.growth_exponent
                    .filter(|_| r.outcome.completed())
                    .map_or("-".into(), |g| format!("{g:.3}")),
                r.reason
            );
            emit(a.case.json, &r, &text, r.verdict)
        }
        Command::Symplectic(a) => {
            let r = a.case.case()?.symplectic(&SymplecticSpec { h: a.h })?;
            let text = format!(
                "{} on {}: det(J) - 1 = {:.3e}, symplectic residual {:.3e} over {} samples: {}",
                r.scheme,
                r.scene,
                r.det_minus_one,
                r.symplectic_residual,
                r.samples.len(),
                r.reason
            );
            emit(a.case.json, &r, &text, r.verdict)
        }
        Command::Reverse(a) => {
            let r = a.case.case()?.reverse(&ReverseSpec {
                h: a.h,
                steps: a.steps,
            })?;
            let text = format!(
                "{} on {}: {} steps of {} and back, return error {}: {}",
                r.scheme,
                r.scene,
                r.steps,
                exact(r.h),
                r.return_error.map_or("-".into(), |e| format!("{e:.3e}")),
                r.reason
            );
            emit(a.case.json, &r, &text, r.verdict)
        }
    }
}

/// The stability study of a catalogue scheme.
struct StabilityOf;
impl stepladder::scheme::SchemeVisitor for StabilityOf {
    type Output = StabilityRecord;
    fn visit<M: stepladder::scheme::Scheme + Sync + 'static>(
        self,
        scheme: &'static M,
    ) -> StabilityRecord {
        stability(scheme)
    }
}

/// Prints a record as JSON or as its one-line summary; exit status from its verdict.
fn emit<T: Serialize>(
    json: bool,
    record: &T,
    text: &str,
    verdict: Verdict,
) -> Result<ExitCode, Error> {
    if json {
        print_json(record);
    } else {
        println!("{}: {text}", verdict.name().to_uppercase());
    }
    Ok(exit_for(verdict == Verdict::Pass))
}

fn report(args: &ReportArgs) -> Result<ExitCode, Error> {
    if args.threads == Some(0) {
        return Err(Error::InvalidParameter {
            name: "threads",
            value: 0.0,
            expected: "at least 1",
        });
    }
    report::check_writable(&args.output)?;
    let show = std::io::stderr().is_terminal();
    let records = run_suite(args.threads.unwrap_or_else(default_threads), &|p| {
        // a terminal sees one line rewritten in place; a pipe or a CI log
        // sees nothing
        if show && p.item.is_empty() {
            eprint!("\r\x1b[2K{}...", p.part);
        } else if show {
            eprint!("\r\x1b[2K{} [{}/{}] {}", p.part, p.done, p.total, p.item);
        }
    })?;
    if show {
        eprintln!();
    }
    report::write_atomically(&args.output, &report::render(&records))?;
    let dir = args
        .figures
        .clone()
        .unwrap_or_else(|| report::figures::beside(&args.output));
    let written = report::figures::write_figures(&dir, &records)?;
    eprintln!("{} figures written to {}", written.len(), dir.display());
    let pages = report::pages::beside(&args.output);
    let written = report::pages::write_pages(&pages, &records)?;
    eprintln!(
        "{} detail pages written to {}",
        written.len(),
        pages.display()
    );
    print!("{}", report::order_table(&records.order()));
    println!();
    print!("{}", report::geometry_table(&records.cases));
    let (passed, total) = records.verdicts();
    println!(
        "\n{passed} of {total} verdicts pass; report written to {} in {:.1} s",
        args.output.display(),
        records.total.as_secs_f64()
    );
    Ok(exit_for(passed == total))
}

#[derive(Serialize)]
struct Listing {
    schemes: Vec<&'static stepladder::scheme::SchemeMeta>,
    scenes: Vec<SceneListing>,
}

#[derive(Serialize)]
struct SceneListing {
    #[serde(flatten)]
    meta: stepladder::scene::SceneMeta,
    /// `(name, meaning)` of every parameter `--scene id:name=value` accepts.
    accepts: &'static [(&'static str, &'static str)],
}

fn list(json: bool) {
    let listing = Listing {
        schemes: catalogue(),
        scenes: AnyScene::all()
            .iter()
            .map(|s| SceneListing {
                meta: s.meta(),
                accepts: s.accepts(),
            })
            .collect(),
    };
    if json {
        print_json(&listing);
        return;
    }
    let mut t = report::Table::new(&[
        "scheme",
        "order",
        "symplectic",
        "symmetric",
        "forces/step",
        "name",
    ]);
    for m in &listing.schemes {
        let yn = |b: bool| if b { "yes" } else { "no" }.to_string();
        t.row(vec![
            m.id.into(),
            m.order.to_string(),
            yn(m.symplectic),
            yn(m.symmetric),
            m.forces_label(),
            m.name.into(),
        ]);
    }
    println!("{}", t.render());
    let mut t = report::Table::new(&[
        "scene",
        "dimension",
        "defaults",
        "parameters (--scene id:name=value)",
    ]);
    for s in &listing.scenes {
        let accepts: Vec<String> = s.accepts.iter().map(|(n, m)| format!("{n}: {m}")).collect();
        t.row(vec![
            s.meta.id.into(),
            s.meta.dimension.to_string(),
            s.meta.parameters.clone(),
            if accepts.is_empty() {
                "none".into()
            } else {
                accepts.join("; ")
            },
        ]);
    }
    print!("{}", t.render());
}

fn order(args: &OrderArgs) -> Result<ExitCode, Error> {
    let scene = AnyScene::parse(&args.scene)?;
    let c = case(&args.scheme, &scene)?;
    let ladder = if args.h0.is_none() && args.levels.is_none() && args.ratio.is_none() {
        LadderChoice::Auto
    } else {
        let period = scene.period();
        LadderChoice::Fixed(Ladder::new(
            args.h0.unwrap_or(AUTO_START * period),
            args.ratio.unwrap_or(0.5),
            args.levels.unwrap_or(10),
        )?)
    };
    let record = c.order(&OrderSpec {
        t_end: args.t_end,
        ladder,
    })?;
    if args.json {
        print_json(&record);
    } else {
        print_order(&record);
    }
    Ok(exit_for(record.passed()))
}

fn corpus(threads: Option<usize>, json: bool) -> Result<ExitCode, Error> {
    use crate::corpus::{Confusion, entries, judge_all};
    if threads == Some(0) {
        return Err(Error::InvalidParameter {
            name: "threads",
            value: 0.0,
            expected: "at least 1",
        });
    }
    let outcomes = judge_all(
        &entries(),
        threads.unwrap_or_else(default_threads),
        &|_, _| {},
    )?;
    let matrix = Confusion::of(&outcomes);
    if json {
        #[derive(Serialize)]
        struct CorpusJson<'a> {
            confusion: Confusion,
            outcomes: &'a [crate::corpus::Outcome],
        }
        print_json(&CorpusJson {
            confusion: matrix,
            outcomes: &outcomes,
        });
    } else {
        print!("{}", report::corpus_section(&outcomes));
        println!();
        print!("{}", report::corpus_entries(&outcomes));
    }
    Ok(exit_for(matrix.wrong() == 0))
}

fn exit_for(passed: bool) -> ExitCode {
    if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn print_order(r: &OrderRecord) {
    println!(
        "{} on {} ({}), t_end = {}: theoretical order {}",
        r.scheme,
        r.scene,
        r.scene_parameters,
        exact(r.t_end),
        r.theoretical_order
    );
    println!(
        "{:>4} {:>11} {:>10} {:>11} {:>11} {:>11} {:>7}  status",
        "rung", "h", "steps", "error", "final", "round-off", "local"
    );
    for (i, g) in r.rungs.iter().enumerate() {
        let e = |x: Option<f64>| x.map_or("-".into(), |x| format!("{x:.3e}"));
        let status = match (g.used, g.dropped) {
            (true, _) => "fitted",
            (false, Some(d)) => d.explain(),
            (false, None) => "unused",
        };
        println!(
            "{i:>4} {:>11.4e} {:>10} {:>11} {:>11} {:>11} {:>7}  {status}",
            g.h,
            g.steps,
            e(g.error),
            e(g.final_error),
            e(g.round_off_bound),
            g.local_order.map_or("-".into(), |p| format!("{p:.3}")),
        );
    }
    println!("{}: {}", r.verdict.name().to_uppercase(), r.reason);
    if let Some(advice) = &r.advice {
        println!("to decide: {advice}");
    }
}

/// Prints a record as pretty JSON on stdout.
pub(super) fn print_json<T: Serialize + ?Sized>(value: &T) {
    println!(
        "{}",
        serde_json::to_string_pretty(value).expect("plain data serialises")
    );
}
