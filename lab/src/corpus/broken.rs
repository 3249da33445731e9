//! Broken schemes: plausible bugs, each claiming what the correct scheme
//! claims (unless its documentation says otherwise) while its steps, its
//! data or its claims are wrong. Each item's documentation states exactly what
//! is wrong and what the scheme really is, derived from theory: its true
//! order, whether it is still symplectic and symmetric, and the error term
//! that appears.
//!
//! Where the bug is data (a table of weights, a tableau, a claim) the scheme
//! reuses the correct stepper with the wrong data; only bugs in code (a stale
//! force, a missing start-up term, unsynchronised output, a truncated solve)
//! have small steppers of their own, which delegate to the catalogue's where
//! they can.
//!
//! Notation: `z = h w0` on the oscillator `x'' = -w0^2 x`; `D(d)` a drift
//! `q += d h v`, `K(c)` a kick `v += c h a(q)`; for a composition of velocity
//! Verlet with weights `w_i`, Verlet's own modified field is `h X1 + h^3 X3 +
//! ...`, so the composition's is `h (sum w) X1 + h^3 (sum w^3) X3 + ...`
//! (see [`stepladder::scheme::VerletComposition`]).

use super::correct::{DORMAND_PRINCE5, RUTH3, RUTH3_KICKS, TRAPEZOIDAL};
use stepladder::scene::Scene;
use stepladder::scheme::{
    EULER_CROMER, ExplicitRk, FOREST_RUTH, Flow, ImplicitMidpoint, ImplicitRk, KAHAN_LI8, Leapfrog,
    OneStep, Rk4, Scheme, SchemeMeta, SplittingTable, StepFailure, StormerVerlet, VELOCITY_VERLET,
    VerletComposition, YOSHIDA6,
};
use stepladder::state::{Real, State};

/// The correct scheme's claims under another id and name, with no
/// hand-derived phase error.
const fn posing_as(base: SchemeMeta, id: &'static str, name: &'static str) -> SchemeMeta {
    SchemeMeta {
        id,
        name,
        phase_error: None,
        ..base
    }
}

// ------------------------------------------------------ rounded or perturbed weights

/// Forest-Ruth's weights retyped with four decimals.
const FOREST_RUTH_4_DECIMALS_STAGES: VerletComposition<3, 4> =
    VerletComposition::new([1.3512, -1.7024, 1.3512]);

/// [`FOREST_RUTH`] with its weights retyped as `(1.3512, -1.7024, 1.3512)`.
///
/// Still symplectic and symmetric (a palindromic composition of Verlet), and
/// `sum w = 1` exactly in decimals (to one rounding in doubles), but the
/// fourth-order condition `sum w^3 = 0` is lost: `sum w^3 = 2 (1.3512)^3 -
/// (1.7024)^3 = 4.6277632e-5`. The step's modified field is `h X1 +
/// 4.63e-5 h^3 X3 + O(h^5)`: ORDER 2, with an error `4.63e-5` times velocity
/// Verlet's at the same step (a relative frequency error `1.93e-6 z^2` on the
/// oscillator) on top of Forest-Ruth's own fourth-order error (`0.068 z^4`
/// on the oscillator), which hides it at large steps: the measured order is 4
/// down to `h = T/400`, the two terms (of opposite signs) cancel near
/// `T/1200`, and the order is 2 below `T/3000`. Claims order 4.
pub const FOREST_RUTH_4_DECIMALS: SplittingTable = FOREST_RUTH_4_DECIMALS_STAGES.table(posing_as(
    FOREST_RUTH.meta,
    "forest-ruth-4-decimals",
    "Forest-Ruth with weights retyped to four decimals",
));

/// Yoshida's solution A with the first weight `+1e-8`.
const YOSHIDA6_FIRST_WEIGHT_STAGES: VerletComposition<7, 8> = {
    let w = YOSHIDA6.drift;
    VerletComposition::new([w[0] + 1e-8, w[1], w[2], w[3], w[4], w[5], w[6]])
};

