//! AUDIT.md: a table per crate, the refuted claims with their independent
//! evidence, the findings on properties the crates do not claim, the
//! defects autonomous scenes cannot show, and where each claim was read.

use crate::race::{Contender, ESTIMATE_TOLERANCE, STARTS_PER_STEP, SceneRace, TARGETS};
use crate::target_cost::{self, Reach};
use crate::{Audit, FIXED_PROPS, Prop, Provenance, disagreements};
use std::fmt::Write;
use stepladder::scene::{OuterSolarSystem, Scene};
use stepladder::study::Verdict;

/// Defects the audit's autonomous scenes cannot see, with the independent
/// confirmation that found them.
pub const NOT_VISIBLE: &[&str] = &[
    "ode_solvers 0.6.2 Dop853: stage 12 is evaluated at t instead of t + h: its c12 is 0.0 (butcher_tableau.rs:278, in the C table at l.266-283) where Hairer's DOP853 has c12 = 1. Not visible on autonomous scenes, whose forces ignore t; read from the published source.",
    "differential-equations 0.7.0 velocity_verlet and ruth_forest: every force is evaluated at the step's start time `self.t` (velocity_verlet.rs:110, 124, 135; ruth_forest.rs:110, 120), so a time-dependent force is frozen over each step. Not visible on autonomous scenes; read from the published source.",
    "russell_ode 5.0.0 equal steps: `solve` with `h_equal` rounds the step count up, n = ceil(span / h_equal), h = span / n (ode_solver.rs:203-204), then takes ceil(span / h) steps with no clamp at x1 (ode_solver.rs:240), so a run can take one step too many and end past x1. Not visible through a per-step adapter (each call is one step over [0, h]). Replaying that arithmetic in doubles over spans 1, 2, ..., 28 and N = 1 ... 1000 with h_equal = span / N, 1255 of the 28000 pairs take a number of steps other than N and 149 end a whole step past x1, the first with span 1 at N = 196; the crate itself, on y' = 1 over [0, 1] with h_equal = 1/196 and `Method::Rk4`, takes 198 steps of 1/197 (792 right-hand-side calls, 4 a step) and integrates time 1.005076 (reproduce: `cargo test --release --test independent russell_equal_steps -- --nocapture`).",
    "peroxide 0.43.1 BasicODESolver advances its clock by the requested dt, not by the step the integrator took after internal rejections (`t += dt` after `let dt_step = self.integrator.step(...)`, ode.rs:241-242): the audit drives `ODEIntegrator::step` itself instead. Read from the published source.",
];

/// Where a check that calls the crate directly and the harness's studies
/// say different things of the same method.
pub const HARNESS_VS_INDEPENDENT: &[&str] = &[
    "peroxide 0.43.1 GL4 (ImplicitSolver::Broyden) on the oscillator: the harness fits a single order with a narrow interval over its own ladder (its row above; the rungs and steps are in its reason, to t_end = 17.8); called directly on q'' = -q from (1, 0) to T = 1, the error follows no single power of h: its ratio per halving of h from 1/16 to 1/1024 is 16.0, 2.5, 16.0, 16.0, 16.2, then 0.0034, as the Broyden solve stops after fewer iterations (`cargo test --release --test independent peroxide_gl4_broyden -- --nocapture`). Both say the step is not Gauss-Legendre's to the tolerance asked; the fitted order describes the harness's ladder, not a property of the crate's step.",
    "Elsewhere the direct checks agree with the harness: RALS4 and GL4 with the fixed-point solve halve their error with h (the harness: order 1 in their rows), RK5 fails only its fifth-order condition (the harness: order 4 on the oscillator), russell_ode's Rk4 spends 4 calls a step (the harness's count in its rows), TSIT45's error weights sum to 0.97, not 0 (the harness: steps growing like 1/TOL, s in its rows), and for each of the four refuted order claims stepladder's probe of the step names first the condition the source reading or a direct call found broken, with the same defect (each method's audit test checks it).",
];

fn verdict(v: Verdict) -> &'static str {
    match v {
        Verdict::Pass => "holds",
        Verdict::Fail => "**refuted**",
        Verdict::Inconclusive => "inconclusive",
        Verdict::NotClaimed => "not claimed",
    }
}

/// What stepladder's probe of the step names for a refuted order claim (the
/// failure message's last clause, which the 300 characters above cut), on
/// each scene, with the source reading's figure where there is one; the
/// audit's tests check that the two agree.
fn probe_line(f: &crate::FixedAudit) -> Option<String> {
    let named: Vec<String> = f
        .rows
        .iter()
        .filter_map(|row| {
            let probe = row.probe.as_ref()?;
            let what = match probe.first_violated() {
                Some(first) => format!(
                    "order {} condition {} fails by {:.2e} (allowance {:.1e})",
                    first.order, first.condition, first.defect, first.allowance
                ),
                None => format!(
                    "no condition it separates fails through order {}",
                    probe.holds_through()
                ),
            };
            Some(format!("on {}, {what}", row.scene))
        })
        .collect();
    if named.is_empty() {
        return None;
    }
    let source = f.expected.named.map_or(String::new(), |n| {
        format!(
            "; from the published coefficients, {} fails by {:.2e} ({})",
            n.condition, n.defect, n.source
        )
    });
    let rule = f
        .rows
        .iter()
        .find_map(|row| row.quadrature.as_ref().map(|q| (row.scene, q)))
        .map_or(String::new(), |(scene, q)| {
            format!(
                "; its weights and nodes, recovered from its moments \
                 (`stepladder::study::recover_quadrature`, on {scene}'s dimension): {}",
                q.describe()
            )
        });
    Some(format!(
        "named by stepladder's probe of the first step (`stepladder::study::probe_conditions`, \
         the failure message's last clause): {}{source}{rule}",
        named.join("; ")
    ))
}

