//! Composition methods as data: velocity Verlet, a symmetric second-order
//! step, taken with the step sizes `w_1 h, ..., w_s h` in turn.
//!
//! Why this raises the order (Yoshida 1990; Hairer, Lubich & Wanner,
//! Geometric Numerical Integration, 2006, II.4 and V.3): a symmetric step is
//! the exact flow of a modified vector field, `exp(h X1 + h^3 X3 + h^5 X5 + ...)`
//! with odd powers only, since stepping with `-h` must undo it. By the
//! Baker-Campbell-Hausdorff formula the composition is
//! `exp(h (sum w) X1 + h^3 (sum w^3) X3 + h^5 (sum w^5 X5 + commutators) + ...)`,
//! and weights that cancel every term but `h X1` up to `h^p` give order `p`. A
//! palindromic weight sequence keeps the composition symmetric, which cancels
//! the even powers for free.
//!
//! Each Verlet step is kick `w/2`, drift `w`, kick `w/2`; adjacent half kicks
//! merge, so the composition is the splitting
//! `K(w_1/2) D(w_1) K((w_1+w_2)/2) D(w_2) ... D(w_s) K(w_s/2)`, built at compile
//! time by [`VerletComposition::new`] and run by the generic drift/kick stepper
//! with `s` force evaluations per step (the last kick's acceleration is the
//! next step's first).
//!
//! Every weight is the double nearest to an exact solution of the order
//! conditions: published digits are refined by Newton iteration on those
//! conditions in 60-digit arithmetic (`tests/refine_coefficients.py`), and
//! `tests/order_conditions.rs` checks them independently to round-off.

use super::SchemeMeta;
use super::splitting::{Flow, SplittingTable};

/// Velocity Verlet composed with the weights `w_1..w_S`, together with the
/// kick weights of the equivalent splitting, all compile-time constants.
///
/// `K` must be `S + 1`; a mismatch fails when the constant is evaluated, so it
/// does not compile.
///
/// ```
/// use stepladder::scheme::VerletComposition;
/// const TWO_HALVES: VerletComposition<2, 3> = VerletComposition::new([0.5, 0.5]);
/// assert_eq!(TWO_HALVES.kicks, [0.25, 0.5, 0.25]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VerletComposition<const S: usize, const K: usize> {
    /// The weights `w_i`, which are the splitting's drift weights.
    pub weights: [f64; S],
    /// The kick weights `w_1/2, (w_1+w_2)/2, ..., (w_(S-1)+w_S)/2, w_S/2`.
    pub kicks: [f64; K],
}

impl<const S: usize, const K: usize> VerletComposition<S, K> {
    /// The composition with these weights, its half kicks merged.
    pub const fn new(weights: [f64; S]) -> Self {
        assert!(
            S >= 1 && K == S + 1,
            "a composition of S Verlet steps has S + 1 kicks"
        );
        let mut kicks = [0.0; K];
        kicks[0] = 0.5 * weights[0];
        let mut i = 1;
        while i < S {
            // (a + b) / 2 rounds once, like a/2 + b/2: a palindrome stays one
            kicks[i] = 0.5 * (weights[i - 1] + weights[i]);
            i += 1;
        }
        kicks[S] = 0.5 * weights[S - 1];
        Self { weights, kicks }
    }

    /// The splitting table that runs this composition, with `meta`'s
    /// `force_evaluations` derived from the weights (`S` per step).
    pub const fn table(&'static self, meta: SchemeMeta) -> SplittingTable {
        let table = SplittingTable::new(meta, Flow::Kick, &self.weights, &self.kicks);
        SplittingTable {
            composition: Some(&self.weights),
            ..table
        }
    }
}

/// The triple jump `w_1 = w_3 = 1/(2 - 2^(1/3))`, `w_2 = 1 - 2 w_1`: the
/// fourth-order Forest-Ruth method, found independently by Yoshida as the
/// first step of his recursive construction.
///
/// Three force evaluations per step. The middle weight is negative (a step
/// backwards) and the error constant is large: the price of the fewest stages.
pub const FOREST_RUTH: SplittingTable = FOREST_RUTH_STAGES.table(SchemeMeta {
    id: "forest-ruth",
    name: "Forest-Ruth / Yoshida triple jump",
    order: 4,
    symplectic: true,
    symmetric: true,
    reference: "E. Forest, R. D. Ruth, Physica D 43, 105 (1990); H. Yoshida, Phys. Lett. A 150, 262 (1990)",
    phase_error: None, // measured only: no hand-derived leading term
    force_evaluations: 0, // derived by `table`
    implicit: false,
});