/// [`YOSHIDA6`] with its first weight changed by `+1e-8`.
///
/// `sum w = 1 + 1e-8`: ORDER 0, the step is to leading order Verlet's
/// composition over a time rescaled by `1 + 1e-8` (the drift and the kick
/// weights both sum to `1 + 1e-8`), so the error tends to a phase error of
/// `1e-8 w0 t` as `h -> 0` instead of to zero. The palindrome is broken: NOT
/// symmetric, though only just: Verlet's modified field has odd powers of `h`
/// only, so the reversal-odd part of the composition's first appears in the
/// `h^4 [X1, X3]` term of the Baker-Campbell-Hausdorff series, with the
/// coefficient `sum_(i<j) (w_j w_i^3 - w_i w_j^3) / 2`, which vanishes for a
/// palindrome and is `O(1e-8)` here: `h` then `-h` misses the start by
/// `O(1e-8 h^4)` a step (1.4e-10 after 50 steps of `h = 0.4` on the
/// anharmonic well, 4.4e-13 at `h = 0.1`). Still symplectic. Claims order 6,
/// symmetric.
pub const YOSHIDA6_FIRST_WEIGHT: SplittingTable = YOSHIDA6_FIRST_WEIGHT_STAGES.table(posing_as(
    YOSHIDA6.meta,
    "yoshida6-first-weight",
    "Yoshida sixth order with the first weight off by 1e-8",
));

/// Yoshida's solution A, outer weights `+1e-8`, middle weight `-2e-8`.
const YOSHIDA6_PALINDROME_STAGES: VerletComposition<7, 8> = {
    let w = YOSHIDA6.drift;
    VerletComposition::new([
        w[0] + 1e-8,
        w[1],
        w[2],
        w[3] - 2e-8,
        w[4],
        w[5],
        w[6] + 1e-8,
    ])
};

/// [`YOSHIDA6`] with both outer weights `w_3` changed by `+1e-8` and the
/// middle weight `w_0` by `-2e-8`.
///
/// The palindrome and `sum w = 1` are kept: symplectic and symmetric, and the
/// even orders still cancel, but `sum w^3` moves from 0 to `6e-8 (w_3^2 -
/// w_0^2) = -6.6855e-8`: the modified field is `h X1 - 6.69e-8 h^3 X3 + ...`,
/// ORDER 2 with a tiny coefficient (`6.69e-8` times velocity Verlet's error,
/// a relative frequency error `-2.79e-9 z^2` on the oscillator), visible only
/// at steps small enough for the sixth-order error to fall below it: on the
/// oscillator the measured order is 6 at `T/50`, the two terms cancel near
/// `T/200`, and the order is 2 from `T/400` to `T/3200` (errors `1e-11` to
/// `5e-14`, just above round-off). Claims order 6.
pub const YOSHIDA6_PALINDROME: SplittingTable = YOSHIDA6_PALINDROME_STAGES.table(posing_as(
    YOSHIDA6.meta,
    "yoshida6-palindrome",
    "Yoshida sixth order with a palindromic 1e-8 perturbation",
));

/// Kahan and Li's weights rounded to eight significant digits.
const KAHAN_LI8_8_DIGITS_STAGES: VerletComposition<17, 18> = {
    const G: [f64; 9] = [
        0.13020248,
        0.56116298,
        -0.38947496,
        0.15884191,
        -0.39590389,
        0.18453964,
        0.25837439,
        0.29501172,
        -0.60550853,
    ];
    VerletComposition::new([
        G[0], G[1], G[2], G[3], G[4], G[5], G[6], G[7], G[8], G[7], G[6], G[5], G[4], G[3], G[2],
        G[1], G[0],
    ])
};

/// [`KAHAN_LI8`] with its nine weights rounded to eight significant digits
/// (`0.13020248, 0.56116298, -0.38947496, 0.15884191, -0.39590389,
/// 0.18453964, 0.25837439, 0.29501172, -0.60550853`, palindromic).
///
/// The rounding errors (up to `4e-9` each) do not cancel: `sum w - 1 =
/// +1.0e-8` (exactly, in decimals). ORDER 0: the flow of a time rescaled by
/// `1 + 1e-8`, a phase error `1e-8 w0 t` that does not shrink with `h`;
/// behind it `sum w^3 = 6.2e-9` and `sum w^5 = 2.3e-9` would leave order 2
/// even with the sum repaired. The palindrome is kept: still symplectic and
/// symmetric. Claims order 8.
pub const KAHAN_LI8_8_DIGITS: SplittingTable = KAHAN_LI8_8_DIGITS_STAGES.table(posing_as(
    KAHAN_LI8.meta,
    "kahan-li8-8-digits",
    "Kahan-Li eighth order with weights rounded to 8 digits",
));

/// Ruth's drift weights with the first two swapped.
const RUTH3_SWAPPED_DRIFTS_WEIGHTS: [f64; 3] = [-2.0 / 3.0, 2.0 / 3.0, 1.0];