/// A study's reason cut to its first 300 characters, for one line.
fn first_sentence(reason: &str) -> String {
    let flat = reason.replace('\n', " ");
    if flat.chars().count() > 300 {
        format!("{}...", flat.chars().take(300).collect::<String>())
    } else {
        flat
    }
}

/// A study's reason about a property the crate does not claim: stepladder
/// words the value it tests as "claimed", here it is the value tested.
fn tested_wording(reason: &str) -> String {
    reason
        .replace(
            "cost figures from the claim",
            "cost figures from the tested count",
        )
        .replace("though claimed", "though tested")
        .replace(" claimed", " tested")
}

/// `s` of steps ~ TOL^-s, marked when it is a lower bound.
fn step_exponent(row: &crate::AdaptiveRow) -> String {
    let bound = if row.step_exponent_is_bound {
        ">= "
    } else {
        ""
    };
    format!("{bound}{}", opt(row.step_exponent, 3))
}

fn yes(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

fn opt(x: Option<f64>, digits: usize) -> String {
    x.map_or("-".into(), |x| format!("{x:.digits$}"))
}

/// A tested value, starred when the crate does not claim it.
fn starred(p: &Provenance, prop: Prop, value: String) -> String {
    if p.claims(prop) {
        value
    } else {
        format!("{value}*")
    }
}

/// The cell of one property on one scene: the verdict on a claim, or, for
/// a property not claimed, what was measured, a miss of the tested value
/// marked as a finding.
fn cell(p: &Provenance, prop: Prop, v: Verdict, measured: &str) -> String {
    if p.claims(prop) {
        return verdict(v).to_string();
    }
    match v {
        Verdict::Pass => format!("not claimed: {measured}"),
        Verdict::Fail => format!("not claimed: **{measured}** (finding)"),
        Verdict::Inconclusive | Verdict::NotClaimed => "not claimed: not judged".to_string(),
    }
}

fn is_are(b: bool, word: &str) -> String {
    if b {
        word.to_string()
    } else {
        format!("not {word}")
    }
}

/// The properties of a fixed-step method that failed their test, split
/// into claims refuted and findings on properties not claimed.
fn fixed_failures(f: &crate::FixedAudit) -> (Vec<usize>, Vec<usize>) {
    let (mut refuted, mut findings) = (Vec::new(), Vec::new());
    for (i, prop) in FIXED_PROPS.iter().enumerate() {
        if f.rows.iter().any(|r| r.verdicts()[i] == Verdict::Fail) {
            if f.provenance.claims(*prop) {
                refuted.push(i);
            } else {
                findings.push(i);
            }
        }
    }
    (refuted, findings)
}

fn evidence_on(evidence: &[crate::Evidence], props: &[Prop]) -> Vec<&'static str> {
    evidence
        .iter()
        .filter(|(about, _)| about.iter().any(|a| props.contains(a)))
        .map(|(_, text)| *text)
        .collect()
}

