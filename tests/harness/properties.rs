//! Properties over random inputs: the window and the fit recover any power
//! law they are given, and a correct scheme passes on any oscillator.

use proptest::prelude::*;
use stepladder::ladder::AUTO_MAX_RUNG_EVALUATIONS;
use stepladder::ladder::per_octave;
use stepladder::measure::accuracy::order::{OrderSpec, RungData, analyse, global_order};
use stepladder::measure::geometry::reverse::{ReverseSpec, reversibility};
use stepladder::measure::geometry::tangent::step_jacobian;
use stepladder::run::integrate;
use stepladder::scene::Harmonic;
use stepladder::scene::Scene;
use stepladder::scheme::{Scheme, SchemeVisitor, VELOCITY_VERLET, scheme_ids, visit_scheme};
use stepladder::state::State;
use stepladder::tolerance::{MIN_WINDOW_HALVINGS, clean_fraction, order_verdict};

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
        use stepladder::measure::accuracy::phase::one_step_matrix;
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
