//! The Runge-Kutta-Nyström tableaux of the catalogue and the adaptive
//! pairs, as published: Dormand and Prince's RKN6(4)6FD and RKN8(6)9FD
//! pairs and Nyström's three-stage fourth-order method. Run by the one
//! stepper of `nystrom_rk.rs`.

use super::SchemeMeta;
use super::nystrom_rk::{Embedded, NystromTable};

/// `r = sqrt(8581)`, the surd of every DPRKN6 coefficient (nearest double).
pub(super) const R8581: f64 = 92.633_687_176_966_02;

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