/// [`RUTH3`] with its first two drift weights swapped:
/// `K(7/24) D(-2/3) K(3/4) D(2/3) K(-1/24) D(1)`.
///
/// The weights still sum to one (drifts and kicks), and the step is still a
/// sequence of exact flows, so symplectic (and not symmetric, as before), but
/// the second-order condition `sigma = sum_(kick i before drift j) c_i d_j =
/// 1/2` becomes `sigma = 7/24 + (3/4)(5/3) - 1/24 = 3/2`: the log of the step
/// gains `(sigma - 1/2) h^2 [D, K] = h^2 [D, K]` (the Lie bracket of the
/// drift and kick fields, whose Hamiltonian is `v . grad V` up to sign).
/// ORDER 1. Swapping any two of Ruth's drift weights gives order 1 as well
/// (`sigma = 41/72` or `19/72`). Claims order 3.
pub const RUTH3_SWAPPED_DRIFTS: SplittingTable = SplittingTable::new(
    posing_as(
        RUTH3.meta,
        "ruth3-swapped-drifts",
        "Ruth's third order with two drift weights swapped",
    ),
    Flow::Kick,
    &RUTH3_SWAPPED_DRIFTS_WEIGHTS,
    &RUTH3_KICKS,
);

// ------------------------------------------------------------ Runge-Kutta typos

