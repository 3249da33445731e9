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
    Inconclusive,
    /// The integrator makes no claim this measurement could judge: an
    /// implicit black box that does not report its solves has no count of
    /// its own to check, an adaptive integrator that states no error factor
    /// has none to meet. The record shows what was measured.
    NotClaimed,
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
            Verdict::NotClaimed => "not-claimed",
        }
    }

    /// The one rule every guard follows: a claim fails its guard when the
    /// measurement refutes it **or cannot decide it**.
    ///
    /// A guard stands between a refactor and a green `cargo test`; it may
    /// only pass on evidence that the claim still holds. An inconclusive
    /// record (a ladder that never reached its asymptotic range, a run that
    /// stopped at the counting step, an energy record too short to tell
    /// bounded from drifting) is no such evidence, so it fails, and its
    /// message says what to change to decide it. A claim the integrator does
    /// not make ([`Verdict::NotClaimed`]) has nothing to refute and passes.
    pub fn fails_a_guard(self) -> bool {
        matches!(self, Verdict::Fail | Verdict::Inconclusive)
    }
}
