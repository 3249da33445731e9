//! Linear stability against its analytic values, and runs above the limit
//! that must end early with a clear verdict.

use stepladder::internals::accuracy::phase::one_step_matrix;
use stepladder::internals::geometry::energy::{EnergySpec, energy_drift};
use stepladder::internals::run::Outcome;
use stepladder::internals::stability::{StabilityRecord, spectral_radius, stability};
use stepladder::internals::verdict::Verdict;
use stepladder::scene::Harmonic;
use stepladder::scheme::{Scheme, SchemeVisitor, VELOCITY_VERLET, scheme_ids, visit_scheme};

struct Stability;
impl SchemeVisitor for Stability {
    type Output = StabilityRecord;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> StabilityRecord {
        stability(scheme)
    }
}

fn limit(id: &str) -> StabilityRecord {
    visit_scheme(id, Stability).unwrap()
}

/// Every scheme whose one-step map on the oscillator has determinant 1 and
/// trace `2 - z^2` (the Verlet family and Euler-Cromer) is stable exactly
/// while `|2 - z^2| < 2`, that is for `z < 2`.
#[test]
fn verlet_family_and_euler_cromer_are_stable_up_to_two() {
    for id in [
        "euler-cromer",
        "stormer-verlet",
        "leapfrog",
        "velocity-verlet",
        "position-verlet",
    ] {
        let r = limit(id);
        let z = r.stability_limit.expect("a finite limit");
        assert!((z - 2.0).abs() < 1e-9, "{id}: {z}");
        assert_eq!(
            r.stable_intervals.len(),
            1,
            "{id}: {:?}",
            r.stable_intervals
        );
    }
}

/// Explicit Euler's eigenvalues `1 -+ i z` have modulus `sqrt(1 + z^2) > 1`
/// for every `z > 0`: stable for no step.
#[test]
fn explicit_euler_is_stable_for_no_step() {
    let r = limit("euler");
    assert_eq!(r.stability_limit, Some(0.0));
    assert!(r.stable_intervals.is_empty());
}

/// RK4: `|R(iz)|^2 = 1 - z^6/72 + z^8/576 <= 1` exactly while `z^2 <= 8`.
#[test]
fn rk4_is_stable_up_to_two_root_two() {
    let r = limit("rk4");
    let z = r.stability_limit.expect("a finite limit");
    assert!((z - 8f64.sqrt()).abs() < 1e-9, "{z}");
    assert!((r.limit_per_force_evaluation.unwrap() - 8f64.sqrt() / 4.0).abs() < 1e-9);
}

/// The implicit midpoint rule's eigenvalues `(1 + iz/2)/(1 - iz/2)` have
/// modulus one for every `z`: stable for every step, reported as no limit.
#[test]
fn implicit_midpoint_is_stable_for_every_step() {
    let r = limit("implicit-midpoint");
    assert_eq!(r.stability_limit, None, "{r:?}");
    assert_eq!(r.stable_intervals, vec![[Some(0.0), None]]);
}

/// Every gap between two stable intervals is a real instability, not
/// round-off splitting one interval: somewhere inside it the spectral radius
/// exceeds 1 by far more than the `1e-13` a many-stage map's rounding gives.
struct Gaps;
impl SchemeVisitor for Gaps {
    type Output = Vec<String>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Vec<String> {
        let r = stability(scheme);
        r.stable_intervals
            .windows(2)
            .filter_map(|w| {
                let (b, c) = (
                    w[0][1].expect("a closed interval"),
                    w[1][0].expect("a start"),
                );
                let worst = (1..16)
                    .map(|k| b + (c - b) * k as f64 / 16.0)
                    .filter_map(|z| one_step_matrix(scheme, z).map(|m| spectral_radius(&m)))
                    .fold(0.0, f64::max);
                (worst < 1.0 + 1e-8)
                    .then(|| format!("{}: gap ({b}, {c}) peaks at radius {worst}", r.scheme))
            })
            .collect()
    }
}