/// The classical RK4 tableau, the base of the typos below.
pub const RK4_A: [[f64; 4]; 4] = [
    [0.0, 0.0, 0.0, 0.0],
    [0.5, 0.0, 0.0, 0.0],
    [0.0, 0.5, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
];
/// RK4's weights.
pub const RK4_B: [f64; 4] = [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0];
/// RK4's nodes.
const RK4_C: [f64; 4] = [0.0, 0.5, 0.5, 1.0];

/// RK4 with its third stage formed from the first stage's slopes instead of
/// the second's: `k3 = f(y + h/2 k1)` (`a31 = 1/2`, `a32 = 0`).
///
/// The order-1 and order-2 conditions and the bushy order-3 one `sum b c^2 =
/// 1/3` still hold (the nodes are unchanged), but the order-3 condition of
/// the tall tree, `sum b_i a_ij c_j = 1/6`, gives `b4 a43 c3 = 1/12`: off by
/// `-1/12`. ORDER 2; on a linear problem the step is `1 + z + z^2/2 +
/// z^3/12` against `exp(z)`, a local error `z^3/12`. Neither symplectic nor
/// symmetric, as RK4. Claims order 4.
pub const RK4_STAGE3_TYPO: ExplicitRk<4> = ExplicitRk::new(
    posing_as(
        Rk4::META,
        "rk4-stage3-typo",
        "RK4 with the third stage built from k1",
    ),
    [
        [0.0, 0.0, 0.0, 0.0],
        [0.5, 0.0, 0.0, 0.0],
        [0.5, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ],
    RK4_B,
    RK4_C,
);

/// RK4 with its weights typed `(1, 2, 1, 2)/6` instead of `(1, 2, 2, 1)/6`.
///
/// `sum b = 1` still, but `sum b c = (2/6)(1/2) + (1/6)(1/2) + (2/6)(1) =
/// 7/12`, not `1/2`: the order-2 condition fails by `+1/12`. ORDER 1; on a
/// linear problem the step is `1 + z + 7/12 z^2 + ...`. Neither symplectic nor
/// symmetric, as RK4. Claims order 4.
pub const RK4_WEIGHTS_TYPO: ExplicitRk<4> = ExplicitRk::new(
    posing_as(
        Rk4::META,
        "rk4-weights-typo",
        "RK4 with weights typed (1, 2, 1, 2)/6",
    ),
    RK4_A,
    [1.0 / 6.0, 2.0 / 6.0, 1.0 / 6.0, 2.0 / 6.0],
    RK4_C,
);

/// [`DORMAND_PRINCE5`] with its first weight `35/384 = 0.0911458...` rounded
/// to four decimals, `0.0911`.
///
/// `sum b - 1 = 0.0911 - 35/384 = -11/240000 = -4.58e-5`: every step adds
/// `-4.58e-5 h f(y_n)` to the correct one, which is to leading order the flow
/// over a time rescaled by `1 - 4.58e-5`. ORDER 0: the error tends to
/// `4.58e-5 t |f|` as `h -> 0` (a phase error `4.58e-5 w0 t` on the
/// oscillator). Neither symplectic nor symmetric, as before. Claims order 5.
pub const DORMAND_PRINCE5_ROUNDED_WEIGHT: ExplicitRk<6> = {
    let mut t = DORMAND_PRINCE5;
    t.b[0] = 0.0911;
    t.meta = posing_as(
        DORMAND_PRINCE5.meta,
        "dormand-prince5-rounded-weight",
        "Dormand-Prince fifth order with b1 rounded to 4 decimals",
    );
    t
};

/// `sqrt(3)/6` as typed from a table: `0.2887`.
pub const SQRT3_6_TYPED: f64 = 0.2887;

/// The two-stage Gauss method with `sqrt(3)/6 = 0.288675...` typed as
/// `0.2887` everywhere (nodes and matrix).
///
/// With `s = 0.2887` the tableau keeps `sum b = 1`, `sum b c = 1/2`, the
/// symplecticity conditions `b_i a_ij + b_j a_ji = b_i b_j` and the symmetry
/// conditions exactly, for any `s`: still symplectic and symmetric. But both
/// order-3 conditions need `s^2 = 1/12`: `sum b c^2 - 1/3 = s^2 - 1/12 =
/// +1.43567e-5` and `sum b a c - 1/6 = -(s^2 - 1/12) = -1.43567e-5`. ORDER 2
/// with a tiny coefficient: on the oscillator the step is `(1 + z/2 + s^2
/// z^2)/(1 - z/2 + s^2 z^2)`, of modulus one, with the relative frequency
/// error `(s^2 - 1/12) z^2 - z^4/720 + ...`; the second-order term dominates
/// below `z = sqrt(720 (s^2 - 1/12)) = 0.10` (the two cancel there). Claims
/// order 4.
pub const GAUSS4_ROUNDED: ImplicitRk<2> = ImplicitRk::new(
    posing_as(
        super::correct::GAUSS4.meta,
        "gauss4-rounded",
        "Gauss-Legendre (2 stages) with sqrt(3)/6 typed as 0.2887",
    ),
    [[0.25, 0.25 - SQRT3_6_TYPED], [0.25 + SQRT3_6_TYPED, 0.25]],
    [0.5, 0.5],
    [0.5 - SQRT3_6_TYPED, 0.5 + SQRT3_6_TYPED],
);

// --------------------------------------------------------------- bugs in code

/// Velocity Verlet whose closing half kick reuses the opening acceleration
/// `a(q_n)` (a stale force): `v += h/2 a(q_n)`, `q += h v`, `v += h/2 a(q_n)`,
/// i.e. `q' = q + h v + h^2/2 a(q)`, `v' = v + h a(q)`.
///
/// The position is still second-order accurate, but the velocity is explicit
/// Euler's (local error `h^2/2 da/dt`): ORDER 1. NOT symplectic: on the
/// oscillator the step is `[[1 - z^2/2, h], [-w0^2 h, 1]]` with determinant
/// `1 + z^2/2`, so the energy grows. NOT symmetric. One force evaluation per
/// step. Claims velocity Verlet's order 2, symplecticity and symmetry.
#[derive(Clone, Copy, Debug)]
pub struct StaleKickVerlet {
    /// The (false) claims.
    pub meta: SchemeMeta,
}

impl OneStep for StaleKickVerlet {
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
        let half = h * R::of(0.5);
        let a = scene.acceleration(&s.q);
        s.v += a * half;
        s.q += s.v * h;
        s.v += a * half; // the bug: a(q_n), not a(q_(n+1))
        Ok(())
    }
}

/// The stale-force velocity Verlet (see [`StaleKickVerlet`]).
pub const STALE_KICK_VERLET: StaleKickVerlet = StaleKickVerlet {
    meta: posing_as(
        VELOCITY_VERLET.meta,
        "verlet-stale-kick",
        "velocity Verlet with a stale closing kick",
    ),
};

/// The catalogue's [`Leapfrog`] with a start-up or output bug: its steps are
/// the catalogue's, only `start` (the half kick `v(1/2) = v0 + h/2 a(q0)`)
/// or `state` (the synchronisation `v(n) = v(n+1/2) - h/2 a(q(n))`) is
/// broken, as the flags say.
#[derive(Clone, Copy, Debug)]
pub struct LeapfrogBug {
    /// The (false) claims.
    pub meta: SchemeMeta,
    /// Start with `v(1/2) = v0 + h/2 a(q0)`; when false, `v(1/2) = v0`.
    pub half_kick_at_start: bool,
    /// Hand out `v(n) = v(n+1/2) - h/2 a(q(n))`; when false, `v(n+1/2)`.
    pub synchronised_output: bool,
}

impl Scheme for LeapfrogBug {
    type Carry<R: Real, const D: usize> = <Leapfrog as Scheme>::Carry<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        h: R,
    ) -> Self::Carry<R, D> {
        let mut c = Leapfrog.start(scene, s, h);
        if !self.half_kick_at_start {
            c.v_half = s.v;
        }
        c
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut Self::Carry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        Leapfrog.step(scene, c, h)
    }

    fn state<R: Real, const D: usize>(&self, c: &Self::Carry<R, D>, h: R) -> State<D, R> {
        if self.synchronised_output {
            Leapfrog.state(c, h)
        } else {
            State::new(c.q, c.v_half)
        }
    }
}

