//! What several test modules share.

use std::sync::OnceLock;
use stepladder::internals::parallel::default_threads;
use stepladder_lab::suite::{SuiteRecords, run_suite};

/// Every study on every scheme and scene, run once for the whole binary.
pub fn suite() -> &'static SuiteRecords {
    static SUITE: OnceLock<SuiteRecords> = OnceLock::new();
    SUITE.get_or_init(|| run_suite(default_threads(), &|_| {}).expect("the suite runs"))
}

/// The workspace root: the repository that holds REPORT.md, the figures,
/// the snapshots and the audit (this crate is its `lab/` folder).
pub fn root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("lab/ has a parent")
        .to_path_buf()
}

/// insta settings for the change detectors: snapshots live in the top-level
/// `snapshots/` folder (relative to the asserting file in `lab/tests/harness/`),
/// each carrying a description of what it pins.
pub fn settings(description: &str) -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path("../../../snapshots");
    s.set_prepend_module_to_snapshot(false);
    s.set_description(description);
    s.set_omit_expression(true);
    s
}
