//! Double-double arithmetic, `hi + lo` with about 32 significant digits,
//! where doubles cannot resolve what is measured: in the order conditions
//! the rounding of the many cancelling terms of a truncated series is far
//! larger than the effect of a coefficient a few units in the last place
//! off; in a long run the energy's own rounding in doubles (about `1e-16` of
//! it) hides the random walk of a compensated integrator's round-off.

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

// Named methods rather than operators: each rounding stays visible in the
// formulas that use them.
#[allow(clippy::should_implement_trait)]
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

    /// `self / y`: the quotient of the leading parts, then two corrections
    /// from the exact remainder, each adding 53 bits.
    pub fn div(self, y: Dd) -> Dd {
        let q0 = self.hi / y.hi;
        let r = self.sub(y.mul(Dd::of(q0)));
        let q1 = r.hi / y.hi;
        let r = r.sub(y.mul(Dd::of(q1)));
        let q2 = r.hi / y.hi;
        Dd::of(q0).add(Dd::of(q1)).add(Dd::of(q2))
    }

    /// `sqrt(self)` for `self > 0`: one Newton step from the double root,
    /// which doubles its 53 bits.
    pub fn sqrt(self) -> Dd {
        let s = self.hi.sqrt();
        let r = self.sub(Dd::of(s).mul(Dd::of(s)));
        Dd::of(s).add(Dd::of(r.hi / (2.0 * s)))
    }

    /// `(sin self, cos self)` for `|self|` up to about `1e6`: the argument
    /// less the nearest multiple of `pi/2` (in double-double, so the
    /// reduction keeps its 32 digits), then both Taylor series on
    /// `|r| <= pi/4`, whose terms past `r^29/29!` are below `1e-34`. Each
    /// next term is the last times `r^2` times a double-double reciprocal
    /// ([`Dd::recip`], one division of doubles), not a double-double
    /// division: the Kepler scenes' exact solutions call this at every
    /// point an error is measured.
    pub fn sin_cos(self) -> (Dd, Dd) {
        const HALF_PI: Dd = Dd {
            hi: std::f64::consts::FRAC_PI_2,
            lo: 6.123_233_995_736_766e-17,
        };
        let k = (self.hi / HALF_PI.hi).round();
        let r = self.sub(HALF_PI.mul(Dd::of(k)));
        let r2 = r.mul(r);
        let (mut sin, mut cos) = (Dd::default(), Dd::default());
        let (mut s_term, mut c_term) = (r, Dd::of(1.0));
        for j in 0..15 {
            sin = sin.add(s_term);
            cos = cos.add(c_term);
            // both terms below the double-double unit of a sum near one
            // (the cosine's is): the rest cannot change either sum
            if s_term.hi.abs().max(c_term.hi.abs()) < 1e-33 {
                break;
            }
            // r^(2j+1)/(2j+1)! and r^(2j)/(2j)! to the next terms
            let (m1, m2) = ((2 * j + 1) as f64, (2 * j + 2) as f64);
            s_term = s_term.mul(r2).mul(Dd::recip(-m2 * (m2 + 1.0)));
            c_term = c_term.mul(r2).mul(Dd::recip(-m1 * m2));
        }
        match (k as i64).rem_euclid(4) {
            0 => (sin, cos),
            1 => (cos, sin.neg()),
            2 => (sin.neg(), cos.neg()),
            _ => (cos.neg(), sin),
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

    /// `2/3` and `sqrt(2)` to the double-double unit: each squared or
    /// multiplied back gives its argument to a few units of `2^-104`.
    #[test]
    fn quotients_and_roots_carry_the_low_part() {
        let q = Dd::of(2.0).div(Dd::of(3.0));
        assert!(q.mul(Dd::of(3.0)).sub(Dd::of(2.0)).to_f64().abs() <= 4.0 * UNIT);
        assert!(q.lo != 0.0, "the low part of 2/3 is not zero: {q:?}");
        let r = Dd::of(2.0).sqrt();
        assert!(r.mul(r).sub(Dd::of(2.0)).to_f64().abs() <= 8.0 * UNIT);
        let third = Dd::recip(3.0);
        let back = Dd::of(1.0).div(third);
        assert!(
            back.sub(Dd::of(3.0)).to_f64().abs() <= 8.0 * UNIT,
            "{back:?}"
        );
    }

    /// `sin^2 + cos^2 = 1` to the unit at arguments from 0 to 20 radians,
    /// the sine at `pi/6` is `1/2` and the cosine at `pi/3` is `1/2` with
    /// `pi` in double-double, and the doubles agree with the library's.
    #[test]
    fn sines_and_cosines_reach_the_double_double_unit() {
        const PI: Dd = Dd {
            hi: std::f64::consts::PI,
            lo: 1.224_646_799_147_353_2e-16,
        };
        for i in 0..200 {
            let x = Dd::of(0.1 * i as f64 + 0.013);
            let (s, c) = x.sin_cos();
            let one = s.mul(s).add(c.mul(c)).sub(Dd::of(1.0)).to_f64();
            assert!(one.abs() <= 16.0 * UNIT, "x = {x:?}: {one:e}");
            let (fs, fc) = x.hi.sin_cos();
            assert!((s.to_f64() - fs).abs() <= 2.0 * f64::EPSILON, "{x:?}");
            assert!((c.to_f64() - fc).abs() <= 2.0 * f64::EPSILON, "{x:?}");
        }
        let sixth = PI.div(Dd::of(6.0)).sin_cos().0.sub(Dd::of(0.5));
        assert!(sixth.to_f64().abs() <= 8.0 * UNIT, "{sixth:?}");
        let third = PI.div(Dd::of(3.0)).sin_cos().1.sub(Dd::of(0.5));
        assert!(third.to_f64().abs() <= 8.0 * UNIT, "{third:?}");
    }

    #[test]
    fn a_coefficient_moves_by_one_unit_and_zero_stays() {
        assert_eq!(moved_one_ulp(1.0), Some(1.0 + f64::EPSILON));
        assert_eq!(moved_one_ulp(-1.0), Some(-1.0 + f64::EPSILON / 2.0));
        assert_eq!(moved_one_ulp(0.0), None);
        assert_eq!(moved_one_ulp(-0.0), None);
    }
}
