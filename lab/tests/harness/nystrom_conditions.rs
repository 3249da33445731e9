//! Every splitting table against the order conditions of `q'' = a(q)`
//! itself, independently of the integration runs: the check that applies to
//! the Runge-Kutta-Nystrom tables, which the generic-matrix check of
//! `order_conditions.rs` rejects by design.
//!
//! Two views of the same claim, both [`stepladder::conditions`]'s, on a
//! polynomial force of degree 7 at four random points: the local error
//! coefficients `E_k` as exact power series in `h` in double-double
//! ([`conditions::splitting_nystrom`]), and the local error of one numerical
//! step at `h` and `h/2`, whose ratio must be `2^(p+1)` within what the
//! expansion and rounding allow ([`conditions::splitting_step_ratio`]).

use stepladder::conditions::{self, BEYOND_ORDER, Conditions};
use stepladder::scheme::{Flow, MCLACHLAN_ATELA4, MCLACHLAN_SB3A4, SplittingTable, TABLES};

/// The failures of the claim "order `p` for `q'' = a(q)`": a condition
/// through `h^p` off by more than rounding, or `h^(p+1)` nearly holding.
fn series_failures(id: &str, p: usize, c: &Conditions) -> Vec<String> {
    let mut failures = Vec::new();
    for d in c.defects.iter().take(p).filter(|d| !d.holds()) {
        failures.push(format!(
            "{id}: h^{} Nystrom defect {:.2e}, {:.1} times what rounding explains",
            d.degree,
            d.value,
            d.ratio()
        ));
    }
    let beyond = c.at(p + 1).unwrap();
    if !beyond.clearly_fails() {
        failures.push(format!(
            "{id}: the h^{} Nystrom defect nearly vanishes ({:.2e}): order {p} underclaimed?",
            p + 1,
            beyond.value
        ));
    }
    failures
}