/// `1/(2 - 2^(1/3))` and `-2^(1/3)/(2 - 2^(1/3))`, each the nearest double.
const FOREST_RUTH_STAGES: VerletComposition<3, 4> =
    VerletComposition::new([1.3512071919596575, -1.7024143839193153, 1.3512071919596575]);

/// Yoshida's sixth-order composition, solution A: seven Verlet steps with
/// weights `w_3 w_2 w_1 w_0 w_1 w_2 w_3`.
///
/// Yoshida's table gives 15 digits, which satisfy the order conditions only to
/// 1e-14 and are off by up to 3e-15; the weights here are the exact solution
/// nearest to them, refined by Newton iteration.
pub const YOSHIDA6: SplittingTable = YOSHIDA6_STAGES.table(SchemeMeta {
    id: "yoshida6",
    name: "Yoshida sixth-order composition, solution A (7 stages)",
    order: 6,
    symplectic: true,
    symmetric: true,
    reference: "H. Yoshida, Phys. Lett. A 150, 262 (1990), Table 1, solution A",
    phase_error: None,    // measured only: no hand-derived leading term
    force_evaluations: 0, // derived by `table`
    implicit: false,
});

/// Solution A: published `w_1 = -1.17767998417887`, `w_2 = 0.235573213359357`,
/// `w_3 = 0.784513610477560`, `w_0 = 1 - 2 (w_1 + w_2 + w_3)`; refined values.
mod yoshida6 {
    pub const W1: f64 = -1.177679984178871;
    pub const W2: f64 = 0.23557321335935813;
    pub const W3: f64 = 0.7845136104775573;
    pub const W0: f64 = 1.3151863206839112;
}

const YOSHIDA6_STAGES: VerletComposition<7, 8> = VerletComposition::new([
    yoshida6::W3,
    yoshida6::W2,
    yoshida6::W1,
    yoshida6::W0,
    yoshida6::W1,
    yoshida6::W2,
    yoshida6::W3,
]);

/// Kahan and Li's eighth-order composition `s17odr8a`: seventeen Verlet steps
/// with palindromic weights `g_1 .. g_8 g_9 g_8 .. g_1`.
///
/// Fifteen stages suffice for order 8 (Yoshida's solutions); the two extra
/// stages buy small weights (all below 0.61 in size) and a leading error term
/// about a million times smaller than that of Yoshida's eighth-order solution A
/// (on the test matrices of `tests/refine_coefficients.py`), whose published
/// 15 digits moreover satisfy the order conditions only to 3e-11. Kahan and
/// Li's 26 digits are confirmed to 4e-27 by Newton iteration on the order
/// conditions.
pub const KAHAN_LI8: SplittingTable = KAHAN_LI8_STAGES.table(SchemeMeta {
    id: "kahan-li8",
    name: "Kahan-Li eighth-order composition s17odr8a (17 stages)",
    order: 8,
    symplectic: true,
    symmetric: true,
    reference: "W. Kahan, R.-C. Li, Math. Comp. 66, 1089 (1997), s17odr8a; 26 digits in Hairer, Lubich, Wanner, Geometric Numerical Integration (2006), V.3.2",
    phase_error: None, // measured only: no hand-derived leading term
    force_evaluations: 0, // derived by `table`
    implicit: false,
});

/// `s17odr8a`'s weights, each the nearest double to the published 26 digits.
mod kahan_li8 {
    pub const G1: f64 = 0.13020248308889007;
    pub const G2: f64 = 0.5611629817751084;
    pub const G3: f64 = -0.38947496264484727;
    pub const G4: f64 = 0.1588419065551556;
    pub const G5: f64 = -0.39590389413323757;
    pub const G6: f64 = 0.1845396409783157;
    pub const G7: f64 = 0.25837438768632204;
    pub const G8: f64 = 0.2950117236093103;
    pub const G9: f64 = -0.6055085338300346;
}

const KAHAN_LI8_STAGES: VerletComposition<17, 18> = {
    use kahan_li8::*;
    VerletComposition::new([
        G1, G2, G3, G4, G5, G6, G7, G8, G9, G8, G7, G6, G5, G4, G3, G2, G1,
    ])
};
