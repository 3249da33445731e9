//! Runge-Kutta-Nystrom splittings: drift/kick sequences whose weights are
//! fitted to `q'' = a(q)` rather than to any two non-commuting flows.
//!
//! Why they can do better than compositions of Verlet. Write the drift
//! `q += c h v` as `exp(c h A)` and the kick `v += c h a(q)` as `exp(c h B)`.
//! The kick's field depends on `q` alone and the drift's is linear in `v`, so
//! `[B, [B, [B, A]]]` is a field that differentiates the force three times
//! along velocities that do not move under kicks: it vanishes for every force
//! (Hairer, Lubich, Wanner, Geometric Numerical Integration, 2006, III.3.2).
//! The order conditions attached to that bracket, and to every bracket built
//! on it, drop out: fewer conditions at the same order, so the free weights go
//! into shrinking the leading error terms (McLachlan & Atela 1992; McLachlan
//! 1995). The price is that such a table may have its order only for
//! `q'' = a(q)`: it is marked with [`SplittingTable::only_for_nystrom`] when
//! a generic splitting of two flows would not reach the claimed order.
//!
//! The layout of each table (which weights are kicks, which flow comes
//! first) is the one with the claimed order and the published error:
//! exchanging kicks and drifts costs McLachlan-Atela an order and nearly
//! triples the fifth-order error of SB3A. Every weight is the double nearest
//! to an exact solution of the Nystrom order conditions, found from the
//! published digits by Newton iteration in 60-digit arithmetic
//! (`tests/refine_nystrom_coefficients.py`).

use super::SchemeMeta;
use super::splitting::{Flow, SplittingTable};

/// McLachlan's `SB3A` method with four force evaluations: five drifts and
/// four kicks, drift first,
/// `D(a1) K(b1) D(a2) K(b2) D(a3) K(b2) D(a2) K(b1) D(a1)` with
/// `b1 = 1`, `b2 = -1/2`, `a3 = 2/3`.
///
/// Fourth order for any splitting (symmetric, with the `h^3` conditions
/// met); its free weight removes the fifth-order error terms that survive
/// `[B, [B, [B, A]]] = 0` as far as four stages allow. The published 20
/// digits satisfy the order conditions to 2e-22: each weight is the double
/// nearest to its published value.
pub const MCLACHLAN_SB3A4: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "mclachlan-sb3a4",
        name: "McLachlan SB3A, 4 stages (Runge-Kutta-Nystrom)",
        order: 4,
        symplectic: true,
        symmetric: true,
        reference: "R. I. McLachlan, SIAM J. Sci. Comput. 16, 151 (1995), SB3A with four stages",
        phase_error: None,    // measured only: no hand-derived leading term
        force_evaluations: 0, // derived by `new`
        implicit: false,
    },
    Flow::Drift,
    &[sb3a4::A1, sb3a4::A2, sb3a4::A3, sb3a4::A2, sb3a4::A1],
    &[sb3a4::B1, sb3a4::B2, sb3a4::B2, sb3a4::B1],
);

/// Published `a1 = 0.18819521776883821787`, `a2 = -0.021528551102171551201`,
/// `a3 = 1 - 2 (a1 + a2) = 2/3`, `b1 = 1`, `b2 = -1/2`.
mod sb3a4 {
    pub const A1: f64 = 0.1881952177688382;
    pub const A2: f64 = -0.021528551102171552;
    pub const A3: f64 = 0.6666666666666666;
    pub const B1: f64 = 1.0;
    pub const B2: f64 = -0.5;
}

