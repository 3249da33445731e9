//! Round-off: where the error stops falling, how it grows over long runs, and
//! whether an integrator loses no more to it than it must (Brouwer's law).

pub mod brouwer;
pub mod floor;
pub mod longrun;
