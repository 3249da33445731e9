//! Properties over random inputs: the window and the fit recover any power
//! law they are given, and a correct scheme passes on any oscillator.

use proptest::prelude::*;
use stepladder::internals::accuracy::order::{OrderSpec, RungData, analyse, global_order};
use stepladder::internals::geometry::reverse::{ReverseSpec, reversibility};
use stepladder::internals::ladder::AUTO_MAX_RUNG_EVALUATIONS;
use stepladder::internals::ladder::per_octave;
use stepladder::internals::maths::tangent::step_jacobian;
use stepladder::internals::run::integrate;
use stepladder::internals::tolerance::{MIN_WINDOW_HALVINGS, clean_fraction, order_verdict};
use stepladder::scene::Harmonic;
use stepladder::scene::Scene;
use stepladder::scheme::{Scheme, SchemeVisitor, VELOCITY_VERLET, scheme_ids, visit_scheme};
use stepladder::state::State;

/// Cases per property: 64, or `PROPTEST_CASES` when set (to search harder).
fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(64)
}

proptest! {
    // the floor property rejects the draws whose clean rungs cannot span a window
    #![proptest_config(ProptestConfig {
        max_global_rejects: cases().max(1024),
        ..ProptestConfig::with_cases(cases())
    })]

    /// Errors `C h^p (1 + r h / h0)` plus round-off `u_k f / h` on the
    /// automatic ladder's ratio from `h0`, where the error is 3% of the
    /// orbit; the round-off's size varies from rung to rung (`u_k` in [0.5,
    /// 1.5), as each run rounds differently) and the analysis is given its
    /// bound `1.5 f / h`, as the twins' law would give it. Time is in units of
    /// the run, down to `AUTO_MAX_RUNG_EVALUATIONS` steps. Wherever the clean rungs
    /// (round-off bound within `clean_fraction` of the error) span the
    /// window's two halvings, the window must lie among them and the verdict
    /// must accept `p`.
    #[test]
    fn window_and_fit_recover_a_power_law_above_a_floor(
        p in 1.0f64..8.0,
        log_c in -3.0f64..3.0,
        r in -0.3f64..0.3,
        floor in 1e-17f64..1e-15,
    ) {
        let c = 10f64.powf(log_c);
        let h0 = (0.03 / c).powf(1.0 / p);
        let m = per_octave(p.ceil() as u32);
        let ratio = 2f64.powf(-1.0 / m as f64);
        let finest = 1.0 / AUTO_MAX_RUNG_EVALUATIONS as f64;
        let bound = |h: f64| 1.5 * floor / h;
        // the finest step whose round-off bound is a clean part of its error
        let clean_below = (bound(1.0) / (clean_fraction(ratio.recip().ln(), p) * c)).powf(1.0 / (p + 1.0));
        prop_assume!((h0 / clean_below.max(finest)).log2() > MIN_WINDOW_HALVINGS + 1.0);
        let data: Vec<RungData> = (0..200)
            .map(|k| h0 * ratio.powi(k))
            .take_while(|&h| h >= finest)
            .enumerate()
            .map(|(k, h)| {
                // a pseudo-random draw per rung, independent of its neighbours
                let bits = (k as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ p.to_bits();
                let u = 0.5 + (bits.wrapping_mul(0xBF58_476D_1CE4_E5B9) >> 11) as f64 / (1u64 << 53) as f64;
                RungData {
                    h,
                    error: Some(c * h.powf(p) * (1.0 + r * h / h0) + u * floor / h),
                    round_off: bound(h),
                }
            })
            .collect();
        let analysis = analyse(&data, 1.0);
        let (a, b) = analysis.choice.window.expect("a window exists");
        let (fit, interval) = (analysis.fit.expect("a fit exists"), analysis.ci95.unwrap());
        let verdict = order_verdict(p, fit.order, interval);
        prop_assert!(verdict.is_ok(), "p = {p}, {verdict:?}: {fit:?} over {a}..{b}, trend {:?}", analysis.trend_systematic);
        // the last fitted rung's round-off is a clean part of its error
        let last = data[b];
        prop_assert!(
            last.round_off < clean_fraction(ratio.recip().ln(), p + 1.0) * last.error.unwrap(),
            "rung {b} at e = {:?} is on the floor {}", last.error, last.round_off
        );
    }

    /// Velocity Verlet is second order on any oscillator, whatever its
    /// frequency, amplitude and phase: the measured order must not depend on
    /// the units of time and length.
    #[test]
    fn velocity_verlet_passes_on_any_oscillator(
        w0 in 0.01f64..100.0,
        x0 in -10.0f64..10.0,
        v0 in -10.0f64..10.0,
    ) {
        prop_assume!(x0.abs() + v0.abs() > 1e-3);
        let osc = Harmonic::new(w0, x0, v0).unwrap();
        let r = global_order(&VELOCITY_VERLET, &osc, &OrderSpec::default()).unwrap();
        prop_assert!(r.passed(), "w0 = {w0}, x0 = {x0}, v0 = {v0}: {}", r.reason);
    }
}

