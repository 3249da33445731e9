//! `stepladder`: with no arguments, runs the whole suite and writes REPORT.md.

fn main() -> std::process::ExitCode {
    // Rust ignores SIGPIPE, so writing to a closed pipe (`stepladder | head`)
    // would panic; the default action ends the process quietly, as for any
    // command-line tool.
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any thread exists; SIG_DFL is
    // a valid disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    stepladder_lab::cli::main()
}
