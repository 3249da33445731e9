//! The one answer every study gives about a claim.

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