/// Leap-frog that hands out its half-step velocity `v(n+1/2)` as the
/// whole-step `v(n)` (unsynchronised output).
///
/// The positions are leap-frog's, second order; the velocity handed out is
/// off by `v(n+1/2) - v(n) = h/2 a(q(n)) + O(h^2)`: ORDER 1 in `v`, hence in
/// phase space. The map from a state to the next output, `K(1/2) D(1) K(1)`,
/// is still symplectic, but NOT symmetric: `h` then `-h` from the output
/// returns `O(h)` off. Claims leap-frog's order 2 and symmetry.
pub const LEAPFROG_HALF_STEP_OUTPUT: LeapfrogBug = LeapfrogBug {
    meta: posing_as(
        Leapfrog::META,
        "leapfrog-half-step-output",
        "leap-frog handing out its half-step velocity",
    ),
    half_kick_at_start: true,
    synchronised_output: false,
};

/// Leap-frog started without the initial half kick: `v(1/2) = v0`.
///
/// Every later step is leap-frog's, but it starts from a velocity off by
/// `-h/2 a(q0)`, an `O(h)` error carried along the whole orbit: ORDER 1. The
/// whole run is leap-frog composed with the kick `K(-1/2)` at the start, so
/// still symplectic (the one-step map from a state is `D(1) K(1/2)`), but NOT
/// symmetric: `h` then `-h` returns `O(h)` off. Claims order 2, symmetric.
pub const LEAPFROG_NO_HALF_KICK: LeapfrogBug = LeapfrogBug {
    meta: posing_as(
        Leapfrog::META,
        "leapfrog-no-half-kick",
        "leap-frog started without the half kick",
    ),
    half_kick_at_start: false,
    synchronised_output: true,
};

/// The two-step Störmer-Verlet scheme started with the Euler step
/// `q1 = q0 + h v0`, the `h^2/2 a(q0)` term forgotten.
///
/// The recursion `q(n+1) = 2 q(n) - q(n-1) + h^2 a(q(n))` is the catalogue's;
/// the start-up error `-h^2/2 a(q0)` in `q1` is a velocity error `-h/2 a(q0)`
/// that the recursion carries along (it grows like `n h^2`, like an initial
/// velocity error): ORDER 1. It is the same algorithm as
/// [`LEAPFROG_NO_HALF_KICK`] (the same positions, the same synchronised
/// velocities, to round-off): the correct run composed with a kick `K(-1/2)`
/// at the start (the map from a state to the next output is `D(1) K(1/2)`),
/// still symplectic, NOT symmetric. Claims order 2, symmetric.
#[derive(Clone, Copy, Debug)]
pub struct StormerEulerStart {
    /// The (false) claims.
    pub meta: SchemeMeta,
}

impl Scheme for StormerEulerStart {
    type Carry<R: Real, const D: usize> = <StormerVerlet as Scheme>::Carry<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        h: R,
    ) -> Self::Carry<R, D> {
        let mut c = StormerVerlet.start(scene, s, h);
        // q(-1) such that the first step gives q1 = 2 q0 - q(-1) + h^2 a0 = q0 + h v0
        c.previous = s.q - s.v * h + c.a * (h * h);
        c
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut Self::Carry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        StormerVerlet.step(scene, c, h)
    }

    fn state<R: Real, const D: usize>(&self, c: &Self::Carry<R, D>, h: R) -> State<D, R> {
        StormerVerlet.state(c, h)
    }
}