/// The tangent-map and reversibility claims of one scheme on one oscillator.
struct Tangent {
    w0: f64,
    x0: f64,
    v0: f64,
    z: f64,
}

impl SchemeVisitor for &Tangent {
    type Output = Result<(), String>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        let meta = scheme.meta();
        let osc = Harmonic::new(self.w0, self.x0, self.v0).map_err(|e| e.to_string())?;
        let h = self.z / self.w0;
        let j = step_jacobian(scheme, &osc, &osc.initial(), h).map_err(|e| e.to_string())?;
        let defect = (j.determinant() - 1.0).abs();
        if meta.symplectic && defect > 1e-13 {
            return Err(format!("{}: det J - 1 = {defect:e}", meta.id));
        }
        if meta.symmetric {
            let r = reversibility(
                scheme,
                &osc,
                &ReverseSpec {
                    h: Some(h),
                    steps: Some(200),
                },
            )
            .map_err(|e| e.to_string())?;
            if !r.measured {
                return Err(format!("{}: {}", meta.id, r.reason));
            }
        }
        Ok(())
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Over random oscillators, states and stable steps (`h w0 < 1.5`, inside
    /// every catalogue scheme's stability interval): symplectic schemes have
    /// `det J = 1`, symmetric ones come back when run backwards.
    #[test]
    fn symplectic_and_symmetric_claims_hold_for_any_oscillator_and_step(
        w0 in 0.05f64..20.0,
        x0 in -5.0f64..5.0,
        v0 in -5.0f64..5.0,
        z in 0.01f64..1.5,
    ) {
        prop_assume!(x0.abs() + v0.abs() > 1e-3);
        let t = Tangent { w0, x0, v0, z };
        for id in scheme_ids() {
            let result = visit_scheme(id, &t).unwrap();
            prop_assert!(result.is_ok(), "{}", result.unwrap_err());
        }
    }

    /// Velocity Verlet keeps `v^2/2 + w^2 x^2 (1 - z^2/4)/2` to round-off on
    /// any oscillator (see tests/geometry.rs for the derivation).
    #[test]
    fn verlet_modified_energy_is_conserved_for_any_oscillator(
        w0 in 0.05f64..20.0,
        x0 in -5.0f64..5.0,
        v0 in -5.0f64..5.0,
        z in 0.01f64..1.9,
    ) {
        prop_assume!(x0.abs() + v0.abs() > 1e-3);
        let osc = Harmonic::new(w0, x0, v0).unwrap();
        let h = z / w0;
        let modified = |s: &State<1>| 0.5 * s.v[0].powi(2) + 0.5 * w0 * w0 * s.q[0].powi(2) * (1.0 - z * z / 4.0);
        let m0 = modified(&osc.initial());
        let mut worst = 0.0f64;
        integrate(&VELOCITY_VERLET, &osc, &osc.initial(), h, 2000, |_, _, s| {
            worst = worst.max((modified(s) - m0).abs() / m0);
        });
        prop_assert!(worst < 1e-12, "modified energy moved by {worst:e}");
    }
}

/// Steps `n` times from `(x0, v0)` and compares with the closed form of the
/// linear one-step map `M` (from one step of the two basis states): with
/// eigenvalues `r e^(-+i t)`, `M^n = r^(n-1) (sin(n t) M - r sin((n-1) t) I) / sin t`
/// (Cayley-Hamilton, `M^2 = 2 r cos t M - r^2 I`).
struct ClosedForm {
    w0: f64,
    x0: f64,
    v0: f64,
    z: f64,
    n: u64,
}

impl SchemeVisitor for &ClosedForm {
    type Output = Result<(), String>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        use stepladder::internals::accuracy::phase::one_step_matrix;
        let id = scheme.meta().id;
        // the matrix of x'' = -x at step z; on w0 the same map in units of 1/w0
        let m = one_step_matrix(scheme, self.z).ok_or(format!("{id}: no step"))?;
        let (det, half_trace) = (m.determinant(), 0.5 * m.trace());
        if half_trace * half_trace >= det {
            return Ok(()); // real eigenvalues: outside the rotation regime
        }
        let r = det.sqrt();
        let t = (half_trace / r).acos();
        let n = self.n as f64;
        let power = (m * (n * t).sin()
            - nalgebra::Matrix2::identity() * (r * ((n - 1.0) * t).sin()))
            * (r.powf(n - 1.0) / t.sin());
        // the scene's state in the oscillator's units: (x, v / w0)
        let osc = Harmonic::new(self.w0, self.x0, self.v0).unwrap();
        let h = self.z / self.w0;
        let mut end = osc.initial();
        if !integrate(scheme, &osc, &osc.initial(), h, self.n, |_, _, s| end = *s).completed() {
            return Ok(()); // grew past the blow-up bound: nothing to compare at the end
        }
        let expected = power * nalgebra::Vector2::new(self.x0, self.v0 / self.w0);
        let size = self.x0.abs() + (self.v0 / self.w0).abs();
        let miss =
            ((end.q[0] - expected[0]).abs() + (end.v[0] / self.w0 - expected[1]).abs()) / size;
        // round-off in n steps, and in the closed form's angle (n t to a few ulps)
        let bound = 1e-13 * n.max(1.0) * power.amax().max(1.0);
        if miss > bound {
            return Err(format!(
                "{id}: z = {}, n = {}: missed the closed form by {miss:e} (bound {bound:e})",
                self.z, self.n
            ));
        }
        Ok(())
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// On any oscillator and at any stable step, every scheme's trajectory
    /// is its one-step matrix to the power `n`: the carry (two-step,
    /// staggered, reused accelerations, implicit solves) adds nothing.
    #[test]
    fn the_numerical_oscillator_is_the_one_step_matrix_to_the_power_n(
        w0 in 0.05f64..20.0,
        x0 in -5.0f64..5.0,
        v0 in -5.0f64..5.0,
        z in 0.01f64..1.0,
        n in 1u64..2000,
    ) {
        prop_assume!(x0.abs() + v0.abs() > 1e-3);
        let case = ClosedForm { w0, x0, v0, z, n };
        for id in scheme_ids() {
            let result = visit_scheme(id, &case).unwrap();
            prop_assert!(result.is_ok(), "{}", result.unwrap_err());
        }
    }
}

// ---------------------------------------------------------------------------
// Units never change a verdict.
//
// A scene in units of length `L` and time `T` times smaller
// (`stepladder::scene::Scaled::units`) is the same motion, and every scheme
// here is the same map on it when its step is measured in the same units
// (`h' v' = L h v`, `h'^2 a' = L h^2 a`). Every threshold of the studies is
// meant to be unit-free, so two things follow:
//
// - With `L` and `T` powers of two every operation of every run is the same
//   operation on numbers that differ by an exact power of two, so the runs
//   are the same bit for bit: each rung's error is exactly `L` times the
//   original, relative energy errors, tangent-map residuals and return
//   errors in ulps are identical. Any difference in a verdict, a window or
//   a drop is then a threshold that depends on the units, with nothing
//   else to blame.
// - With any other `L` and `T` the runs differ by round-off only (every
//   number is rounded anew; the wrapper itself adds a rounding or two to each
//   force and state). Verdicts must agree, and each measured order must lie
//   inside the other's 95% interval: the interval is the study's own
//   statement of how far round-off and the choice of window can move its
//   estimate (never narrower than `ORDER_RESOLUTION` either side), and a
//   rerun that differs only in rounding lands outside it only if that
//   statement is too narrow.
// ---------------------------------------------------------------------------

use stepladder::internals::accuracy::order::OrderRecord;
use stepladder::internals::geometry::energy::{EnergyRecord, EnergySpec, energy_drift};
use stepladder::internals::geometry::reverse::ReverseRecord;
use stepladder::internals::geometry::symplectic::{
    SymplecticRecord, SymplecticSpec, symplecticity,
};
use stepladder::internals::tolerance::ORDER_RESOLUTION;
use stepladder::scene::{Anharmonic, AnyScene, KeplerCircular, KeplerEccentric, Scaled};
use stepladder::study::Verdict;
use stepladder_lab::case::case;

/// The four verdicts of one scheme on one scene, with their records.
#[derive(Clone, Debug)]
struct Verdicts {
    order: OrderRecord,
    energy: EnergyRecord,
    symplectic: SymplecticRecord,
    reverse: ReverseRecord,
}

/// Every study at its defaults.
fn verdicts<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) -> Verdicts {
    Verdicts {
        order: global_order(scheme, scene, &OrderSpec::default()).expect("the order study runs"),
        energy: energy_drift(scheme, scene, &EnergySpec::default()).expect("the energy study runs"),
        symplectic: symplecticity(scheme, scene, &SymplecticSpec::default())
            .expect("the symplecticity study runs"),
        reverse: reversibility(scheme, scene, &ReverseSpec::default())
            .expect("the reversibility study runs"),
    }
}

