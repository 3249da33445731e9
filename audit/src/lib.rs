//! An audit of integrators published by other crates: each method's claims,
//! quoted from its crate with file and line or marked not claimed, against
//! stepladder's studies, run through the public black-box adapters on
//! autonomous scenes q'' = a(q).
//!
//! Every method carries the verdicts expected of it, each with the reason
//! that does not come from this harness: a coefficient check of the
//! published tableau, a source line, or a standalone probe of the crate.
//! [`disagreements`] lists every measured verdict that differs from its
//! expectation; the tests require it empty.

pub mod glue;
pub mod methods;
pub mod race;
pub mod report;
pub mod target_cost;

use stepladder::internals::accuracy::order::{OrderSpec, global_order};
use stepladder::internals::adaptive::{ToleranceLadderSpec, tolerance_ladder};
use stepladder::internals::cost::evaluations::{counting_step, evaluations};
use stepladder::internals::geometry::energy::{EnergySpec, energy_drift};
use stepladder::internals::geometry::reverse::{ReverseSpec, reversibility};
use stepladder::internals::geometry::symplectic::{SymplecticSpec, symplecticity};
use stepladder::scene::{Harmonic, KeplerEccentric, Scene};
use stepladder::scheme::Scheme;
use stepladder::scheme::{AdaptiveClaims, AdaptiveIntegrator};
use stepladder::study::{Verdict, recover_quadrature};

/// The words in which a crate states a property of a method, quoted, and
/// where they stand in its published source (`crate-version/path:line`, or
/// `:first-last` when the sentence runs over several lines).
#[derive(Clone, Copy, Debug)]
pub struct Cited {
    pub quote: &'static str,
    pub at: &'static str,
}

/// The properties the audit looks at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Prop {
    /// Order of the solution advanced.
    Order,
    Symplectic,
    /// Symmetric (time-reversible) as a map.
    Symmetric,
    /// Long-term energy behaviour.
    Energy,
    /// Force (right-hand side) evaluations per step.
    Evaluations,
    /// Order of an adaptive pair's error estimate.
    Estimate,
}

impl Prop {
    pub fn name(self) -> &'static str {
        match self {
            Prop::Order => "order",
            Prop::Symplectic => "symplectic",
            Prop::Symmetric => "symmetric",
            Prop::Energy => "energy",
            Prop::Evaluations => "evaluations",
            Prop::Estimate => "estimate order",
        }
    }
}

/// One property of a method: the crate's statement of it, if it makes
/// one, and what the value the studies test rests on when it does not.
#[derive(Clone, Copy, Debug)]
pub struct Property {
    pub prop: Prop,
    /// `None`: the crate does not claim it.
    pub claim: Option<Cited>,
    /// The source of the tested value when nothing is claimed (theory of
    /// the method the crate names, or its published source), or a remark on
    /// the claim.
    pub basis: &'static str,
}

/// A property the crate states, in its own words.
pub const fn said(prop: Prop, quote: &'static str, at: &'static str) -> Property {
    Property {
        prop,
        claim: Some(Cited { quote, at }),
        basis: "",
    }
}

/// A property the crate states, with a remark on what the audit tests.
pub const fn said_and(
    prop: Prop,
    quote: &'static str,
    at: &'static str,
    basis: &'static str,
) -> Property {
    Property {
        prop,
        claim: Some(Cited { quote, at }),
        basis,
    }
}

/// A property the crate does not claim; `basis` says where the tested
/// value comes from.
pub const fn unsaid(prop: Prop, basis: &'static str) -> Property {
    Property {
        prop,
        claim: None,
        basis,
    }
}

/// A method, where its claims were read, and what is expected of them.
#[derive(Clone, Copy, Debug)]
pub struct Provenance {
    /// The crate and version.
    pub krate: &'static str,
    /// The method's name in the crate.
    pub method: &'static str,
    /// Each property looked at: quoted from the crate, or not claimed.
    pub properties: &'static [Property],
    /// The fewest force evaluations per step the method needs (with a
    /// first-same-as-last force where it can have one), for comparison.
    pub minimum_evaluations: u32,
    /// The reproduction: the audit test that runs this method alone.
    pub test: &'static str,
}

