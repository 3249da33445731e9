//! Double-double arithmetic, `hi + lo` with about 32 significant digits, for
//! the order-condition tests: in doubles the rounding of the many cancelling
//! terms of a truncated series is far larger than the effect of a weight a
//! few units in the last place off, which those tests must resolve.

/// A double-double `hi + lo`: the sum of two doubles, `|lo| <= ulp(hi)/2`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Dd {
    /// The leading double.
    pub hi: f64,
    /// The rounding error of `hi`.
    pub lo: f64,
}

impl Dd {
    pub fn of(x: f64) -> Self {
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

    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
}