/// The records in the scene's own units, computed once per scheme and scene
/// for all the draws of a property.
fn original<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) -> Verdicts {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static CACHE: OnceLock<Mutex<HashMap<String, Verdicts>>> = OnceLock::new();
    let meta = scene.meta();
    let key = format!("{} on {} ({})", scheme.meta().id, meta.id, meta.parameters);
    let cache = CACHE.get_or_init(Default::default);
    if let Some(found) = cache.lock().unwrap().get(&key) {
        return found.clone();
    }
    let computed = verdicts(scheme, scene);
    cache.lock().unwrap().insert(key, computed.clone());
    computed
}

/// The two order records agree as two roundings of one run must: the same
/// verdict, and each measured order inside the other's interval.
fn same_order(a: &OrderRecord, b: &OrderRecord) -> Result<(), String> {
    let what = format!("{} on {}", a.scheme, a.scene);
    if a.verdict != b.verdict {
        return Err(format!(
            "{what}: order verdict {:?} ({}) became {:?} ({})",
            a.verdict, a.reason, b.verdict, b.reason
        ));
    }
    match (a.measured_order.zip(a.ci95), b.measured_order.zip(b.ci95)) {
        (Some((p, [lo, hi])), Some((q, [lo2, hi2]))) => {
            if !(lo2..=hi2).contains(&p) || !(lo..=hi).contains(&q) {
                return Err(format!(
                    "{what}: order {p} in [{lo}, {hi}] became {q} in [{lo2}, {hi2}]"
                ));
            }
        }
        (None, None) => {}
        (x, y) => return Err(format!("{what}: order {x:?} became {y:?}")),
    }
    Ok(())
}