/// Every table has its claimed order `p` for `q'' = a(q)`, no more: the
/// local error's coefficients `E_1 .. E_p` vanish to rounding and `E_(p+1)`
/// does not. Generic splittings are checked too (the Nystrom conditions are
/// a subset of theirs), so no table escapes both checks.
#[test]
fn every_table_has_its_order_for_second_order_equations() {
    let mut failures = Vec::new();
    for t in TABLES {
        let p = t.meta.order as usize;
        let c = conditions::splitting_nystrom(&t.sequence(), p + 1).unwrap();
        failures.extend(series_failures(t.meta.id, p, &c));
        println!(
            "{:>20}: h^1..h^{} Nystrom defect / allowance: {c}",
            t.meta.id,
            p + 1
        );
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The local error of one step falls by `2^(p+1)` when the step is halved,
/// within the range the error expansion and rounding allow, and that range
/// is narrow enough to tell `p` from `p - 1` and `p + 1` (it lies within a
/// factor `sqrt 2` of `2^(p+1)`).
#[test]
fn every_table_has_a_local_error_ratio_of_two_to_the_order_plus_one() {
    let mut failures = Vec::new();
    for t in TABLES {
        let p = t.meta.order as usize;
        let r = conditions::splitting_step_ratio(&t.sequence(), p).unwrap();
        let expected = 2f64.powi(p as i32 + 1);
        println!(
            "{:>20}: h = 2^{}: e(h)/e(h/2) = {:.4} in [{:.4}, {:.4}], 2^{} = {expected}",
            t.meta.id,
            r.h.log2(),
            r.measured,
            r.low,
            r.high,
            p + 1
        );
        if !r.holds() {
            failures.push(format!("{}: {r:?}", t.meta.id));
        }
        if r.low < expected / 2f64.sqrt() || r.high > expected * 2f64.sqrt() {
            failures.push(format!(
                "{}: range too wide to tell the order: {r:?}",
                t.meta.id
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// `table` with one weight of `flow` moved by `delta` and others moved to
/// keep the weights of `flow` summing to one, so that only a condition from
/// `h^2` on can see it: in a palindrome the first weight and its mirror image
/// move by `delta` and the centre weight by `-2 delta` (or the two centre
/// weights by `-delta` each), which keeps it symmetric and leaves the first
/// violated condition at `h^3`; otherwise the first weight moves by `delta`
/// and the second by `-delta`.
fn perturbed(table: &SplittingTable, flow: Flow, delta: f64) -> Vec<(Flow, f64)> {
    let mut seq = table.sequence();
    let at: Vec<usize> = (0..seq.len()).filter(|&i| seq[i].0 == flow).collect();
    let n = at.len();
    if table.meta.symmetric {
        seq[at[0]].1 += delta;
        seq[at[n - 1]].1 += delta;
        // the centre weight twice, or each of the two of an even palindrome
        for i in [at[n / 2], at[(n - 1) / 2]] {
            seq[i].1 -= delta;
        }
    } else {
        seq[at[0]].1 += delta;
        seq[at[1]].1 -= delta;
    }
    seq
}

/// Both checks must be able to fail. A weight moved by one unit in its 8th
/// significant digit (others moved to stay consistent and, for the symmetric
/// table, symmetric) leaves a defect at `h^2` or `h^3` near 1e-9, which the
/// series check sees as a million times what rounding explains and which
/// moves the local error of one step out of its range.
#[test]
fn a_weight_off_in_its_eighth_digit_fails_both_checks() {
    for (t, flow) in [
        (&MCLACHLAN_SB3A4, Flow::Drift),
        (&MCLACHLAN_SB3A4, Flow::Kick),
        (&MCLACHLAN_ATELA4, Flow::Kick),
        (&MCLACHLAN_ATELA4, Flow::Drift),
    ] {
        let p = t.meta.order as usize;
        let first = t.sequence().into_iter().find(|s| s.0 == flow).unwrap().1;
        let delta = 10f64.powf(first.abs().log10().floor() - 7.0);
        let seq = perturbed(t, flow, delta);
        let c = conditions::splitting_nystrom(&seq, p + 1).unwrap();
        let worst = c.worst_through(p).unwrap().ratio();
        let r = conditions::splitting_step_ratio(&seq, p).unwrap();
        println!(
            "{} with a {flow:?} weight moved by {delta:e}: worst condition through h^{p} at {worst:.1e} times rounding; step ratio {:.3} against [{:.3}, {:.3}] at h = {}",
            t.meta.id, r.measured, r.low, r.high, r.h
        );
        assert!(worst >= BEYOND_ORDER, "{}: {c:?}", t.meta.id);
        assert!(!r.holds(), "{}: {r:?}", t.meta.id);
    }
}

/// A plausible layout mistake is caught: McLachlan and Atela's weights with
/// drifts and kicks exchanged (the kick weights applied as drifts) are a
/// different method, of order 3 only.
#[test]
fn mclachlan_atela_with_drifts_and_kicks_exchanged_is_rejected() {
    let swapped: Vec<(Flow, f64)> = MCLACHLAN_ATELA4
        .sequence()
        .into_iter()
        .map(|(f, w)| {
            let other = if f == Flow::Kick {
                Flow::Drift
            } else {
                Flow::Kick
            };
            (other, w)
        })
        .collect();
    let c = conditions::splitting_nystrom(&swapped, 5).unwrap();
    assert!(!series_failures("swapped", 4, &c).is_empty(), "{c:?}");
    assert!(c.at(4).unwrap().clearly_fails(), "{c:?}");
    assert!(
        !conditions::splitting_step_ratio(&swapped, 4)
            .unwrap()
            .holds()
    );
}

/// The crate's DPRKN6 table against the one typed apart for the held-out
/// batch, from the same paper.
#[test]
fn dprkn6_coefficients_match_the_independently_typed_table() {
    let typed = stepladder_lab::corpus::held_out::DPRKN6;
    let ours = stepladder::scheme::DPRKN6;
    for i in 0..6 {
        assert!((ours.c[i] - typed.c[i]).abs() < 2e-16, "c{i}");
        assert!((ours.b[i] - typed.b[i]).abs() < 2e-16, "b{i}");
        assert!((ours.b_bar[i] - typed.b_bar[i]).abs() < 2e-16, "b_bar{i}");
        for j in 0..6 {
            assert!((ours.a[i][j] - typed.a[i][j]).abs() < 4e-16, "a{i}{j}");
        }
    }
}
