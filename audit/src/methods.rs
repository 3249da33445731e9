//! The audited methods: each property the audit tests, with the sentence in
//! which the crate states it (quoted, with its file and line in the
//! published source) or marked as not claimed, together with the value
//! tested, the verdict expected, and the independent reason for it.
//!
//! A property the crate does not claim is still tested, against the value
//! the method it names has in theory (Gauss-Legendre is symplectic, a
//! palindromic composition symmetric) or the cost its own table needs; a
//! miss is then a finding about the implementation, never a refuted claim.
//!
//! "Independent" means not measured by this harness: a source line, or a
//! check calling the crate directly in `tests/independent.rs`, named beside
//! each figure it reproduces.

use crate::Prop::{Energy, Estimate, Evaluations, Order, Symmetric, Symplectic};
use crate::glue::{self, OsPair, UtsuroiFixed};
use crate::{
    AdaptiveExpectation, Audit, Evidence, FixedExpectation, Property, Provenance, audit_adaptive,
    audit_fixed, said, said_and, unsaid,
};
use differential_equations::methods::SymplecticIntegrator;
use differential_equations::prelude::ExplicitRungeKutta;
use peroxide::fuga::{ButcherTableau, DP45, GL4, ImplicitSolver, RALS3, RALS4, RK4, RK5, TSIT45};
use stepladder::scheme::{AdaptiveBlackBox, AdaptiveClaims};
use stepladder::scheme::{BlackBox, SchemeMeta};
use stepladder::study::Verdict::{Fail, Inconclusive, NotClaimed, Pass};

/// Claims of a fixed-step method.
const fn claims(
    id: &'static str,
    order: u32,
    symplectic: bool,
    symmetric: bool,
    evaluations: u32,
    implicit: bool,
    reference: &'static str,
) -> SchemeMeta {
    SchemeMeta {
        id,
        name: id,
        order,
        symplectic,
        symmetric,
        force_evaluations: evaluations,
        implicit,
        reference,
        phase_error: None,
    }
}

/// Every claim expected to hold, for a method whose coefficients pass the
/// independent checks.
/// `sum b_i c_i^m - 1/(m+1)` of an explicit tableau, with `c` the row sums
/// of `a` (what an autonomous problem sees).
fn bushy_defect(a: &[&[f64]], b: &[f64], m: i32) -> f64 {
    let nodes = a.iter().map(|row| row.iter().sum::<f64>());
    b.iter().zip(nodes).map(|(b, c)| b * c.powi(m)).sum::<f64>() - 1.0 / f64::from(m + 1)
}

const fn holds(why: &'static str) -> FixedExpectation {
    FixedExpectation {
        harmonic: [Pass; 5],
        kepler: [Pass; 5],
        why,
        evidence: &[],
        named: None,
    }
}

/// Every claim expected to hold on both scenes except those named `Fail`
/// in `verdicts` (order, symplectic, reversible, energy, evaluations).
const fn except(
    verdicts: [stepladder::study::Verdict; 5],
    why: &'static str,
    evidence: &'static [Evidence],
) -> FixedExpectation {
    FixedExpectation {
        harmonic: verdicts,
        kepler: verdicts,
        why,
        evidence,
        named: None,
    }
}

/// Symplecticity, symmetry and energy not claimed by a Runge-Kutta method
/// that is neither: the studies test "not symplectic, not symmetric", which
/// promises nothing, and report what they measure.
const RK_NOT_GEOMETRIC: [Property; 3] = [
    unsaid(
        Symplectic,
        "explicit Runge-Kutta: not symplectic in theory (tested: no)",
    ),
    unsaid(
        Symmetric,
        "explicit Runge-Kutta: not symmetric in theory (tested: no)",
    ),
    unsaid(
        Energy,
        "tested: drift allowed, as for a scheme neither symplectic nor symmetric",
    ),
];

/// What is tested of a Gauss-Legendre method the crate claims only the
/// order of: the properties of Gauss collocation in theory.
const GL4_NOT_CLAIMED: [Property; 4] = [
    unsaid(
        Symplectic,
        "not claimed (the doc's only other statement is \"better stability properties compared to explicit methods\", ode.rs:1204); tested: yes, as Gauss collocation is symplectic in theory",
    ),
    unsaid(
        Symmetric,
        "not claimed; tested: yes, as Gauss collocation is symmetric in theory",
    ),
    unsaid(
        Energy,
        "not claimed; tested: bounded, as follows for a symplectic, symmetric map",
    ),
    unsaid(
        Evaluations,
        "not claimed; shown, not judged (an implicit method's iterations are its own); 2 = stages",
    ),
];

// ---------------------------------------------------------------- utsuroi

pub fn utsuroi_stormer_verlet() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "utsuroi 0.2.0",
            method: "StormerVerlet",
            properties: const {
                &[
                    said(
                        Order,
                        "A 2nd-order symplectic method for separable Hamiltonian systems",
                        "utsuroi-0.2.0/src/solver/verlet.rs:9",
                    ),
                    said(
                        Symplectic,
                        "A 2nd-order symplectic method for separable Hamiltonian systems",
                        "utsuroi-0.2.0/src/solver/verlet.rs:9",
                    ),
                    said_and(
                        Symmetric,
                        "Verlet is time-reversible: N steps forward + N steps backward = identity.",
                        "utsuroi-0.2.0/src/solver/verlet.rs:466",
                        "stated on the crate's own test, not in its API docs",
                    ),
                    said(
                        Energy,
                        "has excellent long-term energy conservation properties",
                        "utsuroi-0.2.0/src/solver/verlet.rs:11-12",
                    ),
                    unsaid(
                        Evaluations,
                        "not claimed; tested: 2, the two kicks of the kick-drift-kick form the doc writes out (verlet.rs:20-23); 1 if the last force were kept for the next step",
                    ),
                ]
            },
            minimum_evaluations: 1,
            test: "utsuroi_stormer_verlet",
        },
        &BlackBox::new(
            claims("utsuroi-verlet", 2, true, true, 2, false, "utsuroi 0.2.0"),
            |q: &mut [f64], v: &mut [f64], h: f64, f: &stepladder::scheme::Force<f64>| {
                glue::utsuroi_step(UtsuroiFixed::StormerVerlet, q, v, h, f)
            },
        ),
        holds("kick-drift-kick Verlet as written in verlet.rs:24-55"),
    ))
}