/// Same verdicts from every study, same orders within their intervals.
fn same_verdicts(a: &Verdicts, b: &Verdicts) -> Result<(), String> {
    same_order(&a.order, &b.order)?;
    let what = format!("{} on {}", a.order.scheme, a.order.scene);
    let pairs = [
        (
            "energy",
            a.energy.verdict,
            b.energy.verdict,
            &a.energy.reason,
            &b.energy.reason,
        ),
        (
            "symplecticity",
            a.symplectic.verdict,
            b.symplectic.verdict,
            &a.symplectic.reason,
            &b.symplectic.reason,
        ),
        (
            "reversibility",
            a.reverse.verdict,
            b.reverse.verdict,
            &a.reverse.reason,
            &b.reverse.reason,
        ),
    ];
    for (study, x, y, why_x, why_y) in pairs {
        if x != y {
            return Err(format!(
                "{what}: {study} verdict {x:?} ({why_x}) became {y:?} ({why_y})"
            ));
        }
    }
    Ok(())
}

/// The records of one run and of the same run in units `length`, `time`,
/// both powers of two: every measured number is the original's, scaled by
/// its dimension exactly.
///
/// The one exception is the fitted order: the fit sees `ln h` and `ln e`
/// shifted by the constants `ln T` and `ln L`, which its intercept absorbs
/// in exact arithmetic, and its corrections use `h / H`, which does not
/// change; in doubles every logarithm carries one extra rounding, at most
/// `eps |ln x|` < 1.4e-14 for the `|ln x| < 60` of these runs, and the order
/// is a combination of them with weights summing in modulus to at most a few
/// hundred (windows of six or more rungs spanning two halvings of `h`), so it
/// moves by 1e-11 at most. 1e-9 is a hundred times that, and far below what
/// any changed decision (a rung dropped or kept, a window moved) moves it by.
fn same_numbers(a: &Verdicts, b: &Verdicts, length: f64, time: f64) -> Result<(), String> {
    same_verdicts(a, b)?;
    let what = format!(
        "{} on {} in units x {length:e}, x {time:e}",
        a.order.scheme, a.order.scene
    );
    let (oa, ob) = (&a.order, &b.order);
    let scaled = |x: Option<f64>| x.map(|x| x * length);
    let rungs_agree = oa.rungs.len() == ob.rungs.len()
        && oa.rungs.iter().zip(&ob.rungs).all(|(x, y)| {
            x.steps == y.steps
                && scaled(x.error) == y.error
                && scaled(x.round_off_sample) == y.round_off_sample
                && x.dropped == y.dropped
                && x.used == y.used
        });
    if !rungs_agree || oa.window != ob.window || oa.t_end * time != ob.t_end {
        return Err(format!(
            "{what}: the order study's rungs differ: {:?} over {:?} against {:?} over {:?}",
            oa.window,
            oa.rungs
                .iter()
                .map(|r| (r.steps, r.error, r.dropped))
                .collect::<Vec<_>>(),
            ob.window,
            ob.rungs
                .iter()
                .map(|r| (r.steps, r.error.map(|e| e / length), r.dropped))
                .collect::<Vec<_>>(),
        ));
    }
    if let (Some(p), Some(q)) = (oa.measured_order, ob.measured_order)
        && (p - q).abs() > 1e-9
    {
        return Err(format!("{what}: order {p} became {q}"));
    }
    let (ea, eb) = (&a.energy, &b.energy);
    if ea.h * time != eb.h
        || ea.steps != eb.steps
        || ea.max_relative_energy_error != eb.max_relative_energy_error
        || ea.class != eb.class
    {
        return Err(format!(
            "{what}: energy at h = {}, {} steps, {:e} ({:?}) became h = {}, {} steps, {:e} ({:?})",
            ea.h,
            ea.steps,
            ea.max_relative_energy_error,
            ea.class,
            eb.h / time,
            eb.steps,
            eb.max_relative_energy_error,
            eb.class
        ));
    }
    let (sa, sb) = (&a.symplectic, &b.symplectic);
    if sa.symplectic_residual != sb.symplectic_residual || sa.det_minus_one != sb.det_minus_one {
        return Err(format!(
            "{what}: symplectic residual {:e} became {:e}",
            sa.symplectic_residual, sb.symplectic_residual
        ));
    }
    let (ra, rb) = (&a.reverse, &b.reverse);
    if ra.return_ulps != rb.return_ulps || ra.growth != rb.growth {
        return Err(format!(
            "{what}: return {:?} ulps (growth {}) became {:?} (growth {})",
            ra.return_ulps, ra.growth, rb.return_ulps, rb.growth
        ));
    }
    Ok(())
}

