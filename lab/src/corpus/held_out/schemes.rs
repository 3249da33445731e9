//! The held-out batch's schemes, correct and broken.
//!
//! Its Runge-Kutta, Runge-Kutta-Nyström and splitting steppers ([`ButcherRk`],
//! [`Rkn`], [`Splitting`]) repeat, on purpose, what the core's table-driven
//! steppers ([`stepladder::scheme::ExplicitRk`],
//! [`stepladder::scheme::NystromTable`], [`stepladder::scheme::SplittingTable`])
//! already do. Independence is the point of this batch: its correct entries
//! must pass on code the harness was never run with while its rules were
//! written, so a fault shared by a core stepper and the studies that judge
//! it cannot make a wrong scheme look right here. The other batches
//! ([`super::super::correct`], [`super::super::broken`]) are tables run by
//! the core's steppers.

use nalgebra::SVector;
use stepladder::scene::Scene;
use stepladder::scheme::{OneStep, Rk4, Scheme, SchemeMeta, StepFailure};
use stepladder::state::{Real, State};

// ====================================================================== schemes

/// The claims of an explicit scheme with no hand-derived phase error.
pub(super) const fn explicit(
    id: &'static str,
    name: &'static str,
    order: u32,
    symplectic: bool,
    symmetric: bool,
    force_evaluations: u32,
    reference: &'static str,
) -> SchemeMeta {
    SchemeMeta {
        id,
        name,
        order,
        symplectic,
        symmetric,
        force_evaluations,
        implicit: false,
        reference,
        phase_error: None,
    }
}

/// The same claims under another id and name (what a buggy copy claims).
pub(super) const fn posing_as(
    base: SchemeMeta,
    id: &'static str,
    name: &'static str,
) -> SchemeMeta {
    SchemeMeta {
        id,
        name,
        phase_error: None,
        ..base
    }
}

// ------------------------------------------------------------ explicit Runge-Kutta

/// An explicit Runge-Kutta method with Butcher tableau `(a, b, c)` on the
/// first-order system `y = (q, v)`, `y' = (v, a(q))`: stage `i` is
/// `Y_i = y + h sum_(j<i) a_ij k_j`, `k_i = f(Y_i)`, the step
/// `y' = y + h sum b_i k_i`. The entries on and above the diagonal are
/// ignored; `c` (the row sums) documents the tableau and serves the tests.
/// One force evaluation per stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ButcherRk<const S: usize> {
    /// The claims.
    pub meta: SchemeMeta,
    /// The Runge-Kutta matrix (strictly lower triangle used).
    pub a: [[f64; S]; S],
    /// The weights.
    pub b: [f64; S],
    /// The nodes.
    pub c: [f64; S],
}

impl<const S: usize> OneStep for ButcherRk<S> {
    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    #[inline(always)]
    fn advance<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let mut kq = [SVector::<R, D>::zeros(); S];
        let mut kv = [SVector::<R, D>::zeros(); S];
        for i in 0..S {
            let (mut q, mut v) = (s.q, s.v);
            for j in 0..i {
                let aij = self.a[i][j];
                if aij != 0.0 {
                    let w = h * R::of(aij);
                    q += kq[j] * w;
                    v += kv[j] * w;
                }
            }
            kq[i] = v;
            kv[i] = scene.acceleration(&q);
        }
        let (mut dq, mut dv) = (SVector::<R, D>::zeros(), SVector::<R, D>::zeros());
        for ((bi, q), v) in self.b.iter().zip(&kq).zip(&kv) {
            if *bi != 0.0 {
                dq += q * R::of(*bi);
                dv += v * R::of(*bi);
            }
        }
        s.q += dq * h;
        s.v += dv * h;
        Ok(())
    }
}

/// Butcher's sixth-order method with seven stages (1964):
/// `c = (0, 1/3, 2/3, 1/3, 1/2, 1/2, 1)`, `b = (11/120, 0, 27/40, 27/40,
/// -4/15, -4/15, 11/120)`.
///
/// Order six (all 37 Butcher trees of order up to six hold in exact
/// rationals; checked in the tests), the fewest stages for order six;
/// neither symplectic nor symmetric (explicit).
pub const BUTCHER6: ButcherRk<7> = ButcherRk {
    meta: explicit(
        "butcher6",
        "Butcher's sixth-order Runge-Kutta method (7 stages)",
        6,
        false,
        false,
        7,
        "J. C. Butcher, J. Austral. Math. Soc. 4, 179 (1964); J. C. Butcher, Numerical Methods for Ordinary Differential Equations (2016), 325",
    ),
    a: BUTCHER6_A,
    b: [
        11.0 / 120.0,
        0.0,
        27.0 / 40.0,
        27.0 / 40.0,
        -4.0 / 15.0,
        -4.0 / 15.0,
        11.0 / 120.0,
    ],
    c: [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0, 0.5, 0.5, 1.0],
};

/// Butcher's sixth-order matrix.
pub(super) const BUTCHER6_A: [[f64; 7]; 7] = [
    [0.0; 7],
    [1.0 / 3.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.0, 2.0 / 3.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0 / 12.0, 1.0 / 3.0, -1.0 / 12.0, 0.0, 0.0, 0.0, 0.0],
    [
        -1.0 / 16.0,
        9.0 / 8.0,
        -3.0 / 16.0,
        -3.0 / 8.0,
        0.0,
        0.0,
        0.0,
    ],
    [0.0, 9.0 / 8.0, -3.0 / 8.0, -3.0 / 4.0, 0.5, 0.0, 0.0],
    [
        9.0 / 44.0,
        -9.0 / 11.0,
        63.0 / 44.0,
        18.0 / 11.0,
        0.0,
        -16.0 / 11.0,
        0.0,
    ],
];

