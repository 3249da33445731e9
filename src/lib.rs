//! # stepladder
//!
//! Tells, in one `cargo test`, whether a time integrator for Newton's
//! equations `q'' = a(q)` is as accurate as it claims, by running it over a
//! ladder of step sizes against scenes with exact solutions.
//!
//! - [`scheme`]: the catalogue (explicit Euler, Euler-Cromer, Störmer-Verlet,
//!   leap-frog, velocity and position Verlet, the implicit midpoint rule,
//!   RK4, PEFRL and the Forest-Ruth, Yoshida and Kahan-Li compositions),
//!   compensated-summation variants of the Verlet forms
//!   ([`scheme::compensated`]), and the [`scheme::Scheme`] trait to bring
//!   your own.
//! - [`scene`]: the harmonic oscillator, the circular Earth-Sun orbit, an
//!   eccentric Kepler orbit and the anharmonic well (trapped orbits in Jacobi
//!   elliptic functions, and its separatrix), with exact solutions; the
//!   [`scene::Scene`] trait to bring your own.
//! - [`measure`]: the studies; [`measure::accuracy::order::global_order`] measures the
//!   global order with a 95% interval over an automatically chosen window;
//!   [`measure::roundoff::floor`] and [`measure::roundoff::longrun`] the round-off floors and
//!   the growth of round-off over long runs;
//!   [`measure::hard`] the hard cases: orders and energy on eccentric Kepler
//!   orbits, how long a scheme follows the anharmonic well's separatrix, and
//!   whether it tells an orbit just below the barrier from one just above;
//!   [`measure::cost`] speed against error, the force evaluations and the time
//!   each scheme needs to reach target errors, and the time of a step against
//!   a hand-written floor.
//! - [`guard`]: one-line assertions of a scheme's claims for a downstream
//!   crate's tests, with the deciding figures in the failure message, and
//!   [`guard_claims!`], one `#[test]` per claim; [`measure::accuracy::pin`] pins the error
//!   at a coarse step, to its round-off, in the crate's own snapshot folder.
//! - [`scheme::BlackBox`] guards an integrator that only runs on `f64` or
//!   `f32` (a step function on slices, from any crate);
//!   [`scene::FromPotential`] makes a scene from a potential alone.
//! - `report`, `suite` and `cli` (features `report` and `cli`, on by
//!   default): the whole catalogue's studies, REPORT.md and its figures, and
//!   the `stepladder` command. With `default-features = false` the crate is
//!   the measurement core alone, on nalgebra, num-dual, statrs, serde and
//!   thiserror.
//!
//! ```
//! use stepladder::measure::accuracy::order::{global_order, OrderSpec};
//! use stepladder::scene::KeplerCircular;
//! use stepladder::scheme::Leapfrog;
//!
//! let record = global_order(&Leapfrog, &KeplerCircular, &OrderSpec::default())?;
//! assert!(record.passed(), "{}", record.reason);
//! let [lo, hi] = record.ci95.unwrap();
//! assert!(lo <= 2.0 && 2.0 <= hi);
//! # Ok::<(), stepladder::error::Error>(())
//! ```
#![warn(missing_docs)]

/// The nalgebra version stepladder is built on, for writing generic schemes
/// and scenes against the same vector types.
pub use nalgebra;
pub mod error;
pub mod guard;
pub mod ladder;
pub mod measure;
pub mod parallel;
pub mod run;
pub mod scene;
pub mod scheme;
pub mod state;
pub mod tolerance;

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
