//! The double-double triple jump behind the outer solar system's
//! reference: its composition weights satisfy the conditions of order
//! eight to double-double rounding.

use stepladder::internals::maths::dd::{Dd, UNIT};
use stepladder_lab::suite::dd_reference::triple_jump_weights;

/// Consistency (the weights sum to one), symmetry, and, since a symmetric
/// composition of symmetric second-order steps has no error terms of even
/// order, the odd moments `sum w^k = 0` for `k = 3, 5, 7` that order eight
/// needs. Each level of the triple jump makes one of them zero through
/// `2^(1/(p+1))`, so a root a unit of the doubles off (not computed in
/// double-double) leaves its moment about `1e-16` of its terms' size. In
/// double-double each `w^k` is `k` products and the moment a sum of 27
/// terms, each rounding at `2^-104` of what it combines: the moment is
/// zero to within `(k + 27) 2^-104 sum |w|^k`, allowed twice over.
#[test]
fn the_triple_jump_is_consistent_symmetric_and_of_order_eight() {
    let w = triple_jump_weights();
    assert_eq!(w.len(), 27);
    let sum = w.iter().fold(Dd::default(), |s, x| s.add(*x));
    assert!(sum.sub(Dd::of(1.0)).to_f64().abs() < 1e-30);
    for (a, b) in w.iter().zip(w.iter().rev()) {
        assert!(a.sub(*b).to_f64().abs() < 1e-30);
    }
    for k in [3, 5, 7] {
        let power = |x: &Dd| (0..k).fold(Dd::of(1.0), |p, _| p.mul(*x));
        let moment = w.iter().fold(Dd::default(), |s, x| s.add(power(x)));
        let size: f64 = w.iter().map(|x| x.hi.abs().powi(k)).sum();
        let allowed = 2.0 * f64::from(k + 27) * UNIT * size;
        assert!(
            moment.to_f64().abs() <= allowed,
            "sum w^{k} = {:e}, allowed {allowed:e}",
            moment.to_f64()
        );
    }
}