/// McLachlan and Atela's optimal fourth-order method for a quadratic kinetic
/// energy: four kicks and four drifts, kick first,
/// `K(b1) D(a1) K(b2) D(a2) K(b3) D(a3) K(b4) D(a4)`, four force evaluations
/// per step. Not symmetric (so no reused acceleration), but the fewest
/// stages for order 4 here.
///
/// Fourth order only for `q'' = a(q)`: a generic splitting needs eight
/// conditions at that order, `q'' = a(q)` seven, and the eighth weight
/// minimises the fifth-order error terms. The published 19 digits satisfy
/// the order conditions to 3e-20 and are within 7e-20 of the exact solution:
/// each weight is the double nearest to its published value.
pub const MCLACHLAN_ATELA4: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "mclachlan-atela4",
        name: "McLachlan-Atela optimal fourth order (4 stages, Runge-Kutta-Nystrom)",
        order: 4,
        symplectic: true,
        symmetric: false,
        reference: "R. I. McLachlan, P. Atela, Nonlinearity 5, 541 (1992), Table 2, optimal fourth-order method",
        phase_error: None,    // measured only: no hand-derived leading term
        force_evaluations: 0, // derived by `new`
        implicit: false,
    },
    Flow::Kick,
    &[
        mclachlan_atela4::A1,
        mclachlan_atela4::A2,
        mclachlan_atela4::A3,
        mclachlan_atela4::A4,
    ],
    &[
        mclachlan_atela4::B1,
        mclachlan_atela4::B2,
        mclachlan_atela4::B3,
        mclachlan_atela4::B4,
    ],
)
.only_for_nystrom();

/// Published `a1 = 0.5153528374311229364`, `a2 = -0.085782019412973646`,
/// `a3 = 0.4415830236164665242`, `a4 = 0.1288461583653841854`,
/// `b1 = 0.1344961992774310892`, `b2 = -0.2248198030794208058`,
/// `b3 = 0.7563200005156682911`, `b4 = 0.3340036032863214255`.
mod mclachlan_atela4 {
    pub const A1: f64 = 0.5153528374311229;
    pub const A2: f64 = -0.08578201941297364;
    pub const A3: f64 = 0.4415830236164665;
    pub const A4: f64 = 0.12884615836538418;
    pub const B1: f64 = 0.1344961992774311;
    pub const B2: f64 = -0.22481980307942082;
    pub const B3: f64 = 0.7563200005156683;
    pub const B4: f64 = 0.33400360328632145;
}

/// McLachlan's `SB3A` method with five force evaluations: six drifts and
/// five kicks, drift first,
/// `D(a1) K(b1) D(a2) K(b2) D(a3) K(b3) D(a3) K(b2) D(a2) K(b1) D(a1)` with
/// `b1 = -3/73`, `b2 = 17/59`.
///
/// Fourth order for any splitting; one stage more than the four-stage
/// `SB3A` buys a fifth-order error for `q'' = a(q)` five times smaller. The
/// published 20 digits satisfy the order conditions to 2e-21: each weight is
/// the double nearest to its published value.
pub const MCLACHLAN_SB3A5: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "mclachlan-sb3a5",
        name: "McLachlan SB3A, 5 stages (Runge-Kutta-Nystrom)",
        order: 4,
        symplectic: true,
        symmetric: true,
        reference: "R. I. McLachlan, SIAM J. Sci. Comput. 16, 151 (1995), SB3A with five stages",
        phase_error: None,    // measured only: no hand-derived leading term
        force_evaluations: 0, // derived by `new`
        implicit: false,
    },
    Flow::Drift,
    &[
        sb3a5::A1,
        sb3a5::A2,
        sb3a5::A3,
        sb3a5::A3,
        sb3a5::A2,
        sb3a5::A1,
    ],
    &[sb3a5::B1, sb3a5::B2, sb3a5::B3, sb3a5::B2, sb3a5::B1],
);

