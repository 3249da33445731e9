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
pub mod held_out;
mod pairs;
pub mod scenes;

pub use pairs::{broken as broken_pairs, correct as correct_pairs, entries};

use crate::case::{Bound, Case};
use serde::Serialize;
use stepladder::scene::Scene;
use stepladder::scheme::Scheme;
use stepladder::study::Verdict;

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

/// The verdict each of the five claims must get.
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
    /// Force evaluations per step, counted.
    pub evaluations: Expect,
}

impl Expected {
    /// Every claim confirmed: what a correct scheme must get.
    pub const PASS: Expected = Expected {
        order: Expect::Pass,
        energy: Expect::Pass,
        symplectic: Expect::Pass,
        reversible: Expect::Pass,
        evaluations: Expect::Pass,
    };
    /// Nothing judged; start from here and set the claims an entry is about.
    pub const ANY: Expected = Expected {
        order: Expect::Any,
        energy: Expect::Any,
        symplectic: Expect::Any,
        reversible: Expect::Any,
        evaluations: Expect::Any,
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
    /// The same with the evaluation count's verdict set.
    pub const fn evaluations(self, e: Expect) -> Self {
        Self {
            evaluations: e,
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

/// The five claims a corpus entry is judged on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Claim {
    /// The global order.
    Order,
    /// No secular energy drift (symplectic or symmetric), or none promised.
    Energy,
    /// Symplecticity of the one-step map.
    Symplectic,
    /// Time symmetry.
    Reversible,
    /// Force evaluations per step.
    Evaluations,
}

impl Claim {
    /// Every claim, in the order of [`Expected`]'s fields.
    pub const ALL: [Claim; 5] = [
        Claim::Order,
        Claim::Energy,
        Claim::Symplectic,
        Claim::Reversible,
        Claim::Evaluations,
    ];

    /// The kebab-case name.
    pub fn name(self) -> &'static str {
        match self {
            Claim::Order => "order",
            Claim::Energy => "energy",
            Claim::Symplectic => "symplectic",
            Claim::Reversible => "reversible",
            Claim::Evaluations => "evaluations",
        }
    }
}

impl Expected {
    /// What `claim` must get.
    pub fn of(&self, claim: Claim) -> Expect {
        match claim {
            Claim::Order => self.order,
            Claim::Energy => self.energy,
            Claim::Symplectic => self.symplectic,
            Claim::Reversible => self.reversible,
            Claim::Evaluations => self.evaluations,
        }
    }
}

/// One claim of one entry, as judged.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Judged {
    /// The claim.
    pub claim: Claim,
    /// What it must get.
    pub expected: Expect,
    /// What it got.
    pub verdict: Verdict,
    /// The study's reason.
    pub reason: String,
    /// What the guard for this claim prints when the verdict is not a pass
    /// ([`stepladder::guard`]'s `*_failure`): the reason with the figures around it.
    pub message: Option<String>,
}

impl Judged {
    /// The verdict is the one expected (`Any` accepts every verdict).
    pub fn right(&self) -> bool {
        match self.expected {
            Expect::Any => true,
            Expect::Pass => self.verdict == Verdict::Pass,
            Expect::Fail => self.verdict == Verdict::Fail,
            Expect::Inconclusive => self.verdict == Verdict::Inconclusive,
        }
    }
}

/// An entry's outcome.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Outcome {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id and parameters.
    pub scene: String,
    /// Correct or broken.
    pub truth: Truth,
    /// Why the expectations are what they are.
    pub why: &'static str,
    /// Every judged claim (those expected `Any` are run too, and shown).
    pub claims: Vec<Judged>,
}

impl Outcome {
    /// Every claim got its expected verdict.
    pub fn right(&self) -> bool {
        self.claims.iter().all(Judged::right)
    }
}

/// Runs every study of `entry` and judges its claims.
pub fn judge(entry: &Entry) -> Result<Outcome, stepladder::error::Error> {
    use stepladder::internals::accuracy::order::OrderSpec;
    use stepladder::internals::geometry::energy::EnergySpec;
    use stepladder::internals::geometry::reverse::ReverseSpec;
    use stepladder::internals::geometry::symplectic::SymplecticSpec;
    let c = &entry.case;
    let order = c.order(&OrderSpec::default())?;
    let energy = c.energy(&EnergySpec::default())?;
    let symplectic = c.symplectic(&SymplecticSpec::default())?;
    let reverse = c.reverse(&ReverseSpec::default())?;
    let evaluations = c.evaluations();
    use stepladder::study::ClaimVerdict;
    let judged = |v: ClaimVerdict, reason: String| {
        let message = v.failure().map(str::to_string);
        (v.verdict, message, reason)
    };
    let verdicts = [
        judged((&order).into(), order.reason.clone()),
        judged((&energy).into(), energy.reason.clone()),
        judged((&symplectic).into(), symplectic.reason.clone()),
        judged((&reverse).into(), reverse.reason.clone()),
        judged((&evaluations).into(), evaluations.reason.clone()),
    ];
    let scene = c.scene();
    Ok(Outcome {
        scheme: c.scheme().id,
        scene: format!("{} ({})", scene.id, scene.parameters),
        truth: entry.truth,
        why: entry.why,
        claims: Claim::ALL
            .iter()
            .zip(verdicts)
            .map(|(&claim, (verdict, message, reason))| Judged {
                claim,
                expected: entry.expected.of(claim),
                verdict,
                reason,
                message,
            })
            .collect(),
    })
}

/// Judges every entry on `threads` threads, outcomes in entry order.
pub fn judge_all(
    entries: &[Entry],
    threads: usize,
    finished: &(dyn Fn(usize, &Entry) + Sync),
) -> Result<Vec<Outcome>, stepladder::error::Error> {
    stepladder::internals::parallel::parallel_map(entries, threads, judge, finished)
        .into_iter()
        .collect()
}

/// The corpus read as a classifier's test set: a correct pair is a *correct
/// pass* when every claim gets its expected verdict and a *false alarm*
/// otherwise; a broken pair is *caught* when every claim gets its expected
/// verdict (the broken claim refuted, the others as expected) and *missed*
/// otherwise.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Confusion {
    /// Correct pairs judged as expected.
    pub correct_pass: usize,
    /// Correct pairs with a wrong verdict.
    pub false_alarm: usize,
    /// Broken pairs judged as expected.
    pub broken_caught: usize,
    /// Broken pairs with a wrong verdict.
    pub missed: usize,
}

impl Confusion {
    /// The matrix of these outcomes.
    pub fn of(outcomes: &[Outcome]) -> Self {
        let mut c = Confusion::default();
        for o in outcomes {
            match (o.truth, o.right()) {
                (Truth::Correct, true) => c.correct_pass += 1,
                (Truth::Correct, false) => c.false_alarm += 1,
                (Truth::Broken, true) => c.broken_caught += 1,
                (Truth::Broken, false) => c.missed += 1,
            }
        }
        c
    }

    /// Wrong verdicts.
    pub fn wrong(&self) -> usize {
        self.false_alarm + self.missed
    }
}
