//! Studies: each turns runs of one scheme on one scene into a record.

pub mod fit;
pub mod order;