macro_rules! utsuroi_yoshida {
    ($fn:ident, $variant:ident, $id:literal, $order:literal, $evals:literal, $min:literal, $props:expr, $why:literal) => {
        pub fn $fn() -> Audit {
            Audit::Fixed(audit_fixed(
                Provenance {
                    krate: "utsuroi 0.2.0",
                    method: stringify!($variant),
                    properties: const { $props },
                    minimum_evaluations: $min,
                    test: stringify!($fn),
                },
                &BlackBox::new(
                    claims($id, $order, true, true, $evals, false, "utsuroi 0.2.0"),
                    |q: &mut [f64], v: &mut [f64], h: f64, f: &stepladder::scheme::Force<f64>| {
                        glue::utsuroi_step(UtsuroiFixed::$variant, q, v, h, f)
                    },
                ),
                holds($why),
            ))
        }
    };
}
utsuroi_yoshida!(
    utsuroi_yoshida4,
    Yoshida4,
    "utsuroi-yoshida4",
    4,
    6,
    3,
    &[
        said(
            Order,
            "4th-order accuracy with symplectic structure preservation.",
            "utsuroi-0.2.0/src/solver/yoshida.rs:76"
        ),
        said(
            Symplectic,
            "4th-order accuracy with symplectic structure preservation.",
            "utsuroi-0.2.0/src/solver/yoshida.rs:76"
        ),
        said_and(
            Symmetric,
            "fn yoshida4_time_reversible(",
            "utsuroi-0.2.0/src/solver/yoshida.rs:443",
            "the name of the crate's own test, under \"// --- Time-reversibility ---\" (yoshida.rs:415); not in its API docs",
        ),
        unsaid(
            Energy,
            "not claimed; tested: bounded, as follows for a symplectic, symmetric map"
        ),
        said(
            Evaluations,
            "Cost: 6 force evaluations per step (3 Verlet substeps × 2).",
            "utsuroi-0.2.0/src/solver/yoshida.rs:77"
        ),
    ],
    "composition check of the published weights: sum g = 1, sum g^3 = 0"
);
utsuroi_yoshida!(
    utsuroi_yoshida6,
    Yoshida6,
    "utsuroi-yoshida6",
    6,
    14,
    7,
    &[
        said(
            Order,
            "6th-order accuracy with symplectic structure preservation.",
            "utsuroi-0.2.0/src/solver/yoshida.rs:83"
        ),
        said(
            Symplectic,
            "6th-order accuracy with symplectic structure preservation.",
            "utsuroi-0.2.0/src/solver/yoshida.rs:83"
        ),
        said_and(
            Symmetric,
            "fn yoshida6_time_reversible(",
            "utsuroi-0.2.0/src/solver/yoshida.rs:458",
            "the name of the crate's own test, under \"// --- Time-reversibility ---\" (yoshida.rs:415); not in its API docs",
        ),
        unsaid(
            Energy,
            "not claimed; tested: bounded, as follows for a symplectic, symmetric map"
        ),
        said(
            Evaluations,
            "Cost: 14 force evaluations per step.",
            "utsuroi-0.2.0/src/solver/yoshida.rs:84"
        ),
    ],
    "composition check of the published weights: order 6"
);
utsuroi_yoshida!(
    utsuroi_yoshida8,
    Yoshida8,
    "utsuroi-yoshida8",
    8,
    30,
    15,
    &[
        said(
            Order,
            "8th-order accuracy with symplectic structure preservation.",
            "utsuroi-0.2.0/src/solver/yoshida.rs:90"
        ),
        said(
            Symplectic,
            "8th-order accuracy with symplectic structure preservation.",
            "utsuroi-0.2.0/src/solver/yoshida.rs:90"
        ),
        said_and(
            Symmetric,
            "fn yoshida8_time_reversible(",
            "utsuroi-0.2.0/src/solver/yoshida.rs:473",
            "the name of the crate's own test, under \"// --- Time-reversibility ---\" (yoshida.rs:415); not in its API docs",
        ),
        unsaid(
            Energy,
            "not claimed; tested: bounded, as follows for a symplectic, symmetric map"
        ),
        said(
            Evaluations,
            "Cost: 30 force evaluations per step.",
            "utsuroi-0.2.0/src/solver/yoshida.rs:91"
        ),
    ],
    "composition check of the published weights: order 8"
);

pub fn utsuroi_rk4() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "utsuroi 0.2.0",
            method: "Rk4",
            properties: const {
                &[
                    said(
                        Order,
                        "Classic 4th-order Runge-Kutta integrator.",
                        "utsuroi-0.2.0/src/solver/rk4.rs:3",
                    ),
                    RK_NOT_GEOMETRIC[0],
                    said_and(
                        Symmetric,
                        "RK4 is NOT time-reversible: forward+backward does NOT recover initial state.",
                        "utsuroi-0.2.0/src/comparison.rs:19",
                        "a claim that it is not (tested: no), on the crate's own test",
                    ),
                    RK_NOT_GEOMETRIC[2],
                    unsaid(
                        Evaluations,
                        "not claimed as a count; tested: 4, the stages k1..k4 the doc writes out (rk4.rs:9-13)",
                    ),
                ]
            },
            minimum_evaluations: 4,
            test: "utsuroi_rk4",
        },
        &BlackBox::new(
            claims("utsuroi-rk4", 4, false, false, 4, false, "utsuroi 0.2.0"),
            |q: &mut [f64], v: &mut [f64], h: f64, f: &stepladder::scheme::Force<f64>| {
                glue::utsuroi_step(UtsuroiFixed::Rk4, q, v, h, f)
            },
        ),
        holds("Butcher-tree check of the parsed tableau: order 4"),
    ))
}