/// The whole AUDIT.md, for `audits` in the order of [`crate::methods::ALL`],
/// with the wall time the run took.
pub fn audit_md(audits: &[Audit], races: &[SceneRace], seconds: f64, fingerprint: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Audit of published Rust integrators\n\n\
         Generated by `cargo run --release` in `audit/` ({seconds:.0} s of studies). For each method the audit\n\
         tests its order, symplecticity, time symmetry, long-term energy and force evaluations per step (for\n\
         adaptive pairs: the order advanced, the order of the error estimate, the evaluations). A property\n\
         counts as claimed only where the crate states it: the sentence, quoted, with its file and line in the\n\
         published crate, is listed under \"Where the claims were read\", and `cargo test --release --test\n\
         independent citations` checks every quote against the published source. Where the crate states\n\
         nothing, the tables say \"not claimed\" and mark the tested value with *: the studies then test the value\n\
         the method it names has in theory, or the cost its own table needs, and a miss is a finding, not a\n\
         refuted claim.\n\n\
         Each method is measured through stepladder's public black-box adapters on two autonomous scenes, the\n\
         harmonic oscillator and the eccentric Kepler orbit (e = 0.6). \"holds\" / \"**refuted**\" is stepladder's\n\
         verdict on a claim; \"as expected\" compares every verdict with the one written in `src/methods.rs`\n\
         beside each method, whose reason is a line of the published source or a check that calls the crate\n\
         directly, without stepladder (`tests/independent.rs`). Reproduce one method's rows with\n\
         `cargo test --release --test audit <test>`; every other figure names the command that reproduces it.\n\n\
         Made from sources with fingerprint `{fingerprint}` (this crate, its lock file, and the stepladder\n\
         library it builds); the repository's `cargo test --release` fails when they no longer match, until\n\
         this file is made again.\n"
    );
    let mut crates: Vec<&str> = Vec::new();
    for a in audits {
        if !crates.contains(&a.provenance().krate) {
            crates.push(a.provenance().krate);
        }
    }
    for krate in crates {
        let _ = writeln!(s, "## {krate}\n");
        let fixed: Vec<_> = audits
            .iter()
            .filter_map(|a| match a {
                Audit::Fixed(f) if f.provenance.krate == krate => Some(f),
                _ => None,
            })
            .collect();
        if !fixed.is_empty() {
            let _ = writeln!(
                s,
                "Fixed step. Tested: order p, symplectic S, symmetric R, force evaluations per step E (minimum in\n\
                 brackets); * marks a value the crate does not claim.\n\n\
                 | method | tested p / S / R / E (min) | scene | order [95 %] | order | symplectic | reversible | energy | evaluations counted | evaluations | as expected | test |\n\
                 | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
            );
            for f in fixed {
                let c = &f.claims;
                let p = &f.provenance;
                for row in &f.rows {
                    let agree = disagreements(&Audit::Fixed(f.clone()))
                        .iter()
                        .all(|d| !d.contains(&format!(" on {}:", row.scene)));
                    let energy = row.energy_class.map_or("-", |c| c.name());
                    let evaluations = match row.evaluations {
                        Verdict::Fail => format!("{:.2} > {}", row.per_step, c.force_evaluations),
                        _ => format!("{}", c.force_evaluations),
                    };
                    let _ = writeln!(
                        s,
                        "| {} | {} / {} / {} / {} ({}) | {} | {} [{}] | {} | {} | {} | {} | {:.2} | {} | {} | `{}` |",
                        p.method,
                        starred(p, Prop::Order, c.order.to_string()),
                        starred(p, Prop::Symplectic, yes(c.symplectic).into()),
                        starred(p, Prop::Symmetric, yes(c.symmetric).into()),
                        starred(p, Prop::Evaluations, c.force_evaluations.to_string()),
                        p.minimum_evaluations,
                        row.scene,
                        opt(row.measured_order, 2),
                        row.ci95
                            .map_or("-".into(), |[a, b]| format!("{a:.2}, {b:.2}")),
                        cell(p, Prop::Order, row.order, "-"),
                        cell(
                            p,
                            Prop::Symplectic,
                            row.symplectic,
                            &is_are(row.symplectic_measured, "symplectic")
                        ),
                        cell(
                            p,
                            Prop::Symmetric,
                            row.reversible,
                            &is_are(row.reversible_measured, "symmetric")
                        ),
                        cell(p, Prop::Energy, row.energy, energy),
                        row.per_step,
                        cell(p, Prop::Evaluations, row.evaluations, &evaluations),
                        if agree { "yes" } else { "**NO**" },
                        p.test,
                    );
                }
            }
            s.push('\n');
        }
        let adaptive: Vec<_> = audits
            .iter()
            .filter_map(|a| match a {
                Audit::Adaptive(x) if x.provenance.krate == krate => Some(x),
                _ => None,
            })
            .collect();
        if !adaptive.is_empty() {
            let _ = writeln!(
                s,
                "Adaptive. Tested: order p of the solution advanced, estimate ~ h^m; the global error should follow\n\
                 TOL^(p/m) (no single value for DOP853's blended estimate); accepted steps grow like TOL^(-1/m),\n\
                 s below is that exponent between the two loosest tolerances reached (above 1/2: an estimate ~ h).\n\
                 Evaluations per accepted step are shown, not judged (* : the crate gives no count).\n\n\
                 | method | claims p, m | scene | exponent [95 %] (theory) | runs unfinished | steps ~ TOL^-s | evaluations per accepted step (min) | tolerance ladder | as expected | test |\n\
                 | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
            );
            for a in adaptive {
                let p = &a.provenance;
                for row in &a.rows {
                    let _ = writeln!(
                        s,
                        "| {} | {}, {} | {} | {} [{}] ({}) | {} | {} | {} ({}) | {} | {} | `{}` |",
                        p.method,
                        starred(p, Prop::Order, a.claims.order.to_string()),
                        starred(p, Prop::Estimate, a.claims.estimate_power.to_string()),
                        row.scene,
                        opt(row.exponent, 2),
                        row.ci95
                            .map_or("-".into(), |[x, y]| format!("{x:.2}, {y:.2}")),
                        opt(row.theory, 2),
                        row.unfinished,
                        step_exponent(row),
                        starred(p, Prop::Evaluations, opt(row.evaluations_per_accepted, 2)),
                        p.minimum_evaluations,
                        verdict(row.verdict),
                        if disagreements(&Audit::Adaptive(a.clone()))
                            .iter()
                            .all(|d| !d.contains(&format!(" on {}:", row.scene)))
                        {
                            "yes"
                        } else {
                            "**NO**"
                        },
                        p.test,
                    );
                }
            }
            s.push('\n');
        }
    }
    let _ = writeln!(s, "## Refuted claims and their independent confirmation\n");
    for a in audits {
        let p = a.provenance();
        match a {
            Audit::Fixed(f) => {
                let (refuted, _) = fixed_failures(f);
                if refuted.is_empty() {
                    continue;
                }
                let props: Vec<Prop> = refuted.iter().map(|&i| FIXED_PROPS[i]).collect();
                let names: Vec<&str> = props.iter().map(|p| p.name()).collect();
                let _ = writeln!(
                    s,
                    "- {} {}: {} (reproduce: `cargo test --release --test audit {}`)",
                    p.krate,
                    p.method,
                    names.join(", "),
                    p.test
                );
                let evidence = evidence_on(f.expected.evidence, &props);
                for e in &evidence {
                    let _ = writeln!(s, "  - {e}");
                }
                if evidence.is_empty() {
                    let _ = writeln!(
                        s,
                        "  - no independent evidence on file: see the disagreements below"
                    );
                }
                for row in &f.rows {
                    for &i in &refuted {
                        if let Some(reason) = &row.reasons[i] {
                            let _ = writeln!(
                                s,
                                "  - measured on {}: {}",
                                row.scene,
                                first_sentence(reason)
                            );
                        }
                    }
                }
                if let Some(line) = probe_line(f) {
                    let _ = writeln!(s, "  - {line}");
                }
            }
            Audit::Adaptive(x) => {
                let refuted = x.rows.iter().any(|r| {
                    r.verdict == Verdict::Fail
                        || r.step_exponent
                            .is_some_and(|s| s > crate::FIRST_ORDER_GROWTH)
                });
                if !refuted {
                    continue;
                }
                let ladder_failed = x.rows.iter().any(|r| r.verdict == Verdict::Fail);
                let _ = writeln!(
                    s,
                    "- {} {}: {} (reproduce: `cargo test --release --test audit {}`)",
                    p.krate,
                    p.method,
                    if ladder_failed {
                        "order and estimate order (tolerance ladder)"
                    } else {
                        "estimate order (step growth)"
                    },
                    p.test
                );
                for e in evidence_on(x.expected.evidence, &[Prop::Estimate, Prop::Order]) {
                    let _ = writeln!(s, "  - {e}");
                }
                for row in &x.rows {
                    let _ = writeln!(
                        s,
                        "  - measured on {}: accepted steps ~ TOL^-s, s = {} ({} of 12 runs unfinished); ladder: {}",
                        row.scene,
                        step_exponent(row),
                        row.unfinished,
                        first_sentence(&row.reason)
                    );
                }
            }
        }
    }
    let _ = writeln!(
        s,
        "\n## Findings on properties the crates do not claim\n\n\
         Each tested value below is the method's in theory or its own table's cost, not the crate's word; in\n\
         the measured lines stepladder's \"claimed\" reads \"tested\".\n"
    );
    for a in audits {
        let Audit::Fixed(f) = a else { continue };
        let (_, findings) = fixed_failures(f);
        if findings.is_empty() {
            continue;
        }
        let p = &f.provenance;
        let props: Vec<Prop> = findings.iter().map(|&i| FIXED_PROPS[i]).collect();
        let _ = writeln!(
            s,
            "- {} {} (reproduce: `cargo test --release --test audit {}`)",
            p.krate, p.method, p.test
        );
        for prop in &props {
            if let Some(property) = p.property(*prop) {
                let _ = writeln!(s, "  - {}: {}", prop.name(), property.basis);
            }
        }
        for e in evidence_on(f.expected.evidence, &props) {
            let _ = writeln!(s, "  - {e}");
        }
        for row in &f.rows {
            for &i in &findings {
                if let Some(reason) = &row.reasons[i] {
                    let _ = writeln!(
                        s,
                        "  - measured on {}: {}",
                        row.scene,
                        first_sentence(&tested_wording(reason))
                    );
                }
            }
        }
    }
    let _ = writeln!(s, "\n## Not visible on autonomous scenes\n");
    for line in NOT_VISIBLE {
        let _ = writeln!(s, "- {line}");
    }
    let _ = writeln!(
        s,
        "\n## Where the harness and the independent checks differ\n"
    );
    for line in HARNESS_VS_INDEPENDENT {
        let _ = writeln!(s, "- {line}");
    }
    let all: Vec<String> = audits.iter().flat_map(disagreements).collect();
    let _ = writeln!(s, "\n## Verdicts that differ from their expectation\n");
    if all.is_empty() {
        let _ = writeln!(s, "None.");
    } else {
        for d in all {
            let _ = writeln!(s, "- {d}");
        }
    }
    let _ = writeln!(
        s,
        "\n## Where the claims were read\n\n\
         Paths are inside the published crates (`~/.cargo/registry/src/*/` after `cargo fetch`); a line range\n\
         is a sentence that runs over several lines. \"not claimed\" gives where the tested value comes from.\n\n\
         | method | property | the crate's words | where | remark |\n\
         | --- | --- | --- | --- | --- |"
    );
    for a in audits {
        let p = a.provenance();
        for property in p.properties {
            let (words, at) = match &property.claim {
                Some(c) => (
                    format!("\"{}\"", c.quote.replace('|', "\\|")),
                    format!("`{}`", c.at),
                ),
                None => ("not claimed".to_string(), "-".to_string()),
            };
            let _ = writeln!(
                s,
                "| {} {} | {} | {} | {} | {} |",
                p.krate,
                p.method,
                property.prop.name(),
                words,
                at,
                property.basis
            );
        }
    }
    s.push_str(&race_section(races));
    s
}