impl Provenance {
    /// The property `prop`, if listed.
    pub fn property(&self, prop: Prop) -> Option<&Property> {
        self.properties.iter().find(|p| p.prop == prop)
    }

    /// Whether the crate claims `prop`.
    pub fn claims(&self, prop: Prop) -> bool {
        self.property(prop).is_some_and(|p| p.claim.is_some())
    }
}

/// One line of independent evidence and the properties it bears on.
pub type Evidence = (&'static [Prop], &'static str);

/// The verdicts expected of a fixed-step method's five claims on one scene,
/// in the order order, symplectic, reversible, energy, evaluations.
pub type ClaimVerdicts = [Verdict; 5];

/// The names of the five claims, in [`ClaimVerdicts`] order.
pub const CLAIMS: [&str; 5] = ["order", "symplectic", "reversible", "energy", "evaluations"];

/// The properties of [`ClaimVerdicts`], in its order.
pub const FIXED_PROPS: [Prop; 5] = [
    Prop::Order,
    Prop::Symplectic,
    Prop::Symmetric,
    Prop::Energy,
    Prop::Evaluations,
];

/// The verdict expected of each claim of a fixed-step method on each scene,
/// and why (independently of this harness).
#[derive(Clone, Copy, Debug)]
pub struct FixedExpectation {
    /// On the harmonic oscillator.
    pub harmonic: ClaimVerdicts,
    /// On the eccentric Kepler orbit.
    pub kepler: ClaimVerdicts,
    /// The independent reason for the expectation.
    pub why: &'static str,
    /// Independent evidence for each verdict that is not a pass.
    pub evidence: &'static [Evidence],
    /// For an order claim expected to fail, the order condition the source
    /// reading found broken: stepladder's probe of the step must name it
    /// first, with the same defect.
    pub named: Option<Named>,
}

/// An order condition broken in a method's published coefficients, and its
/// defect computed from them directly (never through stepladder).
#[derive(Clone, Copy, Debug)]
pub struct Named {
    /// The condition as stepladder's probe words it (`sum b_i c_i^4 = 1/5`).
    pub condition: &'static str,
    /// Its defect, computed from the published coefficients.
    pub defect: f64,
    /// How that defect was computed.
    pub source: &'static str,
}

impl FixedExpectation {
    /// The expectation with the broken condition the source reading names.
    pub fn naming(mut self, condition: &'static str, defect: f64, source: &'static str) -> Self {
        self.named = Some(Named {
            condition,
            defect,
            source,
        });
        self
    }
}

/// What the studies measured of one fixed-step method on one scene.
#[derive(Clone, Debug)]
pub struct FixedRow {
    pub scene: &'static str,
    pub measured_order: Option<f64>,
    pub ci95: Option<[f64; 2]>,
    pub order: Verdict,
    pub symplectic: Verdict,
    pub symplectic_residual: f64,
    /// The maps sampled are symplectic to the allowance.
    pub symplectic_measured: bool,
    pub reversible: Verdict,
    pub return_ulps: Option<f64>,
    /// The round trip returned within its allowance.
    pub reversible_measured: bool,
    pub energy: Verdict,
    pub energy_growth: Option<f64>,
    pub energy_class: Option<stepladder::internals::geometry::energy::EnergyClass>,
    pub evaluations: Verdict,
    pub per_step: f64,
    /// Each study's failure, if any, in [`ClaimVerdicts`] order.
    pub reasons: [Option<String>; 5],
    /// A failed order claim's probe of the step's order conditions.
    pub probe: Option<stepladder::study::ConditionProbe>,
    /// For a failed order claim, the step's weights and nodes recovered
    /// from its moments.
    pub quadrature: Option<stepladder::study::RecoveredQuadrature>,
}