/// Runge's third-order method (1895), four stages: `k1 = f(y)`,
/// `k2 = f(y + h/2 k1)`, `k3 = f(y + h k2)`, `k4 = f(y + h k3)`,
/// `y' = y + h (k1 + 4 k2 + k4)/6`.
///
/// Third order: `sum b c^2 = 1/3` and `sum b a c = b4 a43 c3 = 1/6`; of the
/// fourth-order trees `sum b c^3 = 1/4` holds but `sum b c a c = 1/6`, not
/// 1/8. Neither symplectic nor symmetric.
pub const RUNGE3: ButcherRk<4> = ButcherRk {
    meta: explicit(
        "runge3",
        "Runge's third-order method (4 stages)",
        3,
        false,
        false,
        4,
        "C. Runge, Math. Ann. 46, 167 (1895); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.1",
    ),
    a: [
        [0.0; 4],
        [0.5, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ],
    b: [1.0 / 6.0, 2.0 / 3.0, 0.0, 1.0 / 6.0],
    c: [0.0, 0.5, 1.0, 1.0],
};

/// Kutta's 3/8 rule: `c = (0, 1/3, 2/3, 1)`, `a21 = 1/3`, `a31 = -1/3`,
/// `a32 = 1`, `a41 = 1`, `a42 = -1`, `a43 = 1`, `b = (1, 3, 3, 1)/8`.
///
/// Fourth order (all eight trees of order up to four), a different map from
/// the classical RK4 on nonlinear problems (on linear ones both are the
/// Taylor polynomial of degree four); neither symplectic nor symmetric.
pub const KUTTA38: ButcherRk<4> = ButcherRk {
    meta: explicit(
        "kutta-3-8",
        "Kutta's 3/8 rule (fourth order)",
        4,
        false,
        false,
        4,
        "W. Kutta, Z. Math. Phys. 46, 435 (1901); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.1",
    ),
    a: [
        [0.0; 4],
        [1.0 / 3.0, 0.0, 0.0, 0.0],
        [-1.0 / 3.0, 1.0, 0.0, 0.0],
        [1.0, -1.0, 1.0, 0.0],
    ],
    b: [0.125, 0.375, 0.375, 0.125],
    c: [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0],
};

/// BROKEN: [`BUTCHER6`] with the two inner entries of its fourth row
/// swapped, `a42 = -1/12`, `a43 = 1/3` (instead of `1/3, -1/12`).
///
/// The row sum `c4 = 1/3` is kept, so every condition built from row sums
/// alone still holds (`sum b = 1`, `sum b c = 1/2`, `sum b c^2 = 1/3`), but
/// the tall third-order tree `sum b_i a_ij c_j = 1/6` gains
/// `b4 (a42' - a42)(c2 - c3) = (27/40)(-5/12)(-1/3) = 3/32`: ORDER 2 (the
/// local error gains `(3/32) h^3 f' f' f`, the tall tree, which linear
/// problems see too). Neither symplectic nor symmetric, as claimed. Claims
/// order 6.
pub const BUTCHER6_SWAPPED: ButcherRk<7> = {
    let mut t = BUTCHER6;
    t.a[3][1] = -1.0 / 12.0;
    t.a[3][2] = 1.0 / 3.0;
    t.meta = posing_as(
        BUTCHER6.meta,
        "butcher6-swapped-a42-a43",
        "Butcher's sixth order with a42 and a43 swapped",
    );
    t
};

/// What [`DifferencedVelocity`] carries: the inner scheme's state, the
/// position one step earlier, and whether a step has been taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PositionHistory<R: Real, const D: usize> {
    /// The inner scheme's synchronised state (its velocity is correct).
    pub state: State<D, R>,
    /// `q(n-1)`.
    pub previous: SVector<R, D>,
    /// At least one step has been taken.
    pub stepped: bool,
}

/// BROKEN: a correct explicit Runge-Kutta method whose output velocity is
/// the backward difference `(q(n) - q(n-1))/h` of its positions, not the
/// velocity it integrates (the stored state stays correct: the error does
/// not feed back).
///
/// `(q(n) - q(n-1))/h = v(n) - h/2 a(q(n)) + O(h^2)`: the output velocity is
/// off by `h/2 |a|`, ORDER 1 in phase space whatever the inner order, with
/// the relative error `z/2 |a|/(w |v|)` (`7.8e-3` at `T/1000` on the
/// eccentric Kepler orbit, where `|a|` peaks at perihelion).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DifferencedVelocity<const S: usize> {
    /// The (false) claims.
    pub meta: SchemeMeta,
    /// The correct stepper.
    pub inner: ButcherRk<S>,
}

impl<const S: usize> Scheme for DifferencedVelocity<S> {
    type Carry<R: Real, const D: usize> = PositionHistory<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        _: &P,
        s: &State<D, R>,
        _: R,
    ) -> PositionHistory<R, D> {
        PositionHistory {
            state: *s,
            previous: s.q,
            stepped: false,
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut PositionHistory<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        c.previous = c.state.q;
        self.inner.advance(scene, &mut c.state, h)?;
        c.stepped = true;
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &PositionHistory<R, D>, h: R) -> State<D, R> {
        if c.stepped {
            State::new(c.state.q, (c.state.q - c.previous) / h)
        } else {
            c.state
        }
    }
}

/// BROKEN: [`BUTCHER6`]'s positions with backward-difference velocities
/// (see [`DifferencedVelocity`]): ORDER 1, claims order 6.
pub const BUTCHER6_DIFFERENCED: DifferencedVelocity<7> = DifferencedVelocity {
    meta: posing_as(
        BUTCHER6.meta,
        "butcher6-differenced-velocity",
        "Butcher's sixth order reporting (q(n) - q(n-1))/h as the velocity",
    ),
    inner: BUTCHER6,
};

// ------------------------------------------------------------ Runge-Kutta-Nyström

/// An explicit Runge-Kutta-Nyström method for `q'' = a(q)`:
/// `k_i = a(q + c_i h v + h^2 sum_(j<i) a_ij k_j)`,
/// `q' = q + h v + h^2 sum b_bar_i k_i`, `v' = v + h sum b_i k_i`.
/// One force evaluation per stage (no first-same-as-last saving).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rkn<const S: usize> {
    /// The claims.
    pub meta: SchemeMeta,
    /// The nodes.
    pub c: [f64; S],
    /// The stage matrix of the `h^2` terms (strictly lower triangle used).
    pub a: [[f64; S]; S],
    /// The position weights.
    pub b_bar: [f64; S],
    /// The velocity weights.
    pub b: [f64; S],
}