/// Published `a1 = 0.4051886183952522772`, `a2 = -0.2871440408165240890`,
/// `a3 = 1/2 - (a1 + a2) = 0.3819554224212718118`,
/// `b1 = -0.041095890410958904110`, `b2 = 0.28813559322033898305`,
/// `b3 = 1 - 2 (b1 + b2) = 0.50592059438123984212`.
mod sb3a5 {
    pub const A1: f64 = 0.4051886183952523;
    pub const A2: f64 = -0.2871440408165241;
    pub const A3: f64 = 0.3819554224212718;
    pub const B1: f64 = -0.0410958904109589;
    pub const B2: f64 = 0.288135593220339;
    pub const B3: f64 = 0.5059205943812398;
}

/// Blanes and Moan's sixth-order symmetric Runge-Kutta-Nystrom splitting
/// `SRKN_11^b`: twelve kicks and eleven drifts, kick first,
/// `K(b1) D(a1) ... K(b6) D(a6) K(b6) ... D(a1) K(b1)`; the last kick and the
/// next step's first share one force evaluation, so eleven per step.
///
/// Sixth order only for `q'' = a(q)`: of the conditions of a generic
/// symmetric splitting at `h^5`, two belong to brackets that vanish here,
/// and the weights they would have fixed go into the `h^7` error terms:
/// measured, it reaches a global error of 1e-9 with 2.3 (circular orbit) to
/// 3.8 (oscillator) times fewer force evaluations than Yoshida's sixth
/// order, a global error 140 to 3000 times smaller at equal force
/// evaluations. The published 15 digits satisfy the order
/// conditions to 8e-18; the weights below are the doubles nearest to the
/// exact solution nearest to them (they move by at most 6.1e-16).
pub const BLANES_MOAN_SRKN11: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "blanes-moan-srkn11b",
        name: "Blanes-Moan SRKN_11^b, sixth order (Runge-Kutta-Nystrom)",
        order: 6,
        symplectic: true,
        symmetric: true,
        reference: "S. Blanes, P. C. Moan, J. Comput. Appl. Math. 142, 313 (2002), Table 3, SRKN_11^b",
        phase_error: None,    // measured only: no hand-derived leading term
        force_evaluations: 0, // derived by `new`
        implicit: false,
    },
    Flow::Kick,
    &[
        srkn11b::A1,
        srkn11b::A2,
        srkn11b::A3,
        srkn11b::A4,
        srkn11b::A5,
        srkn11b::A6,
        srkn11b::A5,
        srkn11b::A4,
        srkn11b::A3,
        srkn11b::A2,
        srkn11b::A1,
    ],
    &[
        srkn11b::B1,
        srkn11b::B2,
        srkn11b::B3,
        srkn11b::B4,
        srkn11b::B5,
        srkn11b::B6,
        srkn11b::B6,
        srkn11b::B5,
        srkn11b::B4,
        srkn11b::B3,
        srkn11b::B2,
        srkn11b::B1,
    ],
)
.only_for_nystrom();

/// Published `b1 = 0.0414649985182624`, `b2 = 0.198128671918067`,
/// `b3 = -0.0400061921041533`, `b4 = 0.0752539843015807`,
/// `b5 = -0.0115113874206879`, `b6 = 1/2 - (b1 + ... + b5)`,
/// `a1 = 0.123229775946271`, `a2 = 0.290553797799558`,
/// `a3 = -0.127049212625417`, `a4 = -0.246331761062075`,
/// `a5 = 0.357208872795928`, `a6 = 1 - 2 (a1 + ... + a5)`.
mod srkn11b {
    pub const A1: f64 = 0.12322977594627116;
    pub const A2: f64 = 0.29055379779955826;
    pub const A3: f64 = -0.1270492126254169;
    pub const A4: f64 = -0.2463317610620754;
    pub const A5: f64 = 0.3572088727959278;
    pub const A6: f64 = 0.20477705429147028;
    pub const B1: f64 = 0.041464998518262845;
    pub const B2: f64 = 0.19812867191806655;
    pub const B3: f64 = -0.04000619210415269;
    pub const B4: f64 = 0.07525398430158034;
    pub const B5: f64 = -0.01151138742068777;
    pub const B6: f64 = 0.23666992478693072;
}
