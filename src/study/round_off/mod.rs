//! Round-off: where the error stops falling, and how it grows over long runs.

pub mod floor;
pub mod longrun;