pub fn utsuroi_dormand_prince() -> Audit {
    Audit::Adaptive(audit_adaptive(
        Provenance {
            krate: "utsuroi 0.2.0",
            method: "DormandPrince (stepper)",
            properties: const {
                &[
                    said(
                        Order,
                        "The 5th-order solution is propagated (local extrapolation)",
                        "utsuroi-0.2.0/src/solver/dp45/mod.rs:15-16",
                    ),
                    said(
                        Estimate,
                        "the 4th-order solution is used only for error estimation.",
                        "utsuroi-0.2.0/src/solver/dp45/mod.rs:16-17",
                    ),
                    said_and(
                        Evaluations,
                        "The FSAL (First Same As Last) property allows reuse of the 7th stage derivative as the 1st stage of the next step.",
                        "utsuroi-0.2.0/src/solver/dp45/mod.rs:17-18",
                        "7 stages less the reused one: 6 per step; shown per accepted step, not judged (the stepper reports no count)",
                    ),
                ]
            },
            minimum_evaluations: 6,
            test: "utsuroi_dormand_prince",
        },
        &AdaptiveBlackBox::new(
            "utsuroi-dp45",
            AdaptiveClaims::pair(5, 4),
            glue::utsuroi_dp45,
        ),
        AdaptiveExpectation {
            verdict: Pass,
            first_order_estimate: false,
            why: "Butcher-tree check: b order 5, b - e order 4",
            evidence: &[],
        },
    ))
}

// ---------------------------------------------------- differential-equations

pub fn de_velocity_verlet() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "differential-equations 0.7.0",
            method: "SymplecticIntegrator::velocity_verlet",
            properties: const {
                &[
                    said(
                        Order,
                        "Velocity Verlet (2nd Order Symplectic Integrator).",
                        "differential-equations-0.7.0/src/methods/symplectic/velocity_verlet.rs:16",
                    ),
                    said(
                        Symplectic,
                        "Velocity Verlet (2nd Order Symplectic Integrator).",
                        "differential-equations-0.7.0/src/methods/symplectic/velocity_verlet.rs:16",
                    ),
                    unsaid(
                        Symmetric,
                        "not claimed; tested: yes, as the documented table c = (0, 1), d = (1/2, 1/2) (velocity_verlet.rs:21-23) is palindromic",
                    ),
                    said(
                        Energy,
                        "Ideal for conservative physics and orbital mechanics where energy conservation over long periods is required.",
                        "differential-equations-0.7.0/src/methods/symplectic/velocity_verlet.rs:18-19",
                    ),
                    unsaid(
                        Evaluations,
                        "not claimed (the crate's own counter, `evals.function += 1` after each `ode.diff`, reports what it spends); tested: 2, the two kicks d1, d2 of the documented table; 1 if the last force were kept for the next step",
                    ),
                ]
            },
            minimum_evaluations: 1,
            test: "de_velocity_verlet",
        },
        &BlackBox::new(
            claims(
                "de-velocity-verlet",
                2,
                true,
                true,
                2,
                false,
                "differential-equations 0.7.0",
            ),
            |q: &mut [f64], v: &mut [f64], h: f64, f: &stepladder::scheme::Force<f64>| {
                glue::de_fresh_step(SymplecticIntegrator::velocity_verlet, q, v, h, f)
            },
        ),
        except(
            [Pass, Pass, Pass, Pass, Fail],
            "velocity Verlet as its table says on autonomous scenes; three full right-hand-side calls per step where the table's two kicks need two",
            &[(
                &[Evaluations],
                "source: step() calls `ode.diff` three times (velocity_verlet.rs:110, 124, 135), the one at l.124 only to read the velocity for the drift, and none in init; each call is followed by `evals.function += 1`, so the crate's own count is 3 too",
            )],
        ),
    ))
}

pub fn de_ruth_forest() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "differential-equations 0.7.0",
            method: "SymplecticIntegrator::ruth_forest",
            properties: const {
                &[
                    said(
                        Order,
                        "Ruth-Forest (4th Order Symplectic Integrator).",
                        "differential-equations-0.7.0/src/methods/symplectic/ruth_forest.rs:16",
                    ),
                    said(
                        Symplectic,
                        "Ruth-Forest (4th Order Symplectic Integrator).",
                        "differential-equations-0.7.0/src/methods/symplectic/ruth_forest.rs:16",
                    ),
                    unsaid(
                        Symmetric,
                        "not claimed; tested: yes, as the Forest-Ruth composition is palindromic",
                    ),
                    said(
                        Energy,
                        "Ideal for conservative physics and orbital mechanics where energy conservation over long periods is required.",
                        "differential-equations-0.7.0/src/methods/symplectic/ruth_forest.rs:18-19",
                    ),
                    unsaid(
                        Evaluations,
                        "not claimed (the crate's own counter reports what it spends); tested: 3, the nonzero kicks of its table d = (theta, 1 - 2 theta, theta, 0) (ruth_forest.rs:36)",
                    ),
                ]
            },
            minimum_evaluations: 3,
            test: "de_ruth_forest",
        },
        &BlackBox::new(
            claims(
                "de-ruth-forest",
                4,
                true,
                true,
                3,
                false,
                "differential-equations 0.7.0",
            ),
            |q: &mut [f64], v: &mut [f64], h: f64, f: &stepladder::scheme::Force<f64>| {
                glue::de_fresh_step(SymplecticIntegrator::ruth_forest, q, v, h, f)
            },
        ),
        except(
            [Pass, Pass, Pass, Pass, Fail],
            "Forest-Ruth as its table says on autonomous scenes; eight full right-hand-side calls per step where the table's three kicks need three",
            &[(
                &[Evaluations],
                "source: step() runs 4 passes, each calling `ode.diff` before the drift and again before the kick (ruth_forest.rs:108-121), 8 calls, the last kick (d4 = 0) included; each call is counted by `evals.function += 1`, so the crate's own count is 8 too",
            )],
        ),
    ))
}

pub fn de_rk4() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "differential-equations 0.7.0",
            method: "ExplicitRungeKutta::rk4",
            properties: const {
                &[
                    said(
                        Order,
                        "Creates the classical 4th order Runge-Kutta method.",
                        "differential-equations-0.7.0/src/methods/erk/fixed/mod.rs:74",
                    ),
                    RK_NOT_GEOMETRIC[0],
                    RK_NOT_GEOMETRIC[1],
                    RK_NOT_GEOMETRIC[2],
                    said(
                        Evaluations,
                        "- Number of stages: 4",
                        "differential-equations-0.7.0/src/tableau/runge_kutta.rs:14",
                    ),
                ]
            },
            minimum_evaluations: 4,
            test: "de_rk4",
        },
        &BlackBox::stateful(
            claims(
                "de-rk4",
                4,
                false,
                false,
                4,
                false,
                "differential-equations 0.7.0",
            ),
            || None,
            |kept, q: &mut [f64], v: &mut [f64], h: f64, f: &stepladder::scheme::Force<f64>| {
                // the crate stops a run after 10 000 steps unless told otherwise
                let make = |h| ExplicitRungeKutta::rk4(h).max_steps(usize::MAX);
                glue::de_step(make, kept, q, v, h, f)
            },
        ),
        holds(
            "Butcher-tree check of the tableau dumped through the crate's public constructor: order 4",
        ),
    ))
}