impl<const S: usize> OneStep for Rkn<S> {
    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    #[inline(always)]
    fn advance<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let h2 = h * h;
        let mut k = [SVector::<R, D>::zeros(); S];
        for i in 0..S {
            let mut q = s.q + s.v * (h * R::of(self.c[i]));
            for (kj, &aij) in k[..i].iter().zip(&self.a[i]) {
                if aij != 0.0 {
                    q += kj * (h2 * R::of(aij));
                }
            }
            k[i] = scene.acceleration(&q);
        }
        let (mut dq, mut dv) = (SVector::<R, D>::zeros(), SVector::<R, D>::zeros());
        for ((ki, bb), b) in k.iter().zip(&self.b_bar).zip(&self.b) {
            dq += ki * R::of(*bb);
            dv += ki * R::of(*b);
        }
        s.q += s.v * h + dq * h2;
        s.v += dv * h;
        Ok(())
    }
}

/// The nodes of RKN6(4)6FD: `(0, (209 - r)/900, (209 - r)/450,
/// (209 + r)/450, 9/10, 1)`, `r = sqrt(8581)`, each the nearest double (from
/// 25 digits).
pub(super) const DPRKN6_C: [f64; 6] = [
    0.0,
    0.129_295_903_136_704_42,
    0.258_591_806_273_408_83,
    0.670_297_082_615_48,
    0.9,
    1.0,
];

/// `b_bar_3 = (84119543 + 366727 r)/409622616` of RKN6(4)6FD.
pub(super) const DPRKN6_BB3: f64 = 0.288_291_741_189_766_8;
/// `b_bar_4 = (84119543 - 366727 r)/409622616` of RKN6(4)6FD.
pub(super) const DPRKN6_BB4: f64 = 0.122_425_537_174_570_41;

/// The sixth-order solution of Dormand and Prince's RKN6(4)6FD triple at
/// fixed step (the embedded fourth-order solution and the dense output
/// unused). Six stages, the last at `c = 1` with `a_6j = b_bar_j` (first
/// same as last, not exploited here: six force evaluations).
///
/// Coefficients in `r = sqrt(8581)`, as published, typed as the nearest
/// doubles (the tests recompute them from the closed forms). Sixth order:
/// the quadrature conditions `sum b c^k = 1/(k+1)` (`k <= 5`) and `sum b_bar
/// c^k = 1/((k+1)(k+2))` (`k <= 4`) and the row sums `sum_j a_ij = c_i^2/2`
/// hold to round-off (tests), and the measured order on the 3-D Kepler orbit
/// is six. Neither symplectic nor symmetric.
pub const DPRKN6: Rkn<6> = Rkn {
    meta: explicit(
        "dprkn6",
        "Dormand-Prince RKN6(4)6FD (sixth-order Runge-Kutta-Nystrom, fixed step)",
        6,
        false,
        false,
        6,
        "J. R. Dormand, P. J. Prince, Comput. Math. Appl. 13, 937 (1987) (RKN6(4)6FD); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.14",
    ),
    c: DPRKN6_C,
    a: [
        [0.0; 6],
        [0.008_358_715_283_968_025, 0.0, 0.0, 0.0, 0.0, 0.0],
        [
            0.011_144_953_711_957_367,
            0.022_289_907_423_914_734,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.145_474_742_801_091_8,
            -0.229_860_640_522_647_49,
            0.309_034_987_202_967_5,
            0.0,
            0.0,
            0.0,
        ],
        [
            -0.207_668_262_950_789_97,
            0.686_366_784_292_514_3,
            -0.199_549_277_872_349_25,
            0.125_850_756_530_624_89,
            0.0,
            0.0,
        ],
        [
            0.078_110_161_443_494_78,
            0.0,
            DPRKN6_BB3,
            DPRKN6_BB4,
            0.011_172_560_192_168_035,
            0.0,
        ],
    ],
    b_bar: [
        0.078_110_161_443_494_78,
        0.0,
        DPRKN6_BB3,
        DPRKN6_BB4,
        0.011_172_560_192_168_035,
        0.0,
    ],
    b: [
        0.078_110_161_443_494_78,
        0.0,
        0.388_843_478_705_982_6,
        0.371_320_757_928_842_3,
        0.111_725_601_921_680_35,
        0.05,
    ],
};

/// BROKEN: [`DPRKN6`] with the sign of `r = sqrt(8581)` typed the wrong
/// way in its position weights: `b_bar_3` and `b_bar_4`, the conjugate pair
/// `(84119543 +- 366727 r)/409622616`, swapped (the stage matrix, the
/// velocity weights and so the sixth stage are untouched).
///
/// `sum b_bar = 1/2` is kept (the pair's sum is symmetric in the sign), but
/// `sum b_bar c`, which must be `1/6`, gains `(b_bar_4 - b_bar_3)(c_3 -
/// c_4) = (-0.1659)(-0.4117) = +0.0683`: every step adds `0.0683 h^3 a'(q)
/// v` to the position, a local error `O(h^3)`: ORDER 2. Neither symplectic
/// nor symmetric, as claimed. Claims order 6.
pub const DPRKN6_SWAPPED: Rkn<6> = {
    let mut t = DPRKN6;
    t.b_bar[2] = DPRKN6_BB4;
    t.b_bar[3] = DPRKN6_BB3;
    t.meta = posing_as(
        DPRKN6.meta,
        "dprkn6-conjugate-swap",
        "Dormand-Prince RKN6 with the sign of sqrt(8581) flipped in b_bar",
    );
    t
};

// --------------------------------------------------------------------- splittings

/// One sub-step of a splitting method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sub {
    /// `q += w h v`.
    Drift,
    /// `v += w h a(q)`.
    Kick,
}

/// A splitting method: a sequence of drifts and kicks with weights. With
/// `lagged_force` (a bug) every kick uses the force at the position where
/// the preceding drift started (computed before the drift and not
/// refreshed after it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Splitting<const N: usize> {
    /// The claims; `force_evaluations` is the number of kicks.
    pub meta: SchemeMeta,
    /// The sub-steps, applied first to last.
    pub sequence: [(Sub, f64); N],
    /// Kicks use the force before the preceding drift (the bug).
    pub lagged_force: bool,
}

impl<const N: usize> Splitting<N> {
    /// The method with these claims and sub-steps; `force_evaluations` is
    /// set to the number of kicks.
    pub const fn new(mut meta: SchemeMeta, sequence: [(Sub, f64); N], lagged_force: bool) -> Self {
        let mut kicks = 0;
        let mut i = 0;
        while i < N {
            if matches!(sequence[i].0, Sub::Kick) {
                kicks += 1;
            }
            i += 1;
        }
        meta.force_evaluations = kicks;
        Self {
            meta,
            sequence,
            lagged_force,
        }
    }
}

