//! The library's typed errors: every way a request can be refused.
//!
//! A scheme that blows up or a fit that finds no asymptotic window is not an
//! error: it is a measured outcome and lives in the study's record.

use crate::wording::{exact, figure};
use std::path::PathBuf;

/// Why a request could not be carried out.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A numeric parameter outside its domain.
    #[error("{name} = {} is invalid: expected {expected}", exact(*value))]
    InvalidParameter {
        /// The parameter's name as the user wrote it.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What would have been accepted.
        expected: &'static str,
    },

    /// A numeric parameter outside a range that depends on the others: a
    /// step longer than the run it divides, a run longer than its time can
    /// hold.
    #[error("{name} = {} is invalid: expected {expected}", exact(*value))]
    OutOfRange {
        /// The parameter's name as the user wrote it.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The valid range with the figures it follows from.
        expected: String,
    },

    /// An id that would name a file (a pin) but is not plain kebab-case,
    /// `[a-z0-9]+(-[a-z0-9]+)*`: a path such as `../x` or `a/b` would write
    /// outside the folder it is meant for.
    #[error(
        "{what} id {id:?} is invalid: expected plain kebab-case, lower-case letters and digits in words joined by single hyphens (`my-verlet`)"
    )]
    InvalidId {
        /// What the id names: `scheme`, `scene`, `integrator`.
        what: &'static str,
        /// The id given.
        id: String,
    },

    /// Scene parameters that are individually valid but make no problem.
    #[error("invalid scene: {0}")]
    InvalidScene(String),

    /// A tableau that makes no method (no stages or flows, a coefficient
    /// that is not finite, weight lists that do not alternate) or that the
    /// order conditions cannot judge.
    #[error("invalid table: {0}")]
    InvalidTable(String),

    /// No scheme with this id in the catalogue.
    #[error("unknown scheme '{id}'; valid schemes: {valid}")]
    UnknownScheme {
        /// The id asked for.
        id: String,
        /// Every valid id, comma separated.
        valid: String,
    },

    /// No scene with this id.
    #[error("unknown scene '{id}'; valid scenes: {valid}")]
    UnknownScene {
        /// The id asked for.
        id: String,
        /// Every valid id, comma separated.
        valid: String,
    },

    /// A ladder that cannot measure an order (too few rungs, rungs that round
    /// to the same step count, a ratio that does not refine).
    #[error("invalid ladder: {0}")]
    InvalidLadder(String),

    /// A request whose cost is out of proportion; refused before any work.
    #[error(
        "refusing a run of {} steps ({} s at the estimated speed); the limit is {limit} steps: ask for less work (a larger step, fewer steps, rungs, periods or repeats)",
        count(*steps),
        about(*seconds)
    )]
    TooExpensive {
        /// Steps the request would take in total: the true count, which may
        /// be beyond any integer type (a run of 1e12 periods at 100 steps a
        /// period), infinite when it exceeds the largest double.
        steps: f64,
        /// The most steps a single request may take.
        limit: u64,
        /// Rough wall time the request would need.
        seconds: f64,
    },

    /// The study needs an exact solution the scene does not have.
    #[error("scene '{0}' has no exact solution, which this study needs")]
    NoExactSolution(&'static str),

    /// Reading or writing a file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
}

/// A step count as a figure (`1.59e13`), or, past the largest double, what
/// it exceeds.
/// A rough figure: "about X", or "more than" the largest double.
fn about(x: f64) -> String {
    if x.is_finite() {
        format!("about {}", figure(x))
    } else {
        count(x)
    }
}

fn count(steps: f64) -> String {
    if steps.is_finite() {
        figure(steps)
    } else {
        format!("more than {}", figure(f64::MAX))
    }
}

/// True for plain kebab-case, `[a-z0-9]+(-[a-z0-9]+)*`: lower-case ASCII
/// letters and digits in words joined by single hyphens. Such an id is a
/// file name on every system, never a path.
pub const fn is_kebab_case(id: &str) -> bool {
    let b = id.as_bytes();
    if b.is_empty() || b[0] == b'-' || b[b.len() - 1] == b'-' {
        return false;
    }
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let word = c.is_ascii_lowercase() || c.is_ascii_digit();
        if !(word || (c == b'-' && b[i - 1] != b'-')) {
            return false;
        }
        i += 1;
    }
    true
}

/// `id` if it is plain kebab-case ([`is_kebab_case`]), else
/// [`Error::InvalidId`].
pub fn kebab_id<'a>(what: &'static str, id: &'a str) -> Result<&'a str, Error> {
    if is_kebab_case(id) {
        Ok(id)
    } else {
        Err(Error::InvalidId {
            what,
            id: id.to_string(),
        })
    }
}