/// A fixed-step method's audit: claims, expectation, rows per scene.
#[derive(Clone, Debug)]
pub struct FixedAudit {
    pub provenance: Provenance,
    pub claims: stepladder::scheme::SchemeMeta,
    pub expected: FixedExpectation,
    pub rows: Vec<FixedRow>,
}

fn study<T>(what: &str, r: Result<T, stepladder::error::Error>) -> T {
    r.unwrap_or_else(|e| panic!("audit: the {what} study could not run: {e}"))
}

/// The message of a verdict other than a pass (a claim not made included:
/// the report shows what was measured for it).
fn failure(v: stepladder::study::ClaimVerdict) -> Option<String> {
    (v.verdict != stepladder::study::Verdict::Pass).then_some(v.message)
}

fn fixed_row<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) -> FixedRow {
    let order = study("order", global_order(scheme, scene, &OrderSpec::default()));
    let symplectic = study(
        "symplectic",
        symplecticity(scheme, scene, &SymplecticSpec::default()),
    );
    let reverse = study(
        "reversibility",
        reversibility(scheme, scene, &ReverseSpec::default()),
    );
    let energy = study(
        "energy",
        energy_drift(scheme, scene, &EnergySpec::default()),
    );
    let counted = evaluations(scheme, scene, counting_step(scene));
    FixedRow {
        scene: scene.meta().id,
        measured_order: order.measured_order,
        ci95: order.fit.as_ref().map(|f| f.ci95),
        order: order.verdict,
        symplectic: symplectic.verdict,
        symplectic_residual: symplectic.symplectic_residual,
        symplectic_measured: symplectic.measured,
        reversible: reverse.verdict,
        return_ulps: reverse.return_ulps,
        reversible_measured: reverse.measured,
        energy: energy.verdict,
        energy_growth: energy.growth_exponent,
        energy_class: energy.class,
        evaluations: counted.verdict,
        per_step: counted.per_step,
        reasons: [
            failure((&order).into()),
            failure((&symplectic).into()),
            failure((&reverse).into()),
            failure((&energy).into()),
            failure((&counted).into()),
        ],
        quadrature: order
            .probe
            .is_some()
            .then(|| recover_quadrature::<M, D>(scheme))
            .flatten(),
        probe: order.probe,
    }
}

/// Runs every study of a fixed-step method on the audit's scenes: the
/// oscillator (linear) and the eccentric Kepler orbit (nonlinear, e = 0.6).
pub fn audit_fixed<M: Scheme>(
    provenance: Provenance,
    scheme: &M,
    expected: FixedExpectation,
) -> FixedAudit {
    FixedAudit {
        provenance,
        claims: *scheme.meta(),
        expected,
        rows: vec![
            fixed_row(scheme, &Harmonic::default()),
            fixed_row(scheme, &KeplerEccentric::default()),
        ],
    }
}

/// The verdict expected of an adaptive integrator's tolerance ladder.
#[derive(Clone, Copy, Debug)]
pub struct AdaptiveExpectation {
    /// The tolerance ladder's verdict.
    pub verdict: Verdict,
    /// Whether the accepted steps grow like an `O(h)` estimate's, i.e.
    /// faster than `TOL^(-1/2)` (see [`FIRST_ORDER_GROWTH`]).
    pub first_order_estimate: bool,
    pub why: &'static str,
    pub evidence: &'static [Evidence],
}

/// The step-growth exponent above which an estimate is at best first order
/// in `h`. A controller keeping an estimate `~ C h^m` at the tolerance takes
/// steps `h ~ TOL^(1/m)`, so `N ~ TOL^(-1/m)`: `s = 1/5` for the 5(4) pairs'
/// claimed estimates, `1/8` for DOP853's, `1` for an estimate `~ h`. The
/// threshold 1/2 (`m = 2`) separates them with room on both sides; at the
/// loosest tolerances (1e-3, 1e-4) the runs are far from round-off.
pub const FIRST_ORDER_GROWTH: f64 = 0.5;