/// One scheme's verdicts on `scene` and on `scene` in units `length`,
/// `time`: the same bit for bit when `exact` (powers of two), the same
/// verdicts and orders otherwise.
struct Units<'a, S, const D: usize> {
    scene: &'a S,
    length: f64,
    time: f64,
    exact: bool,
}

impl<S: Scene<D> + Clone, const D: usize> SchemeVisitor for &Units<'_, S, D> {
    type Output = Result<(), String>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        let before = original(scheme, self.scene);
        let rescaled =
            Scaled::units(self.scene.clone(), self.length, self.time).map_err(|e| e.to_string())?;
        let after = verdicts(scheme, &rescaled);
        if self.exact {
            same_numbers(&before, &after, self.length, self.time)
        } else {
            same_verdicts(&before, &after)
        }
    }
}

/// Runs `check` on the four schemes of the unit properties (a first-order
/// non-geometric scheme, the second-order symplectic one, a fourth-order
/// non-symplectic and a fourth-order symplectic composition) on one of two
/// scenes (a nonlinear oscillator near nothing special, and an eccentric
/// orbit whose pericentre every ladder must resolve).
fn on_unit_scenes(scene: usize, length: f64, time: f64, exact: bool) -> Result<(), String> {
    for id in ["euler", "velocity-verlet", "rk4", "forest-ruth"] {
        match scene {
            0 => visit_scheme(
                id,
                &Units {
                    scene: &Anharmonic::default(),
                    length,
                    time,
                    exact,
                },
            ),
            _ => visit_scheme(
                id,
                &Units {
                    scene: &KeplerEccentric::default(),
                    length,
                    time,
                    exact,
                },
            ),
        }
        .map_err(|e| e.to_string())??;
    }
    Ok(())
}