#[test]
fn gaps_between_stable_intervals_are_real_instabilities() {
    let spurious: Vec<String> = scheme_ids()
        .into_iter()
        .flat_map(|id| visit_scheme(id, Gaps).unwrap())
        .collect();
    assert!(spurious.is_empty(), "{spurious:#?}");
}

/// `h w0 = 2.5` is beyond velocity Verlet's limit 2: the run must stop as
/// soon as the state leaves the bound, and say so.
#[test]
fn a_stiff_oscillator_above_the_limit_ends_early_with_a_clear_verdict() {
    let stiff = Harmonic::new(50.0, 1.0, 0.0).unwrap();
    let r = energy_drift(
        &VELOCITY_VERLET,
        &stiff,
        &EnergySpec {
            h: Some(0.05),
            periods: None,
        },
    )
    .unwrap();
    let Outcome::Unstable { h, step, .. } = r.outcome else {
        panic!("{:?}", r.outcome)
    };
    assert_eq!(h, 0.05);
    // the larger eigenvalue is 2.67 in modulus (2.5^2/2 - 1 + sqrt(...)): the
    // state grows by 1e6 within about 15 steps
    assert!(step < 30, "stopped only after {step} steps");
    assert!(r.reason.starts_with("unstable: q[0] = "), "{}", r.reason);
    // the reason says why: the step is past the scheme's limit, and a finer
    // one runs
    assert!(
        r.reason
            .contains("h w = 2.50 is past the scheme's linear stability limit h w = 2.00"),
        "{}",
        r.reason
    );
    assert_eq!(r.verdict, Verdict::Inconclusive, "{}", r.reason);
}

// ---------------------------------------------------------------------------
// Maps unstable at every step: the growth law against independent values.

use stepladder::internals::stability::{
    GrowthLaw, GrowthSource, determinant_round_off, growth_law, per_period,
};
use stepladder::internals::tolerance::{
    GROWTH_POWER_TOLERANCE, GROWTH_VALUE_RESOLUTION, STABILITY_BISECTION,
};
use stepladder::scheme::{BlackBox, DPRKN6, FOREST_RUTH, Force, QUINLAN_TREMAINE8, SchemeMeta};

/// DPRKN6's `det M - 1 = d4 z^8 + d5 z^10` and its growth, exactly: the
/// output of `python3 tests/check_dprkn6_stability.py`, which solves the
/// stage equations of the published tableau (closed forms in `sqrt(8581)`)
/// in exact arithmetic and evaluates in 40 digits.
mod dprkn6_exact {
    /// `9384727/218700000000 - 40339 sqrt(8581)/109350000000`.
    pub const D4: f64 = 8.739_032_400_259_419e-6;
    /// `-1383173/729000000000 + 6461 sqrt(8581)/364500000000`.
    pub const D5: f64 = -2.553_641_897_108_985e-7;
    /// `(z, rho - 1, rho^(2 pi / z) - 1)`, to 12 digits.
    pub const GROWTH: [(f64, f64, f64); 5] = [
        (0.1, 4.36823937918e-14, 2.74464574856e-12),
        (0.5, 1.69437329675e-8, 2.12921248924e-7),
        (1.0, 4.24182510873e-6, 2.66524718429e-5),
        (2.0, 0.000987362240005, 0.00310517070801),
        (3.0, 0.0209102759498, 0.0442958052428),
    ];
    /// Relative rounding of the figures above (12 significant digits).
    pub const DIGITS: f64 = 5e-12;
    /// The one stable window: `det M = 1` at its lower end, `|trace| = 1 +
    /// det` at its upper.
    pub const STABLE_WINDOW: [f64; 2] = [5.8499435755, 5.88957742249];
}

/// Polynomials in `w = z^2`, constant term first, with a running bound of
/// the absolute values (for a round-off bound of the result).
#[derive(Clone)]
struct Poly {
    value: Vec<f64>,
    size: Vec<f64>,
}

