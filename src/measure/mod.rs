//! Studies: each turns runs of one scheme on one scene into a record, plain
//! serde data that feeds the CLI's `--json`, the snapshots and the report.
//! They are grouped by the question they answer:
//!
//! - [`accuracy`]: the global order (and its fit), the phase error, the
//!   course notes' trajectories, the check of every scene's exact solution;
//! - [`geometry`]: energy over long runs, symplecticity of the tangent map,
//!   reversibility;
//! - [`stability`]: the linear stability intervals;
//! - [`roundoff`]: the round-off floor of the Verlet forms and its growth
//!   over long runs;
//! - [`cost`]: time per step, force evaluations against error, the peer;
//! - [`hard`]: eccentric orbits, the separatrix, escape or trapped;
//! - [`wording`]: how reasons print figures and comparisons, and a reader
//!   that checks every printed comparison holds.

pub mod accuracy;
pub mod adaptive;
pub mod case;
pub mod cost;
pub mod geometry;
pub mod hard;
pub mod roundoff;
pub mod stability;
pub mod wording;

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
