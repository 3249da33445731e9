//! The Runge-Kutta-Nyström tableaux of the catalogue and the adaptive
//! pairs, as published: Dormand and Prince's RKN6(4)6FD and RKN8(6)9FD
//! pairs, their RKN12(10)17M, and Nyström's three-stage fourth-order
//! method. Run by the one
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

/// Dormand, El-Mikkawy and Prince's twelfth-order Nyström method with an
/// embedded tenth-order solution, RKN12(10)17M: seventeen stages, none of
/// them the next step's first, so seventeen force evaluations a step. The
/// standard for stringent tolerances on `q'' = a(q)`: at a step where
/// DPRKN8(6) makes an error `C h^9`, this one makes `C' h^13`.
///
/// Every coefficient is the double nearest its published rational, which
/// `tests/check_dprkn12.py` checks (with the rows' sums `c_i^2/2` and every
/// Nyström order condition, exactly); the tests check every order condition
/// again in double-double ([`crate::conditions::nystrom`]: the main
/// solution's local error vanishes through `h^12`, the embedded one's
/// through `h^10`, to the rounding of the coefficients).
pub const DPRKN12: NystromTable<17> = {
    let c = [
        0.0,
        0.02,
        0.04,
        0.1,
        0.13333333333333333,
        0.16,
        0.05,
        0.2,
        0.25,
        0.3333333333333333,
        0.5,
        0.5555555555555556,
        0.75,
        0.8571428571428571,
        0.9452162222720143,
        1.0,
        1.0,
    ];
    let mut a = [[0.0; 17]; 17];
    a[1][0] = 0.0002;
    a[2][0] = 0.0002666666666666667;
    a[2][1] = 0.0005333333333333334;
    a[3][0] = 0.002916666666666667;
    a[3][1] = -0.004166666666666667;
    a[3][2] = 0.00625;
    a[4][0] = 0.0016460905349794238;
    a[4][2] = 0.0054869684499314125;
    a[4][3] = 0.0017558299039780521;
    a[5][0] = 0.0019456;
    a[5][2] = 0.007151746031746032;
    a[5][3] = 0.0029127111111111113;
    a[5][4] = 0.0007899428571428571;
    a[6][0] = 0.00056640625;
    a[6][2] = 0.0008809730489417989;
    a[6][3] = -0.0004369212962962963;
    a[6][4] = 0.00033900669642857143;
    a[6][5] = -9.946469907407407e-05;
    a[7][0] = 0.0030833333333333333;
    a[7][3] = 0.0017777777777777779;
    a[7][4] = 0.0027;
    a[7][5] = 0.0015782828282828283;
    a[7][6] = 0.01086060606060606;
    a[8][0] = 0.00365183937480113;
    a[8][2] = 0.003965171714072343;
    a[8][3] = 0.0031972582629306284;
    a[8][4] = 0.008221467306855435;
    a[8][5] = -0.0013130926959572379;
    a[8][6] = 0.009771586968064868;
    a[8][7] = 0.003755769069232834;
    a[9][0] = 0.003707241068718501;
    a[9][2] = 0.005082045854555286;
    a[9][3] = 0.001174708002175412;
    a[9][4] = -0.021147629915126993;
    a[9][5] = 0.06010463698107881;
    a[9][6] = 0.02010573476850619;
    a[9][7] = -0.02835075012293358;
    a[9][8] = 0.014879568918581932;
    a[10][0] = 0.03512537656073344;
    a[10][2] = -0.008615749195138479;
    a[10][3] = -0.005791448051007917;
    a[10][4] = 1.945554823782616;
    a[10][5] = -3.4351238674565137;
    a[10][6] = -0.10930701107475221;
    a[10][7] = 2.3496383118995166;
    a[10][8] = -0.7560094086870229;
    a[10][9] = 0.10952897222156927;
    a[11][0] = 0.020527792537482496;
    a[11][2] = -0.00728644676448018;
    a[11][3] = -0.0021153556079618403;
    a[11][4] = 0.9275807968723522;
    a[11][5] = -1.6522824844257367;
    a[11][6] = -0.02107956300568657;
    a[11][7] = 1.2065364326207872;
    a[11][8] = -0.4137144770010661;
    a[11][9] = 0.09079873982809654;
    a[11][10] = 0.005355552600533985;
    a[12][0] = -0.14324078875545515;
    a[12][2] = 0.012528703773091817;
    a[12][3] = 0.006826019163969827;
    a[12][4] = -4.799555395574387;
    a[12][5] = 5.6986250439519415;
    a[12][6] = 0.7553430369523645;
    a[12][7] = -0.12755487858281084;
    a[12][8] = -1.9605926051117384;
    a[12][9] = 0.9185609056635262;
    a[12][10] = -0.23880085505284432;
    a[12][11] = 0.15911081357234216;
    a[13][0] = 0.8045019205520489;
    a[13][2] = -0.016658527067011247;
    a[13][3] = -0.021415834042629735;
    a[13][4] = 16.827235928962466;
    a[13][5] = -11.172835357176098;
    a[13][6] = -3.377159297226324;
    a[13][7] = -15.243326655360846;
    a[13][8] = 17.179835738215417;
    a[13][9] = -5.437719239823995;
    a[13][10] = 1.3878671618364655;
    a[13][11] = -0.5925827732652812;
    a[13][12] = 0.029603873171297354;
    a[14][0] = -0.913296766697358;
    a[14][2] = 0.0024112725757805178;
    a[14][3] = 0.01765812269386174;
    a[14][4] = -14.851649779720384;
    a[14][5] = 2.1589708670045757;
    a[14][6] = 3.99791558311788;
    a[14][7] = 28.434151800232232;
    a[14][8] = -25.2593643549416;
    a[14][9] = 7.733878542362238;
    a[14][10] = -1.8913028948478674;
    a[14][11] = 1.0014845070224718;
    a[14][12] = 0.004641199599109052;
    a[14][13] = 0.011218755022148957;
    a[15][0] = -0.27519629720559396;
    a[15][2] = 0.03661188877915492;
    a[15][3] = 0.009789519688231562;
    a[15][4] = -12.293062345886211;
    a[15][5] = 14.207226453937903;
    a[15][6] = 1.5866476906789537;
    a[15][7] = 2.4577735327595946;
    a[15][8] = -8.935193694403273;
    a[15][9] = 4.373672731613407;
    a[15][10] = -1.8347181765449492;
    a[15][11] = 1.1592085289061491;
    a[15][12] = -0.017290253165383924;
    a[15][13] = 0.019325977904460768;
    a[15][14] = 0.005204442937554993;
    a[16][0] = 1.3076391847404059;
    a[16][2] = 0.017364109189745843;
    a[16][3] = -0.018544456454265796;
    a[16][4] = 14.811522032867726;
    a[16][5] = 9.38317630848247;
    a[16][6] = -5.2284261999445425;
    a[16][7] = -48.95128052584765;
    a[16][8] = 38.297096034337926;
    a[16][9] = -10.58738133697598;
    a[16][10] = 2.4332304376226275;
    a[16][11] = -1.0453406042575444;
    a[16][12] = 0.0717732095086726;
    a[16][13] = 0.0021622109708082783;
    a[16][14] = 0.007009595759602514;
    let b_bar = [
        0.012127868517185414,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.08629746251568875,
        0.2525469581187147,
        -0.1974186799326823,
        0.2031869190789726,
        -0.020775808077714918,
        0.10967804874502014,
        0.038065132526466504,
        0.01163406880432423,
        0.0046580297040248785,
        0.0,
        0.0,
    ];
    let b = [
        0.012127868517185414,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.09083943422704079,
        0.3156836976483934,
        -0.2632249065769097,
        0.3047803786184589,
        -0.041551616155429835,
        0.2467756096762953,
        0.15226053010586602,
        0.08143848163026961,
        0.08502571193890811,
        -0.009155189630077963,
        0.025,
    ];
    let embedded_b_bar = [
        0.01700870190700699,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0722593359308314,
        0.372026177326753,
        -0.40182114500930355,
        0.3354550683013517,
        -0.13130650107533182,
        0.18943190661604864,
        0.026840802040029046,
        0.016305665605917924,
        0.0037999883566965944,
        0.0,
        0.0,
    ];
    let embedded_b = [
        0.01700870190700699,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.07606245887455937,
        0.4650327216584413,
        -0.5357615266790714,
        0.5031826024520275,
        -0.26261300215066363,
        0.4262217898861095,
        0.10736320816011619,
        0.11413965924142547,
        0.06936338665004868,
        0.02,
        0.0,
    ];
    NystromTable::new(
        SchemeMeta {
            id: "rkn12-dormand-el-mikkawy-prince",
            name: "Dormand-El-Mikkawy-Prince RKN12(10), 17 stages (Runge-Kutta-Nystrom, fixed step)",
            order: 12,
            symplectic: false,
            symmetric: false,
            force_evaluations: 0, // derived by `new`
            implicit: false,
            reference: "J. R. Dormand, M. E. A. El-Mikkawy, P. J. Prince, High-order embedded Runge-Kutta-Nystrom formulae, IMA J. Numer. Anal. 7, 423 (1987) (RKN12(10)17M)",
            phase_error: None,
        },
        c,
        a,
        b_bar,
        b,
        Some(Embedded {
            order: 10,
            b_bar: embedded_b_bar,
            b: embedded_b,
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