/// A cost with its interval or bracket.
fn reach(r: Reach) -> String {
    match r {
        Reach::Estimated(c) => {
            let [lo, hi] = c.interval();
            format!("{:.2e} [{lo:.2e}, {hi:.2e}]", c.cost())
        }
        Reach::Bracketed { least, most } if least == most => {
            format!("{most:.2e} (its cheapest run)")
        }
        Reach::Bracketed { least, most } => format!("{least:.2e} to {most:.2e} (runs)"),
        Reach::NotReached => "not reached".to_string(),
    }
}

/// Who is cheaper at one target: brahe's cost over the cheaper of
/// stepladder's pairs and its interval.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Standing {
    ratio: f64,
    interval: [f64; 2],
}

impl Standing {
    /// `Some(true)` when stepladder is cheaper beyond the scatter,
    /// `Some(false)` when brahe is, `None` when the interval holds 1.
    fn resolved(&self) -> Option<bool> {
        let [lo, hi] = self.interval;
        if lo > 1.0 {
            Some(true)
        } else if hi < 1.0 {
            Some(false)
        } else {
            None
        }
    }

    fn figure(&self) -> String {
        let [lo, hi] = self.interval;
        format!("{:.2} [{lo:.2}, {hi:.2}]", self.ratio)
    }