/// Two-step Störmer-Verlet with the Euler start (see [`StormerEulerStart`]).
pub const STORMER_EULER_START: StormerEulerStart = StormerEulerStart {
    meta: posing_as(
        StormerVerlet::META,
        "stormer-verlet-euler-start",
        "two-step Störmer-Verlet started with q1 = q0 + h v0",
    ),
};

/// The implicit midpoint rule `y1 = y0 + h f((y0 + y1)/2)` with its solve
/// truncated: an explicit Euler predictor `y1 = y0 + h f(y0)`, then exactly
/// `iterations` fixed-point iterations, no convergence test.
///
/// Each iteration multiplies the distance to the midpoint rule's solution by
/// `O(h)`: from the predictor's `O(h^2)`, two iterations leave `O(h^4)` per
/// step, below the rule's own `O(h^3)` local error, so ORDER 2 holds; but the
/// `O(h^4)` remainder is neither symplectic nor symmetric. On the oscillator
/// the step is `1 + z + z^2/2 + z^3/4` (`y = (q, v/w0)`), whose modulus
/// squared is `1 - z^4/4 + z^6/16` (the determinant: the energy decays) and
/// `R(z) R(-z) = 1 - z^4/4 - z^6/16` (not the identity after `h` then `-h`).
/// It is explicit now: `1 + iterations` force evaluations per step.
#[derive(Clone, Copy, Debug)]
pub struct TruncatedMidpoint {
    /// The claims: the midpoint rule's order, symplecticity and symmetry,
    /// with an honest `implicit: false` and force count.
    pub meta: SchemeMeta,
    /// Fixed-point iterations after the predictor.
    pub iterations: u32,
}

impl OneStep for TruncatedMidpoint {
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
        let half = R::of(0.5);
        let (q0, v0) = (s.q, s.v);
        let (mut q1, mut v1) = (q0 + v0 * h, v0 + scene.acceleration(&q0) * h);
        for _ in 0..self.iterations {
            let a = scene.acceleration(&((q0 + q1) * half));
            (q1, v1) = (q0 + (v0 + v1) * (h * half), v0 + a * h);
        }
        *s = State::new(q1, v1);
        Ok(())
    }
}

/// The midpoint rule truncated to two iterations (see [`TruncatedMidpoint`]).
pub const MIDPOINT_TWO_ITERATIONS: TruncatedMidpoint = TruncatedMidpoint {
    meta: SchemeMeta {
        implicit: false,
        force_evaluations: 3,
        ..posing_as(
            ImplicitMidpoint::META,
            "implicit-midpoint-two-iterations",
            "implicit midpoint rule truncated to two fixed-point iterations",
        )
    },
    iterations: 2,
};

/// Velocity Verlet with the acceleration's sign flipped in both kicks (the
/// kick weights `-1/2, -1/2`): it integrates `q'' = -a(q)`.
///
/// A correct velocity Verlet for the wrong equation: symplectic and symmetric
/// (a palindromic splitting, for the Hamiltonian `|v|^2/2 - V`), second order
/// towards the wrong solution, so NO convergence to the true one: the error
/// tends to the `O(1)` distance between the two flows as `h -> 0`. On the
/// oscillator it integrates `x'' = +w0^2 x` and grows like `cosh(w0 t)` (the
/// run reaches the blow-up bound before `2 sqrt(2)` periods); in a well it
/// follows the inverted potential. Claims velocity Verlet's order 2.
pub const VERLET_SIGN_FLIPPED: SplittingTable = SplittingTable::new(
    posing_as(
        VELOCITY_VERLET.meta,
        "verlet-sign-flipped",
        "velocity Verlet with the force's sign flipped",
    ),
    Flow::Kick,
    &[1.0],
    &[-0.5, -0.5],
);

// ------------------------------------------------------------------ wrong claims

/// RK4, the steps correct (the classical tableau), claiming to be symplectic.
///
/// It is not: no explicit Runge-Kutta method is (the condition `b_i a_ij +
/// b_j a_ji = b_i b_j` fails at `i = j = 1`: `0` against `1/36`); on the
/// oscillator each step multiplies the energy (and the determinant) by
/// `1 - z^6/72 + z^8/576`. Order 4 and not symmetric, as claimed.
pub const RK4_CLAIMS_SYMPLECTIC: ExplicitRk<4> = ExplicitRk::new(
    SchemeMeta {
        symplectic: true,
        ..posing_as(
            Rk4::META,
            "rk4-claims-symplectic",
            "RK4 claiming to be symplectic",
        )
    },
    RK4_A,
    RK4_B,
    RK4_C,
);

