//! What several test modules share.

use std::sync::OnceLock;
use stepladder::suite::{SuiteRecords, default_threads, run_suite};

/// Every study on every scheme and scene, run once for the whole binary.
pub fn suite() -> &'static SuiteRecords {
    static SUITE: OnceLock<SuiteRecords> = OnceLock::new();
    SUITE.get_or_init(|| run_suite(default_threads(), &|_, _, _| {}).expect("the suite runs"))
}