impl Poly {
    fn constant(x: f64) -> Self {
        Poly {
            value: vec![x],
            size: vec![x.abs()],
        }
    }
    fn axpy(&mut self, a: f64, other: &Poly, shift: usize) {
        let n = other.value.len() + shift;
        self.value.resize(n.max(self.value.len()), 0.0);
        self.size.resize(self.value.len(), 0.0);
        for (j, (v, s)) in other.value.iter().zip(&other.size).enumerate() {
            self.value[j + shift] += a * v;
            self.size[j + shift] += a.abs() * s;
        }
    }
    fn times(&self, other: &Poly) -> Poly {
        let n = self.value.len() + other.value.len() - 1;
        let mut out = Poly {
            value: vec![0.0; n],
            size: vec![0.0; n],
        };
        for i in 0..self.value.len() {
            for j in 0..other.value.len() {
                out.value[i + j] += self.value[i] * other.value[j];
                out.size[i + j] += self.size[i] * other.size[j];
            }
        }
        out
    }
    fn at(&self, z: f64) -> (f64, f64) {
        let w = z * z;
        let eval = |c: &[f64]| c.iter().rev().fold(0.0, |acc, x| acc * w + x);
        (eval(&self.value), eval(&self.size))
    }
}

/// DPRKN6's `det M(z) - 1` as a polynomial in `w = z^2`, from its tableau
/// arrays by the stage algebra (no stepping): with `p = h v` the scaled
/// stages `K_i = h^2 k_i` satisfy `K_i = -w (q + c_i p + sum_j a_ij K_j)`, a
/// forward substitution, and `q' = q + p + b_bar . K`, `p' = p + b . K`.
fn dprkn6_determinant() -> Poly {
    let t = &DPRKN6;
    let column = |q: f64, p: f64| {
        let mut k: Vec<Poly> = Vec::new();
        for i in 0..6 {
            let mut inner = Poly::constant(q + t.c[i] * p);
            for (j, kj) in k.iter().enumerate() {
                inner.axpy(t.a[i][j], kj, 0);
            }
            let mut stage = Poly::constant(0.0);
            stage.axpy(-1.0, &inner, 1);
            k.push(stage);
        }
        let (mut qn, mut pn) = (Poly::constant(q + p), Poly::constant(p));
        for (j, kj) in k.iter().enumerate() {
            qn.axpy(t.b_bar[j], kj, 0);
            pn.axpy(t.b[j], kj, 0);
        }
        (qn, pn)
    };
    let ((m11, m21), (m12, m22)) = (column(1.0, 0.0), column(0.0, 1.0));
    let mut det = m11.times(&m22);
    det.axpy(-1.0, &m12.times(&m21), 0);
    det.value[0] -= 1.0;
    det.size[0] += 1.0;
    det
}

/// Round-off of [`dprkn6_determinant`] per unit of the absolute values it
/// summed: fewer than 128 roundings lie on any path (six chained stages of
/// at most eight terms, the weights' sums, the products of the
/// determinant, and the rounding of each table entry), so `128 eps` bounds
/// the relative error of every coefficient's absolute-value sum.
const ALGEBRA_ROUND_OFF: f64 = 128.0 * f64::EPSILON;

/// The crate's tableau gives, by algebra alone, the published
/// `det M - 1 = d4 z^8 + d5 z^10`: the terms below `z^8` cancel and those
/// above `z^10` vanish to round-off.
#[test]
fn dprkn6_tableau_gives_the_published_determinant() {
    let det = dprkn6_determinant();
    let expected = |j: usize| match j {
        4 => dprkn6_exact::D4,
        5 => dprkn6_exact::D5,
        _ => 0.0,
    };
    for (j, (v, s)) in det.value.iter().zip(&det.size).enumerate() {
        let bound = ALGEBRA_ROUND_OFF * s + 1e-19 * expected(j).abs();
        assert!(
            (v - expected(j)).abs() <= bound,
            "w^{j}: {v:e} against {:e} (bound {bound:e})",
            expected(j)
        );
    }
}