/// Cases per unit property: 8 (each runs every study on four schemes, about
/// a second), or `PROPTEST_CASES` when set.
fn unit_cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(8)
}

proptest! {
    #![proptest_config(ProptestConfig {
        max_shrink_iters: 16,
        ..ProptestConfig::with_cases(unit_cases())
    })]

    /// Units of length and time that are powers of two, over twelve decades
    /// each: the same runs bit for bit, so the same records.
    #[test]
    fn power_of_two_units_give_the_same_records_bit_for_bit(
        length_exponent in -20i32..=20,
        time_exponent in -20i32..=20,
        scene in 0usize..2,
    ) {
        let (length, time) = (2f64.powi(length_exponent), 2f64.powi(time_exponent));
        let checked = on_unit_scenes(scene, length, time, true);
        prop_assert!(checked.is_ok(), "{}", checked.unwrap_err());
    }

    /// Any units of length and time from 1e-6 to 1e6: the same verdicts from
    /// all four studies and the same orders within their intervals.
    #[test]
    fn any_units_give_the_same_verdicts_and_orders(
        log_length in -6.0f64..6.0,
        log_time in -6.0f64..6.0,
        scene in 0usize..2,
    ) {
        let (length, time) = (10f64.powf(log_length), 10f64.powf(log_time));
        let checked = on_unit_scenes(scene, length, time, false);
        prop_assert!(checked.is_ok(), "{}", checked.unwrap_err());
    }
}