pub fn de_dopri5() -> Audit {
    Audit::Adaptive(audit_adaptive(
        Provenance {
            krate: "differential-equations 0.7.0",
            method: "ExplicitRungeKutta::dopri5",
            properties: const {
                &[
                    said(
                        Order,
                        "Creates the DOPRI5 method (5th order, 7 stages).",
                        "differential-equations-0.7.0/src/methods/erk/dormandprince/mod.rs:57",
                    ),
                    said(
                        Estimate,
                        "- Embedded order: 4 (for error estimation)",
                        "differential-equations-0.7.0/src/tableau/dorman_prince.rs:11",
                    ),
                    said_and(
                        Evaluations,
                        "Creates the DOPRI5 method (5th order, 7 stages).",
                        "differential-equations-0.7.0/src/methods/erk/dormandprince/mod.rs:57",
                        "7 stages; shown per accepted step from the crate's own count (Solution.evals.function), checked against the calls, not judged",
                    ),
                ]
            },
            minimum_evaluations: 6,
            test: "de_dopri5",
        },
        &AdaptiveBlackBox::new("de-dopri5", AdaptiveClaims::pair(5, 4), glue::de_dopri5),
        AdaptiveExpectation {
            verdict: Pass,
            first_order_estimate: false,
            why: "Butcher-tree check of the public tableau: 5(4)",
            evidence: &[],
        },
    ))
}

// ------------------------------------------------------------- ode_solvers

pub fn os_rk4() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "ode_solvers 0.6.2",
            method: "Rk4",
            properties: const {
                &[
                    said(
                        Order,
                        "Explicit Runge-Kutta method of order 4 with fixed step size.",
                        "ode_solvers-0.6.2/src/rk4.rs:1",
                    ),
                    RK_NOT_GEOMETRIC[0],
                    RK_NOT_GEOMETRIC[1],
                    RK_NOT_GEOMETRIC[2],
                    unsaid(
                        Evaluations,
                        "not claimed in the docs (its counter adds 4 a step, rk4.rs:92); tested: 4, the stages of the classical method",
                    ),
                ]
            },
            minimum_evaluations: 4,
            test: "os_rk4",
        },
        &BlackBox::new(
            claims(
                "ode_solvers-rk4",
                4,
                false,
                false,
                4,
                false,
                "ode_solvers 0.6.2",
            ),
            glue::os_rk4,
        ),
        holds("Butcher-tree check of the parsed tableau: order 4"),
    ))
}

pub fn os_dopri5() -> Audit {
    Audit::Adaptive(audit_adaptive(
        Provenance {
            krate: "ode_solvers 0.6.2",
            method: "Dopri5",
            properties: const {
                &[
                    said(
                        Order,
                        "Explicit Runge-Kutta method with Dormand-Prince coefficients of order 5(4) and dense output of order 4.",
                        "ode_solvers-0.6.2/src/dopri5.rs:1",
                    ),
                    said(
                        Estimate,
                        "| Dormand-Prince | Dopri5 | 5     | 4                    | 4                  |",
                        "ode_solvers-0.6.2/README.md:73",
                    ),
                    unsaid(
                        Evaluations,
                        "not claimed; shown per accepted step from the crate's own count (Stats.num_eval), checked against the calls, not judged",
                    ),
                ]
            },
            minimum_evaluations: 6,
            test: "os_dopri5",
        },
        &AdaptiveBlackBox::new(
            "ode_solvers-dopri5",
            AdaptiveClaims::pair(5, 4),
            |q: &mut [f64],
             v: &mut [f64],
             t0: f64,
             t1: f64,
             tol: f64,
             f: &stepladder::scheme::Force<f64>| {
                glue::os_pair(OsPair::Dopri5, q, v, t0, t1, tol, f)
            },
        ),
        AdaptiveExpectation {
            verdict: Pass,
            first_order_estimate: false,
            why: "Butcher-tree check: b order 5, b - e order 4, rows consistent",
            evidence: &[],
        },
    ))
}

pub fn os_dop853() -> Audit {
    Audit::Adaptive(audit_adaptive(
        Provenance {
            krate: "ode_solvers 0.6.2",
            method: "Dop853",
            properties: const {
                &[
                    said(
                        Order,
                        "Explicit Runge-Kutta method with Dormand-Prince coefficients of order 8(5,3) and dense output of order 7.",
                        "ode_solvers-0.6.2/src/dop853.rs:1",
                    ),
                    said(
                        Estimate,
                        "| Dormand-Prince | Dop853 | 8     | (5, 3)               | 7                  |",
                        "ode_solvers-0.6.2/README.md:74",
                    ),
                    unsaid(
                        Evaluations,
                        "not claimed; shown per accepted step from the crate's own count (Stats.num_eval), checked against the calls, not judged",
                    ),
                ]
            },
            minimum_evaluations: 12,
            test: "os_dop853",
        },
        // Hairer's estimate blends the 5th- and 3rd-order differences as
        // err5^2 / sqrt(err5^2 + 0.01 err3^2), ~ h^8 once err3 dominates and
        // ~ h^6 before (HNW I, II.10): the exponent moves between 8/6 and 1
        // along the ladder, so it is measured and not judged, as for
        // stepladder's own DOP853 peer
        &AdaptiveBlackBox::new(
            "ode_solvers-dop853",
            AdaptiveClaims {
                order: 8,
                estimate_power: 8,
                proportionality: None,
                symplectic: false,
                symmetric: false,
                error_factor: None,
            },
            |q: &mut [f64],
             v: &mut [f64],
             t0: f64,
             t1: f64,
             tol: f64,
             f: &stepladder::scheme::Force<f64>| {
                glue::os_pair(OsPair::Dop853, q, v, t0, t1, tol, f)
            },
        ),
        AdaptiveExpectation {
            verdict: Pass,
            first_order_estimate: false,
            why: "Butcher-tree check: b order 8, estimators 5 and 3; its defect (c12 = 0) needs time-dependent forces, which the autonomous scenes do not have",
            evidence: &[],
        },
    ))
}

