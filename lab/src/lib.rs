//! # stepladder-lab
//!
//! What stepladder runs on itself: the test [`corpus`] (correct and broken
//! schemes and scenes, and a held-out batch written apart from the
//! harness), the [`suite`]s over the whole catalogue, the [`peer`]
//! comparison with `ode_solvers` and `numeris`, [`report`] (REPORT.md and its
//! figures) and the `stepladder` command ([`cli`]). None of it is published: a crate that
//! guards its integrator depends on `stepladder` alone.

pub mod case;
pub mod cli;
pub mod corpus;
pub mod fingerprint;
pub mod peer;
pub mod report;
pub mod sensitivity;
pub mod suite;