/// The Earth's circular orbit in metres and seconds (1 AU = 1.495978707e11 m,
/// a Julian year of 3.15576e7 s; `GM` becomes 1.32716e20 m^3/s^2, the
/// Sun's 1.32712440018e20 to the 3e-5 by which the idealised orbit's year is
/// not the Julian one) gets the verdicts it gets in astronomical units and
/// years, for every scheme of the catalogue and all four studies.
#[test]
fn the_earth_in_metres_and_seconds_gets_the_verdicts_of_au_and_years() {
    let (au, year) = (1.495978707e11, 3.15576e7);
    let failures: Vec<String> = scheme_ids()
        .into_iter()
        .filter_map(|id| {
            let check = Units {
                scene: &KeplerCircular,
                length: au,
                time: year,
                exact: false,
            };
            visit_scheme(id, &check).unwrap().err()
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The oscillator at `w0 = 1000` is the `w0 = 1` oscillator with time in
/// units of 1/1000: every catalogue scheme's order verdict must be the same,
/// with orders inside each other's intervals, whether `w0` is the scene's
/// own parameter or the wrapper's unit of time. At `w0 = 1024` the two are
/// the same runs bit for bit (velocities and times scale by powers of two),
/// so the order study must find the same rungs, window and order.
#[test]
fn the_oscillator_at_w0_1000_gets_the_order_verdicts_of_w0_1() {
    let slow = AnyScene::Harmonic(Harmonic::default());
    let order = |id: &str, scene: &AnyScene| {
        case(id, scene)
            .unwrap()
            .order(&OrderSpec::default())
            .unwrap()
    };
    /// The order record of the `w0 = 1` oscillator in time units `time`.
    struct InTimeUnits(f64);
    impl SchemeVisitor for &InTimeUnits {
        type Output = OrderRecord;
        fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> OrderRecord {
            let fast = Scaled::units(Harmonic::default(), 1.0, self.0).unwrap();
            global_order(scheme, &fast, &OrderSpec::default()).unwrap()
        }
    }
    let mut failures = Vec::new();
    for id in scheme_ids() {
        let base = order(id, &slow);
        let direct = order(
            id,
            &AnyScene::Harmonic(Harmonic::new(1000.0, 1.0, 0.0).unwrap()),
        );
        let rescaled = visit_scheme(id, &InTimeUnits(1e-3)).unwrap();
        failures.extend(same_order(&base, &direct).err());
        failures.extend(same_order(&base, &rescaled).err());
        let twin = order(
            id,
            &AnyScene::Harmonic(Harmonic::new(1024.0, 1.0, 0.0).unwrap()),
        );
        let same = base.rungs.len() == twin.rungs.len()
            && base
                .rungs
                .iter()
                .zip(&twin.rungs)
                .all(|(x, y)| x.steps == y.steps && x.error == y.error)
            && base.window == twin.window
            && base
                .measured_order
                .zip(twin.measured_order)
                .is_none_or(|(p, q)| (p - q).abs() <= 1e-9);
        if !same || base.verdict != twin.verdict {
            failures.push(format!(
                "{id}: w0 = 1024 is not w0 = 1 bit for bit: {:?} {:?} over {:?} against {:?} {:?} over {:?}",
                base.verdict, base.measured_order, base.window, twin.verdict, twin.measured_order, twin.window
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The comparison of orders above can fail: two orders `2 ORDER_RESOLUTION`
/// apart, each with the narrowest interval the study reports (`-+
/// ORDER_RESOLUTION`), are not the same order, and neither are two verdicts.
#[test]
fn orders_two_resolutions_apart_are_not_the_same() {
    let mut base = global_order(
        &VELOCITY_VERLET,
        &Harmonic::default(),
        &OrderSpec::default(),
    )
    .unwrap();
    let p0 = base.measured_order.unwrap();
    base.ci95 = Some(stepladder::internals::tolerance::order_interval(
        p0,
        [p0, p0],
    ));
    let mut moved = base.clone();
    let p = p0 + 2.0 * ORDER_RESOLUTION;
    moved.measured_order = Some(p);
    moved.ci95 = Some(stepladder::internals::tolerance::order_interval(p, [p, p]));
    assert!(same_order(&base, &moved).is_err());
    let mut refuted = base.clone();
    refuted.verdict = Verdict::Fail;
    assert!(same_order(&base, &refuted).is_err());
    assert!(same_order(&base, &base).is_ok());
}