/// DPRKN6's map grows at every `z` up to 5.85: reported weakly unstable with
/// limit 0, the law `d4 z^8` of the exact determinant, and its growth per
/// step and per period at each `z` equal to the exact values to within the
/// round-off of the stepped map.
#[test]
fn dprkn6_is_weakly_unstable_with_the_exact_growth() {
    let r = limit("rkn6-dormand-prince");
    assert_eq!(r.stability_limit, Some(0.0), "{r:?}");
    assert_eq!(r.limit_per_force_evaluation, Some(0.0));
    assert!(r.weakly_unstable(), "{r:?}");
    let g: &GrowthLaw = r.growth.as_ref().unwrap();
    assert_eq!(g.power, 8);
    assert!((g.power_fitted - 8.0).abs() <= GROWTH_POWER_TOLERANCE);
    // the fit of (det - 1)/z^8 linear in z^2 is exact for d4 + d5 z^2: only
    // round-off separates its intercept from d4
    let table_round_off = ALGEBRA_ROUND_OFF * dprkn6_determinant().size[4];
    assert!(
        (g.coefficient - dprkn6_exact::D4).abs() <= g.coefficient_round_off + table_round_off,
        "{} against {}",
        g.coefficient,
        dprkn6_exact::D4
    );
    // the stable interval [0, b] a plain scan sees ends where d4 z^8 meets
    // the round-off bound `res` (5 evaluations: products are 1 at small z);
    // the actual round-off is at most a third of `res` (the slack's margin),
    // so d4 b^8 lies in [2/3, 4/3] res
    let res = 2.0 * r.growth_resolution.unwrap();
    let predicted = (res / dprkn6_exact::D4).powf(1.0 / 8.0);
    let b = g.unresolved_below.unwrap();
    assert!(
        b >= predicted * (2.0f64 / 3.0).powf(0.125) && b <= predicted * (4.0f64 / 3.0).powf(0.125),
        "{b} against {predicted}"
    );
    // the one genuinely stable window, where det < 1
    assert_eq!(r.stable_intervals.len(), 1, "{:?}", r.stable_intervals);
    let [lo, hi] = r.stable_intervals[0];
    for (got, want) in [lo, hi].into_iter().zip(dprkn6_exact::STABLE_WINDOW) {
        assert!(
            (got.unwrap() - want).abs() < 10.0 * STABILITY_BISECTION,
            "{got:?} against {want}"
        );
    }
    let det = dprkn6_determinant();
    for (z, step, period) in dprkn6_exact::GROWTH {
        let at = g.at.iter().find(|a| a.z == z).expect("every z reported");
        let (got_step, got_period) = (at.per_step.unwrap(), at.per_period.unwrap());
        let bound_step = match at.source {
            // rho - 1 = (det - 1)/(1 + sqrt(det)): the stepped determinant's
            // round-off bound and the table's, over 1 + sqrt(det) >= 2
            GrowthSource::Measured => {
                let m = one_step_matrix(&DPRKN6, z).unwrap();
                0.5 * (determinant_round_off(&DPRKN6, &m) + ALGEBRA_ROUND_OFF * det.at(z).1)
            }
            // c z^8 / 2 leaves out d5 z^10 / 2, and c carries its round-off
            GrowthSource::Law => {
                step * ((dprkn6_exact::D5 / dprkn6_exact::D4).abs() * z * z
                    + (g.coefficient_round_off + table_round_off) / g.coefficient)
            }
            GrowthSource::Unresolved => panic!("z = {z}: unresolved"),
        } + dprkn6_exact::DIGITS * step;
        assert!(
            (got_step - step).abs() <= bound_step,
            "z = {z}: {got_step:e} per step against {step:e} (bound {bound_step:e})"
        );
        // per period = exp((2 pi / z) ln(1 + step)) - 1 moves by
        // (2 pi / z)(1 + period)/(1 + step) per unit of step
        let bound_period = std::f64::consts::TAU / z * (1.0 + period) * bound_step
            + 2.0 * dprkn6_exact::DIGITS * period;
        assert!(
            (got_period - period).abs() <= bound_period,
            "z = {z}: {got_period:e} per period against {period:e}"
        );
    }
    // below z = 0.5 nothing is measured: z = 0.1 comes from the law
    assert_eq!(g.at[0].source, GrowthSource::Law);
    assert!(g.at[1..].iter().all(|a| a.source == GrowthSource::Measured));
}

