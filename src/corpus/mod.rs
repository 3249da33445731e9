//! The verdict corpus: integrators and scenes the harness was not built
//! around, correct ones and broken ones, each with the verdict it must get
//! and why. It is the harness's test set, read like a classifier's: correct
//! pairs must pass (no false alarms), broken pairs must fail on the claim
//! they break (no misses).
//!
//! - [`scenes`]: problems without exact solutions (a three-body
//!   choreography in six dimensions, a pendulum near its separatrix, a
//!   regular Hénon-Heiles orbit, a Fermi-Pasta-Ulam-Tsingou chain) and one
//!   with an exact solution the harness has never seen (the Morse
//!   oscillator);
//! - [`correct`]: correct schemes outside the catalogue (odd orders, order
//!   five, implicit, symmetric but not symplectic, symplectic but not
//!   symmetric);
//! - [`broken`]: plausible bugs (rounded or perturbed weights, stale
//!   forces, unsynchronised output, typos in Runge-Kutta stages, wrong
//!   claims of symmetry or symplecticity).

pub mod broken;
pub mod correct;
pub mod scenes;

use crate::case::{Bound, Case};
use crate::scene::Scene;
use crate::scheme::Scheme;
use serde::Serialize;

/// What one claim of a corpus entry must be judged.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Expect {
    /// The claim must be confirmed.
    Pass,
    /// The claim must be refuted.
    Fail,
    /// The data cannot decide, and the record must say so.
    Inconclusive,
    /// Not judged: the entry is about another claim.
    Any,
}

/// The verdict each of the four claims must get.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Expected {
    /// The global order.
    pub order: Expect,
    /// Energy behaviour over a long run.
    pub energy: Expect,
    /// Symplecticity of the one-step map.
    pub symplectic: Expect,
    /// Time symmetry (return after stepping back).
    pub reversible: Expect,
}

impl Expected {
    /// Every claim confirmed: what a correct scheme must get.
    pub const PASS: Expected = Expected {
        order: Expect::Pass,
        energy: Expect::Pass,
        symplectic: Expect::Pass,
        reversible: Expect::Pass,
    };
    /// Nothing judged; start from here and set the claims an entry is about.
    pub const ANY: Expected = Expected {
        order: Expect::Any,
        energy: Expect::Any,
        symplectic: Expect::Any,
        reversible: Expect::Any,
    };
    /// The same with the order's verdict set.
    pub const fn order(self, e: Expect) -> Self {
        Self { order: e, ..self }
    }
    /// The same with the energy verdict set.
    pub const fn energy(self, e: Expect) -> Self {
        Self { energy: e, ..self }
    }
    /// The same with the symplecticity verdict set.
    pub const fn symplectic(self, e: Expect) -> Self {
        Self {
            symplectic: e,
            ..self
        }
    }
    /// The same with the time-symmetry verdict set.
    pub const fn reversible(self, e: Expect) -> Self {
        Self {
            reversible: e,
            ..self
        }
    }
}

/// Is the scheme, on this scene, what it claims?
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Truth {
    /// Every claim holds.
    Correct,
    /// At least one claim is false.
    Broken,
}

/// One `(scheme, scene)` pair with the verdicts it must get.
pub struct Entry {
    /// Correct or broken.
    pub truth: Truth,
    /// The verdict each claim must get.
    pub expected: Expected,
    /// Why, from theory.
    pub why: &'static str,
    /// The scheme bound to the scene.
    pub case: Box<dyn Case>,
}

impl Entry {
    /// A correct pair: every claim must pass.
    pub fn correct<M, S, const D: usize>(scheme: &'static M, scene: S, why: &'static str) -> Self
    where
        M: Scheme + Sync + 'static,
        S: Scene<D> + Send + Sync + 'static,
    {
        Self::new(Truth::Correct, Expected::PASS, scheme, scene, why)
    }

    /// A broken pair with the verdicts it must get (at least one `Fail`).
    pub fn broken<M, S, const D: usize>(
        scheme: &'static M,
        scene: S,
        expected: Expected,
        why: &'static str,
    ) -> Self
    where
        M: Scheme + Sync + 'static,
        S: Scene<D> + Send + Sync + 'static,
    {
        Self::new(Truth::Broken, expected, scheme, scene, why)
    }

    /// Any pair.
    pub fn new<M, S, const D: usize>(
        truth: Truth,
        expected: Expected,
        scheme: &'static M,
        scene: S,
        why: &'static str,
    ) -> Self
    where
        M: Scheme + Sync + 'static,
        S: Scene<D> + Send + Sync + 'static,
    {
        Self {
            truth,
            expected,
            why,
            case: Box::new(Bound::<M, S, D> { scheme, scene }),
        }
    }
}