// ---------------------------------------------------------------- peroxide

macro_rules! peroxide_fixed {
    ($fn:ident, $value:expr, $name:literal, $id:literal, $order:literal, $evals:literal, $props:expr, $expected:expr) => {
        pub fn $fn() -> Audit {
            Audit::Fixed(audit_fixed(
                Provenance {
                    krate: "peroxide 0.43.1",
                    method: $name,
                    properties: const { $props },
                    minimum_evaluations: $evals,
                    test: stringify!($fn),
                },
                &BlackBox::new(
                    claims($id, $order, false, false, $evals, false, "peroxide 0.43.1"),
                    |q: &mut [f64], v: &mut [f64], h: f64, f: &stepladder::scheme::Force<f64>| {
                        glue::px_step(&$value, q, v, h, f)
                    },
                ),
                $expected,
            ))
        }
    };
}

peroxide_fixed!(
    peroxide_rk4,
    RK4,
    "RK4",
    "peroxide-rk4",
    4,
    4,
    &[
        said(
            Order,
            "This integrator uses the classical 4th order Runge-Kutta method to numerically integrate the ODE system.",
            "peroxide-0.43.1/src/numerical/ode.rs:395"
        ),
        RK_NOT_GEOMETRIC[0],
        RK_NOT_GEOMETRIC[1],
        RK_NOT_GEOMETRIC[2],
        said(
            Evaluations,
            "It calculates four intermediate values (k1, k2, k3, k4) to estimate the next step solution.",
            "peroxide-0.43.1/src/numerical/ode.rs:396"
        ),
    ],
    holds("Butcher-tree check of the public consts C, A, BU: order 4")
);
peroxide_fixed!(
    peroxide_rals3,
    RALS3,
    "RALS3",
    "peroxide-rals3",
    3,
    3,
    &[
        said(
            Order,
            "Ralston's 3rd order integrator",
            "peroxide-0.43.1/src/numerical/ode.rs:374"
        ),
        RK_NOT_GEOMETRIC[0],
        RK_NOT_GEOMETRIC[1],
        RK_NOT_GEOMETRIC[2],
        unsaid(
            Evaluations,
            "not claimed; tested: 3, the stages of its tableau (C, A, BU at ode.rs:387-389)"
        ),
    ],
    holds("Butcher-tree check of the public consts: order 3")
);
peroxide_fixed!(
    peroxide_rals4,
    RALS4,
    "RALS4",
    "peroxide-rals4",
    4,
    4,
    &[
        said(
            Order,
            "This fourth order method is known as minimum truncation error RK4.",
            "peroxide-0.43.1/src/numerical/ode.rs:414"
        ),
        RK_NOT_GEOMETRIC[0],
        RK_NOT_GEOMETRIC[1],
        RK_NOT_GEOMETRIC[2],
        unsaid(
            Evaluations,
            "not claimed; tested: 4, the stages of its tableau (ode.rs:424-431)"
        ),
    ],
    except(
        [Fail, Pass, Pass, Pass, Pass],
        "two digit typos in A make the rows inconsistent: first order",
        &[(
            &[Order],
            "published a32 = 0.158575964 and a42 = -3.050965616 (ode.rs:428-429) leave c3 - (a31 + a32) = 1.84e-4 and 1 - (a41 + a42 + a43) = 4.6e-7; with c the row sums of A (what an autonomous problem sees) the order-2 condition sum b c = 1/2 fails by -2.2e-4 (by -4.9e-9 with the published C): order 1; the crate's RALS4 on q'' = -q, (q, v)(0) = (1, 0), to T = 1, halves its error with each halving of h from h = 1/16 to 1/1024 (reproduce both: `cargo test --release --test independent peroxide_rals4 -- --nocapture`)",
        )]
    )
    .naming(
        "sum b_i c_i = 1/2",
        bushy_defect(RALS4::A, RALS4::BU, 1),
        "the public consts A and BU, c the row sums of A"
    )
);
peroxide_fixed!(
    peroxide_rk5,
    RK5,
    "RK5",
    "peroxide-rk5",
    5,
    7,
    &[
        said(
            Order,
            "This integrator uses the 5th order Runge-Kutta method to numerically integrate the ODE system.",
            "peroxide-0.43.1/src/numerical/ode.rs:437"
        ),
        RK_NOT_GEOMETRIC[0],
        RK_NOT_GEOMETRIC[1],
        RK_NOT_GEOMETRIC[2],
        unsaid(
            Evaluations,
            "not claimed; tested: 7, the stages of its tableau (ode.rs:447-484)"
        ),
    ],
    except(
        [Fail, Pass, Pass, Pass, Pass],
        "Dormand-Prince's A with its 4th-order weights: order 4",
        &[(
            &[Order],
            "BU (ode.rs:475-483) = (5179/57600, 0, 7571/16695, 393/640, -92097/339200, 187/2100, 1/40), Dormand-Prince's embedded 4th-order weights: the order-5 condition sum b c^4 = 1/5 fails by -2.6e-4 while those of order 1 to 4 for the bushy trees hold to round-off (reproduce: `cargo test --release --test independent peroxide_rk5 -- --nocapture`)",
        )]
    )
    .naming(
        "sum b_i c_i^4 = 1/5",
        bushy_defect(RK5::A, RK5::BU, 4),
        "the public consts A and BU, c the row sums of A"
    )
);

/// GL4's own iteration tolerance is set near round-off (absolute 1e-14 on
/// the stage derivatives, up to 200 sweeps) so the order ladder measures
/// the method and not the default 1e-8 floor of its iteration.
const GL4_TOLERANCE: f64 = 1e-14;
const GL4_SWEEPS: usize = 200;

