//! # stepladder
//!
//! Tells, in one `cargo test`, whether a time integrator for Newton's
//! equations `q'' = a(q)` is as accurate, as stable and as geometric as it
//! claims, by running it over a ladder of step sizes `h, h/2, h/4, ...` on
//! scenes with exact solutions.
//!
//! One import guards an integrator:
//!
//! ```
//! use stepladder::prelude::*;
//! use stepladder::scheme::{Leapfrog, VELOCITY_VERLET};
//! use stepladder::study::{OrderSpec, global_order};
//!
//! // the global order with its 95% interval, against the claimed 2
//! let record = global_order(&Leapfrog, &KeplerCircular, &OrderSpec::default())?;
//! assert!(record.passed(), "{}", record.reason);
//! let [lo, hi] = record.ci95.unwrap();
//! assert!(lo <= 2.0 && 2.0 <= hi);
//!
//! // or every claim at once, panicking with the deciding figures
//! assert_claims(&VELOCITY_VERLET, &Harmonic::default());
//! # Ok::<(), Error>(())
//! ```
//!
//! - [`scheme`]: the catalogue below, the [`Scheme`](scheme::Scheme) trait
//!   and [`SchemeMeta`](scheme::SchemeMeta) to bring your own, and
//!   [`BlackBox`](scheme::BlackBox) for an integrator from any crate (a step
//!   function on `f64` or `f32` slices, first-order, canonical or on its own
//!   vectors, stateful or implicit);
//! - [`scene`]: the harmonic oscillator, the circular and eccentric Kepler
//!   orbits, the anharmonic well and its separatrix, N-body scenes, each with
//!   its exact or reference solution, and [`Scene`](scene::Scene) and
//!   [`FromPotential`](scene::FromPotential) to bring your own;
//! - [`study`]: one function per question (global order, energy drift,
//!   symplecticity, reversibility, stability, round-off, force evaluations,
//!   the hard cases, adaptive integrators over a tolerance ladder), each
//!   with its spec and its record;
//! - [`conditions`]: the order conditions of a splitting, composition or
//!   Nyström tableau, in double-double arithmetic, checked before any ladder
//!   runs;
//! - [`guard`]: one-line assertions of a scheme's claims for a test, with the
//!   deciding figures in the failure message; [`guard_claims!`] and
//!   [`guard_adaptive!`] write one `#[test]` per claim, with a pinned error;
//! - [`prelude`]: the thirty names a test that guards an integrator needs,
//!   in one `use`.
//!
//! The catalogue (claimed global order; every scheme here is measured
//! against its claim on every scene):
//!
//! | id | order | family |
//! |---|---|---|
//! | `euler` | 1 | explicit Euler |
//! | `euler-cromer` | 1 | splitting (symplectic Euler) |
//! | `stormer-verlet` | 2 | two-step Störmer-Verlet, positions only |
//! | `leapfrog` | 2 | leap-frog, half-step velocities |
//! | `velocity-verlet` | 2 | splitting |
//! | `position-verlet` | 2 | splitting |
//! | `implicit-midpoint` | 2 | implicit Runge-Kutta |
//! | `rk4` | 4 | Runge-Kutta |
//! | `forest-ruth` | 4 | composition of velocity Verlet |
//! | `pefrl` | 4 | splitting |
//! | `yoshida6` | 6 | composition of velocity Verlet |
//! | `kahan-li8` | 8 | composition of velocity Verlet |
//! | `mclachlan-atela4` | 4 | Nyström splitting |
//! | `mclachlan-sb3a4` | 4 | splitting |
//! | `mclachlan-sb3a5` | 4 | splitting |
//! | `blanes-moan-srkn11b` | 6 | Nyström splitting |
//! | `rkn4-nystrom` | 4 | Runge-Kutta-Nyström |
//! | `rkn6-dormand-prince` | 6 | Runge-Kutta-Nyström |
//!
//! Beside it: compensated-summation Verlet forms, Quinlan and Tremaine's
//! eighth-order multistep method, the DPRKN8 and DPRKN12 methods and the
//! adaptive DPRKN6(4), DPRKN8(6) and DPRKN12(10) pairs, the last two also
//! with compensated state updates.
#![warn(missing_docs)]

pub mod error;
pub mod guard;
pub mod prelude;
pub mod scene;
pub mod scheme;
pub mod state;
pub mod study;

/// The nalgebra version stepladder is built on, for writing generic schemes
/// and scenes against the same vector types.
pub use nalgebra;

/// The order conditions of a splitting, composition, Runge-Kutta-Nyström or
/// Runge-Kutta tableau, checked in double-double arithmetic before any
/// ladder runs.
pub use maths::conditions;

// The floors under the studies and the machinery that runs them: public only
// so that `internals`, the one door the lab (corpus, suites, report), the
// tests and the audit use, can name them; not part of the API.
#[doc(hidden)]
pub mod internals;
#[doc(hidden)]
pub mod ladder;
#[doc(hidden)]
pub mod maths;
#[doc(hidden)]
pub mod parallel;
#[doc(hidden)]
pub mod run;
#[doc(hidden)]
pub mod tolerance;
#[doc(hidden)]
pub mod wording;

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