impl<const N: usize> OneStep for Splitting<N> {
    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    #[inline(always)]
    fn advance<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let mut before_drift = s.q;
        for &(sub, w) in &self.sequence {
            match sub {
                Sub::Drift => {
                    before_drift = s.q;
                    s.q += s.v * (h * R::of(w));
                }
                Sub::Kick => {
                    let at = if self.lagged_force { before_drift } else { s.q };
                    s.v += scene.acceleration(&at) * (h * R::of(w));
                }
            }
        }
        Ok(())
    }
}

/// The triple-jump weight `x1 = 1/(2 - 2^(1/3))`, the nearest double (from
/// 25 digits, `1.351207191959657634047688`).
pub const TRIPLE_X1: f64 = 1.351_207_191_959_657_5;
/// The triple-jump weight `x0 = -2^(1/3)/(2 - 2^(1/3)) = 1 - 2 x1`, the
/// nearest double (`-1.702414383919315268095376`).
pub const TRIPLE_X0: f64 = -1.702_414_383_919_315_3;

/// The Candy-Rozmus sub-steps: position Verlet (`D(1/2) K(1) D(1/2)`)
/// composed with the triple jump `x1, x0, x1`.
pub const CANDY_ROZMUS_SEQUENCE: [(Sub, f64); 7] = [
    (Sub::Drift, 0.5 * TRIPLE_X1),
    (Sub::Kick, TRIPLE_X1),
    (Sub::Drift, 0.5 * (TRIPLE_X1 + TRIPLE_X0)),
    (Sub::Kick, TRIPLE_X0),
    (Sub::Drift, 0.5 * (TRIPLE_X1 + TRIPLE_X0)),
    (Sub::Kick, TRIPLE_X1),
    (Sub::Drift, 0.5 * TRIPLE_X1),
];

/// Candy and Rozmus's fourth-order symplectic integrator, drift first:
/// `D(x1/2) K(x1) D((x1+x0)/2) K(x0) D((x1+x0)/2) K(x1) D(x1/2)`, the
/// triple jump of POSITION Verlet (the catalogue's Forest-Ruth composes
/// velocity Verlet; the two are different maps with different error
/// constants).
///
/// Fourth order (`2 x1 + x0 = 1`, `2 x1^3 + x0^3 = 0`, and the palindrome
/// cancels the even terms; the tests check the series up to `h^4` on random
/// matrices), symplectic (exact flows), symmetric (a palindrome). Three
/// force evaluations per step.
pub const CANDY_ROZMUS4: Splitting<7> = Splitting::new(
    explicit(
        "candy-rozmus4",
        "Candy-Rozmus fourth order (drift-first triple jump)",
        4,
        true,
        true,
        0,
        "J. Candy, W. Rozmus, J. Comput. Phys. 92, 230 (1991); E. Forest, R. D. Ruth, Physica D 43, 105 (1990)",
    ),
    CANDY_ROZMUS_SEQUENCE,
    false,
);

/// BROKEN: [`CANDY_ROZMUS4`] whose kicks use the force computed before the
/// preceding drift (the loop evaluates `a(q)`, drifts, then kicks with the
/// stale value): kick `i` uses `a(q - d_i h v)` where it needs `a(q)`.
///
/// The total impulse is off by `h^2 a'(q) v sum_i c_i d_i` to leading order,
/// `sum c_i d_i = x1 (x1/2) + x0 (x1 + x0)/2 + x1 (x1 + x0)/2 = 0.97455`,
/// so the velocity takes a local error `O(h^2)`: ORDER 1. The kicks are no
/// longer flows of the potential at the current position, so NOT
/// symplectic: on the oscillator `x'' = -w^2 x` the step's determinant is
/// `1 + 0.97455 z^2 + O(z^4)` (the tests measure `0.9746 z^2` at `z =
/// 0.01`), an exponential growth of the energy by `e^(0.97 z^2)` a step,
/// which the long run (`z = 2 pi/100`, `10^6` steps) cannot survive (the
/// Toda lattice blows up, the trimer dissociates); and NOT symmetric.
/// Claims order 4, symplectic, symmetric.
pub const CANDY_ROZMUS4_LAGGED: Splitting<7> = Splitting::new(
    posing_as(
        CANDY_ROZMUS4.meta,
        "candy-rozmus4-lagged-force",
        "Candy-Rozmus fourth order kicking with the force from before each drift",
    ),
    CANDY_ROZMUS_SEQUENCE,
    true,
);

/// Blanes-Moan `SRKN_6^b` drift weights `a1, a2` (to the published 15
/// digits); `a3 = 1/2 - a1 - a2`.
pub(super) const SRKN6B_A: [f64; 2] = [0.245_298_957_184_271, 0.604_872_665_711_080];
/// Blanes-Moan `SRKN_6^b` kick weights `b1, b2, b3`; `b4 = 1 - 2 (b1 + b2 +
/// b3)`.
pub(super) const SRKN6B_B: [f64; 3] = [
    0.082_984_406_417_405_2,
    0.396_309_801_498_368,
    -0.039_056_304_922_348_6,
];

/// The `SRKN_6^b` sequence with the kick weights `b1, b2, b3` (so that a
/// typo can be made in one of them).
pub(super) const fn srkn6b(b: [f64; 3]) -> [(Sub, f64); 13] {
    let a3 = 0.5 - (SRKN6B_A[0] + SRKN6B_A[1]);
    let b4 = 1.0 - 2.0 * (b[0] + b[1] + b[2]);
    [
        (Sub::Kick, b[0]),
        (Sub::Drift, SRKN6B_A[0]),
        (Sub::Kick, b[1]),
        (Sub::Drift, SRKN6B_A[1]),
        (Sub::Kick, b[2]),
        (Sub::Drift, a3),
        (Sub::Kick, b4),
        (Sub::Drift, a3),
        (Sub::Kick, b[2]),
        (Sub::Drift, SRKN6B_A[1]),
        (Sub::Kick, b[1]),
        (Sub::Drift, SRKN6B_A[0]),
        (Sub::Kick, b[0]),
    ]
}