pub fn peroxide_gl4_fixed_point() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "peroxide 0.43.1",
            method: "GL4 (ImplicitSolver::FixedPoint, the default)",
            properties: const {
                &[
                    said(
                        Order,
                        "Gauss-Legendre 4th order integrator.",
                        "peroxide-0.43.1/src/numerical/ode.rs:1200",
                    ),
                    GL4_NOT_CLAIMED[0],
                    GL4_NOT_CLAIMED[1],
                    GL4_NOT_CLAIMED[2],
                    GL4_NOT_CLAIMED[3],
                ]
            },
            minimum_evaluations: 2,
            test: "peroxide_gl4_fixed_point",
        },
        &BlackBox::new(
            claims(
                "peroxide-gl4-fixed-point",
                4,
                true,
                true,
                2,
                true,
                "peroxide 0.43.1",
            ),
            |q: &mut [f64], v: &mut [f64], h: f64, f: &stepladder::scheme::Force<f64>| {
                glue::px_step(
                    &GL4::new(ImplicitSolver::FixedPoint, GL4_TOLERANCE, GL4_SWEEPS),
                    q,
                    v,
                    h,
                    f,
                )
            },
        ),
        // evaluations: an implicit black box that reports no solves makes no
        // count to check (its iterations are its own): not claimed
        except(
            [Fail, Fail, Fail, Fail, NotClaimed],
            "stage 2 is formed with row 1 of A: a one-stage theta-method with theta = c1 = 0.211, first order, neither symplectic nor symmetric",
            &[
                (
                    &[Order],
                    "ode.rs:1269-1270 forms y2 = y + dt (A11 k1 + A12 k2) (row 1 again; the Broyden residual at ode.rs:1406-1407 uses A21, A22); the crate's step on q'' = -q, (q, v)(0) = (1, 0), to T = 1, at iteration tolerance 1e-14, halves its error with each halving of h from h = 1/16 to 1/256 (reproduce: `cargo test --release --test independent peroxide_gl4_fixed_point -- --nocapture`)",
                ),
                (
                    &[Symplectic, Symmetric, Energy],
                    "both stages then share y + c1 h k: the theta-method with theta = c1 = 1/2 - sqrt(3)/6 = 0.211, whose map on q'' = -q has determinant (1 + (1 - theta)^2 h^2) / (1 + theta^2 h^2), not 1, and is not its own adjoint (theta != 1/2); the crate's one-step map has that determinant, 1.005771 at h = 0.1 (same test)",
                ),
            ],
        )
        .naming(
            "sum b_i c_i = 1/2",
            -(3f64.sqrt()) / 6.0,
            "the theta-method's sum b c = theta = 1/2 - sqrt(3)/6"
        ),
    ))
}

pub fn peroxide_gl4_broyden() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "peroxide 0.43.1",
            method: "GL4 (ImplicitSolver::Broyden)",
            properties: const {
                &[
                    said(
                        Order,
                        "Gauss-Legendre 4th order integrator.",
                        "peroxide-0.43.1/src/numerical/ode.rs:1200",
                    ),
                    GL4_NOT_CLAIMED[0],
                    GL4_NOT_CLAIMED[1],
                    GL4_NOT_CLAIMED[2],
                    GL4_NOT_CLAIMED[3],
                ]
            },
            minimum_evaluations: 2,
            test: "peroxide_gl4_broyden",
        },
        &BlackBox::new(
            claims(
                "peroxide-gl4-broyden",
                4,
                true,
                true,
                2,
                true,
                "peroxide 0.43.1",
            ),
            |q: &mut [f64], v: &mut [f64], h: f64, f: &stepladder::scheme::Force<f64>| {
                glue::px_step(
                    &GL4::new(ImplicitSolver::Broyden, GL4_TOLERANCE, GL4_SWEEPS),
                    q,
                    v,
                    h,
                    f,
                )
            },
        ),
        FixedExpectation {
            // the ladder on the oscillator reaches errors of 1e-13, where the
            // solve's departures dominate; on the Kepler orbit its errors stay
            // far above them (order, energy), while symplecticity and time
            // symmetry are judged at round-off and see them on both scenes
            harmonic: [Fail, Fail, Fail, Fail, NotClaimed],
            kepler: [Pass, Fail, Fail, Pass, NotClaimed],
            why: "the Broyden iteration stops on an absolute test |delta . J_inv dF| < 1e-12 (ode.rs:1325), a quantity ~ |delta|^2, i.e. while the update is still ~1e-6 and the residual far above the requested 1e-14: the step is Gauss-Legendre only to ~1e-10 (the residual uses the full A, ode.rs:1406-1407, so the method itself is right); an implicit black box's count is shown, not judged",
            evidence: &[(
                &[Order, Symplectic, Symmetric, Energy],
                "compared step by step with the exact GL4 map of q'' = -q (the (2,2) Pade approximant R(z) = (1 + z/2 + z^2/12)/(1 - z/2 + z^2/12)), from (q, v) = (1, 0) to T = 1 at iteration tolerance 1e-14, the crate's step departs from it by up to 1.5e-10 at h = 1/16, 9.7e-12 at 1/64, 5.0e-16 at 1/512 and 3.8e-14 at 1/1024, irregularly, as the calls per step fall from 11 to 9 to 7 (fewer iterations); its error at T = 1 is 6.5x GL4's at h = 1/64; at h = 1/1024 it is 3.9e-11, 317x the GL4 map iterated in doubles (1.2e-13, round-off: GL4's own truncation error there, h^4 T / 720 in phase, is 1.26e-15) and 3.1e4x that truncation error (reproduce: `cargo test --release --test independent peroxide_gl4_broyden -- --nocapture`)",
            ), (
                &[Order],
                "under a weak force the solve stops before the stages feel each other: one step of h = 0.9 on q'' = c q from (q, v) = (1, 0) has no part quadratic in c at all, (q1(c) + q1(-c) - 2 q1(0)) / (2 c^2) = 0 exactly at c = 1.4e-4 and 1e-3, where the GL4 map's is h^4/24 = 2.73e-2 (the crate's is that from c = 1e-2 on): the chain condition sum b_bar_i a_bar_ij = 1/24, which that part measures, fails by -1/24 under such forces (reproduce: `cargo test --release --test independent peroxide_gl4_broyden_weak_force -- --nocapture`)",
            )],
            named: None,
        }
        .naming(
            "sum b_bar_i a_bar_ij = 1/24",
            -1.0 / 24.0,
            "no part quadratic in c on q'' = c q for |c| <= 1e-3, independent.rs"
        ),
    ))
}