    fn cell(&self) -> String {
        self.cell_between("brahe", "stepladder")
    }

    /// The figure and who is cheaper, the ratio being `numerator`'s cost
    /// over `denominator`'s.
    fn cell_between(&self, numerator: &str, denominator: &str) -> String {
        let outcome = match self.resolved() {
            Some(true) => format!("{denominator} cheaper"),
            Some(false) => format!("{numerator} cheaper"),
            None => "not resolved".to_string(),
        };
        format!("{}: {outcome}", self.figure())
    }
}

/// brahe's standing at one target by `cost`; `None` unless brahe and one of
/// stepladder's pairs reach it.
fn standing(race: &SceneRace, cost: impl Fn(&Contender) -> Reach) -> Option<Standing> {
    standing_of(&race.contenders[0], race, cost)
}

/// `peer`'s standing against stepladder's cheaper pair at one target by
/// `cost`; `None` unless both reach it.
fn standing_of(
    peer: &Contender,
    race: &SceneRace,
    cost: impl Fn(&Contender) -> Reach,
) -> Option<Standing> {
    standing_against(&cost(peer), race, cost)
}

/// `reach`'s standing against stepladder's cheaper pair by `cost`; `None`
/// unless both reach the target.
fn standing_against(
    reach: &Reach,
    race: &SceneRace,
    cost: impl Fn(&Contender) -> Reach,
) -> Option<Standing> {
    let (ratio, interval) = target_cost::ratio(reach, &best_own(race, cost)?)?;
    Some(Standing { ratio, interval })
}

/// The cheaper of stepladder's pairs by `cost`, where one reaches the
/// target.
fn best_own(race: &SceneRace, cost: impl Fn(&Contender) -> Reach) -> Option<Reach> {
    race.contenders[1..]
        .iter()
        .map(&cost)
        .filter(|r| r.cost().is_some())
        .min_by(|a, b| a.cost().partial_cmp(&b.cost()).expect("finite costs"))
}

/// What equal steps of the same tableau cost at every judged target,
/// against brahe and stepladder's cheaper pair, and where they are cheaper
/// than the pair beyond the scatter.
fn uniform_section(races: &[SceneRace]) -> String {
    let mut s = String::from(
        "\n**Equal steps.** The same tableau without step control: brahe's own step, every step\n\
         accepted, at `N` equal steps over the interval, `N` = 1, 2, ... (each next count the larger of\n\
         `N + 1` and `10^(1/96) N` rounded down, at most an eighth of a decade of a twelfth-order error), until the error is a\n\
         decade below the smallest judged target or a run would cost more than the dearest adaptive run\n\
         on the scene; its evaluations to a target are estimated as the contenders' are. It is a\n\
         reference beside the race, not a contender: the count that reaches a target is known only in\n\
         hindsight (a user of equal steps finds it by trial, or by a ladder like this one). The last column\n\
         divides them by the cheaper of stepladder's pairs: above 1 the pair is cheaper, below 1 equal\n\
         steps are. Step control pays where the motion's time scale changes along the run; where it\n\
         hardly changes, equal steps are the best steps, and what a controller spends to find and hold\n\
         them (a first step off the best one, rejected attempts, a short last step, steps that follow\n\
         its estimate's swings) is not won back.\n\n\
         | scene | target | equal steps | brahe RKN1210 | cheaper of stepladder's pairs | equal steps / best |\n\
         | --- | --- | --- | --- | --- | --- |\n",
    );
    let mut cheaper: Vec<String> = Vec::new();
    for race in races {
        for target in TARGETS.into_iter().filter(|&t| race.judges(t)) {
            let uniform = race.uniform.evaluations(target);
            let standing = standing_against(&uniform, race, |c| c.evaluations(target));
            if let Some(st) = standing.filter(|st| st.resolved() == Some(false)) {
                cheaper.push(format!(
                    "`{}` at {target:.0e} ({})",
                    race.scene,
                    st.figure()
                ));
            }
            let _ = writeln!(
                s,
                "| `{}` | {target:.0e} | {} | {} | {} | {} |",
                race.scene,
                reach(uniform),
                reach(race.contenders[0].evaluations(target)),
                best_own(race, |c| c.evaluations(target)).map_or("not reached".to_string(), reach),
                standing.map_or("-".to_string(), |st| st.cell_between("equal steps", "pair")),
            );
        }
    }
    let _ = writeln!(
        s,
        "\nEqual steps are cheaper than stepladder's pairs beyond the scatter {}.",
        if cheaper.is_empty() {
            "nowhere".to_string()
        } else {
            format!("on {}", cheaper.join(", "))
        }
    );
    s
}