/// Blanes and Moan's symplectic Runge-Kutta-Nyström splitting `SRKN_6^b`:
/// the palindrome `K(b1) D(a1) K(b2) D(a2) K(b3) D(a3) K(b4) D(a3) K(b3)
/// D(a2) K(b2) D(a1) K(b1)`, six force evaluations with first same as last
/// (seven here, without the saving).
///
/// Fourth order even for general splittings `A + B` (the tests check the
/// series up to `h^4` on random matrices, `h^5` not), optimised for `q'' =
/// a(q)` where its fifth- and sixth-order error terms are small;
/// symplectic, symmetric.
pub const SRKN6B: Splitting<13> = Splitting::new(
    explicit(
        "blanes-moan-srkn6b",
        "Blanes-Moan symplectic RKN splitting SRKN6b (order 4)",
        4,
        true,
        true,
        0,
        "S. Blanes, P. C. Moan, J. Comput. Appl. Math. 142, 313 (2002), table 3 (SRKN_6^b)",
    ),
    srkn6b(SRKN6B_B),
    false,
);

/// BROKEN: [`SRKN6B`] with the small negative kick weight `b3 =
/// -0.0391` typed positive (in both of its places, so the palindrome stays),
/// the middle weight `b4 = 1 - 2 (b1 + b2 + b3)` computed from the typed
/// ones as the paper prescribes (`-0.0367` instead of `0.1195`).
///
/// The weights still sum to one in drifts and in kicks (consistent), the
/// sequence is still a palindrome of exact flows: SYMPLECTIC and SYMMETRIC,
/// so the even-order terms of the error vanish and the energy stays bounded.
/// But the third-order conditions, which need the original `b3`, fail (the
/// tests find the `h^3` Taylor coefficient off by 3% of its size on random
/// matrices, 11% with the Nyström structure): ORDER 2. Claims order 4.
pub const SRKN6B_SIGN_FLIPPED: Splitting<13> = Splitting::new(
    posing_as(
        SRKN6B.meta,
        "blanes-moan-srkn6b-b3-sign",
        "Blanes-Moan SRKN6b with the sign of b3 flipped",
    ),
    srkn6b([SRKN6B_B[0], SRKN6B_B[1], -SRKN6B_B[2]]),
    false,
);

// --------------------------------------------------------------------- Beeman

/// What Beeman's algorithm carries: the state, `a(q(n))` and `a(q(n-1))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BeemanCarry<R: Real, const D: usize> {
    /// The synchronised state.
    pub state: State<D, R>,
    /// `a(q(n))`.
    pub a: SVector<R, D>,
    /// `a(q(n-1))`.
    pub a_previous: SVector<R, D>,
}

/// Beeman's algorithm (1976), as used in molecular dynamics:
/// `q(n+1) = q(n) + h v(n) + h^2 (p0 a(n) + p1 a(n-1))`,
/// `v(n+1) = v(n) + h (w0 a(n+1) + w1 a(n) + w2 a(n-1))`, with Beeman's
/// `p = (4, -1)/6`, `w = (2, 5, -1)/6`.
///
/// Start-up: `a(-1) = a(q0 - h v0 + h^2/2 a(q0))`, a second-order Taylor
/// step back (two force evaluations at the start, one a step after).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beeman {
    /// The claims.
    pub meta: SchemeMeta,
    /// The position weights `(p0, p1)` of `a(n)` and `a(n-1)`.
    pub position: [f64; 2],
    /// The velocity weights `(w0, w1, w2)` of `a(n+1)`, `a(n)`, `a(n-1)`.
    pub velocity: [f64; 3],
}

impl Scheme for Beeman {
    type Carry<R: Real, const D: usize> = BeemanCarry<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        h: R,
    ) -> BeemanCarry<R, D> {
        let a = scene.acceleration(&s.q);
        let back = s.q - s.v * h + a * (h * h * R::of(0.5));
        BeemanCarry {
            state: *s,
            a,
            a_previous: scene.acceleration(&back),
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut BeemanCarry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        let [p0, p1] = self.position.map(R::of);
        let [w0, w1, w2] = self.velocity.map(R::of);
        let q = c.state.q + c.state.v * h + (c.a * p0 + c.a_previous * p1) * (h * h);
        let a = scene.acceleration(&q);
        let v = c.state.v + (a * w0 + c.a * w1 + c.a_previous * w2) * h;
        c.state = State::new(q, v);
        c.a_previous = c.a;
        c.a = a;
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &BeemanCarry<R, D>, _: R) -> State<D, R> {
        c.state
    }
}

/// Beeman's algorithm with its published coefficients.
///
/// Global ORDER 2: eliminating the velocities gives exactly the two-step
/// Störmer-Verlet recursion `q(n+1) - 2 q(n) + q(n-1) = h^2 a(n)` for the
/// positions (from the second step on), whose global error is `O(h^2)`;
/// the velocities are a local third-order formula of those positions
/// (local error `h^3 a''/12`). As a map of `(q, v)` (start-up, one step,
/// output) neither symplectic nor symmetric (on the double well the step's
/// determinant is `1 - 0.40` at `h = 0.3`, and 50 steps of `h = 0.1` there
/// and back miss by 0.18), and it claims neither.
pub const BEEMAN: Beeman = Beeman {
    meta: explicit(
        "beeman",
        "Beeman's algorithm",
        2,
        false,
        false,
        1,
        "D. Beeman, J. Comput. Phys. 20, 130 (1976); M. P. Allen, D. J. Tildesley, Computer Simulation of Liquids (2017), 3.2.2",
    ),
    position: [4.0 / 6.0, -1.0 / 6.0],
    velocity: [2.0 / 6.0, 5.0 / 6.0, -1.0 / 6.0],
};

/// BROKEN: Beeman with a sign typo in the position update, `h^2 (4 a(n) +
/// a(n-1))/6` instead of `(4 a(n) - a(n-1))/6`.
///
/// The `h^2` coefficient sums to `5/6`, not `1/2`; eliminating the
/// velocities, the positions obey `q(n+1) - 2 q(n) + q(n-1) = h^2 (a(n) +
/// (a(n-1) - a(n-2))/3)`: Störmer's recursion with the force perturbed by
/// `-(h/3) da/dt`, and the first step's `q1` is `h^2/3 a(q0)` too far (a
/// velocity error `h/3 a(q0)` carried along). ORDER 1, with a relative
/// error of order `z w t / 3` (`1.1e-3` on the trimer and `2.3e-2` on the
/// Toda lattice at `T/1000`). Claims order 2.
pub const BEEMAN_SIGN_TYPO: Beeman = Beeman {
    meta: posing_as(
        BEEMAN.meta,
        "beeman-sign-typo",
        "Beeman's algorithm with +a(n-1) in the position update",
    ),
    position: [4.0 / 6.0, 1.0 / 6.0],
    velocity: BEEMAN.velocity,
};

