//! Correct schemes outside the catalogue, each claim true: odd orders (two
//! second-order Runge-Kutta methods, Kutta's third order, Ruth's symplectic
//! third order), order five (Dormand-Prince), a Runge-Kutta-Nyström method,
//! implicit Runge-Kutta methods that are symmetric but not symplectic (the
//! trapezoidal rule, Lobatto IIIA) or both (Gauss), and two more compositions
//! of velocity Verlet (Suzuki's fractal and Yoshida's recursive ones).
//!
//! Every entry here is a coefficient table and its claims, run by the core's
//! table-driven steppers: [`ExplicitRk`] for a Butcher tableau,
//! [`NystromTable`] for a Runge-Kutta-Nyström tableau, [`ImplicitRk`] for an
//! implicit tableau, and [`SplittingTable`] for splittings and compositions. The
//! tests check every tableau against its order conditions
//! ([`stepladder::conditions`]: Butcher trees, the Nyström conditions, and
//! for splittings the Taylor series of a product of matrix exponentials) and
//! every scheme's order on the harmonic oscillator.

use stepladder::scheme::{
    BlackBox, ExplicitRk, FOREST_RUTH, Flow, Force, ImplicitRk, NystromTable, SchemeMeta,
    SplittingTable, Stateful, VELOCITY_VERLET, VerletComposition,
};

/// Neither symplectic nor symmetric, explicit, and no hand-derived phase
/// error: what every explicit Runge-Kutta method of this module claims
/// besides its id, name, order and reference.
const fn explicit(
    id: &'static str,
    name: &'static str,
    order: u32,
    reference: &'static str,
) -> SchemeMeta {
    SchemeMeta {
        id,
        name,
        order,
        symplectic: false,
        symmetric: false,
        force_evaluations: 0, // set from the tableau
        implicit: false,
        reference,
        phase_error: None,
    }
}

/// Heun's method, the explicit trapezoidal rule:
/// `k1 = f(y)`, `k2 = f(y + h k1)`, `y' = y + h/2 (k1 + k2)`.
///
/// Second order (`sum b = 1`, `sum b c = 1/2`; `sum b c^2 = 1/2`, not 1/3),
/// neither symplectic nor symmetric: on the oscillator each step multiplies
/// the energy by `|1 + iz - z^2/2|^2 = 1 + z^4/4` (`z = h w0`).
pub const HEUN: ExplicitRk<2> = ExplicitRk::new(
    explicit(
        "heun",
        "Heun's method (explicit trapezoidal RK2)",
        2,
        "K. Heun, Z. Math. Phys. 45, 23 (1900); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.1",
    ),
    [[0.0, 0.0], [1.0, 0.0]],
    [0.5, 0.5],
    [0.0, 1.0],
);

/// The explicit midpoint rule (Runge's RK2): `k1 = f(y)`,
/// `k2 = f(y + h/2 k1)`, `y' = y + h k2`.
///
/// Second order (`sum b c = 1/2`; `sum b c^2 = 1/4`, not 1/3), neither
/// symplectic nor symmetric. On a linear problem it is the same map as
/// [`HEUN`] (both are `1 + z + z^2/2`); they differ on nonlinear scenes.
pub const EXPLICIT_MIDPOINT: ExplicitRk<2> = ExplicitRk::new(
    explicit(
        "explicit-midpoint",
        "explicit midpoint rule (RK2)",
        2,
        "C. Runge, Math. Ann. 46, 167 (1895); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.1",
    ),
    [[0.0, 0.0], [0.5, 0.0]],
    [0.0, 1.0],
    [0.0, 0.5],
);

