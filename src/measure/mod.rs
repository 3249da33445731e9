//! Studies: each turns runs of one scheme on one scene into a record, plain
//! serde data that feeds the CLI's `--json`, the snapshots and the report.

pub mod cost;
pub mod eccentric;
pub mod energy;
pub mod escape;
pub mod fit;
pub mod following;
pub mod longrun;
pub mod order;
pub mod peer;
pub mod phase;
pub mod reverse;
pub mod roundoff;
pub mod scene_check;
pub mod stability;
pub mod symplectic;
pub mod tangent;
pub mod trajectory;
pub mod work;

use serde::Serialize;

/// Does the measurement agree with the claim?
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// The measurement agrees with the claim.
    Pass,
    /// It refutes the claim.
    Fail,
    /// The data cannot decide; the record says why and what to change.
    /// Guards treat it as a failure unless told otherwise.
    Inconclusive,
}

impl Verdict {
    /// `Pass` when `ok`.
    pub fn from_bool(ok: bool) -> Self {
        if ok { Verdict::Pass } else { Verdict::Fail }
    }

    /// The kebab-case name used in records and tables.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Pass => "pass",
            Verdict::Fail => "fail",
            Verdict::Inconclusive => "inconclusive",
        }
    }
}