/// BROKEN (a false claim): Beeman's algorithm, correct, claiming to be
/// time-symmetric because its positions are Störmer-Verlet's.
///
/// The positions are symmetric in that sense, but the scheme's map of
/// `(q, v)` is not: its velocity formula `v(n+1) = v(n) + h (2 a(n+1) +
/// 5 a(n) - a(n-1))/6` is not invariant under exchanging past and future,
/// and its start-up extrapolates `a(n-1)`; `h` then `-h` misses the start
/// (by 0.18 after 50 steps of `h = 0.1` each way on the double well, whose
/// scale is 1.6). Its energy does not drift: the positions are those of
/// the Störmer-Verlet recursion (bounded modified-energy error), and the
/// velocities a fixed local formula of three consecutive positions, so the
/// energy error stays an `O(h^2)` oscillation. Second order, not symplectic
/// (not claimed).
pub const BEEMAN_CLAIMS_SYMMETRIC: Beeman = Beeman {
    meta: SchemeMeta {
        symmetric: true,
        ..posing_as(
            BEEMAN.meta,
            "beeman-claims-symmetric",
            "Beeman's algorithm claiming time symmetry",
        )
    },
    ..BEEMAN
};

// ------------------------------------------------------ Adams-Bashforth-Moulton

/// What the Adams-Bashforth-Moulton scheme carries: the state and the last
/// four slopes `f = (v, a(q))`, newest first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdamsCarry<R: Real, const D: usize> {
    /// The synchronised state.
    pub state: State<D, R>,
    /// Velocity slopes `v(n), v(n-1), v(n-2), v(n-3)`.
    pub fv: [SVector<R, D>; 4],
    /// Acceleration slopes `a(n), ..., a(n-3)`.
    pub fa: [SVector<R, D>; 4],
}

/// The Adams-Bashforth-Moulton predictor-corrector in PECE mode on
/// `y = (q, v)`, `y' = f(y) = (v, a(q))`: predict with the four-step
/// Adams-Bashforth formula `y~ = y(n) + h/24 (55 f(n) - 59 f(n-1) + 37
/// f(n-2) - 9 f(n-3))`, evaluate, correct with a three-step Adams-Moulton
/// formula `y(n+1) = y(n) + h (g0 f~ + g1 f(n) + g2 f(n-1) + g3 f(n-2))`,
/// evaluate: two force evaluations per step.
///
/// Start-up: the history `y(-1), y(-2), y(-3)` from three classical RK4
/// steps of `-h` (local errors `O(h^5)`), or, with `cold_start` (a bug),
/// every past slope set to `f(y0)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Abm4 {
    /// The claims.
    pub meta: SchemeMeta,
    /// The corrector weights `(g0, g1, g2, g3)`.
    pub corrector: [f64; 4],
    /// Fill the history with `f(y0)` instead of computing it.
    pub cold_start: bool,
}

impl Scheme for Abm4 {
    type Carry<R: Real, const D: usize> = AdamsCarry<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        h: R,
    ) -> AdamsCarry<R, D> {
        let a0 = scene.acceleration(&s.q);
        let mut c = AdamsCarry {
            state: *s,
            fv: [s.v; 4],
            fa: [a0; 4],
        };
        if !self.cold_start {
            let mut y = *s;
            for k in 1..4 {
                // the classical RK4 never fails
                let _ = OneStep::advance(&Rk4, scene, &mut y, -h);
                c.fv[k] = y.v;
                c.fa[k] = scene.acceleration(&y.q);
            }
        }
        c
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut AdamsCarry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        const BASHFORTH: [f64; 4] = [55.0 / 24.0, -59.0 / 24.0, 37.0 / 24.0, -9.0 / 24.0];
        let (q0, v0) = (c.state.q, c.state.v);
        let (mut qp, mut vp) = (q0, v0);
        for (k, beta) in BASHFORTH.iter().enumerate() {
            let w = h * R::of(*beta);
            qp += c.fv[k] * w;
            vp += c.fa[k] * w;
        }
        let ap = scene.acceleration(&qp);
        let g = self.corrector.map(|x| h * R::of(x));
        let q = q0 + vp * g[0] + c.fv[0] * g[1] + c.fv[1] * g[2] + c.fv[2] * g[3];
        let v = v0 + ap * g[0] + c.fa[0] * g[1] + c.fa[1] * g[2] + c.fa[2] * g[3];
        let a = scene.acceleration(&q);
        c.fv = [v, c.fv[0], c.fv[1], c.fv[2]];
        c.fa = [a, c.fa[0], c.fa[1], c.fa[2]];
        c.state = State::new(q, v);
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &AdamsCarry<R, D>, _: R) -> State<D, R> {
        c.state
    }
}

/// The three-step Adams-Moulton weights `(9, 19, -5, 1)/24` (order 4).
pub(super) const MOULTON4: [f64; 4] = [9.0 / 24.0, 19.0 / 24.0, -5.0 / 24.0, 1.0 / 24.0];

/// The fourth-order Adams-Bashforth-Moulton pair (AB4 predictor, AM4
/// corrector, PECE) with an RK4 start-up.
///
/// ORDER 4: both formulas have order four, and in PECE mode the order is
/// `min(p_corrector, p_predictor + 1) = 4`; the start-up's local errors
/// `O(h^5)` keep it. Zero-stable (Adams: `rho(x) = x^3 (x - 1)`). Neither
/// symplectic nor symmetric, as claimed (a multistep method is not a
/// one-step map; its energy is not promised).
pub const ABM4: Abm4 = Abm4 {
    meta: explicit(
        "abm4-pece",
        "Adams-Bashforth-Moulton 4 (PECE, RK4 start-up)",
        4,
        false,
        false,
        2,
        "F. Bashforth, J. C. Adams (1883); F. R. Moulton, New Methods in Exterior Ballistics (1926); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), III.1",
    ),
    corrector: MOULTON4,
    cold_start: false,
};

