//! Explicit Runge-Kutta-Nyström methods as data: one stepper over tableaux.
//!
//! For `q'' = a(q)` a Nyström method integrates the second-order equation
//! directly:
//! `k_i = a(q + c_i h v + h^2 sum_(j<i) a_ij k_j)`,
//! `q' = q + h v + h^2 sum b_bar_i k_i`, `v' = v + h sum b_i k_i`.
//! Since the right-hand side does not depend on `v`, the order conditions are
//! far fewer than for a Runge-Kutta method on `(q, v)`, so fewer stages buy
//! the same order (three for order four, five for order six). None of these
//! methods is symplectic or symmetric: they are the non-geometric baseline
//! of the high orders, and DPRKN6 and DPRKN8 carry embedded fourth- and
//! sixth-order solutions for step-size control (see
//! [`crate::study::adaptive`]).

use super::{Scheme, SchemeMeta, StepFailure, WithAcceleration};
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;

/// The weights of a lower-order solution computed from the same stages: the
/// difference to the main solution estimates the local error of the
/// lower-order one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Embedded<const S: usize> {
    /// Order of the embedded solution.
    pub order: u32,
    /// Its position weights.
    pub b_bar: [f64; S],
    /// Its velocity weights.
    pub b: [f64; S],
}

/// An explicit Runge-Kutta-Nyström tableau with `S` stages.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NystromTable<const S: usize> {
    /// The claims; `force_evaluations` is derived by [`NystromTable::new`].
    pub meta: SchemeMeta,
    /// The nodes; `c_1 = 0`, so the first stage is the force at the step's
    /// start.
    pub c: [f64; S],
    /// The `h^2` coefficients of the stage positions (strict lower triangle).
    pub a: [[f64; S]; S],
    /// Position weights.
    pub b_bar: [f64; S],
    /// Velocity weights.
    pub b: [f64; S],
    /// The embedded solution, for a pair.
    pub embedded: Option<Embedded<S>>,
}

/// The stages, the new state and, for a pair, the local error estimate of
/// one step (what a step-size controller needs).
#[derive(Clone, Copy, Debug)]
pub struct NystromStep<R: Real, const D: usize> {
    /// The main solution after the step.
    pub state: State<D, R>,
    /// `a(state.q)` when the tableau is first same as last, else unused.
    pub a_end: SVector<R, D>,
    /// Main minus embedded solution, in position and velocity (zero without
    /// an embedded solution).
    pub error: State<D, R>,
}

impl<const S: usize> NystromTable<S> {
    /// A table from its claims and coefficients. `meta.force_evaluations` is
    /// derived here (one per stage, less the last when it is the next step's
    /// first), so whatever the caller wrote there is replaced.
    pub const fn new(
        mut meta: SchemeMeta,
        c: [f64; S],
        a: [[f64; S]; S],
        b_bar: [f64; S],
        b: [f64; S],
        embedded: Option<Embedded<S>>,
    ) -> Self {
        assert!(c[0] == 0.0, "the first stage is the force at the start");
        let table = Self {
            meta,
            c,
            a,
            b_bar,
            b,
            embedded,
        };
        meta.force_evaluations = S as u32 - table.first_same_as_last() as u32;
        Self { meta, ..table }
    }

    /// True when the last stage is evaluated at the new position
    /// (`c_S = 1`, `a_Sj = b_bar_j`, `b_bar_S = 0`): its force is the next
    /// step's first stage and is evaluated once ("first same as last").
    pub const fn first_same_as_last(&self) -> bool {
        let last = S - 1;
        if self.c[last] != 1.0 || self.b_bar[last] != 0.0 {
            return false;
        }
        let mut j = 0;
        while j < last {
            if self.a[last][j] != self.b_bar[j] {
                return false;
            }
            j += 1;
        }
        true
    }

    /// `q + c h v + h^2 sum_j w_j k_j` over the first `n` stages: the one
    /// formula for stage positions and the new position, so that a first-
    /// same-as-last stage is bit for bit the next step's start.
    #[inline(always)]
    fn position<R: Real, const D: usize>(
        s: &State<D, R>,
        k: &[SVector<R, D>; S],
        w: &[f64; S],
        n: usize,
        ch: R,
        h2: R,
    ) -> SVector<R, D> {
        let mut q = s.q + s.v * ch;
        for (kj, &wj) in k[..n].iter().zip(w) {
            if wj != 0.0 {
                q += kj * (h2 * R::of(wj));
            }
        }
        q
    }

