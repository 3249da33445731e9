//! Double-double arithmetic, `hi + lo` with about 32 significant digits: in
//! doubles the rounding of the many cancelling terms of a truncated series is
//! far larger than the effect of a coefficient a few units in the last place
//! off, which the checks must resolve.

/// A double-double `hi + lo`: the unevaluated sum of two doubles with
/// `|lo| <= ulp(hi)/2`. Each operation below rounds at about `2^-104`
/// relative to the terms it combines.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dd {
    /// The leading double.
    pub hi: f64,
    /// The rounding error of `hi`.
    pub lo: f64,
}

/// The relative rounding of one double-double operation.
pub const UNIT: f64 = 4.930_380_657_631_324e-32; // 2^-104

impl Dd {
    /// `x`, exactly.
    pub const fn of(x: f64) -> Self {
        Dd { hi: x, lo: 0.0 }
    }

    /// Knuth's error-free sum, then renormalised.
    pub fn add(self, y: Dd) -> Dd {
        let s = self.hi + y.hi;
        let b = s - self.hi;
        let e = (self.hi - (s - b)) + (y.hi - b) + self.lo + y.lo;
        let hi = s + e;
        Dd {
            hi,
            lo: e - (hi - s),
        }
    }

    /// `self - y`.
    pub fn sub(self, y: Dd) -> Dd {
        self.add(y.neg())
    }

    /// The error-free product through a fused multiply-add.
    pub fn mul(self, y: Dd) -> Dd {
        let p = self.hi * y.hi;
        let e = self.hi.mul_add(y.hi, -p) + (self.hi * y.lo + self.lo * y.hi);
        let hi = p + e;
        Dd {
            hi,
            lo: e - (hi - p),
        }
    }

    /// `-self`, exactly.
    pub fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }

    /// `1 / n` to double-double accuracy.
    pub fn recip(n: f64) -> Dd {
        let hi = 1.0 / n;
        Dd {
            hi,
            lo: -n.mul_add(hi, -1.0) / n,
        }
    }

    /// The nearest double.
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
}

/// `w` moved by one unit in the last place (up for a positive `w`, down
/// in its bit pattern for a negative one): what rounding a coefficient to a
/// double can do to it. A zero coefficient is exact (a structural zero of
/// the table) and is not moved.
pub fn moved_one_ulp(w: f64) -> Option<f64> {
    (w != 0.0).then(|| {
        f64::from_bits(if w > 0.0 {
            w.to_bits() + 1
        } else {
            w.to_bits() - 1
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_unit_is_two_to_the_minus_104() {
        assert_eq!(UNIT, 2f64.powi(-104));
    }

    /// `1/3 * 3 - 1` vanishes to the double-double unit, where doubles
    /// leave `2^-54`; and `0.1 + 0.2 - 0.3` keeps the decimal rounding of
    /// the three doubles, exactly.
    #[test]
    fn sums_and_products_carry_the_low_part() {
        let third = Dd::recip(3.0);
        let one = third.mul(Dd::of(3.0)).sub(Dd::of(1.0));
        assert!(one.to_f64().abs() <= 2.0 * UNIT, "{one:?}");
        let s = Dd::of(0.1).add(Dd::of(0.2)).sub(Dd::of(0.3));
        assert_eq!(s.to_f64(), 2f64.powi(-55));
    }

    #[test]
    fn a_coefficient_moves_by_one_unit_and_zero_stays() {
        assert_eq!(moved_one_ulp(1.0), Some(1.0 + f64::EPSILON));
        assert_eq!(moved_one_ulp(-1.0), Some(-1.0 + f64::EPSILON / 2.0));
        assert_eq!(moved_one_ulp(0.0), None);
        assert_eq!(moved_one_ulp(-0.0), None);
    }
}
