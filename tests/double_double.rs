//! Double-double division by divisors far from one. A quotient is the
//! leading parts' quotient corrected twice from the exact remainder, so a
//! leading quotient or a first correction that is wrong by a factor near
//! one is repaired by the corrections after it; only a divisor many orders
//! of magnitude from one (a wrong part then too large for the next to
//! cancel within the unit) shows that each part divides by it.

use stepladder::internals::maths::dd::{Dd, UNIT};

/// `x / y` times `y` gives `x` back to a few units of `2^-104` of `x`, for
/// divisors from `1e-12` to `1e12` and dividends whose quotients do not
/// terminate in binary.
#[test]
fn quotients_by_large_and_small_divisors_are_exact_to_the_unit() {
    for y in [1e-12, 3e-7, 7.0, 1.1e5, 1e12] {
        for x in [Dd::of(2.0), Dd::of(1.0).div(Dd::of(3.0)), Dd::of(-5.5e3)] {
            let q = x.div(Dd::of(y));
            let back = q.mul(Dd::of(y)).sub(x).to_f64().abs();
            assert!(
                back <= 8.0 * UNIT * x.hi.abs(),
                "({x:?}) / {y:e} = {q:?}: times the divisor it is off by {back:e}"
            );
        }
    }
}