/// How stepladder's estimate for one step of a fixed size varies along
/// each run, and where it rises over one step by more than the margin its
/// controller leaves.
fn estimate_section(races: &[SceneRace]) -> String {
    let margin = races.first().map_or(f64::NAN, |r| r.estimate.margin);
    let mut s = format!(
        "\n**The estimate along the run.** What a step controller follows: stepladder's plain pair's\n\
         own estimate (the number it accepts a step by, in units of the tolerance) for one step of\n\
         `h`, the run's length over the steps the pair accepts at TOL {ESTIMATE_TOLERANCE:.0e}, from start points\n\
         {STARTS_PER_STEP} a step along the run (the compensated pair's states there, at a tolerance five decades\n\
         tighter). A controller sets each step from the estimates it has seen and aims at `0.9^11`\n\
         of the tolerance, so a step of the size it holds is rejected where the estimate one step on\n\
         is more than its margin, `0.9^-11` = {margin:.2}, above the last. It can avoid that only by\n\
         knowing the rise in advance, or by steps shorter everywhere by the 11th root of the rise over\n\
         the margin. Equal steps and a step cap do not follow the estimate at all.\n\n\
         | scene | h | start points | smallest | largest | largest / smallest | largest rise over one step | start points whose rise exceeds {margin:.2} |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- |\n"
    );
    for race in races {
        let e = &race.estimate;
        let (lo, hi) = e.range();
        let rises = e.rises();
        let over = rises.iter().filter(|&&r| r > e.margin).count();
        let largest_rise = rises.iter().copied().fold(f64::NAN, f64::max);
        // a ratio in two decimals up to 100, in three digits beyond
        let ratio = |x: f64| {
            if x < 100.0 {
                format!("{x:.2}")
            } else {
                format!("{x:.2e}")
            }
        };
        let _ = writeln!(
            s,
            "| `{}` | {:.4} | {} | {lo:.2e} | {hi:.2e} | {} | {} | {over} of {} |",
            race.scene,
            e.step,
            e.estimates.len(),
            ratio(hi / lo),
            ratio(largest_rise),
            rises.len(),
        );
    }
    s
}

/// Per scene, at the judged targets both sides reach, where stepladder and
/// where brahe is cheaper beyond the scatter and where neither is, by
/// evaluations and by time, and the targets only one side reaches.
fn race_summary(races: &[SceneRace]) -> String {
    let mut s = String::from(
        "\nIn short (brahe's cost over the cheaper of stepladder's pairs and its 95% interval, at the judged \
         targets both reach):\n\n",
    );
    for race in races {
        let judged: Vec<f64> = TARGETS.into_iter().filter(|&t| race.judges(t)).collect();
        let verdicts = |cost: &dyn Fn(&Contender, f64) -> Reach| {
            let mut groups: [(&str, Vec<String>); 3] = [
                ("stepladder cheaper at", Vec::new()),
                ("brahe cheaper at", Vec::new()),
                ("not resolved at", Vec::new()),
            ];
            for &t in &judged {
                let Some(st) = standing(race, |c| cost(c, t)) else {
                    continue;
                };
                let slot = match st.resolved() {
                    Some(true) => 0,
                    Some(false) => 1,
                    None => 2,
                };
                groups[slot].1.push(format!("{t:.0e} ({})", st.figure()));
            }
            let parts: Vec<String> = groups
                .iter()
                .filter(|(_, v)| !v.is_empty())
                .map(|(what, v)| format!("{what} {}", v.join(", ")))
                .collect();
            if parts.is_empty() {
                "no target both reach".to_string()
            } else {
                parts.join("; ")
            }
        };
        // the judged targets one side reaches and the other does not
        let reached = |c: &Contender, t: f64| c.evaluations(t).cost().is_some();
        let only = |who: &str, brahe_side: bool| {
            let targets: Vec<String> = judged
                .iter()
                .filter(|&&t| {
                    let brahe = reached(&race.contenders[0], t);
                    let own = race.contenders[1..].iter().any(|c| reached(c, t));
                    if brahe_side {
                        brahe && !own
                    } else {
                        own && !brahe
                    }
                })
                .map(|t| format!("{t:.0e}"))
                .collect();
            if targets.is_empty() {
                String::new()
            } else {
                format!("; only {who} reaches {}", targets.join(", "))
            }
        };
        let _ = writeln!(
            s,
            "- `{}`: by evaluations {}; by time {}{}{}.",
            race.scene,
            verdicts(&|c, t| c.evaluations(t)),
            verdicts(&|c, t| c.seconds(t)),
            only("brahe", true),
            only("stepladder", false),
        );
    }
    s.push_str(
        "\nWhat differs between the implementations, read from the sources: brahe measures the estimate in\n\
         the largest component against `tol (1 + max(|y0|, |y1|))` (traits.rs, `compute_normalized_error_s`)\n\
         where stepladder takes the root mean square of the same ratios; brahe grows an accepted step by\n\
         `0.9 err^(-1/12)` within 0.2 to 10 times and at most 900 time units (config.rs, `Default`), stepladder\n\
         by `0.9 err^(-1/11)` within 0.2 to 5 times, or by Gustafsson's predicted step where that is\n\
         smaller (the estimate's growth over the last two accepted steps carried one step further, which\n\
         the pairs take to be rejected less where the estimate grows); brahe's first attempt is the step its caller passes\n\
         (here the whole interval, cut to no less than a fifth a rejection), stepladder's first trial is the\n\
         state's size over its rate, `||y0|| / ||f(y0)||`, in the same scaled norm with each block's\n\
         (positions', velocities') length in place of each component's, a rejected one retried where its\n\
         estimate points; stepladder's compensated pair adds each increment with its rounding\n\
         carried. One of these is measured: the step cap, below.\n",
    );
    s
}

