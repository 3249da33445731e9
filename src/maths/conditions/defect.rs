//! One condition's defect against its allowance, the shared currency of the
//! three checks (and of the one-step ratio), kept below them so that each
//! check imports it and none imports another.

/// How far above its allowance the first violated condition must be for
/// the claimed order not to be an underclaim: a condition that nearly holds
/// (between 1 and this many allowances) is neither. The catalogue's tables
/// violate their first condition beyond the order by at least `1e9`
/// allowances (DPRKN8's `h^9`, in the Nyström check) and satisfy the others
/// within one.
pub const BEYOND_ORDER: f64 = 1e6;

/// The order conditions at one power `h^degree`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Defect {
    /// The power of `h` (for a Butcher tree, its number of vertices).
    pub degree: usize,
    /// The size of the method's `h^degree` coefficient minus the exact
    /// flow's (the largest entry over the test problem).
    pub value: f64,
    /// What rounding the coefficients to doubles and the double-double
    /// arithmetic can explain: a condition that holds exactly for the
    /// unrounded coefficients has `value <= allowance`.
    pub allowance: f64,
    /// The size of the exact flow's `h^degree` coefficient that `value` is
    /// measured against (for a tree, `1/gamma`).
    pub scale: f64,
}

impl Defect {
    /// The defect in units of its allowance: at most 1 for a condition
    /// that holds.
    pub fn ratio(&self) -> f64 {
        self.value / self.allowance
    }

    /// The condition holds to what doubles allow.
    pub fn holds(&self) -> bool {
        self.ratio() <= 1.0
    }

    /// The condition is violated by [`BEYOND_ORDER`] allowances or more.
    pub fn clearly_fails(&self) -> bool {
        self.ratio() >= BEYOND_ORDER
    }

    /// The defect relative to the exact coefficient's size.
    pub fn relative(&self) -> f64 {
        self.value / self.scale
    }
}

/// One Butcher tree's condition `sum b Phi(t) = 1/gamma(t)`.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeDefect {
    /// The tree in bracket notation: `τ` one vertex, `[t1,t2]` a root
    /// with the subtrees `t1` and `t2` (`[[τ]]` the tall tree of order 3).
    pub tree: String,
    /// Its defect; `degree` is the tree's number of vertices.
    pub defect: Defect,
    /// `sum b Phi(t) - 1/gamma(t)` itself, with its sign (`defect.value` is
    /// its size).
    pub signed: f64,
}

/// One numerical step of a splitting against the exact flow, at `h` and
/// `h/2`, on the Nyström test problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepRatio {
    /// The step: the power of two, at most 1/4, at which the error
    /// expansion gives the narrowest range.
    pub h: f64,
    /// `e(h) / e(h/2)`, `e` the largest entry of one step minus the exact
    /// flow.
    pub measured: f64,
    /// The least ratio the expansion allows for the claimed order.
    pub low: f64,
    /// The largest ratio the expansion allows for the claimed order.
    pub high: f64,
}

impl StepRatio {
    /// The measured ratio lies in the range the claimed order allows.
    pub fn holds(&self) -> bool {
        self.low <= self.measured && self.measured <= self.high
    }
}

/// Uniform in `[-1, 1]` from SplitMix64: the test problems' fixed random
/// numbers.
pub(super) fn uniform(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    2.0 * (z >> 11) as f64 / (1u64 << 53) as f64 - 1.0
}