/// What the tolerance ladder measured on one scene.
#[derive(Clone, Debug)]
pub struct AdaptiveRow {
    pub scene: &'static str,
    pub exponent: Option<f64>,
    pub ci95: Option<[f64; 2]>,
    pub theory: Option<f64>,
    pub evaluations_per_accepted: Option<f64>,
    /// `s` in accepted steps ~ `TOL^(-s)` between the two loosest
    /// tolerances the runs reached.
    pub step_exponent: Option<f64>,
    /// The tighter of the two runs stopped at its step limit: the exponent
    /// is a lower bound.
    pub step_exponent_is_bound: bool,
    pub unfinished: usize,
    pub verdict: Verdict,
    pub reason: String,
}

/// An adaptive integrator's audit.
#[derive(Clone, Debug)]
pub struct AdaptiveAudit {
    pub provenance: Provenance,
    pub claims: AdaptiveClaims,
    pub expected: AdaptiveExpectation,
    pub rows: Vec<AdaptiveRow>,
}

fn adaptive_row<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    integrator: &I,
    scene: &S,
) -> AdaptiveRow {
    let r = study(
        "tolerance ladder",
        tolerance_ladder(integrator, scene, &ToleranceLadderSpec::default()),
    );
    let (evals, accepted) = r
        .points
        .iter()
        .filter(|p| p.end == stepladder::scheme::RunEnd::Reached)
        .fold((0u64, 0u64), |(e, a), p| {
            (e + p.evaluations, a + p.accepted)
        });
    // the loosest run that reached t_end, and the next tighter one: if that
    // one stopped at its step limit, the steps it had accepted are a lower
    // bound on what the whole run needs, and the exponent a lower bound too
    let loosest = r
        .points
        .iter()
        .position(|p| p.end == stepladder::scheme::RunEnd::Reached && p.accepted > 0);
    let (step_exponent, step_exponent_is_bound) = match loosest {
        Some(i) if i + 1 < r.points.len() && r.points[i + 1].accepted > 0 => {
            let (a, b) = (&r.points[i], &r.points[i + 1]);
            let s = (b.accepted as f64 / a.accepted as f64).ln() / (a.tolerance / b.tolerance).ln();
            let bound = b.end != stepladder::scheme::RunEnd::Reached;
            // a bound is only evidence of growth, never of its absence
            (Some(s), bound)
        }
        _ => (None, false),
    };
    AdaptiveRow {
        scene: scene.meta().id,
        step_exponent,
        step_exponent_is_bound,
        exponent: r.proportionality.as_ref().map(|p| p.exponent),
        ci95: r.proportionality.as_ref().map(|p| p.ci95),
        theory: r.proportionality.as_ref().and_then(|p| p.theory),
        evaluations_per_accepted: (accepted > 0).then(|| evals as f64 / accepted as f64),
        unfinished: r
            .points
            .iter()
            .filter(|p| p.end != stepladder::scheme::RunEnd::Reached)
            .count(),
        verdict: r.verdict,
        reason: r.reason,
    }
}

/// Runs the tolerance ladder of an adaptive integrator on the audit's scenes.
pub fn audit_adaptive<I: AdaptiveIntegrator>(
    provenance: Provenance,
    integrator: &I,
    expected: AdaptiveExpectation,
) -> AdaptiveAudit {
    AdaptiveAudit {
        provenance,
        claims: integrator.claims(),
        expected,
        rows: vec![
            adaptive_row(integrator, &Harmonic::default()),
            adaptive_row(integrator, &KeplerEccentric::default()),
        ],
    }
}

/// One audited method, fixed-step or adaptive.
#[derive(Clone, Debug)]
pub enum Audit {
    Fixed(FixedAudit),
    Adaptive(AdaptiveAudit),
}

impl FixedRow {
    /// The measured verdicts in [`ClaimVerdicts`] order.
    pub fn verdicts(&self) -> ClaimVerdicts {
        [
            self.order,
            self.symplectic,
            self.reversible,
            self.energy,
            self.evaluations,
        ]
    }
}