/// What brahe's step cap does: where brahe's runs take as many steps as
/// steps of the cap would, and brahe run again without it, at every judged
/// target of the scenes where that changes a run.
fn cap_section(races: &[SceneRace]) -> String {
    let Some(cap) = crate::glue::brahe_max_step() else {
        return String::new();
    };
    let mut s = format!(
        "\n**brahe's step cap.** brahe's defaults hold every step to at most {cap} time units, a bound\n\
         its documentation gives in seconds (config.rs:69, `max_step: Some(900.0) (15 minutes)`); the\n\
         audit passes each scene in its own units, so on the outer solar system, in days, no step may\n\
         exceed {cap} days, {share:.2} of Jupiter's period.\n",
        share = cap / OuterSolarSystem::default().period(),
    );
    let mut any_held = false;
    for race in races {
        let fewest = (race.t_end / cap).ceil() as u64;
        let held: Vec<f64> = race.contenders[0]
            .points
            .iter()
            .filter(|p| p.error.is_some() && p.accepted == fewest)
            .map(|p| p.tolerance)
            .collect();
        if let (Some(first), Some(last)) = (held.first(), held.last()) {
            any_held = true;
            let _ = writeln!(
                s,
                "On `{}` (end time {:.0}) {} of brahe's runs, at tolerances from {first:.2e} to {last:.2e},\n\
                 accept {fewest} steps, as many as steps of {cap} time units take to the end (`ceil(t_end / max_step)`):\n\
                 there the cap, not brahe's estimate, sets the steps.",
                race.scene,
                race.t_end,
                held.len(),
            );
        }
    }
    if any_held {
        s.push_str(
            "Called directly on the outer solar system at 1e-7, with a force written apart from stepladder\n\
             (`tests/independent.rs`), brahe steps exactly the cap every step but the first (the caller's\n\
             proposal, cut down from the whole interval by rejections: the cap bounds only the proposals\n\
             brahe returns) and the last (cut to land on the end time).\n",
        );
    }
    // a scene where no run changes without the cap needs no row
    let same_runs = |a: &Contender, b: &Contender| {
        let key = |c: &Contender| -> Vec<_> {
            c.points
                .iter()
                .map(|p| (p.evaluations, p.accepted, p.rejected, p.error))
                .collect()
        };
        key(a) == key(b)
    };
    let (unchanged, changed): (Vec<&SceneRace>, Vec<&SceneRace>) = races
        .iter()
        .partition(|r| same_runs(&r.contenders[0], &r.uncapped));
    if !unchanged.is_empty() {
        let names: Vec<String> = unchanged.iter().map(|r| format!("`{}`", r.scene)).collect();
        let _ = writeln!(
            s,
            "On {} every run is the same without the cap, run for run:\n\
             no step reaches it.",
            names.join(", ")
        );
    }
    if changed.is_empty() {
        return s;
    }
    s.push_str(
        "Run again with `max_step: None`, every other setting the same (the same glue, brahe's own\n\
         code), brahe needs these evaluations where the cap changes its runs; the last column divides them\n\
         by the cheaper of stepladder's pairs, as \"brahe / best\" does above:\n\n\
         | scene | target | brahe RKN1210 | without its step cap | without its step cap / best |\n\
         | --- | --- | --- | --- | --- |\n",
    );
    for race in changed {
        for target in TARGETS.into_iter().filter(|&t| race.judges(t)) {
            let cell = standing_of(&race.uncapped, race, |c| c.evaluations(target))
                .map_or("-".to_string(), |st| st.cell());
            let _ = writeln!(
                s,
                "| `{}` | {target:.0e} | {} | {} | {cell} |",
                race.scene,
                reach(race.contenders[0].evaluations(target)),
                reach(race.uncapped.evaluations(target)),
            );
        }
    }
    s
}

/// A run's error at the end time, or that it did not get there.
fn end_error(error: Option<f64>) -> String {
    error.map_or("did not reach the end".to_string(), |e| format!("{e:.2e}"))
}

/// The spread of a decade grid's interpolated evaluations over the grid's
/// offsets, at every judged target that every offset reaches: the median
/// and the largest, in percent, and how many.
fn decade_spreads(races: &[SceneRace]) -> Option<(f64, f64, usize)> {
    let spreads: Vec<f64> = races
        .iter()
        .flat_map(|race| {
            TARGETS
                .into_iter()
                .filter(|&t| race.judges(t))
                .flat_map(move |t| {
                    race.contenders
                        .iter()
                        .filter_map(move |c| c.decade_spread(t))
                })
        })
        .map(|r| 100.0 * (r - 1.0))
        .collect();
    let largest = spreads.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let n = spreads.len();
    target_cost::median(spreads).map(|median| (median, largest, n))
}

