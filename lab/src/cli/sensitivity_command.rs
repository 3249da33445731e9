//! `stepladder sensitivity`: the sensitivity map, written to its page.

use crate::fingerprint::fingerprint_of;
use crate::sensitivity::page::{PAGE, page};
use crate::sensitivity::{SOURCES, sensitivity_map};
use clap::Args;
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;
use stepladder::error::Error;
use stepladder::internals::parallel::default_threads;
use stepladder::scene::AnyScene;

#[derive(Debug, Args)]
pub struct SensitivityArgs {
    /// Map one table only (a scheme id; default: every table), printed and
    /// not written.
    #[arg(long)]
    scheme: Option<String>,
    /// Map on one scene only (default: every scene), printed and not
    /// written.
    #[arg(long)]
    scene: Option<String>,
    /// Where to write the page (the whole map only).
    #[arg(long, default_value = PAGE)]
    output: PathBuf,
    /// Worker threads (default: every core); results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Print the map as JSON (every coefficient's row) instead of writing
    /// the page.
    #[arg(long)]
    json: bool,
}

pub fn sensitivity(args: &SensitivityArgs) -> Result<ExitCode, Error> {
    let threads = args.threads.unwrap_or_else(default_threads);
    if threads == 0 {
        return Err(Error::InvalidParameter {
            name: "threads",
            value: 0.0,
            expected: "at least 1",
        });
    }
    let scenes = match &args.scene {
        Some(s) => vec![AnyScene::parse(s)?],
        None => AnyScene::all(),
    };
    // the sources the map is made from, read before it runs
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let fingerprint =
        fingerprint_of(&root, &SOURCES, &[]).map_err(|source| Error::Io { path: root, source })?;
    let clock = Instant::now();
    // a terminal sees one line rewritten in place, a log one line per table
    let terminal = std::io::stderr().is_terminal();
    let progress = |id: &str| {
        let line = format!("mapping `{id}` ({:.0} s)", clock.elapsed().as_secs_f64());
        if terminal {
            eprint!("\r\x1b[2K{line}");
            let _ = std::io::stderr().flush();
        } else {
            eprintln!("{line}");
        }
    };
    let maps = sensitivity_map(&scenes, args.scheme.as_deref(), threads, &progress)?;
    if terminal {
        eprintln!();
    }
    if args.json {
        super::print_json(&maps);
        return Ok(ExitCode::SUCCESS);
    }
    let text = page(&maps, &fingerprint, clock.elapsed().as_secs_f64(), threads);
    if args.scheme.is_some() || args.scene.is_some() {
        print!("{text}");
    } else {
        crate::report::write_atomically(&args.output, &text)?;
        println!("wrote {}", args.output.display());
    }
    Ok(ExitCode::SUCCESS)
}