/// A peroxide adaptive pair as its doc suggests building it:
/// `new(tol, safety 0.9, min step, max step, max_step_iter)`; the min step
/// 0 and max step 1 leave the controller free, `max_step_iter = 1` turns a
/// rejection into an error the driver in [`glue::px_adaptive`] handles.
pub fn peroxide_dp45() -> Audit {
    Audit::Adaptive(audit_adaptive(
        Provenance {
            krate: "peroxide 0.43.1",
            method: "DP45",
            properties: const {
                &[
                    said(
                        Order,
                        "This is an adaptive step size integrator based on a 5th order Runge-Kutta method with 4th order embedded error estimation.",
                        "peroxide-0.43.1/src/numerical/ode.rs:685-686",
                    ),
                    said(
                        Estimate,
                        "This is an adaptive step size integrator based on a 5th order Runge-Kutta method with 4th order embedded error estimation.",
                        "peroxide-0.43.1/src/numerical/ode.rs:685-686",
                    ),
                    unsaid(
                        Evaluations,
                        "not claimed, not reported by the crate; shown per accepted step (7: no first-same-as-last reuse), not judged",
                    ),
                ]
            },
            minimum_evaluations: 6,
            test: "peroxide_dp45",
        },
        &AdaptiveBlackBox::new(
            "peroxide-dp45",
            AdaptiveClaims::pair(5, 4),
            |q: &mut [f64],
             v: &mut [f64],
             t0: f64,
             t1: f64,
             tol: f64,
             f: &stepladder::scheme::Force<f64>| {
                glue::px_adaptive(|tol| DP45::new(tol, 0.9, 0.0, 1.0, 1), q, v, t0, t1, tol, f)
            },
        ),
        AdaptiveExpectation {
            verdict: Pass,
            first_order_estimate: false,
            why: "Butcher-tree check of the public consts: BU order 5, BE order 4",
            evidence: &[],
        },
    ))
}

pub fn peroxide_tsit45() -> Audit {
    Audit::Adaptive(audit_adaptive(
        Provenance {
            krate: "peroxide 0.43.1",
            method: "TSIT45",
            properties: const {
                &[
                    said(
                        Order,
                        "This is an adaptive step size integrator based on a 5th order Runge-Kutta method with 4th order embedded error estimation, using the coefficients from Tsitouras (2011).",
                        "peroxide-0.43.1/src/numerical/ode.rs:806-807",
                    ),
                    said(
                        Estimate,
                        "This is an adaptive step size integrator based on a 5th order Runge-Kutta method with 4th order embedded error estimation, using the coefficients from Tsitouras (2011).",
                        "peroxide-0.43.1/src/numerical/ode.rs:806-807",
                    ),
                    unsaid(
                        Evaluations,
                        "not claimed, not reported by the crate; shown per accepted step, not judged",
                    ),
                ]
            },
            minimum_evaluations: 6,
            test: "peroxide_tsit45",
        },
        &AdaptiveBlackBox::new(
            "peroxide-tsit45",
            AdaptiveClaims::pair(5, 4),
            |q: &mut [f64],
             v: &mut [f64],
             t0: f64,
             t1: f64,
             tol: f64,
             f: &stepladder::scheme::Force<f64>| {
                glue::px_adaptive(
                    |tol| TSIT45::new(tol, 0.9, 0.0, 1.0, 1),
                    q,
                    v,
                    t0,
                    t1,
                    tol,
                    f,
                )
            },
        ),
        // the ladder cannot fit an exponent: with steps ~ TOL/|f| the
        // fifth-order solution's error is near round-off at every tolerance
        // the runs reach, and from 1e-5 on they exceed the step limit; the
        // step growth between the loosest tolerances shows the estimate
        AdaptiveExpectation {
            verdict: Inconclusive,
            first_order_estimate: true,
            why: "the error weights BU - BE sum to 0.97, not 0: the estimate is ~0.97 h |f|, O(h), so steps grow like 1/TOL",
            evidence: &[(
                &[Estimate],
                "BE (ode.rs:909-917) is minus Tsitouras' b - b_hat in six entries and the same sign in the last; sum BU = 1 and sum BE = 0.0303, so the error weights BU - BE sum to 0.9697 where an estimate of any order needs 0: it is ~ 0.97 h f, first order in h (reproduce: `cargo test --release --test independent peroxide_tsit45 -- --nocapture`); the steps' growth with 1/TOL is in the table (s)",
            )],
        },
    ))
}

// ------------------------------------------------------------- russell_ode

pub fn russell_rk4() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "russell_ode 5.0.0",
            method: "Method::Rk4 (h_equal)",
            properties: const {
                &[
                    said(
                        Order,
                        "\"The\" Runge-Kutta method (explicit, order 4)",
                        "russell_ode-5.0.0/src/enums.rs:82",
                    ),
                    RK_NOT_GEOMETRIC[0],
                    RK_NOT_GEOMETRIC[1],
                    RK_NOT_GEOMETRIC[2],
                    unsaid(
                        Evaluations,
                        "not claimed; tested: 4, the stages of the classical method its doc cites (HNW I p. 138, enums.rs:84); the crate's own step is counted in `cargo test --release --test independent russell_equal_steps`",
                    ),
                ]
            },
            minimum_evaluations: 4,
            test: "russell_rk4",
        },
        &BlackBox::new(
            claims(
                "russell-rk4",
                4,
                false,
                false,
                4,
                false,
                "russell_ode 5.0.0",
            ),
            glue::russell_rk4,
        ),
        holds("Butcher-tree check of the parsed tableau: order 4"),
    ))
}

pub fn russell_dopri5() -> Audit {
    Audit::Adaptive(audit_adaptive(
        Provenance {
            krate: "russell_ode 5.0.0",
            method: "Method::DoPri5",
            properties: const {
                &[
                    said(
                        Order,
                        "Dormand-Prince method (explicit, order 5(4), embedded)",
                        "russell_ode-5.0.0/src/enums.rs:113",
                    ),
                    said(
                        Estimate,
                        "For DoPri5(4): q = 4 = min(order(y1), order(y1bar))",
                        "russell_ode-5.0.0/src/enums.rs:9",
                    ),
                    said_and(
                        Evaluations,
                        "Method::DoPri5     => Information { order: 5, order_of_estimator: 4, implicit: false, embedded: true,  multiple_stages: true,  first_step_same_as_last: true  },",
                        "russell_ode-5.0.0/src/enums.rs:145",
                        "first same as last: 6 per step; shown per accepted step from the crate's own count (Stats.n_function), checked against the calls, not judged",
                    ),
                ]
            },
            minimum_evaluations: 6,
            test: "russell_dopri5",
        },
        &AdaptiveBlackBox::new(
            "russell-dopri5",
            AdaptiveClaims::pair(5, 4),
            glue::russell_dopri5,
        ),
        AdaptiveExpectation {
            verdict: Pass,
            first_order_estimate: false,
            why: "Butcher-tree check of the parsed tableau: 5(4)",
            evidence: &[],
        },
    ))
}

