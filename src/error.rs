//! The library's typed errors: every way a request can be refused.
//!
//! A scheme that blows up or a fit that finds no asymptotic window is not an
//! error: it is a measured outcome and lives in the study's record.

use std::path::PathBuf;

/// Why a request could not be carried out.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A numeric parameter outside its domain.
    #[error("{name} = {value} is invalid: expected {expected}")]
    InvalidParameter {
        /// The parameter's name as the user wrote it.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What would have been accepted.
        expected: &'static str,
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
        "refusing a run of {steps} steps (about {seconds:.0} s at the estimated speed); the limit is {limit} steps: use a larger step or a shorter end time"
    )]
    TooExpensive {
        /// Steps the request would take in total.
        steps: u64,
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