    /// One step from `s` with `a0 = a(s.q)`: the new state, the force at it
    /// (first same as last) and the embedded error estimate. `S - 1` force
    /// evaluations; no allocation.
    #[inline(always)]
    pub fn attempt<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        a0: SVector<R, D>,
        h: R,
    ) -> NystromStep<R, D> {
        let h2 = h * h;
        let mut k = [SVector::<R, D>::zeros(); S];
        k[0] = a0;
        let mut last_position = s.q;
        for i in 1..S {
            last_position = Self::position(s, &k, &self.a[i], i, h * R::of(self.c[i]), h2);
            k[i] = scene.acceleration(&last_position);
        }
        let fsal = self.first_same_as_last();
        let q = if fsal {
            last_position
        } else {
            Self::position(s, &k, &self.b_bar, S, h, h2)
        };
        let mut dv = SVector::<R, D>::zeros();
        for (ki, &bi) in k.iter().zip(&self.b) {
            dv += ki * R::of(bi);
        }
        let mut error = State::new(SVector::zeros(), SVector::zeros());
        if let Some(e) = &self.embedded {
            for (i, ki) in k.iter().enumerate() {
                error.q += ki * R::of(self.b_bar[i] - e.b_bar[i]);
                error.v += ki * R::of(self.b[i] - e.b[i]);
            }
            error.q *= h2;
            error.v *= h;
        }
        NystromStep {
            state: State::new(q, s.v + dv * h),
            a_end: k[S - 1],
            error,
        }
    }
}

impl<const S: usize> Scheme for NystromTable<S> {
    type Carry<R: Real, const D: usize> = WithAcceleration<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        state: &State<D, R>,
        _: R,
    ) -> WithAcceleration<R, D> {
        let a = if self.first_same_as_last() {
            scene.acceleration(&state.q)
        } else {
            SVector::zeros()
        };
        WithAcceleration { state: *state, a }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut WithAcceleration<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        let a0 = if self.first_same_as_last() {
            c.a
        } else {
            scene.acceleration(&c.state.q)
        };
        let next = self.attempt(scene, &c.state, a0, h);
        c.state = next.state;
        c.a = next.a_end;
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &WithAcceleration<R, D>, _: R) -> State<D, R> {
        c.state
    }
}

/// `r = sqrt(8581)`, the surd of every DPRKN6 coefficient (nearest double).
const R8581: f64 = 92.633_687_176_966_02;

