//! Runs every audited method and writes AUDIT.md beside Cargo.toml; exits
//! with an error if any verdict differs from its expectation.

#[path = "../../lab/src/fingerprint.rs"]
mod audit_fingerprint;

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;
use stepladder_audit::{disagreements, methods::ALL, report::audit_md};

fn main() -> ExitCode {
    // the sources the studies below are built from, read before they run
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let fingerprint = match audit_fingerprint::fingerprint(&root) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("cannot read the sources to fingerprint them: {e}");
            return ExitCode::FAILURE;
        }
    };
    let clock = Instant::now();
    let audits: Vec<_> = ALL
        .iter()
        .map(|(name, run)| {
            let start = Instant::now();
            let audit = run();
            eprintln!("{name}: {:.1} s", start.elapsed().as_secs_f64());
            audit
        })
        .collect();
    let start = Instant::now();
    let races = match stepladder_audit::race::race() {
        Ok(r) => r,
        Err(e) => {
            eprintln!("cannot race: {e}");
            return ExitCode::FAILURE;
        }
    };
    eprintln!("the race: {:.1} s", start.elapsed().as_secs_f64());
    let seconds = clock.elapsed().as_secs_f64();
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/AUDIT.md");
    if let Err(e) = std::fs::write(path, audit_md(&audits, &races, seconds, &fingerprint)) {
        eprintln!("cannot write {path}: {e}");
        return ExitCode::FAILURE;
    }
    let differing: Vec<String> = audits.iter().flat_map(disagreements).collect();
    for d in &differing {
        eprintln!("{d}");
    }
    eprintln!(
        "{} methods in {seconds:.1} s; {} verdicts differ from their expectation",
        audits.len(),
        differing.len()
    );
    if differing.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