// ------------------------------------------------------------------- brahe

/// What brahe says of its RKN12(10), for both ways it is audited.
const BRAHE_ORDER: Property = said(
    Order,
    "12th order accurate solution with 10th order embedded error estimate",
    "brahe-1.8.1/src/integrators/rkn1210.rs:47",
);

/// RKN12(10) is an explicit Runge-Kutta-Nystrom pair: neither symplectic
/// nor symmetric in theory, and its energy may drift.
const RKN_NOT_GEOMETRIC: [Property; 3] = [
    unsaid(
        Symplectic,
        "explicit Runge-Kutta-Nystrom: not symplectic in theory (tested: no)",
    ),
    unsaid(
        Symmetric,
        "explicit Runge-Kutta-Nystrom: not symmetric in theory (tested: no)",
    ),
    unsaid(
        Energy,
        "tested: drift allowed, as for a scheme neither symplectic nor symmetric",
    ),
];

/// brahe's RKN12(10) as a fixed-step method: one `step` at the `h` given,
/// with tolerances so wide that no attempt is rejected (see the glue).
pub fn brahe_rkn1210_fixed() -> Audit {
    Audit::Fixed(audit_fixed(
        Provenance {
            krate: "brahe 1.8.1",
            method: "RKN1210SIntegrator, every step accepted",
            properties: const {
                &[
                    BRAHE_ORDER,
                    RKN_NOT_GEOMETRIC[0],
                    RKN_NOT_GEOMETRIC[1],
                    RKN_NOT_GEOMETRIC[2],
                    said(
                        Evaluations,
                        "17 function evaluations per step",
                        "brahe-1.8.1/src/integrators/rkn1210.rs:46",
                    ),
                ]
            },
            minimum_evaluations: 17,
            test: "brahe_rkn1210_fixed",
        },
        &brahe_rkn1210_step(),
        // the order is the harness's limit, not the crate's: see `why`
        except(
            [Inconclusive, Pass, Pass, Pass, Pass],
            "twelfth order is past what a fixed-step ladder in doubles resolves on these scenes: a settled local order needs two halvings, 2^24 in error, and the error goes from its pre-asymptotic range to the round-off floor in about one (stepladder's own DPRKN12 table, the same tableau, is inconclusive on the same ladders, with the same local orders on the Kepler orbit); called directly, brahe's step shows order 12.2 on the oscillator and 17 calls a step (tests/independent.rs, brahe_rkn1210)",
            &[],
        ),
    ))
}

/// brahe's step as a fixed-step black box: one `step` of RKN1210 at the
/// `h` given, every step accepted (see the glue).
pub(crate) fn brahe_rkn1210_step() -> BlackBox<f64, stepladder::scheme::StepFn<f64>> {
    BlackBox::new(
        claims("brahe-rkn1210", 12, false, false, 17, false, "brahe 1.8.1"),
        glue::brahe_rkn1210_step,
    )
}

/// brahe's RKN12(10) under its own step control, driven to the end time
/// by the glue the way the crate leaves it to its caller.
pub fn brahe_rkn1210() -> Audit {
    Audit::Adaptive(audit_adaptive(
        Provenance {
            krate: "brahe 1.8.1",
            method: "RKN1210SIntegrator",
            properties: const {
                &[
                    BRAHE_ORDER,
                    said(
                        Estimate,
                        "12th order accurate solution with 10th order embedded error estimate",
                        "brahe-1.8.1/src/integrators/rkn1210.rs:47",
                    ),
                    unsaid(
                        Evaluations,
                        "17 per attempt (rkn1210.rs:46); shown per accepted step from the calls counted, rejected attempts included, not judged",
                    ),
                ]
            },
            minimum_evaluations: 17,
            test: "brahe_rkn1210",
        },
        // an estimate from a tenth-order solution behaves like h^11; brahe
        // grows accepted steps by (1/err)^(1/12) (rkn1210.rs, "uses 12th
        // order for accept"), which changes the error it settles at by a
        // constant factor, not the exponent 12/11
        &AdaptiveBlackBox::new(
            "brahe-rkn1210",
            AdaptiveClaims::pair(12, 10),
            glue::brahe_rkn1210,
        ),
        AdaptiveExpectation {
            verdict: Pass,
            first_order_estimate: false,
            why: "the published 12(10) pair with an error-per-step controller: global error ~ TOL^(12/11)",
            evidence: &[],
        },
    ))
}

/// An audited method: its test name and the function that audits it.
pub type Entry = (&'static str, fn() -> Audit);

/// Every audited method, by test name.
pub const ALL: &[Entry] = &[
    ("utsuroi_stormer_verlet", utsuroi_stormer_verlet),
    ("utsuroi_yoshida4", utsuroi_yoshida4),
    ("utsuroi_yoshida6", utsuroi_yoshida6),
    ("utsuroi_yoshida8", utsuroi_yoshida8),
    ("utsuroi_rk4", utsuroi_rk4),
    ("utsuroi_dormand_prince", utsuroi_dormand_prince),
    ("de_velocity_verlet", de_velocity_verlet),
    ("de_ruth_forest", de_ruth_forest),
    ("de_rk4", de_rk4),
    ("de_dopri5", de_dopri5),
    ("os_rk4", os_rk4),
    ("os_dopri5", os_dopri5),
    ("os_dop853", os_dop853),
    ("peroxide_rk4", peroxide_rk4),
    ("peroxide_rals3", peroxide_rals3),
    ("peroxide_rals4", peroxide_rals4),
    ("peroxide_rk5", peroxide_rk5),
    ("peroxide_gl4_fixed_point", peroxide_gl4_fixed_point),
    ("peroxide_gl4_broyden", peroxide_gl4_broyden),
    ("peroxide_dp45", peroxide_dp45),
    ("peroxide_tsit45", peroxide_tsit45),
    ("russell_rk4", russell_rk4),
    ("russell_dopri5", russell_dopri5),
    ("brahe_rkn1210_fixed", brahe_rkn1210_fixed),
    ("brahe_rkn1210", brahe_rkn1210),
];