/// Euler-Cromer (the catalogue's weights, `K(1) D(1)`) claiming to be
/// symmetric.
///
/// It is not: its adjoint is `D(1) K(1)`, the other symplectic Euler; `h`
/// then `-h` leaves an `O(h^2)` error per step pair. First order and
/// symplectic, as claimed.
pub const EULER_CROMER_CLAIMS_SYMMETRIC: SplittingTable = SplittingTable {
    meta: SchemeMeta {
        symmetric: true,
        ..posing_as(
            EULER_CROMER.meta,
            "euler-cromer-claims-symmetric",
            "Euler-Cromer claiming to be symmetric",
        )
    },
    ..EULER_CROMER
};

/// The implicit trapezoidal rule (the correct tableau and solve) claiming to
/// be symplectic.
///
/// True on the linear oscillator, where it is the same map as the implicit
/// midpoint rule, `(1 + z/2)/(1 - z/2)`; false on nonlinear scenes, where
/// `b_i a_ij + b_j a_ji = b_i b_j` fails (`0` against `1/4` at `i = j = 1`)
/// and the step's Jacobian has a determinant `1 + O(h^3)` off one. Second
/// order and symmetric, as claimed.
pub const TRAPEZOIDAL_CLAIMS_SYMPLECTIC: ImplicitRk<2> = ImplicitRk {
    meta: SchemeMeta {
        symplectic: true,
        ..posing_as(
            TRAPEZOIDAL.meta,
            "implicit-trapezoidal-claims-symplectic",
            "implicit trapezoidal rule claiming to be symplectic",
        )
    },
    ..TRAPEZOIDAL
};

/// Velocity Verlet (the catalogue's steps) claiming order 3: an overclaim.
/// It is second order (symmetric, so its order is even, and `h^3 X3` is not
/// zero); symplectic and symmetric as claimed.
pub const VERLET_CLAIMS_ORDER3: SplittingTable = SplittingTable {
    meta: SchemeMeta {
        order: 3,
        ..posing_as(
            VELOCITY_VERLET.meta,
            "velocity-verlet-claims-order3",
            "velocity Verlet claiming order 3",
        )
    },
    ..VELOCITY_VERLET
};

/// Velocity Verlet (the catalogue's steps) claiming order 1: an underclaim.
/// It is second order; symplectic and symmetric as claimed.
pub const VERLET_CLAIMS_ORDER1: SplittingTable = SplittingTable {
    meta: SchemeMeta {
        order: 1,
        ..posing_as(
            VELOCITY_VERLET.meta,
            "velocity-verlet-claims-order1",
            "velocity Verlet claiming order 1",
        )
    },
    ..VELOCITY_VERLET
};

// ------------------------------------------------- another equation, a bias, a cost

/// What is wrong with a [`VerletWithBug`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VerletBug {
    /// Velocity Verlet whose kicks give every component the acceleration of the
    /// first: `v_k += (h/2) a_0(q)` for every `k`.
    ///
    /// The bug changes the equation, not the method: the step is exactly
    /// velocity Verlet for `q'' = a_0(q) (1, 1, ..., 1)`, so it converges at ORDER
    /// 2 to the solution of that equation. The field `a_0 (1, ..., 1)` is not
    /// a gradient unless `a_0` depends on `sum q` alone, so the map is NOT
    /// symplectic in general; it is still symmetric (the Verlet form of any
    /// field is). On a scene without an exact solution the
    /// runs at `h` and `h/2` agree to `O(h^2)`, so the half-step comparison sees
    /// order 2; the energy, momentum and angular momentum of the scene's
    /// equations change by amounts of order one that do not shrink with `h`.
    /// Claims velocity Verlet's order 2.
    FirstComponentKick,
    /// Velocity Verlet whose kicks scale the last component's force by `1 -
    /// 1e-3`: a mass typed `1.001` where `1` was meant.
    ///
    /// Again another equation, `q'' = diag(1, ..., 1, 0.999) a(q)`, solved at
    /// ORDER 2; its field is not a gradient (symplecticity is lost at `O(1e-3)`),
    /// its flow still symmetric. The scene's energy changes by `O(1e-3)` of the
    /// motion's and the momentum by `1e-3` of the last body's impulse, limits
    /// that do not shrink with `h`. Claims order 2.
    ScaledLastKick,
    /// Velocity Verlet whose step passes through `f32` on its way in, as a units
    /// helper returning `f32` would do: it steps `h' = fl32(h)`, `|h' / h - 1|
    /// <= 2^-24`.
    ///
    /// Each rung is a correct second-order run of the exact flow over `N h'`
    /// instead of `N h`: its error is `C h^2 + |x'| t (h' / h - 1)`, a phase
    /// error of up to `6e-8` relative times `w t` that does not shrink with `h`
    /// (it jumps with the rounding of each `h`), so against the exact solution
    /// the error falls like `h^2` down to about `1e-8` and stalls there, far
    /// above the round-off floor of an `f64` run (`1e-15`). Against its own
    /// half step it converges (`fl32(h / 2) = fl32(h) / 2` exactly), and every
    /// invariant is conserved as well as velocity Verlet conserves it: only an
    /// exact solution can see this bias. Claims order 2.
    F32Step,
    /// Velocity Verlet that evaluates the force at both ends of every step
    /// instead of reusing the last one: the same map as the catalogue's, so
    /// every geometric claim and the order hold, but it spends 2 evaluations a
    /// step and claims the catalogue's 1. Every cost figure built on the claim
    /// (work against precision, stability per evaluation) would be twice too
    /// cheap; only counting the calls can see it.
    UnderClaimed,
}