/// The race of brahe's RKN12(10) against stepladder's own (`crate::race`).
pub fn race_section(races: &[SceneRace]) -> String {
    let mut s = String::new();
    let names: Vec<&str> = races
        .first()
        .map(|r| r.contenders.iter().map(|c| c.name).collect())
        .unwrap_or_default();
    let spread = decade_spreads(races).map_or(String::new(), |(median, largest, n)| {
        format!(
            "Why not interpolate between the two runs that bracket a target, as the repository's race does:\n\
             on a grid of one tolerance a decade that is too coarse here. Over the {per} offsets of such a grid\n\
             within this one, the interpolated evaluations at a judged target move by {median:.0}% (median of\n\
             {n}) and up to {largest:.0}%, more than most of the differences below.\n",
            per = crate::race::PER_DECADE,
        )
    });
    let _ = writeln!(
        s,
        "\n## The race at the highest accuracy: brahe's RKN12(10) against stepladder's\n\n\
         brahe's RKN1210SIntegrator, stepladder's DPRKN12(10) pair and the same pair with compensated state\n\
         updates advance with one published tableau (Dormand, El-Mikkawy and Prince 1987); what separates\n\
         them is the step control, the error norm, the arithmetic of the updates and the cost of a step.\n\
         Each runs the tolerances 1e-3 down to 1e-16, {per} a decade (relative and absolute alike), until\n\
         its error is a decade below the smallest target judged; its error is the phase-space distance at\n\
         the end time to the reference, its evaluations are counted on the callback, and each run is timed\n\
         the fastest of {repeats} rounds in which the three (and brahe without its step cap, below) take turns\n\
         (on a machine shared with other work).\n\
         A target is judged where the reference's own error is at most a tenth of it. The references are\n\
         the repository's race's (`lab/references/`). Reproduce with `cargo run --release` in `audit/`.\n\n\
         Every run whose error lies within a decade of a target predicts the evaluations to reach it by the\n\
         method's order, `evaluations (error / target)^(1/12)`; with one prediction per distinct evaluation\n\
         count (the mean of its runs': neighbouring tolerances that take as many steps place them almost\n\
         alike), their mean on log axes is the estimate and their scatter its 95% interval (Student's t).\n\
         With fewer than three counts near a target, the runs bracket its cost instead: at least the\n\
         cheapest run of any tolerance, at most the cheapest that reaches it. The seconds to a target are\n\
         its evaluations at the contender's median seconds per evaluation over all its runs (a step's cost\n\
         per evaluation does not depend on the tolerance, and the median votes out the stretches in which\n\
         the shared machine ran slow, which otherwise fall in or out of a target's window by chance); their\n\
         interval is the evaluations', and leaves out how reproducible that median is from one build or run\n\
         of the audit to the next. \"brahe / best\" divides brahe's cost by the cheaper of stepladder's two\n\
         pairs, with its 95% interval (Welch's, or the quotient of a bracket and an interval): above 1\n\
         stepladder's pair is cheaper, and a side is called cheaper only where the interval excludes 1.\n\n\
         {spread}",
        per = crate::race::PER_DECADE,
        repeats = crate::race::REPEATS,
    );
    let _ = writeln!(
        s,
        "| scene | end time | reference | its error |\n| --- | --- | --- | --- |"
    );
    for race in races {
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {:.2e} |",
            race.scene, race.t_end, race.reference, race.reference_error
        );
    }
    let _ = writeln!(
        s,
        "\n| scene | target | evaluations: {} | {} | {} | brahe / best | seconds: {} | {} | {} | brahe / best |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
        names.first().unwrap_or(&"-"),
        names.get(1).unwrap_or(&"-"),
        names.get(2).unwrap_or(&"-"),
        names.first().unwrap_or(&"-"),
        names.get(1).unwrap_or(&"-"),
        names.get(2).unwrap_or(&"-"),
    );
    for race in races {
        for target in TARGETS {
            if !race.judges(target) {
                let _ = writeln!(
                    s,
                    "| `{}` | {target:.0e} | not judged: the reference's error is {:.1e} | | | | | | | |",
                    race.scene, race.reference_error
                );
                continue;
            }
            let evaluations: Vec<String> = race
                .contenders
                .iter()
                .map(|c| reach(c.evaluations(target)))
                .collect();
            let seconds: Vec<String> = race
                .contenders
                .iter()
                .map(|c| reach(c.seconds(target)))
                .collect();
            let cell = |st: Option<Standing>| st.map_or("-".to_string(), |st| st.cell());
            let _ = writeln!(
                s,
                "| `{}` | {target:.0e} | {} | {} | {} | {} |",
                race.scene,
                evaluations.join(" | "),
                cell(standing(race, |c| c.evaluations(target))),
                seconds.join(" | "),
                cell(standing(race, |c| c.seconds(target))),
            );
        }
    }
    s.push_str(&race_summary(races));
    s.push_str(&cap_section(races));
    s.push_str(&uniform_section(races));
    s.push_str(&estimate_section(races));
    let _ = writeln!(
        s,
        "\nThe runs of each contender (tolerance: force evaluations (accepted steps + rejected attempts),\n\
         error at the end time; for equal steps, the count: force evaluations, error), and the\n\
         nanoseconds per evaluation over its runs (the whole step's cost divided by its evaluations;\n\
         median and range):\n\n\
         | scene | contender | runs | ns per evaluation |\n\
         | --- | --- | --- | --- |"
    );
    for race in races {
        for c in race.contenders.iter().chain([&race.uncapped]) {
            let runs: Vec<String> = c
                .points
                .iter()
                .map(|p| {
                    format!(
                        "{:.2e}: {} ({} + {}), {}",
                        p.tolerance,
                        p.evaluations,
                        p.accepted,
                        p.rejected,
                        end_error(p.error)
                    )
                })
                .collect();
            let ns: Vec<f64> = c
                .points
                .iter()
                .map(|p| 1e9 * p.seconds / p.evaluations.max(1) as f64)
                .collect();
            let lo = ns.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = ns.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let ns = if ns.is_empty() {
                "-".to_string()
            } else {
                let mid = 1e9 * c.seconds_per_evaluation();
                format!("{mid:.0} ({lo:.0} to {hi:.0})")
            };
            let _ = writeln!(
                s,
                "| `{}` | {} | {} | {} |",
                race.scene,
                c.name,
                runs.join("; "),
                ns
            );
        }
        let runs: Vec<String> = race
            .uniform
            .points
            .iter()
            .map(|p| {
                format!(
                    "{} steps: {}, {}",
                    p.steps,
                    p.evaluations,
                    end_error(p.error)
                )
            })
            .collect();
        let _ = writeln!(
            s,
            "| `{}` | brahe's step, equal steps | {} | - |",
            race.scene,
            runs.join("; ")
        );
    }
    s
}