/// Dormand and Prince's RKN6(4)6FD: a sixth-order Nyström method with an
/// embedded fourth-order solution, six stages of which the last is the next
/// step's first (five force evaluations per step).
///
/// Coefficients are the published closed forms in `r = sqrt(8581)`,
/// evaluated in `f64` at compile time; the tests check them against the
/// independently typed table of the held-out corpus and against every
/// Nyström order condition ([`crate::conditions::nystrom`]: sixth order for
/// the main solution, fourth for the embedded one, which fails a fifth-order
/// condition).
pub const DPRKN6: NystromTable<6> = {
    let r = R8581;
    let bb3 = (84_119_543.0 + 366_727.0 * r) / 409_622_616.0;
    let bb4 = (84_119_543.0 - 366_727.0 * r) / 409_622_616.0;
    let bb = [329.0 / 4212.0, 0.0, bb3, bb4, 200.0 / 17901.0, 0.0];
    NystromTable::new(
        SchemeMeta {
            id: "rkn6-dormand-prince",
            name: "Dormand-Prince RKN6(4)6FD (Runge-Kutta-Nystrom, FSAL, fixed step)",
            order: 6,
            symplectic: false,
            symmetric: false,
            force_evaluations: 0, // derived by `new`
            implicit: false,
            reference: "J. R. Dormand, P. J. Prince, Runge-Kutta-Nystrom triples, Comput. Math. Appl. 13, 937 (1987) (RKN6(4)6FD); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.14",
            phase_error: None,
        },
        [
            0.0,
            (209.0 - r) / 900.0,
            (209.0 - r) / 450.0,
            (209.0 + r) / 450.0,
            0.9,
            1.0,
        ],
        [
            [0.0; 6],
            [(26_131.0 - 209.0 * r) / 810_000.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [
                (26_131.0 - 209.0 * r) / 607_500.0,
                (26_131.0 - 209.0 * r) / 303_750.0,
                0.0,
                0.0,
                0.0,
                0.0,
            ],
            [
                (980_403_512_254.0 + 7_781_688_431.0 * r) / 11_694_469_921_875.0,
                -(1_262_884_486_208.0 + 15_385_481_287.0 * r) / 11_694_469_921_875.0,
                (7_166_233_891_441.0 + 78_694_563_299.0 * r) / 46_777_879_687_500.0,
                0.0,
                0.0,
                0.0,
            ],
            [
                -9.0 * (329_260.0 + 3181.0 * r) / 27_040_000.0,
                27.0 * (35_129.0 + 3331.0 * r) / 13_520_000.0,
                -27.0 * (554_358_343.0 + 31_040_327.0 * r) / 464_060_480_000.0,
                153.0 * (8_555_257.0 - 67_973.0 * r) / 2_745_920_000.0,
                0.0,
                0.0,
            ],
            bb,
        ],
        bb,
        [
            329.0 / 4212.0,
            0.0,
            (389_225_579.0 + 96_856.0 * r) / 1_024_056_540.0,
            (389_225_579.0 - 96_856.0 * r) / 1_024_056_540.0,
            2000.0 / 17901.0,
            0.05,
        ],
        Some(Embedded {
            order: 4,
            b_bar: [
                (2701.0 + 23.0 * r) / 4563.0,
                -(9829.0 + 131.0 * r) / 9126.0,
                5.0 * (1798.0 + 17.0 * r) / 9126.0,
                0.0,
                0.0,
                0.0,
            ],
            b: [
                115.0 / 2106.0,
                0.0,
                (84_119_543.0 + 366_727.0 * r) / 256_014_135.0,
                (84_119_543.0 - 366_727.0 * r) / 256_014_135.0,
                6950.0 / 17901.0,
                -0.1,
            ],
        }),
    )
};

/// `n / d` correctly rounded (both are exact doubles below 2^53).
const fn ratio(n: i64, d: i64) -> f64 {
    n as f64 / d as f64
}

/// Dormand, El-Mikkawy and Prince's eighth-order Nyström method with an
/// embedded sixth-order solution: nine stages, the last at the new position
/// (first same as last), so eight force evaluations per step. The stage
/// nodes `c = 0, 1/20, 1/10, 3/10, 1/2, 7/10, 9/10, 1, 1`.
///
/// Every coefficient is a published rational, rounded once. Checked here by
/// every Nyström order condition in double-double
/// ([`crate::conditions::nystrom`]: the main solution's local error vanishes
/// through `h^8`, the embedded one's through `h^6`, to the rounding of the
/// coefficients) and by the local error on a nonlinear orbit;
/// `tests/check_nystrom_rk_orders.py` checks the rationals exactly.
pub const DPRKN8: NystromTable<9> = {
    let bb = [
        ratio(223, 7938),
        0.0,
        ratio(1175, 8064),
        ratio(925, 6048),
        ratio(41, 448),
        ratio(925, 14112),
        ratio(1175, 72576),
        0.0,
        0.0,
    ];
    NystromTable::new(
        SchemeMeta {
            id: "rkn8-dormand-el-mikkawy-prince",
            name: "Dormand-El-Mikkawy-Prince RKN8(6), 9 stages (Runge-Kutta-Nystrom, FSAL, fixed step)",
            order: 8,
            symplectic: false,
            symmetric: false,
            force_evaluations: 0, // derived by `new`
            implicit: false,
            reference: "J. R. Dormand, M. E. A. El-Mikkawy, P. J. Prince, High-order embedded Runge-Kutta-Nystrom formulae, IMA J. Numer. Anal. 7, 423 (1987)",
            phase_error: None,
        },
        [0.0, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0, 1.0],
        [
            [0.0; 9],
            [ratio(1, 800), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [
                ratio(1, 600),
                ratio(1, 300),
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
            ],
            [
                ratio(9, 200),
                ratio(-9, 100),
                ratio(9, 100),
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
            ],
            [
                ratio(-66_701, 197_352),
                ratio(28_325, 32_892),
                ratio(-2665, 5482),
                ratio(2170, 24_669),
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
            ],
            [
                ratio(227_015_747, 304_251_000),
                ratio(-54_897_451, 30_425_100),
                ratio(12_942_349, 10_141_700),
                ratio(-9499, 304_251),
                ratio(539, 9250),
                0.0,
                0.0,
                0.0,
                0.0,
            ],
            [
                ratio(-1_131_891_597, 901_789_000),
                ratio(41_964_921, 12_882_700),
                ratio(-6_663_147, 3_220_675),
                ratio(270_954, 644_135),
                ratio(-108, 5875),
                ratio(114, 1645),
                0.0,
                0.0,
                0.0,
            ],
            [
                ratio(13_836_959, 3_667_458),
                ratio(-17_731_450, 1_833_729),
                ratio(1_063_919_505, 156_478_208),
                ratio(-33_213_845, 39_119_552),
                ratio(13_335, 28_544),
                ratio(-705, 14_272),
                ratio(1645, 57_088),
                0.0,
                0.0,
            ],
            bb,
        ],
        bb,
        [
            ratio(223, 7938),
            0.0,
            ratio(5875, 36_288),
            ratio(4625, 21_168),
            ratio(41, 224),
            ratio(4625, 21_168),
            ratio(5875, 36_288),
            ratio(223, 7938),
            0.0,
        ],
        Some(Embedded {
            order: 6,
            b_bar: [
                ratio(7_987_313, 109_941_300),
                0.0,
                ratio(1_610_737, 44_674_560),
                ratio(10_023_263, 33_505_920),
                ratio(-497_221, 12_409_600),
                ratio(10_023_263, 78_180_480),
                ratio(1_610_737, 402_071_040),
                0.0,
                0.0,
            ],
            b: [
                ratio(7_987_313, 109_941_300),
                0.0,
                ratio(1_610_737, 40_207_104),
                ratio(10_023_263, 23_454_144),
                ratio(-497_221, 6_204_800),
                ratio(10_023_263, 23_454_144),
                ratio(1_610_737, 40_207_104),
                ratio(-4_251_941, 54_970_650),
                0.15,
            ],
        }),
    )
};

/// Nyström's classical fourth-order method: three stages at `c = (0, 1/2,
/// 1)`, three force evaluations per step (RK4 on `(q, v)` needs four), no
/// embedded solution.
pub const NYSTROM4: NystromTable<3> = NystromTable::new(
    SchemeMeta {
        id: "rkn4-nystrom",
        name: "Nystrom's fourth-order Runge-Kutta-Nystrom method (3 stages)",
        order: 4,
        symplectic: false,
        symmetric: false,
        force_evaluations: 0, // derived by `new`
        implicit: false,
        reference: "E. J. Nystrom, Acta Soc. Sci. Fenn. 50, No. 13 (1925); E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I (1993), II.14",
        phase_error: None,
    },
    [0.0, 0.5, 1.0],
    [[0.0; 3], [0.125, 0.0, 0.0], [0.0, 0.5, 0.0]],
    [1.0 / 6.0, 1.0 / 3.0, 0.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    None,
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conditions;
    use crate::scene::{Harmonic, KeplerCircular};

    #[test]
    fn the_surd_is_the_square_root_of_8581() {
        assert!((R8581 * R8581 - 8581.0).abs() < 4e-12);
    }

    /// Every Nyström order condition through `h^7`: the main solutions of
    /// DPRKN6 and Nyström's method have their orders and fail the next, and
    /// the embedded solution is fourth order and fails order five (an
    /// embedded solution of order five would make the estimate useless).
    #[test]
    fn the_main_solutions_have_their_order_and_the_embedded_one_fails_order_five() {
        let c = conditions::nystrom(&DPRKN6).unwrap();
        println!(
            "dprkn6 {}
       embedded {}",
            c.main,
            c.embedded.as_ref().unwrap()
        );
        assert!(c.main.confirms(6), "{}", c.main);
        assert!(c.embedded.unwrap().confirms(4));
        // rows sum to c^2/2 (the stage positions are consistent)
        for i in 0..6 {
            let row: f64 = DPRKN6.a[i].iter().sum();
            assert!((row - DPRKN6.c[i].powi(2) / 2.0).abs() < 1e-16, "row {i}");
        }
        let c = conditions::nystrom(&NYSTROM4).unwrap();
        assert!(c.main.confirms(4), "{}", c.main);
    }

    /// DPRKN8's every Nyström order condition through `h^8` (its estimate's
    /// through `h^6`) and none beyond, its rows summing to `c^2/2`, and its
    /// local error on the Kepler orbit falling like `h^9` (halving `h`
    /// divides it by 512), its estimate's like `h^7` (by 128). The same
    /// trees are checked in exact rationals by
    /// `tests/check_nystrom_rk_orders.py`.
    #[test]
    fn dprkn8_has_order_eight_and_its_estimate_order_six() {
        let t = &DPRKN8;
        for i in 0..9 {
            let row: f64 = t.a[i].iter().sum();
            assert!((row - t.c[i].powi(2) / 2.0).abs() < 4e-16, "row {i}: {row}");
        }
        let c = conditions::nystrom(t).unwrap();
        println!(
            "dprkn8 {}
       embedded {}",
            c.main,
            c.embedded.as_ref().unwrap()
        );
        assert!(c.main.confirms(8), "{}", c.main);
        assert!(c.embedded.unwrap().confirms(6));
        assert!(t.first_same_as_last());
        assert_eq!(t.meta.force_evaluations, 8);
        let scene = KeplerCircular;
        let s = scene.initial();
        let a0 = scene.acceleration(&s.q);
        let local = |h: f64| {
            let x = t.attempt(&scene, &s, a0, h).state;
            scene.phase_distance(&x, &scene.exact(h).unwrap())
        };
        let estimate = |h: f64| {
            let e = t.attempt(&scene, &s, a0, h).error;
            (e.q.norm_squared() + e.v.norm_squared()).sqrt()
        };
        for h in [0.08, 0.04] {
            let r = local(h) / local(h / 2.0);
            assert!((r / 512.0 - 1.0).abs() < 0.15, "h = {h}: local ratio {r}");
            let r = estimate(h) / estimate(h / 2.0);
            assert!(
                (r / 128.0 - 1.0).abs() < 0.15,
                "h = {h}: estimate ratio {r}"
            );
        }
    }

    #[test]
    fn dprkn6_is_first_same_as_last_and_nystrom4_is_not() {
        assert!(DPRKN6.first_same_as_last());
        assert_eq!(DPRKN6.meta.force_evaluations, 5);
        assert!(!NYSTROM4.first_same_as_last());
        assert_eq!(NYSTROM4.meta.force_evaluations, 3);
    }

    /// The reused force is bit for bit the force at the new position: the
    /// FSAL step computes the same map as a step that evaluates it afresh.
    #[test]
    fn the_reused_force_is_the_force_at_the_new_position() {
        let scene = KeplerCircular;
        let mut c = DPRKN6.start(&scene, &scene.initial(), 0.1);
        for _ in 0..50 {
            DPRKN6.step(&scene, &mut c, 0.1).unwrap();
            assert_eq!(c.a, scene.acceleration(&c.state.q));
        }
    }

    /// The error estimate is the difference of a sixth- and a fourth-order
    /// solution: its local size falls like `h^5` (halving `h` divides it by
    /// 32), the main solution's local error like `h^7`.
    #[test]
    fn the_error_estimate_scales_like_h_to_the_fifth() {
        let scene = Harmonic::default();
        let s = scene.initial();
        let a0 = scene.acceleration(&s.q);
        let size = |h: f64| {
            let e = DPRKN6.attempt(&scene, &s, a0, h).error;
            (e.q.norm_squared() + e.v.norm_squared()).sqrt()
        };
        for h in [0.02, 0.01] {
            let ratio = size(h) / size(h / 2.0);
            assert!((ratio / 32.0 - 1.0).abs() < 0.1, "h = {h}: ratio {ratio}");
        }
        let local = |h: f64| {
            let x = DPRKN6.attempt(&scene, &s, a0, h).state;
            scene.phase_distance(&x, &scene.exact(h).unwrap())
        };
        let ratio = local(0.2) / local(0.1);
        assert!((ratio / 128.0 - 1.0).abs() < 0.1, "{ratio}");
    }
}