/// Explicit Euler: `det M = 1 + z^2` exactly, `rho = sqrt(1 + z^2)`. Its
/// growth is resolved from the first point of the scan, so it is unstable
/// (limit 0, as before) but not weakly.
#[test]
fn explicit_euler_grows_as_its_determinant_says() {
    let r = limit("euler");
    assert_eq!(r.stability_limit, Some(0.0));
    assert!(!r.weakly_unstable());
    let g = r.growth.expect("a growth law");
    assert_eq!(g.power, 2);
    assert!((g.coefficient - 1.0).abs() <= g.coefficient_round_off);
    for a in &g.at {
        assert_eq!(a.source, GrowthSource::Measured);
        let exact = (1.0 + a.z * a.z).sqrt() - 1.0;
        assert!(
            (a.per_step.unwrap() - exact).abs() <= 4.0 * f64::EPSILON,
            "{a:?}"
        );
        assert!(
            (a.per_period.unwrap() - per_period(exact, a.z)).abs()
                <= 1e-13 * (1.0 + a.per_period.unwrap())
        );
    }
}

/// Damped maps at small `z` are stable there, not weakly unstable: RK4
/// (`det M - 1 = -z^6/72 + z^8/576`) and Nystrom's method (`det M - 1 =
/// -z^6/288`, `tests/check_dprkn6_stability.py`), whose limits come from
/// a zero of `det - 1` (RK4, `z^2 = 8`) and from the trace condition
/// (Nystrom) — neither from round-off.
#[test]
fn damped_maps_are_not_weakly_unstable() {
    for id in ["rk4", "rkn4-nystrom"] {
        let r = limit(id);
        assert!(r.growth.is_none(), "{id}: {:?}", r.growth);
        assert!(r.stability_limit.unwrap() > 2.5, "{id}: {r:?}");
        // the map's determinant is resolvably below 1 at small z
        let z = 0.1;
        let m = match id {
            "rk4" => visit_scheme(id, MatrixAt(z)).unwrap(),
            _ => one_step_matrix(&stepladder::scheme::NYSTROM4, z).unwrap(),
        };
        let exact = if id == "rk4" {
            -z.powi(6) / 72.0 + z.powi(8) / 576.0
        } else {
            -z.powi(6) / 288.0
        };
        assert!(
            (m.determinant() - 1.0 - exact).abs() < 1e-14,
            "{id}: {:e} against {exact:e}",
            m.determinant() - 1.0
        );
    }
}

struct MatrixAt(f64);
impl SchemeVisitor for MatrixAt {
    type Output = nalgebra::Matrix2<f64>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        one_step_matrix(scheme, self.0).unwrap()
    }
}

/// No symplectic scheme of the catalogue has a growth law (its determinant
/// is 1 to round-off at every `z`), and each has a stable interval from 0.
struct GrowthOf;
impl SchemeVisitor for GrowthOf {
    type Output = (bool, StabilityRecord);
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        (scheme.meta().symplectic, stability(scheme))
    }
}

#[test]
fn symplectic_schemes_have_no_growth_and_keep_their_limits() {
    for id in scheme_ids() {
        let (symplectic, r) = visit_scheme(id, GrowthOf).unwrap();
        if symplectic {
            assert!(r.growth.is_none(), "{id}: {:?}", r.growth);
            assert_eq!(r.stable_intervals[0][0], Some(0.0), "{id}");
        }
    }
}

