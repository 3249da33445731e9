//! Every splitting and composition table of the catalogue against the algebra
//! behind its claims, independently of the integration runs: consistency,
//! symmetry, and the order conditions up to the claimed order, satisfied as
//! well as doubles can satisfy them, and the first condition beyond the order
//! clearly violated. The conditions are [`stepladder::conditions`]'s, for the
//! splitting of any two non-commuting flows.

use stepladder::conditions::{self, BEYOND_ORDER};
use stepladder::scheme::{FOREST_RUTH, Flow, SplittingTable, TABLES, VerletComposition, YOSHIDA6};

/// A table has order `p` exactly when its series agrees with `exp(h (A + B))`
/// through `h^p` for generic non-commuting `A`, `B` (the local error is
/// `O(h^(p+1))`; the order conditions of a splitting of `|v|^2/2 + V(q)` into
/// its two exact flows are those of the free Lie algebra of the two flows,
/// which the random matrices see in full). Each condition through `h^p` must
/// hold as well as weights rounded to doubles can make it hold, which fails
/// for weights a few units in the last place off (published digits not
/// refined); the `h^(p+1)` one must be far from holding, so the claimed order
/// is no underclaim either. A table marked `nystrom_only` has its order only
/// where `[B, [B, [B, A]]] = 0`, which generic matrices do not satisfy: it is
/// checked on `q'' = a(q)` instead (`nystrom_conditions.rs`), and below it
/// must fail here, so that the mark cannot hide a table from this check.
#[test]
fn every_table_satisfies_its_order_conditions_and_no_more() {
    let mut failures = Vec::new();
    for t in TABLES.iter().filter(|t| !t.nystrom_only) {
        let p = t.meta.order as usize;
        let c = conditions::splitting_general(&t.sequence(), p + 1).unwrap();
        for d in c.defects.iter().take(p).filter(|d| !d.holds()) {
            failures.push(format!(
                "{}: h^{} condition off by {:.2e}, {:.1} times what rounding explains",
                t.meta.id,
                d.degree,
                d.value,
                d.ratio()
            ));
        }
        let beyond = c.at(p + 1).unwrap();
        if !beyond.clearly_fails() {
            failures.push(format!(
                "{}: the h^{} condition nearly holds ({:.2e}): order {p} underclaimed?",
                t.meta.id,
                p + 1,
                beyond.value
            ));
        }
        println!("{:>16}: h^1..h^{} defect / rounding: {c}", t.meta.id, p + 1);
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The condition through the claimed order furthest from holding, with its
/// ratio to its allowance.
fn worst_condition(t: &SplittingTable) -> (usize, f64) {
    let p = t.meta.order as usize;
    let c = conditions::splitting_general(&t.sequence(), p).unwrap();
    let worst = c.worst_through(p).unwrap();
    (worst.degree, worst.ratio())
}

/// Only a table that needs the mark has it: each `nystrom_only` table
/// violates a generic condition through its claimed order by far more than
/// rounding explains (McLachlan and Atela's fourth-order table is of generic
/// order 3 only).
#[test]
fn nystrom_only_tables_fail_the_generic_conditions() {
    let marked: Vec<_> = TABLES.iter().filter(|t| t.nystrom_only).collect();
    assert!(!marked.is_empty(), "the Nystrom tables are in TABLES");
    for t in marked {
        let (k, ratio) = worst_condition(t);
        println!(
            "{}: generic h^{k} condition at {ratio:.1e} times rounding",
            t.meta.id
        );
        assert!(
            ratio >= BEYOND_ORDER,
            "{} needs no mark: h^{k} at {ratio}",
            t.meta.id
        );
    }
}

/// The test must be able to fail. Forest-Ruth with its weights moved by 1e-6
/// (still consistent and palindromic, but `sum w^3 != 0`) is second order:
/// its `h^3` condition fails by far more than rounding explains.
#[test]
fn a_perturbed_composition_fails_at_h3() {
    const W1: f64 = 1.3512071919596575 - 1e-6;
    const NEAR_FOREST_RUTH: VerletComposition<3, 4> =
        VerletComposition::new([W1, 1.0 - 2.0 * W1, W1]);
    let t = NEAR_FOREST_RUTH.table(FOREST_RUTH.meta);
    let c = conditions::splitting_general(&t.sequence(), 4).unwrap();
    assert_eq!(c.order(), 2, "{c}");
    assert!(c.at(3).unwrap().clearly_fails(), "{c}");
}

/// Published digits short of double precision are caught: Yoshida's 15
/// digits, each weight up to 3e-15 (13 units in the last place) off the exact
/// solution, fail the conditions that the refined weights pass.
#[test]
fn unrefined_published_digits_fail_the_order_conditions() {
    const W1: f64 = -1.17767998417887;
    const W2: f64 = 0.235573213359357;
    const W3: f64 = 0.784513610477560;
    const W0: f64 = 1.0 - 2.0 * (W1 + W2 + W3);
    const PUBLISHED_YOSHIDA6: VerletComposition<7, 8> =
        VerletComposition::new([W3, W2, W1, W0, W1, W2, W3]);
    let (k, ratio) = worst_condition(&PUBLISHED_YOSHIDA6.table(YOSHIDA6.meta));
    println!("published Yoshida: worst h^{k} at {ratio}");
    assert!(ratio > 3.0, "published Yoshida: worst h^{k} at {ratio}");
}

/// Largest `sum |x_i|^power` error allowed for a sum of `n` rounded terms
/// that should vanish: one rounding per term and per addition, twice over.
fn sum_allowance(xs: &[f64], power: i32) -> f64 {
    let size: f64 = xs.iter().map(|x| x.abs().powi(power)).sum();
    2.0 * (xs.len() as f64 + power as f64) * f64::EPSILON * size
}

/// Each flow must advance the full step, or the method is not even
/// consistent; a palindromic sequence of flows is time-symmetric (its adjoint,
/// the reversed sequence with `-h`, is itself), and a splitting of two exact
/// flows is symmetric only if palindromic.
#[test]
fn weights_sum_to_one_and_the_symmetry_claims_hold() {
    for t in TABLES {
        for (flow, w) in [("drift", t.drift), ("kick", t.kick)] {
            let sum: f64 = w.iter().sum();
            assert!(
                (sum - 1.0).abs() <= sum_allowance(w, 1),
                "{}: {flow} weights sum to 1 + {:e}",
                t.meta.id,
                sum - 1.0
            );
        }
        let seq = t.sequence();
        let palindrome = seq
            .iter()
            .zip(seq.iter().rev())
            .all(|(a, b)| a.0 == b.0 && a.1 == b.1);
        assert_eq!(palindrome, t.meta.symmetric, "{}", t.meta.id);
        assert!(
            t.meta.symplectic,
            "every splitting is symplectic: {}",
            t.meta.id
        );
    }
}

/// Conditions on the weights of a composition of a symmetric second-order
/// step `S(h) = exp(h X1 + h^3 X3 + h^5 X5 + h^7 X7 + ...)` (odd powers only,
/// since `S(-h) S(h) = 1`). By the Baker-Campbell-Hausdorff formula the
/// composition `S(w_s h) ... S(w_1 h)` is the exponential of
///
/// `h sum(w) X1 + h^3 sum(w^3) X3 + h^5 (sum(w^5) X5 + P5(w) [X1, [X1, X3]])
///  + h^7 (sum(w^7) X7 + commutators) + ...`
///
/// with `P5` a polynomial in the weights: each `X_(2k+1)` enters alone with
/// the factor `sum w^(2k+1)`, and every other term at that power is a
/// commutator. For a generic problem `X3, X5, X7` are independent of one
/// another and of the commutators, so order `p` needs `sum w = 1`
/// (consistency) and `sum w^(2k+1) = 0` for `3 <= 2k+1 < p`: necessary
/// conditions, not sufficient (the commutator terms give the rest, which the
/// series above check).
#[test]
fn composition_weights_satisfy_the_power_sum_conditions() {
    let mut compositions = 0;
    for t in TABLES {
        let Some(w) = t.composition else { continue };
        compositions += 1;
        let sum: f64 = w.iter().sum();
        assert!(
            (sum - 1.0).abs() <= sum_allowance(w, 1),
            "{}: sum w = 1 + {:e}",
            t.meta.id,
            sum - 1.0
        );
        for power in (3..t.meta.order as i32).step_by(2) {
            let s: f64 = w.iter().map(|x| x.powi(power)).sum();
            assert!(
                s.abs() <= sum_allowance(w, power),
                "{}: sum w^{power} = {s:e}",
                t.meta.id
            );
        }
        // the table really is velocity Verlet composed with these weights
        assert_eq!(t.first, Flow::Kick, "{}", t.meta.id);
        assert_eq!(t.drift, w, "{}", t.meta.id);
        assert_eq!(t.kick.len(), w.len() + 1, "{}", t.meta.id);
        assert_eq!(t.kick[0], w[0] / 2.0, "{}", t.meta.id);
        for i in 1..w.len() {
            assert_eq!(t.kick[i], (w[i - 1] + w[i]) / 2.0, "{}", t.meta.id);
        }
        assert_eq!(t.kick[w.len()], w[w.len() - 1] / 2.0, "{}", t.meta.id);
        assert_eq!(t.meta.force_evaluations as usize, w.len(), "{}", t.meta.id);
    }
    assert!(
        compositions >= 3,
        "the catalogue's compositions are in TABLES"
    );
}

/// Forest-Ruth's weights have a closed form: `w1 = 1/(2 - 2^(1/3))` solves
/// `2 w1^3 + (1 - 2 w1)^3 = 0`.
#[test]
fn forest_ruth_weights_match_their_closed_form() {
    let w1 = 1.0 / (2.0 - 2f64.cbrt());
    let w = FOREST_RUTH.composition.unwrap();
    assert!(
        (w[0] - w1).abs() <= 4.0 * f64::EPSILON * w1,
        "{}",
        w[0] - w1
    );
    assert!(
        (w[1] - (1.0 - 2.0 * w1)).abs() <= 8.0 * f64::EPSILON * w1,
        "{}",
        w[1] - (1.0 - 2.0 * w1)
    );
}