/// BROKEN: [`ABM4`] with the first two corrector weights swapped,
/// `(19, 9, -5, 1)/24`.
///
/// The weights still sum to one (consistent, zero-stable), but the
/// first-moment condition `19 - 5 (-1) + 1 (-2) = 22` (in 24ths), not `12`
/// (`int_0^1 t dt = 1/2`): each corrected step carries a local error
/// `(22/24 - 1/2) h^2 f' = (5/12) h^2 f'`. ORDER 1, a relative error of
/// order `(5/12) z w t` (`5e-2` to `0.12` at `T/1000` on the paired scenes).
/// Claims order 4.
pub const ABM4_SWAPPED: Abm4 = Abm4 {
    meta: posing_as(
        ABM4.meta,
        "abm4-swapped-corrector",
        "Adams-Bashforth-Moulton 4 with the corrector weights 19 and 9 swapped",
    ),
    corrector: [19.0 / 24.0, 9.0 / 24.0, -5.0 / 24.0, 1.0 / 24.0],
    cold_start: false,
};

/// BROKEN: [`ABM4`] started cold, every past slope `f(-1), f(-2), f(-3)`
/// set to `f(y0)` (a start-up of order zero instead of RK4).
///
/// The past slopes are off by `-k h f'`, and they enter the first three
/// steps multiplied by `h`: with a constant history the predictor is
/// Euler's step and the first corrected step misses by `h^2 f'/8`, the next
/// two by similar amounts; those `O(h^2)` errors are then carried along like
/// a perturbed initial condition. ORDER 2 (capped by the start-up, the
/// formulas being fourth order), with a relative error of order `z^2` times
/// the orbit's sensitivity (`1.7e-4` on the planets, `3.9e-3` on the
/// eccentric Kepler orbit at `T/1000`). Claims order 4.
pub const ABM4_COLD_START: Abm4 = Abm4 {
    meta: posing_as(
        ABM4.meta,
        "abm4-cold-start",
        "Adams-Bashforth-Moulton 4 with the history filled with f(y0)",
    ),
    corrector: MOULTON4,
    cold_start: true,
};

// ------------------------------------------------------------- Lobatto IIIA-IIIB

/// Iterations an implicit solve may take.
pub const SOLVE_ITERATIONS: u32 = 60;

/// Units of round-off at which a solve counts as converged.
pub(super) const SOLVE_UNITS: f64 = 8.0;

/// What an implicit partitioned Runge-Kutta method carries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartitionedCarry<R: Real, const D: usize, const S: usize> {
    /// The synchronised state.
    pub state: State<D, R>,
    /// The last stage accelerations, the next solve's guess.
    pub k: [SVector<R, D>; S],
    /// Force evaluations spent since `start` (the start's one included).
    pub evaluations: u64,
}

/// An implicit partitioned Runge-Kutta method for `q' = v`, `v' = a(q)`:
/// `Q_i = q + h sum_j aq_ij V_j`, `V_i = v + h sum_j av_ij k_j`,
/// `k_i = a(Q_i)`, `q' = q + h sum b_i V_i`, `v' = v + h sum b_i k_i`. The
/// stage accelerations are found by fixed-point iteration from the previous
/// step's (`a(q0)` at the start), each iteration evaluating every stage,
/// until the stage positions stop moving at round-off; a solve that does not
/// get there in [`SOLVE_ITERATIONS`] fails and leaves the state unchanged.
///
/// With `closing_force_from_start` (a bug) the velocity update uses the
/// first stage's force `k_1` in place of the last stage's `k_S`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartitionedRk<const S: usize> {
    /// The claims; `force_evaluations` is `S` per iteration.
    pub meta: SchemeMeta,
    /// The matrix of the position stages.
    pub aq: [[f64; S]; S],
    /// The matrix of the velocity stages.
    pub av: [[f64; S]; S],
    /// The weights (shared).
    pub b: [f64; S],
    /// The nodes.
    pub c: [f64; S],
    /// Close the step with `k_1` instead of `k_S` (the bug).
    pub closing_force_from_start: bool,
}

impl<const S: usize> PartitionedRk<S> {
    /// The stage positions and velocities for stage accelerations `k`.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    pub(super) fn stages<R: Real, const D: usize>(
        &self,
        q: &SVector<R, D>,
        v: &SVector<R, D>,
        k: &[SVector<R, D>; S],
        h: R,
    ) -> ([SVector<R, D>; S], [SVector<R, D>; S]) {
        let mut vs = [*v; S];
        for (vi, row) in vs.iter_mut().zip(&self.av) {
            for (kj, &a) in k.iter().zip(row) {
                if a != 0.0 {
                    *vi += kj * (h * R::of(a));
                }
            }
        }
        let mut qs = [*q; S];
        for (qi, row) in qs.iter_mut().zip(&self.aq) {
            for (vj, &a) in vs.iter().zip(row) {
                if a != 0.0 {
                    *qi += vj * (h * R::of(a));
                }
            }
        }
        (qs, vs)
    }
}

impl<const S: usize> Scheme for PartitionedRk<S> {
    type Carry<R: Real, const D: usize> = PartitionedCarry<R, D, S>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        _: R,
    ) -> PartitionedCarry<R, D, S> {
        PartitionedCarry {
            state: *s,
            k: [scene.acceleration(&s.q); S],
            evaluations: 1,
        }
    }

    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut PartitionedCarry<R, D, S>,
        h: R,
    ) -> Result<(), StepFailure> {
        let (q0, v0) = (c.state.q, c.state.v);
        let units = R::of(SOLVE_UNITS) * R::default_epsilon();
        let mut k = c.k;
        let (mut qs, _) = self.stages(&q0, &v0, &k, h);
        let mut previous: Option<R> = None;
        let mut correction = R::zero();
        for _ in 0..SOLVE_ITERATIONS {
            for (ki, qi) in k.iter_mut().zip(&qs) {
                *ki = scene.acceleration(qi);
            }
            c.evaluations += S as u64;
            let (next, vs) = self.stages(&q0, &v0, &k, h);
            correction = R::zero();
            let mut size = (v0 * h).norm_squared();
            for (n, q) in next.iter().zip(&qs) {
                correction += (n - q).norm_squared();
                size += q0.norm_squared() + n.norm_squared();
            }
            qs = next;
            if !(correction.is_finite() && size.is_finite()) {
                break;
            }
            let settled = correction == R::zero() || previous.is_some_and(|p| correction >= p);
            if correction <= units * units * size && settled {
                let (mut dq, mut dv) = (SVector::<R, D>::zeros(), SVector::<R, D>::zeros());
                for i in 0..S {
                    let ki = if self.closing_force_from_start && i == S - 1 {
                        k[0]
                    } else {
                        k[i]
                    };
                    dq += vs[i] * (h * R::of(self.b[i]));
                    dv += ki * (h * R::of(self.b[i]));
                }
                c.state = State::new(q0 + dq, v0 + dv);
                c.k = k;
                return Ok(());
            }
            previous = Some(correction);
        }
        Err(StepFailure::NotConverged {
            iterations: SOLVE_ITERATIONS,
            residual: correction.sqrt().to_subset().unwrap_or(f64::NAN),
        })
    }

    fn state<R: Real, const D: usize>(&self, c: &PartitionedCarry<R, D, S>, _: R) -> State<D, R> {
        c.state
    }

    fn solver_evaluations<R: Real, const D: usize>(
        &self,
        c: &PartitionedCarry<R, D, S>,
    ) -> Option<u64> {
        Some(c.evaluations)
    }
}