/// Velocity Verlet, kick-drift-kick with the force evaluated at both ends
/// of the step, with one of the bugs of [`VerletBug`].
#[derive(Clone, Copy, Debug)]
pub struct VerletWithBug {
    /// The (false) claims.
    pub meta: SchemeMeta,
    /// The bug.
    pub bug: VerletBug,
}

impl OneStep for VerletWithBug {
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
        // the f32 bug rounds the step (in the dual numbers of a tangent map
        // the step is a constant, kept as it is)
        let h = match (self.bug, stepladder::state::as_f64(h)) {
            (VerletBug::F32Step, Some(x)) => R::of((x as f32) as f64),
            _ => h,
        };
        let force = |q: &nalgebra::SVector<R, D>| {
            let mut a: nalgebra::SVector<R, D> = scene.acceleration(q);
            match self.bug {
                VerletBug::FirstComponentKick => a = nalgebra::SVector::from_element(a[0]),
                VerletBug::ScaledLastKick => a[D - 1] *= R::of(0.999),
                VerletBug::F32Step | VerletBug::UnderClaimed => {}
            }
            a
        };
        let half = h * R::of(0.5);
        s.v += force(&s.q) * half;
        s.q += s.v * h;
        s.v += force(&s.q) * half;
        Ok(())
    }
}

/// A velocity Verlet with `bug`, claiming the catalogue's order and geometry.
/// It evaluates the force at both ends of every step, and claims so (2
/// evaluations), so that each pair is broken by its one bug alone; only
/// [`VerletBug::UnderClaimed`] claims the catalogue's 1.
const fn verlet_with(bug: VerletBug, id: &'static str, name: &'static str) -> VerletWithBug {
    let force_evaluations = match bug {
        VerletBug::UnderClaimed => VELOCITY_VERLET.meta.force_evaluations,
        _ => 2,
    };
    VerletWithBug {
        meta: SchemeMeta {
            force_evaluations,
            ..posing_as(VELOCITY_VERLET.meta, id, name)
        },
        bug,
    }
}

/// [`VerletBug::FirstComponentKick`].
pub const FIRST_COMPONENT_KICK: VerletWithBug = verlet_with(
    VerletBug::FirstComponentKick,
    "verlet-first-component-kick",
    "velocity Verlet kicking every component with the first one's force",
);

/// [`VerletBug::ScaledLastKick`].
pub const SCALED_LAST_KICK: VerletWithBug = verlet_with(
    VerletBug::ScaledLastKick,
    "verlet-scaled-last-kick",
    "velocity Verlet with the last component's force scaled by 0.999",
);

/// [`VerletBug::F32Step`].
pub const F32_STEP_VERLET: VerletWithBug = verlet_with(
    VerletBug::F32Step,
    "verlet-f32-step",
    "velocity Verlet with its step rounded to f32",
);

/// [`VerletBug::UnderClaimed`].
pub const UNDER_CLAIMED_VERLET: VerletWithBug = verlet_with(
    VerletBug::UnderClaimed,
    "verlet-under-claimed",
    "velocity Verlet claiming one force evaluation, spending two",
);
