//! `stepladder`: with no arguments, runs the whole suite and writes REPORT.md.

fn main() -> std::process::ExitCode {
    stepladder::cli::main()
}