/// The three-stage Lobatto IIIA matrix.
pub(super) const LOBATTO_IIIA: [[f64; 3]; 3] = [
    [0.0, 0.0, 0.0],
    [5.0 / 24.0, 1.0 / 3.0, -1.0 / 24.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
];

/// The three-stage Lobatto IIIB matrix.
pub(super) const LOBATTO_IIIB: [[f64; 3]; 3] = [
    [1.0 / 6.0, -1.0 / 6.0, 0.0],
    [1.0 / 6.0, 1.0 / 3.0, 0.0],
    [1.0 / 6.0, 5.0 / 6.0, 0.0],
];

/// The claims of the Lobatto IIIA-IIIB pair.
pub(super) const LOBATTO_PAIR_META: SchemeMeta = SchemeMeta {
    id: "lobatto-iiia-iiib3",
    name: "Lobatto IIIA-IIIB partitioned pair (3 stages, order 4)",
    order: 4,
    symplectic: true,
    symmetric: true,
    force_evaluations: 3,
    implicit: true,
    reference: "L. O. Jay, SIAM J. Numer. Anal. 33, 368 (1996); E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration (2006), II.2.2 and VI.4",
    phase_error: None,
};

/// The three-stage Lobatto IIIA-IIIB pair: positions by Lobatto IIIA,
/// velocities by Lobatto IIIB, `b = (1, 4, 1)/6`, `c = (0, 1/2, 1)`.
///
/// On `q'' = a(q)` it reduces to an implicit Runge-Kutta-Nyström method
/// with `k1 = a(q)`, `k2 = a(q + h/2 v + h^2 (k1/12 + k2/24))` (the only
/// implicit stage), `q' = q + h v + h^2 (k1/6 + k2/3)`, `k3 = a(q')`,
/// `v' = v + h (k1 + 4 k2 + k3)/6`. ORDER 4 (`2s - 2`), SYMPLECTIC (`b_i
/// av_ij + b_j aq_ji = b_i b_j` for all `i, j`; as an RKN, `b_bar_i =
/// b_i (1 - c_i)` and `b_i (b_bar_j - a_ij) = b_j (b_bar_i - a_ji)`),
/// SYMMETRIC (the pair is its own adjoint), implicit: the partitioned
/// analogue of Störmer-Verlet, which is the two-stage pair.
pub const LOBATTO_IIIA_IIIB: PartitionedRk<3> = PartitionedRk {
    meta: LOBATTO_PAIR_META,
    aq: LOBATTO_IIIA,
    av: LOBATTO_IIIB,
    b: [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    c: [0.0, 0.5, 1.0],
    closing_force_from_start: false,
};

/// BROKEN: the Lobatto IIIA-IIIB pair with the IIIA matrix typed for the
/// velocity stages too: the (non-partitioned) three-stage Lobatto IIIA
/// collocation method, claiming the pair's symplecticity.
///
/// Lobatto IIIA is still ORDER 4 and SYMMETRIC (a symmetric collocation
/// method), so its energy does not drift on reversible integrable scenes,
/// but it is NOT symplectic: `2 b1 a11 = 0`, not `b1^2 = 1/36`. On linear
/// problems it is the (2,2) Padé approximant of the exponential, which is
/// symplectic: the defect shows only through the force's curvature (the
/// tests measure `det - 1 = 6.4e-4` at `h = 0.3` on the double well and
/// `|J^T W J - W| = 3e-4` at `h = T/10` on the Toda lattice). Claims order
/// 4, symplectic, symmetric.
pub const LOBATTO_IIIA_BOTH: PartitionedRk<3> = PartitionedRk {
    meta: posing_as(
        LOBATTO_PAIR_META,
        "lobatto-iiia-for-both",
        "Lobatto IIIA-IIIB with the IIIA matrix used for the velocities too",
    ),
    av: LOBATTO_IIIA,
    ..LOBATTO_IIIA_IIIB
};

/// BROKEN: the Lobatto IIIA-IIIB pair closing its velocity update with the
/// force at the start of the step, `v' = v + h (k1 + 4 k2 + k1)/6`, instead
/// of the force `k3 = a(q')` at its end (a first-same-as-last cache read
/// before it is refreshed).
///
/// The velocity weights become `(1/3, 2/3, 0)` at nodes `(0, 1/2, 1)`:
/// `sum b c = 1/3`, not `1/2`, a local velocity error `-h^2/6 da/dt`:
/// ORDER 1. The force at the end no longer enters, so the step is NOT
/// symmetric, and NOT symplectic (`b_bar_1 = 1/6` against `b_1 (1 - c_1) =
/// 1/3`): on the oscillator the step's determinant is `1 + z^2/6 + O(z^4)`,
/// an exponential energy growth of `e^(z^2/6)` a step, which the long run
/// (`z = 2 pi/100`, `10^6` steps) turns into a blow-up. Claims order 4,
/// symplectic, symmetric.
pub const LOBATTO_STALE_CLOSING_FORCE: PartitionedRk<3> = PartitionedRk {
    meta: posing_as(
        LOBATTO_PAIR_META,
        "lobatto-iiia-iiib-stale-closing-force",
        "Lobatto IIIA-IIIB closing the velocity with the start-of-step force",
    ),
    closing_force_from_start: true,
    ..LOBATTO_IIIA_IIIB
};