/// Kutta's third-order method: `c = (0, 1/2, 1)`, `a21 = 1/2`, `a31 = -1`,
/// `a32 = 2`, `b = (1/6, 2/3, 1/6)` (Simpson's weights).
///
/// Third order (both order-3 trees: `sum b c^2 = 1/3`, `sum b a c = 1/6`),
/// neither symplectic nor symmetric: on the oscillator each step multiplies
/// the energy by `1 - z^4/12 + z^6/36`.
pub const KUTTA3: ExplicitRk<3> = ExplicitRk::new(
    explicit(
        "kutta3",
        "Kutta's third-order Runge-Kutta method",
        3,
        "W. Kutta, Z. Math. Phys. 46, 435 (1901); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.1",
    ),
    [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [-1.0, 2.0, 0.0]],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    [0.0, 0.5, 1.0],
);

/// The fifth-order solution of Dormand and Prince's RK5(4)7M pair, at fixed
/// step and without error control. The pair's seventh stage (first same as
/// last) serves only the embedded fourth-order estimate, and its fifth-order
/// weight is zero, so a fixed step needs the first six stages:
/// six force evaluations.
///
/// Fifth order (all 17 Butcher trees up to order five hold exactly in
/// rationals), neither symplectic nor symmetric.
pub const DORMAND_PRINCE5: ExplicitRk<6> = ExplicitRk::new(
    explicit(
        "dormand-prince5",
        "Dormand-Prince fifth order (fixed step, no error control)",
        5,
        "J. R. Dormand, P. J. Prince, J. Comput. Appl. Math. 6, 19 (1980); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.5",
    ),
    [
        [0.0; 6],
        [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
        [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
        [
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
            0.0,
            0.0,
        ],
        [
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
            0.0,
        ],
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
    [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0],
);

/// The classical fourth-order Runge-Kutta-Nyström method with three force
/// evaluations: `c = (0, 1/2, 1)`, `a21 = 1/8`, `a31 = 0`, `a32 = 1/2`,
/// `b_bar = (1/6, 1/3, 0)`, `b = (1/6, 2/3, 1/6)`:
/// `k1 = a(q)`, `k2 = a(q + h/2 v + h^2/8 k1)`, `k3 = a(q + h v + h^2/2 k2)`,
/// `q' = q + h v + h^2 (k1/6 + k2/3)`, `v' = v + h (k1 + 4 k2 + k3)/6`.
///
/// Fourth order: the Nyström trees give `sum b_bar = 1/2`, `sum b_bar c =
/// 1/6`, `sum b_bar c^2 = 1/12`, `sum b_bar a 1 = 1/24` for the positions and
/// `sum b c^k = 1/(k+1)` (k = 0..3), `sum b a 1 = 1/6`, `sum b c a 1 = 1/8`,
/// `sum b a c = 1/24` for the velocities, all exact; `sum b c^4 = 5/24`, not
/// 1/5, so not fifth. Neither symplectic nor symmetric: of the conditions
/// for a symplectic Runge-Kutta-Nyström method, `b_bar_i = b_i (1 - c_i)`
/// holds but `b_i (b_bar_j - a_ij) = b_j (b_bar_i - a_ji)` fails at
/// `(i, j) = (1, 2)` (`1/18` against `1/36`).
pub const RKN4: NystromTable<3> = NystromTable::new(
    SchemeMeta {
        id: "rkn4",
        name: "classical Runge-Kutta-Nystrom method (order 4, 3 stages)",
        order: 4,
        symplectic: false,
        symmetric: false,
        force_evaluations: 0, // derived by `new`
        implicit: false,
        reference: "E. J. Nystrom, Acta Soc. Sci. Fenn. 50, No. 13 (1925); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.14",
        phase_error: None,
    },
    [0.0, 0.5, 1.0],
    [[0.0, 0.0, 0.0], [1.0 / 8.0, 0.0, 0.0], [0.0, 0.5, 0.0]],
    [1.0 / 6.0, 1.0 / 3.0, 0.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    None,
);

/// Ruth's third-order symplectic method (1983), the first symplectic
/// integrator beyond second order: kick-drift three times,
/// `K(7/24) D(2/3) K(3/4) D(-2/3) K(-1/24) D(1)`.
///
/// Symplectic (a sequence of exact flows), not symmetric (the sequence is not
/// a palindrome, and its adjoint, the reversed sequence, is a different
/// method), third order: the weights sum to one in drifts and in kicks, the
/// second-order condition `sum_(kick i before drift j) c_i d_j = 1/2` holds,
/// and so do the two third-order ones; the fourth-order terms do not vanish.
/// Three force evaluations per step.
pub const RUTH3: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "ruth3",
        name: "Ruth's third-order symplectic method",
        order: 3,
        symplectic: true,
        symmetric: false,
        force_evaluations: 0, // derived by `new`
        implicit: false,
        reference: "R. D. Ruth, IEEE Trans. Nucl. Sci. 30, 2669 (1983)",
        phase_error: None,
    },
    Flow::Kick,
    &RUTH3_DRIFTS,
    &RUTH3_KICKS,
);

/// Ruth's drift weights `d = (2/3, -2/3, 1)`.
pub const RUTH3_DRIFTS: [f64; 3] = [2.0 / 3.0, -2.0 / 3.0, 1.0];

/// Ruth's kick weights `c = (7/24, 3/4, -1/24)`.
pub const RUTH3_KICKS: [f64; 3] = [7.0 / 24.0, 3.0 / 4.0, -1.0 / 24.0];

/// Suzuki's `p = 1/(4 - 4^(1/3))`, the nearest double (from 40 digits,
/// `0.41449077179437573714...`).
pub const SUZUKI_P: f64 = 0.4144907717943757;

/// The five Verlet steps of Suzuki's fractal composition.
const SUZUKI4_STAGES: VerletComposition<5, 6> =
    VerletComposition::new([SUZUKI_P, SUZUKI_P, 1.0 - 4.0 * SUZUKI_P, SUZUKI_P, SUZUKI_P]);

/// Suzuki's fractal fourth-order composition: velocity Verlet with the steps
/// `p h, p h, (1 - 4p) h, p h, p h`, `p = 1/(4 - 4^(1/3))`.
///
/// Fourth order: `sum w = 1`, and `sum w^3 = 4 p^3 + (1 - 4p)^3 = 0` exactly
/// when `1 - 4p = -4^(1/3) p`, which defines `p`; the palindrome cancels the
/// even orders. Symplectic and symmetric. Five force evaluations per step;
/// the only backward step, `1 - 4p = -0.658`, is shorter than Forest-Ruth's
/// `-1.70`, and so is the error constant.
pub const SUZUKI4: SplittingTable = SUZUKI4_STAGES.table(SchemeMeta {
    id: "suzuki4",
    name: "Suzuki's fractal fourth-order composition (5 stages)",
    order: 4,
    symplectic: true,
    symmetric: true,
    force_evaluations: 0, // derived by `table`
    implicit: false,
    reference: "M. Suzuki, Phys. Lett. A 146, 319 (1990)",
    phase_error: None,
});

/// `z1 = 1/(2 - 2^(1/5))`, the outer weight of the second triple jump, the
/// nearest double (from 40 digits, `1.17467175808936338449...`).
pub const YOSHIDA_Z1: f64 = 1.1746717580893633;

/// `z0 = -2^(1/5)/(2 - 2^(1/5)) = 1 - 2 z1`, the nearest double (from 40
/// digits, `-1.34934351617872676899...`).
pub const YOSHIDA_Z0: f64 = -1.3493435161787268;

/// The nine Verlet steps: Forest-Ruth's weights `x1 x0 x1` (from the
/// catalogue's table) scaled by `z1`, `z0`, `z1` in turn.
const YOSHIDA6_RECURSIVE_STAGES: VerletComposition<9, 10> = {
    let (x1, x0) = (FOREST_RUTH.drift[0], FOREST_RUTH.drift[1]);
    let (z1, z0) = (YOSHIDA_Z1, YOSHIDA_Z0);
    VerletComposition::new([
        z1 * x1,
        z1 * x0,
        z1 * x1,
        z0 * x1,
        z0 * x0,
        z0 * x1,
        z1 * x1,
        z1 * x0,
        z1 * x1,
    ])
};

/// Yoshida's recursive sixth-order composition: the triple jump applied to
/// the fourth-order Forest-Ruth method `S4`, `S6(h) = S4(z1 h) S4(z0 h)
/// S4(z1 h)` with `z1 = 1/(2 - 2^(1/5))`, `z0 = 1 - 2 z1`: nine Verlet steps
/// whose weights are the products `z_i x_j` of the two triple jumps.
///
/// Sixth order: `S4` is symmetric with the modified field `h X + h^5 X5 +
/// ...`, and `2 z1 + z0 = 1`, `2 z1^5 + z0^5 = 0` cancel its `h^5` term; the
/// palindrome cancels `h^6`. Symplectic and symmetric, nine force
/// evaluations; the large weights (up to `2.3` in size) make its error
/// constant large, which is why solution A of [`stepladder::scheme::YOSHIDA6`]
/// with seven stages is preferred.
pub const YOSHIDA6_RECURSIVE: SplittingTable = YOSHIDA6_RECURSIVE_STAGES.table(SchemeMeta {
    id: "yoshida6-recursive",
    name: "Yoshida's recursive sixth order (triple jump of Forest-Ruth, 9 stages)",
    order: 6,
    symplectic: true,
    symmetric: true,
    force_evaluations: 0, // derived by `table`
    implicit: false,
    reference: "H. Yoshida, Phys. Lett. A 150, 262 (1990), section 4 (the recursive triple jump); M. Suzuki, Phys. Lett. A 146, 319 (1990)",
    phase_error: None,
});

/// The implicit trapezoidal rule, `y' = y + h/2 (f(y) + f(y'))`: the
/// two-stage Lobatto IIIA method, `A = [[0, 0], [1/2, 1/2]]`, `b = (1/2,
/// 1/2)`, `c = (0, 1)`. On `(q, v)`: `v' = v + h/2 (a(q) + a(q'))`,
/// `q' = q + h/2 (v + v')`.
///
/// Second order, symmetric (the tableau is its own adjoint), implicit, and NOT
/// symplectic: the condition `b_i a_ij + b_j a_ji = b_i b_j` fails at
/// `i = j = 1` (`0` against `1/4`). It is conjugate to the implicit midpoint
/// rule (trapezoid = half explicit Euler after half implicit Euler, midpoint
/// the other way round), so its energy does not drift; on the linear
/// oscillator it is the same map as the midpoint rule, `(1 + z/2)/(1 - z/2)`,
/// and symplectic there: its non-symplecticity shows only on nonlinear
/// scenes. Two force evaluations per iteration (the first stage, `a(q)`, is
/// re-evaluated each iteration).
pub const TRAPEZOIDAL: ImplicitRk<2> = ImplicitRk::new(
    SchemeMeta {
        id: "implicit-trapezoidal",
        name: "implicit trapezoidal rule (Lobatto IIIA, 2 stages)",
        order: 2,
        symplectic: false,
        symmetric: true,
        force_evaluations: 0, // set by `new`
        implicit: true,
        reference: "E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration (2006), II.1 and VI.4; E. Hairer, G. Wanner, Solving Ordinary Differential Equations II (1996), IV.5",
        phase_error: None,
    },
    [[0.0, 0.0], [0.5, 0.5]],
    [0.5, 0.5],
    [0.0, 1.0],
);

/// `sqrt(3)/6`, the nearest double (from 40 digits,
/// `0.28867513459481288225...`).
pub const SQRT3_6: f64 = 0.28867513459481287;

/// The two-stage Gauss-Legendre collocation method: `c = 1/2 -+ sqrt(3)/6`,
/// `A = [[1/4, 1/4 - sqrt(3)/6], [1/4 + sqrt(3)/6, 1/4]]`, `b = (1/2, 1/2)`.
///
/// Order four (`2s`, the highest of any two-stage method), symplectic (`b_i
/// a_ij + b_j a_ji = b_i b_j` for all `i, j`), symmetric, implicit. On the
/// oscillator the map is the (2,2) Padé approximant of the rotation and
/// conserves the energy exactly. Two force evaluations per iteration.
pub const GAUSS4: ImplicitRk<2> = ImplicitRk::new(
    SchemeMeta {
        id: "gauss4",
        name: "Gauss-Legendre collocation (2 stages, order 4)",
        order: 4,
        symplectic: true,
        symmetric: true,
        force_evaluations: 0, // set by `new`
        implicit: true,
        reference: "J. C. Butcher, Math. Comp. 18, 50 (1964); E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration (2006), II.1 and VI.4",
        phase_error: None,
    },
    [[0.25, 0.25 - SQRT3_6], [0.25 + SQRT3_6, 0.25]],
    [0.5, 0.5],
    [0.5 - SQRT3_6, 0.5 + SQRT3_6],
);

/// The three-stage Lobatto IIIA collocation method: `c = (0, 1/2, 1)`,
/// `A = [[0, 0, 0], [5/24, 1/3, -1/24], [1/6, 2/3, 1/6]]`,
/// `b = (1/6, 2/3, 1/6)`.
///
/// Order four (`2s - 2`), symmetric, implicit, and NOT symplectic: `2 b1 a11
/// = 0` against `b1^2 = 1/36`. On the linear oscillator it is the same map as
/// [`GAUSS4`] (both are the (2,2) Padé approximant) and so symplectic there;
/// its non-symplecticity shows on nonlinear scenes. Three force evaluations
/// per iteration.
pub const LOBATTO_IIIA4: ImplicitRk<3> = ImplicitRk::new(
    SchemeMeta {
        id: "lobatto-iiia4",
        name: "Lobatto IIIA collocation (3 stages, order 4)",
        order: 4,
        symplectic: false,
        symmetric: true,
        force_evaluations: 0, // set by `new`
        implicit: true,
        reference: "B. L. Ehle, Univ. Waterloo Research Report CSRR 2010 (1969); E. Hairer, G. Wanner, Solving Ordinary Differential Equations II (1996), IV.5; E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration (2006), II.1",
        phase_error: None,
    },
    [
        [0.0, 0.0, 0.0],
        [5.0 / 24.0, 1.0 / 3.0, -1.0 / 24.0],
        [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    ],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    [0.0, 0.5, 1.0],
);

// ------------------------------------------------------ state kept between steps

/// The step of [`FSAL_VERLET`]: velocity Verlet on slices, as a black box,
/// keeping the force at the end of each step for the next one's first kick
/// (first same as last). The kept force is only valid for the run it came
/// from: each run must start from an empty one.
fn fsal_verlet_step(last: &mut Vec<f64>, q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    if last.len() != q.len() {
        last.resize(q.len(), 0.0);
        force(q, last);
    }
    for i in 0..q.len() {
        v[i] += 0.5 * h * last[i];
        q[i] += h * v[i];
    }
    force(q, last);
    for i in 0..q.len() {
        v[i] += 0.5 * h * last[i];
    }
}

/// The type of [`fsal_verlet_step`].
type FsalStep = fn(&mut Vec<f64>, &mut [f64], &mut [f64], f64, &Force<'_, f64>);

/// The stateful black box [`FSAL_VERLET`] is.
type FsalVerlet = BlackBox<f64, Stateful<fn() -> Vec<f64>, FsalStep>>;

/// Velocity Verlet as a stateful black box (see `fsal_verlet_step` below): one
/// force evaluation a step, every claim of the catalogue's velocity Verlet,
/// and correct only because every run starts from a fresh, empty state.
pub static FSAL_VERLET: FsalVerlet = BlackBox::stateful(
    SchemeMeta {
        id: "verlet-fsal-black-box",
        name: "velocity Verlet keeping its last force, as a stateful black box",
        phase_error: None,
        ..VELOCITY_VERLET.meta
    },
    Vec::new,
    fsal_verlet_step,
);