/// Forest-Ruth is three velocity Verlet steps of `theta z, (1 - 2 theta) z,
/// theta z`: its limit is where the trace of the product of three exact
/// Verlet matrices reaches -2 (the determinant is 1), found here by
/// bisection of that product, independently of the crate's stepper.
#[test]
fn forest_ruth_limit_is_where_its_composed_trace_reaches_two() {
    let theta = 1.0 / (2.0 - 2f64.cbrt());
    let verlet = |z: f64| {
        nalgebra::Matrix2::new(
            1.0 - z * z / 2.0,
            z,
            -z * (1.0 - z * z / 4.0),
            1.0 - z * z / 2.0,
        )
    };
    let excess = |z: f64| {
        let m = verlet(theta * z) * verlet((1.0 - 2.0 * theta) * z) * verlet(theta * z);
        m.trace().abs() - 2.0
    };
    let (mut lo, mut hi) = (1.5, 1.6);
    assert!(excess(lo) < 0.0 && excess(hi) > 0.0);
    while hi - lo > 1e-13 {
        let mid = 0.5 * (lo + hi);
        if excess(mid) < 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    let r = stability(&FOREST_RUTH);
    assert!(r.growth.is_none());
    // the bisection's width, and the shift of the edge by the trace slack
    // (a few eps over a trace slope of order one)
    assert!(
        (r.stability_limit.unwrap() - lo).abs() <= STABILITY_BISECTION + 1e-12,
        "{:?} against {lo}",
        r.stability_limit
    );
}

/// A multistep recurrence is judged by its roots: no growth law, no
/// growth resolution, and the resonance limit as before.
#[test]
fn multistep_recurrences_keep_their_root_test() {
    let r = stability(&QUINLAN_TREMAINE8);
    assert!(r.growth.is_none() && r.growth_resolution.is_none(), "{r:?}");
    assert!(growth_law(&QUINLAN_TREMAINE8).is_none());
    assert!((0.70..0.74).contains(&r.stability_limit.unwrap()), "{r:?}");
}

// ---------------------------------------------------------------------------
// Synthetic maps whose determinant is known exactly: adversarial cases the
// growth rule was not designed on.

/// The step of a synthetic black box.
type SyntheticStep = Box<dyn Fn(&mut [f64], &mut [f64], f64, &Force<'_, f64>)>;

/// A black box that applies `sqrt(det(z))` times the rotation by `z` (w0 =
/// 1, one force evaluation made and ignored): a map with eigenvalues of
/// modulus `sqrt(det)`, whose `det - 1` is given by `excess(z)` (computed
/// without cancellation).
fn scaled_rotation(id: &'static str, excess: fn(f64) -> f64) -> BlackBox<f64, SyntheticStep> {
    let meta = SchemeMeta {
        id,
        name: "scaled rotation (synthetic)",
        order: 1,
        symplectic: false,
        symmetric: false,
        force_evaluations: 1,
        implicit: false,
        reference: "synthetic: a rotation by z scaled by sqrt(det)",
        phase_error: None,
    };
    BlackBox::new(
        meta,
        Box::new(
            move |q: &mut [f64], v: &mut [f64], h: f64, force: &Force<'_, f64>| {
                let mut a = [0.0];
                force(q, &mut a);
                let e = excess(h);
                let scale = 1.0 + e / (1.0 + (1.0 + e).sqrt());
                let (s, c) = h.sin_cos();
                let (q0, v0) = (q[0], v[0]);
                q[0] = scale * (c * q0 + s * v0);
                v[0] = scale * (-s * q0 + c * v0);
            },
        ),
    )
}

/// `det = 1 + 1e-12 z^12`: below round-off up to `z = 0.66`, where a plain
/// scan ends a "stable" interval; resolved above it, it must be reported
/// weakly unstable with the law it was built with.
#[test]
fn a_synthetic_twelfth_power_growth_is_weakly_unstable() {
    let bb = scaled_rotation("growth-z12", |z| 1e-12 * z.powi(12));
    let r = stability(&bb);
    assert_eq!(r.stability_limit, Some(0.0), "{r:?}");
    assert!(r.weakly_unstable());
    let g = r.growth.unwrap();
    assert_eq!(g.power, 12);
    assert!(
        (g.coefficient - 1e-12).abs() <= g.coefficient_round_off,
        "{g:?}"
    );
    // it ends where 1e-12 z^12 meets the round-off bound (32 eps, one
    // evaluation, unit products), within the slack's margin of three
    let res = 32.0 * f64::EPSILON;
    let predicted = (res / 1e-12).powf(1.0 / 12.0);
    let b = g.unresolved_below.unwrap();
    assert!(
        (b / predicted).powi(12) > 2.0 / 3.0 && (b / predicted).powi(12) < 4.0 / 3.0,
        "{b} against {predicted}"
    );
    // below its window the growth comes from the law, above it is measured
    for a in &g.at {
        let e = 1e-12 * a.z.powi(12);
        let exact = e / (1.0 + (1.0 + e).sqrt());
        // a measured det - 1 is within 1/64 of itself (its resolution), the
        // law's within its coefficient's round-off
        let bound = match a.source {
            GrowthSource::Law => {
                assert!(a.z < g.window[0]);
                g.coefficient_round_off / g.coefficient
            }
            GrowthSource::Measured => 1.0 / GROWTH_VALUE_RESOLUTION,
            GrowthSource::Unresolved => panic!("{a:?}"),
        };
        assert!(
            (a.per_step.unwrap() / exact - 1.0).abs() <= bound,
            "{a:?} against {exact:e}"
        );
    }
}

/// `det = 1 + 1e-20 z^2/(1 + z^2)`: unstable at every `z > 0` in exact
/// arithmetic, but by at most `5e-21` a step, far below what a double can
/// resolve at any `z`. The honest answer is "no growth resolvable in double
/// precision": no growth law and no limit at some round-off crossing (the
/// map is reported stable at every step scanned, and the record's growth
/// resolution says how small a growth that claim covers).
#[test]
fn a_growth_below_round_off_everywhere_is_not_resolved() {
    let bb = scaled_rotation("growth-unresolvable", |z| 1e-20 * z * z / (1.0 + z * z));
    let r = stability(&bb);
    assert!(r.growth.is_none(), "{r:?}");
    assert_eq!(r.stability_limit, None, "{r:?}");
    assert!(r.growth_resolution.unwrap() > 1e-20);
}

/// `det - 1 = 1e-3 (z^8 - z^6)`: damped below `z = 1`, growing above. The
/// limit is the zero of `det - 1` at 1, a physical boundary, and the map is
/// not weakly unstable: where `det - 1` is first resolved it is negative.
#[test]
fn a_damped_map_growing_past_a_zero_has_a_real_limit() {
    let bb = scaled_rotation("damped-then-growing", |z| 1e-3 * (z.powi(8) - z.powi(6)));
    let r = stability(&bb);
    assert!(r.growth.is_none(), "{r:?}");
    // det - 1 rises at rate 2e-3 through z = 1: the round-off bound (32 eps)
    // moves the edge by 4e-12, below the bisection's width
    assert!(
        (r.stability_limit.unwrap() - 1.0).abs() <= STABILITY_BISECTION + 1e-11,
        "{r:?}"
    );
}

/// `det = 1` up to `z = 0.3` and `1 + 1e-6 (z - 0.3)` above: a boundary
/// at a simple zero of the growth, not a power law. The growth is first
/// resolved just above 0.3, where its log-slope `z/(z - 0.3)` is far from
/// constant, so no law is fitted and the limit stays at the zero.
#[test]
fn a_simple_zero_of_the_growth_is_not_read_as_a_power_law() {
    let bb = scaled_rotation("simple-zero", |z| 1e-6 * (z - 0.3).max(0.0));
    let r = stability(&bb);
    assert!(r.growth.is_none(), "{r:?}");
    // the round-off bound (32 eps) over the rate 1e-6 moves the edge by 7e-9
    assert!((r.stability_limit.unwrap() - 0.3).abs() <= 1e-8, "{r:?}");
}