impl FixedExpectation {
    /// The expectation on the scene with id `scene`.
    pub fn on(&self, scene: &str) -> ClaimVerdicts {
        if scene == "harmonic" {
            self.harmonic
        } else {
            self.kepler
        }
    }
}

impl Audit {
    pub fn provenance(&self) -> &Provenance {
        match self {
            Audit::Fixed(a) => &a.provenance,
            Audit::Adaptive(a) => &a.provenance,
        }
    }
}

/// How the probe of a row's step departs from the condition the source
/// reading names: another condition first, none, or another defect (by
/// more than the probe's allowance).
fn probe_disagrees(named: &Named, row: &FixedRow) -> Option<String> {
    let Some(probe) = &row.probe else {
        return Some(format!(
            "no probe of the step, expected {} to fail by {:.2e}",
            named.condition, named.defect
        ));
    };
    match probe.first_violated() {
        Some(first)
            if first.condition == named.condition
                && (first.defect - named.defect).abs() <= first.allowance =>
        {
            None
        }
        _ => Some(format!(
            "the probe found \"{}\", the source reading {} failing by {:.2e} ({})",
            probe.describe(),
            named.condition,
            named.defect,
            named.source
        )),
    }
}

/// Every measured verdict that differs from its expectation, one line each
/// with the study's own reason.
pub fn disagreements(audit: &Audit) -> Vec<String> {
    let p = audit.provenance();
    let mut out = Vec::new();
    match audit {
        Audit::Fixed(a) => {
            for row in &a.rows {
                // only a failed order claim is probed
                let named = a
                    .expected
                    .named
                    .as_ref()
                    .filter(|_| row.order == Verdict::Fail);
                if let Some(miss) = named.and_then(|n| probe_disagrees(n, row)) {
                    out.push(format!("{} {} on {}: {miss}", p.krate, p.method, row.scene));
                }
                let want = a.expected.on(row.scene);
                for ((claim, got), want) in CLAIMS.iter().zip(row.verdicts()).zip(want) {
                    if got != want {
                        out.push(format!(
                            "{} {} on {}: {claim} measured {}, expected {} ({}); studies: {}",
                            p.krate,
                            p.method,
                            row.scene,
                            got.name(),
                            want.name(),
                            a.expected.why,
                            row.reasons
                                .iter()
                                .flatten()
                                .cloned()
                                .collect::<Vec<_>>()
                                .join(" | ")
                        ));
                    }
                }
            }
        }
        Audit::Adaptive(a) => {
            for row in &a.rows {
                let first_order = row.step_exponent.and_then(|s| {
                    if s > FIRST_ORDER_GROWTH {
                        Some(true)
                    } else if row.step_exponent_is_bound {
                        None // a lower bound below the threshold decides nothing
                    } else {
                        Some(false)
                    }
                });
                if first_order != Some(a.expected.first_order_estimate) {
                    out.push(format!(
                        "{} {} on {}: accepted steps ~ TOL^-{} between the two loosest tolerances reached, expected {} {FIRST_ORDER_GROWTH} ({})",
                        p.krate,
                        p.method,
                        row.scene,
                        row.step_exponent.map_or("? (fewer than two runs reached t_end)".into(), |s| format!("{s:.3}")),
                        if a.expected.first_order_estimate { "above" } else { "at most" },
                        a.expected.why,
                    ));
                }
                if row.verdict != a.expected.verdict {
                    out.push(format!(
                        "{} {} on {}: tolerance ladder measured {}, expected {} ({}); study: {}",
                        p.krate,
                        p.method,
                        row.scene,
                        row.verdict.name(),
                        a.expected.verdict.name(),
                        a.expected.why,
                        row.reason
                    ));
                }
            }
        }
    }
    out
}

/// Panics with every disagreement of `audit`, if any.
pub fn assert_as_expected(audit: &Audit) {
    let d = disagreements(audit);
    assert!(d.is_empty(), "{}", d.join("\n"));
}
